//! A banded scene: a lit, spinning cube circling the Stanford bunny behind a pane of
//! tinted glass, three meshes with their own model matrices in one depth buffer, drawn
//! 16 rows at a time. A `Scene` draws every object into each band (the picture is the
//! whole frame's), while each object's vertices are transformed once a frame (into its
//! vertex cache) and its triangles sorted by band once a frame (into its run of the
//! bins). The glass is a `Translucent` material at half opacity: it is drawn after all
//! the opaque faces, blended over them, and does not hide what is behind it.
//!
//! (A textured object cannot join a scene yet: textures are drawn by
//! `Renderer::draw_textured`, one mesh at a time; so the cube here is lit, not textured.)
//!
//! `cargo run --release --example scene` writes `scene.png`; `--features window` shows
//! it turning.
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
#[cfg(feature = "window")]
use embedded_graphics_simulator::{SimulatorEvent::Quit, Window};
use std::time::{Duration, Instant};
use zraster::math::{radians, Mat4, Vec3};
use zraster::mesh::{Faces, Materials, Mesh, CUBE_POSITIONS};
use zraster::scene::Scene;
use zraster::shade::{Shading, Translucent};
use zraster::{BandBuffers, Bands, CachedVertex, Camera, DrawError, FrameStats};
use zraster::{RenderOptions, Renderer, Viewport};
use zraster_bench_scene::bunny::{BUNNY_FIT, BUNNY_INDICES, BUNNY_MESH, BUNNY_POSITIONS};

const W: u32 = 320;
const H: u32 = 240;
const ROWS: u32 = 16; // rows a band
#[cfg(not(feature = "window"))]
const FRAMES: u32 = 100; // headless: 100 frames, then the PNG
#[cfg(feature = "window")]
const FRAMES: u32 = u32::MAX; // in the window: until it is closed

// Every object of a scene has the same material type: here `Translucent`, a colour
// with an opacity (255: opaque).
const fn opaque(r: u8, g: u8, b: u8) -> Translucent {
    Translucent::new(Rgb888::new(r, g, b), 255)
}

// The unit cube as 12 triangles (triangle meshes bin), a colour a side.
#[rustfmt::skip]
const CUBE_TRIANGLES: [[u16; 3]; 12] = [
    [0, 1, 2], [0, 2, 3], [1, 5, 6], [1, 6, 2], [2, 6, 7], [2, 7, 3],
    [3, 7, 4], [3, 4, 0], [0, 4, 5], [0, 5, 1], [7, 6, 5], [7, 5, 4],
];
const CUBE_COLOURS: [Translucent; 12] = {
    let sides = [
        opaque(230, 60, 50),
        opaque(60, 200, 90),
        opaque(60, 110, 240),
        opaque(240, 200, 60),
        opaque(200, 80, 220),
        opaque(60, 220, 220),
    ];
    let mut out = [sides[0]; 12];
    let mut i = 0;
    while i < 12 {
        out[i] = sides[i / 2];
        i += 1;
    }
    out
};
const CUBE: Mesh<Translucent> = Mesh {
    positions: &CUBE_POSITIONS,
    scale: 1.0 / 16384.0,
    faces: Faces::Triangles {
        indices: &CUBE_TRIANGLES,
        materials: Materials::PerFace(&CUBE_COLOURS),
    },
    face_normals: None,
    vertex_normals: None,
};

// The bunny from flash, with its face normals for Lambert lighting.
const BUNNY: Mesh<Translucent> = Mesh {
    positions: &BUNNY_POSITIONS,
    scale: BUNNY_MESH.scale,
    faces: Faces::Triangles {
        indices: &BUNNY_INDICES,
        materials: Materials::Uniform(opaque(235, 215, 190)),
    },
    face_normals: BUNNY_MESH.face_normals,
    vertex_normals: None,
};

// A pane of glass, 0.8 units square in the plane z = 0, blue-green at half opacity.
const S: i16 = 16384;
const PANE_CORNERS: [[i16; 3]; 4] = [[-S, -S, 0], [S, -S, 0], [S, S, 0], [-S, S, 0]];
const PANE: Mesh<Translucent> = Mesh::triangles(
    &PANE_CORNERS,
    0.4 / 16384.0,
    &[[0, 1, 2], [0, 2, 3]],
    Translucent::new(Rgb888::new(80, 200, 255), 128),
);

const SKY: Rgb565 = Rgb565::new(6, 14, 12);

/// Each object and its model matrix at time `t` (seconds).
fn objects(t: f32) -> [(Mesh<'static, Translucent>, Mat4); 3] {
    let fit = BUNNY_FIT * 0.9;
    let cube = Mat4::rotation_y(0.9 * t - 2.2)
        * Mat4::translation(Vec3::new(0.8, 0.1, 0.0))
        * Mat4::rotation_x(1.7 * t)
        * Mat4::rotation_z(0.6 * t)
        * Mat4::scaling(Vec3::new(0.35, 0.35, 0.35))
        * Mat4::translation(Vec3::new(-0.5, -0.5, -0.5));
    [
        (CUBE, cube),
        (
            BUNNY,
            Mat4::rotation_y(0.25 * t) * Mat4::scaling(Vec3::new(fit, fit, fit)),
        ),
        (
            PANE,
            Mat4::translation(Vec3::new(-0.45, 0.0, 0.6)) * Mat4::rotation_y(0.5),
        ),
    ]
}

/// Draw the scene at time `t` into `display`, band by band.
fn render<D: DrawTarget<Color = Rgb565>>(
    display: &mut D,
    buffers: &mut BandBuffers<Rgb565>,
    caches: &mut [Vec<CachedVertex>; 3],
    t: f32,
) -> Result<FrameStats, DrawError<D::Error>> {
    let camera = Camera::look_at(Vec3::new(0.0, 0.5, 2.6), Vec3::new(0.0, 0.0, 0.0), Vec3::Y)?
        .perspective(radians(45.0), 0.5, 6.0, Viewport::new(W, H)?)?;
    let lit = RenderOptions {
        shading: Shading::Lambert,
        ..Default::default()
    };
    // One renderer an object, each with its own model matrix and vertex cache.
    let [a, b, c] = caches;
    let [(cube, m0), (bunny, m1), (pane, m2)] = objects(t);
    let mut renderers = [
        Renderer::with_cache(&cube, &camera.with_model(m0), lit, a)?,
        Renderer::with_cache(&bunny, &camera.with_model(m1), lit, b)?,
        Renderer::with_cache(&pane, &camera.with_model(m2), RenderOptions::default(), c)?,
    ];
    let mut scene = Scene::new(&mut renderers);
    scene.draw(&mut Bands::new(display, buffers, SKY))?;
    Ok(scene.stats())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // Caller memory: one band of colour and depth, a vertex cache for each object and
    // the bins for all three (their sum: `Scene::bins_needed`).
    let (mut color, mut depth) = (vec![SKY; (W * ROWS) as usize], vec![0; (W * ROWS) as usize]);
    let mut caches = [CUBE, BUNNY, PANE].map(|m| vec![CachedVertex::EMPTY; m.positions.len()]);
    let bins_needed = [CUBE, BUNNY, PANE]
        .iter()
        .map(|m| BandBuffers::<Rgb565>::bins_needed(m.face_count(), H, ROWS))
        .sum();
    let mut bins = vec![0u16; bins_needed];
    let ram = color.len() * 2
        + depth.len() * 2
        + bins.len() * 2
        + caches.iter().map(|c| c.len() * 8).sum::<usize>();
    println!(
        "RAM: {ram} bytes ({ROWS}-row bands, vertex caches, bins), not {} for a whole frame",
        W * H * 4
    );
    let mut buffers = BandBuffers::new(&mut color, &mut depth, W, ROWS, H, &mut bins)?;
    let mut display = SimulatorDisplay::new(Size::new(W, H));
    let settings = OutputSettingsBuilder::new().scale(2).build();
    #[cfg(feature = "window")]
    let mut window = Window::new("zraster: a banded scene", &settings);
    let mut drawing = Duration::ZERO;
    for n in 1..=FRAMES {
        let start = Instant::now();
        let stats = render(&mut display, &mut buffers, &mut caches, n as f32 / 60.0)?;
        drawing += start.elapsed(); // drawing and sending to the display
        if n % 100 == 0 {
            let ms = drawing.as_secs_f64() * 10.0; // 1000 ms / 100 frames
            println!(
                "{ms:.3} ms/frame, {:.0} fps; {} triangles drawn",
                1000.0 / ms,
                stats.drawn
            );
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
        let image = display.to_rgb_output_image(&settings);
        image.save_png("scene.png")?;
        println!("wrote scene.png");
    }
    Ok(())
}
