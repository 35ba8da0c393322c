//! `cargo run --release --example normmap`: Seed 001 §1.12, normalization cube map. Run with `--help` for the command line.
shaderlab::lab_example!();
