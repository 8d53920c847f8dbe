//! Host benchmarks (criterion): `cargo bench`.
//!
//! - `bunny-320`: the bench scene (`bench/scene`, the frame `bench/mcu` counts), one
//!   frame (transform, cull, draw).
//! - `bunny-320 banded 16`: the same frame in 16-row bands with bins.
//! - `fill-bound cube`: the seeds' cube filling a 320×240 screen.
//! - `tiny triangles`: 2000 triangles of a few pixels each, screen space (setup cost).
//! - `transform`: the bunny's 1839 vertices transformed and projected alone.
//! - `scene`: bunny-320 with two cubes (12 triangles each) beside it, each object its own
//!   model matrix, drawn as one `Scene`: whole frame, and in 16-row bands with every
//!   object binned.
//!
//! Times on a shared host move around; the instruction counts in the README (callgrind,
//! QEMU) are the figures to compare across commits.

use criterion::{criterion_group, criterion_main, Criterion};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use std::hint::black_box;
use zraster::{
    camera::{Camera, Viewport},
    math::{radians, Mat4, Vec3},
    mesh::{Mesh, CUBE, CUBE_POSITIONS},
    BandBuffers, Bands, CachedVertex, ColorBuffer, Frame, RenderOptions, Renderer, Scene,
    ScreenVertex, ZBuffer,
};

use zraster_bench_scene::{self as scene, bunny, H, W};

fn benches(c: &mut Criterion) {
    let n = (W * H) as usize;
    let mut pixels = vec![Rgb565::BLACK; n];
    let mut depth = vec![0u16; n];
    let mut cache = vec![CachedVertex::EMPTY; bunny::BUNNY_POSITIONS.len()];
    let (mesh, xf, opts) = (scene::mesh(), scene::transform(), scene::options());

    c.bench_function("bunny-320", |b| {
        b.iter(|| {
            let mut frame = Frame::new(&mut pixels, &mut depth, W, H).unwrap();
            frame.clear(Rgb565::BLACK);
            let mut r = Renderer::with_cache(&mesh, &xf, opts, &mut cache).unwrap();
            r.draw(&mut frame).unwrap();
            black_box(r.stats())
        })
    });

    let rows = 16;
    let mut band_px = vec![Rgb565::BLACK; (W * rows) as usize];
    let mut band_z = vec![0u16; (W * rows) as usize];
    let mut bins =
        vec![0u16; BandBuffers::<Rgb565>::bins_needed(bunny::BUNNY_INDICES.len(), H, rows)];
    c.bench_function("bunny-320 banded 16", |b| {
        b.iter(|| {
            let mut frame = ColorBuffer::new(&mut pixels, W, H).unwrap();
            let mut bands =
                BandBuffers::new(&mut band_px, &mut band_z, W, rows, H, &mut bins).unwrap();
            let mut r = Renderer::with_cache(&mesh, &xf, opts, &mut cache).unwrap();
            r.draw(&mut Bands::new(&mut frame, &mut bands, Rgb565::BLACK))
                .unwrap();
            black_box(r.stats())
        })
    });

    let cube_xf = Camera::look_at(Vec3::new(0.5, 0.5, 1.3), Vec3::new(0.5, 0.5, 0.0), Vec3::Y)
        .unwrap()
        .perspective(radians(60.0), 0.1, 10.0, Viewport::new(W, H).unwrap())
        .unwrap();
    c.bench_function("fill-bound cube", |b| {
        b.iter(|| {
            let mut frame = Frame::new(&mut pixels, &mut depth, W, H).unwrap();
            frame.depth_mut().clear();
            let mut r = Renderer::new(&CUBE, &cube_xf, RenderOptions::default()).unwrap();
            r.draw(&mut frame).unwrap();
            black_box(r.stats())
        })
    });

    // 2000 screen triangles of 2-8 px, scattered (deterministic).
    let mut s = 12345u32;
    let mut rnd = move |m: u32| {
        s = s.wrapping_mul(1664525).wrapping_add(1013904223);
        (s >> 8) % m
    };
    let tris: Vec<[ScreenVertex; 3]> = (0..2000)
        .map(|_| {
            let (x, y) = (rnd(300 * 16) as i32, rnd(220 * 16) as i32);
            let v = |dx: u32, dy: u32, z: u32| {
                ScreenVertex::new(x + dx as i32, y + dy as i32, z << 16).unwrap()
            };
            [
                v(0, 0, rnd(60000)),
                v(16 + rnd(64), rnd(32), rnd(60000)),
                v(rnd(32), 16 + rnd(64), rnd(60000)),
            ]
        })
        .collect();
    c.bench_function("tiny triangles (2000)", |b| {
        b.iter(|| {
            let mut frame = ColorBuffer::new(&mut pixels, W, H).unwrap();
            let mut zbuf = ZBuffer::new(&mut depth, W, H).unwrap();
            zbuf.clear();
            let mut written = 0;
            for t in &tris {
                written += zraster::fill_triangle(&mut frame, &mut zbuf, t, Rgb565::RED)
                    .unwrap()
                    .pixels_written;
            }
            black_box(written)
        })
    });

    c.bench_function("transform (1839 vertices)", |b| {
        b.iter(|| {
            black_box(
                Renderer::with_cache(&mesh, &xf, opts, &mut cache)
                    .unwrap()
                    .stats(),
            )
        })
    });
}

/// The unit cube as 12 triangles, outward (binning wants triangles).
const CUBE_TRIANGLES: [[u16; 3]; 12] = [
    [0, 1, 2],
    [0, 2, 3],
    [1, 5, 6],
    [1, 6, 2],
    [2, 6, 7],
    [2, 7, 3],
    [3, 7, 4],
    [3, 4, 0],
    [0, 4, 5],
    [0, 5, 1],
    [7, 6, 5],
    [7, 5, 4],
];

fn scene_benches(c: &mut Criterion) {
    let n = (W * H) as usize;
    let (mut pixels, mut depth) = (vec![Rgb565::BLACK; n], vec![0u16; n]);
    let (bunny_mesh, xf, opts) = (scene::mesh(), scene::transform(), scene::options());
    let cube = Mesh::triangles(
        &CUBE_POSITIONS,
        1.0 / 16384.0,
        &CUBE_TRIANGLES,
        embedded_graphics::pixelcolor::Rgb888::new(90, 160, 220),
    );
    // Two small cubes left and right of the bunny, in the bench camera's model space.
    let small = |x: f32| {
        xf.with_model(
            Mat4::translation(Vec3::new(x, -0.05, 0.0)) * Mat4::scaling(Vec3::new(0.2, 0.2, 0.2)),
        )
    };
    let (left, right) = (small(-0.75), small(0.55));
    let mut bunny_cache = vec![CachedVertex::EMPTY; bunny::BUNNY_POSITIONS.len()];
    let (mut cache_l, mut cache_r) = ([CachedVertex::EMPTY; 8], [CachedVertex::EMPTY; 8]);
    let rows = 16;
    let (mut band_px, mut band_z) = (
        vec![Rgb565::BLACK; (W * rows) as usize],
        vec![0u16; (W * rows) as usize],
    );
    let bins_len = [bunny::BUNNY_INDICES.len(), 12, 12]
        .map(|f| BandBuffers::<Rgb565>::bins_needed(f, H, rows))
        .iter()
        .sum();
    let mut bins = vec![0u16; bins_len];
    c.bench_function("scene: bunny-320 and two cubes", |b| {
        b.iter(|| {
            let mut frame = Frame::new(&mut pixels, &mut depth, W, H).unwrap();
            frame.clear(Rgb565::BLACK);
            let mut objects = [
                Renderer::with_cache(&bunny_mesh, &xf, opts, &mut bunny_cache).unwrap(),
                Renderer::with_cache(&cube, &left, opts, &mut cache_l).unwrap(),
                Renderer::with_cache(&cube, &right, opts, &mut cache_r).unwrap(),
            ];
            let mut scene = Scene::new(&mut objects);
            scene.draw(&mut frame).unwrap();
            black_box(scene.stats())
        })
    });
    c.bench_function("scene: bunny-320 and two cubes, banded 16", |b| {
        b.iter(|| {
            let mut frame = ColorBuffer::new(&mut pixels, W, H).unwrap();
            let mut bands =
                BandBuffers::new(&mut band_px, &mut band_z, W, rows, H, &mut bins).unwrap();
            let mut objects = [
                Renderer::with_cache(&bunny_mesh, &xf, opts, &mut bunny_cache).unwrap(),
                Renderer::with_cache(&cube, &left, opts, &mut cache_l).unwrap(),
                Renderer::with_cache(&cube, &right, opts, &mut cache_r).unwrap(),
            ];
            let mut scene = Scene::new(&mut objects);
            scene
                .draw(&mut Bands::new(&mut frame, &mut bands, Rgb565::BLACK))
                .unwrap();
            black_box(scene.stats())
        })
    });
}

criterion_group!(render, benches, scene_benches);
criterion_main!(render);
