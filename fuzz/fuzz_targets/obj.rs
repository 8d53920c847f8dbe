#![no_main]
//! cargo fuzz run obj

#[path = "../harness.rs"]
mod harness;

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::obj(data));
