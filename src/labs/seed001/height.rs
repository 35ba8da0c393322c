//! Seed 001 `height` (SPEC §1.1): a custom vertex attribute, `attribute float height`, coloured
//! `(s, 0.25, 1 − s)` with `s = (height + 2)/4`: a square, red at the top, blue at the bottom.
//!
//! The course feeds `height` two ways, and both are here as `mode`: 0 per-vertex calls
//! (`glBegin(GL_TRIANGLE_STRIP)`, `glVertexAttrib1f(loc, h)` before each `glVertex2f`), 1 client
//! arrays (`vertices[8]`, `heights[4]`, `glVertexPointer` + `glVertexAttribPointer`,
//! `glDrawArrays(GL_TRIANGLE_STRIP, 0, 4)`). They give the same image. Keys: `v` toggles the
//! mode; left drag rotates.

use glam::Vec3;

use crate::error::Result;
use crate::geometry::shapes::HeightVertex;
use crate::lab::{FilesTaken, Input, Lab, LabContext, LabEntry, LabInfo};
use crate::params::{ParamSpec, Params};
use crate::render::{Frame, GpuMesh, Load, Program, RenderState};

use crate::labs::seed001::immediate::Immediate;
use crate::labs::seed001::stage::{UstcStage, ROTATION};

/// Seed 001, §1.1.
pub static INFO: LabInfo = LabInfo {
    name: "height",
    title: "ref001",
    label: "custom vertex attribute",
    lecture: "001 USTC GLSL (III)",
    size: (512, 512),
    keys: crate::lab::Keys::text("v: feeding mode (per-vertex calls / arrays; same image); left drag rotates"),
    files: FilesTaken::NONE,
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params,
    new,
};

// glVertex2f's x, y and the `height` attribute (GL converts both to the shader's types).
crate::vertex_type!(HeightVertex, {
    position: "vertex_position" => Float32x2,
    height: "height" => Float32,
});

const OWN: &[ParamSpec] = &[ParamSpec::choice(
    "mode",
    &[0.0],
    &["immediate", "arrays"],
    "how height is fed: 0 glVertexAttrib1f per vertex, 1 attribute arrays (v)",
)];

fn params() -> Params {
    let mut p = Params::new(OWN);
    p.extend(ROTATION);
    p
}

/// Mode 0, the course's first listing: `glBegin(GL_TRIANGLE_STRIP)`, then
/// `glVertexAttrib1f(loc, h); glVertex2f(x, y);` four times.
pub fn immediate_strip() -> Vec<HeightVertex> {
    let mut strip = Immediate::begin(HeightVertex {
        position: [0.0; 2],
        height: 0.0, // glVertexAttrib's default x
    });
    for (h, x, y) in [(2.0, -1.0, 1.0), (2.0, 1.0, 1.0), (-2.0, -1.0, -1.0), (-2.0, 1.0, -1.0)] {
        strip.attrib(|v| v.height = h);
        strip.vertex(|v| v.position = [x, y]);
    }
    strip.end()
}

/// Mode 1, the course's second listing: `float vertices[8] = {-1,1, 1,1, -1,-1, 1,-1};
/// float heights[4] = {2,2,-2,-2};` read as `glVertexPointer(2, GL_FLOAT, 0, vertices)` and
/// `glVertexAttribPointer(loc, 1, GL_FLOAT, 0, 0, heights)` (tightly packed arrays; the vertex
/// buffer holds them interleaved).
pub fn array_strip() -> Vec<HeightVertex> {
    let vertices: [f32; 8] = [-1.0, 1.0, 1.0, 1.0, -1.0, -1.0, 1.0, -1.0];
    let heights: [f32; 4] = [2.0, 2.0, -2.0, -2.0];
    vertices
        .chunks_exact(2)
        .zip(heights)
        .map(|(xy, height)| HeightVertex {
            position: [xy[0], xy[1]],
            height,
        })
        .collect()
}

struct Height {
    params: Params,
    stage: UstcStage,
    program: Program<HeightVertex>,
    /// Indexed by `mode`.
    strips: [GpuMesh<HeightVertex>; 2],
}

fn new(cx: &LabContext) -> Result<Box<dyn Lab>> {
    let stage = UstcStage::new(cx.gpu, "height", Vec3::new(0.0, 0.0, 4.0));
    let state = RenderState::default().topology(wgpu::PrimitiveTopology::TriangleStrip);
    let mut program = Program::new(cx, "height", "height.vert", "pass_color.frag", state)?;
    program.bind(cx.gpu, vec![stage.transform.bind()])?;
    let strips = [
        GpuMesh::new(cx.gpu, "height.immediate", &immediate_strip(), None),
        GpuMesh::new(cx.gpu, "height.arrays", &array_strip(), None),
    ];
    Ok(Box::new(Height {
        params: params(),
        stage,
        program,
        strips,
    }))
}

impl Lab for Height {
    fn info(&self) -> &'static LabInfo {
        &INFO
    }
    fn params(&self) -> &Params {
        &self.params
    }
    fn params_mut(&mut self) -> &mut Params {
        &mut self.params
    }
    fn input(&mut self, input: Input) -> bool {
        match input {
            Input::Key('v') => {
                self.params.cycle("mode");
                true
            }
            _ => self.stage.input(&mut self.params, input),
        }
    }
    fn reload(&mut self, cx: &LabContext) -> Result<()> {
        self.program.reload(cx)
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        self.stage.upload(frame.gpu, &self.params, frame.width, frame.height);
        let strip = &self.strips[self.params.index_of("mode").min(1)];
        let mut pass = frame.pass("height", Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, strip);
        Ok(())
    }
}
