//! Exercise 28: tri-nodes. The checks, and the plausible wrong answers they must reject.

use super::common::*;
use super::ex27_tree_measures::each_tree;

/// The checks of exercise 28.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 28,
            name: "tri-node records: one per node at an even depth, as TriNodes stores them",
            points: 4,
            run: |e| {
                each_tree(|what, tree| {
                    let Some((records, _)) = library(tree) else {
                        return fail(format!("the grader could not store {what} as tri-nodes"));
                    };
                    let call = format!("tri_node_records({what})");
                    same(format!("{call}.0 (records)"), records, e.tri_node_records(tree).0)
                })
            },
        },
        Check {
            exercise: 28,
            name: "tri-node waste: two empty slots per record rooted at a leaf (a leaf at an even depth)",
            points: 4,
            run: |e| {
                each_tree(|what, tree| {
                    let Some(want) = library(tree) else {
                        return fail(format!("the grader could not store {what} as tri-nodes"));
                    };
                    same(format!("tri_node_records({what})"), want, e.tri_node_records(tree))
                })
            },
        },
        Check {
            exercise: 28,
            name: "the empty tree stores nothing; a tree that is one leaf is one record with two slots empty",
            points: 2,
            run: |e| {
                let empty = Bvh::<Aabb>::from_raw_parts(&[], &[], 0);
                let leaf = [node([0.0; 3], [1.0; 3], true)];
                let one = Bvh::from_raw_parts(&leaf, &[0], 0);
                same("tri_node_records(an empty tree)", (0, 0), e.tri_node_records(&empty))
                    && same("tri_node_records(a tree that is one leaf)", (1, 2), e.tri_node_records(&one))
            },
        },
    ]
}

/// `(records, unused slots)` of the library's tri-node layout of `tree`.
fn library(tree: &Bvh<Aabb>) -> Option<(usize, usize)> {
    use bvhkit::layout::{TriNode, TriNodes};
    if tree.is_empty() {
        return Some((0, 0));
    }
    let n = TriNodes::records_needed(tree).ok()?;
    let mut recs = vec![TriNode::EMPTY; n];
    let t = TriNodes::from_bvh(tree, &mut recs).ok()?;
    let unused = t.records().iter().map(|r| 3 - r.used() as usize).sum();
    Some((t.records().len(), unused))
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 7;

    pub fn tri_node_records(which: u32, tree: &Bvh<Aabb>) -> (usize, usize) {
        let right = Reference.tri_node_records(tree);
        let nodes = tree.nodes();
        let leaves = nodes.iter().filter(|n| n.is_leaf()).count();
        match which {
            // A third of the nodes, as if every record were full.
            1 => (nodes.len().div_ceil(3), right.1),
            // Records at odd depths instead (the root taken as depth 1).
            2 => {
                let (records, _) = Reference.tri_node_records(tree);
                (nodes.len() - records, right.1)
            }
            // Two wasted slots for every leaf, at any depth.
            3 => (right.0, 2 * leaves),
            // Two wasted slots for every leaf at an odd depth (parity swapped).
            4 => {
                let odd_leaves = leaves - right.1 / 2;
                (right.0, 2 * odd_leaves)
            }
            // Reads the root without checking for the empty tree.
            5 => {
                let _root = nodes[0];
                right
            }
            // Counts only internal nodes at an even depth: a leaf's own record is forgotten.
            6 => (right.0 - right.1 / 2, right.1),
            // Assumes a complete tree: 1 + 4 + 16 + ... records down to the depth.
            7 => {
                let depth = tree.depth();
                let records = (0..=depth).step_by(2).map(|d| 1usize << d).sum();
                (records, right.1)
            }
            _ => right,
        }
    }
}
