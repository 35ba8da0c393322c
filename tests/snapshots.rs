//! The redesign guard, as one table: the port's own output for every lab at a state away from
//! its defaults (and seed 000's labs on every object, and the port-only modes) must stay
//! byte-identical to `tests/snapshots/NAME.png`. Those files are written only by the deliberate
//! `scripts/write-snapshots` (this file's ignored `write_snapshots`, which also needs
//! `SHADERLAB_WRITE_REFERENCES=1`, run when a picture is meant to change), never by the test
//! that reads them, even under `--include-ignored`.

mod common;

/// One row: the snapshot's name, the lab, its state (`--set` assignments on its defaults).
type Row = (&'static str, &'static str, &'static [(&'static str, &'static str)]);

const TURNED: &[(&str, &str)] = &[("xangle", "30"), ("yangle", "45")];

static ROWS: &[Row] = &[
    // Seed 000: every exercise on every object at a rotated state (the noise labs at 1.7 s).
    (
        "position_rgb_cube",
        "position_rgb",
        &[("object", "cube"), ("xangle", "30"), ("yangle", "45"), ("zangle", "10")],
    ),
    (
        "position_rgb_sphere",
        "position_rgb",
        &[
            ("object", "sphere"),
            ("xangle", "30"),
            ("yangle", "45"),
            ("zangle", "10"),
        ],
    ),
    (
        "position_rgb_torus",
        "position_rgb",
        &[
            ("object", "torus"),
            ("xangle", "30"),
            ("yangle", "45"),
            ("zangle", "10"),
        ],
    ),
    (
        "position_rgb_teapot",
        "position_rgb",
        &[
            ("object", "teapot"),
            ("xangle", "30"),
            ("yangle", "45"),
            ("zangle", "10"),
        ],
    ),
    (
        "normal_rgb_cube",
        "normal_rgb",
        &[("object", "cube"), ("xangle", "30"), ("yangle", "45"), ("zangle", "10")],
    ),
    (
        "normal_rgb_sphere",
        "normal_rgb",
        &[
            ("object", "sphere"),
            ("xangle", "30"),
            ("yangle", "45"),
            ("zangle", "10"),
        ],
    ),
    (
        "normal_rgb_torus",
        "normal_rgb",
        &[
            ("object", "torus"),
            ("xangle", "30"),
            ("yangle", "45"),
            ("zangle", "10"),
        ],
    ),
    (
        "normal_rgb_teapot",
        "normal_rgb",
        &[
            ("object", "teapot"),
            ("xangle", "30"),
            ("yangle", "45"),
            ("zangle", "10"),
        ],
    ),
    (
        "phong_cube",
        "phong",
        &[("object", "cube"), ("xangle", "30"), ("yangle", "45"), ("zangle", "10")],
    ),
    (
        "phong_sphere",
        "phong",
        &[
            ("object", "sphere"),
            ("xangle", "30"),
            ("yangle", "45"),
            ("zangle", "10"),
        ],
    ),
    (
        "phong_torus",
        "phong",
        &[
            ("object", "torus"),
            ("xangle", "30"),
            ("yangle", "45"),
            ("zangle", "10"),
        ],
    ),
    (
        "phong_teapot",
        "phong",
        &[
            ("object", "teapot"),
            ("xangle", "30"),
            ("yangle", "45"),
            ("zangle", "10"),
        ],
    ),
    (
        "noise_cube",
        "noise",
        &[
            ("object", "cube"),
            ("xangle", "30"),
            ("yangle", "45"),
            ("zangle", "10"),
            ("time", "1.7"),
        ],
    ),
    (
        "noise_sphere",
        "noise",
        &[
            ("object", "sphere"),
            ("xangle", "30"),
            ("yangle", "45"),
            ("zangle", "10"),
            ("time", "1.7"),
        ],
    ),
    (
        "noise_torus",
        "noise",
        &[
            ("object", "torus"),
            ("xangle", "30"),
            ("yangle", "45"),
            ("zangle", "10"),
            ("time", "1.7"),
        ],
    ),
    (
        "noise_teapot",
        "noise",
        &[
            ("object", "teapot"),
            ("xangle", "30"),
            ("yangle", "45"),
            ("zangle", "10"),
            ("time", "1.7"),
        ],
    ),
    (
        "displacement_cube",
        "displacement",
        &[
            ("object", "cube"),
            ("xangle", "30"),
            ("yangle", "45"),
            ("zangle", "10"),
            ("time", "1.7"),
        ],
    ),
    (
        "displacement_sphere",
        "displacement",
        &[
            ("object", "sphere"),
            ("xangle", "30"),
            ("yangle", "45"),
            ("zangle", "10"),
            ("time", "1.7"),
        ],
    ),
    (
        "displacement_torus",
        "displacement",
        &[
            ("object", "torus"),
            ("xangle", "30"),
            ("yangle", "45"),
            ("zangle", "10"),
            ("time", "1.7"),
        ],
    ),
    (
        "displacement_teapot",
        "displacement",
        &[
            ("object", "teapot"),
            ("xangle", "30"),
            ("yangle", "45"),
            ("zangle", "10"),
            ("time", "1.7"),
        ],
    ),
    // Seed 000's port-only modes.
    (
        "phong_torus_flat",
        "phong",
        &[
            ("object", "torus"),
            ("xangle", "20"),
            ("yangle", "30"),
            ("shading", "flat"),
        ],
    ),
    (
        "phong_torus_gouraud",
        "phong",
        &[
            ("object", "torus"),
            ("xangle", "20"),
            ("yangle", "30"),
            ("shading", "gouraud"),
        ],
    ),
    (
        "phong_torus_blinn",
        "phong",
        &[
            ("object", "torus"),
            ("xangle", "20"),
            ("yangle", "30"),
            ("shading", "blinn"),
        ],
    ),
    (
        "phong_sphere_tess_auto",
        "phong",
        &[("object", "sphere"), ("tess", "-1")],
    ),
    (
        "phong_teapot_keys",
        "phong",
        &[
            ("Ka", "0.3"),
            ("shininess", "8"),
            ("lightPosition", "1,2,3"),
            ("camera", "0.5,0,4.5"),
        ],
    ),
    (
        "displacement_teapot_smooth",
        "displacement",
        &[("object", "teapot"), ("smooth", "1"), ("time", "0.5")],
    ),
    (
        "displacement_sphere_tess_40",
        "displacement",
        &[("object", "sphere"), ("tess", "40"), ("time", "2.5")],
    ),
    (
        "noise_torus_shade",
        "noise",
        &[("object", "torus"), ("shade", "1,0.5,0.25"), ("time", "100")],
    ),
    // Every other lab, at a state away from its defaults.
    (
        "height_arrays",
        "height",
        &[("mode", "1"), ("xangle", "30"), ("yangle", "45")],
    ),
    ("uniform_arrays_turned", "uniform_arrays", TURNED),
    (
        "wave_moving",
        "wave",
        &[("time", "1.3"), ("xangle", "30"), ("yangle", "45"), ("subdiv", "2")],
    ),
    ("morph_midway", "morph", &[("time", "1"), ("xangle", "30")]),
    ("particles_falling", "particles", &[("time", "0.6"), ("yangle", "45")]),
    (
        "toon_torus",
        "toon",
        &[("object", "torus"), ("xangle", "30"), ("yangle", "45")],
    ),
    (
        "phong_vertex_sphere",
        "phong_vertex",
        &[("object", "sphere"), ("lx", "-2"), ("shininess", "10")],
    ),
    (
        "phong_fragment_compare",
        "phong_fragment",
        &[("compare", "1"), ("xangle", "30")],
    ),
    ("texture_turned", "texture", TURNED),
    (
        "envmap_torus",
        "envmap",
        &[("object", "torus"), ("xangle", "30"), ("yangle", "45")],
    ),
    (
        "bump_turned",
        "bump",
        &[("xangle", "20"), ("yangle", "-30"), ("blx", "-1")],
    ),
    (
        "normmap_turned",
        "normmap",
        &[("xangle", "20"), ("yangle", "-30"), ("blx", "-1")],
    ),
    (
        "twist_twisting_2",
        "twist",
        &[("twisting", "2"), ("color", "0.9,0.4,0.2")],
    ),
    (
        "double_vision_apart",
        "double_vision",
        &[("left_x", "0.3"), ("right_y", "0.2")],
    ),
    ("normal_world_turned", "normal_world", &[("rx", "30"), ("ry", "45")]),
    ("phong_dir_fixed", "phong_dir", &[("rx", "40"), ("fixpos", "1")]),
    (
        "specular_strip_moved",
        "specular_strip",
        &[("forward", "1"), ("yaw", "10"), ("lightx", "1")],
    ),
    ("suzanne_normal_color_turned", "suzanne_normal_color", TURNED),
    ("suzanne_normal_matrix_turned", "suzanne_normal_matrix", TURNED),
    ("suzanne_smooth_turned", "suzanne_smooth", TURNED),
    (
        "suzanne_texture_uv",
        "suzanne_texture",
        &[("tex", "1"), ("xangle", "30"), ("yangle", "45")],
    ),
    ("suzanne_texture_color_turned", "suzanne_texture_color", TURNED),
    (
        "texparams_clamped",
        "texparams",
        &[("wrap_s", "1"), ("min", "3"), ("mag", "1")],
    ),
    (
        "suzanne_flat_turned",
        "suzanne_flat",
        &[("xangle", "30"), ("yangle", "45"), ("shininess", "8")],
    ),
    ("suzanne_gouraud_turned", "suzanne_gouraud", TURNED),
    (
        "suzanne_phong_turned",
        "suzanne_phong",
        &[("xangle", "30"), ("yangle", "45"), ("lightx", "-2")],
    ),
    (
        "legacy_default_torus",
        "legacy",
        &[("object", "torus"), ("xangle", "30"), ("yangle", "45")],
    ),
];

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
