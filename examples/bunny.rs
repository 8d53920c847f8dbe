//! The Stanford bunny (3674 triangles) with flat Lambert shading (left: one brightness a
//! face) and Gouraud shading (right: brightness worked out at each vertex and blended).
//! The model comes as `const` flash tables (see lesson 6); one 240 × 200 frame in RAM
//! draws both views in turn.
//!
//! `cargo run --release --example bunny` writes `bunny.png` (the README's picture) and
//! prints the time a frame takes; `--features window` shows the bunny turning.
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
#[cfg(feature = "window")]
use embedded_graphics_simulator::{SimulatorEvent::Quit, Window};
use std::error::Error;
use std::time::{Duration, Instant};
use zraster::math::{radians, Mat4, Vec3};
use zraster::mesh::{Faces, Materials, Mesh};
use zraster::shade::Shading;
use zraster::{Camera, Frame, RenderOptions, Renderer, Viewport};
use zraster_bench_scene::bunny::{BUNNY_FIT, BUNNY_INDICES, BUNNY_MESH};

pub const W: u32 = 240; // each view; the picture is two views and an 8-pixel gap
pub const H: u32 = 200;
#[cfg(not(feature = "window"))]
const FRAMES: u32 = 100; // headless: 100 frames, then the PNG
#[cfg(feature = "window")]
const FRAMES: u32 = u32::MAX; // in the window: until it is closed
#[cfg(not(feature = "window"))]
const SPIN: f32 = 0.0; // headless: the README's picture every time
#[cfg(feature = "window")]
const SPIN: f32 = 0.02; // radians a frame

const BUNNY: Mesh = Mesh {
    faces: Faces::Triangles {
        indices: &BUNNY_INDICES,
        materials: Materials::Uniform(Rgb888::new(255, 204, 153)),
    },
    ..BUNNY_MESH
};

/// Draw the bunny turned `angle` radians, Lambert then Gouraud, each through `frame`
/// into its place on `display`.
pub fn render(
    display: &mut SimulatorDisplay<Rgb565>,
    frame: &mut Frame<Rgb565>,
    angle: f32,
) -> Result<(), Box<dyn Error>> {
    let fit = Mat4::scaling(Vec3::new(BUNNY_FIT, BUNNY_FIT, BUNNY_FIT)); // 1 unit across
    let camera = Camera::look_at(Vec3::new(0.0, 0.0, 1.5), Vec3::default(), Vec3::Y)?
        .perspective(radians(50.0), 0.1, 20.0, Viewport::new(W, H)?)?
        .with_model(Mat4::rotation_y(angle) * fit);
    for (i, shading) in [Shading::Lambert, Shading::Gouraud].into_iter().enumerate() {
        frame.clear(Rgb565::BLACK);
        let options = RenderOptions {
            shading,
            ..Default::default()
        };
        Renderer::new(&BUNNY, &camera, options)?.draw(frame)?;
        frame.flush(&mut display.translated(Point::new(i as i32 * (W as i32 + 8), 0)))?;
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    let (mut pixels, mut depth) = ([Rgb565::BLACK; (W * H) as usize], [0; (W * H) as usize]);
    let mut frame = Frame::new(&mut pixels, &mut depth, W, H)?;
    let mut display = SimulatorDisplay::new(Size::new(2 * W + 8, H));
    let settings = OutputSettingsBuilder::new().scale(2).build();
    #[cfg(feature = "window")]
    let mut window = Window::new("zraster: the bunny, Lambert and Gouraud", &settings);
    let mut drawing = Duration::ZERO;
    for n in 1..=FRAMES {
        let start = Instant::now();
        render(&mut display, &mut frame, radians(30.0) + SPIN * n as f32)?;
        drawing += start.elapsed();
        if n % 100 == 0 {
            let ms = drawing.as_secs_f64() * 10.0; // 1000 ms / 100 frames
            println!("{ms:.3} ms/frame (both views), {:.0} fps", 1000.0 / ms);
            drawing = Duration::ZERO;
        }
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
        display
            .to_rgb_output_image(&settings)
            .save_png("bunny.png")?;
        println!("wrote bunny.png");
    }
    Ok(())
}
