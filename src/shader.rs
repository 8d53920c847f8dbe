//! Pixel shaders: user code that colours each pixel of a triangle (being built).
