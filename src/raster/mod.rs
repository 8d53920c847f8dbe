//! Screen-space triangles: vertices, the back-face test, the depth plane and scan
//! conversion into spans.
//!
//! Scan conversion walks the triangle's left and right edges row by row with an exact
//! integer DDA (a quotient and a remainder per edge, no division per row), giving each
//! row's span of covered pixel centres. The result is identical to testing every pixel
//! centre against the three edge functions with the top-left rule, so triangles that
//! share an edge cover each pixel along it exactly once.

use crate::fixed::{GUARD_BAND, MAX_DEPTH, SUBPIXEL, SUBPIXEL_BITS};
use crate::num::round_f32;
use crate::Error;

/// A vertex in screen space: `x`, `y` in 28.4 fixed point (1/16 pixel), depth in 16.16.
///
/// The y axis points down (row 0 at the top). Construction checks the ranges documented
/// in [`fixed`](crate::fixed): `|x|, |y| ≤ GUARD_BAND`, `depth ≤ MAX_DEPTH`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
// x, y, z at offsets 0, 4, 8: the small triangle's assembly set-up reads them in place.
#[repr(C)]
pub struct ScreenVertex {
    x: i32,
    y: i32,
    z: u32,
}

// The layout the set-up assembly reads (`num::kernel::rows`).
const _: () = {
    use core::mem::offset_of;
    assert!(offset_of!(ScreenVertex, x) == 0 && offset_of!(ScreenVertex, y) == 4);
    assert!(offset_of!(ScreenVertex, z) == 8);
};

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
/// the classic back-face test. Exact for any inputs in the guard band (the products stay
/// below 2⁵¹).
///
/// The sign depends on which way y points. In the classic projected coordinates (y up)
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
/// default, and the classic back-face rule "`V1 × V2 > 0` is front" in left-handed projected
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
    /// The facing for twice-signed-area `area` computed in a y-up frame (as the classic
    /// back-face test computes it): positive is front.
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

/// Counts from drawing one or more triangles.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct SpanStats {
    /// Pixel centres inside the triangles and the clip area (depth-tested).
    pub pixels_tested: u32,
    /// Pixels that passed the depth test and were drawn.
    pub pixels_written: u32,
    /// Horizontal runs handed to the draw target.
    pub runs: u32,
}

impl core::ops::AddAssign for SpanStats {
    fn add_assign(&mut self, o: SpanStats) {
        self.pixels_tested += o.pixels_tested;
        self.pixels_written += o.pixels_written;
        self.runs += o.runs;
    }
}

mod edge;
mod line;
mod plane;

pub(crate) use edge::{EdgeDivide, EdgeWalk, Setup, SmallEdge, SMALL};
pub(crate) use line::draw_line;
#[cfg(test)]
pub(crate) use plane::plane_origin;
pub use plane::{depth_at, Plane};
pub(crate) use plane::{small_steps, DepthRows, DEPTH_BIAS};

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::div_ceil;

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
