//! Unit tests of the translation, construct by construct, and of error positions.

use super::*;

fn src(path: &str, text: &str) -> LegacySource {
    LegacySource::new(path, text)
}

fn fixture(dir: &str, name: &str) -> LegacySource {
    let path = format!("{}/tests/fixtures/{dir}/{name}", env!("CARGO_MANIFEST_DIR"));
    LegacySource::read(std::path::Path::new(&path)).expect("fixture")
}

/// Seed 000's shaders: the course's files, lab 4 and 5 with their one-parenthesis mend.
fn course(lab: u32) -> (LegacySource, LegacySource) {
    let pick = |name: String| {
        if name == "lab4.frag" || name == "lab5.vert" {
            fixture("course000-mended", &name)
        } else {
            fixture("course000", &name)
        }
    };
    (pick(format!("lab{lab}.vert")), pick(format!("lab{lab}.frag")))
}

#[test]
fn course_shaders_translate_and_validate() {
    for lab in 1..=5 {
        let (v, f) = course(lab);
        let t = translate(&v, &f).unwrap_or_else(|e| panic!("lab{lab}: {e}"));
        t.compile()
            .unwrap_or_else(|e| panic!("lab{lab}: {e}\n{}\n{}", t.vertex.output.text, t.fragment.output.text));
    }
}

#[test]
fn course_parenthesis_errors_point_at_the_course_line() {
    let (v, _) = course(4);
    let e = translate(&v, &fixture("course000", "lab4.frag")).unwrap_err();
    let Error::Shader { file, line, column, message } = e else { panic!("{e:?}") };
    assert!(file.ends_with("course000/lab4.frag"), "{file}");
    assert_eq!((line, column), (34, 46), "{message}");
    assert!(message.contains("unexpected `)`"), "{message}");
}

#[test]
#[ignore]
fn print_lab3() {
    let (v, f) = course(3);
    let t = translate(&v, &f).unwrap();
    println!("{}\n-----\n{}", t.vertex.output.text, t.fragment.output.text);
}
