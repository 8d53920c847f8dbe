//! Binning in the cull scan: the scan's assembly loop (ARMv7E-M) extended so that each
//! drawn face of a cached mesh is appended to its band's bin chain without leaving the
//! loop, beside its portable twin.
#![allow(unsafe_code)]

use super::cull::{culled_run_portable, CullScan};

/// Whether [`bin_scan`] is the assembly loop (ARMv7E-M); elsewhere the band binning
/// keeps its own loop over the walk (on ARMv6-M the cull scan's assembly) and does not
/// call it.
pub(crate) const BIN_KERNEL: bool = cfg!(all(zraster_thumb, zraster_dsp));

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
}

/// What the assembly reads of [`BinChains`] through one register (offsets in the
/// comments).
#[repr(C)]
struct BinConsts {
    last_row: i32,   // 0: the screen's last row
    rows: u32,       // 4: rows a band (≥ 1)
    drawn: u32,      // 8: drawn faces found
    tall: u32,       // 12: the chain of faces reaching more than two bands
    tails: *mut u16, // 16, 20: set from the slices before each run of the assembly
    slots: *mut u16,
}

const _: () = {
    use core::mem::offset_of;
    assert!(offset_of!(BinConsts, last_row) == 0 && offset_of!(BinConsts, rows) == 4);
    assert!(offset_of!(BinConsts, drawn) == 8 && offset_of!(BinConsts, tall) == 12);
    // The pointers as the assembly (32-bit) reads them by one LDRD.
    assert!(offset_of!(BinConsts, tails) == 16);
    assert!(
        core::mem::size_of::<usize>() != 4 || offset_of!(BinConsts, slots) == 20,
        "the assembly reads the two pointers by one LDRD"
    );
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
                tall: (chains - 1) as u32,
                tails: core::ptr::null_mut(),
                slots: core::ptr::null_mut(),
            },
            tails,
            slots,
        })
    }

    /// Append face `f` (its corners' y `ys`, 1/16 pixel) to the chain of the rows whose
    /// pixel centres it may cover, if any ([`chain_of`]).
    #[inline(always)]
    pub(crate) fn bin(&mut self, f: usize, ys: [i32; 3]) {
        let rows = self.consts.rows as i32; // at most `height`, an i32
        let (last, tall) = (self.consts.last_row, self.consts.tall as usize);
        if let Some(c) = chain_of(ys, last, tall, |row| row / rows) {
            self.append(c, f);
        }
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
/// `tall` when it reaches further; `None` when it covers no row's pixel centre.
#[inline(always)]
pub(crate) fn chain_of(
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
    let bottom = ((ya.max(yb).max(yc) >> 4) - 1).min(last_row);
    if top > bottom {
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
pub(crate) fn append(tails: &mut [u16], slots: &mut [u16], c: usize, f: usize) {
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
pub(crate) fn end_chains(tails: &[u16], slots: &mut [u16], end: u16) {
    for c in 0..tails.len() {
        if let Some(slot) = tails.get(c).and_then(|&t| slots.get_mut(usize::from(t))) {
            *slot = end;
        }
    }
}

/// Advance `pos` past the faces of `scan` from `pos` on that are dropped or drawn,
/// appending each drawn one to its chain in `chains` ([`BinChains::bin`]) and counting
/// it there: it stops at the end or at a face with a bad index or an unplaced corner
/// (which the caller decides on). Dropped and drawn are as [`skip_culled`](super::skip_culled)
/// has them.
///
/// On ARMv7E-M the cull scan's assembly loop, with a drawn face binned in 44
/// instructions instead of leaving the loop.
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

/// [`bin_scan`] on ARMv7E-M.
#[cfg(all(zraster_thumb, zraster_dsp))]
#[inline(always)]
fn bin_scan_dsp<T>(pos: &mut usize, scan: &CullScan<'_, T>, chains: &mut BinChains<'_>) {
    let r = scan.regs();
    chains.consts.tails = chains.tails.as_mut_ptr();
    chains.consts.slots = chains.slots.as_mut_ptr();
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
    // them): 2⌊top/rows⌋ + 1 and 2⌊bottom/rows⌋ for 0 ≤ top ≤ bottom ≤ last_row =
    // height − 1 are below 2 · bands + 1 (rows ≥ 1, so UDIV never divides by 0), and
    // `tall` is the last.
    // r6 and r7 (not allowed as operands) are pushed and popped with r8–r11 (r7 counts
    // the drawn faces, stored back at the end); the flags are scratch.
    unsafe {
        core::arch::asm!(
            "push {{r6-r11}}",
            "mov r6, {consts}",
            "ldr r7, [r6, #8]", // the drawn faces so far
            "add r0, r0, r1, lsl #1",
            "add r0, r0, r1, lsl #2", // the face at `pos`
            "subs r1, lr, r1",        // the faces left
            "bls 3f",                 // none (`pos` at or past the end)
            "2:",
            "ldrh r8, [r0], #6",
            "ldrh r9, [r0, #-4]",
            "ldrh r10, [r0, #-2]",
            "cmp r8, r3",
            "itt lo",
            "cmplo r9, r3",
            "cmplo r10, r3",
            "bhs 3f",
            "ldr r8, [r2, r8, lsl #3]",
            "ldr r9, [r2, r9, lsl #3]",
            "ldr r10, [r2, r10, lsl #3]",
            "cmp r12, r8, lsl #16",
            "itt le",
            "cmple r12, r9, lsl #16",
            "cmple r12, r10, lsl #16",
            "bgt 3f",
            "ssub16 r9, r9, r8",
            "ssub16 r10, r10, r8",
            "smlsdx r11, r9, r10, r4",
            "cmp r11, r5",
            "bhi 4f",
            "5:",
            "subs r1, #1",
            "bne 2b",
            "3:", // a bad index or an unplaced corner, or none left
            "sub r1, lr, r1", // the face it stopped at (`pos` if none was left)
            "str r7, [r6, #8]",
            "pop {{r6-r11}}",
            "b 9f",
            // Drawn: its rows top..=bottom from the corners' y (y0 and the differences).
            "4:",
            "asr r11, r8, #16",
            "asr r9, r9, #16",
            "asr r10, r10, #16",
            "cmp r9, r10",
            "ite lt",
            "movlt r8, r9",
            "movge r8, r10",
            "it lt",
            "movlt r9, r10",
            "and r8, r8, r8, asr #31", // min(dy1, dy2, 0)
            "bic r9, r9, r9, asr #31", // max(dy1, dy2, 0)
            "add r11, r11, #7",
            "add r8, r8, r11",
            "add r9, r9, r11",
            "asr r8, r8, #4",
            "bic r8, r8, r8, asr #31", // top, at least 0
            "asr r9, r9, #4",
            "sub r9, r9, #1",
            "ldrd r10, r11, [r6]", // last_row, rows
            "cmp r9, r10",
            "it gt",
            "movgt r9, r10", // bottom, at most last_row
            "adds r7, #1", // one more drawn
            "cmp r8, r9",
            "bgt 5b", // no row
            "udiv r8, r8, r11",
            "udiv r9, r9, r11",
            "subs r9, r9, r8",
            "add r8, r8, r8",
            "beq 6f", // one band: chain 2·top band + 1
            "cmp r9, #1",
            "beq 7f", // two: chain 2·top band
            "ldr r8, [r6, #12]", // more: the tall chain
            "b 7f",
            "6:",
            "add r8, r8, #1",
            "7:", // append the face (its place) to chain r8
            "ldrd r10, r11, [r6, #16]",
            "add r10, r10, r8, lsl #1",
            "ldrh r9, [r10]",
            "sub r8, lr, r1",
            "strh r8, [r11, r9, lsl #1]",
            "strh r8, [r10]",
            "b 5b",
            "9:",
            consts = in(reg) consts,
            inout("r0") r.faces => _,
            inout("r1") *pos,
            inout("r2") r.xy => _,
            in("r3") r.len,
            in("r4") r.neg_lo,
            in("r5") r.span,
            in("r12") r.mark,
            in("lr") r.faces_len,
        );
    }
}

/// On-target check of the assembly binning scan (`bin_scan`) against its twin, for
/// the bench firmware: `cases` random runs as `check_cull_kernel` makes them (faces with
/// unplaced corners, bad indices, degenerate and extreme triangles, every cull mode),
/// binned for random screen heights (up to 128 rows, some faces above or below it) and
/// band heights, the chains in `scratch` (two sets of up to 2 · 257 + 12 entries: every
/// case counts as differing when it holds fewer than 1,052). Returns the number of runs
/// where the two stop at different faces, count different drawn faces, or leave
/// different chains.
#[inline(never)] // its arrays stay out of the caller's frame (the bench's stack figure)
pub fn check_bin_kernel(scratch: &mut [u16], cases: usize) -> usize {
    /// A cache entry of either layout: x and y in `w[k]`, `w[k + 1]`.
    #[derive(Clone, Copy, Default)]
    #[repr(C, align(4))]
    struct Entry {
        w: [i16; 4],
    }
    let mut seed = 0x7f4a_7c15_u32;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 17;
        seed ^= seed << 5;
        seed
    };
    let m = (1 << 14) - 1;
    let mut bad = 0;
    if scratch.len() < 2 * (2 * 257 + 12) {
        return cases;
    }
    let (mine, twin) = scratch.split_at_mut(scratch.len() / 2);
    for case in 0..cases {
        let k = (case & 1) * 2;
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
            let (x, y) = if r % 16 == 0 {
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
                if rnd() % 64 == 0 {
                    *i = (len as u32 + rnd() % 4) as u16; // out of range
                }
            }
        }
        let (lo, span) = match rnd() % 4 {
            0 => (0, i32::MAX as u32),
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
        let rows = 1 + rnd() % 40;
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
                    if kernel {
                        bin_scan(&mut pos, &scan, &mut b);
                    } else {
                        bin_scan_portable(&mut pos, &scan, &mut b);
                    }
                    b.drawn()
                }
                None => u32::MAX,
            };
            (pos, drawn)
        };
        if run(mine, true) != run(twin, false) || mine != twin {
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
        let mut seed = 0x0bad_5eed_u32;
        let mut rnd = move || {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            seed
        };
        for _ in 0..3000 {
            let cache: std::vec::Vec<[i16; 4]> = (0..rnd() % 10)
                .map(|_| {
                    let c = |r: u32| (r % 3000) as i16 - 500;
                    let x = if rnd() % 12 == 0 { i16::MIN } else { c(rnd()) };
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
