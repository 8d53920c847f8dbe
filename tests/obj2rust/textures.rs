//! `to_rust_textured`: a textured box becomes a `const` mesh, a UV table and a `const`
//! texture that compile, hold the model's coordinates and sample the right texels.

use zraster::texture::{TexCoord, Texture, Wrap, MESH_UV_ONE};
use zraster_obj::{parse_obj, to_rust_textured, ObjImage, RustForm, RustOptions};

use super::{here, textured, textured_included};

/// A crate: the unit cube with the whole texture on each side (a corner meets up to
/// three texture coordinates: 8 positions become 16 vertices), and a quad beside it
/// across which the texture repeats twice (u from 0 to 2).
pub const CRATE_OBJ: &str = "\
mtllib crate.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
v 2 0 0
v 2 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vt 2 0
vt 2 1
usemtl wood
f 1/2 4/3 3/4 2/1
f 5/1 6/2 7/3 8/4
f 1/1 2/2 6/3 5/4
f 4/4 8/1 7/2 3/3
f 1/2 5/1 8/4 4/3
f 2/1 3/4 7/3 6/2
f 2/1 9/5 10/6 3/4
";

pub const CRATE_MTL: &str = "newmtl wood\nKd 0.6 0.4 0.2\nmap_Kd tex/wood.png\n";

/// The texture: 4×2 texels, each its own colour.
pub const WOOD: [[u8; 4]; 8] = [
    [255, 0, 0, 255],
    [0, 255, 0, 255],
    [0, 0, 255, 255],
    [255, 255, 255, 255],
    [0, 0, 0, 255],
    [128, 128, 128, 255],
    [255, 255, 0, 255],
    [0, 255, 255, 255],
];

fn wood(path: &str) -> Result<ObjImage, String> {
    match path {
        "tex/wood.png" => Ok(ObjImage {
            width: 4,
            height: 2,
            rgba: WOOD.to_vec(),
        }),
        _ => Err("no such file".into()),
    }
}

const WARNINGS: [&str; 2] = [
    "7 polygons of more than 3 vertices fan-triangulated into 14 triangles",
    "8 vertices added where faces give a position different texture coordinates (18 in all)",
];

/// The checked-in files are what `to_rust_textured` makes of `CRATE_OBJ` now
/// (`ZRASTER_BLESS=1 cargo test --test obj2rust` rewrites them).
#[test]
fn the_textured_files_are_what_to_rust_textured_makes() {
    for (file, form) in [
        ("textured.rs", RustForm::Module),
        ("textured_included.rs", RustForm::Include),
    ] {
        let mut warnings = Vec::new();
        let opts = RustOptions {
            name: "crate",
            form,
        };
        let rust = to_rust_textured(
            CRATE_OBJ,
            |_| Ok(CRATE_MTL.into()),
            wood,
            &opts,
            &mut warnings,
        )
        .unwrap();
        assert_eq!(warnings, WARNINGS);
        assert_eq!((rust.vertices, rust.triangles, rust.textures), (18, 14, 1));
        let path = here(file);
        if std::env::var_os("ZRASTER_BLESS").is_some() {
            std::fs::write(&path, &rust.code).unwrap();
        }
        let checked_in = std::fs::read_to_string(&path).unwrap();
        assert!(
            checked_in == rust.code,
            "{file} is not what to_rust_textured makes: ZRASTER_BLESS=1 cargo test --test obj2rust"
        );
    }
}

/// The generated tables hold the model: every triangle's corners have the position and
/// the texture coordinates (Q12, v flipped) the OBJ gives them, split vertices keep
/// their position's normal, and the texture samples the PNG's texels.
#[test]
fn the_textured_tables_hold_the_model() {
    use textured::*;
    let model = parse_obj(CRATE_OBJ, |_| Some(CRATE_MTL.into())).unwrap();
    assert_eq!(CRATE_INDICES.len(), model.triangles.len());
    assert_eq!(CRATE_UVS.len(), CRATE_POSITIONS.len());
    assert_eq!(CRATE_VERTEX_NORMALS.len(), CRATE_POSITIONS.len());
    let unsplit = zraster_obj::quantize(&model.positions, true);
    for (tri, t) in CRATE_INDICES.iter().zip(&model.triangles) {
        let vt = t.texcoords.unwrap();
        for k in 0..3 {
            let v = usize::from(tri[k]);
            let p = t.vertices[k] as usize;
            assert_eq!(CRATE_POSITIONS[v], unsplit.positions[p]);
            // The copies of a position share its normal (the first copy is at `p`).
            assert_eq!(CRATE_VERTEX_NORMALS[v], CRATE_VERTEX_NORMALS[p]);
            let [u, w] = model.texcoords[vt[k] as usize];
            let q12 = |x: f64| (x * f64::from(MESH_UV_ONE)) as i16;
            assert_eq!(CRATE_UVS[v], [q12(u), q12(1.0 - w)], "triangle {tri:?}");
        }
    }
    // The texture: RGB565 of the PNG, 4×2, repeating.
    assert_eq!((CRATE_TEXTURE_WIDTH, CRATE_TEXTURE_HEIGHT), (4, 2));
    assert_eq!(CRATE_TEXELS[..4], [0xF800, 0x07E0, 0x001F, 0xFFFF]);
    assert_eq!(CRATE_TEXTURE.wrap(), Wrap::Repeat);
    assert!(core::ptr::eq(CRATE_TEXTURE.texels(), &CRATE_TEXELS[..]));
    // The render contract: the texel at column ⌊u·W⌋ mod W, row ⌊(1 − v)·H⌋ mod H.
    let at = |u: f64, v: f64| {
        let uv = TexCoord::new((u * 65536.0) as i32, ((1.0 - v) * 65536.0).floor() as i32);
        CRATE_TEXTURE.sample_raw(uv)
    };
    let texel = |x: usize, y: usize| CRATE_TEXELS[y * 4 + x];
    assert_eq!(at(0.1, 0.9), texel(0, 0)); // OBJ's v up: the top row
    assert_eq!(at(0.6, 0.1), texel(2, 1));
    assert_eq!(at(1.9, 0.6), texel(3, 0)); // u = 1.9 repeats to 0.9
    assert_eq!(at(-0.2, 1.7), texel(3, 0)); // -0.2 → 0.8; 1 − 1.7 = -0.7 → 0.3
                                            // The last face repeats the texture twice: u to 2 (8192), no face moved.
    let last = CRATE_INDICES[13];
    assert!(last
        .iter()
        .any(|&v| CRATE_UVS[usize::from(v)][0] == 2 * MESH_UV_ONE));
    // The include! form is the same.
    assert_eq!(textured_included::CRATE_UVS, CRATE_UVS);
    assert_eq!(textured_included::CRATE_TEXELS, CRATE_TEXELS);
    assert_eq!(textured_included::CRATE_TEXTURE, CRATE_TEXTURE);
    assert_eq!(textured_included::CRATE_MESH, CRATE_MESH);
    let _: Texture<'static, u16> = textured_included::CRATE_TEXTURE;
}
