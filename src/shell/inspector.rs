//! The pixel inspector's sequence, written once for the window and the page (the
//! [`super::session::Session`] owns it): the frame just drawn is encoded again offscreen with
//! its draws written down ([`crate::debug::capture_start`]), their buffers are read back while
//! the shell goes on drawing ([`Inspector::poll`] never blocks), and the pixel is replayed by
//! the runner the shell hands in: a worker thread in the window, so inspecting never stalls
//! its frame loop; inline on the page, which has no threads. A panic in the replay is
//! contained and shown like its errors.

use std::sync::mpsc;

use crate::debug::{Inspection, Pending};
use crate::gpu::Gpu;
use crate::lab::Lab;

/// The replay of one pixel, for a runner to run once ([`Inspector::poll`]).
pub type Job = Box<dyn FnOnce() + Send + 'static>;

/// An inspection, or why there is none (the capture's, the replay's or the runner's error, or
/// the replay's panic), as the panel and the page show it.
pub type Shown = Result<Inspection, String>;

/// The inspector's work in flight and its last result.
#[derive(Default)]
pub struct Inspector {
    /// The buffers being read back, and the pixel.
    pending: Option<(Pending, (u32, u32))>,
    /// The replay handed to the runner, until it sends its result.
    replay: Option<mpsc::Receiver<Shown>>,
    /// The last inspection (or why it failed).
    shown: Option<Shown>,
}

impl Inspector {
    /// Whether a capture or replay is under way.
    pub fn busy(&self) -> bool {
        self.pending.is_some() || self.replay.is_some()
    }

    /// The last inspection, or why it failed; `None` before the first.
    pub fn shown(&self) -> Option<&Shown> {
        self.shown.as_ref()
    }

    /// Starts inspecting `pixel` of `lab`'s frame at `size` in the screen's `format`; returns
    /// whether the result changed (the capture failed: its error is shown).
    pub fn start(
        &mut self,
        gpu: &Gpu,
        lab: &mut dyn Lab,
        size: (u32, u32),
        format: wgpu::TextureFormat,
        pixel: (u32, u32),
    ) -> bool {
        match crate::debug::capture_start(gpu, lab, size, format) {
            Ok(pending) => {
                self.pending = Some((pending, pixel));
                false
            }
            Err(e) => {
                self.shown = Some(Err(e.to_string()));
                true
            }
        }
    }

    /// Moves the work on without blocking: a read-back that finished becomes a [`Job`] handed
    /// to `run` (which starts it, or says why it cannot), a finished replay becomes
    /// [`Inspector::shown`]. `lab` names the lab in the report. Returns whether the result
    /// changed.
    pub fn poll(&mut self, gpu: &Gpu, lab: &'static str, run: impl FnOnce(Job) -> Result<(), String>) -> bool {
        let mut changed = false;
        if let Some((pending, _)) = &self.pending {
            let _ = gpu.device.poll(wgpu::PollType::Poll);
            if pending.ready() {
                let (pending, (x, y)) = self.pending.take().expect("checked above");
                match pending.finish() {
                    Ok(captured) => {
                        let (tx, rx) = mpsc::channel();
                        let job: Job = Box::new(move || {
                            let result = match crate::panics::contained(|| Inspection::new(lab, &captured, x, y)) {
                                Ok(replayed) => replayed.map_err(|e| e.to_string()),
                                Err(report) => Err(report.into_error().to_string()),
                            };
                            let _ = tx.send(result);
                        });
                        match run(job) {
                            Ok(()) => self.replay = Some(rx),
                            Err(e) => {
                                self.shown = Some(Err(e));
                                changed = true;
                            }
                        }
                    }
                    Err(e) => {
                        self.shown = Some(Err(e.to_string()));
                        changed = true;
                    }
                }
            }
        }
        if let Some(rx) = &self.replay {
            let result = match rx.try_recv() {
                Ok(result) => Some(result),
                Err(mpsc::TryRecvError::Empty) => None,
                Err(mpsc::TryRecvError::Disconnected) => {
                    Some(Err("the inspector's replay ended without a result".into()))
                }
            };
            if let Some(result) = result {
                self.replay = None;
                self.shown = Some(result);
                changed = true;
            }
        }
        changed
    }

    /// Forgets the result (inspect mode turned off).
    pub fn clear(&mut self) {
        self.shown = None;
    }
}

/// The window's runner: the replay on a worker thread of its own.
#[cfg(not(target_arch = "wasm32"))]
pub fn on_a_thread(job: Job) -> Result<(), String> {
    std::thread::Builder::new()
        .name("shaderlab-inspect".into())
        .spawn(job)
        .map(drop)
        .map_err(|e| format!("cannot start the inspector's thread: {e}"))
}

/// The page's runner: the replay at once, on the page's only thread.
pub fn inline(job: Job) -> Result<(), String> {
    job();
    Ok(())
}
