//! Exercise 40: leaf collapse, the cheapest cut of a one-primitive-per-leaf
//! tree. The checks, and the plausible wrong answers they must reject. The
//! trees are real: PLOC trees of a rock and of a row of boxes as the
//! merges made them, and a top-down tree whose leaves already hold two.

use super::common::*;
use bvhkit::builders::{BottomUp, Collapse, MergeMetric, Method};
use bvhkit::{Bvh, Primitive};

/// The (largest leaf, traversal cost) pairs every tree is graded with.
const SETTINGS: [(u32, f64); 5] = [(4, 2.0), (4, 1.0), (8, 3.0), (1, 2.0), (2, 0.5)];

/// The checks of exercise 40.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 40,
            name: "the best cut's cost on built trees, for five limits and node prices",
            points: 4,
            run: |e| {
                each_tree(|name, tree| {
                    SETTINGS.iter().all(|&(max, ct)| {
                        let want = Reference.best_cut_cost(tree, max, ct);
                        let got = e.best_cut_cost(tree, max, ct);
                        close(got, want)
                            || fail(format!(
                                "best_cut_cost({name}, max_leaf_size {max}, traversal_cost {ct}) \
                                 returned {got}, expected {want}"
                            ))
                    })
                })
            },
        },
        Check {
            exercise: 40,
            name: "a tie makes a leaf; an empty tree costs 0",
            points: 2,
            run: |e| {
                let twins = twins();
                let tree = twins.tree();
                // Two leaves of one box each: 2A either way when a visit is free.
                let area = f64::from(unit_at(0.0).surface_area());
                same(
                    "best_cut_cost(an empty tree, 4, 2.0)",
                    0.0,
                    e.best_cut_cost(&Bvh::from_raw_parts(&[], &[], 0), 4, 2.0),
                ) && close(e.best_cut_cost(&tree, 2, 0.0), 2.0 * area)
                    && same(
                        "collapsed_leaves(two leaves holding the same box, max_leaf_size 2, \
                         traversal_cost 0.0)",
                        vec![(0, 2)],
                        e.collapsed_leaves(&tree, 2, 0.0),
                    )
                    && same(
                        "collapsed_leaves(an empty tree, 4, 2.0)",
                        vec![],
                        e.collapsed_leaves(&Bvh::from_raw_parts(&[], &[], 0), 4, 2.0),
                    )
            },
        },
        Check {
            exercise: 40,
            name: "the leaves of the best cut on built trees",
            points: 4,
            run: |e| {
                each_tree(|name, tree| {
                    SETTINGS.iter().all(|&(max, ct)| {
                        same_list(
                            format!(
                                "collapsed_leaves({name}, max_leaf_size {max}, traversal_cost {ct})"
                            ),
                            &Reference.collapsed_leaves(tree, max, ct),
                            &e.collapsed_leaves(tree, max, ct),
                            |&(first, count)| format!("(first {first}, count {count})"),
                        )
                    })
                })
            },
        },
        Check {
            exercise: 40,
            name: "a collapsed subtree is one leaf, with its primitives' run",
            points: 2,
            run: |e| {
                // Four unit boxes staggered by 0.1, a balanced tree over them:
                // each half and then the whole are cheaper as leaves.
                let cluster = Tree::build(
                    (0..4).map(|i| unit_at(i as f32 * 0.1)).collect(),
                    BottomUp::exhaustive(MergeMetric::SurfaceArea),
                );
                let tree = cluster.tree();
                same(
                    "collapsed_leaves(four unit boxes staggered by 0.1, max_leaf_size 4, \
                     traversal_cost 1.0)",
                    vec![(0, 4)],
                    e.collapsed_leaves(&tree, 4, 1.0),
                ) && same(
                    "collapsed_leaves(the same, max_leaf_size 1, traversal_cost 1.0)",
                    vec![(0, 1), (1, 1), (2, 1), (3, 1)],
                    e.collapsed_leaves(&tree, 1, 1.0),
                )
            },
        },
    ]
}

/// A tree of two leaves holding the same unit box.
fn twins() -> Tree {
    Tree::build(
        vec![unit_at(0.0), unit_at(0.0)],
        BottomUp::exhaustive(MergeMetric::SurfaceArea),
    )
}

/// A bottom-up tree with one primitive per leaf, with its storage.
struct Tree {
    nodes: Vec<bvhkit::Node<Aabb>>,
    indices: Vec<u32>,
    depth: usize,
}

impl Tree {
    fn build(boxes: Vec<Aabb>, builder: BottomUp) -> Tree {
        let builder = BottomUp {
            collapse: Collapse::None,
            ..builder
        };
        let owned = bvhkit_std::OwnedBvh::<Aabb>::build_bottom_up(&builder, &boxes)
            .expect("the grader's scenes build");
        let view = owned.view();
        Tree {
            nodes: view.nodes().to_vec(),
            indices: view.indices().to_vec(),
            depth: view.depth(),
        }
    }

    fn tree(&self) -> Bvh<'_, Aabb> {
        Bvh::from_raw_parts(&self.nodes, &self.indices, self.depth)
    }
}

/// Calls `check(name, tree)` on the graded trees: PLOC (radius 4) over a
/// 320-triangle rock and over 37 boxes in a row, one primitive per leaf, and
/// a top-down tree of the rock with leaves of 2.
fn each_tree(check: impl Fn(&str, &Bvh<Aabb>) -> bool) -> bool {
    let rock: Vec<Aabb> = bvhkit_std::scene::rock(2, 3)
        .iter()
        .map(|t| t.bounds())
        .collect();
    let row: Vec<Aabb> = (0..37)
        .map(|i| b([i as f32 * 1.3, 0.0, 0.0], [i as f32 * 1.3 + 1.0, 1.0, 1.0]))
        .collect();
    let ploc = BottomUp {
        method: Method::Ploc { radius: 4 },
        ..BottomUp::default()
    };
    let top_down = {
        let mut nodes = vec![bvhkit::Node::<Aabb>::EMPTY; bvhkit::max_nodes(rock.len())];
        let mut idx = vec![0u32; rock.len()];
        let (n, depth) = TopDown::sah()
            .with_max_leaf_size(2)
            .build(&rock, &mut nodes, &mut idx)
            .map(|t| (t.node_count(), t.depth()))
            .expect("the grader's rock builds");
        nodes.truncate(n);
        Tree {
            nodes,
            indices: idx,
            depth,
        }
    };
    let trees = [
        (
            "a PLOC tree of a 320-triangle rock",
            Tree::build(rock, ploc),
        ),
        ("a PLOC tree of 37 boxes in a row", Tree::build(row, ploc)),
        ("a top-down tree of the rock with leaves of 2", top_down),
    ];
    trees.iter().all(|(name, t)| check(name, &t.tree()))
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 8;

    /// `(cost, primitives, first, leaf)` under wrong answer `which`.
    fn cut(which: u32, nodes: &[Node<Aabb>], x: u32, max: u32, ct: f64) -> (f64, u32, u32, bool) {
        let n = &nodes[x as usize];
        let area = f64::from(n.bv.surface_area());
        let Some((l, r)) = n.children() else {
            return (f64::from(n.count) * area, n.count, n.first, true);
        };
        let (lc, ln, lf, _) = cut(which, nodes, l, max, ct);
        let (rc, rn, rf, _) = cut(which, nodes, r, max, ct);
        let count = ln + rn;
        // The children as they are, one leaf each, not at their best.
        let as_they_are = |c: u32| {
            let child = &nodes[c as usize];
            f64::from(child.count.max(1)) * f64::from(child.bv.surface_area())
        };
        let keep = match which {
            2 => ct * area + as_they_are(l) + as_they_are(r),
            3 => area + lc + rc,
            _ => ct * area + lc + rc,
        };
        let leaf = f64::from(count) * area;
        let collapse = match which {
            // Every subtree small enough becomes a leaf, whatever it costs.
            1 => count <= max,
            4 => count <= max && leaf < keep,
            5 => leaf <= keep,
            _ => count <= max && leaf <= keep,
        };
        let first = if which == 8 { n.first } else { lf.min(rf) };
        if collapse {
            (leaf, count, first, true)
        } else {
            (keep, count, first, false)
        }
    }

    pub fn best_cut_cost(which: u32, tree: &Bvh<Aabb>, max: u32, ct: f64) -> f64 {
        if !(1..=6).contains(&which) || tree.node_count() == 0 {
            return Reference.best_cut_cost(tree, max, ct);
        }
        let nodes = tree.nodes();
        let (cost, _, _, leaf) = cut(which, nodes, 0, max, ct);
        match which {
            // The root's own visit left out.
            6 if !leaf => cost - ct * f64::from(nodes[0].bv.surface_area()),
            _ => cost,
        }
    }

    pub fn collapsed_leaves(which: u32, tree: &Bvh<Aabb>, max: u32, ct: f64) -> Vec<(u32, u32)> {
        if !matches!(which, 1..=5 | 7 | 8) || tree.node_count() == 0 {
            return Reference.collapsed_leaves(tree, max, ct);
        }
        let nodes = tree.nodes();
        let mut out = Vec::new();
        let mut stack = vec![0u32];
        while let Some(x) = stack.pop() {
            let (_, count, first, leaf) = cut(which, nodes, x, max, ct);
            match nodes[x as usize].children() {
                Some((l, r)) if !leaf || which == 7 => {
                    // 7: every node cheaper as a leaf reported, nested ones too.
                    if leaf {
                        out.push((first, count));
                    }
                    stack.extend([l, r]);
                }
                _ => out.push((first, count)),
            }
        }
        out.sort_unstable();
        out
    }
}
