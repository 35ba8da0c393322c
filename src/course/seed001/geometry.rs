//! The geometry every seed-001 exercise shares (SPEC §1, "Common frame"): `gluPerspective(45,
//! aspect, 0.1, 100)`, `gluLookAt(eye, origin, +y)` with a per-exercise eye, the model turned by
//! `glRotatef(xangle, 1,0,0); glRotatef(yangle, 0,1,0)` that the left-button drag changes, the
//! GL 2.0 matrices as the `Transform` block (`transform_block.glsl`), and, for the exercises that
//! draw them, GLUT's solids in seed 001's `object` numbering (0 teapot, 1 sphere, 2 torus,
//! 3 cube; keys `1` cube, `2` sphere, `3` torus, `4` teapot as in seed 000).

use std::collections::HashMap;

use glam::{Mat4, Vec3};

use crate::camera;
use crate::gpu::Gpu;
use crate::lab::Input;
use crate::mesh::tess::Object;
use crate::mesh::Vertex;
use crate::params::{ParamSpec, Params};
use crate::render::{Bind, Culling, GpuMesh, Uniforms, VertexType, ViewOrdered};

use crate::course::common::{self, object_key, FaceOrder, GlutMouse, TransformUniforms, XANGLE, YANGLE};

/// Seed 001's object numbering.
pub const OBJECTS_001: &[&str] = &["teapot", "sphere", "torus", "cube"];

/// The objects in [`OBJECTS_001`] order.
const OBJECTS: [Object; 4] = [Object::Teapot, Object::Sphere, Object::Torus, Object::Cube];

/// The model rotation every seed-001 exercise has (defaults 0).
pub const ROTATION: &[ParamSpec] = &[XANGLE, YANGLE];

/// The GLUT solid of the exercises that draw one (default the teapot), and the port's face
/// order for it ([`common::FACES`]).
pub const OBJECT: &[ParamSpec] = &[
    ParamSpec::choice(
        "object",
        &[0.0],
        OBJECTS_001,
        "GLUT solid (keys 1 cube, 2 sphere, 3 torus, 4 teapot)",
    ),
    common::FACES,
];

/// The face order of `faces=auto` for `toon`: the torus's triangles facing the eye first
/// ([`FaceOrder::FacingFirst`]: the same pixels, fewer fragments shaded), the others in mesh
/// order, where no order measured faster for the cheapest shading (figures: `docs/speed.md`,
/// "Face orders").
pub fn torus_facing_first(object: Object) -> FaceOrder {
    match object {
        Object::Torus => FaceOrder::FacingFirst,
        _ => FaceOrder::Mesh,
    }
}

/// The face order of `faces=auto` for the other lit solids (uniform_arrays, phong_vertex,
/// phong_fragment): teapot and torus facing the eye first, which shades fewer fragments. The
/// teapot's exact depth ties (its spout and handle pass through its body, and this camera's
/// near plane at 0.1 makes depths coarse) are what [`crate::render::TieGuard`] keeps in mesh
/// order, so the pixels are mesh order's (figures: `docs/speed.md`, "Face orders").
pub fn teapot_and_torus_facing_first(object: Object) -> FaceOrder {
    match object {
        Object::Torus | Object::Teapot => FaceOrder::FacingFirst,
        _ => FaceOrder::Mesh,
    }
}

/// `gluPerspective` of every seed-001 exercise: fovy 45°, near 0.1, far 100.
const PERSPECTIVE: (f64, f64, f64) = (45.0, 0.1, 100.0);

/// Camera, rotation, mouse and the Transform block of one exercise.
pub struct UstcCamera {
    /// The eye of `gluLookAt(eye, (0,0,0), (0,1,0))`.
    pub eye: Vec3,
    mouse: GlutMouse,
    /// The Transform block (`gl_ModelViewMatrix`, `gl_ModelViewProjectionMatrix`, `gl_NormalMatrix`).
    pub transform: Uniforms<TransformUniforms>,
}

impl UstcCamera {
    /// A geometry looking from `eye` at the origin.
    pub fn new(gpu: &Gpu, label: &str, eye: Vec3) -> Self {
        let identity = TransformUniforms::new(Mat4::IDENTITY, Mat4::IDENTITY);
        UstcCamera {
            eye,
            mouse: GlutMouse::default(),
            transform: Uniforms::new(gpu, &format!("{label}.transform"), identity),
        }
    }

    /// The object chosen by `object` (the teapot for a lab without one).
    pub fn object(params: &Params) -> Object {
        if params.has("object") {
            OBJECTS[params.index_of("object").min(OBJECTS.len() - 1)]
        } else {
            Object::Teapot
        }
    }

    /// The model matrix `Rx(xangle)·Ry(yangle)` as the matrix stack holds it after
    /// `glLoadIdentity(); glRotatef(xangle,1,0,0); glRotatef(yangle,0,1,0)`.
    pub fn model(params: &Params) -> Mat4 {
        camera::gl_rotate(params.f("xangle"), Vec3::X) * camera::gl_rotate(params.f("yangle"), Vec3::Y)
    }

    /// `gluLookAt(eye, 0, y)` followed by the two rotations, multiplied in the order Mesa's
    /// matrix stack does (each `glRotatef` multiplies the current matrix on the right, in float).
    pub fn modelview(&self, params: &Params) -> Mat4 {
        let view = camera::glu_look_at(self.eye, Vec3::ZERO, Vec3::Y);
        view * camera::gl_rotate(params.f("xangle"), Vec3::X) * camera::gl_rotate(params.f("yangle"), Vec3::Y)
    }

    /// Object to clip space for a `width` x `height` viewport: [`Self::projection`] times
    /// [`Self::modelview`] (what the facing test of `faces=facing_first` needs).
    pub fn object_to_clip(&self, params: &Params, width: u32, height: u32) -> Mat4 {
        Self::projection(width, height) * self.modelview(params)
    }

    /// `gluPerspective(45, (float)w/h, 0.1, 100)` for a viewport, in wgpu's depth convention.
    pub fn projection(width: u32, height: u32) -> Mat4 {
        let (fovy, near, far) = PERSPECTIVE;
        let aspect = (width as f32 / height.max(1) as f32) as f64;
        camera::gl_to_wgpu_depth(camera::glu_perspective(fovy, aspect, near, far))
    }

    /// Writes the Transform block for a `width` x `height` viewport.
    pub fn upload(&mut self, gpu: &Gpu, params: &Params, width: u32, height: u32) {
        self.upload_with(gpu, params, Self::projection(width, height));
    }

    /// Writes the Transform block with the given (wgpu-depth) projection.
    pub fn upload_with(&mut self, gpu: &Gpu, params: &Params, projection: Mat4) {
        self.transform.value = TransformUniforms::new(self.modelview(params), projection);
        self.transform.upload(gpu);
    }

    /// Keys `1`-`4` choose cube, sphere, torus, teapot (when the lab has `object`); a
    /// left-button drag turns yangle by ±2° per horizontal motion event and xangle by ±1° per
    /// vertical one. Like the GLUT originals, a coordinate that was 0 at the press does not turn.
    pub fn input(&mut self, params: &mut Params, input: Input) -> bool {
        object_key(params, input) || self.mouse.input(params, input)
    }
}

/// A port addition for the labs comparing per-vertex with per-pixel lighting (`phong_vertex`,
/// `phong_fragment`, `toon`): the tessellation of sphere, torus and teapot, GLUT's by default.
pub const TESS: &[ParamSpec] = &[ParamSpec::int(
    "tess",
    &[0.0],
    0.0,
    crate::mesh::tess::MAX_LEVEL as f64,
    "port: tessellation of sphere, torus (slices = stacks) and teapot (0: GLUT's 24, 24, 8)",
)];

/// GLUT's four solids at GLUT's levels (or the `tess` asked for), uploaded on first use.
#[derive(Default)]
pub struct Solids {
    meshes: HashMap<(Object, u32), ViewOrdered<Vertex>>,
}

impl Solids {
    /// The mesh of `object` (`glutSolidTeapot(1)`, `glutSolidSphere(1,24,24)`,
    /// `glutSolidTorus(0.5,1,24,24)`, `glutSolidCube(1.5)`); `level` 0 is GLUT's, another
    /// tessellates sphere, torus and teapot that finely (the cube has none). With a view
    /// (object-to-clip matrix), its triangles facing the eye come first.
    pub fn get(&mut self, gpu: &Gpu, object: Object, level: u32, view: Option<Mat4>) -> &GpuMesh<Vertex> {
        let level = match object {
            Object::Cube => 0,
            _ => level,
        };
        if !self.meshes.contains_key(&(object, level)) {
            // Keep GLUT's levels; of the others only the newest.
            self.meshes.retain(|&(_, l), _| l == 0);
        }
        self.meshes
            .entry((object, level))
            .or_insert_with(|| {
                let mesh = match level {
                    0 => object.mesh(),
                    l => crate::mesh::tess::mesh(
                        object,
                        l.clamp(crate::mesh::tess::MIN_LEVEL, crate::mesh::tess::MAX_LEVEL),
                    ),
                };
                let positions = mesh.vertices.iter().map(|v| v.position).collect();
                ViewOrdered::new(
                    gpu,
                    &format!("mesh.{}", object.name()),
                    &mesh.vertices,
                    Some(mesh.indices),
                    positions,
                )
            })
            .get(gpu, view.map(|mvp| (mvp, object.outside_winding())))
    }
}

/// The geometry as the runner draws it ([`crate::lab::Geometry`]): GLUT's solid chosen by `object`.
pub struct SolidGeometry {
    /// The shared camera and matrices ([`UstcCamera`]).
    pub camera: UstcCamera,
    solids: Solids,
    /// The face order of `faces=auto`, by solid ([`teapot_and_torus_facing_first`] unless the
    /// lab sets it).
    pub auto: fn(Object) -> FaceOrder,
}

impl SolidGeometry {
    /// A geometry looking from `eye`.
    pub fn new(gpu: &Gpu, label: &str, eye: Vec3) -> Self {
        SolidGeometry {
            camera: UstcCamera::new(gpu, label, eye),
            solids: Solids::default(),
            auto: teapot_and_torus_facing_first,
        }
    }
}

/// The geometry as the runner draws it ([`crate::lab::Geometry`]): the lab's own mesh.
pub struct MeshGeometry<V: VertexType> {
    /// The shared camera and matrices ([`UstcCamera`]).
    pub camera: UstcCamera,
    /// The mesh.
    pub mesh: GpuMesh<V>,
}

impl crate::lab::Geometry for SolidGeometry {
    type Vertex = Vertex;
    fn input(&mut self, p: &mut Params, input: Input) -> bool {
        self.camera.input(p, input)
    }
    fn binds(&self) -> Vec<Bind> {
        vec![self.camera.transform.bind()]
    }
    /// By the `faces` parameter (`auto`: [`SolidGeometry::auto`]).
    fn culling(&self, p: &Params) -> Option<Culling> {
        let object = UstcCamera::object(p);
        Some(FaceOrder::of(p, (self.auto)(object)).culling(object.outside_winding()))
    }
    fn prepare(&mut self, gpu: &Gpu, p: &Params, width: u32, height: u32) -> &GpuMesh<Vertex> {
        self.camera.upload(gpu, p, width, height);
        let level = if p.has("tess") { p.f64("tess") as u32 } else { 0 };
        let object = UstcCamera::object(p);
        let view = (FaceOrder::of(p, (self.auto)(object)) == FaceOrder::FacingFirst)
            .then(|| self.camera.object_to_clip(p, width, height));
        self.solids.get(gpu, object, level, view)
    }
}

impl<V: VertexType + 'static> crate::lab::Geometry for MeshGeometry<V> {
    type Vertex = V;
    fn input(&mut self, p: &mut Params, input: Input) -> bool {
        self.camera.input(p, input)
    }
    fn binds(&self) -> Vec<Bind> {
        vec![self.camera.transform.bind()]
    }
    fn prepare(&mut self, gpu: &Gpu, p: &Params, width: u32, height: u32) -> &GpuMesh<V> {
        self.camera.upload(gpu, p, width, height);
        &self.mesh
    }
}

/// The geometry as the runner draws it ([`crate::lab::Geometry`]): the lab's own mesh of a solid in
/// the face order the `faces` parameter asks for ([`FACES`]; `auto`: [`OrderedGeometry::auto`]).
pub struct OrderedGeometry<V: VertexType> {
    /// The shared camera and matrices ([`UstcCamera`]).
    pub camera: UstcCamera,
    /// The mesh, with its positions for the CPU's facing test.
    pub mesh: ViewOrdered<V>,
    /// How the solid's outside faces are wound.
    pub outside: wgpu::FrontFace,
    /// The face order of `faces=auto`.
    pub auto: FaceOrder,
}

/// The face order parameter alone, for the labs on [`OrderedGeometry`].
pub const FACES: &[ParamSpec] = &[common::FACES];

impl<V: VertexType + 'static> crate::lab::Geometry for OrderedGeometry<V> {
    type Vertex = V;
    fn input(&mut self, p: &mut Params, input: Input) -> bool {
        self.camera.input(p, input)
    }
    fn binds(&self) -> Vec<Bind> {
        vec![self.camera.transform.bind()]
    }
    fn culling(&self, p: &Params) -> Option<Culling> {
        Some(FaceOrder::of(p, self.auto).culling(self.outside))
    }
    fn prepare(&mut self, gpu: &Gpu, p: &Params, width: u32, height: u32) -> &GpuMesh<V> {
        self.camera.upload(gpu, p, width, height);
        let view = (FaceOrder::of(p, self.auto) == FaceOrder::FacingFirst)
            .then(|| (self.camera.object_to_clip(p, width, height), self.outside));
        self.mesh.get(gpu, view)
    }
}

/// The geometry as the runner draws it ([`crate::lab::Geometry`]): one of the lab's meshes, the one a
/// choice parameter names (meshes in the choice's order).
pub struct ChosenGeometry<V: VertexType> {
    /// The shared camera and matrices ([`UstcCamera`]).
    pub camera: UstcCamera,
    /// The meshes, indexed by the choice.
    pub meshes: Vec<GpuMesh<V>>,
    /// The choice parameter.
    pub choice: &'static str,
}

impl<V: VertexType + 'static> crate::lab::Geometry for ChosenGeometry<V> {
    type Vertex = V;
    fn input(&mut self, p: &mut Params, input: Input) -> bool {
        self.camera.input(p, input)
    }
    fn binds(&self) -> Vec<Bind> {
        vec![self.camera.transform.bind()]
    }
    fn prepare(&mut self, gpu: &Gpu, p: &Params, width: u32, height: u32) -> &GpuMesh<V> {
        self.camera.upload(gpu, p, width, height);
        &self.meshes[p.index_of(self.choice).min(self.meshes.len() - 1)]
    }
}
