//! Caller-owned pixel memory: the 16-bit depth buffer and the colour buffer, each a
//! whole frame or a band of rows.

mod color;
mod zbuffer;

pub use color::ColorBuffer;
pub(crate) use zbuffer::{band_origin, check_dims, row_span};
pub use zbuffer::{DepthTest, ZBuffer};
