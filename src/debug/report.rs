//! The debugger's report: an [`Inspection`] (why a pixel has its colour) made from a replay,
//! and written for people ([`Inspection::text`], [`Inspection::rows`]) and for programs
//! ([`Inspection::json`]).

use std::fmt::Write as _;

use super::interp;
use super::replay::{self, replay, Named, Replayed};
use super::value;
use super::{locate, source_line, user_name, Captured};
use crate::error::{Error, Result};
use crate::shader::CompiledShader;

/// Which stage a step ran in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// The vertex shader (at one corner).
    Vertex,
    /// The fragment shader (at the pixel).
    Fragment,
}

impl Stage {
    fn name(self) -> &'static str {
        match self {
            Stage::Vertex => "vertex",
            Stage::Fragment => "fragment",
        }
    }
}

/// One step of the trace, placed in the user's file.
#[derive(Clone, Debug, PartialEq)]
pub struct TraceStep {
    /// The stage.
    pub stage: Stage,
    /// For a vertex step, which corner (0–2).
    pub corner: Option<usize>,
    /// The file, as shown to the user.
    pub file: String,
    /// The 1-based line.
    pub line: u32,
    /// What it did: the variable assigned (`L`, `color.rgb`), or `if`, `loop`, `call f`,
    /// `discard`.
    pub name: String,
    /// Its value's components (bools as 0/1; the iteration for `loop`; 1/0 for `if`): at most
    /// [`interp::MAX_COMPONENTS`].
    pub value: Vec<f64>,
    /// The value's components left out after those (an array's later elements).
    pub more: usize,
    /// Whether the value is a bool.
    pub boolean: bool,
}

/// Steps of one line left out of the trace (past [`interp::HEAD_STEPS`], before the last
/// [`interp::TAIL_STEPS`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Dropped {
    /// The stage.
    pub stage: Stage,
    /// The file.
    pub file: String,
    /// The 1-based line.
    pub line: u32,
    /// How many steps (one per corner at a vertex step).
    pub steps: usize,
}

impl TraceStep {
    /// The step in words: `L = (0.1, 0.2, 0.9)`, `if → then`, `iteration 3`, `call f`, with
    /// the corner first for a vertex step (`[1] v = …`).
    pub fn describe(&self) -> String {
        let corner = self.corner.map(|c| format!("[{c}] ")).unwrap_or_default();
        let v = match (self.boolean, self.value.as_slice()) {
            (true, [b]) if self.more == 0 => (if *b != 0.0 { "true" } else { "false" }).to_owned(),
            _ if self.more > 0 => format!(
                "({}, … {} more)",
                self.value.iter().map(|x| num(*x)).collect::<Vec<_>>().join(", "),
                self.more
            ),
            _ => vector(&self.value),
        };
        match self.name.as_str() {
            "if" => format!(
                "{corner}if → {}",
                if self.value.first() == Some(&1.0) {
                    "then"
                } else {
                    "else"
                }
            ),
            "loop" => format!("{corner}iteration {v}"),
            n if n.starts_with("call ") || n == "discard" => format!("{corner}{n}"),
            n => format!("{corner}{n} = {v}"),
        }
    }
}

/// A line of a shader that ran, with what it computed.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The file.
    pub file: String,
    /// The 1-based line.
    pub line: u32,
    /// The line as written (trimmed).
    pub text: String,
    /// Its steps in words, `; `-separated.
    pub values: String,
}

/// Why a pixel has its colour.
#[derive(Clone, Debug)]
pub struct Inspection {
    /// The lab.
    pub lab: String,
    /// The pixel: column and row from the top left.
    pub x: u32,
    /// Its row.
    pub y: u32,
    /// The picture's size.
    pub width: u32,
    /// Its height.
    pub height: u32,
    /// The replay.
    pub replayed: Replayed,
    /// Every step kept, vertex corners first, then the fragment.
    pub steps: Vec<TraceStep>,
    /// The steps left out, by line.
    pub dropped: Vec<Dropped>,
    /// What the replay cannot promise for the adapter that drew the frame ([`caveats`]).
    pub caveats: Vec<String>,
    /// The RGBA bytes the GPU stored at the pixel in the frame that was captured
    /// ([`Captured::picture`]), beside the replay's ([`Replayed::pixel`]); none where the
    /// frame was not run.
    pub gpu_pixel: Option<[u8; 4]>,
    /// The steps the fragment shader's trace lists (kept and left out): the pixel's cost, as
    /// a cost view ([`super::view`]) counts it on the GPU.
    pub cost: usize,
}

/// How far the replay's stored byte may be from the GPU's, per channel, before an inspection
/// says that the two disagree.
pub const GPU_TOLERANCE: u8 = 2;

/// The replay follows llvmpipe's rules (Mesa 22.3, the same through 24.0): what it cannot
/// promise about a frame drawn by `adapter` (name and driver, as [`Captured::adapter`]), with
/// an `anisotropic` sampler bound to the covering draw or not. Empty for lavapipe 22.3–24.0.
pub fn caveats(adapter: &str, anisotropic: bool) -> Vec<String> {
    let llvmpipe = adapter.to_ascii_lowercase().contains("llvmpipe");
    let mesa = adapter.split("Mesa ").nth(1).and_then(|v| {
        let mut parts = v.split(|c: char| !c.is_ascii_digit());
        Some((parts.next()?.parse::<u32>().ok()?, parts.next()?.parse::<u32>().ok()?))
    });
    let who = if adapter.trim_matches([' ', ',']).is_empty() {
        "this GPU"
    } else {
        adapter
    };
    let mut out = Vec::new();
    if !llvmpipe {
        out.push(format!(
            "replayed by the rules of llvmpipe (lavapipe); on {who} a pixel on a triangle's edge or a texel boundary can differ by a step"
        ));
    }
    let known = llvmpipe && mesa.is_some_and(|m| ((22, 3)..=(24, 0)).contains(&m));
    if anisotropic && !known {
        out.push(format!(
            "anisotropic filtering is replayed as llvmpipe of Mesa 22.3–24.0 does it (an elliptical weighted average); {who} may filter differently, so lookups through this draw's anisotropic sampler are approximate"
        ));
    }
    out
}

/// A replay's failure as the user reads it: at the file and line of the user's source it met,
/// with the line.
pub(crate) fn replay_error(e: super::error::ReplayError) -> Error {
    match e.at {
        Some((shader, span)) => match locate(&shader, span) {
            Some((file, line)) => {
                let text = source_line(&shader, &file, line).unwrap_or("").trim();
                Error::Debug(format!("{file}:{line}: {}\n    {line} | {text}", e.message))
            }
            None => Error::Debug(format!("{}: {}", shader.path, e.message)),
        },
        None => Error::Debug(e.message),
    }
}

/// The steps of `trace` (one lane per corner for the vertex stage) as the report lists them,
/// in the user's files and names; the steps left out are counted in `dropped`.
pub(crate) fn steps_of(
    stage: Stage,
    shader: &CompiledShader,
    trace: &interp::Trace,
    out: &mut Vec<TraceStep>,
    dropped: &mut Vec<Dropped>,
) {
    for step in &trace.steps {
        // The translator's own `main` (it calls the user's) is not the user's code.
        if shader.translated && step.function.as_deref() == Some("main") {
            continue;
        }
        let Some((file, line)) = locate(shader, step.span) else {
            continue;
        };
        let name = match &step.kind {
            interp::StepKind::Assign(n) => user_name(shader, n),
            interp::StepKind::Branch => "if".into(),
            interp::StepKind::Iteration => "loop".into(),
            interp::StepKind::Call(f) => format!("call {}", user_name(shader, f)),
            interp::StepKind::Discard => "discard".into(),
        };
        let boolean = step.kinds.iter().all(|k| *k == value::Kind::Bool) && !step.kinds.is_empty();
        for (lane, v) in step.values.iter().enumerate() {
            let Some(v) = v else { continue };
            out.push(TraceStep {
                stage,
                corner: (stage == Stage::Vertex).then_some(lane),
                file: file.clone(),
                line,
                name: name.clone(),
                value: v.clone(),
                more: step.more,
                boolean,
            });
        }
    }
    for &(span, steps) in &trace.dropped {
        // Steps no line holds are not shown when kept either.
        let Some((file, line)) = locate(shader, span) else {
            continue;
        };
        match dropped
            .iter_mut()
            .find(|d| d.stage == stage && d.file == file && d.line == line)
        {
            Some(d) => d.steps += steps,
            None => dropped.push(Dropped {
                stage,
                file,
                line,
                steps,
            }),
        }
    }
}

impl Inspection {
    /// The inspection of pixel (x, y) of a captured frame of lab `lab`.
    pub fn new(lab: &str, captured: &Captured, x: u32, y: u32) -> Result<Inspection> {
        let (width, height) = captured.passes.last().map_or((0, 0), |p| (p.1, p.2));
        let replayed = replay(captured, x, y).map_err(replay_error)?;
        let mut steps = Vec::new();
        let mut dropped = Vec::new();
        let mut anisotropic = false;
        if let Some(f) = &replayed.fragment {
            steps_of(Stage::Vertex, &f.vertex, &f.vertex_steps, &mut steps, &mut dropped);
            steps_of(
                Stage::Fragment,
                &f.fragment,
                &f.fragment_steps,
                &mut steps,
                &mut dropped,
            );
            anisotropic = captured
                .draws
                .get(f.draw)
                .is_some_and(|d| d.samplers.iter().any(|(_, s)| s.anisotropy > 1));
        }
        let mut caveats = caveats(&captured.adapter, anisotropic);
        if let Some(f) = &replayed.fragment {
            let stages = [
                (&f.vertex, &f.vertex_undefined, "vertex"),
                (&f.fragment, &f.fragment_undefined, "fragment"),
            ];
            for (shader, notes, stage) in stages {
                for (span, what) in notes {
                    let at = locate(shader, *span)
                        .map(|(file, line)| format!("{file}:{line}"))
                        .unwrap_or_else(|| format!("the {stage} shader"));
                    caveats.push(format!("{at}: {what}; the replay gives what lavapipe gives"));
                }
            }
        }
        let gpu_pixel = captured
            .picture
            .as_ref()
            .and_then(|p| (x < p.width() && y < p.height()).then(|| p.get_pixel(x, y).0));
        let cost = steps.iter().filter(|s| s.stage == Stage::Fragment).count()
            + dropped
                .iter()
                .filter(|d| d.stage == Stage::Fragment)
                .map(|d| d.steps)
                .sum::<usize>();
        Ok(Inspection {
            cost,
            lab: lab.to_owned(),
            x,
            y,
            width,
            height,
            replayed,
            steps,
            dropped,
            caveats,
            gpu_pixel,
        })
    }

    /// Where the GPU stored a pixel more than [`GPU_TOLERANCE`] from the replay's in any
    /// channel: the two in words (the replay does not follow this GPU's rules there).
    pub fn disagreement(&self) -> Option<String> {
        let gpu = self.gpu_pixel?;
        let cpu = self.replayed.pixel;
        let off = (0..4).map(|k| cpu[k].abs_diff(gpu[k])).max().unwrap_or(0);
        (off > GPU_TOLERANCE).then(|| {
            format!(
                "the GPU stored rgba({}, {}, {}, {}) at this pixel but the replay gives rgba({}, {}, {}, {}) ({off}/255 apart, more than {GPU_TOLERANCE}/255): the replay does not follow what this GPU did here, so its values may not be the GPU's",
                gpu[0], gpu[1], gpu[2], gpu[3], cpu[0], cpu[1], cpu[2], cpu[3]
            )
        })
    }

    /// The GPU's byte beside the replay's, for the report's last lines: `; the GPU stored
    /// rgba(…)`, then the disagreement on its own line where there is one.
    fn gpu_words(&self) -> String {
        let Some(g) = self.gpu_pixel else {
            return String::new();
        };
        let mut out = format!("; the GPU stored rgba({}, {}, {}, {})", g[0], g[1], g[2], g[3]);
        if let Some(words) = self.disagreement() {
            let _ = write!(out, "\nwarning: {words}");
        }
        out
    }

    /// How many steps were left out of [`Inspection::steps`] (one per corner at a vertex step).
    pub fn steps_dropped(&self) -> usize {
        self.dropped.iter().map(|d| d.steps).sum()
    }

    /// Whether a primitive covers the pixel.
    pub fn covered(&self) -> bool {
        self.replayed.fragment.is_some()
    }

    /// The report for people: what covers the pixel, the corners, the inputs, the fragment
    /// shader line by line with the values each line computed, and the stored colour.
    pub fn text(&self) -> String {
        let mut out = String::new();
        let r = &self.replayed;
        let _ = writeln!(
            out,
            "{}: pixel {},{} of {}x{}",
            self.lab, self.x, self.y, self.width, self.height
        );
        let Some(f) = &r.fragment else {
            let c = r.clear;
            let _ = writeln!(
                out,
                "no triangle covers this pixel: the clear colour ({}, {}, {}) shows, stored as rgba({}, {}, {}, {}){}",
                num(c[0]),
                num(c[1]),
                num(c[2]),
                r.pixel[0],
                r.pixel[1],
                r.pixel[2],
                r.pixel[3],
                self.gpu_words()
            );
            return out;
        };
        let what = if f.points { "point" } else { "triangle" };
        let ids: Vec<String> = f.corners.iter().map(|c| c.index.to_string()).collect();
        let _ = writeln!(
            out,
            "covered by {what} {} of draw {} (`{}`; vertices {}), {}, depth {}{}",
            f.primitive,
            f.draw,
            f.label,
            ids.join(", "),
            if f.front_facing { "front-facing" } else { "back-facing" },
            num(f64::from(f.depth)),
            if r.covering > 1 {
                format!("; {} fragments covered the pixel, this one stayed", r.covering)
            } else {
                String::new()
            }
        );
        let _ = writeln!(out, "\nvertex shader {} at the corners:", f.vertex.path);
        let corner_row = |out: &mut String, label: &str, pick: &dyn Fn(&replay::Corner) -> &Vec<Named>| {
            let Some(first) = f.corners.first() else { return };
            for (k, n) in pick(first).iter().enumerate() {
                let values: Vec<String> = f.corners.iter().map(|c| vector(&pick(c)[k].value)).collect();
                let _ = writeln!(out, "  {label} {} = {}", n.name, values.join(" | "));
            }
        };
        corner_row(&mut out, "in ", &|c| &c.inputs);
        self.listing(&mut out, Stage::Vertex, &f.vertex);
        corner_row(&mut out, "out", &|c| &c.outputs);
        let _ = writeln!(out, "\nfragment inputs at the pixel:");
        for n in &f.inputs {
            let _ = writeln!(out, "  {} = {}", n.name, vector(&n.value));
        }
        let _ = writeln!(out, "\nfragment shader {}:", f.fragment.path);
        self.listing(&mut out, Stage::Fragment, &f.fragment);
        let _ = writeln!(out, "\ncost: {} steps of the fragment shader", self.cost);
        let dropped = self.steps_dropped();
        if dropped > 0 {
            let _ = writeln!(
                out,
                "\n{dropped} steps not kept: a shader's trace keeps its first {} and its last {} (one per corner at a vertex step); each line above says how many it lost",
                interp::HEAD_STEPS,
                interp::TAIL_STEPS
            );
        }
        let c = r.color;
        let _ = writeln!(
            out,
            "\ncolour {} → stored rgba({}, {}, {}, {}){}",
            vector(&c.map(f64::from)),
            r.pixel[0],
            r.pixel[1],
            r.pixel[2],
            r.pixel[3],
            self.gpu_words()
        );
        for caveat in &self.caveats {
            let _ = writeln!(out, "note: {caveat}");
        }
        out
    }

    /// The lines of the shader that ran in `stage`, in file order (the main file first, then
    /// the included ones), each with what its steps computed.
    pub fn rows(&self, stage: Stage) -> Vec<Row> {
        let Some(f) = &self.replayed.fragment else {
            return Vec::new();
        };
        let shader = if stage == Stage::Vertex { &f.vertex } else { &f.fragment };
        let mut lines: Vec<(&str, u32)> = Vec::new();
        let here = self
            .steps
            .iter()
            .map(|s| (s.stage, s.file.as_str(), s.line))
            .chain(self.dropped.iter().map(|d| (d.stage, d.file.as_str(), d.line)));
        for (s, file, line) in here {
            if s == stage && !lines.contains(&(file, line)) {
                lines.push((file, line));
            }
        }
        let order: Vec<&str> = shader.source.files.iter().map(|(p, _)| p.as_str()).collect();
        lines.sort_by_key(|(file, line)| (order.iter().position(|p| p == file).unwrap_or(usize::MAX), *line));
        lines
            .into_iter()
            .map(|(file, line)| {
                // What the line computed; its calls show at the called function's lines.
                let here: Vec<&TraceStep> = self
                    .steps
                    .iter()
                    .filter(|s| s.stage == stage && s.file == file && s.line == line && !s.name.starts_with("call "))
                    .collect();
                let mut said = String::new();
                for (i, s) in here.iter().enumerate() {
                    if i >= 12 {
                        let _ = write!(said, "; … ({} more)", here.len() - i);
                        break;
                    }
                    if !said.is_empty() {
                        said.push_str("; ");
                    }
                    said.push_str(&s.describe());
                }
                let lost: usize = self
                    .dropped
                    .iter()
                    .filter(|d| d.stage == stage && d.file == file && d.line == line)
                    .map(|d| d.steps)
                    .sum();
                if lost > 0 {
                    if !said.is_empty() {
                        said.push_str("; ");
                    }
                    let _ = write!(said, "{lost} steps not kept");
                }
                Row {
                    file: file.to_owned(),
                    line,
                    text: source_line(shader, file, line).unwrap_or("").trim().to_owned(),
                    values: said,
                }
            })
            .collect()
    }

    fn listing(&self, out: &mut String, stage: Stage, shader: &CompiledShader) {
        let mut current = String::new();
        for row in self.rows(stage) {
            if row.file != current {
                if row.file != shader.path {
                    let _ = writeln!(out, "  {}:", row.file);
                }
                current = row.file.clone();
            }
            let _ = writeln!(out, "  {:>4} | {}", row.line, row.text);
            let _ = writeln!(out, "       ⇒ {}", row.values);
        }
    }

    /// The report for programs: one JSON object with `pixel` (the stored RGBA bytes),
    /// `gpu_pixel` (the GPU's, or null where the frame was not run; with `gpu_disagrees`, in
    /// words, where they differ by more than [`GPU_TOLERANCE`]), `covered`, and `trace` (steps with `stage`, `file`, `line`, `name`, `value`), and the
    /// covering draw, corners, inputs, the listing by line and the caveats. A step's `more`
    /// counts its value's components left out; `dropped` lists the steps left out, by line.
    /// Numbers JSON cannot hold are the strings `"NaN"`, `"Infinity"` and `"-Infinity"`.
    pub fn json(&self) -> String {
        use serde_json::{json, Value};
        let r = &self.replayed;
        let value = |v: &[f64]| -> Value {
            match v {
                [x] => json_number(*x),
                _ => v.iter().map(|x| json_number(*x)).collect(),
            }
        };
        let floats = |v: &[f32]| -> Value { v.iter().map(|x| json_number(f64::from(*x))).collect() };
        let named =
            |v: &[Named]| -> Value { Value::Object(v.iter().map(|n| (n.name.clone(), value(&n.value))).collect()) };
        let listing = |stage: Stage| -> Value {
            self.rows(stage)
                .iter()
                .map(|r| json!({"file": r.file, "line": r.line, "text": r.text, "values": r.values}))
                .collect()
        };
        let trace: Value = self
            .steps
            .iter()
            .map(|s| {
                let mut step = json!({
                    "stage": s.stage.name(), "file": s.file, "line": s.line, "name": s.name, "value": value(&s.value)
                });
                if let Some(c) = s.corner {
                    step["corner"] = json!(c);
                }
                if s.more > 0 {
                    step["more"] = json!(s.more);
                }
                step
            })
            .collect();
        let mut o = json!({
            "lab": self.lab, "x": self.x, "y": self.y, "width": self.width, "height": self.height,
            "pixel": r.pixel, "covered": self.covered(), "color": floats(&r.color), "clear": value(&r.clear),
            "listing": {"vertex": listing(Stage::Vertex), "fragment": listing(Stage::Fragment)},
            "caveats": self.caveats, "trace": trace, "gpu_pixel": self.gpu_pixel, "cost": self.cost,
        });
        if let Some(words) = self.disagreement() {
            o["gpu_disagrees"] = json!(words);
        }
        if !self.dropped.is_empty() {
            o["dropped"] = self
                .dropped
                .iter()
                .map(|d| json!({"stage": d.stage.name(), "file": d.file, "line": d.line, "steps": d.steps}))
                .collect();
        }
        if let Some(f) = &r.fragment {
            let corners: Value = f
                .corners
                .iter()
                .map(|c| json!({"index": c.index, "inputs": named(&c.inputs), "outputs": named(&c.outputs)}))
                .collect();
            let covering = json!({
                "draw": f.draw, "label": f.label, "primitive": f.primitive, "points": f.points,
                "vertex_shader": f.vertex.path, "fragment_shader": f.fragment.path,
                "depth": json_number(f64::from(f.depth)),
                "front_facing": f.front_facing, "covering": r.covering, "corners": corners,
                "inputs": named(&f.inputs), "steps_dropped": self.steps_dropped(),
            });
            if let (Some(o), Value::Object(more)) = (o.as_object_mut(), covering) {
                o.extend(more);
            }
        }
        o.to_string()
    }
}

/// A number in JSON: itself where JSON holds it, else `"NaN"`, `"Infinity"` or `"-Infinity"`
/// (so that the three stay apart; JSON has no such numbers).
pub fn json_number(v: f64) -> serde_json::Value {
    if v.is_nan() {
        "NaN".into()
    } else if v.is_infinite() {
        (if v > 0.0 { "Infinity" } else { "-Infinity" }).into()
    } else {
        serde_json::json!(v)
    }
}

/// A number as people read it: up to 4 decimals, no trailing zeros.
pub(crate) fn num(v: f64) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.to_owned()
    }
}

fn vector(v: &[f64]) -> String {
    match v {
        [x] => num(*x),
        _ => format!("({})", v.iter().map(|x| num(*x)).collect::<Vec<_>>().join(", ")),
    }
}
