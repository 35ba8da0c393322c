//! Seed 001 `particles` (SPEC §1.5): the course's particle-system vertex shader moves 2000
//! one-pixel points, all starting at (0, −1, 0) with their own initial velocity (`attribute vec3
//! vel`), under gravity: `y = y0 + vy·t + g/(2m)·t²`. With g = −2 and m = 1 they rise about one
//! unit in the first second and fall back after. Seen from (0, 1, 4).
//!
//! Keys: Space pauses the clock; `r` restarts at t = 0; `g`/`G` g ∓0.5; `m`/`M` m ∓0.25
//! (at least 0.25); left drag rotates.

use glam::{Mat4, Vec3};

use crate::gpu::Gpu;
use crate::lab::{Geometry, Input, Key::C, KeyRow, Keys, Material, MaterialScene, Recipe, ShaderPair};
use crate::mesh::shapes::{particle_velocities, PARTICLE_COUNT};
use crate::params::{ParamSpec, Params};
use crate::render::{Bind, Derived, GpuMesh, RenderState};

use crate::course::seed001::geometry::{UstcCamera, ROTATION};
use crate::course::seed001::immediate::Immediate;

/// Seed 001, §1.5: the `Particles` block's `g` and `m` are parameters, its `t` the clock
/// `time` as is (no wrap: the course's t grows).
pub static RECIPE: Recipe = Recipe::new(
    super::info(
        lab_name!(),
        "ref001",
        "particle system",
        Keys::rows(
            &[
                KeyRow::step(&[C('g'), C('G')], "g", 0.5),
                KeyRow::step(&[C('m'), C('M')], "m", 0.25),
            ],
            "Space pauses the clock; r: restart at t = 0; left drag rotates",
        ),
    ),
    &[
        &[
            ParamSpec::real(
                "time",
                &[0.0],
                -1e9,
                1e9,
                "t in seconds (a clock in a window; Space pauses, r restarts)",
            ),
            ParamSpec::real("g", &[-2.0], -1000.0, 1000.0, "gravity (g G)"),
            ParamSpec::real("m", &[1.0], 0.25, 1000.0, "mass (m M)"),
        ],
        ROTATION,
    ],
    |cx, p| {
        let geometry = Fountain {
            camera: UstcCamera::new(cx.gpu, cx.name, Vec3::new(0.0, 1.0, 4.0)),
            points: GpuMesh::new(cx.gpu, "particles.points", &course_points(), None),
        };
        MaterialScene::build(cx, p, geometry, &MATERIAL)
    },
)
.animated();

// GL_POINTS at GL's default point size 1 (the only size WebGPU draws).
static MATERIAL: Material = Material::new(&[ShaderPair::new("particles.vert", "particles.frag")
    .state(RenderState::GL.topology(wgpu::PrimitiveTopology::PointList))])
.derive(|p: &Params, c: &mut Derived| c.set("t", &[p.f("time")]));

/// One particle: `glVertexAttrib3fv(vel, …); glVertex3f(0, −1, 0);`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ParticleVertex {
    /// `gl_Vertex`: where it starts.
    pub position: [f32; 3],
    /// The `vel` attribute: its initial velocity.
    pub vel: [f32; 3],
}
crate::vertex_type!(ParticleVertex, {
    position: "vertex_position" => Float32x3,
    vel: "vel" => Float32x3,
});

/// The 2000 particles as the pinned loop sends them: for each, `glVertexAttrib3fv(vel, v_i)`
/// then `glVertex3f(0, −1, 0)` inside `glBegin(GL_POINTS)`.
pub fn course_points() -> Vec<ParticleVertex> {
    let mut points = Immediate::begin(ParticleVertex {
        position: [0.0; 3],
        vel: [0.0; 3],
    });
    for v in particle_velocities(PARTICLE_COUNT) {
        points.attrib(|p| p.vel = v);
        points.vertex(|p| p.position = [0.0, -1.0, 0.0]);
    }
    points.end()
}

/// Subpixel bits of the rasterizer (llvmpipe/lavapipe: 8, i.e. positions snap to 1/256 pixel).
const SUBPIXEL_BITS: i32 = 8;

/// Makes a 1-pixel point light the pixel GL lights. GL's (non-sprite) points light the pixel
/// `floor(x_w)` of the snapped window position; Vulkan's points are 1×1 squares whose left edge
/// is inside, which lights `ceil(x_w) − 1`: the same except where x_w snaps to a whole number,
/// where Vulkan lights the pixel to the left. Moving every point right by one subpixel makes the
/// two rules agree everywhere. (In y the two conventions already agree: Vulkan's y runs down.)
/// Applied to the projection, so the course's shader stays as written.
pub fn gl_point_rule(projection: Mat4, width: u32) -> Mat4 {
    // One subpixel in clip units: x_ndc spans `width` pixels over 2 units; x_clip = x_ndc · w.
    let subpixel = 2.0 / (width.max(1) as f32 * 2f32.powi(SUBPIXEL_BITS));
    let mut shift = Mat4::IDENTITY;
    shift.w_axis.x = subpixel;
    shift * projection
}

/// The frame with the points drawn by GL's rule ([`gl_point_rule`]), and key `r`.
struct Fountain {
    camera: UstcCamera,
    points: GpuMesh<ParticleVertex>,
}

impl Geometry for Fountain {
    type Vertex = ParticleVertex;
    fn input(&mut self, p: &mut Params, input: Input) -> bool {
        if input == Input::Key('r') {
            p.set_unchecked("time", &[0.0]);
            return true;
        }
        self.camera.input(p, input)
    }
    fn binds(&self) -> Vec<Bind> {
        vec![self.camera.transform.bind()]
    }
    fn prepare(&mut self, gpu: &Gpu, p: &Params, width: u32, height: u32) -> &GpuMesh<ParticleVertex> {
        let projection = gl_point_rule(UstcCamera::projection(width, height), width);
        self.camera.upload_with(gpu, p, projection);
        &self.points
    }
}
