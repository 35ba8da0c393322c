//! `cargo run --release --example phong_vertex`: Seed 001 §1.7, modified Phong per vertex. Run with `--help` for the command line.
fn main() -> std::process::ExitCode {
    shaderlab::shell::main(shaderlab::labs::PHONG_VERTEX)
}
