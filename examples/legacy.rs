//! `cargo run --release --example legacy -- VERT FRAG`: a course's own GLSL 1.10/1.20 shaders, unchanged, on wgpu. Run with `--help` for the command line.
shaderlab::lab_example!();
