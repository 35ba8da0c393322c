//! Parameters by name: the one mechanism behind `--set NAME=VALUE`, `--help`, keys, the window
//! title and tests, for every lab.
//!
//! A lab (or each part it is composed of) declares its parameters as [`ParamSpec`]s with a
//! default, a range and a kind; [`Params`] holds the current values. Values are parsed and kept
//! in f64 so that a clock can run for hours without losing precision before a lab narrows them
//! to the f32 its uniforms take, so that a whole number is exact over the whole i32 range
//! (`uniform int k` = 16777217), and so that a documented bound (`near` 0.0001, `Ka` 1e30) is
//! accepted: the value is compared with the range in the type both are stored in.

use std::path::PathBuf;

use crate::error::{Error, Result};

/// What kind of values a parameter takes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// Any finite number within the range (one or more components).
    Real,
    /// A whole number within the range.
    Int,
    /// 0 or 1.
    Bool,
    /// One of several named values, stored as its index (`--set object=torus` or `object=2`).
    Choice(&'static [&'static str]),
}

/// One named parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamSpec {
    /// The name used by `--set`, tests and the title (SPEC's state keys).
    pub name: &'static str,
    /// Default value, one entry per component.
    pub default: &'static [f64],
    /// Smallest value of each component.
    pub min: f64,
    /// Largest value of each component.
    pub max: f64,
    /// Kind of value.
    pub kind: Kind,
    /// One line for `--help`.
    pub help: &'static str,
    /// One more value accepted outside `[min, max]` (GL's `spotCutoff`: 0..90 or 180).
    pub or: Option<f64>,
    /// The value the word `auto` stands for (`--set grid=auto`), shown as `auto`.
    pub auto: Option<f64>,
}

impl ParamSpec {
    /// A real number in `[min, max]`.
    pub const fn real(name: &'static str, default: &'static [f64], min: f64, max: f64, help: &'static str) -> Self {
        ParamSpec {
            name,
            default,
            min,
            max,
            kind: Kind::Real,
            help,
            or: None,
            auto: None,
        }
    }

    /// The same parameter, also taking exactly `value` outside its range.
    pub const fn or_exactly(mut self, value: f64) -> Self {
        self.or = Some(value);
        self
    }

    /// The same parameter, with the word `auto` standing for `value` (a value in its range
    /// that the lab reads as "choose for me"), in `--set` and in what is shown.
    pub const fn with_auto(mut self, value: f64) -> Self {
        self.auto = Some(value);
        self
    }

    /// A whole number in `[min, max]`.
    pub const fn int(name: &'static str, default: &'static [f64], min: f64, max: f64, help: &'static str) -> Self {
        ParamSpec {
            name,
            default,
            min,
            max,
            kind: Kind::Int,
            help,
            or: None,
            auto: None,
        }
    }

    /// A switch, 0 or 1.
    pub const fn flag(name: &'static str, default: &'static [f64], help: &'static str) -> Self {
        ParamSpec {
            name,
            default,
            min: 0.0,
            max: 1.0,
            kind: Kind::Bool,
            help,
            or: None,
            auto: None,
        }
    }

    /// One of `names` (index 0, 1, ...).
    pub const fn choice(
        name: &'static str,
        default: &'static [f64],
        names: &'static [&'static str],
        help: &'static str,
    ) -> Self {
        ParamSpec {
            name,
            default,
            min: 0.0,
            max: (names.len() - 1) as f64,
            kind: Kind::Choice(names),
            help,
            or: None,
            auto: None,
        }
    }

    /// The default as text, e.g. `0.2,0.2,0.2` or `teapot`.
    pub fn default_text(&self) -> String {
        format_value(self, self.default)
    }
}

fn format_value(spec: &ParamSpec, values: &[f64]) -> String {
    if spec.auto.is_some() && values.len() == 1 && spec.auto == values.first().copied() {
        return "auto".into();
    }
    match spec.kind {
        Kind::Choice(names) => values
            .first()
            .and_then(|v| names.get(*v as usize))
            .map(|s| s.to_string())
            .unwrap_or_default(),
        // Reals as the f32 the shaders get; whole numbers exactly (16777217 is no f32).
        Kind::Real => values
            .iter()
            .map(|v| format!("{}", *v as f32))
            .collect::<Vec<_>>()
            .join(","),
        _ => values.iter().map(|v| format!("{v}")).collect::<Vec<_>>().join(","),
    }
}

/// A bound as `--help` and the range errors write it: whole numbers in full (2147483647), huge
/// ones short (1e30), the rest in the shortest form that reads back as the same f64 (0.0001),
/// so that the text is the bound that is checked.
pub fn bound_text(v: f64) -> String {
    let short = |v: f64| {
        // A bound that is an f32 (f32::MAX) in its f32 form: 3.4028235e38, not 3.4028234663852886e38.
        if f64::from(v as f32) == v {
            format!("{:e}", v as f32)
        } else {
            format!("{v:e}")
        }
    };
    if v.abs() >= 1e16 || (v != 0.0 && v.abs() < 1e-6) {
        short(v)
    } else {
        format!("{v}")
    }
}

/// A value in a message: as typed for everyday sizes, in shortest exponent form when huge or
/// tiny (`1e308`, not a 309-digit number).
pub fn value_text(v: f64) -> String {
    if v.abs() >= 1e16 || (v != 0.0 && v.abs() < 1e-6) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// The range of a spec as text, `0..90 or 180` where one more value is taken.
fn range_text(spec: &ParamSpec) -> String {
    let or = spec.or.map(|v| format!(" or {}", bound_text(v))).unwrap_or_default();
    format!("{}..{}{or}", bound_text(spec.min), bound_text(spec.max))
}

/// Files a lab takes on the command line (positional `FILES...`), and the parameters those
/// files declare (e.g. the uniforms of a user's shaders). The shell reads them, and checks
/// `--set` against what they declare, before a GPU is opened; a lab without `FileArgs` takes
/// no positional files.
#[derive(Clone, Copy, Debug)]
pub struct FileArgs {
    /// Their names in the usage line, e.g. `["VERT", "FRAG"]`: all of them, or none (the lab
    /// then uses its built-in data).
    pub names: &'static [&'static str],
    /// Reads the files and adds the parameters they declare; with no paths, adds those of the
    /// lab's built-in data.
    pub declare: fn(&[PathBuf], &mut Params) -> Result<()>,
}

/// The current values of a set of parameters.
#[derive(Clone, Debug, Default)]
pub struct Params {
    specs: Vec<ParamSpec>,
    values: Vec<Vec<f64>>,
    /// Where each name is in `specs` (a user's shader may declare thousands of uniforms).
    by_name: std::collections::HashMap<&'static str, usize>,
    files: Option<FileArgs>,
    /// Rules between parameters (`near` < `far`), run by [`Params::check`] once all values are
    /// set: one `--set` at a time cannot be judged (`--set near=200 --set far=1000`).
    checks: Vec<fn(&Params) -> Result<()>>,
}

impl Params {
    /// Parameters at their defaults.
    pub fn new(specs: &[ParamSpec]) -> Self {
        let mut params = Params::default();
        params.extend(specs);
        params
    }

    /// Adds more parameters (a part of a lab adding its own). A name declared twice keeps the
    /// first declaration: parts compose, they do not override each other.
    pub fn extend(&mut self, specs: &[ParamSpec]) {
        for spec in specs {
            if let std::collections::hash_map::Entry::Vacant(slot) = self.by_name.entry(spec.name) {
                slot.insert(self.specs.len());
                self.specs.push(*spec);
                self.values.push(spec.default.to_vec());
            }
        }
    }

    /// Declares the files the lab takes on the command line ([`FileArgs`]).
    pub fn with_files(mut self, files: FileArgs) -> Self {
        self.files = Some(files);
        self
    }

    /// Adds a rule between parameters, checked by [`Params::check`].
    pub fn with_check(mut self, check: fn(&Params) -> Result<()>) -> Self {
        self.checks.push(check);
        self
    }

    /// Runs the rules between parameters (after the command line is applied).
    pub fn check(&self) -> Result<()> {
        self.checks.iter().try_for_each(|c| c(self))
    }

    /// The files the lab takes on the command line, if any.
    pub fn file_args(&self) -> Option<FileArgs> {
        self.files
    }

    /// Adds the parameters declared by the files `paths` (as many as [`FileArgs::names`], or
    /// none for the lab's built-in data). Files given to a lab that takes none are a usage
    /// error; no files for such a lab add nothing.
    pub fn declare_files(&mut self, paths: &[PathBuf]) -> Result<()> {
        let Some(files) = self.files else {
            return match paths.first() {
                Some(first) => Err(Error::Param(format!(
                    "unexpected argument `{}`: this lab takes no files",
                    first.display()
                ))),
                None => Ok(()),
            };
        };
        if !paths.is_empty() && paths.len() != files.names.len() {
            return Err(Error::Param(format!(
                "expected {} file(s) {}, got {}",
                files.names.len(),
                files.names.join(" "),
                paths.len()
            )));
        }
        (files.declare)(paths, self)
    }

    fn index(&self, name: &str) -> Option<usize> {
        self.by_name.get(name).copied()
    }

    /// Every declared parameter, in declaration order.
    pub fn specs(&self) -> &[ParamSpec] {
        &self.specs
    }

    /// Whether `name` is a parameter.
    pub fn has(&self, name: &str) -> bool {
        self.index(name).is_some()
    }

    /// The values of `name`.
    pub fn get(&self, name: &str) -> Option<&[f64]> {
        self.index(name).map(|i| self.values[i].as_slice())
    }

    /// The first component of `name` as f64 (0 for an unknown name, which a test catches).
    pub fn f64(&self, name: &str) -> f64 {
        debug_assert!(self.has(name), "unknown parameter {name}");
        self.get(name).and_then(|v| v.first().copied()).unwrap_or(0.0)
    }

    /// The first component of `name` as f32.
    pub fn f(&self, name: &str) -> f32 {
        self.f64(name) as f32
    }

    /// The value of a whole-number or choice parameter.
    pub fn index_of(&self, name: &str) -> usize {
        self.f64(name).max(0.0) as usize
    }

    /// Whether a switch is on.
    pub fn on(&self, name: &str) -> bool {
        self.f64(name) != 0.0
    }

    /// Three components as f32.
    pub fn v3(&self, name: &str) -> [f32; 3] {
        let v = self.get(name).unwrap_or(&[]);
        std::array::from_fn(|i| v.get(i).copied().unwrap_or(0.0) as f32)
    }

    /// Four components as f32.
    pub fn v4(&self, name: &str) -> [f32; 4] {
        let v = self.get(name).unwrap_or(&[]);
        std::array::from_fn(|i| v.get(i).copied().unwrap_or(0.0) as f32)
    }

    /// Sets `name` from numbers, checking count, finiteness, kind and range.
    pub fn set(&mut self, name: &str, values: &[f64]) -> Result<()> {
        let i = self.index(name).ok_or_else(|| self.unknown(name))?;
        let spec = self.specs[i];
        if values.len() != spec.default.len() {
            return Err(Error::Param(format!(
                "parameter `{name}` takes {} number(s), got {}",
                spec.default.len(),
                values.len()
            )));
        }
        for &v in values {
            if !v.is_finite() {
                return Err(Error::Param(format!("parameter `{name}`: {v} is not a finite number")));
            }
            if spec.kind == Kind::Bool && v != 0.0 && v != 1.0 {
                let v = value_text(v);
                return Err(Error::Param(format!("parameter `{name}` takes 0 or 1, not {v}")));
            }
            let whole = !matches!(spec.kind, Kind::Real);
            if whole && v.fract() != 0.0 {
                let v = value_text(v);
                return Err(Error::Param(format!(
                    "parameter `{name}` takes a whole number{}, not {v}",
                    self.choices_hint(&spec)
                )));
            }
            // In f64, the type the value is kept in; a bound as printed (`3.4028235e38` for
            // f32::MAX, a little above it in f64) is itself taken, and nothing else beyond.
            let printed = |b: f64| bound_text(b).parse::<f64>().ok() == Some(v);
            let inside = (spec.min..=spec.max).contains(&v) || printed(spec.min) || printed(spec.max);
            if !inside && spec.or != Some(v) {
                let v = value_text(v);
                return Err(Error::Param(format!(
                    "parameter `{name}`: {v} is outside {}{}",
                    range_text(&spec),
                    self.choices_hint(&spec)
                )));
            }
        }
        self.values[i] = values.to_vec();
        Ok(())
    }

    fn choices_hint(&self, spec: &ParamSpec) -> String {
        match spec.kind {
            Kind::Choice(names) => format!(
                " ({})",
                names
                    .iter()
                    .enumerate()
                    .map(|(i, n)| format!("{i} = {n}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            _ => String::new(),
        }
    }

    /// Sets `name` from text: comma-separated numbers, or a choice's name.
    pub fn set_str(&mut self, name: &str, text: &str) -> Result<()> {
        let i = self.index(name).ok_or_else(|| self.unknown(name))?;
        if let (Some(auto), "auto") = (self.specs[i].auto, text.trim()) {
            return self.set(name, &[auto]);
        }
        if let Kind::Choice(names) = self.specs[i].kind {
            if let Some(k) = names.iter().position(|n| *n == text.trim()) {
                return self.set(name, &[k as f64]);
            }
        }
        let values = parse_numbers(text).map_err(|e| match self.specs[i].kind {
            Kind::Choice(names) => {
                Error::Param(format!("unknown {name} `{}`; valid: {}", text.trim(), names.join(", ")))
            }
            _ => Error::Param(format!("parameter `{name}`: {e}")),
        })?;
        self.set(name, &values)
    }

    /// Adds `delta` to every component of `name`, clamped to its range (the keys of the
    /// originals step values; their bounds checks let a value step just past a bound, the port
    /// clamps).
    pub fn step(&mut self, name: &str, delta: f64) {
        self.step_component(name, usize::MAX, delta);
    }

    /// Adds `delta` to component `c` of `name` (all components for `usize::MAX`), clamped.
    pub fn step_component(&mut self, name: &str, c: usize, delta: f64) {
        debug_assert!(self.has(name), "unknown parameter {name}");
        if let Some(i) = self.index(name) {
            let (lo, hi) = (self.specs[i].min, self.specs[i].max);
            for (k, v) in self.values[i].iter_mut().enumerate() {
                if c == usize::MAX || c == k {
                    // Steps are computed in f32, as the originals' globals are floats.
                    *v = f64::from((*v as f32 + delta as f32).clamp(lo as f32, hi as f32));
                }
            }
        }
    }

    /// Adds `delta` to component `c` of `name` (all for `usize::MAX`), clamped to `[lo, hi]`
    /// instead of the declared range: for keys whose bounds are narrower than what `--set`
    /// accepts (seed 000's keys clamp to [0, 1], its `--set` takes any finite value).
    pub fn step_clamped(&mut self, name: &str, c: usize, delta: f64, lo: f64, hi: f64) {
        debug_assert!(self.has(name), "unknown parameter {name}");
        if let Some(i) = self.index(name) {
            for (k, v) in self.values[i].iter_mut().enumerate() {
                if c == usize::MAX || c == k {
                    *v = f64::from((*v as f32 + delta as f32).clamp(lo as f32, hi as f32));
                }
            }
        }
    }

    /// Sets `name` to `value` without range checks beyond clamping (keys, clocks).
    pub fn set_unchecked(&mut self, name: &str, values: &[f64]) {
        debug_assert!(self.has(name), "unknown parameter {name}");
        if let Some(i) = self.index(name) {
            let (lo, hi, or) = (self.specs[i].min, self.specs[i].max, self.specs[i].or);
            self.values[i] = values
                .iter()
                .map(|&v| if or == Some(v) { v } else { v.clamp(lo, hi) })
                .collect();
        }
    }

    /// Flips a switch.
    pub fn toggle(&mut self, name: &str) {
        let v = if self.on(name) { 0.0 } else { 1.0 };
        self.set_unchecked(name, &[v]);
    }

    /// Moves a choice or whole number to its next value, wrapping to the minimum.
    pub fn cycle(&mut self, name: &str) {
        if let Some(i) = self.index(name) {
            let (lo, hi) = (self.specs[i].min, self.specs[i].max);
            let next = self.values[i][0] + 1.0;
            self.values[i][0] = if next > hi { lo } else { next };
        }
    }

    /// The parameters away from their defaults, in declaration order, as `(name, text)`: the
    /// state a title shows and a link keeps.
    pub fn changed(&self) -> impl Iterator<Item = (&'static str, String)> + '_ {
        self.specs
            .iter()
            .zip(&self.values)
            .filter(|(s, v)| v.as_slice() != s.default)
            .map(|(s, v)| (s.name, format_value(s, v)))
    }

    /// The value of `name` as text (a choice's name, or numbers).
    pub fn text(&self, name: &str) -> String {
        match self.index(name) {
            Some(i) => format_value(&self.specs[i], &self.values[i]),
            None => String::new(),
        }
    }

    fn unknown(&self, name: &str) -> Error {
        let valid: Vec<&str> = self.specs.iter().map(|s| s.name).collect();
        Error::Param(format!(
            "unknown parameter `{name}`; valid: {}",
            if valid.is_empty() {
                "(none)".to_string()
            } else {
                valid.join(", ")
            }
        ))
    }

    /// `--help` text: one line per parameter with its default and range.
    pub fn help(&self) -> String {
        let mut out = String::new();
        for s in &self.specs {
            let range = match s.kind {
                Kind::Choice(names) => format!(
                    "one of {}",
                    names
                        .iter()
                        .enumerate()
                        .map(|(i, n)| format!("{n} ({i})"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
                Kind::Bool => "0 or 1".into(),
                Kind::Int if s.auto.is_some() => format!("whole number {} or auto", range_text(s)),
                Kind::Int => format!("whole number {}", range_text(s)),
                // A range no lab declared (the floats a shader holds, ±f32::MAX) is any value.
                Kind::Real if s.min <= -f64::from(f32::MAX) && s.max >= f64::from(f32::MAX) => "any value".into(),
                Kind::Real => range_text(s),
            };
            // A long array's default is abbreviated: `uniform float a[100000]` would print
            // 100,000 zeros.
            let default = if s.default.len() > 16 {
                format!("{},... ({} numbers)", format_value(s, &s.default[..4]), s.default.len())
            } else {
                s.default_text()
            };
            out.push_str(&format!(
                "  {:<16} default {:<14} {range}: {}\n",
                s.name, default, s.help
            ));
        }
        out
    }
}

/// Parses one finite number, in f64: the value is compared with its range in the type it is
/// stored in (an f32 parse made `0.0001` 0.0000999999974, below a bound of 0.0001, and
/// `16777217` 16777216), and narrowed to f32 only where a shader takes a float.
pub fn parse_finite(s: &str) -> std::result::Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("`{s}` is not a finite number")),
    }
}

/// Parses comma-separated finite numbers.
pub fn parse_numbers(s: &str) -> std::result::Result<Vec<f64>, String> {
    s.split(',').map(parse_finite).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const SPECS: &[ParamSpec] = &[
        ParamSpec::real("ka", &[0.2], 0.0, 1.0, "ambient"),
        ParamSpec::real("light", &[2.0, 2.0, 2.0], -50.0, 50.0, "light"),
        ParamSpec::choice("object", &[0.0], &["teapot", "sphere", "torus", "cube"], "object"),
        ParamSpec::flag("fixpos", &[0.0], "fix"),
    ];

    #[test]
    fn set_checks_names_counts_ranges_and_kinds() {
        let mut p = Params::new(SPECS);
        assert_eq!(p.f("ka"), 0.2);
        p.set_str("ka", "0.5").unwrap();
        assert_eq!(p.f("ka"), 0.5);
        assert!(p.set_str("ka", "1.5").unwrap_err().to_string().contains("outside"));
        assert!(p.set_str("ka", "nan").is_err());
        assert!(p.set_str("light", "1,2").unwrap_err().to_string().contains("3 number"));
        p.set_str("object", "torus").unwrap();
        assert_eq!(p.index_of("object"), 2);
        p.set_str("object", "3").unwrap();
        assert_eq!(p.text("object"), "cube");
        assert!(p.set_str("object", "4").unwrap_err().to_string().contains("3 = cube"));
        assert!(p.set_str("object", "1.5").is_err());
        assert!(p.set_str("fixpos", "2").is_err());
        let e = p.set_str("nope", "1").unwrap_err().to_string();
        assert!(
            e.contains("unknown parameter `nope`") && e.contains("ka, light, object, fixpos"),
            "{e}"
        );
    }

    #[test]
    fn changed_lists_what_is_away_from_its_default_in_order() {
        let mut p = Params::new(SPECS);
        assert_eq!(p.changed().count(), 0);
        p.set_str("object", "torus").unwrap();
        p.set_str("ka", "0.5").unwrap();
        let changed: Vec<(&str, String)> = p.changed().collect();
        assert_eq!(changed, [("ka", "0.5".to_owned()), ("object", "torus".to_owned())]);
        p.set_str("ka", "0.2").unwrap();
        assert_eq!(p.changed().map(|(n, _)| n).collect::<Vec<_>>(), ["object"]);
    }

    #[test]
    fn steps_clamp_and_choices_cycle() {
        let mut p = Params::new(SPECS);
        for _ in 0..30 {
            p.step("ka", 0.05);
        }
        assert_eq!(p.f("ka"), 1.0);
        p.step_component("light", 1, -0.25);
        assert_eq!(p.v3("light"), [2.0, 1.75, 2.0]);
        for _ in 0..4 {
            p.cycle("object");
        }
        assert_eq!(p.index_of("object"), 0);
        p.toggle("fixpos");
        assert!(p.on("fixpos"));
        assert!(p.help().contains("teapot (0)"));
    }

    #[test]
    fn documented_bounds_are_taken_and_whole_numbers_are_exact() {
        const EDGES: &[ParamSpec] = &[
            ParamSpec::real("near", &[1.0], 1e-4, 1e6, "near"),
            ParamSpec::real("Ka", &[0.0], -1e30, 1e30, "big"),
            ParamSpec::int("k", &[0.0], -2147483648.0, 2147483647.0, "int"),
        ];
        let mut p = Params::new(EDGES);
        // f32 parsing made 0.0001 0.0000999999974 (below the bound) and 1e30 1.00000002e30.
        p.set_str("near", "0.0001").unwrap();
        p.set_str("Ka", "1e30").unwrap();
        p.set_str("Ka", "-1e30").unwrap();
        p.set_str("k", "2147483647").unwrap();
        p.set_str("k", "-2147483648").unwrap();
        // 16777217 is no f32: it must reach the shader as itself.
        p.set_str("k", "16777217").unwrap();
        assert_eq!(p.get("k"), Some(&[16777217.0][..]));
        assert_eq!(p.text("k"), "16777217");
        // Errors and --help name the bounds that are checked.
        let e = p.set_str("k", "2147483648").unwrap_err().to_string();
        assert!(e.contains("2147483648 is outside -2147483648..2147483647"), "{e}");
        let e = p.set_str("near", "0.00001").unwrap_err().to_string();
        assert!(e.contains("0.00001 is outside 0.0001..1000000"), "{e}");
        let help = p.help();
        assert!(
            help.contains("0.0001..1000000") && help.contains("-1e30..1e30"),
            "{help}"
        );
        assert!(help.contains("whole number -2147483648..2147483647"), "{help}");
        // A range of any f32 is `any value` in --help, and its bound, as an error prints it,
        // is taken.
        let mut f = Params::new(&[ParamSpec::real("x", &[0.0], -f32::MAX as f64, f32::MAX as f64, "x")]);
        assert!(
            f.help().contains("any value") && !f.help().contains("e38"),
            "{}",
            f.help()
        );
        f.set_str("x", "3.4028235e38").unwrap();
        let e = f.set_str("x", "1e39").unwrap_err().to_string();
        assert!(e.contains("1e39 is outside -3.4028235e38..3.4028235e38"), "{e}");
    }

    #[test]
    fn one_extra_value_rules_between_parameters_and_long_defaults() {
        const SPOT: &[ParamSpec] = &[
            ParamSpec::real("spotCutoff", &[180.0], 0.0, 90.0, "cutoff").or_exactly(180.0),
            ParamSpec::real("near", &[1.0], 1e-4, 1e6, "near"),
            ParamSpec::real("far", &[100.0], 1e-3, 1e7, "far"),
            ParamSpec::real("a", &[0.0; 100], -1.0, 1.0, "array"),
        ];
        fn near_far(p: &Params) -> Result<()> {
            if p.f64("near") >= p.f64("far") {
                return Err(Error::Param("near must be less than far".into()));
            }
            Ok(())
        }
        let mut p = Params::new(SPOT).with_check(near_far);
        let e = p.set_str("spotCutoff", "90.5").unwrap_err().to_string();
        assert!(e.contains("90.5 is outside 0..90 or 180"), "{e}");
        p.set_str("spotCutoff", "180").unwrap();
        p.set_unchecked("spotCutoff", &[180.0]);
        assert_eq!(p.f("spotCutoff"), 180.0, "put keeps the extra value");
        p.set_str("spotCutoff", "45").unwrap();
        assert!(p.check().is_ok());
        p.set_str("near", "200").unwrap();
        assert!(p
            .check()
            .unwrap_err()
            .to_string()
            .contains("near must be less than far"));
        let help = p.help();
        assert!(help.contains("0..90 or 180"), "{help}");
        assert!(help.contains("0,0,0,0,... (100 numbers)"), "{help}");
        assert!(help.len() < 1000, "a long default is abbreviated:\n{help}");
    }
}
