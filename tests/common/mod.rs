//! Helpers shared by the GPU tests: one headless GPU per test binary, rendering a lab at a
//! state, and reference images.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use glam::Vec3;
use image::RgbImage;
use shaderlab::lab::{BuildContext, Input, Lab, LabEntry};
use shaderlab::offscreen::{to_rgb, COLOR_FORMAT};
use shaderlab::shader::ShaderSource;
use shaderlab::{Gpu, Object};

/// The shared headless GPU. No adapter is a failure, never a skip.
pub fn gpu() -> &'static Gpu {
    static GPU: OnceLock<Gpu> = OnceLock::new();
    GPU.get_or_init(|| match Gpu::headless() {
        Ok(gpu) => gpu,
        Err(e) => {
            panic!("GPU tests need an adapter (on Debian/Ubuntu: sudo apt-get install -y mesa-vulkan-drivers): {e}")
        }
    })
}

/// A lab under test, with the seed-000 shorthands the tests use.
pub struct TestLab {
    /// The lab.
    pub lab: Box<dyn Lab>,
    /// Where its shaders come from.
    pub source: ShaderSource,
    /// The target format it was built for.
    pub format: wgpu::TextureFormat,
}

impl TestLab {
    /// A key press; returns whether it changed anything.
    pub fn key(&mut self, c: char) -> bool {
        self.lab.input(Input::Key(c))
    }
    /// A left-button press at (x, y).
    pub fn mouse_press(&mut self, x: i32, y: i32) {
        self.lab.input(Input::Press(x, y));
    }
    /// A drag to (x, y).
    pub fn mouse_motion(&mut self, x: i32, y: i32) {
        self.lab.input(Input::Drag(x, y));
    }
    /// A parameter's values as f32.
    pub fn get(&self, name: &str) -> Option<Vec<f32>> {
        self.lab
            .params()
            .get(name)
            .map(|v| v.iter().map(|x| *x as f32).collect())
    }
    /// A parameter's value as text.
    pub fn text(&self, name: &str) -> String {
        self.lab.params().text(name)
    }
    /// Sets a parameter from f32 values.
    pub fn set(&mut self, name: &str, values: &[f32]) -> shaderlab::Result<()> {
        let v: Vec<f64> = values.iter().map(|x| f64::from(*x)).collect();
        self.lab.params_mut().set(name, &v)
    }
    /// Sets a parameter from text (`object=torus`).
    pub fn set_str(&mut self, name: &str, value: &str) -> shaderlab::Result<()> {
        self.lab.params_mut().set_str(name, value)
    }
    /// The object drawn.
    pub fn object(&self) -> Object {
        let name = self.text("object");
        Object::ALL.into_iter().find(|o| o.name() == name).expect("an object")
    }
    /// Chooses the object.
    pub fn set_object(&mut self, object: Object) {
        self.set_str("object", object.name()).expect("object");
    }
    /// xangle, yangle, zangle.
    pub fn angles(&self) -> Vec3 {
        let p = self.lab.params();
        Vec3::new(p.f("xangle"), p.f("yangle"), p.f("zangle"))
    }
    /// Sets xangle, yangle, zangle.
    pub fn set_angles(&mut self, a: [f32; 3]) {
        self.set("xangle", &[a[0]]).expect("xangle");
        self.set("yangle", &[a[1]]).expect("yangle");
        self.set("zangle", &[a[2]]).expect("zangle");
    }
    /// Sets the time, for labs that have one.
    pub fn set_time(&mut self, t: f64) {
        if self.lab.params().has("time") {
            self.lab.params_mut().set("time", &[t]).expect("time");
        }
    }
    /// Compiles the shaders again from the lab's source (live reload).
    pub fn reload(&mut self) -> shaderlab::Result<()> {
        let cx = BuildContext::new(gpu(), &self.source, self.format, &shaderlab::lab::NO_FILES);
        self.lab.reload(&cx)
    }
    /// Renders offscreen (RGBA).
    pub fn screenshot(&mut self, gpu: &Gpu, w: u32, h: u32) -> shaderlab::Result<image::RgbaImage> {
        shaderlab::shell::screenshot(gpu, self.lab.as_mut(), w, h)
    }
    /// Renders into an `Rgba32Float` target (the lab must be built for it, see [`lab_with`]) and
    /// returns the raw shader outputs, top row first.
    pub fn render_f32(&mut self, w: u32, h: u32) -> shaderlab::Result<Vec<[f32; 4]>> {
        let target = shaderlab::offscreen::Offscreen::with_format(gpu(), w, h, self.format);
        shaderlab::shell::render_into(gpu(), self.lab.as_mut(), &target)?;
        target.read_f32(gpu())
    }
    /// Renders offscreen (RGB).
    pub fn rgb(&mut self, w: u32, h: u32) -> RgbImage {
        to_rgb(&self.screenshot(gpu(), w, h).expect("screenshot"))
    }
}

/// A lab with the built-in shaders.
pub fn lab(entry: &LabEntry) -> TestLab {
    lab_from(entry, &ShaderSource::Embedded)
}

/// A lab with shaders from `source`.
pub fn lab_from(entry: &LabEntry, source: &ShaderSource) -> TestLab {
    lab_with(entry, source, COLOR_FORMAT)
}

/// A lab with shaders from `source`, built for targets of `format`.
pub fn lab_with(entry: &LabEntry, source: &ShaderSource, format: wgpu::TextureFormat) -> TestLab {
    let cx = BuildContext::new(gpu(), source, format, &shaderlab::lab::NO_FILES);
    TestLab {
        lab: (entry.new)(&cx).expect("lab builds"),
        source: source.clone(),
        format,
    }
}

/// Renders a seed-000 lab at an object, rotation and time, 640x360, with `--set`-style parameters.
pub fn render(entry: &LabEntry, object: Object, angles: [f32; 3], time: f32, set: &[(&str, &[f32])]) -> RgbImage {
    render_sized(entry, object, angles, time, set, 640, 360)
}

/// As [`render`] at any size.
pub fn render_sized(
    entry: &LabEntry,
    object: Object,
    angles: [f32; 3],
    time: f32,
    set: &[(&str, &[f32])],
    w: u32,
    h: u32,
) -> RgbImage {
    let mut lab = lab(entry);
    lab.set_object(object);
    lab.set_angles(angles);
    lab.set_time(f64::from(time));
    for (name, values) in set {
        lab.set(name, values).expect("parameter");
    }
    lab.rgb(w, h)
}

/// The directory of checked-in reference images.
pub fn reference_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/reference")
}

/// Loads a reference image; a missing one fails the test (never written silently).
pub fn reference(name: &str) -> RgbImage {
    let path = reference_dir().join(name);
    image::open(&path)
        .unwrap_or_else(|e| panic!("reference image {} missing or unreadable ({e}); references come from the original program and are never generated by the tests", path.display()))
        .to_rgb8()
}

/// Where tests write images for people to look at (`target/test-output/`).
pub fn output_dir() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/test-output");
    let _ = std::fs::create_dir_all(&dir);
    dir
}

/// `target/<profile>/examples/NAME`, built once per test binary with the test's own profile
/// (`cargo test --test X` alone does not build the examples, so a nested build makes sure they
/// are there and never stale; cargo releases its build lock while tests run).
pub fn example(name: &str) -> PathBuf {
    static BUILT: OnceLock<Result<PathBuf, String>> = OnceLock::new();
    let dir = BUILT.get_or_init(|| {
        // target/<profile>/deps/e2e_window-HASH -> target/<profile>/examples
        let exe = std::env::current_exe().map_err(|e| e.to_string())?;
        let profile_dir = exe
            .parent()
            .and_then(Path::parent)
            .ok_or_else(|| format!("cannot find the target directory from {}", exe.display()))?;
        if let Some(cargo) = std::env::var_os("CARGO") {
            let mut build = Command::new(cargo);
            build
                .current_dir(env!("CARGO_MANIFEST_DIR"))
                .args(["build", "--examples", "--quiet"]);
            if profile_dir.file_name().is_some_and(|n| n == "release") {
                build.arg("--release");
            }
            let status = build.status().map_err(|e| format!("cannot run cargo: {e}"))?;
            if !status.success() {
                return Err(format!("`cargo build --examples` failed ({status})"));
            }
        }
        Ok(profile_dir.join("examples"))
    });
    let path = match dir {
        Ok(dir) => dir.join(name),
        Err(e) => panic!("cannot build the examples: {e}"),
    };
    assert!(
        path.is_file(),
        "{} is missing: run `cargo build --release --examples`",
        path.display()
    );
    path
}

/// Writes a copy of every built-in shader (the contents of `shaders_glsl/`) into `dir`, creating
/// it, for tests that edit or break a shader and load it with `--shaders DIR`.
pub fn copy_shaders(dir: &Path) {
    std::fs::create_dir_all(dir).expect("create the shader directory");
    for name in shaderlab::shader::embedded_names() {
        let text = shaderlab::shader::embedded_source(name).expect("an embedded shader");
        std::fs::write(dir.join(name), text).expect("write a shader copy");
    }
}

/// A lab at its defaults, with the built-in shaders and data, as the shell holds it.
pub fn build(entry: &LabEntry) -> Box<dyn Lab> {
    lab(entry).lab
}

/// The browser build (`scripts/web` writes it into `target/web`); none is a failure saying how
/// to build it.
pub fn site() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/web");
    assert!(
        dir.join("index.html").is_file() && dir.join("web_bg.wasm").is_file(),
        "no site in {}: build it first with `scripts/web`",
        dir.display()
    );
    dir
}

/// The lab `name` drawn from `source` with the user's `files`, at the state `set` (as `--set`
/// takes it).
pub fn lab_at(
    name: &str,
    source: &ShaderSource,
    files: &shaderlab::lab::UserFiles,
    set: &[(&str, &str)],
) -> Box<dyn Lab> {
    let entry = shaderlab::course::find(name).expect("a lab");
    let cx = BuildContext::new(gpu(), source, COLOR_FORMAT, files);
    let mut lab = (entry.new)(&cx).unwrap_or_else(|e| panic!("{name} builds: {e}"));
    set_state(lab.as_mut(), set);
    lab
}

/// Sets `key=value` assignments as `--set` takes them (a state of SPEC on top of the defaults).
pub fn set_state(lab: &mut dyn Lab, state: &[(&str, &str)]) {
    for (key, value) in state {
        lab.params_mut()
            .set_str(key, value)
            .unwrap_or_else(|e| panic!("{}: {key}={value}: {e}", lab.info().name));
    }
}

/// One frame of `lab` at its default size.
pub fn shot(lab: &mut dyn Lab) -> RgbImage {
    let (w, h) = lab.info().size;
    to_rgb(&shaderlab::shell::screenshot(gpu(), lab, w, h).expect("screenshot"))
}

/// `entry` rendered at its default size at a state given as `key=value` assignments.
pub fn render_state(entry: &LabEntry, state: &[(&str, &str)]) -> RgbImage {
    let mut lab = build(entry);
    set_state(lab.as_mut(), state);
    shot(lab.as_mut())
}

/// An image of the original programs of seeds 001–004 (`tests/reference/seeds/NAME`, kept in the repository); a
/// missing one fails the test (they come from the reference renderer, never from the tests).
pub fn seed_reference(name: &str) -> RgbImage {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/reference/seeds")
        .join(name);
    image::open(&path)
        .unwrap_or_else(|e| {
            panic!(
                "reference {} missing or unreadable ({e}); references come from the original programs and are never written by the tests",
                path.display()
            )
        })
        .to_rgb8()
}

/// Runs `command` to its end, collecting its output, and also returns the CPU seconds (user +
/// system) the process and its threads used: a measure of work that a busy machine does not
/// inflate, unlike the wall clock, for tests that guard against slow (quadratic) paths.
pub fn output_with_cpu(command: &mut Command) -> (std::process::Output, f64) {
    let (output, usage) = output_with_usage(command);
    (output, usage.cpu)
}

/// What a child process used: CPU seconds (user + system) and its peak resident memory.
#[derive(Clone, Copy, Debug)]
pub struct Usage {
    /// CPU seconds, its threads' included.
    pub cpu: f64,
    /// Its peak resident set in kilobytes (0 where the system does not say).
    pub peak_kb: u64,
}

/// Runs `command` to its end as [`output_with_cpu`] does, and returns what it used.
// Waited for with wait4 (for its resource usage), which clippy does not see.
#[allow(clippy::zombie_processes)]
pub fn output_with_usage(command: &mut Command) -> (std::process::Output, Usage) {
    use std::io::Read;
    use std::process::Stdio;
    let mut child = command
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start the command");
    let read = |mut pipe: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            let _ = pipe.read_to_end(&mut bytes);
            bytes
        })
    };
    let stdout = read(Box::new(child.stdout.take().expect("piped")));
    let stderr = read(Box::new(child.stderr.take().expect("piped")));
    #[cfg(target_os = "linux")]
    let (status, usage) = {
        use std::os::unix::process::ExitStatusExt;
        let mut raw = 0;
        // SAFETY: a zeroed rusage for wait4 to fill; the pid is our own unwaited child.
        let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
        let pid = child.id() as libc::pid_t;
        // SAFETY: as above.
        let waited = unsafe { libc::wait4(pid, &mut raw, 0, &mut usage) };
        assert_eq!(waited, pid, "wait4: {}", std::io::Error::last_os_error());
        let seconds = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 / 1e6;
        (
            std::process::ExitStatus::from_raw(raw),
            Usage {
                cpu: seconds(usage.ru_utime) + seconds(usage.ru_stime),
                peak_kb: usage.ru_maxrss.max(0) as u64,
            },
        )
    };
    #[cfg(not(target_os = "linux"))]
    let (status, usage) = {
        let started = std::time::Instant::now();
        let status = child.wait().expect("wait");
        (
            status,
            Usage {
                cpu: started.elapsed().as_secs_f64(),
                peak_kb: 0,
            },
        )
    };
    let output = std::process::Output {
        status,
        stdout: stdout.join().expect("stdout reader"),
        stderr: stderr.join().expect("stderr reader"),
    };
    (output, usage)
}

/// Fails unless `SHADERLAB_WRITE_REFERENCES=1`: a test that writes files other tests read
/// (the snapshots, assets/uvgrid.bmp) runs only when its script asks, never beside the tests
/// that read them under `cargo test -- --include-ignored`.
pub fn require_write_opt_in(script: &str) {
    assert!(
        std::env::var_os("SHADERLAB_WRITE_REFERENCES").is_some_and(|v| v == "1"),
        "this test writes files other tests read, so it runs only when asked: run {script}, or \
         set SHADERLAB_WRITE_REFERENCES=1 and run it alone"
    );
}

/// The names in `dir`, sorted (to see that no temporary file was left behind).
pub fn names_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// `target/test-output/TAG`, made empty for one test.
pub fn fresh_dir(tag: &str) -> PathBuf {
    let dir = output_dir().join(tag);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("the test folder");
    dir
}

/// Runs `shaderlab ARGS` in `dir` to its end.
pub fn shaderlab_in(dir: &Path, args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_shaderlab"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("shaderlab runs")
}

/// A NumPy array as `--npy` writes it, read back: its shape and its float32 values, the header
/// checked as NumPy's format 1.0 says it.
pub fn parse_npy(bytes: &[u8]) -> (Vec<usize>, Vec<f32>) {
    assert_eq!(&bytes[..6], b"\x93NUMPY", "the magic");
    assert_eq!((bytes[6], bytes[7]), (1, 0), "version 1.0");
    let length = usize::from(u16::from_le_bytes([bytes[8], bytes[9]]));
    assert_eq!((10 + length) % 64, 0, "the header is padded to 64 bytes");
    let header = std::str::from_utf8(&bytes[10..10 + length]).expect("an ASCII header");
    assert!(header.ends_with('\n'), "{header:?}");
    assert!(header.contains("'descr': '<f4'"), "{header}");
    assert!(header.contains("'fortran_order': False"), "{header}");
    let shape = header
        .split("'shape': (")
        .nth(1)
        .and_then(|s| s.split(')').next())
        .expect("a shape");
    let shape: Vec<usize> = shape
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().expect("a dimension"))
        .collect();
    let data = &bytes[10 + length..];
    assert_eq!(data.len(), 4 * shape.iter().product::<usize>(), "{header}");
    let values = data
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    (shape, values)
}

/// What bash's completion function of `script` (`shaderlab completions bash`) offers for
/// `words` (the last one being completed), run in a bash subprocess.
pub fn bash_offers(script: &Path, words: &[&str]) -> Vec<String> {
    let quoted: Vec<String> = words.iter().map(|w| format!("'{w}'")).collect();
    let program = format!(
        "source '{}'\nCOMP_WORDS=({})\nCOMP_CWORD=$((${{#COMP_WORDS[@]}} - 1))\n\
         _shaderlab shaderlab \"${{COMP_WORDS[COMP_CWORD]}}\" \"${{COMP_WORDS[COMP_CWORD-1]}}\"\n\
         printf '%s\\n' \"${{COMPREPLY[@]}}\"\n",
        script.display(),
        quoted.join(" ")
    );
    let out = Command::new("bash")
        .current_dir(script.parent().unwrap_or(Path::new(".")))
        .arg("-c")
        .arg(&program)
        .output()
        .expect("bash runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(str::to_owned)
        .collect()
}
