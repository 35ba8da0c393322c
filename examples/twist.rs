//! `cargo run --release --example twist`: Seed 002 (Lecture 12), 2D twisting (`ref002`). Run with `--help` for the command line.
shaderlab::lab_example!();
