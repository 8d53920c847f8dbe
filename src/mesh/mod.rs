//! Meshes: a vertex table and a face table (the classic "vertex list" polygon model), in borrowed (flash-friendly) slices.

use embedded_graphics::pixelcolor::Rgb888;

use crate::error::prefix_mut;

mod quantize;
use crate::math::Vec3;
use crate::shade::Shading;
use crate::Error;
pub use quantize::{quantize, Quantized};

/// One polygon of the face table: three or more vertex indices and a material.
///
/// Vertices are listed counter-clockwise as seen from the front (as in OBJ files and
/// OpenGL); polygons are drawn as a fan around their first vertex, so they should be
/// convex and planar.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Face<'a, M> {
    /// Indices into the vertex table.
    pub vertices: &'a [u16],
    /// The face's material (for `Rgb888`, its colour).
    pub material: M,
}

/// How faces get their materials in a triangle list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Materials<'a, M> {
    /// Every face has this material.
    Uniform(M),
    /// One material per face.
    PerFace(&'a [M]),
}

/// The face table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Faces<'a, M> {
    /// Polygons of any size, each with its own material (as [`CUBE`]).
    Polygons(&'a [Face<'a, M>]),
    /// Triangles (compact: 6 bytes a face).
    Triangles {
        /// Three vertex indices per triangle, counter-clockwise from the front.
        indices: &'a [[u16; 3]],
        /// Their materials.
        materials: Materials<'a, M>,
    },
}

/// A mesh: a vertex table of quantised positions and a face table.
///
/// A model-space position is `positions[i] × scale`. Quantising to `i16` keeps a
/// vertex in 6 bytes of flash with 1/65536 of the model's extent as the step. The
/// optional normal tables hold unit vectors in Q14 (16384 = 1.0); without them the
/// renderer computes face normals from the positions when lighting needs them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mesh<'a, M = Rgb888> {
    /// The vertex table.
    pub positions: &'a [[i16; 3]],
    /// Model units per position step.
    pub scale: f32,
    /// The face table.
    pub faces: Faces<'a, M>,
    /// Optional unit face normals (Q14), one per face.
    pub face_normals: Option<&'a [[i16; 3]]>,
    /// Optional unit vertex normals (Q14), one per vertex, for Gouraud lighting.
    pub vertex_normals: Option<&'a [[i16; 3]]>,
}

/// Q14 fixed point: 16384 = 1.0.
pub const NORMAL_ONE: i32 = 1 << 14;

/// The rule for a mesh's `scale`, checked by [`Mesh::validate`], [`Mesh::check_for`]
/// and [`quantize`] alike: finite ([`Error::NotFinite`] otherwise, as for every other
/// `f32` input) and positive ([`Error::InvalidParameter`]`(`[`SCALE_RULE`]`)`). A
/// negative scale would mirror the mesh and turn every face's winding, so culling would
/// hide the wrong faces; zero collapses it to a point.
pub const fn check_scale(scale: f32) -> Result<(), Error> {
    if !scale.is_finite() {
        Err(Error::NotFinite)
    } else if scale > 0.0 {
        Ok(())
    } else {
        Err(Error::InvalidParameter(SCALE_RULE))
    }
}

/// The message of the [`Error::InvalidParameter`] that [`check_scale`] returns for a
/// scale of zero or below.
pub const SCALE_RULE: &str = "mesh scale must be finite and positive";

impl<'a, M: Copy> Mesh<'a, M> {
    /// A mesh of polygons, without normal tables.
    pub const fn new(positions: &'a [[i16; 3]], scale: f32, faces: &'a [Face<'a, M>]) -> Self {
        Mesh {
            positions,
            scale,
            faces: Faces::Polygons(faces),
            face_normals: None,
            vertex_normals: None,
        }
    }

    /// A mesh of triangles, all of one material, without normal tables.
    pub const fn triangles(
        positions: &'a [[i16; 3]],
        scale: f32,
        indices: &'a [[u16; 3]],
        material: M,
    ) -> Self {
        Mesh {
            positions,
            scale,
            faces: Faces::Triangles {
                indices,
                materials: Materials::Uniform(material),
            },
            face_normals: None,
            vertex_normals: None,
        }
    }

    /// The same mesh with face and/or vertex normal tables.
    pub const fn with_normals(
        mut self,
        face_normals: Option<&'a [[i16; 3]]>,
        vertex_normals: Option<&'a [[i16; 3]]>,
    ) -> Self {
        self.face_normals = face_normals;
        self.vertex_normals = vertex_normals;
        self
    }

    /// The number of faces.
    pub fn face_count(&self) -> usize {
        match self.faces {
            Faces::Polygons(f) => f.len(),
            Faces::Triangles { indices, .. } => indices.len(),
        }
    }

    /// Face `i`: its vertex indices and material. `None` when there is no face `i`, or
    /// (for `Materials::PerFace`) no material for it.
    pub fn face(&self, i: usize) -> Option<(&'a [u16], M)> {
        match self.faces {
            Faces::Polygons(f) => f.get(i).map(|f| (f.vertices, f.material)),
            Faces::Triangles { indices, materials } => {
                let t = indices.get(i)?;
                let m = match materials {
                    Materials::Uniform(m) => m,
                    Materials::PerFace(ms) => *ms.get(i)?,
                };
                Some((t.as_slice(), m))
            }
        }
    }

    /// The model-space position of vertex `i`. Out of line without an FPU, where it is
    /// six float calls.
    #[cfg_attr(zraster_soft_float, inline(never))]
    pub fn position(&self, i: usize) -> Option<Vec3> {
        let p = self.positions.get(i)?;
        Some(Vec3::new(f32::from(p[0]), f32::from(p[1]), f32::from(p[2])) * self.scale)
    }

    /// The box around every vertex, in model units: its lowest and highest corners.
    /// `None` for a mesh without vertices (or with a scale that is not finite). For
    /// [`Camera::fit_depth`](crate::camera::Camera::fit_depth).
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let first = self.positions.first()?;
        let (mut lo, mut hi) = (*first, *first);
        for p in self.positions {
            for ((l, h), &c) in lo.iter_mut().zip(hi.iter_mut()).zip(p) {
                *l = (*l).min(c);
                *h = (*h).max(c);
            }
        }
        let v = |a: [i16; 3]| Vec3::new(f32::from(a[0]), f32::from(a[1]), f32::from(a[2]));
        let (a, b) = (v(lo) * self.scale, v(hi) * self.scale);
        // A negative scale swaps the corners.
        let lo = Vec3::new(a.x.min(b.x), a.y.min(b.y), a.z.min(b.z));
        let hi = Vec3::new(a.x.max(b.x), a.y.max(b.y), a.z.max(b.z));
        (lo.is_finite() && hi.is_finite()).then_some((lo, hi))
    }

    /// Check every table: indices in range, polygons of three or more vertices, one
    /// material and one normal per face, one normal per vertex, a finite positive scale.
    ///
    /// The renderer checks faces as it draws them too (and returns the same errors), so
    /// calling this is optional; it reports a problem before anything is drawn.
    pub fn validate(&self) -> Result<(), Error> {
        self.check_tables()?;
        let n = self.face_count();
        for i in 0..n {
            let (vs, _) = self
                .face(i)
                .ok_or(Error::CapacityExceeded { capacity: i })?;
            if vs.len() < 3 {
                return Err(Error::DegenerateFace { face: i });
            }
            if let Some(&bad) = vs.iter().find(|&&v| usize::from(v) >= self.positions.len()) {
                return Err(Error::IndexOutOfRange {
                    face: i,
                    index: usize::from(bad),
                });
            }
        }
        Ok(())
    }

    /// What a renderer checks of a mesh before drawing it with `shading`, in a few
    /// comparisons (no walk over the tables): the [scale rule](check_scale), normal
    /// tables as long as their faces and vertices, and vertex normals for
    /// [`Shading::Gouraud`] ([`Error::MissingNormals`]: without them every vertex would
    /// be fully lit, the mesh drawn unlit; [`compute_vertex_normals`] makes them).
    ///
    /// ```
    /// use zraster::{mesh::{compute_vertex_normals, CUBE}, math::Vec3, shade::Shading, Error};
    /// assert_eq!(CUBE.check_for(Shading::Lambert), Ok(())); // face normals from the positions
    /// assert_eq!(CUBE.check_for(Shading::Gouraud), Err(Error::MissingNormals));
    /// let (mut scratch, mut normals) = ([Vec3::default(); 8], [[0i16; 3]; 8]);
    /// compute_vertex_normals(&CUBE, &mut scratch, &mut normals)?;
    /// assert_eq!(CUBE.with_normals(None, Some(&normals)).check_for(Shading::Gouraud), Ok(()));
    /// # Ok::<(), Error>(())
    /// ```
    pub fn check_for(&self, shading: Shading) -> Result<(), Error> {
        self.check_tables()?;
        if shading == Shading::Gouraud && self.vertex_normals.is_none() {
            return Err(Error::MissingNormals);
        }
        Ok(())
    }

    /// Check a texture-coordinate table for this mesh: one [`MeshUv`] per vertex at
    /// least (what [`Renderer::draw_textured`](crate::Renderer::draw_textured) checks
    /// before drawing, besides [`check_for`](Mesh::check_for)).
    ///
    /// Texture coordinates live beside the mesh, not in it (a [`Texturing`] holds them
    /// with the texture), so that meshes in flash written before textures, and the
    /// `Mesh { .. }` literals `obj2rust` writes, stay as they are.
    ///
    /// Errors: [`Error::InvalidParameter`] for a table shorter than the vertex table.
    ///
    /// [`MeshUv`]: crate::texture::MeshUv
    /// [`Texturing`]: crate::Texturing
    pub fn check_uvs(&self, uvs: &[crate::texture::MeshUv]) -> Result<(), Error> {
        if uvs.len() < self.positions.len() {
            return Err(Error::InvalidParameter(
                "fewer texture coordinates than vertices",
            ));
        }
        Ok(())
    }

    /// The scale rule and the lengths of the normal tables.
    fn check_tables(&self) -> Result<(), Error> {
        check_scale(self.scale)?;
        if self
            .face_normals
            .is_some_and(|f| f.len() < self.face_count())
        {
            return Err(Error::InvalidParameter("fewer face normals than faces"));
        }
        if self
            .vertex_normals
            .is_some_and(|v| v.len() < self.positions.len())
        {
            return Err(Error::InvalidParameter(
                "fewer vertex normals than vertices",
            ));
        }
        Ok(())
    }
}

/// The unit cube of the classic back-face culling example: positions are 0 or 16384 (scale 1/16384, so the cube spans
/// 0..1), vertices a–h in that example's order.
pub const CUBE_POSITIONS: [[i16; 3]; 8] = {
    const S: i16 = 16384;
    [
        [0, 0, 0], // a
        [S, 0, 0], // b
        [S, 0, S], // c
        [0, 0, S], // d
        [0, S, 0], // e
        [S, S, 0], // f
        [S, S, S], // g
        [0, S, S], // h
    ]
};

/// Its face table, in the example's order: bottom, right, front, left, back, top.
///
/// Each face lists its vertices counter-clockwise as seen from outside the cube in a
/// right-handed model space, which is the front-face convention of OBJ and OpenGL that
/// the renderer uses.
pub const CUBE_FACES: [Face<'static, Rgb888>; 6] = [
    Face {
        vertices: &[0, 1, 2, 3],
        material: Rgb888::new(255, 0, 0),
    }, // bottom a b c d: red
    Face {
        vertices: &[1, 5, 6, 2],
        material: Rgb888::new(0, 255, 0),
    }, // right b f g c: green
    Face {
        vertices: &[2, 6, 7, 3],
        material: Rgb888::new(0, 0, 255),
    }, // front c g h d: blue
    Face {
        vertices: &[3, 7, 4, 0],
        material: Rgb888::new(255, 255, 0),
    }, // left d h e a: yellow
    Face {
        vertices: &[0, 4, 5, 1],
        material: Rgb888::new(128, 0, 128),
    }, // back a e f b: purple
    Face {
        vertices: &[7, 6, 5, 4],
        material: Rgb888::new(0, 255, 255),
    }, // top h g f e: light blue
];

/// That cube as a ready mesh (spanning 0..1 on each axis).
pub const CUBE: Mesh<'static, Rgb888> = Mesh::new(&CUBE_POSITIONS, 1.0 / 16384.0, &CUBE_FACES);

/// Compute unit face normals (Q14) of `mesh` into `out` (one per face), from the first
/// three vertices of each face. Zero-area faces get a zero normal.
pub fn compute_face_normals<M: Copy>(
    mesh: &Mesh<'_, M>,
    out: &mut [[i16; 3]],
) -> Result<(), Error> {
    mesh.validate()?;
    let n = mesh.face_count();
    let out = prefix_mut(out, n)?;
    for (i, o) in out.iter_mut().enumerate() {
        *o = quantize_normal(face_normal(mesh, i).unwrap_or_default());
    }
    Ok(())
}

/// Compute unit vertex normals (Q14) of `mesh` into `out` (one per vertex): the
/// area-weighted average of the normals of the faces around each vertex. `scratch` needs
/// one `Vec3` per vertex.
pub fn compute_vertex_normals<M: Copy>(
    mesh: &Mesh<'_, M>,
    scratch: &mut [Vec3],
    out: &mut [[i16; 3]],
) -> Result<(), Error> {
    mesh.validate()?;
    let nv = mesh.positions.len();
    let acc = prefix_mut(scratch, nv)?;
    let out = prefix_mut(out, nv)?;
    acc.fill(Vec3::default());
    for f in 0..mesh.face_count() {
        let Some((vs, _)) = mesh.face(f) else {
            continue;
        };
        // Unnormalised cross product: its length is twice the area (area weighting).
        let n = face_normal_raw(mesh, vs).unwrap_or_default();
        for &v in vs {
            if let Some(a) = acc.get_mut(usize::from(v)) {
                *a = *a + n;
            }
        }
    }
    for (o, a) in out.iter_mut().zip(acc.iter()) {
        *o = quantize_normal(a.normalize());
    }
    Ok(())
}

/// The unit normal of face `i` in model space.
pub(crate) fn face_normal<M: Copy>(mesh: &Mesh<'_, M>, i: usize) -> Option<Vec3> {
    let (vs, _) = mesh.face(i)?;
    Some(face_normal_raw(mesh, vs)?.normalize())
}

fn face_normal_raw<M: Copy>(mesh: &Mesh<'_, M>, vs: &[u16]) -> Option<Vec3> {
    let p = |k: usize| mesh.position(usize::from(*vs.get(k)?));
    let (a, b, c) = (p(0)?, p(1)?, p(2)?);
    Some((b - a).cross(c - a))
}

/// A unit vector in Q14.
pub(crate) fn quantize_normal(n: Vec3) -> [i16; 3] {
    let q = |v: f32| crate::num::round_f32(v.clamp(-1.0, 1.0) * NORMAL_ONE as f32) as i16;
    [q(n.x), q(n.y), q(n.z)]
}

#[cfg(test)]
mod tests;
