//! Exercise 32: insertion, where a new object goes and why the order
//! matters. The checks, and the plausible wrong answers they must reject.

use super::common::*;
use bvhkit::builders::{DynNode, DynamicConfig, DynamicTree, Rotations, SiblingSearch, NULL};

/// The checks of exercise 32.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 32,
            name: "32a: a tree of one leaf: the new object goes next to it",
            points: 1,
            run: |e| {
                // The root need not be node 0: here it is node 2.
                let nodes = [DynNode::EMPTY, DynNode::EMPTY, leaf(unit_at(0.0), NULL)];
                sibling_is(e, &nodes, 2, &unit_at(5.0), 2)
            },
        },
        Check {
            exercise: 32,
            name: "32a: an object far from everything stays at the root",
            points: 2,
            run: |e| {
                // Staying: 2 * 86 = 172; into the left leaf 2 * (86 - 14)
                // + 86 = 230, into the right one 144 + 78 = 222.
                sibling_is(e, &pair_tree(), 0, &unit_at(20.0), 0)
            },
        },
        Check {
            exercise: 32,
            name: "32a: descends into the child that grows least, down to a leaf",
            points: 3,
            run: |e| {
                // Inside the root and inside R: growth 0 there; the leaf
                // [6, 7] costs its new parent's area 6 < staying at R (28).
                let new = b([6.25, 0.25, 0.25], [6.75, 0.75, 0.75]);
                sibling_is(e, &four_tree(), 0, &new, 6)
                    // Left of L's first leaf: into L, whose first leaf wins.
                    && sibling_is(e, &four_tree(), 0, &b([0.25, 0.0, 0.0], [0.5, 1.0, 1.0]), 3)
            },
        },
        Check {
            exercise: 32,
            name: "32a: ties: equal children go left, and staying must be strictly cheaper",
            points: 2,
            run: |e| {
                // Centred between the two leaves: both cost 9.
                sibling_is(e, &pair_tree(), 0, &b([1.25, 0.0, 0.0], [1.75, 1.0, 1.0]), 1)
                    // Staying costs 72, the right leaf 2 * (36 - 14) + 28 = 72 too.
                    && sibling_is(e, &pair_tree(), 0, &b([8.0, 0.0, 0.0], [8.5, 1.0, 1.0]), 2)
            },
        },
        Check {
            exercise: 32,
            name: "32a: the sibling the library's DynamicTree picks, on grown trees",
            points: 3,
            run: |e| {
                let mut r = Rng(3232);
                [(boxes(40, 32, Vec3::ZERO), 32), (boxes(120, 33, Vec3::ZERO), 33)]
                    .iter()
                    .all(|(prims, seed)| {
                        let (nodes, root) = grown(prims);
                        (0..40).all(|_| {
                            let lo = r.point(12.0, Vec3::new(4.5, 4.5, 0.5));
                            let s = Vec3::new(r.next(), r.next(), r.next()) * 3.0 + 0.01;
                            let new = Aabb::new(lo, lo + s);
                            let call = format!(
                                "insertion_sibling(the tree grown by inserting boxes(n = {}, \
                                 seed {seed}) in order, root {root}, {})",
                                prims.len(),
                                show_box(&new)
                            );
                            same(
                                call,
                                library_sibling(prims, &new),
                                e.insertion_sibling(&nodes, root, &new),
                            )
                        })
                    })
            },
        },
        Check {
            exercise: 32,
            name: "32b: no object and one object",
            points: 1,
            run: |e| {
                let three = [unit_at(0.0), unit_at(2.0), b([0.0; 3], [2.0, 3.0, 4.0])];
                build_is(e, &three, &[], (0, 0.0))
                    && build_is(e, &three, &[0], (0, 6.0))
                    && build_is(e, &three, &[2], (0, 52.0))
            },
        },
        Check {
            exercise: 32,
            name: "32b: three objects by hand",
            points: 2,
            run: |e| {
                // 0 is the root; 1 joins it under [0, 3] (area 14); 2 is far
                // away and stays at the root: [0, 11] (area 46) over [0, 3]
                // and 2. Sum 46 + 14 + 3 * 6, height 2.
                let row = [unit_at(0.0), unit_at(2.0), unit_at(10.0)];
                build_is(e, &row, &[0, 1, 2], (2, 78.0))
                    // Only the objects `order` names are inserted.
                    && build_is(e, &row, &[2, 1], (1, 50.0))
            },
        },
        Check {
            exercise: 32,
            name: "32b: sorted, reversed and shuffled orders build what the library's DynamicTree builds",
            points: 4,
            run: |e| {
                let mut r = Rng(3233);
                let row: Vec<Aabb> = (0..40).map(|i| unit_at(2.0 * i as f32)).collect();
                let scattered = boxes(60, 34, Vec3::ZERO);
                let sorted: Vec<u32> = (0..40).collect();
                let reversed: Vec<u32> = (0..40).rev().collect();
                [
                    (&row, sorted.clone(), "the row in order"),
                    (&row, reversed, "the row from its far end"),
                    (&row, shuffled(&mut r, 40), "the row shuffled"),
                    (&scattered, shuffled(&mut r, 60), "60 scattered boxes shuffled"),
                    (&scattered, (0..60).step_by(2).collect(), "every second one of 60 boxes"),
                ]
                .iter()
                .all(|(boxes, order, what)| {
                    let want = Reference.insertion_build(boxes, order);
                    let got = e.insertion_build(boxes, order);
                    (got.0 == want.0 && close(got.1, want.1))
                        || fail(format!(
                            "insertion_build({what}: {} boxes, order {order:?}) returned \
                             {got:?}, expected {want:?}",
                            boxes.len()
                        ))
                })
            },
        },
    ]
}

/// A leaf of a hand-made tree.
fn leaf(bv: Aabb, parent: u32) -> DynNode<Aabb> {
    DynNode {
        bv,
        parent,
        left: NULL,
        right: NULL,
        item: 0,
        height: 0,
        generation: 0,
    }
}

/// An internal node of a hand-made tree.
fn inner(bv: Aabb, parent: u32, left: u32, right: u32, height: u32) -> DynNode<Aabb> {
    DynNode {
        bv,
        parent,
        left,
        right,
        item: 0,
        height,
        generation: 0,
    }
}

/// Root 0 = [0, 3] x [0, 1]^2 over the unit cubes at x = 0 (node 1) and
/// x = 2 (node 2).
fn pair_tree() -> Vec<DynNode<Aabb>> {
    vec![
        inner(b([0.0; 3], [3.0, 1.0, 1.0]), NULL, 1, 2, 1),
        leaf(unit_at(0.0), 0),
        leaf(unit_at(2.0), 0),
    ]
}

/// Root 0 = [0, 7] over L (node 1) = [0, 3] and R (node 2) = [4, 7]; L over
/// the leaves at x = 0 (3) and 2 (4), R over those at 4 (5) and 6 (6).
fn four_tree() -> Vec<DynNode<Aabb>> {
    let span = |lo: f32, hi: f32| b([lo, 0.0, 0.0], [hi, 1.0, 1.0]);
    vec![
        inner(span(0.0, 7.0), NULL, 1, 2, 2),
        inner(span(0.0, 3.0), 0, 3, 4, 1),
        inner(span(4.0, 7.0), 0, 5, 6, 1),
        leaf(unit_at(0.0), 1),
        leaf(unit_at(2.0), 1),
        leaf(unit_at(4.0), 2),
        leaf(unit_at(6.0), 2),
    ]
}

/// A tree over `nodes` as `index:[box](left, right)`, for explanations.
fn show_tree(nodes: &[DynNode<Aabb>], n: u32) -> String {
    let node = &nodes[n as usize];
    let here = format!("{n}:{}", show_box(&node.bv));
    if node.left == NULL {
        here
    } else {
        format!(
            "{here}({}, {})",
            show_tree(nodes, node.left),
            show_tree(nodes, node.right)
        )
    }
}

/// Asks for the sibling of `new` in a hand-made tree; explained on failure.
fn sibling_is(
    e: &dyn Exercises,
    nodes: &[DynNode<Aabb>],
    root: u32,
    new: &Aabb,
    want: u32,
) -> bool {
    let call = format!(
        "insertion_sibling(tree {}, root {root}, {})",
        show_tree(nodes, root),
        show_box(new)
    );
    same(call, want, e.insertion_sibling(nodes, root, new))
}

/// Asks for the build of `boxes` in `order`; explained on failure.
fn build_is(e: &dyn Exercises, boxes: &[Aabb], order: &[u32], want: (usize, f64)) -> bool {
    let got = e.insertion_build(boxes, order);
    (got.0 == want.0 && close(got.1, want.1))
        || fail(format!(
            "insertion_build([{}], order {order:?}) returned {got:?}, expected {want:?}",
            boxes.iter().map(show_box).collect::<Vec<_>>().join(", ")
        ))
}

/// The library's insertion by descent, without rotations.
fn descent() -> DynamicConfig {
    DynamicConfig {
        search: SiblingSearch::Descent,
        rotations: Rotations::Off,
        margin: 0.0,
    }
}

/// `prims` inserted in order into storage with room for one more object,
/// and the root's index.
fn grown(prims: &[Aabb]) -> (Vec<DynNode<Aabb>>, u32) {
    let mut storage = vec![DynNode::<Aabb>::EMPTY; bvhkit::max_nodes(prims.len() + 1)];
    if let Ok(mut tree) = DynamicTree::new(&mut storage, descent()) {
        for (i, p) in prims.iter().enumerate() {
            let _ = tree.insert(i as u32, p);
        }
    }
    let root = storage
        .iter()
        .position(|n| n.height != u32::MAX && n.parent == NULL)
        .map_or(NULL, |i| i as u32);
    (storage, root)
}

/// The sibling the library gives `new` in [`grown`]`(prims)`: grown again
/// the same way (so every node keeps its index), `new` inserted, and read
/// back as the other child of its new parent.
fn library_sibling(prims: &[Aabb], new: &Aabb) -> u32 {
    let mut storage = vec![DynNode::<Aabb>::EMPTY; bvhkit::max_nodes(prims.len() + 1)];
    let Ok(mut tree) = DynamicTree::new(&mut storage, descent()) else {
        return NULL;
    };
    for (i, p) in prims.iter().enumerate() {
        let _ = tree.insert(i as u32, p);
    }
    let Ok(leaf) = tree.insert(prims.len() as u32, new) else {
        return NULL;
    };
    // The tree's borrow of `storage` ends here.
    let leaf = leaf.index();
    let parent = &storage[storage[leaf as usize].parent as usize];
    if parent.left == leaf {
        parent.right
    } else {
        parent.left
    }
}

/// `0..n` in a random order.
fn shuffled(r: &mut Rng, n: u32) -> Vec<u32> {
    let mut v: Vec<u32> = (0..n).collect();
    for i in (1..v.len()).rev() {
        let j = ((r.next() * (i + 1) as f32) as usize).min(i);
        v.swap(i, j);
    }
    v
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 7;

    pub fn insertion_sibling(which: u32, nodes: &[DynNode<Aabb>], root: u32, new: &Aabb) -> u32 {
        let area = |b: &Aabb| b.surface_area() as f64;
        let rule = match which {
            1..=5 => which,
            _ => return Reference.insertion_sibling(nodes, root, new),
        };
        let mut n = root;
        while nodes[n as usize].left != NULL {
            let node = &nodes[n as usize];
            let combined = area(&node.bv.union(new));
            // 2: the new parent counted once.
            let here = if rule == 2 { combined } else { 2.0 * combined };
            // 1: the growth of the node itself forgotten.
            let inheritance = if rule == 1 {
                0.0
            } else {
                2.0 * (combined - area(&node.bv))
            };
            let child_cost = |c: u32| {
                let cb = &nodes[c as usize].bv;
                let m = area(&cb.union(new));
                // 5: a leaf costs its growth, like an internal node.
                let is_leaf = nodes[c as usize].left == NULL && rule != 5;
                inheritance + if is_leaf { m } else { m - area(cb) }
            };
            let (cl, cr) = (child_cost(node.left), child_cost(node.right));
            // 4: staying wins ties.
            let stay = if rule == 4 {
                here <= cl && here <= cr
            } else {
                here < cl && here < cr
            };
            if stay {
                break;
            }
            // 3: ties go right.
            let left = if rule == 3 { cl < cr } else { cl <= cr };
            n = if left { node.left } else { node.right };
        }
        n
    }

    pub fn insertion_build(which: u32, boxes: &[Aabb], order: &[u32]) -> (usize, f64) {
        match which {
            // Every box, in index order: the order ignored.
            6 => Reference.insertion_build(boxes, &(0..boxes.len() as u32).collect::<Vec<_>>()),
            // The height counted in levels (nodes), not edges.
            7 => {
                let (h, s) = Reference.insertion_build(boxes, order);
                (h + 1, s)
            }
            _ => Reference.insertion_build(boxes, order),
        }
    }
}
