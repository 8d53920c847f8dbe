//! The face walk: one place decides, for every triangle of every face, whether it is
//! outside the view volume, needs clipping, lies off the rows asked for, is culled,
//! or is drawn ([`decide`]). Every renderer walks through it: the Z-buffer paths
//! ([`CachedWalk`] over a cached triangle mesh, [`Renderer::for_each_triangle`] over
//! any mesh, which also clips), band binning, depth sorting and hidden-line.

use super::*;
use crate::num::kernel::{bin_scan, skip_culled, skip_culled_by, BinChains, CullScan};
use crate::num::kernel::{ScanRegs, BIN_KERNEL, CULL_KERNEL};

/// Whether the placed cache entries lie wholly above or below rows `row0..row1` (in
/// 1/16 pixel): later passes (bands) skip such triangles before anything else.
#[inline(always)]
pub(crate) fn cached_outside_rows([a, b, c]: [&CachedVertex; 3], row0: i32, row1: i32) -> bool {
    ys_outside_rows([a.xy().1, b.xy().1, c.xy().1], row0, row1)
}

/// [`cached_outside_rows`] for the corners' y alone.
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

/// The faces `first..` of a cached triangle mesh through the decisions of [`decide`]:
/// yields each face to draw (`Some` corners) or to clip (`None`), in face order.
///
/// Its loop is the cull pass of a frame, so it is written for the common face (placed
/// corners, culled): three indices, three cache entries, an area in `i32` (cached
/// coordinates lie within ±2¹⁴, see [`CachedVertex`]) and one unsigned compare against
/// the cull mode's range of dropped areas ([`DropRange`]). It counts only the rare
/// outcomes and the drawn faces (the culled ones, most of them, are what is left over),
/// so the compiler keeps its few values in registers.
pub(crate) struct CachedWalk<'a> {
    faces: core::slice::Iter<'a, [u16; 3]>,
    /// The number of the first face.
    first: usize,
    walked: usize,
    cache: &'a [CachedVertex],
    drop: DropRange,
    /// Faces by outcome: clipped (counted by the general path), outside, drawn.
    tally: [u32; 3],
    /// Where there is an assembly scan over the dropped faces ([`CULL_KERNEL`]), the
    /// walk goes by it and by `pos`, the next face's place in the faces, instead of
    /// `faces` (which it leaves alone).
    scan: CullScan<'a, CachedVertex>,
    pos: usize,
    /// A copy of the scan's operands to read them from ([`CachedWalk::reading`]).
    operands: Option<&'a ScanRegs<'a>>,
}

/// The byte offset of a cache entry's word of x and y, which [`skip_culled`] reads.
const XY_AT: usize = core::mem::offset_of!(CachedVertex, xy);

/// The twice-signed screen areas a cull mode drops, as `area − lo ≤ span` in unsigned
/// arithmetic: one subtraction and one compare a face for any mode (zero is in every
/// range: a zero-area face is never drawn).
#[derive(Clone, Copy)]
pub(crate) struct DropRange {
    lo: i32,
    span: u32,
}

impl DropRange {
    pub(crate) fn of(cull: Cull) -> DropRange {
        let (lo, hi) = match cull {
            // Front faces have negative screen area (see `Cull::drops`).
            Cull::Back => (0, i32::MAX),
            Cull::Front => (i32::MIN, 0),
            Cull::None => (0, 0),
        };
        DropRange {
            lo,
            span: hi.wrapping_sub(lo) as u32,
        }
    }

    /// Whether a face of twice-signed screen area `area` is dropped.
    #[inline(always)]
    pub(crate) fn drops(self, area: i32) -> bool {
        area.wrapping_sub(self.lo) as u32 <= self.span
    }
}

/// Twice the signed area of three placed cache entries: their coordinates lie within
/// ±2¹⁴ (1/16 pixel), so each difference is below 2¹⁵, each product below 2³⁰ and the
/// area below 2³¹ in magnitude.
#[inline(always)]
fn cached_area(a: &CachedVertex, b: &CachedVertex, c: &CachedVertex) -> i32 {
    let ((xa, ya), (xb, yb), (xc, yc)) = (a.xy(), b.xy(), c.xy());
    (xb - xa) * (yc - ya) - (xc - xa) * (yb - ya)
}

/// [`CachedVertex::marked`] as a signed compare of x: a placed x lies within ±2¹⁴, the
/// mark below (the test `cached_areas_are_exact_at_the_limits` checks both). On Thumb-2
/// one compare of the x the area reads, not a compare of its low half.
#[inline(always)]
fn unplaced(v: &CachedVertex) -> bool {
    v.xy().0 < -(1 << 14)
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
        let drop = DropRange::of(cull);
        CachedWalk {
            faces: faces.iter(),
            first,
            walked: faces.len(),
            cache,
            drop,
            tally: [0; 3],
            scan: CullScan::new(faces, cache, XY_AT, CachedVertex::xy, drop.lo, drop.span),
            pos: 0,
            operands: None,
        }
    }

    /// A copy of the scan's operands, which the caller keeps (apart from the walk) for
    /// [`reading`](CachedWalk::reading).
    #[inline(always)]
    pub(crate) fn operands(&self) -> ScanRegs<'a> {
        self.scan.operands()
    }

    /// The walk reading the scan's operands from `operands`, its own copied (on
    /// ARMv7E-M by one LDM a call, see [`skip_culled_by`]), which the caller keeps
    /// apart from the walk. Any other operands are ignored: the scan trusts their
    /// lengths to index its own faces and cache.
    #[inline(always)]
    pub(crate) fn reading<'b>(self, operands: &'b ScanRegs<'b>) -> CachedWalk<'b>
    where
        'a: 'b,
    {
        let walk: CachedWalk<'b> = self;
        let own = *operands == walk.scan.operands();
        CachedWalk {
            operands: own.then_some(operands),
            ..walk
        }
    }

    /// The scan's place, the faces and the cache, for the fused face loop
    /// (`num::kernel::faces`), which goes on from there ([`CachedWalk::fused_to`]).
    #[inline(always)]
    pub(crate) fn fused(&self) -> (usize, &'a [[u16; 3]], &'a [CachedVertex]) {
        // Without an assembly scan the walk goes by `faces`.
        let pos = if CULL_KERNEL {
            self.pos
        } else {
            self.walked - self.faces.len()
        };
        (pos, self.scan.faces(), self.cache)
    }

    /// The walk on from the scan's place `pos`, `drawn` more faces drawn before it.
    #[inline(always)]
    pub(crate) fn fused_to(&mut self, pos: usize, drawn: u32) {
        self.pos = pos;
        if !CULL_KERNEL {
            self.faces = self.scan.faces().get(pos..).unwrap_or(&[]).iter();
        }
        self.tally[2] += drawn;
    }

    /// The number of the walk's first face.
    #[inline(always)]
    pub(crate) fn first(&self) -> usize {
        self.first
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
        if CULL_KERNEL {
            return self.next_scanned();
        }
        let (cache, drop) = (self.cache, self.drop);
        loop {
            let t = self.faces.next()?;
            // The face just taken: its number from how many are left (worked out for the
            // faces that leave the loop only).
            let f = |rest: &core::slice::Iter<'_, _>| self.first + self.walked - rest.len() - 1;
            let get = |i: u16| cache.get(usize::from(i));
            let (Some(a), Some(b), Some(c)) = (get(t[0]), get(t[1]), get(t[2])) else {
                let f = f(&self.faces);
                return Some(cached_triangle(cache, f, t).map(|_| (f, None)));
            };
            if unplaced(a) | unplaced(b) | unplaced(c) {
                if a.code() & b.code() & c.code() != 0 {
                    self.tally[1] += 1;
                    continue;
                }
                self.tally[0] += 1;
                return Some(Ok((f(&self.faces), None)));
            }
            if drop.drops(cached_area(a, b, c)) {
                continue;
            }
            self.tally[2] += 1;
            return Some(Ok((f(&self.faces), Some([a, b, c]))));
        }
    }
}

impl<'a> CachedWalk<'a> {
    /// [`Iterator::next`] for a banded frame's binning: where there is an assembly
    /// binning scan ([`BIN_KERNEL`], [`BinChains::scans`]) the drawn faces it finds on
    /// the way are binned into `chains` there ([`bin_scan`]) and counted, not returned;
    /// every other face comes back as `next` returns it (and elsewhere every face).
    #[inline(always)]
    pub(crate) fn next_binned(
        &mut self,
        chains: &mut BinChains<'_>,
    ) -> Option<<Self as Iterator>::Item> {
        if BIN_KERNEL && chains.scans() {
            let before = chains.drawn();
            bin_scan(&mut self.pos, &self.scan, chains);
            self.tally[2] += chains.drawn() - before;
        }
        self.next()
    }

    /// [`Iterator::next`] past the dropped faces in assembly ([`skip_culled`]), to the
    /// next face to look at: a face it finds drawn comes with its corners, any other
    /// takes the decisions of the Rust scan.
    #[inline(always)]
    fn next_scanned(&mut self) -> Option<<Self as Iterator>::Item> {
        let (cache, drop, faces) = (self.cache, self.drop, self.scan.faces());
        let get = |i: u16| cache.get(usize::from(i));
        loop {
            let found = match self.operands {
                Some(operands) => skip_culled_by(&mut self.pos, &self.scan, operands),
                None => skip_culled(&mut self.pos, &self.scan),
            };
            if let Some(corners) = found {
                let f = self.first + self.pos;
                self.pos += 1;
                self.tally[2] += 1;
                return Some(Ok((f, Some(corners))));
            }
            let t = faces.get(self.pos)?;
            let f = self.first + self.pos;
            self.pos += 1;
            let (Some(a), Some(b), Some(c)) = (get(t[0]), get(t[1]), get(t[2])) else {
                return Some(cached_triangle(cache, f, t).map(|_| (f, None)));
            };
            if unplaced(a) | unplaced(b) | unplaced(c) {
                if a.code() & b.code() & c.code() != 0 {
                    self.tally[1] += 1;
                    continue;
                }
                self.tally[0] += 1;
                return Some(Ok((f, None)));
            }
            if drop.drops(cached_area(a, b, c)) {
                continue;
            }
            self.tally[2] += 1;
            return Some(Ok((f, Some([a, b, c]))));
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
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cull pass's unsigned range test drops exactly what `Cull::drops` drops, over
    /// every area a cached triangle can have.
    #[test]
    fn drop_ranges_are_the_cull_modes() {
        let areas = [i32::MIN + 1, -(1 << 30), -2, -1, 0, 1, 2, 1 << 30, i32::MAX];
        for cull in [Cull::Back, Cull::Front, Cull::None] {
            for a in areas {
                assert_eq!(
                    DropRange::of(cull).drops(a),
                    cull.drops(i64::from(a)),
                    "{cull:?} {a}"
                );
            }
        }
    }

    /// The walk through the assembly scan's twin (`next_scanned`, on hosts the portable
    /// scan of `num::kernel`), also reading the scan's operands from a copy, yields the
    /// faces, errors and counts of the Rust walk, over random caches (unplaced corners,
    /// outside ones, extremes) and faces (bad indices, degenerate triangles), for every
    /// cull mode.
    #[test]
    fn the_scanned_walk_is_the_rust_walk() {
        let mut rnd = crate::num::kernel::xorshift32(0x1234_5679_u32);
        let m = (1 << 14) - 1;
        for case in 0..3000 {
            let cache: std::vec::Vec<CachedVertex> = (0..rnd() % 12)
                .map(|_| {
                    let r = rnd();
                    let c = |r: u32| match r % 6 {
                        0 => m,
                        1 => -m,
                        _ => (r >> 3) as i32 % (2 * m + 1) - m,
                    };
                    let code = if r.is_multiple_of(8) {
                        1 << ((r >> 3) % 3)
                    } else {
                        0
                    };
                    let (x, y) = (c(rnd()), c(rnd()));
                    CachedVertex::new(code, ScreenVertex::from_raw(x, y, rnd()))
                })
                .collect();
            let faces: std::vec::Vec<[u16; 3]> = (0..rnd() % 16)
                .map(|_| [0u16; 3].map(|_| (rnd() % (cache.len() as u32 + 2)) as u16))
                .collect();
            let cull = [Cull::Back, Cull::Front, Cull::None][case % 3];
            let start = rnd() as usize % 3;
            let range = start..faces.len().max(start);
            let mut rust = CachedWalk::new(&faces, range.clone(), &cache, cull);
            let mut scanned = CachedWalk::new(&faces, range.clone(), &cache, cull);
            let drawing = CachedWalk::new(&faces, range, &cache, cull);
            let operands = drawing.operands();
            let mut drawing = drawing.reading(&operands);
            type Item<'a> = <CachedWalk<'a> as Iterator>::Item;
            let key =
                |x: Option<Item<'_>>| x.map(|r| r.map(|(f, c)| (f, c.map(|c| c.map(|v| *v)))));
            loop {
                let (a, b) = (key(rust.next()), key(scanned.next_scanned()));
                assert_eq!(a, b, "case {case}");
                assert_eq!(a, key(drawing.next_scanned()), "case {case}");
                if a.is_none() {
                    break;
                }
            }
            assert_eq!(rust.stats(), scanned.stats(), "case {case}");
            assert_eq!(rust.stats(), drawing.stats(), "case {case}");
        }
    }

    /// The `i32` area of cached corners is the exact area at the cache's extremes.
    #[test]
    fn cached_areas_are_exact_at_the_limits() {
        let m = (1 << 14) - 1;
        let v = |x: i32, y: i32| CachedVertex::new(0, ScreenVertex::from_raw(x, y, 0));
        let corners = [(-m, -m), (m, -m), (m, m), (-m, m), (0, 0), (m, 0)];
        for p in corners {
            for q in corners {
                for r in corners {
                    let (a, b, c) = (v(p.0, p.1), v(q.0, q.1), v(r.0, r.1));
                    assert!(!(a.marked() | b.marked() | c.marked()));
                    assert!(!(unplaced(&a) | unplaced(&b) | unplaced(&c)));
                    assert_eq!(i64::from(cached_area(&a, &b, &c)), signed_area(p, q, r));
                }
            }
        }
        // One step further out is not placed: it takes the general path.
        assert!(v(1 << 14, 0).marked() && v(0, -(1 << 14)).marked());
        assert!(unplaced(&v(1 << 14, 0)) && unplaced(&v(0, -(1 << 14))));
        assert!(unplaced(&CachedVertex::new(1, ScreenVertex::ORIGIN)));
    }
}
