//! The book's figures, drawn by bvhkit itself: every picture is computed
//! from the library's own builders, volumes and queries (2-D scenes at
//! z = 0 where a picture reads better), written as SVG by `bvhkit figures`
//! into `book/src/figures/`, and checked by the book's tests to match what
//! the code draws now.
//!
//! ```
//! let figures = bvhkit_std::figures::all(std::path::Path::new("../book/src"))?;
//! let volumes = figures.iter().find(|f| f.name == "volumes-around-points").unwrap();
//! assert!(volumes.svg.starts_with("<svg") && volumes.chapter == "bounding-volumes.md");
//! # Ok::<(), bvhkit_std::figures::FigureError>(())
//! ```

mod bottom_up;
mod characteristics;
mod collision;
mod descent;
mod embedded;
mod engines;
mod exercises;
mod insertion;
mod introduction;
mod performance;
mod representations;
mod robustness;
pub mod svg;
mod top_down;
mod traversal;
mod tree_degree;
mod volumes;
mod walk_log;

use bvhkit::glam::{Vec2, Vec3};
use bvhkit::{Kdop, Obb};
use std::fmt;
use std::path::{Path, PathBuf};

/// One figure: its file name (without `.svg`), the chapter that shows it,
/// and the drawing.
#[derive(Clone, Debug)]
pub struct Figure {
    /// File stem, unique: the figure is `figures/NAME.svg`.
    pub name: &'static str,
    /// The chapter file (as in `SUMMARY.md`) that includes it.
    pub chapter: &'static str,
    /// The SVG document.
    pub svg: String,
}

/// Why figures could not be drawn or written.
#[derive(Debug)]
pub struct FigureError(pub String);

impl fmt::Display for FigureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for FigureError {}

impl From<bvhkit::Error> for FigureError {
    fn from(e: bvhkit::Error) -> Self {
        FigureError(format!("a figure's build or query failed: {e}"))
    }
}

/// Every figure of the book. `book_src` is the book's `src` folder: the
/// plots of recorded runs read their data from its `measured/` files.
pub fn all(book_src: &Path) -> Result<Vec<Figure>, FigureError> {
    let mut out = Vec::new();
    // In the book's order.
    out.extend(introduction::figures(book_src)?);
    out.extend(volumes::figures()?);
    out.extend(characteristics::figures(book_src)?);
    out.extend(tree_degree::figures(book_src)?);
    out.extend(top_down::figures(book_src)?);
    out.extend(bottom_up::figures(book_src)?);
    out.extend(insertion::figures(book_src)?);
    out.extend(traversal::figures(book_src)?);
    out.extend(descent::figures(book_src)?);
    out.extend(collision::figures(book_src)?);
    out.extend(engines::figures(book_src)?);
    out.extend(representations::figures(book_src)?);
    out.extend(robustness::figures(book_src)?);
    out.extend(performance::figures(book_src)?);
    out.extend(embedded::figures(book_src)?);
    out.extend(exercises::figures(book_src)?);
    let mut names: Vec<&str> = out.iter().map(|f| f.name).collect();
    names.sort_unstable();
    if let Some(w) = names.windows(2).find(|w| w[0] == w[1]) {
        return Err(FigureError(format!("two figures are named {}", w[0])));
    }
    Ok(out)
}

/// Writes every figure into `dir` (created if missing) as `NAME.svg`, and
/// returns the paths written.
pub fn write_all(book_src: &Path, dir: &Path) -> Result<Vec<PathBuf>, FigureError> {
    let io = |p: &Path, e: std::io::Error| FigureError(format!("{}: {e}", p.display()));
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let mut written = Vec::new();
    for f in all(book_src)? {
        let path = dir.join(format!("{}.svg", f.name));
        std::fs::write(&path, &f.svg).map_err(|e| io(&path, e))?;
        written.push(path);
    }
    Ok(written)
}

/// Compares the figures in `dir` with what the code draws now: the list of
/// differences (a figure missing, different, or a file no figure draws),
/// empty when they match.
pub fn check(book_src: &Path, dir: &Path) -> Result<Vec<String>, FigureError> {
    let figures = all(book_src)?;
    let mut problems = Vec::new();
    for f in &figures {
        let path = dir.join(format!("{}.svg", f.name));
        match std::fs::read_to_string(&path) {
            Ok(s) if s == f.svg => {}
            Ok(_) => problems.push(format!(
                "{} differs from what the code draws",
                path.display()
            )),
            Err(e) => problems.push(format!("{}: {e}", path.display())),
        }
    }
    if let Ok(entries) = std::fs::read_dir(dir) {
        for e in entries.flatten() {
            let name = e.file_name().to_string_lossy().into_owned();
            if let Some(stem) = name.strip_suffix(".svg") {
                if !figures.iter().any(|f| f.name == stem) {
                    problems.push(format!("{name} is drawn by no figure"));
                }
            }
        }
    }
    Ok(problems)
}

/// The 2-D cross-section at z = 0 of a k-DOP's polytope: the square of the
/// x and y slabs clipped by every other slab that cuts the plane.
pub fn kdop_section<const K: usize>(dop: &Kdop<K>) -> Vec<Vec2> {
    let mut poly = vec![
        Vec2::new(dop.min[0], dop.min[1]),
        Vec2::new(dop.max[0], dop.min[1]),
        Vec2::new(dop.max[0], dop.max[1]),
        Vec2::new(dop.min[0], dop.max[1]),
    ];
    for i in 0..K {
        let [a, b, _] = Kdop::<K>::direction(i);
        if a == 0 || b == 0 {
            continue; // parallel to an axis slab, or to z: no cut in the plane
        }
        let n = Vec2::new(a as f32, b as f32);
        poly = clip(&poly, n, dop.max[i]);
        poly = clip(&poly, -n, -dop.min[i]);
    }
    poly
}

/// The polygon `poly` cut to the half-plane `n . p <= d`.
fn clip(poly: &[Vec2], n: Vec2, d: f32) -> Vec<Vec2> {
    let mut out = Vec::new();
    for (i, &p) in poly.iter().enumerate() {
        let q = poly[(i + 1) % poly.len()];
        let (dp, dq) = (n.dot(p) - d, n.dot(q) - d);
        if dp <= 0.0 {
            out.push(p);
        }
        if (dp < 0.0) != (dq < 0.0) && dp != dq {
            out.push(p + (q - p) * (dp / (dp - dq)));
        }
    }
    out
}

/// The four corners at z = 0 of an OBB whose third axis is z (a box
/// fitted to points in the plane).
pub fn obb_section(obb: &Obb) -> Vec<Vec2> {
    let c = obb.center.truncate();
    let (u, v) = (
        obb.axes[0].truncate() * obb.half_extents.x,
        obb.axes[1].truncate() * obb.half_extents.y,
    );
    vec![c - u - v, c + u - v, c + u + v, c - u + v]
}

/// Points of the plane as the library's 3-D points.
pub fn lift(points: &[Vec2]) -> Vec<Vec3> {
    points.iter().map(|p| p.extend(0.0)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use bvhkit::{BoundingVolume, Dop18};

    #[test]
    fn a_square_dop_section_is_an_octagon_with_cut_corners() {
        let pts = lift(&[
            Vec2::new(1.0, 0.0),
            Vec2::new(-1.0, 0.0),
            Vec2::new(0.0, 1.0),
            Vec2::new(0.0, -1.0),
        ]);
        let dop = Dop18::fit(pts.as_slice());
        let section = kdop_section(&dop);
        // The diamond itself: the diagonal slabs cut the box to its four points.
        assert!(
            section
                .iter()
                .all(|p| (p.x.abs() + p.y.abs() - 1.0).abs() < 1e-5),
            "{section:?}"
        );
        assert!(section.len() >= 4);
    }

    #[test]
    fn every_figure_has_a_unique_name_and_an_svg() {
        let figures = all(Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../book/src"
        )))
        .unwrap();
        assert!(!figures.is_empty());
        for f in &figures {
            assert!(
                f.svg.starts_with("<svg") && f.svg.ends_with("</svg>\n"),
                "{}",
                f.name
            );
        }
    }
}
