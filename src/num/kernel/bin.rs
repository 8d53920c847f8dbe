//! Binning in the cull scan: the scan's assembly loop (ARMv7E-M, ARMv6-M) extended so
//! that each drawn face of a cached mesh is appended to its band's bin chain without
//! leaving the loop, beside its portable twin.
#![allow(unsafe_code)]

use super::cull::{culled_run_portable, CullScan};

/// Whether [`bin_scan`] is the assembly loop (ARMv7E-M; ARMv6-M for bands of a power of
/// two rows, [`BinChains::scans`]); elsewhere the band binning keeps its own loop over
/// the walk and does not call it.
pub(crate) const BIN_KERNEL: bool = cfg!(all(zraster_thumb, any(zraster_dsp, zraster_armv6m)));

/// The bin chains of a banded frame as the binning appends to them: for each chain its
/// tail (the slot of its last face), and the slots, one a face (its link) and one a
/// chain (its head), so that a chain's tail starts at its head's slot. Chain `2b` holds
/// the faces whose rows start in band `b` and reach band `b + 1`, chain `2b + 1` those
/// that stay in band `b`, the last chain the taller ones.
pub(crate) struct BinChains<'b> {
    tails: &'b mut [u16],
    slots: &'b mut [u16],
    /// The constants the assembly reads, and the drawn faces it counts.
    consts: BinConsts,
    /// No cache entry is unplaced (the renderer's `placed`): the assembly scans may then
    /// skip the corners' test where back faces are dropped (elsewhere not kept).
    #[cfg(all(zraster_thumb, any(zraster_dsp, zraster_armv6m)))]
    placed: bool,
}

/// What the assembly reads of [`BinChains`] through one register (offsets in the
/// comments). A chain `c` is found as `c − 1` (`2·tb − (bb − tb)` for a face whose rows
/// lie in bands `tb..=bb`, one or two of them), so the tails are addressed from the
/// second.
#[repr(C)]
struct BinConsts {
    last_row: i32,    // 0: the screen's last row
    rows: u32,        // 4: rows a band (≥ 1)
    drawn: u32,       // 8: drawn faces found
    tall_less1: u32,  // 12: the chain of faces reaching more than two bands, less 1
    tails1: *mut u16, // 16, 20: the second tail and the slots, set from the slices
    slots: *mut u16,  //   before each run of the assembly
    shift: u32,       // 24: log2(rows) (ARMv6-M: rows a power of two)
    /// ARMv7E-M's scan: the faces' number (kept there by the assembly), and not 0
    /// where `placed` is claimed (see `bin_scan_dsp`).
    #[cfg(all(zraster_thumb, zraster_dsp))]
    faces_len: u32, // 28
    #[cfg(all(zraster_thumb, zraster_dsp))]
    placed: u32, // 32
    /// The ARMv6-M scan's copy, filled before each run (kept here rather than on the
    /// stack: LLVM then fully unrolls the chains' loops around it, +0.7 KB of hot code).
    #[cfg(all(zraster_thumb, zraster_armv6m))]
    v6m: V6mConsts,
}

const _: () = {
    use core::mem::offset_of;
    assert!(offset_of!(BinConsts, last_row) == 0 && offset_of!(BinConsts, rows) == 4);
    assert!(offset_of!(BinConsts, drawn) == 8 && offset_of!(BinConsts, tall_less1) == 12);
    // The pointers as the assembly (32-bit) reads them by one LDRD.
    assert!(offset_of!(BinConsts, tails1) == 16);
    assert!(core::mem::size_of::<usize>() != 4 || offset_of!(BinConsts, slots) == 20);
    #[cfg(all(zraster_thumb, zraster_dsp))]
    assert!(offset_of!(BinConsts, faces_len) == 28 && offset_of!(BinConsts, placed) == 32);
};

/// What the ARMv6-M scan ([`bin_scan`]) reads through one register, in the order its
/// LDMs take them: a drawn face's last row and shift by one, the tails, slots and first
/// face by another (offsets in the comments).
#[cfg(all(zraster_thumb, zraster_armv6m))]
#[repr(C)]
struct V6mConsts {
    last_row: i32,          // 0: the screen's last row
    shift: u32,             // 4: log2(rows), rows a power of two
    tails1: *mut u16,       // 8: the second tail
    slots: *mut u16,        // 12
    faces: *const [u16; 3], // 16: the first face
    third: u32,             // 20: 1/3 modulo 2³² (a place from a face's offset)
    tall_less1: u32,        // 24: the tall faces' chain, less 1
    span: u32,              // 28: the scan's range of dropped areas
    drawn: u32,             // 32: drawn faces found
    placed: u32,            // 36: not 0: `placed` claimed (see `bin_scan_v6m`)
}

#[cfg(all(zraster_thumb, zraster_armv6m))]
const _: () = {
    use core::mem::offset_of;
    type V = V6mConsts;
    assert!(offset_of!(V, last_row) == 0 && offset_of!(V, shift) == 4);
    assert!(offset_of!(V, tails1) == 8 && offset_of!(V, slots) == 12);
    assert!(offset_of!(V, faces) == 16 && offset_of!(V, third) == 20);
    assert!(offset_of!(V, tall_less1) == 24 && offset_of!(V, span) == 28);
    assert!(offset_of!(V, drawn) == 32 && offset_of!(V, placed) == 36);
};

impl<'b> BinChains<'b> {
    /// Chains `tails` (one a chain) over `slots` for a screen of `height` rows drawn
    /// `rows` at a time: `None` unless there is a chain for every band's two and the
    /// tall faces.
    pub(crate) fn new(
        tails: &'b mut [u16],
        slots: &'b mut [u16],
        height: u32,
        rows: u32,
    ) -> Option<Self> {
        let bands = height.checked_div(rows).map(|_| height.div_ceil(rows))?;
        let chains = usize::try_from(bands)
            .ok()?
            .checked_mul(2)?
            .checked_add(1)?;
        let last_row = i32::try_from(height).ok()?.checked_sub(1)?;
        (height > 0 && chains == tails.len()).then(|| BinChains {
            consts: BinConsts {
                last_row,
                rows,
                drawn: 0,
                tall_less1: (chains - 2) as u32,
                tails1: core::ptr::null_mut(),
                slots: core::ptr::null_mut(),
                shift: rows.trailing_zeros(),
                #[cfg(all(zraster_thumb, zraster_dsp))]
                faces_len: 0,
                #[cfg(all(zraster_thumb, zraster_dsp))]
                placed: 0,
                #[cfg(all(zraster_thumb, zraster_armv6m))]
                v6m: V6mConsts {
                    last_row,
                    shift: 0,
                    tails1: core::ptr::null_mut(),
                    slots: core::ptr::null_mut(),
                    faces: core::ptr::null(),
                    third: 0,
                    tall_less1: 0,
                    span: 0,
                    drawn: 0,
                    placed: 0,
                },
            },
            tails,
            slots,
            #[cfg(all(zraster_thumb, any(zraster_dsp, zraster_armv6m)))]
            placed: false,
        })
    }

    /// Append face `f` (its corners' y `ys`, 1/16 pixel) to the chain of the rows whose
    /// pixel centres it may cover, if any ([`chain_of`]).
    #[inline(always)]
    pub(crate) fn bin(&mut self, f: usize, ys: [i32; 3]) {
        let rows = self.consts.rows as i32; // at most `height`, an i32
        let (last, tall) = (self.consts.last_row, self.consts.tall_less1 as usize + 1);
        // ARMv6-M divides by a library call: a shift there when `rows` is a power of two.
        let (shift, pow2) = (
            self.consts.shift,
            crate::num::ARMV6M && rows.count_ones() == 1,
        );
        let band_of = |row: i32| if pow2 { row >> shift } else { row / rows };
        if let Some(c) = chain_of(ys, last, tall, band_of) {
            self.append(c, f);
        }
    }

    /// Whether [`bin_scan`] is worth calling: on ARMv6-M only for a power of two rows
    /// a band (else the walk's scan and [`BinChains::bin`] serve).
    #[inline(always)]
    pub(crate) fn scans(&self) -> bool {
        !crate::num::ARMV6M || self.consts.rows.is_power_of_two()
    }

    /// Claim that no entry of the scans' cache is unplaced (`placed`, the renderer's:
    /// a wrong claim bins the wrong faces but writes nothing outside the chains).
    #[inline(always)]
    pub(crate) fn set_placed(&mut self, placed: bool) {
        #[cfg(all(zraster_thumb, any(zraster_dsp, zraster_armv6m)))]
        {
            self.placed = placed;
        }
        let _ = placed;
    }

    /// Append face `f` to chain `c`.
    #[inline(always)]
    pub(crate) fn append(&mut self, c: usize, f: usize) {
        append(self.tails, self.slots, c, f);
    }

    /// End every chain with `end`: after its last face, or at its head when empty.
    pub(crate) fn end_chains(&mut self, end: u16) {
        end_chains(self.tails, self.slots, end);
    }

    /// The drawn faces [`bin_scan`] has binned.
    pub(crate) fn drawn(&self) -> u32 {
        self.consts.drawn
    }
}

/// The chain of a face whose corners' y are `ys` (1/16 pixel) on a screen whose last row
/// is `last_row`, for bands `band_of` a row: the chain of the band holding its first
/// row (`2b + 1` when it stays in band `b`, `2b` when it reaches band `b + 1`), or
/// `tall` when it reaches further; `None` when it covers no row's pixel centre on the
/// screen. Its rows below the screen count too (the last row is not a bound on them:
/// one compare less): such a face may be kept for a band that never comes, or be tall.
#[inline(always)]
fn chain_of(
    ys: [i32; 3],
    last_row: i32,
    tall: usize,
    band_of: impl Fn(i32) -> i32,
) -> Option<usize> {
    // The rows whose pixel centres the face may cover: top..=bottom. (Rounding each y
    // before the minimum and maximum keeps them 32-bit: of 16-bit values LLVM takes
    // them in 16 bits and extends them again.)
    let (ya, yb, yc) = (ys[0] + 7, ys[1] + 7, ys[2] + 7);
    let top = (ya.min(yb).min(yc) >> 4).max(0);
    let bottom = (ya.max(yb).max(yc) >> 4) - 1;
    if top > last_row || top > bottom {
        return None;
    }
    let (tb, bb) = (band_of(top), band_of(bottom));
    Some(match bb - tb {
        0 => 2 * tb as usize + 1,
        1 => 2 * tb as usize,
        _ => tall,
    })
}

/// Append face `f` to chain `c` of the chains whose tails are `tails` (see
/// [`BinChains`]).
#[inline(always)]
fn append(tails: &mut [u16], slots: &mut [u16], c: usize, f: usize) {
    if let Some(tail) = tails.get_mut(c) {
        if let Some(slot) = slots.get_mut(usize::from(*tail)) {
            *slot = f as u16;
        }
        *tail = f as u16;
    }
}

/// End every chain of `tails` with `end`: after its last face, or at its head when
/// empty.
#[inline(always)]
fn end_chains(tails: &[u16], slots: &mut [u16], end: u16) {
    for c in 0..tails.len() {
        if let Some(slot) = tails.get(c).and_then(|&t| slots.get_mut(usize::from(t))) {
            *slot = end;
        }
    }
}

/// Advance `pos` past the faces of `scan` from `pos` on that are dropped or drawn,
/// appending each drawn one to its chain in `chains` ([`BinChains::bin`]) and counting
/// it there: it stops at the end or at a face with a bad index or an unplaced corner
/// (which the caller decides on). On ARMv6-M, where its kernel does not apply (not
/// [`BinChains::scans`]), it leaves `pos` as it is. Dropped and drawn are as [`skip_culled`](super::skip_culled)
/// has them.
///
/// On ARMv7E-M the cull scan's assembly loop, with a drawn face binned without leaving
/// the loop: 23 instructions a dropped face, 18 where `placed` is claimed and back
/// faces are dropped (ARMv6-M likewise: 42, 31).
#[inline(always)]
pub(crate) fn bin_scan<T>(pos: &mut usize, scan: &CullScan<'_, T>, chains: &mut BinChains<'_>) {
    // The assembly writes the slot a tail names and makes a face's place a tail: only
    // when every tail and every face names a slot (else the twin, which checks each).
    let slots = chains.slots.len();
    let fits = scan.faces().len() <= slots && chains.tails.iter().all(|&t| usize::from(t) < slots);
    #[cfg(all(zraster_thumb, zraster_dsp))]
    if fits {
        return bin_scan_dsp(pos, scan, chains);
    }
    // ARMv6-M leaves every face to the caller where its kernel does not apply (so the
    // twin, a Rust scan, is not built into the draw path there).
    #[cfg(all(zraster_thumb, zraster_armv6m))]
    {
        if fits && chains.scans() {
            bin_scan_v6m(pos, scan, chains);
        }
        return;
    }
    #[allow(unreachable_code)]
    let _ = fits;
    bin_scan_portable(pos, scan, chains)
}

/// The portable twin of [`bin_scan`].
pub(crate) fn bin_scan_portable<T>(
    pos: &mut usize,
    scan: &CullScan<'_, T>,
    chains: &mut BinChains<'_>,
) {
    let faces = scan.faces();
    loop {
        let (n, drawn) = culled_run_portable(faces.get(*pos..).unwrap_or(&[]), scan);
        if *pos < faces.len() {
            *pos += n;
        }
        let corners = faces.get(*pos).and_then(|t| scan.corners(t));
        let (true, Some(c)) = (drawn, corners) else {
            return;
        };
        chains.consts.drawn += 1;
        chains.bin(*pos, c.map(|(_, y)| y));
        *pos += 1;
    }
}

/// One loop of the ARMv7E-M binning scan (`bin_scan_dsp`), headed by label `$head`:
/// the face at r0 (moved on to the next; its indices below r3, else to `3f`; its cache
/// words from r2 into r8, r9, r10), the corners' tests `$placed` (each may go to `3f`),
/// the cull test of the area against the range r4, r5 (a drawn face to `4f`), while r1
/// counts faces down.
#[cfg(all(zraster_thumb, zraster_dsp))]
macro_rules! bin_dsp_loop {
    ($head:literal $(, $placed:literal)*) => {
        concat!(
            $head, ":\n",
            "ldrh r8, [r0], #6\nldrh r9, [r0, #-4]\nldrh r10, [r0, #-2]\n",
            "cmp r8, r3\nitt lo\ncmplo r9, r3\ncmplo r10, r3\nbhs 3f\n",
            "ldr r8, [r2, r8, lsl #3]\nldr r9, [r2, r9, lsl #3]\nldr r10, [r2, r10, lsl #3]\n",
            $($placed,)*
            "ssub16 r9, r9, r8\nssub16 r10, r10, r8\nsmlsdx r11, r9, r10, r4\n",
            "cmp r11, r5\nbhi 4f\n",
            "subs r1, #1\nbne ", $head, "b\n",
        )
    };
}

/// [`bin_scan`] on ARMv7E-M.
#[cfg(all(zraster_thumb, zraster_dsp))]
#[inline(always)]
fn bin_scan_dsp<T>(pos: &mut usize, scan: &CullScan<'_, T>, chains: &mut BinChains<'_>) {
    let r = scan.regs();
    chains.consts.tails1 = chains.tails.as_mut_ptr().wrapping_add(1);
    chains.consts.slots = chains.slots.as_mut_ptr();
    chains.consts.placed = u32::from(chains.placed);
    let consts: *mut BinConsts = &mut chains.consts;
    // SAFETY: the scan is `skip_culled`'s loop (see its SAFETY comment: it reads only
    // faces from `pos` on, inside the faces, and only cache words of indices it found
    // below `regs.len`, inside the cache; r1 ends as the place of the face it stops at).
    // What it adds, for a drawn face: it reads the `BinConsts` through r6 (an exclusive
    // borrow of `chains`, whose slices it describes), works out the face's chain as
    // `BinChains::bin` does from the corners' y (the high halves of the words it read,
    // and of their differences: below 2¹⁵ in magnitude), and writes two halfwords: the
    // slot its chain's tail names and that tail. `bin_scan` checked that every tail
    // names a slot (an index below `slots.len()`) and that there is a slot for each
    // face; a tail only ever becomes a face's place (below the faces' number, r1 counts
    // them), and the chain is below `tails.len()` (`BinChains::new`: 2 · bands + 1 of
    // them): for 0 ≤ top ≤ last_row = height − 1 and top ≤ bottom (below 2¹¹), the
    // bands tb = ⌊top/rows⌋ < bands and bb = ⌊bottom/rows⌋ ≥ tb (rows ≥ 1, so UDIV
    // never divides by 0), a face of one or two bands (bb − tb ≤ 1) has chain
    // 2·tb + 1 or 2·tb, below 2 · bands, and `tall` is the last; the tails are
    // addressed from the second (`tails1`, `tails` has at least three), as chain − 1
    // (2·tb − (bb − tb)).
    // Two loops share the drawn faces' part: `checked` and, for `placed` claimed, lo 0
    // and span 2³¹ − 1, `back` without the corners' test (a wrong claim changes which
    // faces are binned, not what is read or written: y is any i16 all the same, which
    // the bounds above take). The drawn part goes back to its loop's head by lr, set
    // once by a BL from just before that head; the faces' number (lr's operand) waits
    // in the `BinConsts` meanwhile.
    // r6 and r7 (not allowed as operands) are pushed and popped with r8–r11 (r7 counts
    // the drawn faces, stored back at the end); the flags are scratch (USAT may set
    // the sticky Q flag, which nothing in the crate reads).
    unsafe {
        core::arch::asm!(
            "push {{r6-r11}}",
            "mov r6, {consts}",
            "ldr r7, [r6, #8]", // the drawn faces so far
            "add r0, r0, r1, lsl #1",
            "add r0, r0, r1, lsl #2", // the face at `pos`
            "str lr, [r6, #28]",      // the faces' number, for the places
            "subs r1, lr, r1",        // the faces left
            "bls 3f",                 // none (`pos` at or past the end)
            // `back` for `placed` claimed, lo 0 and span 2³¹ − 1 (+ 1 overflows).
            "ldr r8, [r6, #32]",
            "cmp r8, #0",
            "beq 1f",
            "cmp r4, #0",
            "bne 1f",
            "adds r8, r5, #1",
            "bvs 11f",
            "1:",
            "bl 10f", // the loop's head (the return address) into lr, and on there
            // `checked`: the corners' test.
            bin_dsp_loop!(
                "2",
                "cmp r12, r8, lsl #16\nitt le\ncmple r12, r9, lsl #16\n",
                "cmple r12, r10, lsl #16\nbgt 3f\n"
            ),
            "b 3f",
            // `back`: no corners' test.
            "11:",
            "bl 10f",
            bin_dsp_loop!("20"),
            "3:", // a bad index or an unplaced corner, or none left
            "ldr lr, [r6, #28]",
            "sub r1, lr, r1", // the face it stopped at (`pos` if none was left)
            "str r7, [r6, #8]",
            "pop {{r6-r11}}",
            "b 9f",
            // Drawn: its rows top..=bottom from the corners' y (y0 and the differences,
            // the high halves of r8, r9, r10: SSUB16 sets GE[3:2] where dy1 ≥ dy2, and
            // SEL takes the high halves by them; the shifts take them out).
            "4:",
            "asr r11, r8, #16",
            "add r11, r11, #7",
            "ssub16 r8, r9, r10",
            "sel r8, r10, r9", // min(dy1, dy2) in the high half
            "sel r9, r9, r10", // max(dy1, dy2)
            "and r8, r8, r8, asr #31", // min(dy1, dy2, 0)
            "bic r9, r9, r9, asr #31", // max(dy1, dy2, 0)
            "add r8, r11, r8, asr #16",
            "add r9, r11, r9, asr #16",
            "usat r8, #16, r8, asr #4", // top, at least 0 (and below 2¹¹)
            "asr r9, r9, #4",
            "sub r9, r9, #1", // bottom
            "ldrd r10, r11, [r6]", // last_row, rows
            "adds r7, #1", // one more drawn
            "cmp r8, r10",
            "it le",
            "cmple r8, r9",
            "bgt 5f", // no row: below the screen, or none covered
            "udiv r8, r8, r11",
            "udiv r9, r9, r11",
            "sub r10, r9, r8", // d = bb − tb
            "cmp r10, #1",
            "bhi 8f",
            "rsb r8, r10, r8, lsl #1", // one or two bands: chain 2·tb − d + 1
            "7:", // append the face (its place) to chain r8 + 1
            "ldrd r10, r11, [r6, #16]",
            "add r10, r10, r8, lsl #1",
            "ldrh r9, [r10]",
            "ldr r8, [r6, #28]",
            "sub r8, r8, r1", // the face's place: the faces less those left
            "strh r8, [r11, r9, lsl #1]",
            "strh r8, [r10]",
            "5:",
            "subs r1, #1",
            "beq 3b",
            "bx lr", // the loop's head
            "8:",
            "ldr r8, [r6, #12]", // more: the tall chain
            "b 7b",
            "10:",
            "bx lr",
            "9:",
            consts = in(reg) consts,
            inout("r0") r.faces => _,
            inout("r1") *pos,
            inout("r2") r.xy => _,
            in("r3") r.len,
            in("r4") r.neg_lo,
            in("r5") r.span,
            in("r12") r.mark,
            inout("lr") r.faces_len => _,
        );
    }
}

/// [`bin_scan`] on ARMv6-M, for a power of two rows a band. Two scan loops share the
/// drawn faces' part, picked once a call: `checked` (the corners' test, any dropped
/// range) and `back`, for a cache [`BinChains::set_placed`] claims has no unplaced
/// entry and back faces dropped (lo 0, span 2³¹ − 1): no corners' test, the area's
/// sign alone (11 instructions a face fewer).
/// One loop of the ARMv6-M binning scan (`bin_scan_v6m`), headed by label `$head`:
/// the face at r0 (its indices below r8, else to `3f`; its cache words from r1 into r2,
/// r3, r4), the corners' tests `$placed` (each may go to `3f`), the area (xb − xa)(yc −
/// ya) − (xc − xa)(yb − ya) into r5 (ya in r2, yb − ya in r3, yc − ya in r4: the drawn
/// face's rows), the cull test `$cull` (a drawn face to `4f`), the next face until r7.
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! bin_v6m_loop {
    ($head:literal $(, $placed:literal)*; $cull:literal) => {
        concat!(
            $head, ":\n",
            "ldrh r2, [r0, #0]\nldrh r3, [r0, #2]\nldrh r4, [r0, #4]\n",
            "cmp r2, r8\nbhs 3f\ncmp r3, r8\nbhs 3f\ncmp r4, r8\nbhs 3f\n",
            "lsls r2, r2, #3\nlsls r3, r3, #3\nlsls r4, r4, #3\n",
            "ldr r2, [r1, r2]\nldr r3, [r1, r3]\nldr r4, [r1, r4]\n",
            $($placed,)*
            "subs r5, r3, r2\nsxth r5, r5\nsubs r6, r4, r2\nsxth r6, r6\n",
            "asrs r2, r2, #16\nasrs r3, r3, #16\nsubs r3, r3, r2\n",
            "asrs r4, r4, #16\nsubs r4, r4, r2\n",
            "muls r5, r4, r5\nmuls r6, r3, r6\nsubs r5, r5, r6\n",
            $cull,
            "adds r0, #6\ncmp r0, r7\nbne ", $head, "b\n",
        )
    };
}

#[cfg(all(zraster_thumb, zraster_armv6m))]
#[inline(always)]
fn bin_scan_v6m<T>(pos: &mut usize, scan: &CullScan<'_, T>, chains: &mut BinChains<'_>) {
    let r = scan.regs();
    if *pos >= r.faces_len {
        return;
    }
    let c = &mut chains.consts;
    c.v6m = V6mConsts {
        last_row: c.last_row,
        shift: c.shift,
        tails1: chains.tails.as_mut_ptr().wrapping_add(1),
        slots: chains.slots.as_mut_ptr(),
        faces: r.faces,
        third: 0xAAAA_AAAB,
        tall_less1: c.tall_less1,
        span: r.span,
        drawn: c.drawn,
        placed: u32::from(chains.placed),
    };
    let consts: *mut V6mConsts = &mut c.v6m;
    let at: *const [u16; 3];
    // SAFETY: each loop is `skip_culled_v6m`'s (see its SAFETY comment: `pos` is below
    // the number of faces, tested above; it reads one face a turn up to `end`, and
    // only cache words of indices it found below `regs.len`; r0 ends at the face it
    // stops at). The `back` loop leaves out the corners' test and tests the area's sign
    // (the checked test for lo 0, span 2³¹ − 1): a wrong `placed` claim changes which
    // faces are binned, not what is read or written (a corner's y is any i16 all the
    // same, which the chain's bounds below take). What it adds, for a drawn face: it
    // reads the `V6mConsts` through their address, pushed at [sp, #4] (a copy of
    // `chains`' constants and the pointers of its slices, which `chains` borrows
    // exclusively; `bin_scan` calls it only for a power of two rows, whose log2 is
    // `shift`; the LDMs read it in order), works out the face's chain as
    // `BinChains::bin` does from the corners' y (y0 and the differences the area took,
    // below 2¹⁷ in magnitude) and writes two halfwords: the slot its chain's tail names
    // and that tail. As in `bin_scan_dsp`: `bin_scan` checked that every tail names a
    // slot and that there is a slot for each face; a tail only ever becomes a face's
    // place ((r0 − faces) / 6, below the faces' number: the offset halved times 1/3
    // modulo 2³², exact for a multiple of 3); for 0 ≤ top ≤ last_row and top ≤ bottom
    // the bands tb = top >> shift ≤ bb = bottom >> shift, tb below the bands' number,
    // so chain 2·tb − (bb − tb) + 1 for bb − tb ≤ 1, and the tall one, are below
    // `tails.len()`, addressed from the second tail as chain − 1. The drawn part goes
    // back to its loop's head through r9, set once (by a BL from just before it) to
    // one of the two heads.
    // r6–r11 are pushed first and popped last (r6 and r7 cannot be operands; r8 holds
    // the entries' number, r9 the loop's head, r10 the drawn faces, stored back at the
    // end, r11 one); r12 and lr (−lo and span, for `checked`) are declared clobbered,
    // the flags are scratch.
    unsafe {
        core::arch::asm!(
            "push {{r6, r7}}",
            "mov r6, r8",
            "mov r7, r9",
            "push {{r6, r7}}",
            "mov r6, r10",
            "mov r7, r11",
            "push {{r6, r7}}",
            "push {{r4, r5}}", // the constants at [sp, #4]
            "mov r8, r2",      // the entries' number
            "mov r7, r3",      // the faces' end
            "mov r12, r4",     // −lo
            "ldr r6, [r5, #32]",
            "mov r10, r6", // the drawn faces so far
            "movs r6, #1",
            "mov r11, r6",
            // `back` for `placed` claimed, lo 0 and span 2³¹ − 1 (+ 1 overflows).
            "ldr r6, [r5, #36]",
            "cmp r6, #0",
            "beq 1f",
            "cmp r4, #0",
            "bne 1f",
            "ldr r6, [r5, #28]",
            "adds r6, #1",
            "bvs 11f",
            "1:",
            "bl 10f", // the loop's head (the return address) into r9, and on there
            bin_v6m_loop!(
                "2",
                // `checked`: the corners' test, the range of dropped areas.
                "lsls r5, r2, #16\nadds r5, r5, r5\nbvs 3f\n",
                "lsls r5, r3, #16\nadds r5, r5, r5\nbvs 3f\n",
                "lsls r5, r4, #16\nadds r5, r5, r5\nbvs 3f\n";
                "add r5, r12\ncmp r5, lr\nbhi 4f\n"
            ),
            "b 3f",
            // `back`: no corners' test, back faces (area ≥ 0) dropped.
            "11:",
            "bl 10f",
            bin_v6m_loop!("20"; "bmi 4f\n"),
            "3:", // a bad index or an unplaced corner, or none left
            "ldr r6, [sp, #4]",
            "mov r5, r10",
            "str r5, [r6, #32]",
            "add sp, #8",
            "pop {{r6, r7}}",
            "mov r10, r6",
            "mov r11, r7",
            "pop {{r6, r7}}",
            "mov r8, r6",
            "mov r9, r7",
            "pop {{r6, r7}}",
            "b 9f",
            // Drawn: its rows top..=bottom from ya (r2) and the differences (r3, r4).
            "4:",
            "cmp r3, r4",
            "bge 6f",
            "mov r5, r3",
            "mov r3, r4",
            "b 7f",
            "6:",
            "mov r5, r4",
            "7:", // r5 the least difference, r3 the greatest
            "asrs r4, r5, #31",
            "ands r5, r4", // min(dy1, dy2, 0)
            "asrs r4, r3, #31",
            "bics r3, r4", // max(dy1, dy2, 0)
            "adds r2, #7",
            "adds r5, r5, r2",
            "asrs r5, r5, #4",
            "asrs r4, r5, #31",
            "bics r5, r4", // top, at least 0
            "adds r3, r3, r2",
            "asrs r3, r3, #4",
            "subs r3, #1",
            "ldr r6, [sp, #4]",
            "ldm r6!, {{r2, r4}}", // last_row, log2(rows); r6 at the tails
            "add r10, r11",        // one more drawn
            "cmp r5, r2",
            "bgt 8f", // below the screen
            "cmp r5, r3",
            "bgt 8f", // no row
            "lsrs r5, r4",
            "lsrs r3, r4",
            "subs r3, r3, r5", // d = bb − tb
            "cmp r3, #1",
            "bhi 12f",
            "lsls r5, r5, #1",
            "subs r5, r5, r3",         // one or two bands: chain 2·tb − d + 1
            "13:",                     // append the face (its place) to chain r5 + 1
            "ldm r6!, {{r2, r3, r4}}", // the second tail, the slots, the first face
            "subs r4, r0, r4",
            "lsrs r4, r4, #1",
            "ldr r6, [r6]",     // 1/3
            "muls r4, r6, r4",  // the face's place
            "lsls r5, r5, #1",
            "ldrh r6, [r2, r5]", // the chain's tail
            "strh r4, [r2, r5]",
            "lsls r6, r6, #1",
            "strh r4, [r3, r6]",
            "8:",
            "adds r0, #6",
            "cmp r0, r7",
            "beq 3b",
            "mov pc, r9", // the loop's head
            "12:",
            "ldr r5, [r6, #16]", // more: the tall chain (r6 at the tails)
            "b 13b",
            // The set-up's end: the head the BL left in lr into r9 (bit 0, the Thumb
            // bit, set: a MOV to the PC ignores it), then lr the span, and to the head.
            "10:",
            "mov r9, lr",
            "ldr r6, [r5, #28]",
            "mov lr, r6",
            "mov pc, r9",
            "9:",
            inout("r0") r.faces.wrapping_add(*pos) => at,
            inout("r1") r.xy => _,
            inout("r2") r.len => _,
            inout("r3") r.end => _,
            inout("r4") r.neg_lo => _,
            inout("r5") consts => _,
            out("r12") _,
            out("lr") _,
        );
    }
    chains.consts.drawn = chains.consts.v6m.drawn;
    // The place: the bytes from the first face over 6 (as in `skip_culled_v6m`).
    let bytes = at as usize - r.faces as usize;
    *pos = (bytes >> 1).wrapping_mul(0xAAAA_AAAB);
}

/// On-target check of the assembly binning scan (`bin_scan`) against its twin, for
/// the bench firmware: `cases` random runs as `check_cull_kernel` makes them (faces with
/// unplaced corners, bad indices, degenerate and extreme triangles, every cull mode),
/// binned for random screen heights (up to 128 rows, some faces above or below it) and
/// band heights (half of them a power of two; on ARMv6-M the others must leave
/// everything as it was), the chains in `scratch` (two sets of up to 2 · 257 + 12
/// entries: every case counts as differing when it holds fewer than 1,052). Half the
/// cases claim `placed` (`BinChains::set_placed`): for a cache with no unplaced entry
/// on most, and on some for one that may have them (never the renderer's state: the
/// faces binned may then be wrong, so such a case checks only that nothing outside the
/// chains is written and that the place stays among the faces). Returns the number of
/// runs where the two stop at different faces, count different drawn faces, or leave
/// different chains.
#[inline(never)] // its arrays stay out of the caller's frame (the bench's stack figure)
pub fn check_bin_kernel(scratch: &mut [u16], cases: usize) -> usize {
    /// A cache entry of either layout: x and y in `w[k]`, `w[k + 1]`.
    #[derive(Clone, Copy, Default)]
    #[repr(C, align(4))]
    struct Entry {
        w: [i16; 4],
    }
    let mut rnd = super::xorshift32(0x7f4a_7c15_u32);
    let m = (1 << 14) - 1;
    let mut bad = 0;
    if scratch.len() < 2 * (2 * 257 + 12) {
        return cases;
    }
    let (mine, twin) = scratch.split_at_mut(scratch.len() / 2);
    for case in 0..cases {
        let k = (case & 1) * 2;
        // 0, 1: `placed` claimed, no entry unplaced; 2: claimed, entries may be
        // unplaced; 3: not claimed.
        let sort = case / 4 % 4;
        let len = rnd() as usize % 25;
        let mut cache = [Entry::default(); 24];
        for e in cache.iter_mut() {
            let r = rnd();
            // Extremes, and many corners on a 128-row screen and around it.
            let coord = |r: u32| match r % 8 {
                0 => m,
                1 => -m,
                2 => 0,
                3 | 4 => (r >> 3) as i32 % 2400 - 200,
                _ => (r >> 3) as i32 % (2 * m + 1) - m,
            };
            let (x, y) = if sort > 1 && r.is_multiple_of(16) {
                (i32::from(i16::MIN), (r >> 4) as i32 % 64) // unplaced: the mark, a code
            } else {
                (coord(rnd()), coord(rnd()))
            };
            let (x, y, r) = (x as i16, y as i16, rnd() as i16);
            e.w = if k == 0 { [x, y, r, r] } else { [r, r, x, y] };
        }
        let mut faces = [[0u16; 3]; 12];
        let span_of = (len + 2).min(8) as u32;
        for t in faces.iter_mut() {
            for i in t.iter_mut() {
                *i = (rnd() % span_of) as u16;
                if rnd().is_multiple_of(64) {
                    *i = (len as u32 + rnd() % 4) as u16; // out of range
                }
            }
        }
        // Back faces dropped on most cases that claim `placed` (the ARMv6-M `back` loop).
        let (lo, span) = match if sort < 3 { rnd() % 8 } else { rnd() % 4 } {
            0 | 4.. => (0, i32::MAX as u32),
            1 => (i32::MIN, 1 << 31),
            2 => (0, 0),
            _ => (rnd() as i32 >> (rnd() % 32), rnd()),
        };
        let faces = faces.get(..rnd() as usize % 13).unwrap_or(&[]);
        let cache = cache.get(..len).unwrap_or(&[]);
        let xy = if k == 0 {
            (|e: &Entry| (i32::from(e.w[0]), i32::from(e.w[1]))) as fn(&Entry) -> (i32, i32)
        } else {
            |e: &Entry| (i32::from(e.w[2]), i32::from(e.w[3]))
        };
        let scan = CullScan::new(faces, cache, 2 * k, xy, lo, span);
        let height = 1 + rnd() % 128;
        // A power of two half the time (the ARMv6-M kernel's bands; the others take
        // the twin there).
        let rows = if case & 2 == 0 {
            1 << (rnd() % 6)
        } else {
            1 + rnd() % 40
        };
        let chains = 2 * height.div_ceil(rows) as usize + 1;
        let start = rnd() as usize % 4;
        let run = |store: &mut [u16], kernel: bool| {
            store.fill(0);
            let Some((tails, slots)) = store.split_at_mut_checked(chains) else {
                return (usize::MAX, 0);
            };
            let slots = slots.get_mut(..12 + chains).unwrap_or(&mut []);
            for (c, t) in tails.iter_mut().enumerate() {
                *t = (12 + c) as u16;
            }
            let mut pos = start;
            let drawn = match BinChains::new(tails, slots, height, rows) {
                Some(mut b) => {
                    b.set_placed(sort < 3);
                    if kernel {
                        bin_scan(&mut pos, &scan, &mut b);
                    } else if b.scans() {
                        bin_scan_portable(&mut pos, &scan, &mut b);
                    }
                    b.drawn()
                }
                None => u32::MAX,
            };
            (pos, drawn)
        };
        let wrong = sort == 2 && cache.iter().any(|e| xy(e).0 < -(1 << 14));
        if wrong {
            // Only the bounds: the chains' slots are the first 2 · chains + 12.
            let (pos, _) = run(mine, true);
            let outside = mine.get(2 * chains + 12..).unwrap_or(&[]);
            if pos > faces.len().max(start) || outside.iter().any(|&v| v != 0) {
                bad += 1;
            }
        } else if run(mine, true) != run(twin, false) || mine != twin {
            bad += 1;
        }
    }
    bad
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The twin bins exactly the faces the cull rules draw (indices in range, no corner
    /// unplaced, the area outside the dropped range), each into the chain of its rows,
    /// and stops at the first face with a bad index or an unplaced corner; the on-target
    /// check runs clean on the host (where the kernel is the twin).
    #[test]
    fn the_twin_bins_the_drawn_faces_and_stops_where_the_walk_decides() {
        assert_eq!(check_bin_kernel(&mut [0; 1200], 3000), 0);
        let mut rnd = crate::num::kernel::xorshift32(0x0bad_5eed_u32);
        for _ in 0..3000 {
            let cache: std::vec::Vec<[i16; 4]> = (0..rnd() % 10)
                .map(|_| {
                    let c = |r: u32| (r % 3000) as i16 - 500;
                    let x = if rnd().is_multiple_of(12) {
                        i16::MIN
                    } else {
                        c(rnd())
                    };
                    [x, c(rnd()), 0, 0]
                })
                .collect();
            let n = cache.len() as u32 + 1;
            let faces: std::vec::Vec<[u16; 3]> = (0..rnd() % 12)
                .map(|_| [0; 3].map(|_: u16| (rnd() % n) as u16))
                .collect();
            let xy = |e: &[i16; 4]| (i32::from(e[0]), i32::from(e[1]));
            let scan = CullScan::new(&faces, &cache, 0, xy, 0, i32::MAX as u32);
            let (height, rows) = (1 + rnd() % 200, 1 + rnd() % 40);
            let chains = 2 * height.div_ceil(rows) as usize + 1;
            let fresh = || {
                let mut store = std::vec![0u16; 2 * chains + faces.len()];
                for (c, t) in store.iter_mut().take(chains).enumerate() {
                    *t = (faces.len() + c) as u16;
                }
                store
            };
            let (mut got, mut want) = (fresh(), fresh());
            let mut pos = 0;
            let (g_tails, g_slots) = got.split_at_mut(chains);
            let mut g = BinChains::new(g_tails, g_slots, height, rows).unwrap();
            bin_scan_portable(&mut pos, &scan, &mut g);
            let drawn = g.drawn();
            // The reference: face by face.
            let (w_tails, w_slots) = want.split_at_mut(chains);
            let mut w = BinChains::new(w_tails, w_slots, height, rows).unwrap();
            let mut stop = faces.len();
            for (f, t) in faces.iter().enumerate() {
                let c = t.map(|i| cache.get(usize::from(i)).map(xy));
                let [Some(a), Some(b), Some(c)] = c else {
                    stop = f;
                    break;
                };
                if [a, b, c].iter().any(|p| p.0 < -(1 << 14)) {
                    stop = f;
                    break;
                }
                let area = (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1);
                if area < 0 {
                    w.bin(f, [a.1, b.1, c.1]);
                    w.consts.drawn += 1;
                }
            }
            assert_eq!((pos, drawn), (stop, w.drawn()));
            assert_eq!(got, want);
        }
    }
}
