//! The renderers: from a mesh and a transform to pixels.
//!
//! One [`Renderer`] holds a frame's geometry state (the fixed-point transform, the
//! light in model space and, optionally, a cache of transformed vertices) and draws it
//! in any of four ways: with the Z-buffer ([`draw`](Renderer::draw), into a
//! [`DepthTarget`]: a frame in RAM, a display with a Z-buffer, or a display drawn in
//! bands), by depth sorting ([`draw_depth_sorted`](Renderer::draw_depth_sorted)), as
//! hidden-line ([`draw_hidden_line`](Renderer::draw_hidden_line)) or as wireframe
//! ([`draw_wireframe`](Renderer::draw_wireframe)).

use embedded_graphics::{pixelcolor::PixelColor, prelude::DrawTarget};

mod binning;
mod lines;
mod painter;
mod solid;
mod target;
mod textured;
mod walk;

pub use crate::fill::UvMode;
pub use crate::geometry::cull::Cull;
pub use crate::state::{Dynamic, RenderState};
pub use binning::{Binning, Unbinned};
pub use painter::DepthSort;
pub(crate) use solid::per_colouring;
pub(crate) use target::sealed;
pub use target::{DepthTarget, WithDepth};
pub use textured::{TexturedTarget, Texturing};
pub(crate) use walk::{cached_outside_rows, cached_triangle, CachedWalk};
use walk::{decide, edges, fan, Seen};

use crate::camera::Camera;
use crate::fill::{clip_of, depth_runs, fill_flat_buffered, shade_triangle, FlatTarget};
use crate::geometry::clip::{clip_polygon, clip_segment, ClipPolygon, ClipVertex};
use crate::geometry::project::{outcode_of, to_f32, ScreenMap, W_SHIFT_HINT};
use crate::geometry::transform::FixedTransform;
use crate::math::{clamp2, round_q15, Vec3};
use crate::mesh::{face_normal, Faces, Mesh, NORMAL_ONE};
/// Defined beside the set-up kernel that reads its entries in place.
pub use crate::num::kernel::CachedVertex;
use crate::num::kernel::{place_quads, LightBlock, XyWord, PLACE4_KERNEL};
use crate::raster::{
    draw_line, signed_area, signed_area_guarded, Clip, Plane, ScreenVertex, SpanStats,
};
use crate::shade::{Intensity, Light, Material, Shading, ONE};
use crate::{ColorBuffer, DrawError, Error, ZBuffer};

/// How a mesh is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RenderOptions {
    /// Face culling.
    pub cull: Cull,
    /// Shading model.
    pub shading: Shading,
    /// The light for [`Shading::Lambert`] and [`Shading::Gouraud`].
    pub light: Light,
}

/// Counts for a frame.
///
/// Geometry counts (triangles in, culled, outside, clipped, drawn) are taken by the
/// first draw call of a [`Renderer`]; pixel counts add up over every call, so a frame
/// drawn band by band reports the same totals as one drawn whole.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct FrameStats {
    /// Triangles after fan triangulation of the faces.
    pub triangles_in: u32,
    /// Triangles dropped by face culling (or with zero area).
    pub culled: u32,
    /// Triangles entirely outside the view volume.
    pub outside: u32,
    /// Triangles cut by a clip plane (near, far or guard band).
    pub clipped: u32,
    /// Triangles handed to the rasterizer (pieces of clipped ones included).
    pub drawn: u32,
    /// Pixels depth-tested (64 bits: overdraw at large sizes passes 2³²).
    pub pixels_tested: u64,
    /// Pixels written.
    pub pixels_written: u64,
    /// Runs handed to the draw target (drawing into a [`Frame`](crate::Frame) or
    /// [`Bands`](crate::Bands) writes flat-coloured pixels directly and hands over none).
    pub runs: u64,
}

impl FrameStats {
    /// Add the triangle counts of `g` (not its pixel counts).
    pub(crate) fn add_geometry(&mut self, g: &FrameStats) {
        self.triangles_in += g.triangles_in;
        self.culled += g.culled;
        self.outside += g.outside;
        self.clipped += g.clipped;
        self.drawn += g.drawn;
    }

    pub(crate) fn add_pixel_counts(&mut self, o: &FrameStats) {
        self.pixels_tested += o.pixels_tested;
        self.pixels_written += o.pixels_written;
        self.runs += o.runs;
    }

    pub(crate) fn add_pixels(&mut self, s: SpanStats) {
        self.add_fill(s);
        self.runs += u64::from(s.runs);
    }

    /// Add the pixel counts of `s`, which has no runs (a fill into buffers).
    #[inline(always)]
    pub(crate) fn add_fill(&mut self, s: SpanStats) {
        self.pixels_tested += u64::from(s.pixels_tested);
        self.pixels_written += u64::from(s.pixels_written);
    }
}

impl CachedVertex {
    /// `x` of a vertex the entry does not place.
    const MARK: i16 = i16::MIN;

    /// The word of x and y.
    #[inline(always)]
    const fn pack(x: i16, y: i16) -> XyWord {
        XyWord::new(x, y)
    }

    /// x.
    #[inline(always)]
    const fn x(&self) -> i16 {
        self.xy.x()
    }

    /// y.
    #[inline(always)]
    const fn y(&self) -> i16 {
        self.xy.y()
    }

    /// The entry for a vertex with outcode `code` and screen position `v`.
    #[inline]
    pub(crate) fn new(code: u8, v: ScreenVertex) -> CachedVertex {
        let fits = |c: i32| crate::num::abs_below(c, 1 << 14);
        if code == 0 && fits(v.x()) && fits(v.y()) {
            CachedVertex {
                xy: Self::pack(v.x() as i16, v.y() as i16),
                z: v.z(),
            }
        } else {
            CachedVertex {
                xy: Self::pack(Self::MARK, i16::from(code)),
                z: 0,
            }
        }
    }

    /// The entry placing `v`, a vertex inside the view volume, if it is within ±1024
    /// pixels (`None`: its entry is marked).
    #[inline(always)]
    pub(crate) fn placing(v: ScreenVertex) -> Option<CachedVertex> {
        // |c| < 2¹⁴ as one unsigned compare (a branch here: the other way is a call).
        let fits = |c: i32| c.wrapping_add((1 << 14) - 1) as u32 <= 2 * ((1 << 14) - 1);
        (fits(v.x()) && fits(v.y())).then(|| CachedVertex {
            xy: Self::pack(v.x() as i16, v.y() as i16),
            z: v.z(),
        })
    }

    /// Whether the entry holds no screen position (outside, or beyond ±1024 pixels).
    #[inline(always)]
    pub(crate) fn marked(&self) -> bool {
        self.x() == Self::MARK
    }

    /// The vertex's outcode (0 for every vertex inside the view volume).
    #[inline(always)]
    pub(crate) fn code(&self) -> u8 {
        if self.marked() {
            self.y() as u8
        } else {
            0
        }
    }

    /// The screen position (the origin for a marked entry).
    #[inline(always)]
    pub(crate) fn screen(&self) -> ScreenVertex {
        if self.marked() {
            ScreenVertex::ORIGIN
        } else {
            self.placed()
        }
    }

    /// x and y (1/16 pixel) of an entry known not to be marked.
    #[inline(always)]
    pub(crate) fn xy(&self) -> (i32, i32) {
        (i32::from(self.x()), i32::from(self.y()))
    }

    /// The screen position of an entry known not to be marked.
    #[inline(always)]
    pub(crate) fn placed(&self) -> ScreenVertex {
        ScreenVertex::from_raw(i32::from(self.x()), i32::from(self.y()), self.z)
    }

    /// An empty entry, to initialise cache arrays.
    pub const EMPTY: CachedVertex = CachedVertex {
        xy: XyWord::new(0, 0),
        z: 0,
    };
}

impl Default for CachedVertex {
    fn default() -> Self {
        CachedVertex::EMPTY
    }
}

/// Draws one mesh, placed by one transform, into targets with the methods below:
/// [`draw`](Renderer::draw) with the Z-buffer into any [`DepthTarget`], or by another
/// algorithm (depth sorting, hidden-line, wireframe).
///
/// A renderer is made for one frame (the transform is applied as it is built) and
/// counts what it draws ([`stats`](Renderer::stats)); make a new one for the next
/// frame, or for the next mesh of the same frame.
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb565;
/// use embedded_graphics::prelude::*;
/// use zraster::{math::{radians, Vec3}, mesh::CUBE, Camera, Viewport};
/// use zraster::{Frame, Renderer, RenderOptions};
///
/// let vp = Viewport::new(64, 48)?;
/// let xf = Camera::look_at(Vec3::new(2.0, 1.5, 3.0), Vec3::new(0.5, 0.5, 0.5), Vec3::Y)?
///     .perspective(radians(45.0), 0.1, 10.0, vp)?;
/// let mut pixels = [Rgb565::BLACK; 64 * 48];
/// let mut depth = [0u16; 64 * 48];
/// let mut frame = Frame::new(&mut pixels, &mut depth, 64, 48)?;
/// frame.clear(Rgb565::BLACK);
/// let mut renderer = Renderer::new(&CUBE, &xf, RenderOptions::default())?;
/// renderer.draw(&mut frame)?;
/// // Three faces of the cube face the camera: six triangles.
/// assert_eq!(renderer.stats().drawn, 6);
/// assert_eq!(frame.color().pixel(32, 24), Some(Rgb565::new(0, 0, 31))); // the blue front face
/// # Ok::<(), zraster::Error>(())
/// ```
pub struct Renderer<'m, 'c, M, S = Dynamic> {
    pub(crate) mesh: Mesh<'m, M>,
    pub(crate) fixed: FixedTransform,
    pub(crate) map: ScreenMap,
    pub(crate) options: RenderOptions,
    /// Unit light direction in model space, for model-space normals.
    pub(crate) light_model: Vec3,
    /// The light for Q14 normals: `L` in Q15, the ambient weight in Q15 and the diffuse
    /// weight in Q15 shifted up by [`LAMBERT_SCALE`].
    pub(crate) light_q: ([i32; 3], i64, i64),
    pub(crate) cache: Option<&'c mut [CachedVertex]>,
    /// Whether no entry of `cache` is marked (each placed: |x|, |y| < 2¹⁴), known where
    /// a vertex kernel filled it: ARMv6-M's face loop and the binning scans then skip
    /// that test.
    pub(crate) placed: bool,
    pub(crate) stats: FrameStats,
    pub(crate) counted: bool,
    /// Whether the mesh has see-through faces, once a see-through pass has looked.
    pub(crate) see_through: Option<bool>,
    /// Whether the last banded draw binned its triangles (see [`Binning`]).
    pub(crate) binning: Binning,
    /// What is fixed at compile time (see [`state`](crate::state)).
    pub(crate) state: core::marker::PhantomData<S>,
}

/// How far the diffuse weight of [`Renderer::light_q`] is shifted up for
/// [`lambert_term`]: by 3 where it takes the high word of its product, by 0 on ARMv6-M.
const LAMBERT_SCALE: u32 = if crate::num::ARMV6M { 0 } else { 3 };

/// The diffuse term of [`Renderer::lambert_q14`]: `dot · w / 2²⁹` rounded, for `0 ≤ dot ≤
/// 2²⁹` and the Q15 weight `w` (|w| ≤ 2¹⁶) stored as `diff = w << LAMBERT_SCALE`. On
/// ARMv6-M in 32-bit products ([`lambert_term_narrow`]); elsewhere the high word of
/// `dot · 8w` rounded (the same quotient: numerator and divisor times 8), which with the
/// ambient add is one SMMLAR on Thumb-2.
#[inline(always)]
pub(crate) fn lambert_term(dot: i32, diff: i32) -> i32 {
    if crate::num::ARMV6M {
        lambert_term_narrow(dot, diff)
    } else {
        ((i64::from(dot) * i64::from(diff) + (1 << 31)) >> 32) as i32
    }
}

/// [`lambert_term`] without a 64-bit product: with `dot = h·2¹⁶ + m·2⁸ + n` (h < 2¹⁴,
/// m, n < 2⁸), `dot · w + 2²⁸ = 2¹⁶ · (h·w + q + 2¹²) + r` where `q = ⌊(m·w + ⌊n·w /
/// 2⁸⌋) / 2⁸⌋` = ⌊(m·2⁸ + n)·w / 2¹⁶⌋ (nested floors compose) and `0 ≤ r < 2¹⁶`, so
/// the term is `(h·w + q + 2¹²) >> 13` (r cannot carry past a multiple of 2¹³). Every
/// product is below 2³⁰ in magnitude.
#[inline(always)]
fn lambert_term_narrow(dot: i32, w: i32) -> i32 {
    let (h, m, n) = (dot >> 16, (dot >> 8) & 0xFF, dot & 0xFF);
    let q = (m * w + ((n * w) >> 8)) >> 8;
    (h * w + q + (1 << 12)) >> 13
}

/// What [`Renderer::light_block`] gives: the block of
/// [`lit_565`](crate::num::kernel::lit_565), the colour of a packed value and whether
/// that colour is the packed value ([`Raw565`](crate::shade::Raw565)).
pub(crate) type LitFaces<'m, C> = (
    LightBlock<'m>,
    fn(u16) -> C,
    Option<crate::shade::Raw565<C>>,
);

/// [`Renderer::lambert_q14`] for the renderer's `light_q`.
#[inline(always)]
fn lambert_q14_of(([lx, ly, lz], amb, diff): ([i32; 3], i64, i64), n: &[i16; 3]) -> Intensity {
    let dot = i32::from(n[0]) * lx + i32::from(n[1]) * ly + i32::from(n[2]) * lz;
    let term = lambert_term(dot.max(0), diff as i32);
    (amb as i32 + term).clamp(0, i32::from(u16::MAX)) as u16
}

/// Fills `cache` with the entries of `positions` (as many as it holds);
/// whether it knows that none is marked (where a vertex kernel filled it).
fn fill_cache(
    fixed: &FixedTransform,
    map: &ScreenMap,
    positions: &[[i16; 3]],
    cache: &mut [CachedVertex],
) -> bool {
    // The usual vertex by the vertex kernel (which only places), any other out of
    // line (on ARMv6-M always: the loop below is not built there).
    let mut placed = true;
    let kernel = map.place_all(fixed, positions, cache, |p| {
        let e = cache_entry(fixed, map, p);
        placed &= !e.marked();
        e
    });
    if kernel || crate::num::kernel::PLACE_V6M_KERNEL {
        return kernel && placed;
    }
    // x86-64: the usual vertex four at a time in SSE2, any other out of line.
    if PLACE4_KERNEL {
        if let Some(block) = map.place_block(fixed) {
            place_quads(&block, positions, cache, |p| cache_entry(fixed, map, p));
            return false;
        }
    }
    // w's bits beyond 31 at the previous vertex, for the next (project_fast).
    let mut sh_hint = W_SHIFT_HINT;
    for (p, slot) in positions.iter().zip(cache.iter_mut()) {
        // The usual vertex (project_vertex's fast path) here, any other out of line.
        let c = fixed.apply(p);
        let usual = if !crate::num::INTEGER_PROJECTION {
            map.project_float_inside(c.to_f32())
        } else if crate::num::ARMV6M {
            map.project_fast(&c, &mut sh_hint)
        } else {
            None
        };
        *slot = match usual.and_then(CachedVertex::placing) {
            Some(entry) => entry,
            None => cache_entry(fixed, map, p),
        };
    }
    false
}

/// The cache entry of position `p`, out of line: [`Renderer::project_vertex`]'s without
/// the fast path (for the vertices it does not place).
#[inline(never)]
fn cache_entry(fixed: &FixedTransform, map: &ScreenMap, p: &[i16; 3]) -> CachedVertex {
    let c = fixed.apply(p);
    let (code, screen) = if crate::num::INTEGER_PROJECTION {
        map.project_exact(&c)
    } else {
        map.classify_float(c.to_f32())
    };
    CachedVertex::new(code, screen)
}

/// A fetched vertex: screen position if inside (code 0), and its light.
#[derive(Clone, Copy)]
pub(crate) struct Fetched {
    index: u16,
    code: u8,
    screen: ScreenVertex,
    light: Intensity,
}

impl<'m, 'c, M: Copy> Renderer<'m, 'c, M> {
    /// A renderer that transforms vertices as faces need them (no cache memory; shared
    /// vertices are transformed once per face that uses them, and again in every band).
    ///
    /// Errors: a NaN/∞ or degenerate transform, a mesh scale that is not finite.
    pub fn new(mesh: &Mesh<'m, M>, xf: &Camera, options: RenderOptions) -> Result<Self, Error> {
        Self::build(mesh, xf, options, None)
    }

    /// [`new`](Renderer::new), and with `cache` [`with_cache`](Renderer::with_cache):
    /// the renderer made in the place it is returned to (a move of the 300-byte renderer
    /// is a copy), the cache filled before.
    #[inline(never)]
    fn build(
        mesh: &Mesh<'m, M>,
        xf: &Camera,
        options: RenderOptions,
        cache: Option<&'c mut [CachedVertex]>,
    ) -> Result<Self, Error> {
        mesh.check_for(options.shading)?;
        let mvp = xf.model_view_projection();
        let fixed = FixedTransform::new(&mvp, mesh.scale)?;
        if !(options.light.direction.is_finite()
            && crate::math::finite(options.light.ambient)
            && crate::math::finite(options.light.diffuse))
        {
            return Err(Error::NotFinite);
        }
        let light_model = xf
            .model
            .transpose_dir(options.light.direction.normalize())
            .normalize();
        let map = ScreenMap::new(&xf.viewport);
        let (cache, placed) = match cache {
            Some(cache) => {
                let cache = crate::error::prefix_mut(cache, mesh.positions.len())?;
                let placed = fill_cache(&fixed, &map, mesh.positions, cache);
                (Some(cache), placed)
            }
            None => (None, false),
        };
        Ok(Renderer {
            mesh: *mesh,
            fixed,
            map,
            options,
            light_model,
            light_q: (
                [light_model.x, light_model.y, light_model.z].map(round_q15),
                i64::from(round_q15(clamp2(options.light.ambient))),
                i64::from(round_q15(clamp2(options.light.diffuse))) << LAMBERT_SCALE,
            ),
            cache,
            placed,
            stats: FrameStats::default(),
            counted: false,
            see_through: None,
            binning: Binning::NotBanded,
            state: core::marker::PhantomData,
        })
    }

    /// A renderer that transforms every vertex once, now, into `cache` (one
    /// [`CachedVertex`] per mesh vertex, 8 bytes each).
    ///
    /// Errors: as [`new`](Renderer::new), and [`Error::BufferTooSmall`] for a short cache.
    pub fn with_cache(
        mesh: &Mesh<'m, M>,
        xf: &Camera,
        options: RenderOptions,
        cache: &'c mut [CachedVertex],
    ) -> Result<Self, Error> {
        Self::build(mesh, xf, options, Some(cache))
    }

    /// This renderer with the render state `T` fixed at compile time: a firmware that
    /// draws only with `T`'s depth test and shading carries only their code (see
    /// [`state`](crate::state)). `T`'s depth test replaces the Z-buffer's.
    ///
    /// ```
    /// # use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
    /// # use zraster::{math::{radians, Vec3}, mesh::CUBE, shade::Shading};
    /// # use zraster::{Camera, Frame, RenderOptions, Renderer, Viewport};
    /// use zraster::state::LambertLess;
    /// # let camera = Camera::look_at(Vec3::new(2.0, 1.5, 3.0), Vec3::new(0.5, 0.5, 0.5), Vec3::Y)?
    /// #     .perspective(radians(45.0), 0.1, 10.0, Viewport::new(32, 32)?)?;
    /// # let mut px = [Rgb565::BLACK; 32 * 32];
    /// # let mut depth = [0u16; 32 * 32];
    /// # let mut frame = Frame::new(&mut px, &mut depth, 32, 32)?;
    /// # frame.clear(Rgb565::BLACK);
    /// let options = RenderOptions { shading: Shading::Lambert, ..Default::default() };
    /// let mut renderer = Renderer::new(&CUBE, &camera, options)?.with_state::<LambertLess>()?;
    /// renderer.draw(&mut frame)?;
    /// assert_eq!(renderer.stats().drawn, 6);
    /// // A state that disagrees with the options is an error, not a silent override.
    /// let flat = RenderOptions::default(); // Shading::Flat
    /// assert!(Renderer::new(&CUBE, &camera, flat)?.with_state::<LambertLess>().is_err());
    /// # Ok::<(), zraster::Error>(())
    /// ```
    ///
    /// Errors: [`Error::InvalidParameter`] when `T` fixes a shading other than the
    /// options'.
    pub fn with_state<T: RenderState>(self) -> Result<Renderer<'m, 'c, M, T>, Error> {
        if T::SHADING.is_some_and(|s| s != self.options.shading) {
            return Err(Error::InvalidParameter(
                "the render state fixes another shading than the options'",
            ));
        }
        Ok(Renderer {
            mesh: self.mesh,
            fixed: self.fixed,
            map: self.map,
            options: self.options,
            light_model: self.light_model,
            light_q: self.light_q,
            cache: self.cache,
            placed: self.placed,
            stats: self.stats,
            counted: self.counted,
            see_through: self.see_through,
            binning: self.binning,
            state: core::marker::PhantomData,
        })
    }
}

impl<'m, 'c, M: Copy, S: RenderState> Renderer<'m, 'c, M, S> {
    /// The shading in use: the state's if it fixes one, else the options'.
    #[inline(always)]
    pub(crate) fn shading(&self) -> Shading {
        S::shading(self.options.shading)
    }

    /// The light of a drawn triangle's corners for the shading in use: full (flat), the
    /// face's Lambert light, or the vertices' own `vertex` lights (Gouraud).
    #[inline(always)]
    pub(crate) fn corner_lights(&self, f: usize, vertex: [Intensity; 3]) -> [Intensity; 3] {
        match self.shading() {
            Shading::Flat => [ONE; 3],
            Shading::Lambert => [self.face_light(f); 3],
            Shading::Gouraud => vertex,
        }
    }

    /// The counts so far (see [`FrameStats`]).
    pub fn stats(&self) -> FrameStats {
        self.stats
    }

    /// Whether the last draw into [`Bands`](crate::Bands) sorted the triangles into
    /// bins, and if not, why: without bins every band walks the whole mesh, which is
    /// slower but draws the same picture. [`Binning::NotBanded`](crate::Binning::NotBanded) before any banded draw.
    pub fn binning(&self) -> Binning {
        self.binning
    }

    /// Transform, classify and project position `p`: the clip coordinates exactly in
    /// integers, then on cores with an FPU the planes and the division in `f32`, on
    /// the others in integers (every path of a target projects the same way, so
    /// cached, banded and general drawing agree).
    #[inline(always)]
    pub(crate) fn project_vertex(&self, p: &[i16; 3]) -> (u8, ScreenVertex) {
        let c = self.fixed.apply(p);
        if crate::num::INTEGER_PROJECTION {
            self.map.project_fixed(&c)
        } else {
            self.map.project_float(c.to_f32())
        }
    }

    /// The clip coordinates of position `p` in `f32`, for clipping.
    #[inline]
    pub(crate) fn clip_coords(&self, p: &[i16; 3]) -> [f32; 4] {
        to_f32(&self.fixed.apply(p))
    }

    /// Transform, classify and project vertex `i`.
    fn transform(&self, i: u16) -> Result<Fetched, Error> {
        let p = self
            .mesh
            .positions
            .get(usize::from(i))
            .ok_or(Error::IndexOutOfRange {
                face: usize::MAX,
                index: usize::from(i),
            })?;
        let (code, screen) = self.project_vertex(p);
        let light = if self.shading() == Shading::Gouraud {
            self.vertex_light(usize::from(i))
        } else {
            ONE
        };
        Ok(Fetched {
            index: i,
            code,
            screen,
            light,
        })
    }

    #[inline]
    fn fetch(&self, i: u16, face: usize) -> Result<Fetched, Error> {
        let bad = || Error::IndexOutOfRange {
            face,
            index: usize::from(i),
        };
        let Some(cache) = &self.cache else {
            return self.transform(i).map_err(|_| bad());
        };
        let c = cache.get(usize::from(i)).ok_or_else(bad)?;
        if c.marked() && c.code() == 0 {
            // Inside, but too far out for the cache's 16 bits: projected again.
            return self.transform(i).map_err(|_| bad());
        }
        let light = if self.shading() == Shading::Gouraud {
            self.vertex_light(usize::from(i))
        } else {
            ONE
        };
        Ok(Fetched {
            index: i,
            code: c.code(),
            screen: c.screen(),
            light,
        })
    }

    /// Gouraud light of vertex `i` from the mesh's vertex normals (full light without).
    pub(crate) fn vertex_light(&self, i: usize) -> Intensity {
        match self.mesh.vertex_normals.and_then(|n| n.get(i)) {
            Some(n) => self.options.light.intensity(self.dot_q14(n)),
            None => ONE,
        }
    }

    pub(crate) fn dot_q14(&self, n: &[i16; 3]) -> f32 {
        let l = self.light_model;
        (f32::from(n[0]) * l.x + f32::from(n[1]) * l.y + f32::from(n[2]) * l.z) / NORMAL_ONE as f32
    }

    /// Lambert light of face `f` (inlined into the face loops).
    #[inline(always)]
    pub(crate) fn face_light(&self, f: usize) -> Intensity {
        match self.mesh.face_normals.and_then(|n| n.get(f)) {
            Some(n) => self.lambert_q14(n),
            None => self
                .options
                .light
                .intensity(face_normal(&self.mesh, f).map_or(0.0, |n| n.dot(self.light_model))),
        }
    }

    /// For the faces of one material `m` lit into a 5-6-5 colour: the block of
    /// [`lit_565`](crate::num::kernel::lit_565) (the colour [`face_light`] and `m`'s
    /// `shade` give, in one go, for a face with a normal) and the colour of a packed
    /// value.
    ///
    /// [`face_light`]: Renderer::face_light
    #[inline(always)]
    pub(crate) fn light_block<C>(&self, m: &M) -> Option<LitFaces<'m, C>>
    where
        M: Material<C>,
    {
        let (channels, color, raw) = m.packed_565()?;
        let (light, ambient, diffuse) = self.light_q;
        let normals = self.mesh.face_normals.unwrap_or(&[]);
        // Ambient within ±2¹⁶, diffuse within ±2¹⁹ (see `light_q`; ±2¹⁶ on ARMv6-M).
        let block = LightBlock::new(light, ambient as i32, diffuse as i32, channels, normals);
        Some((block, color, raw))
    }

    /// `ambient + diffuse · max(0, n·L)` for a Q14 unit normal, in integers: n·L is Q29
    /// and at most 2²⁹ in magnitude (two unit vectors), so it fits `i32`. Ambient and
    /// diffuse are Q15 within ±2: the diffuse term (see [`lambert_term`]) is within
    /// ±2¹⁶ and the sum within ±2¹⁷, so the sum and its clamp fit `i32` (one saturating
    /// instruction on a Cortex-M3/M4).
    #[inline]
    pub(crate) fn lambert_q14(&self, n: &[i16; 3]) -> Intensity {
        lambert_q14_of(self.light_q, n)
    }

    /// Face `f`'s vertex list, checked.
    pub(crate) fn face(&self, f: usize) -> Result<(&'m [u16], M), Error> {
        let (vs, m) = self
            .mesh
            .face(f)
            .ok_or(Error::CapacityExceeded { capacity: f })?;
        if vs.len() < 3 {
            return Err(Error::DegenerateFace { face: f });
        }
        Ok((vs, m))
    }

    /// Record the geometry counts of a frame (taken once, by its first pass).
    pub(crate) fn count(&mut self, geometry: FrameStats) {
        if !self.counted {
            let FrameStats {
                pixels_tested,
                pixels_written,
                runs,
                ..
            } = self.stats;
            self.stats = FrameStats {
                pixels_tested,
                pixels_written,
                runs,
                ..geometry
            };
            self.counted = true;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 5-6-5 face colour in one step (`num::kernel::lit_565`'s twin) is the
    /// renderer's: `lambert_q14` then the material's `shade`, in both packings, at every
    /// intensity (a light straight along the normal, no diffuse, the ambient the
    /// intensity) for materials of extreme and spread channels, then over random normals,
    /// lights and materials.
    #[test]
    fn the_one_step_face_colour_is_the_shaded_light() {
        use crate::num::kernel::{lit_565_portable, LightBlock};
        use embedded_graphics::pixelcolor::{Bgr565, Rgb565, Rgb888};
        use embedded_graphics::prelude::{IntoStorage, RgbColor};
        let check = |light_q: ([i32; 3], i64, i64), n: [i16; 3], m: Rgb888| {
            let i = lambert_q14_of(light_q, &n);
            let (l, a, d) = light_q;
            let rgb: Rgb565 = m.shade(i, 0, 0);
            let bgr: Bgr565 = m.shade(i, 0, 0);
            let normals = [n];
            let block = |ch| LightBlock::new(l, a as i32, d as i32, ch, &normals);
            let want = (Some(rgb.into_storage()), Some(bgr.into_storage()));
            let got = (
                lit_565_portable(0, &block([m.r(), m.g(), m.b()])),
                lit_565_portable(0, &block([m.b(), m.g(), m.r()])),
            );
            assert_eq!(got, want, "{light_q:?} {n:?} {m:?} i {i}");
        };
        let mut rnd = crate::num::kernel::xorshift32(0x5eed_1175_u32);
        let values = [0u8, 1, 2, 7, 8, 127, 128, 200, 253, 254, 255];
        for (k, &v) in values.iter().enumerate() {
            let m = Rgb888::new(v, values[(k + 3) % values.len()], rnd() as u8);
            for i in 0..=i64::from(u16::MAX) {
                check(([32768, 0, 0], i, 0), [16384, 0, 0], m);
            }
            // Past either end of the intensity.
            for i in [-65536, -1, 65536] {
                check(([32768, 0, 0], i, 0), [16384, 0, 0], m);
            }
        }
        for _ in 0..200_000 {
            let mut r = || rnd();
            let n = [0; 3].map(|_| ((r() % 32769) as i32 - 16384) as i16);
            let l = [0; 3].map(|_| (r() % 65537) as i32 - 32768);
            let (a, d) = (
                i64::from((r() % 131_073) as i32 - 65536),
                i64::from((r() % 131_073) as i32 - 65536) << LAMBERT_SCALE,
            );
            check((l, a, d), n, Rgb888::new(r() as u8, r() as u8, r() as u8));
        }
    }

    /// The diffuse term in either form is the rounded quotient it stands for, over the
    /// extremes and a spread of products.
    #[test]
    fn lambert_term_is_the_rounded_quotient() {
        let weights = [
            -65536, -40000, -32768, -1, 0, 1, 6554, 26214, 32768, 65535, 65536,
        ];
        let edges = [0, 1, 2, (1 << 28) - 1, 1 << 28, (1 << 29) - 1, 1 << 29];
        let spread = (0..20_000u32).scan(12345u32, |x, _| {
            *x = x.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            Some((*x >> 3) as i32)
        });
        let dots = || edges.into_iter().chain(spread.clone());
        let check = |dot: i32, w: i32| {
            let want = ((i64::from(dot) * i64::from(w) + (1 << 28)) >> 29) as i32;
            assert_eq!(lambert_term(dot, w << LAMBERT_SCALE), want, "{dot} {w}");
            assert_eq!(lambert_term_narrow(dot, w), want, "{dot} {w}");
        };
        for w in weights {
            dots().for_each(|dot| check(dot, w));
        }
        // Every 7th weight against the edges and a few hundred products.
        for w in (-65536..=65536).step_by(7) {
            dots().take(300).for_each(|dot| check(dot, w));
        }
    }
}
