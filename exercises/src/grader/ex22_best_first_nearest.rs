//! Exercise 22: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 22.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 22,
            name: "the nearest primitive and its distance, as brute force finds it",
            points: 5,
            run: |e| {
                let mut r = Rng(22);
                nearest_cases().iter().all(|t| {
                    let tree = t.bvh();
                    (0..40).all(|_| {
                        let p = r.point(14.0, Vec3::new(4.5, 4.5, 1.0));
                        let dist = |b: &Aabb| b.distance_squared(p).sqrt();
                        let want = t.prims.iter().map(dist).fold(f32::INFINITY, f32::min);
                        match e.best_first_nearest(&tree, &t.prims, p) {
                            None => t.prims.is_empty(),
                            Some((k, d, _)) => {
                                let tol = 1e-5 * want.max(1.0);
                                (dist(&t.prims[k as usize]) - want).abs() <= tol
                                    && (d - want).abs() <= tol
                            }
                        }
                    })
                })
            },
        },
        Check {
            exercise: 22,
            name: "best-first: takes few nodes (at most 1.5x the reference's + 2)",
            points: 5,
            run: |e| {
                let mut r = Rng(23);
                nearest_cases()
                    .iter()
                    .filter(|t| !t.prims.is_empty())
                    .all(|t| {
                        let tree = t.bvh();
                        (0..40).all(|_| {
                            let p = r.point(14.0, Vec3::new(4.5, 4.5, 1.0));
                            let taken = |x: &dyn Exercises| {
                                x.best_first_nearest(&tree, &t.prims, p)
                                    .map_or(usize::MAX, |a| a.2)
                            };
                            taken(e) * 2 <= taken(&Reference) * 3 + 4
                        })
                    })
            },
        },
    ]
}

/// Trees for the nearest-primitive search: empty, and grids of boxes.
fn nearest_cases() -> Vec<Tree> {
    vec![
        Tree::new(vec![], 1),
        Tree::new(boxes(1, 31, Vec3::ZERO), 1),
        Tree::new(boxes(60, 37, Vec3::ZERO), 1),
        Tree::new(boxes(300, 41, Vec3::ZERO), 4),
    ]
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 2;

    pub fn best_first_nearest(
        which: u32,
        tree: &Bvh<Aabb>,
        prims: &[Aabb],
        p: Vec3,
    ) -> Option<(u32, f32, usize)> {
        match which {
            // Depth-first over every node: the right answer, all the work.
            1 => {
                let best = Reference.best_first_nearest(tree, prims, p)?;
                Some((best.0, best.1, tree.nodes().len()))
            }
            // Greedy: into the nearer child down to one leaf, whose
            // primitive is near but not always the nearest.
            2 => {
                let nodes = tree.nodes();
                let dist = |b: &Aabb| b.distance_squared(p).sqrt();
                let mut i = 0usize;
                let mut taken = 0;
                loop {
                    taken += 1;
                    let node = nodes.get(i)?;
                    match node.children() {
                        Some((l, r)) => {
                            let (dl, dr) =
                                (dist(&nodes[l as usize].bv), dist(&nodes[r as usize].bv));
                            i = if dl <= dr { l } else { r } as usize;
                        }
                        None => {
                            let k = tree.indices()[node.first as usize];
                            return Some((k, dist(&prims[k as usize]), taken));
                        }
                    }
                }
            }
            _ => Reference.best_first_nearest(tree, prims, p),
        }
    }
}
