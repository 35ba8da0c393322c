//! `cargo run --release --example morph`: Seed 001 §1.4, morphing vertex shader. Run with `--help` for the command line.
fn main() -> std::process::ExitCode {
    shaderlab::shell::main(shaderlab::labs::MORPH)
}
