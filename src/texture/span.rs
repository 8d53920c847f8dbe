//! The span interpolators: texture coordinates pixel by pixel along a row of a
//! triangle, perspective-correct or affine.

use super::{TexCoord, UV_BITS, UV_LIMIT};
use crate::num::{div_floor_pair, floor_div32, mul_i64_i32};
use crate::{Error, MAX_DIMENSION};

/// u/w, v/w and 1/w at a pixel, or their change per pixel: the three quantities that
/// vary linearly across a screen triangle under perspective.
///
/// `q` is 1/w at any positive scale (only ratios count), and `uq`, `vq` are u·q and v·q
/// at the same scale with u, v in Q16, so that `uq / q` is u in Q16. A
/// [`PerspectiveSpan`] needs the values at both ends of its span within ±2⁶² (and q
/// positive there).
///
/// The scale is a trade: the precision of q sets how well far parts of a face are
/// placed (a vertex 64 times farther than the nearest has a q 64 times smaller: 6 bits
/// fewer), while q below 2¹⁶ with |uq|, |vq| below 2⁴⁸ takes the cheap divisions (see
/// [`PerspectiveSpan`]). The rasterizer's 16.16 planes through per-vertex q of 2¹⁴ to
/// 2¹⁵ at the nearest vertex give q ≈ 2³⁰ with exact steps: the precise, slower end.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub struct Homogeneous {
    /// u·q, u in Q16.
    pub uq: i64,
    /// v·q, v in Q16.
    pub vq: i64,
    /// 1/w at any positive scale.
    pub q: i64,
}

/// The largest magnitude of a [`Homogeneous`] value a span accepts at its ends: 2⁶².
const H_LIMIT: i128 = 1 << 62;

/// `a + k·b` for the values of a span's last pixel, in 128 bits (no overflow).
fn at(a: i64, b: i64, k: u32) -> i128 {
    i128::from(a) + i128::from(b) * i128::from(k)
}

/// The exact coordinates at a point: `⌊uq/q⌋`, `⌊vq/q⌋` (q below 1 taken as 1),
/// clamped to ±[`UV_LIMIT`].
#[inline]
fn divide(h: &Homogeneous) -> (i32, i32) {
    let (u, v) = div_floor_pair(h.uq, h.vq, h.q.max(1));
    let lim = i64::from(UV_LIMIT);
    (u.clamp(-lim, lim) as i32, v.clamp(-lim, lim) as i32)
}

/// Texture coordinates along a span of pixels, perspective-correct: u/w, v/w and 1/w
/// stepped, an exact division every `SEGMENT` pixels (a power of two from 2 to 32;
/// 16 by default) and at the last pixel, u and v stepped linearly between.
///
/// # Accuracy
/// At pixel 0, `SEGMENT`, 2·`SEGMENT`, … and at the last pixel, u is `⌊uq/q⌋` of the
/// stepped values exactly (and v alike), clamped to ±[`UV_LIMIT`]. In between, in a
/// segment from pixel a to pixel b, u differs from `uq/q` by at most
/// `¼·|u_b − u_a|·|q_b − q_a| / min(q_a, q_b) + 3` (Q16; the hyperbola's bow against
/// its chord, plus the floors of the ends, of a short segment's step and of the
/// result). The tests check both against an exact reference on random spans and on a
/// steep wall. Neighbouring segments share their end point, so no
/// seam jumps.
///
/// # Cost and ranges
/// Per pixel two `i32` additions and shifts. Per segment one `i64` step of each
/// quantity and one pair of divisions by one divisor (on a Cortex-M0+ by reciprocal
/// when q < 2¹⁶ and |uq|, |vq| < 2⁴⁸, on a Cortex-M3/M4 by 32-bit divides when
/// q < 2¹⁶ and |uq|, |vq| < 2⁴⁸ too; a 64-bit library division otherwise). Nothing
/// overflows, in debug builds neither: the values at both ends are checked
/// (|·| ≤ 2⁶²), so every point in between is inside too; quotients are clamped to
/// ±2²⁴, segment differences are then below 2²⁵ and times `SEGMENT` (≤ 2⁵) below 2³⁰.
///
/// ```
/// use zraster::texture::{Homogeneous, PerspectiveSpan, UV_ONE};
///
/// // q constant: perspective-correct is linear. u from 0 by 1/64 texture a pixel.
/// let one = 1i64 << 16;
/// let start = Homogeneous { uq: 0, vq: 0, q: one };
/// let step = Homogeneous { uq: one * i64::from(UV_ONE) / 64, vq: 0, q: 0 };
/// let us: Vec<i32> = PerspectiveSpan::<8>::new(start, step, 40)?.map(|c| c.u).collect();
/// assert_eq!(us, (0..40).map(|x| x * UV_ONE / 64).collect::<Vec<_>>());
/// # Ok::<(), zraster::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct PerspectiveSpan<const SEGMENT: u32 = 16> {
    /// The homogeneous values at the next exact point.
    h: Homogeneous,
    step: Homogeneous,
    /// The exact coordinates at the next exact point.
    next: (i32, i32),
    /// u, v times `SEGMENT`, and their steps per pixel.
    u: i32,
    v: i32,
    du: i32,
    dv: i32,
    /// Pixels left in the span, and in the current segment.
    left: u32,
    in_segment: u32,
}

impl<const SEGMENT: u32> PerspectiveSpan<SEGMENT> {
    /// `SEGMENT` is a power of two from 2 to 32 (checked at compile time).
    const SHIFT: u32 = {
        assert!(
            SEGMENT.is_power_of_two() && SEGMENT >= 2 && SEGMENT <= 32,
            "SEGMENT must be 2, 4, 8, 16 or 32"
        );
        SEGMENT.trailing_zeros()
    };

    /// The coordinates of `n` pixels from the one where the values are `start`, each
    /// next pixel `step` further.
    ///
    /// Errors: [`Error::TooLarge`] for `n` above [`MAX_DIMENSION`];
    /// [`Error::OutOfRange`] when a value at the first or last pixel exceeds ±2⁶².
    /// A q of 0 or below (which a triangle in front of the eye does not have) is taken
    /// as 1.
    pub fn new(start: Homogeneous, step: Homogeneous, n: u32) -> Result<Self, Error> {
        let _ = Self::SHIFT;
        if n > MAX_DIMENSION {
            return Err(Error::TooLarge);
        }
        let last = n.saturating_sub(1);
        let ends = [(start.uq, step.uq), (start.vq, step.vq), (start.q, step.q)];
        for (a, b) in ends {
            if i128::from(a).abs() > H_LIMIT || at(a, b, last).abs() > H_LIMIT {
                return Err(Error::OutOfRange);
            }
        }
        Ok(PerspectiveSpan {
            h: start,
            step,
            next: if n > 0 { divide(&start) } else { (0, 0) },
            u: 0,
            v: 0,
            du: 0,
            dv: 0,
            left: n,
            in_segment: 0,
        })
    }

    /// Start the segment at the next exact point: step to the one after it (at most
    /// `SEGMENT` pixels on, at most the last pixel) and divide there.
    #[inline]
    fn start_segment(&mut self) {
        let (ua, va) = self.next;
        self.u = ua << Self::SHIFT;
        self.v = va << Self::SHIFT;
        let m = (self.left - 1).min(SEGMENT);
        if m == 0 {
            // The last pixel, exact already.
            self.in_segment = 1;
            return;
        }
        // m·step is the difference of two points of the span: within ±2⁶³.
        let k = m as i32;
        self.h.uq = self.h.uq.wrapping_add(mul_i64_i32(self.step.uq, k));
        self.h.vq = self.h.vq.wrapping_add(mul_i64_i32(self.step.vq, k));
        self.h.q = self.h.q.wrapping_add(mul_i64_i32(self.step.q, k));
        let (ub, vb) = divide(&self.h);
        self.next = (ub, vb);
        // u times SEGMENT moves by Δu·SEGMENT/m a pixel: by Δu itself over a whole
        // segment (exact), by a floored quotient over the last, shorter one.
        // |Δu| ≤ 2²⁵ (both ends clamped to ±2²⁴), times SEGMENT ≤ 2⁵: below 2³⁰.
        let (du, dv) = (ub - ua, vb - va);
        (self.du, self.dv) = if m == SEGMENT {
            (du, dv)
        } else {
            (
                floor_div32(du << Self::SHIFT, k),
                floor_div32(dv << Self::SHIFT, k),
            )
        };
        self.in_segment = m;
    }
}

impl<const SEGMENT: u32> Iterator for PerspectiveSpan<SEGMENT> {
    type Item = TexCoord;

    #[inline]
    fn next(&mut self) -> Option<TexCoord> {
        if self.left == 0 {
            return None;
        }
        if self.in_segment == 0 {
            self.start_segment();
        }
        let out = TexCoord {
            u: self.u >> Self::SHIFT,
            v: self.v >> Self::SHIFT,
        };
        self.u = self.u.wrapping_add(self.du);
        self.v = self.v.wrapping_add(self.dv);
        self.in_segment -= 1;
        self.left -= 1;
        Some(out)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.left as usize, Some(self.left as usize))
    }
}

impl<const SEGMENT: u32> ExactSizeIterator for PerspectiveSpan<SEGMENT> {}

/// Texture coordinates along a span of pixels, affine: u and v themselves stepped, no
/// division. Cheaper than [`PerspectiveSpan`], and right where the depth does not
/// change along the span (faces square to the view); on faces seen at a slant the
/// texture swims (the tests show a floor where they differ by 5 texels of 16).
///
/// Per pixel two `i64` additions. Nothing overflows: the values at both ends are
/// checked (|u|, |v| ≤ 2⁴⁰ in Q32, that is ±[`UV_LIMIT`] in Q16), and the
/// accumulators step with wrapping additions whose last one is never read.
///
/// ```
/// use zraster::texture::{AffineSpan, UV_ONE};
///
/// // From u = 0.25 by 1/128 of a texture per pixel (Q32).
/// let span = AffineSpan::new(1 << 30, 0, 1 << 25, 0, 3)?;
/// assert_eq!(span.map(|c| c.u).collect::<Vec<_>>(), [UV_ONE / 4, UV_ONE / 4 + 512, UV_ONE / 4 + 1024]);
/// # Ok::<(), zraster::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct AffineSpan {
    u: i64,
    v: i64,
    du: i64,
    dv: i64,
    left: u32,
}

impl AffineSpan {
    /// The coordinates of `n` pixels from one at (u, v), each next pixel (du, dv)
    /// further; all four in Q32 texture units (2³² is one texture: the 16.16 form of
    /// Q16 coordinates). Pixel k gets `⌊(u + k·du) / 2¹⁶⌋` in Q16, exactly.
    ///
    /// Errors: [`Error::TooLarge`] for `n` above [`MAX_DIMENSION`];
    /// [`Error::OutOfRange`] when u or v at the first or last pixel is beyond
    /// ±[`UV_LIMIT`] in Q16 (±2⁴⁰ in Q32).
    pub fn new(u: i64, v: i64, du: i64, dv: i64, n: u32) -> Result<Self, Error> {
        if n > MAX_DIMENSION {
            return Err(Error::TooLarge);
        }
        let limit = i128::from(UV_LIMIT) << UV_BITS;
        let last = n.saturating_sub(1);
        for (a, b) in [(u, du), (v, dv)] {
            if i128::from(a).abs() > limit || at(a, b, last).abs() > limit {
                return Err(Error::OutOfRange);
            }
        }
        Ok(AffineSpan {
            u,
            v,
            du,
            dv,
            left: n,
        })
    }
}

impl Iterator for AffineSpan {
    type Item = TexCoord;

    #[inline]
    fn next(&mut self) -> Option<TexCoord> {
        if self.left == 0 {
            return None;
        }
        // Within ±2⁴⁰ (checked at both ends): the shifted value fits i32.
        let out = TexCoord {
            u: (self.u >> UV_BITS) as i32,
            v: (self.v >> UV_BITS) as i32,
        };
        self.u = self.u.wrapping_add(self.du);
        self.v = self.v.wrapping_add(self.dv);
        self.left -= 1;
        Some(out)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.left as usize, Some(self.left as usize))
    }
}

impl ExactSizeIterator for AffineSpan {}
