//! A Wavefront OBJ reader for zraster's host tools: the `render` example, the
//! `obj2rust` converter, the tests.
//!
//! Reads `v` and `f` (with `v`, `v/vt`, `v/vt/vn`, `v//vn` and negative indices),
//! `mtllib` + `usemtl` with `Kd` colours; other statements are ignored. Errors name the
//! line. A UTF-8 byte-order mark at the start of an OBJ or MTL text is skipped.
//! [`MtlLoader`] reads the material libraries from disk safely (regular files of at most
//! [`MAX_MTL_BYTES`], each once). [`quantize`] turns the positions into the `i16`
//! vertex table of a `zraster::mesh::Mesh`; [`fit_scale_f64`] sizes any finite model,
//! up to coordinates of ±`f32::MAX`.
//!
//! [`to_rust`] turns a model into Rust source for a `const` mesh in flash (what the
//! `obj2rust` example prints), from a build script too, and says what it left out.
//!
//! It lives in its own crate because it allocates: zraster itself never does.

use std::collections::HashSet;
use std::fmt;
use std::io::Read;
use std::path::{Path, PathBuf};

mod to_rust;
pub use to_rust::{rust_prefix, to_rust, RustForm, RustMesh, RustOptions};

/// A material from an MTL file.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjMaterial {
    /// The `newmtl` name.
    pub name: String,
    /// The diffuse colour `Kd`, each in 0..=1.
    pub kd: [f32; 3],
}

/// One triangle of the model (polygons are fan-triangulated while reading).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ObjTriangle {
    /// Vertex indices (0-based), counter-clockwise from the front.
    pub vertices: [u32; 3],
    /// Index into [`ObjModel::materials`], if a known `usemtl` was in force.
    pub material: Option<usize>,
    /// The line of the `f` statement.
    pub line: usize,
}

/// A parsed OBJ file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ObjModel {
    /// The `v` statements.
    pub positions: Vec<[f32; 3]>,
    /// The faces as triangles.
    pub triangles: Vec<ObjTriangle>,
    /// Materials from the `mtllib` files.
    pub materials: Vec<ObjMaterial>,
    /// Problems that did not stop reading (a missing MTL file, an unknown material).
    pub warnings: Vec<String>,
    /// What was read but not kept, or changed (for the converter's warnings).
    pub notes: ReadNotes,
}

/// What the reader read but did not keep, or changed: [`to_rust`] reports each.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ReadNotes {
    /// Faces of more than three vertices, fan-triangulated.
    pub polygons: usize,
    /// The triangles those faces became.
    pub polygon_triangles: usize,
    /// `vn` statements (zraster computes normals from the positions).
    pub normals: usize,
    /// `vt` statements (zraster has no textures).
    pub texcoords: usize,
    /// OBJ statements the reader does not use (`o`, `g`, `s`, `l`, ...), by keyword in
    /// order of first appearance (at most [`MAX_SKIPPED_KINDS`] kinds; the rest are
    /// counted in `skipped_other`).
    pub skipped: Vec<Skipped>,
    /// MTL statements the reader does not use (`Ka`, `Ks`, `map_Kd`, ...), alike; their
    /// line is that of the `mtllib` statement.
    pub skipped_mtl: Vec<Skipped>,
    /// Skipped statements beyond the first [`MAX_SKIPPED_KINDS`] kinds.
    pub skipped_other: usize,
    /// Faces left out because they could not be used (only when reading leniently,
    /// as [`to_rust`] does).
    pub bad_faces: usize,
}

/// One kind of statement the reader skipped.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Skipped {
    /// The keyword (at most 32 bytes of it).
    pub keyword: String,
    /// How many times it occurred.
    pub count: usize,
    /// The line of its first occurrence (1-based).
    pub first_line: usize,
}

/// The most kinds of skipped statement [`ReadNotes`] tells apart.
pub const MAX_SKIPPED_KINDS: usize = 32;

/// The most bad faces a lenient read names one by one in the warnings.
const MAX_BAD_FACE_WARNINGS: usize = 10;

impl ReadNotes {
    fn skip(list: &mut Vec<Skipped>, other: &mut usize, keyword: &str, line: usize) {
        let mut end = keyword.len().min(32);
        while !keyword.is_char_boundary(end) {
            end -= 1;
        }
        let keyword = &keyword[..end];
        if let Some(s) = list.iter_mut().find(|s| s.keyword == keyword) {
            s.count += 1;
        } else if list.len() < MAX_SKIPPED_KINDS {
            list.push(Skipped {
                keyword: keyword.to_string(),
                count: 1,
                first_line: line,
            });
        } else {
            *other += 1;
        }
    }
}

impl ObjModel {
    /// The triangles' vertex indices as `u16`, the form of a zraster triangle list (the
    /// reader accepts at most [`MAX_VERTICES`] = 2¹⁶ vertices, so every index fits).
    pub fn triangle_indices(&self) -> Vec<[u16; 3]> {
        self.triangles
            .iter()
            .map(|t| t.vertices.map(|v| v as u16))
            .collect()
    }
}

/// A reading error, with the (1-based) line it was found on.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ObjError {
    /// The line number (1-based); 0 for errors about the whole file.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for ObjError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line == 0 {
            write!(f, "{}", self.message)
        } else {
            write!(f, "line {}: {}", self.line, self.message)
        }
    }
}

impl std::error::Error for ObjError {}

fn err(line: usize, message: impl ToString) -> ObjError {
    ObjError {
        line,
        message: message.to_string(),
    }
}

fn number(tok: Option<&str>, line: usize, what: &str) -> Result<f32, ObjError> {
    let tok = tok.ok_or_else(|| err(line, format!("missing {what}")))?;
    let v: f32 = tok
        .parse()
        .map_err(|_| err(line, format!("{what} is not a number: {tok:?}")))?;
    if !v.is_finite() {
        return Err(err(line, format!("{what} is not finite: {tok:?}")));
    }
    Ok(v)
}

/// The most vertices a model may have (meshes index them with `u16`).
pub const MAX_VERTICES: usize = 1 << 16;

/// Read an OBJ file. `load_mtl(name)` returns the text of an MTL file named by `mtllib`
/// (relative to the OBJ file), or `None` if it cannot be read (a warning, not an error).
/// Each library name is asked for once, however often `mtllib` repeats it.
///
/// ```
/// let model = zraster_obj::parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 3\n", |_| None)?;
/// assert_eq!(model.triangles.len(), 2); // the quad, fanned
/// let err = zraster_obj::parse_obj("v 0 0 0\nf 1 2 3\n", |_| None).unwrap_err();
/// assert_eq!(err.to_string(), "line 2: vertex index 2 out of range (the file has 1 vertices)");
/// # Ok::<(), zraster_obj::ObjError>(())
/// ```
pub fn parse_obj(
    src: &str,
    mut load_mtl: impl FnMut(&str) -> Option<String>,
) -> Result<ObjModel, ObjError> {
    parse_obj_with(src, |name| load_mtl(name).ok_or_else(String::new))
}

/// [`parse_obj`], with `load_mtl` saying why a library cannot be read: `Err(reason)`
/// becomes the warning `line N: cannot read material library NAME: REASON` (an empty
/// reason leaves off the `: REASON`). [`MtlLoader::load`] is such a loader.
pub fn parse_obj_with(
    src: &str,
    load_mtl: impl FnMut(&str) -> Result<String, String>,
) -> Result<ObjModel, ObjError> {
    parse(src, load_mtl, false)
}

/// Leave out a face that cannot be used, with a warning (the first few by line).
fn bad_face(m: &mut ObjModel, e: ObjError) {
    m.notes.bad_faces += 1;
    if m.notes.bad_faces <= MAX_BAD_FACE_WARNINGS {
        m.warnings.push(format!("{e}: face skipped"));
    }
}

/// One `f` statement's vertex indices (0-based; a forward reference stays unchecked).
fn face(toks: std::str::SplitWhitespace<'_>, line: usize, n: usize) -> Result<Vec<u32>, ObjError> {
    let mut idx: Vec<u32> = Vec::new();
    for t in toks {
        let first = t.split('/').next().unwrap_or("");
        let v: i64 = first
            .parse()
            .map_err(|_| err(line, format!("bad vertex reference {t:?}")))?;
        let resolved = match v {
            0 => return Err(err(line, "vertex index 0 (OBJ indices start at 1)")),
            v if v < 0 => n as i64 + v,
            v => v - 1,
        };
        if resolved < 0 || resolved >= MAX_VERTICES as i64 {
            return Err(err(line, format!("vertex index {v} out of range")));
        }
        idx.push(resolved as u32);
    }
    if idx.len() < 3 {
        return Err(err(
            line,
            format!(
                "a face needs 3 or more vertices, this one has {}",
                idx.len()
            ),
        ));
    }
    Ok(idx)
}

/// The reader. `lenient`: a face that cannot be used is left out with a warning
/// instead of failing the read.
pub(crate) fn parse(
    src: &str,
    mut load_mtl: impl FnMut(&str) -> Result<String, String>,
    lenient: bool,
) -> Result<ObjModel, ObjError> {
    let mut m = ObjModel::default();
    let mut current: Option<usize> = None;
    // The libraries already asked for: a repeated `mtllib` is not read again.
    let mut libraries: HashSet<&str> = HashSet::new();
    // A UTF-8 byte-order mark is not part of the first statement.
    let src = src.strip_prefix('\u{feff}').unwrap_or(src);
    for (i, raw) in src.lines().enumerate() {
        let line = i + 1;
        let text = raw.split('#').next().unwrap_or("");
        let mut toks = text.split_whitespace();
        let Some(kw) = toks.next() else { continue };
        match kw {
            "v" => {
                let x = number(toks.next(), line, "x")?;
                let y = number(toks.next(), line, "y")?;
                let z = number(toks.next(), line, "z")?;
                if m.positions.len() >= MAX_VERTICES {
                    return Err(err(line, format!("more than {MAX_VERTICES} vertices")));
                }
                m.positions.push([x, y, z]);
            }
            "f" => {
                let idx = match face(toks, line, m.positions.len()) {
                    Ok(idx) => idx,
                    Err(e) if lenient => {
                        bad_face(&mut m, e);
                        continue;
                    }
                    Err(e) => return Err(e),
                };
                if idx.len() > 3 {
                    m.notes.polygons += 1;
                    m.notes.polygon_triangles += idx.len() - 2;
                }
                if let Some((&first, rest)) = idx.split_first() {
                    for pair in rest.windows(2) {
                        if let &[b, c] = pair {
                            m.triangles.push(ObjTriangle {
                                vertices: [first, b, c],
                                material: current,
                                line,
                            });
                        }
                    }
                }
            }
            "mtllib" => {
                for name in toks {
                    if !libraries.insert(name) {
                        continue;
                    }
                    match load_mtl(name) {
                        Ok(text) => {
                            let skipped = (&mut m.notes.skipped_mtl, &mut m.notes.skipped_other);
                            parse_mtl_noting(&text, &mut m.materials, line, skipped)
                                .map_err(|e| err(line, format!("in {name}: {e}")))?
                        }
                        Err(why) if why.is_empty() => m
                            .warnings
                            .push(format!("line {line}: cannot read material library {name}")),
                        Err(why) => m.warnings.push(format!(
                            "line {line}: cannot read material library {name}: {why}"
                        )),
                    }
                }
            }
            "usemtl" => {
                let name = toks.next().unwrap_or("");
                current = m.materials.iter().position(|mat| mat.name == name);
                if current.is_none() {
                    m.warnings
                        .push(format!("line {line}: unknown material {name:?}"));
                }
            }
            "vn" => m.notes.normals += 1,
            "vt" => m.notes.texcoords += 1,
            kw => ReadNotes::skip(&mut m.notes.skipped, &mut m.notes.skipped_other, kw, line),
        }
    }
    let n = m.positions.len();
    let out_of_range = |t: &ObjTriangle| t.vertices.iter().find(|&&v| v as usize >= n).copied();
    if lenient {
        // Whole faces go: every triangle of a line with a bad one.
        let mut bad_lines: Vec<(usize, u32)> = Vec::new();
        for t in &m.triangles {
            if let Some(v) = out_of_range(t) {
                if bad_lines.last().is_none_or(|&(l, _)| l != t.line) {
                    bad_lines.push((t.line, v));
                }
            }
        }
        if !bad_lines.is_empty() {
            let lines: HashSet<usize> = bad_lines.iter().map(|&(l, _)| l).collect();
            m.triangles.retain(|t| !lines.contains(&t.line));
            for (line, v) in bad_lines {
                let e = err(
                    line,
                    format!(
                        "vertex index {} out of range (the file has {n} vertices)",
                        v + 1
                    ),
                );
                bad_face(&mut m, e);
            }
        }
        if m.notes.bad_faces > MAX_BAD_FACE_WARNINGS {
            m.warnings.push(format!(
                "{} more faces skipped ({} in all)",
                m.notes.bad_faces - MAX_BAD_FACE_WARNINGS,
                m.notes.bad_faces
            ));
        }
    } else if let Some((t, bad)) = m
        .triangles
        .iter()
        .find_map(|t| out_of_range(t).map(|v| (t, v)))
    {
        return Err(err(
            t.line,
            format!(
                "vertex index {} out of range (the file has {n} vertices)",
                bad + 1
            ),
        ));
    }
    Ok(m)
}

/// Read `newmtl` / `Kd` statements of an MTL file into `out`.
pub fn parse_mtl(src: &str, out: &mut Vec<ObjMaterial>) -> Result<(), ObjError> {
    parse_mtl_noting(src, out, 0, (&mut Vec::new(), &mut 0))
}

/// [`parse_mtl`], noting the statements it skips (as if on line `at`).
fn parse_mtl_noting(
    src: &str,
    out: &mut Vec<ObjMaterial>,
    at: usize,
    (skipped, other): (&mut Vec<Skipped>, &mut usize),
) -> Result<(), ObjError> {
    let src = src.strip_prefix('\u{feff}').unwrap_or(src);
    for (i, raw) in src.lines().enumerate() {
        let line = i + 1;
        let text = raw.split('#').next().unwrap_or("");
        let mut toks = text.split_whitespace();
        match toks.next() {
            Some("newmtl") => out.push(ObjMaterial {
                name: toks.next().unwrap_or("").to_string(),
                kd: [1.0; 3],
            }),
            Some("Kd") => {
                let r = number(toks.next(), line, "Kd red")?;
                let g = number(toks.next(), line, "Kd green")?;
                let b = number(toks.next(), line, "Kd blue")?;
                let mat = out
                    .last_mut()
                    .ok_or_else(|| err(line, "Kd before any newmtl"))?;
                mat.kd = [r.clamp(0.0, 1.0), g.clamp(0.0, 1.0), b.clamp(0.0, 1.0)];
            }
            Some(kw) => ReadNotes::skip(skipped, other, kw, at),
            None => {}
        }
    }
    Ok(())
}

/// The largest material library [`MtlLoader`] reads: 16 MiB.
pub const MAX_MTL_BYTES: u64 = 16 << 20;

/// Reads the material libraries an OBJ file names, from the OBJ file's folder, for
/// [`parse_obj_with`] — safe for files from anywhere: it reads only regular files (never
/// a device such as `/dev/zero`, which never ends, or a FIFO, which blocks its reader
/// until something writes), of at most [`MAX_MTL_BYTES`], and each file once (by its
/// canonical path: a library named again, under any name, reads as empty).
///
/// ```
/// let dir = std::env::temp_dir();
/// let mut mtl = zraster_obj::MtlLoader::new(&dir);
/// let model = zraster_obj::parse_obj_with("mtllib /dev/zero\n", |name| mtl.load(name))?;
/// assert_eq!(
///     model.warnings,
///     ["line 1: cannot read material library /dev/zero: not a regular file"]
/// );
/// # Ok::<(), zraster_obj::ObjError>(())
/// ```
#[derive(Debug, Clone, Default)]
pub struct MtlLoader {
    dir: PathBuf,
    seen: HashSet<PathBuf>,
}

impl MtlLoader {
    /// A loader for the libraries of an OBJ file in `dir`.
    pub fn new(dir: impl AsRef<Path>) -> MtlLoader {
        MtlLoader {
            dir: dir.as_ref().to_path_buf(),
            seen: HashSet::new(),
        }
    }

    /// The text of the library `name` (relative to the folder, or absolute); `""` for a
    /// file read before. `Err` says why it cannot be read.
    pub fn load(&mut self, name: &str) -> Result<String, String> {
        let path = self.dir.join(name);
        let too_big = || format!("larger than {} MiB", MAX_MTL_BYTES >> 20);
        // The type and size before opening: opening a FIFO for reading blocks.
        let meta = std::fs::metadata(&path).map_err(|e| e.to_string())?;
        if !meta.is_file() {
            return Err("not a regular file".into());
        }
        if meta.len() > MAX_MTL_BYTES {
            return Err(too_big());
        }
        let key = std::fs::canonicalize(&path).map_err(|e| e.to_string())?;
        if !self.seen.insert(key) {
            return Ok(String::new());
        }
        let file = std::fs::File::open(&path).map_err(|e| e.to_string())?;
        // What was opened may not be what was looked at; and a file may grow.
        if !file.metadata().is_ok_and(|m| m.is_file()) {
            return Err("not a regular file".into());
        }
        let mut bytes = Vec::new();
        file.take(MAX_MTL_BYTES + 1)
            .read_to_end(&mut bytes)
            .map_err(|e| e.to_string())?;
        if bytes.len() as u64 > MAX_MTL_BYTES {
            return Err(too_big());
        }
        String::from_utf8(bytes).map_err(|_| "not UTF-8 text".into())
    }
}

/// Positions quantised to `i16` for a `zraster::mesh::Mesh`: `q × scale + offset`
/// reproduces each position to within half a step.
#[derive(Debug, Clone, PartialEq)]
pub struct Quantized {
    /// The quantised positions.
    pub positions: Vec<[i16; 3]>,
    /// Model units per step.
    pub scale: f32,
    /// Added after scaling (the bounding-box centre when centred, else zero).
    pub offset: [f32; 3],
}

/// The bounding box of `positions`: its lowest and highest corner (both zero when there
/// are no positions).
pub fn bounds(positions: &[[f32; 3]]) -> ([f32; 3], [f32; 3]) {
    if positions.is_empty() {
        return ([0.0; 3], [0.0; 3]);
    }
    let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
    for p in positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

/// The uniform scale that makes the largest extent of the bounding box 1 (1 when the
/// box is a point or there are no positions), as `f32`: [`fit_scale_f64`] rounded. For
/// a box wider than 2¹²⁶ (8.5·10³⁷) that is below `f32`'s normal range and loses
/// precision; use [`fit_scale_f64`] for such models.
pub fn fit_scale(positions: &[[f32; 3]]) -> f32 {
    fit_scale_f64(positions) as f32
}

/// [`fit_scale`] without overflow: the extent of a box of `f32` coordinates reaches
/// 2 × `f32::MAX`, which is ∞ in `f32` (the scale was then 0). The value is the one
/// `f32` arithmetic gives (the extent rounded to `f32`, then `1 / extent` rounded)
/// wherever that is a normal `f32`; for wider and narrower boxes, the same two
/// roundings to 24 bits, without the `f32` exponent range.
pub fn fit_scale_f64(positions: &[[f32; 3]]) -> f64 {
    let (lo, hi) = bounds(positions);
    let extent = (0..3)
        .map(|k| f64::from(hi[k]) - f64::from(lo[k]))
        .fold(0.0f64, f64::max);
    if extent > 0.0 {
        // extent = m·2^e with m in [1, 2): f32 arithmetic on m, the exponent apart.
        let e = exponent(extent);
        let m = (extent * pow2(-e)) as f32;
        f64::from(1.0 / m) * pow2(-e)
    } else {
        1.0
    }
}

/// ⌊log₂ x⌋ of a positive normal `f64` (every `f32` value, and every difference of two,
/// is one).
fn exponent(x: f64) -> i32 {
    ((x.to_bits() >> 52) & 0x7ff) as i32 - 1023
}

/// 2^e, for e in -1022..=1023.
fn pow2(e: i32) -> f64 {
    f64::from_bits(((e + 1023) as u64) << 52)
}

/// Quantise positions to `i16`. With `centre`, around the bounding-box centre (best
/// precision); otherwise around the origin.
pub fn quantize(positions: &[[f32; 3]], centre: bool) -> Quantized {
    let (lo, hi) = bounds(positions);
    // The centre in f64: lo + hi overflows f32 beyond ±f32::MAX / 2 (the result is
    // that of f32 arithmetic wherever that does not overflow).
    let mid = |k: usize| ((f64::from(lo[k]) + f64::from(hi[k])) * 0.5) as f32;
    let offset = if centre {
        [mid(0), mid(1), mid(2)]
    } else {
        [0.0; 3]
    };
    // Around the centre a position is at most half the extent away, within f32::MAX.
    let mut reach = 0.0f32;
    for p in positions {
        for k in 0..3 {
            reach = reach.max((p[k] - offset[k]).abs());
        }
    }
    let scale = if reach > 0.0 { reach / 32767.0 } else { 1.0 };
    let q = |v: f32| (v / scale).round().clamp(-32767.0, 32767.0) as i16;
    Quantized {
        positions: positions
            .iter()
            .map(|p| {
                [
                    q(p[0] - offset[0]),
                    q(p[1] - offset[1]),
                    q(p[2] - offset[2]),
                ]
            })
            .collect(),
        scale,
        offset,
    }
}

#[cfg(test)]
mod tests;
