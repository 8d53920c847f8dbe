//! Textured drawing: [`Renderer::draw_textured`] draws a mesh with texture coordinates
//! and a [`Texture`](crate::texture::Texture) with the Z-buffer, into the same three targets as
//! [`Renderer::draw`]: a [`Frame`], a [`WithDepth`] and [`Bands`]
//! ([`TexturedTarget`]).
//!
//! Coverage and depth are those of the untextured drawing (the same walk through
//! [`decide`], the same clipping, the same raster setup and depth rows), so a textured
//! mesh hides and is hidden by untextured ones exactly as it would be in flat colours.
//! Each pixel gets the texel at its centre's texture coordinates (nearest, wrapped as
//! the texture says), perspective-correct or affine ([`UvMode`]), lit by the shading of
//! the [`RenderOptions`] as a flat colour of the texel's value is lit
//! ([`modulate`](crate::texture::modulate)): flat (full light: the texel itself on a
//! display of its colour type), Lambert (the face's light) or Gouraud (the vertices'
//! light interpolated as [`fill_triangle_shaded`](crate::fill_triangle_shaded) does).
//! The faces' materials are not used.

use embedded_graphics::pixelcolor::Rgb888;

use super::walk::Corner;
use super::*;
use crate::buffer::{AfterBand, Bands, Frame};
#[cfg(doc)]
use crate::fill::UvMode;
use crate::fill::{fill_textured_buffers, fill_textured_runs, TexCorners};
use crate::raster::SpanStats;
use crate::shade::DisplayColor;
use crate::shader::{Fragment, PixelShader};
pub use crate::texture::Texturing;
use crate::texture::{MeshUv, TexCoord, Texel, UV_LIMIT};
use crate::DepthTest;

/// A corner of a textured triangle: its outcode and screen position (as the untextured
/// walk has them), clip w, texture coordinates and Gouraud light.
#[derive(Clone, Copy)]
struct TexVertex {
    index: u16,
    code: u8,
    screen: ScreenVertex,
    w: i64,
    uv: TexCoord,
    light: Intensity,
}

impl Corner for TexVertex {
    #[inline(always)]
    fn needs_clip(&self) -> bool {
        self.code != 0
    }
    #[inline(always)]
    fn code(&self) -> u8 {
        self.code
    }
    #[inline(always)]
    fn xy(&self) -> (i32, i32) {
        (self.screen.x(), self.screen.y())
    }
}

/// Something [`Renderer::draw_textured`] and [`Renderer::draw_with_shader`] draw
/// into: a [`Frame`], a [`WithDepth`] or [`Bands`], as for [`Renderer::draw`]
/// ([`DepthTarget`]). Sealed.
pub trait TexturedTarget: sealed::Sealed {
    /// The target's pixel colour.
    type Color: DisplayColor;
    /// What drawing into it can fail with besides bad input.
    type Error;

    /// Draw `renderer`'s mesh textured by `texturing` (what
    /// [`Renderer::draw_textured`] calls).
    #[doc(hidden)]
    fn draw_textured_mesh<M: Copy, S: RenderState, X>(
        &mut self,
        renderer: &mut Renderer<'_, '_, M, S>,
        texturing: &Texturing<'_, X>,
    ) -> Result<(), DrawError<Self::Error>>
    where
        X: Texel,
        X::Color: Into<Rgb888> + 'static,
        Self::Color: 'static;

    /// Draw `renderer`'s mesh coloured by `shader` (what
    /// [`Renderer::draw_with_shader`] calls).
    #[doc(hidden)]
    fn draw_shaded_mesh<M: Copy, S: RenderState, P: PixelShader<Self::Color, M>>(
        &mut self,
        renderer: &mut Renderer<'_, '_, M, S>,
        shader: &P,
    ) -> Result<(), DrawError<Self::Error>>;
}

impl<C: DisplayColor> TexturedTarget for Frame<'_, C> {
    type Color = C;
    type Error = core::convert::Infallible;

    fn draw_textured_mesh<M: Copy, S: RenderState, X>(
        &mut self,
        renderer: &mut Renderer<'_, '_, M, S>,
        texturing: &Texturing<'_, X>,
    ) -> Result<(), DrawError<Self::Error>>
    where
        X: Texel,
        X::Color: Into<Rgb888> + 'static,
        C: 'static,
    {
        let (color, depth) = self.parts_mut();
        renderer
            .draw_textured_buffers(color, depth, texturing)
            .map_err(DrawError::Input)
    }

    fn draw_shaded_mesh<M: Copy, S: RenderState, P: PixelShader<C, M>>(
        &mut self,
        renderer: &mut Renderer<'_, '_, M, S>,
        shader: &P,
    ) -> Result<(), DrawError<Self::Error>> {
        let (color, depth) = self.parts_mut();
        renderer
            .draw_shaded_buffers(color, depth, shader)
            .map_err(DrawError::Input)
    }
}

impl<D: DrawTarget> TexturedTarget for WithDepth<'_, '_, D>
where
    D::Color: DisplayColor,
{
    type Color = D::Color;
    type Error = D::Error;

    fn draw_textured_mesh<M: Copy, S: RenderState, X>(
        &mut self,
        renderer: &mut Renderer<'_, '_, M, S>,
        texturing: &Texturing<'_, X>,
    ) -> Result<(), DrawError<Self::Error>>
    where
        X: Texel,
        X::Color: Into<Rgb888> + 'static,
        D::Color: 'static,
    {
        let (display, zbuf) = self.parts();
        let texture = texturing.texture;
        let mode = texturing.mode;
        renderer.draw_attr_runs(display, zbuf, Some(texturing.uvs), |t, z, c, f| {
            fill_textured_runs(t, z, c.clip, c.test, c.tri, c.corners, &texture, mode, f.1)
        })
    }

    fn draw_shaded_mesh<M: Copy, S: RenderState, P: PixelShader<D::Color, M>>(
        &mut self,
        renderer: &mut Renderer<'_, '_, M, S>,
        shader: &P,
    ) -> Result<(), DrawError<Self::Error>> {
        let (display, zbuf) = self.parts();
        let uvs = shader.uvs();
        let mode = uvs.map(|(_, m)| m);
        renderer.draw_attr_runs(display, zbuf, uvs.map(|(u, _)| u), |t, z, c, (m, light)| {
            let shade = |x, y, depth, uv, light| {
                shader.shade(&Fragment {
                    x,
                    y,
                    depth,
                    uv,
                    light,
                    material: m,
                })
            };
            c.corners
                .fill_shaded_runs(t, z, c.clip, c.test, c.tri, mode, light, shade)
        })
    }
}

/// Band by band, every band walking the whole mesh (textured faces are not binned:
/// [`Renderer::binning`] keeps what the last untextured banded draw said).
impl<D, F> TexturedTarget for Bands<'_, '_, D, F>
where
    D: DrawTarget,
    D::Color: DisplayColor,
    F: AfterBand<D::Color>,
{
    type Color = D::Color;
    type Error = D::Error;

    fn draw_textured_mesh<M: Copy, S: RenderState, X>(
        &mut self,
        renderer: &mut Renderer<'_, '_, M, S>,
        texturing: &Texturing<'_, X>,
    ) -> Result<(), DrawError<Self::Error>>
    where
        X: Texel,
        X::Color: Into<Rgb888> + 'static,
        D::Color: 'static,
    {
        each_band(self, |color, zbuf| {
            renderer.draw_textured_buffers(color, zbuf, texturing)
        })
    }

    fn draw_shaded_mesh<M: Copy, S: RenderState, P: PixelShader<D::Color, M>>(
        &mut self,
        renderer: &mut Renderer<'_, '_, M, S>,
        shader: &P,
    ) -> Result<(), DrawError<Self::Error>> {
        each_band(self, |color, zbuf| {
            renderer.draw_shaded_buffers(color, zbuf, shader)
        })
    }
}

/// Each band of `bands` cleared, drawn by `draw` and handed to the display.
fn each_band<D, F>(
    bands: &mut Bands<'_, '_, D, F>,
    mut draw: impl FnMut(&mut ColorBuffer<'_, D::Color>, &mut ZBuffer<'_>) -> Result<(), Error>,
) -> Result<(), DrawError<D::Error>>
where
    D: DrawTarget,
    F: AfterBand<D::Color>,
{
    let buffers = &mut *bands.buffers;
    let (w, rows, height) = (buffers.width, buffers.rows, buffers.height);
    for k in 0..buffers.bands() {
        let y0 = k * rows;
        let n = rows.min(height - y0);
        let mut color = ColorBuffer::new_band(&mut *buffers.color, w, n, y0 as i32)?;
        let mut zbuf = ZBuffer::new_band(&mut *buffers.depth, w, n, y0 as i32)?;
        crate::num::fill(color.data_mut(), bands.background);
        zbuf.clear();
        draw(&mut color, &mut zbuf)?;
        bands.after.after(&mut color, &zbuf);
        color.flush(bands.display)?;
    }
    Ok(())
}

/// One triangle to fill, as [`Renderer::draw_attr_buffers`] and [`Renderer::draw_attr_runs`]
/// hand it over: where it may draw, its depth test, its corners.
struct ToFill<'a> {
    clip: &'a Clip,
    test: DepthTest,
    tri: &'a [ScreenVertex; 3],
    corners: &'a TexCorners,
}

impl<'m, 'c, M: Copy, S: RenderState> Renderer<'m, 'c, M, S> {
    /// Draw the mesh with the Z-buffer into `target`, textured: `texturing`'s texture
    /// placed by its texture coordinates (one per vertex), interpolated
    /// perspective-correctly (or affinely, see [`UvMode`]), nearest texel at each pixel
    /// centre, lit by the options' shading as a flat colour of the texel's value would
    /// be. The faces' materials are not used; coverage and depth are those of
    /// [`draw`](Renderer::draw), so textured and untextured meshes share a Z-buffer
    /// as meshes do.
    ///
    /// With [`Shading::Flat`] a pixel is the texel at column ⌊u·W⌋ mod W and row
    /// ⌊v·H⌋ mod H (repeat; v down the image, as [`MeshUv`] has it), u and v taken at the
    /// pixel's centre, converted to the display's colour type (on a display of the
    /// texel's own type, the texel itself).
    ///
    /// A corner's texture coordinates within the [`MeshUv`] range (±8 textures) are
    /// used as they are; interpolated ones (clipping at the near plane) are clamped to
    /// ±[`UV_LIMIT`] (NaN, which only a broken transform could give, counts as 0).
    ///
    /// Errors: [`Error::InvalidParameter`] when `texturing.uvs` is shorter than the
    /// vertex table ([`Mesh::check_uvs`](crate::mesh::Mesh::check_uvs)), and those of
    /// [`draw`](Renderer::draw).
    pub fn draw_textured<T, X>(
        &mut self,
        target: &mut T,
        texturing: &Texturing<'_, X>,
    ) -> Result<(), DrawError<T::Error>>
    where
        T: TexturedTarget,
        T::Color: 'static,
        X: Texel,
        X::Color: Into<Rgb888> + 'static,
    {
        self.mesh
            .check_uvs(texturing.uvs)
            .map_err(DrawError::Input)?;
        target.draw_textured_mesh(self, texturing)
    }

    /// Draw the mesh with the Z-buffer into `target`, each pixel that passes the depth
    /// test coloured by `shader` (see [`shader`](crate::shader)): coverage, depth and
    /// clipping are those of [`draw`](Renderer::draw), the targets those of
    /// [`draw_textured`](Renderer::draw_textured). The [`Fragment`] has the pixel's
    /// position and depth, the face's material, the light of the options' shading and,
    /// when the shader has a UV table ([`PixelShader::uvs`]), the texture coordinates
    /// interpolated as [`draw_textured`](Renderer::draw_textured) does.
    ///
    /// The shader is a type parameter: its `shade` is inlined into its own pixel loop.
    ///
    /// Every face is drawn opaque, writing depth, whatever its material's
    /// [`alpha`](crate::shade::Material::alpha): see-through faces
    /// ([`Translucent`](crate::shade::Translucent)) are blended by
    /// [`draw`](Renderer::draw) and [`Scene`](crate::Scene) only (as textured faces are
    /// drawn opaque by [`draw_textured`](Renderer::draw_textured)).
    ///
    /// Errors: [`Error::InvalidParameter`] when the shader's UV table is shorter than
    /// the vertex table, and those of [`draw`](Renderer::draw).
    pub fn draw_with_shader<T, P>(
        &mut self,
        target: &mut T,
        shader: &P,
    ) -> Result<(), DrawError<T::Error>>
    where
        T: TexturedTarget,
        P: PixelShader<T::Color, M>,
    {
        if let Some((uvs, _)) = shader.uvs() {
            self.mesh.check_uvs(uvs).map_err(DrawError::Input)?;
        }
        target.draw_shaded_mesh(self, shader)
    }

    /// [`draw_textured`](Renderer::draw_textured) into a colour buffer and a Z-buffer.
    pub(crate) fn draw_textured_buffers<C, X>(
        &mut self,
        frame: &mut ColorBuffer<'_, C>,
        zbuf: &mut ZBuffer<'_>,
        texturing: &Texturing<'_, X>,
    ) -> Result<(), Error>
    where
        C: DisplayColor + 'static,
        X: Texel,
        X::Color: Into<Rgb888> + 'static,
    {
        let (texture, mode) = (&texturing.texture, texturing.mode);
        self.draw_attr_buffers(frame, zbuf, Some(texturing.uvs), |fr, z, c, (_, light)| {
            fill_textured_buffers(
                fr, z, c.clip, c.test, c.tri, c.corners, texture, mode, light,
            )
        })
    }

    /// [`draw_with_shader`](Renderer::draw_with_shader) into a colour buffer and a
    /// Z-buffer.
    pub(crate) fn draw_shaded_buffers<C, P>(
        &mut self,
        frame: &mut ColorBuffer<'_, C>,
        zbuf: &mut ZBuffer<'_>,
        shader: &P,
    ) -> Result<(), Error>
    where
        C: DisplayColor,
        P: PixelShader<C, M>,
    {
        let uvs = shader.uvs();
        let mode = uvs.map(|(_, m)| m);
        self.draw_attr_buffers(frame, zbuf, uvs.map(|(u, _)| u), |fr, z, c, (m, light)| {
            let shade = |x, y, depth, uv, light| {
                shader.shade(&Fragment {
                    x,
                    y,
                    depth,
                    uv,
                    light,
                    material: m,
                })
            };
            c.corners
                .fill_shaded_buffers(fr, z, c.clip, c.test, c.tri, mode, light, shade)
        })
    }

    /// Each triangle of the mesh (with texture coordinates from `uvs`, if any) filled
    /// by `fill` into a colour buffer and a Z-buffer, with its face's material and its
    /// corners' lights; the counts recorded.
    fn draw_attr_buffers<C: PixelColor>(
        &mut self,
        frame: &mut ColorBuffer<'_, C>,
        zbuf: &mut ZBuffer<'_>,
        uvs: Option<&[MeshUv]>,
        mut fill: impl FnMut(
            &mut ColorBuffer<'_, C>,
            &mut ZBuffer<'_>,
            &ToFill<'_>,
            (M, [Intensity; 3]),
        ) -> SpanStats,
    ) -> Result<(), Error> {
        let clip = clip_of(frame, zbuf);
        let test = S::depth_test(zbuf.test());
        let first = !self.counted;
        let mut pixels = FrameStats::default();
        let geometry = self
            .for_each_textured::<core::convert::Infallible>(
                uvs,
                &clip,
                first,
                |tri, corners, lights, m| {
                    let c = ToFill {
                        clip: &clip,
                        test,
                        tri,
                        corners,
                    };
                    pixels.add_pixels(fill(frame, zbuf, &c, (m, lights)));
                    Ok(())
                },
            )
            .map_err(|e| match e {
                DrawError::Input(e) => e,
                DrawError::Target(never) => match never {},
            })?;
        self.count(geometry);
        self.stats.add_pixel_counts(&pixels);
        Ok(())
    }

    /// [`draw_attr_buffers`](Renderer::draw_attr_buffers) into a draw target through a Z-buffer.
    fn draw_attr_runs<D: DrawTarget>(
        &mut self,
        target: &mut D,
        zbuf: &mut ZBuffer<'_>,
        uvs: Option<&[MeshUv]>,
        mut fill: impl FnMut(
            &mut D,
            &mut ZBuffer<'_>,
            &ToFill<'_>,
            (M, [Intensity; 3]),
        ) -> Result<SpanStats, D::Error>,
    ) -> Result<(), DrawError<D::Error>> {
        let clip = clip_of(target, zbuf);
        let test = S::depth_test(zbuf.test());
        let first = !self.counted;
        let mut pixels = FrameStats::default();
        let geometry = self.for_each_textured(uvs, &clip, first, |tri, corners, lights, m| {
            let c = ToFill {
                clip: &clip,
                test,
                tri,
                corners,
            };
            let s = fill(target, zbuf, &c, (m, lights)).map_err(DrawError::Target)?;
            pixels.add_pixels(s);
            Ok(())
        })?;
        self.count(geometry);
        self.stats.add_pixel_counts(&pixels);
        Ok(())
    }

    /// Vertex `i` of face `f` for textured drawing: transformed, classified and
    /// projected as [`project_vertex`](Renderer::project_vertex) does, with its clip w,
    /// texture coordinates and Gouraud light.
    fn tex_vertex(&self, i: u16, f: usize, uvs: Option<&[MeshUv]>) -> Result<TexVertex, Error> {
        let bad = || Error::IndexOutOfRange {
            face: f,
            index: usize::from(i),
        };
        let p = self.mesh.positions.get(usize::from(i)).ok_or_else(bad)?;
        let uv = match uvs {
            Some(uvs) => TexCoord::from_mesh(*uvs.get(usize::from(i)).ok_or_else(bad)?),
            None => TexCoord::default(),
        };
        let c = self.fixed.apply(p);
        let (code, screen) = if crate::num::INTEGER_PROJECTION {
            self.map.project_fixed(&c)
        } else {
            self.map.project_float(c.to_f32())
        };
        let light = if self.shading() == Shading::Gouraud {
            self.vertex_light(usize::from(i))
        } else {
            ONE
        };
        Ok(TexVertex {
            index: i,
            code,
            screen,
            w: c.zw().1,
            uv,
            light,
        })
    }

    /// [`for_each_triangle`](Renderer::for_each_triangle) for textured drawing: every
    /// triangle that survives clipping and culling (the same decisions, the same counts),
    /// with its corners' texture attributes; clipping interpolates texture coordinates
    /// with the other attributes in clip space.
    pub(crate) fn for_each_textured<E>(
        &self,
        uvs: Option<&[MeshUv]>,
        clip: &Clip,
        first: bool,
        mut emit: impl FnMut(
            &[ScreenVertex; 3],
            &TexCorners,
            [Intensity; 3],
            M,
        ) -> Result<(), DrawError<E>>,
    ) -> Result<FrameStats, DrawError<E>> {
        let mut st = FrameStats::default();
        let cull = self.options.cull;
        let rows = (!first).then(|| clip.subpixel_rows());
        for f in 0..self.mesh.face_count() {
            let (vs, material) = self.face(f)?;
            for (i0, i1, i2) in fan(vs) {
                let v0 = self.tex_vertex(i0, f, uvs)?;
                let v1 = self.tex_vertex(i1, f, uvs)?;
                let v2 = self.tex_vertex(i2, f, uvs)?;
                let seen = decide([&v0, &v1, &v2], rows, cull);
                seen.count(&mut st);
                if seen == Seen::Front {
                    let tri = [v0.screen, v1.screen, v2.screen];
                    let corners = TexCorners {
                        w: [v0.w, v1.w, v2.w],
                        uv: [v0.uv, v1.uv, v2.uv],
                    };
                    let lights = self.corner_lights(f, [v0.light, v1.light, v2.light]);
                    emit(&tri, &corners, lights, material)?;
                }
                if seen != Seen::Clip {
                    continue;
                }
                st.triangles_in += 1;
                st.clipped += 1;
                let mut poly = ClipPolygon::new();
                for v in [&v0, &v1, &v2] {
                    let p = self.mesh.positions.get(usize::from(v.index)).ok_or(
                        Error::IndexOutOfRange {
                            face: f,
                            index: usize::from(v.index),
                        },
                    )?;
                    let _ = poly.push(ClipVertex {
                        c: self.clip_coords(p),
                        light: f32::from(v.light),
                        uv: [v.uv.u as f32, v.uv.v as f32],
                    });
                }
                clip_polygon(&mut poly, v0.code | v1.code | v2.code);
                let mut out: heapless::Vec<TexVertex, { crate::geometry::clip::MAX_CLIPPED }> =
                    heapless::Vec::new();
                let lim = UV_LIMIT as f32;
                for c in &poly {
                    if let Some(s) = self.map.project(&c.c) {
                        // Saturating casts; NaN is 0.
                        let _ = out.push(TexVertex {
                            index: 0,
                            code: 0,
                            screen: s,
                            w: (c.c[3] as i64).max(1),
                            uv: TexCoord::new(
                                c.uv[0].clamp(-lim, lim) as i32,
                                c.uv[1].clamp(-lim, lim) as i32,
                            ),
                            light: crate::shade::to_intensity(c.light / f32::from(ONE)),
                        });
                    }
                }
                let Some((a, rest)) = out.split_first() else {
                    continue;
                };
                for pair in rest.windows(2) {
                    let &[b, c] = pair else { continue };
                    let tri = [a.screen, b.screen, c.screen];
                    let p = |v: &ScreenVertex| (v.x(), v.y());
                    if cull.drops(signed_area_guarded(p(&tri[0]), p(&tri[1]), p(&tri[2]))) {
                        continue;
                    }
                    st.drawn += 1;
                    let corners = TexCorners {
                        w: [a.w, b.w, c.w],
                        uv: [a.uv, b.uv, c.uv],
                    };
                    let lights = self.corner_lights(f, [a.light, b.light, c.light]);
                    emit(&tri, &corners, lights, material)?;
                }
            }
        }
        Ok(st)
    }
}
