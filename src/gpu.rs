//! The GPU context: instance, adapter, device and queue. The window code owns its surface.

use crate::error::{Error, Result};

pub mod targets;

/// Colour targets made of host memory, for the window's shared-memory presenter.
#[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
pub(crate) mod host_memory;

/// How long [`Gpu::poll_then_wait`] polls before it blocks, unless `SHADERLAB_POLL_US` says
/// otherwise (0: block at once; for measuring): long enough to cover a cheap frame whole, short
/// enough to leave a dear one's CPU to the rasteriser (figures: `docs/speed.md`, "Polling").
pub const POLL_BEFORE_WAIT: std::time::Duration = std::time::Duration::from_micros(200);

/// [`POLL_BEFORE_WAIT`], or `SHADERLAB_POLL_US` microseconds (at most one second) when set to a
/// whole number; read once.
#[cfg(not(target_arch = "wasm32"))]
fn poll_before_wait() -> std::time::Duration {
    static CHOSEN: std::sync::OnceLock<std::time::Duration> = std::sync::OnceLock::new();
    *CHOSEN.get_or_init(|| match std::env::var("SHADERLAB_POLL_US") {
        Err(_) => POLL_BEFORE_WAIT,
        Ok(v) => match v.trim().parse::<u64>() {
            Ok(us) => std::time::Duration::from_micros(us.min(1_000_000)),
            Err(_) => {
                // A measuring knob: a typo should not silently measure something else.
                eprintln!(
                    "shaderlab: SHADERLAB_POLL_US={v:?} is not a whole number of microseconds; \
                     polling {} µs before blocking",
                    POLL_BEFORE_WAIT.as_micros()
                );
                POLL_BEFORE_WAIT
            }
        },
    })
}

/// Instance, adapter, device and queue, created once and shared by every effect.
pub struct Gpu {
    /// The wgpu instance (needed to create window surfaces).
    pub instance: wgpu::Instance,
    /// The chosen adapter.
    pub adapter: wgpu::Adapter,
    /// The logical device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// Whether timestamp queries work (GPU timings in benchmarks).
    pub timestamps: bool,
    /// Whether the device imports host memory (`VK_EXT_external_memory_host`): opened so by
    /// [`Gpu::for_window`] on a CPU Vulkan adapter under X11, so that the window's
    /// shared-memory presenter can draw frames in the X server's memory.
    pub host_memory: bool,
    /// The watchdog: how long a wait for submitted work may take before it is given up as a
    /// frame that never ends (a shader looping for ever), [`Error::Hang`]; `None` waits for
    /// ever (the library's default; the command line sets [`WATCHDOG`]).
    pub watchdog: Option<std::time::Duration>,
    /// The first error wgpu reported outside any error scope (out of memory in a buffer made
    /// by a mesh, a validation error in a submitted frame), kept for [`Gpu::wait`] and
    /// [`Gpu::checked`] to return: wgpu's own default handler panics. A window replaces the
    /// handler with its own (`shell::surface::on_trouble`).
    uncaptured: std::sync::Arc<std::sync::Mutex<Option<String>>>,
    /// Whether building a pipeline is bounded ([`Gpu::compiling`]): past [`Gpu::watchdog`],
    /// or past the memory the process can take, it ends the process with a message saying
    /// which. Set by the command line, whose run can do nothing else while the driver compiles;
    /// a window compiles off its frame loop instead.
    pub bounded_compiles: bool,
}

/// How often [`Gpu::compiling`] looks at the process's memory while the driver compiles.
#[cfg(not(target_arch = "wasm32"))]
const COMPILE_CHECK: std::time::Duration = std::time::Duration::from_millis(25);

/// What [`Gpu::compiling`] leaves free of the memory the process could take when it began:
/// a driver's compiler that runs out of memory crashes without a word, so the run ends first.
#[cfg(not(target_arch = "wasm32"))]
const COMPILE_MEMORY_MARGIN: u64 = 256 << 20;

/// The command line's default watchdog ([`Gpu::watchdog`], `--timeout`): well above what a
/// frame of the labs or the largest model takes on lavapipe (figures in docs/speed.md).
pub const WATCHDOG: std::time::Duration = std::time::Duration::from_secs(10);

/// Set once a wait for the GPU has been given up: its queue holds work that may never end.
static HUNG: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Whether a wait for the GPU was given up ([`Error::Hang`]). The device then must not be
/// waited for again, not even to drop it: a process in this state ends with
/// [`crate::fsutil::signals::exit_now`], and a [`Gpu`] dropped meanwhile keeps its device.
pub fn hung() -> bool {
    HUNG.load(std::sync::atomic::Ordering::SeqCst)
}

impl Drop for Gpu {
    fn drop(&mut self) {
        if hung() {
            // Destroying the device waits for its queue, which never empties.
            std::mem::forget(self.device.clone());
            std::mem::forget(self.queue.clone());
        }
    }
}

impl Gpu {
    /// A new instance honouring `WGPU_BACKEND` and friends. Without `WGPU_BACKEND` it holds the
    /// primary backends (Vulkan, Metal, DX12) only: starting the GL backend as well (EGL and
    /// its driver) lengthens every start (figures: `docs/speed.md`, "Start-up");
    /// [`Gpu::fallback_instance`] is GL.
    pub fn new_instance() -> wgpu::Instance {
        let mut desc = Self::descriptor();
        if std::env::var_os("WGPU_BACKEND").is_none() {
            desc.backends = wgpu::Backends::PRIMARY;
        }
        wgpu::Instance::new(desc)
    }

    /// The instance to try when [`Gpu::new_instance`] finds no adapter: GL, unless
    /// `WGPU_BACKEND` chose the backends already (then there is nothing else to try).
    pub fn fallback_instance() -> Option<wgpu::Instance> {
        if std::env::var_os("WGPU_BACKEND").is_some() {
            return None;
        }
        let mut desc = Self::descriptor();
        desc.backends = wgpu::Backends::GL;
        Some(wgpu::Instance::new(desc))
    }

    /// wgpu's options from the environment, less the validation of indirect draws: shaderlab
    /// draws nothing indirectly, and that validation builds compute pipelines at device
    /// creation, in every start (figures: `docs/speed.md`, "Start-up").
    /// `WGPU_VALIDATION_INDIRECT_CALL=1` turns it back on.
    fn descriptor() -> wgpu::InstanceDescriptor {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.flags.remove(wgpu::InstanceFlags::VALIDATION_INDIRECT_CALL);
        desc.with_env()
    }

    /// A context with no window (offscreen rendering, tests, benchmarks): the primary backends
    /// first, GL if they have no adapter. Native only: it blocks, which a browser cannot (there,
    /// await [`Gpu::new`]).
    #[cfg(not(target_arch = "wasm32"))]
    pub fn headless() -> Result<Self> {
        match pollster::block_on(Self::new(Self::new_instance(), None)) {
            Err(Error::NoAdapter(first)) => match Self::fallback_instance() {
                Some(gl) => pollster::block_on(Self::new(gl, None)).map_err(|e| match e {
                    Error::NoAdapter(_) => Error::NoAdapter(first),
                    e => e,
                }),
                None => Err(Error::NoAdapter(first)),
            },
            result => result,
        }
    }

    /// A context whose adapter can present to `surface` (if given).
    pub async fn new(instance: wgpu::Instance, surface: Option<&wgpu::Surface<'_>>) -> Result<Self> {
        Self::create(instance, surface, false).await
    }

    /// [`Gpu::new`] for a window: under X11, on a CPU Vulkan adapter that offers it, the device
    /// also imports host memory ([`Gpu::host_memory`]), so that the shared-memory presenter
    /// draws frames in the X server's segments. Elsewhere the same as [`Gpu::new`].
    pub async fn for_window(instance: wgpu::Instance, surface: &wgpu::Surface<'_>) -> Result<Self> {
        Self::create(instance, Some(surface), true).await
    }

    async fn create(instance: wgpu::Instance, surface: Option<&wgpu::Surface<'_>>, host_memory: bool) -> Result<Self> {
        let adapter = instance
            .request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::default(),
                force_fallback_adapter: false,
                compatible_surface: surface,
                ..Default::default()
            })
            .await
            .map_err(|e| Error::NoAdapter(e.to_string()))?;
        let wanted = wgpu::Features::TIMESTAMP_QUERY;
        // WebGL2 offers less than wgpu's downlevel defaults (no storage buffers, smaller
        // uniform blocks): ask for what it guarantees there, the downlevel defaults elsewhere.
        let base = if cfg!(target_arch = "wasm32") && adapter.get_info().backend == wgpu::Backend::Gl {
            wgpu::Limits::downlevel_webgl2_defaults()
        } else {
            wgpu::Limits::downlevel_defaults()
        };
        let features = adapter.features() & wanted;
        let desc = wgpu::DeviceDescriptor {
            label: Some("shaderlab.device"),
            required_features: features,
            required_limits: wgpu::Limits {
                // The adapter's own largest buffer: a big offscreen picture (a supersampled
                // reference) is read back through one buffer.
                max_buffer_size: adapter.limits().max_buffer_size.max(base.max_buffer_size),
                ..base.using_resolution(adapter.limits())
            },
            ..Default::default()
        };
        let timestamps = features.contains(wgpu::Features::TIMESTAMP_QUERY);
        // Where the device cannot import host memory it opens the usual way: the presenter
        // then copies each frame (and says why with SHADERLAB_PRESENT=shm).
        #[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
        if host_memory {
            if let Some((device, queue)) = host_memory::open_device(&adapter, &desc) {
                return Ok(Gpu::assemble(instance, adapter, device, queue, timestamps, true));
            }
        }
        let _ = host_memory;
        let (device, queue) = adapter
            .request_device(&desc)
            .await
            .map_err(|e| Error::Device(e.to_string()))?;
        Ok(Gpu::assemble(instance, adapter, device, queue, timestamps, false))
    }

    fn assemble(
        instance: wgpu::Instance,
        adapter: wgpu::Adapter,
        device: wgpu::Device,
        queue: wgpu::Queue,
        timestamps: bool,
        host_memory: bool,
    ) -> Self {
        let uncaptured = std::sync::Arc::new(std::sync::Mutex::new(None));
        let keep = uncaptured.clone();
        device.on_uncaptured_error(std::sync::Arc::new(move |e| {
            // Kept as its words: wgpu's error is not `Send` in the browser build.
            if let Ok(mut first) = keep.lock() {
                first.get_or_insert_with(|| error_words(&e));
            }
        }));
        Gpu {
            instance,
            adapter,
            device,
            queue,
            timestamps,
            host_memory,
            watchdog: None,
            uncaptured,
            bounded_compiles: false,
        }
    }

    /// Runs `work` (building `what`'s pipelines: the driver compiles its shaders then) under the
    /// bounds of [`Gpu::bounded_compiles`]. A driver's compiler cannot be stopped: past
    /// [`Gpu::watchdog`], or when the process comes within [`COMPILE_MEMORY_MARGIN`] of the
    /// memory it could take ([`crate::memory::available`]: the machine's, or the
    /// address-space limit's), a watching thread says so and ends the process
    /// ([`crate::fsutil::signals::exit_now`], which removes what it was writing).
    #[cfg(not(target_arch = "wasm32"))]
    pub fn compiling<T>(&self, what: &str, work: impl FnOnce() -> T) -> T {
        if !self.bounded_compiles {
            return work();
        }
        let (done, finished) = std::sync::mpsc::channel::<()>();
        let (what, limit) = (what.to_owned(), self.watchdog);
        let budget = crate::memory::available()
            .map(|free| (crate::memory::in_use().unwrap_or(0) + free).saturating_sub(COMPILE_MEMORY_MARGIN));
        let spawned = std::thread::Builder::new()
            .name("shaderlab-compile-watch".into())
            .spawn(move || {
                let start = std::time::Instant::now();
                loop {
                    match finished.recv_timeout(COMPILE_CHECK) {
                        Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {}
                        _ => return,
                    }
                    let why = if let Some(limit) = limit.filter(|l| start.elapsed() > *l) {
                        format!(
                            "the GPU's driver was still compiling {what}'s shaders after {} s (the watchdog, \
                             --timeout): they are too large for it (a large local array, a long chain of function \
                             calls); make them smaller, or give --timeout 0 to wait",
                            limit.as_secs_f64()
                        )
                    } else if let (Some(budget), Some(used)) = (
                        budget,
                        crate::memory::in_use().filter(|u| budget.is_some_and(|b| *u > b)),
                    ) {
                        format!(
                            "the GPU's driver took {} of memory compiling {what}'s shaders, all but {} of what this \
                             process may use ({} with the machine's free memory and `ulimit -v`): they are too \
                             large for it (a large local array, a long chain of function calls); make them smaller",
                            crate::fsutil::human_bytes(used),
                            crate::fsutil::human_bytes(COMPILE_MEMORY_MARGIN),
                            crate::fsutil::human_bytes(budget + COMPILE_MEMORY_MARGIN),
                        )
                    } else {
                        continue;
                    };
                    eprintln!("shaderlab: error: {why}");
                    crate::fsutil::signals::exit_now(1);
                }
            });
        let value = work();
        drop(done);
        if let Ok(watch) = spawned {
            let _ = watch.join();
        }
        value
    }

    /// [`Gpu::compiling`] in the browser: no thread to watch with, and the browser bounds it.
    #[cfg(target_arch = "wasm32")]
    pub fn compiling<T>(&self, _what: &str, work: impl FnOnce() -> T) -> T {
        work()
    }

    /// The first error wgpu reported outside an error scope since the last call, as an
    /// [`Error`] about `context`.
    pub fn take_uncaptured(&self, context: &str) -> Option<Error> {
        let message = self.uncaptured.lock().ok()?.take()?;
        Some(Error::Wgpu {
            context: context.to_owned(),
            message,
        })
    }

    /// One line naming the adapter and backend, e.g. `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan, Cpu)`.
    pub fn describe(&self) -> String {
        let info = self.adapter.get_info();
        format!("{} ({:?}, {:?})", info.name, info.backend, info.device_type)
    }

    /// Runs `f` inside a validation error scope and turns a wgpu error into [`Error::Wgpu`].
    pub fn checked<T>(&self, context: &str, f: impl FnOnce() -> T) -> Result<T> {
        #[cfg(target_arch = "wasm32")]
        if self.adapter.get_info().backend == wgpu::Backend::BrowserWebGpu {
            // The browser's WebGPU answers an error scope only later (a promise), and the web
            // cannot block for it: no scope there, so a validation error reaches the device's
            // uncaptured-error handler instead of this Result.
            return Ok(f());
        }
        // Scopes are a stack: popped in the reverse order of pushing.
        let scopes = [
            wgpu::ErrorFilter::OutOfMemory,
            wgpu::ErrorFilter::Internal,
            wgpu::ErrorFilter::Validation,
        ]
        .map(|filter| self.device.push_error_scope(filter));
        // A panic inside wgpu or naga (a bug in either) is contained and said like an error.
        let value = crate::panics::contained(f);
        let mut first = None;
        for scope in scopes.into_iter().rev() {
            #[cfg(not(target_arch = "wasm32"))]
            let error = pollster::block_on(scope.pop());
            // WebGL2 runs through wgpu-core, which answers a scope at once: the first poll has it.
            #[cfg(target_arch = "wasm32")]
            let error = poll_once(scope.pop()).flatten();
            first = first.or(error);
        }
        // wgpu's error first: a panic after it (wgpu's own helpers panic on a buffer that
        // could not be made) is its consequence.
        if let Some(err) = first {
            return Err(wgpu_error(context, &err));
        }
        if let Some(err) = self.take_uncaptured(context) {
            return Err(err);
        }
        value.map_err(|panic| Error::Wgpu {
            context: context.to_owned(),
            message: format!("wgpu failed inside itself (a bug in wgpu or naga, not in the shader): {panic}"),
        })
    }

    /// Blocks until the GPU has finished all submitted work ([`Gpu::poll_then_wait`]), at most
    /// [`Gpu::watchdog`].
    pub fn wait(&self) -> Result<()> {
        let wait = wgpu::PollType::Wait {
            submission_index: None,
            timeout: self.watchdog,
        };
        self.poll_then_wait(|status| status.is_queue_empty(), wait)
            .map_err(|e| self.wait_error(e))?;
        match self.take_uncaptured("drawing") {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    /// Blocks until the GPU has finished all submitted work ([`Gpu::wait`]) and then until
    /// `done` holds: a read-back's callbacks run inside whichever thread polls the device, so
    /// when another thread shares it they may still be running as the queue empties. Gives up
    /// after [`Gpu::watchdog`] (10 s without one) with an error naming `what`.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn wait_until(&self, what: &str, done: impl Fn() -> bool) -> Result<()> {
        self.wait()?;
        let start = std::time::Instant::now();
        let limit = self.watchdog.unwrap_or(std::time::Duration::from_secs(10));
        while !done() {
            if start.elapsed() > limit {
                return Err(Error::Wgpu {
                    context: what.to_owned(),
                    message: format!("the read-back did not arrive within {:.0} s", limit.as_secs_f64()),
                });
            }
            let _ = self.device.poll(wgpu::PollType::Poll);
            std::thread::yield_now();
        }
        Ok(())
    }

    /// The error of a wait for the GPU: a timeout is [`Error::Hang`] (and marks the device as
    /// [`hung`]), anything else [`Error::Wgpu`].
    pub fn wait_error(&self, e: wgpu::PollError) -> Error {
        match (e, self.watchdog) {
            (wgpu::PollError::Timeout, Some(limit)) => {
                HUNG.store(true, std::sync::atomic::Ordering::SeqCst);
                let why = if crate::shader::loops_compiled() {
                    "most likely a shader never ends (a `while` or `for` whose condition stays true), or is too \
                     large for the driver to compile or run in time (a large local array)"
                } else {
                    "no shader has a loop, so one is too large for the driver to compile or run in time (a \
                     large local array, a long chain of function calls), or the frame is too large"
                };
                Error::Hang(format!(
                    "the GPU did not finish a frame within {} s: {why}; fix the shader, or give `--timeout SECONDS` \
                     (0: no limit) if the frame is only slow",
                    limit.as_secs_f64()
                ))
            }
            (e, _) => Error::Wgpu {
                context: "waiting for the GPU".into(),
                message: e.to_string(),
            },
        }
    }

    /// Polls without blocking, yielding the CPU between polls, until `done` says the work
    /// waited for has finished or [`POLL_BEFORE_WAIT`] has passed (`SHADERLAB_POLL_US`); then
    /// blocks with `wait`. `done` sees each poll's status (callbacks, such as a buffer's `map_async`, have run).
    ///
    /// Why not block at once: on a CPU driver (lavapipe) the work runs on the driver's queue
    /// thread and rasteriser threads, and a blocked waiter is woken by a futex from another
    /// CPU, which is slow on a small virtual machine. Polling for the whole frame takes CPU
    /// from the rasteriser threads, so only the first [`POLL_BEFORE_WAIT`] is polled: it covers
    /// a cheap frame whole, and in a dear one it overlaps the driver's vertex and binning work,
    /// when the rasterisers are idle (figures: `docs/speed.md`, "Polling").
    pub fn poll_then_wait(
        &self,
        done: impl Fn(wgpu::PollStatus) -> bool,
        wait: wgpu::PollType,
    ) -> std::result::Result<(), wgpu::PollError> {
        #[cfg(not(target_arch = "wasm32"))]
        {
            let (start, spin) = (std::time::Instant::now(), poll_before_wait());
            while start.elapsed() < spin {
                if done(self.device.poll(wgpu::PollType::Poll)?) {
                    return Ok(());
                }
                std::thread::yield_now();
            }
        }
        // The browser has no clock for this (and no CPU driver behind it): it blocks at once.
        #[cfg(target_arch = "wasm32")]
        let _ = &done;
        self.device.poll(wait).map(|_| ())
    }
}

/// wgpu's error as [`Error::Wgpu`].
fn wgpu_error(context: &str, error: &wgpu::Error) -> Error {
    Error::Wgpu {
        context: context.to_owned(),
        message: error_words(error),
    }
}

/// What to say of wgpu's error: running out of memory says where the memory is and what
/// limits it.
fn error_words(error: &wgpu::Error) -> String {
    match error {
        wgpu::Error::OutOfMemory { .. } => "the GPU ran out of memory (on a CPU adapter such as lavapipe the GPU's \
             memory is the machine's, within the process's limit, `ulimit -v`): draw less, a smaller model, a \
             lower --tess or a smaller --size"
            .to_string(),
        e => e.to_string(),
    }
}

/// The output of a future that is ready on its first poll (none if it is not): the browser
/// build's stand-in for blocking on a future that never waits.
#[cfg(target_arch = "wasm32")]
fn poll_once<F: std::future::Future>(future: F) -> Option<F::Output> {
    let mut future = std::pin::pin!(future);
    let mut cx = std::task::Context::from_waker(std::task::Waker::noop());
    match future.as_mut().poll(&mut cx) {
        std::task::Poll::Ready(output) => Some(output),
        std::task::Poll::Pending => None,
    }
}
