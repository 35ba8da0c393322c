//! A frame's draws brought to the CPU: the [`DrawLog`] of a frame with every buffer it drew
//! from read back (vertices, uniform blocks), the indices and texels as uploaded, and each
//! sampler's state, as plain data that another thread can replay.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use super::error::ReplayError;
use crate::error::{Error, Result};
use crate::gpu::Gpu;
use crate::render::{DrawLog, DrawSetup, Load, Resource, SamplerDesc, Texels};

/// A texture binding as the debugger reads it.
#[derive(Clone, Debug)]
pub struct TextureBinding {
    /// The binding number.
    pub binding: u32,
    /// The texels.
    pub texels: Arc<Texels>,
    /// The levels the bound view shows.
    pub levels: std::ops::Range<u32>,
    /// A cube map.
    pub cube: bool,
}

/// One draw with its data on the CPU: its setup (read through, as `draw.state`) and the
/// bytes of what it read.
#[derive(Clone)]
pub struct CapturedDraw {
    /// Shaders, state, layout, range, as recorded.
    pub setup: DrawSetup,
    /// The vertex buffer's bytes.
    pub vertices: Arc<Vec<u8>>,
    /// Uniform blocks: binding and bytes.
    pub uniforms: Vec<(u32, Arc<Vec<u8>>)>,
    /// Textures.
    pub textures: Vec<TextureBinding>,
    /// Samplers: binding and state.
    pub samplers: Vec<(u32, SamplerDesc)>,
    /// The clip-space positions of its vertices, computed by the first replay that needs them
    /// (every pixel of a frame shares them).
    pub(crate) positions: Arc<std::sync::OnceLock<Positions>>,
}

impl CapturedDraw {
    /// Whether the clip-space positions of its vertices came with the capture (computed by
    /// the GPU for a big draw, [`super::positions`]) rather than by the interpreter at the
    /// first replay.
    pub fn positions_captured(&self) -> bool {
        self.positions.get().is_some()
    }
}

impl std::ops::Deref for CapturedDraw {
    type Target = DrawSetup;

    fn deref(&self) -> &DrawSetup {
        &self.setup
    }
}

/// A draw's shaded vertices: their ids, sorted, and their clip-space positions (or why the
/// vertex shader could not run); the replay computes them once per captured draw.
pub(crate) type Positions = std::result::Result<Arc<(Vec<u32>, Vec<[f32; 4]>)>, ReplayError>;

/// A frame on the CPU: its passes (load operation, size) and draws.
#[derive(Clone)]
pub struct Captured {
    /// The passes: how each began, and the target's size.
    pub passes: Vec<(Load, u32, u32)>,
    /// The adapter that drew the frame: its name and driver (`llvmpipe (LLVM 15.0.6, 256
    /// bits), Mesa 22.3.6 (LLVM 15.0.6)`), for what the replay can promise about it.
    pub adapter: String,
    /// The draws, in order.
    pub draws: Vec<CapturedDraw>,
    /// The picture the GPU drew when it ran the recorded frame (8-bit RGBA, top row first),
    /// where the capture ran it ([`super::capture_start`], [`super::Capture::draw`]): what
    /// each inspection's replayed pixel is checked against.
    pub picture: Option<Arc<image::RgbaImage>>,
}

/// The buffers of a [`DrawLog`] being read back.
pub struct Pending {
    log: Vec<crate::render::DrawCall>,
    adapter: String,
    passes: Vec<(Load, u32, u32)>,
    /// Each distinct buffer, its staging copy and its size.
    buffers: Vec<(wgpu::Buffer, wgpu::Buffer, u64)>,
    /// The big draws' positions computed by the GPU ([`super::positions`]), and the draws
    /// that share one of them (the same vertex shader, vertices and bindings): the draw and
    /// the index of the job it shares.
    jobs: Vec<super::positions::Job>,
    shared: Vec<(usize, usize)>,
    mapped: Arc<AtomicUsize>,
    /// Why a buffer could not be mapped, if one could not.
    failed: Arc<Mutex<Option<String>>>,
    /// The frame's target being read back after the frame ran ([`Pending::draw`]), and
    /// whether its mapping finished (either way).
    picture: Option<(crate::offscreen::Offscreen, Arc<std::sync::atomic::AtomicBool>)>,
}

impl Pending {
    /// Copies every buffer `log` drew from into staging buffers and asks for them to be
    /// mapped; call after the frame was submitted.
    pub fn start(gpu: &Gpu, log: &DrawLog) -> Pending {
        let draws = log.draws();
        let mut buffers: Vec<(wgpu::Buffer, wgpu::Buffer, u64)> = Vec::new();
        let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("shaderlab.debug.readback"),
        });
        let mut want = |buffer: &wgpu::Buffer| {
            if buffers.iter().any(|(b, _, _)| b == buffer) {
                return;
            }
            let size = buffer.size() & !3;
            let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("shaderlab.debug.staging"),
                size: size.max(4),
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            });
            if size > 0 {
                encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
            }
            buffers.push((buffer.clone(), staging, size));
        };
        for d in &draws {
            want(&d.vertices);
            for r in &d.resources {
                match &r.resource {
                    Resource::Buffer { buffer, .. } | Resource::Block { buffer, .. } => want(buffer),
                    _ => {}
                }
            }
        }
        gpu.queue.submit([encoder.finish()]);
        let (jobs, shared) = positions_start(gpu, &draws);
        let mapped = Arc::new(AtomicUsize::new(0));
        let failed = Arc::new(Mutex::new(None));
        let stagings = buffers
            .iter()
            .map(|(_, s, _)| s)
            .chain(jobs.iter().flat_map(|j| &j.staging));
        for staging in stagings {
            let (m, f) = (mapped.clone(), failed.clone());
            staging.slice(..).map_async(wgpu::MapMode::Read, move |r| {
                if let Err(e) = r {
                    if let Ok(mut why) = f.lock() {
                        why.get_or_insert(e.to_string());
                    }
                }
                m.fetch_add(1, Ordering::SeqCst);
            });
        }
        let info = gpu.adapter.get_info();
        Pending {
            log: draws,
            adapter: format!("{}, {}", info.name, info.driver_info),
            passes: log.passes(),
            buffers,
            jobs,
            shared,
            mapped,
            failed,
            picture: None,
        }
    }

    /// Runs the recorded `frame` (after the read-back's copies, on the same queue) and starts
    /// reading back `target`, which it draws into: [`Pending::finish`] then brings the picture
    /// the GPU stored ([`Captured::picture`]).
    pub fn draw(mut self, gpu: &Gpu, target: crate::offscreen::Offscreen, frame: wgpu::CommandBuffer) -> Pending {
        gpu.queue.submit([frame]);
        let done = Arc::new(std::sync::atomic::AtomicBool::new(false));
        let flag = done.clone();
        target.request_read(gpu, move |_| flag.store(true, Ordering::SeqCst));
        self.picture = Some((target, done));
        self
    }

    /// Whether every buffer is mapped (or failed).
    pub fn ready(&self) -> bool {
        let positions: usize = self.jobs.iter().map(|j| j.staging.len()).sum();
        let picture = self
            .picture
            .as_ref()
            .is_none_or(|(_, done)| done.load(Ordering::SeqCst));
        self.mapped.load(Ordering::SeqCst) >= self.buffers.len() + positions && picture
    }

    /// Blocks until the buffers are mapped, then [`Pending::finish`].
    #[cfg(not(target_arch = "wasm32"))]
    pub fn wait(self, gpu: &Gpu) -> Result<Captured> {
        let failed = || self.failed.lock().map_or(true, |w| w.is_some());
        gpu.wait_until("reading the frame's buffers back for the debugger", || {
            self.ready() || failed()
        })?;
        self.finish()
    }

    /// The frame on the CPU, once [`Pending::ready`].
    pub fn finish(self) -> Result<Captured> {
        let why = self.failed.lock().ok().and_then(|w| w.clone());
        if why.is_some() || !self.ready() {
            return Err(Error::Wgpu {
                context: "reading the frame's buffers back for the debugger".into(),
                message: format!(
                    "a buffer could not be mapped: {}",
                    why.unwrap_or_else(|| "not mapped yet".into())
                ),
            });
        }
        let mut bytes: Vec<(wgpu::Buffer, Arc<Vec<u8>>)> = Vec::new();
        for (buffer, staging, size) in &self.buffers {
            let data = {
                let view = staging.slice(..).get_mapped_range().map_err(|e| Error::Wgpu {
                    context: "reading the frame's buffers back for the debugger".into(),
                    message: e.to_string(),
                })?;
                view[..*size as usize].to_vec()
            };
            staging.unmap();
            // Its memory goes now, before the next buffer's copy is made.
            staging.destroy();
            bytes.push((buffer.clone(), Arc::new(data)));
        }
        let find = |b: &wgpu::Buffer| -> Arc<Vec<u8>> {
            bytes
                .iter()
                .find(|(x, _)| x == b)
                .map(|(_, d)| d.clone())
                .unwrap_or_default()
        };
        let mut draws = Vec::with_capacity(self.log.len());
        for call in &self.log {
            let mut uniforms = Vec::new();
            let mut textures = Vec::new();
            let mut samplers = Vec::new();
            for binding in &call.setup.bindings {
                let Some(bind) = call.resources.iter().find(|r| r.name == binding.name) else {
                    continue;
                };
                match &bind.resource {
                    Resource::Buffer { buffer, .. } | Resource::Block { buffer, .. } => {
                        uniforms.push((binding.binding, find(buffer)));
                    }
                    Resource::Texture {
                        texels,
                        levels,
                        dimension,
                        ..
                    } => textures.push(TextureBinding {
                        binding: binding.binding,
                        texels: texels.clone(),
                        levels: levels.clone(),
                        cube: *dimension == wgpu::TextureViewDimension::Cube,
                    }),
                    Resource::Sampler(s) => samplers.push((binding.binding, s.desc)),
                }
            }
            draws.push(CapturedDraw {
                setup: call.setup.clone(),
                vertices: find(&call.vertices),
                uniforms,
                textures,
                samplers,
                positions: Arc::default(),
            });
        }
        for (k, job) in self.jobs.iter().enumerate() {
            let read = {
                let views = job
                    .staging
                    .iter()
                    .map(|b| b.slice(..).get_mapped_range())
                    .collect::<std::result::Result<Vec<_>, _>>()
                    .map_err(|e| Error::Wgpu {
                        context: "reading the frame's positions back for the debugger".into(),
                        message: e.to_string(),
                    })?;
                let bytes: Vec<&[u8]> = views.iter().map(|v| &v[..]).collect();
                super::positions::read(job, &bytes)
            };
            for staging in &job.staging {
                staging.unmap();
                staging.destroy();
            }
            let _ = draws[job.draw].positions.set(Ok(Arc::new(read)));
            for &(draw, shares) in &self.shared {
                if shares == k {
                    draws[draw].positions = draws[job.draw].positions.clone();
                }
            }
        }
        // A picture that could not be read back is left out: the inspections then say that
        // the GPU's pixel is not known, and nothing else is lost.
        let picture = self
            .picture
            .as_ref()
            .and_then(|(target, _)| target.mapped_rgba().ok())
            .map(Arc::new);
        Ok(Captured {
            passes: self.passes,
            adapter: self.adapter,
            draws,
            picture,
        })
    }
}

/// Starts the GPU's positions for the big draws of `draws` ([`super::positions`]), one job per
/// distinct vertex shader, vertex buffer, bind group and vertex range; the draws that share a
/// job, with its index. None in the browser, whose WebGPU answers errors only later.
fn positions_start(gpu: &Gpu, draws: &[crate::render::DrawCall]) -> (Vec<super::positions::Job>, Vec<(usize, usize)>) {
    let mut jobs: Vec<super::positions::Job> = Vec::new();
    let mut shared = Vec::new();
    if cfg!(target_arch = "wasm32") {
        return (jobs, shared);
    }
    for (k, d) in draws.iter().enumerate() {
        let same = jobs.iter().position(|j| {
            let e = &draws[j.draw];
            Arc::ptr_eq(&e.setup.vertex, &d.setup.vertex)
                && e.vertices == d.vertices
                && e.bind_group == d.bind_group
                && super::positions::span(e) == super::positions::span(d)
        });
        if let Some(j) = same {
            shared.push((k, j));
        } else if let Some(job) = super::positions::start(gpu, k, d) {
            jobs.push(job);
        }
    }
    (jobs, shared)
}
