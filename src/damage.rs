//! Damage tracking: send the display only what changed since the last frame.
//!
//! On a microcontroller the display bus often bounds the frame rate: a 320×240 RGB565
//! frame is 153,600 bytes, about 20 ms on a 62.5 MHz SPI bus, while the renderer draws
//! it in a few. A [`Damage`] tracker sits between the frame (or band) buffers and the
//! display: for each row it sends only the columns that hold anything but the
//! background now, or did last frame (to restore the background there). Everything
//! else on the display already shows the background.
//!
//! It is exact: after any sequence of frames the display holds what a full redraw
//! would show, provided the display starts out cleared to the background (or the first
//! frame is sent whole, which [`Damage::new`] arranges) and nothing else draws on it.
//!
//! RAM: one `(u16, u16)` per screen row for last frame's columns (960 bytes at 240
//! rows) and one row of colours (640 bytes for 320 RGB565 pixels), both the caller's.
//!
//! ```
//! use embedded_graphics::{mock_display::MockDisplay, pixelcolor::BinaryColor, prelude::*};
//! use zraster::{damage::Damage, ColorBuffer};
//!
//! let mut pixels = [BinaryColor::Off; 8 * 4];
//! let (mut last, mut row) = ([(0u16, 0u16); 4], [BinaryColor::Off; 8]);
//! let mut damage = Damage::new(&mut last, &mut row, BinaryColor::Off)?;
//! let mut display = MockDisplay::new();
//! // Frame 1: one pixel at (2, 1). The first frame is sent whole.
//! let mut frame = ColorBuffer::new(&mut pixels, 8, 4)?;
//! frame.clear(BinaryColor::Off).unwrap();
//! Pixel(Point::new(2, 1), BinaryColor::On).draw(&mut frame).unwrap();
//! frame.flush(&mut damage.target(&mut display)).unwrap();
//! assert_eq!(damage.sent(), 32);
//! // Frame 2: the pixel moves to (5, 1): only row 1, columns 2..6, is sent.
//! frame.clear(BinaryColor::Off).unwrap();
//! Pixel(Point::new(5, 1), BinaryColor::On).draw(&mut frame).unwrap();
//! display.set_allow_overdraw(true);
//! frame.flush(&mut damage.target(&mut display)).unwrap();
//! assert_eq!(damage.sent(), 4);
//! display.assert_pattern(&["........", ".....#..", "........", "........"]);
//! # Ok::<(), zraster::Error>(())
//! ```

use embedded_graphics::{
    pixelcolor::PixelColor,
    prelude::{DrawTarget, OriginDimensions, Point, Size},
    primitives::Rectangle,
    Pixel,
};

use crate::Error;

/// Columns `start..end` of a row; empty when `start >= end`.
type Span = (u16, u16);

/// The whole row: what [`Damage::new`] assumes of every row before the first frame.
const WHOLE: Span = (0, u16::MAX);

/// Tracks which columns of each row differ from the background, frame to frame.
#[derive(Debug)]
pub struct Damage<'a, C> {
    /// Per screen row: the columns that held something else than the background when
    /// last sent.
    last: &'a mut [Span],
    /// One row of colours, to look at a row before sending part of it.
    row: &'a mut [C],
    background: C,
    /// Pixels sent since [`target`](Damage::target) was last called.
    sent: u64,
}

impl<'a, C: PixelColor> Damage<'a, C> {
    /// A tracker for a display of `last.len()` rows of at most `row.len()` pixels,
    /// cleared to `background`. The first frame is sent whole (the display's content is
    /// not known yet). Errors: [`Error::ZeroSize`] for no rows or columns,
    /// [`Error::TooLarge`] beyond 65,535 columns.
    pub fn new(last: &'a mut [(u16, u16)], row: &'a mut [C], background: C) -> Result<Self, Error> {
        if last.is_empty() || row.is_empty() {
            return Err(Error::ZeroSize);
        }
        if row.len() > usize::from(u16::MAX) {
            return Err(Error::TooLarge);
        }
        last.fill(WHOLE);
        Ok(Damage {
            last,
            row,
            background,
            sent: 0,
        })
    }

    /// Forget what the display shows: the next frame is sent whole.
    pub fn invalidate(&mut self) {
        self.last.fill(WHOLE);
    }

    /// The pixels sent to the display through the last [`target`](Damage::target).
    pub fn sent(&self) -> u64 {
        self.sent
    }

    /// A draw target over `display` to flush a frame or bands into
    /// ([`ColorBuffer::flush`](crate::ColorBuffer::flush), or the bands of a banded
    /// drawing): each row of a `fill_contiguous` goes out as the span that changed, if
    /// any. Other calls pass through whole (and mark their rows changed).
    pub fn target<'d, D>(&'d mut self, display: &'d mut D) -> DamageTarget<'d, 'a, D, C>
    where
        D: DrawTarget<Color = C>,
    {
        self.sent = 0;
        DamageTarget {
            damage: self,
            display,
        }
    }

    /// Mark the columns `x0..x1` (clipped to the row) of row `y` as changed.
    fn touch(&mut self, y: i32, x0: i32, x1: i32) {
        let Ok(y) = usize::try_from(y) else {
            return;
        };
        if let Some(s) = self.last.get_mut(y) {
            *s = union(*s, (clamp_u16(x0), clamp_u16(x1)));
        }
    }

    /// `area` goes out whole: its pixels counted as sent, its rows marked changed.
    fn sent_whole(&mut self, area: &Rectangle) {
        let (x0, w) = (area.top_left.x, area.size.width as i32);
        for y in area.rows() {
            self.touch(y, x0, x0.saturating_add(w));
        }
        self.sent += u64::from(area.size.width) * u64::from(area.size.height);
    }
}

/// `v` clamped into `u16`.
fn clamp_u16(v: i32) -> u16 {
    v.clamp(0, i32::from(u16::MAX)) as u16
}

/// The smallest span holding both.
fn union(a: Span, b: Span) -> Span {
    match (a.0 < a.1, b.0 < b.1) {
        (false, _) => b,
        (_, false) => a,
        _ => (a.0.min(b.0), a.1.max(b.1)),
    }
}

/// The draw target of [`Damage::target`].
pub struct DamageTarget<'d, 'a, D, C> {
    damage: &'d mut Damage<'a, C>,
    display: &'d mut D,
}

impl<D: DrawTarget<Color = C>, C: PixelColor> OriginDimensions for DamageTarget<'_, '_, D, C> {
    fn size(&self) -> Size {
        self.display.bounding_box().size
    }
}

impl<D: DrawTarget<Color = C>, C: PixelColor> DrawTarget for DamageTarget<'_, '_, D, C> {
    type Color = C;
    type Error = D::Error;

    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(&mut self, pixels: I) -> Result<(), D::Error> {
        let (damage, display) = (&mut *self.damage, &mut *self.display);
        display.draw_iter(pixels.into_iter().inspect(|Pixel(p, _)| {
            damage.sent += 1;
            damage.touch(p.y, p.x, p.x + 1);
        }))
    }

    fn fill_solid(&mut self, area: &Rectangle, color: C) -> Result<(), D::Error> {
        self.damage.sent_whole(area);
        self.display.fill_solid(area, color)
    }

    fn fill_contiguous<I: IntoIterator<Item = C>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), D::Error> {
        let width = area.size.width as usize;
        let x0 = area.top_left.x;
        if width > self.damage.row.len() {
            // Wider than the row buffer: sent whole, rows marked changed.
            self.damage.sent_whole(area);
            return self.display.fill_contiguous(area, colors);
        }
        let mut colors = colors.into_iter();
        for y in area.rows() {
            let Damage {
                last,
                row,
                background,
                sent,
            } = &mut *self.damage;
            let Some(row) = row.get_mut(..width) else {
                break;
            };
            for (slot, c) in row.iter_mut().zip(&mut colors) {
                *slot = c;
            }
            // This row's columns that are not the background, in screen columns.
            let first = row.iter().position(|c| c != background);
            let now = match first {
                Some(i) => {
                    let end = row
                        .iter()
                        .rposition(|c| c != background)
                        .map_or(i, |e| e + 1);
                    let s = |v: usize| clamp_u16(x0.saturating_add(v as i32));
                    (s(i), s(end))
                }
                None => (0, 0),
            };
            let Some(was) = usize::try_from(y).ok().and_then(|y| last.get_mut(y)) else {
                continue;
            };
            // Send what is not the background now, or was not last time.
            let send = union(*was, now);
            *was = now;
            let lo = i32::from(send.0).max(x0);
            let hi = i32::from(send.1).min(x0.saturating_add(width as i32));
            if lo >= hi {
                continue;
            }
            let (a, b) = ((lo - x0) as usize, (hi - x0) as usize);
            let Some(part) = row.get(a..b) else { continue };
            *sent += (b - a) as u64;
            let rect = Rectangle::new(Point::new(lo, y), Size::new((b - a) as u32, 1));
            self.display.fill_contiguous(&rect, part.iter().copied())?;
        }
        Ok(())
    }
}
