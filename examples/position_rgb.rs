//! `cargo run --release --example position_rgb`: Exercise 1, position → RGB (`Lab05-1`). Run with `--help` for the command line.
shaderlab::lab_example!();
