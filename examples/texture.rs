//! `cargo run --release --example texture`: Seed 001 §1.9, texture mapping with a sampler. Run with `--help` for the command line.
fn main() -> std::process::ExitCode {
    shaderlab::shell::main(shaderlab::labs::TEXTURE)
}
