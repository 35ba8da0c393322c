//! What SIGINT, SIGTERM and SIGHUP do to files being written.
//!
//! By default a signal ends the process at once, as it would without shaderlab, after removing
//! the temporary files being written (registered as they are made), so that an interrupted run leaves what was
//! there before.
//!
//! Work that must end cleanly instead (a recording that is kept, a set of files moved into
//! place together) runs inside [`defer`]: the first signal is only noted ([`pending`],
//! [`check`]) and optionally wakes an event loop ([`set_wake_fd`]); the work stops at its next
//! check, cleans up, and when the last [`Deferred`] guard is dropped the process ends as the
//! signal asked (its exit status, 128 + N in a shell). A second signal while one is pending
//! ends the process at once, so a stuck program can still be stopped.

use crate::error::{Error, Result};

/// A section in which signals are noted instead of ending the process; see the module docs.
/// Dropping the last one ends the process if a signal came meanwhile.
#[must_use = "signals are deferred only while the guard lives"]
pub struct Deferred(());

/// Notes SIGINT, SIGTERM and SIGHUP instead of dying, until the guard is dropped.
pub fn defer() -> Deferred {
    imp::defer_enter();
    Deferred(())
}

impl Drop for Deferred {
    fn drop(&mut self) {
        if let Some(signal) = imp::defer_leave() {
            end_by(signal);
        }
    }
}

/// The signal that came while deferred, if any.
pub fn pending() -> Option<i32> {
    imp::pending()
}

/// [`Error::Interrupted`] if a signal came while deferred: long loops call it between steps.
pub fn check() -> Result<()> {
    match pending() {
        Some(signal) => Err(Error::Interrupted { signal }),
        None => Ok(()),
    }
}

/// Writes one byte (the signal's number) to `fd` when a signal is deferred, so that a thread
/// blocked reading the other end of a pipe can wake an event loop. `-1`: none.
pub fn set_wake_fd(fd: i32) {
    imp::set_wake_fd(fd);
}

/// Ends the process as `signal` would have (removing registered temporary files first), as if
/// no handler had been installed.
pub fn end_by(signal: i32) -> ! {
    imp::end_by(signal)
}

/// Ends the process at once with `code`, removing registered temporary files first, without
/// running anything else: no destructor and no exit handler, so that a driver thread stuck in
/// work that never ends ([`crate::gpu::hung`]) cannot keep the process from ending.
pub fn exit_now(code: i32) -> ! {
    imp::exit_now(code)
}

/// The name of a signal, for messages: `SIGINT`, `SIGTERM`, `SIGHUP` or `signal N`.
pub fn name(signal: i32) -> String {
    crate::error::signal_name(signal)
}

pub(super) use imp::{register, Registered};

#[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
mod imp {
    use std::ffi::{c_char, CString};
    use std::os::unix::ffi::OsStrExt;
    use std::path::Path;
    use std::sync::atomic::{AtomicI32, AtomicPtr, AtomicUsize, Ordering};
    use std::sync::Once;

    /// Temporary files being written at once that the handler removes (more are written, just
    /// not removed by a signal that ends the process at once; a later run sweeps them).
    const SLOTS: usize = 32;

    /// The paths, as C strings, that the handler unlinks. A path is never freed once it has
    /// been published here: the handler may run on another thread at any moment and read it, so
    /// freeing it would race; a few dozen bytes per file written is the price.
    static TEMPS: [AtomicPtr<c_char>; SLOTS] = [const { AtomicPtr::new(std::ptr::null_mut()) }; SLOTS];
    static INSTALL: Once = Once::new();
    const SIGNALS: [libc::c_int; 3] = [libc::SIGINT, libc::SIGTERM, libc::SIGHUP];
    /// Open [`super::Deferred`] guards.
    static DEFER: AtomicUsize = AtomicUsize::new(0);
    /// The deferred signal (0: none).
    static PENDING: AtomicI32 = AtomicI32::new(0);
    static WAKE: AtomicI32 = AtomicI32::new(-1);

    /// A temporary file known to the handler until this is dropped.
    pub(in crate::fsutil) struct Registered(Option<usize>);

    pub(in crate::fsutil) fn register(path: &Path) -> Registered {
        INSTALL.call_once(install);
        let Ok(c) = CString::new(path.as_os_str().as_bytes()) else {
            return Registered(None);
        };
        let ptr = c.into_raw();
        for (i, slot) in TEMPS.iter().enumerate() {
            if slot
                .compare_exchange(std::ptr::null_mut(), ptr, Ordering::SeqCst, Ordering::SeqCst)
                .is_ok()
            {
                return Registered(Some(i));
            }
        }
        // SAFETY: `ptr` came from `into_raw` above and was never published.
        drop(unsafe { CString::from_raw(ptr) });
        Registered(None)
    }

    impl Drop for Registered {
        fn drop(&mut self) {
            if let Some(i) = self.0 {
                // Leaked on purpose, see TEMPS.
                TEMPS[i].store(std::ptr::null_mut(), Ordering::SeqCst);
            }
        }
    }

    pub(super) fn defer_enter() {
        INSTALL.call_once(install);
        DEFER.fetch_add(1, Ordering::SeqCst);
    }

    /// Leaves a deferred section; the pending signal when it was the last one.
    pub(super) fn defer_leave() -> Option<i32> {
        if DEFER.fetch_sub(1, Ordering::SeqCst) == 1 {
            return pending();
        }
        None
    }

    pub(super) fn pending() -> Option<i32> {
        match PENDING.load(Ordering::SeqCst) {
            0 => None,
            s => Some(s),
        }
    }

    pub(super) fn set_wake_fd(fd: i32) {
        WAKE.store(fd, Ordering::SeqCst);
    }

    fn unlink_temps() {
        for slot in &TEMPS {
            let path = slot.load(Ordering::SeqCst);
            if !path.is_null() {
                // SAFETY: a published path is a valid C string that is never freed.
                unsafe { libc::unlink(path) };
            }
        }
    }

    pub(super) fn end_by(signal: i32) -> ! {
        unlink_temps();
        // SAFETY: plain libc calls with valid arguments. The signal is unblocked in case the
        // caller runs with it blocked; if it is ignored, exit with the status a shell shows.
        unsafe {
            libc::signal(signal, libc::SIG_DFL);
            let mut set: libc::sigset_t = std::mem::zeroed();
            libc::sigemptyset(&mut set);
            libc::sigaddset(&mut set, signal);
            libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, std::ptr::null_mut());
            libc::raise(signal);
            libc::_exit(128 + signal)
        }
    }

    pub(super) fn exit_now(code: i32) -> ! {
        unlink_temps();
        // SAFETY: _exit ends the process; nothing after it runs.
        unsafe { libc::_exit(code) }
    }

    extern "C" fn on_signal(signal: libc::c_int) {
        // Only async-signal-safe calls here: atomics, write, unlink, signal, raise.
        if DEFER.load(Ordering::SeqCst) > 0
            && PENDING
                .compare_exchange(0, signal, Ordering::SeqCst, Ordering::SeqCst)
                .is_ok()
        {
            let fd = WAKE.load(Ordering::SeqCst);
            if fd >= 0 {
                let byte = signal as u8;
                // SAFETY: write of one byte from a valid buffer; a full pipe is ignored.
                unsafe { libc::write(fd, (&byte as *const u8).cast(), 1) };
            }
            return;
        }
        unlink_temps();
        // End the way the signal asks (status, core), as if no handler had been there.
        // SAFETY: plain libc calls with valid arguments.
        unsafe {
            libc::signal(signal, libc::SIG_DFL);
            libc::raise(signal);
        }
    }

    /// Installs the handler for each signal that has its default action (one ignored, as under
    /// `nohup`, or handled by someone else is left alone).
    fn install() {
        for signal in SIGNALS {
            // SAFETY: sigaction with a zeroed struct to read, then a filled one to set.
            unsafe {
                let mut old: libc::sigaction = std::mem::zeroed();
                if libc::sigaction(signal, std::ptr::null(), &mut old) != 0 || old.sa_sigaction != libc::SIG_DFL {
                    continue;
                }
                let mut new: libc::sigaction = std::mem::zeroed();
                new.sa_sigaction = on_signal as extern "C" fn(libc::c_int) as libc::sighandler_t;
                libc::sigemptyset(&mut new.sa_mask);
                libc::sigaction(signal, &new, std::ptr::null_mut());
            }
        }
    }
}

/// Elsewhere: no handler (a stopped process may leave its temporary file, which a later run
/// sweeps), and nothing is ever pending.
#[cfg(not(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android")))))]
mod imp {
    pub(in crate::fsutil) struct Registered;
    pub(in crate::fsutil) fn register(_: &std::path::Path) -> Registered {
        Registered
    }
    pub(super) fn defer_enter() {}
    pub(super) fn defer_leave() -> Option<i32> {
        None
    }
    pub(super) fn pending() -> Option<i32> {
        None
    }
    pub(super) fn set_wake_fd(_: i32) {}
    pub(super) fn end_by(signal: i32) -> ! {
        std::process::exit(128 + signal)
    }
    pub(super) fn exit_now(code: i32) -> ! {
        std::process::exit(code)
    }
}
