//! zraster's textured fill on Cortex-M under QEMU: instructions a pixel.
//!
//! Run with `bench/texture.sh` (both instruction sets). QEMU's `-icount shift=0` makes
//! the CMSDK timer count exactly one tick per 40 executed instructions, so the figures
//! are the same from run to run. The scene is `bench/mcu`'s fill-bound cube (the cube's
//! front face close up, covering all 320×240 pixels), drawn untextured (the reference)
//! and with a 64×64 RGB565 checker from flash, perspective-correct and affine, and
//! through the pixel-shader hook (the texel shader, and fog over it).
#![no_std]
#![no_main]

use core::ptr::{addr_of_mut, read_volatile, write_volatile};

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use embedded_graphics::{
    pixelcolor::{Rgb565, Rgb888},
    prelude::*,
};
use panic_semihosting as _;
use zraster::{
    camera::{Camera, Viewport},
    math::{radians, Vec3},
    mesh::{CUBE, CUBE_POSITIONS},
    shade::Shading,
    shader::{Fog, Textured},
    texture::{MeshUv, Texture},
    Frame, RenderOptions, Renderer, Texturing, UvMode,
};

const W: u32 = 320;
const H: u32 = 240;
const N: usize = (W * H) as usize;

static mut PIXELS: [Rgb565; N] = [Rgb565::BLACK; N];
static mut DEPTH: [u16; N] = [0; N];

/// A 64×64 checker of 8×8-texel squares, raw RGB565 (a `const`: it stays in flash).
const CHECKER: [u16; 64 * 64] = {
    let mut t = [0u16; 64 * 64];
    let mut i = 0;
    while i < 64 * 64 {
        let (x, y) = (i % 64, i / 64);
        t[i] = if (x / 8 + y / 8) % 2 == 0 {
            0xFD20
        } else {
            0x18E3
        };
        i += 1;
    }
    t
};

/// Texture coordinates for the cube's eight vertices: u = 4x, v = 4(1 − y) textures, so
/// the front face (z = 1) carries the checker four times across and down.
const CUBE_UVS: [MeshUv; 8] = {
    let mut uv = [[0i16; 2]; 8];
    let mut i = 0;
    while i < 8 {
        let p = CUBE_POSITIONS[i];
        // Positions are 0 or 16384 (one unit): 16384 in Q12 is four textures.
        uv[i] = [p[0], 16384 - p[1]];
        i += 1;
    }
    uv
};

// Region markers for bench/tools/pcprof.c (QEMU's plugin): empty, never inlined.
core::arch::global_asm!(
    ".global bench_start",
    ".type bench_start,%function",
    ".thumb_func",
    "bench_start:",
    "bx lr",
    ".global bench_stop",
    ".type bench_stop,%function",
    ".thumb_func",
    "bench_stop:",
    "bx lr",
);
extern "C" {
    fn bench_start();
    fn bench_stop();
}

const TIMER_CTRL: *mut u32 = 0x4000_0000 as *mut u32;
const TIMER_VALUE: *mut u32 = 0x4000_0004 as *mut u32;
const TIMER_RELOAD: *mut u32 = 0x4000_0008 as *mut u32;

fn timer_start() {
    // SAFETY: CMSDK TIMER0 registers of the mps2-an386 board.
    unsafe {
        write_volatile(TIMER_CTRL, 0);
        write_volatile(TIMER_RELOAD, u32::MAX);
        write_volatile(TIMER_VALUE, u32::MAX);
        write_volatile(TIMER_CTRL, 1);
    }
}

fn ticks() -> u32 {
    // SAFETY: as above.
    unsafe { read_volatile(TIMER_VALUE) }
}

/// Instructions spent in `f` (±40), via the timer; also marked for the plugin.
fn measure<R>(f: impl FnOnce() -> R) -> (R, u32) {
    let t0 = ticks();
    // SAFETY: empty assembly functions.
    unsafe { bench_start() };
    let r = f();
    unsafe { bench_stop() };
    let t1 = ticks();
    (r, t0.wrapping_sub(t1) * 40)
}

/// FNV-1a of the frame's pixels.
fn checksum(px: &[Rgb565]) -> u32 {
    px.iter().fold(0x811c_9dc5u32, |h, c| {
        let v = c.into_storage();
        ((h ^ u32::from(v & 0xff)).wrapping_mul(0x0100_0193) ^ u32::from(v >> 8))
            .wrapping_mul(0x0100_0193)
    })
}

fn report(what: &str, instructions: u32, written: u32, sum: u32) {
    let written = written.max(1);
    hprintln!(
        "{}: {} instructions, {} pixels written, {}.{:02} per pixel (checksum {:08x})",
        what,
        instructions,
        written,
        instructions / written,
        (instructions % written) * 100 / written,
        sum
    );
}

#[entry]
fn main() -> ! {
    timer_start();
    // SAFETY: single-threaded; each static is borrowed once.
    let (pixels, depth) = unsafe { (&mut *addr_of_mut!(PIXELS), &mut *addr_of_mut!(DEPTH)) };
    let camera = Camera::look_at(Vec3::new(0.5, 0.5, 1.3), Vec3::new(0.5, 0.5, 0.0), Vec3::Y)
        .unwrap()
        .perspective(radians(60.0), 0.1, 10.0, Viewport::new(W, H).unwrap())
        .unwrap();
    let texture = Texture::new(&CHECKER, 64, 64).unwrap();

    // The textured segment's assembly against its portable twin (bench/texture.sh fails
    // unless none differ).
    let bad = zraster::check_texel_kernel(&mut depth[..], 4000);
    hprintln!("texel kernel cases differing from the portable twin: {}", bad);

    // The reference: bench/mcu's flat fill-bound cube.
    {
        let mut frame = Frame::new(&mut pixels[..], &mut depth[..], W, H).unwrap();
        frame.clear(Rgb565::BLACK);
        let mut r = Renderer::new(&CUBE, &camera, RenderOptions::default()).unwrap();
        let (_, n) = measure(|| r.draw(&mut frame).unwrap());
        let written = r.stats().pixels_written as u32;
        report(
            "flat fill-bound cube",
            n,
            written,
            checksum(frame.color().as_slice()),
        );
    }
    let cases = [
        (
            "textured fill-bound cube, perspective-correct",
            UvMode::Perspective,
            Shading::Flat,
        ),
        (
            "textured fill-bound cube, affine",
            UvMode::Affine,
            Shading::Flat,
        ),
        (
            "textured fill-bound cube, perspective-correct, Lambert",
            UvMode::Perspective,
            Shading::Lambert,
        ),
    ];
    for (what, mode, shading) in cases {
        let mut frame = Frame::new(&mut pixels[..], &mut depth[..], W, H).unwrap();
        frame.clear(Rgb565::BLACK);
        let options = RenderOptions {
            shading,
            ..Default::default()
        };
        let mut r = Renderer::new(&CUBE, &camera, options).unwrap();
        let t = Texturing::new(&CUBE_UVS, texture).with_mode(mode);
        let (_, n) = measure(|| r.draw_textured(&mut frame, &t).unwrap());
        let written = r.stats().pixels_written as u32;
        report(what, n, written, checksum(frame.color().as_slice()));
    }
    // The same cube through the pixel-shader hook (the general loop, a shader inlined
    // in it): the texel shader (the perspective-correct picture again) and fog over it.
    let options = RenderOptions::default();
    let textured = Textured::new(&CUBE_UVS, texture);
    // The face is at window depth 0.673 (0.3 units away): 58 % fog.
    let fog = Fog::new(textured, 0.5, 0.8, Rgb888::new(170, 180, 190)).unwrap();
    for (what, fogged) in [
        ("textured fill-bound cube, shader Textured", false),
        ("textured fill-bound cube, shader Fog(Textured)", true),
    ] {
        let mut frame = Frame::new(&mut pixels[..], &mut depth[..], W, H).unwrap();
        frame.clear(Rgb565::BLACK);
        let mut r = Renderer::new(&CUBE, &camera, options).unwrap();
        let (_, n) = if fogged {
            measure(|| r.draw_with_shader(&mut frame, &fog).unwrap())
        } else {
            measure(|| r.draw_with_shader(&mut frame, &textured).unwrap())
        };
        let written = r.stats().pixels_written as u32;
        report(what, n, written, checksum(frame.color().as_slice()));
    }
    debug::exit(debug::EXIT_SUCCESS);
    loop {}
}
