//! Assembly loops for Cortex-M, each beside its portable twin: the twin is what every
//! other target runs, and what the host tests and the QEMU bench check the assembly
//! against (`bench/mcu` compares them on the Cortex-M4F and M0+ for every length and
//! alignment it tries, and fails otherwise). The loops: the frame clear
//! ([`fill_u16`](fill::fill_u16)) and the depth-tested span of a flat-coloured row ([`span_less_u16`](span::span_less_u16));
//! a small flat-coloured triangle, set-up and rows ([`small_less_as_u16`](rows::small_less_as_u16),
//! on ARMv7E-M, which runs the span loop's SIMD steps for rows of eight pixels or more;
//! its rows alone are [`rows_less_as_u16`](rows::rows_less_as_u16), checked on their own);
//! on ARMv6-M a small triangle walked by its bounding box and three edge functions, set-up
//! and rows in one routine ([`small_walk_less_as_u16`](rows_v6m::small_walk_less_as_u16)),
//! and the DDA rows of `fill::small`'s own set-up ([`rows_walk_less_as_u16`](rows_v6m::rows_walk_less_as_u16));
//! the cull pass's scan over dropped faces ([`skip_culled`](cull::skip_culled), checked
//! by `check_cull_kernel`), and the same scan binning the drawn faces of a banded frame
//! ([`bin_scan`](bin::bin_scan), checked by `check_bin_kernel`); the vertex cache's
//! usual vertex, transform, projection and entry ([`place_run`](place::place_run),
//! ARMv7E-M with an FPU, checked by `check_place_kernel`; on ARMv6-M
//! [`place_run_v6m`](place_v6m::place_run_v6m), checked by `check_place_v6m_kernel`);
//! a face's flat Lambert colour in 5-6-5 ([`lit_565`](light::lit_565), ARMv7E-M,
//! checked by `check_light_kernel`); the whole frame's face loop, scan, colour, set-up
//! and rows composed from those ([`faces_less`](faces::faces_less), ARMv7E-M, checked
//! by `check_faces_kernel`); on ARMv6-M the whole frame's face loop and the bands'
//! ([`faces_less_v6m`](faces_v6m::faces_less_v6m),
//! [`band_faces_less_v6m`](faces_v6m::band_faces_less_v6m): scan or merge and carry,
//! the colour, a call of the small triangle's set-up), checked by
//! `check_faces_v6m_kernel` and `check_band_faces_v6m_kernel`;
//! and one instruction, the vertex transform's dual multiply-accumulate
//! ([`smlad`](mac::smlad)), checked against its twin by `check_fill_kernel`.
//! On x86-64, checked against their twins by host tests: the vertex cache's usual
//! vertex four at a time in SSE2 ([`place_quads`](place4::place_quads)), a small
//! triangle's rows ([`rows_x86`](rows_x86::rows_x86)) and its set-up with them
//! ([`small_x86`](small_x86::small_x86)); the whole frame's face loop, scan, colour,
//! set-up and rows ([`FacesX86`](faces_x86::FacesX86)).
//!
//! The only `unsafe` code of the crate lives here
//! (`fill`, `span`, `rows`, `rows_v6m`, `cull`, `bin`, `place`, `place_v6m`, `light`,
//! `faces`, `faces_v6m`, `mac`, `texel`, `place4`, `rows_x86`, `small_x86` and `faces_x86`, each with
//! `#![allow(unsafe_code)]`).

/// Marsaglia's 32-bit xorshift (13, 17, 5): the state after `seed` (non-zero), which it
/// also returns. The reproducible inputs of the kernels' checks, on target as in tests.
pub(crate) fn xorshift_next(seed: &mut u32) -> u32 {
    *seed ^= *seed << 13;
    *seed ^= *seed >> 17;
    *seed ^= *seed << 5;
    *seed
}

/// [`xorshift_next`] as a generator from `seed` (non-zero).
pub(crate) fn xorshift32(mut seed: u32) -> impl FnMut() -> u32 {
    move || xorshift_next(&mut seed)
}

/// ARMv6-M assembly functions' entry: lr and r4–r11 saved as AAPCS wants (Thumb-1
/// pushes only low registers and lr, so r8–r11 go through r4–r7).
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! v6m_save {
    () => {
        "push {{r4, r5, r6, r7, lr}}\nmov r4, r8\nmov r5, r9\nmov r6, r10\nmov r7, r11\npush {{r4, r5, r6, r7}}\n"
    };
}

/// Their return: r4–r11 restored as [`v6m_save`] saved them, then to the caller.
#[cfg(all(zraster_thumb, zraster_armv6m))]
macro_rules! v6m_return {
    () => {
        "pop {{r4, r5, r6, r7}}\nmov r8, r4\nmov r9, r5\nmov r10, r6\nmov r11, r7\npop {{r4, r5, r6, r7, pc}}\n"
    };
}

mod bin;
// Before `faces`, which uses the scan's, the colour's and the set-up's macros.
#[macro_use]
mod cull;
mod fill;
#[macro_use]
mod light;
mod mac;
mod place;
mod place4;
mod place_v6m;
// Before `rows`, which uses its SIMD pixel macros.
#[macro_use]
mod span;
#[macro_use]
mod rows;
mod faces;
mod faces_v6m;
mod rows_v6m;
mod rows_x86;
// Before `faces_x86`, which uses the set-up's body.
#[macro_use]
mod small_x86;
mod faces_x86;
mod texel;

pub use bin::check_bin_kernel;
pub(crate) use bin::{bin_scan, BinChains, BIN_KERNEL};
pub use cull::check_cull_kernel;
pub(crate) use cull::{skip_culled, skip_culled_by, CullScan, ScanRegs, XyWord, CULL_KERNEL};
pub use faces::Raw565;
pub(crate) use faces::{
    band_faces_less, faces_less, BandCarry, BandStop, FaceColor, FacesCounts, FacesStop,
    KeptStates, CARRY, FACES_KERNEL, STATE_WORDS,
};
pub use faces::{check_band_carry_kernel, check_band_faces_kernel, check_faces_kernel};
pub(crate) use faces_v6m::{band_faces_less_v6m, faces_less_v6m, FACES_V6M_KERNEL};
pub use faces_v6m::{
    check_band_carry_v6m_kernel, check_band_faces_v6m_kernel, check_faces_v6m_kernel,
};
#[cfg(zraster_x86_64)]
pub(crate) use faces_x86::FacesX86;
pub(crate) use faces_x86::FACES_X86_KERNEL;
#[cfg(test)]
pub(crate) use faces_x86::TWIN as FACES_X86_TWIN;
pub use fill::check_fill_kernel;
pub(crate) use fill::fill_as_u16;
pub use light::check_light_kernel;
#[cfg(test)]
pub(crate) use light::lit_565_portable;
pub(crate) use light::{lit_565, LightBlock};
pub(crate) use mac::smlad;
pub use place::check_place_kernel;
#[cfg(test)]
pub(crate) use place::place_portable;
pub use place::CachedVertex;
pub(crate) use place::{place_run, PlaceBlock, PLACE_KERNEL};
pub(crate) use place4::{place_quads, PLACE4_KERNEL};
pub use place_v6m::check_place_v6m_kernel;
#[cfg(test)]
pub(crate) use place_v6m::place_v6m_portable;
pub(crate) use place_v6m::{place_run_v6m, recip62_low, PlaceV6m, PLACE_V6M_KERNEL};
pub use rows::check_rows_kernel;
pub(crate) use rows::two_bytes;
pub(crate) use rows::{
    small_less_as_u16, small_less_cached, RowsAt, SmallDone, SmallTarget, ROWS_KERNEL,
};
pub use rows_v6m::check_rows_walk_kernel;
pub(crate) use rows_v6m::{
    cache_entries, rows_walk_less_as_u16, Buffers, RowsWalk, WalkEdge, WALK_KERNEL,
};
pub(crate) use rows_x86::{rows_x86, ROWS_X86_KERNEL};
pub(crate) use small_x86::{small_x86, SmallRun, SmallX86, SMALL_X86_KERNEL};
pub use span::check_span_kernel;
pub(crate) use span::{span_kernel_pays, span_less_as_u16};
pub use texel::check_texel_kernel;
pub(crate) use texel::{TexelGrid, TEXEL_KERNEL};
