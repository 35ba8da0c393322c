//! `cargo run --release --example phong_dir`: Seed 002 (Lecture 12), Phong with a directional light (`ref002`). Run with `--help` for the command line.
shaderlab::lab_example!();
