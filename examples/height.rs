//! `cargo run --release --example height`: Seed 001 §1.1, custom vertex attribute `height`. Run with `--help` for the command line.
shaderlab::lab_example!();
