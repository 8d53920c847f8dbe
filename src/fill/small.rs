//! The fast path of the common case: a small triangle in one flat colour, drawn into a
//! colour buffer and a Z-buffer of the same geometry.
//!
//! It computes exactly what the general path computes (the same spans, the same depth
//! at every pixel: a test checks this on many random triangles), with everything in
//! local variables: edges set up in `i32` around a local origin, the depth plane's row
//! start stepped with one add a row, one index into both buffers, and the two halves of
//! the triangle walked by two plain loops.

use crate::fixed::{SUBPIXEL, SUBPIXEL_BITS};
use crate::num::{div_floor_pair, mul_i64_i32};
use crate::raster::{plane_origin, Clip, EdgeWalk, ScreenVertex, DEPTH_BIAS, SMALL};

/// Colour and depth rows of the same geometry, and the pixels drawing may touch.
pub(crate) struct Buffers<'z, 'c, C> {
    pub zdata: &'z mut [u16],
    pub cdata: &'c mut [C],
    pub width: usize,
    pub first_row: i32,
    pub clip: Clip,
}

/// The depth plane stepped per pixel and per row (wrapping `u32`, biased), with the
/// vertices' range to clamp each row start to: as [`crate::raster::DepthRows`] has it.
#[derive(Clone, Copy)]
struct Depth {
    z00: u32,
    sx: u32,
    sy: u32,
    lo: u32,
    hi: u32,
}

impl Depth {
    /// The depth plane, from the first vertex as the general path has it; `None` for a
    /// zero-area triangle. Out of line on the Cortex-M3/M4/M7, where its 64-bit
    /// arithmetic would crowd the registers of the whole setup; inline elsewhere.
    #[cfg_attr(zraster_thumb2, inline(never))]
    #[cfg_attr(not(zraster_thumb2), inline(always))]
    fn new(tri: &[ScreenVertex; 3]) -> Option<Depth> {
        let [p0, p1, p2] = tri;
        let (dx1, dy1) = (p1.x() - p0.x(), p1.y() - p0.y());
        let (dx2, dy2) = (p2.x() - p0.x(), p2.y() - p0.y());
        let area = dx1 * dy2 - dx2 * dy1; // < 2²⁷
        if area == 0 {
            return None;
        }
        // With multiply-accumulate (SMLAL) the offset form is the cheaper.
        let (a, bb) = if crate::num::THUMB2 {
            numerators_offset(tri, [dx1, dy1, dx2, dy2])
        } else {
            numerators_diff(tri, [dx1, dy1, dx2, dy2])
        };
        let (sx, sy) = div_floor_pair(
            a * i64::from(SUBPIXEL),
            bb * i64::from(SUBPIXEL),
            i64::from(area),
        );
        let (zlo, zhi) = (
            p0.z().min(p1.z()).min(p2.z()),
            p0.z().max(p1.z()).max(p2.z()),
        );
        Some(Depth {
            z00: plane_origin(p0, sx, sy),
            sx: sx as u32, // modulo 2³², on purpose (see plane_origin)
            sy: sy as u32,
            lo: zlo + DEPTH_BIAS,
            hi: zhi + DEPTH_BIAS,
        })
    }
}

/// The depth plane's numerators a = Δz1·dy2 − Δz2·dy1 and b = Δz2·dx1 − Δz1·dx2 of a
/// small triangle (Δzᵢ = zᵢ − z0, below 2³² in magnitude; |dx|, |dy| < 2¹³: both below
/// 2⁴⁶), from the differences.
#[inline(always)]
fn numerators_diff(tri: &[ScreenVertex; 3], [dx1, dy1, dx2, dy2]: [i32; 4]) -> (i64, i64) {
    let [p0, p1, p2] = tri;
    let (dz1, dz2) = (
        i64::from(p1.z()) - i64::from(p0.z()),
        i64::from(p2.z()) - i64::from(p0.z()),
    );
    (
        mul_i64_i32(dz1, dy2) - mul_i64_i32(dz2, dy1),
        mul_i64_i32(dz2, dx1) - mul_i64_i32(dz1, dx2),
    )
}

/// [`numerators_diff`] in 32×32 → 64-bit multiply-accumulates (one instruction each on
/// a Cortex-M3/M4): expanded, a = z0·(dy1 − dy2) + z1·dy2 − z2·dy1, whose coefficients
/// sum to zero, so each z may be taken as the `i32` z − 2³¹ (the offsets cancel). Each
/// product is below 2¹⁴·2³¹, the sums below 2⁴⁷. Likewise b.
#[inline(always)]
fn numerators_offset(tri: &[ScreenVertex; 3], [dx1, dy1, dx2, dy2]: [i32; 4]) -> (i64, i64) {
    let zc = |v: &ScreenVertex| (v.z() ^ 1 << 31) as i32;
    let [z0, z1, z2] = tri.each_ref().map(zc);
    let m = |c: i32, z: i32| i64::from(c) * i64::from(z);
    (
        m(dy1 - dy2, z0) + m(dy2, z1) - m(dy1, z2),
        m(dx2 - dx1, z0) + m(dx1, z2) - m(dx2, z1),
    )
}

/// Fill `tri` if it is small (extents below 512 pixels); `None` means "not for this
/// path", and nothing was drawn. Otherwise returns (pixels tested, pixels written).
#[inline(always)]
pub(crate) fn fill_small<C: Copy>(
    b: &mut Buffers<'_, '_, C>,
    tri: &[ScreenVertex; 3],
    color: C,
    write: bool,
    pass: impl Fn(u16, u16) -> bool + Copy,
) -> Option<(u32, u32)> {
    let [p0, p1, p2] = tri;
    let (xmin, xmax) = (
        p0.x().min(p1.x()).min(p2.x()),
        p0.x().max(p1.x()).max(p2.x()),
    );
    let (ymin, ymax) = (
        p0.y().min(p1.y()).min(p2.y()),
        p0.y().max(p1.y()).max(p2.y()),
    );
    if xmax - xmin >= SMALL || ymax - ymin >= SMALL {
        return None;
    }
    let Some(depth) = Depth::new(tri) else {
        return Some((0, 0));
    };

    // Vertices top to bottom, around the local origin (ox, oy).
    let (ox, oy) = (xmin & !(SUBPIXEL - 1), ymin & !(SUBPIXEL - 1));
    let mut v = [
        (p0.x() - ox, p0.y() - oy),
        (p1.x() - ox, p1.y() - oy),
        (p2.x() - ox, p2.y() - oy),
    ];
    if v[1].1 < v[0].1 {
        v.swap(0, 1);
    }
    if v[2].1 < v[1].1 {
        v.swap(1, 2);
    }
    if v[1].1 < v[0].1 {
        v.swap(0, 1);
    }
    let [v0, v1, v2] = v;
    let mid_right = (v1.0 - v0.0) * (v2.1 - v0.1) - (v2.0 - v0.0) * (v1.1 - v0.1) > 0;
    let (px0, py0) = (ox >> SUBPIXEL_BITS, oy >> SUBPIXEL_BITS);
    let row = |y: i32| ((y + (SUBPIXEL / 2 - 1)) >> SUBPIXEL_BITS) + py0;
    let (top, mid, bottom) = (row(v0.1), row(v1.1), row(v2.1));
    let start = top.max(b.clip.y0);
    let end = bottom.min(b.clip.y1);
    if start >= end || b.clip.x0 >= b.clip.x1 {
        return Some((0, 0));
    }
    let edge = |a: (i32, i32), c: (i32, i32), py: i32| {
        let mut e = EdgeWalk::new_small(a, c, py - py0);
        e.x += px0;
        e
    };
    let mut long = edge(v0, v2, start);
    let mut counts = (0, 0);
    let mut half = |left: &mut EdgeWalk, right: &mut EdgeWalk, from: i32, to: i32| {
        rows(
            b,
            left,
            right,
            from,
            to,
            depth,
            color,
            write,
            pass,
            &mut counts,
        );
    };
    // Two calls in each half rather than a choice of references: the loop then keeps
    // each edge in the same registers every row.
    let upper_end = mid.min(end);
    if start < upper_end {
        let mut short = edge(v0, v1, start);
        if mid_right {
            half(&mut long, &mut short, start, upper_end);
        } else {
            half(&mut short, &mut long, start, upper_end);
        }
    }
    let lower_start = mid.max(start);
    if lower_start < end {
        let mut short = edge(v1, v2, lower_start);
        if mid_right {
            half(&mut long, &mut short, lower_start, end);
        } else {
            half(&mut short, &mut long, lower_start, end);
        }
    }
    Some(counts)
}

/// Rows `from..to` between the `left` and `right` edges.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn rows<C: Copy>(
    b: &mut Buffers<'_, '_, C>,
    left: &mut EdgeWalk,
    right: &mut EdgeWalk,
    from: i32,
    to: i32,
    d: Depth,
    color: C,
    write: bool,
    pass: impl Fn(u16, u16) -> bool,
    (tested, written): &mut (u32, u32),
) {
    let (cx0, cx1) = (b.clip.x0, b.clip.x1);
    let mut row_z = d.z00.wrapping_add((from as u32).wrapping_mul(d.sy));
    let mut base = (from - b.first_row) as usize * b.width;
    for _ in from..to {
        let (xa, xb) = (left.x.max(cx0), right.x.min(cx1));
        left.advance();
        right.advance();
        if xa < xb {
            // lo ≤ hi: max then min is the clamp, without `clamp`'s check (which the
            // compiler sometimes leaves as a call here).
            let acc = row_z
                .wrapping_add((xa as u32).wrapping_mul(d.sx))
                .max(d.lo)
                .min(d.hi);
            let (s, e) = (base + xa as usize, base + xb as usize);
            if e == s + 1 {
                // One pixel, the commonest row of a small triangle: no call.
                if let (Some(zp), Some(cp)) = (b.zdata.get_mut(s), b.cdata.get_mut(s)) {
                    let z = (acc >> 16) as u16;
                    *tested += 1;
                    if pass(z, *zp) {
                        if write {
                            *zp = z;
                        }
                        *cp = color;
                        *written += 1;
                    }
                }
            } else if crate::num::ARM32 && e == s + 2 {
                // Two pixels inline too on Arm (x86-64 does better calling).
                if let (Some([z0, z1]), Some([c0, c1])) = (
                    b.zdata
                        .get_mut(s..e)
                        .and_then(|z| <&mut [u16; 2]>::try_from(z).ok()),
                    b.cdata
                        .get_mut(s..e)
                        .and_then(|c| <&mut [C; 2]>::try_from(c).ok()),
                ) {
                    *tested += 2;
                    let mut px = |zp: &mut u16, cp: &mut C, acc: u32| {
                        let z = (acc >> 16) as u16;
                        if pass(z, *zp) {
                            if write {
                                *zp = z;
                            }
                            *cp = color;
                            *written += 1;
                        }
                    };
                    px(z0, c0, acc);
                    px(z1, c1, acc.wrapping_add(d.sx));
                }
            } else if let (Some(zr), Some(cr)) = (b.zdata.get_mut(s..e), b.cdata.get_mut(s..e)) {
                let n = (xb - xa) as u32;
                let failed = super::flat_span(zr, cr, acc, d.sx, color, write, &pass);
                *tested += n;
                *written += n - failed;
            }
        }
        row_z = row_z.wrapping_add(d.sy);
        base += b.width;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The two forms of the plane numerators agree, at the ends of their ranges and on
    /// random small triangles.
    #[test]
    fn plane_numerator_forms_agree() {
        let mut rnd = crate::testing::xorshift32(0x2545_f491);
        let edge_z = [0, 1, 1 << 31, u32::MAX >> 1, crate::fixed::MAX_DEPTH];
        let edge_d = [-(SMALL - 1), -1, 0, 1, SMALL - 1];
        for i in 0..200_000u32 {
            let mut zs = [0u32; 3];
            for (k, z) in zs.iter_mut().enumerate() {
                *z = if i % 4 == 0 {
                    edge_z[(i as usize / 4 + k) % 5]
                } else {
                    rnd() % (crate::fixed::MAX_DEPTH + 1)
                };
            }
            let mut ds = [0i32; 4];
            for (k, d) in ds.iter_mut().enumerate() {
                *d = if i % 3 == 0 {
                    edge_d[(i as usize / 3 + k * 7) % 5]
                } else {
                    (rnd() % (2 * SMALL as u32 - 1)) as i32 - (SMALL - 1)
                };
            }
            let z = |k: usize| zs[k];
            let d = |k: usize| ds[k];
            let (dx1, dy1, dx2, dy2) = (d(0), d(1), d(2), d(3));
            let tri = [
                ScreenVertex::from_raw(0, 0, z(0)),
                ScreenVertex::from_raw(dx1, dy1, z(1)),
                ScreenVertex::from_raw(dx2, dy2, z(2)),
            ];
            let d4 = [dx1, dy1, dx2, dy2];
            assert_eq!(
                numerators_offset(&tri, d4),
                numerators_diff(&tri, d4),
                "{tri:?}"
            );
        }
    }
}
