//! The textured test cube: −1..1 (scale 1/16384), four vertices a face so that each
//! face carries the whole texture (shared by the texture and shader tests).

use zraster::texture::MeshUv;

/// A cube spanning −1..1 (scale 1/16384), four vertices a face so that each face has
/// its own texture coordinates: the whole texture on each face, upright as seen from
/// outside (v down the image: the face's top edge at v = 0).
pub const S: i16 = 16384;
pub const T: i16 = 4096; // one texture in Q12
pub const CUBE_POSITIONS: [[i16; 3]; 24] = [
    // front (z = +1): bottom left, bottom right, top right, top left as seen from +z
    [-S, -S, S],
    [S, -S, S],
    [S, S, S],
    [-S, S, S],
    // back (z = −1), seen from −z
    [S, -S, -S],
    [-S, -S, -S],
    [-S, S, -S],
    [S, S, -S],
    // right (x = +1), seen from +x
    [S, -S, S],
    [S, -S, -S],
    [S, S, -S],
    [S, S, S],
    // left (x = −1), seen from −x
    [-S, -S, -S],
    [-S, -S, S],
    [-S, S, S],
    [-S, S, -S],
    // top (y = +1), seen from +y
    [-S, S, S],
    [S, S, S],
    [S, S, -S],
    [-S, S, -S],
    // bottom (y = −1), seen from −y
    [-S, -S, -S],
    [S, -S, -S],
    [S, -S, S],
    [-S, -S, S],
];
pub const CUBE_UVS: [MeshUv; 24] = {
    let face = [[0, T], [T, T], [T, 0], [0, 0]];
    let mut uvs = [[0i16; 2]; 24];
    let mut i = 0;
    while i < 24 {
        uvs[i] = face[i % 4];
        i += 1;
    }
    uvs
};
pub const CUBE_INDICES: [[u16; 3]; 12] = {
    let mut t = [[0u16; 3]; 12];
    let mut f = 0;
    while f < 6 {
        let b = 4 * f as u16;
        t[2 * f] = [b, b + 1, b + 2];
        t[2 * f + 1] = [b, b + 2, b + 3];
        f += 1;
    }
    t
};
