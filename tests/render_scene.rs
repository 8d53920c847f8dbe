//! The `render` contract for textures (`vt`, `map_Kd`) and scenes (`--add`), checked
//! against hand-computed pictures.

mod common;

use std::path::{Path, PathBuf};

use common::cli::{fails_with, load, render, run_ok, tmp};
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettings, SimulatorDisplay};

/// A folder of its own for a test's files.
fn folder(name: &str) -> PathBuf {
    let dir = tmp(name);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Write a PNG of `w × h` texels coloured by `texel(column, row)`.
fn write_png(path: &Path, w: u32, h: u32, texel: impl Fn(u32, u32) -> Rgb888) {
    let mut image = SimulatorDisplay::<Rgb888>::new(Size::new(w, h));
    for (x, y) in (0..h).flat_map(|y| (0..w).map(move |x| (x, y))) {
        Pixel(Point::new(x as i32, y as i32), texel(x, y))
            .draw(&mut image)
            .unwrap();
    }
    image
        .to_rgb_output_image(&OutputSettings::default())
        .save_png(path)
        .unwrap();
}

/// The 8×8 test texture: column and row in red and green, so every texel differs.
fn texel(c: u32, r: u32) -> Rgb888 {
    Rgb888::new((c * 32 + 16) as u8, (r * 32 + 16) as u8, 200)
}

/// A floor at y = −0.5 from z = 1 to z = −10, two textures across (u) and four deep
/// (v): seen from the default camera (0, 0, 2.5) it recedes steeply.
const FLOOR: &str = "mtllib floor.mtl\n\
    v -1 -0.5 1\nv 1 -0.5 1\nv 1 -0.5 -10\nv -1 -0.5 -10\n\
    vt 0 0\nvt 2 0\nvt 2 4\nvt 0 4\n\
    usemtl tex\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";

/// The floor's folder, with `mtl` as its material library and the texture.
fn floor(name: &str, mtl: &str) -> PathBuf {
    let dir = folder(name);
    std::fs::write(dir.join("floor.obj"), FLOOR).unwrap();
    std::fs::write(dir.join("floor.mtl"), mtl).unwrap();
    write_png(&dir.join("checker.png"), 8, 8, texel);
    dir
}

const W: u32 = 320;
const H: u32 = 240;

/// Where the ray through pixel (px, py)'s centre meets the floor, as the camera of
/// `render` (eye at z = 2.5 looking down −z, 60° vertical field of view) sees it.
fn floor_point(px: f64, py: f64) -> Option<(f64, f64)> {
    let t = (30f64).to_radians().tan();
    let nx = (px + 0.5) / f64::from(W) * 2.0 - 1.0;
    let ny = 1.0 - (py + 0.5) / f64::from(H) * 2.0;
    let d = [nx * t * f64::from(W) / f64::from(H), ny * t, -1.0];
    if d[1] >= 0.0 {
        return None;
    }
    let s = -0.5 / d[1];
    let (x, z) = (s * d[0], 2.5 - s);
    (x.abs() < 0.95 && z < 0.95 && z > -9.95).then_some((x, z))
}

/// The floor's (u, v) at a point on it.
fn floor_uv((x, z): (f64, f64)) -> (f64, f64) {
    (x + 1.0, (1.0 - z) / 11.0 * 4.0)
}

/// The texel (u, v) samples under the contract: column ⌊u·W⌋ mod W, row ⌊(1 − v)·H⌋
/// mod H; `None` within 0.15 texel of a texel's border (rounding may go either way).
fn sampled((u, v): (f64, f64)) -> Option<(u32, u32)> {
    let (x, y) = (u * 8.0, (1.0 - v) * 8.0);
    let clear = |a: f64| (0.15..0.85).contains(&(a - a.floor()));
    (clear(x) && clear(y)).then(|| {
        (
            (x.floor() as i64).rem_euclid(8) as u32,
            (y.floor() as i64).rem_euclid(8) as u32,
        )
    })
}

/// The floor's corners on screen (pixel units) with their (u, v).
fn floor_corners() -> [((f64, f64), (f64, f64)); 4] {
    let t = (30f64).to_radians().tan();
    let aspect = f64::from(W) / f64::from(H);
    let screen = |x: f64, y: f64, z: f64| {
        let dist = 2.5 - z;
        let (nx, ny) = (x / dist / t / aspect, y / dist / t);
        (
            (nx + 1.0) / 2.0 * f64::from(W),
            (1.0 - ny) / 2.0 * f64::from(H),
        )
    };
    [
        (screen(-1.0, -0.5, 1.0), (0.0, 0.0)),
        (screen(1.0, -0.5, 1.0), (2.0, 0.0)),
        (screen(1.0, -0.5, -10.0), (2.0, 4.0)),
        (screen(-1.0, -0.5, -10.0), (0.0, 4.0)),
    ]
}

/// The (u, v) an affine mapping gives pixel (px, py): interpolated linearly across
/// the screen triangle (1, 2, 3) or (1, 3, 4) holding its centre.
fn affine_uv(px: f64, py: f64) -> Option<(f64, f64)> {
    let c = floor_corners();
    let p = (px + 0.5, py + 0.5);
    for [a, b, d] in [[c[0], c[1], c[2]], [c[0], c[2], c[3]]] {
        let area = |p: (f64, f64), q: (f64, f64), r: (f64, f64)| {
            (q.0 - p.0) * (r.1 - p.1) - (r.0 - p.0) * (q.1 - p.1)
        };
        let all = area(a.0, b.0, d.0);
        let (wa, wb, wd) = (
            area(p, b.0, d.0) / all,
            area(a.0, p, d.0) / all,
            area(a.0, b.0, p) / all,
        );
        if wa >= 0.0 && wb >= 0.0 && wd >= 0.0 {
            let u = wa * a.1 .0 + wb * b.1 .0 + wd * d.1 .0;
            let v = wa * a.1 .1 + wb * b.1 .1 + wd * d.1 .1;
            return Some((u, v));
        }
    }
    None
}

/// The texel a pixel of the picture shows, as `render` writes it (RGB565).
fn shown(t: Rgb888) -> Rgb888 {
    Rgb565::from(t).into()
}

/// A steep textured floor with `--shade none`: every pixel whose centre samples a
/// texel clearly (away from texel borders, where a pixel spans under a quarter of a
/// texel) is exactly that texel, perspective-correct. An affine mapping would show
/// other texels, several rows off, on most of those pixels: the test tells them apart.
#[test]
fn a_steep_textured_floor_shows_the_perspective_correct_texel() {
    let dir = floor("floor", "newmtl tex\nKd 1 1 1\nmap_Kd checker.png\n");
    let out = dir.join("out.png");
    let obj = dir.join("floor.obj");
    let args = [obj.to_str().unwrap(), "--no-fit", "--cull", "none"];
    run_ok(
        &[
            &args[..],
            &["--shade", "none", "--out", out.to_str().unwrap()],
        ]
        .concat(),
    );
    let picture = load(&out);
    let (mut checked, mut affine_off) = (0, 0);
    for (px, py) in (0..H).flat_map(|y| (0..W).map(move |x| (x, y))) {
        let (x, y) = (f64::from(px), f64::from(py));
        let Some(at) = floor_point(x, y) else {
            continue;
        };
        // Under a quarter texel a pixel, across and down.
        let (u0, v0) = floor_uv(at);
        let step = |p: Option<(f64, f64)>| {
            p.map(floor_uv)
                .map(|(u, v)| ((u - u0) * 8.0).abs() + ((v - v0) * 8.0).abs())
        };
        if !matches!((step(floor_point(x + 1.0, y)), step(floor_point(x, y + 1.0))), (Some(a), Some(b)) if a < 0.25 && b < 0.25)
        {
            continue;
        }
        let Some((c, r)) = sampled((u0, v0)) else {
            continue;
        };
        let got = picture.get_pixel(Point::new(px as i32, py as i32));
        assert_eq!(
            got,
            shown(texel(c, r)),
            "pixel ({px}, {py}): texel ({c}, {r})"
        );
        checked += 1;
        let (au, av) = affine_uv(x, y).unwrap();
        let affine_row = (((1.0 - av) * 8.0).floor() as i64).rem_euclid(8) as u32;
        let affine_col = ((au * 8.0).floor() as i64).rem_euclid(8) as u32;
        if (affine_col, affine_row) != (c, r) && affine_row.abs_diff(r) >= 2 {
            affine_off += 1;
        }
    }
    assert!(checked > 2_000, "only {checked} pixels checked");
    assert!(
        affine_off * 2 > checked,
        "affine would differ by 2+ texel rows on only {affine_off} of {checked}"
    );
}

/// Lit textures are lit as flat colours are: a 1×1 texture of a colour gives exactly
/// the picture of the same faces in a `Kd` of that colour, with Lambert and Gouraud
/// light. A texture that cannot be read is a warning, and the faces take their `Kd`.
#[test]
fn lit_textures_match_flat_colours_and_missing_ones_fall_back() {
    let dir = folder("lit");
    let obj = "mtllib m.mtl\nv -1 -1 0\nv 1 -1 0.3\nv 1 1 0\nv -1 1 -0.4\n\
               vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nusemtl m\n\
               f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
    std::fs::write(dir.join("q.obj"), obj).unwrap();
    write_png(&dir.join("one.png"), 1, 1, |_, _| Rgb888::new(200, 120, 40));
    let kd = format!("{:?} {:?} {:?}", 200.0 / 255.0, 120.0 / 255.0, 40.0 / 255.0);
    let draw = |mtl: &str, shade: &str, name: &str| {
        std::fs::write(dir.join("m.mtl"), mtl).unwrap();
        let out = dir.join(format!("{name}.png"));
        let args = [
            dir.join("q.obj").to_str().unwrap().to_string(),
            "--shade".into(),
            shade.into(),
            "--yaw".into(),
            "25".into(),
            "--out".into(),
            out.to_str().unwrap().to_string(),
        ];
        let result = render(&args.iter().map(String::as_str).collect::<Vec<_>>());
        assert!(
            result.status.success(),
            "{}",
            String::from_utf8_lossy(&result.stderr)
        );
        (
            load(&out),
            String::from_utf8_lossy(&result.stderr).into_owned(),
        )
    };
    for shade in ["lambert", "gouraud", "none"] {
        let (textured, _) = draw("newmtl m\nKd 1 1 1\nmap_Kd one.png\n", shade, "t");
        let (flat, _) = draw(&format!("newmtl m\nKd {kd}\n"), shade, "f");
        assert!(
            textured.diff(&flat).is_none(),
            "{shade}: texture and Kd differ"
        );
        let (missing, warning) = draw(&format!("newmtl m\nKd {kd}\nmap_Kd gone.png\n"), shade, "m");
        assert!(
            missing.diff(&flat).is_none(),
            "{shade}: missing texture not drawn in Kd"
        );
        assert!(
            warning.contains("cannot read texture gone.png"),
            "{warning}"
        );
    }
}

/// A unit square facing the camera (extent 1 once fitted).
const SQUARE: &str = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";

/// `--add` places another model beside the main one: fitted like it, moved by its
/// offset, then turned with the rest; `--band` draws the same scene byte for byte.
#[test]
fn added_models_join_the_scene() {
    let dir = folder("add");
    let square = dir.join("square.obj");
    std::fs::write(&square, SQUARE).unwrap();
    let sq = square.to_str().unwrap();
    let beside = format!("{sq}@1.5,0,0");
    let run = |extra: &[&str], name: &str| {
        let out = dir.join(format!("{name}.png"));
        let depth = dir.join(format!("{name}.pgm"));
        let stats = run_ok(
            &[
                &[
                    sq,
                    "--shade",
                    "none",
                    "--stats",
                    "--out",
                    out.to_str().unwrap(),
                    "--depth-out",
                    depth.to_str().unwrap(),
                ][..],
                extra,
            ]
            .concat(),
        );
        (
            std::fs::read(&out).unwrap(),
            std::fs::read(&depth).unwrap(),
            stats,
        )
    };
    let (alone, _, _) = run(&[], "alone");
    let (both, both_depth, both_stats) = run(&["--add", &beside], "both");
    let picture = load(&dir.join("both.png"));
    let lit = |x: i32| picture.get_pixel(Point::new(x, 120)) != Rgb888::BLACK;
    // The main square spans x = ±0.5 at distance 2.5: pixels 118..202 (60° high,
    // 4:3); the added one x = 1..2: from pixel 243 to the right edge.
    assert!(lit(160) && lit(125) && lit(195), "the main square");
    assert!(!lit(220) && !lit(236), "the gap between them");
    assert!(lit(250) && lit(300) && lit(319), "the added square");
    assert_ne!(alone, both);
    assert!(both_stats.contains("\"triangles_in\":4"), "{both_stats}");
    // Turned with the rest: at yaw 180 the added square is on the left.
    let (turned, _, _) = run(
        &["--add", &beside, "--yaw", "180", "--cull", "none"],
        "turned",
    );
    let _ = turned;
    let t = load(&dir.join("turned.png"));
    assert!(t.get_pixel(Point::new(20, 120)) != Rgb888::BLACK);
    assert!(t.get_pixel(Point::new(300, 120)) == Rgb888::BLACK);
    // The same scene in bands of 7 rows: picture, depth and stats identical.
    let (banded, banded_depth, banded_stats) = run(&["--add", &beside, "--band", "7"], "banded");
    assert_eq!(banded, both);
    assert_eq!(banded_depth, both_depth);
    assert_eq!(banded_stats, both_stats);
    // The same model added at the same place hides nothing and adds nothing.
    let (twice, _, twice_stats) = run(&["--add", &format!("{sq}@0,0,0")], "twice");
    assert_eq!(twice, alone);
    assert!(twice_stats.contains("\"triangles_in\":4"), "{twice_stats}");
}

/// A textured scene (the floor with a square added above it) drawn in bands equals
/// the whole frame: picture, depth and stats.
#[test]
fn textured_scenes_in_bands_equal_the_whole_frame() {
    let dir = floor("banded", "newmtl tex\nKd 1 1 1\nmap_Kd checker.png\n");
    let square = dir.join("square.obj");
    std::fs::write(&square, SQUARE).unwrap();
    let add = format!("{}@0,0.2,-2", square.to_str().unwrap());
    let obj = dir.join("floor.obj");
    let run = |band: &[&str], name: &str| {
        let (out, depth) = (
            dir.join(format!("{name}.png")),
            dir.join(format!("{name}.pgm")),
        );
        let args = [
            obj.to_str().unwrap(),
            "--add",
            &add,
            "--pitch",
            "20",
            "--stats",
            "--out",
            out.to_str().unwrap(),
            "--depth-out",
            depth.to_str().unwrap(),
        ];
        let stats = run_ok(&[&args[..], band].concat());
        (
            std::fs::read(out).unwrap(),
            std::fs::read(depth).unwrap(),
            stats,
        )
    };
    let whole = run(&[], "whole");
    for rows in ["1", "13", "240"] {
        assert_eq!(run(&["--band", rows], "bands"), whole, "--band {rows}");
    }
}

#[test]
fn bad_add_options_exit_2() {
    let dir = folder("badadd");
    let square = dir.join("square.obj");
    std::fs::write(&square, SQUARE).unwrap();
    let sq = square.to_str().unwrap();
    fails_with(&[sq, "--add", sq], "--add needs FILE.obj@X,Y,Z");
    fails_with(
        &[sq, "--add", &format!("{sq}@1,2")],
        "--add needs FILE.obj@X,Y,Z",
    );
    fails_with(&[sq, "--add", &format!("{sq}@1,nan,2")], "finite number");
    fails_with(&[sq, "--add", "/nonexistent/b.obj@0,0,0"], "b.obj");
}

/// MTL `d` (and `Tr`, its complement): see-through faces drawn after the opaque ones,
/// blended over them, their depth not written. A blue square at opacity `d` in front
/// of a red one (listed first, so order in the file does not matter).
#[test]
fn see_through_materials_blend_over_what_is_behind() {
    let dir = folder("alpha");
    let obj = "mtllib m.mtl\n\
               v -0.5 -0.5 0\nv 0.5 -0.5 0\nv 0.5 0.5 0\nv -0.5 0.5 0\n\
               v -1 -1 -0.5\nv 1 -1 -0.5\nv 1 1 -0.5\nv -1 1 -0.5\n\
               usemtl glass\nf 1 2 3 4\nusemtl red\nf 5 6 7 8\n";
    std::fs::write(dir.join("q.obj"), obj).unwrap();
    let run = |glass: &str, extra: &[&str], name: &str| {
        std::fs::write(
            dir.join("m.mtl"),
            format!("newmtl red\nKd 1 0 0\nnewmtl glass\nKd 0 0 1\n{glass}\n"),
        )
        .unwrap();
        let (out, depth) = (
            dir.join(format!("{name}.png")),
            dir.join(format!("{name}.pgm")),
        );
        let q = dir.join("q.obj");
        let args = [
            q.to_str().unwrap(),
            "--no-fit",
            "--shade",
            "none",
            "--stats",
        ];
        let outs = [
            "--out",
            out.to_str().unwrap(),
            "--depth-out",
            depth.to_str().unwrap(),
        ];
        let stats = run_ok(&[&args[..], &outs, extra].concat());
        let pgm = std::fs::read(&depth).unwrap();
        (load(&out), pgm, stats)
    };
    let rgb = |r, g, b| -> Rgb888 { Rgb565::new(r, g, b).into() };
    let (centre, edge) = (Point::new(160, 120), Point::new(212, 120));
    // d 0.5: alpha 128, the mean of the two, rounded down.
    let (half, half_depth, half_stats) = run("d 0.5", &[], "half");
    assert_eq!(half.get_pixel(centre), rgb(15, 0, 15));
    assert_eq!(half.get_pixel(edge), rgb(31, 0, 0));
    // Tr 0.75 is d 0.25: alpha 64, red + (blue − red) · 64 / 255 rounded.
    let (quarter, _, _) = run("Tr 0.75", &[], "quarter");
    assert_eq!(quarter.get_pixel(centre), rgb(23, 0, 8));
    // Opaque glass hides the red; its depth is the one stored there. See-through, the
    // red square's depth stays.
    let (opaque, opaque_depth, _) = run("d 1", &[], "opaque");
    assert_eq!(opaque.get_pixel(centre), rgb(0, 0, 31));
    let at = |pgm: &[u8], p: Point| {
        let i = pgm.len() - 2 * (W * H) as usize + 2 * (p.y as usize * W as usize + p.x as usize);
        u16::from_be_bytes([pgm[i], pgm[i + 1]])
    };
    let (red_only, red_depth, _) = run("d 0", &[], "clear");
    assert_eq!(red_only.get_pixel(centre), rgb(31, 0, 0));
    assert_eq!(at(&half_depth, centre), at(&red_depth, centre));
    assert!(at(&opaque_depth, centre) < at(&half_depth, centre));
    // In bands: the same picture, depths and counts.
    let (banded, banded_depth, banded_stats) = run("d 0.5", &["--band", "7"], "banded");
    assert!(banded.diff(&half).is_none());
    assert_eq!((banded_depth, banded_stats), (half_depth, half_stats));
}
