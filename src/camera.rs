//! The camera: where a mesh is placed (model, view and projection matrices) and the
//! screen rectangle it is drawn into.

use crate::math::{Mat4, Vec3};
use crate::{Error, MAX_DIMENSION};

/// The screen rectangle that normalised device coordinates map to.
///
/// NDC x = −1 is the left edge, y = +1 the top edge (row 0); window depth
/// `(z_ndc + 1) / 2` maps to 0..=65535. In banded rendering the viewport stays the
/// whole screen while the targets cover one band.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Viewport {
    pub(crate) x: i32,
    pub(crate) y: i32,
    pub(crate) width: u32,
    pub(crate) height: u32,
}

impl Viewport {
    /// A viewport of `width × height` pixels at (0, 0).
    pub fn new(width: u32, height: u32) -> Result<Viewport, Error> {
        Viewport::at(0, 0, width, height)
    }

    /// A viewport of `width × height` pixels with its top-left corner at (x, y).
    /// Errors: zero or over [`MAX_DIMENSION`] sizes, corners beyond ±8192.
    pub fn at(x: i32, y: i32, width: u32, height: u32) -> Result<Viewport, Error> {
        if width == 0 || height == 0 {
            return Err(Error::ZeroSize);
        }
        let lim = MAX_DIMENSION;
        if width > MAX_DIMENSION
            || height > MAX_DIMENSION
            || x.unsigned_abs() > lim
            || y.unsigned_abs() > lim
        {
            return Err(Error::TooLarge);
        }
        Ok(Viewport {
            x,
            y,
            width,
            height,
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Width / height.
    pub fn aspect(&self) -> f32 {
        self.width as f32 / self.height as f32
    }
}

/// Everything that places a mesh on the screen: model, view and projection matrices
/// and the viewport.
///
/// The model matrix should be a rotation, translation and uniform scale (lighting
/// turns the light into model space with its transpose); view and projection are any
/// `gluLookAt`/`gluPerspective`/`glOrtho`-style matrices.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transform {
    /// Model to world.
    pub model: Mat4,
    /// World to eye (the camera looks down −Z).
    pub view: Mat4,
    /// Eye to clip space.
    pub projection: Mat4,
    /// Normalised device coordinates to screen pixels.
    pub viewport: Viewport,
}

impl Transform {
    /// A camera at `eye` looking at `target` (+Y up) with a `fovy_deg` degree vertical
    /// field of view and clip planes at `near` and `far`, over `viewport`; the model
    /// matrix is the identity.
    ///
    /// Errors: [`Error::InvalidParameter`] unless `0 < near < far` and `0 < fovy < 180`,
    /// [`Error::NotFinite`] for NaN or infinite inputs.
    pub fn perspective(
        eye: Vec3,
        target: Vec3,
        fovy_deg: f32,
        near: f32,
        far: f32,
        viewport: Viewport,
    ) -> Result<Transform, Error> {
        if !(eye.is_finite()
            && target.is_finite()
            && fovy_deg.is_finite()
            && near.is_finite()
            && far.is_finite())
        {
            return Err(Error::NotFinite);
        }
        if !(near > 0.0 && far > near) {
            return Err(Error::InvalidParameter("need 0 < near < far"));
        }
        if !(fovy_deg > 0.0 && fovy_deg < 180.0) {
            return Err(Error::InvalidParameter("need 0 < fov < 180 degrees"));
        }
        let projection =
            Mat4::perspective(crate::math::radians(fovy_deg), viewport.aspect(), near, far);
        let view = Mat4::look_at(eye, target, Vec3::new(0.0, 1.0, 0.0));
        Ok(Transform {
            model: Mat4::IDENTITY,
            view,
            projection,
            viewport,
        })
    }

    /// The same transform with another model matrix.
    pub fn with_model(mut self, model: Mat4) -> Transform {
        self.model = model;
        self
    }

    /// Model to clip space.
    pub fn model_view_projection(&self) -> Mat4 {
        self.projection * self.view * self.model
    }
}
