//! Scenes: several meshes, each with its own model matrix, options and materials, in one
//! depth buffer. Drawn in bands they are byte-identical to the whole frame (colour,
//! depth and summed stats) with or without bins; bins too short leave the objects that
//! do not fit unbinned, to the same picture; objects tie in depth in object order.

use embedded_graphics::{
    mock_display::MockDisplay,
    pixelcolor::{Rgb565, Rgb888},
    prelude::*,
};
use proptest::prelude::*;
use zraster::{
    camera::{Camera, Viewport},
    math::{radians, Mat4, Vec3},
    mesh::{compute_vertex_normals, Faces, Materials, Mesh, CUBE, CUBE_POSITIONS},
    scene::Scene,
    shade::Shading,
    BandBuffers, Bands, Binning, CachedVertex, ColorBuffer, Cull, Frame, FrameStats, RenderOptions,
    Renderer, Unbinned, WithDepth, ZBuffer,
};

const W: u32 = 48;
const H: u32 = 40;

/// The unit cube's faces as triangles, counter-clockwise from outside.
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

/// A mesh the test owns: the polygon cube, a triangle cube, or a random soup of
/// triangles with coplanar copies, each with vertex normals (for Gouraud).
struct Object {
    positions: Vec<[i16; 3]>,
    indices: Vec<[u16; 3]>,
    colours: Vec<Rgb888>,
    normals: Vec<[i16; 3]>,
    polygons: bool,
}

impl Object {
    fn polygon_cube() -> Object {
        Object::with_normals(CUBE_POSITIONS.to_vec(), vec![], vec![], true)
    }

    fn triangle_cube(seed: u8) -> Object {
        let colours = (0..12u8)
            .map(|i| Rgb888::new(40 + 17 * i, seed.wrapping_mul(29), 250 - 9 * i))
            .collect();
        Object::with_normals(
            CUBE_POSITIONS.to_vec(),
            CUBE_TRIANGLES.to_vec(),
            colours,
            false,
        )
    }

    /// `n` random triangles, about two in three followed later by a coplanar copy.
    fn soup(seed: u64, n: usize) -> Object {
        let mut s = seed | 1;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        let (mut positions, mut indices, mut colours) = (vec![], vec![], vec![]);
        for _ in 0..n {
            let base = positions.len() as u16;
            for _ in 0..3 {
                let c = |r: u64| ((r % 16385) as i16) - 8192;
                positions.push([c(next()), c(next()), c(next())]);
            }
            indices.push([base, base + 1, base + 2]);
            colours.push(Rgb888::new(next() as u8, next() as u8, next() as u8));
        }
        for i in 0..n {
            if next() % 3 != 0 {
                let at = i + 1 + (next() as usize % (indices.len() - i));
                indices.insert(at, indices[i]);
                colours.insert(at, Rgb888::new(next() as u8, 255, next() as u8));
            }
        }
        Object::with_normals(positions, indices, colours, false)
    }

    fn with_normals(
        positions: Vec<[i16; 3]>,
        indices: Vec<[u16; 3]>,
        colours: Vec<Rgb888>,
        polygons: bool,
    ) -> Object {
        let mut o = Object {
            normals: vec![[0; 3]; positions.len()],
            positions,
            indices,
            colours,
            polygons,
        };
        let mut scratch = vec![Vec3::default(); o.positions.len()];
        let mut normals = vec![[0i16; 3]; o.positions.len()];
        compute_vertex_normals(&o.mesh(), &mut scratch, &mut normals).unwrap();
        o.normals = normals;
        o
    }

    fn mesh(&self) -> Mesh<'_, Rgb888> {
        let faces = if self.polygons {
            CUBE.faces
        } else {
            Faces::Triangles {
                indices: &self.indices,
                materials: Materials::PerFace(&self.colours),
            }
        };
        Mesh {
            positions: &self.positions,
            scale: 1.0 / 16384.0,
            faces,
            face_normals: None,
            vertex_normals: Some(&self.normals),
        }
    }
}

/// How an object is placed and drawn.
#[derive(Debug, Clone, Copy)]
struct Placing {
    model: Mat4,
    options: RenderOptions,
}

fn camera() -> Camera {
    Camera::look_at(Vec3::new(0.0, 0.4, 3.0), Vec3::default(), Vec3::Y)
        .unwrap()
        .perspective(radians(60.0), 0.5, 10.0, Viewport::new(W, H).unwrap())
        .unwrap()
}

/// Where the scene goes.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Into {
    Frame,
    Display,
    /// Bands of this many rows with `bins` bin entries (`usize::MAX`: what the scene
    /// needs).
    Bands {
        rows: u32,
        bins: usize,
    },
}

/// One frame: colours, depths, the scene's stats, each object's binning.
struct Drawn {
    colour: Vec<Rgb565>,
    depth: Vec<u16>,
    stats: FrameStats,
    binning: Vec<Binning>,
}

/// Draw `objects` placed by `placings` (with vertex caches unless `cached` is false).
fn draw(objects: &[Object], placings: &[Placing], into: Into, cached: bool) -> Drawn {
    let meshes: Vec<_> = objects.iter().map(Object::mesh).collect();
    let mut caches: Vec<Vec<CachedVertex>> = meshes
        .iter()
        .map(|m| vec![CachedVertex::EMPTY; m.positions.len()])
        .collect();
    let mut renderers: Vec<Renderer<'_, '_, Rgb888>> = meshes
        .iter()
        .zip(placings)
        .zip(caches.iter_mut())
        .map(|((mesh, p), cache)| {
            let xf = camera().with_model(p.model);
            match cached {
                true => Renderer::with_cache(mesh, &xf, p.options, cache).unwrap(),
                false => Renderer::new(mesh, &xf, p.options).unwrap(),
            }
        })
        .collect();
    let n = (W * H) as usize;
    let (mut colour, mut depth) = (vec![Rgb565::BLACK; n], vec![0u16; n]);
    let mut scene = Scene::new(&mut renderers);
    match into {
        Into::Frame => {
            let mut frame = Frame::new(&mut colour, &mut depth, W, H).unwrap();
            frame.clear(Rgb565::BLACK);
            scene.draw(&mut frame).unwrap();
        }
        Into::Display => {
            let mut display = ColorBuffer::new(&mut colour, W, H).unwrap();
            let mut zbuf = ZBuffer::new(&mut depth, W, H).unwrap();
            zbuf.clear();
            scene
                .draw(&mut WithDepth::new(&mut display, &mut zbuf))
                .unwrap();
        }
        Into::Bands { rows, bins } => {
            let wanted = Scene::bins_needed(scene.objects(), H, rows);
            let mut bins = vec![0u16; bins.min(wanted)];
            colour.fill(Rgb565::BLUE); // every pixel must be sent
            let mut display = ColorBuffer::new(&mut colour, W, H).unwrap();
            let (mut cb, mut zb) = (
                vec![Rgb565::RED; (W * rows) as usize],
                vec![7; (W * rows) as usize],
            );
            let mut buffers = BandBuffers::new(&mut cb, &mut zb, W, rows, H, &mut bins).unwrap();
            let mut bands =
                Bands::new(&mut display, &mut buffers, Rgb565::BLACK).after_band(|band, z| {
                    let y0 = band.first_row();
                    for y in y0..y0 + band.rows() as i32 {
                        for x in 0..W as i32 {
                            depth[(y as u32 * W + x as u32) as usize] = z.depth(x, y).unwrap();
                        }
                    }
                });
            scene.draw(&mut bands).unwrap();
        }
    }
    Drawn {
        stats: scene.stats(),
        binning: scene.objects().iter().map(Renderer::binning).collect(),
        colour,
        depth,
    }
}

fn assert_identical(got: &Drawn, want: &Drawn, what: &str) {
    let differ = |a: &[Rgb565], b: &[Rgb565]| a.iter().zip(b).filter(|(p, q)| p != q).count();
    assert_eq!(
        differ(&got.colour, &want.colour),
        0,
        "{what}: colours differ"
    );
    assert!(got.depth == want.depth, "{what}: depths differ");
    assert_eq!(got.stats, want.stats, "{what}: stats differ");
}

fn options(shading: Shading, cull: Cull) -> RenderOptions {
    RenderOptions {
        shading,
        cull,
        ..Default::default()
    }
}

fn placed(x: f32, y: f32, z: f32, yaw: f32, pitch: f32, size: f32) -> Mat4 {
    Mat4::translation(Vec3::new(x, y, z))
        * Mat4::rotation_y(yaw)
        * Mat4::rotation_x(pitch)
        * Mat4::scaling(Vec3::new(size, size, size))
        * Mat4::translation(Vec3::new(-0.5, -0.5, -0.5))
}

fn kind() -> impl Strategy<Value = (u8, u64, usize)> {
    (0u8..3, any::<u64>(), 1usize..24)
}

fn placing() -> impl Strategy<Value = Placing> {
    (
        (-1.2f32..1.2, -0.8f32..0.8, -1.5f32..2.2),
        (-3.2f32..3.2, -1.6f32..1.6, 0.3f32..1.6),
        0u8..3,
        prop_oneof![Just(Cull::Back), Just(Cull::None), Just(Cull::Front)],
    )
        .prop_map(|((x, y, z), (yaw, pitch, size), shading, cull)| {
            let shading = [Shading::Flat, Shading::Lambert, Shading::Gouraud][shading as usize];
            Placing {
                model: placed(x, y, z, yaw, pitch, size),
                options: options(shading, cull),
            }
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    /// 2 to 4 random objects (cubes, random soups with coplanar copies), placed and
    /// shaded at random, some through the near plane: every band height, with all the
    /// bins, some or none, draws the whole frame's colours, depths and stats.
    #[test]
    fn random_scenes_band_exactly(
        objects in prop::collection::vec((kind(), placing()), 2..=4),
        rows in 1u32..=H,
        bins in prop_oneof![Just(usize::MAX), Just(0usize), 0usize..120],
    ) {
        let (kinds, placings): (Vec<_>, Vec<_>) = objects.into_iter().unzip();
        let objects: Vec<Object> = kinds
            .iter()
            .map(|&(k, seed, n)| match k {
                0 => Object::polygon_cube(),
                1 => Object::triangle_cube(seed as u8),
                _ => Object::soup(seed, n),
            })
            .collect();
        let want = draw(&objects, &placings, Into::Frame, true);
        let got = draw(&objects, &placings, Into::Bands { rows, bins }, true);
        assert_identical(&got, &want, &format!("rows {rows} bins {bins}"));
        // Each object binned unless it cannot: polygons, Gouraud, or no room.
        for ((o, p), b) in objects.iter().zip(&placings).zip(&got.binning) {
            if o.polygons {
                prop_assert_eq!(*b, Binning::Off(Unbinned::Polygons));
            } else if p.options.shading == Shading::Gouraud {
                prop_assert_eq!(*b, Binning::Off(Unbinned::Gouraud));
            } else if bins == usize::MAX {
                prop_assert_eq!(*b, Binning::Binned);
            }
        }
        // Without caches every band walks every mesh: the same frame again.
        let uncached = draw(&objects, &placings, Into::Bands { rows, bins }, false);
        assert_identical(&uncached, &want, &format!("uncached rows {rows}"));
    }
}

/// Three triangle cubes, Lambert, in 8-row bands.
fn three_cubes() -> (Vec<Object>, Vec<Placing>) {
    let objects = (0..3).map(Object::triangle_cube).collect();
    let lambert = options(Shading::Lambert, Cull::Back);
    let placings = [(-1.0, 0.3), (0.0, -0.1), (1.0, 0.2)]
        .map(|(x, yaw)| Placing {
            model: placed(x, 0.0, 0.0, yaw, 0.4, 0.8),
            options: lambert,
        })
        .to_vec();
    (objects, placings)
}

/// With one entry fewer than the scene needs, the last object's run does not fit: it
/// draws unbinned (and says why), the others binned; with none, none is binned. The
/// picture is the whole frame's every time, as it is drawing into a display.
#[test]
fn short_bins_unbin_the_objects_that_do_not_fit() {
    let (objects, placings) = three_cubes();
    let want = draw(&objects, &placings, Into::Frame, true);
    assert!(want.stats.drawn >= 12, "{:?}", want.stats);
    let needed = Scene::<Rgb888>::bins_needed(
        &objects
            .iter()
            .map(|o| Renderer::new(&o.mesh(), &camera(), RenderOptions::default()).unwrap())
            .collect::<Vec<_>>(),
        H,
        8,
    );
    let binned = Binning::Binned;
    let short = Binning::Off(Unbinned::BinsTooShort);
    for (bins, binning) in [
        (needed, [binned; 3]),
        (needed - 1, [binned, binned, short]),
        (needed / 3, [binned, short, short]),
        (needed / 3 - 1, [short; 3]),
        (0, [short; 3]),
    ] {
        let got = draw(&objects, &placings, Into::Bands { rows: 8, bins }, true);
        assert_eq!(got.binning, binning, "{bins} of {needed} bins");
        assert_identical(&got, &want, &format!("{bins} of {needed} bins"));
    }
    // Without caches: unbinned, for that reason.
    let got = draw(
        &objects,
        &placings,
        Into::Bands {
            rows: 8,
            bins: needed,
        },
        false,
    );
    assert_eq!(got.binning, [Binning::Off(Unbinned::NoCache); 3]);
    assert_identical(&got, &want, "no caches");
    // Into a display with a Z-buffer: the same colours and depths and pixel counts.
    let got = draw(&objects, &placings, Into::Display, true);
    assert_eq!(got.colour, want.colour);
    assert!(got.depth == want.depth);
    assert_eq!(
        FrameStats {
            runs: 0,
            ..got.stats
        },
        want.stats
    );
}

/// The bins a scene needs: for each object one entry a face and four a band plus two
/// (here 5 bands of 8 rows, or 3 of 16), added up over the objects.
#[test]
fn bins_needed_adds_up_each_objects_bins() {
    let tri = Object::triangle_cube(1);
    let (tri_mesh, poly_mesh) = (tri.mesh(), CUBE);
    let xf = camera();
    let objects = [
        Renderer::new(&tri_mesh, &xf, RenderOptions::default()).unwrap(),
        Renderer::new(&poly_mesh, &xf, RenderOptions::default()).unwrap(),
        Renderer::new(&tri_mesh, &xf, RenderOptions::default()).unwrap(),
    ];
    assert_eq!(
        Scene::bins_needed(&objects, 40, 8),
        (12 + 22) + (6 + 22) + (12 + 22)
    );
    assert_eq!(
        Scene::bins_needed(&objects, 40, 16),
        (12 + 14) + (6 + 14) + (12 + 14)
    );
    assert_eq!(
        Scene::bins_needed(&objects[..1], 40, 8),
        BandBuffers::<Rgb565>::bins_needed(12, 40, 8)
    );
    assert_eq!(Scene::bins_needed(&objects[..0], 40, 8), 0);
    // A band of 0 rows counts as 1 row (40 bands), as BandBuffers::bins_needed does.
    assert_eq!(Scene::bins_needed(&objects[..1], 40, 0), 12 + 2 * 81);
}

/// A square facing the camera, two triangles, in one colour.
const SQUARE_CORNERS: [[i16; 3]; 4] = [[0, 0, 0], [16384, 0, 0], [16384, 16384, 0], [0, 16384, 0]];
const SQUARE_TRIANGLES: [[u16; 3]; 2] = [[0, 1, 2], [0, 2, 3]];

/// Two coplanar squares in two objects, red then green, the same model: every pixel
/// ties in depth, and the first object keeps it (the depth test is `Less`), in the
/// whole frame and in bands of every height with and without bins; in the other order
/// the other colour wins.
#[test]
fn earlier_objects_win_ties_in_depth() {
    let red = Mesh::triangles(
        &SQUARE_CORNERS,
        1.0 / 16384.0,
        &SQUARE_TRIANGLES,
        Rgb888::RED,
    );
    let green = Mesh::triangles(
        &SQUARE_CORNERS,
        1.0 / 16384.0,
        &SQUARE_TRIANGLES,
        Rgb888::GREEN,
    );
    let model = Mat4::rotation_y(0.3) * Mat4::translation(Vec3::new(-0.5, -0.5, 0.0));
    let xf = camera().with_model(model);
    for (first, second, colour) in [(&red, &green, Rgb565::RED), (&green, &red, Rgb565::GREEN)] {
        let whole = {
            let mut display = MockDisplay::<Rgb565>::new();
            display.set_allow_overdraw(true);
            let mut depth = [0u16; 64 * 64];
            let mut zbuf = ZBuffer::new(&mut depth, 64, 64).unwrap();
            zbuf.clear();
            let mut objects = [
                Renderer::new(first, &xf, RenderOptions::default()).unwrap(),
                Renderer::new(second, &xf, RenderOptions::default()).unwrap(),
            ];
            Scene::new(&mut objects)
                .draw(&mut WithDepth::new(&mut display, &mut zbuf))
                .unwrap();
            display
        };
        let mut frame_px = vec![Rgb565::BLACK; (W * H) as usize];
        let mut frame_z = vec![0u16; (W * H) as usize];
        let mut frame = Frame::new(&mut frame_px, &mut frame_z, W, H).unwrap();
        frame.clear(Rgb565::BLACK);
        let mut objects = [
            Renderer::new(first, &xf, RenderOptions::default()).unwrap(),
            Renderer::new(second, &xf, RenderOptions::default()).unwrap(),
        ];
        Scene::new(&mut objects).draw(&mut frame).unwrap();
        let mut covered = 0;
        for y in 0..H as i32 {
            for x in 0..W as i32 {
                let got = frame.color().pixel(x, y).unwrap();
                assert!(got == Rgb565::BLACK || got == colour, "({x}, {y}): {got:?}");
                covered += usize::from(got == colour);
                // The display drawn run by run agrees (the second object drew nothing).
                let shown = whole.get_pixel(Point::new(x, y)).unwrap_or(Rgb565::BLACK);
                assert_eq!(shown, got, "({x}, {y})");
            }
        }
        assert!(covered > 100, "{covered} pixels of the square");
        for rows in [1, 3, 8, 16, H] {
            for bins in [0, usize::MAX] {
                let mut shown = vec![Rgb565::BLUE; (W * H) as usize];
                let mut display = ColorBuffer::new(&mut shown, W, H).unwrap();
                let (mut cb, mut zb) = (
                    vec![Rgb565::BLACK; (W * rows) as usize],
                    vec![0; (W * rows) as usize],
                );
                let (mut ca, mut cb2) = ([CachedVertex::EMPTY; 4], [CachedVertex::EMPTY; 4]);
                let mut objects = [
                    Renderer::with_cache(first, &xf, RenderOptions::default(), &mut ca).unwrap(),
                    Renderer::with_cache(second, &xf, RenderOptions::default(), &mut cb2).unwrap(),
                ];
                let mut bin_memory = vec![0u16; bins.min(Scene::bins_needed(&objects, H, rows))];
                let mut buffers =
                    BandBuffers::new(&mut cb, &mut zb, W, rows, H, &mut bin_memory).unwrap();
                let mut scene = Scene::new(&mut objects);
                scene
                    .draw(&mut Bands::new(&mut display, &mut buffers, Rgb565::BLACK))
                    .unwrap();
                let binned = scene
                    .objects()
                    .iter()
                    .all(|r| r.binning() == Binning::Binned);
                assert_eq!(binned, bins > 0, "rows {rows}");
                assert!(shown == frame.color().as_slice(), "rows {rows} bins {bins}");
            }
        }
    }
}
