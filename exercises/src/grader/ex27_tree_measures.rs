//! Exercise 27: measuring a tree. The checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 27.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 27,
            name: "depths: the root at 0, the mean over leaves (not primitives), trees deeper than 32",
            points: 4,
            run: |e| {
                // The grader's answers agree with the library's `Bvh::stats`.
                let agree = on_measured_trees(|tree| {
                    let (want, stats) = (Reference.tree_measures(tree), tree.stats());
                    want.max_depth == stats.max_depth
                        && close(want.mean_leaf_depth, stats.mean_leaf_depth)
                });
                if !agree {
                    return fail("the grader disagrees with Bvh::stats on depths");
                }
                each_tree(|what, tree| {
                    let (got, want) = (e.tree_measures(tree), Reference.tree_measures(tree));
                    let call = format!("tree_measures({what})");
                    same(format!("{call}.max_depth"), want.max_depth, got.max_depth)
                        && (close(got.mean_leaf_depth, want.mean_leaf_depth)
                            || fail(format!(
                                "{call}.mean_leaf_depth returned {}, expected {} (each leaf \
                                 counts once, whatever it holds)",
                                got.mean_leaf_depth, want.mean_leaf_depth
                            )))
                })
            },
        },
        Check {
            exercise: 27,
            name: "SAH cost: internal nodes once, leaves times their size, areas relative to the root in f64",
            points: 4,
            run: |e| {
                // The grader's answers agree with the library's `Bvh::stats`.
                let agree = on_measured_trees(|tree| {
                    let want = Reference.tree_measures(tree).sah_cost;
                    (want - tree.stats().sah_cost).abs() <= 1e-4 * want.max(1.0)
                });
                if !agree {
                    return fail("the grader disagrees with Bvh::stats on SAH costs");
                }
                each_tree(|what, tree| {
                    let (got, want) = (e.tree_measures(tree), Reference.tree_measures(tree));
                    close(got.sah_cost, want.sah_cost)
                        || fail(format!(
                            "tree_measures({what}).sah_cost returned {}, expected {}",
                            got.sah_cost, want.sah_cost
                        ))
                })
            },
        },
        Check {
            exercise: 27,
            name: "edge cases: the empty tree, one leaf of three (cost 3), a flat root (every ratio 1)",
            points: 2,
            run: |e| {
                let empty = Bvh::<Aabb>::from_raw_parts(&[], &[], 0);
                let zero = crate::TreeMeasures::default();
                if !same("tree_measures(an empty tree)", zero, e.tree_measures(&empty)) {
                    return false;
                }
                // One leaf of three: depth 0, and the SAH counts its three tests.
                let tris = &measured_trees()[1].0;
                let mut nodes = vec![Node::<Aabb>::EMPTY; 1];
                let mut idx = vec![0u32; tris.len()];
                let one = TopDown::sah()
                    .with_max_leaf_size(8)
                    .build(tris, &mut nodes, &mut idx)
                    .is_ok_and(|t| {
                        let want = crate::TreeMeasures {
                            max_depth: 0,
                            mean_leaf_depth: 0.0,
                            sah_cost: 3.0,
                        };
                        same("tree_measures(a tree that is one leaf of 3 triangles)", want, e.tree_measures(&t))
                    });
                // Eight points on a line, leaves of one: every box is flat
                // (area 0), so 7 internal nodes count 1 and 8 leaves 1 each.
                let line: Vec<Vec3> = (0..8).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
                let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(8)];
                let mut idx = vec![0u32; 8];
                one && TopDown::median()
                    .with_max_leaf_size(1)
                    .build(&line, &mut nodes, &mut idx)
                    .is_ok_and(|t| {
                        let want = crate::TreeMeasures {
                            max_depth: 3,
                            mean_leaf_depth: 3.0,
                            sah_cost: 15.0,
                        };
                        same(
                            "tree_measures(a balanced tree over 8 points on a line, leaves of one)",
                            want,
                            e.tree_measures(&t),
                        )
                    })
            },
        },
    ]
}

/// Builds each tree of [`measured_trees`] and a few more (a row of points
/// 40 deep, points on a line, points 6e38 apart) and asks `check` about it
/// with a description; false if a build fails or an answer is false.
pub(super) fn each_tree(check: impl Fn(&str, &Bvh<Aabb>) -> bool) -> bool {
    let names = [
        "an empty tree",
        "a tree that is one leaf of 3 triangles",
        "an SAH tree over a row of 40 triangles, leaves of one",
        "an SAH tree over 300 scattered triangles, leaf size 4",
        "an SAH tree over 50 triangles spread over 1e30, leaf size 2",
    ];
    let measured = measured_trees()
        .iter()
        .zip(names)
        .all(|((tris, leaf), what)| {
            let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(tris.len())];
            let mut idx = vec![0u32; tris.len()];
            match TopDown::sah()
                .with_max_leaf_size(*leaf)
                .build(tris, &mut nodes, &mut idx)
            {
                Ok(tree) => check(what, &tree),
                Err(_) => fail(format!("the grader could not build {what}")),
            }
        });
    let deep: Vec<Vec3> = (0..40)
        .map(|i| Vec3::new(1.5f32.powi(i), 0.0, 0.0))
        .collect();
    let line: Vec<Vec3> = (0..20).map(|i| Vec3::new(0.0, i as f32, 0.0)).collect();
    let spatial = TopDown {
        split: bvhkit::SplitPoint::SpatialMedian,
        ..TopDown::median()
    };
    let extra = [
        (
            "a tree over 40 points at 1.5^i on a line, cut at the spatial middle (39 deep), leaves of one",
            deep,
            spatial,
        ),
        ("a median tree over 20 points on a line (every box flat), leaves of one", line, TopDown::median()),
    ];
    // Built by hand (builders refuse coordinates past 1e32): a root 6e38
    // wide, wider than f32 holds, over a leaf of one and a leaf of two.
    let wide = |lo: f32, hi: f32, count: u32, first: u32| Node {
        bv: b([lo, -3.0e38, 0.0], [hi, 3.0e38, 1.0]),
        first,
        count,
    };
    let nodes = [
        wide(-3.0e38, 3.0e38, 0, 1),
        wide(-3.0e38, 0.0, 1, 0),
        wide(-1.0, 3.0e38, 2, 1),
    ];
    let wide_tree = Bvh::from_raw_parts(&nodes, &[0, 1, 2], 1);
    measured
        && extra.iter().all(|(what, pts, builder)| {
            let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(pts.len())];
            let mut idx = vec![0u32; pts.len()];
            match builder
                .with_max_leaf_size(1)
                .build(pts, &mut nodes, &mut idx)
            {
                Ok(tree) => check(what, &tree),
                Err(err) => fail(format!("the grader could not build {what}: {err}")),
            }
        })
        && check(
            "a root 6e38 wide and tall (past f32's range) over a leaf of one and a leaf of two",
            &wide_tree,
        )
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 9;

    pub fn tree_measures(which: u32, tree: &Bvh<Aabb>) -> crate::TreeMeasures {
        let right = Reference.tree_measures(tree);
        let nodes = tree.nodes();
        if nodes.is_empty() {
            // No guard for the empty tree: the mean is 0 / 0.
            if which == 9 {
                return crate::TreeMeasures {
                    mean_leaf_depth: f64::NAN,
                    ..right
                };
            }
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
            // Areas in f32: 1e30 wide, they overflow to infinity.
            5 => {
                let area32 = |b: &Aabb| {
                    let e = b.max - b.min;
                    (2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)) as f64
                };
                let root = area32(&nodes[0].bv);
                crate::TreeMeasures {
                    sah_cost: all
                        .iter()
                        .map(|(_, n)| area32(&n.bv) / root * n.count.max(1) as f64)
                        .sum(),
                    ..right
                }
            }
            // Extents subtracted in f32, then widened: 6e38 wide is infinite.
            6 => {
                let area = |b: &Aabb| {
                    let e = (b.max - b.min).as_dvec3();
                    2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
                };
                let root = area(&nodes[0].bv);
                crate::TreeMeasures {
                    sah_cost: all
                        .iter()
                        .map(|(_, n)| area(&n.bv) / root * n.count.max(1) as f64)
                        .sum(),
                    ..right
                }
            }
            // Divides by the root's area even when it is 0.
            7 => crate::TreeMeasures {
                sah_cost: all
                    .iter()
                    .map(|(_, n)| area(&n.bv) / root * n.count.max(1) as f64)
                    .sum(),
                ..right
            },
            // The mean depth over all nodes, not over leaves.
            8 => crate::TreeMeasures {
                mean_leaf_depth: all.iter().map(|(d, _)| *d as f64).sum::<f64>() / all.len() as f64,
                ..right
            },
            _ => right,
        }
    }
}
