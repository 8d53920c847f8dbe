//! Scan conversion: a triangle's rows walked edge by edge with an exact integer DDA.

use super::{signed_area, Clip, ScreenVertex};
use crate::fixed::{SUBPIXEL, SUBPIXEL_BITS};
use crate::num::{div_ceil, div_floor, floor_div32};

/// One edge walked downward: at each row, `x` is the first pixel whose centre lies on
/// or to the right of the edge.
pub(crate) struct EdgeWalk {
    pub(crate) x: i32,
    pub(super) err: i32,
    denom: i32,
    step: i32,
    rem: i32,
}

impl EdgeWalk {
    const EMPTY: EdgeWalk = EdgeWalk {
        x: 0,
        err: 0,
        denom: 1,
        step: 0,
        rem: 0,
    };

    /// The edge from `a` to `b` (`a.1 < b.1`), positioned at pixel row `py`.
    ///
    /// Pixel `px` on row `py` is on or right of the edge when
    /// `(16px + 8 − xa)·dy ≥ (16py + 8 − ya)·dx`, i.e. `px ≥ T/(16dy)` with
    /// `T = (16py + 8 − ya)·dx + (xa − 8)·dy`. The walk keeps `x = ⌈T/(16dy)⌉` and
    /// `err = x·16dy − T ∈ [0, 16dy)`; each row adds `16dx` to `T`.
    pub(super) fn new(a: (i32, i32), b: (i32, i32), py: i32) -> EdgeWalk {
        let dx = i64::from(b.0) - i64::from(a.0);
        let dy = i64::from(b.1) - i64::from(a.1); // 0 < dy ≤ 2²⁵
        let denom = dy * i64::from(SUBPIXEL); // ≤ 2²⁹
        let yc = i64::from(py) * i64::from(SUBPIXEL) + i64::from(SUBPIXEL / 2);
        let t = (yc - i64::from(a.1)) * dx + (i64::from(a.0) - i64::from(SUBPIXEL / 2)) * dy;
        let x = div_ceil(t, denom);
        let err = x * denom - t;
        let step = div_floor(dx, dy);
        let rem = (dx - step * dy) * i64::from(SUBPIXEL);
        EdgeWalk {
            // py lies within the edge's rows, so x lies within its pixel columns (±1):
            // inside ±2²⁰ + 1.
            x: x as i32,
            err: err as i32,
            denom: denom as i32,
            step: step as i32,
            rem: rem as i32,
        }
    }

    /// [`EdgeWalk::new`] for an edge whose coordinates are relative to a local origin
    /// and below 2¹⁴ in magnitude (extents below 2¹³): every product fits `i32`.
    #[inline(always)]
    pub(crate) fn new_small(a: (i32, i32), b: (i32, i32), py: i32) -> EdgeWalk {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1); // |dx| < 2¹⁴, 0 < dy < 2¹⁴
        let denom = dy * SUBPIXEL;
        let yc = py * SUBPIXEL + SUBPIXEL / 2;
        let t = (yc - a.1) * dx + (a.0 - SUBPIXEL / 2) * dy; // < 2²⁹
        let x = -floor_div32(-t, denom); // ⌈t / denom⌉
        let step = floor_div32(dx, dy);
        EdgeWalk {
            x,
            err: x * denom - t,
            denom,
            step,
            rem: (dx - step * dy) * SUBPIXEL,
        }
    }

    /// The walk's state for an assembly loop: `[x, err, rem, denom, step]`.
    #[inline(always)]
    pub(crate) fn parts(&self) -> [i32; 5] {
        [self.x, self.err, self.rem, self.denom, self.step]
    }

    #[inline(always)]
    pub(crate) fn advance(&mut self) {
        self.x += self.step;
        self.err -= self.rem;
        if self.err < 0 {
            self.x += 1;
            self.err += self.denom;
        }
    }
}

/// An edge of a small triangle walked downward in coordinates relative to a local
/// origin at or above-left of its vertices (so every column it meets is ≥ 0): at each
/// row, [`x`](SmallEdge::x) is the first column whose centre lies on or right of the
/// edge. Two forms give the same columns: [`EdgeWalk`] (a DDA, for cores without a
/// divide instruction) and [`EdgeDivide`] (one division a row).
pub(crate) trait SmallEdge {
    /// The edge from `a` to `b` (`a.1 < b.1`, both with extents below [`SMALL`]) at row
    /// `py`, one of the rows whose centres lie in `[a.1, b.1)`.
    fn new(a: (i32, i32), b: (i32, i32), py: i32) -> Self;
    /// The first covered column of the current row.
    fn x(&self) -> i32;
    /// Move to the next row.
    fn advance(&mut self);
}

impl SmallEdge for EdgeWalk {
    #[inline(always)]
    fn new(a: (i32, i32), b: (i32, i32), py: i32) -> Self {
        EdgeWalk::new_small(a, b, py)
    }

    #[inline(always)]
    fn x(&self) -> i32 {
        self.x
    }

    #[inline(always)]
    fn advance(&mut self) {
        EdgeWalk::advance(self)
    }
}

/// [`SmallEdge`] by a division a row: the column is `⌈T/16dy⌉` with `T` as in
/// [`EdgeWalk::new`]. On the edge's rows its x lies between its endpoints', so
/// `T > −16dy`, and `⌈T/16dy⌉ = ⌊(T + 16dy − 1)/16dy⌋` is an unsigned division (below
/// 2²⁷ for extents below 2¹³); each row adds `16dx` to `T`.
pub(crate) struct EdgeDivide {
    pub(crate) t: u32,
    pub(crate) dt: u32,
    pub(crate) d: u32,
}

impl SmallEdge for EdgeDivide {
    #[inline(always)]
    fn new(a: (i32, i32), b: (i32, i32), py: i32) -> Self {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1); // |dx| < 2¹⁴, 0 < dy < 2¹⁴
        let d = dy * SUBPIXEL;
        let yc = py * SUBPIXEL + SUBPIXEL / 2;
        let t = (yc - a.1) * dx + (a.0 - SUBPIXEL / 2) * dy; // > −d, < 2²⁷
        EdgeDivide {
            t: (t + d - 1) as u32,
            dt: (dx * SUBPIXEL) as u32,
            d: d as u32,
        }
    }

    #[inline(always)]
    fn x(&self) -> i32 {
        (self.t / self.d) as i32
    }

    #[inline(always)]
    fn advance(&mut self) {
        self.t = self.t.wrapping_add(self.dt);
    }
}

/// Extents (in 1/16 pixel) below which a triangle takes the all-`i32` setup: 512 pixels.
pub(crate) const SMALL: i32 = 1 << 13;

/// A triangle prepared for scan conversion: vertices sorted top to bottom.
pub(crate) struct Setup {
    v: [(i32, i32); 3],
    /// The middle vertex lies right of the long edge v0→v2.
    mid_right: bool,
    /// Extents below [`SMALL`]: edges are set up in `i32` around a local origin.
    pub(crate) small: bool,
}

impl Setup {
    /// `None` for a zero-area triangle.
    #[inline(always)]
    pub(crate) fn new(tri: &[ScreenVertex; 3]) -> Option<Setup> {
        let mut v = [
            (tri[0].x, tri[0].y),
            (tri[1].x, tri[1].y),
            (tri[2].x, tri[2].y),
        ];
        if v[1].1 < v[0].1 {
            v.swap(0, 1);
        }
        if v[2].1 < v[1].1 {
            v.swap(1, 2);
        }
        if v[1].1 < v[0].1 {
            v.swap(0, 1);
        }
        let xmin = v[0].0.min(v[1].0).min(v[2].0);
        let xmax = v[0].0.max(v[1].0).max(v[2].0);
        let small = xmax - xmin < SMALL && v[2].1 - v[0].1 < SMALL;
        let area = if small {
            let (dx1, dy1) = (v[1].0 - v[0].0, v[1].1 - v[0].1);
            let (dx2, dy2) = (v[2].0 - v[0].0, v[2].1 - v[0].1);
            i64::from(dx1 * dy2 - dx2 * dy1)
        } else {
            signed_area(v[0], v[1], v[2])
        };
        if area == 0 {
            return None;
        }
        // With y down, area > 0 means v0→v1→v2 turns clockwise on screen: v1 is right of v0→v2.
        Some(Setup {
            v,
            mid_right: area > 0,
            small,
        })
    }

    /// The rows of covered pixels inside `clip`, top to bottom.
    #[inline(always)]
    pub(crate) fn spans(&self, clip: &Clip) -> Spans {
        let [v0, v1, v2] = self.v;
        // First row whose centre 16py + 8 is ≥ y: ⌈(y − 8)/16⌉ = (y + 7) >> 4.
        let row = |y: i32| (y + (SUBPIXEL / 2 - 1)) >> SUBPIXEL_BITS;
        let (top, mid, bottom) = (row(v0.1), row(v1.1), row(v2.1));
        let start = top.max(clip.y0);
        let end = if clip.x0 < clip.x1 {
            bottom.min(clip.y1)
        } else {
            start
        };
        // Small triangles: edges in i32 around the pixel corner (ox, oy) at or above-left
        // of every vertex; pixel columns come back shifted by ox / 16.
        let origin = if self.small {
            (
                v0.0.min(v1.0).min(v2.0) & !(SUBPIXEL - 1),
                v0.1 & !(SUBPIXEL - 1),
            )
        } else {
            (0, 0)
        };
        let mut spans = Spans {
            long: EdgeWalk::EMPTY,
            short: EdgeWalk::EMPTY,
            py: start,
            mid,
            end,
            lower: (v1, v2),
            on_lower: false,
            mid_right: self.mid_right,
            small: self.small,
            origin,
            x0: clip.x0,
            x1: clip.x1,
        };
        if start < end {
            spans.long = spans.edge(v0, v2, start);
            if start < mid {
                spans.short = spans.edge(v0, v1, start);
            } else {
                spans.short = spans.edge(v1, v2, start);
                spans.on_lower = true;
            }
        }
        spans
    }
}

/// The rows of a triangle: an iterator of `(y, x0, x1)`, pixel columns `x0..x1`.
pub(crate) struct Spans {
    long: EdgeWalk,
    short: EdgeWalk,
    py: i32,
    mid: i32,
    end: i32,
    lower: ((i32, i32), (i32, i32)),
    on_lower: bool,
    mid_right: bool,
    small: bool,
    origin: (i32, i32),
    x0: i32,
    x1: i32,
}

impl Spans {
    #[inline(always)]
    fn edge(&self, a: (i32, i32), b: (i32, i32), py: i32) -> EdgeWalk {
        if self.small {
            let (ox, oy) = self.origin;
            let mut e = EdgeWalk::new_small(
                (a.0 - ox, a.1 - oy),
                (b.0 - ox, b.1 - oy),
                py - (oy >> SUBPIXEL_BITS),
            );
            e.x += ox >> SUBPIXEL_BITS;
            e
        } else {
            EdgeWalk::new(a, b, py)
        }
    }

    /// The next row with covered pixels inside the clip area.
    #[inline(always)]
    pub(crate) fn next_span(&mut self) -> Option<(i32, i32, i32)> {
        while self.py < self.end {
            let py = self.py;
            if py == self.mid && !self.on_lower {
                let (a, b) = self.lower;
                self.short = self.edge(a, b, py);
                self.on_lower = true;
            }
            let (l, r) = if self.mid_right {
                (self.long.x, self.short.x)
            } else {
                (self.short.x, self.long.x)
            };
            self.long.advance();
            self.short.advance();
            self.py += 1;
            let (x0, x1) = (l.max(self.x0), r.min(self.x1));
            if x0 < x1 {
                return Some((py, x0, x1));
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The two small-edge forms give the same column on every row of random edges
    /// with extents up to the small limit, and both agree with the general walk.
    #[test]
    fn small_edge_forms_agree() {
        let mut rnd = crate::testing::xorshift32(0x1234_5678);
        for i in 0..50_000u32 {
            let mut r = |m: u32| (rnd() % m) as i32;
            // Mostly short edges (the usual case), some up to the limit.
            let span = if i % 8 == 0 { SMALL as u32 } else { 160 };
            let (ax, ay) = (r(span), r(span));
            let (bx, by) = (r(span), ay + 1 + r(span - ay as u32));
            if by >= SMALL {
                continue;
            }
            let (a, b) = ((ax, ay), (bx, by));
            let first = (ay + SUBPIXEL / 2 - 1) >> SUBPIXEL_BITS;
            let last = (by + SUBPIXEL / 2 - 1) >> SUBPIXEL_BITS;
            if first >= last {
                continue;
            }
            let mut walk = <EdgeWalk as SmallEdge>::new(a, b, first);
            let mut div = <EdgeDivide as SmallEdge>::new(a, b, first);
            let mut wide = EdgeWalk::new(a, b, first);
            for py in first..last {
                assert_eq!(walk.x(), div.x(), "{a:?} {b:?} row {py}");
                assert_eq!(wide.x, div.x(), "{a:?} {b:?} row {py}");
                walk.advance();
                div.advance();
                wide.advance();
            }
        }
    }
}
