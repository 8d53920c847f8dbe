//! The rows of a small flat-coloured triangle, both halves in one pass: edges by one
//! division a row, the depth test `Less` with depth writes, a two-byte colour.
//! Assembly on ARMv7E-M (the row's state in registers, its constants in one block read
//! by `LDRD`/`LDM`), beside its portable twin.
#![allow(unsafe_code)]

/// Whether [`rows_less_as_u16`] runs the assembly (ARMv7E-M). Elsewhere it runs the
/// portable twin, which the rasterizer does not call (its own row loop is the faster
/// there): the twin is for the tests and the bench's check.
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
/// its column `x` is `clamp(z + x·sx, lo, hi)` then `+ sx` a pixel, `z`
/// ([`RowsAt::z`]) stepping by `sy` a row (all wrapping). Filled field by field as the
/// triangle's set-up finds the values, so that they need not stay in registers
/// meanwhile.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub(crate) struct RowsLess {
    sx: u32,          // 0
    lo: u32,          // 4
    hi: u32,          // 8
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
    assert!(offset_of!(RowsLess, hi) == 8 && offset_of!(RowsLess, color) == 12);
    assert!(offset_of!(RowsLess, delta) == 16 && offset_of!(RowsLess, dt) == 20);
    assert!(offset_of!(RowsLess, cx) == 28 && offset_of!(RowsLess, sy) == 36);
    assert!(offset_of!(RowsLess, pitch) == 40 && offset_of!(RowsLess, failed) == 44);
    assert!(offset_of!(RowsLess, t) == 48 && offset_of!(RowsLess, d) == 56);
    assert!(offset_of!(RowsLess, n1) == 64 && offset_of!(RowsLess, side) == 68);
    assert!(offset_of!(RowsLess, short1) == 72 && size_of::<RowsLess>() == 84);
    assert!(align_of::<RowsLess>() >= 4);
};

impl RowsLess {
    /// Rows clipped to the columns `cx0..cx1`, everything else 0 (field by field: each
    /// is written again before the assembly reads it, and the compiler drops these).
    #[inline(always)]
    pub(crate) fn new(cx0: i32, cx1: i32) -> RowsLess {
        RowsLess {
            sx: 0,
            lo: 0,
            hi: 0,
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

    /// The depth plane's steps `sx` and `sy`, and the clamp `lo..=hi`.
    #[inline(always)]
    pub(crate) fn depth(&mut self, sx: u32, sy: u32, lo: u32, hi: u32) {
        (self.sx, self.sy, self.lo, self.hi) = (sx, sy, lo, hi);
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
            let depth = [zrow, r.sx, r.lo, r.hi];
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

/// [`rows_less_u16`] for ARMv7E-M. Rows of one and two pixels inline; longer ones by
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
    // colour at the depth address + delta). Rows of three or more pixels run the loop
    // of `span_less_dsp` over exactly that range (its own SAFETY argument: the colour
    // and depth addresses alike modulo 4, tested on `delta`), with r0–r8 pushed around
    // it and popped after, or (not alike) a loop of exactly that many pixels with
    // r1–r3 pushed and popped. Quotients come from UDIV (x/0 = 0, as the twin has it).
    // The block is read and written through r0 (`failed`, `dt` reordered, the second
    // half's count). r6 and r7 (not allowed as operands) are pushed and popped; every
    // other register written is declared; the flags (GE included) are scratch.
    unsafe {
        core::arch::asm!(
            "push {{r6, r7}}",
            "movs r6, #0",
            // The long and short edges to the left and right.
            "ldr r12, [r0, #68]",
            "cmp r12, #0",
            "bne 11f",
            "ldrd r1, r2, [r0, #48]",
            "ldrd r7, r8, [r0, #56]",
            "b 12f",
            "11:",
            "ldrd r2, r1, [r0, #48]",
            "ldrd r8, r7, [r0, #56]",
            "ldrd r9, r10, [r0, #20]",
            "strd r10, r9, [r0, #20]",
            "12:",
            "cmp r5, #0",
            "beq 8f",
            // A row: its columns, clamped to the clip.
            "1:",
            "udiv r10, r1, r7",
            "udiv r11, r2, r8",
            "ldrd r9, r12, [r0, #20]",
            "add r1, r9",
            "add r2, r12",
            "ldrd r9, r12, [r0, #28]",
            // Inside the clip (usually): cx0 ≤ x and x' ≤ cx1; else clamped at 14.
            "cmp r10, r9",
            "it ge",
            "cmpge r12, r11",
            "blt 14f",
            "15:",
            "subs r11, r11, r10",
            "ble 5f",
            // Its depth at the first column, clamped, and that column's address.
            "add r6, r11",
            "ldm r0, {{r9, r12, lr}}",
            "mla r9, r10, r9, r3",
            "add r10, r4, r10, lsl #1",
            // Inside lo..=hi (usually); else clamped at 16.
            "cmp r9, r12",
            "it hs",
            "cmphs lr, r9",
            "blo 16f",
            "17:",
            "cmp r11, #1",
            "bne 3f",
            "lsr r9, r9, #16",
            rows_pixel!("[r10]", "6f"),
            // The next row.
            "5:",
            "ldrd r9, r12, [r0, #36]",
            "add r3, r9",
            "add r4, r12",
            "subs r5, #1",
            "bne 1b",
            // The second half, its count cleared so that it runs once: the short edge
            // replaced, the long one carried on.
            "8:",
            "ldr r5, [r0, #64]",
            "cmp r5, #0",
            "beq 9f",
            "movs r9, #0",
            "str r9, [r0, #64]",
            "add lr, r0, #72",
            "ldm lr, {{r9, r10, r11}}",
            "ldr r12, [r0, #68]",
            "cmp r12, #0",
            "bne 13f",
            "mov r2, r9",
            "mov r8, r10",
            "str r11, [r0, #24]",
            "b 1b",
            "13:",
            "mov r1, r9",
            "mov r7, r10",
            "str r11, [r0, #20]",
            "b 1b",
            // Two pixels.
            "3:",
            "cmp r11, #2",
            "bne 4f",
            "ldr r12, [r0]",
            "add r11, r9, r12",
            "lsr r9, r9, #16",
            rows_pixel!("[r10]", "7f"),
            "2:",
            "lsr r9, r11, #16",
            rows_pixel!("[r10, #2]!", "6f"),
            "b 5b",
            // The row's columns clamped to the clip.
            "14:",
            "cmp r10, r9",
            "it lt",
            "movlt r10, r9",
            "cmp r11, r12",
            "it gt",
            "movgt r11, r12",
            "b 15b",
            // The row's first depth clamped to lo..=hi.
            "16:",
            "cmp r9, r12",
            "it lo",
            "movlo r9, r12",
            "cmp r9, lr",
            "it hi",
            "movhi r9, lr",
            "b 17b",
            "6:",
            rows_failed!("5b"),
            "7:",
            rows_failed!("2b"),
            // Three pixels or more: span_less_dsp's loop, r0–r8 saved meanwhile, when
            // the colour and depth rows are aligned alike; else one pixel a turn.
            "4:",
            "ldr r12, [r0, #16]",
            "tst r12, #2",
            "bne 40f",
            "push {{r0-r8}}",
            "ldr r4, [r0]",
            "ldr r1, [r0, #16]",
            "ldr r5, [r0, #12]",
            "orr r5, r5, r5, lsl #16",
            "eor r6, r5, #0x00010001",
            "add r1, r10",
            "mov r0, r10",
            "mov r2, r11",
            "mov r3, r9",
            "movs r7, #0",
            dsp_span!("20", "21", "22", "23", "24", "25"),
            "pop {{r0-r8}}",
            "ldr r9, [r0, #44]",
            "add r9, r12",
            "str r9, [r0, #44]",
            "b 5b",
            "40:",
            "push {{r1-r3}}",
            "ldr r1, [r0]",
            "ldrd r2, r3, [r0, #12]",
            "41:",
            "lsr lr, r9, #16",
            "ldrh r12, [r10]",
            "add r9, r1",
            "cmp lr, r12",
            "bhs 43f",
            "strh lr, [r10]",
            "strh r2, [r10, r3]",
            "42:",
            "add r10, r10, #2",
            "subs r11, #1",
            "bne 41b",
            "pop {{r1-r3}}",
            "b 5b",
            "43:",
            rows_failed!("42b"),
            "9:",
            "mov r1, r6",
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

/// The xorshift32 generator of the rows kernels' checks.
pub(super) fn next(seed: &mut u32) -> u32 {
    *seed ^= *seed << 13;
    *seed ^= *seed >> 17;
    *seed ^= *seed << 5;
    *seed
}

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

/// On-target check of the rows assembly against its twin, for the bench firmware
/// (`check_cases`): random triangles' rows (edges, depths, clip columns, both
/// halves, rows of every length from empty to 40 pixels) through `rows_less_as_u16`
/// and `rows_less_portable`. Returns the number of cases that differ (where there is
/// no assembly, the twin against itself). Out of line: its frame is not the bench's.
#[inline(never)]
pub fn check_rows_kernel(buf: &mut [u16]) -> usize {
    let kernel = rows_less_as_u16::<u16>;
    check_cases(buf, 0x2545_f491, check_case, kernel, rows_less_portable)
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
