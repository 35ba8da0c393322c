//! Links that carry the shaders, on the command line: `shaderlab link` makes the page's link
//! with the files of a folder that differ from the built-in ones (or legacy's pair), and
//! `shaderlab open` writes a link's files into a folder and draws what `shaderlab run NAME
//! --shaders DIR` draws; a bad link (cut, damaged, past a limit, for no lab, with a parameter
//! the lab lacks, with a file name that is no plain name of a shader file) is one message,
//! status 2, and writes nothing; `open` never writes over a file. The page's side is in
//! tests/web.rs; the codec's own cases in src/shell/link.rs.

mod common;

use std::collections::BTreeMap;
use std::io::Write;
use std::path::Path;

use base64::Engine;
use shaderlab::shader::{embedded_names, embedded_source};
use shaderlab::shell::link::{Link, DEFAULT_BASE, MAX_FRAGMENT};

const SIZE: &str = "160x90";

fn ok(dir: &Path, args: &[&str]) -> String {
    let out = common::shaderlab_in(dir, args);
    assert!(
        out.status.success(),
        "{args:?}: status {:?}: {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("UTF-8")
}

fn read(path: &Path) -> Vec<u8> {
    std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The files of `dir` whose text differs from the built-in namesake's (or that have none), by
/// name.
fn differing(dir: &Path) -> BTreeMap<String, String> {
    common::names_in(dir)
        .into_iter()
        .filter_map(|name| {
            let text = std::fs::read_to_string(dir.join(&name)).expect("a text file");
            (embedded_source(&name) != Some(text.as_str())).then_some((name, text))
        })
        .collect()
}

/// A copy of the built-in shaders in `dir` with phong's diffuse term floored at 0.5.
fn edited_copy(dir: &Path) -> String {
    common::copy_shaders(dir);
    let text = embedded_source("phong.frag").unwrap();
    let edited = text.replacen("max(dot(N, L), 0.0)", "max(dot(N, L), 0.5)", 1);
    assert_ne!(text, edited, "the edit applies");
    std::fs::write(dir.join("phong.frag"), &edited).expect("the edit");
    edited
}

const STATE: &[&str] = &["--set", "Ka=0.2", "--set", "object=torus", "--size", SIZE];

#[test]
fn a_link_opened_writes_its_files_and_draws_what_run_draws_from_the_copy() {
    let dir = common::fresh_dir("links_phong");
    let edited = edited_copy(&dir.join("copy"));
    let mut args = vec![
        "link",
        "phong",
        "--shaders",
        "copy",
        "--set",
        "Ka=0.2",
        "--set",
        "object=torus",
    ];
    let link = ok(&dir, &args).trim().to_owned();
    println!("{} characters: {link}", link.len());
    assert!(
        link.starts_with("http://127.0.0.1:8000/?lab=phong&set=Ka%3D0.2&set=object%3Dtorus#files="),
        "{link}"
    );
    assert_eq!(
        Link::parse(&link).unwrap().files.keys().collect::<Vec<_>>(),
        ["phong.frag"]
    );
    let mut open = vec!["open", &link, "--into", "opened", "--screenshot", "opened.png"];
    open.extend_from_slice(&STATE[4..]);
    ok(&dir, &open);
    // The folder: the link's file, and the built-in ones beside it, so that it serves
    // --shaders as it is.
    let opened = dir.join("opened");
    let names: Vec<String> = common::names_in(&opened);
    let mut built_in: Vec<String> = embedded_names().map(str::to_owned).collect();
    built_in.sort();
    assert_eq!(names, built_in, "a whole copy, nothing else");
    assert_eq!(
        differing(&opened),
        BTreeMap::from([("phong.frag".to_owned(), edited)]),
        "exactly the link's file differs from the built-in text"
    );
    let mut run = vec!["run", "phong", "--shaders", "copy", "--screenshot", "run.png"];
    run.extend_from_slice(STATE);
    ok(&dir, &run);
    assert_eq!(
        read(&dir.join("opened.png")),
        read(&dir.join("run.png")),
        "the same bytes"
    );
    let mut plain = vec!["run", "phong", "--screenshot", "built-in.png"];
    plain.extend_from_slice(STATE);
    ok(&dir, &plain);
    assert_ne!(
        read(&dir.join("opened.png")),
        read(&dir.join("built-in.png")),
        "the link's copy draws, not the built-in shader"
    );
    // The folder open wrote makes the same link again.
    args[3] = "opened";
    assert_eq!(ok(&dir, &args).trim(), link, "the link comes back from the folder");
}

#[test]
fn legacys_pair_travels_by_its_names_and_draws_as_legacy_draws_it() {
    let dir = common::fresh_dir("links_legacy");
    let course = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/course/seed000");
    let (vert, frag) = (course.join("lab3.vert"), course.join("lab3.frag"));
    let (vert, frag) = (vert.to_str().unwrap(), frag.to_str().unwrap());
    let mut state: Vec<String> = vec!["--set".into(), "object=torus".into()];
    for (k, v) in shaderlab::course::legacy::course_state(3) {
        state.extend(["--set".to_owned(), format!("{k}={v}")]);
    }
    let state: Vec<&str> = state.iter().map(String::as_str).collect();
    let mut args = vec!["link", "legacy", vert, frag, "--base", "http://example.org/shaderlab/"];
    args.extend_from_slice(&state);
    let link = ok(&dir, &args).trim().to_owned();
    assert!(
        link.starts_with(
            "http://example.org/shaderlab/?lab=legacy&set=files%3Dlab3.vert%2Clab3.frag&set=object%3Dtorus"
        ),
        "{link}"
    );
    ok(
        &dir,
        &[
            "open",
            &link,
            "--into",
            "pair",
            "--screenshot",
            "opened.png",
            "--size",
            SIZE,
        ],
    );
    assert_eq!(
        common::names_in(&dir.join("pair")),
        ["lab3.frag", "lab3.vert"],
        "the pair alone"
    );
    assert_eq!(read(&dir.join("pair/lab3.vert")), read(Path::new(vert)));
    assert_eq!(read(&dir.join("pair/lab3.frag")), read(Path::new(frag)));
    let mut run = vec!["legacy", vert, frag, "--screenshot", "run.png", "--size", SIZE];
    run.extend_from_slice(&state);
    ok(&dir, &run);
    assert_eq!(
        read(&dir.join("opened.png")),
        read(&dir.join("run.png")),
        "the same bytes"
    );
    // Names a link cannot carry, and --shaders, which legacy does not read.
    for (args, says) in [
        (vec!["link", "legacy", vert, vert], "the same file name `lab3.vert`"),
        (vec!["link", "legacy", vert], "legacy takes two files: VERT FRAG"),
        (
            vec!["link", "legacy", "--shaders", "."],
            "`--shaders` reads a lab's shaders from a folder",
        ),
        (vec!["link", "phong", vert, frag], "phong takes no files"),
        (vec!["link", "phong", "--base", "http://h/?x=1"], "without `?` or `#`"),
    ] {
        let out = common::shaderlab_in(&dir, &args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?}");
    }
    // A pair that does not compile (the course's lab 5 as printed) is carried as it is: open
    // writes it, to be mended, and the run says what is wrong with it.
    let (v5, f5) = (course.join("lab5.vert"), course.join("lab5.frag"));
    let link5 = ok(&dir, &["link", "legacy", v5.to_str().unwrap(), f5.to_str().unwrap()]);
    let out = common::shaderlab_in(
        &dir,
        &["open", link5.trim(), "--into", "lab5", "--screenshot", "lab5.png"],
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("lab5/lab5.vert:37:45:"),
        "the shader's error, in the file written: {err}"
    );
    assert_eq!(common::names_in(&dir.join("lab5")), ["lab5.frag", "lab5.vert"]);
    assert!(!dir.join("lab5.png").exists());
    std::fs::copy(vert, dir.join("V")).unwrap();
    std::fs::copy(frag, dir.join("F")).unwrap();
    let out = common::shaderlab_in(&dir, &["link", "legacy", "V", "F"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("a file named `V`: not the name of a shader file legacy reads"),
        "{err}"
    );
}

/// A link's fragment of `json`, compressed as a link's is.
fn fragment_of(json: &[u8]) -> String {
    let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::best());
    z.write_all(json).unwrap();
    base64::engine::general_purpose::URL_SAFE_NO_PAD.encode(z.finish().unwrap())
}

/// Each kind of bad link, as `shaderlab open` is given it: status 2, its message, and nothing
/// written (neither the folder, named or the default, nor the picture).
#[test]
fn a_bad_link_says_what_is_wrong_and_writes_nothing() {
    let dir = common::fresh_dir("links_bad");
    let work = dir.join("work");
    std::fs::create_dir_all(&work).unwrap();
    let edited = edited_copy(&dir.join("copy"));
    let good = ok(&dir, &["link", "phong", "--shaders", "copy"]).trim().to_owned();
    let (head, fragment) = good.split_once('#').unwrap();
    let with_file = |name: &str| {
        let link = Link {
            files: [(name.to_owned(), edited.clone())].into(),
            ..Link::new(DEFAULT_BASE, "phong")
        };
        link.to_url().unwrap()
    };
    let mut unknown_parameter = Link::parse(&good).unwrap();
    unknown_parameter.push_set("nosuch=1");
    let middle = fragment.len() / 2;
    let flipped = if fragment.as_bytes()[middle] == b'A' { "B" } else { "A" };
    let mut bomb = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::best());
    for _ in 0..16 {
        bomb.write_all(&[b' '; 1 << 20]).unwrap();
    }
    let bomb = base64::engine::general_purpose::URL_SAFE_NO_PAD.encode(bomb.finish().unwrap());
    let cases: Vec<(&str, String, &str)> = vec![
        ("cut", good[..good.len() - 30].to_owned(), "cut short or damaged"),
        (
            "damaged",
            format!("{head}#{}{flipped}{}", &fragment[..middle], &fragment[middle + 1..]),
            "cut short or damaged",
        ),
        (
            "unknown lab",
            good.replace("lab=phong", "lab=nosuch"),
            "no lab called `nosuch`",
        ),
        (
            "unknown parameter",
            unknown_parameter.to_url().unwrap(),
            "the link's `set=nosuch=1`: unknown parameter `nosuch` for phong",
        ),
        (
            "folder",
            with_file("sub/phong.frag"),
            "`sub/phong.frag`: the name has a folder",
        ),
        (
            "dotdot",
            with_file("../phong.frag"),
            "`../phong.frag`: `..` climbs out of the folder",
        ),
        (
            "absolute",
            with_file("/tmp/phong.frag"),
            "`/tmp/phong.frag`: an absolute path",
        ),
        (
            "not a shader",
            with_file("notes.txt"),
            "not a shader file phong could read",
        ),
        (
            "too long",
            format!("{head}#files={}", "A".repeat(MAX_FRAGMENT + 1)),
            "more than a link carries (32768)",
        ),
        (
            "too large",
            format!("{head}#files={bomb}"),
            "more than 1048576 bytes (1 MiB) once decompressed",
        ),
        (
            "newer",
            format!("{head}#files={}", fragment_of(br#"{"v":2,"files":{}}"#)),
            "format 2, newer than this shaderlab reads",
        ),
        ("not a link", "phong".to_owned(), "the link names no lab"),
    ];
    for (what, link, says) in &cases {
        for into in [&["--into", "out"][..], &[]] {
            let mut args = vec!["open", link.as_str()];
            args.extend_from_slice(into);
            args.extend(["--screenshot", "x.png"]);
            let out = common::shaderlab_in(&work, &args);
            let err = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{what}: {err}");
            assert!(err.contains(says), "{what}: {err}");
            assert_eq!(err.trim().lines().count(), 1, "{what}: one message: {err}");
            assert!(!err.contains("panicked"), "{what}: {err}");
            assert_eq!(common::names_in(&work), Vec::<String>::new(), "{what}: nothing written");
        }
    }
    // A bad flag or state given with a good link writes nothing either.
    for (args, says) in [
        (
            vec!["open", &good, "--set", "nosuch=1"],
            "unknown parameter `nosuch` for phong",
        ),
        (
            vec!["open", &good, "--shaders", "copy"],
            "`--shaders` reads a lab's shaders from a folder",
        ),
        (vec!["open", &good, "--diff", "copy"], "`--diff` compares a copy"),
        (vec!["open", &good, "--screenshot", "x.txt"], "x.txt"),
        (vec!["open", &good, "--into"], "`--into` needs a folder"),
        (vec!["open"], "which link?"),
    ] {
        let out = common::shaderlab_in(&work, &args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert_eq!(
            common::names_in(&work),
            Vec::<String>::new(),
            "{args:?}: nothing written"
        );
    }
}

/// `open` writes over no file: a folder that has one of the names (the link's file or a
/// built-in one beside it) is refused and keeps its bytes, and nothing else is written.
#[test]
fn open_never_writes_over_a_file() {
    let dir = common::fresh_dir("links_overwrite");
    edited_copy(&dir.join("copy"));
    let link = ok(&dir, &["link", "phong", "--shaders", "copy"]).trim().to_owned();
    for name in ["phong.frag", "bump.frag"] {
        let into = dir.join(format!("mine-{name}"));
        std::fs::create_dir_all(&into).unwrap();
        std::fs::write(into.join(name), "my own work").unwrap();
        let out = common::shaderlab_in(
            &dir,
            &["open", &link, "--into", into.to_str().unwrap(), "--screenshot", "x.png"],
        );
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(
            err.contains(&format!("{name}: exists; shaderlab open never writes over a file")),
            "{err}"
        );
        assert_eq!(common::names_in(&into), [name], "nothing written beside it");
        assert_eq!(std::fs::read_to_string(into.join(name)).unwrap(), "my own work");
        assert!(!dir.join("x.png").exists());
    }
    // The default folder, ./NAME-shaders/: made by the first open, refused by the second.
    ok(&dir, &["open", &link, "--screenshot", "first.png", "--size", SIZE]);
    assert!(dir.join("phong-shaders/phong.frag").is_file());
    let out = common::shaderlab_in(&dir, &["open", &link, "--screenshot", "second.png"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("exists"), "{err}");
    assert!(!dir.join("second.png").exists());
}

/// A copy too large for a link says so, and prints no link.
#[test]
fn a_copy_too_large_for_a_link_says_so() {
    let dir = common::fresh_dir("links_large");
    let copy = dir.join("copy");
    common::copy_shaders(&copy);
    let mut state = 7u64;
    let noise: String = (0..60_000)
        .map(|k| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            if k % 80 == 79 {
                '\n'
            } else {
                char::from(b'!' + (state >> 58) as u8)
            }
        })
        .collect();
    std::fs::write(copy.join("mine.glsl"), format!("// {noise}\n")).unwrap();
    let out = common::shaderlab_in(&dir, &["link", "phong", "--shaders", "copy"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("(mine.glsl) come to") && err.contains("more than a link carries"),
        "{err}"
    );
    assert!(out.stdout.is_empty());
}
