//! Exercise 33: best-first search for a ray's closest hit. The checks, and
//! the plausible wrong answers they must reject.

use super::common::*;
use bvhkit::query::{Ray, RayTarget};

/// The checks of exercise 33.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 33,
            name: "an empty tree and one box: hit, missed, behind the origin",
            points: 2,
            run: |e| {
                let empty = Tree::new(vec![], 1);
                let one = Tree::new(vec![b([0.0; 3], [1.0; 3])], 1);
                let left = Vec3::new(-1.0, 0.5, 0.5);
                closest_is(e, &empty, left, Vec3::X, None)
                    && closest_is(e, &one, left, Vec3::X, Some((0, 1.0)))
                    && closest_is(e, &one, left, -Vec3::X, None)
                    && closest_is(e, &one, Vec3::new(-1.0, 5.0, 0.5), Vec3::X, None)
                    && closest_is(
                        e,
                        &one,
                        Vec3::new(-1.0, 5.0, 0.5),
                        Vec3::new(1.0, -4.0, 0.0),
                        Some((0, 1.0)),
                    )
            },
        },
        Check {
            exercise: 33,
            name: "a ray starting inside a box hits it at t = 0",
            points: 1,
            run: |e| {
                let one = Tree::new(vec![b([0.0; 3], [1.0; 3])], 1);
                let row = row_of(8);
                closest_is(e, &one, Vec3::splat(0.5), Vec3::new(1.0, 2.0, 3.0), Some((0, 0.0)))
                    // Inside box 3, with boxes 4.. ahead of it.
                    && closest_is(e, &row, Vec3::new(6.5, 0.5, 0.5), Vec3::X, Some((3, 0.0)))
            },
        },
        Check {
            exercise: 33,
            name: "rays along the axes (a zero in dir), touching faces and edges, and a long dir",
            points: 2,
            run: |e| {
                let row = row_of(8); // unit cubes at x = 0, 2, .., 14
                closest_is(e, &row, Vec3::new(-1.0, 0.5, 0.5), Vec3::X, Some((0, 1.0)))
                    // t in units of dir: 1 / 2.
                    && closest_is(e, &row, Vec3::new(-1.0, 0.5, 0.5), Vec3::new(2.0, 0.0, 0.0), Some((0, 0.5)))
                    // Along the top faces (y = 1), along an edge (y = z = 1).
                    && closest_is(e, &row, Vec3::new(-1.0, 1.0, 0.5), Vec3::X, Some((0, 1.0)))
                    && closest_is(e, &row, Vec3::new(-1.0, 1.0, 1.0), Vec3::X, Some((0, 1.0)))
                    // Just above the top faces: nothing.
                    && closest_is(e, &row, Vec3::new(-1.0, 1.001, 0.5), Vec3::X, None)
                    // From the far end, backwards; and down the y axis.
                    && closest_is(e, &row, Vec3::new(100.0, 0.5, 0.5), -Vec3::X, Some((7, 85.0)))
                    && closest_is(e, &row, Vec3::new(4.5, -3.0, 1.0), Vec3::Y, Some((2, 3.0)))
                    && closest_is(e, &row, Vec3::new(5.0, 9.0, 0.0), -Vec3::Y, Some((2, 8.0)))
            },
        },
        Check {
            exercise: 33,
            name: "ties: at equal t the smaller index, wherever its leaf is",
            points: 2,
            run: |e| {
                // Two boxes stacked in z, touching at z = 1; the ray runs
                // along the shared face and enters both at t = 2. Both
                // numberings, with decoys, in leaves of one and of four.
                let (low, high) = (
                    b([2.0, 0.0, 0.0], [3.0, 1.0, 1.0]),
                    b([2.0, 0.0, 1.0], [3.0, 1.0, 2.0]),
                );
                let decoys = [
                    b([2.0, 5.0, 0.0], [3.0, 6.0, 2.0]),
                    b([6.0, 0.0, 0.0], [7.0, 1.0, 2.0]),
                ];
                [1, 4].iter().all(|&leaf| {
                    [[low, high], [high, low]].iter().all(|pair| {
                        let mut prims = pair.to_vec();
                        prims.extend(decoys);
                        let t = Tree::new(prims, leaf);
                        closest_is(e, &t, Vec3::new(0.0, 0.5, 1.0), Vec3::X, Some((0, 2.0)))
                    })
                })
            },
        },
        Check {
            exercise: 33,
            name: "the closest hit of random rays, as testing every primitive finds it",
            points: 3,
            run: |e| {
                let mut r = Rng(3333);
                ray_scenes().iter().all(|t| {
                    random_rays(&mut r, 40).iter().all(|&(o, d)| {
                        let want = brute(&t.prims, o, d);
                        closest_is(e, t, o, d, want)
                    })
                })
            },
        },
        Check {
            exercise: 33,
            name: "best-first: tests few primitives (at most 1.5x the reference's + 2), none twice",
            points: 4,
            run: |e| {
                let mut r = Rng(3334);
                ray_scenes().iter().all(|t| {
                    random_rays(&mut r, 40).iter().all(|&(o, d)| {
                        let (_, mine) = ask(e, t, o, d);
                        let (_, reference) = ask(&Reference, t, o, d);
                        mine.len() * 2 <= reference.len() * 3 + 4
                            || fail(format!(
                                "ray_closest({}, origin {}, dir {}) called hit {} times, the \
                                 best-first search needs {}: at most {} allowed",
                                show_scene(t),
                                show_point(o),
                                show_point(d),
                                mine.len(),
                                reference.len(),
                                (reference.len() * 3 + 4) / 2
                            ))
                    })
                })
            },
        },
    ]
}

/// Unit cubes at x = 0, 2, 4, .., in leaves of one.
fn row_of(n: usize) -> Tree {
    Tree::new((0..n).map(|i| unit_at(2.0 * i as f32)).collect(), 1)
}

/// Trees for the random rays: a grid of 60 boxes in leaves of one, 300 in
/// leaves of four.
fn ray_scenes() -> Vec<Tree> {
    vec![
        Tree::new(boxes(60, 331, Vec3::ZERO), 1),
        Tree::new(boxes(300, 332, Vec3::ZERO), 4),
    ]
}

/// Rays from around the grids towards points in them (some start inside,
/// some miss), a few along the axes.
fn random_rays(r: &mut Rng, n: usize) -> Vec<(Vec3, Vec3)> {
    (0..n)
        .map(|i| {
            let o = r.point(30.0, Vec3::new(4.5, 4.5, 1.0));
            let target = r.point(10.0, Vec3::new(4.5, 4.5, 1.0));
            let mut d = target - o;
            if i % 5 == 0 {
                d = Vec3::new(0.0, 0.0, d.z); // straight up or down
            }
            if d == Vec3::ZERO {
                d = Vec3::X;
            }
            (o, d)
        })
        .collect()
}

/// What went in, in words.
fn show_scene(t: &Tree) -> String {
    if t.prims.len() <= 8 {
        let boxes: Vec<String> = t.prims.iter().map(show_box).collect();
        format!("tree over [{}]", boxes.join(", "))
    } else {
        format!("tree over {} boxes", t.prims.len())
    }
}

/// Asks `e` for the closest hit of the ray `o + t d` in `t`, with the
/// library's ray test of each primitive box as `hit`; returns its answer
/// and the primitives it tested, in order.
fn ask(e: &dyn Exercises, t: &Tree, o: Vec3, d: Vec3) -> (Option<(u32, f32)>, Vec<u32>) {
    let Ok(ray) = Ray::new(o, d, f32::INFINITY) else {
        return (None, Vec::new());
    };
    let mut calls = Vec::new();
    let got = e.ray_closest(&t.bvh(), o, d, &mut |k| {
        calls.push(k);
        t.prims.get(k as usize)?.ray_hit(&ray)
    });
    (got, calls)
}

/// The closest hit by testing every primitive, the smaller index on ties.
fn brute(prims: &[Aabb], o: Vec3, d: Vec3) -> Option<(u32, f32)> {
    let ray = Ray::new(o, d, f32::INFINITY).ok()?;
    let mut best = None::<(u32, f32)>;
    for (k, p) in prims.iter().enumerate() {
        if let Some(t) = p.ray_hit(&ray) {
            if best.is_none_or(|(_, b)| t < b) {
                best = Some((k as u32, t));
            }
        }
    }
    best
}

/// The answer must be `want`, and no primitive may be tested twice.
fn closest_is(e: &dyn Exercises, t: &Tree, o: Vec3, d: Vec3, want: Option<(u32, f32)>) -> bool {
    let call = format!(
        "ray_closest({}, origin {}, dir {})",
        show_scene(t),
        show_point(o),
        show_point(d)
    );
    let (got, calls) = ask(e, t, o, d);
    let mut seen = calls.clone();
    seen.sort_unstable();
    if let Some(w) = seen.windows(2).find(|w| w[0] == w[1]) {
        return fail(format!("{call} called hit({}) twice", w[0]));
    }
    same(call, want, got)
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;
    use std::cmp::Reverse;
    use std::collections::BinaryHeap;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 7;

    pub fn ray_closest(
        which: u32,
        tree: &Bvh<Aabb>,
        o: Vec3,
        d: Vec3,
        hit: &mut dyn FnMut(u32) -> Option<f32>,
    ) -> Option<(u32, f32)> {
        let nodes = tree.nodes();
        let leaf_ids =
            |n: &Node<Aabb>| &tree.indices()[n.first as usize..(n.first + n.count) as usize];
        let better = |k: u32, t: f32, best: Option<(u32, f32)>| {
            best.is_none_or(|(j, b)| t < b || (t == b && k < j))
        };
        match which {
            // Brute force: every primitive, the right answer, all the work.
            1 => {
                let mut best = None;
                for k in 0..tree.primitive_count() as u32 {
                    if let Some(t) = hit(k) {
                        if better(k, t, best) {
                            best = Some((k, t));
                        }
                    }
                }
                best
            }
            // Depth-first without the cut-off: every leaf the ray enters.
            2 => {
                let mut best = None;
                let mut stack: Vec<u32> = if nodes.is_empty() { vec![] } else { vec![0] };
                while let Some(i) = stack.pop() {
                    let node = &nodes[i as usize];
                    if entry(&node.bv, o, d).is_none() {
                        continue;
                    }
                    match node.children() {
                        Some((l, r)) => stack.extend([r, l]),
                        None => {
                            for &k in leaf_ids(node) {
                                if let Some(t) = hit(k) {
                                    if better(k, t, best) {
                                        best = Some((k, t));
                                    }
                                }
                            }
                        }
                    }
                }
                best
            }
            3..=7 => {
                // Best-first with one slip each.
                let enter = |b: &Aabb| match which {
                    5 => naive_entry(b, o, d),
                    6 => unclamped_entry(b, o, d),
                    _ => entry(b, o, d),
                };
                let mut queue = BinaryHeap::new();
                if let Some(t) = nodes.first().and_then(|n| enter(&n.bv)) {
                    queue.push(Reverse(((t + 0.0).to_bits(), 0u32)));
                }
                let mut best = None::<(u32, f32)>;
                while let Some(Reverse((t, i))) = queue.pop() {
                    let t = f32::from_bits(t);
                    // 3: stops at a node as far as the best (a tie lost).
                    let done = match (which, best) {
                        (_, None) => false,
                        (3, Some((_, b))) => t >= b,
                        // 7: stops at the first hit.
                        (7, Some(_)) => true,
                        (_, Some((_, b))) => t > b,
                    };
                    if done {
                        break;
                    }
                    let node = &nodes[i as usize];
                    match node.children() {
                        Some((l, r)) => {
                            for c in [l, r] {
                                if let Some(tc) = enter(&nodes[c as usize].bv) {
                                    queue.push(Reverse(((tc + 0.0).to_bits(), c)));
                                }
                            }
                        }
                        None => {
                            for &k in leaf_ids(node) {
                                if let Some(t) = hit(k) {
                                    // 4: the first found keeps a tie.
                                    let wins = if which == 4 {
                                        best.is_none_or(|(_, b)| t < b)
                                    } else {
                                        better(k, t, best)
                                    };
                                    if wins {
                                        best = Some((k, t));
                                    }
                                }
                            }
                        }
                    }
                }
                best
            }
            _ => Reference.ray_closest(tree, o, d, hit),
        }
    }

    /// The exact entry distance (the library's box test).
    fn entry(b: &Aabb, o: Vec3, d: Vec3) -> Option<f32> {
        b.ray_hit(&Ray::new(o, d, f32::INFINITY).ok()?)
    }

    /// The slab test dividing by zero: `0 * inf` is NaN where the origin
    /// lies on a plane the ray runs along, and the touching ray is lost.
    fn naive_entry(b: &Aabb, o: Vec3, d: Vec3) -> Option<f32> {
        let inv = Vec3::ONE / d;
        let (mut t0, mut t1) = (0.0f32, f32::INFINITY);
        for k in 0..3 {
            let (x, y) = ((b.min[k] - o[k]) * inv[k], (b.max[k] - o[k]) * inv[k]);
            t0 = t0.max(x.min(y));
            t1 = t1.min(x.max(y));
        }
        (t0 <= t1).then_some(t0)
    }

    /// The slab test without the clamp at 0, taking a negative entry (the
    /// origin inside the box) for a box behind the ray.
    fn unclamped_entry(b: &Aabb, o: Vec3, d: Vec3) -> Option<f32> {
        let (mut t0, mut t1) = (f32::NEG_INFINITY, f32::INFINITY);
        for k in 0..3 {
            if d[k] == 0.0 {
                if o[k] < b.min[k] || o[k] > b.max[k] {
                    return None;
                }
                continue;
            }
            let (x, y) = ((b.min[k] - o[k]) / d[k], (b.max[k] - o[k]) / d[k]);
            t0 = t0.max(x.min(y));
            t1 = t1.min(x.max(y));
        }
        (t0 <= t1 && t0 >= 0.0).then_some(t0)
    }
}
