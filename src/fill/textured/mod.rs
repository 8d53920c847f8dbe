//! Textured triangles: the same coverage and depth as flat ones (the raster setup's
//! spans and depth rows), and at every covered pixel a texel, perspective-correct or
//! affine, lit as a flat colour of the texel's value is.
//!
//! # Fixed-point formats and ranges
//!
//! | what | form | range |
//! |---|---|---|
//! | corner w | `i64`, the fixed transform's exact clip w | 1 ≤ w < 2⁴⁵ |
//! | corner q = 1/w | `i64`, `round(2¹⁵ · w_min / w)`: the nearest corner of each triangle gets 2¹⁵ (only ratios count) | 1 ≤ q ≤ 2¹⁵ |
//! | corner u, v | Q16 texture units ([`TexCoord`]) | clamped to ±[`UV_LIMIT`] = ±2²⁴ |
//! | corner u·q, v·q | `i64` | below 2³⁹ |
//! | planes ([`Lin`]) | value at a pixel centre with [`F`] = 16 fractional bits: `o + px·sx + py·sy` in wrapping `i64` | values within 2⁵⁵ |
//! | affine u, v | Q32 (Q16 with 16 more bits): what [`AffineSpan`](crate::texture::AffineSpan) steps | within 2⁴⁰ |
//!
//! A plane is set up once per triangle in `i128`: with corner values below 2⁴¹ (q·u
//! and the differences) and coordinate differences below 2²⁶ (the guard band in
//! 1/16 pixel), its numerators `Δv₁·Δy₂ − Δv₂·Δy₁` stay below 2⁶⁸, times 2²⁰ (a pixel
//! in 1/16 and the 16 fractional bits) below 2⁸⁸, and the origin term
//! (`a·(8 − x₀) + b·(8 − y₀)`, x₀ within 2²⁵) below 2⁹⁴, times 2¹⁶ below 2¹¹⁰. The
//! steps are floored, so a value at a pixel (x, y) of the frame (x, y < 2¹³) is within
//! (x + y + 1)/2¹⁶ < ½ of a unit of the exact plane. The wrapping sum is exact modulo
//! 2⁶⁴, and the true value at a covered pixel centre lies between the corners' values
//! (to that half unit), far inside `i64`: so the wrapping sum is the value itself, as
//! for the depth rows (a sliver's steps may wrap; its sums do not). Each value read is
//! clamped to the corners' range.
//!
//! # Perspective
//!
//! Along a span, u·q, v·q and q are stepped (wrapping `i64`, exact as above) and divided
//! every [`SEGMENT`] pixels and at the last pixel, as
//! [`PerspectiveSpan`](crate::texture::PerspectiveSpan) does: `⌊(u·q ≫ 16) / (q ≫ 16)⌋`,
//! with q ≫ 16 ≤ 2¹⁵ and |u·q ≫ 16| < 2³⁹, the cheap divisions of every core (a pair of
//! 32-bit divides on a Cortex-M3/M4, a reciprocal on the M0+). Between, u and v step
//! linearly in `i32` (times 16: |Δu| ≤ 2²⁵, so below 2²⁹). The bound of
//! `PerspectiveSpan` holds: exact (to the floors) at the segment ends, within
//! `¼·|Δu|·|Δq|/min q + 3` between.
//!
//! # The loops
//!
//! Every pixel goes through one of two loops with the same result (tests/shader.rs and
//! tests/texture.rs compare them): the general one ([`shaded`]: any depth test, light,
//! texture and colour type, a closure per pixel, also what pixel shaders run in), and
//! for the common case ([`span`]: `Less`, one light a face, a repeating power-of-two
//! texture, undithered light) a loop per segment: a whole segment's 16 depths tested
//! first (a mask of failures), then its texels by shifts and a multiply-add straight
//! into the colour row. The QEMU figures: `bash bench/texture.sh`.

use embedded_graphics::pixelcolor::Rgb888;

use crate::num::div_floor_wide;
use crate::raster::{Clip, DepthRows, Plane, ScreenVertex, Setup, SpanStats};
use crate::shade::{DisplayColor, Intensity, ONE};
use crate::texture::{TexCoord, Texel, Texture, UV_LIMIT};
use crate::DepthTest;

mod runs;
mod segments;
mod shaded;
mod span;
pub(crate) use runs::fill_textured_runs;
pub(crate) use segments::{SegmentSteps, Segments};
use span::{pow2_rows, Fetch};

pub use crate::texture::UvMode;

/// Fractional bits of the attribute planes.
pub(crate) const F: u32 = 16;
/// Pixels between exact divisions along a row.
pub(crate) const SEGMENT: i32 = 16;
pub(crate) const SHIFT: u32 = SEGMENT.trailing_zeros();
/// q of a triangle's nearest corner.
const Q_BITS: u32 = 15;

/// A quantity linear across the screen triangle, at pixel centres: `o + px·sx + py·sy`
/// with [`F`] fractional bits, in wrapping `i64` (see the module docs), clamped to
/// `lo..=hi`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Lin {
    o: i64,
    sx: i64,
    sy: i64,
    lo: i64,
    hi: i64,
}

impl Lin {
    /// The plane through the corners' `values` (each below 2⁴⁰ in magnitude); `area2`
    /// is the triangle's doubled signed area in 1/256 pixel² (not 0).
    fn new(tri: &[ScreenVertex; 3], values: [i64; 3], area2: i128) -> Lin {
        let [p0, p1, p2] = tri;
        let (x0, y0) = (i128::from(p0.x()), i128::from(p0.y()));
        let (dx1, dy1) = (i128::from(p1.x()) - x0, i128::from(p1.y()) - y0);
        let (dx2, dy2) = (i128::from(p2.x()) - x0, i128::from(p2.y()) - y0);
        let v0 = i128::from(values[0]);
        let (dv1, dv2) = (i128::from(values[1]) - v0, i128::from(values[2]) - v0);
        let a = dv1 * dy2 - dv2 * dy1;
        let b = dx1 * dv2 - dx2 * dv1;
        // Per pixel (16 units of 1/16 pixel), with F fractional bits.
        let sx = div_floor_wide(a << (4 + F), area2);
        let sy = div_floor_wide(b << (4 + F), area2);
        // At the centre of pixel (0, 0): (8, 8) in 1/16 pixel.
        let o = (v0 << F) + div_floor_wide((a * (8 - x0) + b * (8 - y0)) << F, area2);
        let lo = values[0].min(values[1]).min(values[2]);
        let hi = values[0].max(values[1]).max(values[2]);
        Lin {
            // Modulo 2⁶⁴ on purpose (see the module docs).
            o: o as i64,
            sx: sx as i64,
            sy: sy as i64,
            lo: lo << F,
            hi: hi << F,
        }
    }

    /// The value at the centre of pixel (x, y), clamped to the corners' range.
    #[inline(always)]
    fn at(&self, x: i32, y: i32) -> i64 {
        self.o
            .wrapping_add(self.sx.wrapping_mul(i64::from(x)))
            .wrapping_add(self.sy.wrapping_mul(i64::from(y)))
            .clamp(self.lo, self.hi)
    }
}

/// A triangle's texture coordinates at its corners: w (the clip w, ≥ 1) and (u, v).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct TexCorners {
    pub w: [i64; 3],
    pub uv: [TexCoord; 3],
}

/// The planes a span reads its texture coordinates from.
#[derive(Debug, Clone, Copy)]
pub(crate) enum UvPlanes {
    /// u·q, v·q and q.
    Perspective([Lin; 3]),
    /// u and v in Q32.
    Affine([Lin; 2]),
    /// No texture coordinates: every pixel's are 0.
    None,
}

impl UvPlanes {
    /// The planes of `tri` (zero area: `None`).
    pub(crate) fn new(
        tri: &[ScreenVertex; 3],
        c: &TexCorners,
        mode: Option<UvMode>,
    ) -> Option<Self> {
        let [p0, p1, p2] = tri;
        let (dx1, dy1) = (
            i128::from(p1.x()) - i128::from(p0.x()),
            i128::from(p1.y()) - i128::from(p0.y()),
        );
        let (dx2, dy2) = (
            i128::from(p2.x()) - i128::from(p0.x()),
            i128::from(p2.y()) - i128::from(p0.y()),
        );
        let area2 = dx1 * dy2 - dx2 * dy1;
        if area2 == 0 {
            return None;
        }
        let lim = i64::from(UV_LIMIT);
        let u = c.uv.map(|t| i64::from(t.u).clamp(-lim, lim));
        let v = c.uv.map(|t| i64::from(t.v).clamp(-lim, lim));
        Some(match mode {
            None => UvPlanes::None,
            Some(UvMode::Affine) => {
                UvPlanes::Affine([Lin::new(tri, u, area2), Lin::new(tri, v, area2)])
            }
            Some(UvMode::Perspective) => {
                // 1 ≤ w < 2⁴⁵ (clamped: a clipped corner's w comes from f32).
                let w = c.w.map(|w| w.clamp(1, 1 << 45));
                let wmin = w[0].min(w[1]).min(w[2]);
                // 2¹⁵·w_min/w, rounded: in 1..=2¹⁵ (2¹⁵·w_min < 2⁶⁰).
                let q = w.map(|w| (((wmin << Q_BITS) + w / 2) / w).max(1));
                // |u|, |v| ≤ 2²⁴ and q ≤ 2¹⁵: below 2³⁹.
                let times = |a: [i64; 3]| [a[0] * q[0], a[1] * q[1], a[2] * q[2]];
                let (uq, vq) = (times(u), times(v));
                UvPlanes::Perspective([
                    Lin::new(tri, uq, area2),
                    Lin::new(tri, vq, area2),
                    Lin::new(tri, q, area2),
                ])
            }
        })
    }

    /// The texture coordinates of the `n` pixels from (x0, y) on, in order:
    /// `pixel(k, uv)` for k = 0..n.
    #[inline(always)]
    pub(crate) fn span(&self, x0: i32, y: i32, n: i32, mut pixel: impl FnMut(usize, TexCoord)) {
        if let UvPlanes::None = self {
            for k in 0..n.max(0) as usize {
                pixel(k, TexCoord::default());
            }
            return;
        }
        let mut segments = self.segments(x0, y, n);
        while let Some(s) = segments.next_segment() {
            let (mut u, mut v) = s.uv;
            for k in s.first..s.first + s.len {
                pixel(k, TexCoord::new(u >> SHIFT, v >> SHIFT));
                u = u.wrapping_add(s.step.0);
                v = v.wrapping_add(s.step.1);
            }
        }
    }

    /// The `n` pixels from (x0, y) on as [`Segment`](segments::Segment)s.
    #[inline(always)]
    pub(crate) fn segments(&self, x0: i32, y: i32, n: i32) -> Segments {
        let (h, step, range, perspective) = match self {
            UvPlanes::Perspective(p) => (
                [p[0].at(x0, y), p[1].at(x0, y), p[2].at(x0, y)],
                [p[0].sx, p[1].sx, p[2].sx],
                [(p[0].lo, p[0].hi), (p[1].lo, p[1].hi), (p[2].lo, p[2].hi)],
                true,
            ),
            UvPlanes::Affine(p) => (
                [p[0].at(x0, y), p[1].at(x0, y), 0],
                [p[0].sx, p[1].sx, 0],
                [(p[0].lo, p[0].hi), (p[1].lo, p[1].hi), (0, 0)],
                false,
            ),
            UvPlanes::None => ([0; 3], [0; 3], [(0, 0); 3], false),
        };
        let mut s = Segments {
            h,
            step,
            whole: step.map(|s| s.wrapping_mul(i64::from(SEGMENT))),
            range,
            perspective,
            uv: (0, 0),
            i: 0,
            n,
        };
        if n > 0 {
            s.uv = SegmentSteps::of(&s).exact(s.h);
        }
        s
    }
}

/// The light along a span: one intensity for the face, or Gouraud's plane stepped as
/// [`shade_triangle`](super::shade_triangle) steps it (so that a texel is lit exactly
/// as a flat colour of its value would be).
#[derive(Clone, Copy)]
pub(crate) enum SpanLight {
    Face(Intensity),
    Vertex {
        plane: Plane,
        lo: i64,
        hi: i64,
        step: i64,
    },
}

impl SpanLight {
    pub(crate) fn new(tri: &[ScreenVertex; 3], light: [Intensity; 3]) -> Option<Self> {
        if light[0] == light[1] && light[1] == light[2] {
            return Some(SpanLight::Face(light[0]));
        }
        let plane = Plane::new(tri, light.map(|i| u32::from(i) << 16))?;
        let lo = i64::from(light[0].min(light[1]).min(light[2])) << 16;
        let hi = i64::from(light[0].max(light[1]).max(light[2])) << 16;
        let step = plane.step_x_i64();
        Some(SpanLight::Vertex {
            plane,
            lo,
            hi,
            step,
        })
    }
}

/// The colour of texel `t` at pixel (x, y) lit by `i`: as an `Rgb888` material of the
/// texel's colour is ([`modulate`](crate::texture::modulate)); at full light on a
/// display of the texel's own colour type (and undithered), the texel itself, which is
/// the same colour (a test checks each such type over its values).
#[inline(always)]
pub(crate) fn texel_color<X, C>(t: X, i: Intensity, x: i32, y: i32) -> C
where
    X: Texel,
    X::Color: Into<Rgb888> + 'static,
    C: DisplayColor + 'static,
{
    let c = t.color();
    if i == ONE && !C::DITHERED {
        if let Some(&same) = (&c as &dyn core::any::Any).downcast_ref::<C>() {
            return same;
        }
    }
    C::lit(c.into(), i, x, y)
}

/// [`texel_color`] undithered at `(0, 0)`, out of line: the lit loop's call when the
/// texel value changes, so that the lighting is not inlined into each pixel of the
/// segment loop around the common, cached, case (on ARMv6-M inlined costs less).
#[inline(never)]
fn lit_texel<X, C>(t: X, i: Intensity) -> C
where
    X: Texel,
    X::Color: Into<Rgb888> + 'static,
    C: DisplayColor + 'static,
{
    texel_color::<X, C>(t, i, 0, 0)
}

/// Everything a textured triangle's rows need.
pub(crate) struct TexSetup {
    pub setup: Setup,
    pub rows: DepthRows,
    pub dz: u32,
    pub uv: UvPlanes,
    pub light: SpanLight,
}

impl TexSetup {
    /// `None` for a zero-area triangle.
    #[inline]
    pub(crate) fn new(
        tri: &[ScreenVertex; 3],
        corners: &TexCorners,
        mode: Option<UvMode>,
        light: [Intensity; 3],
    ) -> Option<Self> {
        let setup = Setup::new(tri)?;
        let (rows, dz) = DepthRows::new(tri, &setup)?;
        let uv = UvPlanes::new(tri, corners, mode)?;
        let light = SpanLight::new(tri, light)?;
        Some(TexSetup {
            setup,
            rows,
            dz,
            uv,
            light,
        })
    }

    /// Walk the span (y, x0..x1): `pixel(k, depth, uv, light)` for each of its pixels
    /// in order, with the depth as the flat loops have it.
    #[inline(always)]
    pub(crate) fn span(
        &self,
        y: i32,
        x0: i32,
        x1: i32,
        mut pixel: impl FnMut(usize, u16, TexCoord, Intensity),
    ) {
        let mut acc = self.rows.at(x0, y);
        let dz = self.dz;
        match self.light {
            SpanLight::Face(i) => self.uv.span(x0, y, x1 - x0, |k, uv| {
                let z = (acc >> 16) as u16;
                acc = acc.wrapping_add(dz);
                pixel(k, z, uv, i);
            }),
            SpanLight::Vertex {
                ref plane,
                lo,
                hi,
                step,
            } => {
                let mut li = plane.at_pixel(x0, y).clamp(lo, hi) + (1 << 15);
                self.uv.span(x0, y, x1 - x0, |k, uv| {
                    let z = (acc >> 16) as u16;
                    acc = acc.wrapping_add(dz);
                    let i = (li >> 16).clamp(0, 65535) as u16;
                    li = li.saturating_add(step);
                    pixel(k, z, uv, i);
                })
            }
        }
    }
}

/// Fill a textured triangle into a colour buffer and a Z-buffer: the depth test as the
/// flat loops have it, and each passing pixel the texel lit by `light`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn fill_textured_buffers<C, X>(
    frame: &mut crate::ColorBuffer<'_, C>,
    zbuf: &mut crate::ZBuffer<'_>,
    clip: &Clip,
    test: DepthTest,
    tri: &[ScreenVertex; 3],
    corners: &TexCorners,
    texture: &Texture<'_, X>,
    mode: UvMode,
    light: [Intensity; 3],
) -> SpanStats
where
    X: Texel,
    X::Color: Into<Rgb888> + 'static,
    C: DisplayColor + 'static,
{
    let stats = SpanStats::default();
    if clip.is_empty() {
        return stats;
    }
    let Some(ts) = TexSetup::new(tri, corners, Some(mode), light) else {
        return stats;
    };
    // The common case, the default depth test and one light for the face: a loop per
    // segment over both rows, no call per pixel.
    if let (DepthTest::Less, SpanLight::Face(i)) = (test, ts.light) {
        let full = i == ONE && !C::DITHERED;
        return match (Fetch::new(texture), full) {
            (Fetch::Pow2(tex), true) => {
                // Full light, undithered: no position, a constant intensity.
                let colour = move |t: X, _: usize| texel_color::<X, C>(t, ONE, 0, 0);
                // Where the colours are the texels' bits, the assembly segment.
                match tex.grid() {
                    Some(g) => {
                        pow2_rows::<C, X, true>(frame, zbuf, clip, &ts, tex, Some(g), colour)
                    }
                    None => pow2_rows::<C, X, false>(frame, zbuf, clip, &ts, tex, None, colour),
                }
            }
            (Fetch::Pow2(tex), false) if !C::DITHERED => {
                // Lit: the lit colour of the last texel value is kept, as neighbouring
                // pixels mostly show the same value and lighting one costs some 60
                // instructions. (Undithered: the colour does not depend on the pixel.)
                let Some(&t0) = texture.texels().first() else {
                    return stats;
                };
                let last = core::cell::Cell::new((t0.color(), texel_color::<X, C>(t0, i, 0, 0)));
                let colour = |t: X, _: usize| {
                    let (was, c) = last.get();
                    let now = t.color();
                    if now == was {
                        return c;
                    }
                    let c = if crate::num::ARMV6M {
                        texel_color::<X, C>(t, i, 0, 0)
                    } else {
                        lit_texel::<X, C>(t, i)
                    };
                    last.set((now, c));
                    c
                };
                pow2_rows::<C, X, false>(frame, zbuf, clip, &ts, tex, None, colour)
            }
            (Fetch::Pow2(_), false) | (Fetch::Any(_), _) => {
                let colour = move |x: i32, y: i32, _: u16, uv: TexCoord, i: Intensity| {
                    texel_color::<X, C>(texture.sample_raw(uv), i, x, y)
                };
                shaded::shaded_rows(frame, zbuf, clip, test, &ts, colour)
            }
        };
    }
    let texture = *texture;
    let shade = move |x: i32, y: i32, _: u16, uv: TexCoord, i: Intensity| {
        texel_color::<X, C>(texture.sample_raw(uv), i, x, y)
    };
    shaded::shaded_rows(frame, zbuf, clip, test, &ts, shade)
}

#[cfg(test)]
mod tests;
