//! The Cortex-M bench's scene (`bench/mcu`), drawn on the host: its checksum is the one
//! every firmware build must print (`bench/mcu.sh` reads [`BENCH_CHECKSUM`] from here).
//! Code paths that only Arm builds take (and the integer projection of soft-float
//! chips) are thereby held to the host's picture, which the golden image holds.

#[path = "../bench/mcu/src/bunny.rs"]
mod bunny;
#[path = "../bench/mcu/src/scene.rs"]
mod scene;

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use scene::{checksum, H, W};
use zraster::{BandBuffers, CachedVertex, ColorBuffer, Renderer, ZBuffer};

/// FNV-1a over the frame's Rgb565 values, as the firmware computes it.
const BENCH_CHECKSUM: u32 = 0xfb19_6b71;

#[test]
fn the_bench_frame_has_the_bench_checksum() {
    let (mesh, xf, opts) = (scene::mesh(), scene::transform(), scene::options());
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
