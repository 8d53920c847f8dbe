//! Scenes: several meshes drawn into one frame or one banded display, sharing one
//! depth buffer (being built).
