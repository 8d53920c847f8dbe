//! The seeds' cube with per-face colours: drawn in face-table order with no
//! hidden-surface removal (left, wrong), and with back faces culled (right).
//!
//! `cargo run --release --example cube` writes `cube.png`.
mod common;

fn main() {
    common::present(&zraster_scenes::cube_culling(), "cube", 2);
}
