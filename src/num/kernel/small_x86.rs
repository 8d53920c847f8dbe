//! A small flat triangle read from the vertex cache, set-up and rows, in one x86-64
//! assembly block: the corners sorted by y, the extents tested, the clip's rows, the
//! edges in the `EdgeDivide` form, the depth steps by two 64-bit unsigned divisions
//! with the signs folded in, the first row's depth, then both halves' rows (the loop of
//! [`rows_x86`](super::rows_x86)). Its portable twin is `fill::small`'s
//! `fill_small_divide` (set-up and `rows_divide`), which the renderer runs on other
//! targets and for what this block refuses; a host test compares the two.
#![allow(unsafe_code)]

use super::rows::SmallTarget;
use super::CachedVertex;
use crate::raster::Clip;

/// Whether [`small_x86`] runs the assembly (x86-64); elsewhere it refuses every call.
pub(crate) const SMALL_X86_KERNEL: bool = cfg!(zraster_x86_64);

/// The block the assembly reads and writes, at the offsets in the comments: the rows'
/// operands (as [`rows_x86`](super::rows_x86)'s), the buffers and the clip, the lower
/// half's short edge, and the set-up's values kept for later.
#[cfg_attr(not(zraster_x86_64), allow(dead_code))]
#[derive(Default)]
#[repr(C)]
struct Block {
    rows: [u32; 14], // 0: sx, sy, lo, hi, cx0, cx1, dtl, dtr, tested, failed, n, dl, dr, color
    pitch: usize,    // 56
    zbase: usize,    // 64
    delta: isize,    // 72
    width: isize,    // 80
    /// First row, clip x0, y0, x1, y1, lower rows, spare.
    at: [i32; 10], // 88
    /// dxl, dyl, dxs, dys, area, start, mid, n0, px0, ya, ym, xa', q, r.
    set: [i32; 14], // 128
}

#[cfg(target_pointer_width = "64")]
const _: () = {
    use core::mem::offset_of;
    assert!(offset_of!(Block, pitch) == 56 && offset_of!(Block, zbase) == 64);
    assert!(offset_of!(Block, delta) == 72 && offset_of!(Block, width) == 80);
    assert!(offset_of!(Block, at) == 88 && offset_of!(Block, set) == 128);
};

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
    b: Block,
    /// The length both buffers must have: every pixel of the clip lies below it.
    #[cfg_attr(not(zraster_x86_64), allow(dead_code))]
    need: usize,
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
        Some(SmallRun {
            b: Block {
                pitch: width * 2,
                width: width as isize,
                at: [first_row, clip.x0, clip.y0, clip.x1, clip.y1, 0, 0, 0, 0, 0],
                ..Block::default()
            },
            need,
        })
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
            b.zbase = z.as_mut_ptr() as usize;
            b.delta = (c.as_mut_ptr() as isize).wrapping_sub(z.as_mut_ptr() as isize);
            b.rows[8] = 0;
            b.rows[9] = 0;
            b.rows[13] = u32::from(bits);
            let refused: usize;
            // SAFETY: reads the three cache entries (8 bytes each: the depth at 0, x and y
            // at 4 and 6) and reads and writes `b` (`repr(C)`, offsets asserted above). The
            // rows are those `fill_small_divide` draws: screen rows start..end inside the
            // clip's y0..y1, each of its pixels at a column inside the clip's x0..x1 (the
            // row's columns clamped to them). `SmallRun::new` has checked that the clip lies
            // inside the rows (columns within the width, rows from `first_row`) and `draw`
            // that `z` and `c` reach `need`, past the clip's last row: every depth written at
            // `zbase + 2·index` and colour `delta` bytes on lies inside them. The divisors:
            // |area| ≠ 0 (tested), an edge's 16·dy > 0 on the rows it bounds. Clobbers rax,
            // rcx, rdx, rsi, r8–r15 and the flags; no stack.
            unsafe {
                core::arch::asm!(
                    // Extents in x (the corners in any order): 512 pixels or more refused;
                    // px0 = xmin >> 4.
                    "movsx eax, word ptr [rsi + 4]",
                    "movsx r8d, word ptr [rdx + 4]",
                    "movsx r9d, word ptr [rcx + 4]",
                    "mov r10d, eax",
                    "cmp r8d, r10d",
                    "cmovl r10d, r8d",
                    "cmp r9d, r10d",
                    "cmovl r10d, r9d",
                    "mov r11d, eax",
                    "cmp r8d, r11d",
                    "cmovg r11d, r8d",
                    "cmp r9d, r11d",
                    "cmovg r11d, r9d",
                    "sub r11d, r10d",
                    "cmp r11d, 8191",
                    "jg 91f",
                    "sar r10d, 4",
                    "mov dword ptr [rdi + 160], r10d",
                    // p0 kept; a, m, c sorted by y (stable, as `by_rows`).
                    "mov r15, rsi",
                    "movsx eax, word ptr [rsi + 6]",
                    "movsx r8d, word ptr [rdx + 6]",
                    "cmp r8d, eax",
                    "jge 21f",
                    "xchg rsi, rdx",
                    "xchg eax, r8d",
                    "21:",
                    "movsx r9d, word ptr [rcx + 6]",
                    "cmp r9d, r8d",
                    "jge 22f",
                    "xchg rdx, rcx",
                    "xchg r8d, r9d",
                    "22:",
                    "cmp r8d, eax",
                    "jge 23f",
                    "xchg rsi, rdx",
                    "xchg eax, r8d",
                    "23:",
                    // dyl = yc − ya (refused from 8192); start, end, mid.
                    "mov r11d, r9d",
                    "sub r11d, eax",
                    "cmp r11d, 8191",
                    "jg 91f",
                    "mov dword ptr [rdi + 132], r11d",
                    "lea r12d, [rax + 7]",
                    "sar r12d, 4",
                    "cmp r12d, dword ptr [rdi + 96]",
                    "cmovl r12d, dword ptr [rdi + 96]",
                    "lea r13d, [r9 + 7]",
                    "sar r13d, 4",
                    "cmp r13d, dword ptr [rdi + 104]",
                    "cmovg r13d, dword ptr [rdi + 104]",
                    "cmp r12d, r13d",
                    "jge 90f",
                    "lea r14d, [r8 + 7]",
                    "sar r14d, 4",
                    "cmp r14d, r12d",
                    "cmovl r14d, r12d",
                    "cmp r14d, r13d",
                    "cmovg r14d, r13d",
                    "mov dword ptr [rdi + 148], r12d",
                    "mov dword ptr [rdi + 152], r14d",
                    "sub r13d, r14d",
                    "mov dword ptr [rdi + 108], r13d",
                    "mov r13d, r14d",
                    "sub r13d, r12d",
                    "mov dword ptr [rdi + 156], r13d",
                    "mov dword ptr [rdi + 164], eax",
                    "mov dword ptr [rdi + 168], r8d",
                    // dys; dxl, dxs; area (0: nothing to draw).
                    "mov r9d, r8d",
                    "sub r9d, eax",
                    "mov dword ptr [rdi + 140], r9d",
                    "movsx r12d, word ptr [rsi + 4]",
                    "movsx r13d, word ptr [rdx + 4]",
                    "movsx r14d, word ptr [rcx + 4]",
                    "sub r14d, r12d",
                    "mov dword ptr [rdi + 128], r14d",
                    "sub r13d, r12d",
                    "mov dword ptr [rdi + 136], r13d",
                    "imul r11d, r13d",
                    "imul r9d, r14d",
                    "sub r11d, r9d",
                    "jz 90f",
                    "mov dword ptr [rdi + 144], r11d",
                    // xa' = xa − 16·px0 + 8.
                    "mov r9d, r10d",
                    "shl r9d, 4",
                    "sub r12d, r9d",
                    "add r12d, 8",
                    "mov dword ptr [rdi + 172], r12d",
                    // The depths: lo, hi (biased), dz₁, dz₂ of z >> 4.
                    "mov eax, dword ptr [rsi]",
                    "mov r8d, dword ptr [rdx]",
                    "mov r9d, dword ptr [rcx]",
                    "mov r12d, eax",
                    "cmp r8d, r12d",
                    "cmovb r12d, r8d",
                    "cmp r9d, r12d",
                    "cmovb r12d, r9d",
                    "add r12d, 32768",
                    "mov dword ptr [rdi + 8], r12d",
                    "mov r12d, eax",
                    "cmp r8d, r12d",
                    "cmova r12d, r8d",
                    "cmp r9d, r12d",
                    "cmova r12d, r9d",
                    "add r12d, 32768",
                    "mov dword ptr [rdi + 12], r12d",
                    "shr eax, 4",
                    "shr r8d, 4",
                    "shr r9d, 4",
                    "sub r8d, eax",
                    "sub r9d, eax",
                    "movsxd rax, r8d",
                    "movsxd r8, r9d",
                    // na = dz₁·dyl − dz₂·dys, nb = dz₂·dxs − dz₁·dxl (64-bit).
                    "movsxd r9, dword ptr [rdi + 132]",
                    "imul r9, rax",
                    "movsxd r12, dword ptr [rdi + 140]",
                    "imul r12, r8",
                    "sub r9, r12",
                    "movsxd r12, r13d",
                    "imul r12, r8",
                    "movsxd r13, r14d",
                    "imul r13, rax",
                    "sub r12, r13",
                    // ⌊16n/area⌋ = ⌊±16n/|area|⌋ = s ^ ⌊(k ^ s)/|area|⌋ (k = ±16n, s its sign).
                    "movsxd r13, r11d",
                    "mov r14, r13",
                    "sar r14, 63",
                    "xor r13, r14",
                    "sub r13, r14",
                    "shl r9, 4",
                    "xor r9, r14",
                    "sub r9, r14",
                    "shl r12, 4",
                    "xor r12, r14",
                    "sub r12, r14",
                    "mov rax, r9",
                    "sar r9, 63",
                    "xor rax, r9",
                    "xor edx, edx",
                    "div r13",
                    "xor rax, r9",
                    "mov dword ptr [rdi + 176], eax",
                    "shl eax, 4",
                    "mov dword ptr [rdi], eax",
                    "mov rax, r12",
                    "sar r12, 63",
                    "xor rax, r12",
                    "xor edx, edx",
                    "div r13",
                    "xor rax, r12",
                    "mov dword ptr [rdi + 180], eax",
                    "shl eax, 4",
                    "mov dword ptr [rdi + 4], eax",
                    // The first row's depth at local column 0, from p0:
                    // z + bias + q·(8 − (x − 16·px0)) + r·(8 − (y − 16·start)).
                    "movsx eax, word ptr [r15 + 4]",
                    "mov r9d, dword ptr [rdi + 160]",
                    "shl r9d, 4",
                    "sub r9d, eax",
                    "add r9d, 8",
                    "imul r9d, dword ptr [rdi + 176]",
                    "movsx eax, word ptr [r15 + 6]",
                    "mov r12d, dword ptr [rdi + 148]",
                    "shl r12d, 4",
                    "sub r12d, eax",
                    "add r12d, 8",
                    "imul r12d, dword ptr [rdi + 180]",
                    "add r9d, r12d",
                    "add r9d, dword ptr [r15]",
                    "add r9d, 32768",
                    "mov r10d, r9d",
                    // The edges: s0 = 16·start + 8 − ya; long t = s0·dxl + xa'·dyl − 1,
                    // short t = s0·dxs + xa'·dys − 1.
                    "mov r9d, dword ptr [rdi + 148]",
                    "shl r9d, 4",
                    "add r9d, 8",
                    "sub r9d, dword ptr [rdi + 164]",
                    "mov r12d, r9d",
                    "imul r12d, dword ptr [rdi + 128]",
                    "mov r13d, dword ptr [rdi + 172]",
                    "imul r13d, dword ptr [rdi + 132]",
                    "lea r12d, [r12 + r13 - 1]",
                    "mov r13d, r9d",
                    "imul r13d, dword ptr [rdi + 136]",
                    "mov r14d, dword ptr [rdi + 172]",
                    "imul r14d, dword ptr [rdi + 140]",
                    "lea r13d, [r13 + r14 - 1]",
                    // The first row's address; the clip's columns, local.
                    "mov r9d, dword ptr [rdi + 148]",
                    "sub r9d, dword ptr [rdi + 88]",
                    "movsxd r9, r9d",
                    "imul r9, qword ptr [rdi + 80]",
                    "movsxd rdx, dword ptr [rdi + 160]",
                    "add r9, rdx",
                    "mov r11, qword ptr [rdi + 64]",
                    "lea r11, [r11 + r9 * 2]",
                    "mov edx, dword ptr [rdi + 92]",
                    "sub edx, dword ptr [rdi + 160]",
                    "mov dword ptr [rdi + 16], edx",
                    "mov edx, dword ptr [rdi + 100]",
                    "sub edx, dword ptr [rdi + 160]",
                    "mov dword ptr [rdi + 20], edx",
                    // Sides: with the middle corner right of the long edge (area > 0) the
                    // long edge is the left one (r8), else the right one (r9).
                    "mov eax, dword ptr [rdi + 128]",
                    "shl eax, 4",
                    "mov edx, dword ptr [rdi + 132]",
                    "shl edx, 4",
                    "mov r14d, dword ptr [rdi + 136]",
                    "shl r14d, 4",
                    "mov r15d, dword ptr [rdi + 140]",
                    "shl r15d, 4",
                    "cmp dword ptr [rdi + 144], 0",
                    "jle 31f",
                    "mov r8d, r12d",
                    "mov r9d, r13d",
                    "mov dword ptr [rdi + 24], eax",
                    "mov dword ptr [rdi + 44], edx",
                    "mov dword ptr [rdi + 28], r14d",
                    "mov dword ptr [rdi + 48], r15d",
                    "jmp 32f",
                    "31:",
                    "mov r8d, r13d",
                    "mov r9d, r12d",
                    "mov dword ptr [rdi + 24], r14d",
                    "mov dword ptr [rdi + 44], r15d",
                    "mov dword ptr [rdi + 28], eax",
                    "mov dword ptr [rdi + 48], edx",
                    "32:",
                    "mov r14d, dword ptr [rdi + 52]",
                    "mov r15, qword ptr [rdi + 72]",
                    // The upper half (ecx 1: the lower one still to come).
                    "mov ecx, 1",
                    "mov eax, dword ptr [rdi + 156]",
                    "test eax, eax",
                    "jle 40f",
                    "mov dword ptr [rdi + 40], eax",
                    // The rows (`rows_x86`'s loop).
                    "2:",
                    "mov eax, r8d",
                    "xor edx, edx",
                    "div dword ptr [rdi + 44]",
                    "cmp eax, dword ptr [rdi + 16]",
                    "cmovl eax, dword ptr [rdi + 16]",
                    "movsxd r12, eax",
                    "mov eax, r9d",
                    "xor edx, edx",
                    "div dword ptr [rdi + 48]",
                    "cmp eax, dword ptr [rdi + 20]",
                    "cmovg eax, dword ptr [rdi + 20]",
                    "add r8d, dword ptr [rdi + 24]",
                    "add r9d, dword ptr [rdi + 28]",
                    "sub eax, r12d",
                    "jle 5f",
                    "add dword ptr [rdi + 32], eax",
                    "mov edx, r12d",
                    "imul edx, dword ptr [rdi]",
                    "add edx, r10d",
                    "cmp edx, dword ptr [rdi + 8]",
                    "cmovb edx, dword ptr [rdi + 8]",
                    "cmp edx, dword ptr [rdi + 12]",
                    "cmova edx, dword ptr [rdi + 12]",
                    "lea r12, [r11 + r12 * 2]",
                    "3:",
                    "mov r13d, edx",
                    "shr r13d, 16",
                    "cmp r13w, word ptr [r12]",
                    "jae 6f",
                    "mov word ptr [r12], r13w",
                    "mov word ptr [r12 + r15], r14w",
                    "4:",
                    "add edx, dword ptr [rdi]",
                    "add r12, 2",
                    "dec eax",
                    "jnz 3b",
                    "5:",
                    "add r10d, dword ptr [rdi + 4]",
                    "add r11, qword ptr [rdi + 56]",
                    "dec dword ptr [rdi + 40]",
                    "jnz 2b",
                    "test ecx, ecx",
                    "jz 90f",
                    // The lower half: the short edge replaced on its side.
                    "40:",
                    "xor ecx, ecx",
                    "mov eax, dword ptr [rdi + 108]",
                    "test eax, eax",
                    "jle 90f",
                    "mov dword ptr [rdi + 40], eax",
                    // Its short edge (only now: the rows' registers r8–r11, r14, r15 kept):
                    // s1 = 16·mid + 8 − ym, from xa' + dxs, by (dxl − dxs, dyl − dys);
                    // t in r12, its step in r13, its divisor in esi.
                    "mov r12d, dword ptr [rdi + 152]",
                    "shl r12d, 4",
                    "add r12d, 8",
                    "sub r12d, dword ptr [rdi + 168]",
                    "mov r13d, dword ptr [rdi + 128]",
                    "sub r13d, dword ptr [rdi + 136]",
                    "imul r12d, r13d",
                    "shl r13d, 4",
                    "mov esi, dword ptr [rdi + 132]",
                    "sub esi, dword ptr [rdi + 140]",
                    "mov edx, dword ptr [rdi + 172]",
                    "add edx, dword ptr [rdi + 136]",
                    "imul edx, esi",
                    "lea r12d, [r12 + rdx - 1]",
                    "shl esi, 4",
                    "cmp dword ptr [rdi + 144], 0",
                    "jle 41f",
                    "mov r9d, r12d",
                    "mov dword ptr [rdi + 28], r13d",
                    "mov dword ptr [rdi + 48], esi",
                    "jmp 2b",
                    "41:",
                    "mov r8d, r12d",
                    "mov dword ptr [rdi + 24], r13d",
                    "mov dword ptr [rdi + 44], esi",
                    "jmp 2b",
                    "6:",
                    "inc dword ptr [rdi + 36]",
                    "jmp 4b",
                    "91:",
                    "mov esi, 1",
                    "jmp 92f",
                    "90:",
                    "xor esi, esi",
                    "92:",
                    in("rdi") &raw mut *b,
                    inout("rsi") core::ptr::from_ref(tri[0]) as usize => refused,
                    inout("rdx") core::ptr::from_ref(tri[1]) => _,
                    inout("rcx") core::ptr::from_ref(tri[2]) => _,
                    out("rax") _,
                    out("r8") _,
                    out("r9") _,
                    out("r10") _,
                    out("r11") _,
                    out("r12") _,
                    out("r13") _,
                    out("r14") _,
                    out("r15") _,
                    options(nostack),
                );
            }
            if refused != 0 {
                return SmallX86::Refused;
            }
            return SmallX86::Drawn(b.rows[8], b.rows[9]);
        }
        #[allow(unreachable_code)]
        {
            let _ = (tri, z, c, bits);
            SmallX86::Refused
        }
    }
}
