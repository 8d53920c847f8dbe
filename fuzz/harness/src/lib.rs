//! Fuzz harnesses: arbitrary bytes into zraster's public API. Shared by the cargo-fuzz
//! targets (`fuzz/fuzz_targets/`) and by `tests/fuzz_corpus.rs`, which replays the
//! committed corpus in `cargo test` so CI checks the regressions on stable Rust. An
//! internal crate (`publish = false`), so that both use it as a dependency.
//!
//! Every harness asserts what must hold whatever the input: no panic, nothing drawn
//! outside the target (`MockDisplay` panics on that), and the invariants noted below.

use embedded_graphics::{
    mock_display::MockDisplay,
    pixelcolor::{BinaryColor, Rgb565, Rgb888},
    prelude::*,
};
use zraster::{
    camera::{Camera, Transform, Viewport},
    math::{radians, Mat4, Vec3},
    mesh::{Face, Faces, Materials, Mesh},
    shade::{Light, Shading},
    BandBuffers, Bands, CachedVertex, ColorBuffer, Cull, DepthSort, DepthTest, Error, Frame,
    FrameStats, RenderOptions, Renderer, ScreenVertex, WithDepth, ZBuffer,
};

/// Reads numbers off the input, yielding zeros once it runs out.
pub struct Bytes<'a>(pub &'a [u8]);

impl Bytes<'_> {
    pub fn u8(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }
    pub fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.u8(), self.u8()])
    }
    pub fn u32(&mut self) -> u32 {
        u32::from_le_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }
    pub fn i32(&mut self) -> i32 {
        self.u32() as i32
    }
    /// Any f32 bit pattern: NaN, ±∞, subnormals included.
    pub fn f32(&mut self) -> f32 {
        f32::from_bits(self.u32())
    }
    /// Mostly ordinary floats, sometimes raw bits.
    pub fn float(&mut self) -> f32 {
        match self.u8() % 8 {
            0 => self.f32(),
            _ => f32::from(self.u16() as i16) / 64.0,
        }
    }
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

fn test_of(b: u8) -> DepthTest {
    [
        DepthTest::Less,
        DepthTest::LessEqual,
        DepthTest::Greater,
        DepthTest::Equal,
        DepthTest::Always,
        DepthTest::Never,
    ][usize::from(b % 6)]
}

/// Screen-space triangles into a Z-buffer band and a 64×64 mock display.
pub fn raster(data: &[u8]) {
    let mut r = Bytes(data);
    let width = u32::from(r.u8() % 70);
    let rows = u32::from(r.u8() % 70);
    let first_row = i32::from(r.u8() as i8);
    let test = test_of(r.u8());
    let write = r.u8() & 1 == 0;
    let mut depth = vec![0u16; usize::from(r.u16() % 5000)];
    let mut zbuf = match ZBuffer::new_band(&mut depth, width, rows, first_row) {
        Ok(z) => z,
        Err(_) => {
            // Rejected sizes must be the ones that are wrong.
            assert!(width == 0 || rows == 0 || (width * rows) as usize > depth.len());
            return;
        }
    };
    zbuf.clear();
    zbuf.set_test(test);
    zbuf.set_write(write);
    let mut display = MockDisplay::<Rgb565>::new();
    display.set_allow_overdraw(true);
    display.set_allow_out_of_bounds_drawing(false);
    while !r.is_empty() {
        let kind = r.u8();
        let v = |r: &mut Bytes| match kind % 3 {
            0 => ScreenVertex::new(r.i32() % (1 << 25), r.i32() % (1 << 25), r.u32()),
            1 => ScreenVertex::from_f32(r.f32(), r.f32(), r.f32()),
            _ => {
                ScreenVertex::from_pixels(i32::from(r.u8() as i8), i32::from(r.u8() as i8), r.u16())
            }
        };
        let (a, b, c) = (v(&mut r), v(&mut r), v(&mut r));
        let (Ok(a), Ok(b), Ok(c)) = (a, b, c) else {
            continue;
        };
        let before: Vec<u16> = zbuf.as_slice().to_vec();
        let color = Rgb565::new(r.u8() & 31, r.u8() & 63, r.u8() & 31);
        let stats = if kind & 0x80 == 0 {
            zraster::fill_triangle(&mut display, &mut zbuf, &[a, b, c], color).unwrap()
        } else {
            let i = [r.u16(), r.u16(), r.u16()];
            zraster::fill_triangle_shaded(
                &mut display,
                &mut zbuf,
                &[a, b, c],
                Rgb888::new(200, 100, 50),
                i,
            )
            .unwrap()
        };
        assert!(stats.pixels_written <= stats.pixels_tested);
        // With the Less test, stored depths only ever come nearer.
        if test == DepthTest::Less {
            assert!(zbuf.as_slice().iter().zip(&before).all(|(n, o)| n <= o));
        }
        if !write {
            assert_eq!(zbuf.as_slice(), &before[..]);
        }
    }
}

/// Build a mesh, a transform and options from the bytes and draw them every way.
pub fn pipeline(data: &[u8]) {
    let mut r = Bytes(data);
    let nv = usize::from(r.u8() % 40);
    let positions: Vec<[i16; 3]> = (0..nv)
        .map(|_| [r.u16() as i16, r.u16() as i16, r.u16() as i16])
        .collect();
    let nf = usize::from(r.u8() % 40);
    let mut index_store: Vec<Vec<u16>> = Vec::new();
    for _ in 0..nf {
        let n = usize::from(r.u8() % 6);
        // Indices mostly in range, sometimes not.
        index_store.push((0..n).map(|_| r.u16() % (nv as u16 + 2).max(1)).collect());
    }
    let faces: Vec<Face<'_, Rgb888>> = index_store
        .iter()
        .map(|v| Face {
            vertices: v,
            material: Rgb888::new(r.u8(), r.u8(), r.u8()),
        })
        .collect();
    let scale = if r.u8() % 4 == 0 {
        r.f32()
    } else {
        1.0 / 4096.0
    };
    let mesh = Mesh::new(&positions, scale, &faces);
    let w = u32::from(r.u8() % 64);
    let h = u32::from(r.u8() % 64);
    let Ok(vp) = Viewport::new(w, h) else { return };
    let eye = Vec3::new(r.float(), r.float(), r.float());
    let target = Vec3::new(r.float(), r.float(), r.float());
    let (fov, near, far) = (r.float(), r.float(), r.float());
    let Ok(mut xf) = Camera::look_at(eye, target, Vec3::Y)
        .and_then(|look| look.perspective(radians(fov), near, far, vp))
    else {
        return;
    };
    if r.u8() % 3 == 0 {
        let mut m = Mat4::IDENTITY;
        for row in m.m.iter_mut() {
            for v in row.iter_mut() {
                *v = r.float();
            }
        }
        xf.model = m;
    }
    let options = RenderOptions {
        cull: [Cull::Back, Cull::Front, Cull::None][usize::from(r.u8() % 3)],
        shading: [Shading::Flat, Shading::Lambert, Shading::Gouraud][usize::from(r.u8() % 3)],
        light: Light {
            direction: Vec3::new(r.float(), r.float(), r.float()),
            ambient: r.float(),
            diffuse: r.float(),
        },
    };
    let mode = r.u8();
    let band = u32::from(r.u8() % 16) + 1;
    let n = (w * h) as usize;
    let mut display = MockDisplay::<Rgb565>::new();
    display.set_allow_overdraw(true);
    let mut depth = vec![0u16; n];
    let Ok(mut zbuf) = ZBuffer::new(&mut depth, w, h) else {
        return;
    };
    zbuf.clear();
    let mut cache = vec![CachedVertex::EMPTY; nv];
    let renderer = if mode & 0x10 == 0 {
        Renderer::new(&mesh, &xf, options)
    } else {
        Renderer::with_cache(&mesh, &xf, options, &mut cache)
    };
    let Ok(mut renderer) = renderer else { return };
    let _ = match mode % 6 {
        0 => renderer.draw(&mut WithDepth::new(&mut display, &mut zbuf)),
        1 => renderer.draw_hidden_line(&mut display, &mut zbuf, Rgb565::WHITE),
        2 => renderer.draw_wireframe(&mut display, Rgb565::WHITE),
        3 => {
            let mut sort = DepthSort::<16>::new();
            renderer.draw_depth_sorted(&mut display, &mut sort)
        }
        4 => {
            let mut pixels = vec![Rgb565::BLACK; n];
            let Ok(frame) = ColorBuffer::new(&mut pixels, w, h) else {
                return;
            };
            let _ = renderer.draw(&mut Frame::from_buffers(frame, zbuf));
            Ok(())
        }
        _ => {
            let rows = band.min(h);
            let mut c = vec![Rgb565::BLACK; (w * rows) as usize];
            let mut z = vec![0u16; (w * rows) as usize];
            let mut bins = vec![0u16; BandBuffers::<Rgb565>::bins_needed(nf * 4, h, rows)];
            let Ok(mut bands) = BandBuffers::new(&mut c, &mut z, w, rows, h, &mut bins) else {
                return;
            };
            renderer.draw(&mut Bands::new(&mut display, &mut bands, Rgb565::BLACK))
        }
    };
    let s = renderer.stats();
    assert!(s.culled + s.outside <= s.triangles_in + s.clipped * 8);
}

/// Read the bytes as an OBJ file; when they parse, draw the model on a 48×32 mono
/// screen.
pub fn obj(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let Ok(model) =
        zraster_obj::parse_obj(&text, |_| Some(String::from_utf8_lossy(data).into_owned()))
    else {
        return;
    };
    assert!(model.triangles.iter().all(|t| t
        .vertices
        .iter()
        .all(|&v| (v as usize) < model.positions.len())));
    if model.triangles.is_empty() || model.triangles.len() > 2000 {
        return;
    }
    let q = zraster_obj::quantize(&model.positions, true);
    let indices = model.triangle_indices();
    let mesh = Mesh::triangles(&q.positions, q.scale, &indices, Rgb888::WHITE);
    let Ok(vp) = Viewport::new(48, 32) else {
        return;
    };
    let Ok(xf) = Camera::look_at(
        Vec3::new(0.0, 0.0, 2.0 * q.scale * 32767.0 + 0.5),
        Vec3::default(),
        Vec3::Y,
    )
    .and_then(|look| look.perspective(radians(60.0), 0.01, 1e4, vp)) else {
        return;
    };
    let mut display = MockDisplay::<BinaryColor>::new();
    display.set_allow_overdraw(true);
    let mut depth = vec![0u16; 48 * 32];
    let Ok(mut zbuf) = ZBuffer::new(&mut depth, 48, 32) else {
        return;
    };
    zbuf.clear();
    if let Ok(mut r) = Renderer::new(
        &mesh,
        &xf,
        RenderOptions {
            shading: Shading::Lambert,
            ..Default::default()
        },
    ) {
        let _ = r.draw(&mut WithDepth::new(&mut display, &mut zbuf));
    }
}

/// One frame: its colours, its depths and the renderer's stats.
type Pictures = (Vec<Rgb565>, Vec<u16>, FrameStats);

/// The whole frame, drawn at once with the fused buffer path (as `tests/bands.rs`).
fn whole_frame(
    mesh: &Mesh<'_, Rgb888>,
    xf: &Transform,
    opts: RenderOptions,
    (w, h): (u32, u32),
) -> Result<Pictures, Error> {
    let mut colour = vec![Rgb565::BLACK; (w * h) as usize];
    let mut depth = vec![0u16; (w * h) as usize];
    let mut cache = vec![CachedVertex::EMPTY; mesh.positions.len()];
    let stats = {
        let mut frame = Frame::new(&mut colour, &mut depth, w, h)?;
        frame.clear(Rgb565::BLACK);
        let mut r = Renderer::with_cache(mesh, xf, opts, &mut cache)?;
        r.draw(&mut frame)?;
        r.stats()
    };
    Ok((colour, depth, stats))
}

/// The same frame band by band, `rows` lines at a time, with `bins` bin entries
/// (initially `junk`); the depth is collected from each band as it is finished.
fn banded_frame(
    mesh: &Mesh<'_, Rgb888>,
    xf: &Transform,
    opts: RenderOptions,
    (w, h, rows): (u32, u32, u32),
    (bins, junk): (usize, u16),
) -> Result<Pictures, Error> {
    let mut colour = vec![Rgb565::BLUE; (w * h) as usize];
    let mut depth = vec![7u16; (w * h) as usize];
    let mut cb = vec![Rgb565::BLACK; (w * rows) as usize];
    let mut zb = vec![0u16; (w * rows) as usize];
    let mut bins = vec![junk; bins];
    let mut cache = vec![CachedVertex::EMPTY; mesh.positions.len()];
    let stats = {
        let mut display = ColorBuffer::new(&mut colour, w, h)?;
        let mut bands = BandBuffers::new(&mut cb, &mut zb, w, rows, h, &mut bins)?;
        let mut r = Renderer::with_cache(mesh, xf, opts, &mut cache)?;
        let mut target =
            Bands::new(&mut display, &mut bands, Rgb565::BLACK).after_band(|band, z| {
                let y0 = band.first_row();
                assert_eq!((z.first_row(), z.rows()), (y0, band.rows()));
                for y in y0..y0 + band.rows() as i32 {
                    for x in 0..w as i32 {
                        depth[(y as u32 * w + x as u32) as usize] = z.depth(x, y).unwrap();
                    }
                }
            });
        r.draw(&mut target)?;
        r.stats()
    };
    Ok((colour, depth, stats))
}

/// A random triangle mesh with coplanar duplicates (triangles repeated, quads split
/// again along the other diagonal, each copy in another colour), a random view,
/// options, band height and bins: drawn band by band it is byte-identical to the
/// whole frame in colour, depth and stats.
pub fn bands(data: &[u8]) {
    bands_stats(data);
}

/// [`bands`], returning the frame's stats when it was drawn.
pub fn bands_stats(data: &[u8]) -> Option<FrameStats> {
    let mut r = Bytes(data);
    let w = u32::from(r.u8() % 48) + 1;
    let h = u32::from(r.u8() % 48) + 1;
    let rows = u32::from(r.u8()) % h + 1;
    let flags = r.u8();
    let cull = [Cull::None, Cull::Back, Cull::Front][usize::from(flags % 3)];
    // Flat and Lambert take the binned path; Gouraud (rarely) the per-band general one.
    let shading = match (flags / 3) % 8 {
        0..=3 => Shading::Flat,
        4..=6 => Shading::Lambert,
        _ => Shading::Gouraud,
    };
    // Bins: none, exactly enough, one short (so not used), or more than enough; the
    // slice starts out holding junk.
    let bin_mode = (flags >> 5) & 3;
    let junk = r.u16();
    let light = if flags & 0x80 != 0 {
        Light {
            direction: Vec3::new(r.float(), r.float(), r.float()),
            ambient: r.float(),
            diffuse: r.float(),
        }
    } else {
        Light::default()
    };
    let opts = RenderOptions {
        cull,
        shading,
        light,
    };

    // The camera.
    let vp = Viewport::new(w, h).ok()?;
    let view = r.u8();
    let xf = if view % 4 == 2 {
        let eye = Vec3::new(r.float(), r.float(), r.float());
        let target = Vec3::new(r.float(), r.float(), r.float());
        let (fov, near, far) = (r.float(), r.float(), r.float());
        Camera::look_at(eye, target, Vec3::Y)
            .and_then(|look| look.perspective(radians(fov), near, far, vp))
    } else {
        // As tests/bands.rs: orbiting the origin.
        let yaw = f32::from(r.u8()) * (360.0 / 256.0) - 180.0;
        let pitch = f32::from(r.u8() as i8) * (85.0 / 128.0);
        let distance = 0.2 + f32::from(r.u8()) / 50.0;
        let fov = 20.0 + f32::from(r.u8() % 128);
        Camera::look_at(Vec3::new(0.0, 0.0, distance), Vec3::default(), Vec3::Y)
            .and_then(|look| look.perspective(radians(fov), 0.1, 10.0, vp))
            .map(|xf| {
                xf.with_model(Mat4::rotation_x(radians(pitch)) * Mat4::rotation_y(radians(yaw)))
            })
    };
    let mut xf = xf.ok()?;
    if view % 4 == 3 {
        // Any model matrix at all.
        for row in xf.model.m.iter_mut() {
            for v in row.iter_mut() {
                *v = r.float();
            }
        }
    }

    // The mesh: positions in ±2¹⁵ >> shift, times the scale.
    let shape = r.u8();
    let shift = shape % 8;
    let scale = match shape >> 3 {
        0 => r.f32(),
        1..=3 => 1.0 / 4096.0,
        4..=15 => 1.0 / 1024.0,
        _ => 1.0 / f32::from(r.u8().max(1)) / 64.0,
    };
    let mut positions: Vec<[i16; 3]> = Vec::new();
    let mut indices: Vec<[u16; 3]> = Vec::new();
    let mut colours: Vec<Rgb888> = Vec::new();
    // Parallelograms a b c d, for splitting again.
    let mut quads: Vec<[u16; 4]> = Vec::new();
    let vertex = |r: &mut Bytes, positions: &mut Vec<[i16; 3]>| {
        let mut c = || (r.u16() as i16) >> shift;
        positions.push([c(), c(), c()]);
        (positions.len() - 1) as u16
    };
    let colour = |r: &mut Bytes| Rgb888::new(r.u8(), r.u8(), r.u8());
    while !r.is_empty() && indices.len() < 300 && positions.len() < 600 {
        let op = r.u8();
        match op % 8 {
            0..=2 => {
                let t = [0; 3].map(|_| vertex(&mut r, &mut positions));
                indices.push(t);
                colours.push(colour(&mut r));
            }
            3 | 4 => {
                // A parallelogram (planar exactly, unless d is clamped), split a–c.
                let [a, b, c] = [0; 3].map(|_| vertex(&mut r, &mut positions));
                let [pa, pb, pc] = [a, b, c].map(|i| positions[usize::from(i)]);
                let d = [0, 1, 2].map(|k| {
                    (i32::from(pa[k]) + i32::from(pc[k]) - i32::from(pb[k]))
                        .clamp(i32::from(i16::MIN), i32::from(i16::MAX)) as i16
                });
                positions.push(d);
                let d = (positions.len() - 1) as u16;
                let col = colour(&mut r);
                indices.extend([[a, b, c], [a, c, d]]);
                colours.extend([col, col]);
                quads.push([a, b, c, d]);
            }
            5 if !indices.is_empty() => {
                // An earlier triangle again, perhaps starting at another vertex.
                let [a, b, c] = indices[usize::from(r.u8()) % indices.len()];
                let t = [[a, b, c], [b, c, a], [c, a, b]][usize::from(op >> 3) % 3];
                indices.push(t);
                colours.push(colour(&mut r));
            }
            6 if !quads.is_empty() => {
                // An earlier quad again, split along the other diagonal (b–d).
                let [a, b, c, d] = quads[usize::from(r.u8()) % quads.len()];
                let col = colour(&mut r);
                indices.extend([[a, b, d], [b, c, d]]);
                colours.extend([col, col]);
            }
            7 if !positions.is_empty() => {
                // A triangle of existing vertices (shared edges, slivers, degenerates).
                let n = positions.len();
                let t = [0; 3].map(|_| (usize::from(r.u16()) % n) as u16);
                indices.push(t);
                colours.push(colour(&mut r));
            }
            _ => {}
        }
    }
    let mesh = Mesh {
        positions: &positions,
        scale,
        faces: Faces::Triangles {
            indices: &indices,
            materials: Materials::PerFace(&colours),
        },
        face_normals: None,
        vertex_normals: None,
    };
    let needed = BandBuffers::<Rgb565>::bins_needed(indices.len(), h, rows);
    let bins = match bin_mode {
        0 => 0,
        1 => needed,
        2 => needed - 1,
        _ => needed + 5,
    };
    let want = whole_frame(&mesh, &xf, opts, (w, h));
    let got = banded_frame(&mesh, &xf, opts, (w, h, rows), (bins, junk));
    let what = format!(
        "{w}×{h} rows {rows} bins {bins}/{needed} {cull:?} {shading:?}, {} faces",
        indices.len()
    );
    let (want, got) = match (want, got) {
        (Ok(want), Ok(got)) => (want, got),
        (Err(_), Err(_)) => return None,
        (want, got) => panic!(
            "{what}: whole frame {:?}, bands {:?}",
            want.map(|f| f.2),
            got.map(|f| f.2)
        ),
    };
    fn differ<T: PartialEq>(x: &[T], y: &[T]) -> (usize, Option<usize>) {
        let n = x.iter().zip(y).filter(|(p, q)| p != q).count();
        (n, x.iter().zip(y).position(|(p, q)| p != q))
    }
    let at = |i: Option<usize>| i.map(|i| (i as u32 % w, i as u32 / w));
    let (n, i) = differ(&got.0, &want.0);
    assert_eq!(
        n,
        0,
        "{what}: {n} pixels of colour differ, first at {:?}",
        at(i)
    );
    let (n, i) = differ(&got.1, &want.1);
    assert_eq!(n, 0, "{what}: {n} depths differ, first at {:?}", at(i));
    assert_eq!(got.2, want.2, "{what}: stats differ");
    Some(want.2)
}
