//! Put memory.x where the linker finds it; set zraster's capability cfgs for its
//! kernel source built into the firmware (src/main.rs, `mod texel`), as zraster's own
//! build.rs sets them.
use std::{env, fs, path::PathBuf};

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").unwrap());
    fs::copy("memory.x", out.join("memory.x")).unwrap();
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo::rustc-check-cfg=cfg(zraster_thumb, zraster_dsp)");
    let target = env::var("TARGET").unwrap_or_default();
    if target.starts_with("thumb") {
        println!("cargo::rustc-cfg=zraster_thumb");
    }
    if target.starts_with("thumbv7em") {
        println!("cargo::rustc-cfg=zraster_dsp");
    }
}
