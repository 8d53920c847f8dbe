//! zraster on a Raspberry Pi Pico (RP2040, Cortex-M0+) driving a 240×240 ST7789 over
//! SPI, as on Waveshare's Pico-LCD-1.3: a cube and the Stanford bunny, turning,
//! Lambert-lit, drawn band by band (8 rows at a time) into 7.5 KiB of band buffers.
//!
//! Pins (Pico-LCD-1.3): SPI1 SCK GP10, MOSI GP11, CS GP9, DC GP8, RST GP12, backlight
//! GP13. Build: `cargo build --release` in this folder; flash the ELF with a probe
//! (`probe-rs run --chip RP2040 …`) or convert it to UF2 (`elf2uf2-rs`).
//!
//! RAM: band colour and depth 240 × 8 × (2 + 2) = 7,680 B, vertex caches (1839 + 8) ×
//! 8 = 14,776 B, bins 3,796 × 2 = 7,592 B (the cube uses the front of the bunny's);
//! the bunny's tables stay in flash. Both meshes are triangle lists with a vertex cache,
//! so every band draw bins its triangles: the state `Binned<LambertLess>` leaves the
//! unbinned path out of the firmware. With zraster's
//! `ram-code` feature its innermost pixel loops (about 1.2 KB) run from RAM, out of the
//! way of the 16 KiB flash cache. 8-row bands rather than 16 save 7.7 KB of RAM for
//! about 8 % more instructions a frame (bunny-320 on the M0+ under QEMU: 5,824,920
//! against 5,415,520).
#![no_std]
#![no_main]

use core::ptr::addr_of_mut;

use embedded_graphics::{pixelcolor::Rgb565, pixelcolor::Rgb888, prelude::*};
use embedded_hal::digital::OutputPin;
use embedded_hal_bus::spi::ExclusiveDevice;
use fugit::RateExtU32;
use mipidsi::{interface::SpiInterface, models::ST7789, options::ColorInversion, Builder};
use panic_halt as _;
use rp2040_hal::{self as hal, clocks::{init_clocks_and_plls, Clock}, gpio::FunctionSpi, pac, Sio, Spi, Timer, Watchdog};
use zraster::{
    camera::{Camera, Viewport},
    math::{radians, Mat4, Vec3},
    mesh::{Faces, Materials, Mesh, CUBE_POSITIONS},
    shade::Shading,
    state::{Binned, LambertLess}, BandBuffers, Bands, CachedVertex, RenderOptions, Renderer,
};
use zraster_bench_scene::bunny;

/// The second-stage boot loader for the Pico's W25Q080 flash.
#[link_section = ".boot2"]
#[used]
pub static BOOT2: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

const W: u32 = 240;
const H: u32 = 240;
const ROWS: u32 = 8;
const BAND: usize = (W * ROWS) as usize;
const BINS: usize = BandBuffers::<Rgb565>::bins_needed(bunny::BUNNY_INDICES.len(), H, ROWS);

static mut BAND_COLOR: [Rgb565; BAND] = [Rgb565::BLACK; BAND];
static mut BAND_DEPTH: [u16; BAND] = [0; BAND];
static mut BINS_BUF: [u16; BINS] = [0; BINS];
static mut CACHE: [CachedVertex; bunny::BUNNY_POSITIONS.len()] = [CachedVertex::EMPTY; bunny::BUNNY_POSITIONS.len()];
static mut CUBE_CACHE: [CachedVertex; 8] = [CachedVertex::EMPTY; 8];

/// zraster's unit cube (`mesh::CUBE`) as triangles, each face fanned from its first
/// vertex as polygons are drawn, so that it bins: bottom, right, front, left, back, top.
const CUBE_TRIANGLES: [[u16; 3]; 12] = [
    [0, 1, 2], [0, 2, 3], [1, 5, 6], [1, 6, 2], [2, 6, 7], [2, 7, 3],
    [3, 7, 4], [3, 4, 0], [0, 4, 5], [0, 5, 1], [7, 6, 5], [7, 5, 4],
];
/// Its colours, one a triangle: `mesh::CUBE_FACES`' (red, green, blue, yellow, purple,
/// light blue), twice each.
const CUBE_COLORS: [Rgb888; 12] = {
    let faces = [(255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 0), (128, 0, 128), (0, 255, 255)];
    let mut c = [Rgb888::BLACK; 12];
    let mut i = 0;
    while i < 12 {
        let (r, g, b) = faces[i / 2];
        c[i] = Rgb888::new(r, g, b);
        i += 1;
    }
    c
};
const CUBE: Mesh<'static, Rgb888> = Mesh {
    faces: Faces::Triangles { indices: &CUBE_TRIANGLES, materials: Materials::PerFace(&CUBE_COLORS) },
    ..Mesh::triangles(&CUBE_POSITIONS, 1.0 / 16384.0, &CUBE_TRIANGLES, Rgb888::BLACK)
};

#[hal::entry]
fn main() -> ! {
    let mut pac = pac::Peripherals::take().unwrap();
    let mut watchdog = Watchdog::new(pac.WATCHDOG);
    let clocks = init_clocks_and_plls(
        12_000_000,
        pac.XOSC,
        pac.CLOCKS,
        pac.PLL_SYS,
        pac.PLL_USB,
        &mut pac.RESETS,
        &mut watchdog,
    )
    .ok()
    .unwrap();
    let sio = Sio::new(pac.SIO);
    let pins = hal::gpio::Pins::new(pac.IO_BANK0, pac.PADS_BANK0, sio.gpio_bank0, &mut pac.RESETS);
    let mut timer = Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);

    let sck = pins.gpio10.into_function::<FunctionSpi>();
    let mosi = pins.gpio11.into_function::<FunctionSpi>();
    let spi = Spi::<_, _, _, 8>::new(pac.SPI1, (mosi, sck)).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        62_500_000u32.Hz(),
        embedded_hal::spi::MODE_0,
    );
    let cs = pins.gpio9.into_push_pull_output();
    let dc = pins.gpio8.into_push_pull_output();
    let rst = pins.gpio12.into_push_pull_output();
    let mut backlight = pins.gpio13.into_push_pull_output();
    let device = ExclusiveDevice::new_no_delay(spi, cs).unwrap();
    let mut spi_buffer = [0u8; 512];
    let interface = SpiInterface::new(device, dc, &mut spi_buffer);
    let mut display = Builder::new(ST7789, interface)
        .display_size(W as u16, H as u16)
        .invert_colors(ColorInversion::Inverted)
        .reset_pin(rst)
        .init(&mut timer)
        .unwrap();
    backlight.set_high().unwrap();

    // SAFETY: main never returns and these statics are borrowed only here, once.
    let (band_color, band_depth, bins, cache, cube_cache) = unsafe {
        (
            &mut *addr_of_mut!(BAND_COLOR),
            &mut *addr_of_mut!(BAND_DEPTH),
            &mut *addr_of_mut!(BINS_BUF),
            &mut *addr_of_mut!(CACHE),
            &mut *addr_of_mut!(CUBE_CACHE),
        )
    };
    let mut bunny: Mesh<'static, Rgb888> = bunny::BUNNY_MESH;
    bunny.faces = Faces::Triangles {
        indices: &bunny::BUNNY_INDICES,
        materials: Materials::Uniform(Rgb888::new(255, 204, 153)),
    };
    let viewport = Viewport::new(W, H).unwrap();
    let camera = Camera::look_at(Vec3::new(0.0, 0.0, 2.2), Vec3::default(), Vec3::Y).unwrap().perspective(radians(50.0), 0.1, 10.0, viewport).unwrap();
    let options = RenderOptions { shading: Shading::Lambert, ..Default::default() };
    let mut frame = 0u32;
    loop {
        let yaw = radians((frame * 3 % 360) as f32);
        let spin = Mat4::rotation_x(radians(20.0)) * Mat4::rotation_y(yaw);
        let mut bands = BandBuffers::new(band_color, band_depth, W, ROWS, H, bins).unwrap();
        // The first half of each turn shows the cube, the second the bunny.
        if (frame / 60) % 2 == 0 {
            let xf = camera.with_model(spin * Mat4::scaling(Vec3::new(1.2, 1.2, 1.2)) * Mat4::translation(Vec3::new(-0.5, -0.5, -0.5)));
            // Lambert, `Less` and binned bands fixed at compile time: only their code is
            // linked (a draw that cannot bin is an error, not a slower path).
            let mut renderer = Renderer::with_cache(&CUBE, &xf, options, cube_cache).unwrap().with_state::<Binned<LambertLess>>().unwrap();
            renderer.draw(&mut Bands::new(&mut display, &mut bands, Rgb565::BLACK)).ok();
        } else {
            let fit = bunny::BUNNY_FIT * 1.4;
            let xf = camera.with_model(spin * Mat4::scaling(Vec3::new(fit, fit, fit)));
            let mut renderer = Renderer::with_cache(&bunny, &xf, options, cache).unwrap().with_state::<Binned<LambertLess>>().unwrap();
            renderer.draw(&mut Bands::new(&mut display, &mut bands, Rgb565::BLACK)).ok();
        }
        frame = frame.wrapping_add(1);
    }
}
