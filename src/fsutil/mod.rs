//! Files in and out, without ever losing or replacing one by mistake: outputs are checked
//! before anything is touched and written as [`output`'s rules](Dest) say (a file through a
//! temporary file renamed into place once complete and on disk; a FIFO, a device or the
//! process's own descriptor as a stream; anything else refused); several files that belong
//! together appear together ([`Batch`]); a signal removes what was half-written ([`signals`]);
//! user files are read only when regular and within a size cap ([`read_user_file`]); no output
//! replaces one of the run's inputs ([`inputs`]).
//!
//! ```no_run
//! use std::io::Write;
//! use std::path::Path;
//!
//! shaderlab::fsutil::check_png_path(Path::new("out.png"))?; // before any rendering
//! shaderlab::fsutil::write_atomic(Path::new("notes.txt"), |w| writeln!(w, "hello"))?;
//! # Ok::<(), shaderlab::Error>(())
//! ```

pub mod inputs;
mod output;
pub mod signals;

use std::fs::{self, File};
use std::io::{self};
use std::path::Path;

pub use output::{claim_stdout, stdout_taken, sweep_stale, write_atomic, AtomicFile, Batch, Dest, Stream};

use crate::error::{Error, Result};

/// The directory a file `path` lives in (`.` for a bare file name).
fn parent_dir(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

fn io_error(path: &Path, kind: io::ErrorKind, message: String) -> Error {
    Error::Io {
        path: path.to_owned(),
        source: io::Error::new(kind, message),
    }
}

/// Checks that `path` can name an output (touching nothing): not a directory, socket or block
/// device ([`Dest::of`]); not one of the run's inputs, through any path or link ([`inputs`]);
/// a file in a directory that exists; a FIFO or device this user may write; a descriptor open
/// for writing.
pub fn check_output_path(path: &Path) -> Result<()> {
    let dest = Dest::of(path)?;
    inputs::check(path, &dest)?;
    match dest {
        Dest::Stream(stream) => stream.check(path),
        Dest::File(target) => {
            for name in [path, target.as_path()] {
                if name.file_name().is_none() {
                    // `dir/..`, `/`: no file name to write.
                    return Err(Error::Param(format!("{}: not a file name", path.display())));
                }
            }
            let parent = parent_dir(&target);
            match fs::metadata(parent) {
                Ok(meta) if meta.is_dir() => Ok(()),
                Ok(_) => Err(io_error(
                    path,
                    io::ErrorKind::NotADirectory,
                    format!("{} is not a directory", parent.display()),
                )),
                Err(e) if e.kind() == io::ErrorKind::NotFound => Err(io_error(
                    path,
                    io::ErrorKind::NotFound,
                    format!("the directory {} does not exist", parent.display()),
                )),
                Err(source) => Err(Error::Io {
                    path: parent.to_owned(),
                    source,
                }),
            }
        }
    }
}

/// Checks that `path` can take a PNG: passes [`check_output_path`] and, for a file, ends in
/// `.png` (any case), so that a photo named by mistake is never replaced; a stream (a FIFO,
/// `/dev/stdout`) takes the PNG whatever its name. Run it before rendering, so a bad name fails
/// fast.
pub fn check_png_path(path: &Path) -> Result<()> {
    check_output_path(path)?;
    let is_png = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !is_png && matches!(Dest::of(path)?, Dest::File(_)) {
        return Err(Error::Param(format!(
            "{}: only PNG is written; use a .png name",
            path.display()
        )));
    }
    Ok(())
}

/// Checks, before any work is done, that [`write_atomic`] will be able to write `path`:
/// [`check_output_path`], then, for a file, a temporary file is created next to the file the
/// bytes will go to (through links) and removed again. A read-only or full directory is found
/// here, not after a long render.
pub fn check_writable(path: &Path) -> Result<()> {
    check_output_path(path)?;
    if let Dest::File(target) = Dest::of(path)? {
        let (temp, file) = output::create_temp(&target)?;
        drop(file);
        let _ = fs::remove_file(&temp);
    }
    Ok(())
}

/// A folder an output makes for its files (`tradeoff --out DIR`, `glsl2wgsl --all DIR OUTDIR`),
/// made as late as possible and unmade if the output fails: every level that
/// [`NewDir::create`] made is removed again when the guard is dropped without
/// [`NewDir::keep`] (innermost first, and only while empty, so a file someone else put there
/// meanwhile keeps its folder). A run that fails leaves no new empty folder behind.
#[must_use = "the folder is removed again when the guard is dropped without keep()"]
pub struct NewDir {
    /// The levels this guard made, innermost first.
    made: Vec<std::path::PathBuf>,
}

impl NewDir {
    /// Checks, making nothing, that [`NewDir::create`] can make `dir` (or that it is a
    /// directory already) and that files can be written there: the nearest level that exists
    /// must be a directory in which a file can be made.
    pub fn check(dir: &Path) -> Result<()> {
        let mut existing = dir;
        loop {
            match fs::metadata(existing) {
                Ok(meta) if meta.is_dir() => break,
                Ok(_) => {
                    return Err(Error::Io {
                        path: existing.to_owned(),
                        source: not_a_directory(),
                    })
                }
                Err(e) if e.kind() == io::ErrorKind::NotFound => match existing.parent() {
                    Some(parent) if !parent.as_os_str().is_empty() => existing = parent,
                    _ => {
                        existing = Path::new(".");
                        break;
                    }
                },
                Err(source) => {
                    return Err(Error::Io {
                        path: existing.to_owned(),
                        source,
                    })
                }
            }
        }
        let (temp, file) = output::create_temp(&existing.join("probe"))?;
        drop(file);
        let _ = fs::remove_file(temp);
        Ok(())
    }

    /// Makes `dir` and any missing level above it (as `create_dir_all`); a level made before
    /// a failure is removed again.
    pub fn create(dir: &Path) -> Result<NewDir> {
        let mut guard = NewDir { made: Vec::new() };
        let mut missing = Vec::new();
        let mut level = dir;
        while fs::symlink_metadata(level).is_err() {
            missing.push(level.to_owned());
            match level.parent() {
                Some(parent) if !parent.as_os_str().is_empty() => level = parent,
                _ => break,
            }
        }
        for level in missing.into_iter().rev() {
            match fs::create_dir(&level) {
                Ok(()) => guard.made.insert(0, level),
                // Made by someone else meanwhile: theirs, not removed.
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists && level.is_dir() => {}
                Err(source) => return Err(Error::Io { path: level, source }),
            }
        }
        if !dir.is_dir() {
            return Err(Error::Io {
                path: dir.to_owned(),
                source: not_a_directory(),
            });
        }
        Ok(guard)
    }

    /// The output succeeded: the folder stays.
    pub fn keep(mut self) {
        self.made.clear();
    }
}

/// The system's own "Not a directory", as `create_dir_all` would say it.
fn not_a_directory() -> io::Error {
    #[cfg(unix)]
    return io::Error::from_raw_os_error(libc::ENOTDIR);
    #[cfg(not(unix))]
    io::Error::from(io::ErrorKind::NotADirectory)
}

impl Drop for NewDir {
    fn drop(&mut self) {
        for level in &self.made {
            if fs::remove_dir(level).is_err() {
                break;
            }
        }
    }
}

/// A human size: `1 MiB`, `64 MiB`, `1.5 GiB`, `300 bytes`.
pub fn human_bytes(n: u64) -> String {
    const UNITS: [&str; 4] = ["KiB", "MiB", "GiB", "TiB"];
    if n < 1024 {
        return format!("{n} bytes");
    }
    let mut value = n as f64;
    let mut unit = "bytes";
    for u in UNITS {
        if value < 1024.0 {
            break;
        }
        value /= 1024.0;
        unit = u;
    }
    if value.fract() == 0.0 {
        format!("{value:.0} {unit}")
    } else {
        format!("{value:.1} {unit}")
    }
}

/// Reads a file the user named (a shader, a model, a picture): it must be a regular file (not a
/// directory, device, pipe or socket: checked before opening, as opening a FIFO blocks) of at
/// most `cap` bytes, checked from its size before reading and again while reading (at most
/// `cap + 1` bytes are read, in case the size lies, as for files in `/proc`). `what` names the
/// kind in messages (`shader files`, `OBJ models`, `pictures`). A missing or unreadable file
/// is [`Error::Io`] with the system's error kind (e.g. `NotFound`), anything else
/// [`Error::Io`] with a message naming the size and the cap. The file becomes one of the run's
/// [`inputs`], which no output may replace.
pub fn read_user_file(path: &Path, cap: u64, what: &str) -> Result<Vec<u8>> {
    use std::io::Read;
    let io = |source: io::Error| Error::Io {
        path: path.to_owned(),
        source,
    };
    let meta = fs::metadata(path).map_err(io)?;
    if !meta.is_file() {
        let kind = if meta.is_dir() {
            "a directory"
        } else {
            "not a regular file (a device, pipe or socket)"
        };
        return Err(io_error(
            path,
            io::ErrorKind::InvalidInput,
            format!("{kind}; {what} must be regular files"),
        ));
    }
    let too_big = |size: u64, at_least: &str| {
        io_error(
            path,
            io::ErrorKind::InvalidData,
            format!(
                "{at_least}{size} bytes ({}); {what} are limited to {cap} bytes ({})",
                human_bytes(size),
                human_bytes(cap)
            ),
        )
    };
    if meta.len() > cap {
        return Err(too_big(meta.len(), ""));
    }
    inputs::note(path, what);
    let file = File::open(path).map_err(io)?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(cap + 1).read_to_end(&mut bytes).map_err(io)?;
    if bytes.len() as u64 > cap {
        return Err(too_big(bytes.len() as u64, "at least "));
    }
    Ok(bytes)
}

/// A fresh directory under the system's temp directory for one unit test, removed when the
/// test passes (kept for a look when it fails).
#[cfg(test)]
pub(crate) struct ScratchDir {
    root: std::path::PathBuf,
    dir: std::path::PathBuf,
}

#[cfg(test)]
impl ScratchDir {
    /// `TMP/shaderlab-TAG-PID`, empty.
    pub(crate) fn new(tag: &str) -> Self {
        Self::nested(tag, "")
    }

    /// `TMP/shaderlab-TAG-PID/SUB`, empty, inside a directory of its own (so a test can put
    /// files next to it).
    pub(crate) fn nested(tag: &str, sub: &str) -> Self {
        let root = std::env::temp_dir().join(format!("shaderlab-{tag}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&root);
        let dir = root.join(sub);
        fs::create_dir_all(&dir).unwrap();
        ScratchDir { root, dir }
    }
}

/// The names in `dir`, sorted: what a test sees to know that no temporary file was left.
#[cfg(test)]
pub(crate) fn sorted_names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[cfg(test)]
impl std::ops::Deref for ScratchDir {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.dir
    }
}

#[cfg(test)]
impl Drop for ScratchDir {
    fn drop(&mut self) {
        if !std::thread::panicking() {
            let _ = fs::remove_dir_all(&self.root);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn test_dir(name: &str) -> ScratchDir {
        ScratchDir::new(&format!("fsutil-{name}"))
    }

    #[test]
    fn png_path_needs_the_png_extension() {
        let dir = test_dir("png_ext");
        for name in ["x.jpg", "x.JPEG", "x.bmp", "x.gif", "x.tiff", "x", "x.png.bak", ".png"] {
            let err = check_png_path(&dir.join(name)).unwrap_err();
            assert!(matches!(err, Error::Param(_)), "{name}: {err:?}");
            assert!(
                err.to_string().contains("only PNG is written; use a .png name"),
                "{name}: {err}"
            );
        }
        for name in ["x.png", "x.PNG", "x.Png"] {
            check_png_path(&dir.join(name)).unwrap();
        }
        assert!(sorted_names(&dir).is_empty(), "checking touched the directory");
    }

    #[test]
    fn directory_and_missing_parent_are_clear() {
        let dir = test_dir("dirs");
        fs::create_dir(dir.join("shot.png")).unwrap();
        let err = check_png_path(&dir.join("shot.png")).unwrap_err();
        assert!(
            matches!(err, Error::Param(_)) && err.to_string().contains("is a directory"),
            "{err}"
        );
        let err = write_atomic(&dir, |_| Ok(())).unwrap_err();
        assert!(err.to_string().contains("is a directory"), "{err}");
        let missing = dir.join("nope").join("x.png");
        let err = check_png_path(&missing).unwrap_err();
        assert!(
            matches!(&err, Error::Io { source, .. } if source.kind() == io::ErrorKind::NotFound),
            "{err:?}"
        );
        assert!(err.to_string().contains("does not exist"), "{err}");
        fs::write(dir.join("file"), b"x").unwrap();
        let err = check_png_path(&dir.join("file").join("x.png")).unwrap_err();
        assert!(err.to_string().contains("is not a directory"), "{err}");
    }

    #[test]
    fn write_atomic_replaces_the_file_and_leaves_no_temp() {
        let dir = test_dir("replace");
        let path = dir.join("out.csv");
        fs::write(&path, b"old").unwrap();
        write_atomic(&path, |w| w.write_all(b"new contents")).unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"new contents");
        assert_eq!(sorted_names(&dir), ["out.csv"]);
        // A bare file name writes into the current directory's form of the path too.
        let fresh = dir.join("fresh.txt");
        write_atomic(&fresh, |w| w.write_all(b"1")).unwrap();
        assert_eq!(fs::read(&fresh).unwrap(), b"1");
    }

    #[test]
    fn a_failing_writer_keeps_the_old_file_and_removes_the_temp() {
        let dir = test_dir("failing");
        let path = dir.join("out.png");
        fs::write(&path, b"precious").unwrap();
        let err = write_atomic(&path, |w| {
            w.write_all(&[7; 100_000])?;
            Err(io::Error::other("encoder failed half way"))
        })
        .unwrap_err();
        assert!(err.to_string().contains("encoder failed half way"), "{err}");
        assert_eq!(fs::read(&path).unwrap(), b"precious");
        assert_eq!(sorted_names(&dir), ["out.png"], "a temporary file was left behind");
        // Nothing there before: nothing there after.
        let new = dir.join("new.png");
        write_atomic(&new, |_| Err(io::Error::other("no"))).unwrap_err();
        assert_eq!(sorted_names(&dir), ["out.png"]);
    }

    #[cfg(unix)]
    #[test]
    fn write_atomic_writes_through_a_link_and_keeps_permissions() {
        use std::os::unix::fs::PermissionsExt;
        let dir = test_dir("link");
        let real = dir.join("real.txt");
        fs::write(&real, b"a").unwrap();
        fs::set_permissions(&real, fs::Permissions::from_mode(0o640)).unwrap();
        std::os::unix::fs::symlink(&real, dir.join("link.txt")).unwrap();
        write_atomic(&dir.join("link.txt"), |w| w.write_all(b"b")).unwrap();
        assert!(fs::symlink_metadata(dir.join("link.txt"))
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(fs::read(&real).unwrap(), b"b");
        assert_eq!(fs::metadata(&real).unwrap().permissions().mode() & 0o777, 0o640);
    }

    #[test]
    fn temp_names_are_short_so_any_target_name_works() {
        let dir = test_dir("long");
        // 255 bytes, the longest name ext4 and most file systems take.
        let name = format!("{}.png", "a".repeat(251));
        write_atomic(&dir.join(&name), |w| w.write_all(b"1")).unwrap();
        assert_eq!(sorted_names(&dir), std::slice::from_ref(&name));
        check_writable(&dir.join(&name)).unwrap();
        assert_eq!(sorted_names(&dir), [name], "the writability probe left a file");
    }

    #[cfg(unix)]
    #[test]
    fn a_dangling_link_is_written_through_to_its_target() {
        let dir = test_dir("dangling");
        fs::create_dir(dir.join("real")).unwrap();
        // Relative to the link's directory, and through a chain of two links.
        std::os::unix::fs::symlink("real/shot.png", dir.join("inner.png")).unwrap();
        std::os::unix::fs::symlink("inner.png", dir.join("outer.png")).unwrap();
        write_atomic(&dir.join("outer.png"), |w| w.write_all(b"picture")).unwrap();
        for link in ["inner.png", "outer.png"] {
            assert!(
                fs::symlink_metadata(dir.join(link)).unwrap().file_type().is_symlink(),
                "{link} was replaced by a file"
            );
        }
        assert_eq!(fs::read(dir.join("real/shot.png")).unwrap(), b"picture");
        assert_eq!(sorted_names(&dir.join("real")), ["shot.png"]);
        // A link loop is an error, not a hang, and writes nothing.
        std::os::unix::fs::symlink("loop_b", dir.join("loop_a")).unwrap();
        std::os::unix::fs::symlink("loop_a", dir.join("loop_b")).unwrap();
        let err = write_atomic(&dir.join("loop_a"), |w| w.write_all(b"x")).unwrap_err();
        assert!(err.to_string().contains("symbolic links"), "{err}");
    }

    #[cfg(unix)]
    #[test]
    fn hard_links_are_broken_by_design_and_the_mode_and_owner_kept() {
        use std::os::unix::fs::{MetadataExt, PermissionsExt};
        let dir = test_dir("hard");
        let a = dir.join("a.png");
        fs::write(&a, b"old").unwrap();
        fs::set_permissions(&a, fs::Permissions::from_mode(0o604)).unwrap();
        fs::hard_link(&a, dir.join("b.png")).unwrap();
        let before = fs::metadata(&a).unwrap();
        write_atomic(&a, |w| w.write_all(b"new")).unwrap();
        assert_eq!(fs::read(&a).unwrap(), b"new");
        // The other name keeps the old file: atomic replacement makes a new one.
        assert_eq!(fs::read(dir.join("b.png")).unwrap(), b"old");
        let after = fs::metadata(&a).unwrap();
        assert_eq!(after.permissions().mode() & 0o777, 0o604);
        assert_eq!((after.uid(), after.gid()), (before.uid(), before.gid()));
    }

    #[test]
    fn user_files_must_be_regular_and_within_the_cap() {
        let dir = test_dir("user_files");
        let ok = dir.join("ok.txt");
        fs::write(&ok, b"12345").unwrap();
        assert_eq!(read_user_file(&ok, 5, "notes").unwrap(), b"12345");
        let err = read_user_file(&ok, 4, "notes").unwrap_err().to_string();
        assert!(
            err.ends_with("ok.txt: 5 bytes (5 bytes); notes are limited to 4 bytes (4 bytes)"),
            "{err}"
        );
        // A sparse file claiming 1 GiB is refused from its size, without reading it.
        let big = dir.join("big.frag");
        File::create(&big).unwrap().set_len(1 << 30).unwrap();
        let err = read_user_file(&big, 1 << 20, "shader files").unwrap_err().to_string();
        assert!(
            err.ends_with("big.frag: 1073741824 bytes (1 GiB); shader files are limited to 1048576 bytes (1 MiB)"),
            "{err}"
        );
        let err = read_user_file(&dir, 10, "pictures").unwrap_err().to_string();
        assert!(err.contains("a directory; pictures must be regular files"), "{err}");
        let err = read_user_file(&dir.join("missing"), 10, "pictures").unwrap_err();
        assert!(
            matches!(&err, Error::Io { source, .. } if source.kind() == io::ErrorKind::NotFound),
            "{err:?}"
        );
        #[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
        {
            // A FIFO: opening it would block; it is refused before that.
            let fifo = dir.join("fifo");
            let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
            // SAFETY: a valid C string.
            assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
            let err = read_user_file(&fifo, 10, "OBJ models").unwrap_err().to_string();
            assert!(
                err.contains("not a regular file (a device, pipe or socket); OBJ models must be regular files"),
                "{err}"
            );
        }
    }

    #[test]
    fn human_sizes() {
        assert_eq!(human_bytes(5), "5 bytes");
        assert_eq!(human_bytes(1 << 20), "1 MiB");
        assert_eq!(human_bytes(64 << 20), "64 MiB");
        assert_eq!(human_bytes(3 << 29), "1.5 GiB");
    }

    /// The directory `signal_child` writes into, set by the test that runs it.
    #[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
    const SIGNAL_CHILD_DIR: &str = "SHADERLAB_TEST_SIGNAL_CHILD_DIR";

    /// Not a test of its own: the child process of
    /// `a_signal_while_writing_removes_the_temp_file`, stuck half-way through a write.
    #[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
    #[test]
    #[ignore = "the child of a_signal_while_writing_removes_the_temp_file"]
    fn signal_child() {
        let Some(dir) = std::env::var_os(SIGNAL_CHILD_DIR) else {
            return;
        };
        // A process started in the background by a non-interactive shell (as CI may start the
        // tests) inherits SIGINT ignored, and the handler leaves an ignored signal alone: give
        // this child the default actions, so that it tests the handler and is not immune.
        // SAFETY: plain libc calls with valid arguments, before any other thread is started.
        unsafe {
            libc::signal(libc::SIGINT, libc::SIG_DFL);
            libc::signal(libc::SIGTERM, libc::SIG_DFL);
        }
        let _ = write_atomic(&Path::new(&dir).join("shot.png"), |w| {
            w.write_all(&[7; 100_000])?;
            w.flush()?;
            loop {
                std::thread::sleep(std::time::Duration::from_millis(50));
            }
        });
    }

    #[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
    #[test]
    fn a_signal_while_writing_removes_the_temp_file() {
        use std::os::unix::process::ExitStatusExt;
        use std::process::{Command, Stdio};
        for signal in [libc::SIGTERM, libc::SIGINT] {
            let dir = test_dir(&format!("signal{signal}"));
            let mut child = Command::new(std::env::current_exe().unwrap())
                .args([
                    "--exact",
                    "fsutil::tests::signal_child",
                    "--ignored",
                    "--test-threads=1",
                ])
                .env(SIGNAL_CHILD_DIR, &*dir)
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn()
                .unwrap();
            let start = std::time::Instant::now();
            while sorted_names(&dir).is_empty() {
                assert!(start.elapsed().as_secs() < 60, "the child never started writing");
                std::thread::sleep(std::time::Duration::from_millis(10));
            }
            // Let it get into its writer (the temp file exists from before that).
            std::thread::sleep(std::time::Duration::from_millis(100));
            // SAFETY: a plain kill of our own child.
            assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, signal) }, 0);
            // Never hang the suite: a child that outlives the signal is killed and reported.
            let status = loop {
                if let Some(status) = child.try_wait().unwrap() {
                    break status;
                }
                if start.elapsed().as_secs() > 60 {
                    let _ = child.kill();
                    let _ = child.wait();
                    panic!("the child ignored signal {signal} and was killed");
                }
                std::thread::sleep(std::time::Duration::from_millis(10));
            };
            assert_eq!(status.signal(), Some(signal), "{status:?}");
            assert!(sorted_names(&dir).is_empty(), "left behind: {:?}", sorted_names(&dir));
        }
    }

    /// A folder an output made is removed again when the output fails (every level it made,
    /// not one that was there before or that holds someone else's file), and kept when it
    /// succeeds; the check before makes nothing and says why a folder cannot be made.
    #[test]
    fn a_failed_output_leaves_no_new_folder() {
        let dir = test_dir("newdir");
        let out = dir.join("a/b/c");
        NewDir::check(&out).unwrap();
        assert!(sorted_names(&dir).is_empty(), "the check made something");
        {
            let _made = NewDir::create(&out).unwrap();
            assert!(out.is_dir());
            // The output fails here: its batch is dropped, then the folder.
        }
        assert!(sorted_names(&dir).is_empty(), "left behind: {:?}", sorted_names(&dir));
        // A batch that fails half-way inside a new folder: nothing is left at all.
        {
            let _made = NewDir::create(&out).unwrap();
            let mut batch = Batch::new(true);
            batch.write(&out.join("x.csv"), |w| w.write_all(b"1")).unwrap();
            batch
                .write(&out.join("y.svg"), |_| Err(io::Error::other("No space left on device")))
                .unwrap_err();
        }
        assert!(sorted_names(&dir).is_empty(), "left behind: {:?}", sorted_names(&dir));
        // Someone else's file keeps its folder (and the folders above it).
        {
            let _made = NewDir::create(&out).unwrap();
            fs::write(out.join("theirs.txt"), b"x").unwrap();
        }
        assert!(out.join("theirs.txt").is_file());
        fs::remove_dir_all(dir.join("a")).unwrap();
        // A level that was there before stays.
        fs::create_dir(dir.join("a")).unwrap();
        drop(NewDir::create(&out).unwrap());
        assert_eq!(sorted_names(&dir.join("a")), Vec::<String>::new());
        assert!(dir.join("a").is_dir());
        // Kept on success.
        NewDir::create(&out).unwrap().keep();
        assert!(out.is_dir());
        // Under a file: said, nothing made.
        fs::write(dir.join("file"), b"x").unwrap();
        for err in [
            NewDir::check(&dir.join("file/sub")).unwrap_err(),
            NewDir::create(&dir.join("file/sub/deeper")).err().unwrap(),
        ] {
            assert!(
                err.to_string().contains("/file") && err.to_string().contains("Not a directory"),
                "{err}"
            );
        }
        assert!(!dir.join("file/sub").exists());
    }
}
