//! The fast pixel loop of textured spans: the default depth test, one light a face.

use super::{Segments, TexSetup, SHIFT};
use crate::raster::{Clip, SpanStats};
use crate::texture::{Texel, Texture};

/// How a span's pixels find their texel from the stepped u and v (Q16 times
/// [`SEGMENT`]): for a repeating texture of power-of-two sizes (W ≥ 2) by shifts
/// and masks (the texel ⌊u·W⌋ mod W is bits of u), else through
/// [`Texture::sample_raw`].
#[derive(Clone, Copy)]
pub(crate) enum Fetch<'a, X> {
    Pow2 {
        texels: &'a [X],
        /// The texel's index is `(u ≫ su) | (v ≫ sv & hmask)`.
        shifts: Pow2Shifts,
    },
    Any(Texture<'a, X>),
}

/// The shifts and mask of [`texel_pow2`].
#[derive(Clone, Copy)]
pub(crate) struct Pow2Shifts {
    su: u32,
    sv: u32,
    hmask: u32,
}

impl<'a, X: Texel> Fetch<'a, X> {
    pub(crate) fn new(t: &Texture<'a, X>) -> Self {
        let (w, h) = (t.width(), t.height());
        let (lw, lh) = (w.trailing_zeros(), h.trailing_zeros()); // ≤ 13 each
        match t.wrap() {
            crate::texture::Wrap::Repeat
                if w.is_power_of_two() && h.is_power_of_two() && lw >= 1 =>
            {
                Fetch::Pow2 {
                    texels: t.texels(),
                    shifts: Pow2Shifts {
                        // 1 ≤ lw, lh + lw ≤ 26: both shifts within 6..=31.
                        su: 32 - lw,
                        sv: 32 - lh - lw,
                        hmask: (h - 1) << lw,
                    },
                }
            }
            _ => Fetch::Any(*t),
        }
    }
}

/// How far [`face_span`] shifts stepped coordinates (Q16 times [`SEGMENT`]) up for
/// [`texel_pow2`]: to the fraction of a texture in all 32 bits, so that wrapping
/// arithmetic is the repeat.
pub(super) const TOP: u32 = 32 - 16 - SHIFT;

/// The texel at coordinates `u`, `v` whose 32 bits are the fraction of a texture (Q16
/// times [`SEGMENT`] shifted up by [`TOP`]): ⌊u·W⌋ mod W is the top log₂ W bits of u,
/// for negative u too (two's complement), and the same as ⌊(u ≫ 4)·W / 2¹⁶⌋ mod W
/// (floors of divisions by powers of two compose); the row likewise, already times W.
#[inline(always)]
pub(super) fn texel_pow2<X: Copy>(texels: &[X], k: Pow2Shifts, u: u32, v: u32) -> Option<X> {
    // Below W·H, the slice's length: always `Some`.
    texels.get(texel_index_pow2(k, u, v)).copied()
}

/// The index of [`texel_pow2`]'s texel, below W·H.
#[inline(always)]
pub(super) fn texel_index_pow2(k: Pow2Shifts, u: u32, v: u32) -> usize {
    let col = u >> k.su;
    let row = (v >> k.sv) & k.hmask;
    (row | col) as usize
}

/// The rows of [`fill_textured_buffers`] for [`DepthTest::Less`] and one light for the
/// face: each span by [`face_span`], the same pixels as the general loop.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn face_rows<C: embedded_graphics::pixelcolor::PixelColor, X>(
    frame: &mut crate::ColorBuffer<'_, C>,
    zbuf: &mut crate::ZBuffer<'_>,
    clip: &Clip,
    ts: &TexSetup,
    write: bool,
    up: u32,
    fetch: impl Fn(u32, u32) -> Option<X> + Copy,
    colour: impl Fn(X, i32, i32) -> C + Copy,
) -> SpanStats {
    let mut stats = SpanStats::default();
    let mut spans = ts.setup.spans(clip);
    while let Some((y, x0, x1)) = spans.next_span() {
        let (Some(zrow), Some(crow)) = (zbuf.span_mut(y, x0, x1), frame.span_mut(y, x0, x1)) else {
            continue;
        };
        let acc = ts.rows.at(x0, y);
        let mut segments = ts.uv.segments(x0, y, x1 - x0);
        let colour = move |t: X, k: usize| colour(t, x0 + k as i32, y);
        let failed = if write {
            face_span::<C, X, true>(zrow, crow, acc, ts.dz, &mut segments, up, fetch, colour)
        } else {
            face_span::<C, X, false>(zrow, crow, acc, ts.dz, &mut segments, up, fetch, colour)
        };
        stats.pixels_tested += (x1 - x0) as u32;
        stats.pixels_written += (x1 - x0) as u32 - failed;
    }
    stats
}

/// The pixel loop of [`face_rows`]: a span's segments, each pixel's depth tested
/// (`Less`) and written (`WRITE`), and its colour `colour(fetch(u, v), k)` for the
/// k-th pixel, u and v the stepped coordinates (Q16 times [`SEGMENT`]) shifted up by
/// `up` (wrapping). Out of line, so that the loop has the registers to itself. Returns
/// the number of pixels that failed the test.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn face_span<C: Copy, X, const WRITE: bool>(
    zrow: &mut [u16],
    crow: &mut [C],
    mut acc: u32,
    dz: u32,
    segments: &mut Segments,
    up: u32,
    fetch: impl Fn(u32, u32) -> Option<X>,
    colour: impl Fn(X, usize) -> C,
) -> u32 {
    let mut failed = 0;
    while let Some(s) = segments.next_segment() {
        let end = s.first + s.len;
        let (Some(zs), Some(cs)) = (zrow.get_mut(s.first..end), crow.get_mut(s.first..end)) else {
            continue;
        };
        let ((u, v), (du, dv)) = (s.uv, s.step);
        let (mut u, mut v) = ((u as u32) << up, (v as u32) << up);
        let (du, dv) = ((du as u32) << up, (dv as u32) << up);
        for (k, (d, c)) in zs.iter_mut().zip(cs.iter_mut()).enumerate() {
            let z = (acc >> 16) as u16;
            acc = acc.wrapping_add(dz);
            if z < *d {
                if WRITE {
                    *d = z;
                }
                // Always a texel (see `texel_pow2`): no fallback to keep at hand.
                if let Some(t) = fetch(u, v) {
                    *c = colour(t, s.first + k);
                }
            } else {
                crate::fill::span::one_failed(&mut failed);
            }
            u = u.wrapping_add(du);
            v = v.wrapping_add(dv);
        }
    }
    failed
}
