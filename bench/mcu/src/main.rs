//! zraster on Cortex-M under QEMU: instructions per frame, static RAM, stack.
//!
//! Run with `bench/mcu.sh` (both instruction sets). QEMU's `-icount shift=0` makes the
//! CMSDK timer count exactly one tick per 40 executed instructions, so the figures are
//! the same from run to run. The `bench_start`/`bench_stop` markers let the region-count
//! plugin attribute exact counts to each region too.
#![no_std]
#![no_main]

use core::ptr::{addr_of, addr_of_mut, read_volatile, write_volatile};

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
use panic_semihosting as _;
use zraster::{
    camera::{Camera, Viewport},
    math::{radians, Vec3},
    mesh::CUBE,
    BandBuffers, Bands, CachedVertex, ColorBuffer, Frame, RenderOptions, Renderer, ZBuffer,
};
use zraster_bench_scene::{self as scene, bunny, checksum, H, W};

const BAND: u32 = 16;
const N: usize = (W * H) as usize;

static mut PIXELS: [Rgb565; N] = [Rgb565::BLACK; N];
static mut DEPTH: [u16; N] = [0; N];
static mut CACHE: [CachedVertex; bunny::BUNNY_POSITIONS.len()] = [CachedVertex::EMPTY; bunny::BUNNY_POSITIONS.len()];

// Region markers for the QEMU region-count plugin: empty, never inlined.
core::arch::global_asm!(
    ".global bench_start", ".type bench_start,%function", ".thumb_func", "bench_start:", "bx lr",
    ".global bench_stop", ".type bench_stop,%function", ".thumb_func", "bench_stop:", "bx lr",
);
extern "C" {
    fn bench_start();
    fn bench_stop();
    static mut __sheap: u32;
    static __ebss: u32;
    static __sdata: u32;
    static _stack_start: u32;
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

const PAINT: u32 = 0x5A5A_A5A5;

/// Fill the unused stack (from the heap start up to just below the current stack
/// pointer) with a pattern.
fn paint_stack() {
    let sp = cortex_m::register::msp::read() as usize;
    // SAFETY: the words between the end of static data and the live stack are unused.
    unsafe {
        let mut p = addr_of_mut!(__sheap) as usize;
        while p + 64 < sp {
            write_volatile(p as *mut u32, PAINT);
            p += 4;
        }
    }
}

/// The deepest the stack has reached since `paint_stack`, in bytes.
fn stack_high_water() -> usize {
    // SAFETY: reading the painted region.
    unsafe {
        let top = addr_of!(_stack_start) as usize;
        let mut p = addr_of!(__sheap) as usize;
        while p < top && read_volatile(p as *const u32) == PAINT {
            p += 4;
        }
        top - p
    }
}

/// A 320×240 display that accepts the bands and drops them.
struct Sink;

impl OriginDimensions for Sink {
    fn size(&self) -> Size {
        Size::new(W, H)
    }
}

impl DrawTarget for Sink {
    type Color = Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, _: I) -> Result<(), Self::Error> {
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(&mut self, _: &embedded_graphics::primitives::Rectangle, _: I) -> Result<(), Self::Error> {
        Ok(())
    }
}

#[entry]
fn main() -> ! {
    paint_stack();
    timer_start();
    // SAFETY: single-threaded; each static is borrowed once at a time.
    let (pixels, depth, cache) = unsafe { (&mut *addr_of_mut!(PIXELS), &mut *addr_of_mut!(DEPTH), &mut *addr_of_mut!(CACHE)) };
    if cfg!(feature = "only-fill") {
        // The fill-bound cube alone (to profile the pixel loop).
        let mut frame = Frame::new(&mut pixels[..], &mut depth[..], W, H).unwrap();
        frame.depth_mut().clear();
        let cube_xf = Camera::look_at(Vec3::new(0.5, 0.5, 1.3), Vec3::new(0.5, 0.5, 0.0), Vec3::Y).unwrap().perspective(radians(60.0), 0.1, 10.0, Viewport::new(W, H).unwrap()).unwrap();
        let mut r = Renderer::new(&CUBE, &cube_xf, RenderOptions::default()).unwrap();
        r.draw(&mut frame).unwrap();
        debug::exit(debug::EXIT_SUCCESS);
    }
    let (mesh, xf, opts) = (scene::mesh(), scene::transform(), scene::options());

    // The assembly fill loop against its portable twin, at every alignment and length
    // up to 680 (every remainder after several turns of the main loops; bench/mcu.sh
    // fails unless none differ).
    let bad = zraster::check_fill_kernel(&mut depth[..720], 680);
    hprintln!("fill kernel cases differing from the portable twin: {}", bad);
    // The assembly span loop likewise: every length up to 64 (every entry point of the
    // M0+ loop, every remainder of the M4 one) at every relative alignment.
    let bad = zraster::check_span_kernel(&mut depth[..512], 64);
    hprintln!("span kernel cases differing from the portable twin: {}", bad);
    // The rows of small triangles likewise (random rows of every length, both halves).
    let bad = zraster::check_rows_kernel(&mut depth[..4096]);
    hprintln!("rows kernel cases differing from the portable twin: {}", bad);
    let bad = zraster::check_rows_walk_kernel(&mut depth[..4096]);
    hprintln!("rows walk kernel cases differing from the portable twin: {}", bad);
    // The assembly cull scan likewise: random runs of faces over random caches.
    let bad = zraster::check_cull_kernel(20_000);
    hprintln!("cull kernel cases differing from the portable twin: {}", bad);
    // The cull scan binning a banded frame's faces likewise.
    let bad = zraster::check_bin_kernel(&mut depth[..1200], 20_000);
    hprintln!("bin kernel cases differing from the portable twin: {}", bad);
    // The fused face loop (scan, colour, set-up and rows) likewise: random meshes.
    let bad = zraster::check_faces_kernel(&mut depth[..4096], 4_000);
    hprintln!("faces kernel cases differing from the portable twin: {}", bad);
    // The fused band loop (merge, carry, colour, set-up and rows) likewise: random bins.
    let bad = zraster::check_band_faces_kernel(&mut depth[..4096], 4_000);
    hprintln!("band faces kernel cases differing from the portable twin: {}", bad);
    // And with the set-ups of faces reaching the band below kept and resumed there.
    let bad = zraster::check_band_carry_kernel(&mut depth[..4096], carry_band(), 4_000);
    hprintln!("band carry kernel cases differing from the portable twin: {}", bad);
    check_faces_v6m(&mut depth[..4096]);
    check_light();
    check_place();
    check_place_v6m();

    // ---- bunny-320, full frame.
    let mut frame = Frame::new(&mut pixels[..], &mut depth[..], W, H).unwrap();
    let (_, clear) = measure(|| frame.clear(Rgb565::BLACK));
    let (renderer, transform) = measure(|| Renderer::with_cache(&mesh, &xf, opts, cache).unwrap());
    let mut renderer = renderer;
    let (_, draw) = measure(|| renderer.draw(&mut frame).unwrap());
    let stats = renderer.stats();
    if cfg!(feature = "only-full") {
        // For profiling the full-frame path alone (see bench/README.md).
        debug::exit(debug::EXIT_SUCCESS);
    }
    let sum = checksum(frame.color().as_slice());
    // Culling alone: the same draw into a one-row band that no triangle reaches (the
    // first draw of a renderer culls every triangle before it looks at rows; setup
    // happens only for triangles inside the band, so it counts with the raster).
    let (mut setup_only, _) = measure(|| Renderer::with_cache(&mesh, &xf, opts, cache).unwrap());
    let mut row = [0u16; W as usize];
    let zrow = ZBuffer::new_band(&mut row, W, 1, -1000).unwrap();
    let mut culling = Frame::from_buffers(frame.into_parts().0, zrow);
    let (_, setup) = measure(|| setup_only.draw(&mut culling).unwrap());
    hprintln!("bunny-320 full: clear {} transform {} cull {} setup+raster+output {} total {}",
        clear, transform, setup, draw - setup, clear + transform + draw);
    hprintln!("bunny-320 stats: drawn {} written {} runs {} checksum {:08x}", stats.drawn, stats.pixels_written, stats.runs, sum);

    // ---- bunny-320, banded (16 rows): colour and depth band, flushed to the frame.
    let mut frame = ColorBuffer::new(&mut pixels[..], W, H).unwrap();
    let (band_pixels, _) = pixels_band();
    let bins = bins_band();
    let (_, banded) = measure(|| {
        let mut renderer = Renderer::with_cache(&mesh, &xf, opts, cache).unwrap();
        let mut bands = BandBuffers::new(&mut band_pixels[..], &mut depth[..(W * BAND) as usize], W, BAND, H, &mut bins[..]).unwrap().with_carry(carry_band());
        renderer.draw(&mut Bands::new(&mut frame, &mut bands, Rgb565::BLACK)).unwrap();
    });
    // The same into a display that takes the bands and does nothing with them: the
    // whole-frame figure has no transfer in it either, so this is the like-for-like one.
    let (_, banded_sink) = measure(|| {
        let mut renderer = Renderer::with_cache(&mesh, &xf, opts, cache).unwrap();
        let mut bands = BandBuffers::new(&mut band_pixels[..], &mut depth[..(W * BAND) as usize], W, BAND, H, &mut bins[..]).unwrap().with_carry(carry_band());
        renderer.draw(&mut Bands::new(&mut Sink, &mut bands, Rgb565::BLACK)).unwrap();
    });
    let banded_sum = checksum(frame.as_slice());
    hprintln!("bunny-320 banded-16: total {} checksum {:08x} (same picture: {})", banded, banded_sum, banded_sum == sum);
    hprintln!("bunny-320 banded-16 without the copy to the frame: total {}", banded_sink);
    if cfg!(feature = "only-banded") {
        // For profiling the banded path: subtract an `only-full` profile.
        debug::exit(debug::EXIT_SUCCESS);
    }

    // ---- Fill-bound: the seeds' cube close up, covering the whole screen.

    let mut frame = Frame::new(&mut pixels[..], &mut depth[..], W, H).unwrap();
    frame.clear(Rgb565::BLACK);
    let cube_xf = Camera::look_at(Vec3::new(0.5, 0.5, 1.3), Vec3::new(0.5, 0.5, 0.0), Vec3::Y).unwrap().perspective(radians(60.0), 0.1, 10.0, Viewport::new(W, H).unwrap()).unwrap();
    let mut r = Renderer::new(&CUBE, &cube_xf, RenderOptions::default()).unwrap();
    let (_, fill) = measure(|| r.draw(&mut frame).unwrap());
    let written = r.stats().pixels_written.max(1) as u32; // one frame: far below 2³²
    hprintln!("fill-bound cube: {} instructions, {} pixels written, {}.{:02} per pixel",
        fill, written, fill / written, (fill % written) * 100 / written);

    // ---- Memory.
    // SAFETY: linker symbols.
    let (sdata, ebss) = (addr_of!(__sdata) as usize, addr_of!(__ebss) as usize);
    hprintln!("static RAM {} bytes (frame {} + depth {} + vertex cache {}); stack high-water {} bytes",
        ebss - sdata, N * 2, N * 2, core::mem::size_of::<CachedVertex>() * bunny::BUNNY_POSITIONS.len(), stack_high_water());
    debug::exit(debug::EXIT_SUCCESS);
    loop {}
}

static mut BAND_PIXELS: [Rgb565; (W * BAND) as usize] = [Rgb565::BLACK; (W * BAND) as usize];
const BINS: usize = BandBuffers::<Rgb565>::bins_needed(bunny::BUNNY_INDICES.len(), H, BAND);
static mut BINS_BAND: [u16; BINS] = [0; BINS];
/// The set-ups of triangles reaching into the next band, kept for it (64 a band edge;
/// bunny-320 has at most 51).
const CARRY: usize = BandBuffers::<Rgb565>::carry_needed(64);
static mut CARRY_BAND: [u32; CARRY] = [0; CARRY];

fn bins_band() -> &'static mut [u16] {
    // SAFETY: borrowed once.
    unsafe { &mut *addr_of_mut!(BINS_BAND) }
}

fn carry_band() -> &'static mut [u32] {
    // SAFETY: borrowed once at a time (by the band check, then by the banded frames).
    unsafe { &mut *addr_of_mut!(CARRY_BAND) }
}

fn pixels_band() -> (&'static mut [Rgb565], ()) {
    // SAFETY: borrowed once.
    (unsafe { &mut *addr_of_mut!(BAND_PIXELS) }, ())
}

/// The ARMv6-M fused face and band loops (scan or merge and carry, colour, set-up and
/// rows) against their twins (random meshes and bins; bench/mcu.sh fails unless none
/// differ; 0 where there are no such loops). Out of line, as `check_place`.
#[inline(never)]
fn check_faces_v6m(buf: &mut [u16]) {
    let bad = zraster::check_faces_v6m_kernel(buf, 4_000);
    hprintln!("faces v6m kernel cases differing from the portable twin: {}", bad);
    let bad = zraster::check_band_faces_v6m_kernel(buf, 4_000);
    hprintln!("band faces v6m kernel cases differing from the portable twin: {}", bad);
    // And with the walks of faces reaching the band below kept and resumed there.
    let bad = zraster::check_band_carry_v6m_kernel(buf, carry_band(), 4_000);
    hprintln!("band carry v6m kernel cases differing from the portable twin: {}", bad);
}

/// The lit face colour against its portable twin (random normals, lights and
/// materials; bench/mcu.sh fails unless none differ). Out of line, as `check_place`.
#[inline(never)]
fn check_light() {
    let bad = zraster::check_light_kernel(20_000);
    hprintln!("light kernel cases differing from the portable twin: {}", bad);
}

/// The assembly vertex loop against its portable twin (random transforms and
/// positions; bench/mcu.sh fails unless none differ). Out of line: main's frame stays
/// as it was.
#[inline(never)]
fn check_place() {
    let bad = zraster::check_place_kernel(800);
    hprintln!("place kernel cases differing from the portable twin: {}", bad);
}

/// The ARMv6-M vertex loop against its portable twin (random transforms and
/// positions; bench/mcu.sh fails unless none differ; 0 where there is no such loop).
/// Out of line, as `check_place`.
#[inline(never)]
fn check_place_v6m() {
    let bad = zraster::check_place_v6m_kernel(800);
    hprintln!("place v6m kernel cases differing from the portable twin: {}", bad);
}
