//! Exercise 28: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 28.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 28,
            name: "tri-node records: one per node at an even depth, as TriNodes stores them",
            points: 5,
            run: |e| {
                use bvhkit::layout::{TriNode, TriNodes};
                on_measured_trees(|tree| {
                    let got = e.tri_node_records(tree).0;
                    let Ok(n) = TriNodes::records_needed(tree) else {
                        return false;
                    };
                    let mut recs = vec![TriNode::EMPTY; n];
                    got == n
                        && (tree.is_empty()
                            || TriNodes::from_bvh(tree, &mut recs)
                                .is_ok_and(|t| t.records().len() == got))
                })
            },
        },
        Check {
            exercise: 28,
            name: "tri-node waste: two empty slots per record rooted at a leaf",
            points: 5,
            run: |e| {
                use bvhkit::layout::{TriNode, TriNodes};
                on_measured_trees(|tree| {
                    let (records, unused) = e.tri_node_records(tree);
                    let Ok(n) = TriNodes::records_needed(tree) else {
                        return false;
                    };
                    let mut recs = vec![TriNode::EMPTY; n];
                    // The library's records: 3 slots each, `used()` of them filled.
                    let library = if tree.is_empty() {
                        0
                    } else {
                        match TriNodes::from_bvh(tree, &mut recs) {
                            Ok(t) => t.records().iter().map(|r| 3 - r.used() as usize).sum(),
                            Err(_) => return false,
                        }
                    };
                    records == n && unused == library
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
    pub const COUNT: u32 = 3;

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
            _ => right,
        }
    }
}
