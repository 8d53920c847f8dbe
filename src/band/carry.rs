//! The colours of faces that reach into the band below, carried to it ([`ColorCarry`])
//! so that they are not lit again, and where the fused band loop runs, their set-ups,
//! so that they are not set up again.

use crate::num::kernel::{BandCarry, KeptStates, CARRY};

/// The colours of the faces that reach into the band below, kept for it. That band
/// walks them in the same order (the chain of the band above, in face order), so a
/// queue read from its start serves. Its own faces are merged in among them, so what
/// it keeps goes into the other half of the store, not over colours not yet taken.
/// Lighting such a face again would cost some 70 instructions on a Cortex-M4. Beside
/// them, the set-ups the fused band loop keeps in the caller's scratch ([`KeptStates`]).
pub(crate) struct ColorCarry<'s, C> {
    colors: [[C; CARRY]; 2],
    /// The half this band reads (what the band above kept); it keeps into the other.
    /// A `bool`, so that indexing the two halves by it needs no bounds test.
    read: bool,
    /// Colours the band above kept; how many this band has taken; how many it keeps.
    filled: usize,
    taken: usize,
    kept: usize,
    states: KeptStates<'s>,
}

impl<'s, C: Copy> ColorCarry<'s, C> {
    /// Colours `fill` at first; set-ups kept in `scratch` where the loop keeps them.
    pub(crate) fn new(fill: C, scratch: &'s mut [u32]) -> Self {
        ColorCarry {
            colors: [[fill; CARRY]; 2],
            read: false,
            filled: 0,
            taken: 0,
            kept: 0,
            states: KeptStates::new(scratch, CARRY),
        }
    }

    /// A new band: what the band before kept is what this one takes.
    pub(crate) fn start_band(&mut self) {
        self.read = !self.read;
        self.filled = self.kept;
        self.taken = 0;
        self.kept = 0;
        self.states.start_band();
    }

    /// The next carried colour, `None` past what was kept.
    #[inline]
    pub(crate) fn take(&mut self) -> Option<C> {
        let i = self.taken;
        self.taken += 1;
        if i < self.filled {
            self.colors.get(usize::from(self.read))?.get(i).copied()
        } else {
            None
        }
    }

    /// The colour the last [`take`](ColorCarry::take) gave, if it gave one.
    pub(crate) fn last_taken(&self) -> Option<C> {
        let i = self.taken.checked_sub(1)?;
        if i < self.filled {
            self.colors.get(usize::from(self.read))?.get(i).copied()
        } else {
            None
        }
    }

    /// The halves and cursors for the band loop in assembly
    /// ([`band_faces_less`](crate::num::kernel::band_faces_less)), which takes and keeps
    /// as [`take`](ColorCarry::take) and [`keep`](ColorCarry::keep) do.
    pub(crate) fn parts(&mut self) -> BandCarry<'_, 's, C> {
        let [a, b] = &mut self.colors;
        let (read, keep) = if self.read { (b, a) } else { (a, b) };
        BandCarry {
            read: &read[..],
            keep: &mut keep[..],
            filled: self.filled,
            taken: &mut self.taken,
            kept: &mut self.kept,
            states: &mut self.states,
        }
    }

    /// Keep `c` for the band below (dropped when full: that face is lit again there).
    #[inline]
    pub(crate) fn keep(&mut self, c: C) {
        let half = self.colors.get_mut(usize::from(!self.read));
        if let Some(slot) = half.and_then(|h| h.get_mut(self.kept)) {
            *slot = c;
            self.kept += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The band below takes the kept colours in order; past the capacity it gets
    /// `None` (and lights those faces again), never another face's colour.
    #[test]
    fn carried_colours_come_back_in_order_up_to_the_capacity() {
        let mut carry = ColorCarry::new(0u16, &mut []);
        for kept in [0, 1, CARRY - 1, CARRY, CARRY + 5] {
            carry.start_band();
            // This band takes what the one before kept (checked below), then keeps its own.
            for i in 0..kept {
                carry.keep(i as u16 + 100);
            }
            carry.start_band();
            for i in 0..kept + 3 {
                let want = (i < kept.min(CARRY)).then_some(i as u16 + 100);
                assert_eq!(carry.take(), want, "kept {kept}, take {i}");
            }
            // What this band keeps goes to the band below, whatever it took.
            carry.keep(7);
            carry.start_band();
            assert_eq!((carry.take(), carry.take()), (Some(7), None));
        }
        // Keeping does not overwrite colours this band has still to take.
        carry.start_band();
        carry.keep(1);
        carry.keep(2);
        carry.start_band();
        assert_eq!(carry.take(), Some(1));
        carry.keep(30);
        carry.keep(40);
        assert_eq!(carry.take(), Some(2));
        carry.start_band();
        assert_eq!((carry.take(), carry.take()), (Some(30), Some(40)));
    }
}
