//! Exercise 30: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 30.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 30,
            name:
                "preorder offsets as built: 1 + the left subtree, as the Preorder layout links them",
            points: 5,
            run: |e| {
                use bvhkit::layout::{PreNode, Preorder};
                on_measured_trees(|tree| {
                    let mut recs = vec![PreNode::<Aabb, u32>::EMPTY; tree.node_count()];
                    let Ok(pre) = Preorder::from_bvh(tree, &mut recs) else {
                        return false;
                    };
                    let library = (pre.records().iter().enumerate())
                        .filter_map(|(i, r)| r.right().map(|right| right - i))
                        .max()
                        .unwrap_or(0);
                    e.preorder_offsets(tree).0 == library
                }) && on_lopsided_trees(|tree| {
                    e.preorder_offsets(tree).0 == Reference.preorder_offsets(tree).0
                })
            },
        },
        Check {
            exercise: 30,
            name: "preorder offsets with the smaller subtree first: 1 + the smaller side",
            points: 5,
            run: |e| {
                on_measured_trees(|tree| {
                    e.preorder_offsets(tree) == Reference.preorder_offsets(tree)
                }) && on_lopsided_trees(|tree| {
                    e.preorder_offsets(tree) == Reference.preorder_offsets(tree)
                })
            },
        },
    ]
}

/// Trees whose big subtree is sometimes on the left, sometimes on the
/// right: points growing geometrically, split at the spatial median (the
/// top one or two points split off at each level), and the same row
/// reversed.
fn on_lopsided_trees(check: impl Fn(&Bvh<Aabb>) -> bool) -> bool {
    [false, true].iter().all(|&reversed| {
        let pts: Vec<Vec3> = (0..40)
            .map(|i| {
                let x = 1.5f32.powi(i);
                Vec3::new(if reversed { -x } else { x }, 0.0, 0.0)
            })
            .collect();
        let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(pts.len())];
        let mut idx = vec![0u32; pts.len()];
        TopDown {
            split: bvhkit::SplitPoint::SpatialMedian,
            ..TopDown::median()
        }
        .with_max_leaf_size(1)
        .build(&pts, &mut nodes, &mut idx)
        .is_ok_and(|tree| check(&tree))
    })
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 3;

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
            _ => right,
        }
    }
}
