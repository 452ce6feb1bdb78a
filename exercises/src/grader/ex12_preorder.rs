//! Exercise 12: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 12.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 12,
            name: "a seven-node tree",
            points: 3,
            run: |e| {
                let pts: Vec<Vec3> = (0..4).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
                let mut nodes = vec![Node::<Aabb>::EMPTY; 7];
                let mut idx = vec![0; 4];
                let Ok(t) = TopDown::median()
                    .with_max_leaf_size(1)
                    .build(&pts, &mut nodes, &mut idx)
                else {
                    return fail("the grader could not build its seven-node tree");
                };
                let n = t.nodes();
                let (l, r) = n[0].children().unwrap_or((0, 0));
                let (ll, lr) = n[l as usize].children().unwrap_or((0, 0));
                let (rl, rr) = n[r as usize].children().unwrap_or((0, 0));
                let order = [0, l, ll, lr, r, rl, rr];
                let links = [Some(4), Some(3), None, None, Some(6), None, None];
                let want: Vec<(Aabb, Option<u32>)> = order
                    .iter()
                    .zip(links)
                    .map(|(&i, link)| (n[i as usize].bv, link))
                    .collect();
                let call = "to_preorder(a tree of 7 nodes over the points x = 0, 1, 2, 3, \
                            leaf size 1; canonical order root 0, children 1 and 2, \
                            grandchildren 3, 4 under 1 and 5, 6 under 2)";
                same_list(call, &want, &e.to_preorder(&t), show_entry)
            },
        },
        Check {
            exercise: 12,
            name: "agrees with the library's Preorder on random trees",
            points: 3,
            run: |e| {
                [(40usize, 1u32, 5u64), (200, 4, 6), (97, 2, 7)]
                    .iter()
                    .all(|&(n, leaf, seed)| {
                        let prims = boxes(n, seed, Vec3::ZERO);
                        let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(n)];
                        let mut idx = vec![0; n];
                        let Ok(t) = TopDown::sah()
                            .with_max_leaf_size(leaf)
                            .build(&prims, &mut nodes, &mut idx)
                        else {
                            return fail("the grader could not build its tree");
                        };
                        let call = format!(
                            "to_preorder(an SAH tree over {n} boxes, leaf size {leaf}, {} nodes)",
                            t.node_count()
                        );
                        same_list(call, &library(&t), &e.to_preorder(&t), show_entry)
                    })
            },
        },
        Check {
            exercise: 12,
            name: "a tree 60 levels deep (every left child internal)",
            points: 2,
            run: |e| {
                let (nodes, idx) = left_deep(60);
                let t = Bvh::from_raw_parts(&nodes, &idx, 60);
                let call = "to_preorder(a tree 60 levels deep, 121 nodes: each level's left \
                            child internal, its right child a leaf; a stack of nodes to \
                            visit holds one right child per level)";
                same_list(call, &library(&t), &e.to_preorder(&t), show_entry)
            },
        },
        Check {
            exercise: 12,
            name: "a tree that is a single leaf",
            points: 1,
            run: |e| {
                let prims = [b([1.0; 3], [2.0; 3])];
                let mut nodes = [Node::<Aabb>::EMPTY; 1];
                let mut idx = [0; 1];
                let Ok(t) = TopDown::default().build(&prims, &mut nodes, &mut idx) else {
                    return fail("the grader could not build its one-leaf tree");
                };
                let call = "to_preorder(a tree of one leaf, box [min (1, 1, 1), max (2, 2, 2)])";
                same_list(call, &[(prims[0], None)], &e.to_preorder(&t), show_entry)
            },
        },
        Check {
            exercise: 12,
            name: "the empty tree (no primitives) has no records",
            points: 1,
            run: |e| {
                let none: [Aabb; 0] = [];
                let Ok(t) = TopDown::default().build(&none, &mut [], &mut []) else {
                    return fail("the grader could not build its empty tree");
                };
                same_list(
                    "to_preorder(the tree built from no primitives)",
                    &[],
                    &e.to_preorder(&t),
                    show_entry,
                )
            },
        },
    ]
}

/// What the library's [`bvhkit::layout::Preorder`] writes for `t`.
fn library(t: &Bvh<Aabb>) -> Vec<(Aabb, Option<u32>)> {
    use bvhkit::layout::{PreNode, Preorder};
    let mut recs = vec![PreNode::<Aabb, u32>::EMPTY; t.node_count()];
    match Preorder::from_bvh(t, &mut recs) {
        Ok(pre) => pre
            .records()
            .iter()
            .map(|r| (r.bv, r.right().map(|i| i as u32)))
            .collect(),
        Err(err) => panic!("the grader's preorder failed: {err}"),
    }
}

/// One output entry in words.
fn show_entry(x: &(Aabb, Option<u32>)) -> String {
    match x.1 {
        Some(r) => format!("(box {}, right child at {r})", show_box(&x.0)),
        None => format!("(box {}, leaf)", show_box(&x.0)),
    }
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 7;

    /// Preorder with a stack of at most `cap` waiting nodes (pushes past it
    /// are dropped), the first child visited first unless `right_first`:
    /// canonical indices in output order, and each internal entry's
    /// (canonical right child) to link to.
    fn walk(tree: &Bvh<Aabb>, cap: usize, right_first: bool) -> (Vec<u32>, Vec<Option<u32>>) {
        let nodes = tree.nodes();
        let (mut order, mut stack) = (Vec::new(), Vec::new());
        if !nodes.is_empty() {
            stack.push(0u32);
        }
        while let Some(i) = stack.pop() {
            order.push(i);
            if let Some((l, r)) = nodes[i as usize].children() {
                let (first, second) = if right_first { (r, l) } else { (l, r) };
                for c in [second, first] {
                    if stack.len() < cap {
                        stack.push(c);
                    }
                }
            }
        }
        let links = order
            .iter()
            .map(|&i| nodes[i as usize].children().map(|(_, r)| r))
            .collect();
        (order, links)
    }

    /// The output of [`walk`], each link the output position of its target
    /// moved by `shift` (or measured from its parent when `relative`).
    fn emit(
        tree: &Bvh<Aabb>,
        (order, links): (Vec<u32>, Vec<Option<u32>>),
        shift: i64,
        relative: bool,
    ) -> Vec<(Aabb, Option<u32>)> {
        let pos = |c: u32| order.iter().position(|&x| x == c).unwrap_or(0) as i64;
        order
            .iter()
            .zip(links)
            .enumerate()
            .map(|(k, (&i, link))| {
                let base = if relative { k as i64 } else { 0 };
                let link = link.map(|r| (pos(r) - base + shift).max(0) as u32);
                (tree.nodes()[i as usize].bv, link)
            })
            .collect()
    }

    pub fn to_preorder(which: u32, tree: &Bvh<Aabb>) -> Vec<(Aabb, Option<u32>)> {
        let nodes = tree.nodes();
        match which {
            // The canonical array's order and its right-child index, unchanged.
            1 => nodes
                .iter()
                .map(|n| (n.bv, n.children().map(|(_, r)| r)))
                .collect(),
            // Preorder, but the link points at the left child (the next entry).
            2 => Reference
                .to_preorder(tree)
                .iter()
                .enumerate()
                .map(|(i, x)| (x.0, x.1.map(|_| i as u32 + 1)))
                .collect(),
            // Starts from the root without asking whether there is one.
            3 => {
                let root = nodes[0];
                let mut out = vec![(root.bv, None)];
                out.extend(Reference.to_preorder(tree).into_iter().skip(1));
                out
            }
            // The link as an offset from the parent's entry, not a position.
            4 => emit(tree, walk(tree, usize::MAX, false), 0, true),
            // The left child pushed last: the right subtree comes out first.
            5 => emit(tree, walk(tree, usize::MAX, true), 0, false),
            // A fixed stack of 32 nodes: deeper waiting nodes are dropped.
            6 => emit(tree, walk(tree, 32, false), 0, false),
            // Off by one: the link names the last entry of the left subtree.
            7 => emit(tree, walk(tree, usize::MAX, false), -1, false),
            _ => Reference.to_preorder(tree),
        }
    }
}
