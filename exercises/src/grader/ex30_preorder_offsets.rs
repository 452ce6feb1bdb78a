//! Exercise 30: offsets instead of pointers. The checks, and the plausible wrong answers they must reject.

use super::common::*;
use super::ex27_tree_measures::each_tree;

/// The checks of exercise 30.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 30,
            name:
                "preorder offsets as built: 1 + the left subtree, as the Preorder layout links them",
            points: 4,
            run: |e| {
                use bvhkit::layout::{PreNode, Preorder};
                on_all_trees(|what, tree| {
                    let mut recs = vec![PreNode::<Aabb, u32>::EMPTY; tree.node_count()];
                    let Ok(pre) = Preorder::from_bvh(tree, &mut recs) else {
                        return fail(format!("the grader could not lay out {what} in preorder"));
                    };
                    let library = (pre.records().iter().enumerate())
                        .filter_map(|(i, r)| r.right().map(|right| right - i))
                        .max()
                        .unwrap_or(0);
                    same(
                        format!("preorder_offsets({what}).0 (as built)"),
                        library,
                        e.preorder_offsets(tree).0,
                    )
                })
            },
        },
        Check {
            exercise: 30,
            name: "preorder offsets with the smaller subtree first: 1 + the smaller side",
            points: 4,
            run: |e| {
                on_all_trees(|what, tree| {
                    same(
                        format!("preorder_offsets({what}).1 (smaller first)"),
                        Reference.preorder_offsets(tree).1,
                        e.preorder_offsets(tree).1,
                    )
                })
            },
        },
        Check {
            exercise: 30,
            name: "no internal node (an empty tree, one leaf): (0, 0)",
            points: 2,
            run: |e| {
                let empty = Bvh::<Aabb>::from_raw_parts(&[], &[], 0);
                let leaf = [node([0.0; 3], [1.0; 3], true)];
                let one = Bvh::from_raw_parts(&leaf, &[0], 0);
                same(
                    "preorder_offsets(an empty tree)",
                    (0, 0),
                    e.preorder_offsets(&empty),
                ) && same(
                    "preorder_offsets(a tree that is one leaf)",
                    (0, 0),
                    e.preorder_offsets(&one),
                )
            },
        },
    ]
}

/// The trees of exercise 27 (see [`each_tree`]), the lopsided ones, and a
/// small one whose largest offset is below the root: a leaf on the root's
/// left, a balanced subtree of seven nodes on its right.
fn on_all_trees(check: impl Fn(&str, &Bvh<Aabb>) -> bool) -> bool {
    let unit = |first: u32, count: u32| Node {
        bv: b([0.0; 3], [1.0; 3]),
        first,
        count,
    };
    let nodes = [
        unit(1, 0),
        unit(0, 1),
        unit(3, 0),
        unit(5, 0),
        unit(7, 0),
        unit(1, 1),
        unit(2, 1),
        unit(3, 1),
        unit(4, 1),
    ];
    let small = Bvh::from_raw_parts(&nodes, &[0, 1, 2, 3, 4], 3);
    each_tree(&check)
        && on_lopsided_trees(&check)
        && check(
            "a tree of 9 nodes: a leaf on the root's left, a balanced subtree of 7 on its right",
            &small,
        )
}

/// Trees whose big subtree is sometimes on the left, sometimes on the
/// right: points growing geometrically, split at the spatial median (the
/// top one or two points split off at each level), and the same row
/// reversed.
fn on_lopsided_trees(check: impl Fn(&str, &Bvh<Aabb>) -> bool) -> bool {
    [false, true].iter().all(|&reversed| {
        let pts: Vec<Vec3> = (0..40)
            .map(|i| {
                let x = 1.5f32.powi(i);
                Vec3::new(if reversed { -x } else { x }, 0.0, 0.0)
            })
            .collect();
        let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(pts.len())];
        let mut idx = vec![0u32; pts.len()];
        let what = if reversed {
            "a tree over 40 points at -1.5^i, cut at the spatial middle, leaves of one (the big side on the right)"
        } else {
            "a tree over 40 points at 1.5^i, cut at the spatial middle, leaves of one (the big side on the left)"
        };
        TopDown {
            split: bvhkit::SplitPoint::SpatialMedian,
            ..TopDown::median()
        }
        .with_max_leaf_size(1)
        .build(&pts, &mut nodes, &mut idx)
        .is_ok_and(|tree| check(what, &tree))
    })
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 7;

    pub fn preorder_offsets(which: u32, tree: &Bvh<Aabb>) -> (usize, usize) {
        let right = Reference.preorder_offsets(tree);
        let nodes = tree.nodes();
        let mut size = vec![1usize; nodes.len()];
        for i in (0..nodes.len()).rev() {
            if let Some((l, r)) = nodes[i].children() {
                size[i] = 1 + size[l as usize] + size[r as usize];
            }
        }
        let over = |f: &dyn Fn(usize, usize) -> usize| {
            nodes
                .iter()
                .filter_map(|n| n.children())
                .map(|(l, r)| f(size[l as usize], size[r as usize]))
                .max()
                .unwrap_or(0)
        };
        match which {
            // The size of the left subtree, without the parent's step.
            1 => (over(&|l, _| l), right.1),
            // Counts leaves, not nodes, in the left subtree.
            2 => (over(&|l, _| 1 + l.div_ceil(2)), right.1),
            // The larger subtree first instead of the smaller.
            3 => (right.0, over(&|l, r| 1 + l.max(r))),
            // 1 + the right subtree instead of the left.
            4 => (over(&|_, r| 1 + r), right.1),
            // Only the root's offsets, as if the largest were always there.
            5 => match nodes.first().and_then(|n| n.children()) {
                Some((l, r)) => {
                    let (l, r) = (size[l as usize], size[r as usize]);
                    (1 + l, 1 + l.min(r))
                }
                None => (0, 0),
            },
            // The largest offsets start at 1: a tree without internal nodes gives (1, 1).
            6 => (right.0.max(1), right.1.max(1)),
            // The smaller side without the parent's step.
            7 => (right.0, over(&|l, r| l.min(r))),
            _ => right,
        }
    }
}
