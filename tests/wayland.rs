//! A window on Wayland: each test starts its own headless Weston (`weston
//! --backend=headless-backend.so --use-pixman`, its own socket and runtime folder), runs a lab
//! example with only `WAYLAND_DISPLAY` set, waits for the program's own signals
//! (`SHADERLAB_TEST_LOG`), and takes the compositor's screenshot (`weston-screenshooter`, which
//! Weston allows with `--debug`). Weston has no input a test can drive, so the F1 panel is opened
//! by `SHADERLAB_TEST_PANEL=1`. Needs `weston` (`scripts/install-deps` installs it); a missing
//! Weston is a failure, never a skip.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::{mpsc, Arc, Mutex};
use std::time::{Duration, Instant};

mod common;

use common::example;

/// How long a wait for a signal may take before the test calls it a hang.
const PATIENCE: Duration = Duration::from_secs(120);

fn test_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("target/tmp/wayland")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn private_dir(dir: &Path) -> PathBuf {
    use std::os::unix::fs::PermissionsExt;
    let runtime = dir.join("xdg");
    std::fs::create_dir_all(&runtime).unwrap();
    std::fs::set_permissions(&runtime, std::fs::Permissions::from_mode(0o700)).unwrap();
    runtime
}

fn poll<T>(limit: Duration, mut f: impl FnMut() -> Option<T>) -> Option<T> {
    let start = Instant::now();
    loop {
        if let Some(v) = f() {
            return Some(v);
        }
        if start.elapsed() > limit {
            return None;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// A headless Weston, stopped on drop.
struct Weston {
    child: Child,
    runtime: PathBuf,
    socket: String,
}

impl Weston {
    fn start(dir: &Path) -> Weston {
        let runtime = private_dir(dir);
        let socket = format!("shaderlab-{}", std::process::id());
        let child = Command::new("weston")
            .args([
                "--backend=headless-backend.so",
                "--use-pixman",
                "--debug",
                "--width=1024",
                "--height=768",
                "--idle-time=0",
            ])
            .arg(format!("--socket={socket}"))
            .env("XDG_RUNTIME_DIR", &runtime)
            .env_remove("DISPLAY")
            .env_remove("WAYLAND_DISPLAY")
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(std::fs::File::create(dir.join("weston.log")).unwrap())
            .spawn()
            .unwrap_or_else(|e| {
                panic!("cannot start weston ({e}); run scripts/install-deps (apt-get install -y weston)")
            });
        let weston = Weston { child, runtime, socket };
        let up = poll(PATIENCE, || weston.runtime.join(&weston.socket).exists().then_some(()));
        assert!(up.is_some(), "weston made no socket; its log:\n{}", weston.log(dir));
        weston
    }

    fn log(&self, dir: &Path) -> String {
        std::fs::read_to_string(dir.join("weston.log")).unwrap_or_default()
    }

    fn command(&self, program: &Path) -> Command {
        let mut c = Command::new(program);
        c.env("XDG_RUNTIME_DIR", &self.runtime)
            .env("WAYLAND_DISPLAY", &self.socket)
            .env_remove("DISPLAY")
            .env_remove("RUST_BACKTRACE");
        c
    }

    /// The compositor's whole output as a picture.
    fn screenshot(&self, dir: &Path) -> image::RgbaImage {
        let shots = dir.join("shots");
        let _ = std::fs::remove_dir_all(&shots);
        std::fs::create_dir_all(&shots).unwrap();
        let status = self
            .command(Path::new("weston-screenshooter"))
            .current_dir(&shots)
            .stdin(Stdio::null())
            .status()
            .expect("weston-screenshooter runs (apt-get install -y weston)");
        assert!(status.success(), "weston-screenshooter: {status}");
        let shot = std::fs::read_dir(&shots)
            .unwrap()
            .filter_map(|e| e.ok().map(|e| e.path()))
            .find(|p| p.extension().is_some_and(|e| e == "png"))
            .expect("weston-screenshooter wrote a PNG");
        let picture = image::open(&shot).expect("a PNG").to_rgba8();
        picture.save(dir.join("screen.png")).unwrap();
        picture
    }
}

impl Drop for Weston {
    fn drop(&mut self) {
        let _ = Command::new("kill")
            .args(["-TERM", &self.child.id().to_string()])
            .status();
        if poll(Duration::from_secs(5), || self.child.try_wait().ok().flatten()).is_none() {
            let _ = self.child.kill();
        }
        let _ = self.child.wait();
    }
}

/// The lines a child writes to stderr, gathered as they come.
fn gather(child: &mut Child) -> Arc<Mutex<Vec<String>>> {
    let lines = Arc::new(Mutex::new(Vec::new()));
    let into = lines.clone();
    let stderr = child.stderr.take().expect("stderr piped");
    std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            into.lock().unwrap().push(line);
        }
    });
    lines
}

#[test]
fn a_window_opens_on_wayland_draws_shows_the_panel_and_closes_cleanly() {
    let dir = test_dir("window");
    let weston = Weston::start(&dir);
    let mut lab = weston
        .command(&example("phong"))
        .current_dir(&dir)
        .env("SHADERLAB_TEST_LOG", "1")
        .env("SHADERLAB_TEST_PANEL", "1")
        .env("SHADERLAB_PRESENT", "shm")
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("phong starts");
    let lines = gather(&mut lab);
    let said = |what: &str| lines.lock().unwrap().iter().any(|l| l.contains(what));
    let drawn = poll(PATIENCE, || {
        if let Ok(Some(status)) = lab.try_wait() {
            panic!("phong ended ({status}) before drawing: {:?}", lines.lock().unwrap());
        }
        (said("shaderlab-test: frame 1") && said("shaderlab-test: idle")).then_some(())
    });
    assert!(drawn.is_some(), "no frame on Wayland: {:?}", lines.lock().unwrap());
    // The swapchain serves Wayland (the shared-memory presenter is X11's).
    assert!(
        said("presenting with the swapchain: not an X11 window"),
        "{:?}",
        lines.lock().unwrap()
    );

    let screen = weston.screenshot(&dir);
    // The teapot in phong's orange, and the panel's dark background beside it.
    let orange = screen
        .pixels()
        .filter(|p| p[0] > 200 && (60..200).contains(&p[1]) && p[2] < 60)
        .count();
    let panel = screen
        .pixels()
        .filter(|p| (20..=32).contains(&p[0]) && (20..=32).contains(&p[1]) && (20..=32).contains(&p[2]))
        .count();
    assert!(
        orange > 5_000,
        "{orange} orange pixels: is the teapot drawn? see {}",
        dir.display()
    );
    assert!(
        panel > 40_000,
        "{panel} panel pixels: is the panel shown? see {}",
        dir.display()
    );

    // SIGTERM ends the window through its own loop, and then the process as the signal asks
    // (src/fsutil/signals.rs: killed by SIGTERM, 143 in a shell), as on X11.
    let _ = Command::new("kill").args(["-TERM", &lab.id().to_string()]).status();
    let status = poll(PATIENCE, || lab.try_wait().ok().flatten()).expect("phong ends after SIGTERM");
    {
        use std::os::unix::process::ExitStatusExt;
        assert_eq!(
            status.signal(),
            Some(15),
            "phong ended with {status}, not by SIGTERM: {:?}",
            lines.lock().unwrap()
        );
    }
    let lines = lines.lock().unwrap();
    assert!(
        !lines.iter().any(|l| l.contains("panicked") || l.contains("error")),
        "{lines:?}"
    );
}

#[test]
fn a_wayland_display_that_is_not_there_is_one_clear_message() {
    let dir = test_dir("absent");
    let runtime = private_dir(&dir);
    let (tx, rx) = mpsc::channel();
    let mut command = Command::new(example("phong"));
    command
        .current_dir(&dir)
        .env("XDG_RUNTIME_DIR", &runtime)
        .env("WAYLAND_DISPLAY", "no-such-compositor")
        .env_remove("DISPLAY")
        .env_remove("RUST_BACKTRACE");
    std::thread::spawn(move || {
        let _ = tx.send(command.output());
    });
    let out = rx.recv_timeout(PATIENCE).expect("phong ends").expect("phong runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("cannot open a window on WAYLAND_DISPLAY=no-such-compositor"),
        "{err}"
    );
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(!err.contains("panicked") && !err.contains(".cargo"), "{err}");
    assert!(
        !dir.join("phong.png").exists(),
        "no screenshot instead of a window that failed"
    );
}
