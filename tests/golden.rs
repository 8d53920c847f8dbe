//! Golden images: every example scene, compared pixel for pixel with `tests/golden/`.
//!
//! After a deliberate change to a scene or to the renderer, regenerate them with
//! `ZRASTER_BLESS=1 cargo test --test golden` and commit the new images with the change.

use zraster_scenes as scenes;

use embedded_graphics::{pixelcolor::Rgb888, prelude::*};
use embedded_graphics_simulator::{OutputSettings, SimulatorDisplay};

fn to_rgb<C: PixelColor + Into<Rgb888>>(d: &SimulatorDisplay<C>) -> SimulatorDisplay<Rgb888> {
    let size = d.size();
    let mut out = SimulatorDisplay::new(size);
    let pixels = (0..size.height as i32)
        .flat_map(|y| (0..size.width as i32).map(move |x| Point::new(x, y)))
        .map(|p| Pixel(p, d.get_pixel(p).into()));
    out.draw_iter(pixels).unwrap();
    out
}

fn check<C: PixelColor + Into<Rgb888>>(name: &str, display: &SimulatorDisplay<C>) {
    let path = format!("{}/tests/golden/{name}.png", env!("CARGO_MANIFEST_DIR"));
    let got = to_rgb(display);
    if std::env::var_os("ZRASTER_BLESS").is_some() {
        got.to_rgb_output_image(&OutputSettings::default())
            .save_png(&path)
            .unwrap();
        return;
    }
    let want = SimulatorDisplay::<Rgb888>::load_png(&path)
        .unwrap_or_else(|e| panic!("{path}: {e} (run with ZRASTER_BLESS=1 to create it)"));
    assert_eq!(want.size(), got.size(), "{name}: size");
    if let Some(diff) = want.diff(&got) {
        let n = diff
            .bounding_box()
            .points()
            .filter(|&p| diff.get_pixel(p).is_on())
            .count();
        let out = format!("{}/target/{name}.actual.png", env!("CARGO_MANIFEST_DIR"));
        got.to_rgb_output_image(&OutputSettings::default())
            .save_png(&out)
            .ok();
        panic!("{name}: {n} pixels differ from {path} (actual image: {out})");
    }
}

#[test]
fn cube_culling() {
    check("cube", &scenes::cube_culling());
}

#[test]
fn painter_vs_zbuffer() {
    check("painter", &scenes::painter_vs_zbuffer());
}

#[test]
fn bunny_lambert_and_gouraud() {
    check("bunny", &scenes::bunny_shading());
}

#[test]
fn cube_hidden_line_and_wireframe() {
    check("hidden_line", &scenes::cube_hidden_line());
}

#[test]
fn monochrome_oled() {
    check("oled", &scenes::mono_oled());
}
