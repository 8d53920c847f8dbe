//! The whole frame's face loop of a cached mesh in one assembly loop on ARMv7E-M: the
//! cull scan, the face's colour and the small triangle's set-up and rows, face after
//! face with no Rust between them. Its portable twin is the renderer's own loop (the
//! cull walk, `lit_565` and `small_less_cached`), which also takes every face this
//! loop leaves to it.
#![allow(unsafe_code)]

use super::cull::{CullScan, ScanRegs};
use super::light::LightBlock;
use super::rows::{RowsLess, SmallTarget};
use super::CachedVertex;
use core::marker::PhantomData;
use embedded_graphics::pixelcolor::{Bgr565, Rgb565};

/// Whether [`faces_less`] runs the assembly loop (ARMv7E-M); elsewhere it leaves every
/// face to the caller and the renderer does not call it.
pub(crate) const FACES_KERNEL: bool = cfg!(all(zraster_thumb, zraster_dsp));

/// The colour of every face of the fused loop.
#[cfg_attr(not(all(zraster_thumb, zraster_dsp)), allow(dead_code))]
#[derive(Clone, Copy)]
pub(crate) enum FaceColor<'b, C> {
    /// One colour for all.
    Flat(C),
    /// Lit by the block (`lit_565`), the packed value made a `C` by the function (with
    /// [`Raw565`], written as it is).
    Lit(&'b LightBlock<'b>, fn(u16) -> C, Option<Raw565<C>>),
}

/// Proof that the colour `Material::packed_565`'s function makes of a packed value `c`
/// is two bytes holding `c`, so the fused loop writes `c` with no call. Only made here:
/// for `Rgb565` and `Bgr565` (their one field the `RawU16` of `c`; the test
/// `raw_565_is_the_packed_value` checks every value) and for the check's `u16`.
#[doc(hidden)]
#[derive(Clone, Copy, Debug)]
pub struct Raw565<C>(PhantomData<fn() -> C>);

const _: () = {
    use core::mem::{align_of, size_of};
    assert!(size_of::<Rgb565>() == 2 && align_of::<Rgb565>() == 2);
    assert!(size_of::<Bgr565>() == 2 && align_of::<Bgr565>() == 2);
};

impl Raw565<Rgb565> {
    /// The proof for `Rgb565`, its function `|c| Rgb565::from(RawU16::new(c))`.
    pub(crate) const PROOF: Self = Self(PhantomData);
}

impl Raw565<Bgr565> {
    /// The proof for `Bgr565`, its function `|c| Bgr565::from(RawU16::new(c))`.
    pub(crate) const PROOF: Self = Self(PhantomData);
}

impl Raw565<u16> {
    /// The proof for `u16`, its function the identity (the checks').
    pub(super) const PROOF: Self = Self(PhantomData);
}

/// The fused loop's pixel and face counts: pixels tested and failed by its fills, and
/// the faces it drew.
#[derive(Clone, Copy, Default, Debug, PartialEq, Eq)]
pub(crate) struct FacesCounts {
    pub tested: u64,
    pub failed: u64,
    pub drawn: u32,
}

impl FacesCounts {
    /// Add what a fused loop counted in its block: the 64-bit tested and failed sums
    /// (two words each) with the running 32-bit ones not yet flushed into them, and the
    /// drawn faces as its flushes of [`FLUSH`] and the countdown to the next.
    #[cfg_attr(not(all(zraster_thumb, zraster_dsp)), allow(dead_code))]
    fn add_loop(
        &mut self,
        (tested, run, failed, rows_failed): ([u32; 2], u32, [u32; 2], u32),
        (flushes, countdown): (u32, u32),
    ) {
        let wide = |w: [u32; 2]| u64::from(w[0]) | u64::from(w[1]) << 32;
        let tested = wide(tested).wrapping_add(u64::from(run));
        let failed = wide(failed).wrapping_add(u64::from(rows_failed));
        self.tested = self.tested.wrapping_add(tested);
        self.failed = self.failed.wrapping_add(failed);
        let drawn = flushes.wrapping_mul(FLUSH).wrapping_add(FLUSH - countdown);
        self.drawn = self.drawn.wrapping_add(drawn);
    }
}

/// Where [`faces_less`] stopped.
#[cfg_attr(not(all(zraster_thumb, zraster_dsp)), allow(dead_code))]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum FacesStop<'a> {
    /// At face `pos` (or the end), which it does not know what to do with (a bad index,
    /// an unplaced corner): the caller's walk's.
    Scan,
    /// Past face `k`, found drawn but left to the caller (no normal for its colour, or
    /// a triangle the set-up refuses), with its corners.
    Face(usize, [&'a CachedVertex; 3]),
    /// Not run: the buffers or the scan are not the loop's (nothing moved).
    Refused,
}

/// What the assembly loop reads and writes, at the offsets in the comments: the rows'
/// block of the set-up, the scan's place and operands (in the order of its registers),
/// the set-up's operands, the colour, the counts.
#[cfg_attr(not(all(zraster_thumb, zraster_dsp)), allow(dead_code))]
#[repr(C)]
struct FacesBlock {
    rows: RowsLess, // 0
    /// The next face's address and the faces left from it.
    face: *const [u16; 3], // 84
    left: u32,      // 88
    /// The scan's x/y word address, entries, −lo, span, mark and faces' number.
    scan: [u32; 6], // 92
    /// The set-up's depth row 0 address, clip y0, y1, x0, x1, pitch and colour delta.
    setup: [u32; 7], // 116
    /// The colour's bits (one colour for all).
    color: u32, // 144
    /// The light block and the function making a packed value a `C`.
    light: *const u8, // 148
    to_color: *const u8, // 152
    tested: [u32; 2], // 156
    failed: [u32; 2], // 164
    /// Faces to draw before the next flush (8192 down to 1).
    drawn: u32, // 172
    /// Pixels tested since the last flush into `tested` (those failed: the rows' `failed`).
    run: u32, // 176
    /// Flushes so far (8192 faces drawn each).
    flushes: u32, // 180
}

#[cfg(target_pointer_width = "32")]
const _: () = {
    use core::mem::offset_of;
    type B = FacesBlock;
    assert!(offset_of!(B, face) == 84 && offset_of!(B, left) == 88);
    assert!(offset_of!(B, scan) == 92 && offset_of!(B, setup) == 116);
    assert!(offset_of!(B, color) == 144 && offset_of!(B, light) == 148);
    assert!(offset_of!(B, to_color) == 152 && offset_of!(B, tested) == 156);
    assert!(offset_of!(B, failed) == 164 && offset_of!(B, drawn) == 172);
    assert!(offset_of!(B, run) == 176 && offset_of!(B, flushes) == 180);
};

/// Faces drawn between the fused loop's flushes of its 32-bit sums (the `8192` there).
#[cfg_attr(not(all(zraster_thumb, zraster_dsp)), allow(dead_code))]
const FLUSH: u32 = 8192;

/// The colour of a face into the rows' block (at 12): the block's, stored there once
/// (`flat`), or (`lit`) `lit_565` of the face (r1) through the function making it a
/// `C`, or (`raw`) as it is (a face without a normal is left to the caller, at 68).
#[cfg(all(zraster_thumb, zraster_dsp))]
#[rustfmt::skip]
macro_rules! faces_color {
    (flat) => {
        ""
    };
    (lit) => {
        concat!(
            "ldr r0, [r7, #148]\n",
            lit_565_asm!(),
            "lsrs r1, r0, #16\n",
            "bne 68f\n",
            "ldr r1, [r7, #152]\n",
            "bl {bits}\n",
            "str r0, [r7, #12]\n",
        )
    };
    (raw) => {
        concat!(
            "ldr r0, [r7, #148]\n",
            lit_565_asm!(),
            "lsrs r1, r0, #16\n",
            "bne 68f\n",
            "str r0, [r7, #12]\n",
        )
    };
}

/// The fused loop (the block in r0): the scan to the next face not dropped; a drawn
/// face's colour (`$color`, [`faces_color`]), set-up and rows (`small_body`), its
/// counts into the block, and on. Ends with r0 0 when the scan stopped (the faces left
/// in the block), 1 at a drawn face left to the caller (the faces left after it).
#[cfg(all(zraster_thumb, zraster_dsp))]
#[rustfmt::skip]
macro_rules! faces_body {
    ($color:ident) => {
        concat!(
            "push {{r6, r7}}\n",
            "mov r7, r0\n",
            // The entries' address (the x/y words' less 4), kept in r6.
            "ldr r6, [r7, #92]\n",
            "subs r6, #4\n",
            // The colour (one for all: the block's), its delta and the pitch into the
            // rows' block once: the set-up's `fused` form does not store them.
            "ldr r0, [r7, #144]\n",
            "ldr r1, [r7, #140]\n",
            "strd r0, r1, [r7, #12]\n",
            "ldr r0, [r7, #136]\n",
            "str r0, [r7, #40]\n",
            "60:\n",
            "add r0, r7, #84\n",
            "ldm r0, {{r0, r1, r2, r3, r4, r5, r12, lr}}\n",
            "cbz r1, 3f\n",
            dsp_cull_scan!(),
            // Stopped (r1 the faces left from the face it stopped at).
            "3:\n",
            "str r1, [r7, #88]\n",
            "movs r0, #0\n",
            "b 69f\n",
            // Drawn: the place after it, its number (r1), its indices (r8–r10).
            "4:\n",
            "subs r2, r1, #1\n",
            "strd r0, r2, [r7, #84]\n",
            "sub r1, lr, r1\n",
            "ldrh r8, [r0, #-6]\n",
            "ldrh r9, [r0, #-4]\n",
            "ldrh r10, [r0, #-2]\n",
            faces_color!($color),
            // The set-up's operands (as `small_less_dsp` hands them over).
            "add r1, r6, r8, lsl #3\n",
            "add r2, r6, r9, lsl #3\n",
            "add r3, r6, r10, lsl #3\n",
            "mov r0, r7\n",
            small_body!(
                fused,
                "ldrsh",
                "6",
                "ldrsh",
                "4",
                "0",
                "ldrsh r6, [lr, #4]\nldrsh r7, [lr, #6]\nldr r8, [lr]\n"
            ),
            // Refused by the set-up: the caller's. Else its counts: drawn, and tested
            // into a 32-bit sum (failed the rows add up at 44), both flushed into the
            // 64-bit sums every 8192 drawn faces (each tests < 2^18.01 pixels: no wrap).
            "cbnz r2, 68f\n",
            "ldrd r4, r5, [r7, #172]\n",
            "subs r4, #1\n",
            "add r5, r1\n",
            "strd r4, r5, [r7, #172]\n",
            "bne 60b\n",
            "ldrd r8, r9, [r7, #156]\n",
            "adds r8, r8, r5\n",
            "adc r9, r9, #0\n",
            "ldrd r10, r11, [r7, #164]\n",
            "ldr r4, [r7, #44]\n",
            "adds r10, r10, r4\n",
            "adc r11, r11, #0\n",
            "strd r8, r9, [r7, #156]\n",
            "strd r10, r11, [r7, #164]\n",
            "movs r4, #0\n",
            "str r4, [r7, #176]\n",
            "str r4, [r7, #44]\n",
            "ldr r4, [r7, #180]\n",
            "adds r4, #1\n",
            "str r4, [r7, #180]\n",
            "mov r4, #8192\n",
            "str r4, [r7, #172]\n",
            "b 60b\n",
            "68:\n",
            "movs r0, #1\n",
            "69:\n",
            "pop {{r6, r7}}\n",
        )
    };
}

/// The packed colour `c` made a `C` by `to` (a `fn(u16) -> C`), as its two bytes:
/// called by the fused loop, so that it writes only the bits of a `C` the function
/// made.
#[cfg(all(zraster_thumb, zraster_dsp))]
extern "C" fn bits_of<C: Copy>(c: u32, to: *const u8) -> u32 {
    // SAFETY: `faces_less` hands over a `fn(u16) -> C` as a pointer (the same size).
    let f = unsafe { core::mem::transmute::<*const u8, fn(u16) -> C>(to) };
    super::rows::as_u16(&mut [], f(c as u16)).map_or(0, |(_, bits)| u32::from(bits))
}

/// A fused loop's `asm!` for the colouring `to_color` names (raw 5-6-5, lit through
/// the caller's function, or one flat colour): the loop `$body!` with its block in r0
/// (its status back), every register it and its calls write declared, the floating-point
/// ones too. Both bodies push r6 and r7 (not allowed as operands) first and pop them
/// last, r7 holding the block meanwhile; their calls (`bits_of`, the set-up's
/// `wide_steps_c`) keep r4–r11 and the stack 8-aligned; the flags are scratch. The
/// bounds argument is each caller's SAFETY comment.
#[cfg(all(zraster_thumb, zraster_dsp))]
macro_rules! fused_asm {
    ($body:ident, $block:ident, $to_color:expr) => {{
        let status: u32;
        if let Some((_, true)) = $to_color {
            fused_asm!(@one $body raw, $block, status);
        } else if let Some((f, _)) = $to_color {
            $block.to_color = f as *const u8;
            fused_asm!(@one $body lit, $block, status, bits = sym bits_of::<C>,);
        } else {
            fused_asm!(@one $body flat, $block, status);
        }
        status
    }};
    (@one $body:ident $kind:ident, $block:ident, $status:ident $(, $($extra:tt)*)?) => {
        core::arch::asm!(
            $body!($kind),
            inout("r0") &mut $block as *mut _ => $status,
            out("r1") _, out("r2") _, out("r3") _, out("r4") _, out("r5") _,
            out("r8") _, out("r9") _, out("r10") _, out("r11") _,
            out("r12") _, out("lr") _,
            wide = sym super::rows::wide_steps_c,
            $($($extra)*)?
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

/// Draw the faces of `scan` from `*pos` on into `t`, those the common case covers: the
/// scan past the dropped faces, each drawn face coloured by `color` and drawn by the
/// small triangles' set-up and rows (`small_less_cached`: the depth test `Less` with
/// depth writes, a two-byte colour), its counts into `counts`. Returns where it
/// stopped ([`FacesStop`]): `*pos` the face it stopped at, or the one after the face it
/// leaves to the caller. On ARMv7E-M one assembly loop; elsewhere it leaves every face
/// to the caller ([`FacesStop::Refused`]).
#[inline(always)]
pub(crate) fn faces_less<'a, C: Copy>(
    pos: &mut usize,
    scan: (&ScanRegs<'_>, &'a [[u16; 3]], &'a [CachedVertex]),
    color: &FaceColor<'_, C>,
    t: &mut SmallTarget<'_, '_, C>,
    counts: &mut FacesCounts,
) -> FacesStop<'a> {
    #[cfg(all(zraster_thumb, zraster_dsp))]
    return faces_less_dsp(pos, scan, color, t, counts);
    #[allow(unreachable_code)]
    {
        let _ = (pos, scan, color, t, counts);
        FacesStop::Refused
    }
}

/// [`faces_less`] on ARMv7E-M. Out of line (it runs once for a run of faces): its
/// block is not stacked on the caller's frame.
#[cfg(all(zraster_thumb, zraster_dsp))]
#[inline(never)]
fn faces_less_dsp<'a, C: Copy>(
    pos: &mut usize,
    (regs, faces, cache): (&ScanRegs<'_>, &'a [[u16; 3]], &'a [CachedVertex]),
    color: &FaceColor<'_, C>,
    t: &mut SmallTarget<'_, '_, C>,
    counts: &mut FacesCounts,
) -> FacesStop<'a> {
    // Operands that are those of a scan of `faces` over `cache` (`CullScan::new`: x/y
    // at byte 4 of the 8-byte entries, an entry's address the word's less 4); a face
    // left.
    let xy_at = cache.as_ptr().cast::<u8>().wrapping_add(4);
    let own = regs.xy == xy_at
        && regs.len == cache.len()
        && regs.faces == faces.as_ptr()
        && regs.faces_len == faces.len();
    if !own || *pos >= faces.len() {
        return FacesStop::Refused;
    }
    let (probe, light, to_color) = match *color {
        FaceColor::Flat(c) => (c, core::ptr::null(), None),
        FaceColor::Lit(b, f, raw) => (
            f(0),
            core::ptr::from_ref(b).cast::<u8>(),
            Some((f, raw.is_some())),
        ),
    };
    let clip = t.clip;
    let (first_row, width) = (t.first_row, t.width);
    let Some((z, c, bits)) = t.kernel_buffers(probe) else {
        return FacesStop::Refused;
    };
    let zaddr = z.as_mut_ptr() as u32;
    let pitch = (width as u32).wrapping_mul(2);
    let zrow0 = zaddr.wrapping_sub((first_row as u32).wrapping_mul(pitch));
    let delta = (c.as_mut_ptr() as u32).wrapping_sub(zaddr);
    let mut block = FacesBlock {
        rows: RowsLess::new(0, 0),
        face: regs.faces.wrapping_add(*pos),
        left: (regs.faces_len - *pos) as u32,
        scan: [
            regs.xy as u32,
            regs.len as u32,
            regs.neg_lo as u32,
            regs.span,
            regs.mark as u32,
            regs.faces_len as u32,
        ],
        setup: [
            zrow0,
            clip.y0 as u32,
            clip.y1 as u32,
            clip.x0 as u32,
            clip.x1 as u32,
            pitch,
            delta,
        ],
        color: u32::from(bits),
        light,
        to_color: core::ptr::null(),
        tested: [0; 2],
        failed: [0; 2],
        drawn: FLUSH,
        run: 0,
        flushes: 0,
    };
    let status: u32;
    // SAFETY: the loop composes three blocks whose bounds arguments hold as they do
    // alone. The scan (`dsp_cull_scan`) is `skip_culled_dsp`'s over operands tested
    // above to be those of `faces` and `cache` (`regs.len` = the cache's length), from
    // face `pos` < the faces' number with the faces left from it: it reads only faces
    // and entries below `regs.len`; its place is stored back before anything else
    // runs, and taken up again from there. A drawn face's entries are the word's
    // address less 4 (r6) plus 8·index, for indices it has found below `len`: three
    // `CachedVertex` of the cache (8 bytes each, the word at byte 4). The colour (`lit`)
    // reads the light block as `lit_565` does (its SAFETY argument, `f` the face's
    // place below the faces' number) and leaves a face with no normal to the caller;
    // its value becomes a `C` by `bits_of`, which calls the caller's function (handed
    // over as a pointer, `to_color`) and returns that
    // `C`'s two bytes (`two_bytes`, checked by `kernel_buffers`): only the bits of a
    // `C` are written; with a `Raw565` (`raw`) the value itself, which is those bytes.
    // The set-up and rows (`small_body`, its `fused` form) are `small_less_dsp`'s with
    // the same operands (depth row 0's address, the clip, the pitch, the colour's
    // delta, worked out as there from `kernel_buffers`' slices: every row and column
    // of the clip inside both buffers; the delta and pitch stored into the rows' block
    // once before the loop, the colour each face or once, zrow0 and the clip read
    // from `setup`, none of them written by the rows) and the same block
    // (`RowsLess` at offset 0 of this block, word-aligned; its SAFETY argument); a
    // triangle it refuses goes to the caller. The counts are stored into the block by
    // its pinned offsets. Registers and calls: as `fused_asm!` says.
    unsafe {
        status = fused_asm!(faces_body, block, to_color);
    }
    counts.add_loop(
        (block.tested, block.run, block.failed, block.rows.failed()),
        (block.flushes, block.drawn),
    );
    *pos = regs.faces_len - block.left as usize;
    if status == 0 {
        return FacesStop::Scan;
    }
    let k = *pos - 1;
    let get = |i: u16| cache.get(usize::from(i));
    match faces.get(k) {
        Some(&[a, b, c]) => match (get(a), get(b), get(c)) {
            (Some(a), Some(b), Some(c)) => FacesStop::Face(k, [a, b, c]),
            _ => {
                *pos = k;
                FacesStop::Scan
            }
        },
        None => {
            *pos = k;
            FacesStop::Scan
        }
    }
}

/// A band's colours carried from the band above and kept for the band below (the
/// band loop's `ColorCarry`, as [`band_faces_less`] uses it): the colours to take, the
/// half to keep into, how many were kept above, this band's cursors, and the kept
/// faces' set-ups ([`KeptStates`]), which follow the kept colours one for one.
#[cfg_attr(not(all(zraster_thumb, zraster_dsp)), allow(dead_code))]
pub(crate) struct BandCarry<'k, 's, C> {
    pub read: &'k [C],
    pub keep: &'k mut [C],
    pub filled: usize,
    pub taken: &'k mut usize,
    pub kept: &'k mut usize,
    pub states: &'k mut KeptStates<'s>,
}

/// Words of a kept face's set-up ([`KeptStates`]): the rows' block's fields its rows
/// read but the band's own (`sx`, `lo`, `span`, `color`, the two edges' steps `dt`,
/// `sy`), its rows in the first half before any clip, `xmax`, the first row's depth,
/// `px0`, the first row, then the block's words from `t` to `short1` (the second half's
/// rows before any clip among them), as the band loop's `keep_state` saves them.
pub(crate) const STATE_WORDS: usize = 21;

/// How many faces a band carries to the next: their colours (the band loop's
/// `ColorCarry`; faces beyond it are lit again) and, with a caller's scratch, their
/// set-ups ([`KeptStates`]).
pub(crate) const CARRY: usize = 64;

/// The set-ups of a band's faces that reach the band below, kept for it by the fused
/// band loop (ARMv7E-M; ARMv6-M's keeps the walks of `rows_v6m::KEPT_WALK_WORDS`):
/// the band below resumes their rows where this band stops them rather than set them
/// up again. Two halves of the caller's scratch, a slot of [`STATE_WORDS`] a face, at
/// most as many as the colours carried: a band resumes from one what the band above
/// saved, and saves into the other. Only the loop writes a slot, and it counts one
/// only once written, so that a band resumes only set-ups the loop made in this draw.
#[cfg(all(zraster_thumb, any(zraster_dsp, zraster_armv6m)))]
pub(crate) struct KeptStates<'s> {
    /// The two halves, one after the other.
    scratch: &'s mut [u32],
    /// Slots a half holds (each half holds this many [`STATE_WORDS`]).
    pub(super) slots: usize,
    /// The half this band resumes from; it saves into the other.
    read: bool,
    /// Slots of the read half the band above saved.
    pub(super) filled: usize,
    /// Slots of the other half this band has saved.
    pub(super) saved: usize,
    /// ARMv6-M: the clip's columns of the band that saved each half, x0 and x1 in a
    /// word's halves (its walks stay inside them; a band of other columns sets them up
    /// again).
    #[cfg(zraster_armv6m)]
    pub(super) columns: [u32; 2],
}

#[cfg(all(zraster_thumb, any(zraster_dsp, zraster_armv6m)))]
impl<'s> KeptStates<'s> {
    /// Slots for at most `faces` kept faces a band in `scratch` (none when it holds
    /// fewer than two words).
    pub(crate) fn new(scratch: &'s mut [u32], faces: usize) -> Self {
        let slots = (scratch.len() / (2 * STATE_WORDS)).min(faces);
        KeptStates {
            scratch,
            slots,
            read: false,
            filled: 0,
            saved: 0,
            #[cfg(zraster_armv6m)]
            columns: [0; 2],
        }
    }

    /// A new band: what the band before saved is what this one resumes.
    pub(crate) fn start_band(&mut self) {
        self.read = !self.read;
        self.filled = self.saved;
        self.saved = 0;
    }

    /// ARMv6-M: the columns of the band that saved the read half, and those of this
    /// band, which saves into the other.
    #[cfg(zraster_armv6m)]
    pub(super) fn columns(&mut self) -> (&u32, &mut u32) {
        let [a, b] = &mut self.columns;
        if self.read {
            (b, a)
        } else {
            (a, b)
        }
    }

    /// The slots this band resumes from (filled) and saves into (saved so far).
    pub(super) fn halves(&mut self) -> (&[u32], &mut [u32]) {
        let n = self.slots * STATE_WORDS;
        let (a, b) = self.scratch.split_at_mut_checked(n).unwrap_or_default();
        let b = b.get_mut(..n).unwrap_or_default();
        if self.read {
            (b, a)
        } else {
            (a, b)
        }
    }
}

/// Where there is no fused band loop, nothing is kept.
#[cfg(not(all(zraster_thumb, any(zraster_dsp, zraster_armv6m))))]
pub(crate) struct KeptStates<'s>(core::marker::PhantomData<&'s mut [u32]>);

#[cfg(not(all(zraster_thumb, any(zraster_dsp, zraster_armv6m))))]
impl<'s> KeptStates<'s> {
    /// Nothing kept.
    #[inline(always)]
    pub(crate) fn new(_scratch: &'s mut [u32], _faces: usize) -> Self {
        KeptStates(core::marker::PhantomData)
    }

    /// Nothing to do.
    #[inline(always)]
    pub(crate) fn start_band(&mut self) {}
}

/// Where [`band_faces_less`] stopped; a face left to the caller as its chain's head
/// `face << 2 | chain` (the heads already past it).
#[cfg_attr(not(all(zraster_thumb, zraster_dsp)), allow(dead_code))]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum BandStop {
    /// At the end of the band's faces.
    Done,
    /// At a face it leaves whole to the caller (tall, or no normal for its colour),
    /// the carry untouched by it.
    Whole(u32),
    /// At a face whose carry it has done (a colour taken, a colour kept) but which it
    /// does not draw (a corner past the cache, or refused by the set-up).
    Fill(u32),
    /// Not run: the buffers or the colour are not the loop's (nothing moved).
    Refused,
}

/// What the band loop reads and writes, at the offsets in the comments: the rows'
/// block, the merge's heads and tables, the set-up's operands and the colour at the
/// offsets of [`FacesBlock`] (the set-up's `fused` form and [`faces_color`] read them
/// there), the carry, the counts.
#[cfg_attr(not(all(zraster_thumb, zraster_dsp)), allow(dead_code))]
#[repr(C)]
struct BandBlock {
    rows: RowsLess, // 0
    /// The chains' heads in increasing order (`face << 2 | chain`).
    heads: [u32; 4], // 84
    links: *const u16, // 100
    /// Faces below which both the links and the faces' indices lie.
    n: u32, // 104
    faces: *const [u16; 3], // 108
    /// The cache's entries.
    len: u32, // 112
    setup: [u32; 7], // 116
    color: u32,     // 144
    light: *const u8, // 148
    to_color: *const u8, // 152
    entries: *const CachedVertex, // 156
    /// The colours to take and the half to keep into.
    read: *const u16, // 160
    keep: *mut u16, // 164
    /// Resumed below `sfilled` (the read half's saved set-ups).
    sfilled: u32, // 168
    taken: u32,     // 172
    kept: u32,      // 176
    /// A kept face whose colour goes to `kept` below `sroom` saves its set-up at
    /// `skeep`, slot `kept`: `sroom` is the other half's slots (at most `room`)
    /// while the slots saved follow the kept colours (`kept` of each), else 0.
    sroom: u32, // 180
    /// Taken below `filled` (at most `read`'s length), kept below `room` (`keep`'s).
    filled: u32, // 184
    room: u32,      // 188
    /// The read half's slot `taken` (moved on a slot with each face resumed: they
    /// are the first ones taken, in order), the next slot of the other to save into.
    sread: *const u32, // 192
    skeep: *mut u32, // 196
    tested: [u32; 2], // 200
    failed: [u32; 2], // 208
    /// The pixels tested since the last flush into `tested` (with the rows' `failed`
    /// into `failed`), added by the rows themselves (`small_body`'s `band` and `keep`
    /// forms), below 2³¹ + 2¹⁹ (a flush at 2³¹; a face tests under 2¹⁹).
    run: u32, // 216
    /// The head of the face the loop stopped at.
    least: u32, // 220
}

#[cfg(all(zraster_thumb, zraster_dsp))]
impl BandBlock {
    /// A block to be filled: its counts 0, the rest `v` or null (each written before
    /// the loop reads it).
    #[inline(always)]
    fn splat(v: u32) -> BandBlock {
        BandBlock {
            rows: RowsLess::splat(v),
            heads: [v; 4],
            links: core::ptr::null(),
            n: v,
            faces: core::ptr::null(),
            len: v,
            setup: [v; 7],
            color: v,
            light: core::ptr::null(),
            to_color: core::ptr::null(),
            entries: core::ptr::null(),
            read: core::ptr::null(),
            keep: core::ptr::null_mut(),
            sfilled: v,
            taken: v,
            kept: v,
            sroom: v,
            filled: v,
            room: v,
            sread: core::ptr::null(),
            skeep: core::ptr::null_mut(),
            tested: [0; 2],
            failed: [0; 2],
            run: 0,
            least: 0,
        }
    }
}

#[cfg(target_pointer_width = "32")]
const _: () = {
    use core::mem::offset_of;
    type B = BandBlock;
    assert!(offset_of!(B, heads) == 84 && offset_of!(B, links) == 100);
    assert!(offset_of!(B, n) == 104 && offset_of!(B, faces) == 108);
    assert!(offset_of!(B, len) == 112 && offset_of!(B, setup) == 116);
    assert!(offset_of!(B, color) == 144 && offset_of!(B, light) == 148);
    assert!(offset_of!(B, to_color) == 152 && offset_of!(B, entries) == 156);
    assert!(offset_of!(B, read) == 160 && offset_of!(B, keep) == 164);
    assert!(offset_of!(B, sfilled) == 168 && offset_of!(B, taken) == 172);
    assert!(offset_of!(B, kept) == 176 && offset_of!(B, sroom) == 180);
    assert!(offset_of!(B, filled) == 184 && offset_of!(B, room) == 188);
    assert!(offset_of!(B, sread) == 192 && offset_of!(B, skeep) == 196);
    assert!(offset_of!(B, tested) == 200 && offset_of!(B, failed) == 208);
    assert!(offset_of!(B, run) == 216 && offset_of!(B, least) == 220);
};

/// The colour of a face into the rows' block (at 12) and r0 for the band loop: the
/// block's one colour, or `faces_color`'s.
#[cfg(all(zraster_thumb, zraster_dsp))]
#[rustfmt::skip]
macro_rules! band_color {
    (flat) => {
        concat!(
            "ldr r0, [r7, #144]\n",
            "str r0, [r7, #12]\n",
        )
    };
    ($kind:ident) => {
        faces_color!($kind)
    };
}

/// The least head's face's corners (r8 the head): its three indices, each below the
/// cache's length (else the caller's, at `$bad`), made the entries' addresses in r1–r3
/// as `small_less_dsp` hands them over, the block in r0.
#[cfg(all(zraster_thumb, zraster_dsp))]
#[rustfmt::skip]
macro_rules! band_corners {
    ($bad:literal) => {
        concat!(
            "ldrd r0, lr, [r7, #108]\n",
            "lsr r12, r8, #2\n",
            "add r12, r12, r12, lsl #1\n",
            "add r12, r0, r12, lsl #1\n",
            "ldrh r1, [r12]\n",
            "ldrh r2, [r12, #2]\n",
            "ldrh r3, [r12, #4]\n",
            "cmp r1, lr\n",
            "itt lo\n",
            "cmplo r2, lr\n",
            "cmplo r3, lr\n",
            concat!("bhs ", $bad, "\n"),
            // The set-up's operands (as `small_less_dsp` hands them over).
            "ldr r0, [r7, #156]\n",
            "add r1, r0, r1, lsl #3\n",
            "add r2, r0, r2, lsl #3\n",
            "add r3, r0, r3, lsl #3\n",
            "mov r0, r7\n",
        )
    };
}

/// A kept face's set-up saved into its slot (the band loop's r4 as pushed, at sp + 16),
/// the next slot made `skeep`, then its rows in this band cut at the clip's last row: the
/// `$hook` of `small_body!(keep, ..)` (its registers there: r3 the first row's depth,
/// r4 px0, r5 the first row, n0 at sp + 8, xmax at sp + 12, n1 at 64, none of them the
/// clip's: the set-up ran unclipped below). Slot layout: [`STATE_WORDS`].
#[cfg(all(zraster_thumb, zraster_dsp))]
#[rustfmt::skip]
macro_rules! keep_state {
    () => {
        concat!(
            "ldr r12, [sp, #16]\n",
            "ldm r0, {{r1, r2, r6, r7}}\n",
            "ldrd r8, r9, [r0, #20]\n",
            "ldr r10, [r0, #36]\n",
            "ldrd r11, lr, [sp, #8]\n",
            "stm r12!, {{r1, r2, r6, r7, r8, r9, r10, r11, lr}}\n",
            "stm r12!, {{r3, r4, r5}}\n",
            "add r1, r0, #48\n",
            "ldm r1, {{r1, r2, r6, r7, r8, r9, r10, r11, lr}}\n",
            "stm r12!, {{r1, r2, r6, r7, r8, r9, r10, r11, lr}}\n",
            // The next slot is the one after it (the caller counts the slots saved
            // from where it ends).
            "str r12, [r0, #196]\n",
            // This band's rows: n0 = min(n0, m), n1 = min(n1, m − n0), m = clip.y1 − first
            // row, at least 0.
            "ldr r12, [r0, #124]\n",
            "sub r12, r12, r5\n",
            "usat r12, #16, r12\n",
            "ldr r1, [sp, #8]\n",
            "cmp r1, r12\n",
            "it hi\n",
            "movhi r1, r12\n",
            "sub r12, r12, r1\n",
            "cmp r8, r12\n",
            "it hi\n",
            "movhi r8, r12\n",
            "str r1, [sp, #8]\n",
            "str r8, [r0, #64]\n",
        )
    };
}

/// The band loop (the block in r7, the heads in r6, r9, r10, r11): the least head's
/// face (the merge: its chain's next face takes the head's place, moved down past the
/// heads below it), its colour (taken from the band above, or `$color`, and kept for
/// the band below), set-up and rows (`small_body`), counts, and on. A face kept for the
/// band below saves its set-up too (`keep_state`) while the slots follow the kept
/// colours one for one; a face taken from the band above whose set-up was saved resumes
/// it at this band's first row instead of being set up again. Ends with r0 0 at the end
/// of the faces, 1 at a face left whole to the caller, 2 at a face whose carry is done
/// but which it does not draw (its head at 220), the heads stored back.
#[cfg(all(zraster_thumb, zraster_dsp))]
#[rustfmt::skip]
macro_rules! band_body {
    ($color:ident) => {
        concat!(
            "push {{r6, r7}}\n",
            "mov r7, r0\n",
            "add r0, r7, #84\n",
            "ldm r0, {{r6, r9, r10, r11}}\n",
            // The colour's delta and the pitch into the rows' block once.
            "ldr r0, [r7, #140]\n",
            "str r0, [r7, #16]\n",
            "ldr r0, [r7, #136]\n",
            "str r0, [r7, #40]\n",
            "60:\n",
            // The least head (r8): its face f (r4) below n, else the end.
            "ldrd r0, r1, [r7, #100]\n",
            "lsr r4, r6, #2\n",
            "cmp r4, r1\n",
            "bhs 66f\n",
            "ldrh r1, [r0, r4, lsl #1]\n",
            "mov r8, r6\n",
            // Its chain's next face (the link in place of the face: r6) moved down
            // past the heads below it.
            "bfi r6, r1, #2, #16\n",
            "cmp r6, r9\n",
            "blo 64f\n",
            // Each head it passes moves up a place as it takes the next one's (MOVs,
            // no IT: the 4-way merge's last head, the tall faces', is mostly END).
            "mov r3, r6\n",
            "mov r6, r9\n",
            "mov r9, r3\n",
            "cmp r3, r10\n",
            "blo 64f\n",
            "mov r9, r10\n",
            "mov r10, r3\n",
            "cmp r3, r11\n",
            "blo 64f\n",
            "mov r10, r11\n",
            "mov r11, r3\n",
            "64:\n",
            // By the chain (one shift: its bit 1 into C, Z set when its bit 0 is clear):
            // tall (3) the caller's; its own (2) worked out (r1 the face); taken (0):
            // resumed while there is a set-up, else the next carried colour while
            // there is one, else worked out, and counted; kept (1): worked out and
            // kept, with its set-up while the slots follow.
            "lsls r5, r8, #31\n",
            "bhi 68f\n",
            "bcs 27f\n",
            "bne 25f\n",
            "ldrd r0, r1, [r7, #168]\n",
            "cmp r1, r0\n",
            "blo 30f\n",
            "ldr r0, [r7, #184]\n",
            "cmp r1, r0\n",
            "bhs 26f\n",
            "ldr r0, [r7, #160]\n",
            "ldrh r0, [r0, r1, lsl #1]\n",
            "adds r1, #1\n",
            "str r1, [r7, #172]\n",
            "str r0, [r7, #12]\n",
            "b 22f\n",
            "25:\n",
            "lsr r1, r8, #2\n",
            band_color!($color),
            "ldrd r1, r2, [r7, #176]\n",
            "cmp r1, r2\n",
            "blo 31f\n",
            "ldr r2, [r7, #188]\n",
            "cmp r1, r2\n",
            "bhs 22f\n",
            "ldr r2, [r7, #164]\n",
            "strh r0, [r2, r1, lsl #1]\n",
            "adds r1, #1\n",
            "str r1, [r7, #176]\n",
            "b 22f\n",
            "26:\n",
            "lsr r1, r8, #2\n",
            band_color!($color),
            "ldr r1, [r7, #172]\n",
            "adds r1, #1\n",
            "str r1, [r7, #172]\n",
            "b 22f\n",
            "27:\n",
            "lsr r1, r8, #2\n",
            band_color!($color),
            // The corners' indices, each below the cache's length, else the caller's.
            "22:\n",
            band_corners!("67f"),
            small_body!(
                band,
                "ldrsh",
                "6",
                "ldrsh",
                "4",
                "0",
                "ldrsh r6, [lr, #4]\nldrsh r7, [lr, #6]\nldr r8, [lr]\n"
            ),
            // Its tested pixels (below 2¹⁹) are in the running sum (r1 the sum, 0 with
            // no rows drawn; N its bit 31), flushed with the rows' failed ones into the
            // 64-bit sums once it reaches 2³¹ (no face count: the bands take none);
            // refused by the set-up (r1 −1, N set, r2 1): the caller's.
            "61:\n",
            "bpl 60b\n",
            "cbnz r2, 67f\n",
            "ldr r5, [r7, #216]\n",
            "ldrd r2, r3, [r7, #200]\n",
            "adds r2, r2, r5\n",
            "adc r3, r3, #0\n",
            "strd r2, r3, [r7, #200]\n",
            "ldrd r2, r3, [r7, #208]\n",
            "ldr r4, [r7, #44]\n",
            "adds r2, r2, r4\n",
            "adc r3, r3, #0\n",
            "strd r2, r3, [r7, #208]\n",
            "movs r4, #0\n",
            "str r4, [r7, #216]\n",
            "str r4, [r7, #44]\n",
            "b 60b\n",
            "66:\n",
            "movs r0, #0\n",
            "b 69f\n",
            "67:\n",
            "movs r0, #2\n",
            "b 65f\n",
            "68:\n",
            "movs r0, #1\n",
            "65:\n",
            "str r8, [r7, #220]\n",
            "69:\n",
            "add r1, r7, #84\n",
            "stm r1, {{r6, r9, r10, r11}}\n",
            "pop {{r6, r7}}\n",
            "b 39f\n",
            // Kept with its set-up (r1 the slot's number, r0 the colour): the colour
            // kept too, counted, the slot's address in r4 for `keep_state`.
            "31:\n",
            "ldr r2, [r7, #164]\n",
            "strh r0, [r2, r1, lsl #1]\n",
            "adds r1, #1\n",
            "str r1, [r7, #176]\n",
            "ldr r4, [r7, #196]\n",
            band_corners!("67b"),
            small_body!(
                keep,
                keep_state!(),
                "str r2, [r0, #180]\n",
                "ldrsh",
                "6",
                "ldrsh",
                "4",
                "0",
                "ldrsh r6, [lr, #4]\nldrsh r7, [lr, #6]\nldr r8, [lr]\n"
            ),
            "b 61b\n",
            // Resumed (r1 the slot's number, taken): the set-up's frame as `small_body`
            // makes it, the saved fields into the rows' block, the rows moved on to
            // this band's first row (skip = clip.y0 − the saved first row s, at least
            // 0: the edges and depth stepped by skip rows, into the second half when
            // the first has no more; the first row s + skip), cut to the clip's rows,
            // then `small_body`'s rows (at 73). Slot layout: [`STATE_WORDS`].
            "30:\n",
            "adds r0, r1, #1\n",
            "str r0, [r7, #172]\n",
            "ldr r12, [r7, #192]\n",
            "add r0, r12, #84\n",
            "str r0, [r7, #192]\n",
            "mov r0, r7\n",
            "push {{r0-r12}}\n",
            "ldm r12!, {{r1, r2, r3, r4, r5, r6, r8}}\n",
            "stm r0, {{r1, r2, r3, r4}}\n",
            "strd r5, r6, [r0, #20]\n",
            "str r8, [r0, #36]\n",
            "ldm r12!, {{r1, r2, r3, r4, r9}}\n",
            "str r2, [sp, #12]\n",
            "ldrd r10, r11, [r0, #120]\n",
            "sub lr, r10, r9\n",
            "usat lr, #16, lr\n",
            "add r10, r9, lr\n",
            "mla r3, lr, r8, r3\n",
            "sub r11, r11, r10\n",
            "usat r11, #16, r11\n",
            "ldrd r2, r7, [r12], #8\n",
            "mla r2, lr, r5, r2\n",
            "subs r1, r1, lr\n",
            "ble 32f\n",
            "mla r7, lr, r6, r7\n",
            "strd r2, r7, [r0, #48]\n",
            "ldm r12, {{r2, r5, r6, r7, r8, r9, lr}}\n",
            "b 33f\n",
            "32:\n",
            "str r2, [r0, #48]\n",
            "ldm r12, {{r2, r5, r6, r7, r8, r9, lr}}\n",
            "rsb r1, r1, #0\n",
            "mla r8, r1, lr, r8\n",
            "sub r6, r6, r1\n",
            "usat r6, #16, r6\n",
            "movs r1, #0\n",
            "33:\n",
            "add r12, r0, #56\n",
            "stm r12, {{r2, r5, r6, r7, r8, r9, lr}}\n",
            "cmp r1, r11\n",
            "it hi\n",
            "movhi r1, r11\n",
            "sub r11, r11, r1\n",
            "cmp r6, r11\n",
            "it hi\n",
            "movhi r6, r11\n",
            "str r1, [sp, #8]\n",
            "str r6, [r0, #64]\n",
            "mov r5, r10\n",
            "b 73b\n",
            "39:\n",
        )
    };
}

/// Draw a band's faces from its merged bin chains (`heads` in increasing order, each
/// `face << 2 | chain`, the chains linked through `links`), those the common case
/// covers: each face's colour taken from the band above (chain 0) while `carry` has
/// one, else coloured by `color`, and kept for the band below (chain 1) while there is
/// room; drawn by the small triangles' set-up and rows (`small_less_cached`: the depth
/// test `Less` with depth writes, a two-byte colour); its pixel counts into `counts`. A face
/// taken from the band above whose set-up `carry.states` holds is not set up again:
/// its rows go on from there; a kept face's set-up is kept too while the slots follow
/// the colours. The heads move past each face it takes. Returns where it stopped
/// ([`BandStop`]). On ARMv7E-M one assembly loop; elsewhere it leaves every face to the
/// caller ([`BandStop::Refused`]).
#[inline(always)]
pub(crate) fn band_faces_less<C: Copy>(
    heads: &mut [u32; 4],
    (links, faces, cache): (&[u16], &[[u16; 3]], &[CachedVertex]),
    carry: &mut BandCarry<'_, '_, C>,
    color: &FaceColor<'_, C>,
    t: &mut SmallTarget<'_, '_, C>,
    counts: &mut FacesCounts,
) -> BandStop {
    #[cfg(all(zraster_thumb, zraster_dsp))]
    return band_faces_less_dsp(heads, (links, faces, cache), carry, color, t, counts);
    #[allow(unreachable_code)]
    {
        let _ = (heads, links, faces, cache, carry, color, t, counts);
        BandStop::Refused
    }
}

/// [`band_faces_less`] on ARMv7E-M. Out of line (it runs once for a band's run of
/// faces): its block is not stacked on the caller's frame.
#[cfg(all(zraster_thumb, zraster_dsp))]
#[inline(never)]
fn band_faces_less_dsp<C: Copy>(
    heads: &mut [u32; 4],
    (links, faces, cache): (&[u16], &[[u16; 3]], &[CachedVertex]),
    carry: &mut BandCarry<'_, '_, C>,
    color: &FaceColor<'_, C>,
    t: &mut SmallTarget<'_, '_, C>,
    counts: &mut FacesCounts,
) -> BandStop {
    let (probe, light, to_color) = match *color {
        FaceColor::Flat(c) => (c, core::ptr::null(), None),
        FaceColor::Lit(b, f, raw) => (
            f(0),
            core::ptr::from_ref(b).cast::<u8>(),
            Some((f, raw.is_some())),
        ),
    };
    let clip = t.clip;
    let (first_row, width) = (t.first_row, t.width);
    // `kernel_buffers` checks `C` is two bytes aligned to two: the carried colours are
    // read and kept as u16s too.
    let Some((z, c, bits)) = t.kernel_buffers(probe) else {
        return BandStop::Refused;
    };
    let zaddr = z.as_mut_ptr() as u32;
    let pitch = (width as u32).wrapping_mul(2);
    // Made with no clearing call, then filled field by field as each is worked out
    // (worked out first, the values were kept on the stack meanwhile).
    let mut block = BandBlock::splat(pitch);
    block.heads = *heads;
    block.links = links.as_ptr();
    block.n = links.len().min(faces.len()).min(u32::MAX as usize) as u32;
    block.faces = faces.as_ptr();
    block.len = cache.len().min(u32::MAX as usize) as u32;
    block.setup = [
        zaddr.wrapping_sub((first_row as u32).wrapping_mul(pitch)),
        clip.y0 as u32,
        clip.y1 as u32,
        clip.x0 as u32,
        clip.x1 as u32,
        pitch,
        (c.as_mut_ptr() as u32).wrapping_sub(zaddr),
    ];
    block.color = u32::from(bits);
    block.light = light;
    block.entries = cache.as_ptr();
    block.read = carry.read.as_ptr().cast::<u16>();
    block.keep = carry.keep.as_mut_ptr().cast::<u16>();
    block.filled = carry.filled.min(carry.read.len()) as u32;
    // Only compared with `filled` (at most the read half's length) and counted on: the
    // delta goes back into the caller's cursor.
    let taken0 = (*carry.taken).min(carry.read.len() + 1) as u32;
    block.taken = taken0;
    let room = carry.keep.len();
    block.kept = (*carry.kept).min(room) as u32;
    block.room = room.min(u32::MAX as usize) as u32;
    // The set-ups: those the band above saved, resumed below `sfilled`; the slots this
    // band saves into (at most one a colour it can keep), from the one after those it
    // has saved.
    let (filled, saved) = (carry.states.filled, carry.states.saved);
    let (sread, skeep) = carry.states.halves();
    let sroom = (skeep.len() / STATE_WORDS).min(room);
    let snext = saved.min(sroom);
    block.sfilled = filled.min(sread.len() / STATE_WORDS) as u32;
    // Read only below `sfilled` (at most the half's slots), as the slot of `taken`.
    block.sread = sread
        .as_ptr()
        .wrapping_add((taken0 as usize).wrapping_mul(STATE_WORDS));
    let skeep_at = skeep.as_mut_ptr().wrapping_add(snext * STATE_WORDS);
    block.skeep = skeep_at;
    // Slots only while they follow the kept colours one for one.
    block.sroom = if block.kept as usize == snext {
        sroom as u32
    } else {
        0
    };
    let status: u32;
    // SAFETY: the loop composes blocks whose bounds arguments hold as they do alone.
    // The merge reads `links[f]` and `faces[f]` only for the least head's face f (the
    // head >> 2) below n, the smaller of the two lengths, whatever the heads and links
    // hold (hostile bins included: END, or any number past the faces, fails the test
    // and ends the loop); the chain's next head is that face's 16-bit link put in place
    // of f by BFI (f < n < 2¹⁶: nothing above it), so again a face and the chain's
    // number, tested the same way when it is least. A face's three indices are each
    // tested below the cache's length before its entries' addresses (entries +
    // 8·index: three `CachedVertex`, 8 bytes each) are formed. The carried colours:
    // one read at `read[taken]` only when taken < filled ≤ `read`'s length, one written
    // at `keep[kept]` only when kept < `keep`'s length (`room`); `C` is two bytes aligned
    // to two (checked by `kernel_buffers`), and every value kept is a `C`'s bytes: one
    // taken from `read`, the flat colour's bits, `bits_of`'s bytes of the caller's
    // function's `C`, or (`raw`) the packed value which `Raw565` proves is those
    // bytes. The colour (`faces_color`) reads the light block as `lit_565` does (its
    // SAFETY argument, r1 the face's number) and leaves a face with no normal to the
    // caller. The set-up and rows (`small_body`, its `fused` form) are `faces_less`'s
    // with the same operands at the same offsets of this block (`RowsLess` at 0,
    // word-aligned; the clip inside both buffers by `kernel_buffers`; its SAFETY
    // argument); a triangle it refuses goes to the caller. The counts are stored into
    // the block by its pinned offsets. The set-ups: a slot is read only for a face taken
    // at `taken` < sfilled ≤ the read half's slots, at `sread`, which starts at slot
    // `taken` and moves on one slot (21 words) with each face resumed, the only ones
    // taking a slot, all taken before any other (once `taken` reaches `sfilled` it only
    // grows): so at slot `taken` then too; one is written only at `skeep`, slot
    // `kept` < sroom ≤ the other half's slots: a kept face saves only below `sroom`,
    // which is 0 unless `skeep` is slot `kept` (so made at the entry, from the slots
    // saved; each save moves both on by one; a kept face whose set-up saves nothing,
    // having no rows, makes it 0 before the loop goes on; one that stops the loop
    // leaves it to the next entry), and at most `room`: its colour is kept at
    // `keep[kept]` then too; then `skeep` moves to the next slot. Every slot below `sfilled` holds what `keep_state` saved there in the
    // band above (`KeptStates`: the loop's count alone makes `sfilled`): a triangle's
    // set-up as `small_body` made it, whose rows the set-up's argument bounds
    // (first row s, its two halves' rows before any clip, each edge's t stepped exactly
    // and its columns inside [0, ⌊(xmax + 8)/16⌋ − px0] on every one of those rows). A
    // resumed face's rows are those rows from s + skip on, skip ≥ 0 (USAT), its edges
    // and depth stepped by skip rows with one MLA each (the values the rows would have
    // stepped to, t below 2²⁸: no wrapping), at most clip.y1 − clip.y0 of them (USAT:
    // at least 0) from clip.y0, and the second half's rows at least 0 (USAT): rows of
    // this band's clip, addressed from its zrow0 and pitch; the columns as the set-up's
    // (the clip's own test at 73 against this band's clip, px0 and xmax). A kept face's
    // set-up (`small_body`'s `keep` form) runs with no last row (0x7fff), then its rows
    // are cut at clip.y1 (n0 ≤ m, n1 ≤ m − n0, m = clip.y1 − s at least 0) before they
    // run. Registers and calls: as `fused_asm!` says.
    unsafe {
        status = fused_asm!(band_body, block, to_color);
    }
    // No face count: the countdown as at the start (none drawn, none flushed).
    counts.add_loop(
        (block.tested, block.run, block.failed, block.rows.failed()),
        (0, FLUSH),
    );
    *heads = block.heads;
    *carry.taken = carry
        .taken
        .wrapping_add(block.taken.wrapping_sub(taken0) as usize);
    *carry.kept = block.kept as usize;
    // The slots saved: those before where `skeep` ended (it moves a slot a save).
    let moved = (block.skeep as usize).wrapping_sub(skeep_at as usize);
    carry.states.saved = (snext + moved / (4 * STATE_WORDS)).min(sroom);
    match status {
        0 => BandStop::Done,
        1 => BandStop::Whole(block.least),
        _ => BandStop::Fill(block.least),
    }
}

/// On-target check of the fused loop (`faces_less`) against its twin (the scan's,
/// the colour's and the set-up's portable twins face by face), for the bench firmware:
/// `cases` random meshes (up to 16 faces over up to 12 cache entries, some unplaced or
/// far apart, indices out of range; normals for some faces only; lit or one colour;
/// the three cull modes) drawn into copies of the same random 48 × 16 buffers (the
/// colour rows at both alignments to the depth rows, clips of the whole or part), the
/// faces the loop leaves drawn by the twin as the renderer would. `buf` holds four
/// 48 × 16 buffers (a shorter one is a failure). Returns the number of cases whose
/// buffers, pixel counts or drawn faces differ (where there is no assembly, the loop
/// leaves every face to the twin).
#[inline(never)]
pub fn check_faces_kernel(buf: &mut [u16], cases: usize) -> usize {
    use super::cull::culled_run_portable;
    use super::light::lit_565_portable;
    use super::rows::{small_less_portable, SmallDone};
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
    let mut rnd = super::xorshift32(0x6a09_e667);
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
        let clip = if case % 3 == 0 {
            let (x0, y0) = ((rnd() % 20) as i32, (rnd() % 6) as i32);
            Clip {
                x0,
                y0: first_row + y0,
                x1: x0 + (rnd() % 30) as i32,
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
        let span = 64 << (case % 4); // 4 to 32 pixels
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
        // Light and normals as `check_light_kernel`'s; the packed value turned.
        let normals = [[0i16; 3]; 16].map(|n| n.map(|_| ((rnd() % 32769) as i32 - 16384) as i16));
        let light = [0; 3].map(|_| (rnd() % 65537) as i32 - 32768);
        let ambient = (rnd() % 131_073) as i32 - 65536;
        let diffuse = ((rnd() % 131_073) as i32 - 65536) << 3;
        let channels = [0; 3].map(|_| rnd() as u8);
        let count = rnd() as usize % (faces.len() + 2);
        let block = LightBlock::new(
            light,
            ambient,
            diffuse,
            channels,
            normals.get(..count).unwrap_or(&normals),
        );
        let turn: fn(u16) -> u16 = |c| c.rotate_left(3);
        let flat = rnd() as u16;
        let same: fn(u16) -> u16 = |c| c;
        let color = match case % 4 {
            3 => FaceColor::Flat(flat),
            2 => FaceColor::Lit(&block, same, Some(Raw565::<u16>::PROOF)),
            _ => FaceColor::Lit(&block, turn, None),
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
        // The fused loop, the faces it leaves drawn by the twin.
        let mut mine = FacesCounts::default();
        let (Some(ca), Some(cb)) = (c1.get_mut(off..), c2.get_mut(off..)) else {
            return usize::MAX;
        };
        let mut t = SmallTarget {
            z: &mut z1[..],
            c: ca,
            width: W,
            first_row,
            clip,
        };
        let mut pos = 0;
        let mut refused = false;
        while pos < faces.len() {
            match faces_less(&mut pos, (&regs, faces, cache), &color, &mut t, &mut mine) {
                FacesStop::Scan => pos += 1,
                FacesStop::Face(k, tri) => {
                    let [p, q, r] = corners(tri);
                    mine.drawn += 1;
                    let (z, c) = (&mut *t.z, &mut *t.c);
                    let done =
                        small_less_portable([&p, &q, &r], &clip, first_row, W, z, c, color_of(k));
                    if let SmallDone::Drawn(tested, failed) = done {
                        mine.tested += u64::from(tested);
                        mine.failed += u64::from(failed);
                    }
                }
                FacesStop::Refused => {
                    // Only where there is no assembly: the twin's face by face.
                    refused = true;
                    break;
                }
            }
        }
        if FACES_KERNEL && refused {
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
                    small_less_portable([&p, &q, &r], &clip, first_row, W, z, c, color_of(k));
                if let SmallDone::Drawn(tested, failed) = done {
                    counts.tested += u64::from(tested);
                    counts.failed += u64::from(failed);
                }
            }
        };
        let mut theirs = FacesCounts::default();
        if refused {
            twin(z1, c1.get_mut(off..).unwrap_or(&mut []), &mut mine);
        }
        twin(z2, cb, &mut theirs);
        if mine != theirs || z1 != z2 || c1 != c2 {
            bad += 1;
        }
    }
    bad
}

/// On-target check of the fused band loop (`band_faces_less`) against its twin (the
/// band loop's merge, carry, colour and the set-up's portable twin, face by face), for
/// the bench firmware: `cases` random bands (buffers, clips, caches, meshes and colours
/// as [`check_faces_kernel`]'s) walked from random bins: four chains' heads, links
/// increasing, ending in `END` or a face past the faces, over links shorter or longer
/// than the faces; tall faces among them; carried colours up to and past the read
/// half, the keep half sometimes full. Every other case is two bands of eight rows, one
/// below the other, the second taking the first's kept faces, the mesh often across
/// the two. The faces the loop leaves are drawn by the twin as the band loop would.
/// Returns the number of cases whose buffers, pixel counts, drawn faces, heads or carry
/// differ. `buf` holds four 48 × 16 buffers (a shorter one is a failure). No set-ups
/// are kept ([`check_band_carry_kernel`] keeps them).
#[inline(never)]
pub fn check_band_faces_kernel(buf: &mut [u16], cases: usize) -> usize {
    band_faces_cases::<DspLoop>(buf, &mut [], cases, 0x3c6e_f372)
}

/// [`check_band_faces_kernel`] with the kept faces' set-ups in `carry` (up to four
/// slots a band, none on some cases): the loop keeps them in the first band and
/// resumes them in the second, where the twin sets them up again. `carry` holds at
/// least [`BandBuffers::carry_needed`](crate::BandBuffers::carry_needed)`(4)` words (a
/// shorter one is a failure).
#[inline(never)]
pub fn check_band_carry_kernel(buf: &mut [u16], carry: &mut [u32], cases: usize) -> usize {
    match carry.get_mut(..2 * 4 * STATE_WORDS) {
        Some(carry) => band_faces_cases::<DspLoop>(buf, carry, cases, 0x9e37_79b9),
        None => usize::MAX,
    }
}

/// The band checks' model of the band loop's carry (`ColorCarry`): two halves of eight
/// colours (ARMv7E-M's [`check_band_faces_kernel`], ARMv6-M's
/// [`check_band_faces_v6m_kernel`](super::check_band_faces_v6m_kernel)).
#[derive(Clone, PartialEq)]
pub(super) struct Carry8 {
    pub(super) read: [u16; 8],
    pub(super) keep: [u16; 8],
    pub(super) filled: usize,
    pub(super) taken: usize,
    pub(super) kept: usize,
}
impl Carry8 {
    /// The next colour the band above kept, if it kept one.
    pub(super) fn take(&mut self) -> Option<u16> {
        let i = self.taken;
        self.taken += 1;
        (i < self.filled)
            .then(|| self.read.get(i).copied())
            .flatten()
    }
    /// The colour taken last, again (a face the fused loop carried itself).
    pub(super) fn last_taken(&self) -> Option<u16> {
        let i = self.taken.checked_sub(1)?;
        (i < self.filled)
            .then(|| self.read.get(i).copied())
            .flatten()
    }
    /// Keep colour `c` for the band below, while there is room.
    pub(super) fn keep(&mut self, c: u16) {
        if let Some(slot) = self.keep.get_mut(self.kept) {
            *slot = c;
            self.kept += 1;
        }
    }
    /// A new band: what this band kept is what the next one takes.
    pub(super) fn start_band(&mut self) {
        core::mem::swap(&mut self.read, &mut self.keep);
        (self.filled, self.taken, self.kept) = (self.kept, 0, 0);
    }
}

/// A small triangle's portable twin: corners, clip, first row, width, depth and colour
/// rows, colour.
pub(super) type SmallTwin = fn(
    [&crate::raster::ScreenVertex; 3],
    &crate::raster::Clip,
    i32,
    usize,
    &mut [u16],
    &mut [u16],
    u16,
) -> super::SmallDone;

/// A band loop as the band checks drive it: the loop over a band's rows and the small
/// triangles' twin its faces must match, with what it takes. Generic (not function
/// pointers): the check's frame is the bench's deepest stack.
pub(super) trait BandLoop {
    /// Whether it takes lit colours written by a function (not only packed 5-6-5).
    const ANY_LIT: bool;
    /// The diffuse weights' range, ±2^(16 + this).
    const DIFFUSE_SHIFT: u32;
    /// Whether a refusal fails a case (where the loop is assembly).
    const NEVER_REFUSES: bool;
    /// The small triangle's portable twin its faces must match.
    const TWIN: SmallTwin;
    /// A band's rows as the loop takes them: depth rows `z` and colour rows `c` (48
    /// pixels a row from screen row `first_row`) drawn inside `clip`, made once a band
    /// (ARMv6-M's set-up block lives in them across the loop's calls, as in a frame).
    type Rows<'a>;
    /// The rows of a band.
    fn rows<'a>(
        z: &'a mut [u16],
        c: &'a mut [u16],
        band: (i32, crate::raster::Clip),
    ) -> Self::Rows<'a>;
    /// Their depth and colour rows, for the faces the twin draws.
    fn parts<'r>(rows: &'r mut Self::Rows<'_>) -> (&'r mut [u16], &'r mut [u16]);
    /// The loop on `rows`: as [`band_faces_less`], a face it leaves named with the
    /// heads already past it.
    fn run(
        heads: &mut [u32; 4],
        tables: (&[u16], &[[u16; 3]], &[CachedVertex]),
        carry: &mut BandCarry<'_, '_, u16>,
        color: &FaceColor<'_, u16>,
        rows: &mut Self::Rows<'_>,
        counts: &mut FacesCounts,
    ) -> BandStop;
}

/// ARMv7E-M's band loop ([`band_faces_less`]; the twin's alone elsewhere).
struct DspLoop;

impl BandLoop for DspLoop {
    const ANY_LIT: bool = true;
    const DIFFUSE_SHIFT: u32 = 3;
    const NEVER_REFUSES: bool = false;
    const TWIN: SmallTwin = super::rows::small_less_portable;
    type Rows<'a> = SmallTarget<'a, 'a, u16>;
    #[inline(always)]
    fn rows<'a>(
        z: &'a mut [u16],
        c: &'a mut [u16],
        (first_row, clip): (i32, crate::raster::Clip),
    ) -> Self::Rows<'a> {
        SmallTarget {
            z,
            c,
            width: 48,
            first_row,
            clip,
        }
    }
    #[inline(always)]
    fn parts<'r>(t: &'r mut Self::Rows<'_>) -> (&'r mut [u16], &'r mut [u16]) {
        (&mut *t.z, &mut *t.c)
    }
    #[inline(always)]
    fn run(
        heads: &mut [u32; 4],
        tables: (&[u16], &[[u16; 3]], &[CachedVertex]),
        carry: &mut BandCarry<'_, '_, u16>,
        color: &FaceColor<'_, u16>,
        t: &mut Self::Rows<'_>,
        counts: &mut FacesCounts,
    ) -> BandStop {
        band_faces_less(heads, tables, carry, color, t, counts)
    }
}

/// The band loop's merge (the checks' model): the least head's face (`None` past the
/// faces or links, the smaller `n` of their lengths), its chain's next in its place.
pub(super) fn merge_next(heads: &mut [u32; 4], links: &[u16], n: usize) -> Option<u32> {
    let least = heads[0];
    let f = (least >> 2) as usize;
    let &link = links.get(f).filter(|_| f < n)?;
    let next = u32::from(link) << 2 | least & 3;
    let mut i = 0;
    while let Some(&h) = heads.get(i + 1).filter(|&&h| next >= h) {
        if let Some(slot) = heads.get_mut(i) {
            *slot = h;
        }
        i += 1;
    }
    if let Some(slot) = heads.get_mut(i) {
        *slot = next;
    }
    Some(least)
}

/// The band checks' clips of one case (`[x0, y0, x1, y1]`, small numbers): the whole
/// band or random ones; two bands of `rows` rows from `first_row` when `two` (the
/// colour rows end `off` sooner). Random clips of two bands meet (the first's reaches
/// its last row, the second's starts at its first) and share their columns on some
/// cases: the second then resumes what the first kept; else it must set those faces up
/// again (a kept walk stays inside the columns it was set up in). The first of two
/// bands stops short of the second by 0 to 2 rows on some cases (its last rows not
/// drawn: the second sets up again what the first kept).
#[inline(never)]
fn band_clips(
    rnd: &mut impl FnMut() -> u32,
    case: usize,
    two: bool,
    first_row: i32,
    rows: usize,
    off: usize,
) -> [[i8; 4]; 2] {
    const W: i32 = 48;
    let (sx0, sx1) = ((rnd() % 6) as i32, W - (rnd() % 6) as i32);
    let shared = two && rnd().is_multiple_of(2);
    let gap = (rnd() % 4).saturating_sub(1) as usize;
    let mut clip_of = |b: usize| {
        let y = first_row + (b * rows) as i32;
        let n = (rows - if b == 0 && two { gap } else { off }) as i32;
        let [x0, y0, x1, y1] = if case.is_multiple_of(3) {
            let (x0, y0) = ((rnd() % 20) as i32, (rnd() % 6) as i32);
            let x1 = x0 + (rnd() % 30) as i32;
            // Two bands: wide columns, the second's the first's or inside them.
            let inset = (2 + rnd() % 6) as i32;
            let (x0, x1) = match (two, b == 0 || shared) {
                (true, true) => (sx0, sx1),
                (true, false) => (sx0 + inset, sx1 - inset),
                (false, _) => (x0, x1),
            };
            let (top, bottom) = (y + y0, (y + y0 + (rnd() % 10) as i32).min(y + n));
            match (two, b) {
                (true, 0) => [x0, top, x1, y + n],
                (true, _) => [x0, y, x1, bottom],
                _ => [x0, top, x1, bottom],
            }
        } else {
            [0, y, W, y + n]
        };
        [x0, y0, x1, y1].map(|v| v as i8)
    };
    [clip_of(0), clip_of(1)]
}

/// The cases of the band checks from `seed` for `kernel`, kept set-ups in `scratch`.
pub(super) fn band_faces_cases<K: BandLoop>(
    buf: &mut [u16],
    scratch: &mut [u32],
    cases: usize,
    seed: u32,
) -> usize {
    use super::light::lit_565_portable;
    use super::rows::SmallDone;
    use crate::raster::{Clip, ScreenVertex};
    const W: usize = 48;
    const H: usize = 16;
    const N: usize = W * H;
    const END: u16 = u16::MAX;
    let Some(buf) = buf.get_mut(..4 * N) else {
        return usize::MAX;
    };
    let (mine, theirs) = buf.split_at_mut(2 * N);
    let (z1, c1) = mine.split_at_mut(N);
    let (z2, c2) = theirs.split_at_mut(N);
    let mut rnd = super::xorshift32(seed);
    let mut bad = 0;
    for case in 0..cases {
        for (d, c) in z1.iter_mut().zip(c1.iter_mut()) {
            (*d, *c) = (rnd() as u16 | 0x8000 >> (case % 3), rnd() as u16);
        }
        z2.copy_from_slice(z1);
        c2.copy_from_slice(c1);
        let off = case / 2 % 2;
        let two = case % 2 == 1;
        let first_row = (rnd() % 5) as i32 - 2;
        // The bands' first rows and rows (the colour rows end `off` sooner).
        let band_rows = if two { 8 } else { H };
        // Each band's clip, as small numbers, out of line (the check's stack is the
        // bench's deepest).
        let clips = band_clips(&mut rnd, case, two, first_row, band_rows, off);
        let clip_at = |b: usize| {
            let [x0, y0, x1, y1] = clips.get(b).copied().unwrap_or_default().map(i32::from);
            Clip { x0, y0, x1, y1 }
        };
        let len = match two {
            true => 4 + rnd() as usize % 9,
            false => rnd() as usize % 13,
        };
        let mut cache = [CachedVertex::EMPTY; 12];
        let span = 64 << (case % 4);
        // Two bands: the corners about their common row, mostly at depths near each
        // other as a mesh's are (random depths leave most triangles to the general
        // path: too steep for the small set-ups).
        let near = two && !rnd().is_multiple_of(4);
        let z0 = rnd() >> 2;
        let (bx, by) = (
            (rnd() % (W as u32 * 16)) as i32 - 40,
            match two {
                true => (first_row + 8) * 16 + (rnd() % 96) as i32 - 48,
                false => (rnd() % (H as u32 * 16)) as i32 - 40 + first_row * 16,
            },
        );
        for (i, e) in cache.iter_mut().enumerate() {
            let far = if case % 11 == 0 && i == 1 { 9000 } else { 0 };
            let x = ((rnd() % span) as i32 + bx - span as i32 / 2 + far) as i16;
            let y = ((rnd() % span) as i32 + by - span as i32 / 2) as i16;
            // Near ones on a half-pixel grid on some cases: edges through pixel centres.
            let grid = if near && case % 8 < 4 { !7 } else { !0 };
            let (x, y) = (x & grid, y & grid);
            let z = match near {
                true => z0 + rnd() % (1 << 16),
                false => rnd() >> 1,
            }
            .min(crate::fixed::MAX_DEPTH);
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
                if rnd().is_multiple_of(64) {
                    *i = (len as u32 + rnd() % 4) as u16; // out of range
                }
            }
        }
        // Two bands: more faces and links, each face in the chains more often.
        let more = |n: u32, r: u32| if two { n / 2 + r % (n - n / 2) } else { r % n };
        let faces = faces.get(..more(17, rnd()) as usize).unwrap_or(&[]);
        // The bins: links increasing (so every chain ends), to END or past the faces.
        let mut links = [0u16; 18];
        for (f, l) in links.iter_mut().enumerate() {
            *l = match rnd() % 8 {
                0 => END,
                1 => 16 + (rnd() % 3) as u16,
                _ => (f as u32 + 1 + rnd() % 3) as u16,
            };
        }
        let links = links.get(..more(19, rnd()) as usize).unwrap_or(&[]);
        // Each band's four chains' first faces; the second band takes the first's kept
        // chain and shares its tall one.
        let mut first = [[0u16; 4]; 2];
        for (c, f) in first.iter_mut().flatten().enumerate() {
            *f = if rnd().is_multiple_of(5) {
                END
            } else {
                (rnd() % 18) as u16
            };
            // Tall faces (chain 3) on some cases only, as a band has few.
            if c % 4 == 3 && case % 4 != 0 {
                *f = END;
            }
        }
        if two {
            first[0][1] = (rnd() % 6) as u16;
        }
        first[1][0] = first[0][1];
        first[1][3] = first[0][3];
        let heads_of = |f: [u16; 4]| {
            let mut h = [0u32; 4];
            for (c, (h, f)) in h.iter_mut().zip(f).enumerate() {
                *h = u32::from(f) << 2 | c as u32;
            }
            h.sort_unstable();
            h
        };
        let normals = [[0i16; 3]; 16].map(|n| n.map(|_| ((rnd() % 32769) as i32 - 16384) as i16));
        let light = [0; 3].map(|_| (rnd() % 65537) as i32 - 32768);
        let ambient = (rnd() % 131_073) as i32 - 65536;
        let diffuse = ((rnd() % 131_073) as i32 - 65536) << K::DIFFUSE_SHIFT;
        let channels = [0; 3].map(|_| rnd() as u8);
        let count = match two && !rnd().is_multiple_of(4) {
            true => faces.len(),
            false => rnd() as usize % (faces.len() + 2),
        };
        let block = LightBlock::new(
            light,
            ambient,
            diffuse,
            channels,
            normals.get(..count).unwrap_or(&normals),
        );
        let turn: fn(u16) -> u16 = |c| c.rotate_left(3);
        let flat = rnd() as u16;
        let same: fn(u16) -> u16 = |c| c;
        let color = match case % 4 {
            3 => FaceColor::Flat(flat),
            2 => FaceColor::Lit(&block, same, Some(Raw565::<u16>::PROOF)),
            _ if !K::ANY_LIT => FaceColor::Lit(&block, same, Some(Raw565::<u16>::PROOF)),
            _ => FaceColor::Lit(&block, turn, None),
        };
        let color_of = |k: usize| match color {
            FaceColor::Flat(c) => c,
            FaceColor::Lit(b, f, _) => lit_565_portable(k, b).map_or(0x1234, f),
        };
        let mut carry = Carry8 {
            read: [0; 8].map(|_| rnd() as u16),
            keep: [0; 8].map(|_| rnd() as u16),
            filled: rnd() as usize % 11,
            taken: rnd() as usize % 3,
            kept: rnd() as usize % 9,
        };
        // Two bands mostly from a band's start, where set-ups are kept from the first.
        if two && !rnd().is_multiple_of(4) {
            (carry.taken, carry.kept) = (0, 0);
        }
        let mut carry2 = carry.clone();
        // Up to four slots of set-ups, none on some cases.
        let slots = rnd() as usize % 6;
        let mut states = KeptStates::new(&mut *scratch, slots);
        // One face as the band loop draws it (`carried`: its carry done by the fused
        // loop) in band `b`; `false` at a corner past the cache (the band loop's
        // error: it stops).
        let face = |head: u32,
                    carried: bool,
                    carry: &mut Carry8,
                    b: usize,
                    z: &mut [u16],
                    c: &mut [u16],
                    counts: &mut FacesCounts| {
            let (f, k) = ((head >> 2) as usize, head & 3);
            let Some(&t) = faces.get(f) else {
                return false;
            };
            let get = |i: u16| cache.get(usize::from(i));
            let (Some(a), Some(e1), Some(e2)) = (get(t[0]), get(t[1]), get(t[2])) else {
                return false;
            };
            let taken = match (k, carried) {
                (0, false) => carry.take(),
                (0, true) => carry.last_taken(),
                _ => None,
            };
            let col = taken.unwrap_or_else(|| color_of(f));
            if k == 1 && !carried {
                carry.keep(col);
            }
            let [p, q, r] = [a, e1, e2].map(|e| {
                let (x, y) = e.xy();
                ScreenVertex::from_raw(x, y, e.z)
            });
            let (clip, row) = (clip_at(b), first_row + (b * band_rows) as i32);
            let done = (K::TWIN)([&p, &q, &r], &clip, row, W, z, c, col);
            // The pixels only: the band loop counts no faces (the bands take theirs
            // from the binning).
            if let SmallDone::Drawn(tested, failed) = done {
                counts.tested += u64::from(tested);
                counts.failed += u64::from(failed);
            }
            true
        };
        // The band loop's merge: the least head's face, its chain's next in its place.
        let n = links.len().min(faces.len());
        let next = |heads: &mut [u32; 4]| merge_next(heads, links, n);
        let (mut mine, mut theirs) = (FacesCounts::default(), FacesCounts::default());
        let (mut stopped, mut stopped2) = (false, false);
        let (mut same_heads, mut refused) = (true, false);
        for (b, &first) in first.iter().enumerate().take(1 + usize::from(two)) {
            let at = b * band_rows * W;
            let (Some(za), Some(ca)) = (z1.get_mut(at..), c1.get_mut(off + at..)) else {
                return usize::MAX;
            };
            let (Some(zb), Some(cb)) = (z2.get_mut(at..), c2.get_mut(off + at..)) else {
                return usize::MAX;
            };
            let row = first_row + (b * band_rows) as i32;
            // The fused loop, the faces it leaves drawn by the twin.
            let mut heads1 = heads_of(first);
            let mut t = K::rows(za, ca, (row, clip_at(b)));
            while !stopped {
                let Carry8 {
                    read,
                    keep,
                    filled,
                    taken,
                    kept,
                } = &mut carry;
                let mut parts = BandCarry {
                    read: &read[..],
                    keep: &mut keep[..],
                    filled: *filled,
                    taken,
                    kept,
                    states: &mut states,
                };
                let tables = (links, faces, cache);
                let stop = K::run(&mut heads1, tables, &mut parts, &color, &mut t, &mut mine);
                let (head, carried) = match stop {
                    BandStop::Done => break,
                    BandStop::Whole(h) => (h, false),
                    BandStop::Fill(h) => (h, true),
                    BandStop::Refused => {
                        // Only where there is no assembly: the twin's face by face.
                        refused = true;
                        match next(&mut heads1) {
                            Some(h) => (h, false),
                            None => break,
                        }
                    }
                };
                let (z, c) = K::parts(&mut t);
                if !face(head, carried, &mut carry, b, z, c, &mut mine) {
                    stopped = true;
                }
            }
            // The twin.
            let mut heads2 = heads_of(first);
            while !stopped2 {
                let Some(head) = next(&mut heads2) else {
                    break;
                };
                stopped2 = !face(head, false, &mut carry2, b, zb, cb, &mut theirs);
            }
            same_heads &= heads1 == heads2;
            carry.start_band();
            carry2.start_band();
            states.start_band();
        }
        // After a stop (an error: the frame is not drawn on) the carry is not compared.
        let same_carry = stopped || carry == carry2;
        let same_draw = mine == theirs && z1 == z2 && c1 == c2 && same_heads;
        if !same_draw || stopped != stopped2 || !same_carry || (K::NEVER_REFUSES && refused) {
            bad += 1;
        }
    }
    bad
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faces_kernel_matches_its_twin() {
        let mut buf = [0u16; 4 * 48 * 16];
        assert_eq!(check_faces_kernel(&mut buf, 2_000), 0);
        assert_eq!(check_faces_kernel(&mut buf[..100], 1), usize::MAX);
    }

    #[test]
    fn band_faces_kernel_matches_its_twin() {
        let mut buf = [0u16; 4 * 48 * 16];
        assert_eq!(check_band_faces_kernel(&mut buf, 4_000), 0);
        assert_eq!(check_band_faces_kernel(&mut buf[..100], 1), usize::MAX);
        let mut carry = [0u32; 2 * 4 * STATE_WORDS];
        assert_eq!(check_band_carry_kernel(&mut buf, &mut carry, 4_000), 0);
        assert_eq!(
            check_band_carry_kernel(&mut buf, &mut carry[1..], 1),
            usize::MAX
        );
    }

    /// `Raw565`'s promise: the colour of every packed value is two bytes holding it.
    #[test]
    fn raw_565_is_the_packed_value() {
        use crate::shade::DisplayColor;
        use embedded_graphics::pixelcolor::Rgb888;
        fn holds<C: DisplayColor + Copy>() {
            let (_, f, raw) = C::packed_565(Rgb888::new(1, 2, 3)).unwrap();
            assert!(raw.is_some());
            for c in 0..=u16::MAX {
                let v = f(c);
                // SAFETY: `C` is two bytes (the const assert above).
                assert_eq!(unsafe { core::mem::transmute_copy::<C, u16>(&v) }, c);
            }
        }
        holds::<Rgb565>();
        holds::<Bgr565>();
    }
}
