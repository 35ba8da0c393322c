//! Where a copy of a lab's shaders departs from a reference: the same frame captured twice
//! (the copy's shaders and the reference's, at the same state), compared pixel by pixel (a
//! picture of the difference, PSNR, the number of pixels that differ, the worst one), then
//! where the copy departs, in the order the shaders run:
//!
//! - the vertex stage as vertices: each draw's vertex shader run over the same vertices in
//!   both frames, and the first vertex whose outputs differ traced in both. A vertex-shader bug
//!   that moves the surface covers a pixel with other triangles in the two frames, whose traces
//!   are not runs of the same vertex; compared vertex by vertex, they are.
//! - where every vertex agrees, the worst pixel traced in both ([`Inspection`]).
//!
//! The first step whose name or value differs is the line where the copy departs.

use image::RgbaImage;

use super::replay::{self, CHUNK};
use super::{Captured, CapturedDraw, Inspection, Stage, TraceStep};
use crate::error::{Error, Result};

/// How far apart two traced values may be, relative to the larger (or absolutely below 1),
/// and still be the same value: the two copies may compute one value in a different order.
pub const VALUE_TOLERANCE: f64 = 1e-4;

/// The pixel that differs most.
#[derive(Clone, Debug, PartialEq)]
pub struct Worst {
    /// Its column from the left.
    pub x: u32,
    /// Its row from the top.
    pub y: u32,
    /// The copy's RGBA bytes there.
    pub mine: [u8; 4],
    /// The reference's.
    pub reference: [u8; 4],
}

/// The first step, in the order the shaders ran, at which the copy's trace departs from the
/// reference's.
#[derive(Clone, Debug, PartialEq)]
pub struct Divergence {
    /// The stage.
    pub stage: Stage,
    /// For a vertex step at the worst pixel, the corner (0–2) of the triangle covering it.
    pub corner: Option<usize>,
    /// For a vertex compared as a vertex: the draw and the vertex's index.
    pub vertex: Option<VertexAt>,
    /// The copy's file.
    pub file: String,
    /// Its 1-based line.
    pub line: u32,
    /// What the copy's step did there (`L`, `if`, `call f`).
    pub name: String,
    /// The copy's value (empty where the copy's trace had ended).
    pub mine: Vec<f64>,
    /// The reference's step there: its file, line, name and value (none where the
    /// reference's trace had ended).
    pub reference: Option<TraceStep>,
    /// How they differ, in words.
    pub why: String,
}

/// A vertex of a frame: which draw, and its index in the draw's vertex buffer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VertexAt {
    /// The draw, in the frame's order.
    pub draw: usize,
    /// The vertex's index.
    pub index: u32,
}

/// The comparison of a copy's frame with the reference's.
#[derive(Clone, Debug)]
pub struct Diff {
    /// The lab.
    pub lab: String,
    /// The picture's width.
    pub width: u32,
    /// Its height.
    pub height: u32,
    /// PSNR over the RGB channels in dB: infinite where the pictures are the same.
    pub psnr: f64,
    /// Pixels where any channel differs.
    pub differing: usize,
    /// The pixel that differs most (none where none differs).
    pub worst: Option<Worst>,
    /// The first step where the traces at the worst pixel depart (none where no pixel
    /// differs, or where the traces agree and only what follows them differs).
    pub first_divergence: Option<Divergence>,
    /// What the traces said when one could not be followed, or why there is no divergence.
    pub notes: Vec<String>,
    /// The picture of the difference with its legend ([`super::picture::difference`]).
    pub picture: RgbaImage,
    /// The two pictures compared: the copy's, then the reference's.
    pub frames: (std::sync::Arc<RgbaImage>, std::sync::Arc<RgbaImage>),
}

/// Refuses two captures whose shaders take different inputs (draws, uniform blocks, textures,
/// vertex attributes): such a copy is another program, not a copy, and its picture cannot be
/// compared line by line. The message names the first difference.
pub fn check_inputs(mine: &Captured, reference: &Captured) -> Result<()> {
    let refuse = |what: String| {
        Err(Error::Debug(format!(
            "the copy's shaders take different inputs from the reference's, so the two cannot be compared: {what}"
        )))
    };
    if mine.draws.len() != reference.draws.len() {
        return refuse(format!(
            "the copy draws {} times, the reference {}",
            mine.draws.len(),
            reference.draws.len()
        ));
    }
    for (k, (a, b)) in mine.draws.iter().zip(&reference.draws).enumerate() {
        let label = &b.label;
        for r in &b.bindings {
            match a.bindings.iter().find(|m| m.binding == r.binding) {
                None => {
                    return refuse(format!(
                        "draw {k} (`{label}`): `{}` at binding {} is not declared by the copy",
                        r.name, r.binding
                    ))
                }
                Some(m) if m.kind != r.kind || m.name != r.name => {
                    return refuse(format!(
                        "draw {k} (`{label}`): binding {} is `{}` ({:?}) in the copy, `{}` ({:?}) in the reference",
                        r.binding, m.name, m.kind, r.name, r.kind
                    ))
                }
                Some(_) => {}
            }
        }
        if let Some(extra) = a
            .bindings
            .iter()
            .find(|m| !b.bindings.iter().any(|r| r.binding == m.binding))
        {
            return refuse(format!(
                "draw {k} (`{label}`): the copy declares `{}` at binding {}, which the reference does not",
                extra.name, extra.binding
            ));
        }
        let inputs = |c: &crate::shader::CompiledShader| -> Vec<(u32, wgpu::VertexFormat)> {
            crate::render::reflect_inputs(c)
                .map(|v| v.into_iter().map(|i| (i.location, i.format)).collect())
                .unwrap_or_default()
        };
        let (ia, ib) = (inputs(&a.vertex), inputs(&b.vertex));
        if ia != ib {
            return refuse(format!(
                "draw {k} (`{label}`): the vertex shader's attributes are {} in the copy, {} in the reference",
                attributes(&ia),
                attributes(&ib)
            ));
        }
    }
    Ok(())
}

fn attributes(a: &[(u32, wgpu::VertexFormat)]) -> String {
    if a.is_empty() {
        return "none".into();
    }
    a.iter()
        .map(|(l, f)| format!("location {l} {f:?}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Whether two traced values are the same within [`VALUE_TOLERANCE`].
pub fn same_value(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(x, y)| {
            if x.is_nan() || y.is_nan() {
                return x.is_nan() && y.is_nan();
            }
            if x.is_infinite() || y.is_infinite() {
                return x == y;
            }
            (x - y).abs() <= VALUE_TOLERANCE * x.abs().max(y.abs()).max(1.0)
        })
}

/// The first step of `mine` that departs from `reference`, comparing the two in the order
/// they ran: a step of another stage, corner or name (the copy took another branch, assigned
/// another variable or ran another function) or of another value.
pub fn first_divergence(mine: &[TraceStep], reference: &[TraceStep]) -> Option<Divergence> {
    for (k, a) in mine.iter().enumerate() {
        // The divergence at `a`, the copy's step.
        let at = |reference: Option<&TraceStep>, why: String| Divergence {
            stage: a.stage,
            corner: a.corner,
            vertex: None,
            file: a.file.clone(),
            line: a.line,
            name: a.name.clone(),
            mine: a.value.clone(),
            reference: reference.cloned(),
            why,
        };
        let Some(b) = reference.get(k) else {
            return Some(at(
                None,
                "the copy runs this step after the reference's shader has ended".into(),
            ));
        };
        let why = if a.stage != b.stage || a.corner != b.corner || a.name != b.name {
            format!(
                "the copy's shader does `{}` here where the reference's does `{}` ({}:{})",
                a.describe(),
                b.describe(),
                b.file,
                b.line
            )
        } else if !same_value(&a.value, &b.value) {
            "the value differs".to_owned()
        } else {
            continue;
        };
        let mut d = at(Some(b), why);
        at_call_site(mine, k, &mut d);
        return Some(d);
    }
    reference.get(mine.len()).map(|b| Divergence {
        stage: b.stage,
        corner: b.corner,
        vertex: None,
        file: mine.last().map_or_else(|| b.file.clone(), |a| a.file.clone()),
        line: mine.last().map_or(b.line, |a| a.line),
        name: b.name.clone(),
        mine: Vec::new(),
        reference: Some(b.clone()),
        why: format!(
            "the copy's shader ends after this line; the reference's goes on with `{}` ({}:{})",
            b.describe(),
            b.file,
            b.line
        ),
    })
}

/// A divergence in a parameter of a called function (the steps that follow a `call` step
/// on the callee's first line) is the call's: the argument was computed at the call's line.
/// `d` is moved there, named `f's argument x`.
fn at_call_site(steps: &[TraceStep], k: usize, d: &mut Divergence) {
    let here = &steps[k];
    let plain =
        |s: &TraceStep| !(s.name == "if" || s.name == "loop" || s.name == "discard" || s.name.starts_with("call "));
    if !plain(here) {
        return;
    }
    let mut j = k;
    while j > 0 {
        j -= 1;
        let s = &steps[j];
        if let Some(function) = s.name.strip_prefix("call ") {
            if s.stage == here.stage && s.corner == here.corner {
                d.file = s.file.clone();
                d.line = s.line;
                d.name = format!("{function}'s argument {}", here.name);
                d.why = format!("the argument `{}` passed to {function} differs", here.name);
            }
            return;
        }
        if !plain(s) || s.file != here.file || s.line != here.line {
            return;
        }
    }
}

/// Compares the copy's captured frame with the reference's, both with their pictures
/// ([`Captured::picture`]), and traces both at the worst pixel.
pub fn diff(lab: &str, mine: &Captured, reference: &Captured) -> Result<Diff> {
    check_inputs(mine, reference)?;
    let picture = |c: &Captured, whose: &str| {
        c.picture
            .clone()
            .ok_or_else(|| Error::Debug(format!("the {whose} frame was captured without its picture")))
    };
    let (a, b) = (picture(mine, "copy's")?, picture(reference, "reference's")?);
    if a.dimensions() != b.dimensions() {
        return Err(Error::Debug(format!(
            "the copy's picture is {}x{}, the reference's {}x{}",
            a.width(),
            a.height(),
            b.width(),
            b.height()
        )));
    }
    let (width, height) = b.dimensions();
    let mut differing = 0;
    let mut worst: Option<(u8, Worst)> = None;
    for (x, y, p) in a.enumerate_pixels() {
        let q = b.get_pixel(x, y).0;
        let off = (0..4).map(|c| p.0[c].abs_diff(q[c])).max().unwrap_or(0);
        if off == 0 {
            continue;
        }
        differing += 1;
        if worst.as_ref().is_none_or(|(w, _)| off > *w) {
            worst = Some((
                off,
                Worst {
                    x,
                    y,
                    mine: p.0,
                    reference: q,
                },
            ));
        }
    }
    let psnr =
        crate::study::metrics::psnr(&crate::offscreen::to_rgb(&a), &crate::offscreen::to_rgb(&b)).unwrap_or(f64::NAN);
    let (diff_picture, _) = super::picture::difference(&a, &b);
    let mut notes = Vec::new();
    let mut first = None;
    if worst.is_some() {
        match vertex_divergence(mine, reference) {
            Ok(found) => first = found,
            Err(e) => notes.push(format!("the vertices could not be compared: {e}")),
        }
    }
    if let (Some((_, w)), None) = (&worst, &first) {
        let traced = (
            Inspection::new(lab, mine, w.x, w.y),
            Inspection::new(lab, reference, w.x, w.y),
        );
        match traced {
            (Ok(m), Ok(r)) => {
                first = first_divergence(&m.steps, &r.steps);
                if first.is_none() {
                    notes.push(match (m.covered(), r.covered()) {
                        (false, false) => "no triangle covers the worst pixel in either frame".to_owned(),
                        _ => "the two traces at the worst pixel agree step by step: the pixels differ by what follows the shaders (blending, depth, another draw)".to_owned(),
                    });
                }
                if let (Some(a), Some(b)) = (&m.replayed.fragment, &r.replayed.fragment) {
                    if (a.draw, a.primitive) != (b.draw, b.primitive) {
                        notes.push(format!(
                            "the worst pixel is covered by primitive {} of draw {} in the copy's frame and by primitive {} of draw {} in the reference's: their vertex shader steps are of different vertices",
                            a.primitive, a.draw, b.primitive, b.draw
                        ));
                    }
                }
                if m.covered() != r.covered() {
                    notes.push(format!(
                        "the worst pixel is covered in {} frame only",
                        if m.covered() { "the copy's" } else { "the reference's" }
                    ));
                }
            }
            (m, r) => {
                for (whose, e) in [("copy", m.err()), ("reference", r.err())] {
                    if let Some(e) = e {
                        notes.push(format!("the {whose}'s trace at the worst pixel stopped: {e}"));
                    }
                }
            }
        }
    } else if worst.is_none() {
        notes.push("the two pictures are the same".to_owned());
    }
    Ok(Diff {
        lab: lab.to_owned(),
        width,
        height,
        psnr,
        differing,
        worst: worst.map(|(_, w)| w),
        first_divergence: first,
        notes,
        picture: diff_picture,
        frames: (a, b),
    })
}

/// The first vertex, in draw order and then index order, whose vertex shader outputs differ
/// between the two frames (beyond [`VALUE_TOLERANCE`]), traced in both: the first step that
/// departs there. None where every vertex agrees, or where the two frames' draws read other
/// vertices (then only pixels can be compared).
fn vertex_divergence(mine: &Captured, reference: &Captured) -> Result<Option<Divergence>> {
    for (k, (a, b)) in mine.draws.iter().zip(&reference.draws).enumerate() {
        let ids = replay::drawn_vertices(b).map_err(super::report::replay_error)?;
        if replay::drawn_vertices(a).map_err(super::report::replay_error)? != ids {
            continue;
        }
        for chunk in ids.chunks(CHUNK) {
            let ours = replay::vertex_outputs(a, chunk).map_err(super::report::replay_error)?;
            let theirs = replay::vertex_outputs(b, chunk).map_err(super::report::replay_error)?;
            let Some(i) = (0..chunk.len()).find(|&i| !same_value(&ours[i], &theirs[i])) else {
                continue;
            };
            let at = VertexAt {
                draw: k,
                index: chunk[i],
            };
            return Ok(Some(traced_vertex(a, b, at)?));
        }
    }
    Ok(None)
}

/// The first step at which the copy's vertex shader departs from the reference's at vertex
/// `at` (both traced there), or, where the traces agree step by step, the output that differs.
fn traced_vertex(mine: &CapturedDraw, reference: &CapturedDraw, at: VertexAt) -> Result<Divergence> {
    let steps = |draw: &CapturedDraw| -> Result<Vec<TraceStep>> {
        let trace = replay::trace_vertex(draw, at.index).map_err(super::report::replay_error)?;
        let (mut steps, mut dropped) = (Vec::new(), Vec::new());
        super::report::steps_of(Stage::Vertex, &draw.vertex, &trace, &mut steps, &mut dropped);
        for s in &mut steps {
            s.corner = None;
        }
        Ok(steps)
    };
    let (ours, theirs) = (steps(mine)?, steps(reference)?);
    let mut d = first_divergence(&ours, &theirs).unwrap_or_else(|| Divergence {
        stage: Stage::Vertex,
        corner: None,
        vertex: None,
        file: mine.vertex.path.clone(),
        line: ours.last().map_or(0, |s| s.line),
        name: "(outputs)".into(),
        mine: Vec::new(),
        reference: None,
        why: "the traces agree step by step, yet the outputs differ".into(),
    });
    d.vertex = Some(at);
    Ok(d)
}

/// The two frames a diff compares (the copy's and the reference's), captured with their
/// pictures and being read back: waited for natively, or taken once both are back (the
/// page, which cannot block). The window's F4, the page's Compare and the check use it.
pub struct Frames {
    mine: super::Pending,
    reference: super::Pending,
}

impl Frames {
    /// Starts capturing the frames of `mine` and `reference` at `size`, both drawing in
    /// `format`.
    pub fn start(
        gpu: &crate::gpu::Gpu,
        mine: &mut dyn crate::lab::Lab,
        reference: &mut dyn crate::lab::Lab,
        size: (u32, u32),
        format: wgpu::TextureFormat,
    ) -> Result<Frames> {
        Ok(Frames {
            mine: super::capture_start(gpu, mine, size, format)?,
            reference: super::capture_start(gpu, reference, size, format)?,
        })
    }

    /// Whether both frames are back (the device moved on to see).
    pub fn ready(&self, gpu: &crate::gpu::Gpu) -> bool {
        let _ = gpu.device.poll(wgpu::PollType::Poll);
        self.mine.ready() && self.reference.ready()
    }

    /// Both frames: waited for where `wait` (natively; the page never waits), else as they
    /// are ([`Frames::ready`] first).
    pub fn take(self, gpu: &crate::gpu::Gpu, wait: bool) -> Result<(Captured, Captured)> {
        #[cfg(not(target_arch = "wasm32"))]
        if wait {
            return Ok((self.mine.wait(gpu)?, self.reference.wait(gpu)?));
        }
        let _ = (gpu, wait);
        Ok((self.mine.finish()?, self.reference.finish()?))
    }
}

/// Draws `mine` and `reference` at `size` and compares them ([`diff`]); each frame's draws
/// are brought to the CPU before it runs.
#[cfg(not(target_arch = "wasm32"))]
pub fn diff_labs(
    gpu: &crate::gpu::Gpu,
    name: &str,
    mine: &mut dyn crate::lab::Lab,
    reference: &mut dyn crate::lab::Lab,
    (width, height): (u32, u32),
) -> Result<Diff> {
    let (_, mine) = super::capture_lab(gpu, mine, width, height, true)?;
    let (_, reference) = super::capture_lab(gpu, reference, width, height, true)?;
    diff(name, &mine, &reference)
}

/// A traced value in words, as the text says it: each number to 4 decimals, trailing zeros
/// dropped, several in parentheses, `(none)` for none.
pub fn value_text(v: &[f64]) -> String {
    let one = |x: f64| {
        if !x.is_finite() {
            return format!("{x}");
        }
        let s = format!("{x:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s == "-0" {
            "0".into()
        } else {
            s.to_owned()
        }
    };
    match v {
        [] => "(none)".into(),
        [x] => one(*x),
        _ => format!("({})", v.iter().map(|x| one(*x)).collect::<Vec<_>>().join(", ")),
    }
}

impl Diff {
    /// The comparison for people.
    pub fn text(&self) -> String {
        use std::fmt::Write as _;
        let mut out = String::new();
        let total = u64::from(self.width) * u64::from(self.height);
        let _ = writeln!(
            out,
            "{}: {}x{}, the copy against the reference",
            self.lab, self.width, self.height
        );
        if self.differing == 0 {
            let _ = writeln!(out, "the pictures are identical (PSNR infinite, 0 pixels differ)");
        } else {
            let _ = writeln!(
                out,
                "PSNR {:.2} dB; {} of {total} pixels differ ({:.2} %)",
                self.psnr,
                self.differing,
                100.0 * self.differing as f64 / total.max(1) as f64
            );
        }
        if let Some(w) = &self.worst {
            let _ = writeln!(
                out,
                "worst pixel {},{}: the copy stores rgba({}, {}, {}, {}), the reference rgba({}, {}, {}, {})",
                w.x,
                w.y,
                w.mine[0],
                w.mine[1],
                w.mine[2],
                w.mine[3],
                w.reference[0],
                w.reference[1],
                w.reference[2],
                w.reference[3]
            );
        }
        if let Some(d) = &self.first_divergence {
            let stage = match (d.stage, d.corner, d.vertex) {
                (Stage::Vertex, _, Some(v)) => format!("vertex shader, draw {} vertex {}", v.draw, v.index),
                (Stage::Vertex, Some(c), None) => format!("vertex shader, corner {c}"),
                (Stage::Vertex, None, None) => "vertex shader".to_owned(),
                (Stage::Fragment, _, _) => "fragment shader".to_owned(),
            };
            let _ = writeln!(
                out,
                "first divergence, in the order the shaders ran: {}:{} ({stage}) `{}`: the copy {}, the reference {} ({})",
                d.file,
                d.line,
                d.name,
                value_text(&d.mine),
                d.reference.as_ref().map_or_else(|| "(ended)".to_owned(), |r| value_text(&r.value)),
                d.why
            );
        }
        for note in &self.notes {
            let _ = writeln!(out, "note: {note}");
        }
        out
    }

    /// The comparison for programs: `psnr` (`"Infinity"` where the pictures are the same),
    /// `differing`, `worst` {x, y, mine, reference} and `first_divergence` {stage, corner,
    /// vertex {draw, index}, file, line, name, mine, reference, reference_file,
    /// reference_line, why} (null where
    /// there is none), with `width`, `height` and `notes`.
    pub fn json(&self) -> String {
        use serde_json::{json, Value};
        let value = |v: &[f64]| -> Value {
            match v {
                [x] => super::json_number(*x),
                _ => v.iter().map(|x| super::json_number(*x)).collect(),
            }
        };
        let worst = self.worst.as_ref().map_or(
            Value::Null,
            |w| json!({"x": w.x, "y": w.y, "mine": w.mine, "reference": w.reference}),
        );
        let first = self.first_divergence.as_ref().map_or(Value::Null, |d| {
            json!({
                "stage": if d.stage == Stage::Vertex { "vertex" } else { "fragment" },
                "corner": d.corner,
                "vertex": d.vertex.map(|v| json!({"draw": v.draw, "index": v.index})),
                "file": d.file, "line": d.line, "name": d.name,
                "mine": if d.mine.is_empty() { Value::Null } else { value(&d.mine) },
                "reference": d.reference.as_ref().map_or(Value::Null, |r| value(&r.value)),
                "reference_file": d.reference.as_ref().map(|r| r.file.clone()),
                "reference_line": d.reference.as_ref().map(|r| r.line),
                "reference_name": d.reference.as_ref().map(|r| r.name.clone()),
                "why": d.why,
            })
        });
        json!({
            "lab": self.lab, "width": self.width, "height": self.height,
            "psnr": super::json_number(self.psnr), "differing": self.differing,
            "worst": worst, "first_divergence": first, "notes": self.notes,
        })
        .to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn step(stage: Stage, name: &str, line: u32, value: &[f64]) -> TraceStep {
        TraceStep {
            stage,
            corner: None,
            file: "a.frag".into(),
            line,
            name: name.into(),
            value: value.to_vec(),
            more: 0,
            boolean: false,
        }
    }

    #[test]
    fn the_first_step_that_differs_in_value_or_shape_is_found_in_order() {
        let r = vec![
            step(Stage::Fragment, "N", 3, &[0.0, 0.0, 1.0]),
            step(Stage::Fragment, "d", 4, &[0.5]),
            step(Stage::Fragment, "c", 5, &[0.25]),
        ];
        assert_eq!(first_divergence(&r, &r), None);
        // Within the tolerance is the same value.
        let mut m = r.clone();
        m[1].value = vec![0.500_01];
        assert_eq!(first_divergence(&m, &r), None);
        m[1].value = vec![0.6];
        m[2].value = vec![0.9];
        let d = first_divergence(&m, &r).expect("a divergence");
        assert_eq!((d.line, d.name.as_str(), d.mine.clone()), (4, "d", vec![0.6]));
        assert_eq!(d.reference.map(|s| s.value), Some(vec![0.5]));
        // Another name at the same place is a divergence of shape.
        let mut m = r.clone();
        m[2].name = "e".into();
        let d = first_divergence(&m, &r).expect("a divergence");
        assert_eq!((d.line, d.name.as_str()), (5, "e"));
        assert!(d.why.contains("where the reference's does"), "{}", d.why);
        // A trace that ends early.
        let d = first_divergence(&r[..2], &r).expect("a divergence");
        assert!(d.why.contains("ends after"), "{}", d.why);
        assert!(same_value(&[f64::NAN], &[f64::NAN]) && !same_value(&[f64::NAN], &[0.0]));
        // An argument that differs is the call's line.
        let mut call = step(Stage::Fragment, "call f", 9, &[]);
        call.file = "main.frag".into();
        let r = vec![
            call,
            step(Stage::Fragment, "x", 2, &[1.0]),
            step(Stage::Fragment, "y", 2, &[2.0]),
        ];
        let mut m = r.clone();
        m[2].value = vec![3.0];
        let d = first_divergence(&m, &r).expect("a divergence");
        assert_eq!(
            (d.file.as_str(), d.line, d.name.as_str()),
            ("main.frag", 9, "f's argument y")
        );
    }
}
