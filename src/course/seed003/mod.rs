//! Seed 003, LETI lab 5: a Bézier strip with specular light and a fly camera.

pub mod specular_strip;
