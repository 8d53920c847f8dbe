//! A model for `render`: an OBJ file with its materials and textures, quantised into
//! zraster meshes. Faces without a texture form one mesh over the file's positions;
//! the faces of each texture form another over the positions split at texture seams
//! (zraster indexes one vertex table for positions and texture coordinates).

use std::path::Path;

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use zraster::{
    math::{Mat4, Vec3},
    mesh::{compute_face_normals, compute_vertex_normals, Faces, Materials, Mesh},
    shade::{DisplayColor, Intensity, Material, Packed565, Translucent, ONE},
    texture::{MeshUv, Texture, Wrap},
    Texturing, UvMode,
};
use zraster_obj::{fit_scale_f64, load_textures, parse_obj_with, quantize, MtlLoader, ObjModel};

/// A face colour as the contract states it: `Kd × I`, rounded to RGB565 exactly; and
/// its opacity (MTL `d`, 255 opaque): see-through faces are drawn after the opaque
/// ones, blended over them. `SEE_THROUGH` says whether the type may be see-through:
/// `Kd<false>` for models without a `d` below 1 spares every face the alpha test.
/// The third field is [`exact_rgb888`] of the `Kd`: where that is `Some`, zraster's
/// packed 5-6-5 path (the same colour at every intensity) lights the faces.
#[derive(Clone, Copy)]
pub struct Kd<const SEE_THROUGH: bool = true>(pub [f32; 3], pub u8, pub Option<Rgb888>);

/// The `Rgb888` whose lit 5-6-5 colour is `Kd × I` rounded at every intensity `I`,
/// if there is one (checked at all 65,536 intensities): then zraster's integer lit
/// path draws the faces, faster than `Kd::shade` in `f32`, and the picture is the same.
pub fn exact_rgb888(kd: [f32; 3]) -> Option<Rgb888> {
    let v = kd.map(|c| (c * 255.0).round());
    if !v.iter().all(|v| (0.0..=255.0).contains(v)) {
        return None;
    }
    let m = Rgb888::new(v[0] as u8, v[1] as u8, v[2] as u8);
    let k = Kd::<false>(kd, 255, None);
    (0..=u16::MAX)
        .all(|i| k.shade(i, 0, 0) == <Rgb565 as DisplayColor>::lit(m, i, 0, 0))
        .then_some(m)
}

impl<const SEE_THROUGH: bool> Material<Rgb565> for Kd<SEE_THROUGH> {
    const TRANSLUCENT: bool = SEE_THROUGH;

    fn shade(&self, i: Intensity, _x: i32, _y: i32) -> Rgb565 {
        let i = f32::from(i) / f32::from(ONE);
        let q = |c: f32, max: f32| ((c * i * max + 0.5) as u32).min(max as u32) as u8;
        Rgb565::new(q(self.0[0], 31.0), q(self.0[1], 63.0), q(self.0[2], 31.0))
    }

    fn packed_565(&self) -> Option<Packed565<Rgb565>> {
        self.2.and_then(<Rgb565 as DisplayColor>::packed_565)
    }

    fn alpha(&self) -> u8 {
        self.1
    }

    fn blend(&self, dst: Rgb565, src: Rgb565, x: i32, y: i32) -> Rgb565 {
        <Rgb565 as DisplayColor>::blend(dst, src, self.1, x, y)
    }
}

/// A material type `render` draws with: [`Kd`] see-through capable or not, each with
/// its table in a [`Part`].
pub trait Colours: Material<Rgb565> + Copy {
    /// The colours of `part`'s faces.
    fn of(part: &Part) -> &[Self];
}

impl Colours for Kd<true> {
    fn of(part: &Part) -> &[Self] {
        &part.materials
    }
}

impl Colours for Kd<false> {
    fn of(part: &Part) -> &[Self] {
        &part.opaque
    }
}

/// Faces drawn as one mesh: their vertex table (shared or split), corners, colours
/// and normals, and the texture they are drawn with, if any.
pub struct Part {
    /// Which vertex table of the [`Model`]: the file's (`false`) or the split one.
    split: bool,
    pub indices: Vec<[u16; 3]>,
    materials: Vec<Kd>,
    /// The same colours as an opaque type (`d` ignored).
    opaque: Vec<Kd<false>>,
    /// Whether every face has the same colour and opacity: then the mesh's material is
    /// uniform, which zraster lights without a table look-up a face.
    uniform: bool,
    face_normals: Vec<[i16; 3]>,
    /// The texture (8-bit texels as the PNG has them, lit as a `Kd` of their value
    /// is), its size and wrap.
    texture: Option<(Vec<Rgb888>, u32, u32, Wrap)>,
}

/// A model read from an OBJ file, ready to draw.
pub struct Model {
    /// Positions as read (quantised), and split at texture seams (with the split
    /// vertices' texture coordinates).
    positions: Vec<[i16; 3]>,
    split_positions: Vec<[i16; 3]>,
    uvs: Vec<MeshUv>,
    /// Model units per position step.
    scale: f32,
    /// Vertex normals over all faces, for each vertex table.
    vertex_normals: Vec<[i16; 3]>,
    split_normals: Vec<[i16; 3]>,
    /// Every face, untextured, over the file's positions (painter, hidden-line and
    /// wireframe draw it).
    pub all: Part,
    /// For the Z-buffer: the untextured faces, then each texture's faces.
    pub parts: Vec<Part>,
    /// Model space → fitted (`--fit`: centred, largest extent 1) or raw coordinates.
    pub place: Mat4,
    /// The bounding box of the positions, in model space.
    pub bounds: Option<(Vec3, Vec3)>,
}

impl Model {
    /// Read `path`: its materials from its folder, textures for faces with `vt`
    /// coordinates; `color` for faces without a material. Warnings (a library or
    /// texture that cannot be read, skipped statements) go to `warn`; `Err` says what
    /// is wrong with the file.
    pub fn load(
        path: &str,
        color: [f32; 3],
        fit: bool,
        gouraud: bool,
        warn: &mut dyn FnMut(String),
    ) -> Result<Model, String> {
        let bytes = std::fs::read(path).map_err(|e| format!("{path}: {e}"))?;
        let text = String::from_utf8(bytes).map_err(|_| format!("{path}: not a text file"))?;
        let dir = Path::new(path)
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default();
        let mut libraries = MtlLoader::new(&dir);
        let obj = parse_obj_with(&text, |name| libraries.load(name))
            .map_err(|e| format!("{path}: {e}"))?;
        for w in &obj.warnings {
            warn(format!("{path}: {w}"));
        }
        if obj.triangles.is_empty() {
            return Err(format!("{path}: no faces"));
        }
        let mut notes = Vec::new();
        let textures = load_textures(&obj, |p| libraries.load_texture(p), &mut notes);
        for w in notes {
            warn(format!("{path}: {w}"));
        }
        Model::build(&obj, &textures, color, fit, gouraud).map_err(|e| format!("{path}: {e}"))
    }

    fn build(
        obj: &ObjModel,
        textures: &zraster_obj::ModelTextures,
        color: [f32; 3],
        fit: bool,
        gouraud: bool,
    ) -> Result<Model, String> {
        let q = quantize(&obj.positions, true);
        // The mesh's position scale is q.scale times 2^-k, and the placement takes 2^k
        // back. k is 0 unless the model reaches beyond 2^±16: then its normals' cross
        // and dot products (the fourth power of its size) would overflow or vanish in
        // f32, and a fit below f32's normal range would lose precision. k then brings
        // the positions to about ±2^8. A power of two scales f32 arithmetic exactly, so
        // the image is exactly that of the model scaled by 2^-k (drawn with k = 0).
        let k = balance_exponent(q.scale);
        let scale = (f64::from(q.scale) * pow2(-k)) as f32;
        // Opacity d rounded to 1/255 as zraster rounds it (NaN opaque).
        let exact: Vec<_> = obj.materials.iter().map(|m| exact_rgb888(m.kd)).collect();
        let exact_color = exact_rgb888(color);
        let kd = |t: &zraster_obj::ObjTriangle| match t.material {
            Some(m) => {
                let (kd, d) = (obj.materials[m].kd, obj.materials[m].alpha);
                Kd(
                    kd,
                    Translucent::from_opacity(Rgb888::new(0, 0, 0), d).alpha,
                    exact[m],
                )
            }
            None => Kd(color, 255, exact_color),
        };
        let all = Part {
            split: false,
            indices: obj.triangle_indices(),
            materials: obj.triangles.iter().map(kd).collect(),
            face_normals: Vec::new(),
            texture: None,
            opaque: Vec::new(),
            uniform: false,
        };
        let mut model = Model {
            positions: q.positions.clone(),
            split_positions: Vec::new(),
            uvs: Vec::new(),
            scale,
            vertex_normals: vec![[0; 3]; q.positions.len()],
            split_normals: Vec::new(),
            all,
            parts: Vec::new(),
            place: Mat4::default(),
            bounds: None,
        };
        // Vertex normals over every face, so that seams split for textures stay smooth.
        if gouraud {
            let mut scratch = vec![Vec3::default(); q.positions.len()];
            let mesh = model.mesh::<Kd>(&model.all);
            let mut normals = vec![[0; 3]; q.positions.len()];
            compute_vertex_normals(&mesh, &mut scratch, &mut normals).map_err(|e| e.to_string())?;
            model.vertex_normals = normals;
        }
        model.parts = model.split_by_texture(obj, textures, &kd)?;
        for i in 0..model.parts.len() {
            let mut normals = vec![[0; 3]; model.parts[i].indices.len()];
            compute_face_normals(&model.mesh::<Kd>(&model.parts[i]), &mut normals)
                .map_err(|e| e.to_string())?;
            model.parts[i].face_normals = normals;
        }
        let mut normals = vec![[0; 3]; model.all.indices.len()];
        compute_face_normals(&model.mesh::<Kd>(&model.all), &mut normals)
            .map_err(|e| e.to_string())?;
        model.all.face_normals = normals;
        model.bounds = model.mesh::<Kd>(&model.all).bounds();
        // Each part's colours as the opaque type too, and whether they are all one.
        let opaque = |p: &mut Part| {
            p.opaque = p.materials.iter().map(|k| Kd(k.0, k.1, k.2)).collect();
            let same =
                |a: &Kd, b: &Kd| a.0.map(f32::to_bits) == b.0.map(f32::to_bits) && a.1 == b.1;
            p.uniform = p.materials.windows(2).all(|w| same(&w[0], &w[1]));
        };
        opaque(&mut model.all);
        model.parts.iter_mut().for_each(opaque);
        // Model space → fitted: centre the bounding box, largest extent 1 (positions
        // are already stored around the bounding-box centre, q.offset).
        model.place = if fit {
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
        Ok(model)
    }

    /// The Z-buffer's parts: all faces as one when nothing is textured; otherwise the
    /// untextured faces, then one part per texture over the split vertex table.
    fn split_by_texture(
        &mut self,
        obj: &ObjModel,
        textures: &zraster_obj::ModelTextures,
        kd: &dyn Fn(&zraster_obj::ObjTriangle) -> Kd,
    ) -> Result<Vec<Part>, String> {
        let textured = |t: &zraster_obj::ObjTriangle| textures.of_triangle(t).is_some();
        if !obj.triangles.iter().any(textured) {
            return Ok(vec![Part {
                split: false,
                indices: self.all.indices.clone(),
                materials: self.all.materials.clone(),
                face_normals: Vec::new(),
                texture: None,
                opaque: Vec::new(),
                uniform: false,
            }]);
        }
        let split = obj.split_vertices(textured).map_err(|e| e.to_string())?;
        self.split_positions = split
            .vertices
            .iter()
            .map(|v| self.positions[v.position as usize])
            .collect();
        self.split_normals = split
            .vertices
            .iter()
            .map(|v| self.vertex_normals[v.position as usize])
            .collect();
        self.uvs = split.uvs();
        let split_indices = split.triangle_indices();
        let mut plain = Part {
            split: false,
            indices: Vec::new(),
            materials: Vec::new(),
            face_normals: Vec::new(),
            texture: None,
            opaque: Vec::new(),
            uniform: false,
        };
        let mut parts: Vec<Part> = textures
            .textures
            .iter()
            .map(|t| {
                let texels = t.image.rgba.iter().map(|p| Rgb888::new(p[0], p[1], p[2]));
                let wrap = if t.map.clamp {
                    Wrap::Clamp
                } else {
                    Wrap::Repeat
                };
                Part {
                    split: true,
                    indices: Vec::new(),
                    materials: Vec::new(),
                    face_normals: Vec::new(),
                    texture: Some((texels.collect(), t.image.width, t.image.height, wrap)),
                    opaque: Vec::new(),
                    uniform: false,
                }
            })
            .collect();
        for (i, t) in obj.triangles.iter().enumerate() {
            let (part, corners) = match textures.of_triangle(t) {
                Some(k) => (&mut parts[k], split_indices[i]),
                None => (&mut plain, self.all.indices[i]),
            };
            part.indices.push(corners);
            part.materials.push(kd(t));
        }
        parts.insert(0, plain);
        parts.retain(|p| !p.indices.is_empty());
        Ok(parts)
    }

    /// The mesh of `part`, with its normals.
    pub fn mesh<'a, K: Colours>(&'a self, part: &'a Part) -> Mesh<'a, K> {
        let (positions, normals) = if part.split {
            (&self.split_positions, &self.split_normals)
        } else {
            (&self.positions, &self.vertex_normals)
        };
        let face_normals = (!part.face_normals.is_empty()).then_some(&part.face_normals[..]);
        Mesh {
            positions,
            scale: self.scale,
            faces: Faces::Triangles {
                indices: &part.indices,
                materials: match K::of(part) {
                    [m, ..] if part.uniform => Materials::Uniform(*m),
                    ms => Materials::PerFace(ms),
                },
            },
            face_normals,
            vertex_normals: Some(normals),
        }
    }

    /// Whether some face is see-through (an MTL `d` below 1).
    pub fn see_through(&self) -> bool {
        self.all.materials.iter().any(|k| k.1 < u8::MAX)
    }

    /// The vertex count of `part`'s table (the size of its vertex cache).
    pub fn vertices(&self, part: &Part) -> usize {
        if part.split {
            self.split_positions.len()
        } else {
            self.positions.len()
        }
    }

    /// How `part` is textured, if it is: perspective-correct, nearest texel.
    pub fn texturing<'a>(
        &'a self,
        part: &'a Part,
    ) -> Result<Option<Texturing<'a, Rgb888>>, String> {
        let Some((texels, w, h, wrap)) = &part.texture else {
            return Ok(None);
        };
        let texture = Texture::new(texels, *w, *h)
            .map_err(|e| format!("texture of {w}x{h} texels: {e}"))?
            .with_wrap(*wrap);
        Ok(Some(
            Texturing::new(&self.uvs, texture).with_mode(UvMode::Perspective),
        ))
    }
}

/// The k of the mesh scale `scale × 2^-k`: 0 for a model within 2^±16 (`scale` is its
/// reach / 32767), else the k that brings `scale` into [2^-8, 2^-7) (positions to about
/// ±2^8), within what an `f32` power of two can take back.
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
