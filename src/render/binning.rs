//! Whether a banded draw binned its triangles, and why not: what
//! [`Renderer::binning`](crate::Renderer::binning) reports (the band loop, `band.rs`,
//! sets it).

use crate::Error;

#[cfg(doc)]
use crate::{state::RenderState, BandBuffers, Bands, Renderer};

/// Whether a banded draw sorted its triangles into bins ([`Renderer::binning`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Binning {
    /// No draw into [`Bands`] yet (whole frames need no bins).
    NotBanded,
    /// Binned: each band visited only the triangles that reach it.
    Binned,
    /// Not binned, for this reason: every band walked the whole mesh.
    Off(Unbinned),
}

/// Why a banded draw could not bin its triangles ([`Binning::Off`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Unbinned {
    /// The renderer has no vertex cache ([`Renderer::with_cache`]).
    NoCache,
    /// The mesh has polygon faces, not a triangle list.
    Polygons,
    /// Gouraud shading (binning serves flat colours: flat and Lambert).
    Gouraud,
    /// A dithered colour type (its pattern is drawn through the general path).
    Dithered,
    /// The bin slice is shorter than [`BandBuffers::bins_needed`] asks (an empty one
    /// included).
    BinsTooShort,
    /// More than 250 bands, or more than 65,534 triangles with the bands' chains.
    TooLarge,
}

impl Unbinned {
    /// The error a banded draw returns for this reason under a state that bins or
    /// fails ([`RenderState::BINNED_BANDS`], [`Binned`](crate::state::Binned)): an
    /// [`Error::InvalidParameter`] naming it.
    pub const fn error(self) -> Error {
        Error::InvalidParameter(match self {
            Unbinned::NoCache => "binned bands only: the renderer has no vertex cache",
            Unbinned::Polygons => "binned bands only: the mesh has polygon faces",
            Unbinned::Gouraud => "binned bands only: Gouraud shading does not bin",
            Unbinned::Dithered => "binned bands only: a dithered colour type does not bin",
            Unbinned::BinsTooShort => "binned bands only: the bins are shorter than bins_needed",
            Unbinned::TooLarge => "binned bands only: more than 250 bands or 65,534 triangles",
        })
    }
}

impl core::fmt::Display for Unbinned {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Unbinned::NoCache => f.write_str("no vertex cache"),
            Unbinned::Polygons => f.write_str("the mesh has polygon faces"),
            Unbinned::Gouraud => f.write_str("Gouraud shading"),
            Unbinned::Dithered => f.write_str("a dithered colour type"),
            Unbinned::BinsTooShort => f.write_str("the bin slice is shorter than bins_needed"),
            Unbinned::TooLarge => f.write_str("more than 250 bands or 65,534 triangles"),
        }
    }
}
