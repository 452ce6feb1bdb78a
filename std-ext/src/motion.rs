//! Moving objects: how long does refitting stay good enough?
//!
//! A rock is twisted a little more every frame (each vertex turns about the
//! vertical axis by an angle proportional to its height). Each frame the tree
//! built at frame 0 is refitted, and a fresh tree is built for comparison; both
//! are queried against a second, static rock. The tree's shape stays while its
//! content moves, so the refitted tree's SAH cost and query time drift away
//! from the rebuilt one's.

use crate::{median_time, scene, OwnedBvh};
use bvhkit::builders::refit_all;
use bvhkit::glam::{Mat3, Vec3};
use bvhkit::{overlapping_pairs, Aabb, Descent, Node, TopDown, Triangle};
use serde::Serialize;

/// One frame of the comparison.
#[derive(Clone, Debug, Serialize)]
pub struct MotionRow {
    /// Frame number.
    pub frame: usize,
    /// Twist at the top of the rock relative to its middle, in degrees.
    pub twist_degrees: f32,
    /// SAH cost of the refitted tree.
    pub refit_sah: f64,
    /// SAH cost of a tree rebuilt for this frame.
    pub rebuild_sah: f64,
    /// Median time of the refit.
    pub refit_ms: f64,
    /// Median time of the rebuild.
    pub rebuild_ms: f64,
    /// Pair query time with the refitted tree.
    pub refit_query_ms: f64,
    /// Pair query time with the rebuilt tree.
    pub rebuild_query_ms: f64,
    /// Whether both trees found the same pairs.
    pub same_pairs: bool,
}

/// `rock` twisted about the vertical axis: each vertex turns by
/// `radians_per_unit` times its height (`y`), the motion of
/// [`refit_vs_rebuild`].
///
/// ```
/// use bvhkit_std::{motion::twisted, scene};
/// let rock = scene::rock(2, 1);
/// let moved = twisted(&rock, 0.3);
/// assert_eq!(moved.len(), rock.len());
/// // A vertex at height 0 stays; one higher up turns about the y axis.
/// assert_eq!(twisted(&rock, 0.0), rock);
/// let (p, q) = (rock[0].v[0], moved[0].v[0]);
/// assert!((p.y - q.y).abs() < 1e-6 && (p.length() - q.length()).abs() < 1e-5);
/// ```
pub fn twisted(rock: &[Triangle], radians_per_unit: f32) -> Vec<Triangle> {
    rock.iter()
        .map(|t| Triangle {
            v: t.v
                .map(|p| Mat3::from_rotation_y(p.y * radians_per_unit) * p),
        })
        .collect()
}

/// Runs `frames + 1` frames (0 to `frames`), twisting by `step` radians per
/// unit of height per frame.
pub fn refit_vs_rebuild(
    subdivisions: u32,
    frames: usize,
    step: f32,
    runs: usize,
) -> Result<Vec<MotionRow>, bvhkit::Error> {
    let rock = scene::rock(subdivisions, 1);
    let other = scene::transformed(
        &scene::rock(subdivisions, 2),
        0.7,
        Vec3::new(1.35, 0.2, 0.1),
    );
    let builder = TopDown::sah();
    let first = OwnedBvh::<Aabb>::build(&builder, &rock)?;
    let fixed = OwnedBvh::<Aabb>::build(&builder, &other)?;
    let t_other = fixed.view();
    let view = first.view();
    let mut nodes: Vec<Node<Aabb>> = view.nodes().to_vec();
    let indices: Vec<u32> = view.indices().to_vec();
    let depth = view.depth();
    let mut rows = Vec::new();
    for frame in 0..=frames {
        let k = step * frame as f32;
        let moved = twisted(&rock, k);
        let (refit_t, r) = median_time(runs, || refit_all(&mut nodes, &indices, &moved, 0.0, ()));
        r?;
        let refitted = bvhkit::Bvh::from_raw_parts(&nodes, &indices, depth);
        let (rebuild_t, rebuilt) = median_time(runs, || OwnedBvh::<Aabb>::build(&builder, &moved));
        let rebuilt = rebuilt?;
        let mut pairs_refit = Vec::new();
        let (q_refit, r) = median_time(runs, || {
            pairs_refit.clear();
            overlapping_pairs(
                &refitted,
                &moved,
                &t_other,
                &other,
                Descent::Larger,
                |i, j| pairs_refit.push((i, j)),
            )
        });
        r?;
        let mut pairs_rebuilt = Vec::new();
        let (q_rebuilt, r) = median_time(runs, || {
            pairs_rebuilt.clear();
            overlapping_pairs(
                &rebuilt.view(),
                &moved,
                &t_other,
                &other,
                Descent::Larger,
                |i, j| pairs_rebuilt.push((i, j)),
            )
        });
        r?;
        pairs_refit.sort_unstable();
        pairs_rebuilt.sort_unstable();
        rows.push(MotionRow {
            frame,
            // The rock spans y in about [-1, 1]: top against middle.
            twist_degrees: k.to_degrees(),
            refit_sah: refitted.stats().sah_cost,
            rebuild_sah: rebuilt.view().stats().sah_cost,
            refit_ms: refit_t.as_secs_f64() * 1e3,
            rebuild_ms: rebuild_t.as_secs_f64() * 1e3,
            refit_query_ms: q_refit.as_secs_f64() * 1e3,
            rebuild_query_ms: q_rebuilt.as_secs_f64() * 1e3,
            same_pairs: pairs_refit == pairs_rebuilt,
        });
    }
    Ok(rows)
}

/// The frames as a text table.
pub fn render(rows: &[MotionRow]) -> String {
    let mut s = format!(
        "{:>5} {:>8} {:>10} {:>11} {:>8} {:>9} {:>10} {:>12} {:>5}\n",
        "frame",
        "twist",
        "refit SAH",
        "rebuild SAH",
        "ratio",
        "refit ms",
        "rebuild ms",
        "query r/b ms",
        "ok"
    );
    for r in rows {
        s += &format!(
            "{:>5} {:>7.0}° {:>10.2} {:>11.2} {:>8.2} {:>9.2} {:>10.2} {:>5.2}/{:<6.2} {:>5}\n",
            r.frame,
            r.twist_degrees,
            r.refit_sah,
            r.rebuild_sah,
            r.refit_sah / r.rebuild_sah,
            r.refit_ms,
            r.rebuild_ms,
            r.refit_query_ms,
            r.rebuild_query_ms,
            if r.same_pairs { "yes" } else { "NO" }
        );
    }
    s
}
