//! Filling screen triangles through the Z-buffer into any [`DrawTarget`].
//!
//! The per-pixel work is Catmull's Z-buffer algorithm and nothing more: step the depth (one
//! add), compare with the stored depth, store it. Pixels that pass leave as horizontal
//! runs, one `fill_solid` per run (or one `fill_contiguous` for shaded runs), already
//! clipped to the target's bounding box.

use embedded_graphics::{
    pixelcolor::PixelColor,
    prelude::{DrawTarget, Point, Size},
    primitives::Rectangle,
};

use crate::num::kernel::CachedVertex;
use crate::raster::{Clip, DepthRows, Plane, ScreenVertex, Setup, SpanStats};
use crate::shade::{Intensity, Material};
pub(crate) mod blend;
mod small;
mod span;

use crate::state::{Dynamic, RenderState};
use crate::{ColorBuffer, DepthTest, DrawError, ZBuffer};
use small::{fill_small, fill_small_cached, Buffers};
pub(crate) use span::flat_span;

/// `$body` with `$pass` bound to the comparison of depth test `$test`, in one arm per
/// test so that each gets its own copy of the loop in `$body` (the comparison is a
/// constant there); `$never` for [`DepthTest::Never`], where nothing passes.
macro_rules! per_depth_test {
    ($test:expr, $never:expr, |$pass:ident| $body:expr) => {
        match $test {
            DepthTest::Less => {
                let $pass = |f: u16, s: u16| DepthTest::Less.passes(f, s);
                $body
            }
            DepthTest::LessEqual => {
                let $pass = |f: u16, s: u16| DepthTest::LessEqual.passes(f, s);
                $body
            }
            DepthTest::Greater => {
                let $pass = |f: u16, s: u16| DepthTest::Greater.passes(f, s);
                $body
            }
            DepthTest::Equal => {
                let $pass = |f: u16, s: u16| DepthTest::Equal.passes(f, s);
                $body
            }
            DepthTest::Always => {
                let $pass = |_: u16, _: u16| true;
                $body
            }
            DepthTest::Never => $never,
        }
    };
}

// After `per_depth_test!`, which it uses.
mod textured;
pub use textured::UvMode;
pub(crate) use textured::{fill_textured_buffers, fill_textured_runs, TexCorners};

/// The pixels both the target and the Z-buffer hold.
pub(crate) fn clip_of<D: DrawTarget>(target: &D, zbuf: &ZBuffer<'_>) -> Clip {
    let (r0, r1) = zbuf.row_range();
    let z = Clip {
        x0: 0,
        y0: r0,
        x1: zbuf.width() as i32,
        y1: r1,
    };
    Clip::from_rect(&target.bounding_box()).intersect(z)
}

/// Fill a screen triangle with a flat colour, depth-tested against `zbuf`. The only
/// error is the target's ([`DrawError::Target`]).
///
/// Either winding is drawn (cull beforehand with [`Facing`](crate::Facing)); a
/// zero-area triangle draws nothing. The triangle is clipped to the target's bounding
/// box and to the rows and columns the Z-buffer holds. Coverage follows pixel centres
/// and the top-left rule, so a mesh's shared edges are covered exactly once.
///
/// ```
/// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::BinaryColor};
/// use zraster::{fill_triangle, ScreenVertex, ZBuffer};
///
/// let v = |x, y| ScreenVertex::from_pixels(x, y, 100).unwrap();
/// let mut display = MockDisplay::<BinaryColor>::new();
/// let mut depth = [0u16; 64 * 64];
/// let mut zbuf = ZBuffer::new(&mut depth, 64, 64)?;
/// zbuf.clear();
/// fill_triangle(&mut display, &mut zbuf, &[v(0, 0), v(4, 0), v(0, 4)], BinaryColor::On).unwrap();
/// // Centres on the hypotenuse x + y = 4 belong to the triangle right of it (top-left rule).
/// display.assert_pattern(&[
///     "### ",
///     "##  ",
///     "#   ",
/// ]);
/// # Ok::<(), zraster::Error>(())
/// ```
pub fn fill_triangle<D: DrawTarget>(
    target: &mut D,
    zbuf: &mut ZBuffer<'_>,
    tri: &[ScreenVertex; 3],
    color: D::Color,
) -> Result<SpanStats, DrawError<D::Error>> {
    let clip = clip_of(target, zbuf);
    depth_runs::<Dynamic, _>(Some(zbuf), tri, &clip, |y, x0, x1| {
        target.fill_solid(&run_rect(y, x0, x1), color)
    })
    .map_err(DrawError::Target)
}

/// Fill a screen triangle with a material lit at each vertex (`intensity`, Q15, see
/// [`shade`](crate::shade)), interpolated across the face: Gouraud shading. Runs go to
/// the target with `fill_contiguous`; with equal intensities and an undithered material,
/// with `fill_solid`.
pub fn fill_triangle_shaded<D, M>(
    target: &mut D,
    zbuf: &mut ZBuffer<'_>,
    tri: &[ScreenVertex; 3],
    material: M,
    intensity: [Intensity; 3],
) -> Result<SpanStats, DrawError<D::Error>>
where
    D: DrawTarget,
    M: Material<D::Color>,
{
    let clip = clip_of(target, zbuf);
    shade_triangle::<Dynamic, _, _>(target, Some(zbuf), &clip, tri, material, intensity)
        .map_err(DrawError::Target)
}

/// Draw a triangle in `material` with per-vertex intensities, choosing the cheapest
/// way to emit its runs.
pub(crate) fn shade_triangle<S: RenderState, D, M>(
    target: &mut D,
    zbuf: Option<&mut ZBuffer<'_>>,
    clip: &Clip,
    tri: &[ScreenVertex; 3],
    material: M,
    intensity: [Intensity; 3],
) -> Result<SpanStats, D::Error>
where
    D: DrawTarget,
    M: Material<D::Color>,
{
    let uniform = intensity[0] == intensity[1] && intensity[1] == intensity[2];
    if uniform && !M::DITHERED {
        let color = material.shade(intensity[0], 0, 0);
        return depth_runs::<S, _>(zbuf, tri, clip, |y, x0, x1| {
            target.fill_solid(&run_rect(y, x0, x1), color)
        });
    }
    if uniform {
        let i = intensity[0];
        return depth_runs::<S, _>(zbuf, tri, clip, |y, x0, x1| {
            let colors = (x0..x1).map(|x| material.shade(i, x, y));
            target.fill_contiguous(&run_rect(y, x0, x1), colors)
        });
    }
    let Some(plane) = Plane::new(tri, intensity.map(|i| u32::from(i) << 16)) else {
        return Ok(SpanStats::default());
    };
    let (lo, hi) = (
        i64::from(*intensity.iter().min().unwrap_or(&0)) << 16,
        i64::from(*intensity.iter().max().unwrap_or(&0)) << 16,
    );
    let step = plane.step_x_i64();
    depth_runs::<S, _>(zbuf, tri, clip, |y, x0, x1| {
        let start = plane.at_pixel(x0, y).clamp(lo, hi) + (1 << 15);
        let colors = (x0..x1).scan(start, |acc, x| {
            let i = (*acc >> 16).clamp(0, 65535) as u16;
            *acc = acc.saturating_add(step);
            Some(material.shade(i, x, y))
        });
        target.fill_contiguous(&run_rect(y, x0, x1), colors)
    })
}

/// Fill a flat-coloured triangle into a colour buffer and a Z-buffer together: the
/// depth test and the colour write share one loop, with no runs to emit. Gives the same
/// pixels as [`depth_runs`] with `fill_solid` runs.
pub(crate) fn fill_flat_buffered<S: RenderState, C: PixelColor>(
    frame: &mut ColorBuffer<'_, C>,
    zbuf: &mut ZBuffer<'_>,
    clip: &Clip,
    tri: &[ScreenVertex; 3],
    color: C,
) -> SpanStats {
    let mut target = FlatTarget::<C, S>::new(frame, zbuf, clip);
    target.start();
    target.fill(tri.each_ref(), color)
}

/// A colour buffer and a Z-buffer borrowed for a run of flat triangles: what
/// [`fill_flat_buffered`] works out about them (geometry, depth test, clip) is worked
/// out once, not per triangle.
pub(crate) enum FlatTarget<'a, 'z, 'c, C, S, const SPLIT: bool = true> {
    /// Same geometry: one index serves both buffers.
    Fused {
        b: Buffers<'a, 'a, C>,
        test: DepthTest,
        write: bool,
        /// `test` is `Less` with depth writes (the small triangles' kernel's case).
        less: bool,
        /// The render state fixing the depth test, if it does.
        state: core::marker::PhantomData<S>,
    },
    /// Different geometries (or nothing to draw when `clip` is empty).
    Split {
        frame: &'a mut ColorBuffer<'c, C>,
        zbuf: &'a mut ZBuffer<'z>,
        clip: Clip,
    },
}

impl<'a, 'z, 'c, C: PixelColor, S: RenderState, const SPLIT: bool>
    FlatTarget<'a, 'z, 'c, C, S, SPLIT>
{
    /// The target for `frame` and `zbuf` drawn inside `clip`, not yet
    /// [`start`](FlatTarget::start)ed.
    pub(crate) fn new(
        frame: &'a mut ColorBuffer<'c, C>,
        zbuf: &'a mut ZBuffer<'z>,
        clip: &Clip,
    ) -> Self {
        if clip.is_empty() || zbuf.geometry() != frame.geometry() {
            return FlatTarget::Split {
                frame,
                zbuf,
                clip: *clip,
            };
        }
        let (w, _, first_row) = zbuf.geometry();
        let (test, write) = (S::depth_test(zbuf.test()), zbuf.write_enabled());
        FlatTarget::Fused {
            b: Buffers::unstarted(
                zbuf.data_mut(),
                frame.data_mut(),
                usize::from(w),
                first_row,
                *clip,
            ),
            test,
            write,
            less: test == DepthTest::Less && write,
            state: core::marker::PhantomData,
        }
    }

    /// Writes what the small triangles' kernel keeps for the buffers (see
    /// [`Buffers::unstarted`]); until then it leaves every triangle to the general
    /// path. Called once the target is where it stays: [`new`](FlatTarget::new) cannot,
    /// as its value is moved on return (a copy of the block, and its stack).
    #[inline(always)]
    pub(crate) fn start(&mut self) {
        if let FlatTarget::Fused { b, .. } = self {
            b.start();
        }
    }

    /// Fill one triangle in `color`.
    #[inline(always)]
    pub(crate) fn fill(&mut self, tri: [&ScreenVertex; 3], color: C) -> SpanStats {
        let Filled { tested, written } = self.fill_counted(tri, color);
        SpanStats {
            pixels_tested: tested,
            pixels_written: written,
            runs: 0,
        }
    }

    /// [`fill`](FlatTarget::fill) inlined into the caller: in a loop where the target
    /// is a local whose address is never taken, what it works out from the target
    /// alone (the clip's inside-ness, the kernel's operands) is worked out once.
    /// The usual depth test (`Less` with writes) is one test of a flag there, not a
    /// choice among the tests.
    #[inline(always)]
    pub(crate) fn fill_inline(&mut self, tri: [&ScreenVertex; 3], color: C) -> SpanStats {
        if let FlatTarget::Fused { b, less: true, .. } = self {
            return fill_fused::<S, C>(b, DepthTest::Less, true, tri, color);
        }
        let Filled { tested, written } = self.counted(tri, color);
        SpanStats {
            pixels_tested: tested,
            pixels_written: written,
            runs: 0,
        }
    }

    /// [`fill_inline`](FlatTarget::fill_inline) with the corners as the vertex cache
    /// holds them (unmarked entries): read in place by the small triangles' kernel where
    /// it runs, else (and for what it leaves) placed as screen vertices first.
    #[inline(always)]
    pub(crate) fn fill_cached(&mut self, tri: [&CachedVertex; 3], color: C) -> SpanStats {
        if let FlatTarget::Fused { b, less: true, .. } = self {
            if let Some((tested, written)) = fill_small_cached(b, tri, color) {
                return SpanStats {
                    pixels_tested: tested,
                    pixels_written: written,
                    runs: 0,
                };
            }
        }
        let [p, q, r] = tri.map(CachedVertex::placed);
        self.fill_inline([&p, &q, &r], color)
    }

    /// [`fill_cached`](FlatTarget::fill_cached) with what the kernel leaves (all of it
    /// where there is none) to the out-of-line [`fill`](FlatTarget::fill), for loops
    /// that keep one copy of the general fill (the bands').
    #[inline(always)]
    pub(crate) fn fill_cached_or_call(&mut self, tri: [&CachedVertex; 3], color: C) -> SpanStats {
        if let Some(s) = self.kernel_cached(tri, color) {
            return s;
        }
        let [p, q, r] = tri.map(CachedVertex::placed);
        self.fill([&p, &q, &r], color)
    }

    /// The small triangles' kernel on the cache entries `tri`, where it runs and takes
    /// them.
    #[inline(always)]
    fn kernel_cached(&mut self, tri: [&CachedVertex; 3], color: C) -> Option<SpanStats> {
        let FlatTarget::Fused { b, less: true, .. } = self else {
            return None;
        };
        let (tested, written) = fill_small_cached(b, tri, color)?;
        Some(SpanStats {
            pixels_tested: tested,
            pixels_written: written,
            runs: 0,
        })
    }

    /// [`fill`](FlatTarget::fill) returning the two counts it has (a fill into buffers
    /// emits no runs), in registers rather than through memory.
    fn fill_counted(&mut self, tri: [&ScreenVertex; 3], color: C) -> Filled {
        self.counted(tri, color)
    }

    /// The body of [`fill_counted`](FlatTarget::fill_counted).
    #[inline(always)]
    fn counted(&mut self, tri: [&ScreenVertex; 3], color: C) -> Filled {
        let s = match self {
            // The corners stay where they are: no copy of the triangle a call.
            FlatTarget::Fused { b, test, write, .. } => {
                fill_fused::<S, C>(b, *test, *write, tri, color)
            }
            // Without SPLIT (bands: both buffers cut from one band) only an empty clip
            // comes here, and the loop for two geometries is not built.
            FlatTarget::Split { frame, zbuf, clip } if SPLIT => {
                let [p, q, r] = tri;
                fill_split::<S, C>(frame, zbuf, clip, &[*p, *q, *r], color)
            }
            FlatTarget::Split { .. } => SpanStats::default(),
        };
        Filled {
            tested: s.pixels_tested,
            written: s.pixels_written,
        }
    }
}

/// The pixel counts of one [`FlatTarget`] fill: eight bytes, returned in two registers.
#[derive(Clone, Copy)]
pub(crate) struct Filled {
    /// Pixels depth-tested.
    pub(crate) tested: u32,
    /// Pixels written.
    pub(crate) written: u32,
}

/// [`FlatTarget::fill`] into buffers of the same geometry; inlined into it (one call a
/// triangle less) except on ARMv6-M (see docs/tuning.md).
#[cfg_attr(not(zraster_armv6m), inline(always))]
fn fill_fused<S: RenderState, C: Copy>(
    b: &mut Buffers<'_, '_, C>,
    test: DepthTest,
    write: bool,
    tri: [&ScreenVertex; 3],
    color: C,
) -> SpanStats {
    // A constant when the state fixes it: then only its loops are built.
    let test = S::depth_test(test);
    let done = per_depth_test!(test, Some((0, 0)), |pass| fill_small(
        b, tri, color, write, pass
    ));
    if let Some((tested, written)) = done {
        return SpanStats {
            pixels_tested: tested,
            pixels_written: written,
            runs: 0,
        };
    }
    let [p, q, r] = tri;
    let tri = &[*p, *q, *r];
    let Some(setup) = Setup::new(tri) else {
        return SpanStats::default();
    };
    let Some((rows, dz)) = DepthRows::new(tri, &setup) else {
        return SpanStats::default();
    };
    let (clip, w, first_row) = (b.clip, b.width, b.first_row);
    let rows = (&setup, &rows, dz, &clip);
    let (zdata, cdata) = b.parts();
    per_depth_test!(test, SpanStats::default(), |pass| flat_rows_fused(
        zdata, cdata, w, first_row, rows, write, color, pass
    ))
}

/// [`FlatTarget::fill`] into buffers of different geometries.
fn fill_split<S: RenderState, C: PixelColor>(
    frame: &mut ColorBuffer<'_, C>,
    zbuf: &mut ZBuffer<'_>,
    clip: &Clip,
    tri: &[ScreenVertex; 3],
    color: C,
) -> SpanStats {
    if clip.is_empty() {
        return SpanStats::default();
    }
    let Some(setup) = Setup::new(tri) else {
        return SpanStats::default();
    };
    let Some((rows, dz)) = DepthRows::new(tri, &setup) else {
        return SpanStats::default();
    };
    let write = zbuf.write_enabled();
    let rows = (&setup, &rows, dz, clip);
    per_depth_test!(S::depth_test(zbuf.test()), SpanStats::default(), |pass| {
        flat_rows(frame, zbuf, rows, write, color, pass)
    })
}

/// The row loop of [`fill_fused`] for one depth test: one index serves both buffers.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn flat_rows_fused<C: Copy>(
    zdata: &mut [u16],
    cdata: &mut [C],
    w: usize,
    first_row: i32,
    (setup, rows, dz, clip): (&Setup, &DepthRows, u32, &Clip),
    write: bool,
    color: C,
    pass: impl Fn(u16, u16) -> bool,
) -> SpanStats {
    let mut stats = SpanStats::default();
    let mut spans = setup.spans(clip);
    while let Some((y, x0, x1)) = spans.next_span() {
        let acc = rows.at(x0, y);
        let start = (y - first_row) as usize * w + x0 as usize;
        let end = start + (x1 - x0) as usize;
        let (Some(zrow), Some(crow)) = (zdata.get_mut(start..end), cdata.get_mut(start..end))
        else {
            continue;
        };
        let failed = flat_span(zrow, crow, acc, dz, color, write, &pass);
        stats.pixels_tested += (x1 - x0) as u32;
        stats.pixels_written += (x1 - x0) as u32 - failed;
    }
    stats
}

/// The row loop of [`fill_split`] for one depth test.
#[inline(always)]
fn flat_rows<C: PixelColor>(
    frame: &mut ColorBuffer<'_, C>,
    zbuf: &mut ZBuffer<'_>,
    (setup, rows, dz, clip): (&Setup, &DepthRows, u32, &Clip),
    write: bool,
    color: C,
    pass: impl Fn(u16, u16) -> bool,
) -> SpanStats {
    let mut stats = SpanStats::default();
    let mut spans = setup.spans(clip);
    while let Some((y, x0, x1)) = spans.next_span() {
        let acc = rows.at(x0, y);
        let (Some(zrow), Some(crow)) = (zbuf.span_mut(y, x0, x1), frame.span_mut(y, x0, x1)) else {
            continue;
        };
        let failed = flat_span(zrow, crow, acc, dz, color, write, &pass);
        stats.pixels_tested += (x1 - x0) as u32;
        stats.pixels_written += (x1 - x0) as u32 - failed;
    }
    stats
}

/// The 1-pixel-high rectangle of a run.
#[inline]
pub(crate) fn run_rect(y: i32, x0: i32, x1: i32) -> Rectangle {
    Rectangle::new(Point::new(x0, y), Size::new((x1 - x0) as u32, 1))
}

/// Scan-convert `tri` inside `clip`, depth-test every covered pixel against `zbuf`
/// (every pixel passes without one) and call `run(y, x0, x1)` for each horizontal run
/// of passing pixels.
pub(crate) fn depth_runs<S: RenderState, E>(
    zbuf: Option<&mut ZBuffer<'_>>,
    tri: &[ScreenVertex; 3],
    clip: &Clip,
    mut run: impl FnMut(i32, i32, i32) -> Result<(), E>,
) -> Result<SpanStats, E> {
    let mut stats = SpanStats::default();
    if clip.is_empty() {
        return Ok(stats);
    }
    let Some(setup) = Setup::new(tri) else {
        return Ok(stats);
    };
    let Some(zbuf) = zbuf else {
        let mut spans = setup.spans(clip);
        while let Some((y, x0, x1)) = spans.next_span() {
            let n = (x1 - x0) as u32;
            stats.pixels_tested += n;
            stats.pixels_written += n;
            stats.runs += 1;
            run(y, x0, x1)?;
        }
        return Ok(stats);
    };
    let Some((rows, dz)) = DepthRows::new(tri, &setup) else {
        return Ok(stats);
    };
    let write = zbuf.write_enabled();
    per_depth_test!(S::depth_test(zbuf.test()), Ok(stats), |pass| depth_rows(
        zbuf, &setup, &rows, dz, clip, write, pass, run
    ))
}

/// The row loop of [`depth_runs`] for one depth test.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn depth_rows<E>(
    zbuf: &mut ZBuffer<'_>,
    setup: &Setup,
    rows: &DepthRows,
    dz: u32,
    clip: &Clip,
    write: bool,
    pass: impl Fn(u16, u16) -> bool + Copy,
    mut run: impl FnMut(i32, i32, i32) -> Result<(), E>,
) -> Result<SpanStats, E> {
    let mut stats = SpanStats::default();
    let mut spans = setup.spans(clip);
    while let Some((y, x0, x1)) = spans.next_span() {
        let acc = rows.at(x0, y);
        let Some(row) = zbuf.span_mut(y, x0, x1) else {
            continue;
        };
        stats.pixels_tested += (x1 - x0) as u32;
        let mut emit = |a: usize, b: usize| {
            stats.runs += 1;
            stats.pixels_written += (b - a) as u32;
            run(y, x0 + a as i32, x0 + b as i32)
        };
        scan(row, acc, dz, write, pass, &mut emit)?;
    }
    Ok(stats)
}

/// The pixel loop: one add, one compare, one store per pixel; runs of passing pixels
/// go to `emit(first, end)` as offsets into `row`.
#[inline(always)]
fn scan<E>(
    row: &mut [u16],
    mut acc: u32,
    dz: u32,
    write: bool,
    pass: impl Fn(u16, u16) -> bool,
    emit: &mut impl FnMut(usize, usize) -> Result<(), E>,
) -> Result<(), E> {
    let mut open: Option<usize> = None;
    for (i, stored) in row.iter_mut().enumerate() {
        let z = (acc >> 16) as u16;
        acc = acc.wrapping_add(dz);
        if pass(z, *stored) {
            if write {
                *stored = z;
            }
            open.get_or_insert(i);
        } else if let Some(start) = open.take() {
            emit(start, i)?;
        }
    }
    match open {
        Some(start) => emit(start, row.len()),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::span::is_less;
    use super::*;

    /// `is_less` picks out `Less` among the comparisons `per_depth_test!` binds.
    #[test]
    fn is_less_knows_the_less_test() {
        use DepthTest::*;
        for test in [Less, LessEqual, Greater, Equal, Always, Never] {
            let less = per_depth_test!(test, false, |pass| is_less(&pass));
            assert_eq!(less, test == Less, "{test:?}");
        }
    }
}
