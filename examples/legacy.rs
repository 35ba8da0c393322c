//! `cargo run --release --example legacy -- VERT FRAG`: a course's own GLSL 1.10/1.20 shaders, unchanged, on wgpu. Run with `--help` for the command line.
fn main() -> std::process::ExitCode {
    shaderlab::shell::main(shaderlab::labs::LEGACY)
}
