//! Exercise 22: best-first search for the nearest primitive. The checks,
//! and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 22.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 22,
            name: "the nearest primitive and its distance, as brute force finds it; None for no tree",
            points: 3,
            run: |e| {
                let mut r = Rng(22);
                nearest_cases().iter().all(|(what, t)| {
                    let tree = t.bvh();
                    (0..40).all(|_| {
                        let p = r.point(14.0, Vec3::new(4.5, 4.5, 1.0));
                        let call = call(what, p);
                        let want = nearest(&t.prims, p);
                        let got = e.best_first_nearest(&tree, &t.prims, p);
                        let Some((k, d)) = want else {
                            return same(call, None, got);
                        };
                        let Some((gk, gd, _)) = got else {
                            return fail(format!(
                                "{call} returned None, expected primitive {k} at distance {d}"
                            ));
                        };
                        let tol = 1e-5 * d.max(1.0);
                        let Some(b) = t.prims.get(gk as usize) else {
                            return fail(format!(
                                "{call} returned primitive {gk}, which does not exist (there \
                                 are {}); expected primitive {k} at distance {d}",
                                t.prims.len()
                            ));
                        };
                        if (dist(b, p) - d).abs() > tol {
                            return fail(format!(
                                "{call} returned primitive {gk}, at distance {} from p; the \
                                 nearest is primitive {k} at distance {d}",
                                dist(b, p)
                            ));
                        }
                        (gd - d).abs() <= tol
                            || fail(format!(
                                "{call} returned distance {gd} (primitive {gk}); expected {d}, \
                                 the distance itself (not its square)"
                            ))
                    })
                })
            },
        },
        Check {
            exercise: 22,
            name: "ties: among primitives at the same distance, the smallest index",
            points: 2,
            run: |e| {
                tie_cases().iter().all(|(what, t)| {
                    let tree = t.bvh();
                    tie_points().iter().all(|&p| {
                        let (k, d) = nearest(&t.prims, p).expect("a tie case has boxes");
                        let got = e.best_first_nearest(&tree, &t.prims, p).map(|a| (a.0, a.1));
                        same(call(what, p), Some((k, d)), got)
                    })
                })
            },
        },
        Check {
            exercise: 22,
            name: "best-first prunes: at most 1.5x the nodes the search needs (+ 2), not every node",
            points: 3,
            run: |e| {
                let mut r = Rng(23);
                nearest_cases()
                    .iter()
                    .filter(|(_, t)| !t.prims.is_empty())
                    .all(|(what, t)| {
                        let tree = t.bvh();
                        (0..40).all(|_| {
                            let p = r.point(14.0, Vec3::new(4.5, 4.5, 1.0));
                            let need = needed(t, p);
                            let got = e.best_first_nearest(&tree, &t.prims, p).map(|a| a.2);
                            got.is_some_and(|n| n * 2 <= need * 3 + 4)
                                || fail(format!(
                                    "{} returned {got:?} nodes taken; the search needs {need} \
                                     (the nodes no farther than the answer) of the tree's {}",
                                    call(what, p),
                                    t.nodes.len()
                                ))
                        })
                    })
            },
        },
        Check {
            exercise: 22,
            name: "the count: exactly the nodes taken from the queue (those no farther than the answer)",
            points: 2,
            run: |e| {
                let mut r = Rng(24);
                let cases = nearest_cases().into_iter().chain(tie_cases());
                cases
                    .filter(|(_, t)| !t.prims.is_empty())
                    .all(|(what, t)| {
                        let tree = t.bvh();
                        let points: Vec<Vec3> = (0..20)
                            .map(|_| r.point(14.0, Vec3::new(4.5, 4.5, 1.0)))
                            .chain(tie_points())
                            .collect();
                        points.iter().all(|&p| {
                            let got = e.best_first_nearest(&tree, &t.prims, p).map(|a| a.2);
                            same(
                                format!("{} (nodes taken)", call(&what, p)),
                                Some(needed(&t, p)),
                                got,
                            )
                        })
                    })
            },
        },
    ]
}

/// The distance from `p` to box `b`, as the statement computes it.
fn dist(b: &Aabb, p: Vec3) -> f32 {
    b.distance_squared(p).sqrt()
}

/// Brute force: the nearest primitive (the smallest index on a tie) and its distance.
fn nearest(prims: &[Aabb], p: Vec3) -> Option<(u32, f32)> {
    let mut best: Option<(u32, f32)> = None;
    for (k, b) in prims.iter().enumerate() {
        let d = dist(b, p);
        if best.is_none_or(|(_, x)| d < x) {
            best = Some((k as u32, d));
        }
    }
    best
}

/// The nodes a best-first search takes: those whose box is no farther than
/// the answer (every other node waits in the queue when the search stops).
fn needed(t: &Tree, p: Vec3) -> usize {
    let Some((_, d)) = nearest(&t.prims, p) else {
        return 0;
    };
    t.nodes.iter().filter(|n| dist(&n.bv, p) <= d).count()
}

fn call(what: &str, p: Vec3) -> String {
    format!("best_first_nearest({what}, p = {})", show_point(p))
}

/// Trees for the nearest-primitive search: empty, one box, and grids of boxes.
fn nearest_cases() -> Vec<(String, Tree)> {
    vec![
        ("an empty tree".into(), Tree::new(vec![], 1)),
        (
            "a tree over one box".into(),
            Tree::new(boxes(1, 31, Vec3::ZERO), 1),
        ),
        (
            "a tree over 60 jittered grid boxes, leaf size 1".into(),
            Tree::new(boxes(60, 37, Vec3::ZERO), 1),
        ),
        (
            "a tree over 300 jittered grid boxes, leaf size 4".into(),
            Tree::new(boxes(300, 41, Vec3::ZERO), 4),
        ),
    ]
}

/// Unit boxes on an 8 x 8 grid, each touching its neighbours, numbered out
/// of spatial order (box `k` at cell `13 k mod 64`): many primitives at
/// exactly the same distance from a grid point.
fn tie_cases() -> Vec<(String, Tree)> {
    let grid = || -> Vec<Aabb> {
        (0..64u32)
            .map(|k| {
                let c = k * 13 % 64;
                let o = Vec3::new((c % 8) as f32, (c / 8) as f32, 0.0);
                Aabb::new(o, o + Vec3::ONE)
            })
            .collect()
    };
    vec![
        (
            "a tree over 64 touching unit boxes on an 8x8 grid, box k at cell 13k mod 64, \
             leaf size 1"
                .into(),
            Tree::new(grid(), 1),
        ),
        (
            "a tree over 64 touching unit boxes on an 8x8 grid, box k at cell 13k mod 64, \
             leaf size 3"
                .into(),
            Tree::new(grid(), 3),
        ),
    ]
}

/// Points at the grid's corners, edges and faces, inside and outside it.
fn tie_points() -> Vec<Vec3> {
    let mut out = Vec::new();
    for (x, y) in [(2.0, 3.0), (4.0, 4.0), (0.0, 5.0), (7.0, 1.0), (8.0, 8.0)] {
        for z in [0.5, 0.0, 3.0] {
            out.push(Vec3::new(x, y, z));
        }
    }
    out.extend([
        Vec3::new(-1.0, 3.0, 0.5),
        Vec3::new(4.0, -2.0, 0.5),
        Vec3::new(9.0, 4.0, 2.0),
        Vec3::new(2.5, 6.0, -1.0),
    ]);
    out
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 8;

    /// A best-first search with one of its steps done wrong.
    #[derive(Default)]
    struct Slip {
        stop_on_equal: bool,
        farthest_first: bool,
        squared: bool,
        later_tie_wins: bool,
        count_pushes: bool,
        first_leaf_only: bool,
    }

    fn search(s: Slip, tree: &Bvh<Aabb>, prims: &[Aabb], p: Vec3) -> Option<(u32, f32, usize)> {
        use std::cmp::Reverse;
        use std::collections::BinaryHeap;
        let key = |b: &Aabb| dist(b, p).to_bits() as i64;
        let key = |b: &Aabb| if s.farthest_first { key(b) } else { -key(b) };
        let nodes = tree.nodes();
        let mut queue = BinaryHeap::new();
        if let Some(root) = nodes.first() {
            queue.push((key(&root.bv), Reverse(0u32)));
        }
        let (mut best, mut taken, mut pushed) = (None::<(u32, f32)>, 0, 1);
        while let Some((_, Reverse(i))) = queue.pop() {
            let d = dist(&nodes[i as usize].bv, p);
            if best.is_some_and(|(_, b)| d > b || (s.stop_on_equal && d >= b)) {
                break;
            }
            taken += 1;
            let node = &nodes[i as usize];
            match node.children() {
                Some((l, r)) => {
                    for c in [l, r] {
                        queue.push((key(&nodes[c as usize].bv), Reverse(c)));
                        pushed += 1;
                    }
                }
                None => {
                    for &k in tree.leaf_primitives(node) {
                        let d = dist(&prims[k as usize], p);
                        let better = match best {
                            None => true,
                            Some((_, b)) if s.later_tie_wins => d <= b,
                            Some((j, b)) => d < b || (d == b && k < j),
                        };
                        if better {
                            best = Some((k, d));
                        }
                    }
                    if s.first_leaf_only {
                        break;
                    }
                }
            }
        }
        let count = if s.count_pushes { pushed } else { taken };
        let square = |d: f32| if s.squared { d * d } else { d };
        best.map(|(k, d)| (k, square(d), count))
    }

    pub fn best_first_nearest(
        which: u32,
        tree: &Bvh<Aabb>,
        prims: &[Aabb],
        p: Vec3,
    ) -> Option<(u32, f32, usize)> {
        let slip = match which {
            // Depth-first over every node: the right answer, all the work.
            1 => {
                let best = Reference.best_first_nearest(tree, prims, p)?;
                return Some((best.0, best.1, tree.nodes().len()));
            }
            // Greedy: into the nearer child down to one leaf, whose
            // primitive is near but not always the nearest.
            2 => {
                let nodes = tree.nodes();
                let mut i = 0usize;
                let mut taken = 0;
                loop {
                    taken += 1;
                    let node = nodes.get(i)?;
                    match node.children() {
                        Some((l, r)) => {
                            let (dl, dr) = (
                                dist(&nodes[l as usize].bv, p),
                                dist(&nodes[r as usize].bv, p),
                            );
                            i = if dl <= dr { l } else { r } as usize;
                        }
                        None => {
                            let k = tree.indices()[node.first as usize];
                            return Some((k, dist(&prims[k as usize], p), taken));
                        }
                    }
                }
            }
            // Stops when the nearest waiting node is as far as the best
            // (>= for >): misses an equally near primitive with a smaller index.
            3 => Slip {
                stop_on_equal: true,
                ..Slip::default()
            },
            // Forgets `Reverse`: the max-heap hands out the farthest node first.
            4 => Slip {
                farthest_first: true,
                ..Slip::default()
            },
            // Returns the squared distance.
            5 => Slip {
                squared: true,
                ..Slip::default()
            },
            // `<=` when comparing with the best: the last of equally near primitives wins.
            6 => Slip {
                later_tie_wins: true,
                ..Slip::default()
            },
            // Counts the nodes pushed on the queue, not those taken from it.
            7 => Slip {
                count_pushes: true,
                ..Slip::default()
            },
            // Stops at the first leaf taken: its primitives are near, not always nearest.
            8 => Slip {
                first_leaf_only: true,
                ..Slip::default()
            },
            _ => return Reference.best_first_nearest(tree, prims, p),
        };
        search(slip, tree, prims, p)
    }
}
