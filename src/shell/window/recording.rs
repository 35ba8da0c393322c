//! F10 in a window: what is shown, frame by frame, into a looping GIF in the current directory
//! (named as F12's screenshots are), written whole when F10 stops it or the window closes.
//! Each frame is the lab drawn again offscreen at the window's size (as F12 does), so the file
//! holds the lab's pixels only; its delay is the time the window showed it.

use std::cell::RefCell;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::time::Instant;

use image::codecs::gif::{GifEncoder, Repeat};

use crate::error::{Error, Result};
use crate::fsutil::AtomicFile;
use crate::gpu::Gpu;
use crate::lab::Lab;
use crate::offscreen::Offscreen;

/// The temporary file, shared by the encoder (which writes) and the recording (which commits).
#[derive(Clone)]
struct Shared(Rc<RefCell<Option<AtomicFile>>>);

impl Write for Shared {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match self.0.borrow_mut().as_mut() {
            Some(f) => f.write(buf),
            None => Err(io::Error::other("the recording was closed")),
        }
    }
    fn flush(&mut self) -> io::Result<()> {
        self.0.borrow_mut().as_mut().map_or(Ok(()), Write::flush)
    }
}

/// A recording in progress.
pub struct Recording {
    path: PathBuf,
    file: Shared,
    encoder: Option<GifEncoder<Shared>>,
    /// The last frame, waiting for the next one to know how long it was shown.
    pending: Option<(image::RgbaImage, Instant)>,
    frames: u32,
    /// Where frames are drawn, kept while the window keeps its size and format.
    target: Option<Offscreen>,
}

impl Recording {
    /// Starts writing `path`.
    pub fn start(path: &Path) -> Result<Recording> {
        let file = Shared(Rc::new(RefCell::new(Some(AtomicFile::create(path)?))));
        let mut encoder = GifEncoder::new_with_speed(file.clone(), 10);
        encoder.set_repeat(Repeat::Infinite).map_err(|e| gif_error(path, e))?;
        Ok(Recording {
            path: path.to_owned(),
            file,
            encoder: Some(encoder),
            pending: None,
            frames: 0,
            target: None,
        })
    }

    /// Frames so far.
    pub fn frames(&self) -> u32 {
        self.frames
    }

    /// Adds what the window shows now: `lab` drawn at `width` × `height` in `format`.
    pub fn add(
        &mut self,
        gpu: &Gpu,
        lab: &mut dyn Lab,
        width: u32,
        height: u32,
        format: wgpu::TextureFormat,
    ) -> Result<()> {
        let fits = |t: &Offscreen| t.width == width && t.height == height && t.format() == format;
        if !self.target.as_ref().is_some_and(fits) {
            self.target = Some(Offscreen::with_format(gpu, width, height, format));
        }
        let target = self.target.as_ref().expect("made above");
        crate::lab::frame::render_into(gpu, lab, target)?;
        let image = target.read(gpu)?;
        let now = Instant::now();
        if let Some((previous, at)) = self.pending.replace((image, now)) {
            self.encode(previous, now - at)?;
        }
        self.frames += 1;
        Ok(())
    }

    fn encode(&mut self, image: image::RgbaImage, shown: std::time::Duration) -> Result<()> {
        // GIF counts hundredths of a second; 0 would mean "as fast as possible" to viewers.
        let centis = ((shown.as_secs_f64() * 100.0).round() as u32).clamp(1, 65535);
        let delay = image::Delay::from_numer_denom_ms(centis * 10, 1);
        let encoder = self.encoder.as_mut().expect("open until finished");
        encoder
            .encode_frame(image::Frame::from_parts(image, 0, 0, delay))
            .map_err(|e| gif_error(&self.path, e))
    }

    /// Ends the recording and renames the file into place.
    pub fn finish(mut self) -> Result<PathBuf> {
        if let Some((image, at)) = self.pending.take() {
            self.encode(image, at.elapsed())?;
        }
        // Dropping the encoder writes GIF's trailer.
        drop(self.encoder.take());
        let file = self.file.0.borrow_mut().take().expect("open until finished");
        file.commit()?;
        Ok(self.path.clone())
    }
}

fn gif_error(path: &Path, e: image::ImageError) -> Error {
    Error::Io {
        path: path.to_owned(),
        source: io::Error::other(e.to_string()),
    }
}
