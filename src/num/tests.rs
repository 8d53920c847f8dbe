//! Each backend form against the plain operation it replaces, on the host.

use super::armv6m::{floor_div32_pair_small, recip32_small, udivrem};
use super::*;

#[test]
fn div_floor_pair32_agrees_with_div_floor_pair() {
    let mut rnd = crate::testing::xorshift32(0x0bad_cafe);
    let edges = [
        i32::MIN,
        i32::MIN + 1,
        -65536,
        -17,
        -1,
        0,
        1,
        17,
        65535,
        i32::MAX,
    ];
    for i in 0..200_000u32 {
        let pick = |r: u32, k: usize| {
            if i % 5 == 0 {
                edges[(r as usize + k) % edges.len()]
            } else {
                r as i32 >> (r % 24)
            }
        };
        let (n1, n2) = (pick(rnd(), 0), pick(rnd(), 3));
        let d = match pick(rnd(), 7) {
            0 => 1,
            d => d,
        };
        let (n1, n2) = (i64::from(n1), i64::from(n2));
        match div_floor_pair32(n1, n2, d) {
            Some((a, b)) => {
                assert_eq!(
                    (i64::from(a), i64::from(b)),
                    div_floor_pair(n1, n2, i64::from(d))
                )
            }
            // Only where a quotient or a negation leaves i32 (or on ARMv6-M).
            None => assert!(
                !DIVIDE || d == i32::MIN || n1 == i64::from(i32::MIN) || n2 == i64::from(i32::MIN)
            ),
        }
    }
    assert_eq!(div_floor_pair32(1 << 40, 1, 3), None);
}

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
        assert_eq!(mul_wide_narrow(a, b), want, "{a} * {b}");
        assert_eq!(
            mul_narrow_parts(a & 0xffff, b),
            u64::from(a & 0xffff) * u64::from(b)
        );
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

/// The one-reciprocal pair is floor division for every divisor below 2¹⁶, numerators
/// at both ends of `i32` (but `i32::MIN`) and random ones.
#[test]
fn small_reciprocal_pair_is_floor_division() {
    let ns = [
        0,
        1,
        -1,
        2,
        -2,
        65535,
        -65536,
        i32::MAX,
        -i32::MAX,
        i32::MAX - 1,
    ];
    let mut next = crate::testing::xorshift32(0x1357_9bdf);
    for d in 1..1u32 << 16 {
        let di = d as i32;
        let check = |n1: i32, n2: i32| {
            let want = (n1.div_euclid(di), n2.div_euclid(di));
            assert_eq!(floor_div32_pair_small(n1, n2, d), want, "{n1} {n2} / {d}");
        };
        for &n in &ns {
            check(n, -n);
        }
        for _ in 0..8 {
            let n = |v: u32| (v as i32 >> (v % 31)).max(-i32::MAX);
            check(n(next()), n(next()));
        }
    }
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
fn wide_division_by_shift_and_subtract_is_exact() {
    let edges = [
        0i128,
        1,
        -1,
        7,
        -7,
        i128::from(i64::MAX),
        i128::from(i64::MIN),
        1 << 100,
        -(1 << 100) - 3,
        i128::MAX,
        i128::MIN + 1,
    ];
    for &n in &edges {
        for &d in edges.iter().filter(|&&d| d > 0) {
            assert_eq!(div_floor_wide_soft(n, d), n.div_euclid(d), "{n} / {d}");
        }
    }
    let mut x = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = || {
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        x
    };
    for _ in 0..100_000 {
        // Numerators to about 2⁸⁰ and divisors to 2⁵², as the plane's.
        let n = (i128::from(next() as i64) << 16 >> (next() % 80)) | i128::from(next() % 3);
        let d = (i128::from(next() >> 11) >> (next() % 52)).max(1);
        assert_eq!(div_floor_wide_soft(n, d), n.div_euclid(d), "{n} / {d}");
        assert_eq!(div_floor_wide(n, -d), (-n).div_euclid(d), "{n} / -{d}");
    }
}

#[test]
fn rounding_and_saturation() {
    assert_eq!(round_f32(2.5), 3);
    assert_eq!(round_f32(-2.5), -3);
    assert_eq!(round_f32(2.49), 2);
    assert_eq!(sat_i32(1 << 40), i32::MAX);
    assert_eq!(sat_i32(-(1 << 40)), i32::MIN);
}

#[test]
fn abs_below_is_the_magnitude_test() {
    let mut rnd = crate::testing::xorshift32(0x5eed_1234);
    for lim in [
        1u32,
        2,
        3,
        1 << 14,
        (1 << 14) + 1,
        1 << 29,
        (1 << 30) - 1,
        1 << 30,
    ] {
        let l = lim as i64;
        let edges = [
            0,
            1,
            -1,
            l - 1,
            l,
            l + 1,
            -l + 1,
            -l,
            -l - 1,
            i32::MAX as i64,
            i32::MIN as i64,
        ];
        for c in edges.into_iter().filter_map(|c| i32::try_from(c).ok()) {
            assert_eq!(abs_below(c, lim), c.unsigned_abs() < lim, "{c} {lim}");
            let m = lim - 1;
            assert_eq!(
                c.wrapping_add(m as i32) as u32 <= 2 * m,
                c.unsigned_abs() < lim,
                "{c} {lim}"
            );
        }
        for _ in 0..100_000 {
            let c = rnd() as i32 >> (rnd() % 32);
            let m = lim - 1;
            assert_eq!(
                c.wrapping_add(m as i32) as u32 <= 2 * m,
                c.unsigned_abs() < lim,
                "{c} {lim}"
            );
        }
    }
}

/// The random cases of the fast-against-exact tests: `ZRASTER_FAST_CASES`, else ten
/// million (under half a second in a debug build).
pub(crate) fn fast_cases() -> u64 {
    std::env::var("ZRASTER_FAST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(10_000_000)
}

#[test]
fn scaled_ratio_parts_is_the_exact_rounded_ratio_or_none() {
    use super::armv6m::scaled_ratio_parts;
    let exact = |a: u32, r: u32, h: u32| {
        ((u128::from(a) * u128::from(h) * u128::from(r) + (1 << 61)) >> 62) as u32
    };
    // Cases not aimed at a boundary, and how many of them were told fast.
    let (mut fast, mut all) = (0u64, 0u64);
    let mut check = |a: u32, r: u32, h: u32, aimed: bool| {
        let want = exact(a, r, h);
        all += u64::from(!aimed);
        if let Some(q) = scaled_ratio_parts(a, r, h) {
            assert_eq!(q, want, "a {a} r {r} h {h}");
            fast += u64::from(!aimed);
        }
    };
    // The edges of each range.
    let edge_a = [
        0,
        1,
        2,
        0xffff,
        0x1_0000,
        0x1_0001,
        0x7fff_0000,
        (1 << 31) - 1,
    ];
    let edge_r = [
        0,
        1,
        0xffff,
        1 << 31,
        (1 << 31) + 1,
        0xaaaa_aaab,
        u32::MAX - 1,
        u32::MAX,
    ];
    let edge_h = [1, 2, 8, 1280, 0xffff, 1 << 16];
    for &a in &edge_a {
        for &r in &edge_r {
            for &h in &edge_h {
                check(a, r, h, true);
            }
        }
    }
    // Random: a of every magnitude, r of the projection's range (2³¹, 2³²) and below,
    // h any viewport's half size; every tenth case aimed at a rounding boundary (a·h/d
    // close to an odd multiple of ½).
    let mut rnd = crate::testing::xorshift64(0x9e37_79b9_7f4a_7c15);
    for i in 0..fast_cases() {
        let v = rnd();
        let a = (v as u32 & 0x7fff_ffff) >> ((v >> 32) % 31);
        let r = if i % 7 == 0 {
            (v >> 32) as u32
        } else {
            (v >> 32) as u32 | 1 << 31
        };
        let h = ((v >> 40) as u32 % (1 << 16)) + 1;
        let aimed = i % 10 == 0;
        let a = if aimed {
            // a ≈ (k + ½)·2⁶²/(h·r): the exact value lands next to a boundary.
            let k = u128::from(a >> 13);
            let t = ((2 * k + 1) << 61) / (u128::from(h) * u128::from(r.max(1)));
            u32::try_from(t).unwrap_or(a).min((1 << 31) - 1)
        } else {
            a
        };
        check(a, r, h, aimed);
    }
    assert!(fast * 1000 > all * 998, "{fast} of {all} cases fast");
}
