//! Caller memory for drawing a frame band by band ([`BandBuffers`]), and the display
//! drawn that way ([`Bands`]), which `band.rs` draws into.

use embedded_graphics::{pixelcolor::PixelColor, prelude::DrawTarget};

use super::{ColorBuffer, ZBuffer};
use crate::num::kernel::{CARRY, STATE_WORDS};
use crate::{Error, MAX_DIMENSION};

/// Caller memory for banded drawing: a colour band, a depth band and (optionally) bins.
#[derive(Debug)]
pub struct BandBuffers<'a, C> {
    pub(crate) color: &'a mut [C],
    pub(crate) depth: &'a mut [u16],
    pub(crate) width: u32,
    pub(crate) rows: u32,
    pub(crate) height: u32,
    /// The bin chains (their layout: `END` in `band.rs`).
    pub(crate) bins: &'a mut [u16],
    /// Where the set-ups of faces reaching the band below are kept for it (see
    /// [`with_carry`](BandBuffers::with_carry)); may be empty.
    pub(crate) carry: &'a mut [u32],
}

impl<'a, C: PixelColor> BandBuffers<'a, C> {
    /// Band buffers for a `width × height` screen drawn `rows` lines at a time.
    /// `color` and `depth` need `width × rows` entries; `bins` may be empty (every band
    /// then walks every triangle) or hold at least
    /// [`bins_needed`](BandBuffers::bins_needed) entries.
    pub fn new(
        color: &'a mut [C],
        depth: &'a mut [u16],
        width: u32,
        rows: u32,
        height: u32,
        bins: &'a mut [u16],
    ) -> Result<Self, Error> {
        if width == 0 || rows == 0 || height == 0 {
            return Err(Error::ZeroSize);
        }
        if width > MAX_DIMENSION || height > MAX_DIMENSION {
            return Err(Error::TooLarge);
        }
        let rows = rows.min(height);
        let needed = (width * rows) as usize;
        for got in [color.len(), depth.len()] {
            if got < needed {
                return Err(Error::BufferTooSmall { needed, got });
            }
        }
        Ok(BandBuffers {
            color,
            depth,
            width,
            rows,
            height,
            bins,
            carry: &mut [],
        })
    }

    /// The same, keeping in `carry` the set-ups of the triangles that reach from one
    /// band into the next, so that the next band goes on drawing them rather than set
    /// them up again: for [`carry_needed`](BandBuffers::carry_needed)`(n)` words, up to
    /// `n` such triangles a band (at most 64; those beyond are set up again, as they
    /// all are without it). The picture is the same either way. Used by the bands'
    /// assembly loops on ARMv7E-M (Cortex-M4, M7) and ARMv6-M (Cortex-M0+, RP2040) for
    /// a cached triangle mesh drawn with flat or Lambert shading, the `Less` depth test
    /// and a two-byte colour; elsewhere the scratch is left unused.
    pub fn with_carry(self, carry: &'a mut [u32]) -> Self {
        BandBuffers { carry, ..self }
    }

    /// The number of bands.
    pub fn bands(&self) -> u32 {
        self.height.div_ceil(self.rows)
    }

    /// Bin entries needed for a mesh of `triangles` triangles: one per triangle, four
    /// per band and two more. (Meshes of more than 65,534 triangles are drawn without
    /// bins.)
    pub const fn bins_needed(triangles: usize, height: u32, rows: u32) -> usize {
        bins_for(triangles, height, rows)
    }

    /// Carry words ([`with_carry`](BandBuffers::with_carry)) for the set-ups of up to
    /// `triangles` triangles a band reaching into the next (at most 64 count): two
    /// halves of 21 words a triangle, 168 bytes a triangle in all.
    pub const fn carry_needed(triangles: usize) -> usize {
        let n = if triangles < CARRY { triangles } else { CARRY };
        2 * n * STATE_WORDS
    }
}

/// Bin entries for a mesh of `triangles` triangles drawn in bands of `rows` of a
/// `height`-row screen: one a triangle, and a head and a tail for each of the
/// 2 · bands + 1 chains (see the band loop, `band.rs`). Saturates rather than overflow.
pub(crate) const fn bins_for(triangles: usize, height: u32, rows: u32) -> usize {
    let rows = if rows == 0 { 1 } else { rows };
    let bands = height.div_ceil(rows) as usize; // < 2³²
    triangles.saturating_add(2 * (2 * bands + 1))
}

/// A display drawn band by band: [`Renderer::draw`] (or [`Scene::draw`], for several
/// meshes) draws each band of rows into the
/// [`BandBuffers`], cleared to the background, and sends it to the display with one
/// `fill_contiguous`. The picture, its depths and the stats are exactly those of a
/// whole [`Frame`](super::Frame), in a fraction of its RAM.
///
/// With a vertex cache ([`Renderer::with_cache`]), a triangle mesh, flat or Lambert
/// shading and enough bins ([`BandBuffers::bins_needed`]), the visible triangles are
/// sorted by band first, so each band only visits the triangles that reach it; without
/// them every band walks the whole mesh (or, under a binned-only state,
/// [`Binned`](crate::state::Binned), the draw fails with the reason).
///
/// ```
/// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::Rgb565, prelude::*};
/// use zraster::camera::{Camera, Viewport};
/// use zraster::{math::{radians, Vec3}, mesh::CUBE, BandBuffers, Bands, RenderOptions, Renderer};
///
/// let mut display = MockDisplay::<Rgb565>::new(); // 64 × 64
/// // Bands of 8 rows: 64 × 8 colours and depths instead of 64 × 64.
/// let (mut color, mut depth) = ([Rgb565::BLACK; 64 * 8], [0u16; 64 * 8]);
/// let mut buffers = BandBuffers::new(&mut color, &mut depth, 64, 8, 64, &mut [])?;
/// assert_eq!(buffers.bands(), 8);
/// let xf = Camera::look_at(Vec3::new(2.0, 1.5, 3.0), Vec3::new(0.5, 0.5, 0.5), Vec3::Y)?
///     .perspective(radians(45.0), 0.1, 10.0, Viewport::new(64, 64)?)?;
/// let mut renderer = Renderer::new(&CUBE, &xf, RenderOptions::default())?;
/// let mut rows_seen = 0;
/// renderer
///     .draw(&mut Bands::new(&mut display, &mut buffers, Rgb565::BLACK).after_band(|band, _depth| {
///         // Each band once drawn, before it is sent: an overlay could be drawn here.
///         rows_seen += band.rows();
///     }))
///     .unwrap();
/// assert_eq!(rows_seen, 64);
/// assert_eq!(display.get_pixel(Point::new(32, 32)), Some(Rgb565::new(0, 0, 31))); // the front face
/// # Ok::<(), zraster::Error>(())
/// ```
///
/// [`Renderer::draw`]: crate::Renderer::draw
/// [`Scene::draw`]: crate::scene::Scene::draw
/// [`Renderer::with_cache`]: crate::Renderer::with_cache
pub struct Bands<'a, 'b, D: DrawTarget, F = ()> {
    pub(crate) display: &'a mut D,
    pub(crate) buffers: &'a mut BandBuffers<'b, D::Color>,
    pub(crate) background: D::Color,
    pub(crate) after: F,
}

impl<'a, 'b, D: DrawTarget> Bands<'a, 'b, D> {
    /// `display` drawn in the bands of `buffers`, each cleared to `background` first.
    pub fn new(
        display: &'a mut D,
        buffers: &'a mut BandBuffers<'b, D::Color>,
        background: D::Color,
    ) -> Self {
        Bands {
            display,
            buffers,
            background,
            after: (),
        }
    }
}

impl<'a, 'b, D: DrawTarget, F> Bands<'a, 'b, D, F> {
    /// The same, calling `after(band, depth)` for each band once it is drawn and before
    /// it is sent: to draw an overlay into it (text, a cursor: anything embedded-graphics
    /// draws), or to look at its depths. Both cover the band's screen rows
    /// ([`ColorBuffer::first_row`], [`ColorBuffer::rows`]).
    pub fn after_band<G>(self, after: G) -> Bands<'a, 'b, D, G>
    where
        G: FnMut(&mut ColorBuffer<'_, D::Color>, &ZBuffer<'_>),
    {
        Bands {
            display: self.display,
            buffers: self.buffers,
            background: self.background,
            after,
        }
    }
}

impl<D: DrawTarget, F> core::fmt::Debug for Bands<'_, '_, D, F>
where
    D::Color: core::fmt::Debug,
{
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Bands")
            .field("buffers", &self.buffers)
            .field("background", &self.background)
            .finish_non_exhaustive()
    }
}

/// What [`Bands`] calls after drawing each band: nothing (`()`), or the closure given
/// to [`Bands::after_band`]. Sealed: implemented for those alone.
pub trait AfterBand<C>: AfterBandSealed<C> {
    /// Whether it may draw into the band (so a band left as cleared by the one before
    /// must be cleared again).
    #[doc(hidden)]
    const DRAWS: bool;
    /// Called for each band once it is drawn.
    #[doc(hidden)]
    fn after(&mut self, band: &mut ColorBuffer<'_, C>, depth: &ZBuffer<'_>);
}

mod sealed {
    pub trait AfterBandSealed<C> {}
}
use sealed::AfterBandSealed;

impl<C> AfterBandSealed<C> for () {}

impl<C> AfterBand<C> for () {
    const DRAWS: bool = false;
    #[inline(always)]
    fn after(&mut self, _: &mut ColorBuffer<'_, C>, _: &ZBuffer<'_>) {}
}

impl<C, F> AfterBandSealed<C> for F where F: FnMut(&mut ColorBuffer<'_, C>, &ZBuffer<'_>) {}

impl<C, F> AfterBand<C> for F
where
    F: FnMut(&mut ColorBuffer<'_, C>, &ZBuffer<'_>),
{
    const DRAWS: bool = true;
    #[inline(always)]
    fn after(&mut self, band: &mut ColorBuffer<'_, C>, depth: &ZBuffer<'_>) {
        self(band, depth)
    }
}
