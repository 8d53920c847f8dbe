//! The vertex cache's entries, and its usual vertex on ARMv7E-M with an FPU: the
//! fixed-point transform, the projection and the entry in one assembly loop, two
//! vertices a turn, beside its portable twin.
//!
//! It computes the `f32` path's entry ([`ScreenMap::project_float_inside`] of
//! [`Clip4::to_f32`], then [`CachedVertex::placing`]) bit for bit, with every scale
//! taken as a power of two out of the values (rounding commutes with those): z and w
//! in units of 2¹⁴ (the low partial sum converted with 14 fraction bits, no multiply),
//! x and y without their scale `s` (folded into the screen scales), and the screen
//! coordinates rounded from their doubles truncated. The planes it tests are narrower
//! than the `f32` path's, so that it places no vertex that path would not: w by the
//! reciprocal's sign (w is an integer: w > 0 is w ≥ 1), near and far by the depth (two
//! units of room), the guard band by the cache's screen range (±1024 pixels, inside the
//! band for the viewports [`PlaceBlock`] takes). Any other vertex stops the loop for the
//! caller's exact path.
//!
//! [`ScreenMap::project_float_inside`]: crate::geometry::project::ScreenMap
//! [`Clip4::to_f32`]: crate::geometry::transform::Clip4
#![allow(unsafe_code)]

use super::XyWord;

/// A vertex transformed and projected once per frame (8 bytes), so that every band
/// and every face sharing it reuses the work. See [`Renderer::with_cache`].
///
/// It holds the screen position of a vertex inside the view volume within ±1024 pixels
/// of the origin (x and y in 1/16 pixel below 2¹⁴ in magnitude, so that the cull pass
/// works out areas in `i32`; depth in 16.16). Any other vertex is marked and
/// holds its outcode: faces using it take the general path, which clips them or
/// projects that vertex again.
///
/// [`Renderer::with_cache`]: crate::Renderer::with_cache
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(C)]
pub struct CachedVertex {
    /// Depth in 16.16.
    pub(crate) z: u32,
    /// x and y as one word, x in the low half (the cull scans read the word): x in
    /// 1/16 pixel, or `i16::MIN` (the mark); y in 1/16 pixel, or the outcode when
    /// marked.
    pub(crate) xy: XyWord,
}

// The place kernel stores an entry as two words, depth then x/y, and the set-up kernel
// (`rows::small_less_cached`) reads them in place.
const _: () = assert!(
    core::mem::offset_of!(CachedVertex, z) == 0
        && core::mem::offset_of!(CachedVertex, xy) == 4
        && core::mem::size_of::<CachedVertex>() == 8
        && core::mem::align_of::<CachedVertex>() >= 4
);

/// Whether [`place_pairs`] is the assembly loop (ARMv7E-M with an FPU).
pub(crate) const PLACE_KERNEL: bool =
    cfg!(all(zraster_thumb, zraster_dsp, not(zraster_soft_float)));

/// The operands of [`place_pairs`], read by the loop at fixed offsets (`repr(C)`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub(crate) struct PlaceBlock {
    /// The transform's rows x, y, z high, w high, z low, w low, each as `c₀c₁` and
    /// `c₁c₂` packed ([`pack_i16`](crate::num::pack_i16)), then `t`.
    rows: [[u32; 3]; 6],
    /// The loop's sixteen to twenty-seventh float registers at the start of a pair, as
    /// bits: the sums' starting values (x offset, y offset, x offset, y offset, ½, the
    /// first reciprocal's place, ½, the second's, then 1 and 1 for the depths) and two
    /// words the loop takes back as they are (the end of the pair's entries, and a word
    /// it does not use).
    start: [u32; 12],
    /// 1, the x scale, the y scale and half the depth range.
    scales: [f32; 4],
}

// The loop reads the second pair of rows at 24, the third below `start` (72), the
// scales 48 bytes above it.
const _: () = assert!(
    core::mem::offset_of!(PlaceBlock, start) == 72
        && core::mem::offset_of!(PlaceBlock, scales) == 120
        && core::mem::size_of::<PlaceBlock>() == 136
);

/// Where in [`PlaceBlock::start`] the end of the entries goes.
#[cfg(all(zraster_thumb, zraster_dsp, not(zraster_soft_float)))]
const END: usize = 8;

impl PlaceBlock {
    /// The block of the rows `rows` (x, y, z high, w high, z low, w low, each `c₀c₁`
    /// packed, `c₂`, `t`, as `FixedTransform` gives them) and the screen mapping `x·sx +
    /// ox`, `y·sy + oy` (x and y divided by w, in the rows' scale).
    pub(crate) fn new(rows: [[u32; 3]; 6], [sx, ox, sy, oy]: [f32; 4]) -> PlaceBlock {
        let f = f32::to_bits;
        PlaceBlock {
            rows: rows.map(|[c01, c2, t]| [c01, (c01 >> 16) | (c2 << 16), t]),
            start: [
                f(ox),
                f(oy),
                f(ox),
                f(oy),
                f(0.5),
                0,
                f(0.5),
                0,
                0,
                0,
                f(1.0),
                f(1.0),
            ],
            scales: [1.0, sx, sy, DEPTH_HALF],
        }
    }
}

impl PlaceBlock {
    /// The rows (`c₀c₁`, `c₁c₂`, `t`), the scales (1, x, y, half the depth range) and
    /// the screen offsets (x, y): the operands of the SSE2 loop (`place4`).
    #[cfg_attr(not(any(zraster_x86_64, test)), allow(dead_code))]
    pub(super) fn parts(&self) -> ([[u32; 3]; 6], [f32; 4], [f32; 2]) {
        let [ox, oy, ..] = self.start;
        (self.rows, self.scales, [ox, oy].map(f32::from_bits))
    }
}

/// 65535 · 65536 / 2: window depth (z_ndc + 1)/2 in 16.16 of 0..=65535.
const DEPTH_HALF: f32 = 65535.0 * 32768.0;

/// The entry of position `p`, or `None` where the loop stops: the portable twin of one
/// vertex of [`place_pairs`]'s loop (every operation the same, in the same order, but
/// for the integer sums' order, which wrapping sums do not see).
#[inline(always)]
pub(crate) fn place_portable(b: &PlaceBlock, p: &[i16; 3]) -> Option<CachedVertex> {
    let [x, y, z] = p.map(i32::from);
    let half = |v: u32, k: u32| i32::from((v >> k) as u16 as i16);
    let row = |[c01, c12, t]: [u32; 3]| {
        (half(c01, 0) * x)
            .wrapping_add(half(c01, 16) * y)
            .wrapping_add(half(c12, 16) * z)
            .wrapping_add(t as i32)
    };
    let [x, y, zh, wh, zl, wl] = b.rows.map(row);
    let [one, sx, sy, depth_half] = b.scales;
    let start = b.start.map(f32::from_bits);
    let (ox, oy, half, unit) = (start[0], start[1], start[4], start[10]);
    // z/2¹⁴, w/2¹⁴ as to_f32 rounds them (its z, w times 2⁻¹⁴ exactly).
    let scaled = |h: i32, l: i32| h as f32 + l as f32 * (1.0 / 16384.0);
    let (zf, wf) = (scaled(zh, zl), scaled(wh, wl));
    let inv = one / wf;
    let cx = x as f32 * inv * sx + ox;
    let cy = y as f32 * inv * sy + oy;
    let sz = ((zf * inv + unit) * depth_half + half) as u32;
    // Twice the screen coordinates, truncated and saturated to 16 bits (as VCVT), then
    // rounded (halves away from zero): within ±(2¹⁴ − 1).
    let doubled = |c: f32| ((c * 2.0) as i32).clamp(-32768, 32767);
    let (rx, ry) = (round_doubled(doubled(cx)), round_doubled(doubled(cy)));
    let fits = |r: i32| r.unsigned_abs() < 1 << 14;
    // w > 0 (an integer: w ≥ 1); depth units 1..65533: strictly inside the near and far
    // planes.
    if inv.is_sign_negative() || !(fits(rx) && fits(ry)) || sz.wrapping_sub(1 << 16) >= 0xfffd_0000
    {
        return None;
    }
    Some(CachedVertex {
        z: sz,
        xy: XyWord::new(rx as i16, ry as i16),
    })
}

/// `round_f32(c)` (halves away from zero) from `t = trunc(2c)`, for |c| < 2²²: ⌊c + ½⌋
/// is ⌊(t + 1)/2⌋ for c ≥ 0, and −⌊−c + ½⌋ is ⌊t/2⌋ for c < 0.
#[inline(always)]
fn round_doubled(t: i32) -> i32 {
    (t + i32::from(t >= 0)) >> 1
}

/// Whether `positions` starts on a word (four bytes), as [`place_pairs`] loads them.
#[inline(always)]
fn on_word(positions: &[[i16; 3]]) -> bool {
    (positions.as_ptr() as usize).is_multiple_of(4)
}

/// Writes the entries of `positions` into `out` from the first on, up to the first
/// position [`place_portable`] does not place, and returns how many it wrote (at most the
/// shorter length): pairs of positions by [`place_pairs`] where they start on a word,
/// the rest (the first of a pair the loop stops at, one on a half word, the last) by
/// the twin.
#[inline]
pub(crate) fn place_run(
    b: &mut PlaceBlock,
    positions: &[[i16; 3]],
    out: &mut [CachedVertex],
) -> usize {
    let n = positions.len().min(out.len());
    let mut at = 0;
    while let (Some(p), Some(o)) = (positions.get(at..n), out.get_mut(at..n)) {
        if p.len() >= 2 && on_word(p) {
            at += place_pairs(b, p, o);
        }
        let (Some(p), Some(e)) = (positions.get(at), out.get_mut(at)) else {
            break;
        };
        match place_portable(b, p) {
            Some(v) => *e = v,
            None => return at,
        }
        at += 1;
    }
    n
}

/// Writes the entries of `positions` into `out` two by two from the first on, up to the
/// first pair with a position [`place_portable`] does not place, and returns how many it
/// wrote (even, at most the shorter length rounded down). `positions` starts on a word
/// (else it writes nothing). On ARMv7E-M with an FPU an assembly loop of 95 instructions
/// a pair; elsewhere the twin.
#[inline]
fn place_pairs(b: &mut PlaceBlock, positions: &[[i16; 3]], out: &mut [CachedVertex]) -> usize {
    let pairs = positions.len().min(out.len()) / 2;
    if pairs == 0 || !on_word(positions) {
        return 0;
    }
    #[cfg(all(zraster_thumb, zraster_dsp, not(zraster_soft_float)))]
    {
        let start = out.as_mut_ptr();
        b.start[END] = start.wrapping_add(2 * pairs) as usize as u32;
        let end: *mut CachedVertex;
        // SAFETY: reads `PlaceBlock`'s 34 words (`repr(C)`: rows at 0, `start` at 72,
        // `scales` at 120) and, for `pairs` ≥ 1 turns at most, two positions a turn
        // (12 bytes by one LDM, from `positions`' start, which is word-aligned; `[i16;
        // 3]` is 6 bytes) and writes two entries a turn with one STM (16 bytes, from
        // `out`'s start, 4-byte aligned as `CachedVertex` is), until `out` reaches the
        // end written in the block, 2·pairs entries on; `pairs` is at most half either
        // length, and a turn that stops writes nothing. `CachedVertex` is `repr(C)`: the
        // depth word, then the x/y word (x in the low half: `XyWord`), any bits valid.
        // r4–r11 and lr are pushed first and popped last; r3 and r12 are clobbered, as
        // are s0–s27 (the compiler saves s16–s27) and the flags. A turn pushes 48 bytes
        // of sums and 40 of float registers, and pops them.
        //
        // A turn: the two positions (a = x₀y₀, b = z₀x₁, c = y₁z₁), each pair of rows
        // by one LDM (r0 and r3 are the block plus 24 and 72: the first below r0, the
        // second above it, the third below r3) and four multiply-accumulates a row
        // (SMLABT and SMLAD for the first position, SMLAD and SMLATB for the second),
        // the sums pushed four at a time and popped into s0–s11 (z, w low; z, w high;
        // x, y; each first then second position); the conversions (the low sums with
        // 14 fraction bits), one VDIV each, the screen coordinates accumulated from
        // their offsets (VMLA rounds the product, then the sum), doubled, truncated and
        // saturated to 16 bits, the depths from ½; s16–s25 pushed and popped into
        // r4–lr. Then both reciprocals' signs, the halves rounded by SHADD16 (plus 1
        // where above 0: USAT16 to [0, 1]), and three products of halves, one for each
        // coordinate of the two positions, each zero if a half is: of the depths' top
        // halves plus 2 without their low two bits (a carry from the first half only
        // where that is already zero), and of 2r + 2¹⁵ for the rounded x and y (zero
        // modulo 2¹⁶ only for r = ±2¹⁴).
        unsafe {
            core::arch::asm!(
                "push {{r4-r11, lr}}",
                "add r3, r0, #72",
                "add r0, r0, #24",
                "add r12, r3, #48",
                "vldm r12, {{s12-s15}}",
                "2:",
                "ldm r1!, {{r10, r11, r12}}",
                "ldmdb r0, {{r4-r9}}",
                "smlabt lr, r11, r5, r6",
                "smlad r6, r12, r5, r6",
                "smlad r5, r10, r4, lr",
                "smlatb r6, r11, r4, r6",
                "smlabt lr, r11, r8, r9",
                "smlad r9, r12, r8, r9",
                "smlad r8, r10, r7, lr",
                "smlatb r9, r11, r7, r9",
                "push {{r5, r6, r8, r9}}",
                "ldm r0, {{r4-r9}}",
                "smlabt lr, r11, r5, r6",
                "smlad r6, r12, r5, r6",
                "smlad r5, r10, r4, lr",
                "smlatb r6, r11, r4, r6",
                "smlabt lr, r11, r8, r9",
                "smlad r9, r12, r8, r9",
                "smlad r8, r10, r7, lr",
                "smlatb r9, r11, r7, r9",
                "push {{r5, r6, r8, r9}}",
                "ldmdb r3, {{r4-r9}}",
                "smlabt lr, r11, r5, r6",
                "smlad r6, r12, r5, r6",
                "smlad r5, r10, r4, lr",
                "smlatb r6, r11, r4, r6",
                "smlabt lr, r11, r8, r9",
                "smlad r9, r12, r8, r9",
                "smlad r8, r10, r7, lr",
                "smlatb r9, r11, r7, r9",
                "push {{r5, r6, r8, r9}}",
                "vpop {{s0-s11}}",
                "vldm r3, {{s16-s27}}",
                "vcvt.f32.s32 s0, s0, #14",
                "vcvt.f32.s32 s1, s1, #14",
                "vcvt.f32.s32 s2, s2, #14",
                "vcvt.f32.s32 s3, s3, #14",
                "vcvt.f32.s32 s4, s4",
                "vcvt.f32.s32 s5, s5",
                "vcvt.f32.s32 s6, s6",
                "vcvt.f32.s32 s7, s7",
                "vcvt.f32.s32 s8, s8",
                "vcvt.f32.s32 s9, s9",
                "vcvt.f32.s32 s10, s10",
                "vcvt.f32.s32 s11, s11",
                "vadd.f32 s6, s6, s2",
                "vadd.f32 s7, s7, s3",
                "vdiv.f32 s21, s12, s6",
                "vdiv.f32 s23, s12, s7",
                "vadd.f32 s4, s4, s0",
                "vadd.f32 s5, s5, s1",
                "vmul.f32 s8, s8, s21",
                "vmul.f32 s9, s9, s23",
                "vmul.f32 s10, s10, s21",
                "vmul.f32 s11, s11, s23",
                "vmla.f32 s16, s8, s13",
                "vmla.f32 s17, s10, s14",
                "vmla.f32 s18, s9, s13",
                "vmla.f32 s19, s11, s14",
                "vmla.f32 s26, s4, s21",
                "vmla.f32 s27, s5, s23",
                "vmla.f32 s20, s26, s15",
                "vmla.f32 s22, s27, s15",
                "vcvt.s16.f32 s16, s16, #1",
                "vcvt.s16.f32 s17, s17, #1",
                "vcvt.s16.f32 s18, s18, #1",
                "vcvt.s16.f32 s19, s19, #1",
                "vcvt.u32.f32 s20, s20",
                "vcvt.u32.f32 s22, s22",
                "vpush {{s16-s25}}",
                "pop {{r4-r12, lr}}",
                "orrs r9, r9, r11",
                "bmi 3f",
                "pkhtb lr, r10, r8, asr #16",
                "add.w lr, lr, #0x20002",
                "bic.w lr, lr, #0x30003",
                "pkhbt r4, r4, r5, lsl #16",
                "pkhbt r6, r6, r7, lsl #16",
                "usat16 r5, #1, r4",
                "usat16 r7, #1, r6",
                "shadd16 r9, r4, r5",
                "shadd16 r11, r6, r7",
                "sadd16 r4, r9, r9",
                "sadd16 r6, r11, r11",
                "eor r4, r4, #0x80008000",
                "eor r6, r6, #0x80008000",
                "smulbb r5, r4, r6",
                "smultt r7, r4, r6",
                "smulbt r4, lr, lr",
                "cbz r5, 3f",
                "cbz r7, 3f",
                "cbz r4, 3f",
                "stm r2!, {{r8-r11}}",
                "cmp r2, r12",
                "bne 2b",
                "3:",
                "pop {{r4-r11, lr}}",
                inout("r0") &raw const *b => _,
                inout("r1") positions.as_ptr() => _,
                inout("r2") start => end,
                out("r3") _,
                out("r12") _,
                out("s0") _,
                out("s1") _,
                out("s2") _,
                out("s3") _,
                out("s4") _,
                out("s5") _,
                out("s6") _,
                out("s7") _,
                out("s8") _,
                out("s9") _,
                out("s10") _,
                out("s11") _,
                out("s12") _,
                out("s13") _,
                out("s14") _,
                out("s15") _,
                out("s16") _,
                out("s17") _,
                out("s18") _,
                out("s19") _,
                out("s20") _,
                out("s21") _,
                out("s22") _,
                out("s23") _,
                out("s24") _,
                out("s25") _,
                out("s26") _,
                out("s27") _,
            );
        }
        return (end as usize - start as usize) / 8;
    }
    #[allow(unreachable_code)]
    place_pairs_portable(b, positions, out)
}

/// [`place_pairs`] by its twin.
fn place_pairs_portable(b: &PlaceBlock, positions: &[[i16; 3]], out: &mut [CachedVertex]) -> usize {
    if !on_word(positions) {
        return 0;
    }
    let pairs = positions.chunks_exact(2).zip(out.chunks_exact_mut(2));
    for (i, (p, e)) in pairs.enumerate() {
        match (p, e) {
            ([p0, p1], [e0, e1]) => match (place_portable(b, p0), place_portable(b, p1)) {
                (Some(v0), Some(v1)) => (*e0, *e1) = (v0, v1),
                _ => return 2 * i,
            },
            _ => return 2 * i,
        }
    }
    positions.len().min(out.len()) & !1
}

/// The vertex loop (`place_pairs`) against its twin on this target: 24 transforms of
/// the kind `FixedTransform` makes for a perspective camera (random coefficients, w near
/// 2⁴² or anywhere within ±2⁴⁰, x and y scaled by 2¹², 2¹⁴ or 2¹⁶ to reach ±1.5·w to
/// ±24·w, viewports of several sizes and offsets), each over `n` random positions
/// (rounded up to a multiple of 4) in runs of two pairs (some placed, some stopping the
/// loop: behind, beside or beyond the screen's range), the second pair again alone.
/// Returns the number of positions whose entry or stop differs.
pub fn check_place_kernel(n: usize) -> usize {
    // Only the assembly needs checking (the host tests run the twin through it).
    if !PLACE_KERNEL {
        return 0;
    }
    place_check(n).0
}

/// Two pairs of positions starting on a word, as [`place_pairs`] takes them.
#[repr(C, align(4))]
struct Run([[i16; 3]; 4]);

/// The six rows of a random fixed-point transform for the vertex kernels' checks, as
/// coefficients and translation: x and y rows with c₀, c₁, c₂ within ±2¹⁴; the z and w
/// high sums (w about 2²⁸, 2⁴² in all, z a part of it; every fourth `case` a w anywhere
/// within ±2²⁶); the low sums in [0, 2¹⁴).
pub(super) fn random_rows(rnd: &mut impl FnMut() -> u32, case: u32) -> [([i32; 3], i32); 6] {
    // A value within ±2^bits.
    let mut within = |bits: u32| (rnd() as i32) >> (31 - bits);
    let mut rows = [([0; 3], 0); 6];
    for (r, row) in rows.iter_mut().enumerate() {
        *row = match r {
            0 | 1 => ([within(14), within(14), within(14)], within(20)),
            2 => ([within(11), within(11), within(11)], within(27)),
            3 if case % 4 == 3 => ([within(11), within(11), within(11)], within(26)),
            3 => ([within(11), within(11), within(11)], (1 << 28) + within(26)),
            _ => ([0; 3].map(|_| within(14) & 0x3fff), within(14) & 0x3fff),
        };
    }
    rows
}

/// [`check_place_kernel`]'s cases: the differences, the entries placed and the stops.
fn place_check(n: usize) -> (usize, usize, usize) {
    let mut rnd = super::xorshift32(0x9e37_79b9_u32);
    let (mut bad, mut placed, mut stops) = (0, 0, 0);
    let mut run = Run([[0; 3]; 4]);
    let mut got = [CachedVertex::EMPTY; 4];
    let mut want = [CachedVertex::EMPTY; 4];
    let mut rows = [[0; 3]; 6];
    for case in 0..24u32 {
        for (row, ([c0, c1, c2], t)) in rows.iter_mut().zip(random_rows(&mut rnd, case)) {
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
        let mut block = PlaceBlock::new(rows, [hw * f, hw + dx, -hh * f, hh + dy]);
        for _ in 0..n.div_ceil(4) {
            for p in &mut run.0 {
                *p = [rnd() as i16, rnd() as i16, rnd() as i16];
            }
            // Both pairs, then the second alone.
            for at in [0, 2] {
                let (Some(p), Some(g), Some(w)) =
                    (run.0.get(at..), got.get_mut(at..), want.get_mut(at..))
                else {
                    continue;
                };
                let k = place_pairs(&mut block, p, g);
                let j = place_pairs_portable(&block, p, w);
                let same = g.iter().zip(w.iter()).take(k.min(j));
                bad += usize::from(k != j) + same.filter(|(g, w)| g != w).count();
                placed += j;
                stops += usize::from(j < p.len());
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

    /// The loop's tests on packed halves are the twin's: for every truncated double t
    /// (VCVT's 16 bits), the halves rounded by SHADD16 with USAT16's addend are
    /// `round_doubled`, and 2r + 2¹⁵ is zero modulo 2¹⁶ exactly where r leaves ±(2¹⁴ −
    /// 1); for every depth unit of either position (the other's in and out of range),
    /// the depths' product of halves is zero exactly where the twin stops.
    #[test]
    fn packed_tests_are_the_twins() {
        let halves = |w: u32| [w as u16 as i16 as i32, (w >> 16) as u16 as i16 as i32];
        let pack = |[lo, hi]: [i32; 2]| (lo as u32 & 0xffff) | (hi as u32) << 16;
        for t in -32768..32768 {
            let p = pack([t, -1 - t]);
            let m = pack(halves(p).map(|h| h.clamp(0, 1))); // USAT16 #1
            let r = pack([0, 1].map(|k| (halves(p)[k] + halves(m)[k]) >> 1)); // SHADD16
            assert_eq!(halves(r), [round_doubled(t), round_doubled(-1 - t)]);
            let z = halves(r).map(|h| (2 * h + 0x8000) as u16); // SADD16, EOR
            let fits = |h: i32| h.unsigned_abs() < 1 << 14;
            assert_eq!(z.map(|h| h != 0), halves(r).map(fits), "{t}");
        }
        let depth_ok = |sz: u32| sz.wrapping_add(2 << 16) >= 4 << 16;
        for h in 0..1 << 16 {
            for other in [0u32, 1, 2, 3, 100, 65533, 65534, 65535] {
                for (a, b) in [(h, other), (other, h)] {
                    let (sa, sb) = (a << 16 | 0x8000, b << 16 | 0x1234);
                    let d = ((sb & 0xffff_0000) | sa >> 16).wrapping_add(0x2_0002) & !0x3_0003;
                    let product = i32::from(d as u16 as i16) * i32::from((d >> 16) as u16 as i16);
                    assert_eq!(product != 0, depth_ok(sa) && depth_ok(sb), "{a} {b}");
                }
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
