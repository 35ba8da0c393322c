//! The course's modified Phong (Blinn, no distance term) lighting, per vertex and per fragment:
//! the one scene behind seed 001's `phong_vertex` (§1.7) and `phong_fragment` (§1.8), which differ
//! in which program draws by default. Both read GL's light and material (`gl_light.glsl`): light
//! (2, 2, 2) in eye space, material (0.2, 0.3, 0.8) with a white highlight of shininess 40.
//!
//! `compare` (key `c`, a port addition) draws the one scene twice with the two programs, in two
//! square viewports side by side: per vertex on the left, per fragment on the right, so the
//! blotchy per-vertex highlight is seen next to the round per-fragment one. `compare=0` (the
//! default) renders exactly SPEC's image.
//!
//! Keys: `c` compare; light keys (`←→↑↓`, PageUp/PageDown, `h`/`H` shininess ∓5); `1`-`4`
//! objects; left drag rotates.

use glam::Vec3;

use crate::error::Result;
use crate::lab::{BuildContext, Geometry, Input, Key::C, KeyRow, Keys, Scene};
use crate::mesh::Vertex;
use crate::params::{ParamSpec, Params};
use crate::render::{AnyProgram, Frame, Load, Program, RenderState, Viewport};

use crate::course::seed001::geometry::{SolidGeometry, OBJECT, ROTATION, TESS};
use crate::course::seed001::gl_light::{Lit, COURSE, COURSE_KEYS};

/// Where the lighting is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shading {
    /// `phong_vertex`: in the vertex shader, the colour interpolated.
    Vertex,
    /// `phong_fragment`: N, L, E interpolated, the lighting in the fragment shader.
    Fragment,
}

/// The key rows of both labs: `c` compare, then the light keys.
const ROWS: &[KeyRow] = &[
    KeyRow::toggle(&[C('c')], "compare"),
    COURSE_KEYS[0],
    COURSE_KEYS[1],
    COURSE_KEYS[2],
    COURSE_KEYS[3],
];

/// The keys both labs show.
pub const KEYS: Keys = Keys::rows(ROWS, "1-4: objects; left drag rotates");

const OWN: &[ParamSpec] = &[ParamSpec::flag(
    "compare",
    &[0.0],
    "port: per vertex (left) and per fragment (right) side by side (c)",
)];

/// The parameters of both labs.
pub const PARAMS: &[&[ParamSpec]] = &[OBJECT, ROTATION, COURSE.params, OWN, TESS];

/// Both programs on one lit frame.
struct ModifiedPhong {
    label: &'static str,
    shading: Shading,
    geometry: Lit<SolidGeometry>,
    per_vertex: Program<Vertex>,
    per_fragment: Program<Vertex>,
}

/// Builds the scene drawn by default with `shading`.
pub fn build(cx: &BuildContext, label: &'static str, shading: Shading) -> Result<Box<dyn Scene>> {
    let geometry = Lit::new(
        cx.gpu,
        label,
        &COURSE,
        SolidGeometry::new(cx.gpu, label, Vec3::new(0.0, 0.0, 4.0)),
    );
    let program = |suffix: &str, vert: &str, frag: &str| -> Result<Program<Vertex>> {
        let mut program = Program::new(cx, &format!("{label}.{suffix}"), vert, frag, RenderState::GL)?;
        program.bind(cx.gpu, geometry.binds())?;
        Ok(program)
    };
    let per_vertex = program("per_vertex", "phong_vertex.vert", "pass_color.frag")?;
    let per_fragment = program("per_fragment", "phong_fragment.vert", "phong_fragment.frag")?;
    Ok(Box::new(ModifiedPhong {
        label,
        shading,
        geometry,
        per_vertex,
        per_fragment,
    }))
}

/// The two square viewports of the comparison, (x, y, side) each: the largest squares that fit
/// the two halves of a `width` x `height` target, centred in them.
pub fn compare_viewports(width: u32, height: u32) -> [(u32, u32, u32); 2] {
    let half = width / 2;
    let side = half.min(height).max(1);
    let y = (height.saturating_sub(side)) / 2;
    let x = (half.saturating_sub(side)) / 2;
    [(x, y, side), (half + x, y, side)]
}

impl Scene for ModifiedPhong {
    fn input(&mut self, p: &mut Params, input: Input) -> bool {
        self.geometry.input(p, input)
    }
    fn programs(&mut self) -> Vec<&mut dyn AnyProgram> {
        vec![&mut self.per_vertex, &mut self.per_fragment]
    }
    fn render(&mut self, p: &Params, frame: &mut Frame<'_>) -> Result<()> {
        let (width, height) = (frame.width, frame.height);
        let compare = p.on("compare");
        let viewports = compare_viewports(width, height);
        // Compared, both halves are squares: one projection (aspect 1) for the one scene.
        let side = viewports[0].2;
        let (w, h) = if compare { (side, side) } else { (width, height) };
        let mesh = self.geometry.prepare(frame.gpu, p, w, h);
        let mut pass = frame.pass(self.label, Load::Clear([0.0; 3]));
        if compare {
            for ((x, y, side), program) in viewports.into_iter().zip([&self.per_vertex, &self.per_fragment]) {
                pass.set_viewport(Viewport {
                    x: x as f32,
                    y: y as f32,
                    width: side as f32,
                    height: side as f32,
                    min_depth: 0.0,
                    max_depth: 1.0,
                });
                program.draw(&mut pass, mesh);
            }
        } else {
            let program = match self.shading {
                Shading::Vertex => &self.per_vertex,
                Shading::Fragment => &self.per_fragment,
            };
            program.draw(&mut pass, mesh);
        }
        Ok(())
    }
}
