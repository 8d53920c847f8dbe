//! Texture images: PNG decoding, RGB565, and the textures of a model's materials.

use std::collections::HashMap;

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::IntoStorage;

use crate::{ObjModel, TextureMap};

/// The largest texture file [`MtlLoader::load_texture`](crate::MtlLoader::load_texture)
/// reads: 64 MiB.
pub const MAX_TEXTURE_BYTES: u64 = 64 << 20;

/// The largest texture width or height: zraster's
/// [`MAX_DIMENSION`](zraster::MAX_DIMENSION), 8192.
pub const MAX_TEXTURE_SIZE: u32 = zraster::MAX_DIMENSION;

/// A decoded texture: 8-bit RGBA texels, row by row from the top.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ObjImage {
    /// Texels across.
    pub width: u32,
    /// Texels down.
    pub height: u32,
    /// `width × height` texels, row by row from the top.
    pub rgba: Vec<[u8; 4]>,
}

impl ObjImage {
    /// The texels as raw RGB565 (`0xF800` is red), each channel rounded to its depth as
    /// embedded-graphics converts `Rgb888` to `Rgb565`; alpha dropped.
    pub fn rgb565(&self) -> Vec<u16> {
        self.rgba.iter().map(|&p| rgb565(p)).collect()
    }

    /// Whether every texel is fully opaque.
    pub fn opaque(&self) -> bool {
        self.rgba.iter().all(|p| p[3] == 255)
    }
}

/// An 8-bit colour as raw RGB565.
pub fn rgb565([r, g, b, _]: [u8; 4]) -> u16 {
    Rgb565::from(Rgb888::new(r, g, b)).into_storage()
}

/// Decode a PNG file's bytes: any colour type and bit depth (palettes expanded, 16-bit
/// channels cut to 8, grey spread to RGB, no alpha taken as opaque), interlaced or not.
/// `Err` says what is wrong: not a PNG, a broken one, or a size of 0 or above
/// [`MAX_TEXTURE_SIZE`].
pub fn decode_png(bytes: &[u8]) -> Result<ObjImage, String> {
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::normalize_to_color8());
    let mut reader = decoder
        .read_info()
        .map_err(|e| format!("not a PNG image: {e}"))?;
    let (width, height) = reader.info().size();
    if width == 0 || height == 0 {
        return Err(format!("image of {width}x{height} texels"));
    }
    if width > MAX_TEXTURE_SIZE || height > MAX_TEXTURE_SIZE {
        return Err(format!(
            "image of {width}x{height} texels: larger than {MAX_TEXTURE_SIZE}"
        ));
    }
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| format!("image of {width}x{height} texels: too large"))?;
    let mut buf = vec![0u8; size];
    let info = reader
        .next_frame(&mut buf)
        .map_err(|e| format!("broken PNG image: {e}"))?;
    let channels = match info.color_type {
        png::ColorType::Grayscale => 1,
        png::ColorType::GrayscaleAlpha => 2,
        png::ColorType::Rgb => 3,
        png::ColorType::Rgba => 4,
        png::ColorType::Indexed => return Err("palette left unexpanded".into()),
    };
    let mut rgba = Vec::with_capacity(width as usize * height as usize);
    for row in buf.chunks(info.line_size).take(height as usize) {
        for px in row.chunks_exact(channels).take(width as usize) {
            rgba.push(match *px {
                [l] => [l, l, l, 255],
                [l, a] => [l, l, l, a],
                [r, g, b] => [r, g, b, 255],
                [r, g, b, a] => [r, g, b, a],
                _ => [0, 0, 0, 255],
            });
        }
    }
    if rgba.len() != width as usize * height as usize {
        return Err("broken PNG image: short image data".into());
    }
    Ok(ObjImage {
        width,
        height,
        rgba,
    })
}

/// One texture of a model, read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LoadedTexture {
    /// The file and its wrap, as the material gives them.
    pub map: TextureMap,
    /// The texels.
    pub image: ObjImage,
}

/// The textures of a model's materials: each file (and wrap) once.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ModelTextures {
    /// The textures, in the order the faces first use them.
    pub textures: Vec<LoadedTexture>,
    /// For each material of [`ObjModel::materials`], its entry in `textures`: `None`
    /// for materials without a texture, whose texture could not be read, or whose faces
    /// have no texture coordinates.
    pub of_material: Vec<Option<usize>>,
}

impl ModelTextures {
    /// The texture triangle `t` of `model` is drawn with, if any: its material's, when
    /// it has texture coordinates.
    pub fn of_triangle(&self, t: &crate::ObjTriangle) -> Option<usize> {
        t.texcoords?;
        self.of_material.get(t.material?).copied().flatten()
    }
}

/// Read the textures of the materials that faces with texture coordinates use, each
/// file once, with `load` ([`MtlLoader::load_texture`](crate::MtlLoader::load_texture)
/// reads them safely from the OBJ file's folder).
///
/// **A texture that cannot be read is not an error**: a warning naming the material,
/// the file and why (missing, unreadable, not a PNG, too large), and the material's
/// faces are drawn untextured, in its `Kd` colour, as faces of a material whose
/// library cannot be read are drawn in the default colour. Materials with a texture
/// but whose faces have no `vt` coordinates get a warning too.
pub fn load_textures(
    model: &ObjModel,
    mut load: impl FnMut(&str) -> Result<ObjImage, String>,
    warnings: &mut Vec<String>,
) -> ModelTextures {
    let n = model.materials.len();
    let mut with_uv = vec![false; n];
    let mut used = vec![false; n];
    let mut order = Vec::new();
    for t in &model.triangles {
        let Some(m) = t.material.filter(|&m| m < n) else {
            continue;
        };
        if !used[m] {
            used[m] = true;
            order.push(m);
        }
        with_uv[m] |= t.texcoords.is_some();
    }
    let mut out = ModelTextures {
        textures: Vec::new(),
        of_material: vec![None; n],
    };
    let mut by_map: HashMap<&TextureMap, Result<usize, ()>> = HashMap::new();
    for m in order {
        let mat = &model.materials[m];
        let Some(map) = &mat.map_kd else { continue };
        if !with_uv[m] {
            warnings.push(format!(
                "material {:?}: texture {} not used: its faces have no `vt` texture coordinates",
                mat.name, map.path
            ));
            continue;
        }
        let entry = by_map.entry(map).or_insert_with(|| match load(&map.path) {
            Ok(image) => {
                out.textures.push(LoadedTexture {
                    map: map.clone(),
                    image,
                });
                Ok(out.textures.len() - 1)
            }
            Err(why) => {
                warnings.push(format!(
                    "material {:?}: cannot read texture {}: {why}: its faces are drawn untextured, in its Kd colour",
                    mat.name, map.path
                ));
                Err(())
            }
        });
        out.of_material[m] = entry.ok();
    }
    out
}
