//! Lesson 7: a scene. Several meshes, each placed by its own model matrix, drawn one
//! after another into the same frame: the depth buffer is cleared once a frame, not once
//! a mesh, so every pixel keeps whatever is nearest of all of them. Meshes may then be
//! drawn in any order and may even pass through each other, as the two cubes here pass
//! through the bunny, which no ordering of whole faces could draw right.
//!
//! `cargo run --release --example lesson7_scene` writes `lesson7_scene.png`;
//! `--features window` shows the cubes circling.
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
#[cfg(feature = "window")]
use embedded_graphics_simulator::{SimulatorEvent::Quit, Window};
use std::f32::consts::FRAC_PI_2;
use std::time::{Duration, Instant};
use zraster::math::{radians, Mat4, Vec3};
use zraster::mesh::{Faces, Materials, Mesh, CUBE};
use zraster::shade::Shading;
use zraster::{Camera, Frame, RenderOptions, Renderer, Viewport};
use zraster_bench_scene::bunny::{BUNNY_FIT, BUNNY_INDICES, BUNNY_MESH};

pub const W: u32 = 320;
pub const H: u32 = 240;
#[cfg(not(feature = "window"))]
const FRAMES: u32 = 100; // headless: 100 frames, then the PNG
#[cfg(feature = "window")]
const FRAMES: u32 = u32::MAX; // in the window: until it is closed

// A square floor, facing up (+y): 2.6 units across.
const S: i16 = 16384;
const FLOOR_CORNERS: [[i16; 3]; 4] = [[-S, 0, S], [S, 0, S], [S, 0, -S], [-S, 0, -S]];
const MOSS: Rgb888 = Rgb888::new(110, 140, 100);
const FLOOR: Mesh = Mesh::triangles(&FLOOR_CORNERS, 1.3 / 16384.0, &[[0, 1, 2], [0, 2, 3]], MOSS);
// The bunny of lesson 6, from flash, in another colour.
const BUNNY: Mesh = Mesh {
    faces: Faces::Triangles {
        indices: &BUNNY_INDICES,
        materials: Materials::Uniform(Rgb888::new(255, 204, 153)),
    },
    ..BUNNY_MESH
};
pub const SKY: Rgb565 = Rgb565::new(4, 10, 14);

/// The camera, before any model matrix.
pub fn camera() -> Result<Camera, zraster::Error> {
    Camera::look_at(Vec3::new(0.0, 0.6, 1.9), Vec3::new(0.0, -0.1, 0.0), Vec3::Y)?.perspective(
        radians(50.0),
        0.5,
        5.0,
        Viewport::new(W, H)?,
    )
}

/// What is where at time `t` (seconds): each mesh, its model matrix and its options.
pub fn scene(t: f32) -> [(Mesh<'static>, Mat4, RenderOptions); 4] {
    let shaded = |shading| RenderOptions {
        shading,
        ..Default::default()
    };
    let fit = Mat4::scaling(Vec3::new(BUNNY_FIT, BUNNY_FIT, BUNNY_FIT)); // 1 unit tall
                                                                         // A small cube (0.24 a side, centred on its origin) circling at height y, tumbling.
    let cube = |phase: f32, y: f32| {
        Mat4::rotation_y(0.8 * t + phase)
            * Mat4::translation(Vec3::new(0.5, y, 0.0))
            * Mat4::rotation_x(2.0 * t)
            * Mat4::scaling(Vec3::new(0.24, 0.24, 0.24))
            * Mat4::translation(Vec3::new(-0.5, -0.5, -0.5))
    };
    [
        (
            FLOOR,
            Mat4::translation(Vec3::new(0.0, -0.49, 0.0)),
            shaded(Shading::Lambert),
        ),
        (
            BUNNY,
            Mat4::rotation_y(0.3 * t) * fit,
            shaded(Shading::Gouraud),
        ),
        (CUBE, cube(FRAC_PI_2, 0.05), shaded(Shading::Flat)),
        (CUBE, cube(-FRAC_PI_2, -0.25), shaded(Shading::Flat)),
    ]
}

/// Draw the scene at time `t`.
pub fn render(frame: &mut Frame<Rgb565>, t: f32) -> Result<(), zraster::Error> {
    frame.clear(SKY); // once a frame: colours and depths
    let camera = camera()?;
    for (mesh, model, options) in scene(t) {
        // Each mesh through its own model matrix, into the same frame and depths.
        Renderer::new(&mesh, &camera.with_model(model), options)?.draw(frame)?;
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (mut pixels, mut depth) = ([SKY; (W * H) as usize], [0; (W * H) as usize]);
    let mut frame = Frame::new(&mut pixels, &mut depth, W, H)?;
    let mut display = SimulatorDisplay::new(Size::new(W, H));
    let settings = OutputSettingsBuilder::new().scale(2).build();
    #[cfg(feature = "window")]
    let mut window = Window::new("zraster lesson 7: a scene", &settings);
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
        image.save_png("lesson7_scene.png")?;
        println!("wrote lesson7_scene.png");
    }
    Ok(())
}
