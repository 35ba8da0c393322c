//! The geometry of the GLUT programs: one of GLUT's four solids, rotated by `glRotatef` angles that
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
use crate::render::{Culling, GpuMesh, Uniforms, ViewOrdered};

use crate::course::common::{self, object_key, std140_mat3, FaceOrder, GlutMouse, TransformUniforms, XANGLE, YANGLE};
use crate::mesh::tess::{self, Object};

/// Seed 000's object order (keys `1`-`4`: cube, sphere, torus, teapot).
pub const OBJECTS_000: &[&str] = &["cube", "sphere", "torus", "teapot"];

/// How a lab's GLUT geometry looks.
#[derive(Clone, Copy, Debug)]
pub struct GeometryConfig {
    /// `gluPerspective` fovy, near, far (the aspect is the window's).
    pub perspective: (f64, f64, f64),
    /// The eye at start; the view looks down -z from it (`gluLookAt(eye, eye - z, y)`).
    pub eye: Vec3,
}

/// Parameters of the geometry with seed 000's object order and the port's tessellation and
/// normal-matrix study knobs.
pub const PARAMS_000: &[ParamSpec] = &[
    ParamSpec::choice("object", &[3.0], OBJECTS_000, "object drawn (keys 1-4)"),
    XANGLE,
    YANGLE,
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
    common::FACES,
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
        info.original_title,
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

/// Object, rotation, mouse, meshes and the Transform block.
pub struct GlutGeometry {
    config: GeometryConfig,
    /// Where the eye is (a lab may move it, e.g. Phong's W/A/S/D).
    pub eye: Vec3,
    mouse: GlutMouse,
    meshes: HashMap<(Object, u32, bool), ViewOrdered<Vertex>>,
    /// The Transform block of the object.
    pub transform: Uniforms<TransformUniforms>,
}

impl GlutGeometry {
    /// A geometry with no mesh built yet: [`GlutGeometry::prepare`] builds the drawn one on first use
    /// (building all four up front would lengthen every start for objects never drawn; figures:
    /// `docs/speed.md`, "Start-up").
    pub fn new(gpu: &Gpu, label: &str, config: GeometryConfig) -> Self {
        let meshes = HashMap::new();
        let identity = TransformUniforms::new(Mat4::IDENTITY, Mat4::IDENTITY);
        GlutGeometry {
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

    /// The face order for the current object by the `faces` parameter; in `auto`, the order
    /// `auto` lists for the object (each lab lists what it measured faster), mesh order for an
    /// object it does not list.
    pub fn face_order(params: &Params, auto: &[(Object, FaceOrder)]) -> FaceOrder {
        let object = Self::object(params);
        let measured = auto
            .iter()
            .find(|(o, _)| *o == object)
            .map_or(FaceOrder::Mesh, |&(_, f)| f);
        FaceOrder::of(params, measured)
    }

    /// The faces a lab's program draws for the current object. With `cull` on, the outside
    /// faces only ([`Culling::OutsideOnly`], back-face culling: not exact, an opt-in); otherwise
    /// as [`GlutGeometry::face_order`] says ([`FaceOrder::culling`]).
    pub fn culling(params: &Params, auto: &[(Object, FaceOrder)]) -> Culling {
        let winding = Self::object(params).outside_winding();
        if params.on("cull") {
            return Culling::OutsideOnly(winding);
        }
        Self::face_order(params, auto).culling(winding)
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
                let level = tess::choose_level(object, distance, height, tess::DEFAULT_BUDGET_PX);
                if tess::silhouette_error_px(object, level, distance, height) > tess::DEFAULT_BUDGET_PX {
                    crate::render::note_once(format!(
                        "tess=auto: the {} needs a level above {level} (the most auto draws of it) to keep its \
                         silhouette within half a pixel at {height} rows; drawing {level}",
                        object.name()
                    ));
                }
                level
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
    /// draw (built on first use; GLUT's levels stay cached, of the others only the one in use),
    /// its triangles facing the eye first when `order` says so (and `cull` is off).
    #[allow(clippy::too_many_arguments)]
    pub fn prepare(
        &mut self,
        gpu: &Gpu,
        params: &Params,
        width: u32,
        height: u32,
        faithful: bool,
        smooth: bool,
        order: FaceOrder,
    ) -> &GpuMesh<Vertex> {
        let modelview = self.modelview(params);
        let projection = self.projection(width, height);
        let mut transform = TransformUniforms::new(modelview, projection);
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
        let view = (order == FaceOrder::FacingFirst && !params.on("cull"))
            .then(|| (projection * modelview, object.outside_winding()));
        self.meshes
            .entry(key)
            .or_insert_with(|| {
                let mesh = tess::mesh(object, level);
                let mesh: Mesh = if smooth { mesh.welded() } else { mesh };
                let positions = mesh.vertices.iter().map(|v| v.position).collect();
                ViewOrdered::new(
                    gpu,
                    &format!("mesh.{}.{level}{}", object.name(), if smooth { ".smooth" } else { "" }),
                    &mesh.vertices,
                    Some(mesh.indices),
                    positions,
                )
                .unguarded()
            })
            .get(gpu, view)
    }
}

/// Seed 000's camera: `gluPerspective(45, w/h, 1, 100)` from (0, 0, 4).
pub const CAMERA_000: GeometryConfig = GeometryConfig {
    perspective: (45.0, 1.0, 100.0),
    eye: Vec3::new(0.0, 0.0, 4.0),
};

/// The geometry as the runner draws it ([`crate::lab::Geometry`]): the chosen solid at GLUT's level
/// (smoothed, at the level of a port-only mode, when the lab has `smooth` on), each object in
/// the face order `auto` lists for it ([`GlutGeometry::face_order`]).
pub struct Solid {
    /// The geometry.
    pub geometry: GlutGeometry,
    /// The face order the lab measured faster, by object (mesh order for the others).
    pub auto: &'static [(Object, FaceOrder)],
    /// The window title (the original's state summary).
    pub title: fn(&LabInfo, &Params) -> String,
}

impl Solid {
    /// Seed 000's geometry for lab `label`, titled as exercises 1 and 2 are.
    pub fn new(gpu: &Gpu, label: &str, auto: &'static [(Object, FaceOrder)]) -> Self {
        Solid {
            geometry: GlutGeometry::new(gpu, label, CAMERA_000),
            auto,
            title: super::geometry_title,
        }
    }

    /// With its own window title.
    pub fn titled(self, title: fn(&LabInfo, &Params) -> String) -> Self {
        Solid { title, ..self }
    }
}

impl crate::lab::Geometry for Solid {
    type Vertex = Vertex;
    fn input(&mut self, p: &mut Params, input: Input) -> bool {
        self.geometry.input(p, input)
    }
    fn binds(&self) -> Vec<crate::render::Bind> {
        vec![self.geometry.transform.bind()]
    }
    fn culling(&self, p: &Params) -> Option<Culling> {
        Some(GlutGeometry::culling(p, self.auto))
    }
    fn title(&self, info: &LabInfo, p: &Params) -> String {
        (self.title)(info, p)
    }
    fn prepare(&mut self, gpu: &Gpu, p: &Params, width: u32, height: u32) -> &GpuMesh<Vertex> {
        let smooth = p.has("smooth") && p.on("smooth");
        let order = GlutGeometry::face_order(p, self.auto);
        self.geometry.prepare(gpu, p, width, height, !smooth, smooth, order)
    }
}
