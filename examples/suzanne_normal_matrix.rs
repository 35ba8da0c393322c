//! `cargo run --release --example suzanne_normal_matrix`: seed 004 §4.2, normal matrix. Run with `--help` for the command line.
shaderlab::lab_example!();
