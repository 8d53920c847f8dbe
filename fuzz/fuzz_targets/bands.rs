#![no_main]
//! cargo fuzz run bands

#[path = "../harness.rs"]
mod harness;

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::bands(data));
