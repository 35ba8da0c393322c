//! CPU-side data of the lecture ports (SPEC seeds 001–004), no GPU code: the procedural
//! textures and their mipmaps ([`images`]), Wavefront OBJ models ([`obj`]) and the lectures'
//! hand-made meshes ([`shapes`]).

pub mod images;
pub mod obj;
pub mod shapes;
