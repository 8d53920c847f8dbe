//! Replays the fuzz corpus (`fuzz/corpus/<target>/*`) through the fuzz harnesses, so
//! every input the fuzzers kept — including any that once found a bug — is checked on
//! stable Rust in `cargo test`.

#[path = "../fuzz/harness.rs"]
mod harness;

use std::path::Path;

fn replay(target: &str, run: fn(&[u8])) -> usize {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fuzz/corpus")
        .join(target);
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.unwrap().path();
        let data = std::fs::read(&path).unwrap();
        let result = std::panic::catch_unwind(|| run(&data));
        assert!(result.is_ok(), "{} panicked", path.display());
        n += 1;
    }
    n
}

#[test]
fn raster_corpus() {
    assert!(replay("raster", harness::raster) > 0);
}

#[test]
fn pipeline_corpus() {
    assert!(replay("pipeline", harness::pipeline) > 0);
}

#[test]
fn obj_corpus() {
    assert!(replay("obj", harness::obj) > 0);
}
