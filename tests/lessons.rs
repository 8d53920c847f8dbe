//! The example lessons (`examples/lesson*.rs`) and the demos (`bunny`, `cube`,
//! `hidden_line`, `oled`, `painter`) draw what they say: each file is included here as
//! a module and its `render` checked on concrete pixels. The demos must draw exactly the
//! scenes of `zraster-scenes`, whose pictures `tests/golden.rs` pins, so that the PNGs the
//! examples write are the README's.

use embedded_graphics::pixelcolor::{BinaryColor, Gray4, GrayColor, Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::SimulatorDisplay;
use std::collections::HashSet;
use zraster::math::radians;
use zraster::{BandBuffers, CachedVertex, ColorBuffer, Frame, Renderer};

#[allow(dead_code)]
#[path = "../examples/lesson1_triangle.rs"]
mod lesson1;
#[allow(dead_code)]
#[path = "../examples/lesson2_mesh.rs"]
mod lesson2;
#[allow(dead_code)]
#[path = "../examples/lesson3_camera.rs"]
mod lesson3;
#[allow(dead_code)]
#[path = "../examples/lesson4_lighting.rs"]
mod lesson4;
#[allow(dead_code)]
#[path = "../examples/lesson5_bands.rs"]
mod lesson5;
#[allow(dead_code)]
#[path = "../examples/lesson6_flash_mesh.rs"]
mod lesson6;
#[allow(dead_code)]
#[path = "../examples/lesson7_scene.rs"]
mod lesson7;

#[allow(dead_code)]
#[path = "../examples/bunny.rs"]
mod bunny;
#[allow(dead_code)]
#[path = "../examples/cube.rs"]
mod cube;
#[allow(dead_code)]
#[path = "../examples/hidden_line.rs"]
mod hidden_line;
#[allow(dead_code)]
#[path = "../examples/oled.rs"]
mod oled;
#[allow(dead_code)]
#[path = "../examples/painter.rs"]
mod painter;

type Result = std::result::Result<(), Box<dyn std::error::Error>>;

/// A frame's colour and depth memory.
fn memory<C: Copy>(w: u32, h: u32, background: C) -> (Vec<C>, Vec<u16>) {
    (
        vec![background; (w * h) as usize],
        vec![0; (w * h) as usize],
    )
}

/// The distinct colours in the `w`-wide rectangle of `frame` from (x0, 0) to (x1, h).
fn colours(frame: &Frame<Rgb565>, x0: i32, x1: i32) -> HashSet<Rgb565> {
    let rows = frame.color().rows() as i32;
    (0..rows)
        .flat_map(|y| (x0..x1).map(move |x| (x, y)))
        .filter_map(|(x, y)| frame.color().pixel(x, y))
        .collect()
}

#[test]
fn lesson1_draws_the_triangle_and_turns_it() -> Result {
    use lesson1::{render, H, W};
    let (mut pixels, mut depth) = memory(W, H, Rgb565::WHITE);
    let mut frame = Frame::new(&mut pixels, &mut depth, W, H)?;
    render(&mut frame, 0.0)?;
    let at = |frame: &Frame<Rgb565>, x, y| frame.color().pixel(x, y);
    // Rgb888 (255, 140, 0) in RGB565: 255 → 31 of 31, 140 → 35 of 63.
    let orange = Some(Rgb565::new(31, 35, 0));
    assert_eq!(at(&frame, 0, 0), Some(Rgb565::BLACK), "cleared background");
    assert_eq!(at(&frame, 80, 60), orange, "the middle of the triangle");
    assert_eq!(at(&frame, 80, 20), orange, "near the apex, upright");
    assert_eq!(frame.depth().depth(0, 0), Some(zraster::ZBuffer::FAR));
    // Turned upside down, the apex points down: the top is background.
    render(&mut frame, std::f32::consts::PI)?;
    assert_eq!(at(&frame, 80, 20), Some(Rgb565::BLACK));
    assert_eq!(at(&frame, 80, 60), orange);
    Ok(())
}

#[test]
fn lesson2_culls_the_faces_turned_away() -> Result {
    use lesson2::{render, H, PYRAMID, W};
    PYRAMID.validate()?;
    let (mut pixels, mut depth) = memory(W, H, Rgb565::WHITE);
    let mut frame = Frame::new(&mut pixels, &mut depth, W, H)?;
    let stats = render(&mut frame, 0.0)?;
    // Six triangles (the base quad is two); from above and in front, the base and the
    // back face turn away; the front, left and right sides are drawn.
    assert_eq!((stats.triangles_in, stats.culled, stats.drawn), (6, 3, 3));
    assert_eq!(frame.color().pixel(0, 0), Some(Rgb565::BLACK));
    // The front face, flat red (230, 40, 40) in RGB565, in the middle of the screen.
    assert_eq!(frame.color().pixel(80, 70), Some(Rgb565::new(28, 10, 5)));
    // Left, front and right faces in their colours, and the background: four colours.
    assert_eq!(colours(&frame, 0, W as i32).len(), 4);
    Ok(())
}

#[test]
fn lesson3_perspective_and_orthographic_differ() -> Result {
    use lesson3::{render, H, W};
    let (mut pixels, mut depth) = memory(W, H, Rgb565::WHITE);
    let mut frame = Frame::new(&mut pixels, &mut depth, W, H)?;
    let sky = Rgb565::new(2, 4, 8);
    for t in [0.0, 1.0, 2.5] {
        render(&mut frame, t)?;
        for (x, y) in [(0, 0), (159, 159), (160, 0), (319, 159)] {
            assert_eq!(
                frame.color().pixel(x, y),
                Some(sky),
                "corner ({x}, {y}) at t = {t}"
            );
        }
        // The cube at the centre of both views, each in its own viewport.
        assert_ne!(
            frame.color().pixel(80, 80),
            Some(sky),
            "perspective, t = {t}"
        );
        assert_ne!(
            frame.color().pixel(240, 80),
            Some(sky),
            "orthographic, t = {t}"
        );
        let lit = |x0: i32| {
            (0..160)
                .flat_map(|y| (x0..x0 + 160).map(move |x| (x, y)))
                .filter(|&(x, y)| frame.color().pixel(x, y) != Some(sky))
                .count()
        };
        let (left, right) = (lit(0), lit(160));
        assert!(
            left > 1000 && right > 1000 && left != right,
            "{left} {right}"
        );
        // fit_depth spreads the cube over the depth range: its nearest point is near 0.
        let nearest = frame.depth().as_slice().iter().min().copied();
        assert!(nearest < Some(2000), "nearest depth {nearest:?}");
    }
    Ok(())
}

#[test]
fn lesson4_flat_lambert_and_gouraud_differ() -> Result {
    use lesson4::{render, H, W};
    let (mut pixels, mut depth) = memory(W, H, Rgb565::WHITE);
    let mut frame = Frame::new(&mut pixels, &mut depth, W, H)?;
    render(&mut frame, 0.7)?;
    for x in [60, 180, 300] {
        assert_ne!(
            frame.color().pixel(x, 60),
            Some(Rgb565::BLACK),
            "ball at x = {x}"
        );
    }
    let panel = |i: i32| colours(&frame, 120 * i, 120 * (i + 1));
    let (flat, lambert, gouraud) = (panel(0), panel(1), panel(2));
    // Flat: the background and the ball's one colour.
    let blue = Rgb565::from(Rgb888::new(90, 170, 255));
    assert_eq!(flat, HashSet::from([Rgb565::BLACK, blue]));
    // Lambert: one brightness a face, at most 20 faces; Gouraud: a smooth ramp.
    assert!(
        (4..=21).contains(&lambert.len()),
        "{} Lambert colours",
        lambert.len()
    );
    assert!(
        gouraud.len() > 2 * lambert.len(),
        "{} Gouraud colours",
        gouraud.len()
    );
    Ok(())
}

#[test]
fn lesson5_bands_equal_the_whole_frame() -> Result {
    use lesson5::{camera, render, CUBE, H, OPTIONS, ROWS, W};
    let (mut band_color, mut band_depth) = memory(W, ROWS, Rgb565::BLACK);
    let mut bins = vec![0; BandBuffers::<Rgb565>::bins_needed(12, H, ROWS)];
    let mut buffers = BandBuffers::new(&mut band_color, &mut band_depth, W, ROWS, H, &mut bins)?;
    assert_eq!(buffers.bands(), 15);
    let mut cache = [CachedVertex::EMPTY; 8];
    for angle in [0.0, 0.4, 1.3, 2.9] {
        let (mut pixels, mut depth) = memory(W, H, Rgb565::WHITE);
        let mut whole = Frame::new(&mut pixels, &mut depth, W, H)?;
        whole.clear(Rgb565::BLACK);
        let mut renderer = Renderer::new(&CUBE, &camera(angle)?, OPTIONS)?;
        renderer.draw(&mut whole)?;

        let mut shown = vec![Rgb565::WHITE; (W * H) as usize];
        let mut display = ColorBuffer::new(&mut shown, W, H)?;
        let stats = render(&mut display, &mut buffers, &mut cache, angle, "")?;
        assert!(
            display.as_slice() == whole.color().as_slice(),
            "angle {angle}"
        );
        assert_eq!(stats, renderer.stats(), "angle {angle}");
        assert!(stats.pixels_written > 10_000, "the cube is on the screen");

        // The caption lands in the bottom rows only.
        let mut captioned = vec![Rgb565::WHITE; (W * H) as usize];
        let mut display = ColorBuffer::new(&mut captioned, W, H)?;
        render(
            &mut display,
            &mut buffers,
            &mut cache,
            angle,
            "16-row bands",
        )?;
        let changed: Vec<usize> = (0..(W * H) as usize)
            .filter(|&i| captioned[i] != shown[i])
            .map(|i| i / W as usize)
            .collect();
        assert!(!changed.is_empty());
        assert!(
            changed.iter().all(|&y| (220..235).contains(&y)),
            "rows {changed:?}"
        );
    }
    Ok(())
}

#[test]
fn lesson6_draws_the_flash_bunny_on_three_colour_types() -> Result {
    use lesson6::{render, H, W};
    let n = (W * H) as usize;
    let mut depth = vec![0; n];
    let (mut rgb, mut grey, mut mono) = (
        vec![Rgb565::WHITE; n],
        vec![Gray4::WHITE; n],
        vec![BinaryColor::On; n],
    );
    render(&mut rgb, &mut depth, Rgb565::BLACK, 0.5)?;
    let rgb_depth = depth.clone();
    render(&mut grey, &mut depth, Gray4::BLACK, 0.5)?;
    assert_eq!(depth, rgb_depth, "the same depths whatever the colour type");
    render(&mut mono, &mut depth, BinaryColor::Off, 0.5)?;
    // Background where the bunny is not, its body in the middle of the view.
    let middle = (H / 2 * W + W / 2) as usize;
    assert_eq!(
        (rgb[0], grey[0], mono[0]),
        (Rgb565::BLACK, Gray4::BLACK, BinaryColor::Off)
    );
    assert_ne!(rgb[middle], Rgb565::BLACK);
    assert_ne!(grey[middle], Gray4::BLACK);
    let covered = depth
        .iter()
        .filter(|&&z| z != zraster::ZBuffer::FAR)
        .count();
    assert!(covered > n / 5, "the bunny covers {covered} of {n} pixels");
    // Shading: many greys; on/off, dithering lights part of the covered pixels.
    let levels: HashSet<u8> = grey.iter().map(|g| g.luma()).collect();
    assert!(levels.len() >= 10, "{} grey levels", levels.len());
    let on = mono.iter().filter(|&&p| p == BinaryColor::On).count();
    assert!(
        on > covered / 5 && on < covered,
        "{on} of {covered} pixels on"
    );
    Ok(())
}

#[test]
fn lesson7_meshes_share_one_depth_buffer_in_any_order() -> Result {
    use lesson7::{camera, render, scene, H, SKY, W};
    let (mut pixels, mut depth) = memory(W, H, Rgb565::WHITE);
    let mut frame = Frame::new(&mut pixels, &mut depth, W, H)?;
    let (mut pixels2, mut depth2) = memory(W, H, Rgb565::WHITE);
    let mut reversed = Frame::new(&mut pixels2, &mut depth2, W, H)?;
    for t in [0.0, 1.0, 100.0 / 60.0] {
        render(&mut frame, t)?;
        assert_eq!(frame.color().pixel(0, 0), Some(SKY));
        // Every mesh drawn alone covers pixels; together the nearest wins, so drawing
        // them in the opposite order gives the same frame.
        reversed.clear(SKY);
        let mut written = 0;
        for (mesh, model, options) in scene(t).into_iter().rev() {
            let mut renderer = Renderer::new(&mesh, &camera()?.with_model(model), options)?;
            renderer.draw(&mut reversed)?;
            assert!(
                renderer.stats().pixels_written > 0,
                "a mesh is not in view at t = {t}"
            );
            written += renderer.stats().pixels_written;
        }
        assert!(written > u64::from(W * H) / 2);
        assert!(
            reversed.color().as_slice() == frame.color().as_slice(),
            "t = {t}"
        );
        assert_eq!(
            reversed.depth().as_slice(),
            frame.depth().as_slice(),
            "t = {t}"
        );
    }
    Ok(())
}

/// The number of pixels where `a` and `b` differ (all of them if the sizes differ).
fn differing<C: PixelColor>(a: &SimulatorDisplay<C>, b: &SimulatorDisplay<C>) -> usize {
    if a.size() != b.size() {
        return usize::MAX;
    }
    a.bounding_box()
        .points()
        .filter(|&p| a.get_pixel(p) != b.get_pixel(p))
        .count()
}

#[test]
fn bunny_draws_the_golden_scene() -> Result {
    let (w, h) = (bunny::W, bunny::H);
    let (mut pixels, mut depth) = memory(w, h, Rgb565::WHITE);
    let mut frame = Frame::new(&mut pixels, &mut depth, w, h)?;
    let mut display = SimulatorDisplay::new(Size::new(2 * w + 8, h));
    bunny::render(&mut display, &mut frame, radians(30.0))?;
    assert_eq!(differing(&display, &zraster_scenes::bunny_shading()), 0);
    // Turned, it draws another picture.
    bunny::render(&mut display, &mut frame, radians(40.0))?;
    assert!(differing(&display, &zraster_scenes::bunny_shading()) > 1000);
    Ok(())
}

#[test]
fn cube_draws_the_golden_scene() -> Result {
    let (w, h) = (cube::W, cube::H);
    let (mut pixels, mut depth) = memory(w, h, Rgb565::WHITE);
    let mut frame = Frame::new(&mut pixels, &mut depth, w, h)?;
    let mut display = SimulatorDisplay::new(Size::new(2 * w + 8, h));
    cube::render(&mut display, &mut frame, 0.0)?;
    assert_eq!(differing(&display, &zraster_scenes::cube_culling()), 0);
    Ok(())
}

#[test]
fn hidden_line_draws_the_golden_scene() -> Result {
    let (w, h) = (hidden_line::W, hidden_line::H);
    let (mut pixels, mut depth) = memory(w, h, Rgb565::WHITE);
    let mut frame = Frame::new(&mut pixels, &mut depth, w, h)?;
    let mut display = SimulatorDisplay::new(Size::new(2 * w + 8, h));
    hidden_line::render(&mut display, &mut frame, 0.0)?;
    assert_eq!(differing(&display, &zraster_scenes::cube_hidden_line()), 0);
    Ok(())
}

#[test]
fn oled_draws_the_golden_scene() -> Result {
    let (w, h) = (oled::W, oled::H);
    let (mut pixels, mut depth) = memory(w, h, BinaryColor::On);
    let mut frame = Frame::new(&mut pixels, &mut depth, w, h)?;
    oled::render(&mut frame, radians(-40.0))?;
    let mut display = SimulatorDisplay::new(Size::new(w, h));
    frame.flush(&mut display)?;
    assert_eq!(differing(&display, &zraster_scenes::mono_oled()), 0);
    Ok(())
}

#[test]
fn painter_draws_the_golden_scene() -> Result {
    let (w, h) = (painter::W, painter::H);
    let (mut pixels, mut depth) = memory(w, h, Rgb565::WHITE);
    let mut frame = Frame::new(&mut pixels, &mut depth, w, h)?;
    let mut display = SimulatorDisplay::new(Size::new(2 * w + 8, 3 * h + 16));
    painter::render(&mut display, &mut frame, &painter::cases(), 0.0)?;
    assert_eq!(
        differing(&display, &zraster_scenes::painter_vs_zbuffer()),
        0
    );
    Ok(())
}
