//! The fast path of the common case: a small triangle in one flat colour, drawn into a
//! colour buffer and a Z-buffer of the same geometry.
//!
//! It computes exactly what the general path computes (the same spans, the same depth
//! at every pixel: a test checks this on many random triangles), with everything in
//! local variables: edges set up in `i32` around a local origin, the depth plane's row
//! start stepped with one add a row, one index into both buffers, and the two halves of
//! the triangle walked by two plain loops.

use super::span::is_less;
use crate::fixed::{SUBPIXEL, SUBPIXEL_BITS};
use crate::num::kernel::cache_entries;
pub(crate) use crate::num::kernel::Buffers;
use crate::num::kernel::{rows_walk_less_as_u16, RowsAt, RowsWalk, WalkEdge, WALK_KERNEL};
use crate::num::kernel::{rows_x86, SmallDone, ROWS_KERNEL, ROWS_X86_KERNEL};
use crate::num::kernel::{small_less_as_u16, small_less_cached, two_bytes, CachedVertex};
use crate::num::kernel::{small_x86, SmallX86, SMALL_X86_KERNEL};
use crate::num::{div_floor_pair, floor_div32, floor_div32_pair_small, ARMV6M, DIVIDE, WIDE};
use crate::raster::{
    small_steps, EdgeDivide, EdgeWalk, ScreenVertex, SmallEdge, DEPTH_BIAS, SMALL,
};

/// The depth plane stepped per pixel and per row (wrapping `u32`, biased), with the
/// vertices' range to clamp each row start to: as [`crate::raster::DepthRows`] has it
/// for small triangles.
#[derive(Clone, Copy)]
struct Depth {
    sx: u32,
    sy: u32,
    lo: u32,
    hi: u32,
}

/// Where the row loop is: the depth at column 0 of the current row (local columns),
/// the index of that column in the buffers, and the counts so far.
struct Row {
    z: u32,
    base: usize,
    tested: u32,
    failed: u32,
}

/// Fill `tri` if it is small (extents below 512 pixels); `None` means "not for this
/// path", and nothing was drawn. Otherwise returns (pixels tested, pixels written).
#[inline(always)]
pub(crate) fn fill_small<C: Copy>(
    b: &mut Buffers<'_, '_, C>,
    tri: [&ScreenVertex; 3],
    color: C,
    write: bool,
    pass: impl Fn(u16, u16) -> bool + Copy,
) -> Option<(u32, u32)> {
    if ROWS_KERNEL {
        // ARMv7E-M: the kernel for `Less` with depth writes; the other tests keep the
        // general row loop.
        fill_small_with::<EdgeDivide, C>(b, tri, color, write, pass, true, false)
    } else if crate::num::DIVIDE {
        if write {
            fill_small_divide::<C, true>(b, tri, color, pass)
        } else {
            fill_small_divide::<C, false>(b, tri, color, pass)
        }
    } else if WALK_KERNEL {
        fill_small_walk(b, tri, color, write, pass)
    } else {
        fill_small_with::<EdgeWalk, C>(b, tri, color, write, pass, false, false)
    }
}

/// [`fill_small`] for the depth test `Less` with depth writes where a small
/// triangles' kernel runs, the corners as the vertex cache holds them, read in place
/// by ARMv7E-M's ([`small_less_cached`]) and ARMv6-M's ([`walk_cached`]); `None` as
/// [`fill_small`] has it (then also for a colour that is not two bytes, or without a
/// kernel).
#[inline(always)]
pub(crate) fn fill_small_cached<C: Copy>(
    b: &mut Buffers<'_, '_, C>,
    tri: [&CachedVertex; 3],
    color: C,
) -> Option<(u32, u32)> {
    if WALK_KERNEL {
        return walk_cached_or_none(b, tri, color);
    }
    if !ROWS_KERNEL {
        if !SMALL_X86_KERNEL {
            return None;
        }
        // x86-64: set-up and rows in one assembly block.
        let mut t = b.target();
        return match small_x86(&mut t, tri, color) {
            SmallX86::Drawn(tested, failed) => Some((tested, tested.wrapping_sub(failed))),
            SmallX86::Refused => None,
        };
    }
    let mut t = b.target();
    match small_less_cached(&mut t, tri, color) {
        SmallDone::Drawn(tested, failed) => Some((tested, tested.wrapping_sub(failed))),
        SmallDone::General => None,
    }
}

/// ARMv6-M's small triangle of cache entries `tri` (`Less` with depth writes, a
/// two-byte colour) by [`Buffers::walk_cached`] (set-up and rows in assembly, the
/// block's per-buffer fields written once for `b`): (pixels tested, pixels written),
/// or `None` (nothing drawn) for what it leaves to the general path.
#[inline(always)]
fn walk_cached_or_none<C: Copy>(
    b: &mut Buffers<'_, '_, C>,
    tri: [&CachedVertex; 3],
    color: C,
) -> Option<(u32, u32)> {
    match b.walk_cached(tri, color) {
        SmallDone::Drawn(tested, failed) => Some((tested, tested.wrapping_sub(failed))),
        SmallDone::General => None,
    }
}

/// ARMv6-M's small path: `Less` with depth writes in a two-byte colour by
/// [`walk_cached`] (set-up and rows in assembly) when the corners fit the vertex
/// cache's form, what it leaves (steep depth, a clip beyond the buffers: rare) by the
/// general path; the other tests by [`fill_small_with`].
#[inline(always)]
fn fill_small_walk<C: Copy>(
    b: &mut Buffers<'_, '_, C>,
    tri: [&ScreenVertex; 3],
    color: C,
    write: bool,
    pass: impl Fn(u16, u16) -> bool + Copy,
) -> Option<(u32, u32)> {
    if write && is_less(&pass) && two_bytes::<C>() {
        let [p, q, r] = cache_entries(tri)?;
        return walk_cached_or_none(b, [&p, &q, &r], color);
    }
    fill_small_with::<EdgeWalk, C>(b, tri, color, write, pass, false, true)
}

/// [`fill_small`] with edges of kind `E`; with `kernel`, the depth test `Less` with
/// depth writes in a two-byte colour goes to [`small_less_as_u16`] (set-up and rows;
/// what it leaves goes to the general path); with `walk`, to ARMv6-M's
/// [`rows_walk_less_as_u16`] after the set-up here (which may refuse: then `None`,
/// and the general path draws the triangle; with `walk`, `Less` without depth writes
/// is `None` too).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn fill_small_with<E: SmallEdge, C: Copy>(
    b: &mut Buffers<'_, '_, C>,
    tri: [&ScreenVertex; 3],
    color: C,
    write: bool,
    pass: impl Fn(u16, u16) -> bool + Copy,
    kernel: bool,
    walk: bool,
) -> Option<(u32, u32)> {
    if kernel && write && is_less(&pass) && two_bytes::<C>() {
        let mut t = b.target();
        return match small_less_as_u16(&mut t, tri, color) {
            SmallDone::Drawn(tested, failed) => Some((tested, tested.wrapping_sub(failed))),
            SmallDone::General => None,
        };
    }
    let [p0, p1, p2] = tri;
    let top = by_rows(tri);
    let (xmin, xmax) = (
        p0.x().min(p1.x()).min(p2.x()),
        p0.x().max(p1.x()).max(p2.x()),
    );
    let (ymin, ymax) = (top[0].y(), top[2].y());
    if xmax - xmin >= SMALL || ymax - ymin >= SMALL {
        return None;
    }
    // The rows whose centres may be covered, inside the clip: nothing more is worked
    // out for a triangle above or below it (a band's neighbours). One left or right
    // of it (rare: bands are whole rows) finds each row's columns empty.
    let centre = |v: i32| (v + (SUBPIXEL / 2 - 1)) >> SUBPIXEL_BITS;
    let clip = b.clip;
    let (start, end) = (centre(ymin).max(clip.y0), centre(ymax).min(clip.y1));
    if start >= end {
        return Some((0, 0));
    }
    let (ox, oy) = (xmin & !(SUBPIXEL - 1), ymin & !(SUBPIXEL - 1));
    let Some((q, r, mid_right)) = small_steps_q(top) else {
        return Some((0, 0));
    };
    let depth = Depth {
        sx: q << 4,
        sy: r << 4,
        lo: p0.z().min(p1.z()).min(p2.z()) + DEPTH_BIAS,
        hi: p0.z().max(p1.z()).max(p2.z()) + DEPTH_BIAS,
    };
    let local = |p: &ScreenVertex| (p.x() - ox, p.y() - oy);
    let [v0, v1, v2] = top.map(local);
    let (px0, py0) = (ox >> SUBPIXEL_BITS, oy >> SUBPIXEL_BITS);
    let mid = centre(v1.1) + py0;
    let (cx0, cx1) = (clip.x0 - px0, clip.x1 - px0);

    // Column 0 of row `start`: its depth and its index (wrapping: it may lie left of
    // the buffer; the indices of covered columns do not).
    let at = (p0.x() - ox, p0.y() - start * SUBPIXEL);
    let mut row = Row {
        z: small_origin(p0.z(), at, q, r),
        base: ((start - b.first_row) as usize * b.width).wrapping_add(px0 as usize),
        tested: 0,
        failed: 0,
    };
    if walk && is_less(&pass) && two_bytes::<C>() {
        // Without depth writes (rare) the general path draws it: the row loop below is
        // then not built for `Less` at all.
        if !write {
            return None;
        }
        let (rows, at) = ((start, mid, end, py0), (start - b.first_row, px0, row.z));
        return small_walk(
            b,
            [v0, v1, v2],
            mid_right,
            rows,
            at,
            depth,
            (cx0, cx1),
            color,
        );
    }
    let edge = |a: (i32, i32), c: (i32, i32), py: i32| E::new(a, c, py - py0);
    let mut long = edge(v0, v2, start);
    // Two calls in each half rather than a choice of references: the loop then keeps
    // each edge in the same registers every row.
    let upper_end = mid.min(end);
    if start < upper_end {
        let mut short = edge(v0, v1, start);
        let n = upper_end - start;
        if mid_right {
            rows(
                b,
                &mut long,
                &mut short,
                n,
                &mut row,
                depth,
                (cx0, cx1),
                color,
                write,
                pass,
            );
        } else {
            rows(
                b,
                &mut short,
                &mut long,
                n,
                &mut row,
                depth,
                (cx0, cx1),
                color,
                write,
                pass,
            );
        }
    }
    let lower_start = mid.max(start);
    if lower_start < end {
        let mut short = edge(v1, v2, lower_start);
        let n = end - lower_start;
        if mid_right {
            rows(
                b,
                &mut long,
                &mut short,
                n,
                &mut row,
                depth,
                (cx0, cx1),
                color,
                write,
                pass,
            );
        } else {
            rows(
                b,
                &mut short,
                &mut long,
                n,
                &mut row,
                depth,
                (cx0, cx1),
                color,
                write,
                pass,
            );
        }
    }
    Some((row.tested, row.tested - row.failed))
}

/// [`fill_small`] on cores with a divide instruction and no assembly for the case
/// (x86-64, AArch64, RISC-V, ARMv7-M): what
/// [`fill_small_with`] does with [`EdgeDivide`] edges, its rows through
/// [`rows_divide`] with the depth write `WRITE` fixed.
#[inline(always)]
fn fill_small_divide<C: Copy, const WRITE: bool>(
    b: &mut Buffers<'_, '_, C>,
    tri: [&ScreenVertex; 3],
    color: C,
    pass: impl Fn(u16, u16) -> bool + Copy,
) -> Option<(u32, u32)> {
    let p0 = tri[0];
    let [a, m, c] = by_rows(tri);
    let xmin = a.x().min(m.x()).min(c.x());
    let xmax = a.x().max(m.x()).max(c.x());
    if c.y() - a.y() >= SMALL || xmax - xmin >= SMALL {
        return None;
    }
    // Rows whose centres may be covered, inside the clip; the middle corner's row
    // between them splits the halves.
    let centre = |y: i32| (y + (SUBPIXEL / 2 - 1)) >> SUBPIXEL_BITS;
    let clip = b.clip;
    let (start, end) = (centre(a.y()).max(clip.y0), centre(c.y()).min(clip.y1));
    if start >= end {
        return Some((0, 0));
    }
    let mid = centre(m.y()).max(start).min(end);
    let (dxl, dyl) = (c.x() - a.x(), c.y() - a.y());
    let (dxs, dys) = (m.x() - a.x(), m.y() - a.y());
    let area = dxs * dyl - dxl * dys; // |·| < 2²⁷
    if area == 0 {
        return Some((0, 0));
    }
    let (q, r) = steps_q([a, m, c], (dxs, dys), (dxl, dyl), area);
    let depth = Depth {
        sx: q << 4,
        sy: r << 4,
        lo: a.z().min(m.z()).min(c.z()) + DEPTH_BIAS,
        hi: a.z().max(m.z()).max(c.z()) + DEPTH_BIAS,
    };
    // Columns local to px0, the pixel column of the leftmost corner: an edge's `t` at
    // row y is (16y + 8 − a.y)·dx + (a.x − 16px0 + 8)·dy − 1, as `EdgeDivide::new`.
    let px0 = xmin >> SUBPIXEL_BITS;
    let edge = |s: i32, x: i32, dx: i32, dy: i32| EdgeDivide {
        t: (s * dx + x * dy - 1) as u32,
        dt: (dx * SUBPIXEL) as u32,
        d: (dy * SUBPIXEL) as u32,
    };
    let (s, xa) = (
        SUBPIXEL * start + SUBPIXEL / 2 - a.y(),
        a.x() - SUBPIXEL * px0 + SUBPIXEL / 2,
    );
    let mut long = edge(s, xa, dxl, dyl);
    // The depth at local column 0 of row `start`, from the first corner given.
    let at = (p0.x() - SUBPIXEL * px0, p0.y() - SUBPIXEL * start);
    let mut row = Row {
        z: small_origin(p0.z(), at, q, r),
        base: ((start - b.first_row) as usize * b.width).wrapping_add(px0 as usize),
        tested: 0,
        failed: 0,
    };
    // Both buffers cut to one length: a row's one bounds test then serves both.
    let width = b.width;
    let (zdata, cdata) = b.parts();
    let len = zdata.len().min(cdata.len());
    let (Some(zw), Some(cw)) = (zdata.get_mut(..len), cdata.get_mut(..len)) else {
        return None;
    };
    let cx = (clip.x0 - px0, clip.x1 - px0);
    let mut run = |left: &mut EdgeDivide, right: &mut EdgeDivide, n: i32, row: &mut Row| {
        rows_divide::<C, WRITE>(zw, cw, width, left, right, n, row, depth, cx, color, pass)
    };
    let mid_right = area > 0;
    if start < mid {
        let mut short = edge(s, xa, dxs, dys);
        if mid_right {
            run(&mut long, &mut short, mid - start, &mut row);
        } else {
            run(&mut short, &mut long, mid - start, &mut row);
        }
    }
    if mid < end {
        let s1 = SUBPIXEL * mid + SUBPIXEL / 2 - m.y();
        let mut short = edge(s1, xa + dxs, dxl - dxs, dyl - dys);
        if mid_right {
            run(&mut long, &mut short, end - mid, &mut row);
        } else {
            run(&mut short, &mut long, end - mid, &mut row);
        }
    }
    Some((row.tested, row.tested - row.failed))
}

/// [`small_steps_q`]'s steps for corners sorted top to bottom whose offsets from the
/// first, (`dxs`, `dys`) and (`dxl`, `dyl`), and non-zero area are already known.
#[inline(always)]
fn steps_q(
    [a, m, c]: [&ScreenVertex; 3],
    (dxs, dys): (i32, i32),
    (dxl, dyl): (i32, i32),
    area: i32,
) -> (u32, u32) {
    let zq = |p: &ScreenVertex| (p.z() >> 4) as i32; // < 2²⁸
    let (dz1, dz2) = (zq(m) - zq(a), zq(c) - zq(a));
    let cross =
        |a: i32, b: i32, c: i32, d: i32| i64::from(a) * i64::from(b) - i64::from(c) * i64::from(d);
    let (na, nb) = (cross(dz1, dyl, dz2, dys), cross(dz2, dxs, dz1, dxl));
    if WIDE {
        // A 64-bit divide instruction: |16n| < 2⁴⁶, no range to test.
        let (q, r) = div_floor_pair(na * 16, nb * 16, i64::from(area));
        return (q as u32, r as u32);
    }
    // In [−2²⁶, 2²⁶): 16n and the area's sign folded in stay inside i32.
    let fits = |n: i64| i64::from((n as i32) << 5 >> 5) == n;
    if fits(na) && fits(nb) {
        let m = area >> 31;
        let fold = |n: i64| (((n as i32) << 4) ^ m) - m;
        let d = (area ^ m) - m;
        (
            floor_div32(fold(na), d) as u32,
            floor_div32(fold(nb), d) as u32,
        )
    } else {
        let (sx, sy) = small_steps([a, m, c]).unwrap_or_default();
        ((sx >> 4) as u32, (sy >> 4) as u32)
    }
}

/// [`rows`] for [`fill_small_divide`]: buffers `z`, `c` of one length, rows `width`
/// apart, the depth write `WRITE`, every span inline but the long ones.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn rows_divide<C: Copy, const WRITE: bool>(
    z: &mut [u16],
    c: &mut [C],
    width: usize,
    left: &mut EdgeDivide,
    right: &mut EdgeDivide,
    n: i32,
    row: &mut Row,
    d: Depth,
    (cx0, cx1): (i32, i32),
    color: C,
    pass: impl Fn(u16, u16) -> bool,
) {
    if ROWS_X86_KERNEL && WRITE && is_less(&pass) {
        // x86-64: the assembly loop, where the rows lie inside the buffers.
        let (l, r) = (
            (&mut left.t, left.dt, left.d),
            (&mut right.t, right.dt, right.d),
        );
        let steps = [d.sx, d.sy, d.lo, d.hi];
        let at = (&mut row.z, &mut row.base, width);
        if let Some((t, f)) = rows_x86((l, r), n, steps, (cx0, cx1), at, z, c, color) {
            row.tested += t;
            row.failed += f;
            return;
        }
    }
    let (mut zrow, mut base) = (row.z, row.base);
    let (mut tested, mut failed) = (row.tested, row.failed);
    let mut n = n;
    while n > 0 {
        n -= 1;
        let (xa, xb) = (left.x().max(cx0), right.x().min(cx1));
        left.advance();
        right.advance();
        if xa < xb {
            let mut acc = zrow
                .wrapping_add((xa as u32).wrapping_mul(d.sx))
                .max(d.lo)
                .min(d.hi);
            let (s, e) = (
                base.wrapping_add(xa as usize),
                base.wrapping_add(xb as usize),
            );
            if let (Some(zr), Some(cr)) = (z.get_mut(s..e), c.get_mut(s..e)) {
                tested += (xb - xa) as u32;
                if zr.len() >= LONG {
                    failed += super::flat_span(zr, cr, acc, d.sx, color, WRITE, &pass);
                } else {
                    // A failure out of line: the loop then stays rolled.
                    for (zp, cp) in zr.iter_mut().zip(cr) {
                        let v = (acc >> 16) as u16;
                        acc = acc.wrapping_add(d.sx);
                        if pass(v, *zp) {
                            if WRITE {
                                *zp = v;
                            }
                            *cp = color;
                        } else {
                            super::span::one_failed(&mut failed);
                        }
                    }
                }
            }
        }
        zrow = zrow.wrapping_add(d.sy);
        base = base.wrapping_add(width);
    }
    (row.z, row.base, row.tested, row.failed) = (zrow, base, tested, failed);
}

/// Spans from this length on leave [`rows_divide`] for [`flat_span`](super::flat_span).
const LONG: usize = 8;

/// The vertices of `tri` top to bottom (a stable sort by y).
#[inline(always)]
fn by_rows(mut v: [&ScreenVertex; 3]) -> [&ScreenVertex; 3] {
    if v[1].y() < v[0].y() {
        v.swap(0, 1);
    }
    if v[2].y() < v[1].y() {
        v.swap(1, 2);
    }
    if v[1].y() < v[0].y() {
        v.swap(0, 1);
    }
    v
}

/// [`fill_small_with`]'s rows through ARMv6-M's loop [`rows_walk_less_as_u16`], edges
/// in the [`EdgeWalk`] form: vertices `v` sorted top to bottom (local coordinates),
/// rows `start..end` split at `mid`, the first at buffer row `row0`, local column 0 at
/// `px0` with depth `z`. `None` when it refuses (nothing drawn).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn small_walk<C: Copy>(
    b: &mut Buffers<'_, '_, C>,
    [v0, v1, v2]: [(i32, i32); 3],
    mid_right: bool,
    (start, mid, end, py0): (i32, i32, i32, i32),
    (row0, px0, z): (i32, i32, u32),
    d: Depth,
    cx: (i32, i32),
    color: C,
) -> Option<(u32, u32)> {
    let edge = |a: (i32, i32), c: (i32, i32), py: i32| {
        WalkEdge::from_parts(EdgeWalk::new_small(a, c, py - py0).parts())
    };
    let lower_start = mid.max(start);
    let (n0, n1) = ((mid.min(end) - start).max(0), (end - lower_start).max(0));
    // A half with no rows has no short edge to walk (it may be flat).
    let short = |n: i32, a, c, py| {
        if n > 0 {
            edge(a, c, py)
        } else {
            WalkEdge::default()
        }
    };
    let short = [short(n0, v0, v1, start), short(n1, v1, v2, lower_start)];
    let depth = [d.sx, d.sy, d.lo, d.hi];
    let long = edge(v0, v2, start);
    let mut r = RowsWalk::new(depth, [cx.0, cx.1], long, short, n1 as u32, mid_right);
    let at = RowsAt {
        row0: row0 as usize,
        width: b.width,
        px0,
        n0: n0 as u32,
        z,
    };
    let (z, c) = b.parts();
    let (tested, failed) = rows_walk_less_as_u16(&mut r, at, z, c, color)?;
    Some((tested, tested.wrapping_sub(failed)))
}

/// [`small_steps`] over 16 (the steps a pixel in 20.12, `⌊16a/area⌋` and
/// `⌊16b/area⌋`) modulo 2³², for vertices sorted top to bottom ([`by_rows`]), and
/// whether the middle one lies right of the long edge; `None` for zero area. That is
/// all the small path needs: its steps are these times 16, and its depths
/// ([`small_origin`]) depend on them only modulo 2³². The order of the vertices does
/// not change the steps (a permutation turns the signs of `a`, `b` and the area
/// alike), so they are the sorted vertices' and the area is worked out once.
///
/// With a divide instruction, numerators `a`, `b` in [−2²⁶, 2²⁶) (the usual: tens of
/// depth units across a few pixels; one test each, a round trip through 27 bits) take
/// two 32-bit divisions by |area| (< 2²⁷): 16a then lies inside ±2³⁰, so folding in
/// the area's sign (`(n ^ m) − m`) cannot overflow, and ⌊16a/area⌋ = ⌊±16a/|area|⌋ is
/// the quotient small_steps finds.
/// Anything else takes small_steps itself.
#[inline(always)]
fn small_steps_q([p0, p1, p2]: [&ScreenVertex; 3]) -> Option<(u32, u32, bool)> {
    let (dx1, dy1) = (p1.x() - p0.x(), p1.y() - p0.y());
    let (dx2, dy2) = (p2.x() - p0.x(), p2.y() - p0.y());
    let area = dx1 * dy2 - dx2 * dy1; // |·| < 2²⁷
    if area == 0 {
        return None;
    }
    // With y down, a positive area in sorted order puts v1 right of v0→v2.
    let mid_right = area > 0;
    if DIVIDE {
        let zq = |p: &ScreenVertex| (p.z() >> 4) as i32; // < 2²⁸
        let (dz1, dz2) = (zq(p1) - zq(p0), zq(p2) - zq(p0));
        let cross = |a: i32, b: i32, c: i32, d: i32| {
            i64::from(a) * i64::from(b) - i64::from(c) * i64::from(d)
        };
        let (a, b) = (cross(dz1, dy2, dz2, dy1), cross(dz2, dx1, dz1, dx2));
        // a and b in [−2²⁶, 2²⁶): they survive a round trip through 27 bits.
        let fits = |n: i64| i64::from((n as i32) << 5 >> 5) == n;
        if fits(a) && fits(b) {
            let m = area >> 31;
            let fold = |n: i64| (((n as i32) << 4) ^ m) - m;
            let d = (area ^ m) - m;
            return Some((
                floor_div32(fold(a), d) as u32,
                floor_div32(fold(b), d) as u32,
                mid_right,
            ));
        }
    }
    if ARMV6M {
        let (q, r) = steps_narrow([p0, p1, p2], [dx1, dy1, dx2, dy2], area)
            .unwrap_or_else(|| steps_wide([p0, p1, p2]));
        return Some((q, r, mid_right));
    }
    let (sx, sy) = small_steps([p0, p1, p2])?;
    Some(((sx >> 4) as u32, (sy >> 4) as u32, mid_right))
}

/// [`small_steps`] over 16 for a triangle of non-zero area, out of line: on ARMv6-M
/// the rare triangle [`steps_narrow`] leaves.
#[inline(never)]
fn steps_wide(tri: [&ScreenVertex; 3]) -> (u32, u32) {
    let (sx, sy) = small_steps(tri).unwrap_or((0, 0));
    ((sx >> 4) as u32, (sy >> 4) as u32)
}

/// [`small_steps_q`]'s quotients without a divide instruction (ARMv6-M) for the usual
/// small triangle: `|area| < 2¹⁶` and numerators `a`, `b` inside ±(2²⁷ − 1), which
/// then come out of 32-bit products and take one reciprocal of |area| between them
/// ([`floor_div32_pair_small`]); `None` otherwise.
///
/// `a = dz₁·dy₂ − dz₂·dy₁` is worked out modulo 2³² (wrapping products) and, to tell
/// whether that is `a` itself, over 2¹⁶: with `dz = h·2¹⁶ + l` (`0 ≤ l < 2¹⁶`, `|h| ≤
/// 2¹²`) and every `|dx|`, `|dy|` below 2¹³, `a = (h₁·dy₂ − h₂·dy₁)·2¹⁶ + L` with
/// `|L| < 2³⁰`; a high part in [−2¹², 2¹²) puts `|a|` below 2²⁸ + 2³⁰ < 2³¹, where the
/// wrapped value is exact (likewise `b`). Then `16a` fits `i32`, and so does its
/// negation.
#[inline(always)]
fn steps_narrow(
    [p0, p1, p2]: [&ScreenVertex; 3],
    [dx1, dy1, dx2, dy2]: [i32; 4],
    area: i32,
) -> Option<(u32, u32)> {
    let d = area.unsigned_abs();
    if d >= 1 << 16 {
        return None;
    }
    let zq = |p: &ScreenVertex| (p.z() >> 4) as i32; // < 2²⁸
    let (dz1, dz2) = (zq(p1) - zq(p0), zq(p2) - zq(p0));
    let cross = |a: i32, b: i32, c: i32, d: i32| a.wrapping_mul(b).wrapping_sub(c.wrapping_mul(d));
    let (a, b) = (cross(dz1, dy2, dz2, dy1), cross(dz2, dx1, dz1, dx2));
    let (h1, h2) = (dz1 >> 16, dz2 >> 16);
    let (ah, bh) = (cross(h1, dy2, h2, dy1), cross(h2, dx1, h1, dx2));
    let within = |v: i32, lim: i32| (v.wrapping_add(lim - 1) as u32) < (2 * lim - 1) as u32;
    // Both high parts in [−2¹², 2¹²) by one test.
    let high = (ah.wrapping_add(1 << 12) | bh.wrapping_add(1 << 12)) as u32;
    if !(high < 1 << 13 && within(a, 1 << 27) && within(b, 1 << 27)) {
        return None;
    }
    let m = area >> 31;
    let fold = |n: i32| ((n << 4) ^ m) - m;
    let (q, r) = floor_div32_pair_small(fold(a), fold(b), d);
    Some((q as u32, r as u32))
}

/// The biased depth, modulo 2³², at the centre of a pixel whose top-left corner lies
/// `(x, y)` (1/16 pixel) above-left of the vertex of depth `z` the plane is taken
/// from, for the steps `16q`, `16r` of [`small_steps_q`]:
/// `z + DEPTH_BIAS + q·(8 − x) + r·(8 − y)`.
///
/// This is [`plane_origin`](crate::raster::plane_origin) stepped to that pixel: for
/// steps `sx = 16q`, `sy = 16r` its floor `⌊(sx·(8 − xf) + sy·(8 − yf))/16⌋` is exactly
/// `q·(8 − xf) + r·(8 − yf)` (no rounding, and no wrapping in `i64`: |q|, |r| < 2⁵⁰),
/// its whole-pixel parts `−16q·xi − 16r·yi` join them as `q·(8 − x₀) + r·(8 − y₀)`,
/// and each pixel stepped adds 16q or 16r: modulo 2³² only q and r modulo 2³² count.
#[inline(always)]
fn small_origin(z: u32, (x, y): (i32, i32), q: u32, r: u32) -> u32 {
    let half = (SUBPIXEL / 2) as u32;
    z.wrapping_add(DEPTH_BIAS)
        .wrapping_add(q.wrapping_mul(half.wrapping_sub(x as u32)))
        .wrapping_add(r.wrapping_mul(half.wrapping_sub(y as u32)))
}

/// `n` rows between the `left` and `right` edges, columns clipped to `cx0..cx1`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn rows<C: Copy>(
    b: &mut Buffers<'_, '_, C>,
    left: &mut impl SmallEdge,
    right: &mut impl SmallEdge,
    n: i32,
    row: &mut Row,
    d: Depth,
    (cx0, cx1): (i32, i32),
    color: C,
    write: bool,
    pass: impl Fn(u16, u16) -> bool,
) {
    let width = b.width;
    let (zdata, cdata) = b.parts();
    for _ in 0..n {
        let (xa, xb) = (left.x().max(cx0), right.x().min(cx1));
        left.advance();
        right.advance();
        if xa < xb {
            // lo ≤ hi: max then min is the clamp, without `clamp`'s check.
            let acc = row
                .z
                .wrapping_add((xa as u32).wrapping_mul(d.sx))
                .max(d.lo)
                .min(d.hi);
            let (s, e) = (
                row.base.wrapping_add(xa as usize),
                row.base.wrapping_add(xb as usize),
            );
            if e == s + 1 {
                // One pixel, the commonest row of a small triangle: no call.
                if let (Some(zp), Some(cp)) = (zdata.get_mut(s), cdata.get_mut(s)) {
                    let z = (acc >> 16) as u16;
                    row.tested += 1;
                    if pass(z, *zp) {
                        if write {
                            *zp = z;
                        }
                        *cp = color;
                    } else {
                        row.failed += 1;
                    }
                }
            } else if crate::num::ARM && e == s + 2 {
                // Two pixels inline too on Arm (x86-64 does better calling).
                if let (Some([z0, z1]), Some([c0, c1])) = (
                    zdata
                        .get_mut(s..e)
                        .and_then(|z| <&mut [u16; 2]>::try_from(z).ok()),
                    cdata
                        .get_mut(s..e)
                        .and_then(|c| <&mut [C; 2]>::try_from(c).ok()),
                ) {
                    row.tested += 2;
                    let mut px = |zp: &mut u16, cp: &mut C, acc: u32| {
                        let z = (acc >> 16) as u16;
                        if pass(z, *zp) {
                            if write {
                                *zp = z;
                            }
                            *cp = color;
                        } else {
                            row.failed += 1;
                        }
                    };
                    px(z0, c0, acc);
                    px(z1, c1, acc.wrapping_add(d.sx));
                }
            } else if let (Some(zr), Some(cr)) = (zdata.get_mut(s..e), cdata.get_mut(s..e)) {
                row.tested += (xb - xa) as u32;
                row.failed += super::flat_span(zr, cr, acc, d.sx, color, write, &pass);
            }
        }
        row.z = row.z.wrapping_add(d.sy);
        row.base = row.base.wrapping_add(width);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::Clip;
    use std::vec;

    /// `small_steps_q` and `small_origin` give the steps and depths of `small_steps`
    /// and `plane_origin` (modulo 2³²) on random small triangles: depths across the
    /// whole range and a few units apart, extents from 1 to 511 pixels, both windings,
    /// the area's and the numerators' 32-bit limits on either side; so does ARMv6-M's
    /// `steps_narrow` wherever it takes the triangle, and `steps_wide` everywhere.
    #[test]
    fn small_depth_matches_the_plane_origin() {
        use crate::raster::plane_origin;
        let mut rnd = crate::testing::xorshift32(0x5eed_1234);
        let mut narrow_cases = 0;
        for i in 0..200_000u32 {
            let mut r = |m: u32| rnd() % m;
            let span = [40, 160, 2048, SMALL as u32][(i % 4) as usize];
            const MAX: u32 = crate::fixed::MAX_DEPTH;
            let z0 = r(MAX);
            let spread = [1 << 12, 1 << 20, 1 << 28, MAX][(i / 4 % 4) as usize];
            let mut vertex = || {
                let (x, y) = (r(span) as i32 + 300, r(span) as i32 - 100);
                let z = if spread == MAX {
                    r(MAX + 1)
                } else {
                    z0.saturating_add(r(spread)).min(MAX)
                };
                ScreenVertex::new(x, y, z).unwrap()
            };
            let tri = [vertex(), vertex(), vertex()];
            let t = tri.each_ref();
            let (want, got) = (small_steps(t), small_steps_q(by_rows(t)));
            let Some((sx, sy)) = want else {
                assert!(got.is_none(), "{tri:?}");
                continue;
            };
            let (q, r0, mid_right) = got.unwrap();
            let [v0, v1, v2] = by_rows(t).map(|p| (p.x(), p.y()));
            let area = (v1.0 - v0.0) * (v2.1 - v0.1) - (v2.0 - v0.0) * (v1.1 - v0.1);
            assert_eq!(mid_right, area > 0, "{tri:?}");
            assert_eq!((q << 4, r0 << 4), (sx as u32, sy as u32), "{tri:?}");
            // ARMv6-M's narrow form, where it takes the triangle, and its fallback.
            assert_eq!(steps_wide(by_rows(t)), (q, r0), "{tri:?}");
            let [d0, d1, d2] = by_rows(t).map(|p| (p.x(), p.y()));
            let d = [d1.0 - d0.0, d1.1 - d0.1, d2.0 - d0.0, d2.1 - d0.1];
            if let Some(narrow) = steps_narrow(by_rows(t), d, area) {
                assert_eq!(narrow, (q, r0), "{tri:?}");
                narrow_cases += 1;
            }
            // `fill_small_divide`'s form, from the sorted corners' offsets.
            let [a, m, c] = by_rows(t);
            let (s, l) = (
                (m.x() - a.x(), m.y() - a.y()),
                (c.x() - a.x(), c.y() - a.y()),
            );
            assert_eq!(steps_q([a, m, c], s, l, area), (q, r0), "{tri:?}");
            let (cx, cy) = (r(64) as i32 + 10, r(64) as i32 - 20);
            let z00 = plane_origin(&tri[0], sx, sy)
                .wrapping_add((cx as u32).wrapping_mul(sx as u32))
                .wrapping_add((cy as u32).wrapping_mul(sy as u32));
            let at = (tri[0].x() - cx * SUBPIXEL, tri[0].y() - cy * SUBPIXEL);
            assert_eq!(small_origin(tri[0].z(), at, q, r0), z00, "{tri:?}");
        }
        assert!(narrow_cases > 50_000, "{narrow_cases} narrow cases");
    }

    /// The rows through `small_less_as_u16` (on the host its portable twin, on ARMv7E-M
    /// the assembly) and through `rows_walk_less_as_u16` (its twin; on ARMv6-M the
    /// assembly) give the pixels, depths and counts of the row loop, for random
    /// triangles from 3 to 700 pixels across (from 512 on, neither takes the small
    /// path), clipped by every side, in buffers that start on row 3 (a band).
    #[test]
    fn kernel_rows_match_the_row_loop() {
        const W: usize = 40;
        const H: usize = 30;
        let mut rnd = crate::testing::xorshift32(0x0bad_cafe);
        let less = |a: u16, b: u16| a < b;
        let mut cached_taken = 0;
        for i in 0..20_000u32 {
            let span = [3, 12, 40, 700][(i % 4) as usize];
            let mut r = |m: i32| (rnd() % m as u32) as i32;
            let vertex = |r: &mut dyn FnMut(i32) -> i32| {
                let (x, y) = (r(span * 16) - 64, r(span * 16) - 16 + 48);
                ScreenVertex::new(x, y, r(1 << 20) as u32 * 4096).unwrap()
            };
            let tri = [vertex(&mut r), vertex(&mut r), vertex(&mut r)];
            let clip = if i % 3 == 0 {
                Clip {
                    x0: r(12),
                    y0: 3 + r(10),
                    x1: W as i32 - r(12),
                    y1: 3 + H as i32 - r(10),
                }
            } else {
                Clip {
                    x0: 0,
                    y0: 3,
                    x1: W as i32,
                    y1: 3 + H as i32,
                }
            };
            let depth: vec::Vec<u16> = (0..W * H).map(|_| (r(65536) | 0x4000) as u16).collect();
            // The row loop, `rows_less_as_u16` (`Some(false)`), `rows_walk_less_as_u16`.
            let run = |kernel: Option<bool>, write: bool| {
                let (mut zdata, mut cdata) = (depth.clone(), vec![0u16; W * H]);
                let mut b = Buffers::new(&mut zdata, &mut cdata, W, 3, clip);
                let t = tri.each_ref();
                let done = match kernel {
                    None => {
                        fill_small_with::<EdgeDivide, u16>(&mut b, t, 7, write, less, false, false)
                    }
                    Some(false) => {
                        fill_small_with::<EdgeDivide, u16>(&mut b, t, 7, write, less, true, false)
                    }
                    Some(true) => {
                        fill_small_with::<EdgeWalk, u16>(&mut b, t, 7, write, less, false, true)
                    }
                };
                (done, zdata, cdata)
            };
            let want = run(None, true);
            // The divide path's own row loop, with and without depth writes, and
            // with another depth test.
            let divide = |write: bool, pass: fn(u16, u16) -> bool| {
                let (mut zdata, mut cdata) = (depth.clone(), vec![0u16; W * H]);
                let mut b = Buffers::new(&mut zdata, &mut cdata, W, 3, clip);
                let t = tri.each_ref();
                let done = if write {
                    fill_small_divide::<u16, true>(&mut b, t, 7, pass)
                } else {
                    fill_small_divide::<u16, false>(&mut b, t, 7, pass)
                };
                (done, zdata, cdata)
            };
            assert!(
                want == divide(true, less),
                "triangle {i}: {tri:?} in {clip:?}"
            );
            // The cache entries' path (on x86-64 the assembly set-up and rows of
            // `small_x86`, elsewhere with a kernel its own): what it takes, drawn alike.
            let (mut zdata, mut cdata) = (depth.clone(), vec![0u16; W * H]);
            let mut b = Buffers::new(&mut zdata, &mut cdata, W, 3, clip);
            let cached = tri.map(|v| CachedVertex::new(0, v));
            if let Some(done) = fill_small_cached::<u16>(&mut b, cached.each_ref(), 7) {
                cached_taken += 1;
                assert!(
                    want == (Some(done), zdata, cdata),
                    "triangle {i}: {tri:?} in {clip:?}, cached"
                );
            } else {
                assert!(
                    zdata == depth && cdata.iter().all(|&c| c == 0),
                    "triangle {i}"
                );
            }
            let reference = |write: bool, pass: fn(u16, u16) -> bool| {
                let (mut zdata, mut cdata) = (depth.clone(), vec![0u16; W * H]);
                let mut b = Buffers::new(&mut zdata, &mut cdata, W, 3, clip);
                let t = tri.each_ref();
                let done =
                    fill_small_with::<EdgeDivide, u16>(&mut b, t, 7, write, pass, false, false);
                (done, zdata, cdata)
            };
            let greater_equal: fn(u16, u16) -> bool = |a, b| a >= b;
            for (write, pass) in [(false, less as fn(u16, u16) -> bool), (true, greater_equal)] {
                assert!(
                    reference(write, pass) == divide(write, pass),
                    "triangle {i}: {tri:?} in {clip:?}, write {write}"
                );
            }
            for kernel in [false, true] {
                assert!(
                    want == run(Some(kernel), true),
                    "triangle {i}: {tri:?} in {clip:?}"
                );
            }
            // ARMv6-M's path: the set-up of `small_walk_less_as_u16` (on the host its
            // twin, in the assembly's order); what it leaves (`None`, nothing drawn)
            // goes to the general path.
            let (mut zdata, mut cdata) = (depth.clone(), vec![0u16; W * H]);
            let mut b = Buffers::new(&mut zdata, &mut cdata, W, 3, clip);
            let done = fill_small_walk::<u16>(&mut b, tri.each_ref(), 7, true, less);
            let left = done.is_none() && zdata == depth && cdata.iter().all(|&c| c == 0);
            assert!(
                left || want == (done, zdata, cdata),
                "triangle {i}: {tri:?} in {clip:?}"
            );
            // With `walk`, `Less` without depth writes is left to the general path (or
            // has no rows inside): nothing drawn.
            let (done, zdata, cdata) = run(Some(true), false);
            let drawn = zdata != depth || cdata.iter().any(|&c| c != 0);
            assert!(
                !drawn && matches!(done, None | Some((0, 0))),
                "triangle {i}"
            );
        }
        // Where there is a cached path (assembly on x86-64 and ARMv7E-M), it takes the
        // small triangles.
        if SMALL_X86_KERNEL || ROWS_KERNEL {
            assert!(cached_taken > 14_000, "{cached_taken} taken");
        }
    }
}
