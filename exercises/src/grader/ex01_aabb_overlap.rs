//! Exercise 1: AABB overlap. The checks, and the plausible wrong answers
//! they must reject.

use super::common::*;

/// The checks of exercise 1.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 1,
            name: "overlapping boxes overlap",
            points: 2,
            run: |e| overlap_is(e, &b([0.0; 3], [2.0; 3]), &b([1.0; 3], [3.0; 3]), true),
        },
        Check {
            exercise: 1,
            name: "boxes apart along one axis only do not overlap",
            points: 2,
            run: |e| {
                (0..3).all(|k| {
                    let mut lo = [0.0; 3];
                    lo[k] = 5.0;
                    let hi = lo.map(|x| x + 1.0);
                    overlap_is(e, &b([0.0; 3], [1.0; 3]), &b(lo, hi), false)
                })
            },
        },
        Check {
            exercise: 1,
            name: "touching faces, edges and corners overlap",
            points: 2,
            run: |e| {
                let a = b([0.0; 3], [1.0; 3]);
                overlap_is(e, &a, &b([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]), true)
                    && overlap_is(e, &a, &b([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]), true)
                    && overlap_is(e, &a, &b([1.0; 3], [2.0; 3]), true)
                    && overlap_is(e, &a, &b([0.5, 0.5, 1.0], [0.5, 0.5, 1.0]), true)
            },
        },
        Check {
            exercise: 1,
            name: "a box inside another overlaps it",
            points: 1,
            run: |e| overlap_is(e, &b([0.0; 3], [10.0; 3]), &b([4.0; 3], [5.0; 3]), true),
        },
        Check {
            exercise: 1,
            name: "crossing boxes (no corner of either inside the other) overlap",
            points: 1,
            run: |e| {
                let (long_x, long_y) = (
                    b([-5.0, -1.0, 0.0], [5.0, 1.0, 1.0]),
                    b([-1.0, -5.0, 0.0], [1.0, 5.0, 1.0]),
                );
                overlap_is(e, &long_x, &long_y, true)
            },
        },
        Check {
            exercise: 1,
            name: "boxes touching at arbitrary coordinates overlap (no rounding allowed)",
            points: 1,
            run: |e| {
                // Centre and half-extent forms round; min/max comparisons do not.
                let mut r = Rng(7);
                (0..300).all(|_| {
                    let lo = r.point(2000.0, Vec3::ZERO);
                    let mid = lo + Vec3::new(r.next(), r.next(), r.next()) * 3.7 + 0.01;
                    let hi = mid + Vec3::new(r.next(), r.next(), r.next()) * 0.3 + 0.01;
                    let k = (r.next() * 3.0) as usize % 3;
                    let (mut a_max, mut b_min) = (hi, lo);
                    a_max[k] = mid[k];
                    b_min[k] = mid[k];
                    overlap_is(e, &Aabb::new(lo, a_max), &Aabb::new(b_min, hi), true)
                })
            },
        },
        Check {
            exercise: 1,
            name: "500 random pairs",
            points: 1,
            run: |e| {
                let mut r = Rng(42);
                (0..500).all(|_| {
                    let (p, q) = (r.point(4.0, Vec3::ZERO), r.point(4.0, Vec3::ZERO));
                    let (s, t) = (r.point(2.0, Vec3::ONE), r.point(2.0, Vec3::ONE));
                    let x = Aabb::new(p.min(q), p.max(q));
                    let y = Aabb::new(s.min(t), s.max(t));
                    let truth = (0..3).all(|k| x.min[k] <= y.max[k] && y.min[k] <= x.max[k]);
                    overlap_is(e, &x, &y, truth)
                })
            },
        },
    ]
}

/// Asks about `a, b` and `b, a`: the answer must be `want` both ways.
fn overlap_is(e: &dyn Exercises, a: &Aabb, b: &Aabb, want: bool) -> bool {
    let ask = |a: &Aabb, b: &Aabb| {
        let call = format!("aabb_overlaps({}, {})", show_box(a), show_box(b));
        same(call, want, e.aabb_overlaps(a, b))
    };
    ask(a, b) && ask(b, a)
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 6;

    pub fn aabb_overlaps(which: u32, a: &Aabb, b: &Aabb) -> bool {
        match which {
            1 => (0..3).all(|k| a.min[k] < b.max[k] && b.min[k] < a.max[k]), // strict
            2 => (0..3).any(|k| a.min[k] <= b.max[k] && b.min[k] <= a.max[k]), // any axis
            3 => (0..2).all(|k| a.min[k] <= b.max[k] && b.min[k] <= a.max[k]), // forgets z
            // One side of the interval test only.
            4 => (0..3).all(|k| a.min[k] <= b.max[k]),
            // Centres and half extents in f32: rounds on touching boxes.
            5 => (0..3).all(|k| {
                let (ca, cb) = ((a.min[k] + a.max[k]) * 0.5, (b.min[k] + b.max[k]) * 0.5);
                let (ha, hb) = ((a.max[k] - a.min[k]) * 0.5, (b.max[k] - b.min[k]) * 0.5);
                (ca - cb).abs() <= ha + hb
            }),
            // A corner of one box inside the other.
            6 => {
                let corner_in = |x: &Aabb, y: &Aabb| {
                    (0..8).any(|c| {
                        let p = Vec3::new(
                            if c & 1 == 0 { x.min.x } else { x.max.x },
                            if c & 2 == 0 { x.min.y } else { x.max.y },
                            if c & 4 == 0 { x.min.z } else { x.max.z },
                        );
                        y.contains_point(p)
                    })
                };
                corner_in(a, b) || corner_in(b, a)
            }
            _ => Reference.aabb_overlaps(a, b),
        }
    }
}
