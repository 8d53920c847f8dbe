//! Helpers shared by the unit tests.

pub(crate) use crate::num::kernel::xorshift32;

/// Marsaglia's 64-bit xorshift (13, 7, 17) from `x` (non-zero): each call returns the
/// next state.
pub(crate) fn xorshift64(mut x: u64) -> impl FnMut() -> u64 {
    move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x
    }
}
