//! The per-vertex transform in fixed point: the model-view-projection matrix with the
//! mesh scale folded in, applied to `i16` positions in exact integer arithmetic.
// Indexing here is into fixed 4-element arrays by constants below 4: it cannot panic.
#![allow(clippy::indexing_slicing)]

use crate::math::Mat4;
use crate::num::{dot2_add, pack_i16, shl64, DUAL_MAC};
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

    /// x and y in their own scale, and the exponent `e` of `s = 2^e` (x and y in the
    /// z/w scale are `x·2^e`, `y·2^e`), when `0 ≤ e ≤ 20` ([`xy_wide`](Clip4::xy_wide)'s
    /// range; `None` otherwise).
    #[inline]
    pub(crate) fn xy_scaled(self) -> Option<([i32; 2], u32)> {
        let e = (self.s.to_bits() as i32 >> 23) - 127;
        if !(0..=20).contains(&e) {
            return None;
        }
        Some((self.xy, e as u32))
    }

    /// z and w as their partial sums: `(hi, lo)`, each `[z, w]`, the value being
    /// `hi · 2¹⁴ + lo` (below 2⁴⁵ in magnitude).
    #[inline(always)]
    pub(crate) fn zw_parts(self) -> ([i32; 2], [i32; 2]) {
        (self.hi, self.lo)
    }

    /// The clip coordinates of these parts (tests build them directly).
    #[cfg(test)]
    pub(crate) fn from_parts(xy: [i32; 2], hi: [i32; 2], lo: [i32; 2], s: f32) -> Clip4 {
        Clip4 { xy, hi, lo, s }
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
/// The M0+'s single-cycle `MULS` suffices for all of it; a core with the DSP extension
/// takes `c₀·x + c₁·y` in one dual multiply-accumulate ([`RowOps::at`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FixedTransform {
    /// x, y, z high, w high, z low, w low.
    rows: [Row; 6],
    s: f32,
}

/// One row of [`FixedTransform`], `c₀·x + c₁·y + c₂·z + t`. Every coefficient fits 16
/// bits (|c| ≤ 16383): `c₀` and `c₁` are kept packed ([`pack_i16`]), for the dual
/// multiply-accumulate of cores that have one ([`dot2_add`]).
#[cfg(not(zraster_armv6m))]
#[derive(Debug, Clone, Copy, PartialEq)]
struct Row {
    c01: u32,
    c2: i32,
    t: i32,
}

/// One row of [`FixedTransform`] on ARMv6-M: `[c₀, c₁, c₂, t]`, as the vertex kernel
/// (`num::kernel::place_v6m`) reads the rows in place.
#[cfg(zraster_armv6m)]
type Row = [i32; 4];

/// What a row of [`FixedTransform`] does, whichever its form.
trait RowOps {
    /// The row of coefficients `c` (each within ±16383) and translation `t`.
    fn new(c: [i32; 3], t: i32) -> Self;
    /// `[c₀, c₁, c₂, t]`.
    fn coefficients(&self) -> [i32; 4];
    /// `c₀`, `c₁` packed ([`pack_i16`]).
    fn c01(&self) -> u32;

    /// `c₀c₁` packed ([`pack_i16`]), `c₂`, `t`.
    #[inline(always)]
    fn words(&self) -> [u32; 3] {
        let [_, _, c2, t] = self.coefficients();
        [self.c01(), c2 as u32, t as u32]
    }

    /// The row at `(x, y, z)`, with `xy` the pair `(x, y)` packed ([`pack_i16`]).
    #[inline(always)]
    fn at(&self, xy: u32, [x, y, z]: [i32; 3]) -> i32 {
        let [c0, c1, c2, t] = self.coefficients();
        let zt = c2 * z + t;
        if DUAL_MAC {
            dot2_add(xy, self.c01(), zt)
        } else {
            c0 * x + c1 * y + zt
        }
    }
}

#[cfg(not(zraster_armv6m))]
impl RowOps for Row {
    fn new([c0, c1, c2]: [i32; 3], t: i32) -> Row {
        Row {
            c01: pack_i16(c0 as i16, c1 as i16),
            c2,
            t,
        }
    }

    #[inline(always)]
    fn coefficients(&self) -> [i32; 4] {
        let (c0, c1) = (i32::from(self.c01 as i16), (self.c01 as i32) >> 16);
        [c0, c1, self.c2, self.t]
    }

    #[inline(always)]
    fn c01(&self) -> u32 {
        self.c01
    }
}

#[cfg(zraster_armv6m)]
impl RowOps for Row {
    fn new([c0, c1, c2]: [i32; 3], t: i32) -> Row {
        [c0, c1, c2, t]
    }

    #[inline(always)]
    fn coefficients(&self) -> [i32; 4] {
        *self
    }

    #[inline(always)]
    fn c01(&self) -> u32 {
        pack_i16(self[0] as i16, self[1] as i16)
    }
}

impl FixedTransform {
    #[inline(never)] // once a frame: its locals stay off the drawing code's stack
    pub(crate) fn new(mvp: &Mat4, scale: f32) -> Result<FixedTransform, Error> {
        // An exponent field of all ones: infinite or NaN.
        let finite = |v: f32| v.to_bits() & 0x7f80_0000 != 0x7f80_0000;
        if !finite(scale) {
            return Err(Error::NotFinite);
        }
        // Every value below is exact: a coefficient times the scale is a product of
        // two f32 mantissas (48 bits) and a power of two, kept as integers (no f64,
        // which a core without an FPU emulates in some 2 KB of library code). The
        // coefficients carry the mesh scale; the translation column does not.
        // Entry i of the matrix is row i / 4, column i % 4 (one loop each: their
        // bodies once in the code).
        let (m, scale) = (mvp.m.as_flattened(), Exact::of(scale));
        // Limits by pair of rows (x and y; z and w) and column (coefficient, translation).
        fn limit<T: Copy>(i: usize, table: [[T; 2]; 2]) -> T {
            table[i / 8][usize::from(i % 4 == 3)]
        }
        // Each pair of rows takes the largest power of two k that keeps all its values
        // within their limits: the least of each value's own.
        let mut k = [1000; 2];
        // Each value once (a product of two f32 is some 30 instructions).
        let mut values = [Exact { m: 0, e: 0 }; 16];
        for (i, v) in values.iter_mut().enumerate() {
            if !finite(m[i]) {
                return Err(Error::NotFinite);
            }
            let a = Exact::of(m[i]);
            // A zero stays zero: it bounds no k and rounds to 0 (camera matrices are
            // mostly zeros).
            if a.m != 0 {
                *v = if i % 4 < 3 { a.times(scale) } else { a };
                k[i / 8] = k[i / 8].min(v.largest_fit(limit(i, FIT_LIMITS), limit(i, FIT_ZEROS)));
            }
        }
        // Only zero values leave k at 1000 (any other fits below 2^400).
        if k[1] == 1000 {
            return Err(Error::InvalidParameter(
                "degenerate or overflowing transform",
            ));
        }
        let mut q = [[0; 4]; 4];
        for (i, v) in q.as_flattened_mut().iter_mut().enumerate() {
            *v = values[i].round_scaled(k[i / 8], limit(i, ROUND_LIMITS));
        }
        // z and w as hi·2¹⁴ + lo with 0 ≤ lo < 2¹⁴ (an arithmetic shift floors).
        let part = |r: usize, f: fn(i64) -> i32| q[r].map(f);
        let (xy, hi, lo) = (|v| v as i32, |v| (v >> 14) as i32, |v| (v & 0x3fff) as i32);
        Ok(FixedTransform::from_rows(
            [part(0, xy), part(1, xy)],
            [part(2, hi), part(3, hi)],
            [part(2, lo), part(3, lo)],
            pow2_f32(k[1] - k[0]),
        ))
    }

    /// The transform of the rows `[c₀, c₁, c₂, t]` (coefficients within ±16383).
    fn from_rows(xy: [[i32; 4]; 2], hi: [[i32; 4]; 2], lo: [[i32; 4]; 2], s: f32) -> Self {
        let [[x, y], [zh, wh], [zl, wl]] = [xy, hi, lo];
        let rows = [x, y, zh, wh, zl, wl].map(|[c0, c1, c2, t]| Row::new([c0, c1, c2], t));
        FixedTransform { rows, s }
    }

    /// The rows x, y, z high, w high, z low, w low as words (`c₀c₁` packed, `c₂`, `t`
    /// each), and the scale `s` of x and y to z and w: the vertex kernel's operands.
    pub(crate) fn words(&self) -> ([[u32; 3]; 6], f32) {
        (self.rows.map(|r| r.words()), self.s)
    }

    /// `f` of the rows x, y, z high, w high, z low, w low as `[c₀, c₁, c₂, t]` each: the
    /// ARMv6-M vertex kernel's operands (there the rows themselves, elsewhere a copy).
    #[inline(always)]
    pub(crate) fn with_rows_v6m<R>(&self, f: impl FnOnce(&[[i32; 4]; 6]) -> R) -> R {
        #[cfg(zraster_armv6m)]
        {
            f(&self.rows)
        }
        #[cfg(not(zraster_armv6m))]
        {
            f(&self.rows.map(|r| r.coefficients()))
        }
    }

    /// The scale `s` of x and y to z and w.
    pub(crate) fn scale(&self) -> f32 {
        self.s
    }

    /// Transform one position to clip space.
    #[inline]
    pub(crate) fn apply(&self, p: &[i16; 3]) -> Clip4 {
        let xy = pack_i16(p[0], p[1]);
        let p = p.map(i32::from);
        let [x, y, zh, wh, zl, wl] = &self.rows;
        Clip4 {
            xy: [x.at(xy, p), y.at(xy, p)],
            hi: [zh.at(xy, p), wh.at(xy, p)],
            lo: [zl.at(xy, p), wl.at(xy, p)],
            s: self.s,
        }
    }
}

/// A finite binary number `m · 2^e` held exactly (|m| < 2⁴⁸: an `f32`, or a product of
/// two), for setting up the fixed-point transform without floating point.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Exact {
    m: i64,
    e: i32,
}

impl Exact {
    /// A finite `f32`, exactly.
    fn of(v: f32) -> Exact {
        let bits = v.to_bits();
        let (exp, frac) = ((bits >> 23) & 0xff, i64::from(bits & 0x7f_ffff));
        let (m, e) = if exp == 0 {
            (frac, -149) // zero and subnormals
        } else {
            (frac | 1 << 23, exp as i32 - 150)
        };
        Exact {
            m: if v.is_sign_negative() { -m } else { m },
            e,
        }
    }

    /// `self · o`, exactly.
    fn times(self, o: Exact) -> Exact {
        Exact {
            m: self.m * o.m,
            e: self.e + o.e,
        }
    }

    /// The largest k in ±1000 with |self|·2^k ≤ lim (1000 for zero), for
    /// 0 < lim < 2⁶³ with `lim_zeros` leading zeros.
    fn largest_fit(self, lim: u64, lim_zeros: u32) -> i32 {
        let m = self.m.unsigned_abs();
        if m == 0 {
            return 1000;
        }
        // m·2^s has lim's top bit; one less when that is still above lim. Leading zeros
        // of 32-bit halves: one library call without CLZ (ARMv6-M), not two.
        let hi = (m >> 32) as u32;
        let zeros = if hi != 0 {
            hi.leading_zeros()
        } else {
            32 + (m as u32).leading_zeros()
        };
        let s = zeros as i32 - lim_zeros as i32;
        let over = if s >= 0 { m << s > lim } else { m > lim << -s };
        (s - i32::from(over) - self.e).clamp(-1000, 1000)
    }

    /// `self · 2^k` rounded to the nearest integer (halves away from zero), clamped to
    /// `±max`.
    fn round_scaled(self, k: i32, max: u64) -> i64 {
        let (m, s) = (self.m.unsigned_abs(), self.e + k);
        let r = if m == 0 {
            0
        } else if s >= 0 {
            if s >= 63 || m > max >> s {
                max
            } else {
                m << s
            }
        } else if -s >= 63 {
            0 // below 2⁴⁸⁻⁶³
        } else {
            (m + (1 << (-s - 1))) >> -s
        };
        let r = r.min(max) as i64;
        if self.m < 0 {
            -r
        } else {
            r
        }
    }
}

/// The limits of [`FixedTransform`]'s values when fitting the scale: x and y rows'
/// coefficients and translations, then z and w rows'.
const FIT_LIMITS: [[u64; 2]; 2] = [[16383, 1 << 29], [(1 << 27) - (1 << 14), 1 << 43]];

/// The leading zeros of each of [`FIT_LIMITS`].
const FIT_ZEROS: [[u32; 2]; 2] = {
    let [[a, b], [c, d]] = FIT_LIMITS;
    [
        [a.leading_zeros(), b.leading_zeros()],
        [c.leading_zeros(), d.leading_zeros()],
    ]
};

/// The clamps of [`FixedTransform`]'s values once scaled, ordered as [`FIT_LIMITS`].
const ROUND_LIMITS: [[u64; 2]; 2] = [[16383, 1 << 29], [1 << 27, 1 << 43]];

/// 2^k as `f32`, as converting the exact power would give it: infinite above 2¹²⁷,
/// subnormal down to 2⁻¹⁴⁹, zero below.
fn pow2_f32(k: i32) -> f32 {
    if k > 127 {
        f32::INFINITY
    } else if k >= -126 {
        f32::from_bits(((k + 127) as u32) << 23)
    } else if k >= -149 {
        f32::from_bits(1 << (k + 149))
    } else {
        0.0
    }
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

    /// The set-up as it was, in `f64` (exact for these products), as the reference.
    fn new_f64(mvp: &Mat4, scale: f32) -> Result<FixedTransform, Error> {
        fn pow2_f64(k: i32) -> f64 {
            f64::from_bits(((k.clamp(-1022, 1023) + 1023) as u64) << 52)
        }
        fn fit_f64(m: f64, t: f64, mlim: f64, tlim: f64) -> i32 {
            let fits = |k: i32| m * pow2_f64(k) <= mlim && t * pow2_f64(k) <= tlim;
            let mut k = 0i32;
            while k < 1000 && fits(k + 1) {
                k += 1;
            }
            while k > -1000 && !fits(k) {
                k -= 1;
            }
            k
        }
        // An exponent field of all ones: infinite or NaN.
        let finite = |v: f32| v.to_bits() & 0x7f80_0000 != 0x7f80_0000;
        if !finite(scale) {
            return Err(Error::NotFinite);
        }
        let scale = f64::from(scale);
        let value = |r: usize, c: usize| {
            let v = f64::from(mvp.m[r][c]);
            if c < 3 {
                v * scale
            } else {
                v
            }
        };
        let maxes = |rows: core::ops::Range<usize>| {
            let (mut m, mut t) = (0.0f64, 0.0f64);
            for r in rows {
                for c in 0..3 {
                    m = m.max(value(r, c).abs());
                }
                t = t.max(value(r, 3).abs());
            }
            (m, t)
        };
        let (mxy, txy) = maxes(0..2);
        let (mzw, tzw) = maxes(2..4);
        if mzw == 0.0 && tzw == 0.0 {
            return Err(Error::InvalidParameter(
                "degenerate or overflowing transform",
            ));
        }
        let kxy = fit_f64(mxy, txy, 16383.0, (1u32 << 29) as f64);
        let kzw = fit_f64(
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
        let (mut xy, mut hi, mut lo) = ([[0; 4]; 2], [[0; 4]; 2], [[0; 4]; 2]);
        for r in 0..4 {
            for c in 0..4 {
                let v = value(r, c);
                if r < 2 {
                    xy[r][c] = q(v, kxy, if c < 3 { 16383 } else { 1 << 29 }) as i32;
                } else {
                    let v = q(v, kzw, if c < 3 { 1 << 27 } else { 1 << 43 });
                    hi[r - 2][c] = (v >> 14) as i32;
                    lo[r - 2][c] = (v & 0x3fff) as i32;
                }
            }
        }
        Ok(FixedTransform::from_rows(
            xy,
            hi,
            lo,
            pow2_f64(kzw - kxy) as f32,
        ))
    }

    /// The integer set-up gives exactly the `f64` one's transform: for random matrices
    /// and scales over a wide range of magnitudes, signs, zeros and subnormals.
    #[test]
    fn integer_setup_matches_the_f64_one() {
        let mut next = crate::testing::xorshift32(0x2545_f491);
        let mut value = |wide: bool| -> f32 {
            let r = next();
            match r % 16 {
                0 => 0.0,
                1 => f32::from_bits(r >> 9), // subnormal or tiny
                2 => -1.0,
                _ => {
                    let e = if wide {
                        (r >> 4) % 200
                    } else {
                        (r >> 4) % 40 + 107
                    };
                    let bits = (e << 23) | (next() >> 9) | (r & 1 << 31);
                    f32::from_bits(bits)
                }
            }
        };
        let mut tested = 0;
        for i in 0..20_000 {
            let wide = i % 4 == 0;
            let mut m = Mat4 { m: [[0.0; 4]; 4] };
            for row in &mut m.m {
                for v in row.iter_mut() {
                    *v = value(wide);
                }
            }
            let scale = value(wide);
            let (got, want) = (FixedTransform::new(&m, scale), new_f64(&m, scale));
            assert_eq!(got, want, "{m:?} scale {scale:e}");
            tested += usize::from(got.is_ok());
        }
        assert!(tested > 10_000, "{tested}");
        // Exact powers of two, near the limits and ties of the rounding.
        for k in -60..60 {
            let p = f32::from_bits(((k + 127) as u32) << 23);
            let mut m = Mat4::IDENTITY;
            m.m[0][0] = 1.5 * p;
            m.m[2][3] = 16383.5 * p;
            m.m[3][2] = -0.5 * p;
            assert_eq!(FixedTransform::new(&m, 1.0), new_f64(&m, 1.0), "2^{k}");
        }
    }

    #[test]
    fn pow2_f32_converts_like_f64() {
        for k in -200..200 {
            let want = (2.0f64).powi(k) as f32;
            assert_eq!(pow2_f32(k).to_bits(), want.to_bits(), "2^{k}");
        }
    }
}
