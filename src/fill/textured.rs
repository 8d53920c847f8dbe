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

use embedded_graphics::pixelcolor::Rgb888;

use crate::num::{div_floor_pair, div_floor_wide, floor_div32};
use crate::raster::{Clip, DepthRows, Plane, ScreenVertex, Setup, SpanStats};
use crate::shade::{DisplayColor, Intensity, ONE};
use crate::texture::{TexCoord, Texel, Texture, UV_LIMIT};
use crate::DepthTest;

/// How texture coordinates are interpolated across a face.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum UvMode {
    /// Perspective-correct: u/w, v/w and 1/w stepped along each row, an exact division
    /// every 16 pixels and at the row's last pixel, u and v stepped linearly between
    /// (within a bounded error, see [`PerspectiveSpan`](crate::texture::PerspectiveSpan)).
    #[default]
    Perspective,
    /// Affine: u and v stepped linearly across the screen triangle, no division. Exact
    /// for faces square to the view; faces at a slant swim.
    Affine,
}

/// Fractional bits of the attribute planes.
pub(crate) const F: u32 = 16;
/// Pixels between exact divisions along a row.
pub(crate) const SEGMENT: i32 = 16;
const SHIFT: u32 = SEGMENT.trailing_zeros();
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
}

impl UvPlanes {
    /// The planes of `tri` (zero area: `None`).
    pub(crate) fn new(tri: &[ScreenVertex; 3], c: &TexCorners, mode: UvMode) -> Option<Self> {
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
            UvMode::Affine => UvPlanes::Affine([Lin::new(tri, u, area2), Lin::new(tri, v, area2)]),
            UvMode::Perspective => {
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
    pub(crate) fn span(&self, x0: i32, y: i32, n: i32, pixel: impl FnMut(usize, TexCoord)) {
        match self {
            UvPlanes::Perspective(p) => perspective_span(p, x0, y, n, pixel),
            UvPlanes::Affine(p) => affine_span(p, x0, y, n, pixel),
        }
    }
}

/// ⌊u·q / q⌋ and ⌊v·q / q⌋ of values with [`F`] fractional bits, clamped to ±2²⁴.
#[inline(always)]
fn divide(h: [i64; 3]) -> (i32, i32) {
    let q = (h[2] >> F).max(1); // ≤ 2¹⁵
    let (u, v) = div_floor_pair(h[0] >> F, h[1] >> F, q);
    let lim = i64::from(UV_LIMIT);
    (u.clamp(-lim, lim) as i32, v.clamp(-lim, lim) as i32)
}

/// [`UvPlanes::span`], perspective-correct.
#[inline(always)]
fn perspective_span(p: &[Lin; 3], x0: i32, y: i32, n: i32, mut pixel: impl FnMut(usize, TexCoord)) {
    if n <= 0 {
        return;
    }
    let mut h = [p[0].at(x0, y), p[1].at(x0, y), p[2].at(x0, y)];
    let step = [p[0].sx, p[1].sx, p[2].sx];
    let (mut ua, mut va) = divide(h);
    let mut i = 0;
    loop {
        let m = (n - 1 - i).min(SEGMENT);
        if m == 0 {
            // The last pixel: exact.
            pixel(i as usize, TexCoord::new(ua, va));
            return;
        }
        // Wrapping: the values at the segment's end lie between the corners' (see the
        // module docs); each is clamped to its plane's range.
        for ((h, step), p) in h.iter_mut().zip(step).zip(p) {
            *h = h
                .wrapping_add(step.wrapping_mul(i64::from(m)))
                .clamp(p.lo, p.hi);
        }
        let (ub, vb) = divide(h);
        // u and v times SEGMENT step by Δu·SEGMENT/m a pixel: Δu itself over a whole
        // segment, a floored quotient over the last, shorter one. |Δu| ≤ 2²⁵: below 2²⁹.
        let (du, dv) = if m == SEGMENT {
            (ub - ua, vb - va)
        } else {
            (
                floor_div32((ub - ua) << SHIFT, m),
                floor_div32((vb - va) << SHIFT, m),
            )
        };
        let (mut u, mut v) = (ua << SHIFT, va << SHIFT);
        for k in i..i + m {
            pixel(k as usize, TexCoord::new(u >> SHIFT, v >> SHIFT));
            u = u.wrapping_add(du);
            v = v.wrapping_add(dv);
        }
        i += m;
        (ua, va) = (ub, vb);
    }
}

/// [`UvPlanes::span`], affine.
#[inline(always)]
fn affine_span(p: &[Lin; 2], x0: i32, y: i32, n: i32, mut pixel: impl FnMut(usize, TexCoord)) {
    let (mut u, mut v) = (p[0].at(x0, y), p[1].at(x0, y));
    let (du, dv) = (p[0].sx, p[1].sx);
    for k in 0..n.max(0) {
        // Within ±2⁴⁰ (between the corners', clamped at the start; a row's pixels lie
        // inside the triangle): the shifted value fits i32.
        let uv = TexCoord::new((u >> F) as i32, (v >> F) as i32);
        pixel(k as usize, uv);
        u = u.wrapping_add(du).clamp(p[0].lo, p[0].hi);
        v = v.wrapping_add(dv).clamp(p[1].lo, p[1].hi);
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
        mode: UvMode,
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
    let mut stats = SpanStats::default();
    if clip.is_empty() {
        return stats;
    }
    let Some(ts) = TexSetup::new(tri, corners, mode, light) else {
        return stats;
    };
    let write = zbuf.write_enabled();
    per_depth_test!(test, stats, |pass| {
        let mut spans = ts.setup.spans(clip);
        while let Some((y, x0, x1)) = spans.next_span() {
            let (Some(zrow), Some(crow)) = (zbuf.span_mut(y, x0, x1), frame.span_mut(y, x0, x1))
            else {
                continue;
            };
            let mut written = 0;
            ts.span(y, x0, x1, |k, z, uv, i| {
                if let (Some(d), Some(c)) = (zrow.get_mut(k), crow.get_mut(k)) {
                    if pass(z, *d) {
                        if write {
                            *d = z;
                        }
                        *c = texel_color(texture.sample_raw(uv), i, x0 + k as i32, y);
                        written += 1;
                    }
                }
            });
            stats.pixels_tested += (x1 - x0) as u32;
            stats.pixels_written += written;
        }
        stats
    })
}

/// Pixels a run to a draw target is gathered in before it is handed over.
const RUN: usize = 32;

/// Fill a textured triangle into any draw target through a Z-buffer: each row's passing
/// pixels as runs of colours (`fill_contiguous`, at most [`RUN`] pixels each), the same
/// colours as [`fill_textured_buffers`].
#[allow(clippy::too_many_arguments)]
pub(crate) fn fill_textured_runs<D, X>(
    target: &mut D,
    zbuf: &mut crate::ZBuffer<'_>,
    clip: &Clip,
    test: DepthTest,
    tri: &[ScreenVertex; 3],
    corners: &TexCorners,
    texture: &Texture<'_, X>,
    mode: UvMode,
    light: [Intensity; 3],
) -> Result<SpanStats, D::Error>
where
    D: embedded_graphics::prelude::DrawTarget,
    D::Color: DisplayColor + 'static,
    X: Texel,
    X::Color: Into<Rgb888> + 'static,
{
    let mut stats = SpanStats::default();
    if clip.is_empty() {
        return Ok(stats);
    }
    let Some(ts) = TexSetup::new(tri, corners, mode, light) else {
        return Ok(stats);
    };
    let write = zbuf.write_enabled();
    let background = texel_color::<X, D::Color>(texture.sample_raw(TexCoord::default()), ONE, 0, 0);
    per_depth_test!(test, Ok(stats), |pass| {
        let mut spans = ts.setup.spans(clip);
        while let Some((y, x0, x1)) = spans.next_span() {
            let Some(zrow) = zbuf.span_mut(y, x0, x1) else {
                continue;
            };
            stats.pixels_tested += (x1 - x0) as u32;
            // The run being gathered: its first pixel and its colours.
            let mut run = [background; RUN];
            let (mut start, mut len) = (0usize, 0usize);
            let mut result = Ok(());
            let mut flush =
                |start: usize, len: usize, run: &[D::Color; RUN], stats: &mut SpanStats| {
                    if len == 0 {
                        return Ok(());
                    }
                    stats.runs += 1;
                    stats.pixels_written += len as u32;
                    let rect = super::run_rect(y, x0 + start as i32, x0 + (start + len) as i32);
                    target.fill_contiguous(&rect, run.iter().take(len).copied())
                };
            ts.span(y, x0, x1, |k, z, uv, i| {
                if result.is_err() {
                    return;
                }
                let Some(d) = zrow.get_mut(k) else { return };
                if pass(z, *d) {
                    if write {
                        *d = z;
                    }
                    if len == RUN || (len > 0 && start + len != k) {
                        result = flush(start, len, &run, &mut stats);
                        len = 0;
                    }
                    if len == 0 {
                        start = k;
                    }
                    if let Some(slot) = run.get_mut(len) {
                        *slot = texel_color(texture.sample_raw(uv), i, x0 + k as i32, y);
                    }
                    len += 1;
                }
            });
            result?;
            flush(start, len, &run, &mut stats)?;
        }
        Ok(stats)
    })
}
