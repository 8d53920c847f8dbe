//! A span cut into segments: the exact division at each segment's ends, the linear
//! steps between (see the parent module's docs, "Perspective").

use super::{F, SEGMENT, SHIFT};
use crate::num::{div_floor_pair, div_floor_signless, floor_div32};
use crate::texture::UV_LIMIT;

/// Pixels `first..first + len` of a span: their u and v (Q16) are `uv.0 >> SHIFT`,
/// `(uv.0 + step.0) >> SHIFT`, ... (u and v times [`SEGMENT`], stepped a pixel).
#[derive(Clone, Copy)]
pub(crate) struct Segment {
    pub first: usize,
    pub len: usize,
    pub uv: (i32, i32),
    pub step: (i32, i32),
}

/// A span cut into segments of at most [`SEGMENT`] pixels ([`UvPlanes::segments`](super::UvPlanes::segments)): exact
/// at each segment's first pixel and at the span's last pixel (a segment of its own),
/// linear between.
pub(crate) struct Segments {
    /// The planes' values at pixel `i`, their steps and ranges.
    pub(super) h: [i64; 3],
    pub(super) step: [i64; 3],
    /// The steps of a whole segment.
    pub(super) whole: [i64; 3],
    pub(super) range: [(i64, i64); 3],
    pub(super) perspective: bool,
    /// The exact coordinates at pixel `i`.
    pub(super) uv: (i32, i32),
    pub(super) i: i32,
    pub(super) n: i32,
}

impl Segments {
    /// The next segment.
    #[inline(always)]
    pub(crate) fn next_segment(&mut self) -> Option<Segment> {
        let fixed = SegmentSteps::of(self);
        fixed.next(&mut self.h, &mut self.uv, &mut self.i)
    }
}

/// What does not change along a span's [`Segments`]: the steps, the range of q, the
/// mode and the length. Split from the changing values so that a loop can keep those
/// in locals ([`SegmentSteps::next`]).
#[derive(Clone, Copy)]
pub(crate) struct SegmentSteps {
    step: [i64; 3],
    whole: [i64; 3],
    q_range: (i64, i64),
    perspective: bool,
    n: i32,
}

impl SegmentSteps {
    #[inline(always)]
    pub(crate) fn of(s: &Segments) -> Self {
        SegmentSteps {
            step: s.step,
            whole: s.whole,
            q_range: s.range[2],
            perspective: s.perspective,
            n: s.n,
        }
    }

    /// The exact coordinates where the values are `h`.
    #[inline(always)]
    pub(super) fn exact(&self, h: [i64; 3]) -> (i32, i32) {
        if self.perspective {
            divide(h)
        } else {
            // Q32 within ±2⁴⁰ (clamped to the corners'): Q16 within ±2²⁴.
            let lim = i64::from(UV_LIMIT);
            (
                (h[0] >> F).clamp(-lim, lim) as i32,
                (h[1] >> F).clamp(-lim, lim) as i32,
            )
        }
    }

    /// The segment from pixel `*i`, where the planes' values are `h` and the exact
    /// coordinates `uv`; all three moved on to the next segment's first pixel.
    #[inline(always)]
    pub(crate) fn next(
        &self,
        h: &mut [i64; 3],
        uv: &mut (i32, i32),
        i: &mut i32,
    ) -> Option<Segment> {
        let first = *i;
        if first >= self.n {
            return None;
        }
        let (ua, va) = *uv;
        let m = (self.n - 1 - first).min(SEGMENT);
        if m == 0 {
            // The last pixel: exact.
            *i = self.n;
            return Some(Segment {
                first: first as usize,
                len: 1,
                uv: (ua << SHIFT, va << SHIFT),
                step: (0, 0),
            });
        }
        // Wrapping: the values at the segment's end lie between the corners' (see the
        // module docs), to the steps' rounding; q is clamped to its plane's range (so
        // that it stays a divisor of the cheap divisions), the quotients to ±2²⁴.
        if m == SEGMENT {
            for (h, step) in h.iter_mut().zip(self.whole) {
                *h = h.wrapping_add(step);
            }
        } else {
            for (h, step) in h.iter_mut().zip(self.step) {
                *h = h.wrapping_add(step.wrapping_mul(i64::from(m)));
            }
        }
        let (lo, hi) = self.q_range;
        h[2] = h[2].clamp(lo, hi);
        let (ub, vb) = self.exact(*h);
        // u and v times SEGMENT step by Δu·SEGMENT/m a pixel: Δu itself over a whole
        // segment, a floored quotient over the last, shorter one. |Δu| ≤ 2²⁵: below 2²⁹.
        let step = if m == SEGMENT {
            (ub - ua, vb - va)
        } else {
            (
                floor_div32((ub - ua) << SHIFT, m),
                floor_div32((vb - va) << SHIFT, m),
            )
        };
        *uv = (ub, vb);
        *i = first + m;
        Some(Segment {
            first: first as usize,
            len: m as usize,
            uv: (ua << SHIFT, va << SHIFT),
            step,
        })
    }
}

/// ⌊u·q / q⌋ and ⌊v·q / q⌋ of values with [`F`] fractional bits, clamped to ±2²⁴.
#[inline(always)]
fn divide(h: [i64; 3]) -> (i32, i32) {
    let q = h[2] >> F; // ≤ 2¹⁵
                       // 1 ≤ q < 2¹⁶ (one unsigned comparison) and a divide instruction: two 16-bit digits
                       // each, the clamp read off the first.
    if crate::num::DIVIDE && !crate::num::WIDE && (q as u64).wrapping_sub(1) < 0xFFFF {
        if let (Some(u), Some(v)) = (div_clamped(h[0], q as u32), div_clamped(h[1], q as u32)) {
            return (u, v);
        }
    }
    divide_wide(h[0] >> F, h[1] >> F, q.max(1))
}

/// ⌊n1 / q⌋ and ⌊n2 / q⌋ clamped to ±2²⁴, for any values (q ≥ 1).
#[inline(always)]
pub(super) fn divide_wide(n1: i64, n2: i64, q: i64) -> (i32, i32) {
    let (u, v) = if crate::num::ARMV6M || crate::num::WIDE {
        // A reciprocal of q (ARMv6-M), or a 64-bit divide instruction.
        div_floor_pair(n1, n2, q)
    } else {
        // Two 16-bit digits of long division each, inline (q < 2¹⁶, |n| < 2⁴⁸).
        (div_floor_signless(n1, q), div_floor_signless(n2, q))
    };
    let lim = i64::from(UV_LIMIT);
    (u.clamp(-lim, lim) as i32, v.clamp(-lim, lim) as i32)
}

/// ⌊(h ≫ 16) / q⌋ clamped to ±2²⁴ ([`UV_LIMIT`]) for 1 ≤ q < 2¹⁶ (the caller's
/// check), if |h ≫ 16| < 2⁴⁷ (else `None`): the sign folded in as `div_floor_signless` does (⌊n/q⌋ = s ^ ⌊m/q⌋
/// for m = n ^ s, s = 0 or −1 by n's sign), m divided by two 16-bit digits whose first
/// tells whether the quotient reaches 2²⁴ (it does from 2⁸ on).
#[inline(always)]
pub(super) fn div_clamped(h: i64, q: u32) -> Option<i32> {
    let s = h >> 63;
    let x = (h ^ s) as u64; // m = x ≫ 16
    let hi = (x >> 32) as u32; // m ≫ 16
    if hi >> 31 != 0 {
        return None;
    }
    let s = s as i32;
    let q1 = hi / q;
    if q1 >> 8 != 0 {
        return Some(if s < 0 { -UV_LIMIT } else { UV_LIMIT });
    }
    // r1 < q < 2¹⁶: the second digit's dividend fits 32 bits.
    let r1 = hi - q1 * q;
    let q0 = (r1 << 16 | (x as u32) >> 16) / q;
    // Below 2²⁴: as i32, and s ^ it is within ±2²⁴ too.
    Some((q1 << 16 | q0) as i32 ^ s)
}
