//! A `no_std` Z-buffer 3D rasterizer for microcontroller displays.
//!
//! zraster draws meshes with per-pixel hidden-surface removal (the Z-buffer method)
//! into any [`embedded_graphics`] [`DrawTarget`](embedded_graphics::draw_target::DrawTarget),
//! with fixed-point screen coordinates, a 16-bit depth buffer in memory you provide,
//! and no heap. A mesh is drawn like any embedded-graphics primitive, as a
//! [`Model`] with a [`ModelStyle`] (in bands on the stack: see [`model`]); here the
//! Stanford bunny, Gouraud-shaded, on an RGB565 display and on a 16-grey one:
//!
//! ```
//! use embedded_graphics::{pixelcolor::{Gray4, Rgb565}, prelude::*};
//! use embedded_graphics_simulator::SimulatorDisplay; // your display driver on a device
//! use zraster::{math::{radians, Mat4, Vec3}, Camera, Model, ModelStyle};
//! use zraster_bench_scene::bunny::{BUNNY_FIT, BUNNY_MESH}; // flash tables from examples/obj2rust.rs
//!
//! let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(160, 120));
//! let camera = Camera::look_at(Vec3::new(0.0, 0.0, 1.6), Vec3::default(), Vec3::Y)?
//!     .perspective(radians(40.0), 0.1, 10.0, display.bounding_box().try_into()?)?
//!     .with_model(Mat4::scaling(Vec3::new(BUNNY_FIT, BUNNY_FIT, BUNNY_FIT)));
//! let bunny = Model::new(&BUNNY_MESH, &camera);
//! bunny.into_styled(ModelStyle::gouraud()).draw(&mut display)??; // display error, then zraster's
//! // Any embedded-graphics colour type: the same bunny on a 4-bit greyscale OLED.
//! let mut oled = SimulatorDisplay::<Gray4>::new(Size::new(160, 120));
//! bunny.into_styled(ModelStyle::gouraud()).draw(&mut oled)??;
//! # assert_ne!(display.get_pixel(Point::new(80, 60)), Rgb565::BLACK);
//! # assert_ne!(oled.get_pixel(Point::new(80, 60)), Gray4::BLACK);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Below the model are the calls it makes, for drawing into memory you provide (a
//! whole frame, or [bands](#bands-a-frame-in-a-few-kib) with a vertex cache), with
//! more than one mesh in one depth buffer, or with the other algorithms. A spinning
//! cube on a 160×120 RGB565 display:
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
//! use zraster::math::{radians, Mat4, Vec3};
//! use zraster::{mesh::CUBE, Camera, Frame, RenderOptions, Renderer, Viewport};
//!
//! const W: u32 = 160;
//! const H: u32 = 120;
//! // Memory is yours: colours and 16-bit depths for the frame (or for one band of it).
//! let mut pixels = [Rgb565::BLACK; (W * H) as usize];
//! let mut depth = [0u16; (W * H) as usize];
//! let mut frame = Frame::new(&mut pixels, &mut depth, W, H)?;
//!
//! // The camera: eye, target and up; vertical field of view, near and far planes.
//! let camera = Camera::look_at(Vec3::new(0.0, 1.2, 3.0), Vec3::new(0.0, 0.0, 0.0), Vec3::Y)?
//!     .perspective(radians(45.0), 0.1, 10.0, Viewport::new(W, H)?)?;
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
//! The sections below are the manual: [meshes](#meshes), [the camera](#the-camera),
//! [colour types](#colour-types),
//! [the depth buffer](#the-depth-buffer-and-what-to-draw-into) and what to draw into,
//! [bands](#bands-a-frame-in-a-few-kib), the [other renderers](#other-renderers) and
//! [single triangles](#single-triangles).
//!
//! # What is where
//! - [`Model`] and [`ModelStyle`] ([`model`]): a mesh as an embedded-graphics
//!   `Drawable`, with no buffers of yours.
//! - [`mesh`]: the vertex table and face table (`i16` positions, flash-friendly).
//! - [`camera`]: [`Camera`] (the model, view and projection matrices) and the [`Viewport`].
//! - [`Renderer`]: draws one mesh; [`Renderer::draw`] with the Z-buffer into a
//!   [`DepthTarget`], the other methods by depth sorting (the painter's algorithm), as
//!   hidden-line or as wireframe.
//! - What to draw into: a [`Frame`] (colour and depth in RAM), a [`WithDepth`] (any
//!   display and a [`ZBuffer`]) or [`Bands`] (a display drawn band by band through
//!   [`BandBuffers`], pixel-identical to a whole frame in a few KiB).
//! - [`ZBuffer`] and [`ColorBuffer`]: caller memory for depth and colour, a whole frame
//!   or a band of rows.
//! - [`shade`]: lights and materials (flat, Lambert, Gouraud) for every
//!   embedded-graphics colour type, dithered on 1-, 2- and 4-bit displays.
//! - [`fill_triangle`] and [`ScreenVertex`]: single screen-space triangles.
//! - [`Error`] and [`DrawError`]: what can go wrong; nothing panics on bad input.
//!
//! # Meshes
//!
//! A [`Mesh`](mesh::Mesh) is two tables, as in the classic polygon model: a **vertex
//! table** of positions and a **face table** of polygons, each a list of indices into
//! the vertex table with a material (for an `Rgb888` material, its colour). Positions
//! are `i16` triples times one `scale` (6 bytes a vertex: a model's extent in 65536
//! steps), and the tables are borrowed slices, so a `const` mesh stays in flash. Faces
//! are listed counter-clockwise as seen from their front; with
//! [`Cull::Back`] (the default) faces turned away are not drawn. A mesh of triangles
//! ([`Mesh::triangles`](mesh::Mesh::triangles), 6 bytes a face) takes the fastest paths;
//! polygons ([`Mesh::new`](mesh::Mesh::new)) are drawn as fans. Optional tables of face
//! and vertex normals serve lighting ([`shade`]); `examples/obj2rust.rs` turns an OBJ
//! file into such tables.
//!
//! ```
//! use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
//! use zraster::{math::{radians, Vec3}, mesh::Mesh, Camera, Frame, RenderOptions, Renderer, Viewport};
//!
//! // A square of side 2 around the origin, facing +z: 16384 steps of 1/16384 are 1.0.
//! const SQUARE_POSITIONS: [[i16; 3]; 4] =
//!     [[-16384, -16384, 0], [16384, -16384, 0], [16384, 16384, 0], [-16384, 16384, 0]];
//! const SQUARE_TRIANGLES: [[u16; 3]; 2] = [[0, 1, 2], [0, 2, 3]]; // counter-clockwise
//! const SQUARE: Mesh<'static, Rgb888> =
//!     Mesh::triangles(&SQUARE_POSITIONS, 1.0 / 16384.0, &SQUARE_TRIANGLES, Rgb888::new(255, 0, 0));
//! SQUARE.validate()?; // every index in range: drawing it cannot fail on its input
//!
//! let mut pixels = [Rgb565::new(0, 0, 0); 32 * 32];
//! let mut depth = [0u16; 32 * 32];
//! let mut frame = Frame::new(&mut pixels, &mut depth, 32, 32)?;
//! frame.clear(Rgb565::new(0, 0, 0));
//! let xf = Camera::look_at(Vec3::new(0.0, 0.0, 4.0), Vec3::default(), Vec3::Y)?
//!     .perspective(radians(45.0), 0.1, 10.0, Viewport::new(32, 32)?)?;
//! let mut renderer = Renderer::new(&SQUARE, &xf, RenderOptions::default())?;
//! renderer.draw(&mut frame)?;
//! assert_eq!(renderer.stats().drawn, 2);
//! assert_eq!(frame.color().pixel(16, 16), Some(Rgb565::new(31, 0, 0))); // Rgb888 red, as Rgb565
//! assert_eq!(frame.color().pixel(1, 1), Some(Rgb565::new(0, 0, 0))); // outside the square
//! # Ok::<(), zraster::Error>(())
//! ```
//!
//! # The camera
//!
//! A [`Camera`] places a mesh on the screen: the **model** matrix puts the mesh in the
//! world (turn, move, scale it; a new one each frame animates it), the **view** matrix
//! is where the eye is, what it looks at and which way is up
//! ([`Camera::look_at`]), the **projection** is the lens
//! ([`perspective`](camera::LookAt::perspective): the vertical field of view and the
//! near and far clip planes; or [`orthographic`](camera::LookAt::orthographic): a
//! box, for plans and elevations), and the [`Viewport`] is the screen rectangle. A
//! view that does not say which way it looks (the eye at the target, or up along the
//! line of sight) is an [`Error::DegenerateView`], not a blank frame.
//!
//! **Angles are radians**, everywhere: fields of view and [`Mat4`](math::Mat4)
//! rotations alike; [`math::radians`] converts degrees (`radians(45.0)`). The matrices are `f32` and
//! worked out once per frame; each vertex then goes through a fixed-point form of
//! their product. Parts of faces nearer than the near plane, farther than the far
//! plane or far outside the screen are clipped.
//!
//! The depth buffer's 16 bits are spread between near and far, so the near plane sets
//! the precision: put it as far out as the scene allows, or let
//! [`Camera::fit_depth`] fit both planes to the mesh.
//!
//! ```
//! use embedded_graphics::pixelcolor::Rgb565;
//! use zraster::math::{radians, Mat4, Vec3};
//! use zraster::{mesh::CUBE, Camera, Frame, RenderOptions, Renderer, Viewport};
//!
//! let mut pixels = [Rgb565::new(0, 0, 0); 64 * 32];
//! let mut depth = [0u16; 64 * 32];
//! let mut frame = Frame::new(&mut pixels, &mut depth, 64, 32)?;
//! frame.clear(Rgb565::new(0, 0, 0));
//! // Looking down −z from 5 units away; the unit cube moved to the right of the centre.
//! let camera = Camera::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::default(), Vec3::Y)?
//!     .perspective(radians(40.0), 1.0, 10.0, Viewport::new(64, 32)?)?;
//! let moved = camera.with_model(Mat4::translation(Vec3::new(1.0, -0.5, -0.5)));
//! Renderer::new(&CUBE, &moved, RenderOptions::default())?.draw(&mut frame)?;
//! let lit = |x| frame.color().pixel(x, 16) != Some(Rgb565::new(0, 0, 0));
//! assert!(lit(48) && !lit(16)); // drawn right of the centre, not left of it
//! # Ok::<(), zraster::Error>(())
//! ```
//!
//! # Colour types
//!
//! Materials are `Rgb888` colours, and they draw on a display of any embedded-graphics
//! colour type ([`shade::DisplayColor`]): `Rgb565`, `Bgr565`, `Rgb555`, `Bgr555`,
//! `Rgb666`, `Bgr666`, `Rgb888` and `Bgr888` get each channel lit and rounded to its
//! depth, `Gray8` the colour's luma; `Gray4`, `Gray2` and `BinaryColor` get the luma
//! ordered-dithered (a 4×4 Bayer pattern), so shading survives on greyscale OLEDs,
//! e-paper and monochrome panels. The frame's colour type is the display's. The
//! Stanford bunny, Gouraud-shaded, on a 256×64 16-grey SSD1322:
//!
//! ```
//! use embedded_graphics::{pixelcolor::Gray4, prelude::*};
//! use zraster::{math::{radians, Mat4, Vec3}, shade::Shading, Camera, Frame, RenderOptions, Renderer, Viewport};
//! use zraster_bench_scene::bunny::{BUNNY_FIT, BUNNY_MESH}; // flash tables from examples/obj2rust.rs
//!
//! let (mut pixels, mut depth) = ([Gray4::BLACK; 256 * 64], [0u16; 256 * 64]);
//! let mut frame = Frame::new(&mut pixels, &mut depth, 256, 64)?;
//! frame.clear(Gray4::BLACK);
//! let fit = Mat4::rotation_y(radians(30.0)) * Mat4::scaling(Vec3::new(BUNNY_FIT, BUNNY_FIT, BUNNY_FIT));
//! let camera = Camera::look_at(Vec3::new(0.0, 0.0, 1.6), Vec3::default(), Vec3::Y)?
//!     .perspective(radians(40.0), 0.1, 10.0, Viewport::new(256, 64)?)?
//!     .with_model(fit);
//! let options = RenderOptions { shading: Shading::Gouraud, ..Default::default() };
//! Renderer::new(&BUNNY_MESH, &camera, options)?.draw(&mut frame)?;
//! // frame.flush(&mut ssd1322)?; sends it in one fill_contiguous
//! # let mut levels = [0u32; 16];
//! # frame.color().as_slice().iter().for_each(|p| levels[usize::from(p.luma())] += 1);
//! # assert!(levels[0] > 256 * 64 / 2 && levels[1..].iter().filter(|&&n| n > 20).count() >= 8);
//! # Ok::<(), zraster::Error>(())
//! ```
//!
//! # The depth buffer, and what to draw into
//!
//! A [`ZBuffer`] holds one 16-bit depth per pixel (2 bytes, in a slice you provide):
//! 0 is the near plane, 65535 ([`ZBuffer::FAR`]) the far plane and the cleared value. A
//! pixel of a face is drawn only where it is nearer than what the buffer holds (the
//! [`DepthTest`] can be changed), and its depth is then stored. So faces may be drawn
//! in any order, several meshes into the same buffer, and interpenetrating or
//! cyclically overlapping faces come out right, which depth sorting cannot do.
//!
//! [`Renderer::draw`] draws into a [`DepthTarget`]: you say what memory you have and
//! the renderer picks the way to draw.
//!
//! | you have | target | how it draws |
//! |---|---|---|
//! | RAM for colour and depth | [`Frame`] | depth test and colour write in one loop; [`Frame::flush`] sends the frame |
//! | a display, RAM for depth | [`WithDepth`] | each row of a face that passes the test goes to the display as a run (`fill_solid`) |
//! | a display, a few KiB | [`Bands`] | band by band through [`BandBuffers`] (below) |
//!
//! A [`Frame`] or [`WithDepth`] is cleared by you, once a frame; then every mesh of the
//! frame is drawn into it. Two meshes, the far one drawn last, into a frame and into a
//! display with a Z-buffer, give the same picture:
//!
//! ```
//! use embedded_graphics::{mock_display::MockDisplay, pixelcolor::{Rgb565, Rgb888}, prelude::*};
//! use zraster::math::{radians, Mat4, Vec3};
//! use zraster::mesh::{Mesh, CUBE_POSITIONS};
//! use zraster::{Camera, Frame, RenderOptions, Renderer, Viewport, WithDepth, ZBuffer};
//!
//! // The unit cube's six faces (mesh::CUBE_FACES) as triangles, in one colour each.
//! const CUBE_TRIANGLES: [[u16; 3]; 12] = [
//!     [0, 1, 2], [0, 2, 3], [1, 5, 6], [1, 6, 2], [2, 6, 7], [2, 7, 3],
//!     [3, 7, 4], [3, 4, 0], [0, 4, 5], [0, 5, 1], [7, 6, 5], [7, 5, 4],
//! ];
//! let near = Mesh::triangles(&CUBE_POSITIONS, 1.0 / 16384.0, &CUBE_TRIANGLES, Rgb888::new(255, 0, 0));
//! let far = Mesh::triangles(&CUBE_POSITIONS, 1.0 / 16384.0, &CUBE_TRIANGLES, Rgb888::new(0, 0, 255));
//! let camera = Camera::look_at(Vec3::new(0.5, 0.5, 4.0), Vec3::new(0.5, 0.5, 0.0), Vec3::Y)?
//!     .perspective(radians(40.0), 1.0, 10.0, Viewport::new(64, 64)?)?;
//! let (near_xf, far_xf) = (camera, camera.with_model(Mat4::translation(Vec3::new(0.4, 0.4, -1.0))));
//! let options = RenderOptions::default();
//!
//! // Into a frame in RAM.
//! let mut pixels = [Rgb565::BLACK; 64 * 64];
//! let mut depth = [0u16; 64 * 64];
//! let mut frame = Frame::new(&mut pixels, &mut depth, 64, 64)?;
//! frame.clear(Rgb565::BLACK);
//! Renderer::new(&near, &near_xf, options)?.draw(&mut frame)?;
//! Renderer::new(&far, &far_xf, options)?.draw(&mut frame)?;
//! assert_eq!(frame.color().pixel(32, 32), Some(Rgb565::RED)); // the near cube hides the far one
//!
//! // Into a display, with only the depths in RAM.
//! let mut display = MockDisplay::<Rgb565>::new();
//! display.set_allow_overdraw(true); // runs of the far cube land on pixels already drawn
//! let mut zdepth = [0u16; 64 * 64];
//! let mut zbuf = ZBuffer::new(&mut zdepth, 64, 64)?;
//! zbuf.clear();
//! Renderer::new(&near, &near_xf, options)?.draw(&mut WithDepth::new(&mut display, &mut zbuf)).unwrap();
//! Renderer::new(&far, &far_xf, options)?.draw(&mut WithDepth::new(&mut display, &mut zbuf)).unwrap();
//! for (x, y) in [(32, 32), (20, 50), (50, 14), (2, 2)] {
//!     let shown = display.get_pixel(Point::new(x, y)).unwrap_or(Rgb565::BLACK);
//!     assert_eq!(Some(shown), frame.color().pixel(x, y), "pixel ({x}, {y})");
//! }
//! assert_eq!(zbuf.as_slice(), frame.depth().as_slice());
//! # Ok::<(), zraster::Error>(())
//! ```
//!
//! # Bands: a frame in a few KiB
//!
//! A 320×240 RGB565 frame and its depths take 300 KiB; most microcontrollers have far
//! less. [`Bands`] draws the frame in horizontal bands of a few rows instead: each band
//! is cleared, drawn into [`BandBuffers`] (one band of colour and depth) and sent to the
//! display with one `fill_contiguous`. The picture, its depths and the stats are
//! exactly those of a whole [`Frame`]. Each band walks the mesh again, so for larger
//! meshes give the renderer a vertex cache ([`Renderer::with_cache`], 8 bytes a vertex:
//! each vertex transformed once a frame) and the band buffers bins
//! ([`BandBuffers::bins_needed`] `u16`s: the visible triangles sorted by band once a
//! frame, so that a band visits only those that reach it).
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
//! use zraster::{math::{radians, Vec3}, mesh::CUBE, BandBuffers, Bands, CachedVertex, Camera, Frame, RenderOptions, Renderer, Viewport};
//!
//! let xf = Camera::look_at(Vec3::new(2.0, 1.5, 3.0), Vec3::new(0.5, 0.5, 0.5), Vec3::Y)?
//!     .perspective(radians(45.0), 0.1, 10.0, Viewport::new(48, 40)?)?;
//! // The whole frame, for comparison: 48 × 40 × 4 bytes.
//! let (mut pixels, mut depth) = ([Rgb565::BLACK; 48 * 40], [0u16; 48 * 40]);
//! let mut whole = Frame::new(&mut pixels, &mut depth, 48, 40)?;
//! whole.clear(Rgb565::BLACK);
//! Renderer::new(&CUBE, &xf, RenderOptions::default())?.draw(&mut whole)?;
//!
//! // Bands of 8 rows: 48 × 8 × 4 bytes, a vertex cache and bins. The display here is a
//! // colour buffer; on a device it is the display driver.
//! let mut shown = [Rgb565::WHITE; 48 * 40];
//! let mut display = zraster::ColorBuffer::new(&mut shown, 48, 40)?;
//! let (mut band_color, mut band_depth) = ([Rgb565::BLACK; 48 * 8], [0u16; 48 * 8]);
//! let mut bins = [0u16; BandBuffers::<Rgb565>::bins_needed(12, 40, 8)]; // at most 12 triangles
//! let mut buffers = BandBuffers::new(&mut band_color, &mut band_depth, 48, 8, 40, &mut bins)?;
//! let mut cache = [CachedVertex::EMPTY; 8];
//! let mut renderer = Renderer::with_cache(&CUBE, &xf, RenderOptions::default(), &mut cache)?;
//! renderer.draw(&mut Bands::new(&mut display, &mut buffers, Rgb565::BLACK))?;
//! assert_eq!(display.as_slice(), whole.color().as_slice());
//! # Ok::<(), zraster::Error>(())
//! ```
//!
//! [`Bands::after_band`] calls a closure with each band before it is sent, to draw an
//! overlay (text, a cursor) into it or to read its depths.
//!
//! # Other renderers
//!
//! Besides the Z-buffer, a [`Renderer`] draws by depth sorting
//! ([`draw_depth_sorted`](Renderer::draw_depth_sorted), the painter's algorithm: no
//! depth buffer, faces sorted far to near; wrong for interpenetrating or cyclically
//! overlapping faces), as hidden-line ([`draw_hidden_line`](Renderer::draw_hidden_line):
//! the edges a Z-buffer leaves visible) or as wireframe
//! ([`draw_wireframe`](Renderer::draw_wireframe)), each into any `DrawTarget`.
//!
//! # Single triangles
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
//! - Front faces are counter-clockwise as seen with y up (OpenGL, OBJ, and the classic
//!   back-face rule `V1 × V2 > 0`); on the y-down screen their [`signed_area`] is negative.
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
pub mod damage;
mod error;
mod fill;
pub mod fixed;
mod geometry;
pub mod math;
pub mod mesh;
pub mod model;
mod num;
mod raster;
mod render;
pub mod scene;
pub mod shade;
pub mod shader;
pub mod state;
#[cfg(test)]
mod testing;
pub mod texture;

pub use buffer::{AfterBand, BandBuffers, Bands, ColorBuffer, DepthTest, Frame, ZBuffer};
pub use camera::{Camera, Viewport};
pub use error::{DrawError, Error};
pub use fill::{fill_triangle, fill_triangle_shaded};
pub use model::{Model, ModelStyle};
pub use raster::{depth_at, signed_area, Facing, Plane, ScreenVertex, SpanStats};
pub use render::{Binning, Unbinned};
pub use render::{
    CachedVertex, Cull, DepthSort, DepthTarget, FrameStats, RenderOptions, Renderer, WithDepth,
};
pub use render::{TexturedTarget, Texturing, UvMode};
pub use scene::Scene;

#[doc(hidden)]
pub use num::kernel::check_band_carry_kernel;
#[doc(hidden)]
pub use num::kernel::check_band_carry_v6m_kernel;
#[doc(hidden)]
pub use num::kernel::check_band_faces_kernel;
#[doc(hidden)]
pub use num::kernel::check_band_faces_v6m_kernel;
#[doc(hidden)]
pub use num::kernel::check_bin_kernel;
#[doc(hidden)]
pub use num::kernel::check_cull_kernel;
#[doc(hidden)]
pub use num::kernel::check_faces_kernel;
#[doc(hidden)]
pub use num::kernel::check_faces_v6m_kernel;
#[doc(hidden)]
pub use num::kernel::check_light_kernel;
#[doc(hidden)]
pub use num::kernel::check_place_kernel;
#[doc(hidden)]
pub use num::kernel::check_place_v6m_kernel;
/// For the bench firmware: check the assembly fill and span loops against their
/// portable twins on the target (the number of differing cases; see
/// `src/num/kernel/`).
#[doc(hidden)]
pub use num::kernel::{
    check_fill_kernel, check_rows_kernel, check_rows_walk_kernel, check_span_kernel,
    check_texel_kernel,
};

/// The largest width or height of a Z-buffer or colour buffer, in pixels (8192).
///
/// It bounds the depth accumulator's drift along a row (see [`fixed`]).
pub const MAX_DIMENSION: u32 = 8192;

/// The README's code blocks, compiled as doctests so they stay true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
