//! `cargo run --release --example suzanne_flat`: seed 004 §4.7, Flat shading. Run with `--help` for the command line.
fn main() -> std::process::ExitCode {
    shaderlab::shell::main(shaderlab::labs::SUZANNE_FLAT)
}
