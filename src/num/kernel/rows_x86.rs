//! The rows of a small flat triangle on x86-64 in one assembly loop: two edges by one
//! unsigned division a row each (the `EdgeDivide` form), the columns clamped to the
//! clip's, the row's first depth clamped to the corners', then the pixels (`Less` with
//! depth writes, a two-byte colour). Its portable twin is the Rust row loop of
//! `fill::small` (`rows_divide`), which the renderer runs on every other target and
//! for any rows this loop refuses; a host test compares the two.
#![allow(unsafe_code)]

/// Whether [`rows_x86`] runs the assembly loop (x86-64); elsewhere it refuses every
/// call.
pub(crate) const ROWS_X86_KERNEL: bool = cfg!(zraster_x86_64);

/// What the loop reads at the offsets in the comments (and the counts it adds to).
#[cfg_attr(not(zraster_x86_64), allow(dead_code))]
#[repr(C)]
struct Block {
    /// The depth's step a column and a row, the clamp of a row's first depth.
    sx: u32, // 0
    sy: u32, // 4
    lo: u32, // 8
    hi: u32, // 12
    /// The clip's columns, local (the first at least 0).
    cx0: i32, // 16
    cx1: i32, // 20
    /// The left and right edges' steps of `t` a row.
    dtl: u32, // 24
    dtr: u32, // 28
    tested: u32, // 32
    failed: u32, // 36
    /// Rows left.
    n: i32, // 40
    /// The left and right edges' divisors.
    dl: u32, // 44
    dr: u32, // 48
    /// Bytes from one row to the next.
    pitch: usize, // 56
}

#[cfg(target_pointer_width = "64")]
const _: () = {
    use core::mem::offset_of;
    assert!(offset_of!(Block, cx0) == 16 && offset_of!(Block, dtl) == 24);
    assert!(offset_of!(Block, tested) == 32 && offset_of!(Block, n) == 40);
    assert!(offset_of!(Block, dl) == 44 && offset_of!(Block, dr) == 48);
    assert!(offset_of!(Block, pitch) == 56);
};

/// One edge of the rows: `t`, its step a row and its divisor (a row's column is
/// `t / d`, as `EdgeDivide` has it).
pub(crate) type Edge<'e> = (&'e mut u32, u32, u32);

/// The depth plane of the rows: the steps a column and a row and the clamp of a row's
/// first depth (`Depth` of `fill::small`).
pub(crate) type Steps = [u32; 4];

/// Draws `n` rows (`n ≥ 1`) between the `left` and `right` edges, as the row loop of
/// `fill::small` does for `Less` with depth writes: the row's columns
/// `max(left, cx0)..min(right, cx1)`, its first depth `zrow + x·sx` clamped to
/// `lo..=hi`, each row `width` pixels below the last; local column 0 of the first row
/// at index `base` (wrapping) of `z` and `c` (a two-byte colour, else `None`). On
/// return the edges, `zrow` and `base` are the twin's after the rows and the result is
/// (pixels tested, pixels failed). `None` (nothing drawn, nothing moved) where every
/// pixel the rows may touch does not lie inside both buffers, or without the loop.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn rows_x86<C: Copy>(
    (left, right): (Edge<'_>, Edge<'_>),
    n: i32,
    [sx, sy, lo, hi]: Steps,
    (cx0, cx1): (i32, i32),
    (zrow, base, width): (&mut u32, &mut usize, usize),
    z: &mut [u16],
    c: &mut [C],
    color: C,
) -> Option<(u32, u32)> {
    if !ROWS_X86_KERNEL {
        return None;
    }
    let (c, color) = super::rows::as_u16(c, color)?;
    // The loop keeps every column at cx0 or right of it: from 0 (an edge's column, an
    // unsigned quotient, is never negative on its rows; this only bounds the writes).
    let cx0 = cx0.max(0);
    // Every pixel the rows may touch lies between local column cx0 of the first row
    // and column cx1 of the last (exclusive).
    let len = z.len().min(c.len()) as i64;
    let (b0, w) = (*base as isize as i64, width as i64);
    let first = b0 + i64::from(cx0);
    let last = b0 + i64::from(n - 1) * w + i64::from(cx1);
    if n < 1 || cx1 <= cx0 || first < 0 || last > len || w > 1 << 20 {
        return None;
    }
    #[cfg(zraster_x86_64)]
    {
        let (tl, dtl, dl) = left;
        let (tr, dtr, dr) = right;
        let mut b = Block {
            sx,
            sy,
            lo,
            hi,
            cx0,
            cx1,
            dtl,
            dtr,
            tested: 0,
            failed: 0,
            n,
            dl,
            dr,
            pitch: width * 2,
        };
        let p = z.as_mut_ptr().wrapping_add(*base);
        let delta = (c.as_mut_ptr() as isize).wrapping_sub(z.as_mut_ptr() as isize);
        let (mut t0, mut t1, mut zr, mut at) = (*tl, *tr, *zrow, p);
        // SAFETY: reads and writes `b` (`repr(C)`, the offsets asserted above). Row k
        // (0 ≤ k < n) writes the depths at `p + 2·(k·width + x)` and the colours `delta`
        // bytes on, for the columns x of max(left, cx0)..min(right, cx1), cx0 ≥ 0: all
        // of index base + cx0 or above and below base + (n − 1)·width + cx1, which the
        // test above puts inside both slices (`c` and `z` of at least `len` u16s, the
        // colours at the same index `delta` bytes from the depths). The divisors are the
        // edges' 16·dy > 0 on their rows (as the twin divides by them). Clobbers rax,
        // rdx and the flags; no stack.
        unsafe {
            core::arch::asm!(
                "2:",
                "mov eax, {tl:e}",
                "xor edx, edx",
                "div dword ptr [{b} + 44]",
                "cmp eax, dword ptr [{b} + 16]",
                "cmovl eax, dword ptr [{b} + 16]",
                "movsxd {x}, eax",
                "mov eax, {tr:e}",
                "xor edx, edx",
                "div dword ptr [{b} + 48]",
                "cmp eax, dword ptr [{b} + 20]",
                "cmovg eax, dword ptr [{b} + 20]",
                "add {tl:e}, dword ptr [{b} + 24]",
                "add {tr:e}, dword ptr [{b} + 28]",
                "sub eax, {x:e}",
                "jle 5f",
                "add dword ptr [{b} + 32], eax",
                "mov edx, {x:e}",
                "imul edx, dword ptr [{b}]",
                "add edx, {zr:e}",
                "cmp edx, dword ptr [{b} + 8]",
                "cmovb edx, dword ptr [{b} + 8]",
                "cmp edx, dword ptr [{b} + 12]",
                "cmova edx, dword ptr [{b} + 12]",
                "lea {x}, [{p} + {x} * 2]",
                "3:",
                "mov {v:e}, edx",
                "shr {v:e}, 16",
                "cmp {v:x}, word ptr [{x}]",
                "jae 6f",
                "mov word ptr [{x}], {v:x}",
                "mov word ptr [{x} + {dc}], {col:x}",
                "4:",
                "add edx, dword ptr [{b}]",
                "add {x}, 2",
                "dec eax",
                "jnz 3b",
                "5:",
                "add {zr:e}, dword ptr [{b} + 4]",
                "add {p}, qword ptr [{b} + 56]",
                "dec dword ptr [{b} + 40]",
                "jnz 2b",
                "jmp 7f",
                "6:",
                "inc dword ptr [{b} + 36]",
                "jmp 4b",
                "7:",
                b = in(reg) &raw mut b,
                tl = inout(reg) t0,
                tr = inout(reg) t1,
                zr = inout(reg) zr,
                p = inout(reg) at,
                dc = in(reg) delta,
                col = in(reg) u32::from(color),
                x = out(reg) _,
                v = out(reg) _,
                out("eax") _,
                out("edx") _,
                options(nostack),
            );
        }
        (*tl, *tr, *zrow) = (t0, t1, zr);
        *base = base.wrapping_add((n as usize).wrapping_mul(width));
        let _ = at;
        return Some((b.tested, b.failed));
    }
    #[allow(unreachable_code)]
    {
        let _ = (left, right, sx, sy, lo, hi, zrow, color);
        None
    }
}
