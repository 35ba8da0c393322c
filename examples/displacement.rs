//! `cargo run --release --example displacement`: Exercise 5, displacement (`Lab05-5`). Run with `--help` for the command line.
fn main() -> std::process::ExitCode {
    shaderlab::shell::main(shaderlab::labs::DISPLACEMENT)
}
