//! What each bounding-volume type buys a pair query: a tree of every volume
//! over the same scene, its build time, its SAH cost (each volume's own exact
//! measures), and the default pair query's `Nv` (volume tests), `Np`
//! (primitive tests) and time, checked against brute force.
//!
//! k-DOPs appear twice under a bottom-up build: with the box measures that
//! their builders and descent compare by default (see
//! [`bvhkit::Kdop`]'s module docs), and as [`ExactKdop`], which compares the
//! polytopes' exact measures. The pair of rows is the measurement behind that
//! default. A top-down build scores primitive boxes whatever the volume, so
//! its k-DOP trees do not depend on the choice and are shown once.

use crate::tour::{self, Builder};
use crate::{median_time, OwnedBvh};
use bvhkit::builders::{BottomUp, Collapse, MergeMetric, Method};
use bvhkit::{
    Aabb, BoundingVolume, Counts, Dop14, Dop18, Dop26, ExactKdop, Obb, ObbDito, Pairs, Sphere,
    TopDown, Triangle,
};
use serde::Serialize;

/// One volume type's tree on one scene.
#[derive(Clone, Debug, Serialize)]
pub struct VolumeRow {
    /// The scene.
    pub scene: String,
    /// The volume type ([`BoundingVolume::NAME`]).
    pub volume: String,
    /// The builder.
    pub builder: String,
    /// Median build time of one tree.
    pub build_ms: f64,
    /// SAH cost with the volume's exact measures (lower is better).
    pub sah_cost: f64,
    /// Volume pair tests of the pair query.
    pub bv_tests: u64,
    /// Primitive pair tests of the pair query.
    pub prim_tests: u64,
    /// Median time of the pair query (default walk and descent rule).
    pub query_ms: f64,
    /// Whether the pairs equal the brute-force reference.
    pub verified: bool,
}

/// The bottom-up builder the measure comparison uses: PLOC at radius 1, the
/// kit's fast builder (radius 4 costs four times the cost evaluations, which
/// with exact 26-DOP measures is minutes on a real mesh).
pub const BOTTOM_UP: BottomUp = BottomUp {
    method: Method::Ploc { radius: 1 },
    metric: MergeMetric::SurfaceArea,
    collapse: Collapse::DEFAULT,
};

/// Every volume on the scene `a` against `b`: each type with the default
/// top-down build, and each k-DOP with [`BOTTOM_UP`] under box and exact
/// measures. `exact` false leaves the exact rows out (they take seconds per
/// tree on tens of thousands of triangles).
pub fn measure(
    scene: &str,
    a: &[Triangle],
    b: &[Triangle],
    runs: usize,
    exact: bool,
) -> Result<Vec<VolumeRow>, bvhkit::Error> {
    let reference = tour::reference_pairs(a, b);
    let sah = Builder::TopDown(TopDown::sah());
    let ploc = Builder::BottomUp(BOTTOM_UP);
    let s = Setting {
        scene,
        a,
        b,
        reference: &reference,
        runs,
    };
    let mut rows = vec![
        s.row::<Aabb>("sah", sah)?,
        s.row::<Sphere>("sah", sah)?,
        s.row::<Obb>("sah", sah)?,
        s.row::<ObbDito>("sah", sah)?,
        s.row::<Dop14>("sah", sah)?,
        s.row::<Dop18>("sah", sah)?,
        s.row::<Dop26>("sah", sah)?,
        s.row::<Aabb>("ploc-r1", ploc)?,
        s.row::<Dop14>("ploc-r1", ploc)?,
        s.row::<Dop26>("ploc-r1", ploc)?,
    ];
    if exact {
        rows.push(s.row::<ExactKdop<7>>("ploc-r1", ploc)?);
        rows.push(s.row::<ExactKdop<13>>("ploc-r1", ploc)?);
    }
    Ok(rows)
}

struct Setting<'a> {
    scene: &'a str,
    a: &'a [Triangle],
    b: &'a [Triangle],
    reference: &'a [(u32, u32)],
    runs: usize,
}

impl Setting<'_> {
    fn row<B: BoundingVolume>(
        &self,
        builder_name: &str,
        builder: Builder,
    ) -> Result<VolumeRow, bvhkit::Error> {
        let (build, tree_a) = median_time(self.runs, || builder.build::<B>(self.a));
        let tree_a: OwnedBvh<B> = tree_a?;
        let tree_b = builder.build::<B>(self.b)?;
        let (ta, tb) = (tree_a.view(), tree_b.view());
        let mut counts = Counts::default();
        let mut pairs = Vec::with_capacity(self.reference.len());
        Pairs::new(&ta, self.a, &tb, self.b)
            .counted(&mut counts)
            .for_each(|i, j| pairs.push((i, j)))?;
        pairs.sort_unstable();
        let (query, _) = median_time(self.runs, || Pairs::new(&ta, self.a, &tb, self.b).count());
        Ok(VolumeRow {
            scene: self.scene.to_string(),
            volume: B::NAME.to_string(),
            builder: builder_name.to_string(),
            build_ms: build.as_secs_f64() * 1e3,
            sah_cost: ta.stats().sah_cost,
            bv_tests: counts.bv_tests,
            prim_tests: counts.prim_tests,
            query_ms: query.as_secs_f64() * 1e3,
            verified: pairs == self.reference,
        })
    }
}

/// The rows as a markdown table.
pub fn render(rows: &[VolumeRow]) -> String {
    let mut t = String::from(
        "| scene | volume | builder | build ms | SAH | Nv | Np | pair query ms | exact |\n|---|---|---|---:|---:|---:|---:|---:|---|\n",
    );
    for r in rows {
        t += &format!(
            "| {} | {} | {} | {:.2} | {:.2} | {} | {} | {:.3} | {} |\n",
            r.scene,
            r.volume,
            r.builder,
            r.build_ms,
            r.sah_cost,
            r.bv_tests,
            r.prim_tests,
            r.query_ms,
            if r.verified { "yes" } else { "NO" }
        );
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_volume_answers_exactly_and_exact_measures_change_only_bottom_up_kdops() {
        let (a, b) = crate::scene::rock_pair(2);
        let rows = measure("rocks", &a, &b, 1, true).unwrap();
        assert_eq!(rows.len(), 12);
        assert!(rows.iter().all(|r| r.verified), "{}", render(&rows));
        // Top-down trees of every volume share their topology (the builder
        // scores primitive boxes) and the larger-volume rule compares boxes
        // for k-DOPs, so the 26-DOP tree's walk is the box tree's with
        // more pruned: never more tests of either kind.
        let get = |v: &str, b: &str| {
            rows.iter()
                .find(|r| r.volume == v && r.builder == b)
                .unwrap()
        };
        let (aabb, dop26) = (get("aabb", "sah"), get("26-dop", "sah"));
        assert!(dop26.prim_tests <= aabb.prim_tests, "{}", render(&rows));
        assert!(dop26.bv_tests <= aabb.bv_tests, "{}", render(&rows));
        // Exact measures build another bottom-up tree (its exact SAH differs).
        let (boxed, exact) = (get("26-dop", "ploc-r1"), get("26-dop-exact", "ploc-r1"));
        assert_ne!(exact.sah_cost, boxed.sah_cost, "{}", render(&rows));
        assert_eq!(render(&rows).lines().count(), rows.len() + 2);
    }
}
