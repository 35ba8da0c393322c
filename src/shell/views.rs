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

use crate::debug::view::{PendingView, Probe, ViewDrawer};
use crate::debug::{picture, Stage};
use crate::gpu::Gpu;
use crate::lab::Lab;

/// A view the user asked for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Wanted {
    /// The value a line of a shader assigns, at every pixel.
    Line {
        /// The file as the lab shows it.
        file: String,
        /// The 1-based line.
        line: u32,
        /// The stage (where both include the file).
        stage: Option<Stage>,
    },
    /// The statements the fragment shader ran at every pixel.
    Cost,
    /// The difference from the lab drawn with its built-in shaders.
    Diff,
}

impl Wanted {
    /// The view in a few words, for the title and the panel (`phong.frag:31`, `cost`, `diff`).
    pub fn words(&self) -> String {
        match self {
            Wanted::Line { file, line, .. } => {
                format!("{}:{line}", file.rsplit(['/', '\\']).next().unwrap_or(file))
            }
            Wanted::Cost => "cost".into(),
            Wanted::Diff => "diff with the built-in shaders".into(),
        }
    }

    /// The view as the page's link writes it (`view=FILE:LINE`, `view=cost`, `view=diff`).
    pub fn link(&self) -> String {
        match self {
            Wanted::Line { file, line, .. } => format!("{file}:{line}"),
            Wanted::Cost => "cost".into(),
            Wanted::Diff => "diff".into(),
        }
    }

    /// The view a link's `view=` names: `cost`, `diff` or `FILE:LINE`; `None` for text that is
    /// none of them.
    pub fn from_link(text: &str) -> Option<Wanted> {
        match text {
            "cost" => Some(Wanted::Cost),
            "diff" => Some(Wanted::Diff),
            _ => {
                let (file, line) = text.rsplit_once(':')?;
                let line: u32 = line.parse().ok().filter(|&l| l > 0)?;
                (!file.is_empty()).then(|| Wanted::Line {
                    file: file.to_owned(),
                    line,
                    stage: None,
                })
            }
        }
    }

    fn probe(&self) -> Probe {
        match self {
            Wanted::Line { file, line, stage } => Probe::Line {
                file: file.clone(),
                line: *line,
                name: None,
                stage: *stage,
            },
            _ => Probe::Cost,
        }
    }
}

/// Why a diff has nothing to compare.
const NOTHING_TO_COMPARE: &str =
    "the lab draws with its built-in shaders: there is nothing to compare (edit a shader, or run it with --shaders DIR)";

/// A view's picture and what it says in words (the legend, the diff's findings).
pub struct Picture {
    /// The picture with its legend strip, the surface's size.
    pub image: RgbaImage,
    /// The legend or the diff's report, in words.
    pub text: String,
}

/// The views' state: the view asked for, its last picture (or why there is none), the state
/// it was drawn at, and what draws it again without building anew.
#[derive(Default)]
pub struct Views {
    wanted: Option<Wanted>,
    drawer: ViewDrawer,
    /// The session's version and the size the last picture was drawn at.
    taken: Option<(u64, (u32, u32))>,
    shown: Option<Result<Picture, String>>,
    /// The lab drawn with its built-in shaders, for the diff.
    reference: Option<Box<dyn Lab>>,
    blit: Option<Blit>,
    /// The view being read back without blocking ([`Views::poll`], the page's way), and the
    /// view it is of. It is finished even when another view is asked for meanwhile: the
    /// drawer's read-back buffers are its until then.
    pending: Option<(PendingView, Wanted)>,
    /// The diff's two frames being read back without blocking: the lab's and the reference's.
    pending_diff: Option<(crate::debug::Pending, crate::debug::Pending)>,
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
        self.pending_diff = None;
    }

    /// Whether a view is being read back ([`Views::poll`]).
    pub fn busy(&self) -> bool {
        self.pending.is_some() || self.pending_diff.is_some()
    }

    /// Moves the view on without blocking (the page, which cannot wait for the GPU): values
    /// that are back become the picture; otherwise, when the lab's state (`version`) or `size`
    /// changed since the last picture, the view is drawn again and its read-back starts.
    /// Returns whether a new picture (or error) was made. A diff's two frames are read back
    /// the same way, then compared at once.
    pub fn poll(
        &mut self,
        gpu: &Gpu,
        lab: &mut dyn Lab,
        version: u64,
        size: (u32, u32),
        format: wgpu::TextureFormat,
    ) -> bool {
        if let Some((pending, _)) = &self.pending {
            let _ = gpu.device.poll(wgpu::PollType::Poll);
            if !pending.ready() {
                return false;
            }
            let (pending, of) = self.pending.take().expect("checked above");
            let made = self.drawer.finish(pending);
            // A view asked for since the read-back started is drawn next.
            if self.wanted.as_ref() == Some(&of) {
                self.shown = Some(made.map(|frame| picture_of(&of, &frame)).map_err(|e| e.to_string()));
                return true;
            }
        }
        let Some(wanted) = self.wanted.clone() else {
            return false;
        };
        if let Some((mine, reference)) = &self.pending_diff {
            let _ = gpu.device.poll(wgpu::PollType::Poll);
            if !(mine.ready() && reference.ready()) {
                return false;
            }
            let (mine, reference) = self.pending_diff.take().expect("checked above");
            let name = lab.info().name;
            let made = mine
                .finish()
                .and_then(|mine| Ok((mine, reference.finish()?)))
                .and_then(|(mine, reference)| crate::debug::diff::diff(name, &mine, &reference))
                .map(|diff| Picture {
                    text: diff.text(),
                    image: diff.picture,
                })
                .map_err(|e| e.to_string());
            self.shown = Some(made);
            return true;
        }
        if self.taken == Some((version, size)) {
            return false;
        }
        self.taken = Some((version, size));
        let (w, h) = view_size(size);
        if wanted == Wanted::Diff {
            let Some(reference) = self.reference.as_mut() else {
                self.shown = Some(Err(NOTHING_TO_COMPARE.into()));
                return true;
            };
            carry_params(lab, reference.as_mut());
            let started = crate::debug::capture_start(gpu, lab, (w, h), format).and_then(|mine| {
                Ok((
                    mine,
                    crate::debug::capture_start(gpu, reference.as_mut(), (w, h), format)?,
                ))
            });
            match started {
                Ok(both) => {
                    self.pending_diff = Some(both);
                    return false;
                }
                Err(e) => {
                    self.shown = Some(Err(e.to_string()));
                    return true;
                }
            }
        }
        match crate::debug::view::record_in(gpu, lab, w, h, format)
            .and_then(|log| self.drawer.start(gpu, &log, &wanted.probe(), w, h))
        {
            Ok(pending) => {
                self.pending = Some((pending, wanted));
                false
            }
            Err(e) => {
                self.shown = Some(Err(e.to_string()));
                true
            }
        }
    }

    /// The last picture, or why there is none; `None` while no view is asked for.
    pub fn shown(&self) -> Option<&Result<Picture, String>> {
        self.shown.as_ref().filter(|_| self.wanted.is_some())
    }

    /// The picture to show instead of the lab's frame, if there is one.
    pub fn image(&self) -> Option<&RgbaImage> {
        self.shown().and_then(|s| s.as_ref().ok()).map(|p| &p.image)
    }

    /// Draws the view again for `lab` (whose pipelines draw in `format`) at `size` when its
    /// state (`version`) or the size changed
    /// since the last picture; returns whether a new picture (or error) was made. Blocks until
    /// the GPU's values are back.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn update(
        &mut self,
        gpu: &Gpu,
        lab: &mut dyn Lab,
        version: u64,
        size: (u32, u32),
        format: wgpu::TextureFormat,
    ) -> bool {
        let Some(wanted) = self.wanted.clone() else {
            return false;
        };
        if self.taken == Some((version, size)) {
            return false;
        }
        self.taken = Some((version, size));
        let (w, h) = view_size(size);
        let made = match wanted {
            Wanted::Diff => self.diff(gpu, lab, (w, h), format),
            _ => crate::debug::view::record_in(gpu, lab, w, h, format)
                .and_then(|log| self.drawer.draw(gpu, &log, &wanted.probe(), w, h))
                .map(|frame| picture_of(&wanted, &frame))
                .map_err(|e| e.to_string()),
        };
        self.shown = Some(made);
        true
    }

    #[cfg(not(target_arch = "wasm32"))]
    fn diff(
        &mut self,
        gpu: &Gpu,
        lab: &mut dyn Lab,
        (w, h): (u32, u32),
        format: wgpu::TextureFormat,
    ) -> Result<Picture, String> {
        let Some(reference) = self.reference.as_mut() else {
            return Err(NOTHING_TO_COMPARE.into());
        };
        carry_params(lab, reference.as_mut());
        let name = lab.info().name;
        // Both labs draw in the surface's format: each frame is captured with its picture.
        let capture = |lab: &mut dyn Lab| {
            crate::debug::capture_start(gpu, lab, (w, h), format).and_then(|pending| pending.wait(gpu))
        };
        let diff = capture(lab)
            .and_then(|mine| Ok((mine, capture(reference.as_mut())?)))
            .and_then(|(mine, reference)| crate::debug::diff::diff(name, &mine, &reference))
            .map_err(|e| e.to_string())?;
        Ok(Picture {
            image: diff.picture.clone(),
            text: diff.text(),
        })
    }

    /// Records the picture into `color` (of `format`, `size` pixels) in `encoder`, in place of
    /// the lab's frame; returns whether there was one to record.
    pub fn record(
        &mut self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        color: &wgpu::TextureView,
        format: wgpu::TextureFormat,
    ) -> bool {
        let Some(image) = self
            .shown
            .as_ref()
            .filter(|_| self.wanted.is_some())
            .and_then(|s| s.as_ref().ok())
        else {
            return false;
        };
        let image = &image.image;
        let fits = |b: &Blit| b.device == gpu.device && b.format == format;
        if !self.blit.as_ref().is_some_and(fits) {
            self.blit = Some(Blit::new(&gpu.device, format));
        }
        self.blit
            .as_mut()
            .expect("made above")
            .record(gpu, encoder, color, image);
        true
    }
}

/// The size a view is drawn at for a surface of `size`: its width, its height less the
/// legend strip (at least one pixel).
pub fn view_size((w, h): (u32, u32)) -> (u32, u32) {
    (w.max(1), h.saturating_sub(picture::LEGEND_HEIGHT).max(1))
}

/// The picture of a line or cost view's values, and its legend in words.
pub fn picture_of(wanted: &Wanted, frame: &crate::debug::view::ValueFrame) -> Picture {
    let drawn: Vec<bool> = frame.cost.iter().map(|&c| c > 0).collect();
    match wanted {
        Wanted::Cost => {
            let (image, max) = picture::cost(frame.width, frame.height, &frame.cost, &drawn);
            Picture {
                image,
                text: format!("cost: statements the fragment shader ran, 0 … {max} (viridis); black: no fragment"),
            }
        }
        _ => {
            let (image, legend) = picture::values(
                frame.width,
                frame.height,
                frame.components as usize,
                &frame.values,
                &frame.ran,
                &drawn,
            );
            let what = match &frame.resolved {
                Some(r) => match &r.site.name {
                    Some(n) => format!("{} = `{n}`", wanted.words()),
                    None => wanted.words(),
                },
                None => wanted.words(),
            };
            let vertex = if frame.vertex {
                " (a vertex shader line: its value at the corners, interpolated as a varying)"
            } else {
                ""
            };
            Picture {
                image,
                text: format!("{what}{vertex}: {}", legend.text()),
            }
        }
    }
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
/// the picture does not reach), through a texture it keeps while the size stays.
struct Blit {
    device: wgpu::Device,
    format: wgpu::TextureFormat,
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    texture: Option<(wgpu::Texture, wgpu::BindGroup)>,
}

const BLIT_SHADER: &str = r"
@group(0) @binding(0) var picture: texture_2d<f32>;

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let p = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(p * 2.0 - 1.0, 0.0, 1.0);
}

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
            source: wgpu::ShaderSource::Wgsl(BLIT_SHADER.into()),
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
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(&format!("{label}.pipeline")),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        Blit {
            device: device.clone(),
            format,
            pipeline,
            layout,
            texture: None,
        }
    }

    fn record(&mut self, gpu: &Gpu, encoder: &mut wgpu::CommandEncoder, color: &wgpu::TextureView, image: &RgbaImage) {
        let label = "shaderlab.view_blit";
        let (w, h) = image.dimensions();
        let (w, h) = (w.max(1), h.max(1));
        let fits = |t: &(wgpu::Texture, wgpu::BindGroup)| (t.0.width(), t.0.height()) == (w, h);
        if !self.texture.as_ref().is_some_and(fits) {
            let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(&format!("{label}.picture")),
                size: wgpu::Extent3d {
                    width: w,
                    height: h,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::Rgba8Unorm,
                usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                view_formats: &[],
            });
            let view = texture.create_view(&wgpu::TextureViewDescriptor {
                label: Some(&format!("{label}.picture_view")),
                ..Default::default()
            });
            let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(&format!("{label}.bind_group")),
                layout: &self.layout,
                entries: &[wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&view),
                }],
            });
            self.texture = Some((texture, group));
        }
        let (texture, group) = self.texture.as_ref().expect("made above");
        if image.width() > 0 && image.height() > 0 {
            gpu.queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture,
                    mip_level: 0,
                    origin: wgpu::Origin3d::ZERO,
                    aspect: wgpu::TextureAspect::All,
                },
                image.as_raw(),
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(4 * image.width()),
                    rows_per_image: Some(image.height()),
                },
                wgpu::Extent3d {
                    width: image.width(),
                    height: image.height(),
                    depth_or_array_layers: 1,
                },
            );
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn links_name_views_and_refuse_other_text() {
        for w in [
            Wanted::Cost,
            Wanted::Diff,
            Wanted::Line {
                file: "shaders/phong.frag".into(),
                line: 31,
                stage: None,
            },
        ] {
            assert_eq!(Wanted::from_link(&w.link()), Some(w));
        }
        for bad in ["", "phong.frag", "phong.frag:0", "phong.frag:x", ":3", "costs"] {
            assert_eq!(Wanted::from_link(bad), None, "{bad:?}");
        }
    }

    #[test]
    fn a_view_fills_the_surface_with_its_legend() {
        assert_eq!(view_size((640, 480)), (640, 480 - picture::LEGEND_HEIGHT));
        assert_eq!(view_size((0, 3)), (1, 1));
    }
}
