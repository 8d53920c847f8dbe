//! A 128×64 monochrome view, as on an SSD1306 OLED: the bunny, Lambert-lit and
//! ordered-dithered to on/off pixels.
//!
//! `cargo run --release --example oled` writes `oled.png`.
mod common;

fn main() {
    common::present(&zraster_scenes::mono_oled(), "oled", 4);
}
