//! Drawing with the Z-buffer: into any draw target run by run, or into a colour buffer
//! with the depth test and the colour write fused (the paths behind
//! [`Renderer::draw`] for a [`WithDepth`](super::WithDepth) and a
//! [`Frame`](crate::Frame)).

use super::*;
use crate::fill::blend::{blend_triangle, screen_door_triangle};
#[cfg(zraster_x86_64)]
use crate::num::kernel::FacesX86;
use crate::num::kernel::{faces_less, FaceColor, FacesCounts, FacesStop};
use crate::num::kernel::{faces_less_v6m, FACES_V6M_KERNEL};
use crate::num::kernel::{SmallRun, SmallX86, SMALL_X86_KERNEL};
use crate::num::kernel::{FACES_KERNEL, FACES_X86_KERNEL};

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
            // A uniform material without one colour for all is lit: into a 5-6-5
            // colour from the face normal in one step where it can be.
            (None, crate::mesh::Materials::Uniform(m)) => match $r.light_block(&m) {
                Some((block, color, _)) => {
                    let $shade = |f: usize| {
                        Ok(match crate::num::kernel::lit_565(f, &block) {
                            Some(c) => color(c),
                            None => m.shade($r.face_light(f), 0, 0),
                        })
                    };
                    $body
                }
                None => {
                    let $shade = |f: usize| Ok(m.shade($r.face_light(f), 0, 0));
                    $body
                }
            },
            (None, _) => {
                let $shade = |f: usize| $r.face_color($materials, $lambert, f);
                $body
            }
        }
    };
}
pub(crate) use per_colouring;

/// Whether the whole frame has a fused face loop: ARMv7E-M's `faces_less`, ARMv6-M's
/// `faces_less_v6m`.
const FUSED_FACES: bool = FACES_KERNEL || FACES_V6M_KERNEL;

impl<'m, 'c, M: Copy, S: RenderState> Renderer<'m, 'c, M, S> {
    /// The one colour of every face when it does not depend on the face (a uniform
    /// material, unlit).
    pub(crate) fn flat_color<C>(
        &self,
        materials: crate::mesh::Materials<'m, M>,
        lambert: bool,
    ) -> Option<C>
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
    pub(crate) fn face_color<C>(
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
    /// Draw with the Z-buffer into any draw target, run by run (for [`WithDepth`]):
    /// every visible triangle, depth-tested per pixel, in the mesh's materials and the
    /// chosen shading.
    ///
    /// `target` and `zbuf` may cover the whole screen or one band of it (rows the
    /// Z-buffer does not hold are not drawn).
    ///
    /// [`WithDepth`]: super::WithDepth
    pub(crate) fn draw_runs<D>(
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
        let first = !self.counted;
        let geometry = self.for_each_triangle(
            &clip,
            first,
            0..self.mesh.face_count(),
            |f, mat, tri, lights| {
                if see_through::<D::Color, M>(&mat) {
                    return Ok(()); // drawn after the opaque faces
                }
                let lights = self.corner_lights(f, lights);
                let s =
                    shade_triangle::<S, _, _>(target, Some(&mut *zbuf), &clip, tri, mat, lights)
                        .map_err(DrawError::Target)?;
                pixels.add_pixels(s);
                Ok(())
            },
        )?;
        self.count(geometry);
        self.stats.add_pixel_counts(&pixels);
        Ok(())
    }
    /// Draw with the Z-buffer into a [`ColorBuffer`] (for a [`Frame`]): the same pixels
    /// as [`draw_runs`](Renderer::draw_runs), faster, since the depth test and the colour
    /// write share one loop instead of handing runs to a `DrawTarget`. Flat-coloured
    /// faces (flat shading, Lambert) take this path; Gouraud and dithered materials go
    /// through the buffer's `DrawTarget` runs. The two buffers may differ in geometry:
    /// only the pixels both hold are drawn.
    ///
    /// [`Frame`]: crate::Frame
    pub(crate) fn draw_fused<C>(
        &mut self,
        frame: &mut ColorBuffer<'_, C>,
        zbuf: &mut ZBuffer<'_>,
    ) -> Result<(), Error>
    where
        C: PixelColor,
        M: Material<C>,
    {
        let fast = !M::DITHERED && matches!(self.shading(), Shading::Flat | Shading::Lambert);
        if let (true, Some(_), Faces::Triangles { indices, materials }) =
            (fast, &self.cache, self.mesh.faces)
        {
            return self.draw_buffer_triangles(frame, zbuf, indices, materials, 0..indices.len());
        }
        self.draw_fused_general(frame, zbuf)
    }

    /// [`draw_fused`](Renderer::draw_fused) face by face through the general path.
    #[inline(never)]
    fn draw_fused_general<C>(
        &mut self,
        frame: &mut ColorBuffer<'_, C>,
        zbuf: &mut ZBuffer<'_>,
    ) -> Result<(), Error>
    where
        C: PixelColor,
        M: Material<C>,
    {
        let clip = clip_of(frame, zbuf);
        let mut pixels = FrameStats::default();
        let first = !self.counted;
        let geometry = self
            .for_each_triangle::<core::convert::Infallible>(
                &clip,
                first,
                0..self.mesh.face_count(),
                |f, mat, tri, lights| {
                    if see_through::<C, M>(&mat) {
                        return Ok(()); // drawn after the opaque faces
                    }
                    let s = match self.shading() {
                        Shading::Flat if !M::DITHERED => fill_flat_buffered::<S, _>(
                            frame,
                            zbuf,
                            &clip,
                            tri,
                            mat.shade(ONE, 0, 0),
                        ),
                        Shading::Lambert if !M::DITHERED => fill_flat_buffered::<S, _>(
                            frame,
                            zbuf,
                            &clip,
                            tri,
                            mat.shade(self.face_light(f), 0, 0),
                        ),
                        _ => {
                            let lights = self.corner_lights(f, lights);
                            shade_triangle::<S, _, _>(
                                frame,
                                Some(&mut *zbuf),
                                &clip,
                                tri,
                                mat,
                                lights,
                            )
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
    /// A face near a clip plane in
    /// [`draw_buffer_triangles`](Renderer::draw_buffer_triangles): clipped, culled and
    /// drawn by the general path. Out of line, as it is rare.
    #[inline(never)]
    pub(crate) fn draw_clipped_face<C, const SPLIT: bool>(
        &self,
        target: &mut FlatTarget<'_, '_, '_, C, S, SPLIT>,
        clip: &Clip,
        first: bool,
        f: usize,
    ) -> Result<(FrameStats, SpanStats), Error>
    where
        C: PixelColor,
        M: Material<C>,
    {
        let lambert = self.shading() == Shading::Lambert;
        let mut more = SpanStats::default();
        let g = self
            .for_each_triangle::<core::convert::Infallible>(
                clip,
                first,
                core::iter::once(f),
                |f, mat, tri, _| {
                    if see_through::<C, M>(&mat) {
                        return Ok(()); // drawn after the opaque faces
                    }
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
    /// [`draw_fused`](Renderer::draw_fused) for a cached triangle list with flat colours:
    /// one tight loop over the triangles, instantiated for each way of colouring a face
    /// (one colour; one material, lit; a material per face), so that the loop does not
    /// ask which it is for every face. Faces near the clip planes go through the general
    /// path. Out of line, as is the rest of `draw_fused`, so that neither frame is
    /// stacked on the other.
    #[inline(never)]
    pub(crate) fn draw_buffer_triangles<C>(
        &mut self,
        frame: &mut ColorBuffer<'_, C>,
        zbuf: &mut ZBuffer<'_>,
        indices: &'m [[u16; 3]],
        materials: crate::mesh::Materials<'m, M>,
        faces: core::ops::Range<usize>,
    ) -> Result<(), Error>
    where
        C: PixelColor,
        M: Material<C>,
    {
        let lambert = self.shading() == Shading::Lambert;
        // One opaque material, unlit or lit in 5-6-5: for the fused face loop.
        let lit;
        let fused = match materials {
            crate::mesh::Materials::Uniform(m)
                if (FUSED_FACES || FACES_X86_KERNEL) && !see_through::<C, M>(&m) =>
            {
                match self.flat_color(materials, lambert) {
                    Some(c) => Some(FaceColor::Flat(c)),
                    None => {
                        lit = self.light_block(&m);
                        lit.as_ref().map(|(b, f, raw)| FaceColor::Lit(b, *f, *raw))
                    }
                }
            }
            _ => None,
        };
        let (st, px) = per_colouring!(self, materials, lambert, |shade| {
            self.cull_and_fill(frame, zbuf, indices, faces, shade, fused)?
        });
        self.count(st);
        self.stats.add_pixel_counts(&px);
        Ok(())
    }
    /// The loop of [`draw_buffer_triangles`](Renderer::draw_buffer_triangles), with the
    /// faces' colours from `shade` (and, where there is a fused face loop, `fused`:
    /// the same colours for it); returns the geometry and pixel counts.
    #[inline(always)]
    pub(crate) fn cull_and_fill<C>(
        &self,
        frame: &mut ColorBuffer<'_, C>,
        zbuf: &mut ZBuffer<'_>,
        indices: &'m [[u16; 3]],
        faces: core::ops::Range<usize>,
        shade: impl Fn(usize) -> Result<C, Error>,
        fused: Option<FaceColor<'_, C>>,
    ) -> Result<(FrameStats, FrameStats), Error>
    where
        C: PixelColor,
        M: Material<C>,
    {
        let clip = clip_of(frame, zbuf);
        let first = !self.counted;
        let mut px = FrameStats::default();
        let Some(cache) = self.cache.as_deref() else {
            return Ok((FrameStats::default(), px));
        };
        // A band drawn without bins skips the triangles off its rows.
        let rows = (!first).then(|| clip.subpixel_rows());
        let walk = CachedWalk::new(indices, faces, cache, self.options.cull);
        // The scan's operands apart from the walk, where the scan reads them.
        let operands = walk.operands();
        let mut walk = walk.reading(&operands);
        let mut clipped = FrameStats::default();
        // The drawn faces' pixels in u32 registers, into `px` once at the end.
        let mut counts = FillCounts::default();
        // The common case's faces in one assembly loop (`num::kernel::faces`), where
        // there is one, up to a face it leaves to this loop; a band's row test is not
        // among them.
        // x86-64: the same in `num::kernel::faces_x86`, where its checks of the faces
        // and the cache, made once here, pass.
        #[cfg(zraster_x86_64)]
        let mut x86 = match &fused {
            Some(color) if FACES_X86_KERNEL && rows.is_none() => {
                let (_, faces, cache) = walk.fused();
                FacesX86::new(&operands, faces, cache, walk.first(), color)
            }
            _ => None,
        };
        let mut fused = fused.filter(|_| FUSED_FACES && rows.is_none());
        // ARMv6-M: whether the loop may skip the test of each corner's place.
        let placed = self.placed;
        let mut fused_counts = FacesCounts::default();
        // The target of the fills is a local never borrowed beyond them (a face to clip
        // ends the run and gets a target of its own), so that what the fills work out
        // from it alone is worked out once a run.
        loop {
            let mut target = FlatTarget::<C, S>::new(frame, zbuf, &clip);
            target.start();
            if !matches!(target, FlatTarget::Fused { less: true, .. }) {
                fused = None; // the same for every run
            }
            // x86-64: small triangles set up and drawn in assembly, its block made once
            // a run.
            let mut small = match &target {
                FlatTarget::Fused { b, less: true, .. } if SMALL_X86_KERNEL => {
                    SmallRun::new(b.clip, b.first_row, b.width)
                }
                _ => None,
            };
            let mut to_clip = None;
            loop {
                let mut left = None;
                if let (Some(color), FlatTarget::Fused { b, less: true, .. }) =
                    (&fused, &mut target)
                {
                    let (mut pos, faces, cache) = walk.fused();
                    let scan = (&operands, faces, cache);
                    let stop = if FACES_V6M_KERNEL {
                        faces_less_v6m(&mut pos, scan, placed, color, b, &mut fused_counts)
                    } else {
                        let mut t = b.target();
                        faces_less(&mut pos, scan, color, &mut t, &mut fused_counts)
                    };
                    match stop {
                        FacesStop::Face(k, tri) => {
                            walk.fused_to(pos, 1);
                            left = Some((walk.first() + k, Some(tri)));
                        }
                        FacesStop::Scan => walk.fused_to(pos, 0),
                        FacesStop::Refused => fused = None,
                    }
                }
                #[cfg(zraster_x86_64)]
                if let (Some(k), Some(run), FlatTarget::Fused { b, .. }) =
                    (&mut x86, &small, &mut target)
                {
                    let (mut pos, _, _) = walk.fused();
                    let (zdata, cdata) = b.parts();
                    match k.run(run, zdata, cdata, &mut pos, &mut fused_counts) {
                        FacesStop::Face(k, tri) => {
                            walk.fused_to(pos, 1);
                            left = Some((walk.first() + k, Some(tri)));
                        }
                        FacesStop::Scan => walk.fused_to(pos, 0),
                        FacesStop::Refused => x86 = None,
                    }
                }
                let next = match left {
                    Some(face) => face,
                    None => match walk.next() {
                        Some(next) => next?,
                        None => break,
                    },
                };
                match next {
                    (f, Some([a, b, c])) => {
                        if self.see_through_face::<C>(f) {
                            continue; // drawn after the opaque faces
                        }
                        if let Some((row0, row1)) = rows {
                            if cached_outside_rows([a, b, c], row0, row1) {
                                continue;
                            }
                        }
                        // The colour first: then only the corners' places, not their
                        // values, are kept across it.
                        let color = shade(f)?;
                        if let (Some(run), FlatTarget::Fused { b: buf, .. }) =
                            (&mut small, &mut target)
                        {
                            let tri = [a, b, c];
                            let (zdata, cdata) = buf.parts();
                            if let SmallX86::Drawn(t, failed) = run.draw(zdata, cdata, tri, color) {
                                let s = SpanStats {
                                    pixels_tested: t,
                                    pixels_written: t.wrapping_sub(failed),
                                    runs: 0,
                                };
                                counts.add(s, &mut px);
                                continue;
                            }
                        }
                        counts.add(target.fill_cached([a, b, c], color), &mut px);
                    }
                    // Across a clip plane or far outside the screen (rare).
                    (f, None) => {
                        to_clip = Some(f);
                        break;
                    }
                }
            }
            let Some(f) = to_clip else { break };
            // The general path.
            let mut target = FlatTarget::<C, S>::new(frame, zbuf, &clip);
            target.start();
            let (g, more) = self.draw_clipped_face(&mut target, &clip, first, f)?;
            clipped.add_geometry(&g);
            px.add_pixels(more);
        }
        counts.flush(&mut px);
        walk.fused_to(walk.fused().0, fused_counts.drawn);
        px.pixels_tested += fused_counts.tested;
        px.pixels_written += fused_counts.tested - fused_counts.failed;
        let mut st = walk.stats();
        st.add_geometry(&clipped);
        Ok((st, px))
    }
}

/// Pixel counts summed in `u32` (two adds a face instead of two 64-bit adds through
/// memory), handed to the 64-bit [`FrameStats`] when a sum would wrap and at the end.
#[derive(Default)]
pub(crate) struct FillCounts {
    tested: u32,
    written: u32,
}

impl FrameStats {
    /// Empty [`FillCounts`], for a loop of fills outside this module (the bands').
    #[inline(always)]
    pub(crate) fn fill_counts() -> FillCounts {
        FillCounts::default()
    }
}

impl FillCounts {
    /// Add one fill's counts; when the sum of tested pixels would pass `u32::MAX`, first
    /// move the sums into `spill` (a fill writes at most the pixels it tests, so the
    /// written sum, never above the tested one, cannot wrap first).
    #[inline(always)]
    pub(crate) fn add(&mut self, s: SpanStats, spill: &mut FrameStats) {
        let tested = self.tested.wrapping_add(s.pixels_tested);
        if tested < self.tested {
            self.spill(s, spill);
            return;
        }
        self.tested = tested;
        self.written = self.written.wrapping_add(s.pixels_written);
    }

    /// The rare case of [`add`](FillCounts::add): the sums into `px`, then `s` alone.
    #[cold]
    #[inline(never)]
    fn spill(&mut self, s: SpanStats, px: &mut FrameStats) {
        self.flush(px);
        self.tested = s.pixels_tested;
        self.written = s.pixels_written;
    }

    /// Move the sums into `px`.
    #[inline(always)]
    pub(crate) fn flush(&mut self, px: &mut FrameStats) {
        px.add_fill(SpanStats {
            pixels_tested: self.tested,
            pixels_written: self.written,
            runs: 0,
        });
        *self = FillCounts::default();
    }
}

/// Whether a face of material `m` is left out of the opaque faces, to be drawn after
/// them (a constant `false` for opaque material types).
#[inline(always)]
pub(crate) fn see_through<C, M: Material<C>>(m: &M) -> bool {
    M::TRANSLUCENT && m.alpha() < u8::MAX
}

impl<'m, 'c, M: Copy, S: RenderState> Renderer<'m, 'c, M, S> {
    /// Whether face `f` is see-through (see [`see_through`]).
    #[inline(always)]
    pub(crate) fn see_through_face<C>(&self, f: usize) -> bool
    where
        M: Material<C>,
    {
        M::TRANSLUCENT
            && self
                .mesh
                .face(f)
                .is_some_and(|(_, m)| see_through::<C, M>(&m))
    }

    /// Whether the mesh has see-through faces: never for an opaque material type; else
    /// its materials are looked at once (a read a face, no geometry) and the answer
    /// kept, so that a mesh of opaque faces skips the see-through pass (in every band).
    fn may_see_through<C>(&mut self) -> bool
    where
        M: Material<C>,
    {
        if !M::TRANSLUCENT {
            return false;
        }
        if let Some(known) = self.see_through {
            return known;
        }
        let any = match self.mesh.faces {
            Faces::Triangles {
                materials: crate::mesh::Materials::Uniform(m),
                ..
            } => see_through::<C, M>(&m),
            _ => (0..self.mesh.face_count()).any(|f| self.see_through_face::<C>(f)),
        };
        self.see_through = Some(any);
        any
    }

    /// The see-through faces, after every opaque one (of this mesh, or of every mesh of
    /// a scene), blended over `frame` in face order: depth-tested against `zbuf` without
    /// writing it. Geometry was counted by the opaque pass; this adds pixel counts.
    pub(crate) fn draw_see_through_buffered<C>(
        &mut self,
        frame: &mut ColorBuffer<'_, C>,
        zbuf: &mut ZBuffer<'_>,
    ) -> Result<(), Error>
    where
        C: PixelColor,
        M: Material<C>,
    {
        if !self.may_see_through::<C>() {
            return Ok(());
        }
        let clip = clip_of(frame, zbuf);
        let mut px = FrameStats::default();
        self.for_each_triangle::<core::convert::Infallible>(
            &clip,
            false,
            0..self.mesh.face_count(),
            |f, mat, tri, lights| {
                if see_through::<C, M>(&mat) {
                    let lights = self.corner_lights(f, lights);
                    px.add_fill(blend_triangle::<S, _, _>(
                        frame, zbuf, &clip, tri, mat, lights,
                    ));
                }
                Ok(())
            },
        )
        .map_err(|e| match e {
            DrawError::Input(e) => e,
            DrawError::Target(never) => match never {},
        })?;
        self.stats.add_pixel_counts(&px);
        Ok(())
    }

    /// [`draw_see_through_buffered`](Renderer::draw_see_through_buffered) for a display
    /// whose colours cannot be read: each see-through face as a screen door of its
    /// alpha (see [`Translucent`](crate::shade::Translucent)).
    pub(crate) fn draw_see_through_runs<D>(
        &mut self,
        display: &mut D,
        zbuf: &mut ZBuffer<'_>,
    ) -> Result<(), DrawError<D::Error>>
    where
        D: DrawTarget,
        M: Material<D::Color>,
    {
        if !self.may_see_through::<D::Color>() {
            return Ok(());
        }
        let clip = clip_of(display, zbuf);
        let mut px = FrameStats::default();
        self.for_each_triangle(
            &clip,
            false,
            0..self.mesh.face_count(),
            |f, mat, tri, lights| {
                if see_through::<D::Color, M>(&mat) {
                    let lights = self.corner_lights(f, lights);
                    let s = screen_door_triangle::<S, _, _>(display, zbuf, &clip, tri, mat, lights)
                        .map_err(DrawError::Target)?;
                    px.add_pixels(s);
                }
                Ok(())
            },
        )?;
        self.stats.add_pixel_counts(&px);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use crate::camera::Camera;
    use crate::math::{radians, Mat4, Vec3};
    use crate::mesh::Mesh;
    use crate::shade::{DisplayColor, Shading};
    use crate::{CachedVertex, ColorBuffer, Frame, RenderOptions, Renderer, Viewport};
    use crate::{WithDepth, ZBuffer};
    use embedded_graphics::pixelcolor::{Bgr565, Rgb565, Rgb888};
    use embedded_graphics::prelude::RgbColor;
    use std::vec;
    use zraster_bench_scene::bunny;

    /// The bench's bunny (its tables; the scene crate's own types are another build of
    /// this crate), lit, into a frame (faces of one material coloured by `lit_565` from
    /// their normals) and through `WithDepth` (each face's light, then the material's
    /// `shade`): the same pixels, with the face normals and without (then each face lit
    /// from its corners by `face_light`).
    fn one_step_lit_faces_are_the_general_paths<C: DisplayColor + RgbColor>() {
        let (w, h) = (160, 120);
        let n = (w * h) as usize;
        let cam = Camera::look_at(Vec3::new(0.0, 0.0, 1.6), Vec3::new(0.0, 0.0, 0.6), Vec3::Y)
            .unwrap()
            .perspective(radians(60.0), 0.1, 10.0, Viewport::new(w, h).unwrap())
            .unwrap();
        let fit = bunny::BUNNY_FIT;
        let xf = cam
            .with_model(Mat4::rotation_y(radians(30.0)) * Mat4::scaling(Vec3::new(fit, fit, fit)));
        let opts = RenderOptions {
            shading: Shading::Lambert,
            ..Default::default()
        };
        for normals in [Some(&bunny::BUNNY_FACE_NORMALS[..]), None] {
            let material = Rgb888::new(255, 204, 153);
            let mesh = Mesh::triangles(
                &bunny::BUNNY_POSITIONS,
                bunny::BUNNY_SCALE,
                &bunny::BUNNY_INDICES,
                material,
            )
            .with_normals(normals, None);
            let mut cache = vec![CachedVertex::default(); bunny::BUNNY_POSITIONS.len()];
            let (mut pixels, mut depth) = (vec![C::BLACK; n], vec![u16::MAX; n]);
            let mut frame = Frame::new(&mut pixels, &mut depth, w, h).unwrap();
            let mut r = Renderer::with_cache(&mesh, &xf, opts, &mut cache).unwrap();
            r.draw(&mut frame).unwrap();
            let (mut shown, mut zdepth) = (vec![C::BLACK; n], vec![u16::MAX; n]);
            let mut display = ColorBuffer::new(&mut shown, w, h).unwrap();
            let mut zbuf = ZBuffer::new(&mut zdepth, w, h).unwrap();
            let mut r = Renderer::new(&mesh, &xf, opts).unwrap();
            r.draw(&mut WithDepth::new(&mut display, &mut zbuf))
                .unwrap();
            assert!(frame.color().as_slice() == display.as_slice());
            assert!(frame.color().as_slice().iter().any(|&c| c != C::BLACK));
        }
    }

    #[test]
    fn one_step_lit_faces_are_the_general_paths_in_both_packings() {
        one_step_lit_faces_are_the_general_paths::<Rgb565>();
        one_step_lit_faces_are_the_general_paths::<Bgr565>();
    }
}

/// x86-64's fused face loop (`num::kernel::faces_x86`) against the renderer's own loop,
/// through the whole renderer (here, above the kernels, not inside them).
#[cfg(test)]
mod fused_x86 {
    use crate::camera::Camera;
    use crate::math::{radians, Mat4, Vec3};
    use crate::mesh::{compute_face_normals, Mesh};
    use crate::num::kernel::FACES_X86_TWIN as TWIN;
    use crate::shade::Shading;
    use crate::{CachedVertex, Cull, Frame, FrameStats, RenderOptions, Renderer, Viewport};
    use embedded_graphics::pixelcolor::{Bgr565, Rgb565, Rgb888};
    use embedded_graphics::prelude::RgbColor;
    use std::vec;
    use std::vec::Vec;

    /// One random mesh drawn into a frame of `C` with the fused loop and with the
    /// renderer's own loop: colours, depths and counts.
    fn both<C: crate::shade::DisplayColor + RgbColor>(
        seed: u32,
        shading: Shading,
    ) -> [(Vec<C>, Vec<u16>, FrameStats); 2] {
        let mut r = crate::num::kernel::xorshift32(seed);
        let (w, h) = (96 + r() % 200, 64 + r() % 150);
        let n = 4 + r() as usize % 400;
        // Small triangles (corners about a centre) anywhere, across the screen's
        // edges too, and some large (refused by the set-up) joining any corners; some
        // meshes reach behind the camera (the loop then refuses the draw).
        let spread = [8000, 16000, 32000][r() as usize % 3];
        let size = [64, 400, 2000][r() as usize % 3];
        let mut within = |s: i32| (r() % (2 * s as u32 + 1)) as i32 - s;
        let positions: Vec<[i16; 3]> = (0..n)
            .flat_map(|_| {
                let c = [0; 3].map(|_| within(spread - size));
                [0; 3].map(|_| [0, 1, 2].map(|k| (c[k] + within(size)) as i16))
            })
            .collect();
        let faces: Vec<[u16; 3]> = (0..n)
            .map(|k| {
                if r().is_multiple_of(8) {
                    [0; 3].map(|_| (r() as usize % (3 * n)) as u16)
                } else {
                    [3 * k, 3 * k + 1, 3 * k + 2].map(|i| i as u16)
                }
            })
            .collect();
        let material = Rgb888::new(r() as u8, r() as u8, r() as u8);
        let plain = Mesh::triangles(&positions, 1.0 / 16384.0, &faces, material);
        let mut normals = vec![[0i16; 3]; faces.len()];
        compute_face_normals(&plain, &mut normals).unwrap();
        // Now and then no normals (the loop refuses a lit draw).
        let mesh = plain.with_normals((!r().is_multiple_of(5)).then_some(&normals[..]), None);
        // Now and then a view wider than the frame: triangles across its right edge (the
        // rows' columns clamped to the clip's).
        let view = Viewport::new(w + [0, 0, 40][r() as usize % 3], h).unwrap();
        let cam = Camera::look_at(Vec3::new(0.0, 0.0, 2.2), Vec3::new(0.0, 0.0, 0.0), Vec3::Y)
            .unwrap()
            .perspective(radians(60.0), 0.1, 10.0, view)
            .unwrap();
        // Now and then the light along the view axis with the model unturned: a light
        // component of exactly ±1 in model space, the loop's wide n·L form.
        let axis = r().is_multiple_of(6);
        let turn = if axis {
            0.0
        } else {
            (r() % 6283) as f32 / 1000.0
        };
        let xf = cam.with_model(Mat4::rotation_y(turn) * Mat4::rotation_x(turn * 0.7));
        let mut opts = RenderOptions {
            shading,
            cull: [Cull::Back, Cull::Back, Cull::Front, Cull::None][r() as usize % 4],
            ..Default::default()
        };
        if axis {
            opts.light.direction = Vec3::new(0.0, 0.0, 1.0);
        }
        [false, true].map(|twin| {
            TWIN.with(|t| t.set((twin, t.get().1)));
            let len = (w * h) as usize;
            let (mut px, mut depth) = (vec![C::BLACK; len], vec![u16::MAX; len]);
            let mut cache = vec![CachedVertex::default(); positions.len()];
            let mut frame = Frame::new(&mut px, &mut depth, w, h).unwrap();
            let mut rd = Renderer::with_cache(&mesh, &xf, opts, &mut cache).unwrap();
            rd.draw(&mut frame).unwrap();
            let stats = rd.stats();
            (px, depth, stats)
        })
    }

    #[test]
    fn the_fused_loop_draws_what_the_renderers_loop_draws() {
        let mut drawn = 0;
        for seed in 1..=400u32 {
            let shading = [Shading::Lambert, Shading::Flat][seed as usize % 2];
            let ([a, b], [p, q]) = if seed.is_multiple_of(3) {
                let [a, b] = both::<Bgr565>(seed, shading);
                ([a.2, b.2], [(a.0 == b.0), (a.1 == b.1)])
            } else {
                let [a, b] = both::<Rgb565>(seed, shading);
                ([a.2, b.2], [(a.0 == b.0), (a.1 == b.1)])
            };
            assert!(p, "colours differ, seed {seed}");
            assert!(q, "depths differ, seed {seed}");
            assert_eq!(a, b, "counts differ, seed {seed}");
            drawn += a.drawn;
        }
        assert!(drawn > 10_000);
        // The loop took most draws (on x86-64).
        let made = TWIN.with(|t| t.get().1);
        assert!(!super::FACES_X86_KERNEL || made > 200, "{made}");
    }
}
