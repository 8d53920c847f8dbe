//! Unit tests of shading: intensities, lit colours and their rounding, dithering,
//! blending.

use super::*;

#[test]
fn div255_is_exact_over_its_range() {
    for x in 0..1u32 << 20 {
        assert_eq!(div255_shifts(x), x / 255, "{x}");
        assert_eq!(div255(x), x / 255, "{x}");
    }
    // The largest argument `channel` makes: 255 · 65535 · 255 plus the rounding half.
    assert!((255 * 65535 * 255 + 255 * u32::from(ONE) / 2) >> 15 < 1 << 20);
    for x in 0..DIV255_MUL_BELOW {
        assert_eq!(div255_mul(x), x / 255, "{x}");
    }
    // Where it stops: the first x it misses, and `channel`'s largest for 6-bit depths.
    assert_ne!((DIV255_MUL_BELOW * 32_897) >> 23, DIV255_MUL_BELOW / 255);
    assert!((255 * 65535 * 63 + 255 * u32::from(ONE) / 2) >> 15 < DIV255_MUL_BELOW);
}

/// `channel` (with `div_den` where there is a multiply-high) against the rounding it
/// stands for, `round(v · i · max / (255 · ONE))` saturated to `max`, in `u64`: every
/// channel value × every intensity (over-exposed ones included) × each depth used.
#[test]
fn channel_is_the_rounded_quotient_everywhere() {
    const DEN: u64 = 255 * ONE as u64;
    for max in [1u32, 3, 15, 31, 63, 255] {
        for v in 0..=u8::MAX {
            for i in 0..=u16::MAX {
                let num = u64::from(v) * u64::from(i) * u64::from(max);
                let want = ((num + DEN / 2) / DEN).min(u64::from(max));
                assert_eq!(u64::from(channel(v, i, max)), want, "{v} {i} {max}");
                if i <= ONE {
                    // Unsaturated at most full light (`lit_rgb` leaves the clamps out).
                    assert_eq!(u64::from(rounded_channel(v, i, max)), want, "{v} {i} {max}");
                }
                if i == ONE {
                    assert_eq!(u64::from(full_channel(v, max)), want, "{v} {max}");
                }
            }
        }
    }
    // The largest numerator plus the rounding half stays below 2³².
    const _: () = assert!(255 * 65535 * 255 + DEN / 2 < 1 << 32);
    // div_den at the top of its range and around multiples of the divisor there.
    for x in (u32::MAX - (1 << 20)..=u32::MAX).chain((1..514).flat_map(|q| {
        let d = q * 255 * u32::from(ONE);
        [d - 1, d, d + 1]
    })) {
        assert_eq!(div_den(x), x / (255 * u32::from(ONE)), "{x}");
    }
}

#[test]
fn full_intensity_keeps_the_colour() {
    let c = Rgb888::new(255, 128, 0);
    let r: Rgb565 = c.shade(ONE, 0, 0);
    assert_eq!(r, Rgb565::new(31, 32, 0));
    let r: Rgb888 = c.shade(ONE, 0, 0);
    assert_eq!(r, c);
    let half: Rgb888 = c.shade(ONE / 2, 0, 0);
    assert_eq!(half, Rgb888::new(128, 64, 0));
    let over: Rgb888 = c.shade(u16::MAX, 0, 0);
    assert_eq!(over, Rgb888::new(255, 255, 0));
}

#[test]
fn lambert_intensity() {
    let l = Light::default();
    assert_eq!(l.intensity(1.0), ONE);
    assert_eq!(l.intensity(-0.5), to_intensity(0.2));
    assert_eq!(l.intensity(0.5), to_intensity(0.6));
    assert_eq!(to_intensity(f32::NAN), 0);
    assert_eq!(to_intensity(3.0), u16::MAX);
}

#[test]
fn dithering_lights_the_right_share_of_each_block() {
    for level in [0u8, 1, 17, 64, 128, 200, 254, 255] {
        let on = (0..4)
            .flat_map(|y| (0..4).map(move |x| (x, y)))
            .filter(|&(x, y)| dither(level, x + 8, y + 4) == BinaryColor::On)
            .count() as u32;
        assert_eq!(on, (u32::from(level) * 16 + 127) / 255, "level {level}");
    }
}

/// (200, 100, 50) lit and rounded to each RGB type's depth: 5 bits give
/// (24.3, 12.2, 6.1), 6 bits (49.4, 24.7, 12.4); at half intensity 5 bits give
/// (12.2, 6.1, 3.0), 6 bits (24.7, 12.4, 6.2).
#[test]
fn every_rgb_type_gets_its_channels_rounded_to_its_depth() {
    let m = Rgb888::new(200, 100, 50);
    fn both<C: DisplayColor>(m: Rgb888) -> (C, C) {
        (m.shade(ONE, 3, 5), m.shade(ONE / 2, 3, 5))
    }
    assert_eq!(
        both::<Rgb555>(m),
        (Rgb555::new(24, 12, 6), Rgb555::new(12, 6, 3))
    );
    assert_eq!(
        both::<Bgr555>(m),
        (Bgr555::new(24, 12, 6), Bgr555::new(12, 6, 3))
    );
    assert_eq!(
        both::<Rgb565>(m),
        (Rgb565::new(24, 25, 6), Rgb565::new(12, 12, 3))
    );
    assert_eq!(
        both::<Bgr565>(m),
        (Bgr565::new(24, 25, 6), Bgr565::new(12, 12, 3))
    );
    assert_eq!(
        both::<Rgb666>(m),
        (Rgb666::new(49, 25, 12), Rgb666::new(25, 12, 6))
    );
    assert_eq!(
        both::<Bgr666>(m),
        (Bgr666::new(49, 25, 12), Bgr666::new(25, 12, 6))
    );
    assert_eq!(
        both::<Rgb888>(m),
        (Rgb888::new(200, 100, 50), Rgb888::new(100, 50, 25))
    );
    assert_eq!(
        both::<Bgr888>(m),
        (Bgr888::new(200, 100, 50), Bgr888::new(100, 50, 25))
    );
    // The channels land in their places: blue is the high field of a Bgr565.
    let b: Bgr565 = Rgb888::new(0, 0, 255).shade(ONE, 0, 0);
    assert_eq!(
        embedded_graphics::prelude::IntoStorage::into_storage(b),
        31 << 11
    );
    // None of them dithers; the grey ones below 8 bits and 1-bit do.
    let dithered = [
        <Rgb888 as Material<Rgb555>>::DITHERED,
        <Rgb888 as Material<Bgr666>>::DITHERED,
        <Rgb888 as Material<Gray8>>::DITHERED,
        <Rgb888 as Material<Gray4>>::DITHERED,
        <Rgb888 as Material<Gray2>>::DITHERED,
        <Rgb888 as Material<BinaryColor>>::DITHERED,
    ];
    assert_eq!(dithered, [false, false, false, true, true, true]);
}

/// The luma of (200, 100, 50) is 124 (31978 / 256). In sixteenths of a step that
/// is 117 for Gray4 (124 · 15 · 16 / 255 = 116.7: step 7, 5 pixels of 16 one above)
/// and 23 for Gray2 (23.3: step 1, 7 of 16 above); on/off, 8 of 16 are on (7.8).
#[test]
fn grey_types_get_the_luma_dithered_below_eight_bits() {
    let m = Rgb888::new(200, 100, 50);
    assert_eq!(luma(m), 124);
    let g8: Gray8 = m.shade(ONE, 0, 0);
    assert_eq!(g8, Gray8::new(124));
    let g8: Gray8 = m.shade(ONE / 2, 0, 0);
    assert_eq!(g8, Gray8::new(62));
    let block = |f: &dyn Fn(i32, i32) -> u8| {
        let mut out = [[0u8; 4]; 4];
        for (y, row) in out.iter_mut().enumerate() {
            for (x, v) in row.iter_mut().enumerate() {
                // An aligned block away from the origin: the pattern repeats.
                *v = f(x as i32 + 12, y as i32 - 8);
            }
        }
        out
    };
    // Bayer thresholds: [0 8 2 10] [12 4 14 6] [3 11 1 9] [15 7 13 5].
    let g4 = block(&|x, y| <Rgb888 as Material<Gray4>>::shade(&m, ONE, x, y).luma());
    assert_eq!(g4, [[8, 7, 8, 7], [7, 8, 7, 7], [8, 7, 8, 7], [7, 7, 7, 7]]);
    let g2 = block(&|x, y| <Rgb888 as Material<Gray2>>::shade(&m, ONE, x, y).luma());
    assert_eq!(g2, [[2, 1, 2, 1], [1, 2, 1, 2], [2, 1, 2, 1], [1, 1, 1, 2]]);
    let on =
        block(&|x, y| u8::from(<Rgb888 as Material<BinaryColor>>::shade(&m, ONE, x, y).is_on()));
    assert_eq!(on, [[1, 0, 1, 0], [0, 1, 0, 1], [1, 0, 1, 0], [0, 1, 0, 1]]);
    // White and black are flat at every depth.
    let white = Rgb888::new(255, 255, 255);
    for (x, y) in [(0, 0), (1, 2), (3, 3)] {
        assert_eq!(
            <Rgb888 as Material<Gray4>>::shade(&white, ONE, x, y),
            Gray4::new(15)
        );
        assert_eq!(
            <Rgb888 as Material<Gray2>>::shade(&white, ONE, x, y),
            Gray2::new(3)
        );
        assert_eq!(
            <Rgb888 as Material<Gray2>>::shade(&white, 0, x, y),
            Gray2::new(0)
        );
    }
}

#[test]
fn dithered_blocks_add_up_to_the_level() {
    for max in [1u8, 3, 15] {
        for level in 0..=255u8 {
            let mut sum = 0u32;
            for y in 0..4 {
                for x in 0..4 {
                    let v = dither_level(level, max, x - 4, y + 20);
                    assert!(v <= max, "{level} {max}");
                    sum += u32::from(v);
                }
            }
            let want = (u32::from(level) * u32::from(max) * 16 + 127) / 255;
            assert_eq!(sum, want, "level {level} to {max}");
        }
    }
}

/// The packed 50 % blend of the 16-bit types is the per-channel mean rounded down,
/// as `mix` gives it, for every pair of a spread of colours (all field values
/// included: the masks keep each field's low bit from spilling into the next).
#[test]
fn half_of_565_is_the_mean_of_each_channel() {
    let values: [u8; 8] = [0, 1, 2, 15, 16, 30, 31, 63];
    for &r in &values[..7] {
        for &g in &values {
            for &b in &values[..7] {
                let a = Rgb565::new(r, g, b);
                let z = Rgb565::new(31 - r, 63 - g, b / 2);
                let got = <Rgb565 as DisplayColor>::blend(a, z, 128, 0, 0);
                let want =
                    Rgb565::new(mix(r, 31 - r, 128), mix(g, 63 - g, 128), mix(b, b / 2, 128));
                assert_eq!(got, want, "{a:?} {z:?}");
                assert_eq!(want.r(), (r + 31 - r) / 2);
                // The same on the reversed field order.
                let (ba, bz) = (Bgr565::new(r, g, b), Bgr565::new(31 - r, 63 - g, b / 2));
                let got = <Bgr565 as DisplayColor>::blend(ba, bz, 128, 0, 0);
                assert_eq!((got.r(), got.g(), got.b()), (want.r(), want.g(), want.b()));
            }
        }
    }
}

/// `dst + (src − dst) · a / 255`, rounded: a few by hand.
#[test]
fn blending_mixes_each_channel_by_alpha() {
    // 31 → 0 at 64/255: 31 · 191 / 255 = 23.2; 0 → 31: 31 · 64 / 255 = 7.8.
    let got =
        <Rgb565 as DisplayColor>::blend(Rgb565::new(31, 0, 0), Rgb565::new(0, 0, 31), 64, 0, 0);
    assert_eq!(got, Rgb565::new(23, 0, 8));
    // Opaque gives src, invisible dst, whatever they are.
    let (d, s) = (Rgb888::new(10, 200, 77), Rgb888::new(250, 3, 128));
    assert_eq!(<Rgb888 as DisplayColor>::blend(d, s, 255, 0, 0), s);
    assert_eq!(<Rgb888 as DisplayColor>::blend(d, s, 0, 0, 0), d);
    // 100 over 200 at 128: the mean 150; Gray8 alike.
    let g = <Gray8 as DisplayColor>::blend(Gray8::new(200), Gray8::new(100), 128, 0, 0);
    assert_eq!(g, Gray8::new(150));
    // 200 → 100 at 51 (20 %): (200 · 204 + 100 · 51 + 127) / 255 = 180.
    let g = <Gray8 as DisplayColor>::blend(Gray8::new(200), Gray8::new(100), 51, 0, 0);
    assert_eq!(g, Gray8::new(180));
}

/// The screen door covers `round(alpha · 16 / 255)` pixels of every aligned 4×4
/// block, and dithered types blend by it.
#[test]
fn the_screen_door_covers_alphas_share() {
    for alpha in [0u8, 1, 8, 64, 128, 200, 254, 255] {
        let covered = (0..16)
            .filter(|i| screen_door(alpha, 20 + i % 4, -8 + i / 4))
            .count() as u32;
        assert_eq!(
            covered,
            (u32::from(alpha) * 16 + 127) / 255,
            "alpha {alpha}"
        );
    }
    // Half: the Bayer cells below 8, (0, 0) on and (1, 0) off.
    let on =
        |x, y| <BinaryColor as DisplayColor>::blend(BinaryColor::Off, BinaryColor::On, 128, x, y);
    assert_eq!((on(0, 0), on(1, 0)), (BinaryColor::On, BinaryColor::Off));
    // Translucent carries its alpha to the blend; Rgb888 is opaque.
    let glass = Translucent::from_opacity(Rgb888::new(0, 0, 255), 0.25);
    assert_eq!(glass.alpha, 64);
    assert_eq!(<Translucent as Material<Rgb565>>::alpha(&glass), 64);
    assert_eq!(Translucent::from_opacity(Rgb888::RED, f32::NAN).alpha, 255);
    assert_eq!(Translucent::from_opacity(Rgb888::RED, -3.0).alpha, 0);
    assert_eq!(Translucent::from_opacity(Rgb888::RED, 7.0).alpha, 255);
    const { assert!(!<Rgb888 as Material<Rgb565>>::TRANSLUCENT) };
    const { assert!(<Translucent as Material<Rgb565>>::TRANSLUCENT) };
}

#[test]
fn full_light_is_lit_at_one_for_every_rgb_type() {
    fn check<C: DisplayColor + core::fmt::Debug>() {
        for c in (0..1u32 << 24).step_by(97).chain([0, 0xFF_FFFF]) {
            let m = Rgb888::new((c >> 16) as u8, (c >> 8) as u8, c as u8);
            assert_eq!(C::lit_full(m, 3, 5), C::lit(m, ONE, 3, 5), "{m:?}");
        }
    }
    check::<Rgb555>();
    check::<Bgr555>();
    check::<Rgb565>();
    check::<Bgr565>();
    check::<Rgb666>();
    check::<Bgr666>();
    check::<Rgb888>();
    check::<Bgr888>();
    check::<Gray8>();
}
