//! What [`Renderer::draw`] draws into: the [`DepthTarget`]s, each naming what the
//! caller has (a frame in RAM, a display and a Z-buffer, a display drawn in bands), so
//! that the renderer picks the way to draw.

use super::*;
use crate::buffer::Frame;

/// Keeps [`DepthTarget`] to the crate's targets.
pub(crate) mod sealed {
    pub trait Sealed {}
}

/// Something [`Renderer::draw`] can draw into with per-pixel depth: a [`Frame`] (colour
/// and depth in RAM), a [`WithDepth`] (any display with a [`ZBuffer`]) or a
/// [`Bands`](crate::Bands) (a display drawn band by band).
///
/// The three are all there is (the trait is sealed): each says what memory you have,
/// and the renderer takes the fastest way to draw into it. The pictures, depths and
/// [`FrameStats`] pixel counts are the same whichever you pick (only
/// [`runs`](FrameStats::runs) differs, as a [`Frame`] hands over none), with one
/// exception: see-through faces ([`Translucent`](crate::shade::Translucent)) are
/// blended over a [`Frame`]'s or [`Bands`](crate::Bands)' colours, but drawn as a
/// screen door into a [`WithDepth`], whose display's colours cannot be read.
///
/// Several meshes share one target in a [`Scene`](crate::scene::Scene).
pub trait DepthTarget: sealed::Sealed {
    /// The target's pixel colour.
    type Color: PixelColor;
    /// What drawing into it can fail with besides bad input (`Infallible` for memory).
    type Error;

    /// Draw `renderer`'s mesh into the target (what [`Renderer::draw`] calls).
    #[doc(hidden)]
    fn draw_mesh<M, S: RenderState>(
        &mut self,
        renderer: &mut Renderer<'_, '_, M, S>,
    ) -> Result<(), DrawError<Self::Error>>
    where
        M: Copy + Material<Self::Color>;

    /// Draw every mesh of `objects` into the target: their opaque faces in (object,
    /// face) order, then their see-through ones (what [`Scene::draw`] calls).
    ///
    /// [`Scene::draw`]: crate::scene::Scene::draw
    #[doc(hidden)]
    fn draw_scene<M, S: RenderState>(
        &mut self,
        objects: &mut [Renderer<'_, '_, M, S>],
    ) -> Result<(), DrawError<Self::Error>>
    where
        M: Copy + Material<Self::Color>,
    {
        objects.iter_mut().try_for_each(|r| self.draw_mesh(r))
    }
}

impl<C: PixelColor> sealed::Sealed for Frame<'_, C> {}

/// Colour and depth written in one loop (flat and Lambert shading), without a
/// `DrawTarget` in between.
impl<C: PixelColor> DepthTarget for Frame<'_, C> {
    type Color = C;
    type Error = core::convert::Infallible;

    fn draw_mesh<M, S: RenderState>(
        &mut self,
        renderer: &mut Renderer<'_, '_, M, S>,
    ) -> Result<(), DrawError<Self::Error>>
    where
        M: Copy + Material<C>,
    {
        self.draw_scene(core::slice::from_mut(renderer))
    }

    fn draw_scene<M, S: RenderState>(
        &mut self,
        objects: &mut [Renderer<'_, '_, M, S>],
    ) -> Result<(), DrawError<Self::Error>>
    where
        M: Copy + Material<C>,
    {
        let (color, depth) = self.parts_mut();
        for r in objects.iter_mut() {
            r.draw_fused(color, depth)?;
        }
        for r in objects.iter_mut() {
            r.draw_see_through_buffered(color, depth)?;
        }
        Ok(())
    }
}

/// Any display (any [`DrawTarget`]) with a [`ZBuffer`]: the depth test in the Z-buffer,
/// and each row of a triangle that passes it handed to the display as runs
/// (`fill_solid`, or `fill_contiguous` for Gouraud and dithered materials).
///
/// Use it when the display has no frame buffer of yours in RAM: the Z-buffer is then
/// all the memory drawing needs (2 bytes a pixel, or a band of rows: only the rows it
/// holds are drawn). With RAM for colours too, a [`Frame`] is faster.
///
/// See-through faces ([`Translucent`](crate::shade::Translucent)) cannot be blended
/// here, as the display's colours cannot be read: they are drawn as a screen door (the
/// share alpha / 255 of each 4×4 block of their pixels, depth-tested, without depth
/// writes), never as an error.
///
/// ```
/// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::BinaryColor};
/// use zraster::camera::{Camera, Viewport};
/// use zraster::{math::{radians, Vec3}, mesh::CUBE, RenderOptions, Renderer, WithDepth, ZBuffer};
///
/// let mut display = MockDisplay::<BinaryColor>::new(); // 64 × 64
/// let mut depth = [0u16; 64 * 64];
/// let mut zbuf = ZBuffer::new(&mut depth, 64, 64)?;
/// zbuf.clear();
/// let xf = Camera::look_at(Vec3::new(2.0, 1.5, 3.0), Vec3::new(0.5, 0.5, 0.5), Vec3::Y)?
///     .perspective(radians(45.0), 0.1, 10.0, Viewport::new(64, 64)?)?;
/// let mut renderer = Renderer::new(&CUBE, &xf, RenderOptions::default())?;
/// renderer.draw(&mut WithDepth::new(&mut display, &mut zbuf)).unwrap();
/// assert_eq!(display.get_pixel(embedded_graphics::prelude::Point::new(32, 32)), Some(BinaryColor::On));
/// assert!(renderer.stats().runs > 0);
/// # Ok::<(), zraster::Error>(())
/// ```
#[derive(Debug)]
pub struct WithDepth<'a, 'z, D> {
    display: &'a mut D,
    depth: &'a mut ZBuffer<'z>,
}

impl<'a, 'z, D: DrawTarget> WithDepth<'a, 'z, D> {
    /// `display` drawn with the depth test of `depth`. Clear the Z-buffer before the
    /// first draw of a frame (the display is not cleared: only the pixels that pass the
    /// depth test are drawn).
    pub fn new(display: &'a mut D, depth: &'a mut ZBuffer<'z>) -> Self {
        WithDepth { display, depth }
    }

    /// The display and the Z-buffer.
    pub(crate) fn parts(&mut self) -> (&mut D, &mut ZBuffer<'z>) {
        (self.display, self.depth)
    }
}

impl<D: DrawTarget> sealed::Sealed for WithDepth<'_, '_, D> {}

impl<D: DrawTarget> DepthTarget for WithDepth<'_, '_, D> {
    type Color = D::Color;
    type Error = D::Error;

    fn draw_mesh<M, S: RenderState>(
        &mut self,
        renderer: &mut Renderer<'_, '_, M, S>,
    ) -> Result<(), DrawError<Self::Error>>
    where
        M: Copy + Material<D::Color>,
    {
        self.draw_scene(core::slice::from_mut(renderer))
    }

    fn draw_scene<M, S: RenderState>(
        &mut self,
        objects: &mut [Renderer<'_, '_, M, S>],
    ) -> Result<(), DrawError<Self::Error>>
    where
        M: Copy + Material<D::Color>,
    {
        for r in objects.iter_mut() {
            r.draw_runs(self.display, self.depth)?;
        }
        for r in objects.iter_mut() {
            r.draw_see_through_runs(self.display, self.depth)?;
        }
        Ok(())
    }
}

impl<'m, 'c, M: Copy, S: RenderState> Renderer<'m, 'c, M, S> {
    /// Draw the mesh with the Z-buffer into `target`: every visible triangle,
    /// depth-tested per pixel, in the mesh's materials and the chosen shading.
    ///
    /// The target says what you have, and the renderer picks how to draw:
    /// - a [`Frame`]: colour and depth buffers in RAM (the fastest; flush the frame to
    ///   the display afterwards);
    /// - a [`WithDepth`]: any display and a Z-buffer, drawn run by run;
    /// - a [`Bands`](crate::Bands): a display drawn band by band through a few KiB of
    ///   [`BandBuffers`](crate::BandBuffers), each band cleared and sent for you.
    ///
    /// A [`Frame`] or [`WithDepth`] is not cleared here: clear it before the first call of
    /// a frame. Several meshes (one [`Renderer`] each) may be drawn into the same one;
    /// into [`Bands`](crate::Bands), draw them together as a
    /// [`Scene`](crate::scene::Scene).
    ///
    /// See-through faces ([`Translucent`](crate::shade::Translucent) materials of alpha
    /// below 255) are drawn after the mesh's opaque ones, depth-tested without writing
    /// depth, in face order.
    ///
    /// Errors: [`DrawError::Input`] for a face table that refers to missing vertices or
    /// materials or has a face of fewer than three vertices (the faces before it may be
    /// drawn; [`Mesh::validate`](crate::mesh::Mesh::validate) rules that out), and
    /// [`DrawError::Target`] when the display fails. For a [`Frame`] the target's error
    /// is `Infallible`, and `?` turns the result into an [`Error`].
    pub fn draw<T>(&mut self, target: &mut T) -> Result<(), DrawError<T::Error>>
    where
        T: DepthTarget,
        M: Material<T::Color>,
    {
        target.draw_mesh(self)
    }
}
