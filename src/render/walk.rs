//! The face walk: one place decides, for every triangle of every face, whether it is
//! outside the view volume, needs clipping, lies off the rows asked for, is culled,
//! or is drawn ([`decide`]). Every renderer walks through it: the Z-buffer paths
//! ([`CachedWalk`] over a cached triangle mesh, [`Renderer::for_each_triangle`] over
//! any mesh, which also clips), band binning, depth sorting and hidden-line.

use super::*;

/// Whether `tri` lies wholly above or below rows `row0..row1` (in 1/16 pixel): later
/// passes (bands) skip such triangles before anything else.
#[inline(always)]
pub(crate) fn outside_rows(tri: &[ScreenVertex; 3], row0: i32, row1: i32) -> bool {
    ys_outside_rows([tri[0].y(), tri[1].y(), tri[2].y()], row0, row1)
}

/// [`outside_rows`] for the corners' y alone.
#[inline(always)]
fn ys_outside_rows([a, b, c]: [i32; 3], row0: i32, row1: i32) -> bool {
    a.max(b).max(c) + 8 < row0 || a.min(b).min(c) + 8 > row1
}

/// A triangle corner as the walk sees it: a cache entry or a vertex fetched on demand.
pub(crate) trait Corner {
    /// Whether the corner has no screen position the rasterizer can take as it is.
    fn needs_clip(&self) -> bool;
    /// Its outcode (0 inside the view volume).
    fn code(&self) -> u8;
    /// Its screen x and y (1/16 pixel), when it does not need clipping.
    fn xy(&self) -> (i32, i32);
}

impl Corner for CachedVertex {
    #[inline(always)]
    fn needs_clip(&self) -> bool {
        self.marked()
    }
    #[inline(always)]
    fn code(&self) -> u8 {
        CachedVertex::code(self)
    }
    #[inline(always)]
    fn xy(&self) -> (i32, i32) {
        CachedVertex::xy(self)
    }
}

impl Corner for Fetched {
    #[inline(always)]
    fn needs_clip(&self) -> bool {
        self.code != 0
    }
    #[inline(always)]
    fn code(&self) -> u8 {
        self.code
    }
    #[inline(always)]
    fn xy(&self) -> (i32, i32) {
        (self.screen.x(), self.screen.y())
    }
}

/// What [`decide`] made of a triangle.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Seen {
    /// Drawn.
    Front,
    /// To be clipped (and counted) by the general path.
    Clip,
    /// Outside the view volume.
    Outside,
    /// Off the rows asked for (later passes only: not counted).
    OffRows,
    /// Dropped by the cull mode.
    Culled,
}

impl Seen {
    /// Count a decision other than [`Seen::Clip`] into `st`.
    #[inline(always)]
    pub(crate) fn count(self, st: &mut FrameStats) {
        st.triangles_in += u32::from(self != Seen::Clip);
        match self {
            Seen::Front => st.drawn += 1,
            Seen::Outside => st.outside += 1,
            Seen::Culled => st.culled += 1,
            Seen::Clip | Seen::OffRows => {}
        }
    }
}

/// The decision for one triangle: outside the view volume, to be clipped, outside
/// rows `rows` (in 1/16 pixel), culled, or drawn.
#[inline(always)]
pub(crate) fn decide<V: Corner>([a, b, c]: [&V; 3], rows: Option<(i32, i32)>, cull: Cull) -> Seen {
    if a.needs_clip() | b.needs_clip() | c.needs_clip() {
        if a.code() & b.code() & c.code() != 0 {
            return Seen::Outside;
        }
        return Seen::Clip;
    }
    let (pa, pb, pc) = (a.xy(), b.xy(), c.xy());
    if let Some((row0, row1)) = rows {
        if ys_outside_rows([pa.1, pb.1, pc.1], row0, row1) {
            return Seen::OffRows;
        }
    }
    if cull.drops(signed_area_guarded(pa, pb, pc)) {
        return Seen::Culled;
    }
    Seen::Front
}

/// The faces `first..` of a cached triangle mesh through [`decide`]: yields each face
/// to draw (`Some` corners) or to clip (`None`), in face order. Its loop holds no call,
/// and counts only the rare outcomes and the drawn faces (the culled ones, most of
/// them, are what is left over), so the compiler keeps its state in registers.
pub(crate) struct CachedWalk<'a> {
    faces: core::slice::Iter<'a, [u16; 3]>,
    /// The number of the next face.
    f: usize,
    walked: usize,
    cache: &'a [CachedVertex],
    cull: Cull,
    /// Faces by outcome: clipped (counted by the general path), outside, drawn.
    tally: [u32; 3],
}

impl<'a> CachedWalk<'a> {
    /// A walk over faces `faces` of `indices`, placed by `cache`.
    #[inline(always)]
    pub(crate) fn new(
        indices: &'a [[u16; 3]],
        faces: core::ops::Range<usize>,
        cache: &'a [CachedVertex],
        cull: Cull,
    ) -> Self {
        let first = faces.start;
        let faces = indices.get(faces).unwrap_or(&[]);
        CachedWalk {
            faces: faces.iter(),
            f: first,
            walked: faces.len(),
            cache,
            cull,
            tally: [0; 3],
        }
    }

    /// The geometry counts of the walk, once it has ended: every face walked but the
    /// clipped ones, which the general path counts.
    pub(crate) fn stats(&self) -> FrameStats {
        let [clip, outside, drawn] = self.tally;
        let triangles_in = self.walked as u32 - clip;
        FrameStats {
            triangles_in,
            outside,
            drawn,
            culled: triangles_in - outside - drawn,
            ..FrameStats::default()
        }
    }
}

impl<'a> Iterator for CachedWalk<'a> {
    type Item = Result<(usize, Option<[&'a CachedVertex; 3]>), Error>;

    #[inline(always)]
    fn next(&mut self) -> Option<Self::Item> {
        loop {
            let t = self.faces.next()?;
            let f = self.f;
            self.f += 1;
            let v = match cached_triangle(self.cache, f, t) {
                Ok(v) => v,
                Err(e) => return Some(Err(e)),
            };
            match decide(v, None, self.cull) {
                Seen::Culled | Seen::OffRows => continue,
                Seen::Front => {
                    self.tally[2] += 1;
                    return Some(Ok((f, Some(v))));
                }
                Seen::Clip => {
                    self.tally[0] += 1;
                    return Some(Ok((f, None)));
                }
                Seen::Outside => self.tally[1] += 1,
            }
        }
    }
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
/// The triangles of a polygon fanned around its first vertex.
pub(crate) fn fan(vs: &[u16]) -> impl Iterator<Item = (u16, u16, u16)> + '_ {
    let (first, rest) = vs.split_first().map_or((0, &[][..]), |(f, r)| (*f, r));
    rest.windows(2).filter_map(move |w| match *w {
        [b, c] => Some((first, b, c)),
        _ => None,
    })
}
/// The edges of a polygon, the closing one included.
pub(crate) fn edges(vs: &[u16]) -> impl Iterator<Item = (u16, u16)> + '_ {
    vs.iter().copied().zip(vs.iter().copied().cycle().skip(1))
}

impl<'m, 'c, M: Copy, S: RenderState> Renderer<'m, 'c, M, S> {
    /// Walk every triangle (fan-triangulated faces) that survives clipping and culling,
    /// calling `emit(face, screen triangle, vertex lights)`; returns the geometry counts.
    pub(crate) fn for_each_triangle<E>(
        &self,
        clip: &Clip,
        first: bool,
        faces: impl Iterator<Item = usize>,
        mut emit: impl FnMut(usize, M, &[ScreenVertex; 3], [Intensity; 3]) -> Result<(), DrawError<E>>,
    ) -> Result<FrameStats, DrawError<E>> {
        let mut st = FrameStats::default();
        let cull = self.options.cull;
        // Later passes (bands) skip the triangles off their rows.
        let rows = (!first).then(|| clip.subpixel_rows());
        for f in faces {
            let (vs, mat) = self.face(f)?;
            for (i0, i1, i2) in fan(vs) {
                let v0 = self.fetch(i0, f)?;
                let v1 = self.fetch(i1, f)?;
                let v2 = self.fetch(i2, f)?;
                let seen = decide([&v0, &v1, &v2], rows, cull);
                seen.count(&mut st);
                if seen == Seen::Front {
                    let tri = [v0.screen, v1.screen, v2.screen];
                    emit(f, mat, &tri, [v0.light, v1.light, v2.light])?;
                }
                if seen != Seen::Clip {
                    continue;
                }
                st.triangles_in += 1;
                st.clipped += 1;
                let mut poly = ClipPolygon::new();
                for v in [&v0, &v1, &v2] {
                    let p = self.mesh.positions.get(usize::from(v.index)).ok_or(
                        Error::IndexOutOfRange {
                            face: f,
                            index: usize::from(v.index),
                        },
                    )?;
                    let light = if self.shading() == Shading::Gouraud {
                        f32::from(self.vertex_light(usize::from(v.index)))
                    } else {
                        f32::from(ONE)
                    };
                    let _ = poly.push(ClipVertex {
                        c: self.clip_coords(p),
                        light,
                        uv: [0.0; 2],
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
}
