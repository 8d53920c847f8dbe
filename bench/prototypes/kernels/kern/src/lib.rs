//! Prototype inner loops for zraster on Cortex-M: buffer fill and the depth-tested flat
//! span, each as a `core::arch::asm!` kernel (ARMv7E-M / ARMv7-M and ARMv6-M) with a
//! portable Rust twin that gives identical results, plus plain-Rust variants for
//! comparison. Host tests (`cargo test`) check the twins against plain references; the
//! firmware in `../fw` checks each asm kernel against its twin on random inputs.
#![no_std]

#[cfg(test)]
extern crate std;

pub mod fill;
pub mod span;
