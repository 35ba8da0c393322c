//! `cargo run --release --example bench`: every lab timed offscreen ([`shaderlab::shell::tools::bench`]).

shaderlab::say_when_exhausted!();

fn main() -> std::process::ExitCode {
    shaderlab::shell::tools::bench::main()
}
