//! `shaderlab check NAME --shaders DIR [--states N] [--seed S] [--min-db D] [--json]
//! [--report DIR] [FLAGS…]`: a copy of a lab's shaders checked against the course's at the
//! lab's states ([`super::check`]), in one process on one device: both labs are built once and
//! drawn at every state. Status 0 when every state passes, 1 when one fails (or the copy cannot
//! be checked), 2 for a usage error. `legacy`'s pair is checked against another pair,
//! `--reference VERT0 FRAG0`.

use std::ffi::OsString;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use super::args::Args;
use super::check::{self, Checked, Report};
use super::cli::{say, Failure};
use super::diff_verb::{pair, Pair};
use super::verbs::Mode;
use crate::error::{Error, Result};
use crate::lab::{Lab, LabEntry};

/// The usage line.
pub const USAGE: &str = "shaderlab check NAME --shaders DIR [--states N] [--seed S] [--min-db D] [--json] \
[--report DIR] [FLAGS…]\n       \
shaderlab check legacy VERT FRAG --reference VERT0 FRAG0 [--states N] [--seed S] [--min-db D] [--json] [--report DIR] [FLAGS…]";

/// What `check` takes besides the lab's flags.
struct Own {
    random: usize,
    seed: u64,
    min_db: f64,
    json: bool,
    report: Option<PathBuf>,
    reference: Option<Vec<PathBuf>>,
}

/// Takes `check`'s own flags out of `argv` (the lab's flags stay).
fn take_own(argv: Vec<OsString>) -> std::result::Result<(Own, Vec<OsString>), String> {
    let mut own = Own {
        random: check::DEFAULT_RANDOM,
        seed: 0,
        min_db: check::DEFAULT_MIN_DB,
        json: false,
        report: None,
        reference: None,
    };
    let mut rest = Vec::with_capacity(argv.len());
    let mut words = argv.into_iter().peekable();
    let value = |word: Option<OsString>| word.filter(|w| !w.to_string_lossy().starts_with("--"));
    while let Some(word) = words.next() {
        let text = word.to_string_lossy().into_owned();
        let (flag, inline) = match text.split_once('=') {
            Some((f, v)) if f.starts_with("--") => (f.to_owned(), Some(OsString::from(v))),
            _ => (text.clone(), None),
        };
        let mut one = |what: &str| -> std::result::Result<String, String> {
            inline
                .clone()
                .or_else(|| value(words.next()))
                .map(|v| v.to_string_lossy().into_owned())
                .ok_or_else(|| format!("`{flag}` needs {what}"))
        };
        match flag.as_str() {
            "--json" => own.json = true,
            "--states" => {
                let n = one("a count: --states N")?;
                own.random = n
                    .parse::<usize>()
                    .ok()
                    .filter(|n| *n <= check::MAX_RANDOM)
                    .ok_or_else(|| {
                        format!(
                            "`--states {n}`: the random states to add, a whole number from 0 to {}",
                            check::MAX_RANDOM
                        )
                    })?;
            }
            "--seed" => {
                let s = one("a number: --seed S")?;
                own.seed = s
                    .parse::<u64>()
                    .map_err(|_| format!("`--seed {s}`: a whole number from 0 to {}", u64::MAX))?;
            }
            "--min-db" => {
                let d = one("a PSNR in dB: --min-db D")?;
                own.min_db = d
                    .parse::<f64>()
                    .ok()
                    .filter(|d| d.is_finite() && *d > 0.0 && *d <= 1000.0)
                    .ok_or_else(|| format!("`--min-db {d}`: a PSNR in dB, above 0 and at most 1000"))?;
            }
            "--report" => own.report = Some(PathBuf::from(one("a folder: --report DIR")?)),
            "--reference" => match (value(words.next()), value(words.next())) {
                (Some(vert), Some(frag)) => own.reference = Some(vec![PathBuf::from(vert), PathBuf::from(frag)]),
                _ => return Err("`--reference` needs two files: --reference VERT0 FRAG0".into()),
            },
            _ => rest.push(word),
        }
    }
    Ok((own, rest))
}

/// `shaderlab check NAME …` (program name first).
pub fn check_main_from(entry: &'static LabEntry, argv: Vec<OsString>) -> ExitCode {
    super::ensure_runtime_dir();
    let name = entry.info.name;
    let usage = |why: &str| {
        let _ = writeln!(std::io::stderr(), "shaderlab check: {why}\n\nUsage: {USAGE}");
        ExitCode::from(2)
    };
    let (own, argv) = match take_own(argv) {
        Ok(split) => split,
        Err(e) => return usage(&e),
    };
    let args = Args::parse_from_for(entry, argv);
    if let Some(which) = super::diff_verb::which(entry, &args, own.reference.is_some(), "check against") {
        return usage(&which);
    }
    super::cli::skip_display_device_select();
    match run(entry, &args, &own) {
        Ok(report) if report.failed() == 0 => ExitCode::SUCCESS,
        Ok(_) => ExitCode::from(1),
        Err(failure) => {
            let _ = writeln!(std::io::stderr(), "{name}: error: {}", failure.error);
            if crate::gpu::hung() {
                crate::fsutil::signals::exit_now(i32::from(failure.code));
            }
            ExitCode::from(failure.code)
        }
    }
}

fn run(entry: &'static LabEntry, args: &Args, own: &Own) -> std::result::Result<Report, Failure> {
    let report_file = own.report.as_ref().map(|dir| dir.join("index.html"));
    if let Some(dir) = &own.report {
        crate::fsutil::NewDir::check(dir)?;
    }
    let Pair {
        gpu,
        mut mine,
        mut reference,
        params,
        reference_params,
        size,
    } = pair(entry, args, own.reference.as_ref(), Mode::Check, &[])?;
    if let (Some(dir), Some(file)) = (&own.report, &report_file) {
        // Both labs have read their shaders and the files they include: the report may
        // replace none of them (a folder still to be made holds none).
        if dir.is_dir() {
            crate::fsutil::check_output_path(file)?;
        }
    }
    let states = check::states(entry, &params, own.random, own.seed);
    *mine.params_mut() = params;
    *reference.params_mut() = reference_params;
    let bar = super::progress_bar(states.len() as u64, &format!("{}: checking", entry.info.name));
    let (report, mut mine) = check::run(&gpu, entry, (mine, reference), states, size, own.min_db, |_| bar.inc(1));
    let report = report?;
    bar.finish_and_clear();
    if let (Some(dir), Some(file)) = (&own.report, &report_file) {
        let html = report_html(&report, mine.as_mut())?;
        let made = crate::fsutil::NewDir::create(dir)?;
        crate::fsutil::write_atomic(file, |w| w.write_all(html.as_bytes()))?;
        made.keep();
        eprintln!("wrote {}", file.display());
    }
    if own.json {
        say(&report.json().to_string())?;
    } else {
        super::cli::print(&report.text())?;
    }
    Ok(report)
}

/// `text` with HTML's special characters written as entities.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// `image` as a PNG in a `data:` address, so that the report needs no file beside it.
fn data_png(image: &image::RgbaImage) -> Result<String> {
    use base64::Engine as _;
    let mut png = Vec::new();
    crate::offscreen::write_png(image, &mut png).map_err(|e| Error::Internal(format!("encoding a PNG: {e}")))?;
    Ok(format!(
        "data:image/png;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(png)
    ))
}

/// The text of `file` (a display path, as a trace names it) among `lab`'s shaders.
fn source_of(lab: &mut dyn Lab, file: &str) -> Option<String> {
    for program in lab.programs() {
        let (v, f) = program.shaders();
        for shader in [v, f] {
            if let Some((_, text)) = shader.source.files.iter().find(|(p, _)| p == file) {
                return Some(text.clone());
            }
        }
    }
    None
}

/// The copy's source around a failing state's first divergence, the line marked, with both
/// values.
fn listing(c: &Checked, mine: &mut dyn Lab) -> String {
    let Some(d) = c.divergence() else {
        return String::new();
    };
    let mut out = format!(
        "<p class=\"why\"><b>{}:{}</b> <code>{}</code>: the copy {}, the reference {} ({})</p>",
        escape(&d.file),
        d.line,
        escape(&d.name),
        escape(&crate::debug::diff::value_text(&d.mine)),
        escape(
            &d.reference
                .as_ref()
                .map_or_else(|| "(ended)".to_owned(), |r| crate::debug::diff::value_text(&r.value))
        ),
        escape(&d.why)
    );
    if let Some(text) = source_of(mine, &d.file) {
        let lines: Vec<&str> = text.lines().collect();
        let at = d.line as usize;
        let (from, to) = (at.saturating_sub(4).max(1), (at + 3).min(lines.len()));
        out.push_str("<pre class=\"source\">");
        for n in from..=to {
            let line = lines.get(n - 1).copied().unwrap_or("");
            let mark = if n == at { " class=\"at\"" } else { "" };
            out.push_str(&format!("<span{mark}>{n:>5} | {}</span>\n", escape(line)));
        }
        out.push_str("</pre>");
    }
    out
}

/// The report: a self-contained page (its pictures inside it) with a row per state: the
/// copy's picture, the course's and their difference, and for a failing state the copy's
/// source around the line where it departs, with both values.
fn report_html(report: &Report, mine: &mut dyn Lab) -> Result<String> {
    let mut rows = String::new();
    for (k, c) in report.states.iter().enumerate() {
        let (copy, course) = (&c.diff.frames.0, &c.diff.frames.1);
        let (db, set) = (c.figure(), c.state.line());
        rows.push_str(&format!(
            "<tr class=\"{}\"><td>{}</td><td><b>{}</b><br>{db}<br>{} px differ<br><small>{}</small></td>\
             <td class=\"state\"><code>{}</code>{}</td>\
             <td><img src=\"{}\" alt=\"the copy\"></td><td><img src=\"{}\" alt=\"the course\"></td><td><img src=\"{}\" alt=\"the difference\"></td></tr>\n",
            if c.pass { "pass" } else { "fail" },
            k + 1,
            if c.pass { "pass" } else { "FAIL" },
            c.diff.differing,
            c.state.origin.word(),
            escape(&set),
            listing(c, mine),
            data_png(copy)?,
            data_png(course)?,
            data_png(&c.diff.picture)?,
        ));
    }
    Ok(format!(
        "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>shaderlab check {lab}</title>\n<style>\
body{{font:14px system-ui,sans-serif;margin:1em}} table{{border-collapse:collapse}} td{{border:1px solid #ccc;padding:4px;vertical-align:top}}\
tr.fail td:first-child{{background:#fdd}} tr.pass td:first-child{{background:#dfd}} img{{width:240px;image-rendering:pixelated}}\
td.state{{max-width:420px;overflow-wrap:anywhere}} pre.source{{background:#f6f6f6;padding:4px;margin:4px 0;white-space:pre-wrap}}\
pre.source .at{{background:#ffd54f;display:inline-block;width:100%}} p.why{{margin:2px 0}}\
</style></head><body>\n<h1>shaderlab check: {lab}</h1>\n<p>{n} states at {w}x{h}, passing at {min} dB: <b>{passed} passed, {failed} failed</b>.</p>\n\
<table><tr><th>#</th><th>result</th><th>state (--set) and where the copy departs</th><th>the copy</th><th>the course</th><th>difference</th></tr>\n{rows}</table>\n</body></html>\n",
        lab = escape(&report.lab),
        n = report.states.len(),
        w = report.size.0,
        h = report.size.1,
        min = report.min_db,
        passed = report.passed(),
        failed = report.failed(),
    ))
}
