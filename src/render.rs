//! The renderers: from a mesh and a transform to pixels.
//!
//! One [`Renderer`] holds a frame's geometry state (the fixed-point transform, the
//! light in model space and, optionally, a cache of transformed vertices) and draws it
//! in any of four ways: with the Z-buffer ([`draw`](Renderer::draw)), by depth sorting
//! ([`draw_depth_sorted`](Renderer::draw_depth_sorted)), as hidden-line
//! ([`draw_hidden_line`](Renderer::draw_hidden_line)) or as wireframe
//! ([`draw_wireframe`](Renderer::draw_wireframe)). Each call draws into one target,
//! which may be the whole screen or one band of it.

use embedded_graphics::{pixelcolor::PixelColor, prelude::DrawTarget};

use crate::band::{Carry, ColorCarry};
use crate::camera::Transform;
use crate::fill::{clip_of, depth_runs, fill_flat_buffered, shade_triangle, FlatTarget};
use crate::geometry::clip::{clip_polygon, clip_segment, ClipPolygon, ClipVertex};
use crate::geometry::project::{outcode_of, to_f32, ScreenMap};
use crate::geometry::transform::FixedTransform;
use crate::math::Vec3;
use crate::mesh::{face_normal, Faces, Mesh, NORMAL_ONE};
use crate::raster::{
    draw_line, signed_area, signed_area_guarded, Clip, Plane, ScreenVertex, SpanStats,
};
use crate::shade::{Intensity, Light, Material, Shading, ONE};
use crate::{ColorBuffer, DrawError, Error, ZBuffer};

/// `$body` with `$shade` bound to the colour of a face (`Fn(usize) -> Result<C, Error>`)
/// for the renderer's materials and shading, in one arm for each way of colouring (one
/// colour for all; a uniform material, lit; a material per face), so that the loop in
/// `$body` is instantiated for each and does not ask which it is for every face.
macro_rules! per_colouring {
    ($r:expr, $materials:expr, $lambert:expr, |$shade:ident| $body:expr) => {
        match ($r.flat_color($materials, $lambert), $materials) {
            (Some(c), _) => {
                let $shade = |_: usize| Ok(c);
                $body
            }
            // A uniform material without one colour for all is lit.
            (None, crate::mesh::Materials::Uniform(m)) => {
                let $shade = |f: usize| Ok(m.shade($r.face_light(f), 0, 0));
                $body
            }
            (None, _) => {
                let $shade = |f: usize| $r.face_color($materials, $lambert, f);
                $body
            }
        }
    };
}

/// Which faces are dropped before rasterization, by their winding on screen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum Cull {
    /// Drop faces seen from behind (the default: closed solids).
    #[default]
    Back,
    /// Drop faces seen from the front.
    Front,
    /// Draw both sides.
    None,
}

impl Cull {
    /// Is a triangle with twice-signed *screen* area `area` ([`signed_area`] of y-down
    /// screen coordinates) dropped? Front faces have negative screen area (they are
    /// counter-clockwise with y up). Zero area always is dropped.
    #[inline]
    pub fn drops(self, area: i64) -> bool {
        match self {
            Cull::Back => area >= 0,
            Cull::Front => area <= 0,
            Cull::None => area == 0,
        }
    }
}

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
    /// Runs handed to the draw target (the fused path of
    /// [`Renderer::draw_buffer`] writes pixels directly and hands over none).
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

    fn add_pixel_counts(&mut self, o: &FrameStats) {
        self.pixels_tested += o.pixels_tested;
        self.pixels_written += o.pixels_written;
        self.runs += o.runs;
    }

    fn add_pixels(&mut self, s: SpanStats) {
        self.add_fill(s);
        self.runs += u64::from(s.runs);
    }

    /// Add the pixel counts of `s`, which has no runs (a fill into buffers).
    #[inline(always)]
    fn add_fill(&mut self, s: SpanStats) {
        self.pixels_tested += u64::from(s.pixels_tested);
        self.pixels_written += u64::from(s.pixels_written);
    }
}

/// Whether `tri` lies wholly above or below rows `row0..row1` (in 1/16 pixel): later
/// passes (bands) skip such triangles before anything else.
#[inline(always)]
fn outside_rows(tri: &[ScreenVertex; 3], row0: i32, row1: i32) -> bool {
    let ymin = tri[0].y().min(tri[1].y()).min(tri[2].y());
    let ymax = tri[0].y().max(tri[1].y()).max(tri[2].y());
    ymax + 8 < row0 || ymin + 8 > row1
}

/// The cached vertices of triangle `f` (indices `t`), or the error naming the index
/// the cache does not hold.
#[inline(always)]
pub(crate) fn cached_triangle<'c>(
    cache: &'c [CachedVertex],
    f: usize,
    t: &[u16; 3],
) -> Result<[&'c CachedVertex; 3], Error> {
    let get = |i: u16| {
        cache.get(usize::from(i)).ok_or(Error::IndexOutOfRange {
            face: f,
            index: usize::from(i),
        })
    };
    Ok([get(t[0])?, get(t[1])?, get(t[2])?])
}

/// Whether `cull` drops `tri`.
#[inline(always)]
pub(crate) fn culled(tri: &[ScreenVertex; 3], cull: Cull) -> bool {
    let p = |v: &ScreenVertex| (v.x(), v.y());
    cull.drops(signed_area_guarded(p(&tri[0]), p(&tri[1]), p(&tri[2])))
}

/// A vertex transformed and projected once per frame (16 bytes), so that every band
/// and every face sharing it reuses the work. See [`Renderer::with_cache`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CachedVertex {
    screen: ScreenVertex,
    code: u8,
    light: Intensity,
}

impl CachedVertex {
    #[inline]
    pub(crate) fn code(&self) -> u8 {
        self.code
    }

    #[inline]
    pub(crate) fn screen(&self) -> ScreenVertex {
        self.screen
    }

    /// An empty entry, to initialise cache arrays.
    pub const EMPTY: CachedVertex = CachedVertex {
        screen: ScreenVertex::ORIGIN,
        code: 0,
        light: 0,
    };
}

impl Default for CachedVertex {
    fn default() -> Self {
        CachedVertex::EMPTY
    }
}

/// A capacity-bounded list for the depth-sort (painter's) renderer: one entry (8
/// bytes) per face. More faces than `N` is [`Error::CapacityExceeded`].
#[derive(Debug, Default)]
pub struct DepthSort<const N: usize> {
    items: heapless::Vec<(i32, u16), N>,
}

impl<const N: usize> DepthSort<N> {
    /// An empty list.
    pub const fn new() -> Self {
        DepthSort {
            items: heapless::Vec::new(),
        }
    }

    /// The faces in drawing order (farthest first) after the last sort.
    pub fn order(&self) -> impl Iterator<Item = usize> + '_ {
        self.items.iter().map(|&(_, f)| usize::from(f))
    }
}

/// The triangles of a polygon fanned around its first vertex.
fn fan(vs: &[u16]) -> impl Iterator<Item = (u16, u16, u16)> + '_ {
    let (first, rest) = vs.split_first().map_or((0, &[][..]), |(f, r)| (*f, r));
    rest.windows(2).filter_map(move |w| match *w {
        [b, c] => Some((first, b, c)),
        _ => None,
    })
}

/// The edges of a polygon, the closing one included.
fn edges(vs: &[u16]) -> impl Iterator<Item = (u16, u16)> + '_ {
    vs.iter().copied().zip(vs.iter().copied().cycle().skip(1))
}

/// Draws one mesh, placed by one transform, into targets with the methods below.
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb565;
/// use embedded_graphics::prelude::*;
/// use zraster::{math::{Mat4, Vec3}, mesh::CUBE, camera::{Transform, Viewport}};
/// use zraster::{ColorBuffer, Renderer, RenderOptions, ZBuffer};
///
/// let vp = Viewport::new(64, 48)?;
/// let xf = Transform::perspective(Vec3::new(2.0, 1.5, 3.0), Vec3::new(0.5, 0.5, 0.5), 45.0, 0.1, 10.0, vp)?;
/// let mut pixels = [Rgb565::BLACK; 64 * 48];
/// let mut depth = [0u16; 64 * 48];
/// let mut frame = ColorBuffer::new(&mut pixels, 64, 48)?;
/// let mut zbuf = ZBuffer::new(&mut depth, 64, 48)?;
/// zbuf.clear();
/// let mut renderer = Renderer::new(&CUBE, &xf, RenderOptions::default())?;
/// renderer.draw(&mut frame, &mut zbuf).unwrap();
/// // Three faces of the cube face the camera.
/// assert_eq!(renderer.stats().drawn, 6);
/// assert_eq!(frame.pixel(32, 24), Some(Rgb565::new(0, 0, 31))); // the blue front face
/// # Ok::<(), zraster::Error>(())
/// ```
pub struct Renderer<'m, 'c, M> {
    pub(crate) mesh: Mesh<'m, M>,
    fixed: FixedTransform,
    map: ScreenMap,
    pub(crate) options: RenderOptions,
    /// Unit light direction in model space, for model-space normals.
    light_model: Vec3,
    /// The light for Q14 normals: `L` in Q15, and the ambient and diffuse weights in Q15.
    light_q: ([i32; 3], i64, i64),
    pub(crate) cache: Option<&'c mut [CachedVertex]>,
    stats: FrameStats,
    counted: bool,
}

/// A fetched vertex: screen position if inside (code 0), and its light.
#[derive(Clone, Copy)]
struct Fetched {
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
    pub fn new(mesh: &Mesh<'m, M>, xf: &Transform, options: RenderOptions) -> Result<Self, Error> {
        let mvp = xf.model_view_projection();
        let fixed = FixedTransform::new(&mvp, mesh.scale)?;
        if !(options.light.direction.is_finite()
            && options.light.ambient.is_finite()
            && options.light.diffuse.is_finite())
        {
            return Err(Error::NotFinite);
        }
        let light_model = xf
            .model
            .transpose_dir(options.light.direction.normalize())
            .normalize();
        Ok(Renderer {
            mesh: *mesh,
            fixed,
            map: ScreenMap::new(&xf.viewport),
            options,
            light_model,
            light_q: (
                [light_model.x, light_model.y, light_model.z]
                    .map(|c| crate::num::round_f32(c * 32768.0)),
                i64::from(crate::num::round_f32(
                    options.light.ambient.clamp(-2.0, 2.0) * 32768.0,
                )),
                i64::from(crate::num::round_f32(
                    options.light.diffuse.clamp(-2.0, 2.0) * 32768.0,
                )),
            ),
            cache: None,
            stats: FrameStats::default(),
            counted: false,
        })
    }

    /// A renderer that transforms every vertex once, now, into `cache` (one
    /// [`CachedVertex`] per mesh vertex, 16 bytes each).
    ///
    /// Errors: as [`new`](Renderer::new), and [`Error::BufferTooSmall`] for a short cache.
    pub fn with_cache(
        mesh: &Mesh<'m, M>,
        xf: &Transform,
        options: RenderOptions,
        cache: &'c mut [CachedVertex],
    ) -> Result<Self, Error> {
        let mut r = Self::new(mesh, xf, options)?;
        let n = mesh.positions.len();
        let cache = crate::error::prefix_mut(cache, n)?;
        // Positions first, vertex lights (Gouraud only) in a pass of their own: the
        // projection loop then does not ask for each vertex which shading it is.
        for (p, slot) in mesh.positions.iter().zip(cache.iter_mut()) {
            let (code, screen) = r.map.project_fixed(&r.fixed.apply(p));
            *slot = CachedVertex {
                screen,
                code,
                light: ONE,
            };
        }
        if options.shading == Shading::Gouraud {
            for (i, slot) in cache.iter_mut().enumerate() {
                slot.light = r.vertex_light(i);
            }
        }
        r.cache = Some(cache);
        Ok(r)
    }

    /// The counts so far (see [`FrameStats`]).
    pub fn stats(&self) -> FrameStats {
        self.stats
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
        let (code, screen) = self.map.project_fixed(&self.fixed.apply(p));
        let light = if self.options.shading == Shading::Gouraud {
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
        let bad = Error::IndexOutOfRange {
            face,
            index: usize::from(i),
        };
        match &self.cache {
            Some(cache) => {
                let c = cache.get(usize::from(i)).ok_or(bad)?;
                Ok(Fetched {
                    index: i,
                    code: c.code,
                    screen: c.screen,
                    light: c.light,
                })
            }
            None => self.transform(i).map_err(|_| bad),
        }
    }

    /// Gouraud light of vertex `i` from the mesh's vertex normals (full light without).
    fn vertex_light(&self, i: usize) -> Intensity {
        match self.mesh.vertex_normals.and_then(|n| n.get(i)) {
            Some(n) => self.options.light.intensity(self.dot_q14(n)),
            None => ONE,
        }
    }

    fn dot_q14(&self, n: &[i16; 3]) -> f32 {
        let l = self.light_model;
        (f32::from(n[0]) * l.x + f32::from(n[1]) * l.y + f32::from(n[2]) * l.z) / NORMAL_ONE as f32
    }

    /// Lambert light of face `f` (inlined into the face loops).
    #[inline(always)]
    fn face_light(&self, f: usize) -> Intensity {
        match self.mesh.face_normals.and_then(|n| n.get(f)) {
            Some(n) => self.lambert_q14(n),
            None => self
                .options
                .light
                .intensity(face_normal(&self.mesh, f).map_or(0.0, |n| n.dot(self.light_model))),
        }
    }

    /// `ambient + diffuse · max(0, n·L)` for a Q14 unit normal, in integers: n·L is Q29
    /// and at most 2²⁹ in magnitude (two unit vectors), so it fits `i32`. Ambient and
    /// diffuse are Q15 within ±2: the product is below 2⁴⁶ (in `i64`), the diffuse term
    /// then within ±2¹⁶ and the sum within ±2¹⁷, so the sum and its clamp fit `i32`
    /// (one saturating instruction on a Cortex-M3/M4).
    #[inline]
    fn lambert_q14(&self, n: &[i16; 3]) -> Intensity {
        let ([lx, ly, lz], amb, diff) = self.light_q;
        let dot = i32::from(n[0]) * lx + i32::from(n[1]) * ly + i32::from(n[2]) * lz;
        // |diff| ≤ 2¹⁶: on ARMv6-M three 32-bit multiplies instead of a library call.
        let product = crate::num::mul_i64_i32(i64::from(dot.max(0)), diff as i32);
        let term = ((product + (1 << 28)) >> 29) as i32;
        (amb as i32 + term).clamp(0, i32::from(u16::MAX)) as u16
    }

    /// Face `f`'s vertex list, checked.
    fn face(&self, f: usize) -> Result<(&'m [u16], M), Error> {
        let (vs, m) = self
            .mesh
            .face(f)
            .ok_or(Error::CapacityExceeded { capacity: f })?;
        if vs.len() < 3 {
            return Err(Error::DegenerateFace { face: f });
        }
        Ok((vs, m))
    }

    /// Walk every triangle (fan-triangulated faces) that survives clipping and culling,
    /// calling `emit(face, screen triangle, vertex lights)`; returns the geometry counts.
    fn for_each_triangle<E>(
        &self,
        clip: &Clip,
        first: bool,
        faces: impl Iterator<Item = usize>,
        mut emit: impl FnMut(usize, M, &[ScreenVertex; 3], [Intensity; 3]) -> Result<(), DrawError<E>>,
    ) -> Result<FrameStats, DrawError<E>> {
        let mut st = FrameStats::default();
        let cull = self.options.cull;
        let (row0, row1) = clip.subpixel_rows();
        for f in faces {
            let (vs, mat) = self.face(f)?;
            for (i0, i1, i2) in fan(vs) {
                let v0 = self.fetch(i0, f)?;
                let v1 = self.fetch(i1, f)?;
                let v2 = self.fetch(i2, f)?;
                st.triangles_in += 1;
                if v0.code & v1.code & v2.code != 0 {
                    st.outside += 1;
                    continue;
                }
                if v0.code | v1.code | v2.code == 0 {
                    let tri = [v0.screen, v1.screen, v2.screen];
                    if !first && outside_rows(&tri, row0, row1) {
                        continue;
                    }
                    if culled(&tri, cull) {
                        st.culled += 1;
                        continue;
                    }
                    st.drawn += 1;
                    emit(f, mat, &tri, [v0.light, v1.light, v2.light])?;
                    continue;
                }
                st.clipped += 1;
                let mut poly = ClipPolygon::new();
                for v in [&v0, &v1, &v2] {
                    let p = self.mesh.positions.get(usize::from(v.index)).ok_or(
                        Error::IndexOutOfRange {
                            face: f,
                            index: usize::from(v.index),
                        },
                    )?;
                    let light = if self.options.shading == Shading::Gouraud {
                        f32::from(self.vertex_light(usize::from(v.index)))
                    } else {
                        f32::from(ONE)
                    };
                    let _ = poly.push(ClipVertex {
                        c: to_f32(&self.fixed.apply(p)),
                        light,
                    });
                }
                clip_polygon(&mut poly, v0.code | v1.code | v2.code);
                let mut out: heapless::Vec<
                    (ScreenVertex, Intensity),
                    { crate::geometry::clip::MAX_CLIPPED },
                > = heapless::Vec::new();
                for c in &poly {
                    if let Some(s) = self.map.project(&c.c) {
                        let _ = out.push((s, crate::shade::to_intensity(c.light / f32::from(ONE))));
                    }
                }
                let Some((&a, rest)) = out.split_first() else {
                    continue;
                };
                for pair in rest.windows(2) {
                    let &[b, c] = pair else { continue };
                    let tri = [a.0, b.0, c.0];
                    let p = |v: &ScreenVertex| (v.x(), v.y());
                    if cull.drops(signed_area_guarded(p(&tri[0]), p(&tri[1]), p(&tri[2]))) {
                        continue;
                    }
                    st.drawn += 1;
                    emit(f, mat, &tri, [a.1, b.1, c.1])?;
                }
            }
        }
        Ok(st)
    }

    /// The geometry counts of face `f` alone, drawing nothing.
    pub(crate) fn count_one(
        &self,
        f: usize,
    ) -> Result<FrameStats, DrawError<core::convert::Infallible>> {
        let clip = Clip {
            x0: 0,
            y0: 0,
            x1: 0,
            y1: 0,
        };
        self.for_each_triangle(&clip, true, core::iter::once(f), |_, _, _, _| Ok(()))
    }

    /// Draw a band's listed faces of a cached triangle mesh, in face order. All but the
    /// tall ones ([`Carry::Tall`]) are known to be unclipped, front-facing (as the
    /// options cull) and to reach the rows of `frame`, so those tests are skipped for
    /// them. Colours pass between bands through `carry` as each face's [`Carry`] says.
    pub(crate) fn draw_band_faces<C>(
        &mut self,
        frame: &mut ColorBuffer<'_, C>,
        zbuf: &mut ZBuffer<'_>,
        faces: impl Iterator<Item = (usize, Carry)>,
        carry: &mut ColorCarry<C>,
    ) -> Result<(), Error>
    where
        C: PixelColor,
        M: Material<C>,
    {
        let Faces::Triangles { indices, materials } = self.mesh.faces else {
            return self.draw_buffer(frame, zbuf);
        };
        let lambert = self.options.shading == Shading::Lambert;
        carry.start_band();
        // One loop for each way of colouring a face, as in `draw_buffer_triangles`.
        let px = per_colouring!(self, materials, lambert, |shade| {
            self.band_loop(frame, zbuf, indices, faces, carry, shade)?
        });
        self.stats.add_pixel_counts(&px);
        Ok(())
    }

    /// The loop of [`draw_band_faces`](Renderer::draw_band_faces), with the faces'
    /// colours from `shade` unless carried; returns the pixel counts.
    #[inline(always)]
    fn band_loop<C>(
        &self,
        frame: &mut ColorBuffer<'_, C>,
        zbuf: &mut ZBuffer<'_>,
        indices: &'m [[u16; 3]],
        faces: impl Iterator<Item = (usize, Carry)>,
        carry: &mut ColorCarry<C>,
        shade: impl Fn(usize) -> Result<C, Error>,
    ) -> Result<FrameStats, Error>
    where
        C: PixelColor,
        M: Material<C>,
    {
        let mut px = FrameStats::default();
        let Some(cache) = self.cache.as_deref() else {
            return Ok(px);
        };
        let clip = clip_of(frame, zbuf);
        let (row0, row1) = clip.subpixel_rows();
        let mut target = FlatTarget::new(frame, zbuf, &clip);
        for (f, how) in faces {
            let Some(t) = indices.get(f) else { continue };
            let [a, b, c] = cached_triangle(cache, f, t)?;
            let tri = [&a.screen, &b.screen, &c.screen];
            if how == Carry::Tall {
                // Drawn in every band: clipped by the general path, or skipped when it
                // does not reach this band's rows.
                if a.code | b.code | c.code != 0 {
                    px.add_pixels(self.draw_clipped_face(&mut target, &clip, false, f)?.1);
                    continue;
                }
                if outside_rows(&[a.screen, b.screen, c.screen], row0, row1) {
                    continue;
                }
            }
            // One call of `shade` (so that it is inlined): carried, or worked out.
            let carried = if how == Carry::Take {
                carry.take()
            } else {
                None
            };
            let color = match carried {
                Some(c) => c,
                None => shade(f)?,
            };
            if how == Carry::Keep {
                carry.keep(color);
            }
            px.add_fill(target.fill(tri, color));
        }
        Ok(px)
    }

    /// The one colour of every face when it does not depend on the face (a uniform
    /// material, unlit).
    fn flat_color<C>(&self, materials: crate::mesh::Materials<'m, M>, lambert: bool) -> Option<C>
    where
        M: Material<C>,
    {
        match materials {
            crate::mesh::Materials::Uniform(m) if !lambert => Some(m.shade(ONE, 0, 0)),
            _ => None,
        }
    }

    /// Face `f`'s flat colour: its material, lit by the face's Lambert intensity (or
    /// unlit).
    #[inline(always)]
    fn face_color<C>(
        &self,
        materials: crate::mesh::Materials<'m, M>,
        lambert: bool,
        f: usize,
    ) -> Result<C, Error>
    where
        M: Material<C>,
    {
        let m = match materials {
            crate::mesh::Materials::Uniform(m) => m,
            crate::mesh::Materials::PerFace(ms) => {
                *ms.get(f).ok_or(Error::CapacityExceeded { capacity: f })?
            }
        };
        Ok(m.shade(if lambert { self.face_light(f) } else { ONE }, 0, 0))
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

    /// Draw with the Z-buffer: every visible triangle, depth-tested per pixel, in the
    /// mesh's materials and the chosen shading.
    ///
    /// `target` and `zbuf` may cover the whole screen or one band of it (rows the
    /// Z-buffer does not hold are not drawn). Clear both before the first call of a
    /// frame (or band).
    pub fn draw<D>(
        &mut self,
        target: &mut D,
        zbuf: &mut ZBuffer<'_>,
    ) -> Result<(), DrawError<D::Error>>
    where
        D: DrawTarget,
        M: Material<D::Color>,
    {
        let clip = clip_of(target, zbuf);
        let mut pixels = FrameStats::default();
        let shading = self.options.shading;
        let first = !self.counted;
        let geometry = self.for_each_triangle(
            &clip,
            first,
            0..self.mesh.face_count(),
            |f, mat, tri, lights| {
                let lights = match shading {
                    Shading::Flat => [ONE; 3],
                    Shading::Lambert => [self.face_light(f); 3],
                    Shading::Gouraud => lights,
                };
                let s = shade_triangle(target, Some(&mut *zbuf), &clip, tri, mat, lights)
                    .map_err(DrawError::Target)?;
                pixels.add_pixels(s);
                Ok(())
            },
        )?;
        self.count(geometry);
        self.stats.add_pixel_counts(&pixels);
        Ok(())
    }

    /// Draw with the Z-buffer into a [`ColorBuffer`]: the same pixels as
    /// [`draw`](Renderer::draw), faster, since the depth test and the colour write
    /// share one loop instead of handing runs to a `DrawTarget`. Flat-coloured faces
    /// (flat shading, Lambert) take this path; Gouraud and dithered materials go through
    /// the buffer's `DrawTarget` runs.
    pub fn draw_buffer<C>(
        &mut self,
        frame: &mut ColorBuffer<'_, C>,
        zbuf: &mut ZBuffer<'_>,
    ) -> Result<(), Error>
    where
        C: PixelColor,
        M: Material<C>,
    {
        let fast = !M::DITHERED && matches!(self.options.shading, Shading::Flat | Shading::Lambert);
        if let (true, Some(_), Faces::Triangles { indices, materials }) =
            (fast, &self.cache, self.mesh.faces)
        {
            return self.draw_buffer_triangles(frame, zbuf, indices, materials, 0..indices.len());
        }
        let clip = clip_of(frame, zbuf);
        let mut pixels = FrameStats::default();
        let shading = self.options.shading;
        let first = !self.counted;
        let geometry = self
            .for_each_triangle::<core::convert::Infallible>(
                &clip,
                first,
                0..self.mesh.face_count(),
                |f, mat, tri, lights| {
                    let s = match shading {
                        Shading::Flat if !M::DITHERED => {
                            fill_flat_buffered(frame, zbuf, &clip, tri, mat.shade(ONE, 0, 0))
                        }
                        Shading::Lambert if !M::DITHERED => fill_flat_buffered(
                            frame,
                            zbuf,
                            &clip,
                            tri,
                            mat.shade(self.face_light(f), 0, 0),
                        ),
                        _ => {
                            let lights = match shading {
                                Shading::Flat => [ONE; 3],
                                Shading::Lambert => [self.face_light(f); 3],
                                Shading::Gouraud => lights,
                            };
                            shade_triangle(frame, Some(&mut *zbuf), &clip, tri, mat, lights)
                                .map_err(DrawError::Target)?
                        }
                    };
                    pixels.add_pixels(s);
                    Ok(())
                },
            )
            .map_err(|e| match e {
                DrawError::Input(e) => e,
                DrawError::Target(never) => match never {},
            })?;
        self.count(geometry);
        self.stats.add_pixel_counts(&pixels);
        Ok(())
    }

    /// A face near a clip plane in [`draw_buffer_triangles`]: clipped, culled and drawn
    /// by the general path. Out of line, as it is rare.
    #[inline(never)]
    fn draw_clipped_face<C>(
        &self,
        target: &mut FlatTarget<'_, '_, '_, C>,
        clip: &Clip,
        first: bool,
        f: usize,
    ) -> Result<(FrameStats, SpanStats), Error>
    where
        C: PixelColor,
        M: Material<C>,
    {
        let lambert = self.options.shading == Shading::Lambert;
        let mut more = SpanStats::default();
        let g = self
            .for_each_triangle::<core::convert::Infallible>(
                clip,
                first,
                core::iter::once(f),
                |f, mat, tri, _| {
                    let i = if lambert { self.face_light(f) } else { ONE };
                    more += target.fill(tri.each_ref(), mat.shade(i, 0, 0));
                    Ok(())
                },
            )
            .map_err(|e| match e {
                DrawError::Input(e) => e,
                DrawError::Target(never) => match never {},
            })?;
        Ok((g, more))
    }

    /// [`draw_buffer`](Renderer::draw_buffer) for a cached triangle list with flat colours:
    /// one tight loop over the triangles, instantiated for each way of colouring a face
    /// (one colour; one material, lit; a material per face), so that the loop does not
    /// ask which it is for every face. Faces near the clip planes go through the general
    /// path.
    fn draw_buffer_triangles<C>(
        &mut self,
        frame: &mut ColorBuffer<'_, C>,
        zbuf: &mut ZBuffer<'_>,
        indices: &'m [[u16; 3]],
        materials: crate::mesh::Materials<'m, M>,
        faces: impl Iterator<Item = usize>,
    ) -> Result<(), Error>
    where
        C: PixelColor,
        M: Material<C>,
    {
        let lambert = self.options.shading == Shading::Lambert;
        let (st, px) = per_colouring!(self, materials, lambert, |shade| {
            self.cull_and_fill(frame, zbuf, indices, faces, shade)?
        });
        self.count(st);
        self.stats.add_pixel_counts(&px);
        Ok(())
    }

    /// The loop of [`draw_buffer_triangles`](Renderer::draw_buffer_triangles), with the
    /// faces' colours from `shade`; returns the geometry and pixel counts.
    #[inline(always)]
    fn cull_and_fill<C>(
        &self,
        frame: &mut ColorBuffer<'_, C>,
        zbuf: &mut ZBuffer<'_>,
        indices: &'m [[u16; 3]],
        faces: impl Iterator<Item = usize>,
        shade: impl Fn(usize) -> Result<C, Error>,
    ) -> Result<(FrameStats, FrameStats), Error>
    where
        C: PixelColor,
        M: Material<C>,
    {
        let clip = clip_of(frame, zbuf);
        let first = !self.counted;
        let cull = self.options.cull;
        let (row0, row1) = clip.subpixel_rows();
        let mut st = FrameStats::default();
        let mut px = FrameStats::default();
        let Some(cache) = self.cache.as_deref() else {
            return Ok((st, px));
        };
        let mut target = FlatTarget::new(frame, zbuf, &clip);
        let mut faces = faces;
        loop {
            // The faces up to the next one to draw, in a loop of their own: most are
            // culled, and without the drawing's calls in it the loop keeps its state in
            // registers.
            let next = loop {
                let Some(f) = faces.next() else { break None };
                let Some(t) = indices.get(f) else { continue };
                let [a, b, c] = cached_triangle(cache, f, t)?;
                if a.code | b.code | c.code != 0 {
                    break Some((f, None));
                }
                st.triangles_in += 1;
                if !first && outside_rows(&[a.screen, b.screen, c.screen], row0, row1) {
                    continue;
                }
                // The test of `culled`, written out (the helper's array copy costs).
                let p = |v: &CachedVertex| (v.screen.x(), v.screen.y());
                if cull.drops(signed_area_guarded(p(a), p(b), p(c))) {
                    st.culled += 1;
                    continue;
                }
                st.drawn += 1;
                break Some((f, Some([&a.screen, &b.screen, &c.screen])));
            };
            let Some((f, tri)) = next else { break };
            let Some(tri) = tri else {
                // Outside or across a clip plane: the general path (rare).
                let (g, more) = self.draw_clipped_face(&mut target, &clip, first, f)?;
                st.add_geometry(&g);
                px.add_pixels(more);
                continue;
            };
            px.add_fill(target.fill(tri, shade(f)?));
        }
        Ok((st, px))
    }

    /// Draw by depth sorting (the painter's algorithm of the seeds): faces sorted by the
    /// depth of their centroid, drawn farthest first with no Z-buffer. Cheap in RAM,
    /// and wrong exactly where the seeds say: cyclic overlap, interpenetration.
    ///
    /// Errors: [`Error::CapacityExceeded`] when the mesh has more than `N` faces.
    pub fn draw_depth_sorted<D, const N: usize>(
        &mut self,
        target: &mut D,
        sort: &mut DepthSort<N>,
    ) -> Result<(), DrawError<D::Error>>
    where
        D: DrawTarget,
        M: Material<D::Color>,
    {
        sort.items.clear();
        let n = self.mesh.face_count();
        if n > N || n > usize::from(u16::MAX) + 1 {
            return Err(Error::CapacityExceeded { capacity: N }.into());
        }
        for f in 0..n {
            let (vs, _) = self.face(f)?;
            // In i128: a face may list any number of vertices, each |z| < 2⁴⁵.
            let mut sum = 0i128;
            for &v in vs {
                let p = self
                    .mesh
                    .positions
                    .get(usize::from(v))
                    .ok_or(Error::IndexOutOfRange {
                        face: f,
                        index: usize::from(v),
                    })?;
                // Clip-space z grows with distance from the eye (for both projections).
                sum += i128::from(self.fixed.apply(p).zw().0);
            }
            // The mean |z| < 2⁴⁵ (clip-space scale): dropping 16 bits keeps the order and
            // fits i32.
            let key = ((sum / vs.len() as i128) >> 16) as i32;
            let _ = sort.items.push((key, f as u16));
        }
        // Farthest (largest z) first; equal depths keep the face order.
        sort.items
            .sort_unstable_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
        let clip = Clip::from_rect(&target.bounding_box());
        let mut pixels = FrameStats::default();
        let shading = self.options.shading;
        let first = !self.counted;
        let order = sort.items.iter().map(|&(_, f)| usize::from(f));
        let geometry = self.for_each_triangle(&clip, first, order, |f, mat, tri, lights| {
            let lights = match shading {
                Shading::Flat => [ONE; 3],
                Shading::Lambert => [self.face_light(f); 3],
                Shading::Gouraud => lights,
            };
            let s =
                shade_triangle(target, None, &clip, tri, mat, lights).map_err(DrawError::Target)?;
            pixels.add_pixels(s);
            Ok(())
        })?;
        self.count(geometry);
        self.stats.add_pixel_counts(&pixels);
        Ok(())
    }

    /// Hidden-line removal: the edges of the faces that survive culling, drawn in
    /// `color` only where no surface is in front of them.
    ///
    /// The surfaces go into `zbuf` first (depth only, nothing drawn); then each face's
    /// polygon edges (not the fan's inner diagonals) are depth-tested against it with a
    /// tolerance of the face's depth slope, so that an edge wins against its own faces.
    pub fn draw_hidden_line<D: DrawTarget>(
        &mut self,
        target: &mut D,
        zbuf: &mut ZBuffer<'_>,
        color: D::Color,
    ) -> Result<(), DrawError<D::Error>> {
        let clip = clip_of(target, zbuf);
        let first = !self.counted;
        let mut pixels = FrameStats::default();
        // Pass 1: depth only.
        let geometry =
            self.for_each_triangle(&clip, first, 0..self.mesh.face_count(), |_, _, tri, _| {
                let s = depth_runs::<D::Error>(Some(&mut *zbuf), tri, &clip, |_, _, _| Ok(()))
                    .map_err(DrawError::Target)?;
                pixels.pixels_tested += u64::from(s.pixels_tested);
                Ok(())
            })?;
        self.count(geometry);
        // Pass 2: the edges of faces that are not culled.
        for f in 0..self.mesh.face_count() {
            let (vs, _) = self.face(f)?;
            let mut visible = false;
            let mut bias = 1u16;
            for (i0, i1, i2) in fan(vs) {
                let (v0, v1, v2) = (self.fetch(i0, f)?, self.fetch(i1, f)?, self.fetch(i2, f)?);
                if v0.code | v1.code | v2.code != 0 {
                    // Near the clip planes: decide by the clip-space winding instead.
                    visible |= self.clipped_face_visible(&[v0.index, v1.index, v2.index]);
                    continue;
                }
                let tri = [v0.screen, v1.screen, v2.screen];
                let p = |v: &ScreenVertex| (v.x(), v.y());
                if !self
                    .options
                    .cull
                    .drops(signed_area_guarded(p(&tri[0]), p(&tri[1]), p(&tri[2])))
                {
                    visible = true;
                    if let Some(pl) = Plane::new(&tri, [tri[0].z(), tri[1].z(), tri[2].z()]) {
                        // |step| ≤ 2³¹ each: their sum needs 33 bits.
                        let steep = u64::from(pl.step_x().unsigned_abs())
                            + u64::from(pl.step_y().unsigned_abs());
                        let slope = (steep >> 16) + 1;
                        bias = bias.max(slope.min(u64::from(u16::MAX)) as u16);
                    }
                }
            }
            if !visible {
                continue;
            }
            for (a, b) in edges(vs) {
                let s = self.edge(target, Some(&mut *zbuf), &clip, f, a, b, color, bias)?;
                pixels.add_pixels(s);
            }
        }
        self.stats.add_pixel_counts(&pixels);
        Ok(())
    }

    /// Wireframe: every edge of every face, in `color`, with no hiding and no culling.
    pub fn draw_wireframe<D: DrawTarget>(
        &mut self,
        target: &mut D,
        color: D::Color,
    ) -> Result<(), DrawError<D::Error>> {
        let clip = Clip::from_rect(&target.bounding_box());
        let mut pixels = FrameStats::default();
        let mut geometry = FrameStats::default();
        for f in 0..self.mesh.face_count() {
            let (vs, _) = self.face(f)?;
            geometry.triangles_in += vs.len() as u32 - 2;
            for (a, b) in edges(vs) {
                let s = self.edge(target, None, &clip, f, a, b, color, 0)?;
                pixels.add_pixels(s);
            }
        }
        self.count(geometry);
        self.stats.add_pixel_counts(&pixels);
        Ok(())
    }

    /// Whether a triangle that needs clipping faces the camera, by clipping it and
    /// testing the first non-degenerate piece.
    fn clipped_face_visible(&self, idx: &[u16; 3]) -> bool {
        let mut poly = ClipPolygon::new();
        let mut code_or = 0;
        let mut code_and = 0xff;
        for &i in idx {
            let Some(p) = self.mesh.positions.get(usize::from(i)) else {
                return false;
            };
            let c = to_f32(&self.fixed.apply(p));
            let code = outcode_of(&c);
            code_or |= code;
            code_and &= code;
            let _ = poly.push(ClipVertex { c, light: 0.0 });
        }
        if code_and != 0 {
            return false;
        }
        clip_polygon(&mut poly, code_or);
        let pts: heapless::Vec<ScreenVertex, { crate::geometry::clip::MAX_CLIPPED }> =
            poly.iter().filter_map(|c| self.map.project(&c.c)).collect();
        let p = |v: &ScreenVertex| (v.x(), v.y());
        let Some((first, rest)) = pts.split_first() else {
            return false;
        };
        rest.windows(2).any(|pair| {
            let &[b, c] = pair else { return false };
            let area = signed_area(p(first), p(&b), p(&c));
            area != 0 && !self.options.cull.drops(area)
        })
    }

    /// Draw the edge between vertices `a` and `b` of face `f`, clipped in clip space.
    #[allow(clippy::too_many_arguments)]
    fn edge<D: DrawTarget>(
        &self,
        target: &mut D,
        zbuf: Option<&mut ZBuffer<'_>>,
        clip: &Clip,
        f: usize,
        a: u16,
        b: u16,
        color: D::Color,
        bias: u16,
    ) -> Result<SpanStats, DrawError<D::Error>> {
        let (fa, fb) = (self.fetch(a, f)?, self.fetch(b, f)?);
        if fa.code & fb.code != 0 {
            return Ok(SpanStats::default());
        }
        let (sa, sb) = if fa.code | fb.code == 0 {
            (fa.screen, fb.screen)
        } else {
            let pos = |i: u16| {
                self.mesh
                    .positions
                    .get(usize::from(i))
                    .ok_or(Error::IndexOutOfRange {
                        face: f,
                        index: usize::from(i),
                    })
            };
            let ca = ClipVertex {
                c: to_f32(&self.fixed.apply(pos(a)?)),
                light: 0.0,
            };
            let cb = ClipVertex {
                c: to_f32(&self.fixed.apply(pos(b)?)),
                light: 0.0,
            };
            let Some((ca, cb)) = clip_segment(&ca, &cb, fa.code | fb.code) else {
                return Ok(SpanStats::default());
            };
            match (self.map.project(&ca.c), self.map.project(&cb.c)) {
                (Some(x), Some(y)) => (x, y),
                _ => return Ok(SpanStats::default()),
            }
        };
        draw_line(target, zbuf, clip, &sa, &sb, color, bias).map_err(DrawError::Target)
    }
}
