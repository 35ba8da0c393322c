//! Geometry on the CPU, no GPU code: the general [`mesh`] types, GLUT's solids bit for bit
//! ([`glut`]) and their tessellation levels ([`tess`]), Wavefront OBJ models ([`obj`]), the
//! procedural textures and their mipmaps ([`images`]), the lectures' hand-made meshes
//! ([`shapes`]) and seed 002's twisted square, exactly ([`twist`]).

pub mod glut;
pub mod images;
pub mod mesh;
pub mod obj;
pub mod shapes;
pub mod tess;
pub mod twist;
