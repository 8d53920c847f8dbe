//! Fixed-point conventions and the few integer helpers the rasterizer needs.
//!
//! # Screen coordinates: 28.4
//! `x` and `y` are `i32` in units of 1/16 pixel ([`SUBPIXEL_BITS`] = 4). The pixel
//! with integer coordinates (i, j) covers `[16i, 16i + 16) × [16j, 16j + 16)` and is
//! sampled at its centre `(16i + 8, 16j + 8)`. Accepted vertices satisfy
//! `|x|, |y| ≤ GUARD_BAND` = 2²⁴ (±1,048,576 pixels), so every coordinate difference is
//! below 2²⁵ and every product of two differences below 2⁵¹: edge functions and twice
//! the signed area are exact in `i64`.
//!
//! # Depth: 16.16
//! A vertex's depth is a `u32` with 16 fractional bits, at most [`MAX_DEPTH`]
//! (65535.0). The stored Z-buffer value is the depth rounded to the nearest integer.
//! Depth differences are below 2³², so the plane numerators `Δz·Δy` are below 2⁵⁸ and
//! `16·Δz·Δy` below 2⁶²: exact in `i64`.
//!
//! In the pixel loop depth is a `u32` accumulator `z·2¹⁶ + 2¹⁵` (the bias rounds, and
//! keeps the value away from 0 and 2³²): one wrapping add per pixel. Rounding the slope
//! to 16.16 costs less than 1/65536 per pixel stepped, so over a row of at most
//! [`MAX_DIMENSION`](crate::MAX_DIMENSION) = 8192 pixels the drift is below 2¹³ (1/8 of
//! a depth unit), far inside the bias margin of 2¹⁵: the accumulator never wraps.

/// Fractional bits of a screen coordinate.
pub const SUBPIXEL_BITS: u32 = 4;
/// One pixel in screen-coordinate units (16).
pub const SUBPIXEL: i32 = 1 << SUBPIXEL_BITS;
/// The largest magnitude of an accepted screen coordinate, in 1/16 pixel (2²⁴).
pub const GUARD_BAND: i32 = 1 << 24;
/// The largest vertex depth, 65535.0 in 16.16.
pub const MAX_DEPTH: u32 = 65535 << 16;

/// ⌊n / d⌋ for `d ≠ 0`, exact, avoiding 64-bit division where it can: with 32-bit
/// divisions (one `UDIV` each on a Cortex-M3/M4, a short library call on an M0+)
/// when both fit in 32 bits, or when `|d| < 2¹⁶` and `|n| < 2⁴⁸` (two 16-bit "digits"
/// of long division). Small triangles, the common case, always take those paths.
#[inline]
pub(crate) fn div_floor(n: i64, d: i64) -> i64 {
    let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
    if let (Ok(n), Ok(d)) = (i32::try_from(n), i32::try_from(d)) {
        return i64::from(floor_div32(n, d));
    }
    let m = n.unsigned_abs();
    if d < 1 << 16 && m < 1 << 48 {
        let d32 = d as u32;
        // On ARMv6-M by shift and subtract (the digits are usually a few bits).
        let (q, r0) = by_digits(m, |x| {
            if ARMV6M {
                udivrem(x, d32)
            } else {
                (x / d32, x % d32)
            }
        });
        let q = q as i64;
        // Truncated |n| / d; floor for negative n rounds away from zero when inexact.
        return if n >= 0 {
            q
        } else if r0 == 0 {
            -q
        } else {
            -q - 1
        };
    }
    n.div_euclid(d)
}

/// `(⌊n₁ / d⌋, ⌊n₂ / d⌋)` for `d ≠ 0`, exactly as [`div_floor`] gives them: by the
/// divide instruction on 64-bit hosts; on ARMv6-M, which has no divide instruction,
/// when `|d| < 2¹⁶` and both `|n| < 2⁴⁸` (the depth slopes of every small triangle),
/// by a reciprocal of `d` and each 16-bit digit of the two long divisions by a multiply
/// and at most three corrections, instead of four library divisions; elsewhere by two
/// [`div_floor_signless`]s.
#[inline]
pub(crate) fn div_floor_pair(n1: i64, n2: i64, d: i64) -> (i64, i64) {
    if ARMV6M {
        if let Some(q) = div_floor_pair_recip(n1, n2, d) {
            return q;
        }
    }
    if cfg!(target_pointer_width = "64") {
        // A 64-bit divide instruction (x86-64, AArch64): one each, where the digit
        // method takes about 20 instructions (51 k a bunny frame on x86-64).
        let (n1, n2, d) = if d < 0 { (-n1, -n2, -d) } else { (n1, n2, d) };
        return (n1.div_euclid(d), n2.div_euclid(d));
    }
    (div_floor_signless(n1, d), div_floor_signless(n2, d))
}

/// [`div_floor`] with the sign of `n` folded in rather than tested: for d > 0,
/// ⌊n/d⌋ = −1 − ⌊(−1 − n)/d⌋, so with s = 0 or −1 by n's sign it is s ^ ⌊m/d⌋ for
/// m = n ^ s ≥ 0 — unsigned divisions and no remainder test. (Only for the depth
/// slopes of small triangles: in `div_floor` itself, which the general path inlines,
/// it measured worse.)
#[inline(always)]
fn div_floor_signless(n: i64, d: i64) -> i64 {
    let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
    let sign = n >> 63;
    let m = (n ^ sign) as u64;
    if d > 0 && d < 1 << 16 && m < 1 << 48 {
        let d32 = d as u32;
        return by_digits(m, |x| (x / d32, x % d32)).0 as i64 ^ sign;
    }
    div_floor(n, d)
}

/// The reciprocal form of [`div_floor_pair`]; `None` outside its range.
#[inline]
fn div_floor_pair_recip(n1: i64, n2: i64, d: i64) -> Option<(i64, i64)> {
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

/// `(m / d, m % d)` for `m < 2⁴⁸` and `d < 2¹⁶`, as two 16-bit digits of long division,
/// each by `divrem` (`x ↦ (x / d, x % d)` for a 32-bit `x`): the first digit divides
/// `m / 2¹⁶` (below 2³²), the second its remainder (below `d`) times 2¹⁶ plus the low 16
/// bits, which fits 32 bits.
#[inline(always)]
fn by_digits(m: u64, divrem: impl Fn(u32) -> (u32, u32)) -> (u64, u32) {
    let (q1, r1) = divrem((m >> 16) as u32);
    let (q0, r0) = divrem((r1 << 16) | (m as u32 & 0xffff));
    (u64::from(q1) << 16 | u64::from(q0), r0)
}

/// ⌊(2³² − 1)/d⌋ for 1 ≤ d < 2¹⁶ without a division instruction (on ARMv6-M the
/// library division costs about 200 instructions, this about 60): d normalised to
/// dn = d·2^s in [2¹⁵, 2¹⁶) (s from a table of leading zeros: ARMv6-M has no CLZ), a
/// guess below 2³²/d from a table of dn's leading 9 bits (relative error under 2⁻⁹),
/// two Newton steps from below (under 2⁻¹⁸, then exact for every d), and a fix-up by
/// the remainder that guarantees it. A test checks every d.
#[inline]
pub(crate) fn recip32_small(d: u32) -> u32 {
    if d == 0 || d >= 1 << 16 {
        return u32::MAX / d.max(1);
    }
    let lz8 = |b: u32| u32::from(LEADING_ZEROS8.get(b as usize).copied().unwrap_or(0));
    let s = if d >= 1 << 8 { lz8(d >> 8) } else { 8 + lz8(d) };
    let dn = d << s;
    // 2³²/d = 2^(s + 1) · 2³¹/dn, and the table holds 2²⁵ over the top of dn's part of
    // [2¹⁵, 2¹⁶), a little below 2¹⁵ · 2³¹/dn: so the guess x is below 2³²/d (and 2³²).
    let i = ((dn >> 6) & 0x1ff) as usize;
    let mut x = u32::from(RECIP16.get(i).copied().unwrap_or(0x8000)) << (s + 1);
    // Each step: e = 2³² − d·x > 0 (d·x < 2³², so the wrapping product is exact), and
    // x grows by ⌊x·e/2³²⌋, which is less than 2³²/d − x: x stays below 2³²/d.
    let e = d.wrapping_mul(x).wrapping_neg();
    x += (mul_wide(x, e) >> 32) as u32;
    // Now e is about 2³²·2⁻¹⁸ + d (at most 68,736 over all d), and ⌊x·e/2³²⌋ is
    // ⌊(xh·e + ⌊xl·e/2¹⁶⌋)/2¹⁶⌋ with x = xh·2¹⁶ + xl: two 32-bit products, which stay
    // below 2³² for every d (xh < 2¹⁶/d; the largest term is 3.2·10⁹). Were one to
    // wrap, x would only come out lower, and the fix-up below would repair it.
    let e = d.wrapping_mul(x).wrapping_neg();
    x += ((x >> 16) * e + (((x & 0xffff) * e) >> 16)) >> 16;
    // x ≤ ⌊(2³² − 1)/d⌋ (x < 2³²/d), so the remainder below is exact and never negative.
    let mut rem = u32::MAX - x.wrapping_mul(d);
    while rem >= d {
        x += 1;
        rem -= d;
    }
    x
}

/// ⌊2²⁵ / (513 + i)⌋: 2²⁵ over the top of the i-th of 512 equal parts of [2⁹, 2¹⁰)
/// (dn's leading 9 bits read as 512 + i), which is below 2¹⁶ · 2⁹/top. Worked out at
/// compile time.
#[allow(clippy::indexing_slicing)] // evaluated at compile time: a bad index fails the build
const RECIP16: [u16; 512] = {
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
const LEADING_ZEROS8: [u8; 256] = {
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
fn divrem_by_recip(x: u32, d: u32, r: u32) -> (u32, u32) {
    let mut q = (mul_wide(x, r) >> 32) as u32;
    let mut rem = x.wrapping_sub(q.wrapping_mul(d)); // x − q·d, in 0..x
    while rem >= d {
        q += 1;
        rem -= d;
    }
    (q, rem)
}

/// Whether the target is ARMv6-M (Cortex-M0/M0+), recognised as the Arm profile without
/// 32-bit atomics. It has no divide instruction and no 32×32→64-bit multiply: a division
/// is a library call costing about 130 instructions whatever the operands ([`udivrem`]
/// costs about 7 per quotient bit, and the rasterizer's quotients are mostly a few bits),
/// and a 64-bit product a call costing about 45 ([`mul_wide`] is 4 multiplies inline).
pub(crate) const ARMV6M: bool = cfg!(all(target_arch = "arm", not(target_has_atomic = "32")));

/// `a · b` in 64 bits. On ARMv6-M from four 16×16-bit products, carries added by hand;
/// elsewhere the plain widening multiply (one `UMULL` on a Cortex-M3/M4).
#[inline]
pub(crate) fn mul_wide(a: u32, b: u32) -> u64 {
    if ARMV6M {
        mul_wide_parts(a, b)
    } else {
        u64::from(a) * u64::from(b)
    }
}

/// `a.wrapping_mul(b)`. On ARMv6-M, for `|b| < 2¹⁶` (every use in the rasterizer and
/// the projection but the widest viewports), in three 32-bit multiplies instead of a
/// 64-bit library multiply: `a` in 32-bit halves, `b`'s magnitude in 16 bits.
#[inline]
pub(crate) fn mul_i64_i32(a: i64, b: i32) -> i64 {
    let ub = b.unsigned_abs();
    if !ARMV6M || ub >= 1 << 16 {
        return a.wrapping_mul(i64::from(b));
    }
    mul_small_parts(a, b)
}

/// The three-multiply form of [`mul_i64_i32`], for `|b| < 2¹⁶`.
#[inline]
fn mul_small_parts(a: i64, b: i32) -> i64 {
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

/// `v << s` (wrapping) for `s < 32`. ARMv6-M shifts 64-bit values by a variable
/// amount through library calls; this is four 32-bit shifts inline there.
#[inline]
pub(crate) fn shl64(v: i64, s: u32) -> i64 {
    if ARMV6M && s < 32 {
        shl64_parts(v, s)
    } else {
        v.wrapping_shl(s)
    }
}

/// `v >> s` (arithmetic) for `s < 32`, as [`shl64`].
#[inline]
pub(crate) fn shr64(v: i64, s: u32) -> i64 {
    if ARMV6M && s < 32 {
        shr64_parts(v, s)
    } else {
        v.wrapping_shr(s)
    }
}

/// How many bits `w` has beyond 31 (`w ≥ 0`): the right shift that brings it below 2³¹.
/// On ARMv6-M by comparisons (its leading-zero count is a library call).
#[inline]
pub(crate) fn bits_beyond_31(w: i64) -> u32 {
    if ARMV6M {
        bits_beyond_31_parts(w)
    } else {
        (64 - w.leading_zeros()).saturating_sub(31)
    }
}

/// [`bits_beyond_31`] by a binary search over the high half.
#[inline]
fn bits_beyond_31_parts(w: i64) -> u32 {
    let (lo, hi) = (w as u32, (w as u64 >> 32) as u32);
    if hi == 0 {
        return lo >> 31;
    }
    // 32 + bits(hi) bits in all, bits(x) = b + x after the halvings below.
    let (mut x, mut b) = (hi, 0);
    for k in [16, 8, 4, 2, 1] {
        if x >= 1 << k {
            x >>= k;
            b += k;
        }
    }
    1 + b + x
}

/// [`shl64`] from 32-bit halves.
#[inline]
fn shl64_parts(v: i64, s: u32) -> i64 {
    if s == 0 {
        return v;
    }
    let (lo, hi) = (v as u32, (v as u64 >> 32) as u32);
    let (hi, lo) = ((hi << s) | (lo >> (32 - s)), lo << s);
    (u64::from(hi) << 32 | u64::from(lo)) as i64
}

/// [`shr64`] from 32-bit halves.
#[inline]
fn shr64_parts(v: i64, s: u32) -> i64 {
    if s == 0 {
        return v;
    }
    let (lo, hi) = (v as u32, (v >> 32) as i32);
    let (hi, lo) = (hi >> s, (lo >> s) | ((hi as u32) << (32 - s)));
    ((hi as u64) << 32 | u64::from(lo)) as i64
}

/// The four-product form of [`mul_wide`].
#[inline]
fn mul_wide_parts(a: u32, b: u32) -> u64 {
    let (a1, a0) = (a >> 16, a & 0xffff);
    let (b1, b0) = (b >> 16, b & 0xffff);
    let (mid, carry) = (a1 * b0).overflowing_add(a0 * b1); // each < 2³²; carry is 2⁴⁸
    let (low, c) = (a0 * b0).overflowing_add(mid << 16);
    let high = a1 * b1 + (mid >> 16) + (u32::from(carry) << 16) + u32::from(c);
    (u64::from(high) << 32) | u64::from(low)
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

/// ⌊n / d⌋ in 32 bits for `d > 0` (one division and a correction, inlined: the
/// standard library's `div_euclid` is an out-of-line call on Thumb).
#[inline(always)]
pub(crate) fn floor_div32(n: i32, d: i32) -> i32 {
    if ARMV6M {
        return floor_div32_soft(n, d);
    }
    if cfg!(target_arch = "arm") {
        // One unsigned division, flipping the bits of n before and after when it is
        // negative (for n < 0, ⌊n/d⌋ = −⌊(−n − 1)/d⌋ − 1 and −n − 1 = !n): no floor
        // correction and no signed-overflow check. 13 k instructions less per bunny
        // frame on a Cortex-M4; 30 k more on x86-64, which keeps the signed form.
        return floor_div32_flip(n, d);
    }
    let q = n / d;
    if n % d < 0 {
        q - 1
    } else {
        q
    }
}

/// [`floor_div32`] by one unsigned division of `n` or `!n`.
#[inline(always)]
fn floor_div32_flip(n: i32, d: i32) -> i32 {
    let m = (n >> 31) as u32; // all ones when n < 0
    (((n as u32 ^ m) / d as u32) ^ m) as i32
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

/// ⌈n / d⌉ for `d > 0`.
#[inline]
pub(crate) fn div_ceil(n: i64, d: i64) -> i64 {
    -div_floor(-n, d)
}

/// ⌊n / d⌋ in 128 bits, for the rare exact evaluation of very large triangles.
pub(crate) fn div_floor_wide(n: i128, d: i128) -> i128 {
    let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
    n.div_euclid(d)
}

/// Saturate an `i64` into `i32`.
#[inline]
pub(crate) fn sat_i32(v: i64) -> i32 {
    v.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
}

/// Round an `f32` to the nearest integer (halves away from zero); the caller has checked
/// that the value is finite and within `i32`.
#[inline]
pub(crate) fn round_f32(v: f32) -> i32 {
    // ±½ by the sign bit, then truncation: no branch.
    (v + 0.5f32.copysign(v)) as i32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wide_products_are_exact() {
        let edges = [
            0u32,
            1,
            0xffff,
            0x1_0000,
            0x1_0001,
            0x8000_0000,
            u32::MAX - 1,
            u32::MAX,
        ];
        let mut x = 0x9e37_79b9_7f4a_7c15_u64;
        let mut pairs = edges
            .iter()
            .flat_map(|&a| edges.iter().map(move |&b| (a, b)))
            .collect::<std::vec::Vec<_>>();
        for _ in 0..100_000 {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            pairs.push(((x >> 32) as u32, x as u32 >> (x % 31)));
        }
        for (a, b) in pairs {
            let want = u64::from(a) * u64::from(b);
            assert_eq!(mul_wide_parts(a, b), want, "{a} * {b}");
            assert_eq!(mul_wide(a, b), want, "{a} * {b}");
        }
    }

    #[test]
    fn bits_beyond_31_counts_them() {
        let want = |w: i64| (64 - w.leading_zeros()).saturating_sub(31);
        let mut cases = std::vec![
            0i64,
            1,
            (1 << 31) - 1,
            1 << 31,
            (1 << 32) - 1,
            1 << 32,
            i64::MAX
        ];
        for k in 0..63 {
            cases.extend([1i64 << k, (1i64 << k) - 1, (1i64 << k) + 1]);
        }
        let mut next = crate::testing::xorshift64(0x2545_f491_4f6c_dd1d);
        for _ in 0..100_000 {
            let x = next();
            cases.push((x >> 1) as i64 >> (x % 63));
        }
        for w in cases {
            assert_eq!(bits_beyond_31_parts(w), want(w), "{w}");
            assert_eq!(bits_beyond_31(w), want(w), "{w}");
        }
    }

    #[test]
    fn split_shifts_are_shifts() {
        let mut next = crate::testing::xorshift64(0x2545_f491_4f6c_dd1d);
        for _ in 0..20_000 {
            let x = next();
            let v = x as i64 >> (x % 40);
            for s in 0..32 {
                assert_eq!(shl64_parts(v, s), v.wrapping_shl(s), "{v} << {s}");
                assert_eq!(shr64_parts(v, s), v >> s, "{v} >> {s}");
                assert_eq!(shl64(v, s), v.wrapping_shl(s));
                assert_eq!(shr64(v, s), v >> s);
            }
        }
        for v in [0i64, -1, 1, i64::MIN, i64::MAX] {
            for s in 0..32 {
                assert_eq!(shl64_parts(v, s), v.wrapping_shl(s));
                assert_eq!(shr64_parts(v, s), v >> s);
            }
        }
    }

    #[test]
    fn small_products_wrap_as_i64_does() {
        let mut x = 0x9e37_79b9_7f4a_7c15_u64;
        let mut cases = std::vec![];
        for a in [
            0i64,
            1,
            -1,
            i64::MAX,
            i64::MIN,
            1 << 47,
            -(1 << 53) + 5,
            0xffff_ffff,
        ] {
            for b in [0i32, 1, -1, 8, -8, 65535, -65535, 65536, i32::MIN, i32::MAX] {
                cases.push((a, b));
            }
        }
        for _ in 0..100_000 {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            cases.push((x as i64 >> (x % 17), (x >> 40) as i32 >> (x % 23)));
        }
        for (a, b) in cases {
            let want = a.wrapping_mul(i64::from(b));
            assert_eq!(mul_i64_i32(a, b), want, "{a} * {b}");
            if b.unsigned_abs() < 1 << 16 {
                assert_eq!(mul_small_parts(a, b), want, "{a} * {b}");
            }
        }
    }

    #[test]
    fn signless_division_is_floor_division() {
        // The floor of n/d from Euclid's division (d ≠ 0).
        let floor = |n: i64, d: i64| {
            let q = n.div_euclid(d);
            if d < 0 && n.rem_euclid(d) != 0 {
                q - 1
            } else {
                q
            }
        };
        let edge_n = [
            0i64,
            1,
            -1,
            (1 << 48) - 1,
            -(1 << 48) + 1,
            -(1 << 48),
            1 << 48,
            -(1 << 48) - 1,
            i64::from(i32::MAX),
            i64::from(i32::MIN),
            1 << 52,
        ];
        let edge_d = [1i64, -1, 2, -3, 65535, -65535, 65536, -65536, 1 << 20];
        for &n in &edge_n {
            for &d in &edge_d {
                assert_eq!(div_floor_signless(n, d), floor(n, d), "{n} / {d}");
            }
        }
        let mut next = crate::testing::xorshift64(0x9e37_79b9_7f4a_7c15);
        for _ in 0..300_000 {
            let v = next();
            let n = ((v >> 12) as i64) >> (v % 48); // |n| < 2⁵¹
            let d = (((next() % (1 << 18)) as i64 + 1) >> (next() % 18)).max(1);
            let d = if next().is_multiple_of(2) { d } else { -d };
            assert_eq!(div_floor_signless(n, d), floor(n, d), "{n} / {d}");
        }
    }

    #[test]
    fn small_reciprocal_is_exact_for_every_divisor() {
        for d in 1..1u32 << 16 {
            assert_eq!(recip32_small(d), u32::MAX / d, "d = {d}");
        }
        assert_eq!(recip32_small(1 << 16), u32::MAX >> 16);
        assert_eq!(recip32_small(0), u32::MAX);
    }

    #[test]
    fn reciprocal_pair_division_is_div_floor() {
        let ds = [
            1i64, 2, 3, 7, 255, 256, 4095, 65534, 65535, -1, -2, -3, -65535,
        ];
        let ns = [
            0i64,
            1,
            -1,
            65535,
            -65536,
            (1 << 32) - 1,
            1 << 32,
            -(1 << 40) - 3,
            (1 << 48) - 1,
            -(1 << 48) + 1,
        ];
        let check = |n1: i64, n2: i64, d: i64| {
            let want = (n1.div_euclid(d), n2.div_euclid(d));
            let want = if d < 0 {
                // div_euclid rounds toward −∞ only for positive divisors.
                ((-n1).div_euclid(-d), (-n2).div_euclid(-d))
            } else {
                want
            };
            assert_eq!(
                div_floor_pair_recip(n1, n2, d),
                Some(want),
                "{n1} {n2} / {d}"
            );
            assert_eq!(div_floor_pair(n1, n2, d), want);
            assert_eq!((div_floor(n1, d), div_floor(n2, d)), want);
        };
        for &d in &ds {
            for &n1 in &ns {
                for &n2 in &ns {
                    check(n1, n2, d);
                }
            }
        }
        let mut next = crate::testing::xorshift64(0x2545_f491_4f6c_dd1d);
        for _ in 0..200_000 {
            let d = (next() % 65535) as i64 + 1;
            let d = if next().is_multiple_of(2) { d } else { -d };
            let n = |v: u64| ((v >> 16) as i64) >> (v % 40); // |n| < 2⁴⁸
            check(n(next()), n(next()), d);
        }
        // Outside its range: None.
        assert_eq!(div_floor_pair_recip(1, 1, 1 << 16), None);
        assert_eq!(div_floor_pair_recip(1 << 48, 1, 3), None);
        assert_eq!(div_floor_pair_recip(1, -(1 << 48), 3), None);
        assert_eq!(div_floor_pair_recip(1, 1, 0), None);
    }

    #[test]
    fn shift_and_subtract_division_is_exact() {
        let edges = [
            0u32,
            1,
            2,
            3,
            7,
            8,
            255,
            256,
            65535,
            65536,
            1 << 31,
            u32::MAX - 1,
            u32::MAX,
        ];
        for &n in &edges {
            for &d in edges.iter().filter(|&&d| d > 0) {
                assert_eq!(udivrem(n, d), (n / d, n % d), "{n} / {d}");
            }
        }
        let mut x = 0x9e37_79b9_u64;
        for _ in 0..100_000 {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let n = (x >> 32) as u32 >> (x % 32);
            let d = ((x >> 7) as u32 >> ((x >> 3) % 32)).max(1);
            assert_eq!(udivrem(n, d), (n / d, n % d), "{n} / {d}");
            let (ni, di) = (n as i32, (d >> 1).max(1) as i32);
            assert_eq!(floor_div32_soft(ni, di), ni.div_euclid(di), "{ni} / {di}");
        }
    }

    #[test]
    fn floor_and_ceil_division_round_the_right_way() {
        assert_eq!(div_floor(7, 2), 3);
        assert_eq!(div_floor(-7, 2), -4);
        assert_eq!(div_floor(7, -2), -4);
        assert_eq!(div_floor(-7, -2), 3);
        assert_eq!(div_ceil(7, 2), 4);
        assert_eq!(div_ceil(-7, 2), -3);
        assert_eq!(div_ceil(8, 2), 4);
        for (n, d) in [
            (7, 2),
            (-7, 2),
            (-8, 2),
            (0, 5),
            (i32::MIN, 3),
            (i32::MAX, 7),
        ] {
            assert_eq!(floor_div32(n, d), n.div_euclid(d), "{n} / {d}");
            assert_eq!(floor_div32_flip(n, d), n.div_euclid(d), "{n} / {d}");
            assert_eq!(floor_div32_soft(n, d), n.div_euclid(d), "{n} / {d}");
        }
        let mut x = 0x853c_49e6_748f_ea9b_u64;
        for _ in 0..100_000 {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let (n, d) = (
                (x >> 32) as i32,
                ((x as u32 & i32::MAX as u32) >> (x % 31)).max(1) as i32,
            );
            assert_eq!(floor_div32(n, d), n.div_euclid(d), "{n} / {d}");
            assert_eq!(floor_div32_flip(n, d), n.div_euclid(d), "{n} / {d}");
            assert_eq!(floor_div32_soft(n, d), n.div_euclid(d), "{n} / {d}");
        }
        // The 64-bit and two-digit paths agree with plain division.
        assert_eq!(div_floor(-(1 << 40) - 1, 1 << 20), -(1 << 20) - 1);
        let mut x = 0x1234_5678_9abc_u64;
        for _ in 0..20_000 {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let n = ((x >> 14) as i64) - (1 << 49);
            let d = ((x >> 3) % 70_000) as i64 - 35_000;
            if d != 0 {
                assert_eq!(
                    div_floor(n, d),
                    n.div_euclid(d) - i64::from(d < 0 && n.rem_euclid(d) != 0),
                    "{n} / {d}"
                );
            }
        }
        assert_eq!(div_floor_wide(-7, 2), -4);
    }

    #[test]
    fn rounding_and_saturation() {
        assert_eq!(round_f32(2.5), 3);
        assert_eq!(round_f32(-2.5), -3);
        assert_eq!(round_f32(2.49), 2);
        assert_eq!(sat_i32(1 << 40), i32::MAX);
        assert_eq!(sat_i32(-(1 << 40)), i32::MIN);
    }
}
