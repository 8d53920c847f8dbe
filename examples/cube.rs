//! Why hidden surfaces need removing: the unit cube (`zraster::mesh::CUBE`, one colour a
//! side) drawn with no depth test, so that each face simply paints over the ones before
//! it in the face table. Left: every face drawn (wrong: the back faces listed last cover
//! the front). Right: faces turned away from the eye culled first (right, for a convex
//! solid; lesson 7 shows what the depth buffer does for the rest).
//!
//! `cargo run --release --example cube` writes `cube.png`; `--features window` shows the
//! cube turning.
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
#[cfg(feature = "window")]
use embedded_graphics_simulator::{SimulatorEvent::Quit, Window};
use std::error::Error;
use std::time::{Duration, Instant};
use zraster::math::{radians, Mat4, Vec3};
use zraster::{mesh::CUBE, Camera, Cull, DepthTest, Frame, RenderOptions, Renderer, Viewport};

pub const W: u32 = 160; // each view; the picture is two views and an 8-pixel gap
pub const H: u32 = 120;
#[cfg(not(feature = "window"))]
const FRAMES: u32 = 100; // headless: 100 frames, then the PNG
#[cfg(feature = "window")]
const FRAMES: u32 = u32::MAX; // in the window: until it is closed
#[cfg(not(feature = "window"))]
const SPIN: f32 = 0.0; // headless: the same picture every time
#[cfg(feature = "window")]
const SPIN: f32 = 0.02; // radians a frame

/// Draw the cube turned `angle` radians about its centre, without and with culling,
/// each through `frame` into its place on `display`.
pub fn render(
    display: &mut SimulatorDisplay<Rgb565>,
    frame: &mut Frame<Rgb565>,
    angle: f32,
) -> Result<(), Box<dyn Error>> {
    let centre = Vec3::new(0.5, 0.5, 0.5);
    let turn = Mat4::translation(centre) * Mat4::rotation_y(angle) * Mat4::translation(-centre);
    let camera = Camera::look_at(Vec3::new(2.2, 1.8, 2.8), centre, Vec3::Y)?
        .perspective(radians(45.0), 0.1, 20.0, Viewport::new(W, H)?)?
        .with_model(turn);
    // Always passes: no hidden-surface removal at all, only the order of the faces.
    frame.depth_mut().set_test(DepthTest::Always);
    for (i, cull) in [Cull::None, Cull::Back].into_iter().enumerate() {
        frame.clear(Rgb565::BLACK);
        let options = RenderOptions {
            cull,
            ..Default::default()
        };
        Renderer::new(&CUBE, &camera, options)?.draw(frame)?;
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
    let mut window = Window::new("zraster: the cube, without and with culling", &settings);
    let mut drawing = Duration::ZERO;
    for n in 1..=FRAMES {
        let start = Instant::now();
        render(&mut display, &mut frame, SPIN * n as f32)?;
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
            .save_png("cube.png")?;
        println!("wrote cube.png");
    }
    Ok(())
}
