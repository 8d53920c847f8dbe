//! Damage tracking: after every frame the display holds exactly what a full redraw
//! shows, while the bus carries only what changed.

use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle, Pixel};
use zraster::{damage::Damage, fill_triangle, ColorBuffer, ScreenVertex, ZBuffer};
use zraster_scenes::bus::SpiDisplay;

/// The display model (every pixel kept, the bytes an ST7789 receives counted), showing
/// red at first: not the background, so only what is sent can make it right.
fn spi_display(w: u32, h: u32) -> SpiDisplay {
    SpiDisplay::new(w, h, Rgb565::RED)
}

fn xorshift(mut s: u32) -> impl FnMut() -> u32 {
    move || {
        s ^= s << 13;
        s ^= s >> 17;
        s ^= s << 5;
        s
    }
}

/// Random animations: each frame a few random triangles (sometimes none, sometimes
/// off-screen), flushed whole or in bands of random height through the tracker; after
/// every frame the display equals the frame, pixel for pixel.
#[test]
fn the_display_always_shows_the_full_frame() {
    let (w, h) = (48u32, 36u32);
    let bg = Rgb565::new(1, 2, 3);
    for seed in 1..40u32 {
        let mut rnd = xorshift(seed.wrapping_mul(0x9e37_79b9) | 1);
        let mut display = spi_display(w, h);
        let (mut last, mut row) = (vec![(0u16, 0u16); h as usize], vec![bg; w as usize]);
        let mut damage = Damage::new(&mut last, &mut row, bg).unwrap();
        let mut pixels = vec![bg; (w * h) as usize];
        let mut depth = vec![0u16; (w * h) as usize];
        for frame_no in 0..12 {
            let mut frame = ColorBuffer::new(&mut pixels, w, h).unwrap();
            frame.clear(bg).unwrap();
            let mut zbuf = ZBuffer::new(&mut depth, w, h).unwrap();
            zbuf.clear();
            for _ in 0..(rnd() % 4) {
                let mut v = || {
                    let c = |r: u32, n: u32| (r % (n * 2)) as i32 - (n / 2) as i32;
                    ScreenVertex::from_pixels(c(rnd(), w), c(rnd(), h), (rnd() % 60000) as u16)
                        .unwrap()
                };
                let tri = [v(), v(), v()];
                let color = Rgb565::new((rnd() % 32) as u8, (rnd() % 64) as u8, (rnd() % 32) as u8);
                fill_triangle(&mut frame, &mut zbuf, &tri, color).unwrap();
            }
            if frame_no % 5 == 3 {
                // A stray pixel through draw_iter: passed through and remembered.
                Pixel(
                    Point::new((rnd() % w) as i32, (rnd() % h) as i32),
                    Rgb565::WHITE,
                )
                .draw(&mut frame)
                .unwrap();
            }
            let band = 1 + rnd() % h;
            let mut target = damage.target(&mut display);
            if band >= h {
                frame.flush(&mut target).unwrap();
            } else {
                // Bands: one fill_contiguous each, as the banded renderer sends them.
                let data = frame.as_slice();
                for y0 in (0..h).step_by(band as usize) {
                    let n = band.min(h - y0);
                    let rect = Rectangle::new(Point::new(0, y0 as i32), Size::new(w, n));
                    let rows = &data[(y0 * w) as usize..((y0 + n) * w) as usize];
                    target.fill_contiguous(&rect, rows.iter().copied()).unwrap();
                }
            }
            assert!(
                display.pixels == frame.as_slice() && display.outside == 0,
                "seed {seed}, frame {frame_no}"
            );
        }
    }
}

/// A small object moving on a large screen: far fewer bytes than full frames.
#[test]
fn a_small_moving_object_sends_a_fraction_of_the_frame() {
    let (w, h) = (320u32, 240u32);
    let bg = Rgb565::BLACK;
    let mut display = spi_display(w, h);
    let (mut last, mut row) = (vec![(0u16, 0u16); h as usize], vec![bg; w as usize]);
    let mut damage = Damage::new(&mut last, &mut row, bg).unwrap();
    let mut pixels = vec![bg; (w * h) as usize];
    let mut depth = vec![0u16; (w * h) as usize];
    let full = 11 * u64::from(h) + 2 * u64::from(w * h); // a frame sent as rows
    let mut bytes = Vec::new();
    for step in 0..10 {
        let mut frame = ColorBuffer::new(&mut pixels, w, h).unwrap();
        frame.clear(bg).unwrap();
        let mut zbuf = ZBuffer::new(&mut depth, w, h).unwrap();
        zbuf.clear();
        let x = 40 + step * 8;
        let v = |x: i32, y: i32| ScreenVertex::from_pixels(x, y, 100).unwrap();
        fill_triangle(
            &mut frame,
            &mut zbuf,
            &[v(x, 60), v(x + 60, 60), v(x, 130)],
            Rgb565::GREEN,
        )
        .unwrap();
        display.bytes = 0;
        frame.flush(&mut damage.target(&mut display)).unwrap();
        assert!(display.pixels == frame.as_slice() && display.outside == 0);
        bytes.push(display.bytes);
    }
    assert!(
        bytes[0] >= 2 * u64::from(w * h),
        "the first frame goes whole: {}",
        bytes[0]
    );
    for &b in &bytes[1..] {
        assert!(b * 3 < full, "{b} bytes against {full} for a full frame");
    }
}

/// The bunny turning by random steps, drawn band by band (random band heights) into
/// the tracker: after every frame the display shows the whole-frame picture.
#[test]
fn banded_frames_through_the_tracker_are_exact() {
    use zraster::{
        camera::{Camera, Viewport},
        math::{radians, Mat4, Vec3},
        BandBuffers, Bands, CachedVertex, Frame, Renderer,
    };
    use zraster_bench_scene::{self as scene, bunny};
    let (w, h) = (96u32, 72u32);
    let bg = Rgb565::new(0, 8, 4);
    let mesh = scene::mesh();
    let mut cache = vec![CachedVertex::EMPTY; bunny::BUNNY_POSITIONS.len()];
    let mut display = spi_display(w, h);
    let (mut last, mut row) = (vec![(0u16, 0u16); h as usize], vec![bg; w as usize]);
    let mut damage = Damage::new(&mut last, &mut row, bg).unwrap();
    let mut rnd = xorshift(0x1234_5677);
    let (mut yaw, mut sent) = (0.0f32, Vec::new());
    for _ in 0..16 {
        yaw += (rnd() % 40) as f32;
        let vp = Viewport::new(w, h).unwrap();
        let xf = Camera::look_at(
            Vec3::new(0.0, 0.0, 1.6 + (rnd() % 8) as f32 * 0.1),
            Vec3::new(0.0, 0.0, 0.6),
            Vec3::Y,
        )
        .unwrap()
        .perspective(radians(60.0), 0.1, 10.0, vp)
        .unwrap()
        .with_model(
            Mat4::rotation_y(radians(yaw))
                * Mat4::scaling(Vec3::new(
                    bunny::BUNNY_FIT,
                    bunny::BUNNY_FIT,
                    bunny::BUNNY_FIT,
                )),
        );
        // The whole frame, for reference.
        let (mut pixels, mut depth) = (vec![bg; (w * h) as usize], vec![0u16; (w * h) as usize]);
        let mut frame = Frame::new(&mut pixels, &mut depth, w, h).unwrap();
        frame.clear(bg);
        Renderer::with_cache(&mesh, &xf, scene::options(), &mut cache)
            .unwrap()
            .draw(&mut frame)
            .unwrap();
        // Bands through the tracker.
        let rows = 1 + rnd() % 20;
        let (mut cb, mut zb) = (
            vec![bg; (w * rows) as usize],
            vec![0u16; (w * rows) as usize],
        );
        let mut bins =
            vec![0u16; BandBuffers::<Rgb565>::bins_needed(bunny::BUNNY_INDICES.len(), h, rows)];
        let mut buffers = BandBuffers::new(&mut cb, &mut zb, w, rows, h, &mut bins).unwrap();
        let mut target = damage.target(&mut display);
        let mut bands = Bands::new(&mut target, &mut buffers, bg);
        Renderer::with_cache(&mesh, &xf, scene::options(), &mut cache)
            .unwrap()
            .draw(&mut bands)
            .unwrap();
        sent.push(damage.sent());
        assert!(
            display.pixels == pixels && display.outside == 0,
            "frame {}",
            sent.len()
        );
    }
    // After the first frame, a fraction of the screen goes out.
    assert!(
        sent[1..].iter().all(|&s| s < u64::from(w * h) / 2),
        "{sent:?}"
    );
}
