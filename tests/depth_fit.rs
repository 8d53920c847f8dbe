//! Automatic depth range: near and far fitted to the mesh's bounding sphere.

use zraster::{
    camera::{Camera, Transform, Viewport},
    math::{radians, Mat4, Vec3},
    mesh::{Mesh, CUBE},
    Error,
};
use zraster_bench_scene as scene;

/// The window depth (0..=65535 inside the view volume) of every vertex of `mesh`
/// under `xf`.
fn depths(mesh: &Mesh<'_, embedded_graphics::pixelcolor::Rgb888>, xf: &Transform) -> Vec<f64> {
    let mvp = xf.model_view_projection();
    (0..mesh.positions.len())
        .map(|i| {
            let c = mvp.transform_point(mesh.position(i).unwrap());
            (f64::from(c[2]) / f64::from(c[3]) + 1.0) * 0.5 * 65535.0
        })
        .collect()
}

fn span(d: &[f64]) -> f64 {
    let lo = d.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = d.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    hi - lo
}

/// On bunny-320 (near 0.1, far 10) the vertices cover a few per cent of the 16-bit
/// depth range; fitted to the bunny's bounds, more than half of it, and none is clipped.
#[test]
fn the_bench_bunny_uses_half_the_depth_range_when_fitted() {
    let mesh = scene::mesh();
    let xf = scene::transform();
    let before = span(&depths(&mesh, &xf));
    let (lo, hi) = mesh.bounds().unwrap();
    let fitted = xf.fit_depth(lo, hi, 0.01).unwrap();
    let d = depths(&mesh, &fitted);
    let after = span(&d);
    assert!(before < 0.05 * 65535.0, "fixed planes: {before}");
    assert!(after > 0.5 * 65535.0, "fitted: {after}");
    println!("bunny-320 vertex depths span {before:.0} of 65535 with near 0.1, far 10; {after:.0} fitted");
    assert!(
        d.iter().all(|&z| z > 0.0 && z < 65535.0),
        "a vertex clipped"
    );
    // x and y do not move: the same projection apart from depth.
    let (a, b) = (xf.model_view_projection(), fitted.model_view_projection());
    for i in [0usize, 100, 1000] {
        let (p, q) = (
            a.transform_point(mesh.position(i).unwrap()),
            b.transform_point(mesh.position(i).unwrap()),
        );
        assert!(
            (p[0] / p[3] - q[0] / q[3]).abs() < 1e-5 && (p[1] / p[3] - q[1] / q[3]).abs() < 1e-5
        );
    }
}

/// Every vertex of a mesh stays inside the fitted planes at any distance and turn, and
/// near never goes below the minimum given.
#[test]
fn fitted_planes_enclose_the_mesh_and_respect_min_near() {
    let vp = Viewport::new(64, 48).unwrap();
    let (lo, hi) = CUBE.bounds().unwrap();
    assert_eq!(
        (lo, hi),
        (Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 1.0))
    );
    for dist in [1.2f32, 2.0, 5.0, 40.0] {
        for turn in 0..8 {
            let xf = Camera::look_at(
                Vec3::new(0.5, 0.5, 0.5 + dist),
                Vec3::new(0.5, 0.5, 0.5),
                Vec3::Y,
            )
            .unwrap()
            .perspective(radians(50.0), 0.1, 1000.0, vp)
            .unwrap()
            .with_model(
                Mat4::translation(Vec3::new(0.5, 0.5, 0.5))
                    * Mat4::rotation_y(turn as f32 * 0.7)
                    * Mat4::scaling(Vec3::new(1.5, 1.5, 1.5))
                    * Mat4::translation(Vec3::new(-0.5, -0.5, -0.5)),
            );
            let fitted = xf.fit_depth(lo, hi, 0.05).unwrap();
            let d = depths(&CUBE, &fitted);
            assert!(
                d.iter().all(|&z| (0.0..=65535.0).contains(&z)),
                "{dist} {turn}: {d:?}"
            );
        }
    }
    // Closer than min_near: the near plane stays at min_near (the cube is clipped).
    let xf = Camera::look_at(Vec3::new(0.5, 0.5, 1.3), Vec3::new(0.5, 0.5, 0.5), Vec3::Y)
        .unwrap()
        .perspective(radians(50.0), 0.1, 1000.0, vp)
        .unwrap();
    let fitted = xf.fit_depth(lo, hi, 0.5).unwrap();
    let p = fitted.projection.m;
    let near = p[2][3] / (p[2][2] - 1.0);
    assert!((near - 0.5).abs() < 1e-4, "near {near}");
}

#[test]
fn bad_fits_are_errors() {
    let vp = Viewport::new(64, 48).unwrap();
    let xf = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::default(), Vec3::Y)
        .unwrap()
        .perspective(radians(50.0), 0.1, 10.0, vp)
        .unwrap();
    let (lo, hi) = (Vec3::new(-1.0, -1.0, -1.0), Vec3::new(1.0, 1.0, 1.0));
    let invalid = |r: Result<Transform, Error>| matches!(r, Err(Error::InvalidParameter(_)));
    assert!(invalid(xf.fit_depth(hi, lo, 0.1)));
    assert!(invalid(xf.fit_depth(lo, hi, -1.0)));
    assert!(invalid(xf.fit_depth(lo, hi, 0.0)));
    let nan = Vec3::new(f32::NAN, 1.0, 1.0);
    assert_eq!(xf.fit_depth(lo, nan, 0.1), Err(Error::NotFinite));
    let mut odd = xf;
    odd.projection = Mat4::rotation_y(0.5);
    assert!(invalid(odd.fit_depth(lo, hi, 0.1)));
    // Orthographic: fitted too, the box from z = 1 (near) to z = −1 (far).
    let mut ortho = xf;
    ortho.projection = Mat4::orthographic(-2.0, 2.0, -1.5, 1.5, 0.1, 100.0);
    let f = ortho.fit_depth(lo, hi, 0.1).unwrap();
    let d = |z: f32| {
        let p = f
            .model_view_projection()
            .transform_point(Vec3::new(0.0, 0.0, z));
        p[2] / p[3]
    };
    assert!(d(1.0) > -1.01 && d(1.0) < -0.99, "{}", d(1.0));
    assert!(d(-1.0) < 1.01 && d(-1.0) > 0.99, "{}", d(-1.0));
}

/// Two squares 1/8192 of a unit apart, seen from 5 units: with near 0.1 and far 100
/// their depths round to the same 16-bit values (z-fighting: the one drawn first keeps
/// the pixel); fitted to the squares, every pixel shows the nearer one.
#[test]
fn fitting_the_depth_range_ends_z_fighting() {
    use embedded_graphics::{
        pixelcolor::{Rgb565, Rgb888},
        prelude::RgbColor,
    };
    use zraster::{mesh::Face, shade::Shading, Cull, Frame, RenderOptions, Renderer};
    // Far square first (blue), then the near one (red), both facing the camera.
    const P: [[i16; 3]; 8] = [
        [-8192, -8192, -2],
        [8192, -8192, -2],
        [8192, 8192, -2],
        [-8192, 8192, -2],
        [-8192, -8192, 0],
        [8192, -8192, 0],
        [8192, 8192, 0],
        [-8192, 8192, 0],
    ];
    const FACES: [Face<'static, Rgb888>; 2] = [
        Face {
            vertices: &[0, 1, 2, 3],
            material: Rgb888::BLUE,
        },
        Face {
            vertices: &[4, 5, 6, 7],
            material: Rgb888::RED,
        },
    ];
    let mesh = Mesh::new(&P, 1.0 / 16384.0, &FACES);
    let (w, h) = (64u32, 48u32);
    let vp = Viewport::new(w, h).unwrap();
    let xf = Camera::look_at(Vec3::new(0.1, 0.2, 5.0), Vec3::default(), Vec3::Y)
        .unwrap()
        .perspective(radians(20.0), 0.1, 100.0, vp)
        .unwrap();
    let (lo, hi) = mesh.bounds().unwrap();
    let opts = RenderOptions {
        shading: Shading::Flat,
        cull: Cull::None,
        ..Default::default()
    };
    let blue_pixels = |xf: &Transform| {
        let mut pixels = vec![Rgb565::BLACK; (w * h) as usize];
        let mut depth = vec![0u16; (w * h) as usize];
        let mut frame = Frame::new(&mut pixels, &mut depth, w, h).unwrap();
        frame.clear(Rgb565::BLACK);
        Renderer::new(&mesh, xf, opts)
            .unwrap()
            .draw(&mut frame)
            .unwrap();
        let red = pixels.iter().filter(|&&c| c == Rgb565::RED).count();
        let blue = pixels.iter().filter(|&&c| c == Rgb565::BLUE).count();
        (blue, red)
    };
    let (fighting, shown) = blue_pixels(&xf);
    let (after, covered) = blue_pixels(&xf.fit_depth(lo, hi, 0.01).unwrap());
    println!(
        "z-fighting pixels: {fighting} of {} with near 0.1, far 100; {after} of {} fitted",
        fighting + shown,
        after + covered
    );
    assert!(fighting > 500, "{fighting}");
    assert_eq!(after, 0);
    assert_eq!(after + covered, fighting + shown);
}
