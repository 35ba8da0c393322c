//! The browser build's module: `scripts/web` compiles this example for `wasm32-unknown-unknown`
//! and hands it to wasm-bindgen; the page calls the library's [`shaderlab::shell::web`]
//! exports it carries. Natively it is an empty library (`cargo run --example phong` and the
//! other labs are the native programs).
#[cfg(target_arch = "wasm32")]
pub use shaderlab::shell::web::{course_files, course_state, labs, start, WebApp};
