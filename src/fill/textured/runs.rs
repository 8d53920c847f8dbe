//! Textured triangles into any draw target, as runs of colours.

use embedded_graphics::pixelcolor::Rgb888;

use super::{texel_color, TexCorners, TexSetup, UvMode};
use crate::raster::{Clip, ScreenVertex, SpanStats};
use crate::shade::{DisplayColor, Intensity};
use crate::texture::{TexCoord, Texel, Texture};
use crate::DepthTest;

/// Pixels a run to a draw target is gathered in before it is handed over.
const RUN: usize = 32;

/// Fill a textured triangle into any draw target through a Z-buffer: each row's passing
/// pixels as runs of colours (`fill_contiguous`, at most [`RUN`] pixels each), the same
/// colours as [`fill_textured_buffers`](super::fill_textured_buffers).
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
    let stats = SpanStats::default();
    if clip.is_empty() {
        return Ok(stats);
    }
    let Some(ts) = TexSetup::new(tri, corners, Some(mode), light) else {
        return Ok(stats);
    };
    let texture = *texture;
    let shade = move |x: i32, y: i32, _: u16, uv: TexCoord, i: Intensity| {
        texel_color::<X, D::Color>(texture.sample_raw(uv), i, x, y)
    };
    shaded_runs(target, zbuf, clip, test, &ts, shade)
}

/// The rows of a triangle set up in `ts` into a draw target through a Z-buffer: each
/// row's passing pixels as runs of `shade(x, y, depth, uv, light)` (`fill_contiguous`,
/// at most [`RUN`] pixels each).
pub(super) fn shaded_runs<D>(
    target: &mut D,
    zbuf: &mut crate::ZBuffer<'_>,
    clip: &Clip,
    test: DepthTest,
    ts: &TexSetup,
    shade: impl Fn(i32, i32, u16, TexCoord, Intensity) -> D::Color,
) -> Result<SpanStats, D::Error>
where
    D: embedded_graphics::prelude::DrawTarget,
    D::Color: DisplayColor,
{
    let mut stats = SpanStats::default();
    let write = zbuf.write_enabled();
    // Only fills the run's unused slots.
    let background = D::Color::lit(Rgb888::new(0, 0, 0), 0, 0, 0);
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
                    let rect =
                        crate::fill::run_rect(y, x0 + start as i32, x0 + (start + len) as i32);
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
                        *slot = shade(x0 + k as i32, y, z, uv, i);
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
