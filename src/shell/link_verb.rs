//! `shaderlab link` and `shaderlab open`: the page's links, and the shader files they carry
//! ([`super::link`]), on the command line. `link` prints the link to a lab at a state with the
//! files of a folder that differ from the built-in text (legacy: its pair); `open` writes a
//! link's files into a folder, all together and over no file, and runs the lab from there as
//! `shaderlab run NAME --shaders DIR --set …` does.

use std::collections::BTreeMap;
use std::ffi::OsString;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use super::args::Args;
use super::cli::Failure;
use super::link::{self, Link, LinkError};
use super::verbs;
use crate::error::Error;
use crate::lab::LabEntry;
use crate::shader::{embedded_names, embedded_source, read_shader_file};

const OPEN_USAGE: &str = "Usage: shaderlab open LINK [--into DIR] [FLAGS…]";

/// A link that cannot be made or opened: status 2, or 1 for files too large to carry.
fn refused(e: LinkError) -> Failure {
    Failure {
        code: if matches!(e, LinkError::TooBig { .. }) { 1 } else { 2 },
        error: Error::Param(e.to_string()),
    }
}

fn usage(text: String) -> Failure {
    Failure::from(Error::Param(text))
}

/// Prints `failure` as `shaderlab VERB: error: …` and ends with its status.
fn exit(verb: &str, failure: &Failure) -> ExitCode {
    let _ = writeln!(std::io::stderr(), "shaderlab {verb}: error: {}", failure.error);
    ExitCode::from(failure.code)
}

/// `shaderlab link NAME [VERT FRAG] [--shaders DIR] [--set NAME=VALUE…] [--base URL]`
/// (`argv`: `link` and what follows it): the link on stdout.
pub fn link_main(mut argv: Vec<OsString>) -> ExitCode {
    if let Some(first) = argv.first_mut() {
        *first = "shaderlab link".into();
    }
    let matches = super::cli::parse_command_line(verbs::link_command().bin_name("shaderlab link"), argv);
    match make_link(&matches) {
        Ok(url) => match super::cli::print(&format!("{url}\n")) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => exit("link", &Failure::from(e)),
        },
        Err(failure) => exit("link", &failure),
    }
}

fn make_link(matches: &clap::ArgMatches) -> Result<String, Failure> {
    let name = matches
        .get_one::<String>("NAME")
        .map(String::as_str)
        .unwrap_or_default();
    let entry = crate::course::find(name).ok_or_else(|| usage(format!("no lab called `{name}`")))?;
    let paths: Vec<PathBuf> = matches
        .get_many::<PathBuf>("files")
        .into_iter()
        .flatten()
        .cloned()
        .collect();
    let shaders = matches.get_one::<PathBuf>("shaders");
    let base = matches
        .get_one::<String>("base")
        .map_or(link::DEFAULT_BASE, String::as_str);
    if base.is_empty() || base.contains(['?', '#']) {
        return Err(usage(format!(
            "`--base {base}`: the page's address, without `?` or `#` (e.g. {})",
            link::DEFAULT_BASE
        )));
    }
    let mut link = Link::new(base, name);
    let mut params = (entry.params)();
    let mut broken: Option<Error> = None;
    if link::draws_pair(entry) {
        if shaders.is_some() {
            return Err(usage(format!(
                "`--shaders` reads a lab's shaders from a folder, and does nothing for {name}, which draws the pair VERT FRAG: give your files as VERT FRAG"
            )));
        }
        match paths.as_slice() {
            [] => {}
            [vert, frag] => {
                let file_name = |p: &PathBuf| {
                    p.file_name()
                        .and_then(|n| n.to_str())
                        .map(str::to_owned)
                        .ok_or_else(|| usage(format!("{}: no file name a link can carry", p.display())))
                };
                let (v, f) = (file_name(vert)?, file_name(frag)?);
                if v == f {
                    return Err(usage(format!(
                        "VERT and FRAG have the same file name `{v}`: a link carries files by their names"
                    )));
                }
                for (name, path) in [(&v, vert), (&f, frag)] {
                    link::check_name(entry, name).map_err(refused)?;
                    link.files.insert(name.clone(), read_shader_file(path)?);
                }
                link.set_pair(&v, &f);
                if let Err(e) = params.declare_files(&paths) {
                    // A pair that does not compile is shared as it is; the parameters it
                    // would declare cannot be checked.
                    broken = Some(e);
                }
            }
            _ => return Err(usage(format!("{name} takes two files: VERT FRAG"))),
        }
    } else {
        if let Some(first) = paths.first() {
            return Err(usage(format!(
                "unexpected argument `{}`: {name} takes no files",
                first.display()
            )));
        }
        if let Some(dir) = shaders {
            link.files = changed_files(dir)?;
        }
    }
    for set in matches.get_many::<String>("set").into_iter().flatten() {
        link.push_set(set);
    }
    link.check(&|_| false).map_err(refused)?;
    match &broken {
        None => link.check_sets(&mut params).map_err(refused)?,
        Some(e) => {
            let first = e.to_string();
            eprintln!(
                "shaderlab link: the pair does not compile, so its state goes unchecked: {}",
                first.lines().next().unwrap_or_default()
            );
        }
    }
    let url = link.to_url().map_err(refused)?;
    let carried = if link.files.is_empty() {
        match shaders {
            Some(dir) => format!("the files in {} are the built-in ones: it carries none", dir.display()),
            None => "no files".into(),
        }
    } else {
        let after = url.split_once('#').map_or(0, |(_, f)| f.len());
        let names: Vec<&str> = link.files.keys().map(String::as_str).collect();
        format!("it carries {} ({after} characters after #)", names.join(", "))
    };
    eprintln!("shaderlab link: {} characters; {carried}", url.len());
    Ok(url)
}

/// The files of `dir` a link carries: each of `shaders_glsl/`'s names whose text differs from
/// the built-in one, and each `.glsl` file that has no built-in namesake (one an edited file
/// may `#include`), by name.
fn changed_files(dir: &Path) -> Result<BTreeMap<String, String>, Error> {
    crate::shader::ShaderSource::dir(dir)?;
    let io = |source| Error::Io {
        path: dir.to_owned(),
        source,
    };
    let mut names = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(io)? {
        if let Some(name) = entry.map_err(io)?.file_name().to_str() {
            names.push(name.to_owned());
        }
    }
    names.sort();
    let mut files = BTreeMap::new();
    for name in names {
        let built_in = embedded_source(&name);
        let path = dir.join(&name);
        if (built_in.is_none() && !name.ends_with(".glsl")) || name.starts_with('.') || !path.is_file() {
            continue;
        }
        let text = read_shader_file(&path)?;
        if built_in != Some(text.as_str()) {
            files.insert(name, text);
        }
    }
    Ok(files)
}

/// `shaderlab open LINK [--into DIR] [FLAGS…]` (`argv`: `open` and what follows it).
pub fn open_main(argv: Vec<OsString>) -> ExitCode {
    let words: Vec<String> = argv.iter().map(|a| a.to_string_lossy().into_owned()).collect();
    let text = match words.get(1).map(String::as_str) {
        Some("--help" | "-h") => {
            let mut command = verbs::command();
            let help = command
                .find_subcommand_mut("open")
                .map(|c| c.clone().bin_name("shaderlab open").render_long_help().to_string())
                .unwrap_or_default();
            return match super::cli::print(&help) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => exit("open", &Failure::from(e)),
            };
        }
        Some(word) if !word.starts_with('-') => word.to_owned(),
        _ => {
            eprintln!(
                "shaderlab open: which link? give the page's link first, in quotes (it holds & and #)\n\n{OPEN_USAGE}"
            );
            return ExitCode::from(2);
        }
    };
    let mut into: Option<PathBuf> = None;
    let mut rest: Vec<OsString> = Vec::new();
    let mut k = 2;
    while k < argv.len() {
        let (dir, step) = match words[k].strip_prefix("--into") {
            Some("") => (argv.get(k + 1).map(PathBuf::from), 2),
            Some(value) if value.starts_with('=') => (Some(PathBuf::from(&value[1..])), 1),
            _ => {
                rest.push(argv[k].clone());
                k += 1;
                continue;
            }
        };
        let Some(dir) = dir.filter(|d| !d.as_os_str().is_empty()) else {
            return exit(
                "open",
                &usage(format!("`--into` needs a folder: --into DIR\n\n{OPEN_USAGE}")),
            );
        };
        if into.replace(dir).is_some() {
            return exit("open", &usage("`--into` cannot be used multiple times".into()));
        }
        k += step;
    }
    let (link, entry) = match Link::parse(&text).and_then(|link| link.check(&|_| false).map(|e| (link, e))) {
        Ok(found) => found,
        Err(e) => return exit("open", &refused(e)),
    };
    let program = OsString::from(format!("shaderlab open {}", entry.info.name));
    let args = Args::parse_from_for(entry, std::iter::once(program).chain(rest).collect());
    match prepare(entry, &link, args, into) {
        Ok(args) => super::main_parsed(entry, args),
        Err(failure) => {
            let _ = writeln!(std::io::stderr(), "{}: error: {}", entry.info.name, failure.error);
            ExitCode::from(failure.code)
        }
    }
}

/// Checks everything `open` was given (the link's state, the flags, the outputs), then writes
/// the link's files into `into`, and returns the run's arguments: the link's state, then the
/// flags given, and the lab's shaders from the folder (legacy: the pair in it).
fn prepare(entry: &'static LabEntry, link: &Link, args: Args, into: Option<PathBuf>) -> Result<Args, Failure> {
    let name = entry.info.name;
    if args.shaders.is_some() {
        return Err(usage(
            "`--shaders` reads a lab's shaders from a folder, and does nothing for shaderlab open: the link's files \
             are written into --into DIR, and the lab reads them from there"
                .into(),
        ));
    }
    if args.diff.is_some() {
        return Err(usage(format!(
            "`--diff` compares a copy of a lab's shaders, and does nothing for shaderlab open: compare the folder it \
             writes with `shaderlab diff {name} --shaders DIR`"
        )));
    }
    if let Some(first) = args.files.first() {
        return Err(usage(format!(
            "unexpected argument `{}`: the link gives {name}'s files",
            first.display()
        )));
    }
    verbs::check(entry, &args, verbs::Mode::of(&args))?;
    let dir = into.unwrap_or_else(|| PathBuf::from(format!("{name}-shaders")));
    let pair: Option<Vec<&str>> = link.pair().map(|p| p.split(',').collect());
    let mut sets: Vec<(String, String)> = link
        .sets()
        .iter()
        .filter(|s| !(pair.is_some() && s.starts_with("files=")))
        .filter_map(|s| s.split_once('='))
        .map(|(k, v)| (k.trim().to_owned(), v.trim().to_owned()))
        .collect();
    sets.extend(args.set.iter().cloned());
    let mut run = Args {
        set: sets,
        ..args.clone()
    };
    // The files: legacy's pair, or a whole copy of the built-in shaders with the link's in
    // place of theirs, so that the folder serves `--shaders DIR` (run, diff, link) as is.
    let files: Vec<(String, String)> = if link::draws_pair(entry) {
        link.files.iter().map(|(n, t)| (n.clone(), t.clone())).collect()
    } else {
        let mut all: BTreeMap<String, String> = embedded_names()
            .map(|n| (n.to_owned(), embedded_source(n).unwrap_or_default().to_owned()))
            .collect();
        all.extend(link.files.clone());
        all.into_iter().collect()
    };
    // The state, checked before anything is written: legacy's parameters come from its pair,
    // read from a copy made for that alone. A pair that does not compile is written all the
    // same (its files are there to be mended), and the run says what is wrong with it.
    {
        let staged = match &pair {
            Some(names) => Some(Staged::new(&link.files)?.pair(names)),
            None => None,
        };
        let mut params = (entry.params)();
        let compiles = match &staged {
            Some((_, paths)) => params.declare_files(paths).is_ok(),
            None => true,
        };
        if compiles {
            link.check_sets(&mut params).map_err(refused)?;
            let check = Args {
                files: staged.as_ref().map(|(_, p)| p.clone()).unwrap_or_default(),
                ..run.clone()
            };
            check.params(entry)?;
        }
    }
    if let Some(path) = &args.screenshot {
        super::headless::check_png_path(path)?;
    }
    if let Some(path) = &args.record {
        super::record::Output::parse(path, name)?;
    }
    args.files(entry)?;
    match &pair {
        Some(names) => run.files = names.iter().map(|n| dir.join(n)).collect(),
        None => run.shaders = Some(dir.clone()),
    }
    write_files(&dir, &files)?;
    if !files.is_empty() {
        let carried: Vec<&str> = link.files.keys().map(String::as_str).collect();
        let others = files.len() - carried.len();
        eprintln!(
            "{name}: wrote {} into {}{}",
            if carried.is_empty() {
                "no file from the link (it carries none)".to_owned()
            } else {
                format!("the link's {}", carried.join(", "))
            },
            dir.display(),
            if others > 0 {
                format!(", with the {others} built-in files beside them")
            } else {
                String::new()
            }
        );
    }
    Ok(run)
}

/// Writes `files` into `dir` together ([`crate::fsutil::Batch`]): over no existing file,
/// `dir` made if missing (and removed again if the writing fails), all or none.
fn write_files(dir: &Path, files: &[(String, String)]) -> Result<(), Error> {
    use crate::fsutil::{signals, Batch, NewDir};
    if files.is_empty() {
        return Ok(());
    }
    for (name, _) in files {
        let path = dir.join(name);
        if std::fs::symlink_metadata(&path).is_ok() {
            return Err(Error::Param(format!(
                "{}: exists; shaderlab open never writes over a file: name another folder with --into DIR",
                path.display()
            )));
        }
    }
    NewDir::check(dir)?;
    let _deferred = signals::defer();
    let made = NewDir::create(dir)?;
    let mut batch = Batch::new(false);
    for (name, text) in files {
        batch.write(&dir.join(name), |w| w.write_all(text.as_bytes()))?;
    }
    signals::check()?;
    batch.commit()?;
    made.keep();
    Ok(())
}

/// A private copy of a link's files in the system's temporary folder, removed when dropped:
/// what legacy's parameters are read from before anything is written where the user asked.
struct Staged {
    dir: PathBuf,
}

impl Staged {
    fn new(files: &BTreeMap<String, String>) -> Result<Staged, Error> {
        let dir = std::env::temp_dir().join(format!("shaderlab-open-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let io = |path: &Path, source| Error::Io {
            path: path.to_owned(),
            source,
        };
        std::fs::create_dir(&dir).map_err(|e| io(&dir, e))?;
        let staged = Staged { dir };
        for (name, text) in files {
            let path = staged.dir.join(name);
            std::fs::write(&path, text).map_err(|e| io(&path, e))?;
        }
        Ok(staged)
    }

    /// The copy and the paths of the pair `names` in it.
    fn pair(self, names: &[&str]) -> (Staged, Vec<PathBuf>) {
        let paths = names.iter().map(|n| self.dir.join(n)).collect();
        (self, paths)
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}
