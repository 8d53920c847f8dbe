//! A Wavefront OBJ reader for zraster's host tools: the `render` example, the
//! `obj2rust` converter, the tests.
//!
//! Reads `v` and `f` (with `v`, `v/vt`, `v/vt/vn`, `v//vn` and negative indices),
//! `mtllib` + `usemtl` with `Kd` colours; other statements are ignored. Errors name the
//! line. [`quantize`] turns the positions into the `i16` vertex table of a
//! `zraster::mesh::Mesh`.
//!
//! It lives in its own crate because it allocates: zraster itself never does.

use std::fmt;

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
    let mut m = ObjModel::default();
    let mut current: Option<usize> = None;
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
                    match load_mtl(name) {
                        Some(text) => parse_mtl(&text, &mut m.materials)
                            .map_err(|e| err(line, format!("in {name}: {e}")))?,
                        None => m
                            .warnings
                            .push(format!("line {line}: cannot read material library {name}")),
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
/// box is a point or there are no positions).
pub fn fit_scale(positions: &[[f32; 3]]) -> f32 {
    let (lo, hi) = bounds(positions);
    let extent = (0..3).map(|k| hi[k] - lo[k]).fold(0.0f32, f32::max);
    if extent > 0.0 {
        1.0 / extent
    } else {
        1.0
    }
}

/// Quantise positions to `i16`. With `centre`, around the bounding-box centre (best
/// precision); otherwise around the origin.
pub fn quantize(positions: &[[f32; 3]], centre: bool) -> Quantized {
    let (lo, hi) = bounds(positions);
    let offset = if centre {
        [
            (lo[0] + hi[0]) * 0.5,
            (lo[1] + hi[1]) * 0.5,
            (lo[2] + hi[2]) * 0.5,
        ]
    } else {
        [0.0; 3]
    };
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
