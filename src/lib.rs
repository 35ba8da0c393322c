//! # shaderlab
//!
//! The five exercises of CMP211 Lab05 ("Shader programming", OpenGL 2.0 / GLSL 1.10 / GLUT),
//! ported to wgpu: position → RGB, normal → RGB, Phong, simplex noise and displacement, on
//! GLUT-exact cube, sphere, torus and teapot meshes, rendered like the original in a window or
//! offscreen.
//!
//! The core is small: [`gpu`] (device), [`mesh`] (GLUT geometry), [`camera`] (GLU matrices),
//! [`shader`] (GLSL loading, diagnostics, reflection), [`offscreen`] (render to an image) and
//! [`effect`] (the shared lab renderer). Each exercise is one module in [`effects`]. The window
//! and command line live in [`app`] and [`cli`].
#![warn(missing_docs)]

pub mod app;
pub mod camera;
pub mod cli;
pub mod effect;
pub mod effects;
pub mod error;
pub mod exact;
pub mod gpu;
pub mod mesh;
pub mod metrics;
pub mod noise;
pub mod offscreen;
pub mod shader;
pub mod tess;

pub use effect::{Effect, Lab, Object, Scene};
pub use error::{Error, Result};
pub use gpu::Gpu;
