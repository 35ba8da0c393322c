//! The geometry of seed 004 ("OpenGL III – Basic Shaders", SPEC §4): the course's model — Suzanne,
//! or the user's `--model FILE.obj` — as its 9-float VBO twice (face normals as exported, and
//! the "Smooth Suzanne" vertex normals), turned by `M = rotate(xangle, X)·rotate(yangle, Y)`
//! that a left-button drag changes by 0.5° per pixel, seen from (0, 0, 4) through
//! `perspective(45°, aspect, 0.1, 100)`; the matrices MV, MVP and NM computed in float as glm
//! does and sent as one uniform block (`suzanne_transform.glsl`). [`Model`] is the geometry the
//! runner draws; it answers for the parameters `xangle` and `yangle`.

use glam::{Mat4, Vec3};

use crate::camera::{self, glm};
use crate::course::common::{self, std140_mat3, FaceOrder};
use crate::error::Result;
use crate::gpu::Gpu;
use crate::lab::{BuildContext, Geometry, Input};
use crate::mesh::obj::{self, ObjCorner};
use crate::params::{ParamSpec, Params};
use crate::render::{check_fits, Bind, Culling, GpuMesh, Uniforms, ViewOrdered};

// The course's attributes, found by name (glGetAttribLocation): stride 36, offsets 0, 16, 24.
crate::vertex_type!(ObjCorner, {
    position: "v_coord" => Float32x4,
    uv: "v_texcoord" => Float32x2,
    normal: "v_normal" => Float32x3,
});

/// The `Matrices` block of `suzanne_transform.glsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SuzanneMatrices {
    /// `MV` = V·M.
    pub mv: [[f32; 4]; 4],
    /// `MVP` = P·MV, depth mapped to wgpu's 0..1.
    pub mvp: [[f32; 4]; 4],
    /// `NM` = transpose(inverse(mat3(MV))); std140 stores a mat3 as three vec4 columns.
    pub nm: [[f32; 4]; 3],
}
crate::uniform_block!(SuzanneMatrices, "Matrices", {
    mv: "MV",
    mvp: "MVP",
    nm: "NM",
});

impl SuzanneMatrices {
    /// The course's matrices for model `m`, view `v` and a window of `aspect` (width / height).
    pub fn new(m: Mat4, v: Mat4, aspect: f32) -> Self {
        let mv = v * m;
        let p = camera::gl_to_wgpu_depth(projection(aspect));
        SuzanneMatrices {
            mv: mv.to_cols_array_2d(),
            mvp: (p * mv).to_cols_array_2d(),
            nm: std140_mat3(glm::normal_matrix(mv)),
        }
    }
}

/// P = `glm::perspective(glm::radians(45.0f), aspect, 0.1f, 100.0f)` (GL depth).
pub fn projection(aspect: f32) -> Mat4 {
    glm::perspective(glm::radians(45.0), aspect, 0.1, 100.0)
}

/// M = `rotate(rotate(mat4(1), radians(xangle), X), radians(yangle), Y)`.
pub fn model(xangle: f32, yangle: f32) -> Mat4 {
    let m = glm::rotate(Mat4::IDENTITY, glm::radians(xangle), Vec3::X);
    glm::rotate(m, glm::radians(yangle), Vec3::Y)
}

/// V = `lookAt((0,0,4), (0,0,0), (0,1,0))`.
pub fn view() -> Mat4 {
    glm::look_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, Vec3::Y)
}

/// The model's rotation (pinned: the exercise "turn the normals with the model" needs one),
/// and the port's face order.
pub const ANGLES: &[ParamSpec] = &[
    ParamSpec::real(
        "xangle",
        &[0.0],
        -36000.0,
        36000.0,
        "rotation about x, degrees (vertical drag)",
    ),
    ParamSpec::real(
        "yangle",
        &[0.0],
        -36000.0,
        36000.0,
        "rotation about y, degrees (horizontal drag)",
    ),
    common::FACES,
];

/// Which of the model's two VBOs a program draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Normals {
    /// The file's normals: one per face for the course's export.
    Face,
    /// Vertex normals, the unweighted average of the faces around each `v` (SPEC §4.0).
    Vertex,
}

/// The geometry as the runner draws it ([`Geometry`]): the model, its rotation and the Matrices
/// block, drawing the VBO `normals` picks for the parameters (one exercise's own, or the
/// shading model's).
pub struct Model {
    /// Where the left button was last seen while held.
    drag: Option<(i32, i32)>,
    /// The Matrices block.
    pub matrices: Uniforms<SuzanneMatrices>,
    faces: ViewOrdered<ObjCorner>,
    smooth: ViewOrdered<ObjCorner>,
    /// Which normals to draw.
    pub normals: fn(&Params) -> Normals,
    /// The face order of `faces=auto` ([`FaceOrder`]) on the vertex-normal VBO: mesh order
    /// unless a lab sets otherwise. On the face-normal VBO `auto` is mesh order whatever this
    /// says: reordered, it draws the same pixels but gains nothing (figures: `docs/speed.md`,
    /// "Face orders").
    pub auto: fn(&Params) -> FaceOrder,
}

impl Model {
    /// Uploads the model (`--model`, else the shipped Suzanne) with both kinds of normals.
    pub fn new(cx: &BuildContext, label: &str, normals: fn(&Params) -> Normals) -> Result<Self> {
        let suzanne;
        let model = match &cx.files.model {
            Some(file) => {
                // Two VBOs (face and vertex normals), each uploaded through a staging copy, with
                // the positions and index lists kept to reorder it, and the driver's own work
                // per vertex drawn: about 250 bytes per corner on lavapipe (figures:
                // `docs/speed.md`, "Large meshes, models and pictures").
                let corners = file.data.corners.len() as u64;
                let vbo = corners * std::mem::size_of::<ObjCorner>() as u64;
                let total = corners * 250;
                check_fits(
                    cx.gpu,
                    &format!("{} ({} triangles)", file.path.display(), file.data.triangle_count()),
                    vbo,
                    total,
                )?;
                &file.data
            }
            None => {
                suzanne = obj::suzanne();
                &suzanne
            }
        };
        let matrices = SuzanneMatrices::new(Mat4::IDENTITY, view(), 4.0 / 3.0);
        Ok(Model {
            drag: None,
            matrices: Uniforms::new(cx.gpu, &format!("{label}.matrices"), matrices),
            faces: corners(cx.gpu, &format!("{label}.faces"), &model.corners),
            smooth: corners(cx.gpu, &format!("{label}.smooth"), &model.smooth),
            normals,
            auto: |_| FaceOrder::Mesh,
        })
    }
}

/// An OBJ's corners, three per triangle, as the course's VBO holds them (drawn unindexed in
/// mesh order: drawn indexed, two pixels of `yangle=180` come out otherwise).
fn corners(gpu: &Gpu, label: &str, corners: &[ObjCorner]) -> ViewOrdered<ObjCorner> {
    let positions = corners
        .iter()
        .map(|c| [c.position[0], c.position[1], c.position[2]])
        .collect();
    ViewOrdered::new(gpu, label, corners, None, positions)
}

impl Model {
    /// The face order the `faces` parameter asks for ([`Model::auto`] in `auto`).
    fn order(&self, p: &Params) -> FaceOrder {
        let auto = match (self.normals)(p) {
            Normals::Face => FaceOrder::Mesh,
            Normals::Vertex => (self.auto)(p),
        };
        FaceOrder::of(p, auto)
    }
}

impl Geometry for Model {
    type Vertex = ObjCorner;

    /// Left-button drag: yangle += 0.5° per pixel of x, xangle += 0.5° per pixel of y.
    fn input(&mut self, params: &mut Params, input: Input) -> bool {
        match input {
            Input::Press(x, y) => {
                self.drag = Some((x, y));
                false
            }
            Input::Release(..) => {
                self.drag = None;
                false
            }
            Input::Drag(x, y) => {
                let Some((x0, y0)) = self.drag.replace((x, y)) else {
                    return false;
                };
                // Kept within one turn, so a long session never loses float precision.
                for (name, pixels) in [("yangle", x - x0), ("xangle", y - y0)] {
                    let angle = (params.f(name) + 0.5 * pixels as f32).rem_euclid(360.0);
                    params.set_unchecked(name, &[f64::from(angle)]);
                }
                true
            }
            _ => false,
        }
    }

    fn binds(&self) -> Vec<Bind> {
        vec![self.matrices.bind()]
    }

    /// By the `faces` parameter; in `auto`, as [`Model::auto`] says (Suzanne's outside faces
    /// are counter-clockwise, as Blender writes them): the same pixels, with the faces behind
    /// them rejected by the depth test before they are shaded.
    fn culling(&self, p: &Params) -> Option<Culling> {
        Some(self.order(p).culling(wgpu::FrontFace::Ccw))
    }

    /// Writes the Matrices block for the current angles and returns the VBO `normals` picks.
    fn prepare(&mut self, gpu: &Gpu, p: &Params, width: u32, height: u32) -> &GpuMesh<ObjCorner> {
        let m = model(p.f("xangle"), p.f("yangle"));
        let aspect = width as f32 / height.max(1) as f32;
        self.matrices.value = SuzanneMatrices::new(m, view(), aspect);
        self.matrices.upload(gpu);
        let view = (self.order(p) == FaceOrder::FacingFirst)
            .then(|| (Mat4::from_cols_array_2d(&self.matrices.value.mvp), wgpu::FrontFace::Ccw));
        match (self.normals)(p) {
            Normals::Face => self.faces.get(gpu, view),
            Normals::Vertex => self.smooth.get(gpu, view),
        }
    }
}
