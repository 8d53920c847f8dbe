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

    /// This transform with its near and far planes moved to enclose a box (its lowest
    /// and highest corners in model space, as [`Mesh::bounds`](crate::mesh::Mesh::bounds)
    /// gives them): the box's nearest and farthest corners in eye space, so the depths
    /// the mesh covers use most of the 16-bit range instead of a sliver of a fixed
    /// near…far (which is where z-fighting comes from). x and y are unchanged. Near
    /// never goes below `min_near`: a mesh reaching closer than that is clipped there,
    /// as with any near plane; a mesh wholly behind `min_near` keeps planes that show
    /// nothing of it. Eight corners transformed: cheap enough for every frame.
    ///
    /// Works for perspective and orthographic projections (as built by
    /// [`perspective`](Transform::perspective) and [`Mat4::orthographic`]); other
    /// projection matrices, a `min_near` that is not positive or corners in the wrong
    /// order are an [`Error::InvalidParameter`].
    ///
    /// ```
    /// use zraster::{camera::{Transform, Viewport}, math::Vec3, mesh::CUBE};
    /// let vp = Viewport::new(64, 48)?;
    /// let xf = Transform::perspective(Vec3::new(0.5, 0.5, 4.0), Vec3::new(0.5, 0.5, 0.5), 45.0, 0.1, 100.0, vp)?;
    /// let (lo, hi) = CUBE.bounds().unwrap();
    /// let fitted = xf.fit_depth(lo, hi, 0.1)?;
    /// // The cube's front face now lies at depth 0 and its back face at 1.
    /// let depth = |p: Vec3| { let c = fitted.model_view_projection().transform_point(p); (c[2] / c[3] + 1.0) / 2.0 };
    /// assert!(depth(Vec3::new(0.5, 0.5, 1.0)) < 0.01 && depth(Vec3::new(0.5, 0.5, 0.0)) > 0.99);
    /// # Ok::<(), zraster::Error>(())
    /// ```
    pub fn fit_depth(mut self, lo: Vec3, hi: Vec3, min_near: f32) -> Result<Transform, Error> {
        if !(lo.is_finite() && hi.is_finite() && min_near.is_finite()) {
            return Err(Error::NotFinite);
        }
        if !(min_near > 0.0 && lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z) {
            return Err(Error::InvalidParameter(
                "need min_near > 0 and the lowest corner first",
            ));
        }
        // Eye space looks down −z: a corner's distance is −z.
        let mv = self.view * self.model;
        let (mut nearest, mut farthest) = (f32::INFINITY, f32::NEG_INFINITY);
        for k in 0..8 {
            let pick = |bit: u32, a: f32, b: f32| if k & bit == 0 { a } else { b };
            let corner = Vec3::new(
                pick(1, lo.x, hi.x),
                pick(2, lo.y, hi.y),
                pick(4, lo.z, hi.z),
            );
            let d = -mv.transform_point(corner)[2];
            nearest = nearest.min(d);
            farthest = farthest.max(d);
        }
        // A little margin for rounding: points on the box must not be clipped.
        let margin = (farthest - nearest).abs() * 1e-4 + farthest.abs() * 1e-6;
        let near = (nearest - margin).max(min_near);
        let far = farthest + margin;
        // Wholly nearer than min_near: any far plane beyond near shows nothing of it.
        let far = if far > near { far } else { near * 2.0 };
        if !(near.is_finite() && far.is_finite()) {
            return Err(Error::NotFinite);
        }
        let p = &mut self.projection.m;
        let d = near - far;
        if p[3] == [0.0, 0.0, -1.0, 0.0] {
            p[2][2] = (far + near) / d;
            p[2][3] = 2.0 * far * near / d;
        } else if p[3] == [0.0, 0.0, 0.0, 1.0] && p[2][0] == 0.0 && p[2][1] == 0.0 {
            p[2][2] = 2.0 / d;
            p[2][3] = (far + near) / d;
        } else {
            return Err(Error::InvalidParameter(
                "fit_depth needs a perspective or orthographic projection",
            ));
        }
        Ok(self)
    }

    /// Model to clip space.
    pub fn model_view_projection(&self) -> Mat4 {
        self.projection * self.view * self.model
    }
}
