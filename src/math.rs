//! Small `f32` vector and matrix types for building a frame's transforms.
//!
//! These run once per frame (or once per object), not per vertex: the per-vertex path
//! uses the fixed-point form of [`Mat4`] built by the pipeline. Trigonometry and square
//! roots are computed here to about 1e-7 relative error without `std`, so that host
//! tests and firmware produce the same matrices. (micromath's `sin` is within ~1e-3,
//! which moves vertices by a fifth of a pixel on a 320-pixel screen; its `sqrt` seeds
//! the Newton steps used here.)
// Indexing here is into fixed 4×4 arrays by loop constants below 4: it cannot panic.
#![allow(clippy::indexing_slicing)]

use core::ops::{Add, Mul, Neg, Sub};
use micromath::F32Ext;

/// A 3-component `f32` vector.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Vec3 {
    /// x
    pub x: f32,
    /// y
    pub y: f32,
    /// z
    pub z: f32,
}

impl Vec3 {
    /// The unit vector along +X.
    pub const X: Vec3 = Vec3::new(1.0, 0.0, 0.0);
    /// The unit vector along +Y (up, for a camera looking along the horizon).
    pub const Y: Vec3 = Vec3::new(0.0, 1.0, 0.0);
    /// The unit vector along +Z (towards a camera at the default orientation).
    pub const Z: Vec3 = Vec3::new(0.0, 0.0, 1.0);

    /// A vector from components.
    pub const fn new(x: f32, y: f32, z: f32) -> Vec3 {
        Vec3 { x, y, z }
    }

    /// The dot product.
    pub fn dot(self, o: Vec3) -> f32 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// The cross product `self × o`.
    pub fn cross(self, o: Vec3) -> Vec3 {
        Vec3::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }

    /// The length.
    pub fn length(self) -> f32 {
        sqrt(self.dot(self))
    }

    /// The unit vector in the same direction, or zero for a zero (or non-finite) vector.
    pub fn normalize(self) -> Vec3 {
        let l = self.length();
        // Positive and finite; without an FPU by the bits (float compares are calls).
        let positive = if crate::num::SOFT_FLOAT {
            l.to_bits().wrapping_sub(1) < 0x7f7f_ffff
        } else {
            l > 0.0 && l.is_finite()
        };
        if positive {
            self * (1.0 / l)
        } else {
            Vec3::default()
        }
    }

    /// Are all components finite?
    pub fn is_finite(self) -> bool {
        finite(self.x) && finite(self.y) && finite(self.z)
    }
}

impl Add for Vec3 {
    type Output = Vec3;
    fn add(self, o: Vec3) -> Vec3 {
        Vec3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl Sub for Vec3 {
    type Output = Vec3;
    fn sub(self, o: Vec3) -> Vec3 {
        Vec3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl Neg for Vec3 {
    type Output = Vec3;
    fn neg(self) -> Vec3 {
        Vec3::new(-self.x, -self.y, -self.z)
    }
}

impl Mul<f32> for Vec3 {
    type Output = Vec3;
    fn mul(self, s: f32) -> Vec3 {
        Vec3::new(self.x * s, self.y * s, self.z * s)
    }
}

/// A 4×4 `f32` matrix, row-major: `m[row][col]`, applied to column vectors (`M · v`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mat4 {
    /// The elements, `m[row][col]`.
    pub m: [[f32; 4]; 4],
}

impl Default for Mat4 {
    fn default() -> Self {
        Mat4::IDENTITY
    }
}

impl Mat4 {
    /// The identity.
    pub const IDENTITY: Mat4 = Mat4 {
        m: [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ],
    };

    /// A translation by `t`.
    pub fn translation(t: Vec3) -> Mat4 {
        let mut r = Mat4::IDENTITY;
        r.m[0][3] = t.x;
        r.m[1][3] = t.y;
        r.m[2][3] = t.z;
        r
    }

    /// A scaling by `s` along each axis.
    pub fn scaling(s: Vec3) -> Mat4 {
        let mut r = Mat4::IDENTITY;
        r.m[0][0] = s.x;
        r.m[1][1] = s.y;
        r.m[2][2] = s.z;
        r
    }

    /// A right-handed rotation about +X by `angle` radians.
    pub fn rotation_x(angle: f32) -> Mat4 {
        let (s, c) = sin_cos(angle);
        let mut r = Mat4::IDENTITY;
        r.m[1][1] = c;
        r.m[1][2] = -s;
        r.m[2][1] = s;
        r.m[2][2] = c;
        r
    }

    /// A right-handed rotation about +Y by `angle` radians.
    pub fn rotation_y(angle: f32) -> Mat4 {
        let (s, c) = sin_cos(angle);
        let mut r = Mat4::IDENTITY;
        r.m[0][0] = c;
        r.m[0][2] = s;
        r.m[2][0] = -s;
        r.m[2][2] = c;
        r
    }

    /// A right-handed rotation about +Z by `angle` radians.
    pub fn rotation_z(angle: f32) -> Mat4 {
        let (s, c) = sin_cos(angle);
        let mut r = Mat4::IDENTITY;
        r.m[0][0] = c;
        r.m[0][1] = -s;
        r.m[1][0] = s;
        r.m[1][1] = c;
        r
    }

    /// A view matrix for an eye at `eye` looking at `target` with `up` roughly up
    /// (gluLookAt): the camera looks down its −Z axis.
    pub fn look_at(eye: Vec3, target: Vec3, up: Vec3) -> Mat4 {
        let f = (target - eye).normalize();
        let s = f.cross(up).normalize();
        let u = s.cross(f);
        Mat4 {
            m: [
                [s.x, s.y, s.z, -s.dot(eye)],
                [u.x, u.y, u.z, -u.dot(eye)],
                [-f.x, -f.y, -f.z, f.dot(eye)],
                [0.0, 0.0, 0.0, 1.0],
            ],
        }
    }

    /// A perspective projection (gluPerspective): vertical field of view `fovy` in
    /// radians, `aspect` = width / height, clip planes at distances `near` and `far`.
    pub fn perspective(fovy: f32, aspect: f32, near: f32, far: f32) -> Mat4 {
        let (s, c) = sin_cos(fovy * 0.5);
        let f = c / s;
        let d = near - far;
        Mat4 {
            m: [
                [f / aspect, 0.0, 0.0, 0.0],
                [0.0, f, 0.0, 0.0],
                [0.0, 0.0, (far + near) / d, 2.0 * far * near / d],
                [0.0, 0.0, -1.0, 0.0],
            ],
        }
    }

    /// An orthographic projection (glOrtho).
    pub fn orthographic(left: f32, right: f32, bottom: f32, top: f32, near: f32, far: f32) -> Mat4 {
        let (w, h, d) = (right - left, top - bottom, far - near);
        Mat4 {
            m: [
                [2.0 / w, 0.0, 0.0, -(right + left) / w],
                [0.0, 2.0 / h, 0.0, -(top + bottom) / h],
                [0.0, 0.0, -2.0 / d, -(far + near) / d],
                [0.0, 0.0, 0.0, 1.0],
            ],
        }
    }

    /// Apply to the point `p` (w = 1), returning homogeneous (x, y, z, w).
    pub fn transform_point(&self, p: Vec3) -> [f32; 4] {
        let m = &self.m;
        let row = |r: usize| m[r][0] * p.x + m[r][1] * p.y + m[r][2] * p.z + m[r][3];
        [row(0), row(1), row(2), row(3)]
    }

    /// Apply the upper-left 3×3 part to the direction `d`.
    pub fn transform_dir(&self, d: Vec3) -> Vec3 {
        let m = &self.m;
        Vec3::new(
            m[0][0] * d.x + m[0][1] * d.y + m[0][2] * d.z,
            m[1][0] * d.x + m[1][1] * d.y + m[1][2] * d.z,
            m[2][0] * d.x + m[2][1] * d.y + m[2][2] * d.z,
        )
    }

    /// Apply the transpose of the upper-left 3×3 part to `d` (the inverse rotation, for
    /// a rotation matrix).
    pub fn transpose_dir(&self, d: Vec3) -> Vec3 {
        let m = &self.m;
        Vec3::new(
            m[0][0] * d.x + m[1][0] * d.y + m[2][0] * d.z,
            m[0][1] * d.x + m[1][1] * d.y + m[2][1] * d.z,
            m[0][2] * d.x + m[1][2] * d.y + m[2][2] * d.z,
        )
    }

    /// Are all elements finite?
    pub fn is_finite(&self) -> bool {
        // An exponent field of all ones (infinite or NaN) carries into the top bit:
        // one OR of the 16 sums, without a branch each (or a float compare, a library
        // call without an FPU).
        let exp = |v: &f32| (v.to_bits() & 0x7f80_0000).wrapping_add(0x0080_0000);
        self.m.iter().flatten().fold(0, |acc, v| acc | exp(v)) >> 31 == 0
    }
}

impl Mul for Mat4 {
    type Output = Mat4;
    #[inline(never)]
    fn mul(self, o: Mat4) -> Mat4 {
        // Without an FPU, the 16 sums inlined are a kilobyte of library calls (run once
        // a frame): one loop over the 64 products instead, most of them left out.
        if crate::num::SOFT_FLOAT {
            return mul_sparse(&self, &o);
        }
        let mut r = [[0.0f32; 4]; 4];
        for (row, a) in r.iter_mut().zip(&self.m) {
            for (j, v) in row.iter_mut().enumerate() {
                *v = row_times_column(a, &o, j);
            }
        }
        Mat4 { m: r }
    }
}

/// Row `a` times column `j` of `o`.
#[inline(always)]
fn row_times_column(a: &[f32; 4], o: &Mat4, j: usize) -> f32 {
    (0..4).map(|k| a[k] * o.m[k][j]).sum()
}

/// `a · b` as [`row_times_column`] gives it, bit for bit, without the products of an
/// exact zero and a finite value (each a soft-float multiply and add: camera matrices
/// are mostly zeros). Such a product is ±0, and x + ±0 is x but for x = −0: a sum of −0
/// takes the product's sign.
#[inline(always)]
fn mul_sparse(a: &Mat4, b: &Mat4) -> Mat4 {
    let (a, b) = (a.m.as_flattened(), b.m.as_flattened());
    let mut r = Mat4 { m: [[0.0; 4]; 4] };
    // Sum s: row s / 4 of a by column s % 4 of b, its 4 terms in order of k (the sum
    // stays in a register across them).
    for (s, out) in r.m.as_flattened_mut().iter_mut().enumerate() {
        let mut sum = -0.0f32;
        for k in 0..4 {
            let (x, y) = (a[s / 4 * 4 + k], b[k * 4 + s % 4]);
            let (bx, by) = (x.to_bits(), y.to_bits());
            // Magnitudes' bits: 0 for a zero, below 0xff00_0000 when finite.
            let (mx, my) = (bx << 1, by << 1);
            if mx.min(my) == 0 && mx.max(my) < 0xff00_0000 {
                if sum.to_bits() == 1 << 31 {
                    sum = f32::from_bits((bx ^ by) & 1 << 31);
                }
            } else {
                sum += x * y;
            }
        }
        *out = sum;
    }
    r
}

/// Degrees to radians: zraster takes every angle in radians (rotations, fields of
/// view), so `radians(45.0)` is how to say 45°.
pub fn radians(deg: f32) -> f32 {
    deg * (core::f32::consts::PI / 180.0)
}

/// The square root, to within an ulp or two (micromath's estimate and three Newton steps).
pub fn sqrt(v: f32) -> f32 {
    if v <= 0.0 || !v.is_finite() {
        return if v == 0.0 || v.is_infinite() {
            v
        } else {
            f32::NAN
        };
    }
    // micromath's estimate is within ~5%; each Newton step squares the relative error.
    let mut r = F32Ext::sqrt(v);
    for _ in 0..3 {
        r = half(r + v / r);
    }
    r
}

/// Whether `v` is finite; without an FPU by its exponent field (a float compare is a
/// library call).
#[inline(always)]
pub(crate) fn finite(v: f32) -> bool {
    finite_as(v, crate::num::SOFT_FLOAT)
}

/// [`finite`], by the bits when `soft` (tests take both ways on any target).
#[inline(always)]
fn finite_as(v: f32, soft: bool) -> bool {
    if soft {
        v.to_bits() & 0x7f80_0000 != 0x7f80_0000
    } else {
        v.is_finite()
    }
}

/// `v · 2¹⁵` rounded as [`round_f32`](crate::num::round_f32) rounds it, for a finite `v`
/// with |v| < 2¹⁵. Without an FPU the product by the exponent (exact for a normal
/// result) and the truncation by the bits (each a library call of some 50
/// instructions, the conversion with three float compares). Out of line there: five
/// uses a frame.
#[cfg_attr(zraster_soft_float, inline(never))]
#[cfg_attr(not(zraster_soft_float), inline(always))]
pub(crate) fn round_q15(v: f32) -> i32 {
    round_q15_as(v, crate::num::SOFT_FLOAT)
}

/// [`round_q15`], by the bits when `soft`.
#[inline(always)]
fn round_q15_as(v: f32, soft: bool) -> i32 {
    if !soft {
        return crate::num::round_f32(v * 32768.0);
    }
    let bits = v.to_bits();
    let x = if (bits >> 23 & 0xff).wrapping_sub(1) < 254 - 15 {
        // Exponent fields 1 to 239: v · 2¹⁵ is normal, and exact.
        f32::from_bits(bits + (15 << 23))
    } else {
        // (Opaque: else the multiply is made on both paths, the choice after it.)
        core::hint::black_box(v) * 32768.0
    };
    // round_f32's sum, truncated toward zero: |y| < 2³¹.
    let y = (x + 0.5f32.copysign(x)).to_bits();
    let (e, m) = (
        (y >> 23 & 0xff) as i32 - 150,
        (y & 0x7f_ffff | 0x80_0000) as i32,
    );
    let t = if e < -23 {
        0
    } else if e < 0 {
        m >> -e
    } else {
        m << e
    };
    if y >> 31 != 0 {
        -t
    } else {
        t
    }
}

/// `v.clamp(-2.0, 2.0)` for a finite `v`; without an FPU by the bits (float compares
/// are library calls).
#[inline(always)]
pub(crate) fn clamp2(v: f32) -> f32 {
    clamp2_as(v, crate::num::SOFT_FLOAT)
}

/// [`clamp2`], by the bits when `soft`.
#[inline(always)]
fn clamp2_as(v: f32, soft: bool) -> f32 {
    let bits = v.to_bits();
    if !soft {
        v.clamp(-2.0, 2.0)
    } else if bits & 0x7fff_ffff > 0x4000_0000 {
        f32::from_bits(bits & 0x8000_0000 | 0x4000_0000)
    } else {
        v
    }
}

/// `0.5 · v`; without an FPU, for a normal result, by the exponent (a soft-float
/// multiply is some 50 instructions).
#[inline(always)]
fn half(v: f32) -> f32 {
    half_as(v, crate::num::SOFT_FLOAT)
}

/// [`half`], by the exponent when `soft`.
#[inline(always)]
fn half_as(v: f32, soft: bool) -> f32 {
    let bits = v.to_bits();
    if !soft {
        0.5 * v
    } else if (bits >> 23 & 0xff).wrapping_sub(2) < 253 {
        // Exponent fields 2 to 254: v / 2 is normal, and exact.
        f32::from_bits(bits - (1 << 23))
    } else {
        // (Opaque: else the multiply is made on both paths, the choice after it.)
        0.5 * core::hint::black_box(v)
    }
}

/// Sine and cosine of `x` radians, to about 1e-7 absolute error for |x| ≤ 10⁴.
pub fn sin_cos(x: f32) -> (f32, f32) {
    if !x.is_finite() {
        return (f32::NAN, f32::NAN);
    }
    use core::f64::consts::FRAC_PI_2;
    // Reduce in f64 to [-π/4, π/4] around the nearest multiple of π/2. Every division
    // is a product by the divisor's reciprocal: without an FPU an f64 division is a
    // kilobyte of library code (the results are those of the divisions for every f32
    // tried: each 7th in ±8, and more up to 10⁴).
    const TWO_OVER_PI: f64 = 1.0 / FRAC_PI_2;
    let xd = f64::from(x);
    let kf = xd * TWO_OVER_PI;
    let k = if kf >= 0.0 {
        (kf + 0.5) as i64
    } else {
        (kf - 0.5) as i64
    };
    let r = xd - k as f64 * FRAC_PI_2;
    let r2 = r * r;
    // r² / n.
    let t = |n: f64| r2 * (1.0 / n);
    // Taylor series to r¹¹ / r¹²: error below 1e-12 on [-π/4, π/4].
    let s =
        r * (1.0 - t(6.0) * (1.0 - t(20.0) * (1.0 - t(42.0) * (1.0 - t(72.0) * (1.0 - t(110.0))))));
    let c = 1.0
        - t(2.0)
            * (1.0
                - t(12.0) * (1.0 - t(30.0) * (1.0 - t(56.0) * (1.0 - t(90.0) * (1.0 - t(132.0))))));
    let (s, c) = match k.rem_euclid(4) {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    };
    (s as f32, c as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mat4_is_finite_tests_every_element() {
        assert!(Mat4::IDENTITY.is_finite());
        let finite = [
            0.0,
            -0.0,
            f32::MAX,
            f32::MIN,
            f32::MIN_POSITIVE,
            1e-45,
            -1.5,
        ];
        let bad = [f32::NAN, -f32::NAN, f32::INFINITY, f32::NEG_INFINITY];
        for i in 0..16 {
            for (v, want) in finite
                .iter()
                .map(|&v| (v, true))
                .chain(bad.iter().map(|&v| (v, false)))
            {
                let mut m = Mat4::IDENTITY;
                m.m[i / 4][i % 4] = v;
                assert_eq!(m.is_finite(), want, "{v} at {i}");
            }
        }
    }

    #[test]
    fn the_sparse_product_is_the_full_one_bit_for_bit() {
        // Zeros of both signs, infinities, NaN, subnormals and values whose products
        // cancel, overflow or underflow.
        let special = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            1e-45,
            -3e38,
            3e38,
            1e-30,
            0.1,
        ];
        let mut next = crate::testing::xorshift64(0x9e37_79b9_7f4a_7c15);
        let mut pick = || {
            let r = next();
            if r.is_multiple_of(3) {
                f32::from_bits((r >> 32) as u32)
            } else {
                special[(r >> 8) as usize % special.len()]
            }
        };
        for n in 0..100_000u32 {
            let (mut a, mut b) = (Mat4::IDENTITY, Mat4::IDENTITY);
            a.m.as_flattened_mut().iter_mut().for_each(|v| *v = pick());
            b.m.as_flattened_mut().iter_mut().for_each(|v| *v = pick());
            // Every other pair finite (every zero's products left out).
            if n.is_multiple_of(2) {
                for v in
                    a.m.as_flattened_mut()
                        .iter_mut()
                        .chain(b.m.as_flattened_mut())
                {
                    if !v.is_finite() {
                        *v = if v.is_nan() { 0.0 } else { -0.0 };
                    }
                }
            }
            let got = mul_sparse(&a, &b);
            for (i, got) in got.m.iter().enumerate() {
                for (j, &got) in got.iter().enumerate() {
                    let want = row_times_column(&a.m[i], &b, j);
                    assert!(
                        want.to_bits() == got.to_bits() || want.is_nan() && got.is_nan(),
                        "{a:?} {b:?} {i} {j}: {want:?} vs {got:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn round_q15_and_clamp2_are_the_float_ones() {
        let mut next = crate::testing::xorshift64(0x0bad_cafe_f00d_d00d);
        let special = [
            0.0,
            -0.0,
            1e-45,
            -1e-38,
            1.17e-38,
            0.5 / 32768.0,
            -1.5 / 32768.0,
        ];
        let more = [
            1.0, -1.0, 2.0, -2.0, 2.0000002, -2.0000002, 0.2, 0.8, 32767.998,
        ];
        let random = (0..200_000).map(|_| f32::from_bits(next() as u32));
        let values = special.into_iter().chain(more).chain(random);
        for v in values.filter(|v| v.abs() < 32768.0) {
            let want = crate::num::round_f32(v * 32768.0);
            assert_eq!((round_q15_as(v, true), round_q15(v)), (want, want), "{v:e}");
            let want = v.clamp(-2.0, 2.0).to_bits();
            assert_eq!(clamp2_as(v, true).to_bits(), want, "{v:e}");
        }
        for v in [1e10f32, -3e38, f32::MAX, f32::INFINITY, f32::NAN] {
            assert_eq!(finite_as(v, true), v.is_finite(), "{v:e}");
            if v.is_finite() {
                assert_eq!(clamp2_as(v, true).to_bits(), v.clamp(-2.0, 2.0).to_bits());
            }
        }
    }

    #[test]
    fn half_is_the_product_by_a_half() {
        let mut next = crate::testing::xorshift64(0x1234_5678_9abc_def1);
        let special = [
            0.0,
            -0.0,
            1e-45,
            -1e-38,
            2.4e-38,
            f32::MAX,
            f32::INFINITY,
            f32::NAN,
        ];
        let values = special
            .into_iter()
            .chain((0..100_000).map(|_| f32::from_bits(next() as u32)));
        for v in values {
            let (want, got) = (0.5 * v, half_as(v, true));
            assert!(
                want.to_bits() == got.to_bits() || want.is_nan() && got.is_nan(),
                "{v:e}"
            );
        }
    }

    #[test]
    fn sin_cos_are_accurate() {
        for i in -2000..2000 {
            let x = i as f32 * 0.0123;
            let (s, c) = sin_cos(x);
            let (es, ec) = (libm_sin(f64::from(x)), libm_cos(f64::from(x)));
            assert!((f64::from(s) - es).abs() < 2e-7, "sin {x}");
            assert!((f64::from(c) - ec).abs() < 2e-7, "cos {x}");
        }
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        assert!(sin_cos(f32::NAN).0.is_nan());
    }

    // Reference values from a plain series in f64 with many terms.
    fn libm_sin(x: f64) -> f64 {
        let x = x % (2.0 * core::f64::consts::PI);
        let (mut term, mut sum) = (x, x);
        for n in 1..40 {
            term *= -x * x / ((2 * n) as f64 * (2 * n + 1) as f64);
            sum += term;
        }
        sum
    }

    fn libm_cos(x: f64) -> f64 {
        let x = x % (2.0 * core::f64::consts::PI);
        let (mut term, mut sum) = (1.0, 1.0);
        for n in 1..40 {
            term *= -x * x / ((2 * n - 1) as f64 * (2 * n) as f64);
            sum += term;
        }
        sum
    }

    #[test]
    fn sqrt_is_accurate() {
        for v in [2.0f32, 1e-6, 3.5e7, 0.25, 1.0] {
            let (r, exact) = (f64::from(sqrt(v)), f64::from(v).sqrt());
            assert!(((r - exact) / exact).abs() < 1.2e-7, "{v}: {r} vs {exact}");
        }
        assert_eq!(sqrt(0.0), 0.0);
        assert!(sqrt(-1.0).is_nan());
    }

    #[test]
    fn perspective_maps_near_and_far_to_minus_one_and_one() {
        let p = Mat4::perspective(radians(60.0), 4.0 / 3.0, 0.1, 10.0);
        let n = p.transform_point(Vec3::new(0.0, 0.0, -0.1));
        let f = p.transform_point(Vec3::new(0.0, 0.0, -10.0));
        assert!((n[2] / n[3] + 1.0).abs() < 1e-6);
        assert!((f[2] / f[3] - 1.0).abs() < 1e-5);
        let e = Mat4::look_at(
            Vec3::new(0.0, 0.0, 2.5),
            Vec3::default(),
            Vec3::new(0.0, 1.0, 0.0),
        );
        assert_eq!(e.transform_point(Vec3::default()), [0.0, 0.0, -2.5, 1.0]);
        let r = Mat4::rotation_y(radians(90.0)).transform_dir(Vec3::new(0.0, 0.0, 1.0));
        assert!((r.x - 1.0).abs() < 1e-6 && r.z.abs() < 1e-6);
    }
}
