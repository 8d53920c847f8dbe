//! Pixel shaders (`Renderer::draw_with_shader`): a pattern from the position on exactly
//! the covered pixels, fog at hand-computed depths, a texel shader against
//! `draw_textured`, every target and band height against the whole frame, bad input.

mod common;

use common::textured_cube::{
    CUBE_INDICES as INDICES, CUBE_POSITIONS as POSITIONS, CUBE_UVS as UVS,
};
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use zraster::math::{radians, Mat4, Vec3};
use zraster::mesh::{compute_vertex_normals, Mesh};
use zraster::shade::Shading;
use zraster::shader::{Fog, Fragment, Lit, PixelShader, Textured, WithUvs};
use zraster::texture::{MeshUv, TexCoord, Texture};
use zraster::{
    BandBuffers, Bands, Camera, ColorBuffer, DrawError, Error, Frame, RenderOptions, Renderer,
    Texturing, UvMode, Viewport, WithDepth, ZBuffer,
};

/// An 8×8 texture of raw RGB565 values, each texel different.
const TEXELS: [u16; 64] = {
    let mut t = [0u16; 64];
    let mut i = 0;
    while i < 64 {
        t[i] = ((i as u16 % 8) << 12) | ((i as u16 / 8) << 6) | if i % 3 == 0 { 0x1F } else { 4 };
        i += 1;
    }
    t
};
/// A 3×5 texture (not a power of two: the general sampling path).
const ODD: [Rgb565; 15] = {
    let mut t = [Rgb565::BLACK; 15];
    let mut i = 0;
    while i < 15 {
        t[i] = Rgb565::new(2 * i as u8, 63 - 3 * i as u8, (i % 4) as u8 * 9);
        i += 1;
    }
    t
};

/// The cube, lit with vertex normals (for Gouraud).
fn with_normals(normals: &mut [[i16; 3]; 24]) -> Mesh<'_, Rgb888> {
    let mesh = Mesh::triangles(
        &POSITIONS,
        1.0 / 16384.0,
        &INDICES,
        Rgb888::new(200, 150, 60),
    );
    let mut scratch = [Vec3::default(); 24];
    compute_vertex_normals(&mesh, &mut scratch, normals).unwrap();
    mesh.with_normals(None, Some(normals))
}

/// A camera on the cube turned by `k`, at `dist` (1.3 is close enough for the near plane
/// to cut it).
fn camera(w: u32, h: u32, dist: f32, k: usize) -> Camera {
    Camera::look_at(Vec3::new(0.3, 0.8, dist), Vec3::default(), Vec3::Y)
        .unwrap()
        .perspective(radians(70.0), 0.5, 20.0, Viewport::new(w, h).unwrap())
        .unwrap()
        .with_model(Mat4::rotation_y(radians(25.0 + 40.0 * k as f32)))
}

/// The colour and depth of a whole frame drawn by `draw`, cleared to black first.
fn frame_of(
    w: u32,
    h: u32,
    draw: impl FnOnce(&mut Frame<'_, Rgb565>) -> Result<(), DrawError<core::convert::Infallible>>,
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

/// A display in memory, for the draw-target paths.
struct Canvas {
    w: u32,
    px: Vec<Rgb565>,
}

impl OriginDimensions for Canvas {
    fn size(&self) -> Size {
        Size::new(self.w, self.px.len() as u32 / self.w)
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
            assert!(
                p.x >= 0 && p.y >= 0 && (p.x as u32) < self.w,
                "{p:?} outside"
            );
            self.px[(p.y as u32 * self.w + p.x as u32) as usize] = c;
        }
        Ok(())
    }
}

/// The pattern of the first test: a colour from the position alone.
fn pattern(x: i32, y: i32) -> Rgb565 {
    Rgb565::new((x % 32) as u8, (y % 64) as u8, ((x + y) % 3) as u8 * 10 + 1)
}

#[test]
fn a_pattern_from_the_position_covers_exactly_the_pixels_draw_covers() {
    let (w, h) = (48u32, 40u32);
    let mut normals = [[0i16; 3]; 24];
    let mesh = with_normals(&mut normals);
    for (k, dist) in [4.0f32, 2.5, 1.3].into_iter().enumerate() {
        let cam = camera(w, h, dist, k);
        let options = RenderOptions::default();
        // Coverage and depth of the untextured draw in white (none of the pattern is).
        let white = Mesh::triangles(&POSITIONS, 1.0 / 16384.0, &INDICES, Rgb888::WHITE);
        let (covered, want_depth) = frame_of(w, h, |f| {
            Renderer::new(&white, &cam, options)?.draw(f)?;
            Ok(())
        });
        let shader = |f: &Fragment| pattern(f.x, f.y);
        let (px, depth) = frame_of(w, h, |f| {
            Renderer::new(&mesh, &cam, options)?.draw_with_shader(f, &shader)
        });
        let mut n = 0;
        for y in 0..h as i32 {
            for x in 0..w as i32 {
                let i = (y as u32 * w + x as u32) as usize;
                if covered[i] == Rgb565::BLACK {
                    assert_eq!(px[i], Rgb565::BLACK, "({x}, {y}) is not covered");
                } else {
                    assert_eq!(px[i], pattern(x, y), "({x}, {y})");
                    n += 1;
                }
            }
        }
        assert!(n > 300, "{n} pixels covered");
        assert!(depth == want_depth, "the depths of draw()");
    }
}

#[test]
fn fog_fades_towards_its_colour_linearly_in_depth() {
    let base = |_: &Fragment| Rgb888::new(200, 100, 0);
    let fog = Fog::from_depths(base, 10_000, 50_000, Rgb888::new(40, 40, 240)).unwrap();
    let at = |depth| {
        let f = Fragment {
            x: 3,
            y: 4,
            depth,
            uv: TexCoord::default(),
            light: 0,
            material: Rgb888::BLACK,
        };
        PixelShader::<Rgb888>::shade(&fog, &f)
    };
    // R = ⌊2²⁴/40000⌋ = 419. Depth 20000: t = ⌊10000·419/65536⌋ = ⌊63.93⌋ = 63.
    // r = (200·193 + 40·63 + 128)/256 = 41248/256 = 161.1 → 161; g = (100·193 + 2520
    // + 128)/256 = 21948/256 = 85.7 → 85; b = (240·63 + 128)/256 = 15248/256 = 59.6 → 59.
    assert_eq!(fog.amount(20_000), 63);
    assert_eq!(at(20_000), Rgb888::new(161, 85, 59));
    // Depth 43000: t = ⌊33000·419/65536⌋ = ⌊210.98⌋ = 210. r = (200·46 + 40·210 +
    // 128)/256 = 17728/256 = 69.25 → 69; g = (100·46 + 8400 + 128)/256 = 13128/256 →
    // 51; b = (240·210 + 128)/256 = 50528/256 = 197.4 → 197.
    assert_eq!(fog.amount(43_000), 210);
    assert_eq!(at(43_000), Rgb888::new(69, 51, 197));
    // None before near, all of it after far.
    assert_eq!(at(0), Rgb888::new(200, 100, 0));
    assert_eq!(at(10_000), Rgb888::new(200, 100, 0));
    assert_eq!(at(50_000), Rgb888::new(40, 40, 240));
    assert_eq!(at(u16::MAX), Rgb888::new(40, 40, 240));
    // From window depths: 0.25 and 0.75 are 16384 and 49151.
    let f = Fog::new(base, 0.25, 0.75, Rgb888::BLACK).unwrap();
    assert_eq!(f.amount(16384), 0);
    assert_eq!(f.amount(16385), 0); // ⌊256/32767⌋
    assert_eq!(f.amount(16384 + 32767 / 2), 127);
    assert_eq!(f.amount(49150), 255);
    assert_eq!(f.amount(49151), 256);

    // Drawn: every covered pixel is the lit colour fogged by its own depth (an Rgb888
    // frame: no rounding to RGB565 between).
    let (w, h) = (40u32, 32u32);
    let mut normals = [[0i16; 3]; 24];
    let mesh = with_normals(&mut normals);
    let cam = camera(w, h, 2.5, 1);
    let options = RenderOptions {
        shading: Shading::Gouraud,
        ..Default::default()
    };
    let grey = Rgb888::new(90, 90, 90);
    let fog = Fog::new(Lit, 0.0, 1.0, grey).unwrap();
    let (mut lit, mut fogged) = (vec![Rgb888::BLACK; 1280], vec![Rgb888::BLACK; 1280]);
    let (mut d1, mut d2) = (vec![0u16; 1280], vec![0u16; 1280]);
    let mut frame = Frame::new(&mut lit, &mut d1, w, h).unwrap();
    frame.clear(Rgb888::BLACK);
    Renderer::new(&mesh, &cam, options)
        .unwrap()
        .draw(&mut frame)
        .unwrap();
    let mut frame = Frame::new(&mut fogged, &mut d2, w, h).unwrap();
    frame.clear(Rgb888::BLACK);
    Renderer::new(&mesh, &cam, options)
        .unwrap()
        .draw_with_shader(&mut frame, &fog)
        .unwrap();
    assert_eq!(d1, d2);
    let mut n = 0;
    for i in 0..1280 {
        if d1[i] == u16::MAX {
            continue;
        }
        // Near 0, far 65535: R = ⌊2²⁴/65535⌋ = 256.
        let t = if d1[i] == 65535 {
            256
        } else {
            (u32::from(d1[i]) * 256) >> 16
        };
        let mix = |a: u8| ((u32::from(a) * (256 - t) + 90 * t + 128) >> 8) as u8;
        let c = lit[i];
        assert_eq!(
            fogged[i],
            Rgb888::new(mix(c.r()), mix(c.g()), mix(c.b())),
            "pixel {i}"
        );
        n += 1;
    }
    assert!(n > 200, "{n}");
}

#[test]
fn a_texel_shader_draws_what_draw_textured_draws() {
    let (w, h) = (48u32, 40u32);
    let mut normals = [[0i16; 3]; 24];
    let mesh = with_normals(&mut normals);
    let pow2 = Texture::new(&TEXELS, 8, 8).unwrap();
    let odd = Texture::new(&ODD, 3, 5).unwrap();
    for (k, dist) in [4.0f32, 2.5, 1.3].into_iter().enumerate() {
        let cam = camera(w, h, dist, k);
        for shading in [Shading::Flat, Shading::Lambert, Shading::Gouraud] {
            for mode in [UvMode::Perspective, UvMode::Affine] {
                let options = RenderOptions {
                    shading,
                    ..Default::default()
                };
                let what = format!("distance {dist}, {shading:?}, {mode:?}");
                let t = Texturing::new(&UVS, pow2).with_mode(mode);
                let want = frame_of(w, h, |f| {
                    Renderer::new(&mesh, &cam, options)?.draw_textured(f, &t)
                });
                let shader = Textured::from(t);
                let got = frame_of(w, h, |f| {
                    Renderer::new(&mesh, &cam, options)?.draw_with_shader(f, &shader)
                });
                assert!(got == want, "{what}: 8×8");
                // A closure sampling the texture itself, given the UV table.
                let by_hand = WithUvs::new(&UVS, |f: &Fragment| {
                    pow2.lit::<Rgb565>(f.uv, f.light, f.x, f.y)
                })
                .with_mode(mode);
                let got = frame_of(w, h, |f| {
                    Renderer::new(&mesh, &cam, options)?.draw_with_shader(f, &by_hand)
                });
                assert!(got == want, "{what}: 8×8 by a closure");
                let t = Texturing::new(&UVS, odd).with_mode(mode);
                let want = frame_of(w, h, |f| {
                    Renderer::new(&mesh, &cam, options)?.draw_textured(f, &t)
                });
                let got = frame_of(w, h, |f| {
                    Renderer::new(&mesh, &cam, options)?.draw_with_shader(f, &Textured::from(t))
                });
                assert!(got == want, "{what}: 3×5");
            }
        }
    }
}

#[test]
fn every_target_and_band_height_gives_the_whole_frames_picture() {
    let (w, h) = (48u32, 40u32);
    let mut normals = [[0i16; 3]; 24];
    let mesh = with_normals(&mut normals);
    let texture = Texture::new(&TEXELS, 8, 8).unwrap();
    let textured = Fog::new(
        Textured::new(&UVS, texture),
        0.2,
        0.9,
        Rgb888::new(30, 60, 90),
    )
    .unwrap();
    let plain = Fog::new(Lit, 0.1, 0.95, Rgb888::WHITE).unwrap();
    let pattern = |f: &Fragment| pattern(f.x, f.y + i32::from(f.depth >> 12));
    for (k, dist) in [(0, 4.0f32), (2, 1.3)] {
        let cam = camera(w, h, dist, k);
        for shading in [Shading::Flat, Shading::Gouraud] {
            let options = RenderOptions {
                shading,
                ..Default::default()
            };
            check_targets(w, h, &mesh, &cam, options, &textured, "fogged texture");
            check_targets(w, h, &mesh, &cam, options, &plain, "fogged material");
            check_targets(w, h, &mesh, &cam, options, &pattern, "pattern");
        }
    }
}

/// `shader` drawn into a whole frame, band frames, `Bands` and a `WithDepth`: the same
/// pixels, depths and counts.
fn check_targets(
    w: u32,
    h: u32,
    mesh: &Mesh<'_, Rgb888>,
    cam: &Camera,
    options: RenderOptions,
    shader: &impl PixelShader<Rgb565>,
    what: &str,
) {
    let mut whole_stats = None;
    let (whole, whole_depth) = frame_of(w, h, |f| {
        let mut r = Renderer::new(mesh, cam, options)?;
        r.draw_with_shader(f, shader)?;
        whole_stats = Some(r.stats());
        Ok(())
    });
    let whole_stats = whole_stats.unwrap();
    assert!(whole_stats.pixels_written > 200, "{what}: {whole_stats:?}");
    for rows in [1u32, 7, 16] {
        let mut px = vec![Rgb565::BLACK; (w * h) as usize];
        let mut depth = vec![0u16; (w * h) as usize];
        let mut r = Renderer::new(mesh, cam, options).unwrap();
        for y0 in (0..h).step_by(rows as usize) {
            let n = rows.min(h - y0);
            let range = (y0 * w) as usize..((y0 + n) * w) as usize;
            let color = ColorBuffer::new_band(&mut px[range.clone()], w, n, y0 as i32).unwrap();
            let mut zb = ZBuffer::new_band(&mut depth[range], w, n, y0 as i32).unwrap();
            zb.clear();
            r.draw_with_shader(&mut Frame::from_buffers(color, zb), shader)
                .unwrap();
        }
        assert!(px == whole, "{what}: band frames of {rows} rows");
        assert!(depth == whole_depth, "{what}: band depths of {rows} rows");
        assert_eq!(r.stats(), whole_stats, "{what}: band frames of {rows} rows");
        let mut canvas = Canvas {
            w,
            px: vec![Rgb565::BLACK; (w * h) as usize],
        };
        let (mut bc, mut bd) = (
            vec![Rgb565::BLACK; (w * rows) as usize],
            vec![0u16; (w * rows) as usize],
        );
        let mut buffers = BandBuffers::new(&mut bc, &mut bd, w, rows, h, &mut []).unwrap();
        let mut r = Renderer::new(mesh, cam, options).unwrap();
        r.draw_with_shader(
            &mut Bands::new(&mut canvas, &mut buffers, Rgb565::BLACK),
            shader,
        )
        .unwrap();
        assert!(canvas.px == whole, "{what}: Bands of {rows} rows");
        assert_eq!(
            r.stats().pixels_written,
            whole_stats.pixels_written,
            "{what}"
        );
    }
    let mut canvas = Canvas {
        w,
        px: vec![Rgb565::BLACK; (w * h) as usize],
    };
    let mut depth = vec![0u16; (w * h) as usize];
    let mut zb = ZBuffer::new(&mut depth, w, h).unwrap();
    zb.clear();
    let mut r = Renderer::new(mesh, cam, options).unwrap();
    r.draw_with_shader(&mut WithDepth::new(&mut canvas, &mut zb), shader)
        .unwrap();
    assert!(canvas.px == whole, "{what}: WithDepth");
    assert!(depth == whole_depth, "{what}: WithDepth depths");
    assert_eq!(
        r.stats().pixels_written,
        whole_stats.pixels_written,
        "{what}"
    );
}

#[test]
fn bad_input_is_an_error_never_a_panic() {
    let base = |_: &Fragment| Rgb888::RED;
    let bad = |near: f32, far: f32| Fog::new(base, near, far, Rgb888::WHITE).err().unwrap();
    assert_eq!(bad(f32::NAN, 0.5), Error::NotFinite);
    assert_eq!(bad(0.1, f32::NAN), Error::NotFinite);
    assert_eq!(bad(0.1, f32::INFINITY), Error::NotFinite);
    assert!(matches!(bad(0.5, 0.5), Error::InvalidParameter(_)));
    assert!(matches!(bad(0.6, 0.5), Error::InvalidParameter(_)));
    assert!(matches!(bad(-0.1, 0.5), Error::InvalidParameter(_)));
    assert!(matches!(bad(0.1, 1.5), Error::InvalidParameter(_)));
    // Closer than one depth step apart: the same depth once rounded.
    assert!(matches!(bad(0.5, 0.500001), Error::InvalidParameter(_)));
    assert!(Fog::from_depths(base, 7, 7, Rgb888::WHITE).is_err());
    assert!(Fog::from_depths(base, 0, 1, Rgb888::WHITE).is_ok());

    // A UV table shorter than the vertex table.
    let mut normals = [[0i16; 3]; 24];
    let mesh = with_normals(&mut normals);
    let cam = camera(32, 32, 2.5, 0);
    let (mut px, mut depth) = (vec![Rgb565::BLACK; 1024], vec![0u16; 1024]);
    let mut frame = Frame::new(&mut px, &mut depth, 32, 32).unwrap();
    let short = WithUvs::new(&UVS[..23], |_: &Fragment| Rgb565::RED);
    let err = Renderer::new(&mesh, &cam, RenderOptions::default())
        .unwrap()
        .draw_with_shader(&mut frame, &short)
        .unwrap_err();
    assert_eq!(
        err,
        DrawError::Input(Error::InvalidParameter(
            "fewer texture coordinates than vertices"
        ))
    );
    // Wild coordinates, clipped by the near plane, a shader reading every attribute:
    // drawn, no panic (debug builds check every overflow).
    let wild: [MeshUv; 24] = core::array::from_fn(|i| {
        if i % 2 == 0 {
            [i16::MIN, i16::MAX]
        } else {
            [i16::MAX, i16::MIN]
        }
    });
    for mode in [UvMode::Perspective, UvMode::Affine] {
        let all = WithUvs::new(&wild, |f: &Fragment| {
            Rgb565::new(
                (f.uv.u >> 20) as u8 & 31,
                (f.uv.v >> 20) as u8 & 63,
                (f.depth >> 11) as u8 ^ (f.light >> 11) as u8,
            )
        })
        .with_mode(mode);
        let cam = camera(32, 32, 1.1, 2);
        frame_of(32, 32, |f| {
            Renderer::new(&mesh, &cam, RenderOptions::default())?.draw_with_shader(f, &all)
        });
    }
}

/// The textured draw's fast loop (default depth test, one light a face, a repeating
/// power-of-two texture) where pixels fail the depth test: the cube drawn without
/// culling (its back faces behind its front ones, in every order), over a large cube
/// drawn first that hides part of it, on a 96-pixel-wide frame (rows of many whole
/// segments). The texel shader, which takes the general loop, is the reference.
#[test]
fn the_fast_textured_loop_agrees_with_the_shader_where_pixels_fail_the_depth_test() {
    let (w, h) = (96u32, 64u32);
    let mut normals = [[0i16; 3]; 24];
    let mesh = with_normals(&mut normals);
    let wall = Mesh::triangles(&POSITIONS, 1.0 / 16384.0 * 1.1, &INDICES, Rgb888::CSS_TEAL);
    let texture = Texture::new(&TEXELS, 8, 8).unwrap();
    for (k, dist) in [3.0f32, 2.2].into_iter().enumerate() {
        let cam = camera(w, h, dist, k + 3);
        // The wall: the big cube moved half a unit right and back.
        let wall_cam = cam.with_model(Mat4::translation(Vec3::new(0.6, 0.0, -0.9)));
        for shading in [Shading::Flat, Shading::Lambert] {
            for mode in [UvMode::Perspective, UvMode::Affine] {
                let options = RenderOptions {
                    shading,
                    cull: zraster::Cull::None,
                    ..Default::default()
                };
                let what = format!("distance {dist}, {shading:?}, {mode:?}");
                let t = Texturing::new(&UVS, texture).with_mode(mode);
                let mut stats = Vec::new();
                let mut draw = |textured: bool| {
                    frame_of(w, h, |f| {
                        Renderer::new(&wall, &wall_cam, RenderOptions::default())?.draw(f)?;
                        let mut r = Renderer::new(&mesh, &cam, options)?;
                        if textured {
                            r.draw_textured(f, &t)?;
                        } else {
                            r.draw_with_shader(f, &Textured::from(t))?;
                        }
                        stats.push(r.stats());
                        Ok(())
                    })
                };
                let (fast, general) = (draw(true), draw(false));
                assert!(fast == general, "{what}");
                assert_eq!(stats[0], stats[1], "{what}");
                let s = stats[0];
                assert!(s.pixels_written > 500, "{what}: {s:?}");
                assert!(s.pixels_tested > s.pixels_written + 300, "{what}: {s:?}");
            }
        }
    }
}
