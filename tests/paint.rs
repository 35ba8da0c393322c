//! A view's picture made on the GPU (`debug::paint`, what the window and the page show) is the
//! library's picture of the same values (`debug::picture`, what `shaderlab view --out`
//! writes): its legend strip byte for byte, its pixels within 1 of 255 (the GPU colours in
//! `f32`, the library in `f64`) at no more than 1 pixel in 1,000; across every lab's cost view,
//! its fragment shader's first and last assignments and its vertex shader's first, a scalar
//! changing sign (the diverging map), a line in a branch (pixels where it did not run), and
//! NaN and both infinities, counted as the library counts them.

mod common;

use std::collections::BTreeMap;
use std::sync::Arc;

use common::gpu;
use shaderlab::debug::paint::{self, Painter};
use shaderlab::debug::picture;
use shaderlab::debug::view::{self, Probe, ViewDrawer};
use shaderlab::debug::Stage;
use shaderlab::lab::{Lab, UserFiles};
use shaderlab::shader::ShaderSource;

const WIDTH: u32 = 200;
const HEIGHT: u32 = 120;

fn build(name: &str, source: ShaderSource, set: &[(&str, &str)]) -> Box<dyn Lab> {
    common::lab_at(name, &source, &UserFiles::default(), set)
}

/// How the GPU's picture of `probe` differs from the library's: pixels off, by how much at
/// most; `Err` where the legend strips differ or the counts do.
fn compare(
    lab: &mut dyn Lab,
    drawer: &mut ViewDrawer,
    painter: &mut Painter,
    probe: &Probe,
) -> Result<(usize, u8, Option<picture::Legend>), String> {
    let log = view::encode(gpu(), lab, WIDTH, HEIGHT).map_err(|e| e.to_string())?;
    let frame = drawer
        .draw(gpu(), &log, probe, WIDTH, HEIGHT)
        .map_err(|e| e.to_string())?;
    let (want, legend) = frame.picture();
    let (got, stats) =
        paint::paint_view(gpu(), drawer, painter, (&log, probe), WIDTH, HEIGHT).map_err(|e| e.to_string())?;
    if got.dimensions() != want.dimensions() {
        return Err(format!("{:?} against {:?}", got.dimensions(), want.dimensions()));
    }
    if let Some(l) = &legend {
        let mine = stats.legend(frame.components);
        if mine != *l {
            return Err(format!("legend {mine:?} against {l:?}"));
        }
    }
    let (mut off, mut worst) = (0, 0);
    for (x, y, p) in want.enumerate_pixels() {
        let q = got.get_pixel(x, y);
        let d = (0..4).map(|c| p[c].abs_diff(q[c])).max().unwrap_or(0);
        if y >= HEIGHT && d > 0 {
            return Err(format!("the legend strip differs at {x},{y}: {q:?} against {p:?}"));
        }
        if d > 0 {
            off += 1;
            worst = worst.max(d);
        }
    }
    Ok((off, worst, legend))
}

/// Pixels off by 1 over the views [`agrees`] saw.
static OFF: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

fn agrees(what: &str, result: Result<(usize, u8, Option<picture::Legend>), String>) -> Option<picture::Legend> {
    match result {
        Ok((off, worst, legend)) => {
            OFF.fetch_add(off, std::sync::atomic::Ordering::SeqCst);
            let n = (WIDTH * HEIGHT) as usize;
            assert!(
                worst <= 1 && off * 1000 <= n,
                "{what}: {off} of {n} pixels differ, by up to {worst}"
            );
            legend
        }
        Err(e) => panic!("{what}: {e}"),
    }
}

#[test]
fn the_gpus_picture_is_the_librarys_at_every_lab() {
    let mut drawer = ViewDrawer::new();
    let mut painter = Painter::new(&gpu().device);
    let mut views = 0;
    for entry in shaderlab::course::ALL {
        let name = entry.info.name;
        if name == "legacy" {
            continue;
        }
        let set: &[(&str, &str)] = if name == "particles" { &[("time", "2")] } else { &[] };
        let mut lab = build(name, ShaderSource::Embedded, set);
        agrees(
            &format!("{name} cost"),
            compare(lab.as_mut(), &mut drawer, &mut painter, &Probe::Cost),
        );
        views += 1;
        let (_, captured) = view::capture(gpu(), lab.as_mut(), WIDTH, HEIGHT).expect("captures");
        let Some(draw) = captured.draws.first() else { continue };
        let mine = |shader: &shaderlab::shader::CompiledShader| -> Vec<_> {
            shaderlab::debug::instrument::assignments(shader)
                .into_iter()
                .filter(|a| a.file == shader.path && a.root != "(temporary)")
                .collect()
        };
        let fragment = mine(&draw.fragment);
        let vertex = mine(&draw.vertex);
        let picks = [
            (Stage::Fragment, fragment.first()),
            (Stage::Fragment, fragment.last()),
            (Stage::Vertex, vertex.first()),
        ];
        for (stage, a) in picks {
            let Some(a) = a else { continue };
            let probe = Probe::Line {
                file: a.file.clone(),
                line: a.line,
                name: Some(a.name.clone()),
                stage: Some(stage),
            };
            agrees(
                &format!("{name} {}:{} `{}`", a.file, a.line, a.name),
                compare(lab.as_mut(), &mut drawer, &mut painter, &probe),
            );
            views += 1;
        }
    }
    eprintln!(
        "{views} views of {WIDTH}x{HEIGHT}: the GPU's picture is the library's but for {} pixels off by 1 (both tests)",
        OFF.load(std::sync::atomic::Ordering::SeqCst)
    );
    assert!(views >= 80, "most labs' views were compared: {views}");
}

#[test]
fn the_diverging_map_the_checker_nan_and_infinities_are_the_librarys() {
    let mut drawer = ViewDrawer::new();
    let mut painter = Painter::new(&gpu().device);
    // A value that changes sign, a branch taken in part of the picture, and NaN, +inf and
    // -inf where the normal points one way or another.
    let text = "#version 450\n\
        layout(location = 0) in vec3 normal;\n\
        layout(location = 0) out vec4 frag_color;\n\
        void main() {\n\
        \x20   float s = normal.x;\n\
        \x20   float odd = 0.0;\n\
        \x20   if (normal.y > 0.2) {\n\
        \x20       odd = normal.x / max(normal.z - 0.6, 0.0) + sqrt(0.5 - normal.y);\n\
        \x20   }\n\
        \x20   frag_color = vec4(normal * 0.5 + 0.5 + 0.0 * s * odd, 1.0);\n\
        }\n";
    let edits: BTreeMap<String, String> = [("normal_rgb.frag".to_owned(), text.to_owned())].into();
    let mut lab = build(
        "normal_rgb",
        ShaderSource::Edited(Arc::new(edits)),
        &[("object", "sphere")],
    );
    let log = view::encode(gpu(), lab.as_mut(), WIDTH, HEIGHT).expect("records");
    let file = log
        .draws()
        .first()
        .and_then(|d| d.setup.fragment.source.files.first().map(|f| f.0.clone()))
        .expect("the fragment shader's file");
    let line = |line: u32| Probe::Line {
        file: file.clone(),
        line,
        name: None,
        stage: None,
    };
    let sign = agrees(
        "s (changes sign)",
        compare(lab.as_mut(), &mut drawer, &mut painter, &line(5)),
    )
    .expect("a legend");
    assert_eq!(sign.scale, picture::Scale::Diverging, "{sign:?}");
    let odd = agrees(
        "odd (a branch, NaN, ±inf)",
        compare(lab.as_mut(), &mut drawer, &mut painter, &line(8)),
    )
    .expect("a legend");
    assert!(
        odd.not_run > 100 && odd.nan > 10 && odd.pos_inf > 10 && odd.neg_inf > 10,
        "the branch leaves pixels not run, and NaN and both infinities are there: {odd:?}"
    );
    let colour = agrees(
        "the colour (a vector)",
        compare(lab.as_mut(), &mut drawer, &mut painter, &line(10)),
    )
    .expect("a legend");
    assert_eq!(colour.scale, picture::Scale::Rgb, "{colour:?}");
}
