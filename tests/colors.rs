//! Every embedded-graphics colour type through the renderer: a square of one `Rgb888`
//! material, drawn into a frame, a display with a Z-buffer and bands, with its pixel
//! values checked against hand-computed ones.

use embedded_graphics::pixelcolor::{
    Bgr555, Bgr565, Bgr666, Bgr888, BinaryColor, Gray2, Gray4, Gray8, Rgb555, Rgb565, Rgb666,
    Rgb888,
};
use embedded_graphics::prelude::*;
use zraster::math::Vec3;
use zraster::mesh::Mesh;
use zraster::shade::DisplayColor;
use zraster::{
    BandBuffers, Bands, Camera, ColorBuffer, Frame, RenderOptions, Renderer, Viewport, WithDepth,
    ZBuffer,
};

const W: u32 = 32;
const H: u32 = 16;
/// Luma 124 (Rec. 601: (77·200 + 150·100 + 29·50 + 128) / 256).
const MATERIAL: Rgb888 = Rgb888::new(200, 100, 50);

/// A square x, y in −1..1 facing the camera: through the orthographic camera below it
/// covers pixels 12..=19, rows 4..=11 (an aligned 8×8 block).
fn square() -> Mesh<'static, Rgb888> {
    const P: [[i16; 3]; 4] = [
        [-16384, -16384, 0],
        [16384, -16384, 0],
        [16384, 16384, 0],
        [-16384, 16384, 0],
    ];
    Mesh::triangles(&P, 1.0 / 16384.0, &[[0, 1, 2], [0, 2, 3]], MATERIAL)
}

fn camera() -> Camera {
    Camera::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::default(), Vec3::Y)
        .unwrap()
        .orthographic(4.0, 1.0, 10.0, Viewport::new(W, H).unwrap())
        .unwrap()
}

fn inside(x: i32, y: i32) -> bool {
    (12..20).contains(&x) && (4..12).contains(&y)
}

/// Draw the square on `bg` three ways, check they agree, and check every pixel: inside
/// the square `want(x, y)`, outside `bg`.
fn check<C: DisplayColor + core::fmt::Debug>(bg: C, want: impl Fn(i32, i32) -> C) {
    let mesh = square();
    let options = RenderOptions::default();
    let n = (W * H) as usize;

    let (mut pixels, mut depth) = (vec![bg; n], vec![0u16; n]);
    let mut frame = Frame::new(&mut pixels, &mut depth, W, H).unwrap();
    frame.clear(bg);
    Renderer::new(&mesh, &camera(), options)
        .unwrap()
        .draw(&mut frame)
        .unwrap();

    let (mut shown, mut zdepth) = (vec![bg; n], vec![0u16; n]);
    let mut display = ColorBuffer::new(&mut shown, W, H).unwrap();
    let mut zbuf = ZBuffer::new(&mut zdepth, W, H).unwrap();
    zbuf.clear();
    Renderer::new(&mesh, &camera(), options)
        .unwrap()
        .draw(&mut WithDepth::new(&mut display, &mut zbuf))
        .unwrap();

    let (mut band_color, mut band_depth) = (vec![bg; W as usize * 3], vec![0u16; W as usize * 3]);
    let mut banded = vec![bg; n];
    let mut banded_display = ColorBuffer::new(&mut banded, W, H).unwrap();
    let mut buffers = BandBuffers::new(&mut band_color, &mut band_depth, W, 3, H, &mut []).unwrap();
    Renderer::new(&mesh, &camera(), options)
        .unwrap()
        .draw(&mut Bands::new(&mut banded_display, &mut buffers, bg))
        .unwrap();

    let name = core::any::type_name::<C>();
    for y in 0..H as i32 {
        for x in 0..W as i32 {
            let expected = if inside(x, y) { want(x, y) } else { bg };
            assert_eq!(
                frame.color().pixel(x, y),
                Some(expected),
                "{name} frame ({x}, {y})"
            );
            assert_eq!(
                display.pixel(x, y),
                Some(expected),
                "{name} display ({x}, {y})"
            );
            assert_eq!(
                banded_display.pixel(x, y),
                Some(expected),
                "{name} bands ({x}, {y})"
            );
        }
    }
}

/// 200, 100, 50 at full light: 5 bits (24.3, 12.2, 6.1), 6 bits (49.4, 24.7, 12.4).
#[test]
fn rgb_types() {
    check(Rgb555::BLACK, |_, _| Rgb555::new(24, 12, 6));
    check(Bgr555::BLACK, |_, _| Bgr555::new(24, 12, 6));
    check(Rgb565::BLACK, |_, _| Rgb565::new(24, 25, 6));
    check(Bgr565::BLACK, |_, _| Bgr565::new(24, 25, 6));
    check(Rgb666::BLACK, |_, _| Rgb666::new(49, 25, 12));
    check(Bgr666::BLACK, |_, _| Bgr666::new(49, 25, 12));
    check(Rgb888::BLACK, |_, _| Rgb888::new(200, 100, 50));
    check(Bgr888::WHITE, |_, _| Bgr888::new(200, 100, 50));
}

/// The 4×4 Bayer thresholds, row by row; the square starts at (12, 4), a multiple of 4,
/// so pixel (x, y) takes threshold `BAYER[y % 4][x % 4]`.
const BAYER: [[u8; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];

fn threshold(x: i32, y: i32) -> u8 {
    BAYER[(y & 3) as usize][(x & 3) as usize]
}

/// Luma 124: Gray8 124; Gray4 116.7 sixteenths → 117 = 7 steps and 5/16, so the
/// pixels whose threshold is below 5 take 8, the rest 7; Gray2 23.3 → 23 = 1 step and
/// 7/16; on/off 7.8 → 8 of 16 on.
#[test]
fn grey_and_binary_types() {
    check(Gray8::BLACK, |_, _| Gray8::new(124));
    check(Gray4::BLACK, |x, y| {
        Gray4::new(if threshold(x, y) < 5 { 8 } else { 7 })
    });
    check(Gray2::WHITE, |x, y| {
        Gray2::new(if threshold(x, y) < 7 { 2 } else { 1 })
    });
    check(BinaryColor::Off, |x, y| {
        if threshold(x, y) < 8 {
            BinaryColor::On
        } else {
            BinaryColor::Off
        }
    });
}
