//! `cargo run --release --example suzanne_flat`: seed 004 §4.7, Flat shading. Run with `--help` for the command line.
shaderlab::lab_example!();
