//! Render state fixed at compile time: what a firmware that draws one way can tell the
//! compiler, so that only that way is built into it.
//!
//! A [`Renderer`](super::Renderer) reads its shading from
//! [`RenderOptions`](super::RenderOptions) and its depth test from the
//! [`ZBuffer`](crate::ZBuffer) at run time, and so carries a pixel loop for every depth
//! test and a path for every shading. [`Renderer::with_state`](super::Renderer::with_state)
//! fixes either or both with a type: the choices become constants, and the paths they
//! rule out are not compiled at all.
//!
//! ```
//! use zraster::state::{LambertLess, RenderState};
//! use zraster::{shade::Shading, DepthTest};
//! assert_eq!(LambertLess::DEPTH_TEST, Some(DepthTest::Less));
//! assert_eq!(LambertLess::SHADING, Some(Shading::Lambert));
//!
//! // Your own: flat colours, the depth test `LessEqual`.
//! struct FlatLessEqual;
//! impl RenderState for FlatLessEqual {
//!     const DEPTH_TEST: Option<DepthTest> = Some(DepthTest::LessEqual);
//!     const SHADING: Option<Shading> = Some(Shading::Flat);
//! }
//! ```
//!
//! # Binned bands only
//!
//! A banded draw ([`Bands`](crate::Bands)) sorts the visible triangles by band first
//! when it can (a vertex cache, a triangle list, flat or Lambert shading, an undithered
//! colour type, enough bins: see [`Unbinned`]); when it cannot, every band walks the
//! whole mesh through a second drawing path. A firmware that always bins can leave
//! that path out: [`Binned`] wraps a state and sets [`RenderState::BINNED_BANDS`], and
//! a banded draw that cannot bin then returns the error [`Unbinned::error`] names
//! (before any band is drawn) instead of drawing unbinned.
//! [`Renderer::binning`](crate::Renderer::binning) says which reason it was.
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
//! use zraster::state::{Binned, LambertLess, RenderState};
//! use zraster::{camera::{Camera, Viewport}, math::{radians, Vec3}, mesh::CUBE, shade::Shading};
//! use zraster::{BandBuffers, Bands, Binning, ColorBuffer, DrawError, RenderOptions, Renderer, Unbinned};
//!
//! assert!(Binned::<LambertLess>::BINNED_BANDS);
//! assert_eq!(Binned::<LambertLess>::SHADING, Some(Shading::Lambert));
//! let xf = Camera::look_at(Vec3::new(2.0, 1.5, 3.0), Vec3::new(0.5, 0.5, 0.5), Vec3::Y)?
//!     .perspective(radians(45.0), 0.1, 10.0, Viewport::new(32, 32)?)?;
//! let options = RenderOptions { shading: Shading::Lambert, ..Default::default() };
//! // No vertex cache (and polygon faces): this renderer cannot bin.
//! let mut r = Renderer::new(&CUBE, &xf, options)?.with_state::<Binned<LambertLess>>()?;
//! let (mut color, mut depth, mut shown) = ([Rgb565::BLACK; 32 * 8], [0u16; 32 * 8], [Rgb565::BLACK; 32 * 32]);
//! let mut display = ColorBuffer::new(&mut shown, 32, 32)?;
//! let mut buffers = BandBuffers::new(&mut color, &mut depth, 32, 8, 32, &mut [])?;
//! let result = r.draw(&mut Bands::new(&mut display, &mut buffers, Rgb565::BLACK));
//! assert_eq!(result, Err(DrawError::Input(Unbinned::Polygons.error())));
//! assert_eq!(r.binning(), Binning::Off(Unbinned::Polygons));
//! # Ok::<(), zraster::Error>(())
//! ```

use core::marker::PhantomData;

use crate::shade::Shading;
use crate::DepthTest;
#[cfg(doc)]
use crate::Unbinned;

/// Render state: each constant is a choice fixed at compile time, or `None` to decide
/// at run time. See the [module docs](self).
pub trait RenderState {
    /// The depth test, replacing the Z-buffer's own ([`ZBuffer::test`](crate::ZBuffer::test)).
    const DEPTH_TEST: Option<DepthTest> = None;
    /// The shading, which [`RenderOptions::shading`](super::RenderOptions::shading) must
    /// agree with.
    const SHADING: Option<Shading> = None;
    /// Whether a draw into [`Bands`](crate::Bands) must bin its triangles: one that
    /// cannot returns [`Unbinned::error`] instead of walking the whole mesh in every
    /// band, so that path is not built in. See [`Binned`].
    const BINNED_BANDS: bool = false;

    /// The depth test to use, given the Z-buffer's.
    #[doc(hidden)]
    #[inline(always)]
    fn depth_test(runtime: DepthTest) -> DepthTest {
        match Self::DEPTH_TEST {
            Some(t) => t,
            None => runtime,
        }
    }

    /// The shading to use, given the options'.
    #[doc(hidden)]
    #[inline(always)]
    fn shading(runtime: Shading) -> Shading {
        match Self::SHADING {
            Some(s) => s,
            None => runtime,
        }
    }
}

/// Everything decided at run time (the default): every depth test and shading built in.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Dynamic;
impl RenderState for Dynamic {}

/// Flat colours, the depth test `Less`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FlatLess;
impl RenderState for FlatLess {
    const DEPTH_TEST: Option<DepthTest> = Some(DepthTest::Less);
    const SHADING: Option<Shading> = Some(Shading::Flat);
}

/// Lambert (flat) lighting, the depth test `Less`: what a rotating model usually wants.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct LambertLess;
impl RenderState for LambertLess {
    const DEPTH_TEST: Option<DepthTest> = Some(DepthTest::Less);
    const SHADING: Option<Shading> = Some(Shading::Lambert);
}

/// Gouraud lighting, the depth test `Less`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct GouraudLess;
impl RenderState for GouraudLess {
    const DEPTH_TEST: Option<DepthTest> = Some(DepthTest::Less);
    const SHADING: Option<Shading> = Some(Shading::Gouraud);
}

/// The state `S`, with banded draws that bin or fail ([`RenderState::BINNED_BANDS`]):
/// see [Binned bands only](self#binned-bands-only).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Binned<S>(PhantomData<S>);
impl<S: RenderState> RenderState for Binned<S> {
    const DEPTH_TEST: Option<DepthTest> = S::DEPTH_TEST;
    const SHADING: Option<Shading> = S::SHADING;
    const BINNED_BANDS: bool = true;
}
