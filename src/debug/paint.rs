//! A line or cost view's picture made on the GPU from the targets a
//! [`super::view::ViewDrawer`] drew, so that a window or a page shows a view without bringing
//! its values back: the colours are [`super::picture::values`]' and [`super::picture::cost`]'
//! (the same maps, stops, range rule, NaN, infinity, not-run and background colours), computed
//! in `f32` where those use `f64` (a channel may differ by 1 of 255).
//!
//! The range comes from the frame itself: fragment passes fold the value and info targets in
//! blocks of [`BLOCK`] × [`BLOCK`] pixels into two `Rgba32Float` targets (lowest and highest
//! finite component, the largest count, and the counts of background, NaN, +∞, −∞ and not-run
//! pixels), again and again down to one pixel, which is copied on the GPU into the colouring
//! pass's parameters. Fragment passes rather than a compute pass, because WebGL2 has none. Only those 32 bytes come back to the
//! CPU, later, for the legend strip's words ([`Painter::legend`]); the strip is written into
//! the picture's bottom rows when they arrive, so its numbers may be a frame or two behind a
//! turning object's colours.

use std::sync::atomic::{AtomicU8, Ordering};
use std::sync::Arc;

use image::RgbaImage;

use super::instrument::{COST_SHIFT, RAN_BIT};
use super::picture::{self, Legend, DIVERGING, INFINITE_COLOUR, LEGEND_HEIGHT, NAN_COLOUR, NOT_RUN, VIRIDIS};
use super::view::Drawn;
use crate::error::{Error, Result};
use crate::gpu::targets::texture_and_view;
use crate::gpu::Gpu;

/// The side of the square of pixels each folding pass makes one pixel of.
pub const BLOCK: u32 = 16;

/// The format of the folding passes' targets.
const STATS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The picture's format: bytes as [`super::picture`] writes them.
pub const PICTURE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// The legend strip's grey, as [`super::picture`] draws it.
const STRIP_GREY: f64 = picture::LEGEND_GREY as f64 / 255.0;

/// What the folding passes found over a frame, as the colouring pass reads it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stats {
    /// The lowest finite shown component where the line ran (`f32::MAX` where none).
    pub lo: f32,
    /// The highest (`-f32::MAX` where none).
    pub hi: f32,
    /// The largest step count where a fragment ran.
    pub max_cost: f32,
    /// Pixels where no fragment ran.
    pub background: f32,
    /// Pixels with a NaN.
    pub nan: f32,
    /// Pixels with +∞ (and no NaN).
    pub pos_inf: f32,
    /// Pixels with −∞ (and no NaN or +∞).
    pub neg_inf: f32,
    /// Pixels where a fragment ran and the line did not.
    pub not_run: f32,
}

impl Stats {
    /// The legend of a line view of `components` components with these findings.
    pub fn legend(&self, components: u32) -> Legend {
        let comps = (components as usize).clamp(1, 4);
        Legend {
            nan: self.nan as usize,
            pos_inf: self.pos_inf as usize,
            neg_inf: self.neg_inf as usize,
            not_run: self.not_run as usize,
            background: self.background as usize,
            ..Legend::new(comps, f64::from(self.lo), f64::from(self.hi))
        }
    }
}

/// The shaders: a full-screen triangle, the first folding pass (value and info targets in),
/// the next ones (the previous pass's two targets in), and the colouring pass.
fn shader_source() -> String {
    let colour = |name: &str, c: [u8; 3]| format!("const {name} = vec3<f32>({}.0, {}.0, {}.0);\n", c[0], c[1], c[2]);
    let mut source = String::new();
    source.push_str(&colour("NAN_COLOUR", NAN_COLOUR));
    source.push_str(&colour("INFINITE_COLOUR", INFINITE_COLOUR));
    source.push_str(&colour("NOT_RUN_0", NOT_RUN[0]));
    source.push_str(&colour("NOT_RUN_1", NOT_RUN[1]));
    source.push_str(&format!(
        "const RAN_BIT: u32 = {RAN_BIT}u;\nconst COST_SHIFT: u32 = {COST_SHIFT}u;\nconst BLOCK: u32 = {BLOCK}u;\n"
    ));
    source.push_str(crate::gpu::targets::FULL_SCREEN_WGSL);
    source.push_str(SHADER);
    source
}

/// Where the shader's `Params` holds the last folding pass's two texels.
const FOUND_AT: u64 = 16;

/// The maps' stops as the shader's `Params` holds them after its four words and the two
/// texels found, each as a `vec4`.
fn tables() -> Vec<f32> {
    VIRIDIS
        .iter()
        .chain(DIVERGING.iter())
        .flat_map(|stop| [f32::from(stop[0]), f32::from(stop[1]), f32::from(stop[2]), 0.0])
        .collect()
}

const SHADER: &str = r"
// f32::MAX, written exactly (a decimal past it is an error in some WGSL compilers).
const BIG: f32 = 0x1.fffffep+127f;

struct Params {
    // 0: a line's value; 1: the cost.
    mode: u32,
    components: u32,
    _a: u32,
    _b: u32,
    // The last folding pass's two texels, copied here on the GPU before the colouring pass.
    found_a: vec4<f32>,
    found_b: vec4<f32>,
    // viridis's nine stops, then the diverging map's five.
    stops: array<vec4<f32>, 14>,
}

struct Folded {
    // lowest, highest, largest count, background
    @location(0) a: vec4<f32>,
    // NaN, +inf, -inf, not run
    @location(1) b: vec4<f32>,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var values: texture_2d<f32>;
@group(0) @binding(2) var info: texture_2d<u32>;
@group(0) @binding(3) var folded_a: texture_2d<f32>;
@group(0) @binding(4) var folded_b: texture_2d<f32>;

// 0: finite; 1: a NaN; 2: +inf (no NaN); 3: -inf (no NaN or +inf), over the first n
// components. By the bits: WGSL lets a compiler assume no float is NaN or infinite.
fn kind(v: vec4<f32>, n: u32) -> u32 {
    let bits = bitcast<vec4<u32>>(v);
    let used = vec4<u32>(0u, 1u, 2u, 3u) < vec4<u32>(n);
    let odd = ((bits & vec4<u32>(0x7f800000u)) == vec4<u32>(0x7f800000u)) & used;
    let nan = odd & ((bits & vec4<u32>(0x007fffffu)) != vec4<u32>(0u));
    let negative = (bits & vec4<u32>(0x80000000u)) != vec4<u32>(0u);
    let pos = odd & !nan & !negative;
    let neg = odd & !nan & negative;
    return select(select(select(0u, 3u, any(neg)), 2u, any(pos)), 1u, any(nan));
}

// The lowest and highest of the first n (1 to 3) components.
fn low_high(v: vec4<f32>, n: u32) -> vec2<f32> {
    let y = select(v.x, v.y, n > 1u);
    let z = select(y, v.z, n > 2u);
    return vec2<f32>(min(min(v.x, y), z), max(max(v.x, y), z));
}

@fragment
fn fold_value(@builtin(position) at: vec4<f32>) -> Folded {
    let size = textureDimensions(info);
    let o = vec2<u32>(at.xy) * BLOCK;
    let end = min(o + vec2<u32>(BLOCK), size);
    let n = clamp(params.components, 1u, 4u);
    let shown = min(n, 3u);
    var a = vec4<f32>(BIG, -BIG, 0.0, 0.0);
    var b = vec4<f32>(0.0);
    for (var y = o.y; y < end.y; y++) {
        for (var x = o.x; x < end.x; x++) {
            let p = vec2<i32>(i32(x), i32(y));
            let word = textureLoad(info, p, 0).r;
            let cost = word >> COST_SHIFT;
            let ran = cost != 0u && (word & RAN_BIT) != 0u;
            var k = 4u;
            if (ran) {
                let v = textureLoad(values, p, 0);
                k = kind(v, n);
                if (k == 0u) {
                    let lh = low_high(v, shown);
                    a.x = min(a.x, lh.x);
                    a.y = max(a.y, lh.y);
                }
            }
            a.z = max(a.z, f32(cost));
            a.w += select(0.0, 1.0, cost == 0u);
            b += select(vec4<f32>(0.0), vec4<f32>(1.0, 0.0, 0.0, 0.0), k == 1u)
                + select(vec4<f32>(0.0), vec4<f32>(0.0, 1.0, 0.0, 0.0), k == 2u)
                + select(vec4<f32>(0.0), vec4<f32>(0.0, 0.0, 1.0, 0.0), k == 3u)
                + select(vec4<f32>(0.0), vec4<f32>(0.0, 0.0, 0.0, 1.0), cost != 0u && !ran);
        }
    }
    var out: Folded;
    out.a = a;
    out.b = b;
    return out;
}

@fragment
fn fold_cost(@builtin(position) at: vec4<f32>) -> Folded {
    let size = textureDimensions(info);
    let o = vec2<u32>(at.xy) * BLOCK;
    let end = min(o + vec2<u32>(BLOCK), size);
    var top = 0u;
    var background = 0.0;
    for (var y = o.y; y < end.y; y++) {
        for (var x = o.x; x < end.x; x++) {
            let cost = textureLoad(info, vec2<i32>(i32(x), i32(y)), 0).r >> COST_SHIFT;
            top = max(top, cost);
            background += select(0.0, 1.0, cost == 0u);
        }
    }
    var out: Folded;
    out.a = vec4<f32>(BIG, -BIG, f32(top), background);
    out.b = vec4<f32>(0.0);
    return out;
}

@fragment
fn fold_next(@builtin(position) at: vec4<f32>) -> Folded {
    let size = textureDimensions(folded_a);
    let o = vec2<u32>(at.xy) * BLOCK;
    let end = min(o + vec2<u32>(BLOCK), size);
    var a = vec4<f32>(BIG, -BIG, 0.0, 0.0);
    var b = vec4<f32>(0.0);
    for (var y = o.y; y < end.y; y++) {
        for (var x = o.x; x < end.x; x++) {
            let p = vec2<i32>(i32(x), i32(y));
            let fa = textureLoad(folded_a, p, 0);
            a = vec4<f32>(min(a.x, fa.x), max(a.y, fa.y), max(a.z, fa.z), a.w + fa.w);
            b += textureLoad(folded_b, p, 0);
        }
    }
    var out: Folded;
    out.a = a;
    out.b = b;
    return out;
}

// The map whose stops begin at `base` (of `segments` + 1) at t in 0..1, rounded as the
// library rounds.
fn ramp(t: f32, base: u32, segments: u32) -> vec3<f32> {
    let f = clamp(t, 0.0, 1.0) * f32(segments);
    let k = min(u32(floor(f)), segments - 1u);
    let u = f - f32(k);
    let a = params.stops[base + k].xyz;
    return floor(a + (params.stops[base + k + 1u].xyz - a) * u + 0.5);
}

// round(t * 255) for t in 0..1 as the library rounds it in f64: the f32 estimate is within
// one of it, and whether t * 255 reaches the halfway points around it is settled exactly as
// t * 256 - (e ± 0.5) against t (t * 256 is exact, and near a halfway point the subtraction
// is of two numbers within a factor of two of each other, so exact too).
fn bytes(t: vec3<f32>) -> vec3<f32> {
    let e = floor(t * 255.0 + 0.5);
    let t256 = t * 256.0;
    let down = (e > vec3<f32>(0.0)) & (t256 - (e - 0.5) < t);
    let up = (e < vec3<f32>(255.0)) & (t256 - (e + 0.5) >= t);
    return e - select(vec3<f32>(0.0), vec3<f32>(1.0), down) + select(vec3<f32>(0.0), vec3<f32>(1.0), up);
}

fn checker(p: vec2<i32>) -> vec3<f32> {
    return select(NOT_RUN_1, NOT_RUN_0, ((u32(p.x) / 4u + u32(p.y) / 4u) % 2u) == 0u);
}

fn out(c: vec3<f32>) -> vec4<f32> {
    return vec4<f32>(c / 255.0, 1.0);
}

@fragment
fn colour_cost(@builtin(position) at: vec4<f32>) -> @location(0) vec4<f32> {
    let cost = textureLoad(info, vec2<i32>(at.xy), 0).r >> COST_SHIFT;
    let c = ramp(f32(cost) / max(params.found_a.z, 1.0), 0u, 8u);
    return out(select(c, vec3<f32>(0.0), cost == 0u));
}

// What a pixel that is not a finite value shows, if it is one: (colour, 1) or (_, 0).
fn unless_finite(p: vec2<i32>, word: u32, v: vec4<f32>, n: u32) -> vec4<f32> {
    if ((word >> COST_SHIFT) == 0u) {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    if ((word & RAN_BIT) == 0u) {
        return vec4<f32>(checker(p), 1.0);
    }
    let k = kind(v, n);
    if (k == 1u) {
        return vec4<f32>(NAN_COLOUR, 1.0);
    }
    if (k != 0u) {
        return vec4<f32>(INFINITE_COLOUR, 1.0);
    }
    return vec4<f32>(0.0);
}

// The range the library states: lowest and highest, or 0..1 where nothing was finite.
fn range() -> vec2<f32> {
    let lo = params.found_a.x;
    let hi = params.found_a.y;
    return select(vec2<f32>(lo, hi), vec2<f32>(0.0, 1.0), lo > hi);
}

@fragment
fn colour_scalar(@builtin(position) at: vec4<f32>) -> @location(0) vec4<f32> {
    let p = vec2<i32>(at.xy);
    let word = textureLoad(info, p, 0).r;
    if ((word >> COST_SHIFT) == 0u) {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    let v = textureLoad(values, p, 0);
    let odd = unless_finite(p, word, v, 1u);
    let r = range();
    let diverging = r.x < 0.0 && r.y > 0.0;
    let m = max(abs(r.x), abs(r.y));
    let span = select(1.0, r.y - r.x, r.y > r.x);
    let t = select((v.x - r.x) / span, (v.x / max(m, 0x1p-126f) + 1.0) / 2.0, diverging);
    let c = ramp(t, select(0u, 9u, diverging), select(8u, 4u, diverging));
    return out(select(c, odd.xyz, odd.w > 0.0));
}

@fragment
fn colour_vector(@builtin(position) at: vec4<f32>) -> @location(0) vec4<f32> {
    let p = vec2<i32>(at.xy);
    let word = textureLoad(info, p, 0).r;
    if ((word >> COST_SHIFT) == 0u) {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    let v = textureLoad(values, p, 0);
    let n = clamp(params.components, 1u, 4u);
    let odd = unless_finite(p, word, v, n);
    var r = range();
    if (r.x >= 0.0 && r.y <= 1.0) {
        r = vec2<f32>(0.0, 1.0);
    }
    let span = select(1.0, r.y - r.x, r.y > r.x);
    let t = clamp((v.xyz - vec3<f32>(r.x)) / span, vec3<f32>(0.0), vec3<f32>(1.0));
    var c = bytes(t);
    if (n <= 2u) {
        c.z = 0.0;
    }
    return out(select(c, odd.xyz, odd.w > 0.0));
}
";

/// One folding pass's two targets.
struct Level {
    size: (u32, u32),
    a: (wgpu::Texture, wgpu::TextureView),
    b: (wgpu::Texture, wgpu::TextureView),
}

/// Where the legend's read-back stands.
const IDLE: u8 = 0;
const MAPPING: u8 = 1;
const MAPPED: u8 = 2;
const FAILED: u8 = 3;

/// Makes views' pictures on the GPU ([`Painter::paint`]), keeping its pipelines, its folding
/// targets and the picture while the size stays.
pub struct Painter {
    device: wgpu::Device,
    fold_value: wgpu::RenderPipeline,
    fold_cost: wgpu::RenderPipeline,
    fold_next: wgpu::RenderPipeline,
    colour_cost: wgpu::RenderPipeline,
    colour_scalar: wgpu::RenderPipeline,
    colour_vector: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    params: wgpu::Buffer,
    levels: Vec<Level>,
    /// The passes' bind groups (the first folding pass's, which the colouring pass shares,
    /// then each next one's), kept while the view's targets and the levels stay.
    groups: Option<((wgpu::TextureView, wgpu::TextureView), Vec<wgpu::BindGroup>)>,
    /// What the first folding pass binds where the next ones read the pass before.
    unread: (wgpu::TextureView, wgpu::TextureView),
    picture: Option<(wgpu::Texture, wgpu::TextureView)>,
    /// The last level's 32 bytes, copied for the legend.
    stats: wgpu::Buffer,
    /// The read-back's state, and what it is of: the caller's tag and the view's kind.
    reading: Option<(Arc<AtomicU8>, u64, Kind)>,
}

/// What a painted picture shows, for its legend.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A line's value of this many components.
    Value(u32),
    /// The cost.
    Cost,
}

impl Kind {
    /// The kind of the view `drawn` holds.
    pub fn of(drawn: &Drawn) -> Kind {
        if drawn.value {
            Kind::Value(drawn.components)
        } else {
            Kind::Cost
        }
    }

    /// The legend strip, `width` pixels wide, of a picture with these findings.
    pub fn strip(self, width: u32, stats: &Stats) -> RgbaImage {
        match self {
            Kind::Value(c) => picture::strip(width, &stats.legend(c)),
            Kind::Cost => picture::cost_strip(width, stats.max_cost as u32),
        }
    }
}

impl Painter {
    /// A painter for `device`: its pipelines are built here, its targets at the first paint.
    pub fn new(device: &wgpu::Device) -> Painter {
        let label = "shaderlab.debug.paint";
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(&format!("{label}.shader")),
            source: wgpu::ShaderSource::Wgsl(shader_source().into()),
        });
        let texture = |binding, sample_type| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Texture {
                sample_type,
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            count: None,
        };
        let float = wgpu::TextureSampleType::Float { filterable: false };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&format!("{label}.bind_group_layout")),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
                texture(1, float),
                texture(2, wgpu::TextureSampleType::Uint),
                texture(3, float),
                texture(4, float),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(&format!("{label}.pipeline_layout")),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = |entry: &str, targets: &[Option<wgpu::ColorTargetState>]| {
            crate::gpu::targets::full_screen_pipeline(
                device,
                &format!("{label}.{entry}"),
                &pipeline_layout,
                &module,
                entry,
                targets,
            )
        };
        let stats_target = Some(wgpu::ColorTargetState {
            format: STATS_FORMAT,
            blend: None,
            write_mask: wgpu::ColorWrites::ALL,
        });
        let folds = [stats_target.clone(), stats_target];
        let picture = [Some(wgpu::ColorTargetState {
            format: PICTURE_FORMAT,
            blend: None,
            write_mask: wgpu::ColorWrites::ALL,
        })];
        let mut contents = vec![0u8; FOUND_AT as usize + 32];
        contents.extend_from_slice(bytemuck::cast_slice(&tables()));
        let params = wgpu::util::DeviceExt::create_buffer_init(
            device,
            &wgpu::util::BufferInitDescriptor {
                label: Some(&format!("{label}.params")),
                contents: &contents,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            },
        );
        let stats = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(&format!("{label}.stats")),
            size: 2 * u64::from(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let unread = |name: &str| {
            let usage = wgpu::TextureUsages::TEXTURE_BINDING;
            texture_and_view(device, &format!("{label}.{name}"), (1, 1), STATS_FORMAT, usage).1
        };
        Painter {
            device: device.clone(),
            unread: (unread("unread_a"), unread("unread_b")),
            fold_value: pipeline("fold_value", &folds),
            fold_cost: pipeline("fold_cost", &folds),
            fold_next: pipeline("fold_next", &folds),
            colour_cost: pipeline("colour_cost", &picture),
            colour_scalar: pipeline("colour_scalar", &picture),
            colour_vector: pipeline("colour_vector", &picture),
            layout,
            params,
            levels: Vec::new(),
            groups: None,
            picture: None,
            stats,
            reading: None,
        }
    }

    /// Whether this painter was built for `device`.
    pub fn serves(&self, device: &wgpu::Device) -> bool {
        self.device == *device
    }

    /// The folding levels for a view of `size`, made anew when the size changed.
    fn levels_for(&mut self, size: (u32, u32)) {
        let mut sizes = Vec::new();
        let (mut w, mut h) = size;
        loop {
            (w, h) = (w.div_ceil(BLOCK).max(1), h.div_ceil(BLOCK).max(1));
            sizes.push((w, h));
            if (w, h) == (1, 1) {
                break;
            }
        }
        if self.levels.iter().map(|l| l.size).eq(sizes.iter().copied()) {
            return;
        }
        let label = "shaderlab.debug.paint";
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC;
        let target =
            |name: &str, size| texture_and_view(&self.device, &format!("{label}.{name}"), size, STATS_FORMAT, usage);
        self.groups = None;
        self.levels = sizes
            .into_iter()
            .enumerate()
            .map(|(k, size)| Level {
                size,
                a: target(&format!("fold{k}_a"), size),
                b: target(&format!("fold{k}_b"), size),
            })
            .collect();
    }

    /// The picture for a view of `size` (and its legend strip under it), made anew when the
    /// size changed; returns whether it is new (its strip is then blank).
    fn picture_for(&mut self, (w, h): (u32, u32)) -> bool {
        let full = (w, h + LEGEND_HEIGHT);
        if self
            .picture
            .as_ref()
            .is_some_and(|(t, _)| (t.width(), t.height()) == full)
        {
            return false;
        }
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST;
        let label = "shaderlab.debug.paint.picture";
        let (texture, view) = texture_and_view(&self.device, label, full, PICTURE_FORMAT, usage);
        self.picture = Some((texture, view));
        true
    }

    /// Records into `encoder` the picture of the view `drawn` ([`super::view::ViewDrawer::encode`]
    /// drew it into `targets`, its value and info views): the folding passes and the colouring
    /// pass into the picture ([`Painter::picture`], `drawn.size` plus the legend strip, which
    /// keeps the last legend written). Unless a legend is being read back, the findings are
    /// copied for one, tagged `tag`: call [`Painter::submitted`] once the encoder is submitted.
    pub fn paint(
        &mut self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        targets: (&wgpu::TextureView, &wgpu::TextureView),
        drawn: &Drawn,
        tag: u64,
    ) -> Result<()> {
        let label = "shaderlab.debug.paint";
        let (w, h) = drawn.size;
        let kind = Kind::of(drawn);
        gpu.checked(label, || {
            self.levels_for((w, h));
            let fresh = self.picture_for((w, h));
            let (mode, components) = match kind {
                Kind::Value(c) => (0u32, c),
                Kind::Cost => (1, 0),
            };
            gpu.queue
                .write_buffer(&self.params, 0, bytemuck::cast_slice(&[mode, components, 0, 0]));
            let (values, info) = targets;
            let group = |a: &wgpu::TextureView, b: &wgpu::TextureView| {
                let entries = [
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: self.params.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(values),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: wgpu::BindingResource::TextureView(info),
                    },
                    wgpu::BindGroupEntry {
                        binding: 3,
                        resource: wgpu::BindingResource::TextureView(a),
                    },
                    wgpu::BindGroupEntry {
                        binding: 4,
                        resource: wgpu::BindingResource::TextureView(b),
                    },
                ];
                self.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(&format!("{label}.bind_group")),
                    layout: &self.layout,
                    entries: &entries,
                })
            };
            if self.groups.as_ref().is_none_or(|((v, i), _)| v != values || i != info) {
                // The first pass reads the view's targets; each next one the pass before.
                let mut groups = vec![group(&self.unread.0, &self.unread.1)];
                for pair in self.levels.windows(2) {
                    groups.push(group(&pair[0].a.1, &pair[0].b.1));
                }
                self.groups = Some(((values.clone(), info.clone()), groups));
            }
            let (_, groups) = self.groups.as_ref().expect("made above");
            let attachment = |view| {
                Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                        store: wgpu::StoreOp::Store,
                    },
                })
            };
            for (k, (level, group)) in self.levels.iter().zip(groups).enumerate() {
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some(&format!("{label}.fold{k}")),
                    color_attachments: &[attachment(&level.a.1), attachment(&level.b.1)],
                    depth_stencil_attachment: None,
                    timestamp_writes: None,
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                pass.set_pipeline(match (k, kind) {
                    (0, Kind::Cost) => &self.fold_cost,
                    (0, Kind::Value(_)) => &self.fold_value,
                    _ => &self.fold_next,
                });
                pass.set_bind_group(0, group, &[]);
                pass.draw(0..3, 0..1);
            }
            let last = self.levels.last().expect("at least one level");
            // The findings into the parameters, for every pixel of the colouring pass to read.
            let found = |k: u64| wgpu::TexelCopyBufferInfo {
                buffer: &self.params,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: FOUND_AT + 16 * k,
                    bytes_per_row: None,
                    rows_per_image: None,
                },
            };
            let one = wgpu::Extent3d {
                width: 1,
                height: 1,
                depth_or_array_layers: 1,
            };
            for (k, texture) in [&last.a.0, &last.b.0].into_iter().enumerate() {
                encoder.copy_texture_to_buffer(texture.as_image_copy(), found(k as u64), one);
            }
            let (_, picture) = self.picture.as_ref().expect("made above");
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(&format!("{label}.colour")),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: picture,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        // A new picture's strip starts as the legend's grey; an old one's
                        // keeps the last legend written into it.
                        load: if fresh {
                            wgpu::LoadOp::Clear(wgpu::Color {
                                r: STRIP_GREY,
                                g: STRIP_GREY,
                                b: STRIP_GREY,
                                a: 1.0,
                            })
                        } else {
                            wgpu::LoadOp::Load
                        },
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(match kind {
                Kind::Cost => &self.colour_cost,
                Kind::Value(c) if c > 1 => &self.colour_vector,
                Kind::Value(_) => &self.colour_scalar,
            });
            pass.set_bind_group(0, &groups[0], &[]);
            pass.set_viewport(0.0, 0.0, w as f32, h as f32, 0.0, 1.0);
            pass.draw(0..3, 0..1);
            drop(pass);
            if self.reading.is_none() {
                for (k, texture) in [&last.a.0, &last.b.0].into_iter().enumerate() {
                    encoder.copy_texture_to_buffer(
                        wgpu::TexelCopyTextureInfo {
                            texture,
                            mip_level: 0,
                            origin: wgpu::Origin3d::ZERO,
                            aspect: wgpu::TextureAspect::All,
                        },
                        wgpu::TexelCopyBufferInfo {
                            buffer: &self.stats,
                            layout: wgpu::TexelCopyBufferLayout {
                                offset: k as u64 * u64::from(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT),
                                bytes_per_row: None,
                                rows_per_image: None,
                            },
                        },
                        wgpu::Extent3d {
                            width: 1,
                            height: 1,
                            depth_or_array_layers: 1,
                        },
                    );
                }
                self.reading = Some((Arc::new(AtomicU8::new(IDLE)), tag, kind));
            }
        })
    }

    /// Starts reading back the findings [`Painter::paint`] copied, once its encoder is
    /// submitted.
    pub fn submitted(&mut self) {
        let Some((state, _, _)) = &self.reading else {
            return;
        };
        if state.load(Ordering::SeqCst) != IDLE {
            return;
        }
        state.store(MAPPING, Ordering::SeqCst);
        let state = state.clone();
        self.stats.slice(..).map_async(wgpu::MapMode::Read, move |r| {
            state.store(if r.is_ok() { MAPPED } else { FAILED }, Ordering::SeqCst);
        });
    }

    /// Whether findings are being read back.
    pub fn reading(&self) -> bool {
        self.reading.is_some()
    }

    /// Whether the findings being read back are there (or could not be): [`Painter::legend`]
    /// then takes them.
    pub fn legend_back(&self) -> bool {
        self.reading
            .as_ref()
            .is_none_or(|(state, _, _)| matches!(state.load(Ordering::SeqCst), MAPPED | FAILED))
    }

    /// The findings read back, with their tag and kind, once they are back (poll the device
    /// meanwhile); `None` while they are not (or none were asked for).
    pub fn legend(&mut self) -> Option<Result<(Stats, u64, Kind)>> {
        let (state, tag, kind) = self.reading.as_ref()?;
        let (tag, kind) = (*tag, *kind);
        match state.load(Ordering::SeqCst) {
            MAPPED => {}
            FAILED => {
                self.reading = None;
                return Some(Err(Error::Wgpu {
                    context: "reading a view's legend back".into(),
                    message: "the buffer could not be mapped".into(),
                }));
            }
            _ => return None,
        }
        let read = self.stats.slice(..).get_mapped_range().map(|data| {
            let word = |offset: usize| {
                f32::from_le_bytes([data[offset], data[offset + 1], data[offset + 2], data[offset + 3]])
            };
            let b = wgpu::COPY_BYTES_PER_ROW_ALIGNMENT as usize;
            Stats {
                lo: word(0),
                hi: word(4),
                max_cost: word(8),
                background: word(12),
                nan: word(b),
                pos_inf: word(b + 4),
                neg_inf: word(b + 8),
                not_run: word(b + 12),
            }
        });
        self.stats.unmap();
        self.reading = None;
        Some(read.map(|stats| (stats, tag, kind)).map_err(|e| Error::Wgpu {
            context: "reading a view's legend back".into(),
            message: e.to_string(),
        }))
    }

    /// The picture (the view with its legend strip), once painted.
    pub fn picture(&self) -> Option<&wgpu::TextureView> {
        self.picture.as_ref().map(|(_, v)| v)
    }

    /// Writes the legend strip `strip` into the picture's bottom rows.
    pub fn write_strip(&self, gpu: &Gpu, strip: &RgbaImage) {
        let Some((texture, _)) = &self.picture else {
            return;
        };
        write_rgba(gpu, texture, texture.height().saturating_sub(LEGEND_HEIGHT), strip);
    }

    /// Reads the picture back (blocking): what a window showing it shows.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn read(&self, gpu: &Gpu) -> Result<RgbaImage> {
        let failed = |message: String| Error::Wgpu {
            context: "reading a view's picture back".into(),
            message,
        };
        let Some((texture, _)) = &self.picture else {
            return Err(failed("nothing was painted".into()));
        };
        let (w, h) = (texture.width(), texture.height());
        let stride = crate::gpu::targets::padded_row(4, w);
        let label = "shaderlab.debug.paint.read";
        let buffer = crate::gpu::targets::readback_buffer(&gpu.device, label, stride, h);
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) });
        crate::gpu::targets::copy_to_buffer(&mut encoder, texture, &buffer, stride, (w, h));
        gpu.queue.submit([encoder.finish()]);
        let (tx, rx) = std::sync::mpsc::channel();
        buffer.slice(..).map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        gpu.wait()?;
        rx.recv()
            .map_err(|e| failed(e.to_string()))?
            .map_err(|e| failed(e.to_string()))?;
        let mut pixels = Vec::with_capacity((4 * w * h) as usize);
        {
            let data = buffer.slice(..).get_mapped_range().map_err(|e| failed(e.to_string()))?;
            for row in data.chunks(stride as usize).take(h as usize) {
                pixels.extend_from_slice(&row[..(4 * w) as usize]);
            }
        }
        buffer.unmap();
        RgbaImage::from_raw(w, h, pixels).ok_or_else(|| failed("short buffer".into()))
    }
}

/// Writes `image` into an `Rgba8Unorm` `texture` from row `top` down, as much of it as fits.
pub fn write_rgba(gpu: &Gpu, texture: &wgpu::Texture, top: u32, image: &RgbaImage) {
    let width = image.width().min(texture.width());
    let rows = image.height().min(texture.height().saturating_sub(top));
    if width == 0 || rows == 0 {
        return;
    }
    gpu.queue.write_texture(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d { x: 0, y: top, z: 0 },
            aspect: wgpu::TextureAspect::All,
        },
        image.as_raw(),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(4 * image.width()),
            rows_per_image: Some(image.height()),
        },
        wgpu::Extent3d {
            width,
            height: rows,
            depth_or_array_layers: 1,
        },
    );
}

/// Draws the view `probe` of the frame `log` wrote down (at `width` × `height`) and paints
/// its picture on the GPU, waits for it and its legend, and reads it back: the picture a
/// window showing the view shows once its legend is back (what the tests check).
#[cfg(not(target_arch = "wasm32"))]
pub fn paint_view(
    gpu: &Gpu,
    drawer: &mut super::view::ViewDrawer,
    painter: &mut Painter,
    view: (&crate::render::DrawLog, &super::view::Probe),
    width: u32,
    height: u32,
) -> Result<(RgbaImage, Stats)> {
    let stats = paint_and_wait(gpu, drawer, painter, view.0, view.1, width, height)?;
    Ok((painter.read(gpu)?, stats))
}

/// Draws and paints the view as [`paint_view`] does and waits for its legend, without reading
/// the picture back.
#[cfg(not(target_arch = "wasm32"))]
pub fn paint_and_wait(
    gpu: &Gpu,
    drawer: &mut super::view::ViewDrawer,
    painter: &mut Painter,
    log: &crate::render::DrawLog,
    probe: &super::view::Probe,
    width: u32,
    height: u32,
) -> Result<Stats> {
    // A legend still on its way from an earlier picture is taken first.
    if painter.reading() {
        gpu.wait()?;
        let _ = painter.legend();
    }
    let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("shaderlab.debug.paint.view"),
    });
    let drawn = drawer.encode(gpu, &mut encoder, log, probe, width, height)?;
    let targets = drawer.targets().ok_or_else(|| Error::Wgpu {
        context: "painting a view".into(),
        message: "the view's targets are gone".into(),
    })?;
    painter.paint(gpu, &mut encoder, targets, &drawn, 0)?;
    let commands = gpu.checked("shaderlab.debug.paint.view", || encoder.finish())?;
    gpu.queue.submit([commands]);
    painter.submitted();
    gpu.wait_until("painting a view", || painter.legend_back())?;
    let (stats, _, kind) = painter.legend().unwrap_or_else(|| {
        Err(Error::Wgpu {
            context: "painting a view".into(),
            message: "its legend did not come back".into(),
        })
    })?;
    painter.write_strip(gpu, &kind.strip(drawn.size.0, &stats));
    Ok(stats)
}
