//! `cargo run --release --example morph`: Seed 001 §1.4, morphing vertex shader. Run with `--help` for the command line.
shaderlab::lab_example!();
