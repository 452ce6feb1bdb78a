//! Exercise 49: what to check before trusting a baked tree. The checks,
//! and the plausible wrong answers they must reject.
//!
//! Every honest case is a tree a builder made (its parts as
//! [`Bvh::bake`] writes them); every corrupt case changes one thing of an
//! honest one, or is made by hand where no builder would make it. Each
//! expected answer is the reference's (the library's [`bvhkit::baked::check`]),
//! and the reference is held to the cases' intent: `Some(depth of the
//! built tree)` for every honest case, `None` for every corrupt one.

use super::common::*;

/// The checks of exercise 49.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 49,
            name: "honest trees (leaves of 1 to 6, with and without kept boxes): their depth",
            points: 2,
            run: |e| agrees(e, &honest_cases()),
        },
        Check {
            exercise: 49,
            name: "links: a child before its parent, out of range, reached twice, a cycle, a \
                   node no path reaches",
            points: 2,
            run: |e| agrees(e, &link_cases()),
        },
        Check {
            exercise: 49,
            name: "indices: a leaf past the index array, two leaves on one entry, a primitive \
                   twice, a primitive out of range",
            points: 2,
            run: |e| agrees(e, &index_cases()),
        },
        Check {
            exercise: 49,
            name: "boxes: NaN, infinite, inverted, a parent not containing its child",
            points: 2,
            run: |e| agrees(e, &box_cases()),
        },
        Check {
            exercise: 49,
            name: "kept boxes: too few, one outside its leaf, one NaN",
            points: 1,
            run: |e| agrees(e, &kept_cases()),
        },
        Check {
            exercise: 49,
            name: "the empty tree is valid; a chain 64 deep is, 65 deep is not",
            points: 1,
            run: |e| agrees(e, &edge_cases()),
        },
    ]
}

/// Parts of a tree, what they are, and the answer the statement asks for.
struct Case {
    nodes: Vec<Node<Aabb>>,
    indices: Vec<u32>,
    kept: Vec<Aabb>,
    what: String,
    /// `Some(depth)` for an honest tree, `None` for a corrupt one.
    intent: Option<usize>,
}

fn agrees(e: &dyn Exercises, cases: &[Case]) -> bool {
    cases.iter().all(|c| {
        let want = Reference.baked_depth(&c.nodes, &c.indices, &c.kept);
        if want != c.intent {
            return fail(format!(
                "the reference gives {want:?} on {}, meant {:?} (a grader bug)",
                c.what, c.intent
            ));
        }
        let got = e.baked_depth(&c.nodes, &c.indices, &c.kept);
        got == want || fail(format!("{}: expected {want:?}, got {got:?}", c.what))
    })
}

/// A tree over a random soup of `n` triangles, leaves of up to `leaf`, with
/// or without its kept boxes: (nodes, indices, kept, depth).
fn built(
    n: usize,
    leaf: u32,
    kept: bool,
    seed: u64,
) -> (Vec<Node<Aabb>>, Vec<u32>, Vec<Aabb>, usize) {
    let mut r = Rng(seed);
    let tris: Vec<Triangle> = (0..n)
        .map(|_| {
            let o = r.point(10.0, Vec3::ZERO);
            Triangle::new(
                o,
                o + r.point(1.0, Vec3::ZERO),
                o + r.point(1.0, Vec3::ZERO),
            )
        })
        .collect();
    let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(n)];
    let mut indices = vec![0u32; n];
    let mut boxes = vec![Aabb::EMPTY; n];
    let Ok(tree) =
        TopDown::default()
            .with_max_leaf_size(leaf)
            .build(&tris, &mut nodes, &mut indices)
    else {
        return (Vec::new(), Vec::new(), Vec::new(), 0);
    };
    let (used, depth) = (tree.node_count(), tree.depth());
    if kept && tree.with_leaf_bounds(&tris, &mut boxes).is_err() {
        boxes.clear();
    }
    nodes.truncate(used);
    if !kept {
        boxes.clear();
    }
    (nodes, indices, boxes, depth)
}

fn honest(n: usize, leaf: u32, kept: bool, seed: u64) -> Case {
    let (nodes, indices, kept_boxes, depth) = built(n, leaf, kept, seed);
    Case {
        nodes,
        indices,
        kept: kept_boxes,
        what: format!("an honest tree of {n} triangles, leaves of up to {leaf}, kept boxes {kept}"),
        intent: Some(depth),
    }
}

fn honest_cases() -> Vec<Case> {
    let mut v = Vec::new();
    for (k, n) in [1usize, 2, 3, 7, 40, 200].into_iter().enumerate() {
        for leaf in [1, 2, 4, 6] {
            for kept in [false, true] {
                v.push(honest(
                    n,
                    leaf,
                    kept,
                    0x5eed + k as u64 * 31 + u64::from(leaf),
                ));
            }
        }
    }
    v
}

/// An honest tree of 40 triangles (leaves of up to `leaf`) changed by `f`.
fn corrupt(leaf: u32, kept: bool, what: &str, f: impl FnOnce(&mut Case)) -> Case {
    let mut c = honest(40, leaf, kept, 0xbad + u64::from(leaf));
    c.what = what.to_string();
    c.intent = None;
    f(&mut c);
    c
}

fn first_leaf(c: &Case) -> usize {
    c.nodes.iter().position(|n| n.is_leaf()).unwrap_or(0)
}

fn internal_after_root(c: &Case) -> usize {
    (1..c.nodes.len())
        .find(|&i| !c.nodes[i].is_leaf())
        .unwrap_or(0)
}

/// Root, an internal node stored after its own children, and three leaves:
/// a valid shape but for the order (the format puts children after their
/// parent), every node reached once.
fn child_before_parent() -> Case {
    let all = b([0.0; 3], [4.0; 3]);
    let leaf = |first, x: f32| Node {
        bv: b([x, 0.0, 0.0], [x + 1.0, 1.0, 1.0]),
        first,
        count: 1,
    };
    Case {
        nodes: vec![
            Node {
                bv: all,
                first: 3,
                count: 0,
            },
            leaf(0, 0.0),
            leaf(1, 1.0),
            Node {
                bv: b([0.0; 3], [2.0, 1.0, 1.0]),
                first: 1,
                count: 0,
            },
            leaf(2, 3.0),
        ],
        indices: vec![0, 1, 2],
        kept: Vec::new(),
        what: "a node stored after its own children (every node reached once)".into(),
        intent: None,
    }
}

fn link_cases() -> Vec<Case> {
    vec![
        child_before_parent(),
        corrupt(2, false, "the root's children out of range", |c| {
            c.nodes[0].first = c.nodes.len() as u32 - 1;
        }),
        corrupt(2, false, "a child index of u32::MAX", |c| {
            let i = internal_after_root(c);
            c.nodes[i].first = u32::MAX;
        }),
        corrupt(2, false, "two internal nodes sharing their children", |c| {
            let i = internal_after_root(c);
            let j = (i + 1..c.nodes.len())
                .find(|&j| !c.nodes[j].is_leaf())
                .unwrap_or(i);
            c.nodes[j].first = c.nodes[i].first;
        }),
        corrupt(2, false, "an internal node whose child is itself", |c| {
            let i = internal_after_root(c);
            c.nodes[i].first = i as u32;
        }),
        corrupt(2, false, "a node no path reaches, appended", |c| {
            let extra = Node {
                bv: c.nodes[0].bv,
                first: 1,
                count: 0,
            };
            c.nodes.push(extra);
        }),
    ]
}

fn index_cases() -> Vec<Case> {
    vec![
        corrupt(3, false, "a leaf starting past the index array", |c| {
            let l = first_leaf(c);
            c.nodes[l].first = c.indices.len() as u32;
        }),
        corrupt(3, false, "a leaf whose first + count wraps a u32", |c| {
            let l = first_leaf(c);
            c.nodes[l].first = u32::MAX;
        }),
        corrupt(
            1,
            false,
            "two leaves on the same index entry, one entry in no leaf",
            |c| {
                let leaves: Vec<usize> = (0..c.nodes.len())
                    .filter(|&i| c.nodes[i].is_leaf())
                    .collect();
                let first = c.nodes[leaves[0]].first;
                c.nodes[leaves[1]].first = first;
                // Both leaves' boxes hold both primitives: only the entries lie.
                let both = c.nodes[leaves[0]].bv.union(&c.nodes[leaves[1]].bv);
                c.nodes[leaves[0]].bv = both;
                c.nodes[leaves[1]].bv = both;
                let all = c.nodes.iter().fold(Aabb::EMPTY, |a, n| a.union(&n.bv));
                for n in c.nodes.iter_mut().filter(|n| !n.is_leaf()) {
                    n.bv = all;
                }
            },
        ),
        corrupt(
            2,
            false,
            "a primitive named twice in the index array",
            |c| {
                c.indices[1] = c.indices[0];
            },
        ),
        corrupt(2, false, "a primitive out of range", |c| {
            c.indices[0] = c.indices.len() as u32;
        }),
    ]
}

fn box_cases() -> Vec<Case> {
    vec![
        corrupt(2, false, "a NaN in a leaf's box", |c| {
            let l = first_leaf(c);
            c.nodes[l].bv.max.y = f32::NAN;
        }),
        corrupt(2, false, "every box infinite on every side", |c| {
            let inf = Aabb::new(Vec3::NEG_INFINITY, Vec3::INFINITY);
            for n in &mut c.nodes {
                n.bv = inf;
            }
        }),
        corrupt(2, false, "an inverted leaf box (min above max)", |c| {
            let l = first_leaf(c);
            let bv = c.nodes[l].bv;
            c.nodes[l].bv = Aabb::new(bv.max, bv.min);
        }),
        corrupt(2, false, "the root shrunk to its centre", |c| {
            let m = c.nodes[0].bv.center();
            c.nodes[0].bv = Aabb::new(m, m);
        }),
    ]
}

fn kept_cases() -> Vec<Case> {
    vec![
        corrupt(3, true, "one kept box too few", |c| {
            c.kept.pop();
        }),
        corrupt(3, true, "a kept box outside its leaf's box", |c| {
            let l = first_leaf(c);
            let k = c.nodes[l].first as usize;
            c.kept[k] = Aabb::new(Vec3::splat(1e6), Vec3::splat(1e6 + 1.0));
        }),
        corrupt(3, true, "a NaN in a kept box", |c| {
            c.kept[0].min.x = f32::NAN;
        }),
    ]
}

/// A chain: each internal node has a leaf and the next internal node as
/// children, `depth` edges from the root to the deepest leaf.
fn chain(depth: usize) -> Case {
    let all = b([0.0; 3], [1.0; 3]);
    let mut nodes = Vec::new();
    for level in 0..depth {
        nodes.push(Node {
            bv: all,
            first: (2 * level + 1) as u32,
            count: 0,
        });
        // Children at 2 * level + 1 (a leaf) and 2 * level + 2 (next level);
        // filled in order below.
        nodes.push(Node {
            bv: all,
            first: level as u32,
            count: 1,
        });
    }
    // The last internal node's second child: a leaf.
    nodes.push(Node {
        bv: all,
        first: depth as u32,
        count: 1,
    });
    // Reorder so that node k's children are at first and first + 1: the
    // pushes above put internal node `level` at 2 * level and its leaf at
    // 2 * level + 1, so the children of 2 * level are 2 * level + 1 and
    // 2 * level + 2, as `first` says.
    Case {
        nodes,
        indices: (0..=depth as u32).collect(),
        kept: Vec::new(),
        what: format!("a chain {depth} deep"),
        intent: (depth <= 64).then_some(depth),
    }
}

fn edge_cases() -> Vec<Case> {
    vec![
        Case {
            nodes: Vec::new(),
            indices: Vec::new(),
            kept: Vec::new(),
            what: "the empty tree".into(),
            intent: Some(0),
        },
        Case {
            nodes: Vec::new(),
            indices: vec![0],
            kept: Vec::new(),
            what: "no nodes but an index entry".into(),
            intent: None,
        },
        chain(64),
        chain(65),
    ]
}

/// Plausible wrong answers, numbered from 1; each loses points here: a
/// full checker missing one check.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 8;

    fn sound(b: &Aabb) -> bool {
        b.min.is_finite() && b.max.is_finite() && b.min.cmple(b.max).all()
    }

    /// Wrong answer `which`:
    /// 1 allows a child before its parent; 2 adds a leaf's `first + count`
    /// in 32 bits (a corrupt `first` wraps past the range check); 3 checks only that the leaves' counts
    /// add up to the index array (not which entries they name); 4 never
    /// checks the index array's values for repeats; 5 checks containment
    /// but not that boxes are finite and not inverted; 6 ignores the kept
    /// boxes; 7 has no depth limit; 8 calls an empty tree invalid.
    pub fn baked_depth(
        which: u32,
        nodes: &[Node<Aabb>],
        indices: &[u32],
        kept: &[Aabb],
    ) -> Option<usize> {
        if nodes.is_empty() {
            return (which != 8 && indices.is_empty() && kept.is_empty()).then_some(0);
        }
        if !kept.is_empty() && kept.len() != indices.len() && which != 6 {
            return None;
        }
        let mut reached = vec![false; nodes.len()];
        let (mut stack, mut depth, mut visits, mut slots) = (vec![(0usize, 0usize)], 0, 0, 0);
        reached[0] = true;
        while let Some((i, d)) = stack.pop() {
            visits += 1;
            if visits > nodes.len() {
                return None; // never: a node reached twice stops the walk
            }
            depth = depth.max(d);
            let n = nodes[i];
            if n.is_leaf() {
                let end = if which == 2 {
                    u64::from(n.first.wrapping_add(n.count))
                } else {
                    u64::from(n.first) + u64::from(n.count)
                };
                if end > indices.len() as u64 {
                    return None;
                }
                slots += n.count as usize;
                continue;
            }
            let (l, r) = (n.first as usize, n.first as usize + 1);
            if (l <= i && which != 1) || r >= nodes.len() {
                return None;
            }
            if d >= 64 && which != 7 {
                return None;
            }
            for c in [l, r] {
                if reached[c] {
                    return None;
                }
                reached[c] = true;
                stack.push((c, d + 1));
            }
        }
        if visits != nodes.len() || slots != indices.len() {
            return None;
        }
        if which != 3 {
            let mut entry = vec![false; indices.len()];
            for n in nodes.iter().filter(|n| n.is_leaf()) {
                let range = n.first as usize..(n.first + n.count) as usize;
                for slot in &mut entry[range] {
                    if std::mem::replace(slot, true) {
                        return None;
                    }
                }
            }
        }
        let mut prim = vec![false; indices.len()];
        for &p in indices {
            let slot = prim.get_mut(p as usize)?;
            if std::mem::replace(slot, true) && which != 4 {
                return None;
            }
        }
        for n in nodes {
            if which != 5 && !sound(&n.bv) {
                return None;
            }
            if n.is_leaf() {
                if which != 6 && !kept.is_empty() {
                    let leaf = &kept[n.first as usize..(n.first + n.count) as usize];
                    if !leaf.iter().all(|k| sound(k) && n.bv.contains(k)) {
                        return None;
                    }
                }
            } else {
                let (l, r) = (n.first as usize, n.first as usize + 1);
                if !n.bv.contains(&nodes[l].bv) || !n.bv.contains(&nodes[r].bv) {
                    return None;
                }
            }
        }
        Some(depth)
    }
}
