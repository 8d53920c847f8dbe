//! Triangles coloured pixel by pixel by a caller's function of the position, depth,
//! texture coordinates and light: the machinery of
//! [`Renderer::draw_with_shader`](crate::Renderer::draw_with_shader), and of textured drawing
//! wherever its fast loop does not apply.

use embedded_graphics::pixelcolor::PixelColor;

use super::runs::shaded_runs;
use super::{TexCorners, TexSetup, UvMode};
use crate::raster::{Clip, ScreenVertex, SpanStats};
use crate::shade::{DisplayColor, Intensity};
use crate::texture::TexCoord;
use crate::DepthTest;

/// (Methods of the corners, as `fill` re-exports the type, not new functions.)
impl TexCorners {
    /// Fill a triangle into a colour buffer and a Z-buffer, each pixel that passes the
    /// depth test coloured `shade(x, y, depth, uv, light)`: uv interpolated by `mode` (all
    /// 0 without), the light as textured drawing has it.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    pub(crate) fn fill_shaded_buffers<C: PixelColor>(
        &self,
        frame: &mut crate::ColorBuffer<'_, C>,
        zbuf: &mut crate::ZBuffer<'_>,
        clip: &Clip,
        test: DepthTest,
        tri: &[ScreenVertex; 3],
        mode: Option<UvMode>,
        light: [Intensity; 3],
        shade: impl Fn(i32, i32, u16, TexCoord, Intensity) -> C,
    ) -> SpanStats {
        if clip.is_empty() {
            return SpanStats::default();
        }
        let Some(ts) = TexSetup::new(tri, self, mode, light) else {
            return SpanStats::default();
        };
        shaded_rows(frame, zbuf, clip, test, &ts, shade)
    }

    /// [`fill_shaded_buffers`](TexCorners::fill_shaded_buffers) into any draw target through a Z-buffer: runs of colours.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    pub(crate) fn fill_shaded_runs<D>(
        &self,
        target: &mut D,
        zbuf: &mut crate::ZBuffer<'_>,
        clip: &Clip,
        test: DepthTest,
        tri: &[ScreenVertex; 3],
        mode: Option<UvMode>,
        light: [Intensity; 3],
        shade: impl Fn(i32, i32, u16, TexCoord, Intensity) -> D::Color,
    ) -> Result<SpanStats, D::Error>
    where
        D: embedded_graphics::prelude::DrawTarget,
        D::Color: DisplayColor,
    {
        if clip.is_empty() {
            return Ok(SpanStats::default());
        }
        let Some(ts) = TexSetup::new(tri, self, mode, light) else {
            return Ok(SpanStats::default());
        };
        shaded_runs(target, zbuf, clip, test, &ts, shade)
    }
}

/// The rows of a triangle set up in `ts` into a colour buffer and a Z-buffer: the depth
/// test as the flat loops have it, each passing pixel `shade(x, y, depth, uv, light)`.
pub(super) fn shaded_rows<C: PixelColor>(
    frame: &mut crate::ColorBuffer<'_, C>,
    zbuf: &mut crate::ZBuffer<'_>,
    clip: &Clip,
    test: DepthTest,
    ts: &TexSetup,
    shade: impl Fn(i32, i32, u16, TexCoord, Intensity) -> C,
) -> SpanStats {
    let mut stats = SpanStats::default();
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
                        *c = shade(x0 + k as i32, y, z, uv, i);
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
