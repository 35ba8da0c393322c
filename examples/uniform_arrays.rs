//! `cargo run --release --example uniform_arrays`: Seed 001 §1.2: uniform vectors and arrays. Run with `--help` for the command line.
fn main() -> std::process::ExitCode {
    shaderlab::shell::main(shaderlab::labs::UNIFORM_ARRAYS)
}
