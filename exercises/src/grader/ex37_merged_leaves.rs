//! Exercise 37: fuller quantized records, a small subtree as one leaf slot.
//! The checks, and the plausible wrong answers they must reject.

use super::common::*;
use super::ex27_tree_measures::each_tree;

/// The checks of exercise 37.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 37,
            name: "a leaf is its own run, whatever the limit (0 included)",
            points: 2,
            run: |e| {
                each_tree(|what, tree| {
                    tree.nodes().iter().enumerate().all(|(i, n)| {
                        !n.is_leaf()
                            || [0, 1, 8].into_iter().all(|merge| {
                                same(
                                    format!("merged_run({what}, leaf {i}, merge {merge})"),
                                    Some((n.first, n.count)),
                                    e.merged_run(tree, i as u32, merge),
                                )
                            })
                    })
                })
            },
        },
        Check {
            exercise: 37,
            name: "internal nodes of built trees: merged up to the limit (inclusive), by primitives, 0 merges nothing",
            points: 4,
            run: |e| {
                each_tree(|what, tree| {
                    (0..tree.node_count() as u32).all(|i| {
                        [0, 2, 3, 4, 8, 16].into_iter().all(|merge| {
                            same(
                                format!("merged_run({what}, node {i}, merge {merge})"),
                                Reference.merged_run(tree, i, merge),
                                e.merged_run(tree, i, merge),
                            )
                        })
                    })
                })
            },
        },
        Check {
            exercise: 37,
            name: "trees written by hand: a gap in the entries refuses the merge; the run starts at the smallest entry",
            points: 4,
            run: |e| {
                hand_trees().iter().all(|(what, nodes, idx, want)| {
                    let tree = Bvh::from_raw_parts(nodes, idx, 2);
                    same(format!("merged_run({what}, node 1, merge 8)"), *want, e.merged_run(&tree, 1, 8))
                })
            },
        },
    ]
}

/// A tree written by hand: `(what, nodes, indices, node 1's run under merge 8)`.
type HandTree = (&'static str, Vec<Node<Aabb>>, Vec<u32>, Option<(u32, u32)>);

/// Three-leaf trees whose node 1 holds two leaves of one entry each.
fn hand_trees() -> Vec<HandTree> {
    let leaf = |first: u32| Node {
        first,
        count: 1,
        ..node([0.0; 3], [1.0; 3], true)
    };
    let inner = |first: u32| Node {
        first,
        ..node([0.0; 3], [1.0; 3], false)
    };
    vec![
        (
            "a tree whose node 1 holds entries 0 and 2 (a gap at 1)",
            vec![inner(1), inner(3), leaf(1), leaf(0), leaf(2)],
            vec![0, 1, 2],
            None,
        ),
        (
            "a tree whose node 1 holds entries 1 and 0 (left child's entry after the right's)",
            vec![inner(1), inner(3), leaf(2), leaf(1), leaf(0)],
            vec![0, 1, 2],
            Some((0, 2)),
        ),
        (
            "a tree whose node 1 holds entries 1 and 2",
            vec![inner(1), inner(3), leaf(0), leaf(1), leaf(2)],
            vec![0, 1, 2],
            Some((1, 2)),
        ),
    ]
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 7;

    /// The leaves under `node`: `(first, count)` each, left to right.
    fn leaves(tree: &Bvh<Aabb>, node: u32) -> Vec<(u32, u32)> {
        let n = tree.nodes()[node as usize];
        match n.children() {
            None => vec![(n.first, n.count)],
            Some((l, r)) => [leaves(tree, l), leaves(tree, r)].concat(),
        }
    }

    pub fn merged_run(which: u32, tree: &Bvh<Aabb>, node: u32, merge: u32) -> Option<(u32, u32)> {
        let right = Reference.merged_run(tree, node, merge);
        let is_leaf = tree.nodes()[node as usize].is_leaf();
        let under = leaves(tree, node);
        let count: u32 = under.iter().map(|l| l.1).sum();
        let lo = under.iter().map(|l| l.0).min().unwrap_or(0);
        match which {
            // Strictly under the limit: a subtree of exactly `merge` stays a record.
            1 if !is_leaf && count == merge => None,
            // No contiguity test: the smallest entry and the count, gap or not.
            2 if !is_leaf && count <= merge => Some((lo, count)),
            // Only internal nodes merge: a leaf is "not a merge".
            3 if is_leaf => None,
            // The run starts at the leftmost leaf's entry.
            4 => right.map(|(_, c)| (under[0].0, c)),
            // Counts leaves, not primitives, against the limit.
            5 if !is_leaf => {
                let contiguous = under.iter().map(|l| l.0 + l.1).max().unwrap_or(0) - lo == count;
                (under.len() as u32 <= merge && contiguous).then_some((lo, count))
            }
            // A limit of 0 read as "no limit".
            6 if merge == 0 && !is_leaf => Reference.merged_run(tree, node, u32::MAX),
            // The limit applied to leaves too: a leaf over the limit is "not a run".
            7 if is_leaf && count > merge => None,
            _ => right,
        }
    }
}
