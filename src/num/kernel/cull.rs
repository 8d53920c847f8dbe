//! The cull scan of a cached triangle mesh: an assembly loop on ARMv7E-M and on
//! ARMv6-M over the faces the cull mode drops, beside its portable twin.
#![allow(unsafe_code)]

use core::marker::PhantomData;

/// Whether [`skip_culled`] is an assembly loop (ARMv7E-M, ARMv6-M); elsewhere the cull
/// pass keeps its own Rust scan and does not call it.
pub(crate) const CULL_KERNEL: bool = cfg!(all(zraster_thumb, any(zraster_dsp, zraster_armv6m)));

/// A cache entry's x and y (1/16 pixel) as the cull scans read them: one word, x in its
/// low half. On ARMv6-M an `i32`, whose halves one LDR and SXTH or ASRS give (its
/// halfword loads take a register offset only); elsewhere two `i16`, read by one
/// halfword load each.
#[cfg(zraster_armv6m)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(transparent)]
pub(crate) struct XyWord(i32);

#[cfg(zraster_armv6m)]
impl XyWord {
    /// The word of `x` and `y`.
    #[inline(always)]
    pub(crate) const fn new(x: i16, y: i16) -> XyWord {
        XyWord(((y as i32) << 16) | (x as u16 as i32))
    }
    /// x.
    #[inline(always)]
    pub(crate) const fn x(&self) -> i16 {
        self.0 as i16
    }
    /// y.
    #[inline(always)]
    pub(crate) const fn y(&self) -> i16 {
        (self.0 >> 16) as i16
    }
}

/// A cache entry's x and y (see the ARMv6-M form): x first.
#[cfg(not(zraster_armv6m))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(C)]
pub(crate) struct XyWord {
    x: i16,
    y: i16,
}

#[cfg(not(zraster_armv6m))]
impl XyWord {
    /// The word of `x` and `y`.
    #[inline(always)]
    pub(crate) const fn new(x: i16, y: i16) -> XyWord {
        XyWord { x, y }
    }
    /// x.
    #[inline(always)]
    pub(crate) const fn x(&self) -> i16 {
        self.x
    }
    /// y.
    #[inline(always)]
    pub(crate) const fn y(&self) -> i16 {
        self.y
    }
}

/// The faces of a cached mesh, its cache of 8-byte entries holding x and y (`i16`, y
/// after x) in one word, and a cull mode's range of dropped areas, as [`skip_culled`]
/// reads them.
pub(crate) struct CullScan<'a, T> {
    faces: &'a [[u16; 3]],
    cache: &'a [T],
    /// The entry's x and y, for the portable twin.
    xy: fn(&T) -> (i32, i32),
    /// Dropped: the twice-signed areas `a` with `a − lo ≤ span` (unsigned).
    lo: i32,
    regs: ScanRegs<'a>,
}

impl<'a, T> CullScan<'a, T> {
    /// A copy of the scan's operands, for [`skip_culled_by`].
    #[inline(always)]
    pub(crate) fn operands(&self) -> ScanRegs<'a> {
        self.regs
    }

    /// The faces scanned.
    #[inline(always)]
    pub(crate) fn faces(&self) -> &'a [[u16; 3]] {
        self.faces
    }

    /// The x and y of the corners of face `t`, `None` for an index past the cache.
    #[inline(always)]
    pub(crate) fn corners(&self, t: &[u16; 3]) -> Option<[(i32, i32); 3]> {
        let get = |i: u16| self.cache.get(usize::from(i)).map(self.xy);
        Some([get(t[0])?, get(t[1])?, get(t[2])?])
    }

    /// The assembly loop's operands (for the binning scan's loop, `bin`).
    #[cfg(zraster_thumb)]
    #[inline(always)]
    pub(super) fn regs(&self) -> &ScanRegs<'a> {
        &self.regs
    }
}

/// The assembly loops' operands, handed over in registers (ARMv7E-M: r0, r2–r5, r12,
/// lr; ARMv6-M, whose inline assembly takes r0–r5 only: r0–r5): an address of them
/// taken in the walk would keep the walk's fields in memory. A copy kept apart from
/// the walk ([`CullScan::operands`]) the ARMv7E-M loop can read by one LDM instead
/// ([`skip_culled_by`]; hence `repr(C)` and the order of the first seven words). The
/// twin reads `span`.
#[cfg_attr(not(zraster_thumb), allow(dead_code))]
#[derive(Clone, Copy, PartialEq, Eq)]
#[repr(C)]
pub(crate) struct ScanRegs<'a> {
    pub(super) faces: *const [u16; 3],
    /// The address of the first entry's x.
    pub(super) xy: *const u8,
    /// The entries the loop may read: `cache.len()`, or 0 when the entries are not
    /// laid out as the loop expects.
    pub(super) len: usize,
    pub(super) neg_lo: i32,
    pub(super) span: u32,
    /// −2¹⁴ · 2¹⁶: the marks' bound for x in a word's high half (ARMv7E-M).
    #[cfg_attr(not(zraster_dsp), allow(dead_code))]
    pub(super) mark: i32,
    pub(super) faces_len: usize,
    /// One past the last face (ARMv6-M).
    #[cfg_attr(not(zraster_armv6m), allow(dead_code))]
    pub(super) end: *const [u16; 3],
    cache: PhantomData<&'a [u8]>,
}

// The ARMv7E-M loop reads the first seven words by one LDM, in this order.
#[cfg(target_pointer_width = "32")]
const _: () = {
    use core::mem::offset_of;
    type R = ScanRegs<'static>;
    assert!(offset_of!(R, faces) == 0 && offset_of!(R, xy) == 4 && offset_of!(R, len) == 8);
    assert!(offset_of!(R, neg_lo) == 12 && offset_of!(R, span) == 16);
    assert!(offset_of!(R, mark) == 20 && offset_of!(R, faces_len) == 24);
};

impl<'a, T> CullScan<'a, T> {
    /// The scan of `faces` over `cache`, whose entries hold x at byte `xy_at` and y
    /// after it (`xy` reads both), dropping the areas `a` with `a − lo ≤ span` in
    /// unsigned arithmetic. Entries not of 8 bytes, aligned to 4, with the word at
    /// `xy_at`, make the assembly loop drop no face.
    #[inline(always)]
    pub(crate) fn new(
        faces: &'a [[u16; 3]],
        cache: &'a [T],
        xy_at: usize,
        xy: fn(&T) -> (i32, i32),
        lo: i32,
        span: u32,
    ) -> Self {
        let fits = core::mem::size_of::<T>() == 8
            && core::mem::align_of::<T>() >= 4
            && (xy_at == 0 || xy_at == 4);
        CullScan {
            faces,
            cache,
            xy,
            lo,
            regs: ScanRegs {
                faces: faces.as_ptr(),
                xy: cache.as_ptr().cast::<u8>().wrapping_add(xy_at),
                len: if fits { cache.len() } else { 0 },
                neg_lo: lo.wrapping_neg(),
                span,
                mark: -(1 << 30),
                faces_len: faces.len(),
                end: faces.as_ptr_range().end,
                cache: PhantomData,
            },
        }
    }
}

/// Advance `pos` past the faces of the scan from `pos` on that are dropped: every
/// index below the cache's length, no corner unplaced (x below −2¹⁴, the cache's mark),
/// and the twice-signed area `(xb − xa)(yc − ya) − (xc − xa)(yb − ya)` in the dropped
/// range. Returns the corners of the face it stops at when that face is drawn (every
/// index in range, no corner unplaced, the area not dropped); `None` when none is left,
/// or when that face has a bad index or an unplaced corner. Placed corners must lie
/// within ±(2¹⁴ − 1), as cached ones do, for the area to be exact in `i32`.
///
/// On ARMv7E-M an assembly loop of 23 instructions a dropped face (the Rust scan takes
/// about 40), inline, saving the registers it takes beyond its operands itself, so
/// that the cull pass keeps its own; it reads the faces by place, not by an iterator,
/// so that neither it nor the caller divides a length by 6. On ARMv6-M one of 42 (the
/// Rust scan there spills: about 66).
#[inline(always)]
pub(crate) fn skip_culled<'a, T>(pos: &mut usize, scan: &CullScan<'a, T>) -> Option<[&'a T; 3]> {
    #[cfg(all(zraster_thumb, zraster_dsp))]
    return skip_culled_dsp::<_, false>(pos, scan, &scan.regs);
    #[cfg(all(zraster_thumb, zraster_armv6m))]
    return skip_culled_v6m(pos, scan);
    #[allow(unreachable_code)]
    {
        let (n, drawn) = culled_run_portable(scan.faces.get(*pos..).unwrap_or(&[]), scan);
        *pos += n;
        let t = scan.faces.get(*pos).filter(|_| drawn)?;
        let get = |i: u16| scan.cache.get(usize::from(i));
        Some([get(t[0])?, get(t[1])?, get(t[2])?])
    }
}

/// [`skip_culled`] with the operands read from `regs`, a copy of the scan's own
/// ([`CullScan::operands`]) that the caller keeps apart from its walk: on ARMv7E-M by
/// one LDM at each call instead of seven values the caller reloads. Elsewhere
/// [`skip_culled`] (on ARMv6-M its registers are the cheaper).
#[inline(always)]
pub(crate) fn skip_culled_by<'a, T>(
    pos: &mut usize,
    scan: &CullScan<'a, T>,
    regs: &ScanRegs<'a>,
) -> Option<[&'a T; 3]> {
    #[cfg(all(zraster_thumb, zraster_dsp))]
    return skip_culled_dsp::<_, true>(pos, scan, regs);
    #[allow(unreachable_code)]
    {
        let _ = regs;
        skip_culled(pos, scan)
    }
}

/// What the cull scan makes of one face.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Verdict {
    Dropped,
    Drawn,
    /// A bad index or an unplaced corner: for the caller's general path.
    Other,
}

/// The portable twin of [`skip_culled`] (the cull pass's own Rust scan): how many faces
/// from the start of `faces` are dropped, and whether the next one is drawn.
pub(crate) fn culled_run_portable<T>(faces: &[[u16; 3]], scan: &CullScan<'_, T>) -> (usize, bool) {
    let verdict = |t: &[u16; 3]| {
        let get = |i: u16| scan.cache.get(usize::from(i)).map(scan.xy);
        let (Some(a), Some(b), Some(c)) = (get(t[0]), get(t[1]), get(t[2])) else {
            return Verdict::Other;
        };
        if [a, b, c].iter().any(|p| p.0 < -(1 << 14)) {
            return Verdict::Other;
        }
        let area = (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1);
        if area.wrapping_sub(scan.lo) as u32 <= scan.regs.span {
            Verdict::Dropped
        } else {
            Verdict::Drawn
        }
    };
    let n = faces
        .iter()
        .take_while(|t| verdict(t) == Verdict::Dropped)
        .count();
    (
        n,
        faces.get(n).is_some_and(|t| verdict(t) == Verdict::Drawn),
    )
}

/// The turns of [`skip_culled_dsp`]'s loop from its first face on (r0 at the face at
/// `pos`, r1 the faces left, r2 the first entry's x/y word, r3 the entries' number,
/// r4 −lo, r5 span, r12 the marks' bound): on to `3f` at a bad index or an unplaced
/// corner, to `4f` at a drawn face (r0 past it, r1 counting it), through at the end.
/// Also the scan of the fused face loop (`faces`).
#[cfg(all(zraster_thumb, zraster_dsp))]
macro_rules! dsp_cull_scan {
    () => {
        concat!(
            "2:\n",
            "ldrh r8, [r0], #6\n",
            "ldrh r9, [r0, #-4]\n",
            "ldrh r10, [r0, #-2]\n",
            "cmp r8, r3\n",
            "itt lo\n",
            "cmplo r9, r3\n",
            "cmplo r10, r3\n",
            "bhs 3f\n",
            "ldr r8, [r2, r8, lsl #3]\n",
            "ldr r9, [r2, r9, lsl #3]\n",
            "ldr r10, [r2, r10, lsl #3]\n",
            "cmp r12, r8, lsl #16\n",
            "itt le\n",
            "cmple r12, r9, lsl #16\n",
            "cmple r12, r10, lsl #16\n",
            "bgt 3f\n",
            "ssub16 r9, r9, r8\n",
            "ssub16 r10, r10, r8\n",
            "smlsdx r11, r9, r10, r4\n",
            "cmp r11, r5\n",
            "bhi 4f\n",
            "subs r1, #1\n",
            "bne 2b\n",
        )
    };
}

/// [`dsp_cull_scan`] with [`skip_culled_dsp`]'s ends (lr the faces' number).
#[cfg(all(zraster_thumb, zraster_dsp))]
macro_rules! dsp_cull_loop {
    () => {
        concat!(
            dsp_cull_scan!(),
            // A bad index or an unplaced corner, or none left.
            "3:\n",
            "movs r2, #0\n",
            "b 6f\n",
            // Drawn: its indices.
            "4:\n",
            "ldrh r3, [r0, #-6]\n",
            "ldrh r4, [r0, #-4]\n",
            "ldrh r5, [r0, #-2]\n",
            "movs r2, #1\n",
            "6:\n",
            // The face it stopped at (`pos` if none was left).
            "sub r1, lr, r1\n",
            "pop {{r8-r11}}\n",
        )
    };
}

/// [`skip_culled`] on ARMv7E-M: the operands in registers, or (`BY_LDM`) read from
/// `regs` by one LDM.
#[cfg(all(zraster_thumb, zraster_dsp))]
#[inline(always)]
fn skip_culled_dsp<'a, T, const BY_LDM: bool>(
    pos: &mut usize,
    scan: &CullScan<'a, T>,
    regs: &ScanRegs<'a>,
) -> Option<[&'a T; 3]> {
    let (drawn, a, b, c): (u32, usize, usize, usize);
    let r = regs;
    // SAFETY: reads the faces from `pos` on, none when `pos` is not below their number,
    // one a turn while any is left (r1 counts them down), so only inside the faces; r1
    // ends as the place of the face it stops at (`pos` when none was left). It reads an
    // entry's word at `xy + 8 i` only for indices `i` it has found below `regs.len`,
    // which is the cache's length for a cache of 8-byte entries whose word at `xy_at`
    // (0 or 4) is aligned, or 0 (`CullScan::new`), so only inside the cache (`regs` is
    // the scan's own operands or a copy of them, `CullScan::operands`: the only ones
    // `CachedWalk::reading` keeps; LDM reads its
    // first seven words, `repr(C)`). The registers it takes beyond its operands
    // (r8–r11) are pushed first and popped last. For a drawn face it returns the three
    // indices it found below `regs.len` in r3–r5.
    //
    // A turn: the three indices against the length (the IT block's compares run while
    // the previous ones found the index in range), the three entries' x/y words, the
    // marks (x < −2¹⁴ as x·2¹⁶ < −2³⁰, by the same chain), the differences of the
    // corners as halfword pairs (each below 2¹⁵ in magnitude) and the area less `lo` by
    // one SMLSDX, compared with `span`.
    unsafe {
        if BY_LDM {
            core::arch::asm!(
                "push {{r8-r11}}",
                "ldm r0, {{r0, r2, r3, r4, r5, r12, lr}}",
                "add r0, r0, r1, lsl #1",
                "add r0, r0, r1, lsl #2", // the face at `pos`
                "subs r1, lr, r1",        // the faces left
                "bls 3f",                 // none (`pos` at or past the end)
                dsp_cull_loop!(),
                inout("r0") r as *const ScanRegs<'_> => _,
                inout("r1") *pos,
                out("r2") drawn,
                out("r3") a,
                out("r4") b,
                out("r5") c,
                out("r12") _,
                out("lr") _,
                options(readonly),
            );
        } else {
            core::arch::asm!(
                "push {{r8-r11}}",
                "add r0, r0, r1, lsl #1",
                "add r0, r0, r1, lsl #2", // the face at `pos`
                "subs r1, lr, r1",        // the faces left
                "bls 3f",                 // none (`pos` at or past the end)
                dsp_cull_loop!(),
                inout("r0") r.faces => _,
                inout("r1") *pos,
                inout("r2") r.xy => drawn,
                inout("r3") r.len => a,
                inout("r4") r.neg_lo => b,
                inout("r5") r.span => c,
                inout("r12") r.mark => _,
                inout("lr") r.faces_len => _,
                options(readonly),
            );
        }
    }
    if drawn == 0 {
        return None;
    }
    // SAFETY: the loop returns a drawn face's indices only once it has found each below
    // `regs.len`, which is `scan.cache.len()` or 0 (`CullScan::new`).
    Some(unsafe {
        [
            scan.cache.get_unchecked(a),
            scan.cache.get_unchecked(b),
            scan.cache.get_unchecked(c),
        ]
    })
}

/// [`skip_culled`] on ARMv6-M.
#[cfg(all(zraster_thumb, zraster_armv6m))]
#[inline(always)]
fn skip_culled_v6m<'a, T>(pos: &mut usize, scan: &CullScan<'a, T>) -> Option<[&'a T; 3]> {
    if *pos >= scan.regs.faces_len {
        return None;
    }
    let r = &scan.regs;
    let (at, drawn, a, b, c): (*const [u16; 3], u32, usize, usize, usize);
    // SAFETY: `pos` is below the number of faces (tested above), so r0 starts at a
    // face (`wrapping_add` gives its address); the loop reads one face a turn and stops
    // at `end` (r7), so only inside the faces. It reads an entry's word at `xy + 8 i`
    // only for indices `i` it has found below `regs.len` (r8), which is the cache's
    // length for a cache of 8-byte entries whose word at `xy_at` (0 or 4) is aligned,
    // or 0 (`CullScan::new`), so only inside the cache. r6, r7 (which cannot be
    // operands) and r8 are pushed first and popped last (saved by the caller instead,
    // its frame would grow); r12 and lr are declared clobbered. For a drawn face it
    // returns the three indices it found below `regs.len` in r3–r5; r0 returns the face
    // it stops at.
    //
    // A turn: the three indices against the length, the three entries' x/y words, the
    // marks (bits 15 and 14 of x differ: x < −2¹⁴, or x ≥ 2¹⁴, which a placed corner
    // is not) by the overflow of doubling x·2¹⁶, the differences of x as the low
    // halves of the words' differences (each below 2¹⁵ in magnitude), of y from the
    // high halves, and the area less `lo` (two products, each below 2³⁰ in magnitude),
    // compared with `span`.
    unsafe {
        core::arch::asm!(
            "push {{r6, r7}}",
            "mov r6, r8",
            "push {{r6}}",
            "mov r8, r2",  // the entries' number
            "mov r7, r3",  // the faces' end
            "mov r12, r4", // −lo
            "mov lr, r5",  // span
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
            "sxth r5, r5", // xb − xa
            "subs r6, r4, r2",
            "sxth r6, r6", // xc − xa
            "asrs r2, r2, #16",
            "asrs r3, r3, #16",
            "subs r3, r3, r2", // yb − ya
            "asrs r4, r4, #16",
            "subs r4, r4, r2", // yc − ya
            "muls r5, r4, r5", // (xb − xa)(yc − ya)
            "muls r6, r3, r6", // (xc − xa)(yb − ya)
            "subs r5, r5, r6",
            "add r5, r12",
            "cmp r5, lr",
            "bhi 4f",
            "adds r0, #6",
            "cmp r0, r7",
            "bne 2b",
            "3:", // a bad index or an unplaced corner, or none left
            "movs r2, #0",
            "b 6f",
            "4:", // drawn: its indices
            "ldrh r3, [r0, #0]",
            "ldrh r4, [r0, #2]",
            "ldrh r5, [r0, #4]",
            "movs r2, #1",
            "6:",
            "pop {{r6}}",
            "mov r8, r6",
            "pop {{r6, r7}}",
            inout("r0") r.faces.wrapping_add(*pos) => at,
            inout("r1") r.xy => _,
            inout("r2") r.len => drawn,
            inout("r3") r.end => a,
            inout("r4") r.neg_lo => b,
            inout("r5") r.span => c,
            out("r12") _,
            out("lr") _,
            options(readonly),
        );
    }
    // The place: the bytes from the first face over 6, exactly (a multiple of 6 halved,
    // times the inverse of 3 modulo 2³²; no division routine).
    let bytes = at as usize - scan.regs.faces as usize;
    *pos = (bytes >> 1).wrapping_mul(0xAAAA_AAAB);
    if drawn == 0 {
        return None;
    }
    // SAFETY: the loop returns a drawn face's indices only once it has found each below
    // `regs.len`, which is `scan.cache.len()` or 0 (`CullScan::new`).
    Some(unsafe {
        [
            scan.cache.get_unchecked(a),
            scan.cache.get_unchecked(b),
            scan.cache.get_unchecked(c),
        ]
    })
}

/// On-target check of the assembly cull scan (`skip_culled`) against its twin, for the
/// bench firmware: `cases` random runs of up to 12 faces from a random start, over
/// caches of up to 24 entries (both layouts: x at byte 0 and at byte 4), with unplaced
/// corners, indices out of range, degenerate and extreme triangles (corners at
/// ±(2¹⁴ − 1)), for the three cull modes and random ranges, with the operands in
/// registers and read from a copy (`skip_culled_by`). Returns the number of runs
/// where either stops at a different face than the twin or differs on whether that face
/// is drawn.
#[inline(never)] // its arrays stay out of the caller's frame (the bench's stack figure)
pub fn check_cull_kernel(cases: usize) -> usize {
    /// A cache entry of either layout: x and y in `w[k]`, `w[k + 1]`.
    #[derive(Clone, Copy, Default)]
    #[repr(C, align(4))]
    struct Entry {
        w: [i16; 4],
    }
    let mut rnd = super::xorshift32(0x2545_f491_u32);
    let m = (1 << 14) - 1;
    let mut bad = 0;
    for case in 0..cases {
        let k = (case & 1) * 2;
        let len = rnd() as usize % 25;
        let mut cache = [Entry::default(); 24];
        for e in cache.iter_mut() {
            let r = rnd();
            let coord = |r: u32| match r % 8 {
                0 => m,
                1 => -m,
                2 => 0,
                _ => (r >> 3) as i32 % (2 * m + 1) - m,
            };
            let (x, y) = if r.is_multiple_of(16) {
                (i32::from(i16::MIN), (r >> 4) as i32 % 64) // unplaced: the mark, a code
            } else {
                (coord(rnd()), coord(rnd()))
            };
            let (x, y, r) = (x as i16, y as i16, rnd() as i16);
            e.w = if k == 0 { [x, y, r, r] } else { [r, r, x, y] };
        }
        let mut faces = [[0u16; 3]; 12];
        // Few distinct indices, so that degenerate faces (a corner twice) occur.
        let span_of = (len + 2).min(8) as u32;
        for t in faces.iter_mut() {
            for i in t.iter_mut() {
                *i = (rnd() % span_of) as u16;
                if rnd().is_multiple_of(64) {
                    *i = (len as u32 + rnd() % 4) as u16; // out of range
                }
            }
        }
        let (lo, span) = match rnd() % 4 {
            0 => (0, i32::MAX as u32),                  // back faces
            1 => (i32::MIN, 1 << 31),                   // front faces
            2 => (0, 0),                                // none
            _ => (rnd() as i32 >> (rnd() % 32), rnd()), // any range
        };
        let xy = if k == 0 {
            (|e: &Entry| (i32::from(e.w[0]), i32::from(e.w[1]))) as fn(&Entry) -> (i32, i32)
        } else {
            |e: &Entry| (i32::from(e.w[2]), i32::from(e.w[3]))
        };
        let faces = faces.get(..rnd() as usize % 13).unwrap_or(&[]);
        let cache = cache.get(..len).unwrap_or(&[]);
        let scan = CullScan::new(faces, cache, 2 * k, xy, lo, span);
        let start = rnd() as usize % 4;
        let mut pos = start;
        let corners = skip_culled(&mut pos, &scan).map(|c| c.map(|e| e as *const Entry));
        // The same with the operands read from a copy.
        let (operands, mut pos_by) = (scan.operands(), start);
        let corners_by =
            skip_culled_by(&mut pos_by, &scan, &operands).map(|c| c.map(|e| e as *const Entry));
        let (n, twin_drawn) = culled_run_portable(faces.get(start..).unwrap_or(&[]), &scan);
        let twin_pos = if start < faces.len() {
            start + n
        } else {
            start
        };
        // A drawn face's corners: its entries.
        let twin_corners = faces.get(twin_pos).filter(|_| twin_drawn).and_then(|t| {
            let get = |i: u16| cache.get(usize::from(i)).map(|e| e as *const Entry);
            Some([get(t[0])?, get(t[1])?, get(t[2])?])
        });
        if (pos, corners) != (twin_pos, twin_corners) {
            bad += 1;
        }
        if (pos_by, corners_by) != (twin_pos, twin_corners) {
            bad += 1;
        }
    }
    bad
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cull_kernel_matches_its_twin() {
        assert_eq!(check_cull_kernel(20_000), 0);
    }

    /// The twin stops at the first face not dropped, whatever stops it.
    #[test]
    fn the_twin_stops_where_a_face_is_not_dropped() {
        let cache = [[0i16, 0], [16, 0], [0, 16], [i16::MIN, 3]];
        let xy = |e: &[i16; 2]| (i32::from(e[0]), i32::from(e[1]));
        // Back faces: dropped when the area is 0 or more.
        let scan = CullScan::new(&[], &cache, 0, xy, 0, i32::MAX as u32);
        assert_eq!(
            culled_run_portable(&[[0, 1, 2], [0, 0, 1], [0, 2, 1]], &scan),
            (2, true)
        );
        assert_eq!(
            culled_run_portable(&[[0, 1, 2], [0, 1, 3]], &scan),
            (1, false)
        );
        assert_eq!(
            culled_run_portable(&[[0, 1, 2], [0, 1, 4]], &scan),
            (1, false)
        );
        assert_eq!(culled_run_portable(&[[0, 1, 2]], &scan), (1, false));
        assert_eq!(culled_run_portable(&[], &scan), (0, false));
    }
}
