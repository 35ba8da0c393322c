//! In the shells' shared core: a session's whole-frame view is the library's picture
//! of the lab's state whether it is drawn at once (the window's way, `Platform::NATIVE`) or read
//! back over polls (the page's, `Platform::PAGE`), is drawn again when the lab changes, fills
//! the surface with its legend, and a view that cannot be drawn leaves its reason and the lab's
//! picture.

mod common;

use common::gpu;
use shaderlab::debug::{picture, view};
use shaderlab::lab::{Input, UserFiles};
use shaderlab::offscreen::{Offscreen, COLOR_FORMAT};
use shaderlab::shader::ShaderSource;
use shaderlab::shell::session::{Platform, Session, Sources, Target};
use shaderlab::shell::views::Wanted;

const SIZE: (u32, u32) = (320, 196);

fn session() -> Session {
    let entry = shaderlab::course::find("phong").expect("phong");
    let sources = Sources::new(ShaderSource::Embedded, UserFiles::default(), COLOR_FORMAT);
    let s = Session::open(entry, gpu(), sources, Platform::NATIVE, 0.0, 1.0).expect("phong opens");
    let mut s = s;
    s.set("object", "torus").expect("a torus");
    s
}

/// The library's picture of `probe` for the session's lab now.
fn library(s: &mut Session, probe: &view::Probe) -> image::RgbaImage {
    let (w, h) = (SIZE.0, SIZE.1 - picture::LEGEND_HEIGHT);
    let log = view::encode(gpu(), s.lab_mut(), w, h).expect("records");
    view::draw_view(gpu(), &log, probe, w, h).expect("draws").picture().0
}

fn phong_frag(s: &mut Session) -> String {
    (s.shader_files().into_iter().flat_map(|p| p.spliced))
        .find(|f| f.ends_with("phong.frag"))
        .expect("phong.frag")
}

/// What the session shows on a surface of `SIZE`, read back.
fn shown(s: &mut Session) -> image::RgbaImage {
    let target = Offscreen::with_format(gpu(), SIZE.0, SIZE.1, COLOR_FORMAT);
    let mut encoder = gpu().device.create_command_encoder(&Default::default());
    let drawn = Target {
        color: &target.color,
        depth: &target.depth,
        size: SIZE,
    };
    assert!(s.encode(gpu(), &mut encoder, &drawn).is_none());
    gpu().queue.submit([encoder.finish()]);
    target.read(gpu()).expect("reads back")
}

/// Moves the view on (`Session::poll`) the page's way (`polled`) or the window's, as each does
/// between frames.
fn step(s: &mut Session, polled: bool) -> bool {
    s.set_platform(if polled { Platform::PAGE } else { Platform::NATIVE });
    s.poll(gpu(), SIZE).view
}

/// Moves the view on until its picture and legend are there and nothing waits for the GPU,
/// as the window or the page does frame after frame.
fn settle(s: &mut Session, polled: bool) {
    let mut calls = 0;
    loop {
        step(s, polled);
        if s.view_shown().is_some() && !s.view_busy() {
            break;
        }
        calls += 1;
        assert!(calls < 100_000, "the view never came back");
        std::thread::yield_now();
    }
    let again = step(s, polled);
    assert!(!again, "nothing changed: nothing drawn");
}

/// The surface shows the library's picture: the legend strip byte for byte, the view's pixels
/// within 1 of 255 (the GPU colours in `f32`, the library in `f64`) at no more than 1 in 1,000.
fn same(got: &image::RgbaImage, want: &image::RgbaImage, what: &str) {
    assert_eq!(got.dimensions(), want.dimensions(), "{what}");
    let strip = want.height() - picture::LEGEND_HEIGHT;
    let (mut off, mut worst) = (0, 0);
    for (x, y, p) in want.enumerate_pixels() {
        let q = got.get_pixel(x, y);
        let d = (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap_or(0);
        if y >= strip {
            assert_eq!(d, 0, "{what}: the legend strip at {x},{y}");
        } else if d > 0 {
            off += 1;
            worst = worst.max(d);
        }
    }
    let n = want.width() * strip;
    assert!(
        worst <= 1 && off * 1000 <= n,
        "{what}: {off} of {n} pixels differ, by up to {worst}"
    );
}

#[test]
fn a_view_drawn_at_once_or_over_polls_is_the_librarys_picture_and_follows_the_lab() {
    for polled in [false, true] {
        let mut s = session();
        let file = phong_frag(&mut s);
        for (wanted, probe) in [
            (Wanted::COST, view::Probe::Cost),
            (
                Wanted::from_link(&format!("{file}:17")).expect("a line"),
                view::Probe::Line {
                    file: file.clone(),
                    line: 17,
                    name: None,
                    stage: None,
                },
            ),
        ] {
            s.show_view(gpu(), Some(wanted.clone()));
            let draw = |s: &mut Session| settle(s, polled);
            draw(&mut s);
            let want = library(&mut s, &probe);
            assert_eq!(want.dimensions(), SIZE, "the view and its legend fill the surface");
            let got = shown(&mut s);
            same(&got, &want, &format!("{wanted:?} (polled {polled})"));
            // The object turns and the light moves: the view is drawn again, at the new state.
            let yangle = s.lab().params().get("yangle").expect("yangle")[0] + 35.0;
            s.set("yangle", &yangle.to_string()).expect("turns");
            for _ in 0..6 {
                s.input(Input::Key('X'));
            }
            draw(&mut s);
            let moved = library(&mut s, &probe);
            assert!(moved != want, "the lab changed");
            same(
                &shown(&mut s),
                &moved,
                &format!("{wanted:?} (polled {polled}) follows the lab"),
            );
        }
        // Back to the picture.
        s.show_view(gpu(), None);
        let plain = shown(&mut s);
        let target = Offscreen::with_format(gpu(), SIZE.0, SIZE.1, COLOR_FORMAT);
        let lab = shaderlab::lab::frame::render_into(gpu(), s.lab_mut(), &target).and_then(|()| target.read(gpu()));
        assert!(plain == lab.expect("the lab draws"), "the lab's picture again");
    }
}

#[test]
fn a_view_that_cannot_be_drawn_says_why_and_the_picture_stays() {
    let mut s = session();
    let plain = shown(&mut s);
    let file = phong_frag(&mut s);
    for (wanted, says) in [
        (
            Wanted::from_link(&format!("{file}:1")).expect("a line"),
            "assigns nothing",
        ),
        (
            Wanted::from_link("nofile.frag:3").expect("a line"),
            "is not a file of a shader this lab draws",
        ),
        (Wanted::Diff, "there is nothing to compare"),
    ] {
        s.show_view(gpu(), Some(wanted.clone()));
        assert!(step(&mut s, false));
        let why = match s.view_shown() {
            Some(Err(e)) => e.clone(),
            other => panic!("{wanted:?}: {:?}", other.map(|r| r.as_ref().map(|p| p.text.clone()))),
        };
        assert!(why.contains(says), "{wanted:?}: {why}");
        assert!(shown(&mut s) == plain, "{wanted:?}: the lab's picture stays");
    }
}

/// On the page a view asked for while another is read back waits for that read-back (the
/// drawer's buffers are its until then), then is drawn: the picture is the new view's.
#[test]
fn a_view_asked_for_during_a_read_back_is_drawn_after_it() {
    let mut s = session();
    let file = phong_frag(&mut s);
    let line = Wanted::from_link(&format!("{file}:17")).expect("a line");
    s.show_view(gpu(), Some(Wanted::COST));
    assert!(!step(&mut s, true), "the read-back starts");
    assert!(s.view_busy());
    // The same view again (the same buffers), then another.
    s.show_view(gpu(), Some(Wanted::COST));
    s.show_view(gpu(), Some(line.clone()));
    settle(&mut s, true);
    let probe = view::Probe::Line {
        file,
        line: 17,
        name: None,
        stage: None,
    };
    let want = library(&mut s, &probe);
    same(&shown(&mut s), &want, "the picture is the line's");
    assert!(matches!(s.view_shown(), Some(Ok(p)) if p.text.contains(":17")));
}

/// A line that assigns two variables cannot be drawn as a view until one is chosen: the
/// session offers each name (the window's and the page's buttons), as it does for a name the
/// line does not assign, and the one chosen is drawn, the library's picture of that name, and
/// carried in the link.
#[test]
fn a_line_assigning_two_names_offers_each_and_draws_the_one_chosen() {
    let text = "#version 450\n\
        layout(location = 0) in vec3 normal;\n\
        layout(location = 0) out vec4 frag_color;\n\
        void main() {\n\
        \x20   vec3 a = normal; vec3 b = -normal;\n\
        \x20   frag_color = vec4(a + 0.25 * b, 1.0);\n\
        }\n";
    let edits: std::collections::BTreeMap<String, String> = [("normal_rgb.frag".to_owned(), text.to_owned())].into();
    let entry = shaderlab::course::find("normal_rgb").expect("normal_rgb");
    let sources = Sources::new(
        ShaderSource::Edited(std::sync::Arc::new(edits)),
        UserFiles::default(),
        COLOR_FORMAT,
    );
    let mut s = Session::open(entry, gpu(), sources, Platform::NATIVE, 0.0, 1.0).expect("the copy opens");
    let file = (s.shader_files().into_iter().flat_map(|p| p.spliced))
        .find(|f| f.ends_with("normal_rgb.frag"))
        .expect("normal_rgb.frag");
    s.show_view(gpu(), Wanted::from_link(&format!("{file}:5")));
    settle(&mut s, false);
    let why = match s.view_shown() {
        Some(Err(e)) => e.clone(),
        other => panic!("{:?}", other.map(|r| r.as_ref().map(|p| p.text.clone()))),
    };
    assert!(why.contains("choose one by its name"), "{why}");
    let offered: Vec<&str> = s.view_choices().iter().map(|(w, _)| w.as_str()).collect();
    assert_eq!(offered, ["a", "b"], "each name once");
    // A name the line does not assign (a typo in a link) offers the same choice.
    s.show_view(gpu(), Wanted::from_link(&format!("{file}:5:c")));
    settle(&mut s, false);
    assert!(
        matches!(s.view_shown(), Some(Err(e)) if e.contains("does not assign `c`")),
        "{:?}",
        s.view_shown().map(|r| r.as_ref().err().cloned())
    );
    let offered: Vec<&str> = s.view_choices().iter().map(|(w, _)| w.as_str()).collect();
    assert_eq!(offered, ["a", "b"], "the names it does assign");
    let (_, b) = s.view_choices()[1].clone();
    assert_eq!(b.link(), format!("{file}:5:b"), "the link carries the name");
    s.show_view(gpu(), Some(b));
    settle(&mut s, true);
    assert!(s.view_choices().is_empty(), "nothing to choose once drawn");
    let text = match s.view_shown() {
        Some(Ok(p)) => p.text.clone(),
        other => panic!("{:?}", other.map(|r| r.as_ref().err().cloned())),
    };
    assert!(text.contains("= `b`"), "the legend names b: {text}");
    let probe = view::Probe::Line {
        file: file.clone(),
        line: 5,
        name: Some("b".into()),
        stage: None,
    };
    let want = library(&mut s, &probe);
    same(&shown(&mut s), &want, "b's view");
    let a = view::Probe::Line {
        file,
        line: 5,
        name: Some("a".into()),
        stage: None,
    };
    assert!(library(&mut s, &a) != want, "a's view is another picture");
}

/// Every parameter write goes through the session with `--set`'s checks, the panel's too
/// (`set_values`, `reset`): a value out of range or against the lab's rules between parameters
/// (legacy's near before far) is refused and undone whole, and a taken one is drawn.
#[test]
fn every_parameter_write_is_checked_by_the_session_and_a_refused_one_undone() {
    let entry = shaderlab::course::find("legacy").expect("legacy");
    let sources = Sources::new(ShaderSource::Embedded, UserFiles::default(), COLOR_FORMAT);
    let mut s = Session::open(entry, gpu(), sources, Platform::NATIVE, 0.0, 1.0).expect("legacy opens");
    let value = |s: &Session, name: &str| s.lab().params().get(name).expect("a parameter").to_vec();
    let (near, far) = (value(&s, "near"), value(&s, "far"));
    // The panel's control asks near past far: refused, nothing changed.
    let e = s.set_values("near", &[far[0] + 1.0]).expect_err("near past far");
    assert!(e.to_string().contains("near"), "{e}");
    assert_eq!((value(&s, "near"), value(&s, "far")), (near.clone(), far.clone()));
    // As --set refuses it.
    assert!(s.set("near", &(far[0] + 1.0).to_string()).is_err());
    assert_eq!(value(&s, "near"), near);
    // Taken: the lab is drawn again.
    while s.dirty() > 0 {
        s.drawn();
    }
    s.set_values("near", &[near[0] * 2.0]).expect("a nearer plane");
    assert_eq!(value(&s, "near"), vec![near[0] * 2.0]);
    assert!(s.wants_frame(), "a write taken draws again");
    // Reset all: every parameter back to its default, through the same checks.
    s.reset().expect("the defaults pass the checks");
    assert_eq!(value(&s, "near"), near);
    // An unknown name or a value past a declared range is the same refusal as --set's.
    assert!(s.set_values("nosuch", &[1.0]).is_err());
}

/// The one resolver of a shader file name (the page's, `view`'s and the window's): a file by its
/// path, by a unique ending, or through another path; otherwise why, naming the lab's files.
#[test]
fn a_shader_file_is_found_by_its_path_its_name_or_another_path() {
    let mut s = session();
    let full = phong_frag(&mut s);
    assert_eq!(s.find_file(&full).as_deref(), Ok(full.as_str()));
    assert_eq!(s.find_file("phong.frag").as_deref(), Ok(full.as_str()));
    let absolute = std::fs::canonicalize(&full).expect("the source tree's file");
    assert_eq!(s.find_file(&absolute.to_string_lossy()).as_deref(), Ok(full.as_str()));
    let why = s.find_file("nofile.frag").expect_err("no such file");
    assert!(
        why.contains("is not a file of this lab's shaders") && why.contains(&full),
        "{why}"
    );
    // A diff in a session of the built-in shaders says why, and shows it in place of a view.
    let said = s.show_view(gpu(), Some(Wanted::Diff)).expect("words to say");
    assert!(said.contains("--shaders DIR"), "{said}");
}
