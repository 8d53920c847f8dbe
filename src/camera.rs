//! The camera: where a mesh is placed (model, view and projection matrices) and the
//! screen rectangle it is drawn into.
//!
//! Angles are in radians here as everywhere in zraster; [`radians`](crate::math::radians)
//! turns degrees into radians (and an embedded-graphics `Angle` gives its own with
//! `to_radians()`).

use crate::math::{Mat4, Vec3};
use crate::{Error, MAX_DIMENSION};
use embedded_graphics::{
    geometry::{Point, Size},
    primitives::Rectangle,
};

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

/// The viewport covering a rectangle of the display, such as its `bounding_box()`.
///
/// Errors as [`Viewport::at`]: a zero or too large size, a corner beyond ±8192.
impl TryFrom<Rectangle> for Viewport {
    type Error = Error;

    fn try_from(r: Rectangle) -> Result<Viewport, Error> {
        Viewport::at(r.top_left.x, r.top_left.y, r.size.width, r.size.height)
    }
}

/// The viewport of a display's `size()`, at (0, 0).
///
/// Errors as [`Viewport::new`].
impl TryFrom<Size> for Viewport {
    type Error = Error;

    fn try_from(s: Size) -> Result<Viewport, Error> {
        Viewport::new(s.width, s.height)
    }
}

/// The screen rectangle of a viewport.
impl From<Viewport> for Rectangle {
    fn from(vp: Viewport) -> Rectangle {
        Rectangle::new(Point::new(vp.x, vp.y), Size::new(vp.width, vp.height))
    }
}

/// Everything that places a mesh on the screen: model, view and projection matrices
/// and the viewport.
///
/// Build one from where the eye is and what it looks at, then a lens:
/// [`Camera::look_at`] gives a [`LookAt`], and [`LookAt::perspective`] or
/// [`LookAt::orthographic`] the camera. Angles are in radians, as everywhere in zraster
/// ([`radians`](crate::math::radians) converts degrees).
///
/// ```
/// use zraster::camera::{Camera, Viewport};
/// use zraster::math::{radians, Vec3};
///
/// let vp = Viewport::new(160, 120)?;
/// let eye = Vec3::new(2.0, 1.5, 3.0);
/// let camera = Camera::look_at(eye, Vec3::default(), Vec3::Y)?.perspective(radians(45.0), 0.1, 10.0, vp)?;
/// // Looking straight down with +Y up does not say which way is up on the screen.
/// let top_down = Camera::look_at(Vec3::new(0.0, 5.0, 0.0), Vec3::default(), Vec3::Y);
/// assert_eq!(top_down.err(), Some(zraster::Error::DegenerateView));
/// // +Z as up works from there.
/// let top_down = Camera::look_at(Vec3::new(0.0, 5.0, 0.0), Vec3::default(), -Vec3::Z)?;
/// let plan = top_down.orthographic(4.0, 1.0, 10.0, vp)?; // 4 units tall, 4 × 160/120 wide
/// # let _ = (camera, plan);
/// # Ok::<(), zraster::Error>(())
/// ```
///
/// The model matrix should be a rotation, translation and uniform scale (lighting
/// turns the light into model space with its transpose); view and projection may also
/// be set directly to any `gluLookAt`/`gluPerspective`/`glOrtho`-style matrices.
///
/// Named `Camera` rather than `Transform`, which the embedded-graphics prelude exports.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Model to world.
    pub model: Mat4,
    /// World to eye (the camera looks down −Z).
    pub view: Mat4,
    /// Eye to clip space.
    pub projection: Mat4,
    /// Normalised device coordinates to screen pixels.
    pub viewport: Viewport,
}

/// The old name of [`Camera`], kept so that existing code compiles. It is not exported
/// at the crate root: `embedded_graphics::prelude::Transform` has the name there.
pub type Transform = Camera;

/// Where a camera stands and what it looks at (a view matrix known to be well defined),
/// waiting for its lens: [`perspective`](LookAt::perspective) or
/// [`orthographic`](LookAt::orthographic). Made by [`Camera::look_at`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LookAt {
    view: Mat4,
}

/// The sine of the smallest angle between the line of sight and the up vector that
/// [`Camera::look_at`] accepts (about 0.06°): below it, which way is up on the screen
/// depends on rounding.
const MIN_UP_SINE: f32 = 1e-3;

impl LookAt {
    /// The view matrix (world to eye; the camera looks down −Z).
    pub fn view(&self) -> Mat4 {
        self.view
    }

    /// A perspective camera: `fovy` is the vertical field of view in **radians**,
    /// `near` and `far` the distances of the clip planes (gluPerspective); the model
    /// matrix is the identity.
    ///
    /// Errors: [`Error::NotFinite`] for NaN or infinite inputs,
    /// [`Error::InvalidParameter`] unless `0 < near < far` and `0 < fovy < π`.
    pub fn perspective(
        self,
        fovy: f32,
        near: f32,
        far: f32,
        viewport: Viewport,
    ) -> Result<Camera, Error> {
        if !(fovy.is_finite() && near.is_finite() && far.is_finite()) {
            return Err(Error::NotFinite);
        }
        check_planes(near, far)?;
        if !(fovy > 0.0 && fovy < core::f32::consts::PI) {
            return Err(Error::InvalidParameter("need 0 < fov < π radians"));
        }
        Ok(self.with_projection(
            Mat4::perspective(fovy, viewport.aspect(), near, far),
            viewport,
        ))
    }

    /// An orthographic (parallel) camera: the view volume is `height` world units tall,
    /// `height` × the viewport's width / height wide, centred on the line of sight, from
    /// `near` to `far` along it (glOrtho); the model matrix is the identity. Sizes on the
    /// screen do not shrink with distance, as in plans and elevations.
    ///
    /// Errors: [`Error::NotFinite`] for NaN or infinite inputs,
    /// [`Error::InvalidParameter`] unless `height > 0` and `near < far` (near may be
    /// zero or negative: behind the eye).
    pub fn orthographic(
        self,
        height: f32,
        near: f32,
        far: f32,
        viewport: Viewport,
    ) -> Result<Camera, Error> {
        if !(height.is_finite() && near.is_finite() && far.is_finite()) {
            return Err(Error::NotFinite);
        }
        if !(height > 0.0 && near < far) {
            return Err(Error::InvalidParameter("need height > 0 and near < far"));
        }
        let (h, w) = (height * 0.5, height * 0.5 * viewport.aspect());
        let projection = Mat4::orthographic(-w, w, -h, h, near, far);
        if !projection.is_finite() {
            // A box too thin (or wide) for f32: 2 / (far − near) overflows.
            return Err(Error::InvalidParameter("view volume too thin"));
        }
        Ok(self.with_projection(projection, viewport))
    }

    fn with_projection(self, projection: Mat4, viewport: Viewport) -> Camera {
        Camera {
            model: Mat4::IDENTITY,
            view: self.view,
            projection,
            viewport,
        }
    }
}

/// `0 < near < far`, for perspective projections.
fn check_planes(near: f32, far: f32) -> Result<(), Error> {
    if near > 0.0 && far > near {
        Ok(())
    } else {
        Err(Error::InvalidParameter("need 0 < near < far"))
    }
}

impl Camera {
    /// An eye at `eye` looking at `target`, with `up` pointing up on the screen (it need
    /// not be a unit vector nor at right angles to the line of sight; gluLookAt).
    /// Then give it a lens: [`LookAt::perspective`] or [`LookAt::orthographic`].
    ///
    /// Errors: [`Error::NotFinite`] for NaN or infinite inputs, and
    /// [`Error::DegenerateView`] when the view has no direction (`eye == target`) or no
    /// up (`up` is zero or within about 0.06° of the line of sight, as +Y is when
    /// looking straight down).
    pub fn look_at(eye: Vec3, target: Vec3, up: Vec3) -> Result<LookAt, Error> {
        if !(eye.is_finite() && target.is_finite() && up.is_finite()) {
            return Err(Error::NotFinite);
        }
        let forward = (target - eye).normalize();
        let side = forward.cross(up.normalize());
        // Zero (and overflowing) vectors normalise to zero: both degenerate cases end here.
        if side.length() < MIN_UP_SINE {
            return Err(Error::DegenerateView);
        }
        let view = Mat4::look_at(eye, target, up);
        if !view.is_finite() {
            return Err(Error::NotFinite); // eye · axis overflows f32
        }
        Ok(LookAt { view })
    }

    /// The old form, kept for existing callers: an eye at `eye` looking at `target` with
    /// +Y up and a vertical field of view in **degrees**. It is
    /// `Camera::look_at(eye, target, Vec3::Y)?.perspective(radians(fovy_deg), near, far, viewport)`;
    /// use that, whose angle is in radians like every other angle in zraster.
    #[doc(hidden)]
    pub fn perspective(
        eye: Vec3,
        target: Vec3,
        fovy_deg: f32,
        near: f32,
        far: f32,
        viewport: Viewport,
    ) -> Result<Camera, Error> {
        if !(eye.is_finite()
            && target.is_finite()
            && fovy_deg.is_finite()
            && near.is_finite()
            && far.is_finite())
        {
            return Err(Error::NotFinite);
        }
        check_planes(near, far)?;
        if !(fovy_deg > 0.0 && fovy_deg < 180.0) {
            return Err(Error::InvalidParameter("need 0 < fov < 180 degrees"));
        }
        Camera::look_at(eye, target, Vec3::Y)?.perspective(
            crate::math::radians(fovy_deg),
            near,
            far,
            viewport,
        )
    }

    /// The same camera with another model matrix.
    pub fn with_model(mut self, model: Mat4) -> Camera {
        self.model = model;
        self
    }

    /// This camera with its near and far planes moved to enclose a box (its lowest
    /// and highest corners in model space, as [`Mesh::bounds`](crate::mesh::Mesh::bounds)
    /// gives them): the box's nearest and farthest corners in eye space, so the depths
    /// the mesh covers use most of the 16-bit range instead of a sliver of a fixed
    /// near…far (which is where z-fighting comes from). x and y are unchanged. Near
    /// never goes below `min_near`: a mesh reaching closer than that is clipped there,
    /// as with any near plane; a mesh wholly behind `min_near` keeps planes that show
    /// nothing of it. Eight corners transformed: cheap enough for every frame.
    ///
    /// Works for perspective and orthographic projections (as built by
    /// [`LookAt::perspective`], [`LookAt::orthographic`] and [`Mat4::orthographic`]); other
    /// projection matrices, a `min_near` that is not positive or corners in the wrong
    /// order are an [`Error::InvalidParameter`].
    ///
    /// ```
    /// use zraster::{camera::{Camera, Viewport}, math::{radians, Vec3}, mesh::CUBE};
    /// let vp = Viewport::new(64, 48)?;
    /// let eye = Camera::look_at(Vec3::new(0.5, 0.5, 4.0), Vec3::new(0.5, 0.5, 0.5), Vec3::Y)?;
    /// let xf = eye.perspective(radians(45.0), 0.1, 100.0, vp)?;
    /// let (lo, hi) = CUBE.bounds().unwrap();
    /// let fitted = xf.fit_depth(lo, hi, 0.1)?;
    /// // The cube's front face now lies at depth 0 and its back face at 1.
    /// let depth = |p: Vec3| { let c = fitted.model_view_projection().transform_point(p); (c[2] / c[3] + 1.0) / 2.0 };
    /// assert!(depth(Vec3::new(0.5, 0.5, 1.0)) < 0.01 && depth(Vec3::new(0.5, 0.5, 0.0)) > 0.99);
    /// # Ok::<(), zraster::Error>(())
    /// ```
    pub fn fit_depth(mut self, lo: Vec3, hi: Vec3, min_near: f32) -> Result<Camera, Error> {
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
