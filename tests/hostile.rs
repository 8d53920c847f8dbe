//! Inputs chosen to break arithmetic: each test here failed (a debug-build overflow
//! panic, a wrapped count, or a panic in a later call) before its fix.

use embedded_graphics::{
    pixelcolor::{Rgb565, Rgb888},
    prelude::*,
    primitives::Rectangle,
};
use zraster::{
    camera::{Camera, Transform, Viewport},
    math::{radians, Vec3},
    mesh::{Face, Mesh},
    CachedVertex, ColorBuffer, Cull, DepthSort, Error, Frame, RenderOptions, Renderer, WithDepth,
    ZBuffer,
};

/// A display of any size up to 8192² that only counts what it is sent.
struct Counter {
    size: Size,
    pixels: u64,
}

impl OriginDimensions for Counter {
    fn size(&self) -> Size {
        self.size
    }
}

impl DrawTarget for Counter {
    type Color = Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        it: I,
    ) -> Result<(), Self::Error> {
        let area = self.bounding_box();
        for Pixel(p, _) in it {
            assert!(area.contains(p), "pixel {p:?} outside the display");
            self.pixels += 1;
        }
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, _: Rgb565) -> Result<(), Self::Error> {
        assert_eq!(
            area.intersection(&self.bounding_box()),
            *area,
            "run outside the display"
        );
        self.pixels += u64::from(area.size.width) * u64::from(area.size.height);
        Ok(())
    }
}

fn camera(w: u32, h: u32, eye: Vec3, near: f32, far: f32) -> Transform {
    let vp = Viewport::new(w, h).unwrap();
    Camera::look_at(eye, Vec3::default(), Vec3::Y)
        .unwrap()
        .perspective(radians(60.0), near, far, vp)
        .unwrap()
}

/// Pixel counts are 64-bit: 65 quads covering an 8192² screen, drawn by the painter's
/// algorithm (no depth test, every pixel written), are 65 · 8192² > 2³² pixels.
#[test]
fn pixel_counts_pass_two_to_the_32() {
    const N: usize = 65;
    let positions = [
        [-1000, -1000, 0],
        [1000, -1000, 0],
        [1000, 1000, 0],
        [-1000, 1000, 0],
    ];
    let quad: [u16; 4] = [0, 1, 2, 3];
    let faces = [Face {
        vertices: &quad[..],
        material: Rgb888::WHITE,
    }; N];
    let mesh = Mesh::new(&positions, 0.01, &faces);
    let xf = camera(8192, 8192, Vec3::new(0.0, 0.0, 1.0), 0.1, 10.0);
    let mut display = Counter {
        size: Size::new(8192, 8192),
        pixels: 0,
    };
    let mut sort = DepthSort::<N>::new();
    let mut r = Renderer::new(&mesh, &xf, RenderOptions::default()).unwrap();
    r.draw_depth_sorted(&mut display, &mut sort).unwrap();
    let want = N as u64 * 8192 * 8192;
    assert!(want > u64::from(u32::MAX));
    assert_eq!(display.pixels, want);
    assert_eq!(r.stats().pixels_written, want);
    assert_eq!(r.stats().pixels_tested, want);
}

/// The painter's depth key adds up a face's clip-space depths: a polygon listing
/// millions of vertices far away must not overflow it (it did in `i64`).
#[test]
fn the_painters_key_takes_a_face_of_millions_of_vertices() {
    // Three vertices far down the view axis (so that the translation sets the scale
    // of clip-space depth, near its limit of 2⁴³); the face lists the third over and
    // over (a fan of zero-area triangles after the first).
    let positions = [[-30000, -30000, 0], [30000, -30000, 0], [0, 30000, 0]];
    let mut list = vec![2u16; 2_400_000];
    list[0] = 0;
    list[1] = 1;
    let faces = [Face {
        vertices: &list[..],
        material: Rgb888::RED,
    }];
    let mesh = Mesh::new(&positions, 0.01, &faces);
    let xf = camera(32, 32, Vec3::new(0.0, 0.0, 1000.0), 1.0, 10000.0);
    let mut cache = [CachedVertex::EMPTY; 3];
    let mut pixels = [Rgb565::BLACK; 32 * 32];
    let mut frame = ColorBuffer::new(&mut pixels, 32, 32).unwrap();
    let mut sort = DepthSort::<1>::new();
    let opts = RenderOptions {
        cull: Cull::None,
        ..Default::default()
    };
    let mut r = Renderer::with_cache(&mesh, &xf, opts, &mut cache).unwrap();
    r.draw_depth_sorted(&mut frame, &mut sort).unwrap();
    assert_eq!(sort.order().collect::<Vec<_>>(), [0]);
    // The one real triangle is drawn, red, around the centre.
    assert_eq!(frame.pixel(16, 16), Some(Rgb565::RED));
    assert_eq!(r.stats().drawn, 1);
}

/// Bands far from the screen (|first row| ≥ 2²⁷, where rows in 1/16 pixel leave `i32`)
/// draw nothing and report it, through every path.
#[test]
fn bands_beyond_two_to_the_27_rows_draw_nothing() {
    let faces = [Face {
        vertices: &[0, 1, 2][..],
        material: Rgb888::GREEN,
    }];
    let positions = [[-100, -100, 0], [100, -100, 0], [0, 100, 0]];
    let mesh = Mesh::new(&positions, 0.01, &faces);
    let xf = camera(64, 64, Vec3::new(0.0, 0.0, 2.0), 0.1, 10.0);
    for first in [1 << 27, 1 << 28, i32::MAX - 4, -(1 << 27) - 4, i32::MIN] {
        let mut d = [0u16; 64 * 4];
        let mut c = [Rgb565::BLACK; 64 * 4];
        let mut zbuf = ZBuffer::new_band(&mut d, 64, 4, first).unwrap();
        zbuf.clear();
        let color = ColorBuffer::new_band(&mut c, 64, 4, first).unwrap();
        let mut frame = Frame::from_buffers(color, zbuf);
        let mut r = Renderer::new(&mesh, &xf, RenderOptions::default()).unwrap();
        r.draw(&mut frame).unwrap();
        let (color, zbuf) = frame.parts_mut();
        r.draw(&mut WithDepth::new(color, zbuf)).unwrap();
        r.draw_hidden_line(color, zbuf, Rgb565::WHITE).unwrap();
        assert_eq!(r.stats().pixels_written, 0, "first row {first}");
        assert_eq!(r.stats().drawn, 1, "first row {first}");
        assert!(c.iter().all(|&p| p == Rgb565::BLACK));
    }
}

/// A band whose rows would run past `i32::MAX` is refused (it made `flush` panic), and
/// the last band that fits flushes.
#[test]
fn band_origins_that_overflow_are_errors() {
    let mut c = [Rgb565::RED; 8 * 4];
    let mut d = [0u16; 8 * 4];
    assert_eq!(
        ColorBuffer::new_band(&mut c, 8, 4, i32::MAX - 3).err(),
        Some(Error::OutOfRange)
    );
    assert_eq!(
        ZBuffer::new_band(&mut d, 8, 4, i32::MAX).err(),
        Some(Error::OutOfRange)
    );
    let mut band = ColorBuffer::new_band(&mut c, 8, 4, i32::MAX - 4).unwrap();
    assert_eq!(band.set_first_row(i32::MAX - 2), Err(Error::OutOfRange));
    assert_eq!(band.first_row(), i32::MAX - 4);
    let mut display = Counter {
        size: Size::new(8, 8),
        pixels: 0,
    };
    band.flush(&mut display).unwrap();
    assert_eq!(display.pixels, 0);
    band.set_first_row(i32::MIN).unwrap();
    band.flush(&mut display).unwrap();
    assert_eq!(display.pixels, 0);
    band.set_first_row(6).unwrap();
    band.flush(&mut display).unwrap();
    assert_eq!(display.pixels, 8 * 2);
}

/// Viewport corners at the ends of `i32` are errors, not an `abs` overflow.
#[test]
fn viewport_corners_at_the_ends_of_i32_are_errors() {
    for (x, y) in [(i32::MIN, 0), (0, i32::MIN), (i32::MAX, 0), (-8193, 0)] {
        assert_eq!(
            Viewport::at(x, y, 10, 10),
            Err(Error::TooLarge),
            "({x}, {y})"
        );
    }
    assert!(Viewport::at(-8192, 8192, 10, 10).is_ok());
}

/// Hidden-line removal on slivers seen almost edge-on right at the near plane: their
/// depth slopes reach ±2³¹ per pixel, whose sum overflowed `u32`. Each is drawn without
/// a panic and its visible edges stay on the screen.
#[test]
fn hidden_line_on_edge_on_slivers_at_the_near_plane() {
    let mut s = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        s
    };
    let xf = camera(64, 64, Vec3::new(0.0, 0.0, 1.0), 0.999, 1000.0);
    let mut edges = 0;
    for _ in 0..3000 {
        let mut r = |span: u64| (next() % (2 * span + 1)) as i16 - span as i16;
        // A point just beyond the near plane and two far behind it, nearly on one line
        // of sight: a thin, steep sliver.
        let positions = [
            [r(3), r(3), r(2)],
            [r(40), r(40), -32000 + r(500)],
            [r(40), r(40), -32000 + r(500)],
        ];
        let faces = [Face {
            vertices: &[0, 1, 2][..],
            material: Rgb888::WHITE,
        }];
        let mesh = Mesh::new(&positions, 0.0001, &faces);
        let mut d = [0u16; 64 * 64];
        let mut zbuf = ZBuffer::new(&mut d, 64, 64).unwrap();
        zbuf.clear();
        let mut display = Counter {
            size: Size::new(64, 64),
            pixels: 0,
        };
        let opts = RenderOptions {
            cull: Cull::None,
            ..Default::default()
        };
        let mut r = Renderer::new(&mesh, &xf, opts).unwrap();
        r.draw_hidden_line(&mut display, &mut zbuf, Rgb565::WHITE)
            .unwrap();
        assert_eq!(r.stats().pixels_written, display.pixels);
        edges += usize::from(display.pixels > 0);
    }
    assert!(edges > 100, "only {edges} slivers showed an edge");
}
