//! The edges of every range: the guard band, a 4096×4096 screen, 16-bit depth
//! precision, and non-finite or degenerate parameters.

mod common;

use common::{covers, stored_depth};
use embedded_graphics::{
    pixelcolor::{Rgb565, Rgb888},
    prelude::*,
};
use zraster::{
    camera::{Camera, Transform, Viewport},
    fill_triangle,
    fixed::{GUARD_BAND, MAX_DEPTH},
    math::{radians, Mat4, Vec3},
    mesh::{Face, Mesh},
    BandBuffers, Bands, ColorBuffer, DepthTest, Error, RenderOptions, Renderer, ScreenVertex,
    WithDepth, ZBuffer,
};

#[test]
fn vertices_on_the_guard_band_edge_are_drawn_exactly() {
    let g = GUARD_BAND;
    let tris = [
        [
            ScreenVertex::new(-g, -g, 0).unwrap(),
            ScreenVertex::new(g, 40 * 16, MAX_DEPTH).unwrap(),
            ScreenVertex::new(100, g, 1 << 31).unwrap(),
        ],
        [
            ScreenVertex::new(g, g, 7 << 16).unwrap(),
            ScreenVertex::new(-g, g, 7 << 16).unwrap(),
            ScreenVertex::new(g, -g, 9 << 16).unwrap(),
        ],
    ];
    for tri in &tris {
        let mut depth = vec![0u16; 64 * 64];
        let mut zbuf = ZBuffer::new(&mut depth, 64, 64).unwrap();
        zbuf.clear();
        zbuf.set_test(DepthTest::Always);
        let mut px = vec![Rgb565::BLACK; 64 * 64];
        let mut frame = ColorBuffer::new(&mut px, 64, 64).unwrap();
        fill_triangle(&mut frame, &mut zbuf, tri, Rgb565::WHITE).unwrap();
        for y in 0..64 {
            for x in 0..64 {
                let c = covers(tri, x, y);
                assert_eq!(frame.pixel(x, y) == Some(Rgb565::WHITE), c, "({x},{y})");
                if c {
                    let d = i64::from(zbuf.depth(x, y).unwrap()) - stored_depth(tri, x, y);
                    assert!(d.abs() <= 1, "depth at ({x},{y}) off by {d}");
                }
            }
        }
    }
    assert_eq!(ScreenVertex::new(g + 1, 0, 0), Err(Error::OutOfRange));
    assert_eq!(ScreenVertex::new(0, -g - 1, 0), Err(Error::OutOfRange));
}

#[test]
fn a_4096_square_screen_drawn_in_bands() {
    // Two triangles covering the whole 4096×4096 screen, depth 1000 at the top left to
    // 60000 at the bottom right; checked in bands at the top, middle and bottom.
    let s = 4096 * 16;
    let v = |x, y, z: u32| ScreenVertex::new(x, y, z << 16).unwrap();
    let tris = [
        [v(0, 0, 1000), v(s, 0, 30500), v(s, s, 60000)],
        [v(0, 0, 1000), v(s, s, 60000), v(0, s, 30500)],
    ];
    for first_row in [0, 2032, 4064] {
        let mut depth = vec![0u16; 4096 * 32];
        let mut zbuf = ZBuffer::new_band(&mut depth, 4096, 32, first_row).unwrap();
        zbuf.clear();
        zbuf.set_test(DepthTest::Always);
        let mut px = vec![Rgb565::BLACK; 4096 * 32];
        let mut frame = ColorBuffer::new_band(&mut px, 4096, 32, first_row).unwrap();
        let mut written = 0;
        for t in &tris {
            written += fill_triangle(&mut frame, &mut zbuf, t, Rgb565::WHITE)
                .unwrap()
                .pixels_written;
        }
        assert_eq!(
            written,
            4096 * 32,
            "band at {first_row}: every pixel exactly once"
        );
        for (x, y) in [
            (0, first_row),
            (4095, first_row + 31),
            (2047, first_row + 16),
            (4000, first_row + 3),
        ] {
            let t = if covers(&tris[0], x, y) {
                &tris[0]
            } else {
                &tris[1]
            };
            let d = i64::from(zbuf.depth(x, y).unwrap()) - stored_depth(t, x, y);
            assert!(d.abs() <= 1, "depth at ({x},{y}) off by {d}");
        }
    }
    // The same screen through the pipeline: a quad filling a 4096×4096 viewport.
    let pos = [[-1i16, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]];
    let faces = [Face {
        vertices: &[0u16, 1, 2, 3][..],
        material: Rgb888::WHITE,
    }];
    let quad = Mesh::new(&pos, 1.0, &faces);
    let vp = Viewport::new(4096, 4096).unwrap();
    let xf = Transform {
        model: Mat4::IDENTITY,
        view: Mat4::IDENTITY,
        projection: Mat4::orthographic(-1.0, 1.0, -1.0, 1.0, -1.0, 1.0),
        viewport: vp,
    };
    let mut c = vec![Rgb565::BLACK; 4096 * 64];
    let mut z = vec![0u16; 4096 * 64];
    let mut bands = BandBuffers::new(&mut c, &mut z, 4096, 64, 4096, &mut []).unwrap();
    let mut counter = Coverage { hits: 0 };
    let mut r = Renderer::new(&quad, &xf, RenderOptions::default()).unwrap();
    r.draw(&mut Bands::new(&mut counter, &mut bands, Rgb565::BLACK))
        .unwrap();
    assert_eq!(r.stats().pixels_written, 4096 * 4096);
    assert_eq!(counter.hits, 4096 * 4096);
}

/// A 4096×4096 display that only counts white pixels.
struct Coverage {
    hits: u64,
}

impl OriginDimensions for Coverage {
    fn size(&self) -> Size {
        Size::new(4096, 4096)
    }
}

impl DrawTarget for Coverage {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        self.hits += pixels.into_iter().filter(|p| p.1 == Rgb565::WHITE).count() as u64;
        Ok(())
    }
    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        _: &embedded_graphics::primitives::Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        self.hits += colors.into_iter().filter(|c| *c == Rgb565::WHITE).count() as u64;
        Ok(())
    }
}

/// The smallest depth separation 16 bits resolve at eye distance `z`, for a
/// perspective camera with clip planes `n` and `f`: one unit of window depth,
/// (f − n)·z² / (65535·f·n).
fn resolution(z: f32, n: f32, f: f32) -> f32 {
    (f - n) * z * z / (65535.0 * f * n)
}

/// Two screen-filling squares facing the camera at distances `z` and `z + gap`: does
/// the nearer one win at every pixel, whatever the drawing order?
fn resolved(z: f32, gap: f32, n: f32, f: f32) -> bool {
    let pos = [[-1i16, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]];
    let faces = [Face {
        vertices: &[0u16, 1, 2, 3][..],
        material: Rgb888::RED,
    }];
    let near_quad = Mesh::new(&pos, 1.0, &faces);
    let blue = [Face {
        vertices: &[0u16, 1, 2, 3][..],
        material: Rgb888::BLUE,
    }];
    let far_quad = Mesh::new(&pos, 1.0, &blue);
    let vp = Viewport::new(32, 32).unwrap();
    let cam = Camera::look_at(Vec3::default(), Vec3::new(0.0, 0.0, -1.0), Vec3::Y)
        .unwrap()
        .perspective(radians(60.0), n, f, vp)
        .unwrap();
    // Squares big enough to fill the view at either distance.
    let at = |d: f32| {
        cam.with_model(
            Mat4::translation(Vec3::new(0.0, 0.0, -d)) * Mat4::scaling(Vec3::new(d, d, 1.0)),
        )
    };
    (0..2).all(|order| {
        let mut px = vec![Rgb565::BLACK; 32 * 32];
        let mut depth = vec![0u16; 32 * 32];
        let mut frame = ColorBuffer::new(&mut px, 32, 32).unwrap();
        let mut zbuf = ZBuffer::new(&mut depth, 32, 32).unwrap();
        zbuf.clear();
        let draws = [(&near_quad, at(z)), (&far_quad, at(z + gap))];
        for k in 0..2 {
            let (m, xf) = &draws[(k + order) % 2];
            Renderer::new(m, xf, RenderOptions::default())
                .unwrap()
                .draw(&mut WithDepth::new(&mut frame, &mut zbuf))
                .unwrap();
        }
        frame.as_slice().iter().all(|&c| c == Rgb565::RED)
    })
}

/// The stored depth of a screen-filling square facing the camera at distance `z`.
fn stored(z: f32, n: f32, f: f32) -> u16 {
    let pos = [[-1i16, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]];
    let faces = [Face {
        vertices: &[0u16, 1, 2, 3][..],
        material: Rgb888::RED,
    }];
    let quad = Mesh::new(&pos, 1.0, &faces);
    let vp = Viewport::new(8, 8).unwrap();
    let cam = Camera::look_at(Vec3::default(), Vec3::new(0.0, 0.0, -1.0), Vec3::Y)
        .unwrap()
        .perspective(radians(60.0), n, f, vp)
        .unwrap();
    let xf = cam.with_model(
        Mat4::translation(Vec3::new(0.0, 0.0, -z)) * Mat4::scaling(Vec3::new(z, z, 1.0)),
    );
    let mut px = vec![Rgb565::BLACK; 64];
    let mut depth = vec![0u16; 64];
    let mut frame = ColorBuffer::new(&mut px, 8, 8).unwrap();
    let mut zbuf = ZBuffer::new(&mut depth, 8, 8).unwrap();
    zbuf.clear();
    Renderer::new(&quad, &xf, RenderOptions::default())
        .unwrap()
        .draw(&mut WithDepth::new(&mut frame, &mut zbuf))
        .unwrap();
    zbuf.depth(4, 4).unwrap()
}

#[test]
fn sixteen_bit_depth_resolves_what_the_formula_says() {
    let (n, f) = (0.1, 10.0);
    for z in [0.25f32, 0.5, 1.0, 2.5, 5.0, 9.0] {
        let r = resolution(z, n, f);
        // Three units apart always resolve, in either drawing order.
        assert!(
            resolved(z, 3.0 * r, n, f),
            "z = {z}: 3 units ({}) not resolved",
            3.0 * r
        );
        // The stored depth moves by the formula's count of units (±1 for rounding).
        let units = |gap: f32| i32::from(stored(z + gap, n, f)) - i32::from(stored(z, n, f));
        assert!(
            (2..=4).contains(&units(3.0 * r)),
            "z = {z}: {}",
            units(3.0 * r)
        );
        assert!(
            (0..=1).contains(&units(0.1 * r)),
            "z = {z}: {}",
            units(0.1 * r)
        );
    }
    // Moving the near plane out is what buys precision: at z = 5, near 0.1 → 0.5 is 5×.
    assert!(
        (resolution(5.0, 0.1, 10.0) / resolution(5.0, 0.5, 10.0) - 5.0 * 9.9 / 9.5).abs() < 1e-3
    );
}

#[test]
fn degenerate_and_non_finite_parameters_are_errors() {
    let vp = Viewport::new(32, 32).unwrap();
    let (e, o) = (Vec3::new(0.0, 0.0, 3.0), Vec3::default());
    let look = Camera::look_at(e, o, Vec3::Y).unwrap();
    for (fov, near, far) in [
        (60.0, 1.0, 1.0),
        (60.0, 2.0, 1.0),
        (60.0, 0.0, 1.0),
        (60.0, -1.0, 1.0),
        (0.0, 0.1, 1.0),
        (180.0, 0.1, 1.0),
        (-5.0, 0.1, 1.0),
    ] {
        assert!(
            matches!(
                look.perspective(radians(fov), near, far, vp),
                Err(Error::InvalidParameter(_))
            ),
            "{fov} {near} {far}"
        );
    }
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        assert_eq!(
            look.perspective(bad, 0.1, 1.0, vp).err(),
            Some(Error::NotFinite)
        );
        assert_eq!(
            look.perspective(radians(60.0), bad, 1.0, vp).err(),
            Some(Error::NotFinite)
        );
        assert_eq!(
            Camera::look_at(Vec3::new(bad, 0.0, 0.0), o, Vec3::Y).err(),
            Some(Error::NotFinite)
        );
        assert_eq!(ScreenVertex::from_f32(0.0, 0.0, bad), Err(Error::NotFinite));
        let pos = [[0i16; 3]; 3];
        let tris = [[0u16, 1, 2]];
        let m = Mesh::triangles(&pos, bad, &tris, Rgb888::WHITE);
        let xf = look.perspective(radians(60.0), 0.1, 10.0, vp).unwrap();
        assert_eq!(
            Renderer::new(&m, &xf, RenderOptions::default()).err(),
            Some(Error::NotFinite)
        );
    }
    // The eye at the target is a degenerate view: an error, not a blank frame.
    assert_eq!(
        Camera::look_at(o, o, Vec3::Y).err(),
        Some(Error::DegenerateView)
    );
    // A view matrix set by hand to nothing useful (all zeros): no panic, an error or a
    // blank frame.
    let mut xf = look.perspective(radians(60.0), 0.1, 10.0, vp).unwrap();
    xf.view = Mat4 { m: [[0.0; 4]; 4] };
    let pos = [[0i16, 0, 0], [1, 0, 0], [0, 1, 0]];
    let tris = [[0u16, 1, 2]];
    let m = Mesh::triangles(&pos, 1.0, &tris, Rgb888::WHITE);
    if let Ok(mut r) = Renderer::new(&m, &xf, RenderOptions::default()) {
        let mut px = vec![Rgb565::BLACK; 32 * 32];
        let mut depth = vec![0u16; 32 * 32];
        let mut frame = ColorBuffer::new(&mut px, 32, 32).unwrap();
        let mut zbuf = ZBuffer::new(&mut depth, 32, 32).unwrap();
        r.draw(&mut WithDepth::new(&mut frame, &mut zbuf)).unwrap();
        assert!(px.iter().all(|&p| p == Rgb565::BLACK));
    }
    assert_eq!(Viewport::new(8193, 1), Err(Error::TooLarge));
    assert_eq!(Viewport::at(9000, 0, 10, 10), Err(Error::TooLarge));
}
