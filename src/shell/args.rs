//! The command line of every example. Parameters are the lab's own (`--set NAME=VALUE`,
//! listed by `--help`); `--object`, `--rotate`, `--time`, `--shading`, `--tess`, `--camera`
//! and `--clear` are shorthands for the parameters of the same meaning, kept from seed 000's
//! command line. Positional `FILES...` go to the labs that declare them
//! ([`crate::params::FileArgs`]); any other lab rejects them as a usage error.

use std::path::PathBuf;

use clap::{CommandFactory, FromArgMatches, Parser};

use crate::error::Error;
use crate::lab::{LabEntry, UserFiles};
use crate::params::{parse_finite, parse_numbers, Params};
use crate::shader::ShaderSource;

/// Arguments of every example.
#[derive(Parser, Debug, Clone)]
#[command(version)]
pub struct Args {
    /// Files for labs that take them (e.g. legacy: VERT FRAG); other labs take none.
    #[arg(value_name = "FILES")]
    pub files: Vec<PathBuf>,
    /// Set a parameter by name, e.g. xangle=30, Ka=0.2, object=torus (repeatable; see PARAMETERS below).
    #[arg(long = "set", value_name = "NAME=VALUE", value_parser = parse_set, allow_hyphen_values = true)]
    pub set: Vec<(String, String)>,
    /// Render one frame offscreen (no window), write it to this PNG and exit.
    #[arg(long, value_name = "FILE.png")]
    pub screenshot: Option<PathBuf>,
    /// Render N frames offscreen, waiting for each, and print ms_per_frame.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=100_000), allow_negative_numbers = true)]
    pub bench: Option<u32>,
    /// With --bench: also time each frame on the GPU with timestamp queries (slower on CPU drivers).
    #[arg(long)]
    pub gpu_time: bool,
    /// Image or window size (default: the original's).
    #[arg(long, value_name = "WxH", value_parser = parse_size, allow_hyphen_values = true)]
    pub size: Option<(u32, u32)>,
    /// Read shaders from this directory instead of the built-in copies (same file names as shaders_glsl/).
    #[arg(long, value_name = "DIR")]
    pub shaders: Option<PathBuf>,
    /// Object to draw (the `object` parameter): cube, sphere, torus or teapot.
    #[arg(long, value_name = "NAME")]
    pub object: Option<String>,
    /// Rotation in degrees (the `xangle`, `yangle`, `zangle` parameters), applied as glRotatef X, then Y, then Z.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub rotate: Option<[f64; 3]>,
    /// The `time` parameter in seconds. Default: 0 offscreen, a clock in a window.
    #[arg(long, value_name = "T", value_parser = parse_time, allow_hyphen_values = true)]
    pub time: Option<f64>,
    /// Shading model (the `shading` parameter of labs that have one, e.g. phong: flat, gouraud, phong, blinn).
    #[arg(long, value_name = "NAME")]
    pub shading: Option<String>,
    /// Tessellation of sphere, torus and teapot (the `tess` parameter): a level from 3 to 512, or
    /// `auto` (smallest level with silhouette error under half a pixel). Default: GLUT's, as the
    /// original; `auto` with a port-only mode (`--shading` other than phong, `--set smooth=1`).
    #[arg(long, value_name = "N|auto", value_parser = parse_tess)]
    pub tess: Option<f64>,
    /// A Wavefront OBJ to draw instead of the lab's built-in model (the suzanne_* labs; others refuse it).
    #[arg(long, value_name = "FILE.obj")]
    pub model: Option<PathBuf>,
    /// A PNG or BMP picture to use instead of the lab's picture texture (suzanne_texture, suzanne_texture_color, texparams, legacy; others refuse it); `NAME=FILE` (repeatable) binds it to the texture called NAME in the lab's shaders (legacy).
    #[arg(long, value_name = "[NAME=]FILE", value_parser = parse_texture)]
    pub texture: Vec<TextureArg>,
    /// Eye position (the `camera` parameter of labs that have one, e.g. legacy).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub camera: Option<[f64; 3]>,
    /// Clear colour (the `clear` parameter of labs that have one, e.g. legacy).
    #[arg(long, value_name = "R,G,B", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub clear: Option<[f64; 3]>,
    /// Record frames offscreen at a fixed time step (frame k at time FROM + k/FPS) into NAME.gif,
    /// NAME.mp4 or NAME.webm (through ffmpeg), a PNG sequence (frames-%04d.png) or a directory.
    #[arg(long, value_name = "OUT", requires = "frames", conflicts_with_all = ["screenshot", "bench"])]
    pub record: Option<PathBuf>,
    /// With --record: how many frames.
    #[arg(long, value_name = "N", requires = "record", value_parser = clap::value_parser!(u32).range(1..=i64::from(super::record::MAX_FRAMES)), allow_negative_numbers = true)]
    pub frames: Option<u32>,
    /// With --record: frames per second of lab time (default 25, which GIF's 1/100 s delays hold exactly).
    #[arg(long, value_name = "F", requires = "record", value_parser = parse_fps, allow_hyphen_values = true)]
    pub fps: Option<f64>,
    /// With --record: the lab time of the first frame, in seconds (default: the `time` parameter).
    #[arg(long, value_name = "T", requires = "record", value_parser = parse_time, allow_hyphen_values = true)]
    pub from: Option<f64>,
    /// The watchdog: a frame the GPU has not finished after this many seconds ends the run (a
    /// shader that never ends) with a message; in a window the title says so. 0: no limit.
    #[arg(long, value_name = "SECONDS", default_value_t = crate::gpu::WATCHDOG.as_secs_f64(), value_parser = parse_timeout, allow_hyphen_values = true)]
    pub timeout: f64,
    /// In a window: draw as fast as possible (present mode Immediate, no pacing), to measure frame time.
    #[arg(long)]
    pub unpaced: bool,
    /// Explain pixel X,Y (column, row from the top left, as in --screenshot's PNG): which
    /// triangle covers it, the vertex shader at its corners, the interpolated inputs, the
    /// fragment shader line by line with every value, and the stored colour. No window.
    #[arg(long, value_name = "X,Y", value_parser = parse_pixel, allow_hyphen_values = true, conflicts_with_all = ["record", "bench"])]
    pub debug: Option<(u32, u32)>,
    /// With --debug: print one JSON object (pixel, covered, trace, ...) instead of the text;
    /// with --line or --cost: the view's summary (range, counts) as one JSON object.
    #[arg(long)]
    pub json: bool,
    /// Show, at every pixel, the value line LINE of FILE (a shader file of the lab, by its name)
    /// assigns, drawn on the GPU: written to --screenshot's PNG (default NAME-view.png) with a
    /// legend, to --npy's array, or timed with --bench. No window.
    #[arg(long, value_name = "FILE:LINE", value_parser = parse_line, conflicts_with_all = ["record", "debug", "cost", "diff"])]
    pub line: Option<(String, u32)>,
    /// With --line: the name to show, where the line assigns more than one thing.
    #[arg(long, value_name = "VAR", requires = "line")]
    pub name: Option<String>,
    /// With --line: the stage (vertex or fragment), where both shaders include the file.
    #[arg(long, value_name = "STAGE", value_parser = ["vertex", "fragment"], requires = "line")]
    pub stage: Option<String>,
    /// Show, at every pixel, how many statements the fragment shader ran there (the count
    /// the debugger reports as `cost` for a pixel), drawn on the GPU; outputs as --line's.
    #[arg(long, conflicts_with_all = ["record", "debug", "diff"])]
    pub cost: bool,
    /// With --line or --cost: also write the raw values as a NumPy array (height x width x
    /// components, float32; NaN where the line did not run or no fragment ran).
    #[arg(long, value_name = "FILE.npy")]
    pub npy: Option<PathBuf>,
    /// Compare with the copy of the shaders in DIR, as `shaderlab diff NAME --shaders DIR`:
    /// PSNR, the pixels that differ, the worst one and the first line whose value departs
    /// (the picture of the difference to --screenshot; --json for one JSON object).
    #[arg(long, value_name = "DIR", conflicts_with_all = ["record", "debug", "bench", "shaders"])]
    pub diff: Option<PathBuf>,
    /// The flag the pixel was given with, for messages.
    #[arg(skip)]
    pub pixel_flag: PixelFlag,
    /// The flags typed on the command line, by clap's id (the field's name): a flag that does
    /// nothing where it is given is refused ([`super::verbs::check`]).
    #[arg(skip)]
    pub given: Vec<String>,
}

/// How a command line names the pixel to explain: a lab's `--debug X,Y`, or `shaderlab debug`'s
/// `--pixel X,Y`. Messages about the pixel name the flag the user typed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PixelFlag {
    /// `--debug X,Y` (a lab's command line, `shaderlab run`).
    #[default]
    Debug,
    /// `--pixel X,Y` (`shaderlab debug NAME`).
    Pixel,
}

impl PixelFlag {
    /// The flag as typed: `--debug` or `--pixel`.
    pub fn flag(self) -> &'static str {
        match self {
            PixelFlag::Debug => "--debug",
            PixelFlag::Pixel => "--pixel",
        }
    }

    /// The lab's command line with the pixel's flag named so.
    pub(super) fn apply(self, command: clap::Command) -> clap::Command {
        match self {
            PixelFlag::Debug => command,
            PixelFlag::Pixel => command.mut_arg("debug", |a| a.long("pixel")).mut_arg("json", |a| {
                a.help("With --pixel: print one JSON object (pixel, covered, trace, ...) instead of the text.")
            }),
        }
    }
}

/// One `--texture`: a picture for the lab's texture, or for the texture called `name`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TextureArg {
    /// `NAME` of `NAME=FILE`.
    pub name: Option<String>,
    /// The picture.
    pub path: PathBuf,
}

fn parse_texture(s: &str) -> Result<TextureArg, String> {
    let identifier = |n: &str| {
        n.chars().next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
            && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
    };
    match s.split_once('=') {
        Some((name, path)) if identifier(name) => {
            if path.is_empty() {
                return Err(format!("`{s}`: expected NAME=FILE"));
            }
            Ok(TextureArg {
                name: Some(name.to_owned()),
                path: PathBuf::from(path),
            })
        }
        _ => Ok(TextureArg {
            name: None,
            path: PathBuf::from(s),
        }),
    }
}

fn parse_timeout(s: &str) -> Result<f64, String> {
    match parse_finite(s) {
        Ok(t) if (0.0..=86_400.0).contains(&t) => Ok(t),
        _ => Err(format!("`{s}`: expected seconds from 0 (no limit) to 86400")),
    }
}

fn parse_time(s: &str) -> Result<f64, String> {
    parse_finite(s)
}

fn parse_fps(s: &str) -> Result<f64, String> {
    match parse_finite(s)? {
        f if (0.01..=1000.0).contains(&f) => Ok(f),
        _ => Err(format!("`{s}`: expected frames per second from 0.01 to 1000")),
    }
}

fn parse_tess(s: &str) -> Result<f64, String> {
    if s == "auto" {
        return Ok(-1.0);
    }
    match s.parse::<u32>() {
        Ok(n) if (crate::mesh::tess::MIN_LEVEL..=crate::mesh::tess::MAX_LEVEL).contains(&n) => Ok(f64::from(n)),
        _ => Err(format!("`{s}`: expected `auto` or a level from 3 to 512")),
    }
}

fn parse_vec3(s: &str) -> Result<[f64; 3], String> {
    match parse_numbers(s)?.as_slice() {
        [x, y, z] => Ok([*x, *y, *z]),
        _ => Err(format!("`{s}`: expected three numbers X,Y,Z")),
    }
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("`{s}`: expected WxH with each side between 1 and 8192, e.g. 640x360");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let (w, h) = (
        w.trim().parse::<u32>().map_err(|_| bad())?,
        h.trim().parse::<u32>().map_err(|_| bad())?,
    );
    if !(1..=8192).contains(&w) || !(1..=8192).contains(&h) {
        return Err(bad());
    }
    Ok((w, h))
}

/// `X,Y`: two whole numbers of digits only. A sign is refused (`+5,+6` reads like an offset
/// from somewhere, and `u32`'s own parser would take it).
fn parse_pixel(s: &str) -> Result<(u32, u32), String> {
    let bad = || {
        format!(
            "`{s}`: expected X,Y, two whole numbers without a sign (column and row from the top left, e.g. 320,180)"
        )
    };
    let number = |t: &str| {
        let t = t.trim();
        if t.is_empty() || !t.bytes().all(|b| b.is_ascii_digit()) {
            return Err(bad());
        }
        t.parse::<u32>().map_err(|_| bad())
    };
    let (x, y) = s.split_once(',').ok_or_else(bad)?;
    Ok((number(x)?, number(y)?))
}

/// `FILE:LINE`: a file name (any text, `:` included) and a 1-based line after the last `:`.
fn parse_line(s: &str) -> Result<(String, u32), String> {
    let bad = || format!("`{s}`: expected FILE:LINE, a shader file of the lab and a line from 1, e.g. phong.frag:17");
    let (file, line) = s.rsplit_once(':').ok_or_else(bad)?;
    let line = line.trim();
    if file.is_empty() || line.is_empty() || !line.bytes().all(|b| b.is_ascii_digit()) {
        return Err(bad());
    }
    match line.parse::<u32>() {
        Ok(n) if n >= 1 => Ok((file.to_owned(), n)),
        _ => Err(bad()),
    }
}

fn parse_set(s: &str) -> Result<(String, String), String> {
    let (name, value) = s
        .split_once('=')
        .ok_or_else(|| format!("`{s}`: expected NAME=VALUE, e.g. xangle=30"))?;
    Ok((name.trim().to_owned(), value.trim().to_owned()))
}

impl Args {
    /// Parses the process arguments for `entry`; prints usage and exits 2 on a bad flag.
    pub fn parse_for(entry: &LabEntry) -> Self {
        Self::parse_from_for(entry, std::env::args_os().collect())
    }

    /// Parses `argv` (program name first) for `entry`, as [`Args::parse_for`] does.
    pub fn parse_from_for(entry: &LabEntry, argv: Vec<std::ffi::OsString>) -> Self {
        Self::parse_with(entry, argv, PixelFlag::Debug)
    }

    /// Parses `shaderlab debug NAME`'s `argv` (program name first) for `entry`: the lab's flags,
    /// with the pixel given as `--pixel X,Y` instead of `--debug X,Y` (and named so in help and
    /// in every message).
    pub fn parse_debug_command(entry: &LabEntry, argv: Vec<std::ffi::OsString>) -> Self {
        Self::parse_with(entry, argv, PixelFlag::Pixel)
    }

    fn parse_with(entry: &LabEntry, argv: Vec<std::ffi::OsString>, pixel_flag: PixelFlag) -> Self {
        let info = entry.info;
        let mut params = (entry.params)();
        let (w, h) = info.size;
        let file_args = params.file_args();
        if file_args.is_some() {
            // List the parameters the files on the command line declare (those of the lab's
            // built-in files without any); a file that does not load is reported after parsing.
            let prescan = pixel_flag
                .apply(Args::command())
                .disable_help_flag(true)
                .disable_version_flag(true)
                .ignore_errors(true);
            let files = prescan
                .try_get_matches_from(argv.clone())
                .ok()
                .and_then(|m| Args::from_arg_matches(&m).ok())
                .map(|a| a.files)
                .unwrap_or_default();
            let mut declared = params.clone();
            if declared.declare_files(&files).is_ok() {
                params = declared;
            }
        }
        let after = format!(
            "PARAMETERS (--set NAME=VALUE):\n{}\nKEYS AND MOUSE:\n  {}\n  F1 shows the parameter panel, F2 inspects a pixel (click one: why it has its colour, line by line; click a line of its listing: that line's value at every pixel), F3 shows the cost view, F4 the diff against the built-in shaders, F10 starts/stops recording a GIF, F12 saves a screenshot, Esc quits; shaders edited under --shaders DIR (or shaders_glsl/) reload live.\n\nDefault size {w}x{h}.",
            params.help(),
            info.keys.help().replace('\n', "\n  ")
        );
        let command = Args::command()
            .name(info.name)
            .about(format!(
                "{} {} ({}), on wgpu",
                info.original_title, info.label, info.lecture
            ))
            .after_help(after)
            .mut_arg("files", |a| match file_args {
                Some(f) => a.value_names(f.names.iter().copied()).num_args(0..=f.names.len()),
                None => a.hide(true),
            });
        let matches = super::cli::parse_command_line(pixel_flag.apply(command), argv);
        let args = Args::from_arg_matches(&matches).unwrap_or_else(|e| super::cli::exit_on_clap_error(info.name, e));
        let given = matches
            .ids()
            .filter(|id| matches.value_source(id.as_str()) == Some(clap::parser::ValueSource::CommandLine))
            .map(|id| id.as_str().to_owned())
            .collect();
        Args {
            pixel_flag,
            given,
            ..args
        }
    }

    /// The watchdog `--timeout` asks for ([`crate::gpu::Gpu::watchdog`]).
    pub fn watchdog(&self) -> Option<std::time::Duration> {
        (self.timeout > 0.0).then(|| std::time::Duration::from_secs_f64(self.timeout))
    }

    /// The shader source chosen by `--shaders` (built-in copies otherwise).
    pub fn shader_source(&self) -> Result<ShaderSource, Error> {
        match &self.shaders {
            Some(dir) => ShaderSource::dir(dir),
            None => Ok(ShaderSource::Embedded),
        }
    }

    /// Reads and checks `--model` and `--texture` (errors name the file), printing the model's
    /// notices (missing `vt`/`vn`, ignored elements) on stderr, one line each; the positional
    /// files go along as paths.
    pub fn files(&self, entry: &LabEntry) -> Result<UserFiles, Error> {
        self.check_files_taken(entry)?;
        let mut plain = self.texture.iter().filter(|t| t.name.is_none());
        let texture = plain.next().map(|t| t.path.as_path());
        if let Some(second) = plain.next() {
            return Err(Error::Param(format!(
                "`--texture {}`: one texture without a NAME= is taken; name the others (NAME=FILE)",
                second.path.display()
            )));
        }
        let mut files = UserFiles::load(self.model.as_deref(), texture)?;
        let named: Vec<(String, PathBuf)> = self
            .texture
            .iter()
            .filter_map(|t| t.name.clone().map(|n| (n, t.path.clone())))
            .collect();
        files.load_named_textures(&named)?;
        files.inputs = self.files.clone();
        for notice in files.model.iter().flat_map(|m| &m.data.notices) {
            eprintln!("{}: {notice}", entry.info.name);
        }
        Ok(files)
    }

    /// Refuses `--model` and `--texture` for a lab that draws no such file (as a usage error,
    /// before the file is read), naming the labs that do.
    fn check_files_taken(&self, entry: &LabEntry) -> Result<(), Error> {
        let name = entry.info.name;
        let taken = entry.info.files;
        let those = |which: fn(crate::lab::FilesTaken) -> bool| {
            let names: Vec<&str> = crate::course::ALL
                .iter()
                .filter(|e| which(e.info.files))
                .map(|e| e.info.name)
                .collect();
            names.join(", ")
        };
        if let Some(model) = &self.model {
            if !taken.model {
                return Err(Error::Param(format!(
                    "`--model {}`: {name} draws no model from a file (the labs that do: {})",
                    model.display(),
                    those(|t| t.model)
                )));
            }
        }
        for texture in &self.texture {
            let ok = match texture.name {
                Some(_) => taken.named_textures,
                None => taken.texture,
            };
            if ok {
                continue;
            }
            let arg = match &texture.name {
                Some(n) => format!("{n}={}", texture.path.display()),
                None => texture.path.display().to_string(),
            };
            return Err(Error::Param(if taken.texture {
                format!("`--texture {arg}`: {name} takes one picture, --texture FILE, without a NAME= (the labs that bind textures by name: {})", those(|t| t.named_textures))
            } else {
                format!(
                    "`--texture {arg}`: {name} samples no picture from a file (the labs that do: {})",
                    those(|t| t.texture)
                )
            }));
        }
        Ok(())
    }

    /// The image or window size.
    pub fn size(&self, entry: &LabEntry) -> (u32, u32) {
        self.size.unwrap_or(entry.info.size)
    }

    /// The lab's parameters with the command line applied; usage errors name the lab.
    pub fn params(&self, entry: &LabEntry) -> Result<Params, Error> {
        let name = entry.info.name;
        let mut p = (entry.params)();
        // The files a lab takes declare parameters of their own (e.g. a shader's uniforms).
        p.declare_files(&self.files)?;
        let missing = |flag: &str, what: &str| Error::Param(format!("`{flag}`: {name} has no {what}"));
        if let Some(object) = &self.object {
            if !p.has("object") {
                return Err(missing("--object", "objects to choose from"));
            }
            p.set_str("object", object)?;
        }
        if let Some([x, y, z]) = self.rotate {
            for (axis, v) in [("xangle", x), ("yangle", y), ("zangle", z)] {
                if p.has(axis) {
                    p.set(axis, &[v])?;
                } else if v != 0.0 {
                    return Err(missing("--rotate", &format!("`{axis}` parameter")));
                }
            }
        }
        if let Some(t) = self.time {
            // Labs without a clock ignore it, as seed 000's labs without noise always did.
            if p.has("time") {
                p.set("time", &[t])?;
            }
        }
        if let Some(shading) = &self.shading {
            if !p.has("shading") {
                return Err(missing("--shading", "shading models (no `shading` parameter)"));
            }
            p.set_str("shading", shading)?;
        }
        for (flag, param, value) in [("--camera", "camera", self.camera), ("--clear", "clear", self.clear)] {
            if let Some(v) = value {
                if !p.has(param) {
                    return Err(missing(flag, &format!("`{param}` parameter")));
                }
                p.set(param, &v)?;
            }
        }
        if let Some(tess) = self.tess {
            if !p.has("tess") {
                return Err(missing("--tess", "tessellated objects (no `tess` parameter)"));
            }
            if tess < 0.0 {
                // `--tess auto`: the lab's own automatic level, where it has one.
                // Seed 000's labs say it with -1.
                let spec = p.specs().iter().find(|s| s.name == "tess").copied();
                match spec {
                    Some(spec) if spec.auto.is_some() => p.set_str("tess", "auto")?,
                    Some(spec) if spec.min <= tess => p.set("tess", &[tess])?,
                    Some(spec) => {
                        return Err(Error::Param(format!(
                            "`--tess auto`: {name} has no automatic level; give one from {} to {}",
                            crate::params::bound_text(spec.min),
                            crate::params::bound_text(spec.max)
                        )))
                    }
                    None => {}
                }
            } else {
                p.set("tess", &[tess])?;
            }
        }
        for (key, value) in &self.set {
            if !p.has(key) {
                let valid: Vec<&str> = p.specs().iter().map(|s| s.name).collect();
                return Err(Error::Param(format!(
                    "unknown parameter `{key}` for {name}; valid: {}",
                    valid.join(", ")
                )));
            }
            p.set_str(key, value)?;
        }
        p.check()?;
        Ok(p)
    }
}
