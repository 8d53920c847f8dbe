//! From model space to the screen: the frame's transforms, the fixed-point per-vertex
//! transform, and the projection to screen vertices.
// Indexing here is into fixed 4-element arrays by constants below 4: it cannot panic.
#![allow(clippy::indexing_slicing)]

use crate::fixed::{GUARD_BAND, MAX_DEPTH, SUBPIXEL};
use crate::math::{Mat4, Vec3};
use crate::num::{
    bits_beyond_31, mul_i64_i32, mul_wide, recip62, round_f32, shl64, shr64, INTEGER_PROJECTION,
};
use crate::raster::ScreenVertex;
use crate::{Error, MAX_DIMENSION};

/// The screen rectangle that normalised device coordinates map to.
///
/// NDC x = −1 is the left edge, y = +1 the top edge (row 0); window depth
/// `(z_ndc + 1) / 2` maps to 0..=65535. In banded rendering the viewport stays the
/// whole screen while the targets cover one band.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Viewport {
    x: i32,
    y: i32,
    width: u32,
    height: u32,
}

impl Viewport {
    /// A viewport of `width × height` pixels at (0, 0).
    pub fn new(width: u32, height: u32) -> Result<Viewport, Error> {
        Viewport::at(0, 0, width, height)
    }

    /// A viewport of `width × height` pixels with its top-left corner at (x, y).
    /// Errors: zero or over [`MAX_DIMENSION`] sizes, corners beyond ±8192.
    pub fn at(x: i32, y: i32, width: u32, height: u32) -> Result<Viewport, Error> {
        if width == 0 || height == 0 {
            return Err(Error::ZeroSize);
        }
        let lim = MAX_DIMENSION;
        if width > MAX_DIMENSION
            || height > MAX_DIMENSION
            || x.unsigned_abs() > lim
            || y.unsigned_abs() > lim
        {
            return Err(Error::TooLarge);
        }
        Ok(Viewport {
            x,
            y,
            width,
            height,
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Width / height.
    pub fn aspect(&self) -> f32 {
        self.width as f32 / self.height as f32
    }
}

/// Everything that places a mesh on the screen: model, view and projection matrices
/// and the viewport.
///
/// The model matrix should be a rotation, translation and uniform scale (lighting
/// turns the light into model space with its transpose); view and projection are any
/// `gluLookAt`/`gluPerspective`/`glOrtho`-style matrices.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transform {
    /// Model to world.
    pub model: Mat4,
    /// World to eye (the camera looks down −Z).
    pub view: Mat4,
    /// Eye to clip space.
    pub projection: Mat4,
    /// Normalised device coordinates to screen pixels.
    pub viewport: Viewport,
}

impl Transform {
    /// A camera at `eye` looking at `target` (+Y up) with a `fovy_deg` degree vertical
    /// field of view and clip planes at `near` and `far`, over `viewport`; the model
    /// matrix is the identity.
    ///
    /// Errors: [`Error::InvalidParameter`] unless `0 < near < far` and `0 < fovy < 180`,
    /// [`Error::NotFinite`] for NaN or infinite inputs.
    pub fn perspective(
        eye: Vec3,
        target: Vec3,
        fovy_deg: f32,
        near: f32,
        far: f32,
        viewport: Viewport,
    ) -> Result<Transform, Error> {
        if !(eye.is_finite()
            && target.is_finite()
            && fovy_deg.is_finite()
            && near.is_finite()
            && far.is_finite())
        {
            return Err(Error::NotFinite);
        }
        if !(near > 0.0 && far > near) {
            return Err(Error::InvalidParameter("need 0 < near < far"));
        }
        if !(fovy_deg > 0.0 && fovy_deg < 180.0) {
            return Err(Error::InvalidParameter("need 0 < fov < 180 degrees"));
        }
        let projection =
            Mat4::perspective(crate::math::radians(fovy_deg), viewport.aspect(), near, far);
        let view = Mat4::look_at(eye, target, Vec3::new(0.0, 1.0, 0.0));
        Ok(Transform {
            model: Mat4::IDENTITY,
            view,
            projection,
            viewport,
        })
    }

    /// The same transform with another model matrix.
    pub fn with_model(mut self, model: Mat4) -> Transform {
        self.model = model;
        self
    }

    /// Model to clip space.
    pub fn model_view_projection(&self) -> Mat4 {
        self.projection * self.view * self.model
    }
}

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

/// How far outside the screen (in screen widths) a vertex may project before the
/// triangle is clipped: |x|, |y| ≤ GUARD·w. With viewports of at most 8192 pixels the
/// projected coordinates stay within ±(GUARD + 1)·8192 pixels, inside the rasterizer's
/// range of ±2²⁰ pixels.
pub(crate) const GUARD: f32 = 64.0;

/// Outcode bits: which clip planes a vertex is outside of.
pub(crate) mod outcode {
    pub const NEAR: u8 = 1;
    pub const FAR: u8 = 2;
    pub const LEFT: u8 = 4;
    pub const RIGHT: u8 = 8;
    pub const BOTTOM: u8 = 16;
    pub const TOP: u8 = 32;
    pub const W: u8 = 64;
}

/// `o` with the guard-band bits of an outcode added: `x` and `y` against `±g`
/// (g = GUARD · w), in whichever number type the caller tests in (`f32`, or exact `i64`).
#[inline(always)]
fn guard_code<T: PartialOrd + core::ops::Neg<Output = T> + Copy>(
    mut o: u8,
    x: T,
    y: T,
    g: T,
) -> u8 {
    if x < -g {
        o |= outcode::LEFT;
    }
    if x > g {
        o |= outcode::RIGHT;
    }
    if y < -g {
        o |= outcode::BOTTOM;
    }
    if y > g {
        o |= outcode::TOP;
    }
    o
}

/// The outcode of a clip-space point.
#[inline]
pub(crate) fn outcode_of(c: &[f32; 4]) -> u8 {
    let [x, y, z, w] = *c;
    let g = GUARD * w;
    let mut o = 0;
    if z < -w {
        o |= outcode::NEAR;
    }
    if z > w {
        o |= outcode::FAR;
    }
    o = guard_code(o, x, y, g);
    if w < 1.0 || w.is_nan() {
        o |= outcode::W;
    }
    o
}

/// Fixed clip coordinates as `f32` (rounded once).
#[inline]
pub(crate) fn to_f32(c: &Clip4) -> [f32; 4] {
    c.to_f32()
}

/// Screen mapping of a viewport, precomputed.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ScreenMap {
    sx: f32,
    ox: f32,
    sy: f32,
    oy: f32,
    /// The same in integers (1/16 pixel), for the integer projection; half_w and
    /// half_h are at most 8 · 8192 = 2¹⁶ (so they fit `i32`).
    half_w: i64,
    half_h: i64,
    ox_i: i64,
    oy_i: i64,
}

/// 65535 · 65536 / 2: window depth (z_ndc + 1)/2 in 16.16 of 0..=65535.
const DEPTH_HALF: f32 = 65535.0 * 32768.0;

impl ScreenMap {
    pub(crate) fn new(vp: &Viewport) -> ScreenMap {
        let half_w = vp.width as f32 * (SUBPIXEL as f32 / 2.0);
        let half_h = vp.height as f32 * (SUBPIXEL as f32 / 2.0);
        let (hw, hh) = (i64::from(vp.width) * 8, i64::from(vp.height) * 8);
        ScreenMap {
            sx: half_w,
            ox: half_w + (vp.x * SUBPIXEL) as f32,
            sy: -half_h,
            oy: half_h + (vp.y * SUBPIXEL) as f32,
            half_w: hw,
            half_h: hh,
            ox_i: hw + i64::from(vp.x * SUBPIXEL),
            oy_i: hh + i64::from(vp.y * SUBPIXEL),
        }
    }

    /// Classify and project a fixed-point clip-space point: its outcode, and its screen
    /// vertex when the outcode is 0. The planes are tested in integers (64-bit where a
    /// sum could overflow); only points inside are divided by w.
    #[inline]
    pub(crate) fn project_fixed(&self, c: &Clip4) -> (u8, ScreenVertex) {
        // Near, far and w ≥ 1 exactly, in 64 bits; every plane is tested, also behind
        // the eye, so that clipping cuts at the near plane first, well away from w = 0.
        let (z, w) = c.zw();
        let mut code = if w < 1 { outcode::W } else { 0 };
        if z < -w {
            code |= outcode::NEAR;
        }
        if z > w {
            code |= outcode::FAR;
        }
        if INTEGER_PROJECTION {
            if let Some(v) = self.project_integer(c, z, w, code) {
                return v;
            }
        }
        self.project_fixed_float(c, code)
    }

    /// The rest of [`project_fixed`](ScreenMap::project_fixed) in `f32`.
    #[inline]
    pub(crate) fn project_fixed_float(&self, c: &Clip4, mut code: u8) -> (u8, ScreenVertex) {
        // The guard band in f32: it has room for rounding.
        let [x, y, zf, wf] = c.to_f32();
        let g = GUARD * wf;
        // Both within ±g (the usual case) adds no bit: two compares instead of four.
        if !(x.abs() <= g && y.abs() <= g) {
            code = guard_code(code, x, y, g);
        }
        if code != 0 {
            return (code, ScreenVertex::ORIGIN);
        }
        // Inside: |x|, |y| ≤ 64·w (to f32 rounding) and |z| ≤ w, so x and y land
        // within ±65·8192·8 < 2²³ (no clamp needed) and only z needs clamping.
        let inv = 1.0 / wf;
        let sx = x * inv * self.sx + self.ox;
        let sy = y * inv * self.sy + self.oy;
        let sz = (zf * inv + 1.0) * DEPTH_HALF + 0.5;
        (
            0,
            ScreenVertex::from_raw(round_f32(sx), round_f32(sy), (sz as u32).min(MAX_DEPTH)),
        )
    }

    /// The rest of [`project_fixed`](ScreenMap::project_fixed) in integers: the guard
    /// band exactly, then three 64-by-32-bit divisions by w normalised to 31 bits
    /// (relative precision 2⁻³⁰, well below a 1/16 pixel or a 1/65536 depth unit).
    /// `None` when x and y are not in a scale it handles (then the `f32` path runs).
    pub(crate) fn project_integer(
        &self,
        c: &Clip4,
        z: i64,
        w: i64,
        mut code: u8,
    ) -> Option<(u8, ScreenVertex)> {
        let (x, y) = c.xy_wide()?;
        if code & outcode::W == 0 {
            let g = w << 6; // w < 2⁴⁵
            code = guard_code(code, x, y, g);
        }
        if code != 0 {
            return Some((code, ScreenVertex::ORIGIN));
        }
        // Inside: 1 ≤ w < 2⁴⁵, 0 ≤ z + w ≤ 2w, |x|, |y| ≤ 64w. Shift everything so that
        // w fits 31 bits; the ratios keep 30 bits or more.
        let sh = bits_beyond_31(w);
        let wn = shr64(w, sh); // 1 ..< 2³¹ (≥ 2³⁰ unless w itself is small)
                               // |xn|, |yn| ≤ 2³⁷; 0 ≤ un ≤ 2³².
        let (xn, yn, un) = (shr64(x, sh), shr64(y, sh), shr64(z + w, sh)); // sh ≤ 14
                                                                           // One division: r = ⌊2⁶²/wn⌋ (≤ 2³² when wn ≥ 2³⁰; below that the exact
                                                                           // divisions further down run instead). Each quotient n/wn is then n·r/2⁶², formed
                                                                           // from 32-bit halves of n (no 128-bit arithmetic), exact to within one unit of the
                                                                           // result's last place.
        let r = if wn >= 1 << 30 { recip62(wn as u32) } else { 0 };
        let times_r = |n: u64| -> u64 {
            // (n · r) >> 30, for n < 2⁶⁴ and n·r/2³⁰ < 2⁶⁴; with 32×32-bit products
            // unless r = 2³² (wn = 2³⁰ exactly).
            let (hi, lo) = (n >> 32, n & 0xffff_ffff);
            if r >> 32 == 0 {
                let (hi, lo, r) = (hi as u32, lo as u32, r as u32);
                mul_wide(hi, r)
                    .wrapping_shl(2)
                    .wrapping_add(mul_wide(lo, r) >> 30)
            } else {
                hi.wrapping_mul(r)
                    .wrapping_shl(2)
                    .wrapping_add(lo.wrapping_mul(r) >> 30)
            }
        };
        // A quotient rounded to nearest: (n/wn) in units of 2⁻³², then halved.
        let ratio = |n: i64| -> i64 {
            let q = times_r(n.unsigned_abs()) as i64; // n/wn · 2³²
            let q = (q + (1 << 31)) >> 32;
            if n < 0 {
                -q
            } else {
                q
            }
        };
        let sx = if wn >= 1 << 30 {
            self.ox_i + ratio(mul_i64_i32(xn, self.half_w as i32))
        } else {
            self.ox_i + (2 * xn * self.half_w + wn).div_euclid(2 * wn)
        };
        let sy = if wn >= 1 << 30 {
            self.oy_i - ratio(mul_i64_i32(yn, self.half_h as i32))
        } else {
            self.oy_i - (2 * yn * self.half_h + wn).div_euclid(2 * wn)
        };
        // Depth: (z/w + 1)/2 · 65535 · 2¹⁶ = (un/wn) · 65535 · 2¹⁵, through the ratio in
        // Q30 (≤ 2³¹; times 65535 < 2⁴⁷).
        let q30 = if wn >= 1 << 30 {
            ((times_r(un as u64) >> 1) + 1) as i64 >> 1 // un/wn · 2³⁰, rounded (un ≥ 0)
        } else {
            (2 * (un << 30) + wn).div_euclid(2 * wn)
        };
        let sz = ((mul_i64_i32(q30, 65535) + (1 << 14)) >> 15).clamp(0, i64::from(MAX_DEPTH));
        Some((0, ScreenVertex::from_raw(sx as i32, sy as i32, sz as u32)))
    }

    /// Project a clip-space point inside the guard band and depth range (outcode 0).
    #[inline]
    pub(crate) fn project(&self, c: &[f32; 4]) -> Option<ScreenVertex> {
        let inv = 1.0 / c[3];
        let lim = GUARD_BAND as f32;
        let x = (c[0] * inv * self.sx + self.ox).clamp(-lim, lim);
        let y = (c[1] * inv * self.sy + self.oy).clamp(-lim, lim);
        let z = ((c[2] * inv + 1.0) * DEPTH_HALF).clamp(0.0, MAX_DEPTH as f32);
        if !(x.is_finite() && y.is_finite() && z.is_finite()) {
            return None;
        }
        ScreenVertex::new(round_f32(x), round_f32(y), (z + 0.5) as u32).ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recip62_is_the_exact_quotient() {
        let check = |d: u32| assert_eq!(recip62(d), (1u64 << 62) / u64::from(d), "{d}");
        for d in [
            1 << 30,
            (1 << 30) + 1,
            (1 << 30) + 2,
            0x5555_5555,
            (1 << 31) - 2,
            (1 << 31) - 1,
        ] {
            check(d);
        }
        // Both ends of every interval of the first guess.
        for i in 0..256u32 {
            let d = (1 << 30) + (i << 22);
            for d in [
                d.wrapping_sub(1),
                d,
                d + 1,
                d + (1 << 21),
                d + (1 << 22) - 1,
            ] {
                if d > 0 && d < 1 << 31 {
                    check(d);
                }
            }
        }
        let mut rnd = crate::testing::xorshift32(0x2545_f491);
        for _ in 0..100_000 {
            check((1 << 30) | (rnd() >> 2));
        }
    }
    use crate::math::radians;

    #[test]
    fn the_fixed_transform_matches_the_float_one() {
        let vp = Viewport::new(320, 240).unwrap();
        let xf = Transform::perspective(
            Vec3::new(0.0, 0.0, 2.5),
            Vec3::default(),
            60.0,
            0.1,
            10.0,
            vp,
        )
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
    fn integer_and_float_projections_agree() {
        let vp = Viewport::new(320, 240).unwrap();
        let map = ScreenMap::new(&vp);
        for (yaw, dist) in [(0.0, 2.5), (30.0, 1.6), (200.0, 0.5), (77.0, 9.0)] {
            let xf = Transform::perspective(
                Vec3::new(0.0, 0.0, dist),
                Vec3::default(),
                60.0,
                0.1,
                10.0,
                vp,
            )
            .unwrap()
            .with_model(Mat4::rotation_y(radians(yaw)));
            let fx = FixedTransform::new(&xf.model_view_projection(), 1.0 / 32767.0).unwrap();
            let mut seen = 0;
            for i in 0..2000i32 {
                let p = [
                    ((i * 7919) % 65535 - 32767) as i16,
                    ((i * 104_729) % 65535 - 32767) as i16,
                    ((i * 31) % 65535 - 32767) as i16,
                ];
                let c = fx.apply(&p);
                let (z, w) = c.zw();
                let base = if w < 1 { outcode::W } else { 0 }
                    | if z < -w { outcode::NEAR } else { 0 }
                    | if z > w { outcode::FAR } else { 0 };
                let (code_f, vf) = map.project_fixed_float(&c, base);
                let (code_i, vi) = map.project_integer(&c, z, w, base).unwrap();
                // Away from the guard band's edge the two agree on the outcode.
                if code_f != code_i {
                    continue;
                }
                if code_i == 0 {
                    seen += 1;
                    assert!(
                        (vf.x() - vi.x()).abs() <= 1 && (vf.y() - vi.y()).abs() <= 1,
                        "{p:?}: {vf:?} vs {vi:?}"
                    );
                    // The f32 path rounds depth to 24 bits (512 units of 16.16 near the far end).
                    assert!(
                        (i64::from(vf.z()) - i64::from(vi.z())).abs() <= 1 << 11,
                        "{p:?}: {vf:?} vs {vi:?}"
                    );
                }
            }
            assert!(seen > 100);
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

    #[test]
    fn outcodes() {
        assert_eq!(outcode_of(&[0.0, 0.0, 0.0, 10.0]), 0);
        assert_eq!(outcode_of(&[0.0, 0.0, -11.0, 10.0]), outcode::NEAR);
        assert_eq!(outcode_of(&[0.0, 0.0, 11.0, 10.0]), outcode::FAR);
        assert_eq!(outcode_of(&[641.0, 0.0, 0.0, 10.0]), outcode::RIGHT);
        assert_eq!(outcode_of(&[0.0, 0.0, 0.0, -1.0]) & outcode::W, outcode::W);
    }
}
