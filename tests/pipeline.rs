//! The 3D pipeline: clipping, culling, the renderers and their errors.

use zraster_scenes as scenes;

use embedded_graphics::{
    pixelcolor::{Rgb565, Rgb888},
    prelude::*,
};
use zraster::{
    camera::{Camera, Transform, Viewport},
    math::{radians, Mat4, Vec3},
    mesh::{Face, Faces, Materials, Mesh, CUBE},
    shade::{Intensity, Light, Shading, ONE},
    Bands, CachedVertex, ColorBuffer, Cull, DepthSort, DrawError, Error, Frame, FrameStats,
    RenderOptions, Renderer, ScreenVertex, WithDepth, ZBuffer,
};

const W: u32 = 64;
const H: u32 = 64;

/// Render `mesh` with `xf` into a fresh W×H frame; returns the pixels and the stats.
fn zbuffer_frame(
    mesh: &Mesh<'_, Rgb888>,
    xf: &Transform,
    opts: RenderOptions,
) -> (Vec<Rgb565>, FrameStats) {
    let mut pixels = vec![Rgb565::BLACK; (W * H) as usize];
    let mut depth = vec![0u16; (W * H) as usize];
    let stats;
    {
        let mut frame = ColorBuffer::new(&mut pixels, W, H).unwrap();
        let mut zbuf = ZBuffer::new(&mut depth, W, H).unwrap();
        zbuf.clear();
        let mut r = Renderer::new(mesh, xf, opts).unwrap();
        r.draw(&mut WithDepth::new(&mut frame, &mut zbuf)).unwrap();
        stats = r.stats();
    }
    (pixels, stats)
}

fn painter_frame(mesh: &Mesh<'_, Rgb888>, xf: &Transform, opts: RenderOptions) -> Vec<Rgb565> {
    let mut pixels = vec![Rgb565::BLACK; (W * H) as usize];
    {
        let mut frame = ColorBuffer::new(&mut pixels, W, H).unwrap();
        let mut sort = DepthSort::<64>::new();
        Renderer::new(mesh, xf, opts)
            .unwrap()
            .draw_depth_sorted(&mut frame, &mut sort)
            .unwrap();
    }
    pixels
}

fn camera(eye: Vec3, target: Vec3, fov: f32) -> Transform {
    Camera::look_at(eye, target, Vec3::Y)
        .unwrap()
        .perspective(radians(fov), 0.1, 100.0, Viewport::new(W, H).unwrap())
        .unwrap()
}

/// Assert two frames are identical, reporting how many pixels differ (not the frames).
fn assert_same(a: &[Rgb565], b: &[Rgb565], what: &str) {
    let n = a.iter().zip(b).filter(|(x, y)| x != y).count();
    assert!(n == 0 && a.len() == b.len(), "{what}: {n} pixels differ");
}

fn px(p: &[Rgb565], x: u32, y: u32) -> Rgb565 {
    p[(y * W + x) as usize]
}

#[test]
fn a_floor_that_extends_behind_the_camera_draws_its_visible_part() {
    // A 40×40 floor at y = −1 around the eye at the origin, looking down −Z.
    let pos: [[i16; 3]; 4] = [[-20, -1, -20], [20, -1, -20], [20, -1, 20], [-20, -1, 20]];
    let faces = [Face {
        vertices: &[0u16, 3, 2, 1][..],
        material: Rgb888::WHITE,
    }];
    let floor = Mesh::new(&pos, 1.0, &faces);
    let xf = camera(Vec3::default(), Vec3::new(0.0, 0.0, -1.0), 90.0);
    let (p, stats) = zbuffer_frame(&floor, &xf, RenderOptions::default());
    assert!(stats.clipped >= 1, "{stats:?}");
    // The far edge (z = −20) projects to y_ndc = −0.05: screen row 33.6. Below it the
    // floor covers every pixel; above it, none.
    for y in 0..H {
        for x in 0..W {
            let covered = px(&p, x, y) != Rgb565::BLACK;
            assert_eq!(covered, y >= 34, "pixel ({x},{y})");
        }
    }
}

#[test]
fn from_inside_a_closed_box_every_wall_is_seen_without_gaps() {
    // The seeds' cube scaled to −2..2 around the eye; its faces are seen from inside,
    // that is from the back, so front faces are culled.
    let xf = camera(Vec3::default(), Vec3::new(0.0, 0.0, -1.0), 120.0).with_model(
        Mat4::scaling(Vec3::new(4.0, 4.0, 4.0)) * Mat4::translation(Vec3::new(-0.5, -0.5, -0.5)),
    );
    let opts = RenderOptions {
        cull: Cull::Front,
        ..Default::default()
    };
    let (p, stats) = zbuffer_frame(&CUBE, &xf, opts);
    assert!(p.iter().all(|&c| c != Rgb565::BLACK), "a gap in the walls");
    assert!(stats.clipped > 0 && stats.outside > 0, "{stats:?}");
    let color = |r, g, b| -> Rgb565 { Rgb888::new(r, g, b).into() };
    assert_eq!(
        px(&p, 32, 32),
        color(128, 0, 128),
        "back wall (purple) ahead"
    );
    assert_eq!(px(&p, 2, 32), color(255, 255, 0), "left wall (yellow)");
    assert_eq!(px(&p, 61, 32), color(0, 255, 0), "right wall (green)");
    assert_eq!(
        px(&p, 32, 2),
        color(0, 255, 255),
        "ceiling (top, light blue)"
    );
    assert_eq!(px(&p, 32, 61), color(255, 0, 0), "floor (bottom, red)");
}

#[test]
fn culling_counts_on_the_cube() {
    let xf = camera(Vec3::new(2.2, 1.8, 2.8), Vec3::new(0.5, 0.5, 0.5), 45.0);
    let (_, back) = zbuffer_frame(&CUBE, &xf, RenderOptions::default());
    assert_eq!(
        (
            back.triangles_in,
            back.culled,
            back.drawn,
            back.outside,
            back.clipped
        ),
        (12, 6, 6, 0, 0)
    );
    let (_, front) = zbuffer_frame(
        &CUBE,
        &xf,
        RenderOptions {
            cull: Cull::Front,
            ..Default::default()
        },
    );
    assert_eq!((front.culled, front.drawn), (6, 6));
    let (_, none) = zbuffer_frame(
        &CUBE,
        &xf,
        RenderOptions {
            cull: Cull::None,
            ..Default::default()
        },
    );
    assert_eq!((none.culled, none.drawn), (0, 12));
    // Same picture with and without back-face culling under the Z-buffer.
    assert_eq!(back.pixels_written, {
        let (p1, _) = zbuffer_frame(&CUBE, &xf, RenderOptions::default());
        let (p2, _) = zbuffer_frame(
            &CUBE,
            &xf,
            RenderOptions {
                cull: Cull::None,
                ..Default::default()
            },
        );
        assert_same(&p1, &p2, "culling under the Z-buffer");
        p1.iter().filter(|&&c| c != Rgb565::BLACK).count() as u64
    });
}

#[test]
fn painter_and_zbuffer_agree_on_a_convex_solid() {
    for (yaw, pitch) in [(0.0, 0.0), (30.0, 20.0), (135.0, -40.0), (250.0, 60.0)] {
        let model = Mat4::rotation_x(radians(pitch))
            * Mat4::rotation_y(radians(yaw))
            * Mat4::translation(Vec3::new(-0.5, -0.5, -0.5));
        let xf = camera(Vec3::new(0.0, 0.0, 3.0), Vec3::default(), 45.0).with_model(model);
        let opts = RenderOptions {
            shading: Shading::Lambert,
            ..Default::default()
        };
        let (z, _) = zbuffer_frame(&CUBE, &xf, opts);
        assert_same(
            &painter_frame(&CUBE, &xf, opts),
            &z,
            &format!("yaw {yaw} pitch {pitch}"),
        );
    }
}

#[test]
fn painter_fails_where_the_seeds_say_and_the_zbuffer_does_not() {
    let cases = scenes::failure_cases();
    for (mesh, eye, target, cull, name) in &cases {
        mesh.with(|m, place| {
            let xf = camera(*eye, *target, 45.0).with_model(place);
            let opts = RenderOptions {
                cull: *cull,
                ..Default::default()
            };
            let (z, _) = zbuffer_frame(m, &xf, opts);
            let p = painter_frame(m, &xf, opts);
            let differ = z.iter().zip(&p).filter(|(a, b)| a != b).count();
            assert!(
                differ > 20,
                "{name}: painter and Z-buffer differ on only {differ} pixels"
            );
            // Both cover the same pixels: the painter gets the order wrong, not the coverage.
            let cov = |v: &[Rgb565]| v.iter().map(|&c| c != Rgb565::BLACK).collect::<Vec<_>>();
            assert!(cov(&z) == cov(&p), "{name}: coverage differs");
            // The Z-buffer does not depend on the face order: reverse the face table.
            let faces: Vec<Face<'_, Rgb888>> = (0..m.face_count())
                .rev()
                .map(|f| {
                    let (v, c) = m.face(f).unwrap();
                    Face {
                        vertices: v,
                        material: c,
                    }
                })
                .collect();
            let reversed = Mesh::new(m.positions, m.scale, &faces);
            assert_same(&zbuffer_frame(&reversed, &xf, opts).0, &z, name);
        });
    }
}

#[test]
fn bad_meshes_and_transforms_are_errors() {
    let xf = camera(Vec3::new(0.0, 0.0, 3.0), Vec3::default(), 45.0);
    let pos = [[0i16, 0, 0], [1, 0, 0], [0, 1, 0]];
    let tris = [[0u16, 1, 2], [0, 2, 5]];
    let bad = Mesh::triangles(&pos, 1.0, &tris, Rgb888::WHITE);
    let mut pixels = vec![Rgb565::BLACK; (W * H) as usize];
    let mut depth = vec![0u16; (W * H) as usize];
    let mut frame = ColorBuffer::new(&mut pixels, W, H).unwrap();
    let mut zbuf = ZBuffer::new(&mut depth, W, H).unwrap();
    let mut r = Renderer::new(&bad, &xf, RenderOptions::default()).unwrap();
    assert_eq!(
        r.draw(&mut WithDepth::new(&mut frame, &mut zbuf)),
        Err(DrawError::Input(Error::IndexOutOfRange {
            face: 1,
            index: 5
        }))
    );
    let mut cache = [CachedVertex::EMPTY; 3];
    let mut r = Renderer::with_cache(&bad, &xf, RenderOptions::default(), &mut cache).unwrap();
    assert_eq!(
        r.draw(&mut WithDepth::new(&mut frame, &mut zbuf)),
        Err(DrawError::Input(Error::IndexOutOfRange {
            face: 1,
            index: 5
        }))
    );
    assert_eq!(
        r.draw_wireframe(&mut frame, Rgb565::WHITE),
        Err(DrawError::Input(Error::IndexOutOfRange {
            face: 1,
            index: 5
        }))
    );
    let mut short = [CachedVertex::EMPTY; 2];
    assert!(matches!(
        Renderer::with_cache(&bad, &xf, RenderOptions::default(), &mut short),
        Err(Error::BufferTooSmall { needed: 3, got: 2 })
    ));
    let two = [Face {
        vertices: &[0u16, 1][..],
        material: Rgb888::WHITE,
    }];
    let mut r = Renderer::new(&Mesh::new(&pos, 1.0, &two), &xf, RenderOptions::default()).unwrap();
    assert_eq!(
        r.draw(&mut WithDepth::new(&mut frame, &mut zbuf)),
        Err(DrawError::Input(Error::DegenerateFace { face: 0 }))
    );
    // Capacity of the depth sort.
    let mut small = DepthSort::<5>::new();
    let mut r = Renderer::new(&CUBE, &xf, RenderOptions::default()).unwrap();
    assert_eq!(
        r.draw_depth_sorted(&mut frame, &mut small),
        Err(DrawError::Input(Error::CapacityExceeded { capacity: 5 }))
    );
    // Non-finite transforms and lights.
    let nan = xf.with_model(Mat4::scaling(Vec3::new(f32::NAN, 1.0, 1.0)));
    assert_eq!(
        Renderer::new(&CUBE, &nan, RenderOptions::default()).err(),
        Some(Error::NotFinite)
    );
    let inf = xf.with_model(Mat4::translation(Vec3::new(f32::INFINITY, 0.0, 0.0)));
    assert_eq!(
        Renderer::new(&CUBE, &inf, RenderOptions::default()).err(),
        Some(Error::NotFinite)
    );
    let dark = RenderOptions {
        light: Light {
            ambient: f32::NAN,
            ..Light::default()
        },
        ..Default::default()
    };
    assert_eq!(
        Renderer::new(&CUBE, &xf, dark).err(),
        Some(Error::NotFinite)
    );
    let vp = Viewport::new(W, H).unwrap();
    let o = Vec3::default();
    let e = Vec3::new(0.0, 0.0, 1.0);
    let look = Camera::look_at(e, o, Vec3::Y).unwrap();
    assert!(look.perspective(radians(60.0), 1.0, 1.0, vp).is_err());
    assert!(look.perspective(0.0, 0.1, 1.0, vp).is_err());
    assert!(look
        .perspective(core::f32::consts::PI, 0.1, 1.0, vp)
        .is_err());
    assert!(look.perspective(f32::NAN, 0.1, 1.0, vp).is_err());
    assert_eq!(Viewport::new(0, 5), Err(Error::ZeroSize));
    assert_eq!(Viewport::new(10_000, 5), Err(Error::TooLarge));
}

#[test]
fn hidden_line_hides_the_far_corner_that_wireframe_shows() {
    let xf = camera(Vec3::new(2.2, 1.8, 2.8), Vec3::new(0.5, 0.5, 0.5), 45.0);
    // Where the hidden corner a = (0, 0, 0) lands on the screen.
    let c = xf.model_view_projection().transform_point(Vec3::default());
    let (sx, sy) = (
        ((c[0] / c[3] + 1.0) * 32.0) as u32,
        ((1.0 - c[1] / c[3]) * 32.0) as u32,
    );
    let draw = |hidden: bool| {
        let mut pixels = vec![Rgb565::BLACK; (W * H) as usize];
        let mut depth = vec![0u16; (W * H) as usize];
        {
            let mut frame = ColorBuffer::new(&mut pixels, W, H).unwrap();
            let mut zbuf = ZBuffer::new(&mut depth, W, H).unwrap();
            zbuf.clear();
            let mut r = Renderer::new(&CUBE, &xf, RenderOptions::default()).unwrap();
            if hidden {
                r.draw_hidden_line(&mut frame, &mut zbuf, Rgb565::WHITE)
                    .unwrap();
            } else {
                r.draw_wireframe(&mut frame, Rgb565::WHITE).unwrap();
            }
        }
        pixels
    };
    let (h, w) = (draw(true), draw(false));
    let near = |p: &[Rgb565]| {
        (sx.saturating_sub(1)..=sx + 1)
            .any(|x| (sy.saturating_sub(1)..=sy + 1).any(|y| px(p, x, y) == Rgb565::WHITE))
    };
    assert!(near(&w), "wireframe shows the hidden corner");
    assert!(!near(&h), "hidden-line hides it");
    // Every hidden-line pixel is a wireframe pixel, and the 9 visible edges are all there.
    let lit = |p: &[Rgb565]| p.iter().filter(|&&c| c == Rgb565::WHITE).count();
    assert!(h.iter().zip(&w).all(|(a, b)| *a == Rgb565::BLACK || a == b));
    assert!(
        lit(&h) * 4 > lit(&w) * 2 && lit(&h) < lit(&w),
        "{} vs {}",
        lit(&h),
        lit(&w)
    );
}

#[test]
fn gouraud_interpolates_intensity_across_the_face() {
    let v = |x: i32, y: i32| ScreenVertex::from_pixels(x, y, 100).unwrap();
    let tri = [v(0, 0), v(64, 0), v(0, 64)];
    let mut pixels = vec![Rgb888::BLACK; (W * H) as usize];
    let mut depth = vec![0u16; (W * H) as usize];
    let mut frame = ColorBuffer::new(&mut pixels, W, H).unwrap();
    let mut zbuf = ZBuffer::new(&mut depth, W, H).unwrap();
    zbuf.clear();
    let lights: [Intensity; 3] = [0, ONE, 0];
    zraster::fill_triangle_shaded(&mut frame, &mut zbuf, &tri, Rgb888::WHITE, lights).unwrap();
    // Intensity grows linearly with x: at the centre of column i it is (i + 0.5)/64.
    for x in [0, 10, 31, 50] {
        let want = ((x as f32 + 0.5) / 64.0 * 255.0).round() as i32;
        let got = frame.pixel(x, 3).unwrap().r() as i32;
        assert!((got - want).abs() <= 1, "column {x}: {got} vs {want}");
    }
}

#[test]
fn per_face_materials_and_lambert() {
    let pos = [[-1i16, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]];
    let tris = [[0u16, 1, 2], [0, 2, 3]];
    let mats = [Rgb888::new(255, 0, 0), Rgb888::new(0, 0, 255)];
    let mesh = Mesh {
        faces: Faces::Triangles {
            indices: &tris,
            materials: Materials::PerFace(&mats),
        },
        ..Mesh::triangles(&pos, 1.0, &tris, Rgb888::BLACK)
    };
    let xf = camera(Vec3::new(0.0, 0.0, 3.0), Vec3::default(), 60.0);
    let (flat, _) = zbuffer_frame(&mesh, &xf, RenderOptions::default());
    assert_eq!(px(&flat, 45, 30), Rgb565::RED);
    assert_eq!(px(&flat, 20, 34), Rgb565::BLUE);
    // Lambert with the light straight on: full intensity; from the side: only ambient.
    let head_on = Light {
        direction: Vec3::new(0.0, 0.0, 1.0),
        ambient: 0.25,
        diffuse: 0.75,
    };
    let (lit, _) = zbuffer_frame(
        &mesh,
        &xf,
        RenderOptions {
            shading: Shading::Lambert,
            light: head_on,
            ..Default::default()
        },
    );
    assert_eq!(px(&lit, 45, 30), Rgb565::RED);
    let side = Light {
        direction: Vec3::new(1.0, 0.0, 0.0),
        ..head_on
    };
    let (dim, _) = zbuffer_frame(
        &mesh,
        &xf,
        RenderOptions {
            shading: Shading::Lambert,
            light: side,
            ..Default::default()
        },
    );
    assert_eq!(px(&dim, 45, 30), Rgb565::new(8, 0, 0)); // 31 · 0.25 = 7.75 → 8
}

#[test]
fn a_frame_gives_the_same_pixels_as_a_display_with_depth() {
    let bunny = scenes::Bunny::load();
    let mesh = bunny.mesh(Rgb888::new(255, 204, 153));
    for (yaw, shading, test) in [
        (30.0, Shading::Lambert, zraster::DepthTest::Less),
        (100.0, Shading::Flat, zraster::DepthTest::LessEqual),
        (200.0, Shading::Gouraud, zraster::DepthTest::Less),
        (300.0, Shading::Lambert, zraster::DepthTest::Greater),
    ] {
        let xf = camera(Vec3::new(0.0, 0.0, 1.6), Vec3::default(), 60.0)
            .with_model(Mat4::rotation_y(radians(yaw)) * bunny.fit);
        let opts = RenderOptions {
            shading,
            ..Default::default()
        };
        let run = |buffered: bool| {
            let mut pixels = vec![Rgb565::BLACK; (W * H) as usize];
            let mut depth = vec![0u16; (W * H) as usize];
            let stats;
            {
                let mut frame = ColorBuffer::new(&mut pixels, W, H).unwrap();
                let mut zbuf = ZBuffer::new(&mut depth, W, H).unwrap();
                zbuf.fill(if test == zraster::DepthTest::Greater {
                    0
                } else {
                    u16::MAX
                });
                zbuf.set_test(test);
                let mut r = Renderer::new(&mesh, &xf, opts).unwrap();
                if buffered {
                    r.draw(&mut Frame::from_buffers(frame, zbuf)).unwrap();
                } else {
                    r.draw(&mut WithDepth::new(&mut frame, &mut zbuf)).unwrap();
                }
                stats = r.stats();
            }
            (pixels, depth, stats)
        };
        let (p1, d1, s1) = run(false);
        let (p2, d2, s2) = run(true);
        assert_same(&p1, &p2, &format!("yaw {yaw}"));
        assert!(d1 == d2, "yaw {yaw}: depth differs");
        assert_eq!((s1.pixels_written, s1.drawn), (s2.pixels_written, s2.drawn));
        assert!(s1.pixels_written > 500);
    }
}

#[test]
fn banded_drawing_is_pixel_identical_with_and_without_bins() {
    let bunny = scenes::Bunny::load();
    let mesh = bunny.mesh(Rgb888::new(255, 204, 153));
    let (w, h) = (96u32, 70u32);
    // In the middle; and across the left edge and the near plane, so that faces are
    // outside, clipped, culled and drawn.
    for (eye, target) in [
        (Vec3::new(0.0, 0.0, 1.6), Vec3::default()),
        (Vec3::new(0.25, 0.0, 0.35), Vec3::new(0.25, 0.0, 0.0)),
    ] {
        let s = banded_against_whole(&mesh, &bunny, eye, target, w, h);
        assert!(s.drawn > 0 && s.pixels_written > 500, "{s:?}");
        if eye.z < 1.0 {
            assert!(s.outside > 0 && s.clipped > 0 && s.culled > 0, "{s:?}");
        }
    }
}

/// The vertex cache holds screen positions within ±2048 pixels: with the view placed
/// across x = 2048 the faces beyond take the general path, with the pixels, depths and
/// counts of a renderer without a cache, whole or banded.
#[test]
fn vertices_beyond_the_cache_range_draw_as_without_a_cache() {
    let bunny = scenes::Bunny::load();
    let mesh = bunny.mesh(Rgb888::new(255, 204, 153));
    let (w, h) = (2240u32, 96u32);
    let vp = Viewport::at(1920, 0, 256, h).unwrap();
    let xf = Camera::look_at(Vec3::new(0.0, 0.0, 1.6), Vec3::default(), Vec3::Y)
        .unwrap()
        .perspective(radians(60.0), 0.1, 10.0, vp)
        .unwrap()
        .with_model(Mat4::rotation_y(radians(30.0)) * bunny.fit);
    let opts = RenderOptions {
        shading: Shading::Lambert,
        ..Default::default()
    };
    let whole = |cache: Option<&mut [CachedVertex]>| {
        let mut pixels = vec![Rgb565::BLACK; (w * h) as usize];
        let mut depth = vec![0u16; (w * h) as usize];
        let mut frame = Frame::new(&mut pixels, &mut depth, w, h).unwrap();
        frame.clear(Rgb565::BLACK);
        let mut r = match cache {
            Some(c) => Renderer::with_cache(&mesh, &xf, opts, c).unwrap(),
            None => Renderer::new(&mesh, &xf, opts).unwrap(),
        };
        r.draw(&mut frame).unwrap();
        let stats = r.stats();
        (pixels, depth, stats)
    };
    let mut cache = vec![CachedVertex::EMPTY; bunny.positions.len()];
    let (p1, d1, s1) = whole(Some(&mut cache));
    let (p0, d0, s0) = whole(None);
    assert_same(&p1, &p0, "cached against uncached");
    assert!(d1 == d0, "depth differs");
    assert_eq!(s1, s0);
    // The bunny lies across x = 2048 (128 pixels): drawn on both sides.
    let drawn_at = |x0: u32, x1: u32| {
        (0..h).any(|y| (x0..x1).any(|x| p0[(y * w + x) as usize] != Rgb565::BLACK))
    };
    assert!(drawn_at(1990, 2048) && drawn_at(2048, 2110), "{s0:?}");
    // Banded, with bins.
    let rows = 16;
    let mut out = vec![Rgb565::BLUE; (w * h) as usize];
    let mut cb = vec![Rgb565::BLACK; (w * rows) as usize];
    let mut zb = vec![0u16; (w * rows) as usize];
    let mut bins =
        vec![0u16; zraster::BandBuffers::<Rgb565>::bins_needed(bunny.indices.len(), h, rows)];
    let stats = {
        let mut display = ColorBuffer::new(&mut out, w, h).unwrap();
        let mut bands = zraster::BandBuffers::new(&mut cb, &mut zb, w, rows, h, &mut bins).unwrap();
        let mut r = Renderer::with_cache(&mesh, &xf, opts, &mut cache).unwrap();
        r.draw(&mut Bands::new(&mut display, &mut bands, Rgb565::BLACK))
            .unwrap();
        r.stats()
    };
    assert_same(&out, &p0, "banded against uncached");
    assert_eq!(stats, s0);
}

/// Bands no triangle reaches are not cleared again, unless an overlay may have drawn
/// into the band: a pixel drawn after the first band only must not show in the next.
#[test]
fn an_overlay_does_not_leak_into_the_empty_bands_below() {
    let bunny = scenes::Bunny::load();
    let mesh = bunny.mesh(Rgb888::new(255, 204, 153));
    let (w, h, rows) = (96u32, 70u32, 7u32);
    let xf = Camera::look_at(Vec3::new(0.0, 0.0, 1.6), Vec3::default(), Vec3::Y)
        .unwrap()
        .perspective(radians(60.0), 0.1, 10.0, Viewport::new(w, h).unwrap())
        .unwrap()
        .with_model(bunny.fit);
    let mut cache = vec![CachedVertex::EMPTY; bunny.positions.len()];
    let draw = |cache: &mut [CachedVertex], overlay: bool| {
        let mut out = vec![Rgb565::BLUE; (w * h) as usize];
        let (mut cb, mut zb) = (
            vec![Rgb565::BLACK; (w * rows) as usize],
            vec![0u16; (w * rows) as usize],
        );
        let mut bins =
            vec![0u16; zraster::BandBuffers::<Rgb565>::bins_needed(bunny.indices.len(), h, rows)];
        let mut bands = zraster::BandBuffers::new(&mut cb, &mut zb, w, rows, h, &mut bins).unwrap();
        let mut r = Renderer::with_cache(&mesh, &xf, RenderOptions::default(), cache).unwrap();
        let mut display = ColorBuffer::new(&mut out, w, h).unwrap();
        if overlay {
            let mut target =
                Bands::new(&mut display, &mut bands, Rgb565::BLACK).after_band(|band, depth| {
                    if depth.first_row() == 0 {
                        Pixel(Point::new(3, 1), Rgb565::RED).draw(band).unwrap();
                    }
                });
            r.draw(&mut target).unwrap();
        } else {
            r.draw(&mut Bands::new(&mut display, &mut bands, Rgb565::BLACK))
                .unwrap();
        }
        out
    };
    let plain = draw(&mut cache, false);
    let with = draw(&mut cache, true);
    // The first bands are empty (the bunny sits in the middle), and the drawing is there.
    assert!(plain[..(w * 2 * rows) as usize]
        .iter()
        .all(|&c| c == Rgb565::BLACK));
    assert!(plain.iter().filter(|&&c| c != Rgb565::BLACK).count() > 500);
    for (i, (&a, &b)) in plain.iter().zip(&with).enumerate() {
        let want = if i == (w + 3) as usize {
            Rgb565::RED
        } else {
            a
        };
        assert_eq!(b, want, "pixel ({}, {})", i as u32 % w, i as u32 / w);
    }
}

fn banded_against_whole(
    mesh: &Mesh<'_, Rgb888>,
    bunny: &scenes::Bunny,
    eye: Vec3,
    target: Vec3,
    w: u32,
    h: u32,
) -> FrameStats {
    let xf = Camera::look_at(eye, target, Vec3::Y)
        .unwrap()
        .perspective(radians(60.0), 0.1, 10.0, Viewport::new(w, h).unwrap())
        .unwrap()
        .with_model(Mat4::rotation_y(radians(30.0)) * bunny.fit);
    let opts = RenderOptions {
        shading: Shading::Lambert,
        ..Default::default()
    };
    let mut cache = vec![CachedVertex::EMPTY; bunny.positions.len()];
    // The whole frame at once.
    let mut full = vec![Rgb565::BLACK; (w * h) as usize];
    let mut depth = vec![0u16; (w * h) as usize];
    let full_stats = {
        let mut frame = Frame::new(&mut full, &mut depth, w, h).unwrap();
        frame.clear(Rgb565::BLACK);
        let mut r = Renderer::with_cache(mesh, &xf, opts, &mut cache).unwrap();
        r.draw(&mut frame).unwrap();
        r.stats()
    };
    for rows in [1, 7, 16, h] {
        // No bins, exactly the bins needed, and more (the spare ones unused).
        for extra in [None, Some(0), Some(37)] {
            let mut out = vec![Rgb565::BLUE; (w * h) as usize];
            let mut cb = vec![Rgb565::BLACK; (w * rows) as usize];
            let mut zb = vec![0u16; (w * rows) as usize];
            let n = match extra {
                Some(extra) => {
                    zraster::BandBuffers::<Rgb565>::bins_needed(bunny.indices.len(), h, rows)
                        + extra
                }
                None => 0,
            };
            let mut bins = vec![0u16; n];
            let stats = {
                let mut display = ColorBuffer::new(&mut out, w, h).unwrap();
                let mut bands =
                    zraster::BandBuffers::new(&mut cb, &mut zb, w, rows, h, &mut bins).unwrap();
                let mut r = Renderer::with_cache(mesh, &xf, opts, &mut cache).unwrap();
                r.draw(&mut Bands::new(&mut display, &mut bands, Rgb565::BLACK))
                    .unwrap();
                r.stats()
            };
            let what = format!("rows {rows}, bins {extra:?}");
            assert_same(&out, &full, &what);
            assert_eq!(
                (stats.triangles_in, stats.culled, stats.drawn),
                (full_stats.triangles_in, full_stats.culled, full_stats.drawn),
                "{what}: {stats:?} vs {full_stats:?}"
            );
            // Bands draw in face order, as the whole frame does: every count agrees.
            assert_eq!(stats, full_stats, "{what}");
        }
    }
    // Bins: one a triangle, four a band and two more; no overflow at the extremes.
    assert_eq!(
        zraster::BandBuffers::<Rgb565>::bins_needed(3674, 240, 16),
        3674 + 62
    );
    assert_eq!(zraster::BandBuffers::<Rgb565>::bins_needed(0, 240, 0), 962);
    assert_eq!(
        zraster::BandBuffers::<Rgb565>::bins_needed(usize::MAX, 8192, 1),
        usize::MAX
    );
    // Wrong sizes are errors.
    let (mut c, mut z, mut b) = (vec![Rgb565::BLACK; 10], vec![0u16; 10], vec![0u16; 0]);
    assert_eq!(
        zraster::BandBuffers::new(&mut c, &mut z, 4, 3, 9, &mut b).err(),
        Some(Error::BufferTooSmall {
            needed: 12,
            got: 10
        })
    );
    assert_eq!(
        zraster::BandBuffers::new(&mut c, &mut z, 0, 3, 9, &mut b).err(),
        Some(Error::ZeroSize)
    );
    full_stats
}

/// With a vertex cache, a [`Frame`] of a whole-frame colour buffer and a band Z-buffer
/// (different geometries: the fused path's general form) gives the pixels and depths of
/// a [`WithDepth`] of the same buffers, and touches no row outside the band.
#[test]
fn a_frame_with_a_band_zbuffer_matches_a_display_with_depth() {
    let bunny = scenes::Bunny::load();
    let mesh = bunny.mesh(Rgb888::new(255, 204, 153));
    let xf = camera(Vec3::new(0.0, 0.0, 1.6), Vec3::default(), 60.0)
        .with_model(Mat4::rotation_y(radians(30.0)) * bunny.fit);
    let opts = RenderOptions {
        shading: Shading::Lambert,
        ..Default::default()
    };
    let (first, rows) = (20i32, 25u32);
    let run = |buffered: bool| {
        let mut pixels = vec![Rgb565::BLUE; (W * H) as usize];
        let mut depth = vec![u16::MAX; (W * rows) as usize];
        let mut cache = vec![CachedVertex::EMPTY; bunny.positions.len()];
        {
            let mut frame = ColorBuffer::new(&mut pixels, W, H).unwrap();
            let mut zbuf = ZBuffer::new_band(&mut depth, W, rows, first).unwrap();
            let mut r = Renderer::with_cache(&mesh, &xf, opts, &mut cache).unwrap();
            if buffered {
                r.draw(&mut Frame::from_buffers(frame, zbuf)).unwrap();
            } else {
                r.draw(&mut WithDepth::new(&mut frame, &mut zbuf)).unwrap();
            }
        }
        (pixels, depth)
    };
    let (p1, d1) = run(false);
    let (p2, d2) = run(true);
    assert_same(&p1, &p2, "band Z-buffer");
    assert!(d1 == d2, "depth differs");
    let band = (first as u32 * W) as usize..((first as u32 + rows) * W) as usize;
    assert!(
        p2[band.clone()]
            .iter()
            .filter(|&&c| c != Rgb565::BLUE)
            .count()
            > 100
    );
    for (i, c) in p2.iter().enumerate() {
        if !band.contains(&i) {
            assert_eq!(*c, Rgb565::BLUE, "pixel {i} outside the band");
        }
    }
}
