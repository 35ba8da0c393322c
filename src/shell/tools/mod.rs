//! The command's tools besides the labs: `glsl2wgsl` (GLSL to WGSL with naga, and a course's
//! GLSL 1.10 pair as the `legacy` lab translates it) and `bench` (every lab timed offscreen).
//! `shaderlab NAME` and `cargo run --example NAME` both run them.

pub mod bench;
pub mod glsl2wgsl;
