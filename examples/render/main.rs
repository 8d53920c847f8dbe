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
//!
//! Textures: faces with `vt` coordinates whose material has a `map_Kd` PNG (read from
//! the MTL file's folder) are drawn with the texel at the pixel centre's
//! perspective-correct (u, v): column ⌊u·W⌋ mod W, row ⌊(1 − v)·H⌋ mod H (`-clamp on`
//! clamps instead), lit as a `Kd` of the texel's colour. A texture that cannot be read is
//! a warning, and its faces take their material's `Kd`.
//!
//! MTL `d` (or `Tr`): faces of opacity below 1 are drawn after every opaque face of the
//! scene, depth-tested without writing depth, blended over what is drawn (zraster's
//! `Translucent` rule; textured faces are drawn opaque).
//!
//! `--add FILE.obj@X,Y,Z` adds a model to the scene (see `USAGE`); the models share the
//! frame and its depth buffer, drawn one after another.

use std::io::Write;
use std::process::exit;
use std::time::{Duration, Instant};

use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
use embedded_graphics_simulator::{OutputSettings, SimulatorDisplay};
use zraster::{
    camera::{Camera, Viewport},
    damage::Damage,
    math::{radians, Mat4, Vec3},
    shade::{Light, Material, Shading, ONE},
    BandBuffers, Bands, CachedVertex, ColorBuffer, Cull, DepthSort, DrawError, Frame, FrameStats,
    RenderOptions, Renderer, Scene, ZBuffer,
};
use zraster_scenes::bus::SpiDisplay;

mod model;
use model::{Colours, Kd, Model};

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
  --add FILE.obj@X,Y,Z  another model in the scene (repeatable): fitted like
                      MODEL (unless --no-fit), moved by (X, Y, Z) before the
                      --yaw/--pitch rotation, drawn after MODEL into the same
                      depth buffer
Textures: faces with vt coordinates whose material has map_Kd FILE.png (relative
to the MTL file) show the texel at the pixel's perspective-correct (u, v), lit as
a colour is; a texture that cannot be read is a warning and its faces take Kd. MTL d ALPHA
(or Tr = 1 - d): see-through faces, drawn after the opaque ones with the depth
test on and depth writes off, blended over them (textured faces stay opaque).
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
    /// `--add`: more models, each moved by its offset.
    adds: Vec<(String, Vec3)>,
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
        adds: Vec::new(),
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
            "--add" => {
                let v = value(a);
                let Some((file, at)) = v.rsplit_once('@') else {
                    usage_error(&format!("--add needs FILE.obj@X,Y,Z, got {v:?}"))
                };
                let xyz: Vec<f32> = at.split(',').map(|c| parse_f32(a, c.trim())).collect();
                match xyz[..] {
                    [x, y, z] if !file.is_empty() => o.adds.push((file.into(), Vec3::new(x, y, z))),
                    _ => usage_error(&format!("--add needs FILE.obj@X,Y,Z, got {v:?}")),
                }
            }
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

/// One drawing of `frame` (the whole frame, or one band of it) by one of the scene's
/// renderers, in `mode`.
fn draw_pass(
    renderer: &mut Renderer<'_, '_, impl Colours>,
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

/// The sum of the scene's renderers' statistics.
fn total(stats: impl Iterator<Item = FrameStats>) -> FrameStats {
    stats.fold(FrameStats::default(), |a, s| FrameStats {
        triangles_in: a.triangles_in + s.triangles_in,
        culled: a.culled + s.culled,
        outside: a.outside + s.outside,
        clipped: a.clipped + s.clipped,
        drawn: a.drawn + s.drawn,
        pixels_tested: a.pixels_tested + s.pixels_tested,
        pixels_written: a.pixels_written + s.pixels_written,
        runs: a.runs + s.runs,
    })
}

/// The box, in the space the models are placed in, holding every model's bounding box
/// as `models[i]` places it.
fn scene_bounds(boxes: impl Iterator<Item = ((Vec3, Vec3), Mat4)>) -> Option<(Vec3, Vec3)> {
    let inf = f32::INFINITY;
    let (mut lo, mut hi) = (Vec3::new(inf, inf, inf), Vec3::new(-inf, -inf, -inf));
    let mut any = false;
    for ((a, b), m) in boxes {
        for k in 0..8 {
            let pick = |bit: u32, x: f32, y: f32| if k & bit == 0 { x } else { y };
            let c = m.transform_point(Vec3::new(
                pick(1, a.x, b.x),
                pick(2, a.y, b.y),
                pick(4, a.z, b.z),
            ));
            let p = Vec3::new(c[0] / c[3], c[1] / c[3], c[2] / c[3]);
            lo = Vec3::new(lo.x.min(p.x), lo.y.min(p.y), lo.z.min(p.z));
            hi = Vec3::new(hi.x.max(p.x), hi.y.max(p.y), hi.z.max(p.z));
            any = true;
        }
    }
    any.then_some((lo, hi))
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

    // ---- The models: MODEL, then each --add.
    let gouraud = o.shade == Shade::Gouraud;
    let mut warn = |w: String| eprintln!("render: warning: {w}");
    let mut models = vec![(
        Model::load(&o.model, o.color, o.fit, gouraud, &mut warn)
            .unwrap_or_else(|e| input_error(&e)),
        Vec3::default(),
    )];
    for (file, at) in &o.adds {
        let m = Model::load(file, o.color, o.fit, gouraud, &mut warn)
            .unwrap_or_else(|e| input_error(&e));
        models.push((m, *at));
    }
    // A see-through capable material type only where some face needs it.
    if models.iter().any(|(m, _)| m.see_through()) {
        draw_models::<Kd>(&o, &models);
    } else {
        draw_models::<Kd<false>>(&o, &models);
    }
}

/// Draw `models` as `o` says and write the outputs, with faces of material type `K`.
fn draw_models<K: Colours>(o: &Options, models: &[(Model, Vec3)]) {
    // What each renderer draws: the Z-buffer draws every part (untextured faces, then
    // each texture's), the other modes every face untextured; model by model.
    let parts: Vec<(&Model, &model::Part, Vec3)> = models
        .iter()
        .flat_map(|(m, at)| {
            let parts: Vec<&model::Part> = if o.mode == Mode::ZBuffer {
                m.parts.iter().collect()
            } else {
                vec![&m.all]
            };
            parts.into_iter().map(move |p| (m, p, *at))
        })
        .collect();
    let meshes: Vec<_> = parts.iter().map(|(m, p, _)| m.mesh::<K>(p)).collect();
    let texturings: Vec<_> = parts
        .iter()
        .map(|(m, p, _)| m.texturing(p).unwrap_or_else(|e| input_error(&e)))
        .collect();

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
    let line_color = Kd::<false>(o.color, 255, None).shade(ONE, 0, 0);
    let mut frame_pixels = vec![Rgb565::BLACK; (w * h) as usize];
    let mut depth_full = vec![u16::MAX; (w * h) as usize];
    let band_len = if o.band.is_some() {
        (w * rows) as usize
    } else {
        0
    };
    let mut band_pixels = vec![Rgb565::BLACK; band_len];
    let mut band_depth = vec![u16::MAX; band_len];
    // The Z-buffer draws the untextured parts as one scene (opaque faces first, then the
    // see-through ones), into bands binned when no part is textured.
    let zbuffer = o.mode == Mode::ZBuffer;
    let scene_bands = zbuffer && texturings.iter().all(Option::is_none);
    let bins_len: usize = match o.band {
        Some(_) if scene_bands => meshes
            .iter()
            .map(|m| BandBuffers::<Rgb565>::bins_needed(m.face_count(), h, rows))
            .sum(),
        _ => 0,
    };
    let mut bins = vec![0u16; bins_len];
    let mut caches: Vec<Vec<CachedVertex>> = parts
        .iter()
        .map(|(m, p, _)| vec![CachedVertex::EMPTY; m.vertices(p)])
        .collect();
    let mut sort: Option<Box<DepthSort<65536>>> = None;
    if o.mode == Mode::Painter {
        if meshes.iter().any(|m| m.face_count() > 65536) {
            input_error(&format!(
                "{}: painter mode handles at most 65536 faces",
                o.model
            ));
        }
        sort = Some(Box::default());
    }
    let mut stats = FrameStats::default();
    // --depth-fit: the model's box, for near and far each frame.
    let bounds = models[0].0.bounds;
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
        let turn = Mat4::rotation_x(radians(o.pitch)) * Mat4::rotation_y(radians(yaw));
        // Each model: placed (fitted), moved by its offset, then turned with the rest.
        let place = |m: &Model, at: Vec3| turn * Mat4::translation(at) * m.place;
        let mut fitted = camera;
        if o.depth_fit && o.adds.is_empty() {
            if let Some((lo, hi)) = bounds {
                // One model: its own box, as it has always been fitted.
                fitted = camera
                    .with_model(turn * models[0].0.place)
                    .fit_depth(lo, hi, o.near)
                    .unwrap_or_else(|e| input_error(&format!("--depth-fit: {e}")));
            }
        } else if o.depth_fit {
            // A scene: the box around every model's box, as placed.
            let boxes = models
                .iter()
                .filter_map(|(m, at)| Some((m.bounds?, place(m, *at))));
            if let Some((lo, hi)) = scene_bounds(boxes) {
                fitted = camera
                    .with_model(Mat4::IDENTITY)
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
        // The textured parts (opaque) and the untextured ones, each its own renderer.
        let (mut plain, mut textured) = (Vec::new(), Vec::new());
        for ((((m, _, at), mesh), cache), texturing) in parts
            .iter()
            .zip(&meshes)
            .zip(caches.iter_mut())
            .zip(&texturings)
        {
            let xf = fitted.with_model(place(m, *at));
            let r = Renderer::with_cache(mesh, &xf, options, cache)
                .unwrap_or_else(|e| input_error(&format!("transform: {e}")));
            match texturing {
                Some(t) => textured.push((r, *t)),
                None => plain.push(r),
            }
        }
        let fail = |e: DrawError<core::convert::Infallible>| -> ! {
            input_error(&format!("{}: {e}", o.model))
        };
        // One drawing of a frame or band: the textured parts, then the scene.
        let mut draw_all = |frame: &mut Frame<'_, Rgb565>| {
            for (r, t) in &mut textured {
                r.draw_textured(frame, t).unwrap_or_else(|e| fail(e));
            }
            if zbuffer {
                Scene::new(&mut plain)
                    .draw(frame)
                    .unwrap_or_else(|e| fail(e));
                return;
            }
            for r in &mut plain {
                draw_pass(r, o.mode, sort.as_deref_mut(), frame, line_color)
                    .unwrap_or_else(|e| fail(e));
            }
        };
        if o.band.is_none() {
            // The whole frame at once, straight into the frame buffer.
            let mut whole = Frame::new(&mut frame_pixels, &mut depth_full, w, h)
                .unwrap_or_else(|e| input_error(&e.to_string()));
            whole.clear(Rgb565::BLACK);
            draw_all(&mut whole);
        } else if scene_bands {
            // Band by band, each object's triangles binned once per frame.
            let mut full = ColorBuffer::new(&mut frame_pixels, w, h)
                .unwrap_or_else(|e| input_error(&e.to_string()));
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
            let result = Scene::new(&mut plain).draw(&mut target);
            if let Err(e) = result {
                input_error(&format!("{}: {e:?}", o.model));
            }
            // Same picture without bins, only slower: say so once.
            let unbinned = plain.iter().find_map(|r| match r.binning() {
                zraster::Binning::Off(why) => Some(why),
                _ => None,
            });
            if let (0, Some(why)) = (frame, unbinned) {
                eprintln!("warning: bands drawn without binning ({why})");
            }
        } else {
            // Every renderer into each band in turn (their vertices transformed once).
            let mut full = ColorBuffer::new(&mut frame_pixels, w, h)
                .unwrap_or_else(|e| input_error(&e.to_string()));
            let mut y = 0;
            while y < h {
                let n = rows.min(h - y);
                let color = ColorBuffer::new_band(&mut band_pixels, w, n, y as i32)
                    .unwrap_or_else(|e| input_error(&e.to_string()));
                let zbuf = ZBuffer::new_band(&mut band_depth, w, n, y as i32)
                    .unwrap_or_else(|e| input_error(&e.to_string()));
                let mut band = Frame::from_buffers(color, zbuf);
                band.clear(Rgb565::BLACK);
                draw_all(&mut band);
                band.flush(&mut full).ok();
                let start = (y * w) as usize;
                depth_full[start..start + (n * w) as usize]
                    .copy_from_slice(band.depth().as_slice());
                y += n;
            }
        }
        let all = plain.iter().chain(textured.iter().map(|(r, _)| r));
        stats = total(all.map(Renderer::stats));
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
