//! Links that carry the shaders: the page's link (`?lab=NAME&set=NAME%3DVALUE&…`), with every
//! shader file that differs from the built-in text compressed into its fragment
//! (`#files=…`, which a browser never sends to a server). The page's Copy link makes one
//! ([`page_link`]) and opens one ([`Link::check`], then the files into its editor);
//! `shaderlab link` makes the same link from a folder or a legacy pair, and `shaderlab open`
//! writes a link's files into a folder and runs the lab from there (`super::link_verb`).
//!
//! The fragment is `files=` and the base64url (no padding) of the zlib-compressed JSON
//! `{"v":1,"files":{"NAME":"TEXT",…}}`, the files sorted by name, so the same files make the
//! same link wherever it is made. A link is refused, with one message, when its fragment is
//! cut short or damaged (zlib's checksum), longer than [`MAX_FRAGMENT`] characters, more
//! than [`MAX_FILES_BYTES`] once decompressed (a zip bomb stops there), of a newer format,
//! for a lab there is no such lab, with a parameter the lab lacks, or with a file name that
//! is not a plain name of a shader file the lab could read (no folder, no `..`, no absolute
//! path): docs/web.md has the format, docs/bad-input.md the messages.

use std::collections::BTreeMap;
use std::io::Write;

use base64::Engine;

use crate::lab::LabEntry;
use crate::params::Params;

/// The most characters a link's fragment may hold after `#files=` (32 KiB): a browser keeps
/// links far longer, but a link is for pasting, and this is already about 100 KiB of GLSL.
pub const MAX_FRAGMENT: usize = 32 * 1024;

/// The most bytes the files' JSON may come to once decompressed (1 MiB, the loader's cap on
/// one shader file): a fragment within [`MAX_FRAGMENT`] that inflates past it is refused
/// before more is read.
pub const MAX_FILES_BYTES: usize = 1 << 20;

/// The page's address `shaderlab link` writes when given no `--base`: where `scripts/web
/// --serve` serves the page.
pub const DEFAULT_BASE: &str = "http://127.0.0.1:8000/";

/// The format of the files' JSON (`"v"`).
pub const FORMAT: u64 = 1;

/// The extensions a file of legacy's pair may have in a link (those the page's "Load files"
/// takes as shaders).
pub const PAIR_EXTENSIONS: &[&str] = &["vert", "frag", "glsl", "vs", "fs", "vsh", "fsh"];

/// The names under which the page edits legacy's built-in pair, and the names a link carries
/// them by (a link's names have no folder).
const LEGACY_DEFAULT: [(&str, &str); 2] = [
    ("legacy/default.vert", "default.vert"),
    ("legacy/default.frag", "default.frag"),
];

const FRAGMENT_KEY: &str = "files=";

/// The longest file name a link may carry (most file systems' limit).
const MAX_NAME: usize = 255;

/// Why a link cannot be made or opened.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum LinkError {
    /// The fragment is cut short, damaged, or not shaderlab's.
    #[error("the link's files are cut short or damaged ({0}): copy the whole link again")]
    Damaged(String),
    /// The fragment is longer than [`MAX_FRAGMENT`].
    #[error(
        "the link's files take {len} characters after `#files=`, more than a link carries ({MAX_FRAGMENT}); \
         shaderlab makes no such link"
    )]
    TooLong {
        /// Its length.
        len: usize,
    },
    /// The files come to more than [`MAX_FILES_BYTES`] once decompressed.
    #[error(
        "the link's files come to more than {MAX_FILES_BYTES} bytes (1 MiB) once decompressed, more than a \
         link carries; shaderlab makes no such link"
    )]
    TooLarge,
    /// The files to carry do not fit in a link.
    #[error(
        "the changed shader files ({names}) come to {bytes} bytes, {len} characters compressed, more than a link \
         carries ({MAX_FRAGMENT} characters after `#`, {MAX_FILES_BYTES} bytes of text): share the files themselves"
    )]
    TooBig {
        /// The files.
        names: String,
        /// Their JSON's size.
        bytes: usize,
        /// The fragment's length, or 0 where the text alone is past the cap.
        len: usize,
    },
    /// A format this build does not read.
    #[error("the link's files are in format {0}, newer than this shaderlab reads ({FORMAT}): update shaderlab")]
    Newer(u64),
    /// No `lab=`.
    #[error("the link names no lab (`lab=NAME` after `?`)")]
    NoLab,
    /// `lab=` names no lab.
    #[error("the link names no lab called `{name}`; the labs are: {labs}")]
    UnknownLab {
        /// The name.
        name: String,
        /// Every lab's name.
        labs: String,
    },
    /// A `set=` the lab refuses.
    #[error("the link's `set={set}`: {why}")]
    Param {
        /// The assignment.
        set: String,
        /// The lab's refusal.
        why: String,
    },
    /// A file name the lab cannot take.
    #[error("the link carries a file named `{name}`: {why}")]
    Name {
        /// The name, as the link has it.
        name: String,
        /// Why it is refused.
        why: String,
    },
    /// Legacy's pair and the files carried disagree.
    #[error("{0}")]
    Pair(String),
}

/// A link: the page's address, its query (the lab and its state) and the files it carries.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Link {
    /// Everything before `?` (`http://127.0.0.1:8000/`).
    pub base: String,
    /// The query's pairs in order, decoded: `lab`, each `set` (`NAME=VALUE`), and whatever
    /// else the page keeps (`view`, `inspect`, `paused`, …), which only the page reads.
    pub query: Vec<(String, String)>,
    /// The shader files, by file name.
    pub files: BTreeMap<String, String>,
}

impl Link {
    /// A link to `lab` on the page at `base`, with no state and no files.
    pub fn new(base: &str, lab: &str) -> Link {
        Link {
            base: base.to_owned(),
            query: vec![("lab".into(), lab.into())],
            files: BTreeMap::new(),
        }
    }

    /// Reads a link: an address, or `?query` alone, with or without `#files=…`. Checks the
    /// form only (percent escapes, the fragment); [`Link::check`] checks it against its lab.
    pub fn parse(text: &str) -> Result<Link, LinkError> {
        let text = text.trim();
        let (before, fragment) = match text.split_once('#') {
            Some((before, fragment)) => (before, Some(fragment)),
            None => (text, None),
        };
        let (base, query) = before.split_once('?').unwrap_or((before, ""));
        let mut pairs = Vec::new();
        for part in query.split('&').filter(|p| !p.is_empty()) {
            let (key, value) = part.split_once('=').unwrap_or((part, ""));
            pairs.push((unescape(key)?, unescape(value)?));
        }
        let files = match fragment {
            None | Some("") => BTreeMap::new(),
            Some(fragment) => decode_files(fragment)?,
        };
        Ok(Link {
            base: base.to_owned(),
            query: pairs,
            files,
        })
    }

    /// The link as text: the base, the query, and `#files=…` when it carries files.
    pub fn to_url(&self) -> Result<String, LinkError> {
        let query: Vec<String> = self
            .query
            .iter()
            .map(|(k, v)| format!("{}={}", escape(k), escape(v)))
            .collect();
        let mut url = format!("{}?{}", self.base, query.join("&"));
        if !self.files.is_empty() {
            url.push('#');
            url.push_str(&encode_files(&self.files)?);
        }
        Ok(url)
    }

    /// The lab's name (`lab=`; the last where there are several, as the page reads it).
    pub fn lab(&self) -> Option<&str> {
        self.values("lab").last().copied()
    }

    /// The assignments (`set=`), in order, as the page and `--set` take them.
    pub fn sets(&self) -> Vec<&str> {
        self.values("set")
    }

    /// Adds an assignment.
    pub fn push_set(&mut self, set: &str) {
        self.query.push(("set".into(), set.into()));
    }

    /// Legacy's pair (`set=files=VERT,FRAG`), as written.
    pub fn pair(&self) -> Option<&str> {
        self.sets().iter().rev().find_map(|s| s.strip_prefix("files="))
    }

    /// Names legacy's pair `vert`, `frag` in place of any pair named before (first among the
    /// assignments, where the page writes it).
    pub fn set_pair(&mut self, vert: &str, frag: &str) {
        self.query.retain(|(k, v)| !(k == "set" && v.starts_with("files=")));
        let at = self.query.iter().position(|(k, _)| k == "lab").map_or(0, |i| i + 1);
        self.query.insert(at, ("set".into(), format!("files={vert},{frag}")));
    }

    fn values(&self, key: &str) -> Vec<&str> {
        self.query
            .iter()
            .filter(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
            .collect()
    }

    /// Checks the link against its lab: the lab exists, each file's name is one the lab could
    /// read ([`check_name`]) and, for legacy, the pair it names is carried (or `known`: a
    /// file the page already has) and nothing else is. Returns the lab.
    pub fn check(&self, known: &dyn Fn(&str) -> bool) -> Result<&'static LabEntry, LinkError> {
        let name = self.lab().ok_or(LinkError::NoLab)?;
        let entry = crate::course::find(name).ok_or_else(|| LinkError::UnknownLab {
            name: name.to_owned(),
            labs: crate::course::ALL
                .iter()
                .map(|e| e.info.name)
                .collect::<Vec<_>>()
                .join(", "),
        })?;
        for file in self.files.keys() {
            check_name(entry, file)?;
        }
        if !draws_pair(entry) {
            return Ok(entry);
        }
        let lab = entry.info.name;
        let Some(pair) = self.pair() else {
            if self.files.is_empty() {
                return Ok(entry);
            }
            return Err(LinkError::Pair(format!(
                "the link carries {} but names no pair for {lab} to draw (`set=files=VERT,FRAG`)",
                self.names()
            )));
        };
        let names: Vec<&str> = pair.split(',').collect();
        if names.len() != 2 {
            return Err(LinkError::Param {
                set: format!("files={pair}"),
                why: format!("{lab} takes two files, VERT,FRAG"),
            });
        }
        for name in &names {
            check_name(entry, name)?;
            if !self.files.contains_key(*name) && !known(name) {
                return Err(LinkError::Pair(format!(
                    "the link names the pair files={pair} but carries no text for `{name}`: copy the link again \
                     from a page that has the file"
                )));
            }
        }
        if let Some(extra) = self.files.keys().find(|f| !names.contains(&f.as_str())) {
            return Err(LinkError::Pair(format!(
                "the link carries `{extra}`, which {lab} does not draw: its pair is files={pair}"
            )));
        }
        Ok(entry)
    }

    /// Sets the link's assignments on `params` (the lab's, with a pair's own parameters
    /// declared), as `--set` does, and checks the rules between them; legacy's `files=` is
    /// the pair, not a parameter.
    pub fn check_sets(&self, params: &mut Params) -> Result<(), LinkError> {
        let lab = self.lab().unwrap_or("the lab");
        let pair = params.file_args().is_some();
        for set in self.sets() {
            let refused = |why: String| LinkError::Param {
                set: set.to_owned(),
                why,
            };
            let Some((key, value)) = set.split_once('=') else {
                return Err(refused("expected NAME=VALUE".into()));
            };
            let (key, value) = (key.trim(), value.trim());
            if pair && key == "files" {
                continue;
            }
            if !params.has(key) {
                let valid: Vec<&str> = params.specs().iter().map(|s| s.name).collect();
                return Err(refused(format!(
                    "unknown parameter `{key}` for {lab}; valid: {}",
                    valid.join(", ")
                )));
            }
            params.set_str(key, value).map_err(|e| refused(e.to_string()))?;
        }
        params.check().map_err(|e| LinkError::Param {
            set: self.sets().join("&set="),
            why: e.to_string(),
        })
    }

    fn names(&self) -> String {
        self.files.keys().cloned().collect::<Vec<_>>().join(", ")
    }
}

/// Whether `entry` draws a pair of files it is given (legacy) rather than its own shaders.
pub fn draws_pair(entry: &LabEntry) -> bool {
    (entry.params)().file_args().is_some()
}

/// Checks that a link may carry a file called `name` for `entry`: a plain file name (no
/// folder, no `..`, not absolute, no control character, `:` or leading `.`), at most 255
/// bytes, of a shader file the lab could read: for legacy a GLSL extension
/// ([`PAIR_EXTENSIONS`]) and no comma (the pair is written `files=VERT,FRAG`); for the other
/// labs a file of `shaders_glsl/` or a new `.glsl` file that one of them `#include`s.
pub fn check_name(entry: &LabEntry, name: &str) -> Result<(), LinkError> {
    let refuse = |why: String| {
        Err(LinkError::Name {
            name: name.escape_debug().to_string(),
            why,
        })
    };
    let plain = "a link's files are plain file names, written into one folder";
    let windows_drive = name.len() >= 2 && name.as_bytes()[0].is_ascii_alphabetic() && name.as_bytes()[1] == b':';
    if name.is_empty() {
        return refuse("an empty name".into());
    }
    if name.starts_with(['/', '\\']) || windows_drive {
        return refuse(format!("an absolute path; {plain}"));
    }
    if name.split(['/', '\\']).any(|part| part == "..") {
        return refuse(format!("`..` climbs out of the folder; {plain}"));
    }
    if name.contains(['/', '\\']) {
        return refuse(format!("the name has a folder; {plain}"));
    }
    if name.len() > MAX_NAME {
        return refuse(format!("{} bytes, more than a file name has ({MAX_NAME})", name.len()));
    }
    if name.starts_with('.') || name.chars().any(|c| c.is_control() || c == ':') {
        return refuse("not a plain file name (a leading `.`, `:` or a control character)".into());
    }
    let lab = entry.info.name;
    if draws_pair(entry) {
        let ext = name.rsplit_once('.').map_or("", |(_, e)| e).to_ascii_lowercase();
        if !PAIR_EXTENSIONS.contains(&ext.as_str()) || name.contains(',') {
            return refuse(format!(
                "not the name of a shader file {lab} reads from a link: .{} without a comma",
                PAIR_EXTENSIONS.join(", .")
            ));
        }
    } else if crate::shader::embedded_source(name).is_none() && !name.ends_with(".glsl") {
        return refuse(format!(
            "not a shader file {lab} could read: a link carries files of shaders_glsl/ (phong.frag, noise.glsl, …) \
             and new .glsl files they #include"
        ));
    }
    Ok(())
}

/// The fragment (without `#`) that carries `files`: `files=` and the base64url of their
/// compressed JSON. Refused when it would pass [`MAX_FRAGMENT`] or the text
/// [`MAX_FILES_BYTES`].
pub fn encode_files(files: &BTreeMap<String, String>) -> Result<String, LinkError> {
    let json = serde_json::json!({ "v": FORMAT, "files": files }).to_string();
    let names = || files.keys().cloned().collect::<Vec<_>>().join(", ");
    if json.len() > MAX_FILES_BYTES {
        return Err(LinkError::TooBig {
            names: names(),
            bytes: json.len(),
            len: 0,
        });
    }
    let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::best());
    let compressed = z
        .write_all(json.as_bytes())
        .and_then(|()| z.finish())
        .map_err(|e| LinkError::Damaged(format!("compressing: {e}")))?;
    let text = base64::engine::general_purpose::URL_SAFE_NO_PAD.encode(compressed);
    if text.len() > MAX_FRAGMENT {
        return Err(LinkError::TooBig {
            names: names(),
            bytes: json.len(),
            len: text.len(),
        });
    }
    Ok(format!("{FRAGMENT_KEY}{text}"))
}

/// The files a fragment (without `#`) carries; see [`LinkError`] for what is refused.
pub fn decode_files(fragment: &str) -> Result<BTreeMap<String, String>, LinkError> {
    let Some(text) = fragment.strip_prefix(FRAGMENT_KEY) else {
        let shown: String = fragment.chars().take(24).collect();
        let more = if shown.len() < fragment.len() { "…" } else { "" };
        return Err(LinkError::Damaged(format!(
            "the part after `#` is `{}{more}`, not shaderlab's `files=…`",
            shown.escape_debug()
        )));
    };
    if text.len() > MAX_FRAGMENT {
        return Err(LinkError::TooLong { len: text.len() });
    }
    let lenient = base64::engine::GeneralPurpose::new(
        &base64::alphabet::URL_SAFE,
        base64::engine::GeneralPurposeConfig::new()
            .with_decode_padding_mode(base64::engine::DecodePaddingMode::Indifferent),
    );
    let compressed = lenient.decode(text).map_err(|e| {
        LinkError::Damaged(match e {
            base64::DecodeError::InvalidByte(at, byte) => {
                format!(
                    "`{}` at character {} is not base64url",
                    char::from(byte).escape_debug(),
                    at + 1
                )
            }
            base64::DecodeError::InvalidLength(len) => format!("{len} characters of base64url make no whole bytes"),
            e => format!("not base64url: {e}"),
        })
    })?;
    let json = inflate(&compressed)?;
    let value: serde_json::Value =
        serde_json::from_slice(&json).map_err(|e| LinkError::Damaged(format!("not the files' JSON: {e}")))?;
    let version = value.get("v").and_then(serde_json::Value::as_u64);
    match version {
        Some(FORMAT) => {}
        Some(v) if v > FORMAT => return Err(LinkError::Newer(v)),
        _ => return Err(LinkError::Damaged(format!("no format {FORMAT} (`\"v\": {FORMAT}`)"))),
    }
    let Some(map) = value.get("files").and_then(serde_json::Value::as_object) else {
        return Err(LinkError::Damaged("no `files` object".into()));
    };
    let mut files = BTreeMap::new();
    for (name, text) in map {
        let Some(text) = text.as_str() else {
            return Err(LinkError::Damaged(format!(
                "the text of `{}` is not a string",
                name.escape_debug()
            )));
        };
        files.insert(name.clone(), text.to_owned());
    }
    Ok(files)
}

/// Decompresses a zlib stream of at most [`MAX_FILES_BYTES`]: the whole stream, its checksum
/// checked, and nothing after it; output past the cap stops it.
fn inflate(compressed: &[u8]) -> Result<Vec<u8>, LinkError> {
    let damaged = |why: &str| LinkError::Damaged(format!("the compressed data {why}"));
    let mut z = flate2::Decompress::new(true);
    let mut out: Vec<u8> = Vec::with_capacity(compressed.len().saturating_mul(4).clamp(1024, MAX_FILES_BYTES + 1));
    loop {
        let (read, written) = (z.total_in(), z.total_out());
        let status = z
            .decompress_vec(&compressed[read as usize..], &mut out, flate2::FlushDecompress::None)
            .map_err(|e| LinkError::Damaged(format!("the compressed data is damaged: {e}")))?;
        if out.len() > MAX_FILES_BYTES {
            return Err(LinkError::TooLarge);
        }
        if status == flate2::Status::StreamEnd {
            break;
        }
        if out.len() == out.capacity() {
            out.reserve_exact(out.capacity().min(MAX_FILES_BYTES + 1 - out.len()));
        } else if (z.total_in(), z.total_out()) == (read, written) {
            return Err(damaged("ends early"));
        }
    }
    if (z.total_in() as usize) < compressed.len() {
        return Err(damaged("has bytes after its end"));
    }
    Ok(out)
}

/// The link the page's Copy link gives: `url` (the page's address with its state, as its
/// `updateUrl()` writes it; any fragment is dropped) and the files that differ from the
/// built-in text among the page's `texts` (its edits, its course files and the files handed
/// to it, by name): for legacy the pair it draws (`pair`, the names of `files=`; the built-in
/// pair, when edited, as `default.vert` and `default.frag`), for the other labs each file of
/// `shaders_glsl/` edited and each `.glsl` file handed over.
pub fn page_link(
    url: &str,
    entry: &LabEntry,
    texts: &BTreeMap<String, String>,
    pair: &[String],
) -> Result<String, LinkError> {
    let mut link = Link::parse(url.split('#').next().unwrap_or(url))?;
    if draws_pair(entry) {
        match pair {
            [vert, frag] => {
                for name in [vert, frag] {
                    if let Some(text) = texts.get(name) {
                        link.files.insert(name.clone(), text.clone());
                    }
                }
            }
            _ => {
                let built_in = [crate::course::legacy::DEFAULT_VERT, crate::course::legacy::DEFAULT_FRAG];
                let edited = LEGACY_DEFAULT
                    .iter()
                    .zip(built_in)
                    .any(|((page, _), text)| texts.get(*page).is_some_and(|t| t != text));
                if edited {
                    for ((page, name), text) in LEGACY_DEFAULT.iter().zip(built_in) {
                        let text = texts.get(*page).map_or(text, String::as_str);
                        link.files.insert((*name).to_owned(), text.to_owned());
                    }
                    link.set_pair(LEGACY_DEFAULT[0].1, LEGACY_DEFAULT[1].1);
                }
            }
        }
    } else {
        for (name, text) in texts {
            let differs = crate::shader::embedded_source(name) != Some(text.as_str());
            if differs && check_name(entry, name).is_ok() {
                link.files.insert(name.clone(), text.clone());
            }
        }
    }
    link.to_url()
}

/// Percent-encodes a query's key or value as the page's `URLSearchParams` does (letters,
/// digits and `*-._` as they are, a space as `+`, every other byte `%XX`).
fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for b in s.bytes() {
        match b {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'*' | b'-' | b'.' | b'_' => out.push(b as char),
            b' ' => out.push('+'),
            _ => out.push_str(&format!("%{b:02X}")),
        }
    }
    out
}

/// Decodes a query's key or value (`+` a space, `%XX` a byte), as UTF-8.
fn unescape(s: &str) -> Result<String, LinkError> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'+' => out.push(b' '),
            b'%' => {
                let hex = bytes.get(i + 1..i + 3).and_then(|h| std::str::from_utf8(h).ok());
                match hex.and_then(|h| u8::from_str_radix(h, 16).ok()) {
                    Some(b) => out.push(b),
                    None => {
                        let shown: String = s[i..].chars().take(3).collect();
                        return Err(LinkError::Damaged(format!("`{shown}` is not a percent escape")));
                    }
                }
                i += 2;
            }
            b => out.push(b),
        }
        i += 1;
    }
    String::from_utf8(out).map_err(|_| LinkError::Damaged(format!("`{s}` is not UTF-8 once decoded")))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn phong() -> &'static LabEntry {
        crate::course::find("phong").unwrap()
    }

    fn legacy() -> &'static LabEntry {
        crate::course::find("legacy").unwrap()
    }

    /// phong.frag with its ambient term doubled: an edit as a student makes it.
    fn edited() -> BTreeMap<String, String> {
        let text = crate::shader::embedded_source("phong.frag").unwrap();
        let edited = text.replacen("max(dot(N, L), 0.0)", "max(dot(N, L), 0.5)", 1);
        assert_ne!(text, edited, "the edit applies");
        [("phong.frag".to_owned(), edited)].into()
    }

    fn link_with(files: BTreeMap<String, String>) -> Link {
        let mut link = Link::new(DEFAULT_BASE, "phong");
        link.push_set("Ka=0.2");
        link.push_set("object=torus");
        link.files = files;
        link
    }

    /// A fragment of `json` compressed as a link's.
    fn fragment_of(json: &[u8]) -> String {
        let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::best());
        z.write_all(json).unwrap();
        let text = base64::engine::general_purpose::URL_SAFE_NO_PAD.encode(z.finish().unwrap());
        format!("files={text}")
    }

    fn damaged(result: Result<Link, LinkError>) -> String {
        match result {
            Err(LinkError::Damaged(why)) => why,
            other => panic!("expected a damaged link, got {other:?}"),
        }
    }

    #[test]
    fn a_link_carries_its_files_and_state_there_and_back() {
        let mut files = edited();
        files.insert(
            "mine.glsl".into(),
            "// ünïcode, \"quotes\", \\ and a tab\t\n#define K 1.0\n".into(),
        );
        let mut link = link_with(files);
        link.push_set("lightPosition=1,2,3");
        link.query.push(("note".into(), "a b&c#d%e+f=g/h?ü".into()));
        let url = link.to_url().unwrap();
        assert!(
            url.starts_with("http://127.0.0.1:8000/?lab=phong&set=Ka%3D0.2&set=object%3Dtorus&"),
            "{url}"
        );
        let (_, fragment) = url.split_once('#').expect("the files after #");
        assert!(fragment.starts_with("files="), "{fragment}");
        assert!(
            fragment["files=".len()..]
                .bytes()
                .all(|b| b.is_ascii_alphanumeric() || b == b'-' || b == b'_'),
            "base64url: {fragment}"
        );
        let back = Link::parse(&url).unwrap();
        assert_eq!(back, link);
        assert_eq!(back.to_url().unwrap(), url, "the same files make the same link");
        assert_eq!(back.check(&|_| false).unwrap().info.name, "phong");
        let mut params = (phong().params)();
        back.check_sets(&mut params).unwrap();
        assert_eq!(params.text("Ka"), "0.2");
        // Without files: the state alone, no fragment; a query alone is a link too.
        let bare = Link::new(DEFAULT_BASE, "phong").to_url().unwrap();
        assert_eq!(bare, "http://127.0.0.1:8000/?lab=phong");
        let alone = Link::parse("?lab=noise&set=time%3D1.5").unwrap();
        assert_eq!((alone.lab(), alone.sets()), (Some("noise"), vec!["time=1.5"]));
    }

    #[test]
    fn a_cut_or_damaged_link_is_refused() {
        let url = link_with(edited()).to_url().unwrap();
        let (head, fragment) = url.split_once('#').unwrap();
        // Cut anywhere after `files=`: the stream ends early or its checksum fails.
        for keep in [0, 1, 10, fragment.len() / 2, fragment.len() - 8, fragment.len() - 1] {
            let cut = format!(
                "{head}#{}",
                &fragment[..("files=".len() + keep).min(fragment.len() - 1)]
            );
            let why = damaged(Link::parse(&cut));
            assert!(!why.is_empty(), "{keep}");
        }
        // One character changed, anywhere: zlib's checksum (or the stream) catches it.
        let body = &fragment["files=".len()..];
        for at in [0, body.len() / 3, body.len() / 2, body.len() - 2] {
            let c = body.as_bytes()[at];
            let other = if c == b'A' { 'B' } else { 'A' };
            let changed = format!("{head}#files={}{other}{}", &body[..at], &body[at + 1..]);
            damaged(Link::parse(&changed));
        }
        let message = LinkError::Damaged("x".into()).to_string();
        assert!(message.contains("cut short or damaged") && message.contains("copy the whole link again"));
        assert!(damaged(Link::parse(&format!("{head}#files=abc$def"))).contains("`$` at character 4 is not base64url"));
        assert!(damaged(Link::parse(&format!("{head}#top"))).contains("is `top`, not shaderlab's `files=…`"));
        assert!(damaged(Link::parse(&format!("{head}#{}", fragment_of(b"[1,2]")))).contains("no format 1"));
        assert!(damaged(Link::parse(&format!("{head}#{}", fragment_of(b"{\"v\":1}")))).contains("no `files` object"));
        assert!(damaged(Link::parse(&format!(
            "{head}#{}",
            fragment_of(br#"{"v":1,"files":{"a.glsl":3}}"#)
        )))
        .contains("not a string"));
        assert!(damaged(Link::parse("?lab=phong&set=Ka%3")).contains("not a percent escape"));
        assert!(damaged(Link::parse("?lab=ph%FFong")).contains("not UTF-8"));
        assert_eq!(
            Link::parse(&format!("{head}#{}", fragment_of(br#"{"v":2,"files":{}}"#))),
            Err(LinkError::Newer(2))
        );
    }

    #[test]
    fn links_past_the_limits_are_refused_before_they_are_read() {
        // A fragment longer than a link carries.
        let long = format!("?lab=phong#files={}", "A".repeat(MAX_FRAGMENT + 1));
        assert_eq!(Link::parse(&long), Err(LinkError::TooLong { len: MAX_FRAGMENT + 1 }));
        // A zip bomb: 16 MiB of one byte, compressed into a link's length, stops at the cap.
        let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::best());
        let zeros = vec![b' '; 1 << 20];
        for _ in 0..16 {
            z.write_all(&zeros).unwrap();
        }
        let bomb = base64::engine::general_purpose::URL_SAFE_NO_PAD.encode(z.finish().unwrap());
        assert!(bomb.len() <= MAX_FRAGMENT, "{} characters", bomb.len());
        assert_eq!(
            Link::parse(&format!("?lab=phong#files={bomb}")),
            Err(LinkError::TooLarge)
        );
        assert!(LinkError::TooLarge.to_string().contains("more than 1048576 bytes"));
        // Making one: text that does not compress into 32 KiB, or past 1 MiB.
        let mut state = 1u64;
        let noise: String = (0..40_000)
            .map(|_| {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                char::from(b'!' + (state >> 58) as u8)
            })
            .collect();
        let big = link_with([("phong.frag".to_owned(), noise)].into());
        match big.to_url() {
            Err(e @ LinkError::TooBig { len, .. }) => {
                assert!(len > MAX_FRAGMENT, "{len}");
                let text = e.to_string();
                assert!(
                    text.contains("phong.frag") && text.contains("more than a link carries"),
                    "{text}"
                );
            }
            other => panic!("{other:?}"),
        }
        let huge = link_with([("phong.frag".to_owned(), " ".repeat(MAX_FILES_BYTES))].into());
        assert!(matches!(huge.to_url(), Err(LinkError::TooBig { len: 0, .. })));
    }

    #[test]
    fn a_link_for_no_lab_or_with_a_parameter_the_lab_lacks_is_refused() {
        assert_eq!(
            Link::parse("?set=Ka%3D1").unwrap().check(&|_| false).err(),
            Some(LinkError::NoLab)
        );
        let e = Link::parse("?lab=nosuch").unwrap().check(&|_| false).unwrap_err();
        assert!(matches!(e, LinkError::UnknownLab { .. }));
        assert!(
            e.to_string()
                .starts_with("the link names no lab called `nosuch`; the labs are: "),
            "{e}"
        );
        for (set, says) in [
            (
                "nosuch=1",
                "the link's `set=nosuch=1`: unknown parameter `nosuch` for phong; valid: ",
            ),
            ("Ka=abc", "the link's `set=Ka=abc`: "),
            ("Ka", "the link's `set=Ka`: expected NAME=VALUE"),
            ("files=a.vert,b.frag", "unknown parameter `files` for phong"),
        ] {
            let link = Link::parse(&format!("?lab=phong&set={}", escape(set))).unwrap();
            link.check(&|_| false).unwrap();
            let e = link.check_sets(&mut (phong().params)()).unwrap_err();
            assert!(e.to_string().contains(says), "{set}: {e}");
        }
    }

    #[test]
    fn a_file_name_the_lab_could_not_read_is_refused() {
        let phong_names = [
            ("sub/phong.frag", "the name has a folder"),
            ("..\\phong.frag", "`..` climbs out of the folder"),
            ("../phong.frag", "`..` climbs out of the folder"),
            ("..", "`..` climbs out of the folder"),
            ("/etc/phong.frag", "an absolute path"),
            ("\\phong.frag", "an absolute path"),
            ("C:phong.frag", "an absolute path"),
            ("", "an empty name"),
            (".hidden.glsl", "not a plain file name"),
            ("a\nb.glsl", "not a plain file name"),
            ("notes.txt", "not a shader file phong could read"),
            ("phong.frag.bak", "not a shader file phong could read"),
            ("mine.vert", "not a shader file phong could read"),
        ];
        for (name, says) in phong_names {
            let link = Link {
                files: [(name.to_owned(), "x".to_owned())].into(),
                ..Link::new(DEFAULT_BASE, "phong")
            };
            let url = link.to_url().unwrap();
            let e = Link::parse(&url).unwrap().check(&|_| false).unwrap_err();
            assert!(matches!(e, LinkError::Name { .. }), "{name}: {e:?}");
            assert!(e.to_string().contains(says), "{name}: {e}");
        }
        let long = format!("{}.glsl", "a".repeat(300));
        assert!(check_name(phong(), &long)
            .unwrap_err()
            .to_string()
            .contains("305 bytes"));
        for ok in ["phong.frag", "noise.glsl", "mine.glsl"] {
            check_name(phong(), ok).unwrap();
        }
        for (name, says) in [
            ("V", "not the name of a shader file legacy reads"),
            ("a,b.vert", "without a comma"),
        ] {
            let e = check_name(legacy(), name).unwrap_err();
            assert!(e.to_string().contains(says), "{name}: {e}");
        }
        for ok in ["lab3.vert", "mine.fs", "x.GLSL"] {
            check_name(legacy(), ok).unwrap();
        }
    }

    #[test]
    fn legacys_pair_is_carried_whole_and_alone() {
        let pair: BTreeMap<String, String> = [
            ("a.vert".to_owned(), "v".to_owned()),
            ("b.frag".to_owned(), "f".to_owned()),
        ]
        .into();
        let mut link = Link::new(DEFAULT_BASE, "legacy");
        link.files = pair.clone();
        let e = link.check(&|_| false).unwrap_err();
        assert!(e.to_string().contains("names no pair for legacy to draw"), "{e}");
        link.set_pair("a.vert", "b.frag");
        link.push_set("xangle=30");
        let back = Link::parse(&link.to_url().unwrap()).unwrap();
        assert_eq!(back.pair(), Some("a.vert,b.frag"));
        assert_eq!(back.sets(), vec!["files=a.vert,b.frag", "xangle=30"]);
        back.check(&|_| false).unwrap();
        // A pair whose text is missing, unless the page has the file already.
        let mut half = back.clone();
        half.files.remove("b.frag");
        let e = half.check(&|_| false).unwrap_err();
        assert!(e.to_string().contains("carries no text for `b.frag`"), "{e}");
        half.check(&|n| n == "b.frag").unwrap();
        // A file it does not draw.
        let mut extra = back.clone();
        extra.files.insert("c.frag".into(), "x".into());
        let e = extra.check(&|_| false).unwrap_err();
        assert!(
            e.to_string().contains("carries `c.frag`, which legacy does not draw"),
            "{e}"
        );
        let mut three = back.clone();
        three.set_pair("a.vert", "b.frag,c.frag");
        let e = three.check(&|_| true).unwrap_err();
        assert!(e.to_string().contains("takes two files"), "{e}");
    }

    #[test]
    fn the_page_carries_what_differs_from_the_built_in_text() {
        let base = "http://h/index.html?lab=phong&set=Ka%3D0.2#files=stale";
        let mut texts = edited();
        texts.insert(
            "phong.vert".into(),
            crate::shader::embedded_source("phong.vert").unwrap().into(),
        );
        texts.insert("lab3.vert".into(), "a course file".into());
        texts.insert("tint.glsl".into(), "// handed over".into());
        let link = Link::parse(&page_link(base, phong(), &texts, &[]).unwrap()).unwrap();
        assert_eq!(link.base, "http://h/index.html");
        assert_eq!(link.files.keys().collect::<Vec<_>>(), ["phong.frag", "tint.glsl"]);
        assert_eq!(link.files["phong.frag"], edited()["phong.frag"]);
        // Legacy: the pair drawn, edited or not; the built-in pair once edited, by plain names.
        let legacy_url = "http://h/?lab=legacy&set=files%3Dlab3.vert%2Clab3.frag&set=xangle%3D30";
        texts.insert("lab3.frag".into(), "another".into());
        let pair = ["lab3.vert".to_owned(), "lab3.frag".to_owned()];
        let link = Link::parse(&page_link(legacy_url, legacy(), &texts, &pair).unwrap()).unwrap();
        assert_eq!(link.files.keys().collect::<Vec<_>>(), ["lab3.frag", "lab3.vert"]);
        link.check(&|_| false).unwrap();
        let plain = "http://h/?lab=legacy&set=xangle%3D30";
        let link = Link::parse(&page_link(plain, legacy(), &texts, &[]).unwrap()).unwrap();
        assert!(link.files.is_empty(), "the built-in pair, unedited, needs no files");
        texts.insert("legacy/default.frag".into(), "edited".into());
        let link = Link::parse(&page_link(plain, legacy(), &texts, &[]).unwrap()).unwrap();
        assert_eq!(link.sets(), vec!["files=default.vert,default.frag", "xangle=30"]);
        assert_eq!(link.files["default.frag"], "edited");
        assert_eq!(link.files["default.vert"], crate::course::legacy::DEFAULT_VERT);
        link.check(&|_| false).unwrap();
    }
}
