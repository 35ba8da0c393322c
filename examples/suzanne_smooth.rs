//! `cargo run --release --example suzanne_smooth`: seed 004 §4.3, smooth. Run with `--help` for the command line.
shaderlab::lab_example!();
