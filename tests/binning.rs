//! A banded draw says whether it binned its triangles, and if not, why
//! (`Renderer::binning`): never silently slower.

use embedded_graphics::pixelcolor::{BinaryColor, Gray2, PixelColor, Rgb565, Rgb888};
use zraster::{
    mesh::{Mesh, CUBE},
    shade::{Material, Shading},
    BandBuffers, Bands, Binning, CachedVertex, ColorBuffer, RenderOptions, Renderer, Unbinned,
};
use zraster_bench_scene as scene;

const W: u32 = scene::W;
const H: u32 = scene::H;
const ROWS: u32 = 8;

/// Draw `mesh` in bands of `ROWS` rows into a `C` display, with `bins` bin entries and
/// a cache or not; returns what the renderer says of binning, and the colours.
fn draw<C>(
    mesh: &Mesh<'_, Rgb888>,
    shading: Shading,
    bins: usize,
    cached: bool,
) -> (Binning, Vec<C>)
where
    C: PixelColor + Default,
    Rgb888: Material<C>,
{
    // The bench scene's camera: the bunny fills the middle of a 320×240 screen.
    let xf = scene::transform();
    let opts = RenderOptions {
        shading,
        ..Default::default()
    };
    let mut pixels = vec![C::default(); (W * H) as usize];
    let (mut cb, mut zb) = (
        vec![C::default(); (W * ROWS) as usize],
        vec![0u16; (W * ROWS) as usize],
    );
    let mut bins = vec![0u16; bins];
    let mut cache = vec![CachedVertex::EMPTY; mesh.positions.len()];
    let mut r = if cached {
        Renderer::with_cache(mesh, &xf, opts, &mut cache).unwrap()
    } else {
        Renderer::new(mesh, &xf, opts).unwrap()
    };
    assert_eq!(r.binning(), Binning::NotBanded);
    let mut display = ColorBuffer::new(&mut pixels, W, H).unwrap();
    let mut bands = BandBuffers::new(&mut cb, &mut zb, W, ROWS, H, &mut bins).unwrap();
    r.draw(&mut Bands::new(&mut display, &mut bands, C::default()))
        .unwrap();
    (r.binning(), pixels)
}

fn needed(mesh: &Mesh<'_, Rgb888>) -> usize {
    BandBuffers::<Rgb565>::bins_needed(mesh.face_count(), H, ROWS)
}

#[test]
fn each_reason_for_drawing_without_bins_is_reported() {
    let bunny = scene::mesh();
    let n = needed(&bunny);
    let (b, binned) = draw::<Rgb565>(&bunny, Shading::Lambert, n, true);
    assert_eq!(b, Binning::Binned);
    // One entry short: reported, and the same picture.
    let (b, unbinned) = draw::<Rgb565>(&bunny, Shading::Lambert, n - 1, true);
    assert_eq!(b, Binning::Off(Unbinned::BinsTooShort));
    // No bins at all: the same.
    let (b, _) = draw::<Rgb565>(&bunny, Shading::Lambert, 0, true);
    assert_eq!(b, Binning::Off(Unbinned::BinsTooShort));
    assert_eq!(binned, unbinned);
    assert!(
        binned.iter().any(|&c| c != Rgb565::default()),
        "the bunny is in view"
    );
    let (b, _) = draw::<Rgb565>(&bunny, Shading::Lambert, n, false);
    assert_eq!(b, Binning::Off(Unbinned::NoCache));
    let (b, _) = draw::<Rgb565>(&bunny, Shading::Gouraud, n, true);
    assert_eq!(b, Binning::Off(Unbinned::Gouraud));
    let (b, _) = draw::<Gray2>(&bunny, Shading::Lambert, n, true);
    assert_eq!(b, Binning::Off(Unbinned::Dithered));
    let (b, _) = draw::<BinaryColor>(&bunny, Shading::Flat, n, true);
    assert_eq!(b, Binning::Off(Unbinned::Dithered));
    let (b, _) = draw::<Rgb565>(&CUBE, Shading::Lambert, 1000, true);
    assert_eq!(b, Binning::Off(Unbinned::Polygons));
}

#[test]
fn reasons_read_as_warnings() {
    let s = Unbinned::BinsTooShort.to_string();
    assert_eq!(s, "the bin slice is shorter than bins_needed");
    assert_eq!(Unbinned::NoCache.to_string(), "no vertex cache");
}
