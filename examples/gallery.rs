//! The pictures of the README: what each renderer draws, made by zraster itself.
//!
//! ```text
//! cargo run --release --example gallery [-- --out-dir DIR]   # default: docs/
//! ```
//! Writes `gallery-painter.png` (the painter's algorithm against the Z-buffer on
//! cyclic overlap and interpenetration), `gallery-lines.png` (hidden-line and
//! wireframe, on a torus), `gallery-oled.png` (1-bit Bayer dithering on a 128×64 OLED),
//! `gallery-bands.png` (a frame drawn in 16-row bands) and `bunny-spin.gif` (the bunny
//! turning, 36 frames). `tests/gallery.rs` checks that the checked-in files are what
//! this draws. It always writes files (the `window` feature changes nothing here).
//! Angles go through zraster's own `sin_cos`, not the platform's, so the pictures are
//! the same on every host.

use std::path::{Path, PathBuf};
use std::process::exit;

use embedded_graphics::{
    mono_font::{ascii::FONT_6X10, MonoTextStyle},
    pixelcolor::{BinaryColor, Rgb565, Rgb888},
    prelude::*,
    primitives::Rectangle,
    text::Text,
};
use embedded_graphics_simulator::{
    BinaryColorTheme, OutputSettings, OutputSettingsBuilder, SimulatorDisplay,
};
use zraster::{
    camera::{Transform, Viewport},
    math::{radians, sin_cos, Mat4, Vec3},
    mesh::{compute_face_normals, compute_vertex_normals, Face, Mesh},
    shade::Shading,
    BandBuffers, Bands, CachedVertex, ColorBuffer, Cull, DepthSort, Frame, RenderOptions, Renderer,
    ZBuffer,
};

const BUNNY_OBJ: &str = include_str!("models/bunny.obj");

/// Any failure: a message and exit code 1.
fn fail(what: &str, e: impl std::fmt::Display) -> ! {
    eprintln!("gallery: {what}: {e}");
    exit(1)
}

/// A camera at `eye` looking at the origin (+Y up) with a `fov`° vertical field of
/// view, over a `w`×`h` screen.
fn camera(eye: Vec3, fov: f32, w: u32, h: u32) -> Transform {
    Transform {
        model: Mat4::IDENTITY,
        view: Mat4::look_at(eye, Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)),
        projection: Mat4::perspective(radians(fov), w as f32 / h as f32, 0.5, 20.0),
        viewport: Viewport::new(w, h).unwrap_or_else(|e| fail("viewport", e)),
    }
}

/// The bunny's tables: positions around its centre, normals, and the model matrix
/// that makes its largest extent 1.
struct Bunny {
    positions: Vec<[i16; 3]>,
    scale: f32,
    indices: Vec<[u16; 3]>,
    face_normals: Vec<[i16; 3]>,
    vertex_normals: Vec<[i16; 3]>,
    fit: f32,
}

impl Bunny {
    fn load() -> Bunny {
        let obj = zraster_obj::parse_obj(BUNNY_OBJ, |_| None).unwrap_or_else(|e| fail("bunny", e));
        let q = zraster_obj::quantize(&obj.positions, true);
        let indices = obj.triangle_indices();
        let mut b = Bunny {
            face_normals: vec![[0; 3]; indices.len()],
            vertex_normals: vec![[0; 3]; q.positions.len()],
            positions: q.positions,
            scale: q.scale,
            indices,
            fit: zraster_obj::fit_scale(&obj.positions),
        };
        let mesh = Mesh::triangles(&b.positions, b.scale, &b.indices, ());
        let mut scratch = vec![Vec3::default(); b.positions.len()];
        compute_face_normals(&mesh, &mut b.face_normals).unwrap_or_else(|e| fail("normals", e));
        compute_vertex_normals(&mesh, &mut scratch, &mut b.vertex_normals)
            .unwrap_or_else(|e| fail("normals", e));
        b
    }

    fn mesh(&self, color: Rgb888) -> Mesh<'_, Rgb888> {
        Mesh::triangles(&self.positions, self.scale, &self.indices, color)
            .with_normals(Some(&self.face_normals), Some(&self.vertex_normals))
    }

    /// Fitted, turned `yaw`° about +Y.
    fn model(&self, yaw: f32) -> Mat4 {
        Mat4::rotation_y(radians(yaw)) * Mat4::scaling(Vec3::new(1.0, 1.0, 1.0) * self.fit)
    }
}

/// A mesh of polygons built from `f32` points (quantised like an OBJ file's).
struct Polygons {
    positions: Vec<[i16; 3]>,
    scale: f32,
    centre: Vec3,
    faces: Vec<(Vec<u16>, Rgb888)>,
}

impl Polygons {
    fn new(points: &[[f32; 3]], faces: Vec<(Vec<u16>, Rgb888)>) -> Polygons {
        let q = zraster_obj::quantize(points, true);
        Polygons {
            positions: q.positions,
            scale: q.scale,
            centre: Vec3::new(q.offset[0], q.offset[1], q.offset[2]),
            faces,
        }
    }

    /// Three flat bars, each lying over the next at one end and under it at the
    /// other: no drawing order of whole faces is right.
    fn cyclic_overlap() -> Polygons {
        let colors = [
            Rgb888::new(235, 70, 60),
            Rgb888::new(60, 190, 90),
            Rgb888::new(70, 110, 235),
        ];
        let (mut points, mut faces) = (Vec::new(), Vec::new());
        for (k, color) in colors.into_iter().enumerate() {
            // Bar k runs along direction 90° + 120°·k, rising in z from one end to
            // the other, and passes the centre off to one side.
            let a = radians(90.0 + 120.0 * k as f32);
            let (dy, dx) = sin_cos(a);
            let (nx, ny) = (-dy, dx);
            let off = 0.32;
            let (cx, cy) = (nx * off, ny * off);
            let (half, width) = (1.0, 0.2);
            let base = points.len() as u16;
            for (s, w) in [(-1.0f32, -1.0f32), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                points.push([
                    cx + dx * half * s + nx * width * w,
                    cy + dy * half * s + ny * width * w,
                    0.35 * s,
                ]);
            }
            faces.push((vec![base, base + 1, base + 2, base + 3], color));
        }
        Polygons::new(&points, faces)
    }

    /// A torus of 18 × 9 quads, each counter-clockwise seen from outside.
    fn torus() -> Polygons {
        let (big, small, around, tube) = (0.62f32, 0.26f32, 18u16, 9u16);
        let mut points = Vec::new();
        for i in 0..around {
            let u = radians(360.0 * f32::from(i) / f32::from(around));
            for j in 0..tube {
                let v = radians(360.0 * f32::from(j) / f32::from(tube));
                let ((su, cu), (sv, cv)) = (sin_cos(u), sin_cos(v));
                let ring = big + small * cv;
                points.push([ring * cu, small * sv, ring * su]);
            }
        }
        let at = |i: u16, j: u16| (i % around) * tube + j % tube;
        let mut faces = Vec::new();
        for i in 0..around {
            for j in 0..tube {
                let mut quad = vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                // Outward: the normal points away from the tube's centre line.
                let p = |k: usize| {
                    let q = points[usize::from(quad[k])];
                    Vec3::new(q[0], q[1], q[2])
                };
                let n = (p(1) - p(0)).cross(p(3) - p(0));
                let u = radians(360.0 * f32::from(i) / f32::from(around));
                let (su, cu) = sin_cos(u);
                let axis = Vec3::new(big * cu, 0.0, big * su);
                if n.dot(p(0) - axis) < 0.0 {
                    quad.reverse();
                }
                faces.push((quad, Rgb888::WHITE));
            }
        }
        Polygons::new(&points, faces)
    }

    /// Two triangles that pass through each other.
    fn interpenetration() -> Polygons {
        let points = [
            [-1.0, -0.7, -0.5],
            [1.0, -0.4, 0.6],
            [-0.3, 0.9, -0.5],
            [1.0, -0.8, -0.6],
            [0.4, 0.9, -0.6],
            [-1.0, 0.0, 0.6],
        ];
        let faces = vec![
            (vec![0, 1, 2], Rgb888::new(235, 170, 40)),
            (vec![3, 4, 5], Rgb888::new(60, 150, 235)),
        ];
        Polygons::new(&points, faces)
    }

    fn with<R>(&self, f: impl FnOnce(&Mesh<'_, Rgb888>, Mat4) -> R) -> R {
        let faces: Vec<Face<'_, Rgb888>> = self
            .faces
            .iter()
            .map(|(v, c)| Face {
                vertices: v,
                material: *c,
            })
            .collect();
        f(
            &Mesh::new(&self.positions, self.scale, &faces),
            Mat4::translation(self.centre),
        )
    }
}

/// A `w`×`h` frame of colour and depth, drawn by `draw` on black.
fn panel<C: PixelColor>(
    w: u32,
    h: u32,
    background: C,
    draw: impl FnOnce(&mut Frame<'_, C>),
) -> Vec<C> {
    let mut pixels = vec![background; (w * h) as usize];
    let mut depth = vec![ZBuffer::FAR; (w * h) as usize];
    let mut frame = Frame::new(&mut pixels, &mut depth, w, h).unwrap_or_else(|e| fail("frame", e));
    frame.clear(background);
    draw(&mut frame);
    pixels
}

/// Copy `pixels` (`w` wide) into `display` at `at`, with `label` in its top-left corner.
fn place(
    display: &mut SimulatorDisplay<Rgb565>,
    pixels: &[Rgb565],
    w: u32,
    at: Point,
    label: &str,
) {
    let h = pixels.len() as u32 / w;
    display
        .fill_contiguous(&Rectangle::new(at, Size::new(w, h)), pixels.iter().copied())
        .ok();
    let style = MonoTextStyle::new(&FONT_6X10, Rgb565::new(28, 56, 28));
    Text::new(label, at + Point::new(4, 10), style)
        .draw(display)
        .ok();
}

fn options(cull: Cull, shading: Shading) -> RenderOptions {
    RenderOptions {
        cull,
        shading,
        ..RenderOptions::default()
    }
}

fn save<C>(display: &SimulatorDisplay<C>, settings: &OutputSettings, path: &Path)
where
    C: PixelColor + Into<Rgb888>,
{
    display
        .to_rgb_output_image(settings)
        .save_png(path)
        .unwrap_or_else(|e| fail(&path.display().to_string(), e));
    println!("wrote {}", path.display());
}

fn scaled(scale: u32) -> OutputSettings {
    OutputSettingsBuilder::new().scale(scale).build()
}

/// Painter's algorithm (left) and Z-buffer (right), cyclic overlap and
/// interpenetration (rows).
fn painter_vs_zbuffer(dir: &Path) {
    let (w, h) = (160, 120);
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(2 * w + 1, 2 * h + 1));
    display.clear(Rgb565::new(8, 16, 8)).ok();
    let scenes = [
        (Polygons::cyclic_overlap(), "cyclic overlap"),
        (Polygons::interpenetration(), "interpenetration"),
    ];
    for (row, (scene, name)) in scenes.iter().enumerate() {
        let xf = camera(Vec3::new(0.0, 0.0, 3.2), 50.0, w, h);
        let opts = options(Cull::None, Shading::Flat);
        let painter = panel(w, h, Rgb565::BLACK, |frame| {
            scene.with(|mesh, model| {
                let mut r = Renderer::new(mesh, &xf.with_model(model), opts)
                    .unwrap_or_else(|e| fail(name, e));
                let mut sort = DepthSort::<16>::new();
                r.draw_depth_sorted(frame.color_mut(), &mut sort)
                    .unwrap_or_else(|e| fail(name, format!("{e:?}")));
            })
        });
        let zbuffer = panel(w, h, Rgb565::BLACK, |frame| {
            scene.with(|mesh, model| {
                let mut r = Renderer::new(mesh, &xf.with_model(model), opts)
                    .unwrap_or_else(|e| fail(name, e));
                r.draw(frame)
                    .unwrap_or_else(|e| fail(name, format!("{e:?}")));
            })
        });
        let y = row as i32 * (h as i32 + 1);
        place(
            &mut display,
            &painter,
            w,
            Point::new(0, y),
            &format!("painter: {name}"),
        );
        place(
            &mut display,
            &zbuffer,
            w,
            Point::new(w as i32 + 1, y),
            "Z-buffer",
        );
    }
    save(&display, &scaled(2), &dir.join("gallery-painter.png"));
}

/// A torus with hidden lines removed (left) and as a wireframe (right).
fn lines(dir: &Path) {
    let (w, h) = (200, 150);
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(2 * w + 1, h));
    display.clear(Rgb565::new(8, 16, 8)).ok();
    let torus = Polygons::torus();
    let xf = camera(Vec3::new(0.0, 0.0, 2.6), 45.0, w, h);
    let tilt = Mat4::rotation_x(radians(55.0)) * Mat4::rotation_y(radians(20.0));
    let ink = Rgb565::new(20, 50, 31);
    let hidden = panel(w, h, Rgb565::BLACK, |frame| {
        torus.with(|mesh, model| {
            let mut r = Renderer::new(
                mesh,
                &xf.with_model(tilt * model),
                options(Cull::Back, Shading::Flat),
            )
            .unwrap_or_else(|e| fail("hidden-line", e));
            let (color, depth) = frame.parts_mut();
            r.draw_hidden_line(color, depth, ink)
                .unwrap_or_else(|e| fail("hidden-line", format!("{e:?}")));
        })
    });
    let wire = panel(w, h, Rgb565::BLACK, |frame| {
        torus.with(|mesh, model| {
            let mut r = Renderer::new(
                mesh,
                &xf.with_model(tilt * model),
                options(Cull::None, Shading::Flat),
            )
            .unwrap_or_else(|e| fail("wireframe", e));
            r.draw_wireframe(frame.color_mut(), ink)
                .unwrap_or_else(|e| fail("wireframe", format!("{e:?}")));
        })
    });
    place(&mut display, &hidden, w, Point::zero(), "hidden-line");
    place(
        &mut display,
        &wire,
        w,
        Point::new(w as i32 + 1, 0),
        "wireframe",
    );
    save(&display, &scaled(2), &dir.join("gallery-lines.png"));
}

/// The bunny on a 128×64 1-bit OLED: Lambert shading as Bayer dithering.
fn oled(dir: &Path, bunny: &Bunny) {
    let (w, h) = (128, 64);
    let mesh = bunny.mesh(Rgb888::WHITE);
    let xf = camera(Vec3::new(0.0, 0.0, 1.75), 45.0, w, h).with_model(bunny.model(-30.0));
    let pixels = panel(w, h, BinaryColor::Off, |frame| {
        let mut r = Renderer::new(&mesh, &xf, options(Cull::Back, Shading::Gouraud))
            .unwrap_or_else(|e| fail("oled", e));
        r.draw(frame)
            .unwrap_or_else(|e| fail("oled", format!("{e:?}")));
    });
    let mut display = SimulatorDisplay::<BinaryColor>::new(Size::new(w, h));
    display
        .fill_contiguous(&display.bounding_box(), pixels)
        .ok();
    let settings = OutputSettingsBuilder::new()
        .scale(3)
        .pixel_spacing(1)
        .theme(BinaryColorTheme::OledBlue)
        .build();
    save(&display, &settings, &dir.join("gallery-oled.png"));
}

/// The bunny drawn through 16-row bands (one band of colour and depth in RAM at a
/// time); every other band's background is tinted to show them.
fn bands(dir: &Path, bunny: &Bunny) {
    let (w, h, rows) = (320u32, 240u32, 16u32);
    let mesh = bunny.mesh(Rgb888::new(255, 205, 150));
    let xf = camera(Vec3::new(0.0, 0.0, 1.6), 60.0, w, h).with_model(bunny.model(30.0));
    let mut band_color = vec![Rgb565::BLACK; (w * rows) as usize];
    let mut band_depth = vec![ZBuffer::FAR; (w * rows) as usize];
    let mut bins = vec![0u16; BandBuffers::<Rgb565>::bins_needed(bunny.indices.len(), h, rows)];
    let mut buffers = BandBuffers::new(&mut band_color, &mut band_depth, w, rows, h, &mut bins)
        .unwrap_or_else(|e| fail("bands", e));
    let mut cache = vec![CachedVertex::EMPTY; bunny.positions.len()];
    let mut frame = vec![Rgb565::BLACK; (w * h) as usize];
    let mut screen = ColorBuffer::new(&mut frame, w, h).unwrap_or_else(|e| fail("bands", e));
    let tint = Rgb565::new(3, 7, 5);
    let mut renderer = Renderer::with_cache(
        &mesh,
        &xf,
        options(Cull::Back, Shading::Lambert),
        &mut cache,
    )
    .unwrap_or_else(|e| fail("bands", e));
    let target =
        &mut Bands::new(&mut screen, &mut buffers, Rgb565::BLACK).after_band(|band, depth| {
            let top = band.first_row();
            if (top / rows as i32) % 2 == 1 {
                let empty = (top..top + band.rows() as i32)
                    .flat_map(|y| (0..w as i32).map(move |x| Point::new(x, y)))
                    .filter(|p| depth.depth(p.x, p.y) == Some(ZBuffer::FAR))
                    .map(|p| Pixel(p, tint));
                band.draw_iter(empty).ok();
            }
        });
    renderer
        .draw(target)
        .unwrap_or_else(|e| fail("bands", format!("{e:?}")));
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(w, h));
    place(
        &mut display,
        &frame,
        w,
        Point::zero(),
        &format!(
            "{rows}-row bands: {} KiB of RAM, not {}",
            rows * w * 4 / 1024,
            h * w * 4 / 1024
        ),
    );
    save(&display, &scaled(1), &dir.join("gallery-bands.png"));
}

/// The bunny turning 10° a frame: 36 frames of 160×120, Gouraud shaded, as an
/// endlessly looping GIF. Each frame after the first stores only the rectangle that
/// changed.
fn spinning_gif(dir: &Path, bunny: &Bunny) {
    let (w, h) = (160u32, 120u32);
    let mesh = bunny.mesh(Rgb888::new(255, 200, 140));
    let frames: Vec<Vec<Rgb565>> = (0..36)
        .map(|k| {
            let xf = camera(Vec3::new(0.0, 0.1, 1.45), 50.0, w, h)
                .with_model(bunny.model(10.0 * k as f32));
            panel(w, h, Rgb565::BLACK, |frame| {
                let mut r = Renderer::new(&mesh, &xf, options(Cull::Back, Shading::Gouraud))
                    .unwrap_or_else(|e| fail("gif", e));
                r.draw(frame)
                    .unwrap_or_else(|e| fail("gif", format!("{e:?}")));
            })
        })
        .collect();
    // One palette for all frames: every colour drawn (Kd × I in RGB565 are few).
    let mut palette: Vec<Rgb565> = frames.iter().flatten().copied().collect();
    palette.sort_by_key(|c| c.into_storage());
    palette.dedup();
    if palette.len() > 256 {
        fail("gif", format!("{} colours, more than 256", palette.len()));
    }
    let rgb: Vec<u8> = palette
        .iter()
        .flat_map(|&c| {
            let c: Rgb888 = c.into();
            [c.r(), c.g(), c.b()]
        })
        .collect();
    let index = |c: &Rgb565| {
        palette
            .binary_search_by_key(&c.into_storage(), |p| p.into_storage())
            .unwrap_or(0) as u8
    };
    let path = dir.join("bunny-spin.gif");
    let file = std::fs::File::create(&path).unwrap_or_else(|e| fail("bunny-spin.gif", e));
    let mut gif = gif::Encoder::new(std::io::BufWriter::new(file), w as u16, h as u16, &rgb)
        .unwrap_or_else(|e| fail("bunny-spin.gif", e));
    gif.set_repeat(gif::Repeat::Infinite)
        .unwrap_or_else(|e| fail("bunny-spin.gif", e));
    for (k, pixels) in frames.iter().enumerate() {
        // The rectangle that differs from the frame before (all of the first).
        let (mut x0, mut y0, mut x1, mut y1) = (0, 0, w, h);
        if k > 0 {
            let prev = &frames[k - 1];
            let changed = |x: u32, y: u32| {
                let i = (y * w + x) as usize;
                pixels[i] != prev[i]
            };
            let rows: Vec<u32> = (0..h).filter(|&y| (0..w).any(|x| changed(x, y))).collect();
            let cols: Vec<u32> = (0..w).filter(|&x| (0..h).any(|y| changed(x, y))).collect();
            match (rows.first(), rows.last(), cols.first(), cols.last()) {
                (Some(&a), Some(&b), Some(&c), Some(&d)) => (y0, y1, x0, x1) = (a, b + 1, c, d + 1),
                _ => (x0, y0, x1, y1) = (0, 0, 1, 1),
            }
        }
        let indices: Vec<u8> = (y0..y1)
            .flat_map(|y| (x0..x1).map(move |x| (y * w + x) as usize))
            .map(|i| index(&pixels[i]))
            .collect();
        let mut frame =
            gif::Frame::from_indexed_pixels((x1 - x0) as u16, (y1 - y0) as u16, indices, None);
        (frame.left, frame.top, frame.delay) = (x0 as u16, y0 as u16, 6);
        frame.dispose = gif::DisposalMethod::Keep;
        gif.write_frame(&frame)
            .unwrap_or_else(|e| fail("bunny-spin.gif", e));
    }
    let mut out = gif
        .into_inner()
        .unwrap_or_else(|e| fail("bunny-spin.gif", e));
    std::io::Write::flush(&mut out).unwrap_or_else(|e| fail("bunny-spin.gif", e));
    println!("wrote {}", path.display());
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let dir = match args.as_slice() {
        [] => Path::new(env!("CARGO_MANIFEST_DIR")).join("docs"),
        [flag, d] if flag == "--out-dir" => PathBuf::from(d),
        _ => {
            eprintln!("usage: gallery [--out-dir DIR]");
            exit(2)
        }
    };
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| fail(&dir.display().to_string(), e));
    let bunny = Bunny::load();
    painter_vs_zbuffer(&dir);
    lines(&dir);
    oled(&dir, &bunny);
    bands(&dir, &bunny);
    spinning_gif(&dir, &bunny);
}
