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

use crate::shade::Shading;
use crate::DepthTest;

/// Render state: each constant is a choice fixed at compile time, or `None` to decide
/// at run time. See the [module docs](self).
pub trait RenderState {
    /// The depth test, replacing the Z-buffer's own ([`ZBuffer::test`](crate::ZBuffer::test)).
    const DEPTH_TEST: Option<DepthTest> = None;
    /// The shading, which [`RenderOptions::shading`](super::RenderOptions::shading) must
    /// agree with.
    const SHADING: Option<Shading> = None;

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
