//! The names the translator writes where the user's own cannot stand in GLSL 450, and the way
//! back to the user's: one rule for the translator ([`super::translate()`]) and for the
//! debugger, which shows a translated shader's steps under the names the user wrote
//! ([`user_name`]).
//!
//! Every name the translator makes starts with [`PREFIX`]:
//! - a name GLSL 450 reserves (`texture`) is `sl_texture` ([`reserved`]), and the user's
//!   `main` is [`MAIN`];
//! - a GL built-in input or output held in another form is `sl_` and the rest of GL's name
//!   (`gl_Vertex` → `sl_Vertex`, the varying of `gl_TexCoord[0]` `sl_TexCoord0`: [`builtin`]);
//! - a uniform held in another form is the block's member `sl_u_NAME` ([`encoded`]).

/// The start of every name the translator makes.
pub const PREFIX: &str = "sl_";

/// The start of a uniform block's member that holds a uniform in another form.
const ENCODED: &str = "sl_u_";

/// The user's `main` in the translation (the translator's own `main` calls it).
pub const MAIN: &str = "sl_main";

/// A name GLSL 450 reserves, as the translation spells it: `texture` → `sl_texture`.
pub fn reserved(name: &str) -> String {
    format!("{PREFIX}{name}")
}

/// GL's built-in `gl_NAME` (an input or output the translation holds in another form) as the
/// translation spells it: `sl_NAME`.
pub fn builtin(gl_name: &str) -> String {
    format!("{PREFIX}{}", gl_name.strip_prefix("gl_").unwrap_or(gl_name))
}

/// The uniform block's member that holds the uniform `glsl` (its name in the translation) in
/// another form: `sl_u_NAME`.
pub fn encoded(glsl: &str) -> String {
    format!("{ENCODED}{glsl}")
}

/// A name of the translation as the user wrote it: `sl_u_NAME` is `NAME`, `sl_` and a capital
/// (a built-in) is `gl_` and the rest, `sl_` and anything else (a reserved name, `sl_main`)
/// is the rest; any other name is itself.
pub fn user_name(name: &str) -> String {
    if let Some(rest) = name.strip_prefix(ENCODED) {
        return rest.to_owned();
    }
    match name.strip_prefix(PREFIX) {
        Some(rest) if rest.starts_with(|c: char| c.is_ascii_uppercase()) => format!("gl_{rest}"),
        Some(rest) => rest.to_owned(),
        None => name.to_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn user_name_undoes_each_renaming() {
        for name in ["texture", "textureLod", "main", "x"] {
            assert_eq!(user_name(&reserved(name)), name);
        }
        assert_eq!(user_name(MAIN), "main");
        for gl in ["gl_Vertex", "gl_MultiTexCoord0", "gl_PointSize", "gl_FragData0"] {
            assert_eq!(user_name(&builtin(gl)), gl);
        }
        for name in ["w", "bv", "m2"] {
            assert_eq!(user_name(&encoded(name)), name);
        }
        // Names the user wrote stay as they are.
        for name in ["color", "gl_Position", "gl_Normal", "light_dir"] {
            assert_eq!(user_name(name), name);
        }
    }
}
