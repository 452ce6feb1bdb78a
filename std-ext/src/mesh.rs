//! Loading triangle meshes from files.
//!
//! | format | feature (default on) | how |
//! |---|---|---|
//! | Wavefront OBJ | `obj` | the `tobj` crate, after a line-numbered check of every `v` and `f` line (faces of fewer than 3 vertices, bad or out-of-range indices, negative indices counted back) |
//! | STL, ASCII and binary | `stl` | the `stl_io` crate; a binary file's size must match its triangle count; a bad vertex is named by its line (ASCII) or the byte where it starts (binary) |
//! | PLY, ASCII and binary | `ply` | the `ply-rs` crate; its errors are reduced to one line (the line, or the byte where binary data ends); a bad vertex or face is named by its line (ASCII) or the byte where its record starts (binary, found from the header's types and the list lengths before it) |
//! | OFF, with the `[ST][C][N]OFF` variants (colours, normals, texture coordinates; per-face colours) | always | by hand (a small text format no maintained crate reads) |
//!
//! A file of a format whose feature is off is an error saying so.
//!
//! Polygons are triangulated as fans. Every error names the file and the
//! line (text) or byte offset (binary data) where one is known; indices are checked against the vertex count,
//! coordinates must be finite, and nothing is allocated from a count a header
//! claims before the data behind it has been read, so a hostile file gives an
//! error, not a panic or an out-of-memory abort.

use bvhkit::glam::Vec3;
use bvhkit::Triangle;
use std::fmt;
use std::path::{Path, PathBuf};

/// Why a mesh could not be loaded.
#[derive(Debug)]
pub struct MeshError {
    /// The file.
    pub path: PathBuf,
    /// What went wrong.
    pub reason: String,
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path.display(), self.reason)
    }
}

impl std::error::Error for MeshError {}

/// Loads every triangle of a mesh file (all objects of an OBJ file together);
/// a file with vertices but no faces gives no triangles, not an error.
pub fn load(path: &Path) -> Result<Vec<Triangle>, MeshError> {
    load_indexed(path).map(|m| m.triangles)
}

/// A loaded mesh: its triangles and, for each, the indices of its three
/// corners in the file's vertex list (what "two triangles share a vertex"
/// means for self-collision).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct IndexedMesh {
    /// The triangles, in file order (polygons fan-triangulated).
    pub triangles: Vec<Triangle>,
    /// Each triangle's corner indices. OBJ, PLY and OFF give the file's own
    /// (an OBJ file's objects numbered one after the other); STL has no
    /// vertex list, so its corners are numbered by position
    /// ([`weld`]: equal coordinates, one index).
    pub corners: Vec<[u32; 3]>,
}

/// Like [`load`], keeping each triangle's vertex indices.
pub fn load_indexed(path: &Path) -> Result<IndexedMesh, MeshError> {
    let fail = |reason: String| MeshError {
        path: path.to_path_buf(),
        reason,
    };
    let mesh = match path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .as_deref()
    {
        #[cfg(feature = "obj")]
        Some("obj") => load_obj(path, &fail)?,
        #[cfg(feature = "stl")]
        Some("stl") => {
            let triangles = load_stl(path, &fail)?;
            let corners = weld(&triangles);
            IndexedMesh { triangles, corners }
        }
        #[cfg(feature = "ply")]
        Some("ply") => load_ply(path, &fail)?,
        Some("off") => load_off(path, &fail)?,
        // A format compiled out is named as such, not as unknown.
        #[cfg(not(feature = "obj"))]
        Some("obj") => return Err(fail(left_out("obj"))),
        #[cfg(not(feature = "stl"))]
        Some("stl") => return Err(fail(left_out("stl"))),
        #[cfg(not(feature = "ply"))]
        Some("ply") => return Err(fail(left_out("ply"))),
        _ => {
            return Err(fail(
                "unsupported format (bvhkit reads .obj, .stl, .ply and .off)".into(),
            ))
        }
    };
    // A file with no faces is a valid, empty mesh: it builds the empty tree.
    debug_assert_eq!(mesh.triangles.len(), mesh.corners.len());
    Ok(mesh)
}

/// The error for a format whose feature this build left out.
#[cfg(not(all(feature = "obj", feature = "stl", feature = "ply")))]
fn left_out(format: &str) -> String {
    format!(".{format} files need bvhkit-std's `{format}` feature, which this build left out")
}

/// Corner indices by position: corners with the same coordinates (bit for
/// bit, `-0.0` and `0.0` alike) get the same index. For meshes without a
/// vertex list (STL, generated scenes).
pub fn weld(triangles: &[Triangle]) -> Vec<[u32; 3]> {
    let mut index = std::collections::HashMap::new();
    let key = |v: Vec3| (v + Vec3::ZERO).to_array().map(f32::to_bits);
    triangles
        .iter()
        .map(|t| {
            t.v.map(|v| {
                let next = index.len() as u32;
                *index.entry(key(v)).or_insert(next)
            })
        })
        .collect()
}

type Fail<'a> = &'a dyn Fn(String) -> MeshError;

/// A placement for a loaded mesh: scale about the origin, then rotate by
/// Euler angles (degrees, about x, then y, then z), then translate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// Uniform scale factor.
    pub scale: f32,
    /// Rotation angles in degrees about x, y and z, applied in that order.
    pub rotate_deg: Vec3,
    /// Translation.
    pub translate: Vec3,
}

impl Default for Placement {
    fn default() -> Self {
        Placement {
            scale: 1.0,
            rotate_deg: Vec3::ZERO,
            translate: Vec3::ZERO,
        }
    }
}

impl Placement {
    /// The placement as a rigid motion (rotation, then translation), for a
    /// tree that is moved rather than rebuilt; an error when it scales
    /// (a rigid motion cannot) or is not finite.
    pub fn rigid(&self) -> Result<bvhkit::Rigid, String> {
        if self.scale != 1.0 {
            return Err(format!(
                "scale {} needs mesh files: the built-in scene moves B's tree rigidly, \
                 without rebuilding it, and a rigid motion cannot scale",
                self.scale
            ));
        }
        if !(self.rotate_deg.is_finite() && self.translate.is_finite()) {
            return Err("rotation and translation must be finite".into());
        }
        let r = self.rotate_deg * (std::f32::consts::PI / 180.0);
        let q = bvhkit::glam::Quat::from_euler(bvhkit::glam::EulerRot::ZYX, r.z, r.y, r.x);
        bvhkit::Rigid::new(q, self.translate).map_err(|e| e.to_string())
    }

    /// The placed copy of `tris`; an error when a result is not finite (a
    /// huge scale or translation) or the scale is not positive.
    pub fn apply(&self, tris: &[Triangle]) -> Result<Vec<Triangle>, String> {
        if !(self.scale.is_finite() && self.scale > 0.0) {
            return Err(format!("scale {} must be finite and positive", self.scale));
        }
        if !(self.rotate_deg.is_finite() && self.translate.is_finite()) {
            return Err("rotation and translation must be finite".into());
        }
        let r = self.rotate_deg * (std::f32::consts::PI / 180.0);
        let q = bvhkit::glam::Quat::from_euler(bvhkit::glam::EulerRot::ZYX, r.z, r.y, r.x);
        tris.iter()
            .enumerate()
            .map(|(i, t)| {
                let v = t.v.map(|p| q * (p * self.scale) + self.translate);
                if v.iter().all(|p| p.is_finite()) {
                    Ok(Triangle { v })
                } else {
                    Err(format!("triangle {i} leaves the finite range when placed"))
                }
            })
            .collect()
    }
}

/// A vertex, checked to be finite and within the builders' range
/// ([`bvhkit::MAX_COORDINATE`]), so that the error names the file and the
/// place: `at()` says where ("line 4: vertex 1", "byte 96: vertex 0"),
/// computed only for an error.
fn finite(v: Vec3, at: impl Fn() -> String, fail: Fail<'_>) -> Result<Vec3, MeshError> {
    if !v.is_finite() {
        Err(fail(format!("{} has a non-finite coordinate", at())))
    } else if v.abs().max_element() > bvhkit::MAX_COORDINATE {
        Err(fail(format!(
            "{} has a coordinate beyond {:e}, the largest bvhkit accepts",
            at(),
            bvhkit::MAX_COORDINATE
        )))
    } else {
        Ok(v)
    }
}

/// The 1-based line of the `nth` (0-based) line of `text` whose first word
/// is `word` (an ASCII STL's `vertex` or `facet` lines).
#[cfg(feature = "stl")]
fn line_of_nth(text: &[u8], word: &[u8], nth: usize) -> Option<usize> {
    text.split(|&b| b == b'\n')
        .enumerate()
        .filter(|(_, l)| {
            let l = l.trim_ascii_start();
            l.starts_with(word) && l.get(word.len()).is_none_or(|b| b.is_ascii_whitespace())
        })
        .nth(nth)
        .map(|(n, _)| n + 1)
}

/// Fan-triangulates an indexed polygon, checking every index.
fn fan(
    poly: &[usize],
    vertices: &[Vec3],
    out: &mut IndexedMesh,
    fail: Fail<'_>,
    at: &dyn Fn() -> String,
) -> Result<(), MeshError> {
    if poly.len() < 3 {
        return Err(fail(format!("{}a face with {} vertices", at(), poly.len())));
    }
    let v = |i: usize| {
        vertices.get(i).copied().ok_or_else(|| {
            fail(format!(
                "{}vertex index {i} out of range ({} vertices)",
                at(),
                vertices.len()
            ))
        })
    };
    let first = v(poly[0])?;
    for w in poly[1..].windows(2) {
        out.triangles.push(Triangle::new(first, v(w[0])?, v(w[1])?));
        // In range of `vertices`, whose length came from a file's count.
        out.corners.push([poly[0], w[0], w[1]].map(|i| i as u32));
    }
    Ok(())
}

#[cfg(feature = "stl")]
fn load_stl(path: &Path, fail: Fail<'_>) -> Result<Vec<Triangle>, MeshError> {
    let bytes = std::fs::read(path).map_err(|e| fail(e.to_string()))?;
    // A binary STL is an 80-byte header, a u32 count and 50 bytes per
    // triangle. Check the size against the count before parsing, so a lying
    // count is an error; an ASCII file starts with "solid" and has no count.
    let ascii = bytes.starts_with(b"solid") && {
        let probe = &bytes[..bytes.len().min(512)];
        probe.windows(5).any(|w| w == b"facet") || bytes.len() < 84
    };
    if !ascii {
        if bytes.len() < 84 {
            return Err(fail(format!(
                "truncated binary STL ({} bytes, header needs 84)",
                bytes.len()
            )));
        }
        let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
        let want = 84 + 50 * count;
        if bytes.len() as u64 != want {
            return Err(fail(format!(
                "binary STL claims {count} triangles ({want} bytes) but has {} bytes",
                bytes.len()
            )));
        }
    }
    // Where triangle k's vertex j is: the byte of a binary record (84-byte
    // header, then per triangle a 12-byte normal and three 12-byte
    // vertices), the line of an ASCII file's (3k + j)th `vertex`.
    let at = |k: usize, j: usize| {
        if ascii {
            match line_of_nth(&bytes, b"vertex", 3 * k + j) {
                Some(n) => format!("line {n}: triangle {k} vertex {j}"),
                None => format!("triangle {k} vertex {j}"),
            }
        } else {
            format!(
                "byte {}: triangle {k} vertex {j}",
                84 + 50 * k + 12 + 12 * j
            )
        }
    };
    let facet = |k: usize| match line_of_nth(&bytes, b"facet", k) {
        Some(n) => format!("line {n}: triangle {k}"),
        None => format!("triangle {k}"),
    };
    let mut cursor = std::io::Cursor::new(&bytes);
    let reader = stl_io::create_stl_reader(&mut cursor)
        .map_err(|e| fail(format!("not a readable STL file: {e}")))?;
    let mut out = Vec::new();
    for (k, t) in reader.enumerate() {
        let t = t.map_err(|e| fail(format!("{}: {e}", facet(k))))?;
        let mut v = [Vec3::ZERO; 3];
        for (j, (slot, p)) in v.iter_mut().zip(t.vertices).enumerate() {
            *slot = finite(Vec3::from_array(p.into()), || at(k, j), fail)?;
        }
        out.push(Triangle::new(v[0], v[1], v[2]));
    }
    Ok(out)
}

/// A one-line reason for a ply-rs error, whose text carries the parser's
/// debug output ("Line 12: Couln't read element line.\n\tString: '...'\n\t
/// Error: Custom { .. }"): the line and the text found, or for binary data
/// the byte where it ended.
#[cfg(feature = "ply")]
fn ply_error(text: &str, size: u64) -> String {
    let first = text.lines().next().unwrap_or("").trim();
    if let Some(rest) = first.strip_prefix("Line ") {
        let n = rest.split(':').next().unwrap_or("?");
        let found = text
            .split("String: '")
            .nth(1)
            .and_then(|s| s.split('\'').next())
            .map(str::trim)
            .unwrap_or("");
        return if !first.contains("element line") {
            format!("not a PLY file, or a malformed header: line {n}: '{found}'")
        } else if found.is_empty() {
            format!("line {n}: the file ends before every element the header announces")
        } else {
            format!("line {n}: '{found}' does not match the properties the header declares")
        };
    }
    if first.contains("fill whole buffer") {
        return format!(
            "the binary data ends at byte {size}, before every element the header announces"
        );
    }
    format!("not a readable PLY file: {first}")
}

/// What ply-rs does not check in a header before acting on it: a number too
/// long for 64 bits (it panicked; found by fuzzing), and element counts
/// that the bytes after the header cannot hold (each element takes at least
/// one byte), which would have it read or reserve for data that is not there.
#[cfg(feature = "ply")]
fn check_ply_header(bytes: &[u8], fail: Fail<'_>) -> Result<(), MeshError> {
    let mut offset = 0usize;
    let mut announced: Vec<(usize, String, u64)> = Vec::new();
    for (n, line) in bytes.split(|&b| b == b'\n').enumerate() {
        offset += line.len() + 1;
        let text = String::from_utf8_lossy(line);
        let text = text.trim();
        // Every run of digits, even inside a word: ply-rs's grammar converts
        // the digits it meets before it knows whether the line parses.
        for run in text.split(|c: char| !c.is_ascii_digit()) {
            if !run.is_empty() && run.parse::<u64>().is_err() {
                return Err(fail(format!(
                    "line {}: the number {run} is too large for a PLY header",
                    n + 1
                )));
            }
        }
        if let Some(rest) = text.strip_prefix("element") {
            let words: Vec<&str> = rest.split_whitespace().collect();
            if let [name, count] = words[..] {
                if let Ok(count) = count.parse::<u64>() {
                    announced.push((n + 1, name.to_string(), count));
                }
            }
        }
        if text == "end_header" {
            let data = bytes.len().saturating_sub(offset) as u64;
            let mut total = 0u64;
            for (line, name, count) in &announced {
                total = total.saturating_add(*count);
                if total > data {
                    return Err(fail(format!(
                        "line {line}: the header announces {count} '{name}' elements, more than \
                         the {data} bytes after the header can hold"
                    )));
                }
            }
            break;
        }
    }
    Ok(())
}

/// Where a PLY record is, for an error: the line of an ASCII record (one
/// per line after the header), the byte offset of a binary one, walked from
/// the header's property types with each list's length read from the data.
#[cfg(feature = "ply")]
struct PlyPlaces<'a> {
    bytes: &'a [u8],
    header: &'a ply_rs::ply::Header,
    /// Byte after the `end_header` line.
    data_start: usize,
    /// Lines up to and including `end_header`.
    header_lines: usize,
}

#[cfg(feature = "ply")]
impl<'a> PlyPlaces<'a> {
    fn new(bytes: &'a [u8], header: &'a ply_rs::ply::Header) -> Self {
        let (mut data_start, mut header_lines) = (0, 0);
        for line in bytes.split(|&b| b == b'\n') {
            data_start += line.len() + 1;
            header_lines += 1;
            if line.trim_ascii() == b"end_header" {
                break;
            }
        }
        PlyPlaces {
            bytes,
            header,
            data_start,
            header_lines,
        }
    }

    /// "line N: vertex k" or "byte N: vertex k".
    fn at(&self, element: &str, k: usize) -> String {
        use ply_rs::ply::Encoding;
        let place = match self.header.encoding {
            Encoding::Ascii => {
                let before: usize = self
                    .header
                    .elements
                    .values()
                    .take_while(|e| e.name != element)
                    .map(|e| e.count)
                    .sum();
                Some(format!("line {}", self.header_lines + before + k + 1))
            }
            Encoding::BinaryBigEndian | Encoding::BinaryLittleEndian => {
                self.record_offset(element, k).map(|b| format!("byte {b}"))
            }
        };
        match place {
            Some(p) => format!("{p}: {element} {k}"),
            None => format!("{element} {k}"),
        }
    }

    fn record_offset(&self, element: &str, k: usize) -> Option<usize> {
        use ply_rs::ply::{Encoding, PropertyType, ScalarType};
        let size = |t: &ScalarType| match t {
            ScalarType::Char | ScalarType::UChar => 1,
            ScalarType::Short | ScalarType::UShort => 2,
            ScalarType::Int | ScalarType::UInt | ScalarType::Float => 4,
            ScalarType::Double => 8,
        };
        let big = matches!(self.header.encoding, Encoding::BinaryBigEndian);
        let length = |at: usize, t: &ScalarType| -> Option<usize> {
            let b = self.bytes.get(at..at + size(t))?;
            let word = |b: &[u8]| -> u32 {
                let mut w = [0u8; 4];
                let n = b.len();
                if big {
                    w[4 - n..].copy_from_slice(b);
                    u32::from_be_bytes(w)
                } else {
                    w[..n].copy_from_slice(b);
                    u32::from_le_bytes(w)
                }
            };
            let v = word(b);
            let negative = match t {
                ScalarType::Char => v >= 0x80,
                ScalarType::Short => v >= 0x8000,
                ScalarType::Int => v >= 0x8000_0000,
                ScalarType::Float | ScalarType::Double => return None,
                _ => false,
            };
            (!negative).then_some(v as usize)
        };
        let mut at = self.data_start;
        for e in self.header.elements.values() {
            let last = e.name == element;
            for _ in 0..if last { k } else { e.count } {
                for p in e.properties.values() {
                    at = match &p.data_type {
                        PropertyType::Scalar(t) => at.checked_add(size(t))?,
                        PropertyType::List(count, item) => {
                            let n = length(at, count)?;
                            at.checked_add(size(count))?
                                .checked_add(n.checked_mul(size(item))?)?
                        }
                    };
                }
                if at > self.bytes.len() {
                    return None;
                }
            }
            if last {
                return Some(at);
            }
        }
        None
    }
}

#[cfg(feature = "ply")]
fn load_ply(path: &Path, fail: Fail<'_>) -> Result<IndexedMesh, MeshError> {
    use ply_rs::ply::Property;
    let bytes = std::fs::read(path).map_err(|e| fail(e.to_string()))?;
    check_ply_header(&bytes, fail)?;
    let size = bytes.len() as u64;
    let mut reader = std::io::Cursor::new(&bytes);
    let parser = ply_rs::parser::Parser::<ply_rs::ply::DefaultElement>::new();
    let ply = parser
        .read_ply(&mut reader)
        .map_err(|e| fail(ply_error(&e.to_string(), size)))?;
    let places = PlyPlaces::new(&bytes, &ply.header);
    let scalar = |p: Option<&Property>| -> Option<f64> {
        Some(match *p? {
            Property::Float(x) => x as f64,
            Property::Double(x) => x,
            Property::Int(x) => x as f64,
            Property::UInt(x) => x as f64,
            Property::Short(x) => x as f64,
            Property::UShort(x) => x as f64,
            Property::Char(x) => x as f64,
            Property::UChar(x) => x as f64,
            _ => return None,
        })
    };
    let mut vertices = Vec::new();
    for (k, v) in ply.payload.get("vertex").into_iter().flatten().enumerate() {
        let c = |name: &str| {
            scalar(v.get(name)).ok_or_else(|| {
                let at = places.at("vertex", k);
                fail(format!("{at}: no numeric '{name}' property"))
            })
        };
        let p = Vec3::new(c("x")? as f32, c("y")? as f32, c("z")? as f32);
        vertices.push(finite(p, || places.at("vertex", k), fail)?);
    }
    let mut out = IndexedMesh::default();
    for (k, f) in ply.payload.get("face").into_iter().flatten().enumerate() {
        let list = f.get("vertex_indices").or_else(|| f.get("vertex_index"));
        let poly: Vec<i64> = match list {
            Some(Property::ListInt(l)) => l.iter().map(|&i| i as i64).collect(),
            Some(Property::ListUInt(l)) => l.iter().map(|&i| i as i64).collect(),
            Some(Property::ListShort(l)) => l.iter().map(|&i| i as i64).collect(),
            Some(Property::ListUShort(l)) => l.iter().map(|&i| i as i64).collect(),
            Some(Property::ListChar(l)) => l.iter().map(|&i| i as i64).collect(),
            Some(Property::ListUChar(l)) => l.iter().map(|&i| i as i64).collect(),
            _ => {
                let at = places.at("face", k);
                return Err(fail(format!("{at}: no integer 'vertex_indices' list")));
            }
        };
        let poly: Vec<usize> = poly
            .iter()
            .map(|&i| {
                usize::try_from(i).map_err(|_| {
                    let at = places.at("face", k);
                    fail(format!("{at}: vertex index {i} is negative"))
                })
            })
            .collect::<Result<_, _>>()?;
        fan(&poly, &vertices, &mut out, fail, &|| {
            format!("{}: ", places.at("face", k))
        })?;
    }
    Ok(out)
}

/// OFF and its variants `[ST][C][N]OFF`: texture coordinates, normals and
/// colours follow a vertex's `x y z` on its line, and a face's colour follows
/// its indices; both are read past. The homogeneous `4OFF` and the
/// n-dimensional `nOFF` are refused. One vertex or face per line, as every
/// writer does; the header's counts may share the keyword's line.
fn load_off(path: &Path, fail: Fail<'_>) -> Result<IndexedMesh, MeshError> {
    let text = std::fs::read_to_string(path).map_err(|e| fail(e.to_string()))?;
    // Non-empty lines with their numbers; comments (#) dropped.
    let mut lines = text.lines().enumerate().filter_map(|(n, line)| {
        let line = line.split('#').next().unwrap_or("").trim();
        (!line.is_empty()).then_some((n + 1, line))
    });
    let line_of_end = text.lines().count().max(1);
    let mut next_line = |what: &str| {
        lines
            .next()
            .ok_or_else(|| fail(format!("line {line_of_end}: file ends before {what}")))
    };
    let not_off = || fail("line 1: not an OFF file (no 'OFF' header)".into());
    let (n0, header) = next_line("the 'OFF' header").map_err(|_| not_off())?;
    let mut words = header.split_whitespace();
    let keyword = words.next().unwrap_or("");
    let prefix = keyword.strip_suffix("OFF").ok_or_else(not_off)?;
    if prefix.contains('4') || prefix.contains('n') {
        return Err(fail(format!(
            "line {n0}: '{keyword}' has 4 or n coordinates per vertex; bvhkit reads 3D OFF files"
        )));
    }
    if !prefix.chars().all(|c| "STCN".contains(c)) {
        return Err(not_off());
    }
    let rest: Vec<&str> = words.collect();
    let (nc, counts) = if rest.is_empty() {
        let (n, line) = next_line("the vertex and face counts")?;
        (n, line.split_whitespace().collect())
    } else {
        (n0, rest)
    };
    let count = |i: usize, what: &str| -> Result<usize, MeshError> {
        let t = counts
            .get(i)
            .ok_or_else(|| fail(format!("line {nc}: no {what}")))?;
        t.parse()
            .map_err(|_| fail(format!("line {nc}: {what} '{t}' is not a count")))
    };
    let (nv, nf) = (count(0, "vertex count")?, count(1, "face count")?);
    // Grown as data arrives, never reserved from the header's claim.
    let mut vertices = Vec::new();
    for k in 0..nv {
        let (n, line) = next_line("all vertices")?;
        let mut c = [0f32; 3];
        let mut words = line.split_whitespace();
        for x in &mut c {
            let t = words
                .next()
                .ok_or_else(|| fail(format!("line {n}: a vertex needs x, y and z")))?;
            *x = t
                .parse()
                .map_err(|_| fail(format!("line {n}: coordinate '{t}' is not a number")))?;
        }
        vertices.push(finite(
            Vec3::from_array(c),
            || format!("line {n}: vertex {k}"),
            fail,
        )?);
    }
    let mut out = IndexedMesh::default();
    for k in 0..nf {
        let (n, line) = next_line("all faces")?;
        let mut words = line.split_whitespace();
        let m: usize = match words.next().map(str::parse) {
            Some(Ok(m)) => m,
            _ => {
                return Err(fail(format!(
                    "line {n}: a face starts with its vertex count"
                )))
            }
        };
        let poly = words
            .by_ref()
            .take(m)
            .map(|t| {
                t.parse::<usize>()
                    .map_err(|_| fail(format!("line {n}: index '{t}' is not an index")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        if poly.len() < m {
            return Err(fail(format!(
                "line {n}: the face announces {m} vertices but lists {}",
                poly.len()
            )));
        }
        fan(&poly, &vertices, &mut out, fail, &|| {
            format!("line {n} (face {k}): ")
        })?;
    }
    Ok(out)
}

/// Checks the geometry statements of an OBJ file line by line before `tobj`
/// reads it, so that an error names its line (tobj's errors do not) and a
/// face of fewer than three vertices is refused (tobj would make it a
/// triangle). `v` needs three finite numbers; each `f` vertex
/// (`i`, `i/t`, `i//n`, `i/t/n`) needs an index that exists, counting
/// negative indices back from the last vertex read. Other statements are
/// left to tobj.
#[cfg(feature = "obj")]
fn check_obj(text: &str, fail: Fail<'_>) -> Result<(), MeshError> {
    let mut vertices = 0usize;
    for (n, line) in text.lines().enumerate() {
        let at = |what: String| fail(format!("line {}: {what}", n + 1));
        // Comments are whole lines; tobj reads no comment after a statement.
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let xyz: Vec<&str> = words.take(3).collect();
                if xyz.len() < 3 {
                    return Err(at(format!(
                        "a vertex needs x, y and z, found {}",
                        xyz.len()
                    )));
                }
                for w in xyz {
                    match w.parse::<f32>() {
                        Ok(x) if x.abs() <= bvhkit::MAX_COORDINATE => {}
                        Ok(x) if x.is_finite() => {
                            return Err(at(format!(
                                "coordinate {w} is beyond {:e}, the largest bvhkit accepts",
                                bvhkit::MAX_COORDINATE
                            )))
                        }
                        Ok(_) => return Err(at(format!("non-finite coordinate '{w}'"))),
                        Err(_) => return Err(at(format!("'{w}' is not a number"))),
                    }
                }
                vertices += 1;
            }
            Some("f") => {
                let corners: Vec<&str> = words.collect();
                if corners.len() < 3 {
                    return Err(at(format!(
                        "a face needs at least 3 vertices, found {}",
                        corners.len()
                    )));
                }
                for c in corners {
                    let index = c.split('/').next().unwrap_or("");
                    let i: i64 = index
                        .parse()
                        .map_err(|_| at(format!("'{c}' is not a vertex index")))?;
                    let resolved = if i < 0 { vertices as i64 + i } else { i - 1 };
                    if i == 0 || resolved < 0 || resolved >= vertices as i64 {
                        return Err(at(format!(
                            "vertex index {i} out of range ({vertices} vertices so far)"
                        )));
                    }
                }
            }
            _ => {}
        }
    }
    Ok(())
}

#[cfg(feature = "obj")]
fn load_obj(path: &Path, fail: Fail<'_>) -> Result<IndexedMesh, MeshError> {
    let text = std::fs::read(path).map_err(|e| fail(e.to_string()))?;
    check_obj(&String::from_utf8_lossy(&text), fail)?;
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ..Default::default()
    };
    let (models, _) = tobj::load_obj(path, &options).map_err(|e| fail(e.to_string()))?;
    let mut out = IndexedMesh::default();
    // tobj numbers each object's vertices from 0: the objects' numbers
    // follow one another.
    let mut base = 0u32;
    for m in &models {
        let pos = &m.mesh.positions;
        let vertices = pos.len() / 3;
        let vertex = |i: u32| -> Result<Vec3, MeshError> {
            let i = i as usize;
            if i >= vertices {
                return Err(fail(format!(
                    "object '{}': vertex index {} out of range ({} vertices)",
                    m.name,
                    i + 1,
                    vertices
                )));
            }
            let v = Vec3::new(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
            if !v.is_finite() {
                return Err(fail(format!(
                    "object '{}': vertex {} has a non-finite coordinate",
                    m.name,
                    i + 1
                )));
            }
            Ok(v)
        };
        for f in m.mesh.indices.chunks(3) {
            if f.len() < 3 {
                return Err(fail(format!("object '{}': incomplete face", m.name)));
            }
            out.triangles
                .push(Triangle::new(vertex(f[0])?, vertex(f[1])?, vertex(f[2])?));
            out.corners.push([f[0], f[1], f[2]].map(|i| base + i));
        }
        base += vertices as u32;
    }
    Ok(out)
}

#[cfg(all(test, feature = "obj", feature = "stl", feature = "ply"))]
mod tests {
    use super::*;

    fn write(name: &str, text: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("bvhkit-mesh-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }

    /// Found by fuzzing (`scripts/fuzz`, target `mesh_ply`): an element count
    /// too long for 64 bits panicked inside ply-rs; a count the file cannot
    /// hold is refused before ply-rs acts on it. Both name the line.
    #[test]
    fn ply_headers_with_impossible_counts_are_errors() {
        let huge = format!(
            "ply\nformat ascii 1.0\nelement vertex 2{}\nproperty float x\nend_header\n",
            "1".repeat(60)
        );
        let err = load(&write("huge.ply", &huge)).unwrap_err().to_string();
        assert!(
            err.contains("huge.ply") && err.contains("line 3") && err.contains("too large"),
            "{err}"
        );
        let lying = "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n\x01\x02";
        let err = load(&write("lying.ply", lying)).unwrap_err().to_string();
        assert!(
            err.contains("line 3") && err.contains("4000000000"),
            "{err}"
        );
        // No end_header at all: ply-rs's own error, not a panic.
        assert!(load(&write("open.ply", "ply\nelement ce 21\n")).is_err());
        // Digits glued to letters (the second input fuzzing found).
        let glued = format!("element A77 {}AAA9\n", "7".repeat(40));
        assert!(load(&write("glued.ply", &glued))
            .unwrap_err()
            .to_string()
            .contains("too large"));
    }

    #[test]
    fn corners_keep_the_files_vertex_indices() {
        // A quad (two triangles sharing vertices 0 and 2) and, in OBJ, a
        // second object whose numbers follow the first's.
        let obj = "o a\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n\
                   o b\nv 5 0 0\nv 6 0 0\nv 5 1 0\nf 5 6 7\n";
        let m = load_indexed(&write("two.obj", obj)).unwrap();
        assert_eq!(m.triangles.len(), 3);
        assert_eq!(&m.corners[..2], &[[0, 1, 2], [0, 2, 3]]);
        assert!(m.corners[2].iter().all(|&i| i >= 4), "{:?}", m.corners);
        let off = "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
        let m = load_indexed(&write("quad.off", off)).unwrap();
        assert_eq!(m.corners, [[0, 1, 2], [0, 2, 3]]);
        let ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
                   element face 1\nproperty list uchar int vertex_indices\nend_header\n\
                   0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 3 2 1 0\n";
        let m = load_indexed(&write("quad.ply", ply)).unwrap();
        assert_eq!(m.corners, [[3, 2, 1], [3, 1, 0]]);
        // Two vertices at one position keep two indices (a seam).
        let seam = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 0\nv -1 0 0\nf 1 2 3\nf 4 5 3\n";
        let m = load_indexed(&write("seam.obj", seam)).unwrap();
        assert_eq!(m.corners, [[0, 1, 2], [3, 4, 2]]);
        // STL has no vertex list: corners are numbered by position.
        let stl = "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n\
                   facet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n";
        let m = load_indexed(&write("two.stl", stl)).unwrap();
        assert_eq!(m.corners, [[0, 1, 2], [1, 3, 2]]);
        assert_eq!(
            weld(&[Triangle::new(Vec3::ZERO, -Vec3::ZERO, Vec3::X)]),
            [[0, 0, 1]]
        );
    }

    #[test]
    fn off_variants_load() {
        // Per-vertex colours (COFF), normals (NOFF), both with texture
        // coordinates (STCNOFF), per-face colours, counts on the header line.
        for (name, text) in [
            ("plain.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
            ("colours.off", "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n3 0 1 2\n"),
            ("normals.off", "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n"),
            ("all.off", "STCNOFF 3 1 0\n0 0 0 0 0 1 1 1 1 0 0\n1 0 0 0 0 1 1 1 1 1 0\n0 1 0 0 0 1 1 1 1 0 1\n3 0 1 2 0.5 0.5 0.5\n"),
            ("face_colour.off", "OFF\n# a comment\n3 1 0\n\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 255 128 0\n"),
        ] {
            let tris = load(&write(name, text)).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(tris, [Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y)], "{name}");
        }
    }

    #[test]
    fn obj_negative_indices_and_slashed_faces_load() {
        let p = write(
            "slashes.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n\
             f 1/1/1 2/1/1 3/1/1\nf -4//1 -2//1 -1//1\ns off\ng part\n",
        );
        let tris = load(&p).unwrap();
        assert_eq!(tris.len(), 2);
        assert_eq!(tris[1].v[2], Vec3::new(0.0, 1.0, 0.0));
    }

    #[test]
    fn loads_and_triangulates_obj() {
        let p = write(
            "quad.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n",
        );
        let tris = load(&p).unwrap();
        assert_eq!(tris.len(), 2);
        assert_eq!(tris[0].v[0], Vec3::ZERO);
    }

    fn write_bytes(name: &str, bytes: &[u8]) -> PathBuf {
        let p = write(name, "");
        std::fs::write(&p, bytes).unwrap();
        p
    }

    /// A binary STL of the given triangles, with the count field given.
    fn binary_stl(tris: &[[f32; 9]], count: u32) -> Vec<u8> {
        let mut b = vec![0u8; 80];
        b.extend_from_slice(&count.to_le_bytes());
        for t in tris {
            b.extend_from_slice(&[0u8; 12]); // normal
            for x in t {
                b.extend_from_slice(&x.to_le_bytes());
            }
            b.extend_from_slice(&[0u8; 2]);
        }
        b
    }

    const QUAD: [Vec3; 4] = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];

    #[test]
    fn every_format_loads_the_same_quad() {
        let off = write(
            "quad.off",
            "OFF\n# a comment\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
        );
        let stl_ascii = write(
            "quad.stl",
            "solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\n\
             facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid q\n",
        );
        let tri = |a: Vec3, b: Vec3, c: Vec3| [a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z];
        let faces = [
            tri(QUAD[0], QUAD[1], QUAD[2]),
            tri(QUAD[0], QUAD[2], QUAD[3]),
        ];
        let stl_bin = write_bytes("quad_bin.stl", &binary_stl(&faces, 2));
        let ply_ascii = write(
            "quad.ply",
            "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
             element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
        );
        let mut ply_bin = b"ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n".to_vec();
        for v in QUAD {
            for x in v.to_array() {
                ply_bin.extend_from_slice(&x.to_le_bytes());
            }
        }
        ply_bin.push(4);
        for i in 0i32..4 {
            ply_bin.extend_from_slice(&i.to_le_bytes());
        }
        let ply_bin = write_bytes("quad_bin.ply", &ply_bin);
        let obj = write(
            "quad2.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n",
        );
        let want = vec![
            Triangle::new(QUAD[0], QUAD[1], QUAD[2]),
            Triangle::new(QUAD[0], QUAD[2], QUAD[3]),
        ];
        for p in [off, stl_ascii, stl_bin, ply_ascii, ply_bin, obj] {
            assert_eq!(
                load(&p).unwrap_or_else(|e| panic!("{e}")),
                want,
                "{}",
                p.display()
            );
        }
    }

    /// A binary PLY of three vertices (the second given, the others at 0
    /// and (0, 1, 0)) and triangles, and the length of its header: vertex k
    /// starts 12k bytes after it, face k 36 + 13k.
    fn binary_ply(big_endian: bool, second: [f32; 3], faces: &[[i32; 3]]) -> (Vec<u8>, usize) {
        let order = if big_endian { "big" } else { "little" };
        let mut b = format!(
            "ply\nformat binary_{order}_endian 1.0\nelement vertex 3\nproperty float x\n\
             property float y\nproperty float z\nelement face {}\n\
             property list uchar int vertex_indices\nend_header\n",
            faces.len()
        )
        .into_bytes();
        let header = b.len();
        let put = |mut bytes: [u8; 4], b: &mut Vec<u8>| {
            if big_endian {
                bytes.reverse();
            }
            b.extend_from_slice(&bytes);
        };
        for v in [[0.0; 3], second, [0.0, 1.0, 0.0]] {
            for x in v {
                put(x.to_le_bytes(), &mut b);
            }
        }
        for f in faces {
            b.push(3);
            for i in f {
                put(i.to_le_bytes(), &mut b);
            }
        }
        (b, header)
    }

    /// Binary PLY errors name the byte where the bad record starts; the
    /// offset of a face after the first is found by reading the lengths of
    /// the lists before it, in either byte order.
    #[test]
    fn binary_ply_errors_name_the_byte() {
        for big in [false, true] {
            let (bytes, h) = binary_ply(big, [f32::NAN, 0.0, 0.0], &[[0, 1, 2]]);
            let e = load(&write_bytes("nan.ply", &bytes))
                .unwrap_err()
                .to_string();
            let want = format!(
                "nan.ply: byte {}: vertex 1 has a non-finite coordinate",
                h + 12
            );
            assert!(e.ends_with(&want), "{e}");
            let (bytes, h) = binary_ply(big, [1.0, 0.0, 0.0], &[[0, 1, 7]]);
            let e = load(&write_bytes("far_index.ply", &bytes))
                .unwrap_err()
                .to_string();
            let want = format!("byte {}: face 0: vertex index 7 out of range", h + 36);
            assert!(e.contains(&want), "{e}");
            let (bytes, h) = binary_ply(big, [1.0, 0.0, 0.0], &[[0, 1, 2], [2, 1, 0], [0, 1, -3]]);
            let e = load(&write_bytes("negative.ply", &bytes))
                .unwrap_err()
                .to_string();
            let want = format!(
                "byte {}: face 2: vertex index -3 is negative",
                h + 36 + 2 * 13
            );
            assert!(e.contains(&want), "{e}");
            // The same file, well formed, loads.
            let (bytes, _) = binary_ply(big, [1.0, 0.0, 0.0], &[[0, 1, 2], [2, 1, 0]]);
            assert_eq!(load(&write_bytes("fine.ply", &bytes)).unwrap().len(), 2);
        }
    }

    #[test]
    fn hostile_files_are_errors_naming_the_file_and_line() {
        let one = [[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0f32]];
        let nan = [[0.0, 0.0, 0.0, f32::NAN, 0.0, 0.0, 0.0, 1.0, 0.0f32]];
        let mut truncated = binary_stl(&one, 1);
        truncated.truncate(100);
        for (name, bytes, says) in [
            // A count that promises 4 billion triangles: refused from the size, not allocated.
            ("lying_count.stl", binary_stl(&one, u32::MAX), "claims"),
            ("truncated.stl", truncated, "has 100 bytes"),
            ("short.stl", vec![1, 2, 3], "truncated"),
            // Binary formats name the byte where the bad record starts.
            ("nan.stl", binary_stl(&nan, 1), "byte 108: triangle 0 vertex 1 has a non-finite"),
            // ASCII STL: the STL crate refuses NaN itself (the facet's line);
            // the range check names the vertex's line.
            (
                "nan_ascii.stl",
                b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex nan 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n".to_vec(),
                "line 2: triangle 0: expected finite",
            ),
            (
                "far_ascii.stl",
                b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1e33 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n".to_vec(),
                "line 5: triangle 0 vertex 1 has a coordinate beyond 1e32",
            ),
            (
                "far_ascii.ply",
                b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1e33 0 0\n0 1 0\n3 0 1 2\n".to_vec(),
                "line 11: vertex 1 has a coordinate beyond 1e32",
            ),
            ("huge_off.off", b"OFF\n1000000000000000 1 0\n0 0 0\n".to_vec(), "ends before"),
            ("bad_index.off", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n".to_vec(), "line 6"),
            ("bad_number.off", b"OFF\n3 1 0\n0 0 0\n1 x 0\n".to_vec(), "line 4"),
            ("inf.off", b"OFF\n3 1 0\n0 0 0\ninf 0 0\n0 1 0\n3 0 1 2\n".to_vec(), "line 4: vertex 1 has a non-finite"),
            ("no_header.off", b"3 1 0\n".to_vec(), "not an OFF file"),
            ("two_gon.off", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n".to_vec(), "2 vertices"),
            ("short_face.off", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n".to_vec(), "line 6: the face announces 3 vertices but lists 2"),
            ("four_d.off", b"4OFF\n1 0 0\n0 0 0 1\n".to_vec(), "line 1: '4OFF'"),
            (
                "huge_ply.ply",
                b"ply\nformat ascii 1.0\nelement vertex 999999999999\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n".to_vec(),
                "line 3: the header announces 999999999999 'vertex' elements, more than the 6 bytes",
            ),
            (
                "bad_ply_index.ply",
                b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -5\n".to_vec(),
                "line 13: face 0: vertex index -5 is negative",
            ),
            ("garbage.ply", b"not a ply at all".to_vec(), "PLY"),
            (
                "truncated.ply",
                b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n".to_vec(),
                "line 10: the file ends before every element",
            ),
            (
                "word.ply",
                b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 zero 0\n".to_vec(),
                "line 8: '0 zero 0' does not match",
            ),
            (
                "truncated_binary.ply",
                b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n\x00\x00\x00\x00".to_vec(),
                "binary data ends at byte",
            ),
            ("two_vertex_face.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n".to_vec(), "line 4: a face needs at least 3 vertices, found 2"),
            ("bad_obj_index.obj", b"v 0 0 0\nv 1 0 0\n# comment\nf 1 2 9\n".to_vec(), "line 4: vertex index 9 out of range"),
            ("zero_index.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n".to_vec(), "line 4: vertex index 0"),
            ("negative_too_far.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n".to_vec(), "line 4: vertex index -4"),
            ("nan.obj", b"v 0 0 0\nv nan 0 0\n".to_vec(), "line 2: non-finite"),
            ("word.obj", b"v 0 zero 0\n".to_vec(), "line 1: 'zero' is not a number"),
            ("short_v.obj", b"v 0 0\n".to_vec(), "line 1: a vertex needs x, y and z"),
            ("far.obj", b"v 0 0 0\nv 1e33 0 0\n".to_vec(), "line 2: coordinate 1e33 is beyond 1e32"),
            ("far.off", b"OFF\n3 1 0\n0 0 0\n-2e32 0 0\n0 1 0\n3 0 1 2\n".to_vec(), "line 4: vertex 1 has a coordinate beyond 1e32"),
            ("inline_comment.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 # tail\n".to_vec(), "line 4: '#' is not a vertex index"),
        ] {
            let p = write_bytes(name, &bytes);
            let e = load(&p).expect_err(name).to_string();
            assert!(e.contains(name) && e.contains(says), "{name}: {e}");
            // One line, no parser debug output.
            assert!(!e.contains('\n') && !e.contains("Custom {"), "{name}: {e}");
        }
    }

    #[test]
    fn placement_scales_rotates_then_translates() {
        let t = [Triangle::new(Vec3::X, Vec3::Y, Vec3::Z)];
        let p = Placement {
            scale: 2.0,
            rotate_deg: Vec3::new(0.0, 0.0, 90.0),
            translate: Vec3::new(0.0, 0.0, 1.0),
        };
        let out = p.apply(&t).unwrap();
        // x -> 2x -> (z-rotation by 90 degrees) 2y -> + (0, 0, 1).
        assert!(
            (out[0].v[0] - Vec3::new(0.0, 2.0, 1.0)).length() < 1e-5,
            "{:?}",
            out[0].v[0]
        );
        assert!(Placement { scale: 0.0, ..p }.apply(&t).is_err());
        assert!(Placement { scale: 1e38, ..p }
            .apply(&[Triangle::new(Vec3::splat(1e10), Vec3::ZERO, Vec3::ZERO)])
            .is_err());
    }

    #[test]
    fn files_without_faces_load_as_empty_meshes() {
        let mut binary_stl = vec![0u8; 80];
        binary_stl.extend_from_slice(&0u32.to_le_bytes());
        let mut paths = vec![write_bytes("empty-binary.stl", &binary_stl)];
        for (name, text) in [
            ("empty.obj", "# nothing\n"),
            ("vertices-only.obj", "v 0 0 0\nv 1 0 0\n"),
            ("empty.off", "OFF\n0 0 0\n"),
            ("vertices-only.off", "OFF\n2 0 0\n0 0 0\n1 0 0\n"),
            ("empty.stl", "solid nothing\nendsolid nothing\n"),
            (
                "empty.ply",
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n",
            ),
        ] {
            paths.push(write(name, text));
        }
        for p in paths {
            match load(&p) {
                Ok(tris) => assert!(tris.is_empty(), "{}", p.display()),
                Err(e) => panic!("{e}"),
            }
        }
    }

    #[test]
    fn bad_files_are_errors_naming_the_file() {
        for (name, text) in [
            ("bad_index.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n"),
            ("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"),
            ("garbage.obj", "v 0 zero 0\nf 1 1 1\n"),
        ] {
            let p = write(name, text);
            let e = load(&p).expect_err(name);
            assert!(e.to_string().contains(name), "{e}");
        }
        assert!(load(Path::new("/no/such/file.obj")).is_err());
        assert!(load(&write("mesh.xyz", "")).is_err());
    }
}

/// Runs in every feature set (CI runs it with none): a format compiled out
/// is refused with the feature's name, and OFF always loads.
#[cfg(test)]
mod feature_tests {
    use super::*;

    #[test]
    fn formats_left_out_name_their_feature_and_off_always_loads() {
        let dir = std::env::temp_dir().join(format!("bvhkit-mesh-features-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let off = dir.join("t.off");
        std::fs::write(&off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap();
        assert_eq!(load(&off).unwrap().len(), 1);
        for (ext, on) in [
            ("obj", cfg!(feature = "obj")),
            ("stl", cfg!(feature = "stl")),
            ("ply", cfg!(feature = "ply")),
        ] {
            let path = dir.join(format!("t.{ext}"));
            // Broken in every format (a face with no vertices behind it).
            std::fs::write(&path, "f 1 2 3\n").unwrap();
            let err = load(&path).unwrap_err();
            assert_eq!(err.path, path);
            let names_feature = err.reason.contains(&format!("`{ext}` feature"));
            assert_eq!(names_feature, !on, "{ext}: {}", err.reason);
        }
        std::fs::remove_dir_all(&dir).ok();
    }
}
