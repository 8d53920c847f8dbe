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
///
/// A material may be see-through ([`Translucent`]): faces whose
/// [`alpha`](Material::alpha) is below 255 are left out of the opaque faces and drawn
/// after them, depth-tested without writing depth, blended over what is drawn
/// ([`blend`](Material::blend)). Plain colours are opaque at compile time
/// ([`TRANSLUCENT`](Material::TRANSLUCENT) is `false`), so their loops never ask.
pub trait Material<C>: Copy {
    /// Whether [`shade`](Material::shade) depends on the pixel position (dithering).
    /// When it does not, runs are filled with one colour (`fill_solid`).
    const DITHERED: bool = false;

    /// Whether any value of the type can be see-through (an
    /// [`alpha`](Material::alpha) below 255). `false` (the default) compiles the
    /// transparency pass out.
    const TRANSLUCENT: bool = false;

    /// The colour at intensity `i` (Q15) at pixel (x, y).
    fn shade(&self, i: Intensity, x: i32, y: i32) -> C;

    /// For the renderer's lit faces: when [`shade`](Material::shade) is a 5-6-5
    /// colour's [`DisplayColor::lit`] of an `Rgb888`, the material's 8-bit channels in
    /// the packing's order (high field first) and the colour of a packed value.
    #[doc(hidden)]
    #[inline(always)]
    fn packed_565(&self) -> Option<Packed565<C>> {
        None
    }

    /// Opacity: 255 opaque (the default), 0 invisible.
    #[inline(always)]
    fn alpha(&self) -> u8 {
        255
    }

    /// `src` (this material's colour at pixel (x, y)) over `dst` (what the pixel
    /// holds) at this material's [`alpha`](Material::alpha). The default is `src`.
    #[inline(always)]
    fn blend(&self, dst: C, src: C, x: i32, y: i32) -> C {
        let _ = (dst, x, y);
        src
    }
}

/// A see-through colour: `color` at opacity `alpha` (255 opaque, 0 invisible), as an
/// OBJ material's `d` (`alpha = round(d · 255)`, [`Translucent::from_opacity`]).
///
/// Faces of alpha below 255 are drawn after every opaque face of the renderer (of the
/// whole [`Scene`](crate::scene::Scene) in a scene), depth-tested against the opaque
/// ones and not writing depth, each blended over the pixel's colour:
/// `dst + (src − dst) · alpha / 255` per channel ([`DisplayColor::blend`]; alpha 128
/// is the exact mean, rounded down). They are drawn in (object, face) order, not
/// sorted: where see-through faces overlap each other the result depends on that
/// order, so sort them back to front yourself or keep them from overlapping. Faces of
/// alpha 255 are opaque faces like any other.
///
/// A [`WithDepth`](crate::WithDepth) cannot read the display's colours: there the
/// faces are drawn as a screen door instead, the share `alpha / 255` of each aligned
/// 4×4 block of pixels (ordered, [`screen_door`]), the others left as they were.
///
/// ```
/// use embedded_graphics::{pixelcolor::{Rgb565, Rgb888}, prelude::*};
/// use zraster::shade::{Material, Translucent, ONE};
///
/// let glass = Translucent::new(Rgb888::new(0, 0, 255), 128);
/// let red = Rgb565::new(31, 0, 0);
/// let blue: Rgb565 = glass.shade(ONE, 0, 0);
/// assert_eq!(glass.blend(red, blue, 0, 0), Rgb565::new(15, 0, 15)); // half of each
/// assert_eq!(Translucent::from_opacity(Rgb888::WHITE, 0.5).alpha, 128);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Translucent {
    /// The colour, lit as a plain `Rgb888` material.
    pub color: Rgb888,
    /// Opacity: 255 opaque, 0 invisible.
    pub alpha: u8,
}

impl Translucent {
    /// `color` at opacity `alpha`.
    pub const fn new(color: Rgb888, alpha: u8) -> Self {
        Translucent { color, alpha }
    }

    /// `color` at opacity `d` in 0.0..=1.0 (an MTL `d`; `Tr` is `1 − d`), rounded to
    /// 1/255 and clamped; NaN is opaque.
    pub fn from_opacity(color: Rgb888, d: f32) -> Self {
        let a = d * 255.0 + 0.5;
        let alpha = if a.is_nan() || a >= 255.0 {
            255
        } else if a > 0.0 {
            a as u8
        } else {
            0
        };
        Translucent { color, alpha }
    }
}

impl From<Rgb888> for Translucent {
    /// An opaque material of that colour.
    fn from(color: Rgb888) -> Self {
        Translucent { color, alpha: 255 }
    }
}

impl<C: DisplayColor> Material<C> for Translucent {
    const DITHERED: bool = C::DITHERED;
    const TRANSLUCENT: bool = true;

    #[inline]
    fn shade(&self, i: Intensity, x: i32, y: i32) -> C {
        C::lit(self.color, i, x, y)
    }

    #[inline(always)]
    fn alpha(&self) -> u8 {
        self.alpha
    }

    #[inline]
    fn blend(&self, dst: C, src: C, x: i32, y: i32) -> C {
        C::blend(dst, src, self.alpha, x, y)
    }
}

/// Whether a see-through face of opacity `alpha` covers pixel (x, y) where colours
/// cannot be mixed (the screen door): over any aligned 4×4 block,
/// `round(alpha · 16 / 255)` pixels are covered, in the Bayer order of [`dither`].
pub fn screen_door(alpha: u8, x: i32, y: i32) -> bool {
    dither_level(alpha, 1, x, y) != 0
}

/// A material's 8-bit channels in a 5-6-5 packing's order (high field first), the
/// colour of a packed value and, where the crate knows it, [`Raw565`]: that colour's
/// two bytes are the packed value (see [`Material::packed_565`]).
#[doc(hidden)]
pub type Packed565<C> = ([u8; 3], fn(u16) -> C, Option<Raw565<C>>);

#[doc(hidden)]
pub use crate::num::kernel::Raw565;

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

    /// [`lit`](DisplayColor::lit) at full light ([`ONE`]), where the caller's intensity
    /// is that constant (a shader's colour): RGB types fold the rounding to 32 bits.
    #[doc(hidden)]
    #[inline(always)]
    fn lit_full(material: Rgb888, x: i32, y: i32) -> Self {
        Self::lit(material, ONE, x, y)
    }

    /// For a 5-6-5 type: `material`'s 8-bit channels in the packing's order (high
    /// field first) and the colour of a packed value (see [`Material::packed_565`]).
    #[doc(hidden)]
    #[inline(always)]
    fn packed_565(material: Rgb888) -> Option<Packed565<Self>> {
        let _ = material;
        None
    }

    /// `src` over `dst` at opacity `alpha` at pixel (x, y) (see [`Translucent`]).
    /// RGB types and `Gray8` mix each channel, `dst + (src − dst) · alpha / 255`
    /// rounded (alpha 128: the mean rounded down, `(a & b) + ((a ^ b) >> 1)`); the
    /// default, which the dithered types keep, is the [`screen_door`]: `src` on the
    /// pixels it covers, `dst` on the others.
    #[inline]
    fn blend(dst: Self, src: Self, alpha: u8, x: i32, y: i32) -> Self {
        if screen_door(alpha, x, y) {
            src
        } else {
            dst
        }
    }
}

impl<C: DisplayColor> Material<C> for Rgb888 {
    const DITHERED: bool = C::DITHERED;

    #[inline]
    fn shade(&self, i: Intensity, x: i32, y: i32) -> C {
        C::lit(*self, i, x, y)
    }

    #[inline(always)]
    fn packed_565(&self) -> Option<Packed565<C>> {
        C::packed_565(*self)
    }
}

/// An RGB colour lit: each channel of `m` times `i`, rounded to the depth of `C`.
#[inline]
fn lit_rgb<C: RgbColor>(m: Rgb888, i: Intensity, new: fn(u8, u8, u8) -> C) -> C {
    let (r, g, b) = (
        u32::from(C::MAX_R),
        u32::from(C::MAX_G),
        u32::from(C::MAX_B),
    );
    if i <= ONE && !crate::num::ARMV6M {
        // At most full light no channel passes its depth: no clamps (on ARMv6-M the
        // clamps cost less than the masks the packing then needs).
        let lit = |v: u8, max: u32| rounded_channel(v, i, max) as u8;
        return new(lit(m.r(), r), lit(m.g(), g), lit(m.b(), b));
    }
    new(
        channel(m.r(), i, r),
        channel(m.g(), i, g),
        channel(m.b(), i, b),
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

/// One channel of `src` over `dst` at opacity `a`: the mean rounded down at 128,
/// else `(dst · (255 − a) + src · a) / 255` rounded.
#[inline]
fn mix(dst: u8, src: u8, a: u8) -> u8 {
    if a == 128 {
        return (dst & src) + ((dst ^ src) >> 1);
    }
    // ≤ 255 · 255 + 127 < 2²⁰, where div255 is exact.
    let (d, s, a) = (u32::from(dst), u32::from(src), u32::from(a));
    div255(d * (255 - a) + s * a + 127) as u8
}

/// An RGB colour at full light: [`lit_rgb`] at [`ONE`], each channel's quotient in 32
/// bits off ARMv6-M ([`full_channel`]).
#[inline(always)]
fn full_rgb<C: RgbColor>(m: Rgb888, new: fn(u8, u8, u8) -> C) -> C {
    if crate::num::ARMV6M {
        return lit_rgb(m, ONE, new);
    }
    let full = |v: u8, max: u8| full_channel(v, u32::from(max)) as u8;
    new(
        full(m.r(), C::MAX_R),
        full(m.g(), C::MAX_G),
        full(m.b(), C::MAX_B),
    )
}

/// An RGB colour blended channel by channel.
#[inline]
fn blend_rgb<C: RgbColor>(dst: C, src: C, a: u8, new: fn(u8, u8, u8) -> C) -> C {
    new(
        mix(dst.r(), src.r(), a),
        mix(dst.g(), src.g(), a),
        mix(dst.b(), src.b(), a),
    )
}

/// Half of each 5-6-5 channel of two packed colours, rounded down, in one go: the low
/// bit of each field is masked off before the shift so that none spills into the next.
#[inline]
fn half_565(a: u16, b: u16) -> u16 {
    (a & b) + (((a ^ b) & 0xF7DE) >> 1)
}

macro_rules! rgb_colors {
    ($($t:ident),*) => {$(
        impl DisplayColor for $t {
            const DITHERED: bool = false;

            #[inline]
            fn lit(m: Rgb888, i: Intensity, _x: i32, _y: i32) -> $t {
                lit_rgb(m, i, $t::new)
            }

            #[inline(always)]
            fn lit_full(m: Rgb888, _x: i32, _y: i32) -> $t {
                full_rgb(m, $t::new)
            }

            #[inline]
            fn blend(dst: $t, src: $t, alpha: u8, _x: i32, _y: i32) -> $t {
                blend_rgb(dst, src, alpha, $t::new)
            }
        }
    )*};
}

rgb_colors!(Rgb555, Bgr555, Rgb666, Bgr666, Rgb888, Bgr888);

/// The 16-bit types: their 50 % blend on the packed value.
macro_rules! rgb565_colors {
    ($($t:ident: $high:ident, $low:ident),*) => {$(
        impl DisplayColor for $t {
            const DITHERED: bool = false;

            #[inline]
            fn lit(m: Rgb888, i: Intensity, _x: i32, _y: i32) -> $t {
                lit_rgb(m, i, $t::new)
            }

            #[inline(always)]
            fn lit_full(m: Rgb888, _x: i32, _y: i32) -> $t {
                full_rgb(m, $t::new)
            }

            #[inline(always)]
            fn packed_565(m: Rgb888) -> Option<Packed565<$t>> {
                use embedded_graphics::pixelcolor::raw::RawU16;
                Some(([m.$high(), m.g(), m.$low()], |c| $t::from(RawU16::new(c)), Some(Raw565::<$t>::PROOF)))
            }

            #[inline]
            fn blend(dst: $t, src: $t, alpha: u8, _x: i32, _y: i32) -> $t {
                use embedded_graphics::{pixelcolor::raw::RawU16, prelude::IntoStorage};
                if alpha == 128 {
                    let half = half_565(dst.into_storage(), src.into_storage());
                    return $t::from(RawU16::new(half));
                }
                blend_rgb(dst, src, alpha, $t::new)
            }
        }
    )*};
}

rgb565_colors!(Rgb565: r, b, Bgr565: b, r);

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

gray_colors!(Gray2: true, Gray4: true);

impl DisplayColor for Gray8 {
    const DITHERED: bool = false;

    #[inline]
    fn lit(m: Rgb888, i: Intensity, x: i32, y: i32) -> Gray8 {
        lit_gray(m, i, x, y, false, Gray8::new)
    }

    #[inline]
    fn blend(dst: Gray8, src: Gray8, alpha: u8, _x: i32, _y: i32) -> Gray8 {
        Gray8::new(mix(dst.luma(), src.luma(), alpha))
    }
}

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
    rounded_channel(v, i, max).min(max) as u8
}

/// [`rounded_channel`] at `i = ONE`: `(v·max·2¹⁵ + 255·2¹⁴) / (255·2¹⁵)` and
/// `(v·max + 127) / 255` have the same floor (no integer lies between them).
#[inline]
fn full_channel(v: u8, max: u32) -> u32 {
    (u32::from(v) * max + 127) / 255
}

/// `v · i / ONE · max / 255`, rounded, not saturated: at most `max` for `i ≤ ONE`.
#[inline]
fn rounded_channel(v: u8, i: Intensity, max: u32) -> u32 {
    // ≤ 255 · 65535 · 255 < 2³². Dividing by 255 · 2¹⁵ is dividing by 2¹⁵, then by
    // 255 (nested floors compose); the second is a multiply, also on chips where the
    // compiler would call a division routine for a 32-bit constant divisor (ARMv6-M).
    let num = u32::from(v) * u32::from(i) * max;
    const DEN: u32 = 255 * ONE as u32;
    let x = num + DEN / 2; // < 2³², checked by a test
    if !crate::num::ARMV6M {
        div_den(x)
    } else if max <= 63 {
        // (x >> 15) ≤ (255 · 65535 · 63 + DEN / 2) >> 15 < DIV255_MUL_BELOW.
        div255_mul(x >> 15)
    } else {
        div255_shifts(x >> 15)
    }
}

/// The bound below which [`div255_mul`] is exact (a test checks every `x` below it).
const DIV255_MUL_BELOW: u32 = 66_299;

/// ⌊x / 255⌋ for x < [`DIV255_MUL_BELOW`] as one multiply by ⌈2²³ / 255⌉ and a shift
/// (x · 32897 < 2³² there): on ARMv6-M, for channels of at most 6 bits, two
/// instructions instead of the six of [`div255_shifts`].
#[inline]
fn div255_mul(x: u32) -> u32 {
    debug_assert!(x < DIV255_MUL_BELOW);
    (x * 32_897) >> 23
}

/// ⌊x / (255 · 2¹⁵)⌋ for any `u32` in one multiply-high and a shift (UMULL, LSR on
/// Thumb-2) instead of a shift, a multiply-high and a shift. With
/// M = ⌈2³⁹ / 255⌉ = 2³⁹/255 + e/255 (e = 127), x·M / 2⁵⁴ exceeds x / (255 · 2¹⁵) by
/// x·e / (255 · 2⁵⁴) < 1 / (255 · 2¹⁵) for x < 2³², too little to reach the next
/// integer (a test checks it against the division).
#[inline]
fn div_den(x: u32) -> u32 {
    const M: u64 = (1 << 39) / 255 + 1;
    ((u64::from(x) * M) >> 54) as u32
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
mod tests;
