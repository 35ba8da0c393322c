//! # shaderlab
//!
//! Classic OpenGL/GLSL shader lectures ported to wgpu, starting with the five exercises of
//! CMP211 Lab05 ("Shader programming", OpenGL 2.0 / GLSL 1.10 / GLUT): position → RGB,
//! normal → RGB, Phong, simplex noise and displacement, on GLUT-exact cube, sphere, torus and
//! teapot meshes, rendered like the original in a window or offscreen.
//!
//! Layers, each using only those below it (no module reaches up, and there are no import
//! circles):
//! - [`shell`]: the command line, the window and the browser page, each around one
//!   [`shell::session::Session`]; `--screenshot`, `--bench`, `--record`, the tools. It drives any
//!   [`Lab`] through its [`LabEntry`] and never names an exercise.
//! - [`labs`]: one module per exercise and [`labs::ALL`], the one list of labs.
//! - [`lab`]: the contract a lab fulfils ([`Lab`], [`lab::Input`]) and the runner of labs
//!   described as data ([`lab::Recipe`]: a [`lab::Geometry`] drawn with a [`lab::Material`]).
//! - [`legacy`]: a course's own GLSL 1.10/1.20 shaders translated to GLSL 450 (source-mapped).
//! - [`render`]: programs reflected from their shaders, uniform blocks, meshes, textures, frames.
//! - Foundations: [`shader`] (GLSL loading, diagnostics, reflection), [`offscreen`] and [`gpu`]
//!   (targets and the device), [`camera`] (GLU matrices), [`geometry`] ([`mesh`], [`tess`]:
//!   GLUT's solids, OBJ models, pictures), [`params`] (named, ranged values), [`user_files`],
//!   [`fsutil`] (files in and out, never lost), [`memory`] (what the process may still take),
//!   [`panics`] (dependencies' panics contained),
//!   [`error`].
//! - The speed/accuracy yardsticks of the tests and studies, which nothing above uses: [`exact`],
//!   [`metrics`], [`noise`].
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

pub mod camera;
pub mod debug;
pub mod error;
pub mod fsutil;
pub mod geometry;
pub mod gpu;
pub mod lab;
pub mod labs;
pub mod legacy;
pub mod memory;
pub mod offscreen;
pub mod panics;
pub mod params;
pub mod render;
pub mod shader;
pub mod shell;
pub mod study;
pub mod user_files;

pub use error::{Error, Result};
pub use geometry::{mesh, tess};
pub use gpu::Gpu;
pub use lab::{Lab, LabEntry};
pub use study::{exact, metrics, noise};
pub use tess::Object;
