//! Arithmetic forms that pay on ARMv7-M (Cortex-M3/M4/M7), where the divide
//! instruction is unsigned-friendly and signed-overflow checks cost instructions.

/// [`floor_div32`] by one unsigned division of `n` or `!n`.
#[inline(always)]
pub(crate) fn floor_div32_flip(n: i32, d: i32) -> i32 {
    let m = (n >> 31) as u32; // all ones when n < 0
    (((n as u32 ^ m) / d as u32) ^ m) as i32
}
