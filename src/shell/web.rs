//! The browser's shell: what the window is natively, for a page. The page (`web/index.html`,
//! built by `scripts/web`) owns the DOM: it lists the labs, builds the controls from
//! [`WebApp::params`] (the F1 panel's model, [`super::panel::widgets`]: each parameter's
//! control and group, from the same [`ParamSpec`](crate::params::ParamSpec)s as `--set`,
//! `--help` and the keys), forwards keys and mouse on the canvas, and drives [`WebApp::frame`]
//! from `requestAnimationFrame` while [`WebApp::wants_frame`]. What the lab, its clock, its keys
//! and its mouse do is the [`Session`]'s, shared with the window, so no lab and no rule has a
//! second copy for the web.
//!
//! Differences from the native shell, all forced by the browser: start-up is async (no
//! blocking on the GPU), there are no files (shaders are built in, edits live in memory as
//! [`ShaderSource::Edited`], user files come from the page as bytes), the inspector's replay
//! runs inline (no threads: [`super::inspector::inline`]) and read-backs are mapped
//! asynchronously (polled from the animation frames), and a validation error on WebGPU
//! reaches the console rather than a `Result` ([`Gpu::checked`]). The canvas's surface is a
//! [`Swapchain`], as the window's is.
//!
//! Results cross to JavaScript as JSON text, written with `serde_json` (as the debugger's
//! `--json` is): the labs, the parameters' controls, errors as `{"error": "..."}` and the
//! inspector's report (`Inspection::json`).

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::rc::Rc;
use std::sync::Arc;

use wasm_bindgen::prelude::*;

use crate::gpu::Gpu;
use crate::lab::{UserFile, UserFiles};
use crate::offscreen::Offscreen;
use crate::params::Kind;
use crate::shader::{embedded_source, ShaderSource};

use super::panel::{widgets, Control};
use super::session::{Button, Outcome, Platform, Session, Sources, Target};
use super::surface::{Acquired, Swapchain};
use super::views::Wanted;

/// The course's seed-000 GLSL 1.10 files (the five exercises of Lab05, as the tests run them:
/// the two syntax errors of the printed course mended, `assets/course/seed000-mended`), for
/// `legacy` on the page: loaded and editable without any upload.
const COURSE: &[(&str, &str)] = &[
    ("lab1.vert", include_str!("../../assets/course/seed000/lab1.vert")),
    ("lab1.frag", include_str!("../../assets/course/seed000/lab1.frag")),
    ("lab2.vert", include_str!("../../assets/course/seed000/lab2.vert")),
    ("lab2.frag", include_str!("../../assets/course/seed000/lab2.frag")),
    ("lab3.vert", include_str!("../../assets/course/seed000/lab3.vert")),
    ("lab3.frag", include_str!("../../assets/course/seed000/lab3.frag")),
    ("lab4.vert", include_str!("../../assets/course/seed000/lab4.vert")),
    (
        "lab4.frag",
        include_str!("../../assets/course/seed000-mended/lab4.frag"),
    ),
    (
        "lab5.vert",
        include_str!("../../assets/course/seed000-mended/lab5.vert"),
    ),
    ("lab5.frag", include_str!("../../assets/course/seed000/lab5.frag")),
];

/// `legacy`'s built-in pair, by the names its messages use.
const LEGACY_DEFAULT: [&str; 2] = ["legacy/default.vert", "legacy/default.frag"];

/// The largest file the page may hand over (a model or a picture): the native loaders' caps
/// are per kind and smaller; this one only keeps a wrong pick (a video) out of memory.
const MAX_FILE_BYTES: usize = 64 << 20;

/// An error as the page's JSON answers carry it: `{"error": "..."}`.
fn json_error(e: impl std::fmt::Display) -> String {
    serde_json::json!({ "error": e.to_string() }).to_string()
}

/// A list of strings as JSON.
fn json_list<'a>(items: impl IntoIterator<Item = &'a str>) -> String {
    serde_json::Value::from_iter(items).to_string()
}

fn js_error(e: impl std::fmt::Display) -> JsValue {
    JsValue::from_str(&e.to_string())
}

/// Every lab, in the list's order, as JSON: `name`, `title`, `label`, `lecture`, `width`,
/// `height`, `keys` (the help text of its keys).
#[wasm_bindgen]
pub fn labs() -> String {
    let items: Vec<serde_json::Value> = crate::course::ALL
        .iter()
        .map(|e| {
            let i = e.info;
            serde_json::json!({
                "name": i.name, "title": i.original_title, "label": i.label, "lecture": i.lecture,
                "width": i.size.0, "height": i.size.1, "keys": i.keys.help(),
            })
        })
        .collect();
    serde_json::Value::from(items).to_string()
}

/// The course's GLSL 1.10 files built into the page (`lab1.vert` … `lab5.frag`), as JSON.
#[wasm_bindgen]
pub fn course_files() -> String {
    json_list(COURSE.iter().map(|(name, _)| *name))
}

/// The state seed 000's program sets for the course pair whose vertex shader is `vert`
/// (`lab3.vert`), one `name=value` per line ("" for other files): the page applies it when a
/// course pair is picked, so the pair draws the original's picture.
#[wasm_bindgen]
pub fn course_state(vert: &str) -> String {
    let lab = vert
        .strip_prefix("lab")
        .and_then(|rest| rest.strip_suffix(".vert"))
        .and_then(|n| n.parse().ok())
        .filter(|_| COURSE.iter().any(|(name, _)| *name == vert));
    let state = lab.map(crate::course::legacy::course_state).unwrap_or(&[]);
    state
        .iter()
        .map(|(k, v)| format!("{k}={v}"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// Starts the page's GPU on `canvas`: `backend` is `webgpu`, `webgl2`, or `auto` (WebGPU when
/// the browser offers an adapter, WebGL2 otherwise). Opens no lab yet ([`WebApp::open`]).
#[wasm_bindgen]
pub async fn start(canvas: web_sys::HtmlCanvasElement, backend: String) -> Result<WebApp, JsValue> {
    std::panic::set_hook(Box::new(|info| {
        web_sys::console::error_1(&JsValue::from_str(&info.to_string()))
    }));
    let backends = match backend.as_str() {
        "webgpu" => wgpu::Backends::BROWSER_WEBGPU,
        "webgl2" => wgpu::Backends::GL,
        "" | "auto" => wgpu::Backends::BROWSER_WEBGPU | wgpu::Backends::GL,
        other => {
            return Err(js_error(format!(
                "unknown backend `{other}`; valid: auto, webgpu, webgl2"
            )))
        }
    };
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
    desc.backends = backends;
    let instance = wgpu::util::new_instance_with_webgpu_detection(desc).await;
    let surface = instance
        .create_surface(wgpu::SurfaceTarget::Canvas(canvas.clone()))
        .map_err(|e| js_error(format!("cannot draw on the canvas with {backend}: {e}")))?;
    let gpu = Gpu::new(instance, Some(&surface)).await.map_err(js_error)?;
    super::surface::on_trouble(&gpu, |trouble| {
        web_sys::console::error_1(&JsValue::from_str(&trouble.to_string()))
    });
    let size = (canvas.width(), canvas.height());
    let screen = Swapchain::new(&gpu, "the canvas", surface, size, &[]).map_err(js_error)?;
    let texts = COURSE.iter().map(|(n, t)| (n.to_string(), t.to_string())).collect();
    Ok(WebApp {
        gpu,
        screen,
        canvas,
        open: None,
        texts,
        files: UserFiles::default(),
        now: 0.0,
        error: None,
        reading: None,
        inspection: String::new(),
    })
}

/// The page's GPU, canvas and lab.
#[wasm_bindgen]
pub struct WebApp {
    gpu: Gpu,
    /// The canvas's surface and depth buffer.
    screen: Swapchain,
    canvas: web_sys::HtmlCanvasElement,
    /// The lab on the page.
    open: Option<Session>,
    /// Shader texts edited on the page and the course's files, by file name, over the
    /// built-in shaders (kept across labs: an edited `#include` serves every lab using it).
    texts: BTreeMap<String, String>,
    /// Pictures and models the page handed over, and `legacy`'s pair.
    files: UserFiles,
    /// The page's clock, seconds (the last [`WebApp::frame`]).
    now: f64,
    /// The last error found while drawing, until the page takes it.
    error: Option<String>,
    /// A picture being read back ([`WebApp::read_start`]), and whether it is mapped yet.
    reading: Option<(Offscreen, Rc<RefCell<Option<Result<(), String>>>>)>,
    /// The last inspection as JSON ("" before one).
    inspection: String,
}

#[wasm_bindgen]
impl WebApp {
    /// `WebGPU` or `WebGL2`, and the adapter's name.
    pub fn backend(&self) -> String {
        let info = self.gpu.adapter.get_info();
        let api = match info.backend {
            wgpu::Backend::BrowserWebGpu => "WebGPU",
            wgpu::Backend::Gl => "WebGL2",
            other => return format!("{other:?}"),
        };
        if info.name.is_empty() {
            api.to_owned()
        } else {
            format!("{api} ({})", info.name)
        }
    }

    /// Opens lab `name` at the canvas size of the lab, then sets `sets` (lines `name=value`,
    /// as `--set`; `legacy` also takes `files=VERT,FRAG`, names of the course's files or of
    /// files handed over by [`WebApp::add_file`]). Returns the sets that were refused, one
    /// message per line ("" when all were taken); a lab that cannot be built is an error and
    /// the previous lab stays.
    pub fn open(&mut self, name: &str, sets: &str, paused: bool) -> Result<String, JsValue> {
        let entry = crate::course::find(name).ok_or_else(|| {
            let names: Vec<&str> = crate::course::ALL.iter().map(|e| e.info.name).collect();
            js_error(format!("no lab `{name}`; labs: {}", names.join(", ")))
        })?;
        let mut refused = Vec::new();
        let mut assignments = Vec::new();
        for line in sets.lines().map(str::trim).filter(|l| !l.is_empty()) {
            match line.split_once('=') {
                Some(("files", list)) if entry.info.files.named_textures => {
                    let pair: Vec<PathBuf> = list.split(',').map(|s| PathBuf::from(s.trim())).collect();
                    let missing: Vec<String> = pair
                        .iter()
                        .map(|p| p.to_string_lossy().into_owned())
                        .filter(|p| !self.texts.contains_key(p))
                        .collect();
                    if pair.len() != 2 {
                        refused.push(format!("files={list}: legacy takes two files, VERT,FRAG"));
                    } else if !missing.is_empty() {
                        refused.push(format!(
                            "files={list}: no file {}; the page has {}",
                            missing.join(", "),
                            self.texts.keys().cloned().collect::<Vec<_>>().join(", ")
                        ));
                    } else {
                        self.files.inputs = pair;
                    }
                }
                Some((key, value)) => assignments.push((key.trim().to_owned(), value.trim().to_owned())),
                None => refused.push(format!("`{line}`: expected name=value")),
            }
        }
        if !entry.info.files.named_textures {
            self.files.inputs.clear();
        }
        let source = self.shader_source();
        let sources = Sources::new(source, self.files.clone(), self.screen.format());
        let session = Session::open(entry, &self.gpu, sources, Platform::PAGE, self.now, 1.0).map_err(js_error)?;
        let (width, height) = entry.info.size;
        self.resize(width, height);
        let mut session = if paused { session.paused() } else { session };
        for (key, value) in assignments {
            if let Err(e) = session.set(&key, &value) {
                refused.push(e.to_string());
            }
        }
        self.open = Some(session);
        self.error = None;
        self.inspection.clear();
        Ok(refused.join("\n"))
    }

    /// The open lab's name.
    pub fn lab(&self) -> String {
        self.open.as_ref().map(|o| o.name().to_owned()).unwrap_or_default()
    }

    /// The window title of the native shell: the original's, then the state.
    pub fn title(&self) -> String {
        self.open.as_ref().map(Session::title).unwrap_or_default()
    }

    /// Draws one frame at the page's time `now_ms` (`performance.now()`): the clock of an
    /// animated lab follows it.
    pub fn frame(&mut self, now_ms: f64) {
        self.now = now_ms / 1000.0;
        let Some(open) = self.open.as_mut() else {
            return;
        };
        let frame = match self.screen.acquire() {
            Acquired::Frame(frame) => frame,
            Acquired::Outdated | Acquired::Lost => {
                self.screen.resize(&self.gpu, self.screen.size());
                open.skipped(self.now);
                return;
            }
            Acquired::Skipped | Acquired::Invalid => {
                open.skipped(self.now);
                return;
            }
        };
        let color = frame.texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some("web.frame"),
            ..Default::default()
        });
        let mut encoder = self.gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("web.frame"),
        });
        let target = Target {
            color: &color,
            depth: self.screen.depth(),
            size: self.screen.size(),
        };
        let Outcome { error, .. } = open.frame(&self.gpu, &mut encoder, &target, self.now);
        self.gpu.queue.submit([encoder.finish()]);
        self.gpu.queue.present(frame);
        if let Some(e) = error {
            self.error = Some(e.to_string());
        }
    }

    /// Whether the lab's clock runs (an animated lab, not paused): its title changes every
    /// frame.
    pub fn animated(&self) -> bool {
        self.open.as_ref().is_some_and(Session::animated)
    }

    /// Whether a frame should be drawn now: the lab animates, or something changed (the page
    /// draws from `requestAnimationFrame` only then).
    pub fn wants_frame(&self) -> bool {
        self.open.as_ref().is_some_and(Session::wants_frame)
    }

    /// Turns inspect mode on or off (the page's Inspect button, F2); returns whether it is on.
    /// On, a click on the canvas picks the pixel to inspect ([`Session::button`]).
    pub fn inspect_toggle(&mut self) -> bool {
        let Some(open) = self.open.as_mut() else {
            return false;
        };
        open.toggle_inspect();
        if !open.inspecting() {
            self.inspection.clear();
        }
        open.inspecting()
    }

    /// Inspects pixel (x, y) of the canvas (a link's `inspect=X,Y`).
    pub fn inspect_at(&mut self, x: u32, y: u32) {
        if let Some(open) = self.open.as_mut() {
            open.inspect_pixel(Some((x, y)));
        }
    }

    /// The pixel inspected as `X,Y` (for the link), or "".
    pub fn inspected(&self) -> String {
        self.open
            .as_ref()
            .and_then(Session::inspected)
            .map(|(x, y)| format!("{x},{y}"))
            .unwrap_or_default()
    }

    /// The latest inspection of the inspected pixel as JSON ([`crate::debug::Inspection::json`]:
    /// `pixel`, `covered`, `listing`, `trace`, ...; `{"error": ...}` when it could not be
    /// replayed), "" before the first. Call it every animation frame while inspecting: it
    /// takes a new capture when the lab changed since the last one, and moves the capture's
    /// read-back on (a browser cannot wait for it).
    ///
    /// The capture is the lab's frame recorded again offscreen at the canvas's size, with its
    /// draws written down, rather than the frame on the canvas: the same state draws the same
    /// picture, and a page whose canvas cannot be presented (headless Chromium's WebGPU) can
    /// still be inspected.
    pub fn inspection(&mut self) -> String {
        let Some(open) = self.open.as_mut() else {
            return self.inspection.clone();
        };
        // The page has no threads: the replay runs here, once the read-back is done.
        if open.poll(&self.gpu, self.screen.size()).inspection {
            self.inspection = match open.inspection() {
                Some(Ok(i)) => i.json(),
                Some(Err(e)) => json_error(e),
                None => String::new(),
            };
        }
        self.inspection.clone()
    }

    /// Something on the page changed what is shown (a control, a resize): draw again.
    pub fn changed(&mut self) {
        if let Some(open) = self.open.as_mut() {
            open.touched();
        }
    }

    /// A key pressed on the canvas, by the DOM's `KeyboardEvent.key` ([`Session::key`]: the
    /// arrows and Page Up/Down are GLUT's special keys, Space pauses an animated lab's clock,
    /// any other single character is the original's keyboard callback). Returns whether the lab
    /// took it (the page then keeps the browser from scrolling).
    pub fn key(&mut self, key: &str) -> bool {
        let now = self.now;
        self.open.as_mut().is_some_and(|o| o.key(key, now))
    }

    /// The mouse on the canvas, in canvas pixels from the top left: `down` and `up` of
    /// `button` (the DOM's `MouseEvent.button`), `move`; the rule is the window's
    /// ([`Session::button`]: a move drags while any button is held). Returns whether the lab's
    /// state changed.
    pub fn pointer(&mut self, kind: &str, button: i32, x: i32, y: i32) -> bool {
        let Some(open) = self.open.as_mut() else {
            return false;
        };
        match kind {
            "down" => {
                open.moved(x, y);
                open.button(Button::from_dom(button), true)
            }
            "up" => {
                open.moved(x, y);
                open.button(Button::from_dom(button), false)
            }
            "move" => open.moved(x, y),
            _ => false,
        }
    }

    /// The lab's parameters as JSON, in the panel's order ([`super::panel::widgets`]: by group,
    /// declaration order within one): per parameter `name`, `group` (its heading), `control`
    /// (`slider`, `drag`, `whole`, `check`, `choice`, `colour`: the window panel's control for
    /// it), `kind` (`real`, `int`, `bool`, `choice`), `options` (a choice's names), `min`, `max`,
    /// `help`, `value` (as `--set` writes it), `values` (the numbers), `default` and `sliders`
    /// (per component, the `[min, max]` its slider spans, or null: see
    /// [`super::panel::Widget::sliders`]).
    pub fn params(&self) -> String {
        let Some(open) = self.open.as_ref() else {
            return "[]".into();
        };
        let p = open.lab().params();
        let items: Vec<serde_json::Value> = widgets(p.specs(), open.entry().info.keys.rows)
            .iter()
            .map(|w| {
                let s = &w.spec;
                let control = match w.control {
                    Control::Slider => "slider",
                    Control::Drag => "drag",
                    Control::Whole => "whole",
                    Control::Check => "check",
                    Control::Choice(_) => "choice",
                    Control::Colour => "colour",
                };
                let (kind, options): (&str, &[&str]) = match s.kind {
                    Kind::Real => ("real", &[]),
                    Kind::Int => ("int", &[]),
                    Kind::Bool => ("bool", &[]),
                    Kind::Choice(names) => ("choice", names),
                };
                // JSON has no infinities: an open bound (±1e30 or so, or infinite) is null.
                serde_json::json!({
                    "name": s.name, "group": w.group.title(), "control": control, "kind": kind,
                    "options": options, "min": s.min, "max": s.max, "help": s.help,
                    "value": p.text(s.name), "values": p.get(s.name).unwrap_or(&[]),
                    "default": s.default_text(),
                    "sliders": (0..p.get(s.name).map_or(0, <[f64]>::len))
                        .map(|c| w.slider(c).map(|(a, b)| [a, b]))
                        .collect::<Vec<_>>(),
                })
            })
            .collect();
        serde_json::Value::from(items).to_string()
    }

    /// Sets a parameter from text, as `--set name=value`; returns the refusal ("" when set).
    pub fn set(&mut self, name: &str, value: &str) -> String {
        match self.open.as_mut() {
            Some(open) => open.set(name, value).err().map(|e| e.to_string()).unwrap_or_default(),
            None => "no lab is open".into(),
        }
    }

    /// The state a link reproduces: `name=value` per line for every parameter away from its
    /// default (the running clock's `time` left out), and `legacy`'s `files=`.
    pub fn state(&self) -> String {
        let Some(open) = self.open.as_ref() else {
            return String::new();
        };
        let p = open.lab().params();
        let running = open.animated();
        let mut lines: Vec<String> = p
            .changed()
            .filter(|(name, _)| !(running && *name == "time"))
            .map(|(name, text)| format!("{name}={text}"))
            .collect();
        if open.entry().info.files.named_textures && !self.files.inputs.is_empty() {
            let names: Vec<String> = self
                .files
                .inputs
                .iter()
                .map(|p| p.to_string_lossy().into_owned())
                .collect();
            lines.insert(0, format!("files={}", names.join(",")));
        }
        lines.join("\n")
    }

    /// The link Copy link gives, as JSON `{"link": …}` or `{"error": …}`: `url` (the page's
    /// address with its state, as `updateUrl()` writes it) and, after `#`, every shader file
    /// that differs from the built-in text, compressed ([`super::link::page_link`]).
    pub fn link(&self, url: &str) -> String {
        let Some(open) = self.open.as_ref() else {
            return json_error("no lab is open");
        };
        let pair: Vec<String> = self
            .files
            .inputs
            .iter()
            .map(|p| p.to_string_lossy().into_owned())
            .collect();
        match super::link::page_link(url, open.entry(), &self.texts, &pair) {
            Ok(link) => serde_json::json!({ "link": link }).to_string(),
            Err(e) => json_error(e),
        }
    }

    /// Takes the shader files a link carries (`url`, with `#files=…`) into the page's texts,
    /// before its lab opens: JSON `{"files": [names]}`, or `{"error": …}` with nothing taken
    /// when the link is damaged, past its limits, or carries a file its lab could not read.
    pub fn open_link(&mut self, url: &str) -> String {
        let texts = &self.texts;
        let checked =
            super::link::Link::parse(url).and_then(|link| link.check(&|name| texts.contains_key(name)).map(|_| link));
        match checked {
            Ok(link) => {
                let names: Vec<&String> = link.files.keys().collect();
                let answer = serde_json::json!({ "files": names }).to_string();
                self.texts.extend(link.files);
                answer
            }
            Err(e) => json_error(e),
        }
    }

    /// Whether the clock is paused (a link then keeps its `time`).
    pub fn paused(&self) -> bool {
        self.open.as_ref().is_some_and(Session::is_paused)
    }

    /// The shader files the open lab draws with (each program's two files and what they
    /// `#include`; `legacy`'s pair), as JSON.
    pub fn files(&mut self) -> String {
        json_list(self.file_names().iter().map(String::as_str))
    }

    /// The text of shader file `name`: as edited on the page, else the built-in one.
    pub fn source(&self, name: &str) -> String {
        self.text(name).unwrap_or_default()
    }

    /// Replaces the text of shader file `name` and recompiles the open lab. Returns the
    /// compiler's message (`file:line:column: message`, the line and a caret) when the text is
    /// broken, "" when it built; a broken text leaves the last good pipeline drawing.
    pub fn edit(&mut self, name: &str, text: &str) -> String {
        self.texts.insert(name.to_owned(), text.to_owned());
        self.reload()
    }

    /// Drops the page's edit of `name` (the built-in text again) and recompiles; as [`edit`](WebApp::edit).
    pub fn revert(&mut self, name: &str) -> String {
        match COURSE.iter().find(|(n, _)| *n == name) {
            Some((n, t)) => {
                self.texts.insert((*n).to_owned(), (*t).to_owned());
            }
            None => {
                self.texts.remove(name);
            }
        }
        self.reload()
    }

    /// Takes a file the user picked: GLSL (`.vert`, `.frag`, `.glsl`, `.vs`, `.fs`) becomes
    /// an editable text by its name (for `legacy`'s `files=`), a picture (`.png`, `.bmp`) the
    /// texture of the labs that sample one, an `.obj` the model of the Suzanne labs. Returns
    /// what became of it; a file that cannot be read is an error naming it.
    pub fn add_file(&mut self, name: &str, bytes: &[u8]) -> Result<String, JsValue> {
        if bytes.len() > MAX_FILE_BYTES {
            return Err(js_error(format!(
                "{name}: {} bytes is more than the page takes ({} MiB)",
                bytes.len(),
                MAX_FILE_BYTES >> 20
            )));
        }
        let lower = name.to_ascii_lowercase();
        let ext = lower.rsplit_once('.').map(|(_, e)| e).unwrap_or("");
        let path = PathBuf::from(name);
        match ext {
            "vert" | "frag" | "glsl" | "vs" | "fs" | "vsh" | "fsh" => {
                let text = String::from_utf8(bytes.to_vec()).map_err(|e| {
                    js_error(format!(
                        "{name}: not UTF-8 text (invalid byte at offset {})",
                        e.utf8_error().valid_up_to()
                    ))
                })?;
                self.texts.insert(name.to_owned(), text);
                Ok(format!("{name}: a shader; legacy draws it with files=VERT,FRAG"))
            }
            "png" | "bmp" => {
                let data = crate::images::decode_image(&path, bytes).map_err(js_error)?;
                self.files.texture = Some(UserFile { path, data });
                Ok(format!(
                    "{name}: the texture of the labs that sample one (reopen the lab)"
                ))
            }
            "obj" => {
                let text = String::from_utf8(bytes.to_vec()).map_err(|e| {
                    js_error(format!(
                        "{name}: not UTF-8 text (invalid byte at offset {})",
                        e.utf8_error().valid_up_to()
                    ))
                })?;
                let data = crate::mesh::obj::parse_obj(name, &text).map_err(js_error)?;
                self.files.model = Some(UserFile { path, data });
                Ok(format!("{name}: the model of the Suzanne labs (reopen the lab)"))
            }
            _ => Err(js_error(format!(
                "{name}: not a file the page knows (GLSL .vert/.frag/.glsl, a .png or .bmp picture, an .obj model)"
            ))),
        }
    }

    /// Draws the lab's picture into a texture and starts reading it back through the API (a
    /// headless browser's WebGPU canvas cannot be read: it has no shared image to copy from).
    /// [`WebApp::read_result`] has the pixels once the browser mapped them.
    pub fn read_start(&mut self) -> Result<(), JsValue> {
        let open = self.open.as_mut().ok_or_else(|| js_error("no lab is open"))?;
        let (width, height) = self.screen.size();
        let target = Offscreen::with_format(&self.gpu, width, height, self.screen.format());
        // As on the canvas: an error is shown once ([`WebApp::take_error`]) and the picture
        // is what the frame drew (the view's, while one is shown).
        let mut encoder = self.gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("web.read"),
        });
        let drawn = Target {
            color: &target.color,
            depth: &target.depth,
            size: (target.width, target.height),
        };
        let error = open.encode(&self.gpu, &mut encoder, &drawn);
        self.gpu.queue.submit([encoder.finish()]);
        if let Some(e) = error {
            self.error = Some(e.to_string());
        }
        let done = Rc::new(RefCell::new(None));
        let slot = done.clone();
        target.request_read(&self.gpu, move |r| {
            *slot.borrow_mut() = Some(r.map_err(|e| e.to_string()));
        });
        self.reading = Some((target, done));
        Ok(())
    }

    /// The picture [`WebApp::read_start`] asked for: RGBA bytes, top row first, at the
    /// canvas size; empty while the browser has not mapped them yet.
    pub fn read_result(&mut self) -> Result<Vec<u8>, JsValue> {
        // WebGL2 runs through wgpu-core, which maps on a poll; WebGPU maps by itself.
        let _ = self.gpu.device.poll(wgpu::PollType::Poll);
        let Some((target, done)) = self.reading.as_ref() else {
            return Err(js_error("no picture is being read (read_start first)"));
        };
        let state = done.borrow_mut().take();
        match state {
            None => Ok(Vec::new()),
            Some(Err(e)) => {
                self.reading = None;
                Err(js_error(format!("reading the picture back: {e}")))
            }
            Some(Ok(())) => {
                let image = target.mapped_rgba().map_err(js_error);
                self.reading = None;
                Ok(image?.into_raw())
            }
        }
    }

    /// Shows the view `text` names in place of the picture (a link's `view=`, a line clicked in
    /// the inspector's listing, the Cost and Compare buttons): `FILE:LINE` (the file as the
    /// inspector lists it, or its name alone where one file of the lab's has it), `cost`,
    /// `diff` (with the built-in shaders); "" shows the picture again. Returns why the text
    /// names no view ("" when it does).
    pub fn view_set(&mut self, text: &str) -> String {
        let Some(open) = self.open.as_mut() else {
            return "no lab is open".into();
        };
        if text.is_empty() {
            return open.show_view(&self.gpu, None).unwrap_or_default();
        }
        let Some(mut wanted) = Wanted::from_link(text) else {
            return format!("`{text}` names no view: write FILE:LINE, cost or diff");
        };
        if let Wanted::Probe(crate::debug::view::Probe::Line { file, .. }) = &mut wanted {
            // The page names files without the built-in folder; the lab shows them with it.
            match open.find_file(file) {
                Ok(found) => *file = found,
                Err(why) => return why,
            }
        }
        open.show_view(&self.gpu, Some(wanted)).unwrap_or_default()
    }

    /// The view shown as the link writes it (`FILE:LINE`, `cost`, `diff`), "" for the picture.
    pub fn view(&self) -> String {
        self.open
            .as_ref()
            .and_then(Session::view)
            .map(Wanted::link)
            .unwrap_or_default()
    }

    /// Moves the view on (its values read back, or drawn again after a change) without
    /// drawing the canvas; returns whether its picture is there (or its error).
    pub fn view_poll(&mut self) -> bool {
        let size = self.screen.size();
        let Some(open) = self.open.as_mut() else {
            return false;
        };
        open.poll(&self.gpu, size);
        open.view_shown().is_some() && !open.view_busy()
    }

    /// What may be chosen where the view could not be drawn as asked (the names a line
    /// assigns, or the stage), as JSON: `[[words, view], …]`, each view as the link writes it.
    pub fn view_choices(&self) -> String {
        let choices: Vec<serde_json::Value> = self
            .open
            .as_ref()
            .map(|open| {
                open.view_choices()
                    .iter()
                    .map(|(words, wanted)| serde_json::json!([words, wanted.link()]))
                    .collect()
            })
            .unwrap_or_default();
        serde_json::Value::from(choices).to_string()
    }

    /// The view shown, in words: its legend, the diff's findings, or why it could not be
    /// drawn ("" for the picture, or while its first picture is drawn).
    pub fn view_text(&self) -> String {
        match self.open.as_ref().and_then(Session::view_shown) {
            Some(Ok(p)) => p.text.clone(),
            Some(Err(e)) => e.clone(),
            None => String::new(),
        }
    }

    /// Starts checking the page's shaders against the built-in ones across the lab's states
    /// (the page's Check, as `shaderlab check`): from the state shown, the base state, every
    /// object, the lab's states of record and `random` states drawn with `seed`, at the
    /// canvas's size, passing at 40 dB. Returns why it cannot start ("" when it started).
    pub fn check_start(&mut self, random: u32, seed: u32) -> String {
        let size = self.screen.size();
        let Some(open) = self.open.as_mut() else {
            return "no lab is open".into();
        };
        let random = (random as usize).min(super::check::MAX_RANDOM);
        open.check_start(&self.gpu, size, random, u64::from(seed), super::check::DEFAULT_MIN_DB)
            .unwrap_or_default()
    }

    /// Moves the check on (a state's frames read back, compared, the next state captured);
    /// returns whether it is finished.
    pub fn check_poll(&mut self) -> bool {
        let size = self.screen.size();
        let Some(open) = self.open.as_mut() else {
            return true;
        };
        open.poll(&self.gpu, size);
        open.checking().is_none_or(super::check::Checking::finished)
    }

    /// The check so far as `shaderlab check --json` writes it, with `total` (the states it
    /// checks) and `error` (why it stopped, or null); "" before a check.
    pub fn check_json(&self) -> String {
        let Some(check) = self.open.as_ref().and_then(Session::checking) else {
            return String::new();
        };
        let mut v = check.report().json();
        v["total"] = check.len().into();
        v["error"] = check.failed().map_or(serde_json::Value::Null, |e| e.to_string().into());
        v.to_string()
    }

    /// A picture of state `state` of the check, as a PNG: `which` 0 the page's shaders', 1 the
    /// built-in ones', 2 their difference (with its legend); empty where there is none.
    pub fn check_picture(&self, state: u32, which: u32) -> Vec<u8> {
        let Some(c) =
            (self.open.as_ref().and_then(Session::checking)).and_then(|c| c.report().states.get(state as usize))
        else {
            return Vec::new();
        };
        let image: &image::RgbaImage = match which {
            0 => &c.diff.frames.0,
            1 => &c.diff.frames.1,
            _ => &c.diff.picture,
        };
        let mut png = Vec::new();
        match crate::offscreen::write_png(image, &mut png) {
            Ok(()) => png,
            Err(_) => Vec::new(),
        }
    }

    /// The last error found while drawing, once ("" when none).
    pub fn take_error(&mut self) -> String {
        self.error.take().unwrap_or_default()
    }
}

impl WebApp {
    /// The shaders as the page has them.
    fn shader_source(&self) -> ShaderSource {
        ShaderSource::Edited(Arc::new(self.texts.clone()))
    }

    fn text(&self, name: &str) -> Option<String> {
        if let Some(t) = self.texts.get(name) {
            return Some(t.clone());
        }
        match name {
            n if n == LEGACY_DEFAULT[0] => Some(crate::course::legacy::DEFAULT_VERT.to_owned()),
            n if n == LEGACY_DEFAULT[1] => Some(crate::course::legacy::DEFAULT_FRAG.to_owned()),
            n => embedded_source(n).map(str::to_owned),
        }
    }

    fn file_names(&mut self) -> Vec<String> {
        let Some(open) = self.open.as_mut() else {
            return Vec::new();
        };
        if open.entry().info.files.named_textures {
            return match self.files.inputs.as_slice() {
                [] => LEGACY_DEFAULT.iter().map(|s| (*s).to_owned()).collect(),
                pair => pair.iter().map(|p| p.to_string_lossy().into_owned()).collect(),
            };
        }
        let mut names: Vec<String> = Vec::new();
        for program in open.shader_files() {
            for file in &program.spliced {
                let name = file.strip_prefix("shaders_glsl/").unwrap_or(file).to_owned();
                if !names.contains(&name) {
                    names.push(name);
                }
            }
        }
        names
    }

    fn reload(&mut self) -> String {
        let source = self.shader_source();
        let Some(open) = self.open.as_mut() else {
            return String::new();
        };
        open.reload(&self.gpu, source)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default()
    }

    /// Sizes the canvas, the surface and the depth buffer to the lab's picture.
    fn resize(&mut self, width: u32, height: u32) {
        let max = self.gpu.device.limits().max_texture_dimension_2d;
        let (width, height) = (width.clamp(1, max), height.clamp(1, max));
        self.canvas.set_width(width);
        self.canvas.set_height(height);
        if self.screen.size() != (width, height) {
            self.screen.resize(&self.gpu, (width, height));
        }
    }
}
