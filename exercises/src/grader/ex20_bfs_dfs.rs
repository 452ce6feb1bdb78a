//! Exercise 20: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 20.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 20,
            name: "depth-first: preorder, left before right",
            points: 5,
            run: |e| {
                visit_cases().iter().all(|t| {
                    e.visit_order(&t.bvh(), false) == Reference.visit_order(&t.bvh(), false)
                })
            },
        },
        Check {
            exercise: 20,
            name: "breadth-first: level by level, left to right",
            points: 5,
            run: |e| {
                visit_cases()
                    .iter()
                    .all(|t| e.visit_order(&t.bvh(), true) == Reference.visit_order(&t.bvh(), true))
            },
        },
    ]
}

/// Trees to walk: empty, one leaf, and top-down trees of a few shapes.
fn visit_cases() -> Vec<Tree> {
    let mut cases = vec![Tree::new(vec![], 1), Tree::new(boxes(1, 3, Vec3::ZERO), 1)];
    for (n, seed) in [(2, 5), (7, 11), (40, 13)] {
        cases.push(Tree::new(boxes(n, seed, Vec3::ZERO), 1 + (seed % 3) as u32));
    }
    cases
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 2;

    pub fn visit_order(which: u32, tree: &Bvh<Aabb>, breadth_first: bool) -> Vec<u32> {
        let nodes = tree.nodes();
        match which {
            // Depth-first with the left child pushed first: right before left.
            1 if !breadth_first => {
                let (mut order, mut stack) = (vec![], vec![]);
                if !nodes.is_empty() {
                    stack.push(0u32);
                }
                while let Some(i) = stack.pop() {
                    order.push(i);
                    if let Some((l, r)) = nodes[i as usize].children() {
                        stack.extend([l, r]);
                    }
                }
                order
            }
            // Breadth-first with a stack: depth-first, right first.
            2 if breadth_first => visit_order(1, tree, false),
            _ => Reference.visit_order(tree, breadth_first),
        }
    }
}
