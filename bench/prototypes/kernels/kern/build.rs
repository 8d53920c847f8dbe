//! Capability cfgs, decided from the target as zraster's build.rs does:
//! - `zk_v6m`: ARMv6-M (Cortex-M0/M0+): Arm without 32-bit atomics;
//! - `zk_thumb2`: ARMv7-M and up (Cortex-M3/M4/M7): Arm with 32-bit atomics;
//! - `zk_dsp`: ARMv7E-M (Cortex-M4/M7), the DSP extension's SIMD (USUB16, SEL, PKHTB,
//!   USADA8). Stable Rust does not expose Arm target features to cfg, so it is read
//!   from the target name.
fn main() {
    println!("cargo::rustc-check-cfg=cfg(zk_v6m, zk_thumb2, zk_dsp)");
    println!("cargo::rerun-if-changed=build.rs");
    let var = |k: &str| std::env::var(k).unwrap_or_default();
    let arm = var("CARGO_CFG_TARGET_ARCH") == "arm";
    let atomic32 = var("CARGO_CFG_TARGET_HAS_ATOMIC").split(',').any(|w| w == "32");
    let set = |name: &str, on: bool| {
        if on {
            println!("cargo::rustc-cfg={name}");
        }
    };
    set("zk_v6m", arm && !atomic32);
    set("zk_thumb2", arm && atomic32);
    set("zk_dsp", arm && var("TARGET").starts_with("thumbv7em"));
}
