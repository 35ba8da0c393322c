//! `cargo run --release --example wave`: Seed 001 §1.3, wave-motion vertex shader. Run with `--help` for the command line.
shaderlab::lab_example!();
