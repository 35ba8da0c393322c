//! The window's inspector (F2) at the default 640x360, laid out by egui in the place the window
//! gives it (`panel::layout` above a view's legend strip, `panel::panel_in`): every word it
//! shows lies inside the panel, so its rows wrap instead of being cut at the panel's edge or
//! shortened with "…". For a pixel on the object (the shader's listing with each line's values)
//! and one where no triangle is, with F1's panel open or not, and a line view's legend in words.

mod common;

use common::gpu;
use shaderlab::debug::{picture, Inspection};
use shaderlab::lab::UserFiles;
use shaderlab::offscreen::COLOR_FORMAT;
use shaderlab::shader::ShaderSource;
use shaderlab::shell::panel::{inspector, layout, panel_in, InspectPanel};
use shaderlab::shell::session::{Platform, Session, Sources};
use shaderlab::shell::views::Wanted;

const SIZE: (u32, u32) = (640, 360);

/// Every text egui drew, with where it lies.
fn texts(shapes: &[egui::epaint::ClippedShape]) -> Vec<(String, egui::Rect)> {
    fn walk(shape: &egui::Shape, out: &mut Vec<(String, egui::Rect)>) {
        match shape {
            egui::Shape::Text(t) => out.push((t.galley.text().to_owned(), t.galley.rect.translate(t.pos.to_vec2()))),
            egui::Shape::Vec(shapes) => shapes.iter().for_each(|s| walk(s, out)),
            _ => {}
        }
    }
    let mut out = Vec::new();
    for clipped in shapes {
        walk(&clipped.shape, &mut out);
    }
    out
}

#[test]
fn the_inspectors_words_wrap_inside_it_at_640x360() {
    let entry = shaderlab::course::find("phong").expect("phong");
    let sources = Sources::new(ShaderSource::Embedded, UserFiles::default(), COLOR_FORMAT);
    let mut s = Session::open(entry, gpu(), sources, Platform::NATIVE, 0.0, 1.0).expect("phong opens");
    s.set("object", "torus").expect("a torus");
    let file = (s.shader_files().into_iter().flat_map(|p| p.spliced))
        .find(|f| f.ends_with("phong.frag"))
        .expect("phong.frag");
    // The line view of line 17 and its legend in words, as the inspector shows them.
    s.show_view(gpu(), Some(Wanted::from_link(&format!("{file}:17")).expect("a line")));
    let mut calls = 0;
    while s.view_shown().is_none() || s.view_busy() {
        s.poll(gpu(), SIZE);
        calls += 1;
        assert!(calls < 100_000, "the view never came back");
        std::thread::yield_now();
    }
    let words = match s.view_shown() {
        Some(Ok(p)) => p.text.clone(),
        Some(Err(e)) => panic!("no line view: {e}"),
        None => panic!("no line view"),
    };
    let (_, captured) = shaderlab::debug::capture_lab(gpu(), s.lab_mut(), SIZE.0, SIZE.1, false).expect("captures");
    // The window's panels leave the legend strip free.
    let above = (SIZE.0 as f32, (SIZE.1 - picture::LEGEND_HEIGHT) as f32);
    for (x, y) in [(330, 80), (300, 150)] {
        let result: Result<Inspection, String> = Inspection::new("phong", &captured, x, y).map_err(|e| e.to_string());
        let covered = result.as_ref().expect("inspects").replayed.fragment.is_some();
        assert_eq!(
            covered,
            (x, y) == (330, 80),
            "{x},{y}: the torus covers 330,80, not 300,150"
        );
        let view = InspectPanel {
            pixel: Some((x, y)),
            result: Some(&result),
            busy: false,
            line: Some((file.clone(), 17)),
            view: Some(words.clone()),
            choices: Vec::new(),
        };
        for f1 in [false, true] {
            let what = format!("pixel {x},{y}, F1 {f1}");
            let (_, place) = layout(above, f1, true, Some((x as f32, y as f32))).rects(above);
            let rect = place.expect("an inspector");
            // The panel as the window places it, then as tall as its whole contents (the same
            // width): nothing scrolled out of sight.
            let tall = egui::Rect::from_min_max(rect.min, egui::pos2(rect.max.x, 4000.0));
            let mut shown = Vec::new();
            for (rect, screen) in [(rect, SIZE.1 as f32), (tall, 4000.0)] {
                let ctx = egui::Context::default();
                let input = egui::RawInput {
                    screen_rect: Some(egui::Rect::from_min_size(
                        egui::Pos2::ZERO,
                        egui::vec2(SIZE.0 as f32, screen),
                    )),
                    ..Default::default()
                };
                // egui sizes a grid's columns from the frame before: a few frames settle it.
                let mut shapes = Vec::new();
                for _ in 0..4 {
                    let output = ctx.run_ui(input.clone(), |ui| {
                        panel_in(ui, "inspector", rect, |ui| inspector(ui, &view));
                    });
                    shapes = output.shapes;
                }
                shown = texts(&shapes);
                let all: String = shown.iter().map(|(t, _)| t.as_str()).collect::<Vec<_>>().join(" | ");
                assert!(all.contains("stored rgba"), "{what}: {all}");
                for (text, at) in &shown {
                    assert!(
                        at.min.x >= rect.min.x - 0.5 && at.max.x <= rect.max.x + 0.5,
                        "{what}: `{text}` at {at:?} runs out of the inspector {rect:?}"
                    );
                    assert!(!text.ends_with('…'), "{what}: `{text}` is shortened");
                }
            }
            let all: String = shown.iter().map(|(t, _)| t.as_str()).collect::<Vec<_>>().join(" | ");
            if covered {
                // The listing's line 17 whole, in rows that wrap.
                let line: String = shown
                    .iter()
                    .filter(|(t, _)| t.contains("Idiff") && t.contains("vec4"))
                    .map(|(t, _)| t.replace('\n', ""))
                    .collect();
                assert!(
                    line.contains("vec4 Idiff = vec4(diffuseColor * max(dot(N, L), 0.0), 1.0);"),
                    "{what}: line 17 is not shown whole: {all}"
                );
            }
        }
    }
}
