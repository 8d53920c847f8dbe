//! The depth-tested span of a flat-coloured triangle row (depth test "less", depth
//! write on): for each pixel i, d = (acc >> 16) as u16; if d < z[i] { z[i] = d;
//! c[i] = colour } (else a failure); acc += dz (wrapping). Returns the number of
//! failures (written = n − failures). A 20.12 (or any) fixed-point accumulator maps
//! onto this 16.16 form exactly by shifting acc and dz left (wrapping) so that the depth
//! bits land in the top half: ((acc << 4) >> 16) as u16 == (acc >> 12) as u16, and
//! (acc + k·dz) << 4 == (acc << 4) + k·(dz << 4) modulo 2³².
//!
//! Kernels: [`span_flat`] (counting failures), [`span_flat_nocount`],
//! [`span_depth`] (depth only, no count). Their portable twins: [`span_portable`],
//! [`span_portable`] ignoring the count, [`span_depth_portable`].

/// The plain reference: an index loop, exactly the specification.
#[allow(clippy::needless_range_loop)]
pub fn span_ref(z: &mut [u16], c: &mut [u16], mut acc: u32, dz: u32, color: u16) -> u32 {
    let n = z.len().min(c.len());
    let mut fails = 0;
    for i in 0..n {
        let d = (acc >> 16) as u16;
        if d < z[i] {
            z[i] = d;
            c[i] = color;
        } else {
            fails += 1;
        }
        acc = acc.wrapping_add(dz);
    }
    fails
}

/// The portable twin of [`span_flat`]: a `zip` loop (zraster's `span_pixels`).
#[inline(never)]
pub fn span_portable(z: &mut [u16], c: &mut [u16], mut acc: u32, dz: u32, color: u16) -> u32 {
    let mut fails = 0;
    for (zp, cp) in z.iter_mut().zip(c.iter_mut()) {
        let d = (acc >> 16) as u16;
        acc = acc.wrapping_add(dz);
        if d < *zp {
            *zp = d;
            *cp = color;
        } else {
            fails += 1;
        }
    }
    fails
}

/// The portable twin of [`span_depth`].
#[inline(never)]
pub fn span_depth_portable(z: &mut [u16], mut acc: u32, dz: u32) {
    for zp in z.iter_mut() {
        let d = (acc >> 16) as u16;
        acc = acc.wrapping_add(dz);
        if d < *zp {
            *zp = d;
        }
    }
}

/// The depth-tested flat span, counting failures: on ARMv7E-M two pixels a
/// SIMD step (USUB16 compares a pair, SEL merges depths and colours), 5.25 instructions a
/// pixel (8 a turn); on ARMv6-M a 16-way unrolled loop entered Duff-style, 7.25 a pixel;
/// elsewhere [`span_portable`].
#[inline(never)]
pub fn span_flat(z: &mut [u16], c: &mut [u16], acc: u32, dz: u32, color: u16) -> u32 {
    let n = z.len().min(c.len());
    let (z, c) = (&mut z[..n], &mut c[..n]);
    #[cfg(zk_dsp)]
    if n > 0 && (z.as_ptr() as usize ^ c.as_ptr() as usize) & 2 == 0 {
        return span_flat_dsp(z, c, acc, dz, color);
    }
    #[cfg(zk_v6m)]
    if n > 0 {
        return span_flat_v6m(z, c, acc, dz, color);
    }
    span_portable(z, c, acc, dz, color)
}

/// [`span_flat`] without the failure count (ARMv7E-M: 4.25 instructions a pixel; ARMv6-M
/// 7.25 passing, 5.25 failing).
#[inline(never)]
pub fn span_flat_nocount(z: &mut [u16], c: &mut [u16], acc: u32, dz: u32, color: u16) {
    let n = z.len().min(c.len());
    let (z, c) = (&mut z[..n], &mut c[..n]);
    #[cfg(zk_dsp)]
    if n > 0 && (z.as_ptr() as usize ^ c.as_ptr() as usize) & 2 == 0 {
        return span_flat_nocount_dsp(z, c, acc, dz, color);
    }
    #[cfg(zk_v6m)]
    if n > 0 {
        return span_flat_nocount_v6m(z, c, acc, dz, color);
    }
    span_portable(z, c, acc, dz, color);
}

/// The depth-only span (a depth pre-pass), no count: ARMv7E-M 3.25 instructions a pixel,
/// ARMv6-M 6.19 passing, 5.19 failing.
#[inline(never)]
pub fn span_depth(z: &mut [u16], acc: u32, dz: u32) {
    #[cfg(zk_dsp)]
    if !z.is_empty() {
        return span_depth_dsp(z, acc, dz);
    }
    #[cfg(zk_v6m)]
    if !z.is_empty() {
        return span_depth_v6m(z, acc, dz);
    }
    span_depth_portable(z, acc, dz)
}

// ---------------------------------------------------------------------------------
// ARMv7E-M (Cortex-M4/M7).
//
// Two pixels a step, as halfword lanes of one word: with a1 = acc + dz,
//   PKHTB d, a1, acc, ASR #16   d = [a1 >> 16 : acc >> 16], the pair's depths
//   USUB16 -, d, z              GE flags of each lane set where d >= z (the test fails)
//   SEL z, z, d                 new depths: old where it failed, d where it passed
//   SEL c, c, col2              new colours likewise (col2 = colour in both lanes)
// Counting failures: SEL t, y, col2 with y = col2 ^ 0x0001_0001 gives a lane one byte
// away from col2 (by exactly 1) where the test failed, so USADA8 cnt, t, col2, cnt (sum of
// absolute byte differences, accumulated) adds the pair's failures.
// Pointers must be co-aligned (z and c at the same address modulo 4): LDRD/STRD need
// word alignment, reached by one pixel alone first.

// Registers: r0 z pointer, r1 c pointer, r2 pixels left, r3 acc, r4 dz, r5 col2,
// r6 y, r7 failures (r6/r7 are reserved by Rust: saved on the stack), r8/r9 depth pair,
// r10/r11 colour pair, r12 scratch, lr packed depths.

#[cfg(zk_dsp)]
#[inline(always)]
fn span_flat_dsp(z: &mut [u16], c: &mut [u16], acc: u32, dz: u32, color: u16) -> u32 {
    let n = z.len();
    let fails: u32;
    // SAFETY: the caller passes n = z.len() = c.len() ≥ 1 and z, c at the same address
    // modulo 4 (both 2-aligned as u16). Every access is to z[i] / c[i] for i < n, in
    // order: one pixel if z is not word-aligned (after it both are), then LDRD/STRD of
    // eight pixels while at least eight remain (r2 counts them down), then four
    // (LDRD/STRD), a pair (LDR/STR) and a pixel by the bits of the remainder. r6/r7
    // are pushed and popped around the block (the stack is used, so no `nostack`);
    // every other register written is declared. GE flags and NZCV are scratch (no `preserves_flags`).
    unsafe {
        core::arch::asm!(
            "push {{r6, r7}}",
            "eor r6, r5, #0x00010001",
            "movs r7, #0",
            "tst r0, #2",
            "beq 2f",
            "ldrh r8, [r0]",
            "lsr lr, r3, #16",
            "add r3, r4",
            "cmp lr, r8",
            "itte lo",
            "strhlo lr, [r0]",
            "strhlo r5, [r1]",
            "addhs r7, #1",
            "adds r0, #2",
            "adds r1, #2",
            "subs r2, #1",
            "2:",
            "subs r2, #8",
            "blo 4f",
            "3:",
            "ldrd r8, r9, [r0]",
            "ldrd r10, r11, [r1]",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r8",
            "sel r8, r8, lr",
            "sel r10, r10, r5",
            "sel r12, r6, r5",
            "usada8 r7, r12, r5, r7",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r9",
            "sel r9, r9, lr",
            "sel r11, r11, r5",
            "sel r12, r6, r5",
            "usada8 r7, r12, r5, r7",
            "strd r8, r9, [r0], #8",
            "strd r10, r11, [r1], #8",
            "ldrd r8, r9, [r0]",
            "ldrd r10, r11, [r1]",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r8",
            "sel r8, r8, lr",
            "sel r10, r10, r5",
            "sel r12, r6, r5",
            "usada8 r7, r12, r5, r7",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r9",
            "sel r9, r9, lr",
            "sel r11, r11, r5",
            "sel r12, r6, r5",
            "usada8 r7, r12, r5, r7",
            "strd r8, r9, [r0], #8",
            "strd r10, r11, [r1], #8",
            "subs r2, #8",
            "bhs 3b",
            "4:",
            "lsls r2, r2, #30", // C = remainder bit 2, N = bit 1
            "bcc 5f",
            "ldrd r8, r9, [r0]",
            "ldrd r10, r11, [r1]",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r8",
            "sel r8, r8, lr",
            "sel r10, r10, r5",
            "sel r12, r6, r5",
            "usada8 r7, r12, r5, r7",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r9",
            "sel r9, r9, lr",
            "sel r11, r11, r5",
            "sel r12, r6, r5",
            "usada8 r7, r12, r5, r7",
            "strd r8, r9, [r0], #8",
            "strd r10, r11, [r1], #8",
            "5:",
            "bpl 6f",
            "ldr r8, [r0]",
            "ldr r10, [r1]",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r8",
            "sel r8, r8, lr",
            "sel r10, r10, r5",
            "sel r12, r6, r5",
            "usada8 r7, r12, r5, r7",
            "str r8, [r0], #4",
            "str r10, [r1], #4",
            "6:",
            "lsls r2, r2, #2", // C = remainder bit 0
            "bcc 7f",
            "ldrh r8, [r0]",
            "lsr lr, r3, #16",
            "add r3, r4",
            "cmp lr, r8",
            "itte lo",
            "strhlo lr, [r0]",
            "strhlo r5, [r1]",
            "addhs r7, #1",
            "7:",
            "mov r12, r7",
            "pop {{r6, r7}}",
            inout("r0") z.as_mut_ptr() => _,
            inout("r1") c.as_mut_ptr() => _,
            inout("r2") n => _,
            inout("r3") acc => _,
            in("r4") dz,
            in("r5") u32::from(color) * 0x1_0001,
            out("r8") _, out("r9") _, out("r10") _, out("r11") _,
            out("r12") fails,
            out("lr") _,
        );
    }
    fails
}

#[cfg(zk_dsp)]
#[inline(always)]
fn span_flat_nocount_dsp(z: &mut [u16], c: &mut [u16], acc: u32, dz: u32, color: u16) {
    let n = z.len();
    // SAFETY: as span_flat_dsp, without r6/r7 and the stack.
    unsafe {
        core::arch::asm!(
            "tst r0, #2",
            "beq 2f",
            "ldrh r8, [r0]",
            "lsr lr, r3, #16",
            "add r3, r4",
            "cmp lr, r8",
            "itt lo",
            "strhlo lr, [r0]",
            "strhlo r5, [r1]",
            "adds r0, #2",
            "adds r1, #2",
            "subs r2, #1",
            "2:",
            "subs r2, #8",
            "blo 4f",
            "3:",
            "ldrd r8, r9, [r0]",
            "ldrd r10, r11, [r1]",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r8",
            "sel r8, r8, lr",
            "sel r10, r10, r5",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r9",
            "sel r9, r9, lr",
            "sel r11, r11, r5",
            "strd r8, r9, [r0], #8",
            "strd r10, r11, [r1], #8",
            "ldrd r8, r9, [r0]",
            "ldrd r10, r11, [r1]",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r8",
            "sel r8, r8, lr",
            "sel r10, r10, r5",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r9",
            "sel r9, r9, lr",
            "sel r11, r11, r5",
            "strd r8, r9, [r0], #8",
            "strd r10, r11, [r1], #8",
            "subs r2, #8",
            "bhs 3b",
            "4:",
            "lsls r2, r2, #30", // C = remainder bit 2, N = bit 1
            "bcc 5f",
            "ldrd r8, r9, [r0]",
            "ldrd r10, r11, [r1]",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r8",
            "sel r8, r8, lr",
            "sel r10, r10, r5",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r9",
            "sel r9, r9, lr",
            "sel r11, r11, r5",
            "strd r8, r9, [r0], #8",
            "strd r10, r11, [r1], #8",
            "5:",
            "bpl 6f",
            "ldr r8, [r0]",
            "ldr r10, [r1]",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r8",
            "sel r8, r8, lr",
            "sel r10, r10, r5",
            "str r8, [r0], #4",
            "str r10, [r1], #4",
            "6:",
            "lsls r2, r2, #2", // C = remainder bit 0
            "bcc 7f",
            "ldrh r8, [r0]",
            "lsr lr, r3, #16",
            "add r3, r4",
            "cmp lr, r8",
            "itt lo",
            "strhlo lr, [r0]",
            "strhlo r5, [r1]",
            "7:",
            inout("r0") z.as_mut_ptr() => _,
            inout("r1") c.as_mut_ptr() => _,
            inout("r2") n => _,
            inout("r3") acc => _,
            in("r4") dz,
            in("r5") u32::from(color) * 0x1_0001,
            out("r8") _, out("r9") _, out("r10") _, out("r11") _,
            out("r12") _, out("lr") _,
            options(nostack),
        );
    }
}

#[cfg(zk_dsp)]
#[inline(always)]
fn span_depth_dsp(z: &mut [u16], acc: u32, dz: u32) {
    let n = z.len();
    // SAFETY: as span_flat_dsp for the depth row alone (n = z.len() ≥ 1).
    unsafe {
        core::arch::asm!(
            "tst r0, #2",
            "beq 2f",
            "ldrh r8, [r0]",
            "lsr lr, r3, #16",
            "add r3, r4",
            "cmp lr, r8",
            "it lo",
            "strhlo lr, [r0]",
            "adds r0, #2",
            "subs r2, #1",
            "2:",
            "subs r2, #8",
            "blo 4f",
            "3:",
            "ldrd r8, r9, [r0]",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r8",
            "sel r8, r8, lr",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r9",
            "sel r9, r9, lr",
            "strd r8, r9, [r0], #8",
            "ldrd r8, r9, [r0]",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r8",
            "sel r8, r8, lr",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r9",
            "sel r9, r9, lr",
            "strd r8, r9, [r0], #8",
            "subs r2, #8",
            "bhs 3b",
            "4:",
            "lsls r2, r2, #30", // C = remainder bit 2, N = bit 1
            "bcc 5f",
            "ldrd r8, r9, [r0]",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r8",
            "sel r8, r8, lr",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r9",
            "sel r9, r9, lr",
            "strd r8, r9, [r0], #8",
            "5:",
            "bpl 6f",
            "ldr r8, [r0]",
            "add r12, r3, r4",
            "pkhtb lr, r12, r3, asr #16",
            "add r3, r12, r4",
            "usub16 r12, lr, r8",
            "sel r8, r8, lr",
            "str r8, [r0], #4",
            "6:",
            "lsls r2, r2, #2", // C = remainder bit 0
            "bcc 7f",
            "ldrh r8, [r0]",
            "lsr lr, r3, #16",
            "add r3, r4",
            "cmp lr, r8",
            "it lo",
            "strhlo lr, [r0]",
            "7:",
            inout("r0") z.as_mut_ptr() => _,
            inout("r2") n => _,
            inout("r3") acc => _,
            in("r4") dz,
            out("r8") _, out("r9") _,
            out("r12") _, out("lr") _,
            options(nostack),
        );
    }
}

// ---------------------------------------------------------------------------------
// ARMv6-M (Cortex-M0/M0+): no IT blocks, no post-indexed or SIMD loads. 16 pixels a
// turn with immediate offsets, each pixel 7 two-byte instructions on its passing path
// (LDRH, LSRS, CMP, BHS, STRH, STRH, ADD); failures branch to a cold block that counts
// and returns. The loop is entered Duff-style: s = (−n) mod 16 pixels of the first turn
// are skipped by ADD PC (both pointers moved back by s pixels), so no tail loop.
// Registers: r0 z pointer, r1 c pointer, r2 acc, r3 colour, r4 depth read, r5 depth
// (all must be low: r6/r7 are Rust's), r8 dz, r9 end of z, r10 failures, r11 one
// (r8–r11 are set inside: Thumb-1 asm operands must be low registers).

#[cfg(zk_v6m)]
#[inline(always)]
fn span_flat_v6m(z: &mut [u16], c: &mut [u16], acc: u32, dz: u32, color: u16) -> u32 {
    let n = z.len();
    let fails: u32;
    // SAFETY: n = z.len() = c.len() ≥ 1 (the caller's). The first turn starts s pixels
    // before the rows but skips exactly the code of those s pixels, so the accesses are
    // z[i], c[i] for i in 0..n only, halfword-aligned; the loop ends when the z pointer
    // reaches z + n (a multiple of 16 pixels after the first turn's 16 − s). Every
    // register written is declared; no stack. The computed branch lands on a block
    // boundary: every instruction in the loop is 2 bytes (ARMv6-M has no 32-bit forms
    // of them), and the firmware's check runs every entry point
    // (lengths 1..=64 give every s) against the portable twin.
    unsafe {
        core::arch::asm!(
            // Thumb-1 code can take operands in low registers only: move to r8–r11.
            "mov r8, r5", // dz
            "movs r5, #0",
            "mov r10, r5", // failures
            "movs r5, #1",
            "mov r11, r5", // one
            "lsls r5, r4, #1",
            "adds r5, r0",
            "mov r9, r5", // end of z
            "rsbs r4, r4, #0",
            "lsls r4, r4, #28",
            "lsrs r4, r4, #28", // s = (−n) mod 16
            "lsls r5, r4, #1",
            "subs r0, r0, r5",
            "subs r1, r1, r5",
            "lsls r4, r4, #4",
            "subs r4, r4, r5", // 14·s bytes of code to skip
            "add pc, r4",      // PC reads as this instruction + 4: the first block
            "nop",
            "2:",
            "ldrh r4, [r0, #0]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 30f",
            "strh r5, [r0, #0]",
            "strh r3, [r1, #0]",
            "60:",
            "add r2, r8",
            "ldrh r4, [r0, #2]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 31f",
            "strh r5, [r0, #2]",
            "strh r3, [r1, #2]",
            "61:",
            "add r2, r8",
            "ldrh r4, [r0, #4]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 32f",
            "strh r5, [r0, #4]",
            "strh r3, [r1, #4]",
            "62:",
            "add r2, r8",
            "ldrh r4, [r0, #6]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 33f",
            "strh r5, [r0, #6]",
            "strh r3, [r1, #6]",
            "63:",
            "add r2, r8",
            "ldrh r4, [r0, #8]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 34f",
            "strh r5, [r0, #8]",
            "strh r3, [r1, #8]",
            "64:",
            "add r2, r8",
            "ldrh r4, [r0, #10]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 35f",
            "strh r5, [r0, #10]",
            "strh r3, [r1, #10]",
            "65:",
            "add r2, r8",
            "ldrh r4, [r0, #12]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 36f",
            "strh r5, [r0, #12]",
            "strh r3, [r1, #12]",
            "66:",
            "add r2, r8",
            "ldrh r4, [r0, #14]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 37f",
            "strh r5, [r0, #14]",
            "strh r3, [r1, #14]",
            "67:",
            "add r2, r8",
            "ldrh r4, [r0, #16]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 38f",
            "strh r5, [r0, #16]",
            "strh r3, [r1, #16]",
            "68:",
            "add r2, r8",
            "ldrh r4, [r0, #18]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 39f",
            "strh r5, [r0, #18]",
            "strh r3, [r1, #18]",
            "69:",
            "add r2, r8",
            "ldrh r4, [r0, #20]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 40f",
            "strh r5, [r0, #20]",
            "strh r3, [r1, #20]",
            "70:",
            "add r2, r8",
            "ldrh r4, [r0, #22]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 41f",
            "strh r5, [r0, #22]",
            "strh r3, [r1, #22]",
            "71:",
            "add r2, r8",
            "ldrh r4, [r0, #24]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 42f",
            "strh r5, [r0, #24]",
            "strh r3, [r1, #24]",
            "72:",
            "add r2, r8",
            "ldrh r4, [r0, #26]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 43f",
            "strh r5, [r0, #26]",
            "strh r3, [r1, #26]",
            "73:",
            "add r2, r8",
            "ldrh r4, [r0, #28]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 44f",
            "strh r5, [r0, #28]",
            "strh r3, [r1, #28]",
            "74:",
            "add r2, r8",
            "ldrh r4, [r0, #30]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 45f",
            "strh r5, [r0, #30]",
            "strh r3, [r1, #30]",
            "75:",
            "add r2, r8",
            "adds r0, #32",
            "adds r1, #32",
            "cmp r0, r9",
            "bne 2b",
            "b 9f",
            "30:",
            "add r10, r11",
            "b 60b",
            "31:",
            "add r10, r11",
            "b 61b",
            "32:",
            "add r10, r11",
            "b 62b",
            "33:",
            "add r10, r11",
            "b 63b",
            "34:",
            "add r10, r11",
            "b 64b",
            "35:",
            "add r10, r11",
            "b 65b",
            "36:",
            "add r10, r11",
            "b 66b",
            "37:",
            "add r10, r11",
            "b 67b",
            "38:",
            "add r10, r11",
            "b 68b",
            "39:",
            "add r10, r11",
            "b 69b",
            "40:",
            "add r10, r11",
            "b 70b",
            "41:",
            "add r10, r11",
            "b 71b",
            "42:",
            "add r10, r11",
            "b 72b",
            "43:",
            "add r10, r11",
            "b 73b",
            "44:",
            "add r10, r11",
            "b 74b",
            "45:",
            "add r10, r11",
            "b 75b",
            "9:",
            "mov r5, r10",
            inout("r0") z.as_mut_ptr() => _,
            inout("r1") c.as_mut_ptr() => _,
            inout("r2") acc => _,
            in("r3") u32::from(color),
            inout("r4") n => _,
            inout("r5") dz => fails,
            out("r8") _, out("r9") _, out("r10") _, out("r11") _,
            options(nostack),
        );
    }
    fails
}

#[cfg(zk_v6m)]
#[inline(always)]
fn span_flat_nocount_v6m(z: &mut [u16], c: &mut [u16], acc: u32, dz: u32, color: u16) {
    let n = z.len();
    // SAFETY: as span_flat_v6m; a failure skips straight to the next pixel.
    unsafe {
        core::arch::asm!(
            "mov r8, r5", // dz
            "lsls r5, r4, #1",
            "adds r5, r0",
            "mov r9, r5",
            "rsbs r4, r4, #0",
            "lsls r4, r4, #28",
            "lsrs r4, r4, #28",
            "lsls r5, r4, #1",
            "subs r0, r0, r5",
            "subs r1, r1, r5",
            "lsls r4, r4, #4",
            "subs r4, r4, r5",
            "add pc, r4",
            "nop",
            "2:",
            "ldrh r4, [r0, #0]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 60f",
            "strh r5, [r0, #0]",
            "strh r3, [r1, #0]",
            "60:",
            "add r2, r8",
            "ldrh r4, [r0, #2]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 61f",
            "strh r5, [r0, #2]",
            "strh r3, [r1, #2]",
            "61:",
            "add r2, r8",
            "ldrh r4, [r0, #4]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 62f",
            "strh r5, [r0, #4]",
            "strh r3, [r1, #4]",
            "62:",
            "add r2, r8",
            "ldrh r4, [r0, #6]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 63f",
            "strh r5, [r0, #6]",
            "strh r3, [r1, #6]",
            "63:",
            "add r2, r8",
            "ldrh r4, [r0, #8]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 64f",
            "strh r5, [r0, #8]",
            "strh r3, [r1, #8]",
            "64:",
            "add r2, r8",
            "ldrh r4, [r0, #10]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 65f",
            "strh r5, [r0, #10]",
            "strh r3, [r1, #10]",
            "65:",
            "add r2, r8",
            "ldrh r4, [r0, #12]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 66f",
            "strh r5, [r0, #12]",
            "strh r3, [r1, #12]",
            "66:",
            "add r2, r8",
            "ldrh r4, [r0, #14]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 67f",
            "strh r5, [r0, #14]",
            "strh r3, [r1, #14]",
            "67:",
            "add r2, r8",
            "ldrh r4, [r0, #16]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 68f",
            "strh r5, [r0, #16]",
            "strh r3, [r1, #16]",
            "68:",
            "add r2, r8",
            "ldrh r4, [r0, #18]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 69f",
            "strh r5, [r0, #18]",
            "strh r3, [r1, #18]",
            "69:",
            "add r2, r8",
            "ldrh r4, [r0, #20]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 70f",
            "strh r5, [r0, #20]",
            "strh r3, [r1, #20]",
            "70:",
            "add r2, r8",
            "ldrh r4, [r0, #22]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 71f",
            "strh r5, [r0, #22]",
            "strh r3, [r1, #22]",
            "71:",
            "add r2, r8",
            "ldrh r4, [r0, #24]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 72f",
            "strh r5, [r0, #24]",
            "strh r3, [r1, #24]",
            "72:",
            "add r2, r8",
            "ldrh r4, [r0, #26]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 73f",
            "strh r5, [r0, #26]",
            "strh r3, [r1, #26]",
            "73:",
            "add r2, r8",
            "ldrh r4, [r0, #28]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 74f",
            "strh r5, [r0, #28]",
            "strh r3, [r1, #28]",
            "74:",
            "add r2, r8",
            "ldrh r4, [r0, #30]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 75f",
            "strh r5, [r0, #30]",
            "strh r3, [r1, #30]",
            "75:",
            "add r2, r8",
            "adds r0, #32",
            "adds r1, #32",
            "cmp r0, r9",
            "bne 2b",
            inout("r0") z.as_mut_ptr() => _,
            inout("r1") c.as_mut_ptr() => _,
            inout("r2") acc => _,
            in("r3") u32::from(color),
            inout("r4") n => _,
            inout("r5") dz => _,
            out("r8") _, out("r9") _,
            options(nostack),
        );
    }
}

#[cfg(zk_v6m)]
#[inline(always)]
fn span_depth_v6m(z: &mut [u16], acc: u32, dz: u32) {
    let n = z.len();
    // SAFETY: as span_flat_v6m for the depth row alone; 6 two-byte instructions a pixel.
    unsafe {
        core::arch::asm!(
            "mov r8, r5", // dz
            "lsls r5, r4, #1",
            "adds r5, r0",
            "mov r9, r5",
            "rsbs r4, r4, #0",
            "lsls r4, r4, #28",
            "lsrs r4, r4, #28",
            "lsls r5, r4, #1",
            "subs r0, r0, r5",
            "lsls r4, r4, #3",
            "adds r4, r4, r5",
            "adds r4, r4, r5", // 12·s = 8s + 2s + 2s bytes of code to skip
            "add pc, r4",
            "nop",
            "2:",
            "ldrh r4, [r0, #0]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 60f",
            "strh r5, [r0, #0]",
            "60:",
            "add r2, r8",
            "ldrh r4, [r0, #2]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 61f",
            "strh r5, [r0, #2]",
            "61:",
            "add r2, r8",
            "ldrh r4, [r0, #4]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 62f",
            "strh r5, [r0, #4]",
            "62:",
            "add r2, r8",
            "ldrh r4, [r0, #6]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 63f",
            "strh r5, [r0, #6]",
            "63:",
            "add r2, r8",
            "ldrh r4, [r0, #8]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 64f",
            "strh r5, [r0, #8]",
            "64:",
            "add r2, r8",
            "ldrh r4, [r0, #10]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 65f",
            "strh r5, [r0, #10]",
            "65:",
            "add r2, r8",
            "ldrh r4, [r0, #12]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 66f",
            "strh r5, [r0, #12]",
            "66:",
            "add r2, r8",
            "ldrh r4, [r0, #14]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 67f",
            "strh r5, [r0, #14]",
            "67:",
            "add r2, r8",
            "ldrh r4, [r0, #16]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 68f",
            "strh r5, [r0, #16]",
            "68:",
            "add r2, r8",
            "ldrh r4, [r0, #18]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 69f",
            "strh r5, [r0, #18]",
            "69:",
            "add r2, r8",
            "ldrh r4, [r0, #20]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 70f",
            "strh r5, [r0, #20]",
            "70:",
            "add r2, r8",
            "ldrh r4, [r0, #22]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 71f",
            "strh r5, [r0, #22]",
            "71:",
            "add r2, r8",
            "ldrh r4, [r0, #24]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 72f",
            "strh r5, [r0, #24]",
            "72:",
            "add r2, r8",
            "ldrh r4, [r0, #26]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 73f",
            "strh r5, [r0, #26]",
            "73:",
            "add r2, r8",
            "ldrh r4, [r0, #28]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 74f",
            "strh r5, [r0, #28]",
            "74:",
            "add r2, r8",
            "ldrh r4, [r0, #30]",
            "lsrs r5, r2, #16",
            "cmp r5, r4",
            "bhs 75f",
            "strh r5, [r0, #30]",
            "75:",
            "add r2, r8",
            "adds r0, #32",
            "cmp r0, r9",
            "bne 2b",
            inout("r0") z.as_mut_ptr() => _,
            inout("r2") acc => _,
            inout("r4") n => _,
            inout("r5") dz => _,
            out("r8") _, out("r9") _,
            options(nostack),
        );
    }
}

// ---------------------------------------------------------------------------------
// Plain-Rust shapes, for comparison (all give span_ref's results).

/// zraster's `span_x2` (two pixels a turn, the failure count in a cold call).
#[inline(never)]
pub fn span_x2_project(z: &mut [u16], c: &mut [u16], mut acc: u32, dz: u32, color: u16) -> u32 {
    #[cold]
    #[inline(never)]
    fn one_failed(n: &mut u32) {
        *n += 1;
    }
    let mut failed = 0;
    let mut pixel = |d: &mut u16, c: &mut u16, acc: u32| {
        let zz = (acc >> 16) as u16;
        if zz < *d {
            *d = zz;
            *c = color;
        } else {
            one_failed(&mut failed);
        }
    };
    let n = z.len().min(c.len());
    let (zrow, zrest) = z.split_at_mut(n & !1);
    let (crow, crest) = c.split_at_mut(n & !1);
    for (d, c) in zrow.chunks_exact_mut(2).zip(crow.chunks_exact_mut(2)) {
        if let ([d0, d1], [c0, c1]) = (d, c) {
            pixel(d0, c0, acc);
            acc = acc.wrapping_add(dz);
            pixel(d1, c1, acc);
            acc = acc.wrapping_add(dz);
        }
    }
    for (d, c) in zrest.iter_mut().zip(crest) {
        pixel(d, c, acc);
        acc = acc.wrapping_add(dz);
    }
    failed
}

/// zraster's `span_x2` shape with the failure count inline (`failed += 1`) instead of
/// the cold call.
#[inline(never)]
pub fn span_x2_inline(z: &mut [u16], c: &mut [u16], mut acc: u32, dz: u32, color: u16) -> u32 {
    let mut failed = 0;
    let mut pixel = |d: &mut u16, c: &mut u16, acc: u32| {
        let zz = (acc >> 16) as u16;
        if zz < *d {
            *d = zz;
            *c = color;
        } else {
            failed += 1;
        }
    };
    let n = z.len().min(c.len());
    let (zrow, zrest) = z.split_at_mut(n & !1);
    let (crow, crest) = c.split_at_mut(n & !1);
    for (d, c) in zrow.chunks_exact_mut(2).zip(crow.chunks_exact_mut(2)) {
        if let ([d0, d1], [c0, c1]) = (d, c) {
            pixel(d0, c0, acc);
            acc = acc.wrapping_add(dz);
            pixel(d1, c1, acc);
            acc = acc.wrapping_add(dz);
        }
    }
    for (d, c) in zrest.iter_mut().zip(crest) {
        pixel(d, c, acc);
        acc = acc.wrapping_add(dz);
    }
    failed
}

/// Branch-free: both stores every pixel, selects for the values.
#[inline(never)]
pub fn span_select(z: &mut [u16], c: &mut [u16], mut acc: u32, dz: u32, color: u16) -> u32 {
    let mut fails = 0;
    for (zp, cp) in z.iter_mut().zip(c.iter_mut()) {
        let d = (acc >> 16) as u16;
        acc = acc.wrapping_add(dz);
        let pass = d < *zp;
        *zp = if pass { d } else { *zp };
        *cp = if pass { color } else { *cp };
        fails += u32::from(!pass);
    }
    fails
}

/// Index loop over re-sliced rows (bounds checks proven away), counting passes and
/// deriving failures.
#[inline(never)]
pub fn span_index(z: &mut [u16], c: &mut [u16], mut acc: u32, dz: u32, color: u16) -> u32 {
    let n = z.len().min(c.len());
    let (z, c) = (&mut z[..n], &mut c[..n]);
    let mut written = 0;
    for i in 0..n {
        let d = (acc >> 16) as u16;
        acc = acc.wrapping_add(dz);
        if d < z[i] {
            z[i] = d;
            c[i] = color;
            written += 1;
        }
    }
    n as u32 - written
}

/// The zip loop without a count.
#[inline(never)]
pub fn span_zip_nocount(z: &mut [u16], c: &mut [u16], mut acc: u32, dz: u32, color: u16) {
    for (zp, cp) in z.iter_mut().zip(c.iter_mut()) {
        let d = (acc >> 16) as u16;
        acc = acc.wrapping_add(dz);
        if d < *zp {
            *zp = d;
            *cp = color;
        }
    }
}

/// Four pixels a turn over `chunks_exact_mut(4)`, no count.
#[inline(never)]
pub fn span_x4_nocount(z: &mut [u16], c: &mut [u16], mut acc: u32, dz: u32, color: u16) {
    let n = z.len().min(c.len());
    let (z, c) = (&mut z[..n], &mut c[..n]);
    let mut zc = z.chunks_exact_mut(4);
    let mut cc = c.chunks_exact_mut(4);
    for (zq, cq) in (&mut zc).zip(&mut cc) {
        for k in 0..4 {
            let d = (acc >> 16) as u16;
            acc = acc.wrapping_add(dz);
            if d < zq[k] {
                zq[k] = d;
                cq[k] = color;
            }
        }
    }
    for (zp, cp) in zc.into_remainder().iter_mut().zip(cc.into_remainder()) {
        let d = (acc >> 16) as u16;
        acc = acc.wrapping_add(dz);
        if d < *zp {
            *zp = d;
            *cp = color;
        }
    }
}

/// Pairs as words, SIMD-within-a-register in portable Rust (what the DSP kernel does
/// with USUB16/SEL, spelt out): no count.
#[inline(never)]
pub fn span_swar_nocount(z: &mut [u16], c: &mut [u16], mut acc: u32, dz: u32, color: u16) {
    let n = z.len().min(c.len());
    let (z, c) = (&mut z[..n], &mut c[..n]);
    let mut zc = z.chunks_exact_mut(2);
    let mut cc = c.chunks_exact_mut(2);
    for (zq, cq) in (&mut zc).zip(&mut cc) {
        let a1 = acc.wrapping_add(dz);
        let (d0, d1) = ((acc >> 16) as u16, (a1 >> 16) as u16);
        acc = a1.wrapping_add(dz);
        let p0 = d0 < zq[0];
        let p1 = d1 < zq[1];
        zq[0] = if p0 { d0 } else { zq[0] };
        zq[1] = if p1 { d1 } else { zq[1] };
        cq[0] = if p0 { color } else { cq[0] };
        cq[1] = if p1 { color } else { cq[1] };
    }
    for (zp, cp) in zc.into_remainder().iter_mut().zip(cc.into_remainder()) {
        let d = (acc >> 16) as u16;
        if d < *zp {
            *zp = d;
            *cp = color;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec::Vec;

    fn xorshift(mut s: u32) -> impl FnMut() -> u32 {
        move || {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            s
        }
    }

    type Span = fn(&mut [u16], &mut [u16], u32, u32, u16) -> u32;

    /// Every shape agrees with the reference on depths, colours and failures, for all
    /// lengths up to 64 and all offsets, with depth ramps that pass, fail and mix.
    #[test]
    fn spans_agree() {
        let shapes: [(&str, Span); 6] = [
            ("span_flat", span_flat),
            ("x2_inline", span_x2_inline),
            ("portable", span_portable),
            ("x2_project", span_x2_project),
            ("select", span_select),
            ("index", span_index),
        ];
        let nocount: [(&str, fn(&mut [u16], &mut [u16], u32, u32, u16)); 4] = [
            ("span_flat_nocount", span_flat_nocount),
            ("zip_nocount", span_zip_nocount),
            ("x4_nocount", span_x4_nocount),
            ("swar_nocount", span_swar_nocount),
        ];
        let mut rnd = xorshift(0x9e37_79b9);
        for round in 0..40 {
            for len in 0..65 {
                for (zo, co) in [(0, 0), (1, 1), (0, 1), (1, 0), (2, 3)] {
                    let depth: Vec<u16> = (0..len + 4).map(|_| rnd() as u16).collect();
                    let colour: Vec<u16> = (0..len + 4).map(|_| rnd() as u16).collect();
                    let acc = match round % 4 {
                        0 => rnd() >> 2,
                        1 => 0,             // every pixel passes unless z = 0
                        2 => u32::MAX - 3,  // every pixel fails
                        _ => rnd(),
                    };
                    let dz = if round % 2 == 0 { rnd() >> 12 } else { rnd() };
                    let col = rnd() as u16;
                    let run = |f: &dyn Fn(&mut [u16], &mut [u16]) -> u32| {
                        let (mut z, mut c) = (depth.clone(), colour.clone());
                        let r = f(&mut z[zo..zo + len], &mut c[co..co + len]);
                        (z, c, r)
                    };
                    let want = run(&|z, c| span_ref(z, c, acc, dz, col));
                    for (name, f) in shapes {
                        assert_eq!(run(&|z, c| f(z, c, acc, dz, col)), want, "{name} len {len}");
                    }
                    for (name, f) in nocount {
                        let got = run(&|z, c| {
                            f(z, c, acc, dz, col);
                            want.2
                        });
                        assert_eq!(got, want, "{name} len {len}");
                    }
                    let (mut zd, mut zr) = (depth.clone(), depth.clone());
                    span_depth(&mut zd[zo..zo + len], acc, dz);
                    let mut dummy = std::vec![0u16; len];
                    span_ref(&mut zr[zo..zo + len], &mut dummy, acc, dz, 0);
                    assert_eq!(zd, zr, "depth len {len}");
                    let mut zp = depth.clone();
                    span_depth_portable(&mut zp[zo..zo + len], acc, dz);
                    assert_eq!(zp, zr, "depth portable len {len}");
                }
            }
        }
    }
}
