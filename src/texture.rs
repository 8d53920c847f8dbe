//! Textures: a table of texels in memory you provide (a `const` table in flash stays
//! there), nearest sampling with repeat or clamp, and the span interpolators that turn
//! a triangle's perspective-divided texture coordinates into a texel per pixel.
//! [`Renderer::draw_textured`](crate::Renderer::draw_textured) draws a mesh with one
//! (a [`Texturing`]: the mesh's texture coordinates and the texture).
//!
//! # Formats
//!
//! | what | type | format |
//! |---|---|---|
//! | texture coordinate at a pixel ([`TexCoord`]) | `i32` ×2 | Q16 texture units: 65536 ([`UV_ONE`]) is one whole width (u) or height (v); v grows **down** the image (row 0 at v = 0); results kept within ±[`UV_LIMIT`] (±256 textures) |
//! | a mesh's texture coordinates ([`MeshUv`]) | `[i16; 2]` | Q12 ([`MESH_UV_ONE`] = 4096 is one texture): −8 ≤ u, v < 8 in steps of 1/4096, v down; [`TexCoord::from_mesh`] widens them |
//! | perspective span input ([`Homogeneous`]) | `i64` ×3 | `q` = 1/w at any positive scale; `uq`, `vq` = u·q, v·q at the same scale with u, v in Q16, so that `uq / q` is u in Q16 |
//! | affine span input ([`AffineSpan::new`]) | `i64` ×4 | u, v and their steps per pixel in Q32 texture units (2³² is one texture): the 16.16 form of Q16 values |
//! | texels ([`Texel`]) | any embedded-graphics colour, or `u16` | a `u16` is a raw RGB565 value (`0xF800` is red), the form `obj2rust` writes to flash |
//!
//! Wrapping a Q16 coordinate is a mask (repeat: its low 16 bits, which also maps
//! negative coordinates right) or a clamp to `0..=0xFFFF`, and the texel is
//! `⌊u·W⌋` = `(u·W) >> 16` (u < 2¹⁶, W ≤ 8192: below 2²⁹): no division for any size,
//! and a shift for power-of-two sizes. A mesh's Q12 coordinates of up to ±8 textures
//! cover faces that repeat a texture up to 8 times; `obj2rust` moves each face of a
//! model by whole textures (which repeat does not see) so that it fits, and says so
//! where a face spans more.
//!
//! # Perspective
//!
//! Across a screen triangle u and v are not linear but u/w, v/w and 1/w are: a
//! [`PerspectiveSpan`] steps those three along a row and divides (exactly, both
//! coordinates by one divisor) every `SEGMENT` pixels (16 by default, or 8 or 32),
//! stepping u and v linearly in between. It is exact at the subdivision points and at
//! the span's last pixel; in between, within one segment from pixel a to pixel b, a
//! pixel's u is off the true `uq/q` by at most
//!
//! `¼ · |u_b − u_a| · |q_b − q_a| / min(q_a, q_b)` + 3 units of Q16
//!
//! (the bow of the hyperbola u(x) against its chord, plus the floors). Where 1/w changes
//! by under 1/8 across a segment that is under 1/32 of the segment's change of u. An
//! [`AffineSpan`] steps u and v themselves: no division at all, and the classic
//! swimming of textures on faces seen at a slant.
//!
//! # Light
//!
//! A texel is lit as a flat colour is ([`shade`](crate::shade)): [`modulate`] (and
//! [`Texture::lit`]) turn the texel into its `Rgb888` and light that as an `Rgb888`
//! material, so a textured pixel looks exactly like a face in the texel's colour under
//! the same light, flat, Lambert or Gouraud, on every display colour type. At full
//! intensity an RGB565 texel on an RGB565 display is the texel itself.
//!
//! ```
//! use embedded_graphics::pixelcolor::Rgb565;
//! use zraster::texture::{AffineSpan, Homogeneous, PerspectiveSpan, TexCoord, Texture, Wrap, UV_ONE};
//!
//! // A 2×2 checker as raw RGB565 (as a `const` it stays in flash): red, green / blue, white.
//! const CHECKER: [u16; 4] = [0xF800, 0x07E0, 0x001F, 0xFFFF];
//! let tex = Texture::new(&CHECKER, 2, 2)?;
//! assert_eq!(tex.sample(TexCoord::new(UV_ONE / 4, UV_ONE / 4)), Rgb565::new(31, 0, 0));
//! // Repeat: u = 1.75 is u = 0.75, the right column.
//! assert_eq!(tex.sample(TexCoord::new(UV_ONE * 7 / 4, 0)), Rgb565::new(0, 63, 0));
//! // Clamp: u = 1.75 is u = 1, the right column too; v = −0.5 is v = 0, the top row.
//! let clamped = tex.with_wrap(Wrap::Clamp);
//! assert_eq!(clamped.sample(TexCoord::new(UV_ONE * 7 / 4, -UV_ONE / 2)), Rgb565::new(0, 63, 0));
//!
//! // A row of 33 pixels going away from the eye: 1/w falls from 1 to ¼ (q in Q20) while
//! // u goes from 0 to 1. Half-way along, 1/w = ⅝ and u/w = ⅛: u = ⅕, not ½.
//! let q0 = 1i64 << 20;
//! let start = Homogeneous { uq: 0, vq: 0, q: q0 };
//! let end = Homogeneous { uq: q0 / 4 * i64::from(UV_ONE), vq: 0, q: q0 / 4 };
//! let step = Homogeneous { uq: end.uq / 32, vq: 0, q: (end.q - start.q) / 32 };
//! let span: Vec<TexCoord> = PerspectiveSpan::<16>::new(start, step, 33)?.collect();
//! assert_eq!(span[16].u, UV_ONE / 5); // 13107: 0.2 in Q16, exact at a subdivision point
//! let affine: Vec<TexCoord> = AffineSpan::new(0, 0, (1i64 << 32) / 32, 0, 33)?.collect();
//! assert_eq!(affine[16].u, UV_ONE / 2);
//! # Ok::<(), zraster::Error>(())
//! ```

use embedded_graphics::pixelcolor::{
    raw::RawU16, Bgr555, Bgr565, Bgr666, Bgr888, BinaryColor, Gray2, Gray4, Gray8, PixelColor,
    Rgb555, Rgb565, Rgb666, Rgb888,
};

use crate::shade::{DisplayColor, Intensity};
use crate::{Error, MAX_DIMENSION};

/// Fractional bits of a [`TexCoord`] (16).
pub const UV_BITS: u32 = 16;
/// One whole texture width or height in a [`TexCoord`]: 65536.
pub const UV_ONE: i32 = 1 << UV_BITS;
/// The largest magnitude of a [`TexCoord`] the span interpolators return: 2²⁴, that is
/// ±256 textures (results beyond are clamped to it).
pub const UV_LIMIT: i32 = 1 << 24;
/// Fractional bits of a mesh's texture coordinates ([`MeshUv`]): 12.
pub const MESH_UV_BITS: u32 = 12;
/// One whole texture in a [`MeshUv`]: 4096.
pub const MESH_UV_ONE: i16 = 1 << MESH_UV_BITS;

/// A mesh vertex's texture coordinates `[u, v]`: Q12 ([`MESH_UV_ONE`] = 4096 is one
/// texture), −8 ≤ u, v < 8, v down the image (OBJ's v is up: `obj2rust` stores 1 − v).
pub type MeshUv = [i16; 2];

/// Texture coordinates at a pixel: Q16 texture units ([`UV_ONE`] is one whole texture),
/// v down the image. The texel of a coordinate is `⌊u·W⌋` (wrapped, see [`Wrap`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub struct TexCoord {
    /// Across the texture, Q16.
    pub u: i32,
    /// Down the texture, Q16.
    pub v: i32,
}

impl TexCoord {
    /// Coordinates from Q16 values.
    pub const fn new(u: i32, v: i32) -> TexCoord {
        TexCoord { u, v }
    }

    /// A mesh vertex's Q12 coordinates in Q16 (exact: four more fractional bits).
    pub const fn from_mesh(uv: MeshUv) -> TexCoord {
        TexCoord {
            u: (uv[0] as i32) << (UV_BITS - MESH_UV_BITS),
            v: (uv[1] as i32) << (UV_BITS - MESH_UV_BITS),
        }
    }
}

/// What a coordinate outside `0..1` samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum Wrap {
    /// The texture tiles the plane: u and u + 1 sample the same texel (OBJ's default).
    #[default]
    Repeat,
    /// Coordinates below 0 sample the first texel, those from 1 on the last.
    Clamp,
}

/// What a texture is a table of: a colour, or a stored form of one.
///
/// Every embedded-graphics colour type is a texel of itself, and `u16` is a raw RGB565
/// value (the form `obj2rust` writes: `0xF800` is red), so a `const [u16; N]` in flash
/// is a texture as it is, without copying. The impls are listed per type (coherence
/// does not allow a blanket impl beside the one for `u16`); for a colour type of your
/// own, implement it as `type Color = Self; fn color(self) -> Self { self }`.
pub trait Texel: Copy {
    /// The colour a texel stands for.
    type Color: PixelColor;

    /// The colour of this texel.
    fn color(self) -> Self::Color;
}

impl Texel for u16 {
    type Color = Rgb565;

    #[inline]
    fn color(self) -> Rgb565 {
        Rgb565::from(RawU16::new(self))
    }
}

macro_rules! colors_are_texels {
    ($($t:ident),*) => {$(
        impl Texel for $t {
            type Color = $t;

            #[inline]
            fn color(self) -> $t {
                self
            }
        }
    )*};
}

colors_are_texels!(
    Rgb555,
    Bgr555,
    Rgb565,
    Bgr565,
    Rgb666,
    Bgr666,
    Rgb888,
    Bgr888,
    Gray2,
    Gray4,
    Gray8,
    BinaryColor
);

/// A texture: `width × height` texels in a caller slice, row by row from the top, and
/// how coordinates outside `0..1` wrap.
///
/// Any size from 1×1 to 8192×8192 ([`MAX_DIMENSION`]) samples exactly
/// (`⌊u·W⌋ mod W` for repeat, by a multiply and a shift); power-of-two widths and
/// heights take shifts only. The slice may be longer than `width × height`: the rest
/// is not used.
///
/// ```
/// use embedded_graphics::pixelcolor::Gray8;
/// use zraster::{texture::{TexCoord, Texture}, Error};
///
/// let ramp = [Gray8::new(0), Gray8::new(85), Gray8::new(170)]; // 3×1: any size works
/// let tex = Texture::new(&ramp, 3, 1)?;
/// let at = |u: f64| tex.sample(TexCoord::new((u * 65536.0) as i32, 0));
/// assert_eq!([at(0.0), at(0.34), at(0.99), at(1.5)], [ramp[0], ramp[1], ramp[2], ramp[1]]);
/// assert_eq!(Texture::new(&ramp, 2, 2).unwrap_err(), Error::BufferTooSmall { needed: 4, got: 3 });
/// # Ok::<(), zraster::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Texture<'a, T> {
    /// Exactly `width × height` texels.
    texels: &'a [T],
    width: u16,
    height: u16,
    wrap: Wrap,
    /// Both sizes are powers of two: the texel index is shifts and an or.
    pow2: bool,
    /// log₂ width, and 16 − log₂ width and height (power-of-two sizes only).
    log2_width: u8,
    shift_u: u8,
    shift_v: u8,
    /// The first texel: what an index the checks rule out would read.
    first: T,
}

impl<'a, T: Texel> Texture<'a, T> {
    /// A texture of `width × height` texels from the start of `texels`, row by row from
    /// the top, repeating ([`Wrap::Repeat`]; see [`with_wrap`](Texture::with_wrap)).
    ///
    /// Errors: [`Error::ZeroSize`] for a width or height of 0, [`Error::TooLarge`] above
    /// [`MAX_DIMENSION`] (8192, where Q16 coordinates still give 8 steps a texel),
    /// [`Error::BufferTooSmall`] for a slice shorter than `width × height`. A `const fn`:
    /// a texture in flash can be a `const` too.
    pub const fn new(texels: &'a [T], width: u32, height: u32) -> Result<Self, Error> {
        if width == 0 || height == 0 {
            return Err(Error::ZeroSize);
        }
        if width > MAX_DIMENSION || height > MAX_DIMENSION {
            return Err(Error::TooLarge);
        }
        // ≤ 2²⁶: no overflow, on 16-bit `usize` neither (the slice could not be longer).
        let needed = width as usize * height as usize;
        if texels.len() < needed {
            return Err(Error::BufferTooSmall {
                needed,
                got: texels.len(),
            });
        }
        let texels = texels.split_at(needed).0;
        let first = match texels.first() {
            Some(t) => *t,
            None => return Err(Error::ZeroSize),
        };
        let pow2 = width.is_power_of_two() && height.is_power_of_two();
        let (lw, lh) = (width.trailing_zeros(), height.trailing_zeros());
        Ok(Texture {
            texels,
            width: width as u16,
            height: height as u16,
            wrap: Wrap::Repeat,
            pow2,
            log2_width: lw as u8,
            // Power-of-two sizes are at most 2¹³, so both shifts are 3..=16.
            shift_u: (UV_BITS - lw) as u8,
            shift_v: (UV_BITS - lh) as u8,
            first,
        })
    }

    /// The same texture with coordinates outside `0..1` wrapped by `wrap`.
    pub const fn with_wrap(self, wrap: Wrap) -> Self {
        Texture { wrap, ..self }
    }

    /// The width in texels.
    pub const fn width(&self) -> u32 {
        self.width as u32
    }

    /// The height in texels.
    pub const fn height(&self) -> u32 {
        self.height as u32
    }

    /// How coordinates outside `0..1` wrap.
    pub const fn wrap(&self) -> Wrap {
        self.wrap
    }

    /// The `width × height` texels, row by row from the top.
    pub const fn texels(&self) -> &'a [T] {
        self.texels
    }

    /// The texel at column `x`, row `y` (counted from the top), if inside.
    pub fn texel(&self, x: u32, y: u32) -> Option<T> {
        if x >= self.width() || y >= self.height() {
            return None;
        }
        self.texels
            .get(y as usize * self.width as usize + x as usize)
            .copied()
    }

    /// The index into [`texels`](Texture::texels) of the texel that `uv` samples
    /// (nearest): column `⌊u·W⌋`, row `⌊v·H⌋`, each wrapped. Always below
    /// `width × height`.
    #[inline]
    pub fn index(&self, uv: TexCoord) -> usize {
        let (u, v) = match self.wrap {
            // The low 16 bits: u mod 1, also for negative u (two's complement).
            Wrap::Repeat => (uv.u as u32 & 0xFFFF, uv.v as u32 & 0xFFFF),
            Wrap::Clamp => (uv.u.clamp(0, 0xFFFF) as u32, uv.v.clamp(0, 0xFFFF) as u32),
        };
        if self.pow2 {
            ((v >> self.shift_v) << self.log2_width | u >> self.shift_u) as usize
        } else {
            // u, v < 2¹⁶ and W, H ≤ 2¹³: each product below 2²⁹.
            let (w, h) = (u32::from(self.width), u32::from(self.height));
            (((v * h) >> UV_BITS) * w + ((u * w) >> UV_BITS)) as usize
        }
    }

    /// The stored texel that `uv` samples (nearest, wrapped).
    #[inline]
    pub fn sample_raw(&self, uv: TexCoord) -> T {
        // `index` is below width × height, the slice's length: the fallback is never read.
        self.texels
            .get(self.index(uv))
            .copied()
            .unwrap_or(self.first)
    }

    /// The colour that `uv` samples (nearest, wrapped).
    #[inline]
    pub fn sample(&self, uv: TexCoord) -> T::Color {
        self.sample_raw(uv).color()
    }

    /// The colour that `uv` samples, lit by intensity `i` (Q15) as a flat colour of
    /// the texel's value is ([`modulate`]), for pixel (x, y) of a display of colour
    /// type `C`.
    #[inline]
    pub fn lit<C: DisplayColor>(&self, uv: TexCoord, i: Intensity, x: i32, y: i32) -> C
    where
        T::Color: Into<Rgb888>,
    {
        modulate(self.sample(uv), i, x, y)
    }
}

/// A texel lit by intensity `i` (Q15, [`ONE`](crate::shade::ONE) is full), at pixel
/// (x, y) of a display of colour type `C`: the texel as `Rgb888`, lit as an `Rgb888`
/// material of that colour is (each channel times the intensity, rounded to the
/// display's depth; grey types by luma, dithered below 8 bits). The same light on a
/// flat face of the texel's colour gives the same pixel.
///
/// ```
/// use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
/// use zraster::shade::{Material, ONE};
/// use zraster::texture::modulate;
///
/// let texel = Rgb565::new(20, 40, 10);
/// let flat: Rgb565 = Rgb888::from(texel).shade(ONE / 2, 0, 0);
/// assert_eq!(modulate::<Rgb565>(texel, ONE / 2, 0, 0), flat);
/// assert_eq!(modulate::<Rgb565>(texel, ONE, 0, 0), texel); // full light: the texel
/// ```
#[inline]
pub fn modulate<C: DisplayColor>(texel: impl Into<Rgb888>, i: Intensity, x: i32, y: i32) -> C {
    C::lit(texel.into(), i, x, y)
}

/// How texture coordinates are interpolated across a face.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum UvMode {
    /// Perspective-correct: u/w, v/w and 1/w stepped along each row, an exact division
    /// every 16 pixels and at the row's last pixel, u and v stepped linearly between
    /// (within a bounded error, see [`PerspectiveSpan`]).
    #[default]
    Perspective,
    /// Affine: u and v stepped linearly across the screen triangle, no division. Exact
    /// for faces square to the view; faces at a slant swim.
    Affine,
}

/// What a textured draw needs besides the mesh: each vertex's texture coordinates (a
/// table beside the mesh's positions, as `obj2rust` writes it: `NAME_UVS`), the
/// texture, and how coordinates are interpolated (perspective-correct by default).
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb565;
/// use embedded_graphics::prelude::*;
/// use zraster::texture::{MeshUv, Texture};
/// use zraster::{math::{radians, Vec3}, mesh::{Mesh, Materials}, Camera, Viewport};
/// use zraster::{Frame, RenderOptions, Renderer, Texturing, UvMode};
///
/// // A square facing the camera, UVs 0..1 across it, and a 2×2 checker (raw RGB565).
/// const POSITIONS: [[i16; 3]; 4] = [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]];
/// const INDICES: [[u16; 3]; 2] = [[0, 1, 2], [0, 2, 3]];
/// const UVS: [MeshUv; 4] = [[0, 4096], [4096, 4096], [4096, 0], [0, 0]]; // v down
/// const CHECKER: [u16; 4] = [0xF800, 0x07E0, 0x001F, 0xFFFF]; // red green / blue white
/// let mesh = Mesh::triangles(&POSITIONS, 1.0, &INDICES, embedded_graphics::pixelcolor::Rgb888::BLACK);
/// let camera = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::default(), Vec3::Y)?
///     .perspective(radians(60.0), 0.5, 10.0, Viewport::new(32, 32)?)?;
/// let mut pixels = [Rgb565::BLACK; 32 * 32];
/// let mut depth = [0u16; 32 * 32];
/// let mut frame = Frame::new(&mut pixels, &mut depth, 32, 32)?;
/// frame.clear(Rgb565::BLACK);
/// let texturing = Texturing::new(&UVS, Texture::new(&CHECKER, 2, 2)?);
/// Renderer::new(&mesh, &camera, RenderOptions::default())?.draw_textured(&mut frame, &texturing)?;
/// // The top left quarter of the square is the top left texel, and so on.
/// assert_eq!(frame.color().pixel(12, 12), Some(Rgb565::RED));
/// assert_eq!(frame.color().pixel(19, 12), Some(Rgb565::GREEN));
/// assert_eq!(frame.color().pixel(12, 19), Some(Rgb565::BLUE));
/// assert_eq!(frame.color().pixel(19, 19), Some(Rgb565::WHITE));
/// # Ok::<(), zraster::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Texturing<'a, T> {
    /// One texture coordinate pair per mesh vertex (Q12, v down the image): at least as
    /// many as the mesh has vertices ([`Mesh::check_uvs`](crate::mesh::Mesh::check_uvs)).
    pub uvs: &'a [MeshUv],
    /// The texture.
    pub texture: Texture<'a, T>,
    /// How texture coordinates are interpolated across a face.
    pub mode: UvMode,
}

impl<'a, T: Texel> Texturing<'a, T> {
    /// `texture` placed on the mesh by `uvs`, perspective-correct.
    pub const fn new(uvs: &'a [MeshUv], texture: Texture<'a, T>) -> Self {
        Texturing {
            uvs,
            texture,
            mode: UvMode::Perspective,
        }
    }

    /// The same with coordinates interpolated by `mode`.
    pub const fn with_mode(self, mode: UvMode) -> Self {
        Texturing { mode, ..self }
    }
}

mod span;
pub use span::{AffineSpan, Homogeneous, PerspectiveSpan};

#[cfg(test)]
mod tests;
