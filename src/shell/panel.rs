//! The parameter panel (F1): generated from the lab's [`ParamSpec`]s, so every lab (and
//! `legacy`, whose parameters are its shaders' uniforms and GL state) gets one without a line of
//! its own. It sits over the right side of the window, hidden by default: hidden, the window
//! shows exactly the lab's picture.
//!
//! [`widgets`] decides each parameter's control and group (tested without a window); [`Panel`]
//! runs egui on the window's events and draws with egui-wgpu after the lab, into the same
//! target (the swapchain's frame or the shared-memory presenter's texture).

use crate::lab::{Act, KeyRow, Lab};
use crate::params::{Kind, ParamSpec};

/// How a parameter is edited.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Control {
    /// A slider over the range, one per component.
    Slider,
    /// A drag value, for ranges too wide for a slider (`time`, ±1e30).
    Drag,
    /// A whole number: a slider over a small range, a stepper otherwise.
    Whole,
    /// A checkbox.
    Check,
    /// A combo box of the names.
    Choice(&'static [&'static str]),
    /// A colour picker plus its components.
    Colour,
}

/// Where a parameter is shown.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Group {
    /// Object, angles, camera.
    ObjectView,
    /// Surface: colours and lighting coefficients.
    Material,
    /// The light.
    Light,
    /// The clock.
    Time,
    /// Everything else the course has.
    Effect,
    /// What the port adds (study knobs, faster paths).
    Port,
}

impl Group {
    /// Its heading.
    pub fn title(self) -> &'static str {
        match self {
            Group::ObjectView => "Object & view",
            Group::Material => "Material",
            Group::Light => "Light",
            Group::Time => "Time",
            Group::Effect => "Effect",
            Group::Port => "Port additions",
        }
    }
}

/// One parameter's place in the panel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Widget {
    /// The parameter.
    pub spec: ParamSpec,
    /// Its control.
    pub control: Control,
    /// Its group.
    pub group: Group,
    /// The range a slider spans, per component (the first [`SLIDED`]): the declared range
    /// where it is narrow enough, else the range the lab's keys keep it to (phong's `Ka` in
    /// [0, 1], `shininess` in [6, 200]); `None`: no natural range, a number field alone. A
    /// typed value outside it still counts (within the declared range).
    pub sliders: [Option<(f64, f64)>; SLIDED],
}

/// How many components of a parameter get a slider each.
pub const SLIDED: usize = 4;

impl Widget {
    /// The slider's range for component `c`, if it has one.
    pub fn slider(&self, c: usize) -> Option<(f64, f64)> {
        self.sliders.get(c).copied().flatten()
    }
}

/// The slider ranges of `spec`'s components: its declared range when a slider can span it,
/// else the range the key rows that step it keep to.
pub fn slider_ranges(spec: &ParamSpec, keys: &[KeyRow]) -> [Option<(f64, f64)>; SLIDED] {
    let mut ranges = [None; SLIDED];
    if !matches!(spec.kind, Kind::Real | Kind::Int) {
        return ranges;
    }
    let declared = (spec.max - spec.min <= SLIDER_SPAN).then_some((spec.min, spec.max));
    for (c, range) in ranges.iter_mut().enumerate().take(spec.default.len()) {
        *range = declared.or_else(|| {
            keys.iter().find_map(|row| match row.act {
                Act::Step {
                    component,
                    within: Some((lo, hi)),
                    ..
                } if row.param == spec.name && component.is_none_or(|k| k == c) && lo < hi => Some((lo, hi)),
                _ => None,
            })
        });
    }
    ranges
}

/// The panel's width in logical pixels: it covers the right side of the window, the lab's
/// pixels stay untouched to its left.
pub const PANEL_WIDTH: f32 = 300.0;

/// Widest range a slider spans; a wider one gets a drag value (twist's `twisting`, ±1e4 so
/// that the per-vertex method's failure can be reached, is the widest slider).
const SLIDER_SPAN: f64 = 2e4;

/// Widest range of whole numbers a slider spans.
const WHOLE_SLIDER_SPAN: f64 = 1024.0;

/// The control of a parameter.
pub fn control_of(spec: &ParamSpec) -> Control {
    let span = spec.max - spec.min;
    match spec.kind {
        Kind::Bool => Control::Check,
        Kind::Choice(names) => Control::Choice(names),
        Kind::Int if span <= WHOLE_SLIDER_SPAN => Control::Whole,
        Kind::Real if is_colour(spec) => Control::Colour,
        Kind::Real if span <= SLIDER_SPAN => Control::Slider,
        Kind::Int | Kind::Real => Control::Drag,
    }
}

/// A vector of three or four components named as a colour (`diffuseColor`, `shade`, `clear`).
fn is_colour(spec: &ParamSpec) -> bool {
    let name = spec.name.to_ascii_lowercase();
    matches!(spec.default.len(), 3 | 4)
        && (name.contains("color") || name.contains("colour") || name == "shade" || name == "clear")
}

/// The group of a parameter, from its name and help (the port's additions say "port").
pub fn group_of(spec: &ParamSpec) -> Group {
    let name = spec.name.to_ascii_lowercase();
    let view = [
        "object", "xangle", "yangle", "zangle", "rx", "ry", "rz", "scale", "camera", "eye", "tex",
    ];
    if spec.help.starts_with("port") {
        Group::Port
    } else if name.contains("time") || name == "t" {
        Group::Time
    } else if name.contains("light") || ["lx", "ly", "lz", "blx", "bly", "blz"].contains(&name.as_str()) {
        Group::Light
    } else if view.contains(&name.as_str()) || name.ends_with("angle") {
        Group::ObjectView
    } else if is_colour(spec)
        || name.starts_with("ka")
        || name.starts_with("kd")
        || name.starts_with("ks")
        || name.contains("shininess")
        || name.contains("specular")
        || name.contains("diffuse")
        || name.contains("ambient")
    {
        Group::Material
    } else {
        Group::Effect
    }
}

/// Every parameter's widget, in group order (declaration order within a group); `keys` (the
/// lab's key rows) give the sliders of parameters declared with a wide range.
pub fn widgets(specs: &[ParamSpec], keys: &[KeyRow]) -> Vec<Widget> {
    let mut widgets: Vec<Widget> = specs
        .iter()
        .map(|spec| Widget {
            spec: *spec,
            control: control_of(spec),
            group: group_of(spec),
            sliders: slider_ranges(spec, keys),
        })
        .collect();
    widgets.sort_by_key(|w| w.group);
    widgets
}

/// What the window shows in the panel besides the parameters.
pub struct Status<'a> {
    /// Milliseconds per frame, averaged, while the lab animates; `None` when it draws only on
    /// change.
    pub frame_ms: Option<f64>,
    /// Milliseconds the last frame took to record and submit.
    pub draw_ms: f64,
    /// The shader files of each program (vertex, fragment).
    pub files: Vec<(String, String)>,
    /// Where shaders are read from, and whether they reload live.
    pub source: String,
    /// The last shader error, while one stands.
    pub error: Option<&'a str>,
    /// Frames recorded so far by F10, while it records.
    pub recording: Option<u32>,
    /// The whole-frame view shown, in words (what it is, its legend or why it failed).
    pub view: Option<String>,
    /// What may be chosen where the view could not be drawn as asked (the names a line
    /// assigns, or the stage).
    pub choices: Vec<(String, crate::shell::views::Wanted)>,
    /// Whether the lab draws with shaders other than its built-in ones (a diff is offered).
    pub can_diff: bool,
}

/// A parameter write asked for by the panel's controls: the window hands it to the session,
/// which checks it as it checks `--set` ([`crate::shell::session::Session::set_values`]).
#[derive(Clone, Debug, PartialEq)]
pub enum Edit {
    /// The parameter of this name to these values.
    Set(&'static str, Vec<f64>),
    /// Every parameter to its default (Reset all).
    Reset,
}

/// What the user asked of the window through the panel.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Request {
    /// Write the built-in shaders to a folder and reload from it.
    WriteShaders,
    /// Show a whole-frame view in place of the picture, or the picture again when it is the
    /// view shown (a line clicked in the inspector, the cost or diff button).
    View(crate::shell::views::Wanted),
    /// Show the lab's picture again.
    Picture,
}

/// The panel's contents for `lab`; returns the parameter writes asked for, and a request.
pub fn contents(ui: &mut egui::Ui, lab: &dyn Lab, status: &Status) -> (Vec<Edit>, Option<Request>) {
    let info = lab.info();
    let mut edits = Vec::new();
    let mut request = None;
    ui.heading(format!("{} {}", info.original_title, info.label));
    ui.label(format!("{} · {}", info.lecture, info.name));
    ui.label(match status.frame_ms {
        Some(ms) => format!("{ms:.1} ms/frame · {:.0} FPS", 1000.0 / ms.max(1e-3)),
        None => format!("draws on change · last frame {:.1} ms", status.draw_ms),
    });
    if let Some(frames) = status.recording {
        ui.colored_label(egui::Color32::RED, format!("● recording: {frames} frames (F10 stops)"));
    }
    ui.separator();
    egui::ScrollArea::vertical().show(ui, |ui| {
        let widgets = widgets(lab.params().specs(), lab.info().keys.rows);
        let mut group = None;
        for w in &widgets {
            if group != Some(w.group) {
                group = Some(w.group);
                ui.add_space(4.0);
                ui.strong(w.group.title());
            }
            edits.extend(row(ui, lab, w));
        }
        ui.add_space(4.0);
        if ui.button("Reset all").clicked() {
            edits.push(Edit::Reset);
        }
        ui.separator();
        egui::CollapsingHeader::new("Keys and mouse")
            .default_open(false)
            .show(ui, |ui| {
                for line in info.keys.help().split(";\n") {
                    ui.label(line);
                }
                ui.label(KEYS);
            });
        egui::CollapsingHeader::new("Views")
            .default_open(status.view.is_some())
            .show(ui, |ui| {
                ui.label("Click a line in the inspector (F2) to see its value at every pixel.");
                if ui.button("Cost: statements run per pixel (F3)").clicked() {
                    request = Some(Request::View(crate::shell::views::Wanted::COST));
                }
                if ui
                    .add_enabled(
                        status.can_diff,
                        egui::Button::new("Compare with the built-in shaders (F4)"),
                    )
                    .on_disabled_hover_text("Run the lab with --shaders DIR to compare a copy with them.")
                    .clicked()
                {
                    request = Some(Request::View(crate::shell::views::Wanted::Diff));
                }
                if let Some(view) = &status.view {
                    if ui.button("Back to the picture").clicked() {
                        request = Some(Request::Picture);
                    }
                    ui.label(view);
                    if let Some(chosen) = choose(ui, &status.choices) {
                        request = Some(chosen);
                    }
                }
            });
        egui::CollapsingHeader::new("Shaders")
            .default_open(status.error.is_some())
            .show(ui, |ui| {
                for (vert, frag) in &status.files {
                    ui.monospace(format!("{vert} + {frag}"));
                }
                ui.label(&status.source);
                if let Some(error) = status.error {
                    ui.colored_label(egui::Color32::LIGHT_RED, error);
                }
                if ui
                    .button("Copy the built-in shaders to a folder and edit them live")
                    .clicked()
                {
                    request = Some(Request::WriteShaders);
                }
            });
    });
    (edits, request)
}

/// The window's own keys, as the panel lists them.
pub const KEYS: &str = "F1 panel · F2 inspect a pixel (click a line: its view) · F3 cost view · F4 diff with the built-in shaders · F10 record · F12 screenshot · Esc quits";

/// One parameter's row: its control(s), a reset button, its help on hover; returns the write
/// its controls ask for.
fn row(ui: &mut egui::Ui, lab: &dyn Lab, w: &Widget) -> Option<Edit> {
    let spec = &w.spec;
    let current = lab.params().get(spec.name).map(<[f64]>::to_vec)?;
    let mut values = current.clone();
    let (lo, hi) = (spec.min, spec.max);
    ui.horizontal_wrapped(|ui| {
        let label = ui.label(spec.name);
        label.on_hover_text(spec.help);
        match w.control {
            Control::Check => {
                let mut on = values[0] != 0.0;
                if ui.checkbox(&mut on, "").on_hover_text(spec.help).changed() {
                    values[0] = f64::from(u8::from(on));
                }
            }
            Control::Choice(names) => {
                let mut index = (values[0].max(0.0) as usize).min(names.len() - 1);
                egui::ComboBox::from_id_salt(spec.name)
                    .selected_text(names[index])
                    .show_ui(ui, |ui| {
                        for (i, name) in names.iter().enumerate() {
                            ui.selectable_value(&mut index, i, *name);
                        }
                    });
                values[0] = index as f64;
            }
            Control::Colour => {
                let mut rgb = [values[0] as f32, values[1] as f32, values[2] as f32].map(|c| c.clamp(0.0, 1.0));
                if egui::widgets::color_picker::color_edit_button_rgb(ui, &mut rgb).changed() {
                    for (v, c) in values.iter_mut().zip(rgb) {
                        *v = f64::from(c);
                    }
                }
                for v in values.iter_mut() {
                    ui.add(egui::DragValue::new(v).range(lo..=hi).speed(0.01).max_decimals(3));
                }
            }
            Control::Slider => {
                for v in values.iter_mut() {
                    ui.add(egui::Slider::new(v, lo..=hi).max_decimals(3));
                }
            }
            Control::Whole => {
                for v in values.iter_mut() {
                    ui.add(egui::Slider::new(v, lo..=hi).integer());
                }
            }
            Control::Drag => {
                let whole = spec.kind == Kind::Int;
                for (c, v) in values.iter_mut().enumerate() {
                    if let Some((a, b)) = w.slider(c) {
                        // The keys' range; a value typed into its field may leave it.
                        let slider = egui::Slider::new(v, a..=b).clamping(egui::SliderClamping::Never);
                        ui.add(if whole {
                            slider.integer()
                        } else {
                            slider.max_decimals(3)
                        });
                        continue;
                    }
                    let speed = if whole { 1.0 } else { (v.abs() * 0.01).max(0.01) };
                    let drag = egui::DragValue::new(v).range(lo..=hi).speed(speed);
                    ui.add(if whole {
                        drag.max_decimals(0)
                    } else {
                        drag.max_decimals(4)
                    });
                }
            }
        }
        if ui
            .small_button("reset")
            .on_hover_text(format!("reset to {}", spec.default_text()))
            .clicked()
        {
            values = spec.default.to_vec();
        }
    });
    (values != current).then_some(Edit::Set(spec.name, values))
}

/// A button for each choice a view that could not be drawn offers (`Show: a | b`); returns
/// the view of the one clicked.
fn choose(ui: &mut egui::Ui, choices: &[(String, crate::shell::views::Wanted)]) -> Option<Request> {
    if choices.is_empty() {
        return None;
    }
    let mut chosen = None;
    ui.horizontal_wrapped(|ui| {
        ui.label("Show:");
        for (words, wanted) in choices {
            if ui.button(words).clicked() {
                chosen = Some(Request::View(wanted.clone()));
            }
        }
    });
    chosen
}

/// What the pixel inspector shows (F2).
pub struct InspectPanel<'a> {
    /// The pixel picked, if any.
    pub pixel: Option<(u32, u32)>,
    /// The last inspection, or why it failed.
    pub result: Option<&'a Result<crate::debug::Inspection, String>>,
    /// Whether a capture or replay is under way.
    pub busy: bool,
    /// The line whose view is shown (file, line), to mark in the listing.
    pub line: Option<(String, u32)>,
    /// The view shown, in words (what it is, its legend or why it failed).
    pub view: Option<String>,
    /// What may be chosen where the view could not be drawn as asked.
    pub choices: Vec<(String, crate::shell::views::Wanted)>,
}

/// The narrowest F1's panel gets on the right beside an inspected pixel before it moves to the
/// left, where the pixel leaves more room.
pub const PANEL_MIN_WIDTH: f32 = 200.0;

/// The inspector's width in logical pixels, at most.
pub const INSPECTOR_WIDTH: f32 = 640.0;

/// The largest share of the window's width the inspector takes: the rest of the picture stays
/// in sight to pick the next pixel in.
pub const INSPECTOR_SHARE: f32 = 0.45;

/// The narrowest inspector beside the pixel; with less room it goes above or below the pixel.
pub const INSPECTOR_MIN_WIDTH: f32 = 220.0;

/// The inspector's height above or below the pixel, at most, and the least worth taking (with
/// less room either way it goes beside the pixel however narrow).
pub const INSPECTOR_HEIGHT: f32 = 360.0;
const INSPECTOR_MIN_HEIGHT: f32 = 120.0;

/// Logical pixels kept free around the inspected pixel on every side: its marker and a little
/// of the picture around it, to click near it again.
pub const PIXEL_MARGIN: f32 = 24.0;

/// Where a panel goes: the side of the window it covers, and its size across (logical pixels).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Place {
    /// Along the left edge, this wide.
    Left(f32),
    /// Along the right edge, this wide.
    Right(f32),
    /// Along the top edge (between the side panels), this high.
    Top(f32),
    /// Along the bottom edge (between the side panels), this high.
    Bottom(f32),
}

/// Where F1's panel and the inspector go.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layout {
    /// F1's panel, when shown.
    pub panel: Option<Place>,
    /// The inspector, when shown.
    pub inspector: Option<Place>,
}

/// Where the panels go in a window of `size` (logical pixels) with F1's panel and the inspector
/// shown or not, and the inspected pixel (its top-left corner), if one is picked.
///
/// Inspecting, the pixel and [`PIXEL_MARGIN`] around it stay free at every size, so that the
/// pixel stays in sight and the picture around it can be clicked: F1's panel keeps its place
/// on the right, narrowed to the room beside the pixel (on the left when that room is under
/// [`PANEL_MIN_WIDTH`] and the left has more), and the inspector goes beside the pixel, up to
/// [`INSPECTOR_WIDTH`] and [`INSPECTOR_SHARE`] of the window: on the pixel's outer side (the
/// nearer edge of the window) where that leaves it [`INSPECTOR_MIN_WIDTH`], so that the middle
/// of the picture stays in sight, else on the side with more room; with less than
/// [`INSPECTOR_MIN_WIDTH`] there it goes above or below the pixel instead. The two never
/// overlap ([`Layout::rects`]). Before a pixel is picked, the inspector is
/// [`INSPECTOR_MIN_WIDTH`] wide on the left and the window's centre is kept free, where the
/// labs draw their object. Not inspecting, F1's panel is [`PANEL_WIDTH`] wide.
pub fn layout(size: (f32, f32), panel: bool, inspector: bool, pixel: Option<(f32, f32)>) -> Layout {
    let (width, height) = (size.0.max(0.0), size.1.max(0.0));
    if !inspector {
        return Layout {
            panel: panel.then_some(Place::Right(PANEL_WIDTH.min(width))),
            inspector: None,
        };
    }
    let (x, y) = pixel.unwrap_or((width / 2.0, height / 2.0));
    let mut left = (x - PIXEL_MARGIN).max(0.0);
    let mut right = (width - x - 1.0 - PIXEL_MARGIN).max(0.0);
    let panel = panel.then(|| {
        if pixel.is_none() || right >= PANEL_MIN_WIDTH || right >= left {
            let w = PANEL_WIDTH.min(right);
            right -= w;
            Place::Right(w)
        } else {
            let w = PANEL_WIDTH.min(left);
            left -= w;
            Place::Left(w)
        }
    });
    // Beside the pixel on its outer side (towards the nearer edge of the window) when that is
    // wide enough, so that the middle of the picture stays in sight; else where there is more.
    let outer_left = x < width / 2.0;
    let on_left = match (outer_left, left.max(right)) {
        (true, _) if left >= INSPECTOR_MIN_WIDTH => true,
        (false, _) if right >= INSPECTOR_MIN_WIDTH => false,
        (_, most) => left == most,
    };
    let (room, beside): (f32, fn(f32) -> Place) = if on_left {
        (left, Place::Left)
    } else {
        (right, Place::Right)
    };
    let (above, below) = ((y - PIXEL_MARGIN).max(0.0), (height - y - 1.0 - PIXEL_MARGIN).max(0.0));
    let inspector = if pixel.is_none() {
        // Nothing to show yet but how to pick: a narrow inspector, most of the picture free.
        Place::Left(INSPECTOR_MIN_WIDTH.min(left))
    } else if room >= INSPECTOR_MIN_WIDTH || above.max(below) < INSPECTOR_MIN_HEIGHT {
        let most = INSPECTOR_WIDTH.min(width * INSPECTOR_SHARE).max(INSPECTOR_MIN_WIDTH);
        beside(most.min(room))
    } else if below >= above {
        Place::Bottom(INSPECTOR_HEIGHT.min(below))
    } else {
        Place::Top(INSPECTOR_HEIGHT.min(above))
    };
    // A window too small to leave any room beside the pixel shows no panel there.
    let some_room = |place: &Place| {
        let (Place::Left(size) | Place::Right(size) | Place::Top(size) | Place::Bottom(size)) = *place;
        size >= 1.0
    };
    Layout {
        panel: panel.filter(some_room),
        inspector: Some(inspector).filter(some_room),
    }
}

impl Layout {
    /// The rectangles (logical pixels) of F1's panel and of the inspector in a window of
    /// `size`: a side panel runs along its edge, the whole height, inside any panel placed
    /// before it on that side (F1's goes first); a top or bottom one runs between the side
    /// panels.
    pub fn rects(&self, size: (f32, f32)) -> (Option<egui::Rect>, Option<egui::Rect>) {
        let mut free = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(size.0, size.1));
        let mut take = |place: Place| {
            let mut r = free;
            match place {
                Place::Left(w) => {
                    r.max.x = (r.min.x + w).min(free.max.x);
                    free.min.x = r.max.x;
                }
                Place::Right(w) => {
                    r.min.x = (r.max.x - w).max(free.min.x);
                    free.max.x = r.min.x;
                }
                Place::Top(h) => {
                    r.max.y = (r.min.y + h).min(free.max.y);
                    free.min.y = r.max.y;
                }
                Place::Bottom(h) => {
                    r.min.y = (r.max.y - h).max(free.min.y);
                    free.max.y = r.min.y;
                }
            }
            r
        };
        let panel = self.panel.map(&mut take);
        (panel, self.inspector.map(take))
    }
}

/// Shows `add_contents` in a panel that fills `rect` (logical pixels) and nothing beyond it:
/// a row wider than the panel is cut at its edge, so that the panels' places are exactly
/// those of [`Layout::rects`] (egui's own side panels grow with a wide row and then stack the
/// next panel over it).
pub fn panel_in<R>(ui: &mut egui::Ui, id: &str, rect: egui::Rect, add_contents: impl FnOnce(&mut egui::Ui) -> R) -> R {
    let mut child = ui.new_child(
        egui::UiBuilder::new()
            .id_salt(id)
            .max_rect(rect)
            .layout(egui::Layout::top_down(egui::Align::Min)),
    );
    child.shrink_clip_rect(rect);
    let frame = egui::Frame::side_top_panel(child.style());
    child.painter().rect_filled(rect, 0.0, frame.fill);
    let inner = (rect.size() - frame.total_margin().sum()).max(egui::Vec2::ZERO);
    frame
        .show(&mut child, |ui| {
            ui.set_min_size(inner);
            ui.set_max_width(inner.x);
            add_contents(ui)
        })
        .inner
}

/// The inspector: the pixel's colour, what covers it, the fragment shader line by line with
/// each line's values to its right, the inputs at the pixel, the vertex shader at the
/// triangle's corners.
pub fn inspector(ui: &mut egui::Ui, view: &InspectPanel) -> Option<Request> {
    use crate::debug::Stage;
    let mut request = None;
    ui.horizontal(|ui| {
        ui.heading(match view.pixel {
            Some((x, y)) => format!("Pixel {x},{y}"),
            None => "Inspect".to_owned(),
        });
        if view.busy {
            ui.spinner();
        }
    });
    if let Some(words) = &view.view {
        // The view's words (its legend in words) wrap in the panel, never cut at its edge.
        ui.horizontal_wrapped(|ui| {
            if ui.button("Back to the picture").clicked() {
                request = Some(Request::Picture);
            }
            ui.label(words);
        });
        if let Some(chosen) = choose(ui, &view.choices) {
            request = Some(chosen);
        }
    }
    let Some(result) = view.result else {
        ui.label("Click a pixel of the picture to see why it has its colour (F2 turns this off).");
        return request;
    };
    let i = match result {
        Ok(i) => i,
        Err(e) => {
            ui.colored_label(egui::Color32::LIGHT_RED, e);
            return request;
        }
    };
    let r = &i.replayed;
    ui.horizontal(|ui| {
        let [red, green, blue, _] = r.pixel;
        let (rect, _) = ui.allocate_exact_size(egui::vec2(28.0, 28.0), egui::Sense::hover());
        ui.painter()
            .rect_filled(rect, 3.0, egui::Color32::from_rgb(red, green, blue));
        ui.vertical(|ui| {
            let line = |ui: &mut egui::Ui, text: String| {
                ui.add(egui::Label::new(egui::RichText::new(text).monospace()).wrap());
            };
            line(
                ui,
                format!(
                    "stored rgba({}, {}, {}, {})",
                    r.pixel[0], r.pixel[1], r.pixel[2], r.pixel[3]
                ),
            );
            if let Some(g) = i.gpu_pixel {
                line(
                    ui,
                    format!("the GPU stored rgba({}, {}, {}, {})", g[0], g[1], g[2], g[3]),
                );
            }
            let c = r.color;
            line(
                ui,
                format!("colour ({:.4}, {:.4}, {:.4}, {:.4})", c[0], c[1], c[2], c[3]),
            );
        });
    });
    if let Some(words) = i.disagreement() {
        ui.colored_label(egui::Color32::LIGHT_RED, format!("Warning: {words}."));
    }
    for caveat in &i.caveats {
        ui.colored_label(egui::Color32::from_rgb(230, 190, 90), format!("Note: {caveat}."));
    }
    let Some(f) = &r.fragment else {
        let c = r.clear;
        ui.label(format!(
            "No triangle covers this pixel: the clear colour ({:.3}, {:.3}, {:.3}) shows.",
            c[0], c[1], c[2]
        ));
        return request;
    };
    ui.label(format!(
        "{} {} of draw {} ({}), {}, depth {:.5}{}",
        if f.points { "Point" } else { "Triangle" },
        f.primitive,
        f.draw,
        f.label,
        if f.front_facing { "front-facing" } else { "back-facing" },
        f.depth,
        if r.covering > 1 {
            format!("; {} fragments covered the pixel", r.covering)
        } else {
            String::new()
        }
    ));
    ui.separator();
    ui.label("Click a line to see its value over the whole picture.");
    let clicked = std::cell::Cell::new(None);
    // Every row wraps within the panel's width: a line of the listing and its values each get
    // about half of it, so nothing is cut and nothing needs scrolling sideways.
    egui::ScrollArea::vertical().auto_shrink([false, false]).show(ui, |ui| {
        let font = egui::TextStyle::Monospace.resolve(ui.style());
        let glyph = ui.ctx().fonts_mut(|f| f.glyph_width(&font, '0')).max(1.0);
        let spacing = ui.spacing().item_spacing.x;
        // A column of a grid of `columns` beside a 4-digit line number (or a name as wide).
        let column = |ui: &egui::Ui, columns: f32| {
            ((ui.available_width() - 5.0 * glyph - columns * spacing) / columns).max(MIN_COLUMN_CHARS as f32 * glyph)
        };
        let listing = |ui: &mut egui::Ui, stage: Stage, id: &str| {
            egui::Grid::new(id)
                .num_columns(3)
                .striped(true)
                .max_col_width(column(ui, 2.0))
                .show(ui, |ui| {
                    let mut file = String::new();
                    for row in i.rows(stage) {
                        if row.file != file {
                            file = row.file.clone();
                            ui.label("");
                            ui.strong(file_name(&row.file)).on_hover_text(&row.file);
                            ui.end_row();
                        }
                        let chosen = view
                            .line
                            .as_ref()
                            .is_some_and(|(f, l)| *f == row.file && *l == row.line);
                        let number = egui::RichText::new(format!("{:>4}", row.line)).monospace();
                        let number = if chosen {
                            number.color(egui::Color32::YELLOW).strong()
                        } else {
                            number
                        };
                        let a = ui.add(egui::Label::new(number).sense(egui::Sense::click()));
                        let b = ui.add(
                            egui::Label::new(egui::RichText::new(&row.text).monospace())
                                .wrap()
                                .sense(egui::Sense::click()),
                        );
                        if a.clicked() || b.clicked() {
                            clicked.set(Some(crate::shell::views::Wanted::Probe(
                                crate::debug::view::Probe::Line {
                                    file: row.file.clone(),
                                    line: row.line,
                                    name: None,
                                    stage: Some(stage),
                                },
                            )));
                        }
                        ui.add(
                            egui::Label::new(
                                egui::RichText::new(&row.values)
                                    .monospace()
                                    .color(egui::Color32::LIGHT_GREEN),
                            )
                            .wrap(),
                        );
                        ui.end_row();
                    }
                });
        };
        egui::CollapsingHeader::new(format!("Fragment shader {}", file_name(&f.fragment.path)))
            .default_open(true)
            .show(ui, |ui| listing(ui, Stage::Fragment, "inspector.fragment"));
        egui::CollapsingHeader::new("Inputs at the pixel")
            .default_open(true)
            .show(ui, |ui| {
                egui::Grid::new("inspector.inputs")
                    .num_columns(2)
                    .max_col_width(column(ui, 2.0))
                    .show(ui, |ui| {
                        for n in &f.inputs {
                            ui.add(egui::Label::new(egui::RichText::new(&n.name).monospace()).wrap());
                            ui.add(egui::Label::new(egui::RichText::new(numbers(&n.value)).monospace()).wrap());
                            ui.end_row();
                        }
                    });
            });
        egui::CollapsingHeader::new(format!("Vertex shader {} at the corners", file_name(&f.vertex.path)))
            .default_open(false)
            .show(ui, |ui| {
                egui::Grid::new("inspector.corners")
                    .num_columns(4)
                    .striped(true)
                    .max_col_width(column(ui, 4.0))
                    .show(ui, |ui| {
                        ui.label("");
                        for c in &f.corners {
                            ui.strong(format!("vertex {}", c.index));
                        }
                        ui.end_row();
                        if let Some(first) = f.corners.first() {
                            for (k, n) in first.inputs.iter().enumerate() {
                                ui.monospace(format!("in {}", n.name));
                                for c in &f.corners {
                                    ui.monospace(numbers(&c.inputs[k].value));
                                }
                                ui.end_row();
                            }
                            for (k, n) in first.outputs.iter().enumerate() {
                                ui.monospace(format!("out {}", n.name));
                                for c in &f.corners {
                                    ui.monospace(numbers(&c.outputs[k].value));
                                }
                                ui.end_row();
                            }
                        }
                    });
                ui.add_space(6.0);
                listing(ui, Stage::Vertex, "inspector.vertex");
            });
    });
    clicked.take().map(Request::View).or(request)
}

/// Characters a column of the inspector's listing gets at least, however narrow the inspector:
/// its rows wrap within it.
const MIN_COLUMN_CHARS: usize = 12;

fn file_name(path: &str) -> &str {
    path.rsplit(['/', '\\']).next().unwrap_or(path)
}

fn numbers(v: &[f64]) -> String {
    let one = |x: f64| {
        let s = format!("{x:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.').to_owned();
        if s == "-0" {
            "0".into()
        } else {
            s
        }
    };
    match v {
        [x] => one(*x),
        _ => format!("({})", v.iter().map(|x| one(*x)).collect::<Vec<_>>().join(", ")),
    }
}

/// egui on the window: its input state, context and one renderer per target format.
pub struct Panel {
    /// Whether it is shown (F1).
    pub shown: bool,
    /// Whether the inspector is shown (F2): egui then runs even with the panel hidden.
    pub inspecting: bool,
    ctx: egui::Context,
    input: egui_winit::State,
    renderers: Vec<(wgpu::TextureFormat, egui_wgpu::Renderer)>,
    /// Whether egui asked for another frame soon (an animation, a blinking cursor).
    pub repaint: bool,
    /// Where the panels were drawn last (logical pixels): the pointer over them is theirs.
    drawn: Vec<egui::Rect>,
    /// Where the pointer is (logical pixels), from the window's own events.
    cursor: Option<egui::Pos2>,
    /// Who the buttons held belong to, since a press: egui's widgets (a press on a panel) or
    /// the lab (a press on the picture, whose drag goes on over the panels).
    press: Option<Owner>,
}

/// Who a press belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Owner {
    Panels,
    Lab,
}

impl Panel {
    /// A hidden panel for `window`.
    pub fn new(window: &winit::window::Window) -> Panel {
        let ctx = egui::Context::default();
        let input = egui_winit::State::new(
            ctx.clone(),
            egui::ViewportId::ROOT,
            window,
            Some(window.scale_factor() as f32),
            None,
            None,
        );
        Panel {
            shown: false,
            inspecting: false,
            ctx,
            input,
            renderers: Vec::new(),
            repaint: false,
            drawn: Vec::new(),
            cursor: None,
            press: None,
        }
    }

    /// Whether the pointer at `pos` is over something egui drew: a panel, or a popup (a
    /// drop-down list, a colour picker) reaching over the picture. Judged by where the panels
    /// were drawn and the event's own position, not by egui's idea of the pointer, which is a
    /// frame old (a click right after the pointer moved off a panel belongs to the picture).
    fn over_panels(&self, pos: egui::Pos2) -> bool {
        self.drawn.iter().any(|r| r.contains(pos))
            || self
                .ctx
                .layer_id_at(pos)
                .is_some_and(|l| !matches!(l.order, egui::Order::Background | egui::Order::Tooltip))
    }

    /// Whether a pointer event belongs to the panels (see [`Panel::over_panels`]); follows the
    /// pointer and who owns a press.
    fn pointer_event(&mut self, window: &winit::window::Window, event: &winit::event::WindowEvent) -> bool {
        use winit::event::{ElementState, WindowEvent};
        let over = |panel: &Panel| panel.cursor.is_some_and(|pos| panel.over_panels(pos));
        match event {
            WindowEvent::CursorMoved { position, .. } => {
                let ppp = egui_winit::pixels_per_point(&self.ctx, window);
                self.cursor = Some(egui::pos2(position.x as f32 / ppp, position.y as f32 / ppp));
                match self.press {
                    Some(owner) => owner == Owner::Panels,
                    None => over(self),
                }
            }
            WindowEvent::CursorLeft { .. } => {
                self.cursor = None;
                self.press == Some(Owner::Panels)
            }
            WindowEvent::MouseInput {
                state: ElementState::Pressed,
                ..
            } => {
                let owner = *self
                    .press
                    .get_or_insert(if over(self) { Owner::Panels } else { Owner::Lab });
                owner == Owner::Panels
            }
            WindowEvent::MouseInput {
                state: ElementState::Released,
                ..
            } => self.press.take() == Some(Owner::Panels),
            WindowEvent::MouseWheel { .. } => over(self),
            _ => false,
        }
    }

    /// Feeds a window event to egui while the panel is shown; returns whether egui took it
    /// (a click on the panel, a key typed into one of its fields), so the lab must not.
    pub fn event(&mut self, window: &winit::window::Window, event: &winit::event::WindowEvent) -> bool {
        if !self.shown && !self.inspecting {
            self.drawn.clear();
            self.press = None;
            return false;
        }
        // Esc while a popup (a colour picker, a drop-down list) is open closes the popup, as
        // egui does, instead of reaching the lab (where it quits).
        let escape = matches!(
            event,
            winit::event::WindowEvent::KeyboardInput { event: k, .. }
                if k.logical_key == winit::keyboard::Key::Named(winit::keyboard::NamedKey::Escape)
        );
        let popup = escape && egui::Popup::is_any_open(&self.ctx);
        let response = self.input.on_window_event(window, event);
        if popup {
            return true;
        }
        let keyboard = matches!(event, winit::event::WindowEvent::KeyboardInput { .. });
        let pointer = matches!(
            event,
            winit::event::WindowEvent::MouseInput { .. }
                | winit::event::WindowEvent::CursorMoved { .. }
                | winit::event::WindowEvent::CursorLeft { .. }
                | winit::event::WindowEvent::MouseWheel { .. }
        );
        if pointer {
            return self.pointer_event(window, event);
        }
        (keyboard && self.ctx.egui_wants_keyboard_input()) || (response.consumed && !keyboard)
    }

    /// Runs the panel for this frame and encodes its drawing into `target` (after the lab's
    /// pass, keeping its pixels); returns the parameter writes asked for, and a request. The
    /// panels leave the bottom `legend` pixels of the window free: a whole-frame view's legend
    /// strip, which stays in sight whatever panels are open.
    #[allow(clippy::too_many_arguments)]
    pub fn draw(
        &mut self,
        gpu: &crate::gpu::Gpu,
        window: &winit::window::Window,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        format: wgpu::TextureFormat,
        size: (u32, u32),
        legend: u32,
        lab: &dyn Lab,
        status: &Status,
        inspect: Option<&InspectPanel>,
    ) -> (Vec<Edit>, Option<Request>) {
        self.inspecting = inspect.is_some();
        if !self.shown && !self.inspecting {
            self.repaint = false;
            return (Vec::new(), None);
        }
        let raw = self.input.take_egui_input(window);
        let mut result = (Vec::new(), None);
        let mut drawn = Vec::new();
        let ppp = egui_winit::pixels_per_point(&self.ctx, window);
        // The panels' part of the window: all of it above the legend strip.
        let above = (size.0 as f32 / ppp, size.1.saturating_sub(legend) as f32 / ppp);
        let places = layout(
            above,
            self.shown,
            inspect.is_some(),
            inspect
                .and_then(|v| v.pixel)
                .map(|(x, y)| (x as f32 / ppp, y as f32 / ppp)),
        );
        let (panel_rect, inspector_rect) = places.rects(above);
        let output = self.ctx.run_ui(raw, |ui| {
            if let Some(rect) = panel_rect {
                result = panel_in(ui, "shaderlab.panel", rect, |ui| contents(ui, lab, status));
                drawn.push(rect);
            }
            if let (Some(view), Some(rect)) = (inspect, inspector_rect) {
                if let Some(asked) = panel_in(ui, "shaderlab.inspector", rect, |ui| inspector(ui, view)) {
                    result.1 = Some(asked);
                }
                drawn.push(rect);
                if let Some((x, y)) = view.pixel {
                    // A frame around the inspected pixel.
                    let painter = ui.ctx().layer_painter(egui::LayerId::new(
                        egui::Order::Foreground,
                        egui::Id::unique("shaderlab.inspector.marker"),
                    ));
                    let (px, py) = (x as f32 / ppp, y as f32 / ppp);
                    let rect = egui::Rect::from_min_max(
                        egui::pos2(px - 4.0, py - 4.0),
                        egui::pos2(px + 1.0 / ppp + 4.0, py + 1.0 / ppp + 4.0),
                    );
                    painter.rect_stroke(
                        rect,
                        0.0,
                        egui::Stroke::new(3.0, egui::Color32::BLACK),
                        egui::StrokeKind::Outside,
                    );
                    painter.rect_stroke(
                        rect,
                        0.0,
                        egui::Stroke::new(1.5, egui::Color32::YELLOW),
                        egui::StrokeKind::Outside,
                    );
                }
            }
        });
        self.drawn = drawn;
        // egui animates (a header opening) over frames it asks for; the window draws them.
        self.repaint = output
            .viewport_output
            .get(&egui::ViewportId::ROOT)
            .is_some_and(|v| v.repaint_delay < std::time::Duration::from_millis(100));
        self.input.handle_platform_output(window, output.platform_output);
        let jobs = self.ctx.tessellate(output.shapes, output.pixels_per_point);
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [size.0, size.1],
            pixels_per_point: output.pixels_per_point,
        };
        let renderer = match self.renderers.iter().position(|(f, _)| *f == format) {
            Some(i) => &mut self.renderers[i].1,
            None => {
                let r = egui_wgpu::Renderer::new(&gpu.device, format, egui_wgpu::RendererOptions::default());
                self.renderers.push((format, r));
                &mut self.renderers.last_mut().expect("just pushed").1
            }
        };
        for (id, deltas) in &output.textures_delta.set {
            for delta in deltas {
                renderer.update_texture(&gpu.device, &gpu.queue, *id, delta);
            }
        }
        let extra = renderer.update_buffers(&gpu.device, &gpu.queue, encoder, &jobs, &screen);
        if !extra.is_empty() {
            gpu.queue.submit(extra);
        }
        {
            let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("panel.pass"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            renderer.render(&mut pass.forget_lifetime(), &jobs, &screen);
        }
        for id in &output.textures_delta.free {
            renderer.free_texture(id);
        }
        result
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_labs_parameters_get_a_widget_of_their_kind_and_range() {
        for entry in crate::course::ALL {
            let params = (entry.params)();
            let widgets = widgets(params.specs(), entry.info.keys.rows);
            assert_eq!(widgets.len(), params.specs().len(), "{}", entry.info.name);
            for w in &widgets {
                let s = &w.spec;
                let name = format!("{}.{}", entry.info.name, s.name);
                match (s.kind, w.control) {
                    (Kind::Bool, Control::Check) | (Kind::Int, Control::Whole | Control::Drag) => {}
                    (Kind::Choice(a), Control::Choice(b)) => assert_eq!(a, b, "{name}"),
                    (Kind::Real, Control::Slider) => assert!(s.max - s.min <= SLIDER_SPAN, "{name}"),
                    (Kind::Real, Control::Drag) => assert!(s.max - s.min > SLIDER_SPAN, "{name}"),
                    (Kind::Real, Control::Colour) => assert!(matches!(s.default.len(), 3 | 4), "{name}"),
                    (kind, control) => panic!("{name}: {kind:?} got {control:?}"),
                }
            }
        }
    }

    fn overlap(a: egui::Rect, b: egui::Rect) -> bool {
        a.min.x < b.max.x && b.min.x < a.max.x && a.min.y < b.max.y && b.min.y < a.max.y
    }

    /// At every size, wherever the pixel, with F1's panel or not, the
    /// inspected pixel and its margin stay free, the panels stay apart and in the window, and
    /// the inspector is wide (or high) enough to read wherever the window leaves room for it.
    #[test]
    fn the_inspected_pixel_stays_free_and_the_panels_never_overlap() {
        let sizes = [
            (120.0, 90.0),
            (320.0, 180.0),
            (400.0, 300.0),
            (640.0, 360.0),
            (800.0, 600.0),
            (1280.0, 720.0),
            (1920.0, 1080.0),
            (3000.0, 300.0),
            (300.0, 1000.0),
        ];
        for (w, h) in sizes {
            let mut pixels: Vec<Option<(f32, f32)>> = vec![None];
            for i in 0..=16 {
                for j in 0..=8 {
                    let (x, y) = ((w - 1.0) * i as f32 / 16.0, (h - 1.0) * j as f32 / 8.0);
                    pixels.push(Some((x.floor(), y.floor())));
                }
            }
            for f1 in [false, true] {
                for pixel in &pixels {
                    let l = layout((w, h), f1, true, *pixel);
                    let what = format!("{w}x{h} F1 {f1} pixel {pixel:?}: {l:?}");
                    if w >= 400.0 {
                        assert_eq!(l.panel.is_some(), f1, "{what}");
                        assert!(l.inspector.is_some(), "{what}");
                    }
                    let (panel, inspector) = l.rects((w, h));
                    let rs: Vec<egui::Rect> = panel.into_iter().chain(inspector).collect();
                    for r in &rs {
                        assert!(
                            r.min.x >= 0.0 && r.min.y >= 0.0 && r.max.x <= w && r.max.y <= h,
                            "{what}"
                        );
                    }
                    if let (Some(a), Some(b)) = (panel, inspector) {
                        assert!(!overlap(a, b), "{what}: the panels overlap");
                    }
                    let (x, y) = pixel.unwrap_or((w / 2.0, h / 2.0));
                    let m = PIXEL_MARGIN - 0.01;
                    let kept = egui::Rect::from_min_max(egui::pos2(x - m, y - m), egui::pos2(x + 1.0 + m, y + 1.0 + m));
                    for r in &rs {
                        assert!(!overlap(*r, kept), "{what}: a panel covers the pixel or its margin");
                    }
                    if w >= 640.0 && h >= 360.0 && !f1 {
                        let centre = egui::Rect::from_center_size(egui::pos2(w / 2.0, h / 2.0), egui::vec2(2.0, 2.0));
                        assert!(
                            rs.iter().all(|r| !overlap(*r, centre)),
                            "{what}: the middle of the picture is hidden"
                        );
                    }
                    if w >= 640.0 && h >= 360.0 {
                        let inspector = inspector.expect("the inspector");
                        let (across, along) = (inspector.width(), inspector.height());
                        assert!(
                            along < h || across <= w * INSPECTOR_SHARE,
                            "{what}: the inspector hides the picture"
                        );
                        assert!(
                            (across >= INSPECTOR_MIN_WIDTH && along == h)
                                || (along >= INSPECTOR_MIN_HEIGHT && across >= 120.0),
                            "{what}: an inspector of {across}x{along} is too small to read"
                        );
                    }
                }
            }
        }
        // The default 640x360 with both panels and the centre picked: F1 on the right, the
        // inspector on the left, the middle of the picture between them.
        let l = layout((640.0, 360.0), true, true, Some((320.0, 180.0)));
        assert!(matches!(l.panel, Some(Place::Right(w)) if w > 250.0), "{l:?}");
        assert!(matches!(l.inspector, Some(Place::Left(w)) if w > 250.0), "{l:?}");
        // Not inspecting, F1's panel is as wide as ever.
        let l = layout((640.0, 360.0), true, false, Some((320.0, 180.0)));
        assert_eq!(l.panel, Some(Place::Right(PANEL_WIDTH)));
        assert_eq!(l.inspector, None);
    }

    /// The widget of parameter `name` of lab `lab`.
    fn find(lab: &str, name: &str) -> Widget {
        let entry = crate::course::find(lab).unwrap();
        let params = (entry.params)();
        widgets(params.specs(), entry.info.keys.rows)
            .into_iter()
            .find(|w| w.spec.name == name)
            .unwrap()
    }

    #[test]
    fn controls_and_groups_follow_names_kinds_and_ranges() {
        assert_eq!(find("phong", "diffuseColor").control, Control::Colour);
        assert_eq!(find("phong", "diffuseColor").group, Group::Material);
        assert_eq!(find("noise", "shade").control, Control::Colour);
        assert_eq!(
            find("noise", "time").control,
            Control::Drag,
            "±1e9 is too wide for a slider"
        );
        assert_eq!(find("noise", "time").group, Group::Time);
        assert_eq!(find("phong", "object").group, Group::ObjectView);
        assert!(matches!(find("phong", "object").control, Control::Choice(names) if names.contains(&"torus")));
        assert_eq!(find("phong", "tess").group, Group::Port);
        assert_eq!(find("suzanne_phong", "lightx").group, Group::Light);
        assert_eq!(find("suzanne_phong", "ka").control, Control::Slider);
        assert_eq!(find("suzanne_phong", "ka").group, Group::Material);
        assert_eq!(find("twist", "twisting").control, Control::Slider);
        assert_eq!(find("phong_dir", "fixpos").control, Control::Check);
        // Groups come in order, whatever the declaration order.
        let params = (crate::course::PHONG.params)();
        let groups: Vec<Group> = widgets(params.specs(), crate::course::PHONG.info.keys.rows)
            .iter()
            .map(|w| w.group)
            .collect();
        assert!(groups.windows(2).all(|g| g[0] <= g[1]), "{groups:?}");
    }

    #[test]
    fn the_keys_give_sliders_to_parameters_declared_without_a_range() {
        // phong declares its material as any float; its keys keep it to the original's ranges.
        for (name, range) in [
            ("Ka", (0.0, 1.0)),
            ("Kd", (0.0, 1.0)),
            ("Ks", (0.0, 1.0)),
            ("shininess", (6.0, 200.0)),
        ] {
            let w = find("phong", name);
            assert_eq!(w.control, Control::Drag, "{name}: declared wide");
            assert_eq!(w.slider(0), Some(range), "{name}");
        }
        // Per component: the light's x, y and z keys.
        let light = find("phong", "lightPosition");
        assert!((0..3).all(|c| light.slider(c).is_some()), "{:?}", light.sliders);
        // A narrow declared range is the slider's; a wide one no key bounds has none.
        assert_eq!(find("suzanne_phong", "ka").slider(0), Some((0.0, 1.0)));
        assert_eq!(find("noise", "time").slider(0), None);
        assert_eq!(find("phong", "object").slider(0), None, "a choice has its list");
        // Every lab: a slider's range lies within what --set accepts.
        for entry in crate::course::ALL {
            let params = (entry.params)();
            for w in widgets(params.specs(), entry.info.keys.rows) {
                for (a, b) in w.sliders.iter().flatten() {
                    assert!(
                        w.spec.min <= *a && b <= &w.spec.max && a < b,
                        "{}.{}",
                        entry.info.name,
                        w.spec.name
                    );
                }
            }
        }
    }
}
