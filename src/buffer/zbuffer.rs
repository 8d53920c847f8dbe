//! The depth buffer: 16 bits per pixel in memory the caller owns.

use super::Rows;
use crate::Error;

/// How a fragment's depth is compared with the stored depth.
///
/// Smaller depth is nearer (window depth 0 = near plane, 65535 = far plane), as in the
/// classic Z-buffer algorithm (Catmull, 1974): a fragment is drawn when its `z < Z(i, j)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum DepthTest {
    /// Pass when the fragment is strictly nearer (the default, OpenGL's `GL_LESS`).
    #[default]
    Less,
    /// Pass when the fragment is nearer or at the same depth.
    LessEqual,
    /// Pass when the fragment is strictly farther.
    Greater,
    /// Pass when the depths are equal.
    Equal,
    /// Always pass (depth is still written when writing is on).
    Always,
    /// Never pass.
    Never,
}

impl DepthTest {
    /// Does a fragment at depth `fragment` pass against a stored `stored`?
    #[inline(always)]
    pub fn passes(self, fragment: u16, stored: u16) -> bool {
        match self {
            DepthTest::Less => fragment < stored,
            DepthTest::LessEqual => fragment <= stored,
            DepthTest::Greater => fragment > stored,
            DepthTest::Equal => fragment == stored,
            DepthTest::Always => true,
            DepthTest::Never => false,
        }
    }
}

/// A 16-bit depth buffer over a caller-provided slice.
///
/// It covers `rows` screen rows starting at `first_row`, each `width` entries wide, so
/// it can hold a whole frame or a horizontal band of one (see [`set_first_row`]). Depth
/// 0 is nearest; [`clear`] sets every entry to [`ZBuffer::FAR`] (`u16::MAX`).
///
/// ```
/// use zraster::ZBuffer;
/// let mut depth = [0u16; 32 * 8];
/// let mut zbuf = ZBuffer::new(&mut depth, 32, 8)?;
/// zbuf.clear();
/// assert_eq!(zbuf.depth(31, 7), Some(u16::MAX));
/// assert_eq!(zbuf.depth(32, 7), None);
/// # Ok::<(), zraster::Error>(())
/// ```
///
/// [`set_first_row`]: ZBuffer::set_first_row
/// [`clear`]: ZBuffer::clear
#[derive(Debug)]
pub struct ZBuffer<'a> {
    buf: Rows<'a, u16>,
    test: DepthTest,
    write: bool,
}

impl<'a> ZBuffer<'a> {
    /// The farthest depth and the clear value.
    pub const FAR: u16 = u16::MAX;

    /// A Z-buffer of `width × rows` entries covering screen rows `0..rows`.
    ///
    /// Errors: [`Error::ZeroSize`] for a zero dimension, [`Error::TooLarge`] above
    /// [`MAX_DIMENSION`](crate::MAX_DIMENSION), [`Error::BufferTooSmall`] when `data` is shorter than
    /// `width × rows`. A longer slice is fine; only its first `width × rows` entries are used.
    pub fn new(data: &'a mut [u16], width: u32, rows: u32) -> Result<Self, Error> {
        Ok(ZBuffer {
            buf: Rows::new(data, width, rows)?,
            test: DepthTest::Less,
            write: true,
        })
    }

    /// A Z-buffer covering screen rows `first_row .. first_row + rows` (a band).
    ///
    /// Errors: as [`new`](ZBuffer::new), and [`Error::OutOfRange`] when the last row
    /// would lie beyond `i32::MAX`.
    pub fn new_band(
        data: &'a mut [u16],
        width: u32,
        rows: u32,
        first_row: i32,
    ) -> Result<Self, Error> {
        let mut z = Self::new(data, width, rows)?;
        z.set_first_row(first_row)?;
        Ok(z)
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        u32::from(self.buf.width)
    }

    /// Number of rows held.
    pub fn rows(&self) -> u32 {
        u32::from(self.buf.rows)
    }

    /// The first screen row covered.
    pub fn first_row(&self) -> i32 {
        self.buf.first_row
    }

    /// Move the band: the buffer now covers rows `first_row .. first_row + rows`.
    /// The contents are kept; call [`clear`](ZBuffer::clear) before drawing the new band.
    ///
    /// Errors: [`Error::OutOfRange`] when the last row would lie beyond `i32::MAX`.
    pub fn set_first_row(&mut self, first_row: i32) -> Result<(), Error> {
        self.buf.set_first_row(first_row)
    }

    /// The depth comparison in use.
    pub fn test(&self) -> DepthTest {
        self.test
    }

    /// Set the depth comparison.
    pub fn set_test(&mut self, test: DepthTest) {
        self.test = test;
    }

    /// Whether passing fragments write their depth.
    pub fn write_enabled(&self) -> bool {
        self.write
    }

    /// Turn depth writes on or off (off: test only, as for decals or hidden-line overlays).
    pub fn set_write(&mut self, write: bool) {
        self.write = write;
    }

    /// Set every entry to [`ZBuffer::FAR`].
    pub fn clear(&mut self) {
        crate::num::fill(self.buf.data, Self::FAR);
    }

    /// Set every entry to `depth`.
    pub fn fill(&mut self, depth: u16) {
        crate::num::fill(self.buf.data, depth);
    }

    /// The stored depth at screen pixel (x, y), or `None` outside the rows held.
    pub fn depth(&self, x: i32, y: i32) -> Option<u16> {
        self.buf.get(x, y)
    }

    /// The entries, row by row (row 0 is screen row [`first_row`](ZBuffer::first_row)).
    pub fn as_slice(&self) -> &[u16] {
        self.buf.data
    }

    /// The part of screen row `y` from column `x0` to `x1` (exclusive); `None` when any of
    /// it lies outside the buffer.
    #[inline]
    pub(crate) fn span_mut(&mut self, y: i32, x0: i32, x1: i32) -> Option<&mut [u16]> {
        self.buf.span_mut(y, x0, x1)
    }

    /// (width, rows, first row): two buffers with the same geometry share indices.
    #[inline]
    pub(crate) fn geometry(&self) -> (u16, u16, i32) {
        self.buf.geometry()
    }

    /// The entries, mutable.
    #[inline]
    pub(crate) fn data_mut(&mut self) -> &mut [u16] {
        self.buf.data
    }

    /// Screen rows covered, as a half-open range.
    pub(crate) fn row_range(&self) -> (i32, i32) {
        self.buf.row_range()
    }
}
