//! Lesson 6: a mesh in flash. `examples/obj2rust.rs` turns an OBJ model into `const`
//! tables (positions, triangles, face and vertex normals) and a ready `NAME_MESH`:
//!
//! ```text
//! cargo run --example obj2rust -- examples/models/bunny.obj bunny > src/bunny.rs
//! ```
//! Everything is `const`, so on a microcontroller the model stays in flash and costs no
//! RAM. The Stanford bunny made that way lives in the `zraster-bench-scene` crate; here
//! it is drawn, Gouraud-shaded, on three kinds of display with the same code: RGB565
//! colour, 16-grey `Gray4` (an SSD1322) and on/off `BinaryColor` (an SSD1306), where
//! the shading becomes ordered dithering.
//!
//! `cargo run --release --example lesson6_flash_mesh` writes `lesson6_flash_mesh.png`;
//! `--features window` shows the bunny turning.
use embedded_graphics::pixelcolor::{BinaryColor, Gray4, Rgb565, Rgb888};
use embedded_graphics::{prelude::*, primitives::Rectangle};
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
#[cfg(feature = "window")]
use embedded_graphics_simulator::{SimulatorEvent::Quit, Window};
use std::time::{Duration, Instant};
use zraster::math::{radians, Mat4, Vec3};
use zraster::mesh::{Faces, Materials, Mesh};
use zraster::shade::{DisplayColor, Shading};
use zraster::{Camera, Frame, RenderOptions, Renderer, Viewport};
use zraster_bench_scene::bunny::{BUNNY_FACE_NORMALS, BUNNY_POSITIONS, BUNNY_VERTEX_NORMALS};
use zraster_bench_scene::bunny::{BUNNY_FIT, BUNNY_INDICES, BUNNY_MESH};

pub const W: u32 = 160; // each of the three views
pub const H: u32 = 160;
#[cfg(not(feature = "window"))]
const FRAMES: u32 = 100; // headless: 100 frames, then the PNG
#[cfg(feature = "window")]
const FRAMES: u32 = u32::MAX; // in the window: until it is closed

// A mesh only borrows its tables: the same flash tables in another colour.
const PEACH: Rgb888 = Rgb888::new(255, 204, 153);
pub const BUNNY: Mesh = Mesh {
    faces: Faces::Triangles {
        indices: &BUNNY_INDICES,
        materials: Materials::Uniform(PEACH),
    },
    ..BUNNY_MESH
};

/// Draw the bunny turned `angle` radians into a frame of any embedded-graphics colour
/// type `C` (a `Frame` only wraps the memory: making one each time costs nothing).
/// Materials are `Rgb888`; each `DisplayColor` says how to show one, lit.
pub fn render<C: DisplayColor>(
    pixels: &mut [C],
    depth: &mut [u16],
    background: C,
    angle: f32,
) -> Result<(), zraster::Error> {
    let mut frame = Frame::new(pixels, depth, W, H)?;
    frame.clear(background);
    // BUNNY_FIT scales the model to a largest extent of 1, around its centre.
    let fit = Mat4::scaling(Vec3::new(BUNNY_FIT, BUNNY_FIT, BUNNY_FIT));
    let camera = Camera::look_at(Vec3::new(0.0, 0.15, 1.5), Vec3::default(), Vec3::Y)?
        .perspective(radians(45.0), 0.5, 3.0, Viewport::new(W, H)?)?
        .with_model(Mat4::rotation_y(angle) * fit);
    let options = RenderOptions {
        shading: Shading::Gouraud,
        ..Default::default()
    };
    Renderer::new(&BUNNY, &camera, options)?.draw(&mut frame)?;
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let tables = size_of_val(&BUNNY_POSITIONS) + size_of_val(&BUNNY_INDICES);
    let normals = size_of_val(&BUNNY_FACE_NORMALS) + size_of_val(&BUNNY_VERTEX_NORMALS);
    println!("in flash: {tables} bytes of tables and {normals} of normals; in RAM: none");
    // A colour buffer of each type, and one depth buffer that serves all three in turn.
    const N: usize = (W * H) as usize;
    let (mut rgb, mut grey, mut mono) =
        ([Rgb565::BLACK; N], [Gray4::BLACK; N], [BinaryColor::Off; N]);
    let mut depth = [0u16; N];
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(3 * W, H));
    let settings = OutputSettingsBuilder::new().scale(2).build();
    #[cfg(feature = "window")]
    let mut window = Window::new("zraster lesson 6: a mesh in flash", &settings);
    let mut drawing = Duration::ZERO;
    for n in 1..=FRAMES {
        let angle = n as f32 * 0.02;
        let start = Instant::now();
        render(&mut rgb, &mut depth, Rgb565::BLACK, angle)?;
        render(&mut grey, &mut depth, Gray4::BLACK, angle)?;
        render(&mut mono, &mut depth, BinaryColor::Off, angle)?;
        drawing += start.elapsed();
        if n % 100 == 0 {
            let ms = drawing.as_secs_f64() * 10.0; // 1000 ms / 100 frames
            println!("{ms:.3} ms/frame (three views), {:.0} fps", 1000.0 / ms);
            drawing = Duration::ZERO;
        }
        // Side by side on the simulator's RGB565 display, the grey and on/off converted.
        let area = |i: u32| Rectangle::new(Point::new((i * W) as i32, 0), Size::new(W, H));
        display.fill_contiguous(&area(0), rgb)?;
        display.fill_contiguous(&area(1), grey.map(Rgb565::from))?;
        display.fill_contiguous(&area(2), mono.map(Rgb565::from))?;
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
        image.save_png("lesson6_flash_mesh.png")?;
        println!("wrote lesson6_flash_mesh.png");
    }
    Ok(())
}
