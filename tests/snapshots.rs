//! The redesign guard: the port's own output for every seed-000 lab x object at a rotated state
//! and for the port-only modes must stay byte-identical to `tests/snapshots/*.png`. Those files
//! are written only by the deliberate command `scripts/write-snapshots` (from the examples'
//! command lines), never by this test; this test renders the same states in-process.

mod common;

use shaderlab::labs;

fn snapshot(name: &str) -> image::RgbImage {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/snapshots")
        .join(format!("{name}.png"));
    image::open(&path)
        .unwrap_or_else(|e| {
            panic!(
                "{} missing or unreadable ({e}); snapshots are written by scripts/write-snapshots, never by the tests",
                path.display()
            )
        })
        .to_rgb8()
}

fn check(name: &str, entry: &shaderlab::LabEntry, set: &[(&str, &str)]) {
    let mut lab = common::lab(entry);
    for (key, value) in set {
        lab.set_str(key, value)
            .unwrap_or_else(|e| panic!("{name}: {key}={value}: {e}"));
    }
    let actual = lab.rgb(640, 360);
    let expected = snapshot(name);
    if actual != expected {
        let out = common::output_dir().join(format!("{name}.actual.png"));
        let _ = actual.save(&out);
        let differing = actual.pixels().zip(expected.pixels()).filter(|(a, b)| a != b).count();
        panic!(
            "{name}: {differing} pixels differ from the snapshot (port's image in {})",
            out.display()
        );
    }
}

#[test]
fn every_lab_and_object_is_unchanged() {
    for entry in [
        labs::POSITION_RGB,
        labs::NORMAL_RGB,
        labs::PHONG,
        labs::NOISE,
        labs::DISPLACEMENT,
    ] {
        for object in ["cube", "sphere", "torus", "teapot"] {
            let name = format!("{}_{object}", entry.info.name);
            let mut set = vec![("object", object), ("xangle", "30"), ("yangle", "45"), ("zangle", "10")];
            if entry.info.name == "noise" || entry.info.name == "displacement" {
                set.push(("time", "1.7"));
            }
            check(&name, entry, &set);
        }
    }
}

#[test]
fn port_only_modes_are_unchanged() {
    for shading in ["flat", "gouraud", "blinn"] {
        check(
            &format!("phong_torus_{shading}"),
            labs::PHONG,
            &[
                ("object", "torus"),
                ("xangle", "20"),
                ("yangle", "30"),
                ("shading", shading),
            ],
        );
    }
    check(
        "phong_sphere_tess_auto",
        labs::PHONG,
        &[("object", "sphere"), ("tess", "-1")],
    );
    check(
        "phong_teapot_keys",
        labs::PHONG,
        &[
            ("Ka", "0.3"),
            ("shininess", "8"),
            ("lightPosition", "1,2,3"),
            ("camera", "0.5,0,4.5"),
        ],
    );
    check(
        "displacement_teapot_smooth",
        labs::DISPLACEMENT,
        &[("object", "teapot"), ("smooth", "1"), ("time", "0.5")],
    );
    check(
        "displacement_sphere_tess_40",
        labs::DISPLACEMENT,
        &[("object", "sphere"), ("tess", "40"), ("time", "2.5")],
    );
    check(
        "noise_torus_shade",
        labs::NOISE,
        &[("object", "torus"), ("shade", "1,0.5,0.25"), ("time", "100")],
    );
}
