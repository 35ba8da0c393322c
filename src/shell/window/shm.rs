//! Presenting through X shared memory (MIT-SHM) for CPU adapters.
//!
//! lavapipe's X11 swapchain (Mesa 22) sends every frame through the X socket (`PutImage`;
//! figures: `docs/speed.md`, "Presenting a window's frame"), while the original's GL driver puts
//! its frames through shared memory. For a CPU adapter under X11 the window can do the same: the
//! lab draws into an offscreen `Bgra8Unorm` target, the frame is copied into a System V shared
//! memory segment the X server has attached, and one `ShmPutImage` shows it. Three segments take
//! turns, so the server shows one frame while the next is drawn; a segment is written again
//! only after the server's completion event for it. The pixels are the ones the swapchain would
//! show (same format, same pipelines).
//!
//! Where the device imports host memory ([`Gpu::host_memory`]) each segment holds a colour
//! target and the lab draws straight into the segment, as the original's llvmpipe draws into
//! its shared-memory image; otherwise (or with `SHADERLAB_PRESENT=shm-copy`) the frame is drawn
//! into a texture, copied to a readback buffer and from there into the segment: two 920 KB
//! copies more per 640x360 frame.
//!
//! Anything else (another adapter type, Wayland, no MIT-SHM, a remote server, a visual that is
//! not 24-bit BGRX) keeps the swapchain, and so does `SHADERLAB_PRESENT=swapchain`. A presenter
//! that fails while drawing hands back to the swapchain too.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use winit::raw_window_handle::{HasWindowHandle, RawWindowHandle};
use winit::window::Window;
use x11rb::connection::{Connection, RequestConnection};
use x11rb::protocol::shm::{self, ConnectionExt as _};
use x11rb::protocol::xproto::{self, ConnectionExt as _};
use x11rb::rust_connection::RustConnection;

use crate::gpu::targets::{copyable_color, depth_texture, padded_row, readback_buffer};
use crate::gpu::Gpu;

/// The colour format the presenter draws in: bytes B, G, R, A, which is a little-endian X
/// server's 32-bit pixel `0x00RRGGBB` for a 24-bit TrueColor visual.
pub(super) const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Bgra8Unorm;

/// How many segments take turns.
const SEGMENTS: usize = 3;

/// A System V shared memory segment attached here and by the X server.
struct Segment {
    seg: shm::Seg,
    addr: *mut u8,
    size: usize,
    /// The colour target whose memory is this segment (presenting directly).
    target: Option<Target>,
}

/// A colour target in a segment, and where its rows lie there.
struct Target {
    color: wgpu::TextureView,
    /// Kept with its colour target: the memory is the segment's, dropped before the segment goes.
    _texture: wgpu::Texture,
    /// Bytes from the segment's start to the first row.
    offset: u32,
    /// Bytes from one row to the next.
    stride: u32,
}

/// What copying frames into the segments takes, where the GPU cannot draw in them, and why.
struct Copying {
    why: Why,
    /// The texture the lab draws in ([`ShmPresenter::color`] views it).
    texture: wgpu::Texture,
    /// A readback buffer for the next frame (two take turns while a frame is in flight).
    spare: Option<wgpu::Buffer>,
    /// Bytes per row of the readback and of the image in the segment (a multiple of 256).
    stride: u32,
}

/// The offscreen target and the shared memory a frame goes through.
pub(super) struct ShmPresenter {
    conn: RustConnection,
    window: xproto::Window,
    gc: xproto::Gcontext,
    depth: u8,
    /// Colour target the lab draws the next frame in (the next segment's, presenting directly).
    pub color: wgpu::TextureView,
    /// Depth target.
    pub depth_target: wgpu::TextureView,
    /// A frame submitted but not shown yet (unpaced drawing).
    in_flight: Option<InFlight>,
    /// Target size.
    pub width: u32,
    /// Target size.
    pub height: u32,
    /// Segments in turn, whether the server may still be reading each, and the next one.
    segments: [Segment; SEGMENTS],
    pending: [bool; SEGMENTS],
    next: usize,
    /// The copying path, where frames are not drawn in the segments (`None`: every segment
    /// has its target).
    copying: Option<Copying>,
    /// The device, to wait on dropping for a frame the GPU may still be writing into a segment.
    device: wgpu::Device,
    /// The server refused a request (say, a put into a window another program destroyed). A
    /// refused put never completes, so its `pending` flag can no longer be trusted.
    refused: bool,
    /// What was refused was the window itself: another program destroyed it.
    window_gone: bool,
}

/// How long dropping the presenter waits for the server to finish its last puts.
const DROP_WAIT: Duration = Duration::from_secs(1);

/// A frame on its way: where it is, its submission and its size.
struct InFlight {
    to: Destination,
    submission: wgpu::SubmissionIndex,
    width: u32,
    height: u32,
}

/// Where a frame is on its way to the window.
enum Destination {
    /// A readback buffer (rows of `stride` bytes), copied into a segment when shown.
    Readback { buffer: wgpu::Buffer, stride: u32 },
    /// Segment `k` itself; the flag says when the GPU has finished the frame.
    Segment(usize, Arc<AtomicBool>),
}

/// Why the presenter is not used (said once on stderr with `SHADERLAB_PRESENT=shm`).
type Why = String;

fn x<E: std::fmt::Display>(what: &str) -> impl FnOnce(E) -> Why + '_ {
    move |e| format!("{what}: {e}")
}

impl ShmPresenter {
    /// The colour format it draws in.
    pub(super) const FORMAT: wgpu::TextureFormat = FORMAT;

    /// A presenter for `window` if this adapter, display and visual allow it; otherwise why not.
    pub(super) fn new(gpu: &Gpu, window: &Arc<Window>, width: u32, height: u32) -> Result<Self, Why> {
        let asked = std::env::var("SHADERLAB_PRESENT");
        match asked.as_deref() {
            Ok("swapchain") => return Err("SHADERLAB_PRESENT=swapchain".into()),
            Ok("shm" | "shm-copy") => {}
            _ if gpu.adapter.get_info().device_type != wgpu::DeviceType::Cpu => {
                return Err("the adapter is not a CPU one".into())
            }
            _ => {}
        }
        let window_id = match window.window_handle().map_err(x("window handle"))?.as_raw() {
            RawWindowHandle::Xlib(h) => h.window as u32,
            RawWindowHandle::Xcb(h) => h.window.get(),
            _ => return Err("not an X11 window".into()),
        };
        let (conn, _) = x11rb::connect(None).map_err(x("connecting to the X server"))?;
        if conn
            .extension_information(shm::X11_EXTENSION_NAME)
            .map_err(x("MIT-SHM"))?
            .is_none()
        {
            return Err("the X server has no MIT-SHM".into());
        }
        conn.shm_query_version()
            .map_err(x("MIT-SHM"))?
            .reply()
            .map_err(x("MIT-SHM"))?;
        let geometry = conn
            .get_geometry(window_id)
            .map_err(x("window geometry"))?
            .reply()
            .map_err(x("window geometry"))?;
        let attributes = conn
            .get_window_attributes(window_id)
            .map_err(x("window attributes"))?
            .reply()
            .map_err(x("window attributes"))?;
        let setup = conn.setup();
        if setup.image_byte_order != xproto::ImageOrder::LSB_FIRST {
            return Err("the X server is big-endian".into());
        }
        let depth = geometry.depth;
        let format_ok = setup
            .pixmap_formats
            .iter()
            .any(|f| f.depth == depth && f.bits_per_pixel == 32 && f.scanline_pad == 32);
        let visual_ok = setup
            .roots
            .iter()
            .flat_map(|screen| &screen.allowed_depths)
            .filter(|d| d.depth == depth)
            .flat_map(|d| &d.visuals)
            .any(|v| {
                v.visual_id == attributes.visual
                    && v.class == xproto::VisualClass::TRUE_COLOR
                    && (v.red_mask, v.green_mask, v.blue_mask) == (0xff0000, 0xff00, 0xff)
            });
        if !(format_ok && visual_ok && (depth == 24 || depth == 32)) {
            return Err(format!("the window's visual (depth {depth}) is not 32-bit BGRX"));
        }
        let gc = conn.generate_id().map_err(x("X ids"))?;
        conn.create_gc(gc, window_id, &xproto::CreateGCAux::new().graphics_exposures(0))
            .map_err(x("GC"))?
            .check()
            .map_err(x("GC"))?;
        let direct = if asked.as_deref() == Ok("shm-copy") {
            Err("SHADERLAB_PRESENT=shm-copy".to_owned())
        } else if !gpu.host_memory {
            Err("the device does not import host memory".to_owned())
        } else {
            segments(&conn, Layout::Direct(&gpu.device, width, height))
        };
        let made = match direct {
            Ok(segments) => match color_of(&segments[0]) {
                Ok(color) => Ok((segments, color, None)),
                Err(e) => {
                    release_all(&conn, segments);
                    Err(e)
                }
            },
            Err(why) => {
                let (texture, color, readback, stride) = targets(gpu, width, height);
                segments(&conn, Layout::Copied(stride as usize * height as usize)).map(|segments| {
                    let copying = Copying {
                        why,
                        texture,
                        spare: Some(readback),
                        stride,
                    };
                    (segments, color, Some(copying))
                })
            }
        };
        let (segments, color, copying) = match made {
            Ok(made) => made,
            Err(e) => {
                let _ = conn.free_gc(gc);
                let _ = conn.flush();
                return Err(e);
            }
        };
        Ok(ShmPresenter {
            conn,
            window: window_id,
            gc,
            depth,
            color,
            depth_target: depth_texture(&gpu.device, width, height),
            in_flight: None,
            width,
            height,
            segments,
            pending: [false; SEGMENTS],
            next: 0,
            copying,
            device: gpu.device.clone(),
            refused: false,
            window_gone: false,
        })
    }

    /// Waits for the server's completion event of segment `k` (errors of earlier puts too).
    fn wait_for(&mut self, k: usize) -> Result<(), Why> {
        while self.pending[k] {
            let event = self.conn.wait_for_event().map_err(x("X events"))?;
            self.handle(event)?;
        }
        Ok(())
    }

    /// Like [`Self::wait_for`], but gives up at `deadline`, or at once after a refusal (whose put
    /// never completes). For dropping the presenter, where waiting is only politeness: the
    /// server handles requests in order, so it has finished a put before it sees the detach
    /// that follows, and the memory lives until both sides have detached.
    fn wait_until(&mut self, k: usize, deadline: Instant) -> Result<(), Why> {
        while self.pending[k] && !self.refused {
            match self.conn.poll_for_event().map_err(x("X events"))? {
                Some(event) => self.handle(event)?,
                None if Instant::now() >= deadline => return Err("no completion from the X server".into()),
                None => std::thread::sleep(Duration::from_millis(2)),
            }
        }
        Ok(())
    }

    /// Notes a completion; an X error is the presenter's failure.
    fn handle(&mut self, event: x11rb::protocol::Event) -> Result<(), Why> {
        match event {
            x11rb::protocol::Event::ShmCompletion(done) => {
                for (k, segment) in self.segments.iter().enumerate() {
                    if segment.seg == done.shmseg {
                        self.pending[k] = false;
                    }
                }
                Ok(())
            }
            x11rb::protocol::Event::Error(e) => {
                self.refused = true;
                let gone = matches!(
                    e.error_kind,
                    x11rb::protocol::ErrorKind::Drawable | x11rb::protocol::ErrorKind::Window
                );
                if gone && e.bad_value == self.window {
                    self.window_gone = true;
                    return Err("the window is gone".into());
                }
                Err(format!("the X server refused a frame: {e:?}"))
            }
            _ => Ok(()),
        }
    }

    /// Why frames are copied into the shared memory rather than drawn there (`None`: drawn
    /// there).
    pub(super) fn copying(&self) -> Option<&str> {
        self.copying.as_ref().map(|c| c.why.as_str())
    }

    /// Whether the presenter failed because its window no longer exists (another program
    /// destroyed it): the window is then gone ([`super::gone`]) and ends with its message.
    pub(super) fn window_gone(&self) -> bool {
        self.window_gone
    }

    /// Follows a resize: new targets and, where the frame no longer fits (or each segment
    /// holds its target), new segments.
    pub(super) fn resize(&mut self, gpu: &Gpu, width: u32, height: u32) -> Result<(), Why> {
        self.flush(gpu)?;
        if self.copying.is_none() {
            for k in 0..SEGMENTS {
                self.wait_for(k)?;
                let segment = Segment::new(&self.conn, Layout::Direct(&self.device, width, height))?;
                std::mem::replace(&mut self.segments[k], segment).release(&self.conn);
            }
            self.color = color_of(&self.segments[self.next])?;
        } else {
            let (texture, color, readback, stride) = targets(gpu, width, height);
            let needed = stride as usize * height as usize;
            for k in 0..SEGMENTS {
                if needed > self.segments[k].size {
                    self.wait_for(k)?;
                    let segment = Segment::new(&self.conn, Layout::Copied(needed))?;
                    std::mem::replace(&mut self.segments[k], segment).release(&self.conn);
                }
            }
            if let Some(c) = self.copying.as_mut() {
                (c.texture, c.spare, c.stride) = (texture, Some(readback), stride);
            }
            self.color = color;
        }
        self.depth_target = depth_texture(&gpu.device, width, height);
        (self.width, self.height) = (width, height);
        Ok(())
    }

    /// Finishes a frame the lab recorded into `encoder` (drawing into [`Self::color`]) and
    /// submits it: drawn in a segment already, or copied to a readback buffer. With `pipelined`
    /// the frame stays in flight and the one before it is shown now, while this one renders (one
    /// frame of latency, for drawing as fast as possible); otherwise it is shown before this
    /// returns.
    pub(super) fn present(&mut self, gpu: &Gpu, mut encoder: wgpu::CommandEncoder, pipelined: bool) -> Result<(), Why> {
        let (width, height) = (self.width, self.height);
        let (to, submission) = match self.copying.as_mut() {
            None => {
                // Drawn in segment `next`: the server must have finished reading it before the
                // GPU draws there.
                let k = self.next;
                self.wait_for(k)?;
                let submission = gpu.queue.submit([encoder.finish()]);
                let done = Arc::new(AtomicBool::new(false));
                let flag = done.clone();
                gpu.queue
                    .on_submitted_work_done(move || flag.store(true, Ordering::Release));
                self.next = (k + 1) % SEGMENTS;
                self.color = color_of(&self.segments[self.next])?;
                (Destination::Segment(k, done), submission)
            }
            Some(copying) => {
                let stride = copying.stride;
                let buffer = match copying.spare.take() {
                    Some(buffer) => buffer,
                    None => targets_buffer(gpu, stride, height),
                };
                crate::gpu::targets::copy_to_buffer(&mut encoder, &copying.texture, &buffer, stride, (width, height));
                let submission = gpu.queue.submit([encoder.finish()]);
                (Destination::Readback { buffer, stride }, submission)
            }
        };
        let frame = InFlight {
            to,
            submission,
            width,
            height,
        };
        if let Some(previous) = self.in_flight.replace(frame) {
            self.show(gpu, previous)?;
        }
        if !pipelined {
            self.flush(gpu)?;
        }
        Ok(())
    }

    /// Shows the frame still in flight, if any.
    pub(super) fn flush(&mut self, gpu: &Gpu) -> Result<(), Why> {
        match self.in_flight.take() {
            Some(frame) => self.show(gpu, frame),
            None => Ok(()),
        }
    }

    /// Waits for `frame` and puts it in the window, copying it into the free segment first if
    /// it went to a readback buffer.
    fn show(&mut self, gpu: &Gpu, frame: InFlight) -> Result<(), Why> {
        let wait = wgpu::PollType::Wait {
            submission_index: Some(frame.submission.clone()),
            timeout: gpu.watchdog,
        };
        // A frame that never ends (a shader looping for ever) marks the device hung.
        let waited = |e: wgpu::PollError| gpu.wait_error(e).to_string();
        let (k, offset, stride) = match frame.to {
            Destination::Segment(k, done) => {
                // Ready when its submission is done: poll for that briefly, then block (see
                // Gpu::poll_then_wait).
                gpu.poll_then_wait(|_| done.load(Ordering::Acquire), wait)
                    .map_err(waited)?;
                let target = self.segments[k].target.as_ref().ok_or("a segment without its target")?;
                (k, target.offset, target.stride)
            }
            Destination::Readback { buffer, stride } => {
                let bytes = stride as usize * frame.height as usize;
                let k = self.next;
                self.wait_for(k)?;
                if bytes > self.segments[k].size {
                    return Err("a frame larger than its segment".into());
                }
                let slice = buffer.slice(..bytes as u64);
                let mapped = Arc::new(AtomicBool::new(false));
                let flag = mapped.clone();
                slice.map_async(wgpu::MapMode::Read, move |_| flag.store(true, Ordering::Release));
                // The frame is ready when its buffer is mapped: poll for that briefly, then
                // block (see Gpu::poll_then_wait).
                gpu.poll_then_wait(|_| mapped.load(Ordering::Acquire), wait)
                    .map_err(waited)?;
                {
                    let mapped = slice.get_mapped_range().map_err(x("reading the frame"))?;
                    // SAFETY: the segment is `size >= bytes` bytes mapped here for the
                    // presenter's life, and its completion event says the server has finished
                    // reading it.
                    let dst = unsafe { std::slice::from_raw_parts_mut(self.segments[k].addr, bytes) };
                    dst.copy_from_slice(&mapped);
                }
                buffer.unmap();
                self.next = (k + 1) % SEGMENTS;
                let same_size = (frame.width, frame.height) == (self.width, self.height);
                if let Some(copying) = self.copying.as_mut().filter(|c| same_size && c.spare.is_none()) {
                    copying.spare = Some(buffer);
                }
                (k, 0, stride)
            }
        };
        self.conn
            .shm_put_image(
                self.window,
                self.gc,
                (stride / 4) as u16,
                frame.height as u16,
                0,
                0,
                frame.width as u16,
                frame.height as u16,
                0,
                0,
                self.depth,
                xproto::ImageFormat::Z_PIXMAP.into(),
                true,
                self.segments[k].seg,
                offset,
            )
            .map_err(x("ShmPutImage"))?;
        self.conn.flush().map_err(x("X"))?;
        self.pending[k] = true;
        while let Some(event) = self.conn.poll_for_event().map_err(x("X events"))? {
            self.handle(event)?;
        }
        Ok(())
    }
}

impl Drop for ShmPresenter {
    fn drop(&mut self) {
        // Never `wait_for` here: after a refused put (the window destroyed under it) the
        // completion it waits for never comes, and closing the window hung for good.
        // Every frame drawn in a segment must be finished before the segments go: lavapipe
        // would draw into memory no longer mapped. (A CPU driver's frame always ends.)
        if crate::gpu::hung() {
            // The frame never ends and still draws into the segments: leave them mapped (the
            // process ends without waiting for it, see crate::gpu::hung).
            return;
        }
        if self.copying.is_none() {
            let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
        }
        let deadline = Instant::now() + DROP_WAIT;
        for k in 0..SEGMENTS {
            let _ = self.wait_until(k, deadline);
            let segment = std::mem::replace(
                &mut self.segments[k],
                Segment {
                    seg: 0,
                    addr: std::ptr::null_mut(),
                    size: 0,
                    target: None,
                },
            );
            segment.release(&self.conn);
        }
        let _ = self.conn.free_gc(self.gc);
        let _ = self.conn.flush();
    }
}

/// The colour texture (`FORMAT`, copyable) frames are copied from, its view, and a readback
/// buffer with its row stride.
fn targets(gpu: &Gpu, width: u32, height: u32) -> (wgpu::Texture, wgpu::TextureView, wgpu::Buffer, u32) {
    let (texture, color) = copyable_color(&gpu.device, "shaderlab.shm.color", width, height, FORMAT);
    let stride = padded_row(4, width);
    (texture, color, targets_buffer(gpu, stride, height), stride)
}

/// A readback buffer for `height` rows of `stride` bytes.
fn targets_buffer(gpu: &Gpu, stride: u32, height: u32) -> wgpu::Buffer {
    readback_buffer(&gpu.device, "shaderlab.shm.readback", stride, height)
}

/// What a segment holds.
#[derive(Clone, Copy)]
enum Layout<'a> {
    /// Frames of this many bytes, copied in.
    Copied(usize),
    /// A colour target of this size, made on this device (which imports host memory).
    Direct(&'a wgpu::Device, u32, u32),
}

/// [`SEGMENTS`] segments (see [`Segment::new`]); none if one fails.
fn segments(conn: &RustConnection, layout: Layout<'_>) -> Result<[Segment; SEGMENTS], Why> {
    let mut made = Vec::with_capacity(SEGMENTS);
    for _ in 0..SEGMENTS {
        match Segment::new(conn, layout) {
            Ok(segment) => made.push(segment),
            Err(e) => {
                for segment in made {
                    segment.release(conn);
                }
                return Err(e);
            }
        }
    }
    made.try_into().map_err(|_| "segments".to_owned())
}

/// Releases every segment.
fn release_all(conn: &RustConnection, segments: [Segment; SEGMENTS]) {
    for segment in segments {
        segment.release(conn);
    }
}

/// The colour target in `segment`.
fn color_of(segment: &Segment) -> Result<wgpu::TextureView, Why> {
    segment
        .target
        .as_ref()
        .map(|t| t.color.clone())
        .ok_or_else(|| "a segment without its target".to_owned())
}

impl Segment {
    /// A private segment attached here and by the server, and marked for removal at once (it
    /// goes away when both have detached, even if the process dies), holding what `layout` says.
    fn new(conn: &RustConnection, layout: Layout<'_>) -> Result<Self, Why> {
        let (device, width, height) = match layout {
            Layout::Copied(size) => return Self::attached(conn, size),
            Layout::Direct(device, width, height) => (device, width, height),
        };
        let mut made = None;
        // SAFETY: the segment stays attached here until `release`, which drops the target
        // first; the presenter waits for the server before the GPU draws in a segment, for the
        // GPU before the server reads it, and for both before the segment goes.
        let target = unsafe {
            crate::gpu::host_memory::target(device, width, height, FORMAT, "shaderlab.shm.segment", |size| {
                let segment = Self::attached(conn, size)?;
                let addr = segment.addr;
                made = Some(segment);
                Ok(addr)
            })
        };
        let (target, segment) = match (target, made) {
            (Ok(target), Some(segment)) => (target, segment),
            (Ok(_), None) => return Err("a target without its segment".into()),
            (Err(e), made) => {
                if let Some(segment) = made {
                    segment.release(conn);
                }
                return Err(e);
            }
        };
        let rows = target.row_pitch.checked_mul(u64::from(height));
        let fits = rows
            .and_then(|r| r.checked_add(target.offset))
            .is_some_and(|end| end <= segment.size as u64);
        let (Ok(offset), Ok(stride)) = (u32::try_from(target.offset), u32::try_from(target.row_pitch)) else {
            segment.release(conn);
            return Err("a target too large for an X image".into());
        };
        // X takes rows of whole 32-bit pixels, at most 65535 of them.
        if !fits || stride % 4 != 0 || stride / 4 > u32::from(u16::MAX) || stride / 4 < width {
            segment.release(conn);
            return Err(format!(
                "a target whose rows X cannot take (offset {offset}, {stride} bytes a row)"
            ));
        }
        Ok(Segment {
            target: Some(Target {
                color: target.texture.create_view(&wgpu::TextureViewDescriptor {
                    label: Some("shaderlab.shm.segment"),
                    ..Default::default()
                }),
                _texture: target.texture,
                offset,
                stride,
            }),
            ..segment
        })
    }

    /// A segment of `size` bytes, attached here and by the server.
    fn attached(conn: &RustConnection, size: usize) -> Result<Self, Why> {
        // SAFETY: plain System V calls; every failure is checked and undone.
        unsafe {
            let id = libc::shmget(libc::IPC_PRIVATE, size, libc::IPC_CREAT | 0o600);
            if id < 0 {
                return Err(format!("shmget: {}", std::io::Error::last_os_error()));
            }
            let addr = libc::shmat(id, std::ptr::null(), 0);
            if addr as isize == -1 {
                let e = std::io::Error::last_os_error();
                libc::shmctl(id, libc::IPC_RMID, std::ptr::null_mut());
                return Err(format!("shmat: {e}"));
            }
            let attached = conn.generate_id().map_err(x("X ids")).and_then(|seg| {
                conn.shm_attach(seg, id as u32, false)
                    .map_err(x("ShmAttach"))?
                    .check()
                    .map_err(x("ShmAttach (is the X server on another machine?)"))?;
                Ok(seg)
            });
            libc::shmctl(id, libc::IPC_RMID, std::ptr::null_mut());
            match attached {
                Ok(seg) => Ok(Segment {
                    seg,
                    addr: addr.cast(),
                    size,
                    target: None,
                }),
                Err(e) => {
                    libc::shmdt(addr);
                    Err(e)
                }
            }
        }
    }

    /// Detaches the server and this process (after dropping the target, if any).
    fn release(mut self, conn: &RustConnection) {
        drop(self.target.take());
        if self.addr.is_null() {
            return;
        }
        let _ = conn.shm_detach(self.seg);
        let _ = conn.flush();
        // SAFETY: `addr` came from shmat and is not used after this.
        unsafe {
            libc::shmdt(self.addr.cast());
        }
    }
}
