//! Scenes: several meshes, each placed by its own model matrix and drawn in its own
//! materials and shading, in one frame or one banded display, sharing one depth buffer.
//!
//! A [`Scene`] borrows a slice of [`Renderer`]s (one a mesh, each made from its own
//! [`Camera::with_model`](crate::Camera::with_model)) and draws them together into a
//! [`DepthTarget`]. Into a [`Frame`](crate::Frame) or a [`WithDepth`](crate::WithDepth)
//! that is drawing them one after the other; into [`Bands`] it is what one renderer
//! cannot do alone: every band draws every object, so the picture is the whole frame's,
//! while each vertex is still transformed once a frame (into each renderer's cache) and
//! each object's triangles are sorted by band once a frame (into its run of the bins).
//!
//! The order is fixed: the opaque faces in (object, face) order, then the see-through
//! ones ([`Translucent`](crate::shade::Translucent)) in the same order, unsorted. So
//! where two objects tie in depth the earlier one stays in front, and the banded
//! picture, depths and [`FrameStats`] are byte-identical to the whole frame's.

use crate::render::{Dynamic, RenderState};
use crate::shade::Material;
use crate::{DepthTarget, DrawError, FrameStats, Renderer};

#[cfg(doc)]
use crate::{BandBuffers, Bands};

/// Several meshes drawn into one target with one depth buffer: see the
/// [module docs](self).
///
/// All objects share the material type `M` and the render state `S`; with the
/// default [`Dynamic`] state each keeps its own shading and cull mode (its
/// [`RenderOptions`](crate::RenderOptions)). For [`Bands`], give each renderer a vertex
/// cache ([`Renderer::with_cache`]) and the band buffers
/// [`Scene::bins_needed`] bins: each object's triangles are then sorted by band once a
/// frame, and each band visits only those that reach it. An object without a cache or
/// bins (see [`Renderer::binning`]) walks its whole mesh in every band instead: slower,
/// the same picture; under a binned-only state
/// ([`Binned`](crate::state::Binned)) the draw fails instead, before any band.
///
/// ```
/// use embedded_graphics::{pixelcolor::{Rgb565, Rgb888}, prelude::*};
/// use zraster::math::{radians, Mat4, Vec3};
/// use zraster::mesh::{Mesh, CUBE_POSITIONS};
/// use zraster::{scene::Scene, shade::Shading};
/// use zraster::{BandBuffers, Bands, Binning, CachedVertex, Camera, ColorBuffer, Frame};
/// use zraster::{RenderOptions, Renderer, Viewport};
///
/// const W: u32 = 64;
/// const H: u32 = 48;
/// // The unit cube as 12 triangles (binning wants triangles), in two colours.
/// const TRIANGLES: [[u16; 3]; 12] = [[0, 1, 2], [0, 2, 3], [1, 5, 6], [1, 6, 2], [2, 6, 7],
///     [2, 7, 3], [3, 7, 4], [3, 4, 0], [0, 4, 5], [0, 5, 1], [7, 6, 5], [7, 5, 4]];
/// let cube = |c| Mesh::triangles(&CUBE_POSITIONS, 1.0 / 16384.0, &TRIANGLES, c);
/// let (red, blue) = (cube(Rgb888::RED), cube(Rgb888::BLUE));
///
/// let camera = Camera::look_at(Vec3::new(0.0, 1.5, 4.0), Vec3::default(), Vec3::Y)?
///     .perspective(radians(45.0), 0.5, 10.0, Viewport::new(W, H)?)?;
/// // Each object its own model matrix and options.
/// let left = camera.with_model(Mat4::translation(Vec3::new(-1.3, -0.5, -0.5)));
/// let right = camera.with_model(Mat4::rotation_y(0.6) * Mat4::translation(Vec3::new(0.3, -0.5, -0.5)));
/// let lit = RenderOptions { shading: Shading::Lambert, ..Default::default() };
/// // Caller memory: a vertex cache for each object (8 bytes a vertex) ...
/// let (mut cache_a, mut cache_b) = ([CachedVertex::EMPTY; 8], [CachedVertex::EMPTY; 8]);
/// let mut objects = [
///     Renderer::with_cache(&red, &left, RenderOptions::default(), &mut cache_a)?,
///     Renderer::with_cache(&blue, &right, lit, &mut cache_b)?,
/// ];
/// // ... and bands of 8 rows with bins for both objects.
/// let needed = Scene::bins_needed(&objects, H, 8);
/// assert_eq!(needed, 2 * BandBuffers::<Rgb565>::bins_needed(12, H, 8));
/// let mut bins = [0u16; 2 * (12 + 4 * 6 + 2)];
/// let (mut band_color, mut band_depth) = ([Rgb565::BLACK; (W * 8) as usize], [0u16; (W * 8) as usize]);
/// let mut buffers =
///     BandBuffers::new(&mut band_color, &mut band_depth, W, 8, H, &mut bins[..needed])?;
/// let mut shown = [Rgb565::BLACK; (W * H) as usize]; // the display, here a buffer
/// let mut display = ColorBuffer::new(&mut shown, W, H)?;
/// let mut scene = Scene::new(&mut objects);
/// scene.draw(&mut Bands::new(&mut display, &mut buffers, Rgb565::BLACK))?;
/// assert!(scene.objects().iter().all(|r| r.binning() == Binning::Binned));
/// let banded = scene.stats();
///
/// // The same scene into a whole frame: the same picture and counts.
/// let (mut pixels, mut depth) = ([Rgb565::BLACK; (W * H) as usize], [0u16; (W * H) as usize]);
/// let mut frame = Frame::new(&mut pixels, &mut depth, W, H)?;
/// frame.clear(Rgb565::BLACK);
/// let mut objects = [
///     Renderer::new(&red, &left, RenderOptions::default())?,
///     Renderer::new(&blue, &right, lit)?,
/// ];
/// let mut scene = Scene::new(&mut objects);
/// scene.draw(&mut frame)?;
/// assert_eq!(frame.color().as_slice(), display.as_slice());
/// assert_eq!(scene.stats(), banded);
/// assert_eq!(frame.color().pixel(16, 26), Some(Rgb565::RED)); // the left cube
/// # Ok::<(), zraster::Error>(())
/// ```
pub struct Scene<'r, 'm, 'c, M, S = Dynamic> {
    objects: &'r mut [Renderer<'m, 'c, M, S>],
}

impl<'r, 'm, 'c, M: Copy, S: RenderState> Scene<'r, 'm, 'c, M, S> {
    /// The scene of `objects`, drawn in their order.
    pub fn new(objects: &'r mut [Renderer<'m, 'c, M, S>]) -> Self {
        Scene { objects }
    }

    /// Draw every object into `target`: the opaque faces in (object, face) order, then
    /// the see-through ones in the same order, each depth-tested against all the
    /// opaque ones. A [`Frame`](crate::Frame) or [`WithDepth`](crate::WithDepth) is not
    /// cleared here (clear it once a frame); [`Bands`] clears each band.
    ///
    /// Errors: as [`Renderer::draw`], for the first object that fails (the objects
    /// before it may be drawn).
    pub fn draw<T>(&mut self, target: &mut T) -> Result<(), DrawError<T::Error>>
    where
        T: DepthTarget,
        M: Material<T::Color>,
    {
        target.draw_scene(self.objects)
    }

    /// The counts of every object, added up (see [`FrameStats`]).
    pub fn stats(&self) -> FrameStats {
        let mut sum = FrameStats::default();
        for r in self.objects.iter() {
            let st = r.stats();
            sum.add_geometry(&st);
            sum.add_pixel_counts(&st);
        }
        sum
    }

    /// The objects, in drawing order (for their own [`stats`](Renderer::stats) and
    /// [`binning`](Renderer::binning)).
    pub fn objects(&self) -> &[Renderer<'m, 'c, M, S>] {
        self.objects
    }

    /// Bin entries for drawing `objects` into [`Bands`] of `rows` rows on a screen
    /// `height` rows high: for each object, [`BandBuffers::bins_needed`] of its face
    /// count, added up (saturating). The objects take them in order, each its own run;
    /// with fewer, the objects whose runs do not fit draw unbinned
    /// ([`Unbinned::BinsTooShort`](crate::Unbinned::BinsTooShort)), to the same picture.
    pub fn bins_needed(objects: &[Renderer<'m, 'c, M, S>], height: u32, rows: u32) -> usize {
        objects.iter().fold(0usize, |sum, r| {
            sum.saturating_add(crate::buffer::bins_for(r.mesh.face_count(), height, rows))
        })
    }
}

impl<M, S> core::fmt::Debug for Scene<'_, '_, '_, M, S> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Scene")
            .field("objects", &self.objects.len())
            .finish()
    }
}
