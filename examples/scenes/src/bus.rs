//! A model of an RGB565 display on an SPI bus (an ST7789 or ILI9341 with address
//! windows), for the damage-tracking example, `render --damage` and their tests.

use embedded_graphics::{
    pixelcolor::Rgb565,
    prelude::{DrawTarget, OriginDimensions, Point, PointsIter, Size},
    primitives::Rectangle,
    Pixel,
};

/// Bytes of the commands that open an address window: CASET and RASET (a command byte
/// and four data bytes each), then RAMWR.
pub const WINDOW_BYTES: u64 = 11;

/// A display that keeps every pixel it is sent and counts the bytes the bus carries:
/// [`WINDOW_BYTES`] for each call (a lone pixel opens a window of its own), then 2
/// bytes a pixel. Writes outside the screen are counted in `outside`, not stored.
pub struct SpiDisplay {
    width: u32,
    /// The screen, row by row.
    pub pixels: Vec<Rgb565>,
    /// Bytes sent since it was last set to 0.
    pub bytes: u64,
    /// Pixels sent outside the screen.
    pub outside: u64,
}

impl SpiDisplay {
    /// A `width × height` display showing `initial` everywhere.
    pub fn new(width: u32, height: u32, initial: Rgb565) -> Self {
        SpiDisplay {
            width,
            pixels: vec![initial; (width * height) as usize],
            bytes: 0,
            outside: 0,
        }
    }

    fn put(&mut self, p: Point, c: Rgb565) {
        let inside = p.x >= 0 && p.y >= 0 && (p.x as u32) < self.width;
        match self
            .pixels
            .get_mut((p.y as u32 * self.width + p.x as u32) as usize)
        {
            Some(slot) if inside => *slot = c,
            _ => self.outside += 1,
        }
    }
}

impl OriginDimensions for SpiDisplay {
    fn size(&self) -> Size {
        Size::new(self.width, self.pixels.len() as u32 / self.width)
    }
}

impl DrawTarget for SpiDisplay {
    type Color = Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in pixels {
            self.bytes += WINDOW_BYTES + 2;
            self.put(p, c);
        }
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        self.bytes += WINDOW_BYTES;
        for (p, c) in area.points().zip(colors) {
            self.bytes += 2;
            self.put(p, c);
        }
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, color: Rgb565) -> Result<(), Self::Error> {
        self.fill_contiguous(area, core::iter::repeat(color))
    }
}
