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
        modes: &[Mode::Debug, Mode::Line, Mode::Cost, Mode::Diff],
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
            let instead = if mode == Mode::Diff {
                format!("name the pair to compare against with `shaderlab diff {name} VERT FRAG --reference VERT0 FRAG0`")
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
        }
    }

    /// The modes a run of the verb can be in.
    pub fn modes(self) -> &'static [Mode] {
        match self {
            Verb::Run => Mode::ALL,
            Verb::Record => &[Mode::Record],
            Verb::Legacy => &[
                Mode::Window,
                Mode::Screenshot,
                Mode::Bench,
                Mode::Record,
                Mode::Debug,
                Mode::Line,
                Mode::Cost,
            ],
            Verb::Debug => &[Mode::Debug],
            Verb::Diff => &[Mode::Diff],
            Verb::View => &[Mode::Line, Mode::Cost],
        }
    }

    /// Whether the verb takes the labs' flag `id` (clap's id in [`Args`]): it does something
    /// in one of the verb's modes, and the verb does not give it another way (`record`'s OUT,
    /// `debug`'s `--pixel`, `view`'s and `diff`'s `--out`, `diff`'s copy as `--shaders`, the
    /// pair legacy draws instead of `--shaders`).
    pub fn takes(self, id: &str) -> bool {
        let given_otherwise: &[&str] = match self {
            Verb::Run => &[],
            Verb::Record => &["record"],
            Verb::Legacy => &["shaders"],
            Verb::Debug => &[],
            Verb::Diff => &["screenshot", "diff"],
            Verb::View => &["screenshot"],
        };
        !given_otherwise.contains(&id) && modes_of(id).iter().any(|m| self.modes().contains(m))
    }
}
