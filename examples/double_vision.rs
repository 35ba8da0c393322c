//! `cargo run --release --example double_vision`: Seed 002 (Lecture 12), double vision (`ref002`). Run with `--help` for the command line.
shaderlab::lab_example!();
