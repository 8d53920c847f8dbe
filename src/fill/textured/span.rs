//! The fast pixel loop of textured spans: the default depth test, one light a face.

use super::{SegmentSteps, Segments, TexSetup, SEGMENT, SHIFT};
use crate::num::kernel::{TexelGrid, TEXEL_KERNEL};
use crate::raster::{Clip, SpanStats};
use crate::texture::{Texel, Texture};

/// How a span's pixels find their texel from the stepped u and v (Q16 times
/// [`SEGMENT`]): for a repeating texture of power-of-two sizes (at least
/// 2×2) by shifts ([`Pow2`]), else through [`Texture::sample_raw`].
#[derive(Clone, Copy)]
pub(crate) enum Fetch<'a, X> {
    Pow2(Pow2<'a, X>),
    Any(Texture<'a, X>),
}

/// A repeating texture of W × H texels, both powers of two from 2 on: the texel of
/// coordinates whose 32 bits are the fraction of a texture (see [`TOP`]) is at column
/// `u ≫ (32 − log₂ W)` and row `v ≫ (32 − log₂ H)`.
#[derive(Clone, Copy)]
pub(crate) struct Pow2<'a, X> {
    /// Exactly W·H texels.
    texels: &'a [X],
    lw: u32,
    lh: u32,
    /// W, as a value (multiplied, not shifted: one multiply-add makes the index).
    w: u32,
}

impl<'a, X: Texel> Fetch<'a, X> {
    pub(crate) fn new(t: &Texture<'a, X>) -> Self {
        let (w, h) = (t.width(), t.height());
        let (lw, lh) = (w.trailing_zeros(), h.trailing_zeros()); // ≤ 13 each
        match t.wrap() {
            crate::texture::Wrap::Repeat
                if w.is_power_of_two() && h.is_power_of_two() && lw >= 1 && lh >= 1 =>
            {
                Fetch::Pow2(Pow2 {
                    texels: t.texels(),
                    lw,
                    lh,
                    w,
                })
            }
            _ => Fetch::Any(*t),
        }
    }
}

impl<'a, X: Copy> Pow2<'a, X> {
    /// The texture for the assembly segment of `num::kernel`, where this target has it
    /// and a pixel's colour in `C` is its texel's bits (the caller's colours must be the
    /// texels themselves: full light, undithered).
    #[inline(always)]
    pub(crate) fn grid<C: 'static>(&self) -> Option<TexelGrid<'a, C>> {
        if !TEXEL_KERNEL {
            return None;
        }
        TexelGrid::of(self.texels, self.lw, self.lh)
    }
}

/// How far the fast loops shift stepped coordinates (Q16 times
/// [`SEGMENT`]) up for [`Pow2`]: to the fraction of a texture in all 32
/// bits, so that wrapping arithmetic is the repeat. ⌊u·W⌋ mod W is then the top log₂ W
/// bits of u, for negative u too (two's complement), and the same as ⌊(u ≫ 4)·W / 2¹⁶⌋
/// mod W (floors of divisions by powers of two compose).
pub(super) const TOP: u32 = 32 - 16 - SHIFT;

/// The rows of [`fill_textured_buffers`](super::fill_textured_buffers) for
/// [`DepthTest::Less`](crate::DepthTest::Less), one light for the face and a [`Pow2`]
/// texture: each span by [`pow2_span`], the same pixels as the general loop;
/// `colour(texel, index)` is the pixel's colour for a texel at an index, and `grid`, if
/// any, the same colours by the assembly segment ([`Pow2::grid`]; `GRID` says whether
/// there is one, so that the loops without it are built without its code).
#[inline(always)]
pub(super) fn pow2_rows<C: embedded_graphics::pixelcolor::PixelColor, X: Copy, const GRID: bool>(
    frame: &mut crate::ColorBuffer<'_, C>,
    zbuf: &mut crate::ZBuffer<'_>,
    clip: &Clip,
    ts: &TexSetup,
    tex: Pow2<'_, X>,
    grid: Option<TexelGrid<'_, C>>,
    colour: impl FnMut(X, usize) -> C + Copy,
) -> SpanStats {
    let mut stats = SpanStats::default();
    let write = zbuf.write_enabled();
    let mut spans = ts.setup.spans(clip);
    while let Some((y, x0, x1)) = spans.next_span() {
        let (Some(zrow), Some(crow)) = (zbuf.span_mut(y, x0, x1), frame.span_mut(y, x0, x1)) else {
            continue;
        };
        let acc = ts.rows.at(x0, y);
        let segments = ts.uv.segments(x0, y, x1 - x0);
        let failed = if write {
            pow2_span::<C, X, true, GRID>(zrow, crow, acc, ts.dz, segments, tex, grid, colour)
        } else {
            pow2_span::<C, X, false, false>(zrow, crow, acc, ts.dz, segments, tex, None, colour)
        };
        stats.pixels_tested += (x1 - x0) as u32;
        stats.pixels_written += (x1 - x0) as u32 - failed;
    }
    stats
}

/// A span of [`pow2_rows`], segment by segment in two passes, each loop with few enough
/// values to keep them all in registers: the segment's colours `colour(texel, index)`
/// into a buffer, the texel index `(v ≫ sv)·W + (u ≫ su)` (below W·H, masked by
/// W·H − 1, a no-op, so that the compiler sees it in bounds); then each pixel's depth
/// tested (`Less`) and written (`WRITE`), and the colour copied where it passes; with a
/// `grid` (and `WRITE`), a whole segment in one pass by the assembly segment. Out of
/// line. Returns the number of pixels that failed the test.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn pow2_span<C: Copy, X: Copy, const WRITE: bool, const GRID: bool>(
    zrow: &mut [u16],
    crow: &mut [C],
    acc: u32,
    dz: u32,
    segments: Segments,
    tex: Pow2<'_, X>,
    grid: Option<TexelGrid<'_, C>>,
    mut colour: impl FnMut(X, usize) -> C,
) -> u32 {
    // A length the compiler knows to be a power of two (W·H ≤ 2²⁶).
    let Some(texels) = tex.texels.get(..1usize << (tex.lw + tex.lh)) else {
        return 0;
    };
    let Some(&t0) = texels.first() else {
        return 0;
    };
    let (su, sv, w) = (32 - tex.lw, 32 - tex.lh, tex.w);
    let mask = texels.len() - 1;
    let mut buf = [colour(t0, 0); SEG];
    let mut failed = 0;
    let look = (texels, su, sv, w, mask);
    // The changing values in locals, the rest apart (see `SegmentSteps`).
    let fixed = SegmentSteps::of(&segments);
    let (mut h, mut at_uv, mut i) = (segments.h, segments.uv, segments.i);
    while let Some(s) = fixed.next(&mut h, &mut at_uv, &mut i) {
        let end = s.first + s.len;
        let (Some(zs), Some(cs)) = (zrow.get_mut(s.first..end), crow.get_mut(s.first..end)) else {
            continue;
        };
        let uv = [s.uv.0, s.uv.1, s.step.0, s.step.1].map(|x| (x as u32) << TOP);
        // The depth at the segment's first pixel: `first` steps on.
        let acc = acc.wrapping_add(dz.wrapping_mul(s.first as u32));
        // Whole segments with their length known to the compiler (no counts, no
        // remainders), the others as they come.
        let whole: (Result<&mut [u16; SEG], _>, Result<&mut [C; SEG], _>) =
            (zs.try_into(), cs.try_into());
        match whole {
            (Ok(zs), Ok(cs)) if WRITE && GRID && grid.is_some() => {
                if let Some(g) = &grid {
                    failed += g.segment(zs, cs, acc, dz, uv);
                }
            }
            (Ok(zs), Ok(cs)) => {
                // Depths first: where all pass (mostly), the colours go straight in.
                let fails = depth_mask::<WRITE>(zs, acc, dz);
                if fails == 0 {
                    texel_pass(cs, uv, look, &mut colour);
                } else {
                    failed += fails.count_ones();
                    texel_pass(&mut buf, uv, look, &mut colour);
                    for (k, (c, b)) in cs.iter_mut().zip(buf).enumerate() {
                        if fails >> k & 1 == 0 {
                            *c = b;
                        }
                    }
                }
            }
            (Err(_), _) | (_, Err(_)) => {
                let (Some(zs), Some(cs), Some(bs)) = (
                    zrow.get_mut(s.first..end),
                    crow.get_mut(s.first..end),
                    buf.get_mut(..s.len),
                ) else {
                    continue;
                };
                texel_pass(bs, uv, look, &mut colour);
                failed += depth_pass::<C, WRITE>(zs, cs, bs, acc, dz);
            }
        }
    }
    failed
}

/// Pixels a whole segment has.
const SEG: usize = SEGMENT as usize;

/// The first pass of [`pow2_span`]: the colours of a segment's pixels from u, v and their
/// steps (`[u, v, du, dv]`, fractions of a texture in 32 bits) into `bs`.
#[inline(always)]
fn texel_pass<C, X: Copy>(
    bs: &mut [C],
    [mut u, mut v, du, dv]: [u32; 4],
    (texels, su, sv, w, mask): (&[X], u32, u32, u32, usize),
    colour: &mut impl FnMut(X, usize) -> C,
) {
    for b in bs.iter_mut() {
        let at = ((v >> sv).wrapping_mul(w).wrapping_add(u >> su)) as usize & mask;
        if let Some(&t) = texels.get(at) {
            *b = colour(t, at);
        }
        u = u.wrapping_add(du);
        v = v.wrapping_add(dv);
    }
}

/// The depth test of a whole segment in [`pow2_span`]: each pixel's depth from `acc`
/// stepped by `dz`, tested (`Less`) and written (`WRITE`). Returns the pixels that
/// failed, bit k for the k-th.
#[inline(always)]
fn depth_mask<const WRITE: bool>(zs: &mut [u16; SEG], mut acc: u32, dz: u32) -> u32 {
    let mut fails = 0;
    for (k, d) in zs.iter_mut().enumerate() {
        let z = (acc >> 16) as u16;
        acc = acc.wrapping_add(dz);
        if z < *d {
            if WRITE {
                *d = z;
            }
        } else {
            failed_at(&mut fails, k);
        }
    }
    fails
}

/// Pixel `k` (below 32) failed: out of line and cold, so that the passing path is
/// straight code.
#[cold]
#[inline(never)]
fn failed_at(fails: &mut u32, k: usize) {
    *fails |= 1 << (k & 31);
}

/// The second pass of [`pow2_span`]: each pixel's depth from `acc` stepped by `dz`,
/// tested (`Less`) and written (`WRITE`), and its colour from `bs` where it passes.
/// Returns the number of pixels that failed.
#[inline(always)]
fn depth_pass<C: Copy, const WRITE: bool>(
    zs: &mut [u16],
    cs: &mut [C],
    bs: &[C],
    mut acc: u32,
    dz: u32,
) -> u32 {
    let mut failed = 0;
    for ((d, c), b) in zs.iter_mut().zip(cs.iter_mut()).zip(bs.iter()) {
        let z = (acc >> 16) as u16;
        acc = acc.wrapping_add(dz);
        if z < *d {
            if WRITE {
                *d = z;
            }
            *c = *b;
        } else {
            crate::fill::span::one_failed(&mut failed);
        }
    }
    failed
}
