//! `cargo run --release --example texture`: Seed 001 §1.9, texture mapping with a sampler. Run with `--help` for the command line.
shaderlab::lab_example!();
