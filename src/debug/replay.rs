//! A captured frame replayed on the CPU for one pixel: every draw's vertex shader run over its
//! vertices for their positions, the primitives that cover the pixel found in draw order, the
//! depth test and `discard` deciding which fragment stays, and that fragment traced — its
//! triangle's three corners through the vertex shader, its inputs interpolated, and its 2×2
//! quad through the fragment shader.

use naga::{Binding, BuiltIn, Handle, Module, TypeInner};

use super::capture::{Captured, CapturedDraw};
use super::error::Failure;
use super::error::ReplayError;
use super::interp::{Host, Lod, Run, Trace};
use super::raster::{self, Cover, Interp};
use super::sample::{self, View};
use super::value::{self, Bits, Comp, Kind};
use crate::render::Load;
use crate::shader::CompiledShader;

type Res<T> = std::result::Result<T, ReplayError>;

fn plain(message: impl Into<String>) -> ReplayError {
    ReplayError {
        message: message.into(),
        at: None,
    }
}

fn in_shader(shader: &std::sync::Arc<CompiledShader>) -> impl Fn(Failure) -> ReplayError + '_ {
    move |f| ReplayError {
        message: f.message,
        at: Some((shader.clone(), f.span)),
    }
}

/// The vertices shaded at once when positions are computed for a whole mesh (memory bound).
pub const CHUNK: usize = 4_096;

/// A named value at one place of the interface (`v_normal` at location 1, `gl_Position`).
#[derive(Clone, Debug)]
pub struct Named {
    /// Its name in the shader.
    pub name: String,
    /// Component kinds.
    pub kinds: Vec<Kind>,
    /// Its value (numbers).
    pub value: Vec<f64>,
}

/// One corner of the covering triangle: its vertex, inputs and outputs.
#[derive(Clone, Debug)]
pub struct Corner {
    /// The vertex's index in the vertex buffer.
    pub index: u32,
    /// The vertex shader's inputs.
    pub inputs: Vec<Named>,
    /// Its outputs (`gl_Position` first).
    pub outputs: Vec<Named>,
}

/// The fragment that gives the pixel its colour, traced.
#[derive(Clone, Debug)]
pub struct Fragment {
    /// Which draw of the frame, and its program's label.
    pub draw: usize,
    /// The program's label.
    pub label: String,
    /// Which primitive of the draw.
    pub primitive: usize,
    /// Whether the draw is of points.
    pub points: bool,
    /// The three corners (one for a point).
    pub corners: Vec<Corner>,
    /// The fragment shader's inputs at the pixel (interpolated).
    pub inputs: Vec<Named>,
    /// Its depth.
    pub depth: f32,
    /// Whether its primitive faces the viewer.
    pub front_facing: bool,
    /// The fragment shader's colour output (location 0), before conversion to 8 bits.
    pub color: [f32; 4],
    /// The vertex shader's steps, per corner (values per corner in each step).
    pub vertex_steps: Trace,
    /// The fragment shader's steps (one traced lane).
    pub fragment_steps: Trace,
    /// Steps left out past the trace's limits (one per corner at a vertex step), both stages.
    pub steps_dropped: usize,
    /// Where the corners' run of the vertex shader met what GLSL leaves undefined (or the
    /// GPU's loop limiter), and what.
    pub vertex_undefined: Vec<(naga::Span, String)>,
    /// The same for the pixel's run of the fragment shader.
    pub fragment_undefined: Vec<(naga::Span, String)>,
    /// The draw's shaders.
    pub vertex: std::sync::Arc<CompiledShader>,
    /// The fragment shader.
    pub fragment: std::sync::Arc<CompiledShader>,
}

/// The result of a replay: the pixel's final colour, the clear colour behind it, and the
/// fragment that made it (none where nothing covers the pixel).
#[derive(Clone, Debug)]
pub struct Replayed {
    /// The colour stored, as 8-bit RGBA.
    pub pixel: [u8; 4],
    /// The colour before the 8-bit conversion.
    pub color: [f32; 4],
    /// The last pass's clear colour.
    pub clear: [f64; 3],
    /// The fragment that stayed, traced.
    pub fragment: Option<Fragment>,
    /// Fragments that covered the pixel (before the depth test).
    pub covering: usize,
}

/// Textures and samplers of a draw, for the interpreter.
struct DrawHost<'a> {
    module: &'a Module,
    draw: &'a CapturedDraw,
}

impl DrawHost<'_> {
    fn binding(&self, g: Handle<naga::GlobalVariable>) -> Option<u32> {
        self.module.global_variables[g].binding.as_ref().map(|b| b.binding)
    }

    fn view(&self, image: Handle<naga::GlobalVariable>) -> Result<View, String> {
        let b = self.binding(image).ok_or("a texture without a binding")?;
        let t = self
            .draw
            .textures
            .iter()
            .find(|t| t.binding == b)
            .ok_or_else(|| format!("nothing is bound to texture binding {b}"))?;
        Ok(View {
            texels: t.texels.clone(),
            base: t.levels.start,
            count: t.levels.len() as u32,
            cube: t.cube,
        })
    }
}

impl Host for DrawHost<'_> {
    fn sample(
        &self,
        image: Handle<naga::GlobalVariable>,
        sampler: Handle<naga::GlobalVariable>,
        coord: [f32; 3],
        lod: Lod,
    ) -> Result<[f32; 4], String> {
        let view = self.view(image)?;
        let b = self.binding(sampler).ok_or("a sampler without a binding")?;
        let desc = self
            .draw
            .samplers
            .iter()
            .find(|(s, _)| *s == b)
            .map(|(_, d)| *d)
            .ok_or_else(|| format!("nothing is bound to sampler binding {b}"))?;
        Ok(sample::sample(&view, &desc, coord, lod))
    }
    fn fetch(&self, image: Handle<naga::GlobalVariable>, coord: [i32; 3], level: i32) -> Result<[f32; 4], String> {
        Ok(self.view(image)?.fetch(coord, level))
    }
    fn size(&self, image: Handle<naga::GlobalVariable>, level: i32) -> Result<[u32; 2], String> {
        Ok(self.view(image)?.size(level))
    }
    fn buffer(&self, global: Handle<naga::GlobalVariable>) -> Option<std::sync::Arc<Vec<u8>>> {
        let b = self.binding(global)?;
        self.draw
            .uniforms
            .iter()
            .find(|(k, _)| *k == b)
            .map(|(_, bytes)| bytes.clone())
    }
}

/// The entry point of `stage` in `shader`.
fn entry(shader: &CompiledShader, stage: naga::ShaderStage) -> Res<usize> {
    shader
        .module
        .entry_points
        .iter()
        .position(|e| e.stage == stage)
        .ok_or_else(|| plain(format!("{} has no {stage:?} entry point", shader.path)))
}

/// The uniform blocks' values from the draw's buffers.
fn uniforms(module: &Module, draw: &CapturedDraw) -> Vec<(Handle<naga::GlobalVariable>, Vec<Comp>)> {
    let mut out = Vec::new();
    for (h, var) in module.global_variables.iter() {
        if var.space != naga::AddressSpace::Uniform {
            continue;
        }
        let Some(b) = &var.binding else { continue };
        let Some((_, bytes)) = draw.uniforms.iter().find(|(k, _)| *k == b.binding) else {
            continue;
        };
        let mut comps = Vec::new();
        if value::read_bytes(module, &module.types[var.ty].inner, bytes, 0, &mut comps).is_some() {
            out.push((h, comps));
        }
    }
    out
}

/// One slot of an entry point's interface: its binding, name, type and where its components
/// lie in the argument (or result) they belong to.
struct Slot {
    binding: Binding,
    name: String,
    /// Argument index (inputs) — 0 for the result.
    arg: usize,
    offset: usize,
    len: usize,
}

fn slots_of(
    module: &Module,
    ty: Handle<naga::Type>,
    binding: Option<&Binding>,
    name: Option<&str>,
    arg: usize,
    out: &mut Vec<Slot>,
) {
    let inner = &module.types[ty].inner;
    match (binding, inner) {
        (Some(b), _) => out.push(Slot {
            binding: b.clone(),
            name: name.unwrap_or("?").to_owned(),
            arg,
            offset: 0,
            len: value::count(module, inner),
        }),
        (None, TypeInner::Struct { members, .. }) => {
            let mut at = 0;
            for m in members {
                let n = value::count(module, &module.types[m.ty].inner);
                if let Some(b) = &m.binding {
                    out.push(Slot {
                        binding: b.clone(),
                        name: m.name.clone().unwrap_or_else(|| "?".into()),
                        arg,
                        offset: at,
                        len: n,
                    });
                }
                at += n;
            }
        }
        _ => {}
    }
}

fn input_slots(module: &Module, ep: usize) -> Vec<Slot> {
    let f = &module.entry_points[ep].function;
    let mut out = Vec::new();
    for (i, a) in f.arguments.iter().enumerate() {
        slots_of(module, a.ty, a.binding.as_ref(), a.name.as_deref(), i, &mut out);
    }
    out
}

fn output_slots(module: &Module, ep: usize) -> Vec<Slot> {
    let f = &module.entry_points[ep].function;
    let mut out = Vec::new();
    if let Some(r) = &f.result {
        slots_of(module, r.ty, r.binding.as_ref(), Some("result"), 0, &mut out);
    }
    out
}

fn builtin_name(b: BuiltIn) -> String {
    match b {
        BuiltIn::Position { .. } => "gl_Position".into(),
        BuiltIn::VertexIndex => "gl_VertexIndex".into(),
        BuiltIn::InstanceIndex => "gl_InstanceIndex".into(),
        BuiltIn::FrontFacing => "gl_FrontFacing".into(),
        BuiltIn::FragDepth => "gl_FragDepth".into(),
        BuiltIn::PointSize => "gl_PointSize".into(),
        other => format!("{other:?}"),
    }
}

fn slot_name(shader: &CompiledShader, slot: &Slot) -> String {
    match &slot.binding {
        Binding::BuiltIn(b) => builtin_name(*b),
        Binding::Location { .. } => super::user_name(shader, &slot.name),
    }
}

/// Assembles an entry point's arguments from per-slot values.
fn arguments(module: &Module, ep: usize, slots: &[Slot], values: &[Vec<Comp>]) -> Res<Vec<Vec<Comp>>> {
    let f = &module.entry_points[ep].function;
    let mut args: Vec<Vec<Comp>> = f
        .arguments
        .iter()
        .map(|a| value::zero(module, &module.types[a.ty].inner).unwrap_or_default())
        .collect();
    for (slot, v) in slots.iter().zip(values) {
        let arg = &mut args[slot.arg];
        for (k, c) in v.iter().enumerate() {
            if let Some(dst) = arg.get_mut(slot.offset + k) {
                *dst = c.clone();
            }
        }
    }
    Ok(args)
}

/// Reads attribute `format` of vertex `ids` from `bytes`.
fn attribute(bytes: &[u8], stride: u64, offset: u64, format: wgpu::VertexFormat, ids: &[u32]) -> Res<Vec<Comp>> {
    use wgpu::VertexFormat as F;
    let (kind, n) = match format {
        F::Float32 => (Kind::F32, 1),
        F::Float32x2 => (Kind::F32, 2),
        F::Float32x3 => (Kind::F32, 3),
        F::Float32x4 => (Kind::F32, 4),
        F::Sint32 => (Kind::I32, 1),
        F::Sint32x2 => (Kind::I32, 2),
        F::Sint32x3 => (Kind::I32, 3),
        F::Sint32x4 => (Kind::I32, 4),
        F::Uint32 => (Kind::U32, 1),
        F::Uint32x2 => (Kind::U32, 2),
        F::Uint32x3 => (Kind::U32, 3),
        F::Uint32x4 => (Kind::U32, 4),
        other => return Err(plain(format!("the debugger does not read {other:?} vertex attributes"))),
    };
    Ok((0..n)
        .map(|k| {
            let bits = ids
                .iter()
                .map(|&id| {
                    let at = (u64::from(id) * stride + offset) as usize + 4 * k;
                    bytes
                        .get(at..at + 4)
                        .map_or(0, |b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
                })
                .collect();
            Comp::new(kind, Bits::Each(bits))
        })
        .collect())
}

/// The vertex shader of `draw` run over vertices `ids`: per slot, the inputs; the outputs.
struct VertexRun {
    inputs: Vec<Vec<Comp>>,
    outputs: Vec<Vec<Comp>>,
    trace: Trace,
    undefined: Vec<(naga::Span, String)>,
}

fn run_vertices(draw: &CapturedDraw, ids: &[u32], traced: bool) -> Res<VertexRun> {
    let shader = &draw.vertex;
    let module = &shader.module;
    let ep = entry(shader, naga::ShaderStage::Vertex)?;
    let slots = input_slots(module, ep);
    let mut inputs = Vec::with_capacity(slots.len());
    for slot in &slots {
        inputs.push(match &slot.binding {
            Binding::Location { location, .. } => {
                let a = draw
                    .attributes
                    .iter()
                    .find(|a| a.shader_location == *location)
                    .ok_or_else(|| plain(format!("no vertex attribute feeds location {location}")))?;
                attribute(&draw.vertices, draw.stride, a.offset, a.format, ids)?
            }
            Binding::BuiltIn(BuiltIn::VertexIndex) => vec![Comp::new(Kind::U32, Bits::Each(ids.to_vec()))],
            Binding::BuiltIn(BuiltIn::InstanceIndex) => vec![Comp::new(Kind::U32, Bits::One(0))],
            Binding::BuiltIn(b) => return Err(plain(format!("the debugger does not feed the vertex input {b:?}"))),
        });
    }
    let args = arguments(module, ep, &slots, &inputs)?;
    let host = DrawHost { module, draw };
    let traced_lanes = if traced { (0..ids.len()).collect() } else { Vec::new() };
    let mut run = Run::new(
        module,
        &shader.info,
        ids.len(),
        false,
        &host,
        &uniforms(module, draw),
        traced_lanes,
    )
    .map_err(in_shader(shader))?;
    let result = run.entry(ep, args).map_err(in_shader(shader))?;
    let outputs = output_slots(module, ep)
        .iter()
        .map(|s| {
            result
                .get(s.offset..s.offset + s.len)
                .map(<[Comp]>::to_vec)
                .unwrap_or_default()
        })
        .collect();
    Ok(VertexRun {
        inputs,
        outputs,
        undefined: std::mem::take(&mut run.undefined),
        trace: run.take_trace(),
    })
}

/// Clip-space positions of vertices `ids`.
fn positions(draw: &CapturedDraw, ids: &[u32]) -> Res<Vec<[f32; 4]>> {
    let module = &draw.vertex.module;
    let ep = entry(&draw.vertex, naga::ShaderStage::Vertex)?;
    let slots = output_slots(module, ep);
    let at = slots
        .iter()
        .position(|s| matches!(s.binding, Binding::BuiltIn(BuiltIn::Position { .. })))
        .ok_or_else(|| plain(format!("{} writes no gl_Position", draw.vertex.path)))?;
    let mut out = Vec::with_capacity(ids.len());
    for chunk in ids.chunks(CHUNK) {
        let run = run_vertices(draw, chunk, false)?;
        let p = &run.outputs[at];
        for lane in 0..chunk.len() {
            out.push([0, 1, 2, 3].map(|k| p.get(k).map_or(0.0, |c| c.f(lane))));
        }
    }
    Ok(out)
}

/// A fragment covering the pixel, found by the rasteriser.
struct Candidate {
    draw: usize,
    primitive: usize,
    /// Vertex ids of its corners (provoking first).
    ids: [u32; 3],
    cover: Cover,
    points: bool,
}

/// The vertex ids a draw reads, in the order it draws them.
fn sequence(draw: &CapturedDraw) -> Res<std::borrow::Cow<'_, [u32]>> {
    Ok(match &draw.indices {
        Some(indices) => std::borrow::Cow::Borrowed(
            indices
                .get(draw.range.start as usize..draw.range.end as usize)
                .ok_or_else(|| plain("a draw past the end of its index buffer"))?,
        ),
        None => std::borrow::Cow::Owned(draw.range.clone().collect()),
    })
}

/// The vertices a draw shades: their ids, sorted, each once.
pub fn drawn_vertices(draw: &CapturedDraw) -> Res<Vec<u32>> {
    let mut ids = sequence(draw)?.into_owned();
    ids.sort_unstable();
    ids.dedup();
    Ok(ids)
}

/// The vertex shader of `draw` run over vertices `ids` (at most a few thousand at once): per
/// vertex, every output's components as numbers, the outputs in the order the shader declares
/// them. Two frames' draws are compared vertex by vertex with it ([`super::diff`]).
pub fn vertex_outputs(draw: &CapturedDraw, ids: &[u32]) -> Res<Vec<Vec<f64>>> {
    let run = run_vertices(draw, ids, false)?;
    Ok((0..ids.len())
        .map(|lane| run.outputs.iter().flat_map(|slot| value::numbers(slot, lane)).collect())
        .collect())
}

/// The vertex shader of `draw` traced for vertex `id` alone.
pub fn trace_vertex(draw: &CapturedDraw, id: u32) -> Res<Trace> {
    Ok(run_vertices(draw, &[id], true)?.trace)
}

fn candidates(draw_index: usize, draw: &CapturedDraw, x: u32, y: u32) -> Res<Vec<Candidate>> {
    if !raster::scissored(draw.scissor, x, y) {
        return Ok(Vec::new());
    }
    let vp = draw.viewport;
    let sequence = sequence(draw)?;
    let prims = raster::primitives(draw.state.topology, sequence.len())
        .ok_or_else(|| plain(format!("the debugger does not rasterise {:?}", draw.state.topology)))?;
    let shaded = draw
        .positions
        .get_or_init(|| {
            // Shade each distinct vertex once.
            let mut ids: Vec<u32> = sequence.to_vec();
            ids.sort_unstable();
            ids.dedup();
            let clip = positions(draw, &ids)?;
            Ok(std::sync::Arc::new((ids, clip)))
        })
        .clone()?;
    let (ids, clip) = (&shaded.0, &shaded.1);
    // Ids without gaps (the GPU's positions, most meshes) index the positions directly.
    let first = ids.first().copied().unwrap_or(0);
    let dense = ids.last().is_some_and(|&last| (last - first) as usize + 1 == ids.len());
    let pos = |id: u32| {
        if dense {
            clip[(id - first) as usize]
        } else {
            clip[ids.binary_search(&id).expect("shaded above")]
        }
    };
    let points = draw.state.topology == wgpu::PrimitiveTopology::PointList;
    let mut out = Vec::new();
    for (p, prim) in prims.iter().enumerate() {
        let vid = prim.map(|i| sequence[i]);
        let cover = if points {
            raster::point(pos(vid[0]), vp, x, y)
        } else {
            raster::triangle(vid.map(pos), vp, x, y, draw.state.front_face, draw.cull)
        };
        if let Some(cover) = cover {
            out.push(Candidate {
                draw: draw_index,
                primitive: p,
                ids: vid,
                cover,
                points,
            });
        }
    }
    Ok(out)
}

fn writes_depth_or_discards(shader: &CompiledShader) -> bool {
    fn kills(block: &naga::Block) -> bool {
        block.iter().any(|s| match s {
            naga::Statement::Kill => true,
            naga::Statement::Block(b) => kills(b),
            naga::Statement::If { accept, reject, .. } => kills(accept) || kills(reject),
            naga::Statement::Switch { cases, .. } => cases.iter().any(|c| kills(&c.body)),
            naga::Statement::Loop { body, continuing, .. } => kills(body) || kills(continuing),
            _ => false,
        })
    }
    let module = &shader.module;
    let any_kill = module.functions.iter().any(|(_, f)| kills(&f.body))
        || module.entry_points.iter().any(|e| kills(&e.function.body));
    let depth = (0..module.entry_points.len()).any(|ep| {
        module.entry_points[ep].stage == naga::ShaderStage::Fragment
            && output_slots(module, ep)
                .iter()
                .any(|s| matches!(s.binding, Binding::BuiltIn(BuiltIn::FragDepth)))
    });
    any_kill || depth
}

/// What the fragment shader gave for a candidate: colour, depth, kept (not discarded).
struct Shaded {
    color: [f32; 4],
    depth: f32,
    kept: bool,
    fragment: Fragment,
}

fn shade(captured: &Captured, c: &Candidate) -> Res<Shaded> {
    let draw = &captured.draws[c.draw];
    let corners_ids: Vec<u32> = if c.points { vec![c.ids[0]] } else { c.ids.to_vec() };
    let vrun = run_vertices(draw, &corners_ids, true)?;
    let vmodule = &draw.vertex.module;
    let vep = entry(&draw.vertex, naga::ShaderStage::Vertex)?;
    let vin = input_slots(vmodule, vep);
    let vout = output_slots(vmodule, vep);
    let named = |slots: &[Slot], values: &[Vec<Comp>], lane: usize| -> Vec<Named> {
        slots
            .iter()
            .zip(values)
            .map(|(s, v)| Named {
                name: slot_name(&draw.vertex, s),
                kinds: v.iter().map(|c| c.kind).collect(),
                value: value::numbers(v, lane),
            })
            .collect()
    };
    let corners: Vec<Corner> = corners_ids
        .iter()
        .enumerate()
        .map(|(lane, &index)| Corner {
            index,
            inputs: named(&vin, &vrun.inputs, lane),
            outputs: named(&vout, &vrun.outputs, lane),
        })
        .collect();
    // The fragment shader's inputs, interpolated for the four pixels of the quad.
    let fshader = &draw.fragment;
    let fmodule = &fshader.module;
    let fep = entry(fshader, naga::ShaderStage::Fragment)?;
    let fin = input_slots(fmodule, fep);
    let corner = |lane: usize| if c.points { 0 } else { lane };
    let mut fvalues = Vec::with_capacity(fin.len());
    for slot in &fin {
        fvalues.push(match &slot.binding {
            Binding::Location {
                location,
                interpolation,
                ..
            } => {
                let Some(k) = vout
                    .iter()
                    .position(|o| matches!(o.binding, Binding::Location { location: l, .. } if l == *location))
                else {
                    return Err(plain(format!(
                        "{} reads location {location}, which {} does not write",
                        fshader.path, draw.vertex.path
                    )));
                };
                let v = &vrun.outputs[k];
                v.iter()
                    .map(|comp| {
                        let at = |i: usize| comp.bits.at(corner(i).min(comp.bits.len() - 1));
                        let flat = matches!(interpolation, Some(naga::Interpolation::Flat)) || comp.kind != Kind::F32;
                        if flat {
                            return Comp::new(comp.kind, Bits::One(at(0)));
                        }
                        let mode = if matches!(interpolation, Some(naga::Interpolation::Linear)) {
                            Interp::Linear
                        } else {
                            Interp::Perspective
                        };
                        let v = [0, 1, 2].map(|i| f32::from_bits(at(i)));
                        Comp::f32s(c.cover.interpolate(v, mode))
                    })
                    .collect()
            }
            Binding::BuiltIn(BuiltIn::Position { .. }) => {
                let p = c.cover.pixels;
                vec![
                    Comp::f32s(p.map(|(x, _)| x as f32 + 0.5)),
                    Comp::f32s(p.map(|(_, y)| y as f32 + 0.5)),
                    Comp::f32s(c.cover.depth),
                    Comp::f32s(c.cover.inv_w),
                ]
            }
            Binding::BuiltIn(BuiltIn::FrontFacing) => vec![Comp::new(Kind::Bool, Bits::One(u32::from(c.cover.front)))],
            Binding::BuiltIn(b) => return Err(plain(format!("the debugger does not feed the fragment input {b:?}"))),
        });
    }
    let args = arguments(fmodule, fep, &fin, &fvalues)?;
    let host = DrawHost { module: fmodule, draw };
    let mut run = Run::new(
        fmodule,
        &fshader.info,
        4,
        true,
        &host,
        &uniforms(fmodule, draw),
        vec![c.cover.lane],
    )
    .map_err(in_shader(fshader))?;
    let result = run.entry(fep, args).map_err(in_shader(fshader))?;
    let lane = c.cover.lane;
    let fout = output_slots(fmodule, fep);
    let mut color = [0.0f32; 4];
    let mut depth = c.cover.depth[lane];
    for s in &fout {
        match s.binding {
            Binding::Location { location: 0, .. } => {
                for k in 0..s.len.min(4) {
                    color[k] = result[s.offset + k].f(lane);
                }
                if s.len < 4 {
                    color[3] = 1.0;
                }
            }
            Binding::BuiltIn(BuiltIn::FragDepth) => depth = result[s.offset].f(lane),
            _ => {}
        }
    }
    let inputs = fin
        .iter()
        .zip(&fvalues)
        .map(|(s, v)| Named {
            name: slot_name(fshader, s),
            kinds: v.iter().map(|c| c.kind).collect(),
            value: value::numbers(v, lane),
        })
        .collect();
    let kept = !run.killed[lane];
    let fragment_steps = run.take_trace();
    Ok(Shaded {
        color,
        depth,
        kept,
        fragment: Fragment {
            draw: c.draw,
            label: draw.label.clone(),
            primitive: c.primitive,
            points: c.points,
            corners,
            inputs,
            depth,
            front_facing: c.cover.front,
            color,
            steps_dropped: vrun.trace.dropped_total() + fragment_steps.dropped_total(),
            vertex_steps: vrun.trace,
            fragment_steps,
            vertex_undefined: vrun.undefined,
            fragment_undefined: std::mem::take(&mut run.undefined),
            vertex: draw.vertex.clone(),
            fragment: fshader.clone(),
        },
    })
}

/// How an 8-bit UNORM target stores a colour channel.
pub fn to_unorm8(c: f32) -> u8 {
    if c.is_nan() {
        return 0;
    }
    // clamp(roundeven(x · 255)): the multiply rounded first, then half to even.
    (c.clamp(0.0, 1.0) * 255.0).round_ties_even() as u8
}

/// Replays `captured` for pixel (x, y) of the last pass's target.
pub fn replay(captured: &Captured, x: u32, y: u32) -> Res<Replayed> {
    let Some(&(_, width, height)) = captured.passes.last() else {
        return Err(plain("the lab drew nothing (no render pass)"));
    };
    if x >= width || y >= height {
        return Err(plain(format!(
            "pixel {x},{y} is outside the picture ({width}x{height}: x 0..{}, y 0..{})",
            width - 1,
            height - 1
        )));
    }
    let mut clear = [0.0f64; 3];
    let mut depth = 1.0f32;
    let mut top = Top::Clear([0.0, 0.0, 0.0, 1.0]);
    let mut covering = 0;
    let mut pass = usize::MAX;
    for (i, draw) in captured.draws.iter().enumerate() {
        if draw.pass != pass {
            pass = draw.pass;
            if let Some((Load::Clear(c), _, _)) = captured.passes.get(pass) {
                clear = *c;
                top = Top::Clear([c[0] as f32, c[1] as f32, c[2] as f32, 1.0]);
                depth = 1.0;
            }
        }
        // Without discard, a depth output or blending, the depth test alone decides which
        // fragment stays: only that one is shaded, at the end.
        let decides = writes_depth_or_discards(&draw.fragment) || draw.state.blend.is_some();
        for cand in candidates(i, draw, x, y)? {
            covering += 1;
            let z = cand.cover.depth[cand.cover.lane];
            if !decides {
                if draw.state.depth_test && !depth_passes(z, depth) {
                    continue;
                }
                if draw.state.depth_test {
                    depth = z;
                }
                top = Top::Lazy(Box::new(cand));
                continue;
            }
            let shaded = shade(captured, &cand)?;
            if !shaded.kept || (draw.state.depth_test && !depth_passes(shaded.depth, depth)) {
                continue;
            }
            if draw.state.depth_test {
                depth = shaded.depth;
            }
            let color = match draw.state.blend {
                None => shaded.color,
                Some(state) => {
                    // The destination is what the target stores: 8 bits a channel.
                    let (stored, _, _) = resolve(captured, top)?;
                    blend(state, shaded.color, stored.map(|v| f32::from(v) / 255.0))
                }
            };
            top = Top::Done {
                color,
                fragment: Box::new(shaded.fragment),
            };
        }
    }
    let (pixel, color, fragment) = resolve(captured, top)?;
    Ok(Replayed {
        pixel,
        color,
        clear,
        fragment,
        covering,
    })
}

/// What a pixel holds so far: its clear colour, the fragment that stays but has not been
/// shaded yet, or a colour written.
enum Top {
    Clear([f32; 4]),
    Lazy(Box<Candidate>),
    Done { color: [f32; 4], fragment: Box<Fragment> },
}

/// `GL_LESS` as the rasteriser compares (unordered: a NaN passes).
fn depth_passes(z: f32, stored: f32) -> bool {
    z < stored || z.is_nan() || stored.is_nan()
}

/// The stored bytes, the colour and the fragment that made it.
fn resolve(captured: &Captured, top: Top) -> Res<([u8; 4], [f32; 4], Option<Fragment>)> {
    Ok(match top {
        Top::Clear(c) => (c.map(to_unorm8), c, None),
        Top::Lazy(cand) => {
            let shaded = shade(captured, &cand)?;
            (shaded.color.map(to_unorm8), shaded.color, Some(shaded.fragment))
        }
        Top::Done { color, fragment } => (color.map(to_unorm8), color, Some(*fragment)),
    })
}

fn blend(b: wgpu::BlendState, src: [f32; 4], dst: [f32; 4]) -> [f32; 4] {
    let factor = |f: wgpu::BlendFactor, k: usize| -> f32 {
        use wgpu::BlendFactor as F;
        match f {
            F::Zero => 0.0,
            F::One => 1.0,
            F::Src => src[k],
            F::OneMinusSrc => 1.0 - src[k],
            F::SrcAlpha => src[3],
            F::OneMinusSrcAlpha => 1.0 - src[3],
            F::Dst => dst[k],
            F::OneMinusDst => 1.0 - dst[k],
            F::DstAlpha => dst[3],
            F::OneMinusDstAlpha => 1.0 - dst[3],
            _ => 1.0,
        }
    };
    let op = |c: wgpu::BlendComponent, k: usize| -> f32 {
        let (s, d) = (src[k] * factor(c.src_factor, k), dst[k] * factor(c.dst_factor, k));
        match c.operation {
            wgpu::BlendOperation::Add => s + d,
            wgpu::BlendOperation::Subtract => s - d,
            wgpu::BlendOperation::ReverseSubtract => d - s,
            wgpu::BlendOperation::Min => src[k].min(dst[k]),
            wgpu::BlendOperation::Max => src[k].max(dst[k]),
        }
    };
    [op(b.color, 0), op(b.color, 1), op(b.color, 2), op(b.alpha, 3)].map(|v| v.clamp(0.0, 1.0))
}
