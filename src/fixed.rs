//! Fixed-point conventions and the few integer helpers the rasterizer needs.
//!
//! # Screen coordinates: 28.4
//! `x` and `y` are `i32` in units of 1/16 pixel ([`SUBPIXEL_BITS`] = 4). The pixel
//! with integer coordinates (i, j) covers `[16i, 16i + 16) × [16j, 16j + 16)` and is
//! sampled at its centre `(16i + 8, 16j + 8)`. Accepted vertices satisfy
//! `|x|, |y| ≤ GUARD_BAND` = 2²⁴ (±1,048,576 pixels), so every coordinate difference is
//! below 2²⁵ and every product of two differences below 2⁵¹: edge functions and twice
//! the signed area are exact in `i64`.
//!
//! # Depth: 16.16
//! A vertex's depth is a `u32` with 16 fractional bits, at most [`MAX_DEPTH`]
//! (65535.0). The stored Z-buffer value is the depth rounded to the nearest integer.
//! Depth differences are below 2³², so the plane numerators `Δz·Δy` are below 2⁵⁸ and
//! `16·Δz·Δy` below 2⁶²: exact in `i64`.
//!
//! In the pixel loop depth is a `u32` accumulator `z·2¹⁶ + 2¹⁵` (the bias rounds, and
//! keeps the value away from 0 and 2³²): one wrapping add per pixel. Rounding the slope
//! to 16.16 costs less than 1/65536 per pixel stepped, so over a row of at most
//! [`MAX_DIMENSION`](crate::MAX_DIMENSION) = 8192 pixels the drift is below 2¹³ (1/8 of
//! a depth unit), far inside the bias margin of 2¹⁵: the accumulator never wraps.

/// Fractional bits of a screen coordinate.
pub const SUBPIXEL_BITS: u32 = 4;
/// One pixel in screen-coordinate units (16).
pub const SUBPIXEL: i32 = 1 << SUBPIXEL_BITS;
/// The largest magnitude of an accepted screen coordinate, in 1/16 pixel (2²⁴).
pub const GUARD_BAND: i32 = 1 << 24;
/// The largest vertex depth, 65535.0 in 16.16.
pub const MAX_DEPTH: u32 = 65535 << 16;
