//! `cargo run --release --example specular_strip`: Seed 003 (LETI lab 5), Bezier strip with specular light (`ref003`). Run with `--help` for the command line.
shaderlab::lab_example!();
