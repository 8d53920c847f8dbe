//! A whole segment of a textured span (16 pixels, the depth test `Less` with depth
//! writes, a repeating power-of-two texture of raw RGB565 texels): Thumb-2 assembly on
//! ARMv7E-M with every value in a register, beside its portable twin.
#![allow(unsafe_code)]

use core::any::TypeId;
use core::marker::PhantomData;

use embedded_graphics::pixelcolor::Rgb565;

/// Pixels of a segment.
pub(crate) const TEXEL_SEG: usize = 16;

/// Whether this target has the assembly segment ([`texel_segment_u16`]); elsewhere the
/// crate's own loops (which the compiler vectorises as it likes) are kept.
pub(crate) const TEXEL_KERNEL: bool = cfg!(all(zraster_thumb, zraster_dsp));

/// A repeating texture of W × H = 2^lw × 2^lh raw RGB565 texels (1 ≤ lw, lh and
/// lw + lh ≤ 26), shown on a colour buffer of `C` = `Rgb565`: the texel of coordinates
/// u, v (fractions of a texture in 32 bits) is `texels[(v ≫ sv)·W + (u ≫ su)]` with
/// su = 32 − lw, sv = 32 − lh, an index below W·H = `texels.len()` for every u, v.
#[derive(Clone, Copy)]
pub(crate) struct TexelGrid<'a, C> {
    texels: &'a [u16],
    su: u32,
    sv: u32,
    w: u32,
    colour: PhantomData<C>,
}

impl<'a> TexelGrid<'a, Rgb565> {
    /// The grid of raw texels (exactly 2^(lw + lh) of them), `None` outside the ranges.
    pub(crate) fn new(texels: &'a [u16], lw: u32, lh: u32) -> Option<Self> {
        let fits = (1..=13).contains(&lw) && (1..=13).contains(&lh);
        if !fits || texels.len() != 1 << (lw + lh) {
            return None;
        }
        Some(TexelGrid {
            texels,
            su: 32 - lw,
            sv: 32 - lh,
            w: 1 << lw,
            colour: PhantomData,
        })
    }
}

impl<'a, C: 'static> TexelGrid<'a, C> {
    /// The grid of a texture of `X` drawn at full light into a buffer of `C`, where a
    /// pixel's colour is its texel's bits: `C` is `Rgb565` and `X` is `u16` (raw RGB565,
    /// whose `Texel::color` keeps the bits) or `Rgb565` itself; `None` otherwise. (`X`
    /// may borrow, so it is known by its name: `TypeId` needs `'static`.)
    pub(crate) fn of<X: Copy>(texels: &'a [X], lw: u32, lh: u32) -> Option<Self> {
        let name = core::any::type_name::<X>();
        let raw = name == "u16" || name == core::any::type_name::<Rgb565>();
        if TypeId::of::<C>() != TypeId::of::<Rgb565>()
            || !raw
            || core::mem::size_of::<X>() != 2
            || core::mem::align_of::<X>() != 2
            || !rgb565_is_its_bits()
        {
            return None;
        }
        // SAFETY: X is u16 or Rgb565 (a u16 in a newtype): two bytes, alignment two, no
        // padding, so the same memory read as `texels.len()` u16s is initialised.
        let raw =
            unsafe { core::slice::from_raw_parts(texels.as_ptr().cast::<u16>(), texels.len()) };
        let grid = TexelGrid::new(raw, lw, lh)?;
        Some(TexelGrid {
            texels: grid.texels,
            su: grid.su,
            sv: grid.sv,
            w: grid.w,
            colour: PhantomData,
        })
    }
}

/// Whether an `Rgb565` in memory is its raw RGB565 value (a newtype's layout is not
/// guaranteed, so it is checked, not assumed; the compiler folds the check).
#[inline(always)]
fn rgb565_is_its_bits() -> bool {
    use embedded_graphics::pixelcolor::raw::RawU16;
    if core::mem::size_of::<Rgb565>() != 2 || core::mem::align_of::<Rgb565>() != 2 {
        return false;
    }
    let probe = Rgb565::from(RawU16::new(0xA55A));
    // SAFETY: Rgb565 is two bytes (checked above): its bytes read as one u16.
    unsafe { core::mem::transmute_copy::<Rgb565, u16>(&probe) == 0xA55A }
}

impl<C> TexelGrid<'_, C> {
    /// [`texel_segment_u16`] into a colour row of `C` (`Rgb565`, as the grid's
    /// constructors checked). Returns the number of pixels that failed.
    #[inline(always)]
    pub(crate) fn segment(
        &self,
        z: &mut [u16; TEXEL_SEG],
        c: &mut [C; TEXEL_SEG],
        acc: u32,
        dz: u32,
        uv: [u32; 4],
    ) -> u32 {
        // SAFETY: C is Rgb565 (a grid of another C is never built), two bytes of a u16 in
        // a newtype: every bit pattern is a valid Rgb565, so the array viewed as 16 u16s
        // (the same memory, alignment two) may take any texel's bits.
        let c = unsafe { &mut *c.as_mut_ptr().cast::<[u16; TEXEL_SEG]>() };
        let grid = TexelGrid {
            texels: self.texels,
            su: self.su,
            sv: self.sv,
            w: self.w,
            colour: PhantomData::<Rgb565>,
        };
        texel_segment_u16(z, c, acc, dz, uv, &grid)
    }
}

/// One segment: for each pixel `k` in 0..16, with `d = (acc ≫ 16) as u16`, if
/// `d < z[k]` then `z[k] = d` and `c[k]` = the texel at (u, v), else the pixel fails;
/// then `acc += dz`, `u += du`, `v += dv` (wrapping; `uv = [u, v, du, dv]`). Returns
/// the number of failing pixels. On ARMv7E-M 13 instructions a passing pixel
/// ([`texel_segment_asm`]); elsewhere [`texel_segment_portable`].
#[inline(always)]
pub(crate) fn texel_segment_u16(
    z: &mut [u16; TEXEL_SEG],
    c: &mut [u16; TEXEL_SEG],
    acc: u32,
    dz: u32,
    uv: [u32; 4],
    grid: &TexelGrid<'_, Rgb565>,
) -> u32 {
    #[cfg(all(zraster_thumb, zraster_dsp))]
    return texel_segment_asm(z, c, acc, dz, uv, grid);
    #[allow(unreachable_code)]
    texel_segment_portable(z, c, acc, dz, uv, grid)
}

/// The portable twin of [`texel_segment_u16`].
#[inline(always)]
pub(crate) fn texel_segment_portable(
    z: &mut [u16; TEXEL_SEG],
    c: &mut [u16; TEXEL_SEG],
    mut acc: u32,
    dz: u32,
    [mut u, mut v, du, dv]: [u32; 4],
    grid: &TexelGrid<'_, Rgb565>,
) -> u32 {
    let mut failed = 0;
    for (zp, cp) in z.iter_mut().zip(c.iter_mut()) {
        let at = (v >> grid.sv)
            .wrapping_mul(grid.w)
            .wrapping_add(u >> grid.su) as usize;
        let d = (acc >> 16) as u16;
        if d < *zp {
            *zp = d;
            // Below W·H (see `TexelGrid`): the fallback is never taken.
            *cp = grid.texels.get(at).copied().unwrap_or(*cp);
        } else {
            failed += 1;
        }
        acc = acc.wrapping_add(dz);
        u = u.wrapping_add(du);
        v = v.wrapping_add(dv);
    }
    failed
}

/// Pixel `$k` of [`texel_segment_asm`] at byte offset `$at`: the depth test (a failure
/// branches to `$fail`, which counts it and comes back to `$next`), then the texel
/// index by two shifts and a multiply-add, the texel and the colour store; then the
/// three steps. 13 instructions a passing pixel.
#[cfg(all(zraster_thumb, zraster_dsp))]
#[rustfmt::skip]
macro_rules! texel_pixel {
    ($at:literal, $fail:literal, $next:literal) => {
        concat!(
            "ldrh r6, [r0, #", $at, "]\n",
            "lsr r7, r3, #16\n",
            "cmp r7, r6\n",
            "bhs ", $fail, "f\n",
            "strh r7, [r0, #", $at, "]\n",
            "lsr r6, r8, r12\n",   // v >> sv: the row
            "lsr r7, r5, r11\n",   // u >> su: the column
            "mla r6, r6, lr, r7\n", // row·W + column
            "ldrh r6, [r2, r6, lsl #1]\n",
            "strh r6, [r1, #", $at, "]\n",
            $next, ":\n",
            "add r3, r4\n",
            "add r5, r9\n",
            "add r8, r10\n",
        )
    };
}

/// The failure of the pixel whose test branched to `$fail`: one more in the count on
/// the stack, back to `$next`.
#[cfg(all(zraster_thumb, zraster_dsp))]
macro_rules! texel_failed {
    ($fail:literal, $next:literal) => {
        concat!(
            $fail,
            ":\n",
            "ldr r6, [sp]\n",
            "adds r6, #1\n",
            "str r6, [sp]\n",
            "b ",
            $next,
            "b\n",
        )
    };
}

/// [`texel_segment_u16`] for ARMv7E-M: 16 pixels straight, every value in a register:
/// r0, r1 the depth and colour rows, r2 the texels, r3 `acc`, r4 `dz`, r5 u, r8 v, r9
/// du, r10 dv, r11 su, r12 sv, lr W; r6, r7 scratch (the compiler's: saved on the stack
/// meanwhile, with the failure count below them).
#[cfg(all(zraster_thumb, zraster_dsp))]
#[inline(always)]
fn texel_segment_asm(
    z: &mut [u16; TEXEL_SEG],
    c: &mut [u16; TEXEL_SEG],
    acc: u32,
    dz: u32,
    [u, v, du, dv]: [u32; 4],
    grid: &TexelGrid<'_, Rgb565>,
) -> u32 {
    let failed: u32;
    // SAFETY: z and c are arrays of 16 u16s (the types say so): the accesses are
    // [r0 + 2k] and [r1 + 2k] for k < 16, halfword-aligned. The texel read is
    // texels[(v ≫ sv)·W + (u ≫ su)] with sv = 32 − lh, su = 32 − lw, W = 2^lw and
    // texels.len() = 2^(lw + lh) (`TexelGrid::new`, 1 ≤ lw, lh ≤ 13): v ≫ sv < 2^lh and
    // u ≫ su < W, so the index is at most (2^lh − 1)·W + W − 1 < texels.len() for any
    // u, v, and the product fits 32 bits. r6 and r7 are pushed and popped around the
    // block, with the failure count in the 8 bytes pushed below them (the stack is used:
    // no `nostack`; sp stays 8-aligned); every other register written is declared. The
    // flags are scratch (no `preserves_flags`).
    unsafe {
        core::arch::asm!(
            "push {{r6, r7}}",
            "movs r6, #0",
            "push {{r6, r7}}", // the failure count at [sp]
            texel_pixel!(0, 20, 40),
            texel_pixel!(2, 21, 41),
            texel_pixel!(4, 22, 42),
            texel_pixel!(6, 23, 43),
            texel_pixel!(8, 24, 44),
            texel_pixel!(10, 25, 45),
            texel_pixel!(12, 26, 46),
            texel_pixel!(14, 27, 47),
            texel_pixel!(16, 28, 48),
            texel_pixel!(18, 29, 49),
            texel_pixel!(20, 30, 50),
            texel_pixel!(22, 31, 51),
            texel_pixel!(24, 32, 52),
            texel_pixel!(26, 33, 53),
            texel_pixel!(28, 34, 54),
            texel_pixel!(30, 35, 55),
            "b 9f",
            texel_failed!(20, 40),
            texel_failed!(21, 41),
            texel_failed!(22, 42),
            texel_failed!(23, 43),
            texel_failed!(24, 44),
            texel_failed!(25, 45),
            texel_failed!(26, 46),
            texel_failed!(27, 47),
            texel_failed!(28, 48),
            texel_failed!(29, 49),
            texel_failed!(30, 50),
            texel_failed!(31, 51),
            texel_failed!(32, 52),
            texel_failed!(33, 53),
            texel_failed!(34, 54),
            texel_failed!(35, 55),
            "9:",
            "ldr r0, [sp], #8",
            "pop {{r6, r7}}",
            inout("r0") z.as_mut_ptr() => failed,
            inout("r1") c.as_mut_ptr() => _,
            in("r2") grid.texels.as_ptr(),
            inout("r3") acc => _,
            in("r4") dz,
            inout("r5") u => _,
            inout("r8") v => _,
            in("r9") du,
            in("r10") dv,
            in("r11") grid.su,
            in("r12") grid.sv,
            in("lr") grid.w,
        );
    }
    failed
}

/// On-target check of the segment assembly against its twin, for the bench firmware:
/// segments over textures of every size from 2×2 to 64×64 (powers of two), with
/// coordinates and steps at random (wrapping included) and depths that pass, fail and
/// mix (the accumulator wrapping included), compared with the portable twin (depths,
/// colours and the failure count). `buf` holds the texels and four rows (at least
/// 4096 + 64 halfwords; a shorter one is a failure). Returns the number of cases that
/// differ. (bench/mcu-texture calls it on the target, through the crate's hidden
/// re-export.)
pub fn check_texel_kernel(buf: &mut [u16], cases: usize) -> usize {
    let Some(buf) = buf.get_mut(..4096 + 4 * TEXEL_SEG) else {
        return usize::MAX;
    };
    let (texels, rows) = buf.split_at_mut(4096);
    let mut rnd = super::xorshift32(0x1234_5679_u32);
    for t in texels.iter_mut() {
        *t = rnd() as u16;
    }
    let mut bad = 0;
    for case in 0..cases {
        let (lw, lh) = (1 + case as u32 % 6, 1 + (case as u32 / 6) % 6);
        let Some(grid) = texels
            .get(..1 << (lw + lh))
            .and_then(|t| TexelGrid::new(t, lw, lh))
        else {
            return usize::MAX;
        };
        let mut rows = rows.chunks_exact_mut(TEXEL_SEG);
        let (Some(z1), Some(c1), Some(z2), Some(c2)) =
            (rows.next(), rows.next(), rows.next(), rows.next())
        else {
            return usize::MAX;
        };
        for (d, c) in z1.iter_mut().zip(c1.iter_mut()) {
            (*d, *c) = (rnd() as u16, rnd() as u16);
        }
        if case % 5 == 1 {
            z1.fill(u16::MAX); // every pixel passes but where the depth reaches 65535
        }
        z2.copy_from_slice(z1);
        c2.copy_from_slice(c1);
        let acc = match case % 4 {
            0 => rnd() >> 2,
            1 => 0,
            2 => u32::MAX - 3, // fails until the accumulator wraps
            _ => rnd(),
        };
        let dz = if case % 3 == 0 { rnd() >> 12 } else { rnd() };
        let uv = [rnd(), rnd(), rnd() >> (rnd() % 24), rnd() >> (rnd() % 24)];
        let (Ok(z1), Ok(c1), Ok(z2), Ok(c2)) = (
            <&mut [u16; TEXEL_SEG]>::try_from(z1),
            <&mut [u16; TEXEL_SEG]>::try_from(c1),
            <&mut [u16; TEXEL_SEG]>::try_from(z2),
            <&mut [u16; TEXEL_SEG]>::try_from(c2),
        ) else {
            return usize::MAX;
        };
        let got = texel_segment_u16(z1, c1, acc, dz, uv, &grid);
        let want = texel_segment_portable(z2, c2, acc, dz, uv, &grid);
        if got != want || z1 != z2 || c1 != c2 {
            bad += 1;
        }
    }
    bad
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The specification of a segment, pixel by pixel, as the crate's textured loops
    /// have it: the index masked by W·H − 1, u and v stepped after each pixel.
    fn reference(
        z: &mut [u16; TEXEL_SEG],
        c: &mut [u16; TEXEL_SEG],
        acc: u32,
        dz: u32,
        [u, v, du, dv]: [u32; 4],
        texels: &[u16],
        (lw, lh): (u32, u32),
    ) -> u32 {
        let mut failed = 0;
        for k in 0..TEXEL_SEG as u32 {
            let d = (acc.wrapping_add(dz.wrapping_mul(k)) >> 16) as u16;
            let (u, v) = (
                u.wrapping_add(du.wrapping_mul(k)),
                v.wrapping_add(dv.wrapping_mul(k)),
            );
            let at = (((v >> (32 - lh)) << lw) | (u >> (32 - lw))) as usize & (texels.len() - 1);
            let k = k as usize;
            if d < z[k] {
                (z[k], c[k]) = (d, texels[at]);
            } else {
                failed += 1;
            }
        }
        failed
    }

    #[test]
    fn texel_kernel_matches_its_twin_and_the_reference() {
        let mut buf = [0u16; 4096 + 64];
        assert_eq!(check_texel_kernel(&mut buf, 2000), 0);
        assert_eq!(check_texel_kernel(&mut buf[..4000], 10), usize::MAX);
        let mut rnd = crate::testing::xorshift32(0x2545_f491);
        let texels: std::vec::Vec<u16> = (0..1 << 10).map(|_| rnd() as u16).collect();
        for case in 0..3000u32 {
            let (lw, lh) = (1 + case % 5, 1 + (case / 5) % 5);
            let t = &texels[..1 << (lw + lh)];
            let grid = TexelGrid::new(t, lw, lh).unwrap();
            let mut z = [0u16; TEXEL_SEG].map(|_| rnd() as u16);
            if case % 3 == 0 {
                z = [u16::MAX; TEXEL_SEG];
            }
            let c = [0u16; TEXEL_SEG].map(|_| rnd() as u16);
            let (acc, dz) = (rnd(), rnd() >> (rnd() % 20));
            let uv = [rnd(), rnd(), rnd() >> (rnd() % 28), rnd() >> (rnd() % 28)];
            let (mut z1, mut c1, mut z2, mut c2, mut z3, mut c3) = (z, c, z, c, z, c);
            let want = reference(&mut z1, &mut c1, acc, dz, uv, t, (lw, lh));
            assert_eq!(
                texel_segment_portable(&mut z2, &mut c2, acc, dz, uv, &grid),
                want
            );
            assert_eq!(
                texel_segment_u16(&mut z3, &mut c3, acc, dz, uv, &grid),
                want
            );
            assert_eq!((z1, c1), (z2, c2), "case {case}");
            assert_eq!((z1, c1), (z3, c3), "case {case}");
        }
    }

    #[test]
    fn grids_take_raw_rgb565_only_and_whole_power_of_two_textures() {
        use embedded_graphics::pixelcolor::{Bgr565, Rgb888};
        let raw = [0u16; 64];
        let px = [Rgb565::new(1, 2, 3); 64];
        assert!(TexelGrid::<Rgb565>::of(&raw, 3, 3).is_some());
        assert!(TexelGrid::<Rgb565>::of(&px, 4, 2).is_some());
        assert!(TexelGrid::<Rgb565>::of(&px, 3, 2).is_none()); // 32 texels needed
        assert!(TexelGrid::<Rgb565>::of(&raw, 0, 6).is_none()); // W = 1
        assert!(TexelGrid::<Bgr565>::of(&raw, 3, 3).is_none());
        assert!(TexelGrid::<Rgb565>::of(&[Bgr565::new(1, 2, 3); 64], 3, 3).is_none());
        assert!(TexelGrid::<Rgb888>::of(&raw, 3, 3).is_none());
        assert!(TexelGrid::<Rgb565>::of(&[0i16; 64], 3, 3).is_none());
        // A grid's segment writes the texel's bits as the colour.
        let grid = TexelGrid::<Rgb565>::of(&[0xF800u16; 4], 1, 1).unwrap();
        let (mut z, mut c) = ([u16::MAX; TEXEL_SEG], [Rgb565::new(0, 0, 0); TEXEL_SEG]);
        assert_eq!(grid.segment(&mut z, &mut c, 0, 1 << 16, [0; 4]), 0);
        assert!(c.iter().all(|&p| p == Rgb565::new(31, 0, 0)));
        assert_eq!(z[15], 15);
    }
}
