//! `cargo run --release --example phong`: Exercise 3, Phong per-pixel lighting (`Lab05-3`). Run with `--help` for the command line.
shaderlab::lab_example!();
