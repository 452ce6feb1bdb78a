//! Exercise 5: the checks, and the plausible wrong answers they must reject.
//! Also the scenes exercise 6 shares: trees where every pair overlaps (full
//! and very deep ones) and trees with a node's box moved away from its
//! contents (to see that a traversal prunes).

use super::common::*;

/// The checks of exercise 5.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 5,
            name: "finds exactly the brute-force pairs on overlapping grids",
            points: 5,
            run: |e| {
                let cases = traversal_cases();
                let what = [
                    "the grids of 300 and 250 boxes (leaf sizes 1 and 3)",
                    "the grids of 64 and 500 boxes (leaf sizes 4 and 1)",
                ];
                cases[..2].iter().zip(what).all(|((a, b), what)| {
                    pairs_match(
                        "informed_dfs",
                        what,
                        &reference_pairs(a, b),
                        &run_dfs(e, a, b),
                    )
                })
            },
        },
        Check {
            exercise: 5,
            name: "tiny trees (1-3 leaves), apart and touching",
            points: 3,
            run: |e| {
                traversal_cases()[2..].iter().all(|(a, b)| {
                    let what = tiny(a, b);
                    pairs_match(
                        "informed_dfs",
                        &what,
                        &reference_pairs(a, b),
                        &run_dfs(e, a, b),
                    )
                })
            },
        },
        Check {
            exercise: 5,
            name: "full and very deep trees (depth 40) where every pair overlaps",
            points: 2,
            run: |e| {
                dense_cases().iter().all(|(a, b, what)| {
                    pairs_match(
                        "informed_dfs",
                        what,
                        &reference_pairs(a, b),
                        &run_dfs(e, a, b),
                    )
                })
            },
        },
        Check {
            exercise: 5,
            name: "reports each pair once",
            points: 2,
            run: |e| {
                let mut cases = traversal_cases();
                cases.extend(dense_cases().into_iter().map(|(a, b, _)| (a, b)));
                cases
                    .iter()
                    .all(|(a, b)| once("informed_dfs", &run_dfs(e, a, b)))
            },
        },
        Check {
            exercise: 5,
            name: "prunes: nothing beneath a node whose box misses is reported",
            points: 3,
            run: |e| {
                tampered_cases().iter().all(|(a, b, want, what)| {
                    pairs_match("informed_dfs", what, want, &run_dfs(e, a, b))
                })
            },
        },
    ]
}

fn run_dfs(e: &dyn Exercises, a: &Tree, b: &Tree) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    e.informed_dfs(&a.bvh(), &a.prims, &b.bvh(), &b.prims, &mut out);
    out
}

/// A tiny scene of [`traversal_cases`] in words.
pub(crate) fn tiny(a: &Tree, b: &Tree) -> String {
    let all = |t: &Tree| {
        let v: Vec<String> = t.prims.iter().map(show_box).collect();
        v.join(", ")
    };
    format!("A = [{}], B = [{}], one box per leaf", all(a), all(b))
}

/// Whether `got` (in any order) is `want` (sorted), explained with the
/// first pair missed or the first pair too many.
pub(crate) fn pairs_match(call: &str, what: &str, want: &[(u32, u32)], got: &[(u32, u32)]) -> bool {
    let got = sorted(got.to_vec());
    if got == want {
        return true;
    }
    let missed = want.iter().find(|p| got.binary_search(p).is_err());
    let extra = got.iter().find(|p| want.binary_search(p).is_err());
    let detail = match (missed, extra) {
        (Some(p), _) => format!("the pair {p:?} is missing"),
        (None, Some(p)) => format!("the pair {p:?} should not be there"),
        (None, None) => "some pairs came back more than once".to_string(),
    };
    fail(format!(
        "{call} on {what} gave {} pairs, expected {}: {detail}",
        got.len(),
        want.len()
    ))
}

/// Whether no pair of `got` is there twice, explained with the first one.
pub(crate) fn once(call: &str, got: &[(u32, u32)]) -> bool {
    let s = sorted(got.to_vec());
    match s.windows(2).find(|w| w[0] == w[1]) {
        None => true,
        Some(w) => fail(format!(
            "{call} reported the pair {:?} more than once ({} pairs in all)",
            w[0],
            got.len()
        )),
    }
}

/// One unit cube per leaf, each node's box the same cube: every pair of
/// nodes overlaps. Children `first, first + 1` as the builders store them.
fn cube_tree(nodes: Vec<Node<Aabb>>, depth: usize) -> Tree {
    let leaves = nodes.iter().filter(|n| n.is_leaf()).count();
    Tree {
        prims: vec![b([0.0; 3], [1.0; 3]); leaves],
        nodes,
        indices: (0..leaves as u32).collect(),
        depth,
    }
}

/// A complete tree of `depth` levels below the root, one primitive per leaf,
/// level by level; every box is the unit cube.
pub(crate) fn full_tree(depth: u32) -> Tree {
    let inner = (1u32 << depth) - 1;
    let nodes = (0..2 * inner + 1)
        .map(|i| Node {
            bv: b([0.0; 3], [1.0; 3]),
            first: if i < inner { 2 * i + 1 } else { i - inner },
            count: (i >= inner) as u32,
        })
        .collect();
    cube_tree(nodes, depth as usize)
}

/// A caterpillar `depth` deep: every internal node has an internal first
/// child and a leaf second child (the last one two leaves); every box is the
/// unit cube.
pub(crate) fn spine_tree(depth: u32) -> Tree {
    let mut nodes = Vec::new();
    let mut leaves = 0;
    let mut leaf = |nodes: &mut Vec<Node<Aabb>>| {
        nodes.push(Node {
            bv: b([0.0; 3], [1.0; 3]),
            first: leaves,
            count: 1,
        });
        leaves += 1;
    };
    // Spine node k (depth k) is at index 2k - 1 (the root at 0), its leaf
    // child at 2k + 2.
    for k in 0..depth {
        nodes.push(Node {
            bv: b([0.0; 3], [1.0; 3]),
            first: 2 * k + 1,
            count: 0,
        });
        if k > 0 {
            leaf(&mut nodes);
        }
    }
    leaf(&mut nodes);
    leaf(&mut nodes);
    cube_tree(nodes, depth as usize)
}

/// Trees in which every pair of nodes overlaps: full ones, and a very deep
/// one (depth 40, past anything a 32-bit mask could track).
pub(crate) fn dense_cases() -> Vec<(Tree, Tree, String)> {
    vec![
        (
            full_tree(4),
            full_tree(3),
            "two complete trees of depths 4 and 3 whose boxes are all the unit cube".into(),
        ),
        (
            spine_tree(40),
            full_tree(2),
            "a tree 40 deep (every internal node has a leaf child) and a complete tree of \
             depth 2, all boxes the unit cube"
                .into(),
        ),
    ]
}

/// Primitives at or beneath node `i`.
pub(crate) fn beneath(t: &Tree, i: u32) -> Vec<u32> {
    let n = &t.nodes[i as usize];
    match n.children() {
        None => t.indices[n.first as usize..(n.first + n.count) as usize].to_vec(),
        Some((l, r)) => [beneath(t, l), beneath(t, r)].concat(),
    }
}

/// Moves the box of node `i` (not its contents) by `by`.
pub(crate) fn move_node(t: &mut Tree, i: u32, by: Vec3) {
    let bv = &mut t.nodes[i as usize].bv;
    *bv = Aabb::new(bv.min + by, bv.max + by);
}

/// Two trees, the pairs expected from them, and the scene in words.
pub(crate) type Scene = (Tree, Tree, Vec<(u32, u32)>, String);

/// Scenes where a node's box has been moved far from everything, its
/// contents left in place: a traversal that prunes never looks beneath it,
/// one that walks every leaf pair (or tests only at the leaves) reports its
/// primitives' pairs. Each with the pairs expected and a description.
pub(crate) fn tampered_cases() -> Vec<Scene> {
    let mut out = Vec::new();
    let mut cases = traversal_cases().into_iter();
    let (Some((mut a0, mut b0)), Some((a1, mut b1))) = (cases.next(), cases.next()) else {
        return out;
    };
    let keep = |a: &Tree, b: &Tree, gone_a: &[u32], gone_b: &[u32]| -> Vec<(u32, u32)> {
        reference_pairs(a, b)
            .into_iter()
            .filter(|(i, j)| !gone_a.contains(i) && !gone_b.contains(j))
            .collect()
    };
    // A's node 3 (two levels down) and B's node 2 (the root's second child).
    let (ga, gb) = (beneath(&a0, 3), beneath(&b0, 2));
    let want = keep(&a0, &b0, &ga, &gb);
    let what = format!(
        "the grids of 300 and 250 boxes (leaf sizes 1 and 3) with the box of A's node 3 \
         (two levels below the root, {} primitives beneath) moved 1000 along x and the box of \
         B's node 2 ({} primitives beneath) moved 1000 along -y (their contents left in \
         place, so a traversal that prunes never looks beneath them)",
        ga.len(),
        gb.len()
    );
    move_node(&mut a0, 3, Vec3::X * 1000.0);
    move_node(&mut b0, 2, Vec3::Y * -1000.0);
    out.push((a0, b0, want, what));
    // B's root moved away: nothing at all.
    move_node(&mut b1, 0, Vec3::Z * 1000.0);
    out.push((
        a1,
        b1,
        Vec::new(),
        "the grids of 64 and 500 boxes (leaf sizes 4 and 1) with the box of B's root moved \
         1000 along z (its contents left in place; the roots miss, so nothing is reported)"
            .into(),
    ));
    // Two single leaves whose boxes touch; A's leaf box moved away.
    let (a2, b2) = (&traversal_cases()[2].0, &traversal_cases()[2].1);
    let (mut a2, b2) = (
        Tree::new(a2.prims.clone(), 1),
        Tree::new(b2.prims.clone(), 1),
    );
    move_node(&mut a2, 0, Vec3::X * -1000.0);
    out.push((
        a2,
        b2,
        Vec::new(),
        "A = one leaf holding [min (0, 0, 0), max (1, 1, 1)] but with its box moved to x = \
         -1000, B = one leaf holding [min (1, 0, 0), max (2, 1, 1)] (the leaves' boxes miss, \
         so nothing is reported)"
            .into(),
    ));
    out
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 7;

    /// A recursive walk with the slips of the wrong answers: `which` as in
    /// [`informed_dfs`].
    #[allow(clippy::too_many_arguments)]
    fn visit(
        which: u32,
        a: &Bvh<Aabb>,
        pa: &[Aabb],
        b: &Bvh<Aabb>,
        pb: &[Aabb],
        (i, j): (u32, u32),
        root: bool,
        out: &mut Vec<(u32, u32)>,
    ) {
        let (x, y) = (&a.nodes()[i as usize], &b.nodes()[j as usize]);
        let leaves = x.is_leaf() && y.is_leaf();
        let test = match which {
            3 => leaves,
            7 => !root,
            _ => true,
        };
        if test && !x.bv.overlaps(&y.bv) {
            return;
        }
        if leaves {
            for &p in a.leaf_primitives(x) {
                for &q in b.leaf_primitives(y) {
                    if pa[p as usize].overlaps(&pb[q as usize]) {
                        out.push(if which == 6 { (q, p) } else { (p, q) });
                    }
                }
            }
            return;
        }
        let mut go = |pair| visit(which, a, pa, b, pb, pair, false, out);
        if which == 5 {
            if let Some((l, r)) = x.children() {
                go((l, j));
                go((r, j));
            }
            if let Some((l, r)) = y.children() {
                go((i, l));
                go((i, r));
            }
            return;
        }
        let open_a = Reference.descend_a(x, y);
        let Some((l, r)) = (if open_a { x.children() } else { y.children() }) else {
            return;
        };
        let second = if which == 4 { l } else { r };
        for c in [l, second] {
            go(if open_a { (c, j) } else { (i, c) });
        }
    }

    pub fn informed_dfs(
        which: u32,
        a: &Bvh<Aabb>,
        pa: &[Aabb],
        b: &Bvh<Aabb>,
        pb: &[Aabb],
        out: &mut Vec<(u32, u32)>,
    ) {
        match which {
            // Tests the leaves' volumes but not the primitives inside.
            1 => {
                for x in a.nodes().iter().filter(|n| n.is_leaf()) {
                    for y in b.nodes().iter().filter(|n| n.is_leaf()) {
                        if x.bv.overlaps(&y.bv) {
                            for &p in a.leaf_primitives(x) {
                                for &q in b.leaf_primitives(y) {
                                    out.push((p, q));
                                }
                            }
                        }
                    }
                }
            }
            // No pruning: every pair of leaves in tree order, their boxes
            // then their primitives tested (right on honest trees).
            2 => {
                every_leaf_pair(a, pa, b, pb, out);
            }
            // 3: recursive, but tests boxes only at two leaves (no pruning).
            // 4: recurses into the first child twice, never the second.
            // 5: opens both nodes, each on its own: pairs come back twice.
            // 6: pushes the pair as (j, i).
            // 7: never tests the roots' boxes.
            3..=7 => visit(which, a, pa, b, pb, (0, 0), true, out),
            _ => Reference.informed_dfs(a, pa, b, pb, out),
        }
    }

    /// The traversal without pruning (wrong in exercises 5 and 6): every
    /// pair of leaves in tree order, their boxes then their primitives
    /// tested. Right on honest trees; the tampered ones catch it.
    pub fn every_leaf_pair(
        a: &Bvh<Aabb>,
        pa: &[Aabb],
        b: &Bvh<Aabb>,
        pb: &[Aabb],
        out: &mut Vec<(u32, u32)>,
    ) {
        for x in a.nodes().iter().filter(|n| n.is_leaf()) {
            for y in b.nodes().iter().filter(|n| n.is_leaf()) {
                if x.bv.overlaps(&y.bv) {
                    for &p in a.leaf_primitives(x) {
                        for &q in b.leaf_primitives(y) {
                            if pa[p as usize].overlaps(&pb[q as usize]) {
                                out.push((p, q));
                            }
                        }
                    }
                }
            }
        }
    }
}
