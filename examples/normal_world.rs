//! `cargo run --release --example normal_world`: Seed 002 (Lecture 12), normal as colour in world space (`ref002`). Run with `--help` for the command line.
shaderlab::lab_example!();
