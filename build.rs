//! Capability cfgs for the target-specific code in `src/num/`, decided once here from
//! the target, so that no other file names an architecture:
//! - `zraster_armv6m`: 32-bit Arm without a divide instruction or a 32×32→64-bit
//!   multiply (ARMv6-M: Cortex-M0, M0+, M1), recognised as Arm without 32-bit atomics;
//! - `zraster_thumb2`: 32-bit Arm with both (ARMv7-M, ARMv8-M mainline: Cortex-M3,
//!   M4, M7, M33);
//! - `zraster_soft_float`: 32-bit Arm without hardware floating point, where vertices
//!   are projected in integers;
//! - `zraster_wide`: 64-bit registers with a 64-bit divide instruction (x86-64, AArch64);
//! - `zraster_thumb`: Thumb code (every Cortex-M target: the target name starts with
//!   `thumb`; Arm's instruction-set mode is not a cfg), for which `src/num/kernel.rs`
//!   has assembly loops;
//! - `zraster_dsp`: the DSP extension's SIMD instructions (ARMv7E-M: Cortex-M4, M7; the
//!   target name starts with `thumbv7em`, since stable Rust does not expose Arm target
//!   features to `cfg`), for `src/num/kernel.rs`'s span loop;
//! - `zraster_x86_64`: x86-64 (SSE2 always there), for `src/num/kernel/`'s vertex and
//!   row loops;
//! - `zraster_ram_code`: the `ram-code` feature on a bare-metal target (`target_os =
//!   "none"`), where the innermost loops go to the `.data.zraster` section.
fn main() {
    println!("cargo::rustc-check-cfg=cfg(zraster_armv6m, zraster_thumb2, zraster_soft_float, zraster_wide, zraster_thumb, zraster_dsp, zraster_ram_code, zraster_x86_64)");
    println!("cargo::rerun-if-changed=build.rs");
    let var = |k: &str| std::env::var(k).unwrap_or_default();
    let arm = var("CARGO_CFG_TARGET_ARCH") == "arm";
    let atomic32 = var("CARGO_CFG_TARGET_HAS_ATOMIC")
        .split(',')
        .any(|w| w == "32");
    let set = |name: &str, on: bool| {
        if on {
            println!("cargo::rustc-cfg={name}");
        }
    };
    set("zraster_armv6m", arm && !atomic32);
    set("zraster_thumb2", arm && atomic32);
    set(
        "zraster_soft_float",
        arm && var("CARGO_CFG_TARGET_ABI") != "eabihf",
    );
    set("zraster_thumb", arm && var("TARGET").starts_with("thumb"));
    set("zraster_dsp", arm && var("TARGET").starts_with("thumbv7em"));
    set(
        "zraster_ram_code",
        std::env::var_os("CARGO_FEATURE_RAM_CODE").is_some()
            && var("CARGO_CFG_TARGET_OS") == "none",
    );
    // x86-64 (SSE2 always there), for `src/num/kernel/`'s vertex and row loops.
    set("zraster_x86_64", var("CARGO_CFG_TARGET_ARCH") == "x86_64");
    set(
        "zraster_wide",
        var("CARGO_CFG_TARGET_POINTER_WIDTH") == "64",
    );
}
