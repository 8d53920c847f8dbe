//! The painter's algorithm (left: whole faces sorted by depth and drawn far to near,
//! `draw_depth_sorted`) against the Z-buffer (right: the nearest face kept at each pixel,
//! `draw`) on the three cases where sorting faces fails, one a row: three sticks each
//! lying over the next (no order is right), two triangles passing through each other,
//! and a concave object (a plate with a fin, whose centres sort the wrong way).
//!
//! `cargo run --release --example painter` writes `painter.png`; `--features window`
//! shows the three rocking to and fro.
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
#[cfg(feature = "window")]
use embedded_graphics_simulator::{SimulatorEvent::Quit, Window};
use std::error::Error;
use std::time::{Duration, Instant};
use zraster::math::{radians, Mat4, Vec3};
use zraster::mesh::{quantize, Face, Mesh};
use zraster::{Camera, Cull, DepthSort, Frame, RenderOptions, Renderer, Viewport};

pub const W: u32 = 140; // each view; the picture is 2 × 3 views, 8 pixels apart
pub const H: u32 = 110;
#[cfg(not(feature = "window"))]
const FRAMES: u32 = 100; // headless: 100 frames, then the PNG
#[cfg(feature = "window")]
const FRAMES: u32 = u32::MAX; // in the window: until it is closed

const RED: Rgb888 = Rgb888::new(230, 40, 40);
const GREEN: Rgb888 = Rgb888::new(40, 200, 60);
const BLUE: Rgb888 = Rgb888::new(50, 90, 240);
const YELLOW: Rgb888 = Rgb888::new(240, 220, 40);
const GREY: Rgb888 = Rgb888::new(90, 90, 90);

/// One case: model-space points (quantised when drawn), faces, where the eye is and
/// what it looks at, and the culling.
pub struct Case {
    pub points: Vec<[f32; 3]>,
    pub faces: &'static [Face<'static, Rgb888>],
    pub eye: Vec3,
    pub target: Vec3,
    pub cull: Cull,
}

/// Three sticks, each lying over the next: stick k rises from corner k (z = −0.3) to
/// past corner k + 1 (z = +0.3).
fn cyclic_sticks() -> Case {
    let corners = [(-0.8f32, -0.5f32), (0.8, -0.5), (0.0, 0.85)];
    let mut points = Vec::new();
    for k in 0..3 {
        let (a, b) = (corners[k], corners[(k + 1) % 3]);
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len = (dx * dx + dy * dy).sqrt();
        let (ux, uy) = (dx / len, dy / len);
        let (nx, ny) = (-uy * 0.12, ux * 0.12); // half the stick's width, across it
        let (sx, sy) = (a.0 - ux * 0.25, a.1 - uy * 0.25);
        let (ex, ey) = (b.0 + ux * 0.25, b.1 + uy * 0.25);
        points.extend([[sx - nx, sy - ny, -0.3], [ex - nx, ey - ny, 0.3]]);
        points.extend([[ex + nx, ey + ny, 0.3], [sx + nx, sy + ny, -0.3]]);
    }
    #[rustfmt::skip]
    const FACES: [Face<Rgb888>; 3] = [
        Face { vertices: &[0, 1, 2, 3], material: RED },
        Face { vertices: &[4, 5, 6, 7], material: GREEN },
        Face { vertices: &[8, 9, 10, 11], material: BLUE },
    ];
    let eye = Vec3::new(0.0, 0.0, 3.0);
    Case {
        points,
        faces: &FACES,
        eye,
        target: Vec3::default(),
        cull: Cull::None,
    }
}

/// Two triangles that pass through each other.
fn interpenetrating() -> Case {
    #[rustfmt::skip]
    let points = vec![[-0.9, -0.6, -0.4], [0.9, -0.2, 0.5], [-0.5, 0.8, -0.4],
        [0.9, -0.7, -0.5], [0.5, 0.8, -0.5], [-0.9, 0.0, 0.5]];
    #[rustfmt::skip]
    const FACES: [Face<Rgb888>; 2] =
        [Face { vertices: &[0, 1, 2], material: RED }, Face { vertices: &[3, 4, 5], material: GREEN }];
    let eye = Vec3::new(0.0, 0.0, 3.0);
    Case {
        points,
        faces: &FACES,
        eye,
        target: Vec3::default(),
        cull: Cull::None,
    }
}

/// A long plate with a fin standing on its far half (a hair above it, so no two faces
/// touch). Seen from the front, the plate's centre is nearer than the fin's, so the
/// painter draws the plate last, over the fin that stands in front of its far end.
fn concave_plate() -> Case {
    let mut points = Vec::new();
    for (lo, hi) in [
        ([-1.0, -0.15, -2.0], [1.0, 0.0, 1.0]),
        ([-0.6, 0.01, -1.1], [0.6, 0.9, -0.9]),
    ] {
        // The corners in the order of zraster::mesh::CUBE_POSITIONS.
        for c in zraster::mesh::CUBE_POSITIONS {
            points.push([0, 1, 2].map(|k: usize| if c[k] == 0 { lo[k] } else { hi[k] }));
        }
    }
    // The faces of zraster::mesh::CUBE_FACES (bottom, right, front, left, back, top) for
    // the plate, then the fin (its corners 8 on).
    #[rustfmt::skip]
    const FACES: [Face<Rgb888>; 12] = [
        Face { vertices: &[0, 1, 2, 3], material: GREY },
        Face { vertices: &[1, 5, 6, 2], material: BLUE },
        Face { vertices: &[2, 6, 7, 3], material: GREEN },
        Face { vertices: &[3, 7, 4, 0], material: BLUE },
        Face { vertices: &[0, 4, 5, 1], material: GREY },
        Face { vertices: &[7, 6, 5, 4], material: YELLOW },
        Face { vertices: &[8, 9, 10, 11], material: GREY },
        Face { vertices: &[9, 13, 14, 10], material: GREEN },
        Face { vertices: &[10, 14, 15, 11], material: RED },
        Face { vertices: &[11, 15, 12, 8], material: GREEN },
        Face { vertices: &[8, 12, 13, 9], material: RED },
        Face { vertices: &[15, 14, 13, 12], material: BLUE },
    ];
    let (eye, target) = (Vec3::new(0.3, 1.6, 3.2), Vec3::new(0.0, 0.0, -0.5));
    Case {
        points,
        faces: &FACES,
        eye,
        target,
        cull: Cull::Back,
    }
}

/// The three cases, top to bottom.
pub fn cases() -> [Case; 3] {
    [cyclic_sticks(), interpenetrating(), concave_plate()]
}

/// Draw every case turned `swing` radians, painter left and Z-buffer right, each
/// through `frame` into its place on `display`.
pub fn render(
    display: &mut SimulatorDisplay<Rgb565>,
    frame: &mut Frame<Rgb565>,
    cases: &[Case],
    swing: f32,
) -> Result<(), Box<dyn Error>> {
    for (row, case) in cases.iter().enumerate() {
        // i16 positions around the points' centre; q.model() moves them back.
        let mut table = [[0i16; 3]; 16];
        let q = quantize(&case.points, true, &mut table)?;
        let mesh = Mesh::new(&table[..case.points.len()], q.scale, case.faces);
        let camera = Camera::look_at(case.eye, case.target, Vec3::Y)?
            .perspective(radians(45.0), 0.1, 20.0, Viewport::new(W, H)?)?
            .with_model(Mat4::rotation_y(swing) * q.model());
        let options = RenderOptions {
            cull: case.cull,
            ..Default::default()
        };
        let y = row as i32 * (H as i32 + 8);
        // Depth sorting needs no depth buffer: a list of up to 64 faces, 8 bytes each.
        frame.clear(Rgb565::BLACK);
        let mut sort = DepthSort::<64>::new();
        Renderer::new(&mesh, &camera, options)?.draw_depth_sorted(frame.color_mut(), &mut sort)?;
        frame.flush(&mut display.translated(Point::new(0, y)))?;
        frame.clear(Rgb565::BLACK);
        Renderer::new(&mesh, &camera, options)?.draw(frame)?;
        frame.flush(&mut display.translated(Point::new(W as i32 + 8, y)))?;
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    let (mut pixels, mut depth) = ([Rgb565::BLACK; (W * H) as usize], [0; (W * H) as usize]);
    let mut frame = Frame::new(&mut pixels, &mut depth, W, H)?;
    let mut display = SimulatorDisplay::new(Size::new(2 * W + 8, 3 * H + 16));
    let settings = OutputSettingsBuilder::new().scale(2).build();
    #[cfg(feature = "window")]
    let mut window = Window::new("zraster: painter's algorithm and Z-buffer", &settings);
    let cases = cases();
    let mut drawing = Duration::ZERO;
    for n in 1..=FRAMES {
        // Headless, the views as they are; in the window, rocking ±0.3 radians.
        let swing = if cfg!(feature = "window") {
            0.3 * (n as f32 * 0.02).sin()
        } else {
            0.0
        };
        let start = Instant::now();
        render(&mut display, &mut frame, &cases, swing)?;
        drawing += start.elapsed();
        if n % 100 == 0 {
            let ms = drawing.as_secs_f64() * 10.0; // 1000 ms / 100 frames
            println!("{ms:.3} ms/frame (six views), {:.0} fps", 1000.0 / ms);
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
            .save_png("painter.png")?;
        println!("wrote painter.png");
    }
    Ok(())
}
