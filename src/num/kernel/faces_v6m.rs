//! The whole frame's face loop of a cached mesh in one Thumb-1 loop on ARMv6-M: the
//! cull scan, the face's Lambert colour in 5-6-5 and a call of the small triangle's
//! set-up and rows (`zraster_small_walk_v6m`), face after face with no Rust between
//! them. Its portable twin is the renderer's own loop (the cull walk, `lit_565` and
//! the set-up), which also takes every face this loop leaves to it.
#![allow(unsafe_code)]

use super::cull::ScanRegs;
use super::faces::{
    band_faces_cases, merge_next, BandCarry, BandLoop, BandStop, FaceColor, FacesCounts, FacesStop,
    SmallTwin,
};
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

/// Whether a diffuse weight `w` and ambient weight `a` take `v6m_term`'s `narrow` form
/// (|w| < 2¹⁵) and its rounding with the ambient weight in it (|a| ≤ 2¹⁶).
#[cfg_attr(not(all(zraster_thumb, zraster_armv6m)), allow(dead_code))]
fn narrow(w: i32, a: i32) -> bool {
    w.unsigned_abs() < 1 << 15 && a.unsigned_abs() <= 1 << 16
}

/// The colour's rounding word (`round`) for ambient weight `a` and diffuse weight `w`:
/// 2¹², and for `narrow` also a·2¹³ (`v6m_round`).
#[cfg_attr(not(all(zraster_thumb, zraster_armv6m)), allow(dead_code))]
fn round_of(a: i32, w: i32) -> i32 {
    if narrow(w, a) {
        (1 << 12) + (a << 13)
    } else {
        1 << 12
    }
}

/// The diffuse term's numerator (r3) rounded and the ambient weight (r0) added, with
/// the rounding word in r2: `general` (x + 2¹²) >> 13 + a; `narrow`, whose word holds
/// 2¹² + a·2¹³, (x + that) >> 13, the same (a·2¹³ a multiple of 2¹³; |x| < 2³⁰ as |w| <
/// 2¹⁵ and 0 ≤ dot < 2³¹, |a·2¹³| ≤ 2²⁹: no wrap).
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! v6m_round {
    (general) => {
        "adds r3, r3, r2\nasrs r3, r3, #13\nadds r3, r3, r0\n"
    };
    (narrow) => {
        "adds r3, r3, r2\nasrs r3, r3, #13\n"
    };
}

/// The set-up block's fields the loop writes and reads (`SmallWalk`'s `color` and
/// `failed`, pinned at these offsets in `rows_v6m`).
#[cfg_attr(not(all(zraster_thumb, zraster_armv6m)), allow(dead_code))]
const WALK_COLOR: usize = 12;
#[cfg_attr(not(all(zraster_thumb, zraster_armv6m)), allow(dead_code))]
const WALK_FAILED: usize = 28;
/// `SmallWalk`'s `save`: the slot to keep a walk in (the bands' loop writes it).
#[cfg_attr(not(all(zraster_thumb, zraster_armv6m)), allow(dead_code))]
const WALK_SAVE: usize = 36;

/// The diffuse term's numerator before its rounding, from dot (r3, at least 0) and the
/// weight w (r1) into r3 (r5, r6 written): `general` as `lambert_term_narrow` (dot =
/// h·2¹⁶ + m·2⁸ + n: h·w + ⌊(m·w + ⌊n·w/2⁸⌋)/2⁸⌋, every product below 2³¹ in
/// magnitude for w within ±2¹⁶ and dot up to 3·2²⁹); `narrow`, for |w| < 2¹⁵, h·w +
/// ⌊l·w/2¹⁶⌋ with dot = h·2¹⁶ + l (|l·w| < 2³¹): both ⌊(dot·w + 2²⁸)/2²⁹⌋ once
/// rounded (nested floors), so the same term.
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! v6m_term {
    (general) => {
        concat!(
            "lsrs r5, r3, #16\n",
            "muls r5, r1, r5\n",
            "uxtb r6, r3\n",
            "muls r6, r1, r6\n",
            "asrs r6, r6, #8\n",
            "lsrs r3, r3, #8\n",
            "uxtb r3, r3\n",
            "muls r3, r1, r3\n",
            "adds r3, r3, r6\n",
            "asrs r3, r3, #8\n",
            "adds r3, r3, r5\n",
        )
    };
    (narrow) => {
        concat!(
            "lsrs r5, r3, #16\n",
            "muls r5, r1, r5\n",
            "uxth r6, r3\n",
            "muls r6, r1, r6\n",
            "asrs r6, r6, #16\n",
            "adds r3, r5, r6\n",
        )
    };
}

/// The whole frame's loop's parts by mode: `checked`, any cache and cull mode; `back`,
/// for a cache with no entry unplaced (|x| ≥ 2¹⁴) and back faces dropped.
///
/// `regs`: r10 and r11 from the block: `checked` the scan's −lo and span, `back` the
/// sums of tested pixels and of tested pixels + 1 a drawn face, from `tested` and
/// `drawn` (`back` tests the sign alone, and the caller bounds a call to `FLUSH` faces,
/// so that the sums are kept in registers and do not wrap).
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! v6m_regs {
    (checked) => {
        "ldr r1, [r0, #68]\nmov r10, r1\nldr r1, [r0, #72]\nmov r11, r1\n"
    };
    (back) => {
        "ldr r1, [r0, #88]\nmov r10, r1\nldr r1, [r0, #92]\nmov r11, r1\n"
    };
}

/// The scan's test of a face's corners (x/y words in r2, r3, r0; r5 written): `checked`
/// stops the scan (to `3f`) at one not placed (x's bits 15 and 14 differ: |x| ≥ 2¹⁴, the
/// mark among them); `back` has none.
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! v6m_placed {
    (checked) => {
        concat!(
            "lsls r5, r2, #16\n",
            "adds r5, r5, r5\n",
            "bvs 3f\n",
            "lsls r5, r3, #16\n",
            "adds r5, r5, r5\n",
            "bvs 3f\n",
            "lsls r5, r0, #16\n",
            "adds r5, r5, r5\n",
            "bvs 3f\n",
        )
    };
    (back) => {
        ""
    };
}

/// The cull test of the cross product (r5, just subtracted: the flags its own) to the
/// drawn face (`4f`): `checked` the scan's range test (r5 − lo ≤ span unsigned drops
/// it), `back` its case lo = 0, span = 2³¹ − 1: the product's sign bit.
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! v6m_cull {
    (checked) => {
        "add r5, r10\ncmp r5, r11\nbhi 4f\n"
    };
    (back) => {
        "bmi 4f\n"
    };
}

/// After the set-up's call (r0 its result, the block in r7): refused (u32::MAX) the
/// caller's (`67f`); else the tested pixels into the sum and the face into the drawn
/// count (`checked`: through the block, back to the caller after `FLUSH` faces, `10f`;
/// `back`: r10 the tested sum, r11 that of tested + 1, the drawn faces the
/// difference), then on from the next face (`2b`), or to the stop at the end (`3b`, r1
/// reloaded).
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! v6m_after {
    (checked) => {
        concat!(
            "adds r1, r0, #1\n",
            "beq 67f\n",
            "ldr r1, [r7, #88]\n",
            "adds r1, r1, r0\n",
            "str r1, [r7, #88]\n",
            "adds r4, #6\n",
            "ldr r1, [r7, #56]\n",
            "ldr r2, [r7, #92]\n",
            "subs r2, #1\n",
            "str r2, [r7, #92]\n",
            "beq 10f\n",
            "cmp r4, r9\n",
            "bhs 3b\n",
            "b 2b\n",
        )
    };
    (back) => {
        concat!(
            "adds r1, r0, #1\n",
            "beq 67f\n",
            "add r10, r0\n",
            "add r11, r1\n",
            "adds r4, #6\n",
            "ldr r1, [r7, #56]\n",
            "cmp r4, r9\n",
            "blo 2b\n",
            "b 3b\n",
        )
    };
}

/// A drawn face's colour into r2 (`v6m_colour`, its term `$term`): `checked` to `5f`
/// for a face without a normal; `back`, whose faces all have one, or `flat`: the one
/// colour (the wrapper picks these only then).
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! v6m_face_colour {
    (checked, $term:ident) => {
        v6m_colour!("5f", $term)
    };
    (back, flat) => {
        "ldr r2, [r7, #84]\nuxth r2, r2\n"
    };
    (back, $term:ident) => {
        v6m_colour!(all, $term)
    };
}

/// [`v6m_colour_cold`] where the loop has [`v6m_colour`] (not for `flat`).
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! v6m_face_cold {
    (flat) => {
        ""
    };
    ($term:ident) => {
        v6m_colour_cold!()
    };
}

/// At the return (the block in r7): `back` stores its sums (r10, r11) into the block.
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! v6m_sums {
    (checked) => {
        ""
    };
    (back) => {
        "mov r1, r10\nstr r1, [r7, #88]\nmov r1, r11\nstr r1, [r7, #92]\n"
    };
}

/// The Lambert colour of the face at r4 (its address; the block in r7) into r2, as
/// `lit_565_portable` step for step: its normal at r4 + `ndelta` when r4 < `nend`, else
/// on to `$none` (`all` in its place: no test, for faces all below `nend`); n·L
/// (wrapping), at least 0; the diffuse term (`v6m_term`'s `$term`, rounded: + 2¹², >>
/// 13) plus ambient (`v6m_round`); for an intensity in 0..2¹⁵ each channel
/// ((i·v + half) >> 15) · 32897 >> 23, packed 5-6-5 (any other intensity by
/// `v6m_colour_cold`, which the caller places after its loop: the intensity clamped to
/// 0..=65535, each channel to its maximum). Writes r0–r3, r5–r7 and the flags.
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! v6m_colour {
    ($none:literal, $term:ident) => {
        concat!(
            "ldr r2, [r7, #44]\n",
            "cmp r4, r2\n",
            "bhs ",
            $none,
            "\n",
            v6m_colour!(all, $term),
        )
    };
    // Every face with a normal (no test).
    (all, $term:ident) => {
        concat!(
            "ldr r2, [r7, #48]\n",
            "ldrsh r3, [r4, r2]\n",
            "adds r2, #2\n",
            "ldrsh r5, [r4, r2]\n",
            "adds r2, #2\n",
            "ldrsh r6, [r4, r2]\n",
            "ldm r7!, {{r0, r1, r2}}\n",
            "muls r3, r0, r3\n",
            "muls r5, r1, r5\n",
            "muls r6, r2, r6\n",
            "adds r3, r3, r5\n",
            "adds r3, r3, r6\n",
            // At least 0 (the sum's sign bit).
            "bpl 1f\n",
            "movs r3, #0\n",
            "1:\n",
            "ldm r7!, {{r0, r1, r2}}\n",
            v6m_term!($term),
            v6m_round!($term),
            // The channels, half and k (r0–r2, r5, r6: five words in a row).
            "ldm r7!, {{r0, r1, r2, r5, r6}}\n",
            // From 0 to below full light (0 ≤ i < 2¹⁵) no channel passes its maximum:
            // no clamps.
            "lsrs r7, r3, #15\n",
            "bne 7f\n",
            "muls r0, r3, r0\n",
            "adds r0, r0, r5\n",
            "lsrs r0, r0, #15\n",
            "muls r0, r6, r0\n",
            "lsrs r0, r0, #23\n",
            "muls r1, r3, r1\n",
            "adds r1, r1, r5\n",
            "lsrs r1, r1, #15\n",
            "muls r1, r6, r1\n",
            "lsrs r1, r1, #23\n",
            "muls r2, r3, r2\n",
            "adds r2, r2, r5\n",
            "lsrs r2, r2, #15\n",
            "muls r2, r6, r2\n",
            "lsrs r2, r2, #23\n",
            "6:\n",
            "lsls r0, r0, #11\n",
            "lsls r1, r1, #5\n",
            "orrs r2, r0\n",
            "orrs r2, r1\n",
        )
    };
}

/// The part of [`v6m_colour`] for full light and above or below 0 (i ∉ [0, 2¹⁵),
/// rare): the intensity clamped to 0..=65535, each channel clamped to its maximum,
/// back to the packing. Placed after the loop, within a conditional branch's reach.
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! v6m_colour_cold {
    () => {
        concat!(
            "7:\n",
            "asrs r7, r3, #31\n",
            "bics r3, r7\n",
            "lsrs r7, r3, #16\n",
            "beq 1f\n",
            "movs r3, #0\n",
            "subs r3, #1\n",
            "lsrs r3, r3, #16\n",
            "1:\n",
            "muls r0, r3, r0\n",
            "adds r0, r0, r5\n",
            "lsrs r0, r0, #15\n",
            "muls r0, r6, r0\n",
            "lsrs r0, r0, #23\n",
            "cmp r0, #31\n",
            "bls 1f\n",
            "movs r0, #31\n",
            "1:\n",
            "muls r1, r3, r1\n",
            "adds r1, r1, r5\n",
            "lsrs r1, r1, #15\n",
            "muls r1, r6, r1\n",
            "lsrs r1, r1, #23\n",
            "cmp r1, #63\n",
            "bls 1f\n",
            "movs r1, #63\n",
            "1:\n",
            "muls r2, r3, r2\n",
            "adds r2, r2, r5\n",
            "lsrs r2, r2, #15\n",
            "muls r2, r6, r2\n",
            "lsrs r2, r2, #23\n",
            "cmp r2, #31\n",
            "bls 1f\n",
            "movs r2, #31\n",
            "1:\n",
            "b 6b\n",
        )
    };
}

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
    /// [`zraster_faces_v6m`] for a diffuse weight within ±(2¹⁵ − 1) (`v6m_term`'s
    /// `narrow`).
    ///
    /// # Safety
    ///
    /// As [`zraster_faces_v6m`].
    fn zraster_faces_v6m_narrow(b: *mut FacesV6m) -> u32;
    /// [`zraster_faces_v6m`] in mode `back` (`v6m_regs`): no test of the corners'
    /// places, back faces dropped by the cross product's sign, the sums in the block's
    /// `tested` and `drawn` (added to theirs; `drawn` sums tested + 1 a drawn face:
    /// the faces are its difference to `tested`), no return after `FLUSH` faces;
    /// 2 is not returned. For a cache with no entry unplaced (else a wrong picture,
    /// nothing unsafe), the scan's lo 0 and span 2³¹ − 1, at most `FLUSH` faces to
    /// `end`, and `nend` at `end` or past it (every face's normal read unasked).
    ///
    /// # Safety
    ///
    /// As [`zraster_faces_v6m`].
    fn zraster_faces_v6m_back(b: *mut FacesV6m) -> u32;
    /// [`zraster_faces_v6m_narrow`] in mode `back`.
    ///
    /// # Safety
    ///
    /// As [`zraster_faces_v6m`].
    fn zraster_faces_v6m_narrow_back(b: *mut FacesV6m) -> u32;
    /// [`zraster_faces_v6m_back`] with the one colour `flat` (set) for every face.
    ///
    /// # Safety
    ///
    /// As [`zraster_faces_v6m`].
    fn zraster_faces_v6m_flat_back(b: *mut FacesV6m) -> u32;
}

// SAFETY (for `faces_less_v6m`): the scan is `skip_culled_v6m`'s turn for turn
// (operands in r8–r11 instead of r7/r8/r12/lr): it reads faces from `face` < `end` one
// a turn until `end`, and an entry's x/y word at `xy + 8 i` only for indices found
// below `len`, the cache's length. A drawn face's normal is read at face + `ndelta`
// (three halfwords) only when face < `nend`, the faces' address plus 6 · the normals
// there are (at most the faces'), so only inside the normals' slice. The colour goes
// to the set-up block's `color` (a word), the corners as entries + 8 · index for the
// three indices found below `len`; `zraster_small_walk_v6m`'s contract: a block
// started for buffers whose clip lies inside both (`Buffers::walk_block`). The `back`
// loops skip the corners' x test, which decides which faces go to the caller, not what
// is read or written (the set-up clips whatever the corners are); `end` there is the
// wrapper's, at most the faces' end, and the lit ones read a drawn face's normal
// without the `nend` test, which the wrapper takes them for only where `nend` is the
// faces' end (a normal for every face). The call keeps r4–r11 (AAPCS): the scan's
// operands in r8–r11 and the face in r4 live across it; r1 is reloaded. The call is a
// BL, which the linker gives a long-branch thunk where the set-up lies out of reach
// (in RAM under `ram-code`). The block is read and written through its address at
// [sp]; the frame is 40 bytes (8-aligned at the call); r4–r11 and lr saved and
// restored.
/// The whole frame's loop as the function `$name`, its colour's term `$term`, its
/// mode `$mode` (`v6m_regs`).
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! faces_v6m_fn {
    ($name:literal, $term:ident, $mode:ident) => {
core::arch::global_asm!(
    concat!(".pushsection .text.", $name, ",\"ax\",%progbits"),
    ".balign 4",
    concat!(".global ", $name),
    concat!(".hidden ", $name),
    concat!(".type ", $name, ", %function"),
    ".thumb_func",
    concat!($name, ":"),
    v6m_save!(),
    "sub sp, #4",
    "str r0, [sp]",
    // The scan's operands: entries in r8, end in r9; r10, r11 by the mode.
    "ldr r1, [r0, #60]",
    "mov r8, r1",
    "ldr r1, [r0, #64]",
    "mov r9, r1",
    v6m_regs!($mode),
    "mov r7, r0",
    "ldr r1, [r0, #56]",
    "ldr r4, [r0, #52]",
    "cmp r4, r9",
    "bhs 3f",
    // The scan (`skip_culled_v6m`'s turn, the face in r4).
    "2:",
    "ldrh r2, [r4, #0]",
    "ldrh r3, [r4, #2]",
    "ldrh r0, [r4, #4]",
    "cmp r2, r8",
    "bhs 3f",
    "cmp r3, r8",
    "bhs 3f",
    "cmp r0, r8",
    "bhs 3f",
    "lsls r2, r2, #3",
    "lsls r3, r3, #3",
    "lsls r0, r0, #3",
    "ldr r2, [r1, r2]",
    "ldr r3, [r1, r3]",
    "ldr r0, [r1, r0]",
    v6m_placed!($mode),
    "subs r5, r3, r2",
    "sxth r5, r5",
    "subs r6, r0, r2",
    "sxth r6, r6",
    "asrs r2, r2, #16",
    "asrs r3, r3, #16",
    "subs r3, r3, r2",
    "asrs r0, r0, #16",
    "subs r0, r0, r2",
    "muls r5, r0, r5",
    "muls r6, r3, r6",
    "subs r5, r5, r6",
    v6m_cull!($mode),
    "adds r4, #6",
    "cmp r4, r9",
    "bne 2b",
    // Stopped at r4 (a bad index, an unplaced corner, or the end); the block in r7
    // (the scan leaves it).
    "3:",
    "str r4, [r7, #52]",
    "movs r0, #0",
    "b 9f",
    // Drawn (the face in r4): its colour, else the flat colour or the caller's.
    "4:",
    v6m_face_colour!($mode, $term),
    // The colour (r2) into the set-up's block, the corners' entries, the call.
    "8:",
    "ldr r7, [sp]",
    "ldr r0, [r7, #76]",
    "str r2, [r0, #{color}]",
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
    "bl zraster_small_walk_v6m",
    // The counts and on (the set-up keeps r7, the block).
    v6m_after!($mode),
    // No normal: the flat colour (one for all), else the caller's.
    "5:",
    "ldr r2, [r7, #84]",
    "cmp r2, #0",
    "beq 67f",
    "uxth r2, r2",
    "b 8b",
    // The face in r4 left to the caller.
    "67:",
    "ldr r7, [sp]",
    "str r4, [r7, #52]",
    "movs r0, #1",
    "b 9f",
    // FLUSH faces drawn: back with the next face.
    "10:",
    "str r4, [r7, #52]",
    "movs r0, #2",
    "9:",
    v6m_sums!($mode),
    "add sp, #4",
    v6m_return!(),
    v6m_face_cold!($term),
    concat!(".size ", $name, ", . - ", $name),
    ".popsection",
    color = const WALK_COLOR,
);
    };
}

#[cfg(all(zraster_thumb, zraster_armv6m))]
faces_v6m_fn!("zraster_faces_v6m", general, checked);
#[cfg(all(zraster_thumb, zraster_armv6m))]
faces_v6m_fn!("zraster_faces_v6m_narrow", narrow, checked);
#[cfg(all(zraster_thumb, zraster_armv6m))]
faces_v6m_fn!("zraster_faces_v6m_back", general, back);
#[cfg(all(zraster_thumb, zraster_armv6m))]
faces_v6m_fn!("zraster_faces_v6m_narrow_back", narrow, back);
#[cfg(all(zraster_thumb, zraster_armv6m))]
faces_v6m_fn!("zraster_faces_v6m_flat_back", flat, back);

#[cfg(all(zraster_thumb, zraster_armv6m))]
extern "C" {
    /// The loops' colour code on its own: the colour of the face at `face` by block
    /// `b`'s constants, 65536 without a normal.
    ///
    /// # Safety
    ///
    /// `b`'s `nend` and `ndelta` bound normals it may read (as the loops' blocks).
    fn zraster_colour_v6m(b: *const FacesV6m, face: u32) -> u32;
    /// [`zraster_colour_v6m`] with `v6m_term`'s `narrow` (|diffuse| < 2¹⁵).
    ///
    /// # Safety
    ///
    /// As [`zraster_colour_v6m`].
    fn zraster_colour_v6m_narrow(b: *const FacesV6m, face: u32) -> u32;
}

/// The loops' colour code on its own as the function `$name` (term `$term`), for the
/// checks.
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! colour_v6m_fn {
    ($name:literal, $term:ident) => {
        // SAFETY (for `lit_565_v6m`): reads the block's constants and, below `nend`,
        // the normal at face + `ndelta`; r4–r7 saved and restored.
        core::arch::global_asm!(
            concat!(".pushsection .text.", $name, ",\"ax\",%progbits"),
            ".balign 4",
            concat!(".global ", $name),
            concat!(".hidden ", $name),
            concat!(".type ", $name, ", %function"),
            ".thumb_func",
            concat!($name, ":"),
            "push {{r4, r5, r6, r7, lr}}",
            "mov r7, r0",
            "mov r4, r1",
            v6m_colour!("5f", $term),
            "movs r0, r2",
            "pop {{r4, r5, r6, r7, pc}}",
            "5:",
            "movs r0, #1",
            "lsls r0, r0, #16",
            "pop {{r4, r5, r6, r7, pc}}",
            v6m_colour_cold!(),
            concat!(".size ", $name, ", . - ", $name),
            ".popsection",
        );
    };
}

#[cfg(all(zraster_thumb, zraster_armv6m))]
colour_v6m_fn!("zraster_colour_v6m", general);
#[cfg(all(zraster_thumb, zraster_armv6m))]
colour_v6m_fn!("zraster_colour_v6m_narrow", narrow);

/// The ARMv6-M loops' colour code (`v6m_colour`) for face `f` lit by `l`, as
/// [`lit_565`](super::lit_565) gives it (for the checks); elsewhere
/// `lit_565_portable`.
pub(super) fn lit_565_v6m(f: usize, l: &super::LightBlock<'_>) -> Option<u16> {
    #[cfg(all(zraster_thumb, zraster_armv6m))]
    {
        let normals = l.normals();
        let at = normals.as_ptr() as u32;
        let block = FacesV6m {
            light: l.light,
            ambient: l.ambient,
            diffuse: l.diffuse,
            round: round_of(l.ambient, l.diffuse),
            channels: l.channels,
            half: l.half,
            k: 32_897,
            nend: at.wrapping_add(6 * normals.len() as u32),
            ndelta: 0,
            face: 0,
            xy: 0,
            len: 0,
            end: 0,
            neg_lo: 0,
            span: 0,
            walk: 0,
            entries: 0,
            flat: 0,
            tested: 0,
            drawn: 0,
        };
        // Faces past the normals as the first of them (not below `nend`).
        let face = at.wrapping_add(6 * f.min(normals.len()) as u32);
        // SAFETY: the normals' slice bounds what it reads (`nend`, `ndelta` 0).
        let c = unsafe {
            if narrow(l.diffuse, l.ambient) {
                zraster_colour_v6m_narrow(&block, face)
            } else {
                zraster_colour_v6m(&block, face)
            }
        };
        return u16::try_from(c).ok();
    }
    #[allow(unreachable_code)]
    super::light::lit_565_portable(f, l)
}

/// Draw the faces of `scan` from `*pos` on into `b`, those the common case covers: the
/// scan past the dropped faces, each drawn face coloured by `color` (one colour, or
/// lit into 5-6-5 written as it is: `Raw565`) and drawn by the small triangles' set-up
/// and rows (`Less` with depth writes, a two-byte colour), its counts into `counts`.
/// Returns where it stopped ([`FacesStop`], as `faces_less`). `placed`: no entry of
/// the cache is marked or otherwise has |x| ≥ 2¹⁴ (the renderer's `placed`), so that
/// the scan need not test the corners (a wrong `true` gives a wrong picture, nothing
/// unsafe). On ARMv6-M one assembly loop; elsewhere it leaves every face to the caller
/// ([`FacesStop::Refused`]).
#[inline(always)]
pub(crate) fn faces_less_v6m<'a, C: Copy>(
    pos: &mut usize,
    scan: (&ScanRegs<'_>, &'a [[u16; 3]], &'a [CachedVertex]),
    placed: bool,
    color: &FaceColor<'_, C>,
    b: &mut Buffers<'_, '_, C>,
    counts: &mut FacesCounts,
) -> FacesStop<'a> {
    #[cfg(all(zraster_thumb, zraster_armv6m))]
    return faces_v6m(pos, scan, placed, FLUSH, color, b, counts);
    #[allow(unreachable_code)]
    {
        let _ = (pos, scan, placed, color, b, counts);
        FacesStop::Refused
    }
}

/// [`faces_less_v6m`] on ARMv6-M; `chunk`: the most faces a call of the `back` loop
/// covers (`FLUSH`; the check's fewer test its resumption), ignored by the checked loops. Out of line (it runs once
/// for a run of faces): its block is not stacked on the caller's frame.
#[cfg(all(zraster_thumb, zraster_armv6m))]
#[inline(never)]
fn faces_v6m<'a, C: Copy>(
    pos: &mut usize,
    (regs, faces, cache): (&ScanRegs<'_>, &'a [[u16; 3]], &'a [CachedVertex]),
    placed: bool,
    chunk: u32,
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
            block.round = round_of(l.ambient, l.diffuse);
            block.channels = l.channels;
            block.half = l.half;
            block.nend = at.wrapping_add(6 * n as u32);
            block.ndelta = (normals.as_ptr() as u32).wrapping_sub(at);
        }
        FaceColor::Lit(_, _, None) => return FacesStop::Refused,
    }
    // Mode `back` for a cache with no entry unplaced, back faces dropped and every
    // face's colour known to the loop (a normal, or one colour), at most `chunk` faces
    // a call (its sums do not wrap); else `checked`.
    let flat = block.flat != 0;
    let coloured = flat || block.nend == block.end;
    let back = placed && coloured && regs.neg_lo == 0 && regs.span == i32::MAX as u32;
    let (end, chunk) = (block.end, 6 * chunk.clamp(1, FLUSH));
    let first = if back { 0 } else { FLUSH };
    block.drawn = first;
    let status = loop {
        if back {
            block.end = if end - block.face > chunk {
                block.face + chunk
            } else {
                end
            };
        }
        let failed = walk.wrapping_add(WALK_FAILED).cast::<u32>();
        // SAFETY: `walk` is the started set-up block of `b` (`Buffers::walk_block`),
        // whose `failed` word (at 28, aligned) the loop's calls only add to; the call:
        // the block as built above (see the assembly's SAFETY comment), its `end` at
        // most the faces' end.
        let (status, failed) = unsafe {
            failed.write(0);
            let status = match (narrow(block.diffuse, block.ambient), back, flat) {
                (true, false, _) => zraster_faces_v6m_narrow(&mut block),
                (false, false, _) => zraster_faces_v6m(&mut block),
                (_, true, true) => zraster_faces_v6m_flat_back(&mut block),
                (true, true, false) => zraster_faces_v6m_narrow_back(&mut block),
                (false, true, false) => zraster_faces_v6m_back(&mut block),
            };
            (status, failed.read())
        };
        counts.tested = counts.tested.wrapping_add(u64::from(block.tested));
        counts.failed = counts.failed.wrapping_add(u64::from(failed));
        counts.drawn = counts.drawn.wrapping_add(if back {
            block.drawn.wrapping_sub(block.tested)
        } else {
            FLUSH - block.drawn
        });
        // On after `FLUSH` faces drawn, or (`back`) at the end of a call's faces.
        let more = if back {
            status == 0 && block.face == block.end && block.end != end
        } else {
            status == 2
        };
        if !more {
            break status;
        }
        (block.tested, block.drawn) = (0, first);
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

/// What the band loop reads and writes, at the offsets in the comments: the colour's
/// constants and the set-up's and counts' words at [`FacesV6m`]'s offsets (the same
/// colour code reads them), the faces, the merge's heads and links, the carry.
#[cfg_attr(not(all(zraster_thumb, zraster_armv6m)), allow(dead_code))]
#[repr(C)]
struct BandV6m {
    light: [i32; 3],    // 0
    ambient: i32,       // 12
    diffuse: i32,       // 16
    round: i32,         // 20
    channels: [u32; 3], // 24
    half: u32,          // 36
    k: u32,             // 40
    nend: u32,          // 44
    ndelta: u32,        // 48
    /// The faces' address, the links', the faces below which both lie, the entries.
    faces: u32, // 52
    links: u32,         // 56
    n: u32,             // 60
    len: u32,           // 64
    /// The colours to take and the half to keep into.
    read: u32, // 68
    keep: u32,          // 72
    walk: u32,          // 76
    entries: u32,       // 80
    flat: u32,          // 84
    /// Pixels tested (the loop returns once the sum reaches 2³¹).
    tested: u32, // 88
    /// The walks kept by the band above (slots of `STATE_WORDS` from `sread`) that
    /// were written, resumed as their colours are taken.
    sfilled: u32, // 92
    /// Taken below `filled`, kept below `room`.
    filled: u32, // 96
    taken: u32,         // 100
    kept: u32,          // 104
    room: u32,          // 108
    /// The head of the face the loop stopped at.
    least: u32, // 112
    /// The read half of the walks kept, the half this band keeps into (a slot a colour
    /// kept, below `sroom`).
    sread: u32, // 116
    skeep: u32,         // 120
    sroom: u32,         // 124
    /// The chains' heads in increasing order (`face << 2 | chain`).
    heads: [u32; 4], // 128
}

#[cfg(target_pointer_width = "32")]
const _: () = {
    use core::mem::offset_of;
    type B = BandV6m;
    assert!(offset_of!(B, nend) == 44 && offset_of!(B, faces) == 52);
    assert!(offset_of!(B, links) == 56 && offset_of!(B, n) == 60);
    assert!(offset_of!(B, len) == 64 && offset_of!(B, read) == 68);
    assert!(offset_of!(B, keep) == 72 && offset_of!(B, walk) == 76);
    assert!(offset_of!(B, entries) == 80 && offset_of!(B, flat) == 84);
    assert!(offset_of!(B, tested) == 88);
    assert!(offset_of!(B, filled) == 96 && offset_of!(B, taken) == 100);
    assert!(offset_of!(B, kept) == 104 && offset_of!(B, room) == 108);
    assert!(offset_of!(B, least) == 112 && offset_of!(B, heads) == 128);
    assert!(offset_of!(B, sfilled) == 92 && offset_of!(B, sread) == 116);
    assert!(offset_of!(B, skeep) == 120 && offset_of!(B, sroom) == 124);
};

// A slot holds a kept walk, slots 84 bytes apart (the band loop's stride).
const _: () = {
    use super::{faces::STATE_WORDS, rows_v6m::KEPT_WALK_WORDS};
    assert!(KEPT_WALK_WORDS <= STATE_WORDS && STATE_WORDS * 4 == 84);
};

#[cfg(all(zraster_thumb, zraster_armv6m))]
extern "C" {
    /// The band loop over block `b`: returns 0 at the end of the band's faces, 1 at a
    /// face it leaves to the caller with nothing of its carry done (tall, or no
    /// colour), 2 at one it does not draw (a corner past the cache, or refused by the
    /// set-up) with a taken colour counted, both with the face's head in `least` and
    /// the heads past it (the wrapper takes both back), 3 once the tested sum reaches
    /// 2³¹; the heads stored back.
    ///
    /// # Safety
    ///
    /// As [`band_faces_less_v6m`] builds the block.
    fn zraster_band_faces_v6m(b: *mut BandV6m) -> u32;
}

/// The band loop's set-up call (the colour in r2, the face's address in r4): the
/// corners' indices below the cache's length, the colour into the set-up's block,
/// their entries, the call; a corner past the cache or refused to `67f`, else the
/// tested pixels into the sum (r1, the flags its sign; the block in r7). Keeps r6.
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! band_call {
    () => {
        concat!(
            "ldr r7, [sp]\n",
            "ldr r0, [r7, #76]\n",
            "str r2, [r0, #{color}]\n",
            "ldrh r1, [r4, #0]\n",
            "ldrh r2, [r4, #2]\n",
            "ldrh r3, [r4, #4]\n",
            "ldr r5, [r7, #64]\n",
            "cmp r1, r5\n",
            "bhs 67f\n",
            "cmp r2, r5\n",
            "bhs 67f\n",
            "cmp r3, r5\n",
            "bhs 67f\n",
            "ldr r5, [r7, #80]\n",
            "lsls r1, r1, #3\n",
            "adds r1, r1, r5\n",
            "lsls r2, r2, #3\n",
            "adds r2, r2, r5\n",
            "lsls r3, r3, #3\n",
            "adds r3, r3, r5\n",
            "bl zraster_small_walk_v6m\n",
            "adds r1, r0, #1\n",
            "beq 67f\n",
            "ldr r1, [r7, #88]\n",
            "adds r1, r1, r0\n",
            "str r1, [r7, #88]\n",
        )
    };
}

// SAFETY (for `band_faces_less_v6m`): the merge reads `links[f]` and forms face f's
// address only for the least head's f (head >> 2) below n, the smaller of the links'
// and faces' lengths, whatever the heads and links hold (END or any number past the
// faces fails the test and ends the loop); the chain's next head is the 16-bit link
// shifted above the chain's number. The colour code reads the normal at face + `ndelta`
// only below `nend` (the faces' address plus 6 · the normals there are, at most the
// faces'). A carried colour is read at `read[taken]` only when taken < filled ≤ the
// read half's length, one kept at `keep[kept]` only when kept < `room`, its length;
// `C` is two bytes (the buffers' block is started only then), and each value kept a
// `C`'s bytes (taken from `read`, the flat colour's, or the packed value `Raw565`
// proves is). A face's three indices are tested below the cache's length before its
// entries' addresses (entries + 8 · index) are formed; the set-up is
// `zraster_faces_v6m`'s call. It keeps r4–r11: the heads live in r8–r11 across it.
// The kept walks: slot k (84 bytes from `sread` or `skeep`) is read only for a face
// taken at k < sfilled, at most the slots both halves hold (the wrapper checks their
// lengths), and named for the set-up to write (`save`) only for a face kept at
// k < sroom, at most those slots and the keep half's colours; a slot named and not
// saved is marked empty (word 15, its kept row, i32::MAX: the resume refuses it).
// `save` is never left set after a face: cleared by the set-up once it saved, else
// here (and by the wrapper after a face left midway). So slots 0 .. min(sroom, kept)
// of a band are each saved or marked for that colour's face in this draw, the wrapper
// names slots only while every colour kept so far has its slot (kept = saved at the
// entry), and the band below reads below that count (`sfilled`) only with the same
// clip columns (else 0): each slot it resumes holds the set-up's own walk, so the
// resume's argument holds (`rows_v6m`).
// The block's address is at [sp], the least head at [sp, #4]; the frame is 48 bytes
// (8-aligned at the calls); the colour is a local subroutine (BL, its return by
// `bx lr`: lr was saved by the prologue).
#[cfg(all(zraster_thumb, zraster_armv6m))]
core::arch::global_asm!(
    ".pushsection .text.zraster_band_faces_v6m,\"ax\",%progbits",
    ".balign 4",
    ".global zraster_band_faces_v6m",
    ".hidden zraster_band_faces_v6m",
    ".type zraster_band_faces_v6m, %function",
    ".thumb_func",
    "zraster_band_faces_v6m:",
    v6m_save!(),
    "sub sp, #12",
    "str r0, [sp]",
    "adds r0, #128",
    "ldm r0!, {{r1, r2, r3, r4}}",
    "mov r8, r1",
    "mov r9, r2",
    "mov r10, r3",
    "mov r11, r4",
    "ldr r7, [sp]",
    // The least head (r5, also at [sp, #4]): its face f (r4) below n, else the end
    // (the block in r7).
    "60:",
    "mov r5, r8",
    "str r5, [sp, #4]",
    "lsrs r4, r5, #2",
    "ldr r1, [r7, #60]",
    "cmp r4, r1",
    "bhs 66f",
    // Its chain's next face (least + 4 (link − f)) moved down past the heads below it.
    "ldr r1, [r7, #56]",
    "lsls r2, r4, #1",
    "ldrh r2, [r1, r2]",
    "subs r2, r2, r4",
    "lsls r2, r2, #2",
    "adds r2, r2, r5",
    "cmp r2, r9",
    "bhs 61f",
    "mov r8, r2",
    // The face's address (r4).
    "64:",
    "movs r0, #6",
    "muls r0, r4, r0",
    "ldr r1, [r7, #52]",
    "adds r4, r1, r0",
    // By the chain (bit 0 to N, bit 1 to C): tall (3) the caller's; its own (2)
    // worked out; kept (1) worked out, kept once drawn; taken (0) the next carried
    // colour while there is one, else worked out, and counted.
    "lsls r1, r5, #31",
    "bcs 20f",
    "bmi 25f",
    "ldr r0, [r7, #100]",
    "ldr r1, [r7, #96]",
    "cmp r0, r1",
    "bhs 26f",
    "adds r1, r0, #1",
    "str r1, [r7, #100]",
    "ldr r1, [r7, #68]",
    "lsls r3, r0, #1",
    "ldrh r2, [r1, r3]",
    // Its walk kept by the band above (slot `taken` below `sfilled`): resumed (`40f`).
    "ldr r1, [r7, #92]",
    "cmp r0, r1",
    "bhs 22f",
    "b 40f",
    "26:",
    "bl 30f",
    "ldr r7, [sp]",
    "ldr r1, [r7, #100]",
    "adds r1, #1",
    "str r1, [r7, #100]",
    "b 22f",
    "20:",
    "bmi 68f",
    "bl 30f",
    // The colour in r2: the set-up and rows, the counts; back to the caller once the
    // tested sum reaches 2³¹ (a face tests < 2^18.01 pixels: no wrap, of it nor of the
    // failures, fewer).
    "22:",
    band_call!(),
    "bpl 60b",
    "b 10f",
    // Kept: the colour (r6) into the half for the band below once drawn, while there
    // is room.
    "25:",
    "bl 30f",
    "mov r6, r2",
    // A slot for its walk while one follows each colour kept (kept < sroom): slot
    // `kept` of the keep half, named in the set-up's block (`save`).
    "ldr r7, [sp]",
    "ldr r3, [r7, #104]",
    "ldr r1, [r7, #124]",
    "cmp r3, r1",
    "bhs 23f",
    "movs r1, #84",
    "muls r3, r1",
    "ldr r1, [r7, #120]",
    "adds r3, r3, r1",
    "ldr r0, [r7, #76]",
    "str r3, [r0, #{save}]",
    "23:",
    band_call!(),
    "b 41f",
    "10:",
    "movs r0, #3",
    "b 9f",
    // The merge's other cases: the next head moved down past the second head.
    "61:",
    "mov r8, r9",
    "cmp r2, r10",
    "bhs 62f",
    "mov r9, r2",
    "b 64b",
    "62:",
    "mov r9, r10",
    "cmp r2, r11",
    "bhs 63f",
    "mov r10, r2",
    "b 64b",
    "63:",
    "mov r10, r11",
    "mov r11, r2",
    "b 64b",
    "66:",
    "movs r0, #0",
    "b 9f",
    // A corner past the cache or refused by the set-up (a taken colour counted); left
    // to the caller (tall, no colour: nothing of its carry done). Its head at 112.
    "67:",
    "movs r0, #2",
    "b 65f",
    "68:",
    "movs r0, #1",
    "65:",
    "ldr r1, [sp, #4]",
    "ldr r7, [sp]",
    "str r1, [r7, #112]",
    // The heads back into the block.
    "9:",
    "ldr r7, [sp]",
    "adds r7, #128",
    "mov r1, r8",
    "mov r2, r9",
    "mov r3, r10",
    "mov r4, r11",
    "stm r7!, {{r1, r2, r3, r4}}",
    "add sp, #12",
    v6m_return!(),
    // The colour of the face at r4 into r2 (the block in r7 at every call); without a
    // normal the flat colour, else the face is the caller's (nothing of its carry done
    // yet).
    "30:",
    v6m_colour!("31f", general),
    "bx lr",
    v6m_colour_cold!(),
    "31:",
    "ldr r2, [r7, #84]",
    "cmp r2, #0",
    "bne 32f",
    "b 68b",
    "32:",
    "uxth r2, r2",
    "bx lr",
    // A taken face's walk resumed from slot `taken` (r0) of the read half, its colour
    // in r2 (and r6); the counts as `band_call`'s. A slot it refuses (marked empty) is
    // the set-up's.
    "40:",
    "movs r1, #84",
    "muls r0, r1",
    "ldr r1, [r7, #116]",
    "adds r1, r1, r0",
    "ldr r0, [r7, #76]",
    "str r2, [r0, #{color}]",
    "mov r6, r2",
    "bl zraster_small_resume_v6m",
    "adds r1, r0, #1",
    "bne 1f",
    "mov r2, r6",
    "b 22b",
    "1:",
    "ldr r1, [r7, #88]",
    "adds r1, r1, r0",
    "str r1, [r7, #88]",
    "bmi 2f",
    "b 60b",
    "2:",
    "b 10b",
    // A kept face drawn (r1 the tested sum, kept for its sign; its colour in r6): the
    // set-up clears `save` once it kept the walk there; where it did not (no rows
    // past the band), the slot marked empty (its kept row i32::MAX: the band below sets
    // the face up). The colour kept for the band below while there is room.
    "41:",
    "ldr r0, [r7, #76]",
    "ldr r3, [r0, #{save}]",
    "cmp r3, #0",
    "beq 1f",
    "movs r2, #0",
    "str r2, [r0, #{save}]",
    "movs r2, #1",
    "lsls r2, r2, #31",
    "subs r2, #1",
    "str r2, [r3, #60]",
    "1:",
    "ldr r3, [r7, #104]",
    "ldr r2, [r7, #108]",
    "cmp r3, r2",
    "bhs 1f",
    "ldr r2, [r7, #72]",
    "lsls r0, r3, #1",
    "strh r6, [r2, r0]",
    "adds r3, #1",
    "str r3, [r7, #104]",
    "1:",
    "cmp r1, #0",
    "blt 2f",
    "b 60b",
    "2:",
    "b 10b",
    ".size zraster_band_faces_v6m, . - zraster_band_faces_v6m",
    ".popsection",
    color = const WALK_COLOR,
    save = const WALK_SAVE,
);

/// Draw a band's faces from its merged bin chains (`heads` in increasing order, each
/// `face << 2 | chain`, the chains linked through `links`), those the common case
/// covers, into `b`: each face's colour taken from the band above (chain 0) while
/// `carry` has one, else coloured by `color` (one colour, or lit into 5-6-5 written as
/// it is: `Raw565`), and kept for the band below (chain 1) while there is room; drawn
/// by the small triangles' set-up and rows (`Less` with depth writes, a two-byte
/// colour); its pixel counts into `counts` (not the drawn faces, which the band loop
/// does not use). The heads move past each face it takes. Returns
/// where it stopped ([`BandStop`], as `band_faces_less`). On ARMv6-M one assembly
/// loop; elsewhere it leaves every face to the caller ([`BandStop::Refused`]).
#[inline(always)]
pub(crate) fn band_faces_less_v6m<C: Copy>(
    heads: &mut [u32; 4],
    tables: (&[u16], &[[u16; 3]], &[CachedVertex]),
    carry: &mut BandCarry<'_, '_, C>,
    color: &FaceColor<'_, C>,
    b: &mut Buffers<'_, '_, C>,
    counts: &mut FacesCounts,
) -> BandStop {
    #[cfg(all(zraster_thumb, zraster_armv6m))]
    return band_faces_v6m(heads, tables, carry, color, b, counts);
    #[allow(unreachable_code)]
    {
        let _ = (heads, tables, carry, color, b, counts);
        BandStop::Refused
    }
}

/// [`band_faces_less_v6m`] on ARMv6-M (inlined into its one caller, which runs once a
/// band out of line).
#[cfg(all(zraster_thumb, zraster_armv6m))]
#[inline(always)]
fn band_faces_v6m<C: Copy>(
    heads: &mut [u32; 4],
    (links, faces, cache): (&[u16], &[[u16; 3]], &[CachedVertex]),
    carry: &mut BandCarry<'_, '_, C>,
    color: &FaceColor<'_, C>,
    b: &mut Buffers<'_, '_, C>,
    counts: &mut FacesCounts,
) -> BandStop {
    // The block is started only for a two-byte `C` aligned to two: the carried
    // colours are read and kept as u16s too.
    let Some(walk) = b.walk_block() else {
        return BandStop::Refused;
    };
    let at = faces.as_ptr() as u32;
    let filled = carry.filled.min(carry.read.len()) as u32;
    // Only compared with `filled` (at most the read half's length) and counted on: the
    // delta goes back into the caller's cursor.
    let taken0 = (*carry.taken).min(carry.read.len() + 1) as u32;
    let kept0 = (*carry.kept).min(carry.keep.len()) as u32;
    // The walks the band above kept, resumed below `sfilled` (none where its clip's
    // columns were not this band's); slot `kept` of the other half for a face kept
    // while every colour kept so far has its walk beside it (below `sroom`, else
    // `sroom` is what was saved: no more).
    let states = &mut *carry.states;
    // The clip's columns (inside the buffers: below 2¹⁶) in one word.
    let (saved, kept_above, columns) = (
        states.saved,
        states.filled,
        b.clip.x0 as u16 as u32 | (b.clip.x1 as u32) << 16,
    );
    let (above, here) = states.columns();
    let same = *above == columns;
    *here = columns;
    let slots = states.slots;
    let (sread, skeep) = states.halves();
    // Slots both halves hold (all `slots`: none where they would not).
    let slots = match sread.len().min(skeep.len()) >= slots * super::STATE_WORDS {
        true => slots,
        false => 0,
    };
    let sfilled = if same { kept_above.min(slots) } else { 0 } as u32;
    let slots = slots.min(carry.keep.len());
    let sroom = if kept0 as usize == saved {
        slots
    } else {
        saved.min(slots)
    };
    let mut block = BandV6m {
        light: [0; 3],
        ambient: 0,
        diffuse: 0,
        round: 1 << 12,
        channels: [0; 3],
        half: 0,
        k: 32_897,
        nend: at,
        ndelta: 0,
        faces: at,
        links: links.as_ptr() as u32,
        n: links.len().min(faces.len()).min(u32::MAX as usize) as u32,
        len: cache.len().min(u32::MAX as usize) as u32,
        walk: walk as u32,
        entries: cache.as_ptr() as u32,
        flat: 0,
        tested: 0,
        sfilled,
        heads: *heads,
        read: carry.read.as_ptr() as u32,
        keep: carry.keep.as_mut_ptr() as u32,
        filled,
        taken: taken0,
        kept: kept0,
        room: carry.keep.len().min(u32::MAX as usize) as u32,
        least: 0,
        sread: sread.as_ptr() as u32,
        skeep: skeep.as_mut_ptr() as u32,
        sroom: sroom.min(u32::MAX as usize) as u32,
    };
    match *color {
        FaceColor::Flat(c) => match super::rows::as_u16(&mut [], c) {
            Some((_, bits)) => block.flat = 1 << 16 | u32::from(bits),
            None => return BandStop::Refused,
        },
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
        FaceColor::Lit(_, _, None) => return BandStop::Refused,
    }
    let status = loop {
        let failed = walk.wrapping_add(WALK_FAILED).cast::<u32>();
        // SAFETY: as `faces_v6m`'s (the set-up block's `failed`), the call: the block
        // as built above (see the assembly's SAFETY comment).
        let (status, failed) = unsafe {
            failed.write(0);
            let status = zraster_band_faces_v6m(&mut block);
            (status, failed.read())
        };
        counts.tested = counts.tested.wrapping_add(u64::from(block.tested));
        counts.failed = counts.failed.wrapping_add(u64::from(failed));
        if status != 3 {
            break status;
        }
        block.tested = 0;
    };
    // A face left with a slot named (refused after the set-up flagged it): the slot
    // unnamed, so that no later walk (the Rust path's included) saves there. The face
    // is not counted: `kept` is still its slot's number (its colour is the caller's to
    // keep), below `sroom`. The slots saved are those below where `sroom` and `kept`
    // stop; the next entry names more only if this band's colours and slots still
    // follow one for one.
    let save = walk.wrapping_add(WALK_SAVE).cast::<u32>();
    // SAFETY: the started block's `save` (a word at its pinned offset), as `failed`.
    unsafe { save.write(0) };
    states.saved = block.sroom.min(block.kept) as usize;
    // The face it left (1, 2): the heads and the carry as before it, for the caller's
    // loop (its next head taken out again, the face's put back in front; a taken
    // colour of a refused face given back).
    if status == 1 || status == 2 {
        let least = block.least;
        let f = (least >> 2) as usize;
        let link = links.get(f).map_or(0, |&l| u32::from(l));
        let next = least.wrapping_add(link.wrapping_sub(f as u32).wrapping_mul(4));
        // The heads before it: those below `next` (the first equal one: hostile bins
        // may repeat heads) one place up, the face's in front.
        if let Some(p) = block.heads.iter().position(|&h| h == next) {
            block.heads.copy_within(0..p, 1);
            block.heads[0] = least;
        }
        if status == 2 && least & 3 == 0 {
            block.taken = block.taken.wrapping_sub(1);
        }
    }
    *heads = block.heads;
    *carry.taken = carry
        .taken
        .wrapping_add(block.taken.wrapping_sub(taken0) as usize);
    *carry.kept = block.kept as usize;
    match status {
        0 => BandStop::Done,
        _ => BandStop::Whole(block.least),
    }
}

/// On-target check of the ARMv6-M face loop (`faces_less_v6m`) against its twin (the
/// scan's, the colour's and the set-up's portable twins face by face), for the bench
/// firmware: `cases` random meshes (up to 16 faces over up to 12 cache entries, some
/// unplaced or far apart, indices out of range; normals for some faces only; lit or
/// one colour; the three cull modes) drawn into copies of the same random 48 × 16
/// buffers (the colour rows at both alignments to the depth rows, clips of the whole
/// or part; the loop without the corners' test where no entry is unplaced, on half the
/// cases, its calls over a few faces on some), the faces the loop leaves drawn by the
/// twin as the renderer would. `buf`
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
        // The loop without the corners' test where none is unplaced, on half the
        // cases (with it on the others).
        let placed = case / 8 % 2 == 0 && cache.iter().all(|e| e.xy().0.unsigned_abs() < 1 << 14);
        // Now and then `placed` claimed for a cache with unplaced entries (never the
        // renderer's state): the picture may be wrong, but nothing outside the clip is
        // written (the SAFETY argument of the `back` loops).
        let wrong = case % 16 == 7 && !placed;
        let placed = placed || wrong;
        // The `back` loop's calls over all the faces or a few at a time.
        let chunk = match case / 16 % 4 {
            0 => FLUSH,
            k => 2 * k as u32 - 1,
        };
        let _ = chunk;
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
        // A normal for every face on a third of the cases (the back loop's lit case).
        let count = match rnd() as usize % (faces.len() + 2) {
            _ if case % 3 == 1 => faces.len(),
            n => n,
        };
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
            let scan = (&regs, faces, cache);
            #[cfg(all(zraster_thumb, zraster_armv6m))]
            let stop = faces_v6m(&mut pos, scan, placed, chunk, &color, &mut b, &mut mine);
            #[cfg(not(all(zraster_thumb, zraster_armv6m)))]
            let stop = faces_less_v6m(&mut pos, scan, placed, &color, &mut b, &mut mine);
            match stop {
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
        if wrong {
            // Only the pixels outside the clip are compared, with the untouched copy.
            let inside = |k: usize| {
                let (x, y) = ((k % W) as i32, (k / W) as i32 + first_row);
                (clip.x0..clip.x1).contains(&x) && (clip.y0..clip.y1).contains(&y)
            };
            let depth_out =
                (z1.iter().zip(z2.iter()).enumerate()).any(|(k, (a, b))| !inside(k) && a != b);
            let color_out = (c1.iter().zip(c2.iter()).enumerate())
                .any(|(j, (a, b))| (j < off || !inside(j - off)) && a != b);
            if depth_out || color_out {
                bad += 1;
            }
            continue;
        }
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

/// On-target check of the ARMv6-M band loop (`band_faces_less_v6m`) against its twin
/// (the band loop's merge, carry, colour and the set-up's portable twin, face by
/// face), for the bench firmware: the cases of
/// [`check_band_faces_kernel`](super::check_band_faces_kernel) (random bands and bins,
/// every other case two bands one below the other) with the colours this loop takes.
/// Returns the number of cases whose buffers, pixel counts, heads or carry differ, or
/// where the loop refuses on ARMv6-M. `buf` holds four 48 × 16 buffers (a shorter one
/// is a failure). No walks are kept ([`check_band_carry_v6m_kernel`] keeps them).
#[inline(never)]
pub fn check_band_faces_v6m_kernel(buf: &mut [u16], cases: usize) -> usize {
    band_faces_cases::<V6mLoop>(buf, &mut [], cases, 0xa54f_f53a)
}

/// [`check_band_faces_v6m_kernel`] with the kept faces' walks in `carry` (up to four
/// slots a band, none on some cases): the loop keeps them in the first band and
/// resumes them in the second, where the twin sets them up again. `carry` holds at
/// least [`BandBuffers::carry_needed`](crate::BandBuffers::carry_needed)`(4)` words (a
/// shorter one is a failure).
#[inline(never)]
pub fn check_band_carry_v6m_kernel(buf: &mut [u16], carry: &mut [u32], cases: usize) -> usize {
    match carry.get_mut(..2 * 4 * super::STATE_WORDS) {
        Some(carry) => band_faces_cases::<V6mLoop>(buf, carry, cases, 0x510e_527f),
        None => usize::MAX,
    }
}

/// ARMv6-M's band loop ([`band_faces_less_v6m`]; it leaves every face to the twin
/// elsewhere) for the band checks: packed 5-6-5 light only, diffuse weights within
/// ±2¹⁶.
struct V6mLoop;

impl BandLoop for V6mLoop {
    const ANY_LIT: bool = false;
    const DIFFUSE_SHIFT: u32 = 0;
    const NEVER_REFUSES: bool = FACES_V6M_KERNEL;
    const TWIN: SmallTwin = super::rows_v6m::small_walk_portable;
    // Started once a band, in place: the loop's calls share its set-up block (and what
    // the wrapper leaves in it), as a frame's do.
    type Rows<'a> = Buffers<'a, 'a, u16>;
    #[inline(always)]
    fn rows<'a>(
        z: &'a mut [u16],
        c: &'a mut [u16],
        (first_row, clip): (i32, crate::raster::Clip),
    ) -> Self::Rows<'a> {
        Buffers::unstarted(z, c, 48, first_row, clip)
    }
    #[inline(always)]
    fn parts<'r>(b: &'r mut Self::Rows<'_>) -> (&'r mut [u16], &'r mut [u16]) {
        b.parts()
    }
    #[inline(always)]
    fn run(
        heads: &mut [u32; 4],
        tables: (&[u16], &[[u16; 3]], &[CachedVertex]),
        carry: &mut BandCarry<'_, '_, u16>,
        color: &FaceColor<'_, u16>,
        b: &mut Self::Rows<'_>,
        counts: &mut FacesCounts,
    ) -> BandStop {
        b.start_once();
        match band_faces_less_v6m(heads, tables, carry, color, b, counts) {
            // It leaves a face with the heads before it: past it, as the checks take it.
            BandStop::Whole(_) => {
                let n = tables.0.len().min(tables.1.len());
                match merge_next(heads, tables.0, n) {
                    Some(h) => BandStop::Whole(h),
                    None => BandStop::Done,
                }
            }
            stop => stop,
        }
    }
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

    #[test]
    fn band_faces_v6m_kernel_matches_its_twin() {
        let mut buf = [0u16; 4 * 48 * 16];
        assert_eq!(check_band_faces_v6m_kernel(&mut buf, 4_000), 0);
        assert_eq!(check_band_faces_v6m_kernel(&mut buf[..100], 1), usize::MAX);
        let mut carry = [0u32; 2 * 4 * super::super::STATE_WORDS];
        assert_eq!(check_band_carry_v6m_kernel(&mut buf, &mut carry, 4_000), 0);
        assert_eq!(
            check_band_carry_v6m_kernel(&mut buf, &mut carry[1..], 1),
            usize::MAX
        );
    }
}
