//! Lesson 4: lighting. One ball, three ways, left to right: `Shading::Flat` (each face
//! in its colour, no light), `Shading::Lambert` (one brightness per face, from the angle
//! between its normal and the light) and `Shading::Gouraud` (the brightness worked out
//! at each vertex from its normal, and blended across the face: a smooth look from 20
//! faces). Normals are unit vectors in Q14 (16384 is 1.0), in tables like the positions.
//!
//! `cargo run --release --example lesson4_lighting` writes `lesson4_lighting.png`;
//! `--features window` shows the ball turning under the light.
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
#[cfg(feature = "window")]
use embedded_graphics_simulator::{SimulatorEvent::Quit, Window};
use std::time::{Duration, Instant};
use zraster::math::{radians, Mat4, Vec3};
use zraster::shade::{Light, Shading};
use zraster::{mesh::Mesh, Camera, Frame, RenderOptions, Renderer, Viewport};

pub const W: u32 = 360; // three 120 × 120 views
pub const H: u32 = 120;
#[cfg(not(feature = "window"))]
const FRAMES: u32 = 100; // headless: 100 frames, then the PNG
#[cfg(feature = "window")]
const FRAMES: u32 = u32::MAX; // in the window: until it is closed

// An icosahedron of radius 1: its 12 corners (0, ±1, ±φ) and so on, scaled to unit
// length in Q14. On a ball the normal at a corner points along the corner itself, so
// the vertex table is its own table of vertex normals.
const A: i16 = 8614;
const B: i16 = 13937;
#[rustfmt::skip]
const CORNERS: [[i16; 3]; 12] = [
    [-A, B, 0], [A, B, 0], [-A, -B, 0], [A, -B, 0], [0, -A, B], [0, A, B],
    [0, -A, -B], [0, A, -B], [B, 0, -A], [B, 0, A], [-B, 0, -A], [-B, 0, A],
];
#[rustfmt::skip]
const TRIANGLES: [[u16; 3]; 20] = [
    [0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
    [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8],
    [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1],
];
const SKY_BLUE: Rgb888 = Rgb888::new(90, 170, 255);
// Face normals may be left out (None): lighting then works them out from the positions.
pub const BALL: Mesh = Mesh::triangles(&CORNERS, 1.0 / 16384.0, &TRIANGLES, SKY_BLUE)
    .with_normals(None, Some(&CORNERS));
pub const SHADINGS: [Shading; 3] = [Shading::Flat, Shading::Lambert, Shading::Gouraud];

/// Draw the ball turned `angle` radians, once in each shading.
pub fn render(frame: &mut Frame<Rgb565>, angle: f32) -> Result<(), zraster::Error> {
    frame.clear(Rgb565::BLACK);
    let look = Camera::look_at(Vec3::new(0.0, 0.0, 3.2), Vec3::default(), Vec3::Y)?;
    let spin = Mat4::rotation_y(angle) * Mat4::rotation_x(0.5);
    // A light from the upper left, in world coordinates: brightness = 0.15 (ambient)
    // + 0.85 × the cosine of the angle between the normal and the light.
    let light = Light {
        direction: Vec3::new(-1.0, 1.0, 0.6),
        ambient: 0.15,
        diffuse: 0.85,
    };
    for (i, shading) in SHADINGS.into_iter().enumerate() {
        let view = Viewport::at(120 * i as i32, 0, 120, 120)?;
        let camera = look
            .perspective(radians(40.0), 1.0, 6.0, view)?
            .with_model(spin);
        let options = RenderOptions {
            shading,
            light,
            ..Default::default()
        };
        Renderer::new(&BALL, &camera, options)?.draw(frame)?;
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (mut pixels, mut depth) = ([Rgb565::BLACK; (W * H) as usize], [0; (W * H) as usize]);
    let mut frame = Frame::new(&mut pixels, &mut depth, W, H)?;
    let mut display = SimulatorDisplay::new(Size::new(W, H));
    let settings = OutputSettingsBuilder::new().scale(2).build();
    #[cfg(feature = "window")]
    let mut window = Window::new("zraster lesson 4: flat, Lambert, Gouraud", &settings);
    let mut drawing = Duration::ZERO;
    for n in 1..=FRAMES {
        let start = Instant::now();
        render(&mut frame, n as f32 * 0.02)?;
        drawing += start.elapsed();
        if n % 100 == 0 {
            let ms = drawing.as_secs_f64() * 10.0; // 1000 ms / 100 frames
            println!("{ms:.3} ms/frame, {:.0} fps", 1000.0 / ms);
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
        image.save_png("lesson4_lighting.png")?;
        println!("wrote lesson4_lighting.png");
    }
    Ok(())
}
