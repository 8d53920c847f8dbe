#![no_main]
//! cargo fuzz run raster

#[path = "../harness.rs"]
mod harness;

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::raster(data));
