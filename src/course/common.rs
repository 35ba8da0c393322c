//! What the lectures' geometries share: the GL 2.0 matrices as the `Transform` block, and GLUT's
//! input (keys `1`-`4` choose a solid, the left-button drag turns it).

use glam::{Mat3, Mat4};

use crate::camera;
use crate::lab::Input;
use crate::mesh::tess::Object;
use crate::params::{ParamSpec, Params};
use crate::render::Culling;

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

const OBJECTS_BY_KEY: [Object; 4] = [Object::Cube, Object::Sphere, Object::Torus, Object::Teapot];

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
                params.set_unchecked("xangle", &[f64::from(angles[0].rem_euclid(360.0))]);
                params.set_unchecked("yangle", &[f64::from(angles[1].rem_euclid(360.0))]);
                if params.has("zangle") {
                    let z = params.f("zangle").rem_euclid(360.0);
                    params.set_unchecked("zangle", &[f64::from(z)]);
                }
                true
            }
            _ => false,
        }
    }
}

/// `glRotatef` about x, the vertical drag's angle.
pub const XANGLE: ParamSpec = ParamSpec::real(
    "xangle",
    &[0.0],
    -36000.0,
    36000.0,
    "glRotatef about x, degrees (mouse: vertical drag)",
);

/// `glRotatef` about y, the horizontal drag's angle.
pub const YANGLE: ParamSpec = ParamSpec::real(
    "yangle",
    &[0.0],
    -36000.0,
    36000.0,
    "glRotatef about y, degrees (mouse: horizontal drag)",
);

/// The port's face order (`--set faces=...`), for the labs that draw a solid with the depth
/// test: `auto` is the lab's measured choice, `mesh` GL's mesh order, `outside_first` the
/// outside faces first and then the others in two draws ([`Culling::OutsideFirst`]),
/// `facing_first` one draw of the triangles reordered for the view, those facing the eye first
/// ([`crate::render::facing_first`]). All give the same pixels except at exact depth ties
/// (tests/faces.rs); the last two shade fewer fragments.
pub const FACES: ParamSpec = ParamSpec::choice(
    "faces",
    &[0.0],
    &["auto", "mesh", "outside_first", "facing_first"],
    "port, same pixels: face order; auto = the lab's measured choice, mesh = GL's, \
     outside_first = outside faces first, then the others; facing_first = reordered for the view",
);

/// A face order of [`FACES`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FaceOrder {
    /// GL's: the mesh's order.
    Mesh,
    /// Two draws: the faces wound as the outside, then the others ([`Culling::OutsideFirst`]).
    OutsideFirst,
    /// One draw, the triangles facing the eye first for the view ([`crate::render::ViewOrdered`]).
    FacingFirst,
}

impl FaceOrder {
    /// The order the [`FACES`] parameter asks for, `auto` being the lab's measured choice. A lab
    /// without the parameter draws as `auto` says. Read by index (no text formatted per frame).
    pub fn of(params: &Params, auto: FaceOrder) -> FaceOrder {
        match params.index_of("faces") {
            1 => FaceOrder::Mesh,
            2 => FaceOrder::OutsideFirst,
            3 => FaceOrder::FacingFirst,
            _ => auto,
        }
    }

    /// What the programs draw for this order, `winding` being how the solid's outside faces
    /// are wound: two culled draws for [`FaceOrder::OutsideFirst`], every face once otherwise
    /// (facing-first is an order of the mesh's indices, not of the programs).
    pub fn culling(self, winding: wgpu::FrontFace) -> Culling {
        match self {
            FaceOrder::OutsideFirst => Culling::OutsideFirst(winding),
            FaceOrder::Mesh | FaceOrder::FacingFirst => Culling::AsStated,
        }
    }
}
