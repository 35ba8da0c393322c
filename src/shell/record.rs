//! `--record OUT --frames N [--fps F] [--from T]`: frames rendered offscreen at a fixed time
//! step (frame k at time T + k/F), so two runs write the same bytes. What `OUT` names decides
//! the form: `*.gif` an animated GIF (image's encoder, looping), a name holding `%0Nd` or an
//! existing directory a PNG sequence, `*.mp4`/`*.webm` a video through `ffmpeg`.
//!
//! Every output appears whole or not at all: a GIF or video is written to a temporary file
//! renamed into place ([`crate::fsutil::write_atomic`]); a PNG sequence is written beside its
//! names and moved into them together at the end ([`crate::fsutil::Batch`]), never over an
//! existing file (it stops before rendering when one of its names exists, and fails whole if
//! another program takes one meanwhile). A failure, SIGINT, SIGTERM or SIGHUP half-way leaves
//! the folder as it was.

use std::io::{self, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use crate::error::{Error, Result};
use crate::gpu::Gpu;
use crate::lab::Lab;
use crate::offscreen::{Offscreen, COLOR_FORMAT};

/// Frames a recording may hold.
pub const MAX_FRAMES: u32 = 100_000;

/// What `--record` writes.
#[derive(Clone, Debug, PartialEq)]
pub enum Output {
    /// An animated GIF.
    Gif(PathBuf),
    /// PNG files; the name of frame k.
    Pngs(Sequence),
    /// A video that `ffmpeg` encodes (`mp4` or `webm`).
    Video(PathBuf, &'static str),
}

/// The names of a PNG sequence: `prefix` + k with `width` digits + `suffix`.
#[derive(Clone, Debug, PartialEq)]
pub struct Sequence {
    prefix: String,
    width: usize,
    suffix: String,
}

impl Sequence {
    /// The file of frame `k`.
    pub fn name(&self, k: u32) -> PathBuf {
        PathBuf::from(format!("{}{k:0w$}{}", self.prefix, self.suffix, w = self.width))
    }
}

/// How a recording runs.
#[derive(Clone, Debug, PartialEq)]
pub struct Recording {
    /// Where it goes.
    pub output: Output,
    /// How many frames.
    pub frames: u32,
    /// Frames per second of lab time.
    pub fps: f64,
    /// Lab time of the first frame.
    pub from: f64,
}

impl Recording {
    /// The lab time of frame `k`: FROM + k/FPS.
    pub fn time(&self, k: u32) -> f64 {
        self.from + f64::from(k) / self.fps
    }

    /// The lab time of the last frame.
    pub fn last_time(&self) -> f64 {
        self.time(self.frames.saturating_sub(1))
    }
}

impl Output {
    /// What `path` asks for, for lab `lab` (directories get `LAB-0000.png` …); a usage error
    /// for any other name.
    pub fn parse(path: &Path, lab: &str) -> Result<Output> {
        let text = path.to_string_lossy();
        if path.is_dir() {
            let prefix = path.join(format!("{lab}-")).to_string_lossy().into_owned();
            return Ok(Output::Pngs(Sequence {
                prefix,
                width: 4,
                suffix: ".png".into(),
            }));
        }
        if let Some(at) = text.find('%') {
            let rest = &text[at + 1..];
            let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
            let width = digits.trim_start_matches('0').parse::<usize>().unwrap_or(1).min(9);
            let suffix = rest[digits.len()..].strip_prefix('d').ok_or_else(|| bad_name(path))?;
            // One folder for the whole sequence (the number names files, not folders).
            if suffix.contains(['%', '/', std::path::MAIN_SEPARATOR]) || !suffix.to_ascii_lowercase().ends_with(".png")
            {
                return Err(bad_name(path));
            }
            return Ok(Output::Pngs(Sequence {
                prefix: text[..at].to_owned(),
                width,
                suffix: suffix.to_owned(),
            }));
        }
        let extension = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
        match extension.as_deref() {
            Some("gif") => Ok(Output::Gif(path.to_owned())),
            Some("mp4") => Ok(Output::Video(path.to_owned(), "mp4")),
            Some("webm") => Ok(Output::Video(path.to_owned(), "webm")),
            _ => Err(bad_name(path)),
        }
    }

    /// Checks the names and tools before anything is rendered: the folder can be written, no
    /// frame of a PNG sequence exists, `ffmpeg` is on `PATH` for a video.
    pub fn check(&self, frames: u32) -> Result<()> {
        match self {
            Output::Gif(path) => crate::fsutil::check_writable(path),
            Output::Video(path, _) => {
                crate::fsutil::check_writable(path)?;
                if find_on_path("ffmpeg").is_none() {
                    // A file called ffmpeg that cannot run is named, not called missing.
                    let unusable = std::env::var_os("PATH").and_then(|p| {
                        std::env::split_paths(&p)
                            .map(|d| d.join("ffmpeg"))
                            .find(|f| f.is_file())
                    });
                    let why = match unusable {
                        Some(f) => format!(
                            "writing a video needs ffmpeg; {} is on PATH but is not executable (chmod +x it, or install ffmpeg: apt-get install ffmpeg)",
                            f.display()
                        ),
                        None => "writing a video needs ffmpeg, which is not on PATH (Debian/Ubuntu: apt-get install ffmpeg)".into(),
                    };
                    return Err(Error::Io {
                        path: path.clone(),
                        source: io::Error::new(
                            io::ErrorKind::NotFound,
                            format!("{why}; a .gif or a PNG sequence (OUT-%04d.png) needs nothing more"),
                        ),
                    });
                }
                Ok(())
            }
            Output::Pngs(sequence) => {
                crate::fsutil::check_writable(&sequence.name(0))?;
                for k in 0..frames {
                    let name = sequence.name(k);
                    if std::fs::symlink_metadata(&name).is_ok() {
                        return Err(Error::Io {
                            path: name,
                            source: io::Error::new(
                                io::ErrorKind::AlreadyExists,
                                "exists; a PNG sequence never overwrites: remove the old frames or choose another name",
                            ),
                        });
                    }
                }
                Ok(())
            }
        }
    }
}

fn bad_name(path: &Path) -> Error {
    Error::Param(format!(
        "--record {}: expected NAME.gif, NAME.mp4, NAME.webm, a PNG sequence such as frames-%04d.png, or an existing directory",
        path.display()
    ))
}

/// The first executable file called `program` in `PATH` (a file there without the execute
/// permission is passed over, as the shell does).
fn find_on_path(program: &str) -> Option<PathBuf> {
    let executable = |p: &Path| {
        let Ok(meta) = std::fs::metadata(p) else { return false };
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            meta.is_file() && meta.permissions().mode() & 0o111 != 0
        }
        #[cfg(not(unix))]
        meta.is_file()
    };
    std::env::split_paths(&std::env::var_os("PATH")?)
        .map(|dir| dir.join(program))
        .find(|p| executable(p))
}

/// The GIF frame delay for `fps` in GIF's unit (1/100 s, at least 1), and a note when it is
/// not exact.
pub fn gif_delay(fps: f64) -> (u32, Option<String>) {
    let exact = 100.0 / fps;
    let centis = exact.round().clamp(1.0, 65535.0) as u32;
    let note = ((exact - f64::from(centis)).abs() > 1e-9).then(|| {
        format!(
            "GIF delays are whole hundredths of a second: {fps} fps is written as {centis}/100 s per frame ({:.2} fps)",
            100.0 / f64::from(centis)
        )
    });
    (centis, note)
}

/// Renders and writes the recording; `progress` is told after each frame.
pub fn record(
    gpu: &Gpu,
    lab: &mut dyn Lab,
    recording: &Recording,
    width: u32,
    height: u32,
    progress: &mut dyn FnMut(u32),
) -> Result<()> {
    // A signal stops the recording between frames; what it wrote is removed as it unwinds, and
    // the process then ends as the signal asked.
    let _deferred = crate::fsutil::signals::defer();
    let target = Offscreen::with_format(gpu, width, height, COLOR_FORMAT);
    let has_time = lab.params().has("time");
    let mut frame = |k: u32| -> Result<image::RgbaImage> {
        crate::fsutil::signals::check()?;
        if has_time {
            lab.params_mut().set("time", &[recording.time(k)])?;
        }
        crate::lab::frame::render_into(gpu, lab, &target)?;
        let image = target.read(gpu)?;
        progress(k + 1);
        Ok(image)
    };
    match &recording.output {
        Output::Pngs(sequence) => {
            let mut batch = crate::fsutil::Batch::new(false);
            for k in 0..recording.frames {
                let image = frame(k)?;
                let name = sequence.name(k);
                batch.write(&name, |w| crate::offscreen::write_png(&image, w))?;
            }
            crate::fsutil::signals::check()?;
            batch.commit()
        }
        Output::Gif(path) => {
            let (centis, _) = gif_delay(recording.fps);
            with_errors(path, |w, failed| {
                use image::codecs::gif::{GifEncoder, Repeat};
                // Speed 10 of 1–30: NeuQuant learns the palette from a tenth of the pixels (1:
                // from every pixel), with no visible loss on these flat-shaded pictures.
                let mut encoder = GifEncoder::new_with_speed(w, 10);
                encoder.set_repeat(Repeat::Infinite).map_err(io::Error::other)?;
                for k in 0..recording.frames {
                    let image = frame(k).map_err(&mut *failed)?;
                    let delay = image::Delay::from_numer_denom_ms(centis * 10, 1);
                    encoder
                        .encode_frame(image::Frame::from_parts(image, 0, 0, delay))
                        .map_err(io::Error::other)?;
                }
                Ok(())
            })
        }
        Output::Video(path, format) => {
            let ffmpeg = find_on_path("ffmpeg").ok_or_else(|| Error::Io {
                path: path.clone(),
                source: io::Error::new(io::ErrorKind::NotFound, "ffmpeg is not on PATH"),
            })?;
            with_errors(path, |w, failed| {
                let mut child = Command::new(&ffmpeg)
                    .args([
                        "-hide_banner",
                        "-loglevel",
                        "error",
                        "-f",
                        "rawvideo",
                        "-pix_fmt",
                        "rgba",
                    ])
                    .args([
                        "-s",
                        &format!("{width}x{height}"),
                        "-r",
                        &recording.fps.to_string(),
                        "-i",
                        "-",
                    ])
                    .args(["-pix_fmt", "yuv420p", "-f", format])
                    // mp4 into a pipe must be fragmented (its index cannot be written back).
                    .args(if *format == "mp4" {
                        &["-movflags", "frag_keyframe+empty_moov"][..]
                    } else {
                        &[][..]
                    })
                    .arg("-")
                    .stdin(Stdio::piped())
                    .stdout(Stdio::piped())
                    .stderr(Stdio::piped())
                    .spawn()
                    .map_err(|e| {
                        failed(Error::Io {
                            path: ffmpeg.clone(),
                            source: io::Error::new(e.kind(), format!("cannot run ffmpeg: {e}")),
                        })
                    })?;
                let mut stdout = child.stdout.take().expect("piped");
                let mut stderr = child.stderr.take().expect("piped");
                let reader = std::thread::spawn(move || {
                    let mut out = Vec::new();
                    stdout.read_to_end(&mut out).map(|_| out)
                });
                let errors = std::thread::spawn(move || {
                    let mut text = String::new();
                    let _ = stderr.read_to_string(&mut text);
                    text
                });
                let mut stdin = child.stdin.take().expect("piped");
                let mut result = Ok(());
                for k in 0..recording.frames {
                    match frame(k) {
                        Ok(image) => {
                            if let Err(e) = stdin.write_all(image.as_raw()) {
                                result = Err(e);
                                break;
                            }
                        }
                        Err(e) => {
                            result = Err(failed(e));
                            break;
                        }
                    }
                }
                drop(stdin);
                let status = child.wait()?;
                let bytes = reader
                    .join()
                    .map_err(|_| io::Error::other("ffmpeg reader panicked"))??;
                let messages = errors.join().unwrap_or_default();
                // ffmpeg's own words first: a pipe it closed by failing is only the symptom.
                if !status.success() {
                    return Err(io::Error::other(format!(
                        "ffmpeg failed ({status}): {}",
                        messages.trim()
                    )));
                }
                result?;
                w.write_all(&bytes)
            })
        }
    }
}

/// [`crate::fsutil::write_atomic`] for a writer that also renders: a rendering error inside the
/// writer is carried out as itself, not as an I/O error.
fn with_errors(
    path: &Path,
    write: impl FnOnce(&mut dyn Write, &mut dyn FnMut(Error) -> io::Error) -> io::Result<()>,
) -> Result<()> {
    let mut first: Option<Error> = None;
    let mut failed = |e: Error| {
        let message = e.to_string();
        first.get_or_insert(e);
        io::Error::other(message)
    };
    let result = crate::fsutil::write_atomic(path, |w| write(w, &mut failed));
    match (result, first) {
        (Err(_), Some(e)) => Err(e),
        (result, _) => result,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_choose_the_form() {
        let p = |s: &str| Output::parse(Path::new(s), "wave");
        assert_eq!(p("a.gif").unwrap(), Output::Gif("a.gif".into()));
        assert_eq!(p("a.GIF").unwrap(), Output::Gif("a.GIF".into()));
        assert_eq!(p("a.webm").unwrap(), Output::Video("a.webm".into(), "webm"));
        let Output::Pngs(s) = p("out/f-%04d.png").unwrap() else {
            panic!()
        };
        assert_eq!(s.name(7), PathBuf::from("out/f-0007.png"));
        let Output::Pngs(s) = p("f%d.png").unwrap() else {
            panic!()
        };
        assert_eq!(s.name(12), PathBuf::from("f12.png"));
        let Output::Pngs(s) = p(".").unwrap() else { panic!() };
        assert_eq!(s.name(3), PathBuf::from("./wave-0003.png"));
        for bad in ["a.png", "a.avi", "a", "f-%04x.png", "f-%04d.gif", "f-%d-%d.png"] {
            let err = p(bad).unwrap_err();
            assert!(matches!(err, Error::Param(_)), "{bad}: {err}");
        }
    }

    #[test]
    fn gif_delays_round_to_hundredths_and_say_so() {
        assert_eq!(gif_delay(25.0), (4, None));
        assert_eq!(gif_delay(50.0), (2, None));
        let (d, note) = gif_delay(30.0);
        assert_eq!(d, 3);
        assert!(note.unwrap().contains("33.33 fps"));
        assert_eq!(gif_delay(1000.0).0, 1, "at least one hundredth");
        assert_eq!(gif_delay(0.001).0, 65535, "at most GIF's largest delay");
    }
}
