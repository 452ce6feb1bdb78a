//! Loading triangle meshes from files.
//!
//! Wavefront OBJ through the `tobj` crate (polygons are triangulated). Every
//! error names the file; indices are checked against the vertex count and
//! coordinates must be finite, so a hostile file gives an error, not a panic.

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

/// Loads every triangle of a mesh file (all objects of an OBJ file together).
pub fn load(path: &Path) -> Result<Vec<Triangle>, MeshError> {
    let fail = |reason: String| MeshError {
        path: path.to_path_buf(),
        reason,
    };
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
    {
        Some(ext) if ext == "obj" => {}
        _ => {
            return Err(fail(
                "unsupported format (this version reads .obj; more formats are planned)".into(),
            ))
        }
    }
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ..Default::default()
    };
    let (models, _) = tobj::load_obj(path, &options).map_err(|e| fail(e.to_string()))?;
    let mut tris = Vec::new();
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
            tris.push(Triangle::new(vertex(f[0])?, vertex(f[1])?, vertex(f[2])?));
        }
    }
    if tris.is_empty() {
        return Err(fail("no triangles in the file".into()));
    }
    Ok(tris)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(name: &str, text: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("bvhkit-mesh-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
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

    #[test]
    fn bad_files_are_errors_naming_the_file() {
        for (name, text) in [
            ("bad_index.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n"),
            ("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"),
            ("empty.obj", "# nothing\n"),
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
