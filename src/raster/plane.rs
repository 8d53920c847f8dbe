//! The depth plane of a triangle: the classic plane equation solved for depth, exact
//! for any triangle and in a fast stepped form for the usual ones.

use super::edge::Setup;
use super::ScreenVertex;
use crate::fixed::{SUBPIXEL, SUBPIXEL_BITS};
use crate::num::{
    div_floor, div_floor_pair, div_floor_pair32, div_floor_wide, mul_i64_i32, sat_i32,
};

/// A quantity that varies linearly across a screen triangle — its depth, or a colour
/// channel for Gouraud shading — given by its plane through the three vertices: the
/// plane equation `ax + by + cz = d` solved for z.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Plane {
    // Exact form: value(X, Y) = v0 + (a·(X − x0) + b·(Y − y0)) / area2, in 16.16.
    x0: i32,
    y0: i32,
    v0: i64,
    a: i64,
    b: i64,
    area2: i64,
    // Fast form: value at (X, Y) ≈ v0 + (step_x·(X − x0) + step_y·(Y − y0)) / 16, with
    // the slopes per pixel rounded down to 16.16: one division each, no division later.
    step_x: i64,
    step_y: i64,
    /// The triangle is too large for the fast form's error bound: evaluate exactly.
    pub(super) exact: bool,
}

/// Triangles whose x and y extents stay within this many 1/16 pixels (4096 pixels) use
/// the fast plane form, whose error stays below 2¹³/65536 of a unit (see [`crate::fixed`]).
const FAST_EXTENT: i64 = 1 << 16;

impl Plane {
    /// The plane through the vertices' positions with values `values` (16.16, each
    /// below 2³²). `None` when the triangle has zero area.
    pub fn new(tri: &[ScreenVertex; 3], values: [u32; 3]) -> Option<Plane> {
        let [p0, p1, p2] = tri;
        let (dx1, dy1) = (i64::from(p1.x - p0.x), i64::from(p1.y - p0.y));
        let (dx2, dy2) = (i64::from(p2.x - p0.x), i64::from(p2.y - p0.y));
        let area2 = dx1 * dy2 - dx2 * dy1;
        if area2 == 0 {
            return None;
        }
        let (v0, v1, v2) = (
            i64::from(values[0]),
            i64::from(values[1]),
            i64::from(values[2]),
        );
        let (dv1, dv2) = (v1 - v0, v2 - v0);
        let a = dv1 * dy2 - dv2 * dy1;
        let b = dx1 * dv2 - dx2 * dv1;
        let extent = dx1
            .abs()
            .max(dy1.abs())
            .max(dx2.abs())
            .max(dy2.abs())
            .max((dx1 - dx2).abs())
            .max((dy1 - dy2).abs());
        let exact = extent > FAST_EXTENT;
        let (step_x, step_y) = if exact {
            (0, 0)
        } else {
            // |a|, |b| < 2⁴⁹ here, so 16a and 16b are far inside i64.
            (
                div_floor(a * i64::from(SUBPIXEL), area2),
                div_floor(b * i64::from(SUBPIXEL), area2),
            )
        };
        Some(Plane {
            x0: p0.x,
            y0: p0.y,
            v0,
            a,
            b,
            area2,
            step_x,
            step_y,
            exact,
        })
    }

    /// The plane's exact value (16.16, rounded down) at the point (x, y) in 1/16 pixel.
    /// Outside the triangle the value may lie outside the vertices' range.
    pub fn value_at(&self, x: i32, y: i32) -> i64 {
        let dx = i128::from(x) - i128::from(self.x0);
        let dy = i128::from(y) - i128::from(self.y0);
        let num = i128::from(self.a) * dx + i128::from(self.b) * dy;
        let v = i128::from(self.v0) + div_floor_wide(num, i128::from(self.area2));
        v.clamp(i128::from(i64::MIN), i128::from(i64::MAX)) as i64
    }

    /// The value at the centre of pixel (px, py): exact for large triangles, within
    /// (|Δpx| + |Δpy| + 1)/65536 of a unit of exact otherwise (Δ from the first vertex).
    #[inline]
    pub(crate) fn at_pixel(&self, px: i32, py: i32) -> i64 {
        let (cx, cy) = (px * SUBPIXEL + SUBPIXEL / 2, py * SUBPIXEL + SUBPIXEL / 2);
        if self.exact {
            self.value_at(cx, cy)
        } else {
            // In 128 bits: a sliver's slopes can reach 2⁵⁰ and more.
            let d = i128::from(self.step_x) * i128::from(cx - self.x0)
                + i128::from(self.step_y) * i128::from(cy - self.y0);
            let v = i128::from(self.v0) + (d >> SUBPIXEL_BITS);
            v.clamp(i128::from(i64::MIN), i128::from(i64::MAX)) as i64
        }
    }

    /// Change per pixel along x, 16.16, as a full `i64` (saturated).
    #[inline]
    pub(crate) fn step_x_i64(&self) -> i64 {
        if self.exact {
            let s = div_floor_wide(
                i128::from(self.a) * i128::from(SUBPIXEL),
                i128::from(self.area2),
            );
            s.clamp(i128::from(i64::MIN), i128::from(i64::MAX)) as i64
        } else {
            self.step_x
        }
    }

    /// Change per pixel along y, 16.16, saturated to `i32`.
    #[inline]
    pub(crate) fn step_y(&self) -> i32 {
        if self.exact {
            sat_i32(div_floor_wide(
                i128::from(self.b) * i128::from(SUBPIXEL),
                i128::from(self.area2),
            ) as i64)
        } else {
            sat_i32(self.step_y)
        }
    }

    /// Change per pixel along x, 16.16, saturated to `i32`.
    #[inline]
    pub(crate) fn step_x(&self) -> i32 {
        if self.exact {
            sat_i32(div_floor_wide(
                i128::from(self.a) * i128::from(SUBPIXEL),
                i128::from(self.area2),
            ) as i64)
        } else {
            sat_i32(self.step_x)
        }
    }
}

/// The depth accumulator's bias: half a unit, so `acc >> 16` rounds to nearest (see
/// [`crate::fixed`] for why the accumulator never wraps).
pub(crate) const DEPTH_BIAS: u32 = 1 << 15;

/// The biased plane value at the centre of pixel (0, 0), modulo 2³², for the fast form
/// `v0 + ⌊(sx·(X − x0) + sy·(Y − y0)) / 16⌋` with X = 16px + 8, Y = 16py + 8.
///
/// Split `x0 = 16·xi + xf`: the floor then only involves `sx·(8 − xf)` (below 2⁵⁷ for
/// the slopes of triangles within 4096 pixels, the only ones using this form), and the whole-pixel parts
/// `−sx·xi − sy·yi` are exact in wrapping arithmetic, which is all a value modulo 2³²
/// needs. Steep slopes (a sliver's can exceed 2³²) are fine: each span then has at most
/// one pixel, and stepping modulo 2³² stays exact.
#[inline(always)]
pub(crate) fn plane_origin(p0: &ScreenVertex, sx: i64, sy: i64) -> u32 {
    let (xi, xf) = (p0.x >> SUBPIXEL_BITS, p0.x & (SUBPIXEL - 1));
    let (yi, yf) = (p0.y >> SUBPIXEL_BITS, p0.y & (SUBPIXEL - 1));
    let half = SUBPIXEL / 2;
    // |s| < 2⁵³ on every path that uses this form and |half − f| ≤ 8: below 2⁵⁷.
    let frac = mul_i64_i32(sx, half - xf).wrapping_add(mul_i64_i32(sy, half - yf)) >> SUBPIXEL_BITS;
    (frac as u32)
        .wrapping_add(p0.z)
        .wrapping_sub((sx as u32).wrapping_mul(xi as u32))
        .wrapping_sub((sy as u32).wrapping_mul(yi as u32))
        .wrapping_add(DEPTH_BIAS)
}

/// The depth steps per pixel along x and y (16.16) of a small triangle (extents below
/// [`SMALL`](super::SMALL)); `None` for zero area.
///
/// The plane is taken through the depths in 20.12 (`z >> 4`), so its numerators
/// `16·(Δz₁·Δy₂ − Δz₂·Δy₁)` (|Δz| < 2²⁸, |Δy| < 2¹³: below 2⁴⁶) usually fit 32 bits and
/// each step is one exact division, floored to 20.12 and widened to 16.16. Stepped
/// from the plane's origin ([`plane_origin`]) across at most 2¹⁰ pixels, a step's
/// rounding moves the depth by less than 2¹⁰·2⁻¹² = ¼ unit: each pixel's stored depth is
/// within one unit of the exactly rounded plane value.
#[inline(always)]
pub(crate) fn small_steps([p0, p1, p2]: [&ScreenVertex; 3]) -> Option<(i64, i64)> {
    let (dx1, dy1) = (p1.x - p0.x, p1.y - p0.y);
    let (dx2, dy2) = (p2.x - p0.x, p2.y - p0.y);
    let area = dx1 * dy2 - dx2 * dy1; // |·| < 2²⁷
    if area == 0 {
        return None;
    }
    let zq = |p: &ScreenVertex| i64::from(p.z >> 4);
    let (dz1, dz2) = (zq(p1) - zq(p0), zq(p2) - zq(p0));
    let a = mul_i64_i32(dz1, dy2) - mul_i64_i32(dz2, dy1);
    let b = mul_i64_i32(dz2, dx1) - mul_i64_i32(dz1, dx2);
    let (na, nb) = (a * i64::from(SUBPIXEL), b * i64::from(SUBPIXEL));
    let (sx, sy) = match div_floor_pair32(na, nb, area) {
        Some((sx, sy)) => (i64::from(sx), i64::from(sy)),
        None => div_floor_pair(na, nb, i64::from(area)),
    };
    Some((sx << 4, sy << 4))
}

/// Depth at the start of each row of a triangle, in the pixel loop's biased form.
///
/// For the usual triangle (extent within 4096 pixels, slopes within `i32`) this is the
/// fast plane form rewritten as `z00 + px·sx + py·sy` in wrapping `u32` arithmetic —
/// equal to it modulo 2³², and the true value lies in `u32`, so it is the same number:
/// two multiplies a row, no 64-bit arithmetic. Larger triangles use the exact form.
pub(crate) enum DepthRows {
    Fast {
        z00: u32,
        sx: u32,
        sy: u32,
        lo: u32,
        hi: u32,
    },
    Exact {
        plane: Plane,
        lo: i64,
        hi: i64,
    },
}

impl DepthRows {
    #[inline(always)]
    pub(crate) fn new(tri: &[ScreenVertex; 3], setup: &Setup) -> Option<(DepthRows, u32)> {
        let zs = [tri[0].z, tri[1].z, tri[2].z];
        let (lo, hi) = (zs[0].min(zs[1]).min(zs[2]), zs[0].max(zs[1]).max(zs[2]));
        let fast = |sx: i64, sy: i64| {
            let rows = DepthRows::Fast {
                z00: plane_origin(&tri[0], sx, sy),
                sx: sx as u32, // modulo 2³², on purpose
                sy: sy as u32,
                lo: lo + DEPTH_BIAS,
                hi: hi + DEPTH_BIAS,
            };
            Some((rows, sx as u32))
        };
        if setup.small {
            let (sx, sy) = small_steps(tri.each_ref())?;
            return fast(sx, sy);
        }
        let plane = Plane::new(tri, zs)?;
        if !plane.exact {
            return fast(plane.step_x, plane.step_y);
        }
        let dz = plane.step_x_i64() as u32;
        Some((
            DepthRows::Exact {
                plane,
                lo: i64::from(lo),
                hi: i64::from(hi),
            },
            dz,
        ))
    }

    /// The biased accumulator at the centre of pixel (x, y), clamped to the vertices'
    /// depth range (which keeps it within `u32` whatever the rounding).
    #[inline(always)]
    pub(crate) fn at(&self, x: i32, y: i32) -> u32 {
        match *self {
            DepthRows::Fast {
                z00,
                sx,
                sy,
                lo,
                hi,
            } => {
                let s = z00
                    .wrapping_add((x as u32).wrapping_mul(sx))
                    .wrapping_add((y as u32).wrapping_mul(sy));
                // The true value is within 2¹⁴ of [lo, hi] ⊂ [2¹⁵, 2³² − 2¹⁵], so the
                // wrapping sum is that value itself, and a plain clamp applies.
                s.clamp(lo, hi)
            }
            DepthRows::Exact { ref plane, lo, hi } => {
                (plane.at_pixel(x, y).clamp(lo, hi) + i64::from(DEPTH_BIAS)) as u32
            }
        }
    }
}

/// The depth of a triangle's plane at a point: the classic "depth from the plane equation".
///
/// `x`, `y` are in 1/16 pixel; the result is depth in 16.16 (rounded down), `None` for a
/// zero-area triangle. The rasterizer stores the same plane, rounded to the nearest
/// integer, at each covered pixel centre.
///
/// ```
/// use zraster::{depth_at, ScreenVertex};
/// let v = |x, y, z| ScreenVertex::from_pixels(x, y, z).unwrap();
/// let tri = [v(0, 0, 6), v(3, 0, 9), v(0, 3, 9)];
/// assert_eq!(depth_at(&tri, 16, 16), Some(8 << 16)); // z = 8 at (1, 1)
/// ```
pub fn depth_at(tri: &[ScreenVertex; 3], x: i32, y: i32) -> Option<i64> {
    Plane::new(tri, [tri[0].z, tri[1].z, tri[2].z]).map(|p| p.value_at(x, y))
}
