//! Shading: light intensity per face or per vertex, and materials that turn an
//! intensity into a display colour (with ordered dithering for monochrome displays).

use embedded_graphics::pixelcolor::{BinaryColor, Gray8, Rgb565, Rgb888, RgbColor};

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
    /// Flat Lambert: one intensity per face from its normal and the light (the seeds'
    /// dot-product colour).
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
/// Implemented for `Rgb888` (a plain colour) into `Rgb565`, `Rgb888`, `Gray8` and, with
/// 4×4 ordered dithering, `BinaryColor`. Implement it for your own type to use palettes
/// or exact colour rules.
pub trait Material<C>: Copy {
    /// Whether [`shade`](Material::shade) depends on the pixel position (dithering).
    /// When it does not, runs are filled with one colour (`fill_solid`).
    const DITHERED: bool = false;

    /// The colour at intensity `i` (Q15) at pixel (x, y).
    fn shade(&self, i: Intensity, x: i32, y: i32) -> C;
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

impl Material<Rgb565> for Rgb888 {
    fn shade(&self, i: Intensity, _x: i32, _y: i32) -> Rgb565 {
        Rgb565::new(
            channel(self.r(), i, 31),
            channel(self.g(), i, 63),
            channel(self.b(), i, 31),
        )
    }
}

impl Material<Rgb888> for Rgb888 {
    fn shade(&self, i: Intensity, _x: i32, _y: i32) -> Rgb888 {
        Rgb888::new(
            channel(self.r(), i, 255),
            channel(self.g(), i, 255),
            channel(self.b(), i, 255),
        )
    }
}

impl Material<Gray8> for Rgb888 {
    fn shade(&self, i: Intensity, _x: i32, _y: i32) -> Gray8 {
        Gray8::new(channel(luma(*self), i, 255))
    }
}

impl Material<BinaryColor> for Rgb888 {
    const DITHERED: bool = true;

    fn shade(&self, i: Intensity, x: i32, y: i32) -> BinaryColor {
        dither(channel(luma(*self), i, 255), x, y)
    }
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
    let t = BAYER4
        .get(((y & 3) * 4 + (x & 3)) as usize)
        .copied()
        .unwrap_or(0);
    // Levels 0..=255 map to 0..=16 pixels on; pixel on when its threshold is below.
    let on = (u32::from(level) * 16 + 127) / 255;
    if u32::from(t) < on {
        BinaryColor::On
    } else {
        BinaryColor::Off
    }
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
}
