//! Panics of dependencies, contained. naga's back ends, wgpu and winit panic on some inputs
//! and states (a bug in them, an X11 window another program destroyed); code that calls them
//! where such a panic must not end the program runs them under [`contained`], which turns a
//! panic into a [`Report`] (its message and where it happened) instead of a crash report on
//! stderr. A panic outside [`contained`] reaches the hook that was in place before, as it would
//! without this module. Used by the shader compiler, [`crate::gpu::Gpu::checked`] and the
//! window (its event loop, its shader compiles, its inspector).

use std::cell::{Cell, RefCell};
use std::panic::{self, AssertUnwindSafe, PanicHookInfo};

use crate::error::Error;

/// A panic that was caught: its message and where in the source it happened.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Report {
    /// What the panic said.
    pub message: String,
    /// The source file, line and column of the panic, when known.
    pub location: Option<(String, u32, u32)>,
}

impl Report {
    /// Whether it is winit's X11 backend failing on a request about a window that no longer
    /// exists: another program destroyed the window (`xdotool windowclose`), which is not a
    /// fault of the program.
    pub fn window_destroyed(&self) -> bool {
        let in_winit_x11 = self.location.as_ref().is_some_and(|(file, _, _)| {
            let file = file.replace('\\', "/");
            file.contains("winit") && file.contains("/x11/")
        });
        // x11rb's error kinds for a window id the server no longer knows (BadWindow,
        // BadDrawable), as winit's unwrap prints them.
        in_winit_x11
            && self.message.contains("X11Error")
            && ["error_kind: Window,", "error_kind: Drawable,"]
                .iter()
                .any(|kind| self.message.contains(kind))
    }

    /// The error that says it: [`Error::Internal`] (without a second "internal error: " where
    /// the panic's message starts so, as `unreachable!` does).
    pub fn into_error(self) -> Error {
        let text = self.to_string();
        Error::Internal(
            text.strip_prefix("internal error: ")
                .map_or(text.clone(), str::to_owned),
        )
    }

    fn of(info: &PanicHookInfo<'_>) -> Report {
        Report {
            message: message(info.payload()),
            location: info.location().map(|l| (l.file().to_owned(), l.line(), l.column())),
        }
    }
}

impl std::fmt::Display for Report {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.location {
            Some((file, line, column)) => write!(f, "{} (at {file}:{line}:{column})", self.message),
            None => f.write_str(&self.message),
        }
    }
}

/// The text a panic's payload carries.
fn message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_owned())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".to_owned())
}

thread_local! {
    /// How many [`contained`] sections this thread is in.
    static CATCHING: Cell<u32> = const { Cell::new(0) };
    /// The last panic the hook saw on this thread inside a [`contained`] section.
    static CAUGHT: RefCell<Option<Report>> = const { RefCell::new(None) };
}

/// Installs, once per process, the hook that keeps a panic inside [`contained`] for its caller
/// and prints nothing, and hands any other panic to the hook that was in place before.
fn install_once() {
    static HOOK: std::sync::Once = std::sync::Once::new();
    HOOK.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if CATCHING.with(Cell::get) > 0 {
                CAUGHT.with(|c| *c.borrow_mut() = Some(Report::of(info)));
            } else {
                previous(info);
            }
        }));
    });
}

/// Runs `f`; a panic inside it becomes its [`Report`] (the message and the place it happened)
/// instead of unwinding further.
pub fn contained<T>(f: impl FnOnce() -> T) -> Result<T, Report> {
    install_once();
    CATCHING.with(|c| c.set(c.get() + 1));
    let result = panic::catch_unwind(AssertUnwindSafe(f));
    CATCHING.with(|c| c.set(c.get() - 1));
    result.map_err(|payload| {
        let text = message(payload.as_ref());
        // The hook's report of this very panic (a panic caught deeper inside `f` may have left
        // an older one): the same message.
        CAUGHT
            .with(|c| c.borrow_mut().take())
            .filter(|r| r.message == text)
            .unwrap_or(Report {
                message: text,
                location: None,
            })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_contained_panic_keeps_its_message_and_place() {
        let line = line!() + 1;
        let report = contained(|| panic!("broken: {}", 42)).unwrap_err();
        assert_eq!(report.message, "broken: 42");
        let (file, at, _) = report.location.clone().expect("a location");
        assert!(file.ends_with("panics.rs"), "{file}");
        assert_eq!(at, line);
        assert!(!report.window_destroyed());
        assert_eq!(contained(|| 7).unwrap(), 7);
    }

    #[test]
    fn only_winits_x11_failures_on_a_missing_window_are_a_destroyed_window() {
        let report = |message: &str, file: &str| Report {
            message: message.to_owned(),
            location: Some((file.to_owned(), 1, 1)),
        };
        let winit = "/root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/winit-0.30.13/src/platform_impl/linux/x11/window.rs";
        // What winit 0.30 says when `xdotool windowclose` destroys the window under it.
        let destroyed = "called `Result::unwrap()` on an `Err` value: X11(X11Error { error_kind: Drawable, \
                         error_code: 9, sequence: 269, bad_value: 2097154, minor_opcode: 0, major_opcode: 14, \
                         extension_name: None, request_name: Some(\"GetGeometry\") })";
        assert!(report(destroyed, winit).window_destroyed());
        let window = destroyed.replace(
            "error_kind: Drawable, error_code: 9",
            "error_kind: Window, error_code: 3",
        );
        assert!(report(&window, winit).window_destroyed());
        let other = destroyed.replace(
            "error_kind: Drawable, error_code: 9",
            "error_kind: Alloc, error_code: 11",
        );
        assert!(
            !report(&other, winit).window_destroyed(),
            "out of server memory is no closed window"
        );
        assert!(!report("index out of bounds", winit).window_destroyed());
        assert!(!report(destroyed, "src/shell/window/mod.rs").window_destroyed());
    }
}
