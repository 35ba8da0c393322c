//! The inspector checks itself: every inspection carries the pixel the GPU stored in the frame
//! that was captured (`gpu_pixel`), which is `--screenshot`'s pixel, and says in words where
//! the replay's stored byte is more than 2/255 from it.

mod common;

use common::gpu;
use shaderlab::debug::{capture_lab, capture_start, Inspection};
use shaderlab::lab::{BuildContext, Lab, UserFiles};
use shaderlab::offscreen::COLOR_FORMAT;
use shaderlab::shader::ShaderSource;

fn build(name: &str, set: &[(&str, &str)]) -> Box<dyn Lab> {
    let entry = shaderlab::course::find(name).expect("a lab");
    let files = UserFiles::default();
    let cx = BuildContext::new(gpu(), &ShaderSource::Embedded, COLOR_FORMAT, &files);
    let mut lab = (entry.new)(&cx).unwrap_or_else(|e| panic!("{name} builds: {e}"));
    for (k, v) in set {
        lab.params_mut().set_str(k, v).expect("a state");
    }
    lab
}

/// Pixels spread over the picture: a 7 × 5 grid and the drawn pixels' first, middle and last.
fn pixels(image: &image::RgbaImage) -> Vec<(u32, u32)> {
    let (w, h) = image.dimensions();
    let mut out = Vec::new();
    for j in 0..5 {
        for i in 0..7 {
            out.push(((2 * i + 1) * w / 14, (2 * j + 1) * h / 10));
        }
    }
    let corner = image.get_pixel(0, 0).0;
    let drawn: Vec<(u32, u32)> = image
        .enumerate_pixels()
        .filter(|(_, _, p)| p.0 != corner)
        .map(|(x, y, _)| (x, y))
        .collect();
    if !drawn.is_empty() {
        out.extend([drawn[0], drawn[drawn.len() / 2], drawn[drawn.len() - 1]]);
    }
    out
}

/// The window's and the page's capture ([`capture_start`], polled as they poll it) brings
/// the GPU's picture: at pixels across every lab, each inspection's `gpu_pixel` is the pixel
/// of a `--screenshot` of the same state drawn on its own.
#[test]
fn every_inspection_carries_the_screenshots_pixel() {
    let mut checked = 0;
    let mut misses = Vec::new();
    for entry in shaderlab::course::ALL {
        let name = entry.info.name;
        if name == "legacy" {
            continue;
        }
        let set: &[(&str, &str)] = if name == "particles" { &[("time", "2")] } else { &[] };
        let mut lab = build(name, set);
        let (w, h) = entry.info.size;
        let shot = shaderlab::shell::screenshot(gpu(), lab.as_mut(), w, h).expect("a screenshot");
        let pending = capture_start(gpu(), lab.as_mut(), (w, h), COLOR_FORMAT).expect("a capture");
        let start = std::time::Instant::now();
        while !pending.ready() {
            let _ = gpu().device.poll(wgpu::PollType::Poll);
            assert!(start.elapsed().as_secs() < 300, "{name}: the capture never finished");
            std::thread::yield_now();
        }
        let captured = pending.finish().expect("the captured frame");
        assert!(captured.picture.is_some(), "{name}: the capture ran the frame");
        for (x, y) in pixels(&shot) {
            let i = Inspection::new(name, &captured, x, y).unwrap_or_else(|e| panic!("{name} {x},{y}: {e}"));
            checked += 1;
            let want = shot.get_pixel(x, y).0;
            if i.gpu_pixel != Some(want) {
                misses.push(format!(
                    "{name} {x},{y}: gpu_pixel {:?}, screenshot {want:?}",
                    i.gpu_pixel
                ));
            }
            let json: serde_json::Value = serde_json::from_str(&i.json()).expect("JSON");
            assert_eq!(json["gpu_pixel"], serde_json::json!(i.gpu_pixel), "{name} {x},{y}");
        }
    }
    println!("{checked} pixels checked");
    assert!(checked > 300, "{checked} pixels");
    assert!(misses.is_empty(), "{}", misses.join("\n"));
}

fn shaderlab(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_shaderlab"))
        .args(args)
        .output()
        .expect("shaderlab runs")
}

/// `shaderlab debug … --json` says the GPU's pixel, the one `shaderlab run … --screenshot`
/// stores, and the text report shows it beside the replay's.
#[test]
fn the_debug_command_reports_the_screenshots_pixel() {
    let dir = common::output_dir();
    for (name, set, pixels) in [
        ("phong", "object=torus", [(400, 170), (320, 180), (5, 5)]),
        ("noise", "time=1.5", [(320, 180), (250, 200), (100, 100)]),
        ("toon", "xangle=20", [(256, 256), (280, 150), (500, 20)]),
    ] {
        let png = dir.join(format!("gpu_pixel_{name}.png"));
        let png = png.to_str().expect("utf-8");
        let out = shaderlab(&["run", name, "--set", set, "--screenshot", png]);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let shot = image::open(png).expect("the screenshot").to_rgba8();
        for (x, y) in pixels {
            let at = format!("{x},{y}");
            let out = shaderlab(&["debug", name, "--pixel", &at, "--set", set, "--json"]);
            assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
            let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("one JSON object");
            assert_eq!(v["gpu_pixel"], serde_json::json!(shot.get_pixel(x, y).0), "{name} {at}");
            assert!(v.get("gpu_disagrees").is_none(), "{name} {at}: {v}");
        }
    }
    let out = shaderlab(&["debug", "phong", "--pixel", "320,180"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("; the GPU stored rgba("), "{text}");
    assert!(!text.contains("warning:"), "{text}");
}

/// A replay that does not follow what the GPU did says so in words, in the text and the
/// JSON: here the captured uniform block of phong's lights is zeroed after the GPU drew
/// the frame, so the replay draws black where the GPU drew the lit surface.
#[test]
fn a_replay_that_departs_from_the_gpu_says_so() {
    let mut lab = build("phong", &[]);
    let (w, h) = lab.info().size;
    let (image, mut captured) = capture_lab(gpu(), lab.as_mut(), w, h, true).expect("a capture");
    let image = image.expect("the picture");
    let (x, y) = (320, 180);
    let honest = Inspection::new("phong", &captured, x, y).expect("an inspection");
    assert!(honest.covered());
    assert_eq!(honest.gpu_pixel, Some(image.get_pixel(x, y).0));
    assert_eq!(honest.disagreement(), None, "{}", honest.text());
    let draw = honest.replayed.fragment.as_ref().expect("a fragment").draw;
    let params = captured.draws[draw]
        .bindings
        .iter()
        .find(|b| b.name == "PhongParams")
        .expect("phong's light and material block")
        .binding;
    for (binding, bytes) in &mut captured.draws[draw].uniforms {
        if *binding == params {
            *bytes = std::sync::Arc::new(vec![0u8; bytes.len()]);
        }
    }
    let i = match Inspection::new("phong", &captured, x, y) {
        Ok(i) => i,
        Err(e) => panic!("{e}"),
    };
    let words = i
        .disagreement()
        .unwrap_or_else(|| panic!("no disagreement:\n{}", i.text()));
    assert!(
        words.contains("the GPU stored rgba(") && words.contains("the replay gives"),
        "{words}"
    );
    let text = i.text();
    assert!(text.contains("warning: the GPU stored"), "{text}");
    let json: serde_json::Value = serde_json::from_str(&i.json()).expect("JSON");
    assert_eq!(json["gpu_disagrees"], serde_json::json!(words));
    assert_eq!(json["gpu_pixel"], serde_json::json!(image.get_pixel(x, y).0));
}

/// `shaderlab debug` replays before it runs the frame: where the replay of the pixel ends but
/// the frame never does (a loop taken only right of the pixel), the report still comes, with
/// `gpu_pixel` null and a note saying why, and the run ends at the watchdog.
#[test]
fn a_frame_that_never_ends_still_gets_its_report() {
    let dir = common::output_dir().join("gpu_pixel_endless");
    let _ = std::fs::remove_dir_all(&dir);
    common::copy_shaders(&dir);
    let path = dir.join("phong.frag");
    let heavy = "k = k + sin(k) * cos(k) + sin(k + 1.0) * cos(k + 2.0) + sin(k + 3.0) * cos(k + 4.0);";
    let text = std::fs::read_to_string(&path).expect("phong.frag").replacen(
        "    frag_color = ",
        &format!(
            "    float k = gl_FragCoord.x;\n    if (gl_FragCoord.x > 330.0) {{ for (int i = 0; i < 1000000000; i++) {{ {heavy} }} }}\n    frag_color = min(k, 1.0) * "
        ),
        1,
    );
    std::fs::write(&path, text).expect("write phong.frag");
    // Two lavapipe threads, so that the CPU the watchdog's two seconds cost is the same on any
    // machine.
    let (out, cpu) = common::output_with_cpu(
        std::process::Command::new(env!("CARGO_BIN_EXE_shaderlab"))
            .args(["debug", "phong", "--pixel", "320,180", "--shaders"])
            .arg(&dir)
            .args(["--timeout", "2", "--json"])
            .env("LP_NUM_THREADS", "2"),
    );
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    // Ended by the watchdog, not by the frame (minutes of CPU): CPU seconds, which a busy
    // machine does not inflate.
    assert!(cpu < 20.0, "{cpu:.1} s of CPU");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("one JSON object");
    assert_eq!(v["covered"], serde_json::Value::Bool(true), "{v}");
    assert_eq!(v["gpu_pixel"], serde_json::Value::Null, "{v}");
    let caveats = v["caveats"].to_string();
    assert!(caveats.contains("the pixel the GPU stores is not known"), "{caveats}");
}
