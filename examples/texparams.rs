//! `cargo run --release --example texparams`: seed 004 §4.6, texture parameters. Run with `--help` for the command line.
shaderlab::lab_example!();
