//! See-through faces: the depth test without depth writes, and each passing pixel's
//! colour blended over what the pixel holds ([`blend_triangle`]), or, where the
//! display's colours cannot be read, a screen door of its pixels
//! ([`screen_door_triangle`]). Both hand a face's runs, as [`shade_triangle`] makes them
//! for any shading, to a draw target that mixes instead of overwriting.

use embedded_graphics::{
    prelude::{Dimensions, DrawTarget, PointsIter},
    primitives::Rectangle,
    Pixel,
};

use super::shade_triangle;
use crate::raster::{Clip, ScreenVertex, SpanStats};
use crate::shade::{screen_door, Intensity, Material};
use crate::state::RenderState;
use crate::{ColorBuffer, ZBuffer};

/// Draw `tri` in `material` blended over `frame`: depth-tested against `zbuf`, whose
/// depths it leaves as they are. The pixel counts are the pixels tested and blended
/// (no runs: the colours stay in the buffer).
pub(crate) fn blend_triangle<S: RenderState, C, M>(
    frame: &mut ColorBuffer<'_, C>,
    zbuf: &mut ZBuffer<'_>,
    clip: &Clip,
    tri: &[ScreenVertex; 3],
    material: M,
    lights: [Intensity; 3],
) -> SpanStats
where
    C: embedded_graphics::pixelcolor::PixelColor,
    M: Material<C>,
{
    let mut target = BlendInto { frame, material };
    let mut s = without_depth_writes(zbuf, |z| {
        shade_triangle::<S, _, _>(&mut target, Some(z), clip, tri, material, lights)
    })
    .unwrap_or_else(|never| match never {});
    s.runs = 0;
    s
}

/// Draw `tri` in `material` into `display` as a screen door: the pixels that pass the
/// depth test of `zbuf` (left unwritten) and that the [`screen_door`] of the material's
/// alpha covers.
pub(crate) fn screen_door_triangle<S: RenderState, D, M>(
    display: &mut D,
    zbuf: &mut ZBuffer<'_>,
    clip: &Clip,
    tri: &[ScreenVertex; 3],
    material: M,
    lights: [Intensity; 3],
) -> Result<SpanStats, D::Error>
where
    D: DrawTarget,
    M: Material<D::Color>,
{
    let mut target = ScreenDoor {
        display,
        alpha: material.alpha(),
    };
    without_depth_writes(zbuf, |z| {
        shade_triangle::<S, _, _>(&mut target, Some(z), clip, tri, material, lights)
    })
}

/// `f` with the depth writes of `zbuf` off, then as they were.
fn without_depth_writes<T>(zbuf: &mut ZBuffer<'_>, f: impl FnOnce(&mut ZBuffer<'_>) -> T) -> T {
    let write = zbuf.write_enabled();
    zbuf.set_write(false);
    let out = f(zbuf);
    zbuf.set_write(write);
    out
}

/// A colour buffer that blends what is drawn into it over what it holds, by `material`.
struct BlendInto<'a, 'b, C, M> {
    frame: &'a mut ColorBuffer<'b, C>,
    material: M,
}

impl<C: embedded_graphics::pixelcolor::PixelColor, M: Material<C>> BlendInto<'_, '_, C, M> {
    /// Blend `colors` over `area`, row by row (the pixels outside the buffer skipped).
    fn blend_area(&mut self, area: &Rectangle, mut colors: impl Iterator<Item = C>) {
        let x0 = area.top_left.x;
        let w = i32::try_from(area.size.width).unwrap_or(i32::MAX);
        let x1 = x0.saturating_add(w);
        for dy in 0..i32::try_from(area.size.height).unwrap_or(i32::MAX) {
            let y = area.top_left.y.saturating_add(dy);
            // The rasterizer's runs lie inside the buffer: one slice a row.
            if let Some(row) = self.frame.span_mut(y, x0, x1) {
                for (x, (px, src)) in (x0..).zip(row.iter_mut().zip(&mut colors)) {
                    *px = self.material.blend(*px, src, x, y);
                }
                continue;
            }
            for x in x0..x1 {
                let Some(src) = colors.next() else { return };
                if let Some(px) = self.frame.span_mut(y, x, x + 1).and_then(|s| s.first_mut()) {
                    *px = self.material.blend(*px, src, x, y);
                }
            }
        }
    }
}

impl<C: embedded_graphics::pixelcolor::PixelColor, M> Dimensions for BlendInto<'_, '_, C, M> {
    fn bounding_box(&self) -> Rectangle {
        self.frame.bounding_box()
    }
}

impl<C: embedded_graphics::pixelcolor::PixelColor, M: Material<C>> DrawTarget
    for BlendInto<'_, '_, C, M>
{
    type Color = C;
    type Error = core::convert::Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<C>>,
    {
        for Pixel(p, src) in pixels {
            if let Some(px) = self
                .frame
                .span_mut(p.y, p.x, p.x + 1)
                .and_then(|s| s.first_mut())
            {
                *px = self.material.blend(*px, src, p.x, p.y);
            }
        }
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, color: C) -> Result<(), Self::Error> {
        self.blend_area(area, core::iter::repeat(color));
        Ok(())
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = C>,
    {
        self.blend_area(area, colors.into_iter());
        Ok(())
    }
}

/// A display that takes only the pixels the screen door of `alpha` covers.
struct ScreenDoor<'a, D> {
    display: &'a mut D,
    alpha: u8,
}

impl<D: DrawTarget> Dimensions for ScreenDoor<'_, D> {
    fn bounding_box(&self) -> Rectangle {
        self.display.bounding_box()
    }
}

impl<D: DrawTarget> DrawTarget for ScreenDoor<'_, D> {
    type Color = D::Color;
    type Error = D::Error;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<D::Color>>,
    {
        let alpha = self.alpha;
        self.display.draw_iter(
            pixels
                .into_iter()
                .filter(|Pixel(p, _)| screen_door(alpha, p.x, p.y)),
        )
    }

    fn fill_solid(&mut self, area: &Rectangle, color: D::Color) -> Result<(), Self::Error> {
        self.draw_iter(area.points().map(|p| Pixel(p, color)))
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = D::Color>,
    {
        self.draw_iter(area.points().zip(colors).map(|(p, c)| Pixel(p, c)))
    }
}
