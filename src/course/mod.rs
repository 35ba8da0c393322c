//! The exercises, one folder per lecture (`seed000` … `seed004`, as `../seeds`, `tests/` and
//! `assets/course/` name them), what they share ([`common`]), and the one list of labs,
//! [`ALL`], that examples, the bench, the tests and `find` read. A lab's module, shaders
//! (`shaders_glsl/NAME.*`) and example (`examples/NAME.rs`) share its name.

/// Declares `info(name, title, label, keys)`: the [`LabInfo`](crate::lab::LabInfo) of a lab of
/// one lecture (its lecture name and window size).
macro_rules! lecture {
    ($lecture:literal, $size:expr) => {
        /// A lab of this lecture: its name, the original's window title, the effect, its keys.
        pub const fn info(
            name: &'static str,
            title: &'static str,
            label: &'static str,
            keys: crate::lab::Keys,
        ) -> crate::lab::LabInfo {
            crate::lab::LabInfo::new(name, title, label, $lecture, $size, keys)
        }
    };
}

/// A lab's name is its module's: the last segment of `path` (`module_path!()` in the lab's
/// file, as `lab_name!()` writes it), so that the registration alone names a lab.
pub const fn module_name(path: &'static str) -> &'static str {
    let bytes = path.as_bytes();
    let mut start = bytes.len();
    while start > 0 && bytes[start - 1] != b':' {
        start -= 1;
    }
    match std::str::from_utf8(bytes.split_at(start).1) {
        Ok(name) => name,
        Err(_) => panic!("a module path is UTF-8"),
    }
}

/// The name of the lab whose file this is written in (its module's name).
macro_rules! lab_name {
    () => {
        $crate::course::module_name(module_path!())
    };
}

pub mod common;
pub mod legacy;
pub mod seed000;
pub mod seed001;
pub mod seed002;
pub mod seed003;
pub mod seed004;
pub mod states;

use crate::lab::LabEntry;

/// Registers every lab once: a `pub static NAME: &LabEntry` per lab, and [`ALL`] in this order.
/// A lab is its module's `RECIPE` (driven by [`crate::lab::Runner`]), or its own `ENTRY` where
/// it implements [`crate::lab::Lab`] by hand (`by hand`).
macro_rules! register {
    ($($path:path => $name:ident $($by:ident $hand:ident)?,)*) => {
        $(
            #[doc = concat!("The `", stringify!($path), "` lab.")]
            pub static $name: &LabEntry = register!(@entry $($hand)? $path);
        )*
        /// Every lab, in lecture order.
        pub static ALL: &[&LabEntry] = &[$($name),*];
    };
    (@entry hand $path:path) => {{
        use $path as module;
        &module::ENTRY
    }};
    (@entry $path:path) => {{
        use $path as module;
        &crate::entry!(module::RECIPE)
    }};
}

register! {
    seed000::position_rgb => POSITION_RGB,
    seed000::normal_rgb => NORMAL_RGB,
    seed000::phong => PHONG by hand,
    seed000::noise => NOISE,
    seed000::displacement => DISPLACEMENT,
    seed001::height => HEIGHT,
    seed001::uniform_arrays => UNIFORM_ARRAYS,
    seed001::wave => WAVE,
    seed001::morph => MORPH,
    seed001::particles => PARTICLES,
    seed001::toon => TOON,
    seed001::phong_vertex => PHONG_VERTEX,
    seed001::phong_fragment => PHONG_FRAGMENT,
    seed001::texture => TEXTURE,
    seed001::envmap => ENVMAP,
    seed001::bump => BUMP,
    seed001::normmap => NORMMAP,
    seed002::twist => TWIST,
    seed002::double_vision => DOUBLE_VISION,
    seed002::normal_world => NORMAL_WORLD,
    seed002::phong_dir => PHONG_DIR,
    seed003::specular_strip => SPECULAR_STRIP,
    seed004::suzanne_normal_color => SUZANNE_NORMAL_COLOR,
    seed004::suzanne_normal_matrix => SUZANNE_NORMAL_MATRIX,
    seed004::suzanne_smooth => SUZANNE_SMOOTH,
    seed004::suzanne_texture => SUZANNE_TEXTURE,
    seed004::suzanne_texture_color => SUZANNE_TEXTURE_COLOR,
    seed004::texparams => TEXPARAMS,
    seed004::suzanne_flat => SUZANNE_FLAT,
    seed004::suzanne_gouraud => SUZANNE_GOURAUD,
    seed004::suzanne_phong => SUZANNE_PHONG,
    legacy => LEGACY by hand,
}

/// The lab called `name`.
pub fn find(name: &str) -> Option<&'static LabEntry> {
    ALL.iter().copied().find(|e| e.info.name == name)
}

pub use seed000::NOISE_PERIOD;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_labs_taking_user_files_are_the_ones_built_on_them() {
        let with = |which: fn(crate::lab::FilesTaken) -> bool| -> Vec<&str> {
            ALL.iter()
                .filter(|e| which(e.info.files))
                .map(|e| e.info.name)
                .collect()
        };
        // The model (`seed004::geometry::Model`) is built by `seed004::suzanne`'s three families:
        // `draw` (normals as colour), `sample` (textured) and `shade` (lit).
        assert_eq!(
            with(|t| t.model),
            [
                "suzanne_normal_color",
                "suzanne_normal_matrix",
                "suzanne_smooth",
                "suzanne_texture",
                "suzanne_texture_color",
                "suzanne_flat",
                "suzanne_gouraud",
                "suzanne_phong"
            ]
        );
        // `cx.files.texture` is read by `seed004::suzanne::sample`, texparams and legacy.
        assert_eq!(
            with(|t| t.texture),
            ["suzanne_texture", "suzanne_texture_color", "texparams", "legacy"]
        );
        assert_eq!(with(|t| t.named_textures), ["legacy"]);
    }
}
