//! The vertex cache's usual vertex four at a time in SSE2 (x86-64): the fixed-point
//! rows by `PMADDWD`, the projection in packed `f32`, one `DIVPS` for four
//! reciprocals. It computes [`place_portable`] lane by lane, every `f32` operation the
//! same and in the same order (packed SSE arithmetic rounds as scalar does), so its
//! entries are those of the `f32` path, as the Cortex-M4F's `place_pairs` are; a
//! position the twin does not place is left to the caller. The only `unsafe` is the call
//! into SSE2 code, which x86-64 always has, and the two loads of four positions' bytes.
#![allow(unsafe_code)]

use super::place::{place_portable, PlaceBlock};
use super::CachedVertex;

/// Whether [`place_quads`] runs SSE2 (x86-64); elsewhere the renderer does not call it.
pub(crate) const PLACE4_KERNEL: bool = cfg!(zraster_x86_64);

/// Four entries of `p` (`Some` where [`place_portable`] places the position) by the
/// twin, one lane at a time.
#[cfg_attr(not(test), allow(dead_code))]
#[inline]
pub(crate) fn place4_portable(b: &PlaceBlock, p: &[[i16; 3]; 4]) -> [Option<CachedVertex>; 4] {
    p.each_ref().map(|p| place_portable(b, p))
}

/// The entries of `positions` into `out` (as many as the shorter holds): four at a
/// time by [`place4`] (the twin where SSE2 is missing), any the loop does not place
/// and the last few by `entry`.
#[inline]
pub(crate) fn place_quads(
    b: &PlaceBlock,
    positions: &[[i16; 3]],
    out: &mut [CachedVertex],
    mut entry: impl FnMut(&[i16; 3]) -> CachedVertex,
) {
    let q = Quad::new(b);
    // Whole quads of both, then the rest: one count for the loop.
    let n = positions.len().min(out.len()) / 4 * 4;
    let (positions, rest) = positions.split_at(n);
    let (out, rest_out) = out.split_at_mut(n);
    for (p, o) in positions.chunks_exact(4).zip(out.chunks_exact_mut(4)) {
        let (Ok(p), Ok(o)) = (<&[[i16; 3]; 4]>::try_from(p), <&mut [_; 4]>::try_from(o)) else {
            continue;
        };
        let placed = q.place4(p, o);
        if placed != 0xf {
            for (k, (e, p)) in o.iter_mut().zip(p).enumerate() {
                if placed >> k & 1 == 0 {
                    *e = entry(p);
                }
            }
        }
    }
    for (p, e) in rest.iter().zip(rest_out) {
        *e = entry(p);
    }
}

/// [`PlaceBlock`]'s operands for [`Quad::place4`].
struct Quad<'b> {
    #[cfg_attr(zraster_x86_64, allow(dead_code))]
    block: &'b PlaceBlock,
    #[cfg(zraster_x86_64)]
    sse: sse::Operands,
}

impl<'b> Quad<'b> {
    #[inline(always)]
    fn new(block: &'b PlaceBlock) -> Self {
        Quad {
            block,
            // SAFETY: SSE2 is part of x86-64, the only target `zraster_x86_64` names.
            #[cfg(zraster_x86_64)]
            sse: unsafe { sse::Operands::new(block) },
        }
    }

    /// The entries of four positions into `out` and which of them are placed (bit k for
    /// lane k; the other lanes' entries are to be replaced).
    #[inline(always)]
    fn place4(&self, p: &[[i16; 3]; 4], out: &mut [CachedVertex; 4]) -> u32 {
        // SAFETY: as in `new`: SSE2 is there.
        #[cfg(zraster_x86_64)]
        return unsafe { self.sse.place4(p, out) };
        #[allow(unreachable_code)]
        {
            let mut placed = 0;
            for (k, (g, o)) in place4_portable(self.block, p).iter().zip(out).enumerate() {
                placed |= u32::from(g.is_some()) << k;
                *o = g.unwrap_or(CachedVertex::EMPTY);
            }
            placed
        }
    }
}

#[cfg(zraster_x86_64)]
mod sse {
    use super::super::place::PlaceBlock;
    use super::super::CachedVertex;
    #[cfg(target_arch = "x86")]
    use core::arch::x86::*;
    #[cfg(target_arch = "x86_64")]
    use core::arch::x86_64::*;

    /// The rows as `PMADDWD` operands of the positions' words as they lie (see
    /// [`Operands::place4`]) and `t`, and the projection's constants, each in all four
    /// lanes.
    pub(super) struct Operands {
        /// Each row's `c₀c₁ | 0c₀ | c₀c₁ | 0c₀`, `c₂0 | c₁c₂ | c₂0 | c₁c₂` and `t`.
        rows: [[__m128i; 3]; 6],
        sx: __m128,
        sy: __m128,
        ox: __m128,
        oy: __m128,
        depth_half: __m128,
    }

    impl Operands {
        #[inline]
        #[target_feature(enable = "sse2")]
        pub(super) fn new(b: &PlaceBlock) -> Operands {
            let (rows, [_, sx, sy, depth_half], [ox, oy]) = b.parts();
            let lanes = |v: u32| _mm_set1_epi32(v as i32);
            Operands {
                rows: rows.map(|[c01, c12, t]| {
                    let pair =
                        |a: u32, b: u32| _mm_setr_epi32(a as i32, b as i32, a as i32, b as i32);
                    [pair(c01, c01 << 16), pair(c12 >> 16, c12), lanes(t)]
                }),
                sx: _mm_set1_ps(sx),
                sy: _mm_set1_ps(sy),
                ox: _mm_set1_ps(ox),
                oy: _mm_set1_ps(oy),
                depth_half: _mm_set1_ps(depth_half),
            }
        }

        /// `place_portable` of four positions, a lane each: the entries, and a bit set
        /// for each lane it places.
        #[inline]
        #[target_feature(enable = "sse2")]
        pub(super) fn place4(&self, p: &[[i16; 3]; 4], out: &mut [CachedVertex; 4]) -> u32 {
            // The four positions' 12 words x₀y₀ z₀x₁ y₁z₁ x₂y₂ | z₂x₃ y₃z₃ by two loads,
            // as word pairs: lane k's x, y and z lie in `u`'s and `w`'s pair k, which
            // the rows' pairs (`c₀c₁ | 0c₀ | …` and `c₂0 | c₁c₂ | …`) weigh.
            let at = p.as_ptr().cast::<u8>();
            // SAFETY: `p` is 24 bytes (four `[i16; 3]`): bytes 0..16 and 16..24, read
            // unaligned (any bits are words).
            let (l0, l1) = unsafe {
                (
                    _mm_loadu_si128(at.cast::<__m128i>()),
                    _mm_loadl_epi64(at.add(16).cast::<__m128i>()),
                )
            };
            // u = x₀y₀ z₀x₁ x₂y₂ z₂x₃, w = z₀x₁ y₁z₁ z₂x₃ y₃z₃.
            let u = _mm_unpacklo_epi64(l0, _mm_unpacklo_epi32(_mm_shuffle_epi32(l0, 3), l1));
            let w = _mm_unpacklo_epi64(_mm_shuffle_epi32(l0, 0b1001), l1);
            // c₀·x + c₁·y + c₂·z + t, exact in 32 bits (wrapping as the twin).
            let row = |[k1, k2, t]: [__m128i; 3]| {
                let s = _mm_add_epi32(_mm_madd_epi16(u, k1), t);
                _mm_cvtepi32_ps(_mm_add_epi32(s, _mm_madd_epi16(w, k2)))
            };
            let [x, y, zh, wh, zl, wl] = self.rows.map(row);
            let unit = _mm_set1_ps(1.0 / 16384.0);
            let zf = _mm_add_ps(zh, _mm_mul_ps(zl, unit));
            let wf = _mm_add_ps(wh, _mm_mul_ps(wl, unit));
            let one = _mm_set1_ps(1.0);
            let inv = _mm_div_ps(one, wf);
            let cx = _mm_add_ps(_mm_mul_ps(_mm_mul_ps(x, inv), self.sx), self.ox);
            let cy = _mm_add_ps(_mm_mul_ps(_mm_mul_ps(y, inv), self.sy), self.oy);
            let sz = _mm_mul_ps(_mm_add_ps(_mm_mul_ps(zf, inv), one), self.depth_half);
            let sz = _mm_add_ps(sz, _mm_set1_ps(0.5));
            // Twice the coordinate truncated (out of range: i32::MIN, which the range
            // test below refuses, as it does the twin's saturated values), then
            // rounded: (t + 1 + (t >> 31)) >> 1.
            let two = _mm_set1_ps(2.0);
            let round = |c: __m128| {
                let t = _mm_cvttps_epi32(_mm_mul_ps(c, two));
                let t1 = _mm_add_epi32(t, _mm_set1_epi32(1));
                _mm_srai_epi32(_mm_add_epi32(t1, _mm_srai_epi32(t, 31)), 1)
            };
            let (rx, ry) = (round(cx), round(cy));
            // |r| < 2¹⁴ for both.
            let (lo, hi) = (_mm_set1_epi32(-(1 << 14)), _mm_set1_epi32(1 << 14));
            let fits = |r: __m128i| _mm_and_si128(_mm_cmpgt_epi32(r, lo), _mm_cmpgt_epi32(hi, r));
            let inside = _mm_and_si128(fits(rx), fits(ry));
            // Depth units 1..65533 (the twin's truncated depth minus 2¹⁶ below
            // 0xfffd_0000): 2¹⁶ ≤ sz < 0xfffe_0000, both exact in f32 (NaN fails).
            let deep = _mm_and_ps(
                _mm_cmpge_ps(sz, _mm_set1_ps(65536.0)),
                _mm_cmplt_ps(sz, _mm_set1_ps(4_294_836_224.0)),
            );
            let ok = _mm_and_ps(_mm_castsi128_ps(inside), deep);
            // w > 0: the reciprocal's sign bit clear.
            let placed = (_mm_movemask_ps(ok) & !_mm_movemask_ps(inv)) as u32;
            // The depth as u32: from 2³¹ up, 2³¹ less (exact there) then its top bit.
            let high = _mm_cmpge_ps(sz, _mm_set1_ps(2_147_483_648.0));
            let off = _mm_and_ps(high, _mm_set1_ps(2_147_483_648.0));
            let top = _mm_and_si128(_mm_castps_si128(high), _mm_set1_epi32(i32::MIN));
            let zi = _mm_xor_si128(_mm_cvttps_epi32(_mm_sub_ps(sz, off)), top);
            let xyw = _mm_or_si128(
                _mm_and_si128(rx, _mm_set1_epi32(0xffff)),
                _mm_slli_epi32(ry, 16),
            );
            // Entries (depth, then x/y): lanes 0, 1 and 2, 3 as 64-bit words.
            let (e01, e23) = (_mm_unpacklo_epi32(zi, xyw), _mm_unpackhi_epi32(zi, xyw));
            // SAFETY: `out` is four 8-byte entries (`repr(C)`: the depth word, then x and
            // y, any bits valid): two unaligned 16-byte stores cover them exactly.
            unsafe {
                let o = out.as_mut_ptr().cast::<__m128i>();
                _mm_storeu_si128(o, e01);
                _mm_storeu_si128(o.wrapping_add(1), e23);
            }
            placed
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The SSE2 loop (on hosts without it, the twin) places what `place_portable` places,
    /// with the same entries, over transforms like `place_check`'s: random coefficients,
    /// w near 2⁴² or anywhere within ±2⁴⁰, several viewports, random positions.
    #[test]
    fn place4_is_place_portable() {
        let mut rnd = crate::testing::xorshift32(0x2545_f491);
        let (mut placed, mut left) = (0, 0);
        for case in 0..64u32 {
            let mut within = |bits: u32| (rnd() as i32) >> (31 - bits);
            let mut rows = [[0u32; 3]; 6];
            for (r, row) in rows.iter_mut().enumerate() {
                let (c, t) = match r {
                    0 | 1 => ([within(14), within(14), within(14)], within(20)),
                    2 => ([within(11), within(11), within(11)], within(27)),
                    3 if case % 4 == 3 => ([within(11), within(11), within(11)], within(26)),
                    3 => ([within(11), within(11), within(11)], (1 << 28) + within(26)),
                    _ => ([0; 3].map(|_| within(14) & 0x3fff), within(14) & 0x3fff),
                };
                let [c0, c1, c2] = c;
                *row = [
                    crate::num::pack_i16(c0 as i16, c1 as i16),
                    c2 as u32,
                    t as u32,
                ];
            }
            let (hw, hh) = [(2560.0, 1920.0), (1920.0, 1920.0), (512.0, 384.0)][case as usize % 3];
            let f = [0.25, 1.0, 4.0][case as usize % 3];
            let (dx, dy) = ((case % 3) as f32 * 592.0 - 640.0, (case % 5) as f32 * 176.0);
            let block = PlaceBlock::new(rows, [hw * f, hw + dx, -hh * f, hh + dy]);
            let q = Quad::new(&block);
            for _ in 0..2000 {
                let p = [0; 4].map(|_| [rnd() as i16, rnd() as i16, rnd() as i16]);
                let mut got = [CachedVertex::EMPTY; 4];
                let mask = q.place4(&p, &mut got);
                for (k, (want, g)) in place4_portable(&block, &p).into_iter().zip(got).enumerate() {
                    let lane = (mask >> k & 1 != 0).then_some(g);
                    assert_eq!(lane, want, "case {case}, {p:?} lane {k}");
                    placed += usize::from(want.is_some());
                    left += usize::from(want.is_none());
                }
            }
        }
        assert!(
            placed > 100_000 && left > 40_000,
            "{placed} placed, {left} left"
        );
    }
}
