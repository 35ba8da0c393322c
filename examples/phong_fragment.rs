//! `cargo run --release --example phong_fragment`: Seed 001 §1.8, modified Phong per fragment. Run with `--help` for the command line.
fn main() -> std::process::ExitCode {
    shaderlab::shell::main(shaderlab::labs::PHONG_FRAGMENT)
}
