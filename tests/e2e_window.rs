//! End-to-end tests in a real window: each test starts its own virtual X server (Xvfb), runs a
//! lab example from `target/<profile>/examples/`, drives it with `xdotool` (keys through XTEST,
//! mouse drags, window resizes), captures the screen with ImageMagick's `import` and checks the
//! pictures with `shaderlab::metrics` and the window title.
//!
//! Run alone with `cargo test --release --test e2e_window`. The examples are built first (one
//! nested `cargo build --examples` per test binary, so they are never stale). Needs `Xvfb`,
//! `xdotool` and `import`: `apt-get install -y xvfb xdotool imagemagick`. Missing tools are a
//! failure, never a skip. Pictures are written to `target/tmp/e2e/<test>/` for people to look at.
//!
//! Every child process (Xvfb, the lab) sits in a guard that kills it on drop, even when a test
//! fails. Tests use separate X servers, so they can run in parallel.
//!
//! A busy machine makes these tests slower, never red: they wait for the program's own signals
//! (`SHADERLAB_TEST_LOG`: the frames it shows, an F11 it has handled, that it has nothing left
//! to draw; its title, its output, its exit), each for up to [`PATIENCE`], which only a hang
//! exhausts; and a bound on how long something may take is widened by how much slower than an
//! idle machine this one is right now ([`assert_within`]).

use std::collections::HashSet;
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdout, Command, ExitStatus, Stdio};
use std::sync::{mpsc, Arc, Mutex};
use std::thread;
use std::time::{Duration, Instant};

use image::RgbImage;
use shaderlab::course;
use shaderlab::debug::{picture, view};
use shaderlab::metrics::{bounding_box, coverage, highlight, luma_stats, mask, mean_color, mse, psnr};

mod common;

use common::example;

const INSTALL: &str = "apt-get install -y xvfb xdotool imagemagick";

/// How long a wait for the program's signal may take before the test calls it a hang: long
/// enough for any load, since the wait ends as soon as the signal comes.
const PATIENCE: Duration = Duration::from_secs(120);

/// phong's offscreen frame time (640x360, 60 frames) on the idle 2-core machine the time bounds
/// below were set on.
const IDLE_FRAME_MS: f64 = 1.2;

/// How many times slower than idle this machine is now (at least 1): phong's offscreen frame
/// time against [`IDLE_FRAME_MS`], measured when asked (as load comes and goes).
fn slowness() -> f64 {
    let out = Command::new(example("phong"))
        .args(["--bench", "60"])
        .env_remove("DISPLAY")
        .output()
        .expect("run phong --bench");
    let text = String::from_utf8_lossy(&out.stdout);
    let ms: f64 = text
        .split("ms_per_frame=")
        .nth(1)
        .and_then(|t| t.split_whitespace().next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("no ms_per_frame in `{text}`"));
    (ms / IDLE_FRAME_MS).max(1.0)
}

/// Asserts that `elapsed` is within `bound`, a bound set on an idle machine; one that is
/// exceeded is measured against the machine's present [`slowness`] before it fails.
fn assert_within(elapsed: Duration, bound: Duration, what: &str) {
    if elapsed <= bound {
        return;
    }
    let factor = slowness();
    assert!(
        elapsed.as_secs_f64() <= bound.as_secs_f64() * factor,
        "{what} took {elapsed:?}: more than {bound:?} even scaled by this machine's present slowness ({factor:.1}x)"
    );
    println!("{what}: {elapsed:?}, within {bound:?} scaled by the machine's slowness ({factor:.1}x)");
}

// ---------------------------------------------------------------------------------------------
// Tools, binaries and directories
// ---------------------------------------------------------------------------------------------

fn on_path(tool: &str) -> bool {
    std::env::var_os("PATH")
        .map(|paths| std::env::split_paths(&paths).any(|dir| dir.join(tool).is_file()))
        .unwrap_or(false)
}

/// Fails (never skips) when a tool is missing.
fn require_tools() {
    let missing: Vec<&str> = ["Xvfb", "xdotool", "import"]
        .into_iter()
        .filter(|t| !on_path(t))
        .collect();
    assert!(
        missing.is_empty(),
        "the end-to-end window tests need {missing:?} on PATH; install them with `{INSTALL}`"
    );
}

/// A fresh directory for one test's files: `target/tmp/e2e/<test>/`.
fn test_dir(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("e2e").join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create the test directory");
    dir
}

/// Reads a pipe into a shared string on a thread (so the child never blocks on a full pipe).
fn collect(pipe: impl Read + Send + 'static) -> Arc<Mutex<String>> {
    let text = Arc::new(Mutex::new(String::new()));
    let sink = text.clone();
    thread::spawn(move || {
        for line in BufReader::new(pipe).lines() {
            let Ok(line) = line else { break };
            let mut s = sink.lock().unwrap();
            s.push_str(&line);
            s.push('\n');
        }
    });
    text
}

/// Polls `f` every 50 ms until it gives `Some` or `timeout` passes.
fn poll<T>(timeout: Duration, mut f: impl FnMut() -> Option<T>) -> Option<T> {
    let end = Instant::now() + timeout;
    loop {
        if let Some(v) = f() {
            return Some(v);
        }
        if Instant::now() >= end {
            return None;
        }
        thread::sleep(Duration::from_millis(50));
    }
}

/// PSNR of two pictures that must have one size: pictures of different sizes are a failure,
/// never a pass.
fn psnr_of(a: &RgbImage, b: &RgbImage) -> f64 {
    psnr(a, b).unwrap_or_else(|| {
        panic!(
            "pictures of different sizes: {:?} and {:?}",
            a.dimensions(),
            b.dimensions()
        )
    })
}

fn sleep_ms(ms: u64) {
    thread::sleep(Duration::from_millis(ms));
}

// ---------------------------------------------------------------------------------------------
// The X server
// ---------------------------------------------------------------------------------------------

/// A private Xvfb on a display number it picks itself (`-displayfd`); killed on drop.
struct Xvfb {
    child: Child,
    display: String,
    dir: PathBuf,
    _stdout: ChildStdout,
}

impl Xvfb {
    fn start(test: &str) -> Xvfb {
        Xvfb::start_sized(test, "1024x768x24")
    }

    /// With a screen of `screen` (`WIDTHxHEIGHTxDEPTH`).
    fn start_sized(test: &str, screen: &str) -> Xvfb {
        require_tools();
        let dir = test_dir(test);
        let mut child = Command::new("Xvfb")
            // -noreset: without it the server resets whenever its last client (say, xdotool) leaves,
            // and a lab connecting during the reset fails with "Failed to open connection".
            .args([
                "-displayfd",
                "1",
                "-screen",
                "0",
                screen,
                "-nolisten",
                "tcp",
                "-noreset",
            ])
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .unwrap_or_else(|e| panic!("cannot start Xvfb ({e}); install it with `{INSTALL}`"));
        let stdout = child.stdout.take().expect("Xvfb stdout");
        let (tx, rx) = mpsc::channel();
        let reader = thread::spawn(move || {
            let mut reader = BufReader::new(stdout);
            let mut line = String::new();
            let _ = reader.read_line(&mut line);
            let _ = tx.send(line);
            reader.into_inner()
        });
        let line = rx.recv_timeout(PATIENCE);
        let number = match line {
            Ok(line) if !line.trim().is_empty() => line.trim().to_string(),
            _ => {
                let _ = child.kill();
                let _ = child.wait();
                panic!("Xvfb did not report a display number within 15 s");
            }
        };
        let stdout = reader.join().expect("Xvfb reader");
        let xvfb = Xvfb {
            child,
            display: format!(":{number}"),
            dir,
            _stdout: stdout,
        };
        // The display answers once xdotool can query it.
        let ready = poll(PATIENCE, || xvfb.xdotool_output(&["getdisplaygeometry"]).ok());
        assert!(ready.is_some(), "Xvfb {} does not answer", xvfb.display);
        xvfb
    }

    fn command(&self, program: &str) -> Command {
        let mut c = Command::new(program);
        c.env("DISPLAY", &self.display).env_remove("WAYLAND_DISPLAY");
        c
    }

    /// Runs xdotool and returns its stdout; an error carries its stderr.
    fn xdotool_output(&self, args: &[&str]) -> Result<String, String> {
        let out = self
            .command("xdotool")
            .args(args)
            .stdin(Stdio::null())
            .output()
            .map_err(|e| format!("cannot run xdotool ({e}); install it with `{INSTALL}`"))?;
        if out.status.success() {
            Ok(String::from_utf8_lossy(&out.stdout).into_owned())
        } else {
            Err(format!(
                "xdotool {:?}: {} {}",
                args.first(),
                out.status,
                String::from_utf8_lossy(&out.stderr)
            ))
        }
    }

    fn xdotool(&self, args: &[&str]) -> String {
        self.xdotool_output(args).unwrap_or_else(|e| panic!("{e}"))
    }

    /// The whole screen.
    fn capture_root(&self) -> RgbImage {
        let out = self
            .command("import")
            .args(["-window", "root", "png:-"])
            .stdin(Stdio::null())
            .output()
            .unwrap_or_else(|e| panic!("cannot run import ({e}); install it with `{INSTALL}`"));
        assert!(
            out.status.success(),
            "import failed: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        image::load_from_memory(&out.stdout)
            .expect("import writes a PNG")
            .to_rgb8()
    }

    /// Windows of labs on this display: every lab's title starts with its original's
    /// (`Lab05-N`, `ref001`…`ref003`, `OpenGL III`), or with `legacy`.
    fn windows(&self) -> HashSet<String> {
        self.xdotool_output(&["search", "--name", "^(Lab05|ref00|OpenGL III|legacy)"])
            .map(|s| s.lines().map(str::to_owned).collect())
            .unwrap_or_default()
    }

    /// Starts an example with a window on this display, in this test's directory, and waits
    /// for its window.
    fn launch(&self, name: &str, args: &[&str], env: &[(&str, &str)]) -> App<'_> {
        let runtime = self.dir.join("xdg");
        let _ = std::fs::create_dir_all(&runtime);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let _ = std::fs::set_permissions(&runtime, std::fs::Permissions::from_mode(0o700));
        }
        let mut command = self.command(example(name).to_str().expect("utf-8 path"));
        command
            .args(args)
            .current_dir(&self.dir)
            .env("XDG_RUNTIME_DIR", &runtime)
            .env("SHADERLAB_TEST_LOG", "1")
            .env_remove("RUST_BACKTRACE")
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped());
        for (k, v) in env {
            command.env(k, v);
        }
        let known = self.windows();
        let started = Instant::now();
        let mut child = command.spawn().unwrap_or_else(|e| panic!("cannot start {name}: {e}"));
        let stdout = collect(child.stdout.take().expect("stdout"));
        let stderr = collect(child.stderr.take().expect("stderr"));
        let mut lab = App {
            x: self,
            name: name.to_string(),
            child,
            window: String::new(),
            stdout,
            stderr,
            started,
        };
        let window = poll(PATIENCE, || {
            if let Ok(Some(status)) = lab.child.try_wait() {
                panic!(
                    "{name} exited ({status}) before opening a window; stderr:\n{}",
                    lab.stderr()
                );
            }
            self.windows().into_iter().find(|w| !known.contains(w))
        });
        lab.window =
            window.unwrap_or_else(|| panic!("{name}: no window named Lab05 within 10 s; stderr:\n{}", lab.stderr()));
        lab
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        // SIGTERM first, so that Xvfb removes its lock file and socket; SIGKILL if it lingers.
        let _ = Command::new("kill")
            .args(["-TERM", &self.child.id().to_string()])
            .status();
        let child = &mut self.child;
        if poll(Duration::from_secs(3), || child.try_wait().ok().flatten()).is_none() {
            let _ = self.child.kill();
        }
        let _ = self.child.wait();
    }
}

// ---------------------------------------------------------------------------------------------
// A running lab
// ---------------------------------------------------------------------------------------------

/// A lab example running in a window on an [`Xvfb`]; killed on drop if still running.
struct App<'x> {
    x: &'x Xvfb,
    name: String,
    child: Child,
    window: String,
    stdout: Arc<Mutex<String>>,
    stderr: Arc<Mutex<String>>,
    started: Instant,
}

impl Drop for App<'_> {
    fn drop(&mut self) {
        if let Ok(None) = self.child.try_wait() {
            let _ = self.child.kill();
        }
        let _ = self.child.wait();
    }
}

impl App<'_> {
    fn pid(&self) -> u32 {
        self.child.id()
    }

    fn stdout(&self) -> String {
        self.stdout.lock().unwrap().clone()
    }

    fn stderr(&self) -> String {
        self.stderr.lock().unwrap().clone()
    }

    fn assert_alive(&mut self) {
        if let Ok(Some(status)) = self.child.try_wait() {
            panic!("{} died ({status}); stderr:\n{}", self.name, self.stderr());
        }
    }

    /// No panic and no wgpu error on stderr so far.
    fn assert_clean(&self) {
        let err = self.stderr();
        for bad in ["panicked", "RUST_BACKTRACE", "wgpu error"] {
            assert!(!err.contains(bad), "{} printed `{bad}`:\n{err}", self.name);
        }
    }

    fn title(&self) -> String {
        self.x.xdotool(&["getwindowname", &self.window]).trim_end().to_string()
    }

    /// Waits until the title satisfies `want` (5 s).
    fn wait_title(&self, what: &str, want: impl Fn(&str) -> bool) -> String {
        let mut last = String::new();
        poll(PATIENCE, || {
            last = self.title();
            want(&last).then(|| last.clone())
        })
        .unwrap_or_else(|| {
            self.save(&self.capture(), "title_never_showed");
            panic!(
                "{}: title never showed {what}; last title: {last} (the window: title_never_showed.png); stderr:\n{}",
                self.name,
                self.stderr()
            )
        })
    }

    fn wait_title_contains(&self, part: &str) -> String {
        self.wait_title(&format!("`{part}`"), |t| t.contains(part))
    }

    /// Presses keys (xdotool key names) in the window, `delay_ms` apart.
    fn keys_with_delay(&self, keys: &[&str], delay_ms: u32) {
        let delay = delay_ms.to_string();
        let mut args = vec!["windowfocus", "--sync", &self.window, "key", "--delay", &delay];
        args.extend_from_slice(keys);
        self.x.xdotool(&args);
    }

    fn keys(&self, keys: &[&str]) {
        self.keys_with_delay(keys, 5);
    }

    /// Presses a key `n` times.
    fn key_n(&self, key: &str, n: usize) {
        self.keys(&vec![key; n]);
    }

    /// A left-button drag through `points` (window coordinates).
    fn drag(&self, points: &[(i32, i32)]) {
        let coords: Vec<String> = points
            .iter()
            .flat_map(|(x, y)| [x.to_string(), y.to_string()])
            .collect();
        let mut args = vec!["mousemove", &coords[0], &coords[1], "mousedown", "1"];
        for pair in coords.chunks(2).skip(1) {
            args.extend(["mousemove", &pair[0], &pair[1]]);
        }
        args.extend(["mouseup", "1"]);
        self.x.xdotool(&args);
    }

    /// (x, y, width, height) of the window on the screen.
    fn geometry(&self) -> (u32, u32, u32, u32) {
        let out = self.x.xdotool(&["getwindowgeometry", "--shell", &self.window]);
        let get = |key: &str| -> u32 {
            out.lines()
                .find_map(|l| l.strip_prefix(key).and_then(|v| v.strip_prefix('=')))
                .and_then(|v| v.trim().parse::<i64>().ok())
                .map(|v| v.max(0) as u32)
                .unwrap_or_else(|| panic!("no {key} in xdotool getwindowgeometry: {out}"))
        };
        (get("X"), get("Y"), get("WIDTH"), get("HEIGHT"))
    }

    fn resize(&self, width: u32, height: u32) -> Result<String, String> {
        self.x
            .xdotool_output(&["windowsize", &self.window, &width.to_string(), &height.to_string()])
    }

    /// What the window shows now (the screen cropped to the window).
    fn capture(&self) -> RgbImage {
        let (x, y, w, h) = self.geometry();
        let screen = self.x.capture_root();
        assert!(
            x + w <= screen.width() && y + h <= screen.height(),
            "window {w}x{h}+{x}+{y} is off the screen"
        );
        image::imageops::crop_imm(&screen, x, y, w, h).to_image()
    }

    /// How many times the program has said `shaderlab-test: WHAT` (`SHADERLAB_TEST_LOG`).
    /// Presses F12 and waits for the window's `n`th `screenshot: PATH` line; the path.
    fn f12(&self, n: usize) -> PathBuf {
        self.keys(&["F12"]);
        let line = poll(PATIENCE, || {
            let out = self.stdout();
            let lines: Vec<String> = out
                .lines()
                .filter(|l| l.starts_with("screenshot: "))
                .map(str::to_owned)
                .collect();
            (lines.len() >= n).then(|| lines[n - 1].clone())
        })
        .unwrap_or_else(|| {
            panic!(
                "F12 printed no {n}th `screenshot:` line; stdout:\n{}\nstderr:\n{}",
                self.stdout(),
                self.stderr()
            )
        });
        PathBuf::from(line.trim_start_matches("screenshot: ").trim())
    }

    fn said(&self, what: &str) -> usize {
        let needle = format!("shaderlab-test: {what}");
        self.stderr().lines().filter(|l| l.starts_with(&needle)).count()
    }

    /// Waits until the program has handled every event sent before: it answers an F11, which
    /// reaches it after them.
    fn sync(&self) {
        let before = self.said("sync");
        self.keys(&["F11"]);
        poll(PATIENCE, || (self.said("sync") > before).then_some(()))
            .unwrap_or_else(|| panic!("{}: F11 never handled; stderr:\n{}", self.name, self.stderr()));
    }

    /// Waits until the program has handled every event sent before and drawn what they asked
    /// for, and has nothing left to draw (for the labs that do not animate).
    fn idle(&self) {
        self.sync();
        poll(PATIENCE, || {
            let err = self.stderr();
            let after_sync = err.rsplit_once("shaderlab-test: sync").map_or("", |(_, rest)| rest);
            after_sync.contains("shaderlab-test: idle").then_some(())
        })
        .unwrap_or_else(|| panic!("{}: never idle; stderr:\n{}", self.name, self.stderr()));
    }

    /// What the window shows once it has drawn everything asked of it ([`App::idle`]), for the
    /// labs that do not animate. (The X server shows a frame a moment after it is sent: two
    /// captures in a row must agree.)
    fn settled(&self) -> RgbImage {
        self.idle();
        let mut previous = self.capture();
        poll(PATIENCE, || {
            let current = self.capture();
            let same = current == previous;
            previous = current;
            same.then(|| previous.clone())
        })
        .unwrap_or_else(|| panic!("{}: the picture never settled", self.name))
    }

    /// Waits for the first frame: something other than the background (10 s).
    fn first_frame(&self) -> (RgbImage, Duration) {
        let mut last = None;
        let frame = poll(PATIENCE, || {
            let image = self.capture();
            let ok = coverage(&image, background(&image)) > 0.01;
            last = Some(image.clone());
            ok.then_some(image)
        });
        match frame {
            Some(image) => (image, self.started.elapsed()),
            None => {
                if let Some(image) = last {
                    let _ = image.save(self.x.dir.join("no_first_frame.png"));
                }
                panic!("{}: no picture within 10 s; stderr:\n{}", self.name, self.stderr())
            }
        }
    }

    fn save(&self, image: &RgbImage, name: &str) {
        let _ = image.save(self.x.dir.join(format!("{name}.png")));
    }

    /// Waits for the process to end (`timeout`).
    fn wait_exit(&mut self, timeout: Duration) -> ExitStatus {
        let child = &mut self.child;
        let status = poll(timeout, || child.try_wait().ok().flatten());
        status.unwrap_or_else(|| panic!("{} still runs {timeout:?} later; stderr:\n{}", self.name, self.stderr()))
    }

    /// Resident memory in kB, from /proc.
    fn rss_kb(&self) -> u64 {
        let status = std::fs::read_to_string(format!("/proc/{}/status", self.pid())).expect("/proc/PID/status");
        status
            .lines()
            .find_map(|l| l.strip_prefix("VmRSS:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
            .expect("VmRSS")
    }

    /// CPU time used so far (user + system) in clock ticks, from /proc.
    fn cpu_ticks(&self) -> u64 {
        let stat = std::fs::read_to_string(format!("/proc/{}/stat", self.pid())).expect("/proc/PID/stat");
        let fields: Vec<&str> = stat
            .rsplit_once(')')
            .map(|(_, rest)| rest)
            .unwrap_or("")
            .split_whitespace()
            .collect();
        // After "pid (comm)": state is field 0, utime field 11, stime field 12.
        fields[11].parse::<u64>().unwrap_or(0) + fields[12].parse::<u64>().unwrap_or(0)
    }

    /// Share of one core used over `ms`.
    fn cpu_share(&self, ms: u64) -> f64 {
        let ticks_per_s = 100.0; // USER_HZ on Linux
        let a = self.cpu_ticks();
        sleep_ms(ms);
        let b = self.cpu_ticks();
        (b - a) as f64 / ticks_per_s / (ms as f64 / 1000.0)
    }

    /// Esc ends the lab with status 0, quickly and cleanly.
    fn escape(&mut self) {
        self.keys(&["Escape"]);
        let pressed = Instant::now();
        let status = self.wait_exit(PATIENCE);
        assert_within(
            pressed.elapsed(),
            Duration::from_secs(5),
            &format!("{}: quitting on Esc", self.name),
        );
        assert!(
            status.success(),
            "{} exited with {status} on Esc; stderr:\n{}",
            self.name,
            self.stderr()
        );
        self.assert_clean();
    }
}

// ---------------------------------------------------------------------------------------------
// Picture statistics
// ---------------------------------------------------------------------------------------------

/// The clear colour: the top-left pixel, which no object reaches.
fn background(image: &RgbImage) -> [u8; 3] {
    image.get_pixel(0, 0).0
}

fn object_mask(image: &RgbImage) -> Vec<bool> {
    mask(image, background(image), 2)
}

/// (width, height, fill) of the object: its bounding box and the share of the box it covers.
fn shape(image: &RgbImage) -> (f64, f64, f64) {
    let bg = background(image);
    let (x0, y0, x1, y1) = bounding_box(image, bg).expect("an object on the screen");
    let (w, h) = ((x1 - x0 + 1) as f64, (y1 - y0 + 1) as f64);
    let covered = coverage(image, bg) * (image.width() * image.height()) as f64;
    (w, h, covered / (w * h))
}

/// Mean colour of the object's pixels.
fn object_mean(image: &RgbImage) -> [f64; 3] {
    mean_color(image, (0, 0, image.width(), image.height()), Some(background(image)))
}

fn luma([r, g, b]: [f64; 3]) -> f64 {
    0.299 * r + 0.587 * g + 0.114 * b
}

/// Pixels at least as bright as `level` (0..255 luma): the size of the highlight.
fn bright_pixels(image: &RgbImage, level: f64) -> usize {
    image
        .pixels()
        .filter(|p| luma([p[0] as f64, p[1] as f64, p[2] as f64]) >= level)
        .count()
}

/// Share of horizontally adjacent object pixels with exactly the same colour: near 0 for smooth
/// noise, high when the noise turns blocky or flat.
fn flat_share(image: &RgbImage) -> f64 {
    let m = object_mask(image);
    let w = image.width() as usize;
    let (mut same, mut pairs) = (0usize, 0usize);
    for (i, p) in image.pixels().enumerate() {
        if i % w + 1 < w && m[i] && m[i + 1] {
            pairs += 1;
            let (x, y) = (((i + 1) % w) as u32, ((i + 1) / w) as u32);
            same += (image.get_pixel(x, y) == p) as usize;
        }
    }
    same as f64 / pairs.max(1) as f64
}

// ---------------------------------------------------------------------------------------------
// The Phong title
// ---------------------------------------------------------------------------------------------

/// The values the Phong title shows.
#[derive(Debug, Clone, Copy, PartialEq)]
struct PhongTitle {
    light: [f64; 3],
    ka: f64,
    kd: f64,
    ks: f64,
    shininess: f64,
    diffuse: [f64; 3],
}

fn parse_phong_title(title: &str) -> PhongTitle {
    let bad = || -> ! { panic!("cannot read the Phong values in the title `{title}`") };
    let triple = |key: &str| -> [f64; 3] {
        let start = title.find(key).unwrap_or_else(|| bad()) + key.len();
        let rest = &title[start..];
        let inner = rest.trim_start().strip_prefix('(').unwrap_or_else(|| bad());
        let inner = &inner[..inner.find(')').unwrap_or_else(|| bad())];
        let v: Vec<f64> = inner
            .split(',')
            .map(|s| s.trim().parse::<f64>().unwrap_or(f64::NAN))
            .collect();
        if v.len() != 3 {
            bad();
        }
        [v[0], v[1], v[2]]
    };
    let number = |key: &str| -> f64 {
        let at = title.find(&format!(" {key} ")).unwrap_or_else(|| bad()) + key.len() + 2;
        title[at..]
            .split_whitespace()
            .next()
            .and_then(|s| s.parse::<f64>().ok())
            .unwrap_or(f64::NAN)
    };
    PhongTitle {
        light: triple("light"),
        ka: number("Ka"),
        kd: number("Kd"),
        ks: number("Ks"),
        shininess: number("shininess"),
        diffuse: triple("diffuse"),
    }
}

/// The keysym xdotool needs for a character.
fn keysym(c: char) -> String {
    match c {
        '[' => "bracketleft".into(),
        ']' => "bracketright".into(),
        '{' => "braceleft".into(),
        '}' => "braceright".into(),
        '<' => "less".into(),
        '>' => "greater".into(),
        c => c.to_string(),
    }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-6
}

// ---------------------------------------------------------------------------------------------
// Every lab starts, draws and quits
// ---------------------------------------------------------------------------------------------

fn starts_draws_and_quits(name: &str, title: &str) {
    let x = Xvfb::start(&format!("start_{name}"));
    let mut lab = x.launch(name, &[], &[]);
    let (frame, after) = lab.first_frame();
    lab.save(&frame, "first_frame");
    println!("{name}: first frame after {after:.2?}");
    assert_within(after, Duration::from_secs(8), &format!("{name}: the first frame"));
    assert_eq!(
        frame.dimensions(),
        (640, 360),
        "the window is 640x360 as in the original"
    );
    assert!(lab.title().starts_with(title), "{name}: title `{}`", lab.title());
    assert!(
        lab.title().contains("| teapot |"),
        "{name} starts on the teapot: `{}`",
        lab.title()
    );
    lab.escape();
}

#[test]
fn position_rgb_starts_draws_and_quits_on_esc() {
    starts_draws_and_quits("position_rgb", "Lab05-1");
}

#[test]
fn normal_rgb_starts_draws_and_quits_on_esc() {
    starts_draws_and_quits("normal_rgb", "Lab05-2");
}

#[test]
fn phong_starts_draws_and_quits_on_esc() {
    starts_draws_and_quits("phong", "Lab05-3");
}

#[test]
fn noise_starts_draws_and_quits_on_esc() {
    starts_draws_and_quits("noise", "Lab05-4");
}

#[test]
fn displacement_starts_draws_and_quits_on_esc() {
    starts_draws_and_quits("displacement", "Lab05-5");
}

// ---------------------------------------------------------------------------------------------
// Objects and the mouse
// ---------------------------------------------------------------------------------------------

#[test]
fn keys_1_to_4_change_the_object_and_a_drag_rotates_it() {
    let x = Xvfb::start("objects_and_drag");
    let mut lab = x.launch("position_rgb", &[], &[]);
    lab.first_frame();
    let mut shapes = Vec::new();
    for (key, object) in [("1", "cube"), ("2", "sphere"), ("3", "torus"), ("4", "teapot")] {
        lab.keys(&[key]);
        lab.wait_title_contains(&format!("| {object} |"));
        let image = lab.settled();
        lab.save(&image, object);
        let (w, h, fill) = shape(&image);
        println!("{object}: box {w}x{h}, fill {fill:.3}");
        shapes.push((object, image, w, h, fill));
    }
    let get = |name: &str| shapes.iter().find(|s| s.0 == name).expect("shape");
    // Cube, face on: a filled square.
    let (_, _, w, h, fill) = get("cube");
    assert!(
        (w / h - 1.0).abs() < 0.08 && *fill > 0.95,
        "cube: box {w}x{h}, fill {fill:.3}: not a filled square"
    );
    // Sphere: a disc fills pi/4 of its square box.
    let (_, _, w, h, fill) = get("sphere");
    assert!((w / h - 1.0).abs() < 0.08, "sphere: box {w}x{h} is not square");
    assert!(
        (fill - std::f64::consts::FRAC_PI_4).abs() < 0.05,
        "sphere: fill {fill:.3} is not a disc's"
    );
    // Torus, seen along its axis: a ring with a hole in the middle.
    let (_, image, w, h, _) = get("torus");
    assert!((w / h - 1.0).abs() < 0.08, "torus: box {w}x{h} is not square");
    let bg = background(image);
    let (x0, y0, x1, y1) = bounding_box(image, bg).expect("torus");
    let (cx, cy) = ((x0 + x1) / 2, (y0 + y1) / 2);
    assert_eq!(image.get_pixel(cx, cy).0, bg, "torus: no hole at the centre");
    let ring = (x1 - cx) * 2 / 3; // radius 1 of 1.5: the middle of the tube
    assert_ne!(image.get_pixel(cx + ring, cy).0, bg, "torus: no tube right of the hole");
    // Teapot: wider than tall.
    let (_, _, w, h, _) = get("teapot");
    assert!(w / h > 1.3, "teapot: box {w}x{h} is not wider than tall");
    // Every object looks different.
    for (i, a) in shapes.iter().enumerate() {
        for b in &shapes[i + 1..] {
            assert!(mse(&a.1, &b.1).unwrap() > 10.0, "{} and {} look the same", a.0, b.0);
        }
    }

    // A drag to the right and down turns the teapot (yAngle +2 and xAngle +1 per motion event).
    let before = lab.settled();
    let points: Vec<(i32, i32)> = (0..=30).map(|i| (200 + 5 * i, 150 + 2 * i)).collect();
    lab.drag(&points);
    let after = lab.settled();
    lab.save(&after, "teapot_dragged");
    let db = psnr(&before, &after).unwrap();
    assert!(
        db < 25.0,
        "a drag did not rotate the teapot (PSNR {db:.1} dB against before)"
    );
    let (w2, h2, _) = shape(&after);
    assert!(
        (w2 - w).abs() > 5.0 || (h2 - h).abs() > 5.0,
        "the teapot's box did not change: {w}x{h} -> {w2}x{h2}"
    );
    // Moving without a button does nothing.
    let still = lab.settled();
    lab.x.xdotool(&["mousemove", "100", "100", "mousemove", "400", "300"]);
    assert_eq!(
        lab.settled(),
        still,
        "moving the mouse without a button rotated the object"
    );
    lab.escape();
}

// ---------------------------------------------------------------------------------------------
// Phong keys
// ---------------------------------------------------------------------------------------------

#[test]
fn phong_keys_move_the_light_and_change_the_material() {
    let x = Xvfb::start("phong_keys");
    let mut lab = x.launch("phong", &["--object", "sphere"], &[]);
    lab.first_frame();
    let start = lab.settled();
    lab.save(&start, "start");
    let t0 = parse_phong_title(&lab.title());
    assert_eq!(t0.light, [0.0, 1.0, 1.0], "default light");
    assert!(
        close(t0.ka, 0.1) && close(t0.kd, 1.0) && close(t0.ks, 1.0) && t0.shininess == 32.0,
        "defaults: {t0:?}"
    );

    // X: the light moves right, and so does the highlight.
    let (hx0, _) = highlight(&start, 8.0);
    lab.key_n("X", 20);
    let t = parse_phong_title(&lab.wait_title_contains("light (2.0,1.0,1.0)"));
    assert_eq!(t.light, [2.0, 1.0, 1.0]);
    let moved = lab.settled();
    lab.save(&moved, "light_right");
    let (hx1, _) = highlight(&moved, 8.0);
    println!("highlight x: {hx0:.1} -> {hx1:.1}");
    assert!(
        hx1 > hx0 + 10.0,
        "X moved the light right but the highlight went from x={hx0:.1} to x={hx1:.1}"
    );
    lab.key_n("x", 20);
    // (20 steps of 0.1 up and down in f32 may leave -0.0000001: compare numbers, not text.)
    lab.wait_title("light back at x=0", |t| parse_phong_title(t).light[0].abs() < 0.05);
    let db = psnr(&lab.settled(), &start).unwrap();
    assert!(db >= 40.0, "x undid X, but the picture differs: {db:.1} dB");

    // [ dims (Kd down), ] brightens again.
    lab.key_n("bracketleft", 6);
    let t = parse_phong_title(&lab.wait_title_contains("Kd 0.70"));
    assert!(close(t.kd, 0.7));
    let dim = luma(object_mean(&lab.settled()));
    lab.key_n("bracketright", 4);
    lab.wait_title_contains("Kd 0.90");
    let brighter = luma(object_mean(&lab.settled()));
    println!("object luma: Kd 0.70 {dim:.1}, Kd 0.90 {brighter:.1}");
    assert!(
        brighter > dim + 3.0,
        "] did not brighten: luma {dim:.1} -> {brighter:.1}"
    );
    lab.key_n("bracketright", 2);
    lab.wait_title_contains("Kd 1.00");

    // r lowers the red of the diffuse colour, and of the picture.
    let red0 = object_mean(&lab.settled())[0];
    lab.key_n("r", 30);
    let t = parse_phong_title(&lab.wait_title_contains("diffuse (0.70,0.50,0.00)"));
    assert_eq!(t.diffuse, [0.7, 0.5, 0.0]);
    let red1 = object_mean(&lab.settled())[0];
    println!("object red: {red0:.1} -> {red1:.1}");
    assert!(red1 < red0 - 10.0, "r did not lower the red: {red0:.1} -> {red1:.1}");
    lab.key_n("R", 30);
    lab.wait_title_contains("diffuse (1.00,0.50,0.00)");

    // h widens the highlight (lower shininess), H narrows it.
    let spot32 = bright_pixels(&lab.settled(), 235.0);
    lab.key_n("h", 20);
    lab.wait_title_contains("shininess 12");
    let spot12 = bright_pixels(&lab.settled(), 235.0);
    lab.key_n("H", 68);
    lab.wait_title_contains("shininess 80");
    let spot80 = bright_pixels(&lab.settled(), 235.0);
    println!("highlight pixels: shininess 12 {spot12}, 32 {spot32}, 80 {spot80}");
    assert!(
        spot12 > spot32 && spot32 > spot80,
        "highlight size does not follow shininess: 12 {spot12}, 32 {spot32}, 80 {spot80}"
    );
    lab.key_n("h", 300);
    lab.wait_title_contains("shininess 6 ");
    lab.key_n("H", 300);
    lab.wait_title_contains("shininess 200 ");
    lab.key_n("h", 168);
    lab.wait_title_contains("shininess 32 ");

    // > raises the ambient term (seen in blue, which the orange diffuse colour has none of), < lowers it.
    let blue = |lab: &App| object_mean(&lab.settled())[2];
    let blue_ka010 = blue(&lab);
    lab.key_n("greater", 6);
    let t = parse_phong_title(&lab.wait_title_contains("Ka 0.40"));
    assert!(close(t.ka, 0.4));
    let blue_ka040 = blue(&lab);
    lab.key_n("less", 12);
    lab.wait_title_contains("Ka 0.00");
    let blue_ka000 = blue(&lab);
    println!("object blue: Ka 0 {blue_ka000:.2}, 0.1 {blue_ka010:.2}, 0.4 {blue_ka040:.2}");
    assert!(
        blue_ka040 > blue_ka010 + 3.0 && blue_ka010 > blue_ka000 + 0.5,
        "ambient does not follow Ka"
    );

    // { and } on Ks: the specular highlight disappears at Ks 0.
    lab.key_n("braceleft", 25);
    lab.wait_title_contains("Ks 0.00");
    let no_spec = lab.settled();
    assert!(
        bright_pixels(&no_spec, 235.0) == 0,
        "Ks 0 still shows a white highlight"
    );
    lab.key_n("braceright", 25);
    lab.wait_title_contains("Ks 1.00");
    lab.assert_clean();
    lab.escape();
}

// ---------------------------------------------------------------------------------------------
// Animation
// ---------------------------------------------------------------------------------------------

#[test]
fn noise_animates_and_displacement_keys_change_the_silhouette() {
    let x = Xvfb::start("noise_and_displacement");
    {
        let mut noise = x.launch("noise", &[], &[]);
        let (a, _) = noise.first_frame();
        sleep_ms(500);
        let b = noise.capture();
        noise.save(&a, "noise_a");
        noise.save(&b, "noise_b");
        let db = psnr(&a, &b).unwrap();
        assert!(
            db < 30.0,
            "noise does not animate: two captures 0.5 s apart are {db:.1} dB apart"
        );
        noise.escape();
    }

    let mut lab = x.launch("displacement", &[], &[]);
    let (a, _) = lab.first_frame();
    sleep_ms(500);
    let b = lab.capture();
    assert!(psnr(&a, &b).unwrap() < 30.0, "displacement does not animate");
    assert!(
        lab.title().contains("displacement 0.50"),
        "default displacement: {}",
        lab.title()
    );
    // The object's extent over a few frames (noise < 0 is drawn black, like the background).
    let extent = |lab: &App, tag: &str| -> f64 {
        let mut area: f64 = 0.0;
        for i in 0..4 {
            let image = lab.capture();
            lab.save(&image, &format!("{tag}_{i}"));
            let (w, h, _) = shape(&image);
            area = area.max(w * h);
            sleep_ms(150);
        }
        area
    };
    lab.key_n("bracketleft", 60);
    lab.wait_title_contains("displacement 0.00");
    let flat = extent(&lab, "displacement_0");
    lab.key_n("bracketright", 60);
    lab.wait_title_contains("displacement 0.60");
    lab.key_n("bracketright", 60);
    lab.wait_title_contains("displacement 1.00");
    let full = extent(&lab, "displacement_1");
    println!("object box area: displacement 0 {flat:.0}, 1 {full:.0}");
    assert!(
        full > flat * 1.25,
        "displacement 1 does not push the silhouette out: {flat:.0} -> {full:.0}"
    );
    lab.escape();
}

// ---------------------------------------------------------------------------------------------
// F12
// ---------------------------------------------------------------------------------------------

#[test]
fn f12_writes_what_the_window_shows() {
    let x = Xvfb::start("f12");
    let mut lab = x.launch("phong", &[], &[]);
    lab.first_frame();
    let mut seen = 0;
    let mut check = |lab: &App, tag: &str| {
        let shown = lab.settled();
        seen += 1;
        let path = lab.f12(seen);
        assert!(
            path.is_absolute(),
            "the screenshot path is not absolute: {}",
            path.display()
        );
        assert!(
            path.starts_with(&lab.x.dir),
            "F12 did not write into the current directory: {}",
            path.display()
        );
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        assert!(
            name.starts_with("phong-") && name.ends_with(&format!("-{seen}.png")),
            "screenshot name {name}"
        );
        let written = image::open(&path).expect("F12 writes a PNG").to_rgb8();
        lab.save(&shown, &format!("{tag}_window"));
        assert_eq!(
            written.dimensions(),
            shown.dimensions(),
            "{tag}: F12 image size differs from the window's"
        );
        let db = psnr(&written, &shown).unwrap();
        println!("{tag}: F12 against the window: {db:.1} dB");
        assert!(db >= 40.0, "{tag}: F12 image differs from the window: {db:.1} dB");
    };
    check(&lab, "default");
    lab.keys(&["2", "X", "X", "X", "Y", "r", "r", "h"]);
    lab.wait_title_contains("| sphere |");
    lab.wait_title_contains("shininess 31");
    check(&lab, "changed");
    lab.resize(400, 300).expect("resize");
    poll(PATIENCE, || (lab.geometry().2 == 400).then_some(())).expect("window resized");
    check(&lab, "resized");
    lab.assert_clean();
    lab.escape();
}

// ---------------------------------------------------------------------------------------------
// Resizing, hiding, covering
// ---------------------------------------------------------------------------------------------

#[test]
fn tiny_zero_hidden_and_covered_windows_keep_rendering_correctly() {
    let x = Xvfb::start("resize");
    let mut lab = x.launch("phong", &[], &[]);
    lab.first_frame();
    let reference = lab.settled();
    lab.save(&reference, "reference");
    let sizes = |lab: &App, w: u32, h: u32| {
        poll(PATIENCE, || {
            let g = lab.geometry();
            (g.2 == w && g.3 == h).then_some(())
        })
        .unwrap_or_else(|| panic!("the window never became {w}x{h}: {:?}", lab.geometry()))
    };

    // Tiny.
    lab.resize(50, 1).expect("resize to 50x1");
    sizes(&lab, 50, 1);
    lab.idle();
    lab.assert_alive();
    let strip = lab.capture();
    assert_eq!(strip.dimensions(), (50, 1));
    // Zero height: X has no zero-sized windows (BadValue), and xdotool keeps the old height
    // for a 0. Record what happens; the lab must go on either way.
    let _ = lab.resize(200, 0);
    lab.idle();
    let (_, _, w, h) = lab.geometry();
    println!("windowsize 200 0 gave {w}x{h}");
    assert!(h >= 1, "X made a zero-height window");
    lab.assert_alive();
    let _ = lab.resize(1, 0);
    lab.idle();
    lab.assert_alive();
    lab.resize(640, 360).expect("resize back");
    sizes(&lab, 640, 360);
    let back = lab.settled();
    lab.save(&back, "back_to_640x360");
    let db = psnr(&back, &reference).unwrap();
    assert!(
        db >= 40.0,
        "after resizing back the picture differs from the first one: {db:.1} dB"
    );

    // Hidden (unmapped, as a window manager does on minimise): no busy drawing, and the right
    // picture when it comes back.
    let visible = lab.cpu_share(1500);
    lab.x.xdotool(&["windowunmap", "--sync", &lab.window]);
    sleep_ms(300);
    let hidden = lab.cpu_share(1500);
    lab.x.xdotool(&["windowmap", "--sync", &lab.window]);
    let shown = lab.settled();
    println!("CPU: visible {visible:.2} core, unmapped {hidden:.2} core");
    assert!(hidden < 0.3, "an unmapped window still uses {hidden:.2} of a core");
    let db = psnr(&shown, &reference).unwrap();
    assert!(
        db >= 40.0,
        "after unmapping and mapping again the picture differs: {db:.1} dB"
    );

    // Covered by another window: drawing pauses (WindowEvent::Occluded) and resumes after.
    {
        let cover = lab.x.launch("position_rgb", &[], &[]);
        cover.first_frame();
        sleep_ms(300);
        let covered = lab.cpu_share(1500);
        println!("CPU: fully covered {covered:.2} core");
        assert!(
            covered < 0.3,
            "a fully covered window still uses {covered:.2} of a core"
        );
    }
    lab.assert_alive();
    let uncovered = lab.settled();
    let db = psnr(&uncovered, &reference).unwrap();
    assert!(db >= 40.0, "after being uncovered the picture differs: {db:.1} dB");
    lab.keys(&["X"]);
    lab.wait_title_contains("light (0.1,");
    lab.assert_clean();
    lab.escape();
}

// ---------------------------------------------------------------------------------------------
// Reliability
// ---------------------------------------------------------------------------------------------

/// "An hour of animation in a minute": the noise clock at 60x for ~24 s (24 minutes of lab
/// time). Memory must stay flat and the noise must keep its look.
#[test]
fn noise_runs_at_60x_clock_with_flat_memory_and_steady_noise() {
    let x = Xvfb::start("long_run");
    let mut lab = x.launch("noise", &["--object", "sphere"], &[("SHADERLAB_CLOCK_SCALE", "60")]);
    lab.first_frame();
    sleep_ms(2500);
    let early = lab.capture();
    lab.save(&early, "early");
    let (_, var_early) = luma_stats(&early, &object_mask(&early));
    let flat_early = flat_share(&early);
    let mut rss = Vec::new();
    let run = Instant::now();
    while run.elapsed() < Duration::from_secs(21) {
        lab.assert_alive();
        rss.push(lab.rss_kb());
        sleep_ms(3000);
    }
    lab.assert_alive();
    let late = lab.capture();
    lab.save(&late, "late");
    let (_, var_late) = luma_stats(&late, &object_mask(&late));
    let flat_late = flat_share(&late);
    let cov = (coverage(&early, [0; 3]), coverage(&late, [0; 3]));
    println!("RSS samples (kB): {rss:?}");
    println!("luma variance {var_early:.4} -> {var_late:.4}; equal neighbours {flat_early:.3} -> {flat_late:.3}; coverage {cov:?}");
    let growth = rss.iter().max().unwrap() - rss[0];
    assert!(growth < 20 * 1024, "memory grew by {} kB over the run: {rss:?}", growth);
    assert!(
        var_late > var_early * 0.4 && var_late < var_early * 2.5,
        "the noise changed character: variance {var_early:.4} -> {var_late:.4}"
    );
    assert!(
        flat_late < flat_early + 0.15,
        "the noise turned blocky: equal neighbours {flat_early:.3} -> {flat_late:.3}"
    );
    assert!((cov.0 - cov.1).abs() < 0.05, "the object's coverage changed: {cov:?}");
    // The clock really runs at 60x: a key refreshes the title, which shows the lab's time at
    // the window's last frame. That frame's tick is bracketed by moments the test sees: after
    // `after` (the test waits for a frame the window drew after an F11 sent then, before it
    // sends the key) and before `seen` (when the title showed it). Load widens the bracket,
    // never shifts it. (The time in the title wraps by the noise's period: whole periods are
    // added to the advance.)
    let lab_time = |lab: &App, key: &str, shade: &str| -> (Instant, Instant, f64) {
        let after = Instant::now();
        lab.sync();
        poll(PATIENCE, || {
            let err = lab.stderr();
            let (_, since_sync) = err.rsplit_once("shaderlab-test: sync")?;
            since_sync.contains("shaderlab-test: frame ").then_some(())
        })
        .unwrap_or_else(|| panic!("no frame after F11; stderr:\n{}", lab.stderr()));
        lab.keys(&[key]);
        let title = lab.wait_title_contains(&format!("shade ({shade},"));
        let seen = Instant::now();
        let time: f64 = title
            .rsplit_once("time ")
            .and_then(|(_, t)| t.split_whitespace().next())
            .and_then(|t| t.parse().ok())
            .unwrap_or_else(|| panic!("no time in the title `{title}`"));
        assert!(time.is_finite(), "time is not finite: {title}");
        (after, seen, time)
    };
    let (after0, seen0, time0) = lab_time(&lab, "r", "0.95");
    sleep_ms(500);
    let (after1, seen1, time1) = lab_time(&lab, "R", "1.00");
    let (shortest, longest) = ((after1 - seen0).as_secs_f64(), (seen1 - after0).as_secs_f64());
    let period = shaderlab::course::seed000::NOISE_PERIOD;
    let advanced = (time1 - time0).rem_euclid(period);
    // 60x, to 1% and the title's 0.1 s either side.
    let (low, high) = (0.99 * 60.0 * shortest - 0.1, 1.01 * 60.0 * longest + 0.1);
    let fits = (0..)
        .map(|wraps| advanced + wraps as f64 * period)
        .take_while(|t| *t <= high)
        .any(|t| t >= low);
    println!(
        "lab time {time0:.1} -> {time1:.1} (+{advanced:.1} s and whole periods) while the window's \
         clock ran {shortest:.2} to {longest:.2} s: 60x wants {low:.1} to {high:.1}"
    );
    assert!(
        fits,
        "SHADERLAB_CLOCK_SCALE=60: the lab's time advanced {advanced:.1} s (and whole periods of \
         {period} s) in {shortest:.2} to {longest:.2} s of the window's clock, not {low:.1} to {high:.1}"
    );
    lab.assert_clean();
    lab.escape();
}

/// A deterministic mix of the Phong keys.
fn phong_storm(n: usize) -> Vec<char> {
    let keys: Vec<char> = "XxYyZz[]{}<>HhRrGgBbWASDwasd".chars().collect();
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    (0..n)
        .map(|_| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            keys[(state >> 33) as usize % keys.len()]
        })
        .collect()
}

#[test]
fn input_storm_keeps_values_in_range_and_the_window_responsive() {
    let x = Xvfb::start("storm");
    let mut lab = x.launch("phong", &[], &[]);
    lab.first_frame();
    // 1400 random keys, then runs that hit the bounds.
    let mut storm = phong_storm(1400);
    storm.extend(std::iter::repeat_n('H', 250));
    storm.extend(std::iter::repeat_n('>', 30));
    storm.extend(std::iter::repeat_n('X', 170));
    storm.extend(std::iter::repeat_n('{', 30));
    storm.extend(std::iter::repeat_n('r', 120));
    assert_eq!(storm.len(), 2000);
    // What the lab must end with: the same keys through the effect's own handler.
    let mut model = common::lab(course::PHONG);
    for &c in &storm {
        model.key(c);
    }
    let expected_title = model.lab.title();
    let expected_summary = expected_title
        .split(" | ")
        .nth(2)
        .expect("a summary in the title")
        .to_owned();

    let names: Vec<String> = storm.iter().map(|&c| keysym(c)).collect();
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    let sent = Instant::now();
    lab.keys_with_delay(&names, 0);
    println!("2000 keys sent in {:.2?}", sent.elapsed());
    // A long drag: 1500 motion events in circles.
    let points: Vec<(i32, i32)> = (0..1500)
        .map(|i| {
            let a = i as f64 * 0.05;
            ((320.0 + 150.0 * a.cos()) as i32, (180.0 + 100.0 * a.sin()) as i32)
        })
        .collect();
    lab.drag(&points);
    println!("keys and drag sent in {:.2?}", sent.elapsed());

    let mut last = String::new();
    let done = poll(PATIENCE, || {
        last = lab.title();
        last.contains(&format!("| {expected_summary}")).then_some(())
    });
    println!("title after the storm: {last}");
    let t = parse_phong_title(&last);
    let in01 = |v: f64| (0.0..=1.0).contains(&v);
    assert!(
        !last.contains("NaN") && !last.contains("inf"),
        "a value is not finite: {last}"
    );
    assert!(
        in01(t.ka) && in01(t.kd) && in01(t.ks),
        "a coefficient is out of [0,1]: {t:?}"
    );
    assert!(
        t.diffuse.iter().all(|&v| in01(v)),
        "the diffuse colour is out of [0,1]: {t:?}"
    );
    assert!((6.0..=200.0).contains(&t.shininess), "shininess out of [6,200]: {t:?}");
    assert!(
        t.light.iter().all(|&v| (-50.0..=50.0).contains(&v)),
        "the light left [-50,50]: {t:?}"
    );
    assert!(
        done.is_some(),
        "the lab did not end in the state the 2000 keys lead to\n  expected: …{expected_summary}\n  title:    {last}"
    );
    assert_eq!(t.shininess, 200.0, "250 H end at the bound 200");

    // Still responsive: one more key changes the title within a second.
    lab.assert_alive();
    let before = lab.title();
    lab.keys(&["h"]);
    let pressed = Instant::now();
    let answered = poll(PATIENCE, || (lab.title() != before).then_some(()));
    assert!(answered.is_some(), "the window no longer answers keys");
    assert_within(
        pressed.elapsed(),
        Duration::from_secs(1),
        "answering a key after the storm",
    );
    assert!(
        lab.title().contains("shininess 199 "),
        "h after the storm: {}",
        lab.title()
    );
    let image = lab.settled();
    lab.save(&image, "after_storm");
    assert!(
        coverage(&image, background(&image)) > 0.01,
        "nothing drawn after the storm"
    );
    lab.assert_clean();
    lab.escape();
}

// ---------------------------------------------------------------------------------------------
// Failures in a window
// ---------------------------------------------------------------------------------------------

/// Runs an example on the display and returns its exit status and stderr (it must end by itself).
fn run_to_end(x: &Xvfb, name: &str, args: &[&str], env: &[(&str, &str)]) -> (ExitStatus, String) {
    let mut command = x.command(example(name).to_str().unwrap());
    command
        .args(args)
        .current_dir(&x.dir)
        .env("XDG_RUNTIME_DIR", x.dir.join("xdg"))
        .stdin(Stdio::null());
    let _ = std::fs::create_dir_all(x.dir.join("xdg"));
    for (k, v) in env {
        command.env(k, v);
    }
    let mut child = command
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn");
    let read = |mut pipe: Box<dyn Read + Send>| {
        thread::spawn(move || {
            let mut bytes = Vec::new();
            let _ = pipe.read_to_end(&mut bytes);
            String::from_utf8_lossy(&bytes).into_owned()
        })
    };
    let stdout = read(Box::new(child.stdout.take().unwrap()));
    let stderr = read(Box::new(child.stderr.take().unwrap()));
    struct Kill(Child);
    impl Drop for Kill {
        fn drop(&mut self) {
            let _ = self.0.kill();
            let _ = self.0.wait();
        }
    }
    let mut child = Kill(child);
    let status = poll(PATIENCE, || child.0.try_wait().ok().flatten())
        .unwrap_or_else(|| panic!("{name} {args:?} did not end within 20 s"));
    // The pipes close when the program (which starts no other) has ended: all it wrote is read.
    let stdout = stdout.join().expect("the stdout reader");
    let stderr = stderr.join().expect("the stderr reader");
    let text = format!("{stdout}{stderr}");
    for bad in ["panicked", "RUST_BACKTRACE"] {
        assert!(!text.contains(bad), "{name} {args:?} printed `{bad}`:\n{text}");
    }
    (status, text)
}

#[test]
fn window_mode_failures_are_one_clear_message() {
    let x = Xvfb::start("window_failures");
    // A broken shader: the diagnostic with file:line:column, exit 1, no window left open.
    let shaders = x.dir.join("shaders");
    common::copy_shaders(&shaders);
    let frag = shaders.join("phong.frag");
    let text = std::fs::read_to_string(&frag).unwrap();
    std::fs::write(&frag, text.replacen("void main", "void main oops", 1)).unwrap();
    let (status, out) = run_to_end(&x, "phong", &["--shaders", shaders.to_str().unwrap()], &[]);
    println!("broken shader:\n{out}");
    assert_eq!(status.code(), Some(1), "broken shader: {out}");
    assert!(
        out.contains("phong.frag:") && out.contains("oops"),
        "broken shader message: {out}"
    );

    // No adapter (lavapipe hidden): the install hint, exit 1.
    let (status, out) = run_to_end(
        &x,
        "phong",
        &[],
        &[("VK_ICD_FILENAMES", "/nonexistent"), ("WGPU_BACKEND", "vulkan")],
    );
    println!("no adapter:\n{out}");
    assert_eq!(status.code(), Some(1), "no adapter: {out}");
    assert!(
        out.contains("no GPU adapter found") && out.contains("mesa-vulkan-drivers"),
        "no adapter message: {out}"
    );

    // A lost device (test hook): a clear message and exit 1, not a panic or a hang.
    let (status, out) = run_to_end(&x, "noise", &[], &[("SHADERLAB_TEST_LOSE_DEVICE", "1")]);
    println!("device lost:\n{out}");
    assert_eq!(status.code(), Some(1), "device lost: {out}");
    assert!(out.contains("the GPU device was lost"), "device lost message: {out}");
}

/// Live reload (the shader toolchain's promise): in a window, saving a shader under `--shaders`
/// recompiles it within about a second; a broken save keeps the last good pipeline running and
/// puts SHADER ERROR in the title, with `file:line:column` on stderr; fixing it recovers.
#[test]
fn live_reload_recompiles_keeps_the_last_good_pipeline_and_recovers() {
    let x = Xvfb::start("live_reload");
    let (shaders, frag, original) = phong_shaders(&x);
    let lab = x.launch(
        "phong",
        &["--shaders", shaders.to_str().expect("utf-8 path"), "--object", "sphere"],
        &[],
    );
    lab.first_frame();
    let before = lab.settled();
    let green = |image: &RgbImage| {
        let m = object_mean(image);
        m[1] > 240.0 && m[0] < 10.0 && m[2] < 10.0
    };
    assert!(!green(&before));

    // 1. A good edit shows up within about a second.
    let output = "frag_color = clamp(Ka * Iamb + Kd * Idiff + Ks * Ispec, 0.0, 1.0);";
    assert!(original.contains(output), "phong.frag changed: update this test");
    std::fs::write(
        &frag,
        original.replace(output, "frag_color = vec4(0.0, 1.0, 0.0, 1.0);"),
    )
    .expect("edit");
    let edited = Instant::now();
    let shown = poll(PATIENCE, || {
        let image = lab.capture();
        green(&image).then_some(image)
    })
    .unwrap_or_else(|| panic!("the edit never showed; stderr:\n{}", lab.stderr()));
    let latency = edited.elapsed();
    println!("live reload: the edit showed after {latency:?}");
    assert_within(latency, Duration::from_millis(1500), "live reload");
    lab.save(&shown, "green");

    // 2. A broken save: error with the file and line, title flag, last good pipeline kept.
    let line = original.lines().position(|l| l.contains("void main")).expect("main") + 2;
    std::fs::write(
        &frag,
        original.replace("void main() {", "void main() {\n    oops = 1.0;"),
    )
    .expect("break");
    let title = lab.wait_title_contains("SHADER ERROR");
    assert!(title.starts_with("Lab05-3"), "{title}");
    let needle = format!("phong.frag:{line}:");
    poll(PATIENCE, || lab.stderr().contains(&needle).then_some(()))
        .unwrap_or_else(|| panic!("no `{needle}` on stderr:\n{}", lab.stderr()));
    assert!(green(&lab.settled()), "the last good pipeline must keep running");

    // 3. Fixed: the original picture and a clean title come back.
    std::fs::write(&frag, &original).expect("fix");
    lab.wait_title("a title without SHADER ERROR", |t| {
        !t.contains("SHADER ERROR") && t.starts_with("Lab05-3")
    });
    let after = poll(PATIENCE, || {
        let image = lab.capture();
        (!green(&image)).then_some(image)
    })
    .expect("the original shader must come back");
    let p = psnr(&before, &after).expect("same size");
    assert!(p > 40.0, "after the fix the picture is the original again: {p:.1} dB");
}

/// A copy of the built-in shaders in the display's folder: the folder, its `phong.frag` and that
/// file's text.
fn phong_shaders(x: &Xvfb) -> (PathBuf, PathBuf, String) {
    let shaders = x.dir.join("shaders");
    common::copy_shaders(&shaders);
    let frag = shaders.join("phong.frag");
    let original = std::fs::read_to_string(&frag).expect("read phong.frag");
    (shaders, frag, original)
}

/// phong.frag edited: `add` joins the end of `main`'s first line, and `term` is added to the
/// colour it writes.
fn phong_frag_with(original: &str, add: &str, term: &str) -> String {
    let output = "frag_color = clamp(Ka * Iamb + Kd * Idiff + Ks * Ispec, 0.0, 1.0);";
    assert!(original.contains(output), "phong.frag changed: update this test");
    original
        .replacen("void main() {", &format!("void main() {{\n{add}"), 1)
        .replace(
            output,
            &format!("frag_color = clamp(Ka * Iamb + Kd * Idiff + Ks * Ispec + {term}, 0.0, 1.0);"),
        )
}

/// A panic in the window is said as what it is, an internal error with the
/// panic's message and place, never as a window closed by another program; a reload of
/// `h(c.y)` with an `out` argument (on which naga 30's SPIR-V writer panicked) draws; and a live
/// reload whose compile panics (anything inside the compile, `SHADERLAB_TEST_PANIC=reload`)
/// keeps the window and its last good pipeline, with SHADER ERROR in the title and the message
/// on stderr.
#[test]
fn panics_are_internal_errors_and_a_reload_that_panics_keeps_the_last_good_pipeline() {
    let x = Xvfb::start("panics");
    let (status, out) = run_to_end(&x, "phong", &[], &[("SHADERLAB_TEST_PANIC", "init")]);
    println!("a panic at the start:\n{out}");
    assert_eq!(status.code(), Some(1), "{out}");
    assert!(
        out.contains("phong: error: internal error: SHADERLAB_TEST_PANIC=init (at src/shell/window/mod.rs:"),
        "{out}"
    );
    assert!(!out.contains("closed or destroyed by another program"), "{out}");

    let (shaders, frag, original) = phong_shaders(&x);
    let dir = shaders.to_str().expect("utf-8 path");
    let mut lab = x.launch("phong", &["--shaders", dir, "--object", "sphere"], &[]);
    lab.first_frame();
    let before = lab.settled();
    let out_component = phong_frag_with(&original, "    vec4 c = vec4(0.0);\n    h(c.y);", "c").replacen(
        "void main() {",
        "void h(out float x) { x = 1.0; }\n\nvoid main() {",
        1,
    );
    std::fs::write(&frag, out_component).expect("write h(c.y)");
    // naga 30's SPIR-V writer panicked on it; the compiler passes the component through a local
    // now, so the reload draws it: green added everywhere the sphere is.
    poll(PATIENCE, || {
        (lab.stderr().matches("phong: shaders reloaded").count() >= 1).then_some(())
    })
    .unwrap_or_else(|| panic!("no reload on stderr:\n{}", lab.stderr()));
    lab.assert_alive();
    let title = lab.wait_title("a title without SHADER ERROR", |t| {
        !t.contains("SHADER ERROR") && t.starts_with("Lab05-3")
    });
    assert!(title.starts_with("Lab05-3"), "{title}");
    let after = lab.settled();
    let p = psnr(&before, &after).expect("same size");
    assert!(p < 30.0, "the reloaded shader draws its green: {p:.1} dB");
    lab.assert_clean();
    std::fs::write(&frag, &original).expect("fix");
    poll(PATIENCE, || {
        (lab.stderr().matches("phong: shaders reloaded").count() >= 2).then_some(())
    })
    .unwrap_or_else(|| panic!("no second reload on stderr:\n{}", lab.stderr()));
    lab.escape();

    // Whatever panics inside a reload's compile: the same, with the panic's message and place.
    let mut lab = x.launch("phong", &["--shaders", dir], &[("SHADERLAB_TEST_PANIC", "reload")]);
    lab.first_frame();
    lab.idle();
    std::fs::write(&frag, format!("{original}\n")).expect("save");
    lab.wait_title_contains("SHADER ERROR");
    let said = "internal error: SHADERLAB_TEST_PANIC=reload (at src/shell/reload.rs:";
    poll(PATIENCE, || lab.stderr().contains(said).then_some(()))
        .unwrap_or_else(|| panic!("no `{said}` on stderr:\n{}", lab.stderr()));
    lab.keys(&["2"]);
    lab.wait_title_contains("| sphere");
    lab.escape();
}

/// A window's first compile has no last good pipeline to keep drawing, so it
/// is bounded as the command line's are: a shader the driver compiles for minutes ends the
/// window at the watchdog with a message saying so.
#[test]
fn a_window_whose_first_compile_runs_away_meets_the_watchdog() {
    let x = Xvfb::start("first_compile");
    let (shaders, frag, original) = phong_shaders(&x);
    let slow = phong_frag_with(
        &original,
        "    float a[100000];\n    a[int(gl_FragCoord.x)] = 1.0;",
        "a[int(gl_FragCoord.y)]",
    );
    std::fs::write(&frag, slow).expect("write the slow shader");
    let dir = shaders.to_str().expect("utf-8 path");
    let (status, out) = run_to_end(&x, "phong", &["--shaders", dir, "--timeout", "1"], &[]);
    assert_eq!(status.code(), Some(1), "{out}");
    assert!(
        out.contains("the GPU's driver was still compiling phong") && out.contains("after 1 s (the watchdog"),
        "{out}"
    );
}

/// A live reload whose compile takes minutes (a 100,000-float array on
/// lavapipe) never freezes the window. The compile runs off the frame loop: the last good
/// pipeline keeps drawing, a key changes the lab (its title, a new frame), and Esc or SIGTERM
/// end the process within seconds, without waiting for the compile inside the driver.
#[test]
fn a_reload_that_compiles_for_minutes_keeps_the_window_answering() {
    let x = Xvfb::start("slow_compile");
    let (shaders, frag, original) = phong_shaders(&x);
    let slow = phong_frag_with(
        &original,
        "    float a[100000];\n    for (int i = 0; i < 100000; i++) a[i] = float(i) * 1e-6;",
        "a[int(gl_FragCoord.x)]",
    );
    for ending in ["Escape", "TERM"] {
        std::fs::write(&frag, &original).expect("restore phong.frag");
        let mut lab = x.launch("phong", &["--shaders", shaders.to_str().expect("utf-8 path")], &[]);
        lab.first_frame();
        lab.idle();
        std::fs::write(&frag, &slow).expect("save the slow shader");
        poll(PATIENCE, || (lab.said("compile 1 started") > 0).then_some(()))
            .unwrap_or_else(|| panic!("{ending}: the save was never compiled; stderr:\n{}", lab.stderr()));
        let frames = lab.said("frame");
        lab.keys(&["2"]);
        lab.wait_title_contains("| sphere");
        poll(PATIENCE, || (lab.said("frame") > frames).then_some(()))
            .unwrap_or_else(|| panic!("{ending}: no frame after the key; stderr:\n{}", lab.stderr()));
        assert_eq!(
            lab.said("compile 1 ended"),
            0,
            "{ending}: the slow compile ended already, so this test proves nothing: make it slower"
        );
        let asked = Instant::now();
        if ending == "Escape" {
            lab.keys(&["Escape"]);
        } else {
            let status = Command::new("kill")
                .args(["-TERM", &lab.pid().to_string()])
                .status()
                .expect("kill");
            assert!(status.success());
        }
        let status = lab.wait_exit(PATIENCE);
        assert_within(
            asked.elapsed(),
            Duration::from_secs(5),
            &format!("{ending} while compiling"),
        );
        #[cfg(unix)]
        {
            use std::os::unix::process::ExitStatusExt;
            match ending {
                "Escape" => assert!(status.success(), "{status:?}; stderr:\n{}", lab.stderr()),
                _ => assert_eq!(status.signal(), Some(15), "{status:?}; stderr:\n{}", lab.stderr()),
            }
        }
        lab.assert_clean();
    }
}

/// Issue 9, items 4 and 10: a window destroyed by another program (`xdotool windowclose`) ends
/// the lab with one clear message and status 1, not a panic inside winit; a window resized past
/// what the GPU can draw says so once and keeps drawing, without a flood of validation errors.
#[test]
fn hostile_window_managers_get_clear_answers() {
    let x = Xvfb::start("hostile_windows");
    let mut lab = x.launch("normal_rgb", &[], &[]);
    lab.first_frame();
    let limit = 8192 * 2 + 100; // beyond lavapipe's 16384 texels
    let _ = lab.resize(limit, 300);
    poll(PATIENCE, || {
        lab.stderr().contains("larger than the GPU can draw").then_some(())
    })
    .unwrap_or_else(|| panic!("an oversized window said nothing: {}", lab.stderr()));
    // Every frame at that size drawn (and a key's redraw more): said once, all the same.
    lab.idle();
    lab.keys(&["Right"]);
    lab.idle();
    let err = lab.stderr();
    assert!(
        err.matches("larger than the GPU can draw").count() == 1 && !err.contains("Validation Error"),
        "an oversized window: {err}"
    );
    lab.assert_alive();
    let _ = x.xdotool_output(&["windowclose", &lab.window]);
    let status = lab.wait_exit(PATIENCE);
    let err = lab.stderr();
    println!("window closed by another program: {status}\n{err}");
    assert_eq!(status.code(), Some(1), "{err}");
    assert!(err.contains("closed or destroyed by another program"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

/// Issue 17, item 5: a window destroyed by another program while its frames go through X shared
/// memory. A put the server refuses (BadDrawable) never completes, and dropping the presenter
/// waited for that completion for good: 2 of 30 paced runs and every `--unpaced` run (a put is
/// nearly always in flight) hung. Each cycle must end within 5 s, with the one clear message.
#[test]
fn windows_closed_while_drawing_end_and_never_hang() {
    let x = Xvfb::start("close_while_drawing");
    let cycles: [(&str, &[&str], u64); 6] = [
        ("wave", &["--unpaced"], 300),
        ("particles", &["--unpaced"], 700),
        ("wave", &["--unpaced"], 1200),
        ("particles", &["--unpaced"], 450),
        ("wave", &[], 500),
        ("particles", &[], 900),
    ];
    for (name, args, ms) in cycles {
        // The shared-memory presenter for sure (it is the default only for CPU adapters).
        let mut lab = x.launch(name, args, &[("SHADERLAB_PRESENT", "shm")]);
        sleep_ms(ms);
        x.xdotool(&["windowclose", &lab.window]);
        let closed = Instant::now();
        let status = lab.wait_exit(PATIENCE);
        assert_within(
            closed.elapsed(),
            Duration::from_secs(5),
            &format!("{name} {args:?}: ending once closed"),
        );
        let err = lab.stderr();
        assert_eq!(status.code(), Some(1), "{name} {args:?}: {err}");
        assert!(
            err.contains("closed or destroyed by another program"),
            "{name} {args:?}: {err}"
        );
        // The refused put is the same news: not a second message about the presenter.
        for bad in ["shared-memory presenter", "panicked"] {
            assert!(!err.contains(bad), "{name} {args:?} printed `{bad}`: {err}");
        }
    }
}

/// Issue 9, item 8: F12 names carry the process id, so two windows writing screenshots into one
/// folder in the same second never overwrite each other.
#[test]
fn f12_names_from_two_windows_do_not_collide() {
    let x = Xvfb::start("f12_two_windows");
    let a = x.launch("position_rgb", &[], &[]);
    a.first_frame();
    let b = x.launch("position_rgb", &[], &[]);
    b.first_frame();
    a.keys(&["F12"]);
    b.keys(&["F12"]);
    let pngs = poll(PATIENCE, || {
        let n: Vec<_> = std::fs::read_dir(&x.dir)
            .ok()?
            .filter_map(|e| e.ok())
            .filter(|e| e.path().extension().is_some_and(|x| x == "png"))
            .collect();
        (n.len() == 2).then_some(n)
    });
    assert!(
        pngs.is_some(),
        "two F12 screenshots expected; stdout:\n{}\n{}",
        a.stdout(),
        b.stdout()
    );
}

/// Issue 13: `legacy VERT FRAG` in a window: the user's GLSL 1.10 files reload live wherever
/// they are (a good edit shows, a broken one names its file and line and keeps the last good
/// pipeline), the `1`-`4` keys choose the object, and Esc quits cleanly.
#[test]
fn legacy_window_reloads_the_users_files() {
    let x = Xvfb::start("legacy_window");
    let dir = x.dir.join("course");
    std::fs::create_dir_all(&dir).expect("course dir");
    let (vert, frag) = (dir.join("mine.vert"), dir.join("mine.frag"));
    std::fs::write(
        &vert,
        "varying vec3 n;\nvoid main() { n = gl_Normal; gl_Position = ftransform(); }\n",
    )
    .expect("vert");
    let red = "varying vec3 n;\nvoid main() {\n    gl_FragColor = vec4(1.0, 0.0, 0.0, 1.0);\n}\n";
    std::fs::write(&frag, red).expect("frag");
    let mut lab = x.launch(
        "legacy",
        &[
            vert.to_str().expect("utf-8"),
            frag.to_str().expect("utf-8"),
            "--object",
            "sphere",
        ],
        &[],
    );
    lab.first_frame();
    let is = |image: &RgbImage, want: [f64; 3]| {
        let m = object_mean(image);
        (0..3).all(|k| (m[k] - want[k]).abs() < 10.0)
    };
    let before = lab.settled();
    assert!(is(&before, [255.0, 0.0, 0.0]), "{:?}", object_mean(&before));
    assert!(lab.title().contains("mine.vert + mine.frag"), "{}", lab.title());

    std::fs::write(
        &frag,
        red.replace("vec4(1.0, 0.0, 0.0, 1.0)", "vec4(0.0, 1.0, 0.0, 1.0)"),
    )
    .expect("edit");
    poll(PATIENCE, || is(&lab.capture(), [0.0, 255.0, 0.0]).then_some(()))
        .unwrap_or_else(|| panic!("the edit never showed; stderr:\n{}", lab.stderr()));

    std::fs::write(&frag, red.replace("gl_FragColor = ", "gl_FragColor = oops + ")).expect("break");
    lab.wait_title_contains("SHADER ERROR");
    poll(PATIENCE, || lab.stderr().contains("mine.frag:3:").then_some(()))
        .unwrap_or_else(|| panic!("no `mine.frag:3:` on stderr:\n{}", lab.stderr()));
    assert!(
        is(&lab.settled(), [0.0, 255.0, 0.0]),
        "the last good pipeline keeps running"
    );

    lab.keys(&["1"]);
    lab.wait_title("the cube", |t| t.contains("| cube"));
    lab.escape();
    let status = lab.wait_exit(PATIENCE);
    assert!(status.success(), "{status}; stderr:\n{}", lab.stderr());
}

/// Issues 10–12: every lab of the list besides seed 000's (tested above) opens a window of its
/// original's size and title, draws, matches its offscreen picture where nothing moves, and
/// quits on Esc with status 0.
#[test]
fn every_lecture_lab_opens_draws_and_quits() {
    let x = Xvfb::start("every_lab");
    for entry in shaderlab::course::ALL.iter().skip(5) {
        let name = entry.info.name;
        let mut lab = x.launch(name, &[], &[]);
        let frame = poll(PATIENCE, || {
            let image = lab.capture();
            let drawn = image.pixels().any(|p| p.0 != background(&image));
            drawn.then_some(image)
        })
        .unwrap_or_else(|| panic!("{name}: nothing drawn within 10 s; stderr:\n{}", lab.stderr()));
        assert_eq!(frame.dimensions(), entry.info.size, "{name}: the original's size");
        assert!(
            lab.title().starts_with(entry.info.original_title),
            "{name}: title `{}`",
            lab.title()
        );
        let animated = (entry.params)().has("time");
        if !animated {
            let mut offscreen = common::lab(entry);
            let (w, h) = entry.info.size;
            let expected = offscreen.rgb(w, h);
            let window = lab.settled();
            let db = psnr(&window, &expected).expect("same size");
            println!("{name}: window against offscreen {db:.1} dB");
            assert!(
                db >= 40.0,
                "{name}: the window shows {db:.1} dB from the offscreen picture"
            );
        }
        lab.escape();
    }
}

/// The lecture labs' keys reach them through a real window: a character key, a special key
/// (arrows, Page Up) and a shifted one, each showing in the title.
#[test]
fn lecture_keys_work_in_a_window() {
    let x = Xvfb::start("lecture_keys");
    let mut twist = x.launch("twist", &[], &[]);
    twist.first_frame();
    twist.keys(&["plus"]);
    twist.wait_title_contains("twisting=4.5");
    twist.escape();
    let mut bump = x.launch("bump", &[], &[]);
    bump.first_frame();
    bump.keys(&["Left", "Prior"]);
    bump.wait_title_contains("blx=1.25");
    bump.wait_title_contains("blz=-1.75");
    bump.escape();
    let mut suzanne = x.launch("suzanne_phong", &[], &[]);
    suzanne.first_frame();
    suzanne.keys(&["1", "A"]);
    suzanne.wait_title_contains("flat");
    suzanne.wait_title_contains("ka=0.25");
    suzanne.escape();
}

// ---------------------------------------------------------------------------------------------
// Presentation through X shared memory
// ---------------------------------------------------------------------------------------------

/// On lavapipe under X11 the window presents through MIT-SHM (src/shell/window/shm.rs), lavapipe
/// writing each frame into the shared memory itself; copying it there through a readback buffer
/// (`SHADERLAB_PRESENT=shm-copy`) and the swapchain (`SHADERLAB_PRESENT=swapchain`) stay as
/// fallbacks. All three must show exactly the pixels of `--screenshot`, and each must be the
/// path asked for (`SHADERLAB_PRESENT=shm` prints why when the presenter is not used, or why it
/// copies).
#[test]
fn shared_memory_and_swapchain_windows_show_the_screenshot_pixels() {
    let x = Xvfb::start("shm_present");
    // 333 px: rows of 1332 bytes, which the linear target in the segment pads to 1344
    // (llvmpipe rounds rows up to 4 pixels and 64 bytes), so the put must use the image's own
    // row pitch.
    let cases: [(&str, &[&str]); 3] = [
        ("position_rgb", &["--object", "torus", "--rotate", "30,45,0"]),
        ("phong", &["--object", "teapot", "--rotate", "20,-30,0"]),
        (
            "phong",
            &["--object", "torus", "--rotate", "10,20,0", "--size", "333x217"],
        ),
    ];
    for (i, (name, args)) in cases.into_iter().enumerate() {
        let png = x.dir.join(format!("{name}{i}_screenshot.png"));
        let status = Command::new(example(name))
            .args(args)
            .arg("--screenshot")
            .arg(&png)
            .stdout(Stdio::null())
            .status()
            .expect("run --screenshot");
        assert!(status.success(), "{name} --screenshot failed");
        let expected = image::open(&png).expect("screenshot PNG").to_rgb8();
        for present in ["shm", "shm-copy", "swapchain"] {
            let mut lab = x.launch(name, args, &[("SHADERLAB_PRESENT", present)]);
            lab.first_frame();
            let shown = lab.settled();
            lab.save(&shown, &format!("{name}{i}_{present}"));
            lab.assert_alive();
            let differing = shown.pixels().zip(expected.pixels()).filter(|(a, b)| a != b).count();
            assert_eq!(
                (shown.dimensions(), differing),
                (expected.dimensions(), 0),
                "{name}: the window presented with {present} differs from --screenshot in {differing} pixels"
            );
            assert!(
                !lab.stderr().contains("presenting with the swapchain"),
                "{name}: SHADERLAB_PRESENT={present} did not present as asked:\n{}",
                lab.stderr()
            );
            // Asked for shared memory, the frame goes straight into it on lavapipe.
            assert_eq!(
                lab.stderr().contains("copies each frame"),
                present == "shm-copy",
                "{name}: SHADERLAB_PRESENT={present}:\n{}",
                lab.stderr()
            );
            lab.assert_clean();
            lab.escape();
        }
    }
}

/// Issue 9, item 14: without `XDG_RUNTIME_DIR`, a window run (where Mesa's device-select layer
/// looks for the display server and complains about the variable) prints nothing of Mesa's,
/// because the process gives itself a private directory. The control run, with no temporary
/// directory to make one in, shows the warnings the mechanism removes.
#[test]
fn a_window_without_runtime_dir_prints_no_mesa_warnings() {
    let x = Xvfb::start("no_runtime_dir");
    let run = |tmp: Option<&str>| -> String {
        let mut command = x.command(example("position_rgb").to_str().unwrap());
        command
            .current_dir(&x.dir)
            .env_remove("XDG_RUNTIME_DIR")
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped());
        if let Some(tmp) = tmp {
            command.env("TMPDIR", tmp);
        }
        // Its first frame shown, Mesa has started (and said what it had to).
        command.env("SHADERLAB_TEST_LOG", "1");
        let mut child = command.spawn().expect("spawn");
        let stderr = collect(child.stderr.take().unwrap());
        poll(PATIENCE, || {
            stderr
                .lock()
                .ok()
                .filter(|s| s.contains("shaderlab-test: frame"))
                .map(|_| ())
        })
        .expect("no frame shown");
        let _ = child.kill();
        let _ = child.wait();
        let text = stderr.lock().map(|s| s.clone()).unwrap_or_default();
        text
    };
    let with_dir = run(None);
    assert!(!with_dir.contains("XDG_RUNTIME_DIR"), "{with_dir}");
    let control = run(Some("/nonexistent"));
    assert!(
        control.contains("XDG_RUNTIME_DIR"),
        "the control run should show Mesa's warning; the test would not see a regression: {control}"
    );
}

// ---------------------------------------------------------------------------------------------
// F10
// ---------------------------------------------------------------------------------------------

#[test]
fn f10_records_what_the_window_shows_into_a_gif() {
    use image::AnimationDecoder;
    let x = Xvfb::start("f10");
    let mut lab = x.launch("wave", &[], &[]);
    lab.first_frame();
    lab.keys(&["F10"]);
    let started = poll(PATIENCE, || lab.stderr().contains("recording to ").then_some(()));
    assert!(started.is_some(), "F10 said nothing; stderr:\n{}", lab.stderr());
    lab.wait_title("REC with 3 frames", |t| {
        t.split("REC ")
            .nth(1)
            .and_then(|r| r.split(' ').next())
            .and_then(|n| n.parse::<u32>().ok())
            .is_some_and(|n| n >= 3)
    });
    lab.keys(&["F10"]);
    let line = poll(PATIENCE, || {
        lab.stdout()
            .lines()
            .find(|l| l.starts_with("recording: "))
            .map(str::to_owned)
    })
    .unwrap_or_else(|| panic!("F10 printed no `recording:` line; stderr:\n{}", lab.stderr()));
    let path = PathBuf::from(
        line.trim_start_matches("recording: ")
            .split(" (")
            .next()
            .unwrap()
            .trim(),
    );
    assert!(
        path.starts_with(&lab.x.dir),
        "not in the current directory: {}",
        path.display()
    );
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    assert!(name.starts_with("wave-") && name.ends_with(".gif"), "{name}");
    let bytes = std::fs::read(&path).unwrap();
    let frames = image::codecs::gif::GifDecoder::new(std::io::Cursor::new(bytes))
        .unwrap()
        .into_frames()
        .collect_frames()
        .unwrap();
    assert!(frames.len() >= 3, "{} frames in 1.5 s", frames.len());
    assert_eq!(frames[0].buffer().dimensions(), (512, 512));
    assert_ne!(
        frames[0].buffer(),
        frames[frames.len() - 1].buffer(),
        "the wave moved while recording"
    );
    let leftovers: Vec<_> = std::fs::read_dir(&lab.x.dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");
    lab.escape();
}

/// Presses F10 and waits until the title counts at least 3 frames recorded.
fn record_3_frames(lab: &App) {
    lab.keys(&["F10"]);
    lab.wait_title("REC with 3 frames", |t| {
        t.split("REC ")
            .nth(1)
            .and_then(|r| r.split(' ').next())
            .and_then(|n| n.parse::<u32>().ok())
            .is_some_and(|n| n >= 3)
    });
}

/// The frames of the recording the lab said it kept (`recording: PATH (N frames)` on stdout,
/// waited for: the line may still be on its way from the pipe when the process has ended), and
/// no temporary file left in the lab's directory.
fn recording_kept(lab: &App, what: &str) -> usize {
    use image::AnimationDecoder;
    let line = poll(PATIENCE, || {
        lab.stdout()
            .lines()
            .find(|l| l.starts_with("recording: "))
            .map(str::to_owned)
    })
    .unwrap_or_else(|| panic!("{what}: no `recording:` line; stderr:\n{}", lab.stderr()));
    let path = PathBuf::from(line.trim_start_matches("recording: ").split(" (").next().unwrap());
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{what}: {}: {e}", path.display()));
    let frames = image::codecs::gif::GifDecoder::new(std::io::Cursor::new(bytes))
        .unwrap()
        .into_frames()
        .collect_frames()
        .unwrap_or_else(|e| panic!("{what}: {}: {e}", path.display()));
    let leftovers: Vec<_> = std::fs::read_dir(&lab.x.dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{what}: temporary files left: {leftovers:?}");
    frames.len()
}

/// A recording is finished and kept however the window ends while it runs: destroyed by
/// another program (`xdotool windowclose`: exit 1 with the one message) or told to stop by a
/// signal (SIGTERM, SIGHUP: the process then ends by that signal). Both lost the GIF before.
#[test]
fn f10_recordings_are_kept_when_the_window_is_destroyed_or_signalled() {
    let x = Xvfb::start("f10_kept");
    for ending in ["windowclose", "TERM", "HUP"] {
        let mut lab = x.launch("wave", &[], &[]);
        lab.first_frame();
        record_3_frames(&lab);
        if ending == "windowclose" {
            lab.x.xdotool(&["windowclose", &lab.window]);
        } else {
            let status = Command::new("kill")
                .args([&format!("-{ending}"), &lab.pid().to_string()])
                .status()
                .unwrap();
            assert!(status.success());
        }
        let status = lab.wait_exit(PATIENCE);
        #[cfg(unix)]
        {
            use std::os::unix::process::ExitStatusExt;
            match ending {
                "windowclose" => assert_eq!(status.code(), Some(1), "{ending}: {status:?}"),
                "TERM" => assert_eq!(status.signal(), Some(15), "{ending}: {status:?}"),
                _ => assert_eq!(status.signal(), Some(1), "{ending}: {status:?}"),
            }
        }
        let frames = recording_kept(&lab, ending);
        assert!(frames >= 3, "{ending}: {frames} frames kept");
        lab.assert_clean();
    }
}

/// Issue 47, item 12: a window destroyed by another program ends (exit 1, the one message, no
/// panic) and keeps its F10 recording whatever it is doing: drawing through X shared memory,
/// drawing through the swapchain, or paused under another window (nothing drawn, so nothing
/// fails on the window). Each phase is run as it comes and with winit's `Destroyed` ignored
/// (`SHADERLAB_TEST_IGNORE_DESTROYED`), so that the window's own watch on the X server must
/// notice: before it, a paused window whose `Destroyed` went unseen ran on for ever, unseen
/// (and a drawing one only ended through winit panicking on the window).
#[test]
fn windows_destroyed_in_any_phase_end_and_keep_their_recordings() {
    let x = Xvfb::start("destroyed_any_phase");
    for phase in ["shared memory", "swapchain", "covered"] {
        for ignored in [false, true] {
            let what = format!("{phase}{}", if ignored { ", Destroyed ignored" } else { "" });
            let mut env = Vec::new();
            if phase == "swapchain" {
                env.push(("SHADERLAB_PRESENT", "swapchain"));
            }
            if ignored {
                env.push(("SHADERLAB_TEST_IGNORE_DESTROYED", "1"));
            }
            let mut lab = x.launch("wave", &[], &env);
            poll(PATIENCE, || (lab.said("frame") > 0).then_some(()))
                .unwrap_or_else(|| panic!("{what}: no frame; stderr:\n{}", lab.stderr()));
            record_3_frames(&lab);
            // Another window of the same size on top covers it whole: the lab stops drawing
            // and says it is idle.
            let cover = (phase == "covered").then(|| {
                let idle = lab.said("idle");
                let cover = x.launch("wave", &[], &[]);
                poll(PATIENCE, || (lab.said("idle") > idle).then_some(()))
                    .unwrap_or_else(|| panic!("{what}: drawing went on under the cover; stderr:\n{}", lab.stderr()));
                cover
            });
            x.xdotool(&["windowclose", &lab.window]);
            let status = lab.wait_exit(PATIENCE);
            drop(cover);
            let err = lab.stderr();
            assert_eq!(status.code(), Some(1), "{what}: {status:?}; stderr:\n{err}");
            assert_eq!(
                err.matches("closed or destroyed by another program").count(),
                1,
                "{what}: {err}"
            );
            for bad in ["shared-memory presenter", "panicked", "wgpu error"] {
                assert!(!err.contains(bad), "{what} printed `{bad}`: {err}");
            }
            let frames = recording_kept(&lab, &what);
            assert!(frames >= 3, "{what}: {frames} frames kept");
        }
    }
}

/// A shader that never ends (here: loops until its float stops growing, over a minute a frame)
/// meets the watchdog: the title says so and the window still answers; Esc ends it at once
/// with status 1 and the message, without waiting for the frame.
#[test]
fn a_frame_that_never_ends_is_said_in_the_title_and_esc_still_quits() {
    let x = Xvfb::start("watchdog");
    std::fs::write(x.dir.join("v.vert"), "void main() { gl_Position = ftransform(); }\n").unwrap();
    std::fs::write(
        x.dir.join("endless.frag"),
        "void main() {\n    float x = gl_FragCoord.x;\n    while (x >= 0.0) x += 1.0;\n    gl_FragColor = vec4(x);\n}\n",
    )
    .unwrap();
    for present in ["shm", "swapchain"] {
        let mut lab = x.launch(
            "legacy",
            &["v.vert", "endless.frag", "--size", "1024x1024", "--timeout", "1"],
            &[("SHADERLAB_PRESENT", present)],
        );
        lab.wait_title("GPU STUCK", |t| t.contains("GPU STUCK"));
        lab.assert_alive();
        lab.keys(&["Escape"]);
        let status = lab.wait_exit(PATIENCE);
        assert_eq!(status.code(), Some(1), "{present}: {status:?}\n{}", lab.stderr());
        assert!(
            lab.stderr().contains("the GPU did not finish a frame within 1 s"),
            "{present}: {}",
            lab.stderr()
        );
    }
}

// ---------------------------------------------------------------------------------------------
// F1: the parameter panel
// ---------------------------------------------------------------------------------------------

/// Issue 33: a thin grey line crossed the panel and its widgets (egui's separator line, left
/// where the panel was while it slid in): no column of the panel may be one colour other than
/// its background from top to bottom.
fn assert_no_stray_line(image: &RgbImage, panel_left: u32, what: &str) {
    let (w, h) = image.dimensions();
    let background = *image.get_pixel(w - 20, h - 2);
    // The panel's left edge and its scroll bar at the right are its own.
    for x in panel_left + 2..w - 14 {
        let column: Vec<&image::Rgb<u8>> = (0..h).map(|y| image.get_pixel(x, y)).collect();
        let first = column[0];
        if *first != background && column.iter().all(|p| *p == first) {
            panic!("{what}: a line crosses the panel at x = {x} ({first:?} top to bottom)");
        }
    }
}

/// Issue 33: Esc while the panel's colour picker is open closes the picker, as egui does, and
/// only the next Esc quits the lab (the first one quit it, edits and all).
#[test]
fn esc_closes_the_colour_picker_before_it_quits() {
    let x = Xvfb::start("colour_picker");
    let mut lab = x.launch("phong", &[], &[]);
    lab.first_frame();
    lab.keys(&["F1"]);
    let (w, _) = lab.first_frame().0.dimensions();
    let panel = lab.settled();
    assert_no_stray_line(&panel, w - 300, "phong's panel");
    // The ambientColor swatch (Material group, second row).
    lab.x.xdotool(&["mousemove", &(w as i32 - 185).to_string(), "263"]);
    lab.idle();
    lab.x.xdotool(&["click", "1"]);
    let open = lab.settled();
    lab.save(&open, "picker_open");
    let opened = mse(&open, &panel).unwrap();
    assert!(
        opened > 100.0,
        "the colour picker did not open (MSE {opened:.1} against the panel)"
    );
    lab.keys(&["Escape"]);
    lab.idle();
    lab.assert_alive();
    let closed = lab.settled();
    lab.save(&closed, "picker_closed");
    // Closed: the panel again (but for the swatch under the pointer and the frame time).
    let left = mse(&closed, &panel).unwrap();
    assert!(
        left < opened / 50.0,
        "Esc did not close the picker: MSE {left:.1} against the panel ({opened:.1} open)"
    );
    lab.escape();
}

/// F1 shows the panel over the right 300 pixels (the lab's pixels to its left untouched); a
/// click on its `twisting` slider changes the lab, a key typed into its number field does not
/// reach the lab, "Reset all" restores the defaults, and once F1 hides it the window is the
/// `--screenshot` picture again, byte for byte. On both presenters.
#[test]
fn f1_panel_edits_parameters_and_hides_to_the_exact_picture() {
    let x = Xvfb::start("panel");
    let png = x.dir.join("twist_screenshot.png");
    let status = Command::new(example("twist"))
        .arg("--screenshot")
        .arg(&png)
        .stdout(Stdio::null())
        .status()
        .expect("run --screenshot");
    assert!(status.success());
    let expected = image::open(&png).expect("screenshot PNG").to_rgb8();
    let (w, h) = expected.dimensions();
    let lab_width = w - 300;
    let left = |image: &RgbImage| image::imageops::crop_imm(image, 0, 0, lab_width, h).to_image();
    for present in ["shm", "swapchain"] {
        let mut lab = x.launch("twist", &[], &[("SHADERLAB_PRESENT", present)]);
        lab.first_frame();
        assert_eq!(lab.settled(), expected, "{present}: hidden by default");
        let default_title = lab.title();
        lab.keys(&["F1"]);
        let shown = poll(PATIENCE, || {
            let image = lab.capture();
            (image != expected).then_some(image)
        })
        .unwrap_or_else(|| panic!("{present}: F1 showed nothing"));
        let shown = {
            let _ = shown;
            lab.settled()
        };
        lab.save(&shown, &format!("panel_{present}"));
        assert_no_stray_line(&shown, lab_width, present);
        assert_eq!(
            left(&shown),
            left(&expected),
            "{present}: the lab's pixels left of the panel changed"
        );
        // The panel's `twisting` slider (Effect group, second row): a click at its left end.
        // A person points, then clicks: egui finds the control under the pointer it last saw.
        // egui applies the events of one frame together: the move is handled and drawn before
        // the button goes down (a press in the move's frame would miss the control, a move in
        // the release's frame would drag the slider). A slider takes its value while the
        // button is down, so the press is drawn before the release; a button or a number field
        // wants a click, which egui counts only when the release follows within 0.8 s, so
        // press and release go together (waiting for a frame between them can take longer on
        // a busy machine).
        let point = |x: i32, y: i32| {
            lab.x.xdotool(&["mousemove", &x.to_string(), &y.to_string()]);
            lab.idle();
        };
        let press = |x: i32, y: i32| {
            point(x, y);
            lab.x.xdotool(&["mousedown", "1"]);
            lab.idle();
            lab.x.xdotool(&["mouseup", "1"]);
            lab.idle();
        };
        let click = |x: i32, y: i32| {
            point(x, y);
            lab.x.xdotool(&["click", "1"]);
            lab.idle();
        };
        press(lab_width as i32 + 75, 148);
        let title = lab.wait_title(&format!("{present}: the slider moves twisting"), |t| {
            t != default_title && t.contains("twisting=")
        });
        // A key typed into the number field goes to the field, not to the lab's `+` key. egui
        // counts a click only when the release comes within 0.8 s of the press by its own
        // clock; on a machine busy enough to hold a frame between the two, the click is not
        // one and the field never takes the key. The lab's `-` then undoes its `+`, and the
        // click is tried again: a panel that lets keys through fails every try.
        let mut leaked = Vec::new();
        for _ in 0..5 {
            click(lab_width as i32 + 193, 148);
            lab.keys(&["plus"]);
            lab.idle();
            let now = lab.title();
            if now == title {
                break;
            }
            leaked.push(now);
            lab.keys(&["minus"]);
            lab.idle();
            lab.wait_title(&format!("{present}: the lab's `-` undoes its `+`"), |t| t == title);
        }
        assert!(
            leaked.len() < 5,
            "{present}: `+` typed into the panel reached the lab at every try: {leaked:?}"
        );
        // "Reset all", below the Effect group and the Port additions group (twist's `grid`).
        click(lab_width as i32 + 40, 220);
        lab.wait_title(&format!("{present}: Reset all"), |t| t == default_title);
        lab.keys(&["F1"]);
        let hidden = poll(PATIENCE, || {
            let image = lab.capture();
            (image == expected).then_some(image)
        });
        assert!(
            hidden.is_some(),
            "{present}: with the panel hidden the window differs from --screenshot"
        );
        lab.assert_alive();
        drop(lab);
    }
}

/// F2 turns the inspector on; a click picks a pixel and the inspector shows it, with the
/// colour the window shows there; a key that changes the lab inspects again (the view stays
/// live) while frames keep coming; F2 again hides it, back to the exact picture.
#[test]
fn f2_inspects_the_clicked_pixel_and_follows_the_lab() {
    let x = Xvfb::start("inspect");
    let mut lab = x.launch("phong", &["--set", "object=torus"], &[]);
    lab.first_frame();
    let plain = lab.settled();
    let (px, py) = (450u32, 180u32);
    let inspected = |n: usize| -> [u8; 4] {
        let line = poll(PATIENCE, || {
            let err = lab.stderr();
            let lines: Vec<&str> = err
                .lines()
                .filter(|l| l.starts_with("shaderlab-test: inspected"))
                .collect();
            lines.get(n - 1).map(|l| l.to_string())
        })
        .unwrap_or_else(|| panic!("no inspection {n}; stderr:\n{}", lab.stderr()));
        let rgba = line
            .split_once("rgba(")
            .and_then(|(_, r)| r.strip_suffix(')'))
            .unwrap_or_else(|| panic!("{line}"));
        let v: Vec<u8> = rgba.split(", ").map(|c| c.parse().expect("a byte")).collect();
        assert!(line.contains(&format!("inspected {px},{py} ")), "{line}");
        [v[0], v[1], v[2], v[3]]
    };
    lab.keys(&["F2"]);
    lab.idle();
    lab.x.xdotool(&[
        "mousemove",
        "--window",
        &lab.window,
        &px.to_string(),
        &py.to_string(),
        "click",
        "1",
    ]);
    let first = inspected(1);
    let shown = plain.get_pixel(px, py).0;
    for k in 0..3 {
        assert!(
            (i32::from(first[k]) - i32::from(shown[k])).abs() <= 2,
            "inspected {first:?}, window {shown:?}"
        );
    }
    let with_panel = lab.settled();
    lab.save(&with_panel, "inspector");
    assert_ne!(with_panel, plain, "the inspector is shown");
    // The light moves: the same pixel is inspected again, and its colour changes.
    let frames = lab.said("frame");
    lab.key_n("X", 8);
    let second = inspected(2);
    assert_ne!(first, second, "the inspection follows the lab");
    assert!(lab.said("frame") > frames, "frames kept coming");
    // Hidden, shown again, hidden again: the picture without the inspector is the same.
    lab.keys(&["F2"]);
    let hidden = lab.settled();
    lab.keys(&["F2"]);
    let _ = inspected(3);
    assert_ne!(lab.settled(), hidden, "shown again");
    lab.keys(&["F2"]);
    assert_eq!(lab.settled(), hidden, "hidden again");
    assert!(!lab.stderr().contains("inspected error"), "{}", lab.stderr());
    lab.escape();
}

/// The inspected pixel stays in sight and clickable beside the panels. At the
/// default 640x360 a click on the picture's centre (the teapot) inspects it; a click on the
/// inspector and then one on the picture inspects the picture's pixel, not the panel's; with F1
/// open too the two panels stay apart and the centre shows between them and is clicked; at
/// 1280x720 the pixel picked before stays in sight and clickable, and so does the picture
/// after a click on the inspector. Each time the window shows the inspected colour at the pixel (no panel
/// covers it). The windows are kept as `f1_f2_640x360.png` and `f1_f2_1280x720.png`.
#[test]
fn the_inspected_pixel_stays_visible_and_clickable_beside_the_panels() {
    let x = Xvfb::start_sized("inspect_layout", "1600x900x24");
    let mut lab = x.launch("phong", &[], &[]);
    lab.first_frame();
    assert_eq!(lab.settled().dimensions(), (640, 360));
    let click = |(px, py): (u32, u32)| {
        lab.x.xdotool(&[
            "mousemove",
            "--window",
            &lab.window,
            &px.to_string(),
            &py.to_string(),
            "click",
            "1",
        ]);
    };
    let inspections = || -> Vec<String> {
        lab.stderr()
            .lines()
            .filter(|l| l.starts_with("shaderlab-test: inspected"))
            .map(str::to_owned)
            .collect()
    };
    // Clicks `pixel` and waits for its inspection; the window shows its colour there.
    let inspect = |pixel: (u32, u32), what: &str| {
        let before = inspections().len();
        click(pixel);
        let want = format!("inspected {},{} ", pixel.0, pixel.1);
        let line = poll(PATIENCE, || {
            inspections().into_iter().skip(before).find(|l| l.contains(&want))
        })
        .unwrap_or_else(|| {
            panic!(
                "{what}: no inspection of {pixel:?} after the click; inspections: {:?}",
                inspections()
            )
        });
        let rgba: Vec<i32> = line
            .split_once("rgba(")
            .and_then(|(_, r)| r.strip_suffix(')'))
            .unwrap_or_else(|| panic!("{line}"))
            .split(", ")
            .map(|c| c.parse().expect("a byte"))
            .collect();
        let shown = lab.settled();
        let at = shown.get_pixel(pixel.0, pixel.1).0;
        assert!(
            (0..3).all(|k| (rgba[k] - i32::from(at[k])).abs() <= 2),
            "{what}: the window shows {at:?} at {pixel:?}, the inspection {rgba:?}: a panel covers the pixel"
        );
        shown
    };
    lab.keys(&["F2"]);
    lab.idle();
    inspect((330, 170), "640x360, F2");
    // A click on the inspector (right of the pixel, by the nearer edge), then on the picture's
    // centre.
    click((600, 200));
    lab.idle();
    inspect((320, 180), "640x360, after a click on the inspector");
    lab.keys(&["F1"]);
    lab.idle();
    let both = inspect((322, 182), "640x360, F1 and F2");
    lab.save(&both, "f1_f2_640x360");
    lab.resize(1280, 720).expect("resize");
    poll(PATIENCE, || (lab.geometry().2 == 1280).then_some(())).expect("the window grows to 1280x720");
    lab.idle();
    // The pixel picked before stays in sight: a click near it, then on the inspector (left of
    // it, by the nearer edge), then on the picture again.
    let large = inspect((330, 300), "1280x720, F1 and F2");
    lab.save(&large, "f1_f2_1280x720");
    click((100, 200));
    lab.idle();
    inspect((700, 500), "1280x720, after a click on the inspector");
    lab.escape();
}

/// Issue 47: a whole-frame view's legend strip (its range and counts) stays in sight whatever
/// panels are open at the default 640x360: with the inspector (F2) on the left, with the
/// inspector moved to the right by a pixel picked there, and with F1's panel open too, the
/// window's bottom strip is the view's own (F12 writes the view's picture with its legend).
/// The panels covered all but a part of it before. Keeps `legend_f2.png`, `legend_right.png`
/// and `legend_f1_f2.png`.
#[test]
fn the_views_legend_stays_in_sight_beside_the_panels() {
    let files = shaderlab::lab::UserFiles::default();
    let source = shaderlab::shader::ShaderSource::Dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders_glsl"));
    let cx = shaderlab::lab::BuildContext::new(common::gpu(), &source, shaderlab::offscreen::COLOR_FORMAT, &files);
    let mut lab_ref = (course::find("phong").expect("phong is a lab").new)(&cx).expect("phong builds");
    let file = phong_fragment_file(lab_ref.as_mut());
    let x = Xvfb::start("view_legend");
    let mut lab = x.launch(
        "phong",
        &["--set", "object=torus"],
        &[("SHADERLAB_TEST_VIEW", &format!("{file}:17"))],
    );
    lab.first_frame();
    lab.keys(&["F2"]);
    lab.idle();
    // The first inspection chooses the line's view.
    lab.x
        .xdotool(&["mousemove", "--window", &lab.window, "300", "150", "click", "1"]);
    poll(PATIENCE, || (lab.said("view ") >= 1).then_some(()))
        .unwrap_or_else(|| panic!("no view; stderr:\n{}", lab.stderr()));
    assert!(
        lab.stderr().contains("shaderlab-test: view 640x360"),
        "{}",
        lab.stderr()
    );
    let view = image::open(lab.f12(1)).expect("a PNG").to_rgb8();
    assert_eq!(view.dimensions(), (640, 360));
    let strip = |image: &RgbImage| {
        let h = picture::LEGEND_HEIGHT;
        image::imageops::crop_imm(image, 0, image.height() - h, image.width(), h).to_image()
    };
    let want = strip(&view);
    let legend_shown = |name: &str| {
        let shown = lab.settled();
        lab.save(&shown, name);
        let got = strip(&shown);
        let db = psnr(&got, &want).unwrap_or(f64::INFINITY);
        println!("{name}: the window's legend strip against the view's: {db:.1} dB");
        assert!(db >= 40.0, "{name}: the legend strip is covered ({db:.1} dB)");
    };
    legend_shown("legend_f2");
    // A pixel right of the middle: the inspector goes to the right, beside it.
    let inspected = lab.said("inspected");
    lab.x
        .xdotool(&["mousemove", "--window", &lab.window, "330", "80", "click", "1"]);
    poll(PATIENCE, || (lab.said("inspected") > inspected).then_some(()))
        .unwrap_or_else(|| panic!("no second inspection; stderr:\n{}", lab.stderr()));
    legend_shown("legend_right");
    lab.keys(&["F1"]);
    lab.idle();
    legend_shown("legend_f1_f2");
    lab.escape();
}

// ---------------------------------------------------------------------------------------------
// Whole-frame views
// ---------------------------------------------------------------------------------------------

/// The picture `probe` gives of `lab` at a window of `size` (the view drawn at the window's
/// width and its height less the legend strip), made by the library alone.
fn library_view(lab: &mut dyn shaderlab::lab::Lab, probe: &view::Probe, (w, h): (u32, u32)) -> image::RgbaImage {
    let vh = h - picture::LEGEND_HEIGHT;
    let log = view::encode(common::gpu(), lab, w, vh).expect("the frame records");
    let frame = view::draw_view(common::gpu(), &log, probe, w, vh).expect("the view draws");
    frame.picture().0
}

/// The file the phong lab's fragment shader is read from, as the lab shows it.
fn phong_fragment_file(lab: &mut dyn shaderlab::lab::Lab) -> String {
    let log = view::encode(common::gpu(), lab, 64, 64).expect("the frame records");
    let files: Vec<String> = (log.draws().iter())
        .flat_map(|d| d.setup.fragment.source.files.iter().map(|(p, _)| p.clone()))
        .collect();
    files
        .iter()
        .find(|p| p.ends_with("phong.frag"))
        .cloned()
        .unwrap_or_else(|| panic!("no phong.frag among {files:?}"))
}

/// In the window, F2 and a line chosen in the inspector's listing show that line's
/// value at every pixel in place of the picture, with the legend, the very picture the
/// library draws of the same state (F12 writes it, the screen shows it); a key that changes
/// the lab draws the view again; F3 shows the cost view, and F3 again the lab's picture, as
/// it was. (`SHADERLAB_TEST_VIEW` chooses the line as a click on it in the listing does.)
#[test]
fn line_and_cost_views_replace_the_picture_follow_the_lab_and_go_back() {
    // The window reads the checkout's shaders_glsl/ (live reload); so does this lab.
    let files = shaderlab::lab::UserFiles::default();
    let source = shaderlab::shader::ShaderSource::Dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders_glsl"));
    let cx = shaderlab::lab::BuildContext::new(common::gpu(), &source, shaderlab::offscreen::COLOR_FORMAT, &files);
    let mut lab_ref = (course::find("phong").expect("phong is a lab").new)(&cx).expect("phong builds");
    lab_ref.params_mut().set_str("object", "torus").expect("a torus");
    let file = phong_fragment_file(lab_ref.as_mut());
    // `vec4 Idiff = vec4(diffuseColor * max(dot(N, L), 0.0), 1.0);`
    let line = 17;
    let x = Xvfb::start("views");
    let mut lab = x.launch(
        "phong",
        &["--set", "object=torus"],
        &[("SHADERLAB_TEST_VIEW", &format!("{file}:{line}"))],
    );
    lab.first_frame();
    let plain = lab.settled();
    let (_, _, w, h) = lab.geometry();
    let view_said = |n: usize| {
        poll(PATIENCE, || (lab.said("view ") >= n).then_some(()))
            .unwrap_or_else(|| panic!("no view {n}; stderr:\n{}", lab.stderr()));
        let err = lab.stderr();
        let last = err
            .lines()
            .filter(|l| l.starts_with("shaderlab-test: view "))
            .nth(n - 1)
            .unwrap_or("")
            .to_owned();
        assert_eq!(last, format!("shaderlab-test: view {w}x{h}"), "{err}");
    };
    let f12 = |n: usize| -> image::RgbImage { image::open(lab.f12(n)).expect("a PNG").to_rgb8() };
    let rgb = |i: &image::RgbaImage| image::DynamicImage::ImageRgba8(i.clone()).to_rgb8();
    // F2, then the first inspection chooses the line.
    lab.keys(&["F2"]);
    lab.idle();
    lab.x
        .xdotool(&["mousemove", "--window", &lab.window, "300", "150", "click", "1"]);
    view_said(1);
    assert!(lab.wait_title_contains("| VIEW phong.frag:17").contains("VIEW"));
    let probe = view::Probe::Line {
        file: file.clone(),
        line,
        name: None,
        stage: None,
    };
    let want = rgb(&library_view(lab_ref.as_mut(), &probe, (w, h)));
    let written = f12(1);
    lab.save(&written, "line_f12");
    want.save(lab.x.dir.join("line_library.png")).expect("saved");
    assert_eq!(written.dimensions(), want.dimensions());
    let db = psnr_of(&written, &want);
    println!("line view: F12 against the library: {db:.1} dB");
    assert!(db >= 50.0, "the window's line view is not the library's: {db:.1} dB");
    // F2 off: the screen shows the view itself (no inspector over it).
    lab.keys(&["F2"]);
    let shown = lab.settled();
    lab.save(&shown, "line_window");
    let db = psnr_of(&shown, &want);
    println!("line view: the window against the library: {db:.1} dB");
    assert!(db >= 40.0, "the window does not show the line view: {db:.1} dB");
    // A key moves the light: the view is drawn again, and it is the library's at the new state.
    for _ in 0..8 {
        lab_ref.input(shaderlab::lab::Input::Key('X'));
    }
    lab.key_n("X", 8);
    lab.idle();
    let moved = rgb(&library_view(lab_ref.as_mut(), &probe, (w, h)));
    assert_ne!(moved, want, "the light moved");
    let written = f12(2);
    let db = psnr_of(&written, &moved);
    println!("line view after X×8: F12 against the library: {db:.1} dB");
    assert!(db >= 50.0, "the line view did not follow the lab: {db:.1} dB");
    // F3: the cost view.
    let before = lab.said("view ");
    lab.keys(&["F3"]);
    view_said(before + 1);
    lab.wait_title_contains("| VIEW cost");
    let cost = rgb(&library_view(lab_ref.as_mut(), &view::Probe::Cost, (w, h)));
    let written = f12(3);
    lab.save(&written, "cost_f12");
    let db = psnr_of(&written, &cost);
    println!("cost view: F12 against the library: {db:.1} dB");
    assert!(db >= 50.0, "the window's cost view is not the library's: {db:.1} dB");
    // F3 again: the lab's picture, as a plain window shows it at that state.
    lab.keys(&["F3"]);
    let back = lab.settled();
    assert!(!lab.title().contains("VIEW"), "{}", lab.title());
    lab.save(&back, "back");
    assert!(psnr_of(&back, &cost) < 30.0, "the view is gone");
    assert_ne!(back, plain, "the light moved since the first picture");
    assert!(!lab.stderr().contains("view error"), "{}", lab.stderr());
    lab.escape();
}

/// With `--shaders DIR`, F4 compares the lab with its built-in shaders: the window
/// shows the library's diff picture of the same state (a bug planted in the copy's line 17
/// shows where it changes the picture), and a saved fix draws the diff again, now of two
/// equal pictures.
#[test]
fn f4_diffs_a_copy_against_the_built_in_shaders_and_follows_saved_shaders() {
    let x = Xvfb::start("view_diff");
    let (shaders, frag, original) = phong_shaders(&x);
    let planted = original.replacen("max(dot(N, L), 0.0)", "max(dot(N, L), 0.0) * 0.5", 1);
    assert_ne!(planted, original, "phong.frag changed: update this test");
    std::fs::write(&frag, &planted).expect("write phong.frag");
    let dir = shaders.to_str().expect("utf-8 path");
    let mut lab = x.launch("phong", &["--shaders", dir, "--set", "object=torus"], &[]);
    lab.first_frame();
    lab.idle();
    let (_, _, w, h) = lab.geometry();
    let library_diff = |copy: &str| -> RgbImage {
        let files = shaderlab::lab::UserFiles::default();
        let build = |source: shaderlab::shader::ShaderSource| {
            let cx =
                shaderlab::lab::BuildContext::new(common::gpu(), &source, shaderlab::offscreen::COLOR_FORMAT, &files);
            let mut lab = (course::find("phong").expect("phong").new)(&cx).expect("phong builds");
            lab.params_mut().set_str("object", "torus").expect("a torus");
            lab
        };
        let copy_dir = x.dir.join("library-copy");
        common::copy_shaders(&copy_dir);
        std::fs::write(copy_dir.join("phong.frag"), copy).expect("write the copy");
        let mut mine = build(shaderlab::shader::ShaderSource::Dir(copy_dir));
        let mut reference = build(shaderlab::shader::ShaderSource::Embedded);
        let diff = shaderlab::debug::diff::diff_labs(
            common::gpu(),
            "phong",
            mine.as_mut(),
            reference.as_mut(),
            (w, h - picture::LEGEND_HEIGHT),
        )
        .expect("the library diffs");
        image::DynamicImage::ImageRgba8(diff.picture).to_rgb8()
    };
    let f12 = |n: usize| -> RgbImage { image::open(lab.f12(n)).expect("a PNG").to_rgb8() };
    lab.keys(&["F4"]);
    poll(PATIENCE, || (lab.said("view ") >= 1).then_some(()))
        .unwrap_or_else(|| panic!("no view; stderr:\n{}", lab.stderr()));
    assert!(lab.said(&format!("view {w}x{h}")) == 1, "{}", lab.stderr());
    lab.wait_title_contains("| VIEW diff");
    let want = library_diff(&planted);
    let written = f12(1);
    lab.save(&written, "diff_planted");
    let db = psnr_of(&written, &want);
    println!("diff of the planted bug: F12 against the library: {db:.1} dB");
    assert!(db >= 50.0, "the window's diff is not the library's: {db:.1} dB");
    // The fix is saved: the lab reloads, and the diff is drawn again, of equal pictures.
    let compiles = lab.said("compile 1 ended");
    std::fs::write(&frag, &original).expect("write phong.frag");
    poll(PATIENCE, || (lab.said("compile 1 ended") > compiles).then_some(()))
        .unwrap_or_else(|| panic!("no reload; stderr:\n{}", lab.stderr()));
    poll(PATIENCE, || (lab.said("view ") >= 2).then_some(()))
        .unwrap_or_else(|| panic!("no second view; stderr:\n{}", lab.stderr()));
    lab.idle();
    let fixed = library_diff(&original);
    assert_ne!(fixed, want, "the fix changes the diff");
    let written = f12(2);
    let db = psnr_of(&written, &fixed);
    println!("diff after the fix: F12 against the library: {db:.1} dB");
    assert!(db >= 50.0, "the diff did not follow the saved shader: {db:.1} dB");
    assert!(!lab.stderr().contains("view error"), "{}", lab.stderr());
    lab.escape();
}
