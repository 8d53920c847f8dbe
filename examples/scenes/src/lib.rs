//! The example scenes, shared by the examples (which show them) and the golden-image
//! tests (which compare them pixel for pixel with `tests/golden/`), and the bunny the
//! pipeline tests draw. An internal crate (`publish = false`), so that both use it as
//! a dependency instead of including this file.

pub mod bus;

use embedded_graphics::{
    pixelcolor::{BinaryColor, Rgb565, Rgb888},
    prelude::*,
};
use embedded_graphics_simulator::SimulatorDisplay;
use zraster::{
    camera::{Camera, Viewport},
    math::{radians, Mat4, Vec3},
    mesh::{compute_face_normals, compute_vertex_normals, Face, Mesh, CUBE},
    shade::{Light, Shading},
    ColorBuffer, Cull, DepthSort, DepthTest, RenderOptions, Renderer, WithDepth, ZBuffer,
};
use zraster_obj::{fit_scale, parse_obj, quantize};

/// The Stanford bunny (public domain; see the licence line at the top of the file).
pub const BUNNY_OBJ: &str = include_str!("../../models/bunny.obj");

/// Render into a `w × h` `Rgb565` frame with a fresh colour and depth buffer and paste
/// it into `display` at `at`.
pub fn panel<C>(
    display: &mut SimulatorDisplay<C>,
    at: Point,
    w: u32,
    h: u32,
    draw: impl FnOnce(&mut ColorBuffer<'_, C>, &mut ZBuffer<'_>),
) where
    C: PixelColor + Default,
{
    let mut pixels = vec![C::default(); (w * h) as usize];
    let mut depth = vec![0u16; (w * h) as usize];
    let mut frame = ColorBuffer::new(&mut pixels, w, h).expect("frame");
    let mut zbuf = ZBuffer::new(&mut depth, w, h).expect("zbuf");
    zbuf.clear();
    draw(&mut frame, &mut zbuf);
    frame.flush(&mut display.translated(at)).ok();
}

/// A camera looking at `target` from `eye` (+Y up) with a vertical field of view of
/// `fov` radians.
pub fn camera(eye: Vec3, target: Vec3, fov: f32, w: u32, h: u32) -> Camera {
    Camera::look_at(eye, target, Vec3::Y)
        .expect("view")
        .perspective(fov, 0.1, 20.0, Viewport::new(w, h).expect("viewport"))
        .expect("camera")
}

/// The seeds' cube, per-face colours. Left: every face drawn in table order with no
/// hidden-surface removal (wrong). Right: back faces culled (right, for a convex solid).
pub fn cube_culling() -> SimulatorDisplay<Rgb565> {
    let (w, h) = (160, 120);
    let mut display = SimulatorDisplay::new(Size::new(2 * w + 8, h));
    let xf = camera(
        Vec3::new(2.2, 1.8, 2.8),
        Vec3::new(0.5, 0.5, 0.5),
        radians(45.0),
        w,
        h,
    );
    for (i, cull) in [Cull::None, Cull::Back].into_iter().enumerate() {
        panel(
            &mut display,
            Point::new(i as i32 * (w as i32 + 8), 0),
            w,
            h,
            |frame, zbuf| {
                zbuf.set_test(DepthTest::Always);
                let opts = RenderOptions {
                    cull,
                    ..Default::default()
                };
                Renderer::new(&CUBE, &xf, opts)
                    .expect("renderer")
                    .draw(&mut WithDepth::new(frame, zbuf))
                    .ok();
            },
        );
    }
    display
}

/// Build a mesh from f32 positions (quantised) and polygon faces.
pub struct OwnedMesh {
    pub positions: Vec<[i16; 3]>,
    pub scale: f32,
    pub offset: Vec3,
    pub faces: Vec<(Vec<u16>, Rgb888)>,
}

impl OwnedMesh {
    pub fn new(points: &[[f32; 3]], faces: &[(&[u16], Rgb888)]) -> OwnedMesh {
        let q = quantize(points, true);
        OwnedMesh {
            positions: q.positions,
            scale: q.scale,
            offset: Vec3::new(q.offset[0], q.offset[1], q.offset[2]),
            faces: faces.iter().map(|(v, c)| (v.to_vec(), *c)).collect(),
        }
    }

    /// Draw with `f(mesh, model matrix)`.
    pub fn with<R>(&self, f: impl FnOnce(&Mesh<'_, Rgb888>, Mat4) -> R) -> R {
        let faces: Vec<Face<'_, Rgb888>> = self
            .faces
            .iter()
            .map(|(v, c)| Face {
                vertices: v,
                material: *c,
            })
            .collect();
        let mesh = Mesh::new(&self.positions, self.scale, &faces);
        f(&mesh, Mat4::translation(self.offset))
    }
}

const RED: Rgb888 = Rgb888::new(230, 40, 40);
const GREEN: Rgb888 = Rgb888::new(40, 200, 60);
const BLUE: Rgb888 = Rgb888::new(50, 90, 240);
const YELLOW: Rgb888 = Rgb888::new(240, 220, 40);

/// The seeds' three-way deadlock: three sticks, each lying over the next.
pub fn cyclic_sticks() -> OwnedMesh {
    let mut pts = Vec::new();
    let mut faces: Vec<(Vec<u16>, Rgb888)> = Vec::new();
    // Stick k runs from corner k (low, z = −0.3) to past corner k+1 (high, z = +0.3).
    let corners = [(-0.8f32, -0.5f32), (0.8, -0.5), (0.0, 0.85)];
    for (k, color) in [RED, GREEN, BLUE].into_iter().enumerate() {
        let (a, b) = (corners[k], corners[(k + 1) % 3]);
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len = (dx * dx + dy * dy).sqrt();
        let (ux, uy) = (dx / len, dy / len);
        let (nx, ny) = (-uy * 0.12, ux * 0.12);
        let (sx, sy) = (a.0 - ux * 0.25, a.1 - uy * 0.25);
        let (ex, ey) = (b.0 + ux * 0.25, b.1 + uy * 0.25);
        let base = pts.len() as u16;
        pts.extend_from_slice(&[
            [sx - nx, sy - ny, -0.3],
            [ex - nx, ey - ny, 0.3],
            [ex + nx, ey + ny, 0.3],
            [sx + nx, sy + ny, -0.3],
        ]);
        faces.push((vec![base, base + 1, base + 2, base + 3], color));
    }
    let faces: Vec<(&[u16], Rgb888)> = faces.iter().map(|(v, c)| (v.as_slice(), *c)).collect();
    OwnedMesh::new(&pts, &faces)
}

/// Two triangles that pass through each other.
pub fn interpenetrating() -> OwnedMesh {
    let pts = [
        [-0.9, -0.6, -0.4],
        [0.9, -0.2, 0.5],
        [-0.5, 0.8, -0.4],
        [0.9, -0.7, -0.5],
        [0.5, 0.8, -0.5],
        [-0.9, 0.0, 0.5],
    ];
    OwnedMesh::new(&pts, &[(&[0, 1, 2], RED), (&[3, 4, 5], GREEN)])
}

/// Append an axis-aligned box to `pts`/`faces`, faces counter-clockwise from outside
/// (the seeds' cube face table), in `colors` (bottom, right, front, left, back, top).
fn add_box(
    pts: &mut Vec<[f32; 3]>,
    faces: &mut Vec<(Vec<u16>, Rgb888)>,
    lo: [f32; 3],
    hi: [f32; 3],
    colors: [Rgb888; 6],
) {
    let base = pts.len() as u16;
    for c in zraster::mesh::CUBE_POSITIONS {
        let pick = |k: usize| if c[k] == 0 { lo[k] } else { hi[k] };
        pts.push([pick(0), pick(1), pick(2)]);
    }
    for (face, color) in zraster::mesh::CUBE_FACES.iter().zip(colors) {
        faces.push((face.vertices.iter().map(|v| v + base).collect(), color));
    }
}

/// A concave object: a long plate with a fin standing on its far half (a hair above
/// it, so no two faces touch and the Z-buffer has no ties to break). Seen from the
/// front, the plate's centroid is nearer than the fin's, so the painter draws the
/// plate last, over the fin that stands in front of the plate's far end.
pub fn concave_plate() -> OwnedMesh {
    let (mut pts, mut faces) = (Vec::new(), Vec::new());
    let grey = Rgb888::new(90, 90, 90);
    add_box(
        &mut pts,
        &mut faces,
        [-1.0, -0.15, -2.0],
        [1.0, 0.0, 1.0],
        [grey, BLUE, GREEN, BLUE, grey, YELLOW],
    );
    add_box(
        &mut pts,
        &mut faces,
        [-0.6, 0.01, -1.1],
        [0.6, 0.9, -0.9],
        [grey, GREEN, RED, GREEN, RED, BLUE],
    );
    let faces: Vec<(&[u16], Rgb888)> = faces.iter().map(|(v, c)| (v.as_slice(), *c)).collect();
    OwnedMesh::new(&pts, &faces)
}

/// Where the scenes of [`painter_vs_zbuffer`] are seen from: (mesh, eye, target, culling).
pub fn failure_cases() -> [(OwnedMesh, Vec3, Vec3, Cull, &'static str); 3] {
    [
        (
            cyclic_sticks(),
            Vec3::new(0.0, 0.0, 3.0),
            Vec3::default(),
            Cull::None,
            "cyclic overlap",
        ),
        (
            interpenetrating(),
            Vec3::new(0.0, 0.0, 3.0),
            Vec3::default(),
            Cull::None,
            "interpenetration",
        ),
        (
            concave_plate(),
            Vec3::new(0.3, 1.6, 3.2),
            Vec3::new(0.0, 0.0, -0.5),
            Cull::Back,
            "concave object",
        ),
    ]
}

/// Painter's algorithm (left) against the Z-buffer (right) on the seeds' three failure
/// cases, one per row: cyclic overlap, interpenetration, a concave object.
pub fn painter_vs_zbuffer() -> SimulatorDisplay<Rgb565> {
    let (w, h) = (140, 110);
    let mut display = SimulatorDisplay::new(Size::new(2 * w + 8, 3 * h + 16));
    for (row, (mesh, eye, target, cull, _)) in failure_cases().iter().enumerate() {
        let xf = camera(*eye, *target, radians(45.0), w, h);
        let y = row as i32 * (h as i32 + 8);
        mesh.with(|m, place| {
            let xf = xf.with_model(place);
            let opts = RenderOptions {
                cull: *cull,
                shading: Shading::Flat,
                light: Light::default(),
            };
            panel(&mut display, Point::new(0, y), w, h, |frame, _| {
                let mut sort = DepthSort::<64>::new();
                Renderer::new(m, &xf, opts)
                    .expect("renderer")
                    .draw_depth_sorted(frame, &mut sort)
                    .ok();
            });
            panel(
                &mut display,
                Point::new(w as i32 + 8, y),
                w,
                h,
                |frame, zbuf| {
                    Renderer::new(m, &xf, opts)
                        .expect("renderer")
                        .draw(&mut WithDepth::new(frame, zbuf))
                        .ok();
                },
            );
        });
    }
    display
}

/// The bunny, parsed and quantised, with face and vertex normals.
pub struct Bunny {
    pub positions: Vec<[i16; 3]>,
    pub indices: Vec<[u16; 3]>,
    pub scale: f32,
    pub fit: Mat4,
    pub face_normals: Vec<[i16; 3]>,
    pub vertex_normals: Vec<[i16; 3]>,
}

impl Bunny {
    pub fn load() -> Bunny {
        let obj = parse_obj(BUNNY_OBJ, |_| None).expect("bunny.obj");
        let q = quantize(&obj.positions, true);
        let indices = obj.triangle_indices();
        let mut b = Bunny {
            fit: Mat4::scaling(Vec3::new(1.0, 1.0, 1.0) * fit_scale(&obj.positions)),
            face_normals: vec![[0; 3]; indices.len()],
            vertex_normals: vec![[0; 3]; q.positions.len()],
            positions: q.positions,
            indices,
            scale: q.scale,
        };
        let mesh = Mesh::triangles(&b.positions, b.scale, &b.indices, Rgb888::WHITE);
        let mut scratch = vec![Vec3::default(); b.positions.len()];
        let (mut fnorm, mut vnorm) = (b.face_normals.clone(), b.vertex_normals.clone());
        compute_face_normals(&mesh, &mut fnorm).expect("face normals");
        compute_vertex_normals(&mesh, &mut scratch, &mut vnorm).expect("vertex normals");
        (b.face_normals, b.vertex_normals) = (fnorm, vnorm);
        b
    }

    pub fn mesh(&self, color: Rgb888) -> Mesh<'_, Rgb888> {
        Mesh::triangles(&self.positions, self.scale, &self.indices, color)
            .with_normals(Some(&self.face_normals), Some(&self.vertex_normals))
    }
}

/// The bunny, flat Lambert (left) and Gouraud (right).
pub fn bunny_shading() -> SimulatorDisplay<Rgb565> {
    let (w, h) = (240, 200);
    let bunny = Bunny::load();
    let mesh = bunny.mesh(Rgb888::new(255, 204, 153));
    let xf = camera(
        Vec3::new(0.0, 0.0, 1.5),
        Vec3::default(),
        radians(50.0),
        w,
        h,
    )
    .with_model(Mat4::rotation_y(radians(30.0)) * bunny.fit);
    let mut display = SimulatorDisplay::new(Size::new(2 * w + 8, h));
    for (i, shading) in [Shading::Lambert, Shading::Gouraud].into_iter().enumerate() {
        panel(
            &mut display,
            Point::new(i as i32 * (w as i32 + 8), 0),
            w,
            h,
            |frame, zbuf| {
                let opts = RenderOptions {
                    shading,
                    ..Default::default()
                };
                Renderer::new(&mesh, &xf, opts)
                    .expect("renderer")
                    .draw(&mut WithDepth::new(frame, zbuf))
                    .ok();
            },
        );
    }
    display
}

/// The cube in hidden-line mode (left) and wireframe (right).
pub fn cube_hidden_line() -> SimulatorDisplay<Rgb565> {
    let (w, h) = (160, 120);
    let mut display = SimulatorDisplay::new(Size::new(2 * w + 8, h));
    let xf = camera(
        Vec3::new(2.2, 1.8, 2.8),
        Vec3::new(0.5, 0.5, 0.5),
        radians(45.0),
        w,
        h,
    );
    panel(&mut display, Point::zero(), w, h, |frame, zbuf| {
        Renderer::new(&CUBE, &xf, RenderOptions::default())
            .expect("renderer")
            .draw_hidden_line(frame, zbuf, Rgb565::WHITE)
            .ok();
    });
    panel(
        &mut display,
        Point::new(w as i32 + 8, 0),
        w,
        h,
        |frame, _| {
            Renderer::new(&CUBE, &xf, RenderOptions::default())
                .expect("renderer")
                .draw_wireframe(frame, Rgb565::WHITE)
                .ok();
        },
    );
    display
}

/// A monochrome 128×64 view as on an SSD1306: the bunny, Lambert-lit, dithered.
pub fn mono_oled() -> SimulatorDisplay<BinaryColor> {
    let (w, h) = (128, 64);
    let bunny = Bunny::load();
    let mesh = bunny.mesh(Rgb888::WHITE);
    let xf = camera(
        Vec3::new(0.0, 0.0, 1.25),
        Vec3::new(0.0, -0.04, 0.0),
        radians(60.0),
        w,
        h,
    )
    .with_model(Mat4::rotation_y(radians(-40.0)) * bunny.fit);
    let mut display = SimulatorDisplay::new(Size::new(w, h));
    panel(
        &mut display,
        Point::zero(),
        w,
        h,
        |frame: &mut ColorBuffer<'_, BinaryColor>, zbuf| {
            let opts = RenderOptions {
                shading: Shading::Lambert,
                ..Default::default()
            };
            Renderer::new(&mesh, &xf, opts)
                .expect("renderer")
                .draw(&mut WithDepth::new(frame, zbuf))
                .ok();
        },
    );
    display
}
