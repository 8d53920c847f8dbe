//! Quantising model-space `f32` positions into a mesh's `i16` vertex table.

use super::check_scale;
use crate::error::prefix_mut;
use crate::math::{Mat4, Vec3};
use crate::Error;

/// How [`quantize`] stored positions: a model-space point is `position × scale + offset`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quantized {
    /// Model units per position step: the mesh's [`scale`](super::Mesh::scale).
    pub scale: f32,
    /// What was subtracted before scaling (the bounding box's centre, or zero).
    pub offset: Vec3,
}

impl Quantized {
    /// The model matrix that puts the offset back: `Mat4::translation(offset)`. Multiply
    /// it into the model matrix on the right (`spin * q.model()`), or ignore it to have the
    /// mesh centred on the origin.
    pub fn model(&self) -> Mat4 {
        Mat4::translation(self.offset)
    }
}

/// Quantise `f32` positions into `i16` vertex-table entries in `out` (one per point):
/// the largest coordinate (after subtracting the bounding box's centre, when `centre`)
/// becomes ±32767, every other the nearest step (halves away from zero). Returns the
/// scale and offset; the scale obeys [`check_scale`]. No heap: `out` is yours (a
/// `static mut` table, a stack array).
///
/// Errors: [`Error::BufferTooSmall`] for a short `out` (nothing written),
/// [`Error::NotFinite`] for a NaN or infinite coordinate, and
/// [`Error::InvalidParameter`] for points so close together (below ~10⁻⁴⁰) that their
/// step is not a positive `f32`. No points, or all at one place, give scale 1 and zeros.
///
/// ```
/// use zraster::mesh::{quantize, Mesh};
/// use embedded_graphics::pixelcolor::Rgb888;
///
/// let points = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 1.2, 0.5]];
/// let mut table = [[0i16; 3]; 3];
/// let q = quantize(&points, false, &mut table)?;
/// // 2.0 is the largest: 32767 steps; 1.2 is 19660.2 steps, 0.5 is 8191.75.
/// assert_eq!(table, [[0, 0, 0], [32767, 0, 0], [0, 19660, 8192]]);
/// assert_eq!(q.scale, 2.0 / 32767.0);
/// let mesh = Mesh::triangles(&table, q.scale, &[[0, 1, 2]], Rgb888::new(255, 255, 255));
/// mesh.validate()?;
/// # Ok::<(), zraster::Error>(())
/// ```
pub fn quantize(
    points: &[[f32; 3]],
    centre: bool,
    out: &mut [[i16; 3]],
) -> Result<Quantized, Error> {
    let out = prefix_mut(out, points.len())?;
    if !points.iter().flatten().all(|v| v.is_finite()) {
        return Err(Error::NotFinite);
    }
    let mut offset = [0.0f32; 3];
    if let (Some(first), true) = (points.first(), centre) {
        let (mut lo, mut hi) = (*first, *first);
        for p in points {
            for ((l, h), &v) in lo.iter_mut().zip(hi.iter_mut()).zip(p) {
                *l = l.min(v);
                *h = h.max(v);
            }
        }
        // In f64: lo + hi overflows f32 near ±f32::MAX.
        for ((o, &l), &h) in offset.iter_mut().zip(&lo).zip(&hi) {
            *o = ((f64::from(l) + f64::from(h)) * 0.5) as f32;
        }
    }
    // Around the centre a point is at most half the extent away: within f32.
    let mut reach = 0.0f32;
    for p in points {
        for (&v, &o) in p.iter().zip(&offset) {
            reach = reach.max((v - o).abs());
        }
    }
    let scale = if reach > 0.0 { reach / 32767.0 } else { 1.0 };
    check_scale(scale)?;
    let step = |v: f32| round_half_away(v / scale).clamp(-32767, 32767) as i16;
    for (o, p) in out.iter_mut().zip(points) {
        for ((q, &v), &off) in o.iter_mut().zip(p).zip(&offset) {
            *q = step(v - off);
        }
    }
    Ok(Quantized {
        scale,
        offset: Vec3::new(offset[0], offset[1], offset[2]),
    })
}

/// `v` rounded to the nearest integer, halves away from zero (as `f32::round`), for
/// |v| below 2²⁴ (larger values are clamped to ±2²⁴, which the caller clamps further).
pub(super) fn round_half_away(v: f32) -> i32 {
    let v = v.clamp(-16_777_216.0, 16_777_216.0);
    let t = v as i32; // towards zero
    let frac = v - t as f32; // exact below 2²⁴
    if frac >= 0.5 {
        t + 1
    } else if frac <= -0.5 {
        t - 1
    } else {
        t
    }
}
