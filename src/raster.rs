//! Screen-space triangles: vertices, the back-face test, the depth plane and scan
//! conversion into spans.
//!
//! Scan conversion walks the triangle's left and right edges row by row with an exact
//! integer DDA (a quotient and a remainder per edge, no division per row), giving each
//! row's span of covered pixel centres. The result is identical to testing every pixel
//! centre against the three edge functions with the top-left rule, so triangles that
//! share an edge cover each pixel along it exactly once.

use crate::fixed::{GUARD_BAND, MAX_DEPTH, SUBPIXEL, SUBPIXEL_BITS};
use crate::num::{
    div_ceil, div_floor, div_floor_wide, floor_div32, mul_i64_i32, round_f32, sat_i32,
};
use crate::Error;

/// A vertex in screen space: `x`, `y` in 28.4 fixed point (1/16 pixel), depth in 16.16.
///
/// The y axis points down (row 0 at the top). Construction checks the ranges documented
/// in [`fixed`](crate::fixed): `|x|, |y| ≤ GUARD_BAND`, `depth ≤ MAX_DEPTH`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ScreenVertex {
    x: i32,
    y: i32,
    z: u32,
}

impl ScreenVertex {
    /// The vertex at (0, 0) with depth 0.
    pub const ORIGIN: ScreenVertex = ScreenVertex { x: 0, y: 0, z: 0 };

    /// A vertex from raw fixed-point values: `x`, `y` in 1/16 pixel, `z` in 16.16.
    pub const fn new(x: i32, y: i32, z: u32) -> Result<Self, Error> {
        if x < -GUARD_BAND || x > GUARD_BAND || y < -GUARD_BAND || y > GUARD_BAND || z > MAX_DEPTH {
            return Err(Error::OutOfRange);
        }
        Ok(ScreenVertex { x, y, z })
    }

    /// A vertex from values already known to be in range (the projection clamps them).
    #[inline]
    pub(crate) const fn from_raw(x: i32, y: i32, z: u32) -> Self {
        debug_assert!(
            x >= -GUARD_BAND
                && x <= GUARD_BAND
                && y >= -GUARD_BAND
                && y <= GUARD_BAND
                && z <= MAX_DEPTH
        );
        ScreenVertex { x, y, z }
    }

    /// A vertex at whole-pixel coordinates (the corner of pixel (x, y)) and integer depth.
    pub const fn from_pixels(x: i32, y: i32, depth: u16) -> Result<Self, Error> {
        if x < -(GUARD_BAND >> SUBPIXEL_BITS)
            || x > (GUARD_BAND >> SUBPIXEL_BITS)
            || y < -(GUARD_BAND >> SUBPIXEL_BITS)
            || y > (GUARD_BAND >> SUBPIXEL_BITS)
        {
            return Err(Error::OutOfRange);
        }
        Self::new(x << SUBPIXEL_BITS, y << SUBPIXEL_BITS, (depth as u32) << 16)
    }

    /// A vertex from floating-point pixel coordinates and a depth in `0.0..=65535.0`,
    /// each rounded to the nearest representable value.
    ///
    /// Errors: [`Error::NotFinite`] for NaN or ±∞, [`Error::OutOfRange`] outside the
    /// guard band or the depth range.
    pub fn from_f32(x: f32, y: f32, depth: f32) -> Result<Self, Error> {
        if !(x.is_finite() && y.is_finite() && depth.is_finite()) {
            return Err(Error::NotFinite);
        }
        let lim = GUARD_BAND as f32;
        let (xs, ys) = (x * SUBPIXEL as f32, y * SUBPIXEL as f32);
        if xs.abs() > lim || ys.abs() > lim || !(0.0..=65535.0).contains(&depth) {
            return Err(Error::OutOfRange);
        }
        let z = (depth * 65536.0 + 0.5) as u32; // saturating cast; ≤ MAX_DEPTH by the check
        Self::new(round_f32(xs), round_f32(ys), z.min(MAX_DEPTH))
    }

    /// x in 1/16 pixel.
    pub const fn x(&self) -> i32 {
        self.x
    }

    /// y in 1/16 pixel.
    pub const fn y(&self) -> i32 {
        self.y
    }

    /// Depth in 16.16.
    pub const fn z(&self) -> u32 {
        self.z
    }
}

/// Twice the signed area of a triangle: the z component of `V1 × V2` with
/// `V1 = P1 − P0`, `V2 = P2 − P0`, i.e. `dx1·dy2 − dx2·dy1` (in the points' units) —
/// the seeds' back-face test. Exact for any inputs in the guard band (the products stay
/// below 2⁵¹).
///
/// The sign depends on which way y points. In the seeds' projected coordinates (y up)
/// a positive value is a counter-clockwise, front-facing triangle. On the screen
/// (y down, as [`ScreenVertex`] has it) the same triangle has a negative value: see
/// [`Facing::of`].
pub fn signed_area(p0: (i32, i32), p1: (i32, i32), p2: (i32, i32)) -> i64 {
    // On 32-bit targets: differences of guard-band coordinates fit i32 (below 2²⁵).
    #[cfg(not(zraster_wide))]
    {
        let guard = |v: i32| (v as u32).wrapping_add(GUARD_BAND as u32) <= 2 * GUARD_BAND as u32;
        if guard(p0.0) && guard(p0.1) && guard(p1.0) && guard(p1.1) && guard(p2.0) && guard(p2.1) {
            return signed_area_guarded(p0, p1, p2);
        }
    }
    area_wide(p0, p1, p2)
}

/// [`signed_area`] in `i64` throughout.
#[inline(always)]
fn area_wide(p0: (i32, i32), p1: (i32, i32), p2: (i32, i32)) -> i64 {
    let (dx1, dy1) = (
        i64::from(p1.0) - i64::from(p0.0),
        i64::from(p1.1) - i64::from(p0.1),
    );
    let (dx2, dy2) = (
        i64::from(p2.0) - i64::from(p0.0),
        i64::from(p2.1) - i64::from(p0.1),
    );
    dx1 * dy2 - dx2 * dy1
}

/// [`signed_area`] for vertices inside the guard band (every coordinate difference
/// below 2²⁵, so it fits `i32`).
#[inline(always)]
pub(crate) fn signed_area_guarded(p0: (i32, i32), p1: (i32, i32), p2: (i32, i32)) -> i64 {
    if crate::num::WIDE {
        // 64-bit registers: the general form is as cheap.
        return area_wide(p0, p1, p2);
    }
    let d = [
        p1.0.wrapping_sub(p0.0),
        p1.1.wrapping_sub(p0.1),
        p2.0.wrapping_sub(p0.0),
        p2.1.wrapping_sub(p0.1),
    ];
    if crate::num::ARMV6M {
        if let Some(a) = area_short(d) {
            return a;
        }
    }
    area_narrow(d)
}

/// The area from the differences `[dx1, dy1, dx2, dy2]`: one `SMULL` each on a
/// Cortex-M3/M4.
#[inline(always)]
fn area_narrow([dx1, dy1, dx2, dy2]: [i32; 4]) -> i64 {
    i64::from(dx1) * i64::from(dy2) - i64::from(dx2) * i64::from(dy1)
}

/// [`area_narrow`] in `i32` when all four differences are below 2¹⁵ (so the products
/// fit): on a chip without a 64-bit multiplier (ARMv6-M) two library calls fewer.
#[inline(always)]
fn area_short([dx1, dy1, dx2, dy2]: [i32; 4]) -> Option<i64> {
    let small = |d: i32| (d as u32).wrapping_add(1 << 15);
    (small(dx1) | small(dy1) | small(dx2) | small(dy2) < 1 << 16)
        .then(|| i64::from(dx1 * dy2 - dx2 * dy1))
}

/// Which way a triangle faces.
///
/// Front faces run counter-clockwise as the viewer sees them with y up — OpenGL's
/// default, and the seeds' "`V1 × V2 > 0` is front" in their left-handed projected
/// coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Facing {
    /// Counter-clockwise as seen with y up.
    Front,
    /// Clockwise as seen with y up.
    Back,
    /// Zero area: a line or a point, never drawn.
    Degenerate,
}

impl Facing {
    /// The facing for twice-signed-area `area` computed in a y-up frame (the seeds'):
    /// positive is front.
    pub fn of_area(area: i64) -> Facing {
        match area {
            a if a > 0 => Facing::Front,
            a if a < 0 => Facing::Back,
            _ => Facing::Degenerate,
        }
    }

    /// The facing of a screen triangle (y down, so the area's sign is flipped first).
    pub fn of(tri: &[ScreenVertex; 3]) -> Facing {
        let p = |v: &ScreenVertex| (v.x, v.y);
        Facing::of_area(-signed_area(p(&tri[0]), p(&tri[1]), p(&tri[2])))
    }
}

/// A quantity that varies linearly across a screen triangle — its depth, or a colour
/// channel for Gouraud shading — given by its plane through the three vertices: the
/// seeds' `ax + by + cz = d` solved for z.
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
    exact: bool,
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
            // Extents below 2¹³: the area and the position products fit i32, the plane
            // numerators (|Δz| < 2³², |Δy| < 2¹³) fit i64, and divisions by a small
            // area take the two-digit path.
            let [p0, p1, p2] = tri;
            let (dx1, dy1) = (p1.x - p0.x, p1.y - p0.y);
            let (dx2, dy2) = (p2.x - p0.x, p2.y - p0.y);
            let area = i64::from(dx1 * dy2 - dx2 * dy1);
            if area == 0 {
                return None;
            }
            let (dz1, dz2) = (
                i64::from(p1.z) - i64::from(p0.z),
                i64::from(p2.z) - i64::from(p0.z),
            );
            let a = dz1 * i64::from(dy2) - dz2 * i64::from(dy1);
            let b = i64::from(dx1) * dz2 - i64::from(dx2) * dz1;
            return fast(
                div_floor(a * i64::from(SUBPIXEL), area),
                div_floor(b * i64::from(SUBPIXEL), area),
            );
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

/// The depth of a triangle's plane at a point: the seeds' "depth from the plane equation".
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

/// A half-open rectangle of pixels that drawing is confined to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Clip {
    pub x0: i32,
    pub y0: i32,
    pub x1: i32,
    pub y1: i32,
}

impl Clip {
    pub(crate) fn intersect(self, o: Clip) -> Clip {
        Clip {
            x0: self.x0.max(o.x0),
            y0: self.y0.max(o.y0),
            x1: self.x1.min(o.x1),
            y1: self.y1.min(o.y1),
        }
    }

    pub(crate) fn from_rect(r: &embedded_graphics::primitives::Rectangle) -> Clip {
        let w = i32::try_from(r.size.width).unwrap_or(i32::MAX);
        let h = i32::try_from(r.size.height).unwrap_or(i32::MAX);
        Clip {
            x0: r.top_left.x,
            y0: r.top_left.y,
            x1: r.top_left.x.saturating_add(w),
            y1: r.top_left.y.saturating_add(h),
        }
    }

    pub(crate) fn is_empty(&self) -> bool {
        self.x0 >= self.x1 || self.y0 >= self.y1
    }

    /// The first and last row in 1/16 pixel, saturated: rows beyond ±2²⁷ pixels lie far
    /// outside the guard band either way.
    #[inline]
    pub(crate) fn subpixel_rows(&self) -> (i32, i32) {
        (
            self.y0.saturating_mul(SUBPIXEL),
            self.y1.saturating_mul(SUBPIXEL),
        )
    }
}

/// One edge walked downward: at each row, `x` is the first pixel whose centre lies on
/// or to the right of the edge.
pub(crate) struct EdgeWalk {
    pub(crate) x: i32,
    err: i32,
    denom: i32,
    step: i32,
    rem: i32,
}

impl EdgeWalk {
    const EMPTY: EdgeWalk = EdgeWalk {
        x: 0,
        err: 0,
        denom: 1,
        step: 0,
        rem: 0,
    };

    /// The edge from `a` to `b` (`a.1 < b.1`), positioned at pixel row `py`.
    ///
    /// Pixel `px` on row `py` is on or right of the edge when
    /// `(16px + 8 − xa)·dy ≥ (16py + 8 − ya)·dx`, i.e. `px ≥ T/(16dy)` with
    /// `T = (16py + 8 − ya)·dx + (xa − 8)·dy`. The walk keeps `x = ⌈T/(16dy)⌉` and
    /// `err = x·16dy − T ∈ [0, 16dy)`; each row adds `16dx` to `T`.
    fn new(a: (i32, i32), b: (i32, i32), py: i32) -> EdgeWalk {
        let dx = i64::from(b.0) - i64::from(a.0);
        let dy = i64::from(b.1) - i64::from(a.1); // 0 < dy ≤ 2²⁵
        let denom = dy * i64::from(SUBPIXEL); // ≤ 2²⁹
        let yc = i64::from(py) * i64::from(SUBPIXEL) + i64::from(SUBPIXEL / 2);
        let t = (yc - i64::from(a.1)) * dx + (i64::from(a.0) - i64::from(SUBPIXEL / 2)) * dy;
        let x = div_ceil(t, denom);
        let err = x * denom - t;
        let step = div_floor(dx, dy);
        let rem = (dx - step * dy) * i64::from(SUBPIXEL);
        EdgeWalk {
            // py lies within the edge's rows, so x lies within its pixel columns (±1):
            // inside ±2²⁰ + 1.
            x: x as i32,
            err: err as i32,
            denom: denom as i32,
            step: step as i32,
            rem: rem as i32,
        }
    }

    /// [`EdgeWalk::new`] for an edge whose coordinates are relative to a local origin
    /// and below 2¹⁴ in magnitude (extents below 2¹³): every product fits `i32`.
    #[inline(always)]
    pub(crate) fn new_small(a: (i32, i32), b: (i32, i32), py: i32) -> EdgeWalk {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1); // |dx| < 2¹⁴, 0 < dy < 2¹⁴
        let denom = dy * SUBPIXEL;
        let yc = py * SUBPIXEL + SUBPIXEL / 2;
        let t = (yc - a.1) * dx + (a.0 - SUBPIXEL / 2) * dy; // < 2²⁹
        let x = -floor_div32(-t, denom); // ⌈t / denom⌉
        let step = floor_div32(dx, dy);
        EdgeWalk {
            x,
            err: x * denom - t,
            denom,
            step,
            rem: (dx - step * dy) * SUBPIXEL,
        }
    }

    #[inline(always)]
    pub(crate) fn advance(&mut self) {
        self.x += self.step;
        self.err -= self.rem;
        if self.err < 0 {
            self.x += 1;
            self.err += self.denom;
        }
    }
}

/// Extents (in 1/16 pixel) below which a triangle takes the all-`i32` setup: 512 pixels.
pub(crate) const SMALL: i32 = 1 << 13;

/// A triangle prepared for scan conversion: vertices sorted top to bottom.
pub(crate) struct Setup {
    v: [(i32, i32); 3],
    /// The middle vertex lies right of the long edge v0→v2.
    mid_right: bool,
    /// Extents below [`SMALL`]: edges are set up in `i32` around a local origin.
    pub(crate) small: bool,
}

impl Setup {
    /// `None` for a zero-area triangle.
    #[inline(always)]
    pub(crate) fn new(tri: &[ScreenVertex; 3]) -> Option<Setup> {
        let mut v = [
            (tri[0].x, tri[0].y),
            (tri[1].x, tri[1].y),
            (tri[2].x, tri[2].y),
        ];
        if v[1].1 < v[0].1 {
            v.swap(0, 1);
        }
        if v[2].1 < v[1].1 {
            v.swap(1, 2);
        }
        if v[1].1 < v[0].1 {
            v.swap(0, 1);
        }
        let xmin = v[0].0.min(v[1].0).min(v[2].0);
        let xmax = v[0].0.max(v[1].0).max(v[2].0);
        let small = xmax - xmin < SMALL && v[2].1 - v[0].1 < SMALL;
        let area = if small {
            let (dx1, dy1) = (v[1].0 - v[0].0, v[1].1 - v[0].1);
            let (dx2, dy2) = (v[2].0 - v[0].0, v[2].1 - v[0].1);
            i64::from(dx1 * dy2 - dx2 * dy1)
        } else {
            signed_area(v[0], v[1], v[2])
        };
        if area == 0 {
            return None;
        }
        // With y down, area > 0 means v0→v1→v2 turns clockwise on screen: v1 is right of v0→v2.
        Some(Setup {
            v,
            mid_right: area > 0,
            small,
        })
    }

    /// The rows of covered pixels inside `clip`, top to bottom.
    #[inline(always)]
    pub(crate) fn spans(&self, clip: &Clip) -> Spans {
        let [v0, v1, v2] = self.v;
        // First row whose centre 16py + 8 is ≥ y: ⌈(y − 8)/16⌉ = (y + 7) >> 4.
        let row = |y: i32| (y + (SUBPIXEL / 2 - 1)) >> SUBPIXEL_BITS;
        let (top, mid, bottom) = (row(v0.1), row(v1.1), row(v2.1));
        let start = top.max(clip.y0);
        let end = if clip.x0 < clip.x1 {
            bottom.min(clip.y1)
        } else {
            start
        };
        // Small triangles: edges in i32 around the pixel corner (ox, oy) at or above-left
        // of every vertex; pixel columns come back shifted by ox / 16.
        let origin = if self.small {
            (
                v0.0.min(v1.0).min(v2.0) & !(SUBPIXEL - 1),
                v0.1 & !(SUBPIXEL - 1),
            )
        } else {
            (0, 0)
        };
        let mut spans = Spans {
            long: EdgeWalk::EMPTY,
            short: EdgeWalk::EMPTY,
            py: start,
            mid,
            end,
            lower: (v1, v2),
            on_lower: false,
            mid_right: self.mid_right,
            small: self.small,
            origin,
            x0: clip.x0,
            x1: clip.x1,
        };
        if start < end {
            spans.long = spans.edge(v0, v2, start);
            if start < mid {
                spans.short = spans.edge(v0, v1, start);
            } else {
                spans.short = spans.edge(v1, v2, start);
                spans.on_lower = true;
            }
        }
        spans
    }
}

/// The rows of a triangle: an iterator of `(y, x0, x1)`, pixel columns `x0..x1`.
pub(crate) struct Spans {
    long: EdgeWalk,
    short: EdgeWalk,
    py: i32,
    mid: i32,
    end: i32,
    lower: ((i32, i32), (i32, i32)),
    on_lower: bool,
    mid_right: bool,
    small: bool,
    origin: (i32, i32),
    x0: i32,
    x1: i32,
}

impl Spans {
    #[inline(always)]
    fn edge(&self, a: (i32, i32), b: (i32, i32), py: i32) -> EdgeWalk {
        if self.small {
            let (ox, oy) = self.origin;
            let mut e = EdgeWalk::new_small(
                (a.0 - ox, a.1 - oy),
                (b.0 - ox, b.1 - oy),
                py - (oy >> SUBPIXEL_BITS),
            );
            e.x += ox >> SUBPIXEL_BITS;
            e
        } else {
            EdgeWalk::new(a, b, py)
        }
    }

    /// The next row with covered pixels inside the clip area.
    #[inline(always)]
    pub(crate) fn next_span(&mut self) -> Option<(i32, i32, i32)> {
        while self.py < self.end {
            let py = self.py;
            if py == self.mid && !self.on_lower {
                let (a, b) = self.lower;
                self.short = self.edge(a, b, py);
                self.on_lower = true;
            }
            let (l, r) = if self.mid_right {
                (self.long.x, self.short.x)
            } else {
                (self.short.x, self.long.x)
            };
            self.long.advance();
            self.short.advance();
            self.py += 1;
            let (x0, x1) = (l.max(self.x0), r.min(self.x1));
            if x0 < x1 {
                return Some((py, x0, x1));
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: i32, y: i32, z: u16) -> ScreenVertex {
        ScreenVertex::from_pixels(x, y, z).unwrap()
    }

    #[test]
    fn guarded_area_is_the_wide_area_up_to_the_guard_band() {
        let g = GUARD_BAND;
        let cases = [
            ((1, 3), (5, 5), (2, 7)),
            ((-g, -g), (g, -g), (g, g)),
            ((g, g), (-g, g), (-g, -g)),
            ((-g, g), (g, -g), (0, 0)),
            ((0, 0), (1 << 15, 0), (0, (1 << 15) - 1)),
            ((-(1 << 15), 0), (1 << 15, 1), (3, -(1 << 15))),
        ];
        for (a, b, c) in cases {
            let wide = area_wide(a, b, c);
            assert_eq!(signed_area_guarded(a, b, c), wide, "{a:?} {b:?} {c:?}");
            assert_eq!(signed_area(a, b, c), wide);
            assert_eq!(signed_area_guarded(b, c, a), wide);
            // The 32-bit targets' forms.
            let d = [b.0 - a.0, b.1 - a.1, c.0 - a.0, c.1 - a.1];
            assert_eq!(area_narrow(d), wide);
            let short = d.iter().all(|&d| (-(1 << 15)..1 << 15).contains(&d));
            assert_eq!(area_short(d), short.then_some(wide));
        }
        assert_eq!(area_wide((-g, -g), (g, -g), (g, g)), 1 << 50);
        // Outside the guard band the public form stays exact.
        let m = i32::MAX;
        assert_eq!(
            signed_area((0, 0), (m, 0), (0, m)),
            i64::from(m) * i64::from(m)
        );
    }

    #[test]
    fn edge_walk_matches_direct_ceil_division() {
        let cases = [
            ((3, -5), (40, 77)),
            ((100, 0), (-33, 250)),
            ((0, 0), (0, 160)),
            ((7, 1), (8, 2)),
        ];
        for (a, b) in cases {
            let first = (a.1 + 7) >> 4;
            let mut w = EdgeWalk::new(a, b, first);
            for py in first..(b.1 + 7) >> 4 {
                let yc = i64::from(py * 16 + 8);
                let (dx, dy) = (i64::from(b.0 - a.0), i64::from(b.1 - a.1));
                let t = (yc - i64::from(a.1)) * dx + (i64::from(a.0) - 8) * dy;
                assert_eq!(
                    i64::from(w.x),
                    div_ceil(t, 16 * dy),
                    "edge {a:?}→{b:?} row {py}"
                );
                w.advance();
            }
        }
    }

    #[test]
    fn small_edge_walk_matches_the_general_one() {
        let cases = [
            ((3, 5), (40, 77)),
            ((100, 0), (-33, 250)),
            ((7, 1), (8, 2)),
            ((8000, 3), (0, 8100)),
        ];
        for (a, b) in cases {
            let (ox, oy) = (a.0.min(b.0) & !15, a.1 & !15);
            let first = (a.1 + 7) >> 4;
            let mut g = EdgeWalk::new(a, b, first);
            let mut s = EdgeWalk::new_small(
                (a.0 - ox, a.1 - oy),
                (b.0 - ox, b.1 - oy),
                first - (oy >> 4),
            );
            for _ in first..(b.1 + 7) >> 4 {
                assert_eq!((g.x, g.err), (s.x + (ox >> 4), s.err), "edge {a:?}→{b:?}");
                g.advance();
                s.advance();
            }
        }
    }

    #[test]
    fn plane_fast_form_matches_exact_form_at_pixel_centres() {
        let tri = [v(2, 3, 100), v(40, 9, 60000), v(11, 50, 3000)];
        let p = Plane::new(&tri, [tri[0].z(), tri[1].z(), tri[2].z()]).unwrap();
        assert!(!p.exact);
        for (px, py) in [(2, 3), (20, 20), (39, 9), (11, 49)] {
            let exact = p.value_at(px * 16 + 8, py * 16 + 8);
            let fast = p.at_pixel(px, py);
            let dist = i64::from((px - 2).abs() + (py - 3).abs());
            assert!(
                (exact - fast).abs() <= dist + 1,
                "({px},{py}): {exact} vs {fast}"
            );
        }
    }

    #[test]
    fn vertex_ranges_are_checked() {
        assert_eq!(
            ScreenVertex::new(GUARD_BAND + 1, 0, 0),
            Err(Error::OutOfRange)
        );
        assert_eq!(
            ScreenVertex::new(0, -GUARD_BAND - 1, 0),
            Err(Error::OutOfRange)
        );
        assert_eq!(
            ScreenVertex::new(0, 0, MAX_DEPTH + 1),
            Err(Error::OutOfRange)
        );
        assert!(ScreenVertex::new(-GUARD_BAND, GUARD_BAND, MAX_DEPTH).is_ok());
        assert_eq!(
            ScreenVertex::from_f32(f32::NAN, 0.0, 0.0),
            Err(Error::NotFinite)
        );
        assert_eq!(
            ScreenVertex::from_f32(0.0, f32::INFINITY, 0.0),
            Err(Error::NotFinite)
        );
        assert_eq!(
            ScreenVertex::from_f32(2e6, 0.0, 0.0),
            Err(Error::OutOfRange)
        );
        assert_eq!(
            ScreenVertex::from_f32(0.0, 0.0, -1.0),
            Err(Error::OutOfRange)
        );
        let p = ScreenVertex::from_f32(1.53, -2.0, 65535.0).unwrap();
        assert_eq!((p.x(), p.y(), p.z()), (24, -32, MAX_DEPTH));
    }
}
