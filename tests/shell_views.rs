//! In the shells' shared core: a session's whole-frame view is the library's picture
//! of the lab's state whether it is drawn at once (the window's `Session::view_frame`) or read
//! back over polls (the page's `Session::view_poll`), is drawn again when the lab changes, fills
//! the surface with its legend, and a view that cannot be drawn leaves its reason and the lab's
//! picture.

mod common;

use common::gpu;
use shaderlab::debug::{picture, view};
use shaderlab::lab::{Input, UserFiles};
use shaderlab::offscreen::{Offscreen, COLOR_FORMAT};
use shaderlab::shader::ShaderSource;
use shaderlab::shell::session::Session;
use shaderlab::shell::views::Wanted;

const SIZE: (u32, u32) = (320, 196);

fn session() -> Session {
    let entry = shaderlab::course::find("phong").expect("phong");
    let s = Session::open(
        entry,
        gpu(),
        &ShaderSource::Embedded,
        COLOR_FORMAT,
        &UserFiles::default(),
        0.0,
        1.0,
    )
    .expect("phong opens");
    let mut s = s;
    s.set("object", "torus").expect("a torus");
    s
}

/// The library's picture of `probe` for the session's lab now.
fn library(s: &mut Session, probe: &view::Probe) -> image::RgbaImage {
    let (w, h) = (SIZE.0, SIZE.1 - picture::LEGEND_HEIGHT);
    let log = view::record(gpu(), s.lab_mut(), w, h).expect("records");
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
    if !s.record_view(gpu(), &mut encoder, &target.color, COLOR_FORMAT) {
        assert!(s
            .record(gpu(), &mut encoder, &target.color, &target.depth, SIZE)
            .is_none());
    }
    gpu().queue.submit([encoder.finish()]);
    target.read(gpu()).expect("reads back")
}

/// Moves the view on until its picture and legend are there and nothing waits for the GPU,
/// as the window (`view_frame`) or the page (`view_poll`) does frame after frame.
fn settle(s: &mut Session, polled: bool) {
    let mut calls = 0;
    loop {
        if polled {
            s.view_poll(gpu(), SIZE, COLOR_FORMAT);
        } else {
            s.view_frame(gpu(), SIZE, COLOR_FORMAT);
        }
        if s.view_shown().is_some() && !s.view_busy() {
            break;
        }
        calls += 1;
        assert!(calls < 100_000, "the view never came back");
        std::thread::yield_now();
    }
    let again = if polled {
        s.view_poll(gpu(), SIZE, COLOR_FORMAT)
    } else {
        s.view_frame(gpu(), SIZE, COLOR_FORMAT)
    };
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
            s.set_view(Some(wanted.clone()), None);
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
        s.set_view(None, None);
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
        s.set_view(Some(wanted.clone()), None);
        assert!(s.view_frame(gpu(), SIZE, COLOR_FORMAT));
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
    s.set_view(Some(Wanted::COST), None);
    assert!(!s.view_poll(gpu(), SIZE, COLOR_FORMAT), "the read-back starts");
    assert!(s.view_busy());
    // The same view again (the same buffers), then another.
    s.set_view(Some(Wanted::COST), None);
    s.set_view(Some(line.clone()), None);
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
    let mut s = Session::open(
        entry,
        gpu(),
        &ShaderSource::Edited(std::sync::Arc::new(edits)),
        COLOR_FORMAT,
        &UserFiles::default(),
        0.0,
        1.0,
    )
    .expect("the copy opens");
    let file = (s.shader_files().into_iter().flat_map(|p| p.spliced))
        .find(|f| f.ends_with("normal_rgb.frag"))
        .expect("normal_rgb.frag");
    s.set_view(Wanted::from_link(&format!("{file}:5")), None);
    settle(&mut s, false);
    let why = match s.view_shown() {
        Some(Err(e)) => e.clone(),
        other => panic!("{:?}", other.map(|r| r.as_ref().map(|p| p.text.clone()))),
    };
    assert!(why.contains("choose one by its name"), "{why}");
    let offered: Vec<&str> = s.view_choices().iter().map(|(w, _)| w.as_str()).collect();
    assert_eq!(offered, ["a", "b"], "each name once");
    // A name the line does not assign (a typo in a link) offers the same choice.
    s.set_view(Wanted::from_link(&format!("{file}:5:c")), None);
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
    s.set_view(Some(b), None);
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
