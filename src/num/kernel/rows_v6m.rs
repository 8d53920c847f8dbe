//! A small flat-coloured triangle on ARMv6-M, the depth test `Less` with depth
//! writes, a two-byte colour: set-up and rows in one call
//! ([`small_walk_less_as_u16`]), which walks the triangle's bounding box by three
//! integer edge functions (no sort, no halves, no division but the depth steps', by a
//! reciprocal); and the rows of a triangle set up in Rust, both halves in one loop,
//! edges in the DDA form of [`EdgeWalk`](crate::raster::EdgeWalk)
//! ([`rows_walk_less_as_u16`]). Thumb-1 assembly beside its portable twins.
#![allow(unsafe_code)]

use super::rows::{as_u16, check_cases, check_place, next, twin_row, CHECK_W};
use super::{CachedVertex, RowsAt, SmallDone, SmallTarget, XyWord};
use crate::num::floor_div32_pair_small;
use crate::raster::{Clip, ScreenVertex, DEPTH_BIAS, SMALL};

/// Whether the small triangles' rows go to [`rows_walk_less_as_u16`] (ARMv6-M).
pub(crate) const WALK_KERNEL: bool = cfg!(all(zraster_thumb, zraster_armv6m));

/// One edge as [`EdgeWalk`](crate::raster::EdgeWalk) walks it, in three words: `at`
/// holds the row's first column `x` in its upper half and `⌊err/16⌋` in its lower (in
/// `0..dy`, below 2¹³ for a small triangle). `EdgeWalk`'s `rem` and `denom` are
/// multiples of 16, so its `err` keeps its remainder modulo 16 and goes negative
/// exactly when `⌊err/16⌋` does. Each row `at += step`, `step` being
/// `(step << 16) − rem/16`: `x += step` and `err -= rem` at once, a negative `err`
/// borrowing one from `x` and setting the lower half's bit 15; then `at += fix`, `fix`
/// being `(1 << 16) + denom/16`, gives back the borrowed one, adds one to `x` (the
/// carry out of the lower half) and `denom` to `err` (all wrapping). Laid out `at`,
/// `fix`, `step`: the set-up stores the three by one STM in that order.
#[repr(C)]
#[derive(Clone, Copy, Default, Debug, PartialEq, Eq)]
pub(crate) struct WalkEdge {
    at: u32,
    fix: u32,
    step: u32,
}

impl WalkEdge {
    /// From [`EdgeWalk::parts`](crate::raster::EdgeWalk::parts) of a small triangle's
    /// edge.
    #[inline(always)]
    pub(crate) fn from_parts([x, err, rem, denom, step]: [i32; 5]) -> WalkEdge {
        WalkEdge {
            at: ((x as u32) << 16).wrapping_add((err >> 4) as u32),
            step: ((step as u32) << 16).wrapping_sub((rem >> 4) as u32),
            fix: (1 << 16) + (denom >> 4) as u32,
        }
    }

    /// The row's first column.
    #[inline(always)]
    fn x(&self) -> i32 {
        self.at as i32 >> 16
    }

    /// The next row.
    #[inline(always)]
    fn advance(&mut self) {
        self.at = self.at.wrapping_add(self.step);
        if self.at & 0x8000 != 0 {
            self.at = self.at.wrapping_add(self.fix);
        }
    }
}

/// The rows of a small triangle in columns relative to its origin column `px0`, laid
/// out as the assembly reads them (byte offsets in the comments): [`RowsAt::n0`] rows
/// between the long and the short edge (the long one on the left when `side` is 0),
/// then `n1` rows with the short edge replaced by `short1`. Each row covers
/// `max(left.x(), cx0)..min(right.x(), cx1)`; the depth at its column `x` is
/// `clamp(z + x·sx, lo, hi)` then `+ sx` a pixel, `z` ([`RowsAt::z`]) stepping by `sy`
/// a row (all wrapping).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub(crate) struct RowsWalk {
    sx: u32,              // 0
    lo: u32,              // 4
    span: u32,            // 8: hi − lo
    color: u32,           // 12
    delta: u32,           // 16: colour address − depth address
    cx: [i32; 2],         // 20
    failed: u32,          // 28
    sy: u32,              // 32
    pitch: u32,           // 36: bytes a row
    n1: u32,              // 40
    side: u32,            // 44: 0 with the long edge on the left, else 1
    edges: [WalkEdge; 2], // 48: long, short (the loop swaps them when side is 1)
    short1: WalkEdge,     // 72
}

// The assembly reads and writes the block at these offsets (by LDR/LDM): pinned here,
// so that a change of the layout fails to build.
const _: () = {
    use core::mem::{align_of, offset_of, size_of};
    assert!(offset_of!(RowsWalk, sx) == 0 && offset_of!(RowsWalk, lo) == 4);
    assert!(offset_of!(RowsWalk, span) == 8 && offset_of!(RowsWalk, color) == 12);
    assert!(offset_of!(RowsWalk, delta) == 16 && offset_of!(RowsWalk, cx) == 20);
    assert!(offset_of!(RowsWalk, failed) == 28 && offset_of!(RowsWalk, sy) == 32);
    assert!(offset_of!(RowsWalk, pitch) == 36 && offset_of!(RowsWalk, n1) == 40);
    assert!(offset_of!(RowsWalk, side) == 44 && offset_of!(RowsWalk, edges) == 48);
    assert!(offset_of!(RowsWalk, short1) == 72 && size_of::<RowsWalk>() == 84);
    assert!(offset_of!(WalkEdge, fix) == 4 && offset_of!(WalkEdge, step) == 8);
    assert!(size_of::<WalkEdge>() == 12 && align_of::<RowsWalk>() >= 4);
};

impl RowsWalk {
    /// Rows clipped to the columns `cx[0]..cx[1]` with the depth plane's steps `sx`,
    /// `sy` and clamp `lo..=hi`: `n0` rows (see [`RowsAt`]) between the long edge and
    /// `short[0]`, then `n1` between the long edge carried on and `short[1]`; the long
    /// edge on the left when `mid_right`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn new(
        [sx, sy, lo, hi]: [u32; 4],
        cx: [i32; 2],
        long: WalkEdge,
        short: [WalkEdge; 2],
        n1: u32,
        mid_right: bool,
    ) -> RowsWalk {
        RowsWalk {
            sx,
            lo,
            span: hi.wrapping_sub(lo),
            color: 0,
            delta: 0,
            cx,
            failed: 0,
            sy,
            pitch: 0,
            n1,
            side: u32::from(!mid_right),
            edges: [long, short[0]],
            short1: short[1],
        }
    }
}

/// Draw `r` into the depth rows `z` and colour rows `c` in `color`: the depth test
/// `Less` with depth writes. Returns (pixels tested, pixels failed), or `None` (nothing
/// drawn) when `C` is not a two-byte type or the rows do not lie inside the buffers.
#[inline(always)]
pub(crate) fn rows_walk_less_as_u16<C: Copy>(
    r: &mut RowsWalk,
    at: RowsAt,
    z: &mut [u16],
    c: &mut [C],
    color: C,
) -> Option<(u32, u32)> {
    let (words, bits) = as_u16(c, color)?;
    at.check(r.n1, r.cx, z.len().min(words.len()))?;
    Some(rows_walk_less_u16(r, at, z, words, bits))
}

/// [`rows_walk_less_as_u16`] for `u16` colours, the rows already checked to lie inside
/// both buffers: on ARMv6-M the block's last fields, then one out-of-line call where
/// every row's columns lie inside the clip's (the loop does not clip), else the twin.
#[inline(always)]
fn rows_walk_less_u16(
    r: &mut RowsWalk,
    at: RowsAt,
    z: &mut [u16],
    c: &mut [u16],
    color: u16,
) -> (u32, u32) {
    #[cfg(all(zraster_thumb, zraster_armv6m))]
    {
        if !columns_inside(r, at.n0) {
            return rows_walk_less_portable(r, at, z, c, color);
        }
        let zaddr = z.as_mut_ptr() as u32;
        let index = (at.row0.wrapping_mul(at.width) as u32).wrapping_add(at.px0 as u32);
        r.color = u32::from(color);
        r.delta = (c.as_mut_ptr() as u32).wrapping_sub(zaddr);
        r.pitch = (at.width as u32).wrapping_mul(2);
        r.failed = 0;
        let base = zaddr.wrapping_add(index.wrapping_mul(2));
        // SAFETY: the caller has checked (`RowsAt::check`) that the rows lie inside
        // both buffers; `zraster_rows_walk_v6m`'s own comment says what it touches.
        let tested = unsafe { zraster_rows_walk_v6m(r, at.z, base, at.n0) };
        (tested, r.failed)
    }
    #[cfg(not(all(zraster_thumb, zraster_armv6m)))]
    {
        rows_walk_less_portable(r, at, z, c, color)
    }
}

/// Whether every row of `r` (`n0`, then `r.n1`) whose columns `x .. x'` are not empty
/// has them inside `r.cx`: the assembly loop's contract (it does not clip). The edges
/// walked as the twin walks them.
#[cfg(any(test, all(zraster_thumb, zraster_armv6m)))]
fn columns_inside(r: &RowsWalk, n0: u32) -> bool {
    let mut e = r.edges;
    if r.side != 0 {
        e.reverse();
    }
    for (half, n) in [n0, r.n1].into_iter().enumerate() {
        if half == 1 {
            let [left, right] = &mut e;
            *(if r.side == 0 { right } else { left }) = r.short1;
        }
        for _ in 0..n {
            let (x, x1) = (e[0].x(), e[1].x());
            if x < x1 && (x < r.cx[0] || x1 > r.cx[1]) {
                return false;
            }
            e[0].advance();
            e[1].advance();
        }
    }
    true
}

/// The portable twin of the assembly: the rasterizer's own row loop for this case
/// (the same pixels, depths and counts). Pixels outside the buffers are skipped.
pub(crate) fn rows_walk_less_portable(
    r: &RowsWalk,
    at: RowsAt,
    z: &mut [u16],
    c: &mut [u16],
    color: u16,
) -> (u32, u32) {
    let (mut tested, mut failed) = (0u32, 0u32);
    let mut zrow = at.z;
    let mut base = (at.row0.wrapping_mul(at.width)).wrapping_add_signed(at.px0 as isize);
    let mut e = r.edges;
    if r.side != 0 {
        e.reverse();
    }
    for (half, n) in [at.n0, r.n1].into_iter().enumerate() {
        if half == 1 {
            let [left, right] = &mut e;
            *(if r.side == 0 { right } else { left }) = r.short1;
        }
        for _ in 0..n {
            let (xa, xb) = (e[0].x().max(r.cx[0]), e[1].x().min(r.cx[1]));
            e[0].advance();
            e[1].advance();
            let depth = [zrow, r.sx, r.lo, r.lo.wrapping_add(r.span)];
            let (t, f) = twin_row(z, c, base, (xa, xb), depth, color);
            (tested, failed) = (tested.wrapping_add(t), failed.wrapping_add(f));
            zrow = zrow.wrapping_add(r.sy);
            base = base.wrapping_add(at.width);
        }
    }
    (tested, failed)
}

/// [`small_walk_less_as_u16`]'s block, as the assembly reads it (byte offsets in the
/// comments; `color` and `failed` where `faces_v6m`'s loops write and read them): the
/// depth address of screen row 0's column 0 (wrapping: `zaddr − first_row·pitch`),
/// the bytes a row, the clip (rows `y0..y1`, columns `x0..x1`), the colour, its
/// address's offset from the depth's, the failed pixels' count, and where to keep the
/// set-up of a triangle whose rows go on past the clip (0: nowhere; the bands' loop
/// sets it for a face the band below resumes: [`KEPT_WALK_WORDS`]).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
#[cfg_attr(not(all(zraster_thumb, zraster_armv6m)), allow(dead_code))]
struct SmallWalk {
    base: u32,   // 0
    pitch: u32,  // 4
    y0: i32,     // 8
    color: u32,  // 12
    delta: u32,  // 16: colour address − depth address
    y1: i32,     // 20
    x0: i32,     // 24
    failed: u32, // 28
    x1: i32,     // 32
    save: u32,   // 36
}

#[cfg_attr(not(all(zraster_thumb, zraster_armv6m)), allow(dead_code))]
impl SmallWalk {
    /// Writes the fields that stay the same for buffers (the depth at `zaddr`, the
    /// colour `delta` bytes on, rows of `width` from screen row `first_row`) drawn
    /// inside `clip`, through a pointer to a block that may be uninitialised.
    ///
    /// # Safety
    ///
    /// `p` points to a block, valid for writes.
    #[inline(always)]
    unsafe fn write_buffers(
        p: *mut SmallWalk,
        zaddr: u32,
        delta: u32,
        width: usize,
        first_row: i32,
        clip: Clip,
    ) {
        let pitch = (width as u32).wrapping_mul(2);
        // SAFETY: writes to fields of `*p` (the caller's contract), through the
        // pointer (no reference to uninitialised memory is made).
        unsafe {
            (&raw mut (*p).base).write(zaddr.wrapping_sub((first_row as u32).wrapping_mul(pitch)));
            (&raw mut (*p).pitch).write(pitch);
            (&raw mut (*p).delta).write(delta);
            (&raw mut (*p).y0).write(clip.y0);
            (&raw mut (*p).y1).write(clip.y1);
            (&raw mut (*p).x0).write(clip.x0);
            (&raw mut (*p).x1).write(clip.x1);
            (&raw mut (*p).save).write(0);
        }
    }
}

const _: () = {
    use core::mem::{offset_of, size_of};
    assert!(offset_of!(SmallWalk, pitch) == 4 && offset_of!(SmallWalk, y0) == 8);
    assert!(offset_of!(SmallWalk, color) == 12 && offset_of!(SmallWalk, delta) == 16);
    assert!(offset_of!(SmallWalk, y1) == 20 && offset_of!(SmallWalk, x0) == 24);
    assert!(offset_of!(SmallWalk, failed) == 28 && offset_of!(SmallWalk, x1) == 32);
    assert!(offset_of!(SmallWalk, save) == 36 && size_of::<SmallWalk>() == 40);
    assert!(SMALL == 8192 && DEPTH_BIAS == 32768);
    // The corners as the cache holds them: the depth, then x (low half) and y.
    assert!(offset_of!(CachedVertex, z) == 0 && offset_of!(CachedVertex, xy) == 4);
    assert!(size_of::<CachedVertex>() == 8);
};

/// The small flat triangle `tri` in `color` with the depth test `Less` and depth
/// writes, set-up and rows, on ARMv6-M in one assembly call
/// (`zraster_small_walk_v6m`): the pixels, depths and counts of `fill::small`'s
/// ARMv6-M path. [`SmallDone::General`] (nothing drawn) for a colour that is not two
/// bytes, a clip not inside the buffers, or a triangle the set-up leaves to that path
/// (an extent of 512 pixels or more, `|area| ≥ 2¹⁶`, steep depth).
#[inline(always)]
pub(crate) fn small_walk_less_as_u16<C: Copy>(
    t: &mut SmallTarget<'_, '_, C>,
    tri: [&ScreenVertex; 3],
    color: C,
) -> SmallDone {
    let Some([a, b, c]) = cache_entries(tri) else {
        return SmallDone::General;
    };
    small_walk_cached_as_u16(t, [&a, &b, &c], color)
}

/// The corners `tri` as the vertex cache holds them (an unmarked entry: x and y in
/// `i16`), or `None` when one does not fit.
#[inline(always)]
pub(crate) fn cache_entries(tri: [&ScreenVertex; 3]) -> Option<[CachedVertex; 3]> {
    let entry = |v: &ScreenVertex| {
        let (x, y) = (i16::try_from(v.x()).ok()?, i16::try_from(v.y()).ok()?);
        Some(CachedVertex {
            z: v.z(),
            xy: XyWord::new(x, y),
        })
    };
    Some([entry(tri[0])?, entry(tri[1])?, entry(tri[2])?])
}

/// Whether every row and column of `clip` lies inside buffers of `len` pixels, rows of
/// `width` from screen row `first_row`: then so is every pixel the set-up's rows may
/// touch. In 32-bit arithmetic, as the assembly's addresses: a row's offset from the
/// first is `row − first_row` modulo 2³², those of `y0` and `y1` (`a ≤ b`, both below
/// 2¹⁶, as the width: a 32-bit product) bound every row between (a row lies in
/// `y0..y1` by signed compares, so its offset is `a` plus less than `y1 − y0 = b − a`).
#[inline(always)]
fn clip_inside(clip: Clip, first_row: i32, width: usize, len: usize) -> bool {
    let a = clip.y0.wrapping_sub(first_row) as u32;
    let b = clip.y1.wrapping_sub(first_row) as u32;
    a <= b
        && (b as usize | width) <= 0xffff
        && clip.x0 >= 0
        && clip.x1 <= width as i32
        && b as usize * width <= len
}

/// [`small_walk_less_as_u16`] with the corners as the vertex cache holds them
/// (unmarked entries), read in place by the assembly.
#[inline(always)]
pub(crate) fn small_walk_cached_as_u16<C: Copy>(
    t: &mut SmallTarget<'_, '_, C>,
    tri: [&CachedVertex; 3],
    color: C,
) -> SmallDone {
    let Some((words, bits)) = as_u16(&mut *t.c, color) else {
        return SmallDone::General;
    };
    let (clip, first_row, width) = (t.clip, t.first_row, t.width);
    if !clip_inside(clip, first_row, width, t.z.len().min(words.len())) {
        return SmallDone::General;
    }
    #[cfg(all(zraster_thumb, zraster_armv6m))]
    {
        let zaddr = t.z.as_mut_ptr() as u32;
        // The block's fields the assembly reads before it writes them; the rest it
        // writes (an edge of a half without rows it neither writes nor reads).
        let mut s = core::mem::MaybeUninit::<SmallWalk>::uninit();
        let p = s.as_mut_ptr();
        // SAFETY: writes to fields of `s`, through a pointer to it (no reference to
        // uninitialised memory is made). Then the call: every row and column of the
        // clip lies inside both buffers (checked above), and the assembly draws only
        // inside the clip; its comment says what it touches. `failed` is written
        // here, and the assembly only adds to it.
        unsafe {
            (&raw mut (*p).color).write(u32::from(bits));
            (&raw mut (*p).failed).write(0);
            let delta = (words.as_mut_ptr() as u32).wrapping_sub(zaddr);
            SmallWalk::write_buffers(p, zaddr, delta, width, first_row, clip);
            let tested = zraster_small_walk_v6m(p, tri[0], tri[1], tri[2]);
            if tested == u32::MAX {
                SmallDone::General
            } else {
                SmallDone::Drawn(tested, (&raw const (*p).failed).read())
            }
        }
    }
    #[cfg(not(all(zraster_thumb, zraster_armv6m)))]
    {
        let [p, q, r] = tri.map(CachedVertex::placed);
        small_walk_portable(
            [&p, &q, &r],
            &clip,
            first_row,
            width,
            &mut *t.z,
            words,
            bits,
        )
    }
}

/// Colour and depth rows of the same geometry (`width` pixels a row from screen row
/// `first_row`), and the pixels drawing may touch (`clip`); on ARMv6-M with the fields
/// of the set-up's block that stay the same for these buffers, written once here
/// rather than a triangle (`SmallWalk`'s depth address of row 0, the colour's offset
/// from it, the pitch and the clip, as [`Buffers::start`] found them).
///
/// The buffers are private and handed out only as reborrows, so that the block's
/// addresses stay theirs while it lives: [`walk_cached`](Buffers::walk_cached) relies
/// on it. `width`, `first_row` and `clip` are the Rust paths' copies (the block holds the
/// clip and, folded into its row-0 address and pitch, the width and first row).
pub(crate) struct Buffers<'z, 'c, C> {
    zdata: &'z mut [u16],
    cdata: &'c mut [C],
    /// Pixels a row.
    pub width: usize,
    /// The screen row of the buffers' first row.
    pub first_row: i32,
    /// The pixels drawing may touch.
    pub clip: Clip,
    /// The set-up block, its per-buffer fields written when `walk` is true.
    #[cfg(all(zraster_thumb, zraster_armv6m))]
    block: core::mem::MaybeUninit<SmallWalk>,
    /// Whether the assembly takes these buffers: a two-byte colour, the clip inside
    /// both buffers (then the block's per-buffer fields are written).
    #[cfg(all(zraster_thumb, zraster_armv6m))]
    walk: bool,
}

impl<'z, 'c, C: Copy> Buffers<'z, 'c, C> {
    /// `zdata` and `cdata` of rows of `width` from screen row `first_row`, drawn inside
    /// `clip`, started (the tests' form).
    #[cfg(test)]
    pub(crate) fn new(
        zdata: &'z mut [u16],
        cdata: &'c mut [C],
        width: usize,
        first_row: i32,
        clip: Clip,
    ) -> Self {
        let mut b = Self::unstarted(zdata, cdata, width, first_row, clip);
        b.start();
        b
    }

    /// The buffers, the block's per-buffer fields not yet written:
    /// [`start`](Buffers::start) writes them once the value is where it stays (a move
    /// after would copy the block, and take stack for both copies). Until then
    /// [`walk_cached`](Buffers::walk_cached) leaves every triangle to the general path.
    #[inline(always)]
    pub(crate) fn unstarted(
        zdata: &'z mut [u16],
        cdata: &'c mut [C],
        width: usize,
        first_row: i32,
        clip: Clip,
    ) -> Self {
        Buffers {
            zdata,
            cdata,
            width,
            first_row,
            clip,
            #[cfg(all(zraster_thumb, zraster_armv6m))]
            block: core::mem::MaybeUninit::uninit(),
            #[cfg(all(zraster_thumb, zraster_armv6m))]
            walk: false,
        }
    }

    /// Writes the block's per-buffer fields where the assembly takes the buffers (see
    /// [`Buffers::unstarted`]).
    #[inline(always)]
    pub(crate) fn start(&mut self) {
        #[cfg(all(zraster_thumb, zraster_armv6m))]
        self.start_walk();
    }

    /// [`Buffers::start`] unless started: the band checks call it before each run of
    /// the loop, which then shares one block across its calls, as a frame's band does.
    #[inline(always)]
    pub(crate) fn start_once(&mut self) {
        #[cfg(all(zraster_thumb, zraster_armv6m))]
        if !self.walk {
            self.start_walk();
        }
    }

    /// The depth and colour rows.
    #[inline(always)]
    pub(crate) fn parts(&mut self) -> (&mut [u16], &mut [C]) {
        (&mut *self.zdata, &mut *self.cdata)
    }

    /// The buffers as the small triangles' kernels take them.
    #[inline(always)]
    pub(crate) fn target(&mut self) -> SmallTarget<'_, '_, C> {
        SmallTarget {
            z: &mut *self.zdata,
            c: &mut *self.cdata,
            width: self.width,
            first_row: self.first_row,
            clip: self.clip,
        }
    }

    /// Writes the block's per-buffer fields where the assembly takes the buffers, once
    /// (out of line: one copy for every loop).
    #[cfg(all(zraster_thumb, zraster_armv6m))]
    #[inline(never)]
    fn start_walk(&mut self) {
        let (clip, first_row, width) = (self.clip, self.first_row, self.width);
        let len = self.zdata.len().min(self.cdata.len());
        if !super::two_bytes::<C>() || !clip_inside(clip, first_row, width, len) {
            return;
        }
        let zaddr = self.zdata.as_mut_ptr() as u32;
        let caddr = self.cdata.as_mut_ptr() as u32;
        let p = self.block.as_mut_ptr();
        // SAFETY: writes to fields of the block, through a pointer to it (no reference
        // to uninitialised memory is made).
        unsafe {
            SmallWalk::write_buffers(p, zaddr, caddr.wrapping_sub(zaddr), width, first_row, clip);
        }
        self.walk = true;
    }

    /// The set-up block's address where the assembly takes these buffers (its
    /// per-buffer fields written by [`Buffers::start`]), for the ARMv6-M face loop
    /// (`faces_v6m`), which writes its `color` and `failed` and calls
    /// `zraster_small_walk_v6m` with it as [`walk_cached`](Buffers::walk_cached) does.
    #[cfg(all(zraster_thumb, zraster_armv6m))]
    #[inline(always)]
    pub(crate) fn walk_block(&mut self) -> Option<*mut u8> {
        self.walk.then(|| self.block.as_mut_ptr().cast::<u8>())
    }

    /// [`small_walk_cached_as_u16`] into these buffers, the block's per-buffer fields
    /// as [`Buffers::start`] wrote them: per triangle only the colour, the failures'
    /// count and the call.
    #[inline(always)]
    pub(crate) fn walk_cached(&mut self, tri: [&CachedVertex; 3], color: C) -> SmallDone {
        #[cfg(all(zraster_thumb, zraster_armv6m))]
        {
            if !self.walk {
                return SmallDone::General;
            }
            let p = self.block.as_mut_ptr();
            // SAFETY: `walk` is set only by `start_walk`, after it found `C` two bytes
            // with alignment two (so `color` reads as a u16) and every row and column of
            // the clip inside both buffers, and wrote the block's depth address, colour
            // offset, pitch, clip and first row from them. The buffers are this
            // struct's private fields, never replaced (only reborrows are handed out),
            // and `&mut self` borrows them exclusively for the call: another caller's
            // buffers cannot meet this block (a new `Buffers` writes a block of its
            // own). The assembly writes none of those; `color` (written here, below
            // 2¹⁶) and `save` only where `save` names a slot, which here it never does
            // (`write_buffers` made it 0; only the bands' loop names one, and clears it
            // after each face). `failed` is written here, and the assembly only adds
            // to it.
            unsafe {
                let bits = core::mem::transmute_copy::<C, u16>(&color);
                (&raw mut (*p).color).write(u32::from(bits));
                (&raw mut (*p).failed).write(0);
                let tested = zraster_small_walk_v6m(p, tri[0], tri[1], tri[2]);
                if tested == u32::MAX {
                    SmallDone::General
                } else {
                    SmallDone::Drawn(tested, (&raw const (*p).failed).read())
                }
            }
        }
        #[cfg(not(all(zraster_thumb, zraster_armv6m)))]
        small_walk_cached_as_u16(&mut self.target(), tri, color)
    }
}

/// The DDA's walk of a small triangle, which the bounding-box walk replaced:
/// [`small_walk_setup`] then [`rows_walk_less_portable`], the reference the tests hold
/// [`small_walk_portable`] to (the same pixels, depths and counts). The clip must lie
/// inside the buffers (pixels outside are skipped).
#[cfg(test)]
fn small_walk_dda(
    tri: [&ScreenVertex; 3],
    clip: &Clip,
    first_row: i32,
    width: usize,
    z: &mut [u16],
    c: &mut [u16],
    color: u16,
) -> SmallDone {
    match small_walk_setup(tri, clip, first_row, width) {
        Ok((r, at)) => {
            let (tested, failed) = rows_walk_less_portable(&r, at, z, c, color);
            SmallDone::Drawn(tested, failed)
        }
        Err(done) => done,
    }
}

/// The set-up of the bounding-box walk (`zraster_small_walk_v6m`) as its portable
/// twin works it out: the box's rows and first column, the depth plane, and three
/// edge functions at the box's first pixel centre with their steps a column (`ax`)
/// and a row (`by`), the long edge first (between the highest and lowest corners,
/// alone on its side), then the two on the other side. Each edge function is biased
/// so that a pixel is covered when all three are ≥ 0: the rule of
/// [`EdgeWalk`](crate::raster::EdgeWalk)'s rows (a pixel whose centre lies on an
/// edge is covered when the edge runs down the triangle's left, not its right; a
/// horizontal edge bounds only the rows, which the box's rows already do).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct BoxWalk {
    /// The box's rows (screen) and columns `bx0..bx1`.
    start: i32,
    end: i32,
    bx0: i32,
    bx1: i32,
    /// Depth at the first row's column `bx0`, its steps a column and a row, the clamp.
    z: u32,
    sx: u32,
    sy: u32,
    lo: u32,
    hi: u32,
    /// Edge functions (long, then the other two), their steps a column and a row.
    e: [i32; 3],
    ax: [i32; 3],
    by: [i32; 3],
    /// Whether the long edge runs down the left (then the rows start at it and end at
    /// the first of the other two to go negative), else the right.
    long_left: bool,
}

/// [`BoxWalk`] for the small triangle `tri` in `clip`, or what to do instead: the same
/// refusals, in the same order, as `small_walk_setup` (the DDA's set-up, the tests'
/// reference), so that the two take the same triangles.
fn box_walk_setup(tri: [&ScreenVertex; 3], clip: &Clip) -> Result<BoxWalk, SmallDone> {
    let [p0, p1, p2] = tri;
    let (ymin, ymax) = (
        p0.y().min(p1.y()).min(p2.y()),
        p0.y().max(p1.y()).max(p2.y()),
    );
    if ymax - ymin >= SMALL {
        return Err(SmallDone::General);
    }
    let centre = |y: i32| (y + 7) >> 4;
    let (start, end) = (centre(ymin).max(clip.y0), centre(ymax).min(clip.y1));
    let (xmin, xmax) = (
        p0.x().min(p1.x()).min(p2.x()),
        p0.x().max(p1.x()).max(p2.x()),
    );
    if xmax - xmin >= SMALL {
        return Err(SmallDone::General);
    }
    if start >= end {
        return Err(SmallDone::Drawn(0, 0));
    }
    if xmin >> 4 < clip.x0 || (xmax + 7) >> 4 > clip.x1 {
        return Err(SmallDone::General);
    }
    // The middle corner by y first (a rotation: the same orientation); the deltas
    // from it negated where the area is positive, so that it is negative: inside,
    // every edge function is ≥ 0.
    let word = |p: &ScreenVertex| (i64::from(p.y()) << 16) | i64::from(p.x() & 0xffff);
    let (y0, y1, y2) = (word(p0), word(p1), word(p2));
    let middle = if y0 <= y1 {
        if y0 >= y2 {
            0
        } else if y1 <= y2 {
            1
        } else {
            2
        }
    } else if y0 <= y2 {
        0
    } else if y1 >= y2 {
        1
    } else {
        2
    };
    let v = match middle {
        0 => [p0, p1, p2],
        1 => [p1, p2, p0],
        _ => [p2, p0, p1],
    };
    let (mut dx1, mut dy1, mut dx2, mut dy2) = (
        v[1].x() - v[0].x(),
        v[1].y() - v[0].y(),
        v[2].x() - v[0].x(),
        v[2].y() - v[0].y(),
    );
    let area = dx1 * dy2 - dx2 * dy1;
    if area == 0 {
        return Err(SmallDone::Drawn(0, 0));
    }
    if area > 0 {
        (dx1, dy1, dx2, dy2) = (-dx1, -dy1, -dx2, -dy2);
    }
    let d = area.unsigned_abs();
    if d >= 1 << 16 {
        return Err(SmallDone::General);
    }
    let (za, zb, zc) = (v[0].z(), v[1].z(), v[2].z());
    let (lo, hi) = (za.min(zb).min(zc), za.max(zb).max(zc));
    let extent = (xmax - xmin).max(ymax - ymin) as u32;
    if (((hi - lo) >> 15) + 1) * extent >= 1 << 19 {
        return Err(SmallDone::General);
    }
    let (dz1, dz2) = (
        (zb >> 4) as i32 - (za >> 4) as i32,
        (zc >> 4) as i32 - (za >> 4) as i32,
    );
    let cross = |a: i32, b: i32, c: i32, d: i32| a.wrapping_mul(b).wrapping_sub(c.wrapping_mul(d));
    let (na, nb) = (cross(dz1, dy2, dz2, dy1), cross(dz2, dx1, dz1, dx2));
    let within = |n: i32| (n.wrapping_add((1 << 27) - 1) as u32) < (1 << 28) - 1;
    if !(within(na) && within(nb)) {
        return Err(SmallDone::General);
    }
    // The area (of the deltas as they now are) is negative: the numerators' sign flips.
    let (q, r) = floor_div32_pair_small(-(na << 4), -(nb << 4), d);
    let (q, r) = (q as u32, r as u32);
    let bx0 = (xmin + 7) >> 4;
    let (cx, cy) = (16 * bx0 + 8, 16 * start + 8);
    let z = p0
        .z()
        .wrapping_add(DEPTH_BIAS)
        .wrapping_add(q.wrapping_mul((cx - p0.x()) as u32))
        .wrapping_add(r.wrapping_mul((cy - p0.y()) as u32));
    // The long edge 1 → 2, then 0 → 1 and 2 → 0, at (cx, cy): the three sum to |area|.
    let (x, y) = (cx - v[0].x(), cy - v[0].y());
    let (e01, e20) = (x * dy1 - y * dx1, y * dx2 - x * dy2);
    let dy = [dy2 - dy1, dy1, -dy2];
    let e = [d as i32 - e01 - e20, e01, e20];
    Ok(BoxWalk {
        start,
        end,
        bx0,
        bx1: (xmax + 7) >> 4,
        z,
        sx: q << 4,
        sy: r << 4,
        lo: lo + DEPTH_BIAS,
        hi: hi + DEPTH_BIAS,
        e: [
            e[0] - i32::from(dy[0] < 0),
            e[1] - i32::from(dy[1] < 0),
            e[2] - i32::from(dy[2] < 0),
        ],
        ax: dy.map(|d| 16 * d),
        by: [16 * (dx1 - dx2), -16 * dx1, 16 * dx2],
        long_left: dy[0] > 0,
    })
}

/// The rows of `w` as the assembly walks them: each row from the box's first column
/// until the edges on the left side are all ≥ 0, then pixels while those on the right
/// are (the span is convex); the first pixel's depth clamped. Pixels outside the
/// buffers are skipped; a walk that would leave the box stops (it never does, which
/// the tests check: the left side's edges are ≥ 0 by the box's last column, and a
/// pixel the right side's take is covered).
fn box_walk_rows(
    w: &BoxWalk,
    first_row: i32,
    width: usize,
    z: &mut [u16],
    c: &mut [u16],
    color: u16,
) -> (u32, u32) {
    let (mut tested, mut failed) = (0u32, 0u32);
    let (mut zrow, mut e) = (w.z, w.e);
    let step = |e: &mut [i32; 3], s: &[i32; 3]| {
        for (e, s) in e.iter_mut().zip(s) {
            *e = e.wrapping_add(*s);
        }
    };
    // The long edge alone on one side, the other two on the other.
    let long = |e: &[i32; 3]| e[0] >= 0;
    let pair = |e: &[i32; 3]| (e[1] | e[2]) >= 0;
    let left = |e: &[i32; 3]| if w.long_left { long(e) } else { pair(e) };
    let right = |e: &[i32; 3]| if w.long_left { pair(e) } else { long(e) };
    for row in w.start..w.end {
        let base = (row.wrapping_sub(first_row) as usize).wrapping_mul(width);
        let (mut x, mut acc, mut f) = (w.bx0, zrow, e);
        // The walk to the span's start ends by the box's last column (the assembly
        // relies on it: it has no bound); the tests check it.
        while !left(&f) {
            debug_assert!(x < w.bx1, "{w:?}");
            if x >= w.bx1 {
                break;
            }
            step(&mut f, &w.ax);
            (x, acc) = (x + 1, acc.wrapping_add(w.sx));
        }
        if right(&f) {
            acc = acc.max(w.lo).min(w.hi);
        }
        while right(&f) {
            // Only covered pixels, inside the box (the tests check it).
            debug_assert!(left(&f) && x < w.bx1, "{w:?}");
            if x >= w.bx1 {
                break;
            }
            let i = base.wrapping_add(x as usize);
            if let (Some(zp), Some(cp)) = (z.get_mut(i), c.get_mut(i)) {
                let d = (acc >> 16) as u16;
                if d < *zp {
                    (*zp, *cp) = (d, color);
                } else {
                    failed = failed.wrapping_add(1);
                }
            }
            tested = tested.wrapping_add(1);
            step(&mut f, &w.ax);
            (x, acc) = (x + 1, acc.wrapping_add(w.sx));
        }
        step(&mut e, &w.by);
        zrow = zrow.wrapping_add(w.sy);
    }
    (tested, failed)
}

/// The model of a walk kept and resumed (`.Lbw_save` and `zraster_small_resume_v6m`):
/// `w`, set up in a clip whose rows end at `y1` above the triangle's rows' end `end`,
/// kept at row y1 (its row state stepped there), then resumed in `clip` if that starts
/// at y1 (else `None`: the set-up's). The tests hold it to the set-up in `clip`.
#[cfg(test)]
fn box_walk_resume(w: &BoxWalk, y1: i32, end: i32, clip: &Clip) -> Option<BoxWalk> {
    let step = |v: u32, s: u32, rows: i32| v.wrapping_add(s.wrapping_mul(rows as u32));
    if clip.y0 != y1 {
        return None;
    }
    let rows = y1 - w.start;
    let mut e = w.e;
    for (e, by) in e.iter_mut().zip(w.by) {
        *e = step(*e as u32, by as u32, rows) as i32;
    }
    Some(BoxWalk {
        start: clip.y0,
        end: end.min(clip.y1),
        z: step(w.z, w.sy, rows),
        e,
        ..*w
    })
}

/// The portable twin of `zraster_small_walk_v6m` (the bounding-box walk):
/// [`box_walk_setup`] then [`box_walk_rows`]. The clip must lie inside the buffers
/// (pixels outside are skipped).
pub(crate) fn small_walk_portable(
    tri: [&ScreenVertex; 3],
    clip: &Clip,
    first_row: i32,
    width: usize,
    z: &mut [u16],
    c: &mut [u16],
    color: u16,
) -> SmallDone {
    match box_walk_setup(tri, clip) {
        Ok(w) => {
            let (tested, failed) = box_walk_rows(&w, first_row, width, z, c, color);
            SmallDone::Drawn(tested, failed)
        }
        Err(done) => done,
    }
}

/// The DDA walk's set-up (the set-up of [`small_walk_less_as_u16`] before the box
/// walk, kept as the tests' reference): the rows' block and where they start, or what
/// to do instead. What `fill::small`'s ARMv6-M path works out (`by_rows`,
/// `small_steps_q` by `steps_narrow`, `small_origin`, `EdgeWalk::new_small`), each
/// edge's two divisions unsigned.
#[cfg(test)]
fn small_walk_setup(
    tri: [&ScreenVertex; 3],
    clip: &Clip,
    first_row: i32,
    width: usize,
) -> Result<(RowsWalk, RowsAt), SmallDone> {
    let p0 = tri[0];
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
    let (dy1, dy2) = (b.y() - a.y(), c.y() - a.y());
    if dy2 >= SMALL {
        return Err(SmallDone::General);
    }
    let centre = |y: i32| (y + 7) >> 4;
    let (start, end) = (centre(a.y()).max(clip.y0), centre(c.y()).min(clip.y1));
    let mid = centre(b.y()).max(start).min(end);
    let (dx1, dx2) = (b.x() - a.x(), c.x() - a.x());
    let xmin = a.x().min(b.x()).min(c.x());
    if a.x().max(b.x()).max(c.x()) - xmin >= SMALL {
        return Err(SmallDone::General);
    }
    if start >= end {
        return Err(SmallDone::Drawn(0, 0));
    }
    let px0 = xmin >> 4;
    // Every row's columns lie in px0 ..= ⌈(xmax − 8)/16⌉ (the assembly's rows loop does
    // not clip): a triangle leaving the clip's columns goes to the general path.
    let xmax = a.x().max(b.x()).max(c.x());
    if px0 < clip.x0 || (xmax + 7) >> 4 > clip.x1 {
        return Err(SmallDone::General);
    }
    let k = (px0 << 4) + 8;
    let area = dx1 * dy2 - dx2 * dy1;
    if area == 0 {
        return Err(SmallDone::Drawn(0, 0));
    }
    let m = area >> 31;
    let d = ((area ^ m) - m) as u32;
    if d >= 1 << 16 {
        return Err(SmallDone::General);
    }
    let (za, zb, zc) = (a.z(), b.z(), c.z());
    let (lo, hi) = (za.min(zb).min(zc), za.max(zb).max(zc));
    let (dz1, dz2) = (
        (zb >> 4) as i32 - (za >> 4) as i32,
        (zc >> 4) as i32 - (za >> 4) as i32,
    );
    let cross = |a: i32, b: i32, c: i32, d: i32| a.wrapping_mul(b).wrapping_sub(c.wrapping_mul(d));
    // The numerators exact in 32 bits: |dz₁|, |dz₂| ≤ ⌊(hi − lo)/16⌋ + 1 ≤
    // 2¹¹·(⌊(hi − lo)/2¹⁵⌋ + 1) and every |dx|, |dy| ≤ e = max(width, height), so a
    // bound of 2¹⁹ on the second product by e puts |a|, |b| below 2·2¹¹·2¹⁹ = 2³¹.
    let extent = (xmax - xmin).max(dy2) as u32;
    if (((hi - lo) >> 15) + 1) * extent >= 1 << 19 {
        return Err(SmallDone::General);
    }
    let (na, nb) = (cross(dz1, dy2, dz2, dy1), cross(dz2, dx1, dz1, dx2));
    let within = |n: i32| (n.wrapping_add((1 << 27) - 1) as u32) < (1 << 28) - 1;
    if !(within(na) && within(nb)) {
        return Err(SmallDone::General);
    }
    let fold = |n: i32| ((n << 4) ^ m) - m;
    let (q, r) = floor_div32_pair_small(fold(na), fold(nb), d);
    let (q, r) = (q as u32, r as u32);
    let z = p0
        .z()
        .wrapping_add(DEPTH_BIAS)
        .wrapping_add(q.wrapping_mul((k - p0.x()) as u32))
        .wrapping_add(r.wrapping_mul((16 * start + 8 - p0.y()) as u32));
    let (n0, n1) = (mid - start, end - mid);
    let long = setup_edge(a, start, (dx2, dy2), k);
    let short0 = if n0 > 0 {
        setup_edge(a, start, (dx1, dy1), k)
    } else {
        WalkEdge::default()
    };
    let short1 = if n1 > 0 {
        setup_edge(b, mid, (dx2 - dx1, dy2 - dy1), k)
    } else {
        WalkEdge::default()
    };
    let depth = [q << 4, r << 4, lo + DEPTH_BIAS, hi + DEPTH_BIAS];
    let cx = [clip.x0 - px0, clip.x1 - px0];
    let r = RowsWalk::new(depth, cx, long, [short0, short1], n1 as u32, area > 0);
    let at = RowsAt {
        row0: (start - first_row) as usize,
        width,
        px0,
        n0: n0 as u32,
        z,
    };
    Ok((r, at))
}

/// [`small_walk_setup`]'s edge from corner `v` by (`dx`, `dy` > 0) at row `py`
/// (`k` = 16·px0 + 8): `t = (16py + 8 − y)·dx + (x − k)·dy`, `x = ⌈t/16dy⌉` and
/// `err = x·16dy − t`, `step = ⌊dx/dy⌋` and `dx − step·dy`, each pair by one unsigned
/// division (⌊n/d⌋ = !⌊!n/d⌋ for n < 0).
#[cfg(test)]
fn setup_edge(v: &ScreenVertex, py: i32, (dx, dy): (i32, i32), k: i32) -> WalkEdge {
    let t = (16 * py + 8 - v.y()) * dx + (v.x() - k) * dy;
    let (d, n) = ((16 * dy) as u32, -t);
    let (x, err) = if n >= 0 {
        let q = n as u32 / d;
        ((q as i32).wrapping_neg(), n as u32 - q * d)
    } else {
        let (q, r) = (!n as u32 / d, !n as u32 % d);
        (q as i32 + 1, d - 1 - r)
    };
    let dyu = dy as u32;
    let (step, rem) = if dx >= 0 {
        ((dx as u32 / dyu) as i32, dx as u32 % dyu)
    } else {
        let (q, r) = (!dx as u32 / dyu, !dx as u32 % dyu);
        (!(q as i32), dyu - 1 - r)
    };
    WalkEdge {
        at: ((x as u32) << 16).wrapping_add(err >> 4),
        step: ((step as u32) << 16).wrapping_sub(rem),
        fix: (1 << 16) + dyu,
    }
}

/// The section of [`rows_walk_less_u16`]'s loop: RAM under `zraster_ram_code` (beside
/// the other loops' `.data.zraster`), else text; its own either way, so that a firmware
/// which never calls it (the box walk draws its small triangles) drops it.
#[cfg(all(zraster_thumb, zraster_armv6m, zraster_ram_code))]
macro_rules! rows_walk_section {
    () => {
        ".pushsection .data.zraster_rows_walk_v6m,\"awx\",%progbits"
    };
}
#[cfg(all(zraster_thumb, zraster_armv6m, not(zraster_ram_code)))]
macro_rules! rows_walk_section {
    () => {
        ".pushsection .text.zraster_rows_walk_v6m,\"ax\",%progbits"
    };
}

/// The section of `zraster_small_walk_v6m` (the set-up and rows, run once a
/// triangle): RAM under `zraster_ram_code` (as the other loops), else its own text
/// section.
#[cfg(all(zraster_thumb, zraster_armv6m, zraster_ram_code))]
macro_rules! small_walk_section {
    () => {
        ".pushsection .data.zraster,\"awx\",%progbits"
    };
}
#[cfg(all(zraster_thumb, zraster_armv6m, not(zraster_ram_code)))]
macro_rules! small_walk_section {
    () => {
        ".pushsection .text.zraster_small_walk_v6m,\"ax\",%progbits"
    };
}

#[cfg(all(zraster_thumb, zraster_armv6m))]
extern "C" {
    /// [`rows_walk_less_u16`]'s loop on ARMv6-M, a whole function in `global_asm!`
    /// (its own prologue: inline, the compiler saved every register and spilled the
    /// arguments): the rows of block `r` from the depth address `base` of the first
    /// row's local column 0, whose depth is `z`, the first half `n0` rows; returns the
    /// pixels tested. Registers: r0 the block, r1/r2 the left and right edges' `at`,
    /// r3–r7 scratch; r8 the row's depth at local column 0, r9 its depth address, r10
    /// pixels tested, r11 `sy`, r12 the pitch, lr the half's end address (rows are
    /// counted by address). Rows of one pixel inline, longer ones by a loop of one
    /// pixel a turn (r0–r2 saved meanwhile); failures counted in the block; the clip
    /// and depth clamps out of line (rows inside both are the rule).
    ///
    /// # Safety
    ///
    /// `r` points to a `RowsWalk` whose `pitch`, `delta`, `color` and `failed` are set
    /// as [`rows_walk_less_u16`] sets them, and rows `row0 .. row0 + n0 + n1` of both
    /// buffers (columns `px0 + cx0 .. px0 + cx1`) are inside them ([`RowsAt::check`]).
    fn zraster_rows_walk_v6m(r: *mut RowsWalk, z: u32, base: u32, n0: u32) -> u32;

    /// The small triangle of corners `p0`, `p1`, `p2` (vertex cache entries: the
    /// depth, then x in the low half of a word and y in the high) drawn with block `s`
    /// (every field written: the buffers' by [`SmallWalk::write_buffers`], `color` and
    /// `failed`): its bounding box walked by edge functions, as
    /// [`small_walk_portable`] does. The
    /// pixels tested (the failed ones added to `failed`), or `u32::MAX` (nothing drawn)
    /// for a triangle it leaves to the Rust path.
    ///
    /// # Safety
    ///
    /// `s` points to a valid block; every row and column of the clip lies
    /// inside both buffers; its `color` is below 2¹⁶ (bit 16 is the walk's flag to keep
    /// itself) and its `save` 0 or the address of [`KEPT_WALK_WORDS`] writable words.
    fn zraster_small_walk_v6m(
        s: *mut SmallWalk,
        p0: &CachedVertex,
        p1: &CachedVertex,
        p2: &CachedVertex,
    ) -> u32;
}

/// Words of a small triangle's walk kept for the band below (ARMv6-M): the set-up
/// (`zraster_small_walk_v6m`) keeps it in the slot its block's `save` names when the
/// triangle's rows go on past the clip, once its rows to y1 are drawn (and clears
/// `save`); `zraster_small_resume_v6m` draws the rows below from it. In order: the
/// depth and the three edge functions at the box's first column on row y1, their
/// steps a row, lo, hi − lo, the edges' steps a column, sx, 2·bx0, y1 and the end row
/// (the first row below the triangle's). Every value is the set-up's own: the rows
/// drawn from it are those the set-up would draw in a clip from y1 on.
pub(crate) const KEPT_WALK_WORDS: usize = 17;

/// `zraster_small_walk_v6m`'s reciprocal guess and first Newton step, inline (on
/// either side of its leading-zeros branch): r6 = x, below 2³²/d (d in r4, s in r5,
/// the table's 16 bits t, x = t·2^(s + 1) to start): e = 2³² − 2·dn·t (dn·t < 2³¹),
/// then x = (t·2¹⁶ + ⌊t·⌊e/2⁷⌋/2⁹⌋) >> (15 − s); t·⌊e/2⁷⌋ < 2³² (see
/// `recip_first_step`). r0 and r7 scratch.
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! bw_recip_first {
    () => {
        concat!(
            "movs r6, r4\n",
            "lsls r6, r5\n",
            "movs r0, r6\n",
            "lsrs r6, r6, #6\n",
            "lsls r6, r6, #1\n",
            "ldr r7, .Lbw_recip16\n",
            "ldrh r6, [r7, r6]\n",
            "muls r0, r6\n",
            "lsls r0, r0, #1\n",
            "rsbs r0, r0, #0\n",
            "lsrs r0, r0, #7\n",
            "muls r0, r6\n",
            "lsrs r0, r0, #9\n",
            "lsls r6, r6, #16\n",
            "adds r6, r6, r0\n",
            "movs r7, #15\n",
            "subs r7, r7, r5\n",
            "lsrs r6, r7",
        )
    };
}

/// `zraster_small_walk_v6m`'s quotient, inline (twice): r7 = ⌊r5/r4⌋ (signed r5,
/// 0 < r4 < 2¹⁶) given r6 ≤ 2³²/r4, as `num::armv6m::divrem_by_recip` of |r5| flipped
/// (⌊n/d⌋ = !⌊!n/d⌋): r7 = ⌊r6·r5/2³²⌋ from 16 × 16-bit products (three for d ≥ 2⁸, four
/// below), then fixed up by the remainder, a step a loop (at most 34 steps for d ≥ 2⁸
/// after one Newton step: see `box_walk_first_step_reciprocal_needs_few_fix_ups`; 1 for
/// d < 2⁸, x exact); r0–r3, r5 and r12 scratch.
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! bw_quot {
    (carry) => {
        concat!(
            bw_quot!(@head),
            "muls r2, r3\n",
            "adds r0, r0, r1\n",
            "bcc 1f\n",
            "movs r1, #1\n",
            "lsls r1, r1, #16\n",
            "adds r7, r7, r1\n",
            "1:\n",
            "lsls r1, r0, #16\n",
            "lsrs r0, r0, #16\n",
            "adds r2, r2, r1\n",
            "adcs r7, r0\n",
            bw_quot!(@fix),
        )
    };
    // d ≥ 2⁸: x < 2²⁴, so xh·nl < 2²⁴ and nh·xl < 2³¹ (|n| < 2³¹): their sum carries
    // not; the low product xl·nl is left out (the guess is then at most 1 lower).
    () => {
        concat!(
            bw_quot!(@head),
            "adds r0, r0, r1\n",
            "lsrs r0, r0, #16\n",
            "adds r7, r7, r0\n",
            bw_quot!(@fix),
        )
    };
    // Both forms: |n| with its sign in r12, then xh·nh, xh·nl and xl·nh.
    (@head) => {
        concat!(
            "asrs r0, r5, #31\n",
            "mov r12, r0\n",
            "eors r5, r0\n",
            "lsrs r0, r6, #16\n",
            "lsrs r1, r5, #16\n",
            "uxth r2, r6\n",
            "uxth r3, r5\n",
            "movs r7, r0\n",
            "muls r7, r1\n",
            "muls r0, r3\n",
            "muls r1, r2\n",
        )
    };
    // Both forms: the remainder, the guess raised while it is not below d, the sign
    // given back.
    (@fix) => {
        concat!(
            "movs r0, r7\n",
            "muls r0, r4\n",
            "subs r5, r5, r0\n",
            "2:\n",
            "subs r5, r5, r4\n",
            "blo 3f\n",
            "adds r7, #1\n",
            "b 2b\n",
            "3:\n",
            "mov r0, r12\n",
            "eors r7, r0",
        )
    };
}

// SAFETY (of the loop, for its callers above): rows row0 .. row0 + n0 + n1 of width
// `width` lie inside both buffers, columns px0 + cx0 .. px0 + cx1 inside 0..width,
// and every row's columns x .. x' (the left and right edges' columns, when x < x')
// inside cx0 .. cx1 (the callers' contract); both are u16 rows (2-aligned). The loop
// starts at `base`, the depth address of row row0, column px0, runs each half until
// the row address reaches base + rows · pitch (a half of 0 rows is skipped; the first
// half's end is n0 rows on, the second's n1 more), and writes only columns x .. x' of
// a row: inside both buffers (the colour at the depth address + delta). The block is read and written
// through r0 (`failed`, the edges, `n1` cleared for the second half). r4–r11 and lr
// are saved and restored as AAPCS wants; r0–r2 pushed and popped around the longer
// rows' loop.
//
// SAFETY (of the box walk, `zraster_small_walk_v6m`, for `small_walk_less_as_u16` and
// `Buffers::walk_cached`): every row and column of the clip lies inside both buffers
// (its callers' check). It reads the three corners and the block through r0–r3 and
// writes only the block's `failed`, its own 72-byte frame and pixels, and where the
// block's `save` names a slot (the bands' loop, a slot of the caller's scratch), for a
// triangle whose rows go past clip.y1: the slot's 17 words, the block's `color` (bit
// 16 set: only its low half is ever stored as a pixel) and `save` (cleared). Its rows are
// start .. end with clip.y0 ≤ start < end ≤ clip.y1 (none: it returns first), at depth
// addresses zaddr + (row − first_row)·pitch + 2·column; it goes on only when xmin >> 4
// ≥ clip.x0 and ⌈(xmax − 8)/16⌉ ≤ clip.x1. A pixel is read and written only where all
// three edge functions are ≥ 0: the left side's (growing to the right) by the walk to
// the span's start, which moves right only while one is negative, the right side's
// (falling to the right) by the test before each pixel. Such a pixel is covered, its
// centre inside the triangle, so its column lies in ⌈(xmin − 8)/16⌉ .. ⌈(xmax − 8)/16⌉,
// inside the clip's. The walk to the span's start ends by column ⌈(xmax − 8)/16⌉: the
// left side's functions are ≥ 0 right of the triangle's left boundary on the row, a
// point of the triangle (x ≤ xmax). The division's divisor is |area| > 0. It saves
// r4–r11 and lr as AAPCS wants. A row's state lies above sp only between its POP and
// PUSH, while it is dead (an exception's frame may overwrite it).
#[cfg(all(zraster_thumb, zraster_armv6m))]
core::arch::global_asm!(
    rows_walk_section!(),
    ".balign 4",
    ".global zraster_rows_walk_v6m",
    ".hidden zraster_rows_walk_v6m",
    ".type zraster_rows_walk_v6m, %function",
    ".thumb_func",
    "zraster_rows_walk_v6m:",
    v6m_save!(),
    "mov r8, r1",
    "mov r9, r2",
    "ldr r6, [r0, #36]",
    "mov r12, r6",
    "muls r6, r3",
    "adds r6, r6, r2",
    "mov lr, r6",
    "ldr r6, [r0, #32]",
    "mov r11, r6",
    "movs r6, #0",
    "mov r10, r6",
    // The long and short edges to the left and right: swapped when side is 1.
    "ldr r4, [r0, #44]",
    "cmp r4, #0",
    "beq 7f",
    "movs r1, #48",
    "adds r1, r1, r0",
    "ldm r1!, {{r2, r3, r4}}",
    "ldm r1!, {{r5, r6, r7}}",
    "subs r1, #24",
    "stm r1!, {{r5, r6, r7}}",
    "stm r1!, {{r2, r3, r4}}",
    "7:",
    "ldr r1, [r0, #48]",
    "ldr r2, [r0, #60]",
    "cmp r9, lr",
    "beq 8f",
    // A row: its columns (the edges' upper halves), inside the clip's (the callers'
    // contract: no clip test here); r6 its first column, r5 its length.
    "1:",
    "asrs r6, r1, #16",
    "asrs r7, r2, #16",
    "subs r5, r7, r6",
    "ble 5f",
    "add r10, r5",
    // Its depth at the first column (sx, lo and hi − lo by one LDM), clamped to
    // lo..=hi out of line (when depth − lo > hi − lo, unsigned), and that column's
    // depth address: r3 the depth, r4 the address.
    "mov r7, r0",
    "ldm r7, {{r3, r4, r7}}",
    "muls r3, r6",
    "add r3, r8",
    "subs r4, r3, r4",
    "cmp r4, r7",
    "bhi 16f",
    "17:",
    "lsls r4, r6, #1",
    "add r4, r9",
    "cmp r5, #1",
    "bne 3f",
    "lsrs r6, r3, #16",
    "ldrh r7, [r4]",
    "cmp r6, r7",
    "bhs 6f",
    "strh r6, [r4]",
    "ldr r6, [r0, #12]",
    "ldr r7, [r0, #16]",
    "strh r6, [r4, r7]",
    // The next row: both edges stepped (a borrow out of the lower half, bit 15, is
    // fixed up), then the depth and the address.
    "5:",
    "ldr r3, [r0, #56]",
    "adds r1, r1, r3",
    "lsls r3, r1, #16",
    "bpl 21f",
    "ldr r3, [r0, #52]",
    "adds r1, r1, r3",
    "21:",
    "ldr r3, [r0, #68]",
    "adds r2, r2, r3",
    "lsls r3, r2, #16",
    "bpl 22f",
    "ldr r3, [r0, #64]",
    "adds r2, r2, r3",
    "22:",
    "add r8, r11",
    "add r9, r12",
    "cmp r9, lr",
    "bne 1b",
    // The second half, its count cleared so that it runs once: the short edge
    // replaced, the long one carried on.
    "8:",
    "ldr r5, [r0, #40]",
    "cmp r5, #0",
    "beq 9f",
    "movs r6, #0",
    "str r6, [r0, #40]",
    "mov r6, r12",
    "muls r6, r5",
    "add r6, r9",
    "mov lr, r6",
    "movs r3, #72",
    "adds r3, r3, r0",
    "ldr r4, [r0, #44]",
    "cmp r4, #0",
    "bne 13f",
    "ldm r3!, {{r2, r4, r5}}",
    "str r4, [r0, #64]",
    "str r5, [r0, #68]",
    "b 1b",
    "13:",
    "ldm r3!, {{r1, r4, r5}}",
    "str r4, [r0, #52]",
    "str r5, [r0, #56]",
    "b 1b",
    // The first depth clamped: below lo to lo, else to lo + (hi − lo).
    "16:",
    "ldr r4, [r0, #4]",
    "cmp r3, r4",
    "blo 18f",
    "adds r4, r4, r7",
    "18:",
    "mov r3, r4",
    "b 17b",
    // A failed pixel of a one-pixel row.
    "6:",
    "ldr r6, [r0, #28]",
    "adds r6, #1",
    "str r6, [r0, #28]",
    "b 5b",
    // Two pixels or more: r4 the address, r3 the depth, r5 the count.
    "3:",
    "push {{r0, r1, r2}}",
    "ldr r1, [r0]",
    "ldr r2, [r0, #12]",
    "ldr r7, [r0, #16]",
    "31:",
    "lsrs r6, r3, #16",
    "ldrh r0, [r4]",
    "cmp r6, r0",
    "bhs 33f",
    "strh r6, [r4]",
    "strh r2, [r4, r7]",
    "32:",
    "adds r3, r3, r1",
    "adds r4, #2",
    "subs r5, #1",
    "bne 31b",
    "pop {{r0, r1, r2}}",
    "b 5b",
    "33:",
    "ldr r6, [sp]",
    "ldr r0, [r6, #28]",
    "adds r0, #1",
    "str r0, [r6, #28]",
    "b 32b",
    "9:",
    "mov r0, r10",
    v6m_return!(),
    ".size zraster_rows_walk_v6m, . - zraster_rows_walk_v6m",
    ".popsection",
    small_walk_section!(),
    // The bounding-box walk of a small triangle (see `zraster_small_walk_v6m`, and its
    // twin `box_walk_setup` and `box_walk_rows`). Frame: 72 bytes below the saved
    // registers. In the rows: [sp] the row's depth at the box's first column and its
    // three edge functions there (long, e01, e20), +16 their steps a row, +36 the
    // rows' end address, +40 lo (biased), +44 hi − lo, +48 the colour, +52 its offset
    // from the depth, +56 the block, +60 the pitch; r8–r10 the edges' steps a column,
    // r11 sx, r12 the row's depth address at the box's first column, lr the bytes
    // tested. In the set-up the same slots hold: [sp] the corners (the middle one by y
    // first) then the depth steps' numerators, +12 X = cx − x0, +16 dx1, dx2, dy1, dy2
    // (from the middle corner; negated where the area was positive), +32 the first
    // row, +36 the rows, +48 |area|, +52 Y = cy − y0, +60 the first corner given then
    // sy, +64 the height then max(width, height), +68 cx (16·bx0 + 8, bx0 the box's
    // first column).
    ".balign 4",
    ".global zraster_small_walk_v6m",
    ".hidden zraster_small_walk_v6m",
    ".type zraster_small_walk_v6m, %function",
    ".thumb_func",
    "zraster_small_walk_v6m:",
    v6m_save!(),
    "sub sp, #72",
    "str r0, [sp, #56]",
    "str r1, [sp, #60]",
    // The corners' x and y words in r4–r6 (y in the upper half); the middle corner by
    // y first (a rotation, which keeps the orientation), the words compared whole as
    // `box_walk_setup`'s `middle` (ties by x).
    "ldr r4, [r1, #4]",
    "ldr r5, [r2, #4]",
    "ldr r6, [r3, #4]",
    "cmp r4, r5",
    "bgt 1f",
    "cmp r4, r6",
    "bge 4f",
    "cmp r5, r6",
    "ble 3f",
    "b 2f",
    "1:",
    "cmp r4, r6",
    "ble 4f",
    "cmp r5, r6",
    "bge 3f",
    // The third the middle one ([p2, p0, p1]: the words w0, w1, w2 in r6, r4, r5).
    // Each case stores the corners in that order and leaves x0 in r1, y0 in r4, dx1,
    // dx2, dy1, dy2 in r2, r3, r5, r6.
    "2:",
    "str r3, [sp]",
    "str r1, [sp, #4]",
    "str r2, [sp, #8]",
    "sxth r1, r6",
    "sxth r2, r4",
    "subs r2, r2, r1",
    "sxth r3, r5",
    "subs r3, r3, r1",
    "asrs r7, r6, #16",
    "asrs r6, r5, #16",
    "subs r6, r6, r7",
    "asrs r5, r4, #16",
    "subs r5, r5, r7",
    "movs r4, r7",
    "b 5f",
    // The second ([p1, p2, p0]: the words in r5, r6, r4).
    "3:",
    "str r2, [sp]",
    "str r3, [sp, #4]",
    "str r1, [sp, #8]",
    "sxth r1, r5",
    "sxth r2, r6",
    "subs r2, r2, r1",
    "sxth r3, r4",
    "subs r3, r3, r1",
    "asrs r7, r5, #16",
    "asrs r5, r6, #16",
    "subs r5, r5, r7",
    "asrs r6, r4, #16",
    "subs r6, r6, r7",
    "movs r4, r7",
    "b 5f",
    // The first.
    "4:",
    "mov r7, sp",
    "stm r7!, {{r1, r2, r3}}",
    "sxth r1, r4",
    "sxth r2, r5",
    "subs r2, r2, r1",
    "sxth r3, r6",
    "subs r3, r3, r1",
    "asrs r4, r4, #16",
    "asrs r5, r5, #16",
    "subs r5, r5, r4",
    "asrs r6, r6, #16",
    "subs r6, r6, r4",
    // The deltas to the frame.
    "5:",
    "add r7, sp, #16",
    "stm r7!, {{r2, r3, r5, r6}}",
    // The height |dy2 − dy1| (the middle corner lies between) below SMALL, else the
    // general path; the least y in r5, the greatest in r7.
    "subs r7, r6, r5",
    "bge 5f",
    "rsbs r7, r7, #0",
    "movs r5, r6",
    "5:",
    "lsrs r6, r7, #13",
    "bne .Lbw_refuse",
    "str r7, [sp, #64]",
    "adds r5, r5, r4",
    "adds r7, r7, r5",
    // Rows whose centres may be covered, inside the clip: start in r5, end in r7;
    // Y = 16·start + 8 − y0 at [sp, #52], the rows in r7 and at [sp, #36].
    "adds r5, #7",
    "asrs r5, r5, #4",
    "adds r7, #7",
    "asrs r7, r7, #4",
    "ldr r6, [r0, #8]",
    "cmp r5, r6",
    "bge 6f",
    "mov r5, r6",
    "6:",
    "ldr r6, [r0, #20]",
    "cmp r7, r6",
    "ble 7f",
    // Rows past the clip's last: with a slot to keep the walk in (`save`), the end row
    // into it and the colour flagged (bit 16), so that the rows' end saves there.
    "mov r12, r6",
    "ldr r6, [r0, #36]",
    "cmp r6, #0",
    "beq 8f",
    "str r7, [r6, #64]",
    "ldr r7, [r0, #12]",
    "movs r6, #1",
    "lsls r6, r6, #16",
    "orrs r7, r6",
    "str r7, [r0, #12]",
    "8:",
    "mov r7, r12",
    "7:",
    "str r5, [sp, #32]",
    "subs r7, r7, r5",
    "str r7, [sp, #36]",
    "lsls r5, r5, #4",
    "adds r5, #8",
    "subs r4, r5, r4",
    "str r4, [sp, #52]",
    // The least and greatest of 0, dx1 and dx2 in r5 and r6: the width below SMALL,
    // else the general path; no rows, nothing.
    "movs r5, #0",
    "movs r6, #0",
    "cmp r2, #0",
    "bge 1f",
    "movs r5, r2",
    "b 2f",
    "1:",
    "movs r6, r2",
    "2:",
    "cmp r3, r5",
    "bge 3f",
    "movs r5, r3",
    "b 4f",
    "3:",
    "cmp r3, r6",
    "ble 4f",
    "movs r6, r3",
    "4:",
    "subs r6, r6, r5",
    "lsrs r4, r6, #13",
    "bne .Lbw_refuse",
    "cmp r7, #0",
    "ble .Lbw_empty",
    // The larger extent, max(width, height), at [sp, #64] (for the depth's bound).
    "ldr r7, [sp, #64]",
    "cmp r6, r7",
    "bls 5f",
    "str r6, [sp, #64]",
    "5:",
    // Columns xmin >> 4 ..= ⌈(xmax − 8)/16⌉ inside the clip's, else the general path
    // (the walk does not clip its columns).
    "adds r5, r5, r1",
    "adds r6, r6, r5",
    "asrs r7, r5, #4",
    "ldr r3, [r0, #24]",
    "cmp r7, r3",
    "blt .Lbw_refuse",
    "adds r6, #7",
    "asrs r6, r6, #4",
    "ldr r3, [r0, #32]",
    "cmp r6, r3",
    "bgt .Lbw_refuse",
    // The box's first column bx0 = ⌈(xmin − 8)/16⌉: cx = 16·bx0 + 8, X = cx − x0.
    "adds r5, #7",
    "asrs r5, r5, #4",
    "lsls r5, r5, #4",
    "adds r5, #8",
    "str r5, [sp, #68]",
    "subs r1, r5, r1",
    "str r1, [sp, #12]",
    // The area (none: nothing to draw); positive, the deltas negated (the area then
    // negative: inside, every edge function ≥ 0); |area| below 2¹⁶, else the general
    // path.
    "add r7, sp, #16",
    "ldm r7!, {{r2, r3, r5, r6}}",
    "movs r7, r2",
    "muls r7, r6",
    "movs r0, r3",
    "muls r0, r5",
    "subs r7, r7, r0",
    "beq .Lbw_empty",
    "bmi 1f",
    "rsbs r2, r2, #0",
    "rsbs r3, r3, #0",
    "rsbs r5, r5, #0",
    "rsbs r6, r6, #0",
    "add r0, sp, #16",
    "stm r0!, {{r2, r3, r5, r6}}",
    "rsbs r7, r7, #0",
    "1:",
    "rsbs r7, r7, #0",
    "lsrs r0, r7, #16",
    "bne .Lbw_refuse",
    "str r7, [sp, #48]",
    "b .Lbw_depths",
    // Nothing to draw, or a triangle for the Rust path (here, within the conditional
    // branches' reach).
    ".Lbw_empty:",
    "movs r0, #0",
    "b .Lbw_out",
    ".Lbw_refuse:",
    "movs r0, #0",
    "mvns r0, r0",
    ".Lbw_out:",
    "add sp, #72",
    v6m_return!(),
    // The depths' range: lo (biased) at [sp, #40] and hi − lo at [sp, #44].
    ".Lbw_depths:",
    "mov r7, sp",
    "ldm r7!, {{r1, r2, r3}}",
    "ldr r4, [r1]",
    "ldr r5, [r2]",
    "ldr r6, [r3]",
    // lo in r7, hi in r1: the first two ordered, then the third below lo, else
    // above hi.
    "mov r7, r4",
    "mov r1, r5",
    "cmp r4, r5",
    "bls 1f",
    "mov r7, r5",
    "mov r1, r4",
    "1:",
    "cmp r6, r7",
    "blo 2f",
    "cmp r6, r1",
    "bls 3f",
    "mov r1, r6",
    "b 3f",
    "2:",
    "mov r7, r6",
    "3:",
    "subs r1, r1, r7",
    "str r1, [sp, #44]",
    "ldr r2, .Lbw_bias",
    "adds r7, r7, r2",
    "str r7, [sp, #40]",
    // The numerators exact in 32 bits: (⌊(hi − lo)/2¹⁵⌋ + 1)·max(width, height) below
    // 2¹⁹, else the general path (see `box_walk_setup`).
    "lsrs r1, r1, #15",
    "adds r1, #1",
    "ldr r3, [sp, #64]",
    "muls r1, r3",
    "lsrs r1, r1, #19",
    "bne .Lbw_refuse",
    // dz1 in r6, dz2 in r7 (depths over 16).
    "lsrs r4, r4, #4",
    "lsrs r6, r6, #4",
    "subs r7, r6, r4",
    "lsrs r6, r5, #4",
    "subs r6, r6, r4",
    // The numerators a = dz1·dy2 − dz2·dy1 (r4) and b = dz2·dx1 − dz1·dx2 (r2), modulo
    // 2³², inside ±(2²⁷ − 1).
    "add r5, sp, #16",
    "ldm r5, {{r2, r3, r4, r5}}",
    "muls r2, r7",
    "muls r3, r6",
    "subs r2, r2, r3",
    "muls r5, r6",
    "muls r4, r7",
    "subs r4, r5, r4",
    "ldr r3, .Lbw_within",
    "adds r6, r4, r3",
    "adds r7, r2, r3",
    "ldr r3, .Lbw_range",
    "cmp r6, r3",
    "bhs .Lbw_refuse",
    "cmp r7, r3",
    "bhs .Lbw_refuse",
    // The steps ⌊−16a/|area|⌋, ⌊−16b/|area|⌋ (the area is negative), as
    // `num::floor_div32_pair_small`: the numerators at [sp] and [sp, #4], then
    // x ≤ 2³²/d in r6 (d = |area| in r4) as `num::armv6m::recip32_small`: d normalised
    // to [2¹⁵, 2¹⁶) by s (its leading zeros, from a byte table), a guess from the
    // reciprocal table, one Newton step (a few fix-ups a quotient are cheaper than the
    // second step's 11 instructions), two for d < 2⁸ (then exact).
    "lsls r0, r4, #4",
    "rsbs r0, r0, #0",
    "str r0, [sp]",
    "lsls r1, r2, #4",
    "rsbs r1, r1, #0",
    "str r1, [sp, #4]",
    "ldr r4, [sp, #48]",
    "ldr r7, .Lbw_lz8",
    "lsrs r5, r4, #8",
    "beq 1f",
    "ldrb r5, [r7, r5]",
    bw_recip_first!(),
    "ldr r5, [sp]",
    bw_quot!(),
    "str r7, [sp]",
    "ldr r5, [sp, #4]",
    bw_quot!(),
    "b 4f",
    // d < 2⁸ only: the first step leaves up to 2¹³ to fix up in a quotient, so a second
    // step makes x exact (e under 2¹⁷, two products of 32 bits, `recip32_small`).
    "1:",
    "ldrb r5, [r7, r4]",
    "adds r5, #8",
    bw_recip_first!(),
    "movs r5, r4",
    "muls r5, r6",
    "rsbs r5, r5, #0",
    "lsrs r0, r6, #16",
    "muls r0, r5",
    "uxth r1, r6",
    "muls r1, r5",
    "lsrs r1, r1, #16",
    "adds r0, r0, r1",
    "lsrs r0, r0, #16",
    "adds r6, r6, r0",
    "ldr r5, [sp]",
    bw_quot!(carry),
    "str r7, [sp]",
    "ldr r5, [sp, #4]",
    bw_quot!(carry),
    "4:",
    // q in r0, r in r1: sx = 16q in r11, sy = 16r at [sp, #60] (after the first corner
    // given is read from there).
    "movs r1, r7",
    "ldr r0, [sp]",
    "lsls r2, r0, #4",
    "mov r11, r2",
    "lsls r3, r1, #4",
    "ldr r2, [sp, #60]",
    "str r3, [sp, #60]",
    // The first row's depth at the box's first column, from the first corner given:
    // z + DEPTH_BIAS + q·(cx − x) + r·(cy − y), at [sp] (the row state's first word).
    "ldm r2!, {{r4, r6}}",
    "ldr r7, [sp, #68]",
    "sxth r5, r6",
    "subs r5, r7, r5",
    "muls r0, r5",
    "asrs r6, r6, #16",
    "ldr r5, [sp, #32]",
    "lsls r5, r5, #4",
    "adds r5, #8",
    "subs r6, r5, r6",
    "muls r1, r6",
    "adds r0, r0, r1",
    "adds r0, r0, r4",
    "ldr r4, .Lbw_bias",
    "adds r0, r0, r4",
    "str r0, [sp]",
    // The edge functions at the first pixel centre (cx, cy), from the middle corner:
    // e01 = X·dy1 − Y·dx1 (corner 0 to 1) in r0, e20 = Y·dx2 − X·dy2 (2 to 0) in r7 and
    // the long edge's e12 = |area| − e01 − e20 in r1.
    "ldr r4, [sp, #52]",
    "add r7, sp, #12",
    "ldm r7!, {{r1, r2, r3, r5, r6}}",
    "movs r0, r5",
    "muls r0, r1",
    "movs r7, r2",
    "muls r7, r4",
    "subs r0, r0, r7",
    "movs r7, r3",
    "muls r7, r4",
    "muls r1, r6",
    "subs r7, r7, r1",
    "ldr r1, [sp, #48]",
    "subs r1, r1, r0",
    "subs r1, r1, r7",
    // Their steps a column, 16·dy (dy from the edge's start to its end), in r9, r10
    // and r8; each function one less where dy < 0 (an edge running up, on the right:
    // a centre on it is not covered).
    "asrs r4, r5, #31",
    "adds r0, r0, r4",
    "lsls r4, r5, #4",
    "mov r9, r4",
    "lsls r4, r6, #4",
    "rsbs r4, r4, #0",
    "mov r10, r4",
    "asrs r4, r4, #31",
    "adds r7, r7, r4",
    "subs r4, r6, r5",
    "lsls r4, r4, #4",
    "mov r8, r4",
    "asrs r4, r4, #31",
    "adds r1, r1, r4",
    // The first row's state: the depth, the long edge's, e01, e20; then the steps a
    // row: sy, −16·dx of each.
    "movs r5, r1",
    "movs r6, r0",
    "add r0, sp, #4",
    "stm r0!, {{r5, r6, r7}}",
    "subs r5, r2, r3",
    "lsls r5, r5, #4",
    "lsls r6, r2, #4",
    "rsbs r6, r6, #0",
    "lsls r7, r3, #4",
    "ldr r4, [sp, #60]",
    "stm r0!, {{r4, r5, r6, r7}}",
    // The first row's depth address at column bx0: base + start·pitch + 2·bx0
    // (2·bx0 = cx/8 − 1); the pitch at [sp, #60], nothing tested yet, the colour and
    // its offset.
    "ldr r0, [sp, #56]",
    "ldr r1, [sp, #32]",
    "ldr r3, [r0, #4]",
    "str r3, [sp, #60]",
    "muls r1, r3",
    "ldr r2, [r0]",
    "adds r1, r1, r2",
    "ldr r2, [sp, #68]",
    "asrs r2, r2, #3",
    "subs r2, #1",
    "adds r1, r1, r2",
    "mov r12, r1",
    "ldr r2, [sp, #36]",
    "muls r2, r3",
    "adds r2, r2, r1",
    "str r2, [sp, #36]",
    "ldr r2, [r0, #12]",
    "str r2, [sp, #48]",
    "lsrs r2, r2, #16",
    "mov lr, r2",
    "ldr r2, [r0, #16]",
    "str r2, [sp, #52]",
    "mov r2, r8",
    "cmp r2, #0",
    "blt .Lbw_rowR",
    // The rows with the long edge on the left. A row: its state and the next one's
    // by POP and PUSH (r0 the depth, r1 the long edge, r2 and r3 the others; r5 the
    // depth address); from the box's first column while the long edge is negative,
    // then pixels while the other two are ≥ 0 (the colour in r1, its offset in r7).
    ".Lbw_rowL:",
    "pop {{r0, r1, r2, r3}}",
    "mov r7, sp",
    "ldm r7, {{r4, r5, r6, r7}}",
    "adds r4, r4, r0",
    "adds r5, r5, r1",
    "adds r6, r6, r2",
    "adds r7, r7, r3",
    "push {{r4, r5, r6, r7}}",
    "mov r5, r12",
    "ldr r4, [sp, #60]",
    "add r12, r4",
    "cmp r1, #0",
    "bge 12f",
    "11:",
    "add r0, r11",
    "adds r5, #2",
    "add r1, r8",
    "add r2, r9",
    "add r3, r10",
    "cmp r1, #0",
    "blt 11b",
    "12:",
    "movs r4, r2",
    "orrs r4, r3",
    "bmi 16f",
    // The span's first pixel: where it starts, its depth clamped to lo..=hi (out of
    // line).
    "rsbs r4, r5, #0",
    "add lr, r4",
    "ldr r1, [sp, #48]",
    "ldr r7, [sp, #52]",
    "ldr r4, [sp, #40]",
    "subs r6, r0, r4",
    "ldr r4, [sp, #44]",
    "cmp r6, r4",
    "bhi 17f",
    "13:",
    "lsrs r6, r0, #16",
    "ldrh r4, [r5]",
    "cmp r6, r4",
    "bhs 18f",
    "strh r6, [r5]",
    "strh r1, [r5, r7]",
    "14:",
    "add r0, r11",
    "adds r5, #2",
    "add r2, r9",
    "add r3, r10",
    "movs r4, r2",
    "orrs r4, r3",
    "bpl 13b",
    "add lr, r5",
    "16:",
    "ldr r4, [sp, #36]",
    "cmp r4, r12",
    "bne .Lbw_rowL",
    "b .Lbw_done",
    // The first depth clamped: below lo to lo, else to lo + (hi − lo).
    "17:",
    "ldr r6, [sp, #40]",
    "cmp r0, r6",
    "blo 15f",
    "adds r6, r6, r4",
    "15:",
    "mov r0, r6",
    "b 13b",
    // A failed pixel.
    "18:",
    "ldr r6, [sp, #56]",
    "ldr r4, [r6, #28]",
    "adds r4, #1",
    "str r4, [r6, #28]",
    "b 14b",
    // The rows with the long edge on the right: from the box's first column while
    // one of the other two is negative, then pixels while the long edge is ≥ 0.
    ".Lbw_rowR:",
    "pop {{r0, r1, r2, r3}}",
    "mov r7, sp",
    "ldm r7, {{r4, r5, r6, r7}}",
    "adds r4, r4, r0",
    "adds r5, r5, r1",
    "adds r6, r6, r2",
    "adds r7, r7, r3",
    "push {{r4, r5, r6, r7}}",
    "mov r5, r12",
    "ldr r4, [sp, #60]",
    "add r12, r4",
    // (One of the two at a time: both grow to the right, so the first stays ≥ 0
    // while the walk waits for the second.)
    "cmp r2, #0",
    "bge 20f",
    "21:",
    "add r0, r11",
    "adds r5, #2",
    "add r1, r8",
    "add r2, r9",
    "add r3, r10",
    "cmp r2, #0",
    "blt 21b",
    "20:",
    "cmp r3, #0",
    "bge 22f",
    "19:",
    "add r0, r11",
    "adds r5, #2",
    "add r1, r8",
    "add r2, r9",
    "add r3, r10",
    "cmp r3, #0",
    "blt 19b",
    "22:",
    "cmp r1, #0",
    "blt 26f",
    "rsbs r4, r5, #0",
    "add lr, r4",
    "ldr r2, [sp, #48]",
    "ldr r7, [sp, #52]",
    "ldr r4, [sp, #40]",
    "subs r6, r0, r4",
    "ldr r4, [sp, #44]",
    "cmp r6, r4",
    "bhi 27f",
    "23:",
    "lsrs r6, r0, #16",
    "ldrh r4, [r5]",
    "cmp r6, r4",
    "bhs 28f",
    "strh r6, [r5]",
    "strh r2, [r5, r7]",
    "24:",
    "add r0, r11",
    "adds r5, #2",
    "add r1, r8",
    "cmp r1, #0",
    "bge 23b",
    "add lr, r5",
    "26:",
    "ldr r4, [sp, #36]",
    "cmp r4, r12",
    "bne .Lbw_rowR",
    // Done: the pixels tested (bytes over 2; bit 0 the flag to keep the walk).
    ".Lbw_done:",
    "mov r0, lr",
    "lsrs r0, r0, #1",
    "bcs .Lbw_save",
    ".Lbw_ret:",
    "add sp, #72",
    v6m_return!(),
    // The walk kept in the slot (`KEPT_WALK_WORDS`), the slot cleared in the block (the
    // bands' loop reads that it saved): the row state at y1 where the rows stopped, its
    // steps, lo, hi − lo, the steps a column, sx, 2·bx0 and y1 (the end row is there).
    ".Lbw_save:",
    "ldr r1, [sp, #56]",
    "ldr r2, [r1, #36]",
    "movs r3, #0",
    "str r3, [r1, #36]",
    "mov r7, sp",
    "ldm r7!, {{r3, r4, r5, r6}}",
    "stm r2!, {{r3, r4, r5, r6}}",
    "ldm r7!, {{r3, r4, r5, r6}}",
    "stm r2!, {{r3, r4, r5, r6}}",
    "ldr r3, [sp, #40]",
    "ldr r4, [sp, #44]",
    "mov r5, r8",
    "mov r6, r9",
    "stm r2!, {{r3, r4, r5, r6}}",
    "mov r3, r10",
    "mov r4, r11",
    "ldr r5, [sp, #68]",
    "asrs r5, r5, #3",
    "subs r5, #1",
    "ldr r6, [r1, #20]",
    "stm r2!, {{r3, r4, r5, r6}}",
    "b .Lbw_ret",
    "27:",
    "ldr r6, [sp, #40]",
    "cmp r0, r6",
    "blo 25f",
    "adds r6, r6, r4",
    "25:",
    "mov r0, r6",
    "b 23b",
    "28:",
    "ldr r6, [sp, #56]",
    "ldr r4, [r6, #28]",
    "adds r4, #1",
    "str r4, [r6, #28]",
    "b 24b",
    ".balign 4",
    ".Lbw_lz8:",
    ".word {lz8}",
    ".Lbw_recip16:",
    ".word {recip16} - 1024",
    ".Lbw_bias:",
    ".word 32768",
    ".Lbw_within:",
    ".word 0x07ffffff",
    ".Lbw_range:",
    ".word 0x0fffffff",
    ".size zraster_small_walk_v6m, . - zraster_small_walk_v6m",
    // `zraster_small_resume_v6m(s, slot)`, called by the bands' loop (`faces_v6m`): the
    // rows of a walk `.Lbw_save` kept in `slot` ([`KEPT_WALK_WORDS`]) drawn with block
    // `s` as the set-up would draw that triangle in its clip: from y0, the row it was
    // kept at (else u32::MAX, nothing drawn, for the set-up to do), to the end row or
    // y1. Returns the pixels tested (the failed ones added to `failed`).
    // SAFETY: as the walk's, `slot` holding what the walk kept there from a block of
    // the same clip columns (x0, x1): every value as the set-up makes it, so the rows
    // are the set-up's (its argument above), those of rows y0 .. min(end, y1) of the
    // triangle's own (y0 the kept row, below the triangle's first).
    ".balign 2",
    ".global zraster_small_resume_v6m",
    ".hidden zraster_small_resume_v6m",
    ".type zraster_small_resume_v6m, %function",
    ".thumb_func",
    "zraster_small_resume_v6m:",
    v6m_save!(),
    "sub sp, #72",
    "str r0, [sp, #56]",
    // Its rows from y0, the row it was kept at (else the set-up's: never for bands one
    // below the other, always for a slot marked empty by a kept row of i32::MAX), to
    // the end row or y1; none, nothing.
    "ldr r2, [r0, #8]",
    "ldr r3, [r1, #60]",
    "cmp r2, r3",
    "beq 1f",
    "b .Lbw_refuse",
    "1:",
    "ldr r4, [r1, #64]",
    "ldr r5, [r0, #20]",
    "cmp r4, r5",
    "ble 1f",
    "mov r4, r5",
    "1:",
    "subs r4, r4, r2",
    "bgt 1f",
    "b .Lbw_empty",
    "1:",
    // The first row's depth address at column bx0 (base + y0·pitch + 2·bx0) in r12,
    // the rows' end address, the pitch, the colour and its offset; nothing tested.
    "ldr r5, [r0, #4]",
    "str r5, [sp, #60]",
    "muls r2, r5",
    "ldr r6, [r0]",
    "adds r2, r2, r6",
    "ldr r6, [r1, #56]",
    "adds r2, r2, r6",
    "mov r12, r2",
    "muls r4, r5",
    "adds r4, r4, r2",
    "str r4, [sp, #36]",
    "ldr r4, [r0, #12]",
    "str r4, [sp, #48]",
    "ldr r4, [r0, #16]",
    "str r4, [sp, #52]",
    "movs r4, #0",
    "mov lr, r4",
    // lo and hi − lo; the steps a column and sx in r8–r11.
    "ldr r4, [r1, #32]",
    "str r4, [sp, #40]",
    "ldr r4, [r1, #36]",
    "str r4, [sp, #44]",
    "movs r0, r1",
    "adds r0, #40",
    "ldm r0!, {{r4, r5, r6, r7}}",
    "mov r8, r4",
    "mov r9, r5",
    "mov r10, r6",
    "mov r11, r7",
    // The row state, then its steps.
    "ldm r1!, {{r4, r5, r6, r7}}",
    "mov r0, sp",
    "stm r0!, {{r4, r5, r6, r7}}",
    "ldm r1!, {{r4, r5, r6, r7}}",
    "stm r0!, {{r4, r5, r6, r7}}",
    "mov r2, r8",
    "cmp r2, #0",
    "blt 4f",
    "b .Lbw_rowL",
    "4:",
    "b .Lbw_rowR",
    ".size zraster_small_resume_v6m, . - zraster_small_resume_v6m",
    ".popsection",
    lz8 = sym crate::num::armv6m::LEADING_ZEROS8,
    recip16 = sym crate::num::armv6m::RECIP16,
);

/// A random edge of a small triangle (local coordinates, extents below 32 pixels) at
/// one of its rows, as [`EdgeWalk`](crate::raster::EdgeWalk) sets it up.
fn check_edge(seed: &mut u32) -> WalkEdge {
    loop {
        let a = ((next(seed) % 512) as i32, (next(seed) % 512) as i32);
        let b = (
            (next(seed) % 512) as i32,
            a.1 + 1 + (next(seed) % 480) as i32,
        );
        // The rows whose centres lie in [a.1, b.1).
        let (r0, r1) = ((a.1 + 7) >> 4, (b.1 + 7) >> 4);
        if r0 < r1 {
            let py = r0 + (next(seed) % (r1 - r0) as u32) as i32;
            return WalkEdge::from_parts(crate::raster::EdgeWalk::new_small(a, b, py).parts());
        }
    }
}

/// On-target check of the ARMv6-M rows assembly against its twin, for the bench
/// firmware (`rows::check_cases`): random edges, depths, clip columns, both halves,
/// rows from empty to 40 pixels, through `rows_walk_less_as_u16` and
/// `rows_walk_less_portable`. Returns the number of cases that differ (where there is
/// no assembly, the twin against itself). Out of line: its frame is not the bench's.
#[inline(never)]
pub fn check_rows_walk_kernel(buf: &mut [u16]) -> usize {
    let make = |seed: &mut u32, case| {
        let (left, right, short1) = (check_edge(seed), check_edge(seed), check_edge(seed));
        let place = check_place(seed, case, CHECK_W);
        let mid_right = next(seed).is_multiple_of(2);
        let (depth, cx, n1) = (place.depth, place.cx, place.n1);
        let r = RowsWalk::new(depth, cx, left, [right, short1], n1, mid_right);
        (r, place)
    };
    let kernel = rows_walk_less_as_u16::<u16>;
    let bad = check_cases(buf, 0x1357_9bdf, make, kernel, rows_walk_less_portable);
    let Some(buf) = buf.get_mut(..4 * CHECK_W * 16) else {
        return usize::MAX;
    };
    let (mine, twin) = buf.split_at_mut(2 * CHECK_W * 16);
    bad.saturating_add(check_small_walk(&mut 0x2468_ace1, mine, twin))
}

/// The set-up's cases of [`check_rows_walk_kernel`]: random triangles (from a pixel to
/// the buffer across, some 512 pixels or more, flat, of steep depth; clips inside the
/// buffers, some narrower) through `small_walk_less_as_u16` and `small_walk_portable`
/// into copies of the same buffers (a depth and a colour buffer of 48 × 16 each in
/// `mine` and `twin`), compared. Returns the number of cases that differ.
fn check_small_walk(seed: &mut u32, mine: &mut [u16], twin: &mut [u16]) -> usize {
    const W: usize = CHECK_W;
    const H: usize = 16;
    let (z1, c1) = mine.split_at_mut(W * H);
    let (z2, c2) = twin.split_at_mut(W * H);
    let mut bad = 0;
    for case in 0..3000u32 {
        for (d, c) in z1.iter_mut().zip(c1.iter_mut()) {
            (*d, *c) = (next(seed) as u16 | 0x8000 >> (case % 3), next(seed) as u16);
        }
        z2.copy_from_slice(z1);
        c2.copy_from_slice(c1);
        let first_row = (next(seed) % 5) as i32 - 2;
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
                y1: first_row + H as i32,
            }
        };
        let span = 12u32 << (case % 9); // 1/16 pixel: 12 to 3,072
        let z0 = next(seed) >> 1;
        let spread = 1u32 << (10 + case / 9 % 4 * 7); // 2¹⁰, 2¹⁷, 2²⁴, 2³¹
                                                      // Corners near a random point of the buffer (1/16 pixel), one far on some.
        let (bx, by) = (
            (next(seed) % (W as u32 * 16)) as i32 - 40,
            (next(seed) % (H as u32 * 16)) as i32 - 40 + first_row * 16,
        );
        let mut vertex = |k: u32| {
            let far = if case % 29 == 0 && k == 1 { 9000 } else { 0 };
            let x = (next(seed) % span) as i32 + bx - span as i32 / 2 + far;
            let y = (next(seed) % span) as i32 + by - span as i32 / 2;
            // Corners on pixel centres or corners on some (edges through centres).
            let (x, y) = match case / 3 % 4 {
                1 => ((x & !15) + 8, (y & !15) + 8),
                2 => (x & !15, y & !15),
                _ => (x, y),
            };
            let z = z0
                .saturating_add(next(seed) % spread)
                .min(crate::fixed::MAX_DEPTH);
            ScreenVertex::new(x, y, z).unwrap_or(ScreenVertex::ORIGIN)
        };
        let mut tri = [vertex(0), vertex(1), vertex(2)];
        if case % 7 == 0 {
            tri[2] = tri[1];
        }
        if case / 12 % 3 == 1 {
            // A horizontal edge.
            let (a, b) = (tri[0], tri[2]);
            tri[2] = ScreenVertex::new(b.x(), a.y(), b.z()).unwrap_or(b);
        }
        let color = next(seed) as u16;
        let mut t = SmallTarget {
            z: &mut z1[..],
            c: &mut c1[..],
            width: W,
            first_row,
            clip,
        };
        let got = small_walk_less_as_u16(&mut t, tri.each_ref(), color);
        let want = small_walk_portable(tri.each_ref(), &clip, first_row, W, z2, c2, color);
        if got != want || z1 != z2 || c1 != c2 {
            bad += 1;
        }
    }
    bad
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The box walk's reciprocal after one Newton step, as its assembly works it out
    /// (`bw_recip_first`): d normalised to dn = d·2^s in [2¹⁵, 2¹⁶), the table's guess
    /// t, then x = (t·2¹⁶ + ⌊t·⌊e/2⁷⌋/2⁹⌋) >> (15 − s) with e = 2³² − 2·dn·t.
    fn recip_first_step(d: u32) -> u32 {
        let s = d.leading_zeros() - 16;
        let dn = d << s;
        let t = u32::from(crate::num::armv6m::RECIP16[((dn >> 6) & 0x1ff) as usize]);
        let e = (2 * dn * t).wrapping_neg();
        ((t << 16) + ((t * (e >> 7)) >> 9)) >> (15 - s)
    }

    /// The quotients' fix-up loop after one Newton step (d ≥ 2⁸): x is at most 2³²/d,
    /// so ⌊n·x/2³²⌋ is at most ⌊n/d⌋, and short of it by under
    /// n·(2³² − d·x)/(d·2³²) + 1 < (2³² − d·x)/(2d) + 1 ≤ 34 for n < 2³¹, and the
    /// guess without the low product at most 1 short of that: at most 34 steps,
    /// whatever the triangle; and x < 2²⁴.
    #[test]
    fn box_walk_first_step_reciprocal_needs_few_fix_ups() {
        for d in 1u32 << 8..1 << 16 {
            let x = recip_first_step(d);
            let e = (1u64 << 32) - u64::from(d) * u64::from(x);
            assert!(u64::from(d) * u64::from(x) < 1 << 32, "d = {d}");
            // x < 2²⁴: the quotients' middle products sum without a carry (`bw_quot`).
            assert!(x < 1 << 24, "d = {d}");
            assert!(e < 66 * u64::from(d), "d = {d}: e = {e}");
            for n in [(1u32 << 31) - 1, (1 << 31) - d, 1 << 30] {
                // As `bw_quot` works it out for d ≥ 2⁸: three products, the low one dropped.
                let (xh, xl, nh, nl) = (x >> 16, x & 0xffff, n >> 16, n & 0xffff);
                let guess = xh * nh + ((xh * nl + nh * xl) >> 16);
                assert!(guess <= n / d && n / d - guess <= 34, "d = {d}, n = {n}");
            }
        }
    }

    #[test]
    fn rows_walk_kernel_matches_its_twin() {
        let mut buf = [0u16; 4 * 48 * 16];
        assert_eq!(check_rows_walk_kernel(&mut buf), 0);
        assert_eq!(check_rows_walk_kernel(&mut buf[..100]), usize::MAX);
    }

    /// The bounding-box walk's twin draws what the DDA's walk drew: the same outcome,
    /// pixels, depths and counts, on random small triangles in random clips, corners
    /// often on pixel centres or grid lines (edges through centres, ties), sharing a
    /// row or a column (horizontal and vertical edges), some too large or of steep
    /// depth (refused alike), some flat.
    #[test]
    fn box_walk_matches_the_dda_walk() {
        const W: usize = 40;
        const H: usize = 24;
        let mut seed = 0x0b0b_5eed;
        let (mut zs, mut cs) = ([0u16; W * H], [0u16; W * H]);
        let (mut drawn, mut pixels) = (0, 0u64);
        for case in 0..200_000u32 {
            let n = |seed: &mut u32, m: u32| (next(seed) % m) as i32;
            for (d, c) in zs.iter_mut().zip(cs.iter_mut()) {
                (*d, *c) = (next(&mut seed) as u16 | 0x8000 >> (case % 3), 0);
            }
            let (mut z2, mut c2) = (zs, cs);
            let first_row = n(&mut seed, 5) - 2;
            let clip = if case % 2 == 0 {
                let (x0, y0) = (n(&mut seed, 20), n(&mut seed, 12));
                Clip {
                    x0,
                    y0: first_row + y0,
                    x1: x0 + n(&mut seed, (W as u32) - x0 as u32 + 1),
                    y1: first_row + y0 + n(&mut seed, (H as u32) - y0 as u32 + 1),
                }
            } else {
                Clip {
                    x0: 0,
                    y0: first_row,
                    x1: W as i32,
                    y1: first_row + H as i32,
                }
            };
            let span = [24, 48, 96, 200, 400, 9000][(case % 6) as usize];
            let (bx, by) = (
                n(&mut seed, W as u32 * 16) - 40,
                n(&mut seed, H as u32 * 16) - 40 + first_row * 16,
            );
            let grid = case / 6 % 4; // 0: free, 1: pixel centres, 2: pixel corners, 3: half
            let z0 = next(&mut seed) >> 2;
            let spread = 1u32 << (8 + case / 24 % 4 * 7);
            let mut pts = [(0i32, 0i32, 0u32); 3];
            for p in pts.iter_mut() {
                let mut x = n(&mut seed, span) + bx - span as i32 / 2;
                let mut y = n(&mut seed, span) + by - span as i32 / 2;
                match grid {
                    1 => (x, y) = ((x & !15) + 8, (y & !15) + 8),
                    2 => (x, y) = (x & !15, y & !15),
                    3 => (x, y) = (x & !7, y & !7),
                    _ => {}
                }
                let z = z0.saturating_add(next(&mut seed) % spread);
                *p = (x, y, z.min(crate::fixed::MAX_DEPTH));
            }
            match case / 96 % 8 {
                0 => pts[1].1 = pts[0].1, // a horizontal edge
                1 => pts[2].1 = pts[1].1,
                2 => pts[2].0 = pts[0].0, // a vertical edge
                3 => {
                    // Two corners in a row and one in a column.
                    pts[1].1 = pts[0].1;
                    pts[2].0 = pts[1].0;
                }
                4 => pts[2] = pts[1],
                _ => {}
            }
            let tri =
                pts.map(|(x, y, z)| ScreenVertex::new(x, y, z).unwrap_or(ScreenVertex::ORIGIN));
            let col = next(&mut seed) as u16;
            let got =
                small_walk_portable(tri.each_ref(), &clip, first_row, W, &mut zs, &mut cs, col);
            let want = small_walk_dda(tri.each_ref(), &clip, first_row, W, &mut z2, &mut c2, col);
            assert_eq!(
                got, want,
                "case {case}: {tri:?} in {clip:?} from row {first_row}"
            );
            assert!(
                zs == z2 && cs == c2,
                "case {case}: {tri:?} in {clip:?} from row {first_row}"
            );
            if let SmallDone::Drawn(t, _) = got {
                drawn += 1;
                pixels += u64::from(t);
            }
        }
        assert!(
            drawn > 100_000 && pixels > 150_000,
            "{drawn} drawn, {pixels} pixels"
        );
    }

    /// A walk kept at the end of a clip and resumed in the clip just below it with the
    /// same columns (`box_walk_resume`, the model of the assembly's save and resume) is
    /// the set-up's own in that clip, field for field, or none when the set-up finds
    /// no rows there: on random small triangles crossing random clips' last rows. A
    /// clip starting rows further on, or above, is left to the set-up.
    #[test]
    fn kept_walk_resumes_as_the_set_up_below() {
        let mut seed = 0x4b45_5054;
        let mut resumed = 0;
        for case in 0..200_000u32 {
            let n = |seed: &mut u32, m: u32| (next(seed) % m) as i32;
            let (x0, x1) = (n(&mut seed, 8), 40 + n(&mut seed, 8));
            let a = Clip {
                x0,
                y0: n(&mut seed, 8) - 4,
                x1,
                y1: n(&mut seed, 8) + 4,
            };
            let span = [48, 96, 200, 400][(case % 4) as usize];
            let (bx, by) = (200 + n(&mut seed, 400), a.y1 * 16 + n(&mut seed, 96) - 48);
            let z0 = next(&mut seed) >> 2;
            let tri = [0; 3].map(|_| {
                let (mut x, mut y) = (bx + n(&mut seed, span), by + n(&mut seed, span));
                if case % 8 < 3 {
                    (x, y) = (x & !7, y & !7);
                }
                let z = z0.saturating_add(next(&mut seed) % (1 << 20));
                ScreenVertex::new(x, y, z.min(crate::fixed::MAX_DEPTH))
                    .unwrap_or(ScreenVertex::ORIGIN)
            });
            let end = (tri.iter().map(ScreenVertex::y).max().unwrap_or(0) + 7) >> 4;
            let Ok(w) = box_walk_setup(tri.each_ref(), &a) else {
                continue;
            };
            if end <= a.y1 {
                continue;
            }
            let y0 = a.y1;
            let b = Clip {
                x0,
                y0,
                x1,
                y1: y0 + 1 + n(&mut seed, 12),
            };
            let kept = box_walk_resume(&w, a.y1, end, &b);
            // (The set-up refuses nothing below a walk it took: its tests are of the
            // triangle and the columns.)
            match box_walk_setup(tri.each_ref(), &b) {
                Ok(fresh) => {
                    assert_eq!(kept, Some(fresh), "case {case}: {tri:?} in {a:?}, {b:?}");
                    resumed += 1;
                }
                done => {
                    assert_eq!(done, Err(SmallDone::Drawn(0, 0)), "case {case}");
                    assert!(kept.is_some_and(|k| k.start >= k.end), "case {case}");
                }
            }
            // Above or below the row it was kept at, the set-up's.
            for y0 in [a.y1 - 1, a.y1 + 1] {
                assert_eq!(box_walk_resume(&w, a.y1, end, &Clip { y0, ..b }), None);
            }
        }
        assert!(resumed > 10_000, "{resumed} resumed");
    }

    /// The tests' DDA reference (`small_walk_setup`) keeps every row's columns inside the
    /// clip's, as the DDA rows loop needs (it does not clip): random small triangles near and across the edges of
    /// random clips, each taken one checked.
    #[test]
    fn small_walk_setup_keeps_rows_inside_the_clip() {
        let mut seed = 0x5151_7357;
        let mut taken = 0;
        for i in 0..200_000u32 {
            let clip = Clip {
                x0: (next(&mut seed) % 8) as i32,
                y0: (next(&mut seed) % 8) as i32,
                x1: 12 + (next(&mut seed) % 8) as i32,
                y1: 12 + (next(&mut seed) % 8) as i32,
            };
            let span = [24, 96, 400][(i % 3) as usize];
            let mut vertex = || {
                let x = (next(&mut seed) % span) as i32 + 16 * 10 - span as i32 / 2;
                let y = (next(&mut seed) % span) as i32 + 16 * 10 - span as i32 / 2;
                ScreenVertex::new(x, y, 1 << 20).unwrap_or(ScreenVertex::ORIGIN)
            };
            let tri = [vertex(), vertex(), vertex()];
            if let Ok((r, at)) = small_walk_setup(tri.each_ref(), &clip, 0, 32) {
                taken += 1;
                assert!(columns_inside(&r, at.n0), "{tri:?} in {clip:?}");
            }
        }
        assert!(taken > 20_000, "{taken} taken");
    }

    /// The set-up draws the usual small triangle itself (the Rust path takes only
    /// what it refuses): of random triangles up to 10 pixels across, of depths a few
    /// units apart, all but the flat ones.
    #[test]
    fn box_walk_takes_the_usual_triangle() {
        let mut seed = 0x1234_5678;
        let clip = Clip {
            x0: 0,
            y0: 0,
            x1: 48,
            y1: 48,
        };
        let mut taken = 0;
        for _ in 0..1000 {
            let mut vertex = || {
                let (x, y) = (
                    (next(&mut seed) % 160) as i32,
                    (next(&mut seed) % 160) as i32,
                );
                let z = (1 << 20) + next(&mut seed) % (1 << 20);
                ScreenVertex::new(x + 100, y + 100, z).unwrap_or(ScreenVertex::ORIGIN)
            };
            let tri = [vertex(), vertex(), vertex()];
            if box_walk_setup(tri.each_ref(), &clip).is_ok() {
                taken += 1;
            }
        }
        assert!(taken > 950, "{taken} of 1000 taken");
    }
}
