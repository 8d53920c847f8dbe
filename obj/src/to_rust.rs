//! OBJ → Rust source for a flash-resident mesh: what `obj2rust` prints, callable from a
//! build script.

use std::fmt::Write;

use zraster::math::Vec3;
use zraster::mesh::{compute_face_normals, compute_vertex_normals, Mesh};

mod textures;

use crate::{
    err, fit_scale, load_textures, parse, quantize, ModelTextures, ObjError, ObjImage, ObjModel,
    Skipped, SplitVertices,
};

/// The shape of [`to_rust`]'s output.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RustForm {
    /// A module file (`mod model;`): inner attributes and `use` lines at the top, as
    /// `obj2rust` prints it for checking in.
    #[default]
    Module,
    /// Items only, every path in full, for `include!` inside a module of yours (a build
    /// script's `OUT_DIR` file: `include!` takes no inner attributes).
    Include,
}

/// What [`to_rust`] writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RustOptions<'a> {
    /// The model's name: the items are `NAME_MESH`, `NAME_POSITIONS`, ... with the name
    /// made a SCREAMING_SNAKE prefix ([`rust_prefix`]).
    pub name: &'a str,
    /// Module file or `include!` items.
    pub form: RustForm,
}

impl Default for RustOptions<'_> {
    fn default() -> Self {
        RustOptions {
            name: "model",
            form: RustForm::Module,
        }
    }
}

/// What [`to_rust`] made.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RustMesh {
    /// The Rust source.
    pub code: String,
    /// The items' prefix: `MY_MODEL` for `MY_MODEL_MESH`.
    pub prefix: String,
    /// Vertices in the tables.
    pub vertices: usize,
    /// Triangles in the tables.
    pub triangles: usize,
    /// Distinct colours the faces take from MTL materials (0: the mesh is white).
    pub materials: usize,
    /// Textures written (0 for [`to_rust`], or when no face is textured).
    pub textures: usize,
}

/// `name` as the SCREAMING_SNAKE prefix of Rust items: ASCII letters and digits upper
/// case, a word break (`-`, space, `.`, a lower-to-upper case change, any other
/// character) one `_`, none at either end; `MODEL_` before a leading digit, and `MODEL`
/// for a name with no letter or digit. Every item adds a suffix (`_MESH`), so no item
/// is a keyword.
///
/// ```
/// use zraster_obj::rust_prefix;
/// assert_eq!(rust_prefix("my-model"), "MY_MODEL");
/// assert_eq!(rust_prefix("teaPot v2.obj"), "TEA_POT_V2_OBJ");
/// assert_eq!(rust_prefix("3d"), "MODEL_3D");
/// assert_eq!(rust_prefix("--"), "MODEL");
/// ```
pub fn rust_prefix(name: &str) -> String {
    let mut out = String::new();
    let mut prev_lower = false;
    for c in name.chars() {
        if c.is_ascii_alphanumeric() {
            if c.is_ascii_uppercase() && prev_lower {
                out.push('_');
            }
            out.push(c.to_ascii_uppercase());
            prev_lower = c.is_ascii_lowercase() || c.is_ascii_digit();
        } else {
            if !out.is_empty() && !out.ends_with('_') {
                out.push('_');
            }
            prev_lower = false;
        }
    }
    let out = out.trim_end_matches('_');
    match out.chars().next() {
        None => "MODEL".into(),
        Some(c) if c.is_ascii_digit() => format!("MODEL_{out}"),
        Some(_) => out.into(),
    }
}

/// Convert an OBJ model into Rust source for a `const` zraster mesh in flash: `i16`
/// positions around the bounding-box centre (`NAME_POSITIONS`, `NAME_SCALE`,
/// `NAME_CENTRE`), `u16` triangles (`NAME_INDICES`), Q14 face and vertex normals
/// computed as the renderer does, `NAME_FIT` (the scale that gives the model a largest
/// extent of one) and `NAME_MESH`, a `zraster::mesh::Mesh<'static, Rgb888>`. Faces take
/// their MTL `Kd` colour (`NAME_MATERIALS`, `NAME_FACE_COLORS`) as the `render` example
/// does; faces without a material are white.
///
/// `load_mtl(name)` returns the text of a material library named by `mtllib`, or why it
/// cannot ([`crate::MtlLoader::load`] reads them safely from a folder). Faces that
/// cannot be used (bad vertex references) are left out. Everything left out or changed
/// is a line in `warnings`: faces left out, polygons fan-triangulated, `vn` dropped,
/// `vt` and `map_Kd` textures dropped (a texture cannot be read here:
/// [`to_rust_textured`] writes them), statements skipped, libraries not read, unknown materials, faces without a
/// material, a name changed to make identifiers. Errors: malformed numbers, too many
/// vertices, a broken material library, or no faces left.
///
/// ```
/// use zraster_obj::{to_rust, RustOptions};
/// let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n\
///            usemtl red\nf 1//1 2//1 3//1 4//1\nf 1 2 9\n";
/// let mut warnings = Vec::new();
/// let opts = RustOptions { name: "my-quad", ..Default::default() };
/// let rust = to_rust(obj, |_| Ok("newmtl red\nKd 1 0 0\n".into()), &opts, &mut warnings)?;
/// assert_eq!((rust.prefix.as_str(), rust.triangles, rust.materials), ("MY_QUAD", 2, 1));
/// assert!(rust.code.contains("pub const MY_QUAD_MESH: Mesh<'static, Rgb888>"));
/// assert!(rust.code.contains("Materials::Uniform(Rgb888::new(255, 0, 0))"));
/// assert_eq!(warnings, [
///     "name \"my-quad\" makes the item prefix MY_QUAD (MY_QUAD_MESH, ...)",
///     "line 9: vertex index 9 out of range (the file has 4 vertices): face skipped",
///     "1 polygon of more than 3 vertices fan-triangulated into 2 triangles",
///     "1 `vn` normal dropped: the normal tables are computed from the positions",
/// ]);
/// # Ok::<(), zraster_obj::ObjError>(())
/// ```
///
/// From a build script (`zraster-obj` in `[build-dependencies]`), the warnings go to
/// cargo and the mesh into `OUT_DIR`:
///
/// ```no_run
/// // build.rs
/// use zraster_obj::{to_rust, MtlLoader, RustForm, RustOptions};
///
/// fn main() -> Result<(), Box<dyn std::error::Error>> {
///     println!("cargo:rerun-if-changed=models");
///     let obj = std::fs::read_to_string("models/teapot.obj")?;
///     let mut mtl = MtlLoader::new("models");
///     let opts = RustOptions { name: "teapot", form: RustForm::Include };
///     let mut warnings = Vec::new();
///     let rust = to_rust(&obj, |name| mtl.load(name), &opts, &mut warnings)?;
///     for w in &warnings {
///         println!("cargo:warning=models/teapot.obj: {w}");
///     }
///     let out = std::path::Path::new(&std::env::var("OUT_DIR")?).join("teapot.rs");
///     std::fs::write(out, rust.code)?;
///     Ok(())
/// }
/// // and in the crate:
/// // #[allow(dead_code, clippy::all)]
/// // mod teapot { include!(concat!(env!("OUT_DIR"), "/teapot.rs")); }
/// // ... Renderer::new(&teapot::TEAPOT_MESH, ...)
/// ```
pub fn to_rust(
    obj: &str,
    load_mtl: impl FnMut(&str) -> Result<String, String>,
    options: &RustOptions<'_>,
    warnings: &mut Vec<String>,
) -> Result<RustMesh, ObjError> {
    let no_textures = |_: &str| Err("to_rust reads no textures (to_rust_textured does)".into());
    to_rust_textured(obj, load_mtl, no_textures, options, warnings)
}

/// [`to_rust`] with textures: `load_texture(path)` reads a material's `map_Kd` image
/// ([`crate::MtlLoader::load_texture`] reads PNG files safely from the OBJ file's
/// folder; the path is relative to it).
///
/// When faces with `vt` coordinates use a material with a texture, the output gains
/// (besides everything [`to_rust`] writes, the same for an untextured model):
///
/// - `NAME_UVS: [[i16; 2]; N]`: each vertex's texture coordinates in zraster's Q12
///   [`MeshUv`](zraster::texture::MeshUv) form: 4096 is one texture, −8 ≤ u, v < 8, v
///   down the image (1 − OBJ's v). Each face is moved by whole textures if it does not
///   fit as it is (the same under repeat); a face spanning more than 8 textures is
///   clamped (a warning). Where faces give a position different coordinates, the
///   position is split into several vertices (copies at the end of the tables, with
///   the normals of the position).
/// - per texture: `NAME_TEXELS: [u16; W×H]`, raw RGB565 (`0xF800` is red, rounded as
///   embedded-graphics converts `Rgb888`), row by row from the top;
///   `NAME_TEXTURE_WIDTH`, `NAME_TEXTURE_HEIGHT: u32`; and `NAME_TEXTURE`, a
///   `zraster::texture::Texture<'static, u16>` over the table (repeating, or clamped for
///   `map_Kd -clamp on`). With several textures the names take `_0`, `_1`, ...
///   (`NAME_TEXELS_0`, `NAME_TEXTURE_0_WIDTH`), in order of first use.
/// - `NAME_FACE_TEXTURES: [u8; triangles]`, each triangle's texture (255: none), when
///   there are several textures or faces without one.
/// - `NAME_ALPHA: u8` (one material) or `NAME_MATERIAL_ALPHA: [u8; K]` (beside
///   `NAME_MATERIALS`), 255 opaque, when a material has `d` or `Tr` below opaque —
///   with a warning: zraster draws faces opaque.
///
/// A texture that cannot be read (missing, unreadable, not a PNG, larger than 8192
/// texels) is a warning, and its faces are drawn in their material's `Kd` colour (see
/// [`crate::load_textures`]); a texture's alpha channel is dropped with a warning.
///
/// ```
/// use zraster_obj::{to_rust_textured, ObjImage, RustOptions};
/// let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
///            vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl wood\nf 1/1 2/2 3/3 4/4\n";
/// let mtl = |_: &str| Ok("newmtl wood\nmap_Kd wood.png\n".to_string());
/// // A 2×1 texture: red, blue.
/// let png = |path: &str| {
///     assert_eq!(path, "wood.png");
///     Ok(ObjImage { width: 2, height: 1, rgba: vec![[255, 0, 0, 255], [0, 0, 255, 255]] })
/// };
/// let mut warnings = Vec::new();
/// let opts = RustOptions { name: "quad", ..Default::default() };
/// let rust = to_rust_textured(obj, mtl, png, &opts, &mut warnings)?;
/// assert_eq!((rust.vertices, rust.textures), (4, 1));
/// assert!(rust.code.contains("pub const QUAD_UVS: [[i16; 2]; 4] = [\n    [0, 4096], [4096, 4096], [4096, 0], [0, 0],\n];"));
/// assert!(rust.code.contains("pub const QUAD_TEXELS: [u16; 2] = [\n    0xF800, 0x001F,\n];"));
/// assert!(rust.code.contains("pub const QUAD_TEXTURE: Texture<'static, u16>"));
/// assert_eq!(warnings, ["1 polygon of more than 3 vertices fan-triangulated into 2 triangles"]);
/// # Ok::<(), zraster_obj::ObjError>(())
/// ```
pub fn to_rust_textured(
    obj: &str,
    load_mtl: impl FnMut(&str) -> Result<String, String>,
    load_texture: impl FnMut(&str) -> Result<ObjImage, String>,
    options: &RustOptions<'_>,
    warnings: &mut Vec<String>,
) -> Result<RustMesh, ObjError> {
    let prefix = rust_prefix(options.name);
    if prefix != options.name.to_ascii_uppercase() {
        warnings.push(format!(
            "name {:?} makes the item prefix {prefix} ({prefix}_MESH, ...)",
            options.name
        ));
    }
    let model = parse(obj, load_mtl, true)?;
    warnings.extend(model.warnings.iter().cloned());
    notes_to_warnings(&model, warnings);
    if model.triangles.is_empty() {
        return Err(err(0, "no faces"));
    }
    let mut textures = load_textures(&model, load_texture, warnings);
    if textures.textures.len() > MAX_TEXTURES {
        warnings.push(format!(
            "{} textures: those after the first {MAX_TEXTURES} are left out, their faces drawn untextured",
            textures.textures.len()
        ));
        textures.textures.truncate(MAX_TEXTURES);
        for t in &mut textures.of_material {
            *t = t.filter(|&k| k < MAX_TEXTURES);
        }
    }
    let textured = model
        .triangles
        .iter()
        .any(|t| textures.of_triangle(t).is_some());
    if !model.texcoords.is_empty() && !textured {
        let n = model.texcoords.len();
        warnings.push(format!(
            "{n} `vt` texture {} dropped: no face has both them and a material with a texture",
            plural(n, "coordinate", "coordinates")
        ));
    }
    let split = if textured {
        let split = model.split_vertices(|t| textures.of_triangle(t).is_some())?;
        split_warnings(&split, warnings);
        Some(split)
    } else {
        textures.textures.clear();
        None
    };
    for t in &textures.textures {
        if !t.image.opaque() {
            warnings.push(format!(
                "texture {}: its alpha channel is dropped (zraster draws textures opaque)",
                printable(&t.map.path)
            ));
        }
    }
    let colors = FaceColors::of(&model);
    let coloured =
        colors.palette.len() - usize::from(colors.white_faces > 0 && !colors.palette.is_empty());
    if colors.white_faces > 0 && coloured > 0 {
        let n = colors.white_faces;
        warnings.push(format!(
            "{n} {} without a material {} white",
            plural(n, "triangle", "triangles"),
            if n == 1 { "is" } else { "are" }
        ));
    }
    let tex = Textured {
        textures: &textures,
        split: split.as_ref(),
    };
    let code = write_rust(&model, &colors, &tex, &prefix, options.form, warnings)?;
    Ok(RustMesh {
        code,
        prefix,
        vertices: split
            .as_ref()
            .map_or(model.positions.len(), |s| s.vertices.len()),
        triangles: model.triangles.len(),
        materials: coloured,
        textures: textures.textures.len(),
    })
}

/// The most textures one model's output holds (a face's texture is a `u8`, 255 none).
const MAX_TEXTURES: usize = 255;

/// What [`write_rust`] adds for a textured model.
struct Textured<'a> {
    textures: &'a ModelTextures,
    /// The split vertex table (`None`: the model is written untextured).
    split: Option<&'a SplitVertices>,
}

/// The vertex splitting's notes as warning lines.
fn split_warnings(split: &SplitVertices, warnings: &mut Vec<String>) {
    if split.added > 0 {
        warnings.push(format!(
            "{} {} added where faces give a position different texture coordinates ({} in all)",
            split.added,
            plural(split.added, "vertex", "vertices"),
            split.vertices.len()
        ));
    }
    if split.moved_faces > 0 {
        warnings.push(format!(
            "{} {} moved by whole textures to fit the UV table's ±8 textures (the same under repeat, not under `-clamp on`)",
            split.moved_faces,
            plural(split.moved_faces, "face", "faces")
        ));
    }
    if let Some(first) = split.clamped_faces.first() {
        let n = split.clamped_faces.len();
        warnings.push(format!(
            "{n} {} more than 8 textures: texture coordinates clamped (first on line {first})",
            plural(n, "face spans", "faces span")
        ));
    }
    if split.huge > 0 {
        warnings.push(format!(
            "{} texture {} of magnitude 2^40 or more: their place within the texture is below f64 precision",
            split.huge,
            plural(split.huge, "coordinate", "coordinates")
        ));
    }
}

fn plural<'a>(n: usize, one: &'a str, many: &'a str) -> &'a str {
    if n == 1 {
        one
    } else {
        many
    }
}

/// The reader's notes as warning lines.
fn notes_to_warnings(model: &ObjModel, warnings: &mut Vec<String>) {
    let n = &model.notes;
    if n.polygons > 0 {
        warnings.push(format!(
            "{} {} of more than 3 vertices fan-triangulated into {} triangles",
            n.polygons,
            plural(n.polygons, "polygon", "polygons"),
            n.polygon_triangles
        ));
    }
    if n.normals > 0 {
        warnings.push(format!(
            "{} `vn` {} dropped: the normal tables are computed from the positions",
            n.normals,
            plural(n.normals, "normal", "normals")
        ));
    }
    if n.texcoord_w > 0 {
        warnings.push(format!(
            "{} `vt` {} a third (w) coordinate, dropped",
            n.texcoord_w,
            plural(n.texcoord_w, "statement has", "statements have")
        ));
    }
    // OBJ statements with their (first) line; MTL ones with their count alone.
    let list = |s: &[Skipped], lines: bool| {
        s.iter()
            .map(|s| {
                let kw = printable(&s.keyword);
                match (s.count, lines) {
                    (1, true) => format!("`{kw}` (line {})", s.first_line),
                    (c, true) => format!("`{kw}` ×{c} (first on line {})", s.first_line),
                    (1, false) => format!("`{kw}`"),
                    (c, false) => format!("`{kw}` ×{c}"),
                }
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    if !n.skipped.is_empty() {
        warnings.push(format!("statements skipped: {}", list(&n.skipped, true)));
    }
    if !n.skipped_mtl.is_empty() {
        warnings.push(format!(
            "material statements skipped (only `newmtl`, `Kd`, `map_Kd`, `d` and `Tr` are read): {}",
            list(&n.skipped_mtl, false)
        ));
    }
    if n.skipped_other > 0 {
        warnings.push(format!(
            "{} more statements of other kinds skipped",
            n.skipped_other
        ));
    }
}

/// `s` with anything but printable ASCII as `?`, at most 64 characters: safe in a
/// message and in a Rust comment (no line breaks, no bidirectional controls).
fn printable(s: &str) -> String {
    s.chars()
        .take(64)
        .map(|c| {
            if c.is_ascii_graphic() || c == ' ' {
                c
            } else {
                '?'
            }
        })
        .collect()
}

/// The faces' colours: a palette and one palette entry per triangle.
struct FaceColors {
    /// Name, RGB and opacity (255 opaque) of each colour used, in order of first use
    /// (white last, for faces without a material, when there are both).
    palette: Vec<(String, [u8; 3], u8)>,
    /// Palette entry of each triangle.
    faces: Vec<usize>,
    /// Triangles without a material.
    white_faces: usize,
}

impl FaceColors {
    fn of(model: &ObjModel) -> FaceColors {
        let mut palette = Vec::new();
        let mut of_material: Vec<Option<usize>> = vec![None; model.materials.len()];
        let mut faces = Vec::with_capacity(model.triangles.len());
        let mut white = Vec::new();
        for (i, t) in model.triangles.iter().enumerate() {
            let Some(m) = t.material.filter(|&m| m < model.materials.len()) else {
                white.push(i);
                faces.push(usize::MAX);
                continue;
            };
            let entry = *of_material[m].get_or_insert_with(|| {
                let mat = &model.materials[m];
                let rgb = mat.kd.map(|c| (c * 255.0).round().clamp(0.0, 255.0) as u8);
                let alpha = (mat.alpha * 255.0).round().clamp(0.0, 255.0) as u8;
                palette.push((printable(&mat.name), rgb, alpha));
                palette.len() - 1
            });
            faces.push(entry);
        }
        if !white.is_empty() && !palette.is_empty() {
            palette.push(("(no material)".into(), [255; 3], 255));
            for i in &white {
                faces[*i] = palette.len() - 1;
            }
        }
        // No material at all: every entry stays usize::MAX, the mesh is uniformly white.
        FaceColors {
            palette,
            faces,
            white_faces: white.len(),
        }
    }
}

/// The Rust source.
fn write_rust(
    model: &ObjModel,
    colors: &FaceColors,
    tex: &Textured<'_>,
    n: &str,
    form: RustForm,
    warnings: &mut Vec<String>,
) -> Result<String, ObjError> {
    let q = quantize(&model.positions, true);
    let indices = model.triangle_indices();
    // Unit normals do not depend on the scale: outside 2^±16 of reach, the positions
    // are taken as about ±1 so f32 products neither overflow nor vanish.
    let reach = f64::from(q.scale) * 32767.0;
    let normal_scale = if (1.0 / 65536.0..=65536.0).contains(&reach) {
        q.scale
    } else {
        1.0 / 32767.0
    };
    let mesh = Mesh::triangles(&q.positions, normal_scale, &indices, ());
    let mut fnorm = vec![[0i16; 3]; indices.len()];
    let mut vnorm = vec![[0i16; 3]; q.positions.len()];
    let mut scratch = vec![Vec3::default(); q.positions.len()];
    compute_face_normals(&mesh, &mut fnorm).map_err(|e| err(0, format!("normals: {e}")))?;
    compute_vertex_normals(&mesh, &mut scratch, &mut vnorm)
        .map_err(|e| err(0, format!("normals: {e}")))?;
    let fit = fit_scale(&model.positions);
    // A textured model's tables hold the split vertices: each a position, with the
    // position's normal (computed over all its faces, so no seam shows in the light).
    let (positions, vnorm, indices) = match tex.split {
        Some(split) => (
            split
                .vertices
                .iter()
                .map(|v| q.positions[v.position as usize])
                .collect(),
            split
                .vertices
                .iter()
                .map(|v| vnorm[v.position as usize])
                .collect(),
            split.triangle_indices(),
        ),
        None => (q.positions.clone(), vnorm, indices),
    };
    let texture_count = if tex.split.is_some() {
        tex.textures.textures.len()
    } else {
        0
    };

    let include = form == RustForm::Include;
    let (rgb, mesh_mod) = if include {
        ("embedded_graphics::pixelcolor::Rgb888", "zraster::mesh::")
    } else {
        ("Rgb888", "")
    };
    let mut out = String::new();
    let w = &mut out;
    // Writing into a String cannot fail.
    if include {
        let _ = writeln!(
            w,
            "// Generated by zraster_obj::to_rust from an OBJ model: do not edit."
        );
    } else {
        let _ = writeln!(
            w,
            "// Generated by `cargo run --example obj2rust` from an OBJ model: do not edit."
        );
    }
    let _ = write!(
        w,
        "// {} vertices, {} triangles",
        positions.len(),
        indices.len()
    );
    match texture_count {
        0 => {}
        1 => {
            let _ = write!(w, ", 1 texture");
        }
        k => {
            let _ = write!(w, ", {k} textures");
        }
    }
    let _ = writeln!(w, ".");
    if !include {
        let _ = writeln!(w, "#![allow(clippy::all, dead_code)]");
        let _ = writeln!(w, "#![cfg_attr(rustfmt, rustfmt::skip)]");
        let _ = writeln!(w, "use embedded_graphics::pixelcolor::Rgb888;");
        let _ = writeln!(w, "use zraster::mesh::{{Faces, Materials, Mesh}};");
        if texture_count > 0 {
            let _ = writeln!(w, "{}", textures::imports(tex.textures));
        }
    }
    let _ = writeln!(w);
    let _ = writeln!(
        w,
        "/// Model units per position step.\npub const {n}_SCALE: f32 = {:?};",
        q.scale
    );
    let _ = writeln!(
        w,
        "/// The bounding-box centre the positions are stored around."
    );
    let _ = writeln!(w, "pub const {n}_CENTRE: [f32; 3] = {:?};", q.offset);
    let _ = writeln!(
        w,
        "/// The uniform scale that makes the largest extent 1.\npub const {n}_FIT: f32 = {fit:?};"
    );
    let fmt3 = |v: &[i16; 3]| format!("[{}, {}, {}]", v[0], v[1], v[2]);
    table(
        w,
        "Vertex positions.",
        &format!("{n}_POSITIONS"),
        "[i16; 3]",
        positions.iter().map(fmt3).collect(),
        6,
    );
    table(
        w,
        "Triangles, counter-clockwise from the front.",
        &format!("{n}_INDICES"),
        "[u16; 3]",
        indices
            .iter()
            .map(|t| format!("[{}, {}, {}]", t[0], t[1], t[2]))
            .collect(),
        6,
    );
    table(
        w,
        "Unit face normals, Q14.",
        &format!("{n}_FACE_NORMALS"),
        "[i16; 3]",
        fnorm.iter().map(fmt3).collect(),
        6,
    );
    table(
        w,
        "Unit vertex normals, Q14.",
        &format!("{n}_VERTEX_NORMALS"),
        "[i16; 3]",
        vnorm.iter().map(fmt3).collect(),
        6,
    );
    let new_rgb = |c: [u8; 3]| format!("{rgb}::new({}, {}, {})", c[0], c[1], c[2]);
    let (doc, materials) = match colors.palette.as_slice() {
        [] => (
            "The mesh, in white.".to_string(),
            format!("Uniform({})", new_rgb([255; 3])),
        ),
        [(name, c, _)] => (
            format!("The mesh, in its material's colour ({name}, MTL `Kd`)."),
            format!("Uniform({})", new_rgb(*c)),
        ),
        palette => {
            let _ = writeln!(
                w,
                "/// The materials' colours (MTL `Kd`), in order of first use.\npub const {n}_MATERIALS: [{rgb}; {}] = [",
                palette.len()
            );
            for (name, c, _) in palette {
                let _ = writeln!(w, "    {}, // {name}", new_rgb(*c));
            }
            let _ = writeln!(w, "];");
            table(
                w,
                "Each triangle's colour.",
                &format!("{n}_FACE_COLORS"),
                rgb,
                colors
                    .faces
                    .iter()
                    .map(|k| format!("{n}_MATERIALS[{k}]"))
                    .collect(),
                8,
            );
            (
                "The mesh, in its materials' colours.".to_string(),
                format!("PerFace(&{n}_FACE_COLORS)"),
            )
        }
    };
    alpha(w, colors, n, warnings);
    if let Some(split) = tex.split {
        textures::write(w, tex.textures, split, model, n, include);
    }
    let _ = writeln!(
        w,
        "/// {doc}\npub const {n}_MESH: {mesh_mod}Mesh<'static, {rgb}> = {mesh_mod}Mesh {{\n    positions: &{n}_POSITIONS,\n    scale: {n}_SCALE,\n    faces: {mesh_mod}Faces::Triangles {{ indices: &{n}_INDICES, materials: {mesh_mod}Materials::{materials} }},\n    face_normals: Some(&{n}_FACE_NORMALS),\n    vertex_normals: Some(&{n}_VERTEX_NORMALS),\n}};"
    );
    Ok(out)
}

/// `const ITEM: [TY; N] = [...]` with its doc line, `per` entries a line.
fn table(w: &mut String, doc: &str, item: &str, ty: &str, rows: Vec<String>, per: usize) {
    let _ = writeln!(w, "/// {doc}\npub const {item}: [{ty}; {}] = [", rows.len());
    for chunk in rows.chunks(per) {
        let _ = writeln!(w, "    {},", chunk.join(", "));
    }
    let _ = writeln!(w, "];");
}

/// The materials' opacity, when one is not opaque: `NAME_ALPHA` for one material,
/// `NAME_MATERIAL_ALPHA` beside `NAME_MATERIALS` for several; a warning each.
fn alpha(w: &mut String, colors: &FaceColors, n: &str, warnings: &mut Vec<String>) {
    let translucent: Vec<&(String, [u8; 3], u8)> =
        colors.palette.iter().filter(|p| p.2 < 255).collect();
    if translucent.is_empty() {
        return;
    }
    let item = if colors.palette.len() == 1 {
        format!("{n}_ALPHA")
    } else {
        format!("{n}_MATERIAL_ALPHA")
    };
    for (name, _, a) in translucent {
        warnings.push(format!(
            "material {name}: opacity {a}/255 (MTL d or Tr) carried in {item}; zraster draws faces opaque"
        ));
    }
    if let [(name, _, a)] = colors.palette.as_slice() {
        let _ = writeln!(
            w,
            "/// The material's opacity ({name}, MTL `d`), 255 opaque; zraster draws it opaque.\npub const {item}: u8 = {a};"
        );
    } else {
        table(
            w,
            "Each material's opacity (MTL `d`), 255 opaque, as `MATERIALS`; zraster draws them opaque.",
            &item,
            "u8",
            colors.palette.iter().map(|p| p.2.to_string()).collect(),
            16,
        );
    }
}
