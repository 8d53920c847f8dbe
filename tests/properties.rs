//! Property tests: random triangles against a plain float reference rasterizer, and
//! random meshes that must cover every inner pixel exactly once.

mod common;

use embedded_graphics::{pixelcolor::BinaryColor, prelude::*, primitives::Rectangle, Pixel};
use proptest::prelude::*;
use zraster::{
    fill_triangle, fill_triangle_shaded, ColorBuffer, DepthTest, Frame, ScreenVertex, WithDepth,
    ZBuffer,
};

const W: i32 = 64;
const H: i32 = 48;

/// A draw target that counts how often each pixel is written.
struct Counter {
    counts: Vec<u8>,
}

impl Counter {
    fn new() -> Counter {
        Counter {
            counts: vec![0; (W * H) as usize],
        }
    }
    fn at(&self, x: i32, y: i32) -> u8 {
        self.counts[(y * W + x) as usize]
    }
}

impl OriginDimensions for Counter {
    fn size(&self) -> Size {
        Size::new(W as u32, H as u32)
    }
}

impl DrawTarget for Counter {
    type Color = BinaryColor;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<BinaryColor>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, _) in pixels {
            assert!(
                p.x >= 0 && p.x < W && p.y >= 0 && p.y < H,
                "write outside the target at {p:?}"
            );
            self.counts[(p.y * W + p.x) as usize] += 1;
        }
        Ok(())
    }
    fn fill_solid(&mut self, area: &Rectangle, color: BinaryColor) -> Result<(), Self::Error> {
        self.draw_iter(area.points().map(|p| Pixel(p, color)))
    }
}

/// The float reference: is the centre of pixel (px, py) inside the (unsnapped) triangle,
/// and how far (in pixels) is it from the nearest edge line?
fn reference(t: &[(f64, f64); 3], px: i32, py: i32) -> (bool, f64) {
    let (cx, cy) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
    let mut p = *t;
    let area = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1);
    if area < 0.0 {
        p.swap(1, 2);
    }
    let mut inside = area != 0.0;
    let mut dist = f64::INFINITY;
    for i in 0..3 {
        let (a, b) = (p[i], p[(i + 1) % 3]);
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let e = dx * (cy - a.1) - dy * (cx - a.0);
        let len = (dx * dx + dy * dy).sqrt();
        if len > 0.0 {
            dist = dist.min(e.abs() / len);
        }
        inside &= e > 0.0 || (e == 0.0 && ((dy == 0.0 && dx > 0.0) || dy < 0.0));
    }
    (inside, dist)
}

/// Depth of the plane through the (snapped) vertices at the centre of (px, py), in f64.
fn plane_depth(v: &[ScreenVertex; 3], px: i32, py: i32) -> f64 {
    let f = |s: &ScreenVertex| {
        (
            f64::from(s.x()) / 16.0,
            f64::from(s.y()) / 16.0,
            f64::from(s.z()) / 65536.0,
        )
    };
    let (a, b, c) = (f(&v[0]), f(&v[1]), f(&v[2]));
    let (cx, cy) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
    let det = (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1);
    let l1 = ((cx - a.0) * (c.1 - a.1) - (c.0 - a.0) * (cy - a.1)) / det;
    let l2 = ((b.0 - a.0) * (cy - a.1) - (cx - a.0) * (b.1 - a.1)) / det;
    a.2 + l1 * (b.2 - a.2) + l2 * (c.2 - a.2)
}

/// Snapping moves a vertex by at most 1/32 pixel along each axis.
const SNAP: f64 = 0.045;

fn vertex() -> impl Strategy<Value = (f64, f64, f64)> {
    (-40.0f64..104.0, -40.0f64..88.0, 0.0f64..65535.0)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Coverage equals the float reference's except within snapping distance of an
    /// edge; depth is within ±1 of the plane through the snapped vertices.
    #[test]
    fn triangles_match_the_float_reference(a in vertex(), b in vertex(), c in vertex()) {
        let t = [(a.0, a.1), (b.0, b.1), (c.0, c.1)];
        let v = [a, b, c].map(|(x, y, z)| ScreenVertex::from_f32(x as f32, y as f32, z as f32).unwrap());
        let mut depth = vec![0u16; (W * H) as usize];
        let mut zbuf = ZBuffer::new(&mut depth, W as u32, H as u32).unwrap();
        zbuf.clear();
        zbuf.set_test(DepthTest::Always);
        let mut counter = Counter::new();
        fill_triangle(&mut counter, &mut zbuf, &v, BinaryColor::On).unwrap();
        let snapped_area = zraster::signed_area((v[0].x(), v[0].y()), (v[1].x(), v[1].y()), (v[2].x(), v[2].y()));
        for py in 0..H {
            for px in 0..W {
                let n = counter.at(px, py);
                prop_assert!(n <= 1, "pixel ({px},{py}) written {n} times");
                let (inside, dist) = reference(&t, px, py);
                if dist > SNAP && snapped_area != 0 {
                    prop_assert_eq!(n == 1, inside, "pixel ({},{}) at {} px from an edge", px, py, dist);
                }
                if n == 1 {
                    let want = plane_depth(&v, px, py);
                    let got = f64::from(zbuf.depth(px, py).unwrap());
                    prop_assert!((got - want).abs() <= 1.0, "depth at ({},{}): {} vs {}", px, py, got, want);
                }
            }
        }
    }

    /// A jittered grid of triangles (shared edges and vertices, slivers included) covers
    /// every pixel inside its outline exactly once, flat or shaded.
    #[test]
    fn grids_are_watertight(seed in any::<u64>(), n in 2i32..9, shaded in any::<bool>()) {
        let mut s = seed;
        let mut rnd = move || { s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407); (s >> 33) as i32 };
        let cell = (W - 4) * 16 / n;
        // Jitter of up to an eighth of the shorter cell side keeps every quad convex, so
        // either diagonal splits it into two triangles that do not overlap.
        let r = cell * (H - 4) / (W - 4) / 8;
        let grid: Vec<Vec<ScreenVertex>> = (0..=n).map(|j| (0..=n).map(|i| {
            let (mut x, mut y) = (32 + i * cell, 32 + j * cell * (H - 4) / (W - 4));
            if i > 0 && i < n { x += rnd() % (2 * r + 1) - r; }
            if j > 0 && j < n { y += rnd() % (2 * r + 1) - r; }
            ScreenVertex::new(x, y, (rnd() & 0xffff) as u32 * 1000).unwrap()
        }).collect()).collect();
        let mut depth = vec![0u16; (W * H) as usize];
        let mut zbuf = ZBuffer::new(&mut depth, W as u32, H as u32).unwrap();
        zbuf.set_test(DepthTest::Always);
        let mut counter = Counter::new();
        for j in 0..n as usize {
            for i in 0..n as usize {
                let (a, b, c, d) = (grid[j][i], grid[j][i + 1], grid[j + 1][i + 1], grid[j + 1][i]);
                let tris = if rnd() % 2 == 0 { [[a, b, c], [a, c, d]] } else { [[a, d, b], [b, d, c]] };
                for t in &tris {
                    if shaded {
                        fill_triangle_shaded(&mut counter, &mut zbuf, t, embedded_graphics::pixelcolor::Rgb888::WHITE, [1000, 20000, 32768]).unwrap();
                    } else {
                        fill_triangle(&mut counter, &mut zbuf, t, BinaryColor::On).unwrap();
                    }
                }
            }
        }
        // Inside the outline: pixel centres from the first column/row of vertices (at
        // pixel corner 2) up to, not including, the last (the top-left rule).
        let (x1, y1) = (grid[0][n as usize].x(), grid[n as usize][0].y());
        for py in 0..H {
            for px in 0..W {
                let (cx, cy) = (px * 16 + 8, py * 16 + 8);
                let inside = (32..x1).contains(&cx) && (32..y1).contains(&cy);
                prop_assert_eq!(counter.at(px, py), u8::from(inside), "pixel ({}, {})", px, py);
            }
        }
    }

    /// A fan around a random centre covers its polygon exactly once.
    #[test]
    fn fans_are_watertight(cx in 10.0f32..54.0, cy in 10.0f32..38.0, k in 3usize..40, seed in any::<u64>()) {
        let mut s = seed;
        let mut rnd = move || { s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407); (s >> 40) as f32 / 16777216.0 };
        let centre = ScreenVertex::from_f32(cx, cy, 100.0).unwrap();
        let rim: Vec<ScreenVertex> = (0..k).map(|i| {
            let a = (i as f32 + 0.3 * rnd()) * core::f32::consts::TAU / k as f32;
            let r = 4.0 + 30.0 * rnd();
            ScreenVertex::from_f32(cx + r * a.cos(), cy + r * a.sin(), 500.0).unwrap()
        }).collect();
        let fan: Vec<[ScreenVertex; 3]> = (0..k).map(|i| [centre, rim[i], rim[(i + 1) % k]]).collect();
        let mut depth = vec![0u16; (W * H) as usize];
        let mut zbuf = ZBuffer::new(&mut depth, W as u32, H as u32).unwrap();
        zbuf.set_test(DepthTest::Always);
        let mut counter = Counter::new();
        for t in &fan {
            fill_triangle(&mut counter, &mut zbuf, t, BinaryColor::On).unwrap();
        }
        for py in 0..H {
            for px in 0..W {
                let want = fan.iter().filter(|t| common::covers(t, px, py)).count();
                prop_assert!(want <= 1);
                prop_assert_eq!(usize::from(counter.at(px, py)), want, "pixel ({}, {})", px, py);
            }
        }
    }

    /// The fused colour-and-depth path gives the same pixels and depths as runs.
    #[test]
    fn fused_and_run_paths_agree(tris in proptest::collection::vec((vertex(), vertex(), vertex()), 1..12)) {
        use embedded_graphics::pixelcolor::Rgb888;
        use zraster::{camera::{Transform, Viewport}, math::{Mat4, Vec3}, mesh::Mesh, RenderOptions, Renderer};
        // The triangles as a mesh seen through an orthographic camera that maps model
        // x, y to pixels and z to depth.
        let mut pos = Vec::new();
        let mut idx = Vec::new();
        for (a, b, c) in &tris {
            let base = pos.len() as u16;
            for p in [a, b, c] {
                pos.push([(p.0 * 64.0) as i16, (p.1 * 64.0) as i16, ((p.2 / 65535.0 * 2.0 - 1.0) * 16000.0) as i16]);
            }
            idx.push([base, base + 1, base + 2]);
        }
        let mesh = Mesh::triangles(&pos, 1.0 / 64.0, &idx, Rgb888::new(90, 200, 30));
        let vp = Viewport::new(W as u32, H as u32).unwrap();
        let xf = Transform {
            model: Mat4::IDENTITY,
            view: Mat4::IDENTITY,
            projection: Mat4::orthographic(0.0, W as f32, H as f32, 0.0, -300.0, 300.0),
            viewport: vp,
        };
        let _ = Vec3::default();
        let opts = RenderOptions { cull: zraster::Cull::None, ..Default::default() };
        let draw = |fused: bool| {
            let mut px = vec![embedded_graphics::pixelcolor::Rgb565::BLACK; (W * H) as usize];
            let mut depth = vec![0u16; (W * H) as usize];
            {
                let mut frame = ColorBuffer::new(&mut px, W as u32, H as u32).unwrap();
                let mut zbuf = ZBuffer::new(&mut depth, W as u32, H as u32).unwrap();
                zbuf.clear();
                let mut cache = vec![zraster::CachedVertex::EMPTY; pos.len()];
                let mut r = Renderer::with_cache(&mesh, &xf, opts, &mut cache).unwrap();
                if fused { r.draw(&mut Frame::from_buffers(frame, zbuf)).unwrap() } else { r.draw(&mut WithDepth::new(&mut frame, &mut zbuf)).unwrap() }
            }
            (px, depth)
        };
        let (a, b) = (draw(false), draw(true));
        prop_assert!(a == b, "the fused path differs from the run path");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(60))]

    /// A jittered grid mesh through the renderers that fill — Z-buffer (runs), Z-buffer
    /// fused into a colour buffer, and depth sort — covers every pixel of its outline
    /// exactly once.
    #[test]
    fn renderer_grids_are_watertight(seed in any::<u64>(), n in 2usize..7) {
        use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
        use zraster::{camera::{Transform, Viewport}, math::Mat4, mesh::Mesh, DepthSort, RenderOptions, Renderer};
        let mut s = seed;
        let mut rnd = move || { s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407); (s >> 40) as i32 };
        // Model units are 1/16 pixel; the outline is the rectangle (2, 2)–(62, 46) px.
        let (cx, cy) = ((W - 4) * 16 / n as i32, (H - 4) * 16 / n as i32);
        let r = cx.min(cy) / 8;
        let mut pos = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                let (mut x, mut y) = (32 + i as i32 * cx, 32 + j as i32 * cy);
                if i > 0 && i < n { x += rnd() % (2 * r + 1) - r; }
                if j > 0 && j < n { y += rnd() % (2 * r + 1) - r; }
                pos.push([x as i16, y as i16, (rnd() % 2000) as i16]);
            }
        }
        let at = |i: usize, j: usize| (j * (n + 1) + i) as u16;
        let mut idx = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                if rnd() % 2 == 0 { idx.push([a, d, c]); idx.push([a, c, b]); } else { idx.push([a, d, b]); idx.push([b, d, c]); }
            }
        }
        let mesh = Mesh::triangles(&pos, 1.0 / 16.0, &idx, Rgb888::WHITE);
        let xf = Transform {
            model: Mat4::IDENTITY,
            view: Mat4::IDENTITY,
            projection: Mat4::orthographic(0.0, W as f32, H as f32, 0.0, -200.0, 200.0),
            viewport: Viewport::new(W as u32, H as u32).unwrap(),
        };
        let opts = RenderOptions { cull: zraster::Cull::None, ..Default::default() };
        let inside = |px: i32, py: i32| (2..62).contains(&px) && (2..46).contains(&py);
        // Z-buffer through runs, with Always so that nothing hides an overdraw.
        let mut depth = vec![0u16; (W * H) as usize];
        let mut zbuf = ZBuffer::new(&mut depth, W as u32, H as u32).unwrap();
        zbuf.set_test(DepthTest::Always);
        let mut counter = Counter::new();
        Renderer::new(&mesh, &xf, opts).unwrap().draw(&mut WithDepth::new(&mut BinaryTarget(&mut counter), &mut zbuf)).unwrap();
        // Depth sort (no Z-buffer).
        let mut sorted = Counter::new();
        let mut sort = DepthSort::<128>::new();
        Renderer::new(&mesh, &xf, opts).unwrap().draw_depth_sorted(&mut BinaryTarget(&mut sorted), &mut sort).unwrap();
        // Fused: every pixel of the outline written once (pixels_written counts writes).
        let mut px = vec![Rgb565::BLACK; (W * H) as usize];
        let frame = ColorBuffer::new(&mut px, W as u32, H as u32).unwrap();
        zbuf.fill(0);
        let mut r = Renderer::new(&mesh, &xf, opts).unwrap();
        r.draw(&mut Frame::from_buffers(frame, zbuf)).unwrap();
        prop_assert_eq!(r.stats().pixels_written, 60 * 44);
        for py in 0..H {
            for px in 0..W {
                prop_assert_eq!(counter.at(px, py), u8::from(inside(px, py)), "Z-buffer, pixel ({}, {})", px, py);
                prop_assert_eq!(sorted.at(px, py), u8::from(inside(px, py)), "depth sort, pixel ({}, {})", px, py);
            }
        }
    }
}

/// Presents the counting target as an `Rgb565` one (the renderers' materials are
/// `Rgb888`, which shades to `Rgb565`).
struct BinaryTarget<'a>(&'a mut Counter);

impl OriginDimensions for BinaryTarget<'_> {
    fn size(&self) -> Size {
        self.0.size()
    }
}

impl DrawTarget for BinaryTarget<'_> {
    type Color = embedded_graphics::pixelcolor::Rgb565;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Self::Color>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        self.0.draw_iter(
            pixels
                .into_iter()
                .map(|Pixel(p, _)| Pixel(p, BinaryColor::On)),
        )
    }
}
