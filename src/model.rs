//! A mesh as an embedded-graphics primitive: [`Model`], drawn with a [`ModelStyle`]
//! through `Drawable`, like a `Circle` with a `PrimitiveStyle`.
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
//! use zraster::{math::{radians, Mat4, Vec3}, Camera, Model, ModelStyle};
//! use zraster_bench_scene::bunny::{BUNNY_FIT, BUNNY_MESH}; // flash tables from examples/obj2rust.rs
//!
//! // Any DrawTarget: a display driver, here the embedded-graphics simulator's display.
//! let mut display = embedded_graphics_simulator::SimulatorDisplay::<Rgb565>::new(Size::new(160, 120));
//! let camera = Camera::look_at(Vec3::new(0.0, 0.0, 1.6), Vec3::default(), Vec3::Y)?
//!     .perspective(radians(40.0), 0.1, 10.0, display.bounding_box().try_into()?)?
//!     .with_model(Mat4::scaling(Vec3::new(BUNNY_FIT, BUNNY_FIT, BUNNY_FIT)));
//! let style = ModelStyle::gouraud().with_background(Rgb565::BLACK);
//! // The outer `?` is the display's error, the inner one zraster's (bad input).
//! let stats = Model::new(&BUNNY_MESH, &camera).into_styled(style).draw(&mut display)??;
//! assert!(stats.drawn > 1000);
//! # assert_ne!(display.get_pixel(Point::new(80, 60)), Rgb565::BLACK);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! A model draws on a display of any colour type its materials shade to (for `Rgb888`
//! materials, every embedded-graphics colour type: [`DisplayColor`](crate::shade::DisplayColor)).
//! Without a background it is drawn over what the display shows, like any other
//! primitive: here a Lambert-lit cube, dithered, inside a frame on a 1-bit panel.
//!
//! ```
//! use embedded_graphics::{pixelcolor::BinaryColor, prelude::*, primitives::{PrimitiveStyle, Rectangle}};
//! use embedded_graphics_simulator::SimulatorDisplay;
//! use zraster::{math::{radians, Vec3}, mesh::CUBE, Camera, Model, ModelStyle, Viewport};
//!
//! let mut display = SimulatorDisplay::<BinaryColor>::new(Size::new(128, 64)); // an SSD1306
//! let outline = Rectangle::new(Point::zero(), Size::new(128, 64));
//! outline.into_styled(PrimitiveStyle::with_stroke(BinaryColor::On, 1)).draw(&mut display)?;
//! // The cube in the middle 64 × 64 pixels of the display.
//! let camera = Camera::look_at(Vec3::new(2.0, 1.5, 3.0), Vec3::new(0.5, 0.5, 0.5), Vec3::Y)?
//!     .perspective(radians(40.0), 0.1, 10.0, Viewport::at(32, 0, 64, 64)?)?;
//! let cube = Model::new(&CUBE, &camera);
//! assert_eq!(cube.bounding_box(), Rectangle::new(Point::new(32, 0), Size::new(64, 64)));
//! cube.into_styled(ModelStyle::lambert()).draw(&mut display)??;
//! assert_eq!(display.get_pixel(Point::new(0, 32)), BinaryColor::On); // the outline stays
//! # let lit = (40..88).filter(|&x| display.get_pixel(Point::new(x, 32)).is_on()).count();
//! # assert!(lit > 4 && lit < 48, "{lit}"); // dithered grey: some pixels on, some off
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Memory: bands on the stack
//!
//! `Drawable::draw` takes `&self` and no buffers, so a model brings its own: it draws the
//! display in horizontal bands through a colour buffer and a depth buffer of `N` pixels
//! each, on the stack (`N × (size_of::<C>() + 2)` bytes: 4 KiB for the default
//! `N` = 1024 on an `Rgb565` display). A band is as many whole rows as fit, so the display
//! (as far as the model covers it: from column 0 to the right edge of its bounding box,
//! the camera's viewport) must be at most `N` pixels wide, or drawing fails with
//! [`Error::CapacityExceeded`]. Pick another `N` with
//! [`Model::with_band_pixels`]: more rows a band means fewer bands, each of which walks
//! the whole mesh again.
//!
//! The pixels are exactly those of a whole [`Frame`] drawn with the same camera and
//! options (banded drawing is pixel-identical to whole-frame drawing). For a large mesh
//! drawn often, the lower-level calls are faster and let you choose the memory: a
//! [`Renderer`] with a vertex cache ([`Renderer::with_cache`]) into [`Bands`](crate::Bands)
//! with bins, or into a [`Frame`].
//!
//! # Background or not
//!
//! With a [background](ModelStyle::with_background), each band is cleared to it, drawn
//! and sent whole (one `fill_contiguous`): every pixel of the model's area is written once,
//! as a frame flush would write it. Without one (the default), only the pixels the model
//! covers are sent, row run by row run: whatever the display showed elsewhere stays, so a
//! model can be drawn over a picture, text or another model (each model has its own depth
//! buffer: the last one drawn is on top where they overlap).
//!
//! # Errors
//!
//! `Drawable::draw` returns the display's error in its `Err`; zraster's own, for input
//! that is wrong (a face referring to a missing vertex, Gouraud shading without vertex
//! normals, a display wider than the band capacity), are the
//! [`Output`](embedded_graphics::Drawable::Output), a `Result<FrameStats, Error>`, checked
//! before anything is drawn. [`Model::render`] gives both as one [`DrawError`].

use embedded_graphics::{
    geometry::Dimensions,
    pixelcolor::{PixelColor, Rgb888},
    prelude::{DrawTarget, Point, Size},
    primitives::{Primitive, Rectangle, StyledDimensions, StyledDrawable},
};

use crate::shade::{Light, Material, Shading};
use crate::{
    Camera, ColorBuffer, Cull, DrawError, Error, Frame, FrameStats, RenderOptions, Renderer,
    ZBuffer,
};

/// The default band capacity of a [`Model`], in pixels: 1024 colours and 1024 depths on
/// the stack while it draws (4 KiB for `Rgb565`), bands of 8 rows on a 128-pixel-wide
/// display and of 3 rows on a 320-pixel-wide one.
pub const DEFAULT_BAND_PIXELS: usize = 1024;

/// A mesh placed by a camera, as an embedded-graphics primitive: style it with
/// [`into_styled`](Primitive::into_styled) and a [`ModelStyle`], then
/// [`draw`](embedded_graphics::Drawable::draw) it on any display.
///
/// `N` is the band capacity in pixels (see the [module docs](crate::model)); its
/// [`bounding_box`](Dimensions::bounding_box) is the camera's [`Viewport`](crate::Viewport): the model
/// draws nothing outside it.
///
/// ```
/// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::Rgb565, prelude::*};
/// use zraster::{math::{radians, Vec3}, mesh::CUBE, Camera, Model, ModelStyle, Viewport};
///
/// let mut display = MockDisplay::<Rgb565>::new(); // 64 × 64
/// let camera = Camera::look_at(Vec3::new(2.0, 1.5, 3.0), Vec3::new(0.5, 0.5, 0.5), Vec3::Y)?
///     .perspective(radians(45.0), 0.1, 10.0, Viewport::new(64, 64)?)?;
/// let stats = Model::new(&CUBE, &camera).into_styled(ModelStyle::flat()).draw(&mut display)??;
/// assert_eq!(stats.drawn, 6); // three faces turned to the camera
/// assert_eq!(display.get_pixel(Point::new(32, 32)), Some(Rgb565::new(0, 0, 31))); // the front face
/// assert_eq!(display.get_pixel(Point::new(0, 0)), None); // not drawn: no background
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Model<'m, M = Rgb888, const N: usize = DEFAULT_BAND_PIXELS> {
    mesh: crate::mesh::Mesh<'m, M>,
    camera: Camera,
}

impl<'m, M: Copy> Model<'m, M> {
    /// `mesh` placed by `camera` (both copied: a mesh is a few borrowed slices), with the
    /// default band capacity ([`DEFAULT_BAND_PIXELS`]). Nothing is checked until it is
    /// drawn.
    pub fn new(mesh: &crate::mesh::Mesh<'m, M>, camera: &Camera) -> Self {
        Model {
            mesh: *mesh,
            camera: *camera,
        }
    }
}

impl<'m, M: Copy, const N: usize> Model<'m, M, N> {
    /// The same model drawn in bands of at most `K` pixels (so with `K` colours and `K`
    /// depths on the stack).
    ///
    /// ```
    /// # use zraster::{math::{radians, Vec3}, mesh::CUBE, Camera, Model, Viewport};
    /// # let camera = Camera::look_at(Vec3::new(2.0, 1.5, 3.0), Vec3::default(), Vec3::Y)?
    /// #     .perspective(radians(45.0), 0.1, 10.0, Viewport::new(320, 240)?)?;
    /// // 320-pixel rows, 16 at a time: 5 KiB of colours and 10 KiB of depths for Rgb565.
    /// let model = Model::new(&CUBE, &camera).with_band_pixels::<{ 320 * 16 }>();
    /// assert_eq!(model.band_pixels(), 5120);
    /// # Ok::<(), zraster::Error>(())
    /// ```
    pub fn with_band_pixels<const K: usize>(self) -> Model<'m, M, K> {
        Model {
            mesh: self.mesh,
            camera: self.camera,
        }
    }

    /// The band capacity in pixels: `N`.
    pub const fn band_pixels(&self) -> usize {
        N
    }

    /// The mesh.
    pub fn mesh(&self) -> &crate::mesh::Mesh<'m, M> {
        &self.mesh
    }

    /// The camera.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// Draw the model with `style` into `display`, as `into_styled(style).draw(display)`
    /// does, with both kinds of error in one [`DrawError`]: [`DrawError::Input`] for wrong
    /// input (checked before anything is drawn: the mesh's tables, the camera, the light,
    /// and the band capacity, [`Error::CapacityExceeded`] when the display is wider than
    /// `N` pixels), [`DrawError::Target`] when the display fails.
    ///
    /// Returns the frame's [`FrameStats`].
    ///
    /// ```
    /// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::Gray8, prelude::*};
    /// use zraster::{math::{radians, Vec3}, mesh::CUBE, Camera, DrawError, Error, Model, ModelStyle, Viewport};
    ///
    /// let camera = Camera::look_at(Vec3::new(2.0, 1.5, 3.0), Vec3::new(0.5, 0.5, 0.5), Vec3::Y)?
    ///     .perspective(radians(45.0), 0.1, 10.0, Viewport::new(64, 64)?)?;
    /// let mut display = MockDisplay::<Gray8>::new();
    /// // Gouraud shading needs vertex normals, which the cube has not.
    /// let r = Model::new(&CUBE, &camera).render(&ModelStyle::gouraud(), &mut display);
    /// assert_eq!(r, Err(DrawError::Input(Error::MissingNormals)));
    /// // Rows of 64 pixels do not fit bands of 32.
    /// let narrow = Model::new(&CUBE, &camera).with_band_pixels::<32>();
    /// let r = narrow.render(&ModelStyle::flat(), &mut display);
    /// assert_eq!(r, Err(DrawError::Input(Error::CapacityExceeded { capacity: 32 })));
    /// assert_eq!(display, MockDisplay::new()); // nothing drawn
    /// # Ok::<(), zraster::Error>(())
    /// ```
    pub fn render<D>(
        &self,
        style: &ModelStyle<D::Color>,
        display: &mut D,
    ) -> Result<FrameStats, DrawError<D::Error>>
    where
        D: DrawTarget,
        D::Color: Default,
        M: Material<D::Color>,
    {
        // Every input check before the first pixel is sent: the renderer checks the
        // camera, the light and the mesh's scale and normal tables; the face table is
        // walked here once, so that a bad face is not found halfway down the display.
        self.mesh.validate()?;
        let mut renderer = Renderer::new(&self.mesh, &self.camera, style.options())?;
        let Some(area) = self.area(display.bounding_box()) else {
            return Ok(renderer.stats()); // the model's area is off the display
        };
        // The band buffers cover columns 0..right (as a frame does), of which the
        // columns left..right are sent.
        let (left, right) = (area.left, area.right);
        let width = right as u32; // right ≤ 8192: a viewport ends there
        if right as usize > N {
            return Err(Error::CapacityExceeded { capacity: N }.into());
        }
        let rows = (N / right as usize) as u32; // ≥ 1
        let fill = style.background.unwrap_or_default();
        let mut colors = [fill; N];
        let mut depths = [ZBuffer::FAR; N];
        let mut y = area.top;
        while y < area.bottom {
            let n = rows.min((area.bottom - y) as u32);
            let len = (width * n) as usize; // ≤ N
            let color = ColorBuffer::new_band(colors.as_mut_slice(), width, n, y)?;
            let depth = ZBuffer::new_band(depths.as_mut_slice(), width, n, y)?;
            let mut band = Frame::from_buffers(color, depth);
            match style.background {
                Some(background) => band.clear(background),
                None => band.depth_mut().clear(), // only covered pixels are sent
            }
            renderer.draw(&mut band).map_err(Error::from)?;
            let (color, depth) = band.into_parts();
            let (color, depth) = (color.as_slice(), depth.as_slice());
            let (color, depth) = (prefix(color, len), prefix(depth, len));
            let columns = left as usize..right as usize;
            if style.background.is_some() {
                send_band(display, color, width, columns, y).map_err(DrawError::Target)?;
            } else {
                send_covered(display, color, depth, width, columns, y)
                    .map_err(DrawError::Target)?;
            }
            y += n as i32;
        }
        Ok(renderer.stats())
    }

    /// The screen rectangle drawn on `display`: the viewport, within the display and at
    /// coordinates ≥ 0 (where zraster's buffers are); `None` when that is empty.
    fn area(&self, display: Rectangle) -> Option<Area> {
        let vp = &self.camera.viewport;
        let (dx, dy) = (i64::from(display.top_left.x), i64::from(display.top_left.y));
        let left = i64::from(vp.x).max(dx).max(0);
        let top = i64::from(vp.y).max(dy).max(0);
        let right = (i64::from(vp.x) + i64::from(vp.width)).min(dx + i64::from(display.size.width));
        let bottom =
            (i64::from(vp.y) + i64::from(vp.height)).min(dy + i64::from(display.size.height));
        // Within the viewport: every coordinate lies in ±2 · 8192.
        (left < right && top < bottom).then_some(Area {
            left: left as i32,
            top: top as i32,
            right: right as i32,
            bottom: bottom as i32,
        })
    }
}

/// The part of the screen a model draws: columns `left..right`, rows `top..bottom`,
/// all ≥ 0.
struct Area {
    left: i32,
    top: i32,
    right: i32,
    bottom: i32,
}

/// The first `len` entries of `s` (all of it if shorter).
fn prefix<T>(s: &[T], len: usize) -> &[T] {
    s.get(..len).unwrap_or(s)
}

/// Send columns `columns` of a band of `width`-pixel rows starting at screen row `y`,
/// with one `fill_contiguous`.
fn send_band<D: DrawTarget>(
    display: &mut D,
    color: &[D::Color],
    width: u32,
    columns: core::ops::Range<usize>,
    y: i32,
) -> Result<(), D::Error> {
    let w = width as usize;
    let rows = color.len() / w;
    let area = Rectangle::new(
        Point::new(columns.start as i32, y),
        Size::new(columns.len() as u32, rows as u32),
    );
    if columns.start == 0 && columns.end == w {
        return display.fill_contiguous(&area, color.iter().copied());
    }
    let pixels = color
        .chunks_exact(w)
        .flat_map(move |row| row.get(columns.clone()).unwrap_or(&[]).iter().copied());
    display.fill_contiguous(&area, pixels)
}

/// Send the pixels of a band that the model covers (depth nearer than
/// [`ZBuffer::FAR`], which nothing drawn can have with the default depth test), within
/// `columns`: one `fill_contiguous` per run of them in a row.
fn send_covered<D: DrawTarget>(
    display: &mut D,
    color: &[D::Color],
    depth: &[u16],
    width: u32,
    columns: core::ops::Range<usize>,
    y: i32,
) -> Result<(), D::Error> {
    let w = width as usize;
    let rows = color.chunks_exact(w).zip(depth.chunks_exact(w));
    for (row_y, (colors, depths)) in (y..).zip(rows) {
        let (Some(colors), Some(depths)) =
            (colors.get(columns.clone()), depths.get(columns.clone()))
        else {
            continue;
        };
        let mut x = 0;
        // Skip what is not covered, then send the run that is.
        while let Some(start) = depths
            .get(x..)
            .and_then(|d| d.iter().position(|&d| d != ZBuffer::FAR))
        {
            let start = x + start;
            let run = depths.get(start..).unwrap_or(&[]);
            let end = start + run.iter().take_while(|&&d| d != ZBuffer::FAR).count();
            if let Some(run) = colors.get(start..end) {
                let area = Rectangle::new(
                    Point::new((columns.start + start) as i32, row_y),
                    Size::new(run.len() as u32, 1),
                );
                display.fill_contiguous(&area, run.iter().copied())?;
            }
            x = end;
        }
    }
    Ok(())
}

impl<M, const N: usize> Dimensions for Model<'_, M, N> {
    /// The camera's viewport: the model draws no pixel outside it.
    fn bounding_box(&self) -> Rectangle {
        self.camera.viewport.into()
    }
}

impl<M, const N: usize> Primitive for Model<'_, M, N> {}

impl<M, C, const N: usize> StyledDimensions<ModelStyle<C>> for Model<'_, M, N> {
    /// The camera's viewport, whatever the style.
    fn styled_bounding_box(&self, _style: &ModelStyle<C>) -> Rectangle {
        self.camera.viewport.into()
    }
}

/// What makes `model.into_styled(style)` a `Drawable`. Its
/// [`Output`](embedded_graphics::Drawable::Output) is zraster's result: the frame's
/// [`FrameStats`], or the [`Error`] in the input (then nothing was drawn); the display's
/// own error is `draw`'s `Err`. [`Model::render`] gives both in one [`DrawError`].
impl<M, C, const N: usize> StyledDrawable<ModelStyle<C>> for Model<'_, M, N>
where
    M: Material<C>,
    C: PixelColor + Default,
{
    type Color = C;
    type Output = Result<FrameStats, Error>;

    fn draw_styled<D>(
        &self,
        style: &ModelStyle<C>,
        target: &mut D,
    ) -> Result<Self::Output, D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        match self.render(style, target) {
            Ok(stats) => Ok(Ok(stats)),
            Err(DrawError::Input(e)) => Ok(Err(e)),
            Err(DrawError::Target(e)) => Err(e),
        }
    }
}

/// How a [`Model`] is drawn: shading, culling, the light, and whether its area is
/// cleared to a background first.
///
/// Made with [`flat`](ModelStyle::flat), [`lambert`](ModelStyle::lambert) or
/// [`gouraud`](ModelStyle::gouraud) and the `with_` methods; the fields can be read and
/// changed.
///
/// ```
/// use embedded_graphics::pixelcolor::Gray4;
/// use zraster::{math::Vec3, shade::{Light, Shading}, Cull, ModelStyle};
///
/// let style = ModelStyle::lambert()
///     .with_light(Light { direction: Vec3::new(0.0, 1.0, 1.0), ambient: 0.1, diffuse: 0.9 })
///     .with_cull(Cull::None)
///     .with_background(Gray4::new(2));
/// assert_eq!(style.shading, Shading::Lambert);
/// assert_eq!(style.background, Some(Gray4::new(2)));
/// assert_eq!(style.options().cull, Cull::None); // the same as the lower-level options
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct ModelStyle<C> {
    /// The shading model (flat, Lambert or Gouraud: see [`Shading`]). Gouraud needs the
    /// mesh's vertex normals.
    pub shading: Shading,
    /// Which faces are not drawn (the back faces by default).
    pub cull: Cull,
    /// The light for Lambert and Gouraud shading.
    pub light: Light,
    /// The colour the model's area is cleared to before drawing; `None` (the default)
    /// draws over what the display shows, sending only the pixels the model covers.
    pub background: Option<C>,
}

impl<C> ModelStyle<C> {
    /// A style with `shading`, back faces culled, the default light and no background.
    pub fn new(shading: Shading) -> Self {
        let options = RenderOptions::default();
        ModelStyle {
            shading,
            cull: options.cull,
            light: options.light,
            background: None,
        }
    }

    /// Each face in its material's colour, unlit ([`Shading::Flat`]).
    pub fn flat() -> Self {
        Self::new(Shading::Flat)
    }

    /// Each face lit by the light as a whole ([`Shading::Lambert`]).
    pub fn lambert() -> Self {
        Self::new(Shading::Lambert)
    }

    /// Lit at each vertex and interpolated across faces ([`Shading::Gouraud`]); the mesh
    /// needs vertex normals.
    pub fn gouraud() -> Self {
        Self::new(Shading::Gouraud)
    }

    /// The same style with another shading model.
    pub fn with_shading(mut self, shading: Shading) -> Self {
        self.shading = shading;
        self
    }

    /// The same style with another culling mode.
    pub fn with_cull(mut self, cull: Cull) -> Self {
        self.cull = cull;
        self
    }

    /// The same style with another light.
    pub fn with_light(mut self, light: Light) -> Self {
        self.light = light;
        self
    }

    /// The same style clearing the model's area to `background` first: each band is then
    /// sent whole, every pixel once.
    pub fn with_background(mut self, background: C) -> Self {
        self.background = Some(background);
        self
    }

    /// The same style drawing over the display (the default): only the pixels the model
    /// covers are sent.
    pub fn without_background(mut self) -> Self {
        self.background = None;
        self
    }

    /// The lower-level [`RenderOptions`] of this style, for a [`Renderer`] that draws the
    /// same pixels.
    pub fn options(&self) -> RenderOptions {
        RenderOptions {
            cull: self.cull,
            shading: self.shading,
            light: self.light,
        }
    }
}

impl<C> Default for ModelStyle<C> {
    /// [`ModelStyle::flat`].
    fn default() -> Self {
        Self::flat()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{radians, Vec3};
    use crate::mesh::CUBE;
    use crate::Viewport;
    use embedded_graphics::pixelcolor::Rgb565;

    fn camera(vp: Viewport) -> Camera {
        Camera::look_at(Vec3::new(2.0, 1.5, 3.0), Vec3::new(0.5, 0.5, 0.5), Vec3::Y)
            .unwrap()
            .perspective(radians(45.0), 0.1, 10.0, vp)
            .unwrap()
    }

    #[test]
    fn area_is_the_viewport_on_the_display() {
        let m = Model::new(&CUBE, &camera(Viewport::at(-4, 10, 40, 40).unwrap()));
        let display = Rectangle::new(Point::zero(), Size::new(32, 32));
        let a = m.area(display).unwrap();
        assert_eq!((a.left, a.top, a.right, a.bottom), (0, 10, 32, 32));
        let off = Rectangle::new(Point::new(100, 0), Size::new(32, 32));
        assert!(m.area(off).is_none());
        assert!(m.area(Rectangle::zero()).is_none());
    }

    #[test]
    fn viewport_rectangle_round_trip() {
        let r = Rectangle::new(Point::new(3, -2), Size::new(20, 10));
        let vp = Viewport::try_from(r).unwrap();
        assert_eq!(Rectangle::from(vp), r);
        assert_eq!(Viewport::try_from(Size::new(0, 5)), Err(Error::ZeroSize));
        let style: ModelStyle<Rgb565> = ModelStyle::default();
        assert_eq!(style.options(), RenderOptions::default());
    }
}
