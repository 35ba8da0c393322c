//! The translated text and where each piece of it came from, so that an error naga finds in
//! the GLSL 450 points at the user's own file, line and column.

use std::ops::Range;

use crate::error::Error;
use crate::shader::format_diagnostic;

/// A shader file as the user wrote it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LegacySource {
    /// The path shown in messages.
    pub path: String,
    /// Its text.
    pub text: String,
}

impl LegacySource {
    /// A source from a path and its text.
    pub fn new(path: impl Into<String>, text: impl Into<String>) -> Self {
        LegacySource {
            path: path.into(),
            text: text.into(),
        }
    }

    /// Reads a file: a regular file of at most 1 MiB in UTF-8, as every shader file
    /// ([`crate::shader::read_shader_file`]).
    pub fn read(path: &std::path::Path) -> crate::error::Result<Self> {
        // The rule of every shader file: a regular file of at most 1 MiB, UTF-8.
        let text = crate::shader::read_shader_file(path)?;
        // A byte-order mark is not GLSL.
        let text = text.strip_prefix('\u{feff}').map(str::to_owned).unwrap_or(text);
        Ok(LegacySource::new(path.display().to_string(), text))
    }

    /// The 1-based line and column (in characters) of a byte offset, and the line's text.
    pub fn line_col(&self, offset: usize) -> (u32, u32, &str) {
        let offset = floor_char_boundary(&self.text, offset.min(self.text.len()));
        let start = self.text[..offset].rfind('\n').map_or(0, |i| i + 1);
        let end = self.text[offset..].find('\n').map_or(self.text.len(), |i| offset + i);
        let line = self.text[..start].matches('\n').count() as u32 + 1;
        let column = self.text[start..offset].chars().count() as u32 + 1;
        (line, column, self.text[start..end].trim_end_matches('\r'))
    }

    /// An error at `range` of this file, formatted as `path:line:col: message` with the line
    /// and a caret, like every other shader error of shaderlab.
    pub fn error(&self, range: Range<usize>, message: &str) -> Error {
        let (line, column, text) = self.line_col(range.start);
        let len = self
            .text
            .get(range.clone())
            .map_or(1, |t| t.lines().next().unwrap_or("").chars().count());
        Error::Shader {
            file: self.path.clone(),
            line,
            column,
            message: format_diagnostic(&self.path, line, column, message, text, len.max(1)),
        }
    }
}

/// The start of every line of a text, for line numbers in O(log n) each.
pub struct LineIndex(Vec<usize>);

impl LineIndex {
    /// The index of `text`.
    pub fn new(text: &str) -> Self {
        LineIndex(
            std::iter::once(0)
                .chain(text.match_indices('\n').map(|(i, _)| i + 1))
                .collect(),
        )
    }

    /// The 1-based line of a byte offset (as [`LegacySource::line_col`] counts it).
    pub fn line(&self, offset: usize) -> u32 {
        self.0.partition_point(|&start| start <= offset) as u32
    }
}

fn floor_char_boundary(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

/// Which file a piece of generated text stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum File {
    /// The stage's own file.
    This,
    /// The other stage's file (a uniform both declare, a varying matched by name).
    Other,
}

/// A place in one of the two files.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Origin {
    /// The file.
    pub file: File,
    /// Byte offset in it.
    pub offset: usize,
    /// Length of the construct, for the caret.
    pub len: usize,
}

impl Origin {
    /// A place in the stage's own file.
    pub fn this(range: Range<usize>) -> Self {
        Origin {
            file: File::This,
            offset: range.start,
            len: range.len(),
        }
    }
}

#[derive(Clone, Copy, Debug)]
struct Piece {
    start: usize,
    end: usize,
    origin: Origin,
    /// Copied verbatim: offsets inside map one to one.
    exact: bool,
}

/// Generated text with a map back to the user's files.
#[derive(Clone, Debug, Default)]
pub struct Output {
    /// The GLSL 450 text.
    pub text: String,
    pieces: Vec<Piece>,
}

impl Output {
    /// Appends generated text that stands for `origin`.
    pub fn generated(&mut self, text: &str, origin: Origin) {
        let start = self.text.len();
        self.text.push_str(text);
        self.pieces.push(Piece {
            start,
            end: self.text.len(),
            origin,
            exact: false,
        });
    }

    /// Appends `range` of the stage's own file verbatim.
    pub fn copy(&mut self, source: &str, range: Range<usize>) {
        let start = self.text.len();
        self.text.push_str(&source[range.clone()]);
        self.pieces.push(Piece {
            start,
            end: self.text.len(),
            origin: Origin::this(range),
            exact: true,
        });
    }

    /// Where the byte `offset` of the generated text came from.
    pub fn locate(&self, offset: usize) -> Option<Origin> {
        let i = self.pieces.partition_point(|p| p.end <= offset);
        let piece = self.pieces.get(i).or_else(|| self.pieces.last())?;
        if piece.exact {
            let delta = offset.saturating_sub(piece.start).min(piece.end - piece.start);
            Some(Origin {
                file: piece.origin.file,
                offset: piece.origin.offset + delta,
                len: 1,
            })
        } else {
            Some(piece.origin)
        }
    }

    /// For each line of the text (0-based), the origin of its first mapped character.
    pub fn line_origins(&self) -> Vec<Option<Origin>> {
        let mut out = Vec::new();
        let mut start = 0;
        for line in self.text.split_inclusive('\n') {
            let trimmed = line.len() - line.trim_start().len();
            out.push(self.locate(start + trimmed));
            start += line.len();
        }
        out
    }
}

/// One replacement in a file: `range` becomes `text`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Edit {
    /// Bytes replaced.
    pub range: Range<usize>,
    /// Their replacement.
    pub text: String,
}

/// Copies `source` into `out` with `edits` applied (sorted, not overlapping: an edit inside
/// one already applied is dropped, the outer one wins).
pub fn apply(out: &mut Output, source: &str, edits: &[Edit]) {
    let mut edits: Vec<&Edit> = edits.iter().collect();
    edits.sort_by_key(|e| (e.range.start, std::cmp::Reverse(e.range.end)));
    let mut at = 0;
    for edit in edits {
        if edit.range.start < at {
            continue;
        }
        if edit.range.start > at {
            out.copy(source, at..edit.range.start);
        }
        out.generated(&edit.text, Origin::this(edit.range.clone()));
        at = edit.range.end;
    }
    if at < source.len() {
        out.copy(source, at..source.len());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edits_keep_positions() {
        let src = "attribute vec3 a;\nvoid main() { x = a; }\n";
        let mut out = Output::default();
        out.generated("#version 450\n", Origin::this(0..0));
        apply(
            &mut out,
            src,
            &[
                Edit {
                    range: 0..17,
                    text: "layout(location=0) in vec3 a;".into(),
                },
                Edit {
                    range: 23..27,
                    text: "sl_main".into(),
                },
            ],
        );
        assert_eq!(
            out.text,
            "#version 450\nlayout(location=0) in vec3 a;\nvoid sl_main() { x = a; }\n"
        );
        // The `x` of the second line is at offset 32 of the source.
        let x = out.text.find("x =").unwrap();
        assert_eq!(out.locate(x).unwrap().offset, 32);
        let s = LegacySource::new("a.vert", src);
        assert_eq!(s.line_col(32), (2, 15, "void main() { x = a; }"));
        let index = LineIndex::new(src);
        for offset in 0..=src.len() + 1 {
            assert_eq!(index.line(offset), s.line_col(offset).0, "{offset}");
        }
        // Inside a replacement: its start.
        let loc = out.text.find("location").unwrap();
        assert_eq!(out.locate(loc).unwrap().offset, 0);
    }
}
