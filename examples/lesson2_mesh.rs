//! Lesson 2: a mesh. A solid is two tables: a vertex table of positions and a face table
//! of polygons, each a list of indices into the vertex table and a colour. Faces are
//! listed counter-clockwise as seen from outside, so the renderer can drop those that
//! turn away from the eye (back-face culling) before drawing anything.
//!
//! `cargo run --release --example lesson2_mesh` writes `lesson2_mesh.png` and prints
//! the time a frame takes and what was culled; `--features window` shows it turning.
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
#[cfg(feature = "window")]
use embedded_graphics_simulator::{SimulatorEvent::Quit, Window};
use std::time::{Duration, Instant};
use zraster::math::{radians, Mat4, Vec3};
use zraster::mesh::{Face, Mesh};
use zraster::{Camera, Frame, FrameStats, RenderOptions, Renderer, Viewport};

pub const W: u32 = 160;
pub const H: u32 = 120;
#[cfg(not(feature = "window"))]
const FRAMES: u32 = 100; // headless: 100 frames, then the PNG
#[cfg(feature = "window")]
const FRAMES: u32 = u32::MAX; // in the window: until it is closed

// A square pyramid. The vertex table: i16 steps of 1/16384 (16384 is one unit), 6 bytes
// a vertex, around the origin: the base corners front-left, front-right, back-right,
// back-left, then the apex.
const S: i16 = 16384;
#[rustfmt::skip]
const CORNERS: [[i16; 3]; 5] =
    [[-S, -12288, S], [S, -12288, S], [S, -12288, -S], [-S, -12288, -S], [0, 12288, 0]];
// The face table: the base is a quad (drawn as two triangles), the sides triangles.
#[rustfmt::skip]
const FACES: [Face<Rgb888>; 5] = [
    Face { vertices: &[0, 3, 2, 1], material: Rgb888::new(128, 128, 128) }, // base
    Face { vertices: &[0, 1, 4], material: Rgb888::new(230, 40, 40) },      // front
    Face { vertices: &[1, 2, 4], material: Rgb888::new(40, 200, 60) },      // right
    Face { vertices: &[2, 3, 4], material: Rgb888::new(50, 90, 240) },      // back
    Face { vertices: &[3, 0, 4], material: Rgb888::new(240, 220, 40) },     // left
];
// Both tables are consts: on a microcontroller the whole mesh stays in flash.
// (`zraster::mesh::CUBE` is a ready cube made the same way.)
pub const PYRAMID: Mesh = Mesh::new(&CORNERS, 1.0 / 16384.0, &FACES);

/// Draw the pyramid turned `angle` radians about its axis; the counts of that frame.
pub fn render(frame: &mut Frame<Rgb565>, angle: f32) -> Result<FrameStats, zraster::Error> {
    frame.clear(Rgb565::BLACK);
    let camera = Camera::look_at(Vec3::new(0.0, 1.5, 4.0), Vec3::default(), Vec3::Y)?
        .perspective(radians(45.0), 0.1, 10.0, Viewport::new(W, H)?)?
        .with_model(Mat4::rotation_x(0.3 * angle.sin()) * Mat4::rotation_y(angle));
    // Default options: flat colours, back faces culled (`Cull::Back`).
    let mut renderer = Renderer::new(&PYRAMID, &camera, RenderOptions::default())?;
    renderer.draw(frame)?;
    Ok(renderer.stats())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    PYRAMID.validate()?; // every index in range: drawing it cannot fail on its tables
    let (mut pixels, mut depth) = ([Rgb565::BLACK; (W * H) as usize], [0; (W * H) as usize]);
    let mut frame = Frame::new(&mut pixels, &mut depth, W, H)?;
    let mut display = SimulatorDisplay::new(Size::new(W, H));
    let settings = OutputSettingsBuilder::new().scale(2).build();
    #[cfg(feature = "window")]
    let mut window = Window::new("zraster lesson 2: a mesh", &settings);
    let mut drawing = Duration::ZERO;
    for n in 1..=FRAMES {
        let start = Instant::now();
        let stats = render(&mut frame, n as f32 * 0.03)?;
        drawing += start.elapsed();
        if n % 100 == 0 {
            let ms = drawing.as_secs_f64() * 10.0; // 1000 ms / 100 frames
            println!("{ms:.3} ms/frame, {:.0} fps", 1000.0 / ms);
            let (of, culled, drawn) = (stats.triangles_in, stats.culled, stats.drawn);
            println!("  last frame: of {of} triangles, {culled} culled, {drawn} drawn");
            drawing = Duration::ZERO;
        }
        frame.flush(&mut display)?;
        #[cfg(feature = "window")]
        {
            window.update(&display);
            if window.events().any(|e| e == Quit) {
                break;
            }
        }
    }
    #[cfg(not(feature = "window"))]
    {
        let image = display.to_rgb_output_image(&settings);
        image.save_png("lesson2_mesh.png")?;
        println!("wrote lesson2_mesh.png");
    }
    Ok(())
}
