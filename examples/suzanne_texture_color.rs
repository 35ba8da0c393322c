//! `cargo run --release --example suzanne_texture_color`: seed 004 §4.5, texture × colour. Run with `--help` for the command line.
fn main() -> std::process::ExitCode {
    shaderlab::shell::main(shaderlab::labs::SUZANNE_TEXTURE_COLOR)
}
