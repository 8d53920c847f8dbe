//! Integer arithmetic behind small portable functions, with a backend per kind of
//! core: division, widening multiplication, reciprocals, wide shifts and rounding.
//!
//! The stages call the functions here and never ask which chip they run on. Each
//! function chooses, at compile time, between the plain operation (hosts, and
//! Cortex-M3/M4/M7, whose divide and long-multiply instructions make it cheap) and the
//! [`armv6m`] forms for cores without them (Cortex-M0/M0+), and [`armv7m`] holds the
//! forms that pay on Cortex-M3/M4/M7 only. The capability cfgs they test are set once,
//! in `build.rs`. Every backend function is written in portable Rust and tested against
//! the plain operation on the host.

mod armv6m;
mod armv7m;
pub(crate) mod kernel;

pub(crate) use armv6m::{
    bits_beyond_31_parts, div_floor_pair_recip, div_floor_wide_soft, floor_div32_pair_small,
    floor_div32_soft, mul_narrow_parts, mul_small_parts, mul_wide_parts, scaled_ratio_parts,
    shl64_parts, shr64_parts, udivrem_call,
};
use armv7m::floor_div32_flip;

/// ⌊n / d⌋ for `d ≠ 0`, exact, avoiding 64-bit division where it can: with 32-bit
/// divisions (one `UDIV` each on a Cortex-M3/M4, a short library call on an M0+)
/// when both fit in 32 bits, or when `|d| < 2¹⁶` and `|n| < 2⁴⁸` (two 16-bit "digits"
/// of long division). Small triangles, the common case, always take those paths.
/// Out of line on ARMv6-M, where every caller calls it anyway: `#[inline]` gave each
/// crate that instantiates a caller its own copy (two of 900 bytes in a firmware).
#[cfg_attr(zraster_armv6m, inline(never))]
#[cfg_attr(not(zraster_armv6m), inline)]
pub(crate) fn div_floor(n: i64, d: i64) -> i64 {
    let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
    if let (Ok(n), Ok(d)) = (i32::try_from(n), i32::try_from(d)) {
        return i64::from(floor_div32(n, d));
    }
    let m = n.unsigned_abs();
    if d < 1 << 16 && m < 1 << 48 {
        let d32 = d as u32;
        // On ARMv6-M by shift and subtract (the digits are usually a few bits), out of
        // line: one copy for both digits.
        let (q, r0) = by_digits(m, |x| {
            if ARMV6M {
                udivrem_call(x, d32)
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
    div_floor_plain(n, d)
}

/// [`div_floor`]'s last resort (`d > 0`), the plain 64-bit division: out of line on
/// ARMv6-M, where it is a library call and rare (inline, its fix-up deepened the
/// drawing's deepest stack).
#[cfg_attr(zraster_armv6m, inline(never))]
#[cfg_attr(not(zraster_armv6m), inline(always))]
fn div_floor_plain(n: i64, d: i64) -> i64 {
    n.div_euclid(d)
}

/// `(⌊n₁ / d⌋, ⌊n₂ / d⌋)` for `d ≠ 0`, exactly as [`div_floor`] gives them: by the
/// divide instruction on 64-bit hosts; on ARMv6-M, which has no divide instruction,
/// when `|d| < 2¹⁶` and both `|n| < 2⁴⁸` (the depth slopes of every small triangle),
/// by a reciprocal of `d` and each 16-bit digit of the two long divisions by a multiply
/// and at most three corrections, instead of four library divisions (else two
/// [`div_floor`]s, out of line there); elsewhere by
/// [`div_floor_pair32`] when everything fits 32 bits, else two [`div_floor_signless`]s.
#[cfg_attr(zraster_armv6m, inline(never))]
#[cfg_attr(not(zraster_armv6m), inline)]
pub(crate) fn div_floor_pair(n1: i64, n2: i64, d: i64) -> (i64, i64) {
    if ARMV6M {
        // Outside the reciprocal's range the digit method below would divide by library
        // calls: the out-of-line general form instead (rare: very large triangles).
        return div_floor_pair_recip(n1, n2, d)
            .unwrap_or_else(|| (div_floor(n1, d), div_floor(n2, d)));
    }
    let (n1, n2, d) = if d < 0 { (-n1, -n2, -d) } else { (n1, n2, d) };
    if WIDE {
        // A 64-bit divide instruction: one each, cheaper than the digit method.
        return (n1.div_euclid(d), n2.div_euclid(d));
    }
    if let Some((a, b)) = i32::try_from(d)
        .ok()
        .and_then(|d| div_floor_pair32(n1, n2, d))
    {
        return (i64::from(a), i64::from(b));
    }
    (div_floor_signless(n1, d), div_floor_signless(n2, d))
}

/// [`div_floor_pair`] when both numerators and the divisor (`d ≠ 0`) fit 32 bits, on
/// cores with a divide instruction: two divisions inline. `None` otherwise (and always
/// on ARMv6-M, whose reciprocal form is the cheaper).
#[inline(always)]
pub(crate) fn div_floor_pair32(n1: i64, n2: i64, d: i32) -> Option<(i32, i32)> {
    if !DIVIDE {
        return None;
    }
    let (n1, n2) = (i32::try_from(n1).ok()?, i32::try_from(n2).ok()?);
    let (n1, n2, d) = if d < 0 {
        (n1.checked_neg()?, n2.checked_neg()?, d.checked_neg()?)
    } else {
        (n1, n2, d)
    };
    Some((floor_div32(n1, d), floor_div32(n2, d)))
}

/// [`div_floor`] with the sign of `n` folded in rather than tested: for d > 0,
/// ⌊n/d⌋ = −1 − ⌊(−1 − n)/d⌋, so with s = 0 or −1 by n's sign it is s ^ ⌊m/d⌋ for
/// m = n ^ s ≥ 0 — unsigned divisions and no remainder test. (Only for the depth
/// slopes of small triangles: `div_floor` itself, inlined in the general path, keeps
/// the plain form.)
#[inline(always)]
pub(crate) fn div_floor_signless(n: i64, d: i64) -> i64 {
    let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
    let sign = n >> 63;
    let m = (n ^ sign) as u64;
    if d > 0 && d < 1 << 16 && m < 1 << 48 {
        let d32 = d as u32;
        return by_digits(m, |x| (x / d32, x % d32)).0 as i64 ^ sign;
    }
    div_floor(n, d)
}

/// `(m / d, m % d)` for `m < 2⁴⁸` and `d < 2¹⁶`, as two 16-bit digits of long division,
/// each by `divrem` (`x ↦ (x / d, x % d)` for a 32-bit `x`): the first digit divides
/// `m / 2¹⁶` (below 2³²), the second its remainder (below `d`) times 2¹⁶ plus the low 16
/// bits, which fits 32 bits.
#[inline(always)]
pub(crate) fn by_digits(m: u64, divrem: impl Fn(u32) -> (u32, u32)) -> (u64, u32) {
    let (q1, r1) = divrem((m >> 16) as u32);
    let (q0, r0) = divrem((r1 << 16) | (m as u32 & 0xffff));
    (u64::from(q1) << 16 | u64::from(q0), r0)
}

/// ARMv6-M (Cortex-M0/M0+): no divide instruction and no 32×32→64-bit multiply. A
/// division is a library call costing about 130 instructions whatever the operands
/// ([`udivrem`](armv6m::udivrem) costs about 7 per quotient bit, and the rasterizer's quotients are
/// mostly a few bits), and a 64-bit product a call costing about 45 ([`mul_wide`] is
/// four multiplies inline).
pub(crate) const ARMV6M: bool = cfg!(zraster_armv6m);
/// ARMv7-M and ARMv8-M mainline (Cortex-M3/M4/M7/M33): divide, long multiply and
/// multiply-accumulate instructions.
pub(crate) const THUMB2: bool = cfg!(zraster_thumb2);
/// A divide instruction (everything but ARMv6-M): a division costs about as much as
/// a multiply, so loops may divide where a DDA would step.
pub(crate) const DIVIDE: bool = !ARMV6M;
/// The DSP extension (ARMv7E-M: Cortex-M4, M7): two 16 × 16-bit products summed into
/// an accumulator in one instruction ([`dot2_add`]).
pub(crate) const DUAL_MAC: bool = cfg!(all(zraster_thumb, zraster_dsp));
/// 32-bit Arm of either kind.
pub(crate) const ARM: bool = ARMV6M || THUMB2;
/// 64-bit registers and a 64-bit divide instruction (x86-64, AArch64).
pub(crate) const WIDE: bool = cfg!(zraster_wide);
/// No hardware floating point: vertices are projected in integers (a soft-float divide
/// and its conversions cost thousands of instructions a vertex on a Cortex-M0+).
pub(crate) const INTEGER_PROJECTION: bool = SOFT_FLOAT;
/// No hardware floating point: each `f32` operation is a library call.
pub(crate) const SOFT_FLOAT: bool = cfg!(zraster_soft_float);

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

/// `a · b` in 64 bits, as [`mul_wide`], for a small `a` (below 2¹⁶ in the common case):
/// on ARMv6-M then two 16×32-bit products instead of four.
#[inline]
pub(crate) fn mul_wide_narrow(a: u32, b: u32) -> u64 {
    if ARMV6M && a >> 16 == 0 {
        mul_narrow_parts(a, b)
    } else {
        mul_wide(a, b)
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

/// `acc + a₀·b₀ + a₁·b₁` (wrapping) for pairs of signed 16-bit values packed as the low
/// and high halves of `a` and `b` ([`pack_i16`]): one `SMLAD` where [`DUAL_MAC`] (the
/// assembly of [`kernel`]), else its portable twin.
#[inline(always)]
pub(crate) fn dot2_add(a: u32, b: u32, acc: i32) -> i32 {
    kernel::smlad(a, b, acc)
}

/// Whether `|c| < lim`, for `1 ≤ lim ≤ 2³⁰`. On ARMv6-M as one unsigned compare,
/// `−(lim − 1) ≤ c ≤ lim − 1` shifted up by `lim − 1` (the sign test and negation of
/// `|c|` are three instructions more there); elsewhere `|c| < lim`, which on Thumb-2
/// keeps the vertex cache's test a branch (the compare form had LLVM select the
/// entry's fields without one: +14 instructions a vertex on the M4F).
#[inline(always)]
pub(crate) fn abs_below(c: i32, lim: u32) -> bool {
    if ARMV6M {
        let m = lim.wrapping_sub(1);
        c.wrapping_add(m as i32) as u32 <= 2 * m
    } else {
        c.unsigned_abs() < lim
    }
}

/// `lo` and `hi` as the low and high halves of a word, for [`dot2_add`].
#[inline(always)]
pub(crate) fn pack_i16(lo: i16, hi: i16) -> u32 {
    u32::from(lo as u16) | u32::from(hi as u16) << 16
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

/// ⌊n / d⌋ in 32 bits for `d > 0` (one division and a correction, inlined: the
/// standard library's `div_euclid` is an out-of-line call on Thumb).
#[inline(always)]
pub(crate) fn floor_div32(n: i32, d: i32) -> i32 {
    if ARMV6M {
        return floor_div32_soft(n, d);
    }
    if THUMB2 {
        // One unsigned division, flipping the bits of n before and after when it is
        // negative (for n < 0, ⌊n/d⌋ = −⌊(−n − 1)/d⌋ − 1 and −n − 1 = !n): no floor
        // correction and no signed-overflow check (hosts keep the signed form).
        return floor_div32_flip(n, d);
    }
    let q = n / d;
    if n % d < 0 {
        q - 1
    } else {
        q
    }
}

/// ⌈n / d⌉ for `d > 0`.
#[inline]
pub(crate) fn div_ceil(n: i64, d: i64) -> i64 {
    -div_floor(-n, d)
}

/// ⌊n / d⌋ in 128 bits for `d ≠ 0`, for the rare exact evaluation of very large
/// triangles: on ARMv6-M by shift and subtract ([`div_floor_wide_soft`], a tenth of the
/// code of LLVM's inline expansion). Out of line: rare.
#[inline(never)]
#[cold]
pub(crate) fn div_floor_wide(n: i128, d: i128) -> i128 {
    let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
    if ARMV6M {
        return div_floor_wide_soft(n, d);
    }
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

/// `data.fill(value)`: on Cortex-M, two-byte values (RGB565, depth) by the
/// store-multiple loop of [`kernel::fill_u16`]. On x86-64 the value goes through
/// `black_box`, so that the compiler emits vector stores rather than `memset` (glibc's
/// `rep stosb`, counted byte by byte by instruction counters), 64 values a turn.
#[inline]
pub(crate) fn fill<T: Copy>(data: &mut [T], value: T) {
    if ARM && kernel::fill_as_u16(data, value) {
        return;
    }
    #[cfg(target_arch = "x86_64")]
    {
        let value = core::hint::black_box(value);
        let mut chunks = data.chunks_exact_mut(64);
        for chunk in &mut chunks {
            if let Ok(chunk) = <&mut [T; 64]>::try_from(chunk) {
                *chunk = [value; 64];
            }
        }
        chunks.into_remainder().fill(value);
    }
    #[cfg(not(target_arch = "x86_64"))]
    data.fill(value);
}

#[cfg(test)]
pub(crate) mod tests;
