//! A face's flat Lambert colour in RGB565 (or BGR565) from its Q14 normal: one
//! assembly block on ARMv7E-M, beside its portable twin (the renderer's
//! `lambert_q14` and `shade::lit_rgb`, with the same roundings).
#![allow(unsafe_code)]

use core::marker::PhantomData;

/// Half of the channel divisor `255 · 2¹⁵` (the rounding of `shade::rounded_channel`).
const HALF: u32 = 255 * 32768 / 2;
/// ⌈2³⁹ / 255⌉: `⌊x / (255 · 2¹⁵)⌋ = (x · MUL) >> 54` for every `u32` (`shade::div_den`).
const MUL: u32 = ((1u64 << 39) / 255 + 1) as u32;

/// What [`lit_565`] reads, in the order its assembly loads it: the light direction
/// (Q15), ambient (Q15) and diffuse weight (Q15 · 8, Q15 on ARMv6-M: see
/// `render::lambert_term`) of the renderer, the channel
/// constants, each 8-bit channel of the material times its depth (31, 63, 31) in the
/// packing's order from the high field down, and the face normals (Q14).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub(crate) struct LightBlock<'n> {
    pub(super) light: [i32; 3],
    pub(super) ambient: i32,
    pub(super) diffuse: i32,
    pub(super) half: u32,
    mul: u32,
    pub(super) channels: [u32; 3],
    /// The normals, `count` of them (the slice's parts, at known offsets).
    normals: *const [i16; 3],
    count: usize,
    life: PhantomData<&'n [[i16; 3]]>,
}

// The assembly reads the block at these offsets (`count` at 44 on 32-bit targets).
const _: () = {
    assert!(core::mem::offset_of!(LightBlock, ambient) == 12);
    assert!(core::mem::offset_of!(LightBlock, half) == 20);
    assert!(core::mem::offset_of!(LightBlock, channels) == 28);
    assert!(core::mem::offset_of!(LightBlock, normals) == 40);
    assert!(core::mem::offset_of!(LightBlock, count) == 40 + core::mem::size_of::<usize>());
    assert!(core::mem::size_of::<[i16; 3]>() == 6);
};

impl<'n> LightBlock<'n> {
    /// The block of light `light`, `ambient`, `diffuse` (as the renderer keeps them:
    /// ambient within ±2¹⁶, diffuse within ±2¹⁹), a material of 8-bit channels
    /// `[high, middle, low]` (the 5-, 6- and 5-bit fields, high to low) and the face
    /// normals `normals`.
    pub(crate) fn new(
        light: [i32; 3],
        ambient: i32,
        diffuse: i32,
        [h, m, l]: [u8; 3],
        normals: &'n [[i16; 3]],
    ) -> Self {
        LightBlock {
            light,
            ambient,
            diffuse,
            half: HALF,
            mul: MUL,
            channels: [u32::from(h) * 31, u32::from(m) * 63, u32::from(l) * 31],
            normals: normals.as_ptr(),
            count: normals.len(),
            life: PhantomData,
        }
    }

    /// The light, ambient and diffuse (for the x86-64 face loop, `faces_x86`).
    #[cfg_attr(not(zraster_x86_64), allow(dead_code))]
    pub(super) fn light_parts(&self) -> ([i32; 3], i32, i32) {
        (self.light, self.ambient, self.diffuse)
    }

    /// Each channel's `v · max · MUL` and `HALF · MUL`: a channel is then
    /// `(i · v·max·MUL + HALF·MUL) >> 54`, the same product as [`lit_565_portable`]'s
    /// (for the x86-64 face loop, `faces_x86`).
    #[cfg_attr(not(zraster_x86_64), allow(dead_code))]
    pub(super) fn wide_channels(&self) -> ([u64; 3], u64) {
        let mul = u64::from(self.mul);
        (
            self.channels.map(|v| u64::from(v) * mul),
            u64::from(self.half) * mul,
        )
    }

    /// The normals.
    pub(super) fn normals(&self) -> &'n [[i16; 3]] {
        // SAFETY: the parts of a slice borrowed for 'n (see `new`).
        unsafe { core::slice::from_raw_parts(self.normals, self.count) }
    }
}

/// The template of [`lit_565`]: the block's address in r0, the face in r1; the colour
/// in r0 (65536 when the block has no normal r1). Clobbers r1–r5, r12 and the flags.
/// Also the colour of the fused face loop (`faces`).
#[cfg(all(zraster_thumb, zraster_dsp))]
#[rustfmt::skip]
macro_rules! lit_565_asm {
    () => {
        concat!(
            "ldrd r2, r3, [r0, #40]\n",
            "cmp r1, r3\n",
            "blo 2f\n",
            // No normal f: past any colour.
            "mov.w r0, #65536\n",
            "b 3f\n",
            "2:\n",
            "add r2, r2, r1, lsl #1\n",
            "add r1, r2, r1, lsl #2\n",
            "ldrsh r2, [r1]\n",
            "ldrsh r3, [r1, #2]\n",
            "ldrsh r1, [r1, #4]\n",
            // n·L; max(0, n·L), then ambient + the rounded high word of dot · diffuse.
            "ldm r0!, {{r4, r5, r12}}\n",
            "mul r2, r2, r4\n",
            "mla r2, r3, r5, r2\n",
            "mla r2, r1, r12, r2\n",
            "bic r2, r2, r2, asr #31\n",
            "ldm r0!, {{r3, r4, r5, r12}}\n",
            "smmlar r2, r2, r4, r3\n",
            "usat r2, #16, r2\n",
            // The channels, high to low: (i · v·max + half) · mul >> 54, saturated.
            "ldm r0, {{r0, r1, r3}}\n",
            "mla r0, r2, r0, r5\n",
            "umull r4, r0, r0, r12\n",
            "usat r0, #5, r0, asr #22\n",
            "mla r1, r2, r1, r5\n",
            "umull r4, r1, r1, r12\n",
            "usat r1, #6, r1, asr #22\n",
            "orr r0, r1, r0, lsl #6\n",
            "mla r3, r2, r3, r5\n",
            "umull r4, r3, r3, r12\n",
            "usat r3, #5, r3, asr #22\n",
            "orr r0, r3, r0, lsl #5\n",
            "3:\n",
        )
    };
}

/// The packed 5-6-5 colour of face `f` lit by `b`, from its Q14 normal `n`: the
/// intensity `clamp(ambient + ⌊(max(0, n·L) · diffuse + 2³¹) / 2³²⌋, 0, 2¹⁶ − 1)`, then
/// each channel `min(⌊(v · max · i + 255 · 2¹⁴) / (255 · 2¹⁵)⌋, max)`; `None` when the
/// block has no normal `f`. On ARMv7E-M one assembly block (the bounds and the normal's
/// place, then 24 instructions: three LDM of the block, MUL/MLA, SMMLAR, USAT, and each
/// channel MLA, UMULL, USAT); elsewhere [`lit_565_portable`].
#[inline(always)]
pub(crate) fn lit_565(f: usize, b: &LightBlock<'_>) -> Option<u16> {
    #[cfg(all(zraster_thumb, zraster_dsp))]
    {
        let c: u32;
        // SAFETY: reads the twelve words of `b` (offsets pinned above) and, when
        // `f < count`, the three halfwords of normal `f` inside the slice the block
        // borrows; writes only the registers named, no memory and not the stack. CMP
        // sets the flags (not declared preserved); MLA, UMULL and SMMLAR do not; USAT
        // may set the sticky Q flag, which nothing in the crate reads. The registers are
        // fixed so that the block's words come in by LDM (in ascending order).
        unsafe {
            core::arch::asm!(
                lit_565_asm!(),
                inout("r0") b as *const LightBlock => c,
                inout("r1") f => _,
                out("r2") _,
                out("r3") _,
                out("r4") _,
                out("r5") _,
                out("r12") _,
                options(pure, readonly, nostack),
            );
        }
        return (c <= u32::from(u16::MAX)).then_some(c as u16);
    }
    #[allow(unreachable_code)]
    lit_565_portable(f, b)
}

/// The portable twin of [`lit_565`].
#[inline(always)]
pub(crate) fn lit_565_portable(f: usize, b: &LightBlock<'_>) -> Option<u16> {
    let n = b.normals().get(f)?;
    let [lx, ly, lz] = b.light;
    let dot = (i32::from(n[0]).wrapping_mul(lx))
        .wrapping_add(i32::from(n[1]).wrapping_mul(ly))
        .wrapping_add(i32::from(n[2]).wrapping_mul(lz));
    let term = crate::render::lambert_term(dot.max(0), b.diffuse);
    let i = (b.ambient + term).clamp(0, i32::from(u16::MAX)) as u32;
    let channel = |v: u32, max: u32| {
        // i · v·max + half < 2³⁰: ⌊x / (255 · 2¹⁵)⌋ by `mul` where there is a 32 × 32 →
        // 64-bit product, else ⌊(x >> 15) / 255⌋ by ⌈2²³ / 255⌉ (exact below 66,299).
        let x = i * v + b.half;
        let q = if crate::num::ARMV6M {
            ((x >> 15) * 32_897) >> 23
        } else {
            ((u64::from(x) * u64::from(b.mul)) >> 54) as u32
        };
        q.min(max)
    };
    let [h, m, l] = b.channels;
    Some((channel(h, 31) << 11 | channel(m, 63) << 5 | channel(l, 31)) as u16)
}

/// `lit_565` and the ARMv6-M loops' colour code against their portable twin on this
/// target: in each of `n` cases up to three random normals, asked for faces 0 to 3 and
/// one far past them; every material's extremes and random ones; lights of every
/// strength within the renderer's ranges; then every intensity (and past both ends)
/// for four materials and both of the ARMv6-M colour code's forms. Returns the number
/// of cases that differ.
pub fn check_light_kernel(n: usize) -> usize {
    let mut rnd = super::xorshift32(0x1d87_2b41_u32);
    let mut bad = 0;
    for case in 0..n {
        let mut r = || rnd();
        // Normals and a light of Q14 / Q15 components, whose dot products stay in i32.
        let normals = [[0i16; 3]; 3].map(|n| n.map(|_| ((r() % 32769) as i32 - 16384) as i16));
        let light = [0; 3].map(|_| (r() % 65537) as i32 - 32768);
        let ambient = (r() % 131_073) as i32 - 65536;
        let diffuse = ((r() % 131_073) as i32 - 65536) << if crate::num::ARMV6M { 0 } else { 3 };
        let extremes = [0u8, 1, 127, 128, 254, 255];
        let channels = if case % 4 == 0 {
            [0; 3].map(|_| extremes.get(r() as usize % 6).copied().unwrap_or(0))
        } else {
            [0; 3].map(|_| r() as u8)
        };
        let count = r() as usize % 4;
        let b = LightBlock::new(
            light,
            ambient,
            diffuse,
            channels,
            normals.get(..count).unwrap_or(&[]),
        );
        for f in [0, 1, 2, 3, usize::MAX] {
            let want = lit_565_portable(f, &b);
            if lit_565(f, &b) != want || super::faces_v6m::lit_565_v6m(f, &b) != want {
                bad += 1;
            }
        }
    }
    // Every intensity (a zero normal: the ambient alone) and beyond both ends, for
    // materials of extreme channels and a spread one, with a diffuse weight of each
    // of the ARMv6-M loops' two forms.
    let normals = [[0i16; 3]];
    let materials = [
        [255, 255, 255],
        [0, 1, 128],
        [254, 127, 255],
        [200, 100, 50],
    ];
    for (channels, diffuse) in materials.into_iter().flat_map(|m| [(m, 0), (m, 1 << 15)]) {
        for ambient in -2..=65538 {
            let b = LightBlock::new([0; 3], ambient, diffuse, channels, &normals);
            let want = lit_565_portable(0, &b);
            if lit_565(0, &b) != want || super::faces_v6m::lit_565_v6m(0, &b) != want {
                bad += 1;
            }
        }
    }
    bad
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_light_kernel_is_its_twin() {
        assert_eq!(check_light_kernel(100_000), 0);
    }
}
