//! The Cortex-M bench's scene (`bench/mcu`), drawn on the host: its checksum is the one
//! every firmware build must print (`bench/mcu.sh` reads [`BENCH_CHECKSUM`] from here).
//! Code paths that only Arm builds take (and the integer projection of soft-float
//! chips) are thereby held to the host's picture, which the golden image holds.

#[path = "../bench/mcu/src/bunny.rs"]
mod bunny;

use embedded_graphics::pixelcolor::{raw::RawU16, Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use zraster::{
    camera::{Transform, Viewport},
    math::{radians, Mat4, Vec3},
    mesh::{Faces, Materials, Mesh},
    shade::Shading,
    BandBuffers, CachedVertex, ColorBuffer, RenderOptions, Renderer, ZBuffer,
};

/// FNV-1a over the frame's Rgb565 values, as the firmware computes it.
const BENCH_CHECKSUM: u32 = 0xfb19_6b71;

const W: u32 = 320;
const H: u32 = 240;

fn checksum(pixels: &[Rgb565]) -> u32 {
    pixels.iter().fold(0x811c_9dc5u32, |h, p| {
        (h ^ u32::from(RawU16::from(*p).into_inner())).wrapping_mul(0x0100_0193)
    })
}

fn scene() -> (Mesh<'static, Rgb888>, Transform) {
    let mut mesh = bunny::BUNNY_MESH;
    mesh.faces = Faces::Triangles {
        indices: &bunny::BUNNY_INDICES,
        materials: Materials::Uniform(Rgb888::new(255, 204, 153)),
    };
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
    let fit = bunny::BUNNY_FIT;
    let xf =
        cam.with_model(Mat4::rotation_y(radians(30.0)) * Mat4::scaling(Vec3::new(fit, fit, fit)));
    (mesh, xf)
}

#[test]
fn the_bench_frame_has_the_bench_checksum() {
    let (mesh, xf) = scene();
    let opts = RenderOptions {
        shading: Shading::Lambert,
        ..Default::default()
    };
    let mut cache = vec![CachedVertex::default(); bunny::BUNNY_POSITIONS.len()];
    let mut pixels = vec![Rgb565::BLACK; (W * H) as usize];
    let mut depth = vec![u16::MAX; (W * H) as usize];
    let mut frame = ColorBuffer::new(&mut pixels, W, H).unwrap();
    let mut zbuf = ZBuffer::new(&mut depth, W, H).unwrap();
    let mut r = Renderer::with_cache(&mesh, &xf, opts, &mut cache).unwrap();
    r.draw_buffer(&mut frame, &mut zbuf).unwrap();
    assert_eq!(r.stats().drawn, 1481);
    assert_eq!(r.stats().pixels_written, 11177);
    assert_eq!(checksum(frame.as_slice()), BENCH_CHECKSUM);

    // The 16-row banded draw gives the same frame.
    let mut band_pixels = vec![Rgb565::BLACK; (W * 16) as usize];
    let mut band_depth = vec![0u16; (W * 16) as usize];
    let mut bins = vec![0u16; BandBuffers::<Rgb565>::bins_needed(3674, H, 16)];
    let mut again = vec![Rgb565::WHITE; (W * H) as usize];
    let mut out = ColorBuffer::new(&mut again, W, H).unwrap();
    let mut bands =
        BandBuffers::new(&mut band_pixels, &mut band_depth, W, 16, H, &mut bins).unwrap();
    let mut r = Renderer::with_cache(&mesh, &xf, opts, &mut cache).unwrap();
    r.draw_banded(&mut out, &mut bands, Rgb565::BLACK).unwrap();
    assert_eq!(checksum(out.as_slice()), BENCH_CHECKSUM);
}
