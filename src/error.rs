//! The crate's errors: one family.
//!
//! [`Error`] is what can be wrong with the input; [`DrawError`] is what a drawing call
//! returns, the input error or the draw target's own. Both implement
//! [`Display`](core::fmt::Display) and [`core::error::Error`] (a `DrawError`'s
//! [`source`](core::error::Error::source) is its input error), and `?` turns an
//! `Error` into a `DrawError`, or a `DrawError` of a target that cannot fail (a
//! [`Frame`](crate::Frame)) back into an `Error`.

use core::fmt;

/// Everything that can be wrong with input handed to zraster.
///
/// Drawing errors of the display itself are not in here: functions that draw return the
/// target's own `D::Error` (or [`DrawError`] where both kinds can occur), never a panic.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
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
    /// A look-at camera that does not say which way it looks: the eye is at the target,
    /// or the up vector is zero or parallel to the line of sight (looking straight up or
    /// down with +Y up). See [`Camera::look_at`](crate::camera::Camera::look_at).
    DegenerateView,
    /// Gouraud shading of a mesh without vertex normals (it would be drawn unlit).
    /// [`compute_vertex_normals`](crate::mesh::compute_vertex_normals) makes them.
    MissingNormals,
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
            Error::DegenerateView => f.write_str(
                "degenerate view: eye at the target, or up parallel to the line of sight",
            ),
            Error::MissingNormals => f.write_str("Gouraud shading needs the mesh's vertex normals"),
        }
    }
}

impl core::error::Error for Error {}

/// An error from a drawing call: either the input was wrong or the display failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
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

/// Display targets' errors implement `Debug` (embedded-graphics asks no more), so that is
/// all this needs; the input error is the [`source`](core::error::Error::source).
impl<E: fmt::Debug> core::error::Error for DrawError<E> {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            DrawError::Input(e) => Some(e),
            DrawError::Target(_) => None,
        }
    }
}

impl<E> DrawError<E> {
    /// The input error, if that is what this is.
    pub fn input(&self) -> Option<Error> {
        match self {
            DrawError::Input(e) => Some(*e),
            DrawError::Target(_) => None,
        }
    }

    /// The target's error, if that is what this is.
    pub fn target(self) -> Option<E> {
        match self {
            DrawError::Input(_) => None,
            DrawError::Target(e) => Some(e),
        }
    }
}

/// The first `n` entries of a caller slice, or [`Error::BufferTooSmall`].
pub(crate) fn prefix_mut<T>(s: &mut [T], n: usize) -> Result<&mut [T], Error> {
    let got = s.len();
    s.get_mut(..n)
        .ok_or(Error::BufferTooSmall { needed: n, got })
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::error::Error as _;
    use std::string::ToString;

    #[test]
    fn errors_display_and_chain() {
        assert_eq!(
            Error::BufferTooSmall { needed: 6, got: 5 }.to_string(),
            "buffer too small: 6 entries needed, 5 given"
        );
        assert_eq!(
            Error::MissingNormals.to_string(),
            "Gouraud shading needs the mesh's vertex normals"
        );
        let input: DrawError<u8> = Error::DegenerateView.into();
        assert_eq!(input.to_string(), Error::DegenerateView.to_string());
        assert_eq!(input.input(), Some(Error::DegenerateView));
        let source = input.source().map(|s| s.to_string());
        assert_eq!(source, Some(Error::DegenerateView.to_string()));
        let target: DrawError<u8> = DrawError::Target(7);
        assert_eq!(target.to_string(), "draw target error: 7");
        assert!(target.source().is_none());
        assert_eq!(target.target(), Some(7));
        // Both are `core::error::Error`s: they box into `dyn Error`.
        let boxed: std::boxed::Box<dyn core::error::Error> = std::boxed::Box::new(target);
        assert_eq!(boxed.to_string(), "draw target error: 7");
    }
}
