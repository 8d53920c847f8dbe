#![no_main]
//! cargo fuzz run obj

use zraster_fuzz_harness as harness;

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::obj(data));
