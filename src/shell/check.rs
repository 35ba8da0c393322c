//! A copy of a lab's shaders checked against the course's across the lab's states, not one:
//! the defaults, every object, the lab's states of record ([`crate::course::states`]) and
//! seeded random states across each parameter's slider range. At each state the two frames are
//! compared as `shaderlab diff` compares them ([`crate::debug::diff`]): the PSNR, the pixels
//! that differ, and for a state that fails the first line where the copy departs.
//!
//! The states are the same for the same lab, base state, count and seed (the generator is a
//! fixed SplitMix64 and every random value is rounded to what `--set` writes back, so a state's
//! `--set` list reproduces it exactly with `shaderlab diff`). The command line
//! (`shaderlab check`) and the page's Check run the same list.

use crate::debug::diff::{Diff, Divergence};
use crate::error::Result;
use crate::lab::LabEntry;
use crate::params::{Kind, Params};

/// The PSNR a state must reach to pass, by default (the references' own threshold).
pub const DEFAULT_MIN_DB: f64 = 40.0;

/// Random states checked by default, beside the lab's own.
pub const DEFAULT_RANDOM: usize = 8;

/// The most random states a check takes (each one a pair of frames and maybe two traces).
pub const MAX_RANDOM: usize = 1000;

/// Where a state comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Origin {
    /// The base state (the lab's defaults with the user's `--set`).
    Base,
    /// The base state on another object.
    Object,
    /// One of the lab's states of record (a reference or snapshot state).
    Record,
    /// Drawn at random across the parameters' slider ranges.
    Random,
}

impl Origin {
    /// The word for it.
    pub fn word(self) -> &'static str {
        match self {
            Origin::Base => "base",
            Origin::Object => "object",
            Origin::Record => "record",
            Origin::Random => "random",
        }
    }
}

/// One state: `--set` assignments on the base state, and where it comes from.
#[derive(Clone, Debug, PartialEq)]
pub struct State {
    /// The assignments, as `--set NAME=VALUE` writes them.
    pub set: Vec<(String, String)>,
    /// Where it comes from.
    pub origin: Origin,
}

impl State {
    /// The assignments on one line (`(the base state)` for none).
    pub fn line(&self) -> String {
        if self.set.is_empty() {
            "(the base state)".to_owned()
        } else {
            self.words().join(" ")
        }
    }

    /// The assignments as `NAME=VALUE` words.
    pub fn words(&self) -> Vec<String> {
        self.set.iter().map(|(n, v)| format!("{n}={v}")).collect()
    }

    /// `base` with this state's assignments (those `base` has: a reference pair may declare
    /// other uniforms).
    pub fn apply(&self, base: &Params) -> Result<Params> {
        let mut p = base.clone();
        for (name, value) in &self.set {
            if p.has(name) {
                p.set_str(name, value)?;
            }
        }
        p.check()?;
        Ok(p)
    }
}

/// SplitMix64: a generator whose sequence is fixed by its seed for good (a crate's generator
/// may change its sequence between versions, and a check's states must not).
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in 0..n.
    fn below(&mut self, n: usize) -> usize {
        ((self.unit() * n as f64) as usize).min(n.saturating_sub(1))
    }
}

/// The assignments that take `base` to `p`, in declaration order.
fn assignments(base: &Params, p: &Params) -> Vec<(String, String)> {
    p.specs()
        .iter()
        .filter(|s| p.get(s.name) != base.get(s.name))
        .map(|s| (s.name.to_owned(), p.text(s.name)))
        .collect()
}

/// The states to check `entry`'s lab at, from `base` (its defaults with the user's `--set`):
/// the base state, the base on every other object, the lab's states of record, then `random`
/// states drawn with `seed` across the sliders of every parameter the course has (the port's
/// additions, such as the tessellation, stay at the base's), each once.
pub fn states(entry: &LabEntry, base: &Params, random: usize, seed: u64) -> Vec<State> {
    let mut out = vec![State {
        set: Vec::new(),
        origin: Origin::Base,
    }];
    let push = |out: &mut Vec<State>, p: &Params, origin: Origin| {
        let set = assignments(base, p);
        if !out.iter().any(|s| s.set == set) {
            out.push(State { set, origin });
        }
    };
    if let Some(spec) = base.specs().iter().find(|s| s.name == "object") {
        if let Kind::Choice(names) = spec.kind {
            for name in names {
                let mut p = base.clone();
                if p.set_str("object", name).and_then(|_| p.check()).is_ok() {
                    push(&mut out, &p, Origin::Object);
                }
            }
        }
    }
    for state in crate::course::states::of(entry.info.name) {
        let mut p = base.clone();
        let applied = state.iter().try_for_each(|(n, v)| p.set_str(n, v).map(drop));
        if applied.and_then(|()| p.check()).is_ok() {
            push(&mut out, &p, Origin::Record);
        }
    }
    let widgets = super::panel::widgets(base.specs(), entry.info.keys.rows);
    let mut rng = SplitMix(seed);
    let mut drawn = 0;
    let mut tries = 0;
    while drawn < random.min(MAX_RANDOM) && tries < 20 * random.min(MAX_RANDOM) + 20 {
        tries += 1;
        let mut p = base.clone();
        for w in widgets.iter().filter(|w| w.group != super::panel::Group::Port) {
            let Some(current) = p.get(w.spec.name).map(<[f64]>::to_vec) else {
                continue;
            };
            let values: Vec<f64> = match w.spec.kind {
                Kind::Choice(names) => vec![rng.below(names.len()) as f64],
                Kind::Bool => vec![rng.below(2) as f64],
                Kind::Real | Kind::Int => (0..current.len())
                    .map(|c| match w.slider(c) {
                        Some((lo, hi)) => {
                            let v = lo + rng.unit() * (hi - lo);
                            if w.spec.kind == Kind::Int {
                                v.round()
                            } else {
                                // What `--set` writes back exactly.
                                (v * 1000.0).round() / 1000.0
                            }
                        }
                        None => current[c],
                    })
                    .collect(),
            };
            let _ = p.set(w.spec.name, &values);
        }
        if p.check().is_ok() {
            let before = out.len();
            push(&mut out, &p, Origin::Random);
            drawn += usize::from(out.len() > before);
        }
    }
    out
}

/// What a state gave.
pub struct Checked {
    /// The state.
    pub state: State,
    /// The comparison there, as `shaderlab diff` makes it.
    pub diff: Diff,
    /// Whether it passes: the pictures are the same, or at least the PSNR asked for.
    pub pass: bool,
}

impl Checked {
    /// The state compared, passing at `min_db`.
    pub fn new(state: State, diff: Diff, min_db: f64) -> Checked {
        let pass = diff.differing == 0 || diff.psnr >= min_db;
        Checked { state, diff, pass }
    }

    /// Its figure in words: `identical`, or the PSNR.
    pub fn figure(&self) -> String {
        if self.diff.differing == 0 {
            "identical".to_owned()
        } else {
            format!("{:.2} dB", self.diff.psnr)
        }
    }

    /// The first divergence, for a state that fails.
    pub fn divergence(&self) -> Option<&Divergence> {
        self.diff.first_divergence.as_ref().filter(|_| !self.pass)
    }
}

/// A whole check: the states, what each gave, and the threshold.
pub struct Report {
    /// The lab.
    pub lab: String,
    /// The pictures' size.
    pub size: (u32, u32),
    /// The PSNR a state must reach.
    pub min_db: f64,
    /// The states in order, each checked.
    pub states: Vec<Checked>,
}

impl Report {
    /// How many states passed.
    pub fn passed(&self) -> usize {
        self.states.iter().filter(|c| c.pass).count()
    }

    /// How many failed.
    pub fn failed(&self) -> usize {
        self.states.len() - self.passed()
    }

    /// The check for programs: one document, `{"lab", "size", "min_db", "states": [{"set",
    /// "origin", "psnr", "differing", "pass", "worst", "first_divergence"}], "passed",
    /// "failed"}`; a state's `first_divergence` (null where it passes) is `shaderlab diff
    /// --json`'s.
    pub fn json(&self) -> serde_json::Value {
        use serde_json::{json, Value};
        let states: Vec<Value> = self
            .states
            .iter()
            .map(|c| {
                let diff: Value = serde_json::from_str(&c.diff.json()).unwrap_or(Value::Null);
                json!({
                    "set": c.state.words(),
                    "origin": c.state.origin.word(),
                    "psnr": diff["psnr"],
                    "differing": c.diff.differing,
                    "pass": c.pass,
                    "worst": diff["worst"],
                    "first_divergence": if c.pass { Value::Null } else { diff["first_divergence"].clone() },
                })
            })
            .collect();
        json!({
            "lab": self.lab,
            "size": [self.size.0, self.size.1],
            "min_db": self.min_db,
            "states": states,
            "passed": self.passed(),
            "failed": self.failed(),
        })
    }

    /// The check for people: a line per state, then the counts.
    pub fn text(&self) -> String {
        use std::fmt::Write as _;
        let mut out = String::new();
        let _ = writeln!(
            out,
            "{}: {} states at {}x{}, passing at {} dB",
            self.lab,
            self.states.len(),
            self.size.0,
            self.size.1,
            self.min_db
        );
        for (k, c) in self.states.iter().enumerate() {
            let (db, set) = (c.figure(), c.state.line());
            let _ = writeln!(
                out,
                "{:>3} {} {:>10} {:>8} px  {set}",
                k + 1,
                if c.pass { "pass" } else { "FAIL" },
                db,
                c.diff.differing
            );
            if let Some(d) = c.divergence() {
                let at = c
                    .diff
                    .worst
                    .as_ref()
                    .map(|w| format!(" (worst pixel {},{})", w.x, w.y))
                    .unwrap_or_default();
                let _ = writeln!(
                    out,
                    "             first divergence: {}:{} `{}`: the copy {}, the reference {}{at}",
                    d.file,
                    d.line,
                    d.name,
                    crate::debug::diff::value_text(&d.mine),
                    d.reference
                        .as_ref()
                        .map_or_else(|| "(ended)".to_owned(), |r| crate::debug::diff::value_text(&r.value))
                );
            } else if !c.pass {
                for note in &c.diff.notes {
                    let _ = writeln!(out, "             note: {note}");
                }
            }
        }
        let _ = writeln!(out, "{} passed, {} failed", self.passed(), self.failed());
        out
    }
}

/// A check moved on a state at a time between frames ([`crate::shell::session::Session::poll`],
/// the page's Check): both labs are built once, each state's two frames are captured, read
/// back without blocking (or waited for, natively) and compared.
pub struct Checking {
    entry: &'static LabEntry,
    mine: Box<dyn crate::lab::Lab>,
    reference: Box<dyn crate::lab::Lab>,
    base: Params,
    reference_base: Params,
    states: Vec<State>,
    format: wgpu::TextureFormat,
    /// The state being captured: its two frames on their way.
    pending: Option<crate::debug::diff::Frames>,
    /// What the states checked so far gave.
    report: Report,
    /// Why the check stopped before its end, if it did.
    failed: Option<crate::error::Error>,
}

impl Checking {
    /// A check of the copy `mine` against `reference` (labs of `entry` drawing in `format`,
    /// each from its own parameters) at `states`, at `size`, passing at `min_db`.
    pub fn new(
        entry: &'static LabEntry,
        (mine, reference): (Box<dyn crate::lab::Lab>, Box<dyn crate::lab::Lab>),
        states: Vec<State>,
        (size, format): ((u32, u32), wgpu::TextureFormat),
        min_db: f64,
    ) -> Checking {
        let (base, reference_base) = (mine.params().clone(), reference.params().clone());
        Checking {
            entry,
            mine,
            reference,
            base,
            reference_base,
            report: Report {
                lab: entry.info.name.to_owned(),
                size,
                min_db,
                states: Vec::with_capacity(states.len()),
            },
            states,
            format,
            pending: None,
            failed: None,
        }
    }

    /// How many states it checks.
    pub fn len(&self) -> usize {
        self.states.len()
    }

    /// Whether it checks no state.
    pub fn is_empty(&self) -> bool {
        self.states.is_empty()
    }

    /// Whether every state was checked (or the check stopped).
    pub fn finished(&self) -> bool {
        self.failed.is_some() || self.report.states.len() == self.states.len()
    }

    /// The states checked so far.
    pub fn report(&self) -> &Report {
        &self.report
    }

    /// Why the check stopped before its end, if it did.
    pub fn failed(&self) -> Option<&crate::error::Error> {
        self.failed.as_ref()
    }

    /// The whole report (or why the check stopped), and the copy's lab (whose sources a report
    /// quotes).
    pub fn end(self) -> (Result<Report>, Box<dyn crate::lab::Lab>) {
        match self.failed {
            Some(e) => (Err(e), self.mine),
            None => (Ok(self.report), self.mine),
        }
    }

    /// Moves the check on without blocking (`wait`: waiting for the frames, natively): a
    /// state's frames that are back are compared, and the next state's captured. Returns
    /// whether a state was checked (or the check stopped).
    pub fn poll(&mut self, gpu: &crate::gpu::Gpu, wait: bool) -> bool {
        if self.finished() {
            return false;
        }
        let Some(pending) = &self.pending else {
            self.start(gpu);
            return self.failed.is_some();
        };
        let wait = wait && cfg!(not(target_arch = "wasm32"));
        if !wait && !pending.ready(gpu) {
            return false;
        }
        let frames = self.pending.take().expect("checked above").take(gpu, wait);
        let state = self.states[self.report.states.len()].clone();
        match frames.and_then(|(a, b)| crate::debug::diff::diff(self.entry.info.name, &a, &b)) {
            Ok(diff) => {
                let min_db = self.report.min_db;
                self.report.states.push(Checked::new(state, diff, min_db));
                if !self.finished() {
                    self.start(gpu);
                }
            }
            Err(e) => self.failed = Some(e),
        }
        true
    }

    /// Sets both labs to the next state and starts capturing their frames.
    fn start(&mut self, gpu: &crate::gpu::Gpu) {
        let state = &self.states[self.report.states.len()];
        let size = self.report.size;
        let started = state.apply(&self.base).and_then(|p| {
            *self.reference.params_mut() = state.apply(&self.reference_base)?;
            *self.mine.params_mut() = p;
            crate::debug::diff::Frames::start(gpu, self.mine.as_mut(), self.reference.as_mut(), size, self.format)
        });
        match started {
            Ok(both) => self.pending = Some(both),
            Err(e) => self.failed = Some(e),
        }
    }
}

/// Checks the copy `mine` against `reference` (labs of `entry`, built once and kept for every
/// state: their pipelines are reused, each drawn from its own parameters) at each of `states`,
/// at `size`, passing at `min_db`, waiting for each state's frames; `each` hears of every state
/// checked (a progress bar). Returns the report and the copy's lab.
#[cfg(not(target_arch = "wasm32"))]
pub fn run(
    gpu: &crate::gpu::Gpu,
    entry: &'static LabEntry,
    labs: (Box<dyn crate::lab::Lab>, Box<dyn crate::lab::Lab>),
    states: Vec<State>,
    size: (u32, u32),
    min_db: f64,
    mut each: impl FnMut(&Checked),
) -> (Result<Report>, Box<dyn crate::lab::Lab>) {
    let mut checking = Checking::new(entry, labs, states, (size, crate::offscreen::COLOR_FORMAT), min_db);
    while !checking.finished() {
        if checking.poll(gpu, true) {
            if let Some(last) = checking.report().states.last() {
                each(last);
            }
        }
    }
    checking.end()
}
