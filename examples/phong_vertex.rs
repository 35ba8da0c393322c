//! `cargo run --release --example phong_vertex`: Seed 001 §1.7, modified Phong per vertex. Run with `--help` for the command line.
shaderlab::lab_example!();
