//! The run's inputs: every file the process reads as a user file (a model, a picture, a shader
//! and every file it `#include`s) is noted here by [`super::read_user_file`], and a tool may
//! note a file before it reads it ([`note`]). Every output is checked against this one list
//! ([`check`], called by [`super::check_output_path`], so by every writer of [`super`]): an
//! output that is, or leads to, one of the inputs is refused with a message naming the input.
//!
//! A file is the same as an input when its canonical path is the input's, or when it has the
//! input's device and inode now: symbolic links, `..`, other spellings and hard links are all
//! caught. The input's device and inode are read at the time of the check, not kept from when
//! it was read, so an input that was deleted meanwhile (whose inode number the file system may
//! give to a new file) protects nothing.

use std::fs;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, PoisonError};

use super::{Dest, Stream};
use crate::error::{Error, Result};

/// One input of the run.
struct Input {
    /// The name it was read by, for messages.
    path: PathBuf,
    /// What it is, in the plural, as [`super::read_user_file`] names it (`pictures`,
    /// `OBJ models`, `shader files`).
    what: String,
    /// Its canonical path when it was noted.
    canonical: PathBuf,
}

/// The inputs, each once (by canonical path). A window that reloads its shaders reads the same
/// files again, so the list holds at most the distinct files of the run.
static INPUTS: Mutex<Vec<Input>> = Mutex::new(Vec::new());

/// Notes `path` as one of the run's inputs; `what` names its kind in the plural (`shader
/// files`). A file that does not exist is not noted (there is nothing to protect).
pub fn note(path: &Path, what: &str) {
    let Ok(canonical) = fs::canonicalize(path) else {
        return;
    };
    let mut inputs = INPUTS.lock().unwrap_or_else(PoisonError::into_inner);
    if inputs.iter().any(|i| i.canonical == canonical) {
        return;
    }
    inputs.push(Input {
        path: path.to_owned(),
        what: what.to_owned(),
        canonical,
    });
}

/// Refuses `dest` (what the output `path` names) when it is one of the run's inputs.
pub(super) fn check(path: &Path, dest: &Dest) -> Result<()> {
    let inputs = INPUTS.lock().unwrap_or_else(PoisonError::into_inner);
    if inputs.is_empty() {
        return Ok(());
    }
    let found = match dest {
        Dest::File(target) => {
            let canonical = fs::canonicalize(target).ok();
            let id = file_id(target);
            inputs.iter().find(|input| {
                canonical.as_ref() == Some(&input.canonical) || (id.is_some() && id == file_id(&input.canonical))
            })
        }
        Dest::Stream(Stream::Fd(fd)) => {
            let id = fd_id(*fd);
            inputs
                .iter()
                .find(|input| id.is_some() && id == file_id(&input.canonical))
        }
        // FIFOs and devices: never a regular file, which every input is.
        Dest::Stream(_) => None,
    };
    match found {
        Some(input) => Err(Error::Param(format!(
            "{}: would replace {}, one of the {} this run reads; an output never replaces an \
             input: choose another name",
            path.display(),
            input.path.display(),
            input.what
        ))),
        None => Ok(()),
    }
}

/// The device and inode of the file `path` leads to now, if it exists.
#[cfg(unix)]
fn file_id(path: &Path) -> Option<(u64, u64)> {
    use std::os::unix::fs::MetadataExt;
    fs::metadata(path).ok().map(|m| (m.dev(), m.ino()))
}

#[cfg(not(unix))]
fn file_id(_: &Path) -> Option<(u64, u64)> {
    None
}

/// The device and inode of the regular file open on descriptor `fd` (a shell's `3<>FILE`).
#[cfg(unix)]
fn fd_id(fd: i32) -> Option<(u64, u64)> {
    // SAFETY: a struct of plain integers, for which all zeroes is a valid value.
    let mut stat: libc::stat = unsafe { std::mem::zeroed() };
    // SAFETY: fstat fills the struct, or fails (EBADF on a closed descriptor).
    if unsafe { libc::fstat(fd, &mut stat) } != 0 || stat.st_mode & libc::S_IFMT != libc::S_IFREG {
        return None;
    }
    #[allow(clippy::unnecessary_cast)]
    Some((stat.st_dev as u64, stat.st_ino as u64))
}

#[cfg(not(unix))]
fn fd_id(_: i32) -> Option<(u64, u64)> {
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fsutil::{check_output_path, sorted_names, write_atomic, ScratchDir};

    /// An input is refused as an output by any path that leads to it (another spelling, a
    /// symbolic link, a hard link), with a message naming it; its bytes stay; other files and
    /// new names are written as before.
    #[test]
    fn every_path_to_an_input_is_refused() {
        let dir = ScratchDir::new("inputs-paths");
        let input = dir.join("tex.png");
        fs::write(&input, b"the picture").unwrap();
        crate::fsutil::read_user_file(&input, 100, "pictures").unwrap();
        fs::create_dir(dir.join("sub")).unwrap();
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(&input, dir.join("link.png")).unwrap();
            fs::hard_link(&input, dir.join("hard.png")).unwrap();
        }
        for name in ["tex.png", "sub/../tex.png", "./tex.png", "link.png", "hard.png"] {
            let out = dir.join(name);
            if fs::symlink_metadata(&out).is_err() {
                continue;
            }
            let err = write_atomic(&out, |w| w.write_all(b"a screenshot")).unwrap_err();
            assert!(matches!(err, Error::Param(_)), "{name}: {err:?}");
            let message = err.to_string();
            assert!(
                message.contains(&format!(
                    "would replace {}, one of the pictures this run reads",
                    input.display()
                )),
                "{name}: {message}"
            );
            assert_eq!(fs::read(&input).unwrap(), b"the picture", "{name} changed the input");
        }
        // Another file, and a new name, are outputs as before.
        fs::write(dir.join("other.png"), b"x").unwrap();
        write_atomic(&dir.join("other.png"), |w| w.write_all(b"y")).unwrap();
        check_output_path(&dir.join("new.png")).unwrap();
        assert!(!sorted_names(&dir).iter().any(|n| n.starts_with(".sl-")));
    }

    /// A deleted input protects no other file: a new file, which the file system may give the
    /// deleted input's inode number, is an output like any other.
    #[test]
    fn a_deleted_input_protects_nothing() {
        let dir = ScratchDir::new("inputs-deleted");
        let input = dir.join("model.obj");
        fs::write(&input, b"v 0 0 0").unwrap();
        note(&input, "OBJ models");
        fs::remove_file(&input).unwrap();
        let other = dir.join("new.obj");
        fs::write(&other, b"new").unwrap();
        write_atomic(&other, |w| w.write_all(b"newer")).unwrap();
        assert_eq!(fs::read(&other).unwrap(), b"newer");
    }

    /// The process's own descriptor open on an input (`--screenshot /dev/fd/3 3<>tex.png`)
    /// is refused too.
    #[cfg(target_os = "linux")]
    #[test]
    fn a_descriptor_open_on_an_input_is_refused() {
        use std::os::fd::AsRawFd;
        let dir = ScratchDir::new("inputs-fd");
        let input = dir.join("a.frag");
        fs::write(&input, b"void main() {}").unwrap();
        note(&input, "shader files");
        let file = fs::OpenOptions::new().read(true).write(true).open(&input).unwrap();
        let path = PathBuf::from(format!("/proc/self/fd/{}", file.as_raw_fd()));
        let err = check_output_path(&path).unwrap_err().to_string();
        assert!(err.contains("one of the shader files this run reads"), "{err}");
        assert_eq!(fs::read(&input).unwrap(), b"void main() {}");
    }
}
