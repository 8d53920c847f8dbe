//! Texture coordinates for a mesh: quantised to zraster's Q12 form
//! ([`zraster::texture::MeshUv`]) and the vertices split where faces that meet give a
//! position different coordinates (the renderer indexes one vertex table).

use std::collections::HashMap;

use zraster::texture::MeshUv;

use crate::{err, ObjError, ObjModel, ObjTriangle, MAX_VERTICES};

/// One vertex of a [`SplitVertices`] table: a position and the texture coordinates
/// the faces using it give it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SplitVertex {
    /// Index into [`ObjModel::positions`].
    pub position: u32,
    /// Texture coordinates in zraster's Q12 form (4096 is one texture, v down the
    /// image: 1 − OBJ's v); `None` for a vertex of untextured faces only (or of none).
    pub uv: Option<MeshUv>,
}

/// The vertex table of a textured mesh: one vertex for each combination of position
/// and texture coordinates the faces use.
///
/// Vertex `i` for `i < positions.len()` is position `i` with the coordinates of the
/// first face corner that uses it, so a model without seams keeps its vertex order;
/// the copies a seam needs follow, in order of first use.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct SplitVertices {
    /// The vertices.
    pub vertices: Vec<SplitVertex>,
    /// The triangles of [`ObjModel::triangles`], in order, as indices into `vertices`.
    pub triangles: Vec<[u32; 3]>,
    /// Vertices added at seams (`vertices.len() − positions.len()`).
    pub added: usize,
    /// Faces moved by whole textures to fit the Q12 range (invisible under repeat).
    pub moved_faces: usize,
    /// Faces spanning more than the Q12 range (8 textures): their coordinates clamped.
    pub clamped_faces: Vec<usize>,
    /// Texture coordinates of magnitude 2⁴⁰ or more: their place within the texture
    /// (the fraction) is below `f64` precision at the Q12 step.
    pub huge: usize,
}

impl SplitVertices {
    /// The triangles as `u16` indices (at most [`MAX_VERTICES`] vertices: every index
    /// fits).
    pub fn triangle_indices(&self) -> Vec<[u16; 3]> {
        self.triangles.iter().map(|t| t.map(|v| v as u16)).collect()
    }

    /// The texture coordinate table, `[0, 0]` for vertices without coordinates.
    pub fn uvs(&self) -> Vec<MeshUv> {
        self.vertices
            .iter()
            .map(|v| v.uv.unwrap_or([0, 0]))
            .collect()
    }
}

/// The most a Q12 coordinate holds: 8 textures less one step.
const Q12_MAX: f64 = 32767.0;

/// The coordinates of a face's three corners in Q12, v flipped to point down: moved by
/// whole textures where they would not fit ±8 otherwise (repeat does not see it),
/// clamped where the face spans more than that. Returns (coordinates, moved, clamped).
fn face_uvs(uv: [[f64; 2]; 3]) -> ([MeshUv; 3], bool, bool) {
    let (u, u_moved, u_clamped) = axis(uv.map(|c| c[0]));
    let (v, v_moved, v_clamped) = axis(uv.map(|c| 1.0 - c[1]));
    (
        [[u[0], v[0]], [u[1], v[1]], [u[2], v[2]]],
        u_moved || v_moved,
        u_clamped || v_clamped,
    )
}

/// One coordinate of a face's three corners in Q12 (see [`face_uvs`]).
fn axis(x: [f64; 3]) -> ([i16; 3], bool, bool) {
    let lo = x.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = x.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let q = |v: f64| (v * 4096.0).round();
    let shift = if q(lo) >= -32768.0 && q(hi) <= Q12_MAX {
        0.0
    } else {
        lo.floor()
    };
    let s = x.map(|v| q(v - shift));
    let clamped = s.iter().any(|&v| v > Q12_MAX);
    (
        s.map(|v| v.clamp(-32768.0, Q12_MAX) as i16),
        shift != 0.0,
        clamped,
    )
}

impl ObjModel {
    /// The vertex table with texture coordinates: every position once with the first
    /// coordinates a face gives it, then a copy for each other coordinates a face gives
    /// it (a texture seam). Only triangles for which `textured` is true carry their
    /// coordinates (`|t| t.texcoords.is_some()` for all that have them); the others'
    /// corners have none.
    ///
    /// The coordinates are quantised to Q12 (1/4096 of a texture) with v flipped
    /// (zraster's v points down the image), each face moved by whole textures when it
    /// does not fit ±8 textures as it is: exact under repeat, and so are coordinates of
    /// any size up to 2⁴⁰; beyond 2⁴⁰ `f64` itself no longer holds the fraction. A face
    /// spanning more than 8 textures is clamped (`clamped_faces` names their lines).
    ///
    /// Errors: more than [`MAX_VERTICES`] vertices once split.
    ///
    /// ```
    /// // Two triangles sharing an edge whose second vertex has u = 1 in one and u = 0
    /// // in the other (the seam of a wrapped texture): that position becomes two vertices.
    /// let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n\
    ///            f 1/1 2/2 3/3\nf 2/1 4/2 3/3\n";
    /// let model = zraster_obj::parse_obj(obj, |_| None)?;
    /// let split = model.split_vertices(|t| t.texcoords.is_some())?;
    /// assert_eq!(split.vertices.len(), 5);
    /// assert_eq!(split.triangles, [[0, 1, 2], [4, 3, 2]]);
    /// assert_eq!(split.vertices[1].uv, Some([4096, 4096])); // u = 1, v = 0 → 1 − 0
    /// assert_eq!((split.vertices[4].position, split.vertices[4].uv), (1, Some([0, 4096])));
    /// # Ok::<(), zraster_obj::ObjError>(())
    /// ```
    pub fn split_vertices(
        &self,
        textured: impl Fn(&ObjTriangle) -> bool,
    ) -> Result<SplitVertices, ObjError> {
        let n = self.positions.len();
        // The coordinates each position has as vertex `position` (None: not used yet).
        let mut first: Vec<Option<Option<MeshUv>>> = vec![None; n];
        let mut copies: HashMap<(u32, MeshUv), u32> = HashMap::new();
        let mut extra: Vec<SplitVertex> = Vec::new();
        let mut out = SplitVertices::default();
        for t in &self.triangles {
            let uvs = match t.texcoords.filter(|_| textured(t)) {
                Some(idx) => {
                    let uv = idx.map(|i| self.texcoords.get(i as usize).copied());
                    match uv {
                        [Some(a), Some(b), Some(c)] => {
                            let flat = [a, b, c];
                            out.huge += flat
                                .iter()
                                .flatten()
                                .filter(|x| x.abs() >= (1u64 << 40) as f64)
                                .count();
                            let (q, moved, clamped) = face_uvs(flat);
                            out.moved_faces += usize::from(moved);
                            if clamped {
                                out.clamped_faces.push(t.line);
                            }
                            q.map(Some)
                        }
                        _ => [None; 3],
                    }
                }
                None => [None; 3],
            };
            let mut tri = [0u32; 3];
            for k in 0..3 {
                let (p, uv) = (t.vertices[k], uvs[k]);
                let slot = first
                    .get_mut(p as usize)
                    .ok_or_else(|| err(t.line, format!("vertex index {} out of range", p + 1)))?;
                tri[k] = match (*slot, uv) {
                    (None, _) => {
                        *slot = Some(uv);
                        p
                    }
                    (Some(have), _) if have == uv => p,
                    // First used untextured: the textured corner gives it coordinates.
                    (Some(None), Some(_)) => {
                        *slot = Some(uv);
                        p
                    }
                    // An untextured corner of a textured position: any coordinates do.
                    (Some(_), None) => p,
                    (Some(_), Some(uv)) => match copies.get(&(p, uv)) {
                        Some(&v) => v,
                        None => {
                            let v = (n + extra.len()) as u32;
                            if n + extra.len() >= MAX_VERTICES {
                                return Err(err(
                                    t.line,
                                    format!(
                                        "more than {MAX_VERTICES} vertices once split at texture seams"
                                    ),
                                ));
                            }
                            extra.push(SplitVertex {
                                position: p,
                                uv: Some(uv),
                            });
                            copies.insert((p, uv), v);
                            v
                        }
                    },
                };
            }
            out.triangles.push(tri);
        }
        out.added = extra.len();
        out.vertices = first
            .iter()
            .enumerate()
            .map(|(p, uv)| SplitVertex {
                position: p as u32,
                uv: uv.flatten(),
            })
            .chain(extra)
            .collect();
        Ok(out)
    }
}
