//! A textured, Lambert-lit, spinning cube beside an untextured one, in one frame drawn
//! in bands of 16 rows: the lesson of `Renderer::draw_textured`.
//!
//! `cargo run --release --example textured` writes `textured.png` (one moment of the
//! spin); with `--features window` the cube spins in a window until you close it.
//!
//! What it shows:
//! - texture coordinates as a table beside the mesh (one `MeshUv` a vertex, Q12: 4096
//!   is one whole texture, v down the image), the texture a `const` RGB565 table (in
//!   flash on a microcontroller), both handed to the draw in a `Texturing`;
//! - a cube needs four vertices a face to give each face the whole texture;
//! - texels lit as flat colours are (Lambert here: each face by its angle to the light);
//! - two meshes in one Z-buffer, drawn band by band: each band is cleared, both meshes
//!   are drawn into it (each renderer skips what is off the band), and it goes to the
//!   display. Only `WIDTH × BAND` pixels of colour and depth are in RAM.
mod common;

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::SimulatorDisplay;
use zraster::math::{radians, Mat4, Vec3};
use zraster::mesh::{Mesh, CUBE};
use zraster::shade::Shading;
use zraster::texture::{MeshUv, Texture};
use zraster::{
    Camera, ColorBuffer, Error, Frame, RenderOptions, Renderer, Texturing, Viewport, ZBuffer,
};

const WIDTH: u32 = 240;
const HEIGHT: u32 = 160;
/// Rows a band: the RAM drawing needs is WIDTH × BAND × (2 + 2) bytes (15 KiB).
const BAND: u32 = 16;

/// The textured cube: −1..1 on each axis (positions in 1/16384), four vertices a face,
/// counter-clockwise as seen from outside: front, back, right, left, top, bottom.
const S: i16 = 16384;
const POSITIONS: [[i16; 3]; 24] = [
    [-S, -S, S],
    [S, -S, S],
    [S, S, S],
    [-S, S, S],
    [S, -S, -S],
    [-S, -S, -S],
    [-S, S, -S],
    [S, S, -S],
    [S, -S, S],
    [S, -S, -S],
    [S, S, -S],
    [S, S, S],
    [-S, -S, -S],
    [-S, -S, S],
    [-S, S, S],
    [-S, S, -S],
    [-S, S, S],
    [S, S, S],
    [S, S, -S],
    [-S, S, -S],
    [-S, -S, -S],
    [S, -S, -S],
    [S, -S, S],
    [-S, -S, S],
];
/// Two triangles a face.
const INDICES: [[u16; 3]; 12] = [
    [0, 1, 2],
    [0, 2, 3],
    [4, 5, 6],
    [4, 6, 7],
    [8, 9, 10],
    [8, 10, 11],
    [12, 13, 14],
    [12, 14, 15],
    [16, 17, 18],
    [16, 18, 19],
    [20, 21, 22],
    [20, 22, 23],
];
/// Each face's corners: bottom left, bottom right, top right, top left of the texture
/// (v = 0 is the texture's top row).
const ONE: i16 = 4096;
const UVS: [MeshUv; 24] = {
    let corners = [[0, ONE], [ONE, ONE], [ONE, 0], [0, 0]];
    let mut uvs = [[0; 2]; 24];
    let mut i = 0;
    while i < 24 {
        uvs[i] = corners[i % 4];
        i += 1;
    }
    uvs
};

/// A 32×32 crate-like texture, raw RGB565: planks with a darker frame.
const TEXELS: [u16; 32 * 32] = {
    let mut t = [0u16; 32 * 32];
    let mut i = 0;
    while i < 32 * 32 {
        let (x, y) = (i % 32, i / 32);
        let frame = x < 3 || x > 28 || y < 3 || y > 28;
        let seam = y % 8 == 0;
        t[i] = if frame {
            0x6180 // dark brown
        } else if seam {
            0x8A22
        } else if (x + y / 8 * 5) % 11 == 0 {
            0xB3A6 // a grain line
        } else {
            0xD4A8 // light wood
        };
        i += 1;
    }
    t
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(WIDTH, HEIGHT));
    #[cfg(not(feature = "window"))]
    {
        draw_frame(&mut display, 30.0)?;
        common::present(&display, "textured", 2);
    }
    #[cfg(feature = "window")]
    {
        use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorEvent, Window};
        let mut window = Window::new("textured", &OutputSettingsBuilder::new().scale(3).build());
        let mut degrees = 0.0;
        'spin: loop {
            draw_frame(&mut display, degrees)?;
            window.update(&display);
            if window.events().any(|e| e == SimulatorEvent::Quit) {
                break 'spin;
            }
            degrees = (degrees + 2.0) % 360.0;
        }
    }
    Ok(())
}

/// One frame, the textured cube turned by `degrees`, drawn band by band into `display`.
fn draw_frame(display: &mut SimulatorDisplay<Rgb565>, degrees: f32) -> Result<(), Error> {
    let mesh = Mesh::triangles(
        &POSITIONS,
        1.0 / 16384.0,
        &INDICES,
        embedded_graphics::pixelcolor::Rgb888::WHITE,
    );
    let texturing = Texturing::new(&UVS, Texture::new(&TEXELS, 32, 32)?);
    let lit = RenderOptions {
        shading: Shading::Lambert,
        ..Default::default()
    };
    let camera = Camera::look_at(Vec3::new(0.0, 1.6, 6.0), Vec3::new(0.3, 0.0, 0.0), Vec3::Y)?
        .perspective(radians(45.0), 0.5, 20.0, Viewport::new(WIDTH, HEIGHT)?)?;
    // The textured cube on the left, spinning; the flat-coloured seeds' cube (0..1) on
    // the right, turning the other way. One renderer each (a renderer is made per mesh
    // and frame: it transforms with its camera and model as it is made).
    let spin = Mat4::translation(Vec3::new(-1.2, 0.0, 0.0))
        * Mat4::rotation_y(radians(degrees))
        * Mat4::rotation_x(radians(20.0));
    let turn = Mat4::translation(Vec3::new(1.6, -0.2, 0.0))
        * Mat4::rotation_y(radians(-degrees))
        * Mat4::scaling(Vec3::new(1.4, 1.4, 1.4))
        * Mat4::translation(Vec3::new(-0.5, -0.5, -0.5));
    let mut textured = Renderer::new(&mesh, &camera.with_model(spin), lit)?;
    let mut plain = Renderer::new(&CUBE, &camera.with_model(turn), lit)?;

    // The band memory: this is all the RAM drawing needs.
    let mut colors = [Rgb565::BLACK; (WIDTH * BAND) as usize];
    let mut depths = [0u16; (WIDTH * BAND) as usize];
    for first in (0..HEIGHT).step_by(BAND as usize) {
        let rows = BAND.min(HEIGHT - first);
        let n = (WIDTH * rows) as usize;
        let color = ColorBuffer::new_band(&mut colors[..n], WIDTH, rows, first as i32)?;
        let depth = ZBuffer::new_band(&mut depths[..n], WIDTH, rows, first as i32)?;
        let mut band = Frame::from_buffers(color, depth);
        band.clear(Rgb565::new(4, 8, 12));
        textured.draw_textured(&mut band, &texturing)?;
        plain.draw(&mut band)?;
        band.flush(display)?;
    }
    Ok(())
}
