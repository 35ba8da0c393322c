//! `cargo run --release --example normal_rgb`: Exercise 2, normal → RGB (`Lab05-2`). Run with `--help` for the command line.
shaderlab::lab_example!();
