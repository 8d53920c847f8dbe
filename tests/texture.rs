//! Textured drawing (`Renderer::draw_textured`): hand-computed texels on a floor seen at a
//! steep angle (perspective-correct against affine), a checker on a cube face seen
//! head-on, the same picture in every target and band height, light exactly as for
//! flat colours, and bad input.

mod common;

use common::textured_cube::{CUBE_INDICES, CUBE_POSITIONS, CUBE_UVS, T};
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use zraster::math::{radians, Mat4, Vec3};
use zraster::mesh::{compute_vertex_normals, Mesh};
use zraster::shade::Shading;
use zraster::texture::{MeshUv, Texture, Wrap};
use zraster::{
    BandBuffers, Bands, Camera, Cull, DrawError, Error, Frame, RenderOptions, Renderer, Texturing,
    UvMode, Viewport, WithDepth, ZBuffer,
};

fn cube(material: Rgb888) -> Mesh<'static, Rgb888> {
    Mesh::triangles(&CUBE_POSITIONS, 1.0 / 16384.0, &CUBE_INDICES, material)
}

/// An 8×8 checker of two raw RGB565 colours with each texel's column and row in it:
/// texel (c, r) is `(c << 11) | (r << 5)`, plus blue on the "black" squares.
const CHECKER: [u16; 64] = {
    let mut t = [0u16; 64];
    let mut i = 0;
    while i < 64 {
        let (c, r) = (i % 8, i / 8);
        t[i] = ((c as u16) << 11) | ((r as u16) << 5) | if (c + r) % 2 == 0 { 0x1F } else { 0 };
        i += 1;
    }
    t
};

/// The texel (column, row) an RGB565 pixel of [`CHECKER`] shows.
fn texel_of(c: Rgb565) -> (u8, u8) {
    (c.r(), c.g() & 7)
}

fn frame_pixels(
    w: u32,
    h: u32,
    draw: impl FnOnce(&mut Frame<'_, Rgb565>) -> Result<(), Error>,
) -> (Vec<Rgb565>, Vec<u16>) {
    let mut px = vec![Rgb565::BLACK; (w * h) as usize];
    let mut depth = vec![0u16; (w * h) as usize];
    {
        let mut frame = Frame::new(&mut px, &mut depth, w, h).unwrap();
        frame.clear(Rgb565::BLACK);
        draw(&mut frame).unwrap();
    }
    (px, depth)
}

/// A floor seen at a steep angle, perspective-correct against affine.
///
/// The eye is at the origin looking down −z, 90° field of view on a 64×64 viewport, so
/// a point (x, y, z) lands at column (1 + x/d)·32 and row (1 − y/d)·32 with d = −z. The
/// floor is y = −1 from d = 1 to d = 9 (x from −1 to 1), its texture a column of 16
/// rows running from the near edge (v = 0) to the far one (v = 1): v = (d − 1)/8.
///
/// Row py's centre (py + ½) sees the floor at 1/d = (py + ½)/32 − 1:
/// - py = 48: 1/d = 0.515625, d = 1.939, v = 0.1174: texel row ⌊16v⌋ = **1**;
/// - py = 40: 1/d = 0.265625, d = 3.765, v = 0.3456: texel row **5**.
///
/// The quad is two triangles, near left A (0, 64), near right B (64, 64), far right
/// C (35.56, 35.56) and far left D (28.44, 35.56) on screen, split along A–C, which
/// crosses column 32 (centre 32.5) at row 38: rows 40 and 48 there lie in A B C, whose
/// affine v is linear on screen, 0 along A B (row 64) and 1 at C: v = (64 − y)/28.44.
/// - py = 48: v = 15.5/28.44 = 0.545: row **8**, 7 texels off the perspective-correct 1;
/// - py = 40: v = 23.5/28.44 = 0.826: row **13**, 8 texels off 5.
#[test]
fn a_floor_at_a_steep_angle_shows_the_hand_computed_texels() {
    // Scale 1/2048: x = ±1 is ±2048, d = 9 is −18432.
    const U: i16 = 2048;
    const FLOOR: [[i16; 3]; 4] = [[-U, -U, -U], [U, -U, -U], [U, -U, -9 * U], [-U, -U, -9 * U]];
    const FLOOR_UVS: [MeshUv; 4] = [[0, 0], [T, 0], [T, T], [0, T]];
    const FLOOR_INDICES: [[u16; 3]; 2] = [[0, 1, 2], [0, 2, 3]];
    // 1×16: row k is raw red k (k << 11).
    const COLUMN: [u16; 16] = {
        let mut t = [0u16; 16];
        let mut k = 0;
        while k < 16 {
            t[k] = (k as u16) << 11;
            k += 1;
        }
        t
    };
    let mesh = Mesh::triangles(&FLOOR, 1.0 / 2048.0, &FLOOR_INDICES, Rgb888::WHITE);
    let camera = Camera::look_at(Vec3::default(), Vec3::new(0.0, 0.0, -1.0), Vec3::Y)
        .unwrap()
        .perspective(radians(90.0), 0.5, 100.0, Viewport::new(64, 64).unwrap())
        .unwrap();
    let options = RenderOptions {
        cull: Cull::None,
        ..Default::default()
    };
    let texture = Texture::new(&COLUMN, 1, 16).unwrap();
    let row_at = |mode: UvMode, x: i32, y: i32| {
        let (px, _) = frame_pixels(64, 64, |frame| {
            let t = Texturing::new(&FLOOR_UVS, texture).with_mode(mode);
            Renderer::new(&mesh, &camera, options)?.draw_textured(frame, &t)?;
            Ok(())
        });
        px[(y * 64 + x) as usize].r()
    };
    assert_eq!(row_at(UvMode::Perspective, 32, 48), 1);
    assert_eq!(row_at(UvMode::Perspective, 32, 40), 5);
    assert_eq!(row_at(UvMode::Affine, 32, 48), 8);
    assert_eq!(row_at(UvMode::Affine, 32, 40), 13);

    // Every covered pixel against the exact perspective-correct row, within the span
    // interpolator's bound (off by one row only where v lies within 1/64 of a row's edge).
    let (px, _) = frame_pixels(64, 64, |frame| {
        let t = Texturing::new(&FLOOR_UVS, texture);
        Renderer::new(&mesh, &camera, options)?.draw_textured(frame, &t)?;
        Ok(())
    });
    let mut checked = 0;
    for y in 37..63 {
        let inv_d = (f64::from(y) + 0.5) / 32.0 - 1.0;
        let v = (1.0 / inv_d - 1.0) / 8.0;
        for x in 0..64 {
            let xd = (f64::from(x) + 0.5) / 32.0 - 1.0; // x/d
            if xd.abs() / inv_d > 0.99 {
                continue; // beyond the floor's sides (or on them)
            }
            let got = f64::from(px[(y * 64 + x) as usize].r());
            let want = v * 16.0;
            assert!(
                got <= want + 1.0 / 64.0 && got + 1.0 > want - 1.0 / 64.0,
                "({x}, {y}): row {got}, exact v·16 = {want:.3}"
            );
            checked += 1;
        }
    }
    assert!(checked > 500, "{checked}");
}

/// The cube's front face seen head-on from (0, 0, 3), 90° on 64×64: at distance 2 it
/// spans x and y from −1 to 1, columns and rows 16 to 48, so each of the 8×8 checker's
/// texels is 4×4 pixels: pixel (x, y) of the face shows texel ((x − 16)/4, (y − 16)/4).
#[test]
fn a_checker_on_a_cube_face_seen_head_on_has_its_edges_on_the_expected_columns() {
    let camera = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::default(), Vec3::Y)
        .unwrap()
        .perspective(radians(90.0), 0.5, 10.0, Viewport::new(64, 64).unwrap())
        .unwrap();
    let texture = Texture::new(&CHECKER, 8, 8).unwrap();
    for mode in [UvMode::Perspective, UvMode::Affine] {
        let (px, _) = frame_pixels(64, 64, |frame| {
            let t = Texturing::new(&CUBE_UVS, texture).with_mode(mode);
            Renderer::new(&cube(Rgb888::WHITE), &camera, RenderOptions::default())?
                .draw_textured(frame, &t)?;
            Ok(())
        });
        for y in 0..64 {
            for x in 0..64 {
                let c = px[(y * 64 + x) as usize];
                if (16..48).contains(&x) && (16..48).contains(&y) {
                    let want = (((x - 16) / 4) as u8, ((y - 16) / 4) as u8);
                    assert_eq!(texel_of(c), want, "{mode:?} ({x}, {y})");
                } else {
                    assert_eq!(c, Rgb565::BLACK, "{mode:?} ({x}, {y})");
                }
            }
        }
    }
}

/// A display in memory, for the draw-target paths.
struct Canvas {
    w: u32,
    h: u32,
    px: Vec<Rgb565>,
}

impl Canvas {
    fn new(w: u32, h: u32) -> Canvas {
        Canvas {
            w,
            h,
            px: vec![Rgb565::BLACK; (w * h) as usize],
        }
    }
}

impl OriginDimensions for Canvas {
    fn size(&self) -> Size {
        Size::new(self.w, self.h)
    }
}

impl DrawTarget for Canvas {
    type Color = Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in pixels {
            if (0..self.w as i32).contains(&p.x) && (0..self.h as i32).contains(&p.y) {
                self.px[(p.y as u32 * self.w + p.x as u32) as usize] = c;
            }
        }
        Ok(())
    }
}

/// The spinning cube at a few angles and distances (the last close enough for the near
/// plane to cut it): a whole frame, band frames, `Bands` at several heights and a
/// `WithDepth` give the same picture, lit by each shading, in both modes.
#[test]
fn every_target_and_band_height_gives_the_whole_frames_picture() {
    let (w, h) = (48u32, 40u32);
    let material = Rgb888::new(200, 180, 40);
    let mesh = cube(material);
    let mut scratch = [Vec3::default(); 24];
    let mut normals = [[0i16; 3]; 24];
    compute_vertex_normals(&mesh, &mut scratch, &mut normals).unwrap();
    let mesh = mesh.with_normals(None, Some(&normals));
    let texture = Texture::new(&CHECKER, 8, 8).unwrap();
    for (k, dist) in [4.0f32, 2.5, 1.3].into_iter().enumerate() {
        let camera = Camera::look_at(Vec3::new(0.3, 0.8, dist), Vec3::default(), Vec3::Y)
            .unwrap()
            .perspective(radians(70.0), 0.5, 20.0, Viewport::new(w, h).unwrap())
            .unwrap()
            .with_model(Mat4::rotation_y(radians(25.0 + 40.0 * k as f32)));
        for shading in [Shading::Flat, Shading::Lambert, Shading::Gouraud] {
            for mode in [UvMode::Perspective, UvMode::Affine] {
                let options = RenderOptions {
                    shading,
                    ..Default::default()
                };
                let t = Texturing::new(&CUBE_UVS, texture).with_mode(mode);
                let what = format!("distance {dist}, {shading:?}, {mode:?}");
                let mut whole_stats = None;
                let (whole, whole_depth) = frame_pixels(w, h, |frame| {
                    let mut r = Renderer::new(&mesh, &camera, options)?;
                    r.draw_textured(frame, &t)?;
                    whole_stats = Some(r.stats());
                    Ok(())
                });
                let whole_stats = whole_stats.unwrap();
                assert!(whole_stats.pixels_written > 200, "{what}");
                if dist < 2.0 {
                    assert!(
                        whole_stats.clipped > 0,
                        "{what}: the near plane cuts the cube"
                    );
                }
                // Band frames, by hand.
                for rows in [1u32, 7, 16] {
                    let mut px = vec![Rgb565::BLACK; (w * h) as usize];
                    let mut depth = vec![0u16; (w * h) as usize];
                    let mut r = Renderer::new(&mesh, &camera, options).unwrap();
                    for y0 in (0..h).step_by(rows as usize) {
                        let n = rows.min(h - y0);
                        let range = (y0 * w) as usize..((y0 + n) * w) as usize;
                        let color =
                            zraster::ColorBuffer::new_band(&mut px[range.clone()], w, n, y0 as i32)
                                .unwrap();
                        let mut zb = ZBuffer::new_band(&mut depth[range], w, n, y0 as i32).unwrap();
                        zb.clear();
                        let mut frame = Frame::from_buffers(color, zb);
                        r.draw_textured(&mut frame, &t).unwrap();
                    }
                    assert!(px == whole, "{what}: band frames of {rows} rows");
                    assert!(depth == whole_depth, "{what}: band depths of {rows} rows");
                    let mut st = r.stats();
                    assert_eq!(st, whole_stats, "{what}: band frames of {rows} rows");
                    // Bands.
                    let mut canvas = Canvas::new(w, h);
                    let (mut bc, mut bd) = (
                        vec![Rgb565::BLACK; (w * rows) as usize],
                        vec![0u16; (w * rows) as usize],
                    );
                    let mut buffers =
                        BandBuffers::new(&mut bc, &mut bd, w, rows, h, &mut []).unwrap();
                    let mut r = Renderer::new(&mesh, &camera, options).unwrap();
                    r.draw_textured(
                        &mut Bands::new(&mut canvas, &mut buffers, Rgb565::BLACK),
                        &t,
                    )
                    .unwrap();
                    assert!(canvas.px == whole, "{what}: Bands of {rows} rows");
                    st = r.stats();
                    assert_eq!(st.pixels_written, whole_stats.pixels_written, "{what}");
                    assert_eq!(st.drawn, whole_stats.drawn, "{what}");
                }
                // A display with a Z-buffer.
                let mut canvas = Canvas::new(w, h);
                let mut depth = vec![0u16; (w * h) as usize];
                let mut zb = ZBuffer::new(&mut depth, w, h).unwrap();
                zb.clear();
                let mut r = Renderer::new(&mesh, &camera, options).unwrap();
                r.draw_textured(&mut WithDepth::new(&mut canvas, &mut zb), &t)
                    .unwrap();
                assert!(canvas.px == whole, "{what}: WithDepth");
                assert!(depth == whole_depth, "{what}: WithDepth depths");
                assert_eq!(
                    r.stats().pixels_written,
                    whole_stats.pixels_written,
                    "{what}"
                );
            }
        }
    }
}

/// A 1×1 texture of a colour draws exactly the pixels and depths of the untextured mesh
/// in that colour, under every shading (flat, Lambert, Gouraud), also where the near
/// plane cuts the cube.
#[test]
fn a_one_texel_texture_is_lit_exactly_as_the_flat_colour() {
    let (w, h) = (56u32, 44u32);
    let colour = Rgb888::new(210, 120, 60);
    let one = [colour];
    let texture = Texture::new(&one, 1, 1).unwrap();
    let mesh = cube(colour);
    let mut scratch = [Vec3::default(); 24];
    let mut normals = [[0i16; 3]; 24];
    compute_vertex_normals(&mesh, &mut scratch, &mut normals).unwrap();
    let mesh = mesh.with_normals(None, Some(&normals));
    for dist in [3.5f32, 1.2] {
        let camera = Camera::look_at(Vec3::new(0.9, 1.1, dist), Vec3::default(), Vec3::Y)
            .unwrap()
            .perspective(radians(75.0), 0.5, 20.0, Viewport::new(w, h).unwrap())
            .unwrap()
            .with_model(Mat4::rotation_y(radians(33.0)));
        for shading in [Shading::Flat, Shading::Lambert, Shading::Gouraud] {
            let options = RenderOptions {
                shading,
                ..Default::default()
            };
            let flat = frame_pixels(w, h, |frame| {
                Renderer::new(&mesh, &camera, options)?.draw(frame)?;
                Ok(())
            });
            let textured = frame_pixels(w, h, |frame| {
                let t = Texturing::new(&CUBE_UVS, texture);
                Renderer::new(&mesh, &camera, options)?.draw_textured(frame, &t)?;
                Ok(())
            });
            assert!(flat.0.iter().filter(|&&c| c != Rgb565::BLACK).count() > 300);
            assert!(textured.0 == flat.0, "{shading:?} at {dist}: colours");
            assert!(textured.1 == flat.1, "{shading:?} at {dist}: depths");
        }
    }
}

/// At full light on a display of the texel's own type a pixel is the texel itself,
/// which is what lighting the texel as an `Rgb888` material at full intensity gives.
#[test]
fn full_light_keeps_every_rgb565_texel() {
    use zraster::shade::{Material, ONE};
    for raw in 0..=u16::MAX {
        let c = Rgb565::from(embedded_graphics::pixelcolor::raw::RawU16::new(raw));
        let lit: Rgb565 = Rgb888::from(c).shade(ONE, 0, 0);
        assert_eq!(lit, c, "{raw:#06x}");
    }
}

#[test]
fn bad_input_is_an_error_or_a_documented_fallback() {
    let camera = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::default(), Vec3::Y)
        .unwrap()
        .perspective(radians(90.0), 0.5, 10.0, Viewport::new(64, 64).unwrap())
        .unwrap();
    let mesh = cube(Rgb888::WHITE);
    let texture = Texture::new(&CHECKER, 8, 8).unwrap();
    // A UV table shorter than the vertex table.
    let (mut px, mut depth) = (vec![Rgb565::BLACK; 64 * 64], vec![0u16; 64 * 64]);
    let mut frame = Frame::new(&mut px, &mut depth, 64, 64).unwrap();
    let short = Texturing::new(&CUBE_UVS[..23], texture);
    let err = Renderer::new(&mesh, &camera, RenderOptions::default())
        .unwrap()
        .draw_textured(&mut frame, &short)
        .unwrap_err();
    assert_eq!(
        err,
        DrawError::Input(Error::InvalidParameter(
            "fewer texture coordinates than vertices"
        ))
    );
    assert_eq!(
        mesh.check_uvs(&CUBE_UVS[..23]),
        Err(Error::InvalidParameter(
            "fewer texture coordinates than vertices"
        ))
    );
    assert_eq!(mesh.check_uvs(&CUBE_UVS), Ok(()));
    // Textures of size 0 or on a short slice are errors where they are made.
    assert_eq!(Texture::new(&CHECKER, 0, 8).unwrap_err(), Error::ZeroSize);
    assert_eq!(
        Texture::new(&CHECKER, 9, 8).unwrap_err(),
        Error::BufferTooSmall {
            needed: 72,
            got: 64
        }
    );
    // The extremes of a mesh's Q12 coordinates (−8 and 8 − 1/4096 textures; a mesh table
    // holds no NaN: obj2rust rejects NaN and moves huge ones by whole textures): the
    // whole face samples u = 7.99976 (repeat: the last column) and v = −8 (the first row).
    let extreme = [[i16::MAX, i16::MIN]; 24];
    for (wrap, want) in [(Wrap::Repeat, (7, 0)), (Wrap::Clamp, (7, 0))] {
        let t = Texturing::new(&extreme, texture.with_wrap(wrap));
        let (px, _) = frame_pixels(64, 64, |frame| {
            Renderer::new(&mesh, &camera, RenderOptions::default())?.draw_textured(frame, &t)?;
            Ok(())
        });
        for y in 16..48 {
            for x in 16..48 {
                assert_eq!(texel_of(px[y * 64 + x]), want, "{wrap:?} ({x}, {y})");
            }
        }
    }
    // Coordinates that differ by ±16 textures across a face, seen at a slant and clipped
    // by the near plane: drawn, no panic (debug builds check every overflow).
    let wild: [MeshUv; 24] = core::array::from_fn(|i| {
        if i % 2 == 0 {
            [i16::MIN, i16::MAX]
        } else {
            [i16::MAX, i16::MIN]
        }
    });
    for dist in [1.1f32, 3.0] {
        let camera = Camera::look_at(Vec3::new(0.7, 0.4, dist), Vec3::default(), Vec3::Y)
            .unwrap()
            .perspective(radians(100.0), 0.05, 10.0, Viewport::new(64, 64).unwrap())
            .unwrap();
        for mode in [UvMode::Perspective, UvMode::Affine] {
            let t = Texturing::new(&wild, texture).with_mode(mode);
            frame_pixels(64, 64, |frame| {
                Renderer::new(&mesh, &camera, RenderOptions::default())?
                    .draw_textured(frame, &t)?;
                Ok(())
            });
        }
    }
}

/// The checksum of bench/mcu-texture's perspective-correct picture, which
/// `bench/texture.sh` requires of the Cortex-M4F and M0+ builds: the same pixels there
/// as here.
const TEXTURE_BENCH_CHECKSUM: u32 = 0xfc84_39c5;

/// bench/mcu-texture's scene on the host: the fill-bound cube (`mesh::CUBE`, its front
/// face filling 320×240 pixels) with its 64×64 checker, four times across.
#[test]
fn the_texture_bench_picture_has_the_pinned_checksum() {
    use zraster::mesh::{CUBE, CUBE_POSITIONS};
    let checker: Vec<u16> = (0..64 * 64)
        .map(|i| {
            if (i % 64 / 8 + i / 64 / 8) % 2 == 0 {
                0xFD20
            } else {
                0x18E3
            }
        })
        .collect();
    let uvs: Vec<MeshUv> = CUBE_POSITIONS
        .iter()
        .map(|p| [p[0], 16384 - p[1]])
        .collect();
    let camera = Camera::look_at(Vec3::new(0.5, 0.5, 1.3), Vec3::new(0.5, 0.5, 0.0), Vec3::Y)
        .unwrap()
        .perspective(radians(60.0), 0.1, 10.0, Viewport::new(320, 240).unwrap())
        .unwrap();
    let t = Texturing::new(&uvs, Texture::new(&checker, 64, 64).unwrap());
    let (px, _) = frame_pixels(320, 240, |frame| {
        Renderer::new(&CUBE, &camera, RenderOptions::default())?.draw_textured(frame, &t)?;
        Ok(())
    });
    // FNV-1a over each pixel's two bytes, low first (as the firmware sums them).
    let sum = px.iter().fold(0x811c_9dc5u32, |h, c| {
        let v = c.into_storage();
        ((h ^ u32::from(v & 0xff)).wrapping_mul(0x0100_0193) ^ u32::from(v >> 8))
            .wrapping_mul(0x0100_0193)
    });
    assert_eq!(sum, TEXTURE_BENCH_CHECKSUM, "{sum:08x}");
}

/// Textures of every kind of size (power-of-two or not, square or not, one texel wide
/// or high) on the cube's front face seen head-on: pixel (x, y) of the face shows texel
/// (⌊u·W⌋, ⌊v·H⌋) with u = (x + ½ − 16)/32 and v = (y + ½ − 16)/32, whichever way the
/// texel is found (shifts for power-of-two sizes, the texture's own sampling else),
/// and a display with a Z-buffer gets the same pixels.
#[test]
fn every_texture_size_samples_the_texel_under_each_pixel_centre() {
    let camera = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::default(), Vec3::Y)
        .unwrap()
        .perspective(radians(90.0), 0.5, 10.0, Viewport::new(64, 64).unwrap())
        .unwrap();
    for (w, h) in [(4u32, 16u32), (16, 2), (3, 5), (2, 1), (1, 1), (64, 64)] {
        // Texel (c, r) is (c << 11) | (r << 5) as raw RGB565 (c, r < 32 here; 64×64
        // keeps the low 5 bits of each).
        let texels: Vec<u16> = (0..w * h)
            .map(|i| (((i % w) as u16 & 31) << 11) | (((i / w) as u16 & 31) << 5))
            .collect();
        let t = Texturing::new(&CUBE_UVS, Texture::new(&texels, w, h).unwrap());
        let (px, _) = frame_pixels(64, 64, |frame| {
            Renderer::new(&cube(Rgb888::WHITE), &camera, RenderOptions::default())?
                .draw_textured(frame, &t)?;
            Ok(())
        });
        for y in 16..48 {
            for x in 16..48 {
                let u = (f64::from(x) + 0.5 - 16.0) / 32.0;
                let v = (f64::from(y) + 0.5 - 16.0) / 32.0;
                let (c, r) = ((u * f64::from(w)) as u8 & 31, (v * f64::from(h)) as u8 & 31);
                let got = px[(y * 64 + x) as usize];
                assert_eq!((got.r(), got.g() & 31), (c, r), "{w}×{h} at ({x}, {y})");
            }
        }
        let mut canvas = Canvas::new(64, 64);
        let mut depth = vec![0u16; 64 * 64];
        let mut zb = ZBuffer::new(&mut depth, 64, 64).unwrap();
        zb.clear();
        Renderer::new(&cube(Rgb888::WHITE), &camera, RenderOptions::default())
            .unwrap()
            .draw_textured(&mut WithDepth::new(&mut canvas, &mut zb), &t)
            .unwrap();
        assert!(canvas.px == px, "{w}×{h}: WithDepth");
    }
}
