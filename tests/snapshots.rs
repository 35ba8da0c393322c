//! The redesign guard, as one table: the port's own output for every lab at a state away from
//! its defaults (and seed 000's labs on every object, and the port-only modes) must stay
//! byte-identical to `tests/snapshots/NAME.png`. Those files are written only by the deliberate
//! `scripts/write-snapshots` (this file's ignored `write_snapshots`, which also needs
//! `SHADERLAB_WRITE_REFERENCES=1`, run when a picture is meant to change), never by the test
//! that reads them, even under `--include-ignored`.

mod common;

use shaderlab::course::states::SNAPSHOTS as ROWS;

fn path(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/snapshots")
        .join(format!("{name}.png"))
}

/// The port's picture of a row, at the lab's own size.
fn render(lab: &str, state: &[(&str, &str)]) -> image::RgbImage {
    let entry = shaderlab::course::find(lab).unwrap_or_else(|| panic!("no lab {lab}"));
    common::render_state(entry, state)
}

#[test]
fn every_lab_is_unchanged() {
    let mut failures = Vec::new();
    for (name, lab, state) in ROWS {
        let expected = image::open(path(name))
            .unwrap_or_else(|e| {
                panic!("{name}.png missing or unreadable ({e}); snapshots are written by scripts/write-snapshots, never by the tests")
            })
            .to_rgb8();
        let actual = render(lab, state);
        if actual != expected {
            let out = common::output_dir().join(format!("{name}.actual.png"));
            let _ = actual.save(&out);
            let differing = if actual.dimensions() == expected.dimensions() {
                actual.pixels().zip(expected.pixels()).filter(|(a, b)| a != b).count()
            } else {
                usize::MAX
            };
            failures.push(format!(
                "{name}: {differing} pixels differ (the port's picture: {})",
                out.display()
            ));
        }
    }
    assert!(failures.is_empty(), "snapshots changed:\n{}", failures.join("\n"));
}

/// Every lab has at least one row.
#[test]
fn every_lab_has_a_snapshot() {
    for entry in shaderlab::course::ALL {
        let name = entry.info.name;
        assert!(ROWS.iter().any(|r| r.1 == name), "{name} has no snapshot row");
    }
}

/// Writes every row's picture: run deliberately (`scripts/write-snapshots`, which sets
/// `SHADERLAB_WRITE_REFERENCES=1`) when a picture is meant to change, and look at what changed
/// before committing it.
#[test]
#[ignore = "writes tests/snapshots/: run through scripts/write-snapshots"]
fn write_snapshots() {
    common::require_write_opt_in("scripts/write-snapshots");
    for (name, lab, state) in ROWS {
        render(lab, state).save(path(name)).expect("write a snapshot");
    }
}
