//! Seed 004, OpenGL III – Basic Shaders: Suzanne ([`stage`]) with normals as colour,
//! textures ([`gl_textures`]) and the three shading models ([`lit`]).

pub mod stage;

pub mod gl_textures;
pub mod lit;
pub mod plain;
pub mod textured;

pub mod suzanne_flat;
pub mod suzanne_gouraud;
pub mod suzanne_normal_color;
pub mod suzanne_normal_matrix;
pub mod suzanne_phong;
pub mod suzanne_smooth;
pub mod suzanne_texture;
pub mod suzanne_texture_color;
pub mod texparams;
