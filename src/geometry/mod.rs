//! From model space to screen triangles: the fixed-point vertex transform, projection
//! with outcodes, clipping against the view volume, and face culling.

pub(crate) mod clip;
pub(crate) mod cull;
pub(crate) mod project;
pub(crate) mod transform;
