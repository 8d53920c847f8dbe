//! The whole frame's face loop of a cached mesh in one x86-64 assembly loop: the cull
//! scan (a face's area by one SSE2 multiply-add of its corners' x/y words), the face's
//! lit 5-6-5 colour and the small triangle's set-up and rows (`small_x86`'s body), face
//! after face with no Rust between them. Its portable twin is the renderer's own loop
//! (the cull walk, `lit_565` and `fill_small_divide`), which also takes every face this
//! loop leaves to it; a host test draws random meshes both ways.
#![allow(unsafe_code)]
// Elsewhere the renderer never makes the loop.
#![cfg_attr(not(zraster_x86_64), allow(dead_code))]

use super::cull::ScanRegs;
use super::faces::{FaceColor, FacesCounts, FacesStop};
use super::small_x86::{Block, SmallRun};
use super::CachedVertex;
use core::marker::PhantomData;

/// Whether [`FacesX86`] runs the assembly loop (x86-64); elsewhere it is never made.
pub(crate) const FACES_X86_KERNEL: bool = cfg!(zraster_x86_64);

/// ⌈2²³ / 255⌉: `⌊y / 255⌋ = (y · DIV255) >> 23` for every `y` below 2¹⁵ (the colour's
/// channels, whose `y = x >> 15` stays below it).
const DIV255: u16 = 32897;

/// What the loop reads and writes, at the offsets in the comments: `small_x86`'s block,
/// the scan's place and operands, the light, the count of faces drawn.
#[cfg_attr(not(zraster_x86_64), allow(dead_code))]
#[repr(C, align(16))]
struct FacesBlock {
    small: Block, // 0
    /// The next face's byte offset from the end of the faces (negative while one is left).
    pos: isize, // 200
    end: *const [u16; 3], // 208
    cache: *const CachedVertex, // 216
    /// The normals' address less the faces', plus the faces' end: a face's normal at
    /// this plus the face's `pos` (wrapping).
    normals: isize, // 224
    /// The cull mode's dropped areas: `area − lo ≤ span`, unsigned.
    neg_lo: i32, // 232
    span: u32,    // 236
    /// The words 1 and −1.
    sign: u32, // 240
    drawn: u32,   // 244
    light: [i32; 3], // 248
    ambient: i32, // 260
    diffuse: i64, // 264
    /// Each channel's `v · max` (words, high field first), and `HALF` in every lane.
    channels: [u16; 8], // 272
    half: [u32; 4], // 288
    /// The 5- and 6-bit fields' greatest values, 0 and the greatest intensity.
    max: [u32; 4], // 304
    /// rbx and rbp while the loop runs.
    saved: [u64; 2], // 320
    /// ⌈2²³ / 255⌉ in every word, the fields' greatest values (words) and their
    /// places' weights (2¹¹, 2⁵, 1).
    div255: [u16; 8], // 336
    fields: [u16; 8], // 352
    weights: [u16; 8], // 368
    /// The light's components as words (where they fit), then 0.
    light16: [i16; 8], // 384
}

#[cfg(target_pointer_width = "64")]
const _: () = {
    use core::mem::offset_of;
    type B = FacesBlock;
    assert!(offset_of!(B, pos) == 200 && offset_of!(B, end) == 208);
    assert!(offset_of!(B, cache) == 216 && offset_of!(B, normals) == 224);
    assert!(offset_of!(B, neg_lo) == 232 && offset_of!(B, span) == 236);
    assert!(offset_of!(B, sign) == 240 && offset_of!(B, drawn) == 244);
    assert!(offset_of!(B, light) == 248 && offset_of!(B, ambient) == 260);
    assert!(offset_of!(B, diffuse) == 264 && offset_of!(B, channels) == 272);
    assert!(offset_of!(B, half) == 288 && offset_of!(B, max) == 304);
    assert!(offset_of!(B, saved) == 320 && offset_of!(B, div255) == 336);
    assert!(offset_of!(B, fields) == 352 && offset_of!(B, weights) == 368);
    assert!(offset_of!(B, light16) == 384);
};

/// On to `52` with a face of area r8d the cull mode keeps: `back` (`Cull::Back`: a
/// negative area), else `area − lo ≤ span` (unsigned) drops it.
#[cfg(zraster_x86_64)]
#[rustfmt::skip]
macro_rules! faces_x86_drop {
    (back) => {
        concat!(
            "test r8d, r8d\n",
            "js 52f\n",
        )
    };
    (range) => {
        concat!(
            "add r8d, dword ptr [rdi + 232]\n",
            "cmp r8d, dword ptr [rdi + 236]\n",
            "ja 52f\n",
        )
    };
}

/// A lit face's packed 5-6-5 colour into the rows' colour (at 52), as `lit_565`: the
/// face at `rbx + rsi`, its normal at `[rdi + 224] + rsi`; keeps r15, rcx, rdx
/// (the corners' indices); clobbers r8–r11.
#[cfg(zraster_x86_64)]
#[rustfmt::skip]
macro_rules! faces_x86_color {
    (flat) => {
        ""
    };
    // n·L (wrapping) into r9d: each product and their sum in 32 bits.
    (@dot lit) => {
        concat!(
            "movsx r9d, word ptr [r8 + rsi]\n",
            "imul r9d, dword ptr [rdi + 248]\n",
            "movsx r10d, word ptr [r8 + rsi + 2]\n",
            "imul r10d, dword ptr [rdi + 252]\n",
            "add r9d, r10d\n",
            "movsx r10d, word ptr [r8 + rsi + 4]\n",
            "imul r10d, dword ptr [rdi + 256]\n",
            "add r9d, r10d\n",
        )
    };
    // The same by PMADDWD where the light's components fit words (at 384): the first
    // two products summed in one lane, the third in the next (the same wrapping sum).
    (@dot lit16) => {
        concat!(
            "movd xmm0, dword ptr [r8 + rsi]\n",
            "pinsrw xmm0, word ptr [r8 + rsi + 4], 2\n",
            "pmaddwd xmm0, xmmword ptr [rdi + 384]\n",
            "pshufd xmm1, xmm0, 1\n",
            "paddd xmm0, xmm1\n",
            "movd r9d, xmm0\n",
        )
    };
    ($lit:ident) => {
        concat!(
            "mov r8, qword ptr [rdi + 224]\n",
            // n·L, max(0, n·L), the rounded high word of its product with the diffuse
            // weight, plus ambient, clamped to 0 ..= 65535.
            faces_x86_color!(@dot $lit),
            "test r9d, r9d\n",
            "cmovs r9d, dword ptr [rdi + 312]\n",
            "imul r9, qword ptr [rdi + 264]\n",
            "sub r9, -2147483648\n",
            "sar r9, 32\n",
            "add r9d, dword ptr [rdi + 260]\n",
            "cmovs r9d, dword ptr [rdi + 312]\n",
            "cmp r9d, 65535\n",
            "cmova r9d, dword ptr [rdi + 316]\n",
            // The three channels at once (words, high to low): x = i · v·max + HALF
            // (below 2³⁰, `new` checked), ⌊x / (255 · 2¹⁵)⌋ as ⌊(x >> 15) · ⌈2²³/255⌉
            // >> 23⌋ (exact below 2¹⁵ · 2), at most the field's greatest value, then
            // weighed into their places and summed.
            "movd xmm0, r9d\n",
            "pshuflw xmm0, xmm0, 0\n",
            "movdqa xmm1, xmm0\n",
            "pmullw xmm0, xmmword ptr [rdi + 272]\n",
            "pmulhuw xmm1, xmmword ptr [rdi + 272]\n",
            "punpcklwd xmm0, xmm1\n",
            "paddd xmm0, xmmword ptr [rdi + 288]\n",
            "psrld xmm0, 15\n",
            "packssdw xmm0, xmm0\n",
            "pmulhuw xmm0, xmmword ptr [rdi + 336]\n",
            "psrlw xmm0, 7\n",
            "pminsw xmm0, xmmword ptr [rdi + 352]\n",
            "pmaddwd xmm0, xmmword ptr [rdi + 368]\n",
            "pshufd xmm1, xmm0, 1\n",
            "paddd xmm0, xmm1\n",
            "movd dword ptr [rdi + 52], xmm0\n",
        )
    };
}

/// The fused loop (the block in rdi): the scan to the next face not dropped, its
/// colour ([`faces_x86_color`]), set-up and rows (`small_x86_body`), on to the next.
/// Ends with eax 0 at the end of the faces, 1 at a face the set-up refused (its place
/// in the block).
#[cfg(zraster_x86_64)]
#[rustfmt::skip]
macro_rules! faces_x86_body {
    ($color:ident, $cull:ident) => {
        concat!(
            // rbx and rbp (not operands) kept in the block: the faces' end and the
            // cache in them, which the set-up leaves alone.
            "mov qword ptr [rdi + 320], rbx\n",
            "mov qword ptr [rdi + 328], rbp\n",
            "mov rbx, qword ptr [rdi + 208]\n",
            "mov rbp, qword ptr [rdi + 216]\n",
            "mov rsi, qword ptr [rdi + 200]\n",
            "movd xmm4, dword ptr [rdi + 240]\n",
            // The scan: the corners' x/y words; (b − a) · (1, −1) and (c − a) swapped,
            // multiplied and added: (xb − xa)(yc − ya) − (yb − ya)(xc − xa).
            "50:\n",
            "movzx r15d, word ptr [rbx + rsi]\n",
            "movzx edx, word ptr [rbx + rsi + 2]\n",
            "movzx ecx, word ptr [rbx + rsi + 4]\n",
            "movd xmm0, dword ptr [rbp + r15 * 8 + 4]\n",
            "movd xmm1, dword ptr [rbp + rdx * 8 + 4]\n",
            "movd xmm2, dword ptr [rbp + rcx * 8 + 4]\n",
            "psubw xmm1, xmm0\n",
            "psubw xmm2, xmm0\n",
            "pshuflw xmm2, xmm2, 0xe1\n",
            "pmullw xmm1, xmm4\n",
            "pmaddwd xmm1, xmm2\n",
            "movd r8d, xmm1\n",
            faces_x86_drop!($cull),
            "add rsi, 6\n",
            "jnz 50b\n",
            "jmp 58f\n",
            // Drawn: its place kept, its colour, its corners' entries (indices r15,
            // rdx and rcx of the cache at rbp, as the body takes them).
            "52:\n",
            "mov qword ptr [rdi + 200], rsi\n",
            faces_x86_color!($color),
            small_x86_body!(),
            // Drawn (perhaps nothing): counted, the scan's registers back, on.
            "90:\n",
            "inc dword ptr [rdi + 244]\n",
            "mov rsi, qword ptr [rdi + 200]\n",
            "add rsi, 6\n",
            "jnz 50b\n",
            "58:\n",
            "mov qword ptr [rdi + 200], rsi\n",
            "xor eax, eax\n",
            "jmp 59f\n",
            "91:\n",
            "mov eax, 1\n",
            "59:\n",
            "mov rbx, qword ptr [rdi + 320]\n",
            "mov rbp, qword ptr [rdi + 328]\n",
        )
    };
}

/// The fused loop for one draw's faces: its operands, and what it checked once of the
/// faces and the cache (every index below the cache's length, every entry placed with
/// x and y within ±(2¹⁴ − 1) and one more below).
pub(crate) struct FacesX86<'a, C> {
    #[cfg_attr(not(zraster_x86_64), allow(dead_code))]
    b: FacesBlock,
    #[cfg_attr(not(zraster_x86_64), allow(dead_code))]
    faces: &'a [[u16; 3]],
    #[cfg_attr(not(zraster_x86_64), allow(dead_code))]
    cache: &'a [CachedVertex],
    /// The normals the loop reads (those of the faces), kept borrowed.
    normals: PhantomData<&'a [[i16; 3]]>,
    /// A colour for the rows: the one colour of every face, or any (the bits written
    /// then are the lit packed values, which `Raw565` says are a `C`'s bytes).
    #[cfg_attr(not(zraster_x86_64), allow(dead_code))]
    color: C,
    #[cfg_attr(not(zraster_x86_64), allow(dead_code))]
    lit: bool,
}

impl<'a, C: Copy> FacesX86<'a, C> {
    /// The loop for faces `faces` (face `first` on of the mesh) over `cache`, dropped
    /// by the cull mode of `regs` and coloured by `color` (one colour, or lit into a
    /// packed value that is the colour's bytes, every face with its normal); `None`
    /// where it does not take them (elsewhere than x86-64, a colour of another kind, an
    /// index past the cache, an entry unplaced or out of range, a face without normal).
    pub(crate) fn new(
        regs: &ScanRegs<'_>,
        faces: &'a [[u16; 3]],
        cache: &'a [CachedVertex],
        first: usize,
        color: &FaceColor<'a, C>,
    ) -> Option<Self> {
        if !FACES_X86_KERNEL || !indices_below(faces, cache.len()) || !all_placed(cache) {
            return None;
        }
        let mut b = FacesBlock {
            small: Block::default(),
            pos: 0,
            end: faces.as_ptr_range().end,
            cache: cache.as_ptr(),
            normals: 0,
            neg_lo: regs.neg_lo,
            span: regs.span,
            sign: 0xffff_0001,
            drawn: 0,
            light: [0; 3],
            ambient: 0,
            diffuse: 0,
            channels: [0; 8],
            half: [0; 4],
            max: [31, 63, 0, 65535],
            saved: [0; 2],
            div255: [DIV255; 8],
            fields: [31, 63, 31, 0, 0, 0, 0, 0],
            weights: [1 << 11, 1 << 5, 1, 0, 0, 0, 0, 0],
            light16: [0; 8],
        };
        let (color, lit, normals) = match *color {
            FaceColor::Flat(c) => (c, false, &[][..]),
            FaceColor::Lit(block, to_color, Some(_)) => {
                let (light, ambient, diffuse) = block.light_parts();
                let normals = block.normals().get(first..)?;
                // The channels' arithmetic here: `(i·v + HALF)·MUL >> 54` (`lit_565`)
                // with MUL = ⌈2³⁹/255⌉, a division by 255 · 2¹⁵, and i·v + HALF below
                // 2³⁰ for every intensity i up to 65535.
                let (wide, half) = block.wide_channels();
                let v = block.channels;
                let mul = (1u64 << 39) / 255 + 1;
                let small = v
                    .iter()
                    .all(|&v| 65535 * u64::from(v) + u64::from(block.half) < 1 << 30);
                if !small
                    || wide != v.map(|v| u64::from(v) * mul)
                    || half != u64::from(block.half) * mul
                {
                    return None;
                }
                if normals.len() < faces.len() {
                    return None;
                }
                b.normals = (normals.as_ptr() as isize)
                    .wrapping_sub(faces.as_ptr() as isize)
                    .wrapping_add(b.end as isize);
                (b.light, b.ambient, b.diffuse) = (light, ambient, i64::from(diffuse));
                for (w, &l) in b.light16.iter_mut().zip(&light) {
                    *w = l as i16;
                }
                b.channels[..3].copy_from_slice(&v.map(|v| v as u16));
                b.half = [block.half; 4];
                (to_color(0), true, normals)
            }
            FaceColor::Lit(_, _, None) => return None,
        };
        let _ = normals;
        if Self::twin_asked() {
            return None;
        }
        Some(FacesX86 {
            b,
            faces,
            cache,
            normals: PhantomData,
            color,
            lit,
        })
    }

    /// Draw the faces from `*pos` on into `z` and `c` (the buffers of `run`, `Less` with
    /// depth writes), the counts into `counts`, up to the end ([`FacesStop::Scan`],
    /// `*pos` the faces' number) or a drawn face the set-up refuses
    /// ([`FacesStop::Face`], `*pos` the face after it), which is the caller's to draw.
    /// [`FacesStop::Refused`] (nothing drawn) where the buffers are not the block's.
    #[inline(always)]
    pub(crate) fn run(
        &mut self,
        run: &SmallRun,
        z: &mut [u16],
        c: &mut [C],
        pos: &mut usize,
        counts: &mut FacesCounts,
    ) -> FacesStop<'a> {
        let Some((c, bits)) = super::rows::as_u16(c, self.color) else {
            return FacesStop::Refused;
        };
        let Some(small) = run.block_for(z, c) else {
            return FacesStop::Refused;
        };
        let n = self.faces.len();
        if *pos >= n {
            *pos = n;
            return FacesStop::Scan;
        }
        let b = &mut self.b;
        b.small = small;
        b.small.set_color(bits);
        // Faces below 2⁶⁰ (a slice's bytes fit an isize): no wrap.
        b.pos = (*pos as isize - n as isize) * 6;
        b.drawn = 0;
        let refused = fused(&mut self.b, self.lit);
        let b = &self.b;
        let (tested, failed) = b.small.counts();
        counts.tested = counts.tested.wrapping_add(tested);
        counts.failed = counts.failed.wrapping_add(failed);
        counts.drawn = counts.drawn.wrapping_add(b.drawn);
        // The face the loop stopped at (the end when it ran out).
        let k = n - (b.pos.unsigned_abs() / 6);
        if !refused {
            *pos = n;
            return FacesStop::Scan;
        }
        *pos = k + 1;
        let get = |i: u16| self.cache.get(usize::from(i));
        match self.faces.get(k) {
            Some(&[i, j, l]) => match (get(i), get(j), get(l)) {
                (Some(p), Some(q), Some(r)) => FacesStop::Face(k, [p, q, r]),
                _ => FacesStop::Scan,
            },
            None => FacesStop::Scan,
        }
    }
}

/// The fused loop's `asm!` for a colouring and a cull test, the block `$b`, the status
/// into `$status`.
#[cfg(zraster_x86_64)]
macro_rules! faces_x86_asm {
    ($color:ident, $cull:ident, $b:ident, $status:ident) => {
        core::arch::asm!(
            faces_x86_body!($color, $cull),
            in("rdi") &raw mut *$b,
            out("eax") $status,
            out("rcx") _, out("rdx") _, out("rsi") _,
            out("r8") _, out("r9") _, out("r10") _, out("r11") _,
            out("r12") _, out("r13") _, out("r14") _, out("r15") _,
            out("xmm0") _, out("xmm1") _, out("xmm2") _, out("xmm4") _,
            options(nostack),
        )
    };
}

/// The assembly loop on the block `b` (a [`FacesX86`]'s, `lit` its colouring):
/// whether it stopped at a face the set-up refused.
#[inline(always)]
fn fused(b: &mut FacesBlock, lit: bool) -> bool {
    #[cfg(zraster_x86_64)]
    {
        let status: u32;
        // SAFETY: reads and writes `b` (`repr(C)`, the offsets asserted above; the
        // rows' block `small_x86`'s at 0). The scan reads the faces at `end + pos`
        // for pos from the caller's face (below the faces' number) up to −6 by 6:
        // faces of the loop's faces; their indices all lie below the cache's length
        // (`indices_below`, checked when the loop was made over these borrowed faces
        // and cache), so the entries read (`cache + 8·index`, x/y at 4) lie inside the
        // cache. The colour (`lit`) reads the normal at `normals + pos` (the face's
        // address plus the normals' offset from the faces): normal `first + k` of a
        // slice holding one for every face. The
        // set-up and rows are `small_x86`'s body on the corners' entries, with its
        // bounds argument (`SmallRun::run`): `block_for` made the block from the run's
        // (the clip inside the rows) and checked that both buffers reach past the
        // clip's last row. Every area is exact in the words' arithmetic: each entry's
        // x and y lie within −2¹⁴ … 2¹⁴ − 1 (`all_placed`), so differences fit 16 bits
        // and two products' sum 32. Clobbers rax, rcx, rdx, rsi, r8–r15, xmm0–xmm2,
        // xmm4 and the flags; rbx and rbp (which cannot be operands) are saved in the
        // block first and restored last; no stack.
        unsafe {
            // Cull::Back drops the areas 0 ..= i32::MAX: the sign test.
            let back = b.neg_lo == 0 && b.span == i32::MAX as u32;
            // A light whose components fit words: n·L by PMADDWD.
            let narrow = b.light.iter().all(|&l| i16::try_from(l).is_ok());
            match (lit, narrow, back) {
                (true, true, true) => faces_x86_asm!(lit16, back, b, status),
                (true, true, false) => faces_x86_asm!(lit16, range, b, status),
                (true, false, true) => faces_x86_asm!(lit, back, b, status),
                (true, false, false) => faces_x86_asm!(lit, range, b, status),
                (false, _, true) => faces_x86_asm!(flat, back, b, status),
                (false, _, false) => faces_x86_asm!(flat, range, b, status),
            }
        }
        status != 0
    }
    #[cfg(not(zraster_x86_64))]
    {
        let _ = (b, lit);
        false
    }
}

/// Whether every index of `faces` lies below `len` (16 bytes of indices a step by
/// SSE2's saturating subtract on x86-64).
#[cfg_attr(not(zraster_x86_64), allow(dead_code))]
fn indices_below(faces: &[[u16; 3]], len: usize) -> bool {
    let Some(top) = len.checked_sub(1) else {
        return faces.is_empty();
    };
    let top = top.min(usize::from(u16::MAX)) as u16;
    let all = faces.as_flattened();
    #[cfg(not(zraster_x86_64))]
    let over = false;
    #[cfg(zraster_x86_64)]
    let (over, all) = {
        use core::arch::x86_64::*;
        let mut chunks = all.chunks_exact(8);
        // SAFETY: SSE2 is part of x86-64; each load reads the 16 bytes of a chunk of
        // eight `u16`.
        #[allow(unused_unsafe)]
        unsafe {
            let limit = _mm_set1_epi16(top as i16);
            let mut acc = _mm_setzero_si128();
            for c in &mut chunks {
                let v = _mm_loadu_si128(c.as_ptr().cast::<__m128i>());
                acc = _mm_or_si128(acc, _mm_subs_epu16(v, limit));
            }
            let over = _mm_movemask_epi8(_mm_cmpeq_epi8(acc, _mm_setzero_si128())) != 0xffff;
            (over, chunks.remainder())
        }
    };
    !over && all.iter().all(|&i| i <= top)
}

/// Whether every entry of `cache` is placed with x and y within −2¹⁴ … 2¹⁴ − 1 (16
/// bytes a step by SSE2 on x86-64: each word plus 2¹⁴ is then below 2¹⁵).
#[cfg_attr(not(zraster_x86_64), allow(dead_code))]
fn all_placed(cache: &[CachedVertex]) -> bool {
    let fits = |v: &CachedVertex| {
        let (x, y) = (v.xy.x(), v.xy.y());
        (-(1 << 14)..1 << 14).contains(&x) && (-(1 << 14)..1 << 14).contains(&y)
    };
    #[cfg(not(zraster_x86_64))]
    let out = false;
    #[cfg(zraster_x86_64)]
    let (out, cache) = {
        use core::arch::x86_64::*;
        let mut pairs = cache.chunks_exact(2);
        // SAFETY: SSE2 is part of x86-64; each load reads the 16 bytes of two entries
        // (8 bytes each, `repr(C)`).
        #[allow(unused_unsafe)]
        unsafe {
            // Words 2, 3, 6 and 7 are the entries' x and y.
            let bias = _mm_set_epi16(1 << 14, 1 << 14, 0, 0, 1 << 14, 1 << 14, 0, 0);
            let mut acc = _mm_setzero_si128();
            for p in &mut pairs {
                let v = _mm_loadu_si128(p.as_ptr().cast::<__m128i>());
                acc = _mm_or_si128(acc, _mm_add_epi16(v, bias));
            }
            // The sign bits of the x/y words (bytes 5, 7, 13 and 15).
            let out = _mm_movemask_epi8(acc) & 0xa0a0 != 0;
            (out, pairs.remainder())
        }
    };
    !out && cache.iter().all(fits)
}

#[cfg(test)]
std::thread_local! {
    /// Tests only: whether [`FacesX86::new`] refuses every draw (the renderer's own
    /// loop then draws, the twin), and how many draws it took (`render::solid`'s test of
    /// the fused loop).
    pub(crate) static TWIN: core::cell::Cell<(bool, usize)> = const { core::cell::Cell::new((false, 0)) };
}

impl<C> FacesX86<'_, C> {
    /// Tests only: whether the twin is asked for instead ([`TWIN`]); counts the loops
    /// made otherwise.
    #[inline(always)]
    fn twin_asked() -> bool {
        #[cfg(test)]
        return TWIN.with(|t| {
            let (twin, made) = t.get();
            t.set((twin, made + usize::from(!twin)));
            twin
        });
        #[allow(unreachable_code)]
        false
    }
}

#[cfg(test)]
mod tests {
    /// [`DIV255`](super::DIV255) divides every `y` below 2¹⁵ by 255 (as `PMULHUW`, a
    /// 16-bit high word, then 7 more bits).
    #[test]
    fn div255_divides_by_255() {
        for y in 0..1u32 << 15 {
            let high = (y * u32::from(super::DIV255)) >> 16;
            assert_eq!(high >> 7, y / 255, "{y}");
        }
    }
}
