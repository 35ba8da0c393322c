//! `cargo run --release --example suzanne_phong`: seed 004 §4.9, Phong shading. Run with `--help` for the command line.
shaderlab::lab_example!();
