//! Lesson 1: the first triangle. A mesh of one triangle, a camera, a `Frame` (colour and
//! depth in memory you own) and `Renderer::draw`: the whole pipeline at its smallest.
//!
//! `cargo run --release --example lesson1_triangle` draws 100 frames, prints the time a
//! frame takes and writes `lesson1_triangle.png`; `--features window` shows it turning.
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
#[cfg(feature = "window")]
use embedded_graphics_simulator::{SimulatorEvent::Quit, Window};
use std::time::{Duration, Instant};
use zraster::math::{radians, Mat4, Vec3};
use zraster::{mesh::Mesh, Camera, Frame, RenderOptions, Renderer, Viewport};

pub const W: u32 = 160;
pub const H: u32 = 120;
#[cfg(not(feature = "window"))]
const FRAMES: u32 = 100; // headless: 100 frames, then the PNG
#[cfg(feature = "window")]
const FRAMES: u32 = u32::MAX; // in the window: until it is closed
                              // Positions are i16 steps times a scale, here 1/16384: corners about 1 unit from the
                              // origin, listed counter-clockwise as seen from the front (+z), so the triangle shows.
const CORNERS: [[i16; 3]; 3] = [[-16384, -12000, 0], [16384, -12000, 0], [0, 16384, 0]];
const ORANGE: Rgb888 = Rgb888::new(255, 140, 0);
pub const TRIANGLE: Mesh = Mesh::triangles(&CORNERS, 1.0 / 16384.0, &[[0, 1, 2]], ORANGE);

/// Draw the triangle turned `angle` radians in its plane.
pub fn render(frame: &mut Frame<Rgb565>, angle: f32) -> Result<(), zraster::Error> {
    // Every colour to black, every depth to far; then the eye 3 units in front looking
    // at the origin, a 45° lens, near and far planes, and the model matrix that turns it.
    frame.clear(Rgb565::BLACK);
    let camera = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::default(), Vec3::Y)?
        .perspective(radians(45.0), 0.1, 10.0, Viewport::new(W, H)?)?
        .with_model(Mat4::rotation_z(angle));
    Renderer::new(&TRIANGLE, &camera, RenderOptions::default())?.draw(frame)?;
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (mut pixels, mut depth) = ([Rgb565::BLACK; (W * H) as usize], [0; (W * H) as usize]);
    let mut frame = Frame::new(&mut pixels, &mut depth, W, H)?;
    // The simulator stands in for a display: a window, or a PNG when headless.
    let mut display = SimulatorDisplay::new(Size::new(W, H));
    let settings = OutputSettingsBuilder::new().scale(2).build();
    #[cfg(feature = "window")]
    let mut window = Window::new("zraster lesson 1: a triangle", &settings);
    let mut drawing = Duration::ZERO;
    for n in 1..=FRAMES {
        let start = Instant::now();
        render(&mut frame, n as f32 * 0.03)?;
        drawing += start.elapsed(); // the drawing alone (the window shows ≤ 60 fps)
        if n % 100 == 0 {
            let ms = drawing.as_secs_f64() * 10.0; // 1000 ms / 100 frames
            println!("{ms:.3} ms/frame, {:.0} fps", 1000.0 / ms);
            drawing = Duration::ZERO;
        }
        frame.flush(&mut display)?; // on a device, into the display driver
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
        image.save_png("lesson1_triangle.png")?;
        println!("wrote lesson1_triangle.png");
    }
    Ok(())
}
