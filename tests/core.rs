//! The core rasterizer against the seeds' worked examples and exact pixel cases.

mod common;

use common::{covers, plane_depth, stored_depth, vpx, vsub};
use embedded_graphics::{
    mock_display::MockDisplay,
    pixelcolor::{BinaryColor, Rgb565},
    prelude::*,
};
use zraster::{
    depth_at, fill_triangle, signed_area, ColorBuffer, DepthTest, Error, Facing, ScreenVertex,
    ZBuffer,
};

// ---- The seeds' worked examples -------------------------------------------------------

#[test]
fn seeds_plane_equation_example_gives_z_8_at_1_1() {
    // A (0,0,6), B (3,0,9), C (0,3,9): plane x + y − z = −6, so z = 8 at (1, 1).
    let tri = [vpx(0, 0, 6), vpx(3, 0, 9), vpx(0, 3, 9)];
    assert_eq!(depth_at(&tri, 16, 16), Some(8 << 16));
    // And at the vertices the plane gives the vertex depths back.
    assert_eq!(depth_at(&tri, 48, 0), Some(9 << 16));
    assert_eq!(depth_at(&tri, 0, 0), Some(6 << 16));
    // The rasterizer stores the same plane: at pixel (1, 1)'s centre (1.5, 1.5), z = 9.
    let mut depth = [0u16; 8 * 8];
    let mut zbuf = ZBuffer::new(&mut depth, 8, 8).unwrap();
    zbuf.clear();
    let mut display = MockDisplay::<BinaryColor>::new();
    fill_triangle(&mut display, &mut zbuf, &tri, BinaryColor::On).unwrap();
    // z = x + y + 6: 8 at the centres (1.5, 0.5) and (0.5, 1.5), 7 at (0.5, 0.5).
    assert_eq!(zbuf.depth(1, 0), Some(8));
    assert_eq!(zbuf.depth(0, 1), Some(8));
    assert_eq!(zbuf.depth(0, 0), Some(7));
    // (1.5, 1.5) lies on the hypotenuse, a right edge: not covered, depth untouched.
    assert_eq!(zbuf.depth(1, 1), Some(u16::MAX));
}

#[test]
fn seeds_back_face_example() {
    // P1 (1,3), P2 (5,5), P3 (2,7): (4,2) × (1,4) = 14 → front.
    assert_eq!(signed_area((1, 3), (5, 5), (2, 7)), 14);
    // P4 (3,2), P5 (7,6), P6 (7,1): (4,4) × (4,−1) = −20 → back.
    assert_eq!(signed_area((3, 2), (7, 6), (7, 1)), -20);
    assert_eq!(Facing::of_area(14), Facing::Front);
    assert_eq!(Facing::of_area(-20), Facing::Back);
    assert_eq!(Facing::of_area(0), Facing::Degenerate);
    // The seeds' y axis points up; on the screen it points down, so the same faces have
    // the y coordinates negated there, and keep their facing.
    let front = [vpx(1, -3, 0), vpx(5, -5, 0), vpx(2, -7, 0)];
    let back = [vpx(3, -2, 0), vpx(7, -6, 0), vpx(7, -1, 0)];
    assert_eq!(signed_area((16, -48), (80, -80), (32, -112)), -14 * 256);
    assert_eq!(Facing::of(&front), Facing::Front);
    assert_eq!(Facing::of(&back), Facing::Back);
}

// ---- Hidden surfaces without sorting ---------------------------------------------------

const W: u32 = 48;
const H: u32 = 48;

/// Draw `tris` in the given order into a fresh colour + depth buffer pair.
fn render(tris: &[([ScreenVertex; 3], Rgb565)], order: &[usize]) -> (Vec<Rgb565>, Vec<u16>) {
    let mut pixels = vec![Rgb565::BLACK; (W * H) as usize];
    let mut depth = vec![0u16; (W * H) as usize];
    {
        let mut frame = ColorBuffer::new(&mut pixels, W, H).unwrap();
        let mut zbuf = ZBuffer::new(&mut depth, W, H).unwrap();
        zbuf.clear();
        for &i in order {
            let (tri, c) = &tris[i];
            fill_triangle(&mut frame, &mut zbuf, tri, *c).unwrap();
        }
    }
    (pixels, depth)
}

/// The picture the Z-buffer algorithm must give: at each pixel, the nearest covering
/// triangle by its plane.
fn expected(tris: &[([ScreenVertex; 3], Rgb565)]) -> Vec<Rgb565> {
    let mut out = vec![Rgb565::BLACK; (W * H) as usize];
    for py in 0..H as i32 {
        for px in 0..W as i32 {
            let best = tris
                .iter()
                .filter(|(t, _)| covers(t, px, py))
                .min_by_key(|(t, _)| stored_depth(t, px, py));
            if let Some((_, c)) = best {
                out[(py * W as i32 + px) as usize] = *c;
            }
        }
    }
    out
}

fn sub(x: f32, y: f32, z: f32) -> ScreenVertex {
    ScreenVertex::from_f32(x, y, z).unwrap()
}

#[test]
fn interpenetrating_triangles_any_order_crossing_where_the_planes_say() {
    // A: depth 100·x.  B: depth 100·y + 25.  They cross along x = y + 0.25.
    let a = [
        sub(0.0, 0.0, 0.0),
        sub(48.0, 0.0, 4800.0),
        sub(0.0, 48.0, 0.0),
    ];
    let b = [
        sub(0.0, 0.0, 25.0),
        sub(48.0, 48.0, 4825.0),
        sub(0.0, 48.0, 4825.0),
    ];
    let tris = [(a, Rgb565::RED), (b, Rgb565::GREEN)];
    let (p1, z1) = render(&tris, &[0, 1]);
    let (p2, z2) = render(&tris, &[1, 0]);
    assert_eq!(p1, p2);
    assert_eq!(z1, z2);
    assert_eq!(p1, expected(&tris));
    // Where both cover pixel (i, j), A (100i + 50) is nearer than B (100j + 75) iff i ≤ j.
    let mut both = 0;
    for j in 0..H as i32 {
        for i in 0..W as i32 {
            if covers(&a, i, j) && covers(&b, i, j) {
                both += 1;
                let want = if i <= j { Rgb565::RED } else { Rgb565::GREEN };
                assert_eq!(p1[(j * W as i32 + i) as usize], want, "pixel ({i},{j})");
                let zmin = (100 * i + 50).min(100 * j + 75) as u16;
                assert_eq!(z1[(j * W as i32 + i) as usize], zmin);
            }
        }
    }
    assert!(both > 500, "the triangles overlap on {both} pixels");
}

/// Three slanted strips in cyclic overlap (the seeds' "three-way" case): no drawing
/// order is right for the painter, every order is right for the Z-buffer.
fn cyclic_triangles() -> [([ScreenVertex; 3], Rgb565); 3] {
    // Corners P, Q, R; strip A runs P→Q, B runs Q→R, C runs R→P, each a wedge with its
    // wide base (far, depth 9000) before its first corner and its tip (near, depth 1000)
    // past its second. So A is over B at Q, B over C at R, C over A at P.
    let wedge = |from: (f32, f32), to: (f32, f32)| {
        let (dx, dy) = (to.0 - from.0, to.1 - from.1);
        let len = (dx * dx + dy * dy).sqrt();
        let (ux, uy) = (dx / len, dy / len);
        let (bx, by) = (from.0 - 6.0 * ux, from.1 - 6.0 * uy);
        [
            sub(bx - 7.0 * uy, by + 7.0 * ux, 9000.0),
            sub(bx + 7.0 * uy, by - 7.0 * ux, 9000.0),
            sub(to.0 + 9.0 * ux, to.1 + 9.0 * uy, 1000.0),
        ]
    };
    let (p, q, r) = ((10.0, 12.0), (38.0, 12.0), (24.0, 38.0));
    let (a, b, c) = (wedge(p, q), wedge(q, r), wedge(r, p));
    [(a, Rgb565::RED), (b, Rgb565::GREEN), (c, Rgb565::BLUE)]
}

#[test]
fn cyclic_overlap_drawn_correctly_in_every_order() {
    let tris = cyclic_triangles();
    let want = expected(&tris);
    let orders = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ];
    for order in orders {
        assert_eq!(render(&tris, &order).0, want, "order {order:?}");
    }
    // The overlap really is cyclic: A hides B somewhere, B hides C, C hides A.
    let hides = |x: usize, y: usize| {
        (0..H as i32).any(|py| {
            (0..W as i32).any(|px| {
                let (tx, ty) = (&tris[x].0, &tris[y].0);
                covers(tx, px, py)
                    && covers(ty, px, py)
                    && plane_depth(tx, px, py) < plane_depth(ty, px, py)
                    && (0..3).all(|k| !covers(&tris[k].0, px, py) || k == x || k == y)
            })
        })
    };
    assert!(hides(0, 1) && hides(1, 2) && hides(2, 0));
    assert!(!hides(1, 0) && !hides(2, 1) && !hides(0, 2));
}

// ---- Fill rule and watertightness -------------------------------------------------------

fn zbuffer_for<'a>(depth: &'a mut [u16], test: DepthTest) -> ZBuffer<'a> {
    let mut z = ZBuffer::new(depth, 64, 64).unwrap();
    z.clear();
    z.set_test(test);
    z
}

#[test]
fn top_left_rule_on_edges_through_pixel_centres() {
    // A square with corners at pixel centres (2.5, 1.5) and (6.5, 5.5), as two triangles.
    let (l, t, r, b) = (40, 24, 104, 88);
    let t1 = [vsub(l, t, 5), vsub(r, t, 5), vsub(r, b, 5)];
    let t2 = [vsub(l, t, 5), vsub(r, b, 5), vsub(l, b, 5)];
    let mut depth = [0u16; 64 * 64];
    // `Always` so that a pixel drawn twice reaches the display twice (MockDisplay panics).
    let mut zbuf = zbuffer_for(&mut depth, DepthTest::Always);
    let mut display = MockDisplay::<BinaryColor>::new();
    fill_triangle(&mut display, &mut zbuf, &t1, BinaryColor::On).unwrap();
    fill_triangle(&mut display, &mut zbuf, &t2, BinaryColor::On).unwrap();
    // Left column 2 and top row 1 are in; right column 6 and bottom row 5 are out.
    display.assert_pattern(&["       ", "  #### ", "  #### ", "  #### ", "  #### "]);
}

#[test]
fn top_left_rule_with_the_opposite_winding() {
    let (l, t, r, b) = (40, 24, 104, 88);
    let t1 = [vsub(l, t, 5), vsub(r, b, 5), vsub(r, t, 5)];
    let mut depth = [0u16; 64 * 64];
    let mut zbuf = zbuffer_for(&mut depth, DepthTest::Always);
    let mut display = MockDisplay::<BinaryColor>::new();
    fill_triangle(&mut display, &mut zbuf, &t1, BinaryColor::On).unwrap();
    // The diagonal passes through centres (2.5,1.5), (3.5,2.5), …; it is a left edge here.
    display.assert_pattern(&["       ", "  #### ", "   ### ", "    ## ", "     # "]);
}

/// A deterministic jitter in 1/16 pixel.
fn jitter(i: i32, j: i32) -> (i32, i32) {
    let h = (i * 7919 + j * 104_729) as u32;
    let h = h.wrapping_mul(2_654_435_761);
    (((h >> 8) % 97) as i32 - 48, ((h >> 16) % 89) as i32 - 44)
}

#[test]
fn a_grid_of_triangles_covers_every_pixel_exactly_once() {
    // 6×6 cells over pixels 2..62; inner vertices jittered by up to ±3 pixels in 1/16 steps.
    let n = 6;
    let pt = |i: i32, j: i32| {
        let (mut x, mut y) = (32 + i * 160, 32 + j * 160);
        if i > 0 && i < n {
            x += jitter(i, j).0;
        }
        if j > 0 && j < n {
            y += jitter(i, j).1;
        }
        vsub(x, y, 100)
    };
    let mut depth = [0u16; 64 * 64];
    let mut zbuf = zbuffer_for(&mut depth, DepthTest::Always);
    let mut display = MockDisplay::<BinaryColor>::new(); // panics on any pixel drawn twice
    let mut written = 0;
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (pt(i, j), pt(i + 1, j), pt(i + 1, j + 1), pt(i, j + 1));
            // Alternate the diagonal and the winding, as real meshes do.
            let tris = if (i + j) % 2 == 0 {
                [[a, b, c], [a, c, d]]
            } else {
                [[a, d, b], [b, d, c]]
            };
            for t in &tris {
                written += fill_triangle(&mut display, &mut zbuf, t, BinaryColor::On)
                    .unwrap()
                    .pixels_written;
            }
        }
    }
    assert_eq!(written, 60 * 60);
    for y in 0..64 {
        for x in 0..64 {
            let inside = (2..62).contains(&x) && (2..62).contains(&y);
            let drawn = display.get_pixel(Point::new(x, y)).is_some();
            assert_eq!(drawn, inside, "pixel ({x},{y})");
        }
    }
}

#[test]
fn a_fan_around_one_vertex_covers_its_polygon_exactly_once() {
    // 24 triangles around (31.3, 30.8), rim vertices on an irregular star.
    let centre = sub(31.3, 30.8, 500.0);
    let rim: Vec<ScreenVertex> = (0..24)
        .map(|k| {
            let a = k as f32 * core::f32::consts::TAU / 24.0;
            let r = if k % 2 == 0 { 29.0 } else { 21.37 };
            sub(31.3 + r * a.cos(), 30.8 + r * a.sin(), 900.0)
        })
        .collect();
    let fan: Vec<[ScreenVertex; 3]> = (0..24)
        .map(|k| [centre, rim[k], rim[(k + 1) % 24]])
        .collect();
    let mut depth = [0u16; 64 * 64];
    let mut zbuf = zbuffer_for(&mut depth, DepthTest::Always);
    let mut display = MockDisplay::<BinaryColor>::new();
    for t in &fan {
        fill_triangle(&mut display, &mut zbuf, t, BinaryColor::On).unwrap();
    }
    for y in 0..64 {
        for x in 0..64 {
            let n = fan.iter().filter(|t| covers(t, x, y)).count();
            assert!(n <= 1, "reference covers ({x},{y}) {n} times");
            assert_eq!(
                display.get_pixel(Point::new(x, y)).is_some(),
                n == 1,
                "pixel ({x},{y})"
            );
        }
    }
}

// ---- Small readable cases ---------------------------------------------------------------

#[test]
fn nearer_triangle_wins_whatever_the_order() {
    let back = [vpx(0, 0, 5000), vpx(8, 0, 5000), vpx(0, 8, 5000)];
    let front = [vpx(2, 2, 100), vpx(8, 2, 100), vpx(8, 8, 100)];
    for order in [[0, 1], [1, 0]] {
        let mut depth = [0u16; 64 * 64];
        let mut zbuf = zbuffer_for(&mut depth, DepthTest::Less);
        let mut display = MockDisplay::<Rgb565>::new();
        display.set_allow_overdraw(true);
        for i in order {
            let (t, c) = [(back, Rgb565::RED), (front, Rgb565::GREEN)][i];
            fill_triangle(&mut display, &mut zbuf, &t, c).unwrap();
        }
        display.assert_pattern(&[
            "RRRRRRR ", "RRRRRR  ", "RRGGGGGG", "RRRGGGGG", "RRR GGGG", "RR   GGG", "R     GG",
            "       G",
        ]);
    }
}

#[test]
fn depth_test_modes_and_write_switch() {
    let tri = [vpx(0, 0, 300), vpx(4, 0, 300), vpx(0, 4, 300)];
    let draw = |test: DepthTest, write: bool, stored: u16| {
        let mut depth = [0u16; 64 * 64];
        let mut zbuf = ZBuffer::new(&mut depth, 64, 64).unwrap();
        zbuf.fill(stored);
        zbuf.set_test(test);
        zbuf.set_write(write);
        let mut display = MockDisplay::<BinaryColor>::new();
        let s = fill_triangle(&mut display, &mut zbuf, &tri, BinaryColor::On).unwrap();
        (s.pixels_written, zbuf.depth(0, 0).unwrap())
    };
    assert_eq!(draw(DepthTest::Less, true, 300), (0, 300));
    assert_eq!(draw(DepthTest::Less, true, 301), (6, 300));
    assert_eq!(draw(DepthTest::LessEqual, true, 300), (6, 300));
    assert_eq!(draw(DepthTest::LessEqual, false, 999), (6, 999));
    assert_eq!(draw(DepthTest::Greater, true, 299), (6, 300));
    assert_eq!(draw(DepthTest::Greater, true, 300), (0, 300));
    assert_eq!(draw(DepthTest::Equal, true, 300), (6, 300));
    assert_eq!(draw(DepthTest::Always, true, 0), (6, 300));
    assert_eq!(draw(DepthTest::Never, true, 65535), (0, 65535));
}

#[test]
fn runs_split_where_the_depth_test_fails() {
    // A far triangle drawn over a near vertical bar: each row splits into two runs.
    let mut depth = [0u16; 64 * 64];
    let mut zbuf = zbuffer_for(&mut depth, DepthTest::Less);
    let mut display = MockDisplay::<Rgb565>::new();
    let bar = [
        [vpx(3, 0, 10), vpx(5, 0, 10), vpx(5, 4, 10)],
        [vpx(3, 0, 10), vpx(5, 4, 10), vpx(3, 4, 10)],
    ];
    for t in &bar {
        fill_triangle(&mut display, &mut zbuf, t, Rgb565::BLUE).unwrap();
    }
    let quad = [
        [vpx(0, 0, 90), vpx(8, 0, 90), vpx(8, 4, 90)],
        [vpx(0, 0, 90), vpx(8, 4, 90), vpx(0, 4, 90)],
    ];
    let mut stats = zraster::SpanStats::default();
    for t in &quad {
        stats += fill_triangle(&mut display, &mut zbuf, t, Rgb565::YELLOW).unwrap();
    }
    display.assert_pattern(&["YYYBBYYY", "YYYBBYYY", "YYYBBYYY", "YYYBBYYY"]);
    assert_eq!(stats.pixels_tested, 32);
    assert_eq!(stats.pixels_written, 24);
    // Rows split by the bar and by the diagonal: 4 rows × 2 sides, the diagonal cuts
    // the right-hand part into the upper and lower triangle.
    assert!(stats.runs >= 8, "{stats:?}");
}

// ---- Bands ------------------------------------------------------------------------------

#[test]
fn a_band_zbuffer_confines_drawing_to_its_rows() {
    let mut depth = [0u16; 64 * 3];
    let mut zbuf = ZBuffer::new_band(&mut depth, 64, 3, 2).unwrap();
    zbuf.clear();
    let mut display = MockDisplay::<BinaryColor>::new();
    let tri = [vpx(0, 0, 1), vpx(6, 0, 1), vpx(0, 6, 1)];
    fill_triangle(&mut display, &mut zbuf, &tri, BinaryColor::On).unwrap();
    display.assert_pattern(&["      ", "      ", "###   ", "##    ", "#     "]);
    assert_eq!(zbuf.depth(0, 2), Some(1));
    assert_eq!(zbuf.depth(0, 1), None);
}

// ---- Bad input --------------------------------------------------------------------------

#[test]
fn buffers_reject_wrong_sizes() {
    let mut d = [0u16; 10];
    assert_eq!(
        ZBuffer::new(&mut d, 4, 3).err(),
        Some(Error::BufferTooSmall {
            needed: 12,
            got: 10
        })
    );
    assert_eq!(ZBuffer::new(&mut d, 0, 3).err(), Some(Error::ZeroSize));
    assert_eq!(ZBuffer::new(&mut d, 3, 0).err(), Some(Error::ZeroSize));
    assert_eq!(ZBuffer::new(&mut d, 9000, 1).err(), Some(Error::TooLarge));
    assert_eq!(
        ZBuffer::new(&mut d, 5, 2).map(|z| z.as_slice().len()),
        Ok(10)
    );
    let mut c = [Rgb565::BLACK; 10];
    assert_eq!(
        ColorBuffer::new(&mut c, 4, 3).err(),
        Some(Error::BufferTooSmall {
            needed: 12,
            got: 10
        })
    );
    assert_eq!(ColorBuffer::new(&mut c, 1, 0).err(), Some(Error::ZeroSize));
    assert_eq!(
        ColorBuffer::new(&mut c, 1, 8193).err(),
        Some(Error::TooLarge)
    );
}

#[test]
fn degenerate_triangles_draw_nothing() {
    let mut depth = [0u16; 64 * 64];
    let mut zbuf = zbuffer_for(&mut depth, DepthTest::Always);
    let mut display = MockDisplay::<BinaryColor>::new();
    let cases = [
        [vpx(1, 1, 0), vpx(1, 1, 0), vpx(1, 1, 0)],
        [vpx(0, 0, 0), vpx(5, 5, 0), vpx(10, 10, 0)],
        [vpx(0, 3, 0), vpx(9, 3, 0), vpx(4, 3, 0)],
    ];
    for t in &cases {
        let s = fill_triangle(&mut display, &mut zbuf, t, BinaryColor::On).unwrap();
        assert_eq!(s, zraster::SpanStats::default());
    }
    display.assert_pattern(&[]);
}

#[test]
fn huge_coordinates_neither_overflow_nor_write_outside() {
    // Vertices a million pixels away; the visible part must match the reference exactly.
    let m = 1_000_000.0;
    let cases = [
        [
            sub(-m, -m, 100.0),
            sub(m, 30.5, 60000.0),
            sub(20.25, m, 3000.0),
        ],
        [
            sub(-m, 10.0, 0.0),
            sub(m, 12.0, 65535.0),
            sub(m, 50.0, 65535.0),
        ],
        [sub(m, -m, 7.0), sub(-m, -m, 7.0), sub(0.0, m, 7.0)],
    ];
    for tri in &cases {
        let mut depth = [0u16; 64 * 64];
        let mut zbuf = zbuffer_for(&mut depth, DepthTest::Always);
        let mut display = MockDisplay::<BinaryColor>::new(); // panics outside 64×64
        fill_triangle(&mut display, &mut zbuf, tri, BinaryColor::On).unwrap();
        for y in 0..64 {
            for x in 0..64 {
                let c = covers(tri, x, y);
                assert_eq!(
                    display.get_pixel(Point::new(x, y)).is_some(),
                    c,
                    "({x},{y}) of {tri:?}"
                );
                if c {
                    let want = stored_depth(tri, x, y);
                    let got = i64::from(zbuf.depth(x, y).unwrap());
                    assert!(
                        (got - want).abs() <= 1,
                        "depth at ({x},{y}): {got} vs {want}"
                    );
                }
            }
        }
    }
    // Beyond the guard band a vertex cannot be made at all.
    assert_eq!(
        ScreenVertex::from_f32(1.1e6, 0.0, 0.0),
        Err(Error::OutOfRange)
    );
    assert_eq!(
        ScreenVertex::from_pixels(0, i32::MIN, 0),
        Err(Error::OutOfRange)
    );
}

#[test]
fn depth_at_the_ends_of_its_range() {
    // Depth 0 and 65535 at the vertices: stored values stay in range, never wrap.
    let tri = [vpx(0, 0, 0), vpx(64, 0, 65535), vpx(0, 64, 0)];
    let mut depth = [0u16; 64 * 64];
    let mut zbuf = zbuffer_for(&mut depth, DepthTest::Always);
    let mut display = MockDisplay::<BinaryColor>::new();
    fill_triangle(&mut display, &mut zbuf, &tri, BinaryColor::On).unwrap();
    for y in 0..64 {
        for x in 0..64 {
            if covers(&tri, x, y) {
                assert_eq!(
                    i64::from(zbuf.depth(x, y).unwrap()),
                    stored_depth(&tri, x, y),
                    "({x},{y})"
                );
            }
        }
    }
    assert_eq!(zbuf.depth(0, 0), Some(512)); // 65535/64 · 0.5, rounded
                                             // A steep depth slope (65535 over one pixel) stays clamped within the vertex range.
    let steep = [vsub(0, 0, 0), vsub(16, 0, 65535), vsub(0, 640, 0)];
    display.set_allow_overdraw(true);
    zbuf.fill(u16::MAX);
    fill_triangle(&mut display, &mut zbuf, &steep, BinaryColor::On).unwrap();
    let mut covered = 0;
    for y in 0..64 {
        for x in 0..64 {
            if covers(&steep, x, y) {
                covered += 1;
                let got = i64::from(zbuf.depth(x, y).unwrap());
                assert!((got - stored_depth(&steep, x, y)).abs() <= 1, "({x},{y})");
            } else {
                assert_eq!(zbuf.depth(x, y), Some(u16::MAX));
            }
        }
    }
    assert_eq!(covered, 20);
}

/// `fill_contiguous` into a colour buffer (here a band of rows 10..13): whole rows, part
/// rows, areas partly outside and iterators too short or too long all fill exactly the
/// pixels a pixel-by-pixel reference fills.
#[test]
fn color_buffer_fill_contiguous_matches_a_pixel_reference() {
    use embedded_graphics::{pixelcolor::Gray8, primitives::Rectangle};
    let (w, rows, first) = (5u32, 3u32, 10i32);
    let areas = [
        Rectangle::new(Point::new(0, 10), Size::new(5, 3)),
        Rectangle::new(Point::new(0, 11), Size::new(5, 1)),
        Rectangle::new(Point::new(1, 10), Size::new(3, 2)),
        Rectangle::new(Point::new(-2, 9), Size::new(5, 3)),
        Rectangle::new(Point::new(0, 12), Size::new(5, 4)),
        Rectangle::new(Point::new(0, 20), Size::new(5, 1)),
    ];
    for area in areas {
        for len in [0usize, 3, 7, 15, 40] {
            let mut data = vec![Gray8::new(255); (w * rows) as usize];
            let mut buf = ColorBuffer::new_band(&mut data, w, rows, first).unwrap();
            let colors = (0..len).map(|i| Gray8::new(i as u8));
            buf.fill_contiguous(&area, colors).unwrap();
            let mut want = vec![Gray8::new(255); (w * rows) as usize];
            for (i, p) in area.points().enumerate().take(len) {
                let (x, y) = (p.x, p.y - first);
                if (0..w as i32).contains(&x) && (0..rows as i32).contains(&y) {
                    want[(y as u32 * w + x as u32) as usize] = Gray8::new(i as u8);
                }
            }
            assert_eq!(data, want, "{area:?}, {len} colours");
        }
    }
}
