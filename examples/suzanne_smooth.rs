//! `cargo run --release --example suzanne_smooth`: seed 004 §4.3, smooth. Run with `--help` for the command line.
fn main() -> std::process::ExitCode {
    shaderlab::shell::main(shaderlab::labs::SUZANNE_SMOOTH)
}
