//! A program: a vertex and a fragment shader compiled by naga into one render pipeline.
//!
//! Its bind-group layout is not written by hand: it is read from the shaders (uniform blocks,
//! textures, samplers and their bindings), and resources are bound by their GLSL names. A
//! binding the shaders declare and nobody provides, one provided that the shaders do not
//! declare, a resource of the wrong kind, a uniform struct whose members differ from the
//! block, or a vertex input without a matching attribute is a typed error naming both sides.

use std::marker::PhantomData;
use std::sync::Arc;

use super::BuildContext;
use crate::error::{Error, Result};
use crate::gpu::Gpu;
use crate::offscreen::DEPTH_FORMAT;
use crate::shader::{BlockLayout, CompiledShader, ShaderSource};

use super::mesh::{GpuMesh, VertexType};
use super::Pass;

/// Fixed-function state of a program: what GL sets with glEnable and friends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderState {
    /// Primitive type (`GL_TRIANGLES`, `GL_TRIANGLE_STRIP`, `GL_POINTS`).
    pub topology: wgpu::PrimitiveTopology,
    /// Culling culled (GL: off unless `GL_CULL_FACE`).
    pub cull_mode: Option<wgpu::Face>,
    /// Which winding is the front (GL's default: counter-clockwise).
    pub front_face: wgpu::FrontFace,
    /// `GL_DEPTH_TEST` with `GL_LESS`.
    pub depth_test: bool,
    /// Blending (none in the labs).
    pub blend: Option<wgpu::BlendState>,
    /// Which faces a draw covers and in which order (triangles only; see [`Culling`]).
    pub faces: Culling,
}

/// Which faces of a triangle mesh a program draws, and in which order.
///
/// [`Culling::OutsideFirst`] is a speed-up that keeps every pixel: with the depth test
/// (`GL_LESS`) the colour a pixel ends with is that of the nearest fragment whatever order the
/// triangles are drawn in, except at exact depth ties, where the first one drawn wins. Drawn
/// outside (viewer-facing) faces first, the inside faces they hide fail the early depth test
/// instead of being shaded. It costs a second pass over the geometry (vertex shading and
/// triangle setup twice), so it pays only where fragments are dear: labs choose it per program
/// and object by measurement. Without the depth test the order is the image, so it draws as
/// stated then.
///
/// The winding each variant takes is how the mesh's outside faces are wound seen from outside:
/// GLUT's cube, sphere and torus are counter-clockwise ([`wgpu::FrontFace::Ccw`]), its teapot
/// clockwise ([`wgpu::FrontFace::Cw`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Culling {
    /// Every face in mesh order, culled as [`RenderState::cull_mode`] says (GL's way).
    #[default]
    AsStated,
    /// The faces wound this way first, then the others: two draws of the same mesh, each
    /// culling one winding. Exact except at exact depth ties (see the type). Only for programs
    /// with the depth test and no culling of their own.
    OutsideFirst(wgpu::FrontFace),
    /// Only the faces wound this way (back-face culling). NOT exact: right only for closed
    /// meshes seen from outside, and even there a silhouette pixel may change where an inside
    /// face covered a pixel centre the outside faces miss; open or displaced meshes lose faces
    /// that show.
    OutsideOnly(wgpu::FrontFace),
}

impl Default for RenderState {
    fn default() -> Self {
        RenderState::GL
    }
}

impl RenderState {
    /// GL's defaults plus the depth test every 3D lab enables: triangles, no culling, `GL_LESS`.
    pub const GL: RenderState = RenderState {
        topology: wgpu::PrimitiveTopology::TriangleList,
        cull_mode: None,
        front_face: wgpu::FrontFace::Ccw,
        depth_test: true,
        blend: None,
        faces: Culling::AsStated,
    };

    /// With another topology.
    pub const fn topology(self, topology: wgpu::PrimitiveTopology) -> Self {
        RenderState { topology, ..self }
    }

    /// With the depth test off (2D scenes).
    pub const fn no_depth(self) -> Self {
        RenderState {
            depth_test: false,
            ..self
        }
    }

    /// With another choice of faces (see [`Culling`]).
    pub const fn culling(self, culling: Culling) -> Self {
        RenderState { faces: culling, ..self }
    }

    /// The culling of each draw, in order, that `faces` asks for with this state.
    fn culls(&self) -> Vec<Option<wgpu::Face>> {
        use wgpu::PrimitiveTopology as T;
        let triangles = matches!(self.topology, T::TriangleList | T::TriangleStrip);
        // Culling `Back` keeps the faces wound as `front_face`.
        let keep = |winding: wgpu::FrontFace| {
            if winding == self.front_face {
                wgpu::Face::Back
            } else {
                wgpu::Face::Front
            }
        };
        let other = |face: wgpu::Face| match face {
            wgpu::Face::Back => wgpu::Face::Front,
            wgpu::Face::Front => wgpu::Face::Back,
        };
        match self.faces {
            Culling::OutsideFirst(w) if triangles && self.cull_mode.is_none() && self.depth_test => {
                vec![Some(keep(w)), Some(other(keep(w)))]
            }
            Culling::OutsideOnly(w) if triangles => vec![Some(keep(w))],
            _ => vec![self.cull_mode],
        }
    }
}

/// What kind of resource a binding is.
#[derive(Clone, Debug, PartialEq)]
pub enum BindingKind {
    /// A uniform block of this layout.
    Uniform(BlockLayout),
    /// A float texture of this dimension (`texture2D`, `textureCube`).
    Texture(wgpu::TextureViewDimension),
    /// A filtering sampler.
    Sampler,
}

impl BindingKind {
    fn describe(&self) -> String {
        match self {
            BindingKind::Uniform(b) => format!("uniform block ({} bytes)", b.size),
            BindingKind::Texture(d) => format!("texture ({d:?})"),
            BindingKind::Sampler => "sampler".into(),
        }
    }
}

/// One binding as the shaders declare it.
#[derive(Clone, Debug, PartialEq)]
pub struct BindingInfo {
    /// GLSL name: the block name for uniform blocks, the variable name otherwise.
    pub name: String,
    /// `layout(binding = N)`.
    pub binding: u32,
    /// What it is.
    pub kind: BindingKind,
    /// The stages that declare it.
    pub visibility: wgpu::ShaderStages,
}

/// One vertex input as the vertex shader declares it.
#[derive(Clone, Debug, PartialEq)]
pub struct VertexInput {
    /// GLSL name.
    pub name: String,
    /// `layout(location = N)`.
    pub location: u32,
    /// The format that feeds it exactly.
    pub format: wgpu::VertexFormat,
}

/// A resource for a binding.
#[derive(Clone)]
pub enum Resource {
    /// A uniform buffer and the check of the Rust struct that fills it.
    Buffer {
        /// The buffer.
        buffer: wgpu::Buffer,
        /// The Rust struct's name, for messages.
        rust_name: &'static str,
        /// Compares the struct with the reflected block.
        check: fn(&str, &BlockLayout) -> Result<()>,
    },
    /// The buffer of a [`ParamBlock`](super::ParamBlock), laid out as `layout`.
    Block {
        /// The buffer.
        buffer: wgpu::Buffer,
        /// The layout its bytes follow.
        layout: BlockLayout,
    },
    /// A texture view, its dimension, the texels behind it and the levels the view shows.
    Texture {
        /// The view.
        view: wgpu::TextureView,
        /// `D2` or `Cube`.
        dimension: wgpu::TextureViewDimension,
        /// The texels as uploaded (what the debugger samples).
        texels: Arc<super::Texels>,
        /// The levels the view shows.
        levels: std::ops::Range<u32>,
    },
    /// A sampler.
    Sampler(super::Sampler),
}

impl Resource {
    fn describe(&self) -> String {
        match self {
            Resource::Buffer { rust_name, .. } => format!("uniform buffer of {rust_name}"),
            Resource::Block { layout, .. } => format!("uniform block {} filled by name", layout.name),
            Resource::Texture { dimension, .. } => format!("texture ({dimension:?})"),
            Resource::Sampler(_) => "sampler".into(),
        }
    }
}

/// A named resource to bind.
#[derive(Clone)]
pub struct Bind {
    /// The GLSL name it binds to.
    pub name: String,
    /// The resource.
    pub resource: Resource,
}

impl Bind {
    /// A texture bound to the GLSL `texture2D`/`textureCube` called `name`.
    pub fn texture(name: &str, texture: &super::Texture) -> Bind {
        Bind {
            name: name.to_owned(),
            resource: Resource::Texture {
                view: texture.view.clone(),
                dimension: texture.dimension,
                texels: texture.texels.clone(),
                levels: 0..texture.texels.levels.len().max(1) as u32,
            },
        }
    }

    /// A texture bound to the `texture2D`/`textureCube` called `name`, seen as a sampler with
    /// `desc` reads it ([`Texture::view_for`](super::Texture::view_for)).
    pub fn texture_for(name: &str, texture: &super::Texture, desc: &super::SamplerDesc) -> Bind {
        let all = texture.texels.levels.len().max(1) as u32;
        Bind {
            name: name.to_owned(),
            resource: Resource::Texture {
                view: texture.view_for(desc).clone(),
                dimension: texture.dimension,
                texels: texture.texels.clone(),
                levels: if desc.mipmap.is_some() { 0..all } else { 0..1 },
            },
        }
    }

    /// A sampler bound to the GLSL `sampler` called `name`.
    pub fn sampler(name: &str, sampler: &super::Sampler) -> Bind {
        Bind {
            name: name.to_owned(),
            resource: Resource::Sampler(sampler.clone()),
        }
    }
}

fn stage_bit(stage: naga::ShaderStage) -> wgpu::ShaderStages {
    match stage {
        naga::ShaderStage::Vertex => wgpu::ShaderStages::VERTEX,
        naga::ShaderStage::Fragment => wgpu::ShaderStages::FRAGMENT,
        _ => wgpu::ShaderStages::COMPUTE,
    }
}

/// The bindings declared by a set of shaders (merged by binding number; the stages must agree).
pub fn reflect_bindings(shaders: &[&CompiledShader]) -> Result<Vec<BindingInfo>> {
    let mut out: Vec<BindingInfo> = Vec::new();
    for shader in shaders {
        let module = &shader.module;
        for (_, var) in module.global_variables.iter() {
            let Some(binding) = &var.binding else { continue };
            let ty = &module.types[var.ty];
            let (name, kind) = match (&var.space, &ty.inner) {
                (naga::AddressSpace::Uniform, naga::TypeInner::Struct { .. }) => {
                    let name = ty.name.clone().or_else(|| var.name.clone()).unwrap_or_default();
                    let layout = shader
                        .uniform_block(&name)
                        .ok_or_else(|| Error::Binding(format!("{}: cannot reflect block {name}", shader.path)))?;
                    (name, BindingKind::Uniform(layout))
                }
                (naga::AddressSpace::Handle, naga::TypeInner::Image { dim, arrayed, class }) => {
                    let dimension = match (dim, arrayed) {
                        (naga::ImageDimension::D2, false) => wgpu::TextureViewDimension::D2,
                        (naga::ImageDimension::D2, true) => wgpu::TextureViewDimension::D2Array,
                        (naga::ImageDimension::Cube, false) => wgpu::TextureViewDimension::Cube,
                        (naga::ImageDimension::D3, _) => wgpu::TextureViewDimension::D3,
                        (naga::ImageDimension::D1, _) => wgpu::TextureViewDimension::D1,
                        _ => wgpu::TextureViewDimension::CubeArray,
                    };
                    if !matches!(
                        class,
                        naga::ImageClass::Sampled {
                            kind: naga::ScalarKind::Float,
                            multi: false
                        }
                    ) {
                        return Err(Error::Binding(format!(
                            "{}: texture `{}` is not a plain float texture (only texture2D/textureCube are supported)",
                            shader.path,
                            var.name.as_deref().unwrap_or("?")
                        )));
                    }
                    (var.name.clone().unwrap_or_default(), BindingKind::Texture(dimension))
                }
                (naga::AddressSpace::Handle, naga::TypeInner::Sampler { comparison: false }) => {
                    (var.name.clone().unwrap_or_default(), BindingKind::Sampler)
                }
                _ => {
                    return Err(Error::Binding(format!(
                        "{}: binding {} (`{}`) is of a kind shaderlab does not bind (uniform blocks, \
                         texture2D, textureCube and sampler are supported)",
                        shader.path,
                        binding.binding,
                        var.name.as_deref().unwrap_or("?")
                    )))
                }
            };
            if binding.group != 0 {
                return Err(Error::Binding(format!(
                    "{}: `{name}` uses set = {}; shaderlab binds everything in set 0",
                    shader.path, binding.group
                )));
            }
            let stage = stage_bit(shader.stage);
            match out.iter_mut().find(|b| b.binding == binding.binding) {
                Some(existing) if existing.name == name && existing.kind == kind => existing.visibility |= stage,
                Some(existing) => {
                    return Err(Error::Binding(format!(
                        "binding {} is `{}` ({}) in one stage but `{name}` ({}) in {}",
                        binding.binding,
                        existing.name,
                        existing.kind.describe(),
                        kind.describe(),
                        shader.path
                    )))
                }
                None => out.push(BindingInfo {
                    name,
                    binding: binding.binding,
                    kind,
                    visibility: stage,
                }),
            }
        }
    }
    out.sort_by_key(|b| b.binding);
    Ok(out)
}

fn vertex_format(inner: &naga::TypeInner) -> Option<wgpu::VertexFormat> {
    use naga::{ScalarKind as K, TypeInner as T, VectorSize as S};
    use wgpu::VertexFormat as F;
    let (kind, width, size) = match inner {
        T::Scalar(s) => (s.kind, s.width, 1),
        T::Vector { size, scalar } => (
            scalar.kind,
            scalar.width,
            match size {
                S::Bi => 2,
                S::Tri => 3,
                S::Quad => 4,
            },
        ),
        _ => return None,
    };
    if width != 4 {
        return None;
    }
    Some(match (kind, size) {
        (K::Float, 1) => F::Float32,
        (K::Float, 2) => F::Float32x2,
        (K::Float, 3) => F::Float32x3,
        (K::Float, 4) => F::Float32x4,
        (K::Sint, 1) => F::Sint32,
        (K::Sint, 2) => F::Sint32x2,
        (K::Sint, 3) => F::Sint32x3,
        (K::Sint, 4) => F::Sint32x4,
        (K::Uint, 1) => F::Uint32,
        (K::Uint, 2) => F::Uint32x2,
        (K::Uint, 3) => F::Uint32x3,
        (K::Uint, 4) => F::Uint32x4,
        _ => return None,
    })
}

/// The vertex inputs of a vertex shader's `main`.
pub fn reflect_inputs(vertex: &CompiledShader) -> Result<Vec<VertexInput>> {
    let module = &vertex.module;
    let Some(entry) = module
        .entry_points
        .iter()
        .find(|e| e.stage == naga::ShaderStage::Vertex)
    else {
        return Err(Error::Binding(format!("{} has no vertex entry point", vertex.path)));
    };
    let mut inputs = Vec::new();
    for arg in &entry.function.arguments {
        let Some(naga::Binding::Location { location, .. }) = &arg.binding else {
            continue;
        };
        let name = arg.name.clone().unwrap_or_default();
        let format = vertex_format(&module.types[arg.ty].inner).ok_or_else(|| {
            Error::Binding(format!(
                "{}: vertex input `{name}` (location {location}) has a type no vertex attribute can feed",
                vertex.path
            ))
        })?;
        inputs.push(VertexInput {
            name,
            location: *location,
            format,
        });
    }
    inputs.sort_by_key(|i| i.location);
    Ok(inputs)
}

/// Matches the shader's vertex inputs with `V`'s attributes.
fn vertex_attributes<V: VertexType>(path: &str, inputs: &[VertexInput]) -> Result<Vec<wgpu::VertexAttribute>> {
    let mut out = Vec::new();
    let mut problems = Vec::new();
    for input in inputs {
        match V::ATTRIBUTES.iter().find(|a| a.name == input.name) {
            None => problems.push(format!(
                "vertex input `{}` (location {}, {:?}) of {path} has no attribute in vertex type {}; it has: {}",
                input.name,
                input.location,
                input.format,
                std::any::type_name::<V>(),
                V::ATTRIBUTES.iter().map(|a| a.name).collect::<Vec<_>>().join(", ")
            )),
            Some(a) if a.format != input.format => problems.push(format!(
                "vertex input `{}` of {path} is {:?} but vertex type {} feeds {:?}",
                input.name,
                input.format,
                std::any::type_name::<V>(),
                a.format
            )),
            Some(a) => out.push(wgpu::VertexAttribute {
                format: a.format,
                offset: a.offset,
                shader_location: input.location,
            }),
        }
    }
    if problems.is_empty() {
        Ok(out)
    } else {
        Err(Error::Binding(problems.join("; ")))
    }
}

/// Pipelines by their culling.
type PipelineCache = Vec<(Option<wgpu::Face>, wgpu::RenderPipeline)>;

struct Built {
    vertex: Arc<CompiledShader>,
    fragment: Arc<CompiledShader>,
    bindings: Vec<BindingInfo>,
    bind_group_layout: wgpu::BindGroupLayout,
    stages: CompiledShaders,
    /// Every pipeline built so far, by culling (a program switches between them).
    cache: PipelineCache,
    /// Drawn in order, one per culling of [`RenderState::culls`].
    pipelines: Vec<wgpu::RenderPipeline>,
}

/// What pipelines are made of, kept to make them again with other culling.
struct CompiledShaders {
    layout: wgpu::PipelineLayout,
    attributes: Vec<wgpu::VertexAttribute>,
    vs: wgpu::ShaderModule,
    fs: wgpu::ShaderModule,
}

/// What the shell and tests can do with any program, whatever its vertex type.
pub trait AnyProgram {
    /// The shader file names (vertex, fragment).
    fn files(&self) -> (&str, &str);
    /// Replaces the pipeline with one built from WGSL text for both stages.
    fn use_wgsl(&mut self, gpu: &Gpu, vertex_wgsl: &str, fragment_wgsl: &str) -> Result<()>;
    /// Compiles the shaders again (see [`Program::reload`]).
    fn reload(&mut self, cx: &BuildContext) -> Result<()>;
    /// The compiled vertex and fragment shaders (for the WGSL round trip).
    fn shaders(&self) -> (&CompiledShader, &CompiledShader);
}

impl<V: VertexType> AnyProgram for Program<V> {
    fn files(&self) -> (&str, &str) {
        Program::files(self)
    }
    fn use_wgsl(&mut self, gpu: &Gpu, vertex_wgsl: &str, fragment_wgsl: &str) -> Result<()> {
        Program::use_wgsl(self, gpu, vertex_wgsl, fragment_wgsl)
    }
    fn reload(&mut self, cx: &BuildContext) -> Result<()> {
        Program::reload(self, cx)
    }
    fn shaders(&self) -> (&CompiledShader, &CompiledShader) {
        Program::shaders(self)
    }
}

/// A vertex + fragment program for vertices of type `V`.
pub struct Program<V: VertexType> {
    label: String,
    vert: String,
    frag: String,
    state: RenderState,
    format: wgpu::TextureFormat,
    built: Built,
    resources: Vec<Bind>,
    bind_group: Option<wgpu::BindGroup>,
    _vertex: PhantomData<fn() -> V>,
}

fn layout_entry(b: &BindingInfo) -> wgpu::BindGroupLayoutEntry {
    let ty = match &b.kind {
        BindingKind::Uniform(_) => wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        BindingKind::Texture(dimension) => wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: true },
            view_dimension: *dimension,
            multisampled: false,
        },
        BindingKind::Sampler => wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
    };
    wgpu::BindGroupLayoutEntry {
        binding: b.binding,
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
        ty,
        count: None,
    }
}

impl<V: VertexType> Program<V> {
    /// Compiles `vert` and `frag` from the lab's shader source into a pipeline.
    pub fn new(cx: &BuildContext, label: &str, vert: &str, frag: &str, state: RenderState) -> Result<Self> {
        let built = Self::build(cx.gpu, cx.source, label, vert, frag, state, cx.format)?;
        Ok(Program {
            label: label.to_owned(),
            vert: vert.to_owned(),
            frag: frag.to_owned(),
            state,
            format: cx.format,
            built,
            resources: Vec::new(),
            bind_group: None,
            _vertex: PhantomData,
        })
    }

    /// A program from shaders compiled elsewhere (e.g. translated from another GLSL dialect);
    /// [`Program::reload`] does not apply to it: give it new shaders with
    /// [`Program::set_shaders`].
    pub fn from_shaders(
        gpu: &Gpu,
        label: &str,
        vertex: CompiledShader,
        fragment: CompiledShader,
        state: RenderState,
        format: wgpu::TextureFormat,
    ) -> Result<Self> {
        let built = Self::build_from(gpu, label, vertex, fragment, state, format)?;
        Ok(Program {
            label: label.to_owned(),
            vert: built.vertex.path.clone(),
            frag: built.fragment.path.clone(),
            state,
            format,
            built,
            resources: Vec::new(),
            bind_group: None,
            _vertex: PhantomData,
        })
    }

    /// Replaces the shaders and rebinds the resources bound so far; on failure the last good
    /// pipeline and bindings stay (live reload of shaders compiled elsewhere).
    pub fn set_shaders(&mut self, gpu: &Gpu, vertex: CompiledShader, fragment: CompiledShader) -> Result<()> {
        let built = Self::build_from(gpu, &self.label, vertex, fragment, self.state, self.format)?;
        self.install(gpu, built)
    }

    /// Replaces the shaders and binds `resources` (all of them at once), keeping everything as
    /// it was on failure.
    pub fn set_shaders_and_bind(
        &mut self,
        gpu: &Gpu,
        vertex: CompiledShader,
        fragment: CompiledShader,
        resources: Vec<Bind>,
    ) -> Result<()> {
        let built = Self::build_from(gpu, &self.label, vertex, fragment, self.state, self.format)?;
        let group = Self::bind_group(gpu, &self.label, &built, &resources)?;
        self.vert = built.vertex.path.clone();
        self.frag = built.fragment.path.clone();
        self.built = built;
        self.resources = resources;
        self.bind_group = Some(group);
        Ok(())
    }

    fn build(
        gpu: &Gpu,
        source: &ShaderSource,
        label: &str,
        vert: &str,
        frag: &str,
        state: RenderState,
        format: wgpu::TextureFormat,
    ) -> Result<Built> {
        let vertex = source.compile(vert)?;
        let fragment = source.compile(frag)?;
        Self::build_from(gpu, label, vertex, fragment, state, format)
    }

    fn build_from(
        gpu: &Gpu,
        label: &str,
        vertex: CompiledShader,
        fragment: CompiledShader,
        state: RenderState,
        format: wgpu::TextureFormat,
    ) -> Result<Built> {
        let bindings = reflect_bindings(&[&vertex, &fragment])?;
        let inputs = reflect_inputs(&vertex)?;
        let attributes = vertex_attributes::<V>(&vertex.path, &inputs)?;
        let vs = vertex.create_module(&gpu.device, &vertex.path);
        let fs = fragment.create_module(&gpu.device, &fragment.path);
        let (bind_group_layout, stages, cache) =
            Self::pipelines(gpu, label, &bindings, attributes, vs, fs, state, format)?;
        let pipelines = Self::in_order(&cache, state);
        Ok(Built {
            vertex: Arc::new(vertex),
            fragment: Arc::new(fragment),
            bindings,
            bind_group_layout,
            stages,
            cache,
            pipelines,
        })
    }

    #[allow(clippy::too_many_arguments)]
    fn pipelines(
        gpu: &Gpu,
        label: &str,
        bindings: &[BindingInfo],
        attributes: Vec<wgpu::VertexAttribute>,
        vs: wgpu::ShaderModule,
        fs: wgpu::ShaderModule,
        state: RenderState,
        format: wgpu::TextureFormat,
    ) -> Result<(wgpu::BindGroupLayout, CompiledShaders, PipelineCache)> {
        let device = &gpu.device;
        let entries: Vec<_> = bindings.iter().map(layout_entry).collect();
        gpu.compiling(label, || {
            gpu.checked(label, || {
                let bind_group_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                    label: Some(&format!("{label}.bind_group_layout")),
                    entries: &entries,
                });
                let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                    label: Some(&format!("{label}.pipeline_layout")),
                    bind_group_layouts: &[Some(&bind_group_layout)],
                    immediate_size: 0,
                });
                let stages = CompiledShaders {
                    layout,
                    attributes,
                    vs,
                    fs,
                };
                let pipelines = Self::make_pipelines(gpu, label, &stages, state, format, &[]);
                (bind_group_layout, stages, pipelines)
            })
        })
    }

    /// The pipelines `state` asks for that `cache` lacks (one per culling of
    /// [`RenderState::culls`]); the caller checks for validation errors.
    fn make_pipelines(
        gpu: &Gpu,
        label: &str,
        stages: &CompiledShaders,
        state: RenderState,
        format: wgpu::TextureFormat,
        cache: &[(Option<wgpu::Face>, wgpu::RenderPipeline)],
    ) -> PipelineCache {
        let buffers = [Some(wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<V>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &stages.attributes,
        })];
        state
            .culls()
            .into_iter()
            .filter(|cull| !cache.iter().any(|(c, _)| c == cull))
            .map(|cull_mode| {
                let name = match cull_mode {
                    Some(face) => format!("{label}.pipeline.cull_{face:?}"),
                    None => format!("{label}.pipeline"),
                };
                let pipeline = gpu.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some(&name),
                    layout: Some(&stages.layout),
                    vertex: wgpu::VertexState {
                        module: &stages.vs,
                        entry_point: Some("main"),
                        compilation_options: Default::default(),
                        buffers: if stages.attributes.is_empty() { &[] } else { &buffers },
                    },
                    fragment: Some(wgpu::FragmentState {
                        module: &stages.fs,
                        entry_point: Some("main"),
                        compilation_options: Default::default(),
                        targets: &[Some(wgpu::ColorTargetState {
                            format,
                            blend: state.blend,
                            write_mask: wgpu::ColorWrites::ALL,
                        })],
                    }),
                    primitive: wgpu::PrimitiveState {
                        topology: state.topology,
                        front_face: state.front_face,
                        cull_mode,
                        ..Default::default()
                    },
                    depth_stencil: Some(depth_state(state.depth_test)),
                    multisample: Default::default(),
                    multiview_mask: None,
                    cache: None,
                });
                (cull_mode, pipeline)
            })
            .collect()
    }

    /// The pipelines `state` draws with, in order, from `cache` (which holds them all).
    fn in_order(cache: &[(Option<wgpu::Face>, wgpu::RenderPipeline)], state: RenderState) -> Vec<wgpu::RenderPipeline> {
        state
            .culls()
            .iter()
            .filter_map(|cull| cache.iter().find(|(c, _)| c == cull).map(|(_, p)| p.clone()))
            .collect()
    }

    /// Switches which faces are drawn (see [`Culling`]); builds the pipelines it needs, if any.
    pub fn set_culling(&mut self, gpu: &Gpu, faces: Culling) -> Result<()> {
        if self.state.faces == faces {
            return Ok(());
        }
        let state = self.state.culling(faces);
        let built = &mut self.built;
        let new = gpu.compiling(&self.label, || {
            gpu.checked(&self.label, || {
                Self::make_pipelines(gpu, &self.label, &built.stages, state, self.format, &built.cache)
            })
        })?;
        built.cache.extend(new);
        built.pipelines = Self::in_order(&built.cache, state);
        self.state = state;
        Ok(())
    }

    /// The faces drawn (see [`Culling`]).
    pub fn culling(&self) -> Culling {
        self.state.faces
    }

    /// Compiles the shaders again; on failure the last good pipeline and bindings stay.
    pub fn reload(&mut self, cx: &BuildContext) -> Result<()> {
        let built = Self::build(
            cx.gpu,
            cx.source,
            &self.label,
            &self.vert,
            &self.frag,
            self.state,
            self.format,
        )?;
        self.install(cx.gpu, built)
    }

    fn install(&mut self, gpu: &Gpu, built: Built) -> Result<()> {
        let bind_group = if self.resources.is_empty() && !built.bindings.is_empty() {
            None
        } else {
            Some(Self::bind_group(gpu, &self.label, &built, &self.resources)?)
        };
        self.built = built;
        self.bind_group = bind_group;
        Ok(())
    }

    fn bind_group(gpu: &Gpu, label: &str, built: &Built, resources: &[Bind]) -> Result<wgpu::BindGroup> {
        let mut problems = Vec::new();
        let mut entries = Vec::new();
        let files = format!("{} + {}", built.vertex.path, built.fragment.path);
        for b in &built.bindings {
            let Some(r) = resources.iter().find(|r| r.name == b.name) else {
                problems.push(format!(
                    "{files} declare{} `{}` (binding {}), which {label} does not provide",
                    "", b.name, b.binding
                ));
                continue;
            };
            let resource = match (&b.kind, &r.resource) {
                (
                    BindingKind::Uniform(layout),
                    Resource::Buffer {
                        buffer,
                        rust_name,
                        check,
                    },
                ) => {
                    if let Err(e) = check(rust_name, layout) {
                        problems.push(e.to_string());
                        continue;
                    }
                    buffer.as_entire_binding()
                }
                (BindingKind::Uniform(want), Resource::Block { buffer, layout }) => {
                    if want.size != layout.size || want.members != layout.members {
                        problems.push(format!(
                            "uniform block {} changed its members or their layout in {files}; {label} fills it as it was when the lab started (restart the lab to take the new block)",
                            b.name
                        ));
                        continue;
                    }
                    buffer.as_entire_binding()
                }
                (BindingKind::Texture(want), Resource::Texture { view, dimension, .. }) if want == dimension => {
                    wgpu::BindingResource::TextureView(view)
                }
                (BindingKind::Sampler, Resource::Sampler(s)) => wgpu::BindingResource::Sampler(&s.sampler),
                (kind, resource) => {
                    problems.push(format!(
                        "`{}` is a {} in {files} but {label} provides a {}",
                        b.name,
                        kind.describe(),
                        resource.describe()
                    ));
                    continue;
                }
            };
            entries.push(wgpu::BindGroupEntry {
                binding: b.binding,
                resource,
            });
        }
        for r in resources {
            if !built.bindings.iter().any(|b| b.name == r.name) {
                problems.push(format!(
                    "{label} provides `{}` ({}), which {files} do not declare",
                    r.name,
                    r.resource.describe()
                ));
            }
        }
        if !problems.is_empty() {
            return Err(Error::Binding(problems.join("; ")));
        }
        gpu.checked(label, || {
            gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(&format!("{label}.bind_group")),
                layout: &built.bind_group_layout,
                entries: &entries,
            })
        })
    }

    /// Binds resources by GLSL name (all of them at once).
    pub fn bind(&mut self, gpu: &Gpu, resources: Vec<Bind>) -> Result<()> {
        let group = Self::bind_group(gpu, &self.label, &self.built, &resources)?;
        self.resources = resources;
        self.bind_group = Some(group);
        Ok(())
    }

    /// The uniform block called `name`, as naga laid it out.
    pub fn block(&self, name: &str) -> Option<&BlockLayout> {
        self.built.bindings.iter().find_map(|b| match &b.kind {
            BindingKind::Uniform(layout) if b.name == name => Some(layout),
            _ => None,
        })
    }

    /// The bindings the shaders declare.
    pub fn bindings(&self) -> &[BindingInfo] {
        &self.built.bindings
    }

    /// The compiled vertex and fragment shaders (for WGSL output and tests).
    pub fn shaders(&self) -> (&CompiledShader, &CompiledShader) {
        (&self.built.vertex, &self.built.fragment)
    }

    /// The shader file names.
    pub fn files(&self) -> (&str, &str) {
        (&self.vert, &self.frag)
    }

    /// Replaces the pipeline with one built from WGSL text (the GLSL-to-WGSL round trip check).
    pub fn use_wgsl(&mut self, gpu: &Gpu, vertex_wgsl: &str, fragment_wgsl: &str) -> Result<()> {
        let module = |label: String, code: &str| {
            gpu.checked(&label, || {
                gpu.device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(&label),
                    source: wgpu::ShaderSource::Wgsl(code.into()),
                })
            })
        };
        let vs = module(format!("{}.vert.wgsl", self.label), vertex_wgsl)?;
        let fs = module(format!("{}.frag.wgsl", self.label), fragment_wgsl)?;
        let inputs = reflect_inputs(&self.built.vertex)?;
        let attributes = vertex_attributes::<V>(&self.built.vertex.path, &inputs)?;
        let (layout, stages, cache) = Self::pipelines(
            gpu,
            &format!("{}.wgsl", self.label),
            &self.built.bindings,
            attributes,
            vs,
            fs,
            self.state,
            self.format,
        )?;
        self.built.bind_group_layout = layout;
        self.built.stages = stages;
        self.built.pipelines = Self::in_order(&cache, self.state);
        self.built.cache = cache;
        if !self.resources.is_empty() {
            self.bind_group = Some(Self::bind_group(gpu, &self.label, &self.built, &self.resources)?);
        }
        Ok(())
    }

    /// Draws all of `mesh`.
    pub fn draw(&self, pass: &mut Pass<'_>, mesh: &GpuMesh<V>) {
        self.draw_range(pass, mesh, 0..mesh.count());
    }

    /// Draws `range` of `mesh`'s vertices (or indices): once, or front faces then back faces
    /// (see [`Culling`]); each draw is written into the pass's log when it has one.
    pub fn draw_range(&self, pass: &mut Pass<'_>, mesh: &GpuMesh<V>, range: std::ops::Range<u32>) {
        let culls = self.state.culls();
        for (k, pipeline) in self.built.pipelines.iter().enumerate() {
            if let Some(log) = pass.log() {
                log.draw(super::DrawCall {
                    setup: super::DrawSetup {
                        pass: 0,
                        label: self.label.clone(),
                        vertex: self.built.vertex.clone(),
                        fragment: self.built.fragment.clone(),
                        bindings: self.built.bindings.clone(),
                        state: self.state,
                        cull: culls.get(k).copied().flatten(),
                        viewport: pass.viewport(),
                        scissor: pass.scissor(),
                        stride: std::mem::size_of::<V>() as u64,
                        attributes: self.built.stages.attributes.clone(),
                        indices: mesh.index_data().cloned(),
                        range: range.clone(),
                    },
                    resources: self.resources.clone(),
                    vertices: mesh.vertex_buffer().clone(),
                    layout: self.built.stages.layout.clone(),
                    bind_group: self.bind_group.clone(),
                });
            }
            let raw = pass.raw();
            raw.set_pipeline(pipeline);
            if let Some(group) = &self.bind_group {
                raw.set_bind_group(0, group, &[]);
            }
            mesh.draw_range(raw, range.clone());
        }
    }
}

/// The depth state of a draw with GL_DEPTH_TEST on or off: every pass has a depth attachment,
/// and without the test the pipeline neither tests nor writes it (GL_LESS, GL's default,
/// with it).
pub fn depth_state(depth_test: bool) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(depth_test),
        depth_compare: Some(if depth_test {
            wgpu::CompareFunction::Less
        } else {
            wgpu::CompareFunction::Always
        }),
        stencil: Default::default(),
        bias: Default::default(),
    }
}
