//! Every verb of `shaderlab` × every flag: a flag that does nothing where it is given is a
//! usage error (status 2) that names it and says why, before anything is drawn or written; a
//! flag that does something gets past that check; and each verb's completion script (bash,
//! zsh, fish) and manual page offer exactly the flags it takes.
//!
//! Whether a flag gets past the check is seen without drawing: every run here also sets a
//! parameter no lab has (`--set nosuch=1`), which is refused only after the flags are checked,
//! so a run that says so took every flag it was given (as does one whose lab refuses a
//! shorthand for a parameter it lacks, `--clear` for phong, which comes with the parameters).
//!
//! The expectations are this file's own table (which flag does something in which verb and
//! mode), written from what each flag does, not read from the program.

mod common;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The scene's flags: what every verb draws, so every verb takes them.
const SCENE: &[&str] = &[
    "--set",
    "--size",
    "--shaders",
    "--object",
    "--rotate",
    "--time",
    "--shading",
    "--tess",
    "--model",
    "--texture",
    "--camera",
    "--clear",
    "--timeout",
];

/// Every flag a verb could be given (the labs' and the verbs' own), with a value it takes.
/// `DIR` is a folder of the built-in shaders' copies, `V`/`F` a vertex and a fragment shader.
const FLAGS: &[(&str, &[&str])] = &[
    ("--set", &["xangle=1"]),
    ("--screenshot", &["x.png"]),
    ("--bench", &["2"]),
    ("--gpu-time", &[]),
    ("--size", &["32x18"]),
    ("--shaders", &["DIR"]),
    ("--object", &["cube"]),
    ("--rotate", &["1,2,3"]),
    ("--time", &["1"]),
    ("--shading", &["phong"]),
    ("--tess", &["8"]),
    ("--model", &["m.obj"]),
    ("--texture", &["t.png"]),
    ("--camera", &["0,0,5"]),
    ("--clear", &["0,0,0"]),
    ("--record", &["r.gif"]),
    ("--frames", &["2"]),
    ("--fps", &["10"]),
    ("--from", &["0"]),
    ("--timeout", &["5"]),
    ("--unpaced", &[]),
    ("--debug", &["1,1"]),
    ("--json", &[]),
    ("--line", &["phong.frag:17"]),
    ("--name", &["Idiff"]),
    ("--stage", &["fragment"]),
    ("--cost", &[]),
    ("--npy", &["v.npy"]),
    ("--diff", &["DIR"]),
    ("--out", &["o.png"]),
    ("--pixel", &["1,1"]),
    ("--reference", &["V", "F"]),
    ("--states", &["2"]),
    ("--seed", &["1"]),
    ("--min-db", &["30"]),
    ("--report", &["rep"]),
    ("--into", &["into"]),
    ("--base", &["http://example.org/"]),
];

/// What each verb takes besides the scene's flags; `view` also takes `--screenshot`, the old
/// name of its `--out`.
fn takes(verb: &str) -> Vec<&'static str> {
    // What a run that draws one lab's frame takes: pictures, timing, recordings, a pixel, views.
    const DRAWING: &[&str] = &[
        "--screenshot",
        "--bench",
        "--gpu-time",
        "--record",
        "--frames",
        "--fps",
        "--from",
        "--unpaced",
        "--debug",
        "--json",
        "--line",
        "--name",
        "--stage",
        "--cost",
        "--npy",
    ];
    let with = |more: &[&'static str]| -> Vec<&'static str> { DRAWING.iter().chain(more).copied().collect() };
    let own: Vec<&str> = match verb {
        "run" => with(&["--diff"]),
        // legacy draws the pair it is given: no folder of shaders, nothing to compare with.
        "legacy" => with(&[]),
        "record" => vec!["--frames", "--fps", "--from"],
        "debug" => vec!["--pixel", "--json", "--screenshot"],
        "view" => vec![
            "--out",
            "--screenshot",
            "--bench",
            "--json",
            "--line",
            "--name",
            "--stage",
            "--cost",
            "--npy",
        ],
        "diff" => vec!["--out", "--json", "--reference"],
        "check" => vec!["--json", "--reference", "--states", "--seed", "--min-db", "--report"],
        // open draws the link's files from the folder it writes them into: no --shaders, and
        // nothing to compare.
        "open" => with(&["--into"]),
        // link draws nothing: the lab's state and the folder whose files it carries.
        "link" => return vec!["--set", "--shaders", "--base"],
        _ => panic!("{verb}"),
    };
    let mut all: Vec<&str> = SCENE.to_vec();
    if verb == "legacy" || verb == "open" {
        all.retain(|f| *f != "--shaders");
    }
    all.extend(own);
    all
}

/// The runs of each verb a flag is tried in (each also with `--set nosuch=1`): a flag is taken
/// by the verb when it gets past the check in one of them.
fn bases(verb: &str) -> Vec<Vec<&'static str>> {
    let modes: Vec<Vec<&'static str>> = vec![
        vec![],
        vec!["--screenshot", "x.png"],
        vec!["--bench", "2"],
        vec!["--record", "r.gif", "--frames", "2"],
        vec!["--debug", "1,1"],
        vec!["--line", "phong.frag:17"],
        vec!["--cost"],
        vec!["--diff", "DIR"],
    ];
    let with = |head: &[&'static str], modes: &[Vec<&'static str>]| -> Vec<Vec<&'static str>> {
        modes
            .iter()
            .map(|m| head.iter().copied().chain(m.iter().copied()).collect())
            .collect()
    };
    match verb {
        "run" => with(&["run", "phong"], &modes),
        "legacy" => with(&["legacy", "V", "F"], &modes[..7]),
        "record" => vec![vec!["record", "phong", "r.gif", "--frames", "2"]],
        "debug" => vec![vec!["debug", "phong", "--pixel", "1,1"]],
        "view" => vec![
            vec!["view", "phong", "--line", "phong.frag:17"],
            vec!["view", "phong", "--cost"],
        ],
        "diff" => vec![
            vec!["diff", "phong", "--shaders", "DIR"],
            vec!["diff", "legacy", "V", "F", "--reference", "V", "F"],
        ],
        "check" => vec![
            vec!["check", "phong", "--shaders", "DIR"],
            vec!["check", "legacy", "V", "F", "--reference", "V", "F"],
        ],
        "open" => with(&["open", "http://127.0.0.1:8000/?lab=phong"], &modes[..7]),
        "link" => vec![vec!["link", "phong"]],
        _ => panic!("{verb}"),
    }
}

const VERBS: &[&str] = &[
    "run", "legacy", "record", "debug", "view", "diff", "check", "open", "link",
];

/// A folder for one test, with the inputs the runs name: DIR (the shaders' copies) and the
/// course's pair as V and F.
struct Place {
    dir: PathBuf,
    shaders: String,
}

impl Place {
    fn new(tag: &str) -> Place {
        let dir = common::output_dir().join(format!("verb_flags_{tag}"));
        let _ = std::fs::remove_dir_all(&dir);
        let shaders = dir.join("copy");
        common::copy_shaders(&shaders);
        let course = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/course/seed000");
        std::fs::copy(course.join("lab3.vert"), dir.join("V")).expect("the course's vertex shader");
        std::fs::copy(course.join("lab3.frag"), dir.join("F")).expect("the course's fragment shader");
        Place {
            shaders: shaders.to_str().expect("utf-8").to_owned(),
            dir,
        }
    }

    /// The files in the folder, the inputs aside.
    fn written(&self) -> Vec<String> {
        let mut out: Vec<String> = std::fs::read_dir(&self.dir)
            .expect("the folder")
            .map(|e| e.expect("an entry").file_name().to_string_lossy().into_owned())
            .filter(|n| !["copy", "V", "F"].contains(&n.as_str()))
            .collect();
        out.sort();
        out
    }

    /// Runs `shaderlab` with `args` (DIR standing for the copies) and `--set nosuch=1`: the
    /// status and stderr.
    fn run(&self, args: &[&str]) -> (Option<i32>, String) {
        let args: Vec<&str> = args
            .iter()
            .map(|a| if *a == "DIR" { self.shaders.as_str() } else { a })
            .collect();
        let out = Command::new(env!("CARGO_BIN_EXE_shaderlab"))
            .current_dir(&self.dir)
            .args(&args)
            .args(["--set", "nosuch=1"])
            .output()
            .expect("shaderlab runs");
        assert!(
            out.stdout.is_empty(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stdout)
        );
        (out.status.code(), String::from_utf8_lossy(&out.stderr).into_owned())
    }
}

/// Whether a run got past the flags' check: it reached the parameters, where the one no lab
/// has is refused, or before it a shorthand for a parameter this lab lacks (`--clear` for
/// phong: the lab's to refuse, after the flags' check).
fn passed(err: &str) -> bool {
    err.contains("unknown parameter `nosuch`") || err.contains(": phong has no ") || err.contains(": legacy has no ")
}

/// A refusal says which flag and why: one of shaderlab's (`does nothing`, `is not for`) or
/// clap's (`cannot be used with`, `required arguments`, `unexpected argument`), naming the
/// flag (or, for a requirement, the flag it needs).
fn says_why(flag: &str, err: &str) -> bool {
    let named = err.contains(flag) || err.contains("required arguments were not provided");
    let why = [
        "does nothing",
        "is not for",
        "cannot be used with",
        "required arguments were not provided",
        "unexpected argument",
        "cannot be used multiple times",
    ]
    .iter()
    .any(|w| err.contains(w));
    named && why
}

/// Each verb × flag: taken exactly where the table says, refused with status 2 and a reason
/// elsewhere, and nothing written either way. Returns, per verb, the flags it took.
fn sweep(place: &Place) -> Vec<(&'static str, BTreeSet<&'static str>)> {
    let mut out = Vec::new();
    for &verb in VERBS {
        let expected: BTreeSet<&str> = takes(verb).into_iter().collect();
        let mut taken: BTreeSet<&'static str> = BTreeSet::new();
        for &(flag, values) in FLAGS {
            let mut refusals = Vec::new();
            for base in bases(verb) {
                if base.contains(&flag) {
                    // Given by the base itself: taken if the base is.
                    let (code, err) = place.run(&base);
                    assert_eq!(code, Some(2), "{base:?}: {err}");
                    if passed(&err) {
                        taken.insert(flag);
                    }
                    continue;
                }
                let mut args = base.clone();
                args.push(flag);
                args.extend_from_slice(values);
                let (code, err) = place.run(&args);
                assert_eq!(code, Some(2), "{args:?}: {err}");
                assert!(!err.contains("panicked"), "{args:?}: {err}");
                if passed(&err) {
                    taken.insert(flag);
                } else {
                    refusals.push((args, err));
                }
            }
            if expected.contains(flag) {
                assert!(
                    taken.contains(flag),
                    "shaderlab {verb} should take {flag}; refused: {refusals:#?}"
                );
            } else {
                assert!(
                    !taken.contains(flag),
                    "shaderlab {verb} takes {flag}, which does nothing there"
                );
                for (args, err) in &refusals {
                    assert!(
                        says_why(flag, err),
                        "{args:?}: the refusal says which flag and why: {err}"
                    );
                }
            }
        }
        assert_eq!(place.written(), Vec::<String>::new(), "{verb}: nothing written");
        out.push((verb, taken));
    }
    out
}

/// In `shaderlab run`, the flags that modify a mode, and the modes where each does something.
#[test]
fn a_flag_that_does_nothing_in_its_mode_is_refused_and_says_why() {
    let place = Place::new("modes");
    let modifiers: &[(&str, &[&str])] = &[
        ("--gpu-time", &[]),
        ("--frames", &["2"]),
        ("--fps", &["10"]),
        ("--from", &["0"]),
        ("--unpaced", &[]),
        ("--json", &[]),
        ("--name", &["Idiff"]),
        ("--stage", &["fragment"]),
        ("--npy", &["v.npy"]),
    ];
    // Each mode, and the modifiers that do something there.
    let modes: &[(&[&str], &[&str])] = &[
        (&[], &["--unpaced"]),
        (&["--screenshot", "x.png"], &[]),
        (&["--bench", "2"], &["--gpu-time"]),
        (
            &["--record", "r.gif", "--frames", "2"],
            &["--frames", "--fps", "--from"],
        ),
        (&["--debug", "1,1"], &["--json"]),
        (&["--line", "phong.frag:17"], &["--json", "--name", "--stage", "--npy"]),
        (&["--cost"], &["--json", "--npy"]),
        (&["--diff", "DIR"], &["--json"]),
    ];
    for (mode, works) in modes {
        for (flag, values) in modifiers {
            if mode.contains(flag) {
                continue;
            }
            let mut args = vec!["run", "phong"];
            args.extend_from_slice(mode);
            args.push(flag);
            args.extend_from_slice(values);
            let (code, err) = place.run(&args);
            assert_eq!(code, Some(2), "{args:?}: {err}");
            if works.contains(flag) {
                assert!(passed(&err), "{args:?}: {flag} does something here: {err}");
            } else {
                assert!(!passed(&err), "{args:?}: {flag} does nothing here, and is taken");
                assert!(says_why(flag, &err), "{args:?}: {err}");
            }
        }
    }
    // The sweep's cases, in the words a user sees.
    for (args, says) in [
        (
            &["run", "phong", "--gpu-time"][..],
            "`--gpu-time` times the frames of --bench N on the GPU",
        ),
        (
            &["run", "phong", "--gpu-time"],
            "does nothing in a window: add --bench N",
        ),
        (
            &["view", "phong", "--cost", "--name", "X"],
            "`--name` chooses the name that --line FILE:LINE shows, and does nothing in a cost view",
        ),
        (
            &["view", "phong", "--cost", "--stage", "vertex"],
            "`--stage` chooses the stage of --line FILE:LINE, and does nothing in a cost view",
        ),
        (
            &["diff", "phong", "--shaders", "DIR", "--npy", "F"],
            "`--npy` writes a view's values, and does nothing in a comparison",
        ),
        (
            &["diff", "phong", "--shaders", "DIR", "--line", "phong.frag:17"],
            "`--line` shows a line's value, and does nothing in a comparison",
        ),
        (
            &["diff", "phong", "--shaders", "DIR", "--cost"],
            "and does nothing in a comparison",
        ),
        (
            &["debug", "phong", "--pixel", "1,1", "--gpu-time"],
            "and does nothing with --pixel",
        ),
        (
            &["record", "phong", "r.gif", "--frames", "2", "--unpaced"],
            "`--unpaced` paces the frames of a window, and does nothing in a recording",
        ),
        (
            &["legacy", "V", "F", "--shaders", "DIR"],
            "`--shaders` reads a lab's shaders from a folder, and does nothing for legacy",
        ),
        (&["run", "legacy", "V", "F", "--diff", "DIR"], "--reference VERT0 FRAG0"),
    ] {
        let (code, err) = place.run(args);
        assert_eq!(code, Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
    assert_eq!(place.written(), Vec::<String>::new(), "nothing written");
}

/// The tools and the verbs without a lab: nothing after a verb that takes nothing, no flag
/// that does nothing.
#[test]
fn the_tools_and_plain_verbs_refuse_what_they_would_ignore() {
    let place = Place::new("tools");
    for (args, says) in [
        (&["list", "extra"][..], "`extra`: this takes nothing after it"),
        (&["--version", "extra"], "`extra`: this takes nothing after it"),
        (&["help", "legacy"], "`legacy`: this takes nothing after it"),
        (&["help", "view", "extra"], "`view`: this takes nothing after it"),
        (&["completions", "bash", "extra"], "one shell, and nothing after it"),
        (&["man", "view", "extra"], "expected one VERB or --dir DIR"),
        (&["man", "nosuch"], "no page for `nosuch`"),
        (
            &["bench", "--debugger", "--gpu-time"],
            "`--gpu-time` times frames on the GPU, and does nothing with --debugger",
        ),
        (&["bench", "--only", "nosuch"], "no lab's name contains `nosuch`"),
    ] {
        let out = Command::new(env!("CARGO_BIN_EXE_shaderlab"))
            .current_dir(&place.dir)
            .args(args)
            .output()
            .expect("shaderlab runs");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?}");
    }
}

fn shaderlab_stdout(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_shaderlab"))
        .args(args)
        .output()
        .expect("shaderlab runs");
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("UTF-8")
}

/// The long flags a zsh script's section for `verb` offers.
fn zsh_offers(script: &str, verb: &str) -> BTreeSet<String> {
    let start = script
        .find(&format!("\n({verb})\n_arguments"))
        .unwrap_or_else(|| panic!("zsh: no section for {verb}"));
    let section = &script[start..];
    let section = &section[..section.find("&& ret=0").expect("the section's end")];
    section
        .lines()
        .filter_map(|l| {
            let l = l.strip_prefix('\'')?;
            let l = match l.strip_prefix('(') {
                Some(rest) => &rest[rest.find(')')? + 1..],
                None => l,
            };
            let l = l.strip_prefix('*').unwrap_or(l);
            let end = l.find(['=', '[', '\''])?;
            l[..end].starts_with("--").then(|| l[..end].to_owned())
        })
        .collect()
}

/// The long flags a fish script offers after `verb`.
fn fish_offers(script: &str, verb: &str) -> BTreeSet<String> {
    let condition = format!("-n \"__fish_shaderlab_using_subcommand {verb}\" ");
    script
        .lines()
        .filter(|l| l.contains(&condition))
        .filter_map(|l| {
            let rest = &l[l.find(" -l ")? + 4..];
            Some(format!("--{}", rest.split_whitespace().next()?))
        })
        .collect()
}

/// The long flags a manual page's OPTIONS list (`\fB\-\-set\fR …`, `\fB\-h\fR, \fB\-\-help\fR`).
fn page_offers(page: &str) -> BTreeSet<String> {
    page.lines()
        .filter(|l| l.starts_with("\\fB\\-"))
        .filter_map(|l| {
            let rest = &l[l.find("\\fB\\-\\-")? + "\\fB\\-\\-".len()..];
            let name = &rest[..rest.find("\\fR")?];
            Some(format!("--{}", name.replace("\\-", "-")))
        })
        .collect()
}

/// What each verb takes, as the runs show, is what its completion (bash, zsh, fish) and its
/// manual page offer: no flag it refuses, every flag it takes (`view`'s `--screenshot` aside,
/// the old name of its `--out`).
#[test]
fn each_verb_takes_completes_and_documents_the_same_flags() {
    let place = Place::new("sweep");
    let taken = sweep(&place);
    let bash = shaderlab_stdout(&["completions", "bash"]);
    let script = place.dir.join("completion.bash");
    std::fs::write(&script, &bash).expect("the script");
    let zsh = shaderlab_stdout(&["completions", "zsh"]);
    let fish = shaderlab_stdout(&["completions", "fish"]);
    for (verb, flags) in taken {
        let mut expected: BTreeSet<String> = flags
            .iter()
            .filter(|f| !(verb == "view" && **f == "--screenshot"))
            .map(|f| f.to_string())
            .collect();
        expected.insert("--help".into());
        let words: Vec<&str> = match verb {
            "legacy" => vec!["shaderlab", "legacy", "V", "F", "--"],
            "open" => vec!["shaderlab", "open", "LINK", "--"],
            v => vec!["shaderlab", v, "phong", "--"],
        };
        let offered: BTreeSet<String> = common::bash_offers(&script, &words)
            .into_iter()
            .filter(|w| w.starts_with("--"))
            .collect();
        assert_eq!(offered, expected, "bash: shaderlab {verb} … --<TAB>");
        assert_eq!(zsh_offers(&zsh, verb), expected, "zsh: shaderlab {verb}");
        assert_eq!(fish_offers(&fish, verb), expected, "fish: shaderlab {verb}");
        let page = shaderlab_stdout(&["man", verb]);
        assert!(
            page.contains(&format!(".TH shaderlab-{verb} 1")),
            "{verb}'s page: {}",
            &page[..200.min(page.len())]
        );
        assert_eq!(page_offers(&page), expected, "shaderlab man {verb}");
    }
}
