//! Arithmetic for ARMv6-M (Cortex-M0/M0+), which has no divide instruction, no
//! 32×32→64-bit multiply and only library calls for 64-bit shifts: each function here
//! builds the operation from 32-bit instructions. Plain Rust, so the host tests check
//! each against the operation it replaces.
// Indexing into fixed tables by values masked below their length: it cannot panic.
#![allow(clippy::indexing_slicing)]

use super::{by_digits, mul_wide};

/// The reciprocal form of [`div_floor_pair`]; `None` outside its range.
#[inline]
pub(crate) fn div_floor_pair_recip(n1: i64, n2: i64, d: i64) -> Option<(i64, i64)> {
    let (n1, n2, d) = if d < 0 { (-n1, -n2, -d) } else { (n1, n2, d) };
    let (m1, m2) = (n1.unsigned_abs(), n2.unsigned_abs());
    if d == 0 || d >= 1 << 16 || m1 >= 1 << 48 || m2 >= 1 << 48 {
        return None;
    }
    let d32 = d as u32;
    let r = recip32_small(d32); // ⌊(2³² − 1)/d⌋
    let one = |n: i64, m: u64| {
        let (q, r0) = by_digits(m, |x| divrem_by_recip(x, d32, r));
        let q = q as i64;
        // Truncated |n| / d; floor for negative n rounds away from zero when inexact.
        if n >= 0 {
            q
        } else if r0 == 0 {
            -q
        } else {
            -q - 1
        }
    };
    Some((one(n1, m1), one(n2, m2)))
}

/// `(⌊n₁/d⌋, ⌊n₂/d⌋)` for `0 < d < 2¹⁶` and `|n| < 2³¹`, by one reciprocal of `d`
/// ([`recip32_small`]) and a multiply each: a negative `n` by the flip
/// `⌊n/d⌋ = !⌊!n/d⌋` (`!n = −n − 1 ≥ 0`), so every quotient is unsigned and needs no
/// remainder test.
#[inline(always)]
pub(crate) fn floor_div32_pair_small(n1: i32, n2: i32, d: u32) -> (i32, i32) {
    let r = recip32_small(d);
    let one = |n: i32| {
        let s = n >> 31;
        (divrem_by_recip((n ^ s) as u32, d, r).0 as i32) ^ s
    };
    (one(n1), one(n2))
}

/// ⌊(2³² − 1)/d⌋ for 1 ≤ d < 2¹⁶ without a division instruction (on ARMv6-M the
/// library division costs about 200 instructions, this about 45): d normalised to
/// dn = d·2^s in [2¹⁵, 2¹⁶) (s from a table of leading zeros: ARMv6-M has no CLZ), a
/// guess below 2³²/d from a table of dn's leading 9 bits (relative error under 2⁻⁹),
/// and two Newton steps from below (under 2⁻¹⁸, then exact): no fix-up by the
/// remainder is needed, as the test of every d shows.
#[inline]
pub(crate) fn recip32_small(d: u32) -> u32 {
    if d == 0 || d >= 1 << 16 {
        return u32::MAX / d.max(1);
    }
    let lz8 = |b: u32| u32::from(LEADING_ZEROS8.get(b as usize).copied().unwrap_or(0));
    let s = if d >= 1 << 8 { lz8(d >> 8) } else { 8 + lz8(d) };
    let dn = d << s;
    // 2³²/d = 2^(s + 1) · 2³¹/dn, and the table holds 2²⁵ over the top of dn's part of
    // [2¹⁵, 2¹⁶), a little below 2¹⁵ · 2³¹/dn: so the guess t·2^(s + 1) is below 2³²/d.
    let i = ((dn >> 6) & 0x1ff) as usize;
    let t = u32::from(RECIP16.get(i).copied().unwrap_or(0x8000));
    // The first Newton step on t's 16 bits, with x = t·2^(s + 1): e = 2³² − d·x =
    // 2³² − 2·dn·t (dn·t < 2³¹: the guess is below 2³²/d), and x·e/2³² =
    // t·e/2^(31 − s). e < 2²³ + 2¹⁷, so t·⌊e/2⁷⌋ < 2³² (at most 2³² − 2¹⁶, over every
    // d), and x = (t·2¹⁶ + ⌊t·⌊e/2⁷⌋/2⁹⌋) >> (15 − s) (below 2³²) falls short of the
    // exact step by the dropped bits alone: x stays below 2³²/d. One product fewer
    // than the full step, in 32 bits (the rows kernel's set-up does the same).
    let e = (2 * dn * t).wrapping_neg();
    let x = ((t << 16) + ((t * (e >> 7)) >> 9)) >> (15 - s);
    // Now e is about 2³²·2⁻¹⁸ + d (at most 68,736 over all d), and ⌊x·e/2³²⌋ is
    // ⌊(xh·e + ⌊xl·e/2¹⁶⌋)/2¹⁶⌋ with x = xh·2¹⁶ + xl: two 32-bit products, which stay
    // below 2³² for every d (xh < 2¹⁶/d; the largest term is 3.2·10⁹). The result
    // is ⌊(2³² − 1)/d⌋ itself for every d (`small_reciprocal_is_exact_for_every_divisor`),
    // so the rows kernel's set-up, which does the same, needs no fix-up either.
    let e = d.wrapping_mul(x).wrapping_neg();
    x + (((x >> 16) * e + (((x & 0xffff) * e) >> 16)) >> 16)
}

/// ⌊2²⁵ / (513 + i)⌋: 2²⁵ over the top of the i-th of 512 equal parts of [2⁹, 2¹⁰)
/// (dn's leading 9 bits read as 512 + i), which is below 2¹⁶ · 2⁹/top. Worked out at
/// compile time.
#[allow(clippy::indexing_slicing)] // evaluated at compile time: a bad index fails the build
pub(crate) static RECIP16: [u16; 512] = {
    let mut t = [0u16; 512];
    let mut i = 0;
    while i < 512 {
        t[i] = ((1u32 << 25) / (513 + i as u32)) as u16;
        i += 1;
    }
    t
};

/// Leading zeros of a byte (8 for 0).
#[allow(clippy::indexing_slicing)] // evaluated at compile time: a bad index fails the build
pub(crate) static LEADING_ZEROS8: [u8; 256] = {
    let mut t = [0u8; 256];
    let mut i = 0;
    while i < 256 {
        t[i] = (i as u8).leading_zeros() as u8;
        i += 1;
    }
    t
};

/// `(x / d, x % d)` given `r = ⌊(2³² − 1)/d⌋`, `d > 0`: `x·r/2³²` is at most `x/d` and
/// less than 3 below it, so the remainder is never negative and at most three steps
/// bring it below `d`.
#[inline(always)]
pub(crate) fn divrem_by_recip(x: u32, d: u32, r: u32) -> (u32, u32) {
    let mut q = (mul_wide(x, r) >> 32) as u32;
    let mut rem = x.wrapping_sub(q.wrapping_mul(d)); // x − q·d, in 0..x
    while rem >= d {
        q += 1;
        rem -= d;
    }
    (q, rem)
}

/// The three-multiply form of [`mul_i64_i32`], for `|b| < 2¹⁶`.
#[inline(always)]
pub(crate) fn mul_small_parts(a: i64, b: i32) -> i64 {
    let ub = b.unsigned_abs();
    let (al, ah) = (a as u32, (a as u64 >> 32) as u32);
    // al·ub below 2⁴⁸ from two 16×16-bit halves; ah·ub modulo 2³² is all that stays
    // of the high half modulo 2⁶⁴.
    let low = (u64::from((al >> 16) * ub) << 16) + u64::from((al & 0xffff) * ub);
    let p = low.wrapping_add(u64::from(ah.wrapping_mul(ub)) << 32) as i64;
    if b < 0 {
        p.wrapping_neg()
    } else {
        p
    }
}

/// [`bits_beyond_31`]: the bit length of the high half by two comparisons and a byte
/// table (the projection's w has at most 13 bits there).
#[inline]
pub(crate) fn bits_beyond_31_parts(w: i64) -> u32 {
    let (lo, hi) = (w as u32, (w as u64 >> 32) as u32);
    if hi == 0 {
        return lo >> 31;
    }
    // 32 + bits(hi) bits in all.
    let (mut x, mut b) = (hi, 1);
    if x >> 16 != 0 {
        x >>= 16;
        b += 16;
    }
    if x >> 8 != 0 {
        x >>= 8;
        b += 8;
    }
    b + 8 - u32::from(LEADING_ZEROS8.get(x as usize).copied().unwrap_or(0))
}

/// [`shl64`] from 32-bit halves.
#[inline]
pub(crate) fn shl64_parts(v: i64, s: u32) -> i64 {
    if s == 0 {
        return v;
    }
    let (lo, hi) = (v as u32, (v as u64 >> 32) as u32);
    let (hi, lo) = ((hi << s) | (lo >> (32 - s)), lo << s);
    (u64::from(hi) << 32 | u64::from(lo)) as i64
}

/// [`shr64`] from 32-bit halves.
#[inline]
pub(crate) fn shr64_parts(v: i64, s: u32) -> i64 {
    if s == 0 {
        return v;
    }
    let (lo, hi) = (v as u32, (v >> 32) as i32);
    let (hi, lo) = (hi >> s, (lo >> s) | ((hi as u32) << (32 - s)));
    ((hi as u64) << 32 | u64::from(lo)) as i64
}

/// The four-product form of [`mul_wide`].
#[inline]
pub(crate) fn mul_wide_parts(a: u32, b: u32) -> u64 {
    let (a1, a0) = (a >> 16, a & 0xffff);
    let (b1, b0) = (b >> 16, b & 0xffff);
    let (mid, carry) = (a1 * b0).overflowing_add(a0 * b1); // each < 2³²; carry is 2⁴⁸
    let (low, c) = (a0 * b0).overflowing_add(mid << 16);
    let high = a1 * b1 + (mid >> 16) + (u32::from(carry) << 16) + u32::from(c);
    (u64::from(high) << 32) | u64::from(low)
}

/// [`mul_wide`] for `a < 2¹⁶`: two products, `b`'s halves times `a`.
#[inline(always)]
pub(crate) fn mul_narrow_parts(a: u32, b: u32) -> u64 {
    (u64::from((b >> 16) * a) << 16) + u64::from((b & 0xffff) * a)
}

/// `(n / d, n % d)` for `d > 0` by restoring shift-and-subtract division, one step per
/// quotient bit: the divisor is doubled while it stays at most `n / 2` (so it never
/// overflows), then halved back down, subtracting where it fits.
#[inline]
pub(crate) fn udivrem(n: u32, d: u32) -> (u32, u32) {
    if n < d || d == 0 {
        return (0, n);
    }
    let (mut dd, mut bit) = (d, 1u32);
    while dd <= n >> 1 {
        dd <<= 1;
        bit <<= 1;
    }
    let (mut q, mut r) = (0, n);
    loop {
        if r >= dd {
            r -= dd;
            q |= bit;
        }
        if bit == 1 {
            return (q, r);
        }
        dd >>= 1;
        bit >>= 1;
    }
}

/// `(n / d, n % d)` in 128 bits for `d > 0`, by long division a bit at a time: the
/// remainder takes `n`'s bits from the top as they shift out, the quotient's shift in
/// behind them (one loop for both: LLVM expands a 128-bit division and remainder
/// inline on 32-bit Arm, each by its own loop, some 500 bytes each).
#[inline(never)]
pub(crate) fn udivrem_wide(n: u128, d: u128) -> (u128, u128) {
    let (mut q, mut r, mut steps) = (n, 0u128, 128);
    // A word of n at a time while r stays below d: 32 zero quotient bits each (the
    // bit loop then runs about as many times as the quotient has bits).
    while steps > 0 && r >> 96 == 0 && (r << 32 | q >> 96) < d {
        r = r << 32 | q >> 96;
        q <<= 32;
        steps -= 32;
    }
    for _ in 0..steps {
        // r < d before the step, so 2r + 1 < 2d: when r's top bit shifts out, the
        // remainder is above d.
        let top = r >> 127 != 0;
        r = r << 1 | q >> 127;
        q <<= 1;
        if top || r >= d {
            r = r.wrapping_sub(d);
            q |= 1;
        }
    }
    (q, r)
}

/// [`div_floor_wide`] through [`udivrem_wide`], for `d > 0`.
#[inline]
pub(crate) fn div_floor_wide_soft(n: i128, d: i128) -> i128 {
    let (q, r) = udivrem_wide(n.unsigned_abs(), d as u128);
    let q = q as i128;
    match (n < 0, r == 0) {
        (false, _) => q,
        (true, true) => q.wrapping_neg(),
        (true, false) => q.wrapping_neg() - 1,
    }
}

/// [`udivrem`] out of line (for [`div_floor`]'s two digits: one copy of the loop).
#[inline(never)]
pub(crate) fn udivrem_call(n: u32, d: u32) -> (u32, u32) {
    udivrem(n, d)
}

/// [`floor_div32`] through [`udivrem`]. For `n = i32::MIN` the quotient 2³¹ wraps to
/// `i32::MIN`, which negated is itself: still exact.
#[inline]
pub(crate) fn floor_div32_soft(n: i32, d: i32) -> i32 {
    let (q, r) = udivrem(n.unsigned_abs(), d as u32);
    let q = q as i32;
    match (n < 0, r == 0) {
        (false, _) => q,
        (true, true) => q.wrapping_neg(),
        (true, false) => q.wrapping_neg() - 1,
    }
}

/// `⌊(a·h·r + 2⁶¹) / 2⁶²⌋` (the projection's rounded `a·h/d` through `r = ⌊2⁶²/d⌋`) in
/// five 16 × 16-bit products, or `None` when that cannot be told from them without the
/// exact 64-bit form. For `a < 2³¹`, `r < 2³²` and `1 ≤ h ≤ 2¹⁶`; the result is
/// then below 2¹⁸.
///
/// With `a = a₁·2¹⁶ + a₀` and `r = r₁·2¹⁶ + r₀`, `V = a·r/2³²` lies in `[P, P + 3)` for
/// `P = a₁r₁ + ⌊a₁r₀/2¹⁶⌋ + ⌊a₀r₁/2¹⁶⌋` (three dropped fractions, each below 1; and
/// `P ≤ V < 2³¹`). With `P = p₁·2¹⁶ + p₀`, `S = p₁h + ⌊p₀h/2¹⁶⌋ = ⌊P·h/2¹⁶⌋`
/// (`p₁h < 2³¹`, `p₀h < 2³²`), so `Z = V·h/2¹⁶` lies in `[S, S + 1 + 3h/2¹⁶) ⊆ [S, S + 4)`.
/// The result is `⌊(Z + 2¹³)/2¹⁴⌋`: with `F = S + 2¹³` (below 2³²) it is `⌊F/2¹⁴⌋`
/// unless a multiple of 2¹⁴ lies in `(F, F + 4)`, that is unless `F mod 2¹⁴ > 2¹⁴ − 4`
/// (then `None`: 3 values in 16,384).
#[inline(always)]
pub(crate) fn scaled_ratio_parts(a: u32, r: u32, h: u32) -> Option<u32> {
    let (a1, a0) = (a >> 16, a & 0xffff);
    let (r1, r0) = (r >> 16, r & 0xffff);
    let p = a1 * r1 + ((a1 * r0) >> 16) + ((a0 * r1) >> 16);
    let f = (p >> 16) * h + (((p & 0xffff) * h) >> 16) + (1 << 13);
    if f & 0x3fff > (1 << 14) - 4 {
        return None;
    }
    Some(f >> 14)
}
