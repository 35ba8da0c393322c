//! `cargo run --release --example suzanne_texture_color`: seed 004 §4.5, texture × colour. Run with `--help` for the command line.
shaderlab::lab_example!();
