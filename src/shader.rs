//! Pixel shaders: your code colours each pixel of a mesh.
//!
//! [`Renderer::draw_with_shader`](crate::Renderer::draw_with_shader) draws a mesh with
//! the Z-buffer as [`draw`](crate::Renderer::draw) does (the same coverage, depth,
//! clipping and targets) and asks a [`PixelShader`] for the colour of every pixel that
//! passes the depth test, handing it a [`Fragment`]: the pixel's position, its depth,
//! its perspective-correct texture coordinates (when the shader names a UV table), the
//! light of the options' shading (full, the face's, or the vertices' interpolated) and
//! the face's material. Procedural patterns, fog, depth cueing, textures with a twist.
//!
//! The shader is a type parameter, so each shader gets its own copy of the pixel loop
//! with its `shade` inlined: no `dyn`, no function pointer per pixel, and the built-in
//! drawing ([`draw`](crate::Renderer::draw),
//! [`draw_textured`](crate::Renderer::draw_textured)) does not change at all when no
//! shader is used. A closure `Fn(&Fragment<M>) -> C` is a shader.
//!
//! Ready-made: [`Lit`] (the material lit, as `draw` colours it), [`Textured`] (the
//! texel lit, as `draw_textured` colours it), [`Fog`] (any shader's colour faded
//! towards a fog colour with the depth), and [`WithUvs`] (a closure given a UV table).
//!
//! ```
//! use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
//! use embedded_graphics::prelude::*;
//! use zraster::shader::Fragment;
//! use zraster::{math::{radians, Vec3}, mesh::CUBE, Camera, Frame, RenderOptions, Renderer, Viewport};
//!
//! let camera = Camera::look_at(Vec3::new(2.0, 1.5, 3.0), Vec3::new(0.5, 0.5, 0.5), Vec3::Y)?
//!     .perspective(radians(40.0), 0.5, 10.0, Viewport::new(32, 32)?)?;
//! let (mut pixels, mut depth) = ([Rgb565::BLACK; 32 * 32], [0u16; 32 * 32]);
//! let mut frame = Frame::new(&mut pixels, &mut depth, 32, 32)?;
//! frame.clear(Rgb565::BLACK);
//! // Stripes: every other column of the cube white, the others red.
//! let stripes = |f: &Fragment<Rgb888>| if f.x % 2 == 0 { Rgb565::WHITE } else { Rgb565::RED };
//! Renderer::new(&CUBE, &camera, RenderOptions::default())?.draw_with_shader(&mut frame, &stripes)?;
//! assert_eq!(frame.color().pixel(16, 16), Some(Rgb565::WHITE));
//! assert_eq!(frame.color().pixel(17, 16), Some(Rgb565::RED));
//! assert_eq!(frame.color().pixel(0, 0), Some(Rgb565::BLACK)); // not covered
//! # Ok::<(), zraster::Error>(())
//! ```

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};

use crate::fill::UvMode;
use crate::shade::{DisplayColor, Intensity, Material, ONE};
use crate::texture::{MeshUv, TexCoord, Texel, Texture, Texturing};
use crate::Error;

/// What a [`PixelShader`] knows about a pixel that passed the depth test.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Fragment<M = Rgb888> {
    /// The pixel's column on the display.
    pub x: i32,
    /// The pixel's row on the display.
    pub y: i32,
    /// The depth written to the Z-buffer: 0 at the near plane, 65535 at the far one (as
    /// [`ZBuffer`](crate::ZBuffer) stores it; not linear in the distance under
    /// perspective).
    pub depth: u16,
    /// The texture coordinates at the pixel's centre (Q16, [`UV_ONE`](crate::texture::UV_ONE)
    /// is one texture, v down), interpolated as the shader's [`uvs`](PixelShader::uvs)
    /// say; `(0, 0)` for a shader without.
    pub uv: TexCoord,
    /// The light at the pixel (Q15, [`ONE`] is full): [`ONE`] under
    /// [`Shading::Flat`](crate::shade::Shading::Flat), the face's light under Lambert,
    /// the vertices' lights interpolated under Gouraud.
    pub light: Intensity,
    /// The face's material (its colour in the mesh).
    pub material: M,
}

/// The colour of each pixel of a mesh, from what is known about it ([`Fragment`]).
///
/// `C` is the display's colour type, `M` the mesh's material type (`Rgb888` for
/// meshes of colours). Any `Fn(&Fragment<M>) -> C` is a shader without texture
/// coordinates; give it a UV table with [`WithUvs`].
pub trait PixelShader<C, M = Rgb888> {
    /// The texture coordinates of each mesh vertex (Q12, v down, at least one per
    /// vertex) and how to interpolate them, or `None` (the default): then they are not
    /// interpolated at all and every fragment's `uv` is `(0, 0)`.
    #[inline]
    fn uvs(&self) -> Option<(&[MeshUv], UvMode)> {
        None
    }

    /// The colour of the pixel `f`.
    fn shade(&self, f: &Fragment<M>) -> C;
}

impl<C, M, F: Fn(&Fragment<M>) -> C> PixelShader<C, M> for F {
    #[inline(always)]
    fn shade(&self, f: &Fragment<M>) -> C {
        self(f)
    }
}

/// A shader given texture coordinates: `shader` sees each pixel's `uv` interpolated
/// from `uvs` (one per mesh vertex, Q12), perspective-correct unless
/// [`with_mode`](WithUvs::with_mode) says otherwise.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WithUvs<'a, S> {
    /// One texture coordinate pair per mesh vertex.
    pub uvs: &'a [MeshUv],
    /// How they are interpolated.
    pub mode: UvMode,
    /// The shader.
    pub shader: S,
}

impl<'a, S> WithUvs<'a, S> {
    /// `shader` with the texture coordinates `uvs`, perspective-correct.
    pub const fn new(uvs: &'a [MeshUv], shader: S) -> Self {
        WithUvs {
            uvs,
            mode: UvMode::Perspective,
            shader,
        }
    }

    /// The same, interpolated by `mode`.
    pub fn with_mode(self, mode: UvMode) -> Self {
        WithUvs { mode, ..self }
    }
}

impl<C, M, S: PixelShader<C, M>> PixelShader<C, M> for WithUvs<'_, S> {
    #[inline]
    fn uvs(&self) -> Option<(&[MeshUv], UvMode)> {
        Some((self.uvs, self.mode))
    }

    #[inline(always)]
    fn shade(&self, f: &Fragment<M>) -> C {
        self.shader.shade(f)
    }
}

/// The face's material lit by the fragment's light: the colour
/// [`draw`](crate::Renderer::draw) gives the pixel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub struct Lit;

impl<C, M: Material<C>> PixelShader<C, M> for Lit {
    #[inline(always)]
    fn shade(&self, f: &Fragment<M>) -> C {
        f.material.shade(f.light, f.x, f.y)
    }
}

/// A texture's texel at the fragment's texture coordinates, lit by its light as a flat
/// colour of the texel's value is ([`modulate`](crate::texture::modulate)): the colour
/// [`draw_textured`](crate::Renderer::draw_textured) gives the pixel. (A
/// [`Texturing`] converts into one.)
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Textured<'a, T> {
    /// One texture coordinate pair per mesh vertex (Q12, v down).
    pub uvs: &'a [MeshUv],
    /// The texture.
    pub texture: Texture<'a, T>,
    /// How texture coordinates are interpolated.
    pub mode: UvMode,
}

impl<'a, T: Texel> Textured<'a, T> {
    /// `texture` placed on the mesh by `uvs`, perspective-correct.
    pub const fn new(uvs: &'a [MeshUv], texture: Texture<'a, T>) -> Self {
        Textured {
            uvs,
            texture,
            mode: UvMode::Perspective,
        }
    }

    /// The same with coordinates interpolated by `mode`.
    pub const fn with_mode(self, mode: UvMode) -> Self {
        Textured { mode, ..self }
    }
}

impl<C, M, T> PixelShader<C, M> for Textured<'_, T>
where
    C: DisplayColor + 'static,
    T: Texel,
    T::Color: Into<Rgb888> + 'static,
{
    #[inline]
    fn uvs(&self) -> Option<(&[MeshUv], UvMode)> {
        Some((self.uvs, self.mode))
    }

    #[inline(always)]
    fn shade(&self, f: &Fragment<M>) -> C {
        let c = self.texture.sample(f.uv);
        // At full light on an undithered display of the texel's own colour type, the
        // texel itself (the same colour, without the way through Rgb888; the type test
        // is decided at compile time); of another type, lit by the full light's folded
        // rounding (an Rgb888 under fog: the texel's channels themselves; ARMv6-M's
        // figures are better without the branch).
        if f.light == ONE {
            if !C::DITHERED {
                if let Some(&same) = (&c as &dyn core::any::Any).downcast_ref::<C>() {
                    return same;
                }
            }
            if !crate::num::ARMV6M {
                return C::lit_full(c.into(), f.x, f.y);
            }
        }
        C::lit(c.into(), f.light, f.x, f.y)
    }
}

/// Fog: the colour of another shader faded towards a fog colour linearly in the depth,
/// none at depth `near` and nearer, all of it at `far` and beyond. Towards black it is
/// the classic depth cueing.
///
/// At depth z the fog's share t (in 1/256) is 0 up to `near`, 256 from `far` on, and
/// between `⌊(z − near)·R / 2¹⁶⌋` with `R = ⌊2²⁴ / (far − near)⌋`: 256·(z − near)/(far −
/// near) by a multiply (no division per pixel; at most one below the exact quotient's
/// floor). Each channel of the inner shader's `Rgb888` colour `c` becomes
/// `(c·(256 − t) + fog·t + 128) / 256` (floored), then the display's colour type (as
/// an `Rgb888` material at full light: dithered on dithered types).
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb888;
/// use embedded_graphics::prelude::*;
/// use zraster::shader::{Fog, Fragment, PixelShader};
/// use zraster::texture::TexCoord;
///
/// let red = |_: &Fragment| Rgb888::RED;
/// let fog = Fog::from_depths(red, 1000, 3000, Rgb888::WHITE)?;
/// let at = |depth| {
///     let f = Fragment { x: 0, y: 0, depth, uv: TexCoord::default(), light: 0, material: Rgb888::BLACK };
///     PixelShader::<Rgb888>::shade(&fog, &f)
/// };
/// assert_eq!(at(500), Rgb888::RED);
/// assert_eq!(at(2000), Rgb888::new(255, 127, 127)); // half way: t = ⌊1000·8388 / 2¹⁶⌋ = 127
/// assert_eq!(at(9000), Rgb888::WHITE);
/// assert!(Fog::new(red, f32::NAN, 0.9, Rgb888::WHITE).is_err());
/// # Ok::<(), zraster::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Fog<S> {
    inner: S,
    near: u16,
    /// far − near, at least 1.
    range: u16,
    /// ⌊2²⁴ / range⌋.
    recip: u32,
    color: Rgb888,
}

impl<S> Fog<S> {
    /// Fog over `inner` from window depth `near` to `far` (0 is the camera's near
    /// plane, 1 its far plane, as the Z-buffer's 0..=65535), towards `color`.
    ///
    /// Errors: [`Error::NotFinite`] for a NaN or infinite depth,
    /// [`Error::InvalidParameter`] unless 0 ≤ near < far ≤ 1 (once in Z-buffer units).
    pub fn new(inner: S, near: f32, far: f32, color: Rgb888) -> Result<Self, Error> {
        if !near.is_finite() || !far.is_finite() {
            return Err(Error::NotFinite);
        }
        if !(0.0..=1.0).contains(&near) || !(0.0..=1.0).contains(&far) {
            return Err(Error::InvalidParameter("fog depths must lie in 0..=1"));
        }
        // In 0..=65535: the casts are exact.
        let to_depth = |d: f32| (d * 65535.0 + 0.5) as u16;
        Fog::from_depths(inner, to_depth(near), to_depth(far), color)
    }

    /// Fog over `inner` from Z-buffer depth `near` to `far` (0..=65535), towards `color`.
    ///
    /// Errors: [`Error::InvalidParameter`] unless `near < far`.
    pub fn from_depths(inner: S, near: u16, far: u16, color: Rgb888) -> Result<Self, Error> {
        if near >= far {
            return Err(Error::InvalidParameter("fog needs near < far"));
        }
        let range = far - near;
        Ok(Fog {
            inner,
            near,
            range,
            recip: (1 << 24) / u32::from(range),
            color,
        })
    }

    /// The fog's share at Z-buffer depth `depth`, in 1/256: 0 at `near` and nearer, 256
    /// at `far` and beyond, `⌊(depth − near)·⌊2²⁴ / (far − near)⌋ / 2¹⁶⌋` between.
    #[inline]
    pub fn amount(&self, depth: u16) -> u32 {
        let d = depth.saturating_sub(self.near);
        if d >= self.range {
            return 256;
        }
        // d < range: d·R < 2²⁴, and the share below 256.
        (u32::from(d) * self.recip) >> 16
    }

    /// `c` with the fog's share `t` (in 1/256) of the fog colour.
    #[inline]
    fn blend(&self, c: Rgb888, t: u32) -> Rgb888 {
        let mix = |a: u8, b: u8| ((u32::from(a) * (256 - t) + u32::from(b) * t + 128) >> 8) as u8;
        let f = self.color;
        Rgb888::new(mix(c.r(), f.r()), mix(c.g(), f.g()), mix(c.b(), f.b()))
    }
}

impl<C, M, S> PixelShader<C, M> for Fog<S>
where
    C: DisplayColor,
    S: PixelShader<Rgb888, M>,
{
    #[inline]
    fn uvs(&self) -> Option<(&[MeshUv], UvMode)> {
        self.inner.uvs()
    }

    #[inline]
    fn shade(&self, f: &Fragment<M>) -> C {
        let c = self.blend(self.inner.shade(f), self.amount(f.depth));
        C::lit(c, ONE, f.x, f.y)
    }
}

impl<'a, T: Texel> From<Texturing<'a, T>> for Textured<'a, T> {
    fn from(t: Texturing<'a, T>) -> Self {
        Textured {
            uvs: t.uvs,
            texture: t.texture,
            mode: t.mode,
        }
    }
}
