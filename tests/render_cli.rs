//! The `render` example's command line: the contract outside checks drive.

mod common;

use std::path::Path;
use std::process::Command;
use std::sync::Once;

use common::cli::{example_bin, fails_with, load, render, render_within, run_ok, tmp, write};

use embedded_graphics::{pixelcolor::Rgb888, prelude::*};

const BUNNY: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/models/bunny.obj");
/// The bunny-320 scene of the performance issue.
const BUNNY_320: [&str; 7] = [
    BUNNY,
    "--yaw",
    "30",
    "--distance",
    "1.6",
    "--color",
    "1,0.8,0.6",
];

#[test]
fn bunny_320_matches_its_golden_image_and_stats() {
    let out = tmp("bunny320.png");
    let stats = run_ok(&[&BUNNY_320[..], &["--out", out.to_str().unwrap(), "--stats"]].concat());
    let golden = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden/bunny-320.png");
    if std::env::var_os("ZRASTER_BLESS").is_some() {
        std::fs::copy(&out, &golden).unwrap();
    }
    let (got, want) = (load(&out), load(&golden));
    assert_eq!(got.size(), Size::new(320, 240));
    assert!(
        want.diff(&got).is_none(),
        "bunny-320 differs from {}",
        golden.display()
    );
    // 3674 triangles, about 1480 facing the camera (the count moves by one or two with
    // sub-pixel changes: some are edge-on), about 11,100 covered pixels.
    let field = |name: &str| -> i64 {
        let at = stats.find(&format!("\"{name}\":")).unwrap() + name.len() + 3;
        stats[at..]
            .split(|c: char| !c.is_ascii_digit())
            .next()
            .unwrap()
            .parse()
            .unwrap()
    };
    assert_eq!(field("triangles_in"), 3674, "{stats}");
    assert!((1475..=1485).contains(&field("drawn")), "{stats}");
    assert_eq!(field("culled") + field("drawn"), 3674, "{stats}");
    assert!(
        (11_000..=11_400).contains(&field("pixels_written")),
        "{stats}"
    );
}

#[test]
fn bands_give_identical_output_in_every_mode() {
    for mode in ["zbuffer", "painter", "hidden-line", "wireframe"] {
        let full_png = tmp(&format!("full-{mode}.png"));
        let full_pgm = tmp(&format!("full-{mode}.pgm"));
        let base = [&BUNNY_320[..], &["--size", "160x100", "--mode", mode]].concat();
        run_ok(
            &[
                &base[..],
                &[
                    "--out",
                    full_png.to_str().unwrap(),
                    "--depth-out",
                    full_pgm.to_str().unwrap(),
                ],
            ]
            .concat(),
        );
        for band in ["1", "7", "16", "100"] {
            let png = tmp(&format!("band{band}-{mode}.png"));
            let pgm = tmp(&format!("band{band}-{mode}.pgm"));
            run_ok(
                &[
                    &base[..],
                    &[
                        "--band",
                        band,
                        "--out",
                        png.to_str().unwrap(),
                        "--depth-out",
                        pgm.to_str().unwrap(),
                    ],
                ]
                .concat(),
            );
            assert_eq!(
                std::fs::read(&png).unwrap(),
                std::fs::read(&full_png).unwrap(),
                "{mode} band {band} png"
            );
            assert_eq!(
                std::fs::read(&pgm).unwrap(),
                std::fs::read(&full_pgm).unwrap(),
                "{mode} band {band} pgm"
            );
        }
    }
}

#[test]
fn depth_output_is_a_16_bit_pgm() {
    let (png, pgm) = (tmp("d.png"), tmp("d.pgm"));
    run_ok(&[
        BUNNY,
        "--size",
        "64x48",
        "--out",
        png.to_str().unwrap(),
        "--depth-out",
        pgm.to_str().unwrap(),
    ]);
    let bytes = std::fs::read(&pgm).unwrap();
    let header = b"P5\n64 48\n65535\n";
    assert_eq!(&bytes[..header.len()], header);
    let depth: Vec<u16> = bytes[header.len()..]
        .chunks_exact(2)
        .map(|b| u16::from_be_bytes([b[0], b[1]]))
        .collect();
    assert_eq!(depth.len(), 64 * 48);
    assert_eq!(depth[0], 65535, "a corner is uncovered");
    let img = load(&png);
    for (i, &d) in depth.iter().enumerate() {
        let p = Point::new(i as i32 % 64, i as i32 / 64);
        assert_eq!(d == 65535, img.get_pixel(p) == Rgb888::BLACK, "pixel {p:?}");
    }
    // The bunny at distance 2.5 lies around window depth 0.95-0.97 with near 0.1, far 10.
    let covered: Vec<u16> = depth.iter().copied().filter(|&d| d != 65535).collect();
    assert!(
        covered.iter().all(|&d| (61000..64000).contains(&d)),
        "{:?}",
        covered.iter().min()
    );
}

#[test]
fn bad_input_exits_2_with_a_message() {
    let empty = write("empty.obj", b"");
    fails_with(&[&empty], "no faces");
    let garbage = write("garbage.obj", &[0xff, 0x00, 0x13, 0x80, 0xfe]);
    fails_with(&[&garbage], "not a text file");
    let range = write("range.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 7\n");
    fails_with(&[&range], "line 5");
    let two = write("two.obj", b"v 0 0 0\nv 1 0 0\nf 1 2\n");
    fails_with(&[&two], "line 3");
    let one = write("one.obj", b"v 0 0 0\nf 1\n");
    fails_with(&[&one], "line 2");
    let bad_v = write("badv.obj", b"v 0 zero 0\n");
    fails_with(&[&bad_v], "line 1");
    fails_with(&["/nonexistent/model.obj"], "model.obj");
    // Coordinates that are not finite f32: NaN, ∞, and beyond ±3.4e38 (read as ∞).
    for (i, v) in ["nan", "inf", "-Infinity", "1e39", "-3.5e38"]
        .iter()
        .enumerate()
    {
        let obj = write(
            &format!("nonfinite{i}.obj"),
            format!("v 0 0 0\nv 1 {v} 0\nv 0 1 0\nf 1 2 3\n").as_bytes(),
        );
        fails_with(&[&obj], "line 2: y is not finite");
    }
}

/// A model's f32 coordinates as OBJ text (`{:?}` round-trips every f32 exactly).
fn obj_text(points: &[[f32; 3]], faces: &str) -> Vec<u8> {
    let mut s = String::new();
    for p in points {
        s += &format!("v {:?} {:?} {:?}\n", p[0], p[1], p[2]);
    }
    (s + faces).into_bytes()
}

/// Render `args` with a PNG and a PGM of the depth; their bytes and the stats.
fn render_all(name: &str, args: &[&str]) -> (Vec<u8>, Vec<u8>, String) {
    let (png, pgm) = (tmp(&format!("{name}.png")), tmp(&format!("{name}.pgm")));
    let out = [png.to_str().unwrap(), pgm.to_str().unwrap()];
    let stats = run_ok(&[args, &["--out", out[0], "--depth-out", out[1], "--stats"]].concat());
    (
        std::fs::read(&png).unwrap(),
        std::fs::read(&pgm).unwrap(),
        stats,
    )
}

/// Coordinates up to ±3e38 render exactly as the same model scaled down by a power of
/// two. They drew a blank frame and exited 0: the fit scale's extent overflowed f32
/// (and, from about ±4e9, the face normals did, leaving only the ambient light).
#[test]
fn huge_coordinates_render_as_the_model_scaled_down() {
    let small = [
        [-1.25f32, -1.0, 0.5],
        [1.5, -0.75, -0.25],
        [0.25, 1.75, 0.0],
        [0.0, 0.125, 1.0],
    ];
    let faces = "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
    let scenes: [&[&str]; 3] = [
        &["--size", "96x72"],
        &[
            "--size", "96x72", "--shade", "gouraud", "--yaw", "30", "--pitch", "20",
        ],
        &[
            "--size", "96x72", "--mode", "painter", "--yaw", "200", "--band", "7",
        ],
    ];
    let small_obj = write("tetra.obj", &obj_text(&small, faces));
    for k in [40, 100, 127] {
        let s = 2f32.powi(k);
        let big = small.map(|p| p.map(|v| v * s));
        let big_obj = write(&format!("tetra{k}.obj"), &obj_text(&big, faces));
        for (i, scene) in scenes.iter().enumerate() {
            let want = render_all("tetra", &[&[small_obj.as_str()], *scene].concat());
            let got = render_all("tetra-big", &[&[big_obj.as_str()], *scene].concat());
            assert!(!want.2.contains("\"drawn\":0"), "{}", want.2);
            assert!(want == got, "×2^{k}, scene {i}: {} vs {}", got.2, want.2);
        }
    }
    // The triangle, at ±3e38 and at ±3 (the same quantised positions).
    let tri = |c: &str| format!("v -{c} -{c} 0\nv {c} -{c} 0\nv 0 {c} 0\nf 1 2 3\n");
    let huge = write("tri3e38.obj", tri("3e38").as_bytes());
    let unit = write("tri3.obj", tri("3").as_bytes());
    let (got, want) = (render_all("tri-a", &[&huge]), render_all("tri-b", &[&unit]));
    assert!(got == want, "{} vs {}", got.2, want.2);
    assert!(got.2.contains("\"drawn\":1"), "{}", got.2);
}

/// `mtllib` reads only regular files, each once, of at most 16 MiB: /dev/zero (read
/// without end), a FIFO (blocked forever), a larger file and a missing one are warnings
/// saying why, and the model still renders, in `--color`. Each used to be read whole.
#[test]
fn material_libraries_are_read_safely() {
    let out = tmp("lib-out.png");
    let out = out.to_str().unwrap();
    let tri = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
    let with = |lib: &str| [format!("mtllib {lib}\n").as_bytes(), tri].concat();
    let fifo = tmp("lib.fifo");
    let _ = std::fs::remove_file(&fifo);
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let big = tmp("big.mtl");
    std::fs::File::create(&big)
        .unwrap()
        .set_len((16 << 20) + 1)
        .unwrap();
    let cases = [
        ("/dev/zero", "not a regular file"),
        (fifo.to_str().unwrap(), "not a regular file"),
        (big.to_str().unwrap(), "larger than 16 MiB"),
        ("/nonexistent.mtl", "No such file"),
    ];
    for (lib, why) in cases {
        let obj = write("lib.obj", &with(lib));
        let o = render_within(
            20,
            &[&obj, "--out", out, "--shade", "none", "--color", "0,1,0"],
        );
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{lib}: {err}");
        let want = format!("line 1: cannot read material library {lib}: {why}");
        assert!(err.contains(&want), "{lib}: {err}");
        assert_eq!(
            load(Path::new(out)).get_pixel(Point::new(150, 130)),
            Rgb888::new(0, 255, 0),
            "{lib}: the faces take --color"
        );
    }
    // The same library named three times: read once, and its material used.
    write("red.mtl", b"newmtl red\nKd 1 0 0\n");
    let obj = write(
        "thrice.obj",
        &[
            b"mtllib red.mtl red.mtl\nmtllib ./red.mtl\n".as_slice(),
            tri,
        ]
        .concat(),
    );
    let o = render_within(20, &[&obj, "--out", out, "--shade", "none"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(!String::from_utf8_lossy(&o.stderr).contains("warning"));
    assert_eq!(
        load(Path::new(out)).get_pixel(Point::new(150, 130)),
        Rgb888::new(255, 0, 0)
    );
    // The rule is in --help.
    let help = run_ok(&["--help"]);
    assert!(
        help.contains("regular files only,\nof at most 16 MiB, each once"),
        "{help}"
    );
}

/// A UTF-8 byte-order mark before the first line of an OBJ or MTL file is skipped: the
/// first statement was lost (here the first vertex, then the first material).
#[test]
fn a_byte_order_mark_is_skipped() {
    let dir = tmp("bom");
    std::fs::create_dir_all(&dir).unwrap();
    let obj = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nmtllib m.mtl\nusemtl c\nf 1 2 3 4\n";
    let mtl = "newmtl c\nKd 0.5 0.25 1.0\n";
    let mut outs = Vec::new();
    for bom in ["", "\u{feff}"] {
        std::fs::write(dir.join("m.mtl"), format!("{bom}{mtl}")).unwrap();
        std::fs::write(dir.join("q.obj"), format!("{bom}{obj}")).unwrap();
        let png = dir.join("q.png");
        let o = render(&[
            dir.join("q.obj").to_str().unwrap(),
            "--size",
            "32x32",
            "--out",
            png.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{err}");
        assert!(err.is_empty(), "{err}");
        outs.push(std::fs::read(&png).unwrap());
    }
    assert!(outs[0] == outs[1]);
}

#[test]
fn bad_options_exit_2_with_usage() {
    fails_with(&[], "no MODEL.obj");
    fails_with(&[BUNNY, "--size", "0x10"], "--size");
    fails_with(&[BUNNY, "--size", "1000000x1000000"], "--size");
    fails_with(&[BUNNY, "--size", "big"], "--size");
    fails_with(&[BUNNY, "--mode", "ray"], "--mode");
    fails_with(&[BUNNY, "--cull", "sideways"], "--cull");
    fails_with(&[BUNNY, "--shade", "phong"], "--shade");
    fails_with(&[BUNNY, "--yaw", "nan"], "--yaw");
    fails_with(&[BUNNY, "--near", "1", "--far", "1"], "near");
    fails_with(&[BUNNY, "--fov", "180"], "fov");
    fails_with(&[BUNNY, "--fov", "0"], "fov");
    fails_with(&[BUNNY, "--color", "1,2"], "--color");
    fails_with(&[BUNNY, "--frames", "0"], "--frames");
    fails_with(&[BUNNY, "--band", "0"], "--band");
    fails_with(&[BUNNY, "--bogus"], "unknown option");
    fails_with(&[BUNNY, "--out"], "needs a value");
}

#[test]
fn frames_and_spin_render_the_last_frame() {
    let (a, b) = (tmp("spin.png"), tmp("direct.png"));
    run_ok(&[
        BUNNY,
        "--size",
        "96x72",
        "--frames",
        "3",
        "--spin",
        "15",
        "--out",
        a.to_str().unwrap(),
    ]);
    run_ok(&[
        BUNNY,
        "--size",
        "96x72",
        "--yaw",
        "30",
        "--out",
        b.to_str().unwrap(),
    ]);
    assert!(load(&a).diff(&load(&b)).is_none());
}

#[test]
fn materials_are_used_exactly_without_lighting() {
    let dir = tmp("mtl");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("m.mtl"), "newmtl c\nKd 0.5 0.25 1.0\n").unwrap();
    std::fs::write(
        dir.join("q.obj"),
        "mtllib m.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nusemtl c\nf 1 2 3 4\n",
    )
    .unwrap();
    let out = dir.join("q.png");
    run_ok(&[
        dir.join("q.obj").to_str().unwrap(),
        "--shade",
        "none",
        "--size",
        "32x32",
        "--out",
        out.to_str().unwrap(),
    ]);
    // Kd (0.5, 0.25, 1.0) → RGB565 (16, 16, 31), as e-g converts it to 8 bits.
    let want: Rgb888 = embedded_graphics::pixelcolor::Rgb565::new(16, 16, 31).into();
    assert_eq!(load(&out).get_pixel(Point::new(16, 16)), want);
}

#[test]
fn obj2rust_rejects_bad_input_with_exit_2() {
    static BUILD: Once = Once::new();
    let obj2rust = example_bin("obj2rust", &BUILD);
    // That its output is the committed bench bunny is tests/bench_scene.rs's check.
    // Bad input: a message and exit code 2.
    let bad = Command::new(obj2rust)
        .arg("/nonexistent.obj")
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
}

/// A plain f64 reference of the bunny-320 scene, straight from the OBJ file: the
/// same camera and light, edge functions at pixel centres (top-left rule), depth
/// interpolated in screen space, colour `Kd × I` rounded to RGB565.
fn reference_bunny_320() -> Vec<Option<[u8; 3]>> {
    let obj = zraster_obj::parse_obj(&std::fs::read_to_string(BUNNY).unwrap(), |_| None).unwrap();
    let (w, h) = (320usize, 240usize);
    let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
    for p in &obj.positions {
        for k in 0..3 {
            lo[k] = lo[k].min(f64::from(p[k]));
            hi[k] = hi[k].max(f64::from(p[k]));
        }
    }
    let extent = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    let centre = [
        (lo[0] + hi[0]) / 2.0,
        (lo[1] + hi[1]) / 2.0,
        (lo[2] + hi[2]) / 2.0,
    ];
    let (s, c) = (30f64.to_radians().sin(), 30f64.to_radians().cos());
    // World: fitted, then turned 30° about +Y.
    let world: Vec<[f64; 3]> = obj
        .positions
        .iter()
        .map(|p| {
            let q = [
                (f64::from(p[0]) - centre[0]) / extent,
                (f64::from(p[1]) - centre[1]) / extent,
                (f64::from(p[2]) - centre[2]) / extent,
            ];
            [c * q[0] + s * q[2], q[1], -s * q[0] + c * q[2]]
        })
        .collect();
    let (near, far, dist) = (0.1f64, 10.0f64, 1.6f64);
    let f = 1.0 / 30f64.to_radians().tan();
    let aspect = w as f64 / h as f64;
    // Screen x, y (pixels) and window depth of each vertex.
    let screen: Vec<[f64; 3]> = world
        .iter()
        .map(|p| {
            let ze = p[2] - dist;
            let (xc, yc, wc) = (f / aspect * p[0], f * p[1], -ze);
            let zc = (far + near) / (near - far) * ze + 2.0 * far * near / (near - far);
            [
                (xc / wc + 1.0) / 2.0 * w as f64,
                (1.0 - yc / wc) / 2.0 * h as f64,
                (zc / wc + 1.0) / 2.0,
            ]
        })
        .collect();
    let l = {
        let v = [-1.0f64, 1.0, 1.0];
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        [v[0] / n, v[1] / n, v[2] / n]
    };
    let mut depth = vec![f64::INFINITY; w * h];
    let mut color = vec![None; w * h];
    for t in &obj.triangles {
        let [a, b, cc] = t.vertices.map(|i| screen[i as usize]);
        let area = (b[0] - a[0]) * (cc[1] - a[1]) - (cc[0] - a[0]) * (b[1] - a[1]);
        if area >= 0.0 {
            continue; // back-facing (y down: front faces have negative area)
        }
        let [pa, pb, pc] = t.vertices.map(|i| world[i as usize]);
        let (u, v) = (
            [pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]],
            [pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]],
        );
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let ndl = if len > 0.0 {
            (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / len
        } else {
            0.0
        };
        let i = 0.2 + 0.8 * ndl.max(0.0);
        let q = |kd: f64, max: f64| ((kd * i * max + 0.5).floor()).min(max) as u8;
        let rgb = [q(1.0, 31.0), q(0.8, 63.0), q(0.6, 31.0)];
        // Orient counter-clockwise in y-down terms for the edge tests.
        let p = [a, cc, b];
        let (x0, x1) = (
            p.iter()
                .map(|v| v[0])
                .fold(f64::MAX, f64::min)
                .floor()
                .max(0.0) as usize,
            p.iter()
                .map(|v| v[0])
                .fold(f64::MIN, f64::max)
                .ceil()
                .min(w as f64) as usize,
        );
        let (y0, y1) = (
            p.iter()
                .map(|v| v[1])
                .fold(f64::MAX, f64::min)
                .floor()
                .max(0.0) as usize,
            p.iter()
                .map(|v| v[1])
                .fold(f64::MIN, f64::max)
                .ceil()
                .min(h as f64) as usize,
        );
        for py in y0..y1 {
            for px in x0..x1 {
                let (x, y) = (px as f64 + 0.5, py as f64 + 0.5);
                let mut inside = true;
                let mut bary = [0.0; 3];
                for k in 0..3 {
                    let (e0, e1) = (p[k], p[(k + 1) % 3]);
                    let (dx, dy) = (e1[0] - e0[0], e1[1] - e0[1]);
                    let e = dx * (y - e0[1]) - dy * (x - e0[0]);
                    inside &= e > 0.0 || (e == 0.0 && ((dy == 0.0 && dx > 0.0) || dy < 0.0));
                    bary[(k + 2) % 3] = e;
                }
                if !inside {
                    continue;
                }
                let sum = bary[0] + bary[1] + bary[2];
                let z = (bary[0] * p[0][2] + bary[1] * p[1][2] + bary[2] * p[2][2]) / sum;
                let k = py * w + px;
                if z < depth[k] {
                    depth[k] = z;
                    color[k] = Some(rgb);
                }
            }
        }
    }
    color
}

#[test]
fn bunny_320_is_within_one_lsb_of_a_float_reference_almost_everywhere() {
    let out = tmp("bunny320-ref.png");
    run_ok(&[&BUNNY_320[..], &["--out", out.to_str().unwrap()]].concat());
    let img = load(&out);
    let reference = reference_bunny_320();
    let (mut covered, mut close) = (0, 0);
    for (k, want) in reference.iter().enumerate() {
        let p = Point::new((k % 320) as i32, (k / 320) as i32);
        let got: embedded_graphics::pixelcolor::Rgb565 = img.get_pixel(p).into();
        let got = [got.r(), got.g(), got.b()];
        let drawn = got != [0, 0, 0];
        if want.is_none() && !drawn {
            continue;
        }
        covered += 1;
        if let Some(want) = want {
            if drawn
                && got
                    .iter()
                    .zip(want)
                    .all(|(g, w)| (i16::from(*g) - i16::from(*w)).abs() <= 1)
            {
                close += 1;
            }
        }
    }
    let share = f64::from(close) / f64::from(covered);
    println!(
        "{close} of {covered} covered pixels within 1 LSB ({:.2}%)",
        share * 100.0
    );
    assert!(covered > 11_000);
    assert!(share >= 0.99, "only {:.2}% within 1 LSB", share * 100.0);
}

#[test]
fn no_fit_keeps_raw_coordinates() {
    // A triangle (0,0,0), (0.5,0,0), (0,0.5,0): at distance 2.5 with a 60° field of view
    // its corner (0.5, 0, 0) lands at x = (1 + 0.5·√3/(4/3)/2.5)/2 · 320 = 201.6.
    let tri = write("raw.obj", b"v 0 0 0\nv 0.5 0 0\nv 0 0.5 0\nf 1 2 3\n");
    let (raw, fit) = (tmp("raw.png"), tmp("fit.png"));
    run_ok(&[
        &tri,
        "--no-fit",
        "--shade",
        "none",
        "--out",
        raw.to_str().unwrap(),
    ]);
    run_ok(&[&tri, "--shade", "none", "--out", fit.to_str().unwrap()]);
    let raw = load(&raw);
    let white = Rgb888::WHITE;
    assert_eq!(raw.get_pixel(Point::new(165, 117)), white);
    assert_eq!(raw.get_pixel(Point::new(200, 119)), white);
    assert_eq!(raw.get_pixel(Point::new(203, 119)), Rgb888::BLACK);
    assert_eq!(raw.get_pixel(Point::new(159, 117)), Rgb888::BLACK);
    // Fitted, it is centred on its bounding box and twice the size.
    let fit = load(&fit);
    assert_eq!(fit.get_pixel(Point::new(120, 100)), white);
    assert_eq!(raw.get_pixel(Point::new(120, 100)), Rgb888::BLACK);
}

/// The number after `"key":` in a stats line.
fn stat(stats: &str, key: &str) -> u64 {
    let at = stats
        .find(&format!("\"{key}\":"))
        .unwrap_or_else(|| panic!("{key} in {stats}"));
    let rest = &stats[at + key.len() + 3..];
    rest[..rest.find([',', '}']).unwrap()].parse().unwrap()
}

/// `--damage` sends the last frame of a turning bunny-320 through damage tracking: the
/// same picture, depth and counts, a fraction of the bus bytes of a whole frame
/// (153,611 = 11 + 2 · 320 · 240), whole or banded.
#[test]
fn damage_tracking_sends_a_fraction_and_the_same_picture() {
    let base = [
        BUNNY,
        "--yaw",
        "30",
        "--distance",
        "1.6",
        "--color",
        "1,0.8,0.6",
        "--frames",
        "4",
        "--spin",
        "3",
    ];
    let (png, pgm, stats) = render_all("nodamage", &base);
    for extra in [&["--damage"][..], &["--damage", "--band", "16"]] {
        let (p, d, s) = render_all("damage", &[&base[..], extra].concat());
        assert!(p == png && d == pgm, "{extra:?}: the picture differs");
        assert!(
            s.starts_with(stats.trim_end().trim_end_matches('}')),
            "{s} vs {stats}"
        );
        let (pixels, bytes) = (stat(&s, "damage_pixels"), stat(&s, "bus_bytes"));
        assert!(pixels > 1000 && pixels < 320 * 240 / 4, "{s}");
        assert!(bytes > 2 * pixels && bytes * 3 < 153_611, "{s}");
    }
    assert!(!stats.contains("damage"), "{stats}");
}

/// `--depth-fit` sets near and far from the bunny's bounds: the same picture, and its
/// depths spread over more than half the 16-bit range (2,318 units without).
#[test]
fn depth_fit_spreads_the_depths_over_the_range() {
    let base = [
        BUNNY,
        "--yaw",
        "30",
        "--distance",
        "1.6",
        "--color",
        "1,0.8,0.6",
    ];
    let depths = |pgm: &[u8]| -> Vec<u16> {
        pgm[b"P5\n320 240\n65535\n".len()..]
            .chunks_exact(2)
            .map(|b| u16::from_be_bytes([b[0], b[1]]))
            .filter(|&d| d != 65535)
            .collect()
    };
    let span = |d: &[u16]| d.iter().max().unwrap() - d.iter().min().unwrap();
    let (png, pgm, _) = render_all("nofit", &base);
    let (fpng, fpgm, _) = render_all("fit", &[&base[..], &["--depth-fit"]].concat());
    assert_eq!(png, fpng, "the picture differs");
    let (before, after) = (span(&depths(&pgm)), span(&depths(&fpgm)));
    assert!(before < 3000 && after > 32768, "{before} -> {after}");
}

/// `frames N: X ms/frame, Y fps`, the line `--frames N` prints: N, X and Y.
fn frame_time(line: &str) -> (u32, f64, f64) {
    let parse = || -> Option<(u32, f64, f64)> {
        let rest = line.strip_prefix("frames ")?;
        let (n, rest) = rest.split_once(": ")?;
        let (ms, rest) = rest.split_once(" ms/frame, ")?;
        let fps = rest.strip_suffix(" fps")?;
        // Two decimals for the milliseconds, one for the rate.
        let decimals = |s: &str| s.split_once('.').map(|(_, d)| d.len());
        if decimals(ms) != Some(2) || decimals(fps) != Some(1) {
            return None;
        }
        Some((n.parse().ok()?, ms.parse().ok()?, fps.parse().ok()?))
    };
    parse().unwrap_or_else(|| panic!("not a frame-time line: {line:?}"))
}

/// `--frames N` draws the same frame N times (no `--spin`): the picture is the single
/// frame's, and stdout is one line with the time a frame and the frame rate.
#[test]
fn frames_print_the_frame_time_and_keep_the_picture() {
    let (one, many) = (tmp("frames-1.png"), tmp("frames-12.png"));
    let plain = run_ok(&[&BUNNY_320[..], &["--out", one.to_str().unwrap()]].concat());
    assert_eq!(plain, "", "without --frames stdout stays empty");
    let out = run_ok(
        &[
            &BUNNY_320[..],
            &["--frames", "12", "--out", many.to_str().unwrap()],
        ]
        .concat(),
    );
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 1, "{out}");
    let (n, ms, fps) = frame_time(lines[0]);
    assert_eq!(n, 12);
    assert!(ms > 0.0 && fps > 0.0, "{out}");
    // The same measurement both ways, up to the printed rounding.
    let implied = 1000.0 / fps;
    assert!((implied - ms).abs() <= 0.006 + implied * 0.001, "{out}");
    assert!(std::fs::read(&one).unwrap() == std::fs::read(&many).unwrap());
    assert!(load(&one).diff(&load(&many)).is_none());
    // `--frames 1` given: the line too.
    let out = run_ok(&[
        BUNNY,
        "--size",
        "32x24",
        "--frames",
        "1",
        "--out",
        "/dev/null",
    ]);
    assert_eq!(frame_time(out.trim_end()).0, 1);
}

/// With `--stats`, stdout stays its one JSON line and the frame time goes to stderr.
#[test]
fn frames_with_stats_keep_stdout_one_json_line() {
    let png = tmp("frames-stats.png");
    let args = [
        BUNNY,
        "--size",
        "96x72",
        "--frames",
        "3",
        "--spin",
        "10",
        "--stats",
        "--out",
        png.to_str().unwrap(),
    ];
    let o = render(&args);
    assert!(o.status.success());
    let (out, err) = (
        String::from_utf8(o.stdout).unwrap(),
        String::from_utf8(o.stderr).unwrap(),
    );
    assert_eq!(out.lines().count(), 1, "{out}");
    assert!(out.starts_with("{\"triangles_in\":3674,") && out.ends_with("}\n"));
    let line = err
        .lines()
        .find_map(|l| l.strip_prefix("render: frames "))
        .unwrap_or_else(|| panic!("no frame time on stderr: {err}"));
    assert_eq!(frame_time(&format!("frames {line}")).0, 3);
}

/// A render longer than a second says how far it is on stderr, once a second:
/// `render: frame K/N` with K rising. (More frames until it takes over 1.5 s.)
#[test]
fn long_renders_print_progress() {
    let mut frames = 400u32;
    loop {
        let n = frames.to_string();
        let args = [
            BUNNY,
            "--size",
            "320x240",
            "--frames",
            &n,
            "--spin",
            "1",
            "--out",
            "/dev/null",
        ];
        let o = render(&args);
        assert!(o.status.success());
        let (_, ms, _) = frame_time(String::from_utf8(o.stdout).unwrap().trim_end());
        let seconds = ms * f64::from(frames) / 1000.0;
        let err = String::from_utf8(o.stderr).unwrap();
        let done: Vec<u32> = err
            .lines()
            .map(|l| {
                let k = l
                    .strip_prefix("render: frame ")
                    .and_then(|r| r.strip_suffix(&format!("/{frames}")))
                    .unwrap_or_else(|| panic!("unexpected stderr line {l:?}"));
                k.parse().unwrap()
            })
            .collect();
        // One a second after the first: none under a second, about one per second.
        if seconds < 1.0 {
            assert!(done.is_empty(), "{seconds} s: {err}");
        }
        assert!(done.len() as f64 <= seconds + 0.5, "{seconds} s: {err}");
        assert!(done.windows(2).all(|w| w[0] < w[1]), "{err}");
        assert!(done.iter().all(|&k| k > 0 && k < frames), "{err}");
        if seconds > 1.5 {
            assert!(!done.is_empty(), "{seconds} s and no progress line");
            break;
        }
        assert!(frames < 1 << 20, "rendering never took 1.5 s");
        frames *= 4;
    }
}
