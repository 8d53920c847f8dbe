//! The textured fill's arithmetic against plain references.

use super::segments::{div_clamped, divide_wide};
use super::*;

/// `div_clamped` (the divide-instruction path of `divide`) gives ⌊(h ≫ 16) / q⌋ clamped
/// to ±2²⁴, as the general path does, wherever it answers: random values at every
/// magnitude, both signs, and the edges of the clamp and of its range.
#[test]
fn the_digit_division_agrees_with_the_general_one() {
    let mut rnd = crate::testing::xorshift32(0x2545_f491);
    let check = |h: i64, q: u32| {
        let want = divide_wide(h >> F, 0, i64::from(q)).0;
        if let Some(got) = div_clamped(h, q) {
            assert_eq!(got, want, "h = {h}, q = {q}");
        } else {
            assert!(
                (h >> F).unsigned_abs() >= 1 << 47 || q == 0 || q >= 1 << 16,
                "{h} {q}"
            );
        }
    };
    let lim = i64::from(UV_LIMIT);
    for _ in 0..200_000 {
        let q = (rnd() >> (rnd() % 32)).max(1) & 0xFFFF;
        let bits = rnd() % 64;
        let h = (i64::from(rnd()) << 32 | i64::from(rnd())) >> bits;
        check(h, q.max(1));
        // Around the clamp: quotients of 2²⁴ − 1, 2²⁴ and 2²⁴ + 1, and their negatives.
        let q = q.max(1);
        for k in [lim - 1, lim, lim + 1, -lim - 1, -lim, -lim + 1] {
            for r in [0, i64::from(q) - 1] {
                check((k * i64::from(q) + r) << F | i64::from(rnd() & 0xFFFF), q);
            }
        }
    }
    for h in [
        0,
        -1,
        1,
        i64::MAX,
        i64::MIN,
        (1 << 62) + 12345,
        -(1 << 62),
        (1 << 40 << 16) - 1,
        -(1 << 40 << 16),
    ] {
        for q in [1, 2, 3, 0x7FFF, 0x8000, 0xFFFF] {
            check(h, q);
        }
    }
}
