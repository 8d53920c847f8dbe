//! Shared by the examples: show a finished frame. (The scenes they show are the
//! internal crate `zraster_scenes`, in `examples/scenes`, which the tests use too.)
//!
//! Headless by default: the frame is written as a PNG (one image pixel per display
//! pixel). With `--features window` it opens an SDL window instead (Debian's
//! `libsdl2-dev` is needed to build that).
#![allow(dead_code)]

use embedded_graphics::pixelcolor::{PixelColor, Rgb888};
use embedded_graphics_simulator::{OutputSettings, SimulatorDisplay};

/// Write `display` to `NAME.png` (or show it in a window with the `window` feature).
pub fn present<C>(display: &SimulatorDisplay<C>, name: &str, scale: u32)
where
    C: PixelColor + Into<Rgb888> + From<Rgb888>,
{
    let settings = embedded_graphics_simulator::OutputSettingsBuilder::new()
        .scale(scale)
        .build();
    #[cfg(feature = "window")]
    {
        embedded_graphics_simulator::Window::new(name, &settings).show_static(display);
    }
    #[cfg(not(feature = "window"))]
    {
        let path = format!("{name}.png");
        if let Err(e) = display.to_rgb_output_image(&settings).save_png(&path) {
            eprintln!("error: cannot write {path}: {e}");
            std::process::exit(1);
        }
        println!("wrote {path}");
    }
    let _: &OutputSettings = &settings;
}
