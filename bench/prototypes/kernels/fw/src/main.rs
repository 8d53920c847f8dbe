//! The zkern kernels on Cortex-M under QEMU: first a check that every asm kernel gives
//! its portable twin's results on random inputs (lengths 0..=64, all alignments, with
//! unaligned word accesses trapping), then instruction counts of each variant.
//!
//! Run: `cargo run --release` (M4F) or `cargo run --release --target thumbv6m-none-eabi`;
//! exact counts per region: `REGIONCOUNT=1 /work/shared/tools/qemu-m4/run.sh <elf>`.
#![no_std]
#![no_main]

use core::ptr::{addr_of_mut, read_volatile, write_volatile};

use cortex_m_rt::{entry, exception, ExceptionFrame};
use cortex_m_semihosting::{debug, hprintln};
use panic_semihosting as _;
use zkern::{fill, span};

const W: usize = 320;
const H: usize = 240;
const N: usize = W * H;

static mut A: [u16; N] = [0; N];
static mut B: [u16; N] = [0; N];

core::arch::global_asm!(
    ".global bench_start", ".type bench_start,%function", ".thumb_func", "bench_start:", "bx lr",
    ".global bench_stop", ".type bench_stop,%function", ".thumb_func", "bench_stop:", "bx lr",
);
extern "C" {
    fn bench_start();
    fn bench_stop();
}

const TIMER_CTRL: *mut u32 = 0x4000_0000 as *mut u32;
const TIMER_VALUE: *mut u32 = 0x4000_0004 as *mut u32;
const TIMER_RELOAD: *mut u32 = 0x4000_0008 as *mut u32;
const SCB_CCR: *mut u32 = 0xE000_ED14 as *mut u32;

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

/// Unaligned word accesses fault (CCR.UNALIGN_TRP), as on an ARMv6-M part.
fn unaligned_trap(on: bool) {
    // SAFETY: the System Control Block's configuration register.
    unsafe {
        let v = read_volatile(SCB_CCR);
        write_volatile(SCB_CCR, if on { v | 1 << 3 } else { v & !(1 << 3) });
    }
}

static mut REGION: u32 = 0;

/// Instructions spent in `f` (±40, by the timer), marked for the region-count plugin,
/// printed with the region number and `label`.
fn measure(label: &str, pixels: u32, f: impl FnOnce()) {
    let t0 = ticks();
    // SAFETY: empty assembly functions.
    unsafe { bench_start() };
    f();
    unsafe { bench_stop() };
    let t1 = ticks();
    let insns = t0.wrapping_sub(t1) * 40;
    // SAFETY: single-threaded.
    let r = unsafe {
        let p = addr_of_mut!(REGION);
        *p += 1;
        *p
    };
    let per100 = (insns as u64 * 100 / pixels.max(1) as u64) as u32;
    hprintln!("region {}: {} | px={} | timer ~{} (~{}.{:02} a pixel)", r, label, pixels, insns, per100 / 100, per100 % 100);
}

fn xorshift(mut s: u32) -> impl FnMut() -> u32 {
    move || {
        s ^= s << 13;
        s ^= s >> 17;
        s ^= s << 5;
        s
    }
}

#[exception]
unsafe fn HardFault(ef: &ExceptionFrame) -> ! {
    unaligned_trap(false);
    hprintln!("HardFault at pc {:#010x}", ef.pc());
    debug::exit(debug::EXIT_FAILURE);
    loop {}
}

/// The harness's own cost: a call that does nothing (returns 0 for equal lengths).
#[inline(never)]
fn span_noop(z: &mut [u16], c: &mut [u16], _: u32, _: u32, _: u16) -> u32 {
    (z.len() - c.len()) as u32
}

type Span = fn(&mut [u16], &mut [u16], u32, u32, u16) -> u32;
type SpanNc = fn(&mut [u16], &mut [u16], u32, u32, u16);

/// Random checks: each asm kernel against its portable twin, guards around the slices
/// untouched. Returns the number of cases.
fn check(a: &mut [u16], b: &mut [u16]) -> u32 {
    let mut rnd = xorshift(0x2545_f491);
    let mut cases = 0;
    let (a, b) = (&mut a[..200], &mut b[..200]);
    let (mut a2, mut b2) = ([0u16; 200], [0u16; 200]);
    for round in 0..6 {
        for len in 0..=64usize {
            for zo in 0..4 {
                for co in 0..4 {
                    for i in 0..200 {
                        a[i] = rnd() as u16;
                        b[i] = rnd() as u16;
                    }
                    if round == 4 {
                        // Depths around the ramp: a mix of passes and failures.
                        for x in a.iter_mut() {
                            *x = 0x4000 + (rnd() as u16 & 0x7fff);
                        }
                    }
                    a2.copy_from_slice(a);
                    b2.copy_from_slice(b);
                    let acc = match round {
                        0 => rnd() >> 2,
                        1 => 0,
                        2 => u32::MAX - 3,
                        4 => 0x4000_0000,
                        _ => rnd(),
                    };
                    let dz = match round {
                        4 => 0x8000_0000 / 64,
                        r if r % 2 == 0 => rnd() >> 12,
                        _ => rnd(),
                    };
                    let col = rnd() as u16;
                    let (z, c) = (&mut a[zo..zo + len], &mut b[co..co + len]);
                    let (z2, c2) = (&mut a2[zo..zo + len], &mut b2[co..co + len]);
                    let kernels: [(Span, Span); 1] = [(span::span_flat, span::span_portable)];
                    match cases % 4 {
                        0 => {
                            let (k, t) = kernels[0];
                            let (r1, r2) = (k(z, c, acc, dz, col), t(z2, c2, acc, dz, col));
                            assert!(r1 == r2, "span_flat failures {} {} len {} zo {} co {}", r1, r2, len, zo, co);
                        }
                        1 => {
                            span::span_flat_nocount(z, c, acc, dz, col);
                            span::span_portable(z2, c2, acc, dz, col);
                        }
                        2 => {
                            span::span_depth(z, acc, dz);
                            span::span_depth_portable(z2, acc, dz);
                        }
                        _ => {
                            let v = rnd() as u16;
                            fill::fill_u16(z, v);
                            fill::fill_u16_portable(z2, v);
                            fill::fill_u16(c, v ^ 0x5555);
                            fill::fill_u16_portable(c2, v ^ 0x5555);
                        }
                    }
                    assert!(a[..] == a2[..] && b[..] == b2[..], "mismatch: case {} len {} zo {} co {}", cases % 4, len, zo, co);
                    cases += 1;
                }
            }
        }
    }
    cases
}

/// Long fills: every start alignment, lengths 0..600 and near the whole buffer; the
/// halfwords around the slice keep their values.
fn check_long_fill(la: &mut [u16]) -> u32 {
    let mut rnd = xorshift(0x0bad_cafe);
    let mut cases = 0;
    for len in (0..600).chain(N - 3..=N - 1) {
        for off in 0..2 {
            let n = len.min(N - off);
            let v = rnd() as u16;
            let span = if n < 600 { 700 } else { N };
            for x in la[..span].iter_mut() {
                *x = !v;
            }
            fill::fill_u16(&mut la[off..off + n], v);
            let ok = la[..off].iter().all(|&x| x == !v)
                && la[off..off + n].iter().all(|&x| x == v)
                && la[off + n..span].iter().all(|&x| x == !v);
            assert!(ok, "fill len {} off {}", n, off);
            cases += 1;
        }
    }
    cases
}

#[entry]
fn main() -> ! {
    timer_start();
    if cfg!(feature = "trap-test") {
        unaligned_trap(true);
        let w = [0u32; 2];
        let p = (w.as_ptr() as usize + 2) as *const u32;
        // SAFETY: deliberately unaligned; must fault with UNALIGN_TRP set.
        let v = unsafe { read_volatile(p) };
        hprintln!("no fault: unaligned read gave {}", v);
        debug::exit(debug::EXIT_FAILURE);
    }

    // SAFETY: single-threaded; each static borrowed once.
    let (a, b) = unsafe { (&mut *addr_of_mut!(A), &mut *addr_of_mut!(B)) };

    // ---- Checks (outside any region), unaligned word accesses trapping.
    unaligned_trap(true);
    let cases = check(a, b) + check_long_fill(a);
    unaligned_trap(false);
    hprintln!("check: {} random cases, asm kernels == portable twins", cases);

    // ---- Fill: 76,800 pixels (a 320×240 buffer), starting word-aligned.
    let fills: [(&str, fn(&mut [u16], u16)); 7] = [
        ("fill_u16 (asm)", fill::fill_u16),
        ("buf.fill", fill::fill_u16_portable),
        ("pairs", fill::fill_pairs),
        ("chunks16", fill::fill_chunks16),
        ("u32 align_to", fill::fill_u32),
        ("u64 align_to", fill::fill_u64),
        ("[u32;8] align_to", fill::fill_u32x8),
    ];
    for (name, f) in fills {
        for v in [0x0000u16, 0xffff, 0x1234] {
            let mut label = Label::new();
            label.push(name);
            label.push(" value ");
            label.hex(v);
            measure(label.as_str(), N as u32, || f(&mut a[..], v));
        }
    }
    measure("buf.fill(0) with the constant in view (memset)", N as u32, || a.fill(0));
    measure("buf.fill(0xffff) with the constant in view (memset)", N as u32, || a.fill(0xffff));
    measure("buf.fill(0x1234) with the constant in view", N as u32, || a.fill(0x1234));
    measure("the frame clear today: a.fill(0); b.fill(0xffff) (2 x 76,800 px)", 2 * N as u32, || {
        a.fill(0);
        b.fill(0xffff);
    });
    measure("the same by fill_u16 (asm) (2 x 76,800 px)", 2 * N as u32, || {
        fill::fill_u16(&mut a[..], 0);
        fill::fill_u16(&mut b[..], 0xffff);
    });

    // ---- Span: 200 rows of 200 pixels (40,000) in a 320-wide buffer pair.
    let spans: [(&str, Span); 7] = [
        ("baseline: harness calling an empty fn", span_noop),
        ("span_flat (asm, counts)", span::span_flat),
        ("span_portable (zip)", span::span_portable),
        ("span_x2_project", span::span_x2_project),
        ("span_x2_inline", span::span_x2_inline),
        ("span_select", span::span_select),
        ("span_index", span::span_index),
    ];
    let spans_nc: [(&str, SpanNc); 5] = [
        ("span_flat_nocount (asm)", span::span_flat_nocount),
        ("span_zip_nocount", span::span_zip_nocount),
        ("span_x4_nocount", span::span_x4_nocount),
        ("span_swar_nocount", span::span_swar_nocount),
        ("span_portable, count dropped", |z, c, acc, dz, col| {
            span::span_portable(z, c, acc, dz, col);
        }),
    ];
    const ROWS: usize = 200;
    const LEN: usize = 200;
    let dz = 0x8000_0000u32 / LEN as u32; // the ramp crosses half the depth range in a row
    let acc0 = 0x4000_0000u32;
    // Depths for each case: all pass (cleared), half fail (0x8000, met at the row's middle:
    // first half passes, second fails), random (each pixel passes with p = 1/2).
    let prepare = |a: &mut [u16], b: &mut [u16], case: u32| {
        let mut seed = xorshift(0x1234_5678);
        for y in 0..ROWS {
            for x in 0..LEN {
                a[y * W + x] = match case {
                    0 => 0xffff,
                    1 => 0x8000,
                    _ => {
                        // pass iff d < z, d = (acc0 + x·dz) >> 16
                        let d = ((acc0 + x as u32 * dz) >> 16) as u16;
                        if seed() & 1 == 0 { d.saturating_add(1 + (seed() as u16 & 0xff)) } else { d.saturating_sub(seed() as u16 & 0xff) }
                    }
                };
                b[y * W + x] = 0;
            }
        }
    };
    let cases = ["all pass", "half fail (ramp)", "half fail (random)"];
    let mut written_check = [0u32; 3];
    for (ci, case) in cases.iter().enumerate() {
        for (name, f) in spans {
            prepare(a, b, ci as u32);
            let mut fails = 0u32;
            let mut label = Label::new();
            label.push(name);
            label.push(", ");
            label.push(case);
            measure(label.as_str(), (ROWS * LEN) as u32, || {
                for y in 0..ROWS {
                    let s = y * W;
                    fails += f(&mut a[s..s + LEN], &mut b[s..s + LEN], acc0, dz, 0xf81f);
                }
            });
            if name.starts_with("baseline") {
                continue;
            }
            if written_check[ci] == 0 {
                written_check[ci] = fails + 1;
            }
            assert!(written_check[ci] == fails + 1, "failures differ");
        }
        hprintln!("  ({}: {} of {} written)", case, (ROWS * LEN) as u32 + 1 - written_check[ci], ROWS * LEN);
        for (name, f) in spans_nc {
            prepare(a, b, ci as u32);
            let mut label = Label::new();
            label.push(name);
            label.push(", ");
            label.push(case);
            measure(label.as_str(), (ROWS * LEN) as u32, || {
                for y in 0..ROWS {
                    let s = y * W;
                    f(&mut a[s..s + LEN], &mut b[s..s + LEN], acc0, dz, 0xf81f);
                }
            });
        }
        for (name, f) in [("span_depth (asm)", span::span_depth as fn(&mut [u16], u32, u32)), ("span_depth_portable", span::span_depth_portable)] {
            prepare(a, b, ci as u32);
            let mut label = Label::new();
            label.push(name);
            label.push(", ");
            label.push(case);
            measure(label.as_str(), (ROWS * LEN) as u32, || {
                for y in 0..ROWS {
                    let s = y * W;
                    f(&mut a[s..s + LEN], acc0, dz);
                }
            });
        }
    }

    // ---- Short spans: lengths 1..=16 in turn, 2,000 spans (17,000 pixels), all pass.
    for (name, f) in spans {
        prepare(a, b, 0);
        let mut label = Label::new();
        label.push(name);
        label.push(", short spans 1..=16");
        measure(label.as_str(), 17_000, || {
            for k in 0..2000usize {
                let len = 1 + k % 16;
                let s = (k % 200) * W + (k / 200) * 16;
                f(&mut a[s..s + len], &mut b[s..s + len], acc0, dz, 0xf81f);
            }
        });
    }
    debug::exit(debug::EXIT_SUCCESS);
    loop {}
}

/// A small fixed-capacity string for labels.
struct Label {
    buf: [u8; 96],
    len: usize,
}

impl Label {
    fn new() -> Self {
        Label { buf: [0; 96], len: 0 }
    }
    fn push(&mut self, s: &str) {
        for &c in s.as_bytes() {
            if self.len < self.buf.len() {
                self.buf[self.len] = c;
                self.len += 1;
            }
        }
    }
    fn hex(&mut self, v: u16) {
        self.push("0x");
        for k in (0..4).rev() {
            let d = (v >> (4 * k)) & 0xf;
            let c = if d < 10 { b'0' + d as u8 } else { b'a' + d as u8 - 10 };
            if self.len < self.buf.len() {
                self.buf[self.len] = c;
                self.len += 1;
            }
        }
    }
    fn as_str(&self) -> &str {
        core::str::from_utf8(&self.buf[..self.len]).unwrap_or("?")
    }
}
