//! Exercise 42: self-collision, one tree against itself. The checks, and the
//! plausible wrong answers they must reject. The expected pairs come from
//! `brute_force::self_pairs`; the scenes are exercise 5's, each tree on its
//! own, plus trees small enough to read and trees with a node's box moved
//! away from its contents.

use super::common::*;
use super::ex05_recursive_pairs::{beneath, dense_cases, move_node, once, pairs_match};

/// The checks of exercise 42.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 42,
            name: "finds exactly the brute-force self pairs on overlapping grids",
            points: 4,
            run: |e| {
                grid_scenes()
                    .iter()
                    .all(|(t, what)| matches(what, &want(t), &run(e, t)))
            },
        },
        Check {
            exercise: 42,
            name: "tiny trees (1-3 leaves), and pairs inside one leaf",
            points: 2,
            run: |e| {
                tiny_scenes()
                    .iter()
                    .all(|(t, what)| matches(what, &want(t), &run(e, t)))
            },
        },
        Check {
            exercise: 42,
            name: "every pair once, ordered i < j, never (i, i); also where every box overlaps every box",
            points: 2,
            run: |e| {
                let mut scenes = grid_scenes();
                scenes.extend(tiny_scenes());
                let honest = scenes.iter().all(|(t, what)| {
                    let got = run(e, t);
                    ordered(what, &got) && once(&format!("self_pairs on {what}"), &got)
                });
                // Every pair overlaps: each must come back, once.
                honest
                    && dense_scenes().iter().all(|(t, what)| {
                        let got = run(e, t);
                        once(&format!("self_pairs on {what}"), &got)
                            && matches(what, &want(t), &got)
                    })
            },
        },
        Check {
            exercise: 42,
            name: "prunes: a node whose box misses hides its pairs with the rest, not its own",
            points: 3,
            run: |e| {
                tampered_self_cases().iter().all(|s| {
                    let got = run(e, &s.tree);
                    ordered(&s.what, &got) && pruned(s, &got)
                })
            },
        },
    ]
}

fn run(e: &dyn Exercises, t: &Tree) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    e.self_pairs(&t.bvh(), &t.prims, &mut out);
    out
}

/// The brute-force answer: pairs `i < j` whose boxes overlap, sorted.
fn want(t: &Tree) -> Vec<(u32, u32)> {
    let mut want = Vec::new();
    brute_force::self_pairs(&t.prims, |i, j| want.push((i, j)));
    want.sort_unstable();
    want
}

/// [`ordered`], then [`pairs_match`]: a pair the wrong way round is
/// explained as such rather than as one missing and one too many.
fn matches(what: &str, want: &[(u32, u32)], got: &[(u32, u32)]) -> bool {
    ordered(what, got) && pairs_match("self_pairs", what, want, got)
}

/// Whether every pair of `got` is `(i, j)` with `i < j`, explained with the
/// first that is not.
fn ordered(what: &str, got: &[(u32, u32)]) -> bool {
    if let Some(&(i, _)) = got.iter().find(|(i, j)| i == j) {
        return fail(format!(
            "self_pairs on {what} reported the pair ({i}, {i}): a primitive with itself \
             is not a pair"
        ));
    }
    match got.iter().find(|(i, j)| i > j) {
        None => true,
        Some(&(i, j)) => fail(format!(
            "self_pairs on {what} reported the pair ({i}, {j}): each pair goes in with the \
             smaller index first, as ({j}, {i})"
        )),
    }
}

/// The boxes of a small scene, numbered: `0: [min .., max ..], 1: ...`.
fn numbered(prims: &[Aabb]) -> String {
    let v: Vec<String> = prims
        .iter()
        .enumerate()
        .map(|(i, p)| format!("{i}: {}", show_box(p)))
        .collect();
    v.join(", ")
}

/// Each tree of exercise 5's two grid scenes on its own.
fn grid_scenes() -> Vec<(Tree, String)> {
    let what = [
        "the grid of 300 boxes, one per leaf",
        "the grid of 250 boxes, up to 3 per leaf",
        "the grid of 64 boxes, up to 4 per leaf",
        "the grid of 500 boxes, one per leaf",
    ];
    traversal_cases()
        .into_iter()
        .take(2)
        .flat_map(|(a, b)| [a, b])
        .zip(what)
        .map(|(t, what)| (t, what.to_string()))
        .collect()
}

/// A tree written by hand: one leaf, or a root over two leaves, each leaf
/// holding the ids of its group in that order.
fn by_hand(prims: Vec<Aabb>, groups: &[&[u32]]) -> Tree {
    let fit = |ids: &[u32]| {
        ids.iter()
            .fold(Aabb::EMPTY, |b, &i| b.union(&prims[i as usize]))
    };
    let leaf = |ids: &[u32], first: usize| Node {
        bv: fit(ids),
        first: first as u32,
        count: ids.len() as u32,
    };
    let indices = groups.concat();
    let nodes = match groups {
        [one] => vec![leaf(one, 0)],
        [l, r] => vec![
            Node {
                bv: fit(&indices),
                first: 1,
                count: 0,
            },
            leaf(l, 0),
            leaf(r, l.len()),
        ],
        _ => panic!("grader tree: one or two leaves"),
    };
    Tree {
        prims,
        depth: groups.len() - 1,
        nodes,
        indices,
    }
}

/// Trees of one to three leaves of unit cubes along x (touching, apart,
/// overlapping), one leaf holding five boxes, and a root over two leaves of
/// three boxes each whose index array lists them out of order.
fn tiny_scenes() -> Vec<(Tree, String)> {
    let rows: [&[f32]; 6] = [
        &[0.0],
        &[0.0, 1.0],
        &[0.0, 1.5],
        &[0.0, 1.0, 2.5],
        &[0.0, 0.5, 1.0],
        &[3.0, 0.0, 1.5],
    ];
    let mut out: Vec<(Tree, String)> = rows
        .iter()
        .map(|xs| {
            let t = Tree::new(xs.iter().map(|&x| unit_at(x)).collect(), 1);
            let what = format!("the tree over [{}], one box per leaf", numbered(&t.prims));
            (t, what)
        })
        .collect();
    let five = vec![
        unit_at(0.0),
        unit_at(0.5),
        unit_at(3.0),
        b([0.5, 0.5, 0.5], [0.6, 0.6, 0.6]),
        unit_at(4.0),
    ];
    let what = format!(
        "a tree of one leaf holding all five boxes [{}]",
        numbered(&five)
    );
    out.push((by_hand(five, &[&[0, 1, 2, 3, 4]]), what));
    let six = vec![
        unit_at(0.0),
        unit_at(2.0),
        unit_at(1.0),
        unit_at(3.5),
        unit_at(-0.5),
        unit_at(2.9),
    ];
    let what = format!(
        "a root over two leaves, the first holding boxes 4, 0, 2 and the second 1, 5, 3 \
         (in the index array's order), where [{}]",
        numbered(&six)
    );
    out.push((by_hand(six, &[&[4, 0, 2], &[1, 5, 3]]), what));
    out
}

/// Each tree of exercise 5's dense scenes on its own: every box the unit
/// cube, so every pair overlaps; one of them 40 deep.
fn dense_scenes() -> Vec<(Tree, String)> {
    dense_cases()
        .into_iter()
        .flat_map(|(a, b, _)| [a, b])
        .map(|t| {
            let what = format!(
                "a tree of {} unit cubes, one per leaf, {} levels deep, where every box \
                 overlaps every box",
                t.prims.len(),
                t.depth
            );
            (t, what)
        })
        .collect()
}

/// A tree with an internal node's box moved 1000 away from everything, its
/// contents left in place.
pub(crate) struct Tampered {
    /// The tree, its node's box moved.
    pub(crate) tree: Tree,
    /// The node moved.
    pub(crate) node: u32,
    /// The primitives beneath it.
    pub(crate) under: Vec<u32>,
    /// The pairs expected, sorted: see [`without_crossing`].
    pub(crate) want: Vec<(u32, u32)>,
    /// The scene in words.
    pub(crate) what: String,
}

/// The brute-force pairs of `t` once the box of node `moved` misses
/// everything: a pair with one primitive beneath it is pruned where the
/// walk meets that node, one with both beneath it is found by the node's own
/// self walk (its children against each other), which never tests the
/// node's box.
fn without_crossing(t: &Tree, moved: u32) -> Vec<(u32, u32)> {
    let gone = beneath(t, moved);
    want(t)
        .into_iter()
        .filter(|(i, j)| gone.contains(i) == gone.contains(j))
        .collect()
}

/// Whether `got` is the scene's answer, explained by the rule it breaks
/// when a pair with one primitive beneath the moved node is there, or one
/// with both beneath it is missing.
fn pruned(s: &Tampered, got: &[(u32, u32)]) -> bool {
    let (node, inside) = (s.node, |i: &u32| s.under.contains(i));
    let sorted_got = sorted(got.to_vec());
    let extra = sorted_got
        .iter()
        .find(|p| s.want.binary_search(p).is_err() && inside(&p.0) != inside(&p.1));
    if let Some(&(i, j)) = extra {
        let (x, y) = if inside(&i) { (i, j) } else { (j, i) };
        return fail(format!(
            "self_pairs on {} reported the pair ({i}, {j}): {x} is beneath node {node}, whose \
             box was moved away, and {y} is not, so the walk that meets node {node} must \
             skip it with everything beneath it",
            s.what
        ));
    }
    let missed = s
        .want
        .iter()
        .find(|p| sorted_got.binary_search(p).is_err() && inside(&p.0));
    if let Some(&(i, j)) = missed {
        return fail(format!(
            "self_pairs on {} did not report the pair ({i}, {j}): both are beneath node \
             {node}, whose box was moved away, and such a pair is still found: inside their \
             leaf if they share one, else by walking the two children of the lowest node \
             above both against each other, which never tests node {node}'s own box",
            s.what
        ));
    }
    pairs_match("self_pairs", &s.what, &s.want, got)
}

/// Scenes where an internal node's box has been moved 1000 away from
/// everything, its contents left in place, with the pairs expected.
pub(crate) fn tampered_self_cases() -> Vec<Tampered> {
    let mut out = Vec::new();
    // (grid scene, node, direction, its name): node 2 is the root's second
    // child, nodes 3 and 6 are deeper. Each has pairs across its box (with
    // the rest of the grid) and pairs beneath it.
    let moves = [
        (0, 3, Vec3::X, "x"),
        (1, 2, Vec3::NEG_Y, "-y"),
        (3, 6, Vec3::Z, "z"),
    ];
    let mut grids: Vec<_> = grid_scenes().into_iter().map(Some).collect();
    for (g, node, dir, along) in moves {
        if let Some((t, what)) = grids[g].take() {
            out.push(tampered(t, node, dir, along, &what));
        }
    }
    // Three overlapping cubes: only the pair beneath the moved node is left.
    let t = Tree::new(vec![unit_at(0.0), unit_at(0.5), unit_at(1.0)], 1);
    let inner = (1..t.nodes.len() as u32).find(|&i| !t.nodes[i as usize].is_leaf());
    let what = format!("the tree over [{}], one box per leaf", numbered(&t.prims));
    if let Some(node) = inner {
        out.push(tampered(t, node, Vec3::X, "x", &what));
    }
    out
}

/// `t` with node `node`'s box moved 1000 along `dir`, the pairs expected
/// and the scene in words (`what` names the tree).
fn tampered(mut tree: Tree, node: u32, dir: Vec3, along: &str, what: &str) -> Tampered {
    let want = without_crossing(&tree, node);
    let under = beneath(&tree, node);
    let what = format!(
        "{what}, with the box of internal node {node} ({} primitives beneath it) moved \
         1000 along {along}, its contents left in place",
        under.len()
    );
    move_node(&mut tree, node, dir * 1000.0);
    Tampered {
        tree,
        node,
        under,
        want,
        what,
    }
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 6;

    /// The pair `(p, q)` as pushed: smaller first, except in answer 6.
    fn pair(which: u32, p: u32, q: u32) -> (u32, u32) {
        if which == 6 {
            (p, q)
        } else {
            (p.min(q), p.max(q))
        }
    }

    /// The primitives of leaves `x` and `y` against each other, by their
    /// own boxes.
    fn leaf_pair(
        which: u32,
        t: &Bvh<Aabb>,
        p: &[Aabb],
        x: &Node<Aabb>,
        y: &Node<Aabb>,
        out: &mut Vec<(u32, u32)>,
    ) {
        for &a in t.leaf_primitives(x) {
            for &c in t.leaf_primitives(y) {
                if p[a as usize].overlaps(&p[c as usize]) {
                    out.push(pair(which, a, c));
                }
            }
        }
    }

    /// Exercise 5's walk of nodes `i` and `j` of one tree.
    fn cross(which: u32, t: &Bvh<Aabb>, p: &[Aabb], (i, j): (u32, u32), out: &mut Vec<(u32, u32)>) {
        let (x, y) = (&t.nodes()[i as usize], &t.nodes()[j as usize]);
        if !x.bv.overlaps(&y.bv) {
            return;
        }
        if x.is_leaf() && y.is_leaf() {
            return leaf_pair(which, t, p, x, y, out);
        }
        let open_a = Reference.descend_a(x, y);
        if let Some((l, r)) = if open_a { x.children() } else { y.children() } {
            for c in [l, r] {
                cross(which, t, p, if open_a { (c, j) } else { (i, c) }, out);
            }
        }
    }

    pub fn self_pairs(which: u32, t: &Bvh<Aabb>, p: &[Aabb], out: &mut Vec<(u32, u32)>) {
        // 2: the two-tree walk of the tree against itself.
        if which == 2 {
            return Reference.informed_dfs(t, p, t, p, out);
        }
        let nodes = t.nodes();
        for (n, x) in nodes.iter().enumerate() {
            match x.children() {
                None => {
                    // 1: forgets the pairs inside a leaf.
                    let ids = if which == 1 {
                        &[][..]
                    } else {
                        t.leaf_primitives(x)
                    };
                    for (k, &a) in ids.iter().enumerate() {
                        // 3: each primitive with itself too.
                        for &c in &ids[if which == 3 { k } else { k + 1 }..] {
                            if p[a as usize].overlaps(&p[c as usize]) {
                                out.push(pair(which, a, c));
                            }
                        }
                    }
                    // 5: no pruning: every later leaf, by the primitives' boxes only.
                    if which == 5 {
                        for y in nodes[n + 1..].iter().filter(|y| y.is_leaf()) {
                            leaf_pair(which, t, p, x, y, out);
                        }
                    }
                }
                // 4: only the root's children against each other.
                Some((l, r)) if which != 5 && (which != 4 || n == 0) => {
                    cross(which, t, p, (l, r), out)
                }
                Some(_) => {}
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bvhkit::query::SelfPairs;
    use bvhkit::{Descent, PairTraversal};

    /// The expected answer on each tampered tree is what the library's self
    /// query finds there, with each informed traversal; and each scene
    /// both drops pairs (so a pass without pruning fails) and keeps pairs
    /// beneath the moved node (so a walk that tests the node's own box, or
    /// the tree against itself, fails).
    #[test]
    fn tampered_expectations_are_the_librarys() {
        let cases = tampered_self_cases();
        assert_eq!(cases.len(), 4);
        for Tampered {
            tree: t,
            node,
            under,
            want,
            what,
        } in &cases
        {
            for traversal in [
                PairTraversal::Recursive(Descent::Larger),
                PairTraversal::Stack(Descent::Larger),
                PairTraversal::Stack(Descent::Simultaneous),
            ] {
                let mut got = Vec::new();
                SelfPairs::new(&t.bvh(), &t.prims)
                    .keep_adjacent()
                    .traversal(traversal)
                    .for_each(|i, j| got.push((i, j)))
                    .unwrap();
                assert_eq!(&sorted(got), want, "{traversal:?} on {what}");
            }
            let mut all = Vec::new();
            brute_force::self_pairs(&t.prims, |i, j| all.push((i, j)));
            assert!(want.len() < all.len(), "{what}");
            assert!(!t.nodes[*node as usize].is_leaf(), "{what}");
            assert!(
                want.iter()
                    .any(|(i, j)| under.contains(i) && under.contains(j)),
                "{what}"
            );
        }
    }

    /// The hand-written trees are what the library accepts, and the honest
    /// scenes hold pairs inside leaves and across them.
    #[test]
    fn hand_trees_are_valid() {
        for (t, what) in tiny_scenes() {
            let mut got = Vec::new();
            SelfPairs::new(&t.bvh(), &t.prims)
                .keep_adjacent()
                .for_each(|i, j| got.push((i, j)))
                .unwrap();
            assert_eq!(sorted(got), want(&t), "{what}");
        }
    }
}
