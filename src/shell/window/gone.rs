//! Whether another program destroyed the window (`xdotool windowclose`), known without winit.
//!
//! winit says so with `WindowEvent::Destroyed`, and its requests about the window fail after it;
//! but a window that is not drawing makes no requests, so winit's event was the only notice,
//! and a window whose `Destroyed` was not seen kept running, unseen. Under X11 the window
//! therefore also watches itself on an X connection of its own ([`watch`]): it selects
//! `StructureNotify` on the window (a selection of its own, which leaves winit's alone) and a
//! thread waits for the server's `DestroyNotify`, then marks the window [`Gone`] and wakes the
//! event loop, whatever the loop is doing. The shared-memory presenter marks it too when the
//! server refuses a frame because the window no longer exists.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use winit::window::Window;

use crate::error::Error;

/// What ends a window another program destroyed.
pub(super) fn error() -> Error {
    Error::Surface("the window was closed or destroyed by another program".into())
}

/// Whether the window is gone, set from any thread (the watch, the presenter) and read by the
/// event loop.
#[derive(Clone, Default)]
pub(super) struct Gone(Arc<AtomicBool>);

impl Gone {
    /// Marks the window gone.
    pub fn set(&self) {
        self.0.store(true, Ordering::SeqCst);
    }

    /// Whether the window is gone.
    pub fn is(&self) -> bool {
        self.0.load(Ordering::SeqCst)
    }
}

/// The watch on the window: ends its thread when dropped.
pub(super) struct Watch {
    #[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
    conn: Arc<x11rb::rust_connection::RustConnection>,
}

impl Drop for Watch {
    fn drop(&mut self) {
        // The thread may be blocked reading the connection: shutting its socket down ends the
        // read. The socket stays open (this holds the connection) until both have let go.
        #[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
        {
            use std::os::fd::AsRawFd;
            // SAFETY: shutdown on a socket that `self.conn` keeps open.
            unsafe {
                libc::shutdown(self.conn.stream().as_raw_fd(), libc::SHUT_RDWR);
            }
        }
    }
}

/// Watches `window` (an X11 window; `None` elsewhere, or where the X server cannot be asked):
/// marks `gone` and calls `wake` once when another program destroys it. A window already gone
/// is marked at once.
pub(super) fn watch(window: &Window, gone: Gone, wake: impl FnOnce() + Send + 'static) -> Option<Watch> {
    #[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
    {
        x11::watch(window, gone, wake)
    }
    #[cfg(not(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android")))))]
    {
        let _ = (window, gone, wake);
        None
    }
}

/// Asks the X server whether `window` still exists (a round trip on a connection of its own):
/// for an error while the window opens, which cannot wait for the watch to hear of it. `true`
/// where it cannot be asked.
pub(super) fn exists(window: &Window) -> bool {
    #[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
    {
        x11::exists(window)
    }
    #[cfg(not(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android")))))]
    {
        let _ = window;
        true
    }
}

#[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
mod x11 {
    use std::sync::Arc;

    use winit::raw_window_handle::{HasWindowHandle, RawWindowHandle};
    use winit::window::Window;
    use x11rb::connection::Connection;
    use x11rb::errors::ReplyError;
    use x11rb::protocol::xproto::{ChangeWindowAttributesAux, ConnectionExt as _, EventMask};
    use x11rb::protocol::{ErrorKind, Event};

    use super::{Gone, Watch};

    /// The X id of `window`, if it is an X11 window.
    fn id(window: &Window) -> Option<u32> {
        match window.window_handle().ok()?.as_raw() {
            RawWindowHandle::Xlib(h) => u32::try_from(h.window).ok(),
            RawWindowHandle::Xcb(h) => Some(h.window.get()),
            _ => None,
        }
    }

    /// Whether `result` is the server's answer that the window does not exist.
    fn no_window<T>(result: &Result<T, ReplyError>) -> bool {
        matches!(result, Err(ReplyError::X11Error(e)) if e.error_kind == ErrorKind::Window)
    }

    pub(super) fn exists(window: &Window) -> bool {
        let Some(id) = id(window) else { return true };
        let Ok((conn, _)) = x11rb::connect(None) else {
            return true;
        };
        conn.get_window_attributes(id)
            .map_or(true, |cookie| !no_window(&cookie.reply()))
    }

    pub(super) fn watch(window: &Window, gone: Gone, wake: impl FnOnce() + Send + 'static) -> Option<Watch> {
        let id = id(window)?;
        let (conn, _) = x11rb::connect(None).ok()?;
        let selected = conn
            .change_window_attributes(
                id,
                &ChangeWindowAttributesAux::new().event_mask(EventMask::STRUCTURE_NOTIFY),
            )
            .ok()?
            .check();
        if no_window(&selected) {
            // Destroyed before it could be watched.
            gone.set();
            wake();
            return None;
        }
        selected.ok()?;
        let conn = Arc::new(conn);
        let watched = conn.clone();
        std::thread::Builder::new()
            .name("shaderlab-window".into())
            .spawn(move || loop {
                match watched.wait_for_event() {
                    Ok(Event::DestroyNotify(e)) if e.window == id => {
                        gone.set();
                        wake();
                        return;
                    }
                    Ok(_) => {}
                    // The watch was dropped (its socket shut down), or the server went away,
                    // which winit reports on its own connection.
                    Err(_) => return,
                }
            })
            .ok()?;
        Some(Watch { conn })
    }
}
