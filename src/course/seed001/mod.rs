//! Seed 001, USTC GLSL (III): twelve exercises on one geometry ([`geometry`]), the GL 1.x light
//! state they read ([`gl_light`]), and the immediate-mode recorder ([`immediate`]).

pub mod geometry;

pub mod gl_light;
pub mod immediate;
pub mod modified_phong;
pub mod tangent_bump;

pub mod bump;
pub mod envmap;
pub mod height;
pub mod morph;
pub mod normmap;
pub mod particles;
pub mod phong_fragment;
pub mod phong_vertex;
pub mod texture;
pub mod toon;
pub mod uniform_arrays;
pub mod wave;

lecture!("001 USTC GLSL (III)", (512, 512));
