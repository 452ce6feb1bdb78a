//! Exercise 27: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 27.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 27,
            name: "depths: the root at 0, the mean over leaves (not primitives), a one-leaf tree",
            points: 5,
            run: |e| {
                let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1.0);
                on_measured_trees(|tree| {
                    let (got, want) = (e.tree_measures(tree), Reference.tree_measures(tree));
                    let stats = tree.stats();
                    got.max_depth == want.max_depth
                        && close(got.mean_leaf_depth, want.mean_leaf_depth)
                        && want.max_depth == stats.max_depth
                        && close(want.mean_leaf_depth, stats.mean_leaf_depth)
                }) && {
                    // One leaf of three: depth 0, and the SAH counts its three tests.
                    let tris = &measured_trees()[1].0;
                    let mut nodes = vec![Node::<Aabb>::EMPTY; 1];
                    let mut idx = vec![0u32; tris.len()];
                    TopDown::sah()
                        .with_max_leaf_size(8)
                        .build(tris, &mut nodes, &mut idx)
                        .is_ok_and(|t| {
                            let m = e.tree_measures(&t);
                            m.max_depth == 0 && m.mean_leaf_depth == 0.0 && close(m.sah_cost, 3.0)
                        })
                }
            },
        },
        Check {
            exercise: 27,
            name: "SAH cost: internal nodes once, leaves times their size, areas relative to the root in f64",
            points: 5,
            run: |e| {
                let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1.0);
                on_measured_trees(|tree| {
                    let (got, want) = (e.tree_measures(tree), Reference.tree_measures(tree));
                    close(got.sah_cost, want.sah_cost)
                        && (want.sah_cost - tree.stats().sah_cost).abs()
                            <= 1e-4 * want.sah_cost.max(1.0)
                })
            },
        },
    ]
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 4;

    pub fn tree_measures(which: u32, tree: &Bvh<Aabb>) -> crate::TreeMeasures {
        let right = Reference.tree_measures(tree);
        let nodes = tree.nodes();
        if nodes.is_empty() {
            return right;
        }
        let area = |b: &Aabb| {
            let e = b.max.as_dvec3() - b.min.as_dvec3();
            2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
        };
        let root = area(&nodes[0].bv);
        // (depth, node) for every node, the root at 0.
        let mut all = Vec::new();
        let mut stack = vec![(0u32, 0usize)];
        while let Some((i, d)) = stack.pop() {
            all.push((d, &nodes[i as usize]));
            if let Some((l, r)) = nodes[i as usize].children() {
                stack.extend([(l, d + 1), (r, d + 1)]);
            }
        }
        let leaves = || all.iter().filter(|(_, n)| n.is_leaf());
        match which {
            // The mean weighted by primitives.
            1 => {
                let prims: f64 = leaves().map(|(_, n)| n.count as f64).sum();
                let sum: f64 = leaves().map(|(d, n)| *d as f64 * n.count as f64).sum();
                crate::TreeMeasures {
                    mean_leaf_depth: sum / prims,
                    ..right
                }
            }
            // Leaves counted once, not times their size.
            2 => crate::TreeMeasures {
                sah_cost: all.iter().map(|(_, n)| area(&n.bv) / root).sum(),
                ..right
            },
            // Internal nodes left out.
            3 => crate::TreeMeasures {
                sah_cost: leaves()
                    .map(|(_, n)| area(&n.bv) / root * n.count as f64)
                    .sum(),
                ..right
            },
            // The root at depth 1.
            4 => crate::TreeMeasures {
                max_depth: right.max_depth + 1,
                mean_leaf_depth: right.mean_leaf_depth + 1.0,
                ..right
            },
            _ => right,
        }
    }
}
