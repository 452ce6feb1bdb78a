//! Exercise 20: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 20.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 20,
            name: "depth-first: preorder, left before right",
            points: 4,
            run: |e| {
                visit_cases()
                    .iter()
                    .all(|(t, what)| order_is(e, &t.bvh(), what, false))
            },
        },
        Check {
            exercise: 20,
            name: "breadth-first: level by level, left to right",
            points: 4,
            run: |e| {
                visit_cases()
                    .iter()
                    .all(|(t, what)| order_is(e, &t.bvh(), what, true))
            },
        },
        Check {
            exercise: 20,
            name: "a tree 60 levels deep (every left child internal), both orders",
            points: 2,
            run: |e| {
                let (nodes, idx) = left_deep(60);
                let t = Bvh::from_raw_parts(&nodes, &idx, 60);
                let what = "a tree 60 levels deep, 121 nodes: each level's left child \
                            internal, its right child a leaf";
                order_is(e, &t, what, false) && order_is(e, &t, what, true)
            },
        },
    ]
}

/// Whether the visiting order of `t` is the reference's, explained with
/// the first node out of place.
fn order_is(e: &dyn Exercises, t: &Bvh<Aabb>, what: &str, breadth_first: bool) -> bool {
    same_list(
        format!("visit_order({what}, breadth_first = {breadth_first})"),
        &Reference.visit_order(t, breadth_first),
        &e.visit_order(t, breadth_first),
        |i| format!("node {i}"),
    )
}

/// Trees to walk: empty, one leaf, and top-down trees of a few shapes, each
/// described in words.
fn visit_cases() -> Vec<(Tree, String)> {
    let mut cases = vec![
        (Tree::new(vec![], 1), "the tree over no boxes".to_string()),
        (
            Tree::new(boxes(1, 3, Vec3::ZERO), 1),
            "a tree of one leaf".to_string(),
        ),
    ];
    for (n, seed) in [(2, 5), (7, 11), (40, 13)] {
        let leaf = 1 + (seed % 3) as u32;
        let t = Tree::new(boxes(n, seed, Vec3::ZERO), leaf);
        let what = format!(
            "a top-down tree over {n} boxes, leaf size {leaf}, {} nodes",
            t.nodes.len()
        );
        cases.push((t, what));
    }
    cases
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 7;

    /// Depth-first with a stack of at most `cap` nodes (pushes past it are
    /// dropped), the children pushed in the order `push` gives.
    fn stack_walk(tree: &Bvh<Aabb>, cap: usize, push: fn(u32, u32) -> [u32; 2]) -> Vec<u32> {
        let nodes = tree.nodes();
        let (mut order, mut stack) = (vec![], vec![]);
        if !nodes.is_empty() {
            stack.push(0u32);
        }
        while let Some(i) = stack.pop() {
            order.push(i);
            if let Some((l, r)) = nodes[i as usize].children() {
                for c in push(l, r) {
                    if stack.len() < cap {
                        stack.push(c);
                    }
                }
            }
        }
        order
    }

    /// Children before their parent.
    fn postorder(nodes: &[Node<Aabb>], i: u32, out: &mut Vec<u32>) {
        if let Some((l, r)) = nodes[i as usize].children() {
            postorder(nodes, l, out);
            postorder(nodes, r, out);
        }
        out.push(i);
    }

    pub fn visit_order(which: u32, tree: &Bvh<Aabb>, breadth_first: bool) -> Vec<u32> {
        let nodes = tree.nodes();
        match which {
            // Depth-first with the left child pushed first: right before left.
            1 if !breadth_first => stack_walk(tree, usize::MAX, |l, r| [l, r]),
            // Breadth-first with a stack: depth-first, right first.
            2 if breadth_first => stack_walk(tree, usize::MAX, |l, r| [l, r]),
            // Depth-first on a fixed stack of 32 nodes: deeper ones are dropped.
            3 if !breadth_first => stack_walk(tree, 32, |l, r| [r, l]),
            // Breadth-first with the right child queued first.
            4 if breadth_first => {
                let mut order = vec![];
                let mut queue = std::collections::VecDeque::new();
                if !nodes.is_empty() {
                    queue.push_back(0u32);
                }
                while let Some(i) = queue.pop_front() {
                    order.push(i);
                    if let Some((l, r)) = nodes[i as usize].children() {
                        queue.extend([r, l]);
                    }
                }
                order
            }
            // The root is visited even when the tree is empty.
            5 if nodes.is_empty() => vec![0],
            // Depth-first in postorder: children before their parent.
            6 if !breadth_first => {
                let mut out = vec![];
                if !nodes.is_empty() {
                    postorder(nodes, 0, &mut out);
                }
                out
            }
            // The array's order taken for the visiting order.
            7 => (0..nodes.len() as u32).collect(),
            _ => Reference.visit_order(tree, breadth_first),
        }
    }
}
