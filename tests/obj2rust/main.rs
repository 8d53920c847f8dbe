//! `zraster_obj::to_rust` and the `obj2rust` command: the generated files compile
//! (`module.rs` as a module, `included.rs` through `include!`), are what the converter
//! makes now, carry the MTL colours, and every part of the model left out or changed
//! is a warning.

use std::path::{Path, PathBuf};
use std::process::Command;

use embedded_graphics::pixelcolor::Rgb888;
use zraster::mesh::{Faces, Materials};
use zraster_obj::{rust_prefix, to_rust, RustForm, RustOptions};

/// The checked-in output for `BOX_OBJ`, as a module file.
mod module;

/// The same as items for `include!`, in a module of ours.
#[allow(dead_code, clippy::all)]
mod included {
    include!("included.rs");
}

/// The checked-in textured output (`textures::CRATE_OBJ`), as a module file and as
/// items, and its tests.
mod textured;
#[allow(dead_code, clippy::all)]
mod textured_included {
    include!("textured_included.rs");
}
mod textures;

/// A unit cube: six quads, two MTL colours and one face without a material, with what
/// the converter drops or skips (normals, texture coordinates, grouping, a line, a
/// face with a bad index, an unknown material).
const BOX_OBJ: &str = "\
# a cube with coloured sides
mtllib box.mtl
o box
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
vt 0 0
vt 1 0
vn 0 0 -1
g sides
s off
usemtl red
f 1 4 3 2
f 5/1 6/2 7 8
usemtl blue
f 1//1 2//1 6//1 5//1
f 4 8 7 3
usemtl green
f 1 5 8 4
f 2 3 7
f 7 6 2
l 1 2
f 1 2 99
";

const BOX_MTL: &str = "\
newmtl red
Ka 0 0 0
Kd 1 0 0
newmtl blue
Kd 0 0 1
Ks 1 1 1
";

fn mtl(name: &str) -> Result<String, String> {
    match name {
        "box.mtl" => Ok(BOX_MTL.into()),
        _ => Err("no such file".into()),
    }
}

const WARNINGS: [&str; 9] = [
    "name \"two-colour box\" makes the item prefix TWO_COLOUR_BOX (TWO_COLOUR_BOX_MESH, ...)",
    "line 19: some corners of the face have `vt` texture coordinates and some not: it is kept without",
    "line 23: unknown material \"green\"",
    "line 28: vertex index 99 out of range (the file has 8 vertices): face skipped",
    "5 polygons of more than 3 vertices fan-triangulated into 10 triangles",
    "1 `vn` normal dropped: the normal tables are computed from the positions",
    "statements skipped: `o` (line 3), `g` (line 15), `s` (line 16), `l` (line 27)",
    "material statements skipped (only `newmtl`, `Kd`, `map_Kd`, `d` and `Tr` are read): `Ka`, `Ks`",
    "2 `vt` texture coordinates dropped: no face has both them and a material with a texture",
];

fn here(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/obj2rust")
        .join(file)
}

/// The checked-in files are what `to_rust` makes of `BOX_OBJ` now
/// (`ZRASTER_BLESS=1 cargo test --test obj2rust` rewrites them).
#[test]
fn the_generated_files_are_what_to_rust_makes() {
    for (file, form) in [
        ("module.rs", RustForm::Module),
        ("included.rs", RustForm::Include),
    ] {
        let mut warnings = Vec::new();
        let opts = RustOptions {
            name: "two-colour box",
            form,
        };
        let rust = to_rust(BOX_OBJ, mtl, &opts, &mut warnings).unwrap();
        let last = "4 triangles without a material are white";
        assert_eq!(warnings[..WARNINGS.len()], WARNINGS);
        assert_eq!(warnings[WARNINGS.len()..], [last]);
        assert_eq!(rust.prefix, "TWO_COLOUR_BOX");
        assert_eq!((rust.vertices, rust.triangles, rust.materials), (8, 12, 2));
        let path = here(file);
        if std::env::var_os("ZRASTER_BLESS").is_some() {
            std::fs::write(&path, &rust.code).unwrap();
        }
        let checked_in = std::fs::read_to_string(&path).unwrap();
        assert!(
            checked_in == rust.code,
            "{file} is not what to_rust makes: ZRASTER_BLESS=1 cargo test --test obj2rust"
        );
    }
}

/// The generated consts compile and hold the model: its colours per face, in the order
/// of the faces (red, red, blue, blue, then the unknown material's faces in white).
#[test]
fn the_generated_mesh_carries_the_materials() {
    use module::*;
    let (red, blue, white) = (
        Rgb888::new(255, 0, 0),
        Rgb888::new(0, 0, 255),
        Rgb888::new(255, 255, 255),
    );
    assert_eq!(TWO_COLOUR_BOX_MATERIALS, [red, blue, white]);
    let want: Vec<Rgb888> = [[red; 4], [blue; 4], [white; 4]].concat();
    assert_eq!(TWO_COLOUR_BOX_FACE_COLORS.to_vec(), want);
    match TWO_COLOUR_BOX_MESH.faces {
        Faces::Triangles {
            indices,
            materials: Materials::PerFace(m),
        } => {
            assert_eq!(indices.len(), 12);
            assert_eq!(m, &want[..]);
        }
        other => panic!("{other:?}"),
    }
    // The first quad (1 4 3 2), fanned, around the centre (0.5, 0.5, 0.5).
    assert_eq!(TWO_COLOUR_BOX_INDICES[..2], [[0, 3, 2], [0, 2, 1]]);
    assert_eq!(TWO_COLOUR_BOX_CENTRE, [0.5; 3]);
    assert_eq!(TWO_COLOUR_BOX_POSITIONS[6], [32767; 3]);
    assert_eq!(TWO_COLOUR_BOX_FIT, 1.0);
    // Its first face looks down -Z: the normal is -Z in Q14.
    assert_eq!(TWO_COLOUR_BOX_FACE_NORMALS[0], [0, 0, -16384]);
    assert!(TWO_COLOUR_BOX_MESH.validate().is_ok());
    // The include! form is the same mesh.
    assert_eq!(included::TWO_COLOUR_BOX_MESH, TWO_COLOUR_BOX_MESH);
}

/// One material for every face: a uniform mesh in that colour, no per-face table.
#[test]
fn one_material_makes_a_uniform_mesh() {
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl half\nf 1 2 3\n";
    let mut warnings = Vec::new();
    let rust = to_rust(
        obj,
        |_| Ok("newmtl half\nKd 0.5 0.25 1\n".into()),
        &RustOptions::default(),
        &mut warnings,
    )
    .unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(rust.materials, 1);
    assert!(rust
        .code
        .contains("materials: Materials::Uniform(Rgb888::new(128, 64, 255))"));
    assert!(!rust.code.contains("FACE_COLORS"));
    // A library that cannot be read: white, and said.
    let mut warnings = Vec::new();
    let rust = to_rust(
        obj,
        |_| Err("gone".into()),
        &RustOptions::default(),
        &mut warnings,
    )
    .unwrap();
    assert_eq!(rust.materials, 0);
    assert!(rust.code.contains("Uniform(Rgb888::new(255, 255, 255))"));
    assert_eq!(
        warnings,
        [
            "line 1: cannot read material library m.mtl: gone",
            "line 5: unknown material \"half\""
        ]
    );
}

/// Names become SCREAMING_SNAKE prefixes that are always identifiers.
#[test]
fn names_become_identifiers() {
    let cases = [
        ("bunny", "BUNNY"),
        ("MY-MODEL", "MY_MODEL"),
        ("my-model", "MY_MODEL"),
        ("my model.obj", "MY_MODEL_OBJ"),
        ("myModel", "MY_MODEL"),
        ("HTTPServer", "HTTPSERVER"),
        ("a__b--c", "A_B_C"),
        ("-x-", "X"),
        ("2d", "MODEL_2D"),
        ("1", "MODEL_1"),
        ("", "MODEL"),
        ("___", "MODEL"),
        ("self", "SELF"),
        ("fn", "FN"),
        ("café", "CAF"),
        ("Ωmega", "MEGA"),
        ("v2.1", "V2_1"),
    ];
    for (name, want) in cases {
        assert_eq!(rust_prefix(name), want, "{name:?}");
        // An item made from it parses as a Rust identifier.
        let item = format!("{want}_MESH");
        let mut chars = item.chars();
        assert!(chars.next().is_some_and(|c| c.is_ascii_uppercase()));
        assert!(chars.all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_'));
    }
}

/// Hostile input: an error or warnings, never a panic, and the generated code holds no
/// line break or control character where a name goes into a comment.
#[test]
fn hostile_input_is_an_error_or_a_warning() {
    let errors = [
        ("", "no faces"),
        ("v 0 0 0\n", "no faces"),
        ("v 0 0 0\nf 1 1 9\n", "no faces"),
        ("v 1 2\n", "line 1: missing z"),
        ("v nan 0 0\n", "line 1: x is not finite: \"nan\""),
        ("mtllib m\n", "line 1: in m: line 1: Kd before any newmtl"),
    ];
    for (src, want) in errors {
        let mut warnings = Vec::new();
        let e = to_rust(
            src,
            |_| Ok("Kd 1 0 0\n".into()),
            &RustOptions::default(),
            &mut warnings,
        )
        .unwrap_err();
        assert_eq!(e.to_string(), want, "{src:?}");
    }
    // Eleven bad faces: ten named, then the count.
    let src = format!(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n{}",
        "f 0 1 2\n".repeat(11)
    );
    let mut warnings = Vec::new();
    to_rust(&src, mtl, &RustOptions::default(), &mut warnings).unwrap();
    assert_eq!(warnings.len(), 11, "{warnings:?}");
    assert_eq!(
        warnings[0],
        "line 5: vertex index 0 (OBJ indices start at 1): face skipped"
    );
    assert_eq!(warnings[10], "1 more faces skipped (11 in all)");
    // A material name with a line break's look-alikes and a bidirectional control.
    let obj =
        "mtllib m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\u{202e}b\nf 1 2 3\nusemtl c\nf 1 2 3\n";
    let lib = "newmtl a\u{202e}b\nKd 1 0 0\nnewmtl c\nKd 0 1 0\n";
    let mut warnings = Vec::new();
    let rust = to_rust(
        obj,
        |_| Ok(lib.into()),
        &RustOptions::default(),
        &mut warnings,
    )
    .unwrap();
    assert!(rust.code.contains("// a?b\n"), "{}", rust.code);
    assert!(!rust.code.contains('\u{202e}'));
    // Many kinds of unknown statement: 32 named, the rest counted.
    let src: String = (0..40).map(|k| format!("x{k} 1\n")).collect::<String>()
        + "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let mut warnings = Vec::new();
    to_rust(&src, mtl, &RustOptions::default(), &mut warnings).unwrap();
    assert!(warnings[0].contains("`x31` (line 32)"), "{warnings:?}");
    assert!(!warnings[0].contains("`x32`"));
    assert_eq!(warnings[1], "8 more statements of other kinds skipped");
    // Pseudo-random garbage from the statements the reader knows.
    let words = [
        "v", "f", "vn", "vt", "1", "-1", "0", "2.5", "1e38", "/", "//", "mtllib", "usemtl", "#",
        "x",
    ];
    let mut seed = 0x2545_f491_u32;
    for _ in 0..300 {
        let mut src = String::new();
        for _ in 0..40 {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            src.push_str(words[seed as usize % words.len()]);
            src.push(if seed.is_multiple_of(5) { '\n' } else { ' ' });
        }
        let mut warnings = Vec::new();
        let _ = to_rust(&src, mtl, &RustOptions::default(), &mut warnings);
    }
}

/// The command: the code on stdout, each warning on stderr with the file name, then
/// the counts; the library read from beside the model.
#[test]
fn obj2rust_prints_the_code_and_the_warnings() {
    let dir = std::env::temp_dir().join(format!("zraster-obj2rust-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let obj = dir.join("two-colour box.obj");
    std::fs::write(&obj, BOX_OBJ).unwrap();
    std::fs::write(dir.join("box.mtl"), BOX_MTL).unwrap();
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let run = |args: &[&str]| {
        Command::new(&cargo)
            .args(["run", "--quiet", "--example", "obj2rust", "--"])
            .args(args)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .unwrap()
    };
    let path = obj.to_str().unwrap();
    let out = run(&[path, "two-colour box"]);
    assert!(out.status.success());
    let module = std::fs::read_to_string(here("module.rs")).unwrap();
    assert!(String::from_utf8(out.stdout).unwrap() == module);
    let err = String::from_utf8(out.stderr).unwrap();
    let lines: Vec<&str> = err.lines().collect();
    for (line, want) in lines.iter().zip(WARNINGS) {
        assert_eq!(*line, format!("obj2rust: warning: {path}: {want}"));
    }
    assert_eq!(lines.len(), WARNINGS.len() + 2, "{err}");
    assert_eq!(
        lines[WARNINGS.len() + 1],
        format!("obj2rust: {path}: 8 vertices, 12 triangles, 2 materials: TWO_COLOUR_BOX_MESH")
    );
    let out = run(&["--include", path, "two-colour box"]);
    let included = std::fs::read_to_string(here("included.rs")).unwrap();
    assert!(String::from_utf8(out.stdout).unwrap() == included);
    // Bad input: a message and exit code 2.
    for args in [&["--bogus"][..], &[], &["/nonexistent.obj"]] {
        assert_eq!(run(args).status.code(), Some(2), "{args:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
