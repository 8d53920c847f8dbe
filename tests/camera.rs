//! The camera: look-at with an up vector and its errors, perspective and orthographic
//! lenses, radians, and the old `Transform::perspective` form still giving the same
//! matrices.

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use zraster::camera::{LookAt, Transform};
use zraster::math::{radians, Mat4, Vec3};
use zraster::mesh::{Face, Mesh};
use zraster::{Camera, Cull, Error, Frame, RenderOptions, Renderer, Viewport};

const W: u32 = 32;
const H: u32 = 16;

fn eye(e: Vec3, target: Vec3, up: Vec3) -> Result<LookAt, Error> {
    Camera::look_at(e, target, up)
}

#[test]
fn degenerate_views_are_errors() {
    let o = Vec3::default();
    let above = Vec3::new(0.0, 5.0, 0.0);
    // The eye at the target: no line of sight.
    assert_eq!(eye(o, o, Vec3::Y).err(), Some(Error::DegenerateView));
    let p = Vec3::new(1.0, 2.0, 3.0);
    assert_eq!(eye(p, p, Vec3::Y).err(), Some(Error::DegenerateView));
    // Up along the line of sight, either way, or a little off it (0.01°).
    assert_eq!(eye(above, o, Vec3::Y).err(), Some(Error::DegenerateView));
    assert_eq!(eye(above, o, -Vec3::Y).err(), Some(Error::DegenerateView));
    assert_eq!(
        eye(o, above, Vec3::Y * 7.0).err(),
        Some(Error::DegenerateView)
    );
    let nearly = Vec3::new(radians(0.01), 1.0, 0.0);
    assert_eq!(eye(above, o, nearly).err(), Some(Error::DegenerateView));
    // No up at all.
    assert_eq!(
        eye(p, o, Vec3::default()).err(),
        Some(Error::DegenerateView)
    );
    // NaN or infinity anywhere.
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let v = Vec3::new(0.0, bad, 1.0);
        assert_eq!(eye(v, o, Vec3::Y).err(), Some(Error::NotFinite));
        assert_eq!(eye(p, v, Vec3::Y).err(), Some(Error::NotFinite));
        assert_eq!(eye(p, o, v).err(), Some(Error::NotFinite));
    }
    // Half a degree off the vertical is a view (and up need not be a unit vector, nor
    // at right angles to the line of sight).
    let tilted = Vec3::new(radians(0.5), 1.0, 0.0) * 3.0;
    assert!(eye(above, o, tilted).is_ok());
    assert!(eye(p, o, Vec3::new(0.0, 2.0, 1.0)).is_ok());
    // The old form takes +Y as up, so it refuses a top-down view too.
    let vp = Viewport::new(W, H).unwrap();
    assert_eq!(
        Transform::perspective(above, o, 45.0, 0.1, 10.0, vp).err(),
        Some(Error::DegenerateView)
    );
}

#[test]
fn lens_parameters_out_of_range_are_errors() {
    let vp = Viewport::new(W, H).unwrap();
    let view = eye(Vec3::new(0.0, 0.0, 5.0), Vec3::default(), Vec3::Y).unwrap();
    let pi = core::f32::consts::PI;
    let invalid = |r: Result<Camera, Error>| matches!(r, Err(Error::InvalidParameter(_)));
    // Perspective: 0 < fov < π radians, 0 < near < far.
    for (fov, near, far) in [
        (0.0, 0.1, 10.0),
        (-1.0, 0.1, 10.0),
        (pi, 0.1, 10.0),
        (4.0, 0.1, 10.0),
        (1.0, 0.0, 10.0),
        (1.0, -0.1, 10.0),
        (1.0, 2.0, 2.0),
        (1.0, 3.0, 2.0),
    ] {
        assert!(
            invalid(view.perspective(fov, near, far, vp)),
            "{fov} {near} {far}"
        );
    }
    // 45 given as if it were degrees is 45 radians: refused, not a strange picture.
    assert!(invalid(view.perspective(45.0, 0.1, 10.0, vp)));
    assert!(view.perspective(radians(179.0), 0.1, 10.0, vp).is_ok());
    // Orthographic: height > 0, near < far (near may be behind the eye).
    for (height, near, far) in [
        (0.0, 1.0, 10.0),
        (-2.0, 1.0, 10.0),
        (2.0, 5.0, 5.0),
        (2.0, 6.0, 5.0),
    ] {
        assert!(
            invalid(view.orthographic(height, near, far, vp)),
            "{height} {near} {far}"
        );
    }
    assert!(view.orthographic(2.0, -5.0, 5.0, vp).is_ok());
    // A box too thin for f32 (2 / (far − near) overflows).
    assert!(invalid(view.orthographic(2.0, 1.0, 1.0 + 1e-38, vp)));
    for bad in [f32::NAN, f32::INFINITY] {
        assert_eq!(
            view.perspective(bad, 0.1, 10.0, vp).err(),
            Some(Error::NotFinite)
        );
        assert_eq!(
            view.perspective(1.0, bad, 10.0, vp).err(),
            Some(Error::NotFinite)
        );
        assert_eq!(
            view.perspective(1.0, 0.1, bad, vp).err(),
            Some(Error::NotFinite)
        );
        assert_eq!(
            view.orthographic(bad, 0.1, 10.0, vp).err(),
            Some(Error::NotFinite)
        );
        assert_eq!(
            view.orthographic(1.0, 0.1, bad, vp).err(),
            Some(Error::NotFinite)
        );
    }
}

/// The old `Transform::perspective(eye, target, degrees, …)` builds exactly the
/// matrices it always did (gluLookAt with +Y up, gluPerspective), so pictures drawn
/// through it do not move; and it is the new form with the angle in radians.
#[test]
fn the_old_form_builds_the_same_matrices() {
    let vp = Viewport::new(W, H).unwrap();
    let (e, t) = (Vec3::new(2.2, 1.8, 2.8), Vec3::new(0.5, 0.5, 0.5));
    let old = Transform::perspective(e, t, 45.0, 0.1, 10.0, vp).unwrap();
    assert_eq!(old.view, Mat4::look_at(e, t, Vec3::new(0.0, 1.0, 0.0)));
    assert_eq!(
        old.projection,
        Mat4::perspective(radians(45.0), W as f32 / H as f32, 0.1, 10.0)
    );
    assert_eq!(old.model, Mat4::IDENTITY);
    let new = Camera::look_at(e, t, Vec3::Y)
        .unwrap()
        .perspective(radians(45.0), 0.1, 10.0, vp)
        .unwrap();
    assert_eq!(old, new);
}

/// A square of side `2·half` around `centre`, facing `normal` (one of ±X, ±Y, ±Z), in
/// steps of 1/16384.
fn square(centre: [f32; 3], half: f32, normal: usize) -> [[i16; 3]; 4] {
    let (a, b) = match normal {
        0 => (1, 2),
        1 => (2, 0),
        _ => (0, 1),
    };
    let q = |v: f32| (v * 16384.0).round() as i16;
    let corner = |da: f32, db: f32| {
        let mut p = centre;
        p[a] += da * half;
        p[b] += db * half;
        [q(p[0]), q(p[1]), q(p[2])]
    };
    [
        corner(-1.0, -1.0),
        corner(1.0, -1.0),
        corner(1.0, 1.0),
        corner(-1.0, 1.0),
    ]
}

/// The pixels a square covers, as (x range, y range), drawn flat white with no culling.
fn covered(positions: &[[i16; 3]; 4], camera: &Camera) -> (Vec<i32>, Vec<i32>) {
    let faces = [Face {
        vertices: &[0u16, 1, 2, 3][..],
        material: Rgb888::WHITE,
    }];
    let mesh = Mesh::new(positions, 1.0 / 16384.0, &faces);
    let mut pixels = [Rgb565::BLACK; (W * H) as usize];
    let mut depth = [0u16; (W * H) as usize];
    let mut frame = Frame::new(&mut pixels, &mut depth, W, H).unwrap();
    frame.clear(Rgb565::BLACK);
    let options = RenderOptions {
        cull: Cull::None,
        ..Default::default()
    };
    Renderer::new(&mesh, camera, options)
        .unwrap()
        .draw(&mut frame)
        .unwrap();
    let lit = |x: i32, y: i32| frame.color().pixel(x, y) == Some(Rgb565::WHITE);
    let xs: Vec<i32> = (0..W as i32)
        .filter(|&x| (0..H as i32).any(|y| lit(x, y)))
        .collect();
    let ys: Vec<i32> = (0..H as i32)
        .filter(|&y| (0..W as i32).any(|x| lit(x, y)))
        .collect();
    // A solid rectangle: every pixel in the ranges lit.
    for &y in &ys {
        for &x in &xs {
            assert!(lit(x, y), "hole at ({x}, {y})");
        }
    }
    (xs, ys)
}

fn range(a: i32, b: i32) -> Vec<i32> {
    (a..=b).collect()
}

/// Orthographic, 4 units tall on a 32×16 viewport: 8 units wide, 4 pixels a unit.
/// A world point (x, y) seen down −Z lands at pixel ((x / 4 + 1) · 16, (1 − y / 2) · 8).
#[test]
fn orthographic_pixels_by_hand() {
    let vp = Viewport::new(W, H).unwrap();
    let front = eye(Vec3::new(0.0, 0.0, 5.0), Vec3::default(), Vec3::Y)
        .unwrap()
        .orthographic(4.0, 1.0, 10.0, vp)
        .unwrap();
    // x in −1..1 → pixels 12..20; y in −1..1 → rows 4..12 (y up, rows down).
    let sq = square([0.0, 0.0, 0.0], 1.0, 2);
    assert_eq!(covered(&sq, &front), (range(12, 19), range(4, 11)));
    // Off centre: x in 0.5..1.5 → 18..22, y in 0.5..1.5 → rows 2..6.
    let sq = square([1.0, 1.0, 0.0], 0.5, 2);
    assert_eq!(covered(&sq, &front), (range(18, 21), range(2, 5)));
    // Parallel projection: farther away (z = −3, still inside near..far) is no smaller.
    let far = square([1.0, 1.0, -3.0], 0.5, 2);
    assert_eq!(covered(&far, &front), (range(18, 21), range(2, 5)));
    // A perspective camera shrinks it.
    let persp = eye(Vec3::new(0.0, 0.0, 5.0), Vec3::default(), Vec3::Y)
        .unwrap()
        .perspective(radians(45.0), 1.0, 10.0, vp)
        .unwrap();
    let (near_x, _) = covered(&sq, &persp);
    let (far_x, _) = covered(&far, &persp);
    assert!(far_x.len() < near_x.len());

    // From +X looking back at the origin, +Y up: screen right is world −Z.
    // z in 0.5..1.5 → x_ndc −z/4 → pixels 10..14; y in −0.5..0.5 → rows 6..10.
    let side = eye(Vec3::new(5.0, 0.0, 0.0), Vec3::default(), Vec3::Y)
        .unwrap()
        .orthographic(4.0, 1.0, 10.0, vp)
        .unwrap();
    let sq = square([0.0, 0.0, 1.0], 0.5, 0);
    assert_eq!(covered(&sq, &side), (range(10, 13), range(6, 9)));

    // Top-down with −Z as up (north up on a map): screen right is +X, up is −Z.
    // x in 0.5..1.5 → pixels 18..22; z in −1.25..−0.25 → y_ndc = −z / 2 in
    // 0.125..0.625 → rows 3..7.
    let plan = eye(Vec3::new(0.0, 5.0, 0.0), Vec3::default(), -Vec3::Z)
        .unwrap()
        .orthographic(4.0, 1.0, 10.0, vp)
        .unwrap();
    let sq = square([1.0, 0.0, -0.75], 0.5, 1);
    assert_eq!(covered(&sq, &plan), (range(18, 21), range(3, 6)));
    // Up turned the other way (+Z) turns the picture half round: x 10..14, rows 9..13.
    let south_up = eye(Vec3::new(0.0, 5.0, 0.0), Vec3::default(), Vec3::Z)
        .unwrap()
        .orthographic(4.0, 1.0, 10.0, vp)
        .unwrap();
    assert_eq!(covered(&sq, &south_up), (range(10, 13), range(9, 12)));
}

/// `fit_depth` keeps working on orthographic cameras made by the new constructor.
#[test]
fn orthographic_depth_fits() {
    let vp = Viewport::new(W, H).unwrap();
    let cam = eye(Vec3::new(0.0, 0.0, 5.0), Vec3::default(), Vec3::Y)
        .unwrap()
        .orthographic(4.0, 0.5, 100.0, vp)
        .unwrap();
    let fitted = cam
        .fit_depth(Vec3::new(-1.0, -1.0, -1.0), Vec3::new(1.0, 1.0, 1.0), 0.1)
        .unwrap();
    let depth = |z: f32| {
        let c = fitted
            .model_view_projection()
            .transform_point(Vec3::new(0.0, 0.0, z));
        (c[2] / c[3] + 1.0) / 2.0
    };
    assert!(depth(1.0).abs() < 1e-3 && (depth(-1.0) - 1.0).abs() < 1e-3);
    // Screen x and y untouched.
    assert_eq!(fitted.projection.m[0], cam.projection.m[0]);
    assert_eq!(fitted.projection.m[1], cam.projection.m[1]);
}
