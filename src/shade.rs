//! Shading: light intensity per face or per vertex, and materials that turn an
//! intensity into a display colour of any embedded-graphics colour type
//! ([`DisplayColor`]; ordered dithering for 1-, 2- and 4-bit displays).

use embedded_graphics::pixelcolor::{
    Bgr555, Bgr565, Bgr666, Bgr888, BinaryColor, Gray2, Gray4, Gray8, GrayColor, PixelColor,
    Rgb555, Rgb565, Rgb666, Rgb888, RgbColor,
};

use crate::math::Vec3;

/// Light intensity in Q15: `ONE` (32768) is full brightness; values up to 65535
/// (≈ 2.0) over-expose, saturating each channel.
pub type Intensity = u16;

/// Full intensity (1.0).
pub const ONE: Intensity = 1 << 15;

/// How faces are shaded.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum Shading {
    /// Each face in its material at full intensity.
    #[default]
    Flat,
    /// Flat Lambert: one intensity per face from its normal and the light (Lambert's cosine law:
    /// the dot product of normal and light).
    Lambert,
    /// Gouraud: Lambert intensity at each vertex (from the mesh's vertex normals),
    /// interpolated across the face.
    Gouraud,
}

/// A directional light with an ambient term: `I = ambient + diffuse · max(0, N·L)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// Direction *towards* the light, in world space (need not be normalised).
    pub direction: Vec3,
    /// The ambient term.
    pub ambient: f32,
    /// The diffuse weight.
    pub diffuse: f32,
}

impl Default for Light {
    /// Light from the upper left front, `normalize(−1, 1, 1)`, with `I = 0.2 + 0.8·N·L`.
    fn default() -> Self {
        Light {
            direction: Vec3::new(-1.0, 1.0, 1.0),
            ambient: 0.2,
            diffuse: 0.8,
        }
    }
}

impl Light {
    /// The intensity for a unit normal `n` and unit light direction `l`, in Q15.
    pub fn intensity(&self, n_dot_l: f32) -> Intensity {
        let i = self.ambient + self.diffuse * if n_dot_l > 0.0 { n_dot_l } else { 0.0 };
        to_intensity(i)
    }
}

/// An `f32` intensity (1.0 = full) to Q15, saturating; NaN gives 0.
pub fn to_intensity(i: f32) -> Intensity {
    let q = i * f32::from(ONE) + 0.5;
    if q >= 65535.0 {
        65535
    } else if q > 0.0 {
        q as u16
    } else {
        0
    }
}

/// What a face is made of: how it looks at a given light intensity.
///
/// `Rgb888` (a plain colour) is a material for every colour type that implements
/// [`DisplayColor`]: all of embedded-graphics' (see there). Implement `Material` for
/// your own type to use palettes or exact colour rules.
pub trait Material<C>: Copy {
    /// Whether [`shade`](Material::shade) depends on the pixel position (dithering).
    /// When it does not, runs are filled with one colour (`fill_solid`).
    const DITHERED: bool = false;

    /// The colour at intensity `i` (Q15) at pixel (x, y).
    fn shade(&self, i: Intensity, x: i32, y: i32) -> C;
}

/// A display colour that an `Rgb888` material, lit, turns into.
///
/// Every embedded-graphics colour type implements it, so a mesh of `Rgb888` colours
/// draws on any display:
///
/// | colour types | how |
/// |---|---|
/// | `Rgb555`, `Bgr555`, `Rgb565`, `Bgr565`, `Rgb666`, `Bgr666`, `Rgb888`, `Bgr888` | each channel lit and rounded to its depth |
/// | `Gray8` | the material's luma (Rec. 601), lit |
/// | `Gray4`, `Gray2`, `BinaryColor` | the lit luma, ordered-dithered (4×4 Bayer) to 16, 4 or 2 levels |
///
/// Dithered types (`DITHERED`) shade each pixel by its position: over any aligned 4×4
/// block the mean level is the exact lit luma to within 1/16 of a level, so shading
/// survives on 1-, 2- and 4-bit panels (SSD1306, SSD1322, e-paper).
///
/// The impls are written once, over embedded-graphics' `RgbColor` (channel depths
/// `MAX_R`…) and `GrayColor` (`WHITE.luma()`), and listed per type because
/// coherence does not allow both blanket impls side by side. A colour type of your own
/// can implement this trait too.
///
/// ```
/// use embedded_graphics::pixelcolor::{Bgr565, Gray2, Rgb888};
/// use zraster::shade::{Material, ONE};
///
/// let orange = Rgb888::new(255, 128, 0);
/// let c: Bgr565 = orange.shade(ONE, 0, 0);
/// assert_eq!(c, Bgr565::new(31, 32, 0));
/// // Half-lit white on a 2-bit panel (level 1.5): levels 2 and 1 side by side in a
/// // 4×4 Bayer pattern.
/// let white = Rgb888::new(255, 255, 255);
/// let (left, right): (Gray2, Gray2) = (white.shade(ONE / 2, 0, 0), white.shade(ONE / 2, 1, 0));
/// assert_eq!((left, right), (Gray2::new(2), Gray2::new(1)));
/// ```
pub trait DisplayColor: PixelColor {
    /// Whether [`lit`](DisplayColor::lit) dithers (depends on the pixel position).
    const DITHERED: bool;

    /// The colour of `material` at intensity `i` (Q15) at pixel (x, y).
    fn lit(material: Rgb888, i: Intensity, x: i32, y: i32) -> Self;
}

impl<C: DisplayColor> Material<C> for Rgb888 {
    const DITHERED: bool = C::DITHERED;

    #[inline]
    fn shade(&self, i: Intensity, x: i32, y: i32) -> C {
        C::lit(*self, i, x, y)
    }
}

/// An RGB colour lit: each channel of `m` times `i`, rounded to the depth of `C`.
#[inline]
fn lit_rgb<C: RgbColor>(m: Rgb888, i: Intensity, new: fn(u8, u8, u8) -> C) -> C {
    new(
        channel(m.r(), i, u32::from(C::MAX_R)),
        channel(m.g(), i, u32::from(C::MAX_G)),
        channel(m.b(), i, u32::from(C::MAX_B)),
    )
}

/// A grey level lit: the luma of `m` times `i`, rounded to the depth of `C`, or
/// dithered to it.
#[inline]
fn lit_gray<C: GrayColor>(
    m: Rgb888,
    i: Intensity,
    x: i32,
    y: i32,
    dithered: bool,
    new: fn(u8) -> C,
) -> C {
    let max = C::WHITE.luma();
    if dithered {
        new(dither_level(channel(luma(m), i, 255), max, x, y))
    } else {
        new(channel(luma(m), i, u32::from(max)))
    }
}

macro_rules! rgb_colors {
    ($($t:ident),*) => {$(
        impl DisplayColor for $t {
            const DITHERED: bool = false;

            #[inline]
            fn lit(m: Rgb888, i: Intensity, _x: i32, _y: i32) -> $t {
                lit_rgb(m, i, $t::new)
            }
        }
    )*};
}

rgb_colors!(Rgb555, Bgr555, Rgb565, Bgr565, Rgb666, Bgr666, Rgb888, Bgr888);

macro_rules! gray_colors {
    ($($t:ident: $dithered:expr),*) => {$(
        impl DisplayColor for $t {
            const DITHERED: bool = $dithered;

            #[inline]
            fn lit(m: Rgb888, i: Intensity, x: i32, y: i32) -> $t {
                lit_gray(m, i, x, y, $dithered, $t::new)
            }
        }
    )*};
}

gray_colors!(Gray2: true, Gray4: true, Gray8: false);

impl DisplayColor for BinaryColor {
    const DITHERED: bool = true;

    #[inline]
    fn lit(m: Rgb888, i: Intensity, x: i32, y: i32) -> BinaryColor {
        dither(channel(luma(m), i, 255), x, y)
    }
}

/// `v · i / ONE · max / 255`, rounded and saturated to `max`: an 8-bit channel lit and
/// requantised to `max` levels.
#[inline]
fn channel(v: u8, i: Intensity, max: u32) -> u8 {
    // ≤ 255 · 65535 · 255 < 2³². Dividing by 255 · 2¹⁵ is dividing by 2¹⁵, then by
    // 255 (nested floors compose); the second is a multiply, also on chips where the
    // compiler would call a division routine for a 32-bit constant divisor (ARMv6-M).
    let num = u32::from(v) * u32::from(i) * max;
    const DEN: u32 = 255 * ONE as u32;
    div255((num + DEN / 2) >> 15).min(max) as u8
}

/// ⌊x / 255⌋ for x < 2²⁰. Without a divide instruction (where the compiler would call a
/// division routine even for this constant) in adds and shifts: x/255 = (x + x/255)/256,
/// with x/255 on the right estimated once the same way. Exact over that range: a test
/// checks every x against the formula.
#[inline]
fn div255(x: u32) -> u32 {
    if crate::num::ARMV6M {
        div255_shifts(x)
    } else {
        x / 255 // a multiply-high where the chip has one
    }
}

/// The adds-and-shifts form of [`div255`].
#[inline]
fn div255_shifts(x: u32) -> u32 {
    (x + 1 + ((x + 1 + (x >> 8)) >> 8)) >> 8
}

/// Rec. 601 luma of an 8-bit colour.
pub fn luma(c: Rgb888) -> u8 {
    ((77 * u32::from(c.r()) + 150 * u32::from(c.g()) + 29 * u32::from(c.b()) + 128) >> 8) as u8
}

/// The 4×4 Bayer matrix, row by row.
const BAYER4: [u8; 16] = [0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5];

/// Ordered dithering of a grey level to on/off at pixel (x, y): over any aligned 4×4
/// block, `round(level · 16 / 255)` pixels are on.
pub fn dither(level: u8, x: i32, y: i32) -> BinaryColor {
    if dither_level(level, 1, x, y) == 0 {
        BinaryColor::Off
    } else {
        BinaryColor::On
    }
}

/// Ordered dithering of an 8-bit level to `0..=max` at pixel (x, y).
///
/// The level is `round(level · max · 16 / 255)` sixteenths of an output step: pixel
/// (x, y) takes the step below, or the one above where its 4×4 Bayer threshold is below
/// the remainder, so the 16 pixels of any aligned 4×4 block add up to exactly that many
/// sixteenths. `max` is 1 for on/off, 3 for `Gray2`, 15 for `Gray4`; above 15 it is
/// clamped (finer steps gain nothing from a 4×4 pattern).
pub fn dither_level(level: u8, max: u8, x: i32, y: i32) -> u8 {
    let t = BAYER4
        .get(((y & 3) * 4 + (x & 3)) as usize)
        .copied()
        .unwrap_or(0);
    // ≤ 255 · 15 · 16 + 127 < 2²⁰, where div255 is exact.
    let sixteenths = div255(u32::from(level) * u32::from(max.min(15)) * 16 + 127);
    let (step, rest) = (sixteenths >> 4, sixteenths & 15);
    (step + u32::from(u32::from(t) < rest)) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn div255_is_exact_over_its_range() {
        for x in 0..1u32 << 20 {
            assert_eq!(div255_shifts(x), x / 255, "{x}");
            assert_eq!(div255(x), x / 255, "{x}");
        }
        // The largest argument `channel` makes: 255 · 65535 · 255 plus the rounding half.
        assert!((255 * 65535 * 255 + 255 * u32::from(ONE) / 2) >> 15 < 1 << 20);
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
        let on = block(&|x, y| {
            u8::from(<Rgb888 as Material<BinaryColor>>::shade(&m, ONE, x, y).is_on())
        });
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
}
