//! The states of record of every lab: the reference states each original program's picture
//! was rendered at ([`REFERENCE`], checked by `tests/reference.rs`), and the states the port's
//! own pictures are kept at ([`SNAPSHOTS`], `tests/snapshots.rs`). `shaderlab check` compares a
//! copy of a lab's shaders with the course's at these states ([`of`]) and more.

/// One row: the lab, its state (`--set` assignments on its defaults), the original's picture
/// (under `tests/reference/`) and the PSNR the port must reach.
pub struct Reference {
    /// The lab.
    pub lab: &'static str,
    /// Its state.
    pub state: &'static [(&'static str, &'static str)],
    /// The original's picture, under `tests/reference/`.
    pub reference: &'static str,
    /// The PSNR the port must reach against it.
    pub min_db: f64,
}

const fn row(
    lab: &'static str,
    state: &'static [(&'static str, &'static str)],
    reference: &'static str,
    min_db: f64,
) -> Reference {
    Reference {
        lab,
        state,
        reference,
        min_db,
    }
}

/// Seed 000: each exercise on each object at rotation 0 and time 0, against `labref` (C and
/// GLUT); 35 dB, as seed 000's noise exercises differ in the last bit of a few pixels.
pub const SEED000: f64 = 35.0;
/// Seeds 001–004: each effect's first state against its original program; 40 dB.
pub const SEEDS: f64 = 40.0;

/// Seed 001's bump and normmap seen obliquely (the per-vertex light vectors far apart).
const OBLIQUE: &[(&str, &str)] = &[("xangle", "-20"), ("yangle", "60"), ("blx", "1"), ("bly", "1")];

/// Every lecture's reference states.
pub static REFERENCE: &[Reference] = &[
    row("position_rgb", &[("object", "cube")], "lab1_cube_x0_y0_t0.png", SEED000),
    row(
        "position_rgb",
        &[("object", "sphere")],
        "lab1_sphere_x0_y0_t0.png",
        SEED000,
    ),
    row(
        "position_rgb",
        &[("object", "torus")],
        "lab1_torus_x0_y0_t0.png",
        SEED000,
    ),
    row(
        "position_rgb",
        &[("object", "teapot")],
        "lab1_teapot_x0_y0_t0.png",
        SEED000,
    ),
    row("normal_rgb", &[("object", "cube")], "lab2_cube_x0_y0_t0.png", SEED000),
    row(
        "normal_rgb",
        &[("object", "sphere")],
        "lab2_sphere_x0_y0_t0.png",
        SEED000,
    ),
    row("normal_rgb", &[("object", "torus")], "lab2_torus_x0_y0_t0.png", SEED000),
    row(
        "normal_rgb",
        &[("object", "teapot")],
        "lab2_teapot_x0_y0_t0.png",
        SEED000,
    ),
    row("phong", &[("object", "cube")], "lab3_cube_x0_y0_t0.png", SEED000),
    row("phong", &[("object", "sphere")], "lab3_sphere_x0_y0_t0.png", SEED000),
    row("phong", &[("object", "torus")], "lab3_torus_x0_y0_t0.png", SEED000),
    row("phong", &[("object", "teapot")], "lab3_teapot_x0_y0_t0.png", SEED000),
    row("noise", &[("object", "cube")], "lab4_cube_x0_y0_t0.png", SEED000),
    row("noise", &[("object", "sphere")], "lab4_sphere_x0_y0_t0.png", SEED000),
    row("noise", &[("object", "torus")], "lab4_torus_x0_y0_t0.png", SEED000),
    row("noise", &[("object", "teapot")], "lab4_teapot_x0_y0_t0.png", SEED000),
    row("displacement", &[("object", "cube")], "lab5_cube_x0_y0_t0.png", SEED000),
    row(
        "displacement",
        &[("object", "sphere")],
        "lab5_sphere_x0_y0_t0.png",
        SEED000,
    ),
    row(
        "displacement",
        &[("object", "torus")],
        "lab5_torus_x0_y0_t0.png",
        SEED000,
    ),
    row(
        "displacement",
        &[("object", "teapot")],
        "lab5_teapot_x0_y0_t0.png",
        SEED000,
    ),
    row("height", &[("mode", "0")], "seeds/001_height_immediate.png", SEEDS),
    row("uniform_arrays", &[], "seeds/001_uniform_arrays_default.png", SEEDS),
    row("wave", &[("time", "0")], "seeds/001_wave_t0.png", SEEDS),
    row("morph", &[("time", "4.712389")], "seeds/001_morph_circle.png", SEEDS),
    row("particles", &[("time", "0.25")], "seeds/001_particles_t0.25.png", SEEDS),
    row("toon", &[], "seeds/001_toon_default.png", SEEDS),
    row("phong_vertex", &[], "seeds/001_phong_vertex_default.png", SEEDS),
    row("phong_fragment", &[], "seeds/001_phong_fragment_default.png", SEEDS),
    row("texture", &[], "seeds/001_texture_default.png", SEEDS),
    row("envmap", &[("object", "1")], "seeds/001_envmap_sphere.png", SEEDS),
    row("bump", &[], "seeds/001_bump_default.png", SEEDS),
    row("bump", OBLIQUE, "seeds/001_bump_oblique.png", SEEDS),
    row("normmap", &[], "seeds/001_normmap_default.png", SEEDS),
    row("normmap", OBLIQUE, "seeds/001_normmap_oblique.png", SEEDS),
    row("twist", &[], "seeds/002_twist_default.png", SEEDS),
    row("double_vision", &[], "seeds/002_double_vision_default.png", SEEDS),
    row("normal_world", &[], "seeds/002_normal_world_default.png", SEEDS),
    row("phong_dir", &[], "seeds/002_phong_dir_default.png", SEEDS),
    row("specular_strip", &[], "seeds/003_specular_strip_default.png", SEEDS),
    row("suzanne_normal_color", &[], "seeds/004_normal_color_default.png", SEEDS),
    row(
        "suzanne_normal_matrix",
        &[],
        "seeds/004_normal_matrix_default.png",
        SEEDS,
    ),
    row("suzanne_smooth", &[], "seeds/004_smooth_default.png", SEEDS),
    row(
        "suzanne_texture",
        &[("tex", "0")],
        "seeds/004_texture_checker.png",
        SEEDS,
    ),
    row(
        "suzanne_texture_color",
        &[("tex", "0")],
        "seeds/004_texture_color_checker.png",
        SEEDS,
    ),
    row("texparams", &[], "seeds/004_texparams_default.png", SEEDS),
    row("suzanne_flat", &[], "seeds/004_flat_default.png", SEEDS),
    row("suzanne_gouraud", &[], "seeds/004_gouraud_default.png", SEEDS),
    row("suzanne_phong", &[], "seeds/004_phong_default.png", SEEDS),
];

/// One row: the snapshot's name, the lab, its state (`--set` assignments on its defaults).
pub type Snapshot = (&'static str, &'static str, &'static [(&'static str, &'static str)]);

const TURNED: &[(&str, &str)] = &[("xangle", "30"), ("yangle", "45")];

/// The states the port's own pictures are kept at.
pub static SNAPSHOTS: &[Snapshot] = &[
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

/// The states of record of lab `name` (its reference and snapshot states, each once, in that
/// order; its defaults first where no row is at them).
pub fn of(name: &str) -> Vec<&'static [(&'static str, &'static str)]> {
    let mut out: Vec<&'static [(&'static str, &'static str)]> = vec![&[]];
    let rows = (REFERENCE.iter().filter(|r| r.lab == name).map(|r| r.state))
        .chain(SNAPSHOTS.iter().filter(|r| r.1 == name).map(|r| r.2));
    for state in rows {
        if !out.contains(&state) {
            out.push(state);
        }
    }
    out
}
