//! Where an output's bytes go, and writing them without ever losing or replacing what was
//! there: one rule for every output shaderlab writes (screenshots, recordings, WGSL, studies).
//!
//! What the output path names now decides how it is written ([`Dest`]):
//! - a regular file, or a name not taken yet (also through symbolic links, dangling ones too):
//!   the bytes go to a temporary file `.sl-PID-N.tmp` beside it, which is synced and renamed
//!   over it only when complete; a failure leaves the old file as it was;
//! - one of the process's own descriptors (`/dev/stdout`, `/dev/fd/N`, `/proc/self/fd/N`), a
//!   FIFO or a character device (`/dev/null`, a terminal): written into as a stream, never
//!   truncated, replaced or renamed over; a FIFO nobody reads is an error, not a wait;
//! - a directory, a socket or a block device (a disk): refused with a message.
//!
//! Temporary files left by a process that was killed (`SIGKILL`, a crash) are removed by the
//! next run that writes into the same folder ([`sweep_stale`]).

use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Mutex;

use super::{io_error, parent_dir, signals};
use crate::error::{Error, Result};

/// Symbolic links followed before giving up (Linux's own limit).
const MAX_LINK_HOPS: usize = 40;

/// Where an output's bytes go (see the module docs).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Dest {
    /// A regular file or a free name: the path after its symbolic links, replaced atomically.
    File(PathBuf),
    /// Written into as a stream.
    Stream(Stream),
}

/// An output that is written into as it is, never replaced.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Stream {
    /// One of the process's own file descriptors, written through a copy of it (so a file the
    /// shell opened for appending is appended to).
    Fd(i32),
    /// A FIFO (named pipe).
    Fifo(PathBuf),
    /// A character device (`/dev/null`, a terminal).
    Device(PathBuf),
}

impl Dest {
    /// What `path` names now; an error for what cannot take an output (a directory, a socket,
    /// a block device, a loop of links).
    pub fn of(path: &Path) -> Result<Dest> {
        if path.as_os_str().is_empty() {
            return Err(Error::Param("an empty output file name".into()));
        }
        let mut target = path.to_owned();
        for _ in 0..MAX_LINK_HOPS {
            if let Some(fd) = own_fd(&target) {
                return Ok(Dest::Stream(Stream::Fd(fd)));
            }
            match fs::symlink_metadata(&target) {
                Ok(meta) if meta.file_type().is_symlink() => {
                    let link = fs::read_link(&target).map_err(|source| Error::Io {
                        path: target.clone(),
                        source,
                    })?;
                    // A relative link is relative to the directory holding it; an absolute one
                    // replaces the path (`join` does both).
                    target = parent_dir(&target).join(link);
                }
                Ok(meta) => return classify(path, target, &meta),
                // Missing (or unreadable: the write itself will say why).
                Err(_) => return Ok(Dest::File(target)),
            }
        }
        Err(io_error(
            path,
            io::ErrorKind::InvalidInput,
            format!("more than {MAX_LINK_HOPS} symbolic links to follow; is there a loop?"),
        ))
    }

    /// Whether this output is the process's standard output (messages then go to stderr).
    pub fn is_stdout(&self) -> bool {
        matches!(self, Dest::Stream(Stream::Fd(1)))
    }
}

fn classify(path: &Path, target: PathBuf, meta: &fs::Metadata) -> Result<Dest> {
    let kind = meta.file_type();
    if kind.is_file() {
        return Ok(Dest::File(target));
    }
    if kind.is_dir() {
        return Err(Error::Param(format!(
            "{}: is a directory; give a file name",
            path.display()
        )));
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return Ok(Dest::Stream(Stream::Fifo(target)));
        }
        if kind.is_char_device() {
            return Ok(Dest::Stream(Stream::Device(target)));
        }
        if kind.is_block_device() {
            return Err(io_error(
                path,
                io::ErrorKind::InvalidInput,
                "a block device (a disk); shaderlab writes files, never onto a disk".into(),
            ));
        }
        if kind.is_socket() {
            return Err(io_error(
                path,
                io::ErrorKind::InvalidInput,
                "a socket; an output must be a file, a FIFO or a device such as /dev/null".into(),
            ));
        }
    }
    Err(io_error(
        path,
        io::ErrorKind::InvalidInput,
        "not a regular file, FIFO or device; give a file name".into(),
    ))
}

/// The descriptor a path names directly: `/dev/stdout`, `/dev/stderr`, `/dev/fd/N`,
/// `/proc/self/fd/N`, `/proc/thread-self/fd/N` or `/proc/PID/fd/N` of this process.
fn own_fd(path: &Path) -> Option<i32> {
    if !cfg!(target_os = "linux") {
        return None;
    }
    let text = path.to_str()?;
    match text {
        "/dev/stdout" => return Some(1),
        "/dev/stderr" => return Some(2),
        _ => {}
    }
    let pid = std::process::id().to_string();
    let rest = text
        .strip_prefix("/dev/fd/")
        .or_else(|| text.strip_prefix("/proc/self/fd/"))
        .or_else(|| text.strip_prefix("/proc/thread-self/fd/"))
        .or_else(|| {
            text.strip_prefix("/proc/")?
                .strip_prefix(pid.as_str())?
                .strip_prefix("/fd/")
        })?;
    rest.parse::<u16>().ok().map(i32::from)
}

/// Whether something the process writes as an output is its own standard output, so that its
/// messages go to stderr instead of into the bytes.
static STDOUT_TAKEN: AtomicBool = AtomicBool::new(false);

/// Whether an output of this process is its standard output ([`Dest::is_stdout`]).
pub fn stdout_taken() -> bool {
    STDOUT_TAKEN.load(Ordering::Relaxed)
}

/// Marks standard output as taken by an output (see [`stdout_taken`]).
pub fn claim_stdout(dest: &Dest) {
    if dest.is_stdout() {
        STDOUT_TAKEN.store(true, Ordering::Relaxed);
    }
}

impl Stream {
    /// Checks, touching nothing, that the stream can be written: the device or FIFO is
    /// writable by this user, the descriptor is open for writing.
    pub fn check(&self, path: &Path) -> Result<()> {
        #[cfg(unix)]
        {
            match self {
                Stream::Fd(fd) => {
                    // SAFETY: fcntl on any number is safe; a closed one answers EBADF.
                    let flags = unsafe { libc::fcntl(*fd, libc::F_GETFL) };
                    if flags < 0 || flags & libc::O_ACCMODE == libc::O_RDONLY {
                        return Err(io_error(
                            path,
                            io::ErrorKind::InvalidInput,
                            format!("descriptor {fd} is not open for writing"),
                        ));
                    }
                }
                Stream::Fifo(p) | Stream::Device(p) => {
                    use std::os::unix::ffi::OsStrExt;
                    let c = std::ffi::CString::new(p.as_os_str().as_bytes())
                        .map_err(|_| io_error(path, io::ErrorKind::InvalidInput, "a NUL byte in the name".into()))?;
                    // SAFETY: a valid C string.
                    if unsafe { libc::access(c.as_ptr(), libc::W_OK) } != 0 {
                        return Err(Error::Io {
                            path: path.to_owned(),
                            source: io::Error::last_os_error(),
                        });
                    }
                }
            }
        }
        let _ = path;
        Ok(())
    }

    /// Opens the stream for writing (never creating, truncating or waiting).
    fn open(&self, path: &Path) -> Result<File> {
        let fail = |source: io::Error| Error::Io {
            path: path.to_owned(),
            source,
        };
        match self {
            #[cfg(unix)]
            Stream::Fd(fd) => {
                use std::os::fd::FromRawFd;
                self.check(path)?;
                // SAFETY: dup of a descriptor checked open above; the copy is ours to close.
                let copy = unsafe { libc::fcntl(*fd, libc::F_DUPFD_CLOEXEC, 3) };
                if copy < 0 {
                    return Err(fail(io::Error::last_os_error()));
                }
                // SAFETY: `copy` is a fresh descriptor owned by nothing else.
                Ok(unsafe { File::from_raw_fd(copy) })
            }
            #[cfg(not(unix))]
            Stream::Fd(_) => Err(fail(io::Error::other("descriptors are not supported here"))),
            Stream::Fifo(p) => {
                #[cfg(unix)]
                {
                    use std::os::unix::fs::OpenOptionsExt;
                    // Without a reader, opening a FIFO for writing waits for one for ever;
                    // non-blocking, it fails with ENXIO instead.
                    let file = OpenOptions::new()
                        .write(true)
                        .custom_flags(libc::O_NONBLOCK)
                        .open(p)
                        .map_err(|e| {
                            if e.raw_os_error() == Some(libc::ENXIO) {
                                io_error(
                                    path,
                                    io::ErrorKind::BrokenPipe,
                                    "a FIFO that nothing reads; start the program that reads it first".into(),
                                )
                            } else {
                                fail(e)
                            }
                        })?;
                    use std::os::fd::AsRawFd;
                    // SAFETY: fcntl on our own open descriptor.
                    unsafe {
                        let flags = libc::fcntl(file.as_raw_fd(), libc::F_GETFL);
                        libc::fcntl(file.as_raw_fd(), libc::F_SETFL, flags & !libc::O_NONBLOCK);
                    }
                    Ok(file)
                }
                #[cfg(not(unix))]
                OpenOptions::new().write(true).open(p).map_err(fail)
            }
            Stream::Device(p) => OpenOptions::new().write(true).open(p).map_err(fail),
        }
    }
}

/// Creates a fresh `.sl-PID-N.tmp` next to `target` (never an existing file). The name is short
/// and does not contain the target's, so that any name the file system takes as a target
/// (up to 255 bytes) also works while it is being written.
pub(super) fn create_temp(target: &Path) -> Result<(PathBuf, File)> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let dir = parent_dir(target);
    sweep_stale_once(dir);
    loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let temp = dir.join(format!("{TEMP_PREFIX}{}-{n}{TEMP_SUFFIX}", std::process::id()));
        match OpenOptions::new().write(true).create_new(true).open(&temp) {
            Ok(file) => return Ok((temp, file)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(source) => {
                return Err(io_error(
                    target,
                    source.kind(),
                    format!("cannot create a file in {}: {source}", dir.display()),
                ))
            }
        }
    }
}

const TEMP_PREFIX: &str = ".sl-";
const TEMP_SUFFIX: &str = ".tmp";

/// The process id in a temporary file's name `.sl-PID-N.tmp`.
fn temp_owner(name: &str) -> Option<u32> {
    let middle = name.strip_prefix(TEMP_PREFIX)?.strip_suffix(TEMP_SUFFIX)?;
    let (pid, n) = middle.split_once('-')?;
    n.parse::<u64>().ok()?;
    pid.parse().ok()
}

/// [`sweep_stale`], once per folder and process (a sequence of 10,000 frames reads its folder
/// once).
fn sweep_stale_once(dir: &Path) {
    static SWEPT: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());
    let Ok(mut swept) = SWEPT.lock() else { return };
    if swept.iter().any(|d| d == dir) {
        return;
    }
    swept.push(dir.to_owned());
    drop(swept);
    sweep_stale(dir);
}

/// Removes the temporary files `.sl-PID-N.tmp` in `dir` that this user's processes left when
/// they were killed before they could (SIGKILL, a crash, a power cut): those whose process no
/// longer exists. Returns how many were removed. Best effort: an unreadable folder or file is
/// left alone. (A process of another PID namespace writing into the same folder looks gone; its
/// write then fails with a message, and no finished file is touched.)
pub fn sweep_stale(dir: &Path) -> usize {
    let Ok(entries) = fs::read_dir(dir) else { return 0 };
    let mut removed = 0;
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = name.to_str().and_then(temp_owner) else {
            continue;
        };
        if pid == std::process::id() || process_exists(pid) {
            continue;
        }
        let Ok(meta) = entry.path().symlink_metadata() else {
            continue;
        };
        #[cfg(unix)]
        {
            use std::os::unix::fs::MetadataExt;
            // SAFETY: getuid has no preconditions.
            if meta.uid() != unsafe { libc::getuid() } {
                continue;
            }
        }
        if meta.is_file() && fs::remove_file(entry.path()).is_ok() {
            removed += 1;
        }
    }
    removed
}

/// Whether a process with this id exists (any user's).
fn process_exists(pid: u32) -> bool {
    #[cfg(unix)]
    {
        let Ok(pid) = libc::pid_t::try_from(pid) else {
            return false;
        };
        // SAFETY: signal 0 only checks; it sends nothing.
        if unsafe { libc::kill(pid, 0) } == 0 {
            return true;
        }
        io::Error::last_os_error().raw_os_error() != Some(libc::ESRCH)
    }
    #[cfg(not(unix))]
    {
        let _ = pid;
        true
    }
}

/// Writes `path` all at once, as its [`Dest`] says: a file is written to a temporary file in
/// the same directory, flushed to disk and renamed over `path` (if anything fails, the temporary
/// file is removed and an existing `path` is left as it was; if the process is stopped by
/// SIGINT, SIGTERM or SIGHUP meanwhile, a signal handler removes the temporary file before the
/// process ends as the signal says); a stream gets the bytes only once `write` has produced
/// them all.
///
/// What happens to links and file attributes:
/// - A symbolic link is written through: the file it points to (through any chain of links,
///   and also when it does not exist yet) is replaced, in that file's directory, and the link
///   stays a link.
/// - An existing file keeps its permission bits and, where the process may set them, its owner
///   and group (as a non-root user a file owned by someone else becomes the writer's).
/// - Hard links are broken, by the design of atomic replacement: the new contents are a new
///   file renamed over this name; the other names of the old file keep the old contents.
pub fn write_atomic(path: &Path, write: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> Result<()> {
    super::check_output_path(path)?;
    match Dest::of(path)? {
        Dest::File(_) => {
            let mut file = AtomicFile::create(path)?;
            write(&mut file).map_err(|source| Error::Io {
                path: path.to_owned(),
                source,
            })?;
            file.commit()
        }
        Dest::Stream(stream) => {
            let mut bytes = Vec::new();
            write(&mut bytes).map_err(|source| Error::Io {
                path: path.to_owned(),
                source,
            })?;
            claim_stdout(&Dest::Stream(stream.clone()));
            let mut out = stream.open(path)?;
            out.write_all(&bytes)
                .and_then(|()| out.flush())
                .map_err(|source| Error::Io {
                    path: path.to_owned(),
                    source,
                })
        }
    }
}

/// A file written whole or not at all, for writers that live longer than one call (a
/// recording that grows frame by frame): bytes go to a temporary file next to the target
/// (known to the signal handler), [`AtomicFile::commit`] renames it into place as
/// [`write_atomic`] does, and dropping it uncommitted removes it. A stream output ([`Dest`]) is
/// written into as the bytes come.
pub struct AtomicFile {
    path: PathBuf,
    inner: Inner,
}

enum Inner {
    Temp {
        target: PathBuf,
        temp: PathBuf,
        out: Option<BufWriter<File>>,
        _registered: signals::Registered,
    },
    Stream(BufWriter<File>),
}

impl AtomicFile {
    /// Starts writing `path` (checked with [`super::check_output_path`], written through links).
    pub fn create(path: &Path) -> Result<AtomicFile> {
        super::check_output_path(path)?;
        let inner = match Dest::of(path)? {
            Dest::File(target) => {
                if target != path {
                    super::check_output_path(&target)?;
                }
                let (temp, file) = create_temp(&target)?;
                let registered = signals::register(&temp);
                Inner::Temp {
                    target,
                    temp,
                    out: Some(BufWriter::new(file)),
                    _registered: registered,
                }
            }
            Dest::Stream(stream) => {
                claim_stdout(&Dest::Stream(stream.clone()));
                Inner::Stream(BufWriter::new(stream.open(path)?))
            }
        };
        Ok(AtomicFile {
            path: path.to_owned(),
            inner,
        })
    }

    /// Flushes to disk and renames over the target (keeping an existing file's permission
    /// bits and, where allowed, its owner); on failure the target is left as it was. A stream
    /// is flushed.
    pub fn commit(mut self) -> Result<()> {
        let path = self.path.clone();
        let fail = |source: io::Error| Error::Io {
            path: path.clone(),
            source,
        };
        match &mut self.inner {
            Inner::Stream(out) => out.flush().map_err(fail),
            Inner::Temp { target, temp, out, .. } => {
                let out = out.take().expect("an open file until committed");
                let file = out.into_inner().map_err(|e| fail(e.into_error()))?;
                finish_temp(&path, &file, target)?;
                drop(file);
                replace(temp, target).map_err(fail)?;
                // Renamed: nothing left to remove on drop.
                *temp = PathBuf::new();
                sync_dir(target);
                Ok(())
            }
        }
    }
}

/// Gives a finished temporary file the mode and owner of the file it replaces, and syncs it.
fn finish_temp(path: &Path, file: &File, target: &Path) -> Result<()> {
    let fail = |source: io::Error| Error::Io {
        path: path.to_owned(),
        source,
    };
    if let Ok(meta) = fs::metadata(target) {
        file.set_permissions(meta.permissions()).map_err(fail)?;
        #[cfg(unix)]
        {
            use std::os::unix::fs::MetadataExt;
            // Best effort: only root may give a file away; anyone may keep their own.
            let _ = std::os::unix::fs::fchown(file, Some(meta.uid()), Some(meta.gid()));
        }
    }
    file.sync_all().map_err(fail)
}

/// Renames `temp` over `target`, unless `target` has meanwhile become something that is not a
/// regular file (a FIFO, a device, a directory), which is never renamed over.
fn replace(temp: &Path, target: &Path) -> io::Result<()> {
    if let Ok(meta) = fs::symlink_metadata(target) {
        if !meta.is_file() {
            return Err(io::Error::new(
                io::ErrorKind::AlreadyExists,
                "is no longer a regular file (something replaced it while shaderlab wrote); left as it is",
            ));
        }
    }
    fs::rename(temp, target)
}

/// Makes a rename durable (best effort: not every platform can open a directory).
fn sync_dir(target: &Path) {
    if let Ok(dir) = File::open(parent_dir(target)) {
        let _ = dir.sync_all();
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match &mut self.inner {
            Inner::Temp { out, .. } => out.as_mut().map_or(Ok(0), |o| o.write(buf)),
            Inner::Stream(out) => out.write(buf),
        }
    }
    fn flush(&mut self) -> io::Result<()> {
        match &mut self.inner {
            Inner::Temp { out, .. } => out.as_mut().map_or(Ok(()), BufWriter::flush),
            Inner::Stream(out) => out.flush(),
        }
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if let Inner::Temp { temp, out, .. } = &mut self.inner {
            if !temp.as_os_str().is_empty() {
                *out = None;
                let _ = fs::remove_file(&*temp);
            }
        }
    }
}

/// Several files that appear together or not at all: a PNG sequence, a study's CSV, SVG and
/// notes. Each is written to its own temporary file beside its final name as it comes
/// ([`Batch::write`]); [`Batch::commit`] moves them all into place, with signals deferred so
/// that a SIGINT cannot stop it half-way; dropping the batch uncommitted removes them.
///
/// With `replace` false (a PNG sequence), no existing name is ever replaced, even one that
/// another program creates while the batch is being written: the move claims each name
/// exclusively, and if one is taken, the files already moved are removed again and the commit
/// fails, leaving the folder as it was.
pub struct Batch {
    replace: bool,
    files: Vec<Staged>,
}

struct Staged {
    /// The name the user asked for (for messages).
    path: PathBuf,
    target: PathBuf,
    temp: PathBuf,
}

impl Batch {
    /// An empty batch; `replace`: whether existing files may be replaced.
    pub fn new(replace: bool) -> Batch {
        Batch {
            replace,
            files: Vec::new(),
        }
    }

    /// Files written so far.
    pub fn len(&self) -> usize {
        self.files.len()
    }

    /// Whether nothing has been written yet.
    pub fn is_empty(&self) -> bool {
        self.files.is_empty()
    }

    /// Writes `path`'s future contents to a temporary file beside it. A path that is not a
    /// regular file or free name (a FIFO, a device: [`Dest::Stream`]) is refused: a batch only
    /// makes files.
    pub fn write(&mut self, path: &Path, write: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> Result<()> {
        super::check_output_path(path)?;
        let target = match Dest::of(path)? {
            Dest::File(target) => target,
            Dest::Stream(_) => {
                return Err(io_error(
                    path,
                    io::ErrorKind::InvalidInput,
                    "not a regular file (a FIFO or device); this output writes files".into(),
                ))
            }
        };
        if !self.replace && fs::symlink_metadata(&target).is_ok() {
            return Err(exists(path));
        }
        let (temp, file) = create_temp(&target)?;
        // Known to the batch from here on, so a failure below removes it.
        self.files.push(Staged {
            path: path.to_owned(),
            target: target.clone(),
            temp,
        });
        let fail = |source: io::Error| Error::Io {
            path: path.to_owned(),
            source,
        };
        let mut out = BufWriter::new(file);
        write(&mut out).map_err(fail)?;
        let file = out.into_inner().map_err(|e| fail(e.into_error()))?;
        finish_temp(path, &file, &target)
    }

    /// Moves every file into place (see [`Batch`]).
    pub fn commit(mut self) -> Result<()> {
        let _deferred = signals::defer();
        let files = std::mem::take(&mut self.files);
        let mut moved: Vec<&Staged> = Vec::new();
        for (k, staged) in files.iter().enumerate() {
            let result = if self.replace {
                replace(&staged.temp, &staged.target)
            } else {
                rename_no_replace(&staged.temp, &staged.target)
            };
            if let Err(source) = result {
                // Put the folder back as it was: what was moved is removed (new names only;
                // replaced files cannot come back, which is why a batch that replaces moves
                // only after every file was written), and what was not is dropped.
                if !self.replace {
                    for m in &moved {
                        let _ = fs::remove_file(&m.target);
                    }
                }
                for rest in &files[k..] {
                    let _ = fs::remove_file(&rest.temp);
                }
                return Err(if source.kind() == io::ErrorKind::AlreadyExists && !self.replace {
                    exists(&staged.path)
                } else {
                    Error::Io {
                        path: staged.path.clone(),
                        source,
                    }
                });
            }
            moved.push(staged);
        }
        if let Some(last) = files.last() {
            sync_dir(&last.target);
        }
        Ok(())
    }
}

impl Drop for Batch {
    fn drop(&mut self) {
        for staged in &self.files {
            let _ = fs::remove_file(&staged.temp);
        }
    }
}

fn exists(path: &Path) -> Error {
    io_error(
        path,
        io::ErrorKind::AlreadyExists,
        "exists; this output never overwrites: remove the old files or choose another name".into(),
    )
}

/// Renames `from` to `to` only if `to` does not exist, atomically: `renameat2` with
/// `RENAME_NOREPLACE` where the kernel and file system have it, else a hard link (which fails
/// on an existing name) and the removal of `from`.
fn rename_no_replace(from: &Path, to: &Path) -> io::Result<()> {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        use std::os::unix::ffi::OsStrExt;
        let c = |p: &Path| std::ffi::CString::new(p.as_os_str().as_bytes()).map_err(io::Error::other);
        let (a, b) = (c(from)?, c(to)?);
        // SAFETY: valid C strings; AT_FDCWD resolves them like rename(2).
        let r = unsafe {
            libc::renameat2(
                libc::AT_FDCWD,
                a.as_ptr(),
                libc::AT_FDCWD,
                b.as_ptr(),
                libc::RENAME_NOREPLACE,
            )
        };
        if r == 0 {
            return Ok(());
        }
        let e = io::Error::last_os_error();
        if !matches!(e.raw_os_error(), Some(libc::EINVAL | libc::ENOSYS)) {
            return Err(e);
        }
    }
    fs::hard_link(from, to)?;
    fs::remove_file(from)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fsutil::{sorted_names, ScratchDir};

    #[cfg(unix)]
    fn mkfifo(path: &Path) {
        use std::os::unix::ffi::OsStrExt;
        let c = std::ffi::CString::new(path.as_os_str().as_bytes()).unwrap();
        // SAFETY: a valid C string.
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    }

    #[cfg(unix)]
    fn is_fifo(path: &Path) -> bool {
        use std::os::unix::fs::FileTypeExt;
        fs::symlink_metadata(path).unwrap().file_type().is_fifo()
    }

    /// A FIFO is written into as a stream and stays a FIFO; with nothing reading it, the write
    /// is an error at once instead of a wait for ever.
    #[cfg(unix)]
    #[test]
    fn a_fifo_is_a_stream_never_replaced() {
        let dir = ScratchDir::new("output-fifo");
        let fifo = dir.join("out.wgsl");
        mkfifo(&fifo);
        let err = write_atomic(&fifo, |w| w.write_all(b"x")).unwrap_err().to_string();
        assert!(err.contains("a FIFO that nothing reads"), "{err}");
        assert!(is_fifo(&fifo), "the FIFO was replaced");
        let reader = {
            let fifo = fifo.clone();
            std::thread::spawn(move || fs::read(fifo).unwrap())
        };
        // The reader opens the FIFO when its thread runs: retry until it does.
        let start = std::time::Instant::now();
        loop {
            match write_atomic(&fifo, |w| w.write_all(b"through the pipe")) {
                Ok(()) => break,
                Err(e) if start.elapsed().as_secs() < 60 => {
                    assert!(e.to_string().contains("nothing reads"), "{e}");
                    std::thread::sleep(std::time::Duration::from_millis(10));
                }
                Err(e) => panic!("{e}"),
            }
        }
        assert_eq!(reader.join().unwrap(), b"through the pipe");
        assert!(is_fifo(&fifo));
        assert_eq!(sorted_names(&dir), ["out.wgsl"], "a temporary file was left");
        // A PNG stream needs no .png name; a batch (files only) refuses it.
        crate::fsutil::check_png_path(&fifo).unwrap();
        let err = Batch::new(true).write(&fifo, |_| Ok(())).unwrap_err().to_string();
        assert!(err.contains("not a regular file"), "{err}");
    }

    /// A device, also through a link, is written into, never renamed over: `/dev/full` says it
    /// is full and is still the device afterwards (as root the old code replaced it).
    #[cfg(target_os = "linux")]
    #[test]
    fn a_device_is_written_into_and_stays_a_device() {
        use std::os::unix::fs::FileTypeExt;
        let dir = ScratchDir::new("output-device");
        let link = dir.join("full.png");
        std::os::unix::fs::symlink("/dev/full", &link).unwrap();
        let err = write_atomic(&link, |w| w.write_all(&[1; 5000]))
            .unwrap_err()
            .to_string();
        assert!(err.contains("No space left on device"), "{err}");
        let err = AtomicFile::create(Path::new("/dev/full"))
            .and_then(|mut f| {
                f.write_all(&[1; 100_000]).map_err(|source| Error::Io {
                    path: "/dev/full".into(),
                    source,
                })?;
                f.commit()
            })
            .unwrap_err()
            .to_string();
        assert!(err.contains("No space left on device"), "{err}");
        assert!(fs::metadata("/dev/full").unwrap().file_type().is_char_device());
        assert!(fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
        write_atomic(Path::new("/dev/null"), |w| w.write_all(b"gone")).unwrap();
        assert!(fs::metadata("/dev/null").unwrap().file_type().is_char_device());
        assert_eq!(sorted_names(&dir), ["full.png"]);
    }

    /// `/proc/self/fd/N` (what `/dev/stdout` is) writes into the descriptor itself: into a pipe
    /// here, which the old code named `/proc/self/fd/pipe:[…]` and failed on.
    #[cfg(target_os = "linux")]
    #[test]
    fn the_processs_own_descriptors_are_streams() {
        use std::io::Read;
        use std::os::fd::FromRawFd;
        let mut fds = [0; 2];
        // SAFETY: pipe fills two descriptors that this test then owns.
        assert_eq!(unsafe { libc::pipe(fds.as_mut_ptr()) }, 0);
        // SAFETY: fresh descriptors owned by nothing else.
        let (mut read, write) = unsafe { (File::from_raw_fd(fds[0]), File::from_raw_fd(fds[1])) };
        let path = PathBuf::from(format!("/proc/self/fd/{}", fds[1]));
        assert_eq!(Dest::of(&path).unwrap(), Dest::Stream(Stream::Fd(fds[1])));
        assert_eq!(Dest::of(Path::new("/dev/stdout")).unwrap(), Dest::Stream(Stream::Fd(1)));
        write_atomic(&path, |w| w.write_all(b"piped")).unwrap();
        drop(write);
        let mut got = String::new();
        read.read_to_string(&mut got).unwrap();
        assert_eq!(got, "piped");
        // The read end is not open for writing.
        let err = check_stream(&format!("/dev/fd/{}", fds[0]));
        assert!(err.contains("not open for writing"), "{err}");
    }

    #[cfg(target_os = "linux")]
    fn check_stream(path: &str) -> String {
        crate::fsutil::check_output_path(Path::new(path))
            .unwrap_err()
            .to_string()
    }

    /// A socket cannot take an output: refused, and left alone.
    #[cfg(unix)]
    #[test]
    fn a_socket_is_refused() {
        let dir = ScratchDir::new("output-socket");
        let socket = dir.join("s.png");
        let _listener = std::os::unix::net::UnixListener::bind(&socket).unwrap();
        let err = crate::fsutil::check_png_path(&socket).unwrap_err().to_string();
        assert!(err.contains("a socket"), "{err}");
        let err = write_atomic(&socket, |w| w.write_all(b"x")).unwrap_err().to_string();
        assert!(err.contains("a socket"), "{err}");
        use std::os::unix::fs::FileTypeExt;
        assert!(fs::symlink_metadata(&socket).unwrap().file_type().is_socket());
    }

    /// Two batches that never replace, into the same names: the first to move its files wins
    /// whole; the second fails, removes what it had moved and leaves no temporary file.
    #[test]
    fn batches_that_never_replace_claim_names_whole_or_not_at_all() {
        let dir = ScratchDir::new("output-batch");
        let names: Vec<PathBuf> = (0..5).map(|k| dir.join(format!("f-{k}.png"))).collect();
        let mut a = Batch::new(false);
        let mut b = Batch::new(false);
        for name in &names {
            a.write(name, |w| w.write_all(b"a")).unwrap();
            b.write(name, |w| w.write_all(b"b")).unwrap();
        }
        // Someone else takes the last name while `a` is being written.
        fs::write(&names[4], b"theirs").unwrap();
        let err = a.commit().unwrap_err().to_string();
        assert!(err.contains("f-4.png: exists; this output never overwrites"), "{err}");
        let visible: Vec<String> = sorted_names(&dir)
            .into_iter()
            .filter(|n| !n.starts_with(".sl-"))
            .collect();
        assert_eq!(visible, ["f-4.png"], "the failed batch left files");
        assert_eq!(
            sorted_names(&dir).len(),
            6,
            "the failed batch left temporary files (b has 5)"
        );
        fs::remove_file(&names[4]).unwrap();
        b.commit().unwrap();
        for name in &names {
            assert_eq!(fs::read(name).unwrap(), b"b");
        }
        // Written into names that exist now: refused at once, not after the work.
        let err = Batch::new(false).write(&names[0], |_| Ok(())).unwrap_err().to_string();
        assert!(err.contains("exists"), "{err}");
        // A batch that replaces moves all; one dropped uncommitted leaves nothing.
        let mut c = Batch::new(true);
        for name in &names {
            c.write(name, |w| w.write_all(b"c")).unwrap();
        }
        drop(c);
        let mut d = Batch::new(true);
        d.write(&names[0], |w| w.write_all(b"d")).unwrap();
        d.commit().unwrap();
        assert_eq!(fs::read(&names[0]).unwrap(), b"d");
        assert_eq!(fs::read(&names[1]).unwrap(), b"b");
        assert_eq!(sorted_names(&dir).len(), 5, "{:?}", sorted_names(&dir));
    }

    /// A temporary file left by a process that is gone (killed with SIGKILL) is removed by the
    /// next write into its folder; one of a live process, and other files, are not.
    #[cfg(unix)]
    #[test]
    fn stale_temporary_files_of_dead_processes_are_swept() {
        let dir = ScratchDir::new("output-stale");
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let dead = child.id();
        child.wait().unwrap();
        let stale = dir.join(format!(".sl-{dead}-7.tmp"));
        let live = dir.join(".sl-1-3.tmp");
        let other = dir.join(".sl-notes.tmp");
        for f in [&stale, &live, &other] {
            fs::write(f, vec![0u8; 3 << 20]).unwrap();
        }
        assert!(!process_exists(dead));
        write_atomic(&dir.join("x.txt"), |w| w.write_all(b"1")).unwrap();
        assert_eq!(sorted_names(&dir), [".sl-1-3.tmp", ".sl-notes.tmp", "x.txt"]);
        assert_eq!(temp_owner(".sl-123-4.tmp"), Some(123));
        assert_eq!(temp_owner(".sl-123.tmp"), None);
    }
}
