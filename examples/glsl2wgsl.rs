//! `cargo run --release --example glsl2wgsl -- FILE`: GLSL to WGSL ([`shaderlab::shell::tools::glsl2wgsl`]).

shaderlab::say_when_exhausted!();

fn main() -> std::process::ExitCode {
    shaderlab::shell::tools::glsl2wgsl::main()
}
