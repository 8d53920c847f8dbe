//! The whole frame's face loop of a cached mesh in one Thumb-1 loop on ARMv6-M: the
//! cull scan, the face's Lambert colour in 5-6-5 and a call of the small triangle's
//! set-up and rows (`zraster_small_walk_v6m`), face after face with no Rust between
//! them. Its portable twin is the renderer's own loop (the cull walk, `lit_565` and
//! the set-up), which also takes every face this loop leaves to it.
#![allow(unsafe_code)]

use super::cull::ScanRegs;
use super::faces::{FaceColor, FacesCounts, FacesStop};
use super::{Buffers, CachedVertex};

/// Whether [`faces_less_v6m`] runs the assembly loop (ARMv6-M); elsewhere it leaves
/// every face to the caller.
pub(crate) const FACES_V6M_KERNEL: bool = cfg!(all(zraster_thumb, zraster_armv6m));

/// Faces drawn between the loop's returns to Rust, which moves its 32-bit pixel sums
/// into the 64-bit counts (a small triangle tests < 2^18.01 pixels: no wrap).
#[cfg_attr(not(all(zraster_thumb, zraster_armv6m)), allow(dead_code))]
const FLUSH: u32 = 8192;

/// What the loop reads and writes, at the offsets in the comments: the colour's
/// constants in the order of its LDMs, the normals' place, the scan's place and
/// operands, the set-up's block and the cache, the counts.
#[cfg_attr(not(all(zraster_thumb, zraster_armv6m)), allow(dead_code))]
#[repr(C)]
struct FacesV6m {
    /// The light direction, ambient and diffuse weight (Q15), 2¹² (the term's rounding).
    light: [i32; 3], // 0
    ambient: i32, // 12
    diffuse: i32, // 16
    round: i32,   // 20
    /// Each channel times its depth (31, 63, 31), high field first; ½ · 255 · 2¹⁵; 32897.
    channels: [u32; 3], // 24
    half: u32,    // 36
    k: u32,       // 40
    /// One past the last face with a normal (as a face address), and the normals'
    /// address less the faces' (both 6-byte records).
    nend: u32, // 44
    ndelta: u32,  // 48
    /// The next face's address (in and out), then the scan's operands.
    face: u32, // 52
    xy: u32,      // 56
    len: u32,     // 60
    end: u32,     // 64
    neg_lo: u32,  // 68
    span: u32,    // 72
    /// The set-up's block (its colour at 12, failures at 28), the cache's entries.
    walk: u32, // 76
    entries: u32, // 80
    /// One colour for all: its bits + 2¹⁶, else 0 (lit).
    flat: u32, // 84
    /// Pixels tested; faces left to draw before the next return.
    tested: u32, // 88
    drawn: u32,   // 92
}

#[cfg(target_pointer_width = "32")]
const _: () = {
    use core::mem::offset_of;
    type B = FacesV6m;
    assert!(offset_of!(B, ambient) == 12 && offset_of!(B, round) == 20);
    assert!(offset_of!(B, channels) == 24 && offset_of!(B, k) == 40);
    assert!(offset_of!(B, nend) == 44 && offset_of!(B, ndelta) == 48);
    assert!(offset_of!(B, face) == 52 && offset_of!(B, xy) == 56);
    assert!(offset_of!(B, len) == 60 && offset_of!(B, end) == 64);
    assert!(offset_of!(B, neg_lo) == 68 && offset_of!(B, span) == 72);
    assert!(offset_of!(B, walk) == 76 && offset_of!(B, entries) == 80);
    assert!(offset_of!(B, flat) == 84 && offset_of!(B, tested) == 88);
    assert!(offset_of!(B, drawn) == 92);
};

/// The set-up block's fields the loop writes and reads (`RowsWalk`'s `color` and
/// `failed`, pinned in `rows_v6m`).
#[cfg_attr(not(all(zraster_thumb, zraster_armv6m)), allow(dead_code))]
const WALK_COLOR: usize = 12;
#[cfg_attr(not(all(zraster_thumb, zraster_armv6m)), allow(dead_code))]
const WALK_FAILED: usize = 28;

#[cfg(all(zraster_thumb, zraster_armv6m))]
extern "C" {
    /// The loop over block `b` from its face on: returns 0 when the scan stops (a bad
    /// index, an unplaced corner, or the end: `face` that face), 1 at a drawn face it
    /// leaves to the caller (no normal and no flat colour, or refused by the set-up:
    /// `face` that face), 2 after `FLUSH` drawn faces (`face` the next).
    ///
    /// # Safety
    ///
    /// As [`faces_less_v6m`] builds the block: the scan's operands those of its faces
    /// and cache, the normals inside their slice, `walk` a started set-up block whose
    /// clip lies inside both buffers.
    fn zraster_faces_v6m(b: *mut FacesV6m) -> u32;
}

// SAFETY (for `faces_less_v6m`): the scan is `skip_culled_v6m`'s turn for turn
// (operands in r8–r11 instead of r7/r8/r12/lr): it reads faces from `face` < `end` one
// a turn until `end`, and an entry's x/y word at `xy + 8 i` only for indices found
// below `len`, the cache's length. A drawn face's normal is read at face + `ndelta`
// (three halfwords) only when face < `nend`, the faces' address plus 6 · the normals
// there are (at most the faces'), so only inside the normals' slice. The colour goes
// to the set-up block's `color` (a word), the corners as entries + 8 · index for the
// three indices found below `len`; `zraster_small_walk_v6m`'s contract: a block
// started for buffers whose clip lies inside both (`Buffers::walk_block`). It keeps
// r4–r11 (AAPCS): the scan's operands in r8–r11 and the face in r4 live across it;
// r1 is reloaded. The block is read and written through its address at [sp]; the
// frame is 40 bytes (8-aligned at the call); r4–r11 and lr saved and restored.
#[cfg(all(zraster_thumb, zraster_armv6m))]
core::arch::global_asm!(
    ".pushsection .text.zraster_faces_v6m,\"ax\",%progbits",
    ".balign 4",
    ".global zraster_faces_v6m",
    ".hidden zraster_faces_v6m",
    ".type zraster_faces_v6m, %function",
    ".thumb_func",
    "zraster_faces_v6m:",
    "push {{r4, r5, r6, r7, lr}}",
    "mov r4, r8",
    "mov r5, r9",
    "mov r6, r10",
    "mov r7, r11",
    "push {{r4, r5, r6, r7}}",
    "sub sp, #4",
    "str r0, [sp]",
    // The scan's operands: entries in r8, end in r9, −lo in r10, span in r11.
    "ldr r1, [r0, #60]",
    "mov r8, r1",
    "ldr r1, [r0, #64]",
    "mov r9, r1",
    "ldr r1, [r0, #68]",
    "mov r10, r1",
    "ldr r1, [r0, #72]",
    "mov r11, r1",
    "ldr r1, [r0, #56]",
    "ldr r0, [r0, #52]",
    "cmp r0, r9",
    "bhs 3f",
    // The scan (`skip_culled_v6m`'s turn).
    "2:",
    "ldrh r2, [r0, #0]",
    "ldrh r3, [r0, #2]",
    "ldrh r4, [r0, #4]",
    "cmp r2, r8",
    "bhs 3f",
    "cmp r3, r8",
    "bhs 3f",
    "cmp r4, r8",
    "bhs 3f",
    "lsls r2, r2, #3",
    "lsls r3, r3, #3",
    "lsls r4, r4, #3",
    "ldr r2, [r1, r2]",
    "ldr r3, [r1, r3]",
    "ldr r4, [r1, r4]",
    "lsls r5, r2, #16",
    "adds r5, r5, r5",
    "bvs 3f",
    "lsls r5, r3, #16",
    "adds r5, r5, r5",
    "bvs 3f",
    "lsls r5, r4, #16",
    "adds r5, r5, r5",
    "bvs 3f",
    "subs r5, r3, r2",
    "sxth r5, r5",
    "subs r6, r4, r2",
    "sxth r6, r6",
    "asrs r2, r2, #16",
    "asrs r3, r3, #16",
    "subs r3, r3, r2",
    "asrs r4, r4, #16",
    "subs r4, r4, r2",
    "muls r5, r4, r5",
    "muls r6, r3, r6",
    "subs r5, r5, r6",
    "add r5, r10",
    "cmp r5, r11",
    "bhi 4f",
    "adds r0, #6",
    "cmp r0, r9",
    "bne 2b",
    // Stopped at r0 (a bad index, an unplaced corner, or the end).
    "3:",
    "ldr r7, [sp]",
    "str r0, [r7, #52]",
    "movs r0, #0",
    "b 9f",
    // Drawn (the face in r4): its normal, else the flat colour or the caller's.
    "4:",
    "ldr r7, [sp]",
    "mov r4, r0",
    "ldr r2, [r7, #44]",
    "cmp r0, r2",
    "bhs 5f",
    "ldr r2, [r7, #48]",
    "ldrsh r3, [r0, r2]",
    "adds r0, #2",
    "ldrsh r5, [r0, r2]",
    "adds r0, #2",
    "ldrsh r6, [r0, r2]",
    // n·L (wrapping), at least 0; the term as `lambert_term_narrow`: dot = h·2¹⁶ +
    // m·2⁸ + n, (h·w + ⌊(m·w + ⌊n·w/2⁸⌋)/2⁸⌋ + 2¹²) >> 13; plus ambient.
    "ldm r7!, {{r0, r1, r2}}",
    "muls r3, r0, r3",
    "muls r5, r1, r5",
    "muls r6, r2, r6",
    "adds r3, r3, r5",
    "adds r3, r3, r6",
    "asrs r0, r3, #31",
    "bics r3, r0",
    "ldm r7!, {{r0, r1, r2}}",
    "lsrs r5, r3, #16",
    "muls r5, r1, r5",
    "uxtb r6, r3",
    "muls r6, r1, r6",
    "asrs r6, r6, #8",
    "lsrs r3, r3, #8",
    "uxtb r3, r3",
    "muls r3, r1, r3",
    "adds r3, r3, r6",
    "asrs r3, r3, #8",
    "adds r3, r3, r5",
    "adds r3, r3, r2",
    "asrs r3, r3, #13",
    "adds r3, r3, r0",
    // The intensity clamped to 0..=65535.
    "asrs r0, r3, #31",
    "bics r3, r0",
    "lsrs r0, r3, #16",
    "bne 7f",
    // Each channel min(((i·v + half) >> 15) · 32897 >> 23, max), packed 5-6-5.
    "6:",
    "ldm r7!, {{r0, r1, r2}}",
    "ldm r7!, {{r5, r6}}",
    "muls r0, r3, r0",
    "adds r0, r0, r5",
    "lsrs r0, r0, #15",
    "muls r0, r6, r0",
    "lsrs r0, r0, #23",
    "cmp r0, #31",
    "bls 1f",
    "movs r0, #31",
    "1:",
    "muls r1, r3, r1",
    "adds r1, r1, r5",
    "lsrs r1, r1, #15",
    "muls r1, r6, r1",
    "lsrs r1, r1, #23",
    "cmp r1, #63",
    "bls 1f",
    "movs r1, #63",
    "1:",
    "muls r2, r3, r2",
    "adds r2, r2, r5",
    "lsrs r2, r2, #15",
    "muls r2, r6, r2",
    "lsrs r2, r2, #23",
    "cmp r2, #31",
    "bls 1f",
    "movs r2, #31",
    "1:",
    "lsls r0, r0, #11",
    "lsls r1, r1, #5",
    "orrs r0, r1",
    "orrs r0, r2",
    // The colour (r0) into the set-up's block, the corners' entries, the call.
    "8:",
    "ldr r7, [sp]",
    "ldr r5, [r7, #76]",
    "str r0, [r5, #{color}]",
    "ldrh r1, [r4, #0]",
    "ldrh r2, [r4, #2]",
    "ldrh r3, [r4, #4]",
    "ldr r6, [r7, #80]",
    "lsls r1, r1, #3",
    "adds r1, r1, r6",
    "lsls r2, r2, #3",
    "adds r2, r2, r6",
    "lsls r3, r3, #3",
    "adds r3, r3, r6",
    "mov r0, r5",
    "ldr r5, 11f",
    "blx r5",
    // Refused (u32::MAX): the caller's. Else tested into the sum, one face fewer to
    // the next return, and on from the next face.
    "adds r1, r0, #1",
    "beq 67f",
    "ldr r7, [sp]",
    "ldr r1, [r7, #88]",
    "adds r1, r1, r0",
    "str r1, [r7, #88]",
    "adds r0, r4, #6",
    "ldr r1, [r7, #56]",
    "ldr r2, [r7, #92]",
    "subs r2, #1",
    "str r2, [r7, #92]",
    "beq 10f",
    "cmp r0, r9",
    "bhs 12f",
    "b 2b",
    "12:",
    "b 3b",
    // No normal: the flat colour (one for all), else the caller's.
    "5:",
    "ldr r0, [r7, #84]",
    "cmp r0, #0",
    "beq 67f",
    "uxth r0, r0",
    "b 8b",
    // Above full scale.
    "7:",
    "movs r3, #0",
    "subs r3, #1",
    "lsrs r3, r3, #16",
    "b 6b",
    // The face in r4 left to the caller.
    "67:",
    "ldr r7, [sp]",
    "str r4, [r7, #52]",
    "movs r0, #1",
    "b 9f",
    // FLUSH faces drawn: back with the next face.
    "10:",
    "str r0, [r7, #52]",
    "movs r0, #2",
    "9:",
    "add sp, #4",
    "pop {{r4, r5, r6, r7}}",
    "mov r8, r4",
    "mov r9, r5",
    "mov r10, r6",
    "mov r11, r7",
    "pop {{r4, r5, r6, r7, pc}}",
    ".balign 4",
    "11:",
    ".word zraster_small_walk_v6m",
    ".size zraster_faces_v6m, . - zraster_faces_v6m",
    ".popsection",
    color = const WALK_COLOR,
);

/// Draw the faces of `scan` from `*pos` on into `b`, those the common case covers: the
/// scan past the dropped faces, each drawn face coloured by `color` (one colour, or
/// lit into 5-6-5 written as it is: `Raw565`) and drawn by the small triangles' set-up
/// and rows (`Less` with depth writes, a two-byte colour), its counts into `counts`.
/// Returns where it stopped ([`FacesStop`], as `faces_less`). On ARMv6-M one assembly
/// loop; elsewhere it leaves every face to the caller ([`FacesStop::Refused`]).
#[inline(always)]
pub(crate) fn faces_less_v6m<'a, C: Copy>(
    pos: &mut usize,
    scan: (&ScanRegs<'_>, &'a [[u16; 3]], &'a [CachedVertex]),
    color: &FaceColor<'_, C>,
    b: &mut Buffers<'_, '_, C>,
    counts: &mut FacesCounts,
) -> FacesStop<'a> {
    #[cfg(all(zraster_thumb, zraster_armv6m))]
    return faces_v6m(pos, scan, color, b, counts);
    #[allow(unreachable_code)]
    {
        let _ = (pos, scan, color, b, counts);
        FacesStop::Refused
    }
}

/// [`faces_less_v6m`] on ARMv6-M. Out of line (it runs once for a run of faces): its
/// block is not stacked on the caller's frame.
#[cfg(all(zraster_thumb, zraster_armv6m))]
#[inline(never)]
fn faces_v6m<'a, C: Copy>(
    pos: &mut usize,
    (regs, faces, cache): (&ScanRegs<'_>, &'a [[u16; 3]], &'a [CachedVertex]),
    color: &FaceColor<'_, C>,
    b: &mut Buffers<'_, '_, C>,
    counts: &mut FacesCounts,
) -> FacesStop<'a> {
    // Operands that are those of a scan of `faces` over `cache` (`CullScan::new`: x/y
    // at byte 4 of the 8-byte entries); a face left.
    let xy_at = cache.as_ptr().cast::<u8>().wrapping_add(4);
    let own = regs.xy == xy_at
        && regs.len == cache.len()
        && regs.faces == faces.as_ptr()
        && regs.end == faces.as_ptr_range().end
        && regs.faces_len == faces.len();
    if !own || *pos >= faces.len() {
        return FacesStop::Refused;
    }
    let Some(walk) = b.walk_block() else {
        return FacesStop::Refused;
    };
    let at = faces.as_ptr() as u32;
    let mut block = FacesV6m {
        light: [0; 3],
        ambient: 0,
        diffuse: 0,
        round: 1 << 12,
        channels: [0; 3],
        half: 0,
        k: 32_897,
        nend: at,
        ndelta: 0,
        face: at.wrapping_add(6 * *pos as u32),
        xy: regs.xy as u32,
        len: regs.len as u32,
        end: regs.end as u32,
        neg_lo: regs.neg_lo as u32,
        span: regs.span,
        walk: walk as u32,
        entries: cache.as_ptr() as u32,
        flat: 0,
        tested: 0,
        drawn: FLUSH,
    };
    match *color {
        FaceColor::Flat(c) => match super::rows::as_u16(&mut [], c) {
            Some((_, bits)) => block.flat = 1 << 16 | u32::from(bits),
            None => return FacesStop::Refused,
        },
        // Written as it is: `Raw565` proves the packed value is a `C`'s bytes.
        FaceColor::Lit(l, _, Some(_)) => {
            let normals = l.normals();
            let n = normals.len().min(faces.len());
            block.light = l.light;
            block.ambient = l.ambient;
            block.diffuse = l.diffuse;
            block.channels = l.channels;
            block.half = l.half;
            block.nend = at.wrapping_add(6 * n as u32);
            block.ndelta = (normals.as_ptr() as u32).wrapping_sub(at);
        }
        FaceColor::Lit(_, _, None) => return FacesStop::Refused,
    }
    let status = loop {
        let failed = walk.wrapping_add(WALK_FAILED).cast::<u32>();
        // SAFETY: `walk` is the started set-up block of `b` (`Buffers::walk_block`),
        // whose `failed` word (at 28, aligned) the loop's calls only add to; the call:
        // the block as built above (see the assembly's SAFETY comment).
        let (status, failed) = unsafe {
            failed.write(0);
            let status = zraster_faces_v6m(&mut block);
            (status, failed.read())
        };
        counts.tested = counts.tested.wrapping_add(u64::from(block.tested));
        counts.failed = counts.failed.wrapping_add(u64::from(failed));
        counts.drawn = counts.drawn.wrapping_add(FLUSH - block.drawn);
        if status != 2 {
            break status;
        }
        (block.tested, block.drawn) = (0, FLUSH);
    };
    // The place: the bytes from the first face over 6, exactly (as `skip_culled_v6m`).
    let k = ((block.face.wrapping_sub(at) >> 1).wrapping_mul(0xAAAA_AAAB)) as usize;
    *pos = k;
    if status == 0 {
        return FacesStop::Scan;
    }
    let get = |i: u16| cache.get(usize::from(i));
    match faces.get(k) {
        Some(&[a, b, c]) => match (get(a), get(b), get(c)) {
            (Some(a), Some(b), Some(c)) => {
                *pos = k + 1;
                FacesStop::Face(k, [a, b, c])
            }
            _ => FacesStop::Scan,
        },
        None => FacesStop::Scan,
    }
}

/// On-target check of the ARMv6-M face loop (`faces_less_v6m`) against its twin (the
/// scan's, the colour's and the set-up's portable twins face by face), for the bench
/// firmware: `cases` random meshes (up to 16 faces over up to 12 cache entries, some
/// unplaced or far apart, indices out of range; normals for some faces only; lit or
/// one colour; the three cull modes) drawn into copies of the same random 48 × 16
/// buffers (the colour rows at both alignments to the depth rows, clips of the whole
/// or part), the faces the loop leaves drawn by the twin as the renderer would. `buf`
/// holds four 48 × 16 buffers (a shorter one is a failure). Returns the number of
/// cases whose buffers, pixel counts or drawn faces differ, or where the loop refuses
/// on ARMv6-M (elsewhere it leaves every face to the twin).
#[inline(never)]
pub fn check_faces_v6m_kernel(buf: &mut [u16], cases: usize) -> usize {
    use super::cull::{culled_run_portable, CullScan};
    use super::faces::Raw565;
    use super::light::{lit_565_portable, LightBlock};
    use super::rows_v6m::small_walk_portable;
    use super::SmallDone;
    use crate::raster::{Clip, ScreenVertex};
    const W: usize = 48;
    const H: usize = 16;
    const N: usize = W * H;
    let Some(buf) = buf.get_mut(..4 * N) else {
        return usize::MAX;
    };
    let (mine, theirs) = buf.split_at_mut(2 * N);
    let (z1, c1) = mine.split_at_mut(N);
    let (z2, c2) = theirs.split_at_mut(N);
    let mut rnd = super::xorshift32(0x510e_527f);
    let mut bad = 0;
    for case in 0..cases {
        for (d, c) in z1.iter_mut().zip(c1.iter_mut()) {
            (*d, *c) = (rnd() as u16 | 0x8000 >> (case % 3), rnd() as u16);
        }
        z2.copy_from_slice(z1);
        c2.copy_from_slice(c1);
        let off = case / 2 % 2;
        let first_row = (rnd() % 5) as i32 - 2;
        let rows = (H - off) as i32;
        // Clips inside both buffers (the set-up's condition).
        let clip = if case % 3 == 0 {
            let (x0, y0) = ((rnd() % 20) as i32, (rnd() % 6) as i32);
            Clip {
                x0,
                y0: first_row + y0,
                x1: x0 + (rnd() % 29) as i32,
                y1: first_row + y0 + (rnd() % 10) as i32,
            }
        } else {
            Clip {
                x0: 0,
                y0: first_row,
                x1: W as i32,
                y1: first_row + rows,
            }
        };
        // Entries near the buffers (1/16 pixel), some unplaced, one far on some cases.
        let len = rnd() as usize % 13;
        let mut cache = [CachedVertex::EMPTY; 12];
        let span = 64 << (case % 4);
        let (bx, by) = (
            (rnd() % (W as u32 * 16)) as i32 - 40,
            (rnd() % (H as u32 * 16)) as i32 - 40 + first_row * 16,
        );
        for (i, e) in cache.iter_mut().enumerate() {
            let far = if case % 11 == 0 && i == 1 { 9000 } else { 0 };
            let x = ((rnd() % span) as i32 + bx - span as i32 / 2 + far) as i16;
            let y = ((rnd() % span) as i32 + by - span as i32 / 2) as i16;
            let z = (rnd() >> 1).min(crate::fixed::MAX_DEPTH);
            *e = CachedVertex {
                z,
                xy: super::XyWord::new(x, y),
            };
            if rnd().is_multiple_of(24) {
                e.xy = super::XyWord::new(i16::MIN, (rnd() % 64) as i16);
            }
        }
        let cache = cache.get(..len).unwrap_or(&[]);
        let mut faces = [[0u16; 3]; 16];
        for t in faces.iter_mut() {
            for i in t.iter_mut() {
                *i = (rnd() % (len as u32 + 1).min(12)) as u16;
                if rnd().is_multiple_of(48) {
                    *i = (len as u32 + rnd() % 4) as u16; // out of range
                }
            }
        }
        let faces = faces.get(..rnd() as usize % 17).unwrap_or(&[]);
        let (lo, cspan) = match rnd() % 3 {
            0 => (0, i32::MAX as u32),   // back faces
            1 => (i32::MIN, 1u32 << 31), // front faces
            _ => (0, 0),                 // none
        };
        let scan = CullScan::new(faces, cache, 4, CachedVertex::xy, lo, cspan);
        let regs = scan.operands();
        // Light and normals as `check_light_kernel`'s (ARMv6-M's diffuse range).
        let normals = [[0i16; 3]; 16].map(|n| n.map(|_| ((rnd() % 32769) as i32 - 16384) as i16));
        let light = [0; 3].map(|_| (rnd() % 65537) as i32 - 32768);
        let ambient = (rnd() % 131_073) as i32 - 65536;
        let diffuse = (rnd() % 131_073) as i32 - 65536;
        let channels = [0; 3].map(|_| rnd() as u8);
        let count = rnd() as usize % (faces.len() + 2);
        let block = LightBlock::new(
            light,
            ambient,
            diffuse,
            channels,
            normals.get(..count).unwrap_or(&normals),
        );
        let flat = rnd() as u16;
        let same: fn(u16) -> u16 = |c| c;
        let color = match case % 4 {
            3 => FaceColor::Flat(flat),
            _ => FaceColor::Lit(&block, same, Some(Raw565::<u16>::PROOF)),
        };
        // A drawn face's colour as the renderer gives it (a fixed one without a normal).
        let color_of = |k: usize| match color {
            FaceColor::Flat(c) => c,
            FaceColor::Lit(b, f, _) => lit_565_portable(k, b).map_or(0x1234, f),
        };
        let corners = |t: [&CachedVertex; 3]| {
            t.map(|e| {
                let (x, y) = e.xy();
                ScreenVertex::from_raw(x, y, e.z)
            })
        };
        // The loop, the faces it leaves drawn by the twin.
        let mut mine = FacesCounts::default();
        let (Some(ca), Some(cb)) = (c1.get_mut(off..), c2.get_mut(off..)) else {
            return usize::MAX;
        };
        let mut b = Buffers::unstarted(&mut z1[..], ca, W, first_row, clip);
        b.start();
        let mut pos = 0;
        let mut refused = false;
        while pos < faces.len() {
            match faces_less_v6m(&mut pos, (&regs, faces, cache), &color, &mut b, &mut mine) {
                FacesStop::Scan => pos += 1,
                FacesStop::Face(k, tri) => {
                    let [p, q, r] = corners(tri);
                    mine.drawn += 1;
                    let (z, c) = b.parts();
                    let done =
                        small_walk_portable([&p, &q, &r], &clip, first_row, W, z, c, color_of(k));
                    if let SmallDone::Drawn(tested, failed) = done {
                        mine.tested += u64::from(tested);
                        mine.failed += u64::from(failed);
                    }
                }
                FacesStop::Refused => {
                    refused = true;
                    break;
                }
            }
        }
        if FACES_V6M_KERNEL && refused {
            bad += 1;
        }
        // The twin, face by face (where the loop refused, for both).
        let twin = |z: &mut [u16], c: &mut [u16], counts: &mut FacesCounts| {
            for (k, tri) in faces.iter().enumerate() {
                let (n, drawn) = culled_run_portable(core::slice::from_ref(tri), &scan);
                let get = |i: u16| cache.get(usize::from(i));
                let (Some(a), Some(b), Some(e)) = (get(tri[0]), get(tri[1]), get(tri[2])) else {
                    continue;
                };
                if n == 1 || !drawn {
                    continue;
                }
                let [p, q, r] = corners([a, b, e]);
                counts.drawn += 1;
                let done =
                    small_walk_portable([&p, &q, &r], &clip, first_row, W, z, c, color_of(k));
                if let SmallDone::Drawn(tested, failed) = done {
                    counts.tested += u64::from(tested);
                    counts.failed += u64::from(failed);
                }
            }
        };
        let mut theirs = FacesCounts::default();
        if refused {
            let (z, c) = b.parts();
            twin(z, c, &mut mine);
        }
        twin(z2, cb, &mut theirs);
        if mine != theirs || z1 != z2 || c1 != c2 {
            bad += 1;
        }
    }
    bad
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faces_v6m_kernel_matches_its_twin() {
        let mut buf = [0u16; 4 * 48 * 16];
        assert_eq!(check_faces_v6m_kernel(&mut buf, 2_000), 0);
        assert_eq!(check_faces_v6m_kernel(&mut buf[..100], 1), usize::MAX);
    }
}
