//! The grader: named checks with points, run on any [`Exercises`] implementation.
//!
//! Checks are chosen to reject the plausible wrong answers, not only to accept
//! the right one: strict comparisons on touching boxes, a fit that starts from
//! the origin, a sphere that misses a point by rounding, a partition along a
//! fixed axis, and so on.

use crate::reference::Reference;
use crate::{Exercises, NodeStep};
use bvhkit::glam::Vec3;
use bvhkit::{
    brute_force, Aabb, BoundingVolume, Bvh, CostModel, Counts, Decision, Descent, Dop14, Node, Obb,
    Open, Partition, Sphere, Stop, TopDown, Triangle,
};
use std::panic::{self, AssertUnwindSafe};
use std::sync::mpsc;
use std::time::Duration;

/// One check: a name, its points, and the test.
#[derive(Clone, Copy)]
pub struct Check {
    /// Exercise number it belongs to.
    pub exercise: u32,
    /// What it checks.
    pub name: &'static str,
    /// Points it is worth.
    pub points: u32,
    /// The test.
    pub run: fn(&dyn Exercises) -> bool,
}

impl std::fmt::Debug for Check {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Check({} {})", self.exercise, self.name)
    }
}

/// Titles of the exercises.
pub const EXERCISES: [(u32, &str); 31] = [
    (1, "AABB overlap"),
    (2, "AABB and sphere: fit and merge"),
    (3, "top-down partition: object median"),
    (4, "descent rule: descend the larger volume"),
    (5, "informed depth-first traversal (recursive)"),
    (6, "traversal with a fixed stack"),
    (7, "the cost function T"),
    (8, "bottom-up construction: greedy merges"),
    (9, "refit after motion"),
    (10, "insertion: the cost of a candidate sibling"),
    (11, "implicit array: index arithmetic"),
    (12, "preorder layout: convert a tree"),
    (13, "quantize a box conservatively"),
    (14, "sizing static buffers"),
    (
        15,
        "the advisor's yardstick: workload time and the Pareto front",
    ),
    (16, "the surface area heuristic over a row of bins"),
    (17, "14-DOPs: fit and overlap"),
    (
        18,
        "descent rules: A first, simultaneous, alternate, by overlap",
    ),
    (19, "partition criteria of a top-down split"),
    (20, "breadth-first and depth-first visiting order"),
    (21, "oriented boxes: the separating-axis test"),
    (22, "best-first search: the nearest primitive"),
    (23, "primitive bounds in leaf order"),
    (24, "stopping and falling back"),
    (25, "fitting unit costs to measured queries"),
    (26, "axis choice and split point"),
    (27, "measuring a tree: depth, leaf depth, SAH cost"),
    (28, "tri-nodes: records and wasted slots"),
    (29, "oriented boxes: fit with given axes"),
    (30, "offsets instead of pointers: preorder links"),
    (31, "the collision system: broad phase, then narrow phase"),
];

/// A score for one exercise.
#[derive(Clone, Debug, PartialEq)]
pub struct ExerciseScore {
    /// Exercise number.
    pub exercise: u32,
    /// Title.
    pub title: &'static str,
    /// Points earned.
    pub earned: u32,
    /// Points possible.
    pub possible: u32,
    /// Names of the checks that failed (or panicked).
    pub failed: Vec<String>,
}

/// A small deterministic generator so every run grades the same inputs.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
    fn point(&mut self, scale: f32, offset: Vec3) -> Vec3 {
        Vec3::new(self.next() - 0.5, self.next() - 0.5, self.next() - 0.5) * scale + offset
    }
    fn cloud(&mut self, n: usize, scale: f32, offset: Vec3) -> Vec<Vec3> {
        (0..n).map(|_| self.point(scale, offset)).collect()
    }
}

fn b(min: [f32; 3], max: [f32; 3]) -> Aabb {
    Aabb::new(Vec3::from(min), Vec3::from(max))
}

fn clouds() -> Vec<Vec<Vec3>> {
    let mut r = Rng(0x9e3779b97f4a7c15);
    let mut v = vec![
        vec![Vec3::new(-3.0, -2.0, -1.0), Vec3::new(-1.0, -5.0, -2.0)],
        vec![Vec3::new(7.0, 7.0, 7.0)],
    ];
    for i in 0..20 {
        let off = if i % 2 == 0 {
            Vec3::ZERO
        } else {
            Vec3::new(1.0e5, -3.0e4, 2.0e4)
        };
        v.push(r.cloud(3 + i * 7, 10.0, off));
    }
    // Points on a sphere: Ritter is near its worst here.
    v.push(
        (0..200)
            .map(|i| {
                let (t, p) = (i as f32 * 0.7, i as f32 * 0.31);
                Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos()) * 3.0
            })
            .collect(),
    );
    v
}

/// All checks of all exercises.
pub fn checks() -> Vec<Check> {
    vec![
        // Exercise 1
        Check {
            exercise: 1,
            name: "overlapping boxes overlap",
            points: 2,
            run: |e| {
                e.aabb_overlaps(&b([0.0; 3], [2.0; 3]), &b([1.0; 3], [3.0; 3]))
                    && e.aabb_overlaps(&b([1.0; 3], [3.0; 3]), &b([0.0; 3], [2.0; 3]))
            },
        },
        Check {
            exercise: 1,
            name: "boxes apart along one axis only do not overlap",
            points: 3,
            run: |e| {
                (0..3).all(|k| {
                    let mut lo = [0.0; 3];
                    lo[k] = 5.0;
                    let hi = lo.map(|x| x + 1.0);
                    !e.aabb_overlaps(&b([0.0; 3], [1.0; 3]), &b(lo, hi))
                        && !e.aabb_overlaps(&b(lo, hi), &b([0.0; 3], [1.0; 3]))
                })
            },
        },
        Check {
            exercise: 1,
            name: "touching faces, edges and corners overlap",
            points: 2,
            run: |e| {
                let a = b([0.0; 3], [1.0; 3]);
                e.aabb_overlaps(&a, &b([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]))
                    && e.aabb_overlaps(&a, &b([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]))
                    && e.aabb_overlaps(&a, &b([1.0; 3], [2.0; 3]))
                    && e.aabb_overlaps(&a, &b([0.5, 0.5, 1.0], [0.5, 0.5, 1.0]))
            },
        },
        Check {
            exercise: 1,
            name: "a box inside another overlaps it",
            points: 1,
            run: |e| {
                e.aabb_overlaps(&b([0.0; 3], [10.0; 3]), &b([4.0; 3], [5.0; 3]))
                    && e.aabb_overlaps(&b([4.0; 3], [5.0; 3]), &b([0.0; 3], [10.0; 3]))
            },
        },
        Check {
            exercise: 1,
            name: "500 random pairs",
            points: 2,
            run: |e| {
                let mut r = Rng(42);
                (0..500).all(|_| {
                    let (p, q) = (r.point(4.0, Vec3::ZERO), r.point(4.0, Vec3::ZERO));
                    let (s, t) = (r.point(2.0, Vec3::ONE), r.point(2.0, Vec3::ONE));
                    let x = Aabb::new(p.min(q), p.max(q));
                    let y = Aabb::new(s.min(t), s.max(t));
                    let truth = (0..3).all(|k| x.min[k] <= y.max[k] && y.min[k] <= x.max[k]);
                    e.aabb_overlaps(&x, &y) == truth
                })
            },
        },
        // Exercise 2
        Check {
            exercise: 2,
            name: "aabb_fit is exact (also for negative coordinates)",
            points: 4,
            run: |e| {
                clouds()
                    .iter()
                    .all(|c| e.aabb_fit(c) == Aabb::fit(c.as_slice()))
            },
        },
        Check {
            exercise: 2,
            name: "aabb_fit of one point is that point",
            points: 1,
            run: |e| {
                let p = Vec3::new(-1.0, 2.0, -3.0);
                e.aabb_fit(&[p]) == Aabb::from_point(p)
            },
        },
        Check {
            exercise: 2,
            name: "aabb_merge is exact (disjoint, overlapping, nested)",
            points: 3,
            run: |e| {
                let cases = [
                    (b([0.0; 3], [1.0; 3]), b([5.0; 3], [6.0; 3])),
                    (
                        b([-2.0, 0.0, 0.0], [1.0; 3]),
                        b([0.0, -3.0, 0.5], [0.5, 4.0, 9.0]),
                    ),
                    (b([0.0; 3], [10.0; 3]), b([4.0; 3], [5.0; 3])),
                ];
                cases.iter().all(|(x, y)| {
                    e.aabb_merge(x, y) == x.union(y) && e.aabb_merge(y, x) == x.union(y)
                })
            },
        },
        Check {
            exercise: 2,
            name: "sphere_fit contains every point (near and far from the origin)",
            points: 4,
            run: |e| {
                clouds().iter().all(|c| {
                    let s = e.sphere_fit(c);
                    c.iter().all(|&p| s.contains_point(p))
                })
            },
        },
        Check {
            exercise: 2,
            name: "sphere_fit is within 1.25x of the minimal radius",
            points: 3,
            run: |e| {
                clouds().iter().all(|c| {
                    let s = e.sphere_fit(c);
                    let w = Sphere::welzl(c.as_slice());
                    s.radius <= w.radius * 1.25 + 1e-3
                })
            },
        },
        Check {
            exercise: 2,
            name: "sphere_merge contains both spheres",
            points: 3,
            run: |e| {
                let mut r = Rng(7);
                (0..200).all(|_| {
                    let x = Sphere::new(r.point(10.0, Vec3::ZERO), r.next() * 3.0);
                    let y = Sphere::new(r.point(10.0, Vec3::ZERO), r.next() * 3.0);
                    let m = e.sphere_merge(&x, &y);
                    m.contains(&x) && m.contains(&y)
                })
            },
        },
        Check {
            exercise: 2,
            name: "sphere_merge is minimal (and returns a containing input as is)",
            points: 2,
            run: |e| {
                let mut r = Rng(8);
                let nested = Sphere::new(Vec3::ZERO, 5.0);
                let inner = Sphere::new(Vec3::ONE, 1.0);
                (e.sphere_merge(&nested, &inner).radius - 5.0).abs() < 1e-4
                    && (0..200).all(|_| {
                        let x = Sphere::new(r.point(10.0, Vec3::ZERO), r.next() * 3.0);
                        let y = Sphere::new(r.point(10.0, Vec3::ZERO), r.next() * 3.0);
                        let best = x.merge(&y).radius;
                        e.sphere_merge(&x, &y).radius <= best * (1.0 + 1e-4) + 1e-5
                    })
            },
        },
        // Exercise 3
        Check {
            exercise: 3,
            name: "returns n / 2",
            points: 2,
            run: |e| {
                let mut r = Rng(3);
                (1..40).all(|n| {
                    let c = r.cloud(n, 10.0, Vec3::ZERO);
                    let mut idx: Vec<u32> = (0..n as u32).collect();
                    e.median_partition(&c, &mut idx) == n / 2
                })
            },
        },
        Check {
            exercise: 3,
            name: "indices stay a permutation",
            points: 2,
            run: |e| {
                let mut r = Rng(4);
                let c = r.cloud(101, 10.0, Vec3::ZERO);
                let mut idx: Vec<u32> = (0..101).rev().collect();
                e.median_partition(&c, &mut idx);
                idx.sort_unstable();
                idx == (0..101).collect::<Vec<u32>>()
            },
        },
        Check {
            exercise: 3,
            name: "left half <= right half along the longest axis (y here)",
            points: 3,
            run: |e| median_ok(e, Vec3::new(1.0, 20.0, 3.0), 5),
        },
        Check {
            exercise: 3,
            name: "the axis comes from the centroids (z here), not fixed",
            points: 3,
            run: |e| {
                median_ok(e, Vec3::new(2.0, 1.0, 30.0), 6)
                    && median_ok(e, Vec3::new(40.0, 1.0, 3.0), 9)
            },
        },
        // Exercise 4
        Check {
            exercise: 4,
            name: "never opens a leaf",
            points: 3,
            run: |e| {
                let big = node([0.0; 3], [10.0; 3], false);
                let small_leaf = node([0.0; 3], [1.0; 3], true);
                let big_leaf = node([0.0; 3], [10.0; 3], true);
                let small = node([0.0; 3], [1.0; 3], false);
                e.descend_a(&big, &small_leaf)
                    && e.descend_a(&small, &big_leaf)
                    && !e.descend_a(&big_leaf, &small)
                    && !e.descend_a(&small_leaf, &big)
            },
        },
        Check {
            exercise: 4,
            name: "opens the larger of two internal nodes (A on a tie)",
            points: 4,
            run: |e| {
                let big = node([0.0; 3], [10.0; 3], false);
                let small = node([0.0; 3], [1.0; 3], false);
                e.descend_a(&big, &small)
                    && !e.descend_a(&small, &big)
                    && e.descend_a(&small, &small)
            },
        },
        Check {
            exercise: 4,
            name: "size means volume, not the length along one axis",
            points: 3,
            run: |e| {
                let long_thin = node([0.0; 3], [20.0, 0.1, 0.1], false);
                let cube = node([0.0; 3], [2.0; 3], false);
                !e.descend_a(&long_thin, &cube) && e.descend_a(&cube, &long_thin)
            },
        },
        // Exercise 5
        Check {
            exercise: 5,
            name: "finds exactly the brute-force pairs on overlapping grids",
            points: 6,
            run: |e| {
                traversal_cases()[..2]
                    .iter()
                    .all(|(a, b)| sorted(run_dfs(e, a, b)) == reference_pairs(a, b))
            },
        },
        Check {
            exercise: 5,
            name: "tiny trees (1-3 leaves), apart and touching",
            points: 5,
            run: |e| {
                traversal_cases()[2..]
                    .iter()
                    .all(|(a, b)| sorted(run_dfs(e, a, b)) == reference_pairs(a, b))
            },
        },
        Check {
            exercise: 5,
            name: "reports each pair once",
            points: 4,
            run: |e| {
                traversal_cases().iter().all(|(a, b)| {
                    let got = run_dfs(e, a, b);
                    let mut unique = sorted(got.clone());
                    unique.dedup();
                    unique.len() == got.len()
                })
            },
        },
        // Exercise 6
        Check {
            exercise: 6,
            name: "finds exactly the brute-force pairs",
            points: 6,
            run: |e| {
                traversal_cases().iter().all(|(a, b)| {
                    let (ok, out) = run_stack(e, a, b, 4 * (a.depth + b.depth) + 4);
                    ok && sorted(out) == reference_pairs(a, b)
                })
            },
        },
        Check {
            exercise: 6,
            name: "a stack that is too small gives false, not a panic",
            points: 5,
            run: |e| {
                let (a, b) = &traversal_cases()[0];
                !run_stack(e, a, b, 2).0 && !run_stack(e, a, b, 0).0
            },
        },
        Check {
            exercise: 6,
            name: "one waiting pair per level is enough (depth-bounded stack)",
            points: 4,
            run: |e| {
                traversal_cases()
                    .iter()
                    .all(|(a, b)| run_stack(e, a, b, a.depth + b.depth + 2).0)
            },
        },
        // Exercise 7
        Check {
            exercise: 7,
            name: "T for given counters and unit costs",
            points: 6,
            run: |e| {
                let counts = Counts {
                    bv_tests: 1200,
                    prim_tests: 340,
                    updates: 56,
                };
                let model = CostModel {
                    cv: 2.5,
                    cp: 31.0,
                    cu: 12.0,
                    co: 800.0,
                };
                let t = e.predicted_cost(&counts, &model);
                (t - (1200.0 * 2.5 + 340.0 * 31.0 + 56.0 * 12.0 + 800.0)).abs() < 1e-6
            },
        },
        Check {
            exercise: 7,
            name: "an empty query costs Co",
            points: 2,
            run: |e| {
                let model = CostModel {
                    cv: 2.5,
                    cp: 31.0,
                    cu: 12.0,
                    co: 800.0,
                };
                (e.predicted_cost(&Counts::default(), &model) - 800.0).abs() < 1e-9
            },
        },
        Check {
            exercise: 7,
            name: "no overflow with huge counters",
            points: 2,
            run: |e| {
                let counts = Counts {
                    bv_tests: u64::MAX / 2,
                    prim_tests: 3,
                    updates: 0,
                };
                let model = CostModel {
                    cv: 1.0,
                    cp: 1.0,
                    cu: 1.0,
                    co: 0.0,
                };
                let t = e.predicted_cost(&counts, &model);
                (t / (u64::MAX / 2) as f64 - 1.0).abs() < 1e-9
            },
        },
        // Exercise 8
        Check {
            exercise: 8,
            name: "n - 1 merges of live clusters, ending in one root",
            points: 3,
            run: |e| {
                merge_sets()
                    .iter()
                    .all(|s| replay(s, &e.bottom_up_merges(s), false))
            },
        },
        Check {
            exercise: 8,
            name: "every merge has the smallest merged volume of its step",
            points: 5,
            run: |e| {
                merge_sets()
                    .iter()
                    .all(|s| replay(s, &e.bottom_up_merges(s), true))
            },
        },
        Check {
            exercise: 8,
            name: "one box needs no merge; two need one",
            points: 2,
            run: |e| {
                let one = [b([0.0; 3], [1.0; 3])];
                let two = [b([0.0; 3], [1.0; 3]), b([5.0; 3], [6.0; 3])];
                e.bottom_up_merges(&one).is_empty() && replay(&two, &e.bottom_up_merges(&two), true)
            },
        },
        // Exercise 9
        Check {
            exercise: 9,
            name: "leaves fit their moved primitives exactly",
            points: 4,
            run: |e| {
                [(50, 1), (300, 2)].iter().all(|&(n, seed)| {
                    let (got, want) = refit_case(e, n, seed);
                    got.iter()
                        .zip(&want)
                        .filter(|(_, w)| w.is_leaf())
                        .all(|(g, w)| g.bv == w.bv)
                })
            },
        },
        Check {
            exercise: 9,
            name: "every parent is the union of its children (up to the root)",
            points: 4,
            run: |e| {
                [(50, 3), (300, 4)].iter().all(|&(n, seed)| {
                    let (got, want) = refit_case(e, n, seed);
                    got == want
                })
            },
        },
        Check {
            exercise: 9,
            name: "a tree of one leaf",
            points: 2,
            run: |e| {
                let (got, want) = refit_case(e, 1, 5);
                got == want
            },
        },
        // Exercise 10
        Check {
            exercise: 10,
            name: "a sibling without ancestors: the new parent's area",
            points: 3,
            run: |e| {
                let (s, n) = (b([0.0; 3], [1.0; 3]), b([2.0, 0.0, 0.0], [3.0, 1.0, 1.0]));
                // Union is 3 x 1 x 1: area 2 * (3 + 1 + 3) = 14.
                (e.insertion_cost(&s, &[], &n) - 14.0).abs() < 1e-9
            },
        },
        Check {
            exercise: 10,
            name: "ancestors add only their growth (zero when they contain the object)",
            points: 4,
            run: |e| {
                let (s, n) = (b([0.0; 3], [1.0; 3]), b([2.0, 0.0, 0.0], [3.0, 1.0, 1.0]));
                let big = b([-5.0; 3], [5.0; 3]);
                let small = b([0.0; 3], [2.0, 1.0, 1.0]); // grows to 3 x 1 x 1: 10 -> 14
                (e.insertion_cost(&s, &[big], &n) - 14.0).abs() < 1e-9
                    && (e.insertion_cost(&s, &[small, big], &n) - 18.0).abs() < 1e-9
            },
        },
        Check {
            exercise: 10,
            name: "agrees with the library's DynamicTree on random trees",
            points: 3,
            run: |e| {
                use bvhkit::builders::{DynNode, DynamicConfig, DynamicTree, NULL};
                let prims = boxes(60, 11, Vec3::ZERO);
                let mut storage = vec![DynNode::<Aabb>::EMPTY; 2 * 61 - 1];
                let handles: Vec<u32> = {
                    let Ok(mut tree) = DynamicTree::new(&mut storage, DynamicConfig::default())
                    else {
                        return false;
                    };
                    prims
                        .iter()
                        .enumerate()
                        .filter_map(|(i, p)| tree.insert(i as u32, p).ok())
                        .collect()
                };
                let new = b([3.3, 4.1, 0.2], [4.0, 5.0, 0.9]);
                handles.iter().all(|&h| {
                    let mut ancestors = Vec::new();
                    let mut a = storage[h as usize].parent;
                    while a != NULL {
                        ancestors.push(storage[a as usize].bv);
                        a = storage[a as usize].parent;
                    }
                    let mine = e.insertion_cost(&storage[h as usize].bv, &ancestors, &new);
                    let lib = DynamicTree::insertion_cost_of(&storage, h, &new);
                    (mine - lib).abs() <= 1e-6 * lib.abs().max(1.0)
                })
            },
        },
        // Exercise 11
        Check {
            exercise: 11,
            name: "children of the first entries",
            points: 3,
            run: |e| {
                e.implicit_children(0) == (1, 2)
                    && e.implicit_children(1) == (3, 4)
                    && e.implicit_children(4) == (9, 10)
                    && e.implicit_children(1000) == (2001, 2002)
            },
        },
        Check {
            exercise: 11,
            name: "the parent inverts both children; the root has none",
            points: 4,
            run: |e| {
                e.implicit_parent(0).is_none()
                    && (0..5000).all(|i| {
                        let (l, r) = e.implicit_children(i);
                        e.implicit_parent(l) == Some(i) && e.implicit_parent(r) == Some(i)
                    })
            },
        },
        Check {
            exercise: 11,
            name: "array length of a complete tree of each depth",
            points: 3,
            run: |e| (0..30).all(|d: u32| e.implicit_len(d) == (1usize << (d + 1)) - 1),
        },
        // Exercise 12
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
        // Exercise 13
        Check {
            exercise: 13,
            name: "the decoded box contains the child (grid-line and rounding cases)",
            points: 4,
            run: |e| {
                quantize_cases()
                    .iter()
                    .all(|(p, c)| quantized_contains(e, p, c))
            },
        },
        Check {
            exercise: 13,
            name: "as tight as the grid allows",
            points: 3,
            run: |e| {
                quantize_cases().iter().all(|(p, c)| {
                    let (lo, hi) = e.quantize(p, c);
                    quantized_contains(e, p, c)
                        && (0..3).all(|k| {
                            (lo[k] == 255 || crate::dequantize(p, k, lo[k] + 1) > c.min[k])
                                && (hi[k] == 0 || crate::dequantize(p, k, hi[k] - 1) < c.max[k])
                        })
                })
            },
        },
        Check {
            exercise: 13,
            name: "a child equal to its parent, and flat boxes",
            points: 3,
            run: |e| {
                let p = b([-3.0, 1.0, 5.0], [7.0, 1.0, 9.5]);
                let flat = b([0.0, 1.0, 6.0], [4.0, 1.0, 6.0]);
                e.quantize(&p, &p).0[0] == 0
                    && e.quantize(&p, &p).1[0] == 255
                    && quantized_contains(e, &p, &p)
                    && quantized_contains(e, &p, &flat)
            },
        },
        // Exercise 14
        Check {
            exercise: 14,
            name: "build memory: nodes and indices, for n = 0, 1 and many",
            points: 4,
            run: |e| {
                [(0, 32), (1, 32), (2, 32), (256, 32), (1000, 16), (77, 92)]
                    .iter()
                    .all(|&(n, s)| {
                        let want = if n == 0 { 0 } else { (2 * n - 1) * s + 4 * n };
                        e.top_down_bytes(n, s) == want
                    })
            },
        },
        Check {
            exercise: 14,
            name: "pair stack bound: equal depths and leaves",
            points: 3,
            run: |e| {
                e.pair_stack_bound(0, 0) == 1
                    && e.pair_stack_bound(1, 1) == 4
                    && e.pair_stack_bound(7, 7) == 22
            },
        },
        Check {
            exercise: 14,
            name: "pair stack bound: different depths, and enough for a real traversal",
            points: 3,
            run: |e| {
                let formula = (0..40)
                    .all(|a| (0..40).all(|b| e.pair_stack_bound(a, b) == a + b + a.min(b) + 1));
                // Balanced trees of 64 and 16 boxes: the bound lets a
                // stack-only traversal of exactly that size finish.
                let (pa, pb) = (grid_boxes(64, 0.0), grid_boxes(16, 0.3));
                let (mut na, mut nb) = ([Node::<Aabb>::EMPTY; 127], [Node::<Aabb>::EMPTY; 31]);
                let (mut ia, mut ib) = ([0u32; 64], [0u32; 16]);
                let cfg = TopDown::median().with_max_leaf_size(1);
                let (Ok(ta), Ok(tb)) = (
                    cfg.build(&pa, &mut na, &mut ia),
                    cfg.build(&pb, &mut nb, &mut ib),
                ) else {
                    return false;
                };
                let bound = e.pair_stack_bound(ta.depth(), tb.depth());
                let mut stack = vec![(0u32, 0u32); bound];
                let mut out = Vec::new();
                formula && Reference.stack_dfs(&ta, &pa, &tb, &pb, &mut stack, &mut out)
            },
        },
        // Exercise 15
        Check {
            exercise: 15,
            name: "workload time: built once, rebuilt every frame, and 0 or 1 frames",
            points: 4,
            run: |e| {
                let close = |x: f64, want: f64| (x - want).abs() <= 1e-9 * want.abs().max(1.0);
                close(e.workload_ms(10.0, 2.0, false, 60), 130.0)
                    && close(e.workload_ms(10.0, 2.0, true, 60), 720.0)
                    && close(e.workload_ms(10.0, 2.0, false, 0), 10.0)
                    && close(e.workload_ms(10.0, 2.0, true, 0), 0.0)
                    && close(e.workload_ms(3.5, 0.25, false, 1), 3.75)
                    && close(e.workload_ms(3.5, 0.25, true, 1), 3.75)
            },
        },
        Check {
            exercise: 15,
            name: "Pareto front: a staircase with dominated points",
            points: 3,
            run: |e| {
                e.pareto_front(&[(1.0, 5.0), (2.0, 2.0), (3.0, 3.0), (4.0, 1.0), (5.0, 5.0)])
                    == [0, 1, 3]
                    && e.pareto_front(&[]).is_empty()
                    && e.pareto_front(&[(7.0, 7.0)]) == [0]
            },
        },
        Check {
            exercise: 15,
            name: "Pareto front: ties, duplicates, and random points on a small grid",
            points: 3,
            run: |e| {
                let ties =
                    e.pareto_front(&[(2.0, 2.0), (2.0, 2.0), (2.0, 3.0), (3.0, 2.0)]) == [0, 1];
                let mut s = 0x9e37_79b9_7f4a_7c15u64;
                let random = (0..40).all(|_| {
                    let points: Vec<(f64, f64)> = (0..12)
                        .map(|_| {
                            s = s.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
                            (((s >> 33) % 5) as f64, ((s >> 45) % 5) as f64)
                        })
                        .collect();
                    e.pareto_front(&points) == Reference.pareto_front(&points)
                });
                ties && random
            },
        },
        // Exercise 16
        Check {
            exercise: 16,
            name: "splits off the far primitive where a balanced split would not",
            points: 3,
            run: |e| {
                // Counts 3, 1, 1 side by side and 1 far away: SAH cuts at 3
                // (cost 76 against 116 and 144), halving counts would cut at 1.
                let bins = [
                    (unit_at(0.0), 3),
                    (unit_at(1.0), 1),
                    (unit_at(2.0), 1),
                    (unit_at(10.0), 1),
                ];
                e.sah_best_boundary(&bins) == Some(3)
            },
        },
        Check {
            exercise: 16,
            name: "never leaves a side empty (and None when nothing separates)",
            points: 2,
            run: |e| {
                let empty = (Aabb::EMPTY, 0);
                e.sah_best_boundary(&[empty, (unit_at(0.0), 1), (unit_at(3.0), 1), empty])
                    == Some(2)
                    && e.sah_best_boundary(&[empty, (unit_at(0.0), 2), empty])
                        .is_none()
                    && e.sah_best_boundary(&[(unit_at(0.0), 5)]).is_none()
                    && e.sah_best_boundary(&[]).is_none()
            },
        },
        Check {
            exercise: 16,
            name: "a side's box is the union of its bins (random rows, exact arithmetic)",
            points: 3,
            run: |e| {
                let mut s = 0x2545_f491_4f6c_dd1du64;
                let mut next = |m: u64| {
                    s ^= s << 13;
                    s ^= s >> 7;
                    s ^= s << 17;
                    s % m
                };
                (0..300).all(|_| {
                    let k = 2 + next(15) as usize;
                    // Whole-number corners: every area and cost is exact, so
                    // equal costs are equal in any summation order.
                    let bins: Vec<(Aabb, u32)> = (0..k)
                        .map(|j| {
                            if next(4) == 0 {
                                return (Aabb::EMPTY, 0);
                            }
                            let lo = Vec3::new(j as f32, next(8) as f32, next(8) as f32);
                            let size = Vec3::new(1.0, next(8) as f32, next(8) as f32);
                            (Aabb::new(lo, lo + size), 1 + next(5) as u32)
                        })
                        .collect();
                    e.sah_best_boundary(&bins) == Reference.sah_best_boundary(&bins)
                })
            },
        },
        Check {
            exercise: 16,
            name: "the first of equal costs",
            points: 2,
            run: |e| {
                // Evenly spaced: cutting after the first or the second costs
                // the same (34).
                let bins = [(unit_at(0.0), 1), (unit_at(2.0), 1), (unit_at(4.0), 1)];
                e.sah_best_boundary(&bins) == Some(1)
            },
        },
        // Exercise 17
        Check {
            exercise: 17,
            name: "the fitted 14-DOP contains every point, also where f32 sums round",
            points: 3,
            run: |e| {
                let mut sets = clouds();
                // 1 + 1e-8 is 1.0 in f32: a bound rounded to nearest, not
                // outward, leaves the point outside on the diagonals.
                sets.push(vec![
                    Vec3::new(1.0, 1e-8, 1e-8),
                    Vec3::new(-1.0, -1e-8, 1e-8),
                ]);
                sets.push(vec![Vec3::new(1e6, 0.03, -0.07), Vec3::new(-1e6, 0.1, 0.3)]);
                sets.iter().all(|pts| {
                    let dop = e.dop14_fit(pts);
                    pts.iter().all(|&p| dop.contains_point(p))
                })
            },
        },
        Check {
            exercise: 17,
            name: "the fitted 14-DOP is tight along all seven directions",
            points: 2,
            run: |e| {
                clouds().iter().all(|pts| {
                    let dop = e.dop14_fit(pts);
                    (0..7).all(|i| {
                        let d = Dop14::direction(i);
                        let t = |p: &Vec3| {
                            d[0] as f64 * p.x as f64
                                + d[1] as f64 * p.y as f64
                                + d[2] as f64 * p.z as f64
                        };
                        let lo = pts.iter().map(t).fold(f64::INFINITY, f64::min);
                        let hi = pts.iter().map(t).fold(f64::NEG_INFINITY, f64::max);
                        let tol = 1e-5 * lo.abs().max(hi.abs()).max(1.0);
                        (dop.min[i] as f64 - lo).abs() <= tol
                            && (dop.max[i] as f64 - hi).abs() <= tol
                    })
                })
            },
        },
        Check {
            exercise: 17,
            name: "overlap: touching counts",
            points: 2,
            run: |e| {
                let a = Dop14::fit(&[Vec3::ZERO, Vec3::ONE][..]);
                let mut b = a;
                b.min[0] = a.max[0]; // shares the face x = max
                b.max[0] = a.max[0] + 1.0;
                e.dop14_overlaps(&a, &b) && e.dop14_overlaps(&b, &a) && e.dop14_overlaps(&a, &a)
            },
        },
        Check {
            exercise: 17,
            name: "overlap: separated along a diagonal only, and random pairs",
            points: 3,
            run: |e| {
                // Two corners of boxes that overlap as boxes, cut apart by the
                // x + y + z slab.
                let a = Dop14::fit(&[Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z][..]);
                let b = Dop14::fit(
                    &[
                        Vec3::ONE,
                        Vec3::new(0.0, 1.0, 1.0),
                        Vec3::new(1.0, 0.0, 1.0),
                        Vec3::new(1.0, 1.0, 0.0),
                    ][..],
                );
                let diagonal = !e.dop14_overlaps(&a, &b) && !e.dop14_overlaps(&b, &a);
                let mut r = Rng(17);
                let random = (0..300).all(|_| {
                    let mut dop = || {
                        let centre = r.point(4.0, Vec3::ZERO);
                        Dop14::fit(&r.cloud(4, 2.0, centre)[..])
                    };
                    let (x, y) = (dop(), dop());
                    e.dop14_overlaps(&x, &y) == x.overlaps(&y)
                });
                diagonal && random
            },
        },
        // Exercise 18
        Check {
            exercise: 18,
            name: "A first, B first and simultaneous, at every depth",
            points: 3,
            run: |e| {
                let (a, b) = (unit_at(0.0), unit_at(0.5));
                (0..6).all(|depth| {
                    let d = Decision {
                        a: &a,
                        b: &b,
                        a_children: None,
                        b_children: None,
                        depth,
                    };
                    e.descent_open(Descent::AFirst, &d) == Open::A
                        && e.descent_open(Descent::BFirst, &d) == Open::B
                        && e.descent_open(Descent::Simultaneous, &d) == Open::Both
                })
            },
        },
        Check {
            exercise: 18,
            name: "alternate: A at even depths, B at odd",
            points: 3,
            run: |e| {
                let (a, b) = (unit_at(0.0), unit_at(0.5));
                (0..8).all(|depth| {
                    let d = Decision {
                        a: &a,
                        b: &b,
                        a_children: None,
                        b_children: None,
                        depth,
                    };
                    let want = if depth % 2 == 0 { Open::A } else { Open::B };
                    e.descent_open(Descent::Alternate, &d) == want
                })
            },
        },
        Check {
            exercise: 18,
            name: "by overlap: opens the side whose children stay least inside (not the larger)",
            points: 4,
            run: |e| {
                let slab = |x0: f32, x1: f32| b([x0, 0.0, 0.0], [x1, 4.0, 4.0]);
                // A = [0,4] split at 2: on average a quarter of A's children
                // lies in B. B = [3,10] split at 4: half of B's children lies
                // in A. So A is opened, although B is the larger node.
                let (a, ac) = (slab(0.0, 4.0), [slab(0.0, 2.0), slab(2.0, 4.0)]);
                let (bb, bc) = (slab(3.0, 10.0), [slab(3.0, 4.0), slab(4.0, 10.0)]);
                let d = Decision {
                    a: &a,
                    b: &bb,
                    a_children: Some(&ac),
                    b_children: Some(&bc),
                    depth: 0,
                };
                let swapped = Decision {
                    a: &bb,
                    b: &a,
                    a_children: Some(&bc),
                    b_children: Some(&ac),
                    depth: 1,
                };
                let same = Decision {
                    a: &a,
                    b: &a,
                    a_children: Some(&ac),
                    b_children: Some(&ac),
                    depth: 0,
                };
                e.descent_open(Descent::Overlap, &d) == Open::A
                    && e.descent_open(Descent::Overlap, &swapped) == Open::B
                    && e.descent_open(Descent::Overlap, &same) == Open::A
            },
        },
        // Exercise 19
        Check {
            exercise: 19,
            name: "balance and the SAH (counts weigh the areas)",
            points: 3,
            run: |e| {
                let (l, r) = (b([0.0; 3], [1.0, 1.0, 1.0]), b([0.0; 3], [2.0, 1.0, 1.0]));
                close(e.partition_cost(Partition::Balance, &l, 7, &r, 3), 4.0)
                    && close(e.partition_cost(Partition::Balance, &l, 3, &r, 7), 4.0)
                    // 7 * 6 + 3 * 10
                    && close(e.partition_cost(Partition::SurfaceArea, &l, 7, &r, 3), 72.0)
            },
        },
        Check {
            exercise: 19,
            name: "volume sum and the larger child",
            points: 3,
            run: |e| {
                let (l, r) = (b([0.0; 3], [1.0, 2.0, 3.0]), b([5.0; 3], [9.0, 6.0, 6.0]));
                close(e.partition_cost(Partition::Volume, &l, 1, &r, 1), 10.0)
                    && close(e.partition_cost(Partition::LargerChild, &l, 1, &r, 1), 6.0)
                    && close(e.partition_cost(Partition::LargerChild, &r, 1, &l, 1), 6.0)
            },
        },
        Check {
            exercise: 19,
            name: "overlap volume and separation, apart on one axis or on two",
            points: 4,
            run: |e| {
                let l = b([0.0; 3], [2.0, 2.0, 2.0]);
                let overlapping = b([1.0, 1.0, 1.5], [3.0, 3.0, 3.0]); // shares 1 x 1 x 0.5
                let apart_x = b([4.0, 0.5, 0.5], [5.0, 1.5, 1.5]); // 2 away along x only
                let apart_xy = b([3.0, 5.0, 0.0], [4.0, 6.0, 2.0]); // 1 along x, 3 along y
                let cost = |c, r: &Aabb| e.partition_cost(c, &l, 1, r, 1);
                close(cost(Partition::Overlap, &overlapping), 0.5)
                    && close(cost(Partition::Overlap, &apart_x), 0.0)
                    && close(cost(Partition::Overlap, &apart_xy), 0.0)
                    && close(cost(Partition::Separation, &apart_x), -2.0)
                    && close(cost(Partition::Separation, &apart_xy), -3.0)
                    && close(cost(Partition::Separation, &overlapping), 0.5)
            },
        },
        // Exercise 20
        Check {
            exercise: 20,
            name: "depth-first: preorder, left before right",
            points: 5,
            run: |e| {
                visit_cases().iter().all(|t| {
                    e.visit_order(&t.bvh(), false) == Reference.visit_order(&t.bvh(), false)
                })
            },
        },
        Check {
            exercise: 20,
            name: "breadth-first: level by level, left to right",
            points: 5,
            run: |e| {
                visit_cases()
                    .iter()
                    .all(|t| e.visit_order(&t.bvh(), true) == Reference.visit_order(&t.bvh(), true))
            },
        },
        // Exercise 21
        Check {
            exercise: 21,
            name: "touching and nested boxes overlap",
            points: 3,
            run: |e| {
                let cube = |c: Vec3| Obb {
                    center: c,
                    axes: [Vec3::X, Vec3::Y, Vec3::Z],
                    half_extents: Vec3::ONE,
                };
                let (a, touching) = (cube(Vec3::ZERO), cube(Vec3::new(2.0, 0.5, 0.0)));
                let inner = Obb {
                    half_extents: Vec3::splat(0.25),
                    ..turned(Vec3::ZERO, 0.7, 0.3)
                };
                e.obb_overlaps(&a, &touching)
                    && e.obb_overlaps(&touching, &a)
                    && e.obb_overlaps(&a, &inner)
                    && e.obb_overlaps(&inner, &a)
            },
        },
        Check {
            exercise: 21,
            name: "random turned boxes, edge-to-edge misses included, against the library",
            points: 7,
            run: |e| {
                let mut r = Rng(21);
                let mut clear = 0;
                let agree = (0..4000).all(|_| {
                    let a = turned(r.point(0.5, Vec3::ZERO), r.next() * 6.0, r.next() * 6.0);
                    let b = turned(r.point(5.0, Vec3::ZERO), r.next() * 6.0, r.next() * 6.0);
                    // Only pairs the answer of which does not change when
                    // both boxes grow or shrink by 1%: no rounding question.
                    let scaled = |x: &Obb, f: f32| Obb {
                        half_extents: x.half_extents * f,
                        ..*x
                    };
                    let lo = scaled(&a, 0.99).overlaps(&scaled(&b, 0.99));
                    let hi = scaled(&a, 1.01).overlaps(&scaled(&b, 1.01));
                    if lo != hi {
                        return true;
                    }
                    clear += 1;
                    e.obb_overlaps(&a, &b) == lo && e.obb_overlaps(&b, &a) == lo
                });
                agree && clear > 3000
            },
        },
        // Exercise 22
        Check {
            exercise: 22,
            name: "the nearest primitive and its distance, as brute force finds it",
            points: 5,
            run: |e| {
                let mut r = Rng(22);
                nearest_cases().iter().all(|t| {
                    let tree = t.bvh();
                    (0..40).all(|_| {
                        let p = r.point(14.0, Vec3::new(4.5, 4.5, 1.0));
                        let dist = |b: &Aabb| b.distance_squared(p).sqrt();
                        let want = t.prims.iter().map(dist).fold(f32::INFINITY, f32::min);
                        match e.best_first_nearest(&tree, &t.prims, p) {
                            None => t.prims.is_empty(),
                            Some((k, d, _)) => {
                                let tol = 1e-5 * want.max(1.0);
                                (dist(&t.prims[k as usize]) - want).abs() <= tol
                                    && (d - want).abs() <= tol
                            }
                        }
                    })
                })
            },
        },
        Check {
            exercise: 22,
            name: "best-first: takes few nodes (at most 1.5x the reference's + 2)",
            points: 5,
            run: |e| {
                let mut r = Rng(23);
                nearest_cases()
                    .iter()
                    .filter(|t| !t.prims.is_empty())
                    .all(|t| {
                        let tree = t.bvh();
                        (0..40).all(|_| {
                            let p = r.point(14.0, Vec3::new(4.5, 4.5, 1.0));
                            let taken = |x: &dyn Exercises| {
                                x.best_first_nearest(&tree, &t.prims, p)
                                    .map_or(usize::MAX, |a| a.2)
                            };
                            taken(e) * 2 <= taken(&Reference) * 3 + 4
                        })
                    })
            },
        },
        // Exercise 23
        Check {
            exercise: 23,
            name: "bounds in leaf order: entry k bounds primitive indices[k]",
            points: 5,
            run: |e| {
                leaf_order_cases().iter().all(|(tris, leaf)| {
                    let builder = TopDown::default().with_max_leaf_size(*leaf);
                    let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(tris.len())];
                    let mut idx = vec![0u32; tris.len()];
                    let Ok(tree) = builder.build(tris, &mut nodes, &mut idx) else {
                        return false;
                    };
                    let got = e.leaf_order_bounds(&tree, tris);
                    got.len() == tree.indices().len()
                        && got
                            .iter()
                            .zip(tree.indices())
                            .all(|(b, &p)| *b == bvhkit::Primitive::bounds(&tris[p as usize]))
                })
            },
        },
        Check {
            exercise: 23,
            name: "a leaf pair's candidates: ids in order, touching boxes count",
            points: 5,
            run: |e| {
                let mut r = Rng(2324);
                let unit = |o: Vec3| Aabb::new(o, o + Vec3::ONE);
                // Touching along x (1.0 = 1.0), apart, and nested.
                let fixed = e.leaf_pair_candidates(
                    (&[7, 3], &[unit(Vec3::ZERO), unit(Vec3::splat(5.0))]),
                    (
                        &[9, 2, 4],
                        &[
                            unit(Vec3::X),
                            unit(Vec3::splat(2.5)),
                            unit(Vec3::splat(5.2)),
                        ],
                    ),
                ) == [(7, 9), (3, 4)];
                fixed
                    && (0..300).all(|_| {
                        let leaf = |r: &mut Rng, base: u32| -> (Vec<u32>, Vec<Aabb>) {
                            let n = 1 + (r.next() * 4.0) as usize;
                            let ids = (0..n).map(|k| base + (k as u32 * 7) % 11).collect();
                            // Corners on a half-unit grid: touching is common.
                            let snap = |v: Vec3| (v * 2.0).round() * 0.5;
                            let boxes = (0..n)
                                .map(|_| {
                                    let o = snap(r.point(3.0, Vec3::ZERO));
                                    Aabb::new(o, o + snap(r.point(1.0, Vec3::splat(1.0))))
                                })
                                .collect();
                            (ids, boxes)
                        };
                        let (ia, ba) = leaf(&mut r, 100);
                        let (ib, bb) = leaf(&mut r, 200);
                        e.leaf_pair_candidates((&ia, &ba), (&ib, &bb))
                            == Reference.leaf_pair_candidates((&ia, &ba), (&ib, &bb))
                    })
            },
        },
        // Exercise 24
        Check {
            exercise: 24,
            name: "stopping and the depth budget (leaf size, max depth, ceil(log2(ceil(n/k))))",
            points: 5,
            run: |e| {
                let stop = |k: u32, d: u32| Stop {
                    max_leaf_size: k,
                    max_depth: d,
                    min_volume: 0.0,
                };
                use NodeStep::{Halve, Leaf, Split};
                // (n, depth, leaf size, max depth, want), the split balanced.
                let fixed = [
                    (4, 0, 4, 64, Leaf),    // at the leaf size
                    (500, 64, 4, 64, Leaf), // at the depth limit, however large
                    (500, 10, 4, 10, Leaf),
                    (9, 62, 4, 64, Halve), // 3 leaves need 2 levels: 2 left
                    (9, 61, 4, 64, Split), // 3 left
                    (8, 63, 4, 64, Halve), // 2 leaves need 1 level
                    (8, 62, 4, 64, Split),
                    (5000, 0, 4, 3, Halve), // a cap the input cannot meet
                    (5000, 0, 4, 64, Split),
                    (2, 63, 1, 64, Halve),
                    (1000, 54, 1, 64, Halve), // 1000 leaves need 10 levels: 10 left
                    (1000, 53, 1, 64, Split),
                ];
                let mut r = Rng(2424);
                fixed.iter().all(|&(n, depth, k, d, want)| {
                    e.node_step(n, depth, &stop(k, d), n / 2, true) == want
                }) && (0..2000).all(|_| {
                    let n = 1 + (r.next() * 3000.0) as u32;
                    let k = 1 + (r.next() * 8.0) as u32;
                    let d = (r.next() * 65.0) as u32;
                    let depth = (r.next() * 66.0) as u32;
                    let s = stop(k, d);
                    e.node_step(n, depth, &s, n / 2, true)
                        == Reference.node_step(n, depth, &s, n / 2, true)
                })
            },
        },
        Check {
            exercise: 24,
            name: "failed splits: nothing on one side; a sliver under 1% for count-blind criteria",
            points: 5,
            run: |e| {
                let s = Stop {
                    max_leaf_size: 4,
                    max_depth: 64,
                    min_volume: 0.0,
                };
                use NodeStep::{FallBack, Split};
                // (n, left, weighs counts, want), far from the depth limit.
                let fixed = [
                    (1000, 0, true, FallBack),
                    (1000, 1000, true, FallBack),
                    (1000, 0, false, FallBack),
                    (1000, 1, true, Split), // the SAH prices a 1-in-1000 cut
                    (1000, 1, false, FallBack),
                    (1000, 999, false, FallBack), // either side
                    (1000, 9, false, FallBack),
                    (1000, 10, false, Split), // exactly 1%: not under it
                    (100, 1, false, Split),
                    (101, 1, false, FallBack),
                    (99, 0, false, FallBack),
                    (99, 1, false, Split), // under 100 primitives: no sliver rule
                ];
                let mut r = Rng(2425);
                fixed
                    .iter()
                    .all(|&(n, left, w, want)| e.node_step(n, 0, &s, left, w) == want)
                    && (0..3000).all(|_| {
                        let n = 5 + (r.next() * 3000.0) as u32;
                        let left = if r.next() < 0.5 {
                            (r.next() * 0.03 * n as f32) as u32
                        } else {
                            (r.next() * (n + 1) as f32) as u32
                        }
                        .min(n);
                        let left = if r.next() < 0.5 { left } else { n - left };
                        let w = r.next() < 0.3;
                        e.node_step(n, 0, &s, left, w) == Reference.node_step(n, 0, &s, left, w)
                    })
            },
        },
        // Exercise 25
        Check {
            exercise: 25,
            name: "fit (Cv, Cp) on relative error: exact data back, noisy data as the reference",
            points: 5,
            run: |e| {
                let close = |(a, b): (f64, f64), (c, d): (f64, f64)| {
                    (a - c).abs() <= 1e-6 * c.abs().max(1e-9)
                        && (b - d).abs() <= 1e-6 * d.abs().max(1e-9)
                };
                let mut r = Rng(2525);
                // Times made by a known model come back exactly.
                let exact: Vec<(u64, u64, f64)> = (0..12)
                    .map(|i| {
                        let (nv, np) = (100 + 997 * i as u64, 50 + (i as u64 * 7919) % 3001);
                        (nv, np, 6.0 * nv as f64 + 30.0 * np as f64)
                    })
                    .collect();
                // Small and large queries with +-20% noise: a fit on absolute
                // error lets the large ones decide; the relative one does not.
                let noisy = |r: &mut Rng| -> Vec<(u64, u64, f64)> {
                    (0..10)
                        .map(|i| {
                            let scale = if i % 2 == 0 { 1u64 } else { 10_000 };
                            let nv = scale * (1 + (r.next() * 50.0) as u64);
                            let np = scale * (1 + (r.next() * 20.0) as u64);
                            let t = (5.0 * nv as f64 + 40.0 * np as f64)
                                * (0.8 + 0.4 * r.next() as f64);
                            (nv, np, t)
                        })
                        .collect()
                };
                close(e.fit_unit_costs(&exact), (6.0, 30.0))
                    && (0..200).all(|_| {
                        let d = noisy(&mut r);
                        close(e.fit_unit_costs(&d), Reference.fit_unit_costs(&d))
                    })
            },
        },
        Check {
            exercise: 25,
            name: "costs never negative (the other refitted alone); no usable sample gives (0, 0)",
            points: 5,
            run: |e| {
                let close = |(a, b): (f64, f64), (c, d): (f64, f64)| {
                    (a - c).abs() <= 1e-6 * c.abs().max(1e-9)
                        && (b - d).abs() <= 1e-6 * d.abs().max(1e-9)
                };
                // t = 5 Nv - 1 Np: the unconstrained fit makes Cp negative.
                let negative: Vec<(u64, u64, f64)> = (1..10u64)
                    .map(|i| {
                        (
                            100 * i,
                            30 * i * i,
                            500.0 * i as f64 - 30.0 * (i * i) as f64,
                        )
                    })
                    .collect();
                let (cv, cp) = e.fit_unit_costs(&negative);
                // Cv alone, fitted on relative error: sum(x) / sum(x^2), x = Nv/t.
                let xs: Vec<f64> = negative.iter().map(|&(nv, _, t)| nv as f64 / t).collect();
                let alone = xs.iter().sum::<f64>() / xs.iter().map(|x| x * x).sum::<f64>();
                let mut r = Rng(2526);
                cp == 0.0
                    && (cv - alone).abs() <= 1e-6 * alone
                    && close(e.fit_unit_costs(&[]), (0.0, 0.0))
                    && close(e.fit_unit_costs(&[(0, 0, 5.0), (3, 4, 0.0)]), (0.0, 0.0))
                    && close(
                        e.fit_unit_costs(&[(10, 0, 50.0), (20, 0, -1.0)]),
                        (5.0, 0.0),
                    )
                    && (0..300).all(|_| {
                        // Random signs of the true costs: both clamps happen.
                        let (a, b) = (r.next() as f64 * 20.0 - 5.0, r.next() as f64 * 20.0 - 5.0);
                        let d: Vec<(u64, u64, f64)> = (0..6)
                            .map(|_| {
                                let (nv, np) =
                                    (1 + (r.next() * 90.0) as u64, 1 + (r.next() * 90.0) as u64);
                                (nv, np, (a * nv as f64 + b * np as f64).abs() + 1.0)
                            })
                            .collect();
                        let got = e.fit_unit_costs(&d);
                        got.0 >= 0.0 && got.1 >= 0.0 && close(got, Reference.fit_unit_costs(&d))
                    })
            },
        },
        // Exercise 26
        Check {
            exercise: 26,
            name: "axis choice: longest extent or largest variance, ties to the lower axis",
            points: 5,
            run: |e| {
                use crate::{AxisRule::*, PointRule::SpatialMedian};
                let v = Vec3::new;
                let axis = |c: &[Vec3], rule| e.split_plane(c, rule, SpatialMedian).map(|p| p.0);
                // One far outlier on x: x spreads furthest (10 against 8),
                // y varies most (16 against 9).
                let outlier: Vec<Vec3> = (0..10)
                    .map(|i| {
                        v(
                            if i == 0 { 10.0 } else { 0.0 },
                            if i % 2 == 0 { 4.0 } else { -4.0 },
                            0.0,
                        )
                    })
                    .collect();
                let cube = [v(0.0, 0.0, 0.0), v(1.0, 1.0, 1.0)];
                let yz = [v(0.0, 0.0, 0.0), v(0.0, 2.0, 2.0)];
                let mut r = Rng(2626);
                axis(&outlier, Longest) == Some(0)
                    && axis(&outlier, Variance) == Some(1)
                    && axis(&cube, Longest) == Some(0)
                    && axis(&cube, Variance) == Some(0)
                    && axis(&yz, Longest) == Some(1)
                    && axis(&yz, Variance) == Some(1)
                    && axis(&[v(5.0, 5.0, 5.0)], Longest) == Some(0)
                    && e.split_plane(&[], Longest, SpatialMedian).is_none()
                    && (0..500).all(|_| {
                        let n = 1 + (r.next() * 12.0) as usize;
                        let squash = r.point(1.0, Vec3::ZERO).abs();
                        let c: Vec<Vec3> =
                            (0..n).map(|_| r.point(4.0, Vec3::ZERO) * squash).collect();
                        [Longest, Variance].iter().all(|&rule| {
                            e.split_plane(&c, rule, SpatialMedian)
                                == Reference.split_plane(&c, rule, SpatialMedian)
                        })
                    })
            },
        },
        Check {
            exercise: 26,
            name: "split point: median at n/2, mean and middle of the extent in f64",
            points: 5,
            run: |e| {
                use crate::{AxisRule::Longest, PointRule::*};
                let v = Vec3::new;
                let at = |c: &[Vec3], rule| e.split_plane(c, Longest, rule).map(|p| p.1);
                // x: 0, 1, 2, 10 (longest); the upper middle is 2.
                let row = [
                    v(10.0, 0.0, 0.0),
                    v(0.0, 0.0, 0.0),
                    v(2.0, 0.0, 0.0),
                    v(1.0, 0.0, 0.0),
                ];
                // Near f32::MAX: (min + max) overflows f32 but not f64.
                let huge = [
                    v(3.0e38, 0.0, 0.0),
                    v(3.2e38, 0.0, 0.0),
                    v(2.0e38, 0.0, 0.0),
                ];
                let mut r = Rng(2627);
                at(&row, ObjectMedian) == Some(2.0)
                    && at(&row, ObjectMean) == Some(3.25)
                    && at(&row, SpatialMedian) == Some(5.0)
                    && at(
                        &[v(-1.0, 0.0, 0.0), v(7.0, 0.0, 0.0), v(3.0, 0.0, 0.0)],
                        ObjectMedian,
                    ) == Some(3.0)
                    && at(&huge, SpatialMedian)
                        == Reference
                            .split_plane(&huge, Longest, SpatialMedian)
                            .map(|p| p.1)
                    && at(&huge, ObjectMean)
                        == Reference
                            .split_plane(&huge, Longest, ObjectMean)
                            .map(|p| p.1)
                    && at(&huge, SpatialMedian).is_some_and(f32::is_finite)
                    && (0..500).all(|_| {
                        let n = 1 + (r.next() * 15.0) as usize;
                        let shift = r.point(1e4, Vec3::ZERO);
                        let c: Vec<Vec3> = (0..n).map(|_| r.point(3.0, shift)).collect();
                        [ObjectMedian, ObjectMean, SpatialMedian]
                            .iter()
                            .all(|&rule| {
                                e.split_plane(&c, Longest, rule)
                                    == Reference.split_plane(&c, Longest, rule)
                            })
                    })
            },
        },
        // Exercise 27
        Check {
            exercise: 27,
            name: "depths: the root at 0, the mean over leaves (not primitives), a one-leaf tree",
            points: 5,
            run: |e| {
                let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1.0);
                on_measured_trees(|tree| {
                    let (got, want) = (e.tree_measures(tree), Reference.tree_measures(tree));
                    let stats = tree.stats();
                    got.max_depth == want.max_depth
                        && close(got.mean_leaf_depth, want.mean_leaf_depth)
                        && want.max_depth == stats.max_depth
                        && close(want.mean_leaf_depth, stats.mean_leaf_depth)
                }) && {
                    // One leaf of three: depth 0, and the SAH counts its three tests.
                    let tris = &measured_trees()[1].0;
                    let mut nodes = vec![Node::<Aabb>::EMPTY; 1];
                    let mut idx = vec![0u32; tris.len()];
                    TopDown::sah()
                        .with_max_leaf_size(8)
                        .build(tris, &mut nodes, &mut idx)
                        .is_ok_and(|t| {
                            let m = e.tree_measures(&t);
                            m.max_depth == 0 && m.mean_leaf_depth == 0.0 && close(m.sah_cost, 3.0)
                        })
                }
            },
        },
        Check {
            exercise: 27,
            name: "SAH cost: internal nodes once, leaves times their size, areas relative to the root in f64",
            points: 5,
            run: |e| {
                let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1.0);
                on_measured_trees(|tree| {
                    let (got, want) = (e.tree_measures(tree), Reference.tree_measures(tree));
                    close(got.sah_cost, want.sah_cost)
                        && (want.sah_cost - tree.stats().sah_cost).abs()
                            <= 1e-4 * want.sah_cost.max(1.0)
                })
            },
        },
        // Exercise 28
        Check {
            exercise: 28,
            name: "tri-node records: one per node at an even depth, as TriNodes stores them",
            points: 5,
            run: |e| {
                use bvhkit::layout::{TriNode, TriNodes};
                on_measured_trees(|tree| {
                    let got = e.tri_node_records(tree).0;
                    let Ok(n) = TriNodes::records_needed(tree) else {
                        return false;
                    };
                    let mut recs = vec![TriNode::EMPTY; n];
                    got == n
                        && (tree.is_empty()
                            || TriNodes::from_bvh(tree, &mut recs)
                                .is_ok_and(|t| t.records().len() == got))
                })
            },
        },
        Check {
            exercise: 28,
            name: "tri-node waste: two empty slots per record rooted at a leaf",
            points: 5,
            run: |e| {
                use bvhkit::layout::{TriNode, TriNodes};
                on_measured_trees(|tree| {
                    let (records, unused) = e.tri_node_records(tree);
                    let Ok(n) = TriNodes::records_needed(tree) else {
                        return false;
                    };
                    let mut recs = vec![TriNode::EMPTY; n];
                    // The library's records: 3 slots each, `used()` of them filled.
                    let library = if tree.is_empty() {
                        0
                    } else {
                        match TriNodes::from_bvh(tree, &mut recs) {
                            Ok(t) => t.records().iter().map(|r| 3 - r.used() as usize).sum(),
                            Err(_) => return false,
                        }
                    };
                    records == n && unused == library
                })
            },
        },
        // Exercise 29
        Check {
            exercise: 29,
            name: "OBB fit: every point inside in exact arithmetic, also far from the origin",
            points: 5,
            run: |e| {
                let mut r = Rng(2929);
                obb_cases(&mut r).iter().all(|(pts, axes)| {
                    let b = e.fit_obb(pts, *axes);
                    !pts.is_empty() && obb_contains(&b, pts) && b.axes == *axes
                }) && e.fit_obb(&[], rotated_axes(&mut r)) == Obb::EMPTY
            },
        },
        Check {
            exercise: 29,
            name: "OBB fit: tight along the given axes (not the AABB, not around the mean)",
            points: 5,
            run: |e| {
                let mut r = Rng(2930);
                obb_cases(&mut r).iter().all(|(pts, axes)| {
                    let b = e.fit_obb(pts, *axes);
                    let want = exact_half_extents(pts, axes);
                    // What rounding may add far from the origin: the centre
                    // rounded to f32, and f32 axes that are orthonormal only
                    // to about 1e-7, over a centre 1e6 away.
                    let moved = b.center.abs().max_element() as f64 * 2f64.powi(-20);
                    (0..3).all(|k| {
                        let h = b.half_extents[k] as f64;
                        h <= want[k] * (1.0 + 1e-5) + moved + 1e-30 && h >= want[k] * (1.0 - 1e-5)
                    })
                })
            },
        },
        // Exercise 30
        Check {
            exercise: 30,
            name: "preorder offsets as built: 1 + the left subtree, as the Preorder layout links them",
            points: 5,
            run: |e| {
                use bvhkit::layout::{PreNode, Preorder};
                on_measured_trees(|tree| {
                    let mut recs = vec![PreNode::<Aabb, u32>::EMPTY; tree.node_count()];
                    let Ok(pre) = Preorder::from_bvh(tree, &mut recs) else {
                        return false;
                    };
                    let library = (pre.records().iter().enumerate())
                        .filter_map(|(i, r)| r.right().map(|right| right - i))
                        .max()
                        .unwrap_or(0);
                    e.preorder_offsets(tree).0 == library
                }) && on_lopsided_trees(|tree| e.preorder_offsets(tree).0 == Reference.preorder_offsets(tree).0)
            },
        },
        Check {
            exercise: 30,
            name: "preorder offsets with the smaller subtree first: 1 + the smaller side",
            points: 5,
            run: |e| {
                on_measured_trees(|tree| e.preorder_offsets(tree) == Reference.preorder_offsets(tree))
                    && on_lopsided_trees(|tree| {
                        e.preorder_offsets(tree) == Reference.preorder_offsets(tree)
                    })
            },
        },
        // Exercise 31
        Check {
            exercise: 31,
            name: "broad phase: every overlapping pair a < b (touching counts) goes to the narrow phase once, no other",
            points: 5,
            run: |e| {
                let mut r = Rng(3131);
                object_scenes(&mut r).iter().all(|boxes| {
                    let mut calls = Vec::new();
                    let _ = e.collide_objects(boxes, &mut |a, b| {
                        calls.push((a, b));
                        Vec::new()
                    });
                    calls.sort_unstable();
                    calls == overlapping_object_pairs(boxes)
                })
            },
        },
        Check {
            exercise: 31,
            name: "results: every contact, ordered by object pair, in the narrow phase's order within one",
            points: 5,
            run: |e| {
                let mut r = Rng(3132);
                // A narrow phase whose answer depends on the pair: (a+b) % 3
                // contacts, in a fixed order.
                let narrow = |a: u32, b: u32| -> Vec<(u32, u32)> {
                    (0..(a + b) % 3).map(|k| (a * 10 + k, b * 10 + 2 - k)).collect()
                };
                object_scenes(&mut r).iter().all(|boxes| {
                    let want: Vec<((u32, u32), (u32, u32))> = overlapping_object_pairs(boxes)
                        .into_iter()
                        .flat_map(|(a, b)| narrow(a, b).into_iter().map(move |p| ((a, b), p)))
                        .collect();
                    e.collide_objects(boxes, &mut |a, b| narrow(a, b)) == want
                })
            },
        },
    ]
}

/// Object boxes for exercise 31: none, one, two touching at a face, an
/// empty box among others, a row where each touches the next, and random
/// scenes with duplicates.
fn object_scenes(r: &mut Rng) -> Vec<Vec<Aabb>> {
    let unit = |o: Vec3| Aabb::new(o, o + Vec3::ONE);
    let mut out = vec![
        Vec::new(),
        vec![unit(Vec3::ZERO)],
        vec![unit(Vec3::ZERO), unit(Vec3::X)],
        vec![unit(Vec3::ZERO), Aabb::EMPTY, unit(Vec3::splat(0.5))],
        (0..12).map(|i| unit(Vec3::X * i as f32)).collect(),
    ];
    for _ in 0..40 {
        let n = (r.next() * 30.0) as usize;
        let mut boxes: Vec<Aabb> = (0..n)
            .map(|_| {
                let o = r.point(6.0, Vec3::ZERO);
                Aabb::new(o, o + r.point(1.0, Vec3::splat(1.0)).abs())
            })
            .collect();
        if n > 2 {
            boxes[n - 1] = boxes[0];
        }
        out.push(boxes);
    }
    out
}

/// Every pair `a < b` of boxes that overlap, sorted: the brute-force broad
/// phase.
fn overlapping_object_pairs(boxes: &[Aabb]) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    for a in 0..boxes.len() {
        for b in a + 1..boxes.len() {
            if boxes[a].overlaps(&boxes[b]) {
                out.push((a as u32, b as u32));
            }
        }
    }
    out
}

/// Trees whose big subtree is sometimes on the left, sometimes on the
/// right: points growing geometrically, split at the spatial median (the
/// top one or two points split off at each level), and the same row
/// reversed.
fn on_lopsided_trees(check: impl Fn(&Bvh<Aabb>) -> bool) -> bool {
    [false, true].iter().all(|&reversed| {
        let pts: Vec<Vec3> = (0..40)
            .map(|i| {
                let x = 1.5f32.powi(i);
                Vec3::new(if reversed { -x } else { x }, 0.0, 0.0)
            })
            .collect();
        let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(pts.len())];
        let mut idx = vec![0u32; pts.len()];
        TopDown {
            split: bvhkit::SplitPoint::SpatialMedian,
            ..TopDown::median()
        }
        .with_max_leaf_size(1)
        .build(&pts, &mut nodes, &mut idx)
        .is_ok_and(|tree| check(&tree))
    })
}

/// Orthonormal axes turned by a random rotation.
fn rotated_axes(r: &mut Rng) -> [Vec3; 3] {
    let q = bvhkit::glam::Quat::from_euler(
        bvhkit::glam::EulerRot::XYZ,
        r.next() * 6.0,
        r.next() * 6.0,
        r.next() * 6.0,
    );
    [q * Vec3::X, q * Vec3::Y, q * Vec3::Z]
}

/// Point sets for exercise 29 with axes to fit them in: one point, a
/// stick along an axis, clouds near the origin and a million units away
/// (where f32 rounding of the centre decides containment), squashed along
/// one axis.
fn obb_cases(r: &mut Rng) -> Vec<(Vec<Vec3>, [Vec3; 3])> {
    let mut out = Vec::new();
    let axes = rotated_axes(r);
    out.push((vec![Vec3::new(3.0, -2.0, 7.5)], axes));
    out.push((
        (0..5)
            .map(|i| axes[0] * i as f32 + Vec3::splat(1e3))
            .collect(),
        axes,
    ));
    for k in 0..60 {
        let axes = rotated_axes(r);
        let offset = if k % 2 == 0 { 0.0 } else { 1e6 };
        let base = r.point(offset, Vec3::ZERO);
        let squash = Vec3::new(1.0, 0.3, 0.01 + r.next());
        let n = 1 + (r.next() * 40.0) as usize;
        let pts = (0..n)
            .map(|_| {
                let p = r.point(5.0, Vec3::ZERO) * squash;
                base + axes[0] * p.x + axes[1] * p.y + axes[2] * p.z
            })
            .collect();
        out.push((pts, axes));
    }
    out
}

/// Whether every point is inside `b`, tested in f64 on its f32 values.
fn obb_contains(b: &Obb, pts: &[Vec3]) -> bool {
    pts.iter().all(|p| {
        let v = p.as_dvec3() - b.center.as_dvec3();
        (0..3).all(|k| b.axes[k].as_dvec3().dot(v).abs() <= b.half_extents[k] as f64)
    })
}

/// Half the projection range of the points on each axis, in f64.
fn exact_half_extents(pts: &[Vec3], axes: &[Vec3; 3]) -> [f64; 3] {
    let mut out = [0.0; 3];
    for (k, a) in axes.iter().enumerate() {
        let (lo, hi) = pts
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
                let t = a.as_dvec3().dot(p.as_dvec3());
                (l.min(t), h.max(t))
            });
        out[k] = (hi - lo) / 2.0;
    }
    out
}

/// Builds an SAH tree over each of [`measured_trees`] and asks `check` about
/// it; false if any build fails or any answer is false.
fn on_measured_trees(check: impl Fn(&Bvh<Aabb>) -> bool) -> bool {
    measured_trees().iter().all(|(tris, leaf)| {
        let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(tris.len())];
        let mut idx = vec![0u32; tris.len()];
        TopDown::sah()
            .with_max_leaf_size(*leaf)
            .build(tris, &mut nodes, &mut idx)
            .is_ok_and(|tree| check(&tree))
    })
}

/// Triangles for exercise 27, each with a leaf size: empty, three (one
/// leaf), a row of 40 in leaves of one, 300 scattered, and 50 spread over
/// 1e30 (areas past f32's range).
fn measured_trees() -> Vec<(Vec<Triangle>, u32)> {
    let mut r = Rng(2727);
    let tri = |o: Vec3, s: f32| Triangle::new(o, o + Vec3::X * s, o + Vec3::Y * s);
    let mut out = vec![
        (Vec::new(), 4),
        ((0..3).map(|i| tri(Vec3::splat(i as f32), 0.5)).collect(), 4),
        (
            (0..40)
                .map(|i| tri(Vec3::new(i as f32 * 2.0, 0.0, 0.0), 1.0))
                .collect(),
            1,
        ),
    ];
    out.push((
        (0..300)
            .map(|_| tri(r.point(50.0, Vec3::ZERO), 1.0 + r.next()))
            .collect(),
        4,
    ));
    out.push((
        (0..50)
            .map(|_| tri(r.point(1e30, Vec3::ZERO), 1e28))
            .collect(),
        2,
    ));
    out
}

/// Triangles for exercise 23: empty, one, and grids whose leaves of up to
/// four hold primitives out of their input order.
fn leaf_order_cases() -> Vec<(Vec<Triangle>, u32)> {
    let mut r = Rng(2323);
    [(0, 4), (1, 4), (37, 4), (200, 4), (64, 1)]
        .into_iter()
        .map(|(n, leaf)| {
            let tris = (0..n)
                .map(|i| {
                    let o = Vec3::new((i % 9) as f32, (i / 9 % 9) as f32, (i / 81) as f32)
                        + r.point(0.5, Vec3::ZERO);
                    Triangle::new(o, o + r.point(1.0, Vec3::X), o + r.point(1.0, Vec3::Y))
                })
                .collect();
            (tris, leaf)
        })
        .collect()
}

/// Trees for the nearest-primitive search: empty, and grids of boxes.
fn nearest_cases() -> Vec<Tree> {
    vec![
        Tree::new(vec![], 1),
        Tree::new(boxes(1, 31, Vec3::ZERO), 1),
        Tree::new(boxes(60, 37, Vec3::ZERO), 1),
        Tree::new(boxes(300, 41, Vec3::ZERO), 4),
    ]
}

/// A box with half extents (1, 0.6, 0.3) at `c`, turned by `yaw` about z
/// and `pitch` about x.
fn turned(c: Vec3, yaw: f32, pitch: f32) -> Obb {
    let q = bvhkit::glam::Quat::from_rotation_z(yaw) * bvhkit::glam::Quat::from_rotation_x(pitch);
    Obb {
        center: c,
        axes: [q * Vec3::X, q * Vec3::Y, q * Vec3::Z],
        half_extents: Vec3::new(1.0, 0.6, 0.3),
    }
}

/// Relative closeness for the exercises' `f64` answers.
fn close(x: f64, want: f64) -> bool {
    (x - want).abs() <= 1e-9 * want.abs().max(1.0)
}

/// Trees to walk: empty, one leaf, and top-down trees of a few shapes.
fn visit_cases() -> Vec<Tree> {
    let mut cases = vec![Tree::new(vec![], 1), Tree::new(boxes(1, 3, Vec3::ZERO), 1)];
    for (n, seed) in [(2, 5), (7, 11), (40, 13)] {
        cases.push(Tree::new(boxes(n, seed, Vec3::ZERO), 1 + (seed % 3) as u32));
    }
    cases
}

/// The unit cube at `x` along the x axis.
fn unit_at(x: f32) -> Aabb {
    Aabb::new(Vec3::new(x, 0.0, 0.0), Vec3::new(x + 1.0, 1.0, 1.0))
}

/// `n` unit boxes in a row of a grid, shifted by `shift`.
fn grid_boxes(n: usize, shift: f32) -> Vec<Aabb> {
    (0..n)
        .map(|i| {
            let o = Vec3::new((i % 8) as f32 + shift, (i / 8) as f32 + shift, 0.0);
            Aabb::new(o, o + Vec3::ONE)
        })
        .collect()
}

/// Whether the quantized child decodes to a box containing it.
fn quantized_contains(e: &dyn Exercises, p: &Aabb, c: &Aabb) -> bool {
    let (lo, hi) = e.quantize(p, c);
    (0..3).all(|k| {
        crate::dequantize(p, k, lo[k]) <= c.min[k] && crate::dequantize(p, k, hi[k]) >= c.max[k]
    })
}

/// Parent/child pairs for exercise 13: random children, children whose faces
/// lie on grid lines or one `f32` step beside them, far from the origin.
fn quantize_cases() -> Vec<(Aabb, Aabb)> {
    let mut r = Rng(0x51ed_270b_9a3c_4e5f);
    let mut out = Vec::new();
    for i in 0..400 {
        let off = if i % 3 == 0 {
            Vec3::new(1.0e5, -7.3e3, 0.1)
        } else {
            Vec3::ZERO
        };
        let p = Aabb::fit(&[r.point(20.0, off), r.point(20.0, off)]);
        let mut c = Aabb::fit(&[
            p.min + (p.max - p.min) * Vec3::new(r.next(), r.next(), r.next()),
            p.min + (p.max - p.min) * Vec3::new(r.next(), r.next(), r.next()),
        ]);
        if i % 2 == 1 {
            // Snap the faces to grid lines, then nudge by one ulp either way.
            for k in 0..3 {
                let q = (r.next() * 254.0) as u8;
                let g = crate::dequantize(&p, k, q);
                let nudge = match i % 4 {
                    1 => g,
                    _ => f32::from_bits(g.to_bits().wrapping_sub(1)).max(p.min[k]),
                };
                c.min[k] = nudge.min(c.max[k]);
                c.max[k] = c.max[k].max(c.min[k]);
            }
        }
        out.push((p, c));
    }
    out
}

/// Replays a merge sequence: whether every merge joins two live clusters and
/// exactly one cluster is left. With `check_greedy`, each merge must also have
/// the smallest merged volume among the live pairs of its step.
fn replay(boxes: &[Aabb], merges: &[(u32, u32)], check_greedy: bool) -> bool {
    let n = boxes.len();
    if merges.len() != n.saturating_sub(1) {
        return false;
    }
    let mut live: Vec<Option<Aabb>> = boxes.iter().copied().map(Some).collect();
    for &(a, b) in merges {
        let (a, b) = (a as usize, b as usize);
        let (Some(Some(x)), Some(Some(y))) = (live.get(a).copied(), live.get(b).copied()) else {
            return false;
        };
        if a == b {
            return false;
        }
        let cost = x.union(&y).volume();
        if check_greedy {
            let alive: Vec<Aabb> = live.iter().flatten().copied().collect();
            let best = (0..alive.len())
                .flat_map(|i| (i + 1..alive.len()).map(move |j| (i, j)))
                .map(|(i, j)| alive[i].union(&alive[j]).volume())
                .fold(f32::INFINITY, f32::min);
            if cost > best * (1.0 + 1e-5) {
                return false;
            }
        }
        live[a] = None;
        live[b] = None;
        live.push(Some(x.union(&y)));
    }
    live.iter().flatten().count() == 1
}

fn merge_sets() -> Vec<Vec<Aabb>> {
    let mut r = Rng(99);
    let mut sets: Vec<Vec<Aabb>> = (0..6)
        .map(|k| {
            (0..(5 + 7 * k))
                .map(|_| {
                    let lo = r.point(20.0, Vec3::ZERO);
                    Aabb::new(lo, lo + Vec3::new(r.next(), r.next(), r.next()) * 3.0 + 0.1)
                })
                .collect()
        })
        .collect();
    // Two tight groups far apart: the groups must close before they join.
    let group = |o: Vec3| {
        (0..4).map(move |i| {
            Aabb::new(
                o + Vec3::X * i as f32 * 1.1,
                o + Vec3::X * i as f32 * 1.1 + 1.0,
            )
        })
    };
    sets.push(group(Vec3::ZERO).chain(group(Vec3::splat(100.0))).collect());
    sets
}

/// Builds a tree over boxes, moves every third box, and returns the
/// student's refit next to the library's.
fn refit_case(e: &dyn Exercises, n: usize, seed: u64) -> (Vec<Node<Aabb>>, Vec<Node<Aabb>>) {
    let t = Tree::new(boxes(n, seed, Vec3::ZERO), 2);
    let used = t.bvh().node_count();
    let mut r = Rng(seed + 1);
    let moved: Vec<Aabb> = t
        .prims
        .iter()
        .enumerate()
        .map(|(i, b)| {
            if i % 3 == 0 {
                let d = r.point(6.0, Vec3::ZERO);
                Aabb::new(b.min + d, b.max + d)
            } else {
                *b
            }
        })
        .collect();
    let mut student = t.nodes[..used].to_vec();
    e.refit(&mut student, &t.indices, &moved);
    let mut want = t.nodes[..used].to_vec();
    if let Err(err) = bvhkit::builders::refit_all(&mut want, &t.indices, &moved, 0.0, ()) {
        panic!("grader refit: {err}");
    }
    (student, want)
}

/// A tree over boxes, with its storage.
struct Tree {
    prims: Vec<Aabb>,
    nodes: Vec<Node<Aabb>>,
    indices: Vec<u32>,
    depth: usize,
}

impl Tree {
    fn new(prims: Vec<Aabb>, leaf: u32) -> Tree {
        let builder = TopDown::default().with_max_leaf_size(leaf);
        let mut nodes = vec![Node::EMPTY; bvhkit::max_nodes(prims.len())];
        let mut indices = vec![0u32; prims.len()];
        let (depth, used) = match builder.build(&prims, &mut nodes, &mut indices) {
            Ok(t) => (t.depth(), t.node_count()),
            Err(e) => panic!("grader tree: {e}"),
        };
        nodes.truncate(used);
        Tree {
            prims,
            nodes,
            indices,
            depth,
        }
    }

    fn bvh(&self) -> Bvh<'_, Aabb> {
        Bvh::from_raw_parts(&self.nodes, &self.indices, self.depth)
    }
}

/// Boxes on a jittered grid, some overlapping their neighbours.
fn boxes(n: usize, seed: u64, offset: Vec3) -> Vec<Aabb> {
    let mut r = Rng(seed);
    (0..n)
        .map(|i| {
            let c = Vec3::new((i % 10) as f32, (i / 10 % 10) as f32, (i / 100) as f32) + offset;
            let lo = c + r.point(0.6, Vec3::ZERO);
            Aabb::new(
                lo,
                lo + Vec3::new(r.next(), r.next(), r.next()) * 0.9 + 0.05,
            )
        })
        .collect()
}

fn reference_pairs(a: &Tree, b: &Tree) -> Vec<(u32, u32)> {
    let mut want = Vec::new();
    brute_force::pairs(&a.prims, &b.prims, |i, j| want.push((i, j)));
    want.sort_unstable();
    want
}

/// Scene pairs for the traversal exercises: overlapping grids with different
/// leaf sizes, and tiny trees (1 to 3 leaves) apart and touching.
fn traversal_cases() -> Vec<(Tree, Tree)> {
    let mut cases = vec![
        (
            Tree::new(boxes(300, 1, Vec3::ZERO), 1),
            Tree::new(boxes(250, 2, Vec3::splat(0.4)), 3),
        ),
        (
            Tree::new(boxes(64, 3, Vec3::ZERO), 4),
            Tree::new(boxes(500, 4, Vec3::new(-2.0, 1.0, 0.0)), 1),
        ),
    ];
    for (na, nb) in [(1, 1), (1, 3), (2, 3), (3, 2)] {
        for gap in [0.0f32, 0.5] {
            let a = (0..na)
                .map(|i| Aabb::new(Vec3::X * (2 * i) as f32, Vec3::X * (2 * i) as f32 + 1.0))
                .collect();
            let b = (0..nb)
                .map(|i| {
                    let lo = Vec3::new(1.0 + gap, 0.0, 0.0) + Vec3::Y * (2 * i) as f32;
                    Aabb::new(lo, lo + 1.0)
                })
                .collect();
            cases.push((Tree::new(a, 1), Tree::new(b, 1)));
        }
    }
    cases
}

fn run_dfs(e: &dyn Exercises, a: &Tree, b: &Tree) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    e.informed_dfs(&a.bvh(), &a.prims, &b.bvh(), &b.prims, &mut out);
    out
}

fn run_stack(e: &dyn Exercises, a: &Tree, b: &Tree, size: usize) -> (bool, Vec<(u32, u32)>) {
    let mut out = Vec::new();
    let mut stack = vec![(0u32, 0u32); size];
    let ok = e.stack_dfs(&a.bvh(), &a.prims, &b.bvh(), &b.prims, &mut stack, &mut out);
    (ok, out)
}

fn sorted(mut v: Vec<(u32, u32)>) -> Vec<(u32, u32)> {
    v.sort_unstable();
    v
}

fn node(min: [f32; 3], max: [f32; 3], leaf: bool) -> Node<Aabb> {
    Node {
        bv: b(min, max),
        first: 0,
        count: leaf as u32,
    }
}

fn median_ok(e: &dyn Exercises, stretch: Vec3, seed: u64) -> bool {
    let mut r = Rng(seed);
    let c: Vec<Vec3> = r
        .cloud(77, 1.0, Vec3::ZERO)
        .iter()
        .map(|p| *p * stretch)
        .collect();
    let axis = Aabb::fit(c.as_slice()).longest_axis();
    let mut idx: Vec<u32> = (0..77).collect();
    let mid = e.median_partition(&c, &mut idx);
    if mid != 38 {
        return false;
    }
    let left = idx[..mid]
        .iter()
        .map(|&i| c[i as usize][axis])
        .fold(f32::NEG_INFINITY, f32::max);
    let right = idx[mid..]
        .iter()
        .map(|&i| c[i as usize][axis])
        .fold(f32::INFINITY, f32::min);
    left <= right
}

/// How long one check may run before it scores 0 (a loop that never ends
/// costs only that check's points; the reference answers need well under a
/// second per check even unoptimised).
pub const CHECK_TIME_LIMIT: Duration = Duration::from_secs(10);

/// Runs every check on `e`; a check that fails, panics or runs past
/// [`CHECK_TIME_LIMIT`] scores 0, and the others are still graded.
pub fn grade(e: &'static (dyn Exercises + Sync)) -> Vec<ExerciseScore> {
    grade_each(e, CHECK_TIME_LIMIT, |_| {})
}

/// [`grade`] with a time limit per check, calling `done` with each
/// exercise's score as soon as its checks have run (so that a long or stuck
/// exercise does not hide the results before it).
pub fn grade_each(
    e: &'static (dyn Exercises + Sync),
    limit: Duration,
    mut done: impl FnMut(&ExerciseScore),
) -> Vec<ExerciseScore> {
    quiet_checks();
    let mut scores: Vec<ExerciseScore> = EXERCISES
        .iter()
        .map(|&(exercise, title)| ExerciseScore {
            exercise,
            title,
            earned: 0,
            possible: 0,
            failed: vec![],
        })
        .collect();
    let all = checks();
    for (k, c) in all.iter().enumerate() {
        let s = &mut scores[(c.exercise - 1) as usize];
        s.possible += c.points;
        match run_check(c, e, limit) {
            Ok(()) => s.earned += c.points,
            Err(why) => s.failed.push(why),
        }
        if all
            .get(k + 1)
            .is_none_or(|next| next.exercise != c.exercise)
        {
            done(s);
        }
    }
    scores
}

/// Installs, once, a panic hook that records where a check panicked
/// (instead of printing it) on the grader's check threads, and leaves every
/// other thread's panics to the hook that was there before. Installed for
/// good rather than swapped per run, so that runs on several threads (the
/// tests) cannot leave the quiet hook behind.
fn quiet_checks() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            let is_check = std::thread::current()
                .name()
                .is_some_and(|n| n.starts_with(CHECK_THREAD));
            if is_check {
                let at = info.location().map(|l| (l.file().to_string(), l.line()));
                PANIC_AT.with(|p| *p.borrow_mut() = at);
            } else {
                previous(info);
            }
        }));
    });
}

/// The name prefix of the threads checks run on.
const CHECK_THREAD: &str = "grader check ";

thread_local! {
    /// Where the last panic on this thread happened (file, line).
    static PANIC_AT: std::cell::RefCell<Option<(String, u32)>> = const { std::cell::RefCell::new(None) };
}

/// Runs one check on its own thread, so that one that never returns can be
/// abandoned after `limit`. `Err` says why it scored 0.
fn run_check(c: &Check, e: &'static (dyn Exercises + Sync), limit: Duration) -> Result<(), String> {
    let (tx, rx) = mpsc::channel();
    let run = c.run;
    let spawned = std::thread::Builder::new()
        .name(format!("{CHECK_THREAD}{} {}", c.exercise, c.name))
        .spawn(move || {
            let out = panic::catch_unwind(AssertUnwindSafe(|| run(e)));
            let out = out.map_err(|p| {
                let msg = p
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default();
                (msg, PANIC_AT.with(|at| at.borrow_mut().take()))
            });
            // The receiver is gone if the check ran past its limit.
            let _ = tx.send(out);
        });
    if let Err(err) = spawned {
        return Err(format!("{} (could not start: {err})", c.name));
    }
    match rx.recv_timeout(limit) {
        Ok(Ok(true)) => Ok(()),
        Ok(Ok(false)) => Err(c.name.to_string()),
        Ok(Err((msg, at))) => Err(format!("{} (panicked{}: {msg})", c.name, where_(at))),
        Err(_) => Err(format!(
            "{} (did not finish within {} s: a loop that never ends?)",
            c.name,
            limit.as_secs_f64()
        )),
    }
}

/// " in `method` at student.rs:LINE" when the panic happened in a student's
/// answer (the method found from the source), else " at FILE:LINE".
fn where_(at: Option<(String, u32)>) -> String {
    let Some((file, line)) = at else {
        return String::new();
    };
    if file.ends_with("student.rs") {
        if let Some(method) = enclosing_fn(include_str!("student.rs"), line) {
            return format!(" in your `{method}` at student.rs:{line}");
        }
    }
    format!(" at {file}:{line}")
}

/// The name of the last `fn` declared at or before `line` (1-based) of `source`.
fn enclosing_fn(source: &str, line: u32) -> Option<&str> {
    source
        .lines()
        .take(line as usize)
        .filter_map(|l| {
            let rest = l.trim_start().strip_prefix("fn ")?;
            rest.split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .next()
        })
        .last()
}

/// The header line of the table [`report`] prints.
pub fn report_header() -> String {
    format!("{:<4} {:<44} {:>8}\n", "#", "exercise", "points")
}

/// One exercise's lines of the table: its score, then each failed check.
pub fn report_exercise(x: &ExerciseScore) -> String {
    let mut s = format!(
        "{:<4} {:<44} {:>8}\n",
        x.exercise,
        x.title,
        format!("{}/{}", x.earned, x.possible)
    );
    for f in &x.failed {
        s += &format!("       - failed: {f}\n");
    }
    s
}

/// The last line of the table: `total: E/P points (X%)`.
pub fn report_total(scores: &[ExerciseScore]) -> String {
    let (e, p): (u32, u32) = scores
        .iter()
        .fold((0, 0), |(e, p), x| (e + x.earned, p + x.possible));
    format!(
        "total: {e}/{p} points ({}%)\n",
        (e * 100).checked_div(p).unwrap_or(0)
    )
}

/// The table the `grade` command prints; the last line is `total: E/P points (X%)`.
pub fn report(scores: &[ExerciseScore]) -> String {
    let mut s = report_header();
    for x in scores {
        s += &report_exercise(x);
    }
    s + &report_total(scores)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::Reference;
    use crate::student::Student;

    fn earned(e: &'static (dyn Exercises + Sync), exercise: u32) -> (u32, u32) {
        let s = &grade(e)[(exercise - 1) as usize];
        (s.earned, s.possible)
    }

    #[test]
    fn reference_scores_everything() {
        for s in grade(&Reference) {
            assert_eq!(s.earned, s.possible, "{s:?}");
        }
        assert!(report(&grade(&Reference)).ends_with("total: 330/330 points (100%)\n"));
    }

    /// Plausible wrong answers, each delegating everything else to the reference.
    struct Wrong(u32);
    /// The wrong answer whose exercise 8 never returns.
    const LOOPS: u32 = 1000;
    /// The wrong answer whose exercise 11 (`implicit_len`) panics.
    const PANICS: u32 = 1001;

    /// A never-returning answer scores 0 on its own checks only, after the
    /// time limit, and every other exercise is graded (and reported as it
    /// is done) as if nothing happened.
    #[test]
    fn a_looping_answer_costs_only_its_own_checks() {
        let e: &'static Wrong = Box::leak(Box::new(Wrong(LOOPS)));
        let mut reported = Vec::new();
        let start = std::time::Instant::now();
        let scores = grade_each(e, Duration::from_secs(2), |x| reported.push(x.exercise));
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "{:?}",
            start.elapsed()
        );
        assert_eq!(reported, (1..=EXERCISES.len() as u32).collect::<Vec<_>>());
        for s in &scores {
            if s.exercise == 8 {
                assert_eq!(s.earned, 0, "{s:?}");
                assert!(
                    s.failed
                        .iter()
                        .all(|f| f.contains("did not finish within 2 s")),
                    "{s:?}"
                );
            } else {
                assert_eq!(s.earned, s.possible, "{s:?}");
            }
        }
    }

    /// A panic in an answer names where it happened and its message; the
    /// other checks are graded.
    #[test]
    fn a_panicking_answer_is_named_with_its_message() {
        let e: &'static Wrong = Box::leak(Box::new(Wrong(PANICS)));
        let s = &grade(e)[10];
        assert!(s.exercise == 11 && s.earned < s.possible, "{s:?}");
        assert!(
            s.failed.iter().any(|f| f.contains("panicked at ")
                && f.contains("grader.rs:")
                && f.ends_with(": a slip)")),
            "{s:?}"
        );
        assert_eq!(grade(e)[0].earned, grade(e)[0].possible);
    }

    /// The method around a line of the student's file is found from its source.
    #[test]
    fn a_panic_in_the_students_file_names_the_method() {
        let src = "impl X {\n    fn first(&self) {\n        a();\n    }\n    fn second_one(&self) -> u32 {\n        b()\n    }\n}\n";
        assert_eq!(enclosing_fn(src, 3), Some("first"));
        assert_eq!(enclosing_fn(src, 6), Some("second_one"));
        assert_eq!(enclosing_fn(src, 1), None);
        assert_eq!(where_(None), "");
        assert_eq!(
            where_(Some(("core/src/x.rs".into(), 7))),
            " at core/src/x.rs:7"
        );
        let student = include_str!("student.rs");
        let line = student
            .lines()
            .position(|l| l.contains("fn descend_a"))
            .unwrap() as u32
            + 2;
        assert_eq!(
            where_(Some(("exercises/src/student.rs".into(), line))),
            format!(" in your `descend_a` at student.rs:{line}")
        );
    }
    impl Exercises for Wrong {
        fn aabb_overlaps(&self, a: &Aabb, b: &Aabb) -> bool {
            match self.0 {
                1 => (0..3).all(|k| a.min[k] < b.max[k] && b.min[k] < a.max[k]), // strict
                2 => (0..3).any(|k| a.min[k] <= b.max[k] && b.min[k] <= a.max[k]), // any axis
                _ => Reference.aabb_overlaps(a, b),
            }
        }
        fn aabb_fit(&self, points: &[Vec3]) -> Aabb {
            match self.0 {
                3 => points
                    .iter()
                    .fold(Aabb::new(Vec3::ZERO, Vec3::ZERO), |b, p| {
                        Aabb::new(b.min.min(*p), b.max.max(*p))
                    }),
                _ => Reference.aabb_fit(points),
            }
        }
        fn aabb_merge(&self, a: &Aabb, b: &Aabb) -> Aabb {
            Reference.aabb_merge(a, b)
        }
        fn sphere_fit(&self, points: &[Vec3]) -> Sphere {
            match self.0 {
                // Ritter without any rounding care: f32 arithmetic throughout.
                4 => {
                    let mut c = points[0];
                    let mut r = 0.0f32;
                    for &p in points {
                        let d = (p - c).length();
                        if d > r {
                            let nr = (r + d) * 0.5;
                            c += (p - c) * ((nr - r) / d);
                            r = nr;
                        }
                    }
                    Sphere::new(c, r)
                }
                // The box's circumsphere: always contains, often too large.
                5 => BoundingVolume::from_aabb(&Aabb::fit(points)),
                _ => Reference.sphere_fit(points),
            }
        }
        fn sphere_merge(&self, a: &Sphere, b: &Sphere) -> Sphere {
            match self.0 {
                6 => Sphere::new(
                    (a.center + b.center) * 0.5,
                    a.center.distance(b.center) * 0.5 + a.radius.max(b.radius),
                ),
                _ => Reference.sphere_merge(a, b),
            }
        }
        fn median_partition(&self, centroids: &[Vec3], indices: &mut [u32]) -> usize {
            match self.0 {
                7 => {
                    let mid = indices.len() / 2;
                    indices.sort_unstable_by(|&a, &b| {
                        centroids[a as usize].x.total_cmp(&centroids[b as usize].x)
                    });
                    mid
                }
                8 => indices.len() / 2, // no reordering at all
                _ => Reference.median_partition(centroids, indices),
            }
        }
        fn descend_a(&self, a: &Node<Aabb>, b: &Node<Aabb>) -> bool {
            match self.0 {
                9 => a.bv.volume() >= b.bv.volume(), // forgets the leaves
                10 => b.is_leaf() || (!a.is_leaf() && a.bv.extent().x >= b.bv.extent().x),
                _ => Reference.descend_a(a, b),
            }
        }
        fn informed_dfs(
            &self,
            a: &Bvh<Aabb>,
            pa: &[Aabb],
            b: &Bvh<Aabb>,
            pb: &[Aabb],
            out: &mut Vec<(u32, u32)>,
        ) {
            match self.0 {
                // Tests the leaves' volumes but not the primitives inside.
                11 => {
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
                _ => Reference.informed_dfs(a, pa, b, pb, out),
            }
        }
        fn stack_dfs(
            &self,
            a: &Bvh<Aabb>,
            pa: &[Aabb],
            b: &Bvh<Aabb>,
            pb: &[Aabb],
            stack: &mut [(u32, u32)],
            out: &mut Vec<(u32, u32)>,
        ) -> bool {
            match self.0 {
                // Indexes the stack without a bound check.
                12 => {
                    let _ = stack[stack.len().max(64)];
                    Reference.stack_dfs(a, pa, b, pb, stack, out)
                }
                _ => Reference.stack_dfs(a, pa, b, pb, stack, out),
            }
        }
        fn predicted_cost(&self, counts: &Counts, model: &CostModel) -> f64 {
            match self.0 {
                13 => Reference.predicted_cost(counts, model) - model.co, // forgets Co
                _ => Reference.predicted_cost(counts, model),
            }
        }
        fn bottom_up_merges(&self, boxes: &[Aabb]) -> Vec<(u32, u32)> {
            let n = boxes.len() as u32;
            if self.0 == LOOPS {
                // Never removes the merged clusters: never returns (asleep,
                // so the abandoned thread costs no CPU).
                loop {
                    std::thread::sleep(Duration::from_secs(3600));
                }
            }
            match self.0 {
                // Merges in index order: a chain, not greedy.
                14 => (1..n)
                    .map(|i| (if i == 1 { 0 } else { n + i - 2 }, i))
                    .collect(),
                // Greedy, but by the sum of the two volumes, not the merged volume.
                15 => {
                    let mut live: Vec<(u32, Aabb)> = boxes
                        .iter()
                        .enumerate()
                        .map(|(i, b)| (i as u32, *b))
                        .collect();
                    let mut out = Vec::new();
                    while live.len() > 1 {
                        let mut best = (f32::INFINITY, 0, 1);
                        for i in 0..live.len() {
                            for j in i + 1..live.len() {
                                let v = live[i].1.volume() + live[j].1.volume();
                                if v < best.0 {
                                    best = (v, i, j);
                                }
                            }
                        }
                        let (_, i, j) = best;
                        out.push((live[i].0, live[j].0));
                        live[i] = (n + out.len() as u32 - 1, live[i].1.union(&live[j].1));
                        live.swap_remove(j);
                    }
                    out
                }
                _ => Reference.bottom_up_merges(boxes),
            }
        }
        fn refit(&self, nodes: &mut [Node<Aabb>], indices: &[u32], prims: &[Aabb]) {
            let leaf = |n: &Node<Aabb>| {
                indices[n.first as usize..(n.first + n.count) as usize]
                    .iter()
                    .fold(Aabb::EMPTY, |b, &p| b.union(&prims[p as usize]))
            };
            match self.0 {
                // Only the leaves: parents keep their old boxes.
                16 => {
                    for n in nodes.iter_mut().filter(|n| n.is_leaf()) {
                        n.bv = leaf(n);
                    }
                }
                // Front to back: parents are merged from stale children.
                17 => {
                    for i in 0..nodes.len() {
                        nodes[i].bv = match nodes[i].children() {
                            Some((l, r)) => nodes[l as usize].bv.union(&nodes[r as usize].bv),
                            None => leaf(&nodes[i]),
                        };
                    }
                }
                _ => Reference.refit(nodes, indices, prims),
            }
        }
        fn insertion_cost(&self, sibling: &Aabb, ancestors: &[Aabb], new: &Aabb) -> f64 {
            let area = |b: &Aabb| b.surface_area() as f64;
            match self.0 {
                18 => area(&sibling.union(new)), // forgets the ancestors
                19 => {
                    area(&sibling.union(new))
                        + ancestors.iter().map(|a| area(&a.union(new))).sum::<f64>()
                }
                _ => Reference.insertion_cost(sibling, ancestors, new),
            }
        }
        fn implicit_children(&self, i: usize) -> (usize, usize) {
            match self.0 {
                20 => (2 * i, 2 * i + 1), // the one-based formula on a zero-based array
                _ => Reference.implicit_children(i),
            }
        }
        fn implicit_parent(&self, i: usize) -> Option<usize> {
            match self.0 {
                21 => (i > 0).then_some(i / 2),
                _ => Reference.implicit_parent(i),
            }
        }
        fn implicit_len(&self, depth: u32) -> usize {
            match self.0 {
                PANICS => panic!("a slip"),
                22 => 1 << depth, // only the last level
                _ => Reference.implicit_len(depth),
            }
        }
        fn to_preorder(&self, tree: &Bvh<Aabb>) -> Vec<(Aabb, Option<u32>)> {
            let nodes = tree.nodes();
            match self.0 {
                // The canonical array's order and its right-child index, unchanged.
                23 => nodes
                    .iter()
                    .map(|n| (n.bv, n.children().map(|(_, r)| r)))
                    .collect(),
                // Starts from the root without asking whether there is one.
                36 => {
                    let root = nodes[0];
                    let mut out = vec![(root.bv, None)];
                    out.extend(Reference.to_preorder(tree).into_iter().skip(1));
                    out
                }
                // Preorder, but the link points at the left child (the next entry).
                24 => Reference
                    .to_preorder(tree)
                    .iter()
                    .enumerate()
                    .map(|(i, x)| (x.0, x.1.map(|_| i as u32 + 1)))
                    .collect(),
                _ => Reference.to_preorder(tree),
            }
        }
        fn quantize(&self, parent: &Aabb, child: &Aabb) -> ([u8; 3], [u8; 3]) {
            let grid =
                |k: usize, x: f32| (x - parent.min[k]) / ((parent.max[k] - parent.min[k]) / 255.0);
            match self.0 {
                // Round to the nearest grid line: can cut into the child.
                25 => {
                    let (mut lo, mut hi) = ([0u8; 3], [0u8; 3]);
                    for k in 0..3 {
                        lo[k] = grid(k, child.min[k]).round().clamp(0.0, 255.0) as u8;
                        hi[k] = grid(k, child.max[k]).round().clamp(0.0, 255.0) as u8;
                    }
                    (lo, hi)
                }
                // floor / ceil in f32, never checked against the decoder.
                26 => {
                    let (mut lo, mut hi) = ([0u8; 3], [0u8; 3]);
                    for k in 0..3 {
                        let (a, b) = (grid(k, child.min[k]), grid(k, child.max[k]));
                        lo[k] = if a.is_finite() {
                            a.floor().clamp(0.0, 255.0) as u8
                        } else {
                            0
                        };
                        hi[k] = if b.is_finite() {
                            b.ceil().clamp(0.0, 255.0) as u8
                        } else {
                            255
                        };
                    }
                    (lo, hi)
                }
                // Always the whole parent: safe, but useless.
                27 => ([0; 3], [255; 3]),
                _ => Reference.quantize(parent, child),
            }
        }

        fn top_down_bytes(&self, n: usize, node_bytes: usize) -> usize {
            match self.0 {
                // Forgets the index array.
                28 => bvhkit::max_nodes(n) * node_bytes,
                // One node per primitive plus one, as for a list.
                29 => (n + 1) * node_bytes + 4 * n,
                _ => Reference.top_down_bytes(n, node_bytes),
            }
        }

        fn pair_stack_bound(&self, depth_a: usize, depth_b: usize) -> usize {
            match self.0 {
                // Counts one waiting pair per step, as if only one side opened.
                30 => depth_a + depth_b + 1,
                // The larger depth three times: enough, but not the bound.
                31 => 3 * depth_a.max(depth_b) + 1,
                _ => Reference.pair_stack_bound(depth_a, depth_b),
            }
        }

        fn workload_ms(&self, build: f64, query: f64, rebuild: bool, frames: usize) -> f64 {
            let n = frames as f64;
            match self.0 {
                // Ignores the motion: always builds once.
                32 => build + n * query,
                // Rebuilds every frame and once more before the first.
                33 if rebuild => (n + 1.0) * build + n * query,
                _ => Reference.workload_ms(build, query, rebuild, frames),
            }
        }

        fn pareto_front(&self, points: &[(f64, f64)]) -> Vec<usize> {
            let dominated = |i: usize, strict: bool| {
                let (t, x) = points[i];
                points.iter().enumerate().any(|(j, &(u, y))| {
                    j != i
                        && if strict {
                            u < t && y < x
                        } else {
                            u <= t && y <= x && (u < t || y < x)
                        }
                })
            };
            match self.0 {
                // Dominance only when better on both: keeps points that tie on one.
                34 => (0..points.len()).filter(|&i| !dominated(i, true)).collect(),
                // Keeps only the first of equal points.
                35 => (0..points.len())
                    .filter(|&i| !dominated(i, false) && !points[..i].contains(&points[i]))
                    .collect(),
                _ => Reference.pareto_front(points),
            }
        }

        fn sah_best_boundary(&self, bins: &[(Aabb, u32)]) -> Option<usize> {
            let count = |s: &[(Aabb, u32)]| s.iter().map(|b| b.1).sum::<u32>();
            let union = |s: &[(Aabb, u32)]| s.iter().fold(Aabb::EMPTY, |a, b| a.union(&b.0));
            let pick = |cost: &dyn Fn(usize) -> Option<f32>, ties_last: bool| {
                let mut best: Option<(f32, usize)> = None;
                for b in 1..bins.len() {
                    if let Some(c) = cost(b) {
                        if best.is_none_or(|(x, _)| c < x || (ties_last && c == x)) {
                            best = Some((c, b));
                        }
                    }
                }
                best.map(|(_, b)| b)
            };
            let both = |b: usize| count(&bins[..b]) > 0 && count(&bins[b..]) > 0;
            let sah = |b: usize| {
                let (l, r) = (&bins[..b], &bins[b..]);
                union(l).surface_area() * count(l) as f32
                    + union(r).surface_area() * count(r) as f32
            };
            match self.0 {
                // Balances the counts instead of the cost.
                37 => pick(
                    &|b| {
                        both(b).then(|| (count(&bins[..b]) as f32 - count(&bins[b..]) as f32).abs())
                    },
                    false,
                ),
                // An empty side costs nothing instead of being refused.
                38 => pick(
                    &|b| {
                        let side = |s: &[(Aabb, u32)]| match count(s) {
                            0 => 0.0,
                            n => union(s).surface_area() * n as f32,
                        };
                        Some(side(&bins[..b]) + side(&bins[b..]))
                    },
                    false,
                ),
                // Adds up the bins' areas instead of taking the union's.
                39 => pick(
                    &|b| {
                        both(b).then(|| {
                            let area = |s: &[(Aabb, u32)]| {
                                s.iter()
                                    .filter(|x| x.1 > 0)
                                    .map(|x| x.0.surface_area())
                                    .sum::<f32>()
                            };
                            area(&bins[..b]) * count(&bins[..b]) as f32
                                + area(&bins[b..]) * count(&bins[b..]) as f32
                        })
                    },
                    false,
                ),
                // The last of equal costs.
                40 => pick(&|b| both(b).then(|| sah(b)), true),
                _ => Reference.sah_best_boundary(bins),
            }
        }

        fn dop14_fit(&self, points: &[Vec3]) -> Dop14 {
            match self.0 {
                // The box's corners as the points: loose on the diagonals.
                41 => Dop14::from_aabb(&Aabb::fit(points)),
                // Projections in f32, rounded to nearest.
                42 => {
                    let mut k = Dop14::EMPTY;
                    for p in points {
                        for i in 0..7 {
                            let d = Dop14::direction(i);
                            let t = d[0] as f32 * p.x + d[1] as f32 * p.y + d[2] as f32 * p.z;
                            k.min[i] = k.min[i].min(t);
                            k.max[i] = k.max[i].max(t);
                        }
                    }
                    k
                }
                _ => Reference.dop14_fit(points),
            }
        }

        fn dop14_overlaps(&self, a: &Dop14, b: &Dop14) -> bool {
            match self.0 {
                // Touching is not overlapping.
                43 => (0..7).all(|i| a.min[i] < b.max[i] && b.min[i] < a.max[i]),
                // The box test: the three axes only.
                44 => (0..3).all(|i| a.min[i] <= b.max[i] && b.min[i] <= a.max[i]),
                _ => Reference.dop14_overlaps(a, b),
            }
        }

        fn descent_open(&self, rule: Descent, d: &Decision<'_, Aabb>) -> Open {
            let larger = || {
                if d.a.volume() >= d.b.volume() {
                    Open::A
                } else {
                    Open::B
                }
            };
            match (self.0, rule) {
                // Odd depths open A.
                (45, Descent::Alternate) => {
                    if d.depth % 2 == 1 {
                        Open::A
                    } else {
                        Open::B
                    }
                }
                // Opens the side whose children stay *most* inside.
                (46, Descent::Overlap) => match Reference.descent_open(rule, d) {
                    Open::A => Open::B,
                    _ => Open::A,
                },
                // Simultaneous opens one side only.
                (47, Descent::Simultaneous) => Open::A,
                // By overlap falls back to the larger volume.
                (48, Descent::Overlap) => larger(),
                _ => Reference.descent_open(rule, d),
            }
        }

        fn partition_cost(&self, c: Partition, l: &Aabb, nl: u32, r: &Aabb, nr: u32) -> f64 {
            let ext = |b: &Aabb| (b.max - b.min).as_dvec3();
            match (self.0, c) {
                // Areas without the counts.
                (49, Partition::SurfaceArea) => {
                    let a = |b: &Aabb| {
                        let e = ext(b);
                        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
                    };
                    a(l) + a(r)
                }
                // Intersection extents not clamped.
                (50, Partition::Overlap) => {
                    let s = (l.max.min(r.max) - l.min.max(r.min)).as_dvec3();
                    if s.x < 0.0 && s.y < 0.0 && s.z < 0.0 {
                        0.0
                    } else {
                        s.element_product()
                    }
                }
                // The smallest gap over the axes.
                (51, Partition::Separation) => {
                    -((l.min - r.max).max(r.min - l.max).min_element() as f64)
                }
                // The sum, not the larger.
                (52, Partition::LargerChild) => ext(l).element_product() + ext(r).element_product(),
                _ => Reference.partition_cost(c, l, nl, r, nr),
            }
        }

        fn visit_order(&self, tree: &Bvh<Aabb>, breadth_first: bool) -> Vec<u32> {
            let nodes = tree.nodes();
            match self.0 {
                // Depth-first with the left child pushed first: right before left.
                53 if !breadth_first => {
                    let (mut order, mut stack) = (vec![], vec![]);
                    if !nodes.is_empty() {
                        stack.push(0u32);
                    }
                    while let Some(i) = stack.pop() {
                        order.push(i);
                        if let Some((l, r)) = nodes[i as usize].children() {
                            stack.extend([l, r]);
                        }
                    }
                    order
                }
                // Breadth-first with a stack: depth-first, right first.
                54 if breadth_first => Wrong(53).visit_order(tree, false),
                _ => Reference.visit_order(tree, breadth_first),
            }
        }

        fn obb_overlaps(&self, a: &Obb, b: &Obb) -> bool {
            let apart = |l: Vec3, strict: bool| {
                let radius = |x: &Obb| {
                    (0..3)
                        .map(|k| x.half_extents[k] * x.axes[k].dot(l).abs())
                        .sum::<f32>()
                };
                let d = (b.center - a.center).dot(l).abs();
                let r = radius(a) + radius(b);
                if strict {
                    d >= r
                } else {
                    d > r
                }
            };
            let faces = || a.axes.iter().chain(&b.axes).any(|&l| apart(l, false));
            match self.0 {
                // Face axes only: misses boxes that pass edge to edge.
                55 => !faces(),
                // Touching counts as apart.
                56 => {
                    !a.axes.iter().chain(&b.axes).any(|&l| apart(l, true))
                        && Reference.obb_overlaps(a, b)
                }
                _ => Reference.obb_overlaps(a, b),
            }
        }

        fn best_first_nearest(
            &self,
            tree: &Bvh<Aabb>,
            prims: &[Aabb],
            p: Vec3,
        ) -> Option<(u32, f32, usize)> {
            match self.0 {
                // Depth-first over every node: the right answer, all the work.
                57 => {
                    let best = Reference.best_first_nearest(tree, prims, p)?;
                    Some((best.0, best.1, tree.nodes().len()))
                }
                // Greedy: into the nearer child down to one leaf, whose
                // primitive is near but not always the nearest.
                58 => {
                    let nodes = tree.nodes();
                    let dist = |b: &Aabb| b.distance_squared(p).sqrt();
                    let mut i = 0usize;
                    let mut taken = 0;
                    loop {
                        taken += 1;
                        let node = nodes.get(i)?;
                        match node.children() {
                            Some((l, r)) => {
                                let (dl, dr) =
                                    (dist(&nodes[l as usize].bv), dist(&nodes[r as usize].bv));
                                i = if dl <= dr { l } else { r } as usize;
                            }
                            None => {
                                let k = tree.indices()[node.first as usize];
                                return Some((k, dist(&prims[k as usize]), taken));
                            }
                        }
                    }
                }
                _ => Reference.best_first_nearest(tree, prims, p),
            }
        }

        fn leaf_order_bounds(&self, tree: &Bvh<Aabb>, prims: &[Triangle]) -> Vec<Aabb> {
            match self.0 {
                // In the primitives' own order, not the leaves'.
                59 => prims.iter().map(bvhkit::Primitive::bounds).collect(),
                // Each entry gets its leaf's box: contains the primitive,
                // but is not its bounds.
                60 => {
                    let mut out = vec![Aabb::EMPTY; tree.indices().len()];
                    for n in tree.nodes().iter().filter(|n| n.is_leaf()) {
                        for k in n.first..n.first + n.count {
                            out[k as usize] = n.bv;
                        }
                    }
                    out
                }
                _ => Reference.leaf_order_bounds(tree, prims),
            }
        }

        fn leaf_pair_candidates(
            &self,
            a: (&[u32], &[Aabb]),
            b: (&[u32], &[Aabb]),
        ) -> Vec<(u32, u32)> {
            match self.0 {
                // Positions in the leaves instead of the primitives' ids.
                61 => {
                    let mut out = Vec::new();
                    for (p, x) in a.1.iter().enumerate() {
                        for (q, y) in b.1.iter().enumerate() {
                            if x.overlaps(y) {
                                out.push((p as u32, q as u32));
                            }
                        }
                    }
                    out
                }
                // Touching boxes left out.
                62 => {
                    let strict =
                        |x: &Aabb, y: &Aabb| x.min.cmplt(y.max).all() && y.min.cmplt(x.max).all();
                    let mut out = Vec::new();
                    for (&p, x) in a.0.iter().zip(a.1) {
                        for (&q, y) in b.0.iter().zip(b.1) {
                            if strict(x, y) {
                                out.push((p, q));
                            }
                        }
                    }
                    out
                }
                _ => Reference.leaf_pair_candidates(a, b),
            }
        }

        fn node_step(&self, n: u32, depth: u32, stop: &Stop, left: u32, w: bool) -> NodeStep {
            let k = stop.max_leaf_size;
            let levels_left = stop.max_depth.saturating_sub(depth);
            let budget = |needed: u32| {
                if n <= k || depth >= stop.max_depth {
                    Some(NodeStep::Leaf)
                } else if levels_left <= needed {
                    Some(NodeStep::Halve)
                } else {
                    None
                }
            };
            let ceil_log2 = |x: u32| u32::BITS - (x.max(1) - 1).leading_zeros();
            let rest = |slivers: &dyn Fn(u32) -> bool| {
                let smaller = left.min(n - left.min(n));
                if smaller == 0 || slivers(smaller) {
                    NodeStep::FallBack
                } else {
                    NodeStep::Split
                }
            };
            let normal = |smaller: u32| !w && n >= 100 && smaller * 100 < n;
            match self.0 {
                // floor(log2) levels needed instead of ceil.
                63 => budget(u32::BITS - 1 - n.div_ceil(k).leading_zeros())
                    .unwrap_or_else(|| rest(&normal)),
                // The leaf count rounded down.
                64 => budget(ceil_log2(n / k)).unwrap_or_else(|| rest(&normal)),
                // Forgets that the depth limit stops the build: the budget
                // halves a node at the limit.
                65 => {
                    if n <= k {
                        NodeStep::Leaf
                    } else if levels_left <= ceil_log2(n.div_ceil(k)) {
                        NodeStep::Halve
                    } else {
                        rest(&normal)
                    }
                }
                // The sliver rule for every criterion, the SAH included.
                66 => budget(ceil_log2(n.div_ceil(k)))
                    .unwrap_or_else(|| rest(&|smaller| n >= 100 && smaller * 100 < n)),
                // "At most 1%" instead of "under 1%".
                67 => budget(ceil_log2(n.div_ceil(k)))
                    .unwrap_or_else(|| rest(&|smaller| !w && n >= 100 && smaller * 100 <= n)),
                _ => Reference.node_step(n, depth, stop, left, w),
            }
        }

        fn fit_unit_costs(&self, samples: &[(u64, u64, f64)]) -> (f64, f64) {
            // The 2x2 normal equations with weights w per sample.
            let solve = |weight: &dyn Fn(f64) -> f64| {
                let (mut xx, mut xy, mut yy, mut xt, mut yt) = (0.0, 0.0, 0.0, 0.0, 0.0);
                for &(nv, np, t) in samples.iter().filter(|s| s.2 > 0.0) {
                    let w = weight(t);
                    let (x, y) = (nv as f64 * w, np as f64 * w);
                    (xx, xy, yy) = (xx + x * x, xy + x * y, yy + y * y);
                    (xt, yt) = (xt + x * t * w, yt + y * t * w);
                }
                let det = xx * yy - xy * xy;
                if det.abs() <= 1e-12 * xx * yy {
                    return (0.0, 0.0, xx, yy, xt, yt);
                }
                (
                    (xt * yy - yt * xy) / det,
                    (xx * yt - xy * xt) / det,
                    xx,
                    yy,
                    xt,
                    yt,
                )
            };
            match self.0 {
                // Absolute error: the large queries decide.
                68 => {
                    let (cv, cp, ..) = solve(&|_| 1.0);
                    (cv.max(0.0), cp.max(0.0))
                }
                // The unconstrained answer, negative cost and all.
                69 => {
                    let (cv, cp, ..) = solve(&|t| 1.0 / t);
                    (cv, cp)
                }
                // Clamps a negative cost to 0 without refitting the other.
                70 => {
                    let (cv, cp, ..) = solve(&|t| 1.0 / t);
                    (cv.max(0.0), cp.max(0.0))
                }
                _ => Reference.fit_unit_costs(samples),
            }
        }

        fn split_plane(
            &self,
            centroids: &[Vec3],
            axis: crate::AxisRule,
            point: crate::PointRule,
        ) -> Option<(usize, f32)> {
            use crate::{AxisRule, PointRule};
            let right = Reference.split_plane(centroids, axis, point)?;
            let k = right.0;
            let xs = || centroids.iter().map(move |c| c[k]);
            let extent = |k: usize| {
                let (lo, hi) = centroids
                    .iter()
                    .fold((f32::INFINITY, f32::NEG_INFINITY), |(l, h), c| {
                        (l.min(c[k]), h.max(c[k]))
                    });
                hi - lo
            };
            match self.0 {
                // Ties to the higher axis.
                71 if axis == AxisRule::Longest => {
                    let mut best = 0;
                    for j in 1..3 {
                        if extent(j) >= extent(best) {
                            best = j;
                        }
                    }
                    Reference
                        .split_plane(centroids, AxisRule::Longest, point)
                        .map(|(_, _)| {
                            let moved: Vec<Vec3> =
                                centroids.iter().map(|c| Vec3::splat(c[best])).collect();
                            (
                                best,
                                Reference
                                    .split_plane(&moved, AxisRule::Longest, point)
                                    .map_or(0.0, |p| p.1),
                            )
                        })
                }
                // The extent stands in for the variance.
                72 if axis == AxisRule::Variance => {
                    Reference.split_plane(centroids, AxisRule::Longest, point)
                }
                // The lower middle.
                73 if point == PointRule::ObjectMedian => {
                    let mut v: Vec<f32> = xs().collect();
                    v.sort_by(f32::total_cmp);
                    Some((k, v[(v.len() - 1) / 2]))
                }
                // The middle of the extent in f32: overflows near f32::MAX.
                74 if point == PointRule::SpatialMedian => {
                    let (lo, hi) = xs().fold((f32::INFINITY, f32::NEG_INFINITY), |(l, h), x| {
                        (l.min(x), h.max(x))
                    });
                    Some((k, (lo + hi) / 2.0))
                }
                // The mean taken as the middle of the extent.
                75 if point == PointRule::ObjectMean => {
                    Reference.split_plane(centroids, axis, PointRule::SpatialMedian)
                }
                _ => Some(right),
            }
        }

        fn tree_measures(&self, tree: &Bvh<Aabb>) -> crate::TreeMeasures {
            let right = Reference.tree_measures(tree);
            let nodes = tree.nodes();
            if nodes.is_empty() {
                return right;
            }
            let area = |b: &Aabb| {
                let e = b.max.as_dvec3() - b.min.as_dvec3();
                2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
            };
            let root = area(&nodes[0].bv);
            // (depth, node) for every node, the root at 0.
            let mut all = Vec::new();
            let mut stack = vec![(0u32, 0usize)];
            while let Some((i, d)) = stack.pop() {
                all.push((d, &nodes[i as usize]));
                if let Some((l, r)) = nodes[i as usize].children() {
                    stack.extend([(l, d + 1), (r, d + 1)]);
                }
            }
            let leaves = || all.iter().filter(|(_, n)| n.is_leaf());
            match self.0 {
                // The mean weighted by primitives.
                76 => {
                    let prims: f64 = leaves().map(|(_, n)| n.count as f64).sum();
                    let sum: f64 = leaves().map(|(d, n)| *d as f64 * n.count as f64).sum();
                    crate::TreeMeasures {
                        mean_leaf_depth: sum / prims,
                        ..right
                    }
                }
                // Leaves counted once, not times their size.
                77 => crate::TreeMeasures {
                    sah_cost: all.iter().map(|(_, n)| area(&n.bv) / root).sum(),
                    ..right
                },
                // Internal nodes left out.
                78 => crate::TreeMeasures {
                    sah_cost: leaves()
                        .map(|(_, n)| area(&n.bv) / root * n.count as f64)
                        .sum(),
                    ..right
                },
                // The root at depth 1.
                79 => crate::TreeMeasures {
                    max_depth: right.max_depth + 1,
                    mean_leaf_depth: right.mean_leaf_depth + 1.0,
                    ..right
                },
                _ => right,
            }
        }

        fn tri_node_records(&self, tree: &Bvh<Aabb>) -> (usize, usize) {
            let right = Reference.tri_node_records(tree);
            let nodes = tree.nodes();
            let leaves = nodes.iter().filter(|n| n.is_leaf()).count();
            match self.0 {
                // A third of the nodes, as if every record were full.
                80 => (nodes.len().div_ceil(3), right.1),
                // Records at odd depths instead (the root taken as depth 1).
                81 => {
                    let (records, _) = Reference.tri_node_records(tree);
                    (nodes.len() - records, right.1)
                }
                // Two wasted slots for every leaf, at any depth.
                82 => (right.0, 2 * leaves),
                _ => right,
            }
        }

        fn fit_obb(&self, points: &[Vec3], axes: [Vec3; 3]) -> Obb {
            if points.is_empty() {
                return Obb::EMPTY;
            }
            let ax = axes.map(|a| a.as_dvec3());
            let proj = |p: &Vec3| {
                let p = p.as_dvec3();
                bvhkit::glam::DVec3::new(ax[0].dot(p), ax[1].dot(p), ax[2].dot(p))
            };
            let (lo, hi) = points.iter().fold(
                (
                    bvhkit::glam::DVec3::INFINITY,
                    bvhkit::glam::DVec3::NEG_INFINITY,
                ),
                |(l, h), p| (l.min(proj(p)), h.max(proj(p))),
            );
            let mid = (lo + hi) * 0.5;
            let from_mid =
                |m: bvhkit::glam::DVec3| (ax[0] * m.x + ax[1] * m.y + ax[2] * m.z).as_vec3();
            match self.0 {
                // Half the range, rounded to nearest: the rounded centre
                // leaves far points just outside.
                83 => Obb {
                    center: from_mid(mid),
                    axes,
                    half_extents: ((hi - lo) * 0.5).as_vec3(),
                },
                // The points' AABB: right when the axes are x, y, z, loose
                // otherwise.
                84 => {
                    let mut b = Aabb::EMPTY;
                    for p in points {
                        b.grow(*p);
                    }
                    let h = (b.max - b.min) * 0.5;
                    let r = h.x.abs() + h.y.abs() + h.z.abs();
                    Obb {
                        center: b.center(),
                        axes,
                        half_extents: Vec3::splat(r),
                    }
                }
                // Centred on the mean of the points, not the middle of the
                // range: contains them only with extents past the tight ones.
                85 => {
                    let mean = points
                        .iter()
                        .map(|p| p.as_dvec3())
                        .sum::<bvhkit::glam::DVec3>()
                        / points.len() as f64;
                    let c = mean.as_vec3();
                    let mut h = bvhkit::glam::DVec3::ZERO;
                    for p in points {
                        let v = p.as_dvec3() - c.as_dvec3();
                        h = h.max(bvhkit::glam::DVec3::new(
                            ax[0].dot(v).abs(),
                            ax[1].dot(v).abs(),
                            ax[2].dot(v).abs(),
                        ));
                    }
                    Obb {
                        center: c,
                        axes,
                        half_extents: h.as_vec3() * 1.0001,
                    }
                }
                _ => Reference.fit_obb(points, axes),
            }
        }

        fn preorder_offsets(&self, tree: &Bvh<Aabb>) -> (usize, usize) {
            let right = Reference.preorder_offsets(tree);
            let nodes = tree.nodes();
            let mut size = vec![1usize; nodes.len()];
            for i in (0..nodes.len()).rev() {
                if let Some((l, r)) = nodes[i].children() {
                    size[i] = 1 + size[l as usize] + size[r as usize];
                }
            }
            let over = |f: &dyn Fn(usize, usize) -> usize| {
                nodes
                    .iter()
                    .filter_map(|n| n.children())
                    .map(|(l, r)| f(size[l as usize], size[r as usize]))
                    .max()
                    .unwrap_or(0)
            };
            match self.0 {
                // The size of the left subtree, without the parent's step.
                86 => (over(&|l, _| l), right.1),
                // Counts leaves, not nodes, in the left subtree.
                87 => (over(&|l, _| 1 + l.div_ceil(2)), right.1),
                // The larger subtree first instead of the smaller.
                88 => (right.0, over(&|l, r| 1 + l.max(r))),
                _ => right,
            }
        }

        fn collide_objects(
            &self,
            boxes: &[Aabb],
            narrow: &mut dyn FnMut(u32, u32) -> Vec<(u32, u32)>,
        ) -> Vec<((u32, u32), (u32, u32))> {
            let n = boxes.len() as u32;
            let strict = |x: &Aabb, y: &Aabb| x.min.cmplt(y.max).all() && y.min.cmplt(x.max).all();
            let mut out = Vec::new();
            match self.0 {
                // Both orders of every pair.
                89 => {
                    for a in 0..n {
                        for b in 0..n {
                            if a != b && boxes[a as usize].overlaps(&boxes[b as usize]) {
                                out.extend(narrow(a, b).into_iter().map(|p| ((a, b), p)));
                            }
                        }
                    }
                }
                // Touching boxes left out.
                90 => {
                    for a in 0..n {
                        for b in a + 1..n {
                            if strict(&boxes[a as usize], &boxes[b as usize]) {
                                out.extend(narrow(a, b).into_iter().map(|p| ((a, b), p)));
                            }
                        }
                    }
                }
                // The narrow phase on every pair, its answers filtered after.
                91 => {
                    for a in 0..n {
                        for b in a + 1..n {
                            let found = narrow(a, b);
                            if boxes[a as usize].overlaps(&boxes[b as usize]) {
                                out.extend(found.into_iter().map(|p| ((a, b), p)));
                            }
                        }
                    }
                }
                _ => return Reference.collide_objects(boxes, narrow),
            }
            out
        }
    }

    #[test]
    fn plausible_wrong_answers_lose_points() {
        for (wrong, exercise) in [
            (1, 1),
            (2, 1),
            (3, 2),
            (4, 2),
            (5, 2),
            (6, 2),
            (7, 3),
            (8, 3),
            (9, 4),
            (10, 4),
            (11, 5),
            (12, 6),
            (13, 7),
            (14, 8),
            (15, 8),
            (16, 9),
            (17, 9),
            (18, 10),
            (19, 10),
            (20, 11),
            (21, 11),
            (22, 11),
            (23, 12),
            (24, 12),
            (25, 13),
            (26, 13),
            (27, 13),
            (28, 14),
            (29, 14),
            (30, 14),
            (31, 14),
            (32, 15),
            (33, 15),
            (34, 15),
            (35, 15),
            (36, 12),
            (37, 16),
            (38, 16),
            (39, 16),
            (40, 16),
            (41, 17),
            (42, 17),
            (43, 17),
            (44, 17),
            (45, 18),
            (46, 18),
            (47, 18),
            (48, 18),
            (49, 19),
            (50, 19),
            (51, 19),
            (52, 19),
            (53, 20),
            (54, 20),
            (55, 21),
            (56, 21),
            (57, 22),
            (58, 22),
            (59, 23),
            (60, 23),
            (61, 23),
            (62, 23),
            (63, 24),
            (64, 24),
            (65, 24),
            (66, 24),
            (67, 24),
            (68, 25),
            (69, 25),
            (70, 25),
            (71, 26),
            (72, 26),
            (73, 26),
            (74, 26),
            (75, 26),
            (76, 27),
            (77, 27),
            (78, 27),
            (79, 27),
            (80, 28),
            (81, 28),
            (82, 28),
            (83, 29),
            (84, 29),
            (85, 29),
            (86, 30),
            (87, 30),
            (88, 30),
            (89, 31),
            (90, 31),
            (91, 31),
        ] {
            // Leaked: each check runs on a thread that may outlive the call.
            let (e, p) = earned(Box::leak(Box::new(Wrong(wrong))), exercise);
            assert!(
                e < p,
                "wrong answer {wrong} got full marks on exercise {exercise}"
            );
        }
    }

    #[test]
    fn untouched_stubs_score_zero_without_stopping_the_grader() {
        // Meaningful only while the stubs are untouched; students who start
        // filling them in will see this test fail, which is the point.
        if std::env::var_os("BVHKIT_STUDENT").is_some() {
            return;
        }
        let scores = grade(&Student);
        assert_eq!(scores.len(), EXERCISES.len());
        assert!(
            scores.iter().all(|s| s.earned == 0 && s.possible > 0),
            "the exercise stubs in exercises/src/student.rs are no longer untouched. If you \
             are working on the exercises, this is expected: run the tests with \
             BVHKIT_STUDENT=1 to skip this check (see the book's exercises chapter), and \
             `cargo run -p bvhkit-exercises --bin grade` for your score. Scores now: {:?}",
            scores
                .iter()
                .map(|s| (s.exercise, s.earned))
                .collect::<Vec<_>>()
        );
    }
}
