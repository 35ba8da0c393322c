//! `cargo run --release --example toon`: Seed 001 §1.6, toon (non-photorealistic) shading. Run with `--help` for the command line.
fn main() -> std::process::ExitCode {
    shaderlab::shell::main(shaderlab::labs::TOON)
}
