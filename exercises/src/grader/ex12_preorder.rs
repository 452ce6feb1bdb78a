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
                    return false;
                };
                let got = e.to_preorder(&t);
                let links: Vec<Option<u32>> = got.iter().map(|x| x.1).collect();
                let n = t.nodes();
                let (l, r) = n[0].children().unwrap_or((0, 0));
                let (ll, lr) = n[l as usize].children().unwrap_or((0, 0));
                let (rl, rr) = n[r as usize].children().unwrap_or((0, 0));
                let order = [0, l, ll, lr, r, rl, rr];
                links == [Some(4), Some(3), None, None, Some(6), None, None]
                    && got.iter().zip(order).all(|(x, i)| x.0 == n[i as usize].bv)
            },
        },
        Check {
            exercise: 12,
            name: "agrees with the library's Preorder on random trees",
            points: 4,
            run: |e| {
                use bvhkit::layout::{PreNode, Preorder};
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
                            return false;
                        };
                        let mut recs = vec![PreNode::<Aabb, u32>::EMPTY; t.node_count()];
                        let Ok(pre) = Preorder::from_bvh(&t, &mut recs) else {
                            return false;
                        };
                        let want: Vec<(Aabb, Option<u32>)> = pre
                            .records()
                            .iter()
                            .map(|r| (r.bv, r.right().map(|i| i as u32)))
                            .collect();
                        e.to_preorder(&t) == want
                    })
            },
        },
        Check {
            exercise: 12,
            name: "a tree that is a single leaf",
            points: 2,
            run: |e| {
                let prims = [b([1.0; 3], [2.0; 3])];
                let mut nodes = [Node::<Aabb>::EMPTY; 1];
                let mut idx = [0; 1];
                let Ok(t) = TopDown::default().build(&prims, &mut nodes, &mut idx) else {
                    return false;
                };
                e.to_preorder(&t) == [(prims[0], None)]
            },
        },
        Check {
            exercise: 12,
            name: "the empty tree (no primitives) has no records",
            points: 1,
            run: |e| {
                let none: [Aabb; 0] = [];
                let Ok(t) = TopDown::default().build(&none, &mut [], &mut []) else {
                    return false;
                };
                e.to_preorder(&t).is_empty()
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

    pub fn to_preorder(which: u32, tree: &Bvh<Aabb>) -> Vec<(Aabb, Option<u32>)> {
        let nodes = tree.nodes();
        match which {
            // The canonical array's order and its right-child index, unchanged.
            1 => nodes
                .iter()
                .map(|n| (n.bv, n.children().map(|(_, r)| r)))
                .collect(),
            // Starts from the root without asking whether there is one.
            3 => {
                let root = nodes[0];
                let mut out = vec![(root.bv, None)];
                out.extend(Reference.to_preorder(tree).into_iter().skip(1));
                out
            }
            // Preorder, but the link points at the left child (the next entry).
            2 => Reference
                .to_preorder(tree)
                .iter()
                .enumerate()
                .map(|(i, x)| (x.0, x.1.map(|_| i as u32 + 1)))
                .collect(),
            _ => Reference.to_preorder(tree),
        }
    }
}
