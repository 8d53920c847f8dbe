//! The pixel loops of flat-coloured spans: step the depth, test it, write depth and
//! colour; the target's assembly loop where it has one.

use crate::num::kernel;

/// The pixel loop of [`fill_flat_buffered`]: depth test, depth write, colour write.
/// Out of line, so that the loop has every register to itself. Returns the number of
/// pixels that failed the test.
// SAFETY: `link_section` only places the function: `.data.*` is copied to RAM by the
// start-up code (cortex-m-rt) before `main`, so it is there whenever it is called.
#[cfg_attr(zraster_ram_code, allow(unsafe_code), link_section = ".data.zraster")]
#[inline(never)]
pub(crate) fn flat_span<C: Copy>(
    zrow: &mut [u16],
    crow: &mut [C],
    acc: u32,
    dz: u32,
    color: C,
    write: bool,
    pass: &impl Fn(u16, u16) -> bool,
) -> u32 {
    // The default depth test with depth writes, a 16-bit colour and a span long enough:
    // the target's assembly loop, if it has one.
    if write && is_less(pass) && kernel::span_kernel_pays(zrow.len()) {
        if let Some(failed) = kernel::span_less_as_u16(zrow, crow, acc, dz, color) {
            return failed;
        }
    }
    // Rows of small triangles are mostly 1 to 3 pixels: they take a plain loop here,
    // which needs few registers (a cheap call); longer ones the two-a-turn loop.
    if zrow.len() >= LONG_SPAN {
        return flat_span_long(zrow, crow, acc, dz, color, write, pass);
    }
    span_pixels(zrow, crow, acc, dz, color, write, pass)
}

/// Whether `pass` is [`DepthTest::Less`]'s comparison. The pixel loops get only the
/// comparisons `per_depth_test!` binds, and of those `Less` alone passes 0 against 1
/// but neither 1 against 1 (`LessEqual`, `Always`) nor 2 against 1 (`Greater`): a
/// constant once `pass` is inlined.
#[inline(always)]
pub(super) fn is_less(pass: &impl Fn(u16, u16) -> bool) -> bool {
    pass(0, 1) && !pass(1, 1) && !pass(2, 1)
}

/// Spans at least this long take [`flat_span_long`].
const LONG_SPAN: usize = 8;

/// [`flat_span`] for long spans: two pixels a turn, the depth write decided once.
// SAFETY: `link_section` only places the function: `.data.*` is copied to RAM by the
// start-up code (cortex-m-rt) before `main`, so it is there whenever it is called.
#[cfg_attr(zraster_ram_code, allow(unsafe_code), link_section = ".data.zraster")]
#[inline(never)]
fn flat_span_long<C: Copy>(
    zrow: &mut [u16],
    crow: &mut [C],
    acc: u32,
    dz: u32,
    color: C,
    write: bool,
    pass: &impl Fn(u16, u16) -> bool,
) -> u32 {
    if write {
        span_x2::<C, true>(zrow, crow, acc, dz, color, pass)
    } else {
        span_x2::<C, false>(zrow, crow, acc, dz, color, pass)
    }
}

/// One more failed pixel: out of line and cold, so that the passing path of the pixel
/// loop is straight code (no predicated count), and the compiler does not unroll the
/// loop further (it leaves loops with calls as they are).
#[cold]
#[inline(never)]
// SAFETY: as for `flat_span` (called from it: kept in the same memory).
#[cfg_attr(zraster_ram_code, allow(unsafe_code), link_section = ".data.zraster")]
pub(super) fn one_failed(n: &mut u32) {
    *n += 1;
}

/// [`flat_span_long`]'s loop, two pixels a turn, the depth write decided at compile
/// time.
#[inline(always)]
fn span_x2<C: Copy, const WRITE: bool>(
    zrow: &mut [u16],
    crow: &mut [C],
    mut acc: u32,
    dz: u32,
    color: C,
    pass: &impl Fn(u16, u16) -> bool,
) -> u32 {
    let mut failed = 0;
    let mut pixel = |d: &mut u16, c: &mut C, acc: u32| {
        let z = (acc >> 16) as u16;
        if pass(z, *d) {
            if WRITE {
                *d = z;
            }
            *c = color;
        } else {
            one_failed(&mut failed);
        }
    };
    let n = zrow.len().min(crow.len());
    let (zrow, zrest) = zrow.split_at_mut(n & !1);
    let (crow, crest) = crow.split_at_mut(n & !1);
    for (d, c) in zrow.chunks_exact_mut(2).zip(crow.chunks_exact_mut(2)) {
        if let ([d0, d1], [c0, c1]) = (d, c) {
            pixel(d0, c0, acc);
            acc = acc.wrapping_add(dz);
            pixel(d1, c1, acc);
            acc = acc.wrapping_add(dz);
        }
    }
    for (d, c) in zrest.iter_mut().zip(crest) {
        pixel(d, c, acc);
        acc = acc.wrapping_add(dz);
    }
    failed
}

/// The plain pixel loop of [`flat_span`]'s short spans (and the reference the unrolled
/// loop of [`flat_span_long`] is tested against).
#[inline(always)]
fn span_pixels<C: Copy>(
    zrow: &mut [u16],
    crow: &mut [C],
    mut acc: u32,
    dz: u32,
    color: C,
    write: bool,
    pass: &impl Fn(u16, u16) -> bool,
) -> u32 {
    let mut failed = 0;
    for (d, c) in zrow.iter_mut().zip(crow.iter_mut()) {
        let z = (acc >> 16) as u16;
        acc = acc.wrapping_add(dz);
        if pass(z, *d) {
            if write {
                *d = z;
            }
            *c = color;
        } else {
            failed += 1;
        }
    }
    failed
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unrolled loop of long spans gives the depths, colours and failure counts of
    /// the plain loop, for every length, with and without depth writes.
    #[test]
    fn long_span_loop_matches_the_plain_one() {
        let mut rnd = crate::testing::xorshift32(0x9e37_79b9);
        for len in 0..41 {
            for write in [true, false] {
                let depth: std::vec::Vec<u16> = (0..len).map(|_| rnd() as u16).collect();
                let (acc, dz) = (rnd() >> 1, rnd() >> 12);
                let run = |f: &dyn Fn(&mut [u16], &mut [u8]) -> u32| {
                    let (mut z, mut c) = (depth.clone(), std::vec![0u8; len]);
                    let failed = f(&mut z, &mut c);
                    (z, c, failed)
                };
                let less = |a: u16, b: u16| a < b;
                let plain = run(&|z, c| span_pixels(z, c, acc, dz, 7u8, write, &less));
                let long = run(&|z, c| flat_span_long(z, c, acc, dz, 7u8, write, &less));
                let short = run(&|z, c| flat_span(z, c, acc, dz, 7u8, write, &less));
                assert_eq!(long, plain, "length {len}, write {write}");
                assert_eq!(short, plain, "length {len}, write {write}");
            }
        }
    }
}
