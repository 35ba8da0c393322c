//! `cargo run --release --example particles`: Seed 001 §1.5, particle-system vertex shader. Run with `--help` for the command line.
shaderlab::lab_example!();
