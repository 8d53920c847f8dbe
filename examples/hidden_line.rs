//! The seeds' cube with hidden-line removal (left) and as a plain wireframe (right).
//!
//! `cargo run --release --example hidden_line` writes `hidden_line.png`.
mod common;

fn main() {
    common::present(&zraster_scenes::cube_hidden_line(), "hidden_line", 2);
}
