//! The draws of a frame written down for the debugger: each draw's shaders (the naga modules
//! its pipeline was built from), fixed-function state, vertex and index buffers, bound
//! resources and the pass it belongs to. Nothing is copied while a frame is recorded but
//! handles; [`crate::debug`] reads the buffers back afterwards, so what it replays is what the
//! GPU was given.

use std::cell::RefCell;
use std::ops::Range;
use std::sync::Arc;

use super::{Bind, BindingInfo, Load, RenderState};
use crate::shader::CompiledShader;

/// A texture's texels as the CPU uploaded them: level 0 first, each level `layers` images
/// (1 for 2D, 6 for a cube map: +X, −X, +Y, −Y, +Z, −Z) of RGBA8, row 0 first.
#[derive(Debug)]
pub struct Texels {
    /// Level 0's width.
    pub width: u32,
    /// Level 0's height.
    pub height: u32,
    /// Images per level.
    pub layers: u32,
    /// The levels.
    pub levels: Vec<Vec<u8>>,
}

/// Where a draw lands in its pass's target (`glViewport` and `glDepthRange`): the rectangle
/// that clip space maps to, in pixels from the top left, and the depth range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Viewport {
    /// Left edge in pixels.
    pub x: f32,
    /// Top edge in pixels.
    pub y: f32,
    /// Width in pixels.
    pub width: f32,
    /// Height in pixels.
    pub height: f32,
    /// The depth clip space's 0 maps to.
    pub min_depth: f32,
    /// The depth clip space's 1 maps to.
    pub max_depth: f32,
}

impl Viewport {
    /// The whole of a `width` × `height` target, depth 0 to 1: a pass's viewport until a lab
    /// sets another.
    pub fn whole(width: u32, height: u32) -> Viewport {
        Viewport {
            x: 0.0,
            y: 0.0,
            width: width as f32,
            height: height as f32,
            min_depth: 0.0,
            max_depth: 1.0,
        }
    }
}

/// The scissor rectangle of a draw (`glScissor`): the pixels it may write, x, y, width and
/// height from the top left.
pub type Scissor = [u32; 4];

/// What a draw is apart from the GPU objects it reads: its shaders, fixed-function state,
/// where in the target it lands, vertex layout and range. The recorded [`DrawCall`] and the debugger's CPU copy of it share
/// it.
#[derive(Clone)]
pub struct DrawSetup {
    /// Which pass of the frame (an index into [`DrawLog::passes`]).
    pub pass: usize,
    /// The program's label.
    pub label: String,
    /// The vertex shader the pipeline was built from.
    pub vertex: Arc<CompiledShader>,
    /// The fragment shader.
    pub fragment: Arc<CompiledShader>,
    /// The bindings the shaders declare.
    pub bindings: Vec<BindingInfo>,
    /// The fixed-function state.
    pub state: RenderState,
    /// This draw's culling (a program may draw twice, culling each winding in turn).
    pub cull: Option<wgpu::Face>,
    /// The viewport the pass had when it drew.
    pub viewport: Viewport,
    /// The scissor rectangle the pass had when it drew (its whole target unless set).
    pub scissor: Scissor,
    /// Bytes per vertex.
    pub stride: u64,
    /// The vertex attributes, by shader location.
    pub attributes: Vec<wgpu::VertexAttribute>,
    /// The indices, if indexed (kept on the CPU: WebGL2 cannot copy an index buffer).
    pub indices: Option<Arc<Vec<u32>>>,
    /// The vertices (or indices) drawn.
    pub range: Range<u32>,
}

/// One draw as recorded: its setup and the GPU objects it reads.
#[derive(Clone)]
pub struct DrawCall {
    /// Shaders, state, layout, range.
    pub setup: DrawSetup,
    /// What is bound to the shaders' bindings.
    pub resources: Vec<Bind>,
    /// The vertex buffer.
    pub vertices: wgpu::Buffer,
    /// The pipeline's layout and the bind group drawn with (none where nothing is bound): the
    /// debugger draws the vertex shader again with them for its positions.
    pub layout: wgpu::PipelineLayout,
    /// The bind group.
    pub bind_group: Option<wgpu::BindGroup>,
}

/// The draws of one frame, in order, and its passes (each pass's load operation and target
/// size).
#[derive(Default)]
pub struct DrawLog {
    draws: RefCell<Vec<DrawCall>>,
    passes: RefCell<Vec<(Load, u32, u32)>>,
}

impl DrawLog {
    /// An empty log.
    pub fn new() -> Self {
        Self::default()
    }

    pub(crate) fn begin_pass(&self, load: Load, width: u32, height: u32) {
        self.passes.borrow_mut().push((load, width, height));
    }

    /// Writes down a draw of the current pass.
    pub(crate) fn draw(&self, mut call: DrawCall) {
        call.setup.pass = self.passes.borrow().len().saturating_sub(1);
        self.draws.borrow_mut().push(call);
    }

    /// The draws, in order.
    pub fn draws(&self) -> Vec<DrawCall> {
        self.draws.borrow().clone()
    }

    /// The passes: load operation, target width and height.
    pub fn passes(&self) -> Vec<(Load, u32, u32)> {
        self.passes.borrow().clone()
    }
}
