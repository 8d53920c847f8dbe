//! A small flat triangle read from the vertex cache, set-up and rows, in one x86-64
//! assembly block: the corners sorted by y, the extents tested, the clip's rows, the
//! edges in the `EdgeDivide` form (columns counted from a fixed screen column), the
//! depth steps by two floored 64-bit divisions, the first row's depth, then both
//! halves' rows (the loop of [`rows_x86`](super::rows_x86); without the clip's column
//! clamps for a triangle well inside the clip's columns). Its portable twin is `fill::small`'s
//! `fill_small_divide` (set-up and `rows_divide`), which the renderer runs on other
//! targets and for what this block refuses; a host test compares the two.
#![allow(unsafe_code)]

use super::rows::SmallTarget;
use super::CachedVertex;
use crate::raster::Clip;

/// Whether [`small_x86`] runs the assembly (x86-64); elsewhere it refuses every call.
pub(crate) const SMALL_X86_KERNEL: bool = cfg!(zraster_x86_64);

/// The screen column the assembly's columns count from (its local column 0), left of
/// every cached x (−2¹⁴ in 1/16 pixel): the clip's columns are then worked out once a
/// run and an edge's `t` stays positive (16 in the assembly's `16392` and `−16376`).
const ORIGIN: i32 = -1024;

/// The block the assembly reads and writes, at the offsets in the comments: the rows'
/// operands, the buffers and the clip, and the set-up's values kept for later.
#[cfg_attr(not(zraster_x86_64), allow(dead_code))]
#[derive(Clone, Default)]
#[repr(C)]
pub(super) struct Block {
    /// sx, sy, lo, hi, cx0, cx1, spare, spare, the first row, spare, spare, spare, spare,
    /// color.
    rows: [u32; 14], // 0
    pitch: usize, // 56
    /// The depth's address of screen column `ORIGIN` of screen row 0 (wrapping).
    zbase: usize, // 64
    delta: isize, // 72
    width: isize, // 80
    /// First row, clip x0, y0, x1, y1, spare, the inside test's least x and span, spare.
    at: [i32; 10], // 88
    /// The edges' steps and divisors (dx, dy, of `t >> 4`: ⌊(t >> 4)/dy⌋ = ⌊t/16dy⌋, and
    /// 16·dx steps `t`, a multiple of 16, so dx steps `t >> 4`): the long one, the upper
    /// and the lower short one; the lower one's `t >> 4` at its first row, the row past
    /// the last; the depth's step a pixel rotated (two words: `(sx >> 16) | (sx << 48)`);
    /// the middle row, 16·start + 8, s0 and s1.
    set: [i32; 14], // 128
    /// Pixels tested (twice: the spans' bytes) and failed, summed.
    tested: u64, // 184
    failed: u64,  // 192
}

impl Block {
    /// The address of screen column [`ORIGIN`] of screen row 0 in depth rows `z` of the
    /// block's width from its first row (wrapping: an address the assembly adds only the
    /// offsets of the clip's pixels to).
    #[cfg_attr(not(zraster_x86_64), allow(dead_code))]
    #[inline(always)]
    fn origin(&self, z: &mut [u16]) -> usize {
        let [first_row, ..] = self.at;
        let at = (ORIGIN as isize).wrapping_sub((first_row as isize).wrapping_mul(self.width));
        (z.as_mut_ptr() as usize).wrapping_add_signed(at.wrapping_mul(2))
    }

    /// The colour's bits (at 52: the rows' colour).
    #[cfg_attr(not(zraster_x86_64), allow(dead_code))]
    pub(super) fn set_color(&mut self, bits: u16) {
        self.rows[13] = u32::from(bits);
    }

    /// The pixels tested and failed since the block was made.
    #[cfg_attr(not(zraster_x86_64), allow(dead_code))]
    pub(super) fn counts(&self) -> (u64, u64) {
        (self.tested / 2, self.failed)
    }
}

#[cfg(target_pointer_width = "64")]
const _: () = {
    use core::mem::offset_of;
    assert!(offset_of!(Block, pitch) == 56 && offset_of!(Block, zbase) == 64);
    assert!(offset_of!(Block, delta) == 72 && offset_of!(Block, width) == 80);
    assert!(offset_of!(Block, at) == 88 && offset_of!(Block, set) == 128);
    assert!(offset_of!(Block, tested) == 184 && offset_of!(Block, failed) == 192);
    assert!(core::mem::size_of::<Block>() == 200);
};

/// The set-up and rows of [`small_x86`] (the block in rdi, the corners' entries at
/// indices r15, rdx and rcx of the entries from rbp): on to local label `90` when done
/// (twice the pixels tested and the pixels failed added to the block's sums at 184 and
/// 192), to `91` when refused (nothing drawn). Clobbers rax, rcx, rdx, rsi, r8–r15 and
/// the flags, keeps rbx and rbp; no stack. Also the body of the fused face loop
/// ([`faces_x86`](super::faces_x86)), whose scan leaves the indices there.
#[cfg(zraster_x86_64)]
#[rustfmt::skip]
macro_rules! small_x86_body {
    () => {
        concat!(
            // A triangle well inside the clip's columns (one pixel to spare on each
            // side) needs no clamp of its rows' columns: the rows without it. Each
            // corner's x less the least such x, unsigned, at most the span of them.
            "movsx eax, word ptr [rbp + r15 * 8 + 4]\n",
            "sub eax, dword ptr [rdi + 112]\n",
            "cmp eax, dword ptr [rdi + 116]\n",
            "ja 29f\n",
            "movsx eax, word ptr [rbp + rdx * 8 + 4]\n",
            "sub eax, dword ptr [rdi + 112]\n",
            "cmp eax, dword ptr [rdi + 116]\n",
            "ja 29f\n",
            "movsx eax, word ptr [rbp + rcx * 8 + 4]\n",
            "sub eax, dword ptr [rdi + 112]\n",
            "cmp eax, dword ptr [rdi + 116]\n",
            "ja 29f\n",
            small_x86_rest!(inside),
            "29:\n",
            // Extents in x (the corners in any order): 512 pixels or more refused.
            "movsx eax, word ptr [rbp + r15 * 8 + 4]\n",
            "movsx r8d, word ptr [rbp + rdx * 8 + 4]\n",
            "movsx r9d, word ptr [rbp + rcx * 8 + 4]\n",
            "mov r10d, eax\n",
            "cmp r8d, r10d\n",
            "cmovl r10d, r8d\n",
            "cmp r9d, r10d\n",
            "cmovl r10d, r9d\n",
            "mov r11d, eax\n",
            "cmp r8d, r11d\n",
            "cmovg r11d, r8d\n",
            "cmp r9d, r11d\n",
            "cmovg r11d, r9d\n",
            small_x86_rest!(clamp),
        )
    };
}

/// The clamp of a row's edge column to the clip's (`clamp`: `$op` with the clip's
/// column at `$at`), or none (`inside`).
#[cfg(zraster_x86_64)]
macro_rules! small_x86_clamp {
    (inside, $op:literal, $at:literal) => {
        ""
    };
    (clamp, $op:literal, $at:literal) => {
        concat!(
            "cmp eax, dword ptr [rdi + ",
            $at,
            "]\n",
            $op,
            " eax, dword ptr [rdi + ",
            $at,
            "]\n",
        )
    };
}

/// The x extents' test (xmin in r10d, xmax in r11d: 512 pixels or more refused) where
/// the copy needs it (`clamp`); inside the clip's columns `SmallRun::new` has made
/// them below 512 pixels (a clip of at most 514 columns).
#[cfg(zraster_x86_64)]
macro_rules! small_x86_extents {
    (inside) => {
        ""
    };
    (clamp) => {
        concat!("sub r11d, r10d\n", "cmp r11d, 8191\n", "jg 91f\n")
    };
}

/// One half's rows (`ecx` of them, at least 1): the left edge's `t >> 4` in `$lt` divided by
/// `[rdi + $ld]`, the right one's in `$rt` by `[rdi + $rd]`, each stepped by its
/// `[rdi + …dt]` (the long edge r8 by 128, the short r9 by `$sdt`); the columns clamped
/// or not (`$clamp`); the labels `$a`–`$e` the copy's own (the pixel's failure at `$e`,
/// placed by the caller after the copy). A row's pixels run by a negative byte offset up
/// to the row's end (the tested pixels summed as bytes, twice their number), the depth
/// in rdx rotated (the integer in bits 0–15, the fraction in
/// 48–63: one add and the fraction's carry a pixel, as `acc >> 16` of the 32-bit sum).
#[cfg(zraster_x86_64)]
#[rustfmt::skip]
macro_rules! small_x86_rows {
    ($clamp:ident, $lt:literal, $ld:literal, $rt:literal, $rd:literal, $sdt:literal,
     $a:literal, $b:literal, $c:literal, $d:literal, $e:literal) => {
        concat!(
            $a, ":\n",
            "mov eax, ", $rt, "\n",
            "xor edx, edx\n",
            "div dword ptr [rdi + ", $rd, "]\n",
            small_x86_clamp!($clamp, "cmovg", 20),
            "lea rsi, [r11 + rax * 2]\n",
            "mov eax, ", $lt, "\n",
            "xor edx, edx\n",
            "div dword ptr [rdi + ", $ld, "]\n",
            small_x86_clamp!($clamp, "cmovl", 16),
            "add r8d, dword ptr [rdi + 128]\n",
            "add r9d, dword ptr [rdi + ", $sdt, "]\n",
            // r12 = the left end's address less the right's: the span's negative
            // length in bytes (none from 0 on), counted into the tested bytes.
            "lea r12, [r11 + rax * 2]\n",
            "sub r12, rsi\n",
            "jge ", $d, "f\n",
            "sub qword ptr [rdi + 184], r12\n",
            "imul eax, dword ptr [rdi]\n",
            "lea edx, [rax + r10]\n",
            "cmp edx, dword ptr [rdi + 8]\n",
            "cmovb edx, dword ptr [rdi + 8]\n",
            "cmp edx, dword ptr [rdi + 12]\n",
            "cmova edx, dword ptr [rdi + 12]\n",
            "ror rdx, 16\n",
            "lea r13, [rsi + r15]\n",
            $b, ":\n",
            "cmp dx, word ptr [rsi + r12]\n",
            "jae ", $e, "f\n",
            "mov word ptr [rsi + r12], dx\n",
            "mov word ptr [r13 + r12], r14w\n",
            $c, ":\n",
            "add rdx, qword ptr [rdi + 160]\n",
            "adc rdx, 0\n",
            "add r12, 2\n",
            "jnz ", $b, "b\n",
            $d, ":\n",
            "add r10d, dword ptr [rdi + 4]\n",
            "add r11, qword ptr [rdi + 56]\n",
            "dec ecx\n",
            "jnz ", $a, "b\n",
        )
    };
}

/// [`small_x86_rest`] after the area's sign (`pos`: the middle corner right of the long
/// edge, which is then the left one; `neg`: left of it), the dividends' signs and the
/// rows' copies for that side: the depth steps, the edges, the first
/// row's depth and address, then both halves' rows, on to `90`.
#[cfg(zraster_x86_64)]
#[rustfmt::skip]
macro_rules! small_x86_side {
    ($clamp:ident, pos) => {
        small_x86_side!(@ $clamp, "", "", "mov rax, r13\n",
            "r8d", "132", "r9d", "140", "r8d", "132", "r9d", "148")
    };
    ($clamp:ident, neg) => {
        small_x86_side!(@ $clamp, "neg rcx\n", "neg rax\n", "imul rax, r13, -1\n",
            "r9d", "140", "r8d", "132", "r9d", "148", "r8d", "132")
    };
    (@ $clamp:ident, $neg:literal, $ka:literal, $kb:literal,
     $ul:literal, $uld:literal, $ur:literal, $urd:literal,
     $ll:literal, $lld:literal, $lr:literal, $lrd:literal) => {
        concat!(
            // q = ⌊16·na/area⌋, r = ⌊16·nb/area⌋: the dividends with the area's sign
            // over |area|, IDIV's quotient less 1 where the remainder is negative.
            $neg,
            $ka,
            "cqo\n",
            "idiv rcx\n",
            "sar rdx, 63\n",
            "add rax, rdx\n",
            "mov r12d, eax\n",
            "shl eax, 4\n",
            "mov dword ptr [rdi], eax\n",
            "ror rax, 16\n",
            "mov qword ptr [rdi + 160], rax\n",
            $kb,
            "cqo\n",
            "idiv rcx\n",
            "sar rdx, 63\n",
            "add rax, rdx\n",
            "mov r13d, eax\n",
            "shl eax, 4\n",
            "mov dword ptr [rdi + 4], eax\n",
            // The lower half's short edge at row mid: s1 = 16·mid + 8 − ym, from
            // xa' + dxs, by (dxl − dxs, dy2): t >> 4, its step and divisor.
            "mov eax, r14d\n",
            "sub eax, esi\n",
            "mov edx, eax\n",
            "imul edx, dword ptr [rdi + 180]\n",
            "lea ecx, [r10 + rsi]\n",
            "imul ecx, r9d\n",
            "lea edx, [rdx + rcx - 1]\n",
            "shr edx, 4\n",
            "mov dword ptr [rdi + 152], edx\n",
            "mov dword ptr [rdi + 144], eax\n",
            "mov dword ptr [rdi + 148], r9d\n",
            // The upper short edge into r9: (s0·dxs + xa'·dys − 1) >> 4.
            "mov r9d, esi\n",
            "imul r9d, dword ptr [rdi + 176]\n",
            "mov eax, r10d\n",
            "imul eax, r8d\n",
            "lea r9d, [r9 + rax - 1]\n",
            "shr r9d, 4\n",
            "mov dword ptr [rdi + 136], esi\n",
            "mov dword ptr [rdi + 140], r8d\n",
            // The long edge into r8: (s0·dxl + xa'·dyl − 1) >> 4.
            "mov r8d, r14d\n",
            "imul r8d, dword ptr [rdi + 176]\n",
            "imul r10d, r11d\n",
            "lea r8d, [r8 + r10 - 1]\n",
            "shr r8d, 4\n",
            "mov dword ptr [rdi + 128], r14d\n",
            "mov dword ptr [rdi + 132], r11d\n",
            // The first row's depth at local column 0 (screen column ORIGIN), from
            // p0: z + bias + q·(8 − (x − 16·ORIGIN)) + r·(16·start + 8 − y).
            "movsx ecx, word ptr [rbp + r15 * 8 + 4]\n",
            "add ecx, 16376\n",
            "imul ecx, r12d\n",
            "movsx eax, word ptr [rbp + r15 * 8 + 6]\n",
            "mov r10d, dword ptr [rdi + 172]\n",
            "sub r10d, eax\n",
            "imul r10d, r13d\n",
            "sub r10d, ecx\n",
            "add r10d, dword ptr [rbp + r15 * 8]\n",
            "add r10d, 32768\n",
            // The first row's address: local column 0 of screen row `start`.
            "movsxd r11, dword ptr [rdi + 32]\n",
            "imul r11, qword ptr [rdi + 56]\n",
            "add r11, qword ptr [rdi + 64]\n",
            "mov r14d, dword ptr [rdi + 52]\n",
            "mov r15, qword ptr [rdi + 72]\n",
            // The upper half, then the lower one with its short edge.
            "mov ecx, dword ptr [rdi + 168]\n",
            "sub ecx, dword ptr [rdi + 32]\n",
            "jle 40f\n",
            small_x86_rows!($clamp, $ul, $uld, $ur, $urd, "136", "2", "3", "4", "5", "6"),
            "40:\n",
            "mov ecx, dword ptr [rdi + 156]\n",
            "sub ecx, dword ptr [rdi + 168]\n",
            "jle 90f\n",
            "mov r9d, dword ptr [rdi + 152]\n",
            small_x86_rows!($clamp, $ll, $lld, $lr, $lrd, "144", "12", "13", "14", "15", "16"),
            "jmp 90f\n",
            "6:\n",
            "inc qword ptr [rdi + 192]\n",
            "jmp 4b\n",
            "16:\n",
            "inc qword ptr [rdi + 192]\n",
            "jmp 14b\n",
        )
    };
}

/// [`small_x86_body`] after the extents (xmin in r10d, xmax in r11d), its rows with
/// the columns clamped to the clip's (`clamp`) or not (`inside`): the corners sorted by
/// y, the rows, the depths' clamp and differences, the x offsets, the area and the
/// depth plane's numerators, then [`small_x86_side`] for the area's sign. Its local
/// labels are its own: the two copies follow each other, every jump inside one copy
/// but those to `90`, `91` (after both).
#[cfg(zraster_x86_64)]
#[rustfmt::skip]
macro_rules! small_x86_rest {
    ($clamp:ident) => {
        concat!(
            small_x86_extents!($clamp),
            // p0 kept (r15); a, m, c sorted by y (stable, as `by_rows`).
            "mov rsi, r15\n",
            "movsx eax, word ptr [rbp + rsi * 8 + 6]\n",
            "movsx r8d, word ptr [rbp + rdx * 8 + 6]\n",
            "cmp r8d, eax\n",
            "jge 21f\n",
            "xchg rsi, rdx\n",
            "xchg eax, r8d\n",
            "21:\n",
            "movsx r9d, word ptr [rbp + rcx * 8 + 6]\n",
            "cmp r9d, r8d\n",
            "jge 22f\n",
            "xchg rdx, rcx\n",
            "xchg r8d, r9d\n",
            "22:\n",
            "cmp r8d, eax\n",
            "jge 23f\n",
            "xchg rsi, rdx\n",
            "xchg eax, r8d\n",
            "23:\n",
            // dyl = yc − ya (refused from 8192); start, end, mid (at 32, 156 and 168:
            // the halves' rows are their differences), s1 = 16·mid + 8 − ym at 180,
            // 16·start + 8 at 172, s0 = 16·start + 8 − ya at 176; dy2, dys.
            "mov r11d, r9d\n",
            "sub r11d, eax\n",
            "cmp r11d, 8191\n",
            "jg 91f\n",
            "lea r12d, [rax + 7]\n",
            "sar r12d, 4\n",
            "cmp r12d, dword ptr [rdi + 96]\n",
            "cmovl r12d, dword ptr [rdi + 96]\n",
            "lea r13d, [r9 + 7]\n",
            "sar r13d, 4\n",
            "cmp r13d, dword ptr [rdi + 104]\n",
            "cmovg r13d, dword ptr [rdi + 104]\n",
            "cmp r12d, r13d\n",
            "jge 90f\n",
            "lea r14d, [r8 + 7]\n",
            "sar r14d, 4\n",
            "cmp r14d, r12d\n",
            "cmovl r14d, r12d\n",
            "cmp r14d, r13d\n",
            "cmovg r14d, r13d\n",
            "mov dword ptr [rdi + 156], r13d\n",
            "mov dword ptr [rdi + 168], r14d\n",
            "mov dword ptr [rdi + 32], r12d\n",
            "shl r14d, 4\n",
            "add r14d, 8\n",
            "sub r14d, r8d\n",
            "mov dword ptr [rdi + 180], r14d\n",
            "shl r12d, 4\n",
            "add r12d, 8\n",
            "mov dword ptr [rdi + 172], r12d\n",
            "sub r12d, eax\n",
            "mov dword ptr [rdi + 176], r12d\n",
            "sub r9d, r8d\n",
            "sub r8d, eax\n",
            // The depths: lo, hi (biased); 16·dz1, 16·dz2 of z >> 4 (64-bit).
            "mov r10d, dword ptr [rbp + rsi * 8]\n",
            "mov r12d, dword ptr [rbp + rdx * 8]\n",
            "mov r13d, dword ptr [rbp + rcx * 8]\n",
            "mov eax, r10d\n",
            "mov r14d, r10d\n",
            "cmp r12d, r10d\n",
            "cmovb eax, r12d\n",
            "cmova r14d, r12d\n",
            "cmp r13d, eax\n",
            "cmovb eax, r13d\n",
            "cmp r13d, r14d\n",
            "cmova r14d, r13d\n",
            "add eax, 32768\n",
            "mov dword ptr [rdi + 8], eax\n",
            "add r14d, 32768\n",
            "mov dword ptr [rdi + 12], r14d\n",
            "and r10d, -16\n",
            "and r12d, -16\n",
            "and r13d, -16\n",
            "sub r12, r10\n",
            "sub r13, r10\n",
            // dxs (rsi), dxl (r14), 64-bit; xa' = xa − 16·ORIGIN + 8 (r10).
            "movsx r10, word ptr [rbp + rsi * 8 + 4]\n",
            "movsx rsi, word ptr [rbp + rdx * 8 + 4]\n",
            "sub rsi, r10\n",
            "movsx r14, word ptr [rbp + rcx * 8 + 4]\n",
            "sub r14, r10\n",
            "add r10d, 16392\n",
            // 16·na = 16·(dz1·dyl − dz2·dys) (rax), 16·nb = 16·(dz2·dxs − dz1·dxl) (r13)
            // and the area
            // dxs·dyl − dxl·dys (rcx; 0: nothing to draw), 64-bit.
            "mov rax, r12\n",
            "imul rax, r11\n",
            "mov rcx, r13\n",
            "imul rcx, r8\n",
            "sub rax, rcx\n",
            "imul r13, rsi\n",
            "imul r12, r14\n",
            "sub r13, r12\n",
            "mov rcx, rsi\n",
            "imul rcx, r11\n",
            "mov r12, r14\n",
            "imul r12, r8\n",
            "sub rcx, r12\n",
            "jz 90f\n",
            "jl 30f\n",
            small_x86_side!($clamp, pos),
            "30:\n",
            small_x86_side!($clamp, neg),
        )
    };
}

/// What [`small_x86`] did.
#[cfg_attr(not(zraster_x86_64), allow(dead_code))]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SmallX86 {
    /// Drawn (perhaps nothing): pixels tested and failed.
    Drawn(u32, u32),
    /// Not for the block (extents of 512 pixels or more, buffers it does not take, no
    /// assembly): nothing drawn.
    Refused,
}

/// Draws the triangle of cache entries `tri` (unmarked) into `t` in `color`: the depth
/// test `Less` with depth writes, as `fill_small_divide` does, where the colour is two
/// bytes and the clip lies inside both buffers.
#[inline(always)]
pub(crate) fn small_x86<C: Copy>(
    t: &mut SmallTarget<'_, '_, C>,
    tri: [&CachedVertex; 3],
    color: C,
) -> SmallX86 {
    match SmallRun::new(t.clip, t.first_row, t.width) {
        Some(mut run) => run.draw(t.z, t.c, tri, color),
        None => SmallX86::Refused,
    }
}

/// [`small_x86`]'s block for a run of triangles into the same buffers and clip: what
/// it works out from them alone (the clip's inside-ness) once.
pub(crate) struct SmallRun {
    #[cfg_attr(not(zraster_x86_64), allow(dead_code))]
    pub(super) b: Block,
    /// The length both buffers must have: every pixel of the clip lies below it.
    #[cfg_attr(not(zraster_x86_64), allow(dead_code))]
    pub(super) need: usize,
}

impl SmallRun {
    /// The block for drawing inside `clip` into buffers of rows `width` pixels long,
    /// the first of them screen row `first_row`, where the assembly runs and the clip
    /// lies inside the rows (its columns within the width, its rows from the first).
    #[inline(always)]
    pub(crate) fn new(clip: Clip, first_row: i32, width: usize) -> Option<SmallRun> {
        let inside = clip.x0 >= 0 && clip.x1 as u32 as usize <= width && clip.y0 >= first_row;
        if !SMALL_X86_KERNEL || !inside || clip.is_empty() || width > 1 << 20 {
            return None;
        }
        // Every pixel of the clip lies below this index (rows fewer than 2³¹).
        let need = (clip.y1 - first_row) as u32 as usize * width;
        let inside_ok = (3..=514).contains(&(clip.x1 - clip.x0));
        Some(SmallRun {
            b: Block {
                rows: [
                    0,
                    0,
                    0,
                    0,
                    (clip.x0 - ORIGIN) as u32,
                    (clip.x1 - ORIGIN) as u32,
                    0,
                    0,
                    0,
                    0,
                    0,
                    0,
                    0,
                    0,
                ],
                pitch: width * 2,
                width: width as isize,
                at: [
                    first_row,
                    clip.x0,
                    clip.y0,
                    clip.x1,
                    clip.y1,
                    0,
                    // The least x of a triangle inside the clip's columns by a pixel, and
                    // how far the greatest lies past it (none for a clip of over 514
                    // columns, whose extents may reach 512 pixels, which the rows without
                    // the clamp do not test, or of under 3).
                    if inside_ok {
                        16 * (clip.x0 + 1)
                    } else {
                        i32::MIN
                    },
                    if inside_ok {
                        16 * (clip.x1 - clip.x0 - 2) - 1
                    } else {
                        0
                    },
                    0,
                    0,
                ],
                ..Block::default()
            },
            need,
        })
    }

    /// The block for `z` and `c` (a two-byte colour's rows, as [`SmallRun::draw`] takes
    /// them), its sums zero: for the fused face loop ([`faces_x86`](super::faces_x86)).
    /// `None` where the buffers do not reach past the clip's last row.
    #[cfg_attr(not(zraster_x86_64), allow(dead_code))]
    #[inline(always)]
    pub(super) fn block_for(&self, z: &mut [u16], c: &mut [u16]) -> Option<Block> {
        if z.len().min(c.len()) < self.need {
            return None;
        }
        let mut b = self.b.clone();
        b.zbase = b.origin(z);
        b.delta = (c.as_mut_ptr() as isize).wrapping_sub(z.as_mut_ptr() as isize);
        b.tested = 0;
        b.failed = 0;
        Some(b)
    }

    /// [`small_x86`] of `tri` in `color` into `z` and `c`, which hold the clip of the
    /// block (refused otherwise).
    #[inline(always)]
    pub(crate) fn draw<C: Copy>(
        &mut self,
        z: &mut [u16],
        c: &mut [C],
        tri: [&CachedVertex; 3],
        color: C,
    ) -> SmallX86 {
        let Some((c, bits)) = super::rows::as_u16(c, color) else {
            return SmallX86::Refused;
        };
        if z.len().min(c.len()) < self.need {
            return SmallX86::Refused;
        }
        self.run(z, c, bits, tri)
    }

    /// The assembly block.
    #[inline(always)]
    fn run(
        &mut self,
        z: &mut [u16],
        c: &mut [u16],
        bits: u16,
        tri: [&CachedVertex; 3],
    ) -> SmallX86 {
        #[cfg(zraster_x86_64)]
        {
            let b = &mut self.b;
            b.zbase = b.origin(z);
            b.delta = (c.as_mut_ptr() as isize).wrapping_sub(z.as_mut_ptr() as isize);
            b.tested = 0;
            b.failed = 0;
            b.rows[13] = u32::from(bits);
            let refused: usize;
            // The entries side by side: the body reads them by index from one address.
            let entries = [*tri[0], *tri[1], *tri[2]];
            // SAFETY: reads the three entries of `entries` (8 bytes each: the depth at 0, x
            // and y at 4 and 6; indices 0, 1 and 2 from its address, in rbp while the body
            // runs, rbp saved in `b` and restored) and reads and writes `b` (`repr(C)`,
            // offsets asserted above). The
            // rows are those `fill_small_divide` draws: screen rows start..end inside the
            // clip's y0..y1, each of its pixels at a column inside the clip's x0..x1 (the
            // row's columns clamped to them). `SmallRun::new` has checked that the clip lies
            // inside the rows (columns within the width, rows from `first_row`) and `draw`
            // that `z` and `c` reach `need`, past the clip's last row: every depth written
            // (at `zbase` + row · pitch + 2 · (column − ORIGIN), `zbase` the address of
            // screen column ORIGIN of row 0 for these rows) and colour `delta` bytes on lies
            // inside them. The divisors:
            // |area| ≠ 0 (tested), an edge's dy > 0 on the rows it bounds. Clobbers rax,
            // rcx, rdx, rsi, r8–r15 and the flags; rbp restored; no stack.
            unsafe {
                core::arch::asm!(
                    // rbp (not an operand) kept in the block's spare word at 24 while
                    // it holds the entries' address.
                    "mov qword ptr [rdi + 24], rbp",
                    "mov rbp, rax",
                    small_x86_body!(),
                    "91:",
                    "mov esi, 1",
                    "jmp 92f",
                    "90:",
                    "xor esi, esi",
                    "92:",
                    "mov rbp, qword ptr [rdi + 24]",
                    in("rdi") &raw mut *b,
                    inout("rax") entries.as_ptr() => _,
                    out("rsi") refused,
                    inout("rdx") 1usize => _,
                    inout("rcx") 2usize => _,
                    out("r8") _,
                    out("r9") _,
                    out("r10") _,
                    out("r11") _,
                    out("r12") _,
                    out("r13") _,
                    out("r14") _,
                    inout("r15") 0usize => _,
                    options(nostack),
                );
            }
            if refused != 0 {
                return SmallX86::Refused;
            }
            // A triangle of extents below 512 pixels tests fewer than 2³² pixels.
            let (tested, failed) = b.counts();
            return SmallX86::Drawn(tested as u32, failed as u32);
        }
        #[allow(unreachable_code)]
        {
            let _ = (tri, z, c, bits);
            SmallX86::Refused
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::cull::XyWord;
    use super::*;
    use std::vec;

    /// `fill_small_divide`'s pixels written out plainly (64-bit, a division a pixel
    /// column): corners sorted by y, rows whose centres lie in `[ya, yc)` inside the
    /// clip, each row between the first columns on or right of its left and right
    /// edges (`⌈T/16dy⌉`), the depth planes' steps by floored divisions from the first
    /// corner, a row's first depth clamped to the corners'. `None` for extents of 512
    /// pixels or more.
    fn reference(
        z: &mut [u16],
        c: &mut [u16],
        (width, first_row, clip): (usize, i32, Clip),
        tri: [(i32, i32, u32); 3],
        color: u16,
    ) -> Option<(u32, u32)> {
        let mut v = tri;
        if v[1].1 < v[0].1 {
            v.swap(0, 1);
        }
        if v[2].1 < v[1].1 {
            v.swap(1, 2);
        }
        if v[1].1 < v[0].1 {
            v.swap(0, 1);
        }
        let [a, m, e] = v.map(|(x, y, z)| (i64::from(x), i64::from(y), z));
        let xs = [a.0, m.0, e.0];
        let (xmin, xmax) = (*xs.iter().min()?, *xs.iter().max()?);
        if e.1 - a.1 >= 8192 || xmax - xmin >= 8192 {
            return None;
        }
        let centre = |y: i64| (y + 7) >> 4;
        let (start, end) = (
            centre(a.1).max(clip.y0.into()),
            centre(e.1).min(clip.y1.into()),
        );
        if start >= end {
            return Some((0, 0));
        }
        let mid = centre(m.1).clamp(start, end);
        let (dxl, dyl, dxs, dys) = (e.0 - a.0, e.1 - a.1, m.0 - a.0, m.1 - a.1);
        let area = dxs * dyl - dxl * dys;
        if area == 0 {
            return Some((0, 0));
        }
        let zq = |p: (i64, i64, u32)| i64::from(p.2 >> 4);
        let (dz1, dz2) = (zq(m) - zq(a), zq(e) - zq(a));
        let floor = |n: i64| (n * area.signum()).div_euclid(area.abs());
        let q = floor(16 * (dz1 * dyl - dz2 * dys)) as u32;
        let r = floor(16 * (dz2 * dxs - dz1 * dxl)) as u32;
        let (sx, sy) = (q << 4, r << 4);
        let zs = [a.2, m.2, e.2];
        let lo = zs.iter().min()?.wrapping_add(1 << 15);
        let hi = zs.iter().max()?.wrapping_add(1 << 15);
        let (x0, y0, z0) = tri[0];
        // The first edge column of row py on or right of the edge u → l (dy > 0).
        let column = |u: (i64, i64, u32), l: (i64, i64, u32), py: i64| {
            let (dx, dy) = (l.0 - u.0, l.1 - u.1);
            let t = (16 * py + 8 - u.1) * dx + (u.0 - 8) * dy;
            -(-t).div_euclid(16 * dy)
        };
        let (mut tested, mut failed) = (0, 0);
        for py in start..end {
            let short = if py < mid { (a, m) } else { (m, e) };
            let (long, short) = (column(a, e, py), column(short.0, short.1, py));
            let (cl, cr) = if area > 0 {
                (long, short)
            } else {
                (short, long)
            };
            let (cl, cr) = (cl.max(clip.x0.into()), cr.min(clip.x1.into()));
            if cl >= cr {
                continue;
            }
            // The depth at screen column 0 of the row, then at column cl.
            let zrow = z0
                .wrapping_add(1 << 15)
                .wrapping_add(q.wrapping_mul(8u32.wrapping_sub(x0 as u32)))
                .wrapping_add(r.wrapping_mul((16 * py as i32 + 8 - y0) as u32));
            let mut acc = zrow
                .wrapping_add((cl as u32).wrapping_mul(sx))
                .max(lo)
                .min(hi);
            let _ = sy;
            for px in cl..cr {
                let i = (py - i64::from(first_row)) as usize * width + px as usize;
                let d = (acc >> 16) as u16;
                if d < z[i] {
                    z[i] = d;
                    c[i] = color;
                } else {
                    failed += 1;
                }
                acc = acc.wrapping_add(sx);
            }
            tested += (cr - cl) as u32;
        }
        Some((tested, failed))
    }

    /// `small_x86` (the set-up and rows of the fused face loop) draws what
    /// [`reference`] draws: 250,000 random triangles, most of them a few pixels across
    /// like the bunny's, some up to 700 (from 512 on refused, nothing drawn), in clips of
    /// every side and width (1 to 3 columns and over 514: the rows with the clamp), in
    /// buffers from screen row 0 to 5.
    #[test]
    fn small_x86_draws_the_reference_triangle() {
        let mut rnd = crate::num::kernel::xorshift32(0x5eed_1234);
        let mut drawn = 0;
        for i in 0..250_000u32 {
            let mut r = |m: u32| rnd() % m;
            let (width, height) = if i % 16 == 0 { (600, 12) } else { (40, 30) };
            let first_row = r(6) as i32;
            let clip = match i % 8 {
                0 | 1 => Clip {
                    x0: r(12) as i32,
                    y0: first_row + r(8) as i32,
                    x1: width as i32 - r(12) as i32,
                    y1: first_row + height - r(8) as i32,
                },
                2 => {
                    let x0 = r(width as u32 - 3) as i32;
                    Clip {
                        x0,
                        y0: first_row,
                        x1: x0 + 1 + r(3) as i32,
                        y1: first_row + height,
                    }
                }
                _ => Clip {
                    x0: 0,
                    y0: first_row,
                    x1: width as i32,
                    y1: first_row + height,
                },
            };
            let span = [2, 3, 5, 8, 12, 40, 700][r(7) as usize] * 16;
            let (cx, cy) = (
                r(16 * width as u32 + 64) as i32 - 32,
                16 * first_row + r(16 * height as u32 + 64) as i32 - 32,
            );
            let mut corner = || {
                let x = cx + r(span) as i32 - span as i32 / 2;
                let y = cy + r(span) as i32 - span as i32 / 2;
                // Depths anywhere, or close together (the clamp then bites).
                let z = if i % 3 == 0 {
                    r(u32::MAX)
                } else {
                    0x4000_0000 + r(1 << 20)
                };
                (x, y, z)
            };
            let tri = [corner(), corner(), corner()];
            let len = width * height as usize;
            let depth: vec::Vec<u16> = (0..len)
                .map(|k| ((k as u32).wrapping_mul(2_654_435_761) >> 16) as u16)
                .collect();
            let (mut zw, mut cw) = (depth.clone(), vec![0u16; len]);
            let want = reference(&mut zw, &mut cw, (width, first_row, clip), tri, 0x1234);
            let entries = tri.map(|(x, y, z)| CachedVertex {
                z,
                xy: XyWord::new(x as i16, y as i16),
            });
            let (mut zg, mut cg) = (depth.clone(), vec![0u16; len]);
            let Some(mut run) = SmallRun::new(clip, first_row, width) else {
                assert!(!SMALL_X86_KERNEL || clip.is_empty(), "{clip:?}");
                continue;
            };
            let got = run.draw(&mut zg, &mut cg, entries.each_ref(), 0x1234u16);
            let got = match got {
                SmallX86::Drawn(t, f) => Some((t, f)),
                SmallX86::Refused => None,
            };
            if !SMALL_X86_KERNEL {
                assert_eq!(got, None);
                continue;
            }
            assert_eq!(got, want, "triangle {i}: {tri:?} in {clip:?}");
            assert!(zg == zw && cg == cw, "triangle {i}: {tri:?} in {clip:?}");
            drawn += usize::from(got.is_some_and(|(t, _)| t > 0));
        }
        assert!(!SMALL_X86_KERNEL || drawn > 100_000, "{drawn} drawn");
    }
}
