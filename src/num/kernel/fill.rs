//! The frame clear: a store-multiple loop on Cortex-M, beside its portable twin.
#![allow(unsafe_code)]

/// Fill `buf` with `value`: store-multiple of 10 registers (20 halfwords) at a time on
/// Thumb-2, of 7 on ARMv6-M, eight to a turn; [`fill_u16_portable`] elsewhere. The
/// frame clear takes 0.06 (M4) and 0.09 (M0+) instructions a pixel.
#[inline]
pub(crate) fn fill_u16(buf: &mut [u16], value: u16) {
    #[cfg(all(zraster_thumb, zraster_thumb2))]
    return fill_u16_thumb2(buf, value);
    #[cfg(all(zraster_thumb, zraster_armv6m))]
    return fill_u16_armv6m(buf, value);
    #[allow(unreachable_code)]
    fill_u16_portable(buf, value)
}

/// The portable twin of [`fill_u16`].
#[inline]
pub(crate) fn fill_u16_portable(buf: &mut [u16], value: u16) {
    buf.fill(value);
}

/// [`fill_u16`] for ARMv7-M: eight STMs of 10 registers (160 halfwords) a turn, then
/// by 20, then the remainder by its bits.
#[cfg(all(zraster_thumb, zraster_thumb2))]
#[cfg_attr(zraster_ram_code, link_section = ".data.zraster")]
#[inline(never)]
fn fill_u16_thumb2(buf: &mut [u16], value: u16) {
    let n = buf.len();
    if n == 0 {
        return;
    }
    let v = u32::from(value) * 0x1_0001;
    // SAFETY: stores exactly the `n` halfwords of `buf`, in order from its start. A
    // `u16` slice is 2-aligned: one halfword store first when it is not 4-aligned, after
    // which every word, STRD and STM address is 4-aligned. The loop stores 160 halfwords
    // only while at least 160 remain, the next one 20 while 20 remain; the tail then
    // stores 16, 8, 4, 2 and 1 halfwords by the bits of the remainder (0..=19), so no
    // store passes the end. Every register written is declared; the stack is not touched.
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
            "mov r12, r2",
            "mov lr, r2",
            "subs r1, #160",
            "blo 4f",
            "3:",
            "stm r0!, {{r2-r5, r8-r12, lr}}",
            "stm r0!, {{r2-r5, r8-r12, lr}}",
            "stm r0!, {{r2-r5, r8-r12, lr}}",
            "stm r0!, {{r2-r5, r8-r12, lr}}",
            "stm r0!, {{r2-r5, r8-r12, lr}}",
            "stm r0!, {{r2-r5, r8-r12, lr}}",
            "stm r0!, {{r2-r5, r8-r12, lr}}",
            "stm r0!, {{r2-r5, r8-r12, lr}}",
            "subs r1, #160",
            "bhs 3b",
            "4:",
            "adds r1, #140", // the remainder − 20, the remainder in 0..=159
            "bmi 6f",
            "5:",
            "stm r0!, {{r2-r5, r8-r12, lr}}",
            "subs r1, #20",
            "bpl 5b",
            "6:",
            "adds r1, #20",     // the remainder, in 0..=19
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
            out("r12") _, out("lr") _,
            options(nostack),
        );
    }
}

/// [`fill_u16`] for ARMv6-M: STM takes only r0–r7, so r6 and r7 (reserved by the
/// compiler) are kept in r8 and r9 meanwhile. The main loop ends on an address kept in
/// r10, which frees r1 for a seventh value register: eight STMs (112 halfwords) a turn;
/// then by 48 and 12 (6 value registers, the count back in r1), then the remainder by
/// its bits.
#[cfg(all(zraster_thumb, zraster_armv6m))]
#[cfg_attr(zraster_ram_code, link_section = ".data.zraster")]
#[inline(never)]
fn fill_u16_armv6m(buf: &mut [u16], value: u16) {
    let n = buf.len();
    if n == 0 {
        return;
    }
    let v = u32::from(value) * 0x1_0001;
    // SAFETY: as the Thumb-2 loop: one halfword first to reach a word boundary (ARMv6-M
    // faults on unaligned word stores, and every STM after it is word-aligned), whole
    // words while the remainder allows, the last odd halfword alone; never past the end.
    // The main loop runs only when at least 112 halfwords remain (r10 = the end − 224
    // bytes, not below the start then) and repeats while its address is at most r10;
    // after it, r1 = the halfwords left (0..=111). r6 and r7 are restored before the
    // block ends; every other register written is declared. The stack is not touched.
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
            "subs r1, #112",
            "blo 10f",
            "lsls r1, r1, #1",
            "adds r1, r1, r0",
            "mov r10, r1", // the end − 224 bytes
            "movs r1, r2",
            "11:",
            "stm r0!, {{r1-r7}}",
            "stm r0!, {{r1-r7}}",
            "stm r0!, {{r1-r7}}",
            "stm r0!, {{r1-r7}}",
            "stm r0!, {{r1-r7}}",
            "stm r0!, {{r1-r7}}",
            "stm r0!, {{r1-r7}}",
            "stm r0!, {{r1-r7}}",
            "cmp r0, r10",
            "bls 11b",
            "mov r1, r10",
            "subs r1, r1, r0", // −(bytes left) + 224, even
            "asrs r1, r1, #1",
            "10:",
            "adds r1, #112", // the halfwords left
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
            "adds r1, #36", // remainder − 12, remainder in 0..=47
            "bmi 6f",
            "5:",
            "stm r0!, {{r2-r7}}",
            "subs r1, #12",
            "bpl 5b",
            "6:",
            "adds r1, #12",     // remainder in 0..=11
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
            out("r8") _, out("r9") _, out("r10") _,
            options(nostack),
        );
    }
}

/// `data.fill(value)` for a type of two bytes (and alignment two), through
/// [`fill_u16`]; `false` (nothing written) for other types.
#[inline]
pub(crate) fn fill_as_u16<T: Copy>(data: &mut [T], value: T) -> bool {
    if core::mem::size_of::<T>() != 2 || core::mem::align_of::<T>() < 2 {
        return false;
    }
    // SAFETY: T is two bytes with alignment two (checked above), so `value`'s bytes read
    // as a u16 and `data` viewed as `data.len()` u16s cover exactly the same memory.
    // Each element then holds `value`'s bytes: a valid T (T: Copy has no drop glue).
    let (bits, words) = unsafe {
        (
            core::mem::transmute_copy::<T, u16>(&value),
            core::slice::from_raw_parts_mut(data.as_mut_ptr().cast::<u16>(), data.len()),
        )
    };
    fill_u16(words, bits);
    true
}

/// On-target check of the assembly against its twin, for the bench firmware: fills at
/// every start alignment and length up to `max` (inside `buf`), with guard values
/// around, and compares with the portable fill. Returns the number of cases that
/// differ, counting also those of the vertex transform's multiply-accumulate against
/// its twin (`mac::check_mac_kernel`, 4,096 random cases
/// beside its edge values), which has no entry of its own in the firmware.
pub fn check_fill_kernel(buf: &mut [u16], max: usize) -> usize {
    let mut bad = super::mac::check_mac_kernel(4096);
    let n = buf.len();
    for start in 0..4usize {
        for len in 0..=max {
            if start + len + 1 > n {
                break;
            }
            let value = 0xA5C3 ^ (len as u16);
            buf.fill(0x1234);
            if let Some(s) = buf.get_mut(start..start + len) {
                fill_u16(s, value);
            }
            let ok = buf.iter().enumerate().all(|(i, &v)| {
                if i >= start && i < start + len {
                    v == value
                } else {
                    v == 0x1234
                }
            });
            if !ok {
                bad += 1;
            }
        }
    }
    bad
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::pixelcolor::{BinaryColor, Rgb565, Rgb888};
    use embedded_graphics::prelude::RgbColor;

    #[test]
    fn fill_kernel_matches_its_twin() {
        let mut buf = [0u16; 300];
        assert_eq!(check_fill_kernel(&mut buf, 290), 0);
        let mut a = [7u16; 77];
        let mut b = [7u16; 77];
        fill_u16(&mut a[3..70], 0xBEEF);
        fill_u16_portable(&mut b[3..70], 0xBEEF);
        assert_eq!(a, b);
    }

    #[test]
    fn fill_as_u16_takes_two_byte_types_only() {
        let mut c = [Rgb565::BLACK; 9];
        assert!(fill_as_u16(&mut c, Rgb565::new(3, 9, 27)));
        assert!(c.iter().all(|&p| p == Rgb565::new(3, 9, 27)));
        let mut w = [Rgb888::BLACK; 3];
        assert!(!fill_as_u16(&mut w, Rgb888::WHITE));
        let mut b = [BinaryColor::Off; 4];
        assert!(!fill_as_u16(&mut b, BinaryColor::On));
    }
}
