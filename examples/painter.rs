//! Painter's algorithm (left) against the Z-buffer (right) on the seeds' three failure
//! cases: cyclic overlap, interpenetrating polygons, a concave object.
//!
//! `cargo run --release --example painter` writes `painter.png`.
mod common;

fn main() {
    common::present(&zraster_scenes::painter_vs_zbuffer(), "painter", 2);
}
