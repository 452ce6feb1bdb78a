//! Exercise 23: primitive bounds in leaf order. The checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 23.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 23,
            name: "bounds in leaf order: entry k bounds primitive indices[k]",
            points: 4,
            run: |e| {
                leaf_order_cases().iter().all(|(tris, leaf)| {
                    let builder = TopDown::default().with_max_leaf_size(*leaf);
                    let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(tris.len())];
                    let mut idx = vec![0u32; tris.len()];
                    let Ok(tree) = builder.build(tris, &mut nodes, &mut idx) else {
                        return fail("the grader could not build its tree");
                    };
                    let call = format!(
                        "leaf_order_bounds(a tree over {} scattered triangles, leaf size {leaf})",
                        tris.len()
                    );
                    let got = e.leaf_order_bounds(&tree, tris);
                    if got.len() != tree.indices().len() {
                        return fail(format!(
                            "{call} returned {} boxes, expected {} (one per entry of the index array)",
                            got.len(),
                            tree.indices().len()
                        ));
                    }
                    got.iter().zip(tree.indices()).enumerate().all(|(k, (b, &p))| {
                        let want = bvhkit::Primitive::bounds(&tris[p as usize]);
                        *b == want
                            || fail(format!(
                                "{call}: entry {k} is {}, expected {}, the bounds of primitive \
                                 indices[{k}] = {p}",
                                show_box(b),
                                show_box(&want)
                            ))
                    })
                })
            },
        },
        Check {
            exercise: 23,
            name: "a leaf pair's candidates: ids not positions, touching boxes count, A's order then B's",
            points: 3,
            run: |e| {
                let unit = |o: Vec3| Aabb::new(o, o + Vec3::ONE);
                let v = Vec3::new;
                // Touching along x (1.0 = 1.0), apart, and nested.
                let fixed: [LeafPairCase; 3] = [
                    (
                        &[7, 3],
                        vec![unit(Vec3::ZERO), unit(Vec3::splat(5.0))],
                        &[9, 2, 4],
                        vec![unit(Vec3::X), unit(Vec3::splat(2.5)), unit(Vec3::splat(5.2))],
                        vec![(7, 9), (3, 4)],
                    ),
                    // One big box of A over every box of B, one touching
                    // only B's first at a corner.
                    (
                        &[5, 1, 8],
                        vec![
                            Aabb::new(Vec3::ZERO, Vec3::splat(10.0)),
                            unit(v(-1.0, -1.0, -1.0)),
                            unit(v(20.0, 0.0, 0.0)),
                        ],
                        &[6, 0, 3],
                        vec![unit(Vec3::ZERO), unit(Vec3::splat(4.0)), unit(Vec3::splat(8.5))],
                        vec![(5, 6), (5, 0), (5, 3), (1, 6)],
                    ),
                    // Every box of A overlaps B's second only.
                    (
                        &[2, 4],
                        vec![unit(v(0.0, 0.0, 0.0)), unit(v(0.5, 0.0, 0.0))],
                        &[11, 10],
                        vec![unit(v(0.0, 3.0, 0.0)), unit(v(1.0, 0.5, 0.5))],
                        vec![(2, 10), (4, 10)],
                    ),
                ];
                fixed.iter().all(|(ia, ba, ib, bb, want)| {
                    let got = e.leaf_pair_candidates((ia, ba), (ib, bb));
                    same(pair_call(ia, ba, ib, bb), want.clone(), got)
                })
            },
        },
        Check {
            exercise: 23,
            name: "a leaf pair's candidates: 300 random leaf pairs on a half-unit grid",
            points: 3,
            run: |e| {
                let mut r = Rng(2324);
                (0..300).all(|_| {
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
                    same(
                        pair_call(&ia, &ba, &ib, &bb),
                        Reference.leaf_pair_candidates((&ia, &ba), (&ib, &bb)),
                        e.leaf_pair_candidates((&ia, &ba), (&ib, &bb)),
                    )
                })
            },
        },
    ]
}

/// Two leaves (ids, boxes) and the candidate pairs they should give.
type LeafPairCase = (
    &'static [u32],
    Vec<Aabb>,
    &'static [u32],
    Vec<Aabb>,
    Vec<(u32, u32)>,
);

/// `leaf_pair_candidates((ids, [boxes]), (ids, [boxes]))` as a student reads it.
fn pair_call(ia: &[u32], ba: &[Aabb], ib: &[u32], bb: &[Aabb]) -> String {
    let show = |b: &[Aabb]| b.iter().map(show_box).collect::<Vec<_>>().join(", ");
    format!(
        "leaf_pair_candidates(({ia:?}, [{}]), ({ib:?}, [{}]))",
        show(ba),
        show(bb)
    )
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

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;
    use bvhkit::Primitive;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 7;

    pub fn leaf_order_bounds(which: u32, tree: &Bvh<Aabb>, prims: &[Triangle]) -> Vec<Aabb> {
        match which {
            // In the primitives' own order, not the leaves'.
            1 => prims.iter().map(bvhkit::Primitive::bounds).collect(),
            // Each entry gets its leaf's box: contains the primitive,
            // but is not its bounds.
            2 => {
                let mut out = vec![Aabb::EMPTY; tree.indices().len()];
                for n in tree.nodes().iter().filter(|n| n.is_leaf()) {
                    for k in n.first..n.first + n.count {
                        out[k as usize] = n.bv;
                    }
                }
                out
            }
            // Scatters instead of gathering: entry indices[k] gets primitive k's bounds.
            7 => {
                let mut out = vec![Aabb::EMPTY; tree.indices().len()];
                for (k, &p) in tree.indices().iter().enumerate() {
                    out[p as usize] = prims[k].bounds();
                }
                out
            }
            _ => Reference.leaf_order_bounds(tree, prims),
        }
    }

    pub fn leaf_pair_candidates(
        which: u32,
        a: (&[u32], &[Aabb]),
        b: (&[u32], &[Aabb]),
    ) -> Vec<(u32, u32)> {
        match which {
            // Positions in the leaves instead of the primitives' ids.
            3 => {
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
            4 => {
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
            // B's boxes in the outer loop: the right pairs in the wrong order.
            5 => {
                let mut out = Vec::new();
                for (&q, y) in b.0.iter().zip(b.1) {
                    for (&p, x) in a.0.iter().zip(a.1) {
                        if x.overlaps(y) {
                            out.push((p, q));
                        }
                    }
                }
                out
            }
            // Stops at the first box of B that an A box overlaps (a `break`).
            6 => {
                let mut out = Vec::new();
                for (&p, x) in a.0.iter().zip(a.1) {
                    if let Some((&q, _)) = b.0.iter().zip(b.1).find(|(_, y)| x.overlaps(y)) {
                        out.push((p, q));
                    }
                }
                out
            }
            _ => Reference.leaf_pair_candidates(a, b),
        }
    }
}
