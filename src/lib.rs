//! A `no_std` Z-buffer 3D rasterizer for microcontroller displays.
//!
//! zraster draws meshes with per-pixel hidden-surface removal (the Z-buffer method)
//! into any [`embedded_graphics`] [`DrawTarget`](embedded_graphics::draw_target::DrawTarget),
//! with fixed-point screen coordinates, a 16-bit depth buffer in memory you provide,
//! and no heap. A spinning cube on a 160×120 RGB565 display:
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
//! use zraster::camera::{Transform, Viewport};
//! use zraster::math::{Mat4, Vec3};
//! use zraster::{mesh::CUBE, Frame, RenderOptions, Renderer};
//!
//! const W: u32 = 160;
//! const H: u32 = 120;
//! // Memory is yours: colours and 16-bit depths for the frame (or for one band of it).
//! let mut pixels = [Rgb565::BLACK; (W * H) as usize];
//! let mut depth = [0u16; (W * H) as usize];
//! let mut frame = Frame::new(&mut pixels, &mut depth, W, H)?;
//!
//! // The camera: eye, target, vertical field of view in degrees, near and far planes.
//! let camera = Transform::perspective(
//!     Vec3::new(0.0, 1.2, 3.0), Vec3::new(0.0, 0.0, 0.0),
//!     45.0, 0.1, 10.0, Viewport::new(W, H)?,
//! )?;
//! for frame_number in 0..3 {
//!     // The model matrix turns the unit cube about its centre a little each frame.
//!     let spin = Mat4::rotation_y(0.3 * frame_number as f32)
//!         * Mat4::translation(Vec3::new(-0.5, -0.5, -0.5));
//!     frame.clear(Rgb565::BLACK);
//!     let mut renderer = Renderer::new(&CUBE, &camera.with_model(spin), RenderOptions::default())?;
//!     renderer.draw(&mut frame)?;
//!     // frame.flush(&mut display) would send it in one fill_contiguous.
//!     assert!(renderer.stats().drawn >= 2); // two or three faces turn to the camera
//! }
//! assert_ne!(frame.color().pixel(W as i32 / 2, H as i32 / 2), Some(Rgb565::BLACK));
//! # Ok::<(), zraster::Error>(())
//! ```
//!
//! # What is where
//! - [`mesh`]: the vertex table and face table (`i16` positions, flash-friendly).
//! - [`camera`]: the model, view and projection matrices and the [`Viewport`](camera::Viewport).
//! - [`Renderer`]: draws one mesh; [`Renderer::draw`] with the Z-buffer into a
//!   [`DepthTarget`], the other methods by depth sorting (the painter's algorithm), as
//!   hidden-line or as wireframe.
//! - What to draw into: a [`Frame`] (colour and depth in RAM), a [`WithDepth`] (any
//!   display and a [`ZBuffer`]) or [`Bands`] (a display drawn band by band through
//!   [`BandBuffers`], pixel-identical to a whole frame in a few KiB).
//! - [`ZBuffer`] and [`ColorBuffer`]: caller memory for depth and colour, a whole frame
//!   or a band of rows.
//! - [`shade`]: lights and materials (flat, Lambert, Gouraud; dithering for 1-bit).
//! - [`fill_triangle`] and [`ScreenVertex`]: single screen-space triangles.
//! - [`Error`] and [`DrawError`]: what can go wrong; nothing panics on bad input.
//!
//! Single triangles need no mesh: screen x, y in pixels (y down), depth 0 (near) ..=
//! 65535 (far):
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
//! use zraster::{fill_triangle, ColorBuffer, ScreenVertex, ZBuffer};
//!
//! let mut pixels = [Rgb565::BLACK; 32 * 24];
//! let mut depth = [0u16; 32 * 24];
//! let mut frame = ColorBuffer::new(&mut pixels, 32, 24)?;
//! let mut zbuf = ZBuffer::new(&mut depth, 32, 24)?;
//! zbuf.clear();
//! let v = |x, y, z| ScreenVertex::from_pixels(x, y, z);
//! let far = [v(0, 0, 9000)?, v(32, 0, 9000)?, v(0, 24, 9000)?];
//! let near = [v(4, 4, 1000)?, v(28, 4, 1000)?, v(4, 20, 1000)?];
//! // The near triangle first: the far one is hidden where they overlap.
//! fill_triangle(&mut frame, &mut zbuf, &near, Rgb565::RED).unwrap();
//! fill_triangle(&mut frame, &mut zbuf, &far, Rgb565::BLUE).unwrap();
//! assert_eq!(frame.pixel(5, 5), Some(Rgb565::RED));
//! assert_eq!(frame.pixel(1, 1), Some(Rgb565::BLUE));
//! assert_eq!(zbuf.depth(5, 5), Some(1000));
//! # Ok::<(), zraster::Error>(())
//! ```
//!
//! # Conventions
//! - Screen coordinates are 28.4 fixed point (see [`fixed`]); pixel (i, j) is sampled
//!   at its centre (i + ½, j + ½); edges follow the top-left rule.
//! - Depth is 16-bit, smaller is nearer, cleared to 65535 ([`ZBuffer::FAR`]).
//! - Front faces are counter-clockwise as seen with y up (OpenGL, OBJ, and the seeds'
//!   `V1 × V2 > 0`); on the y-down screen their [`signed_area`] is negative.
#![no_std]
#![deny(missing_docs)]
#![deny(unsafe_code)]
#![deny(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]
#![cfg_attr(
    test,
    allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)
)]

#[cfg(test)]
extern crate std;

mod band;
mod buffer;
pub mod camera;
mod error;
mod fill;
pub mod fixed;
mod geometry;
pub mod math;
pub mod mesh;
mod num;
mod raster;
mod render;
pub mod shade;
#[cfg(test)]
mod testing;

pub use buffer::{AfterBand, BandBuffers, Bands, ColorBuffer, DepthTest, Frame, ZBuffer};
pub use error::{DrawError, Error};
pub use fill::{fill_triangle, fill_triangle_shaded};
pub use raster::{depth_at, signed_area, Facing, Plane, ScreenVertex, SpanStats};
pub use render::{
    CachedVertex, Cull, DepthSort, DepthTarget, FrameStats, RenderOptions, Renderer, WithDepth,
};

/// For the bench firmware: checks the assembly fill loop against its portable twin on
/// the target (the number of differing cases; see `src/num/kernel.rs`).
#[doc(hidden)]
pub use num::kernel::check_fill_kernel;

/// The largest width or height of a Z-buffer or colour buffer, in pixels (8192).
///
/// It bounds the depth accumulator's drift along a row (see [`fixed`]).
pub const MAX_DIMENSION: u32 = 8192;

/// The README's code blocks, compiled as doctests so they stay true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
