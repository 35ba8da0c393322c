//! `cargo run --release --example suzanne_gouraud`: seed 004 §4.8, Gouraud shading. Run with `--help` for the command line.
fn main() -> std::process::ExitCode {
    shaderlab::shell::main(shaderlab::labs::SUZANNE_GOURAUD)
}
