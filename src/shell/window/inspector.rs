//! The window's pixel inspector (F2, then a click): the frame just shown is recorded again
//! with its draws written down ([`crate::debug::capture_start`], as the page does), their
//! buffers are read back while the next frames are drawn, and the pixel is replayed on a
//! worker thread, so inspecting never stalls the frame loop. A change to the lab (a
//! parameter, a key, a saved shader, an animated lab's clock) inspects again.

use std::sync::mpsc;

use crate::debug::{Inspection, Pending};
use crate::gpu::Gpu;
use crate::lab::Lab;

/// The inspector's work in flight and its last result.
#[derive(Default)]
pub struct Inspector {
    /// The buffers being read back, and the pixel.
    pending: Option<(Pending, (u32, u32))>,
    /// The replay running on a worker thread.
    worker: Option<mpsc::Receiver<Result<Inspection, String>>>,
    /// The last inspection (or why it failed), for the panel.
    pub shown: Option<Result<Inspection, String>>,
}

impl Inspector {
    /// Whether a new capture can start (none is in flight).
    pub fn idle(&self) -> bool {
        self.pending.is_none() && self.worker.is_none()
    }

    /// Whether a capture or replay is under way.
    pub fn busy(&self) -> bool {
        !self.idle()
    }

    /// Starts inspecting `pixel` of `lab`'s frame at `size` in the screen's `format`.
    pub fn start(
        &mut self,
        gpu: &Gpu,
        lab: &mut dyn Lab,
        size: (u32, u32),
        format: wgpu::TextureFormat,
        pixel: (u32, u32),
    ) {
        match crate::debug::capture_start(gpu, lab, size, format) {
            Ok(pending) => self.pending = Some((pending, pixel)),
            Err(e) => {
                self.done(Err(e.to_string()));
            }
        }
    }

    /// Moves the work on without blocking: a read-back that finished goes to a worker thread,
    /// a finished replay becomes [`Inspector::shown`]. Returns whether the result changed.
    pub fn poll(&mut self, gpu: &Gpu, lab: &'static str) -> bool {
        if let Some((pending, _)) = &self.pending {
            let _ = gpu.device.poll(wgpu::PollType::Poll);
            if pending.ready() {
                let (pending, (x, y)) = self.pending.take().expect("checked above");
                match pending.finish() {
                    Ok(captured) => {
                        let (tx, rx) = mpsc::channel();
                        let spawned = std::thread::Builder::new()
                            .name("shaderlab-inspect".into())
                            .spawn(move || {
                                // A panic in the replay is said in the panel, like its errors.
                                let result = match crate::panics::contained(|| Inspection::new(lab, &captured, x, y)) {
                                    Ok(replayed) => replayed.map_err(|e| e.to_string()),
                                    Err(report) => Err(report.into_error().to_string()),
                                };
                                let _ = tx.send(result);
                            });
                        match spawned {
                            Ok(_) => self.worker = Some(rx),
                            Err(e) => return self.done(Err(format!("cannot start the inspector's thread: {e}"))),
                        }
                    }
                    Err(e) => return self.done(Err(e.to_string())),
                }
            }
        }
        if let Some(rx) = &self.worker {
            match rx.try_recv() {
                Ok(result) => {
                    self.worker = None;
                    return self.done(result);
                }
                Err(mpsc::TryRecvError::Empty) => {}
                Err(mpsc::TryRecvError::Disconnected) => {
                    self.worker = None;
                    return self.done(Err("the inspector's thread ended without a result".into()));
                }
            }
        }
        false
    }

    fn done(&mut self, result: Result<Inspection, String>) -> bool {
        self.shown = Some(result);
        true
    }

    /// Forgets the result (inspect mode turned off).
    pub fn clear(&mut self) {
        self.shown = None;
    }
}
