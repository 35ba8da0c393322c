//! Whole-frame views in the shells, written once for the window and the page (the
//! [`super::session::Session`] owns them): which view is asked for (a line's value, the cost,
//! the diff against the built-in shaders), its picture at the lab's current state with the
//! legend strip under it ([`crate::debug::picture`]), drawn again whenever the lab's state or
//! the size changes, and a blit that puts the picture where the lab's frame would go.
//!
//! The picture is the size of the surface: the view is drawn at the surface's width and its
//! height less the legend strip ([`crate::debug::picture::LEGEND_HEIGHT`]), so that picture and
//! legend fill the surface pixel for pixel. A view that cannot be drawn (a line that assigns
//! nothing, a diff of a copy with other inputs) leaves the text that says why, and the lab's
//! frame shows.

use image::RgbaImage;

use crate::debug::paint::{Kind, Painter};
use crate::debug::view::{Probe, ViewDrawer};
use crate::debug::{picture, Stage};
use crate::error::Choose;
use crate::gpu::Gpu;
use crate::lab::Lab;
use crate::offscreen::Offscreen;

/// A view the user asked for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Wanted {
    /// A line's value or the cost, at every pixel, drawn by the instrumented shaders.
    Probe(Probe),
    /// The difference from the lab drawn with its built-in shaders.
    Diff,
}

impl From<Probe> for Wanted {
    fn from(probe: Probe) -> Wanted {
        Wanted::Probe(probe)
    }
}

impl Wanted {
    /// The cost view.
    pub const COST: Wanted = Wanted::Probe(Probe::Cost);

    /// The view of `line` of `file` (as the lab shows it), no name or stage chosen.
    pub fn line(file: &str, line: u32) -> Wanted {
        Wanted::Probe(Probe::Line {
            file: file.to_owned(),
            line,
            name: None,
            stage: None,
        })
    }

    /// The view in a few words, for the title and the panel (`phong.frag:31`,
    /// `phong.frag:31 R`, `cost`, `diff`).
    pub fn words(&self) -> String {
        match self {
            Wanted::Probe(Probe::Line { name: Some(n), .. }) => format!("{} {n}", self.place()),
            Wanted::Probe(Probe::Line { .. }) => self.place(),
            Wanted::Probe(Probe::Cost) => "cost".into(),
            Wanted::Diff => "diff with the built-in shaders".into(),
        }
    }

    /// A line's file name and line (`phong.frag:31`); the view's words otherwise.
    fn place(&self) -> String {
        match self {
            Wanted::Probe(Probe::Line { file, line, .. }) => {
                format!("{}:{line}", file.rsplit(['/', '\\']).next().unwrap_or(file))
            }
            _ => self.words(),
        }
    }

    /// The line a line view shows: its file (as the lab shows it) and line.
    pub fn line_shown(&self) -> Option<(&str, u32)> {
        match self {
            Wanted::Probe(Probe::Line { file, line, .. }) => Some((file, *line)),
            _ => None,
        }
    }

    /// The view as the page's link writes it: `FILE:LINE`, then `:NAME` where a name was
    /// chosen and `@vertex` or `@fragment` where a stage was; `cost`; `diff`.
    pub fn link(&self) -> String {
        match self {
            Wanted::Probe(Probe::Line {
                file,
                line,
                name,
                stage,
            }) => {
                let mut text = format!("{file}:{line}");
                if let Some(n) = name {
                    text = format!("{text}:{n}");
                }
                match stage {
                    Some(Stage::Vertex) => text.push_str("@vertex"),
                    Some(Stage::Fragment) => text.push_str("@fragment"),
                    None => {}
                }
                text
            }
            Wanted::Probe(Probe::Cost) => "cost".into(),
            Wanted::Diff => "diff".into(),
        }
    }

    /// The view a link's `view=` names ([`Wanted::link`]'s words); `None` for text that is
    /// none of them.
    pub fn from_link(text: &str) -> Option<Wanted> {
        if text == "diff" {
            return Some(Wanted::Diff);
        }
        let (text, stage) = match text.rsplit_once('@') {
            Some((t, "vertex")) => (t, Some(Stage::Vertex)),
            Some((t, "fragment")) => (t, Some(Stage::Fragment)),
            _ => (text, None),
        };
        // A GLSL name never starts with a digit: a last part that is no number is the name
        // (a variable, or part of one: `c.xy`, `m[1]`, `arr[i]`), and `FILE:LINE` comes
        // before it.
        let named = text.rsplit_once(':').filter(|(_, last)| {
            last.chars().next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
                && last
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '.' | '[' | ']'))
        });
        let (text, name) = match named {
            Some((rest, last)) => (rest, Some(last.to_owned())),
            None => (text, None),
        };
        match text.parse::<Probe>().ok()? {
            Probe::Line { file, line, .. } => Some(Wanted::Probe(Probe::Line {
                file,
                line,
                name,
                stage,
            })),
            Probe::Cost => (name.is_none() && stage.is_none()).then_some(Wanted::COST),
        }
    }

    /// The same line with `name` or `stage` chosen: what a choice offered by a view that
    /// could not be drawn asks for.
    fn with(&self, name: Option<&str>, stage: Option<Stage>) -> Wanted {
        let mut chosen = self.clone();
        if let Wanted::Probe(Probe::Line { name: n, stage: s, .. }) = &mut chosen {
            if let Some(name) = name {
                *n = Some(name.to_owned());
            }
            if stage.is_some() {
                *s = stage;
            }
        }
        chosen
    }
}

/// Why a diff has nothing to compare.
const NOTHING_TO_COMPARE: &str =
    "the lab draws with its built-in shaders: there is nothing to compare (edit a shader, or run it with --shaders DIR)";

/// A view's picture and what it says in words (the legend, the diff's findings).
pub struct Picture {
    /// The picture with its legend strip, the surface's size, where the CPU made it (a diff);
    /// a line or cost view's picture is made on the GPU and stays there ([`Views::read`]).
    pub image: Option<RgbaImage>,
    /// The legend or the diff's report, in words.
    pub text: String,
}

/// The views' state: the view asked for, its last picture (or why there is none), the state
/// it was drawn at, and what draws it again without building anew.
///
/// A line or cost view is drawn on the GPU, picture included ([`Painter`]): drawing it waits
/// for nothing, and only its legend's few numbers come back, a frame or two later. A diff
/// compares two traces on the CPU.
#[derive(Default)]
pub struct Views {
    wanted: Option<Wanted>,
    drawer: ViewDrawer,
    painter: Option<Painter>,
    /// What the lab's frame is recorded against to write its draws down (never drawn).
    scratch: Option<Offscreen>,
    /// The session's version and the size the last picture was drawn at.
    taken: Option<(u64, (u32, u32))>,
    shown: Option<Result<Picture, String>>,
    /// What may be chosen to draw a view that could not be drawn as asked, in words.
    choices: Vec<(String, Wanted)>,
    /// Whether the painter's picture is the view asked for.
    painted: bool,
    /// Pictures painted so far (the last one's number), and the number of the first of the
    /// view asked for.
    paints: u64,
    first_paint: u64,
    /// The legend that came back is of an earlier picture: paint again to read the last's.
    stale: bool,
    /// How the line view's legend begins (`phong.frag:31 = \`NdotL\``).
    legend_words: String,
    /// The lab drawn with its built-in shaders, for the diff.
    reference: Option<Box<dyn Lab>>,
    blit: Option<Blit>,
    /// The diff's picture on the GPU, and whether it needs the CPU's picture uploaded.
    uploaded: Option<(wgpu::Device, wgpu::Texture, wgpu::TextureView)>,
    upload: bool,
    /// The diff's two frames being read back without blocking: the lab's and the reference's.
    pending_diff: Option<crate::debug::diff::Frames>,
}

impl Views {
    /// The view asked for.
    pub fn wanted(&self) -> Option<&Wanted> {
        self.wanted.as_ref()
    }

    /// Asks for `wanted` (none: back to the lab's picture); asking for the view shown turns it
    /// off. `reference` is the lab with its built-in shaders, for a diff.
    pub fn toggle(&mut self, wanted: Wanted, reference: Option<Box<dyn Lab>>) {
        if self.wanted.as_ref() == Some(&wanted) {
            self.set(None, None);
        } else {
            self.set(Some(wanted), reference);
        }
    }

    /// Asks for `wanted` (none: back to the lab's picture).
    pub fn set(&mut self, wanted: Option<Wanted>, reference: Option<Box<dyn Lab>>) {
        self.wanted = wanted;
        self.reference = reference;
        self.taken = None;
        self.shown = None;
        self.choices.clear();
        self.painted = false;
        self.first_paint = self.paints + 1;
        self.stale = false;
        self.pending_diff = None;
    }

    /// Whether the view waits for the GPU: a legend or a diff's frames being read back.
    pub fn busy(&self) -> bool {
        self.pending_diff.is_some() || self.stale || self.painter.as_ref().is_some_and(Painter::reading)
    }

    /// What may be chosen where the view could not be drawn as asked (the names a line
    /// assigns, or the stage of a file both include): the words for each and the view it asks
    /// for. Empty otherwise.
    pub fn choices(&self) -> &[(String, Wanted)] {
        &self.choices
    }

    /// Moves the view on: draws it again when the lab's state (`version`) or `size` changed
    /// since its last picture (or a legend of an older picture came back), takes a legend
    /// that is back, and a diff's frames that are back. Returns whether a new picture, legend
    /// or error was made. With `wait`, a diff is made at once (the window); without, its frames
    /// are read back over calls (the page, which cannot block). A line or cost view waits for
    /// nothing either way.
    pub fn update(
        &mut self,
        gpu: &Gpu,
        lab: &mut dyn Lab,
        version: u64,
        size: (u32, u32),
        format: wgpu::TextureFormat,
        wait: bool,
    ) -> bool {
        let Some(wanted) = self.wanted.clone() else {
            return false;
        };
        let mut made = self.take_legend(gpu, &wanted, size);
        let Wanted::Probe(probe) = &wanted else {
            return made | self.update_diff(gpu, lab, version, size, format, wait);
        };
        if self.taken == Some((version, size)) && !self.stale {
            return made;
        }
        self.taken = Some((version, size));
        self.stale = false;
        let (w, h) = view_size(size);
        match self.paint(gpu, lab, (&wanted, probe), (w, h), format) {
            Ok(()) => {
                self.painted = true;
                if !matches!(self.shown, Some(Ok(_))) {
                    // Drawn; its words come with its legend.
                    self.shown = None;
                }
            }
            Err(e) => {
                self.failed(&wanted, e);
                made = true;
            }
        }
        made
    }

    /// Draws the line or cost view `wanted` (of `probe`) of `lab` at `(w, h)` and its
    /// picture, on the GPU.
    fn paint(
        &mut self,
        gpu: &Gpu,
        lab: &mut dyn Lab,
        (wanted, probe): (&Wanted, &Probe),
        (w, h): (u32, u32),
        format: wgpu::TextureFormat,
    ) -> crate::error::Result<()> {
        let fits = |o: &Offscreen| (o.width, o.height, o.format()) == (w, h, format);
        if !self.scratch.as_ref().is_some_and(fits) {
            self.scratch = Some(Offscreen::with_format(gpu, w, h, format));
        }
        let log = crate::debug::view::encode_to(gpu, lab, self.scratch.as_ref().expect("made above"))?;
        let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("shaderlab.view"),
        });
        let drawn = self.drawer.encode(gpu, &mut encoder, &log, probe, w, h)?;
        if !self.painter.as_ref().is_some_and(|p| p.serves(&gpu.device)) {
            self.painter = Some(Painter::new(&gpu.device));
        }
        let painter = self.painter.as_mut().expect("made above");
        self.paints += 1;
        let targets = self.drawer.targets().expect("drawn above");
        painter.paint(gpu, &mut encoder, targets, &drawn, self.paints)?;
        let commands = gpu.checked("shaderlab.view", || encoder.finish())?;
        gpu.queue.submit([commands]);
        painter.submitted();
        self.legend_words = legend_words(wanted, &drawn);
        Ok(())
    }

    /// Takes a legend that came back: writes its strip into the picture and its words into
    /// the text. One of an older picture of this view still stands until the next, and asks
    /// for the last picture to be painted again for its own; one of another view is dropped.
    fn take_legend(&mut self, gpu: &Gpu, wanted: &Wanted, size: (u32, u32)) -> bool {
        let Some(painter) = self.painter.as_mut() else {
            return false;
        };
        if !painter.reading() {
            return false;
        }
        let _ = gpu.device.poll(wgpu::PollType::Poll);
        let Some(back) = painter.legend() else {
            return false;
        };
        let (stats, tag, kind) = match back {
            Ok(b) => b,
            Err(e) => {
                self.shown = Some(Err(e.to_string()));
                return true;
            }
        };
        if tag < self.first_paint || *wanted == Wanted::Diff {
            self.stale = self.painted;
            return false;
        }
        self.stale = tag < self.paints;
        painter.write_strip(gpu, &kind.strip(size.0.max(1), &stats));
        let text = match kind {
            Kind::Value(c) => format!("{}: {}", self.legend_words, stats.legend(c).text()),
            Kind::Cost => format!(
                "cost: statements the fragment shader ran, 0 … {} (viridis); black: no fragment",
                stats.max_cost as u32
            ),
        };
        self.shown = Some(Ok(Picture { image: None, text }));
        true
    }

    /// Keeps why `wanted` could not be drawn, and what may be chosen instead.
    fn failed(&mut self, wanted: &Wanted, e: crate::error::Error) {
        self.choices = match &e {
            crate::error::Error::View { choose, .. } => match choose {
                Choose::Name(names) => names.iter().map(|n| (n.clone(), wanted.with(Some(n), None))).collect(),
                Choose::Stage => [(Stage::Vertex, "vertex shader"), (Stage::Fragment, "fragment shader")]
                    .into_iter()
                    .map(|(s, words)| (words.to_owned(), wanted.with(None, Some(s))))
                    .collect(),
                Choose::Nothing => Vec::new(),
            },
            _ => Vec::new(),
        };
        self.painted = false;
        self.shown = Some(Err(e.to_string()));
    }

    /// The diff: made at once (`wait`) or over calls when the state or size changed.
    fn update_diff(
        &mut self,
        gpu: &Gpu,
        lab: &mut dyn Lab,
        version: u64,
        size: (u32, u32),
        format: wgpu::TextureFormat,
        wait: bool,
    ) -> bool {
        if let Some(frames) = &self.pending_diff {
            if !frames.ready(gpu) {
                return false;
            }
            let made = self.pending_diff.take().expect("checked above").take(gpu, false);
            self.show_diff(lab, made);
            return true;
        }
        if self.taken == Some((version, size)) {
            return false;
        }
        self.taken = Some((version, size));
        let (w, h) = view_size(size);
        let Some(reference) = self.reference.as_mut() else {
            self.shown = Some(Err(NOTHING_TO_COMPARE.into()));
            return true;
        };
        carry_params(lab, reference.as_mut());
        // Both labs draw in the surface's format: each frame is captured with its picture.
        match crate::debug::diff::Frames::start(gpu, lab, reference.as_mut(), (w, h), format) {
            Ok(frames) if wait && cfg!(not(target_arch = "wasm32")) => {
                let made = frames.take(gpu, true);
                self.show_diff(lab, made);
                true
            }
            Ok(frames) => {
                self.pending_diff = Some(frames);
                false
            }
            Err(e) => {
                self.shown = Some(Err(e.to_string()));
                true
            }
        }
    }

    fn show_diff(
        &mut self,
        lab: &dyn Lab,
        made: crate::error::Result<(crate::debug::Captured, crate::debug::Captured)>,
    ) {
        let name = lab.info().name;
        let made = made
            .and_then(|(mine, reference)| crate::debug::diff::diff(name, &mine, &reference))
            .map(|diff| Picture {
                text: diff.text(),
                image: Some(diff.picture),
            })
            .map_err(|e| e.to_string());
        self.upload = made.is_ok();
        self.shown = Some(made);
    }

    /// The last picture's words, or why there is none; `None` while no view is asked for (or
    /// while its first legend is on its way).
    pub fn shown(&self) -> Option<&Result<Picture, String>> {
        self.shown.as_ref().filter(|_| self.wanted.is_some())
    }

    /// The picture shown instead of the lab's frame, read back (blocking): what the surface
    /// shows. `None` while there is none.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn read(&self, gpu: &Gpu) -> Option<crate::error::Result<RgbaImage>> {
        match self.wanted.as_ref()? {
            Wanted::Diff => match self.shown()? {
                Ok(p) => p.image.clone().map(Ok),
                Err(_) => None,
            },
            _ if self.painted => self.painter.as_ref().map(|p| p.read(gpu)),
            _ => None,
        }
    }

    /// Encodes the picture into `color` (of `format`) in `encoder`, in place of the lab's
    /// frame; returns whether there was one.
    pub fn encode(
        &mut self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        color: &wgpu::TextureView,
        format: wgpu::TextureFormat,
    ) -> bool {
        let Some(wanted) = &self.wanted else {
            return false;
        };
        let source = if *wanted == Wanted::Diff {
            let Some(Ok(Picture { image: Some(image), .. })) = &self.shown else {
                return false;
            };
            let fits = |t: &(wgpu::Device, wgpu::Texture, wgpu::TextureView)| {
                t.0 == gpu.device && (t.1.width(), t.1.height()) == image.dimensions()
            };
            if !self.uploaded.as_ref().is_some_and(fits) {
                let (texture, color) = upload_texture(&gpu.device, image.dimensions());
                self.uploaded = Some((gpu.device.clone(), texture, color));
                self.upload = true;
            }
            let (_, texture, color) = self.uploaded.as_ref().expect("made above");
            if self.upload {
                crate::debug::paint::write_rgba(gpu, texture, 0, image);
                self.upload = false;
            }
            color
        } else {
            match (&self.painter, self.painted) {
                (Some(p), true) => match p.picture() {
                    Some(v) => v,
                    None => return false,
                },
                _ => return false,
            }
        };
        let fits = |b: &Blit| b.device == gpu.device && b.format == format;
        if !self.blit.as_ref().is_some_and(fits) {
            self.blit = Some(Blit::new(&gpu.device, format));
        }
        self.blit.as_mut().expect("made above").encode(encoder, color, source);
        true
    }
}

/// A line view's legend begins with what it shows: `phong.frag:31 = \`NdotL\``, and says
/// when it is a vertex shader's line.
fn legend_words(wanted: &Wanted, drawn: &crate::debug::view::Drawn) -> String {
    let what = match drawn.resolved.as_ref().and_then(|r| r.site.name.as_ref()) {
        Some(n) => format!("{} = `{n}`", wanted.place()),
        None => wanted.words(),
    };
    if drawn.resolved.as_ref().is_some_and(|r| r.stage == Stage::Vertex) {
        format!("{what} (a vertex shader line: its value at the corners, interpolated as a varying)")
    } else {
        what
    }
}

/// The size a view is drawn at for a surface of `size`: its width, its height less the
/// legend strip (at least one pixel).
pub fn view_size((w, h): (u32, u32)) -> (u32, u32) {
    (w.max(1), h.saturating_sub(picture::LEGEND_HEIGHT).max(1))
}

/// Gives `reference` the parameters of `lab`, by name where the count of numbers is the same.
fn carry_params(lab: &dyn Lab, reference: &mut dyn Lab) {
    let from = lab.params();
    let to = reference.params_mut();
    for spec in from.specs() {
        if let (Some(value), Some(default)) = (from.get(spec.name), to.get(spec.name)) {
            if value.len() == default.len() {
                to.set_unchecked(spec.name, value);
            }
        }
    }
}

/// Draws an RGBA picture onto a surface pixel for pixel (top left on top left; black where
/// the picture does not reach).
struct Blit {
    device: wgpu::Device,
    format: wgpu::TextureFormat,
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    /// The bind group of the last picture drawn, kept while the picture is the same.
    group: Option<(wgpu::TextureView, wgpu::BindGroup)>,
}

const BLIT_SHADER: &str = r"
@group(0) @binding(0) var picture: texture_2d<f32>;

@fragment
fn fs(@builtin(position) at: vec4<f32>) -> @location(0) vec4<f32> {
    let size = textureDimensions(picture);
    let p = vec2<u32>(at.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    return vec4<f32>(textureLoad(picture, vec2<i32>(p), 0).rgb, 1.0);
}
";

impl Blit {
    fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Blit {
        let label = "shaderlab.view_blit";
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(&format!("{label}.shader")),
            source: wgpu::ShaderSource::Wgsl(format!("{}{BLIT_SHADER}", crate::gpu::targets::FULL_SCREEN_WGSL).into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&format!("{label}.bind_group_layout")),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: false },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            }],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(&format!("{label}.pipeline_layout")),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let target = [Some(wgpu::ColorTargetState {
            format,
            blend: None,
            write_mask: wgpu::ColorWrites::ALL,
        })];
        let pipeline = crate::gpu::targets::full_screen_pipeline(
            device,
            &format!("{label}.pipeline"),
            &pipeline_layout,
            &module,
            "fs",
            &target,
        );
        Blit {
            device: device.clone(),
            format,
            pipeline,
            layout,
            group: None,
        }
    }

    /// Encodes drawing `picture` (an `Rgba8Unorm` texture's view) into `color`.
    fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, color: &wgpu::TextureView, picture: &wgpu::TextureView) {
        let label = "shaderlab.view_blit";
        if self.group.as_ref().is_none_or(|(v, _)| v != picture) {
            let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(&format!("{label}.bind_group")),
                layout: &self.layout,
                entries: &[wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(picture),
                }],
            });
            self.group = Some((picture.clone(), group));
        }
        let (_, group) = self.group.as_ref().expect("made above");
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(&format!("{label}.pass")),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: color,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, group, &[]);
        pass.draw(0..3, 0..1);
    }
}

/// A texture a CPU-made picture of `(w, h)` is uploaded into, and its view.
fn upload_texture(device: &wgpu::Device, (w, h): (u32, u32)) -> (wgpu::Texture, wgpu::TextureView) {
    let usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
    let label = "shaderlab.view_blit.picture";
    crate::gpu::targets::texture_and_view(
        device,
        label,
        (w.max(1), h.max(1)),
        wgpu::TextureFormat::Rgba8Unorm,
        usage,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn links_name_views_and_refuse_other_text() {
        for w in [
            Wanted::COST,
            Wanted::Diff,
            Wanted::Probe(Probe::Line {
                file: "shaders/phong.frag".into(),
                line: 31,
                name: None,
                stage: None,
            }),
            Wanted::Probe(Probe::Line {
                file: "C:\\shaders\\common.glsl".into(),
                line: 7,
                name: Some("light_dir".into()),
                stage: Some(Stage::Vertex),
            }),
            Wanted::Probe(Probe::Line {
                file: "phong.frag".into(),
                line: 12,
                name: None,
                stage: Some(Stage::Fragment),
            }),
            Wanted::Probe(Probe::Line {
                file: "normal_rgb.frag".into(),
                line: 8,
                name: Some("c.xy".into()),
                stage: None,
            }),
            Wanted::Probe(Probe::Line {
                file: "normal_rgb.frag".into(),
                line: 13,
                name: Some("m[1]".into()),
                stage: Some(Stage::Fragment),
            }),
        ] {
            assert_eq!(Wanted::from_link(&w.link()), Some(w));
        }
        assert_eq!(
            Wanted::from_link("a/phong.frag:31:R").map(|w| w.link()),
            Some("a/phong.frag:31:R".to_owned())
        );
        for bad in [
            "",
            "phong.frag",
            "phong.frag:0",
            "phong.frag:x",
            ":3",
            "costs",
            "phong.frag:3:1x",
            "phong.frag:3:a-b",
            "phong.frag:3@sideways",
        ] {
            assert_eq!(Wanted::from_link(bad), None, "{bad:?}");
        }
    }

    #[test]
    fn a_view_fills_the_surface_with_its_legend() {
        assert_eq!(view_size((640, 480)), (640, 480 - picture::LEGEND_HEIGHT));
        assert_eq!(view_size((0, 3)), (1, 1));
    }
}
