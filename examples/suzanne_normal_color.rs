//! `cargo run --release --example suzanne_normal_color`: seed 004 §4.1, normal colour. Run with `--help` for the command line.
fn main() -> std::process::ExitCode {
    shaderlab::shell::main(shaderlab::labs::SUZANNE_NORMAL_COLOR)
}
