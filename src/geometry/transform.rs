//! The per-vertex transform in fixed point: the model-view-projection matrix with the
//! mesh scale folded in, applied to `i16` positions in exact integer arithmetic.
// Indexing here is into fixed 4-element arrays by constants below 4: it cannot panic.
#![allow(clippy::indexing_slicing)]

use crate::math::Mat4;
use crate::num::shl64;
use crate::Error;

/// Clip-space coordinates in fixed point. x and y come in one scale, z and w in
/// another (`s`, a power of two, is x and y's factor to the z/w scale); z and w are
/// two partial sums each, the value being `hi · 2¹⁴ + lo`. See [`FixedTransform`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Clip4 {
    xy: [i32; 2],
    hi: [i32; 2],
    lo: [i32; 2],
    s: f32,
}

impl Clip4 {
    /// z and w exactly (below 2⁴⁵ in magnitude), in their common scale.
    #[inline]
    pub(crate) fn zw(self) -> (i64, i64) {
        let w = |r: usize| (i64::from(self.hi[r]) << 14) + i64::from(self.lo[r]);
        (w(0), w(1))
    }

    /// x and y in the z/w scale, exactly, when that scale is at most 2²⁰ times finer
    /// (always, for perspective and orthographic cameras; `None` otherwise).
    #[inline]
    pub(crate) fn xy_wide(self) -> Option<(i64, i64)> {
        let e = self.s.to_bits() as i32 >> 23; // the exponent of the power of two s
        let e = e - 127;
        if !(0..=20).contains(&e) {
            return None;
        }
        // e ≤ 20: x and y stay below 2⁵¹.
        let e = e as u32;
        Some((
            shl64(i64::from(self.xy[0]), e),
            shl64(i64::from(self.xy[1]), e),
        ))
    }

    /// The four coordinates as `f32` in one scale, each rounded once: no 64-bit
    /// conversion.
    #[inline]
    pub(crate) fn to_f32(self) -> [f32; 4] {
        let f = |r: usize| self.hi[r] as f32 * 16384.0 + self.lo[r] as f32;
        [
            self.xy[0] as f32 * self.s,
            self.xy[1] as f32 * self.s,
            f(0),
            f(1),
        ]
    }
}

/// The model-view-projection matrix with the mesh's position scale folded in, in
/// fixed point, for `i16` positions `p`.
///
/// The x and y rows have 14-bit coefficients (`|C| ≤ 16383`, `|T| ≤ 2²⁹`): a row
/// `Σ C·p + T ≤ 3·16383·32768 + 2²⁹ < 2³¹` is three 16×16-bit products, exact in `i32`,
/// and 14 bits place a vertex to a hundredth of a pixel. Depth needs more: the z and w
/// rows carry 27-bit coefficients (the `f32` matrix's full precision; with 14 bits every
/// object's depth would be off by a few units, differently for each model matrix). Each
/// is split as `C = hi·2¹⁴ + lo` with `|hi| ≤ 2¹³` and `0 ≤ lo < 2¹⁴` (`T` likewise,
/// `|T_hi| ≤ 2²⁹`), so both partial sums stay exact in `i32`:
/// `Σ hi·p + T_hi ≤ 3·2¹³·2¹⁵ + 2²⁹ < 2³¹` and `Σ lo·p + T_lo < 3·2¹⁴·2¹⁵ + 2¹⁴ < 2³¹`.
/// The M0+'s single-cycle `MULS` suffices for all of it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FixedTransform {
    xy: [[i32; 4]; 2],
    hi: [[i32; 4]; 2],
    lo: [[i32; 4]; 2],
    s: f32,
}

impl FixedTransform {
    pub(crate) fn new(mvp: &Mat4, scale: f32) -> Result<FixedTransform, Error> {
        if !mvp.is_finite() || !scale.is_finite() {
            return Err(Error::NotFinite);
        }
        let scale = f64::from(scale);
        let maxes = |rows: &[[f32; 4]]| {
            let (mut m, mut t) = (0.0f64, 0.0f64);
            for row in rows {
                for v in &row[..3] {
                    m = m.max((f64::from(*v) * scale).abs());
                }
                t = t.max(f64::from(row[3]).abs());
            }
            (m, t)
        };
        let (mxy, txy) = maxes(&mvp.m[..2]);
        let (mzw, tzw) = maxes(&mvp.m[2..]);
        if !(mxy.is_finite() && txy.is_finite() && mzw.is_finite() && tzw.is_finite())
            || (mzw == 0.0 && tzw == 0.0)
        {
            return Err(Error::InvalidParameter(
                "degenerate or overflowing transform",
            ));
        }
        let kxy = fit_exponent(mxy, txy, 16383.0, (1u32 << 29) as f64);
        let kzw = fit_exponent(
            mzw,
            tzw,
            ((1u64 << 27) - (1 << 14)) as f64,
            (1u64 << 43) as f64,
        );
        let q = |v: f64, k: i32, max: i64| {
            let r = v * pow2_f64(k);
            let r = if r >= 0.0 { r + 0.5 } else { r - 0.5 };
            (r as i64).clamp(-max, max)
        };
        let mut out = FixedTransform {
            xy: [[0; 4]; 2],
            hi: [[0; 4]; 2],
            lo: [[0; 4]; 2],
            s: pow2_f64(kzw - kxy) as f32,
        };
        for (r, row) in mvp.m.iter().enumerate() {
            for (c, &v) in row.iter().enumerate() {
                // Coefficients carry the mesh scale; the translation column does not.
                let v = if c < 3 {
                    f64::from(v) * scale
                } else {
                    f64::from(v)
                };
                if r < 2 {
                    let max = if c < 3 { 16383 } else { 1 << 29 };
                    out.xy[r][c] = q(v, kxy, max) as i32;
                } else {
                    let v = q(v, kzw, if c < 3 { 1 << 27 } else { 1 << 43 });
                    // v = hi·2¹⁴ + lo with 0 ≤ lo < 2¹⁴ (an arithmetic shift floors).
                    out.hi[r - 2][c] = (v >> 14) as i32;
                    out.lo[r - 2][c] = (v & 0x3fff) as i32;
                }
            }
        }
        Ok(out)
    }

    /// Transform one position to clip space.
    #[inline]
    pub(crate) fn apply(&self, p: &[i16; 3]) -> Clip4 {
        let (x, y, z) = (i32::from(p[0]), i32::from(p[1]), i32::from(p[2]));
        let row = |m: &[i32; 4]| m[0] * x + m[1] * y + m[2] * z + m[3];
        Clip4 {
            xy: [row(&self.xy[0]), row(&self.xy[1])],
            hi: [row(&self.hi[0]), row(&self.hi[1])],
            lo: [row(&self.lo[0]), row(&self.lo[1])],
            s: self.s,
        }
    }
}

/// The largest power of two k in ±1000 with m·2^k ≤ mlim and t·2^k ≤ tlim (−1000 if
/// none), for non-negative m, t. `fits` only turns false as k grows, so the search may
/// start anywhere: it starts one below the guess from the binary exponents and so takes a
/// step or two (each a pair of soft-float products on an MCU) instead of tens.
fn fit_exponent(m: f64, t: f64, mlim: f64, tlim: f64) -> i32 {
    let fits = |k: i32| m * pow2_f64(k) <= mlim && t * pow2_f64(k) <= tlim;
    let room = |v: f64, lim: f64| {
        if v > 0.0 {
            ilog2_f64(lim) - ilog2_f64(v) - 1
        } else {
            i32::MAX
        }
    };
    let mut k = room(m, mlim).min(room(t, tlim)).clamp(-1000, 1000);
    while k < 1000 && fits(k + 1) {
        k += 1;
    }
    while k > -1000 && !fits(k) {
        k -= 1;
    }
    k
}

/// The binary exponent of a positive, finite `f64` (⌊log₂ v⌋ for normal numbers; −1023
/// for subnormals, which only makes the search above start higher).
fn ilog2_f64(v: f64) -> i32 {
    ((v.to_bits() >> 52) & 0x7ff) as i32 - 1023
}

/// 2^k as `f64`.
fn pow2_f64(k: i32) -> f64 {
    f64::from_bits(((k.clamp(-1022, 1023) + 1023) as u64) << 52)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::{Camera, Viewport};
    use crate::geometry::project::ScreenMap;
    use crate::math::{radians, Vec3};

    #[test]
    fn the_fixed_transform_matches_the_float_one() {
        let vp = Viewport::new(320, 240).unwrap();
        let xf = Camera::look_at(Vec3::new(0.0, 0.0, 2.5), Vec3::default(), Vec3::Y)
            .unwrap()
            .perspective(radians(60.0), 0.1, 10.0, vp)
            .unwrap()
            .with_model(Mat4::rotation_x(radians(20.0)) * Mat4::rotation_y(radians(30.0)));
        let mvp = xf.model_view_projection();
        let scale = 1.0 / 32767.0;
        let fx = FixedTransform::new(&mvp, scale).unwrap();
        let map = ScreenMap::new(&vp);
        for p in [[32767i16, -32768, 100], [0, 0, 0], [-20000, 12345, 32767]] {
            let pf = Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32) * scale;
            let c = mvp.transform_point(pf);
            let sx = (c[0] / c[3] + 1.0) * 160.0 * 16.0;
            let sy = (1.0 - c[1] / c[3]) * 120.0 * 16.0;
            let v = map.project(&fx.apply(&p).to_f32()).unwrap();
            assert!((v.x() as f32 - sx).abs() <= 1.0, "{p:?}: {} vs {sx}", v.x());
            assert!((v.y() as f32 - sy).abs() <= 1.0, "{p:?}: {} vs {sy}", v.y());
            let zw = (c[2] / c[3] + 1.0) * 0.5 * 65535.0 * 65536.0;
            let err = (v.z() as f32 - zw) / 65536.0;
            assert!(err.abs() < 0.05, "{p:?}: depth error {err}");
        }
    }

    #[test]
    fn transform_rejects_bad_matrices() {
        let mut m = Mat4::IDENTITY;
        m.m[1][2] = f32::NAN;
        assert_eq!(FixedTransform::new(&m, 1.0), Err(Error::NotFinite));
        let z = Mat4 { m: [[0.0; 4]; 4] };
        assert!(FixedTransform::new(&z, 1.0).is_err());
        assert_eq!(
            FixedTransform::new(&Mat4::IDENTITY, f32::INFINITY),
            Err(Error::NotFinite)
        );
    }

    #[test]
    fn fit_exponent_matches_the_search_from_zero() {
        // The search as it was: from k = 0, one step at a time.
        let reference = |m: f64, t: f64, mlim: f64, tlim: f64| {
            let fits = |k: i32| m * pow2_f64(k) <= mlim && t * pow2_f64(k) <= tlim;
            let mut k = 0i32;
            while k < 1000 && fits(k + 1) {
                k += 1;
            }
            while k > -1000 && !fits(k) {
                k -= 1;
            }
            k
        };
        let mut next = crate::testing::xorshift32(0x2545_f491);
        let lims = [
            (16383.0, (1u32 << 29) as f64),
            (((1u64 << 27) - (1 << 14)) as f64, (1u64 << 43) as f64),
        ];
        let mut values = std::vec![
            0.0,
            f64::MIN_POSITIVE,
            5e-324,
            1e-300,
            1.0,
            16383.0,
            16384.0,
            1e300,
            f64::MAX,
        ];
        for _ in 0..2000 {
            // Mantissas at and near powers of two, across a wide exponent range.
            let e = (next() % 200) as i32 - 100;
            let mant = [1.0, 1.0 + f64::EPSILON, 2.0 - f64::EPSILON, 1.5][(next() % 4) as usize];
            values.push(mant * pow2_f64(e));
            values.push(f64::from(next()) / f64::from(next().max(1)));
        }
        for (i, &m) in values.iter().enumerate() {
            let t = values[(i * 7 + 3) % values.len()];
            for &(mlim, tlim) in &lims {
                assert_eq!(
                    fit_exponent(m, t, mlim, tlim),
                    reference(m, t, mlim, tlim),
                    "{m:e} {t:e}"
                );
            }
        }
    }
}
