//! A Wavefront OBJ reader for zraster's host tools: the `render` example, the
//! `obj2rust` converter, the tests.
//!
//! Reads `v`, `vt` and `f` (with `v`, `v/vt`, `v/vt/vn`, `v//vn` and negative indices
//! for positions and texture coordinates alike), `mtllib` + `usemtl` with `Kd` colours,
//! `map_Kd` textures and `d`/`Tr` opacity; other statements are ignored. Errors name the
//! line. A UTF-8 byte-order mark at the start of an OBJ or MTL text is skipped.
//! [`MtlLoader`] reads the material libraries and their PNG textures from disk safely
//! (regular files of bounded size, each library once). [`quantize`] turns the
//! positions into the `i16` vertex table of a `zraster::mesh::Mesh`; [`fit_scale_f64`]
//! sizes any finite model, up to coordinates of ±`f32::MAX`.
//!
//! Textures: each face corner keeps its `vt` ([`ObjTriangle::texcoords`]);
//! [`ObjModel::split_vertices`] makes the one vertex table the renderer indexes, a
//! vertex for each position and texture coordinates, quantised to zraster's Q12
//! [`MeshUv`](zraster::texture::MeshUv); [`load_textures`] reads the materials'
//! `map_Kd` images (a texture that cannot be read is a warning, and its faces are
//! drawn in their `Kd` colour).
//!
//! [`to_rust`] turns a model into Rust source for a `const` mesh in flash (what the
//! `obj2rust` example prints), from a build script too, and says what it left out;
//! [`to_rust_textured`] adds the texture coordinates and textures.
//!
//! It lives in its own crate because it allocates: zraster itself never does.

use std::collections::HashSet;
use std::fmt;

mod image;
mod mtl;
mod to_rust;
mod uv;
pub use image::{
    decode_png, load_textures, rgb565, LoadedTexture, ModelTextures, ObjImage, MAX_TEXTURE_BYTES,
    MAX_TEXTURE_SIZE,
};
pub use mtl::{parse_mtl, MtlLoader, ObjMaterial, TextureMap, MAX_MTL_BYTES};
pub use to_rust::{rust_prefix, to_rust, to_rust_textured, RustForm, RustMesh, RustOptions};
pub use uv::{SplitVertex, SplitVertices};

/// One triangle of the model (polygons are fan-triangulated while reading).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ObjTriangle {
    /// Vertex indices (0-based), counter-clockwise from the front.
    pub vertices: [u32; 3],
    /// Texture coordinate indices (0-based, into [`ObjModel::texcoords`]) of the
    /// three corners, when the face gives every corner one.
    pub texcoords: Option<[u32; 3]>,
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
    /// The `vt` statements: u and v as written (OBJ's v points up), as `f64` so that
    /// large coordinates keep their fraction.
    pub texcoords: Vec<[f64; 2]>,
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
    /// `vt` statements with a third (w) coordinate, which is dropped.
    pub texcoord_w: usize,
    /// Faces giving texture coordinates to some corners but not all: they are kept
    /// without texture coordinates.
    pub mixed_faces: usize,
    /// OBJ statements the reader does not use (`o`, `g`, `s`, `l`, ...), by keyword in
    /// order of first appearance (at most [`MAX_SKIPPED_KINDS`] kinds; the rest are
    /// counted in `skipped_other`).
    pub skipped: Vec<Skipped>,
    /// MTL statements the reader does not use (`Ka`, `Ks`, `map_Ks`, ...), alike; their
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

/// A texture coordinate: any finite number (as `f64`, which keeps the fraction of
/// coordinates up to 2⁴⁰ to 1/4096); NaN and infinities are errors.
fn number64(tok: Option<&str>, line: usize, what: &str) -> Result<f64, ObjError> {
    let tok = tok.ok_or_else(|| err(line, format!("missing {what}")))?;
    let v: f64 = tok
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

/// The most `vt` statements a model may have.
pub const MAX_TEXCOORDS: usize = 1 << 20;

/// One `f` statement: its corners' vertex indices and, when every corner gives one,
/// their texture coordinate indices (0-based; forward references stay unchecked), and
/// whether some corners gave one and others not.
type Face = (Vec<u32>, Option<Vec<u32>>, bool);

/// A 1-based (or negative, relative) OBJ index to a 0-based one below `max`.
fn resolve(tok: &str, count: usize, max: usize, line: usize, what: &str) -> Result<u32, ObjError> {
    let i: i64 = tok
        .parse()
        .map_err(|_| err(line, format!("bad {what} reference {tok:?}")))?;
    let resolved = match i {
        0 => {
            return Err(err(
                line,
                format!("{what} index 0 (OBJ indices start at 1)"),
            ))
        }
        i if i < 0 => count as i64 + i,
        i => i - 1,
    };
    if resolved < 0 || resolved >= max as i64 {
        return Err(err(line, format!("{what} index {i} out of range")));
    }
    Ok(resolved as u32)
}

/// One `f` statement (see [`Face`]); `n` and `nt` are the positions and texture
/// coordinates read so far.
fn face(
    toks: std::str::SplitWhitespace<'_>,
    line: usize,
    n: usize,
    nt: usize,
) -> Result<Face, ObjError> {
    let mut idx: Vec<u32> = Vec::new();
    let mut tex: Vec<u32> = Vec::new();
    for t in toks {
        let mut parts = t.split('/');
        let first = parts.next().unwrap_or("");
        idx.push(resolve(first, n, MAX_VERTICES, line, "vertex")?);
        match parts.next() {
            Some(vt) if !vt.is_empty() => {
                tex.push(resolve(vt, nt, MAX_TEXCOORDS, line, "texture coordinate")?)
            }
            _ => {}
        }
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
    let mixed = !tex.is_empty() && tex.len() != idx.len();
    let tex = (tex.len() == idx.len()).then_some(tex);
    Ok((idx, tex, mixed))
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
            "vt" => {
                let u = number64(toks.next(), line, "u")?;
                let v = match toks.next() {
                    Some(t) => number64(Some(t), line, "v")?,
                    None => 0.0,
                };
                if toks.next().is_some() {
                    m.notes.texcoord_w += 1;
                }
                if m.texcoords.len() >= MAX_TEXCOORDS {
                    return Err(err(
                        line,
                        format!("more than {MAX_TEXCOORDS} texture coordinates"),
                    ));
                }
                m.texcoords.push([u, v]);
            }
            "f" => {
                let (idx, tex, mixed) = match face(toks, line, m.positions.len(), m.texcoords.len())
                {
                    Ok(f) => f,
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
                if mixed {
                    m.notes.mixed_faces += 1;
                    if m.notes.mixed_faces <= MAX_BAD_FACE_WARNINGS {
                        m.warnings.push(format!(
                            "line {line}: some corners of the face have `vt` texture coordinates and some not: it is kept without"
                        ));
                    }
                }
                // Fanned from the first corner; texture coordinates with their corners.
                for k in 1..idx.len().saturating_sub(1) {
                    m.triangles.push(ObjTriangle {
                        vertices: [idx[0], idx[k], idx[k + 1]],
                        texcoords: tex.as_ref().map(|t| [t[0], t[k], t[k + 1]]),
                        material: current,
                        line,
                    });
                }
            }
            "mtllib" => {
                for name in toks {
                    if !libraries.insert(name) {
                        continue;
                    }
                    match load_mtl(name) {
                        Ok(text) => {
                            let mut notes = mtl::MtlNotes {
                                skipped: &mut m.notes.skipped_mtl,
                                other: &mut m.notes.skipped_other,
                                warnings: &mut m.warnings,
                            };
                            mtl::parse_mtl_noting(&text, &mut m.materials, line, name, &mut notes)
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
            kw => ReadNotes::skip(&mut m.notes.skipped, &mut m.notes.skipped_other, kw, line),
        }
    }
    if m.notes.mixed_faces > MAX_BAD_FACE_WARNINGS {
        m.warnings.push(format!(
            "{} faces in all kept without texture coordinates (some corners without `vt`)",
            m.notes.mixed_faces
        ));
    }
    let (n, nt) = (m.positions.len(), m.texcoords.len());
    // What is wrong with a triangle's (forward) references, if anything.
    let out_of_range = |t: &ObjTriangle| {
        if let Some(v) = t.vertices.iter().find(|&&v| v as usize >= n) {
            return Some(format!(
                "vertex index {} out of range (the file has {n} vertices)",
                v + 1
            ));
        }
        let vt = t.texcoords?.into_iter().find(|&i| i as usize >= nt)?;
        Some(format!(
            "texture coordinate index {} out of range (the file has {nt} texture coordinates)",
            vt + 1
        ))
    };
    if lenient {
        // Whole faces go: every triangle of a line with a bad one.
        let mut bad_lines: Vec<(usize, String)> = Vec::new();
        for t in &m.triangles {
            if let Some(why) = out_of_range(t) {
                if bad_lines.last().is_none_or(|(l, _)| *l != t.line) {
                    bad_lines.push((t.line, why));
                }
            }
        }
        if !bad_lines.is_empty() {
            let lines: HashSet<usize> = bad_lines.iter().map(|(l, _)| *l).collect();
            m.triangles.retain(|t| !lines.contains(&t.line));
            for (line, why) in bad_lines {
                bad_face(&mut m, err(line, why));
            }
        }
        if m.notes.bad_faces > MAX_BAD_FACE_WARNINGS {
            m.warnings.push(format!(
                "{} more faces skipped ({} in all)",
                m.notes.bad_faces - MAX_BAD_FACE_WARNINGS,
                m.notes.bad_faces
            ));
        }
    } else if let Some((line, why)) = m
        .triangles
        .iter()
        .find_map(|t| out_of_range(t).map(|why| (t.line, why)))
    {
        return Err(err(line, why));
    }
    Ok(m)
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
#[cfg(test)]
mod texture_tests;
