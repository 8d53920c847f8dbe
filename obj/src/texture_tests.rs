//! Texture coordinates, vertex splitting, `map_Kd`/`d`/`Tr`, PNG textures and the
//! textured Rust output.

use super::*;
use std::path::{Path, PathBuf};

fn parse(s: &str) -> Result<ObjModel, ObjError> {
    parse_obj(s, |_| None)
}

/// A scratch folder for one test.
fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("zraster-objtex-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A PNG file of `width × height` samples of `color` type, 8-bit unless `deep`.
fn png_bytes(width: u32, height: u32, color: png::ColorType, deep: bool, data: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, width, height);
        enc.set_color(color);
        enc.set_depth(if deep {
            png::BitDepth::Sixteen
        } else {
            png::BitDepth::Eight
        });
        if color == png::ColorType::Indexed {
            enc.set_palette(vec![255, 0, 0, 0, 0, 255]);
        }
        let mut w = enc.write_header().unwrap();
        w.write_image_data(data).unwrap();
    }
    out
}

#[test]
fn texture_coordinates_are_read_with_their_corners() {
    let src = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
               vt 0.25 0.5\nvt 1 0 0\nvt 0.75\nvt 2.5 -3\n\
               f 1/1 2/2/1 3/3\nf 1//1 3//1 4//1\nf 1/-4 3/-2 4/-1\n";
    let m = parse(src).unwrap();
    assert_eq!(
        m.texcoords,
        [[0.25, 0.5], [1.0, 0.0], [0.75, 0.0], [2.5, -3.0]]
    );
    assert_eq!(m.notes.texcoord_w, 1);
    let tex: Vec<Option<[u32; 3]>> = m.triangles.iter().map(|t| t.texcoords).collect();
    assert_eq!(tex, [Some([0, 1, 2]), None, Some([0, 2, 3])]);
    // A quad fans its texture coordinates with its corners.
    let m = parse(
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n",
    )
    .unwrap();
    let t: Vec<([u32; 3], Option<[u32; 3]>)> = m
        .triangles
        .iter()
        .map(|t| (t.vertices, t.texcoords))
        .collect();
    assert_eq!(
        t,
        [([0, 1, 2], Some([0, 1, 2])), ([0, 2, 3], Some([0, 2, 3]))]
    );
    // Huge coordinates are accepted (repeat).
    let m = parse("vt 1e300 -1e15\n").unwrap();
    assert_eq!(m.texcoords, [[1e300, -1e15]]);
}

#[test]
fn bad_texture_coordinates_are_errors_with_their_line() {
    let cases = [
        ("vt\n", 1, "missing u"),
        ("v 0 0 0\nvt nan 0\n", 2, "u is not finite"),
        ("vt 0 inf\n", 1, "v is not finite"),
        ("vt 0 1e400\n", 1, "v is not finite"),
        ("vt 0 x\n", 1, "v is not a number"),
        (
            "v 0 0 0\nvt 0 0\nf 1/0 1/1 1/1\n",
            3,
            "texture coordinate index 0",
        ),
        (
            "v 0 0 0\nvt 0 0\nf 1/-2 1/1 1/1\n",
            3,
            "texture coordinate index -2 out of range",
        ),
        (
            "v 0 0 0\nvt 0 0\nf 1/x 1/1 1/1\n",
            3,
            "bad texture coordinate reference",
        ),
        (
            "v 0 0 0\nvt 0 0\n\nf 1/1 1/1 1/2\n",
            4,
            "texture coordinate index 2 out of range (the file has 1 texture coordinates)",
        ),
    ];
    for (src, line, what) in cases {
        let e = parse(src).unwrap_err();
        assert_eq!(e.line, line, "{src:?}: {e}");
        assert!(e.message.contains(what), "{src:?}: {e}");
    }
    // A forward reference is fine when the vt comes later.
    let m = parse("v 0 0 0\nf 1/1 1/1 1/1\nvt 0.5 0.5\n").unwrap();
    assert_eq!(m.triangles[0].texcoords, Some([0, 0, 0]));
    // Leniently (to_rust), a face with a bad texture reference is left out.
    let mut warnings = Vec::new();
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 1/1 2/1 3/7\n";
    let rust = to_rust(
        obj,
        |_| Err(String::new()),
        &RustOptions::default(),
        &mut warnings,
    )
    .unwrap();
    assert_eq!(rust.triangles, 1);
    assert_eq!(
        warnings[0],
        "line 6: texture coordinate index 7 out of range (the file has 1 texture coordinates): face skipped"
    );
}

/// Faces whose corners give `vt` to some corners only are kept without.
#[test]
fn a_face_with_some_corners_textured_is_kept_untextured() {
    let m = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3/1\n").unwrap();
    assert_eq!(m.triangles.len(), 1);
    assert_eq!(m.triangles[0].texcoords, None);
    assert_eq!(m.notes.mixed_faces, 1);
    assert_eq!(
        m.warnings,
        ["line 5: some corners of the face have `vt` texture coordinates and some not: it is kept without"]
    );
    let many = "v 0 0 0\nvt 0 0\n".to_string() + &"f 1/1 1 1\n".repeat(12);
    let m = parse(&many).unwrap();
    assert_eq!(m.warnings.len(), 11);
    assert_eq!(
        m.warnings[10],
        "12 faces in all kept without texture coordinates (some corners without `vt`)"
    );
}

/// A position with different texture coordinates in different faces becomes several
/// vertices; the same coordinates (even from another `vt` line) share one.
#[test]
fn vertices_split_at_texture_seams() {
    // A strip of two quads around a cylinder's seam: positions 1 and 4 (u = 0) are
    // also u = 1 where the strip closes.
    let src = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\n\
               vt 0 0\nvt 0.5 0\nvt 1 0\nvt 0 1\nvt 0.5 1\nvt 1 1\nvt 0 0\n\
               f 1/1 2/2 5/5 4/4\nf 2/2 3/3 6/6 5/5\nf 3/3 1/3 4/6 6/6\nf 1/7 2/2 4/4\n";
    let m = parse(src).unwrap();
    let s = m.split_vertices(|t| t.texcoords.is_some()).unwrap();
    assert_eq!(s.vertices.len(), 8);
    assert_eq!(s.added, 2);
    // The six positions keep their places and first coordinates (v flipped: 1 − v).
    let uv = |v: usize| (s.vertices[v].position, s.vertices[v].uv);
    assert_eq!(uv(0), (0, Some([0, 4096])));
    assert_eq!(uv(2), (2, Some([4096, 4096])));
    assert_eq!(uv(3), (3, Some([0, 0])));
    // The seam: positions 0 and 3 again, at u = 1.
    assert_eq!(uv(6), (0, Some([4096, 4096])));
    assert_eq!(uv(7), (3, Some([4096, 0])));
    assert_eq!(
        s.triangles,
        [
            [0, 1, 4],
            [0, 4, 3],
            [1, 2, 5],
            [1, 5, 4],
            [2, 6, 7],
            [2, 7, 5],
            // vt 7 is (0, 0), as vt 1: the same vertex.
            [0, 1, 3],
        ]
    );
    assert_eq!(s.uvs().len(), 8);
    // Only faces that are textured carry coordinates: without any, nothing splits.
    let s = m.split_vertices(|_| false).unwrap();
    assert_eq!((s.vertices.len(), s.added), (6, 0));
    assert!(s.vertices.iter().all(|v| v.uv.is_none()));
    // A position first used untextured takes the coordinates of a textured corner.
    let m = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5 0.5\nf 1 2 3\nf 1/1 2/1 3/1\n").unwrap();
    let s = m.split_vertices(|t| t.texcoords.is_some()).unwrap();
    assert_eq!(s.vertices.len(), 3);
    assert_eq!(s.vertices[0].uv, Some([2048, 2048]));
}

/// Q12 keeps ±8 textures: faces beyond are moved by whole textures, exactly; a face
/// spanning more than 8 is clamped and named.
#[test]
fn large_texture_coordinates_repeat_exactly() {
    let src = "v 0 0 0\nv 1 0 0\nv 0 1 0\n\
               vt 100.25 -7.5\nvt 101 -7.25\nvt 100.5 -7\n\
               vt 1099511627776.125 0\nvt 1099511627776.5 0\nvt 1099511627777 1\n\
               vt 0 0\nvt 20 0\nvt 0 1\n\
               f 1/1 2/2 3/3\nf 1/4 2/5 3/6\nf 1/7 2/8 3/9\n";
    let m = parse(src).unwrap();
    let s = m.split_vertices(|_| true).unwrap();
    let uvs = s.uvs();
    // u 100.25 → 0.25; v: 1 − (−7.5) = 8.5 → 0.5 (moved by 8), 8.25 → 0.25, 8 → 0.
    assert_eq!(uvs[0], [1024, 2048]);
    assert_eq!(s.triangles[0], [0, 1, 2]);
    assert_eq!(&uvs[1..3], [[4096, 1024], [2048, 0]]);
    // 2⁴⁰ + ⅛: the fraction is kept.
    let t1 = s.triangles[1];
    assert_eq!(uvs[t1[0] as usize], [512, 4096]);
    assert_eq!(uvs[t1[2] as usize], [4096, 0]);
    assert_eq!(s.moved_faces, 2);
    assert_eq!(s.huge, 3);
    // u from 0 to 20: clamped at 8 − 1/4096, its line named.
    assert_eq!(s.clamped_faces, [15]);
    let t2 = s.triangles[2];
    assert_eq!(uvs[t2[1] as usize], [32767, 4096]);
}

#[test]
fn materials_carry_textures_and_opacity() {
    let mtl = "newmtl a\nKd 1 0 0\nmap_Kd -clamp on -s 2 2 1 -o 0.5 -bm 0.2 my wood.png\n\
               d 0.25\nnewmtl b\nTr 0.75\nmap_Kd /abs/b.png\nnewmtl c\nd -halo 0.5\nTr 0.1\n";
    let mut m = parse_obj_with("mtllib sub/dir/m.mtl\n", |_| Ok(mtl.into())).unwrap();
    let mats = std::mem::take(&mut m.materials);
    assert_eq!(
        mats[0].map_kd,
        Some(TextureMap {
            path: "sub/dir/my wood.png".into(),
            clamp: true
        })
    );
    assert_eq!(mats[0].alpha, 0.25);
    assert_eq!(mats[0].kd, [1.0, 0.0, 0.0]);
    assert_eq!(mats[1].map_kd.as_ref().unwrap().path, "/abs/b.png");
    assert!(!mats[1].map_kd.as_ref().unwrap().clamp);
    assert_eq!(mats[1].alpha, 0.25);
    assert!((mats[2].alpha - 0.9).abs() < 1e-6); // Tr after d wins
    assert_eq!(mats[2].map_kd, None);
    assert_eq!(
        m.warnings,
        ["line 1: in sub/dir/m.mtl: line 3: map_Kd options ignored: -s, -o, -bm"]
    );
    // parse_mtl keeps the name as written.
    let mut out = Vec::new();
    parse_mtl("newmtl x\nmap_Kd t.png\n", &mut out).unwrap();
    assert_eq!(out[0].map_kd.as_ref().unwrap().path, "t.png");
    // Malformed statements: errors with the MTL line.
    for (src, want) in [
        (
            "map_Kd a.png\n",
            "line 1: in m: line 1: map_Kd before any newmtl",
        ),
        (
            "newmtl a\nmap_Kd\n",
            "line 1: in m: line 2: map_Kd without a file name",
        ),
        (
            "newmtl a\nmap_Kd -clamp on\n",
            "line 1: in m: line 2: map_Kd without a file name",
        ),
        (
            "newmtl a\nmap_Kd -s\n",
            "line 1: in m: line 2: map_Kd option -s without its value",
        ),
        (
            "newmtl a\nd nan\n",
            "line 1: in m: line 2: d is not finite: \"nan\"",
        ),
        ("newmtl a\nTr\n", "line 1: in m: line 2: missing Tr"),
        ("d 1\n", "line 1: in m: line 1: d before any newmtl"),
    ] {
        let e = parse_obj_with("mtllib m\n", |_| Ok(src.into())).unwrap_err();
        assert_eq!(e.to_string(), want, "{src:?}");
    }
}

/// Every PNG colour type and depth decodes to RGBA; RGB565 as embedded-graphics
/// rounds it.
#[test]
fn png_textures_decode() {
    use png::ColorType::*;
    let rgb = decode_png(&png_bytes(2, 1, Rgb, false, &[255, 0, 0, 10, 20, 30])).unwrap();
    assert_eq!((rgb.width, rgb.height), (2, 1));
    assert_eq!(rgb.rgba, [[255, 0, 0, 255], [10, 20, 30, 255]]);
    assert!(rgb.opaque());
    assert_eq!(rgb.rgb565(), [0xF800, (1 << 11) | (5 << 5) | 4]);
    let rgba = decode_png(&png_bytes(1, 2, Rgba, false, &[1, 2, 3, 4, 5, 6, 7, 255])).unwrap();
    assert_eq!(rgba.rgba, [[1, 2, 3, 4], [5, 6, 7, 255]]);
    assert!(!rgba.opaque());
    let grey = decode_png(&png_bytes(2, 1, Grayscale, false, &[0, 200])).unwrap();
    assert_eq!(grey.rgba, [[0, 0, 0, 255], [200, 200, 200, 255]]);
    let ga = decode_png(&png_bytes(1, 1, GrayscaleAlpha, false, &[9, 99])).unwrap();
    assert_eq!(ga.rgba, [[9, 9, 9, 99]]);
    let deep = decode_png(&png_bytes(1, 1, Rgb, true, &[0xAB, 0xCD, 0, 0, 0xFF, 0xFF])).unwrap();
    assert_eq!(deep.rgba, [[0xAB, 0, 0xFF, 255]]);
    let pal = decode_png(&png_bytes(2, 1, Indexed, false, &[1, 0])).unwrap();
    assert_eq!(pal.rgba, [[0, 0, 255, 255], [255, 0, 0, 255]]);
    // Every 8-bit colour converts as embedded-graphics converts Rgb888 to Rgb565.
    for (c, want) in [
        ([0, 0, 0], 0),
        ([255, 255, 255], 0xFFFF),
        ([4, 2, 4], 0x0000),
        ([5, 2, 5], 0x0801),
    ] {
        assert_eq!(rgb565([c[0], c[1], c[2], 255]), want, "{c:?}");
    }
    // Broken and oversized images are errors that say so.
    assert!(decode_png(b"GIF89a")
        .unwrap_err()
        .starts_with("not a PNG image"));
    let mut cut = png_bytes(4, 4, Rgb, false, &[7; 48]);
    cut.truncate(cut.len() - 20);
    assert!(decode_png(&cut).is_err());
    let wide = png_bytes(8193, 1, Grayscale, false, &[0; 8193]);
    assert_eq!(
        decode_png(&wide).unwrap_err(),
        "image of 8193x1 texels: larger than 8192"
    );
}

/// A textured OBJ from disk: the loader reads the library and the PNG beside it; a
/// texture that cannot be read is a warning and the material's faces go untextured.
#[test]
fn textures_load_from_disk_or_fall_back_to_the_colour() {
    let dir = scratch("load");
    std::fs::create_dir_all(dir.join("mat")).unwrap();
    std::fs::write(
        dir.join("mat/m.mtl"),
        "newmtl wood\nmap_Kd wood.png\nnewmtl gone\nKd 0 1 0\nmap_Kd gone.png\n\
         newmtl junk\nmap_Kd junk.png\nnewmtl nouv\nmap_Kd wood.png\n",
    )
    .unwrap();
    let px = png_bytes(
        2,
        2,
        png::ColorType::Rgb,
        false,
        &[255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255],
    );
    std::fs::write(dir.join("mat/wood.png"), px).unwrap();
    std::fs::write(dir.join("mat/junk.png"), "not a png").unwrap();
    let obj = "mtllib mat/m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n\
               usemtl wood\nf 1/1 2/2 3/3\nusemtl gone\nf 1/1 2/2 3/3\nusemtl junk\nf 1/1 2/2 3/3\n\
               usemtl nouv\nf 1 2 3\nusemtl wood\nf 3/1 2/2 1/3\n";
    let mut loader = MtlLoader::new(&dir);
    let model = parse_obj_with(obj, |n| loader.load(n)).unwrap();
    let mut warnings = Vec::new();
    let mut asked = Vec::new();
    let tex = load_textures(
        &model,
        |p| {
            asked.push(p.to_string());
            loader.load_texture(p)
        },
        &mut warnings,
    );
    // wood.png once, for two materials' worth of faces.
    assert_eq!(asked, ["mat/wood.png", "mat/gone.png", "mat/junk.png"]);
    assert_eq!(tex.textures.len(), 1);
    assert_eq!(tex.textures[0].image.rgba[3], [255, 255, 255, 255]);
    assert_eq!(tex.of_material, [Some(0), None, None, None]);
    let per_face: Vec<Option<usize>> = model.triangles.iter().map(|t| tex.of_triangle(t)).collect();
    assert_eq!(per_face, [Some(0), None, None, None, Some(0)]);
    assert_eq!(warnings.len(), 3, "{warnings:?}");
    assert!(warnings[0].starts_with("material \"gone\": cannot read texture mat/gone.png: "));
    assert!(warnings[0].ends_with(": its faces are drawn untextured, in its Kd colour"));
    assert!(warnings[1]
        .starts_with("material \"junk\": cannot read texture mat/junk.png: not a PNG image"));
    assert_eq!(
        warnings[2],
        "material \"nouv\": texture mat/wood.png not used: its faces have no `vt` texture coordinates"
    );
    // Not a regular file, too large.
    assert_eq!(
        loader.load_texture("mat").unwrap_err(),
        "not a regular file"
    );
    let big = std::fs::File::create(dir.join("big.png")).unwrap();
    big.set_len(MAX_TEXTURE_BYTES + 1).unwrap();
    assert_eq!(
        loader.load_texture("big.png").unwrap_err(),
        "larger than 64 MiB"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// to_rust_textured end to end: tables, names, several textures, face textures,
/// opacity, and what is said.
#[test]
fn textured_rust_output() {
    let mtl = "newmtl a\nmap_Kd a.png\nd 0.5\nnewmtl b\nKd 0 0 1\nmap_Kd -clamp on b.png\nnewmtl c\nKd 0 1 0\n";
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\n\
               usemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 2/1 4/2 3/3\nusemtl c\nf 1 3 4\n";
    let image = |p: &str| {
        Ok(ObjImage {
            width: 1,
            height: 1,
            rgba: vec![if p == "a.png" {
                [255, 0, 0, 128]
            } else {
                [0, 255, 0, 255]
            }],
        })
    };
    let mut warnings = Vec::new();
    let opts = RustOptions {
        name: "tex",
        form: RustForm::Module,
    };
    let rust = to_rust_textured(obj, |_| Ok(mtl.into()), image, &opts, &mut warnings).unwrap();
    assert_eq!((rust.vertices, rust.textures, rust.materials), (5, 2, 3));
    let code = &rust.code;
    for want in [
        "// 5 vertices, 3 triangles, 2 textures.",
        "use zraster::texture::{Texture, Wrap};",
        "pub const TEX_TEXELS_0: [u16; 1] = [\n    0xF800,\n];",
        "pub const TEX_TEXELS_1: [u16; 1] = [\n    0x07E0,\n];",
        "pub const TEX_TEXTURE_1_WIDTH: u32 = 1;",
        "        Ok(t) => t.with_wrap(Wrap::Clamp),",
        "pub const TEX_FACE_TEXTURES: [u8; 3] = [\n    0, 1, 255,\n];",
        "pub const TEX_MATERIAL_ALPHA: [u8; 3] = [\n    128, 255, 255,\n];",
        // Position 1 at u = 0 in face 2: a fifth vertex, with position 1's normal.
        "pub const TEX_UVS: [[i16; 2]; 5] = [\n    [0, 4096], [4096, 4096], [0, 0], [4096, 4096], [0, 4096],\n];",
    ] {
        assert!(code.contains(want), "{want}\n---\n{code}");
    }
    assert_eq!(
        warnings,
        [
            "1 vertex added where faces give a position different texture coordinates (5 in all)",
            "texture a.png: its alpha channel is dropped (zraster draws textures opaque)",
            "material a: opacity 128/255 (MTL d or Tr) carried in TEX_MATERIAL_ALPHA; zraster draws faces opaque",
        ]
    );
    // The same model through to_rust: no textures, said.
    let mut warnings = Vec::new();
    let rust = to_rust(obj, |_| Ok(mtl.into()), &opts, &mut warnings).unwrap();
    assert_eq!((rust.vertices, rust.textures), (4, 0));
    assert!(!rust.code.contains("UVS"));
    assert!(warnings[0].contains("cannot read texture a.png: to_rust reads no textures"));
    assert!(warnings.contains(&"4 `vt` texture coordinates dropped: no face has both them and a material with a texture".to_string()), "{warnings:?}");
}

/// The path of a texture is what a loader in the OBJ file's folder opens.
#[test]
fn texture_paths_are_relative_to_the_obj_folder() {
    let dir = scratch("paths");
    std::fs::create_dir_all(dir.join("a/b")).unwrap();
    std::fs::write(dir.join("a/m.mtl"), "newmtl t\nmap_Kd b/t.png\n").unwrap();
    std::fs::write(
        dir.join("a/b/t.png"),
        png_bytes(1, 1, png::ColorType::Rgb, false, &[0, 0, 255]),
    )
    .unwrap();
    let obj = "mtllib a/m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl t\nf 1/1 2/1 3/1\n";
    let mut loader = MtlLoader::new(&dir);
    let model = parse_obj_with(obj, |n| loader.load(n)).unwrap();
    let map = model.materials[0].map_kd.clone().unwrap();
    assert_eq!(Path::new(&map.path), Path::new("a/b/t.png"));
    let img = loader.load_texture(&map.path).unwrap();
    assert_eq!(img.rgb565(), [0x001F]);
    let _ = std::fs::remove_dir_all(&dir);
}
