//! Convert an OBJ model into Rust source for a flash-resident mesh.
//!
//! ```text
//! cargo run --example obj2rust -- [--include] MODEL.obj [NAME] > src/model.rs
//! ```
//! The output holds `const` tables — `i16` positions around the bounding-box centre, `u16`
//! triangle indices, Q14 face and vertex normals, the faces' MTL `Kd` colours — and
//! `NAME_MESH`, a ready `zraster::mesh::Mesh<'static, Rgb888>`, plus `NAME_FIT`, the
//! uniform scale that makes the model's largest extent 1. `NAME` (default `model`)
//! becomes a SCREAMING_SNAKE prefix. Everything is `const`, so on a microcontroller it
//! stays in flash: 6 bytes a vertex and 6 a triangle for the tables, 6 more per vertex
//! and per triangle for the normals. A textured model (`vt`, MTL `map_Kd` PNGs) also
//! gets `NAME_UVS` and its textures as `const` RGB565 tables with a ready
//! `zraster::texture::Texture`. `--include` writes items for `include!` instead of
//! a module file. What was left out or changed is a warning line on stderr, then a line
//! of counts. Exit code 2 on bad input or usage.
//!
//! The conversion is `zraster_obj::to_rust_textured`, which a build script can call too.

use std::cell::RefCell;
use std::path::Path;
use std::process::exit;

use zraster_obj::{to_rust_textured, MtlLoader, RustForm, RustOptions};

const USAGE: &str = "usage: obj2rust [--include] MODEL.obj [NAME] > model.rs";

fn main() {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let mut form = RustForm::Module;
    if let Some(i) = args.iter().position(|a| a == "--include") {
        args.remove(i);
        form = RustForm::Include;
    }
    let (path, name) = match args.as_slice() {
        [p] if !p.starts_with('-') => (p.as_str(), "model"),
        [p, n] if !p.starts_with('-') => (p.as_str(), n.as_str()),
        _ => {
            eprintln!("{USAGE}");
            exit(2)
        }
    };
    let src = std::fs::read_to_string(path).unwrap_or_else(|e| {
        eprintln!("obj2rust: {path}: {e}");
        exit(2)
    });
    let dir = Path::new(path).parent().unwrap_or(Path::new(""));
    // Material libraries and their `map_Kd` textures come from the model's folder.
    let libraries = RefCell::new(MtlLoader::new(dir));
    let mut warnings = Vec::new();
    let result = to_rust_textured(
        &src,
        |lib| libraries.borrow_mut().load(lib),
        |texture| libraries.borrow_mut().load_texture(texture),
        &RustOptions { name, form },
        &mut warnings,
    );
    for w in &warnings {
        eprintln!("obj2rust: warning: {path}: {w}");
    }
    match result {
        Ok(rust) => {
            print!("{}", rust.code);
            eprintln!(
                "obj2rust: {path}: {} vertices, {} triangles, {} materials: {}_MESH",
                rust.vertices, rust.triangles, rust.materials, rust.prefix
            );
        }
        Err(e) => {
            eprintln!("obj2rust: {path}: {e}");
            exit(2)
        }
    }
}
