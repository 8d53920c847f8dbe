//! A 128 × 64 monochrome view, as on an SSD1306 OLED: the bunny, flat Lambert shaded,
//! on a display whose pixels are only on or off. The frame's colour type is the
//! display's (`BinaryColor`); shading becomes ordered (4 × 4 Bayer) dithering. The
//! frame takes 128 × 64 × 3 bytes here: one `BinaryColor` and one depth a pixel.
//!
//! `cargo run --release --example oled` writes `oled.png` (shown 4× larger);
//! `--features window` shows the bunny turning.
use embedded_graphics::pixelcolor::{BinaryColor, Rgb888};
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

pub const W: u32 = 128;
pub const H: u32 = 64;
#[cfg(not(feature = "window"))]
const FRAMES: u32 = 100; // headless: 100 frames, then the PNG
#[cfg(feature = "window")]
const FRAMES: u32 = u32::MAX; // in the window: until it is closed
#[cfg(not(feature = "window"))]
const SPIN: f32 = 0.0; // headless: the same picture every time
#[cfg(feature = "window")]
const SPIN: f32 = 0.02; // radians a frame

// The bunny's flash tables; its material white, the brightest the dithering gives.
const BUNNY: Mesh = Mesh {
    faces: Faces::Triangles {
        indices: &BUNNY_INDICES,
        materials: Materials::Uniform(Rgb888::WHITE),
    },
    ..BUNNY_MESH
};

/// Draw the bunny turned `angle` radians into `frame`.
pub fn render(frame: &mut Frame<BinaryColor>, angle: f32) -> Result<(), zraster::Error> {
    frame.clear(BinaryColor::Off);
    let fit = Mat4::scaling(Vec3::new(BUNNY_FIT, BUNNY_FIT, BUNNY_FIT)); // 1 unit across
    let camera = Camera::look_at(
        Vec3::new(0.0, 0.0, 1.25),
        Vec3::new(0.0, -0.04, 0.0),
        Vec3::Y,
    )?
    .perspective(radians(60.0), 0.1, 20.0, Viewport::new(W, H)?)?
    .with_model(Mat4::rotation_y(angle) * fit);
    let options = RenderOptions {
        shading: Shading::Lambert,
        ..Default::default()
    };
    Renderer::new(&BUNNY, &camera, options)?.draw(frame)?;
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    let (mut pixels, mut depth) = ([BinaryColor::Off; (W * H) as usize], [0; (W * H) as usize]);
    let mut frame = Frame::new(&mut pixels, &mut depth, W, H)?;
    let mut display = SimulatorDisplay::new(Size::new(W, H));
    let settings = OutputSettingsBuilder::new().scale(4).build();
    #[cfg(feature = "window")]
    let mut window = Window::new("zraster: a 128 × 64 OLED", &settings);
    let mut drawing = Duration::ZERO;
    for n in 1..=FRAMES {
        let start = Instant::now();
        render(&mut frame, radians(-40.0) + SPIN * n as f32)?;
        drawing += start.elapsed();
        if n % 100 == 0 {
            let ms = drawing.as_secs_f64() * 10.0; // 1000 ms / 100 frames
            println!("{ms:.3} ms/frame, {:.0} fps", 1000.0 / ms);
            drawing = Duration::ZERO;
        }
        frame.flush(&mut display)?; // on a device: the SSD1306 driver
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
            .save_png("oled.png")?;
        println!("wrote oled.png");
    }
    Ok(())
}
