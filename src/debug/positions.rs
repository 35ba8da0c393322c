//! Clip-space positions of a big draw's vertices computed by the GPU, so that finding the
//! primitives that cover a pixel costs about what drawing them costs.
//!
//! The draw's own vertex shader (the naga module its pipeline was built from) is rewritten to
//! return, besides a position of its own, the bits of the `gl_Position` it computes as a flat
//! `uvec4`; drawn as points, vertex `first + i` lands on texel `i` of an `Rgba32Uint` target,
//! which is read back with the draw's buffers. The bits are the GPU's own, so the replay finds
//! exactly the triangles the GPU rasterised. A small draw keeps the interpreter (no pipeline to
//! build for it); a shader the rewrite or the GPU refuses falls back to it too.

use naga::{
    BinaryOperator, Binding, BuiltIn, Expression, Handle, Literal, Module, ScalarKind, Span, Statement, Type, TypeInner,
};

use crate::gpu::Gpu;
use crate::render::DrawCall;

/// The texels of a row of the positions target.
pub const WIDTH: u32 = 1024;

/// The vertices a draw spans (largest index − smallest + 1) from which the GPU computes their
/// positions; below it the interpreter does, without a pipeline to build.
pub const GPU_FROM: u32 = 16_384;

/// The fragment shader of the positions pass: the bits as they come.
const FRAGMENT: &str = "@fragment
fn main(@location(0) @interpolate(flat) clip: vec4<u32>) -> @location(0) vec4<u32> {
    return clip;
}
";

/// `module`'s vertex entry point rewritten to draw vertex `first + i` as a point on texel
/// `i mod (rows · WIDTH)` (row-major, [`WIDTH`] a row, `rows` rows: a mesh too big for one
/// target is drawn in several passes) carrying the bits of its `gl_Position` at location 0;
/// `None` where the module has no such entry point or the rewrite does not validate.
pub fn module(original: &Module, first: u32, rows: u32) -> Option<Module> {
    let mut module = original.clone();
    let ep = module
        .entry_points
        .iter()
        .position(|e| e.stage == naga::ShaderStage::Vertex)?;
    let keep = module.entry_points.swap_remove(ep);
    module.entry_points = vec![keep];
    let f32t = naga::Scalar::F32;
    let u32t = naga::Scalar::U32;
    let vec4f = module.types.insert(
        Type {
            name: None,
            inner: TypeInner::Vector {
                size: naga::VectorSize::Quad,
                scalar: f32t,
            },
        },
        Span::UNDEFINED,
    );
    let vec4u = module.types.insert(
        Type {
            name: None,
            inner: TypeInner::Vector {
                size: naga::VectorSize::Quad,
                scalar: u32t,
            },
        },
        Span::UNDEFINED,
    );
    let out_ty = module.types.insert(
        Type {
            name: Some("ShaderlabDebugPosition".into()),
            inner: TypeInner::Struct {
                members: vec![
                    naga::StructMember {
                        name: Some("position".into()),
                        ty: vec4f,
                        binding: Some(Binding::BuiltIn(BuiltIn::Position { invariant: false })),
                        offset: 0,
                    },
                    naga::StructMember {
                        name: Some("clip".into()),
                        ty: vec4u,
                        binding: Some(Binding::Location {
                            location: 0,
                            interpolation: Some(naga::Interpolation::Flat),
                            sampling: None,
                            blend_src: None,
                            per_primitive: false,
                        }),
                        offset: 16,
                    },
                ],
                span: 32,
            },
        },
        Span::UNDEFINED,
    );
    let types = &module.types;
    let function = &mut module.entry_points[0].function;
    // Where the result holds gl_Position: the result itself, or member `k` of it.
    let result = function.result.as_ref()?;
    let member = match (&result.binding, &types[result.ty].inner) {
        (Some(Binding::BuiltIn(BuiltIn::Position { .. })), _) => None,
        (None, TypeInner::Struct { members, .. }) => Some(
            members
                .iter()
                .position(|m| matches!(m.binding, Some(Binding::BuiltIn(BuiltIn::Position { .. }))))?
                as u32,
        ),
        _ => return None,
    };
    // The vertex index: an argument of its own, a member of a struct argument, or one added;
    // and whether it is signed (an `int`, bitcast back).
    let signed = |ty: Handle<Type>| matches!(types[ty].inner, TypeInner::Scalar(s) if s.kind == ScalarKind::Sint);
    let mut index_arg = None;
    for (i, a) in function.arguments.iter().enumerate() {
        match (&a.binding, &types[a.ty].inner) {
            (Some(Binding::BuiltIn(BuiltIn::VertexIndex)), _) => index_arg = Some((i as u32, None, signed(a.ty))),
            (None, TypeInner::Struct { members, .. }) => {
                if let Some(m) = members
                    .iter()
                    .position(|m| matches!(m.binding, Some(Binding::BuiltIn(BuiltIn::VertexIndex))))
                {
                    index_arg = Some((i as u32, Some(m as u32), signed(members[m].ty)));
                }
            }
            _ => {}
        }
    }
    let index_arg = match index_arg {
        Some(found) => found,
        None => {
            let u32_ty = module.types.insert(
                Type {
                    name: None,
                    inner: TypeInner::Scalar(u32t),
                },
                Span::UNDEFINED,
            );
            let function = &mut module.entry_points[0].function;
            function.arguments.push(naga::FunctionArgument {
                name: Some("shaderlab_vertex_index".into()),
                ty: u32_ty,
                binding: Some(Binding::BuiltIn(BuiltIn::VertexIndex)),
            });
            (function.arguments.len() as u32 - 1, None, false)
        }
    };
    let function = &mut module.entry_points[0].function;
    function.result = Some(naga::FunctionResult {
        ty: out_ty,
        binding: None,
    });
    let rewrite = Rewrite {
        member,
        index_arg,
        first,
        rows,
        vec4f,
        out_ty,
    };
    let mut body = std::mem::take(&mut function.body);
    rewrite.block(&mut body, &mut function.expressions);
    function.body = body;
    let mut validator =
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all());
    validator.validate(&module).ok()?;
    Some(module)
}

/// What a `return` of the entry point becomes.
struct Rewrite {
    member: Option<u32>,
    /// The argument holding the vertex index, its member (in a struct argument), whether signed.
    index_arg: (u32, Option<u32>, bool),
    first: u32,
    rows: u32,
    vec4f: Handle<Type>,
    out_ty: Handle<Type>,
}

impl Rewrite {
    fn block(&self, block: &mut naga::Block, exprs: &mut naga::Arena<Expression>) {
        for (statement, _) in block.span_iter_mut() {
            match statement {
                Statement::Return { value: Some(value) } => {
                    let value = *value;
                    *statement = Statement::Block(self.returned(value, exprs));
                }
                Statement::Block(b) => self.block(b, exprs),
                Statement::If { accept, reject, .. } => {
                    self.block(accept, exprs);
                    self.block(reject, exprs);
                }
                Statement::Switch { cases, .. } => {
                    for case in cases {
                        self.block(&mut case.body, exprs);
                    }
                }
                Statement::Loop { body, continuing, .. } => {
                    self.block(body, exprs);
                    self.block(continuing, exprs);
                }
                _ => {}
            }
        }
    }

    /// The statements that return the point for `value`, the entry point's original result.
    fn returned(&self, value: Handle<Expression>, exprs: &mut naga::Arena<Expression>) -> naga::Block {
        let s = Span::UNDEFINED;
        // Expressions in scope without an `Emit` first.
        let arg = exprs.append(Expression::FunctionArgument(self.index_arg.0), s);
        let first = exprs.append(Expression::Literal(Literal::U32(self.first)), s);
        let width = exprs.append(Expression::Literal(Literal::U32(WIDTH)), s);
        let per_pass = exprs.append(Expression::Literal(Literal::U32(self.rows * WIDTH)), s);
        let half = exprs.append(Expression::Literal(Literal::F32(0.5)), s);
        let sx = exprs.append(Expression::Literal(Literal::F32(2.0 / WIDTH as f32)), s);
        let sy = exprs.append(Expression::Literal(Literal::F32(2.0 / self.rows as f32)), s);
        let one = exprs.append(Expression::Literal(Literal::F32(1.0)), s);
        let zero = exprs.append(Expression::Literal(Literal::F32(0.0)), s);
        let start = exprs.len();
        let mut add = |e: Expression| exprs.append(e, s);
        let bin = |op, left, right| Expression::Binary { op, left, right };
        let mut vertex = match self.index_arg.1 {
            Some(m) => add(Expression::AccessIndex { base: arg, index: m }),
            None => arg,
        };
        if self.index_arg.2 {
            vertex = add(Expression::As {
                expr: vertex,
                kind: ScalarKind::Uint,
                convert: None,
            });
        }
        let i = add(bin(BinaryOperator::Subtract, vertex, first));
        let i = add(bin(BinaryOperator::Modulo, i, per_pass));
        let column = add(bin(BinaryOperator::Modulo, i, width));
        let row = add(bin(BinaryOperator::Divide, i, width));
        let to_float = |e| Expression::As {
            expr: e,
            kind: ScalarKind::Float,
            convert: Some(4),
        };
        let column = add(to_float(column));
        let row = add(to_float(row));
        // x = (column + 0.5) · 2/WIDTH − 1, y = 1 − (row + 0.5) · 2/rows (row 0 at the top).
        let x = add(bin(BinaryOperator::Add, column, half));
        let x = add(bin(BinaryOperator::Multiply, x, sx));
        let x = add(bin(BinaryOperator::Subtract, x, one));
        let y = add(bin(BinaryOperator::Add, row, half));
        let y = add(bin(BinaryOperator::Multiply, y, sy));
        let y = add(bin(BinaryOperator::Subtract, one, y));
        let point = add(Expression::Compose {
            ty: self.vec4f,
            components: vec![x, y, zero, one],
        });
        let clip = match self.member {
            Some(k) => add(Expression::AccessIndex { base: value, index: k }),
            None => value,
        };
        let bits = add(Expression::As {
            expr: clip,
            kind: ScalarKind::Uint,
            convert: None,
        });
        let out = add(Expression::Compose {
            ty: self.out_ty,
            components: vec![point, bits],
        });
        let mut block = naga::Block::new();
        block.push(Statement::Emit(exprs.range_from(start)), s);
        block.push(Statement::Return { value: Some(out) }, s);
        block
    }
}

/// A draw's positions being computed and read back: the staging buffers (one per pass), the
/// first vertex and how many.
pub struct Job {
    /// Which draw of the log.
    pub draw: usize,
    /// The read-back, a pass's target in each.
    pub staging: Vec<wgpu::Buffer>,
    /// The first vertex.
    pub first: u32,
    /// The vertices.
    pub count: u32,
    /// The vertices of a pass.
    pub per_pass: u32,
}

/// The vertex range of `call` (smallest and largest index drawn), if it is one the GPU
/// computes positions for.
pub(crate) fn span(call: &DrawCall) -> Option<(u32, u32)> {
    let setup = &call.setup;
    let (lo, hi) = match &setup.indices {
        Some(indices) => {
            let drawn = indices.get(setup.range.start as usize..setup.range.end as usize)?;
            (*drawn.iter().min()?, *drawn.iter().max()?)
        }
        None if setup.range.is_empty() => return None,
        None => (setup.range.start, setup.range.end - 1),
    };
    // Indices that skip most of their range (or reach the largest index) are shaded one by
    // one by the interpreter instead.
    let count = u64::from(hi) - u64::from(lo) + 1;
    let drawn = u64::from(setup.range.end - setup.range.start);
    (count >= u64::from(GPU_FROM) && count <= drawn && hi < u32::MAX).then_some((lo, hi))
}

/// Starts computing the positions of draw `index` (`call`) on the GPU, when it is big enough
/// to be worth it and the GPU takes the rewritten shader; submits its own commands.
pub fn start(gpu: &Gpu, index: usize, call: &DrawCall) -> Option<Job> {
    let (lo, hi) = span(call)?;
    let count = hi - lo + 1;
    let limits = gpu.device.limits();
    let most = limits
        .max_texture_dimension_2d
        .min((limits.max_buffer_size / (u64::from(WIDTH) * 16)).min(u64::from(u32::MAX)) as u32);
    let rows = count.div_ceil(WIDTH).min(most);
    let per_pass = rows * WIDTH;
    let passes = count.div_ceil(per_pass);
    let pipeline = pipeline(gpu, call, lo, rows)?;
    let label = format!("shaderlab.debug.positions.{}", call.setup.label);
    let device = &gpu.device;
    let encoded = gpu.checked(&label, || {
        let target = device.create_texture(&wgpu::TextureDescriptor {
            label: Some(&format!("{label}.target")),
            size: wgpu::Extent3d {
                width: WIDTH,
                height: rows,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba32Uint,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = target.create_view(&wgpu::TextureViewDescriptor {
            label: Some(&format!("{label}.view")),
            ..Default::default()
        });
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some(&format!("{label}.encoder")),
        });
        let mut stagings = Vec::new();
        for k in 0..passes {
            let from = lo + k * per_pass;
            let to = from.saturating_add(per_pass).min(hi + 1);
            {
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some(&format!("{label}.pass")),
                    color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                        view: &view,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                            store: wgpu::StoreOp::Store,
                        },
                    })],
                    depth_stencil_attachment: None,
                    timestamp_writes: None,
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                pass.set_pipeline(&pipeline);
                if let Some(group) = &call.bind_group {
                    pass.set_bind_group(0, group, &[]);
                }
                if !call.setup.attributes.is_empty() {
                    pass.set_vertex_buffer(0, call.vertices.slice(..));
                }
                pass.draw(from..to, 0..1);
            }
            let staging = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(&format!("{label}.staging")),
                size: u64::from(per_pass) * 16,
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            });
            encoder.copy_texture_to_buffer(
                wgpu::TexelCopyTextureInfo {
                    texture: &target,
                    mip_level: 0,
                    origin: wgpu::Origin3d::ZERO,
                    aspect: wgpu::TextureAspect::All,
                },
                wgpu::TexelCopyBufferInfo {
                    buffer: &staging,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(WIDTH * 16),
                        rows_per_image: Some(rows),
                    },
                },
                wgpu::Extent3d {
                    width: WIDTH,
                    height: rows,
                    depth_or_array_layers: 1,
                },
            );
            stagings.push(staging);
        }
        (encoder.finish(), stagings, target)
    });
    let (commands, staging, target) = encoded.ok()?;
    gpu.queue.submit([commands]);
    // The target's memory goes once the copy out of it is done.
    target.destroy();
    Some(Job {
        draw: index,
        staging,
        first: lo,
        count,
        per_pass,
    })
}

/// The positions read back into `job`'s staging buffers (`passes`, their mapped bytes in
/// order): vertex ids `first..first + count` and their clip-space positions.
pub fn read(job: &Job, passes: &[&[u8]]) -> (Vec<u32>, Vec<[f32; 4]>) {
    let ids: Vec<u32> = (job.first..job.first + job.count).collect();
    let per_pass = job.per_pass as usize;
    let clip = (0..job.count as usize)
        .map(|i| {
            let bytes = passes.get(i / per_pass).copied().unwrap_or(&[]);
            [0, 1, 2, 3].map(|k| {
                let at = (i % per_pass) * 16 + 4 * k;
                bytes
                    .get(at..at + 4)
                    .map_or(0.0, |b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            })
        })
        .collect();
    (ids, clip)
}

/// The pipelines built for the positions pass, by what they are built from (this thread's:
/// the window captures on its event loop, and an animated frame is captured again and again).
struct Built {
    device: wgpu::Device,
    vertex: std::sync::Weak<crate::shader::CompiledShader>,
    layout: wgpu::PipelineLayout,
    stride: u64,
    attributes: Vec<wgpu::VertexAttribute>,
    first: u32,
    rows: u32,
    pipeline: wgpu::RenderPipeline,
}

/// The most pipelines [`pipeline`] keeps.
const KEPT: usize = 4;

thread_local! {
    static BUILT: std::cell::RefCell<Vec<Built>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// The positions pass's pipeline for `call` with its first vertex and target rows: built
/// again only when one of those changed; `None` where the rewrite or the GPU refuses it.
fn pipeline(gpu: &Gpu, call: &DrawCall, first: u32, rows: u32) -> Option<wgpu::RenderPipeline> {
    let setup = &call.setup;
    let same = |b: &Built| {
        b.device == gpu.device
            && b.vertex
                .upgrade()
                .is_some_and(|v| std::sync::Arc::ptr_eq(&v, &setup.vertex))
            && b.layout == call.layout
            && b.stride == setup.stride
            && b.attributes == setup.attributes
            && (b.first, b.rows) == (first, rows)
    };
    if let Some(p) = BUILT.with_borrow(|built| built.iter().find(|b| same(b)).map(|b| b.pipeline.clone())) {
        return Some(p);
    }
    let vertex = module(&setup.vertex.module, first, rows)?;
    let label = format!("shaderlab.debug.positions.{}", setup.label);
    let device = &gpu.device;
    let pipeline = gpu
        .checked(&label, || {
            let vs = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(&format!("{label}.vertex")),
                source: wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(vertex)),
            });
            let fs = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(&format!("{label}.fragment")),
                source: wgpu::ShaderSource::Wgsl(FRAGMENT.into()),
            });
            let buffers = [Some(wgpu::VertexBufferLayout {
                array_stride: call.setup.stride,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &call.setup.attributes,
            })];
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(&format!("{label}.pipeline")),
                layout: Some(&call.layout),
                vertex: wgpu::VertexState {
                    module: &vs,
                    entry_point: Some("main"),
                    compilation_options: Default::default(),
                    buffers: if call.setup.attributes.is_empty() {
                        &[]
                    } else {
                        &buffers
                    },
                },
                fragment: Some(wgpu::FragmentState {
                    module: &fs,
                    entry_point: Some("main"),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::ColorTargetState {
                        format: wgpu::TextureFormat::Rgba32Uint,
                        blend: None,
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                primitive: wgpu::PrimitiveState {
                    topology: wgpu::PrimitiveTopology::PointList,
                    ..Default::default()
                },
                depth_stencil: None,
                multisample: Default::default(),
                multiview_mask: None,
                cache: None,
            })
        })
        .ok()?;
    BUILT.with_borrow_mut(|built| {
        built.retain(|b| b.vertex.strong_count() > 0);
        if built.len() >= KEPT {
            built.remove(0);
        }
        built.push(Built {
            device: gpu.device.clone(),
            vertex: std::sync::Arc::downgrade(&setup.vertex),
            layout: call.layout.clone(),
            stride: setup.stride,
            attributes: setup.attributes.clone(),
            first,
            rows,
            pipeline: pipeline.clone(),
        });
    });
    Some(pipeline)
}
