//! Live reload from files, for the window: the shader folder and the folders of the lab's input
//! files watched, and each save built anew off the frame loop.
//!
//! Each save builds the lab anew on a worker thread ([`Sources::build`], as the session opened
//! it), so that a compile taking minutes (a large array on a CPU driver) never stops the frame
//! loop: the lab shown keeps drawing, keys and Esc keep working, and the lab of the newest save
//! that finished compiling takes its place ([`Session::rebuilt`]; an older one finishing later
//! is dropped). A compile that fails or panics leaves the last good pipeline drawing
//! ([`Session::rebuild_failed`]). The page reloads the same session with its edited texts at
//! once instead ([`Session::reload`]): it has no files to watch and no threads.

use std::path::PathBuf;
use std::sync::{mpsc, Arc};
use std::time::{Duration, Instant};

use super::session::{Session, Sources};
use crate::error::{Error, Result};
use crate::gpu::Gpu;
use crate::lab::Lab;
use crate::shader::ShaderSource;

/// How many compiles may run at once: a save while one compiles (a fix of a shader that
/// compiles for minutes) starts another; later saves wait for one of them to end.
const MAX_COMPILES: usize = 2;

/// How long editors get to finish writing a save before it is compiled.
const SAVE_SETTLE: Duration = Duration::from_millis(50);

/// How long a compile runs before the title says so.
const SAY_COMPILING_AFTER: Duration = Duration::from_millis(500);

/// What a compile on a worker thread gives: the lab built anew, or why not (an error, or a
/// panic inside the compile).
type Compiled = std::result::Result<Result<Box<dyn Lab>>, crate::panics::Report>;

/// What live reload did, for the window to say (its title, the terminal, the tests' signals).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Event {
    /// The compile of save N started.
    Started(u64),
    /// The compile of save N ended.
    Ended(u64),
    /// A save's lab took the place of the lab shown (`fixed`: a shader error stood before).
    Reloaded {
        /// Whether it fixed a shader error.
        fixed: bool,
    },
    /// A save did not build: the last good pipeline keeps drawing.
    Failed(String),
    /// Whether the title should say that a compile runs changed.
    Compiling(bool),
}

/// Live reload's watcher and compiles (see the module docs).
pub struct LiveReload {
    watcher: Option<(notify::RecommendedWatcher, mpsc::Receiver<()>)>,
    /// Wakes the frame loop when a compile ends.
    wake: Arc<dyn Fn() + Send + Sync>,
    /// `SHADERLAB_TEST_PANIC=reload`: each compile panics, to show what that looks like.
    panic_in_compile: bool,
    /// A save was seen: it is compiled at this time, once the editor has finished writing.
    due: Option<Instant>,
    /// The compiles running: the number of their save, when they started, their result.
    running: Vec<(u64, Instant, mpsc::Receiver<Compiled>)>,
    /// Saves compiled so far (the last one's number).
    started: u64,
    /// The number of the save whose result is shown (its lab, or its error).
    shown: u64,
    /// Whether the title says that a compile runs.
    said: bool,
}

impl LiveReload {
    /// Watches the files `sources` reads (its shader folder and the folders of its input
    /// files); `wake` wakes the frame loop when a compile ends.
    pub fn new(sources: &Sources, wake: Arc<dyn Fn() + Send + Sync>, panic_in_compile: bool) -> LiveReload {
        LiveReload {
            watcher: watch(sources),
            wake,
            panic_in_compile,
            due: None,
            running: Vec::new(),
            started: 0,
            shown: 0,
            said: false,
        }
    }

    /// Watches `sources` from now on (the shaders moved to a folder of their own).
    pub fn watch(&mut self, sources: &Sources) {
        self.watcher = watch(sources);
    }

    /// Whether files are watched.
    pub fn watching(&self) -> bool {
        self.watcher.is_some()
    }

    /// Whether a compile still runs on a worker thread.
    pub fn compiling(&self) -> bool {
        !self.running.is_empty()
    }

    /// Whether the title says that a compile runs.
    pub fn says_compiling(&self) -> bool {
        self.said
    }

    /// Moves live reload on without blocking: notes saves, starts their compiles once the
    /// editor has finished writing, and shows the compiles that ended in `session`. Returns
    /// what happened, in order.
    pub fn check(&mut self, session: &mut Session, gpu: &Arc<Gpu>) -> Vec<Event> {
        let mut events = Vec::new();
        if let Some((_, rx)) = &self.watcher {
            let mut saved = false;
            while rx.try_recv().is_ok() {
                saved = true;
            }
            if saved {
                // Editors write in several steps: compile once they are done.
                self.due = Some(Instant::now() + SAVE_SETTLE);
            }
        }
        self.finish(session, &mut events);
        let due = self.due.is_some_and(|at| Instant::now() >= at);
        if due && self.running.len() < MAX_COMPILES {
            self.due = None;
            self.start(session, gpu, &mut events);
        }
        let say = self.say_at().is_some_and(|at| Instant::now() >= at);
        if say != self.said {
            self.said = say;
            events.push(Event::Compiling(say));
        }
        events
    }

    /// When the loop must wake for live reload: a save to compile, or a compile to say in the
    /// title.
    pub fn wake_at(&self) -> Option<Instant> {
        let due = self.due.filter(|_| self.running.len() < MAX_COMPILES);
        let say = self.say_at().filter(|_| !self.said);
        due.into_iter().chain(say).min()
    }

    /// When the title should say that a compile runs: a compile newer than the result shown
    /// has run for [`SAY_COMPILING_AFTER`].
    fn say_at(&self) -> Option<Instant> {
        self.running
            .iter()
            .filter(|(n, _, _)| *n > self.shown)
            .map(|(_, at, _)| *at + SAY_COMPILING_AFTER)
            .min()
    }

    /// Builds the lab anew from the saved shaders on a worker thread.
    fn start(&mut self, session: &mut Session, gpu: &Arc<Gpu>, events: &mut Vec<Event>) {
        self.started += 1;
        let number = self.started;
        let (tx, rx) = mpsc::channel();
        let gpu = gpu.clone();
        let sources = session.sources().clone();
        let entry = session.entry();
        let wake = self.wake.clone();
        let panic_in_compile = self.panic_in_compile;
        let spawned = std::thread::Builder::new()
            .name("shaderlab-compile".into())
            .spawn(move || {
                let compiled = crate::panics::contained(|| {
                    if panic_in_compile {
                        panic!("SHADERLAB_TEST_PANIC=reload");
                    }
                    sources.build(&gpu, entry)
                });
                let _ = tx.send(compiled);
                wake();
            });
        match spawned {
            Ok(_) => {
                self.running.push((number, Instant::now(), rx));
                events.push(Event::Started(number));
            }
            Err(e) => self.show(
                session,
                number,
                Err(Error::Internal(format!(
                    "cannot start a thread to compile the shaders: {e}"
                ))),
                events,
            ),
        }
    }

    /// Shows the compiles that ended: the newest save's lab, or its error.
    fn finish(&mut self, session: &mut Session, events: &mut Vec<Event>) {
        let mut ended = Vec::new();
        self.running.retain(|(number, _, rx)| match rx.try_recv() {
            Ok(compiled) => {
                ended.push((*number, compiled));
                false
            }
            Err(mpsc::TryRecvError::Empty) => true,
            Err(mpsc::TryRecvError::Disconnected) => {
                ended.push((
                    *number,
                    Ok(Err(Error::Internal(
                        "the compile's thread ended without a result".into(),
                    ))),
                ));
                false
            }
        });
        for (number, compiled) in ended {
            events.push(Event::Ended(number));
            let built = compiled.unwrap_or_else(|report| Err(report.into_error()));
            self.show(session, number, built, events);
        }
    }

    /// Shows the result of save `number`'s compile, unless a newer save's is shown already.
    fn show(&mut self, session: &mut Session, number: u64, built: Result<Box<dyn Lab>>, events: &mut Vec<Event>) {
        if number <= self.shown {
            return;
        }
        self.shown = number;
        let fixed = session.shader_error().is_some();
        match built {
            Ok(lab) => {
                session.rebuilt(lab);
                events.push(Event::Reloaded { fixed });
            }
            Err(e) => {
                session.rebuild_failed(e.to_string());
                events.push(Event::Failed(e.to_string()));
            }
        }
        let say = self.say_at().is_some_and(|at| Instant::now() >= at);
        if say != self.said {
            self.said = say;
            events.push(Event::Compiling(say));
        }
    }
}

/// Watches the shader folder of `sources` and the folders of its input files for saves of
/// shader files and of the inputs; `None` where nothing is read from files (or watching
/// failed, said on stderr).
fn watch(sources: &Sources) -> Option<(notify::RecommendedWatcher, mpsc::Receiver<()>)> {
    use notify::Watcher;
    let mut dirs: Vec<PathBuf> = match &sources.source {
        ShaderSource::Dir(dir) => vec![dir.clone()],
        ShaderSource::Embedded | ShaderSource::Edited(_) => Vec::new(),
    };
    let inputs = &sources.files.inputs;
    for input in inputs {
        let dir = match input.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        if !dirs.contains(&dir) {
            dirs.push(dir);
        }
    }
    if dirs.is_empty() {
        return None;
    }
    let names: Vec<std::ffi::OsString> = inputs
        .iter()
        .filter_map(|p| p.file_name().map(|n| n.to_owned()))
        .collect();
    let (tx, rx) = mpsc::channel();
    let mut watcher = notify::recommended_watcher(move |event: notify::Result<notify::Event>| {
        if let Ok(event) = event {
            // Only shader files and the lab's inputs: a screenshot written into the folder is
            // not an edit.
            let shader = event.paths.iter().any(|p| {
                matches!(
                    p.extension().and_then(|e| e.to_str()),
                    Some("vert" | "frag" | "glsl" | "comp")
                ) || p.file_name().is_some_and(|n| names.iter().any(|m| m == n))
            });
            if shader && (event.kind.is_modify() || event.kind.is_create()) {
                let _ = tx.send(());
            }
        }
    })
    .map_err(|e| eprintln!("live reload disabled: {e}"))
    .ok()?;
    for dir in &dirs {
        watcher
            .watch(dir, notify::RecursiveMode::NonRecursive)
            .map_err(|e| eprintln!("live reload disabled: cannot watch {}: {e}", dir.display()))
            .ok()?;
    }
    Some((watcher, rx))
}
