//! Where each of the labs' flags does something. A run of a lab is in one [`Mode`] (a window,
//! one picture, a benchmark, a recording, a pixel explained, a view, a comparison), set by its
//! verb and flags; one table ([`USES`]) says in which modes each flag of [`Args`] does
//! something. A flag given where it does nothing is a usage error that says why ([`check`]),
//! and each verb of `shaderlab` offers, completes and documents the flags that do something in
//! one of its modes ([`Verb::takes`]), so the refusals, the completion scripts and the manual
//! pages read the same table.

use super::args::Args;
use crate::error::Error;
use crate::lab::LabEntry;

/// What a run of a lab does, from its verb and flags.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// A window: no flag that draws offscreen.
    Window,
    /// One picture: `--screenshot` alone.
    Screenshot,
    /// `--bench N` (with or without `--screenshot`).
    Bench,
    /// `--record OUT`, `shaderlab record`.
    Record,
    /// `--debug X,Y`, `shaderlab debug --pixel X,Y`.
    Debug,
    /// A line's view: `--line FILE:LINE`.
    Line,
    /// The cost view: `--cost`.
    Cost,
    /// A comparison: `--diff DIR`, `shaderlab diff`.
    Diff,
    /// Comparisons across the lab's states: `shaderlab check`.
    Check,
}

impl Mode {
    /// Every mode.
    pub const ALL: &'static [Mode] = &[
        Mode::Window,
        Mode::Screenshot,
        Mode::Bench,
        Mode::Record,
        Mode::Debug,
        Mode::Line,
        Mode::Cost,
        Mode::Diff,
        Mode::Check,
    ];

    /// The modes of a run that draws one lab's frame, not a comparison (`legacy`, `open`).
    pub const DRAWING: &'static [Mode] = &[
        Mode::Window,
        Mode::Screenshot,
        Mode::Bench,
        Mode::Record,
        Mode::Debug,
        Mode::Line,
        Mode::Cost,
    ];

    /// The modes of `shaderlab run`: a frame, or a comparison at one state (`--diff DIR`).
    pub const RUN: &'static [Mode] = &[
        Mode::Window,
        Mode::Screenshot,
        Mode::Bench,
        Mode::Record,
        Mode::Debug,
        Mode::Line,
        Mode::Cost,
        Mode::Diff,
    ];

    /// The mode `args` ask for (`shaderlab diff`, whose copy is `--shaders`, is [`Mode::Diff`]
    /// by its verb).
    pub fn of(args: &Args) -> Mode {
        if args.record.is_some() {
            Mode::Record
        } else if args.debug.is_some() {
            Mode::Debug
        } else if args.diff.is_some() {
            Mode::Diff
        } else if args.line.is_some() {
            Mode::Line
        } else if args.cost {
            Mode::Cost
        } else if args.bench.is_some() {
            Mode::Bench
        } else if args.screenshot.is_some() {
            Mode::Screenshot
        } else {
            Mode::Window
        }
    }

    /// Where a flag does nothing, in a message's words.
    fn here(self, args: &Args) -> String {
        match self {
            Mode::Window => "in a window".into(),
            Mode::Screenshot => "with --screenshot".into(),
            Mode::Bench => "with --bench".into(),
            Mode::Record => "in a recording".into(),
            Mode::Debug => format!("with {}", args.pixel_flag.flag()),
            Mode::Line => "in a line's view (--line)".into(),
            Mode::Cost => "in a cost view (--cost)".into(),
            Mode::Diff => "in a comparison (shaderlab diff)".into(),
            Mode::Check => "in a check across states (shaderlab check)".into(),
        }
    }

    /// Whether a run in this mode can take one more flag (`shaderlab run NAME` with no view,
    /// recording, pixel or comparison), so that a message may say which to add.
    fn plain(self) -> bool {
        matches!(self, Mode::Window | Mode::Screenshot | Mode::Bench)
    }
}

/// Where one of the labs' flags does something, and what it does.
pub struct Use {
    /// The flag's id in [`Args`] (clap's: the field's name).
    pub id: &'static str,
    /// The modes in which it does something.
    pub modes: &'static [Mode],
    /// What it does, as a refusal says it: "`--FLAG` {what}, and does nothing {here}".
    what: &'static str,
    /// What to add for it to do something, in a plain run ([`Mode::plain`]); `NAME` is the lab.
    add: &'static str,
}

/// The scene: what every mode draws, so these flags do something in all of them.
const SCENE: &[&str] = &[
    "files", "set", "size", "shaders", "object", "rotate", "time", "shading", "tess", "model", "texture", "camera",
    "clear", "timeout",
];

/// Where each of the labs' flags other than the scene's ([`SCENE`]) does something.
pub const USES: &[Use] = &[
    Use {
        id: "screenshot",
        modes: &[
            Mode::Screenshot,
            Mode::Bench,
            Mode::Debug,
            Mode::Line,
            Mode::Cost,
            Mode::Diff,
        ],
        what: "writes a picture",
        add: "",
    },
    Use {
        id: "bench",
        modes: &[Mode::Bench, Mode::Line, Mode::Cost],
        what: "times frames",
        add: "",
    },
    Use {
        id: "gpu_time",
        modes: &[Mode::Bench],
        what: "times the frames of --bench N on the GPU (the plain frame's pass, without a view)",
        add: "add --bench N",
    },
    Use {
        id: "record",
        modes: &[Mode::Record],
        what: "records frames",
        add: "",
    },
    Use {
        id: "frames",
        modes: &[Mode::Record],
        what: "is for recordings",
        add: "add --record OUT (or run `shaderlab record NAME OUT …`)",
    },
    Use {
        id: "fps",
        modes: &[Mode::Record],
        what: "is for recordings",
        add: "add --record OUT (or run `shaderlab record NAME OUT …`)",
    },
    Use {
        id: "from",
        modes: &[Mode::Record],
        what: "is for recordings",
        add: "add --record OUT (or run `shaderlab record NAME OUT …`)",
    },
    Use {
        id: "unpaced",
        modes: &[Mode::Window],
        what: "paces the frames of a window",
        add: "",
    },
    Use {
        id: "debug",
        modes: &[Mode::Debug],
        what: "explains a pixel",
        add: "",
    },
    Use {
        id: "json",
        modes: &[Mode::Debug, Mode::Line, Mode::Cost, Mode::Diff, Mode::Check],
        what: "goes with --debug X,Y, --line FILE:LINE, --cost or --diff DIR",
        add: "",
    },
    Use {
        id: "line",
        modes: &[Mode::Line],
        what: "shows a line's value",
        add: "",
    },
    Use {
        id: "name",
        modes: &[Mode::Line],
        what: "chooses the name that --line FILE:LINE shows",
        add: "add --line FILE:LINE",
    },
    Use {
        id: "stage",
        modes: &[Mode::Line],
        what: "chooses the stage of --line FILE:LINE",
        add: "add --line FILE:LINE",
    },
    Use {
        id: "cost",
        modes: &[Mode::Cost],
        what: "shows the statements run",
        add: "",
    },
    Use {
        id: "npy",
        modes: &[Mode::Line, Mode::Cost],
        what: "writes a view's values",
        add: "add --line FILE:LINE or --cost",
    },
    Use {
        id: "diff",
        modes: &[Mode::Diff],
        what: "compares a copy of the shaders",
        add: "",
    },
];

/// The modes in which the flag `id` does something (every mode for the scene's flags; none for
/// an id of no flag).
pub fn modes_of(id: &str) -> &'static [Mode] {
    if SCENE.contains(&id) {
        return Mode::ALL;
    }
    USES.iter().find(|u| u.id == id).map_or(&[], |u| u.modes)
}

/// Whether the lab draws the shader files its command line names (legacy: VERT FRAG) rather
/// than its own shaders, read from `--shaders DIR` or built in.
pub fn draws_named_files(entry: &LabEntry) -> bool {
    (entry.params)().file_args().is_some()
}

/// Refuses a flag given where it does nothing, in `mode` (for `args`, the flags typed:
/// [`Args::given`]), with a message that says what the flag does and, in a plain run, what to
/// add; and, for a lab that draws the files it is given (legacy), `--shaders` and `--diff`.
pub fn check(entry: &LabEntry, args: &Args, mode: Mode) -> Result<(), Error> {
    let name = entry.info.name;
    if draws_named_files(entry) {
        if args.given.iter().any(|g| g == "shaders") {
            let instead = if matches!(mode, Mode::Diff | Mode::Check) {
                let verb = if mode == Mode::Check { "check" } else { "diff" };
                format!(
                    "name the pair to compare against with `shaderlab {verb} {name} VERT FRAG --reference VERT0 FRAG0`"
                )
            } else {
                "give your files as VERT FRAG".into()
            };
            return Err(Error::Param(format!(
                "`--shaders` reads a lab's shaders from a folder, and does nothing for {name}, which draws the pair VERT FRAG: {instead}"
            )));
        }
        if args.given.iter().any(|g| g == "diff") {
            return Err(Error::Param(format!(
                "`--diff` compares a copy of a lab's built-in shaders, and does nothing for {name}, which draws the pair VERT FRAG: compare two pairs with `shaderlab diff {name} VERT FRAG --reference VERT0 FRAG0`"
            )));
        }
    }
    for id in &args.given {
        let Some(rule) = USES.iter().find(|u| u.id == id) else {
            continue;
        };
        if rule.modes.contains(&mode) {
            continue;
        }
        let flag = if rule.id == "debug" {
            args.pixel_flag.flag().to_owned()
        } else {
            format!("--{}", rule.id.replace('_', "-"))
        };
        let add = if mode.plain() && !rule.add.is_empty() {
            format!(": {}", rule.add.replace("NAME", name))
        } else {
            String::new()
        };
        return Err(Error::Param(format!(
            "`{flag}` {}, and does nothing {}{add}",
            rule.what,
            mode.here(args)
        )));
    }
    Ok(())
}

/// The verbs of `shaderlab` that draw a lab.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verb {
    /// `shaderlab run NAME`: every mode.
    Run,
    /// `shaderlab record NAME OUT`.
    Record,
    /// `shaderlab legacy VERT FRAG`: every mode but a comparison.
    Legacy,
    /// `shaderlab debug NAME --pixel X,Y`.
    Debug,
    /// `shaderlab diff NAME --shaders DIR`.
    Diff,
    /// `shaderlab view NAME --line FILE:LINE | --cost`.
    View,
    /// `shaderlab check NAME --shaders DIR`.
    Check,
    /// `shaderlab open LINK`: a link's files written into a folder, then every mode but a
    /// comparison, as `run` from that folder.
    Open,
}

impl Verb {
    /// Every verb that draws a lab.
    pub const ALL: &'static [Verb] = &[
        Verb::Run,
        Verb::Record,
        Verb::Legacy,
        Verb::Debug,
        Verb::Diff,
        Verb::View,
        Verb::Check,
        Verb::Open,
    ];

    /// The verb as typed.
    pub fn name(self) -> &'static str {
        match self {
            Verb::Run => "run",
            Verb::Record => "record",
            Verb::Legacy => "legacy",
            Verb::Debug => "debug",
            Verb::Diff => "diff",
            Verb::View => "view",
            Verb::Check => "check",
            Verb::Open => "open",
        }
    }

    /// The modes a run of the verb can be in.
    pub fn modes(self) -> &'static [Mode] {
        match self {
            Verb::Run => Mode::RUN,
            Verb::Record => &[Mode::Record],
            Verb::Legacy => Mode::DRAWING,
            Verb::Debug => &[Mode::Debug],
            Verb::Diff => &[Mode::Diff],
            Verb::View => &[Mode::Line, Mode::Cost],
            Verb::Check => &[Mode::Check],
            Verb::Open => Mode::DRAWING,
        }
    }

    /// Whether the verb takes the labs' flag `id` (clap's id in [`Args`]): it does something
    /// in one of the verb's modes, and the verb does not give it another way (`record`'s OUT,
    /// `diff`'s own `--out` and its copy as `--shaders`, the pair legacy draws instead of
    /// `--shaders`, the folder `open` writes instead of `--shaders`). `debug` takes `--debug`
    /// as `--pixel`, `view` `--screenshot` as `--out`.
    pub fn takes(self, id: &str) -> bool {
        let given_otherwise: &[&str] = match self {
            Verb::Run => &[],
            Verb::Record => &["record"],
            Verb::Legacy => &["shaders"],
            Verb::Debug => &[],
            Verb::Diff => &["screenshot", "diff"],
            Verb::View => &[],
            Verb::Check => &["diff"],
            Verb::Open => &["shaders"],
        };
        !given_otherwise.contains(&id) && modes_of(id).iter().any(|m| self.modes().contains(m))
    }
}

/// What each verb and tool of `shaderlab` does, as the completion scripts and the manual pages
/// say it.
const ABOUT: &[(&str, &str)] = &[
    ("list", "every lab, by lecture"),
    (
        "run",
        "run a lab in a window, or offscreen with --screenshot, --bench, --record, --debug, --line, --cost or --diff",
    ),
    (
        "record",
        "record a lab's frames offscreen at a fixed time step into OUT (GIF, MP4, WebM, PNGs or a directory)",
    ),
    (
        "legacy",
        "a course's own GLSL 1.10/1.20 pair VERT FRAG, in seed 000's scene",
    ),
    (
        "debug",
        "why a pixel has its colour: the covering triangle, the shaders line by line with their values",
    ),
    (
        "diff",
        "where a copy of the lab's shaders (--shaders DIR), or legacy's pair (--reference VERT0 FRAG0), draws differently, and from which line",
    ),
    (
        "check",
        "a copy of the lab's shaders (--shaders DIR) against the course's at every object, the lab's states of record and seeded random states: PSNR and the first diverging line per state",
    ),
    (
        "view",
        "a line's value (--line FILE:LINE) or the fragment shader's cost (--cost) at every pixel, drawn on the GPU",
    ),
    (
        "open",
        "write a link's shader files into a folder (--into DIR, default ./NAME-shaders/) and run the lab from there at the link's state",
    ),
    (
        "link",
        "the page's link to a lab at a state, carrying the files of --shaders DIR that differ from the built-in ones (legacy: its pair VERT FRAG)",
    ),
    ("glsl2wgsl", "translate GLSL to WGSL"),
    ("bench", "time every lab offscreen"),
    (
        "completions",
        "the shell's completion script (lab names, verbs, each verb's flags and their values)",
    ),
    (
        "man",
        "the manual pages, in roff: shaderlab's, or a verb's, or all of them written into a folder",
    ),
];

fn about(verb: &str) -> &'static str {
    ABOUT.iter().find(|(v, _)| *v == verb).map_or("", |(_, a)| a)
}

/// The names of the choices of the parameter `name` over every lab that has it (`object`:
/// cube, sphere, …), each once.
fn choices(name: &str) -> Vec<&'static str> {
    let mut out: Vec<&'static str> = Vec::new();
    for entry in crate::course::ALL {
        let params = (entry.params)();
        let Some(spec) = params.specs().iter().find(|s| s.name == name) else {
            continue;
        };
        if let crate::params::Kind::Choice(names) = spec.kind {
            for n in names {
                if !out.contains(n) {
                    out.push(n);
                }
            }
        }
    }
    out
}

/// `a` without its relations to other flags (conflicts, requirements), which name flags a
/// verb's description may leave out.
fn bare(a: &clap::Arg) -> clap::Arg {
    let values = a.get_action().takes_values();
    let mut b = clap::Arg::new(a.get_id().clone()).action(a.get_action().clone());
    if let Some(long) = a.get_long() {
        b = b.long(long.to_owned());
    }
    if let Some(help) = a.get_help() {
        b = b.help(help.clone());
    }
    if let Some(help) = a.get_long_help() {
        b = b.long_help(help.clone());
    }
    if values {
        b = b
            .value_parser(a.get_value_parser().clone())
            .allow_hyphen_values(a.is_allow_hyphen_values_set());
        if let Some(n) = a.get_num_args() {
            b = b.num_args(n);
        }
        if let Some(names) = a.get_value_names() {
            b = b.value_names(names.to_vec());
        }
        let defaults = a.get_default_values();
        if !defaults.is_empty() {
            b = b.default_values(defaults.iter());
        }
    }
    b
}

/// The command that lists a lab's flags and parameters for `verb`.
fn lab_help(verb: Verb) -> String {
    match verb {
        Verb::Legacy => "shaderlab legacy VERT FRAG --help".into(),
        Verb::Record => "shaderlab record NAME OUT --help".into(),
        Verb::Open => "shaderlab run NAME --help".into(),
        v => format!("shaderlab {} NAME --help", v.name()),
    }
}

/// `verb`'s command line: the lab (or legacy's pair) and the labs' flags the verb takes, with
/// the values they complete to; `view`'s and `diff`'s `--out`, `debug`'s `--pixel`, `diff`'s
/// `--reference`.
fn verb_command(verb: Verb) -> clap::Command {
    use clap::builder::PossibleValuesParser;
    use clap::{Arg, ArgAction, CommandFactory, ValueHint};
    let names: Vec<&'static str> = crate::course::ALL.iter().map(|e| e.info.name).collect();
    let (objects, shadings) = (choices("object"), choices("shading"));
    let mut flags = Args::command();
    if verb == Verb::Debug {
        flags = super::args::PixelFlag::Pixel.apply(flags);
    }
    let mut command = clap::Command::new(verb.name())
        .about(about(verb.name()))
        .after_help(format!(
            "Each lab's parameters (--set NAME=VALUE), their ranges and its keys: {}.",
            lab_help(verb)
        ));
    let lab = Arg::new("NAME")
        .required(true)
        .help("the lab")
        .value_parser(PossibleValuesParser::new(names));
    let pair = Arg::new("files")
        .value_names(["VERT", "FRAG"])
        .num_args(0..=2)
        .value_hint(ValueHint::FilePath);
    command = match verb {
        Verb::Legacy => command
            .arg(pair.help("the vertex and the fragment shader, GLSL 1.10/1.20 (without them: the built-in pair)")),
        Verb::Open => command.arg(
            Arg::new("LINK")
                .required(true)
                .value_hint(ValueHint::Url)
                .help("a link of the page (in quotes: it holds & and #), as its Copy link or shaderlab link gives it"),
        ),
        Verb::Record => command.arg(lab).arg(
            Arg::new("OUT")
                .required(true)
                .value_hint(ValueHint::FilePath)
                .help("NAME.gif, NAME.mp4, NAME.webm (through ffmpeg), frames-%04d.png or a directory"),
        ),
        _ => command
            .arg(lab)
            .arg(pair.help("legacy's vertex and fragment shader (other labs take no files)")),
    };
    for a in flags.get_arguments().filter(|a| !a.is_positional()) {
        let id = a.get_id().as_str();
        if !verb.takes(id) {
            continue;
        }
        let takes_values = a.get_action().takes_values();
        let open = takes_values && a.get_value_parser().possible_values().is_none();
        let b = bare(a);
        let b = match id {
            "object" => b.value_parser(PossibleValuesParser::new(objects.clone())),
            "shading" => b.value_parser(PossibleValuesParser::new(shadings.clone())),
            "screenshot" | "npy" | "record" | "model" | "texture" => b.value_hint(ValueHint::FilePath),
            "shaders" | "diff" => b.value_hint(ValueHint::DirPath),
            _ if open => b.value_hint(ValueHint::Other),
            _ => b,
        };
        let b = match (verb, id) {
            (_, "set") => b.help(format!(
                "Set a parameter by name, e.g. xangle=30, Ka=0.2, object=torus (repeatable; each lab's parameters and their ranges: {})",
                lab_help(verb)
            )),
            (Verb::Record, "frames") => b.required(true),
            (Verb::View, "screenshot") => b.long("out").help(
                "The picture, with its legend (default NAME-view.png or NAME-cost.png here, unless --npy, --json or --bench is given)",
            ),
            (Verb::Diff, "shaders") => {
                b.help("The copy of the lab's shaders to compare with the built-in ones (same file names as shaders_glsl/)")
            }
            (Verb::Diff, "json") => b.help("Print one JSON object (psnr, differing, worst, first_divergence) instead of the text"),
            (Verb::Check, "shaders") => {
                b.help("The copy of the lab's shaders to check against the built-in ones (same file names as shaders_glsl/)")
            }
            (Verb::Check, "json") => b.help("Print one JSON document (lab, states, passed, failed) instead of the text"),
            _ => b,
        };
        command = command.arg(b);
    }
    // A verb's own flag that takes one value.
    let one = |id: &'static str, value: &'static str, hint: ValueHint, help: &'static str| {
        Arg::new(id)
            .long(id)
            .value_name(value)
            .value_hint(hint)
            .action(ArgAction::Set)
            .help(help)
    };
    // legacy's other pair, for the comparisons.
    let reference = |help: &'static str| {
        Arg::new("reference")
            .long("reference")
            .num_args(2)
            .value_names(["VERT0", "FRAG0"])
            .value_hint(ValueHint::FilePath)
            .help(help)
    };
    match verb {
        Verb::Diff => command
            .arg(one(
                "out",
                "FILE.png",
                ValueHint::FilePath,
                "The picture of the difference, with its legend",
            ))
            .arg(reference(
                "For legacy: the pair to compare VERT FRAG with (instead of --shaders DIR)",
            )),
        Verb::Check => command
            .arg(one(
                "states",
                "N",
                ValueHint::Other,
                "Random states to add to the lab's own (default 8)",
            ))
            .arg(one(
                "seed",
                "S",
                ValueHint::Other,
                "The random states' seed (default 0): the same seed, the same states",
            ))
            .arg(one(
                "min-db",
                "D",
                ValueHint::Other,
                "The PSNR a state must reach to pass (default 40)",
            ))
            .arg(one(
                "report",
                "DIR",
                ValueHint::DirPath,
                "Write DIR/index.html: a page with each state's pictures and, where it fails, the copy's source there",
            ))
            .arg(reference(
                "For legacy: the pair to check VERT FRAG against (instead of --shaders DIR)",
            )),
        Verb::Open => command.arg(one(
            "into",
            "DIR",
            ValueHint::DirPath,
            "The folder the link's files are written into, made if missing (default ./NAME-shaders/); no file in it is ever replaced",
        )),
        _ => command,
    }
}

/// The command line of `shaderlab` as clap describes it, for the completion scripts and the
/// manual pages: each verb with the flags it takes ([`Verb::takes`]) and their values, the
/// tools with theirs. The verbs themselves are dispatched by hand (`src/main.rs`), each
/// handing the rest of its command line to a lab's or a tool's own parser.
pub fn command() -> clap::Command {
    use clap::{Arg, Command};
    let mut command = Command::new("shaderlab")
        .version(env!("CARGO_PKG_VERSION"))
        .about(format!(
            "the GLSL course labs on wgpu: {} labs in a window or offscreen, a course's own GLSL 1.10 files, and a GLSL debugger",
            crate::course::ALL.len()
        ))
        .subcommand_required(true)
        .disable_help_subcommand(true)
        .subcommand(Command::new("list").about(about("list")));
    for &verb in Verb::ALL {
        command = command.subcommand(verb_command(verb));
    }
    command = command.subcommand(link_command());
    let pages: Vec<&'static str> = ["list"]
        .into_iter()
        .chain(Verb::ALL.iter().map(|v| v.name()))
        .chain(["link", "glsl2wgsl", "bench", "completions", "man"])
        .collect();
    command
        .subcommand(
            super::tools::glsl2wgsl::command()
                .name("glsl2wgsl")
                .about(about("glsl2wgsl")),
        )
        .subcommand(super::tools::bench::command().name("bench").about(about("bench")))
        .subcommand(
            Command::new("completions").about(about("completions")).arg(
                Arg::new("SHELL")
                    .required(true)
                    .help("the shell")
                    .value_parser(clap::value_parser!(clap_complete::Shell)),
            ),
        )
        .subcommand(
            Command::new("man")
                .about(about("man"))
                .arg(
                    Arg::new("VERB")
                        .help("the verb whose page to print (without it: shaderlab's own page)")
                        .value_parser(clap::builder::PossibleValuesParser::new(pages)),
                )
                .arg(
                    Arg::new("dir")
                        .long("dir")
                        .value_name("DIR")
                        .value_hint(clap::ValueHint::DirPath)
                        .conflicts_with("VERB")
                        .help("Write every page (shaderlab.1, shaderlab-VERB.1) into DIR, made if missing"),
                ),
        )
}

/// `shaderlab link`'s command line, which it is parsed with: the lab (and legacy's pair),
/// `--shaders DIR`, `--set NAME=VALUE` and `--base URL`.
pub fn link_command() -> clap::Command {
    use clap::builder::PossibleValuesParser;
    use clap::{value_parser, Arg, ArgAction, ValueHint};
    let names: Vec<&'static str> = crate::course::ALL.iter().map(|e| e.info.name).collect();
    clap::Command::new("link")
        .about(about("link"))
        .after_help(format!(
            "The link opens the page with the lab at that state and the files in its editor; `shaderlab open LINK` \
             writes them into a folder and runs the lab from there. It carries at most {} characters of files \
             after `#` (never sent to a server), {} bytes once decompressed.",
            super::link::MAX_FRAGMENT,
            super::link::MAX_FILES_BYTES
        ))
        .arg(
            Arg::new("NAME")
                .required(true)
                .help("the lab")
                .value_parser(PossibleValuesParser::new(names)),
        )
        .arg(
            Arg::new("files")
                .value_names(["VERT", "FRAG"])
                .num_args(0..=2)
                .value_hint(ValueHint::FilePath)
                .value_parser(value_parser!(std::path::PathBuf))
                .help("legacy's pair, carried by its file names (other labs take no files)"),
        )
        .arg(
            Arg::new("shaders")
                .long("shaders")
                .value_name("DIR")
                .value_hint(ValueHint::DirPath)
                .value_parser(value_parser!(std::path::PathBuf))
                .help("Carry the files of DIR that differ from the built-in ones (same file names as shaders_glsl/), and new .glsl files"),
        )
        .arg(
            Arg::new("set")
                .long("set")
                .value_name("NAME=VALUE")
                .action(ArgAction::Append)
                .allow_hyphen_values(true)
                .value_hint(ValueHint::Other)
                .help("Set a parameter by name, e.g. xangle=30, Ka=0.2, object=torus (repeatable; each lab's parameters: shaderlab run NAME --help)"),
        )
        .arg(
            Arg::new("base")
                .long("base")
                .value_name("URL")
                .value_hint(ValueHint::Url)
                .help(format!(
                    "The page's address (default {}, where scripts/web --serve serves it)",
                    super::link::DEFAULT_BASE
                )),
        )
}

/// The completion script for `shell`: clap_complete's, and for fish (whose generator completes
/// no positional argument) the lab after a verb and the values of `man` and `completions`.
pub fn completion_script(shell: clap_complete::Shell) -> String {
    let mut command = command();
    let mut script = Vec::new();
    clap_complete::generate(shell, &mut command, "shaderlab", &mut script);
    let mut script = String::from_utf8_lossy(&script).into_owned();
    if shell == clap_complete::Shell::Fish {
        script.push_str(
            "\n# The first word after a verb (clap_complete's fish script completes no positional argument).\n\
             function __fish_shaderlab_first_word\n    test (count (commandline -opc)) -eq 2\nend\n",
        );
        for sub in command.get_subcommands() {
            let Some(first) = sub.get_positionals().next() else {
                continue;
            };
            for value in first.get_possible_values() {
                let help = match sub.get_name() {
                    "run" | "record" | "debug" | "diff" | "view" | "check" | "link" => {
                        crate::course::find(value.get_name())
                            .map(|e| format!(" -d '{} {}'", e.info.original_title, e.info.label.replace('\'', "\\'")))
                            .unwrap_or_default()
                    }
                    _ => String::new(),
                };
                script.push_str(&format!(
                    "complete -c shaderlab -n \"__fish_shaderlab_using_subcommand {}; and __fish_shaderlab_first_word\" -f -a \"{}\"{help}\n",
                    sub.get_name(),
                    value.get_name()
                ));
            }
        }
    }
    script
}

/// Every manual page: `shaderlab.1`, then `shaderlab-VERB.1` for each verb and tool, as
/// (file name, roff).
pub fn manual_pages() -> std::io::Result<Vec<(String, Vec<u8>)>> {
    let mut command = command();
    command.build();
    let mut pages = Vec::new();
    let mut page = Vec::new();
    clap_mangen::Man::new(command.clone()).render(&mut page)?;
    pages.push(("shaderlab.1".to_owned(), page));
    for sub in command.get_subcommands() {
        let man = clap_mangen::Man::new(sub.clone()).source(format!("shaderlab {}", env!("CARGO_PKG_VERSION")));
        let mut page = Vec::new();
        man.render(&mut page)?;
        pages.push((man.get_filename(), page));
    }
    Ok(pages)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// clap's own checks of the description (run where debug assertions are on), and every
    /// flag of [`Args`] placed: in the scene or in [`USES`].
    #[test]
    fn the_description_is_whole() {
        command().debug_assert();
        use clap::CommandFactory;
        for a in Args::command().get_arguments() {
            let id = a.get_id().as_str();
            assert!(!modes_of(id).is_empty(), "`{id}` is in no mode");
        }
    }
}
