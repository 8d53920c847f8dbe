//! The bunny-320 bench scene, shared by the Cortex-M bench (`bench/mcu`), the criterion
//! benchmarks (`benches/frame.rs`) and the test that pins its checksum
//! (`tests/bench_scene.rs`), so that all three draw the same frame. Each includes this
//! file next to `bunny.rs` (as `crate::bunny`).

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::IntoStorage;
use zraster::{
    camera::{Transform, Viewport},
    math::{radians, Mat4, Vec3},
    mesh::{Faces, Materials, Mesh},
    shade::Shading,
    RenderOptions,
};

/// The screen: 320×240.
pub const W: u32 = 320;
/// The screen: 320×240.
pub const H: u32 = 240;

/// The bunny in one colour (`render --color 1,0.8,0.6`).
pub fn mesh() -> Mesh<'static, Rgb888> {
    let mut mesh = crate::bunny::BUNNY_MESH;
    mesh.faces = Faces::Triangles {
        indices: &crate::bunny::BUNNY_INDICES,
        materials: Materials::Uniform(Rgb888::new(255, 204, 153)),
    };
    mesh
}

/// Fit to the unit cube, turned 30°, seen from z = 1.6 with a 60° field of view.
pub fn transform() -> Transform {
    let vp = Viewport::new(W, H).unwrap();
    let cam = Transform::perspective(
        Vec3::new(0.0, 0.0, 1.6),
        Vec3::new(0.0, 0.0, 0.6),
        60.0,
        0.1,
        10.0,
        vp,
    )
    .unwrap();
    let fit = crate::bunny::BUNNY_FIT;
    cam.with_model(Mat4::rotation_y(radians(30.0)) * Mat4::scaling(Vec3::new(fit, fit, fit)))
}

/// Flat Lambert shading, back faces culled.
pub fn options() -> RenderOptions {
    RenderOptions {
        shading: Shading::Lambert,
        ..Default::default()
    }
}

/// FNV-1a over the frame's Rgb565 values: the checksum every build must print.
pub fn checksum(pixels: &[Rgb565]) -> u32 {
    pixels.iter().fold(0x811c_9dc5u32, |h, p| {
        (h ^ u32::from(p.into_storage())).wrapping_mul(0x0100_0193)
    })
}
