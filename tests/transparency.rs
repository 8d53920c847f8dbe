//! See-through materials: drawn after the opaque faces, depth-tested without depth
//! writes, blended over the colour drawn (hand-computed RGB565 values), the same in
//! bands as in the whole frame; a screen door into a display whose colours cannot be
//! read.

use embedded_graphics::{
    pixelcolor::{Rgb565, Rgb888},
    prelude::*,
};
use zraster::{
    camera::{Camera, Viewport},
    math::{radians, Mat4, Vec3},
    mesh::{Faces, Materials, Mesh},
    scene::Scene,
    shade::{Shading, Translucent},
    BandBuffers, Bands, Binning, CachedVertex, ColorBuffer, Frame, FrameStats, RenderOptions,
    Renderer, WithDepth, ZBuffer,
};

const W: u32 = 64;
const H: u32 = 48;
const RED: Translucent = Translucent::new(Rgb888::RED, 255);

/// Squares facing the camera (+z), corners (x0, y0) and (x1, y1) at depth z, in
/// world units of 1/8192: two triangles each, in the order given.
struct Squares {
    positions: Vec<[i16; 3]>,
    indices: Vec<[u16; 3]>,
    materials: Vec<Translucent>,
}

impl Squares {
    fn new(squares: &[([f32; 5], Translucent)]) -> Squares {
        let (mut positions, mut indices, mut materials) = (vec![], vec![], vec![]);
        for &([x0, y0, x1, y1, z], m) in squares {
            let q = |v: f32| (v * 8192.0) as i16;
            let base = positions.len() as u16;
            positions
                .extend([[x0, y0], [x1, y0], [x1, y1], [x0, y1]].map(|[x, y]| [q(x), q(y), q(z)]));
            indices.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
            materials.extend([m, m]);
        }
        Squares {
            positions,
            indices,
            materials,
        }
    }

    fn mesh(&self) -> Mesh<'_, Translucent> {
        Mesh {
            positions: &self.positions,
            scale: 1.0 / 8192.0,
            faces: Faces::Triangles {
                indices: &self.indices,
                materials: Materials::PerFace(&self.materials),
            },
            face_normals: None,
            vertex_normals: None,
        }
    }
}

fn camera() -> Camera {
    Camera::look_at(Vec3::new(0.0, 0.0, 4.0), Vec3::default(), Vec3::Y)
        .unwrap()
        .perspective(radians(40.0), 1.0, 10.0, Viewport::new(W, H).unwrap())
        .unwrap()
}

/// A frame: colours, depths, stats.
type Pictures = (Vec<Rgb565>, Vec<u16>, FrameStats);

/// `meshes` (each with its model matrix and options) as one scene into a whole frame.
fn whole(meshes: &[(Mesh<'_, Translucent>, Mat4, RenderOptions)]) -> Pictures {
    let (mut colour, mut depth) = (
        vec![Rgb565::BLACK; (W * H) as usize],
        vec![0; (W * H) as usize],
    );
    let mut frame = Frame::new(&mut colour, &mut depth, W, H).unwrap();
    frame.clear(Rgb565::BLACK);
    let mut objects: Vec<_> = meshes
        .iter()
        .map(|(m, model, o)| Renderer::new(m, &camera().with_model(*model), *o).unwrap())
        .collect();
    let mut scene = Scene::new(&mut objects);
    scene.draw(&mut frame).unwrap();
    let stats = scene.stats();
    (colour, depth, stats)
}

/// The same in bands of `rows`, with vertex caches and, if `binned`, all the bins.
fn banded(
    meshes: &[(Mesh<'_, Translucent>, Mat4, RenderOptions)],
    rows: u32,
    binned: bool,
) -> Pictures {
    let (mut colour, mut depth) = (
        vec![Rgb565::BLUE; (W * H) as usize],
        vec![7; (W * H) as usize],
    );
    let mut caches: Vec<_> = meshes
        .iter()
        .map(|(m, ..)| vec![CachedVertex::EMPTY; m.positions.len()])
        .collect();
    let mut objects: Vec<_> = meshes
        .iter()
        .zip(caches.iter_mut())
        .map(|((m, model, o), c)| {
            Renderer::with_cache(m, &camera().with_model(*model), *o, c).unwrap()
        })
        .collect();
    let n = if binned {
        Scene::bins_needed(&objects, H, rows)
    } else {
        0
    };
    let mut bins = vec![0u16; n];
    let (mut cb, mut zb) = (
        vec![Rgb565::RED; (W * rows) as usize],
        vec![0; (W * rows) as usize],
    );
    let mut buffers = BandBuffers::new(&mut cb, &mut zb, W, rows, H, &mut bins).unwrap();
    let mut display = ColorBuffer::new(&mut colour, W, H).unwrap();
    let mut scene = Scene::new(&mut objects);
    scene
        .draw(
            &mut Bands::new(&mut display, &mut buffers, Rgb565::BLACK).after_band(|band, z| {
                for y in band.first_row()..band.first_row() + band.rows() as i32 {
                    for x in 0..W as i32 {
                        depth[(y as u32 * W + x as u32) as usize] = z.depth(x, y).unwrap();
                    }
                }
            }),
        )
        .unwrap();
    let want = if binned {
        Binning::Binned
    } else {
        Binning::Off(zraster::Unbinned::BinsTooShort)
    };
    for r in scene.objects() {
        if r.stats().drawn > 0 && r.binning() != Binning::Off(zraster::Unbinned::Gouraud) {
            assert_eq!(r.binning(), want);
        }
    }
    let stats = scene.stats();
    (colour, depth, stats)
}

fn at(p: &Pictures, x: u32, y: u32) -> (Rgb565, u16) {
    let i = (y * W + x) as usize;
    (p.0[i], p.1[i])
}

fn flat() -> RenderOptions {
    RenderOptions::default()
}

/// An opaque red square (z = 0) behind a half-transparent blue one (z = 0.5) that
/// overhangs it up and to the right; the blue faces come first in the face table but
/// are drawn after the red ones. RGB565 by hand: red (31, 0, 0), blue (0, 0, 31); half
/// of each, rounded down, is (15, 0, 15) where both lie, (0, 0, 15) over the black
/// background; red alone where the blue does not reach.
#[test]
fn half_blue_over_red_is_the_mean_rounded_down() {
    let blue = Translucent::new(Rgb888::BLUE, 128);
    let squares = Squares::new(&[
        ([-0.5, -0.5, 1.5, 1.5, 0.5], blue),
        ([-1.0, -1.0, 1.0, 1.0, 0.0], RED),
    ]);
    let red_only = Squares::new(&[([-1.0, -1.0, 1.0, 1.0, 0.0], RED)]);
    let got = whole(&[(squares.mesh(), Mat4::IDENTITY, flat())]);
    let red = whole(&[(red_only.mesh(), Mat4::IDENTITY, flat())]);
    assert_eq!(at(&got, 32, 20).0, Rgb565::new(15, 0, 15));
    assert_eq!(at(&got, 20, 30).0, Rgb565::new(31, 0, 0));
    assert_eq!(at(&got, 55, 5).0, Rgb565::new(0, 0, 15));
    assert_eq!(at(&got, 5, 5).0, Rgb565::BLACK);
    // The depths are the red square's alone: the blue one wrote none, not even over
    // the background.
    assert!(got.1 == red.1, "the see-through faces changed the depths");
    assert_eq!(at(&got, 55, 5).1, ZBuffer::FAR);
    // Counted once as geometry; their pixels after the red ones'.
    assert_eq!(got.2.drawn, 4);
    assert!(got.2.pixels_written > red.2.pixels_written);
    // At a quarter: 31 · 191 / 255 = 23.2 of the red stays, 31 · 64 / 255 = 7.8 of the
    // blue comes in.
    let quarter = Squares::new(&[
        (
            [-0.5, -0.5, 1.5, 1.5, 0.5],
            Translucent::from_opacity(Rgb888::BLUE, 0.25),
        ),
        ([-1.0, -1.0, 1.0, 1.0, 0.0], RED),
    ]);
    let got = whole(&[(quarter.mesh(), Mat4::IDENTITY, flat())]);
    assert_eq!(at(&got, 32, 20).0, Rgb565::new(23, 0, 8));
}

/// A see-through square behind an opaque one draws nothing where the opaque one hides
/// it: there the picture is the opaque one's alone, pixel for pixel.
#[test]
fn see_through_faces_behind_opaque_ones_draw_nothing() {
    let blue = Translucent::new(Rgb888::BLUE, 128);
    let squares = Squares::new(&[
        ([-1.0, -1.0, 1.0, 1.0, 0.0], RED),
        ([-0.5, -0.5, 1.5, 1.5, -0.5], blue),
    ]);
    let red_only = Squares::new(&[([-1.0, -1.0, 1.0, 1.0, 0.0], RED)]);
    let got = whole(&[(squares.mesh(), Mat4::IDENTITY, flat())]);
    let red = whole(&[(red_only.mesh(), Mat4::IDENTITY, flat())]);
    let mut blended = 0;
    for (i, (&g, &r)) in got.0.iter().zip(&red.0).enumerate() {
        if r != Rgb565::BLACK {
            assert_eq!(g, r, "pixel {i} behind the red square");
        } else if g != Rgb565::BLACK {
            assert_eq!(g, Rgb565::new(0, 0, 15), "pixel {i} over the background");
            blended += 1;
        }
    }
    assert!(blended > 50, "{blended} pixels of blue over the background");
    assert!(got.1 == red.1);
    // Depth-tested everywhere it covers, written (blended) only over the background.
    assert_eq!(got.2.pixels_written, red.2.pixels_written + blended);
    assert!(got.2.pixels_tested > got.2.pixels_written);
}

/// In a scene the see-through objects wait for every opaque one, whatever the object
/// order: a glass square first, the red one behind it second, blend as in one mesh.
#[test]
fn a_scene_draws_every_opaque_object_first() {
    let glass = Squares::new(&[(
        [-0.5, -0.5, 1.5, 1.5, 0.5],
        Translucent::new(Rgb888::BLUE, 128),
    )]);
    let red = Squares::new(&[([-1.0, -1.0, 1.0, 1.0, 0.0], RED)]);
    let scene = [
        (glass.mesh(), Mat4::IDENTITY, flat()),
        (red.mesh(), Mat4::IDENTITY, flat()),
    ];
    let got = whole(&scene);
    assert_eq!(at(&got, 32, 20).0, Rgb565::new(15, 0, 15));
    assert_eq!(at(&got, 20, 30).0, Rgb565::new(31, 0, 0));
    // One renderer drawn alone also draws its see-through faces after its opaque ones.
    let mut colour = vec![Rgb565::BLACK; (W * H) as usize];
    let mut depth = vec![0; (W * H) as usize];
    let mut frame = Frame::new(&mut colour, &mut depth, W, H).unwrap();
    frame.clear(Rgb565::BLACK);
    Renderer::new(&red.mesh(), &camera(), flat())
        .unwrap()
        .draw(&mut frame)
        .unwrap();
    Renderer::new(&glass.mesh(), &camera(), flat())
        .unwrap()
        .draw(&mut frame)
        .unwrap();
    assert_eq!(frame.color().as_slice(), &got.0[..]);
}

/// Opaque and see-through squares, overlapping one another at several alphas (the
/// overlapping see-through ones blend in object then face order), tilted, flat, lit
/// and Gouraud-lit, in two objects: every band height, with and without bins, gives
/// the whole frame's colours, depths and stats.
#[test]
fn bands_blend_exactly_as_the_whole_frame() {
    let a = Squares::new(&[
        ([-1.0, -1.2, 1.0, 0.8, 0.0], RED),
        (
            [-1.5, -0.2, 0.5, 1.5, 0.3],
            Translucent::new(Rgb888::new(0, 200, 255), 128),
        ),
        (
            [-0.4, -1.5, 1.4, 0.4, 0.6],
            Translucent::new(Rgb888::new(255, 255, 0), 90),
        ),
    ]);
    let b = Squares::new(&[
        (
            [-0.8, -0.8, 0.8, 0.8, 0.0],
            Translucent::new(Rgb888::GREEN, 200),
        ),
        (
            [-1.2, 0.0, 0.2, 1.2, -0.3],
            Translucent::new(Rgb888::WHITE, 255),
        ),
    ]);
    let (mut na, mut nb) = (
        vec![[0i16; 3]; a.positions.len()],
        vec![[0i16; 3]; b.positions.len()],
    );
    for (ns, s) in [(&mut na, &a), (&mut nb, &b)] {
        let mut scratch = vec![Vec3::default(); s.positions.len()];
        zraster::mesh::compute_vertex_normals(&s.mesh(), &mut scratch, ns).unwrap();
    }
    let tilt_a = Mat4::rotation_y(0.5) * Mat4::rotation_x(-0.4);
    let tilt_b = Mat4::translation(Vec3::new(0.4, -0.2, 0.2)) * Mat4::rotation_y(-0.7);
    for shading in [Shading::Flat, Shading::Lambert, Shading::Gouraud] {
        let o = RenderOptions {
            shading,
            cull: zraster::Cull::None,
            ..Default::default()
        };
        let scene = [
            (a.mesh().with_normals(None, Some(&na)), tilt_a, o),
            (b.mesh().with_normals(None, Some(&nb)), tilt_b, o),
        ];
        let want = whole(&scene);
        assert!(want.0.iter().filter(|&&c| c != Rgb565::BLACK).count() > 500);
        for rows in 1..=H {
            for binned in [false, true] {
                let got = banded(&scene, rows, binned);
                let what = format!("{shading:?} rows {rows} bins {binned}");
                assert!(got.0 == want.0, "{what}: colours differ");
                assert!(got.1 == want.1, "{what}: depths differ");
                assert_eq!(got.2, want.2, "{what}: stats differ");
            }
        }
        // One renderer, one mesh, drawn into bands alone: the same as its whole frame.
        let one = &scene[..1];
        let want = whole(one);
        for rows in [1, 5, 16] {
            let got = banded(one, rows, true);
            assert!(
                got.0 == want.0 && got.1 == want.1 && got.2 == want.2,
                "{shading:?} one mesh, rows {rows}"
            );
        }
    }
}

/// Into a display with a Z-buffer the colours cannot be read: the see-through square is
/// a screen door, half its pixels blue (each 2×2 block alike at 50 %), half left red,
/// the depths untouched, and nothing fails.
#[test]
fn a_display_gets_a_screen_door() {
    let blue = Translucent::new(Rgb888::BLUE, 128);
    let squares = Squares::new(&[
        ([-0.5, -0.5, 1.5, 1.5, 0.5], blue),
        ([-1.0, -1.0, 1.0, 1.0, 0.0], RED),
    ]);
    let want = whole(&[(squares.mesh(), Mat4::IDENTITY, flat())]);
    let (mut colour, mut depth) = (
        vec![Rgb565::BLACK; (W * H) as usize],
        vec![0; (W * H) as usize],
    );
    let mut display = ColorBuffer::new(&mut colour, W, H).unwrap();
    let mut zbuf = ZBuffer::new(&mut depth, W, H).unwrap();
    zbuf.clear();
    let mut r = Renderer::new(&squares.mesh(), &camera(), flat()).unwrap();
    r.draw(&mut WithDepth::new(&mut display, &mut zbuf))
        .unwrap();
    assert!(
        zbuf.as_slice() == &want.1[..],
        "the screen door wrote depths"
    );
    // Over the red square, in the 8 × 8 block at (28, 16): half blue, half red, with
    // the pattern's two pixels of each 2 × 2 block on a diagonal.
    let (mut blue_px, mut red_px) = (0, 0);
    for y in 16..24 {
        for x in 28..36 {
            let c = display.pixel(x, y).unwrap();
            blue_px += usize::from(c == Rgb565::BLUE);
            red_px += usize::from(c == Rgb565::RED);
        }
    }
    assert_eq!((blue_px, red_px), (32, 32));
    let d = |x, y| display.pixel(x, y).unwrap();
    assert_eq!(d(28, 16), d(29, 17));
    assert_ne!(d(28, 16), d(29, 16));
    // Outside the see-through square the display shows the frame's picture.
    assert_eq!(d(20, 30), Rgb565::RED);
    assert_eq!(d(5, 5), Rgb565::BLACK);
}

/// On a dithered display (16 greys) a see-through face is a screen door in a frame and
/// in bands alike (its colours are not mixed but ordered, as the shading is): bands of
/// every height give the whole frame's picture.
#[test]
fn dithered_types_screen_door_the_same_in_bands() {
    use embedded_graphics::pixelcolor::{Gray4, GrayColor};
    let squares = Squares::new(&[
        (
            [-1.0, -1.0, 1.0, 1.0, 0.0],
            Translucent::new(Rgb888::new(90, 90, 90), 255),
        ),
        (
            [-0.5, -0.5, 1.5, 1.5, 0.5],
            Translucent::new(Rgb888::WHITE, 100),
        ),
    ]);
    let mesh = squares.mesh();
    let (mut pixels, mut depth) = (
        vec![Gray4::BLACK; (W * H) as usize],
        vec![0; (W * H) as usize],
    );
    let mut frame = Frame::new(&mut pixels, &mut depth, W, H).unwrap();
    frame.clear(Gray4::BLACK);
    Renderer::new(&mesh, &camera(), flat())
        .unwrap()
        .draw(&mut frame)
        .unwrap();
    // Over black, white at 100/255 covers round(100 · 16 / 255) = 6 of every 16 pixels.
    let lit = (0..4)
        .flat_map(|y| (0..4).map(move |x| (52 + x, 4 + y)))
        .filter(|&(x, y)| frame.color().pixel(x, y) == Some(Gray4::WHITE))
        .count();
    assert_eq!(lit, 6);
    for rows in [1, 4, 7, 16, H] {
        let mut shown = vec![Gray4::new(3); (W * H) as usize];
        let mut display = ColorBuffer::new(&mut shown, W, H).unwrap();
        let (mut cb, mut zb) = (
            vec![Gray4::BLACK; (W * rows) as usize],
            vec![0; (W * rows) as usize],
        );
        let mut buffers = BandBuffers::new(&mut cb, &mut zb, W, rows, H, &mut []).unwrap();
        let mut r = Renderer::new(&mesh, &camera(), flat()).unwrap();
        r.draw(&mut Bands::new(&mut display, &mut buffers, Gray4::BLACK))
            .unwrap();
        assert!(shown == frame.color().as_slice(), "rows {rows}");
    }
}
