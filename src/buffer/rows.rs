//! Rows of pixels in caller memory: what the colour buffer and the depth buffer share
//! (a whole frame, or a band of `rows` screen rows starting at `first_row`).

use crate::error::prefix_mut;
use crate::{Error, MAX_DIMENSION};

/// `width × rows` entries of `T` covering screen rows `first_row .. first_row + rows`.
#[derive(Debug)]
pub(crate) struct Rows<'a, T> {
    pub(crate) data: &'a mut [T],
    pub(crate) width: u16,
    pub(crate) rows: u16,
    pub(crate) first_row: i32,
}

impl<'a, T> Rows<'a, T> {
    /// The first `width × rows` entries of `data`, covering rows `0..rows`.
    pub(crate) fn new(data: &'a mut [T], width: u32, rows: u32) -> Result<Self, Error> {
        let (w, r) = check_dims(width, rows, data.len())?;
        let data = prefix_mut(data, usize::from(w) * usize::from(r))?;
        Ok(Rows {
            data,
            width: w,
            rows: r,
            first_row: 0,
        })
    }

    /// Cover rows `first_row .. first_row + rows` (contents kept).
    pub(crate) fn set_first_row(&mut self, first_row: i32) -> Result<(), Error> {
        self.first_row = band_origin(first_row, self.rows)?;
        Ok(())
    }

    /// (width, rows, first row): two buffers with the same geometry share indices.
    #[inline]
    pub(crate) fn geometry(&self) -> (u16, u16, i32) {
        (self.width, self.rows, self.first_row)
    }

    /// The index of screen pixel (x, y), `None` outside.
    pub(crate) fn index(&self, x: i32, y: i32) -> Option<usize> {
        let x = usize::try_from(x).ok()?;
        let r = usize::try_from(y.checked_sub(self.first_row)?).ok()?;
        (x < usize::from(self.width) && r < usize::from(self.rows))
            .then(|| r * usize::from(self.width) + x)
    }

    /// The entry at screen pixel (x, y), `None` outside.
    pub(crate) fn get(&self, x: i32, y: i32) -> Option<T>
    where
        T: Copy,
    {
        self.data.get(self.index(x, y)?).copied()
    }

    /// The part of screen row `y` from column `x0` to `x1` (exclusive); `None` when any
    /// of it lies outside.
    #[inline]
    pub(crate) fn span_mut(&mut self, y: i32, x0: i32, x1: i32) -> Option<&mut [T]> {
        row_span(self.data, self.geometry(), y, x0, x1)
    }

    /// Screen rows covered, as a half-open range.
    pub(crate) fn row_range(&self) -> (i32, i32) {
        (
            self.first_row,
            self.first_row.saturating_add(i32::from(self.rows)),
        )
    }
}

/// The part of screen row `y` from column `x0` to `x1` (exclusive) in `data`, a buffer
/// of the given (width, rows, first row) geometry; `None` when any of it lies outside.
#[inline]
pub(crate) fn row_span<T>(
    data: &mut [T],
    (width, rows, first_row): (u16, u16, i32),
    y: i32,
    x0: i32,
    x1: i32,
) -> Option<&mut [T]> {
    let r = y.wrapping_sub(first_row) as u32;
    if r >= u32::from(rows) || x0 < 0 || x1 > i32::from(width) || x0 > x1 {
        return None;
    }
    let start = r as usize * usize::from(width) + x0 as usize;
    data.get_mut(start..start + (x1 - x0) as usize)
}

/// `first_row` when rows `first_row .. first_row + rows` all lie in `i32` (so that
/// bounding boxes and row ranges never overflow), else [`Error::OutOfRange`].
pub(crate) fn band_origin(first_row: i32, rows: u16) -> Result<i32, Error> {
    first_row
        .checked_add(i32::from(rows))
        .map(|_| first_row)
        .ok_or(Error::OutOfRange)
}

/// Validate `width × rows` against [`MAX_DIMENSION`](crate::MAX_DIMENSION) and a slice length.
pub(crate) fn check_dims(width: u32, rows: u32, len: usize) -> Result<(u16, u16), Error> {
    if width == 0 || rows == 0 {
        return Err(Error::ZeroSize);
    }
    if width > MAX_DIMENSION || rows > MAX_DIMENSION {
        return Err(Error::TooLarge);
    }
    // Both ≤ 8192, so the product fits any usize of 32 bits or more.
    let needed = width as usize * rows as usize;
    if len < needed {
        return Err(Error::BufferTooSmall { needed, got: len });
    }
    Ok((width as u16, rows as u16))
}
