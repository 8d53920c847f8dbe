//! Render state fixed at compile time draws exactly what the run-time choice draws:
//! colours, depths and stats, into a frame, a display with a Z-buffer and bands; a
//! fixed depth test replaces the Z-buffer's; a state that contradicts the options is
//! an error; a binned-only state draws the binned picture, and fails a banded draw
//! that cannot bin.

use embedded_graphics::{
    pixelcolor::{Rgb565, Rgb888},
    prelude::*,
};
use zraster::{
    math::{radians, Mat4, Vec3},
    mesh::{self, Mesh},
    shade::Shading,
    state::{Binned, Dynamic, FlatLess, GouraudLess, LambertLess, RenderState},
    BandBuffers, Bands, Binning, CachedVertex, Camera, ColorBuffer, DepthTest, DrawError, Error,
    Frame, FrameStats, RenderOptions, Renderer, Unbinned, Viewport, WithDepth, ZBuffer,
};
use zraster_bench_scene::bunny::{BUNNY_FIT, BUNNY_MESH};

const W: u32 = 96;
const H: u32 = 72;

type Picture = (Vec<Rgb565>, Vec<u16>, FrameStats);

fn camera(yaw: f32) -> Camera {
    let fit = BUNNY_FIT;
    Camera::look_at(Vec3::new(0.0, 0.3, 1.8), Vec3::default(), Vec3::Y)
        .unwrap()
        .perspective(radians(45.0), 0.1, 10.0, Viewport::new(W, H).unwrap())
        .unwrap()
        .with_model(Mat4::rotation_y(radians(yaw)) * Mat4::scaling(Vec3::new(fit, fit, fit)))
}

/// The bunny into a frame, a display with a Z-buffer, and bands of 16 rows, with the
/// state `S` and the depth test `test` in the Z-buffers it makes.
fn draw_all<S: RenderState>(
    mesh: &Mesh<'_, Rgb888>,
    cam: &Camera,
    opts: RenderOptions,
    test: DepthTest,
) -> [Picture; 3] {
    let n = (W * H) as usize;
    let mut cache = vec![CachedVertex::EMPTY; mesh.positions.len()];
    // A frame.
    let (mut c, mut z) = (vec![Rgb565::BLACK; n], vec![0u16; n]);
    let stats = {
        let mut frame = Frame::new(&mut c, &mut z, W, H).unwrap();
        frame.clear(Rgb565::BLACK);
        frame.depth_mut().set_test(test);
        let mut r = make::<S>(mesh, cam, opts, &mut cache);
        r.draw(&mut frame).unwrap();
        r.stats()
    };
    let framed = (c, z, stats);
    // A display with a Z-buffer.
    let (mut c, mut z) = (vec![Rgb565::BLACK; n], vec![u16::MAX; n]);
    let stats = {
        let mut display = ColorBuffer::new(&mut c, W, H).unwrap();
        let mut zbuf = ZBuffer::new(&mut z, W, H).unwrap();
        zbuf.set_test(test);
        let mut r = make::<S>(mesh, cam, opts, &mut cache);
        r.draw(&mut WithDepth::new(&mut display, &mut zbuf))
            .unwrap();
        r.stats()
    };
    let runs = (c, z, stats);
    // Bands (their Z-buffers test `Less`).
    let mut c = vec![Rgb565::BLACK; n];
    let (mut cb, mut zb) = (
        vec![Rgb565::BLACK; (W * 16) as usize],
        vec![0u16; (W * 16) as usize],
    );
    let mut bins = vec![0u16; BandBuffers::<Rgb565>::bins_needed(mesh.face_count(), H, 16)];
    let stats = {
        let mut display = ColorBuffer::new(&mut c, W, H).unwrap();
        let mut bands = BandBuffers::new(&mut cb, &mut zb, W, 16, H, &mut bins).unwrap();
        let mut r = make::<S>(mesh, cam, opts, &mut cache);
        r.draw(&mut Bands::new(&mut display, &mut bands, Rgb565::BLACK))
            .unwrap();
        r.stats()
    };
    [framed, runs, (c, Vec::new(), stats)]
}

fn make<'m, 'c, S: RenderState>(
    mesh: &Mesh<'m, Rgb888>,
    cam: &Camera,
    opts: RenderOptions,
    cache: &'c mut [CachedVertex],
) -> Renderer<'m, 'c, Rgb888, S> {
    Renderer::with_cache(mesh, cam, opts, cache)
        .unwrap()
        .with_state::<S>()
        .unwrap()
}

fn options(shading: Shading) -> RenderOptions {
    RenderOptions {
        shading,
        ..RenderOptions::default()
    }
}

#[test]
fn fixed_states_draw_what_the_run_time_choice_draws() {
    let mesh = BUNNY_MESH;
    let normals_needed = mesh.vertex_normals.is_some();
    for yaw in [0.0, 75.0, 200.0] {
        let cam = camera(yaw);
        let flat = draw_all::<FlatLess>(&mesh, &cam, options(Shading::Flat), DepthTest::Less);
        let want = draw_all::<Dynamic>(&mesh, &cam, options(Shading::Flat), DepthTest::Less);
        assert_eq!(flat, want, "flat, yaw {yaw}");
        assert!(want[0].2.pixels_written > 500, "the bunny is on screen");
        let lit = draw_all::<LambertLess>(&mesh, &cam, options(Shading::Lambert), DepthTest::Less);
        let want = draw_all::<Dynamic>(&mesh, &cam, options(Shading::Lambert), DepthTest::Less);
        assert_eq!(lit, want, "Lambert, yaw {yaw}");
        if normals_needed {
            let g =
                draw_all::<GouraudLess>(&mesh, &cam, options(Shading::Gouraud), DepthTest::Less);
            let want = draw_all::<Dynamic>(&mesh, &cam, options(Shading::Gouraud), DepthTest::Less);
            assert_eq!(g, want, "Gouraud, yaw {yaw}");
        }
    }
}

#[test]
fn a_fixed_depth_test_replaces_the_z_buffers() {
    // The Z-buffers test `Greater` (nothing passes against a cleared buffer but the
    // far plane), yet the state fixes `Less`: the picture is the `Less` one.
    let cam = camera(30.0);
    let mesh = BUNNY_MESH;
    let fixed = draw_all::<LambertLess>(&mesh, &cam, options(Shading::Lambert), DepthTest::Greater);
    let want = draw_all::<Dynamic>(&mesh, &cam, options(Shading::Lambert), DepthTest::Less);
    assert_eq!(fixed, want);
    let greater = draw_all::<Dynamic>(&mesh, &cam, options(Shading::Lambert), DepthTest::Greater);
    assert_ne!(greater[0], want[0], "the run-time test does differ");
}

#[test]
fn a_state_that_contradicts_the_options_is_an_error() {
    let cam = camera(0.0);
    let r = Renderer::new(&mesh::CUBE, &cam, options(Shading::Flat)).unwrap();
    assert!(matches!(
        r.with_state::<LambertLess>(),
        Err(Error::InvalidParameter(_))
    ));
    let r = Renderer::new(&mesh::CUBE, &cam, options(Shading::Lambert)).unwrap();
    assert!(r.with_state::<FlatLess>().is_err());
    // A state that fixes only the depth test takes any shading.
    struct OnlyLessEqual;
    impl RenderState for OnlyLessEqual {
        const DEPTH_TEST: Option<DepthTest> = Some(DepthTest::LessEqual);
    }
    for s in [Shading::Flat, Shading::Lambert] {
        let r = Renderer::new(&mesh::CUBE, &cam, options(s)).unwrap();
        assert!(r.with_state::<OnlyLessEqual>().is_ok());
    }
}

/// The bunny in bands of 16 rows with `bins` bin entries and a vertex cache or not,
/// under state `S`: the draw's result, what the renderer says of binning, the colours.
fn draw_banded<S: RenderState>(
    mesh: &Mesh<'_, Rgb888>,
    shading: Shading,
    bins: usize,
    cached: bool,
) -> (
    Result<(), DrawError<core::convert::Infallible>>,
    Binning,
    Vec<Rgb565>,
) {
    let cam = camera(40.0);
    let mut c = vec![Rgb565::BLACK; (W * H) as usize];
    let (mut cb, mut zb) = (
        vec![Rgb565::BLACK; (W * 16) as usize],
        vec![0u16; (W * 16) as usize],
    );
    let mut bins = vec![0u16; bins];
    let mut cache = vec![CachedVertex::EMPTY; mesh.positions.len()];
    let mut display = ColorBuffer::new(&mut c, W, H).unwrap();
    let mut bands = BandBuffers::new(&mut cb, &mut zb, W, 16, H, &mut bins).unwrap();
    let r = if cached {
        Renderer::with_cache(mesh, &cam, options(shading), &mut cache)
    } else {
        Renderer::new(mesh, &cam, options(shading))
    };
    let mut r = r.unwrap().with_state::<S>().unwrap();
    let result = r.draw(&mut Bands::new(&mut display, &mut bands, Rgb565::BLACK));
    let binning = r.binning();
    (result, binning, c)
}

#[test]
fn a_binned_only_state_draws_the_binned_picture() {
    let mesh = BUNNY_MESH;
    let n = BandBuffers::<Rgb565>::bins_needed(mesh.face_count(), H, 16);
    let (result, binning, picture) =
        draw_banded::<Binned<LambertLess>>(&mesh, Shading::Lambert, n, true);
    assert_eq!((result, binning), (Ok(()), Binning::Binned));
    let (_, _, want) = draw_banded::<LambertLess>(&mesh, Shading::Lambert, n, true);
    assert_eq!(picture, want);
    assert!(
        picture.iter().any(|&p| p != Rgb565::BLACK),
        "the bunny is in view"
    );
    // Flat colours too, and over the run-time state.
    let (result, _, picture) = draw_banded::<Binned<Dynamic>>(&mesh, Shading::Flat, n, true);
    let (_, _, want) = draw_banded::<Dynamic>(&mesh, Shading::Flat, n, true);
    assert_eq!((result, picture), (Ok(()), want));
}

#[test]
fn a_binned_only_state_fails_a_banded_draw_that_cannot_bin() {
    let mesh = BUNNY_MESH;
    let n = BandBuffers::<Rgb565>::bins_needed(mesh.face_count(), H, 16);
    let cases = [
        (mesh, Shading::Lambert, n, false, Unbinned::NoCache),
        (mesh, Shading::Lambert, n - 1, true, Unbinned::BinsTooShort),
        (mesh, Shading::Lambert, 0, true, Unbinned::BinsTooShort),
        (mesh::CUBE, Shading::Lambert, 1000, true, Unbinned::Polygons),
        (mesh, Shading::Gouraud, n, true, Unbinned::Gouraud),
    ];
    for (m, shading, bins, cached, why) in cases {
        if shading == Shading::Gouraud && m.vertex_normals.is_none() {
            continue;
        }
        let (result, binning, picture) = draw_banded::<Binned<Dynamic>>(&m, shading, bins, cached);
        assert_eq!(result, Err(DrawError::Input(why.error())), "{why:?}");
        assert_eq!(binning, Binning::Off(why));
        assert!(
            picture.iter().all(|&p| p == Rgb565::BLACK),
            "{why:?}: nothing drawn"
        );
        // The run-time state draws the same picture unbinned instead.
        let (result, binning, _) = draw_banded::<Dynamic>(&m, shading, bins, cached);
        assert_eq!((result, binning), (Ok(()), Binning::Off(why)));
    }
    // The error names the reason.
    assert_eq!(
        Unbinned::NoCache.error(),
        Error::InvalidParameter("binned bands only: the renderer has no vertex cache")
    );
    // Whole frames need no bins: a binned-only state draws them as ever.
    let cam = camera(40.0);
    let n = (W * H) as usize;
    let (mut c, mut z) = (vec![Rgb565::BLACK; n], vec![0u16; n]);
    let mut frame = Frame::new(&mut c, &mut z, W, H).unwrap();
    frame.clear(Rgb565::BLACK);
    let mut r = Renderer::new(&mesh, &cam, options(Shading::Lambert))
        .unwrap()
        .with_state::<Binned<LambertLess>>()
        .unwrap();
    assert_eq!(r.draw(&mut frame), Ok(()));
    assert!(r.stats().pixels_written > 500);
}
