//! Writing output files without ever losing one: paths are checked before anything is
//! touched, and the bytes go to a temporary file in the same directory that is renamed over
//! the target only once it is complete and on disk.
//!
//! ```no_run
//! use std::io::Write;
//! use std::path::Path;
//!
//! shaderlab::fsutil::check_png_path(Path::new("out.png"))?; // before any rendering
//! shaderlab::fsutil::write_atomic(Path::new("notes.txt"), |w| writeln!(w, "hello"))?;
//! # Ok::<(), shaderlab::Error>(())
//! ```

use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

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

/// Checks that `path` can name an output file: not an existing directory, and in a directory
/// that exists. Touches nothing.
pub fn check_output_path(path: &Path) -> Result<()> {
    if path.as_os_str().is_empty() {
        return Err(Error::Param("an empty output file name".into()));
    }
    if path.is_dir() {
        return Err(Error::Param(format!(
            "{}: is a directory; give a file name",
            path.display()
        )));
    }
    if path.file_name().is_none() {
        // `dir/..`, `/`: no file name to write.
        return Err(Error::Param(format!("{}: not a file name", path.display())));
    }
    let parent = parent_dir(path);
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

/// Checks that `path` can take a PNG: ends in `.png` (any case) and passes
/// [`check_output_path`]. Run it before rendering, so a bad name fails fast.
pub fn check_png_path(path: &Path) -> Result<()> {
    check_output_path(path)?;
    let is_png = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !is_png {
        return Err(Error::Param(format!(
            "{}: only PNG is written; use a .png name",
            path.display()
        )));
    }
    Ok(())
}

/// Where the bytes really go: through a symbolic link to its target, so that the link stays.
fn resolve_target(path: &Path) -> PathBuf {
    match fs::symlink_metadata(path) {
        Ok(meta) if meta.file_type().is_symlink() => fs::canonicalize(path).unwrap_or_else(|_| path.to_owned()),
        _ => path.to_owned(),
    }
}

/// Creates a fresh `.NAME.tmp-PID-N` next to `target` (never an existing file).
fn create_temp(target: &Path) -> Result<(PathBuf, File)> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let dir = parent_dir(target);
    let name = target.file_name().unwrap_or_default().to_string_lossy();
    loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let temp = dir.join(format!(".{name}.tmp-{}-{n}", std::process::id()));
        match OpenOptions::new().write(true).create_new(true).open(&temp) {
            Ok(file) => return Ok((temp, file)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(source) => {
                return Err(Error::Io {
                    path: target.to_owned(),
                    source,
                })
            }
        }
    }
}

/// Writes `path` all at once: checks it with [`check_output_path`], lets `write` fill a
/// temporary file in the same directory, flushes it to disk and renames it over `path`.
/// If anything fails, the temporary file is removed and an existing `path` is left as it was.
/// A symbolic link is written through (its target is replaced), and an existing file keeps its
/// permissions.
pub fn write_atomic(path: &Path, write: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> Result<()> {
    check_output_path(path)?;
    let target = resolve_target(path);
    let (temp, file) = create_temp(&target)?;
    let fail = |source: io::Error| {
        let _ = fs::remove_file(&temp);
        Error::Io {
            path: path.to_owned(),
            source,
        }
    };
    let mut out = BufWriter::new(file);
    write(&mut out).map_err(fail)?;
    let file = out.into_inner().map_err(|e| fail(e.into_error()))?;
    if let Ok(meta) = fs::metadata(&target) {
        file.set_permissions(meta.permissions()).map_err(fail)?;
    }
    file.sync_all().map_err(fail)?;
    drop(file);
    fs::rename(&temp, &target).map_err(fail)?;
    // Make the rename itself durable (best effort: not every platform can open a directory).
    if let Ok(dir) = File::open(parent_dir(&target)) {
        let _ = dir.sync_all();
    }
    Ok(())
}

/// Whether `a` and `b` name the same existing file (through any path, link or hard link).
pub fn same_file(a: &Path, b: &Path) -> bool {
    let (Ok(ca), Ok(cb)) = (fs::canonicalize(a), fs::canonicalize(b)) else {
        return false;
    };
    if ca == cb {
        return true;
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(ma), Ok(mb)) = (fs::metadata(&ca), fs::metadata(&cb)) {
            return ma.dev() == mb.dev() && ma.ino() == mb.ino();
        }
    }
    false
}

/// A fresh directory under the system's temp directory for one unit test, removed when the
/// test passes (kept for a look when it fails).
#[cfg(test)]
pub(crate) struct ScratchDir {
    root: PathBuf,
    dir: PathBuf,
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

    fn entries(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
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
        assert!(entries(&dir).is_empty(), "checking touched the directory");
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
        assert_eq!(entries(&dir), ["out.csv"]);
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
        assert_eq!(entries(&dir), ["out.png"], "a temporary file was left behind");
        // Nothing there before: nothing there after.
        let new = dir.join("new.png");
        write_atomic(&new, |_| Err(io::Error::other("no"))).unwrap_err();
        assert_eq!(entries(&dir), ["out.png"]);
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
    fn same_file_sees_through_other_paths() {
        let dir = test_dir("same");
        let a = dir.join("a.frag");
        fs::write(&a, b"x").unwrap();
        fs::create_dir(dir.join("sub")).unwrap();
        assert!(same_file(&a, &dir.join("sub/../a.frag")));
        assert!(same_file(&a, &dir.join("./a.frag")));
        #[cfg(unix)]
        {
            fs::hard_link(&a, dir.join("hard.frag")).unwrap();
            assert!(same_file(&a, &dir.join("hard.frag")));
        }
        assert!(!same_file(&a, &dir.join("b.frag")));
        fs::write(dir.join("b.frag"), b"x").unwrap();
        assert!(!same_file(&a, &dir.join("b.frag")));
    }
}
