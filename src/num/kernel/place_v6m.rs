//! The vertex cache's usual vertex on ARMv6-M: the fixed-point transform, the integer
//! projection and the entry in one Thumb-1 assembly loop, beside its portable twin.
//!
//! It computes `ScreenMap::project_integer`'s entry for the usual vertex, as
//! `ScreenMap::project_fast` of `FixedTransform::apply` then `CachedVertex::placing`
//! do, in its own steps: the six rows (x, y, z and w in two partial sums each), the
//! near, far and w planes on z and w in units of 2¹⁴, w's bits beyond 31 against the
//! hint the block carries (a four-step search on a miss), w and z + w normalised from
//! the partial sums, the reciprocal ⌊2⁶²/wn⌋ ([`recip62_low`], the integer
//! projection's too, its first step from the 512-entry table `recip32_small` reads),
//! the screen coordinates by five 16 × 16-bit products each in two's complement (x and
//! y's scale folded into the half extent) and the depth by the rounded high word of
//! four. Its coordinates have their own error bound (viewports up to 4096 pixels,
//! centred within ±4096): it leaves 4 values in 16,384 next to a rounding boundary,
//! not the same ones as `project_fast`, and places some that `project_fast` leaves.
//! Any vertex it does not place stops the loop for the caller's exact path.
#![allow(unsafe_code)]

use super::{CachedVertex, XyWord};
use crate::num::armv6m::RECIP16;

/// Whether [`place_run_v6m`] is the assembly loop (ARMv6-M).
pub(crate) const PLACE_V6M_KERNEL: bool = cfg!(all(zraster_thumb, zraster_armv6m));

/// The operands of [`place_run_v6m`], read by the loop at fixed offsets (`repr(C)`).
///
/// x and y in the z/w scale normalised by 2^sh are `v·2^(e − sh)` for the row value v:
/// for k = sh − e > 0 the loop shifts v right by k; otherwise it takes `v·2^L` (L = −k)
/// as v times `h·2^L₂` (L₂ the most of L that keeps the factor within 2¹⁵, and at most
/// 5, which keeps |x|, |y| within 64·w: the guard band) shifted left by the rest L₁.
/// Where some L₁ > 0 (a slow mode: a large image of a small viewport) the hint is 48 +
/// sh, so that every vertex takes the search's way, which shifts and range-tests v.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(C)]
pub(crate) struct PlaceV6m<'a> {
    /// The rows x, y, z high, w high, z low, w low: `c₀`, `c₁`, `c₂`, `t` each (a copy:
    /// the loop's last row LDM leaves its pointer at the hint).
    rows: [[i32; 4]; 6],
    /// 16 + sh for w's bits sh beyond 31 at the last vertex that changed it (the hint,
    /// sh in 1..=14), 48 + sh in the slow mode.
    hint: u32,
    /// 14 − sh.
    up: u32,
    /// The depth's and the coordinates' operands, in the order the loop loads them
    /// (`D_ROUND` to `X_ORIGIN`): 2¹⁵ and 2¹⁴ − 1, then for y and x v's right shift,
    /// the half extent times 2^L₂, the origin (1/16 pixel) times 2¹⁴ plus the rounding
    /// constant, and the bias and limit of a placed coordinate (|c| < 2¹⁴).
    ops: [u32; 12],
    /// Unused: the word the loop's offsets from the hint leave here.
    spare: u32,
    /// The exponent `e` of x and y's scale to z and w's (0..=20).
    e: u32,
    /// The half height and width (1/16 pixel, at most 2¹⁵).
    half: [u32; 2],
    /// For y and x, the most of L folded into the half extent.
    fold: [u32; 2],
    /// For y and x, L₁: the rest of L, v's left shift (0 but in the slow mode).
    left: [u32; 2],
    /// The transform the rows are from.
    from: core::marker::PhantomData<&'a [[i32; 4]; 6]>,
}

// The loop reads the rows at 0 by LDM, and from the hint at 96 on: the hint at +0,
// 14 − sh at +4, the operands at +8, e at +60, the halves at +64, the folds at +72 and
// L₁ at +80 (words).
#[cfg(all(zraster_thumb, zraster_armv6m))]
const _: () = assert!(
    core::mem::offset_of!(PlaceV6m<'_>, rows) == 0
        && core::mem::offset_of!(PlaceV6m<'_>, hint) == 96
        && core::mem::offset_of!(PlaceV6m<'_>, up) == 96 + 4
        && core::mem::offset_of!(PlaceV6m<'_>, ops) == 96 + 8
        && core::mem::offset_of!(PlaceV6m<'_>, spare) == 96 + 56
        && core::mem::offset_of!(PlaceV6m<'_>, e) == 96 + 60
        && core::mem::offset_of!(PlaceV6m<'_>, half) == 96 + 64
        && core::mem::offset_of!(PlaceV6m<'_>, fold) == 96 + 72
        && core::mem::offset_of!(PlaceV6m<'_>, left) == 96 + 80
        && core::mem::size_of::<PlaceV6m<'_>>() == 96 + 88
        && core::mem::size_of::<[[i32; 4]; 6]>() == 96
);

/// Where in `ops` each operand goes: the depth's two constants (one load), y's right
/// shift, factor and origin, x's right shift (the same) with y's bias and limit (one
/// load), x's bias, limit, factor and origin (one load).
const D_ROUND: usize = 0;
const D_K: usize = 1;
const Y_RIGHT: usize = 2;
const Y_FACTOR: usize = 3;
const Y_ORIGIN: usize = 4;
const X_RIGHT: usize = 5;
const Y_BIAS: usize = 6;
const Y_LIMIT: usize = 7;
const X_BIAS: usize = 8;
const X_LIMIT: usize = 9;
const X_FACTOR: usize = 10;
const X_ORIGIN: usize = 11;

impl<'a> PlaceV6m<'a> {
    /// The block of the rows `rows` (x, y, z high, w high, z low, w low, each `[c₀, c₁,
    /// c₂, t]`, as `FixedTransform::with_rows_v6m` gives them), x and y's scale exponent `e`
    /// (0..=20), the half width and height `half` (1/16 pixel, 1 to 2¹⁵) and the
    /// origin `org` (within ±2¹⁶). Its hint misses (a shift by 31 in the slow mode's
    /// test), so that the first vertex's search sets the hint and the shifts.
    pub(crate) fn new(rows: &'a [[i32; 4]; 6], e: u32, half: [u32; 2], org: [i32; 2]) -> Self {
        let k = (1 << 14) - 1;
        // G = org·2¹⁴ + 2¹³ + 2 + F for x, org·2¹⁴ + 2¹³ − F for y (see `placed`).
        let origin = |o: i32, r: u32| ((o << 14) as u32).wrapping_add(r);
        // The shifts and factors (k until the first search) and the rest.
        let mut ops = [k; 12];
        (ops[D_ROUND], ops[D_K]) = (1 << 15, k);
        ops[Y_ORIGIN] = origin(org[1], 1 << 13);
        ops[X_ORIGIN] = origin(org[0], (1 << 13) + 2);
        (ops[Y_LIMIT], ops[X_LIMIT]) = (2 * k, 2 * k);
        let half = [half[1], half[0]];
        PlaceV6m {
            rows: *rows,
            hint: 63,
            up: 0,
            ops,
            spare: 0,
            e,
            half,
            // The most f with h·2^f ≤ 2¹⁵ (15 − ⌈log₂ h⌉), at most 5.
            fold: half.map(|h| h.wrapping_sub(1).leading_zeros().saturating_sub(17).min(5)),
            left: [0; 2],
            from: core::marker::PhantomData,
        }
    }

    /// The hint for w's bits `sh` beyond 31 (1..=14) and the operands of the
    /// normalisation by 2^(sh − e) (see [`PlaceV6m`]).
    fn set_sh(&mut self, sh: u32) {
        let k = sh as i32 - self.e as i32;
        let (right, l) = if k > 0 {
            (k as u32, 0)
        } else {
            (0, (-k) as u32)
        };
        self.up = 14 - sh;
        let [l2y, l2x] = self.fold.map(|f| l.min(f));
        let [hy, hx] = self.half;
        let o = &mut self.ops;
        (o[Y_RIGHT], o[X_RIGHT]) = (right, right);
        (o[Y_FACTOR], o[X_FACTOR]) = (hy << l2y, hx << l2x);
        self.left = [l - l2y, l - l2x];
        self.hint = 16 + sh + if self.left == [0; 2] { 0 } else { 32 };
    }
}

/// v·2^l where |v| < 2^(31 − l) (the slow mode's left shift of a row value), else
/// `None`.
#[inline(always)]
fn widened(v: i32, l: u32) -> Option<i32> {
    if l == 0 {
        return Some(v);
    }
    let m = i32::MAX as u32 >> l;
    ((v as u32).wrapping_add(m) <= 2 * m).then(|| v << l)
}

/// About 2³¹/(v + 1) for 2¹⁵ ≤ v < 2¹⁶, from below: the table's 2²⁵/(513 + i) for v's
/// top nine bits (at most 2³¹/(v + 1), and within 2⁻⁹ of it) and one Newton step,
/// which leaves it in (2³¹/(v + 1) − 1.3, 2³¹/(v + 1)] (the step's square 0.28, the
/// dropped bits 1.01; a test checks every v).
#[inline(always)]
fn recip31_table(v: u32) -> u32 {
    let w = v + 1;
    let i = ((v >> 6) & 0x1ff) as usize;
    let t = u32::from(RECIP16.get(i).copied().unwrap_or(0));
    // e = 2³¹ − w·t in [0, 2²³) (the low 31 bits of −w·t): t·⌊e/2⁷⌋ < 2³².
    let e = w.wrapping_neg().wrapping_mul(t) << 1 >> 1;
    t.wrapping_add(t.wrapping_mul(e >> 7) >> 24)
}

/// ⌊2⁶²/d⌋ for 2³⁰ < d < 2³¹ in 32-bit multiplies, without a division (on ARMv6-M,
/// 64-bit products are long): the integer projection's reciprocal, here beside the
/// vertex loop that does the same. Each step's error is read off the low word of a
/// product, exact because the step keeps it within 32 bits:
///
/// 1. y ≈ 2³¹/(v + 1) from below, within 1.3, for d's top 16 bits v
///    ([`recip31_table`]). Then y ≤ 2³¹/(v + 1) ≤ 2⁴⁶/d, and 2⁴⁶/d − y < 2³¹/(v(v +
///    1)) + 1.3 ≤ 3.3, so e = 2⁴⁶ − d·y is in [0, 3.3·d) and y·e < 3.3·2⁴⁶.
/// 2. e'' = 2⁴⁵ − ⌈d/2⌉·y = (e − (d mod 2)·y)/2, in (−2¹⁵, 1.65·2⁴⁶/y], is the low
///    word of −⌈d/2⌉·y as a signed number (−⌈d/2⌉ = (−d) >> 1). With ε = e/2⁴⁶ <
///    3.3·2⁻¹⁵, 2⁴⁹/d = 8y/(1 − ε) = 8y + y·e/2⁴³ + 8y·ε²/(1 − ε), the last term below
///    0.006: y' = 8y + ⌊y·⌊e''/2¹⁷⌋/2²⁵⌋ (|y·⌊e''/2¹⁷⌋| < 2³¹) lies within
///    (2⁴⁹/d − 1.02, 2⁴⁹/d] (y²/2⁴³ < 2⁻¹¹ for the halved remainder, 2⁻⁹ and 1
///    dropped), so e' = 2⁴⁹ − d·y' is in [0, 2d) ⊂ [0, 2³²).
/// 3. Likewise 2⁶²/d = 2¹³y' + y'·e'/2³⁶ + t with t = 2¹³y'·ε'²/(1 − ε') < ¼
///    (ε' < 2⁻¹⁷, y' < 2¹⁹); x = 2¹³y' + ⌊(y'/8)·e'/2³³⌋ (the product from 16-bit
///    halves of e', y'/8 < 2¹⁶) drops below 0.5 + 2⁻¹⁷ + 1, so 2⁶²/d − x ∈ [0, 2).
///    The remainder 2⁶² − d·x is then in [0, 2d) ⊂ [0, 2³²): x or x + 1.
#[inline(always)]
pub(crate) fn recip62_low(d: u32) -> u32 {
    // 1.
    let y = recip31_table(d >> 15);
    // 2.
    let e = (d.wrapping_neg() as i32 >> 1).wrapping_mul(y as i32);
    let y = (8 * y).wrapping_add(((y as i32).wrapping_mul(e >> 17) >> 25) as u32);
    // 3.
    let e = d.wrapping_mul(y).wrapping_neg();
    let h = y >> 3;
    let x = (y << 13) + ((h * (e >> 16) + ((h * (e & 0xffff)) >> 16)) >> 17);
    x + u32::from(d.wrapping_mul(x).wrapping_neg() >= d)
}

/// F = ⌊P·H/2¹⁶⌋ for a = v >> `right`, P ≈ a·r/2³² (r = ⌊2⁶²/wn⌋ in halves `rh`,
/// `rl`) and the factor H ≤ 2¹⁵: within 2.5 below V = a·H·r/2⁴⁸, the screen
/// coordinate's offset from its origin in units of 2⁻¹⁴ (v already shifted left by
/// L₁), |F| ≤ 2³⁰.
///
/// In two's complement throughout: with a = a₁·2¹⁶ + a₀ (a₁ signed), P = a₁r₁ +
/// ⌊a₁r₀/2¹⁶⌋ + ⌊a₀r₁/2¹⁶⌋ lies in (X − 3, X] for X = a·r/2³² (three dropped
/// fractions; P ≥ −2³¹ as X ≥ −2³¹ + 2 for r ≤ 2³² − 4), F = p₁H + ⌊p₀H/2¹⁶⌋ in
/// (V − 3H/2¹⁶ − 1, V].
#[inline(always)]
fn scaled(v: i32, right: u32, h: u32, rh: u32, rl: u32) -> i32 {
    let a = v >> right;
    let (a1, a0) = (a >> 16, (a & 0xffff) as u32);
    let p = a1
        .wrapping_mul(rh as i32)
        .wrapping_add(a1.wrapping_mul(rl as i32) >> 16)
        .wrapping_add((a0.wrapping_mul(rh) >> 16) as i32);
    (p >> 16)
        .wrapping_mul(h as i32)
        .wrapping_add((((p & 0xffff) as u32).wrapping_mul(h) >> 16) as i32)
}

/// The placed coordinate ⌊G/2¹⁴⌋ with |c| < 2¹⁴ (c + bias ≤ limit unsigned, as
/// `CachedVertex::placing` tests it), or `None` there or where G mod 2¹⁴ < 4.
///
/// For x, G = org·2¹⁴ + 2¹³ + 2 + F: V + 2¹³ lies in [g − 2, g + ½) for g = G −
/// org·2¹⁴, so where G mod 2¹⁴ ≥ 4 no multiple of 2¹⁴ is in it and ⌊G/2¹⁴⌋ is org +
/// ⌊(V + 2¹³)/2¹⁴⌋, no tie: the offset rounded, halves away from zero for either sign.
/// For y, G = org·2¹⁴ + 2¹³ − F = org·2¹⁴ + 2¹⁴ + X for X = −F − 2¹³, and −V − 2¹³
/// lies in (X − 2.5, X]: where X mod 2¹⁴ = G mod 2¹⁴ ≥ 3 no multiple of 2¹⁴ is in
/// [X − 2, X], so ⌊G/2¹⁴⌋ = org + ⌈X/2¹⁴⌉ = org − ⌊(V + 2¹³)/2¹⁴⌋, no tie. (|org| <
/// 2¹⁶ and |F| ≤ 2³⁰: |G| < 2³¹.)
#[inline(always)]
fn placed(g: i32, bias: u32, limit: u32) -> Option<i32> {
    if g & 0x3fff < 4 {
        return None;
    }
    let c = g >> 14;
    ((c as u32).wrapping_add(bias) <= limit).then_some(c)
}

/// The entry of position `p`, or `None` where the loop stops: the portable twin of one
/// vertex of [`place_run_v6m`]'s loop (every step the same, the hint updated alike).
pub(crate) fn place_v6m_portable(b: &mut PlaceV6m<'_>, p: &[i16; 3]) -> Option<CachedVertex> {
    let [px, py, pz] = p.map(i32::from);
    let row = |[c0, c1, c2, t]: [i32; 4]| {
        c0.wrapping_mul(px)
            .wrapping_add(c1.wrapping_mul(py))
            .wrapping_add(c2.wrapping_mul(pz))
            .wrapping_add(t)
    };
    let [mut x, mut y, zh, wh, zl, wl] = b.rows.map(row);
    let (zt, wt) = (zh.wrapping_add(zl >> 14), wh.wrapping_add(wl >> 14));
    // z strictly between −w and w with a unit of room, then w ≥ 2³¹ (the hint's test
    // or the search's; a negative wt fails one of the z tests).
    if zt >= wt.wrapping_sub(1) || i64::from(zt) + i64::from(wt) <= 0 {
        return None;
    }
    // (wt − 1) >> (16 + sh) = 1 for the hint's sh (a shift by 32 or more gives 0),
    // else the slow mode's same sh, else sh = 1 + ⌊log₂(wt/2¹⁷)⌋.
    let (wt, w1) = (wt as u32, wt.wrapping_sub(1) as u32);
    if w1.checked_shr(b.hint).unwrap_or(0) != 1 {
        if b.hint < 48 || w1 >> (b.hint - 32) != 1 {
            let mut t = wt >> 17;
            if t == 0 {
                return None;
            }
            let mut sh = 1;
            for k in [8, 4, 2, 1] {
                if t >> k != 0 {
                    t >>= k;
                    sh += k;
                }
            }
            b.set_sh(sh);
        }
        y = widened(y, b.left[0])?;
        x = widened(x, b.left[1])?;
        // wt = 2¹⁶⁺ˢʰ (where wn may be 2³⁰) left.
        if w1 >> ((b.hint & 31) - 16) >> 16 != 1 {
            return None;
        }
    }
    // wn = ⌊w/2^sh⌋ = (wh << up) + (wl >> sh), un = ⌊(z + w)/2^sh⌋ likewise (the top
    // parts are multiples of 2^sh), both exact modulo 2³² and below it.
    let (sh, up) = ((b.hint & 31) - 16, b.up);
    let wn = ((wh as u32) << up).wrapping_add((wl >> sh) as u32);
    if wn >> 31 != 0 {
        return None; // wt = 2¹⁷⁺ˢʰ, from the hint's test
    }
    let ul = i64::from(zl) + i64::from(wl);
    let un = ((zh.wrapping_add(wh) as u32) << up).wrapping_add((ul >> sh) as u32);
    let r = recip62_low(wn);
    let (rh, rl) = (r >> 16, r & 0xffff);
    // Depth: the rounded high word of un·r (q30), then 2·q30 − ⌊(q30 + 2¹⁴ − 1)/2¹⁵⌋.
    // z < w − 2¹⁴ makes un ≤ 2·wn, so un·r ≤ 2⁶³ and q30 ≤ 2³¹ (where the depth is
    // MAX_DEPTH): no clamp.
    let (a1, a0) = (un >> 16, un & 0xffff);
    let (m1, m2) = (a1.wrapping_mul(rl), a0.wrapping_mul(rh));
    let low = (a0.wrapping_mul(rl) >> 16)
        .wrapping_add(m1 & 0xffff)
        .wrapping_add(m2 & 0xffff)
        .wrapping_add(1 << 15);
    let q30 = a1
        .wrapping_mul(rh)
        .wrapping_add(m1 >> 16)
        .wrapping_add(m2 >> 16)
        .wrapping_add(low >> 16);
    let d = q30.wrapping_add((1 << 14) - 1) >> 15;
    let sz = q30.wrapping_add(q30.wrapping_sub(d));
    let o = &b.ops;
    let fy = scaled(y, o[Y_RIGHT], o[Y_FACTOR], rh, rl);
    let sy = placed((o[Y_ORIGIN] as i32).wrapping_sub(fy), o[Y_BIAS], o[Y_LIMIT])?;
    let fx = scaled(x, o[X_RIGHT], o[X_FACTOR], rh, rl);
    let sx = placed((o[X_ORIGIN] as i32).wrapping_add(fx), o[X_BIAS], o[X_LIMIT])?;
    Some(CachedVertex {
        z: sz,
        xy: XyWord::new(sx as i16, sy as i16),
    })
}

/// Writes the entries of `positions` into `out` from the first on, up to the first
/// position [`place_v6m_portable`] does not place, and returns how many it wrote (at
/// most the shorter length; the entry after those may be written in part, for the
/// caller to write). On ARMv6-M the assembly loop; elsewhere the twin.
#[inline]
pub(crate) fn place_run_v6m(
    b: &mut PlaceV6m<'_>,
    positions: &[[i16; 3]],
    out: &mut [CachedVertex],
) -> usize {
    let n = positions.len().min(out.len());
    if n == 0 {
        return 0;
    }
    #[cfg(all(zraster_thumb, zraster_armv6m))]
    {
        let start = out.as_mut_ptr().cast::<u32>();
        // SAFETY: the loop reads the block (`repr(C)`, 184 bytes, 4-aligned: its rows,
        // then 88 bytes from the hint) and writes its hint and shift words, reads one position a
        // turn (three halfwords, 2-aligned as `[i16; 3]` is) from `positions`' start and
        // writes one entry a turn (a word and two halfwords, 4-aligned as
        // `CachedVertex` is; any bits are a valid entry) from `out`'s start, and stops
        // when the entry pointer reaches `start + n` (n ≥ 1, at most either length) or
        // at a position it does not place: n turns at most, every access inside the
        // slices. See `zraster_place_v6m` for its registers.
        let end = unsafe { zraster_place_v6m(b, positions.as_ptr(), start, start.add(2 * n)) };
        return (end as usize - start as usize) / 8;
    }
    #[allow(unreachable_code)]
    place_run_portable(b, positions, out)
}

/// [`place_run_v6m`] by its twin.
fn place_run_portable(
    b: &mut PlaceV6m<'_>,
    positions: &[[i16; 3]],
    out: &mut [CachedVertex],
) -> usize {
    for (i, (p, e)) in positions.iter().zip(out.iter_mut()).enumerate() {
        match place_v6m_portable(b, p) {
            Some(v) => *e = v,
            None => return i,
        }
    }
    positions.len().min(out.len())
}

#[cfg(all(zraster_thumb, zraster_armv6m))]
extern "C" {
    /// [`place_run_v6m`]'s loop, a whole function in `global_asm!`: block `b`, the
    /// positions from `p`, the entries from `out` up to `end` (exclusive, after
    /// `out`); returns where the entries stopped.
    ///
    /// # Safety
    ///
    /// `b` points to a valid block; `p` to at least as many positions as there are
    /// entries from `out` to `end`, all valid.
    fn zraster_place_v6m(
        b: *mut PlaceV6m<'_>,
        p: *const [i16; 3],
        out: *mut u32,
        end: *mut u32,
    ) -> *mut u32;
}

/// One row of the loop: r0 = c₀·x + c₁·y + c₂·z + t, from the row at r7 (advanced),
/// the position in r4–r6; r1–r3 clobbered.
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! place_row {
    () => {
        "ldm r7!, {{r0, r1, r2, r3}}\n\
         muls r0, r4, r0\n\
         muls r1, r5, r1\n\
         muls r2, r6, r2\n\
         adds r0, r0, r1\n\
         adds r0, r0, r2\n\
         adds r0, r0, r3"
    };
}

/// The slow mode's widening of a coordinate's value (the word at `sp + at`): shifted left
/// by its L₁ (the word at `r7 + shift`) where |v| < 2^(31 − L₁), else the vertex refused
/// (its four pushed words dropped, to 8); nothing for L₁ = 0. r0–r3 clobbered.
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! place_widen {
    ($shift:literal, $at:literal) => {
        concat!(
            "ldr r0, [r7, #",
            $shift,
            "]\n",
            "cmp r0, #0\n",
            "beq 9f\n",
            "ldr r1, [sp, #",
            $at,
            "]\n",
            "ldr r2, ={imax}\n",
            "lsrs r2, r2, r0\n",
            "adds r3, r1, r2\n",
            "lsls r2, r2, #1\n",
            "cmp r3, r2\n",
            "bls 1f\n",
            "add sp, #16\n",
            "b 8f\n",
            "1:\n",
            "lsls r1, r1, r0\n",
            "str r1, [sp, #",
            $at,
            "]\n",
            "9:"
        )
    };
}

/// y's coordinate (the twin's `scaled` and `placed`): its operands at r7 (advanced
/// past them, to x's), y's row value popped, r's halves in r0 (high) and r1 (low),
/// kept; the coordinate written into the entry at r6, x's right shift left in r2.
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! place_y {
    () => {
        // a = v >> right; P = a₁r₁ + ⌊a₁r₀/2¹⁶⌋ + ⌊a₀r₁/2¹⁶⌋, a₁ signed.
        "ldm r7!, {{r2}}
         pop {{r4}}
         asrs r4, r4, r2
         asrs r2, r4, #16
         uxth r4, r4
         movs r3, r2
         muls r3, r0, r3
         muls r2, r1, r2
         asrs r2, r2, #16
         muls r4, r0, r4
         lsrs r4, r4, #16
         adds r3, r3, r2
         adds r3, r3, r4
         ldm r7!, {{r2, r4}}
         asrs r5, r3, #16
         uxth r3, r3
         muls r5, r2, r5
         muls r3, r2, r3
         lsrs r3, r3, #16
         adds r3, r3, r5
         subs r3, r4, r3
         lsls r5, r3, #18
         lsrs r5, r5, #20
         bne 9f
         b 7f
         9:
         asrs r3, r3, #14
         ldm r7!, {{r2, r4, r5}}
         adds r4, r4, r3
         cmp r4, r5
         bls 9f
         b 7f
         9:
         strh r3, [r6, #6]"
    };
}

/// x's coordinate, as [`place_y`] with x's row value, x's right shift in r2 and no
/// copy of a₁ (r's halves are not needed after it), its bias and limit in r0 and r1;
/// the coordinate in r3, not written (r6 kept).
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! place_x {
    () => {
        "pop {{r4}}
         asrs r4, r4, r2
         asrs r2, r4, #16
         uxth r4, r4
         muls r4, r0, r4
         lsrs r4, r4, #16
         muls r1, r2, r1
         asrs r1, r1, #16
         muls r2, r0, r2
         adds r3, r2, r1
         adds r3, r3, r4
         ldm r7!, {{r0, r1, r2, r4}}
         asrs r5, r3, #16
         uxth r3, r3
         muls r5, r2, r5
         muls r3, r2, r3
         lsrs r3, r3, #16
         adds r3, r3, r5
         adds r3, r3, r4
         lsls r5, r3, #18
         lsrs r5, r5, #20
         bne 9f
         b 6f
         9:
         asrs r3, r3, #14
         adds r4, r3, r0
         cmp r4, r1
         bls 9f
         b 6f
         9:"
    };
}

// SAFETY (for `place_run_v6m`): the loop reads the block's rows through r8, its address
// (96 bytes by LDM, which leave the pointer at the hint), the rest through r12, the
// address + 96 (88 bytes: the hint, 14 − sh, the depth's and coordinates' operands, a
// spare word, e, the halves, folds and left shifts), and writes only the hint, 14 −
// sh, right shifts, factors and left shifts (r12 + 0..8, 16..24, 28, 48, 80..88) on a
// search; the slow mode reads and writes the two row values it keeps
// on the stack. A turn reads three halfwords at r9 + 6 and writes the entry at r10
// (advanced by 8 first: its depth word, then the halves of y and x), r9 advancing 6,
// and stops after the entry at r11 (end − 8, so r10 returned past it) or at an entry
// it does not place (r10 returned at it, below end; that entry may hold its depth and
// y): n turns at most, every access inside the slices. It reads RECIP16 at an index
// below 512. The stack: r4–r7, lr and r8–r11 saved and restored as AAPCS wants; a turn
// pushes up to five row values and pops them (a refusal drops what is left by the
// label it takes), the search four registers it pops.
#[cfg(all(zraster_thumb, zraster_armv6m))]
core::arch::global_asm!(
    ".pushsection .text.zraster_place_v6m,\"ax\",%progbits",
    ".balign 4",
    ".global zraster_place_v6m",
    ".hidden zraster_place_v6m",
    ".type zraster_place_v6m, %function",
    ".thumb_func",
    "zraster_place_v6m:",
    v6m_save!(),
    "mov r8, r0",
    "adds r0, #96",
    "mov r12, r0",
    "subs r1, #6",
    "mov r9, r1",
    "subs r2, #8",
    "mov r10, r2",
    "subs r3, #8",
    "mov r11, r3",
    // The position at r9 + 6 (r9 at the last one), r9 advanced by the same 6, r10 by
    // 8 to this turn's entry (r11 at the last entry's).
    "2:",
    "mov r7, r9",
    "movs r3, #6",
    "ldrsh r4, [r7, r3]",
    "add r9, r3",
    "movs r3, #8",
    "ldrsh r5, [r7, r3]",
    "add r10, r3",
    "movs r3, #10",
    "ldrsh r6, [r7, r3]",
    "mov r7, r8",
    // x, y, z high, w high, z low pushed; w low in r0.
    place_row!(),
    "push {{r0}}",
    place_row!(),
    "push {{r0}}",
    place_row!(),
    "push {{r0}}",
    place_row!(),
    "push {{r0}}",
    place_row!(),
    "push {{r0}}",
    place_row!(),
    "pop {{r1, r2, r3}}",
    // r0 = w low, r1 = z low, r2 = w high, r3 = z high; y, x on the stack. r4 = wt,
    // r5 = zt.
    "asrs r4, r0, #14",
    "adds r4, r4, r2",
    "asrs r5, r1, #14",
    "adds r5, r5, r3",
    // zt + wt > 0 (the sum's true sign), zt < wt − 1.
    "adds r6, r5, r4",
    "bgt 9f",
    "b 8f",
    "9:",
    "subs r4, r4, #1",
    "cmp r5, r4",
    "blt 9f",
    "b 8f",
    "9:",
    // (wt − 1) >> (16 + sh) = 1 for the hint's sh (so w > 2³⁰⁺ˢʰ, wn > 2³⁰, and w ≥
    // 2³¹), else the search. r7 at the hint (where the rows' LDMs left it); then r5 =
    // 16 + sh, r6 = up = 14 − sh, r7 at y's operands.
    "ldm r7!, {{r5, r6}}",
    "lsrs r4, r4, r5",
    "cmp r4, #1",
    "beq 3f",
    "b 5f",
    // wn = (wh << up) + (wl >> sh), un = ((zh + wh) << up) + ((zl + wl) >> sh): the
    // top parts are multiples of 2^sh. Where zl + wl overflows, the exact sum apart.
    "3:",
    "subs r5, #16",
    "adds r3, r3, r2",
    "adds r1, r1, r0",
    "bvc 9f",
    "b 4f",
    "9:",
    "lsls r3, r3, r6",
    "asrs r1, r1, r5",
    "lsls r2, r2, r6",
    "asrs r0, r0, r5",
    "adds r5, r3, r1",
    // wn < 2³¹ (wt − 1 < 2¹⁷⁺ˢʰ leaves only wt = 2¹⁷⁺ˢʰ above).
    "adds r2, r2, r0",
    "bpl 1f",
    "b 8f",
    "1:",
    // r2 = wn = d, r6 = −d, r5 = un. The reciprocal: the table and one Newton step. The table's entry 512 + d's bits 29..21 less 512, by an address
    // 1,024 bytes below the table (d < 2³¹).
    "rsbs r6, r2, #0",
    "lsrs r0, r2, #21",
    "lsls r0, r0, #1",
    "ldr r1, ={recip16} - 1024",
    "ldrh r1, [r1, r0]",
    // e = 2³¹ − w·t for w = v + 1 is the low 31 bits of −w·t = ~v·t (w·t ≤ 2³¹).
    "lsrs r0, r2, #15",
    "mvns r4, r0",
    "muls r4, r1, r4",
    "lsls r4, r4, #1",
    "lsrs r4, r4, #8",
    "muls r4, r1, r4",
    "lsrs r4, r4, #24",
    "adds r1, r1, r4",
    // Step 2: y = 8y + ⌊y·⌊e''/2¹⁷⌋/2²⁵⌋, e'' = −⌈d/2⌉·y signed.
    "asrs r4, r6, #1",
    "muls r4, r1, r4",
    "asrs r4, r4, #17",
    "muls r4, r1, r4",
    "asrs r4, r4, #25",
    "lsls r1, r1, #3",
    "adds r1, r1, r4",
    // Step 3, then the correction by the remainder.
    "movs r4, r6",
    "muls r4, r1, r4",
    "lsrs r0, r1, #3",
    "lsrs r3, r4, #16",
    "muls r3, r0, r3",
    "uxth r4, r4",
    "muls r4, r0, r4",
    "lsrs r4, r4, #16",
    "adds r3, r3, r4",
    "lsrs r3, r3, #17",
    "lsls r1, r1, #13",
    "adds r1, r1, r3",
    "muls r6, r1, r6",
    "cmp r6, r2",
    "movs r4, #0",
    "adcs r1, r4",
    // r in r1: its halves in r0 (high), r1 (low). The depth: q30 = the rounded high
    // word of un·r.
    "lsrs r0, r1, #16",
    "uxth r1, r1",
    "lsrs r3, r5, #16",
    "uxth r4, r5",
    "movs r6, r3",
    "muls r6, r1, r6",
    "movs r5, r4",
    "muls r5, r0, r5",
    "muls r3, r0, r3",
    "muls r4, r1, r4",
    "lsrs r4, r4, #16",
    "uxth r2, r6",
    "adds r4, r4, r2",
    "uxth r2, r5",
    "adds r4, r4, r2",
    "lsrs r6, r6, #16",
    "adds r3, r3, r6",
    "lsrs r5, r5, #16",
    "adds r3, r3, r5",
    // 2¹⁵ and 2¹⁴ − 1 from the block (r7 to y's operands).
    "ldm r7!, {{r2, r5}}",
    "adds r4, r4, r2",
    "lsrs r4, r4, #16",
    "adds r3, r3, r4",
    // sz = 2·q30 − ⌊(q30 + 2¹⁴ − 1)/2¹⁵⌋ (q30 ≤ 2³¹: see the twin), into the entry.
    "adds r4, r5, r3",
    "lsrs r4, r4, #15",
    "subs r4, r3, r4",
    "adds r3, r3, r4",
    "mov r6, r10",
    "str r3, [r6, #0]",
    // y, then x, each into its half of the entry's second word.
    place_y!(),
    place_x!(),
    "strh r3, [r6, #4]",
    "cmp r6, r11",
    "beq 9f",
    "b 2b",
    // The last entry written: r10 past it.
    "9:",
    "adds r6, #8",
    "mov r10, r6",
    "b 6f",
    // zl + wl overflowed: un from zt + wt and the low 14 bits of zl and wl (r0 = wl,
    // r1 = zl + wl wrapped, r2 = wh, r3 = zh + wh, r5 = sh, r6 = up).
    "4:",
    "subs r1, r1, r0",
    "asrs r4, r1, #14",
    "adds r3, r3, r4",
    "asrs r4, r0, #14",
    "adds r3, r3, r4",
    "lsls r1, r1, #18",
    "lsrs r1, r1, #18",
    "lsls r4, r0, #18",
    "lsrs r4, r4, #18",
    "adds r1, r1, r4",
    "lsrs r1, r1, r5",
    "lsls r3, r3, r6",
    "adds r3, r3, r1",
    "lsls r2, r2, r6",
    "asrs r0, r0, r5",
    "movs r5, r3",
    "adds r2, r2, r0",
    "bpl 9f",
    "b 8f",
    "9:",
    "b 1b",
    // The hint missed (r5 = its 16 + sh, or 48 + sh in the slow mode; r6 = up; r7 at
    // y's operands): in the slow mode with the same sh only y's and x's shifts,
    // else the search (r0–r3 kept on the stack, y and x above them).
    "5:",
    "push {{r0, r1, r2, r3}}",
    "asrs r4, r0, #14",
    "adds r4, r4, r2",
    "subs r5, #32",
    "bmi 1f",
    "subs r0, r4, #1",
    "lsrs r0, r0, r5",
    "cmp r0, #1",
    "beq 4f",
    // The search: t = wt >> 17 ≥ 1 (else w < 2³¹), 16 + sh = 17 + ⌊log₂ t⌋.
    "1:",
    "lsrs r4, r4, #17",
    "bne 9f",
    "add sp, #16",
    "b 8f",
    "9:",
    "movs r5, #17",
    "lsrs r3, r4, #8",
    "beq 9f",
    "movs r4, r3",
    "adds r5, #8",
    "9:",
    "lsrs r3, r4, #4",
    "beq 9f",
    "movs r4, r3",
    "adds r5, #4",
    "9:",
    "lsrs r3, r4, #2",
    "beq 9f",
    "movs r4, r3",
    "adds r5, #2",
    "9:",
    "lsrs r3, r4, #1",
    "beq 9f",
    "adds r5, #1",
    "9:",
    // up = 14 − sh; k = sh − e: right by k (L = 0) for k > 0, else L = −k.
    "mov r7, r12",
    "movs r6, #30",
    "subs r6, r6, r5",
    "str r6, [r7, #4]",
    "ldr r4, [r7, #60]",
    "subs r4, r5, r4",
    "subs r4, #16",
    "bgt 9f",
    "rsbs r3, r4, #0",
    "movs r4, #0",
    "b 1f",
    "9:",
    "movs r3, #0",
    "1:",
    "str r4, [r7, #16]",
    "str r4, [r7, #28]",
    // Per axis: L₂ = min(L, fold), H = half << L₂, L₁ = L − L₂ (r2: their OR).
    "ldr r0, [r7, #72]",
    "cmp r3, r0",
    "bhs 9f",
    "movs r0, r3",
    "9:",
    "ldr r1, [r7, #64]",
    "lsls r1, r1, r0",
    "str r1, [r7, #20]",
    "subs r0, r3, r0",
    "str r0, [r7, #80]",
    "movs r2, r0",
    "ldr r0, [r7, #76]",
    "cmp r3, r0",
    "bhs 9f",
    "movs r0, r3",
    "9:",
    "ldr r1, [r7, #68]",
    "lsls r1, r1, r0",
    "str r1, [r7, #48]",
    "subs r0, r3, r0",
    "str r0, [r7, #84]",
    "orrs r2, r0",
    // The hint: 16 + sh, 48 + sh in the slow mode (some L₁ > 0).
    "movs r4, r5",
    "cmp r2, #0",
    "beq 9f",
    "adds r4, #32",
    "9:",
    "str r4, [r7, #0]",
    "adds r7, #8",
    // y and x (at sp + 16 and 20) shifted left by their L₁ where |v| < 2^(31 − L₁),
    // else refused.
    "4:",
    place_widen!("72", "16"),
    place_widen!("76", "20"),
    // (wt − 1) >> (16 + sh) = 1 (wt = 2¹⁶⁺ˢʰ would give wn = 2³⁰), r5 = 16 + sh.
    "pop {{r0, r1, r2, r3}}",
    "asrs r4, r0, #14",
    "adds r4, r4, r2",
    "subs r4, r4, #1",
    "lsrs r4, r4, r5",
    "cmp r4, #1",
    "bne 9f",
    "b 3b",
    "9:",
    "b 8f",
    // Refusals: with y and x on the stack (8), with x (7), with neither (6).
    "8:",
    "add sp, #4",
    "7:",
    "add sp, #4",
    "6:",
    "mov r0, r10",
    v6m_return!(),
    ".ltorg",
    ".size zraster_place_v6m, . - zraster_place_v6m",
    ".popsection",
    recip16 = sym RECIP16,
    imax = const i32::MAX,
);

/// The vertex loop (`place_run_v6m`) against its twin on this target: 24 transforms of
/// the kind `FixedTransform` makes for a perspective camera (random coefficients, w
/// near 2⁴² or anywhere within ±2⁴⁰, x and y scaled by 2¹⁰ to 2¹⁶ to reach ±0.4·w to
/// ±24·w, viewports of several sizes and offsets), each over `n` random positions in
/// runs of eight, each run from where the last stopped. Returns the number of
/// positions whose entry or stop, or whose block afterwards, differs.
pub fn check_place_v6m_kernel(n: usize) -> usize {
    // Only the assembly needs checking (the host tests run the twin through it).
    if !PLACE_V6M_KERNEL {
        return 0;
    }
    place_v6m_check(n).0
}

/// [`check_place_v6m_kernel`]'s cases: the differences, the entries placed and the
/// stops.
fn place_v6m_check(n: usize) -> (usize, usize, usize) {
    let mut rnd = super::xorshift32(0x2545_f491_u32);
    let (mut bad, mut placed, mut stops) = (0, 0, 0);
    let mut run = [[0i16; 3]; 8];
    let mut got = [CachedVertex::EMPTY; 8];
    let mut want = [CachedVertex::EMPTY; 8];
    let mut rows = [[0; 4]; 6];
    for case in 0..24u32 {
        for (row, ([c0, c1, c2], t)) in rows
            .iter_mut()
            .zip(super::place::random_rows(&mut rnd, case))
        {
            *row = [c0, c1, c2, t];
        }
        let half = match case % 4 {
            0 => [2560, 1920],
            1 => [1920, 1920],
            2 => [512, 384],
            _ => [1 << 15, 6144],
        };
        let e = match case % 5 {
            0 => 10,
            1 => 12,
            2 => 13,
            3 => 14,
            _ => 16,
        };
        let org = [(case % 3) as i32 * 592 - 640, (case % 5) as i32 * 176];
        let mut mine = PlaceV6m::new(&rows, e, half, org);
        let mut twin = mine;
        for _ in 0..n.div_ceil(8) {
            for p in &mut run {
                *p = [rnd() as i16, rnd() as i16, rnd() as i16];
            }
            let mut at = 0;
            while let (Some(p), Some(g), Some(w)) =
                (run.get(at..), got.get_mut(at..), want.get_mut(at..))
            {
                if p.is_empty() {
                    break;
                }
                let k = place_run_v6m(&mut mine, p, g);
                let j = place_run_portable(&mut twin, p, w);
                let same = g.iter().zip(w.iter()).take(k.min(j));
                bad += usize::from(k != j)
                    + same.filter(|(g, w)| g != w).count()
                    + usize::from(mine != twin);
                placed += j;
                stops += usize::from(j < p.len());
                // Past the stop (the caller's exact path takes that one).
                at += j + 1;
            }
        }
    }
    (bad, placed, stops)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table's first step is within 1.3 below 2³¹/(v + 1) for every v (its
    /// products within `u32`), and the reciprocal ⌊2⁶²/d⌋ at every step's edges and 10⁷ random d;
    /// `ZRASTER_EXHAUSTIVE=1` checks every d (2³⁰ of them; in a release build, some
    /// seconds).
    #[test]
    fn table_reciprocal_is_exact() {
        for v in 1u32 << 15..1 << 16 {
            let w = v + 1;
            let t = u64::from(RECIP16[((v >> 6) & 0x1ff) as usize]);
            assert!(t * u64::from(w) <= 1 << 31, "v {v}");
            let e = (1u64 << 31) - t * u64::from(w);
            assert!(t * (e >> 7) < 1 << 32, "v {v}");
            // Within 1.3 below 2³¹/w: 10·(2³¹ − w·y) < 13·w.
            let y = u64::from(recip31_table(v));
            assert!(y * u64::from(w) <= 1 << 31, "v {v}");
            assert!(
                10 * ((1 << 31) - y * u64::from(w)) < 13 * u64::from(w),
                "v {v}"
            );
            for d in [v << 15, (v << 15) + 1, (v << 15) + (1 << 14), (w << 15) - 1] {
                if d > 1 << 30 && d < 1 << 31 {
                    assert_eq!(u64::from(recip62_low(d)), (1 << 62) / u64::from(d));
                }
            }
        }
        let mut rnd = crate::testing::xorshift64(0x9e37_79b9_7f4a_7c15);
        for _ in 0..crate::num::tests::fast_cases() {
            let d = (rnd() as u32 >> 1 | 1 << 30).max((1 << 30) + 1);
            assert_eq!(u64::from(recip62_low(d)), (1u64 << 62) / u64::from(d));
        }
        if std::env::var_os("ZRASTER_EXHAUSTIVE").is_some() {
            for d in (1u32 << 30) + 1..1 << 31 {
                assert_eq!(u64::from(recip62_low(d)), (1u64 << 62) / u64::from(d));
            }
        }
    }

    #[test]
    fn place_v6m_kernel_is_its_twin() {
        let (bad, placed, stops) = place_v6m_check(2000);
        assert_eq!(bad, 0);
        assert!(
            placed > 10_000 && stops > 2_000,
            "{placed} placed, {stops} stops"
        );
    }
}
