//! Helpers shared by the unit tests.

/// Marsaglia's 32-bit xorshift (13, 17, 5) from `seed` (non-zero): reproducible test
/// inputs without a dependency. Each call returns the next state.
pub(crate) fn xorshift32(mut x: u32) -> impl FnMut() -> u32 {
    move || {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        x
    }
}

/// The 64-bit xorshift (13, 7, 17), likewise.
pub(crate) fn xorshift64(mut x: u64) -> impl FnMut() -> u64 {
    move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x
    }
}
