//! `cargo run --release --example suzanne_texture`: seed 004 §4.4, texture. Run with `--help` for the command line.
fn main() -> std::process::ExitCode {
    shaderlab::shell::main(shaderlab::labs::SUZANNE_TEXTURE)
}
