//! `Model`, the embedded-graphics primitive: the same pixels as the lower-level
//! `Renderer` into a whole `Frame`, for several colour types, shadings and band sizes;
//! drawn over a picture it changes only the pixels it covers; wrong input and failing
//! displays give errors, never a panic, and nothing is drawn on wrong input.

use embedded_graphics::{
    mock_display::MockDisplay,
    pixelcolor::{BinaryColor, Gray4, Rgb565, Rgb888},
    prelude::*,
    primitives::Rectangle,
};
use embedded_graphics_simulator::SimulatorDisplay;
use zraster::{
    math::{radians, Mat4, Vec3},
    mesh::{Faces, Materials, Mesh, CUBE, CUBE_POSITIONS},
    shade::DisplayColor,
    Camera, Cull, DrawError, Error, Frame, FrameStats, Model, ModelStyle, Renderer, Viewport,
};
use zraster_bench_scene::bunny::{BUNNY_FIT, BUNNY_MESH};

/// The bunny fitted to the unit cube, turned 30°, seen from z = 1.6 in `vp`.
fn bunny_camera(vp: Viewport) -> Camera {
    let fit =
        Mat4::rotation_y(radians(30.0)) * Mat4::scaling(Vec3::new(BUNNY_FIT, BUNNY_FIT, BUNNY_FIT));
    Camera::look_at(Vec3::new(0.0, 0.1, 1.6), Vec3::default(), Vec3::Y)
        .unwrap()
        .perspective(radians(40.0), 0.1, 10.0, vp)
        .unwrap()
        .with_model(fit)
}

/// The unit cube from the upper right front, in `vp`.
fn cube_camera(vp: Viewport) -> Camera {
    Camera::look_at(Vec3::new(2.0, 1.5, 3.0), Vec3::new(0.5, 0.5, 0.5), Vec3::Y)
        .unwrap()
        .perspective(radians(45.0), 0.1, 10.0, vp)
        .unwrap()
}

/// The lower-level picture: a whole `w × h` frame cleared to `background`, drawn by a
/// `Renderer` with the style's options; its colours, depths and stats.
fn reference<C>(
    mesh: &Mesh<'_, Rgb888>,
    camera: &Camera,
    style: &ModelStyle<C>,
    background: C,
    (w, h): (u32, u32),
) -> (Vec<C>, Vec<u16>, FrameStats)
where
    C: DisplayColor,
{
    let mut colors = vec![background; (w * h) as usize];
    let mut depths = vec![0u16; (w * h) as usize];
    let mut frame = Frame::new(&mut colors, &mut depths, w, h).unwrap();
    frame.clear(background);
    let mut renderer = Renderer::new(mesh, camera, style.options()).unwrap();
    renderer.draw(&mut frame).unwrap();
    let stats = renderer.stats();
    (colors, depths, stats)
}

/// Every pixel of a simulator display, row by row.
fn pixels<C: PixelColor>(display: &SimulatorDisplay<C>) -> Vec<C> {
    let s = display.size();
    let (w, h) = (s.width as i32, s.height as i32);
    (0..h)
        .flat_map(|y| (0..w).map(move |x| display.get_pixel(Point::new(x, y))))
        .collect()
}

/// A colour for each pixel that no model draws: a picture to draw over.
fn picture<C: DisplayColor>(w: u32, h: u32) -> SimulatorDisplay<C> {
    let mut display =
        SimulatorDisplay::with_default_color(Size::new(w, h), C::lit(Rgb888::BLACK, 0, 0, 0));
    let pattern = (0..h as i32).flat_map(|y| {
        (0..w as i32).map(move |x| {
            let v = ((x * 7 + y * 13) % 256) as u8;
            Pixel(
                Point::new(x, y),
                C::lit(Rgb888::new(v, 255 - v, v / 2), 1 << 15, x, y),
            )
        })
    });
    display.draw_iter(pattern).unwrap();
    display
}

/// `Model` with a background, and without one over a picture, against the reference,
/// with band capacity `N` (rows of `N / w` lines).
fn check<C, const N: usize>(
    mesh: &Mesh<'_, Rgb888>,
    camera: &Camera,
    style: ModelStyle<C>,
    background: C,
    (w, h): (u32, u32),
) where
    C: DisplayColor + Default + core::fmt::Debug,
{
    let what = format!("{} × {}, {N} pixels a band, {:?}", w, h, style.shading);
    let (colors, depths, stats) = reference(mesh, camera, &style, background, (w, h));
    assert!(
        stats.drawn > 0 && stats.pixels_written > 0,
        "{what}: the reference is empty"
    );
    let model = Model::new(mesh, camera).with_band_pixels::<N>();

    // With a background: every pixel is the frame's.
    let mut display = picture::<C>(w, h);
    let drawn = model
        .into_styled(style.with_background(background))
        .draw(&mut display)
        .unwrap()
        .unwrap();
    assert_eq!(pixels(&display), colors, "{what}: with a background");
    assert_eq!(drawn, stats, "{what}: stats with a background");

    // Without: the frame's pixels where the frame drew, the picture elsewhere.
    let before = picture::<C>(w, h);
    let mut display = picture::<C>(w, h);
    let drawn = model
        .into_styled(style.without_background())
        .draw(&mut display)
        .unwrap()
        .unwrap();
    let expected: Vec<C> = pixels(&before)
        .into_iter()
        .zip(colors.iter().zip(&depths))
        .map(|(old, (&new, &depth))| if depth < u16::MAX { new } else { old })
        .collect();
    let covered = depths.iter().filter(|&&d| d < u16::MAX).count();
    assert!(
        covered > 0 && covered < (w * h) as usize,
        "{what}: {covered} covered"
    );
    assert_eq!(pixels(&display), expected, "{what}: over a picture");
    assert_eq!(drawn, stats, "{what}: stats over a picture");
}

#[test]
fn model_equals_renderer_and_frame() {
    let vp = |w, h| Viewport::new(w, h).unwrap();
    // The bunny on RGB565, Lambert: 160-pixel rows, 6 a band (the last band shorter).
    check::<Rgb565, 1000>(
        &BUNNY_MESH,
        &bunny_camera(vp(160, 120)),
        ModelStyle::lambert(),
        Rgb565::new(2, 4, 8),
        (160, 120),
    );
    // Gouraud and dithered on a 16-grey panel, the default capacity (4 rows a band).
    check::<Gray4, 1024>(
        &BUNNY_MESH,
        &bunny_camera(vp(256, 64)),
        ModelStyle::gouraud(),
        Gray4::new(1),
        (256, 64),
    );
    // Flat cube on a 1-bit panel, one row a band; and Lambert with no culling.
    check::<BinaryColor, 128>(
        &CUBE,
        &cube_camera(vp(128, 64)),
        ModelStyle::flat(),
        BinaryColor::Off,
        (128, 64),
    );
    let style = ModelStyle::lambert().with_cull(Cull::None);
    check::<Rgb888, 333>(
        &CUBE,
        &cube_camera(vp(100, 70)),
        style,
        Rgb888::new(10, 20, 30),
        (100, 70),
    );
    // A single band holds the whole display.
    check::<Rgb565, { 64 * 48 }>(
        &CUBE,
        &cube_camera(vp(64, 48)),
        ModelStyle::lambert(),
        Rgb565::BLACK,
        (64, 48),
    );
}

/// A viewport smaller than the display: the model's bounding box, outside which
/// nothing changes (even with a background), inside which the frame's pixels are.
#[test]
fn nothing_outside_the_viewport() {
    let (w, h) = (96, 64);
    let vp = Viewport::at(20, 8, 48, 40).unwrap();
    let camera = cube_camera(vp);
    let model = Model::new(&CUBE, &camera).with_band_pixels::<300>();
    let bbox = Rectangle::new(Point::new(20, 8), Size::new(48, 40));
    assert_eq!(model.bounding_box(), bbox);
    let style = ModelStyle::lambert().with_background(Rgb565::new(0, 10, 0));
    assert_eq!(model.into_styled(style).bounding_box(), bbox);

    let (colors, _, _) = reference(&CUBE, &camera, &style, Rgb565::new(0, 10, 0), (w, h));
    let before = picture::<Rgb565>(w, h);
    let mut display = picture::<Rgb565>(w, h);
    model
        .into_styled(style)
        .draw(&mut display)
        .unwrap()
        .unwrap();
    let mut inside = 0;
    for (i, (&shown, &old)) in pixels(&display).iter().zip(&pixels(&before)).enumerate() {
        let p = Point::new((i as u32 % w) as i32, (i as u32 / w) as i32);
        if bbox.contains(p) {
            assert_eq!(shown, colors[i], "inside, at {p:?}");
            inside += 1;
        } else {
            assert_eq!(shown, old, "outside, at {p:?}");
        }
    }
    assert_eq!(inside, 48 * 40);
}

/// On a `MockDisplay` (which fails the test on any pixel drawn twice or outside it):
/// without a background each covered pixel is sent once and no other; over a picture,
/// the picture stays where the model does not cover it.
#[test]
fn over_a_picture_each_pixel_once() {
    let camera = cube_camera(Viewport::new(64, 64).unwrap());
    let model = Model::new(&CUBE, &camera).into_styled(ModelStyle::flat());
    let mut alone = MockDisplay::<Rgb565>::new();
    let stats = model.draw(&mut alone).unwrap().unwrap();
    assert_eq!(stats.drawn, 6);
    let (colors, depths, _) =
        reference(&CUBE, &camera, &ModelStyle::flat(), Rgb565::BLACK, (64, 64));
    for (i, (&color, &depth)) in colors.iter().zip(&depths).enumerate() {
        let p = Point::new(i as i32 % 64, i as i32 / 64);
        let expected = (depth < u16::MAX).then_some(color);
        assert_eq!(alone.get_pixel(p), expected, "at {p:?}");
    }

    // A picture first: the left half grey.
    let grey = Rgb565::new(12, 24, 12);
    let mut display = MockDisplay::<Rgb565>::new();
    display
        .fill_solid(&Rectangle::new(Point::zero(), Size::new(32, 64)), grey)
        .unwrap();
    let before = display.clone();
    display.set_allow_overdraw(true); // the model draws over the grey
    model.draw(&mut display).unwrap().unwrap();
    for y in 0..64 {
        for x in 0..64 {
            let p = Point::new(x, y);
            let expected = alone.get_pixel(p).or(before.get_pixel(p));
            assert_eq!(display.get_pixel(p), expected, "at {p:?}");
        }
    }
    assert_eq!(display.get_pixel(Point::new(1, 1)), Some(grey));
    assert_eq!(display.get_pixel(Point::new(62, 1)), None);
    assert!((0..64).any(|y| alone.get_pixel(Point::new(31, y)).is_some())); // over the grey
}

/// A display that counts the calls it gets, and fails after `fail_after` of them.
struct Counting {
    size: Size,
    calls: Vec<Rectangle>,
    fail_after: usize,
}

#[derive(Debug, PartialEq)]
struct Broken;

impl OriginDimensions for Counting {
    fn size(&self) -> Size {
        self.size
    }
}

impl DrawTarget for Counting {
    type Color = Rgb565;
    type Error = Broken;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, _: I) -> Result<(), Broken> {
        Err(Broken) // the model sends whole rectangles only
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Broken>
    where
        I: IntoIterator<Item = Rgb565>,
    {
        if self.calls.len() == self.fail_after {
            return Err(Broken);
        }
        assert_eq!(
            colors.into_iter().count(),
            area.size.width as usize * area.size.height as usize
        );
        self.calls.push(*area);
        Ok(())
    }
}

/// With a background, one `fill_contiguous` a band, bands of `N / width` rows tiling the
/// display; a failing display's error is `draw`'s `Err`, or `DrawError::Target`.
#[test]
fn one_call_a_band_and_display_errors() {
    let camera = cube_camera(Viewport::new(50, 23).unwrap());
    let mut display = Counting {
        size: Size::new(50, 23),
        calls: vec![],
        fail_after: usize::MAX,
    };
    let style = ModelStyle::flat().with_background(Rgb565::BLACK);
    let model = Model::new(&CUBE, &camera).with_band_pixels::<240>(); // 4 rows of 50
    model
        .into_styled(style)
        .draw(&mut display)
        .unwrap()
        .unwrap();
    let rows: Vec<(i32, u32)> = display
        .calls
        .iter()
        .map(|r| (r.top_left.y, r.size.height))
        .collect();
    assert_eq!(rows, [(0, 4), (4, 4), (8, 4), (12, 4), (16, 4), (20, 3)]);
    assert!(display
        .calls
        .iter()
        .all(|r| r.top_left.x == 0 && r.size.width == 50));

    let mut failing = Counting {
        size: Size::new(50, 23),
        calls: vec![],
        fail_after: 2,
    };
    assert_eq!(model.into_styled(style).draw(&mut failing), Err(Broken));
    assert_eq!(failing.calls.len(), 2);
    failing.calls.clear();
    assert_eq!(
        model.render(&style, &mut failing),
        Err(DrawError::Target(Broken))
    );
    // Without a background, runs of single rows.
    let mut display = Counting {
        size: Size::new(50, 23),
        calls: vec![],
        fail_after: usize::MAX,
    };
    model
        .into_styled(ModelStyle::flat())
        .draw(&mut display)
        .unwrap()
        .unwrap();
    assert!(display.calls.len() >= 10 && display.calls.iter().all(|r| r.size.height == 1));
}

/// A display wider than a band holds: a clear error, nothing drawn.
#[test]
fn too_wide_for_the_band_capacity() {
    let camera = cube_camera(Viewport::new(200, 40).unwrap());
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(200, 40));
    let untouched = pixels(&display);
    let model = Model::new(&CUBE, &camera).with_band_pixels::<199>();
    let style = ModelStyle::lambert().with_background(Rgb565::RED);
    let r = model.into_styled(style).draw(&mut display);
    assert_eq!(r, Ok(Err(Error::CapacityExceeded { capacity: 199 })));
    let r = Model::new(&CUBE, &camera)
        .with_band_pixels::<0>()
        .render(&style, &mut display);
    assert_eq!(
        r,
        Err(DrawError::Input(Error::CapacityExceeded { capacity: 0 }))
    );
    assert_eq!(pixels(&display), untouched);
    // One row fits: drawn.
    let one_row = Model::new(&CUBE, &camera).with_band_pixels::<200>();
    assert!(one_row
        .into_styled(style)
        .draw(&mut display)
        .unwrap()
        .is_ok());
    assert_ne!(pixels(&display), untouched);
    // A display wider than the viewport needs only the viewport's columns.
    let narrow = cube_camera(Viewport::new(100, 40).unwrap());
    let r = Model::new(&CUBE, &narrow)
        .with_band_pixels::<100>()
        .into_styled(style)
        .draw(&mut display);
    assert!(matches!(r, Ok(Ok(_))), "{r:?}");
}

/// Wrong meshes give zraster's error, before anything is drawn.
#[test]
fn bad_meshes_are_errors() {
    let camera = cube_camera(Viewport::new(64, 64).unwrap());
    let mut display = MockDisplay::<Rgb565>::new();
    // The last triangle refers to vertex 8 of 8.
    const BAD: [[u16; 3]; 3] = [[0, 1, 2], [0, 2, 3], [4, 5, 8]];
    let bad = Mesh::triangles(&CUBE_POSITIONS, 1.0 / 16384.0, &BAD, Rgb888::RED);
    let r = Model::new(&bad, &camera)
        .into_styled(ModelStyle::flat())
        .draw(&mut display);
    assert_eq!(r, Ok(Err(Error::IndexOutOfRange { face: 2, index: 8 })));
    // Per-face materials, one short.
    let mut short = bad;
    short.faces = Faces::Triangles {
        indices: &BAD[..2],
        materials: Materials::PerFace(&[Rgb888::RED]),
    };
    let r = Model::new(&short, &camera)
        .into_styled(ModelStyle::flat())
        .draw(&mut display);
    assert!(matches!(r, Ok(Err(_))), "{r:?}");
    // Gouraud without vertex normals; a scale that is not finite.
    let r = Model::new(&CUBE, &camera).render(&ModelStyle::gouraud(), &mut display);
    assert_eq!(r, Err(DrawError::Input(Error::MissingNormals)));
    let mut nan = CUBE;
    nan.scale = f32::NAN;
    let r = Model::new(&nan, &camera)
        .into_styled(ModelStyle::flat())
        .draw(&mut display);
    assert_eq!(r, Ok(Err(Error::NotFinite)));
    assert_eq!(display, MockDisplay::new());
    // A bad light too.
    let mut light = ModelStyle::<Rgb565>::lambert().light;
    light.ambient = f32::INFINITY;
    let r = Model::new(&CUBE, &camera)
        .into_styled(ModelStyle::lambert().with_light(light))
        .draw(&mut display);
    assert_eq!(r, Ok(Err(Error::NotFinite)));
    assert_eq!(display, MockDisplay::new());
}

/// A viewport off the display draws nothing and is not an error.
#[test]
fn off_the_display() {
    let camera = cube_camera(Viewport::at(100, 0, 64, 64).unwrap());
    let mut display = MockDisplay::<Rgb565>::new();
    let style = ModelStyle::flat().with_background(Rgb565::BLUE);
    let stats = Model::new(&CUBE, &camera)
        .into_styled(style)
        .draw(&mut display)
        .unwrap()
        .unwrap();
    assert_eq!(stats.pixels_written, 0);
    assert_eq!(display, MockDisplay::new());
}

/// The bench scene (bunny-320, Lambert) drawn as a `Model` in 3-row bands on a
/// 320 × 240 display is the pinned bench frame.
#[test]
fn the_bench_scene_as_a_model_has_the_bench_checksum() {
    let (mesh, camera) = (
        zraster_bench_scene::mesh(),
        zraster_bench_scene::transform(),
    );
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(320, 240));
    let style = ModelStyle::lambert().with_background(Rgb565::BLACK);
    assert_eq!(style.options(), zraster_bench_scene::options());
    let model = Model::new(&mesh, &camera);
    assert_eq!(model.band_pixels() / 320, 3);
    model
        .into_styled(style)
        .draw(&mut display)
        .unwrap()
        .unwrap();
    assert_eq!(
        zraster_bench_scene::checksum(&pixels(&display)),
        0xfb19_6b71
    );
}
