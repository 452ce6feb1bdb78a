//! Shared helpers of the fuzz targets.

use std::path::PathBuf;

/// Loads `data` as a mesh file with extension `ext` (written to a file of
/// this process in the temporary directory: the loaders read files, and this
/// is the path users take). Any answer is fine but a panic; a mesh that
/// loads has only finite coordinates within the builders' range.
pub fn load_as(ext: &str, data: &[u8]) {
    thread_local! {
        static PATH: std::cell::RefCell<Option<PathBuf>> = const { std::cell::RefCell::new(None) };
    }
    let dir = std::env::var_os("BVHKIT_FUZZ_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(std::env::temp_dir);
    let path = dir.join(format!("bvhkit-fuzz-{}.{ext}", std::process::id()));
    PATH.with(|p| *p.borrow_mut() = Some(path.clone()));
    std::fs::write(&path, data).expect("temporary file");
    if let Ok(tris) = bvhkit_std::mesh::load(&path) {
        for t in &tris {
            for v in t.v {
                assert!(v.is_finite() && v.abs().max_element() <= bvhkit::MAX_COORDINATE);
            }
        }
    }
}
