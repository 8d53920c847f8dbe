//! Filling a `u16` buffer (the RGB565 / Z-buffer clear).
//!
//! [`fill_u16`] is the kernel: store multiple (STM) of 8 registers on Thumb-2, of 6 low
//! registers on ARMv6-M, after one halfword to reach a word boundary; the portable twin
//! [`fill_u16_portable`] elsewhere. The other functions are plain-Rust shapes measured
//! against it.

/// The portable twin of [`fill_u16`] (and the reference): `slice::fill`.
#[inline(never)]
pub fn fill_u16_portable(buf: &mut [u16], value: u16) {
    buf.fill(value);
}

/// Fill `buf` with `value`: on Cortex-M an `asm!` kernel (STM of 8 or 6 registers, 16 or
/// 12 pixels a store), elsewhere [`fill_u16_portable`].
#[inline(never)]
pub fn fill_u16(buf: &mut [u16], value: u16) {
    #[cfg(zk_thumb2)]
    return fill_u16_thumb2(buf, value);
    #[cfg(zk_v6m)]
    return fill_u16_v6m(buf, value);
    #[cfg(not(any(zk_thumb2, zk_v6m)))]
    fill_u16_portable(buf, value)
}

/// ARMv7-M (Cortex-M3/M4/M7): 0.125 instructions a pixel in the main loop (two STMs of
/// 8 registers, 32 pixels, per turn), ~30 instructions fixed.
#[cfg(zk_thumb2)]
#[inline(always)]
fn fill_u16_thumb2(buf: &mut [u16], value: u16) {
    let n = buf.len();
    if n == 0 {
        return;
    }
    let v = u32::from(value) * 0x1_0001;
    // SAFETY: stores exactly the `n` halfwords of `buf`, in order from its start: one
    // halfword if the start is not word-aligned (a `u16` slice is 2-aligned, so after it
    // the pointer is 4-aligned, as STM and STRD require), then whole words for all but a
    // last odd halfword. The remainder count in r1 never lets a store pass the end:
    // the loop stores 32 halfwords only while at least 32 remain, and the tail stores 16,
    // 8, 4, 2, 1 by the bits of the remainder (0..31). Every register written is declared
    // (inputs consumed as clobbered outputs); no stack.
    unsafe {
        core::arch::asm!(
            "tst r0, #2",
            "beq 2f",
            "strh r2, [r0], #2",
            "subs r1, #1",
            "2:",
            "mov r3, r2",
            "mov r4, r2",
            "mov r5, r2",
            "mov r8, r2",
            "mov r9, r2",
            "mov r10, r2",
            "mov r11, r2",
            "subs r1, #32",
            "blo 4f",
            "3:",
            "stm r0!, {{r2-r5, r8-r11}}",
            "stm r0!, {{r2-r5, r8-r11}}",
            "subs r1, #32",
            "bhs 3b",
            "4:",
            // r1 = remainder − 32; its low five bits are the remainder's.
            "lsls r1, r1, #28", // C = bit 4, N = bit 3
            "it cs",
            "stmcs r0!, {{r2-r5, r8-r11}}",
            "it mi",
            "stmmi r0!, {{r2-r5}}",
            "lsls r1, r1, #2", // C = bit 2, N = bit 1
            "it cs",
            "strdcs r2, r3, [r0], #8",
            "it mi",
            "strmi r2, [r0], #4",
            "lsls r1, r1, #2", // C = bit 0
            "it cs",
            "strhcs r2, [r0]",
            inout("r0") buf.as_mut_ptr() => _,
            inout("r1") n => _,
            in("r2") v,
            out("r3") _, out("r4") _, out("r5") _,
            out("r8") _, out("r9") _, out("r10") _, out("r11") _,
            options(nostack),
        );
    }
}

/// ARMv6-M (Cortex-M0/M0+): STMIA takes only r0–r7 and writes back; r6 and r7 (which
/// Rust reserves) are saved in r8/r9 for the duration, so 6 value registers: 12 pixels a
/// store, 48 per turn: 0.125 instructions a pixel, ~40 fixed.
#[cfg(zk_v6m)]
#[inline(always)]
fn fill_u16_v6m(buf: &mut [u16], value: u16) {
    let n = buf.len();
    if n == 0 {
        return;
    }
    let v = u32::from(value) * 0x1_0001;
    // SAFETY: as for the Thumb-2 kernel: one halfword to reach a word boundary (ARMv6-M
    // faults on unaligned word stores, so every STM after it is word-aligned), then
    // whole words while the remainder count allows, the last odd halfword alone; never
    // past the end. r6 and r7 are restored before the block ends; every other register
    // written is declared. No stack.
    unsafe {
        core::arch::asm!(
            "lsls r3, r0, #31", // C = address bit 1
            "bcc 2f",
            "strh r2, [r0]",
            "adds r0, #2",
            "subs r1, #1",
            "2:",
            "mov r8, r6",
            "mov r9, r7",
            "mov r3, r2",
            "mov r4, r2",
            "mov r5, r2",
            "mov r6, r2",
            "mov r7, r2",
            "subs r1, #48",
            "blo 4f",
            "3:",
            "stm r0!, {{r2-r7}}",
            "stm r0!, {{r2-r7}}",
            "stm r0!, {{r2-r7}}",
            "stm r0!, {{r2-r7}}",
            "subs r1, #48",
            "bhs 3b",
            "4:",
            "adds r1, #36", // remainder − 12, remainder in 0..47
            "bmi 6f",
            "5:",
            "stm r0!, {{r2-r7}}",
            "subs r1, #12",
            "bpl 5b",
            "6:",
            "adds r1, #12", // remainder in 0..11
            "lsls r1, r1, #29", // C = bit 3, N = bit 2
            "bcc 7f",
            "stm r0!, {{r2-r5}}",
            "7:",
            "bpl 8f",
            "stm r0!, {{r2-r3}}",
            "8:",
            "lsls r1, r1, #2", // C = bit 1, N = bit 0
            "bcc 9f",
            "stm r0!, {{r2}}",
            "9:",
            "bpl 20f",
            "strh r2, [r0]",
            "20:",
            "mov r6, r8",
            "mov r7, r9",
            inout("r0") buf.as_mut_ptr() => _,
            inout("r1") n => _,
            in("r2") v,
            out("r3") _, out("r4") _, out("r5") _,
            out("r8") _, out("r9") _,
            options(nostack),
        );
    }
}

// ---- Plain-Rust shapes, for comparison (same results as `fill_u16_portable`).

/// Pairs of halfwords: on ARMv7-M LLVM merges the two stores of a pair into one word
/// store (unaligned word stores are allowed there).
#[inline(never)]
pub fn fill_pairs(buf: &mut [u16], value: u16) {
    let mut chunks = buf.chunks_exact_mut(2);
    for c in &mut chunks {
        c[0] = value;
        c[1] = value;
    }
    chunks.into_remainder().fill(value);
}

/// Blocks of 16 halfwords written from an array.
#[inline(never)]
pub fn fill_chunks16(buf: &mut [u16], value: u16) {
    let block = [value; 16];
    let mut chunks = buf.chunks_exact_mut(16);
    for c in &mut chunks {
        c.copy_from_slice(&block);
    }
    chunks.into_remainder().fill(value);
}

/// Word stores on the aligned middle (`align_to_mut`, unsafe).
#[inline(never)]
pub fn fill_u32(buf: &mut [u16], value: u16) {
    // SAFETY: every bit pattern is a valid u32 and u16.
    let (head, mid, tail) = unsafe { buf.align_to_mut::<u32>() };
    head.fill(value);
    let v = u32::from(value) * 0x1_0001;
    for w in mid {
        *w = v;
    }
    tail.fill(value);
}

/// Doubleword stores on the aligned middle (`align_to_mut`, unsafe).
#[inline(never)]
pub fn fill_u64(buf: &mut [u16], value: u16) {
    // SAFETY: every bit pattern is a valid u64 and u16.
    let (head, mid, tail) = unsafe { buf.align_to_mut::<u64>() };
    head.fill(value);
    let v = u64::from(value) * 0x0001_0001_0001_0001;
    for w in mid {
        *w = v;
    }
    tail.fill(value);
}

/// Eight words a turn on the aligned middle (`[u32; 8]`, unsafe), hoping for STM.
#[inline(never)]
pub fn fill_u32x8(buf: &mut [u16], value: u16) {
    // SAFETY: every bit pattern is a valid u32 and u16; [u32; 8] is 4-aligned.
    let (head, mid, tail) = unsafe { buf.align_to_mut::<[u32; 8]>() };
    head.fill(value);
    let v = u32::from(value) * 0x1_0001;
    for w in mid {
        *w = [v; 8];
    }
    tail.fill(value);
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec::Vec;

    type F = fn(&mut [u16], u16);

    /// Every shape fills exactly the slice, for all lengths and both alignments.
    #[test]
    fn fills_agree() {
        let shapes: [(&str, F); 7] = [
            ("fill_u16", fill_u16),
            ("portable", fill_u16_portable),
            ("pairs", fill_pairs),
            ("chunks16", fill_chunks16),
            ("u32", fill_u32),
            ("u64", fill_u64),
            ("u32x8", fill_u32x8),
        ];
        for (name, f) in shapes {
            for len in 0..200 {
                for off in 0..4 {
                    let mut b: Vec<u16> = (0..len + off + 3).map(|i| i as u16 ^ 0x5a5a).collect();
                    let mut want = b.clone();
                    want[off..off + len].iter_mut().for_each(|x| *x = 0xbeef);
                    f(&mut b[off..off + len], 0xbeef);
                    assert_eq!(b, want, "{name} len {len} off {off}");
                }
            }
        }
    }
}
