//! CPU-side data of the lecture ports (SPEC seeds 001–004), no GPU code: the procedural
//! textures and their mipmaps ([`images`]) and Wavefront OBJ models ([`obj`]).

pub mod images;
pub mod obj;
