//! Building meshes in the core: quantising `f32` positions into caller tables, the one
//! scale rule, and Gouraud shading's vertex normals.

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use zraster::math::{radians, Vec3};
use zraster::mesh::{check_scale, compute_vertex_normals, quantize, Mesh, CUBE, SCALE_RULE};
use zraster::shade::Shading;
use zraster::{Camera, Error, Frame, RenderOptions, Renderer, Viewport};
use zraster_scenes::BUNNY_OBJ;

/// The core's quantiser writes the tables the host tools' one (zraster-obj) makes, for
/// the bunny: same steps, scale and offset, without a heap.
#[test]
fn the_core_quantiser_agrees_with_the_host_one() {
    let obj = zraster_obj::parse_obj(BUNNY_OBJ, |_| None).unwrap();
    for centre in [true, false] {
        let host = zraster_obj::quantize(&obj.positions, centre);
        let mut table = vec![[0i16; 3]; obj.positions.len()];
        let q = quantize(&obj.positions, centre, &mut table).unwrap();
        assert_eq!(table, host.positions, "centre {centre}");
        assert_eq!(q.scale, host.scale);
        assert_eq!([q.offset.x, q.offset.y, q.offset.z], host.offset);
        assert_eq!(check_scale(q.scale), Ok(()));
    }
}

fn cube_camera() -> Camera {
    Camera::look_at(Vec3::new(2.0, 1.5, 3.0), Vec3::new(0.5, 0.5, 0.5), Vec3::Y)
        .unwrap()
        .perspective(radians(45.0), 0.1, 10.0, Viewport::new(48, 40).unwrap())
        .unwrap()
}

fn draw(mesh: &Mesh<'_, Rgb888>, shading: Shading) -> Vec<Rgb565> {
    let mut pixels = vec![Rgb565::BLACK; 48 * 40];
    let mut depth = vec![0u16; 48 * 40];
    let mut frame = Frame::new(&mut pixels, &mut depth, 48, 40).unwrap();
    frame.clear(Rgb565::BLACK);
    let options = RenderOptions {
        shading,
        ..Default::default()
    };
    Renderer::new(mesh, &cube_camera(), options)
        .unwrap()
        .draw(&mut frame)
        .unwrap();
    frame.color().as_slice().to_vec()
}

/// A mesh without vertex normals is refused for Gouraud shading (it would be drawn at
/// full light, unlit); normals computed into a caller buffer light it.
#[test]
fn gouraud_gets_its_normals_or_an_error() {
    assert_eq!(CUBE.check_for(Shading::Gouraud), Err(Error::MissingNormals));
    let mut scratch = [Vec3::default(); 8];
    let mut normals = [[0i16; 3]; 8];
    compute_vertex_normals(&CUBE, &mut scratch, &mut normals).unwrap();
    let lit = CUBE.with_normals(None, Some(&normals));
    assert_eq!(lit.check_for(Shading::Gouraud), Ok(()));
    let flat = draw(&CUBE, Shading::Flat);
    let gouraud = draw(&lit, Shading::Gouraud);
    // The same pixels covered; shaded ones darker than the flat colours somewhere.
    let covered = |p: &[Rgb565]| p.iter().map(|&c| c != Rgb565::BLACK).collect::<Vec<_>>();
    assert_eq!(covered(&flat), covered(&gouraud));
    let darker = flat
        .iter()
        .zip(&gouraud)
        .filter(|(f, g)| g.r() + g.g() + g.b() < f.r() + f.g() + f.b())
        .count();
    assert!(darker > 100, "{darker} pixels darker");
}

/// The renderer applies the same rules as `check_for` (scale, normals for Gouraud).
/// Needs `mesh.check_for(options.shading)?;` at the top of `Renderer::new`
/// (src/render/mod.rs), which is not this change's file to edit.
#[test]
fn the_renderer_agrees_with_check_for() {
    let xf = cube_camera();
    let gouraud = RenderOptions {
        shading: Shading::Gouraud,
        ..Default::default()
    };
    assert_eq!(
        Renderer::new(&CUBE, &xf, gouraud).err(),
        Some(Error::MissingNormals)
    );
    for scale in [0.0, -1.0 / 16384.0] {
        let m = Mesh { scale, ..CUBE };
        assert_eq!(
            Renderer::new(&m, &xf, RenderOptions::default()).err(),
            Some(Error::InvalidParameter(SCALE_RULE))
        );
        assert_eq!(m.validate(), Err(Error::InvalidParameter(SCALE_RULE)));
    }
}
