//! Whole-frame views drawn on the GPU: the value a line of a shader assigns at every pixel (a
//! line view), or how many steps the fragment shader's trace lists there (a cost view).
//!
//! A frame written down in a [`DrawLog`] is drawn again, draw by draw, with the draws' own
//! layouts, bind groups, buffers, culling and depth test and the frame's passes and clears, but
//! with each draw's fragment shader rewritten by [`super::instrument`] to return the probed
//! value (a float target as narrow as the value) and an info word (whether the line ran, the
//! value's components, the steps: `R32Uint`), read back as a [`ValueFrame`]; a cost view draws
//! the info word alone.
//! Draws whose shaders do not hold the line draw too (with `ran` false), so occlusion is as in
//! the frame. A vertex-shader line travels to the fragment shader as an extra varying: the
//! value at the three corners interpolated as any varying is.

// The browser reads a view back asynchronously; what draws and reads one here is native.
#![cfg_attr(target_arch = "wasm32", allow(dead_code))]

use std::sync::{Arc, Weak};

use super::instrument::{self, Assignment, Site};
use super::Stage;
use crate::error::Result;
use crate::gpu::Gpu;
use crate::render::{DrawCall, DrawLog, Load};
use crate::shader::CompiledShader;

/// What a view shows.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Probe {
    /// The value line `line` of `file` assigns (`name`, where it assigns several things), in
    /// `stage` (needed only for a file both stages include).
    Line {
        /// The file as the lab shows it (its display path).
        file: String,
        /// The 1-based line.
        line: u32,
        /// The name assigned, where the line assigns more than one.
        name: Option<String>,
        /// The stage, where both include the file.
        stage: Option<Stage>,
    },
    /// The steps the fragment shader's trace lists at each pixel.
    Cost,
}

impl std::str::FromStr for Probe {
    type Err = ViewError;

    /// `cost`, or `FILE:LINE` (the line 1-based; a Windows path's drive colon is kept): what
    /// the command's `--line` and the page's `&view=` name.
    fn from_str(given: &str) -> std::result::Result<Probe, ViewError> {
        let given = given.trim();
        if given == "cost" {
            return Ok(Probe::Cost);
        }
        let bad = || ViewError::BadProbe {
            given: given.to_owned(),
        };
        let (file, line) = given.rsplit_once(':').ok_or_else(bad)?;
        let line: u32 = line.parse().map_err(|_| bad())?;
        if file.is_empty() || line == 0 {
            return Err(bad());
        }
        Ok(Probe::Line {
            file: file.to_owned(),
            line,
            name: None,
            stage: None,
        })
    }
}

/// Why a view cannot be drawn.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ViewError {
    /// A probe that is neither `FILE:LINE` nor `cost`.
    #[error("`{given}`: expected FILE:LINE (a line of a shader, from 1) or `cost`")]
    BadProbe {
        /// What was given.
        given: String,
    },
    /// No shader the frame draws holds the file (in the stage asked for).
    #[error("{file} is not a file of {what} this lab draws; its files are {files}")]
    NotDrawn {
        /// The file asked for.
        file: String,
        /// `a shader`, `a vertex shader`, `a fragment shader`.
        what: String,
        /// The files it draws, comma-separated.
        files: String,
    },
    /// The line assigns nothing the trace shows.
    #[error("{file}:{line} assigns nothing{near}")]
    Nothing {
        /// The file.
        file: String,
        /// The line.
        line: u32,
        /// The nearest lines that do, in words (`; the nearest lines that assign are 12 (L) and 15 (E)`).
        near: String,
    },
    /// The line is past the end of the file.
    #[error("{file}:{line} is past the end of the file: {file} has {lines} line{}", if *.lines == 1 { "" } else { "s" })]
    PastEnd {
        /// The file.
        file: String,
        /// The line asked for.
        line: u32,
        /// The file's lines.
        lines: usize,
    },
    /// The line does not assign the name asked for.
    #[error("{file}:{line} does not assign `{name}`; it assigns {names}")]
    NoSuchName {
        /// The file.
        file: String,
        /// The line.
        line: u32,
        /// The name asked for.
        name: String,
        /// The names it assigns.
        names: String,
        /// The names to choose from (each variable once).
        choices: Vec<String>,
    },
    /// The line assigns several things and none was chosen.
    #[error("{file}:{line} assigns {names}: choose one by its name")]
    Ambiguous {
        /// The file.
        file: String,
        /// The line.
        line: u32,
        /// The names it assigns.
        names: String,
        /// The names to choose from (each variable once).
        choices: Vec<String>,
    },
    /// The file is included by both stages and the line assigns in both.
    #[error("{file} is included by both the vertex and the fragment shader, and line {line} assigns in both: choose the stage")]
    BothStages {
        /// The file.
        file: String,
        /// The line.
        line: u32,
    },
    /// The frame's passes are not of the view's size.
    #[error("the frame was recorded at {recorded}, not at the view's {width}x{height}")]
    Size {
        /// The passes' sizes.
        recorded: String,
        /// The view's width.
        width: u32,
        /// Its height.
        height: u32,
    },
    /// The rewritten shader was refused.
    #[error("{path}: {message}")]
    Instrument {
        /// The shader.
        path: String,
        /// Why.
        message: String,
    },
}

impl ViewError {
    /// Whether the probe does not fit the frame's shaders (the user's to change), rather than
    /// a rewritten shader refused or a frame of another size.
    pub fn is_usage(&self) -> bool {
        !matches!(self, ViewError::Size { .. } | ViewError::Instrument { .. })
    }
}

impl From<ViewError> for crate::error::Error {
    fn from(e: ViewError) -> Self {
        let choose = match &e {
            ViewError::Ambiguous { choices, .. } | ViewError::NoSuchName { choices, .. } => {
                crate::error::Choose::Name(choices.clone())
            }
            ViewError::BothStages { .. } => crate::error::Choose::Stage,
            _ => crate::error::Choose::Nothing,
        };
        crate::error::Error::View {
            message: e.to_string(),
            usage: e.is_usage(),
            choose,
        }
    }
}

/// A probe resolved against a frame's shaders: the stage and the assignment's site.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Resolved {
    /// The stage the line runs in.
    pub stage: Stage,
    /// The file, line and name.
    pub site: Site,
    /// The value's components a view shows (at most 4).
    pub components: u32,
}

/// A view read back: per pixel (rows top first, like a screenshot) the value, whether the line
/// ran there and the steps the fragment shader took.
#[derive(Clone, Debug)]
pub struct ValueFrame {
    /// Width in pixels.
    pub width: u32,
    /// Height.
    pub height: u32,
    /// The value's components (at most 4; 0 for a cost view).
    pub components: u32,
    /// The value's first components (the rest 0); the last assignment where the line ran
    /// several times.
    pub values: Vec<[f32; 4]>,
    /// Whether the line ran at the pixel (for a vertex line: at all three corners).
    pub ran: Vec<bool>,
    /// The steps the fragment shader's trace lists at the pixel (0 where nothing was drawn).
    pub cost: Vec<u32>,
    /// The line is the vertex shader's: its value at the corners, interpolated as a varying.
    pub vertex: bool,
    /// What was probed (none for a cost view).
    pub resolved: Option<Resolved>,
}

impl ValueFrame {
    /// The index of pixel (x, y).
    pub fn at(&self, x: u32, y: u32) -> usize {
        (y * self.width + x) as usize
    }

    /// Where a fragment ran: the fragment shader's trace has at least one step there.
    pub fn drawn(&self) -> Vec<bool> {
        self.cost.iter().map(|&c| c > 0).collect()
    }

    /// The view's picture with its legend strip ([`super::picture::values`] or
    /// [`super::picture::cost`]), and a line view's legend.
    pub fn picture(&self) -> (image::RgbaImage, Option<super::picture::Legend>) {
        let drawn = self.drawn();
        if self.resolved.is_none() {
            let (image, _) = super::picture::cost(self.width, self.height, &self.cost, &drawn);
            return (image, None);
        }
        let (image, legend) = super::picture::values(
            self.width,
            self.height,
            self.components as usize,
            &self.values,
            &self.ran,
            &drawn,
        );
        (image, Some(legend))
    }
}

/// The distinct shaders of `draws` of one stage.
fn shaders(draws: &[DrawCall], stage: Stage) -> Vec<Arc<CompiledShader>> {
    let mut out: Vec<Arc<CompiledShader>> = Vec::new();
    for d in draws {
        let s = match stage {
            Stage::Vertex => &d.setup.vertex,
            Stage::Fragment => &d.setup.fragment,
        };
        if !out.iter().any(|o| Arc::ptr_eq(o, s)) {
            out.push(s.clone());
        }
    }
    out
}

fn holds(shaders: &[Arc<CompiledShader>], file: &str) -> bool {
    shaders.iter().any(|s| s.source.files.iter().any(|(p, _)| p == file))
}

fn names(list: &[&Assignment]) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for a in list {
        if !out.contains(&a.name) {
            out.push(a.name.clone());
        }
    }
    out
}

fn quoted(names: &[String]) -> String {
    names.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ")
}

/// Resolves a line probe against the shaders `draws` draw with.
pub fn resolve(draws: &[DrawCall], probe: &Probe) -> std::result::Result<Option<Resolved>, ViewError> {
    let Probe::Line {
        file,
        line,
        name,
        stage,
    } = probe
    else {
        return Ok(None);
    };
    let line = *line;
    let by_stage = [Stage::Vertex, Stage::Fragment].map(|s| (s, shaders(draws, s)));
    let file = &full_path(draws, file);
    let text = by_stage
        .iter()
        .flat_map(|(_, list)| list.iter())
        .flat_map(|s| s.source.files.iter())
        .find_map(|(p, text)| (p == file).then_some(text));
    if let Some(lines) = text.map(|t| t.lines().count()).filter(|&n| line as usize > n) {
        return Err(ViewError::PastEnd {
            file: file.clone(),
            line,
            lines,
        });
    }
    let assigns = |s: Stage| -> Vec<Assignment> {
        let list = &by_stage.iter().find(|(k, _)| *k == s).expect("both stages").1;
        let mut out: Vec<Assignment> = Vec::new();
        for shader in list {
            for a in instrument::assignments(shader) {
                if a.file == *file && !out.contains(&a) {
                    out.push(a);
                }
            }
        }
        out
    };
    let has = |s: Stage| holds(&by_stage.iter().find(|(k, _)| *k == s).expect("both stages").1, file);
    let stage = match stage {
        Some(s) if !has(*s) => {
            return Err(not_drawn(draws, file, *s));
        }
        Some(s) => *s,
        None => match (has(Stage::Vertex), has(Stage::Fragment)) {
            (false, false) => {
                return Err(not_drawn(draws, file, Stage::Fragment).generic());
            }
            (true, false) => Stage::Vertex,
            (false, true) => Stage::Fragment,
            (true, true) => {
                let v = assigns(Stage::Vertex).iter().any(|a| a.line == line);
                let f = assigns(Stage::Fragment).iter().any(|a| a.line == line);
                match (v, f) {
                    (true, true) => {
                        return Err(ViewError::BothStages {
                            file: file.clone(),
                            line,
                        })
                    }
                    (true, false) => Stage::Vertex,
                    _ => Stage::Fragment,
                }
            }
        },
    };
    let all = assigns(stage);
    let here: Vec<&Assignment> = all.iter().filter(|a| a.line == line).collect();
    if here.is_empty() {
        return Err(ViewError::Nothing {
            file: file.clone(),
            line,
            near: nearest(&all, line),
        });
    }
    let list = instrument::targets(&here);
    let names: Vec<String> = list.iter().map(|t| t.name.clone()).collect();
    // What the compiler made (a `?:`'s result) is not offered by name.
    let choices: Vec<String> = list
        .iter()
        .filter(|t| t.root != super::interp::TEMPORARY)
        .map(|t| t.name.clone())
        .collect();
    let target = match name {
        Some(n) => {
            let found = list
                .iter()
                .find(|t| t.name == *n)
                .or_else(|| list.iter().find(|t| t.named(n, &list)));
            match found {
                Some(t) => Some(t),
                None => {
                    return Err(ViewError::NoSuchName {
                        file: file.clone(),
                        line,
                        name: n.clone(),
                        names: quoted(&names),
                        choices,
                    })
                }
            }
        }
        None => match choices.as_slice() {
            [] => None,
            [one] => list.iter().find(|t| t.name == *one),
            _ => {
                return Err(ViewError::Ambiguous {
                    file: file.clone(),
                    line,
                    names: quoted(&names),
                    choices,
                })
            }
        },
    };
    let components = match target {
        Some(t) => t.components,
        None => list.iter().map(|t| t.components).max().unwrap_or(0),
    };
    let chosen = target.map(|t| t.name.clone());
    Ok(Some(Resolved {
        stage,
        components,
        site: Site {
            file: file.clone(),
            line,
            name: chosen,
        },
    }))
}

impl ViewError {
    /// The same error, said of any stage.
    fn generic(self) -> Self {
        match self {
            ViewError::NotDrawn { file, files, .. } => ViewError::NotDrawn {
                file,
                what: "a shader".into(),
                files,
            },
            other => other,
        }
    }
}

/// The files of the shaders `draws` draw with (display paths), in order.
fn files(draws: &[DrawCall]) -> Vec<String> {
    let mut files: Vec<String> = Vec::new();
    for s in shaders(draws, Stage::Vertex)
        .iter()
        .chain(&shaders(draws, Stage::Fragment))
    {
        for (p, _) in &s.source.files {
            if !files.contains(p) {
                files.push(p.clone());
            }
        }
    }
    files
}

/// `file` as the draws' shaders name it: itself, or the one file whose path ends with it
/// (`phong.frag` for `shaders_glsl/phong.frag`).
fn full_path(draws: &[DrawCall], file: &str) -> String {
    find_file(&files(draws), file).unwrap_or_else(|| file.to_owned())
}

/// The one of `files` (display paths, as a lab shows its shader files) that `given` names:
/// that path, else the one file whose path ends with `given` as whole path components
/// (`phong.frag` for `shaders_glsl/phong.frag` or `DIR/phong.frag`), else the same file through
/// another path (natively). `None` where none or several fit: the command line, the window and
/// the page resolve a user's file name by this one rule.
pub fn find_file(files: &[String], given: &str) -> Option<String> {
    if files.iter().any(|p| p == given) {
        return Some(given.to_owned());
    }
    let given_path = std::path::Path::new(given.trim_start_matches("./"));
    let ending: Vec<&String> = files
        .iter()
        .filter(|p| std::path::Path::new(p.as_str()).ends_with(given_path))
        .collect();
    if let [one] = ending.as_slice() {
        return Some((*one).clone());
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        let same =
            |p: &String| matches!((std::fs::canonicalize(p), std::fs::canonicalize(given)), (Ok(a), Ok(b)) if a == b);
        files.iter().find(|p| same(p)).cloned()
    }
    #[cfg(target_arch = "wasm32")]
    None
}

fn not_drawn(draws: &[DrawCall], file: &str, stage: Stage) -> ViewError {
    let files = files(draws);
    ViewError::NotDrawn {
        file: file.to_owned(),
        what: match stage {
            Stage::Vertex => "a vertex shader".into(),
            Stage::Fragment => "a fragment shader".into(),
        },
        files: if files.is_empty() {
            "none (the frame draws nothing)".into()
        } else {
            files.join(", ")
        },
    }
}

/// The lines nearest `line` (one before, one after) among `all`, in words.
fn nearest(all: &[Assignment], line: u32) -> String {
    let before = all.iter().filter(|a| a.line < line).map(|a| a.line).max();
    let after = all.iter().filter(|a| a.line > line).map(|a| a.line).min();
    let say = |l: u32| {
        let here: Vec<&Assignment> = all.iter().filter(|a| a.line == l).collect();
        let n = names(&here);
        format!("{l} ({})", n.join(", "))
    };
    match (before, after) {
        (Some(b), Some(a)) => format!("; the nearest lines that do are {} and {}", say(b), say(a)),
        (Some(l), None) | (None, Some(l)) => format!("; the nearest line that does is {}", say(l)),
        (None, None) => "; no line of this file assigns anything".into(),
    }
}

/// One draw's pipeline for a view, and what it was built from.
struct Built {
    device: wgpu::Device,
    vertex: Weak<CompiledShader>,
    fragment: Weak<CompiledShader>,
    resolved: Option<Resolved>,
    layout: wgpu::PipelineLayout,
    stride: u64,
    attributes: Vec<wgpu::VertexAttribute>,
    topology: wgpu::PrimitiveTopology,
    front_face: wgpu::FrontFace,
    cull: Option<wgpu::Face>,
    depth_test: bool,
    pipeline: wgpu::RenderPipeline,
    /// The probed value's components in this draw's shader (0: the line is not in it).
    components: u32,
}

/// The most pipelines a [`ViewDrawer`] keeps.
const KEPT: usize = 32;

/// Draws views, keeping the pipelines (one per draw's program, culling and probe) and index
/// buffers it built, so that a view drawn again each frame builds nothing.
#[derive(Default)]
pub struct ViewDrawer {
    built: Vec<Built>,
    targets: Option<Targets>,
    indices: Vec<(Weak<Vec<u32>>, wgpu::Buffer)>,
    /// Pipelines, index buffers and targets built so far.
    builds: u64,
}

impl ViewDrawer {
    /// A drawer with nothing built.
    pub fn new() -> Self {
        Self::default()
    }

    /// How many pipelines, index buffers and targets this drawer has built: a view drawn again
    /// adds none.
    pub fn builds(&self) -> u64 {
        self.builds
    }

    fn pipeline(
        &mut self,
        gpu: &Gpu,
        call: &DrawCall,
        resolved: Option<&Resolved>,
    ) -> Result<(wgpu::RenderPipeline, u32)> {
        let setup = &call.setup;
        let same = |b: &Built| {
            b.device == gpu.device
                && b.vertex.upgrade().is_some_and(|v| Arc::ptr_eq(&v, &setup.vertex))
                && b.fragment.upgrade().is_some_and(|v| Arc::ptr_eq(&v, &setup.fragment))
                && b.resolved.as_ref() == resolved
                && b.layout == call.layout
                && b.stride == setup.stride
                && b.attributes == setup.attributes
                && b.topology == setup.state.topology
                && b.front_face == setup.state.front_face
                && b.cull == setup.cull
                && b.depth_test == setup.state.depth_test
        };
        if let Some(b) = self.built.iter().find(|b| same(b)) {
            return Ok((b.pipeline.clone(), b.components));
        }
        let refused = |path: &str| {
            let path = path.to_owned();
            move |message: String| ViewError::Instrument { path, message }
        };
        let (vertex, fragment, components) = match resolved {
            Some(r) if r.stage == Stage::Vertex => {
                let at = instrument::free_location(&setup.vertex, &setup.fragment);
                let (v, found) =
                    instrument::vertex(&setup.vertex, Some(&r.site), at).map_err(refused(&setup.vertex.path))?;
                let n = found.into_iter().max().unwrap_or(0);
                let (f, _) = instrument::fragment(&setup.fragment, None, Some((at, n)), true)
                    .map_err(refused(&setup.fragment.path))?;
                (Some(v), f, n)
            }
            _ => {
                let site = resolved.map(|r| &r.site);
                let (f, found) = instrument::fragment(&setup.fragment, site, None, site.is_some())
                    .map_err(refused(&setup.fragment.path))?;
                (None, f, found.into_iter().max().unwrap_or(0))
            }
        };
        let label = format!("shaderlab.debug.view.{}", setup.label);
        let device = &gpu.device;
        // The driver compiles the shaders here: bounded as a lab's own pipelines are.
        let pipeline = gpu.compiling(&label, || {
            gpu.checked(&label, || {
                let vs = match vertex {
                    Some(v) => device.create_shader_module(wgpu::ShaderModuleDescriptor {
                        label: Some(&format!("{label}.vertex")),
                        source: wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(v)),
                    }),
                    None => device.create_shader_module(wgpu::ShaderModuleDescriptor {
                        label: Some(&format!("{label}.vertex")),
                        source: wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(setup.vertex.module.clone())),
                    }),
                };
                let fs = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(&format!("{label}.fragment")),
                    source: wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(fragment)),
                });
                let buffers = [Some(wgpu::VertexBufferLayout {
                    array_stride: setup.stride,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &setup.attributes,
                })];
                let target = |format| {
                    Some(wgpu::ColorTargetState {
                        format,
                        blend: None,
                        write_mask: wgpu::ColorWrites::ALL,
                    })
                };
                let value = target(value_format(resolved.map_or(0, |r| r.components)));
                let info = target(INFO_FORMAT);
                let both = [value, info.clone()];
                let one = [info];
                device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some(&format!("{label}.pipeline")),
                    layout: Some(&call.layout),
                    vertex: wgpu::VertexState {
                        module: &vs,
                        entry_point: Some("main"),
                        compilation_options: Default::default(),
                        buffers: if setup.attributes.is_empty() { &[] } else { &buffers },
                    },
                    fragment: Some(wgpu::FragmentState {
                        module: &fs,
                        entry_point: Some("main"),
                        compilation_options: Default::default(),
                        targets: if resolved.is_some() { &both } else { &one },
                    }),
                    primitive: wgpu::PrimitiveState {
                        topology: setup.state.topology,
                        front_face: setup.state.front_face,
                        cull_mode: setup.cull,
                        ..Default::default()
                    },
                    depth_stencil: Some(crate::render::depth_state(setup.state.depth_test)),
                    multisample: Default::default(),
                    multiview_mask: None,
                    cache: None,
                })
            })
        })?;
        self.built
            .retain(|b| b.vertex.strong_count() > 0 && b.fragment.strong_count() > 0);
        if self.built.len() >= KEPT {
            self.built.remove(0);
        }
        self.builds += 1;
        self.built.push(Built {
            device: gpu.device.clone(),
            vertex: Arc::downgrade(&setup.vertex),
            fragment: Arc::downgrade(&setup.fragment),
            resolved: resolved.cloned(),
            layout: call.layout.clone(),
            stride: setup.stride,
            attributes: setup.attributes.clone(),
            topology: setup.state.topology,
            front_face: setup.state.front_face,
            cull: setup.cull,
            depth_test: setup.state.depth_test,
            pipeline: pipeline.clone(),
            components,
        });
        Ok((pipeline, components))
    }

    /// The index buffer holding `indices` (uploaded once per list).
    fn index_buffer(&mut self, gpu: &Gpu, indices: &Arc<Vec<u32>>) -> Result<wgpu::Buffer> {
        if let Some((_, b)) = self
            .indices
            .iter()
            .find(|(w, _)| w.upgrade().is_some_and(|i| Arc::ptr_eq(&i, indices)))
        {
            return Ok(b.clone());
        }
        self.indices.retain(|(w, _)| w.strong_count() > 0);
        let label = "shaderlab.debug.view.indices";
        let buffer = gpu.checked(label, || {
            let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: (indices.len().max(1) * 4) as u64,
                usage: wgpu::BufferUsages::INDEX | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            gpu.queue
                .write_buffer(&buffer, 0, bytemuck::cast_slice(indices.as_slice()));
            buffer
        })?;
        self.builds += 1;
        self.indices.push((Arc::downgrade(indices), buffer.clone()));
        Ok(buffer)
    }

    /// Draws the view `probe` of the frame `log` wrote down (at `width` × `height`, the size
    /// it was recorded at) and reads it back: band by band of rows through one small buffer,
    /// the info target first, so that a big view holds its targets and the values on the CPU,
    /// never a second copy of them.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn draw(&mut self, gpu: &Gpu, log: &DrawLog, probe: &Probe, width: u32, height: u32) -> Result<ValueFrame> {
        self.draw_keeping(gpu, log, probe, (width, height), true)
    }

    /// Draws and reads back one view as [`ViewDrawer::draw`] does, giving each target back as
    /// soon as it is read (the depth and info targets before the values are read): a big view
    /// then holds about the memory of its values twice, never more.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn draw_once(mut self, gpu: &Gpu, log: &DrawLog, probe: &Probe, width: u32, height: u32) -> Result<ValueFrame> {
        self.draw_keeping(gpu, log, probe, (width, height), false)
    }

    /// [`ViewDrawer::draw`], keeping the targets for the next view (`keep`) or giving them
    /// back as they are read.
    #[cfg(not(target_arch = "wasm32"))]
    fn draw_keeping(
        &mut self,
        gpu: &Gpu,
        log: &DrawLog,
        probe: &Probe,
        (width, height): (u32, u32),
        keep: bool,
    ) -> Result<ValueFrame> {
        let label = "shaderlab.debug.view";
        let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some(&format!("{label}.encoder")),
        });
        let Drawn {
            resolved,
            components,
            value,
            format,
            size: (w, h),
        } = self.encode(gpu, &mut encoder, log, probe, width, height)?;
        let commands = gpu.checked(label, || encoder.finish())?;
        gpu.queue.submit([commands]);
        let targets = self.targets.as_mut().expect("made by encode");
        let n = (w as usize) * (h as usize);
        let (mut ran, mut cost) = (Vec::with_capacity(n), Vec::with_capacity(n));
        targets.read_rows(gpu, Kept::Info, |row| {
            for b in row.chunks_exact(4) {
                let word = u32::from_le_bytes([b[0], b[1], b[2], b[3]]);
                ran.push(word & instrument::RAN_BIT != 0);
                cost.push(word >> instrument::COST_SHIFT);
            }
        })?;
        if !keep {
            targets.info.0.destroy();
            targets.depth = crate::gpu::targets::depth_texture(&gpu.device, 1, 1);
        }
        let values = if value {
            let k = texel_words(format);
            let mut values = Vec::with_capacity(n);
            targets.read_rows(gpu, Kept::Value, |row| {
                values.extend(row.chunks_exact(k * 4).map(|t| {
                    let mut v = [0.0f32; 4];
                    for (c, b) in v.iter_mut().zip(t.chunks_exact(4)) {
                        *c = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
                    }
                    v
                }));
            })?;
            values
        } else {
            // Zeroed by the allocator, never written: a cost view's values cost no memory.
            vec![[0.0f32; 4]; n]
        };
        if !keep {
            self.targets = None;
        }
        let vertex = resolved.as_ref().is_some_and(|r| r.stage == Stage::Vertex);
        Ok(ValueFrame {
            width: w,
            height: h,
            components,
            values,
            ran,
            cost,
            vertex,
            resolved,
        })
    }

    /// The value and info targets the last [`ViewDrawer::encode`] drew into, as views.
    pub fn targets(&self) -> Option<(&wgpu::TextureView, &wgpu::TextureView)> {
        self.targets.as_ref().map(|t| (&t.value.1, &t.info.1))
    }

    /// Encodes the view `probe` of the frame `log` wrote down (at `width` × `height`) into
    /// `encoder`: the value and info targets ([`ViewDrawer::targets`]) hold it once the
    /// encoder runs. Builds what it has not built for an earlier frame.
    pub fn encode(
        &mut self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        log: &DrawLog,
        probe: &Probe,
        width: u32,
        height: u32,
    ) -> Result<Drawn> {
        let draws = log.draws();
        let passes = log.passes();
        if passes.iter().any(|p| (p.1, p.2) != (width, height)) {
            let recorded: Vec<String> = passes.iter().map(|p| format!("{}x{}", p.1, p.2)).collect();
            return Err(ViewError::Size {
                recorded: recorded.join(", "),
                width,
                height,
            }
            .into());
        }
        let resolved = resolve(&draws, probe)?;
        let mut pipelines = Vec::with_capacity(draws.len());
        let mut components = 0;
        for call in &draws {
            let (p, n) = self.pipeline(gpu, call, resolved.as_ref())?;
            components = components.max(n);
            let indices = match &call.setup.indices {
                Some(i) => Some(self.index_buffer(gpu, i)?),
                None => None,
            };
            pipelines.push((p, indices));
        }
        let label = "shaderlab.debug.view";
        let (w, h) = (width.max(1), height.max(1));
        let format = value_format(resolved.as_ref().map_or(0, |r| r.components));
        let fits = |t: &Targets| t.device == gpu.device && (t.width, t.height, t.format) == (w, h, format);
        if !self.targets.as_ref().is_some_and(fits) {
            self.targets = Some(gpu.checked(label, || Targets::new(&gpu.device, w, h, format))?);
            self.builds += 1;
        }
        let targets = self.targets.as_ref().expect("made above");
        let value = resolved.is_some();
        gpu.checked(label, || {
            let views: Vec<&wgpu::TextureView> = if value {
                vec![&targets.value.1, &targets.info.1]
            } else {
                vec![&targets.info.1]
            };
            for (k, (load, _, _)) in passes.iter().enumerate() {
                // A first pass that keeps what was there starts from nothing drawn.
                let (color, depth_load) = match load {
                    Load::Keep if k > 0 => (wgpu::LoadOp::Load, wgpu::LoadOp::Load),
                    _ => (wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT), wgpu::LoadOp::Clear(1.0)),
                };
                let attachments: Vec<_> = views
                    .iter()
                    .map(|v| {
                        Some(wgpu::RenderPassColorAttachment {
                            view: v,
                            depth_slice: None,
                            resolve_target: None,
                            ops: wgpu::Operations {
                                load: color,
                                store: wgpu::StoreOp::Store,
                            },
                        })
                    })
                    .collect();
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some(&format!("{label}.pass")),
                    color_attachments: &attachments,
                    depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                        view: &targets.depth,
                        depth_ops: Some(wgpu::Operations {
                            load: depth_load,
                            store: wgpu::StoreOp::Store,
                        }),
                        stencil_ops: None,
                    }),
                    timestamp_writes: None,
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                for (call, (pipeline, indices)) in draws.iter().zip(&pipelines) {
                    if call.setup.pass != k {
                        continue;
                    }
                    let vp = call.setup.viewport;
                    pass.set_viewport(vp.x, vp.y, vp.width, vp.height, vp.min_depth, vp.max_depth);
                    let [x, y, w, h] = call.setup.scissor;
                    pass.set_scissor_rect(x, y, w, h);
                    pass.set_pipeline(pipeline);
                    if let Some(group) = &call.bind_group {
                        pass.set_bind_group(0, group, &[]);
                    }
                    pass.set_vertex_buffer(0, call.vertices.slice(..));
                    match indices {
                        Some(b) => {
                            pass.set_index_buffer(b.slice(..), wgpu::IndexFormat::Uint32);
                            pass.draw_indexed(call.setup.range.clone(), 0, 0..1);
                        }
                        None => pass.draw(call.setup.range.clone(), 0..1),
                    }
                }
            }
            if passes.is_empty() {
                for v in &views {
                    let _ = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                        label: Some(&format!("{label}.clear")),
                        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                            view: v,
                            depth_slice: None,
                            resolve_target: None,
                            ops: wgpu::Operations {
                                load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                                store: wgpu::StoreOp::Store,
                            },
                        })],
                        depth_stencil_attachment: None,
                        timestamp_writes: None,
                        occlusion_query_set: None,
                        multiview_mask: None,
                    });
                }
            }
        })?;
        Ok(Drawn {
            resolved,
            components,
            value,
            format,
            size: (w, h),
        })
    }
}

/// What [`ViewDrawer::encode`] drew: the line it resolved to (none: a cost view), the
/// value's components, whether there is a value target, its format and the size.
#[derive(Clone, Debug)]
pub struct Drawn {
    /// The line the probe resolved to; `None` for a cost view.
    pub resolved: Option<Resolved>,
    /// The value's components (0 for a cost view).
    pub components: u32,
    /// Whether the value target was drawn (a line view).
    pub value: bool,
    /// The value target's format.
    pub format: wgpu::TextureFormat,
    /// The targets' size.
    pub size: (u32, u32),
}

/// The format of a view's value target for a value of `components` components: as few
/// 32-bit floats a texel as hold them, since reading back is most of a view's time.
fn value_format(components: u32) -> wgpu::TextureFormat {
    match components {
        0 | 1 => wgpu::TextureFormat::R32Float,
        2 => wgpu::TextureFormat::Rg32Float,
        _ => wgpu::TextureFormat::Rgba32Float,
    }
}

/// The 32-bit words of a texel of `format` (a value format).
fn texel_words(format: wgpu::TextureFormat) -> usize {
    match format {
        wgpu::TextureFormat::R32Float => 1,
        wgpu::TextureFormat::Rg32Float => 2,
        _ => 4,
    }
}
/// The format of a view's info target ([`instrument::fragment`]'s info word).
const INFO_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;

/// A view's targets (each with its view), depth and read-back buffers, kept while the size
/// stays.
struct Targets {
    device: wgpu::Device,
    width: u32,
    height: u32,
    /// The value target's format.
    format: wgpu::TextureFormat,
    value: (wgpu::Texture, wgpu::TextureView),
    info: (wgpu::Texture, wgpu::TextureView),
    value_stride: u32,
    info_stride: u32,
    depth: wgpu::TextureView,
    /// The read-back buffer, a band of rows of either target, made by the first read-back (a
    /// view painted on the GPU reads nothing back).
    staging: Option<wgpu::Buffer>,
}

/// One of a view's targets, to read back.
#[cfg(not(target_arch = "wasm32"))]
#[derive(Clone, Copy)]
enum Kept {
    Value,
    Info,
}

/// The most bytes one band of a read-back holds.
#[cfg(not(target_arch = "wasm32"))]
const BAND_BYTES: u64 = 16 << 20;

impl Targets {
    fn new(device: &wgpu::Device, width: u32, height: u32, format: wgpu::TextureFormat) -> Targets {
        let label = "shaderlab.debug.view";
        let target = |name: &str, format| {
            let usage = wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::TEXTURE_BINDING;
            crate::gpu::targets::texture_and_view(device, &format!("{label}.{name}"), (width, height), format, usage)
        };
        let value_stride = crate::offscreen::padded_row(4 * texel_words(format) as u32, width);
        let info_stride = crate::offscreen::padded_row(4, width);
        let depth = crate::gpu::targets::depth_texture(device, width, height);
        Targets {
            device: device.clone(),
            width,
            height,
            format,
            value: target("value", format),
            info: target("info", INFO_FORMAT),
            value_stride,
            info_stride,
            depth,
            staging: None,
        }
    }

    /// Reads target `which` back band by band of rows, top first, through one buffer of at
    /// most [`BAND_BYTES`] (at least a row), handing each row's texels to `take`.
    #[cfg(not(target_arch = "wasm32"))]
    fn read_rows(&mut self, gpu: &Gpu, which: Kept, mut take: impl FnMut(&[u8])) -> Result<()> {
        let label = "shaderlab.debug.view";
        let (texture, stride, texel) = match which {
            Kept::Value => (&self.value.0, self.value_stride, 4 * texel_words(self.format)),
            Kept::Info => (&self.info.0, self.info_stride, 4),
        };
        let biggest = self.value_stride.max(self.info_stride);
        let band = (BAND_BYTES / u64::from(biggest)).clamp(1, u64::from(self.height)) as u32;
        let device = &self.device;
        let staging = self.staging.get_or_insert_with(|| {
            crate::offscreen::readback_buffer(device, &format!("{label}.staging"), biggest, band)
        });
        let row_bytes = self.width as usize * texel;
        let mut top = 0;
        while top < self.height {
            let rows = band.min(self.height - top);
            let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some(&format!("{label}.read_back")),
            });
            encoder.copy_texture_to_buffer(
                wgpu::TexelCopyTextureInfo {
                    texture,
                    mip_level: 0,
                    origin: wgpu::Origin3d { x: 0, y: top, z: 0 },
                    aspect: wgpu::TextureAspect::All,
                },
                wgpu::TexelCopyBufferInfo {
                    buffer: staging,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(stride),
                        rows_per_image: Some(rows),
                    },
                },
                wgpu::Extent3d {
                    width: self.width,
                    height: rows,
                    depth_or_array_layers: 1,
                },
            );
            let commands = gpu.checked(label, || encoder.finish())?;
            gpu.queue.submit([commands]);
            let mapped = Arc::new(std::sync::atomic::AtomicBool::new(false));
            let flag = mapped.clone();
            let slice = staging.slice(..u64::from(stride) * u64::from(rows));
            // Set whether it mapped or not: a mapping that failed shows when read.
            slice.map_async(wgpu::MapMode::Read, move |_| {
                flag.store(true, std::sync::atomic::Ordering::SeqCst);
            });
            let waited = gpu.wait_until("reading a view back", || {
                mapped.load(std::sync::atomic::Ordering::SeqCst)
            });
            let result = waited.and_then(|()| {
                let data = slice.get_mapped_range().map_err(|e| crate::error::Error::Wgpu {
                    context: "reading a view back".into(),
                    message: e.to_string(),
                })?;
                for y in 0..rows as usize {
                    take(&data[y * stride as usize..][..row_bytes]);
                }
                Ok(())
            });
            staging.unmap();
            result?;
            top += rows;
        }
        Ok(())
    }
}

/// Draws the view `probe` of the frame `log` wrote down (at `width` × `height`) with a drawer
/// of its own; see [`ViewDrawer`] to draw views again and again.
#[cfg(not(target_arch = "wasm32"))]
pub fn draw_view(gpu: &Gpu, log: &DrawLog, probe: &Probe, width: u32, height: u32) -> Result<ValueFrame> {
    ViewDrawer::new().draw_once(gpu, log, probe, width, height)
}

/// Encodes one frame of `lab` at `width` × `height` with its draws written down, without
/// running it: what a view draws again.
pub fn encode(gpu: &Gpu, lab: &mut dyn crate::lab::Lab, width: u32, height: u32) -> Result<DrawLog> {
    let target = crate::offscreen::Offscreen::with_format(gpu, width, height, crate::offscreen::COLOR_FORMAT);
    let log = DrawLog::new();
    let _frame = crate::lab::frame::encode(gpu, lab, &target, Some(&log))?;
    Ok(log)
}

/// Encodes one frame of `lab` against `target` (its size and format) with its draws written
/// down, without running it.
pub fn encode_to(gpu: &Gpu, lab: &mut dyn crate::lab::Lab, target: &crate::offscreen::Offscreen) -> Result<DrawLog> {
    let log = DrawLog::new();
    let _frame = crate::lab::frame::encode(gpu, lab, target, Some(&log))?;
    Ok(log)
}

/// Encodes one frame of `lab` as [`encode`] does, for a lab whose pipelines draw in `format`
/// (a window's lab draws in its surface's format).
pub fn encode_in(
    gpu: &Gpu,
    lab: &mut dyn crate::lab::Lab,
    width: u32,
    height: u32,
    format: wgpu::TextureFormat,
) -> Result<DrawLog> {
    let target = crate::offscreen::Offscreen::with_format(gpu, width, height, format);
    let log = DrawLog::new();
    let _frame = crate::lab::frame::encode(gpu, lab, &target, Some(&log))?;
    Ok(log)
}

/// Encodes one frame of `lab` with its draws written down and brings them to the CPU: the log
/// a view draws from and the capture the debugger replays, of the same frame.
#[cfg(not(target_arch = "wasm32"))]
pub fn capture(
    gpu: &Gpu,
    lab: &mut dyn crate::lab::Lab,
    width: u32,
    height: u32,
) -> Result<(DrawLog, super::Captured)> {
    let log = encode(gpu, lab, width, height)?;
    let captured = super::Pending::start(gpu, &log).wait(gpu)?;
    Ok((log, captured))
}
