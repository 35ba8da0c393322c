//! `cargo run --release --example position_rgb`: Exercise 1, position → RGB (`Lab05-1`). Run with `--help` for the command line.
fn main() -> std::process::ExitCode {
    shaderlab::shell::main(shaderlab::labs::POSITION_RGB)
}
