//! The reader's unit tests.

use super::*;
use std::path::PathBuf;

#[test]
fn bounds_and_fit_scale() {
    let box_ = [[-1.0, 0.5, 2.0], [1.0, 0.0, 2.5], [0.0, -0.5, 2.25]];
    assert_eq!(bounds(&box_), ([-1.0, -0.5, 2.0], [1.0, 0.5, 2.5]));
    assert_eq!(fit_scale(&box_), 0.5); // largest extent 2 (x)
    assert_eq!(bounds(&[]), ([0.0; 3], [0.0; 3]));
    assert_eq!(fit_scale(&[]), 1.0);
    assert_eq!(fit_scale(&[[3.0, 3.0, 3.0]]), 1.0);
}

fn parse(s: &str) -> Result<ObjModel, ObjError> {
    parse_obj(s, |_| None)
}

/// A byte-order mark before the first statement is skipped: the first vertex is
/// kept (it was dropped, and the face then referred to a missing vertex).
#[test]
fn a_byte_order_mark_is_skipped() {
    let m = parse("\u{feff}v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    assert_eq!(m.positions.len(), 3);
    assert_eq!(m.positions[0], [0.0, 0.0, 0.0]);
    let mut mats = Vec::new();
    parse_mtl("\u{feff}newmtl red\nKd 1 0 0\n", &mut mats).unwrap();
    assert_eq!(mats.len(), 1);
    assert_eq!(mats[0].name, "red");
}

#[test]
fn faces_in_every_reference_form() {
    let m = parse("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1 2/2/2 3//3 -1\n").unwrap();
    assert_eq!(m.positions.len(), 4);
    let t: Vec<[u32; 3]> = m.triangles.iter().map(|t| t.vertices).collect();
    assert_eq!(t, [[0, 1, 2], [0, 2, 3]]);
    assert_eq!(m.triangle_indices(), [[0u16, 1, 2], [0, 2, 3]]);
}

#[test]
fn materials_from_the_library() {
    let mtl = "newmtl red\nKd 1 0 0\nnewmtl half\nKd 0.5 0.5 0.5\n";
    let src =
        "mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl half\nf 1 2 3\nusemtl nope\nf 1 2 3\n";
    let m = parse_obj(src, |name| (name == "a.mtl").then(|| mtl.to_string())).unwrap();
    assert_eq!(m.materials[1].kd, [0.5; 3]);
    assert_eq!(m.triangles[0].material, Some(1));
    assert_eq!(m.triangles[1].material, None);
    assert_eq!(m.warnings.len(), 1);
}

#[test]
fn malformed_lines_are_errors_with_their_line() {
    let cases = [
        ("v 1 2\n", 1, "missing z"),
        ("v 0 0 0\nv a 0 0\n", 2, "not a number"),
        ("v 0 0 nan\n", 1, "not finite"),
        ("v 0 inf 0\n", 1, "not finite"),
        ("v 0 0 0\nv -infinity 0 0\n", 2, "not finite"),
        // Beyond f32::MAX: it parses as ∞.
        ("v 1e39 0 0\n", 1, "not finite"),
        ("v 0 0 0\nv 0 0 0\nf 1 2\n", 3, "3 or more"),
        ("v 0 0 0\nf 1 2 9\n", 2, "out of range"),
        ("v 0 0 0\n\nf 0 1 1\n", 3, "index 0"),
        ("v 0 0 0\nf -5 1 1\n", 2, "out of range"),
        ("f 1/2 x 3\n", 1, "bad vertex"),
    ];
    for (src, line, what) in cases {
        let e = parse(src).unwrap_err();
        assert_eq!(e.line, line, "{src:?}: {e}");
        assert!(e.message.contains(what), "{src:?}: {e}");
    }
}

/// A library named again (on the same line or another) is asked for once.
#[test]
fn a_repeated_library_is_loaded_once() {
    let mut loads = Vec::new();
    let src = "mtllib a.mtl a.mtl\nmtllib b.mtl\nmtllib a.mtl b.mtl\nv 0 0 0\n";
    let m = parse_obj(src, |name| {
        loads.push(name.to_string());
        Some("newmtl red\nKd 1 0 0\n".into())
    })
    .unwrap();
    assert_eq!(loads, ["a.mtl", "b.mtl"]);
    assert_eq!(m.materials.len(), 2);
    // One that cannot be read: one warning, with the reason.
    let mut asked = 0;
    let m = parse_obj_with("mtllib x.mtl x.mtl\nmtllib x.mtl\n", |_| {
        asked += 1;
        Err("gone".into())
    })
    .unwrap();
    assert_eq!(asked, 1);
    assert_eq!(
        m.warnings,
        ["line 1: cannot read material library x.mtl: gone"]
    );
}

/// A scratch folder for one test.
fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("zraster-obj-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Only regular files of at most MAX_MTL_BYTES are read: a device never ends, a FIFO
/// blocks its reader forever (this test would hang), a large file is refused unread.
#[test]
#[cfg(unix)]
fn the_loader_reads_only_regular_files_of_bounded_size() {
    let dir = scratch("loader-kinds");
    let mut mtl = MtlLoader::new(&dir);
    assert_eq!(mtl.load("/dev/zero"), Err("not a regular file".into()));
    assert_eq!(mtl.load("."), Err("not a regular file".into()));
    let made = std::process::Command::new("mkfifo")
        .arg(dir.join("pipe.mtl"))
        .status()
        .unwrap();
    assert!(made.success());
    assert_eq!(mtl.load("pipe.mtl"), Err("not a regular file".into()));
    // A sparse file one byte over the limit (no 16 MiB written).
    let big = std::fs::File::create(dir.join("big.mtl")).unwrap();
    big.set_len(MAX_MTL_BYTES + 1).unwrap();
    assert_eq!(mtl.load("big.mtl"), Err("larger than 16 MiB".into()));
    let at_limit = std::fs::File::create(dir.join("limit.mtl")).unwrap();
    at_limit.set_len(MAX_MTL_BYTES).unwrap();
    assert_eq!(mtl.load("limit.mtl").map(|t| t.len()), Ok(16 << 20));
    assert!(mtl.load("missing.mtl").is_err());
    std::fs::write(dir.join("latin1.mtl"), b"newmtl caf\xe9\n").unwrap();
    assert_eq!(mtl.load("latin1.mtl"), Err("not UTF-8 text".into()));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Each file is read once, whatever name reaches it; the text is the file's.
#[test]
#[cfg(unix)]
fn the_loader_reads_each_file_once() {
    let dir = scratch("loader-once");
    std::fs::write(dir.join("red.mtl"), "\u{feff}newmtl red\nKd 1 0 0\n").unwrap();
    std::os::unix::fs::symlink(dir.join("red.mtl"), dir.join("alias.mtl")).unwrap();
    let mut mtl = MtlLoader::new(&dir);
    let src = "mtllib red.mtl ./red.mtl\nmtllib alias.mtl\nv 0 0 0\nusemtl red\n";
    let m = parse_obj_with(src, |name| mtl.load(name)).unwrap();
    assert_eq!(m.materials.len(), 1, "{:?}", m.materials);
    assert_eq!(m.materials[0].kd, [1.0, 0.0, 0.0]);
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
    assert_eq!(mtl.load("red.mtl"), Ok(String::new()));
    // By absolute path too.
    let abs = dir.join("red.mtl");
    assert_eq!(mtl.load(abs.to_str().unwrap()), Ok(String::new()));
    let _ = std::fs::remove_dir_all(&dir);
}

/// fit_scale at the top of f32's range: the extent, 6e38, overflowed f32 and the
/// scale was 0 (the model collapsed to a point).
#[test]
fn fit_scale_does_not_overflow_near_f32_max() {
    let huge = [[-3e38, -3e38, 0.0], [3e38, -3e38, 0.0], [0.0, 3e38, 0.0]];
    let s = fit_scale(&huge);
    assert!(s > 0.0 && s.is_finite(), "{s}");
    let s = fit_scale_f64(&huge);
    assert!((s * 6e38 - 1.0).abs() < 1e-7, "{s}");
    let max = [[-f32::MAX; 3], [f32::MAX; 3]];
    assert!((fit_scale_f64(&max) * 2.0 * f64::from(f32::MAX) - 1.0).abs() < 1e-7);
}

/// Where f32 arithmetic suffices, fit_scale is exactly what it always was.
#[test]
fn fit_scale_is_the_f32_quotient_where_that_is_normal() {
    let f32_fit = |p: &[[f32; 3]]| {
        let (lo, hi) = bounds(p);
        1.0 / (0..3).map(|k| hi[k] - lo[k]).fold(0.0f32, f32::max)
    };
    let boxes: [[[f32; 3]; 2]; 6] = [
        [[-0.0947, 0.0330, -0.0619], [0.0610, 0.1873, 0.0588]],
        [[-1.0, 0.5, 2.0], [1.0, 0.0, 2.5]],
        [[0.1, 0.2, 0.3], [0.7, 0.11, 0.3]],
        [[1e-30, 0.0, 0.0], [3e-30, 0.0, 0.0]],
        [[-3e37, 0.0, 0.0], [5e37, 1.0, 1.0]],
        [[123456.79, -7.0, 1e-3], [-98765.43, 3.0, 2.0]],
    ];
    for b in boxes {
        assert_eq!(fit_scale(&b).to_bits(), f32_fit(&b).to_bits(), "{b:?}");
        assert_eq!(fit_scale_f64(&b), f64::from(f32_fit(&b)), "{b:?}");
    }
}

/// A model 2^127 times larger (up to ±3e38) quantises to the same positions, with a
/// scale exactly 2^127 larger, and fits with a scale exactly 2^127 smaller.
#[test]
fn a_model_scaled_by_a_power_of_two_quantises_and_fits_alike() {
    let small = [
        [-1.25f32, -1.0, 0.5],
        [1.5, -0.75, -0.25],
        [0.25, 1.75, 0.0],
        [0.0, 0.125, 1.0],
        [1.7, 1.7, 1.7],
    ];
    let k = 2f32.powi(127);
    let huge = small.map(|p| p.map(|v| v * k));
    for centre in [true, false] {
        let (a, b) = (quantize(&small, centre), quantize(&huge, centre));
        assert_eq!(a.positions, b.positions);
        assert_eq!(a.scale * k, b.scale);
        assert_eq!(a.offset.map(|o| o * k), b.offset);
    }
    assert_eq!(fit_scale_f64(&small), fit_scale_f64(&huge) * f64::from(k));
}

/// All positions above f32::MAX / 2: lo + hi overflowed, the centre was ∞ and every
/// position quantised to -32767.
#[test]
fn quantisation_centres_boxes_near_f32_max() {
    let p = [[2e38, 3e38, 3.4e38], [3.4e38, 2.5e38, 3.3e38]];
    let q = quantize(&p, true);
    assert!(q.offset.iter().all(|o| o.is_finite()), "{:?}", q.offset);
    assert!(q.scale.is_finite());
    for (a, b) in p.iter().zip(&q.positions) {
        for k in 0..3 {
            let back = f64::from(b[k]) * f64::from(q.scale) + f64::from(q.offset[k]);
            let step = f64::from(q.scale);
            assert!((back - f64::from(a[k])).abs() <= step * 0.51, "{a:?} {b:?}");
        }
    }
    // The widest box: 2 × f32::MAX, half of it each side of the centre.
    let p = [[-f32::MAX, 0.0, 0.0], [f32::MAX - 2f32.powi(104), 1.0, 0.0]];
    let q = quantize(&p, true);
    assert!(q.scale.is_finite() && q.scale > 0.0);
    assert_eq!(q.positions[0][0], -32767);
    assert_eq!(q.positions[1][0], 32767);
}

#[test]
fn quantisation_round_trips_within_half_a_step() {
    let p = [[-1.0, 2.0, 0.5], [3.0, -2.0, 0.25], [0.0, 0.0, 0.0]];
    let q = quantize(&p, true);
    for (a, b) in p.iter().zip(&q.positions) {
        for k in 0..3 {
            let back = f32::from(b[k]) * q.scale + q.offset[k];
            assert!((back - a[k]).abs() <= q.scale * 0.5 + 1e-6);
        }
    }
}
