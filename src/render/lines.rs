//! Line renderers: hidden-line removal against a depth-only pass, and wireframe.

use super::*;

impl<'m, 'c, M: Copy, S: RenderState> Renderer<'m, 'c, M, S> {
    /// Hidden-line removal: the edges of the faces that survive culling, drawn in
    /// `color` only where no surface is in front of them.
    ///
    /// The surfaces go into `zbuf` first (depth only, nothing drawn); then each face's
    /// polygon edges (not the fan's inner diagonals) are depth-tested against it with a
    /// tolerance of the face's depth slope, so that an edge wins against its own faces.
    pub fn draw_hidden_line<D: DrawTarget>(
        &mut self,
        target: &mut D,
        zbuf: &mut ZBuffer<'_>,
        color: D::Color,
    ) -> Result<(), DrawError<D::Error>> {
        let clip = clip_of(target, zbuf);
        let first = !self.counted;
        let mut pixels = FrameStats::default();
        // Pass 1: depth only.
        let geometry =
            self.for_each_triangle(&clip, first, 0..self.mesh.face_count(), |_, _, tri, _| {
                let s = depth_runs::<S, D::Error>(Some(&mut *zbuf), tri, &clip, |_, _, _| Ok(()))
                    .map_err(DrawError::Target)?;
                pixels.pixels_tested += u64::from(s.pixels_tested);
                Ok(())
            })?;
        self.count(geometry);
        // Pass 2: the edges of faces that are not culled.
        for f in 0..self.mesh.face_count() {
            let (vs, _) = self.face(f)?;
            let mut visible = false;
            let mut bias = 1u16;
            for (i0, i1, i2) in fan(vs) {
                let (v0, v1, v2) = (self.fetch(i0, f)?, self.fetch(i1, f)?, self.fetch(i2, f)?);
                match decide([&v0, &v1, &v2], None, self.options.cull) {
                    // Near the clip planes: decide by the clip-space winding instead.
                    Seen::Clip => {
                        visible |= self.clipped_face_visible(&[v0.index, v1.index, v2.index]);
                    }
                    Seen::Outside | Seen::OffRows | Seen::Culled => {}
                    Seen::Front => {
                        visible = true;
                        let tri = [v0.screen, v1.screen, v2.screen];
                        if let Some(pl) = Plane::new(&tri, [tri[0].z(), tri[1].z(), tri[2].z()]) {
                            // |step| ≤ 2³¹ each: their sum needs 33 bits.
                            let steep = u64::from(pl.step_x().unsigned_abs())
                                + u64::from(pl.step_y().unsigned_abs());
                            let slope = (steep >> 16) + 1;
                            bias = bias.max(slope.min(u64::from(u16::MAX)) as u16);
                        }
                    }
                }
            }
            if !visible {
                continue;
            }
            for (a, b) in edges(vs) {
                let s = self.edge(target, Some(&mut *zbuf), &clip, f, a, b, color, bias)?;
                pixels.add_pixels(s);
            }
        }
        self.stats.add_pixel_counts(&pixels);
        Ok(())
    }
    /// Wireframe: every edge of every face, in `color`, with no hiding and no culling.
    pub fn draw_wireframe<D: DrawTarget>(
        &mut self,
        target: &mut D,
        color: D::Color,
    ) -> Result<(), DrawError<D::Error>> {
        let clip = Clip::from_rect(&target.bounding_box());
        let mut pixels = FrameStats::default();
        let mut geometry = FrameStats::default();
        for f in 0..self.mesh.face_count() {
            let (vs, _) = self.face(f)?;
            geometry.triangles_in += vs.len() as u32 - 2;
            for (a, b) in edges(vs) {
                let s = self.edge(target, None, &clip, f, a, b, color, 0)?;
                pixels.add_pixels(s);
            }
        }
        self.count(geometry);
        self.stats.add_pixel_counts(&pixels);
        Ok(())
    }
    /// Whether a triangle that needs clipping faces the camera, by clipping it and
    /// testing the first non-degenerate piece.
    pub(crate) fn clipped_face_visible(&self, idx: &[u16; 3]) -> bool {
        let mut poly = ClipPolygon::new();
        let mut code_or = 0;
        let mut code_and = 0xff;
        for &i in idx {
            let Some(p) = self.mesh.positions.get(usize::from(i)) else {
                return false;
            };
            let c = self.clip_coords(p);
            let code = outcode_of(&c);
            code_or |= code;
            code_and &= code;
            let _ = poly.push(ClipVertex {
                c,
                light: 0.0,
                uv: [0.0; 2],
            });
        }
        if code_and != 0 {
            return false;
        }
        clip_polygon(&mut poly, code_or);
        let pts: heapless::Vec<ScreenVertex, { crate::geometry::clip::MAX_CLIPPED }> =
            poly.iter().filter_map(|c| self.map.project(&c.c)).collect();
        let p = |v: &ScreenVertex| (v.x(), v.y());
        let Some((first, rest)) = pts.split_first() else {
            return false;
        };
        rest.windows(2).any(|pair| {
            let &[b, c] = pair else { return false };
            let area = signed_area(p(first), p(&b), p(&c));
            area != 0 && !self.options.cull.drops(area)
        })
    }
    /// Draw the edge between vertices `a` and `b` of face `f`, clipped in clip space.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn edge<D: DrawTarget>(
        &self,
        target: &mut D,
        zbuf: Option<&mut ZBuffer<'_>>,
        clip: &Clip,
        f: usize,
        a: u16,
        b: u16,
        color: D::Color,
        bias: u16,
    ) -> Result<SpanStats, DrawError<D::Error>> {
        let (fa, fb) = (self.fetch(a, f)?, self.fetch(b, f)?);
        if fa.code & fb.code != 0 {
            return Ok(SpanStats::default());
        }
        let (sa, sb) = if fa.code | fb.code == 0 {
            (fa.screen, fb.screen)
        } else {
            let pos = |i: u16| {
                self.mesh
                    .positions
                    .get(usize::from(i))
                    .ok_or(Error::IndexOutOfRange {
                        face: f,
                        index: usize::from(i),
                    })
            };
            let ca = ClipVertex {
                c: self.clip_coords(pos(a)?),
                light: 0.0,
                uv: [0.0; 2],
            };
            let cb = ClipVertex {
                c: self.clip_coords(pos(b)?),
                light: 0.0,
                uv: [0.0; 2],
            };
            let Some((ca, cb)) = clip_segment(&ca, &cb, fa.code | fb.code) else {
                return Ok(SpanStats::default());
            };
            match (self.map.project(&ca.c), self.map.project(&cb.c)) {
                (Some(x), Some(y)) => (x, y),
                _ => return Ok(SpanStats::default()),
            }
        };
        draw_line(target, zbuf, clip, &sa, &sb, color, bias).map_err(DrawError::Target)
    }
}
