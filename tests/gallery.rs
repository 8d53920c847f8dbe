//! The gallery's pictures in `docs/` are what `examples/gallery.rs` draws now: the
//! example runs into a scratch folder and each file is compared with the checked-in
//! one, pixel by pixel (PNG) and frame by frame (GIF). After a deliberate change,
//! `ZRASTER_BLESS=1 cargo test --test gallery` (or `cargo run --example gallery`)
//! rewrites them.

use std::path::{Path, PathBuf};
use std::process::Command;

use embedded_graphics::{pixelcolor::Rgb888, prelude::*};
use embedded_graphics_simulator::SimulatorDisplay;

const PNGS: [&str; 4] = [
    "gallery-painter.png",
    "gallery-lines.png",
    "gallery-oled.png",
    "gallery-bands.png",
];
const GIF: &str = "bunny-spin.gif";

fn docs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("docs")
}

/// The gallery drawn into a scratch folder.
fn draw_gallery() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("zraster-gallery-{}", std::process::id()));
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .args(["run", "--quiet", "--example", "gallery", "--", "--out-dir"])
        .arg(&dir)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "gallery failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let wrote = String::from_utf8(out.stdout).unwrap();
    assert_eq!(wrote.lines().count(), PNGS.len() + 1, "{wrote}");
    dir
}

/// The GIF's frames, each composed onto the canvas as a viewer shows it (frames after
/// the first cover only the rectangle that changed), as RGB.
fn gif_frames(path: &Path) -> (u16, u16, Vec<Vec<[u8; 3]>>) {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::Indexed);
    let mut decoder = options
        .read_info(std::fs::File::open(path).unwrap())
        .unwrap();
    let (w, h) = (decoder.width(), decoder.height());
    assert_eq!(decoder.repeat(), gif::Repeat::Infinite);
    let palette = decoder.global_palette().unwrap().to_vec();
    let mut canvas = vec![[0u8; 3]; usize::from(w) * usize::from(h)];
    let mut frames = Vec::new();
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        assert_eq!(frame.dispose, gif::DisposalMethod::Keep);
        for (k, &index) in frame.buffer.iter().enumerate() {
            let (x, y) = (
                usize::from(frame.left) + k % usize::from(frame.width),
                usize::from(frame.top) + k / usize::from(frame.width),
            );
            let c = &palette[usize::from(index) * 3..usize::from(index) * 3 + 3];
            canvas[y * usize::from(w) + x] = [c[0], c[1], c[2]];
        }
        frames.push(canvas.clone());
    }
    (w, h, frames)
}

#[test]
fn the_checked_in_pictures_are_what_the_gallery_draws() {
    let fresh = draw_gallery();
    let bless = std::env::var_os("ZRASTER_BLESS").is_some();
    for name in PNGS.iter().chain([&GIF]) {
        if bless {
            std::fs::copy(fresh.join(name), docs().join(name)).unwrap();
        }
    }
    for name in PNGS {
        let got = SimulatorDisplay::<Rgb888>::load_png(fresh.join(name)).unwrap();
        let want = SimulatorDisplay::<Rgb888>::load_png(docs().join(name)).unwrap();
        assert_eq!(got.size(), want.size(), "{name}");
        assert!(
            got.diff(&want).is_none(),
            "docs/{name} is not what the gallery draws: \
             `cargo run --release --example gallery` redraws it"
        );
    }
    let (got, want) = (gif_frames(&fresh.join(GIF)), gif_frames(&docs().join(GIF)));
    assert!(got == want, "docs/{GIF} is not what the gallery draws");
    let _ = std::fs::remove_dir_all(&fresh);
}

/// The animation: 36 frames of 160×120 with the bunny turning (every frame differs
/// from the one before, and the last turns back into the first), in under 300 KB.
#[test]
fn the_spinning_bunny_is_small_and_turns() {
    let path = docs().join(GIF);
    let bytes = std::fs::metadata(&path).unwrap().len();
    assert!(bytes < 300_000, "{bytes} bytes");
    let (w, h, frames) = gif_frames(&path);
    assert_eq!((w, h, frames.len()), (160, 120, 36));
    for (k, pair) in frames.windows(2).enumerate() {
        assert!(pair[0] != pair[1], "frames {k} and {} are the same", k + 1);
    }
    // The bunny is there: a warm pixel (more red than blue) in the middle of every
    // frame, an eighth or more of the frame covered, and the corners black.
    for f in &frames {
        let centre = f[60 * 160 + 80];
        assert!(centre[0] > centre[2], "{centre:?}");
        let covered = f.iter().filter(|c| **c != [0, 0, 0]).count();
        assert!(covered > 160 * 120 / 8, "{covered}");
        assert_eq!(f[0], [0, 0, 0]);
    }
}

/// The painter's failures show: on cyclic overlap and interpenetration the painter's
/// panel differs from the Z-buffer's, on covered pixels only.
#[test]
fn the_painter_panels_differ_from_the_z_buffer() {
    let img = SimulatorDisplay::<Rgb888>::load_png(docs().join("gallery-painter.png")).unwrap();
    // 2× scale: panels of 320×240 at x 0 and 322, rows at y 0 and 242.
    for row_y in [0, 242] {
        let (mut differ, mut covered) = (0, 0);
        for y in (row_y + 24..row_y + 240).step_by(2) {
            for x in (0..320).step_by(2) {
                let a = img.get_pixel(Point::new(x, y));
                let b = img.get_pixel(Point::new(x + 322, y));
                covered += usize::from(a != Rgb888::BLACK);
                differ += usize::from(a != b);
            }
        }
        assert!(
            covered > 1000 && differ > 100,
            "row {row_y}: {differ} of {covered}"
        );
    }
}
