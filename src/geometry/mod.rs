//! Geometry on the CPU, no GPU code: the general [`mesh`] types, GLUT's solids bit for bit
//! ([`glut`]) and their tessellation levels ([`tess`]), Wavefront OBJ models ([`obj`]), the
//! procedural textures and their mipmaps ([`images`]) and the lectures' hand-made meshes
//! ([`shapes`]).

pub mod glut;
pub mod images;
pub mod mesh;
pub mod obj;
pub mod shapes;
pub mod tess;
