//! The rows of a small flat-coloured triangle, both halves in one pass: edges by one
//! division a row, the depth test `Less` with depth writes, a two-byte colour; and
//! ([`small_less_as_u16`]) the triangle's set-up before them, from its three corners.
//! Assembly on ARMv7E-M (the row's state in registers, its constants in one block read
//! by `LDRD`/`LDM`), beside its portable twin.
#![allow(unsafe_code)]

use super::{CachedVertex, XyWord};
use crate::fixed::SUBPIXEL;
use crate::num::{div_floor_pair, floor_div32};
use crate::raster::{Clip, ScreenVertex, DEPTH_BIAS, SMALL};

/// Whether [`small_less_as_u16`] and [`rows_less_as_u16`] run the assembly (ARMv7E-M).
/// Elsewhere they run the portable twins, which the rasterizer does not call (its own
/// row loop is the faster there): the twins are for the tests and the bench's check.
pub(crate) const ROWS_KERNEL: bool = cfg!(all(zraster_thumb, zraster_dsp));

/// One edge in the form of [`EdgeDivide`](crate::raster::EdgeDivide): on each row its
/// first column is `t / d` (unsigned; 0 when `d` is 0, as `UDIV` gives it), then `t`
/// steps by `dt` (wrapping).
#[derive(Clone, Copy, Default, Debug, PartialEq, Eq)]
pub(crate) struct DivEdge {
    pub t: u32,
    pub dt: u32,
    pub d: u32,
}

/// The rows of a small triangle, in columns relative to the triangle's origin column
/// `px0` (see [`rows_less_as_u16`]), laid out as the assembly reads them (byte offsets
/// in the comments; the draw fills the fields the setters leave): [`RowsAt::n0`] rows
/// between the long edge `(t, d, dt)[0]` and the short one `[1]`, the long one on the
/// left when `side` is 0, then `n1` rows with the short edge replaced by `short1`, the
/// long one carried on. Each row covers `max(left, cx0)..min(right, cx1)`; the depth at
/// its column `x` is `clamp(z + x·sx, lo, hi)` (`hi = lo + span`) then `+ sx` a pixel, `z`
/// ([`RowsAt::z`]) stepping by `sy` a row (all wrapping). Filled field by field as the
/// triangle's set-up finds the values, so that they need not stay in registers
/// meanwhile.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub(crate) struct RowsLess {
    sx: u32,          // 0
    lo: u32,          // 4
    span: u32,        // 8: hi − lo
    color: u32,       // 12
    delta: u32,       // 16: colour address − depth address
    dt: [u32; 2],     // 20: the long and short edges' steps (the assembly's: left, right)
    cx: [i32; 2],     // 28
    sy: u32,          // 36
    pitch: u32,       // 40: bytes a row
    failed: u32,      // 44
    t: [u32; 2],      // 48: the long and short edges' t
    d: [u32; 2],      // 56: their divisors
    n1: u32,          // 64: rows in the second half
    side: u32,        // 68: 0 with the long edge on the left, else 1
    short1: [u32; 3], // 72: t, d, dt of the second half's short edge
}

// The assembly reads and writes the block at these offsets, by LDRD/STRD/LDM (word
// alignment): pinned here, so that a change of the layout fails to build.
const _: () = {
    use core::mem::{align_of, offset_of, size_of};
    assert!(offset_of!(RowsLess, sx) == 0 && offset_of!(RowsLess, lo) == 4);
    assert!(offset_of!(RowsLess, span) == 8 && offset_of!(RowsLess, color) == 12);
    assert!(offset_of!(RowsLess, delta) == 16 && offset_of!(RowsLess, dt) == 20);
    assert!(offset_of!(RowsLess, cx) == 28 && offset_of!(RowsLess, sy) == 36);
    assert!(offset_of!(RowsLess, pitch) == 40 && offset_of!(RowsLess, failed) == 44);
    assert!(offset_of!(RowsLess, t) == 48 && offset_of!(RowsLess, d) == 56);
    assert!(offset_of!(RowsLess, n1) == 64 && offset_of!(RowsLess, side) == 68);
    assert!(offset_of!(RowsLess, short1) == 72 && size_of::<RowsLess>() == 84);
    assert!(align_of::<RowsLess>() >= 4);
};

impl RowsLess {
    /// The pixels failed since `failed` was last zeroed (the face loop's running sum).
    #[cfg_attr(not(all(zraster_thumb, zraster_dsp)), allow(dead_code))]
    #[inline(always)]
    pub(super) fn failed(&self) -> u32 {
        self.failed
    }

    /// Rows clipped to the columns `cx0..cx1`, everything else 0 (field by field: each
    /// is written again before the assembly reads it, and the compiler drops these).
    #[inline(always)]
    pub(crate) fn new(cx0: i32, cx1: i32) -> RowsLess {
        RowsLess {
            sx: 0,
            lo: 0,
            span: 0,
            color: 0,
            delta: 0,
            dt: [0; 2],
            cx: [cx0, cx1],
            sy: 0,
            pitch: 0,
            failed: 0,
            t: [0; 2],
            d: [0; 2],
            n1: 0,
            side: 0,
            short1: [0; 3],
        }
    }

    /// Rows whose every field is `v` but the failed count, 0: for a block the assembly
    /// fills before it reads it (a word repeated, where the zeros of [`new`] are one
    /// call of `memclr` that the values worked out around it are kept on the stack for).
    ///
    /// [`new`]: RowsLess::new
    #[cfg_attr(not(all(zraster_thumb, zraster_dsp)), allow(dead_code))]
    #[inline(always)]
    pub(crate) fn splat(v: u32) -> RowsLess {
        let i = v as i32;
        RowsLess {
            sx: v,
            lo: v,
            span: v,
            color: v,
            delta: v,
            dt: [v; 2],
            cx: [i; 2],
            sy: v,
            pitch: v,
            failed: 0,
            t: [v; 2],
            d: [v; 2],
            n1: v,
            side: v,
            short1: [v; 3],
        }
    }

    /// The depth plane's steps `sx` and `sy`, and the clamp `lo..=hi` (`lo ≤ hi`: held
    /// as `lo` and `hi − lo`, one unsigned compare a row).
    #[inline(always)]
    pub(crate) fn depth(&mut self, sx: u32, sy: u32, lo: u32, hi: u32) {
        (self.sx, self.sy, self.lo, self.span) = (sx, sy, lo, hi.wrapping_sub(lo));
    }

    /// Rows between the long edge and `short[0]` ([`RowsAt::n0`] of them), then `n1`
    /// between the long edge carried on and `short[1]`; the long edge on the left when
    /// `mid_right`.
    #[inline(always)]
    pub(crate) fn edges(&mut self, long: DivEdge, short: [DivEdge; 2], n1: u32, mid_right: bool) {
        self.t = [long.t, short[0].t];
        self.d = [long.d, short[0].d];
        self.dt = [long.dt, short[0].dt];
        self.short1 = [short[1].t, short[1].d, short[1].dt];
        self.side = u32::from(!mid_right);
        self.n1 = n1;
    }
}

/// Where the rows lie in the buffers (the first row's index, the buffers' width, the
/// column the triangle's local column 0 is) and how they start (the first half's row
/// count, the depth at local column 0 of the first row): passed to the assembly in
/// registers.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RowsAt {
    pub row0: usize,
    pub width: usize,
    pub px0: i32,
    pub n0: u32,
    pub z: u32,
}

impl RowsAt {
    /// Whether every pixel rows clipped to the local columns `cx0..cx1` may touch lies
    /// inside buffers of `len` elements ([`RowsLess`]'s, or the ARMv6-M loop's, with
    /// `n1` rows in the second half): columns `px0 + cx0 .. px0 + cx1` inside
    /// `0..width`, rows `row0 .. row0 + n0 + n1` inside the length. `None` when they do
    /// not.
    #[inline(always)]
    pub(super) fn check(&self, n1: u32, [cx0, cx1]: [i32; 2], len: usize) -> Option<()> {
        let rows = (self.n0 as usize).checked_add(n1 as usize)?;
        let end_row = self.row0.checked_add(rows)?;
        let end = if crate::num::ARMV6M {
            // No 32 × 32 → 64-bit multiply: rows and width below 2¹⁶ multiply in 32 bits.
            if (end_row | self.width) > 0xffff {
                return None;
            }
            end_row * self.width
        } else {
            end_row.checked_mul(self.width)?
        };
        let (x0, x1) = (self.px0.checked_add(cx0)?, self.px0.checked_add(cx1)?);
        (end <= len && x0 >= 0 && x1 <= i32::try_from(self.width).ok()?).then_some(())
    }
}

/// Whether [`rows_less_as_u16`] takes colours of type `C`: two bytes, aligned to two.
#[inline(always)]
pub(crate) const fn two_bytes<C>() -> bool {
    core::mem::size_of::<C>() == 2 && core::mem::align_of::<C>() >= 2
}

/// Draw `r` into the depth rows `z` and colour rows `c` in `color`: the depth test
/// `Less` with depth writes. Returns (pixels tested, pixels failed), or `None` (nothing
/// drawn) when `C` is not a two-byte type or when the rows do not lie inside the
/// buffers ([`RowsAt::check`]).
#[inline(always)]
pub(crate) fn rows_less_as_u16<C: Copy>(
    r: &mut RowsLess,
    at: RowsAt,
    z: &mut [u16],
    c: &mut [C],
    color: C,
) -> Option<(u32, u32)> {
    let (words, bits) = as_u16(c, color)?;
    at.check(r.n1, r.cx, z.len().min(words.len()))?;
    rows_less_u16(r, at, z, words, bits)
}

/// The colour rows `c` and `color` as `u16`s when `C` is two bytes aligned to two
/// ([`two_bytes`]): the same memory, each element then keeping its bytes or taking
/// `color`'s. `None` for any other `C`.
#[inline(always)]
pub(super) fn as_u16<C: Copy>(c: &mut [C], color: C) -> Option<(&mut [u16], u16)> {
    if !two_bytes::<C>() {
        return None;
    }
    // SAFETY: C is two bytes with alignment two (checked above), so `color`'s bytes
    // read as a u16 and `c` viewed as `c.len()` u16s covers exactly the same memory; each
    // element then keeps its bytes or takes `color`'s: a valid C.
    unsafe {
        Some((
            core::slice::from_raw_parts_mut(c.as_mut_ptr().cast::<u16>(), c.len()),
            core::mem::transmute_copy::<C, u16>(&color),
        ))
    }
}

/// [`rows_less_as_u16`] for `u16` colours, the rows already checked to lie inside
/// both buffers.
#[inline(always)]
fn rows_less_u16(
    r: &mut RowsLess,
    at: RowsAt,
    z: &mut [u16],
    c: &mut [u16],
    color: u16,
) -> Option<(u32, u32)> {
    #[cfg(all(zraster_thumb, zraster_dsp))]
    {
        Some(rows_less_dsp(r, at, z, c, color))
    }
    #[cfg(not(all(zraster_thumb, zraster_dsp)))]
    {
        Some(rows_less_portable(r, at, z, c, color))
    }
}

/// The portable twin of the assembly: the rasterizer's own row loop for this case
/// (the same pixels, depths and counts). The rows must lie inside the buffers
/// ([`RowsAt::check`]); pixels outside are skipped.
pub(crate) fn rows_less_portable(
    r: &RowsLess,
    at: RowsAt,
    z: &mut [u16],
    c: &mut [u16],
    color: u16,
) -> (u32, u32) {
    let (mut tested, mut failed) = (0u32, 0u32);
    let mut zrow = at.z;
    let mut base = (at.row0.wrapping_mul(at.width)).wrapping_add_signed(at.px0 as isize);
    // Left and right: the long edge first, or the short one when `side` is not 0.
    let (mut t, mut d, mut dt) = (r.t, r.d, r.dt);
    if r.side != 0 {
        t.reverse();
        d.reverse();
        dt.reverse();
    }
    for (half, n) in [at.n0, r.n1].into_iter().enumerate() {
        if half == 1 {
            let [st, sd, sdt] = r.short1;
            if r.side == 0 {
                (t[1], d[1], dt[1]) = (st, sd, sdt);
            } else {
                (t[0], d[0], dt[0]) = (st, sd, sdt);
            }
        }
        for _ in 0..n {
            let xl = t[0].checked_div(d[0]).unwrap_or(0) as i32;
            let xr = t[1].checked_div(d[1]).unwrap_or(0) as i32;
            t = [t[0].wrapping_add(dt[0]), t[1].wrapping_add(dt[1])];
            let (xa, xb) = (xl.max(r.cx[0]), xr.min(r.cx[1]));
            let depth = [zrow, r.sx, r.lo, r.lo.wrapping_add(r.span)];
            let (t, f) = twin_row(z, c, base, (xa, xb), depth, color);
            (tested, failed) = (tested.wrapping_add(t), failed.wrapping_add(f));
            zrow = zrow.wrapping_add(r.sy);
            base = base.wrapping_add(at.width);
        }
    }
    (tested, failed)
}

/// One row of the portable twins: columns `xa..xb` (none when `xb ≤ xa`) from the
/// buffers' index `base` of local column 0, the depth at local column `x`
/// `clamp(zrow + x·sx, lo, hi)` at the first, then `+ sx` a pixel, tested `Less` and
/// written with `color`. Returns (pixels tested, pixels failed); pixels outside the
/// buffers are skipped.
pub(super) fn twin_row(
    z: &mut [u16],
    c: &mut [u16],
    base: usize,
    (xa, xb): (i32, i32),
    [zrow, sx, lo, hi]: [u32; 4],
    color: u16,
) -> (u32, u32) {
    if xa >= xb {
        return (0, 0);
    }
    let mut failed = 0u32;
    let mut acc = zrow
        .wrapping_add((xa as u32).wrapping_mul(sx))
        .max(lo)
        .min(hi);
    for x in xa..xb {
        let i = base.wrapping_add_signed(x as isize);
        if let (Some(zp), Some(cp)) = (z.get_mut(i), c.get_mut(i)) {
            let d = (acc >> 16) as u16;
            if d < *zp {
                (*zp, *cp) = (d, color);
            } else {
                failed = failed.wrapping_add(1);
            }
        }
        acc = acc.wrapping_add(sx);
    }
    (xb.wrapping_sub(xa) as u32, failed)
}

/// What [`small_less_as_u16`] did with a triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SmallDone {
    /// Drawn (perhaps nothing): pixels tested, pixels failed.
    Drawn(u32, u32),
    /// Not drawn: an extent of 512 pixels or more, a colour that is not two bytes, or a
    /// clip not inside the buffers. The general path's.
    General,
}

/// The buffers a small triangle is drawn into by [`small_less_as_u16`]: rows of `width`
/// pixels, the first of them screen row `first_row`, drawing confined to `clip`.
pub(crate) struct SmallTarget<'z, 'c, C> {
    pub z: &'z mut [u16],
    pub c: &'c mut [C],
    pub width: usize,
    pub first_row: i32,
    pub clip: Clip,
}

// The set-up assembly reads the corners at offsets 0, 4, 8 and has these constants
// written in.
const _: () = {
    assert!(core::mem::size_of::<ScreenVertex>() == 12);
    assert!(SMALL == 8192 && SUBPIXEL == 16 && DEPTH_BIAS == 32768);
};

/// The small flat triangle `tri` in `color` with the depth test `Less` and depth writes,
/// set-up and rows in one pass: the small path of `fill::small` (the same pixels, depths
/// and counts), its set-up in the order the assembly does it. [`SmallDone::General`]
/// when it is not for this path (nothing drawn).
#[inline(always)]
pub(crate) fn small_less_as_u16<C: Copy>(
    t: &mut SmallTarget<'_, '_, C>,
    tri: [&ScreenVertex; 3],
    color: C,
) -> SmallDone {
    let clip = t.clip;
    let (first_row, width) = (t.first_row, t.width);
    let Some((z, c, bits)) = t.kernel_buffers(color) else {
        return SmallDone::General;
    };
    #[cfg(all(zraster_thumb, zraster_dsp))]
    {
        small_less_dsp(tri, &clip, first_row, width, z, c, bits)
    }
    #[cfg(not(all(zraster_thumb, zraster_dsp)))]
    {
        small_less_portable(tri, &clip, first_row, width, z, c, bits)
    }
}

/// [`small_less_as_u16`] with the corners read in place from the vertex cache.
#[inline(always)]
pub(crate) fn small_less_cached<C: Copy>(
    t: &mut SmallTarget<'_, '_, C>,
    tri: [&CachedVertex; 3],
    color: C,
) -> SmallDone {
    let clip = t.clip;
    let (first_row, width) = (t.first_row, t.width);
    let Some((z, c, bits)) = t.kernel_buffers(color) else {
        return SmallDone::General;
    };
    #[cfg(all(zraster_thumb, zraster_dsp))]
    {
        small_less_dsp(tri, &clip, first_row, width, z, c, bits)
    }
    #[cfg(not(all(zraster_thumb, zraster_dsp)))]
    {
        let [p, q, r] = tri.map(cached_corner);
        small_less_portable([&p, &q, &r], &clip, first_row, width, z, c, bits)
    }
}

/// The two corner types the set-up assembly reads in place, by their layout.
#[cfg(all(zraster_thumb, zraster_dsp))]
pub(crate) trait Corner {
    /// A [`CachedVertex`] (else a [`ScreenVertex`]).
    const CACHED: bool;
}

#[cfg(all(zraster_thumb, zraster_dsp))]
impl Corner for ScreenVertex {
    const CACHED: bool = false;
}

#[cfg(all(zraster_thumb, zraster_dsp))]
impl Corner for CachedVertex {
    const CACHED: bool = true;
}

/// The screen position an unmarked cache entry holds (a marked one's x and y as they
/// lie in it): what the set-up kernel reads from it.
#[cfg(not(all(zraster_thumb, zraster_dsp)))]
fn cached_corner(p: &CachedVertex) -> ScreenVertex {
    ScreenVertex::from_raw(i32::from(p.xy.x()), i32::from(p.xy.y()), p.z)
}

impl<C: Copy> SmallTarget<'_, '_, C> {
    /// The depth rows, the colour rows as `u16`s and `color`'s bits, when `C` is two
    /// bytes and every row and column of the clip lies inside both buffers (then so does
    /// every pixel the rows may touch: they lie inside the clip); else `None`.
    #[inline(always)]
    pub(super) fn kernel_buffers(&mut self, color: C) -> Option<(&mut [u16], &mut [u16], u16)> {
        if !two_bytes::<C>() {
            return None;
        }
        let len = self.z.len().min(self.c.len());
        let (clip, w) = (self.clip, self.width);
        // Columns x0..x1 inside 0..w (a negative one is refused: as u32 above any width
        // with rows), rows y0..y1 inside the buffers' first_row.. (when y1 < first_row
        // the wrapped count is refused, or with w = 0 no pixel can be drawn).
        let col = |x: i32| x as u32 as usize;
        let rows = col(clip.y1.wrapping_sub(self.first_row));
        let inside = col(clip.x0) <= w
            && col(clip.x1) <= w
            && clip.y0 >= self.first_row
            && rows.checked_mul(w).is_some_and(|n| n <= len);
        if !inside {
            return None;
        }
        let (words, bits) = as_u16(self.c, color)?;
        Some((&mut *self.z, words, bits))
    }
}

/// The set-up of [`small_less_as_u16`]: the rows' block, where they start (`at`), or
/// what to do instead.
fn small_setup(
    tri: [&ScreenVertex; 3],
    clip: &Clip,
    first_row: i32,
    width: usize,
) -> Result<(RowsLess, RowsAt), SmallDone> {
    let p0 = tri[0];
    // The corners top to bottom (a stable sort by y).
    let mut v = tri;
    if v[1].y() < v[0].y() {
        v.swap(0, 1);
    }
    if v[2].y() < v[1].y() {
        v.swap(1, 2);
        if v[1].y() < v[0].y() {
            v.swap(0, 1);
        }
    }
    let [a, b, c] = v;
    let xmin = a.x().min(b.x()).min(c.x());
    let xmax = a.x().max(b.x()).max(c.x());
    if c.y() - a.y() >= SMALL || xmax - xmin >= SMALL {
        return Err(SmallDone::General);
    }
    // Rows whose centres may be covered, inside the clip; the middle corner's row
    // between them splits the halves.
    let centre = |y: i32| (y + 7) >> 4;
    let (start, end) = (centre(a.y()).max(clip.y0), centre(c.y()).min(clip.y1));
    if start >= end {
        return Err(SmallDone::Drawn(0, 0));
    }
    let mid = centre(b.y()).max(start).min(end);
    // Edges: at row py, t = (16py + 8 − a.y)·dx + (a.x − ox + 8)·dy − 1 (the
    // `EdgeDivide` form around the local origin ox, oy).
    let (px0, k) = (xmin >> 4, (xmin & !15) - 8);
    let (dxl, dyl) = (c.x() - a.x(), c.y() - a.y());
    let (dxs, dys) = (b.x() - a.x(), b.y() - a.y());
    let edge = |s: i32, x: i32, dx: i32, dy: i32| DivEdge {
        t: (s * dx + x * dy - 1) as u32,
        dt: (dx << 4) as u32,
        d: (dy << 4) as u32,
    };
    let (s, xa) = (16 * start + 8 - a.y(), a.x() - k);
    let long = edge(s, xa, dxl, dyl);
    let short0 = edge(s, xa, dxs, dys);
    let short1 = edge(16 * mid + 8 - b.y(), xa + dxs, dxl - dxs, dyl - dys);
    let area = dxs * dyl - dxl * dys;
    if area == 0 {
        return Err(SmallDone::Drawn(0, 0));
    }
    let mut r = RowsLess::new(clip.x0 - px0, clip.x1 - px0);
    r.edges(long, [short0, short1], (end - mid) as u32, area > 0);
    // Depth: ⌊16a/area⌋ and ⌊16b/area⌋ by one unsigned division each (the numerators
    // in [−2²⁶, 2²⁶), |area| < 2²⁷), as `fill::small::small_steps_q`.
    let (za, zb, zc) = (a.z(), b.z(), c.z());
    let (dz1, dz2) = (
        (zb >> 4) as i32 - (za >> 4) as i32,
        (zc >> 4) as i32 - (za >> 4) as i32,
    );
    let wide = |x: i32, y: i32| i64::from(x) * i64::from(y);
    let (na, nb) = (
        wide(dz1, dyl) - wide(dz2, dys),
        wide(dz2, dxs) - wide(dz1, dxl),
    );
    let fits = |n: i64| (-(1 << 26)..1 << 26).contains(&n);
    let (q, rq) = if fits(na) && fits(nb) {
        let m = area >> 31;
        let d = (area ^ m) - m;
        let step = |n: i64| floor_div32(((n as i32) << 4 ^ m) - m, d) as u32;
        (step(na), step(nb))
    } else {
        wide_steps(na, nb, area)
    };
    r.depth(
        q << 4,
        rq << 4,
        za.min(zb).min(zc) + DEPTH_BIAS,
        za.max(zb).max(zc) + DEPTH_BIAS,
    );
    // The depth at column 0 of row `start` from the first corner given (the plane's
    // origin): z + DEPTH_BIAS + q·(ox + 8 − x) + r·(16·start + 8 − y).
    let u = ((px0 << 4) + 8 - p0.x()) as u32;
    let w = (16 * start + 8 - p0.y()) as u32;
    let z = (p0.z() + DEPTH_BIAS)
        .wrapping_add(q.wrapping_mul(u))
        .wrapping_add(rq.wrapping_mul(w));
    let at = RowsAt {
        row0: (start - first_row) as usize,
        width,
        px0,
        n0: (mid - start) as u32,
        z,
    };
    Ok((r, at))
}

/// ⌊16a/area⌋ and ⌊16b/area⌋ modulo 2³² (`area ≠ 0`; |a|, |b| < 2⁴²): the set-up's
/// depth steps for numerators beyond its 32-bit division (steep depth, rare).
fn wide_steps(a: i64, b: i64, area: i32) -> (u32, u32) {
    let (q, r) = div_floor_pair(a * 16, b * 16, i64::from(area));
    (q as u32, r as u32)
}

/// The portable twin of the set-up assembly: [`small_setup`] then
/// [`rows_less_portable`]. The clip must lie inside the buffers (pixels outside are
/// skipped).
pub(crate) fn small_less_portable(
    tri: [&ScreenVertex; 3],
    clip: &Clip,
    first_row: i32,
    width: usize,
    z: &mut [u16],
    c: &mut [u16],
    color: u16,
) -> SmallDone {
    match small_setup(tri, clip, first_row, width) {
        Ok((r, at)) => {
            let (tested, failed) = rows_less_portable(&r, at, z, c, color);
            SmallDone::Drawn(tested, failed)
        }
        Err(done) => done,
    }
}

/// One pixel of a short row: depth in r9, address in r10 (`$at`: `[r10]`, or
/// `[r10, #2]!` to step it first); a failure branches to `$fail`. Clobbers r12 and lr.
#[cfg(all(zraster_thumb, zraster_dsp))]
#[rustfmt::skip]
macro_rules! rows_pixel {
    ($at:literal, $fail:literal) => {
        concat!(
            "ldrh r12, ", $at, "\n",
            "cmp r9, r12\n",
            "bhs ", $fail, "\n",
            "ldrd r12, lr, [r0, #12]\n",
            "strh r9, [r10]\n",
            "strh r12, [r10, lr]\n",
        )
    };
}

/// One more failed pixel in the block's count (r0), then on at `$next`. Clobbers r12.
#[cfg(all(zraster_thumb, zraster_dsp))]
macro_rules! rows_failed {
    ($next:literal) => {
        concat!(
            "ldr r12, [r0, #44]\n",
            "adds r12, #1\n",
            "str r12, [r0, #44]\n",
            "b ",
            $next,
            "\n",
        )
    };
}

/// A row's columns x (r10) .. x' (lr) tested against the clip's (`clip`: clamped at 14
/// when they cross it), or not (`inside`: rows the set-up has proven inside it).
#[cfg(all(zraster_thumb, zraster_dsp))]
#[rustfmt::skip]
macro_rules! rows_clip {
    (clip) => {
        concat!(
            "ldrd r9, r12, [r0, #28]\n",
            // Inside the clip (usually): cx0 ≤ x and x' ≤ cx1; else clamped at 14.
            "cmp r10, r9\n",
            "it ge\n",
            "cmpge r12, lr\n",
            "blt 14f\n",
        )
    };
    (inside) => {
        ""
    };
}

/// The clamp of [`rows_clip`]'s `clip` rows to the clip's columns (cx0, cx1 in r9, r12),
/// then on at 15 (or at 5, the row empty then).
#[cfg(all(zraster_thumb, zraster_dsp))]
#[rustfmt::skip]
macro_rules! rows_clamp {
    (clip) => {
        concat!(
            "14:\n",
            "cmp r10, r9\n",
            "it lt\n",
            "movlt r10, r9\n",
            "cmp lr, r12\n",
            "it gt\n",
            "movgt lr, r12\n",
            "subs r11, lr, r10\n",
            "ble 5b\n",
            "b 15b\n",
        )
    };
    (inside) => {
        ""
    };
}

/// The rows of [`rows_less_dsp`] from the block in r0, the first row's depth in r3, its
/// depth address in r4, the first half's row count in r5 (r6 and r7 pushed by the
/// caller): ends with the pixels tested in r1. `$cols` is `clip` (each row's columns
/// clamped to the clip's) or `inside` (not: the set-up has proven every row inside
/// them). Expanded by `rows_less_dsp` (`clip`) and twice by `small_less_dsp` after its
/// set-up (both). Clobbers r1–r12, lr and the flags. With `$sum0` and `$sum1`, r6
/// starts as `$sum0` makes it and ends as `$sum1` takes it (the band loop's running
/// sum in its block) instead of from 0 into r1.
#[cfg(all(zraster_thumb, zraster_dsp))]
#[rustfmt::skip]
macro_rules! rows_body {
    ($cols:ident) => {
        rows_body!($cols, "movs r6, #0\n", "mov r1, r6\n")
    };
    ($cols:ident, $sum0:expr, $sum1:expr) => {
        concat!(
            $sum0,
            // The long and short edges to the left and right.
            "ldr r7, [r0, #68]\n",
            "cbnz r7, 11f\n",
            "ldrd r1, r2, [r0, #48]\n",
            "ldrd r7, r8, [r0, #56]\n",
            "b 12f\n",
            "11:\n",
            "ldrd r2, r1, [r0, #48]\n",
            "ldrd r8, r7, [r0, #56]\n",
            "ldrd r9, r10, [r0, #20]\n",
            "strd r10, r9, [r0, #20]\n",
            "12:\n",
            "cbz r5, 8f\n",
            // A row: its columns, clamped to the clip.
            "1:\n",
            "udiv r10, r1, r7\n",
            "udiv lr, r2, r8\n",
            "ldrd r9, r12, [r0, #20]\n",
            "add r1, r9\n",
            "add r2, r12\n",
            // Its length (r11), none before the clip is (x' ≤ x: then so after it).
            "subs r11, lr, r10\n",
            "ble 5f\n",
            rows_clip!($cols),
            "15:\n",
            // Its depth at the first column, clamped, and that column's address.
            "add r6, r11\n",
            "ldm r0, {{r9, r12, lr}}\n",
            "mla r9, r10, r9, r3\n",
            "add r10, r4, r10, lsl #1\n",
            // Inside lo..=hi (usually: depth − lo ≤ hi − lo unsigned); else clamped at 16.
            "sub r12, r9, r12\n",
            "cmp r12, lr\n",
            "bhi 16f\n",
            "17:\n",
            "cmp r11, #2\n",
            "bhi 4f\n",
            "beq 3f\n",
            "lsr r9, r9, #16\n",
            rows_pixel!("[r10]", "6f"),
            // The next row.
            "5:\n",
            "ldrd r9, r12, [r0, #36]\n",
            "add r3, r9\n",
            "add r4, r12\n",
            "subs r5, #1\n",
            "bne 1b\n",
            // The second half, its count cleared so that it runs once: the short edge
            // replaced, the long one carried on.
            "8:\n",
            "ldrd r5, r12, [r0, #64]\n",
            "cmp r5, #0\n",
            "beq 9f\n",
            "movs r9, #0\n",
            "str r9, [r0, #64]\n",
            "ldr r11, [r0, #80]\n",
            "cmp r12, #0\n",
            "bne 13f\n",
            "ldrd r2, r8, [r0, #72]\n",
            "str r11, [r0, #24]\n",
            "b 1b\n",
            "13:\n",
            "ldrd r1, r7, [r0, #72]\n",
            "str r11, [r0, #20]\n",
            "b 1b\n",
            // Two pixels.
            "3:\n",
            "ldr r12, [r0]\n",
            "add r11, r9, r12\n",
            "lsr r9, r9, #16\n",
            rows_pixel!("[r10]", "7f"),
            "2:\n",
            "lsr r9, r11, #16\n",
            rows_pixel!("[r10, #2]!", "6f"),
            "b 5b\n",
            // The row's columns clamped to the clip.
            rows_clamp!($cols),
            // The row's first depth clamped to lo..=hi.
            "16:\n",
            "ldr r12, [r0, #4]\n",
            "add lr, lr, r12\n",
            "cmp r9, r12\n",
            "it lo\n",
            "movlo r9, r12\n",
            "cmp r9, lr\n",
            "it hi\n",
            "movhi r9, lr\n",
            "b 17b\n",
            "6:\n",
            rows_failed!("5b"),
            "7:\n",
            rows_failed!("2b"),
            // Eight pixels or more: span_less_dsp's loop, r0–r8 saved meanwhile, when
            // the colour and depth rows are aligned alike; else (and for three to
            // seven) one pixel a turn.
            "4:\n",
            "cmp r11, #8\n",
            "blo 40f\n",
            "ldr r12, [r0, #16]\n",
            "tst r12, #2\n",
            "bne 40f\n",
            "push {{r0-r8}}\n",
            "ldr r4, [r0]\n",
            "ldr r1, [r0, #16]\n",
            "ldr r5, [r0, #12]\n",
            "orr r5, r5, r5, lsl #16\n",
            "eor r6, r5, #0x00010001\n",
            "add r1, r10\n",
            "mov r0, r10\n",
            "mov r2, r11\n",
            "mov r3, r9\n",
            "movs r7, #0\n",
            dsp_span!("20", "21", "22", "23", "24", "25"),
            "pop {{r0-r8}}\n",
            "ldr r9, [r0, #44]\n",
            "add r9, r12\n",
            "str r9, [r0, #44]\n",
            "b 5b\n",
            "40:\n",
            "push {{r1-r3}}\n",
            "ldr r1, [r0]\n",
            "ldrd r2, r3, [r0, #12]\n",
            "41:\n",
            "lsr lr, r9, #16\n",
            "ldrh r12, [r10]\n",
            "add r9, r1\n",
            "cmp lr, r12\n",
            "bhs 43f\n",
            "strh r2, [r10, r3]\n",
            "strh lr, [r10], #2\n",
            "42:\n",
            "subs r11, #1\n",
            "bne 41b\n",
            "pop {{r1-r3}}\n",
            "b 5b\n",
            "43:\n",
            "add r10, r10, #2\n",
            rows_failed!("42b"),
            "9:\n",
            $sum1,
        )
    };
}

/// [`rows_less_u16`] for ARMv7E-M. Rows of one and two pixels inline; from eight by
/// the two-pixel SIMD steps of `span_less_dsp` when `z` and `c` lie at the same
/// address modulo 4, else one pixel a turn. Registers: r0 the block, r1/r2 the left and
/// right `t`, r3 the row's depth at local column 0, r4 its depth address, r5 rows left
/// in the half (r3–r5 come in from [`RowsAt`]), r6 pixels tested, r7/r8 the divisors;
/// r9–r12 and lr scratch (a row: r10 its first column, then its depth address; r11 its
/// length; r9 its depth). Failures are counted in the block (they are rare). The clip
/// and depth clamps are compare chains, the clamping itself out of line (rows inside
/// the clip and the depth range are the rule).
#[cfg(all(zraster_thumb, zraster_dsp))]
#[inline(always)]
fn rows_less_dsp(
    r: &mut RowsLess,
    at: RowsAt,
    z: &mut [u16],
    c: &mut [u16],
    color: u16,
) -> (u32, u32) {
    let zaddr = z.as_mut_ptr() as u32;
    let index = (at.row0.wrapping_mul(at.width) as u32).wrapping_add(at.px0 as u32);
    r.color = u32::from(color);
    r.delta = (c.as_mut_ptr() as u32).wrapping_sub(zaddr);
    r.pitch = (at.width as u32).wrapping_mul(2);
    r.failed = 0;
    let base = zaddr.wrapping_add(index.wrapping_mul(2));
    let tested: u32;
    // SAFETY: the caller has checked (`RowsAt::check`) that rows row0 .. row0 + n0 + n1
    // of width `width` lie inside both `z` and `c`, and columns px0 + cx0 .. px0 + cx1
    // inside 0..width; `z` and `c` are u16 slices (2-aligned). The assembly starts at
    // the address of row row0, column px0 (r4), walks exactly n0 + n1 rows (r5 counts
    // each half down; a half of 0 rows is skipped), stepping the row address by the
    // pitch, and writes only columns max(x, cx0) .. min(x', cx1) of a row (signed
    // compares, clamped whenever either bound is crossed): inside both buffers (the
    // colour at the depth address + delta). Rows of eight or more pixels run the loop
    // of `span_less_dsp` over exactly that range (its own SAFETY argument: the colour
    // and depth addresses alike modulo 4, tested on `delta`), with r0–r8 pushed around
    // it and popped after, or (not alike, or three to seven pixels) a loop of exactly
    // that many pixels with r1–r3 pushed and popped. Quotients come from UDIV (x/0 = 0, as the twin has it).
    // The block is read and written through r0 (`failed`, `dt` reordered, the second
    // half's count). r6 and r7 (not allowed as operands) are pushed and popped; every
    // other register written is declared; the flags (GE included) are scratch.
    unsafe {
        core::arch::asm!(
            "push {{r6, r7}}",
            rows_body!(clip),
            "pop {{r6, r7}}",
            in("r0") r as *mut RowsLess,
            out("r1") tested,
            out("r2") _,
            inout("r3") at.z => _,
            inout("r4") base => _,
            inout("r5") at.n0 => _,
            out("r8") _, out("r9") _, out("r10") _, out("r11") _,
            out("r12") _, out("lr") _,
        );
    }
    (tested, r.failed)
}

/// The end of [`small_body`]'s set-up: the first row's address (r4) from px0 (r4) and
/// zrow0 (loaded into r1 by `$zrow`), the first half's rows (r5), the 16 bytes where r0–r3 were
/// pushed (its scratch: the first corner's address as pushed at sp + 4, n0, xmax)
/// released.
#[cfg(all(zraster_thumb, zraster_dsp))]
#[rustfmt::skip]
macro_rules! rows_start {
    ($zrow:literal) => {
        concat!(
            "ldr r2, [r0, #40]\n",
            $zrow,
            "mla r1, r5, r2, r1\n",
            "add r4, r1, r4, lsl #1\n",
            "ldr r5, [sp, #8]\n",
            "add sp, #16\n",
        )
    };
}

/// The set-up and rows of [`small_less_dsp`] (the assembly template), for corners whose
/// y and x are read by `$ly`/`$lx` at byte offsets `$oy`/`$ox` and z at `$oz`; `$p0` loads
/// the first corner given (its address in lr) into r6 (x), r7 (y), r8 (z). With
/// `fused` first (the face loop's): the colour, its delta and the pitch already in the
/// block, the clip's rows, zrow0 and its columns read from the block at 120, 116 and
/// 128 (not r5, r8, r4, r9, r10: r5 and r8 come back as they were), failed neither
/// zeroed nor read (the face loop's running sum; r3 left undefined). With `keep` (the
/// band loop's face reaching the band below): as `fused`, but its rows not cut at the
/// clip's last row, and `$hook` run between the set-up and the rows (it finds the
/// first row's depth in r3, px0 in r4, the first row in r5, n0 at sp + 8, xmax at
/// sp + 12, n1 in the block, and must leave them so; label 73 follows it, where the
/// band loop enters with a set-up of its own), and `$none` run for a triangle that
/// draws nothing (r0 the block, r2 0). With `band` (the band loop's other
/// faces): as `fused`; `band` and `keep` add the pixels tested to the band block's
/// running sum at 216 and return that sum in r1 (not the face's own count) with the
/// flags' N its bit 31. Every form returns r2 1 for a triangle it leaves to the
/// general path (r1 then −1, N set), else 0 (r1 0, N clear, when nothing was drawn);
/// nothing after those values are set writes the flags.
#[cfg(all(zraster_thumb, zraster_dsp))]
#[rustfmt::skip]
macro_rules! small_body {
    ($ly:literal, $oy:literal, $lx:literal, $ox:literal, $oz:literal, $p0:literal) => {
        small_body!(
            @ "strd lr, r12, [r0, #12]\nmovs r12, #0\nstrd r11, r12, [r0, #40]\n",
            "ldr r1, [sp, #16]\n",
            "ldrd r8, r10, [sp, #36]\n",
            "ldr r3, [r0, #44]\n",
            "",
            "",
            "movs r6, #0\n",
            "mov r1, r6\n",
            $ly, $oy, $lx, $ox, $oz, $p0
        )
    };
    (fused, $ly:literal, $oy:literal, $lx:literal, $ox:literal, $oz:literal, $p0:literal) => {
        small_body!(
            @ "ldrd r5, r8, [r0, #120]\n",
            "ldr r1, [r0, #116]\n",
            "ldrd r8, r10, [r0, #128]\n",
            "",
            "",
            "",
            "movs r6, #0\n",
            "mov r1, r6\n",
            $ly, $oy, $lx, $ox, $oz, $p0
        )
    };
    (band, $ly:literal, $oy:literal, $lx:literal, $ox:literal, $oz:literal, $p0:literal) => {
        small_body!(
            @ "ldrd r5, r8, [r0, #120]\n",
            "ldr r1, [r0, #116]\n",
            "ldrd r8, r10, [r0, #128]\n",
            "",
            "",
            "",
            "ldr r6, [r0, #216]\n",
            "str r6, [r0, #216]\nmovs r1, r6\n",
            $ly, $oy, $lx, $ox, $oz, $p0
        )
    };
    (keep, $hook:expr, $none:literal,
     $ly:literal, $oy:literal, $lx:literal, $ox:literal, $oz:literal, $p0:literal) => {
        small_body!(
            @ "ldr r5, [r0, #120]\nmovw r8, #0x7fff\n",
            "ldr r1, [r0, #116]\n",
            "ldrd r8, r10, [r0, #128]\n",
            "",
            concat!($hook, "73:\n"),
            $none,
            "ldr r6, [r0, #216]\n",
            "str r6, [r0, #216]\nmovs r1, r6\n",
            $ly, $oy, $lx, $ox, $oz, $p0
        )
    };
    (@ $entry:literal, $zrow:literal, $clipx:literal, $failed:literal, $hook:expr,
     $none:literal, $sum0:literal, $sum1:literal,
     $ly:literal, $oy:literal, $lx:literal, $ox:literal, $oz:literal, $p0:literal) => {
        concat!(
            // r0–r3 pushed to make the set-up's 16 bytes of scratch (r1, the first
            // corner's address, kept at sp + 4), r4–r12 for the caller.
            "push {{r0-r12}}\n",
            $entry,
            // The corners top to bottom (r1, r2, r3; their y in r6, r7, r9), stable.
            concat!($ly, " r6, [r1, #", $oy, "]\n"),
            concat!($ly, " r7, [r2, #", $oy, "]\n"),
            concat!($ly, " r9, [r3, #", $oy, "]\n"),
            "cmp r7, r6\n",
            "bge 50f\n",
            "mov r10, r1\n",
            "mov r1, r2\n",
            "mov r2, r10\n",
            "mov r10, r6\n",
            "mov r6, r7\n",
            "mov r7, r10\n",
            "50:\n",
            "cmp r9, r7\n",
            "bge 51f\n",
            "mov r10, r2\n",
            "mov r2, r3\n",
            "mov r3, r10\n",
            "mov r10, r7\n",
            "mov r7, r9\n",
            "mov r9, r10\n",
            "cmp r7, r6\n",
            "bge 51f\n",
            "mov r10, r1\n",
            "mov r1, r2\n",
            "mov r2, r10\n",
            "mov r10, r6\n",
            "mov r6, r7\n",
            "mov r7, r10\n",
            "51:\n",
            // Extents below 8192 (512 pixels), else the general path's; x in r10-r12,
            // the smallest in r4, the largest kept at [sp, #12].
            "sub r10, r9, r6\n",
            "cmp r10, #8192\n",
            "bge 90f\n",
            concat!($lx, " r10, [r1, #", $ox, "]\n"),
            concat!($lx, " r11, [r2, #", $ox, "]\n"),
            concat!($lx, " r12, [r3, #", $ox, "]\n"),
            "mov r4, r10\n",
            "mov lr, r10\n",
            "cmp r11, r10\n",
            "ite lt\n",
            "movlt r4, r11\n",
            "movge lr, r11\n",
            "cmp r12, r4\n",
            "it lt\n",
            "movlt r4, r12\n",
            "cmp r12, lr\n",
            "it gt\n",
            "movgt lr, r12\n",
            "str lr, [sp, #12]\n",
            "sub lr, lr, r4\n",
            "cmp lr, #8192\n",
            "bge 90f\n",
            // Rows start (r5) .. end (r8) inside the clip; none: drawn, nothing.
            "add lr, r6, #7\n",
            "cmp r5, lr, asr #4\n",
            "it lt\n",
            "asrlt r5, lr, #4\n",
            "add lr, r9, #7\n",
            "cmp r8, lr, asr #4\n",
            "it gt\n",
            "asrgt r8, lr, #4\n",
            "cmp r5, r8\n",
            "bge 91f\n",
            // The middle row (lr) between them; n1 into the block, n0 kept.
            "add lr, r7, #7\n",
            "asr lr, lr, #4\n",
            "cmp lr, r5\n",
            "it lt\n",
            "movlt lr, r5\n",
            "cmp lr, r8\n",
            "it gt\n",
            "movgt lr, r8\n",
            "sub r8, r8, lr\n",
            "str r8, [r0, #64]\n",
            "sub r8, lr, r5\n",
            "str r8, [sp, #8]\n",
            // Edges: t = s·dx + (x − k)·dy − 1, k = ox − 8, s = 16·row + 8 − y, as the
            // rows take them: t/16 (LSR; t ≥ 0 on every row an edge is stepped), then dy
            // and dx, not 16dy and 16dx (the same columns: ⌊⌊t/16⌋/dy⌋ = ⌊t/16dy⌋).
            "sub r12, r12, r10\n",
            "sub r11, r11, r10\n",
            "sub r9, r9, r6\n",
            "sub r7, r7, r6\n",
            "rsb r6, r6, #8\n",
            "add lr, r6, lr, lsl #4\n",
            "sub lr, lr, r7\n",
            "add r6, r6, r5, lsl #4\n",
            "bic r8, r4, #15\n",
            "sub r8, r8, #8\n",
            "sub r10, r10, r8\n",
            "asr r4, r4, #4\n",
            "mul r8, r6, r12\n",
            "mla r8, r10, r9, r8\n",
            "sub r8, r8, #1\n",
            "lsr r8, r8, #4\n",
            "str r8, [r0, #48]\n",
            "mul r8, r6, r11\n",
            "mla r8, r10, r7, r8\n",
            "sub r8, r8, #1\n",
            "lsr r8, r8, #4\n",
            "str r8, [r0, #52]\n",
            "add r10, r10, r11\n",
            "sub r6, r12, r11\n",
            "sub r8, r9, r7\n",
            "mul lr, lr, r6\n",
            "mla lr, r10, r8, lr\n",
            "sub lr, lr, #1\n",
            "lsr lr, lr, #4\n",
            "str lr, [r0, #72]\n",
            "strd r8, r6, [r0, #76]\n",
            "strd r12, r11, [r0, #20]\n",
            "strd r9, r7, [r0, #56]\n",
            // The area (r6; 0: nothing drawn), its sign the side.
            "mul r6, r11, r9\n",
            "mls r6, r12, r7, r6\n",
            "cmp r6, #0\n",
            "beq 91f\n",
            "lsr r8, r6, #31\n",
            "str r8, [r0, #68]\n",
            // Depth: the clamp (lo, hi − lo), then the numerators a (r1:r2) and b (r3:r8).
            concat!("ldr r8, [r1, #", $oz, "]\n"),
            concat!("ldr r10, [r2, #", $oz, "]\n"),
            concat!("ldr lr, [r3, #", $oz, "]\n"),
            "mov r1, r8\n",
            "mov r2, r8\n",
            "cmp r10, r8\n",
            "ite lo\n",
            "movlo r1, r10\n",
            "movhs r2, r10\n",
            "cmp lr, r1\n",
            "it lo\n",
            "movlo r1, lr\n",
            "cmp lr, r2\n",
            "it hi\n",
            "movhi r2, lr\n",
            "sub r2, r2, r1\n",
            "add r1, r1, #32768\n",
            "strd r1, r2, [r0, #4]\n",
            "lsr r8, r8, #4\n",
            "rsb r10, r8, r10, lsr #4\n",
            "rsb lr, r8, lr, lsr #4\n",
            "smull r1, r2, r10, r9\n",
            "rsb r7, r7, #0\n",
            "smlal r1, r2, lr, r7\n",
            "smull r3, r8, lr, r11\n",
            "rsb r12, r12, #0\n",
            "smlal r3, r8, r10, r12\n",
            // Both in [−2²⁶, 2²⁶) (the usual), else the steps by `wide_steps` at 92.
            // (n + 2²⁶ as 64 bits below 2²⁷: its high word and low word's bits 27.. 0.)
            "adds r12, r1, #0x4000000\n",
            "adc lr, r2, #0\n",
            "orrs lr, lr, r12, lsr #27\n",
            "bne 92f\n",
            "adds r12, r3, #0x4000000\n",
            "adc lr, r8, #0\n",
            "orrs lr, lr, r12, lsr #27\n",
            "bne 92f\n",
            // q = ⌊16a/area⌋ (r1), r = ⌊16b/area⌋ (r3): the sign folded in, one UDIV of
            // n or !n each.
            "eor r10, r6, r6, asr #31\n",
            "sub r10, r10, r6, asr #31\n",
            "asr r6, r6, #31\n",
            "eor r1, r6, r1, lsl #4\n",
            "sub r1, r1, r6\n",
            "eor r2, r1, r1, asr #31\n",
            "udiv r2, r2, r10\n",
            "eor r1, r2, r1, asr #31\n",
            "eor r3, r6, r3, lsl #4\n",
            "sub r3, r3, r6\n",
            "eor r2, r3, r3, asr #31\n",
            "udiv r2, r2, r10\n",
            "eor r3, r2, r3, asr #31\n",
            "93:\n",
            "lsl r2, r1, #4\n",
            "str r2, [r0]\n",
            "lsl r2, r3, #4\n",
            "str r2, [r0, #36]\n",
            // The first row's depth at column 0 (r3) from the first corner given, its
            // address (r4), the first half's rows (r5).
            "ldr lr, [sp, #4]\n",
            $p0,
            "rsb r6, r6, #8\n",
            "add r6, r6, r4, lsl #4\n",
            "rsb r7, r7, #8\n",
            "add r7, r7, r5, lsl #4\n",
            "add r8, r8, #32768\n",
            "mla r8, r1, r6, r8\n",
            "mla r3, r3, r7, r8\n",
            $hook,
            // The rows inside the clip's columns when px0 ≥ clip.x0 and
            // ⌊(xmax + 8)/16⌋ ≤ clip.x1 (at 200); else the clip's columns made local
            // for the rows' clamp (clip.x0, clip.x1 as pushed by the entry, at sp + 16 + 20).
            $clipx,
            "ldr r12, [sp, #12]\n",
            "add r12, r12, #8\n",
            "cmp r4, r8\n",
            "it ge\n",
            "cmpge r10, r12, asr #4\n",
            "bge 200f\n",
            "sub r8, r8, r4\n",
            "sub r10, r10, r4\n",
            "strd r8, r10, [r0, #28]\n",
            rows_start!($zrow),
            rows_body!(clip, $sum0, $sum1),
            "b 199f\n",
            // Not drawn (90: for the general path), the steep depth's call (92).
            "90:\n",
            "movs r2, #1\n",
            "mvns r1, #0\n",
            "b 98f\n",
            // Steep depth: q and r by a call (AAPCS: a in r0:r1, b in r2:r3, the area
            // on the stack; q, r back in r0, r1), the block kept beside the area.
            "92:\n",
            "strd r6, r0, [sp, #-8]!\n",
            "mov r0, r1\n",
            "mov r1, r2\n",
            "mov r2, r3\n",
            "mov r3, r8\n",
            "bl {wide}\n",
            "mov r3, r1\n",
            "mov r1, r0\n",
            "ldr r0, [sp, #4]\n",
            "add sp, #8\n",
            "b 93b\n",
            "91:\n",
            "movs r2, #0\n",
            $none,
            "movs r1, #0\n",
            "98:\n",
            "add sp, #16\n",
            "mov r3, #0\n",
            "b 99f\n",
            "200:\n",
            rows_start!($zrow),
            rows_body!(inside, $sum0, $sum1),
            "199:\n",
            $failed,
            "mov r2, #0\n",
            "99:\n",
            "pop {{r4-r12}}\n",
        )
    };
}

/// [`small_less_as_u16`] for ARMv7E-M: the set-up of [`small_setup`] in registers, its
/// values stored into the block as they are found, then the rows of [`rows_less_dsp`].
/// The clip must lie inside both buffers (checked by the caller).
#[cfg(all(zraster_thumb, zraster_dsp))]
#[inline(always)]
fn small_less_dsp<T: Corner>(
    tri: [&T; 3],
    clip: &Clip,
    first_row: i32,
    width: usize,
    z: &mut [u16],
    c: &mut [u16],
    color: u16,
) -> SmallDone {
    let mut block = core::mem::MaybeUninit::<RowsLess>::uninit();
    let zaddr = z.as_mut_ptr() as u32;
    let pitch = (width as u32).wrapping_mul(2);
    // The address of screen row 0's column 0 in the depth rows (wrapping: a band's rows
    // start further down); the colour at the depth address + delta.
    let zrow0 = zaddr.wrapping_sub((first_row as u32).wrapping_mul(pitch));
    let delta = (c.as_mut_ptr() as u32).wrapping_sub(zaddr);
    let vertex = |p: &T| core::ptr::from_ref(p) as u32;
    let (tested, status, failed): (u32, u32, u32);
    // SAFETY: the set-up reads the three corners through their references, at the
    // offsets of their type's fields (`Corner::CACHED`: a `CachedVertex`, `repr(C)` and
    // 8 bytes, z at 0 and x, y the i16 halves at 4 and 6; else a `ScreenVertex`,
    // `repr(C)` and 12 bytes, x, y, z at 0, 4, 8: both pinned by const assertions) and
    // writes only the block (a local `RowsLess`, word-aligned, every field written
    // before the rows read it) and the stack it pushes r0–r12 to (its 16 bytes of r0–r3
    // scratch, released before the rows). It then draws rows start..end, start ≥ clip.y0 and end ≤ clip.y1, in
    // columns clamped to clip.x0 − px0 .. clip.x1 − px0 (|px0| ≤ 2²⁰ by the guard band,
    // the clip's columns inside 0..width: no wrapping, so the loop's signed compares are
    // exact), at zrow0 + row·pitch + 2·(px0 + column) = the address of that pixel in
    // `z`: inside `z` and `c` since the clip lies inside both (the caller's check), and
    // n0 + n1 = end − start, both ≥ 0. The rows are those of `rows_less_dsp` (its
    // SAFETY argument). The `inside` rows skip the clamp, taken only when
    // px0 ≥ clip.x0 and ⌊(xmax + 8)/16⌋ ≤ clip.x1 (signed compares of values below 2²⁶
    // in magnitude): every row then lies inside the clip's columns, by the set-up's
    // arithmetic. An edge from (x0, y0) to (x1, y1), dy = y1 − y0, is stepped only on
    // rows whose centre Y lies in [y0, y1) (start = ⌈(a.y − 8)/16⌉ puts the first
    // centre at or below a.y, the split at b likewise, and end = ⌈(c.y − 8)/16⌉ the
    // last above c.y; an edge with dy = 0 gets no rows), so dy > 0 and
    // t = (Y − y0)·dx + (x0 − k)·dy − 1 = dy·(x(Y) − k) − 1 exactly (no wrapping: below
    // 2²⁸), x(Y) between x0 and x1, hence in [xmin, xmax]. With k = 16·px0 − 8 ≤ xmin − 8,
    // t lies in [7, dy·(xmax − k)) (so ⌊t/16⌋ stepped by dx is ⌊t/16⌋ of t stepped by
    // 16dx: the rows' t), and its column ⌊t/16⌋ / dy (UDIV) in
    // [0, ⌊(xmax + 8)/16⌋ − px0]: both ends of every row inside the local clip
    // [clip.x0 − px0, clip.x1 − px0]. r0–r12 are pushed first (r0–r3's 16 bytes the
    // set-up's scratch, released by it) and r4–r12 popped last (r6 and r7 are not
    // allowed as operands; the others are inputs the caller keeps: its loop need not
    // reload them; the set-up reads zrow0, clip.x0 and clip.x1 back where they were
    // pushed); every other register written is declared; the flags are scratch.
    // The template for the corners' layout, the operands alike.
    macro_rules! setup_and_rows {
        ($($layout:tt)*) => {
            core::arch::asm!(
                small_body!($($layout)*),
                in("r0") block.as_mut_ptr(),
                inout("r1") vertex(tri[0]) => tested,
                inout("r2") vertex(tri[1]) => status,
                inout("r3") vertex(tri[2]) => failed,
                in("r4") zrow0,
                in("r5") clip.y0,
                in("r8") clip.y1,
                in("r9") clip.x0,
                in("r10") clip.x1,
                in("r11") pitch,
                in("r12") delta,
                inout("lr") u32::from(color) => _,
                wide = sym wide_steps_c,
                // The call's: the caller-saved floating-point registers, where there are any
                // (its core ones are operands above, or pushed and popped).
                #[cfg(not(zraster_soft_float))] out("d0") _,
                #[cfg(not(zraster_soft_float))] out("d1") _,
                #[cfg(not(zraster_soft_float))] out("d2") _,
                #[cfg(not(zraster_soft_float))] out("d3") _,
                #[cfg(not(zraster_soft_float))] out("d4") _,
                #[cfg(not(zraster_soft_float))] out("d5") _,
                #[cfg(not(zraster_soft_float))] out("d6") _,
                #[cfg(not(zraster_soft_float))] out("d7") _,
            )
        };
    }
    unsafe {
        if T::CACHED {
            setup_and_rows!(
                "ldrsh",
                "6",
                "ldrsh",
                "4",
                "0",
                "ldrsh r6, [lr, #4]\nldrsh r7, [lr, #6]\nldr r8, [lr]\n"
            );
        } else {
            setup_and_rows!("ldr", "4", "ldr", "0", "8", "ldm lr, {{r6, r7, r8}}\n");
        }
    }
    if status == 0 {
        SmallDone::Drawn(tested, failed)
    } else {
        SmallDone::General
    }
}

/// [`wide_steps`] for the set-up assembly, which calls it.
#[cfg(all(zraster_thumb, zraster_dsp))]
pub(super) extern "C" fn wide_steps_c(a: i64, b: i64, area: i32) -> u64 {
    let (q, r) = wide_steps(a, b, area);
    u64::from(q) | u64::from(r) << 32
}

/// The generator of the rows kernels' checks.
pub(super) use super::xorshift_next as next;

/// An edge starting near column `x0` of [`check_rows_kernel`]'s rows, stepping up to
/// three columns a row.
fn check_edge(seed: &mut u32, x0: u32) -> DivEdge {
    let d = 16 * (1 + next(seed) % 24);
    let dt = (next(seed) % 96).wrapping_sub(48).wrapping_mul(16);
    let t = (x0 * d).wrapping_add(next(seed) % d);
    DivEdge { t, dt, d }
}

/// Two edges about `w` columns apart, mostly one or two at first.
fn check_pair(seed: &mut u32) -> (DivEdge, DivEdge) {
    let xl = next(seed) % 24;
    let w = match next(seed) % 4 {
        0 => 1,
        1 => 2,
        _ => next(seed) % 30,
    };
    (check_edge(seed, xl), check_edge(seed, xl + w))
}

/// Case `case` of [`check_rows_kernel`], in rows of width [`CHECK_W`]: its rows, and
/// where they lie.
fn check_case(seed: &mut u32, case: u32) -> (RowsLess, CheckPlace) {
    let mid_right = next(seed).is_multiple_of(2);
    let (l, rt) = check_pair(seed);
    let (long, short0) = if mid_right { (l, rt) } else { (rt, l) };
    let (l, rt) = check_pair(seed);
    let short1 = if mid_right { rt } else { l };
    let place = check_place(seed, case, CHECK_W);
    let mut r = RowsLess::new(place.cx[0], place.cx[1]);
    r.edges(long, [short0, short1], place.n1, mid_right);
    let [sx, sy, lo, hi] = place.depth;
    r.depth(sx, sy, lo, hi);
    (r, place)
}

/// A case of the rows kernels' checks but for its edges: the clip columns, the depth
/// plane `[sx, sy, lo, hi]`, where the rows lie (with the first half's `n0`), the
/// second half's row count, the colour.
pub(super) struct CheckPlace {
    pub cx: [i32; 2],
    pub depth: [u32; 4],
    pub at: RowsAt,
    pub n1: u32,
    pub color: u16,
}

/// A random [`CheckPlace`] for case `case` (clipped or not, and each sign of `sx`, by
/// `case`) in rows of width `w`.
pub(super) fn check_place(seed: &mut u32, case: u32, w: usize) -> CheckPlace {
    let px0 = (next(seed) % 20) as i32 - 6;
    let cx = if case.is_multiple_of(2) {
        [-px0, w as i32 - px0]
    } else {
        let a = next(seed) % w as u32;
        let b = a + next(seed) % (w as u32 - a + 1);
        [a as i32 - px0, b as i32 - px0]
    };
    let sx = match case % 4 {
        0 => next(seed) >> 12,
        1 => (next(seed) >> 12).wrapping_neg(),
        _ => next(seed) >> (8 + next(seed) % 16),
    };
    let (n0, n1) = (next(seed) % 7, next(seed) % 7);
    let (z, sy, lo) = (next(seed), next(seed), next(seed) >> 2);
    let hi = lo.wrapping_add(next(seed) >> 2).max(lo);
    let row0 = (next(seed) % 3) as usize;
    let at = RowsAt {
        row0,
        width: w,
        px0,
        n0,
        z,
    };
    let color = next(seed) as u16;
    CheckPlace {
        cx,
        depth: [sx, sy, lo, hi],
        at,
        n1,
        color,
    }
}

/// The width of the rows kernels' check buffers (48 × 16 each).
pub(super) const CHECK_W: usize = 48;

/// The rows kernels' on-target checks: 600 cases, each `make` from the same seed twice
/// (a kernel writes its block), drawn by `kernel` and by its portable `twin` (where
/// the kernel must not refuse: rows inside the buffers, [`RowsAt::check`]) into
/// copies of the same random buffers (depths failing and passing, the colour rows at
/// both alignments to the depth rows), compared (depths, colours, counts). `buf` holds
/// four 48 × 16 buffers (3,072 halfwords; a shorter one is a failure). Returns the
/// number of cases that differ.
pub(super) fn check_cases<R>(
    buf: &mut [u16],
    mut seed: u32,
    make: impl Fn(&mut u32, u32) -> (R, CheckPlace),
    kernel: impl Fn(&mut R, RowsAt, &mut [u16], &mut [u16], u16) -> Option<(u32, u32)>,
    twin: impl Fn(&R, RowsAt, &mut [u16], &mut [u16], u16) -> (u32, u32),
) -> usize {
    const N: usize = CHECK_W * 16;
    let Some(buf) = buf.get_mut(..4 * N) else {
        return usize::MAX;
    };
    let (mine, theirs) = buf.split_at_mut(2 * N);
    let (z1, c1) = mine.split_at_mut(N);
    let (z2, c2) = theirs.split_at_mut(N);
    let mut bad = 0;
    for case in 0..600u32 {
        for (d, c) in z1.iter_mut().zip(c1.iter_mut()) {
            (*d, *c) = (
                next(&mut seed) as u16 | 0x8000 >> (case % 3),
                next(&mut seed) as u16,
            );
        }
        z2.copy_from_slice(z1);
        c2.copy_from_slice(c1);
        // Odd and even starting offsets: the colour rows at the depth rows' address
        // modulo 4 (the SIMD steps), and (every other case) not.
        let off = (case / 2 % 2) as usize;
        let (Some(ca), Some(cb)) = (c1.get_mut(off..), c2.get_mut(off..)) else {
            return usize::MAX;
        };
        let first = seed;
        let (mut r, p) = make(&mut seed, case);
        let got = kernel(&mut r, p.at, &mut z1[..], ca, p.color);
        let (r, p) = make(&mut first.clone(), case);
        let inside = p.at.check(p.n1, p.cx, N - off);
        let want = inside.map(|()| twin(&r, p.at, &mut z2[..], cb, p.color));
        // Refused only outside the buffers, and nothing written then.
        if got != want || z1 != z2 || c1 != c2 {
            bad += 1;
        }
    }
    bad
}

/// The set-up kernel's cases of [`check_rows_kernel`]: random triangles (from a pixel
/// to the buffer across, some 512 pixels or more, flat, of steep depth; clips inside
/// the buffers, some narrower) through `small_less_as_u16` or (every other one, the
/// corners as cache entries) `small_less_cached`, and `small_less_portable`
/// into copies of the same buffers (a depth and a colour buffer of 48 × 16 each in
/// `mine` and `twin`), compared. Returns the number of cases that differ.
fn check_small_setup(seed: &mut u32, mine: &mut [u16], twin: &mut [u16]) -> usize {
    const W: usize = 48;
    const H: usize = 16;
    let (z1, c1) = mine.split_at_mut(W * H);
    let (z2, c2) = twin.split_at_mut(W * H);
    let mut bad = 0;
    for case in 0..1200u32 {
        for (d, c) in z1.iter_mut().zip(c1.iter_mut()) {
            (*d, *c) = (next(seed) as u16 | 0x8000 >> (case % 3), next(seed) as u16);
        }
        z2.copy_from_slice(z1);
        c2.copy_from_slice(c1);
        // Colour rows at the depth rows' address modulo 4, or not (one row fewer).
        let off = (case / 2 % 2) as usize;
        let first_row = (next(seed) % 5) as i32 - 2;
        let rows = (H - off) as i32;
        let clip = if case % 3 == 0 {
            let (x0, y0) = ((next(seed) % 20) as i32, (next(seed) % 6) as i32);
            Clip {
                x0,
                y0: first_row + y0,
                x1: x0 + (next(seed) % 30) as i32,
                y1: first_row + y0 + (next(seed) % 10) as i32,
            }
        } else {
            Clip {
                x0: 0,
                y0: first_row,
                x1: W as i32,
                y1: first_row + rows,
            }
        };
        let span = 40 << (case % 4 * 3 / 2); // 40, 80, 320, 640
        let z0 = next(seed) >> 1;
        let spread = 1u32 << (10 + case / 4 % 4 * 7); // 2¹⁰, 2¹⁷, 2²⁴, 2³¹
                                                      // Corners near a random point of the buffer (1/16 pixel), one far on some.
        let (bx, by) = (
            (next(seed) % (W as u32 * 16)) as i32 - 40,
            (next(seed) % (H as u32 * 16)) as i32 - 40 + first_row * 16,
        );
        let mut vertex = |k: u32| {
            let far = if case % 29 == 0 && k == 1 { 9000 } else { 0 };
            let x = (next(seed) % span) as i32 + bx - span as i32 / 2 + far;
            let y = (next(seed) % span) as i32 + by - span as i32 / 2;
            let z = z0
                .saturating_add(next(seed) % spread)
                .min(crate::fixed::MAX_DEPTH);
            ScreenVertex::new(x, y, z).unwrap_or(ScreenVertex::ORIGIN)
        };
        let mut tri = [vertex(0), vertex(1), vertex(2)];
        if case % 7 == 0 {
            tri[2] = tri[1];
        }
        let (Some(ca), Some(cb)) = (c1.get_mut(off..), c2.get_mut(off..)) else {
            return usize::MAX;
        };
        let color = next(seed) as u16;
        let mut t = SmallTarget {
            z: &mut z1[..],
            c: ca,
            width: W,
            first_row,
            clip,
        };
        // Every other case through the entry reading the corners as the vertex cache
        // holds them (each coordinate here fits its i16).
        let cached = tri.map(|p| CachedVertex {
            z: p.z(),
            xy: XyWord::new(p.x() as i16, p.y() as i16),
        });
        let got = if case % 2 == 1 {
            small_less_cached(&mut t, cached.each_ref(), color)
        } else {
            small_less_as_u16(&mut t, tri.each_ref(), color)
        };
        let want = small_less_portable(tri.each_ref(), &clip, first_row, W, z2, cb, color);
        if got != want || z1 != z2 || c1 != c2 {
            bad += 1;
        }
    }
    bad
}

/// On-target check of the rows assembly against its twin, for the bench firmware
/// (`check_cases`): random triangles' rows (edges, depths, clip columns, both
/// halves, rows of every length from empty to 40 pixels) through `rows_less_as_u16`
/// and `rows_less_portable`, then whole small triangles, set-up and rows, through
/// `small_less_as_u16` and its twin (`check_small_setup`). Returns the number of
/// cases that differ (where there is no assembly, the twin against itself). Out of
/// line: its frame is not the bench's.
#[inline(never)]
pub fn check_rows_kernel(buf: &mut [u16]) -> usize {
    let kernel = rows_less_as_u16::<u16>;
    let bad = check_cases(buf, 0x2545_f491, check_case, kernel, rows_less_portable);
    let Some(buf) = buf.get_mut(..4 * CHECK_W * 16) else {
        return usize::MAX;
    };
    let (mine, twin) = buf.split_at_mut(2 * CHECK_W * 16);
    bad.saturating_add(check_small_setup(&mut 0x9e37_79b9, mine, twin))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_kernel_matches_its_twin() {
        let mut buf = [0u16; 4 * 48 * 16];
        assert_eq!(check_rows_kernel(&mut buf), 0);
        assert_eq!(check_rows_kernel(&mut buf[..100]), usize::MAX);
    }

    /// Rows outside the buffers are refused, not drawn.
    #[test]
    fn rows_outside_the_buffers_are_refused() {
        let mut r = RowsLess::new(0, 8);
        let (long, short) = (
            DivEdge { t: 0, dt: 0, d: 16 },
            DivEdge {
                t: 64,
                dt: 0,
                d: 16,
            },
        );
        r.edges(long, [short, DivEdge::default()], 0, true);
        let at = |row0, px0| RowsAt {
            row0,
            width: 8,
            px0,
            n0: 4,
            z: 0,
        };
        let len = 8 * 4;
        assert!(at(0, 0).check(r.n1, r.cx, len).is_some());
        assert!(at(1, 0).check(r.n1, r.cx, len).is_none());
        assert!(at(0, 1).check(r.n1, r.cx, len).is_none());
        assert!(at(0, -1).check(r.n1, r.cx, len).is_none());
        assert!(at(usize::MAX, 0).check(r.n1, r.cx, len).is_none());
    }
}
