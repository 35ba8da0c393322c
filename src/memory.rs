//! The memory this process may still take: the machine's, and under an address-space limit
//! (`ulimit -v`, `prlimit --as`, as containers and shared machines set) what is left of it.
//! Checked before large allocations (a model, a picture, a mesh, a shader's compilation), whose
//! failure would otherwise end the process without a word (Rust aborts on a failed allocation,
//! a driver's compiler crashes).

/// The process's memory now as its bound counts it: mapped (`VmSize`) under an address-space
/// limit, resident (`VmRSS`) otherwise.
pub fn in_use() -> Option<u64> {
    match address_space_limit() {
        Some(_) => proc_kib("/proc/self/status", "VmSize:"),
        None => proc_kib("/proc/self/status", "VmRSS:"),
    }
}

/// The memory this process can still take, if known: the machine's (Linux's `MemAvailable`),
/// or less where the process's address space is limited (`ulimit -v`, `prlimit --as`, as
/// containers and shared machines set), what is left under that limit.
/// `SHADERLAB_TEST_AVAILABLE_MEMORY=BYTES` stands in for the machine's, so that tests can show
/// the check without filling the machine.
pub fn available() -> Option<u64> {
    let machine = match std::env::var("SHADERLAB_TEST_AVAILABLE_MEMORY")
        .ok()
        .and_then(|b| b.parse().ok())
    {
        Some(bytes) => Some(bytes),
        None => proc_kib("/proc/meminfo", "MemAvailable:"),
    };
    match (machine, address_space_left()) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// A `NAME: N kB` line of a /proc file, in bytes.
fn proc_kib(file: &str, name: &str) -> Option<u64> {
    let text = std::fs::read_to_string(file).ok()?;
    let line = text.lines().find(|l| l.starts_with(name))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

/// What is left of the process's address-space limit after what it has mapped now
/// (`VmSize`); none without a limit.
fn address_space_left() -> Option<u64> {
    let limit = address_space_limit()?;
    Some(limit.saturating_sub(proc_kib("/proc/self/status", "VmSize:")?))
}

/// The process's address-space limit (`RLIMIT_AS`: `ulimit -v`, `prlimit --as`), if it has one.
fn address_space_limit() -> Option<u64> {
    #[cfg(target_os = "linux")]
    {
        let mut limit = libc::rlimit {
            rlim_cur: 0,
            rlim_max: 0,
        };
        // SAFETY: getrlimit fills the struct it is given.
        if unsafe { libc::getrlimit(libc::RLIMIT_AS, &mut limit) } != 0 || limit.rlim_cur == libc::RLIM_INFINITY {
            return None;
        }
        Some(limit.rlim_cur)
    }
    #[cfg(not(target_os = "linux"))]
    None
}

/// Refuses, as [`crate::error::Error::Limit`], work that needs about `bytes` of memory when this
/// process may take less ([`available`]); `what` names the work (`"big.png (8192×8192)"`).
pub fn check(what: &str, bytes: u64) -> crate::error::Result<()> {
    use crate::fsutil::human_bytes;
    match available() {
        Some(free) if bytes > free => Err(crate::error::Error::Limit(format!(
            "{what} needs about {} of memory; this process may take {} now (the machine's free memory, within \
             its `ulimit -v` if it has one)",
            human_bytes(bytes),
            human_bytes(free)
        ))),
        _ => Ok(()),
    }
}

/// The binaries' allocator (the system's), which says so and ends the run when an allocation
/// fails, instead of Rust's abort (`memory allocation of N bytes failed`, a core dump, exit
/// status 134): one line, the temporary files being written removed, exit status 1. The checks
/// before large allocations ([`check`]) make it rare; it is the floor under them, for an
/// allocation no estimate foresaw. `shaderlab::lab_example!` and the `shaderlab` command install
/// it: a library leaves the choice of allocator to its program.
#[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
pub struct SayWhenExhausted;

#[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
impl SayWhenExhausted {
    /// Writes the message with `write(2)` alone (nothing may be allocated now) and ends.
    #[cold]
    fn exhausted(size: usize) -> ! {
        let mut digits = [0u8; 20];
        let mut at = digits.len();
        let mut n = size;
        loop {
            at -= 1;
            digits[at] = b'0' + (n % 10) as u8;
            n /= 10;
            if n == 0 {
                break;
            }
        }
        let parts: [&[u8]; 3] = [
            b"shaderlab: error: out of memory: an allocation of ",
            &digits[at..],
            b" bytes failed (the machine's memory, or this process's `ulimit -v`, is used up); \
              draw less: a smaller model, picture, --tess or --size\n",
        ];
        for part in parts {
            // SAFETY: writes initialised bytes to standard error.
            let _ = unsafe { libc::write(2, part.as_ptr().cast(), part.len()) };
        }
        crate::fsutil::signals::exit_now(1)
    }
}

// SAFETY: every call is the system allocator's; a null result ends the process instead of
// returning.
#[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
unsafe impl std::alloc::GlobalAlloc for SayWhenExhausted {
    unsafe fn alloc(&self, layout: std::alloc::Layout) -> *mut u8 {
        // SAFETY: the caller's layout, passed on.
        let p = unsafe { std::alloc::System.alloc(layout) };
        if p.is_null() {
            Self::exhausted(layout.size());
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: std::alloc::Layout) -> *mut u8 {
        // SAFETY: the caller's layout, passed on.
        let p = unsafe { std::alloc::System.alloc_zeroed(layout) };
        if p.is_null() {
            Self::exhausted(layout.size());
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: std::alloc::Layout) {
        // SAFETY: the caller's pointer and layout, from this allocator (the system's).
        unsafe { std::alloc::System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: std::alloc::Layout, new_size: usize) -> *mut u8 {
        // SAFETY: the caller's pointer, layout and size, passed on.
        let p = unsafe { std::alloc::System.realloc(ptr, layout, new_size) };
        if p.is_null() {
            Self::exhausted(new_size);
        }
        p
    }
}
