//! The seeds' interpenetrating triangles: two triangles that pass through each other,
//! which no drawing order can show correctly, drawn with the Z-buffer in both orders.
//! Left: red then green. Middle: green then red (identical). Right: the Z-buffer as a
//! grey image (near = light), as the seeds' Java sample shows it.
//!
//! `cargo run --release --example interpenetrating` writes `interpenetrating.png`.

mod common;

use embedded_graphics::{
    pixelcolor::{Gray8, Rgb565, Rgb888},
    prelude::*,
};
use embedded_graphics_simulator::SimulatorDisplay;
use zraster::{fill_triangle, ColorBuffer, ScreenVertex, ZBuffer};

const W: u32 = 160;
const H: u32 = 120;

fn main() -> Result<(), zraster::Error> {
    let v = ScreenVertex::from_f32;
    // Red is near on the left and far on the right, green the other way round: they
    // pass through each other along a slanted line in the middle.
    let red = [
        v(8.0, 8.0, 1000.0)?,
        v(152.0, 40.0, 40000.0)?,
        v(20.0, 112.0, 1000.0)?,
    ];
    let green = [
        v(6.0, 60.0, 40000.0)?,
        v(150.0, 6.0, 1000.0)?,
        v(140.0, 114.0, 6000.0)?,
    ];

    let mut display = SimulatorDisplay::<Rgb888>::new(Size::new(3 * W + 20, H));
    let mut pixels = vec![Rgb565::BLACK; (W * H) as usize];
    let mut depth = vec![0u16; (W * H) as usize];
    for (panel, order) in [[0, 1], [1, 0]].iter().enumerate() {
        let mut frame = ColorBuffer::new(&mut pixels, W, H)?;
        frame.clear(Rgb565::BLACK).ok();
        let mut zbuf = ZBuffer::new(&mut depth, W, H)?;
        zbuf.clear();
        for &i in order {
            let (tri, color) = [(&red, Rgb565::RED), (&green, Rgb565::GREEN)][i];
            fill_triangle(&mut frame, &mut zbuf, tri, color).ok();
        }
        let mut panel_target = display.translated(Point::new(panel as i32 * (W as i32 + 10), 0));
        let mut converted = panel_target.color_converted::<Rgb565>();
        frame.flush(&mut converted).ok();
    }
    // The depth buffer of the last panel, as grey: near is light, the cleared far is black.
    let grey = depth.iter().map(|&z| {
        let l = if z == u16::MAX {
            0
        } else {
            255 - (z >> 7).min(255) as u8
        };
        Rgb888::from(Gray8::new(l))
    });
    let area = embedded_graphics::primitives::Rectangle::new(
        Point::new(2 * (W as i32 + 10), 0),
        Size::new(W, H),
    );
    display.fill_contiguous(&area, grey).ok();
    common::present(&display, "interpenetrating", 2);
    Ok(())
}
