//! A course's own GLSL 1.10/1.20 shaders, unchanged (`legacy VERT FRAG`), in seed 000's scene:
//! GLUT's cube, sphere, torus or teapot (keys `1`-`4`), rotated by a left-button drag, seen
//! through `gluPerspective(45, w/h, 1, 100)` from (0, 0, 4) looking down -z (`camera`,
//! `fovy`, `near`, `far`), cleared to `clear`. The shaders are translated by
//! [`crate::legacy`]; GL's built-in state and every loose uniform are parameters by their GLSL
//! names (`--set Ka=0.2`, `--set gl_LightSource[0].position=2,2,2,1`), `time` runs on a clock
//! when the shaders declare it, and both files reload live (the last good pipeline stays).
//! Without files the lab runs a built-in GLSL 1.10 pair lit by GL's light 0.

use std::collections::HashMap;
use std::path::PathBuf;

use glam::Vec3;

use crate::camera;
use crate::error::{Error, Result};
use crate::gpu::Gpu;
use crate::images::{self, Image};
use crate::lab::{BuildContext, FilesTaken, Input, Lab, LabEntry, LabInfo, UserFiles};
use crate::legacy::{self, state, LegacySource, SamplerDim, Translation, STATE_BLOCK, UNIFORM_BLOCK};
use crate::mesh::tess::{self, Object};
use crate::params::{FileArgs, ParamSpec, Params};
use crate::render::{
    sampler, AnyProgram, Bind, Frame, GpuMesh, Load, Program, RenderState, Resource, SamplerDesc, Texture,
};
use crate::shader::{CompiledShader, ShaderSource};

use crate::course::seed000::geometry::{GeometryConfig, GlutGeometry, PARAMS_000};

/// The lab.
pub static INFO: LabInfo = LabInfo {
    name: "legacy",
    original_title: "legacy",
    label: "GLSL 1.10 shaders",
    lecture: "any course's GLSL 1.10/1.20 shaders",
    size: (640, 360),
    keys: crate::lab::Keys::text("1-4: cube, sphere, torus, teapot; left drag rotates; Space pauses the clock (shaders with `uniform float time`)\nVERT and FRAG reload live when edited"),
    files: FilesTaken {
        texture: true,
        named_textures: true,
        ..FilesTaken::NONE
    },
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params,
    new,
};

/// Objects: seed 000's four, and a 100x100 grid of quads over [-0.5, 0.5]² in z = 0 (SPEC
/// §2.1's, for shaders that write clip coordinates themselves).
const OBJECTS: &[&str] = &["cube", "sphere", "torus", "teapot", "grid"];

const OWN: &[ParamSpec] = &[
    ParamSpec::choice(
        "object",
        &[3.0],
        OBJECTS,
        "object drawn (keys 1-4; grid: SPEC 002's quad grid)",
    ),
    ParamSpec::real(
        "camera",
        &[0.0, 0.0, 4.0],
        -1000.0,
        1000.0,
        "eye position; it looks down -z (gluLookAt)",
    ),
    ParamSpec::real("clear", &[0.0, 0.0, 0.0], 0.0, 1.0, "glClearColor (RGB)"),
    ParamSpec::real("fovy", &[45.0], 1.0, 179.0, "gluPerspective field of view, degrees"),
    ParamSpec::real("near", &[1.0], 1e-4, 1e6, "gluPerspective near plane"),
    ParamSpec::real("far", &[100.0], 1e-3, 1e7, "gluPerspective far plane"),
];

/// The built-in GLSL 1.10 vertex shader (`legacy/default.vert`), drawn when no files are given.
pub const DEFAULT_VERT: &str = include_str!("./default.vert");
/// The built-in fragment shader (`legacy/default.frag`).
pub const DEFAULT_FRAG: &str = include_str!("./default.frag");

/// The state seed 000's C program sets for its exercise `lab` (1-5) when it runs the course's
/// `labN.vert`/`labN.frag`: the uniforms it passes and its camera and clear colour, as `--set`
/// assignments (exercises 1 and 2 set none). With these the course's files draw the originals'
/// pictures (`tests/legacy.rs`); the web page applies them when a course pair is picked.
pub fn course_state(lab: u32) -> &'static [(&'static str, &'static str)] {
    match lab {
        3 => &[
            ("camera", "0,0,5"),
            ("clear", "0.05,0.1,0.2"),
            ("lightPosition", "0,1,1"),
            ("ambientColor", "0.1,0.1,0.1"),
            ("diffuseColor", "1,0.5,0"),
            ("specularColor", "1,1,1"),
            ("Ka", "0.1"),
            ("Kd", "1"),
            ("Ks", "1"),
            ("shininess", "32"),
        ],
        4 => &[("time", "0"), ("shade", "1,1,1")],
        5 => &[("time", "0"), ("displacement", "0.5"), ("shade", "1,1,1")],
        _ => &[],
    }
}

/// gluPerspective needs 0 < near < far; GL would draw nothing (or garbage) otherwise.
fn near_before_far(p: &Params) -> Result<()> {
    let (near, far) = (p.f64("near"), p.f64("far"));
    if near >= far {
        return Err(Error::Param(format!(
            "`near` ({near}) must be less than `far` ({far}): gluPerspective needs 0 < near < far"
        )));
    }
    Ok(())
}

fn base_params() -> Params {
    let mut p = Params::new(OWN).with_check(near_before_far);
    let geometry: Vec<ParamSpec> = PARAMS_000
        .iter()
        .copied()
        .filter(|s| matches!(s.name, "xangle" | "yangle" | "zangle" | "tess"))
        .collect();
    p.extend(&geometry);
    p
}

fn params() -> Params {
    base_params().with_files(FileArgs {
        names: &["VERT", "FRAG"],
        declare,
    })
}

/// Reads the shaders (the built-in pair without files). A text edited in memory under the
/// file's name (the web page's editor, [`ShaderSource::Edited`]) stands in for the file.
fn sources(files: &[PathBuf], edits: &ShaderSource) -> Result<(LegacySource, LegacySource)> {
    let one = |name: &str, built_in: Option<&str>, path: Option<&PathBuf>| match (edits.edited(name), built_in, path) {
        (Some(text), _, _) | (None, Some(text), _) => Ok(LegacySource::new(name, text)),
        (None, None, Some(path)) => LegacySource::read(path),
        (None, None, None) => Err(Error::ShaderNotFound(name.to_owned())),
    };
    match files {
        [] => Ok((
            one("legacy/default.vert", Some(DEFAULT_VERT), None)?,
            one("legacy/default.frag", Some(DEFAULT_FRAG), None)?,
        )),
        [vert, frag] => Ok((
            one(&vert.to_string_lossy(), None, Some(vert))?,
            one(&frag.to_string_lossy(), None, Some(frag))?,
        )),
        _ => Err(Error::Param("legacy takes two files: VERT FRAG".into())),
    }
}

/// Reads and translates the shaders.
fn load(files: &[PathBuf], edits: &ShaderSource) -> Result<(Translation, CompiledShader, CompiledShader)> {
    let (vert, frag) = sources(files, edits)?;
    let translation = legacy::translate(&vert, &frag)?;
    let (vs, fs) = translation.compile()?;
    Ok((translation, vs, fs))
}

fn declared(translation: &Translation) -> Params {
    let mut p = base_params();
    let base = p.clone();
    p.extend(&translation.params(&|n| base.has(n)));
    p
}

/// The parameters the shaders declare: GL's state they use and their loose uniforms.
fn declare(files: &[PathBuf], params: &mut Params) -> Result<()> {
    let (translation, _, _) = load(files, &ShaderSource::Embedded)?;
    let base = params.clone();
    params.extend(&translation.params(&|n| base.has(n)));
    Ok(())
}

/// A vertex of GLUT's meshes as the translated shaders read it.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LegacyVertex {
    /// `gl_Vertex.xyz`.
    pub position: [f32; 3],
    /// `gl_Normal`.
    pub normal: [f32; 3],
    /// `gl_MultiTexCoord0.st` (freeglut's teapot has them; the other solids 0).
    pub texcoord: [f32; 2],
}
crate::vertex_type!(LegacyVertex, {
    position: "sl_Vertex" => Float32x3,
    normal: "gl_Normal" => Float32x3,
    texcoord: "sl_MultiTexCoord0" => Float32x2,
});

/// What the program binds, built for one translation.
struct Bound {
    translation: Translation,
    uniform_params: Vec<&'static str>,
    state: Option<wgpu::Buffer>,
    uniforms: Option<wgpu::Buffer>,
    _textures: Vec<(Texture, crate::render::Sampler)>,
}

struct LegacyLab {
    params: Params,
    geometry: GlutGeometry,
    files: Vec<PathBuf>,
    user_files: UserFiles,
    program: Program<LegacyVertex>,
    bound: Bound,
    meshes: HashMap<(usize, u32), GpuMesh<LegacyVertex>>,
    title: String,
}

fn buffer(gpu: &Gpu, label: &str, size: usize) -> wgpu::Buffer {
    gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(16) as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    })
}

fn buffer_bind(name: &str, buffer: &wgpu::Buffer) -> Bind {
    Bind {
        name: name.to_owned(),
        resource: Resource::Buffer {
            buffer: buffer.clone(),
            rust_name: "the legacy translation's block",
            // The bytes are written by naga's own layout of the block (legacy::block_bytes).
            check: |_, _| Ok(()),
        },
    }
}

/// The picture for a sampler: `--texture NAME=FILE`, else a lone `--texture FILE` for the
/// first sampler2D, else SPEC §0.1's uvgrid (2D) or cube faces (cube).
fn picture(s: &legacy::Sampler, first_2d: bool, files: &UserFiles) -> Result<(Image, PathBuf)> {
    let named = files.named_textures.iter().find(|(n, _)| *n == s.name).map(|(_, f)| f);
    let file = named.or(if first_2d { files.texture.as_ref() } else { None });
    match (s.dim, file) {
        (SamplerDim::D2, Some(f)) => Ok((f.data.clone(), f.path.clone())),
        (SamplerDim::Cube, Some(f)) => Err(Error::Param(format!(
            "--texture {}={}: `{}` is a samplerCube; cube maps from files are not supported (the built-in cube faces are used without one)",
            s.name,
            f.path.display(),
            s.name
        ))),
        (SamplerDim::D2, None) => Ok((images::uvgrid(), PathBuf::from("the built-in uvgrid"))),
        (SamplerDim::Cube, None) => Ok((images::cube_faces(), PathBuf::from("the built-in cube faces"))),
    }
}

fn bind_all(
    gpu: &Gpu,
    translation: Translation,
    vs: &CompiledShader,
    fs: &CompiledShader,
    files: &UserFiles,
) -> Result<(Bound, Vec<Bind>)> {
    let limits = gpu.device.limits();
    translation.check_limits(
        vs,
        fs,
        limits.max_uniform_buffer_binding_size,
        limits.max_inter_stage_shader_variables,
    )?;
    for (name, _) in &files.named_textures {
        if !translation.samplers.iter().any(|s| &s.name == name) {
            let have: Vec<&str> = translation.samplers.iter().map(|s| s.name.as_str()).collect();
            return Err(Error::Param(format!(
                "--texture {name}=...: the shaders have no sampler `{name}` (they have: {})",
                if have.is_empty() {
                    "none".to_owned()
                } else {
                    have.join(", ")
                }
            )));
        }
    }
    let mut binds = Vec::new();
    let state = (!translation.state.is_empty()).then(|| {
        let size = legacy::block_bytes(vs, STATE_BLOCK, &mut |_| None).map_or(16, |b| b.len());
        buffer(gpu, "legacy.state", size)
    });
    if let Some(b) = &state {
        binds.push(buffer_bind(STATE_BLOCK, b));
    }
    let uniforms = (!translation.uniforms.is_empty()).then(|| {
        let size = legacy::block_bytes(vs, UNIFORM_BLOCK, &mut |_| None).map_or(16, |b| b.len());
        buffer(gpu, "legacy.uniforms", size)
    });
    if let Some(b) = &uniforms {
        binds.push(buffer_bind(UNIFORM_BLOCK, b));
    }
    let mut textures = Vec::new();
    let first_2d = translation.samplers.iter().position(|s| s.dim == SamplerDim::D2);
    for (i, s) in translation.samplers.iter().enumerate() {
        let (image, path) = picture(s, first_2d == Some(i), files)?;
        crate::render::check_texture_size(gpu, &path, image.width, image.height)?;
        let texture = Texture::new(
            gpu,
            &format!("legacy.{}", s.name),
            image.width,
            image.height,
            image.layers,
            std::slice::from_ref(&image.rgba),
        );
        let smp = sampler(gpu, &format!("legacy.{}.sampler", s.name), &SamplerDesc::default());
        binds.push(Bind::texture(&s.glsl, &texture));
        binds.push(Bind::sampler(&s.sampler, &smp));
        textures.push((texture, smp));
    }
    let base = base_params();
    let uniform_params = translation.param_names(&|n| base.has(n));
    Ok((
        Bound {
            translation,
            uniform_params,
            state,
            uniforms,
            _textures: textures,
        },
        binds,
    ))
}

fn new(cx: &BuildContext) -> Result<Box<dyn Lab>> {
    let files = cx.files.inputs.clone();
    if files.is_empty() {
        // Running without files stays (every lab runs with no arguments: `labs`, the README
        // pictures, the window tests), but a user who forgot the files must not mistake the
        // built-in pair for theirs.
        eprintln!(
            "legacy: no VERT FRAG given: drawing the built-in GLSL 1.10 pair (legacy/default.vert, legacy/default.frag); run `legacy VERT FRAG` for your own shaders"
        );
    }
    let (translation, vs, fs) = load(&files, cx.source)?;
    let params = declared(&translation).with_files(FileArgs {
        names: &["VERT", "FRAG"],
        declare,
    });
    let (bound, binds) = bind_all(cx.gpu, translation, &vs, &fs, cx.files)?;
    // A uniform named like one of the lab's parameters is `uniform.NAME`; say so once, so
    // that `--set near=...` is not mistaken for the shader's `near`.
    for (u, name) in bound.translation.uniforms.iter().zip(&bound.uniform_params) {
        if u.name != *name {
            eprintln!(
                "legacy: the shaders' uniform `{}` is the parameter `{name}` (`--set {name}=...`): `{}` is the lab's own",
                u.name, u.name
            );
        }
    }
    let mut program = Program::from_shaders(cx.gpu, "legacy", vs, fs, RenderState::default(), cx.format)?;
    program.bind(cx.gpu, binds)?;
    let geometry = GlutGeometry::new(
        cx.gpu,
        "legacy",
        GeometryConfig {
            perspective: (45.0, 1.0, 100.0),
            eye: Vec3::new(0.0, 0.0, 4.0),
        },
    );
    let mut lab = LegacyLab {
        params,
        geometry,
        files,
        user_files: cx.files.clone(),
        program,
        bound,
        meshes: HashMap::new(),
        title: String::new(),
    };
    lab.title = lab.files_title();
    Ok(Box::new(lab))
}

impl LegacyLab {
    fn files_title(&self) -> String {
        let (v, f) = (
            &self.bound.translation.vertex.source.path,
            &self.bound.translation.fragment.source.path,
        );
        let short = |p: &str| {
            std::path::Path::new(p)
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_else(|| p.to_owned())
        };
        format!("{} + {}", short(v), short(f))
    }

    fn object(&self) -> Option<Object> {
        Object::from_name(&self.params.text("object"))
    }

    /// The key of the mesh to draw, built on first use.
    fn mesh(&mut self, gpu: &Gpu, height: u32) -> (usize, u32) {
        let object = self.object();
        let (key, level) = match object {
            Some(o) => {
                let level = self.geometry.level(&self.params, height, true);
                let index = Object::ALL.iter().position(|x| *x == o).unwrap_or(0);
                ((index, level), level)
            }
            None => ((OBJECTS.len(), 0), 0),
        };
        if !self.meshes.contains_key(&key) {
            // Keep GLUT's levels; of the others only the one in use.
            self.meshes.retain(|&(o, l), _| {
                Object::ALL
                    .get(o)
                    .is_none_or(|obj| l == tess::glut_level(*obj) || o != key.0)
            });
        }
        self.meshes.entry(key).or_insert_with(|| {
            let vertices: Vec<LegacyVertex>;
            let mut indices = None;
            match object {
                Some(o) => {
                    let mesh = tess::mesh(o, level);
                    let uv = if o == Object::Teapot {
                        crate::mesh::glut::teapot_texcoords(level)
                    } else {
                        Vec::new()
                    };
                    vertices = mesh
                        .vertices
                        .iter()
                        .enumerate()
                        .map(|(i, v)| LegacyVertex {
                            position: v.position,
                            normal: v.normal,
                            texcoord: uv.get(i).copied().unwrap_or([0.0, 0.0]),
                        })
                        .collect();
                    indices = Some(mesh.indices);
                }
                None => {
                    vertices = crate::mesh::shapes::twist_grid()
                        .into_iter()
                        .map(|[x, y]| LegacyVertex {
                            position: [x, y, 0.0],
                            normal: [0.0, 0.0, 1.0],
                            texcoord: [x + 0.5, y + 0.5],
                        })
                        .collect();
                }
            }
            GpuMesh::new(gpu, "legacy.mesh", &vertices, indices.as_deref())
        });
        key
    }

    /// Writes both blocks for a `width` x `height` frame.
    fn upload(&self, gpu: &Gpu, width: u32, height: u32) {
        let p = &self.params;
        let eye = Vec3::from_array(p.v3("camera"));
        let angles = Vec3::new(p.f("xangle"), p.f("yangle"), p.f("zangle"));
        let modelview = camera::glu_look_at(eye, eye - Vec3::Z, Vec3::Y) * camera::lab_rotation(angles);
        let aspect = (width as f32 / height.max(1) as f32) as f64;
        let projection = camera::glu_perspective(p.f64("fovy"), aspect, p.f64("near"), p.f64("far"));
        let (vs, _) = self.program.shaders();
        let t = &self.bound.translation;
        if let Some(buffer) = &self.bound.state {
            let scene = state::Scene { modelview, projection };
            let values = state::values(&t.state, t.lights, p, &scene);
            let mut lookup = |path: &str| values.get(path).map(|v| v.iter().map(|x| f64::from(*x)).collect());
            if let Some(bytes) = legacy::block_bytes(vs, STATE_BLOCK, &mut lookup) {
                gpu.queue.write_buffer(buffer, 0, &bytes);
            }
        }
        if let Some(buffer) = &self.bound.uniforms {
            let values: Vec<Vec<f64>> = self
                .bound
                .uniform_params
                .iter()
                .map(|n| p.get(n).map(<[f64]>::to_vec).unwrap_or_default())
                .collect();
            let mut lookup = legacy::uniform_lookup(&t.uniforms, &values);
            if let Some(bytes) = legacy::block_bytes(vs, UNIFORM_BLOCK, &mut lookup) {
                gpu.queue.write_buffer(buffer, 0, &bytes);
            }
        }
    }
}

impl Lab for LegacyLab {
    fn info(&self) -> &'static LabInfo {
        &INFO
    }
    fn params(&self) -> &Params {
        &self.params
    }
    fn params_mut(&mut self) -> &mut Params {
        &mut self.params
    }
    fn input(&mut self, input: Input) -> bool {
        self.geometry.input(&mut self.params, input)
    }
    fn programs(&mut self) -> Vec<&mut dyn AnyProgram> {
        vec![&mut self.program]
    }
    fn animated(&self) -> bool {
        let t = &self.bound.translation;
        t.uniforms
            .iter()
            .zip(&self.bound.uniform_params)
            .any(|(u, n)| *n == "time" && u.components() == 1 && u.ty.scalar == legacy::Scalar::Float)
    }
    fn title(&self) -> String {
        let p = &self.params;
        let changed: Vec<String> = p
            .changed()
            .filter(|(name, _)| *name != "object")
            .map(|(name, text)| format!("{name}={text}"))
            .collect();
        let mut title = format!(
            "{} {} | {} | {}",
            INFO.original_title,
            self.title,
            p.text("object"),
            changed.join(" ")
        );
        if changed.is_empty() {
            title.truncate(title.trim_end_matches(" | ").len());
        }
        title
    }
    fn reload(&mut self, cx: &BuildContext) -> Result<()> {
        let (translation, vs, fs) = load(&self.files, cx.source)?;
        let mut params = declared(&translation).with_files(FileArgs {
            names: &["VERT", "FRAG"],
            declare,
        });
        // Values carry over by name where the count of numbers is the same.
        for spec in self.params.specs() {
            if let (true, Some(v)) = (params.has(spec.name), self.params.get(spec.name)) {
                if params.get(spec.name).is_some_and(|d| d.len() == v.len()) {
                    params.set_unchecked(spec.name, v);
                }
            }
        }
        let (bound, binds) = bind_all(cx.gpu, translation, &vs, &fs, &self.user_files)?;
        self.program.set_shaders_and_bind(cx.gpu, vs, fs, binds)?;
        self.bound = bound;
        self.params = params;
        self.title = self.files_title();
        Ok(())
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        self.upload(frame.gpu, frame.width, frame.height);
        let clear = self.params.v3("clear").map(f64::from);
        let height = frame.height;
        let gpu = frame.gpu;
        let key = self.mesh(gpu, height);
        let mut pass = frame.pass("legacy", Load::Clear(clear));
        if let Some(mesh) = self.meshes.get(&key) {
            self.program.draw(&mut pass, mesh);
        }
        Ok(())
    }
}
