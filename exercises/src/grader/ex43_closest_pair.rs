//! Exercise 43: the closest pair of two trees by branch and bound. The
//! checks, and the plausible wrong answers they must reject. The primitives
//! are boxes, measured by `PairDistance` (the squared distance between two
//! boxes); the expected distance is `brute_force::closest_pair`'s. The
//! grader counts the measurements, and moves node boxes away from their
//! contents to see that the walk prunes by what the boxes say, nearer
//! child pair first.

use super::common::*;
use super::ex05_recursive_pairs::{beneath, move_node};
use bvhkit::query::PairDistance;

/// The checks of exercise 43.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 43,
            name: "empty trees, one box against one box, a one-leaf tree against a row",
            points: 2,
            run: |e| small_scenes().iter().all(|s| closest_is(e, s, brute(s))),
        },
        Check {
            exercise: 43,
            name:
                "the closest distance of grids and scattered boxes, as testing every pair finds it",
            points: 3,
            run: |e| honest_scenes().iter().all(|s| closest_is(e, s, brute(s))),
        },
        Check {
            exercise: 43,
            name: "ties: any pair at the smallest distance, really at that distance",
            points: 1,
            run: |e| tie_scenes().iter().all(|s| closest_is(e, s, brute(s))),
        },
        Check {
            exercise: 43,
            name: "prunes by the boxes: nothing beneath a node moved 1000 away is measured",
            points: 2,
            run: |e| tampered_scenes().iter().all(|t| pruned(e, t)),
        },
        Check {
            exercise: 43,
            name: "branch and bound: the right answer with few calls (at most 1.5x the reference's + 2)",
            points: 3,
            run: |e| {
                work_scenes().iter().all(|s| {
                    let (got, mine) = ask(e, s);
                    let (_, reference) = ask(&Reference, s);
                    let allowed = (reference.len() * 3) / 2 + 2;
                    // Few calls count only with the right answer.
                    if !(measured_fairly(s, &mine) && answer_is(s, brute(s), got)) {
                        return false;
                    }
                    mine.len() <= allowed
                        || fail(format!(
                            "closest_pair on {} called distance {} times, branch and bound \
                             (the nearer child pair first, a pair skipped when its bound is \
                             not below the best) needs {}: at most {allowed} allowed",
                            s.what,
                            mine.len(),
                            reference.len(),
                        ))
                })
            },
        },
    ]
}

/// What `closest_pair` returns: a pair and its squared distance.
type Answer = Option<(u32, u32, f64)>;

/// Two trees of boxes and the scene in words.
struct Scene {
    a: Tree,
    b: Tree,
    what: String,
}

fn scene(a: Tree, b: Tree, what: impl Into<String>) -> Scene {
    Scene {
        a,
        b,
        what: what.into(),
    }
}

/// The squared distance between box `i` of A and box `j` of B.
fn measure(s: &Scene, i: u32, j: u32) -> Option<f64> {
    let (p, q) = (s.a.prims.get(i as usize)?, s.b.prims.get(j as usize)?);
    Some(p.closest_points(q).distance_squared)
}

/// Asks `e` for the closest pair of the scene; returns its answer and the
/// pairs it measured, in order (a pair out of range measures as NaN).
fn ask(e: &dyn Exercises, s: &Scene) -> (Answer, Vec<(u32, u32)>) {
    let mut calls = Vec::new();
    let got = e.closest_pair(&s.a.bvh(), &s.b.bvh(), &mut |i, j| {
        calls.push((i, j));
        measure(s, i, j).unwrap_or(f64::NAN)
    });
    (got, calls)
}

/// The smallest squared distance over every pair.
fn brute(s: &Scene) -> Option<f64> {
    brute_force::closest_pair(&s.a.prims, &s.b.prims).map(|c| c.points.distance_squared)
}

/// Whether the pairs measured are in range and none twice, explained with
/// the first that is not.
fn measured_fairly(s: &Scene, calls: &[(u32, u32)]) -> bool {
    let (na, nb) = (s.a.prims.len() as u32, s.b.prims.len() as u32);
    if let Some((i, j)) = calls.iter().find(|(i, j)| *i >= na || *j >= nb) {
        return fail(format!(
            "closest_pair on {} called distance({i}, {j}): A has {na} primitives and B {nb}, \
             and distance takes an index of A, then one of B",
            s.what
        ));
    }
    let seen = sorted(calls.to_vec());
    match seen.windows(2).find(|w| w[0] == w[1]) {
        None => true,
        Some(w) => fail(format!(
            "closest_pair on {} called distance{:?} twice ({} calls in all): each pair is \
             measured once",
            s.what,
            w[0],
            calls.len()
        )),
    }
}

/// The answer must be a pair at the squared distance `want` (`None` for
/// `None`), measured fairly.
fn closest_is(e: &dyn Exercises, s: &Scene, want: Option<f64>) -> bool {
    let (got, calls) = ask(e, s);
    measured_fairly(s, &calls) && answer_is(s, want, got)
}

/// `got` is `want` as a distance, and its pair really is at that distance.
fn answer_is(s: &Scene, want: Option<f64>, got: Answer) -> bool {
    let call = format!("closest_pair on {}", s.what);
    match (want, got) {
        (None, None) => true,
        (None, Some(g)) => fail(format!("{call} returned {g:?}, expected None")),
        (Some(w), None) => fail(format!(
            "{call} returned None, expected a pair at squared distance {w}"
        )),
        (Some(w), Some((i, j, d))) => match measure(s, i, j) {
            None => fail(format!(
                "{call} returned ({i}, {j}, {d}): A has {} primitives and B {} (the pair is \
                 (index in A, index in B))",
                s.a.prims.len(),
                s.b.prims.len()
            )),
            Some(real) if d != w => fail(format!(
                "{call} returned ({i}, {j}, {d}), expected a pair at squared distance {w} \
                 (the pair ({i}, {j}) is at {real})"
            )),
            Some(real) if real != d => fail(format!(
                "{call} returned ({i}, {j}, {d}), but distance({i}, {j}) is {real}: return \
                 the pair whose distance is the smallest, with that distance"
            )),
            Some(_) => true,
        },
    }
}

/// `n` unit cubes along x, two apart (at x = 0, 2, 4, ..), from `x0`.
fn row(n: usize, x0: f32) -> Vec<Aabb> {
    (0..n).map(|i| unit_at(x0 + 2.0 * i as f32)).collect()
}

/// Scattered boxes: `n` of them in a cube `size` wide centred at `at`,
/// each between `small` and `small + spread` wide per axis.
fn scattered(n: usize, seed: u64, size: f32, at: Vec3, small: f32, spread: f32) -> Vec<Aabb> {
    let mut r = Rng(seed);
    (0..n)
        .map(|_| {
            let lo = r.point(size, at);
            let d = Vec3::new(r.next(), r.next(), r.next()) * spread + small;
            Aabb::new(lo, lo + d)
        })
        .collect()
}

/// Empty trees, one box against one box (apart and overlapping), a
/// one-box tree against a row (from either side), and one leaf of five
/// boxes against a row.
fn small_scenes() -> Vec<Scene> {
    let one = || Tree::new(vec![unit_at(0.0)], 1);
    let empty = || Tree::new(vec![], 1);
    let five = vec![
        unit_at(3.0),
        b([0.0, 5.0, 0.0], [1.0, 6.0, 1.0]),
        unit_at(-4.0),
        b([-2.0, -3.0, 0.0], [-1.0, -2.0, 1.0]),
        unit_at(1.5),
    ];
    vec![
        scene(
            empty(),
            one(),
            "A empty, B = one leaf holding [min (0, 0, 0), max (1, 1, 1)]",
        ),
        scene(
            one(),
            empty(),
            "A = one leaf holding [min (0, 0, 0), max (1, 1, 1)], B empty",
        ),
        scene(empty(), empty(), "two empty trees"),
        scene(
            one(),
            Tree::new(vec![unit_at(3.0)], 1),
            "A = one leaf holding [min (0, 0, 0), max (1, 1, 1)], B = one leaf holding \
             [min (3, 0, 0), max (4, 1, 1)]",
        ),
        scene(
            one(),
            Tree::new(vec![b([0.5, 0.5, 0.5], [2.0, 2.0, 2.0])], 1),
            "A = one leaf holding [min (0, 0, 0), max (1, 1, 1)], B = one leaf holding \
             [min (0.5, 0.5, 0.5), max (2, 2, 2)] (overlapping)",
        ),
        scene(
            Tree::new(vec![unit_at(-5.0)], 1),
            Tree::new(row(16, 0.0), 1),
            "A = one leaf holding [min (-5, 0, 0), max (-4, 1, 1)], B = 16 unit cubes at x = \
             0, 2, .., 30, one per leaf",
        ),
        scene(
            Tree::new(row(16, 0.0), 1),
            Tree::new(vec![unit_at(34.0)], 1),
            "A = 16 unit cubes at x = 0, 2, .., 30, one per leaf, B = one leaf holding \
             [min (34, 0, 0), max (35, 1, 1)]",
        ),
        scene(
            Tree::new(five, 8),
            Tree::new(row(8, 7.0), 1),
            "A = one leaf holding five boxes [min (3, 0, 0), max (4, 1, 1)], [min (0, 5, 0), \
             max (1, 6, 1)], [min (-4, 0, 0), max (-3, 1, 1)], [min (-2, -3, 0), max (-1, -2, \
             1)], [min (1.5, 0, 0), max (2.5, 1, 1)], B = 8 unit cubes at x = 7, 9, .., 21, \
             one per leaf",
        ),
    ]
}

/// Grids apart and overlapping, and scattered boxes mixed and apart, with
/// leaves of one to four boxes.
fn honest_scenes() -> Vec<Scene> {
    vec![
        scene(
            Tree::new(boxes(300, 1, Vec3::ZERO), 1),
            Tree::new(boxes(250, 2, Vec3::new(11.5, 0.3, 0.2)), 3),
            "the grid of 300 boxes (one per leaf) and the grid of 250 boxes (up to 3 per \
             leaf) beside it along x",
        ),
        scene(
            Tree::new(boxes(64, 3, Vec3::ZERO), 4),
            Tree::new(boxes(500, 4, Vec3::new(-2.0, 1.0, 0.0)), 1),
            "the grid of 64 boxes (up to 4 per leaf) and the grid of 500 boxes (one per \
             leaf) overlapping it",
        ),
        mixed(),
        apart(),
    ]
}

/// 200 and 150 small boxes scattered through the same 40-wide cube.
fn mixed() -> Scene {
    scene(
        Tree::new(scattered(200, 4301, 40.0, Vec3::ZERO, 0.1, 0.5), 2),
        Tree::new(scattered(150, 4302, 40.0, Vec3::ZERO, 0.1, 0.5), 1),
        "200 boxes (up to 2 per leaf) and 150 boxes (one per leaf), 0.1 to 0.6 wide, \
         scattered through the same cube 40 wide",
    )
}

/// 120 and 90 boxes scattered through two cubes apart along a diagonal.
fn apart() -> Scene {
    scene(
        Tree::new(scattered(120, 4303, 20.0, Vec3::ZERO, 0.5, 1.5), 3),
        Tree::new(
            scattered(90, 4304, 20.0, Vec3::new(26.0, 22.0, 18.0), 0.5, 1.5),
            4,
        ),
        "120 boxes (up to 3 per leaf) and 90 boxes (up to 4 per leaf), 0.5 to 2 wide, \
         scattered through two cubes 20 wide centred at (0, 0, 0) and (26, 22, 18)",
    )
}

/// Two layers of 8 x 8 unit cubes, two apart in x and y, one above the
/// other with a gap of 1: each cube of A faces one of B at distance 1 (B
/// numbered the other way round), every other pair is farther.
fn layers(leaf: u32) -> Scene {
    let layer = |z: f32| -> Vec<Aabb> {
        (0..64)
            .map(|k| {
                let o = Vec3::new(2.0 * (k % 8) as f32, 2.0 * (k / 8) as f32, z);
                Aabb::new(o, o + Vec3::ONE)
            })
            .collect()
    };
    let mut top = layer(2.0);
    top.reverse();
    scene(
        Tree::new(layer(0.0), leaf),
        Tree::new(top, leaf),
        format!(
            "two layers of 8 x 8 unit cubes two apart (up to {leaf} per leaf), B's 1 above \
             A's: 64 pairs face each other at distance 1, box k of A facing box 63 - k of B"
        ),
    )
}

/// Scenes where many pairs share the smallest distance.
fn tie_scenes() -> Vec<Scene> {
    let stacked = vec![
        b([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]),
        b([0.0, 0.0, 1.0], [1.0, 1.0, 2.0]),
    ];
    vec![
        layers(1),
        layers(4),
        scene(
            Tree::new(stacked, 1),
            Tree::new(vec![unit_at(3.0), b([3.0, 0.0, 0.5], [4.0, 1.0, 1.5])], 1),
            "A = [min (0, 0, 0), max (1, 1, 1)], [min (0, 0, 1), max (1, 1, 2)], B = [min \
             (3, 0, 0), max (4, 1, 1)], [min (3, 0, 0.5), max (4, 1, 1.5)], one per leaf: \
             every pair at distance 2",
        ),
    ]
}

/// Scenes for counting the work: a row against a cube beyond either end
/// (the nearer child pair first finds it at once), the layers (a pair at
/// exactly the best distance is skipped), grids apart, boxes apart.
fn work_scenes() -> Vec<Scene> {
    let mut out = vec![
        scene(
            Tree::new(row(64, 0.0), 1),
            Tree::new(vec![unit_at(130.0)], 1),
            "A = 64 unit cubes at x = 0, 2, .., 126, one per leaf, B = one leaf holding [min \
             (130, 0, 0), max (131, 1, 1)]",
        ),
        scene(
            Tree::new(vec![unit_at(-4.0)], 1),
            Tree::new(row(64, 0.0), 1),
            "A = one leaf holding [min (-4, 0, 0), max (-3, 1, 1)], B = 64 unit cubes at x = \
             0, 2, .., 126, one per leaf",
        ),
        layers(1),
    ];
    let mut grids = honest_scenes().into_iter();
    if let Some(s) = grids.next() {
        out.push(s);
    }
    out.push(apart());
    out
}

/// A scene with one node's box moved 1000 away from its contents.
struct Tampered {
    scene: Scene,
    /// Which tree (`'A'` or `'B'`) and node was moved.
    tree: char,
    node: u32,
    /// The primitives beneath it (of that tree).
    under: Vec<u32>,
    /// The smallest squared distance over the pairs not beneath it.
    want: f64,
}

/// Moves node `node` of A (or of B, when `in_b`) 1000 along `dir`; the
/// answer expected is the closest pair with no primitive beneath it: the
/// moved node's sibling pair is nearer, so it is walked first and gives a
/// best far below the moved node's bound.
fn tampered(mut s: Scene, in_b: bool, node: u32, dir: Vec3, along: &str) -> Tampered {
    let t = if in_b { &mut s.b } else { &mut s.a };
    let under = beneath(t, node);
    let kind = if t.nodes[node as usize].is_leaf() {
        "leaf"
    } else {
        "internal node"
    };
    move_node(t, node, dir * 1000.0);
    let mut want = f64::INFINITY;
    for (i, p) in s.a.prims.iter().enumerate() {
        for (j, q) in s.b.prims.iter().enumerate() {
            let k = if in_b { j } else { i } as u32;
            if !under.contains(&k) {
                want = want.min(p.closest_points(q).distance_squared);
            }
        }
    }
    let tree = if in_b { 'B' } else { 'A' };
    s.what = format!(
        "{}, with the box of {tree}'s {kind} {node} ({} primitives beneath it) moved 1000 \
         along {along}, its contents left in place",
        s.what,
        under.len()
    );
    Tampered {
        scene: s,
        tree,
        node,
        under,
        want,
    }
}

/// The node at `depth` (the root at 0) on the path from the root of `t`
/// to the leaf holding primitive `p`.
fn ancestor(t: &Tree, p: u32, depth: usize) -> u32 {
    let mut n = 0;
    for _ in 0..depth {
        match t.nodes[n as usize].children() {
            Some((l, r)) => n = if beneath(t, l).contains(&p) { l } else { r },
            None => break,
        }
    }
    n
}

/// The closest pair of a scene, by testing every pair.
fn closest_of(s: &Scene) -> (u32, u32) {
    brute_force::closest_pair(&s.a.prims, &s.b.prims).map_or((0, 0), |c| (c.a, c.b))
}

/// Scenes where the closest pair is beneath a node whose box was moved
/// 1000 away: the parent of the cube nearest to a cube beyond a row, an
/// internal node two levels down in the grids, the leaf in the scattered
/// boxes.
fn tampered_scenes() -> Vec<Tampered> {
    let mut out = Vec::new();
    let s = scene(
        Tree::new(vec![unit_at(33.0)], 1),
        Tree::new(row(16, 0.0), 1),
        "A = one leaf holding [min (33, 0, 0), max (34, 1, 1)], B = 16 unit cubes at x = 0, \
         2, .., 30, one per leaf",
    );
    let node = ancestor(&s.b, 15, s.b.depth - 1);
    out.push(tampered(s, true, node, Vec3::Z, "z"));
    let s = honest_scenes().swap_remove(0);
    let (i, _) = closest_of(&s);
    let node = ancestor(&s.a, i, 2);
    out.push(tampered(s, false, node, Vec3::NEG_X, "-x"));
    let s = apart();
    let (_, j) = closest_of(&s);
    let node = ancestor(&s.b, j, s.b.depth);
    out.push(tampered(s, true, node, Vec3::Y, "y"));
    out
}

/// Nothing beneath the moved node is measured, and the answer is the
/// closest pair of the rest.
fn pruned(e: &dyn Exercises, t: &Tampered) -> bool {
    let s = &t.scene;
    let (got, calls) = ask(e, s);
    if !measured_fairly(s, &calls) {
        return false;
    }
    let beneath_it = |&(i, j): &(u32, u32)| t.under.contains(if t.tree == 'B' { &j } else { &i });
    if let Some((i, j)) = calls.iter().find(|p| beneath_it(p)) {
        let x = if t.tree == 'B' { j } else { i };
        return fail(format!(
            "closest_pair on {} measured the pair ({i}, {j}): {x} is beneath {}'s node {}, \
             whose box is 1000 away, and the nearer child pair beside it gives a best far \
             below that node's bound, so it must be skipped with everything beneath it (are \
             the child pairs visited nearer first, and is the bound tested when a pair is \
             taken?)",
            s.what, t.tree, t.node
        ));
    }
    answer_is(s, Some(t.want), got)
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 10;

    /// Not wrong: the walk written recursively, the second child pair first
    /// on equal bounds, the last pair found kept on equal distances. Scores
    /// full marks (see the tests).
    pub const HONEST: u32 = 100;

    pub fn closest_pair(
        which: u32,
        a: &Bvh<Aabb>,
        b: &Bvh<Aabb>,
        distance: &mut dyn FnMut(u32, u32) -> f64,
    ) -> Option<(u32, u32, f64)> {
        let single = |t: &Bvh<Aabb>| t.nodes().first().is_some_and(|n| n.is_leaf());
        match which {
            // 1: brute force, every pair: right, and all the work.
            1 => {
                let mut best: Option<(u32, u32, f64)> = None;
                for i in 0..a.primitive_count() as u32 {
                    for j in 0..b.primitive_count() as u32 {
                        let d = distance(i, j);
                        if best.is_none_or(|(_, _, e)| d < e) {
                            best = Some((i, j, d));
                        }
                    }
                }
                best
            }
            // 9: a tree that is one leaf has "no pairs of nodes": None.
            9 if single(a) || single(b) => None,
            2..=8 | 10 => walk(which, a, b, distance),
            HONEST => {
                let mut best = None;
                if !a.nodes().is_empty() && !b.nodes().is_empty() {
                    recurse(a, b, (0, 0), distance, &mut best);
                }
                best
            }
            _ => Reference.closest_pair(a, b, distance),
        }
    }

    /// The walk with one slip each:
    /// 2: tests the bound only at two leaves, children in stored order;
    /// 3: children in stored order (the bound tested right);
    /// 4: skips a pair only when its bound is above the best (`>`);
    /// 5: the bound is the squared distance between the boxes' centres;
    /// 6: visits only the nearer child pair;
    /// 7: returns after the first leaf pair;
    /// 8: each leaf pair's own closest replaces the best;
    /// 10: tests the bound when queuing a pair, not when taking it.
    fn walk(
        which: u32,
        a: &Bvh<Aabb>,
        b: &Bvh<Aabb>,
        distance: &mut dyn FnMut(u32, u32) -> f64,
    ) -> Option<(u32, u32, f64)> {
        let (na, nb) = (a.nodes(), b.nodes());
        if na.is_empty() || nb.is_empty() {
            return None;
        }
        let bound = |i: u32, j: u32| {
            let (x, y) = (&na[i as usize].bv, &nb[j as usize].bv);
            if which == 5 {
                x.center()
                    .as_dvec3()
                    .distance_squared(y.center().as_dvec3())
            } else {
                x.closest_points(y).distance_squared
            }
        };
        let skip = |bd: f64, best: Option<(u32, u32, f64)>| {
            best.is_some_and(|(_, _, d)| if which == 4 { bd > d } else { bd >= d })
        };
        let mut best: Option<(u32, u32, f64)> = None;
        let mut stack = vec![(0u32, 0u32)];
        while let Some((i, j)) = stack.pop() {
            let (x, y) = (&na[i as usize], &nb[j as usize]);
            let leaves = x.is_leaf() && y.is_leaf();
            let test = match which {
                2 => leaves,
                10 => false,
                _ => true,
            };
            if test && skip(bound(i, j), best) {
                continue;
            }
            if leaves {
                let mut here: Option<(u32, u32, f64)> = None;
                for &p in a.leaf_primitives(x) {
                    for &q in b.leaf_primitives(y) {
                        let d = distance(p, q);
                        if here.is_none_or(|(_, _, e)| d < e) {
                            here = Some((p, q, d));
                        }
                    }
                }
                best = match (which, best, here) {
                    (8, _, h) => h.or(best),
                    (_, Some(o), Some(h)) if o.2 <= h.2 => Some(o),
                    (_, o, h) => h.or(o),
                };
                if which == 7 {
                    return best;
                }
                continue;
            }
            let open_a = Reference.descend_a(x, y);
            let Some((l, r)) = (if open_a { x.children() } else { y.children() }) else {
                continue;
            };
            let mut kids: Vec<(u32, u32)> = if open_a {
                vec![(l, j), (r, j)]
            } else {
                vec![(i, l), (i, r)]
            };
            if which != 2 && which != 3 {
                kids.sort_by(|p, q| bound(p.0, p.1).total_cmp(&bound(q.0, q.1)));
            }
            if which == 6 {
                kids.truncate(1);
            }
            if which == 10 {
                kids.retain(|&(p, q)| !skip(bound(p, q), best));
            }
            stack.extend(kids.into_iter().rev());
        }
        best
    }

    /// The honest walk, recursive: the second child pair first on a tie,
    /// and a pair as close as the best replaces it.
    fn recurse(
        a: &Bvh<Aabb>,
        b: &Bvh<Aabb>,
        (i, j): (u32, u32),
        distance: &mut dyn FnMut(u32, u32) -> f64,
        best: &mut Option<(u32, u32, f64)>,
    ) {
        let (x, y) = (&a.nodes()[i as usize], &b.nodes()[j as usize]);
        let bound = |x: &Node<Aabb>, y: &Node<Aabb>| x.bv.closest_points(&y.bv).distance_squared;
        if best.is_some_and(|(_, _, d)| bound(x, y) >= d) {
            return;
        }
        if x.is_leaf() && y.is_leaf() {
            for &p in a.leaf_primitives(x) {
                for &q in b.leaf_primitives(y) {
                    let d = distance(p, q);
                    if best.is_none_or(|(_, _, e)| d <= e) {
                        *best = Some((p, q, d));
                    }
                }
            }
            return;
        }
        let kids = if Reference.descend_a(x, y) {
            x.children().map(|(l, r)| [(l, j), (r, j)])
        } else {
            y.children().map(|(l, r)| [(i, l), (i, r)])
        };
        let Some([first, second]) = kids else {
            return;
        };
        let at = |(p, q): (u32, u32)| bound(&a.nodes()[p as usize], &b.nodes()[q as usize]);
        let order = if at(first) < at(second) {
            [first, second]
        } else {
            [second, first]
        };
        for pair in order {
            recurse(a, b, pair, distance, best);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::wrong::HONEST;
    use super::*;
    use crate::grader::grade_exercises;
    use crate::grader::wrong::Wrong;
    use bvhkit::query::Distance;

    /// The library's branch and bound finds the expected distance on every
    /// scene, the tampered ones included (it prunes the moved node too).
    #[test]
    fn expectations_are_the_librarys() {
        let mut scenes: Vec<(Scene, Option<f64>)> = Vec::new();
        for s in small_scenes()
            .into_iter()
            .chain(honest_scenes())
            .chain(tie_scenes())
            .chain(work_scenes())
        {
            let want = brute(&s);
            scenes.push((s, want));
        }
        for t in tampered_scenes() {
            scenes.push((t.scene, Some(t.want)));
        }
        for (s, want) in &scenes {
            let got = Distance::new(&s.a.bvh(), &s.a.prims, &s.b.bvh(), &s.b.prims)
                .closest()
                .unwrap()
                .map(|c| c.points.distance_squared);
            assert_eq!(got, *want, "{}", s.what);
        }
    }

    /// Each tampered scene's answer differs from the brute-force one (so
    /// brute force fails it), and the honest scenes are not trivial: the
    /// grids apart and the scattered boxes are at a positive distance, the
    /// overlapping grids at 0, and the reference does far less work than
    /// brute force where the work is counted.
    #[test]
    fn scenes_discriminate() {
        for t in tampered_scenes() {
            let all = brute(&t.scene).unwrap();
            assert!(t.want > all, "{}: {} vs {all}", t.scene.what, t.want);
            assert!(!t.under.is_empty(), "{}", t.scene.what);
        }
        let d: Vec<f64> = honest_scenes().iter().map(|s| brute(s).unwrap()).collect();
        assert!(
            d[0] > 0.0 && d[1] == 0.0 && d[2] > 0.0 && d[3] > 0.0,
            "{d:?}"
        );
        for s in work_scenes() {
            let (_, calls) = ask(&Reference, &s);
            let all = s.a.prims.len() * s.b.prims.len();
            assert!(
                calls.len() * 4 <= all,
                "{}: {} of {all}",
                s.what,
                calls.len()
            );
        }
    }

    /// Another honest walk (recursive, the other order on ties, the last of
    /// equal pairs kept) scores every point.
    #[test]
    fn an_honest_variant_scores_everything() {
        let e: &'static Wrong = Box::leak(Box::new(Wrong {
            exercise: 43,
            k: HONEST,
        }));
        let s = &grade_exercises(e, &[43], crate::grader::CHECK_TIME_LIMIT, |_| {})[0];
        assert_eq!(s.earned, s.possible, "{s:?}");
    }

    /// Which checks each wrong answer fails (printed with --nocapture).
    #[test]
    fn each_wrong_answer_fails_where_expected() {
        let names: Vec<&str> = checks().iter().map(|c| c.name).collect();
        for k in 1..=wrong::COUNT {
            let e: &'static Wrong = Box::leak(Box::new(Wrong { exercise: 43, k }));
            let s = &grade_exercises(e, &[43], crate::grader::CHECK_TIME_LIMIT, |_| {})[0];
            println!("wrong answer {k}: {}/{}", s.earned, s.possible);
            for f in &s.failed {
                println!("    {f}");
            }
            assert!(s.earned < s.possible, "wrong answer {k}: {s:?}");
            assert!(s.failed.iter().all(|f| !names.contains(&f.as_str())));
        }
    }
}
