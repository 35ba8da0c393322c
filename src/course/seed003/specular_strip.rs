//! Seed 003 (LETI lab report 5, Qt `QOpenGLWidget`, GL 3.3 core) `specular_strip`, SPEC §3: a
//! yellow Bézier strip, 202 vertices drawn as one `GL_TRIANGLE_STRIP`
//! ([`bezier_strip`]), lit by a point light at `lightPos` (ambient 0.1, diffuse, specular 0.5
//! with exponent 64), seen through the report's free-flying camera ([`FlyCamera`]).
//!
//! Course quirks kept (SPEC §6.3):
//! - `for (float t = 0; t <= 1; t += 0.01)` yields 101 points, the last at t = 0.99999934, not 1
//!   (#3; [`crate::mesh::shapes::bezier_parameters`]).
//! - `calculateNormals` negates only the y component of a downward triangle normal, adds each
//!   triangle's normal to two of its three vertices and leaves the last vertex (201) with
//!   (0, 0, 0), kept by Qt 6's `normalize()` (#2). The fragment shader's `normalize(Normal)` of
//!   that zero vector is NaN, but only at vertex 201 itself: every fragment of the last
//!   triangle interpolates a non-zero normal, and the reference shows no stray pixel there; the
//!   port's shader is the course's, unguarded, and renders the same.
//! - The Camera constructor swaps width and height (640 high, 480 wide); `resizeGL` overwrites
//!   both before the first paint (#1), so the projection uses the window's width / height.
//!
//! **Camera state.** The live camera starts in the state the parameters name (SPEC §3's order:
//! after `initializeGL` — skipped with `preset=1` — `up` × move(Up), `forward` × move(Forward),
//! `right` × move(Right), then one `rotate(yaw, pitch)` if either is non-zero;
//! [`FlyStart`]). Keys and the mouse move the live camera itself, not the parameters: the
//! report's camera operations do not commute (a move goes along the current front), so a
//! sequence of them cannot be written back as those six numbers. Changing a state parameter
//! (`--set`, a test) puts the camera back into the state it names; `r` does so by hand. The
//! window title shows the live camera once it has left its start state.
//!
//! Keys: `W`/`S` forward/back, `A`/`D` left/right, `E`/`Q` up/down (0.5 each), ←/→ yaw ∓2°,
//! ↑/↓ pitch ±2° (clamped to ±89°), left-button drag looks around (0.1° per pixel), `r`
//! resets the camera to the parameters' state (a port addition).

use glam::{Mat4, Vec3};

use crate::camera::fly::{FlyCamera, FlyStart, Move};
use crate::camera::gl_to_wgpu_depth;
use crate::gpu::Gpu;
use crate::lab::{FilesTaken, Geometry, Input, Keys, LabInfo, Material, MaterialScene, Recipe, ShaderPair, Special};
use crate::mesh::shapes::{bezier_strip, bezier_strip_n, StripVertex};
use crate::params::{ParamSpec, Params};
use crate::render::{Bind, GpuMesh, RenderState, Uniforms};

/// `specular_strip`: the strip seen by the live camera ([`Fly`]), one shader pair.
pub static RECIPE: Recipe = Recipe::new(
    LabInfo {
        name: "specular_strip",
        original_title: "ref003",
        label: "Bezier strip, specular light",
        lecture: "003 LETI lab 5",
        size: (640, 480),
        keys: Keys::text(
            "W/S: forward/back; A/D: left/right; E/Q: up/down; Left/Right: yaw ∓2°; Up/Down: pitch ±2°;\n\
               left drag looks around (0.1° per pixel); r: camera back to the parameters' state",
        ),
        files: FilesTaken::NONE,
    },
    &[PARAMS],
    |cx, p| MaterialScene::build(cx, p, Fly::new(cx.gpu, p), &MATERIAL),
);

static MATERIAL: Material = Material::new(&[ShaderPair::new("specular_strip.vert", "specular_strip.frag")
    .state(RenderState::GL.topology(wgpu::PrimitiveTopology::TriangleStrip))]);

crate::vertex_type!(StripVertex, {
    position: "objectPosition" => Float32x3,
    color: "objectColor" => Float32x3,
    normal: "normal" => Float32x3,
});

/// The `Strip` block of `specular_strip_params.glsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct StripUniforms {
    /// `projectionMatrix`, depth mapped to wgpu's 0..1.
    pub projection: [[f32; 4]; 4],
    /// `viewMatrix`.
    pub view: [[f32; 4]; 4],
    /// `modelMatrix`: identity.
    pub model: [[f32; 4]; 4],
    /// `lightPos`.
    pub light_pos: [f32; 3],
    /// std140 padding.
    pub _pad0: f32,
    /// `viewPos`: the camera position.
    pub view_pos: [f32; 3],
    /// std140 padding.
    pub _pad1: f32,
}
crate::uniform_block!(StripUniforms, "Strip", {
    projection: "projectionMatrix",
    view: "viewMatrix",
    model: "modelMatrix",
    light_pos: "lightPos",
    view_pos: "viewPos",
});

impl StripUniforms {
    /// The uniforms of one frame: the camera's matrices for `aspect`, identity model.
    pub fn new(camera: &FlyCamera, aspect: f32, light: [f32; 3]) -> Self {
        StripUniforms {
            projection: gl_to_wgpu_depth(camera.projection(aspect)).to_cols_array_2d(),
            view: camera.view().to_cols_array_2d(),
            model: Mat4::IDENTITY.to_cols_array_2d(),
            light_pos: light,
            _pad0: 0.0,
            view_pos: camera.position.to_array(),
            _pad1: 0.0,
        }
    }
}

/// Bound on the step counts of the state parameters.
const STEPS: f64 = 1000.0;

const PARAMS: &[ParamSpec] = &[
    ParamSpec::flag(
        "preset",
        &[0.0],
        "1: skip initializeGL's rotate(30, 0) and 3 × move(Left)",
    ),
    ParamSpec::int(
        "up",
        &[0.0],
        -STEPS,
        STEPS,
        "start: move(Up) this many times (negative: Down)",
    ),
    ParamSpec::int(
        "forward",
        &[0.0],
        -STEPS,
        STEPS,
        "start: then move(Forward) (negative: Back)",
    ),
    ParamSpec::int(
        "right",
        &[0.0],
        -STEPS,
        STEPS,
        "start: then move(Right) (negative: Left)",
    ),
    ParamSpec::real(
        "yaw",
        &[0.0],
        -36000.0,
        36000.0,
        "start: then rotate(yaw, pitch), degrees",
    ),
    ParamSpec::real(
        "pitch",
        &[0.0],
        -36000.0,
        36000.0,
        "start: pitch of that rotate (clamped to ±89°)",
    ),
    ParamSpec::int(
        "segments",
        &[COURSE_SEGMENTS as f64],
        0.0,
        MAX_SEGMENTS as f64,
        "port: steps of t along the curve (course: its float loop, 100); auto (0): the fewest within half a pixel",
    )
    .with_auto(0.0),
    ParamSpec::real("lightx", &[0.0], -1000.0, 1000.0, "lightPos.x"),
    ParamSpec::real("lighty", &[0.0], -1000.0, 1000.0, "lightPos.y"),
    ParamSpec::real("lightz", &[0.0], -1000.0, 1000.0, "lightPos.z"),
];

/// The camera start state the parameters name.
pub fn start_of(p: &Params) -> FlyStart {
    FlyStart {
        preset: p.on("preset"),
        up: p.f64("up") as i32,
        forward: p.f64("forward") as i32,
        right: p.f64("right") as i32,
        yaw: p.f("yaw"),
        pitch: p.f("pitch"),
    }
}

/// The strip and the report's live camera: its keys and mouse, and the `Strip` block (the
/// camera's matrices and position, the light of the parameters).
pub struct Fly {
    /// The live camera.
    camera: FlyCamera,
    /// The start state `camera` was last put into.
    start: FlyStart,
    /// The last mouse position of a left-button drag.
    mouse: (i32, i32),
    uniforms: Uniforms<StripUniforms>,
    strip: GpuMesh<StripVertex>,
    /// The segments `strip` was built with.
    segments: u32,
    /// `segments=auto`'s last choice and what it depends on (eye position and field of view
    /// as bits, picture height): chosen again only when one of them changes, not every frame.
    auto: Option<([u32; 5], u32)>,
}

/// The course's 100 steps of t (its float loop: [`bezier_strip`]).
pub const COURSE_SEGMENTS: u32 = 100;

/// The most segments `segments` takes.
pub const MAX_SEGMENTS: u32 = 10_000;

/// The chord error `segments=auto` allows, in pixels.
pub const SEGMENTS_BUDGET_PX: f64 = 0.5;

/// The largest turn of the strip's normal between two neighbouring vertices `segments=auto`
/// allows, in degrees: the strip is lit per vertex normal with a specular exponent of 64, so
/// the lighting, not the outline, is what a coarse strip gets wrong first.
pub const SEGMENTS_MAX_TURN_DEG: f64 = 0.5;

/// The fewest equal steps of t for which the strip both stays within [`SEGMENTS_BUDGET_PX`]
/// of the curve seen by `camera` in a picture `height` pixels tall and turns its normal by at
/// most [`SEGMENTS_MAX_TURN_DEG`] from vertex to vertex. A quadratic Bézier has the constant
/// second derivative B'' = 2(P0 − 2P1 + P2), so a chord over a step 1/n strays at most
/// |B''|/(8n²) from its arc (projected at the distance of the curve's nearest point to the
/// eye), and its tangent turns at the rate |B' × B''| / |B'|² per unit of t (its largest over
/// the curve, sampled).
pub fn auto_segments(camera: &FlyCamera, height: u32) -> u32 {
    use crate::mesh::shapes::{bezier_point, BEZIER_CONTROL};
    use glam::DVec2;
    let [p0, p1, p2] = BEZIER_CONTROL.map(|[x, y]| DVec2::new(f64::from(x), f64::from(y)));
    let second = 2.0 * (p0 - 2.0 * p1 + p2);
    let eye = camera.position.as_dvec3();
    let nearest = (0..=64)
        .flat_map(|k| {
            let [x, y] = bezier_point(k as f32 / 64.0);
            [-0.5, 0.5].map(|z| (glam::DVec3::new(f64::from(x), f64::from(y), z) - eye).length())
        })
        .fold(f64::INFINITY, f64::min)
        .max(1e-3);
    let pixels_per_unit = f64::from(height) / (2.0 * (f64::from(camera.fov) / 2.0).to_radians().tan() * nearest);
    let chord = (second.length() * pixels_per_unit / (8.0 * SEGMENTS_BUDGET_PX)).sqrt();
    let turn_rate = (0..=256)
        .map(|k| {
            let t = f64::from(k) / 256.0;
            let first = 2.0 * (1.0 - t) * (p1 - p0) + 2.0 * t * (p2 - p1);
            first.perp_dot(second).abs() / first.length_squared().max(1e-12)
        })
        .fold(0.0, f64::max);
    let turn = turn_rate.to_degrees() / SEGMENTS_MAX_TURN_DEG;
    (chord.max(turn).ceil() as u32).clamp(1, MAX_SEGMENTS)
}

impl Fly {
    /// The strip, and the camera in the parameters' start state.
    pub fn new(gpu: &Gpu, p: &Params) -> Fly {
        let start = start_of(p);
        let camera = FlyCamera::from_start(&start);
        Fly {
            uniforms: Uniforms::new(
                gpu,
                "specular_strip.params",
                StripUniforms::new(&camera, 640.0 / 480.0, [0.0; 3]),
            ),
            camera,
            start,
            mouse: (0, 0),
            strip: GpuMesh::new(gpu, "specular_strip.strip", &bezier_strip(), None),
            segments: COURSE_SEGMENTS,
            auto: None,
        }
    }

    /// Puts the camera into the parameters' start state if they changed since it was last put
    /// there.
    fn sync(&mut self, p: &Params) {
        let start = start_of(p);
        if start != self.start {
            self.start = start;
            self.camera = FlyCamera::from_start(&start);
        }
    }
}

impl Geometry for Fly {
    type Vertex = StripVertex;
    fn input(&mut self, p: &mut Params, input: Input) -> bool {
        self.sync(p);
        let camera = &mut self.camera;
        match input {
            Input::Key(c) => match c.to_ascii_lowercase() {
                'w' => camera.move_(Move::Forward),
                's' => camera.move_(Move::Back),
                'a' => camera.move_(Move::Left),
                'd' => camera.move_(Move::Right),
                'e' => camera.move_(Move::Up),
                'q' => camera.move_(Move::Down),
                'r' => *camera = FlyCamera::from_start(&self.start),
                _ => return false,
            },
            Input::Special(Special::Left) => camera.rotate(-2.0, 0.0),
            Input::Special(Special::Right) => camera.rotate(2.0, 0.0),
            Input::Special(Special::Up) => camera.rotate(0.0, 2.0),
            Input::Special(Special::Down) => camera.rotate(0.0, -2.0),
            Input::Special(_) => return false,
            Input::Press(x, y) | Input::Release(x, y) => {
                self.mouse = (x, y);
                return false;
            }
            Input::Drag(x, y) => {
                let (dx, dy) = (x - self.mouse.0, y - self.mouse.1);
                self.mouse = (x, y);
                if (dx, dy) == (0, 0) {
                    return false;
                }
                camera.rotate(0.1 * dx as f32, -0.1 * dy as f32);
            }
        }
        true
    }
    fn binds(&self) -> Vec<Bind> {
        vec![self.uniforms.bind()]
    }
    fn prepare(&mut self, gpu: &Gpu, p: &Params, width: u32, height: u32) -> &GpuMesh<StripVertex> {
        self.sync(p);
        let light = [p.f("lightx"), p.f("lighty"), p.f("lightz")];
        let aspect = width as f32 / height.max(1) as f32;
        self.uniforms.value = StripUniforms::new(&self.camera, aspect, light);
        self.uniforms.upload(gpu);
        let segments = match p.f64("segments") as u32 {
            0 => {
                let [x, y, z] = self.camera.position.to_array().map(f32::to_bits);
                let key = [x, y, z, self.camera.fov.to_bits(), height];
                match self.auto {
                    Some((k, n)) if k == key => n,
                    _ => {
                        let n = auto_segments(&self.camera, height);
                        self.auto = Some((key, n));
                        n
                    }
                }
            }
            n => n,
        };
        if segments != self.segments {
            self.segments = segments;
            let strip = if segments == COURSE_SEGMENTS {
                bezier_strip()
            } else {
                bezier_strip_n(segments)
            };
            self.strip = GpuMesh::new(gpu, "specular_strip.strip", &strip, None);
        }
        &self.strip
    }
    /// The live camera, once it has left the parameters' start state, and `segments=auto`'s
    /// choice.
    fn title(&self, info: &crate::lab::LabInfo, p: &Params) -> String {
        crate::lab::params_title(info, p)
            + &{
                let c = &self.camera;
                let auto = if p.f64("segments") == 0.0 {
                    format!(" | segments auto: {}", self.segments)
                } else {
                    String::new()
                };
                if *c == FlyCamera::from_start(&start_of(p)) {
                    auto
                } else {
                    let Vec3 { x, y, z } = c.position;
                    format!(
                        " | camera ({x:.3}, {y:.3}, {z:.3}) yaw {:.1} pitch {:.1}{auto}",
                        c.yaw, c.pitch
                    )
                }
            }
    }
}
