//! The texture part of [`to_rust_textured`](super::to_rust_textured)'s output: the UV
//! table, each texture's RGB565 table and `Texture`, each face's texture.

use std::fmt::Write;

use super::{printable, table};
use crate::{ModelTextures, ObjModel, SplitVertices};

/// Texture index of a face without one in `NAME_FACE_TEXTURES`.
const NONE: u8 = 255;

/// The `use` line of a module file with textures.
pub(super) fn imports(textures: &ModelTextures) -> &'static str {
    if textures.textures.iter().any(|t| t.map.clamp) {
        "use zraster::texture::{Texture, Wrap};"
    } else {
        "use zraster::texture::Texture;"
    }
}

/// The UV table, the textures and (when some faces differ) each face's texture.
pub(super) fn write(
    w: &mut String,
    textures: &ModelTextures,
    split: &SplitVertices,
    model: &ObjModel,
    n: &str,
    include: bool,
) {
    let module = if include { "zraster::texture::" } else { "" };
    table(
        w,
        "Each vertex's texture coordinates [u, v], Q12 (4096 is one texture, v down the image: 1 − OBJ's v; `zraster::texture::MeshUv`).",
        &format!("{n}_UVS"),
        "[i16; 2]",
        split
            .uvs()
            .iter()
            .map(|[u, v]| format!("[{u}, {v}]"))
            .collect(),
        8,
    );
    let several = textures.textures.len() > 1;
    for (k, t) in textures.textures.iter().enumerate() {
        let (texels, texture) = if several {
            (format!("{n}_TEXELS_{k}"), format!("{n}_TEXTURE_{k}"))
        } else {
            (format!("{n}_TEXELS"), format!("{n}_TEXTURE"))
        };
        let (width, height) = (t.image.width, t.image.height);
        let path = printable(&t.map.path);
        table(
            w,
            &format!(
                "Texture {path}: {width}x{height} texels, raw RGB565 (`0xF800` is red), row by row from the top."
            ),
            &texels,
            "u16",
            t.image
                .rgb565()
                .iter()
                .map(|c| format!("{c:#06X}").replace("0X", "0x"))
                .collect(),
            16,
        );
        let _ = writeln!(
            w,
            "/// Texels across {texture}.\npub const {texture}_WIDTH: u32 = {width};"
        );
        let _ = writeln!(
            w,
            "/// Texels down {texture}.\npub const {texture}_HEIGHT: u32 = {height};"
        );
        let (wrap, ok) = if t.map.clamp {
            (
                "clamped (map_Kd -clamp on)",
                format!("t.with_wrap({module}Wrap::Clamp)"),
            )
        } else {
            ("repeating", "t".to_string())
        };
        let _ = writeln!(
            w,
            "/// {path}, {wrap}.\npub const {texture}: {module}Texture<'static, u16> =\n    match {module}Texture::new(&{texels}, {texture}_WIDTH, {texture}_HEIGHT) {{\n        Ok(t) => {ok},\n        Err(_) => panic!(\"{texture}: bad size\"),\n    }};"
        );
    }
    let faces: Vec<u8> = model
        .triangles
        .iter()
        .map(|t| textures.of_triangle(t).map_or(NONE, |k| k as u8))
        .collect();
    if several || faces.contains(&NONE) {
        table(
            w,
            "Each triangle's texture (255: none, drawn in its colour).",
            &format!("{n}_FACE_TEXTURES"),
            "u8",
            faces.iter().map(|k| k.to_string()).collect(),
            32,
        );
    }
}
