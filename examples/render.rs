//! Render an OBJ model to a PNG: the command-line contract that outside checks drive.
//!
//! ```text
//! cargo run --release --example render -- MODEL.obj [options]
//! ```
//! See `USAGE` below (or run with `--help`). Exit codes: 0 success, 2 bad options or
//! bad input (with a message naming the problem, and the line for OBJ errors), 1 when
//! an output file cannot be written.
//!
//! Coordinates may be any finite `f32`, up to ±3.4·10³⁸ (a NaN or infinite one, or one
//! beyond that range, is bad input: exit 2, naming the line). Material libraries
//! (`mtllib`) are read with [`MtlLoader`]: regular files only, of at most
//! [`zraster_obj::MAX_MTL_BYTES`] (16 MiB), each file once; one that cannot be read is
//! a warning on stderr, and faces whose `usemtl` it would have defined take `--color`.

use std::io::Write;
use std::path::Path;
use std::process::exit;
use std::time::{Duration, Instant};

use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
use embedded_graphics_simulator::{OutputSettings, SimulatorDisplay};
use zraster::{
    camera::{Camera, Viewport},
    damage::Damage,
    math::{radians, Mat4, Vec3},
    mesh::{compute_face_normals, compute_vertex_normals, Faces, Materials, Mesh},
    shade::{Intensity, Light, Material, Shading, ONE},
    BandBuffers, Bands, CachedVertex, ColorBuffer, Cull, DepthSort, DrawError, Frame, FrameStats,
    RenderOptions, Renderer, ZBuffer,
};
use zraster_obj::{fit_scale_f64, parse_obj_with, quantize, MtlLoader};
use zraster_scenes::bus::SpiDisplay;

const USAGE: &str = "\
usage: render MODEL.obj [options]
  --size WxH          output size in pixels (default 320x240)
  --out FILE.png      colour output, exactly W x H pixels (default render.png)
  --depth-out FILE    the Z-buffer as binary PGM (P5, maxval 65535, big-endian)
  --no-fit            keep raw coordinates (default: centre the bounding box, largest extent 1)
  --yaw DEG           rotation about +Y, applied first (default 0)
  --pitch DEG         rotation about +X, applied second (default 0)
  --distance D        camera at (0, 0, D) looking toward -Z (default 2.5)
  --fov DEG           vertical field of view (default 60)
  --near N --far F    clip planes (default 0.1, 10)
  --cull back|front|none                        (default back)
  --mode zbuffer|painter|hidden-line|wireframe  (default zbuffer)
  --shade none|lambert|gouraud                  (default lambert)
  --color R,G,B       colour of faces without a material, 0..1 (default 1,1,1)
  --frames N          render N frames, write the last (default 1); prints
                      'frames N: X ms/frame, Y fps' to stdout (to stderr with
                      --stats, whose JSON line stays stdout's only line), and
                      'render: frame K/N' to stderr each second after the first
  --spin DEG          yaw added per frame (default 0)
  --band ROWS         render in bands of ROWS rows (output identical)
  --stats             print the last frame's stats as one JSON line
  --damage            send each frame to a model ST7789 display through damage
                      tracking (only the changed spans); --stats adds
                      damage_pixels and bus_bytes of the last frame
  --depth-fit         near and far from the model's bounds each frame (--near
                      stays the lowest near allowed, --far is ignored)
Material libraries (mtllib) are read from MODEL.obj's folder: regular files only,
of at most 16 MiB, each once. One that cannot be read is a warning, and faces whose
material it would have defined take --color.";

/// Everything the command line says.
struct Options {
    model: String,
    width: u32,
    height: u32,
    out: String,
    depth_out: Option<String>,
    fit: bool,
    yaw: f32,
    pitch: f32,
    distance: f32,
    fov: f32,
    near: f32,
    far: f32,
    cull: Cull,
    mode: Mode,
    shade: Shade,
    color: [f32; 3],
    frames: u32,
    /// `--frames` was given: print the frame time.
    timed: bool,
    spin: f32,
    band: Option<u32>,
    stats: bool,
    damage: bool,
    depth_fit: bool,
}

#[derive(Clone, Copy, PartialEq)]
enum Mode {
    ZBuffer,
    Painter,
    HiddenLine,
    Wireframe,
}

#[derive(Clone, Copy, PartialEq)]
enum Shade {
    None,
    Lambert,
    Gouraud,
}

fn usage_error(msg: &str) -> ! {
    eprintln!("render: {msg}\n{USAGE}");
    exit(2)
}

fn input_error(msg: &str) -> ! {
    eprintln!("render: {msg}");
    exit(2)
}

fn parse_f32(name: &str, v: &str) -> f32 {
    match v.parse::<f32>() {
        Ok(x) if x.is_finite() => x,
        _ => usage_error(&format!("{name} needs a finite number, got {v:?}")),
    }
}

fn parse_args(args: &[String]) -> Options {
    let mut o = Options {
        model: String::new(),
        width: 320,
        height: 240,
        out: "render.png".into(),
        depth_out: None,
        fit: true,
        yaw: 0.0,
        pitch: 0.0,
        distance: 2.5,
        fov: 60.0,
        near: 0.1,
        far: 10.0,
        cull: Cull::Back,
        mode: Mode::ZBuffer,
        shade: Shade::Lambert,
        color: [1.0; 3],
        frames: 1,
        timed: false,
        spin: 0.0,
        band: None,
        stats: false,
        damage: false,
        depth_fit: false,
    };
    let mut model = None;
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = |name: &str| -> String {
            it.next()
                .cloned()
                .unwrap_or_else(|| usage_error(&format!("{name} needs a value")))
        };
        match a.as_str() {
            "-h" | "--help" => {
                println!("{USAGE}");
                exit(0)
            }
            "--size" => {
                let v = value(a);
                let parsed = v
                    .split_once(['x', 'X'])
                    .and_then(|(w, h)| Some((w.parse::<u32>().ok()?, h.parse::<u32>().ok()?)));
                match parsed {
                    Some((w, h))
                        if w > 0
                            && h > 0
                            && w <= zraster::MAX_DIMENSION
                            && h <= zraster::MAX_DIMENSION =>
                    {
                        (o.width, o.height) = (w, h)
                    }
                    Some(_) => usage_error(&format!(
                        "--size {v}: width and height must be 1..={}",
                        zraster::MAX_DIMENSION
                    )),
                    None => usage_error(&format!("--size needs WxH, got {v:?}")),
                }
            }
            "--out" => o.out = value(a),
            "--depth-out" => o.depth_out = Some(value(a)),
            "--no-fit" => o.fit = false,
            "--yaw" => o.yaw = parse_f32(a, &value(a)),
            "--pitch" => o.pitch = parse_f32(a, &value(a)),
            "--distance" => o.distance = parse_f32(a, &value(a)),
            "--fov" => o.fov = parse_f32(a, &value(a)),
            "--near" => o.near = parse_f32(a, &value(a)),
            "--far" => o.far = parse_f32(a, &value(a)),
            "--spin" => o.spin = parse_f32(a, &value(a)),
            "--cull" => {
                o.cull = match value(a).as_str() {
                    "back" => Cull::Back,
                    "front" => Cull::Front,
                    "none" => Cull::None,
                    v => usage_error(&format!("--cull must be back, front or none, got {v:?}")),
                }
            }
            "--mode" => {
                o.mode = match value(a).as_str() {
                    "zbuffer" => Mode::ZBuffer,
                    "painter" => Mode::Painter,
                    "hidden-line" => Mode::HiddenLine,
                    "wireframe" => Mode::Wireframe,
                    v => usage_error(&format!("unknown --mode {v:?}")),
                }
            }
            "--shade" => {
                o.shade = match value(a).as_str() {
                    "none" => Shade::None,
                    "lambert" => Shade::Lambert,
                    "gouraud" => Shade::Gouraud,
                    v => usage_error(&format!(
                        "--shade must be none, lambert or gouraud, got {v:?}"
                    )),
                }
            }
            "--color" => {
                let v = value(a);
                let parts: Vec<f32> = v
                    .split(',')
                    .filter_map(|p| p.trim().parse::<f32>().ok())
                    .collect();
                match parts.as_slice() {
                    [r, g, b] if [r, g, b].iter().all(|c| (0.0..=1.0).contains(*c)) => {
                        o.color = [*r, *g, *b]
                    }
                    _ => usage_error(&format!("--color needs R,G,B in 0..1, got {v:?}")),
                }
            }
            "--frames" => {
                let v = value(a);
                o.frames = match v.parse::<u32>() {
                    Ok(n) if n >= 1 => n,
                    _ => usage_error(&format!("--frames needs a whole number ≥ 1, got {v:?}")),
                };
                o.timed = true;
            }
            "--band" => {
                let v = value(a);
                o.band = match v.parse::<u32>() {
                    Ok(n) if (1..=zraster::MAX_DIMENSION).contains(&n) => Some(n),
                    _ => usage_error(&format!("--band needs a row count ≥ 1, got {v:?}")),
                }
            }
            "--stats" => o.stats = true,
            "--damage" => o.damage = true,
            "--depth-fit" => o.depth_fit = true,
            s if s.starts_with('-') && s.len() > 1 => usage_error(&format!("unknown option {s}")),
            s => {
                if model.replace(s.to_string()).is_some() {
                    usage_error("only one MODEL.obj may be given")
                }
            }
        }
    }
    o.model = model.unwrap_or_else(|| usage_error("no MODEL.obj given"));
    if !(o.near > 0.0 && o.far > o.near) {
        usage_error("need 0 < --near < --far");
    }
    if !(o.fov > 0.0 && o.fov < 180.0) {
        usage_error("--fov must be between 0 and 180 degrees");
    }
    o.band = o.band.map(|b| b.min(o.height));
    o
}

/// One drawing of `frame` (the whole frame, or one band of it) in `mode`.
fn draw_pass(
    renderer: &mut Renderer<'_, '_, Kd>,
    mode: Mode,
    sort: Option<&mut DepthSort<65536>>,
    frame: &mut Frame<'_, Rgb565>,
    line_color: Rgb565,
) -> Result<(), DrawError<core::convert::Infallible>> {
    match mode {
        Mode::ZBuffer => renderer.draw(frame),
        Mode::Painter => match sort {
            Some(s) => renderer.draw_depth_sorted(frame.color_mut(), s),
            None => Ok(()),
        },
        Mode::HiddenLine => {
            let (color, depth) = frame.parts_mut();
            renderer.draw_hidden_line(color, depth, line_color)
        }
        Mode::Wireframe => renderer.draw_wireframe(frame.color_mut(), line_color),
    }
}

/// A face colour as the contract states it: `Kd × I`, rounded to RGB565 exactly.
#[derive(Clone, Copy)]
struct Kd([f32; 3]);

impl Material<Rgb565> for Kd {
    fn shade(&self, i: Intensity, _x: i32, _y: i32) -> Rgb565 {
        let i = f32::from(i) / f32::from(ONE);
        let q = |c: f32, max: f32| ((c * i * max + 0.5) as u32).min(max as u32) as u8;
        Rgb565::new(q(self.0[0], 31.0), q(self.0[1], 63.0), q(self.0[2], 31.0))
    }
}

fn write_pgm(path: &str, w: u32, h: u32, depth: &[u16]) -> std::io::Result<()> {
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    write!(f, "P5\n{w} {h}\n65535\n")?;
    for d in depth {
        f.write_all(&d.to_be_bytes())?;
    }
    f.flush()
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let o = parse_args(&args);

    // ---- The model.
    let bytes =
        std::fs::read(&o.model).unwrap_or_else(|e| input_error(&format!("{}: {e}", o.model)));
    let text = String::from_utf8(bytes)
        .unwrap_or_else(|_| input_error(&format!("{}: not a text file", o.model)));
    let dir = Path::new(&o.model)
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let mut libraries = MtlLoader::new(&dir);
    let obj = parse_obj_with(&text, |name| libraries.load(name))
        .unwrap_or_else(|e| input_error(&format!("{}: {e}", o.model)));
    for w in &obj.warnings {
        eprintln!("render: warning: {}: {w}", o.model);
    }
    if obj.triangles.is_empty() {
        input_error(&format!("{}: no faces", o.model));
    }
    let q = quantize(&obj.positions, true);
    // The mesh's position scale is q.scale times 2^-k, and the model matrix takes 2^k
    // back. k is 0 unless the model reaches beyond 2^±16: then its normals' cross and
    // dot products (the fourth power of its size) would overflow or vanish in f32, and
    // a fit below f32's normal range would lose precision. k then brings the positions
    // to about ±2^8. A power of two scales f32 arithmetic exactly, so the image is
    // exactly that of the model scaled by 2^-k (drawn with k = 0).
    let k = balance_exponent(q.scale);
    let mesh_scale = (f64::from(q.scale) * pow2(-k)) as f32;
    let indices = obj.triangle_indices();
    let materials: Vec<Kd> = obj
        .triangles
        .iter()
        .map(|t| Kd(t.material.map_or(o.color, |m| obj.materials[m].kd)))
        .collect();
    let mut mesh = Mesh {
        positions: &q.positions,
        scale: mesh_scale,
        faces: Faces::Triangles {
            indices: &indices,
            materials: Materials::PerFace(&materials),
        },
        face_normals: None,
        vertex_normals: None,
    };
    let mut face_normals = vec![[0i16; 3]; indices.len()];
    let mut vertex_normals = vec![[0i16; 3]; q.positions.len()];
    let mut scratch = vec![Vec3::default(); q.positions.len()];
    compute_face_normals(&mesh, &mut face_normals)
        .unwrap_or_else(|e| input_error(&format!("{}: {e}", o.model)));
    if o.shade == Shade::Gouraud {
        compute_vertex_normals(&mesh, &mut scratch, &mut vertex_normals)
            .unwrap_or_else(|e| input_error(&format!("{}: {e}", o.model)));
    }
    mesh = mesh.with_normals(Some(&face_normals), Some(&vertex_normals));

    // Model space → fitted: centre the bounding box, largest extent 1 (positions are
    // already stored around the bounding-box centre, q.offset).
    let place = if o.fit {
        let fit = (fit_scale_f64(&obj.positions) * pow2(k)) as f32;
        Mat4::scaling(Vec3::new(1.0, 1.0, 1.0) * fit)
    } else {
        let at = Mat4::translation(Vec3::new(q.offset[0], q.offset[1], q.offset[2]));
        if k == 0 {
            at
        } else {
            at * Mat4::scaling(Vec3::new(1.0, 1.0, 1.0) * pow2(k) as f32)
        }
    };

    // ---- The frame.
    let (w, h) = (o.width, o.height);
    let viewport = Viewport::new(w, h).unwrap_or_else(|e| usage_error(&format!("--size: {e}")));
    // --fov is in degrees (the option's meaning); zraster's angles are radians.
    if !(o.fov > 0.0 && o.fov < 180.0) {
        usage_error(&format!(
            "camera: --fov needs 0 < degrees < 180, got {}",
            o.fov
        ));
    }
    let camera = Camera::look_at(
        Vec3::new(0.0, 0.0, o.distance),
        Vec3::new(0.0, 0.0, o.distance - 1.0),
        Vec3::Y,
    )
    .and_then(|eye| eye.perspective(radians(o.fov), o.near, o.far, viewport))
    .unwrap_or_else(|e| usage_error(&format!("camera: {e}")));
    let options = RenderOptions {
        cull: o.cull,
        shading: match o.shade {
            Shade::None => Shading::Flat,
            Shade::Lambert => Shading::Lambert,
            Shade::Gouraud => Shading::Gouraud,
        },
        light: Light::default(),
    };
    let rows = o.band.unwrap_or(h);
    let line_color = Kd(o.color).shade(ONE, 0, 0);
    let mut frame_pixels = vec![Rgb565::BLACK; (w * h) as usize];
    let mut depth_full = vec![u16::MAX; (w * h) as usize];
    let band_len = if o.band.is_some() {
        (w * rows) as usize
    } else {
        0
    };
    let mut band_pixels = vec![Rgb565::BLACK; band_len];
    let mut band_depth = vec![u16::MAX; band_len];
    let bins_len = match o.band {
        Some(_) => BandBuffers::<Rgb565>::bins_needed(indices.len(), h, rows),
        None => 0,
    };
    let mut bins = vec![0u16; bins_len];
    let mut cache = vec![CachedVertex::EMPTY; q.positions.len()];
    let mut sort: Option<Box<DepthSort<65536>>> = None;
    if o.mode == Mode::Painter {
        if indices.len() > 65536 {
            input_error(&format!(
                "{}: painter mode handles at most 65536 faces",
                o.model
            ));
        }
        sort = Some(Box::default());
    }
    let mut stats = FrameStats::default();
    // --depth-fit: the model's box, for near and far each frame.
    let bounds = mesh.bounds();
    // --damage: a display model behind a damage tracker (the display starts black).
    let mut shown = SpiDisplay::new(w, h, Rgb565::BLACK);
    let (mut last_spans, mut damage_row) = (
        vec![(0u16, 0u16); h as usize],
        vec![Rgb565::BLACK; w as usize],
    );
    let mut damage = Damage::new(&mut last_spans, &mut damage_row, Rgb565::BLACK)
        .unwrap_or_else(|e| input_error(&e.to_string()));
    let mut sent = 0u64;
    let start = Instant::now();
    let mut progress = Progress::new(start, o.frames);
    for frame in 0..o.frames {
        progress.tick(frame);
        let yaw = o.yaw + o.spin * frame as f32;
        let model = Mat4::rotation_x(radians(o.pitch)) * Mat4::rotation_y(radians(yaw)) * place;
        let mut xf = camera.with_model(model);
        if o.depth_fit {
            if let Some((lo, hi)) = bounds {
                xf = xf
                    .fit_depth(lo, hi, o.near)
                    .unwrap_or_else(|e| input_error(&format!("--depth-fit: {e}")));
            }
        }
        if o.damage && frame > 0 {
            // The previous frame goes to the display (the last one after the loop).
            let prev = ColorBuffer::new(&mut frame_pixels, w, h)
                .unwrap_or_else(|e| input_error(&e.to_string()));
            shown.bytes = 0;
            prev.flush(&mut damage.target(&mut shown)).ok();
        }
        let mut renderer = Renderer::with_cache(&mesh, &xf, options, &mut cache)
            .unwrap_or_else(|e| input_error(&format!("transform: {e}")));
        if o.band.is_none() {
            // The whole frame at once, straight into the frame buffer.
            let mut whole = Frame::new(&mut frame_pixels, &mut depth_full, w, h)
                .unwrap_or_else(|e| input_error(&e.to_string()));
            whole.clear(Rgb565::BLACK);
            let result = draw_pass(
                &mut renderer,
                o.mode,
                sort.as_deref_mut(),
                &mut whole,
                line_color,
            );
            if let Err(e) = result {
                input_error(&format!("{}: {e}", o.model));
            }
            stats = renderer.stats();
            continue;
        }
        let mut full = ColorBuffer::new(&mut frame_pixels, w, h)
            .unwrap_or_else(|e| input_error(&e.to_string()));
        if o.mode == Mode::ZBuffer {
            // Band by band, triangles binned once per frame.
            let mut bands =
                BandBuffers::new(&mut band_pixels, &mut band_depth, w, rows, h, &mut bins)
                    .unwrap_or_else(|e| input_error(&e.to_string()));
            let keep_depth = o.depth_out.is_some();
            let mut target =
                Bands::new(&mut full, &mut bands, Rgb565::BLACK).after_band(|_, zbuf| {
                    // The Z-buffer as a whole frame, for --depth-out.
                    if keep_depth {
                        let start = (zbuf.first_row() as u32 * w) as usize;
                        let band = zbuf.as_slice();
                        depth_full[start..start + band.len()].copy_from_slice(band);
                    }
                });
            let result = renderer.draw(&mut target);
            if let Err(e) = result {
                input_error(&format!("{}: {e:?}", o.model));
            }
            // Same picture without bins, only slower: say so once.
            if let (0, zraster::Binning::Off(why)) = (frame, renderer.binning()) {
                eprintln!("warning: bands drawn without binning ({why})");
            }
            stats = renderer.stats();
            continue;
        }
        let mut y = 0;
        while y < h {
            let n = rows.min(h - y);
            let color = ColorBuffer::new_band(&mut band_pixels, w, n, y as i32)
                .unwrap_or_else(|e| input_error(&e.to_string()));
            let zbuf = ZBuffer::new_band(&mut band_depth, w, n, y as i32)
                .unwrap_or_else(|e| input_error(&e.to_string()));
            let mut band = Frame::from_buffers(color, zbuf);
            band.clear(Rgb565::BLACK);
            let result = draw_pass(
                &mut renderer,
                o.mode,
                sort.as_deref_mut(),
                &mut band,
                line_color,
            );
            if let Err(e) = result {
                input_error(&format!("{}: {e}", o.model));
            }
            band.flush(&mut full).ok();
            let start = (y * w) as usize;
            depth_full[start..start + (n * w) as usize].copy_from_slice(band.depth().as_slice());
            y += n;
        }
        stats = renderer.stats();
    }

    let elapsed = start.elapsed();

    // ---- Output.
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(w, h));
    let full =
        ColorBuffer::new(&mut frame_pixels, w, h).unwrap_or_else(|e| input_error(&e.to_string()));
    if o.damage {
        // The last frame through the tracker; the picture written is the display's,
        // which must be the frame itself.
        shown.bytes = 0;
        full.flush(&mut damage.target(&mut shown)).ok();
        sent = damage.sent();
        if shown.pixels != full.as_slice() || shown.outside != 0 {
            eprintln!("render: the display after damage tracking differs from the frame");
            exit(1);
        }
    }
    full.flush(&mut display).ok();
    if let Err(e) = display
        .to_rgb_output_image(&OutputSettings::default())
        .save_png(&o.out)
    {
        eprintln!("render: cannot write {}: {e}", o.out);
        exit(1);
    }
    if let Some(path) = &o.depth_out {
        if let Err(e) = write_pgm(path, w, h, &depth_full) {
            eprintln!("render: cannot write {path}: {e}");
            exit(1);
        }
    }
    if o.timed {
        let line = frame_time_line(o.frames, elapsed);
        if o.stats {
            eprintln!("render: {line}");
        } else {
            println!("{line}");
        }
    }
    if o.stats {
        let damage = if o.damage {
            format!(",\"damage_pixels\":{sent},\"bus_bytes\":{}", shown.bytes)
        } else {
            String::new()
        };
        println!(
            "{{\"triangles_in\":{},\"culled\":{},\"outside\":{},\"clipped\":{},\"drawn\":{},\"pixels_tested\":{},\"pixels_written\":{},\"runs\":{}{damage}}}",
            stats.triangles_in,
            stats.culled,
            stats.outside,
            stats.clipped,
            stats.drawn,
            stats.pixels_tested,
            stats.pixels_written,
            stats.runs
        );
    }
}

/// `frames N: X ms/frame, Y fps` for N frames drawn in `elapsed`.
fn frame_time_line(frames: u32, elapsed: Duration) -> String {
    let secs = elapsed.as_secs_f64().max(1e-9);
    let ms = secs * 1000.0 / f64::from(frames);
    let fps = f64::from(frames) / secs;
    format!("frames {frames}: {ms:.2} ms/frame, {fps:.1} fps")
}

/// `render: frame K/N` on stderr once a second, from the first second on: long
/// renders show they are moving.
struct Progress {
    next: Instant,
    frames: u32,
}

impl Progress {
    fn new(start: Instant, frames: u32) -> Progress {
        Progress {
            next: start + Duration::from_secs(1),
            frames,
        }
    }

    /// Before drawing frame `done` (0-based): `done` frames are finished.
    fn tick(&mut self, done: u32) {
        let now = Instant::now();
        if now >= self.next {
            eprintln!("render: frame {done}/{}", self.frames);
            self.next = now + Duration::from_secs(1);
        }
    }
}

/// The k of `main`'s mesh scale `scale × 2^-k`: 0 for a model within 2^±16 (`scale` is
/// its reach / 32767), else the k that brings `scale` into [2^-8, 2^-7) (positions to
/// about ±2^8), within what an `f32` power of two can take back.
fn balance_exponent(scale: f32) -> i32 {
    let reach = f64::from(scale) * 32767.0;
    if (pow2(-16)..=pow2(16)).contains(&reach) {
        return 0;
    }
    let e = ((f64::from(scale).to_bits() >> 52) & 0x7ff) as i32 - 1023;
    (e + 8).clamp(-126, 127)
}

/// 2^e, for e in -1022..=1023.
fn pow2(e: i32) -> f64 {
    f64::from_bits(((e + 1023) as u64) << 52)
}
