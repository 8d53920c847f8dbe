//! The vertex cache's usual vertex on ARMv6-M: the fixed-point transform, the integer
//! projection and the entry in one Thumb-1 assembly loop, beside its portable twin.
//!
//! It computes `ScreenMap::project_fast` of `FixedTransform::apply`, then
//! `CachedVertex::placing`, step for step: the six rows (x, y, z and w in two partial
//! sums each), the near, far and w planes on z and w in units of 2¹⁴, w's bits beyond
//! 31 against the hint the block carries (a four-step search on a miss), w and z + w
//! normalised, x and y normalised by one shift each, the reciprocal ⌊2⁶²/wn⌋, the
//! screen coordinates by five 16 × 16-bit products each and the depth by the rounded
//! high word of four. It refuses one value more next to a screen coordinate's rounding
//! boundary (4 in 16,384 instead of 3), which a shorter test finds. The reciprocal is
//! [`recip62_low`] (the integer projection's too), its first step from the 512-entry
//! table `recip32_small` reads. Any vertex it does not place stops the loop for the
//! caller's exact path.
#![allow(unsafe_code)]

use super::{CachedVertex, XyWord};
use crate::fixed::MAX_DEPTH;
use crate::num::armv6m::RECIP16;

/// Whether [`place_run_v6m`] is the assembly loop (ARMv6-M).
pub(crate) const PLACE_V6M_KERNEL: bool = cfg!(all(zraster_thumb, zraster_armv6m));

/// The operands of [`place_run_v6m`], read by the loop at fixed offsets (`repr(C)`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(C)]
pub(crate) struct PlaceV6m<'a> {
    /// y's operands: right shift, overflow shift, left shift (of the normalisation
    /// by 2^(sh − e)), the half height, 2¹³ + 4, the y origin (1/16 pixel).
    ys: [u32; 6],
    /// x's operands, as `ys` with the half width and the x origin.
    xs: [u32; 6],
    /// The rows x, y, z high, w high, z low, w low: `c₀`, `c₁`, `c₂`, `t` each.
    rows: &'a [[i32; 4]; 6],
    /// sh − 1 for w's bits sh beyond 31 at the last vertex that changed it (the hint,
    /// 0..=13).
    hint: u32,
    /// 14 − sh.
    up: u32,
    /// The exponent `e` of x and y's scale to z and w's (0..=20).
    e: u32,
}

// The loop reads y's operands at 0, x's at 24, the rows' address at 48, the hint at
// 52, 14 − sh at 56 and e at 60 (addresses of 32 bits).
#[cfg(all(zraster_thumb, zraster_armv6m))]
const _: () = assert!(
    core::mem::offset_of!(PlaceV6m<'_>, ys) == 0
        && core::mem::offset_of!(PlaceV6m<'_>, xs) == 24
        && core::mem::offset_of!(PlaceV6m<'_>, rows) == 48
        && core::mem::offset_of!(PlaceV6m<'_>, hint) == 52
        && core::mem::offset_of!(PlaceV6m<'_>, up) == 56
        && core::mem::offset_of!(PlaceV6m<'_>, e) == 60
        && core::mem::size_of::<PlaceV6m<'_>>() == 64
        && core::mem::size_of::<[[i32; 4]; 6]>() == 96
);

/// Where in `ys` and `xs` the half extent, the rounding constant and the origin go.
const HALF: usize = 3;
const ROUND: usize = 4;
const ORIGIN: usize = 5;

impl<'a> PlaceV6m<'a> {
    /// The block of the rows `rows` (x, y, z high, w high, z low, w low, each `[c₀, c₁,
    /// c₂, t]`, as `FixedTransform::with_rows_v6m` gives them), x and y's scale exponent `e`
    /// (0..=20), the half width and height `half` (1/16 pixel, at most 2¹⁶) and the
    /// origin `org`, w's bits beyond 31 guessed as `sh` (1..=14).
    pub(crate) fn new(
        rows: &'a [[i32; 4]; 6],
        e: u32,
        half: [u32; 2],
        org: [i32; 2],
        sh: u32,
    ) -> PlaceV6m<'a> {
        let operands = |h: u32, o: i32| [0, 31, 0, h, (1 << 13) + 4, o as u32];
        let mut b = PlaceV6m {
            ys: operands(half[1], org[1]),
            xs: operands(half[0], org[0]),
            rows,
            hint: 0,
            up: 0,
            e,
        };
        b.set_sh(sh);
        b
    }

    /// The hint for w's bits `sh` beyond 31 (1..=14), and the normalisation's shifts
    /// for k = sh − e: right by k when k ≥ 0, else left by −k, the magnitude first
    /// checked below 2^(31 + k).
    fn set_sh(&mut self, sh: u32) {
        let k = sh as i32 - self.e as i32;
        let (right, left) = (k.max(0) as u32, (-k).max(0) as u32);
        self.hint = sh - 1;
        self.up = 14 - sh;
        for s in [&mut self.ys, &mut self.xs] {
            s[0] = right;
            s[1] = 31 - left;
            s[2] = left;
        }
    }
}

/// ⌊2³¹/(v + 1)⌋ for 2¹⁵ ≤ v < 2¹⁶: the table's 2²⁵/(513 + i) for v's top nine bits
/// (at most 2³¹/(v + 1), and within 2⁻⁹ of it), one Newton step (error below 1.3: the
/// step's square 0.28, the dropped bits 1.01) and a correction by the remainder.
#[inline(always)]
fn recip31_table(v: u32) -> u32 {
    let w = v + 1;
    let i = ((v >> 6) & 0x1ff) as usize;
    let t = u32::from(RECIP16.get(i).copied().unwrap_or(0));
    // e = 2³¹ − w·t in [0, 2²³): t·⌊e/2⁷⌋ < 2³².
    let e = (1u32 << 31).wrapping_sub(w.wrapping_mul(t));
    let y = t.wrapping_add(t.wrapping_mul(e >> 7) >> 24);
    y + u32::from((1u32 << 31).wrapping_sub(w.wrapping_mul(y)) >= w)
}

/// ⌊2⁶²/d⌋ for 2³⁰ < d < 2³¹ in 32-bit multiplies, without a division (on ARMv6-M,
/// 64-bit products are long): the integer projection's reciprocal, here beside the
/// vertex loop that does the same. Each step's error is read off the low word of a
/// product, exact because the step keeps it in `[0, 2³²)`:
///
/// 1. y = ⌊2³¹/(v + 1)⌋ for d's top 16 bits v ([`recip31_table`]: a test checks every
///    v). Then y ≤ 2⁴⁶/d and e = 2⁴⁶ − d·y < 2⁴⁶/(v + 1) + v·2¹⁵ ≤ 2³².
/// 2. With ε = e/2⁴⁶ < 2⁻¹⁴, 2⁴⁹/d = 8y/(1 − ε) = 8y + y·e/2⁴³ + 8y·ε²/(1 − ε), the
///    last term below 2⁻⁹: y' = 8y + ⌊y·⌊e/2¹⁶⌋/2²⁷⌋ lies within [2⁴⁹/d − 2, 2⁴⁹/d]
///    (1 + 2⁻¹⁶ + 2⁻⁹ dropped), so e' = 2⁴⁹ − d·y' is in [0, 2d) ⊂ [0, 2³²).
/// 3. Likewise 2⁶²/d = 2¹³y' + y'·e'/2³⁶ + t with t = 2¹³y'·ε'²/(1 − ε') < ¼
///    (ε' < 2⁻¹⁷, y' < 2¹⁹); x = 2¹³y' + ⌊(y'/8)·e'/2³³⌋ (the product from 16-bit
///    halves of e', y'/8 < 2¹⁶) drops below 0.5 + 2⁻¹⁷ + 1, so 2⁶²/d − x ∈ [0, 2).
///    The remainder 2⁶² − d·x is then in [0, 2d) ⊂ [0, 2³²): x or x + 1.
#[inline(always)]
pub(crate) fn recip62_low(d: u32) -> u32 {
    // 1.
    let y = recip31_table(d >> 15);
    // 2.
    let e = d.wrapping_mul(y).wrapping_neg();
    let y = 8 * y + ((y * (e >> 16)) >> 27);
    // 3.
    let e = d.wrapping_mul(y).wrapping_neg();
    let h = y >> 3;
    let x = (y << 13) + ((h * (e >> 16) + ((h * (e & 0xffff)) >> 16)) >> 17);
    x + u32::from(d.wrapping_mul(x).wrapping_neg() >= d)
}

/// One screen coordinate's offset from its origin: `v·2^e/2^sh · h/wn` rounded (the
/// operands `s` of [`PlaceV6m`]), through r = ⌊2⁶²/wn⌋ in halves `rh`, `rl`, as
/// `project::signed_ratio` where it gives one; `None` where that cannot tell (or one
/// value more) or the normalised v reaches 2³¹.
#[inline(always)]
fn ratio(v: i32, s: &[u32; 6], rh: u32, rl: u32) -> Option<i32> {
    let sign = v >> 31;
    let a = ((v >> s[0]) ^ sign).wrapping_sub(sign) as u32;
    if a >> s[1] != 0 {
        return None;
    }
    let a = a << s[2];
    let (a1, a0) = (a >> 16, a & 0xffff);
    let p = (a1.wrapping_mul(rh))
        .wrapping_add(a1.wrapping_mul(rl) >> 16)
        .wrapping_add(a0.wrapping_mul(rh) >> 16);
    let h = s[HALF];
    let f = (p >> 16)
        .wrapping_mul(h)
        .wrapping_add((p & 0xffff).wrapping_mul(h) >> 16)
        .wrapping_add(s[ROUND]);
    // None within 4 of a rounding boundary (project::signed_ratio's 3 and one more).
    if f & 0x3fff < 4 {
        return None;
    }
    Some(((f >> 14) as i32 ^ sign).wrapping_sub(sign))
}

/// |c| < 2¹⁴ (a placed coordinate), as `CachedVertex::placing` tests it.
#[inline(always)]
fn fits(c: i32) -> bool {
    c.wrapping_add((1 << 14) - 1) as u32 <= 2 * ((1 << 14) - 1)
}

/// The entry of position `p`, or `None` where the loop stops: the portable twin of one
/// vertex of [`place_run_v6m`]'s loop (every step the same, the hint updated alike).
pub(crate) fn place_v6m_portable(b: &mut PlaceV6m<'_>, p: &[i16; 3]) -> Option<CachedVertex> {
    let [px, py, pz] = p.map(i32::from);
    let row = |[c0, c1, c2, t]: [i32; 4]| {
        c0.wrapping_mul(px)
            .wrapping_add(c1.wrapping_mul(py))
            .wrapping_add(c2.wrapping_mul(pz))
            .wrapping_add(t)
    };
    let [x, y, zh, wh, zl, wl] = b.rows.map(row);
    let (zt, wt) = (zh.wrapping_add(zl >> 14), wh.wrapping_add(wl >> 14));
    let (zl, wl) = ((zl & 0x3fff) as u32, (wl & 0x3fff) as u32);
    // w ≥ 2³¹ and z strictly between −w and w with a unit of room (a negative wt fails
    // one of the two z tests).
    if (wt as u32) >> 17 == 0 || i64::from(zt) + i64::from(wt) <= 0 || zt >= wt.wrapping_sub(1) {
        return None;
    }
    // wt >> (16 + sh) = 1 for the hint's sh, else sh = 1 + ⌊log₂(wt/2¹⁷)⌋.
    if (wt as u32) >> 17 >> b.hint != 1 {
        let mut t = (wt as u32) >> 17;
        let mut sh = 1;
        for k in [8, 4, 2, 1] {
            if t >> k != 0 {
                t >>= k;
                sh += k;
            }
        }
        b.set_sh(sh);
    }
    let (sh, up) = (b.hint + 1, b.up);
    let wn = ((wt as u32) << up).wrapping_add(wl >> sh);
    if wn << 2 == 0 {
        return None; // wn = 2³⁰
    }
    let ut = (zt as u32).wrapping_add(wt as u32);
    let un = (ut << up).wrapping_add((zl + wl) >> sh);
    let r = recip62_low(wn);
    let (rh, rl) = (r >> 16, r & 0xffff);
    // Depth: the rounded high word of un·r (q30), then 2·q30 − ⌊(q30 + 2¹⁴ − 1)/2¹⁵⌋.
    let (a1, a0) = (un >> 16, un & 0xffff);
    let (m1, m2) = (a1.wrapping_mul(rl), a0.wrapping_mul(rh));
    let low = (a0.wrapping_mul(rl) >> 16)
        .wrapping_add(m1 & 0xffff)
        .wrapping_add(m2 & 0xffff)
        .wrapping_add(1 << 15);
    let q30 = a1
        .wrapping_mul(rh)
        .wrapping_add(m1 >> 16)
        .wrapping_add(m2 >> 16)
        .wrapping_add(low >> 16);
    // Above q30 = 2³¹ (where it is MAX_DEPTH) the depth is clamped.
    let d = q30.wrapping_add((1 << 14) - 1) >> 15;
    let sz = if q30 > 1 << 31 {
        MAX_DEPTH
    } else {
        q30.wrapping_add(q30.wrapping_sub(d))
    };
    let sy = (b.ys[ORIGIN] as i32).wrapping_sub(ratio(y, &b.ys, rh, rl)?);
    if !fits(sy) {
        return None;
    }
    let sx = (b.xs[ORIGIN] as i32).wrapping_add(ratio(x, &b.xs, rh, rl)?);
    if !fits(sx) {
        return None;
    }
    Some(CachedVertex {
        z: sz,
        xy: XyWord::new(sx as i16, sy as i16),
    })
}

/// Writes the entries of `positions` into `out` from the first on, up to the first
/// position [`place_v6m_portable`] does not place, and returns how many it wrote (at
/// most the shorter length; the entry after those may be written in part, for the
/// caller to write). On ARMv6-M the assembly loop; elsewhere the twin.
#[inline]
pub(crate) fn place_run_v6m(
    b: &mut PlaceV6m<'_>,
    positions: &[[i16; 3]],
    out: &mut [CachedVertex],
) -> usize {
    let n = positions.len().min(out.len());
    if n == 0 {
        return 0;
    }
    #[cfg(all(zraster_thumb, zraster_armv6m))]
    {
        let start = out.as_mut_ptr().cast::<u32>();
        // SAFETY: the loop reads the block (`repr(C)`, 64 bytes, 4-aligned) and the rows
        // it borrows (96 bytes) and writes the block's hint words, reads one position a
        // turn (three halfwords, 2-aligned as `[i16; 3]` is) from `positions`' start and
        // writes one entry a turn (a word and two halfwords, 4-aligned as
        // `CachedVertex` is; any bits are a valid entry) from `out`'s start, and stops
        // when the entry pointer reaches `start + n` (n ≥ 1, at most either length) or
        // at a position it does not place: n turns at most, every access inside the
        // slices. See `zraster_place_v6m` for its registers.
        let end = unsafe { zraster_place_v6m(b, positions.as_ptr(), start, start.add(2 * n)) };
        return (end as usize - start as usize) / 8;
    }
    #[allow(unreachable_code)]
    place_run_portable(b, positions, out)
}

/// [`place_run_v6m`] by its twin.
fn place_run_portable(
    b: &mut PlaceV6m<'_>,
    positions: &[[i16; 3]],
    out: &mut [CachedVertex],
) -> usize {
    for (i, (p, e)) in positions.iter().zip(out.iter_mut()).enumerate() {
        match place_v6m_portable(b, p) {
            Some(v) => *e = v,
            None => return i,
        }
    }
    positions.len().min(out.len())
}

#[cfg(all(zraster_thumb, zraster_armv6m))]
extern "C" {
    /// [`place_run_v6m`]'s loop, a whole function in `global_asm!`: block `b`, the
    /// positions from `p`, the entries from `out` up to `end` (exclusive, after
    /// `out`); returns where the entries stopped.
    ///
    /// # Safety
    ///
    /// `b` points to a valid block; `p` to at least as many positions as there are
    /// entries from `out` to `end`, all valid.
    fn zraster_place_v6m(
        b: *mut PlaceV6m<'_>,
        p: *const [i16; 3],
        out: *mut u32,
        end: *mut u32,
    ) -> *mut u32;
}

/// One row of the loop: r0 = c₀·x + c₁·y + c₂·z + t, from the row at r7 (advanced),
/// the position in r4–r6; r1–r3 clobbered.
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! place_row {
    () => {
        "ldm r7!, {{r0, r1, r2, r3}}\n\
         muls r0, r4, r0\n\
         muls r1, r5, r1\n\
         muls r2, r6, r2\n\
         adds r0, r0, r1\n\
         adds r0, r0, r2\n\
         adds r0, r0, r3"
    };
}

/// One screen coordinate (the twin's `ratio`, then the origin and `fits`): the
/// operands at r7 (the block for y, plus 24 for x), the coordinate's row value
/// popped, r's halves in r0 (high) and r1 (low); the coordinate in r3. `$org` is the
/// origin's operation (`adds r3, r6, r3` for x, `subs r3, r6, r3` for y), `$fail`
/// where a refusal goes.
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! place_coordinate {
    ($org:literal, $fail:literal) => {
        concat!(
            "ldm r7!, {{r2, r3, r6}}\n",
            "pop {{r4}}\n",
            "asrs r5, r4, #31\n",
            "asrs r4, r4, r2\n",
            "eors r4, r4, r5\n",
            "subs r4, r4, r5\n",
            "movs r2, r4\n",
            "lsrs r2, r2, r3\n",
            "beq 9f\n",
            "b ",
            $fail,
            "\n9:\n",
            "lsls r4, r4, r6\n",
            // P = a₁r₁ + ⌊a₁r₀/2¹⁶⌋ + ⌊a₀r₁/2¹⁶⌋.
            "lsrs r2, r4, #16\n",
            "uxth r4, r4\n",
            "movs r3, r2\n",
            "muls r3, r0, r3\n",
            "muls r2, r1, r2\n",
            "lsrs r2, r2, #16\n",
            "muls r4, r0, r4\n",
            "lsrs r4, r4, #16\n",
            "adds r3, r3, r2\n",
            "adds r3, r3, r4\n",
            // f + 4 = ⌊P·h/2¹⁶⌋ + 2¹³ + 4.
            "ldm r7!, {{r2, r4, r6}}\n",
            "uxth r7, r3\n",
            "lsrs r3, r3, #16\n",
            "muls r3, r2, r3\n",
            "muls r7, r2, r7\n",
            "lsrs r7, r7, #16\n",
            "adds r3, r3, r7\n",
            "adds r3, r3, r4\n",
            "lsls r7, r3, #18\n",
            "lsrs r7, r7, #20\n",
            "bne 9f\n",
            "b ",
            $fail,
            "\n9:\n",
            "lsrs r3, r3, #14\n",
            "eors r3, r3, r5\n",
            "subs r3, r3, r5\n",
            $org,
            "\n",
            // |c| < 2¹⁴: c + 16383 ≤ 32766 unsigned.
            "ldr r4, ={k}\n",
            "adds r2, r3, r4\n",
            "lsls r4, r4, #1\n",
            "cmp r2, r4\n",
            "bls 9f\n",
            "b ",
            $fail,
            "\n9:"
        )
    };
}

// SAFETY (for `place_run_v6m`): the loop reads the block through r12 (64 bytes: the
// operands at 0..48, the rows' address, the hint, 14 − sh, e) and the rows through
// r8, that address (96 bytes by LDM), and writes only the block's shifts, hint and
// 14 − sh (0..12, 24..36, 52, 56) on a search; reads three halfwords at r9
// and writes the entry at r10 a turn (its depth word, then the halves of y and x), r9
// advancing 6 and r10 8, and stops when r10 reaches r11 (checked after each entry; the
// caller passes end > out) or at an entry it does not place (r10 still below r11; that
// entry may hold its depth and y). It reads RECIP16 at an index below 512. The stack: r4–r7, lr and
// r8–r11 saved and restored as AAPCS wants; a turn pushes up to five row values and
// pops them (a refusal drops what is left by the label it takes).
#[cfg(all(zraster_thumb, zraster_armv6m))]
core::arch::global_asm!(
    ".pushsection .text.zraster_place_v6m,\"ax\",%progbits",
    ".balign 4",
    ".global zraster_place_v6m",
    ".hidden zraster_place_v6m",
    ".type zraster_place_v6m, %function",
    ".thumb_func",
    "zraster_place_v6m:",
    "push {{r4, r5, r6, r7, lr}}",
    "mov r4, r8",
    "mov r5, r9",
    "mov r6, r10",
    "mov r7, r11",
    "push {{r4, r5, r6, r7}}",
    "mov r12, r0",
    "ldr r4, [r0, #48]",
    "mov r8, r4",
    "mov r9, r1",
    "mov r10, r2",
    "mov r11, r3",
    "2:",
    "mov r7, r9",
    "ldrh r4, [r7, #0]",
    "sxth r4, r4",
    "ldrh r5, [r7, #2]",
    "sxth r5, r5",
    "ldrh r6, [r7, #4]",
    "sxth r6, r6",
    "adds r7, #6",
    "mov r9, r7",
    "mov r7, r8",
    // x, y, z high, w high, z low pushed; w low in r0.
    place_row!(),
    "push {{r0}}",
    place_row!(),
    "push {{r0}}",
    place_row!(),
    "push {{r0}}",
    place_row!(),
    "push {{r0}}",
    place_row!(),
    "push {{r0}}",
    place_row!(),
    "pop {{r1, r2, r3}}",
    // r0 = w low, r1 = z low, r2 = w high, r3 = z high; y, x on the stack. Then
    // r2 = wt, r3 = zt, r0 and r1 the low 14 bits of w and z.
    "asrs r4, r0, #14",
    "adds r2, r2, r4",
    "lsls r0, r0, #18",
    "lsrs r0, r0, #18",
    "asrs r4, r1, #14",
    "adds r3, r3, r4",
    "lsls r1, r1, #18",
    "lsrs r1, r1, #18",
    // wt ≥ 2¹⁷ (or negative), zt + wt > 0 (the sum's true sign), zt < wt − 1.
    "lsrs r4, r2, #17",
    "bne 9f",
    "b 8f",
    "9:",
    "adds r5, r3, r2",
    "bgt 9f",
    "b 8f",
    "9:",
    "subs r6, r2, #1",
    "cmp r3, r6",
    "blt 9f",
    "b 8f",
    "9:",
    // (wt >> 17) >> (sh − 1) = 1 for the hint's sh, else the search.
    "mov r7, r12",
    "ldr r6, [r7, #52]",
    "lsrs r4, r4, r6",
    "cmp r4, #1",
    "beq 3f",
    "b 5f",
    // un = (ut << up) + ((zl + wl) >> sh), wn = (wt << up) + (wl >> sh).
    "3:",
    "ldr r3, [r7, #56]",
    "adds r6, #1",
    "adds r1, r1, r0",
    "lsrs r1, r1, r6",
    "lsls r5, r5, r3",
    "adds r5, r5, r1",
    "lsls r2, r2, r3",
    "lsrs r0, r0, r6",
    "adds r1, r2, r0",
    "lsls r4, r1, #2",
    "bne 9f",
    "b 8f",
    "9:",
    // r1 = wn, r5 = un. The reciprocal: the table, one Newton step, a correction.
    // The table's entry 512 + d's bits 29..21 less 512, by an address 1,024 bytes
    // below the table (d < 2³¹).
    "lsrs r0, r1, #21",
    "lsls r0, r0, #1",
    "ldr r2, ={recip16} - 1024",
    "ldrh r2, [r2, r0]",
    "lsrs r0, r1, #15",
    "adds r0, r0, #1",
    "ldr r3, =0x80000000",
    "movs r4, r0",
    "muls r4, r2, r4",
    "subs r4, r3, r4",
    "lsrs r4, r4, #7",
    "muls r4, r2, r4",
    "lsrs r4, r4, #24",
    "adds r2, r2, r4",
    "movs r4, r0",
    "muls r4, r2, r4",
    "subs r4, r3, r4",
    "cmp r4, r0",
    "movs r4, #0",
    "adcs r2, r2, r4",
    // Step 2: y = 8y + ⌊y·⌊e/2¹⁶⌋/2²⁷⌋, e = −d·y.
    "movs r4, r1",
    "muls r4, r2, r4",
    "rsbs r4, r4, #0",
    "lsrs r4, r4, #16",
    "muls r4, r2, r4",
    "lsrs r4, r4, #27",
    "lsls r2, r2, #3",
    "adds r2, r2, r4",
    // Step 3, then the correction by the remainder.
    "movs r4, r1",
    "muls r4, r2, r4",
    "rsbs r4, r4, #0",
    "lsrs r0, r2, #3",
    "lsrs r3, r4, #16",
    "muls r3, r0, r3",
    "uxth r4, r4",
    "muls r4, r0, r4",
    "lsrs r4, r4, #16",
    "adds r3, r3, r4",
    "lsrs r3, r3, #17",
    "lsls r2, r2, #13",
    "adds r2, r2, r3",
    "movs r4, r1",
    "muls r4, r2, r4",
    "rsbs r4, r4, #0",
    "cmp r4, r1",
    "movs r4, #0",
    "adcs r2, r2, r4",
    // r in r2: its halves in r0 (high), r1 (low). The depth: q30 = the rounded high
    // word of un·r.
    "lsrs r0, r2, #16",
    "uxth r1, r2",
    "lsrs r3, r5, #16",
    "uxth r4, r5",
    "movs r6, r3",
    "muls r6, r1, r6",
    "movs r7, r4",
    "muls r7, r0, r7",
    "muls r3, r0, r3",
    "muls r4, r1, r4",
    "lsrs r4, r4, #16",
    "uxth r5, r6",
    "adds r4, r4, r5",
    "uxth r5, r7",
    "adds r4, r4, r5",
    "lsrs r5, r6, #16",
    "adds r3, r3, r5",
    "lsrs r5, r7, #16",
    "adds r3, r3, r5",
    "ldr r5, =0x8000",
    "adds r4, r4, r5",
    "lsrs r4, r4, #16",
    "adds r3, r3, r4",
    // sz = 2·q30 − ⌊(q30 + 2¹⁴ − 1)/2¹⁵⌋, or MAX_DEPTH where q30 > 2³¹ (sz grows with
    // q30, and is MAX_DEPTH at 2³¹; q30 ≥ 1 as un·r ≥ 2³¹), into the entry.
    "subs r4, r3, #1",
    "bpl 1f",
    "ldr r3, ={max_depth}",
    "b 4f",
    "1:",
    "ldr r4, ={k}",
    "adds r4, r4, r3",
    "lsrs r4, r4, #15",
    "subs r4, r3, r4",
    "adds r3, r3, r4",
    "4:",
    "mov r7, r10",
    "str r3, [r7, #0]",
    // y, then x, each into its half of the entry's second word.
    "mov r7, r12",
    place_coordinate!("subs r3, r6, r3", "7f"),
    "mov r7, r10",
    "strh r3, [r7, #6]",
    "mov r7, r12",
    "adds r7, #24",
    place_coordinate!("adds r3, r6, r3", "6f"),
    "mov r7, r10",
    "strh r3, [r7, #4]",
    "adds r7, #8",
    "mov r10, r7",
    "cmp r10, r11",
    "beq 6f",
    "b 2b",
    // The search: sh − 1 = ⌊log₂(wt/2¹⁷)⌋ and up = 14 − sh, then the shifts for
    // k = sh − e.
    "5:",
    "lsrs r4, r2, #17",
    "movs r6, #0",
    "lsrs r3, r4, #8",
    "beq 1f",
    "movs r4, r3",
    "adds r6, #8",
    "1:",
    "lsrs r3, r4, #4",
    "beq 1f",
    "movs r4, r3",
    "adds r6, #4",
    "1:",
    "lsrs r3, r4, #2",
    "beq 1f",
    "movs r4, r3",
    "adds r6, #2",
    "1:",
    "lsrs r3, r4, #1",
    "beq 1f",
    "adds r6, #1",
    "1:",
    "str r6, [r7, #52]",
    "movs r3, #13",
    "subs r3, r3, r6",
    "str r3, [r7, #56]",
    "ldr r3, [r7, #60]",
    "subs r4, r6, r3",
    "adds r4, #1",
    "bmi 1f",
    // k ≥ 0: right by k, the magnitude below 2³¹, left by 0 (y's at 0, x's at 24).
    "str r4, [r7, #0]",
    "str r4, [r7, #24]",
    "movs r4, #31",
    "str r4, [r7, #4]",
    "str r4, [r7, #28]",
    "movs r4, #0",
    "str r4, [r7, #8]",
    "str r4, [r7, #32]",
    "b 3b",
    "1:",
    // k < 0: right by 0, the magnitude below 2^(31 + k), left by −k.
    "rsbs r4, r4, #0",
    "str r4, [r7, #8]",
    "str r4, [r7, #32]",
    "movs r3, #31",
    "subs r3, r3, r4",
    "str r3, [r7, #4]",
    "str r3, [r7, #28]",
    "movs r4, #0",
    "str r4, [r7, #0]",
    "str r4, [r7, #24]",
    "b 3b",
    // Refusals: with y and x on the stack (8), with x (7), with neither (6).
    "8:",
    "add sp, #4",
    "7:",
    "add sp, #4",
    "6:",
    "mov r0, r10",
    "pop {{r4, r5, r6, r7}}",
    "mov r8, r4",
    "mov r9, r5",
    "mov r10, r6",
    "mov r11, r7",
    "pop {{r4, r5, r6, r7, pc}}",
    ".ltorg",
    ".size zraster_place_v6m, . - zraster_place_v6m",
    ".popsection",
    recip16 = sym RECIP16,
    k = const (1 << 14) - 1,
    max_depth = const MAX_DEPTH,
);

/// The vertex loop (`place_run_v6m`) against its twin on this target: 24 transforms of
/// the kind `FixedTransform` makes for a perspective camera (random coefficients, w
/// near 2⁴² or anywhere within ±2⁴⁰, x and y scaled by 2¹⁰ to 2¹⁶ to reach ±0.4·w to
/// ±24·w, viewports of several sizes and offsets), each over `n` random positions in
/// runs of eight, each run from where the last stopped. Returns the number of
/// positions whose entry or stop, or whose block afterwards, differs.
pub fn check_place_v6m_kernel(n: usize) -> usize {
    // Only the assembly needs checking (the host tests run the twin through it).
    if !PLACE_V6M_KERNEL {
        return 0;
    }
    place_v6m_check(n).0
}

/// [`check_place_v6m_kernel`]'s cases: the differences, the entries placed and the
/// stops.
fn place_v6m_check(n: usize) -> (usize, usize, usize) {
    let mut rnd = super::xorshift32(0x2545_f491_u32);
    let (mut bad, mut placed, mut stops) = (0, 0, 0);
    let mut run = [[0i16; 3]; 8];
    let mut got = [CachedVertex::EMPTY; 8];
    let mut want = [CachedVertex::EMPTY; 8];
    let mut rows = [[0; 4]; 6];
    for case in 0..24u32 {
        // A value within ±2^bits (c₀, c₁ of x and y within ±16383).
        let mut within = |bits: u32| (rnd() as i32) >> (31 - bits);
        for (r, row) in rows.iter_mut().enumerate() {
            let (c, t) = match r {
                0 | 1 => ([within(14), within(14), within(14)], within(20)),
                // z and w high sums: w about 2²⁸ (2⁴² in all), z a part of it.
                2 => ([within(11), within(11), within(11)], within(27)),
                3 if case % 4 == 3 => ([within(11), within(11), within(11)], within(26)),
                3 => ([within(11), within(11), within(11)], (1 << 28) + within(26)),
                // The low sums: coefficients and translation in [0, 2¹⁴).
                _ => ([0; 3].map(|_| within(14) & 0x3fff), within(14) & 0x3fff),
            };
            let [c0, c1, c2] = c;
            *row = [c0, c1, c2, t];
        }
        let half = match case % 4 {
            0 => [2560, 1920],
            1 => [1920, 1920],
            2 => [512, 384],
            _ => [1 << 16, 6144],
        };
        let e = match case % 5 {
            0 => 10,
            1 => 12,
            2 => 13,
            3 => 14,
            _ => 16,
        };
        let org = [(case % 3) as i32 * 592 - 640, (case % 5) as i32 * 176];
        let mut mine = PlaceV6m::new(&rows, e, half, org, 1 + case % 14);
        let mut twin = mine;
        for _ in 0..n.div_ceil(8) {
            for p in &mut run {
                *p = [rnd() as i16, rnd() as i16, rnd() as i16];
            }
            let mut at = 0;
            while let (Some(p), Some(g), Some(w)) =
                (run.get(at..), got.get_mut(at..), want.get_mut(at..))
            {
                if p.is_empty() {
                    break;
                }
                let k = place_run_v6m(&mut mine, p, g);
                let j = place_run_portable(&mut twin, p, w);
                let same = g.iter().zip(w.iter()).take(k.min(j));
                bad += usize::from(k != j)
                    + same.filter(|(g, w)| g != w).count()
                    + usize::from(mine != twin);
                placed += j;
                stops += usize::from(j < p.len());
                // Past the stop (the caller's exact path takes that one).
                at += j + 1;
            }
        }
    }
    (bad, placed, stops)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table's first step is ⌊2³¹/(v + 1)⌋ for every v (its products within
    /// `u32`), and the reciprocal ⌊2⁶²/d⌋ at every step's edges and 10⁷ random d;
    /// `ZRASTER_EXHAUSTIVE=1` checks every d (2³⁰ of them; in a release build, some
    /// seconds).
    #[test]
    fn table_reciprocal_is_exact() {
        for v in 1u32 << 15..1 << 16 {
            let w = v + 1;
            let t = u64::from(RECIP16[((v >> 6) & 0x1ff) as usize]);
            assert!(t * u64::from(w) <= 1 << 31, "v {v}");
            let e = (1u64 << 31) - t * u64::from(w);
            assert!(t * (e >> 7) < 1 << 32, "v {v}");
            assert_eq!(recip31_table(v), (1 << 31) / w, "v {v}");
            for d in [v << 15, (v << 15) + 1, (v << 15) + (1 << 14), (w << 15) - 1] {
                if d > 1 << 30 && d < 1 << 31 {
                    assert_eq!(u64::from(recip62_low(d)), (1 << 62) / u64::from(d));
                }
            }
        }
        let mut rnd = crate::testing::xorshift64(0x9e37_79b9_7f4a_7c15);
        for _ in 0..crate::num::tests::fast_cases() {
            let d = (rnd() as u32 >> 1 | 1 << 30).max((1 << 30) + 1);
            assert_eq!(u64::from(recip62_low(d)), (1u64 << 62) / u64::from(d));
        }
        if std::env::var_os("ZRASTER_EXHAUSTIVE").is_some() {
            for d in (1u32 << 30) + 1..1 << 31 {
                assert_eq!(u64::from(recip62_low(d)), (1u64 << 62) / u64::from(d));
            }
        }
    }

    #[test]
    fn place_v6m_kernel_is_its_twin() {
        let (bad, placed, stops) = place_v6m_check(2000);
        assert_eq!(bad, 0);
        assert!(
            placed > 10_000 && stops > 2_000,
            "{placed} placed, {stops} stops"
        );
    }
}
