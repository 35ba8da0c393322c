//! `cargo run --release --example suzanne_texture`: seed 004 §4.4, texture. Run with `--help` for the command line.
shaderlab::lab_example!();
