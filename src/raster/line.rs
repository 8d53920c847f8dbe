//! Line segments in screen space, optionally depth-tested: the edges of the
//! hidden-line and wireframe renderers.

use embedded_graphics::{
    prelude::{DrawTarget, Point, Size},
    primitives::Rectangle,
};

use super::SpanStats;
use super::{Clip, ScreenVertex};
use crate::fixed::{SUBPIXEL, SUBPIXEL_BITS};
use crate::num::div_floor;
use crate::ZBuffer;

/// Draw the segment `a`–`b`: one pixel per column (or per row, for steep lines), the
/// pixel the line crosses at the column's centre, endpoints included.
///
/// With `zbuf`, a pixel is drawn when the line's depth there is at most the stored
/// depth plus `bias` (the line lies on a surface that was drawn into `zbuf`, so it must
/// win ties and small rounding differences); the Z-buffer is not written. Consecutive
/// pixels along the major axis leave as one run (`fill_solid` of a 1-pixel-high or
/// 1-pixel-wide rectangle).
pub(crate) fn draw_line<D: DrawTarget>(
    target: &mut D,
    mut zbuf: Option<&mut ZBuffer<'_>>,
    clip: &Clip,
    a: &ScreenVertex,
    b: &ScreenVertex,
    color: D::Color,
    bias: u16,
) -> Result<SpanStats, D::Error> {
    let mut stats = SpanStats::default();
    if clip.is_empty() {
        return Ok(stats);
    }
    let steep = (b.y() - a.y()).abs() > (b.x() - a.x()).abs();
    // Work in (major, minor) coordinates, major increasing.
    let (mut p, mut q) = if steep {
        ((a.y(), a.x(), a.z()), (b.y(), b.x(), b.z()))
    } else {
        ((a.x(), a.y(), a.z()), (b.x(), b.y(), b.z()))
    };
    if q.0 < p.0 {
        core::mem::swap(&mut p, &mut q);
    }
    let (lo, hi) = if steep {
        (clip.y0, clip.y1)
    } else {
        (clip.x0, clip.x1)
    };
    let first = (p.0 >> SUBPIXEL_BITS).max(lo);
    let last = (q.0 >> SUBPIXEL_BITS).min(hi - 1);
    let d_major = i64::from(q.0) - i64::from(p.0);
    let d_minor = i64::from(q.1) - i64::from(p.1);
    let d_z = i64::from(q.2) - i64::from(p.2);
    // An open run: (major start, minor, length).
    let mut run: Option<(i32, i32, u32)> = None;
    let mut flush = |run: &mut Option<(i32, i32, u32)>, stats: &mut SpanStats| {
        if let Some((m, n, len)) = run.take() {
            let rect = if steep {
                Rectangle::new(Point::new(n, m), Size::new(1, len))
            } else {
                Rectangle::new(Point::new(m, n), Size::new(len, 1))
            };
            stats.runs += 1;
            stats.pixels_written += len;
            target.fill_solid(&rect, color)?;
        }
        Ok(())
    };
    for m in first..=last {
        // Where the line is at this column's centre (clamped to the segment).
        let c = (m * SUBPIXEL + SUBPIXEL / 2).clamp(p.0, q.0);
        let t = i64::from(c) - i64::from(p.0);
        let (minor, z) = if d_major == 0 {
            (i64::from(p.1), i64::from(p.2.min(q.2)))
        } else {
            (
                i64::from(p.1) + div_floor(t * d_minor, d_major),
                i64::from(p.2) + div_floor(t * d_z, d_major),
            )
        };
        let n = (minor >> SUBPIXEL_BITS) as i32;
        let (x, y) = if steep { (n, m) } else { (m, n) };
        let inside = x >= clip.x0 && x < clip.x1 && y >= clip.y0 && y < clip.y1;
        let visible = inside && {
            stats.pixels_tested += 1;
            match zbuf.as_deref_mut() {
                None => true,
                Some(zb) => match zb.depth(x, y) {
                    Some(stored) => ((z + (1 << 15)) >> 16) <= i64::from(stored) + i64::from(bias),
                    None => false,
                },
            }
        };
        match (&mut run, visible) {
            (Some((_, rn, len)), true) if *rn == n => *len += 1,
            (_, true) => {
                flush(&mut run, &mut stats)?;
                run = Some((m, n, 1));
            }
            (_, false) => flush(&mut run, &mut stats)?,
        }
    }
    flush(&mut run, &mut stats)?;
    Ok(stats)
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::{mock_display::MockDisplay, pixelcolor::BinaryColor};

    fn v(x: i32, y: i32) -> ScreenVertex {
        ScreenVertex::new(x * 16 + 8, y * 16 + 8, 0).unwrap()
    }

    const ALL: Clip = Clip {
        x0: 0,
        y0: 0,
        x1: 64,
        y1: 64,
    };

    #[test]
    fn lines_in_every_direction() {
        let mut d = MockDisplay::<BinaryColor>::new();
        draw_line(&mut d, None, &ALL, &v(0, 0), &v(5, 2), BinaryColor::On, 0).unwrap();
        d.assert_pattern(&["##    ", "  ##  ", "    ##"]);
        let mut d = MockDisplay::<BinaryColor>::new();
        let s = draw_line(&mut d, None, &ALL, &v(1, 4), &v(0, 0), BinaryColor::On, 0).unwrap();
        d.assert_pattern(&["# ", "# ", " #", " #", " #"]);
        assert_eq!(s.runs, 2);
        let mut d = MockDisplay::<BinaryColor>::new();
        draw_line(&mut d, None, &ALL, &v(3, 3), &v(3, 3), BinaryColor::On, 0).unwrap();
        d.assert_pattern(&["    ", "    ", "    ", "   #"]);
    }

    #[test]
    fn lines_are_clipped() {
        let mut d = MockDisplay::<BinaryColor>::new();
        let far = ScreenVertex::new(1 << 23, 8, 0).unwrap();
        let s = draw_line(&mut d, None, &ALL, &v(-5, 0), &far, BinaryColor::On, 0).unwrap();
        assert_eq!(s.pixels_written, 64);
    }
}
