//! `cargo run --release --example uniform_arrays`: Seed 001 §1.2: uniform vectors and arrays. Run with `--help` for the command line.
shaderlab::lab_example!();
