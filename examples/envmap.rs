//! `cargo run --release --example envmap`: Seed 001 §1.10, cube-map environment (reflection) map. Run with `--help` for the command line.
shaderlab::lab_example!();
