//! Tests of the vertex and face tables, the cube, normals and quantising.

use super::quantize::round_half_away;
use super::*;
use crate::math::Mat4;

#[test]
fn the_reference_cube_is_valid_and_closed() {
    assert_eq!(CUBE.validate(), Ok(()));
    assert_eq!(CUBE.face_count(), 6);
    // Closed: each directed edge appears once, and its reverse once.
    let mut edges = std::vec::Vec::new();
    for f in 0..6 {
        let (vs, _) = CUBE.face(f).unwrap();
        for k in 0..vs.len() {
            edges.push((vs[k], vs[(k + 1) % vs.len()]));
        }
    }
    for &(a, b) in &edges {
        assert_eq!(edges.iter().filter(|&&e| e == (a, b)).count(), 1);
        assert_eq!(edges.iter().filter(|&&e| e == (b, a)).count(), 1);
    }
    // Outward normals, counter-clockwise from outside: bottom −Y, right +X, front +Z,
    // left −X, back −Z, top +Y.
    let want = [
        (0, -1, 0),
        (1, 0, 0),
        (0, 0, 1),
        (-1, 0, 0),
        (0, 0, -1),
        (0, 1, 0),
    ];
    for (f, w) in want.iter().enumerate() {
        let n = face_normal(&CUBE, f).unwrap();
        assert_eq!((n.x as i32, n.y as i32, n.z as i32), *w, "face {f}");
    }
}

#[test]
fn bad_tables_are_errors() {
    let pos = [[0i16; 3]; 3];
    let tris = [[0u16, 1, 3]];
    let m = Mesh::triangles(&pos, 1.0, &tris, Rgb888::new(1, 2, 3));
    assert_eq!(
        m.validate(),
        Err(Error::IndexOutOfRange { face: 0, index: 3 })
    );
    let faces = [Face {
        vertices: &[0u16, 1][..],
        material: Rgb888::new(0, 0, 0),
    }];
    assert_eq!(
        Mesh::new(&pos, 1.0, &faces).validate(),
        Err(Error::DegenerateFace { face: 0 })
    );
    let ok = [[0u16, 1, 2]];
    let m = Mesh::triangles(&pos, f32::NAN, &ok, Rgb888::new(0, 0, 0));
    assert_eq!(m.validate(), Err(Error::NotFinite));
    let mats: [Rgb888; 0] = [];
    let m = Mesh {
        faces: Faces::Triangles {
            indices: &ok,
            materials: Materials::PerFace(&mats),
        },
        ..Mesh::triangles(&pos, 1.0, &ok, Rgb888::new(0, 0, 0))
    };
    assert_eq!(m.validate(), Err(Error::CapacityExceeded { capacity: 0 }));
}

#[test]
fn vertex_normals_of_the_cube_point_out_of_the_corners() {
    let mut scratch = [Vec3::default(); 8];
    let mut out = [[0i16; 3]; 8];
    compute_vertex_normals(&CUBE, &mut scratch, &mut out).unwrap();
    // Corner a (0,0,0): (−1,−1,−1)/√3 → −9459 in Q14.
    assert_eq!(out[0], [-9459, -9459, -9459]);
    assert_eq!(out[6], [9459, 9459, 9459]);
    let mut fnorm = [[0i16; 3]; 6];
    compute_face_normals(&CUBE, &mut fnorm).unwrap();
    assert_eq!(fnorm[2], [0, 0, 16384]);
    assert_eq!(
        compute_face_normals(&CUBE, &mut fnorm[..5]),
        Err(Error::BufferTooSmall { needed: 6, got: 5 })
    );
}

#[test]
fn one_scale_rule() {
    let not_positive = Err(Error::InvalidParameter(SCALE_RULE));
    for (bad, want) in [
        (0.0, not_positive),
        (-0.0, not_positive),
        (-1.0, not_positive),
        (f32::NAN, Err(Error::NotFinite)),
        (f32::INFINITY, Err(Error::NotFinite)),
        (f32::NEG_INFINITY, Err(Error::NotFinite)),
    ] {
        assert_eq!(check_scale(bad), want);
        let m = Mesh { scale: bad, ..CUBE };
        assert_eq!(m.validate(), want, "{bad}");
        assert_eq!(m.check_for(Shading::Flat), want, "{bad}");
    }
    assert_eq!(check_scale(f32::MIN_POSITIVE / 4.0), Ok(())); // subnormal: tiny, not wrong
    assert_eq!(check_scale(1e30), Ok(()));
}

#[test]
fn gouraud_needs_vertex_normals() {
    assert_eq!(CUBE.check_for(Shading::Flat), Ok(()));
    assert_eq!(CUBE.check_for(Shading::Lambert), Ok(()));
    assert_eq!(CUBE.check_for(Shading::Gouraud), Err(Error::MissingNormals));
    let short = [[0i16; 3]; 7];
    let m = CUBE.with_normals(None, Some(&short));
    let few = Err(Error::InvalidParameter(
        "fewer vertex normals than vertices",
    ));
    assert_eq!(m.check_for(Shading::Gouraud), few);
    assert_eq!(m.check_for(Shading::Flat), few);
    let faces = [[0i16; 3]; 5];
    let m = CUBE.with_normals(Some(&faces), None);
    let few = Err(Error::InvalidParameter("fewer face normals than faces"));
    assert_eq!(m.check_for(Shading::Lambert), few);
    assert_eq!(m.validate(), few);
    let mut scratch = [Vec3::default(); 8];
    let mut normals = [[0i16; 3]; 8];
    compute_vertex_normals(&CUBE, &mut scratch, &mut normals).unwrap();
    let m = CUBE.with_normals(None, Some(&normals));
    assert_eq!(m.check_for(Shading::Gouraud), Ok(()));
}

#[test]
fn quantize_fills_the_table() {
    // Centred: the box 1..5 × −2..2 × 0..1 has centre (3, 0, 0.5) and reach 2.
    let pts = [
        [1.0, -2.0, 0.0],
        [5.0, 2.0, 1.0],
        [3.0, 1.2, 0.5],
        [2.5, 0.0, 0.75],
    ];
    let mut out = [[7i16; 3]; 5];
    let q = quantize(&pts, true, &mut out).unwrap();
    assert_eq!(q.offset, Vec3::new(3.0, 0.0, 0.5));
    assert_eq!(q.scale, 2.0 / 32767.0);
    // 1 unit is 16383.5 steps: 1.2 is 19660.2, 0.5 is 8191.75, 0.25 is 4095.875.
    assert_eq!(
        out,
        [
            [-32767, -32767, -8192],
            [32767, 32767, 8192],
            [0, 19660, 0],
            [-8192, 0, 4096],
            [7, 7, 7], // beyond the points: untouched
        ]
    );
    // Back to model space within half a step.
    let off = [q.offset.x, q.offset.y, q.offset.z];
    for (p, o) in pts.iter().zip(&out) {
        for k in 0..3 {
            let back = f32::from(o[k]) * q.scale + off[k];
            assert!((back - p[k]).abs() <= q.scale * 0.5 + 1e-6, "{p:?}");
        }
    }
    // Errors: a short table (nothing written), NaN or infinity.
    let mut short = [[9i16; 3]; 3];
    assert_eq!(
        quantize(&pts, true, &mut short),
        Err(Error::BufferTooSmall { needed: 4, got: 3 })
    );
    assert_eq!(short, [[9; 3]; 3]);
    for bad in [f32::NAN, f32::INFINITY] {
        let pts = [[0.0, bad, 0.0]];
        assert_eq!(quantize(&pts, false, &mut out), Err(Error::NotFinite));
    }
    // No points, one point, points far below f32's normal range.
    assert_eq!(quantize(&[], true, &mut []).map(|q| q.scale), Ok(1.0));
    let one = [[4.0, 5.0, 6.0]];
    let q = quantize(&one, true, &mut out).unwrap();
    assert_eq!((q.scale, out[0]), (1.0, [0, 0, 0]));
    assert_eq!(q.model(), Mat4::translation(Vec3::new(4.0, 5.0, 6.0)));
    let tiny = [[0.0, 0.0, 0.0], [1e-44, 0.0, 0.0]];
    assert_eq!(
        quantize(&tiny, false, &mut out),
        Err(Error::InvalidParameter(SCALE_RULE))
    );
    // Near f32::MAX the centre and reach stay finite.
    let huge = [[f32::MAX, -f32::MAX, 0.0], [-f32::MAX, f32::MAX, 1.0]];
    let q = quantize(&huge, true, &mut out).unwrap();
    assert!(q.scale.is_finite() && q.offset == Vec3::new(0.0, 0.0, 0.5));
    assert_eq!(out[0], [32767, -32767, 0]);
}

#[test]
fn rounding_is_half_away_from_zero() {
    for v in [
        0.0f32,
        0.49999997,
        0.5,
        1.5,
        2.5,
        -0.5,
        -1.5,
        -2.4999998,
        1e7 + 0.5,
        3e9,
    ] {
        let want = v.clamp(-16_777_216.0, 16_777_216.0).round() as i32;
        assert_eq!(round_half_away(v), want, "{v}");
    }
}
