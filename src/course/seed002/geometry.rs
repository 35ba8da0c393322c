//! The 3D geometry shared by seed 002's `normal_world` and `phong_dir` (SPEC §2.3, §2.4):
//! `glutSolidTeapot(1.0)` seen through a projection stack that holds the view as well,
//! `gluPerspective(60, 1, 0.1, 100)` then `gluLookAt(0,0,5, 0,0,0, 0,1,0)`, so the modelview is
//! the model transform alone and the normal matrix turns normals into world space (the
//! lecture's stated trick, kept).
//!
//! The model rotations are the slide's `glRotated` calls. Mesa's `glRotated` converts its
//! arguments to float and calls `glRotatef` (`_mesa_Rotated` in `main/matrix.c`), and the
//! matrix stack is float, so [`camera::gl_rotate`] (float) is already exact: no double
//! variant is needed.

use glam::{Mat4, Vec3};

use crate::camera;
use crate::course::common::{FaceOrder, TransformUniforms};
use crate::gpu::Gpu;
use crate::lab::Geometry;
use crate::mesh::tess::Object;
use crate::mesh::Vertex;
use crate::params::Params;
use crate::render::{Bind, GpuMesh, Uniforms, ViewOrdered};

/// `gluPerspective(60, 1, 0.1, 100)`: the course passes aspect 1 whatever the window.
pub const PERSPECTIVE: (f64, f64, f64, f64) = (60.0, 1.0, 0.1, 100.0);

/// The eye of `gluLookAt(0,0,5, 0,0,0, 0,1,0)` (also `phong_dir`'s `eye` uniform).
pub const EYE: Vec3 = Vec3::new(0.0, 0.0, 5.0);

/// The projection stack, `gluPerspective(60, 1, 0.1, 100) · gluLookAt(eye, 0,0,0, 0,1,0)`
/// (the course's eye is [`EYE`]), in GL's depth convention (−w..w): what `ftransform()`
/// multiplies by after the modelview.
pub fn projection_stack_gl(eye: Vec3) -> Mat4 {
    let (fovy, aspect, near, far) = PERSPECTIVE;
    camera::glu_perspective(fovy, aspect, near, far) * camera::glu_look_at(eye, Vec3::ZERO, Vec3::Y)
}

/// [`projection_stack_gl`] with wgpu's depth (0..w); x, y and w are unchanged.
pub fn projection_stack(eye: Vec3) -> Mat4 {
    camera::gl_to_wgpu_depth(projection_stack_gl(eye))
}

/// The modelview of `normal_world`: `glRotated(rz, 0,0,1); glRotated(ry, 0,1,0);
/// glRotated(rx, 1,0,0)` — a vertex is turned about x first, then y, then z.
pub fn model_zyx(rx: f32, ry: f32, rz: f32) -> Mat4 {
    camera::gl_rotate(rz, Vec3::Z) * camera::gl_rotate(ry, Vec3::Y) * camera::gl_rotate(rx, Vec3::X)
}

/// `glutSolidTeapot(1.0)` (freeglut's mesh) on the GPU, to be drawn in mesh order or facing
/// the eye first.
pub fn teapot(gpu: &Gpu, label: &str) -> ViewOrdered<Vertex> {
    let mesh = Object::Teapot.mesh();
    let positions = mesh.vertices.iter().map(|v| v.position).collect();
    ViewOrdered::new(gpu, label, &mesh.vertices, Some(mesh.indices), positions)
}

/// The model matrix and the `gluLookAt` eye a lab computes from its parameters.
pub type Pose = fn(&Params) -> (Mat4, Vec3);

/// The geometry as the runner draws it ([`Geometry`]): the teapot, turned by the lab's [`Pose`], seen
/// through [`projection_stack`] (whatever the window's aspect), as the `Transform` block.
pub struct Teapot {
    pose: Pose,
    transform: Uniforms<TransformUniforms>,
    mesh: ViewOrdered<Vertex>,
    /// The face order of `faces=auto`.
    auto: FaceOrder,
}

impl Teapot {
    /// The teapot of lab `label`, posed by `pose`, drawn in `auto`'s face order by default.
    pub fn new(gpu: &Gpu, label: &str, pose: Pose, auto: FaceOrder) -> Self {
        Teapot {
            pose,
            transform: Uniforms::new(
                gpu,
                &format!("{label}.transform"),
                TransformUniforms::new(Mat4::IDENTITY, projection_stack(EYE)),
            ),
            mesh: teapot(gpu, &format!("{label}.teapot")),
            auto,
        }
    }
}

impl Geometry for Teapot {
    type Vertex = Vertex;
    fn binds(&self) -> Vec<Bind> {
        vec![self.transform.bind()]
    }
    /// By the `faces` parameter (the lab's order in `auto`; freeglut winds the teapot's
    /// outside clockwise): the same pixels as GL's mesh order but at exact depth ties, with
    /// the inside faces behind them rejected by the depth test before they are shaded.
    fn culling(&self, p: &Params) -> Option<crate::render::Culling> {
        Some(FaceOrder::of(p, self.auto).culling(wgpu::FrontFace::Cw))
    }
    fn prepare(&mut self, gpu: &Gpu, p: &Params, _width: u32, _height: u32) -> &GpuMesh<Vertex> {
        let (model, eye) = (self.pose)(p);
        let projection = projection_stack(eye);
        self.transform.value = TransformUniforms::new(model, projection);
        self.transform.upload(gpu);
        let view =
            (FaceOrder::of(p, self.auto) == FaceOrder::FacingFirst).then(|| (projection * model, wgpu::FrontFace::Cw));
        self.mesh.get(gpu, view)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec4;

    #[test]
    fn rotation_order_is_z_y_x() {
        // +y: Rx(90) sends it to +z, Ry(90) then to +x, Rz(90) then to +y.
        let v = model_zyx(90.0, 90.0, 90.0) * Vec4::new(0.0, 1.0, 0.0, 0.0);
        assert!((v - Vec4::new(0.0, 1.0, 0.0, 0.0)).length() < 1e-6, "{v}");
        // Only x: +y goes to +z (glRotated(90, 1,0,0)).
        let x = model_zyx(90.0, 0.0, 0.0) * Vec4::new(0.0, 1.0, 0.0, 0.0);
        assert!((x - Vec4::new(0.0, 0.0, 1.0, 0.0)).length() < 1e-6, "{x}");
        // Not the other order: Rx·Ry·Rz would send +y elsewhere.
        let other = camera::lab_rotation(Vec3::splat(90.0)) * Vec4::new(0.0, 1.0, 0.0, 0.0);
        assert!((other - v).length() > 0.5, "{other}");
    }

    #[test]
    fn projection_stack_sees_the_origin_at_five() {
        let p = projection_stack_gl(EYE) * Vec4::new(0.0, 0.0, 0.0, 1.0);
        assert!(p.x.abs() < 1e-6 && p.y.abs() < 1e-6 && (p.w - 5.0).abs() < 1e-5, "{p}");
        // A point at height 5·tan(30°) on the plane z = 0 is at the top edge.
        let top = projection_stack_gl(EYE) * Vec4::new(0.0, 5.0 * 30f32.to_radians().tan(), 0.0, 1.0);
        assert!((top.y / top.w - 1.0).abs() < 1e-5, "{top}");
        let w = projection_stack(EYE) * Vec4::new(0.3, 0.2, 1.0, 1.0);
        let g = projection_stack_gl(EYE) * Vec4::new(0.3, 0.2, 1.0, 1.0);
        assert_eq!((w.x, w.y, w.w), (g.x, g.y, g.w));
    }
}
