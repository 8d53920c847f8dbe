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
//! It lives in its own crate because it allocates: zraster itself never does.

use std::collections::HashSet;
use std::fmt;
use std::io::Read;
use std::path::{Path, PathBuf};

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
    mut load_mtl: impl FnMut(&str) -> Result<String, String>,
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
                let mut idx: Vec<u32> = Vec::new();
                for t in toks {
                    let first = t.split('/').next().unwrap_or("");
                    let v: i64 = first
                        .parse()
                        .map_err(|_| err(line, format!("bad vertex reference {t:?}")))?;
                    let n = m.positions.len() as i64;
                    let resolved = match v {
                        0 => return Err(err(line, "vertex index 0 (OBJ indices start at 1)")),
                        v if v < 0 => n + v,
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
                        Ok(text) => parse_mtl(&text, &mut m.materials)
                            .map_err(|e| err(line, format!("in {name}: {e}")))?,
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
            _ => {}
        }
    }
    let n = m.positions.len();
    if let Some(t) = m
        .triangles
        .iter()
        .find(|t| t.vertices.iter().any(|&v| v as usize >= n))
    {
        let bad = t
            .vertices
            .iter()
            .find(|&&v| v as usize >= n)
            .copied()
            .unwrap_or(0);
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
            _ => {}
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
mod tests {
    use super::*;

    #[test]
    fn bounds_and_fit_scale() {
        let box_ = [[-1.0, 0.5, 2.0], [1.0, 0.0, 2.5], [0.0, -0.5, 2.25]];
        assert_eq!(bounds(&box_), ([-1.0, -0.5, 2.0], [1.0, 0.5, 2.5]));
        assert_eq!(fit_scale(&box_), 0.5); // largest extent 2 (x)
        assert_eq!(bounds(&[]), ([0.0; 3], [0.0; 3]));
        assert_eq!(fit_scale(&[]), 1.0);
        assert_eq!(fit_scale(&[[3.0, 3.0, 3.0]]), 1.0);
    }

    fn parse(s: &str) -> Result<ObjModel, ObjError> {
        parse_obj(s, |_| None)
    }

    /// A byte-order mark before the first statement is skipped: the first vertex is
    /// kept (it was dropped, and the face then referred to a missing vertex).
    #[test]
    fn a_byte_order_mark_is_skipped() {
        let m = parse("\u{feff}v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        assert_eq!(m.positions.len(), 3);
        assert_eq!(m.positions[0], [0.0, 0.0, 0.0]);
        let mut mats = Vec::new();
        parse_mtl("\u{feff}newmtl red\nKd 1 0 0\n", &mut mats).unwrap();
        assert_eq!(mats.len(), 1);
        assert_eq!(mats[0].name, "red");
    }

    #[test]
    fn faces_in_every_reference_form() {
        let m = parse("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1 2/2/2 3//3 -1\n").unwrap();
        assert_eq!(m.positions.len(), 4);
        let t: Vec<[u32; 3]> = m.triangles.iter().map(|t| t.vertices).collect();
        assert_eq!(t, [[0, 1, 2], [0, 2, 3]]);
        assert_eq!(m.triangle_indices(), [[0u16, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn materials_from_the_library() {
        let mtl = "newmtl red\nKd 1 0 0\nnewmtl half\nKd 0.5 0.5 0.5\n";
        let src =
            "mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl half\nf 1 2 3\nusemtl nope\nf 1 2 3\n";
        let m = parse_obj(src, |name| (name == "a.mtl").then(|| mtl.to_string())).unwrap();
        assert_eq!(m.materials[1].kd, [0.5; 3]);
        assert_eq!(m.triangles[0].material, Some(1));
        assert_eq!(m.triangles[1].material, None);
        assert_eq!(m.warnings.len(), 1);
    }

    #[test]
    fn malformed_lines_are_errors_with_their_line() {
        let cases = [
            ("v 1 2\n", 1, "missing z"),
            ("v 0 0 0\nv a 0 0\n", 2, "not a number"),
            ("v 0 0 nan\n", 1, "not finite"),
            ("v 0 inf 0\n", 1, "not finite"),
            ("v 0 0 0\nv -infinity 0 0\n", 2, "not finite"),
            // Beyond f32::MAX: it parses as ∞.
            ("v 1e39 0 0\n", 1, "not finite"),
            ("v 0 0 0\nv 0 0 0\nf 1 2\n", 3, "3 or more"),
            ("v 0 0 0\nf 1 2 9\n", 2, "out of range"),
            ("v 0 0 0\n\nf 0 1 1\n", 3, "index 0"),
            ("v 0 0 0\nf -5 1 1\n", 2, "out of range"),
            ("f 1/2 x 3\n", 1, "bad vertex"),
        ];
        for (src, line, what) in cases {
            let e = parse(src).unwrap_err();
            assert_eq!(e.line, line, "{src:?}: {e}");
            assert!(e.message.contains(what), "{src:?}: {e}");
        }
    }

    /// A library named again (on the same line or another) is asked for once.
    #[test]
    fn a_repeated_library_is_loaded_once() {
        let mut loads = Vec::new();
        let src = "mtllib a.mtl a.mtl\nmtllib b.mtl\nmtllib a.mtl b.mtl\nv 0 0 0\n";
        let m = parse_obj(src, |name| {
            loads.push(name.to_string());
            Some("newmtl red\nKd 1 0 0\n".into())
        })
        .unwrap();
        assert_eq!(loads, ["a.mtl", "b.mtl"]);
        assert_eq!(m.materials.len(), 2);
        // One that cannot be read: one warning, with the reason.
        let mut asked = 0;
        let m = parse_obj_with("mtllib x.mtl x.mtl\nmtllib x.mtl\n", |_| {
            asked += 1;
            Err("gone".into())
        })
        .unwrap();
        assert_eq!(asked, 1);
        assert_eq!(
            m.warnings,
            ["line 1: cannot read material library x.mtl: gone"]
        );
    }

    /// A scratch folder for one test.
    fn scratch(test: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("zraster-obj-{}-{test}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// Only regular files of at most MAX_MTL_BYTES are read: a device never ends, a FIFO
    /// blocks its reader forever (this test would hang), a large file is refused unread.
    #[test]
    #[cfg(unix)]
    fn the_loader_reads_only_regular_files_of_bounded_size() {
        let dir = scratch("loader-kinds");
        let mut mtl = MtlLoader::new(&dir);
        assert_eq!(mtl.load("/dev/zero"), Err("not a regular file".into()));
        assert_eq!(mtl.load("."), Err("not a regular file".into()));
        let made = std::process::Command::new("mkfifo")
            .arg(dir.join("pipe.mtl"))
            .status()
            .unwrap();
        assert!(made.success());
        assert_eq!(mtl.load("pipe.mtl"), Err("not a regular file".into()));
        // A sparse file one byte over the limit (no 16 MiB written).
        let big = std::fs::File::create(dir.join("big.mtl")).unwrap();
        big.set_len(MAX_MTL_BYTES + 1).unwrap();
        assert_eq!(mtl.load("big.mtl"), Err("larger than 16 MiB".into()));
        let at_limit = std::fs::File::create(dir.join("limit.mtl")).unwrap();
        at_limit.set_len(MAX_MTL_BYTES).unwrap();
        assert_eq!(mtl.load("limit.mtl").map(|t| t.len()), Ok(16 << 20));
        assert!(mtl.load("missing.mtl").is_err());
        std::fs::write(dir.join("latin1.mtl"), b"newmtl caf\xe9\n").unwrap();
        assert_eq!(mtl.load("latin1.mtl"), Err("not UTF-8 text".into()));
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// Each file is read once, whatever name reaches it; the text is the file's.
    #[test]
    #[cfg(unix)]
    fn the_loader_reads_each_file_once() {
        let dir = scratch("loader-once");
        std::fs::write(dir.join("red.mtl"), "\u{feff}newmtl red\nKd 1 0 0\n").unwrap();
        std::os::unix::fs::symlink(dir.join("red.mtl"), dir.join("alias.mtl")).unwrap();
        let mut mtl = MtlLoader::new(&dir);
        let src = "mtllib red.mtl ./red.mtl\nmtllib alias.mtl\nv 0 0 0\nusemtl red\n";
        let m = parse_obj_with(src, |name| mtl.load(name)).unwrap();
        assert_eq!(m.materials.len(), 1, "{:?}", m.materials);
        assert_eq!(m.materials[0].kd, [1.0, 0.0, 0.0]);
        assert!(m.warnings.is_empty(), "{:?}", m.warnings);
        assert_eq!(mtl.load("red.mtl"), Ok(String::new()));
        // By absolute path too.
        let abs = dir.join("red.mtl");
        assert_eq!(mtl.load(abs.to_str().unwrap()), Ok(String::new()));
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// fit_scale at the top of f32's range: the extent, 6e38, overflowed f32 and the
    /// scale was 0 (the model collapsed to a point).
    #[test]
    fn fit_scale_does_not_overflow_near_f32_max() {
        let huge = [[-3e38, -3e38, 0.0], [3e38, -3e38, 0.0], [0.0, 3e38, 0.0]];
        let s = fit_scale(&huge);
        assert!(s > 0.0 && s.is_finite(), "{s}");
        let s = fit_scale_f64(&huge);
        assert!((s * 6e38 - 1.0).abs() < 1e-7, "{s}");
        let max = [[-f32::MAX; 3], [f32::MAX; 3]];
        assert!((fit_scale_f64(&max) * 2.0 * f64::from(f32::MAX) - 1.0).abs() < 1e-7);
    }

    /// Where f32 arithmetic suffices, fit_scale is exactly what it always was.
    #[test]
    fn fit_scale_is_the_f32_quotient_where_that_is_normal() {
        let f32_fit = |p: &[[f32; 3]]| {
            let (lo, hi) = bounds(p);
            1.0 / (0..3).map(|k| hi[k] - lo[k]).fold(0.0f32, f32::max)
        };
        let boxes: [[[f32; 3]; 2]; 6] = [
            [[-0.0947, 0.0330, -0.0619], [0.0610, 0.1873, 0.0588]],
            [[-1.0, 0.5, 2.0], [1.0, 0.0, 2.5]],
            [[0.1, 0.2, 0.3], [0.7, 0.11, 0.3]],
            [[1e-30, 0.0, 0.0], [3e-30, 0.0, 0.0]],
            [[-3e37, 0.0, 0.0], [5e37, 1.0, 1.0]],
            [[123456.79, -7.0, 1e-3], [-98765.43, 3.0, 2.0]],
        ];
        for b in boxes {
            assert_eq!(fit_scale(&b).to_bits(), f32_fit(&b).to_bits(), "{b:?}");
            assert_eq!(fit_scale_f64(&b), f64::from(f32_fit(&b)), "{b:?}");
        }
    }

    /// A model 2^127 times larger (up to ±3e38) quantises to the same positions, with a
    /// scale exactly 2^127 larger, and fits with a scale exactly 2^127 smaller.
    #[test]
    fn a_model_scaled_by_a_power_of_two_quantises_and_fits_alike() {
        let small = [
            [-1.25f32, -1.0, 0.5],
            [1.5, -0.75, -0.25],
            [0.25, 1.75, 0.0],
            [0.0, 0.125, 1.0],
            [1.7, 1.7, 1.7],
        ];
        let k = 2f32.powi(127);
        let huge = small.map(|p| p.map(|v| v * k));
        for centre in [true, false] {
            let (a, b) = (quantize(&small, centre), quantize(&huge, centre));
            assert_eq!(a.positions, b.positions);
            assert_eq!(a.scale * k, b.scale);
            assert_eq!(a.offset.map(|o| o * k), b.offset);
        }
        assert_eq!(fit_scale_f64(&small), fit_scale_f64(&huge) * f64::from(k));
    }

    /// All positions above f32::MAX / 2: lo + hi overflowed, the centre was ∞ and every
    /// position quantised to -32767.
    #[test]
    fn quantisation_centres_boxes_near_f32_max() {
        let p = [[2e38, 3e38, 3.4e38], [3.4e38, 2.5e38, 3.3e38]];
        let q = quantize(&p, true);
        assert!(q.offset.iter().all(|o| o.is_finite()), "{:?}", q.offset);
        assert!(q.scale.is_finite());
        for (a, b) in p.iter().zip(&q.positions) {
            for k in 0..3 {
                let back = f64::from(b[k]) * f64::from(q.scale) + f64::from(q.offset[k]);
                let step = f64::from(q.scale);
                assert!((back - f64::from(a[k])).abs() <= step * 0.51, "{a:?} {b:?}");
            }
        }
        // The widest box: 2 × f32::MAX, half of it each side of the centre.
        let p = [[-f32::MAX, 0.0, 0.0], [f32::MAX - 2f32.powi(104), 1.0, 0.0]];
        let q = quantize(&p, true);
        assert!(q.scale.is_finite() && q.scale > 0.0);
        assert_eq!(q.positions[0][0], -32767);
        assert_eq!(q.positions[1][0], 32767);
    }

    #[test]
    fn quantisation_round_trips_within_half_a_step() {
        let p = [[-1.0, 2.0, 0.5], [3.0, -2.0, 0.25], [0.0, 0.0, 0.0]];
        let q = quantize(&p, true);
        for (a, b) in p.iter().zip(&q.positions) {
            for k in 0..3 {
                let back = f32::from(b[k]) * q.scale + q.offset[k];
                assert!((back - a[k]).abs() <= q.scale * 0.5 + 1e-6);
            }
        }
    }
}
