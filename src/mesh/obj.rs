//! Wavefront OBJ models the way seed 004's `load_obj` reads them (SPEC §4.0).
//!
//! Every triangle corner becomes one [`ObjCorner`] — the course's 9-float VBO record
//! v.xyzw (w = 1), vt.uv, vn.xyz — in file order (Suzanne: 967 triangles, 2901 corners).
//! Polygons with more than three corners are split as a fan (0,1,2), (0,2,3), ….
//!
//! Every line is checked as it is read, so that each malformed file is reported as
//! `file:line: message`: `v`/`vt`/`vn` fields must be finite numbers (`v`: 3 coordinates,
//! optionally a w or an r g b colour, both ignored; `vt`: u v, optionally w; `vn`: x y z); `f`
//! needs at least 3 corners `v`, `v/vt`, `v//vn` or `v/vt/vn`, each index a non-zero integer
//! naming an element defined above it (negative = relative to the last one). Point and line
//! elements (`p`, `l`) are not drawn (a notice says so); objects, groups, materials, smoothing
//! groups and unknown keywords are ignored.
//!
//! Read by hand in one pass, not with `tobj`: the checks above need every line read anyway, and
//! reading the text twice (checked here, then parsed again by tobj and matched back) takes twice
//! the time and memory (figures: `docs/speed.md`, "Large meshes, models and pictures").

use crate::error::{Error, Result};
use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use std::path::Path;

/// One triangle corner, the course's interleaved VBO record: 9 floats, 36 bytes
/// (offsets 0, 16, 24).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ObjCorner {
    /// `v` x, y, z and w = 1.
    pub position: [f32; 4],
    /// `vt` u, v ((0, 0) when the corner has no `vt`).
    pub uv: [f32; 2],
    /// `vn` x, y, z as written in the file (or a computed normal, see [`ObjModel`]).
    pub normal: [f32; 3],
}

/// A loaded model: the triangle corners twice, with face and with vertex normals.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ObjModel {
    /// Every triangle corner in file order, with the file's `vn` as its normal (Blender's flat
    /// export: one normal per face). A corner without `vn` gets its face's normal
    /// normalize((b − a) × (c − a)) from the face's first three positions.
    pub corners: Vec<ObjCorner>,
    /// The same corners with vertex normals (SPEC §4.0 "Smooth Suzanne"): for each `v` index,
    /// the f32 sum, in file order, of the unit normals of the faces using it, normalized (an
    /// unweighted average; zero if the faces cancel). A face's unit normal is its corners' `vn`
    /// normalized (if they differ: the normalized sum of their normalized `vn`), or the
    /// cross-product normal above when some corner has no `vn`. Each face counts once per `v`.
    pub smooth: Vec<ObjCorner>,
    /// One-line remarks about what was filled in or ignored (missing `vt`/`vn`, `w`, points and
    /// lines), for the caller to print.
    pub notices: Vec<String>,
}

impl ObjModel {
    /// Number of triangles (`corners.len() / 3`).
    pub fn triangle_count(&self) -> usize {
        self.corners.len() / 3
    }
}

/// The Suzanne of SPEC §4.0, shipped with the crate (`assets/suzanne.obj`, Blender 5.0.1's
/// export following the course's steps).
pub const SUZANNE_OBJ: &str = include_str!("../../assets/suzanne.obj");

/// The largest OBJ file read (256 MiB, some 5 million triangles); the course's Suzanne is 60 KiB.
pub const MAX_OBJ_BYTES: u64 = 256 << 20;

/// The memory an OBJ file takes to read and parse, per byte of the file, at the most (its text,
/// the positions and the corners, with the spare room of growing lists); the measured peak
/// stays under it (figures: `docs/speed.md`, "Large meshes, models and pictures").
const OBJ_MEMORY_PER_BYTE: u64 = 16;

/// Reads and parses an OBJ file: a regular file of at most [`MAX_OBJ_BYTES`]
/// ([`crate::fsutil::read_user_file`]), in UTF-8. Errors name the file: [`Error::Io`] if it
/// cannot be read (missing, unreadable, not a regular file, too large, not UTF-8),
/// [`Error::Obj`] for its content.
pub fn load_obj(path: &Path) -> Result<ObjModel> {
    if let Ok(meta) = std::fs::metadata(path) {
        crate::memory::check(
            &format!("reading {}", path.display()),
            meta.len().min(MAX_OBJ_BYTES) * OBJ_MEMORY_PER_BYTE,
        )?;
    }
    let bytes = crate::fsutil::read_user_file(path, MAX_OBJ_BYTES, "OBJ models")?;
    let text = String::from_utf8(bytes).map_err(|e| Error::Io {
        path: path.to_path_buf(),
        source: std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "not UTF-8 text (invalid byte at offset {}); an OBJ model is a text file",
                e.utf8_error().valid_up_to()
            ),
        ),
    })?;
    parse(path, &text)
}

/// Parses OBJ text; `name` is the file name used in errors and notices.
pub fn parse_obj(name: &str, text: &str) -> Result<ObjModel> {
    parse(Path::new(name), text)
}

/// The shipped Suzanne ([`SUZANNE_OBJ`]): 507 `v`, 967 triangles, 2901 corners.
pub fn suzanne() -> ObjModel {
    // The text is compiled in and checked by the tests; it cannot fail at run time.
    parse_obj("assets/suzanne.obj", SUZANNE_OBJ).expect("the shipped suzanne.obj parses")
}

/// A face corner as the file gives it: 0-based indices into the whole file's `v`, `vt`, `vn`.
#[derive(Clone, Copy, Debug)]
struct Corner {
    v: usize,
    vt: Option<usize>,
    vn: Option<usize>,
}

fn obj_error(path: &Path, line: Option<usize>, message: impl Into<String>) -> Error {
    Error::Obj {
        path: path.to_path_buf(),
        line,
        message: message.into(),
    }
}

fn parse_number(path: &Path, line: usize, keyword: &str, field: &str) -> Result<f32> {
    match field.parse::<f32>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(obj_error(
            path,
            Some(line),
            format!("`{keyword}`: field `{field}` is not a finite number"),
        )),
        Err(_) => Err(obj_error(
            path,
            Some(line),
            format!("`{keyword}`: field `{field}` is not a number"),
        )),
    }
}

/// Resolves one index of a face corner (`what` = "v", "vt" or "vn") against `count` elements.
fn resolve_index(path: &Path, line: usize, corner: &str, what: &str, text: &str, count: usize) -> Result<usize> {
    let bad = |message: String| obj_error(path, Some(line), format!("face corner `{corner}`: {message}"));
    let digits = text.strip_prefix('-').unwrap_or(text);
    let k: i64 = text.parse().map_err(|_| {
        if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) {
            // A whole number too long for any index.
            bad(format!(
                "{what} index {text} is out of range ({count} {what} defined so far)"
            ))
        } else {
            bad(format!("{what} index `{text}` is not an integer"))
        }
    })?;
    let resolved = if k > 0 {
        usize::try_from(k - 1).ok().filter(|&i| i < count)
    } else if k < 0 {
        usize::try_from(k.unsigned_abs())
            .ok()
            .and_then(|back| count.checked_sub(back))
    } else {
        return Err(bad(format!("{what} index 0 (OBJ indices start at 1)")));
    };
    resolved.ok_or_else(|| {
        bad(format!(
            "{what} index {k} is out of range ({count} {what} defined so far)"
        ))
    })
}

fn parse_corner(path: &Path, line: usize, corner: &str, counts: [usize; 3]) -> Result<Corner> {
    let mut parts = corner.split('/');
    let (v, vt, vn) = (parts.next().unwrap_or(""), parts.next(), parts.next());
    if parts.next().is_some() {
        return Err(obj_error(
            path,
            Some(line),
            format!("face corner `{corner}` has more than v/vt/vn"),
        ));
    }
    if v.is_empty() {
        return Err(obj_error(
            path,
            Some(line),
            format!("face corner `{corner}` has no v index"),
        ));
    }
    let v = resolve_index(path, line, corner, "v", v, counts[0])?;
    let optional = |text: Option<&str>, k: usize, what: &str| -> Result<Option<usize>> {
        match text {
            Some(text) if !text.is_empty() => resolve_index(path, line, corner, what, text, counts[k]).map(Some),
            _ => Ok(None),
        }
    };
    Ok(Corner {
        v,
        vt: optional(vt, 1, "vt")?,
        vn: optional(vn, 2, "vn")?,
    })
}

/// The file's elements as read: every `v`, `vt` and `vn`, and the faces' corners (one flat
/// list; `faces` holds where each face's corners start).
#[derive(Default)]
struct Elements {
    positions: Vec<Vec3>,
    uvs: Vec<[f32; 2]>,
    normals: Vec<Vec3>,
    corners: Vec<Corner>,
    faces: Vec<usize>,
    notices: Vec<String>,
}

/// The fields of a `v`/`vt`/`vn` line as numbers, `count` of them allowed.
fn numbers<const N: usize>(path: &Path, line: usize, keyword: &str, fields: &[&str]) -> Result<[f32; N]> {
    let mut out = [0.0; N];
    for (o, f) in out.iter_mut().zip(fields) {
        *o = parse_number(path, line, keyword, f)?;
    }
    Ok(out)
}

/// Reads every line in one pass, checking it as it goes.
fn read(path: &Path, text: &str) -> Result<Elements> {
    let mut e = Elements::default();
    let mut anything = false;
    let (mut w_ignored, mut points, mut lines) = (0usize, 0usize, 0usize);
    let mut fields: Vec<&str> = Vec::with_capacity(8);
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        let mut words = raw.split_whitespace();
        let Some(keyword) = words.next() else { continue };
        if keyword.starts_with('#') {
            continue;
        }
        anything = true;
        fields.clear();
        fields.extend(words);
        match keyword {
            "v" => {
                if ![3, 4, 6].contains(&fields.len()) {
                    let message = format!(
                        "`v` needs x y z (optionally w, or r g b), found {} field(s)",
                        fields.len()
                    );
                    return Err(obj_error(path, Some(line), message));
                }
                let xyz: [f32; 3] = numbers(path, line, "v", &fields)?;
                for f in &fields[3..] {
                    let extra = parse_number(path, line, "v", f)?;
                    if fields.len() == 4 && extra != 1.0 {
                        w_ignored += 1;
                    }
                }
                e.positions.push(Vec3::from_array(xyz));
            }
            "vt" => {
                if !(2..=3).contains(&fields.len()) {
                    let message = format!("`vt` needs u v (optionally w), found {} field(s)", fields.len());
                    return Err(obj_error(path, Some(line), message));
                }
                let uv: [f32; 2] = numbers(path, line, "vt", &fields)?;
                if let Some(w) = fields.get(2) {
                    parse_number(path, line, "vt", w)?;
                }
                e.uvs.push(uv);
            }
            "vn" => {
                if fields.len() != 3 {
                    let message = format!("`vn` needs x y z, found {} field(s)", fields.len());
                    return Err(obj_error(path, Some(line), message));
                }
                e.normals.push(Vec3::from_array(numbers(path, line, "vn", &fields)?));
            }
            "f" => {
                if fields.len() < 3 {
                    let message = format!("face with {} corner(s); a face needs at least 3", fields.len());
                    return Err(obj_error(path, Some(line), message));
                }
                let counts = [e.positions.len(), e.uvs.len(), e.normals.len()];
                e.faces.push(e.corners.len());
                for c in &fields {
                    e.corners.push(parse_corner(path, line, c, counts)?);
                }
            }
            "p" => points += 1,
            "l" => lines += 1,
            // Objects and groups, materials, smoothing groups, unknown keywords: ignored.
            _ => {}
        }
    }
    let name = path.display();
    if !anything {
        return Err(obj_error(path, None, "empty file (no OBJ statements)"));
    }
    if e.faces.is_empty() {
        return Err(obj_error(path, None, "no faces (`f` lines): nothing to draw"));
    }
    if w_ignored > 0 {
        e.notices.push(format!(
            "{name}: {w_ignored} `v` line(s) with w ≠ 1: w ignored (positions get w = 1)"
        ));
    }
    if points + lines > 0 {
        e.notices.push(format!(
            "{name}: {points} point and {lines} line element(s) ignored (only faces are drawn)"
        ));
    }
    Ok(e)
}

fn parse(path: &Path, text: &str) -> Result<ObjModel> {
    let e = read(path, text)?;
    let triangles: usize = (0..e.faces.len()).map(|f| face_corners(&e, f).len() - 2).sum();
    let mut corners = Vec::with_capacity(triangles * 3);
    let mut keys = Vec::with_capacity(triangles * 3); // the `v` index of every corner
    let mut vertex_sums = vec![Vec3::ZERO; e.positions.len()];
    let (mut no_uv, mut no_normal) = (0usize, 0usize);
    let mut seen: Vec<usize> = Vec::new();
    for f in 0..e.faces.len() {
        let face = face_corners(&e, f);
        // Face normal from positions: the first triangle (corners 0, 1, 2).
        let (a, b, c) = (e.positions[face[0].v], e.positions[face[1].v], e.positions[face[2].v]);
        let geometric = (b - a).cross(c - a).normalize_or_zero();
        // The fan (0, k, k+1) for k = 1 .. n-2, corner by corner (a quad's first corner
        // counts twice in the sum of differing normals, as it is drawn twice).
        let fan = (1..face.len() - 1).flat_map(|k| [face[0], face[k], face[k + 1]]);
        let file_normals: Option<Vec<Vec3>> = fan.map(|c| c.vn.map(|i| e.normals[i])).collect();
        let face_normal = match file_normals {
            Some(ns) if ns.iter().all(|n| *n == ns[0]) => ns[0].normalize_or_zero(),
            Some(ns) => ns
                .iter()
                .map(|n| n.normalize_or_zero())
                .fold(Vec3::ZERO, |s, n| s + n)
                .normalize_or_zero(),
            None => geometric,
        };
        seen.clear();
        for corner in face {
            if !seen.contains(&corner.v) {
                seen.push(corner.v);
                vertex_sums[corner.v] += face_normal;
            }
        }
        for k in 1..face.len() - 1 {
            for c in [face[0], face[k], face[k + 1]] {
                no_uv += usize::from(c.vt.is_none());
                no_normal += usize::from(c.vn.is_none());
                let p = e.positions[c.v];
                corners.push(ObjCorner {
                    position: [p.x, p.y, p.z, 1.0],
                    uv: c.vt.map_or([0.0, 0.0], |i| e.uvs[i]),
                    normal: c.vn.map_or(geometric, |i| e.normals[i]).to_array(),
                });
                keys.push(c.v);
            }
        }
    }
    let vertex_normals: Vec<Vec3> = vertex_sums.iter().map(|n| n.normalize_or_zero()).collect();
    let smooth = corners
        .iter()
        .zip(&keys)
        .map(|(c, &v)| ObjCorner {
            normal: vertex_normals[v].to_array(),
            ..*c
        })
        .collect();

    let name = path.display();
    let mut notices = e.notices;
    if no_uv > 0 {
        notices.push(format!(
            "{name}: {no_uv} of {} corners have no `vt`: uv (0, 0) used",
            corners.len()
        ));
    }
    if no_normal > 0 {
        notices.push(format!(
            "{name}: {no_normal} of {} corners have no `vn`: face normals computed from the positions",
            corners.len()
        ));
    }
    Ok(ObjModel {
        corners,
        smooth,
        notices,
    })
}

/// The corners of face `f`.
fn face_corners(e: &Elements, f: usize) -> &[Corner] {
    let end = e.faces.get(f + 1).copied().unwrap_or(e.corners.len());
    &e.corners[e.faces[f]..end]
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn err(text: &str) -> (Option<usize>, String) {
        match parse_obj("t.obj", text) {
            Err(Error::Obj { path, line, message }) => {
                assert_eq!(path, PathBuf::from("t.obj"));
                let shown = Error::Obj {
                    path,
                    line,
                    message: message.clone(),
                }
                .to_string();
                match line {
                    Some(l) => assert!(shown.starts_with(&format!("t.obj:{l}: ")), "{shown}"),
                    None => assert!(shown.starts_with("t.obj: "), "{shown}"),
                }
                (line, message)
            }
            other => panic!("expected an OBJ error for {text:?}, got {other:?}"),
        }
    }

    const TRI: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

    #[test]
    fn corner_layout_is_nine_floats() {
        assert_eq!(std::mem::size_of::<ObjCorner>(), 36);
        let c = ObjCorner {
            position: [1.0, 2.0, 3.0, 1.0],
            uv: [4.0, 5.0],
            normal: [6.0, 7.0, 8.0],
        };
        let floats: &[f32] = bytemuck::cast_slice(std::slice::from_ref(&c));
        assert_eq!(floats, &[1.0, 2.0, 3.0, 1.0, 4.0, 5.0, 6.0, 7.0, 8.0]);
    }

    #[test]
    fn suzanne_counts_and_values() {
        assert_eq!(SUZANNE_OBJ.lines().filter(|l| l.starts_with("v ")).count(), 507);
        let m = suzanne();
        assert_eq!(m.corners.len(), 2901);
        assert_eq!(m.smooth.len(), 2901);
        assert_eq!(m.triangle_count(), 967);
        assert!(m.notices.is_empty(), "{:?}", m.notices);
        // Every corner has w = 1; uv and normal come from the file.
        assert!(m.corners.iter().all(|c| c.position[3] == 1.0));
        // The first face's corners hold exactly the values its indices name.
        let first_face = SUZANNE_OBJ.lines().find(|l| l.starts_with("f ")).unwrap();
        let v: Vec<&str> = SUZANNE_OBJ.lines().filter(|l| l.starts_with("v ")).collect();
        let vt: Vec<&str> = SUZANNE_OBJ.lines().filter(|l| l.starts_with("vt ")).collect();
        let vn: Vec<&str> = SUZANNE_OBJ.lines().filter(|l| l.starts_with("vn ")).collect();
        let floats = |line: &str| -> Vec<f32> { line.split_whitespace().skip(1).map(|f| f.parse().unwrap()).collect() };
        for (k, corner) in first_face.split_whitespace().skip(1).enumerate() {
            let idx: Vec<usize> = corner.split('/').map(|i| i.parse().unwrap()).collect();
            let c = m.corners[k];
            assert_eq!(c.position[..3], floats(v[idx[0] - 1])[..], "corner {k}");
            assert_eq!(c.uv[..], floats(vt[idx[1] - 1])[..], "corner {k}");
            assert_eq!(c.normal[..], floats(vn[idx[2] - 1])[..], "corner {k}");
            assert_eq!(m.smooth[k].position, c.position);
            assert_eq!(m.smooth[k].uv, c.uv);
        }
    }

    #[test]
    fn suzanne_smooth_normals() {
        let m = suzanne();
        let (mut differing, mut opposed) = (0, 0);
        for (flat, smooth) in m.corners.iter().zip(&m.smooth) {
            let n = Vec3::from_array(smooth.normal);
            assert!((n.length() - 1.0).abs() < 1e-5, "{n}");
            opposed += usize::from(n.dot(Vec3::from_array(flat.normal)) <= 0.0);
            if (n - Vec3::from_array(flat.normal).normalize()).length() > 1e-3 {
                differing += 1;
            }
        }
        assert!(differing > 2800, "{differing}");
        // An unweighted average can point away from a face only at sharp creases (eye rims,
        // ear edges): a few corners, not a side of the model.
        assert!(opposed > 0 && opposed < 40, "{opposed}");
        // Corners sharing a `v` index share the vertex normal (Suzanne has coincident but
        // distinct `v`s, which keep their own).
        let v_indices = SUZANNE_OBJ.lines().filter(|l| l.starts_with("f ")).flat_map(|l| {
            l.split_whitespace()
                .skip(1)
                .map(|c| c.split('/').next().unwrap().parse::<usize>().unwrap())
        });
        let mut by_v = std::collections::HashMap::new();
        for (c, v) in m.smooth.iter().zip(v_indices) {
            assert_eq!(*by_v.entry(v).or_insert(c.normal), c.normal, "v {v}");
        }
        assert_eq!(by_v.len(), 507);
    }

    #[test]
    fn smooth_normal_is_unweighted_average() {
        // Two faces sharing v1 and v3, their file normals at a right angle (one not unit length).
        let text = "v 0 0 0\nv 0 0 1\nv 0 1 0\nv 0 2 2\nvn 1 0 0\nvn 0 0 3\n\
                    f 1//1 2//1 3//1\nf 1//2 3//2 4//2\n";
        let m = parse_obj("t.obj", text).unwrap();
        let flat: Vec<[f32; 3]> = m.corners.iter().map(|c| c.normal).collect();
        assert_eq!(
            flat,
            vec![[1.0, 0.0, 0.0]; 3]
                .into_iter()
                .chain(vec![[0.0, 0.0, 3.0]; 3])
                .collect::<Vec<_>>()
        );
        let h = std::f32::consts::FRAC_1_SQRT_2;
        let smooth: Vec<[f32; 3]> = m.smooth.iter().map(|c| c.normal).collect();
        // v1 and v3 are shared: (1,0,0) + (0,0,1) normalized; v2 only face 1, v4 only face 2.
        assert_eq!(
            smooth,
            vec![
                [h, 0.0, h],
                [1.0, 0.0, 0.0],
                [h, 0.0, h],
                [h, 0.0, h],
                [h, 0.0, h],
                [0.0, 0.0, 1.0]
            ]
        );
    }

    #[test]
    fn quad_is_triangulated_as_a_fan() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n\
                    f 1/1/1 2/2/1 3/3/1 4/4/1\n";
        let m = parse_obj("t.obj", text).unwrap();
        assert_eq!(m.triangle_count(), 2);
        let xy: Vec<[f32; 2]> = m.corners.iter().map(|c| [c.position[0], c.position[1]]).collect();
        assert_eq!(
            xy,
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
        );
        let uv: Vec<[f32; 2]> = m.corners.iter().map(|c| c.uv).collect();
        assert_eq!(uv, xy);
        assert!(m.smooth.iter().all(|c| c.normal == [0.0, 0.0, 1.0]));
        assert!(m.notices.is_empty());
        // A pentagon: three triangles (0,1,2), (0,2,3), (0,3,4).
        let penta = "v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nf 1 2 3 4 5\n";
        let m = parse_obj("p.obj", penta).unwrap();
        assert_eq!(m.triangle_count(), 3);
        assert_eq!(m.corners[6].position, [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(m.corners[8].position, [0.0, 1.0, 0.0, 1.0]);
    }

    #[test]
    fn missing_texcoords_and_normals_are_filled_in() {
        let m = parse_obj("t.obj", &format!("{TRI}f 1 2 3\n")).unwrap();
        assert!(m
            .corners
            .iter()
            .all(|c| c.uv == [0.0, 0.0] && c.normal == [0.0, 0.0, 1.0]));
        assert!(m.smooth.iter().all(|c| c.normal == [0.0, 0.0, 1.0]));
        assert_eq!(m.notices.len(), 2, "{:?}", m.notices);
        assert!(
            m.notices[0].contains("no `vt`") && m.notices[1].contains("no `vn`"),
            "{:?}",
            m.notices
        );
        assert!(m.notices.iter().all(|n| n.starts_with("t.obj: ") && !n.contains('\n')));
        // Mixed: only the corner without vt gets (0,0), even though the file has texcoords
        // (tobj alone would repeat the previous corner's).
        let m = parse_obj("t.obj", &format!("{TRI}vt 0.5 0.25\nvn 0 0 -1\nf 1/1/1 2//1 3/1/1\n")).unwrap();
        let uv: Vec<[f32; 2]> = m.corners.iter().map(|c| c.uv).collect();
        assert_eq!(uv, vec![[0.5, 0.25], [0.0, 0.0], [0.5, 0.25]]);
        assert!(m.corners.iter().all(|c| c.normal == [0.0, 0.0, -1.0]));
        assert_eq!(m.notices.len(), 1);
        // Relative indices, comments, groups, w and ignored elements.
        let text = "# c\no a\nv 0 0 0 2\nv 1 0 0\nv 0 1 0\ns 1\nusemtl x\nl 1 2\ng b\nf -3 -2 -1\n";
        let m = parse_obj("t.obj", text).unwrap();
        assert_eq!(m.corners[0].position, [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(m.corners[1].position, [1.0, 0.0, 0.0, 1.0]);
        assert!(m.notices.iter().any(|n| n.contains("w ignored")), "{:?}", m.notices);
        assert!(
            m.notices.iter().any(|n| n.contains("1 line element")),
            "{:?}",
            m.notices
        );
    }

    #[test]
    fn several_objects_share_vertices() {
        // Vertex normals are per `v` index across objects.
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\no a\nf 1 2 3\no b\nf 1 3 4\n";
        let m = parse_obj("t.obj", text).unwrap();
        assert_eq!(m.triangle_count(), 2);
        assert_eq!(m.smooth[0].normal, m.smooth[3].normal);
        let h = std::f32::consts::FRAC_1_SQRT_2;
        assert_eq!(m.smooth[0].normal, [h, 0.0, h]);
    }

    #[test]
    fn error_cases_name_file_and_line() {
        assert_eq!(err("").0, None);
        assert!(err("   \n# only a comment\n\n").1.contains("empty"));
        let (line, message) = err(TRI);
        assert_eq!(line, None);
        assert!(message.contains("no faces"), "{message}");

        let cases: &[(&str, usize, &str)] = &[
            ("v 0 0 0\nv 1 x 0\n", 2, "not a number"),
            ("v 0 0\n", 1, "found 2 field"),
            ("v 0 0 nan\n", 1, "finite"),
            ("vt 0.5 y\n", 1, "not a number"),
            ("vn 0 0\n", 1, "found 2 field"),
            ("vn 1 2 three\n", 1, "not a number"),
            ("v 0 0 0\nv 1 0 0\nf 1 2\n", 3, "at least 3"),
            ("v 0 0 0\nf 1\n", 2, "at least 3"),
            ("f\n", 1, "at least 3"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", 4, "out of range"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 4, "index 0"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 -2 -1\n", 4, "out of range"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", 4, "not an integer"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3.5\n", 4, "not an integer"),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n",
                4,
                "v index 99999999999999999999 is out of range (3 v defined so far)",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n",
                4,
                "vt index 1 is out of range",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//2 2//1 3//1\n",
                4,
                "vn index 2 is out of range",
            ),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/// 2 3\n", 4, "more than"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf /1 2 3\n", 4, "no v index"),
            // An index must name an element defined above it.
            ("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", 1, "out of range"),
        ];
        for &(text, want_line, want) in cases {
            let (line, message) = err(text);
            assert_eq!(line, Some(want_line), "{text:?}: {message}");
            assert!(message.contains(want), "{text:?}: {message}");
        }
    }

    #[test]
    fn file_errors() {
        let dir = std::env::temp_dir().join(format!("shaderlab-obj-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let missing = dir.join("missing.obj");
        let e = load_obj(&missing).unwrap_err();
        assert!(
            matches!(e, Error::Io { .. }) && e.to_string().contains("missing.obj"),
            "{e}"
        );
        let empty = dir.join("empty.obj");
        std::fs::write(&empty, "").unwrap();
        let e = load_obj(&empty).unwrap_err();
        assert!(e.to_string().starts_with(&format!("{}: empty", empty.display())), "{e}");
        let binary = dir.join("binary.obj");
        std::fs::write(&binary, [0xff, 0xfe, 0x00, 0x80]).unwrap();
        let e = load_obj(&binary).unwrap_err();
        assert!(
            matches!(e, Error::Io { .. }) && e.to_string().contains("binary.obj"),
            "{e}"
        );
        let bad = dir.join("bad.obj");
        std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n").unwrap();
        let e = load_obj(&bad).unwrap_err();
        assert!(e.to_string().starts_with(&format!("{}:4: ", bad.display())), "{e}");
        let good = dir.join("good.obj");
        std::fs::write(&good, SUZANNE_OBJ).unwrap();
        assert_eq!(load_obj(&good).unwrap().corners, suzanne().corners);
        std::fs::remove_dir_all(&dir).ok();
    }
}
