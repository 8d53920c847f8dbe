//! The dual 16 × 16-bit multiply-accumulate of the vertex transform: one `SMLAD` on
//! ARMv7E-M, beside its portable twin.
#![allow(unsafe_code)]

/// `acc + a₀·b₀ + a₁·b₁` (wrapping), where `a₀`, `a₁` are the low and high halves of
/// `a` and `b₀`, `b₁` those of `b`, each read as a signed 16-bit value. On ARMv7E-M one
/// `SMLAD`; elsewhere [`smlad_portable`]. (Both products are below 2³⁰ in magnitude; a
/// caller whose sum stays within `i32`, as the transform's rows do, gets it exactly.)
#[inline(always)]
pub(crate) fn smlad(a: u32, b: u32, acc: i32) -> i32 {
    #[cfg(all(zraster_thumb, zraster_dsp))]
    {
        let sum: i32;
        // SAFETY: one SMLAD on three input registers into a fourth: it reads and writes
        // no memory and not the stack. It may set the sticky Q flag (on a wrapping sum),
        // which nothing in the crate reads; the flags are not declared preserved.
        unsafe {
            core::arch::asm!(
                "smlad {sum}, {a}, {b}, {acc}",
                sum = lateout(reg) sum,
                a = in(reg) a,
                b = in(reg) b,
                acc = in(reg) acc,
                options(pure, nomem, nostack),
            );
        }
        return sum;
    }
    #[allow(unreachable_code)]
    smlad_portable(a, b, acc)
}

/// The portable twin of [`smlad`].
#[inline(always)]
pub(crate) fn smlad_portable(a: u32, b: u32, acc: i32) -> i32 {
    let half = |v: u32, k: u32| i32::from((v >> k) as u16 as i16);
    acc.wrapping_add(half(a, 0) * half(b, 0))
        .wrapping_add(half(a, 16) * half(b, 16))
}

/// The multiply-accumulate against its portable twin on this target: the halves' edge
/// values (0, ±1, ±2¹⁴, −2¹⁵, 2¹⁵ − 1) in every combination, then `n` random cases
/// (wrapping sums included). Returns the number of cases that differ.
pub fn check_mac_kernel(n: usize) -> usize {
    const EDGES: [u16; 8] = [0, 1, 0xffff, 0x4000, 0xc000, 0x8000, 0x7fff, 0x1234];
    let mut bad = 0;
    let mut case = |a: u32, b: u32, acc: i32| {
        if smlad(a, b, acc) != smlad_portable(a, b, acc) {
            bad += 1;
        }
    };
    let pairs = || {
        EDGES.iter().flat_map(|&lo| {
            EDGES
                .iter()
                .map(move |&hi| u32::from(lo) | u32::from(hi) << 16)
        })
    };
    for a in pairs() {
        for b in pairs() {
            for acc in [0, 1, -1, 1 << 29, -(1 << 29), i32::MAX, i32::MIN] {
                case(a, b, acc);
            }
        }
    }
    let mut rnd = super::xorshift32(0x2545_f491_u32);
    for _ in 0..n {
        let (a, b, acc) = (rnd(), rnd(), rnd() as i32);
        case(a, b, acc);
    }
    bad
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smlad_is_the_dual_product_sum() {
        assert_eq!(check_mac_kernel(100_000), 0);
        let pack = |a: i16, b: i16| u32::from(a as u16) | u32::from(b as u16) << 16;
        assert_eq!(smlad(pack(3, -4), pack(-5, 6), 7), 7 - 15 - 24);
        assert_eq!(
            smlad(pack(-32768, -32768), pack(-32768, -32768), 0),
            i32::MIN // 2 · 2³⁰ wraps
        );
        assert_eq!(
            smlad(pack(16383, -16383), pack(32767, 32767), 1 << 29),
            1 << 29
        );
    }
}
