//! `cargo run --release --example suzanne_normal_matrix`: seed 004 §4.2, normal matrix. Run with `--help` for the command line.
fn main() -> std::process::ExitCode {
    shaderlab::shell::main(shaderlab::labs::SUZANNE_NORMAL_MATRIX)
}
