//! Banded drawing is byte-identical to whole-frame drawing: colour, depth and stats,
//! also where faces tie in depth (coplanar duplicates), at every band height.

use embedded_graphics::{
    pixelcolor::{Rgb565, Rgb888},
    prelude::*,
};
use proptest::prelude::*;
use zraster::{
    camera::{Camera, Transform, Viewport},
    math::{radians, Mat4, Vec3},
    mesh::{Faces, Materials, Mesh},
    shade::Shading,
    BandBuffers, Bands, CachedVertex, ColorBuffer, Cull, Frame, FrameStats, RenderOptions,
    Renderer,
};

/// One frame: its colours, its depths and the renderer's stats.
type Pictures = (Vec<Rgb565>, Vec<u16>, FrameStats);

fn whole(mesh: &Mesh<'_, Rgb888>, xf: &Transform, opts: RenderOptions, w: u32, h: u32) -> Pictures {
    let mut colour = vec![Rgb565::BLACK; (w * h) as usize];
    let mut depth = vec![0u16; (w * h) as usize];
    let mut cache = vec![CachedVertex::EMPTY; mesh.positions.len()];
    let stats = {
        let mut frame = Frame::new(&mut colour, &mut depth, w, h).unwrap();
        frame.clear(Rgb565::BLACK);
        let mut r = Renderer::with_cache(mesh, xf, opts, &mut cache).unwrap();
        r.draw(&mut frame).unwrap();
        r.stats()
    };
    (colour, depth, stats)
}

/// The same frame band by band, `rows` lines at a time, with or without bins; the
/// depth is collected from each band as it is finished.
fn banded(
    mesh: &Mesh<'_, Rgb888>,
    xf: &Transform,
    opts: RenderOptions,
    (w, h, rows): (u32, u32, u32),
    binned: bool,
) -> Pictures {
    let mut colour = vec![Rgb565::BLUE; (w * h) as usize];
    let mut depth = vec![7u16; (w * h) as usize];
    let mut cb = vec![Rgb565::BLACK; (w * rows) as usize];
    let mut zb = vec![0u16; (w * rows) as usize];
    let n = mesh.face_count();
    let mut bins = vec![
        0u16;
        if binned {
            BandBuffers::<Rgb565>::bins_needed(n, h, rows)
        } else {
            0
        }
    ];
    let mut cache = vec![CachedVertex::EMPTY; mesh.positions.len()];
    let stats = {
        let mut display = ColorBuffer::new(&mut colour, w, h).unwrap();
        let mut bands = BandBuffers::new(&mut cb, &mut zb, w, rows, h, &mut bins).unwrap();
        let mut r = Renderer::with_cache(mesh, xf, opts, &mut cache).unwrap();
        let mut target =
            Bands::new(&mut display, &mut bands, Rgb565::BLACK).after_band(|band, z| {
                let y0 = band.first_row();
                for y in y0..y0 + band.rows() as i32 {
                    for x in 0..w as i32 {
                        depth[(y as u32 * w + x as u32) as usize] = z.depth(x, y).unwrap();
                    }
                }
            });
        r.draw(&mut target).unwrap();
        r.stats()
    };
    (colour, depth, stats)
}

fn assert_identical(a: &Pictures, b: &Pictures, what: &str) {
    let differ = |x: &[_], y: &[_]| x.iter().zip(y).filter(|(p, q)| p != q).count();
    let colours: usize = a.0.iter().zip(&b.0).filter(|(p, q)| p != q).count();
    assert_eq!(colours, 0, "{what}: {colours} pixels of colour differ");
    assert_eq!(differ(&a.1, &b.1), 0, "{what}: depths differ");
    assert_eq!(a.2, b.2, "{what}: stats differ");
}

/// A floor of `n × n` unit tiles in the y = 0 plane, every tile listed twice (as two
/// triangles each time, split along either diagonal) with another colour: the second copy ties the first in depth
/// everywhere, so the Z-buffer keeps whichever was drawn first (`Less`).
struct Floor {
    positions: Vec<[i16; 3]>,
    indices: Vec<[u16; 3]>,
    colours: Vec<Rgb888>,
}

impl Floor {
    fn new(n: i16) -> Floor {
        let mut positions = Vec::new();
        for z in 0..=n {
            for x in 0..=n {
                positions.push([x * 100 - n * 50, 0, z * 100 - n * 50]);
            }
        }
        let at = |x: i16, z: i16| (z * (n + 1) + x) as u16;
        let (mut indices, mut colours) = (Vec::new(), Vec::new());
        for copy in 0..2u8 {
            for z in 0..n {
                for x in 0..n {
                    let (a, b, c, d) = (at(x, z), at(x + 1, z), at(x + 1, z + 1), at(x, z + 1));
                    // Counter-clockwise seen from above (+y); the copy is split along
                    // the other diagonal, so its triangles span other rows (and bins).
                    let k = (x + z) as u8 & 1;
                    let colour = Rgb888::new(60 + 120 * copy, 40 + 100 * k, 200 - 150 * copy);
                    if copy == 0 {
                        indices.extend([[a, d, c], [a, c, b]]);
                    } else {
                        indices.extend([[a, d, b], [b, d, c]]);
                    }
                    colours.extend([colour, colour]);
                }
            }
        }
        Floor {
            positions,
            indices,
            colours,
        }
    }

    fn mesh(&self) -> Mesh<'_, Rgb888> {
        Mesh {
            positions: &self.positions,
            scale: 0.01,
            faces: Faces::Triangles {
                indices: &self.indices,
                materials: Materials::PerFace(&self.colours),
            },
            face_normals: None,
            vertex_normals: None,
        }
    }
}

fn view(w: u32, h: u32, yaw: f32, pitch: f32, distance: f32) -> Transform {
    let vp = Viewport::new(w, h).unwrap();
    Camera::look_at(Vec3::new(0.0, 0.0, distance), Vec3::default(), Vec3::Y)
        .unwrap()
        .perspective(radians(60.0), 0.1, 10.0, vp)
        .unwrap()
        .with_model(Mat4::rotation_x(radians(pitch)) * Mat4::rotation_y(radians(yaw)))
}

/// Coplanar duplicate tiles seen from above at every band height 1..=H, with and
/// without bins: the first copy wins everywhere, in bands as in the whole frame.
#[test]
fn coplanar_duplicates_at_every_band_height() {
    let (w, h) = (48, 40);
    let floor = Floor::new(6);
    let mesh = floor.mesh();
    for cull in [Cull::None, Cull::Back] {
        for shading in [Shading::Flat, Shading::Lambert] {
            let opts = RenderOptions {
                cull,
                shading,
                ..Default::default()
            };
            let xf = view(w, h, 25.0, 50.0, 1.4);
            let want = whole(&mesh, &xf, opts, w, h);
            assert!(want.2.drawn > 20, "{:?}", want.2);
            for rows in 1..=h {
                for binned in [false, true] {
                    let got = banded(&mesh, &xf, opts, (w, h, rows), binned);
                    let what = format!("{cull:?} {shading:?} rows {rows} bins {binned}");
                    assert_identical(&got, &want, &what);
                }
            }
        }
    }
}

/// A random triangle soup in which every triangle is followed, somewhere later, by a
/// coplanar copy in another colour.
fn soup(seed: u64, n: usize) -> (Vec<[i16; 3]>, Vec<[u16; 3]>, Vec<Rgb888>) {
    let mut s = seed | 1;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        s
    };
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    let mut colours = Vec::new();
    for _ in 0..n {
        let base = positions.len() as u16;
        for _ in 0..3 {
            let c = |r: u64| ((r % 2001) as i16) - 1000;
            positions.push([c(next()), c(next()), c(next())]);
        }
        indices.push([base, base + 1, base + 2]);
        colours.push(Rgb888::new(next() as u8, next() as u8, next() as u8));
    }
    // The copies, shuffled in among later faces: same vertices, other colours.
    for i in 0..n {
        if next() % 3 != 0 {
            let t = indices[i];
            let at = i + 1 + (next() as usize % (indices.len() - i));
            indices.insert(at, t);
            colours.insert(at, Rgb888::new(next() as u8, next() as u8, 255));
        }
    }
    (positions, indices, colours)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Random meshes with coplanar duplicates, random views and band heights: banded
    /// output is byte-identical to the whole frame (colour, depth, stats).
    #[test]
    fn random_soups_band_exactly(
        seed in any::<u64>(),
        n in 1usize..40,
        rows in 1u32..=40,
        yaw in -180.0f32..180.0,
        pitch in -80.0f32..80.0,
        distance in 0.6f32..4.0,
        cull in prop_oneof![Just(Cull::None), Just(Cull::Back), Just(Cull::Front)],
        lambert in any::<bool>(),
        binned in any::<bool>(),
    ) {
        let (w, h) = (40, 40);
        let (positions, indices, colours) = soup(seed, n);
        let mesh = Mesh {
            positions: &positions,
            scale: 0.001,
            faces: Faces::Triangles { indices: &indices, materials: Materials::PerFace(&colours) },
            face_normals: None,
            vertex_normals: None,
        };
        let opts = RenderOptions {
            cull,
            shading: if lambert { Shading::Lambert } else { Shading::Flat },
            ..Default::default()
        };
        let xf = view(w, h, yaw, pitch, distance);
        let want = whole(&mesh, &xf, opts, w, h);
        let got = banded(&mesh, &xf, opts, (w, h, rows), binned);
        assert_identical(&got, &want, &format!("rows {rows} bins {binned}"));
    }
}
