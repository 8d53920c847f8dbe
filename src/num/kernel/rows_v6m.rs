//! The rows of a small flat-coloured triangle on ARMv6-M, both halves in one
//! out-of-line loop: edges in the DDA form of [`EdgeWalk`](crate::raster::EdgeWalk)
//! (there is no divide), the depth test `Less` with depth writes, a two-byte colour.
//! Thumb-1 assembly beside its portable twin.
#![allow(unsafe_code)]

use super::rows::{as_u16, check_cases, check_place, next, twin_row, CHECK_W};
use super::RowsAt;

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
/// carry out of the lower half) and `denom` to `err` (all wrapping).
#[repr(C)]
#[derive(Clone, Copy, Default, Debug, PartialEq, Eq)]
pub(crate) struct WalkEdge {
    at: u32,
    step: u32,
    fix: u32,
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
    assert!(offset_of!(WalkEdge, step) == 4 && offset_of!(WalkEdge, fix) == 8);
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
/// both buffers: on ARMv6-M the block's last fields, then one out-of-line call.
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

/// The section of [`rows_walk_less_u16`]'s loop: RAM under `zraster_ram_code` (as the
/// other loops' `.data.zraster`), else its own text section.
#[cfg(all(zraster_thumb, zraster_armv6m, zraster_ram_code))]
macro_rules! rows_walk_section {
    () => {
        ".pushsection .data.zraster,\"awx\",%progbits"
    };
}
#[cfg(all(zraster_thumb, zraster_armv6m, not(zraster_ram_code)))]
macro_rules! rows_walk_section {
    () => {
        ".pushsection .text.zraster_rows_walk_v6m,\"ax\",%progbits"
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
}

// SAFETY (of the loop, for its callers above): rows row0 .. row0 + n0 + n1 of width
// `width` lie inside both buffers, and columns px0 + cx0 .. px0 + cx1 inside 0..width
// (the caller's contract); both are u16 rows (2-aligned). The loop starts at `base`,
// the depth address of row row0, column px0, runs each half until the row address
// reaches base + rows · pitch (a half of 0 rows is skipped; the first half's end is n0
// rows on, the second's n1 more), and writes only columns max(x, cx0) .. min(x', cx1)
// of a row (signed compares, clamped whenever either bound is crossed): inside both
// buffers (the colour at the depth address + delta). The block is read and written
// through r0 (`failed`, the edges, `n1` cleared for the second half). r4–r11 and lr
// are saved and restored as AAPCS wants; r0–r2 pushed and popped around the longer
// rows' loop.
#[cfg(all(zraster_thumb, zraster_armv6m))]
core::arch::global_asm!(
    rows_walk_section!(),
    ".balign 4",
    ".global zraster_rows_walk_v6m",
    ".hidden zraster_rows_walk_v6m",
    ".type zraster_rows_walk_v6m, %function",
    ".thumb_func",
    "zraster_rows_walk_v6m:",
    "push {{r4, r5, r6, r7, lr}}",
    "mov r4, r8",
    "mov r5, r9",
    "mov r6, r10",
    "mov r7, r11",
    "push {{r4, r5, r6, r7}}",
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
    // A row: its columns (the edges' upper halves), inside the clip (usually; else
    // clamped at 14).
    "1:",
    "asrs r6, r1, #16",
    "asrs r7, r2, #16",
    "ldr r3, [r0, #20]",
    "cmp r6, r3",
    "blt 14f",
    "ldr r4, [r0, #24]",
    "cmp r7, r4",
    "bgt 14f",
    "subs r5, r7, r6",
    "ble 5f",
    // r6 its first column, r5 its length.
    "15:",
    "add r10, r5",
    // Its depth at the first column and that column's depth address; the depth
    // clamped to lo..=hi out of line (when depth − lo > hi − lo, unsigned).
    "ldr r4, [r0]",
    "muls r4, r6",
    "add r4, r8",
    "lsls r3, r6, #1",
    "add r3, r9",
    "ldr r6, [r0, #4]",
    "subs r7, r4, r6",
    "ldr r6, [r0, #8]",
    "cmp r7, r6",
    "bhi 16f",
    "17:",
    "cmp r5, #1",
    "bne 3f",
    "lsrs r6, r4, #16",
    "ldrh r7, [r3]",
    "cmp r6, r7",
    "bhs 6f",
    "strh r6, [r3]",
    "ldr r6, [r0, #12]",
    "ldr r7, [r0, #16]",
    "strh r6, [r3, r7]",
    // The next row: both edges stepped (a borrow out of the lower half, bit 15, is
    // fixed up), then the depth and the address.
    "5:",
    "ldr r3, [r0, #52]",
    "adds r1, r1, r3",
    "lsls r3, r1, #16",
    "bpl 21f",
    "ldr r3, [r0, #56]",
    "adds r1, r1, r3",
    "21:",
    "ldr r3, [r0, #64]",
    "adds r2, r2, r3",
    "lsls r3, r2, #16",
    "bpl 22f",
    "ldr r3, [r0, #68]",
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
    // The row's columns clamped to the clip.
    "14:",
    "ldr r3, [r0, #20]",
    "cmp r6, r3",
    "bge 23f",
    "mov r6, r3",
    "23:",
    "ldr r4, [r0, #24]",
    "cmp r7, r4",
    "bgt 24f",
    "mov r4, r7",
    "24:",
    "subs r5, r4, r6",
    "ble 5b",
    "b 15b",
    // The first depth clamped: below lo to lo, else to lo + (hi − lo).
    "16:",
    "ldr r7, [r0, #4]",
    "cmp r4, r7",
    "blo 18f",
    "adds r7, r7, r6",
    "18:",
    "mov r4, r7",
    "b 17b",
    // A failed pixel of a one-pixel row.
    "6:",
    "ldr r6, [r0, #28]",
    "adds r6, #1",
    "str r6, [r0, #28]",
    "b 5b",
    // Two pixels or more: r3 the address, r4 the depth, r5 the count.
    "3:",
    "push {{r0, r1, r2}}",
    "ldr r1, [r0]",
    "ldr r2, [r0, #12]",
    "ldr r7, [r0, #16]",
    "31:",
    "lsrs r6, r4, #16",
    "ldrh r0, [r3]",
    "cmp r6, r0",
    "bhs 33f",
    "strh r6, [r3]",
    "strh r2, [r3, r7]",
    "32:",
    "adds r4, r4, r1",
    "adds r3, #2",
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
    "pop {{r4, r5, r6, r7}}",
    "mov r8, r4",
    "mov r9, r5",
    "mov r10, r6",
    "mov r11, r7",
    "pop {{r4, r5, r6, r7, pc}}",
    ".size zraster_rows_walk_v6m, . - zraster_rows_walk_v6m",
    ".popsection",
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
    check_cases(buf, 0x1357_9bdf, make, kernel, rows_walk_less_portable)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_walk_kernel_matches_its_twin() {
        let mut buf = [0u16; 4 * 48 * 16];
        assert_eq!(check_rows_walk_kernel(&mut buf), 0);
        assert_eq!(check_rows_walk_kernel(&mut buf[..100]), usize::MAX);
    }
}
