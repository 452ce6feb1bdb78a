//! The ground truth every crate's answers are checked against, computed
//! without any tree so that no crate's traversal can share a mistake with it.
//!
//! Pairs: a uniform grid over B's boxes; each candidate is tested with the
//! closed box test, and a pair is counted only in the cell that holds the
//! low corner of the two boxes' intersection, so it is counted once.
//! Rays: every triangle tested, on a sample of the rays.

use crate::common::{boxes_overlap, hit_triangle, PairSum, RayHit, Scene};
use bvhkit::glam::{IVec3, Vec3};
use std::collections::HashMap;

/// Every pair `(i, j)` of triangles of `a` and `b` that intersect, sorted:
/// the box pairs of [`pairs`]' grid, each decided by the exact triangle
/// test (`bvhkit::Exact`, exact predicates): the definition of the answer.
pub fn exact_pairs(scene: &Scene) -> Vec<(u32, u32)> {
    use bvhkit::Answer;
    let mut out = Vec::new();
    grid_pairs(scene, |i, j| {
        if bvhkit::Exact.accept(&scene.a[i as usize], &scene.b[j as usize]) {
            out.push((i, j));
        }
    });
    out.sort_unstable();
    out
}

/// Every pair `(i, j)` whose boxes overlap, with its checksum.
pub fn pairs(scene: &Scene) -> PairSum {
    let mut sum = PairSum::default();
    grid_pairs(scene, |i, j| sum.add(i, j));
    sum
}

/// Calls `f` once for every pair `(i, j)` whose boxes overlap.
fn grid_pairs(scene: &Scene, mut f: impl FnMut(u32, u32)) {
    let (a, b) = (&scene.boxes_a, &scene.boxes_b);
    if a.is_empty() || b.is_empty() {
        return;
    }
    // Cells about twice the mean box size: few cells per box, few boxes per cell.
    let mean: Vec3 = b.iter().map(|q| q.max - q.min).sum::<Vec3>() / b.len() as f32;
    let cell = (mean.max_element() * 2.0).max(f32::MIN_POSITIVE);
    let origin = b.iter().fold(Vec3::INFINITY, |m, q| m.min(q.min));
    let cell_of = |p: Vec3| ((p - origin) / cell).floor().as_ivec3();
    let mut grid: HashMap<IVec3, Vec<u32>> = HashMap::new();
    for (j, q) in b.iter().enumerate() {
        for_cells(cell_of(q.min), cell_of(q.max), |c| {
            grid.entry(c).or_default().push(j as u32)
        });
    }
    for (i, p) in a.iter().enumerate() {
        for_cells(cell_of(p.min), cell_of(p.max), |c| {
            for &j in grid.get(&c).map_or(&[][..], Vec::as_slice) {
                let q = &b[j as usize];
                if boxes_overlap(p, q) && cell_of(p.min.max(q.min)) == c {
                    f(i as u32, j);
                }
            }
        });
    }
}

fn for_cells(lo: IVec3, hi: IVec3, mut f: impl FnMut(IVec3)) {
    for x in lo.x..=hi.x {
        for y in lo.y..=hi.y {
            for z in lo.z..=hi.z {
                f(IVec3::new(x, y, z));
            }
        }
    }
}

/// The closest hit of ray `k`, testing every triangle.
pub fn ray(scene: &Scene, k: usize) -> RayHit {
    let ray = &scene.rays[k];
    let mut best: RayHit = None;
    for i in 0..scene.a.len() as u32 {
        let t_max = best.map_or(f32::INFINITY, |b| b.1);
        if let Some(t) = hit_triangle(&scene.a, i, ray, t_max) {
            if best.is_none_or(|b| t < b.1) {
                best = Some((i, t));
            }
        }
    }
    best
}

/// Whether two answers for one ray agree: the same distance (two triangles
/// hit at the same distance, e.g. on a shared edge, may be named either).
pub fn same_hit(x: &RayHit, y: &RayHit) -> bool {
    x.map(|h| h.1) == y.map(|h| h.1)
}

#[cfg(test)]
mod tests {
    use crate::common::reference;

    #[test]
    fn grid_pairs_equal_the_quadratic_reference() {
        let scene = reference::small_scene();
        assert_eq!(super::pairs(&scene), reference::pairs(&scene));
    }

    /// The brute-force ray answer equals bvhkit's own brute force
    /// (`brute_force::ray_closest`), an implementation it shares no code with.
    #[test]
    fn brute_rays_equal_the_core_brute_force() {
        let scene = reference::small_scene();
        let mut hits = 0;
        for (k, ray) in scene.rays.iter().enumerate() {
            let want = bvhkit::brute_force::ray_closest(&scene.a, ray).map(|h| (h.prim, h.t));
            let got = super::ray(&scene, k);
            assert!(
                super::same_hit(&got, &want),
                "ray {k}: {got:?} against {want:?}"
            );
            hits += usize::from(got.is_some());
        }
        assert!(hits > 10, "too few hits to mean anything: {hits}");
    }
}
