//! The Stanford bunny with flat Lambert shading (left) and Gouraud shading (right).
//!
//! `cargo run --release --example bunny` writes `bunny.png`.
mod common;

fn main() {
    common::present(&zraster_scenes::bunny_shading(), "bunny", 2);
}
