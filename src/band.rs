//! Drawing a whole frame band by band, in a fraction of a frame's RAM: what
//! [`Renderer::draw`] does for [`Bands`] (defined with [`BandBuffers`] in `buffer/`).
//!
//! A frame of `width × height` pixels is drawn in bands of `rows` lines: each band is
//! cleared, drawn into a band-sized colour buffer and Z-buffer, and sent to the display
//! with one `fill_contiguous`. The pixels are exactly those of a whole-frame drawing.
//!
//! RAM: `rows × width × (size_of::<C>() + 2)` bytes for the band buffers, plus, for a
//! cached triangle mesh, an optional bin list of
//! [`BandBuffers::bins_needed`] `u16`s that sorts the visible triangles by band once per
//! frame, so that a band only looks at the triangles that reach it.

use embedded_graphics::{pixelcolor::PixelColor, prelude::DrawTarget};

use crate::buffer::bins_for;
use crate::fill::{clip_of, FlatTarget};
use crate::mesh::Faces;
use crate::num::kernel::{
    band_faces_less, BandCarry, BandStop, BinChains, CachedVertex, FaceColor, FacesCounts,
    SmallTarget, FACES_KERNEL,
};
use crate::num::kernel::{band_faces_less_v6m, Buffers, FACES_V6M_KERNEL};
#[cfg(zraster_x86_64)]
use crate::num::kernel::{SmallRun, SmallX86, SMALL_X86_KERNEL};
use crate::raster::Clip;
use crate::render::{
    cached_outside_rows, cached_triangle, per_colouring, Binning, CachedWalk, RenderState, Unbinned,
};
use crate::shade::{Material, Shading};
mod carry;
use carry::ColorCarry;

use crate::{
    AfterBand, BandBuffers, Bands, ColorBuffer, DepthTarget, DrawError, Error, FrameStats,
    Renderer, ZBuffer,
};

/// The end of a bin chain (no link to a triangle is this: triangles number at most
/// 65,534).
///
/// Bins: two chains of triangles per band, those whose top row lies in it and that
/// reach the next band too, and those that do not (each in face order); and an extra
/// last chain, which every band visits, for triangles reaching more than two bands
/// (rows below the screen counted as bands go on) or needing clipping. So a band draws the first chain of the band above, then its own
/// two, without looking at any triangle that does not reach it. The chains are linked
/// through a `u16` per triangle. Layout of the caller's slice: the chains' tails
/// (2 · bands + 1), the links (one a triangle), then the chains' heads
/// (2 · bands + 1), so that a head is the link "before" the chain's first triangle.
const END: u16 = u16::MAX;

/// An empty clip: binning counts faces through the drawing path with it, drawing none.
const NOWHERE: Clip = Clip {
    x0: 0,
    y0: 0,
    x1: 0,
    y1: 0,
};

impl<D: DrawTarget, F> crate::render::sealed::Sealed for Bands<'_, '_, D, F> {}

impl<D, F> DepthTarget for Bands<'_, '_, D, F>
where
    D: DrawTarget,
    F: AfterBand<D::Color>,
{
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
        draw_bands(
            objects,
            self.display,
            self.buffers,
            self.background,
            &mut self.after,
        )
    }
}

/// Draw the frame of `objects` band by band into `display` (for [`Bands`]): each band
/// cleared to `background`; every object's opaque faces drawn into it with the
/// Z-buffer in (object, face) order, then their see-through ones; the band handed to
/// `after` and sent with one `fill_contiguous`.
///
/// Each object bins its triangles once a frame into its own run of the bins (see
/// [`BinRuns`]), or, when it cannot, walks its whole mesh in every band. One
/// [`ColorCarry`] serves all: in each band the objects take the colours they kept in
/// the band above in the order they kept them, since each object's faces carried into
/// a band are exactly those it kept in the band above, walked in the same order.
fn draw_bands<M, S, D, A>(
    objects: &mut [Renderer<'_, '_, M, S>],
    display: &mut D,
    bands: &mut BandBuffers<'_, D::Color>,
    background: D::Color,
    after: &mut A,
) -> Result<(), DrawError<D::Error>>
where
    M: Copy + Material<D::Color>,
    S: RenderState,
    D: DrawTarget,
    A: AfterBand<D::Color>,
{
    let BandBuffers {
        color,
        depth,
        width: w,
        rows,
        height,
        bins,
        carry,
    } = bands;
    let (w, rows, height) = (*w, *rows, *height);
    let nb = height.div_ceil(rows);
    // Binning counts the clipped faces through the general path the bands draw them
    // with (one copy of it), into the first band's buffers with nothing to draw in.
    let n0 = rows.min(height);
    let mut cb = ColorBuffer::new_band(color, w, n0, 0)?;
    let mut zb = ZBuffer::new_band(depth, w, n0, 0)?;
    let mut counter = FlatTarget::<D::Color, S, false>::new(&mut cb, &mut zb, &NOWHERE);
    let mut runs = BinRuns::new(height, rows);
    for r in objects.iter_mut() {
        let run = runs.next(r);
        r.bin(
            bins.get_mut(run).unwrap_or(&mut []),
            height,
            rows,
            &mut counter,
        )?;
        // A state that bins or fails: this object cannot bin, so nothing is drawn.
        if S::BINNED_BANDS {
            if let Binning::Off(why) = r.binning {
                return Err(DrawError::Input(why.error()));
            }
        }
    }
    let mut carry = ColorCarry::new(background, carry);
    // Whether the band buffers are still as cleared: no triangle was drawn into the
    // band before (every object's chains were empty), nor, for the colours, an overlay
    // (`after` only reads depth): then the band's clear is skipped.
    let mut untouched = false;
    for k in 0..nb {
        let y0 = k * rows;
        let n = rows.min(height - y0);
        // new() checked both slices hold `width × rows` entries: the last, shorter
        // band uses the front of them.
        let mut color = ColorBuffer::new_band(color, w, n, y0 as i32)?;
        let mut zbuf = ZBuffer::new_band(depth, w, n, y0 as i32)?;
        if !untouched || A::DRAWS {
            crate::num::fill(color.data_mut(), background);
        }
        if !untouched {
            zbuf.clear();
        }
        carry.start_band();
        // See-through faces are not binned: their pass may touch any band.
        let mut touched = M::TRANSLUCENT;
        let mut runs = BinRuns::new(height, rows);
        for r in objects.iter_mut() {
            let run = runs.next(r);
            // Under a binned-only state every object binned (checked above), and the
            // unbinned path below is not built.
            if S::BINNED_BANDS || r.binning == Binning::Binned {
                let faces = BandFaces::new(bins.get(run).unwrap_or(&[]), r, nb, k);
                let empty = faces.is_empty();
                touched |= !empty;
                // A band no face reaches draws nothing and keeps no colour: its set-up
                // (lights, targets, the fused loop's block) is skipped; not on x86-64,
                // where the branch cost its band loop's code 11 k a frame.
                if !empty || cfg!(zraster_x86_64) {
                    r.draw_band_faces(&mut color, &mut zbuf, faces, &mut carry)?;
                }
            } else {
                touched = true;
                r.draw_fused(&mut color, &mut zbuf)?;
            }
        }
        for r in objects.iter_mut() {
            r.draw_see_through_buffered(&mut color, &mut zbuf)?;
        }
        untouched = !touched;
        after.after(&mut color, &zbuf);
        color.flush(display)?;
    }
    Ok(())
}

/// Where each object's bins lie in the caller's slice: consecutive runs of
/// [`bins_for`] entries, one an object in order. An object whose run is not (all) in
/// the slice bins nothing ([`Unbinned::BinsTooShort`]).
struct BinRuns {
    next: usize,
    height: u32,
    rows: u32,
}

impl BinRuns {
    fn new(height: u32, rows: u32) -> Self {
        BinRuns {
            next: 0,
            height,
            rows,
        }
    }

    /// The run of the next object, `r`.
    fn next<M: Copy, S>(&mut self, r: &Renderer<'_, '_, M, S>) -> core::ops::Range<usize> {
        let start = self.next;
        self.next = start.saturating_add(bins_for(r.mesh.face_count(), self.height, self.rows));
        start..self.next
    }
}

impl<'m, 'c, M: Copy, S: RenderState> Renderer<'m, 'c, M, S> {
    /// Sort the visible triangles into bins (see [`END`]); `Some(triangle count)` when
    /// binned.
    /// `bins` is this renderer's own run of them, for a screen of `height` rows drawn
    /// `rows` at a time.
    /// `counter` counts the faces near a clip plane, drawing nothing (an empty clip).
    fn bin<C>(
        &mut self,
        bins: &mut [u16],
        height: u32,
        rows: u32,
        counter: &mut FlatTarget<'_, '_, '_, C, S, false>,
    ) -> Result<Option<usize>, Error>
    where
        C: PixelColor,
        M: Material<C>,
    {
        let off = |r: &mut Self, why| {
            r.binning = Binning::Off(why);
            Ok(None)
        };
        let Faces::Triangles { indices, .. } = self.mesh.faces else {
            return off(self, Unbinned::Polygons);
        };
        if M::DITHERED {
            return off(self, Unbinned::Dithered);
        }
        if self.shading() == Shading::Gouraud {
            return off(self, Unbinned::Gouraud);
        }
        let nt = indices.len();
        let nb = height.div_ceil(rows) as usize;
        let needed = bins_for(nt, height, rows);
        let Some(cache) = self.cache.as_deref() else {
            return off(self, Unbinned::NoCache);
        };
        let chains = 2 * nb + 1;
        // Slot numbers (below `nt + chains`) and triangle numbers fit u16.
        if nb > 250 || nt + chains > usize::from(END) {
            return off(self, Unbinned::TooLarge);
        }
        if bins.len() < needed {
            return off(self, Unbinned::BinsTooShort);
        }
        // Tails, then the links (one a triangle) and the heads as one array of slots:
        // a chain's tail starts at its head's slot, so that appending never asks whether
        // the chain is empty. (`needed` is more than `chains`: the split does not fail.)
        let Some((tails, slots)) = bins.split_at_mut_checked(chains) else {
            return off(self, Unbinned::BinsTooShort);
        };
        self.binning = Binning::Binned;
        for (c, t) in tails.iter_mut().enumerate() {
            *t = (nt + c) as u16;
        }
        let mut walk = CachedWalk::new(indices, 0..nt, cache, self.options.cull);
        let mut clipped = FrameStats::default();
        let tall = chains - 1;
        // The scan bins the drawn faces itself where it is assembly (`BIN_KERNEL`); it
        // leaves the others to the walk's decisions, and so to this loop. Elsewhere the
        // walk yields every face and the loop bins each.
        let Some(mut bins) = BinChains::new(tails, slots, height, rows) else {
            return off(self, Unbinned::BinsTooShort);
        };
        bins.set_placed(self.placed);
        while let Some(next) = walk.next_binned(&mut bins) {
            let (f, tri) = next?;
            let Some([p, q, r]) = tri else {
                // Near a clip plane: drawn by the general path in every band (the last
                // chain); counted now by that path, as the whole frame counts it.
                let (g, _) = self.draw_clipped_face(counter, &NOWHERE, true, f)?;
                clipped.add_geometry(&g);
                bins.append(tall, f);
                continue;
            };
            bins.bin(f, [p.xy().1, q.xy().1, r.xy().1]);
        }
        bins.end_chains(END);
        let mut st = walk.stats();
        st.add_geometry(&clipped);
        self.count(st);
        Ok(Some(nt))
    }
}

impl<'m, 'c, M: Copy, S: RenderState> Renderer<'m, 'c, M, S> {
    /// Draw a band's listed faces of a cached triangle mesh, in face order. All but the
    /// tall ones ([`Carry::Tall`]) are known to be unclipped, front-facing (as the
    /// options cull) and to reach the rows of `frame`, so those tests are skipped for
    /// them. Colours pass between bands through `carry` as each face's [`Carry`] says.
    fn draw_band_faces<C>(
        &mut self,
        frame: &mut ColorBuffer<'_, C>,
        zbuf: &mut ZBuffer<'_>,
        faces: BandFaces<'_>,
        carry: &mut ColorCarry<'_, C>,
    ) -> Result<(), Error>
    where
        C: PixelColor,
        M: Material<C>,
    {
        // Only triangle lists bin (see `bin`), so nothing else comes here; the general
        // path stands in all the same, but not where binned-only leaves it out.
        let Faces::Triangles { indices, materials } = self.mesh.faces else {
            return match S::BINNED_BANDS {
                true => Ok(()),
                false => self.draw_fused(frame, zbuf),
            };
        };
        let lambert = self.shading() == Shading::Lambert;
        // One opaque material, unlit or lit in 5-6-5: for the fused band loop.
        let lit;
        let fused = match materials {
            crate::mesh::Materials::Uniform(m)
                if FACES_KERNEL && !(M::TRANSLUCENT && m.alpha() < u8::MAX) =>
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
        // One loop for each way of colouring a face, as in `draw_buffer_triangles`.
        let px = per_colouring!(self, materials, lambert, |shade| {
            self.band_loop(frame, zbuf, faces.with(indices), carry, shade, fused)?
        });
        self.stats.add_pixel_counts(&px);
        Ok(())
    }

    /// ARMv6-M: a band's faces from `faces` on drawn into `b` by the fused band loop
    /// ([`band_faces_less_v6m`]) for one opaque material, unlit or lit in 5-6-5 (as
    /// ARMv7E-M's), its pixel counts into `px`; up to a face it leaves, the heads and
    /// the carry as before that face for the Rust walk. Whether it ran (`false`: it
    /// will not for these buffers and faces). Out of line: one copy, not one for each
    /// colouring's loop.
    #[inline(never)]
    fn band_fused_v6m<C>(
        &self,
        b: &mut Buffers<'_, '_, C>,
        faces: &mut BandTriangles<'_, 'm>,
        cache: &[CachedVertex],
        carry: &mut ColorCarry<C>,
        px: &mut FrameStats,
    ) -> bool
    where
        C: PixelColor,
        M: Material<C>,
    {
        let Faces::Triangles { materials, .. } = self.mesh.faces else {
            return false;
        };
        let crate::mesh::Materials::Uniform(m) = materials else {
            return false;
        };
        if M::TRANSLUCENT && m.alpha() < u8::MAX {
            return false;
        }
        let lit;
        let color = match self.flat_color(materials, self.shading() == Shading::Lambert) {
            Some(c) => FaceColor::Flat(c),
            None => {
                lit = self.light_block(&m);
                match lit.as_ref() {
                    Some((b, f, raw)) => FaceColor::Lit(b, *f, *raw),
                    None => return false,
                }
            }
        };
        let mut counts = FacesCounts::default();
        let BandFaces { links, heads } = &mut faces.faces;
        let tables = (*links, faces.indices, cache);
        let carry = &mut carry.parts();
        let stop = band_faces_less_v6m(heads, tables, carry, &color, b, &mut counts);
        px.pixels_tested += counts.tested;
        px.pixels_written += counts.tested - counts.failed;
        stop != BandStop::Refused
    }

    /// The loop of [`draw_band_faces`](Renderer::draw_band_faces), with the faces'
    /// colours from `shade` unless carried (and, where there is a fused band loop,
    /// `fused`: the same colours for it); returns the pixel counts.
    #[inline(always)]
    fn band_loop<C>(
        &self,
        frame: &mut ColorBuffer<'_, C>,
        zbuf: &mut ZBuffer<'_>,
        mut faces: BandTriangles<'_, 'm>,
        carry: &mut ColorCarry<'_, C>,
        shade: impl Fn(usize) -> Result<C, Error>,
        fused: Option<FaceColor<'_, C>>,
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
        // The pixels of the common faces in u32 registers, into `px` at the end.
        let mut counts = FrameStats::fill_counts();
        // The common case's faces in one assembly loop (`num::kernel::faces`), where
        // there is one, up to a face it leaves to this loop.
        let mut fused = fused.filter(|_| FACES_KERNEL);
        let mut fused_counts = FacesCounts::default();
        // The target of the fills is a local never borrowed beyond them (a face to clip
        // ends the run and gets a target of its own), so that what the fills work out
        // from it alone is worked out once a run, as in the whole frame's loop.
        loop {
            let mut target = FlatTarget::<C, S, false>::new(frame, zbuf, &clip);
            target.start();
            if !matches!(target, FlatTarget::Fused { less: true, .. }) {
                fused = None; // the same for every run
            }
            // x86-64: small triangles set up and drawn in assembly, its block made once
            // a run, as in the whole frame's loop (compiled out elsewhere, where the
            // unused run still moved the ARMv6-M band loop: +1.8 k).
            #[cfg(zraster_x86_64)]
            let mut small = match &target {
                FlatTarget::Fused { b, less: true, .. } if SMALL_X86_KERNEL => {
                    SmallRun::new(b.clip, b.first_row, b.width)
                }
                _ => None,
            };
            let mut to_clip = None;
            // One face (its carry done by the fused loop when `$carried`): `continue`
            // past it, or `break` at a face to clip.
            macro_rules! face {
                ($f:expr, $t:expr, $how:expr, $carried:expr) => {
                    let (f, how, carried) = ($f, $how, $carried);
                    if self.see_through_face::<C>(f) {
                        // Drawn after the opaque faces. Skipped alike as kept and as
                        // taken, so the carried colours stay in step.
                        continue;
                    }
                    let [a, b, c] = cached_triangle(cache, f, $t)?;
                    if how == Carry::Tall {
                        // Drawn in every band: clipped by the general path, or skipped
                        // when it does not reach this band's rows.
                        if a.marked() | b.marked() | c.marked() {
                            to_clip = Some(f);
                            break;
                        }
                    }
                    if how == Carry::Tall && cached_outside_rows([a, b, c], row0, row1) {
                        continue;
                    }
                    // One call of `shade` (so that it is inlined): carried, or worked
                    // out; after the fused loop, the colour it took, or worked out.
                    let taken = match (how, carried) {
                        (Carry::Take, false) => carry.take(),
                        (Carry::Take, true) => carry.last_taken(),
                        _ => None,
                    };
                    let color = match taken {
                        Some(c) => c,
                        None => shade(f)?,
                    };
                    if how == Carry::Keep && !carried {
                        carry.keep(color);
                    }
                    // Inline, as the whole frame's loop, but out of line on ARMv6-M,
                    // where its copies in each colouring's loop cost flash (Pico code
                    // +1.2 KB).
                    #[cfg(zraster_x86_64)]
                    if let (Some(run), FlatTarget::Fused { b: buf, .. }) = (&mut small, &mut target)
                    {
                        let (zdata, cdata) = buf.parts();
                        if let SmallX86::Drawn(t, failed) = run.draw(zdata, cdata, [a, b, c], color)
                        {
                            let s = crate::raster::SpanStats {
                                pixels_tested: t,
                                pixels_written: t.wrapping_sub(failed),
                                runs: 0,
                            };
                            counts.add(s, &mut px);
                            continue;
                        }
                    }
                    let filled = if crate::num::ARMV6M {
                        target.fill_cached_or_call([a, b, c], color)
                    } else {
                        target.fill_cached([a, b, c], color)
                    };
                    counts.add(filled, &mut px);
                };
            }
            if FACES_V6M_KERNEL {
                // ARMv6-M: the fused band loop (out of line), each face it leaves
                // (the heads and the carry as before it) by the plain walk's turn.
                let mut engaged = true;
                loop {
                    if let (true, FlatTarget::Fused { b, less: true, .. }) = (engaged, &mut target)
                    {
                        engaged = self.band_fused_v6m(b, &mut faces, cache, carry, &mut px);
                    }
                    let Some((f, t, how)) = faces.next() else {
                        break;
                    };
                    face!(f, t, how, false);
                }
            } else if fused.is_none() {
                // Without the fused loop (on every run where there is none) a plain
                // walk: asking for it costs the ARMv6-M band loop 1 k.
                for (f, t, how) in faces.by_ref() {
                    face!(f, t, how, false);
                }
            } else {
                loop {
                    // A face the fused loop left, and whether it did its carry.
                    let mut left = None;
                    if let (Some(color), FlatTarget::Fused { b, less: true, .. }) =
                        (&fused, &mut target)
                    {
                        let mut t = b.target();
                        match faces.fused(
                            cache,
                            &mut carry.parts(),
                            color,
                            &mut t,
                            &mut fused_counts,
                        ) {
                            BandStop::Done => break,
                            BandStop::Whole(head) => left = faces.face_of(head).map(|x| (x, false)),
                            BandStop::Fill(head) => left = faces.face_of(head).map(|x| (x, true)),
                            BandStop::Refused => fused = None,
                        }
                    }
                    let ((f, t, how), carried) = match left {
                        Some(face) => face,
                        None => match faces.next() {
                            Some(face) => (face, false),
                            None => break,
                        },
                    };
                    face!(f, t, how, carried);
                }
            }
            let Some(f) = to_clip else { break };
            let mut target = FlatTarget::<C, S, false>::new(frame, zbuf, &clip);
            target.start();
            px.add_pixels(self.draw_clipped_face(&mut target, &clip, false, f)?.1);
        }
        counts.flush(&mut px);
        px.pixels_tested += fused_counts.tested;
        px.pixels_written += fused_counts.tested - fused_counts.failed;
        Ok(px)
    }
}

/// A band's faces in face order: four bin chains (see [`END`]), each in increasing
/// face order, merged. The chains hold the faces of the band above that reach into
/// this one, this band's own that reach the band below, its other own ones, and the
/// tall or clipped faces that every band visits. Drawing in face order whatever the
/// binning keeps ties in depth resolved as in the whole frame. A walk always ends, as
/// `bin` writes every chain afresh each frame and ends it with [`END`].
struct BandFaces<'a> {
    links: &'a [u16],
    /// The next face of each chain, [`END`] (larger than any face) when done, shifted
    /// left by two above the chain's number, in increasing order: the first names the
    /// band's next face and its chain.
    heads: [u32; 4],
}

impl<'a> BandFaces<'a> {
    /// Band `k`'s faces of `r` (of `nb` bands), binned into `bins` this frame.
    fn new<M: Copy, S>(bins: &'a [u16], r: &Renderer<'_, '_, M, S>, nb: u32, k: u32) -> Self {
        // Layout of the bins (see `END`): tails, links, heads.
        let (nt, chains, k) = (r.mesh.face_count(), 2 * nb as usize + 1, k as usize);
        let slots = bins.get(chains..).unwrap_or(&[]);
        let links = slots.get(..nt).unwrap_or(&[]);
        let heads = slots.get(nt..).unwrap_or(&[]);
        let head = |c: usize| heads.get(c).copied().unwrap_or(END);
        // The triangles of the band above that reach this one, this band's own (those
        // reaching the next band, the others), and the tall or clipped ones.
        let above = if k > 0 { head(2 * k - 2) } else { END };
        let at = |f: u16, c: u32| u32::from(f) << 2 | c;
        let [mut a, mut b, mut c, mut d] = [
            at(above, 0),
            at(head(2 * k), 1),
            at(head(2 * k + 1), 2),
            at(head(chains - 1), 3),
        ];
        // In increasing order (no two are equal: each names its chain), by a sorting
        // network of five compare-exchanges.
        let order = |x: &mut u32, y: &mut u32| {
            if *x > *y {
                core::mem::swap(x, y);
            }
        };
        order(&mut a, &mut b);
        order(&mut c, &mut d);
        order(&mut a, &mut c);
        order(&mut b, &mut d);
        order(&mut b, &mut c);
        BandFaces {
            links,
            heads: [a, b, c, d],
        }
    }

    fn is_empty(&self) -> bool {
        self.heads[0] >> 2 == u32::from(END)
    }

    /// The faces with their corners' indices, from the mesh's `indices`.
    fn with<'m>(self, indices: &'m [[u16; 3]]) -> BandTriangles<'a, 'm> {
        BandTriangles {
            faces: self,
            indices,
        }
    }
}

/// [`BandFaces`] with each face's corner indices: a face is looked up in the links
/// and the indices under one bounds test, which [`END`] fails too.
struct BandTriangles<'a, 'm> {
    faces: BandFaces<'a>,
    indices: &'m [[u16; 3]],
}

impl<'m> BandTriangles<'_, 'm> {
    /// The faces the fused band loop ([`band_faces_less`]) takes, drawn from here on
    /// into `t` over `cache`, up to the end or a face it leaves.
    #[inline(always)]
    fn fused<C: Copy>(
        &mut self,
        cache: &[CachedVertex],
        carry: &mut BandCarry<'_, '_, C>,
        color: &FaceColor<'_, C>,
        t: &mut SmallTarget<'_, '_, C>,
        counts: &mut FacesCounts,
    ) -> BandStop {
        let BandFaces { links, heads } = &mut self.faces;
        band_faces_less(heads, (links, self.indices, cache), carry, color, t, counts)
    }

    /// The face the fused loop stopped at, by its chain's head (as [`next`] gives
    /// it; `None` for none, as it stops only at a listed face).
    ///
    /// [`next`]: Iterator::next
    fn face_of(&self, head: u32) -> Option<(usize, &'m [u16; 3], Carry)> {
        let f = (head >> 2) as usize;
        let t = self.indices.get(f)?;
        Some((f, t, Carry::of_chain(head & 3)))
    }
}

impl<'m> Iterator for BandTriangles<'_, 'm> {
    type Item = (usize, &'m [u16; 3], Carry);

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        let BandFaces { links, heads } = &mut self.faces;
        // The first head names the next face and its chain.
        let least = heads[0];
        let (f, k) = ((least >> 2) as usize, least & 3);
        // Both lookups are in bounds below `n`; END (more than any face) is not.
        let n = links.len().min(self.indices.len());
        if f >= n {
            return None;
        }
        let (Some(&link), Some(t)) = (links.get(f), self.indices.get(f)) else {
            return None;
        };
        // The chain's next face takes the first head's place, moved down past the
        // heads below it (it stays first about half the time in bunny-320: a band's
        // faces come in runs from one chain).
        let next = u32::from(link) << 2 | k;
        if !crate::num::THUMB2 {
            move_down(heads, next);
        } else {
            // On Thumb-2 a chain of compares: the band loop spills less around it than
            // around the loop (which costs less on ARMv6-M and x86-64).
            let [_, b, c, d] = *heads;
            if next < b {
                heads[0] = next;
            } else {
                heads[0] = b;
                if next < c {
                    heads[1] = next;
                } else {
                    heads[1] = c;
                    if next < d {
                        heads[2] = next;
                    } else {
                        heads[2] = d;
                        heads[3] = next;
                    }
                }
            }
        }
        Some((f, t, Carry::of_chain(k)))
    }
}

/// Put `next` in the place of `heads[0]`, moved down past the heads below it, so that
/// `heads` stays in increasing order.
#[inline(always)]
fn move_down(heads: &mut [u32; 4], next: u32) {
    let mut i = 0;
    while let Some(&h) = heads.get(i + 1) {
        if next < h {
            break;
        }
        if let Some(slot) = heads.get_mut(i) {
            *slot = h;
        }
        i += 1;
    }
    if let Some(slot) = heads.get_mut(i) {
        *slot = next;
    }
}

/// What a band's listed face does with the [`ColorCarry`]; the values are the
/// [`BandFaces`] chains' numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub(crate) enum Carry {
    /// The face came from the band above: take the colour kept there.
    Take = 0,
    /// The face continues into the band below: keep its colour for it.
    Keep = 1,
    /// Nothing: the face lies in this band alone.
    No = 2,
    /// Nothing either: a tall or clipped face, drawn in every band it meets (and tested
    /// against the band's rows and clip planes there).
    Tall = 3,
}

impl Carry {
    /// The face's `Carry` from the number of the [`BandFaces`] chain it came from.
    #[inline(always)]
    fn of_chain(k: u32) -> Carry {
        match k {
            0 => Carry::Take,
            1 => Carry::Keep,
            2 => Carry::No,
            _ => Carry::Tall,
        }
    }
}
