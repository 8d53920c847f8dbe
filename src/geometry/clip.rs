//! Clipping polygons against the view volume in homogeneous clip space
//! (Sutherland–Hodgman), before any division by w.

use heapless::Vec;

use super::project::{outcode, GUARD};

/// A clip-space vertex with the attributes interpolated alongside: light intensity, and
/// texture coordinates (Q16 texture units as `f32`; zero for untextured drawing).
/// Clip-space interpolation is perspective-correct for both: the clipper cuts edges
/// before the division by w, where every attribute is linear.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ClipVertex {
    pub c: [f32; 4],
    pub light: f32,
    pub uv: [f32; 2],
}

/// A triangle cut by the 7 planes has at most 3 + 7 vertices.
pub(crate) const MAX_CLIPPED: usize = 10;

/// A clipped polygon.
pub(crate) type ClipPolygon = Vec<ClipVertex, MAX_CLIPPED>;

/// Signed distance to a plane (inside ≥ 0). Out of line without an FPU, where each of
/// its seven cases is a call or two: one copy of them (only clipped triangles come here).
#[cfg_attr(zraster_soft_float, inline(never))]
#[cfg_attr(not(zraster_soft_float), inline)]
fn distance(plane: u8, c: &[f32; 4]) -> f32 {
    let [x, y, z, w] = *c;
    match plane {
        outcode::NEAR => z + w,
        outcode::FAR => w - z,
        outcode::LEFT => x + GUARD * w,
        outcode::RIGHT => GUARD * w - x,
        outcode::BOTTOM => y + GUARD * w,
        outcode::TOP => GUARD * w - y,
        _ => w - 1.0,
    }
}

/// The point where the edge from `inside` to `outside` crosses `plane`. Always
/// computed from the inside end, so two triangles sharing the edge get the same point.
fn intersect(plane: u8, inside: &ClipVertex, outside: &ClipVertex) -> ClipVertex {
    let di = distance(plane, &inside.c);
    let do_ = distance(plane, &outside.c);
    let t = di / (di - do_);
    let lerp = |a: f32, b: f32| a + (b - a) * t;
    ClipVertex {
        c: [
            lerp(inside.c[0], outside.c[0]),
            lerp(inside.c[1], outside.c[1]),
            lerp(inside.c[2], outside.c[2]),
            lerp(inside.c[3], outside.c[3]),
        ],
        light: lerp(inside.light, outside.light),
        uv: [
            lerp(inside.uv[0], outside.uv[0]),
            lerp(inside.uv[1], outside.uv[1]),
        ],
    }
}

/// Clip `poly` in place against every plane in `planes` (an outcode mask). The result
/// may be empty. Capacity cannot run out: each plane adds at most one vertex.
pub(crate) fn clip_polygon(poly: &mut ClipPolygon, planes: u8) {
    for bit in 0..7 {
        let plane = 1u8 << bit;
        if planes & plane == 0 || poly.is_empty() {
            continue;
        }
        let mut out = ClipPolygon::new();
        for (a, b) in poly.iter().zip(poly.iter().cycle().skip(1)) {
            let (ina, inb) = (distance(plane, &a.c) >= 0.0, distance(plane, &b.c) >= 0.0);
            if ina {
                let _ = out.push(*a);
            }
            if ina != inb {
                let p = if ina {
                    intersect(plane, a, b)
                } else {
                    intersect(plane, b, a)
                };
                let _ = out.push(p);
            }
        }
        *poly = out;
    }
}

/// Clip the segment `a`–`b` against `planes`; `None` when nothing is left.
pub(crate) fn clip_segment(
    a: &ClipVertex,
    b: &ClipVertex,
    planes: u8,
) -> Option<(ClipVertex, ClipVertex)> {
    let (mut a, mut b) = (*a, *b);
    for bit in 0..7 {
        let plane = 1u8 << bit;
        if planes & plane == 0 {
            continue;
        }
        let (da, db) = (distance(plane, &a.c), distance(plane, &b.c));
        match (da >= 0.0, db >= 0.0) {
            (true, true) => {}
            (false, false) => return None,
            (true, false) => b = intersect(plane, &a, &b),
            (false, true) => a = intersect(plane, &b, &a),
        }
    }
    Some((a, b))
}

#[cfg(test)]
mod tests {
    use super::super::project::outcode_of;
    use super::*;

    fn v(x: f32, y: f32, z: f32, w: f32) -> ClipVertex {
        ClipVertex {
            c: [x, y, z, w],
            light: 0.0,
            uv: [0.0; 2],
        }
    }

    #[test]
    fn a_triangle_through_the_near_plane_becomes_a_quad() {
        // Two vertices in front (z > −w), one behind the eye (w < 0).
        let mut p = ClipPolygon::new();
        for c in [
            v(-1.0, 0.0, 0.0, 2.0),
            v(1.0, 0.0, 0.0, 2.0),
            v(0.0, 1.0, -3.0, -1.0),
        ] {
            p.push(c).unwrap();
        }
        let mask = p.iter().fold(0, |m, c| m | outcode_of(&c.c));
        clip_polygon(&mut p, mask);
        assert_eq!(p.len(), 4);
        for c in &p {
            assert!(c.c[2] + c.c[3] >= -1e-5, "{c:?}");
            assert!(c.c[3] >= 1.0 - 1e-5, "{c:?}");
        }
    }

    #[test]
    fn shared_edges_clip_to_the_same_point() {
        let a = v(0.0, 0.0, 0.0, 5.0);
        let b = v(3.0, 1.0, -9.0, 2.0);
        let (x, y) = (
            intersect(outcode::NEAR, &a, &b),
            intersect(outcode::NEAR, &a, &b),
        );
        assert_eq!(x, y);
        let seg = clip_segment(&b, &a, outcode::NEAR).unwrap();
        assert_eq!(seg.0, x);
        assert!(clip_segment(&b, &b, outcode::NEAR).is_none());
    }
}
