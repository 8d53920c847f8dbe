//! A plain reference rasterizer for the tests: every pixel centre tested against the
//! three edge functions (top-left rule), depth from the exact plane equation.
#![allow(dead_code)]

pub mod cli;
pub mod textured_cube;

use zraster::{depth_at, ScreenVertex};

/// Is the centre of pixel (px, py) covered by `tri` (either winding), by the top-left rule?
pub fn covers(tri: &[ScreenVertex; 3], px: i32, py: i32) -> bool {
    let mut p: [(i64, i64); 3] = tri.map(|v| (i64::from(v.x()), i64::from(v.y())));
    let area = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1);
    if area == 0 {
        return false;
    }
    if area < 0 {
        p.swap(1, 2);
    }
    let (cx, cy) = (i64::from(px) * 16 + 8, i64::from(py) * 16 + 8);
    (0..3).all(|i| {
        let (a, b) = (p[i], p[(i + 1) % 3]);
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let e = dx * (cy - a.1) - dy * (cx - a.0);
        // Interior has e > 0; on the edge, keep top (horizontal, dx > 0) and left (dy < 0) edges.
        e > 0 || (e == 0 && ((dy == 0 && dx > 0) || dy < 0))
    })
}

/// The exact plane depth (16.16, rounded down) at the centre of pixel (px, py).
pub fn plane_depth(tri: &[ScreenVertex; 3], px: i32, py: i32) -> i64 {
    depth_at(tri, px * 16 + 8, py * 16 + 8).expect("non-degenerate")
}

/// The depth the Z-buffer should hold: the plane depth rounded to the nearest integer.
pub fn stored_depth(tri: &[ScreenVertex; 3], px: i32, py: i32) -> i64 {
    (plane_depth(tri, px, py) + (1 << 15)) >> 16
}

pub fn vpx(x: i32, y: i32, z: u16) -> ScreenVertex {
    ScreenVertex::from_pixels(x, y, z).expect("in range")
}

pub fn vsub(x: i32, y: i32, z: u16) -> ScreenVertex {
    ScreenVertex::new(x, y, u32::from(z) << 16).expect("in range")
}
