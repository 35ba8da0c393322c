//! `cargo run --release --example suzanne_normal_color`: seed 004 §4.1, normal colour. Run with `--help` for the command line.
shaderlab::lab_example!();
