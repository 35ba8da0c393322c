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
//!
//! Everything that needs no GPU can be used directly, e.g. GLUT's meshes and the tessellation
//! level `--tess auto` would pick:
//!
//! ```
//! use shaderlab::mesh::Mesh;
//! use shaderlab::{tess, Object};
//!
//! // glutSolidSphere(1, 24, 24): 24 * 23 + 2 vertices, the pole triangles of zero area dropped.
//! let sphere = Mesh::sphere(1.0, 24, 24);
//! assert_eq!((sphere.vertices.len(), sphere.triangle_count()), (554, 1104));
//! // At 5 units in a 360-row window GLUT's 24 slices leave about 0.9 px of silhouette error;
//! // half a pixel needs more.
//! let level = tess::choose_level(Object::Sphere, 5.0, 360, tess::DEFAULT_BUDGET_PX);
//! assert!(level > 24 && tess::silhouette_error_px(Object::Sphere, level, 5.0, 360) <= 0.5);
//! ```
#![warn(missing_docs)]

pub mod app;
pub mod camera;
pub mod cli;
pub mod effect;
pub mod effects;
pub mod error;
pub mod exact;
pub mod fsutil;
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
