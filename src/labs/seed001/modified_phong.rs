//! The course's modified Phong (Blinn, no distance term) lighting, per vertex and per fragment:
//! the one lab behind seed 001's `phong_vertex` (§1.7) and `phong_fragment` (§1.8), which differ
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
use crate::lab::{Input, Lab, LabContext, LabInfo};
use crate::mesh::Vertex;
use crate::params::{ParamSpec, Params};
use crate::render::{Frame, Load, Program, RenderState};

use crate::labs::seed001::gl_light::{GlLight, COURSE};
use crate::labs::seed001::stage::{Solids, UstcStage, OBJECT, ROTATION};

/// Where the lighting is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shading {
    /// `phong_vertex`: in the vertex shader, the colour interpolated.
    Vertex,
    /// `phong_fragment`: N, L, E interpolated, the lighting in the fragment shader.
    Fragment,
}

/// The keys line both labs show.
pub const KEYS: &str =
    "c: compare per vertex (left) with per fragment (right); ←/→ ↑/↓ PageUp/PageDown: light ±0.25;\n\
                        h/H: shininess ∓5; 1-4: objects; left drag rotates";

const OWN: &[ParamSpec] = &[ParamSpec::flag(
    "compare",
    &[0.0],
    "port: per vertex (left) and per fragment (right) side by side (c)",
)];

/// The parameters of both labs.
pub fn params() -> Params {
    let mut p = Params::new(OBJECT);
    p.extend(ROTATION);
    p.extend(COURSE.params);
    p.extend(OWN);
    p
}

struct ModifiedPhong {
    info: &'static LabInfo,
    shading: Shading,
    params: Params,
    stage: UstcStage,
    light: GlLight,
    per_vertex: Program<Vertex>,
    per_fragment: Program<Vertex>,
    solids: Solids,
}

/// Builds the lab drawn by default with `shading`.
pub fn new(cx: &LabContext, info: &'static LabInfo, shading: Shading) -> Result<Box<dyn Lab>> {
    let stage = UstcStage::new(cx.gpu, info.name, Vec3::new(0.0, 0.0, 4.0));
    let light = GlLight::new(cx.gpu, info.name, &COURSE);
    let bindings = || vec![stage.transform.bind(), light.uniforms.bind()];
    let mut per_vertex = Program::new(
        cx,
        &format!("{}.per_vertex", info.name),
        "phong_vertex.vert",
        "pass_color.frag",
        RenderState::default(),
    )?;
    per_vertex.bind(cx.gpu, bindings())?;
    let mut per_fragment = Program::new(
        cx,
        &format!("{}.per_fragment", info.name),
        "phong_fragment.vert",
        "phong_fragment.frag",
        RenderState::default(),
    )?;
    per_fragment.bind(cx.gpu, bindings())?;
    Ok(Box::new(ModifiedPhong {
        info,
        shading,
        params: params(),
        stage,
        light,
        per_vertex,
        per_fragment,
        solids: Solids::default(),
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

impl Lab for ModifiedPhong {
    fn info(&self) -> &'static LabInfo {
        self.info
    }
    fn params(&self) -> &Params {
        &self.params
    }
    fn params_mut(&mut self) -> &mut Params {
        &mut self.params
    }
    fn input(&mut self, input: Input) -> bool {
        match input {
            Input::Key('c') => {
                self.params.toggle("compare");
                true
            }
            _ => self.light.input(&mut self.params, input) || self.stage.input(&mut self.params, input),
        }
    }
    fn reload(&mut self, cx: &LabContext) -> Result<()> {
        self.per_vertex.reload(cx)?;
        self.per_fragment.reload(cx)
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        let gpu = frame.gpu;
        let (width, height) = (frame.width, frame.height);
        let compare = self.params.on("compare");
        self.light.upload(gpu, &self.params);
        let viewports = compare_viewports(width, height);
        if compare {
            // Both halves are squares: one projection (aspect 1) for the one scene.
            let side = viewports[0].2;
            self.stage.upload(gpu, &self.params, side, side);
        } else {
            self.stage.upload(gpu, &self.params, width, height);
        }
        let mesh = self.solids.get(gpu, UstcStage::object(&self.params));
        let mut pass = frame.pass(self.info.name, Load::Clear([0.0; 3]));
        if compare {
            for ((x, y, side), program) in viewports.into_iter().zip([&self.per_vertex, &self.per_fragment]) {
                pass.set_viewport(x as f32, y as f32, side as f32, side as f32, 0.0, 1.0);
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
