//! `cargo run --release --example phong_fragment`: Seed 001 §1.8, modified Phong per fragment. Run with `--help` for the command line.
shaderlab::lab_example!();
