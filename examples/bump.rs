//! `cargo run --release --example bump`: Seed 001 §1.11, tangent-space bump mapping. Run with `--help` for the command line.
shaderlab::lab_example!();
