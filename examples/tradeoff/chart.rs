//! What the studies share: writing a study's CSV and SVG, and the panel of a sweep (one knob's
//! settings as labelled points, `auto`'s choice marked, the Pareto front drawn) on log-log
//! axes of frame time against an error that can be zero.

use std::path::{Path, PathBuf};

use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;
use shaderlab::fsutil::{signals, Batch, NewDir};

/// Every file a run writes, held in memory until all its studies are done, then moved into
/// place together ([`Outputs::commit`]): a run that fails or is stopped half-way leaves every
/// CSV, SVG and `.md` of the folder as it was.
pub struct Outputs {
    /// The output folder.
    pub dir: PathBuf,
    files: Vec<(PathBuf, String)>,
}

impl Outputs {
    /// Nothing written yet into `dir`.
    pub fn new(dir: &Path) -> Outputs {
        Outputs {
            dir: dir.to_owned(),
            files: Vec::new(),
        }
    }

    /// `DIR/NAME`'s contents, written at [`Outputs::commit`].
    pub fn file(&mut self, name: &str, text: String) {
        self.files.push((self.dir.join(name), text));
    }

    /// What this run has for `DIR/NAME` so far.
    pub fn get(&self, name: &str) -> Option<&str> {
        let path = self.dir.join(name);
        self.files
            .iter()
            .rev()
            .find(|(p, _)| *p == path)
            .map(|(_, t)| t.as_str())
    }

    /// Makes the folder if it is missing, writes every file beside its name and moves them
    /// all in; returns their paths. A failure (a full disk) or a signal that came before the
    /// move leaves the folder untouched, and a folder made here is removed again.
    pub fn commit(self) -> anyhow::Result<Vec<PathBuf>> {
        let _deferred = signals::defer();
        let dir = NewDir::create(&self.dir)?;
        let mut batch = Batch::new(true);
        for (path, text) in &self.files {
            batch.write(path, |w| w.write_all(text.as_bytes()))?;
        }
        signals::check()?;
        batch.commit()?;
        dir.keep();
        Ok(self.files.into_iter().map(|(p, _)| p).collect())
    }
}

/// Keeps `NAME.csv` and `NAME.svg` for the end of the run.
pub fn write(out: &mut Outputs, name: &str, csv: &str, svg: &str) -> anyhow::Result<()> {
    out.file(&format!("{name}.csv"), csv.to_owned());
    out.file(&format!("{name}.svg"), svg.to_owned());
    Ok(())
}

/// One setting of a sweep, as a panel draws it.
pub struct Point {
    /// Milliseconds per frame.
    pub ms: f64,
    /// The error (pixels off or wrong); 0 is drawn at 0.5 on the log axis.
    pub error: f64,
    /// The setting, written beside the point.
    pub label: String,
    /// `auto`'s choice (a red triangle, no label).
    pub auto: bool,
    /// On the Pareto front.
    pub pareto: bool,
}

/// A sweep's panel: `series` names the settings, `auto` the knob's `auto`.
fn sweep_panel(
    panel: &DrawingArea<SVGBackend<'_>, Shift>,
    caption: &str,
    y_desc: &str,
    series: &str,
    auto: &str,
    points: &[Point],
) -> anyhow::Result<()> {
    let floor = 0.5;
    let y = |p: &Point| p.error.max(floor);
    let max_ms = points.iter().map(|p| p.ms).fold(0.0, f64::max) * 1.2;
    let min_ms = points.iter().map(|p| p.ms).fold(f64::INFINITY, f64::min) * 0.8;
    let max_y = points.iter().map(y).fold(1.0, f64::max) * 2.0;
    let mut c = axes(
        panel,
        caption,
        ((min_ms..max_ms).log_scale(), MS_AXIS),
        ((floor * 0.8..max_y).log_scale(), y_desc),
    )?;
    let blue = RGBColor(31, 119, 180);
    let settings = || points.iter().filter(|p| !p.auto);
    c.draw_series(settings().map(|p| Circle::new((p.ms, y(p)), 4, blue.filled())))?
        .label(series)
        .legend(move |(x, y)| Circle::new((x + 10, y), 4, blue.filled()));
    c.draw_series(settings().map(|p| {
        Text::new(
            p.label.clone(),
            (p.ms, y(p)),
            ("sans-serif", 11).into_font().color(&RGBColor(90, 90, 90)),
        )
    }))?;
    let red = RGBColor(214, 39, 40);
    c.draw_series(
        points
            .iter()
            .filter(|p| p.auto)
            .map(|p| TriangleMarker::new((p.ms, y(p)), 8, red.filled())),
    )?
    .label(auto)
    .legend(move |(x, y)| TriangleMarker::new((x + 10, y), 8, red.filled()));
    pareto_line(
        &mut c,
        points.iter().filter(|p| p.pareto).map(|p| (p.ms, y(p))).collect(),
    )?;
    legend(&mut c, SeriesLabelPosition::UpperRight)
}

/// A chart of sweep panels side by side, `size` pixels, one per `(caption, points)` ([`sweep_panel`]
/// with `y_desc`, `series` and `auto`), into `svg`.
pub fn sweep_chart(
    svg: &mut String,
    size: (u32, u32),
    panels: Vec<(String, Vec<Point>)>,
    y_desc: &str,
    series: &str,
    auto: &str,
) -> anyhow::Result<()> {
    let root = SVGBackend::with_string(svg, size).into_drawing_area();
    root.fill(&WHITE)?;
    for (area, (caption, points)) in root.split_evenly((1, panels.len())).iter().zip(panels) {
        sweep_panel(area, &caption, y_desc, series, auto, &points)?;
    }
    root.present()?;
    Ok(())
}

/// The frame-time axis of every chart here.
pub const MS_AXIS: &str = "ms per frame (GPU timestamps, lavapipe)";

/// A chart drawn into an SVG string, with axes of range types `X` and `Y`.
pub type Chart<'a, 'b, X, Y> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<X, Y>>;

/// A panel's chart as every study draws it: its caption above, frame time along x and the
/// error along y (each a range and its description), light grey grid lines only at labels.
pub fn axes<'a, 'b, X, Y>(
    panel: &'a DrawingArea<SVGBackend<'b>, Shift>,
    caption: &str,
    (x, x_desc): (X, &str),
    (y, y_desc): (Y, &str),
) -> anyhow::Result<Chart<'a, 'b, X::CoordDescType, Y::CoordDescType>>
where
    X: AsRangedCoord<Value = f64>,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let mut c = ChartBuilder::on(panel)
        .caption(caption, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(x, y)?;
    c.configure_mesh()
        .light_line_style(TRANSPARENT)
        .bold_line_style(RGBColor(225, 225, 225))
        .x_desc(x_desc)
        .y_desc(y_desc)
        .draw()?;
    Ok(c)
}

/// The Pareto front as a black line through `front`'s points in order of time, in the legend.
pub fn pareto_line<X, Y>(
    c: &mut ChartContext<'_, SVGBackend<'_>, Cartesian2d<X, Y>>,
    mut front: Vec<(f64, f64)>,
) -> anyhow::Result<()>
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    c.draw_series(LineSeries::new(front, BLACK.stroke_width(2)))?
        .label("Pareto front")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
    Ok(())
}

/// The legend box every study's chart draws, at `position`.
pub fn legend<'a, 'b: 'a, X, Y>(
    c: &mut ChartContext<'a, SVGBackend<'b>, Cartesian2d<X, Y>>,
    position: SeriesLabelPosition,
) -> anyhow::Result<()>
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    c.configure_series_labels()
        .position(position)
        .border_style(BLACK)
        .background_style(WHITE.mix(0.9))
        .draw()?;
    Ok(())
}

/// Which rows are on the Pareto front: no other row of the same group (`same`) is at least as
/// fast and at least as accurate, and better in one of the two.
pub fn pareto<T>(
    rows: &[T],
    same: impl Fn(&T, &T) -> bool,
    ms: impl Fn(&T) -> f64,
    error: impl Fn(&T) -> f64,
) -> Vec<bool> {
    rows.iter()
        .map(|r| {
            !rows
                .iter()
                .any(|o| same(o, r) && ms(o) <= ms(r) && error(o) <= error(r) && (ms(o) < ms(r) || error(o) < error(r)))
        })
        .collect()
}

/// One setting of a knob, drawn and timed.
pub struct Measured {
    /// The setting drawn (for `auto`, the one the lab chose, read from its title).
    pub setting: u32,
    /// Whether it was `auto` (the knob at 0).
    pub auto: bool,
    /// Milliseconds per frame (GPU timestamps where the adapter has them).
    pub ms: f64,
    /// The picture, at the study's size.
    pub image: image::RgbImage,
}

/// Draws and times `lab` at each of `settings` of its knob `param`, then at `auto` (0, whose
/// choice the lab's title names after `auto_title`, e.g. `segments auto: `). `after_bench`
/// puts back what timing changed (an animated lab's clock).
#[allow(clippy::too_many_arguments)]
pub fn measure_settings(
    gpu: &shaderlab::Gpu,
    lab: &mut dyn shaderlab::Lab,
    param: &str,
    settings: &[u32],
    auto_title: &str,
    frames: u32,
    (width, height): (u32, u32),
    after_bench: &dyn Fn(&mut dyn shaderlab::Lab) -> anyhow::Result<()>,
) -> anyhow::Result<Vec<Measured>> {
    let mut out = Vec::new();
    for (setting, auto) in settings.iter().map(|&s| (s, false)).chain([(0, true)]) {
        lab.params_mut().set(param, &[f64::from(setting)])?;
        let image = shaderlab::offscreen::to_rgb(&shaderlab::shell::screenshot(gpu, lab, width, height)?);
        let timing = shaderlab::shell::bench(gpu, lab, frames, width, height, true)?;
        after_bench(lab)?;
        let setting = if auto {
            lab.title()
                .split(auto_title)
                .nth(1)
                .and_then(|t| t.split(|c: char| !c.is_ascii_digit()).next())
                .and_then(|t| t.parse().ok())
                .unwrap_or(0)
        } else {
            setting
        };
        out.push(Measured {
            setting,
            auto,
            ms: timing.gpu_ms.unwrap_or(timing.ms_per_frame),
            image,
        });
    }
    Ok(out)
}

/// The built-in shaders, for [`context`].
static EMBEDDED: shaderlab::shader::ShaderSource = shaderlab::shader::ShaderSource::Embedded;

/// What every study builds its labs with: the GPU, the built-in shaders, the offscreen format,
/// no user files.
pub fn context(gpu: &shaderlab::Gpu) -> shaderlab::lab::BuildContext<'_> {
    shaderlab::lab::BuildContext::new(
        gpu,
        &EMBEDDED,
        shaderlab::offscreen::COLOR_FORMAT,
        &shaderlab::lab::NO_FILES,
    )
}

/// One line of a sweep's progress: above the bar on a terminal, on stderr in a log.
pub fn say(bar: &indicatif::ProgressBar, line: String) {
    if bar.is_hidden() {
        eprintln!("{line}");
    } else {
        bar.println(line);
    }
}
