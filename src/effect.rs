//! What every lab effect shares: the scene state of the original `main.c` (object, angles,
//! camera, time), the [`Effect`] trait each exercise implements, and [`Lab`], which owns one
//! effect's pipeline, the GLUT meshes and the uniform buffers and draws a frame into any view.
//! Effects never see winit: the window code calls [`Lab::key`], [`Lab::mouse_press`] and friends.

use std::collections::HashMap;

use glam::{Mat3, Mat4, Vec3};

use crate::camera;
use crate::error::{Error, Result};
use crate::gpu::Gpu;
use crate::mesh::{Mesh, Vertex};
use crate::offscreen::{Offscreen, DEPTH_FORMAT};
use crate::shader::{self, BlockLayout, ShaderSource, UniformBlock};
use crate::tess;

/// The four objects of keys `1`..`4`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Object {
    /// `glutSolidCube(1.5)`
    Cube,
    /// `glutSolidSphere(1, 24, 24)`
    Sphere,
    /// `glutSolidTorus(0.5, 1, 24, 24)`
    Torus,
    /// `glutSolidTeapot(1)`, the default
    Teapot,
}

impl Object {
    /// All objects, in key order.
    pub const ALL: [Object; 4] = [Object::Cube, Object::Sphere, Object::Torus, Object::Teapot];

    /// Lower-case name used on the command line and in file names.
    pub fn name(self) -> &'static str {
        match self {
            Object::Cube => "cube",
            Object::Sphere => "sphere",
            Object::Torus => "torus",
            Object::Teapot => "teapot",
        }
    }

    /// Parses a command-line name.
    pub fn from_name(name: &str) -> Option<Object> {
        Object::ALL.into_iter().find(|o| o.name() == name)
    }

    /// The mesh the original draws for this object.
    pub fn mesh(self) -> Mesh {
        tess::mesh(self, tess::glut_level(self))
    }
}

/// The state every original `main.c` keeps in globals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scene {
    /// The object drawn.
    pub object: Object,
    /// `xAngle`, `yAngle`, `zAngle` in degrees.
    pub angles: Vec3,
    /// The eye position (`camera` in exercise 3; (0,0,4) elsewhere). The view looks down -z.
    pub camera: Vec3,
    /// The time uniform in seconds. Kept in f64 so that a long-running clock reaches the
    /// wrap by the noise period ([`NOISE_PERIOD`]) unrounded; the shader gets f32.
    pub time: f64,
    /// Mouse position remembered at the last left press (`xMotion`, `yMotion`).
    pub motion: (i32, i32),
}

/// Shading models of the Phong exercise (`--shading`, key `m`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Shading {
    /// Per polygon: the triangle's own normal (`phong_flat.frag`).
    Flat,
    /// Per vertex: the formula at the vertices, colours interpolated (`phong_gouraud.*`).
    Gouraud,
    /// Per pixel: the original (`phong.frag`).
    Phong,
    /// Per pixel with the halfway vector (`phong_blinn.frag`).
    Blinn,
}

impl Shading {
    /// All models, in the order key `m` cycles through them.
    pub const ALL: [Shading; 4] = [Shading::Flat, Shading::Gouraud, Shading::Phong, Shading::Blinn];

    /// Command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Shading::Flat => "flat",
            Shading::Gouraud => "gouraud",
            Shading::Phong => "phong",
            Shading::Blinn => "blinn",
        }
    }

    /// Parses a command-line name.
    pub fn from_name(name: &str) -> Option<Shading> {
        Shading::ALL.into_iter().find(|s| s.name() == name)
    }

    /// The next model (key `m`).
    pub fn next(self) -> Shading {
        let i = Shading::ALL.iter().position(|s| *s == self).unwrap_or(0);
        Shading::ALL[(i + 1) % Shading::ALL.len()]
    }
}

/// How finely the sphere, torus and teapot are tessellated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tess {
    /// GLUT's own levels (24 for sphere and torus, the teapot's 8): the original's meshes.
    Glut,
    /// A fixed level: slices = stacks, sides = rings, or teapot grid.
    Level(u32),
    /// The smallest level whose silhouette error stays within a budget in pixels, per frame.
    Auto {
        /// Error budget in pixels.
        budget_px: f64,
    },
}

/// Port-only rendering options (the original has none of these; defaults reproduce it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Shading model (effects with [`Effect::SHADING_MODELS`]).
    pub shading: Shading,
    /// Tessellation.
    pub tess: Tess,
    /// Weld vertices that share a position and average their normals (crack-free displacement).
    pub smooth: bool,
    /// `glScalef` after the rotations (1,1,1 in the labs; for the normal-matrix study).
    pub scale: Vec3,
    /// Use the modelview's upper 3x3 instead of its inverse transpose for normals (wrong under
    /// non-uniform scale; for the "where methods fail" study).
    pub naive_normal_matrix: bool,
    /// Wrap the time uniform by the noise's period (144.5 s) so f32 never loses precision.
    pub wrap_time: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            shading: Shading::Phong,
            tess: Tess::Glut,
            smooth: false,
            scale: Vec3::ONE,
            naive_normal_matrix: false,
            wrap_time: true,
        }
    }
}

/// The simplex noise is periodic in `time` along (1,1,1): its lattice repeats every 289 skewed
/// units, and a shift of t along (1,1,1) moves the skewed coordinates by 2t, so t = 289/2.
pub const NOISE_PERIOD: f64 = 144.5;

/// One lab exercise: its shaders, its uniform block, its defaults and its keys.
pub trait Effect: 'static {
    /// The `#[repr(C)]` struct that feeds the effect's parameter block (binding 1).
    type Uniforms: UniformBlock + std::fmt::Debug;
    /// Name shared by the module, the shader files (`NAME.vert`, `NAME.frag`), the example and tests.
    const NAME: &'static str;
    /// Window title of the original (`Lab05-N`).
    const TITLE: &'static str;
    /// Human name of the exercise.
    const LABEL: &'static str;
    /// Clear colour (`glClearColor`).
    const CLEAR: [f64; 3];
    /// Eye position at start.
    const CAMERA: Vec3 = Vec3::new(0.0, 0.0, 4.0);
    /// Whether the effect draws the light marker (exercise 3).
    const LIGHT_MARKER: bool = false;
    /// Whether the effect has a `camera` parameter (W/A/S/D in exercise 3).
    const MOVABLE_CAMERA: bool = false;
    /// Whether the effect offers shading models (`--shading`, key `m`).
    const SHADING_MODELS: bool = false;
    /// Whether the effect offers welded, crack-free normals (`--set smooth=1`).
    const SMOOTH_OPTION: bool = false;
    /// Vertex and fragment shader files for a shading model.
    fn shader_files(_shading: Shading) -> (String, String) {
        (format!("{}.vert", Self::NAME), format!("{}.frag", Self::NAME))
    }
    /// The original's defaults.
    fn defaults() -> Self::Uniforms;
    /// The original's keyboard handler for the effect's own keys (not 1-4 or Esc). Values are
    /// clamped to sensible ranges. Returns whether the key did anything. Default: no keys.
    fn key(_key: char, _uniforms: &mut Self::Uniforms, _scene: &mut Scene) -> bool {
        false
    }
    /// The light position in eye space, for the marker.
    fn light_position(_uniforms: &Self::Uniforms) -> Option<Vec3> {
        None
    }
    /// A short summary of the parameters, for the window title.
    fn summary(uniforms: &Self::Uniforms) -> String;
}

/// The shared transform block of `transform.glsl` (binding 0): the GL 2.0 built-in matrices.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct TransformUniforms {
    /// `gl_ModelViewMatrix`.
    pub modelview: [[f32; 4]; 4],
    /// `gl_ModelViewProjectionMatrix`, depth already mapped to 0..1.
    pub mvp: [[f32; 4]; 4],
    /// `gl_NormalMatrix`; std140 stores a mat3 as three vec4 columns (48 bytes).
    pub normal_matrix: [[f32; 4]; 3],
}
crate::uniform_block!(TransformUniforms, "Transform", {
    modelview: "modelview",
    mvp: "mvp",
    normal_matrix: "normal_matrix",
});

impl TransformUniforms {
    /// From a modelview and a (wgpu-depth) projection.
    pub fn new(modelview: Mat4, projection: Mat4) -> Self {
        TransformUniforms {
            modelview: modelview.to_cols_array_2d(),
            mvp: (projection * modelview).to_cols_array_2d(),
            normal_matrix: std140_mat3(camera::normal_matrix(modelview)),
        }
    }
}

/// A mat3 as std140 stores it: three columns, each padded to a vec4.
fn std140_mat3(m: Mat3) -> [[f32; 4]; 3] {
    [m.x_axis, m.y_axis, m.z_axis].map(|c| [c.x, c.y, c.z, 0.0])
}

/// A parameter block for effects that have none (exercises 1 and 2): 16 unused bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct NoUniforms {
    _pad: [f32; 4],
}
crate::uniform_block!(NoUniforms, "NoUniforms", {});

struct GpuMesh {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    count: u32,
}

impl GpuMesh {
    fn new(device: &wgpu::Device, mesh: &Mesh, label: &str) -> Self {
        use wgpu::util::DeviceExt;
        GpuMesh {
            vertices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(&format!("{label}.vertices")),
                contents: bytemuck::cast_slice(&mesh.vertices),
                usage: wgpu::BufferUsages::VERTEX,
            }),
            indices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(&format!("{label}.indices")),
                contents: bytemuck::cast_slice(&mesh.indices),
                usage: wgpu::BufferUsages::INDEX,
            }),
            count: mesh.indices.len() as u32,
        }
    }
}

/// The vertex layout of [`Vertex`]: position at location 0, normal at location 1.
pub const VERTEX_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<Vertex>() as u64,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3],
};

/// Both shader stages of an effect, compiled, with the layouts reflected from them.
pub struct EffectShaders {
    /// Vertex stage.
    pub vertex: shader::CompiledShader,
    /// Fragment stage.
    pub fragment: shader::CompiledShader,
    /// The parameter block as naga lays it out (empty for effects without one).
    pub params: BlockLayout,
}

/// Compiles `NAME.vert` and `NAME.frag` and checks both uniform structs against their blocks.
pub fn compile_effect<U: UniformBlock>(source: &ShaderSource, name: &str, rust_name: &str) -> Result<EffectShaders> {
    compile_effect_files::<U>(source, &format!("{name}.vert"), &format!("{name}.frag"), rust_name)
}

/// Compiles a vertex and a fragment file and checks both uniform structs against their blocks.
pub fn compile_effect_files<U: UniformBlock>(
    source: &ShaderSource,
    vert: &str,
    frag: &str,
    rust_name: &str,
) -> Result<EffectShaders> {
    let name = vert.trim_end_matches(".vert");
    let vertex = source.compile(vert)?;
    let fragment = source.compile(frag)?;
    let find = |block: &str| vertex.uniform_block(block).or_else(|| fragment.uniform_block(block));
    let transform = find(TransformUniforms::BLOCK)
        .ok_or_else(|| Error::Layout(format!("{vert} declares no uniform block {}", TransformUniforms::BLOCK)))?;
    shader::check_layout::<TransformUniforms>("TransformUniforms", &transform)?;
    let params = match find(U::BLOCK) {
        Some(block) => {
            shader::check_layout::<U>(rust_name, &block)?;
            block
        }
        None if U::FIELDS.is_empty() => BlockLayout {
            name: U::BLOCK.into(),
            size: std::mem::size_of::<U>(),
            binding: Some(1),
            members: vec![],
        },
        None => {
            return Err(Error::Layout(format!(
                "struct {rust_name} feeds GLSL block {}, but neither {vert} nor {frag} declares it",
                U::BLOCK
            )))
        }
    };
    let _ = name;
    Ok(EffectShaders {
        vertex,
        fragment,
        params,
    })
}

/// Where a frame is drawn: a colour and a depth view of one size.
#[derive(Clone, Copy)]
pub struct FrameTarget<'a> {
    /// Colour attachment.
    pub color: &'a wgpu::TextureView,
    /// Depth attachment.
    pub depth: &'a wgpu::TextureView,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

/// One lab exercise ready to draw: pipeline, meshes, uniforms and state.
pub struct Lab<E: Effect> {
    /// Scene state (object, angles, camera, time).
    pub scene: Scene,
    /// The effect's parameters.
    pub uniforms: E::Uniforms,
    /// Port-only options (shading model, tessellation, smooth normals...).
    pub options: Options,
    params: BlockLayout,
    built_shading: Shading,
    pending_error: Option<Error>,
    source: ShaderSource,
    format: wgpu::TextureFormat,
    layout: wgpu::PipelineLayout,
    pipeline: wgpu::RenderPipeline,
    marker_pipeline: Option<wgpu::RenderPipeline>,
    meshes: HashMap<(Object, u32, bool), GpuMesh>,
    marker_mesh: GpuMesh,
    transform_buffer: wgpu::Buffer,
    params_buffer: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    marker_transform_buffer: wgpu::Buffer,
    marker_bind_group: wgpu::BindGroup,
}

fn uniform_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn uniform_buffer(device: &wgpu::Device, label: &str, size: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(16) as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// Builds a render pipeline from compiled vertex and fragment stages.
pub fn build_pipeline(
    gpu: &Gpu,
    label: &str,
    layout: &wgpu::PipelineLayout,
    vertex: &wgpu::ShaderModule,
    fragment: &wgpu::ShaderModule,
    format: wgpu::TextureFormat,
) -> Result<wgpu::RenderPipeline> {
    gpu.checked(label, || {
        gpu.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(label),
            layout: Some(layout),
            vertex: wgpu::VertexState {
                module: vertex,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                buffers: &[Some(VERTEX_LAYOUT)],
            },
            fragment: Some(wgpu::FragmentState {
                module: fragment,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            // GL draws both faces unless GL_CULL_FACE is on, and the labs never turn it on.
            primitive: wgpu::PrimitiveState {
                cull_mode: None,
                ..Default::default()
            },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less), // GL_LESS, GL's default
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            multiview_mask: None,
            cache: None,
        })
    })
}

impl<E: Effect> Lab<E> {
    /// Compiles the effect's shaders from `source` and builds everything for targets of `format`.
    pub fn new(gpu: &Gpu, source: ShaderSource, format: wgpu::TextureFormat) -> Result<Self> {
        let device = &gpu.device;
        let options = Options::default();
        let (vert, frag) = E::shader_files(options.shading);
        let shaders = compile_effect_files::<E::Uniforms>(&source, &vert, &frag, std::any::type_name::<E::Uniforms>())?;
        let bind_group_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&format!("{}.bind_group_layout", E::NAME)),
            entries: &[uniform_entry(0), uniform_entry(1)],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(&format!("{}.pipeline_layout", E::NAME)),
            bind_group_layouts: &[Some(&bind_group_layout)],
            immediate_size: 0,
        });
        let pipeline = Self::pipeline_from(gpu, &layout, &shaders, format)?;
        let marker_pipeline = if E::LIGHT_MARKER {
            let vs = source.compile("light_marker.vert")?;
            let fs = source.compile("light_marker.frag")?;
            Some(build_pipeline(
                gpu,
                "light_marker.pipeline",
                &layout,
                &vs.create_module(device, "light_marker.vert"),
                &fs.create_module(device, "light_marker.frag"),
                format,
            )?)
        } else {
            None
        };
        let meshes = Object::ALL
            .into_iter()
            .map(|o| {
                (
                    (o, tess::glut_level(o), false),
                    GpuMesh::new(device, &o.mesh(), &format!("mesh.{}", o.name())),
                )
            })
            .collect();
        let marker_mesh = GpuMesh::new(device, &Mesh::sphere(0.05, 4, 4), "mesh.light_marker");
        let transform_buffer = uniform_buffer(
            device,
            &format!("{}.transform", E::NAME),
            std::mem::size_of::<TransformUniforms>(),
        );
        let params_buffer = uniform_buffer(
            device,
            &format!("{}.params", E::NAME),
            std::mem::size_of::<E::Uniforms>(),
        );
        let marker_transform_buffer = uniform_buffer(
            device,
            "light_marker.transform",
            std::mem::size_of::<TransformUniforms>(),
        );
        let bind = |label: &str, transform: &wgpu::Buffer| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(label),
                layout: &bind_group_layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: transform.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: params_buffer.as_entire_binding(),
                    },
                ],
            })
        };
        let bind_group = bind(&format!("{}.bind_group", E::NAME), &transform_buffer);
        let marker_bind_group = bind("light_marker.bind_group", &marker_transform_buffer);
        Ok(Lab {
            scene: Scene {
                object: Object::Teapot,
                angles: Vec3::ZERO,
                camera: E::CAMERA,
                time: 0.0,
                motion: (0, 0),
            },
            uniforms: E::defaults(),
            options,
            params: shaders.params,
            built_shading: options.shading,
            pending_error: None,
            source,
            format,
            layout,
            pipeline,
            marker_pipeline,
            meshes,
            marker_mesh,
            transform_buffer,
            params_buffer,
            bind_group,
            marker_transform_buffer,
            marker_bind_group,
        })
    }

    fn pipeline_from(
        gpu: &Gpu,
        layout: &wgpu::PipelineLayout,
        shaders: &EffectShaders,
        format: wgpu::TextureFormat,
    ) -> Result<wgpu::RenderPipeline> {
        let vs = shaders.vertex.create_module(&gpu.device, &shaders.vertex.path);
        let fs = shaders.fragment.create_module(&gpu.device, &shaders.fragment.path);
        build_pipeline(gpu, &format!("{}.pipeline", E::NAME), layout, &vs, &fs, format)
    }

    /// Recompiles the effect's shaders (for the current shading model) from its source.
    /// On failure the last good pipeline stays.
    pub fn reload(&mut self, gpu: &Gpu) -> Result<()> {
        let shading = self.options.shading;
        let (vert, frag) = E::shader_files(shading);
        let shaders =
            compile_effect_files::<E::Uniforms>(&self.source, &vert, &frag, std::any::type_name::<E::Uniforms>())?;
        self.pipeline = Self::pipeline_from(gpu, &self.layout, &shaders, self.format)?;
        self.params = shaders.params;
        self.built_shading = shading;
        Ok(())
    }

    /// Switches the shading model (effects with [`Effect::SHADING_MODELS`]) and rebuilds the pipeline.
    pub fn set_shading(&mut self, gpu: &Gpu, shading: Shading) -> Result<()> {
        if !E::SHADING_MODELS && shading != Shading::Phong {
            return Err(Error::Param(format!(
                "{} has no shading models; --shading applies to phong",
                E::NAME
            )));
        }
        let previous = self.options.shading;
        self.options.shading = shading;
        if shading == self.built_shading {
            return Ok(()); // already built: no second compile
        }
        self.reload(gpu).inspect_err(|_| self.options.shading = previous)
    }

    /// An error from a deferred rebuild (e.g. key `m` switching to a broken shader file), once.
    pub fn take_error(&mut self) -> Option<Error> {
        self.pending_error.take()
    }

    /// The tessellation level drawn for the current object in a viewport `height` rows high.
    pub fn level(&self, height: u32) -> u32 {
        let object = self.scene.object;
        match self.options.tess {
            _ if object == Object::Cube => 0,
            Tess::Glut => tess::glut_level(object),
            Tess::Level(n) => n.clamp(tess::MIN_LEVEL, tess::MAX_LEVEL),
            Tess::Auto { budget_px } => {
                let distance = self.scene.camera.length() as f64;
                tess::choose_level(object, distance, height, budget_px)
            }
        }
    }

    /// The mesh for `key`, built on first use. GLUT's levels stay cached; of the other levels
    /// only the one in use does, so `--tess auto` in a long session does not pile up meshes.
    fn ensure_mesh(&mut self, gpu: &Gpu, key: (Object, u32, bool)) {
        let (object, level, _) = key;
        if !self.meshes.contains_key(&key) && level != tess::glut_level(object) {
            self.meshes
                .retain(|&(o, l, _), _| o != object || l == tess::glut_level(o));
        }
        self.meshes.entry(key).or_insert_with(|| {
            let (object, level, smooth) = key;
            let mesh = tess::mesh(object, level);
            let mesh = if smooth { mesh.welded() } else { mesh };
            GpuMesh::new(
                &gpu.device,
                &mesh,
                &format!("mesh.{}.{level}{}", object.name(), if smooth { ".smooth" } else { "" }),
            )
        });
    }

    /// Builds a pipeline from WGSL text for both stages (the WGSL path of the GLSL-to-WGSL check).
    pub fn use_wgsl(&mut self, gpu: &Gpu, vertex_wgsl: &str, fragment_wgsl: &str) -> Result<()> {
        let module = |label: String, code: &str| {
            gpu.checked(&label, || {
                gpu.device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(&label),
                    source: wgpu::ShaderSource::Wgsl(code.into()),
                })
            })
        };
        let vs = module(format!("{}.vert.wgsl", E::NAME), vertex_wgsl)?;
        let fs = module(format!("{}.frag.wgsl", E::NAME), fragment_wgsl)?;
        self.pipeline = build_pipeline(
            gpu,
            &format!("{}.wgsl_pipeline", E::NAME),
            &self.layout,
            &vs,
            &fs,
            self.format,
        )?;
        Ok(())
    }

    /// Where the shaders come from (for live reload).
    pub fn shader_source(&self) -> &ShaderSource {
        &self.source
    }

    /// The parameter block as reflected from the shaders.
    pub fn params_layout(&self) -> &BlockLayout {
        &self.params
    }

    /// Every name `--set` accepts.
    pub fn param_names(&self) -> Vec<String> {
        let mut names: Vec<String> = self.params.members.iter().map(|m| m.name.clone()).collect();
        if E::MOVABLE_CAMERA {
            names.push("camera".into());
        }
        if E::SMOOTH_OPTION {
            names.push("smooth".into());
        }
        names
    }

    /// Sets a parameter by its GLSL uniform name (or `camera` where the effect has one).
    /// Values must be finite; an unknown name lists the valid ones.
    pub fn set(&mut self, name: &str, values: &[f32]) -> Result<()> {
        if let Some(bad) = values.iter().find(|v| !v.is_finite()) {
            return Err(Error::Param(format!(
                "parameter `{name}`: {bad} is not a finite number"
            )));
        }
        if name == "camera" && E::MOVABLE_CAMERA {
            if values.len() != 3 {
                return Err(Error::Param(format!(
                    "parameter `camera` takes 3 numbers, got {}",
                    values.len()
                )));
            }
            // The original's gluLookAt uses camera.x and camera.z only.
            self.scene.camera = Vec3::new(values[0], 0.0, values[2]);
            return Ok(());
        }
        if name == "smooth" && E::SMOOTH_OPTION {
            match values {
                [v] if *v == 0.0 || *v == 1.0 => self.options.smooth = *v == 1.0,
                _ => return Err(Error::Param("parameter `smooth` takes 0 or 1".into())),
            }
            return Ok(());
        }
        shader::set_member(&mut self.uniforms, &self.params, name, values).map_err(|e| match e {
            Error::Param(msg) if msg.starts_with("unknown") => Error::Param(format!(
                "unknown parameter `{name}` for {}; valid: {}",
                E::NAME,
                if self.param_names().is_empty() {
                    "(none)".to_string()
                } else {
                    self.param_names().join(", ")
                }
            )),
            e => e,
        })
    }

    /// Reads a parameter by name.
    pub fn get(&self, name: &str) -> Option<Vec<f32>> {
        if name == "camera" && E::MOVABLE_CAMERA {
            return Some(self.scene.camera.to_array().to_vec());
        }
        if name == "smooth" && E::SMOOTH_OPTION {
            return Some(vec![if self.options.smooth { 1.0 } else { 0.0 }]);
        }
        shader::get_member(&self.uniforms, &self.params, name)
    }

    /// The original's keyboard callback: objects `1`-`4`, then the effect's own keys.
    /// (Esc is the window's business.) Returns whether anything changed.
    pub fn key(&mut self, key: char) -> bool {
        let object = match key {
            '1' => Some(Object::Cube),
            '2' => Some(Object::Sphere),
            '3' => Some(Object::Torus),
            '4' => Some(Object::Teapot),
            _ => None,
        };
        if let Some(object) = object {
            self.scene.object = object;
            return true;
        }
        if key == 'm' && E::SHADING_MODELS {
            // Rebuilt before the next frame is drawn (this method has no GPU at hand).
            self.options.shading = self.options.shading.next();
            return true;
        }
        E::key(key, &mut self.uniforms, &mut self.scene)
    }

    /// The original's mouse callback for a left-button press at window coordinates (x, y).
    pub fn mouse_press(&mut self, x: i32, y: i32) {
        self.scene.motion = (x, y);
    }

    /// The original's motion callback (mouse moved with a button down): ±2° of yAngle per
    /// horizontal event, ±1° of xAngle per vertical one. Like the original, a coordinate that was
    /// 0 at the press does not rotate (its `if (xMotion)` test).
    pub fn mouse_motion(&mut self, x: i32, y: i32) {
        let (xm, ym) = &mut self.scene.motion;
        if *xm != 0 {
            self.scene.angles.y += match x.cmp(xm) {
                std::cmp::Ordering::Less => -2.0,
                std::cmp::Ordering::Greater => 2.0,
                std::cmp::Ordering::Equal => 0.0,
            };
            *xm = x;
        }
        if *ym != 0 {
            self.scene.angles.x += match y.cmp(ym) {
                std::cmp::Ordering::Less => -1.0,
                std::cmp::Ordering::Greater => 1.0,
                std::cmp::Ordering::Equal => 0.0,
            };
            *ym = y;
        }
        // Keep angles bounded (a long drag session must not lose float precision).
        self.scene.angles = Vec3::new(
            self.scene.angles.x.rem_euclid(360.0),
            self.scene.angles.y.rem_euclid(360.0),
            self.scene.angles.z.rem_euclid(360.0),
        );
    }

    /// Window title: the original's, the exercise and the current values.
    pub fn title(&self) -> String {
        let mut title = format!(
            "{} {} | {} | {}",
            E::TITLE,
            E::LABEL,
            self.scene.object.name(),
            E::summary(&self.uniforms)
        );
        if E::SHADING_MODELS {
            title.push_str(&format!(" | shading {} (m)", self.options.shading.name()));
        }
        match self.options.tess {
            Tess::Glut => {}
            Tess::Level(n) => title.push_str(&format!(" | tess {n}")),
            Tess::Auto { .. } => title.push_str(" | tess auto"),
        }
        if self.options.smooth {
            title.push_str(" | smooth");
        }
        title
    }

    /// The modelview of the object for the current state.
    pub fn modelview(&self) -> Mat4 {
        let eye = self.scene.camera;
        let model = camera::lab_rotation(self.scene.angles) * Mat4::from_scale(self.options.scale);
        camera::glu_look_at(eye, eye - Vec3::Z, Vec3::Y) * model
    }

    /// Writes the uniforms for a `width` x `height` viewport.
    fn upload(&mut self, gpu: &Gpu, width: u32, height: u32) {
        let projection = camera::lab_projection(width, height);
        if self.params.member("time").is_some() {
            let t = self.scene.time;
            let t = if self.options.wrap_time {
                t.rem_euclid(NOISE_PERIOD)
            } else {
                t
            };
            let _ = shader::set_member(&mut self.uniforms, &self.params, "time", &[t as f32]);
        }
        let modelview = self.modelview();
        let mut transform = TransformUniforms::new(modelview, projection);
        if self.options.naive_normal_matrix {
            transform.normal_matrix = std140_mat3(Mat3::from_mat4(modelview));
        }
        gpu.queue
            .write_buffer(&self.transform_buffer, 0, bytemuck::bytes_of(&transform));
        gpu.queue
            .write_buffer(&self.params_buffer, 0, bytemuck::bytes_of(&self.uniforms));
        if let Some(light) = E::light_position(&self.uniforms) {
            // Drawn with the modelview reset: glLoadIdentity(); glTranslatef(light).
            let t = TransformUniforms::new(Mat4::from_translation(light), projection);
            gpu.queue
                .write_buffer(&self.marker_transform_buffer, 0, bytemuck::bytes_of(&t));
        }
    }

    /// Records one frame into `target`, with optional timestamp writes around the pass.
    pub fn encode(
        &mut self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        target: FrameTarget<'_>,
        timestamps: Option<wgpu::RenderPassTimestampWrites>,
    ) {
        let FrameTarget {
            color: view,
            depth,
            width,
            height,
        } = target;
        if self.built_shading != self.options.shading {
            if let Err(e) = self.reload(gpu) {
                self.options.shading = self.built_shading;
                self.pending_error = Some(e);
            }
        }
        let key = (self.scene.object, self.level(height), self.options.smooth);
        self.ensure_mesh(gpu, key);
        self.upload(gpu, width, height);
        let [r, g, b] = E::CLEAR;
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(&format!("{}.pass", E::NAME)),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a: 1.0 }),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: depth,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: timestamps,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if let Some(marker) = &self.marker_pipeline {
            pass.set_pipeline(marker);
            pass.set_bind_group(0, &self.marker_bind_group, &[]);
            draw(&mut pass, &self.marker_mesh);
        }
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        if let Some(mesh) = self.meshes.get(&key) {
            draw(&mut pass, mesh);
        }
    }

    /// Draws one frame into `view` and submits it.
    pub fn render(&mut self, gpu: &Gpu, view: &wgpu::TextureView, depth: &wgpu::TextureView, width: u32, height: u32) {
        let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some(&format!("{}.encoder", E::NAME)),
        });
        self.encode(
            gpu,
            &mut encoder,
            FrameTarget {
                color: view,
                depth,
                width,
                height,
            },
            None,
        );
        gpu.queue.submit([encoder.finish()]);
    }

    /// Renders one frame offscreen at `width` x `height` and reads it back.
    pub fn screenshot(&mut self, gpu: &Gpu, width: u32, height: u32) -> Result<image::RgbaImage> {
        let target = Offscreen::with_format(gpu, width, height, self.format);
        gpu.checked(&format!("{}.render", E::NAME), || {
            self.render(gpu, &target.color, &target.depth, target.width, target.height)
        })?;
        target.read(gpu)
    }

    /// Renders one frame into an `Rgba32Float` target (the lab must have been built for that
    /// format) and returns the raw shader outputs, top row first.
    pub fn render_f32(&mut self, gpu: &Gpu, width: u32, height: u32) -> Result<Vec<[f32; 4]>> {
        let target = Offscreen::with_format(gpu, width, height, self.format);
        gpu.checked(&format!("{}.render", E::NAME), || {
            self.render(gpu, &target.color, &target.depth, target.width, target.height)
        })?;
        target.read_f32(gpu)
    }
}

fn draw(pass: &mut wgpu::RenderPass<'_>, mesh: &GpuMesh) {
    pass.set_vertex_buffer(0, mesh.vertices.slice(..));
    pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
    pass.draw_indexed(0..mesh.count, 0, 0..1);
}
