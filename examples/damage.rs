//! How many bytes the display bus carries per frame, whole frames against damage
//! tracking (`zraster::damage`), for the bench bunny turning on a 320×240 RGB565
//! screen, near (as bunny-320) and far (half the size).
//!
//! `cargo run --release --example damage` prints a table: bytes per frame counted as an
//! ST7789 on SPI takes them (`zraster_scenes::bus`: CASET, RASET and RAMWR, 11 bytes, per
//! address window, then 2 bytes a pixel) and the frame rate the bus alone allows at 62.5 MHz.

use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
use zraster::{
    camera::{Camera, Viewport},
    damage::Damage,
    math::{radians, Mat4, Vec3},
    CachedVertex, Frame, Renderer,
};
use zraster_bench_scene::{self as scene, bunny, H, W};
use zraster_scenes::bus::SpiDisplay;

/// Mean bytes per frame (after the first) over `frames` frames turning 3° each, whole
/// and through damage tracking; and the share of the screen the bunny covers.
fn measure(distance: f32, frames: u32) -> (u64, u64, f64) {
    let (n, bg) = ((W * H) as usize, Rgb565::BLACK);
    let (mut pixels, mut depth) = (vec![bg; n], vec![0u16; n]);
    let mut cache = vec![CachedVertex::EMPTY; bunny::BUNNY_POSITIONS.len()];
    let (mut last, mut row) = (vec![(0u16, 0u16); H as usize], vec![bg; W as usize]);
    let mut damage = Damage::new(&mut last, &mut row, bg).unwrap();
    let mesh = scene::mesh();
    let vp = Viewport::new(W, H).unwrap();
    let (mut whole, mut damaged, mut covered) = (0u64, 0u64, 0u64);
    for i in 0..=frames {
        let cam = Camera::look_at(
            Vec3::new(0.0, 0.0, distance),
            Vec3::new(0.0, 0.0, 0.6),
            Vec3::Y,
        )
        .unwrap()
        .perspective(radians(60.0), 0.1, 10.0, vp)
        .unwrap();
        let fit = bunny::BUNNY_FIT;
        let xf = cam.with_model(
            Mat4::rotation_y(radians(30.0 + 3.0 * i as f32))
                * Mat4::scaling(Vec3::new(fit, fit, fit)),
        );
        let mut frame = Frame::new(&mut pixels, &mut depth, W, H).unwrap();
        frame.clear(bg);
        let mut r = Renderer::with_cache(&mesh, &xf, scene::options(), &mut cache).unwrap();
        r.draw(&mut frame).unwrap();
        let (mut full, mut bus) = (SpiDisplay::new(W, H, bg), SpiDisplay::new(W, H, bg));
        frame.flush(&mut full).unwrap();
        frame.flush(&mut damage.target(&mut bus)).unwrap();
        if i > 0 {
            whole += full.bytes;
            damaged += bus.bytes;
            covered += frame
                .color()
                .as_slice()
                .iter()
                .filter(|&&c| c != bg)
                .count() as u64;
        }
    }
    let f = u64::from(frames);
    (
        whole / f,
        damaged / f,
        covered as f64 / f as f64 / (W * H) as f64,
    )
}

fn main() {
    const SPI: f64 = 62.5e6 / 8.0; // bytes a second
    println!("| bunny on 320×240 | covers | bytes a frame, whole | with damage tracking | ratio | bus-bound fps, whole | with damage |");
    println!("|---|---:|---:|---:|---:|---:|---:|");
    for (name, distance) in [("near (bunny-320)", 1.6f32), ("far (half size)", 2.6)] {
        let (whole, damaged, share) = measure(distance, 60);
        println!(
            "| {name} | {:.1} % | {whole} | {damaged} | {:.1}× | {:.0} | {:.0} |",
            share * 100.0,
            whole as f64 / damaged as f64,
            SPI / whole as f64,
            SPI / damaged as f64
        );
    }
}
