//! Exercise 16: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 16.
pub fn checks() -> Vec<Check> {
    vec![
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
                boundary_is(e, &bins, Some(3))
            },
        },
        Check {
            exercise: 16,
            name: "never leaves a side empty (and None when nothing separates)",
            points: 2,
            run: |e| {
                let empty = (Aabb::EMPTY, 0);
                boundary_is(
                    e,
                    &[empty, (unit_at(0.0), 1), (unit_at(3.0), 1), empty],
                    Some(2),
                ) && boundary_is(e, &[empty, (unit_at(0.0), 2), empty], None)
                    && boundary_is(e, &[(unit_at(0.0), 5)], None)
                    && boundary_is(e, &[], None)
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
                    boundary_is(e, &bins, Reference.sah_best_boundary(&bins))
                }) && {
                    // Far from the origin: the boxes are 1 to 4 wide, not 100.
                    let far = [
                        (unit_at(100.0), 1),
                        (unit_at(101.0), 1),
                        (unit_at(102.0), 1),
                        (unit_at(103.0), 5),
                    ];
                    boundary_is(e, &far, Some(3))
                }
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
                // Far from the origin, with an empty bin between: 34 and 34 again.
                let far = [
                    (unit_at(100.0), 1),
                    (Aabb::EMPTY, 0),
                    (unit_at(102.0), 1),
                    (unit_at(104.0), 1),
                ];
                boundary_is(e, &bins, Some(1)) && boundary_is(e, &far, Some(1))
            },
        },
    ]
}

/// Whether the boundary chosen for `bins` is `want`; explained with the
/// bins (their boxes and counts) and the costs of both boundaries.
fn boundary_is(e: &dyn Exercises, bins: &[(Aabb, u32)], want: Option<usize>) -> bool {
    let got = e.sah_best_boundary(bins);
    if got == want {
        return true;
    }
    let shown: Vec<String> = bins
        .iter()
        .map(|(b, n)| match n {
            0 => "(empty, 0)".to_string(),
            _ => format!("({}, {n})", show_box(b)),
        })
        .collect();
    let cost = |b: Option<usize>| match b {
        Some(b) if (1..bins.len()).contains(&b) => {
            let side = |s: &[(Aabb, u32)]| {
                s.iter()
                    .fold((Aabb::EMPTY, 0u32), |(x, n), (y, m)| (x.union(y), n + m))
            };
            let ((l, nl), (r, nr)) = (side(&bins[..b]), side(&bins[b..]));
            if nl == 0 || nr == 0 {
                " (leaves a side without primitives)".to_string()
            } else {
                format!(
                    " (cost {})",
                    l.surface_area() * nl as f32 + r.surface_area() * nr as f32
                )
            }
        }
        Some(_) => " (not a boundary between two bins)".to_string(),
        None => String::new(),
    };
    fail(format!(
        "sah_best_boundary([{}]) returned {got:?}{}, expected {want:?}{}",
        shown.join(", "),
        cost(got),
        cost(want)
    ))
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 7;

    pub fn sah_best_boundary(which: u32, bins: &[(Aabb, u32)]) -> Option<usize> {
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
            union(l).surface_area() * count(l) as f32 + union(r).surface_area() * count(r) as f32
        };
        match which {
            // Balances the counts instead of the cost.
            1 => pick(
                &|b| both(b).then(|| (count(&bins[..b]) as f32 - count(&bins[b..]) as f32).abs()),
                false,
            ),
            // An empty side costs nothing instead of being refused.
            2 => pick(
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
            3 => pick(
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
            4 => pick(&|b| both(b).then(|| sah(b)), true),
            // Off by one: never tries the last boundary, bins.len() - 1.
            5 => pick(&|b| (b + 1 < bins.len() && both(b)).then(|| sah(b)), false),
            // Returns the last bin on the left (b - 1), not the boundary.
            6 => Reference.sah_best_boundary(bins).map(|b| b - 1),
            // Each side's box grown from the origin instead of from the empty box.
            7 => pick(
                &|b| {
                    both(b).then(|| {
                        let grown = |s: &[(Aabb, u32)]| {
                            s.iter()
                                .fold(Aabb::new(Vec3::ZERO, Vec3::ZERO), |a, x| a.union(&x.0))
                        };
                        let (l, r) = (&bins[..b], &bins[b..]);
                        grown(l).surface_area() * count(l) as f32
                            + grown(r).surface_area() * count(r) as f32
                    })
                },
                false,
            ),
            _ => Reference.sah_best_boundary(bins),
        }
    }
}
