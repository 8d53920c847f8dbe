//! The vertex cache's usual vertex on ARMv7E-M with an FPU: the fixed-point transform,
//! the projection and the entry in one assembly loop, beside its portable twin.
//!
//! It computes the `f32` path's entry ([`ScreenMap::project_float_inside`] of
//! [`Clip4::to_f32`], then [`CachedVertex::placing`]) bit for bit, with every scale
//! taken as a power of two out of the values (rounding commutes with those): z and w
//! in units of 2¹⁴ (the low partial sum converted with 14 fraction bits, no multiply),
//! x and y without their scale `s` (folded into the screen scales), and the screen
//! coordinates rounded from their doubles truncated. The planes it tests are narrower
//! than the `f32` path's, so that it places no vertex that path would not: w by its
//! high partial sum (w > 2³¹), near and far by the depth (one unit of room), the guard
//! band by the screen range (±1020 pixels, inside the band for the viewports
//! [`PlaceBlock`] takes). Any other vertex stops the loop for the caller's exact path.
//!
//! [`ScreenMap::project_float_inside`]: crate::geometry::project::ScreenMap
//! [`Clip4::to_f32`]: crate::geometry::transform::Clip4
#![allow(unsafe_code)]

use crate::raster::ScreenVertex;
use crate::render::CachedVertex;

/// Whether [`place_run`] is the assembly loop (ARMv7E-M with an FPU).
pub(crate) const PLACE_KERNEL: bool =
    cfg!(all(zraster_thumb, zraster_dsp, not(zraster_soft_float)));

/// The operands of [`place_run`], read by the loop at fixed offsets (`repr(C)`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub(crate) struct PlaceBlock {
    /// The transform's rows x, y, z high, w high, z low, w low, each as `c₀c₁` packed,
    /// `c₂`, `t` (`FixedTransform`'s).
    pub(crate) rows: [[u32; 3]; 6],
    /// 1, the x scale and offset, the y scale and offset, half the depth range, ½.
    pub(crate) consts: [f32; 7],
}

// The loop reads the constants at byte 72 (after the 18 words of rows).
const _: () = assert!(core::mem::offset_of!(PlaceBlock, consts) == 72);

/// The entry of position `p`, or `None` where the loop stops: the portable twin of one
/// turn of [`place_run`]'s loop (every operation the same, in the same order).
#[inline(always)]
pub(crate) fn place_portable(b: &PlaceBlock, p: &[i16; 3]) -> Option<CachedVertex> {
    let xy = crate::num::pack_i16(p[0], p[1]);
    let z = i32::from(p[2]);
    let row = |[c01, c2, t]: [u32; 3]| {
        let zt = (c2 as i32).wrapping_mul(z).wrapping_add(t as i32);
        super::mac::smlad_portable(xy, c01, zt)
    };
    let [x, y, zh, wh, zl, wl] = b.rows.map(row);
    // w > 2¹⁸·2¹⁴ − 2³¹ (the low sum is above −2³¹): w ≥ 1 however it rounds.
    if wh < 1 << 18 {
        return None;
    }
    let [one, sx, ox, sy, oy, depth_half, half] = b.consts;
    // z/2¹⁴, w/2¹⁴ as to_f32 rounds them (its z, w times 2⁻¹⁴ exactly).
    let scaled = |h: i32, l: i32| h as f32 + l as f32 * (1.0 / 16384.0);
    let (zf, wf) = (scaled(zh, zl), scaled(wh, wl));
    let inv = one / wf;
    let cx = x as f32 * inv * sx + ox;
    let cy = y as f32 * inv * sy + oy;
    let sz = ((zf * inv + one) * depth_half + half) as u32;
    // Twice the screen coordinates, truncated (saturating, as VCVT).
    let (tx, ty) = ((cx * 2.0) as i32, (cy * 2.0) as i32);
    let within = |t: i32| t.wrapping_add(32640) as u32 <= 65280;
    // Depth units 1..65533: strictly inside the near and far planes.
    if !(within(tx) && within(ty)) || sz.wrapping_sub(1 << 16) >= 0xfffd_0000 {
        return None;
    }
    CachedVertex::placing(ScreenVertex::from_raw(
        round_doubled(tx),
        round_doubled(ty),
        sz,
    ))
}

/// `round_f32(c)` (halves away from zero) from `t = trunc(2c)`, for |c| < 2²²: ⌊c + ½⌋
/// is ⌊(t + 1)/2⌋ for c ≥ 0, and −⌊−c + ½⌋ is ⌊t/2⌋ for c < 0.
#[inline(always)]
fn round_doubled(t: i32) -> i32 {
    (t + i32::from(t >= 0)) >> 1
}

/// Writes the entries of `positions` into `out` from the first on, up to the first
/// position the loop does not place ([`place_portable`] gives `None`), and returns how
/// many it wrote (at most the shorter length). On ARMv7E-M with an FPU an assembly loop
/// of some 60 instructions a vertex; elsewhere the twin.
#[inline]
pub(crate) fn place_run(b: &PlaceBlock, positions: &[[i16; 3]], out: &mut [CachedVertex]) -> usize {
    let n = positions.len().min(out.len());
    if n == 0 {
        return 0;
    }
    #[cfg(all(zraster_thumb, zraster_dsp, not(zraster_soft_float)))]
    {
        const _: () = assert!(core::mem::size_of::<CachedVertex>() == 8);
        let left: usize;
        // SAFETY: reads `PlaceBlock`'s 25 words (`repr(C)`: rows at 0, constants at
        // 72) and, for n ≥ 1 turns at most, one position a turn (`[i16; 3]`, 6 bytes,
        // from `positions`' start: LDR and LDRSH, unaligned word loads being allowed
        // on ARMv7-M) and writes one entry a turn with STRD (8 bytes, from `out`'s
        // start, 4-byte aligned as `CachedVertex` is); n is at most either length, and a
        // turn that stops writes nothing. `CachedVertex` is `repr(C)`: the depth word,
        // then the x/y word (x in the low half: `XyWord`), any bits valid. r4–r11 and lr
        // are pushed first and popped last (r12 and lr hold the second and third pairs of
        // rows' address); s0–s5, s8–s14 and the flags are clobbered.
        //
        // A turn: the six rows (three LDM of two rows, from r0, r12 and lr; one MLA and
        // one SMLAD a row, as `Row::at`), w's test on its high sum, the conversions (the
        // low sums with 14 fraction bits), one VDIV, the screen coordinates doubled and truncated, the
        // depth, the range tests, the halves rounded by one SHADD16 and the entry.
        unsafe {
            core::arch::asm!(
                "push {{r4-r11, lr}}",
                "add r12, r0, #72",
                "vldm r12, {{s8-s14}}",
                "add r12, r0, #24",
                "add lr, r0, #48",
                "2:",
                "ldr r10, [r1], #6",
                "ldrsh r11, [r1, #-2]",
                "ldm r0, {{r4-r9}}",
                "mla r6, r5, r11, r6",
                "smlad r6, r10, r4, r6",
                "mla r9, r8, r11, r9",
                "smlad r9, r10, r7, r9",
                "vmov s0, s1, r6, r9",
                "ldm r12, {{r4-r9}}",
                "mla r6, r5, r11, r6",
                "smlad r6, r10, r4, r6",
                "mla r9, r8, r11, r9",
                "smlad r9, r10, r7, r9",
                "cmp r9, #0x40000",
                "vmov s2, s3, r6, r9",
                "ldm lr, {{r4-r9}}",
                "mla r6, r5, r11, r6",
                "smlad r6, r10, r4, r6",
                "mla r9, r8, r11, r9",
                "smlad r9, r10, r7, r9",
                "blt 3f",
                "vmov s4, s5, r6, r9",
                "vcvt.f32.s32 s0, s0",
                "vcvt.f32.s32 s1, s1",
                "vcvt.f32.s32 s2, s2",
                "vcvt.f32.s32 s3, s3",
                "vcvt.f32.s32 s4, s4, #14",
                "vcvt.f32.s32 s5, s5, #14",
                "vadd.f32 s2, s2, s4",
                "vadd.f32 s3, s3, s5",
                "vdiv.f32 s3, s8, s3",
                "vmul.f32 s0, s0, s3",
                "vmul.f32 s1, s1, s3",
                "vmul.f32 s2, s2, s3",
                "vmul.f32 s0, s0, s9",
                "vmul.f32 s1, s1, s11",
                "vadd.f32 s2, s2, s8",
                "vadd.f32 s0, s0, s10",
                "vadd.f32 s1, s1, s12",
                "vmul.f32 s2, s2, s13",
                "vadd.f32 s2, s2, s14",
                "vcvt.s32.f32 s0, s0, #1",
                "vcvt.s32.f32 s1, s1, #1",
                "vcvt.u32.f32 s2, s2",
                "vmov r4, r5, s0, s1",
                "vmov r6, s2",
                "add.w r8, r4, #32640",
                "cmp.w r8, #65280",
                "bhi 3f",
                "add.w r8, r5, #32640",
                "cmp.w r8, #65280",
                "bhi 3f",
                "sub.w r8, r6, #65536",
                "cmn.w r8, #196608",
                "bhs 3f",
                "pkhbt r4, r4, r5, lsl #16",
                "mov.w r5, #0x10001",
                "bic.w r5, r5, r4, lsr #15",
                "shadd16 r4, r4, r5",
                "strd r6, r4, [r2], #8",
                "subs r3, r3, #1",
                "bne 2b",
                "3:",
                "pop {{r4-r11, lr}}",
                inout("r0") b as *const PlaceBlock => _,
                inout("r1") positions.as_ptr() => _,
                inout("r2") out.as_mut_ptr() => _,
                inout("r3") n => left,
                out("r12") _,
                out("s0") _,
                out("s1") _,
                out("s2") _,
                out("s3") _,
                out("s4") _,
                out("s5") _,
                out("s8") _,
                out("s9") _,
                out("s10") _,
                out("s11") _,
                out("s12") _,
                out("s13") _,
                out("s14") _,
            );
        }
        return n - left;
    }
    #[allow(unreachable_code)]
    place_run_portable(b, positions, out)
}

/// [`place_run`] by its twin.
fn place_run_portable(b: &PlaceBlock, positions: &[[i16; 3]], out: &mut [CachedVertex]) -> usize {
    for (i, (p, e)) in positions.iter().zip(out.iter_mut()).enumerate() {
        match place_portable(b, p) {
            Some(v) => *e = v,
            None => return i,
        }
    }
    positions.len().min(out.len())
}

/// The vertex loop (`place_run`) against its twin on this target: 24 transforms of the kind
/// `FixedTransform` makes for a perspective camera (random coefficients, w near 2⁴²
/// or anywhere within ±2⁴⁰, x and y scaled by 2¹², 2¹⁴ or 2¹⁶ to reach ±1.5·w to ±24·w,
/// viewports of several sizes and offsets), each over `n` random positions (rounded up to a multiple of 4) in runs of 4 (some placed, some stopping
/// the loop: behind, beside or beyond the screen's range). Returns the number of
/// positions whose entry or stop differs.
pub fn check_place_kernel(n: usize) -> usize {
    // Only the assembly needs checking (the host tests run the twin through it).
    if !PLACE_KERNEL {
        return 0;
    }
    place_check(n).0
}

/// [`check_place_kernel`]'s cases: the differences, the entries placed and the stops.
fn place_check(n: usize) -> (usize, usize, usize) {
    let mut rnd = super::xorshift32(0x9e37_79b9_u32);
    let (mut bad, mut placed, mut stops) = (0, 0, 0);
    let mut positions = [[0i16; 3]; 4];
    let mut got = [CachedVertex::EMPTY; 4];
    let mut want = [CachedVertex::EMPTY; 4];
    let mut block = PlaceBlock {
        rows: [[0; 3]; 6],
        consts: [0.0; 7],
    };
    for case in 0..24u32 {
        // A value within ±2^bits.
        let mut within = |bits: u32| (rnd() as i32) >> (31 - bits);
        for (r, row) in block.rows.iter_mut().enumerate() {
            let (c, t) = match r {
                0 | 1 => ([within(14), within(14), within(14)], within(20)),
                // z and w high sums: w about 2²⁸ (2⁴² in all), z a part of it.
                2 => ([within(11), within(11), within(11)], within(27)),
                3 if case % 4 == 3 => ([within(11), within(11), within(11)], within(26)),
                3 => ([within(11), within(11), within(11)], (1 << 28) + within(26)),
                // The low sums: coefficients and translation in [0, 2¹⁴).
                _ => ([0; 3].map(|_| within(14) & 0x3fff), within(14) & 0x3fff),
            };
            let [c0, c1, c2] = c;
            *row = [
                crate::num::pack_i16(c0 as i16, c1 as i16),
                c2 as u32,
                t as u32,
            ];
        }
        let (hw, hh) = match case % 4 {
            0 => (2560.0, 1920.0),
            1 => (1920.0, 1920.0),
            2 => (512.0, 384.0),
            _ => (8192.0, 6144.0),
        };
        let f = match case % 3 {
            0 => 0.25, // 2^(e − 14) for e = 12, 14, 16
            1 => 1.0,
            _ => 4.0,
        };
        let (dx, dy) = ((case % 3) as f32 * 592.0 - 640.0, (case % 5) as f32 * 176.0);
        block.consts = [
            1.0,
            hw * f,
            hw + dx,
            -hh * f,
            hh + dy,
            65535.0 * 32768.0,
            0.5,
        ];
        for _ in 0..n.div_ceil(4) {
            for p in &mut positions {
                *p = [rnd() as i16, rnd() as i16, rnd() as i16];
            }
            // The first stop, then everything after it, position by position.
            let mut at = 0;
            while let (Some(p), Some(g), Some(w)) =
                (positions.get(at..), got.get_mut(at..), want.get_mut(at..))
            {
                let k = place_run(&block, p, g);
                let j = place_run_portable(&block, p, w);
                let same = g.iter().zip(w.iter()).take(k.min(j));
                bad += usize::from(k != j) + same.filter(|(g, w)| g != w).count();
                placed += j;
                stops += usize::from(j < p.len());
                at += k.min(j) + 1;
            }
        }
    }
    (bad, placed, stops)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding_from_the_double_is_round_f32() {
        let mut next = crate::testing::xorshift32(0x0dd_ba11);
        for k in -80_000..80_000 {
            // Quarters (halves, the ties, among them) and random points beside them.
            let q = k as f32 / 4.0;
            let r = q + (next() % 1000) as f32 / 4096.0 - 0.12;
            for c in [q, r] {
                let want = crate::num::round_f32(c);
                assert_eq!(round_doubled((c * 2.0) as i32), want, "{c}");
            }
        }
    }

    #[test]
    fn place_kernel_is_its_twin() {
        let (bad, placed, stops) = place_check(2000);
        assert_eq!(bad, 0);
        // The check's transforms place most positions and stop at many.
        assert!(
            placed > 24_000 && stops > 4_000,
            "{placed} placed, {stops} stops"
        );
    }
}
