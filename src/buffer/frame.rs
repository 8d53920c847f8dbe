//! A whole frame in RAM: a colour buffer and a depth buffer drawn together.

use embedded_graphics::{pixelcolor::PixelColor, prelude::DrawTarget};

use super::{ColorBuffer, ZBuffer};
use crate::Error;

/// A frame in memory you provide: a [`ColorBuffer`] and a [`ZBuffer`] of the same size,
/// drawn into together by [`Renderer::draw`](crate::Renderer::draw).
///
/// This is the fastest target: for flat and Lambert shading the depth test and the
/// colour write share one loop, and nothing is handed to a `DrawTarget` until you
/// [`flush`](Frame::flush) the finished frame to a display in one `fill_contiguous`.
/// It needs `width × height × (size_of::<C>() + 2)` bytes; when that is too much,
/// draw in [`Bands`](crate::Bands).
///
/// ```
/// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::Rgb565, prelude::*};
/// use zraster::camera::{Camera, Viewport};
/// use zraster::{math::{radians, Vec3}, mesh::CUBE, Frame, RenderOptions, Renderer};
///
/// let mut pixels = [Rgb565::BLACK; 64 * 48];
/// let mut depth = [0u16; 64 * 48];
/// let mut frame = Frame::new(&mut pixels, &mut depth, 64, 48)?;
/// frame.clear(Rgb565::BLACK);
/// let xf = Camera::look_at(Vec3::new(2.0, 1.5, 3.0), Vec3::new(0.5, 0.5, 0.5), Vec3::Y)?
///     .perspective(radians(45.0), 0.1, 10.0, Viewport::new(64, 48)?)?;
/// Renderer::new(&CUBE, &xf, RenderOptions::default())?.draw(&mut frame)?;
/// assert_eq!(frame.color().pixel(32, 24), Some(Rgb565::new(0, 0, 31))); // the blue front face
/// assert!(frame.depth().depth(32, 24) < Some(u16::MAX));
///
/// let mut display = MockDisplay::<Rgb565>::new(); // 64 × 64
/// frame.flush(&mut display).unwrap(); // the whole frame in one fill_contiguous
/// assert_eq!(display.get_pixel(Point::new(32, 24)), Some(Rgb565::new(0, 0, 31)));
/// # Ok::<(), zraster::Error>(())
/// ```
#[derive(Debug)]
pub struct Frame<'a, C> {
    color: ColorBuffer<'a, C>,
    depth: ZBuffer<'a>,
}

impl<'a, C: PixelColor> Frame<'a, C> {
    /// A `width × height` frame over `pixels` and `depth` (each at least
    /// `width × height` entries; only that many are used). Its contents are whatever the
    /// slices hold: [`clear`](Frame::clear) it before drawing.
    ///
    /// Errors as for [`ColorBuffer::new`] and [`ZBuffer::new`]: a zero dimension, one
    /// above [`MAX_DIMENSION`](crate::MAX_DIMENSION), or a slice that is too short.
    pub fn new(
        pixels: &'a mut [C],
        depth: &'a mut [u16],
        width: u32,
        height: u32,
    ) -> Result<Self, Error> {
        Ok(Frame {
            color: ColorBuffer::new(pixels, width, height)?,
            depth: ZBuffer::new(depth, width, height)?,
        })
    }

    /// A frame of buffers you built yourself, for example a band of rows
    /// ([`ColorBuffer::new_band`], [`ZBuffer::new_band`]) or a depth buffer with another
    /// [`DepthTest`](crate::DepthTest). The two may differ in size and rows: only the
    /// pixels both hold are drawn.
    pub fn from_buffers(color: ColorBuffer<'a, C>, depth: ZBuffer<'a>) -> Self {
        Frame { color, depth }
    }

    /// Fill the colour buffer with `background` and the depth buffer with
    /// [`ZBuffer::FAR`]: what every frame starts from.
    pub fn clear(&mut self, background: C) {
        crate::num::fill(self.color.data_mut(), background);
        self.depth.clear();
    }

    /// Send the colour buffer to `display` with one `fill_contiguous`
    /// (see [`ColorBuffer::flush`]).
    pub fn flush<D: DrawTarget<Color = C>>(
        &self,
        display: &mut D,
    ) -> Result<(), crate::DrawError<D::Error>> {
        self.color.flush(display)
    }

    /// The colour buffer (to read pixels, or to flush it).
    pub fn color(&self) -> &ColorBuffer<'a, C> {
        &self.color
    }

    /// The colour buffer, to draw on it with embedded-graphics (text, an overlay).
    pub fn color_mut(&mut self) -> &mut ColorBuffer<'a, C> {
        &mut self.color
    }

    /// The depth buffer.
    pub fn depth(&self) -> &ZBuffer<'a> {
        &self.depth
    }

    /// The depth buffer, to change its test or writing, or to fill it.
    pub fn depth_mut(&mut self) -> &mut ZBuffer<'a> {
        &mut self.depth
    }

    /// Both buffers at once, for calls that take them apart (such as
    /// [`Renderer::draw_hidden_line`](crate::Renderer::draw_hidden_line)).
    pub fn parts_mut(&mut self) -> (&mut ColorBuffer<'a, C>, &mut ZBuffer<'a>) {
        (&mut self.color, &mut self.depth)
    }

    /// The two buffers back.
    pub fn into_parts(self) -> (ColorBuffer<'a, C>, ZBuffer<'a>) {
        (self.color, self.depth)
    }
}
