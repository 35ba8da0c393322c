//! Keys as data. A [`KeyRow`] steps, picks, toggles or cycles one parameter; the same row
//! handles the key ([`Keys::apply`]) and writes its `--help` line and README row
//! ([`Keys::help`]), so a lab's keys are declared once.

use super::{Input, Special};
use crate::params::Params;

/// A key as GLUT reported it: a character or a special key.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Key {
    /// `glutKeyboardFunc`'s character.
    C(char),
    /// `glutSpecialFunc`'s key.
    S(Special),
}

/// ←
pub const LEFT: Key = Key::S(Special::Left);
/// →
pub const RIGHT: Key = Key::S(Special::Right);
/// ↑
pub const UP: Key = Key::S(Special::Up);
/// ↓
pub const DOWN: Key = Key::S(Special::Down);
/// Page Up
pub const PAGE_UP: Key = Key::S(Special::PageUp);
/// Page Down
pub const PAGE_DOWN: Key = Key::S(Special::PageDown);

impl Key {
    fn matches(self, input: Input) -> bool {
        match (self, input) {
            (Key::C(a), Input::Key(b)) => a == b,
            (Key::S(a), Input::Special(b)) => a == b,
            _ => false,
        }
    }

    fn name(self) -> String {
        match self {
            Key::C(c) => c.to_string(),
            Key::S(s) => format!("{s:?}"),
        }
    }
}

/// What a row does to its parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Act {
    /// The first key subtracts `step`, the second adds it: to component `component` (every
    /// component for `None`), clamped to `within` (the declared range for `None`; the
    /// originals' keys often clamp tighter than `--set` accepts).
    Step {
        /// The amount.
        step: f64,
        /// The component stepped.
        component: Option<usize>,
        /// The bounds the keys keep to.
        within: Option<(f64, f64)>,
    },
    /// Key `i` sets the parameter to `i` (a choice's `i`-th name).
    Pick,
    /// The key flips a flag.
    Toggle,
    /// The key moves a choice or whole number to its next value.
    Cycle,
}

/// One row of a lab's key table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KeyRow {
    /// The keys, in the order [`Act`] gives them meaning.
    pub keys: &'static [Key],
    /// The parameter they change.
    pub param: &'static str,
    /// How.
    pub act: Act,
}

impl KeyRow {
    /// `keys[0]` subtracts `step` from every component of `param`, `keys[1]` adds it.
    pub const fn step(keys: &'static [Key], param: &'static str, step: f64) -> KeyRow {
        Self::stepping(keys, param, step, None, None)
    }

    /// As [`KeyRow::step`] on component `c` only, clamped to `[lo, hi]`.
    pub const fn channel(keys: &'static [Key], param: &'static str, c: usize, step: f64, lo: f64, hi: f64) -> KeyRow {
        Self::stepping(keys, param, step, Some(c), Some((lo, hi)))
    }

    /// As [`KeyRow::step`], clamped to `[lo, hi]` instead of the declared range.
    pub const fn clamped(keys: &'static [Key], param: &'static str, step: f64, lo: f64, hi: f64) -> KeyRow {
        Self::stepping(keys, param, step, None, Some((lo, hi)))
    }

    const fn stepping(
        keys: &'static [Key],
        param: &'static str,
        step: f64,
        component: Option<usize>,
        within: Option<(f64, f64)>,
    ) -> KeyRow {
        KeyRow {
            keys,
            param,
            act: Act::Step {
                step,
                component,
                within,
            },
        }
    }

    /// Key `i` of `keys` sets `param` to `i`.
    pub const fn pick(keys: &'static [Key], param: &'static str) -> KeyRow {
        KeyRow {
            keys,
            param,
            act: Act::Pick,
        }
    }

    /// The key flips `param`.
    pub const fn toggle(key: &'static [Key], param: &'static str) -> KeyRow {
        KeyRow {
            keys: key,
            param,
            act: Act::Toggle,
        }
    }

    /// The key moves `param` to its next value.
    pub const fn cycle(key: &'static [Key], param: &'static str) -> KeyRow {
        KeyRow {
            keys: key,
            param,
            act: Act::Cycle,
        }
    }

    /// Applies the row to `p` if `input` is one of its keys; returns whether it was.
    fn apply(&self, p: &mut Params, input: Input) -> bool {
        let Some(i) = self.keys.iter().position(|k| k.matches(input)) else {
            return false;
        };
        match self.act {
            Act::Step {
                step,
                component,
                within,
            } => {
                let delta = if i == 0 { -step } else { step };
                let c = component.unwrap_or(usize::MAX);
                match within {
                    Some((lo, hi)) => p.step_clamped(self.param, c, delta, lo, hi),
                    None => p.step_component(self.param, c, delta),
                }
            }
            Act::Pick => p.set_unchecked(self.param, &[i as f64]),
            Act::Toggle => p.toggle(self.param),
            Act::Cycle => p.cycle(self.param),
        }
        true
    }

    /// The row's help line: `h/H: h -/+0.02`.
    pub fn help(&self) -> String {
        let keys: Vec<String> = self.keys.iter().map(|k| k.name()).collect();
        let what = match self.act {
            Act::Step {
                step,
                component,
                within,
            } => {
                let param = match component {
                    Some(c) => format!("{}[{c}]", self.param),
                    None => self.param.to_owned(),
                };
                match within {
                    Some((lo, hi)) => format!("{param} -/+{step} within [{lo}, {hi}]"),
                    None => format!("{param} -/+{step}"),
                }
            }
            Act::Pick => format!("{} 0..{}", self.param, self.keys.len() - 1),
            Act::Toggle => format!("toggle {}", self.param),
            Act::Cycle => format!("next {}", self.param),
        };
        format!("{}: {what}", keys.join("/"))
    }
}

/// A lab's keys and mouse: rows that change parameters, and a sentence for what rows do not
/// say (the mouse, a geometry's object keys, a hand-written lab's keys).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Keys {
    /// The rows.
    pub rows: &'static [KeyRow],
    /// The rest, as text.
    pub more: &'static str,
}

impl Keys {
    /// Keys described by text alone (a hand-written lab).
    pub const fn text(more: &'static str) -> Keys {
        Keys { rows: &[], more }
    }

    /// Rows, then `more`.
    pub const fn rows(rows: &'static [KeyRow], more: &'static str) -> Keys {
        Keys { rows, more }
    }

    /// Applies the first row that takes `input`; returns whether one did.
    pub fn apply(&self, p: &mut Params, input: Input) -> bool {
        self.rows.iter().any(|r| r.apply(p, input))
    }

    /// The `--help` text: one row per line, then `more`.
    pub fn help(&self) -> String {
        let mut lines: Vec<String> = self.rows.iter().map(KeyRow::help).collect();
        if !self.more.is_empty() {
            lines.push(self.more.to_owned());
        }
        lines.join(";\n")
    }

    /// Every parameter a row names (checked against the lab's parameters by a test).
    pub fn params(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.rows.iter().map(|r| r.param)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::ParamSpec;

    const SPECS: &[ParamSpec] = &[
        ParamSpec::real("h", &[0.1], -1.0, 1.0, "height"),
        ParamSpec::real("shade", &[0.5, 0.5, 0.5], -9.0, 9.0, "colour"),
        ParamSpec::choice("shading", &[0.0], &["flat", "gouraud", "phong"], "model"),
        ParamSpec::flag("fixpos", &[0.0], "flag"),
    ];
    const ROWS: &[KeyRow] = &[
        KeyRow::step(&[Key::C('h'), Key::C('H')], "h", 0.5),
        KeyRow::channel(&[Key::C('r'), Key::C('R')], "shade", 0, 0.25, 0.0, 1.0),
        KeyRow::pick(&[Key::C('1'), Key::C('2'), Key::C('3')], "shading"),
        KeyRow::toggle(&[Key::C('p')], "fixpos"),
        KeyRow::cycle(&[Key::C('m')], "shading"),
        KeyRow::step(&[LEFT, RIGHT], "h", 0.25),
    ];
    const KEYS: Keys = Keys::rows(ROWS, "left drag rotates");

    #[test]
    fn rows_step_clamp_pick_toggle_and_cycle() {
        let mut p = Params::new(SPECS);
        assert!(KEYS.apply(&mut p, Input::Key('H')));
        assert_eq!(p.f("h"), 0.6);
        assert!(KEYS.apply(&mut p, Input::Key('H')));
        assert_eq!(p.f("h"), 1.0, "clamped to the declared range");
        KEYS.apply(&mut p, Input::Special(Special::Left));
        assert_eq!(p.f("h"), 0.75);
        for _ in 0..3 {
            KEYS.apply(&mut p, Input::Key('R'));
        }
        assert_eq!(p.v3("shade"), [1.0, 0.5, 0.5], "one channel, within the row's bounds");
        KEYS.apply(&mut p, Input::Key('3'));
        assert_eq!(p.text("shading"), "phong");
        KEYS.apply(&mut p, Input::Key('m'));
        assert_eq!(p.text("shading"), "flat", "cycling wraps");
        KEYS.apply(&mut p, Input::Key('p'));
        assert!(p.on("fixpos"));
        assert!(!KEYS.apply(&mut p, Input::Key('q')), "a key no row has");
        assert!(!KEYS.apply(&mut p, Input::Special(Special::Up)));
    }

    #[test]
    fn rows_write_the_help() {
        assert_eq!(
            KEYS.help(),
            "h/H: h -/+0.5;\nr/R: shade[0] -/+0.25 within [0, 1];\n1/2/3: shading 0..2;\np: toggle fixpos;\nm: next shading;\nLeft/Right: h -/+0.25;\nleft drag rotates"
        );
        assert_eq!(
            KEYS.params().collect::<Vec<_>>(),
            ["h", "shade", "shading", "fixpos", "shading", "h"]
        );
    }
}
