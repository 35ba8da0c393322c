//! `cargo run --release --example noise`: Exercise 4, simplex noise (`Lab05-4`). Run with `--help` for the command line.
shaderlab::lab_example!();
