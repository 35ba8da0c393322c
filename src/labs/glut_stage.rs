//! The stage of the GLUT programs: one of GLUT's four solids, rotated by `glRotatef` angles that
//! the left-button drag changes, seen through `gluPerspective` + `gluLookAt`, with the GL 2.0
//! built-in matrices as one uniform block (`transform.glsl`). Labs compose it with their own
//! uniforms and programs; it answers for its own parameters (`object`, `xangle`, `yangle`,
//! `zangle`, and for seed 000 the port's `tess`, `scale`, `naive_nm`).

use std::collections::HashMap;

use glam::{Mat3, Mat4, Vec3};

use crate::camera;
use crate::gpu::Gpu;
use crate::lab::{Input, LabInfo};
use crate::mesh::{Mesh, Vertex};
use crate::params::{ParamSpec, Params};
use crate::render::{Faces, GpuMesh, Uniforms};
use crate::tess::{self, Object};

/// The shared transform block of `transform.glsl`: the GL 2.0 built-in matrices.
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
pub fn std140_mat3(m: Mat3) -> [[f32; 4]; 3] {
    [m.x_axis, m.y_axis, m.z_axis].map(|c| [c.x, c.y, c.z, 0.0])
}

/// Seed 000's object order (keys `1`-`4`: cube, sphere, torus, teapot).
pub const OBJECTS_000: &[&str] = &["cube", "sphere", "torus", "teapot"];

const OBJECTS_BY_KEY: [Object; 4] = [Object::Cube, Object::Sphere, Object::Torus, Object::Teapot];

/// How a lab's GLUT stage looks.
#[derive(Clone, Copy, Debug)]
pub struct StageConfig {
    /// `gluPerspective` fovy, near, far (the aspect is the window's).
    pub perspective: (f64, f64, f64),
    /// The eye at start; the view looks down -z from it (`gluLookAt(eye, eye - z, y)`).
    pub eye: Vec3,
}

/// Parameters of the stage with seed 000's object order and the port's tessellation and
/// normal-matrix study knobs.
pub const PARAMS_000: &[ParamSpec] = &[
    ParamSpec::choice("object", &[3.0], OBJECTS_000, "object drawn (keys 1-4)"),
    ParamSpec::real(
        "xangle",
        &[0.0],
        -36000.0,
        36000.0,
        "glRotatef about x, degrees (mouse: vertical drag)",
    ),
    ParamSpec::real(
        "yangle",
        &[0.0],
        -36000.0,
        36000.0,
        "glRotatef about y, degrees (mouse: horizontal drag)",
    ),
    ParamSpec::real("zangle", &[0.0], -36000.0, 36000.0, "glRotatef about z, degrees"),
    ParamSpec::int(
        "tess",
        &[0.0],
        -1.0,
        512.0,
        "port: tessellation level 3-512; 0 = GLUT's (auto in a port-only mode), -1 = auto",
    ),
    ParamSpec::real(
        "scale",
        &[1.0, 1.0, 1.0],
        -100.0,
        100.0,
        "port study: glScalef after the rotations",
    ),
    ParamSpec::choice(
        "faces",
        &[0.0],
        &["auto", "mesh", "outside_first"],
        "port, same pixels: face order; auto = the lab's measured choice per object, mesh = GL's, \
         outside_first = outside faces first, then the others",
    ),
    ParamSpec::flag(
        "cull",
        &[0.0],
        "port, NOT exact: back-face culling, outside faces only (faster; a silhouette pixel may \
         change, and open or displaced meshes lose faces that show)",
    ),
    ParamSpec::flag(
        "naive_nm",
        &[0.0],
        "port study: normals by the modelview's 3x3 instead of its inverse transpose",
    ),
];

/// Seed 000's window title: `Lab05-N label | object | summary`, then the port-only modes
/// (`extra`, e.g. the shading model) and the tessellation when it is not GLUT's.
pub fn title_000(info: &LabInfo, params: &Params, summary: &str, extra: &str) -> String {
    let mut title = format!(
        "{} {} | {} | {summary}{extra}",
        info.title,
        info.label,
        params.text("object")
    );
    match params.f64("tess") as i64 {
        0 => {}
        -1 => title.push_str(" | tess auto"),
        n => title.push_str(&format!(" | tess {n}")),
    }
    title
}

/// Keys `1`-`4` of the GLUT programs: cube, sphere, torus, teapot, for a lab with an `object`
/// choice that names them (seed 000's and seed 001's orders both do). Returns whether it acted.
pub fn object_key(params: &mut Params, input: Input) -> bool {
    match input {
        Input::Key(c @ '1'..='4') if params.has("object") => {
            let object = OBJECTS_BY_KEY[(c as u8 - b'1') as usize];
            params.set_str("object", object.name()).is_ok()
        }
        _ => false,
    }
}

/// The GLUT programs' mouse: a left press remembers the cursor; each motion event with the button
/// down turns yangle by ±2° (horizontal) and xangle by ±1° (vertical), sign by direction. Like
/// the originals, a coordinate that was 0 at the press does not turn (their `if (xMotion)`).
/// Angles are kept in float, as the originals' globals are, and bounded to [0, 360).
#[derive(Clone, Copy, Debug, Default)]
pub struct GlutMouse {
    motion: (i32, i32),
}

impl GlutMouse {
    /// Handles a press or a drag; returns whether the angles changed.
    pub fn input(&mut self, params: &mut Params, input: Input) -> bool {
        match input {
            Input::Press(x, y) => {
                self.motion = (x, y);
                false
            }
            Input::Drag(x, y) => {
                let sign = |a: i32, b: i32| match a.cmp(&b) {
                    std::cmp::Ordering::Less => -1.0,
                    std::cmp::Ordering::Greater => 1.0,
                    std::cmp::Ordering::Equal => 0.0,
                };
                let (xm, ym) = &mut self.motion;
                let mut angles = [params.f("xangle"), params.f("yangle")];
                if *xm != 0 {
                    angles[1] += 2.0 * sign(x, *xm);
                    *xm = x;
                }
                if *ym != 0 {
                    angles[0] += sign(y, *ym);
                    *ym = y;
                }
                // Keep angles bounded (a long drag session must not lose float precision).
                params.put("xangle", &[f64::from(angles[0].rem_euclid(360.0))]);
                params.put("yangle", &[f64::from(angles[1].rem_euclid(360.0))]);
                if params.has("zangle") {
                    let z = params.f("zangle").rem_euclid(360.0);
                    params.put("zangle", &[f64::from(z)]);
                }
                true
            }
            _ => false,
        }
    }
}

/// Object, rotation, mouse, meshes and the Transform block.
pub struct GlutStage {
    config: StageConfig,
    /// Where the eye is (a lab may move it, e.g. Phong's W/A/S/D).
    pub eye: Vec3,
    mouse: GlutMouse,
    meshes: HashMap<(Object, u32, bool), GpuMesh<Vertex>>,
    /// The Transform block of the object.
    pub transform: Uniforms<TransformUniforms>,
}

impl GlutStage {
    /// A stage with no mesh built yet: [`GlutStage::prepare`] builds the drawn one on first use
    /// (building all four up front cost every start ~0.5 ms for objects never drawn).
    pub fn new(gpu: &Gpu, label: &str, config: StageConfig) -> Self {
        let meshes = HashMap::new();
        let identity = TransformUniforms::new(Mat4::IDENTITY, Mat4::IDENTITY);
        GlutStage {
            config,
            eye: config.eye,
            mouse: GlutMouse::default(),
            meshes,
            transform: Uniforms::new(gpu, &format!("{label}.transform"), identity),
        }
    }

    /// The object chosen by the `object` parameter.
    pub fn object(params: &Params) -> Object {
        let name = params.text("object");
        Object::ALL
            .into_iter()
            .find(|o| o.name() == name)
            .unwrap_or(Object::Teapot)
    }

    /// How the object's outside faces are wound seen from outside: GLUT's cube, sphere and
    /// torus counter-clockwise, its teapot clockwise (see [`crate::mesh::Mesh::teapot`]).
    pub fn outside_winding(object: Object) -> wgpu::FrontFace {
        match object {
            Object::Teapot => wgpu::FrontFace::Cw,
            _ => wgpu::FrontFace::Ccw,
        }
    }

    /// The faces a lab's program draws for the current object. With `cull` on, the outside
    /// faces only ([`Faces::OutsideOnly`], back-face culling: not exact, an opt-in). Otherwise by
    /// the `faces` parameter: in `auto`, outside faces first for the objects in `split`
    /// ([`Faces::OutsideFirst`]: the same pixels, fewer fragments shaded; each lab lists the
    /// objects where it measured faster) and every face in mesh order for the others.
    pub fn faces(params: &Params, split: &[Object]) -> Faces {
        let object = Self::object(params);
        let winding = Self::outside_winding(object);
        if params.on("cull") {
            return Faces::OutsideOnly(winding);
        }
        let outside_first = match params.text("faces").as_str() {
            "mesh" => false,
            "outside_first" => true,
            _ => split.contains(&object),
        };
        if outside_first {
            Faces::OutsideFirst(winding)
        } else {
            Faces::AsStated
        }
    }

    /// The GLUT programs' input: keys `1`-`4` choose the object, the left button drags
    /// ([`GlutMouse`]).
    pub fn input(&mut self, params: &mut Params, input: Input) -> bool {
        object_key(params, input) || self.mouse.input(params, input)
    }

    /// The tessellation level drawn for the object in a viewport `height` rows high. GLUT's by
    /// default, as the original; once a port-only mode is on (`faithful` false) the default
    /// becomes the smallest level whose silhouette error stays within half a pixel.
    pub fn level(&self, params: &Params, height: u32, faithful: bool) -> u32 {
        let object = Self::object(params);
        let tess = params.f64("tess") as i64;
        match tess {
            _ if object == Object::Cube => 0,
            0 if faithful => tess::glut_level(object),
            1.. => (tess as u32).clamp(tess::MIN_LEVEL, tess::MAX_LEVEL),
            _ => {
                let distance = self.eye.length() as f64;
                tess::choose_level(object, distance, height, tess::DEFAULT_BUDGET_PX)
            }
        }
    }

    /// The modelview for the current state.
    pub fn modelview(&self, params: &Params) -> Mat4 {
        let angles = Vec3::new(params.f("xangle"), params.f("yangle"), params.f("zangle"));
        let scale = Vec3::from_array(params.v3("scale"));
        let model = camera::lab_rotation(angles) * Mat4::from_scale(scale);
        camera::glu_look_at(self.eye, self.eye - Vec3::Z, Vec3::Y) * model
    }

    /// `gluPerspective` for a viewport, in wgpu's depth convention (`(float)w/h`, h 0 taken as 1).
    pub fn projection(&self, width: u32, height: u32) -> Mat4 {
        let (fovy, near, far) = self.config.perspective;
        let aspect = (width as f32 / height.max(1) as f32) as f64;
        camera::gl_to_wgpu_depth(camera::glu_perspective(fovy, aspect, near, far))
    }

    /// Writes the Transform block for a `width` x `height` viewport and returns the mesh to
    /// draw (built on first use; GLUT's levels stay cached, of the others only the one in use).
    pub fn prepare(
        &mut self,
        gpu: &Gpu,
        params: &Params,
        width: u32,
        height: u32,
        faithful: bool,
        smooth: bool,
    ) -> &GpuMesh<Vertex> {
        let modelview = self.modelview(params);
        let mut transform = TransformUniforms::new(modelview, self.projection(width, height));
        if params.on("naive_nm") {
            transform.normal_matrix = std140_mat3(Mat3::from_mat4(modelview));
        }
        self.transform.value = transform;
        self.transform.upload(gpu);
        let object = Self::object(params);
        let key = (object, self.level(params, height, faithful), smooth);
        let (_, level, _) = key;
        if !self.meshes.contains_key(&key) && level != tess::glut_level(object) {
            self.meshes
                .retain(|&(o, l, _), _| o != object || l == tess::glut_level(o));
        }
        self.meshes.entry(key).or_insert_with(|| {
            let mesh = tess::mesh(object, level);
            let mesh: Mesh = if smooth { mesh.welded() } else { mesh };
            GpuMesh::new(
                gpu,
                &format!("mesh.{}.{level}{}", object.name(), if smooth { ".smooth" } else { "" }),
                &mesh.vertices,
                Some(&mesh.indices),
            )
        })
    }
}
