//! Exercise 34: tree degree, the 4-wide collapse of a binary tree. The
//! checks, and the plausible wrong answers they must reject.

use super::common::*;
use bvhkit::layout::{Wide, WideNode};
use bvhkit::{Content, Hierarchy};

/// The checks of exercise 34.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 34,
            name: "34a: a leaf has nothing to collapse",
            points: 1,
            run: |e| {
                let t = uneven();
                [4u32, 5, 6, 7, 8]
                    .iter()
                    .all(|&n| collapse_is(e, &t, "the uneven tree", n, &[]))
            },
        },
        Check {
            exercise: 34,
            name: "34a: a node over two leaves keeps them: [left, right]",
            points: 1,
            run: |e| {
                let t = Tree::new(vec![unit_at(0.0), unit_at(2.0)], 1);
                let (l, r) = t.nodes[0].children().unwrap_or((0, 0));
                collapse_is(e, &t, "a tree over two unit cubes", 0, &[l, r])
                    && collapse_is(e, &uneven(), "the uneven tree", 3, &[7, 8])
            },
        },
        Check {
            exercise: 34,
            name: "34a: opens the largest internal slot first, left child in its place, right at the end",
            points: 3,
            run: |e| {
                // [1, 2] -> node 1 (area 17) opens: [3, 2, 4] -> node 2
                // (area 11) beats node 3 (7), though it is a level higher.
                let t = uneven();
                collapse_is(e, &t, "the uneven tree", 0, &[3, 5, 4, 6])
                    && collapse_is(e, &t, "the uneven tree", 1, &[7, 4, 8])
            },
        },
        Check {
            exercise: 34,
            name: "34a: ties: equal areas go to the longer box, then to the later slot",
            points: 2,
            run: |e| {
                // Two equal halves: the later one opens first.
                let twin = twins();
                if !collapse_is(e, &twin, "two equal halves", 0, &[3, 5, 6, 4]) {
                    return false;
                }
                // Points on a line: every box is flat (area 0), the longer
                // one opens.
                let line = line_tree(23);
                (0..line.nodes.len() as u32).all(|n| {
                    let want = Reference.wide_collapse(&line.bvh(), n);
                    collapse_is(e, &line, "a tree over 23 points on the x axis", n, &want)
                })
            },
        },
        Check {
            exercise: 34,
            name: "34a: the slots of the library's layout::Wide, on built trees",
            points: 3,
            run: |e| {
                built_trees()
                    .iter()
                    .all(|(t, what)| agrees_with_wide(e, t, what))
            },
        },
        Check {
            exercise: 34,
            name: "34b: no tree and one leaf: (0, 0, 0)",
            points: 1,
            run: |e| {
                measures_are(e, &Tree::new(vec![], 1), "an empty tree", (0, 0, 0))
                    && measures_are(e, &Tree::new(vec![unit_at(0.0)], 1), "one leaf", (0, 0, 0))
                    && measures_are(
                        e,
                        &Tree::new((0..3).map(|i| unit_at(2.0 * i as f32)).collect(), 4),
                        "one leaf of three cubes",
                        (0, 0, 0),
                    )
            },
        },
        Check {
            exercise: 34,
            name: "34b: small trees by hand (16 leaves: 5 nodes, depth 2, nothing empty)",
            points: 2,
            run: |e| {
                measures_are(e, &line_tree(16), "a balanced tree over 16 points", (5, 2, 0))
                    // Three leaves: one wide node with a slot to spare.
                    && measures_are(
                        e,
                        &Tree::new((0..3).map(|i| unit_at(2.0 * i as f32)).collect(), 1),
                        "three cubes in leaves of one",
                        (1, 1, 1),
                    )
                    // [3, 5, 4, 6] then 3 -> [7, 8]: two nodes, 2 + 2 empty.
                    && measures_are(e, &uneven(), "the uneven tree", (2, 2, 2))
            },
        },
        Check {
            exercise: 34,
            name: "34b: built trees, as the library's layout::Wide measures them",
            points: 3,
            run: |e| {
                built_trees().iter().all(|(t, what)| {
                    let want = Reference.wide_measures(&t.bvh());
                    measures_are(e, t, what, want)
                })
            },
        },
    ]
}

/// A canonical tree by hand: `((x from, x to), first, count)` per node, all
/// 1 x 1 across; each leaf holds one primitive, its own box.
fn by_hand(spans: &[((f32, f32), u32, u32)], depth: usize) -> Tree {
    let span = |(lo, hi): (f32, f32)| b([lo, 0.0, 0.0], [hi, 1.0, 1.0]);
    let nodes: Vec<Node<Aabb>> = spans
        .iter()
        .map(|&(x, first, count)| Node {
            bv: span(x),
            first,
            count,
        })
        .collect();
    let mut prims = vec![Aabb::EMPTY; spans.iter().filter(|s| s.2 > 0).count()];
    for &(x, first, _) in spans.iter().filter(|s| s.2 > 0) {
        prims[first as usize] = span(x);
    }
    Tree {
        indices: (0..prims.len() as u32).collect(),
        prims,
        nodes,
        depth,
    }
}

/// Root 0 = [0, 14] over 1 = [0, 8] and 2 = [9, 14]; 1 over 3 = [0, 3]
/// and the leaf 4 = [5, 8]; 2 over the leaves 5 = [9, 10] and 6 = [12, 14];
/// 3 over the leaves 7 = [0, 1] and 8 = [2, 3] (all 1 x 1 across).
fn uneven() -> Tree {
    by_hand(
        &[
            ((0.0, 14.0), 1, 0),
            ((0.0, 8.0), 3, 0),
            ((9.0, 14.0), 5, 0),
            ((0.0, 3.0), 7, 0),
            ((5.0, 8.0), 0, 1),
            ((9.0, 10.0), 1, 1),
            ((12.0, 14.0), 2, 1),
            ((0.0, 1.0), 3, 1),
            ((2.0, 3.0), 4, 1),
        ],
        3,
    )
}

/// Root 0 = [0, 7] over two equal halves 1 = [0, 3] and 2 = [4, 7], each
/// over two unit leaves (3, 4 and 5, 6).
fn twins() -> Tree {
    by_hand(
        &[
            ((0.0, 7.0), 1, 0),
            ((0.0, 3.0), 3, 0),
            ((4.0, 7.0), 5, 0),
            ((0.0, 1.0), 0, 1),
            ((2.0, 3.0), 1, 1),
            ((4.0, 5.0), 2, 1),
            ((6.0, 7.0), 3, 1),
        ],
        2,
    )
}

/// A median tree over `n` points on the x axis at uneven spacing, in
/// leaves of one: every box is flat.
fn line_tree(n: usize) -> Tree {
    let pts: Vec<Aabb> = (0..n)
        .map(|i| {
            let x = (i * i % 17) as f32 + i as f32 * 3.0;
            Aabb::new(Vec3::new(x, 0.0, 0.0), Vec3::new(x, 0.0, 0.0))
        })
        .collect();
    let mut nodes = vec![Node::EMPTY; bvhkit::max_nodes(n)];
    let mut indices = vec![0u32; n];
    let (depth, used) =
        match TopDown::median()
            .with_max_leaf_size(1)
            .build(&pts, &mut nodes, &mut indices)
        {
            Ok(t) => (t.depth(), t.node_count()),
            Err(err) => panic!("grader tree: {err}"),
        };
    nodes.truncate(used);
    Tree {
        prims: pts,
        nodes,
        indices,
        depth,
    }
}

/// Trees built by the library, with what to call them.
fn built_trees() -> Vec<(Tree, &'static str)> {
    vec![
        (
            Tree::new(boxes(5, 341, Vec3::ZERO), 1),
            "5 boxes, leaves of one",
        ),
        (
            Tree::new(boxes(90, 342, Vec3::ZERO), 1),
            "90 boxes, leaves of one",
        ),
        (
            Tree::new(boxes(300, 343, Vec3::ZERO), 4),
            "300 boxes, leaves of four",
        ),
        (line_tree(40), "40 points on the x axis"),
    ]
}

/// Asks for the collapse of `n`; explained on failure.
fn collapse_is(e: &dyn Exercises, t: &Tree, what: &str, n: u32, want: &[u32]) -> bool {
    let call = format!("wide_collapse({what}, node {n})");
    same(call, want.to_vec(), e.wide_collapse(&t.bvh(), n))
}

/// Asks for the measures of the wide tree; explained on failure.
fn measures_are(e: &dyn Exercises, t: &Tree, what: &str, want: (usize, usize, usize)) -> bool {
    same(
        format!("wide_measures({what})"),
        want,
        e.wide_measures(&t.bvh()),
    )
}

/// Walks the library's `Wide` layout of `t` and the canonical tree side by
/// side: each wide internal node's slots must be the boxes (and leaves) of
/// the student's collapse of the node it stands for.
fn agrees_with_wide(e: &dyn Exercises, t: &Tree, what: &str) -> bool {
    let tree = t.bvh();
    let Ok(needed) = Wide::records_needed(&tree) else {
        return fail("grader: Wide::records_needed failed");
    };
    let mut records = vec![WideNode::EMPTY; needed];
    let Ok(wide) = Wide::from_bvh(&tree, &mut records) else {
        return fail("grader: Wide::from_bvh failed");
    };
    let nodes = tree.nodes();
    let mut stack = vec![(wide.root(), 0u32)];
    while let Some((w, c)) = stack.pop() {
        let Content::Inner(kids) = wide.content(w) else {
            continue;
        };
        let got = e.wide_collapse(&tree, c);
        let slots: Vec<Aabb> = kids.as_slice().iter().map(|&k| wide.bv(k)).collect();
        let matches = got.len() == slots.len()
            && got.iter().zip(kids.as_slice()).all(|(&g, &k)| {
                nodes
                    .get(g as usize)
                    .is_some_and(|n| n.bv == wide.bv(k) && n.is_leaf() == wide.is_leaf(k))
            });
        if !matches {
            let boxes: Vec<String> = slots.iter().map(show_box).collect();
            let yours: Vec<String> = got
                .iter()
                .map(|&g| {
                    nodes
                        .get(g as usize)
                        .map_or("no such node".into(), |n| show_box(&n.bv))
                })
                .collect();
            return fail(format!(
                "wide_collapse({what}, node {c}) returned {got:?}, whose boxes are [{}]; \
                 layout::Wide holds [{}] there",
                yours.join(", "),
                boxes.join(", ")
            ));
        }
        stack.extend(kids.as_slice().iter().copied().zip(got));
    }
    true
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 8;

    pub fn wide_collapse(which: u32, tree: &Bvh<Aabb>, node: u32) -> Vec<u32> {
        if !(1..=5).contains(&which) {
            return Reference.wide_collapse(tree, node);
        }
        let nodes = tree.nodes();
        let Some((l, r)) = nodes[node as usize].children() else {
            return Vec::new();
        };
        let mut slots = vec![l, r];
        while slots.len() < 4 {
            let inner: Vec<usize> = (0..slots.len())
                .filter(|&k| !nodes[slots[k] as usize].is_leaf())
                .collect();
            let area = |k: &usize| nodes[slots[*k] as usize].bv.half_area();
            let long = |k: &usize| nodes[slots[*k] as usize].bv.extent().element_sum();
            let by_size = |x: &usize, y: &usize| {
                area(x)
                    .total_cmp(&area(y))
                    .then(long(x).total_cmp(&long(y)))
            };
            let pick = match which {
                // 1: the first internal slot, whatever its size.
                1 => inner.first().copied(),
                // 2: the smallest first.
                2 => inner.iter().copied().min_by(by_size),
                // 3: a complete tie goes to the earlier slot.
                3 => inner.iter().rev().copied().max_by(by_size),
                // 4: the area alone (flat boxes all tie; the later wins).
                4 => inner
                    .iter()
                    .copied()
                    .max_by(|x, y| area(x).total_cmp(&area(y))),
                _ => inner.iter().copied().max_by(by_size),
            };
            let Some(k) = pick else { break };
            let Some((cl, cr)) = nodes[slots[k] as usize].children() else {
                break;
            };
            // 5: the right child in the slot, the left one appended.
            let (here, end) = if which == 5 { (cr, cl) } else { (cl, cr) };
            slots[k] = here;
            slots.push(end);
        }
        slots
    }

    pub fn wide_measures(which: u32, tree: &Bvh<Aabb>) -> (usize, usize, usize) {
        let (inner, depth, empty) = Reference.wide_measures(tree);
        let some = !tree.is_empty() as usize;
        match which {
            // 6: the header record counted as a node.
            6 => (inner + some, depth, empty),
            // 7: the header's three unused slots counted too.
            7 => (inner, depth, empty + 3 * some),
            // 8: half the binary depth, as if every level collapsed evenly.
            8 => (inner, tree.depth().div_ceil(2), empty),
            _ => (inner, depth, empty),
        }
    }
}
