//! Lesson 3: the camera. `Camera::look_at(eye, target, up)` says where the eye is and
//! what it looks at; then a lens: `.perspective(field of view, near, far, viewport)`,
//! where far things look smaller, or `.orthographic(height, near, far, viewport)`, where
//! they do not (plans and elevations). Here the eye flies around a cube and both lenses
//! look at it side by side, each in its own viewport of one frame.
//!
//! `cargo run --release --example lesson3_camera` writes `lesson3_camera.png`;
//! `--features window` shows the flight.
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
#[cfg(feature = "window")]
use embedded_graphics_simulator::{SimulatorEvent::Quit, Window};
use std::time::{Duration, Instant};
use zraster::math::{radians, Mat4, Vec3};
use zraster::{mesh::CUBE, Camera, Frame, RenderOptions, Renderer, Viewport};

pub const W: u32 = 320; // two 160 × 160 views
pub const H: u32 = 160;
#[cfg(not(feature = "window"))]
const FRAMES: u32 = 100; // headless: 100 frames, then the PNG
#[cfg(feature = "window")]
const FRAMES: u32 = u32::MAX; // in the window: until it is closed

/// Draw the cube seen from the eye at time `t` (seconds): perspective on the left,
/// orthographic on the right.
pub fn render(frame: &mut Frame<Rgb565>, t: f32) -> Result<(), zraster::Error> {
    frame.clear(Rgb565::new(2, 4, 8));
    // The eye circles the origin 2.4 units away, rising and sinking; +Y is up. (Straight
    // above the target, +Y up would say nothing: `look_at` returns DegenerateView.)
    let (sin, cos) = (t.sin(), t.cos());
    let eye = Vec3::new(2.4 * sin, 1.2 + 0.8 * (0.7 * t).sin(), 2.4 * cos);
    let look = Camera::look_at(eye, Vec3::default(), Vec3::Y)?;
    // Angles are radians. The viewport is where on the screen the view goes.
    let left = look.perspective(radians(50.0), 0.5, 10.0, Viewport::at(0, 0, 160, 160)?)?;
    let right = look.orthographic(2.4, 0.5, 10.0, Viewport::at(160, 0, 160, 160)?)?;
    // The model matrix centres the unit cube (it spans 0..1) on the origin.
    let centred = Mat4::translation(Vec3::new(-0.5, -0.5, -0.5));
    for camera in [left, right] {
        // Depth has 16 bits between near and far: fit_depth moves both planes to the
        // cube's box, in its own (model) coordinates, so the cube gets all of them.
        let camera = camera.with_model(centred).fit_depth(
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 1.0),
            0.1,
        )?;
        Renderer::new(&CUBE, &camera, RenderOptions::default())?.draw(frame)?;
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (mut pixels, mut depth) = ([Rgb565::BLACK; (W * H) as usize], [0; (W * H) as usize]);
    let mut frame = Frame::new(&mut pixels, &mut depth, W, H)?;
    let mut display = SimulatorDisplay::new(Size::new(W, H));
    let settings = OutputSettingsBuilder::new().scale(2).build();
    #[cfg(feature = "window")]
    let mut window = Window::new("zraster lesson 3: the camera", &settings);
    let mut drawing = Duration::ZERO;
    for n in 1..=FRAMES {
        let start = Instant::now();
        render(&mut frame, n as f32 / 60.0)?;
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
        image.save_png("lesson3_camera.png")?;
        println!("wrote lesson3_camera.png");
    }
    Ok(())
}
