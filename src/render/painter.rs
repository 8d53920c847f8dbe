//! The depth-sort (painter's) renderer: faces sorted by centroid depth, drawn farthest
//! first, with no Z-buffer.

use super::*;

/// A capacity-bounded list for the depth-sort (painter's) renderer: one entry (8
/// bytes) per face. More faces than `N` is [`Error::CapacityExceeded`].
#[derive(Debug, Default)]
pub struct DepthSort<const N: usize> {
    items: heapless::Vec<(i32, u16), N>,
}
impl<const N: usize> DepthSort<N> {
    /// An empty list.
    pub const fn new() -> Self {
        DepthSort {
            items: heapless::Vec::new(),
        }
    }

    /// The faces in drawing order (farthest first) after the last sort.
    pub fn order(&self) -> impl Iterator<Item = usize> + '_ {
        self.items.iter().map(|&(_, f)| usize::from(f))
    }
}

impl<'m, 'c, M: Copy, S: RenderState> Renderer<'m, 'c, M, S> {
    /// Draw by depth sorting (the painter's algorithm): faces sorted by the
    /// depth of their centroid, drawn farthest first with no Z-buffer. Cheap in RAM,
    /// and wrong exactly in its classic failure cases: cyclic overlap, interpenetration.
    ///
    /// Errors: [`Error::CapacityExceeded`] when the mesh has more than `N` faces.
    pub fn draw_depth_sorted<D, const N: usize>(
        &mut self,
        target: &mut D,
        sort: &mut DepthSort<N>,
    ) -> Result<(), DrawError<D::Error>>
    where
        D: DrawTarget,
        M: Material<D::Color>,
    {
        sort.items.clear();
        let n = self.mesh.face_count();
        if n > N || n > usize::from(u16::MAX) + 1 {
            return Err(Error::CapacityExceeded { capacity: N }.into());
        }
        for f in 0..n {
            let (vs, _) = self.face(f)?;
            // In i128: a face may list any number of vertices, each |z| < 2⁴⁵.
            let mut sum = 0i128;
            for &v in vs {
                let p = self
                    .mesh
                    .positions
                    .get(usize::from(v))
                    .ok_or(Error::IndexOutOfRange {
                        face: f,
                        index: usize::from(v),
                    })?;
                // Clip-space z grows with distance from the eye (for both projections).
                sum += i128::from(self.fixed.apply(p).zw().0);
            }
            // The mean |z| < 2⁴⁵ (clip-space scale): dropping 16 bits keeps the order and
            // fits i32.
            let key = ((sum / vs.len() as i128) >> 16) as i32;
            let _ = sort.items.push((key, f as u16));
        }
        // Farthest (largest z) first; equal depths keep the face order.
        sort.items
            .sort_unstable_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
        let clip = Clip::from_rect(&target.bounding_box());
        let mut pixels = FrameStats::default();
        let first = !self.counted;
        let order = sort.items.iter().map(|&(_, f)| usize::from(f));
        let geometry = self.for_each_triangle(&clip, first, order, |f, mat, tri, lights| {
            let lights = self.corner_lights(f, lights);
            let s = shade_triangle::<S, _, _>(target, None, &clip, tri, mat, lights)
                .map_err(DrawError::Target)?;
            pixels.add_pixels(s);
            Ok(())
        })?;
        self.count(geometry);
        self.stats.add_pixel_counts(&pixels);
        Ok(())
    }
}
