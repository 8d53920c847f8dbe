//! Drawing a whole frame band by band, in a fraction of a frame's RAM.
//!
//! A frame of `width × height` pixels is drawn in bands of `rows` lines: each band is
//! cleared, drawn into a band-sized colour buffer and Z-buffer, and sent to the display
//! with one `fill_contiguous`. The pixels are exactly those of a whole-frame drawing.
//!
//! RAM: `rows × width × (size_of::<C>() + 2)` bytes for the band buffers, plus, for a
//! cached triangle mesh, an optional bin list of
//! [`BandBuffers::bins_needed`] `u16`s that sorts the visible triangles by band once per
//! frame, so that a band only looks at the triangles that reach it.

use embedded_graphics::{pixelcolor::PixelColor, prelude::DrawTarget};

use crate::mesh::Faces;
use crate::render::{culled, CachedVertex};
use crate::shade::{Material, Shading};
use crate::{ColorBuffer, DrawError, Error, FrameStats, Renderer, ZBuffer, MAX_DIMENSION};

/// Caller memory for banded drawing: a colour band, a depth band and (optionally) bins.
#[derive(Debug)]
pub struct BandBuffers<'a, C> {
    color: &'a mut [C],
    depth: &'a mut [u16],
    width: u32,
    rows: u32,
    height: u32,
    bins: &'a mut [u16],
}

/// Bins: the band of each triangle's top row (a byte each), and the triangles in band
/// order. A triangle reaching more than two bands, or needing clipping, goes into an
/// extra last bin that every band visits.
const NOT_DRAWN: u8 = 0xff;

impl<'a, C: PixelColor> BandBuffers<'a, C> {
    /// Band buffers for a `width × height` screen drawn `rows` lines at a time.
    /// `color` and `depth` need `width × rows` entries; `bins` may be empty (every band
    /// then walks every triangle) or hold at least
    /// [`bins_needed`](BandBuffers::bins_needed) entries.
    pub fn new(
        color: &'a mut [C],
        depth: &'a mut [u16],
        width: u32,
        rows: u32,
        height: u32,
        bins: &'a mut [u16],
    ) -> Result<Self, Error> {
        if width == 0 || rows == 0 || height == 0 {
            return Err(Error::ZeroSize);
        }
        if width > MAX_DIMENSION || height > MAX_DIMENSION {
            return Err(Error::TooLarge);
        }
        let rows = rows.min(height);
        let needed = (width * rows) as usize;
        for got in [color.len(), depth.len()] {
            if got < needed {
                return Err(Error::BufferTooSmall { needed, got });
            }
        }
        Ok(BandBuffers {
            color,
            depth,
            width,
            rows,
            height,
            bins,
        })
    }

    /// The number of bands.
    pub fn bands(&self) -> u32 {
        self.height.div_ceil(self.rows)
    }

    /// Bin entries needed for a mesh of `triangles` triangles: half a `u16` per
    /// triangle for its band, one per triangle for the order, one per band (+2).
    pub fn bins_needed(triangles: usize, height: u32, rows: u32) -> usize {
        let bands = height.div_ceil(rows.max(1)) as usize;
        triangles.div_ceil(2) + bands + 2 + triangles
    }
}

impl<'m, 'c, M: Copy> Renderer<'m, 'c, M> {
    /// Draw the frame band by band into `display`: each band cleared to `background`,
    /// drawn with the Z-buffer (as [`draw_buffer`](Renderer::draw_buffer)) and sent with
    /// one `fill_contiguous`. The result is pixel-identical to drawing the whole frame.
    ///
    /// With a vertex cache ([`Renderer::with_cache`]), a triangle mesh, flat or Lambert
    /// shading and enough bins, the visible triangles are sorted by band first, so each
    /// band only visits the triangles that reach it.
    pub fn draw_banded<D>(
        &mut self,
        display: &mut D,
        bands: &mut BandBuffers<'_, D::Color>,
        background: D::Color,
    ) -> Result<(), DrawError<D::Error>>
    where
        D: DrawTarget,
        M: Material<D::Color>,
    {
        self.draw_banded_with(display, bands, background, |_, _| {})
    }

    /// [`draw_banded`](Renderer::draw_banded), calling `after(band, depth)` for each
    /// band once it is drawn and before it is sent: to draw an overlay into it, or to
    /// look at its depth.
    pub fn draw_banded_with<D>(
        &mut self,
        display: &mut D,
        bands: &mut BandBuffers<'_, D::Color>,
        background: D::Color,
        mut after: impl FnMut(&mut ColorBuffer<'_, D::Color>, &ZBuffer<'_>),
    ) -> Result<(), DrawError<D::Error>>
    where
        D: DrawTarget,
        M: Material<D::Color>,
    {
        let nb = bands.bands();
        let binned = self.bin(bands)?;
        let (w, rows) = (bands.width, bands.rows);
        for k in 0..nb {
            let y0 = k * rows;
            let n = rows.min(bands.height - y0);
            // new() checked both slices hold `width × rows` entries: the last, shorter
            // band uses the front of them.
            let mut color = ColorBuffer::new_band(&mut *bands.color, w, n, y0 as i32)?;
            let mut zbuf = ZBuffer::new_band(&mut *bands.depth, w, n, y0 as i32)?;
            crate::zbuffer::fill_fast(color.data_mut(), background);
            zbuf.clear();
            match binned {
                Some(nt) => {
                    // Layout of the bins (see `bin`): keys, then nb + 2 bin starts, then the order.
                    let (_, rest) = bands.bins.split_at(nt.div_ceil(2).min(bands.bins.len()));
                    let (start, order) = rest.split_at((nb as usize + 2).min(rest.len()));
                    let bin = |b: usize| -> &[u16] {
                        let (s, e) = (
                            start.get(b).copied().unwrap_or(0),
                            start.get(b + 1).copied().unwrap_or(0),
                        );
                        order.get(usize::from(s)..usize::from(e)).unwrap_or(&[])
                    };
                    // This band's bin, the one above (triangles reaching two bands) and
                    // the tall/clipped bin.
                    let above = if k > 0 { bin(k as usize - 1) } else { &[] };
                    let faces = above
                        .iter()
                        .chain(bin(k as usize))
                        .chain(bin(nb as usize))
                        .map(|&f| usize::from(f));
                    self.draw_listed(&mut color, &mut zbuf, faces)?;
                }
                None => self.draw_buffer(&mut color, &mut zbuf)?,
            }
            after(&mut color, &zbuf);
            color.flush(display).map_err(DrawError::Target)?;
        }
        Ok(())
    }

    /// Sort the visible triangles into bins; `Some(triangle count)` when binned.
    fn bin<C>(&mut self, bands: &mut BandBuffers<'_, C>) -> Result<Option<usize>, Error>
    where
        C: PixelColor,
        M: Material<C>,
    {
        let Faces::Triangles { indices, .. } = self.mesh.faces else {
            return Ok(None);
        };
        let fast = !M::DITHERED && matches!(self.options.shading, Shading::Flat | Shading::Lambert);
        let nt = indices.len();
        let nb = bands.bands() as usize;
        let rows = bands.rows as i32;
        let height = bands.height as i32;
        let Some(cache) = self.cache.as_deref() else {
            return Ok(None);
        };
        if !fast
            || nb > 250
            || nt > usize::from(u16::MAX)
            || bands.bins.len() < BandBuffers::<C>::bins_needed(nt, bands.height, bands.rows)
        {
            return Ok(None);
        }
        let (keys, rest) = bands.bins.split_at_mut(nt.div_ceil(2));
        let (start, order) = rest.split_at_mut(nb + 2);
        start.fill(0);
        let key_set = |keys: &mut [u16], f: usize, v: u8| {
            if let Some(k) = keys.get_mut(f / 2) {
                let sh = (f % 2) * 8;
                *k = (*k & !(0xff << sh)) | (u16::from(v) << sh);
            }
        };
        let key_get = |keys: &[u16], f: usize| {
            keys.get(f / 2)
                .map_or(NOT_DRAWN, |k| (k >> ((f % 2) * 8)) as u8)
        };
        let tall = nb as u8;
        let cull = self.options.cull;
        let mut st = FrameStats::default();
        for (f, t) in indices.iter().enumerate() {
            let get = |i: u16| {
                cache.get(usize::from(i)).ok_or(Error::IndexOutOfRange {
                    face: f,
                    index: usize::from(i),
                })
            };
            let (a, b, c): (&CachedVertex, &CachedVertex, &CachedVertex) =
                (get(t[0])?, get(t[1])?, get(t[2])?);
            let key = if a.code() & b.code() & c.code() != 0 {
                st.triangles_in += 1;
                st.outside += 1;
                NOT_DRAWN
            } else if a.code() | b.code() | c.code() != 0 {
                // Near a clip plane: drawn by the general path in every band; counted now
                // as that path counts it (clipped, and the pieces that survive culling).
                let g = self.count_one(f).map_err(|e| match e {
                    DrawError::Input(e) => e,
                    DrawError::Target(never) => match never {},
                })?;
                st.add_geometry(&g);
                tall
            } else {
                st.triangles_in += 1;
                let tri = [a.screen(), b.screen(), c.screen()];
                let [p, q, r] = tri;
                if culled(&tri, cull) {
                    st.culled += 1;
                    NOT_DRAWN
                } else {
                    st.drawn += 1;
                    let ymin = p.y().min(q.y()).min(r.y());
                    let ymax = p.y().max(q.y()).max(r.y());
                    let (top, bottom) = ((ymin + 7) >> 4, (ymax + 7) >> 4); // rows top..bottom
                    if bottom <= 0 || top >= height || top >= bottom {
                        NOT_DRAWN
                    } else {
                        let (tb, bb) = (top.max(0) / rows, (bottom - 1).min(height - 1) / rows);
                        if bb - tb >= 2 {
                            tall
                        } else {
                            tb as u8
                        }
                    }
                }
            };
            key_set(keys, f, key);
            if key != NOT_DRAWN {
                if let Some(s) = start.get_mut(usize::from(key) + 1) {
                    *s += 1;
                }
            }
        }
        let mut sum = 0;
        for s in start.iter_mut() {
            sum += *s;
            *s = sum;
        }
        // Place, using start[b] as the running position of bin b, then shift back.
        for f in 0..nt {
            let key = key_get(keys, f);
            if key != NOT_DRAWN {
                let b = usize::from(key);
                if let (Some(pos), Some(slot)) = (start.get(b).copied(), start.get_mut(b)) {
                    *slot = pos + 1;
                    if let Some(o) = order.get_mut(usize::from(pos)) {
                        *o = f as u16;
                    }
                }
            }
        }
        start.rotate_right(1);
        if let Some(s) = start.first_mut() {
            *s = 0;
        }
        self.count(st);
        Ok(Some(nt))
    }
}
