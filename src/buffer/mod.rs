//! Caller-owned pixel memory: the 16-bit depth buffer and the colour buffer, each a
//! whole frame or a band of rows, the two together as a [`Frame`], and the band
//! memory of [`Bands`].

mod bands;
mod color;
mod frame;
mod rows;
mod zbuffer;

pub(crate) use bands::bins_for;
pub use bands::{AfterBand, BandBuffers, Bands};
pub use color::ColorBuffer;
pub use frame::Frame;
pub(crate) use rows::Rows;
pub use zbuffer::{DepthTest, ZBuffer};
