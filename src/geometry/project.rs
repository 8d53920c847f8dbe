//! Projection: clip-space vertices classified against the view volume (outcodes) and
//! mapped to screen vertices, in `f32` or, on cores without an FPU, in integers.
// Indexing here is into fixed 4-element arrays by constants below 4: it cannot panic.
#![allow(clippy::indexing_slicing)]

use super::transform::{Clip4, FixedTransform};
use crate::camera::Viewport;
use crate::fixed::{GUARD_BAND, MAX_DEPTH, SUBPIXEL};
use crate::num::kernel::{
    place_run, place_run_v6m, recip62_low, CachedVertex, PlaceBlock, PlaceV6m, PLACE_KERNEL,
    PLACE_V6M_KERNEL,
};
use crate::num::{
    bits_beyond_31, div_floor, mul_i64_i32, mul_wide, mul_wide_narrow, round_f32,
    scaled_ratio_parts, shr64, ARMV6M, INTEGER_PROJECTION,
};
use crate::raster::ScreenVertex;

/// How far outside the screen (in screen widths) a vertex may project before the
/// triangle is clipped: |x|, |y| ≤ GUARD·w. With viewports of at most 8192 pixels the
/// projected coordinates stay within ±(GUARD + 1)·8192 pixels, inside the rasterizer's
/// range of ±2²⁰ pixels.
pub(crate) const GUARD: f32 = 64.0;

/// A first hint for [`ScreenMap::project_fast`] at w's bits beyond 31: w between 2⁴²
/// and 2⁴³, where [`FixedTransform`](super::transform::FixedTransform) puts the w of a
/// model a few times its size from the camera. (The cache passes each vertex the
/// previous one's.)
pub(crate) const W_SHIFT_HINT: u32 = 12;

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

/// `⌊v·2⁻ᵏ⌋` as its sign (0 or −1) and magnitude, when that is below 2³¹: a right
/// shift by `k ≥ 0`, or a left shift by `−k ≤ 31` that loses no bit.
#[inline(always)]
fn normalised(v: i32, k: i32) -> Option<(i32, u32)> {
    let s = v >> 31;
    let a = if k >= 0 {
        let a = ((v >> k) ^ s).wrapping_sub(s) as u32;
        if a >> 31 != 0 {
            return None; // i32::MIN, for k = 0
        }
        a
    } else {
        let (a, m) = (v.unsigned_abs(), k.unsigned_abs());
        if a >> (31 - m) != 0 {
            return None;
        }
        a << m
    };
    Some((s, a))
}

/// `n·h/d` rounded to nearest (halves away from zero) for `n` given as its sign (0 or
/// −1) and magnitude (below 2³¹), given `r = ⌊2⁶²/d⌋` (d > 2³⁰) and `h ≤ 2¹⁶`, as
/// [`scaled_ratio_parts`] (`None` where it cannot tell); the sign applied without a
/// branch.
#[inline(always)]
fn signed_ratio((s, a): (i32, u32), r: u32, h: u32) -> Option<i32> {
    let q = scaled_ratio_parts(a, r, h)? as i32; // below 2¹⁸
    Some((q ^ s) - s)
}

/// ⌊(a·b + 2³¹)/2³²⌋, the high word of `a·b` rounded, in four 16 × 16-bit products
/// and 32-bit sums (ARMv6-M has no long multiply). With 16-bit halves, `a·b` is
/// `h·2³² + (m₁ + m₂)·2¹⁶ + l` for `h = a₁b₁`, `m₁ = a₁b₀`, `m₂ = a₀b₁`, `l = a₀b₀`,
/// so the result is `h + ⌊m₁/2¹⁶⌋ + ⌊m₂/2¹⁶⌋ + ⌊(m₁ mod 2¹⁶ + m₂ mod 2¹⁶ + ⌊l/2¹⁶⌋ +
/// 2¹⁵)/2¹⁶⌋` (that last sum below 2¹⁸). A test checks it against the 64-bit product.
#[inline(always)]
fn rounded_high(a: u32, b: u32) -> u32 {
    let (a1, a0, b1, b0) = (a >> 16, a & 0xffff, b >> 16, b & 0xffff);
    let (m1, m2) = (a1 * b0, a0 * b1);
    let low = (m1 & 0xffff) + (m2 & 0xffff) + ((a0 * b0) >> 16) + (1 << 15);
    // The sum is the rounded high word of a·b, below 2³²: no partial sum wraps.
    a1 * b1 + (m1 >> 16) + (m2 >> 16) + (low >> 16)
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
    #[inline(never)] // one copy: the vertex cache inlines only the fast path
    pub(crate) fn project_fixed(&self, c: &Clip4) -> (u8, ScreenVertex) {
        if INTEGER_PROJECTION && ARMV6M {
            let mut hint = W_SHIFT_HINT;
            if let Some(v) = self.project_fast(c, &mut hint) {
                return (0, v);
            }
        }
        self.project_exact(c)
    }

    /// [`project_fixed`](ScreenMap::project_fixed) without its fast path (which gives
    /// the same vertex where it gives one).
    #[inline(never)]
    pub(crate) fn project_exact(&self, c: &Clip4) -> (u8, ScreenVertex) {
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
    pub(crate) fn project_fixed_float(&self, c: &Clip4, code: u8) -> (u8, ScreenVertex) {
        self.project_rest(c.to_f32(), code)
    }

    /// Classify and project a clip-space point in `f32` (cores with an FPU): its
    /// outcode, and its screen vertex when the outcode is 0. The planes are those of
    /// [`project_fixed`](ScreenMap::project_fixed), tested in `f32` (they can differ
    /// from the exact test only for a point within rounding of a plane, where either
    /// answer clips correctly); a NaN `w` is outside.
    #[inline(always)]
    pub(crate) fn project_float(&self, c: [f32; 4]) -> (u8, ScreenVertex) {
        match self.project_float_inside(c) {
            Some(v) => (0, v),
            None => self.classify_float(c),
        }
    }

    /// [`project_float`](ScreenMap::project_float)'s screen vertex for a point inside
    /// every plane (its outcode 0), `None` for any other: five tests that branch (NaN
    /// fails each; given w ≥ 1, |z| ≤ w is neither near nor far).
    #[inline(always)]
    pub(crate) fn project_float_inside(&self, c: [f32; 4]) -> Option<ScreenVertex> {
        let [x, y, z, w] = c;
        let g = GUARD * w;
        if w >= 1.0 && z.abs() <= w && x.abs() <= g && y.abs() <= g {
            return Some(self.project_inside_float(c));
        }
        None
    }

    /// [`project_float`](ScreenMap::project_float) for any point: every plane tested
    /// and its bit set.
    #[inline]
    pub(crate) fn classify_float(&self, c: [f32; 4]) -> (u8, ScreenVertex) {
        let [_, _, z, w] = c;
        let mut code = if w >= 1.0 { 0 } else { outcode::W };
        if z < -w {
            code |= outcode::NEAR;
        }
        if z > w {
            code |= outcode::FAR;
        }
        self.project_rest(c, code)
    }

    /// The guard band and the projection of an `f32` clip-space point whose other
    /// planes gave `code`.
    #[inline(always)]
    fn project_rest(&self, [x, y, zf, wf]: [f32; 4], mut code: u8) -> (u8, ScreenVertex) {
        // The guard band in f32: it has room for rounding.
        let g = GUARD * wf;
        // Both within ±g (the usual case) adds no bit: two compares instead of four.
        if !(x.abs() <= g && y.abs() <= g) {
            code = guard_code(code, x, y, g);
            // NaN (from an overflowing transform) is nowhere: outside.
            if x.is_nan() || y.is_nan() {
                code |= outcode::W;
            }
        }
        if code != 0 {
            return (code, ScreenVertex::ORIGIN);
        }
        (0, self.project_inside_float([x, y, zf, wf]))
    }

    /// The screen vertex of an `f32` clip-space point inside every plane.
    #[inline(always)]
    fn project_inside_float(&self, [x, y, zf, wf]: [f32; 4]) -> ScreenVertex {
        // Inside: |x|, |y| ≤ 64·w (to f32 rounding) and |z| ≤ w, so x and y land
        // within ±65·8192·8 < 2²³ (no clamp needed) and only z needs clamping.
        let inv = 1.0 / wf;
        let sx = x * inv * self.sx + self.ox;
        let sy = y * inv * self.sy + self.oy;
        let sz = (zf * inv + 1.0) * DEPTH_HALF + 0.5;
        ScreenVertex::from_raw(round_f32(sx), round_f32(sy), (sz as u32).min(MAX_DEPTH))
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
        let sh = bits_beyond_31(w); // ≤ 14
                                    // 1 ≤ wn < 2³¹ (≥ 2³⁰ unless w itself is small); |xn|, |yn| ≤ 2³⁷; 0 ≤ un ≤ 2³².
        let wn = shr64(w, sh);
        let (xn, yn, un) = (shr64(x, sh), shr64(y, sh), shr64(z + w, sh));
        // One division: r = ⌊2⁶²/wn⌋ (≤ 2³² when wn ≥ 2³⁰; below that the exact
        // divisions further down run instead). Each quotient n/wn is then n·r/2⁶²,
        // formed from 32-bit halves of n (no 128-bit arithmetic), exact to within one
        // unit of the result's last place.
        let r = if wn > 1 << 30 {
            recip62_low(wn as u32)
        } else {
            0
        };
        let times_r = |n: u64| -> u64 {
            // (n · r) >> 30, for n < 2⁶⁴ and n·r/2³⁰ < 2⁶⁴, from 32×32-bit products;
            // a shift when r = 2³² (wn = 2³⁰ exactly).
            if wn == 1 << 30 {
                return n.wrapping_shl(2);
            }
            let (hi, lo) = ((n >> 32) as u32, n as u32);
            mul_wide_narrow(hi, r)
                .wrapping_shl(2)
                .wrapping_add(mul_wide(lo, r) >> 30)
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
            self.ox_i + div_floor(2 * xn * self.half_w + wn, 2 * wn)
        };
        let sy = if wn >= 1 << 30 {
            self.oy_i - ratio(mul_i64_i32(yn, self.half_h as i32))
        } else {
            self.oy_i - div_floor(2 * yn * self.half_h + wn, 2 * wn)
        };
        // Depth: (z/w + 1)/2 · 65535 · 2¹⁶ = (un/wn) · 65535 · 2¹⁵, through the ratio in
        // Q30 (≤ 2³¹; times 65535 < 2⁴⁷).
        let q30 = if wn >= 1 << 30 {
            ((times_r(un as u64) >> 1) + 1) as i64 >> 1 // un/wn · 2³⁰, rounded (un ≥ 0)
        } else {
            div_floor(2 * (un << 30) + wn, 2 * wn)
        };
        let sz = ((mul_i64_i32(q30, 65535) + (1 << 14)) >> 15).clamp(0, i64::from(MAX_DEPTH));
        Some((0, ScreenVertex::from_raw(sx as i32, sy as i32, sz as u32)))
    }

    /// [`project_integer`](ScreenMap::project_integer)'s screen vertex for the usual
    /// point, in 32-bit arithmetic (for ARMv6-M, whose 64-bit products and shifts are
    /// long): the same vertex for a point it proves inside the w, near and far planes
    /// with w normalised above 2³⁰ and |x|, |y| normalised below 2³¹ (which puts it
    /// inside the guard band: `project_integer` gives outcode 0), or `None` where it
    /// cannot tell (then the exact path runs). The planes are tested on z and w in units
    /// of 2¹⁴, with a unit of room, and z and w normalised from their partial sums
    /// ([`Clip4::zw_parts`]) without forming them in 64 bits. `sh_hint` is a guess in
    /// 1..=14 at w's bits beyond 31 ([`W_SHIFT_HINT`], or the previous point's), checked
    /// and set to this point's.
    #[inline(always)]
    pub(crate) fn project_fast(&self, c: &Clip4, sh_hint: &mut u32) -> Option<ScreenVertex> {
        let ([x, y], e) = c.xy_scaled()?; // x·2^e, y·2^e in the z/w scale; e ≤ 20
        let ([zh, wh], [zl, wl]) = c.zw_parts();
        // zt = ⌊z/2¹⁴⌋, wt = ⌊w/2¹⁴⌋ (|z|, |w| < 2⁴⁵: both fit i32), and z's and w's low
        // 14 bits: z = zt·2¹⁴ + zl.
        let (zt, wt) = (zh.wrapping_add(zl >> 14), wh.wrapping_add(wl >> 14));
        let (zl, wl) = ((zl & 0x3fff) as u32, (wl & 0x3fff) as u32);
        // w ≥ wt·2¹⁴ ≥ 2³¹ (so w ≥ 1, and w has sh ≥ 1 bits beyond 31), and
        // (1 − wt)·2¹⁴ ≤ z < (wt − 1)·2¹⁴ puts z strictly between −w and w.
        if wt < 1 << 17 || zt <= -wt || zt >= wt - 1 {
            return None;
        }
        // sh = (bits of w) − 31 = (bits of wt) − 17, in 1..=14: usually the hint's.
        let mut sh = *sh_hint;
        if wt >> (16 + sh) != 1 {
            let mut t = (wt >> 17) as u32;
            sh = 1;
            for b in [8, 4, 2, 1] {
                if t >> b != 0 {
                    t >>= b;
                    sh += b;
                }
            }
        }
        // wn = ⌊w/2^sh⌋ in [2³⁰, 2³¹) and un = ⌊(z + w)/2^sh⌋ ≤ 2·wn + 1 < 2³², each a
        // top part shifted up by 14 − sh plus the low bits shifted down by sh (exact:
        // the top part is a multiple of 2^sh). 1 ≤ zt + wt < 2³² as u32.
        *sh_hint = sh;
        let up = 14 - sh;
        let wn = ((wt as u32) << up) + (wl >> sh);
        if wn == 1 << 30 {
            return None;
        }
        let un = ((zt as u32).wrapping_add(wt as u32) << up) + ((zl + wl) >> sh);
        // xn = ⌊x·2^e / 2^sh⌋ (likewise yn) as its sign and magnitude, below 2³¹
        // (e ≤ 20 and sh ≥ 1: k ≥ −19).
        let k = sh as i32 - e as i32;
        let (x, y) = (normalised(x, k)?, normalised(y, k)?);
        // |xn|, |yn| < 2³¹ ≤ 2·wn: |x|, |y| < 2.0000001·w, well inside ±64·w.
        let r = recip62_low(wn);
        // project_integer's i64 sums, truncated to i32 as it truncates them.
        let sx = (self.ox_i as i32).wrapping_add(signed_ratio(x, r, self.half_w as u32)?);
        let sy = (self.oy_i as i32).wrapping_sub(signed_ratio(y, r, self.half_h as u32)?);
        // Depth: q30 = ⌊(un·r + 2³¹)/2³²⌋ ≤ 2³¹ + 1 (un/wn ≤ 2 + 1/wn), and
        // ⌊(q30·65535 + 2¹⁴)/2¹⁵⌋ = 2·q30 − ⌈(q30 − 2¹⁴)/2¹⁵⌉ = 2·q30 − d with
        // d = ⌊(q30 + 2¹⁴ − 1)/2¹⁵⌋ ≤ q30: below 2³² − 2¹⁵.
        let q30 = rounded_high(un, r);
        let d = (q30 + (1 << 14) - 1) >> 15;
        let sz = (q30 + (q30 - d)).min(MAX_DEPTH);
        Some(ScreenVertex::from_raw(sx, sy, sz))
    }

    /// The vertex kernel's operands ([`PlaceBlock`]) for `fixed` and this mapping:
    /// `None` unless x and y's scale is 2^e with 0 ≤ e ≤ 20 and the kernel's screen
    /// range (±1024 pixels) lies inside the guard band with room (a point placed
    /// within it is inside the band however the steps round).
    pub(crate) fn place_block(&self, fixed: &FixedTransform) -> Option<PlaceBlock> {
        let (rows, s) = fixed.words();
        let bits = s.to_bits();
        let e = (bits >> 23) as i32 - 127;
        if bits & 0x807f_ffff != 0 || !(0..=20).contains(&e) {
            return None;
        }
        // x·s·inv·sx = (x·inv')·(sx·s·2⁻¹⁴) with inv' = 2¹⁴·inv: powers of two, exact.
        let f = f32::from_bits(((e - 14 + 127) as u32) << 23);
        let room = |scale: f32, offset: f32| (16384.0 + offset.abs()) <= 63.0 * scale.abs();
        if !(room(self.sx, self.ox) && room(self.sy, self.oy)) {
            return None;
        }
        Some(PlaceBlock::new(
            rows,
            [self.sx * f, self.ox, self.sy * f, self.oy],
        ))
    }

    /// The ARMv6-M vertex kernel's operands ([`PlaceV6m`]) for a transform's rows
    /// (`FixedTransform::with_rows_v6m`) and scale and this mapping: `None` unless the scale
    /// is 2^e with 0 ≤ e ≤ 20 (where [`project_fast`](ScreenMap::project_fast) places
    /// no vertex either), the viewport is at most 4096 pixels on a side and its centre
    /// within ±4096 pixels (the kernel's sums in 32 bits).
    pub(crate) fn place_block_v6m<'a>(
        &self,
        rows: &'a [[i32; 4]; 6],
        s: f32,
    ) -> Option<PlaceV6m<'a>> {
        let bits = s.to_bits();
        let e = (bits >> 23) as i32 - 127;
        // half_w, half_h and the origins fit 32 bits (see ScreenMap).
        let half = [self.half_w as u32, self.half_h as u32];
        let org = [self.ox_i as i32, self.oy_i as i32];
        let fits =
            half.iter().all(|&h| h <= 1 << 15) && org.iter().all(|o| o.unsigned_abs() < 1 << 16);
        if bits & 0x807f_ffff != 0 || !(0..=20).contains(&e) || !fits {
            return None;
        }
        Some(PlaceV6m::new(rows, e as u32, half, org))
    }

    /// Fills `cache` with the entries of `positions` (as many as the shorter holds) by
    /// the vertex kernel, `entry` giving each one it does not place; `false` (nothing
    /// written) where no kernel runs: on targets other than ARMv7E-M with an FPU
    /// ([`place_block`](ScreenMap::place_block)) and ARMv6-M (always, by
    /// [`place_block_v6m`](ScreenMap::place_block_v6m)), or without the former's block. Out of line: its operands stay off the stack of the renderer's set-up.
    #[inline(never)]
    pub(crate) fn place_all(
        &self,
        fixed: &FixedTransform,
        positions: &[[i16; 3]],
        cache: &mut [CachedVertex],
        entry: impl FnMut(&[i16; 3]) -> CachedVertex,
    ) -> bool {
        if PLACE_KERNEL {
            let Some(mut block) = self.place_block(fixed) else {
                return false;
            };
            fill_runs(positions, cache, entry, |p, c| place_run(&mut block, p, c));
            true
        } else if PLACE_V6M_KERNEL {
            // Without a block (a scale project_fast refuses too) every entry by `entry`.
            fixed.with_rows_v6m(|rows| match self.place_block_v6m(rows, fixed.scale()) {
                Some(mut b) => {
                    fill_runs(positions, cache, entry, |p, c| place_run_v6m(&mut b, p, c))
                }
                None => fill_runs(positions, cache, entry, |_, _| 0),
            });
            true
        } else {
            false
        }
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

/// Fills `cache` with the entries of `positions` (as many as the shorter holds): runs
/// by `run` (which writes entries from the first on and returns how many), each
/// position it stops at by `entry`.
#[inline(always)]
fn fill_runs(
    positions: &[[i16; 3]],
    cache: &mut [CachedVertex],
    mut entry: impl FnMut(&[i16; 3]) -> CachedVertex,
    mut run: impl FnMut(&[[i16; 3]], &mut [CachedVertex]) -> usize,
) {
    let mut at = 0;
    while let (Some(p), Some(c)) = (positions.get(at..), cache.get_mut(at..)) {
        at += run(p, c);
        let (Some(p), Some(e)) = (positions.get(at), cache.get_mut(at)) else {
            break;
        };
        *e = entry(p);
        at += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::{Camera, Viewport};
    use crate::math::{radians, Mat4, Vec3};

    /// The planes tested in `f32` ([`ScreenMap::project_float`], the FPU path) give
    /// the exact integer outcode and the same screen vertex, except for points within
    /// rounding of the near or far plane; a NaN `w` or `x` is outside.
    #[test]
    fn float_planes_match_the_exact_ones() {
        let vp = Viewport::new(320, 240).unwrap();
        let map = ScreenMap::new(&vp);
        let mut next = crate::testing::xorshift32(0x1234_5678);
        let (mut inside, mut outside) = (0, 0);
        for (yaw, dist) in [(0.0, 2.5), (30.0, 1.6), (200.0, 0.5), (77.0, 9.0)] {
            let xf = Camera::look_at(Vec3::new(0.0, 0.0, dist), Vec3::default(), Vec3::Y)
                .unwrap()
                .perspective(radians(60.0), 0.1, 10.0, vp)
                .unwrap()
                .with_model(Mat4::rotation_y(radians(yaw)));
            let fx = FixedTransform::new(&xf.model_view_projection(), 1.0 / 32767.0).unwrap();
            for _ in 0..5000 {
                let p = [next() as i16, next() as i16, next() as i16];
                let c = fx.apply(&p);
                let (z, w) = c.zw();
                let exact = map.project_fixed(&c);
                let float = map.project_float(c.to_f32());
                // Within a part in 2²⁰ of the near or far plane either answer is right.
                let margin = w.abs() >> 20;
                if (z + w).abs() <= margin || (z - w).abs() <= margin {
                    continue;
                }
                let want = map.project_fixed_float(
                    &c,
                    exact.0 & !(outcode::LEFT | outcode::RIGHT | outcode::BOTTOM | outcode::TOP),
                );
                assert_eq!(float, want, "{p:?}");
                if float.0 == 0 {
                    inside += 1;
                } else {
                    outside += 1;
                }
            }
        }
        assert!(
            inside > 1000 && outside > 1000,
            "{inside} inside, {outside} outside"
        );
        let nan = map.project_float([f32::NAN, 0.0, 0.0, 2.0]);
        assert_ne!(nan.0, 0);
        assert_ne!(map.project_float([0.0, 0.0, 0.0, f32::NAN]).0, 0);
    }

    /// [`ScreenMap::project_float`]'s fast test for the usual vertex changes nothing:
    /// it gives what classifying every plane gives, for points inside, next to each
    /// plane, outside, infinite and NaN.
    #[test]
    fn float_fast_path_is_the_classification() {
        let map = ScreenMap::new(&Viewport::at(-7, 3, 320, 240).unwrap());
        let mut next = crate::testing::xorshift32(0x0bad_cafe);
        let special = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        let mut fast = 0;
        for i in 0..200_000 {
            let w = match i % 8 {
                0 => special[(next() % 7) as usize],
                1 => 1.0 - f32::EPSILON * (next() % 4) as f32,
                _ => (next() % 100_000) as f32 / 64.0,
            };
            let ratio = |r: u32| match r % 16 {
                0 => special[(r / 16 % 7) as usize],
                1 => 1.0,
                2 => -1.0,
                _ => (r % 300_000) as f32 / 65_536.0 - 2.3,
            };
            let z = w * ratio(next());
            let (x, y) = (
                w * 64.0 * ratio(next()) / 2.0,
                w * 64.0 * ratio(next()) / 2.0,
            );
            let z = if i % 5 == 0 { w.copysign(z) } else { z };
            let c = [x, y, z, w];
            let got = map.project_float(c);
            assert_eq!(got, map.classify_float(c), "{c:?}");
            fast += usize::from(map.project_float_inside(c).is_some());
        }
        assert!(fast > 10_000, "{fast}");
    }

    #[test]
    fn integer_and_float_projections_agree() {
        let vp = Viewport::new(320, 240).unwrap();
        let map = ScreenMap::new(&vp);
        for (yaw, dist) in [(0.0, 2.5), (30.0, 1.6), (200.0, 0.5), (77.0, 9.0)] {
            let xf = Camera::look_at(Vec3::new(0.0, 0.0, dist), Vec3::default(), Vec3::Y)
                .unwrap()
                .perspective(radians(60.0), 0.1, 10.0, vp)
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

    /// [`ScreenMap::project_fast`] (ARMv6-M's 32-bit form) gives the exact outcode 0
    /// and `project_integer`'s vertex wherever it gives one, and gives one for nearly
    /// every point it is meant for: w of every magnitude and sign, at the powers of two
    /// where its normalisation changes, z across [−w, w], at ±w and beyond, x and y out
    /// to ±2.5·w and beyond, every scale exponent, viewports from 1 to 8192 pixels at
    /// corners up to ±8192.
    #[test]
    fn fast_projection_is_the_exact_one() {
        let cases = crate::num::tests::fast_cases() / 4;
        let mut rnd = crate::testing::xorshift64(0x2545_f491_4f6c_dd1d);
        let maps = [
            ScreenMap::new(&Viewport::new(320, 240).unwrap()),
            ScreenMap::new(&Viewport::new(1, 1).unwrap()),
            ScreenMap::new(&Viewport::new(8192, 8192).unwrap()),
            ScreenMap::new(&Viewport::at(-8192, 8000, 4096, 192).unwrap()),
        ];
        let (mut fast, mut meant_for) = (0u64, 0u64);
        for i in 0..cases {
            let (v, u) = (rnd(), rnd());
            let delta = i64::from((u >> 40) as i16); // within ±2¹⁵
                                                     // w below 2⁴⁵, now and then next to 2³¹⁺ᵏ (w normalised to 2³⁰) or negative;
                                                     // w = hi·2¹⁴ + lo, lo a partial sum of either sign.
            let w = ((v & ((1 << 45) - 1)) >> ((v >> 58) % 20)) as i64;
            let w = match i % 16 {
                1 => (1 << (31 + (v >> 50) % 14)) + delta,
                2 => -w,
                _ => w,
            };
            let lo = (u as i32) >> (u >> 59);
            let hi = ((w - i64::from(lo)) >> 14) as i32;
            let w = (i64::from(hi) << 14) + i64::from(lo);
            // z in [−w, w] mostly, else next to ±w or beyond; its parts likewise.
            let z = ((i128::from((u >> 8) & 0xffff_ffff) * 2 * i128::from(w)) >> 32) as i64 - w;
            let z = match (i / 16) % 8 {
                1 => w + delta,
                2 => -w + delta,
                3 => z + (z >> 2),
                _ => z,
            };
            let zlo = (v as i32) >> 3;
            let Ok(zhi) = i32::try_from((z - i64::from(zlo)) >> 14) else {
                continue;
            };
            let z = (i64::from(zhi) << 14) + i64::from(zlo);
            if z.unsigned_abs() >= 1 << 45 {
                continue;
            }
            // x, y: a ratio to w up to ±4 (mostly within ±1), in the scale 2^e.
            let e = (v >> 40) as u32 % 21;
            let ratio = |bits: u64| {
                let t = (bits & 0xffff) as i64 - 0x8000; // ±2¹⁵ is ±1
                let t = if bits & 0x30000 == 0 { t * 4 } else { t };
                let n = (i128::from(w) * i128::from(t)) >> (15 + e);
                i32::try_from(n).unwrap_or(if n < 0 { i32::MIN } else { i32::MAX })
            };
            let (x, y) = if i % 64 == 0 {
                // Edges: the extremes of i32, and zero.
                let pick = [0, 1, -1, i32::MAX, i32::MIN, i32::MIN + 1];
                (pick[(u % 6) as usize], pick[((u >> 3) % 6) as usize])
            } else {
                (ratio(u >> 16), ratio(u >> 36))
            };
            // The guess at w's normalisation: right half of the time, else any.
            let guess = if u >> 20 & 1 == 0 {
                bits_beyond_31(w.max(0)).clamp(1, 14)
            } else {
                1 + (u >> 21) as u32 % 14
            };
            let c = Clip4::from_parts([x, y], [zhi, hi], [zlo, lo], (1u32 << e) as f32);
            let map = &maps[(i % 4) as usize];
            // The exact planes, as project_fixed tests them.
            let code = if w < 1 { outcode::W } else { 0 }
                | if z < -w { outcode::NEAR } else { 0 }
                | if z > w { outcode::FAR } else { 0 };
            let want = map.project_integer(&c, z, w, code);
            // Meant for it: w ≥ 2³¹ (not next to a power of two, where w may normalise to
            // 2³⁰), z not within 2¹⁵ of ±w, |x|, |y| within w. (This generator puts x/w
            // and y/w on multiples of 2⁻¹⁵, often next to a rounding boundary of the
            // screen position: some 0.3 % of these, where the fast path cannot tell.)
            let meant = i % 16 != 1
                && w >= 1 << 31
                && (z + w).min(w - z) >= 1 << 15
                && [x, y].iter().all(|&v| (i64::from(v) << e).abs() < w);
            meant_for += u64::from(meant);
            let mut hint = guess;
            if let Some(got) = map.project_fast(&c, &mut hint) {
                assert_eq!(Some((0, got)), want, "x {x} y {y} z {z} w {w} e {e}");
                fast += u64::from(meant);
            }
        }
        assert!(
            fast >= meant_for - meant_for / 100 && meant_for > cases / 4,
            "{fast} fast of {meant_for}"
        );
    }

    /// [`recip62_low`] is ⌊2⁶²/d⌋: its first step exact for every one of d's top 16
    /// bits (the steps' products within `i32`), then every bucket's ends and middle and
    /// 10⁷ random divisors. `ZRASTER_EXHAUSTIVE=1` checks every divisor (2³⁰ of them;
    /// in a release build, some seconds).
    #[test]
    fn rounded_high_word_is_exact() {
        let mut rnd = crate::testing::xorshift64(0x5851_f42d_4c95_7f2d);
        let edges = [0, 1, 0xffff, 0x1_0000, 0x7fff_ffff, 0x8000_0000, u32::MAX];
        for &a in &edges {
            for &b in &edges {
                let want = ((u64::from(a) * u64::from(b) + (1 << 31)) >> 32) as u32;
                assert_eq!(rounded_high(a, b), want, "{a} {b}");
            }
        }
        for _ in 0..crate::num::tests::fast_cases() {
            let v = rnd();
            let (a, b) = (v as u32, (v >> 32) as u32);
            let want = ((u64::from(a) * u64::from(b) + (1 << 31)) >> 32) as u32;
            assert_eq!(rounded_high(a, b), want, "{a} {b}");
        }
    }

    /// At w = 2³¹ (normalised to exactly 2³⁰, where the reciprocal 2³² is a shift) the
    /// integer projection gives the exactly rounded quotients.
    #[test]
    fn integer_projection_at_a_power_of_two_w() {
        let map = ScreenMap::new(&Viewport::new(320, 240).unwrap());
        let w = 1i64 << 31;
        let round = |n: i64| n.signum() * ((n.abs() + (1 << 29)) >> 30);
        for (x, y, z) in [
            (0, 0, 0i64),
            (12345, -9876, 1 << 30),
            (-(1 << 30) + 3, (1 << 30) - 5, -(1 << 31) + 7),
            (i32::MAX, i32::MIN, (1 << 31) - 1),
        ] {
            let c = Clip4::from_parts(
                [x, y],
                [(z >> 14) as i32, (w >> 14) as i32],
                [(z & 0x3fff) as i32, 0],
                1.0,
            );
            let (xn, yn, un) = (i64::from(x) >> 1, i64::from(y) >> 1, (z + w) >> 1);
            let want = ScreenVertex::from_raw(
                (map.ox_i + round(xn * map.half_w)) as i32,
                (map.oy_i - round(yn * map.half_h)) as i32,
                ((un * 65535 + (1 << 14)) >> 15).clamp(0, i64::from(MAX_DEPTH)) as u32,
            );
            assert_eq!(
                map.project_integer(&c, z, w, 0),
                Some((0, want)),
                "{x} {y} {z}"
            );
        }
    }

    /// The vertex kernel's twin places no vertex otherwise than the `f32` path
    /// (`project_float_inside`, then `CachedVertex::placing`), and places nearly every
    /// vertex that path places: cameras from inside the model to far away, turned,
    /// fields of view from narrow to wide, viewports large and small, off the origin.
    #[test]
    fn place_kernel_twin_is_the_float_path() {
        use crate::num::kernel::place_portable;
        let mut next = crate::testing::xorshift32(0x7f4a_7c15);
        let (mut usual, mut placed, mut blocks) = (0u64, 0u64, 0);
        let per = crate::num::tests::fast_cases() / 400;
        for case in 0..400u32 {
            let (w, h) = [(320, 240), (240, 240), (16, 9), (2048, 1536), (1, 1)][case as usize % 5];
            let vp =
                Viewport::at((case % 7) as i32 * 301 - 900, (case % 3) as i32 * 50, w, h).unwrap();
            let dist = [1.6, 0.9, 3.0, 40.0, 0.3, 2.2, 0.05][case as usize % 7];
            let fov = [60.0, 10.0, 120.0, 45.0][case as usize % 4];
            let cam = Camera::look_at(Vec3::new(0.2, -0.1, dist), Vec3::default(), Vec3::Y)
                .unwrap()
                .perspective(radians(fov), 0.1, 10.0, vp)
                .unwrap()
                .with_model(
                    Mat4::rotation_y(radians(case as f32 * 13.7))
                        * Mat4::rotation_x(radians(case as f32 * 5.3)),
                );
            let scale = [1.0 / 32767.0, 1.0 / 1000.0, 3.0 / 32767.0][case as usize % 3];
            let fixed = FixedTransform::new(&cam.model_view_projection(), scale).unwrap();
            let map = ScreenMap::new(&vp);
            let Some(block) = map.place_block(&fixed) else {
                continue;
            };
            blocks += 1;
            for i in 0..per {
                let r = next();
                let p = match i % 4 {
                    0 => [r as i16, next() as i16, next() as i16],
                    _ => [(r as i16) >> 2, (next() as i16) >> 2, (next() as i16) >> 2],
                };
                let want = map
                    .project_float_inside(fixed.apply(&p).to_f32())
                    .and_then(CachedVertex::placing);
                let got = place_portable(&block, &p);
                if got.is_some() {
                    assert_eq!(got, want, "{p:?} case {case}");
                }
                usual += u64::from(want.is_some());
                placed += u64::from(got.is_some());
            }
        }
        assert!(blocks > 200, "{blocks}");
        assert!(
            placed >= usual - usual / 50 && placed > 0,
            "{placed} of {usual}"
        );
    }

    /// The ARMv6-M vertex kernel's twin gives the integer projection's entry
    /// (`project_integer` then `CachedVertex::placing`, what the cache's `cache_entry`
    /// gives on ARMv6-M) where it gives an entry, and gives one wherever `project_fast` does but next to a screen
    /// coordinate's rounding boundary (4 values in 16,384; its own error bounds, not
    /// `project_fast`'s, so it places some that `project_fast` leaves), the hint carried
    /// alike: for cameras from inside the model to far away, turned,
    /// fields of view from narrow to wide, viewports large and small, off the origin,
    /// mesh scales that put w's bits beyond 31 anywhere from 1 to 14.
    #[test]
    fn place_v6m_twin_is_the_fast_path() {
        use crate::num::kernel::place_v6m_portable;
        let mut next = crate::testing::xorshift32(0x4f6c_dd1d);
        let (mut placed, mut blocks, mut refused) = (0u64, 0, 0);
        let per = crate::num::tests::fast_cases() / 400;
        for case in 0..400u32 {
            let (w, h) =
                [(320, 240), (240, 240), (16, 9), (2048, 1536), (8192, 8192)][case as usize % 5];
            let vp =
                Viewport::at((case % 7) as i32 * 301 - 900, (case % 3) as i32 * 50, w, h).unwrap();
            let dist = [1.6, 0.9, 3.0, 40.0, 0.3, 2.2, 0.05][case as usize % 7];
            let fov = [60.0, 10.0, 120.0, 45.0][case as usize % 4];
            let cam = Camera::look_at(Vec3::new(0.2, -0.1, dist), Vec3::default(), Vec3::Y)
                .unwrap()
                .perspective(radians(fov), 0.1, 10.0, vp)
                .unwrap()
                .with_model(
                    Mat4::rotation_y(radians(case as f32 * 13.7))
                        * Mat4::rotation_x(radians(case as f32 * 5.3)),
                );
            let scale = [1.0 / 32767.0, 1.0 / 1000.0, 3.0 / 32767.0, 1e-7, 40.0][case as usize % 5];
            let Ok(fixed) = FixedTransform::new(&cam.model_view_projection(), scale) else {
                continue;
            };
            let map = ScreenMap::new(&vp);
            let rows = fixed.with_rows_v6m(|r| *r);
            let Some(mut block) = map.place_block_v6m(&rows, fixed.scale()) else {
                continue;
            };
            blocks += 1;
            let mut hint = W_SHIFT_HINT;
            for i in 0..per {
                let r = next();
                let p = match i % 4 {
                    0 => [r as i16, next() as i16, next() as i16],
                    _ => [(r as i16) >> 2, (next() as i16) >> 2, (next() as i16) >> 2],
                };
                let c = fixed.apply(&p);
                let want = map
                    .project_fast(&c, &mut hint)
                    .and_then(CachedVertex::placing);
                let got = place_v6m_portable(&mut block, &p);
                if got.is_some() {
                    // The entry of the integer projection (which `project_fast` gives
                    // where it gives one: the cache's other way on ARMv6-M).
                    let (z, w) = c.zw();
                    let code = if w < 1 { outcode::W } else { 0 }
                        | if z < -w { outcode::NEAR } else { 0 }
                        | if z > w { outcode::FAR } else { 0 };
                    let exact = map
                        .project_integer(&c, z, w, code)
                        .and_then(|(code, v)| (code == 0).then_some(v))
                        .and_then(CachedVertex::placing);
                    assert_eq!(got, exact, "{p:?} case {case}");
                } else if want.is_some() {
                    refused += 1;
                }
                placed += u64::from(got.is_some());
            }
        }
        assert!(blocks > 200 && placed > 1000, "{blocks} {placed}");
        assert!(refused <= placed / 2000, "{refused} refused of {placed}");
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
