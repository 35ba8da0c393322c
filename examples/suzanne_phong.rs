//! `cargo run --release --example suzanne_phong`: seed 004 §4.9, Phong shading. Run with `--help` for the command line.
fn main() -> std::process::ExitCode {
    shaderlab::shell::main(shaderlab::labs::SUZANNE_PHONG)
}
