//! `cargo run --release --example toon`: Seed 001 §1.6, toon (non-photorealistic) shading. Run with `--help` for the command line.
shaderlab::lab_example!();
