//! Textures: construction, sampling against `⌊u·W⌋ mod W`, light, and the span
//! interpolators against an exact reference.

use std::vec::Vec;

use super::*;
use crate::shade::{Material, ONE};
use embedded_graphics::pixelcolor::{Bgr888, BinaryColor, Gray4, Gray8, Rgb565, Rgb888};

/// A xorshift generator: the same spans on every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// Uniform in `lo..=hi`.
    fn range(&mut self, lo: i64, hi: i64) -> i64 {
        lo + (self.next() % (hi - lo + 1) as u64) as i64
    }
}

#[test]
fn bad_sizes_are_errors() {
    let t = [0u16; 12];
    assert_eq!(Texture::new(&t, 0, 3).unwrap_err(), Error::ZeroSize);
    assert_eq!(Texture::new(&t, 3, 0).unwrap_err(), Error::ZeroSize);
    assert_eq!(Texture::new(&t, 8193, 1).unwrap_err(), Error::TooLarge);
    assert_eq!(Texture::new(&t, 1, u32::MAX).unwrap_err(), Error::TooLarge);
    assert_eq!(
        Texture::new(&t, 4, 4).unwrap_err(),
        Error::BufferTooSmall {
            needed: 16,
            got: 12
        }
    );
    assert_eq!(
        Texture::new(&[] as &[u16], 1, 1).unwrap_err(),
        Error::BufferTooSmall { needed: 1, got: 0 }
    );
    // A longer slice: the first width × height texels.
    let tex = Texture::new(&t, 5, 2).unwrap();
    assert_eq!(tex.texels().len(), 10);
    assert_eq!(
        (tex.width(), tex.height(), tex.wrap()),
        (5, 2, Wrap::Repeat)
    );
    assert_eq!(tex.texel(4, 1), Some(0));
    assert_eq!(tex.texel(5, 0), None);
    assert_eq!(tex.texel(0, 2), None);
}

/// A texture in flash: a `const` table and a `const` texture over it, no copy.
#[test]
fn a_const_texture_over_a_const_table() {
    const TEXELS: [u16; 6] = [0xF800, 0x07E0, 0x001F, 0xFFFF, 0x0000, 0x8410];
    const TEX: Texture<'static, u16> = match Texture::new(&TEXELS, 3, 2) {
        Ok(t) => t,
        Err(_) => panic!("bad texture"),
    };
    assert!(core::ptr::eq(TEX.texels(), &TEXELS[..]));
    assert_eq!(TEX.sample(TexCoord::new(0, 0)), Rgb565::new(31, 0, 0));
    assert_eq!(
        TEX.sample(TexCoord::new(UV_ONE / 2, 0)),
        Rgb565::new(0, 63, 0)
    );
    assert_eq!(
        TEX.sample(TexCoord::new(UV_ONE - 1, UV_ONE - 1)),
        Rgb565::new(16, 32, 16)
    );
    assert_eq!(Texel::color(0xFFFFu16), Rgb565::new(31, 63, 31));
}

/// The contract: column ⌊u·W⌋ mod W (repeat) or ⌊clamp(u, 0, 1 − 2⁻¹⁶)·W⌋ (clamp),
/// rows alike, for power-of-two sizes (shifts) and others (multiplies), at every
/// kind of coordinate: in range, negative, several textures out, at ±UV_LIMIT.
#[test]
fn sampling_is_floor_u_times_size_wrapped() {
    let table: Vec<u32> = (0..64 * 64).collect();
    let sizes = [
        (1, 1),
        (1, 7),
        (2, 2),
        (3, 5),
        (8, 4),
        (16, 16),
        (64, 1),
        (7, 64),
    ];
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut coords: Vec<i32> = [
        0,
        1,
        -1,
        UV_ONE - 1,
        UV_ONE,
        -UV_ONE,
        UV_ONE / 3,
        UV_LIMIT,
        -UV_LIMIT,
        i32::MAX,
        i32::MIN,
    ]
    .to_vec();
    coords.extend((0..300).map(|_| rng.range(-4 * 65536, 4 * 65536) as i32));
    for (w, h) in sizes {
        let cells: Vec<Gray8> = table
            .iter()
            .take((w * h) as usize)
            .map(|&i| Gray8::new(i as u8))
            .collect();
        let repeat = Texture::new(&cells, w, h).unwrap();
        let clamp = repeat.with_wrap(Wrap::Clamp);
        let cell = |c: i32, n: u32| (i64::from(c) * i64::from(n)).div_euclid(65536);
        for (k, &u) in coords.iter().enumerate() {
            let v = coords[(k * 7 + 3) % coords.len()];
            let uv = TexCoord::new(u, v);
            let (x, y) = (
                cell(u, w).rem_euclid(i64::from(w)),
                cell(v, h).rem_euclid(i64::from(h)),
            );
            assert_eq!(
                repeat.index(uv),
                (y * i64::from(w) + x) as usize,
                "{w}x{h} {uv:?}"
            );
            let (x, y) = (cell(u.clamp(0, 65535), w), cell(v.clamp(0, 65535), h));
            assert_eq!(
                clamp.index(uv),
                (y * i64::from(w) + x) as usize,
                "{w}x{h} {uv:?}"
            );
            assert_eq!(clamp.sample(uv), cells[clamp.index(uv)]);
        }
    }
    // Extreme coordinates on a 1×1 texture.
    let texels = [Gray8::new(0); 1];
    let t = Texture::new(&texels, 1, 1).unwrap();
    assert_eq!(t.index(TexCoord::new(i32::MAX, i32::MIN)), 0);
}

/// Mesh coordinates (Q12) widen to Q16 exactly; v down.
#[test]
fn mesh_coordinates_widen() {
    assert_eq!(
        TexCoord::from_mesh([MESH_UV_ONE, 0]),
        TexCoord::new(UV_ONE, 0)
    );
    assert_eq!(
        TexCoord::from_mesh([-32768, 32767]),
        TexCoord::new(-8 * UV_ONE, 8 * UV_ONE - 16)
    );
}

/// A texel is lit exactly as a flat face of its colour is, on every kind of display;
/// at full light an RGB565 texel on an RGB565 display is itself (all 65536 of them).
#[test]
fn texels_are_lit_as_flat_colours() {
    for raw in 0..=u16::MAX {
        let t = Texel::color(raw);
        let lit: Rgb565 = modulate(t, ONE, 0, 0);
        assert_eq!(lit, t, "{raw:#06x}");
    }
    let texels = [
        Rgb565::new(20, 40, 10),
        Rgb565::new(31, 0, 17),
        Rgb565::new(1, 63, 30),
    ];
    let tex = Texture::new(&texels, 3, 1).unwrap();
    for (k, &t) in texels.iter().enumerate() {
        let uv = TexCoord::new(k as i32 * UV_ONE / 3 + 5, 0);
        let flat = Rgb888::from(t);
        for i in [
            0,
            1,
            ONE / 3,
            ONE / 2,
            ONE - 1,
            ONE,
            ONE + ONE / 2,
            u16::MAX,
        ] {
            for (x, y) in [(0, 0), (1, 2), (3, 3), (-5, 7)] {
                let want: Gray4 = flat.shade(i, x, y);
                assert_eq!(tex.lit::<Gray4>(uv, i, x, y), want);
                let want: BinaryColor = flat.shade(i, x, y);
                assert_eq!(tex.lit::<BinaryColor>(uv, i, x, y), want);
                let want: Rgb565 = flat.shade(i, x, y);
                assert_eq!(tex.lit::<Rgb565>(uv, i, x, y), want);
                let want: Bgr888 = flat.shade(i, x, y);
                assert_eq!(tex.lit::<Bgr888>(uv, i, x, y), want);
            }
        }
    }
    // Grey and 1-bit textures light alike (through their Rgb888).
    let g = [Gray8::new(200)];
    let t = Texture::new(&g, 1, 1).unwrap();
    let want: Rgb565 = Rgb888::new(200, 200, 200).shade(ONE / 2, 0, 0);
    assert_eq!(t.lit::<Rgb565>(TexCoord::default(), ONE / 2, 0, 0), want);
}

/// ⌊n / d⌋ for d > 0, exactly.
fn floor_div(n: i128, d: i128) -> i128 {
    n.div_euclid(d)
}

/// A span's pixels against the exact quotient: equal at the subdivision points and the
/// last pixel, within the stated bound in between. Returns the largest error seen
/// between subdivision points, in Q16.
fn check_span<const SEGMENT: u32>(start: Homogeneous, step: Homogeneous, n: u32) -> f64 {
    let got: Vec<TexCoord> = PerspectiveSpan::<SEGMENT>::new(start, step, n)
        .unwrap()
        .collect();
    assert_eq!(got.len(), n as usize);
    let point = |j: u32| {
        let j = i128::from(j);
        (
            i128::from(start.uq) + j * i128::from(step.uq),
            i128::from(start.vq) + j * i128::from(step.vq),
            i128::from(start.q) + j * i128::from(step.q),
        )
    };
    let exact = |j: u32| {
        let (s, t, q) = point(j);
        (s as f64 / q as f64, t as f64 / q as f64)
    };
    let mut worst = 0.0f64;
    let last = n - 1;
    let mut a = 0;
    loop {
        let b = (a + SEGMENT).min(last);
        for e in [a, b] {
            let (s, t, q) = point(e);
            let lim = i128::from(UV_LIMIT);
            let want = TexCoord::new(
                floor_div(s, q).clamp(-lim, lim) as i32,
                floor_div(t, q).clamp(-lim, lim) as i32,
            );
            assert_eq!(
                got[e as usize], want,
                "pixel {e} of {n}: {start:?} {step:?}"
            );
        }
        let (qa, qb) = (point(a).2 as f64, point(b).2 as f64);
        let ((ua, va), (ub, vb)) = (exact(a), exact(b));
        let bow = |d: f64| 0.25 * d.abs() * (qb - qa).abs() / qa.min(qb);
        let (bu, bv) = (bow(ub - ua) + 3.0, bow(vb - va) + 3.0);
        for j in a..=b {
            let (u, v) = exact(j);
            let (eu, ev) = (
                (f64::from(got[j as usize].u) - u).abs(),
                (f64::from(got[j as usize].v) - v).abs(),
            );
            assert!(eu <= bu, "u at {j} in {a}..{b}: off by {eu} > {bu}");
            assert!(ev <= bv, "v at {j} in {a}..{b}: off by {ev} > {bv}");
            worst = worst.max(eu).max(ev);
        }
        if b == last {
            return worst;
        }
        a = b;
    }
}

/// Random spans, near and far, short and long, in every subdivision: exact at the
/// subdivision points, within the bow bound between them.
#[test]
fn perspective_spans_are_exact_at_subdivisions_and_bounded_between() {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    for round in 0..600 {
        let n = match round % 4 {
            0 => rng.range(1, 20),
            1 => rng.range(1, 100),
            2 => rng.range(100, 700),
            _ => 8192,
        } as u32;
        // q at the ends, any scale from 2¹⁶ to 2³⁴; their ratio up to 64.
        let scale = 1i64 << rng.range(16, 34);
        let q0 = scale + rng.range(0, scale);
        let q1 = (q0 / rng.range(1, 64)).max(1) + rng.range(0, 3);
        let (q0, q1) = if round % 2 == 0 { (q0, q1) } else { (q1, q0) };
        // u, v at the ends: up to ±64 textures.
        let uv = |rng: &mut Rng| rng.range(-64 * 65536, 64 * 65536);
        let (u0, u1, v0, v1) = (uv(&mut rng), uv(&mut rng), uv(&mut rng), uv(&mut rng));
        let k = i64::from(n.max(2) - 1);
        let start = Homogeneous {
            uq: u0 * q0,
            vq: v0 * q0,
            q: q0,
        };
        let step = Homogeneous {
            uq: (u1 * q1 - u0 * q0) / k,
            vq: (v1 * q1 - v0 * q0) / k,
            q: (q1 - q0) / k,
        };
        if start.q + step.q * k <= 0 {
            continue;
        }
        match round % 3 {
            0 => check_span::<8>(start, step, n),
            1 => check_span::<16>(start, step, n),
            _ => check_span::<32>(start, step, n),
        };
    }
}

/// The hand-computed case: a wall seen at a steep angle, its near edge at
/// w = 1 on the left of a row and its far edge at w = 4 on the right, 32 pixels apart,
/// a 16-texel-wide texture across it (u from 0 to 1).
///
/// Along the row 1/w and u/w are linear: at pixel x (t = x/32), 1/w = 1 − ¾t and
/// u/w = ¼t, so u = ¼t / (1 − ¾t) = t / (4 − 3t):
///
/// | pixel | t | 1/w | u/w | u (perspective) | texel | u (affine) | texel |
/// |---|---|---|---|---|---|---|---|
/// | 8 | ¼ | 13/16 | 1/16 | 1/13 = 0.0769 | 1 | ¼ | 4 |
/// | 16 | ½ | 5/8 | 1/8 | 1/5 = 0.2 | 3 | ½ | 8 |
/// | 24 | ¾ | 7/16 | 3/16 | 3/7 = 0.4286 | 6 | ¾ | 12 |
///
/// Half-way along the row the affine texel is 5 texels off (6 at pixel 24). In Q16
/// with 1/w in Q20: q goes 2²⁰ → 2¹⁸ by −24576 a pixel, uq 0 → 2³⁴ by 2²⁹, all exact,
/// so pixel 16 is 2³³ / 655360 = 13107.2 → u = 13107, texel ⌊13107·16 / 65536⌋ = 3.
///
/// With 8-pixel segments pixels 8, 16 and 24 are subdivision points: exact. With
/// 16-pixel segments pixels 8 and 24 are on chords: pixel 24 half-way from u = ⅕
/// (pixel 16) to 1 (pixel 32), 0.6, texel 9 instead of 6, inside the bound
/// ¼ · (1 − ⅕) · (⅝ − ¼) / ¼ = 0.3 of 3/7; pixel 8 half-way from 0 to ⅕, 0.1, texel 1
/// as it should be (bound ¼ · ⅕ · (1 − ⅝) / ⅝ = 0.03). 1/w falls to 40 % across that
/// segment: so steep a face wants 8-pixel segments.
#[test]
fn a_steep_wall_perspective_against_affine() {
    let start = Homogeneous {
        uq: 0,
        vq: 0,
        q: 1 << 20,
    };
    let step = Homogeneous {
        uq: 1 << 29,
        vq: 0,
        q: -24576,
    };
    let span = |segment: u32| -> Vec<TexCoord> {
        match segment {
            8 => PerspectiveSpan::<8>::new(start, step, 33)
                .unwrap()
                .collect(),
            _ => PerspectiveSpan::<16>::new(start, step, 33)
                .unwrap()
                .collect(),
        }
    };
    let (p8, p16) = (span(8), span(16));
    let affine: Vec<TexCoord> = AffineSpan::new(0, 0, 1 << 27, 0, 33).unwrap().collect();
    let texel = |c: TexCoord| (c.u as u32 * 16) >> 16;
    assert_eq!(p8[16].u, 13107);
    assert_eq!(p16[16].u, 13107);
    assert_eq!((p8[32].u, p16[32].u), (UV_ONE, UV_ONE));
    let at = |x: usize| (texel(p8[x]), texel(affine[x]));
    assert_eq!([at(8), at(16), at(24)], [(1, 4), (3, 8), (6, 12)]);
    // 16-pixel segments: the chords.
    assert_eq!((p16[8].u, p16[24].u), (6553, 39321)); // 0.1 and 0.6, floored
    assert_eq!((texel(p16[8]), texel(p16[24])), (1, 9));
    check_span::<8>(start, step, 33);
    check_span::<16>(start, step, 33);
    // The affine span is exact in its own terms.
    for (k, c) in affine.iter().enumerate() {
        assert_eq!(c.u, ((k as i64 * (1 << 27)) >> 16) as i32);
    }
}

/// Affine spans: ⌊(u + k·du) / 2¹⁶⌋ exactly, both signs.
#[test]
fn affine_spans_are_exact() {
    let mut rng = Rng(77);
    for _ in 0..200 {
        let n = rng.range(0, 500) as u32;
        let (u, v) = (rng.range(-1 << 38, 1 << 38), rng.range(-1 << 38, 1 << 38));
        let (du, dv) = (rng.range(-1 << 28, 1 << 28), rng.range(-1 << 28, 1 << 28));
        let got: Vec<TexCoord> = AffineSpan::new(u, v, du, dv, n).unwrap().collect();
        assert_eq!(got.len(), n as usize);
        for (k, c) in got.iter().enumerate() {
            let k = k as i64;
            assert_eq!(c.u, ((u + k * du) >> 16) as i32);
            assert_eq!(c.v, ((v + k * dv) >> 16) as i32);
        }
    }
}

/// Hostile spans: errors, or coordinates within ±UV_LIMIT, never a panic (these run
/// in debug builds, with overflow checks).
#[test]
fn hostile_spans_are_errors_or_clamped() {
    let h = |uq, vq, q| Homogeneous { uq, vq, q };
    let zero = h(0, 0, 0);
    assert_eq!(
        PerspectiveSpan::<16>::new(h(0, 0, 1), zero, 8193).unwrap_err(),
        Error::TooLarge
    );
    assert_eq!(
        PerspectiveSpan::<16>::new(h(i64::MAX, 0, 1), zero, 1).unwrap_err(),
        Error::OutOfRange
    );
    // In range at the start, out at the end.
    assert_eq!(
        PerspectiveSpan::<16>::new(h(0, 0, 1), h(0, 1 << 61, 0), 5).unwrap_err(),
        Error::OutOfRange
    );
    // One pixel: the step is never taken, whatever it is.
    let one: Vec<_> = PerspectiveSpan::<16>::new(h(5, 7, 1), h(i64::MAX, i64::MIN, i64::MAX), 1)
        .unwrap()
        .collect();
    assert_eq!(one, [TexCoord::new(5, 7)]);
    assert_eq!(
        PerspectiveSpan::<16>::new(zero, zero, 0).unwrap().count(),
        0
    );
    // q of 0 and below, huge quotients: clamped.
    let lim = 1i64 << 62;
    for (start, step) in [
        (h(lim, -lim, 0), zero),
        (h(lim, -lim, -5), h(0, 0, -1)),
        (h(-lim, lim, 1), h(lim / 100, -lim / 100, 3)),
        (h(0, 0, 1 << 40), h(1 << 50, -(1 << 50), -(1 << 31))),
    ] {
        for c in PerspectiveSpan::<32>::new(start, step, 100).unwrap() {
            assert!(c.u.abs() <= UV_LIMIT && c.v.abs() <= UV_LIMIT, "{c:?}");
        }
    }
    let mut full = PerspectiveSpan::<16>::new(h(-lim, lim, 1), zero, 8192).unwrap();
    assert_eq!(full.len(), 8192);
    assert!(full.all(|c| c == TexCoord::new(-UV_LIMIT, UV_LIMIT)));
    // Affine: ends beyond ±2⁴⁰ (Q32), too many pixels.
    assert_eq!(
        AffineSpan::new(0, 0, 0, 0, 8193).unwrap_err(),
        Error::TooLarge
    );
    assert_eq!(
        AffineSpan::new((1 << 40) + 1, 0, 0, 0, 1).unwrap_err(),
        Error::OutOfRange
    );
    assert_eq!(
        AffineSpan::new(0, 0, 0, 1 << 39, 4).unwrap_err(),
        Error::OutOfRange
    );
    let edge: Vec<_> = AffineSpan::new(1 << 40, -(1 << 40), i64::MAX, i64::MIN, 1)
        .unwrap()
        .collect();
    assert_eq!(edge, [TexCoord::new(UV_LIMIT, -UV_LIMIT)]);
}
