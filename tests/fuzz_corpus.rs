//! Replays the fuzz corpus (`fuzz/corpus/<target>/*`) through the fuzz harnesses, so
//! every input the fuzzers kept — including any that once found a bug — is checked on
//! stable Rust in `cargo test`.

use zraster_fuzz_harness as harness;

use std::path::Path;
use zraster::FrameStats;

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

#[test]
fn bands_corpus() {
    assert!(replay("bands", harness::bands) > 0);
}

/// The hand-made bands seeds are not vacuous: each draws pixels, through the binned
/// path, the unbinned one, near-plane clipping and culling between them.
#[test]
fn bands_seeds_draw() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/corpus/bands");
    let mut total = FrameStats::default();
    for name in [
        "floor_flat_bins",
        "floor_lambert_nobins",
        "floor_below_slack",
        "floor_persp",
        "soup_short_bins",
        "soup_light_bins",
        "soup_clipped",
    ] {
        let data = std::fs::read(dir.join(name)).unwrap();
        let s = harness::bands_stats(&data).unwrap_or_else(|| panic!("{name}: not drawn"));
        eprintln!("{name}: {s:?}");
        assert!(s.pixels_written > 50, "{name}: {s:?}");
        total.culled += s.culled;
        total.clipped += s.clipped;
    }
    assert!(total.culled > 0 && total.clipped > 0, "{total:?}");
}
