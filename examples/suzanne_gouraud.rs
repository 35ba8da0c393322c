//! `cargo run --release --example suzanne_gouraud`: seed 004 §4.8, Gouraud shading. Run with `--help` for the command line.
shaderlab::lab_example!();
