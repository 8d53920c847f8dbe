//! Face culling: the classic back-face test on a triangle's winding on screen.

/// Which faces are dropped before rasterization, by their winding on screen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum Cull {
    /// Drop faces seen from behind (the default: closed solids).
    #[default]
    Back,
    /// Drop faces seen from the front.
    Front,
    /// Draw both sides.
    None,
}
impl Cull {
    /// Is a triangle with twice-signed *screen* area `area` ([`signed_area`](crate::signed_area) of y-down
    /// screen coordinates) dropped? Front faces have negative screen area (they are
    /// counter-clockwise with y up). Zero area always is dropped.
    #[inline]
    pub fn drops(self, area: i64) -> bool {
        match self {
            Cull::Back => area >= 0,
            Cull::Front => area <= 0,
            Cull::None => area == 0,
        }
    }
}
