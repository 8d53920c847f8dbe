//! The face walk: every face of a mesh fetched, tested against the view volume and
//! the cull mode, clipped where it must be, and handed on as screen triangles.

use super::*;

/// Whether `tri` lies wholly above or below rows `row0..row1` (in 1/16 pixel): later
/// passes (bands) skip such triangles before anything else.
#[inline(always)]
pub(crate) fn outside_rows(tri: &[ScreenVertex; 3], row0: i32, row1: i32) -> bool {
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

impl<'m, 'c, M: Copy> Renderer<'m, 'c, M> {
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
}
