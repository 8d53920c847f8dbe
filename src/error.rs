//! The crate's error type.

use core::fmt;

/// Everything that can be wrong with input handed to zraster.
///
/// Drawing errors of the display itself are not in here: functions that draw return the
/// target's own `D::Error` (or [`DrawError`] where both kinds can occur), never a panic.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Error {
    /// A width or height of zero.
    ZeroSize,
    /// A width or height larger than the crate supports (see [`MAX_DIMENSION`](crate::MAX_DIMENSION)).
    TooLarge,
    /// A caller slice is shorter than the dimensions need.
    BufferTooSmall {
        /// Entries the dimensions need.
        needed: usize,
        /// Entries the slice has.
        got: usize,
    },
    /// A coordinate is outside the range its type covers (the guard band).
    OutOfRange,
    /// A floating-point input is NaN or infinite.
    NotFinite,
    /// A face refers to a vertex index that the vertex table does not have.
    IndexOutOfRange {
        /// The face (position in the face table).
        face: usize,
        /// The offending index.
        index: usize,
    },
    /// A face has fewer than three vertices.
    DegenerateFace {
        /// The face (position in the face table).
        face: usize,
    },
    /// A fixed capacity (const generic or caller slice) is too small for the input.
    CapacityExceeded {
        /// The capacity.
        capacity: usize,
    },
    /// A parameter is outside its valid range (for example near ≥ far, or a zero field of view).
    InvalidParameter(&'static str),
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::ZeroSize => f.write_str("width and height must be at least 1"),
            Error::TooLarge => write!(
                f,
                "dimension larger than the supported {} pixels",
                crate::MAX_DIMENSION
            ),
            Error::BufferTooSmall { needed, got } => {
                write!(f, "buffer too small: {needed} entries needed, {got} given")
            }
            Error::OutOfRange => f.write_str("coordinate outside the guard band"),
            Error::NotFinite => f.write_str("NaN or infinite value"),
            Error::IndexOutOfRange { face, index } => {
                write!(
                    f,
                    "face {face} refers to vertex {index}, which does not exist"
                )
            }
            Error::DegenerateFace { face } => {
                write!(f, "face {face} has fewer than three vertices")
            }
            Error::CapacityExceeded { capacity } => {
                write!(f, "fixed capacity of {capacity} exceeded")
            }
            Error::InvalidParameter(what) => write!(f, "invalid parameter: {what}"),
        }
    }
}

impl core::error::Error for Error {}

/// An error from a drawing call: either the input was wrong or the display failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DrawError<E> {
    /// The input was rejected. Parameters (transform, light, buffer sizes) are checked
    /// before anything is drawn; a face table is checked as it is walked, so the faces
    /// before the one named by the error may already be drawn. Call
    /// [`Mesh::validate`](crate::mesh::Mesh::validate) once, when the mesh is built, to
    /// rule that out.
    Input(Error),
    /// The draw target returned an error.
    Target(E),
}

impl<E> From<Error> for DrawError<E> {
    fn from(e: Error) -> Self {
        DrawError::Input(e)
    }
}

/// A drawing call that cannot fail in its target (a [`Frame`](crate::Frame), a
/// [`ColorBuffer`](crate::ColorBuffer)) fails only for its input: `?` turns its error
/// into that [`Error`].
impl From<DrawError<core::convert::Infallible>> for Error {
    fn from(e: DrawError<core::convert::Infallible>) -> Self {
        match e {
            DrawError::Input(e) => e,
            DrawError::Target(never) => match never {},
        }
    }
}

impl<E: fmt::Debug> fmt::Display for DrawError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DrawError::Input(e) => write!(f, "{e}"),
            DrawError::Target(e) => write!(f, "draw target error: {e:?}"),
        }
    }
}

/// The first `n` entries of a caller slice, or [`Error::BufferTooSmall`].
pub(crate) fn prefix_mut<T>(s: &mut [T], n: usize) -> Result<&mut [T], Error> {
    let got = s.len();
    s.get_mut(..n)
        .ok_or(Error::BufferTooSmall { needed: n, got })
}
