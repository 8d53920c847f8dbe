//! A colour buffer in caller memory that is also a fast [`DrawTarget`].

use embedded_graphics::{
    pixelcolor::PixelColor,
    prelude::{Dimensions, DrawTarget, Point, Size},
    primitives::Rectangle,
    Pixel,
};

use super::Rows;
use crate::raster::Clip;
use crate::Error;

/// A frame (or a band of one) of colours in a caller-provided slice.
///
/// `embedded_graphics::framebuffer::Framebuffer` owns its array and draws pixel by
/// pixel; this one borrows its memory, fills rectangles with slice operations, and sends
/// itself to a display with a single [`fill_contiguous`](DrawTarget::fill_contiguous)
/// ([`flush`](ColorBuffer::flush)), which display drivers turn into one address window
/// and one burst. It covers screen rows `first_row .. first_row + rows`.
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle};
/// use zraster::ColorBuffer;
/// let mut pixels = [Rgb565::BLACK; 16 * 4];
/// let mut buf = ColorBuffer::new(&mut pixels, 16, 4)?;
/// buf.fill_solid(&Rectangle::new(Point::new(2, 1), Size::new(3, 2)), Rgb565::RED).unwrap();
/// assert_eq!(buf.pixel(4, 2), Some(Rgb565::RED));
/// assert_eq!(buf.pixel(5, 2), Some(Rgb565::BLACK));
/// # Ok::<(), zraster::Error>(())
/// ```
#[derive(Debug)]
pub struct ColorBuffer<'a, C> {
    buf: Rows<'a, C>,
}

impl<'a, C: PixelColor> ColorBuffer<'a, C> {
    /// A buffer of `width × rows` pixels covering screen rows `0..rows`.
    ///
    /// Errors as for [`ZBuffer::new`](crate::ZBuffer::new): zero or too-large dimensions,
    /// or a slice shorter than `width × rows`.
    pub fn new(data: &'a mut [C], width: u32, rows: u32) -> Result<Self, Error> {
        Ok(ColorBuffer {
            buf: Rows::new(data, width, rows)?,
        })
    }

    /// A buffer covering screen rows `first_row .. first_row + rows` (a band).
    ///
    /// Errors: as [`new`](ColorBuffer::new), and [`Error::OutOfRange`] when the last row
    /// would lie beyond `i32::MAX`.
    pub fn new_band(
        data: &'a mut [C],
        width: u32,
        rows: u32,
        first_row: i32,
    ) -> Result<Self, Error> {
        let mut b = Self::new(data, width, rows)?;
        b.set_first_row(first_row)?;
        Ok(b)
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        u32::from(self.buf.width)
    }

    /// Rows held.
    pub fn rows(&self) -> u32 {
        u32::from(self.buf.rows)
    }

    /// The first screen row covered.
    pub fn first_row(&self) -> i32 {
        self.buf.first_row
    }

    /// Move the band to cover rows `first_row .. first_row + rows` (contents kept).
    ///
    /// Errors: [`Error::OutOfRange`] when the last row would lie beyond `i32::MAX`.
    pub fn set_first_row(&mut self, first_row: i32) -> Result<(), Error> {
        self.buf.set_first_row(first_row)
    }

    /// The colour at screen pixel (x, y), `None` outside the buffer.
    pub fn pixel(&self, x: i32, y: i32) -> Option<C> {
        self.buf.get(x, y)
    }

    /// The pixels, row by row.
    pub fn as_slice(&self) -> &[C] {
        self.buf.data
    }

    /// Send the whole buffer to `display` at its screen position with one
    /// `fill_contiguous`. A buffer that overhangs the display's bounding box is clipped
    /// to it first (some drivers do not clip `fill_contiguous` themselves) and sent with
    /// one `fill_contiguous` a visible row.
    pub fn flush<D: DrawTarget<Color = C>>(
        &self,
        display: &mut D,
    ) -> Result<(), crate::DrawError<D::Error>> {
        self.flush_raw(display).map_err(crate::DrawError::Target)
    }

    /// [`flush`](ColorBuffer::flush) with the display's own error.
    fn flush_raw<D: DrawTarget<Color = C>>(&self, display: &mut D) -> Result<(), D::Error> {
        let area = self.bounding_box();
        let visible = area.intersection(&display.bounding_box());
        if visible.size.width == 0 || visible.size.height == 0 {
            return Ok(());
        }
        // The whole buffer in one piece, or each visible row in one when it overhangs
        // the display: one call site of the driver's pixel loop for both, so that it is
        // built (and inlined) once.
        let whole = visible == area;
        let pieces = if whole { 1 } else { visible.size.height };
        let w = usize::from(self.buf.width);
        let (vx, vy) = (visible.top_left.x, visible.top_left.y - self.buf.first_row);
        let vw = visible.size.width as usize;
        for i in 0..pieces {
            let (rect, part) = if whole {
                (area, Some(&self.buf.data[..]))
            } else {
                let start = (vy as usize + i as usize) * w + vx as usize;
                let line = Point::new(vx, visible.top_left.y + i as i32);
                let line = Rectangle::new(line, Size::new(vw as u32, 1));
                (line, self.buf.data.get(start..start + vw))
            };
            let Some(part) = part else { break };
            display.fill_contiguous(&rect, part.iter().copied())?;
        }
        Ok(())
    }

    /// The part of screen row `y` from column `x0` to `x1` (exclusive); `None` when any
    /// of it lies outside the buffer.
    #[inline]
    pub(crate) fn span_mut(&mut self, y: i32, x0: i32, x1: i32) -> Option<&mut [C]> {
        self.buf.span_mut(y, x0, x1)
    }

    /// (width, rows, first row), as [`ZBuffer`](crate::ZBuffer) reports it.
    #[inline]
    pub(crate) fn geometry(&self) -> (u16, u16, i32) {
        self.buf.geometry()
    }

    /// The pixels, mutable.
    #[inline]
    pub(crate) fn data_mut(&mut self) -> &mut [C] {
        self.buf.data
    }

    /// The rows of `area` (already inside the buffer) as mutable slices.
    fn rows_of(&mut self, c: Clip) -> impl Iterator<Item = &mut [C]> {
        let w = usize::from(self.buf.width);
        let (x0, x1) = (c.x0 as usize, c.x1 as usize);
        let r0 = (c.y0 - self.buf.first_row) as usize;
        let n = (c.y1 - c.y0) as usize;
        self.buf
            .data
            .chunks_exact_mut(w)
            .skip(r0)
            .take(n)
            .filter_map(move |row| row.get_mut(x0..x1))
    }

    fn clip(&self, area: &Rectangle) -> Clip {
        Clip::from_rect(area).intersect(Clip::from_rect(&self.bounding_box()))
    }
}

impl<C: PixelColor> Dimensions for ColorBuffer<'_, C> {
    fn bounding_box(&self) -> Rectangle {
        Rectangle::new(
            Point::new(0, self.buf.first_row),
            Size::new(u32::from(self.buf.width), u32::from(self.buf.rows)),
        )
    }
}

impl<C: PixelColor> DrawTarget for ColorBuffer<'_, C> {
    type Color = C;
    type Error = core::convert::Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<C>>,
    {
        for Pixel(p, c) in pixels {
            if let Some(i) = self.buf.index(p.x, p.y) {
                if let Some(px) = self.buf.data.get_mut(i) {
                    *px = c;
                }
            }
        }
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, color: C) -> Result<(), Self::Error> {
        // Runs from the rasterizer: one row, already inside. Fill the slice directly.
        if area.size.height == 1 {
            let (x, y) = (area.top_left.x, area.top_left.y);
            if let (Some(i), Ok(w)) = (self.buf.index(x, y), usize::try_from(area.size.width)) {
                if x as usize + w <= usize::from(self.buf.width) {
                    if let Some(run) = self.buf.data.get_mut(i..i + w) {
                        run.fill(color);
                        return Ok(());
                    }
                }
            }
        }
        let c = self.clip(area);
        if !c.is_empty() {
            self.rows_of(c).for_each(|row| row.fill(color));
        }
        Ok(())
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = C>,
    {
        let c = self.clip(area);
        if c.is_empty() {
            return Ok(());
        }
        let full = Clip::from_rect(area);
        let mut colors = colors.into_iter();
        if c == full && c.x0 == 0 && c.x1 == i32::from(self.buf.width) {
            // Whole rows: one contiguous run of the buffer, filled by one zip (a memcpy
            // when the colours come from a slice, as a band's flush has them).
            let w = usize::from(self.buf.width);
            let start = (c.y0 - self.buf.first_row) as usize * w;
            let end = start + (c.y1 - c.y0) as usize * w;
            if let Some(run) = self.buf.data.get_mut(start..end) {
                copy_run(run, colors);
            }
            return Ok(());
        }
        if c == full {
            for row in self.rows_of(c) {
                for (px, col) in row.iter_mut().zip(&mut colors) {
                    *px = col;
                }
            }
            return Ok(());
        }
        // Partly outside: walk the whole area, keep what falls inside.
        let w = area.size.width as usize;
        for (i, col) in colors.enumerate().take(w * area.size.height as usize) {
            let x = full.x0 + (i % w) as i32;
            let y = full.y0 + (i / w) as i32;
            if let Some(j) = self.buf.index(x, y) {
                if let Some(px) = self.buf.data.get_mut(j) {
                    *px = col;
                }
            }
        }
        Ok(())
    }

    fn clear(&mut self, color: C) -> Result<(), Self::Error> {
        crate::num::fill(self.buf.data, color);
        Ok(())
    }
}

/// Stores `colors` in `run`, pixel by pixel. A function of its own on purpose: with `run`
/// an argument LLVM knows it aliases nothing else and turns a copy from a slice's colours
/// (a band's flush) into one `memcpy` before inlining it; in line, it stays a loop.
#[inline]
fn copy_run<C, I: Iterator<Item = C>>(run: &mut [C], colors: I) {
    for (px, col) in run.iter_mut().zip(colors) {
        *px = col;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::pixelcolor::Gray8;

    /// A band flushed into a smaller display, overhanging it at the top, bottom or
    /// right, lands row by row exactly where its pixels belong.
    #[test]
    fn a_clipped_flush_sends_the_visible_pixels() {
        let value = |x: i32, y: i32| Gray8::new((16 * y + x) as u8);
        for first_row in [-2, 0, 3, 6] {
            let mut px = [Gray8::new(0); 8 * 4];
            for (i, p) in px.iter_mut().enumerate() {
                *p = value(i as i32 % 8, first_row + i as i32 / 8);
            }
            let band = ColorBuffer::new_band(&mut px, 8, 4, first_row).unwrap();
            let mut shown = [Gray8::new(255); 6 * 5];
            let mut display = ColorBuffer::new(&mut shown, 6, 5).unwrap();
            band.flush(&mut display).unwrap();
            for y in 0..5 {
                for x in 0..6 {
                    let inside = (first_row..first_row + 4).contains(&y);
                    let want = if inside { value(x, y) } else { Gray8::new(255) };
                    assert_eq!(display.pixel(x, y), Some(want), "{x}, {y} from {first_row}");
                }
            }
        }
    }
}
