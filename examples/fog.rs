//! Fog: a textured floor and a row of lit cubes fading into a grey haze with distance,
//! through one pixel shader, `shader::Fog`, wrapped around the colour each would have
//! had (`shader::Textured` for the floor, `shader::Lit` for the cubes).
//!
//! `cargo run --release --example fog` writes `fog.png`; `--features window` flies the
//! camera down the row until you close the window.
//!
//! What it shows:
//! - `Renderer::draw_with_shader(&mut frame, &shader)`: the renderer's coverage, depth
//!   and light, your colour; the shader is a type, so its code is inlined in the pixel
//!   loop and plain `draw` pays nothing for the hook;
//! - fog linear in the Z-buffer's depth between two window depths (0 is the near plane,
//!   1 the far one): near the camera none, at the far end all fog colour;
//! - the fog colour is also the background, so far things melt into it.
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
#[cfg(feature = "window")]
use embedded_graphics_simulator::{SimulatorEvent::Quit, Window};
use std::time::{Duration, Instant};
use zraster::math::{radians, Mat4, Vec3};
use zraster::mesh::{Mesh, CUBE};
use zraster::shade::{Light, Shading};
use zraster::shader::{Fog, Lit, Textured};
use zraster::texture::{MeshUv, Texture};
use zraster::{Camera, Frame, RenderOptions, Renderer, Viewport};

const W: u32 = 320;
const H: u32 = 200;
#[cfg(not(feature = "window"))]
const FRAMES: u32 = 100; // headless: 100 frames, then the PNG
#[cfg(feature = "window")]
const FRAMES: u32 = u32::MAX; // in the window: until it is closed

/// The haze, and the sky behind it.
const HAZE: Rgb888 = Rgb888::new(170, 180, 190);

/// The floor: a strip 8 wide (x from −4 to 4) and 64 deep at y = 0, in 16 quads of 4
/// along z with four vertices each (positions in 1/256), so that each carries its own
/// texture coordinates: the tile 4 times across and twice along (UVs in Q12: 4096 is
/// one texture; a mesh's UVs stay within ±8 textures).
const QUADS: usize = 16;
const FLOOR: [[i16; 3]; 4 * QUADS] = {
    let mut p = [[0i16; 3]; 4 * QUADS];
    let mut q = 0;
    while q < QUADS {
        let (z0, z1) = (-1024 * q as i16, -1024 * (q as i16 + 1));
        p[4 * q] = [-1024, 0, z0];
        p[4 * q + 1] = [1024, 0, z0];
        p[4 * q + 2] = [1024, 0, z1];
        p[4 * q + 3] = [-1024, 0, z1];
        q += 1;
    }
    p
};
const FLOOR_UVS: [MeshUv; 4 * QUADS] = {
    let mut uv = [[0i16; 2]; 4 * QUADS];
    let mut q = 0;
    while q < QUADS {
        uv[4 * q] = [0, 0];
        uv[4 * q + 1] = [4 * 4096, 0];
        uv[4 * q + 2] = [4 * 4096, 2 * 4096];
        uv[4 * q + 3] = [0, 2 * 4096];
        q += 1;
    }
    uv
};
const FLOOR_FACES: [[u16; 3]; 2 * QUADS] = {
    let mut f = [[0u16; 3]; 2 * QUADS];
    let mut q = 0;
    while q < QUADS {
        let b = 4 * q as u16;
        f[2 * q] = [b, b + 1, b + 2];
        f[2 * q + 1] = [b, b + 2, b + 3];
        q += 1;
    }
    f
};
const FLOOR_MESH: Mesh = Mesh::triangles(&FLOOR, 1.0 / 256.0, &FLOOR_FACES, Rgb888::WHITE);

/// A 16×16 two-tone tile (raw RGB565 as `obj2rust` writes it: in flash on a device).
const TILE: [u16; 256] = {
    let mut t = [0u16; 256];
    let mut i = 0;
    while i < 256 {
        let (x, y) = (i % 16, i / 16);
        let edge = x == 0 || y == 0;
        t[i] = if edge {
            0x4208
        } else if (x / 8 + y / 8) % 2 == 0 {
            0xC618
        } else {
            0x8C51
        };
        i += 1;
    }
    t
};

/// Draw the scene with the camera `travel` units down the row.
fn render(frame: &mut Frame<Rgb565>, travel: f32) -> Result<(), zraster::Error> {
    frame.clear(Rgb565::from(HAZE));
    let eye = Vec3::new(0.0, 1.6, 2.0 - travel);
    let look = Camera::look_at(eye, Vec3::new(0.0, 1.0, -10.0 - travel), Vec3::Y)?;
    let camera = look.perspective(radians(60.0), 0.3, 60.0, Viewport::new(W, H)?)?;
    let light = Light {
        direction: Vec3::new(-0.5, 1.0, 0.7),
        ambient: 0.25,
        diffuse: 0.75,
    };
    let options = RenderOptions {
        shading: Shading::Lambert,
        light,
        ..Default::default()
    };
    // Window depths: under perspective most of the range is close to 1 (depth
    // 1.005·(1 − 0.3/d) at distance d), so the fog starts at 0.95 (some 6 units away)
    // and is complete at 0.999 (about 50).
    let texture = Texture::new(&TILE, 16, 16)?;
    let floor = Fog::new(Textured::new(&FLOOR_UVS, texture), 0.95, 0.999, HAZE)?;
    Renderer::new(&FLOOR_MESH, &camera, options)?.draw_with_shader(frame, &floor)?;
    let cubes = Fog::new(Lit, 0.95, 0.999, HAZE)?;
    for k in 0..16 {
        // Cubes on both sides of the floor, one every 4 units, each turned a little.
        let side = if k % 2 == 0 { -2.5 } else { 1.5 };
        let at = Vec3::new(side, 0.0, -4.0 * k as f32);
        let model = Mat4::translation(at) * Mat4::rotation_y(0.3 * k as f32);
        let camera = camera.with_model(model);
        Renderer::new(&CUBE, &camera, options)?.draw_with_shader(frame, &cubes)?;
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (mut pixels, mut depth) = (
        vec![Rgb565::BLACK; (W * H) as usize],
        vec![0; (W * H) as usize],
    );
    let mut frame = Frame::new(&mut pixels, &mut depth, W, H)?;
    let mut display = SimulatorDisplay::new(Size::new(W, H));
    let settings = OutputSettingsBuilder::new().scale(2).build();
    #[cfg(feature = "window")]
    let mut window = Window::new("zraster: fog", &settings);
    let mut drawing = Duration::ZERO;
    for n in 1..=FRAMES {
        let start = Instant::now();
        // Down the row and back to the start every 400 frames.
        render(&mut frame, (n % 400) as f32 * 0.04)?;
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
        image.save_png("fog.png")?;
        println!("wrote fog.png");
    }
    Ok(())
}
