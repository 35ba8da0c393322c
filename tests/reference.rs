//! The port against the original programs, as one table: for every lecture, each reference
//! state (a lab and its parameters) must match the original program's picture
//! (`tests/reference/`, rendered by the originals with Mesa llvmpipe; never written by a test)
//! to the PSNR its row states. On a miss the port's picture and a difference picture are
//! written to `target/test-output/` and the failure names every row that missed.

mod common;

use shaderlab::metrics::{diff_image, psnr};

use shaderlab::course::states::REFERENCE as ROWS;

#[test]
fn every_reference_state_matches_the_original() {
    let out = common::output_dir();
    let mut failures = Vec::new();
    for row in ROWS {
        let entry = shaderlab::course::find(row.lab).unwrap_or_else(|| panic!("no lab {}", row.lab));
        let expected = common::reference(row.reference);
        let actual = common::render_state(entry, row.state);
        let db = psnr(&actual, &expected).unwrap_or_else(|| panic!("{}: not the reference's size", row.reference));
        println!("{} {:?} against {}: {db:.2} dB", row.lab, row.state, row.reference);
        if db < row.min_db {
            let stem = row.reference.replace('/', "_").replace(".png", "");
            let _ = actual.save(out.join(format!("{stem}.actual.png")));
            if let Some(d) = diff_image(&actual, &expected) {
                let _ = d.save(out.join(format!("{stem}.diff.png")));
            }
            failures.push(format!(
                "{} {:?}: {db:.2} dB < {} against {}",
                row.lab, row.state, row.min_db, row.reference
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "pictures differ from the originals':\n{}",
        failures.join("\n")
    );
}

/// The table covers every lecture's lab at least once (a new lab needs its row, and its
/// original's picture).
#[test]
fn every_lab_but_legacy_has_a_row() {
    for entry in shaderlab::course::ALL {
        let name = entry.info.name;
        assert!(
            name == "legacy" || ROWS.iter().any(|r| r.lab == name),
            "{name} has no reference row"
        );
    }
}
