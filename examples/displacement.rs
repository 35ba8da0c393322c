//! `cargo run --release --example displacement`: Exercise 5, displacement (`Lab05-5`). Run with `--help` for the command line.
shaderlab::lab_example!();
