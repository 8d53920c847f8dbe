//! Lesson 5: bands in little RAM. A 320 × 240 RGB565 frame and its depths take 300 KiB;
//! most microcontrollers have less. `Bands` draws the frame 16 rows at a time instead:
//! each band is cleared, drawn into `BandBuffers` (one band of colour and depth), handed
//! to `after_band` (an overlay: here the caption) and sent to the display in one
//! `fill_contiguous`. The picture is exactly that of a whole frame, in 20 KiB.
//!
//! `cargo run --release --example lesson5_bands` prints the RAM it takes and writes
//! `lesson5_bands.png`; `--features window` shows it turning.
use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::{prelude::*, text::Text};
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
#[cfg(feature = "window")]
use embedded_graphics_simulator::{SimulatorEvent::Quit, Window};
use std::time::{Duration, Instant};
use zraster::math::{radians, Mat4, Vec3};
use zraster::mesh::{Mesh, CUBE_POSITIONS};
use zraster::shade::{Light, Shading};
use zraster::{BandBuffers, Bands, CachedVertex, Camera, DrawError, FrameStats};
use zraster::{Cull, RenderOptions, Renderer, Viewport};

pub const W: u32 = 320;
pub const H: u32 = 240;
pub const ROWS: u32 = 16; // rows a band
#[cfg(not(feature = "window"))]
const FRAMES: u32 = 100; // headless: 100 frames, then the PNG
#[cfg(feature = "window")]
const FRAMES: u32 = u32::MAX; // in the window: until it is closed

// The unit cube as 12 triangles, in one colour: with a triangle mesh and a vertex
// cache, the visible triangles are sorted by band once a frame ("bins"), so that each
// band visits only the triangles that reach it.
#[rustfmt::skip]
const TRIANGLES: [[u16; 3]; 12] = [
    [0, 1, 2], [0, 2, 3], [1, 5, 6], [1, 6, 2], [2, 6, 7], [2, 7, 3],
    [3, 7, 4], [3, 4, 0], [0, 4, 5], [0, 5, 1], [7, 6, 5], [7, 5, 4],
];
const AMBER: Rgb888 = Rgb888::new(255, 180, 60);
pub const CUBE: Mesh = Mesh::triangles(&CUBE_POSITIONS, 1.0 / 16384.0, &TRIANGLES, AMBER);
// Flat Lambert lighting (one brightness a face) from the upper left, back faces culled.
const LIGHT: Light = Light {
    direction: Vec3::new(-1.0, 1.0, 1.0),
    ambient: 0.2,
    diffuse: 0.8,
};
pub const OPTIONS: RenderOptions = RenderOptions {
    cull: Cull::Back,
    shading: Shading::Lambert,
    light: LIGHT,
};

/// The camera for the cube turned `angle` radians about its centre.
pub fn camera(angle: f32) -> Result<Camera, zraster::Error> {
    let turn = Mat4::rotation_y(angle) * Mat4::rotation_x(0.4 * angle.sin());
    let centred = turn * Mat4::translation(Vec3::new(-0.5, -0.5, -0.5));
    let look = Camera::look_at(Vec3::new(0.0, 0.8, 3.0), Vec3::default(), Vec3::Y)?;
    Ok(look
        .perspective(radians(45.0), 0.1, 10.0, Viewport::new(W, H)?)?
        .with_model(centred))
}

/// Draw the cube turned `angle` into `display`, band by band through `buffers`, with
/// `caption` at the bottom left; the counts of the frame.
pub fn render<D: DrawTarget<Color = Rgb565>>(
    display: &mut D,
    buffers: &mut BandBuffers<Rgb565>,
    cache: &mut [CachedVertex],
    angle: f32,
    caption: &str,
) -> Result<FrameStats, DrawError<D::Error>> {
    // The cache: each vertex transformed once a frame (8 bytes a vertex), not once a band.
    let mut renderer = Renderer::with_cache(&CUBE, &camera(angle)?, OPTIONS, cache)?;
    let style = MonoTextStyle::new(&FONT_6X10, Rgb565::WHITE);
    let text = Text::new(caption, Point::new(4, 232), style);
    // The band is a DrawTarget in screen coordinates, clipped to its rows; drawing into
    // RAM cannot fail (its error type is Infallible), so `let Ok(_)` needs no else.
    let mut bands = Bands::new(display, buffers, Rgb565::BLACK).after_band(|band, _| {
        let Ok(_) = text.draw(band);
    });
    renderer.draw(&mut bands)?;
    Ok(renderer.stats())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // One band of colour and depth, the bins (one u16 a triangle, a few a band) and
    // the vertex cache: all the RAM the drawing needs.
    let (mut color, mut depth) = (
        [Rgb565::BLACK; (W * ROWS) as usize],
        [0; (W * ROWS) as usize],
    );
    let mut bins = [0u16; BandBuffers::<Rgb565>::bins_needed(TRIANGLES.len(), H, ROWS)];
    let mut cache = [CachedVertex::EMPTY; CUBE_POSITIONS.len()];
    let ram = size_of_val(&color) + size_of_val(&depth) + size_of_val(&bins) + size_of_val(&cache);
    let whole = W * H * 4; // two bytes of colour and two of depth a pixel
    println!("RAM: {ram} bytes for {ROWS}-row bands, against {whole} for a whole frame");
    let caption = format!(
        "{ROWS}-row bands: {:.1} KiB, not {} KiB",
        ram as f32 / 1024.0,
        whole / 1024
    );
    let mut buffers = BandBuffers::new(&mut color, &mut depth, W, ROWS, H, &mut bins)?;
    // Bands send each band to the display as it is done: here the simulator's.
    let mut display = SimulatorDisplay::new(Size::new(W, H));
    let settings = OutputSettingsBuilder::new().scale(2).build();
    #[cfg(feature = "window")]
    let mut window = Window::new("zraster lesson 5: bands", &settings);
    let mut drawing = Duration::ZERO;
    for n in 1..=FRAMES {
        let start = Instant::now();
        render(
            &mut display,
            &mut buffers,
            &mut cache,
            n as f32 * 0.02,
            &caption,
        )?;
        drawing += start.elapsed(); // drawing and sending to the display
        if n % 100 == 0 {
            let ms = drawing.as_secs_f64() * 10.0; // 1000 ms / 100 frames
            println!("{ms:.3} ms/frame, {:.0} fps", 1000.0 / ms);
            drawing = Duration::ZERO;
        }
        #[cfg(feature = "window")]
        {
            window.update(&display);
            if window.events().any(|e| e == Quit) {
                break;
            }
        }
    }
    #[cfg(not(feature = "window"))]
    {
        let image = display.to_rgb_output_image(&settings);
        image.save_png("lesson5_bands.png")?;
        println!("wrote lesson5_bands.png");
    }
    Ok(())
}
