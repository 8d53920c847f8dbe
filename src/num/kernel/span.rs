//! The depth-tested span of a flat-coloured row: SIMD on ARMv7E-M, unrolled on
//! ARMv6-M, beside its portable twin.
#![allow(unsafe_code)]

/// The shortest span the assembly loop takes: 8 pixels on ARMv7E-M, 6 on ARMv6-M.
/// Below that the call and the loop's set-up cost more than the crate's own loops,
/// unrolled for spans of a few pixels (docs/tuning.md has the measurements). `None`
/// where there is no assembly loop (hosts, Cortex-M3): on x86-64 the portable twin is
/// slower than the crate's loops.
const SPAN_KERNEL_MIN: Option<usize> = if cfg!(all(zraster_thumb, zraster_dsp)) {
    Some(8)
} else if cfg!(all(zraster_thumb, zraster_armv6m)) {
    Some(6)
} else {
    None
};

/// Whether [`span_less_as_u16`] takes a span of `len` pixels (of a two-byte colour): on
/// targets with an assembly span loop, when the span is long enough for it to pay.
#[inline(always)]
pub(crate) fn span_kernel_pays(len: usize) -> bool {
    SPAN_KERNEL_MIN.is_some_and(|min| len >= min)
}

/// The depth-tested span of a flat-coloured row, for the depth test `Less` with depth
/// writes on and a 16-bit colour: for each pixel `i`, with `d = (acc >> 16) as u16`,
/// if `d < z[i]` then `z[i] = d` and `c[i] = color`, else the pixel fails; then
/// `acc += dz` (wrapping). Returns the number of failing pixels. Over the first
/// `min(z.len(), c.len())` pixels.
///
/// On ARMv7E-M two pixels a SIMD step (5.4 instructions a pixel) when `z` and `c` are
/// at the same address modulo 4, as the rows of two buffers of the same geometry are
/// when both start 4-aligned; on ARMv6-M 16 pixels a turn (7.5 a pixel); elsewhere,
/// and for rows not so aligned, [`span_less_u16_portable`]. Out of line, so that the
/// callers' short loops keep their cheap prologues.
#[cfg_attr(zraster_ram_code, link_section = ".data.zraster")]
#[inline(never)]
pub(crate) fn span_less_u16(z: &mut [u16], c: &mut [u16], acc: u32, dz: u32, color: u16) -> u32 {
    let n = z.len().min(c.len());
    let (z, c) = (z.split_at_mut(n).0, c.split_at_mut(n).0);
    #[cfg(all(zraster_thumb, zraster_dsp))]
    if n > 0 && (z.as_ptr() as usize ^ c.as_ptr() as usize) & 2 == 0 {
        return span_less_dsp(z, c, acc, dz, color);
    }
    #[cfg(all(zraster_thumb, zraster_armv6m))]
    if n > 0 {
        return span_less_armv6m(z, c, acc, dz, color);
    }
    span_less_u16_portable(z, c, acc, dz, color)
}

/// The portable twin of [`span_less_u16`].
#[inline]
pub(crate) fn span_less_u16_portable(
    z: &mut [u16],
    c: &mut [u16],
    mut acc: u32,
    dz: u32,
    color: u16,
) -> u32 {
    let mut failed = 0;
    for (zp, cp) in z.iter_mut().zip(c.iter_mut()) {
        let d = (acc >> 16) as u16;
        acc = acc.wrapping_add(dz);
        if d < *zp {
            *zp = d;
            *cp = color;
        } else {
            failed += 1;
        }
    }
    failed
}

/// [`span_less_u16`] for a colour type of two bytes (and alignment two), where the
/// assembly loop pays ([`span_kernel_pays`]); `None` (nothing written) otherwise.
#[inline(always)]
pub(crate) fn span_less_as_u16<C: Copy>(
    z: &mut [u16],
    c: &mut [C],
    acc: u32,
    dz: u32,
    color: C,
) -> Option<u32> {
    if !span_kernel_pays(z.len())
        || core::mem::size_of::<C>() != 2
        || core::mem::align_of::<C>() < 2
    {
        return None;
    }
    // SAFETY: as in `fill_as_u16`: C is two bytes with alignment two (checked above), so
    // `color`'s bytes read as a u16 and `c` viewed as `c.len()` u16s covers exactly the
    // same memory. Each element then keeps its bytes or takes `color`'s: a valid C.
    let (bits, words) = unsafe {
        (
            core::mem::transmute_copy::<C, u16>(&color),
            core::slice::from_raw_parts_mut(c.as_mut_ptr().cast::<u16>(), c.len()),
        )
    };
    Some(span_less_u16(z, words, acc, dz, bits))
}

/// Two pixels of [`span_less_dsp`], as the halfword lanes of one word: depths in `$z`,
/// colours in `$c`. USUB16 sets a lane's GE flags where the test fails (`d ≥ z`); SEL
/// keeps the old depth and colour there and takes the new ones elsewhere; the third
/// SEL gives a lane one away from `r5` (colour in both lanes) where the test failed,
/// so that USADA8 (sum of absolute byte differences) adds the pair's failures to r7.
#[cfg(all(zraster_thumb, zraster_dsp))]
#[rustfmt::skip]
macro_rules! dsp_pair {
    ($z:literal, $c:literal) => {
        concat!(
            "add r12, r3, r4\n",
            "pkhtb lr, r12, r3, asr #16\n", // the pair's depths: [acc + dz : acc] >> 16
            "add r3, r12, r4\n",
            "usub16 r12, lr, ", $z, "\n",
            "sel ", $z, ", ", $z, ", lr\n",
            "sel ", $c, ", ", $c, ", r5\n",
            "sel r12, r6, r5\n",
            "usada8 r7, r12, r5, r7\n",
        )
    };
}

/// One pixel of [`span_less_dsp`] at [r0] and [r1] (the first when the rows are not
/// word-aligned, and the last of an odd count).
#[cfg(all(zraster_thumb, zraster_dsp))]
macro_rules! dsp_one {
    () => {
        concat!(
            "ldrh r8, [r0]\n",
            "lsr lr, r3, #16\n",
            "add r3, r4\n",
            "cmp lr, r8\n",
            "itte lo\n",
            "strhlo lr, [r0]\n",
            "strhlo r5, [r1]\n",
            "addhs r7, #1\n",
        )
    };
}

/// The body of [`span_less_dsp`] from its first pixel to its count: r0, r1 the rows, r2
/// their length (≥ 1), r3 `acc`, r4 `dz`, r5 the colour in both lanes, r6 `r5 ^
/// 0x0001_0001`, r7 zero; leaves the failures in r12. One pixel alone if the rows are not
/// word-aligned, eight a turn by LDRD/STRD, then four, two and one by the bits of the
/// remainder. `$a`…`$f` are its six local labels (the rows kernel runs it too, beside
/// labels of its own). Clobbers r0–r3 and r7–r11, lr and the flags.
#[cfg(all(zraster_thumb, zraster_dsp))]
#[rustfmt::skip]
macro_rules! dsp_span {
    ($a:literal, $b:literal, $c:literal, $d:literal, $e:literal, $f:literal) => {
        concat!(
            "tst r0, #2\n",
            "beq ", $a, "f\n",
            dsp_one!(),
            "adds r0, #2\n",
            "adds r1, #2\n",
            "subs r2, #1\n",
            $a, ":\n",
            "subs r2, #8\n",
            "blo ", $c, "f\n",
            $b, ":\n",
            "ldrd r8, r9, [r0]\n",
            "ldrd r10, r11, [r1]\n",
            dsp_pair!("r8", "r10"),
            dsp_pair!("r9", "r11"),
            "strd r8, r9, [r0], #8\n",
            "strd r10, r11, [r1], #8\n",
            "ldrd r8, r9, [r0]\n",
            "ldrd r10, r11, [r1]\n",
            dsp_pair!("r8", "r10"),
            dsp_pair!("r9", "r11"),
            "strd r8, r9, [r0], #8\n",
            "strd r10, r11, [r1], #8\n",
            "subs r2, #8\n",
            "bhs ", $b, "b\n",
            $c, ":\n",
            // r2 is the remainder − 8: its low three bits are the remainder's.
            "lsls r2, r2, #30\n", // C = bit 2, N = bit 1
            "bcc ", $d, "f\n",
            "ldrd r8, r9, [r0]\n",
            "ldrd r10, r11, [r1]\n",
            dsp_pair!("r8", "r10"),
            dsp_pair!("r9", "r11"),
            "strd r8, r9, [r0], #8\n",
            "strd r10, r11, [r1], #8\n",
            $d, ":\n",
            "bpl ", $e, "f\n",
            "ldr r8, [r0]\n",
            "ldr r10, [r1]\n",
            dsp_pair!("r8", "r10"),
            "str r8, [r0], #4\n",
            "str r10, [r1], #4\n",
            $e, ":\n",
            "lsls r2, r2, #2\n", // C = bit 0
            "bcc ", $f, "f\n",
            dsp_one!(),
            $f, ":\n",
            "mov r12, r7\n",
        )
    };
}

/// [`span_less_u16`] for ARMv7E-M, `z` and `c` of the same length `n ≥ 1` and at the
/// same address modulo 4: one pixel alone if they are not word-aligned, then eight
/// pixels a turn by LDRD/STRD (42 instructions), then four, two and one by the bits of
/// the remainder. Registers: r0, r1 the row pointers, r2 pixels left, r3 `acc`, r4
/// `dz`, r5 the colour in both lanes, r6 `r5 ^ 0x0001_0001`, r7 the failures (r6 and
/// r7 are the compiler's: saved on the stack meanwhile), r8–r11 two depth and two
/// colour pairs, r12 and lr scratch.
#[cfg(all(zraster_thumb, zraster_dsp))]
#[inline(always)]
fn span_less_dsp(z: &mut [u16], c: &mut [u16], acc: u32, dz: u32, color: u16) -> u32 {
    let n = z.len();
    let failed: u32;
    // SAFETY: the caller passes n = z.len() = c.len() ≥ 1 and z, c at the same address
    // modulo 4 (both 2-aligned, as u16). Every access is to z[i] and c[i] for i < n, in
    // order: one pixel first if z is not word-aligned (after it both are), then
    // LDRD/STRD of eight pixels while at least eight remain (r2 counts them down), then
    // four (LDRD/STRD), two (LDR/STR) and one (LDRH/STRH) by the bits of the remainder,
    // so nothing past the end. Word stores write back a failing pixel's own depth and
    // colour. r6 and r7 are pushed and popped around the block (the stack is used: no
    // `nostack`); every other register written is declared. The flags, GE included,
    // are scratch (no `preserves_flags`).
    unsafe {
        core::arch::asm!(
            "push {{r6, r7}}",
            "eor r6, r5, #0x00010001",
            "movs r7, #0",
            dsp_span!("2", "3", "4", "5", "6", "7"),
            "pop {{r6, r7}}",
            inout("r0") z.as_mut_ptr() => _,
            inout("r1") c.as_mut_ptr() => _,
            inout("r2") n => _,
            inout("r3") acc => _,
            in("r4") dz,
            in("r5") u32::from(color) * 0x1_0001,
            out("r8") _, out("r9") _, out("r10") _, out("r11") _,
            out("r12") failed,
            out("lr") _,
        );
    }
    failed
}

/// One pixel of [`span_less_armv6m`], at byte offset `$at` of the turn: 7 two-byte
/// instructions; a failure branches to `$fail` (which counts it and comes back to
/// `$next`).
#[cfg(all(zraster_thumb, zraster_armv6m))]
#[rustfmt::skip]
macro_rules! v6m_pixel {
    ($at:literal, $fail:literal, $next:literal) => {
        concat!(
            "ldrh r4, [r0, #", $at, "]\n",
            "lsrs r5, r2, #16\n",
            "cmp r5, r4\n",
            "bhs ", $fail, "f\n",
            "strh r5, [r0, #", $at, "]\n",
            "strh r3, [r1, #", $at, "]\n",
            $next, ":\n",
            "add r2, r8\n",
        )
    };
}

/// The failure of the pixel whose test branched to `$fail`: count it, go on at `$next`.
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! v6m_failed {
    ($fail:literal, $next:literal) => {
        concat!($fail, ":\n", "add r10, r11\n", "b ", $next, "b\n")
    };
}

/// [`span_less_u16`] for ARMv6-M (no IT blocks, no SIMD, no post-indexed loads), `z`
/// and `c` of the same length `n ≥ 1`: 16 pixels a turn with immediate offsets, 7
/// two-byte instructions a passing pixel; failures branch to a cold block that counts
/// them and returns. The loop is entered Duff-style: the first turn skips the code of
/// s = (−n) mod 16 pixels by ADD PC (both pointers moved back by s pixels, not
/// dereferenced there), so there is no tail loop. Registers: r0, r1 the row pointers,
/// r2 `acc`, r3 the colour, r4 the stored depth, r5 the new depth (Thumb-1 operands
/// must be low registers), r8 `dz`, r9 the end of `z`, r10 the failures, r11 one.
#[cfg(all(zraster_thumb, zraster_armv6m))]
#[inline(always)]
fn span_less_armv6m(z: &mut [u16], c: &mut [u16], acc: u32, dz: u32, color: u16) -> u32 {
    let n = z.len();
    let failed: u32;
    // SAFETY: the caller passes n = z.len() = c.len() ≥ 1. The first turn starts s
    // pixels before the rows but skips exactly the code of those s pixels, so the
    // accesses are z[i] and c[i] for i in 0..n only, halfword-aligned; the loop ends
    // when the z pointer reaches z + n (16 − s pixels, then multiples of 16). The
    // computed branch lands on a pixel's first instruction: every instruction from the
    // ADD PC to the end of the turn is 2 bytes (ARMv6-M has no 32-bit forms of them),
    // 14 bytes a pixel, and `check_span_kernel` tries every entry point (every length
    // up to 64) against the portable twin. Every register written is declared; the
    // stack is not touched.
    unsafe {
        core::arch::asm!(
            "mov r8, r5", // dz
            "movs r5, #0",
            "mov r10, r5", // failures
            "movs r5, #1",
            "mov r11, r5", // one
            "lsls r5, r4, #1",
            "adds r5, r0",
            "mov r9, r5", // end of z
            "rsbs r4, r4, #0",
            "lsls r4, r4, #28",
            "lsrs r4, r4, #28", // s = (−n) mod 16
            "lsls r5, r4, #1",
            "subs r0, r0, r5",
            "subs r1, r1, r5",
            "lsls r4, r4, #4",
            "subs r4, r4, r5", // 14·s bytes of code to skip
            "add pc, r4",      // PC reads as this instruction + 4: the first pixel's code
            "nop",
            "2:",
            v6m_pixel!(0, 30, 60),
            v6m_pixel!(2, 31, 61),
            v6m_pixel!(4, 32, 62),
            v6m_pixel!(6, 33, 63),
            v6m_pixel!(8, 34, 64),
            v6m_pixel!(10, 35, 65),
            v6m_pixel!(12, 36, 66),
            v6m_pixel!(14, 37, 67),
            v6m_pixel!(16, 38, 68),
            v6m_pixel!(18, 39, 69),
            v6m_pixel!(20, 40, 70),
            v6m_pixel!(22, 41, 71),
            v6m_pixel!(24, 42, 72),
            v6m_pixel!(26, 43, 73),
            v6m_pixel!(28, 44, 74),
            v6m_pixel!(30, 45, 75),
            "adds r0, #32",
            "adds r1, #32",
            "cmp r0, r9",
            "bne 2b",
            "b 9f",
            v6m_failed!(30, 60),
            v6m_failed!(31, 61),
            v6m_failed!(32, 62),
            v6m_failed!(33, 63),
            v6m_failed!(34, 64),
            v6m_failed!(35, 65),
            v6m_failed!(36, 66),
            v6m_failed!(37, 67),
            v6m_failed!(38, 68),
            v6m_failed!(39, 69),
            v6m_failed!(40, 70),
            v6m_failed!(41, 71),
            v6m_failed!(42, 72),
            v6m_failed!(43, 73),
            v6m_failed!(44, 74),
            v6m_failed!(45, 75),
            "9:",
            "mov r5, r10",
            inout("r0") z.as_mut_ptr() => _,
            inout("r1") c.as_mut_ptr() => _,
            inout("r2") acc => _,
            in("r3") u32::from(color),
            inout("r4") n => _,
            inout("r5") dz => failed,
            out("r8") _, out("r9") _, out("r10") _, out("r11") _,
            options(nostack),
        );
    }
    failed
}

/// On-target check of the span assembly against its twin, for the bench firmware:
/// spans of every length up to `max` at every alignment of the depth and colour rows
/// (the same modulo 4 and not), over depths that pass, fail and mix, with guard values
/// around, compared with the portable twin (depths, colours and the failure
/// count). `buf` holds the four rows (at least `4 · (max + 5)` halfwords; a shorter
/// one is a failure). Returns the number of cases that differ.
pub fn check_span_kernel(buf: &mut [u16], max: usize) -> usize {
    let q = (max + 5) & !1; // even: rows at the same offset have the same address modulo 4
    let Some(buf) = buf.get_mut(..4 * q) else {
        return usize::MAX;
    };
    let (mine, twin) = buf.split_at_mut(2 * q);
    let (z1, c1) = mine.split_at_mut(q);
    let (z2, c2) = twin.split_at_mut(q);
    let mut rnd = super::xorshift32(0x9e37_79b9_u32);
    let mut bad = 0;
    for mode in 0..8u32 {
        for (zo, co) in [(0, 0), (1, 1), (0, 1), (1, 0), (2, 0), (3, 0)] {
            for len in 0..=max {
                for (d, c) in z1.iter_mut().zip(c1.iter_mut()) {
                    (*d, *c) = (rnd() as u16, rnd() as u16);
                }
                z2.copy_from_slice(z1);
                c2.copy_from_slice(c1);
                let acc = match mode % 4 {
                    0 => rnd() >> 2,
                    1 => 0,            // every pixel passes but where z is 0
                    2 => u32::MAX - 3, // depth 65535 fails, until the accumulator wraps
                    _ => rnd(),
                };
                let dz = if mode < 4 { rnd() >> 12 } else { rnd() };
                let color = rnd() as u16;
                let (Some(za), Some(ca), Some(zb), Some(cb)) = (
                    z1.get_mut(zo..zo + len),
                    c1.get_mut(co..co + len),
                    z2.get_mut(zo..zo + len),
                    c2.get_mut(co..co + len),
                ) else {
                    continue;
                };
                let got = span_less_u16(za, ca, acc, dz, color);
                let want = span_less_u16_portable(zb, cb, acc, dz, color);
                if got != want || z1 != z2 || c1 != c2 {
                    bad += 1;
                }
            }
        }
    }
    bad
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
    use embedded_graphics::prelude::RgbColor;

    /// The specification of `span_less_u16`, pixel by pixel.
    fn span_reference(z: &mut [u16], c: &mut [u16], mut acc: u32, dz: u32, color: u16) -> u32 {
        let mut failed = 0;
        for (zp, cp) in z.iter_mut().zip(c.iter_mut()) {
            let d = (acc >> 16) as u16;
            if d < *zp {
                (*zp, *cp) = (d, color);
            } else {
                failed += 1;
            }
            acc = acc.wrapping_add(dz);
        }
        failed
    }

    #[test]
    fn span_kernel_matches_its_twin() {
        let mut buf = [0u16; 4 * 69];
        assert_eq!(check_span_kernel(&mut buf, 64), 0);
        assert_ne!(check_span_kernel(&mut buf[..100], 64), 0);
        let mut rnd = crate::testing::xorshift32(0x2545_f491);
        for len in 0..70 {
            let depth: std::vec::Vec<u16> = (0..len).map(|_| rnd() as u16).collect();
            let colour: std::vec::Vec<u16> = (0..len).map(|_| rnd() as u16).collect();
            let (acc, dz, col) = (rnd(), rnd() >> (rnd() % 20), rnd() as u16);
            let run = |f: fn(&mut [u16], &mut [u16], u32, u32, u16) -> u32| {
                let (mut z, mut c) = (depth.clone(), colour.clone());
                let failed = f(&mut z, &mut c, acc, dz, col);
                (z, c, failed)
            };
            let want = run(span_reference);
            assert_eq!(run(span_less_u16_portable), want, "length {len}");
            assert_eq!(run(span_less_u16), want, "length {len}");
        }
    }

    #[test]
    fn span_less_as_u16_takes_two_byte_types_and_long_spans_only() {
        let mut z = [9u16; 40];
        let mut c = [Rgb565::BLACK; 40];
        let taken = span_less_as_u16(&mut z, &mut c, 0, 1 << 16, Rgb565::RED);
        if span_kernel_pays(40) {
            assert_eq!(taken, Some(31)); // depths 0..=8 pass
            assert!(c[..9].iter().all(|&p| p == Rgb565::RED));
            assert!(c[9..].iter().all(|&p| p == Rgb565::BLACK));
        } else {
            assert_eq!(taken, None);
        }
        let mut w = [Rgb888::BLACK; 40];
        assert_eq!(span_less_as_u16(&mut z, &mut w, 0, 0, Rgb888::RED), None);
        assert_eq!(
            span_less_as_u16(&mut z[..1], &mut c[..1], 0, 0, Rgb565::RED),
            None
        );
    }
}
