//! `cargo run --release --example particles`: Seed 001 §1.5, particle-system vertex shader. Run with `--help` for the command line.
fn main() -> std::process::ExitCode {
    shaderlab::shell::main(shaderlab::labs::PARTICLES)
}
