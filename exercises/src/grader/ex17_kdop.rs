//! Exercise 17: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 17.
pub fn checks() -> Vec<Check> {
    vec![
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
                    pts.iter().all(|&p| {
                        dop.contains_point(p)
                            || (0..7)
                                .find(|&i| {
                                    let t = project(i, p);
                                    !(dop.min[i] as f64 <= t && t <= dop.max[i] as f64)
                                })
                                .is_some_and(|i| {
                                    let t = project(i, p);
                                    fail(format!(
                                        "dop14_fit({}) returned {}: point {} projects to {t} \
                                         along direction {i} {:?} (computed in f64), outside \
                                         [{}, {}]",
                                        show_points(pts),
                                        show_dop(&dop),
                                        show_point(p),
                                        Dop14::direction(i),
                                        dop.min[i],
                                        dop.max[i]
                                    ))
                                })
                    })
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
                        let lo = pts
                            .iter()
                            .map(|&p| project(i, p))
                            .fold(f64::INFINITY, f64::min);
                        let hi = pts
                            .iter()
                            .map(|&p| project(i, p))
                            .fold(f64::NEG_INFINITY, f64::max);
                        let tol = 1e-5 * lo.abs().max(hi.abs()).max(1.0);
                        ((dop.min[i] as f64 - lo).abs() <= tol
                            && (dop.max[i] as f64 - hi).abs() <= tol)
                            || fail(format!(
                                "dop14_fit({}) returned {}: along direction {i} {:?} the \
                                 points project to [{lo}, {hi}], the DOP has [{}, {}]",
                                show_points(pts),
                                show_dop(&dop),
                                Dop14::direction(i),
                                dop.min[i],
                                dop.max[i]
                            ))
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
                // Touching along the diagonal x + y + z only.
                let mut c = a;
                c.min[3] = a.max[3];
                c.max[3] = a.max[3] + 1.0;
                overlap_is(e, &a, &b, true)
                    && overlap_is(e, &a, &a, true)
                    && overlap_is(e, &a, &c, true)
            },
        },
        Check {
            exercise: 17,
            name: "overlap: separated along one diagonal only (each of the four), and random pairs",
            points: 3,
            run: |e| {
                // For each diagonal d: the corner of the unit cube lowest
                // along d with its three neighbours, and the highest corner
                // with its three: the same box around both, but apart along d.
                let diagonals = (3..7).all(|i| {
                    let d = Dop14::direction(i);
                    let low = Vec3::new(
                        (d[0] < 0) as u8 as f32,
                        (d[1] < 0) as u8 as f32,
                        (d[2] < 0) as u8 as f32,
                    );
                    let corner_and_neighbours = |c: Vec3| {
                        let mut pts = vec![c];
                        for k in 0..3 {
                            let mut n = c;
                            n[k] = 1.0 - n[k];
                            pts.push(n);
                        }
                        pts
                    };
                    let a = Dop14::fit(&corner_and_neighbours(low)[..]);
                    let b = Dop14::fit(&corner_and_neighbours(Vec3::ONE - low)[..]);
                    overlap_is(e, &a, &b, false)
                });
                let mut r = Rng(17);
                diagonals
                    && (0..300).all(|_| {
                        let mut dop = || {
                            let centre = r.point(4.0, Vec3::ZERO);
                            Dop14::fit(&r.cloud(4, 2.0, centre)[..])
                        };
                        let (x, y) = (dop(), dop());
                        overlap_is(e, &x, &y, x.overlaps(&y))
                    })
            },
        },
    ]
}

/// `p` along direction `i`, in `f64`.
fn project(i: usize, p: Vec3) -> f64 {
    let d = Dop14::direction(i);
    d[0] as f64 * p.x as f64 + d[1] as f64 * p.y as f64 + d[2] as f64 * p.z as f64
}

/// A point set in words: all of a few, or how many and the first.
fn show_points(pts: &[Vec3]) -> String {
    if pts.len() <= 3 {
        let all: Vec<String> = pts.iter().map(|&p| show_point(p)).collect();
        format!("[{}]", all.join(", "))
    } else {
        format!("{} points, the first {}", pts.len(), show_point(pts[0]))
    }
}

/// A 14-DOP in words: its intervals along the seven directions.
fn show_dop(d: &Dop14) -> String {
    let all: Vec<String> = (0..7)
        .map(|i| format!("{:?} [{}, {}]", Dop14::direction(i), d.min[i], d.max[i]))
        .collect();
    format!("{{{}}}", all.join(", "))
}

/// Asks about `a, b` and `b, a`: the answer must be `want` both ways.
fn overlap_is(e: &dyn Exercises, a: &Dop14, b: &Dop14, want: bool) -> bool {
    let ask = |a: &Dop14, b: &Dop14| {
        let call = format!("dop14_overlaps({}, {})", show_dop(a), show_dop(b));
        same(call, want, e.dop14_overlaps(a, b))
    };
    ask(a, b) && ask(b, a)
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 8;

    /// The fit with projections computed by `t` and stored by `store`.
    fn fit_with(
        points: &[Vec3],
        t: impl Fn(usize, Vec3) -> f64,
        start: f32,
        store: impl Fn(f64) -> f32,
    ) -> Dop14 {
        let mut k = Dop14 {
            min: [start.abs(); 7],
            max: [-start.abs(); 7],
        };
        for &p in points {
            for i in 0..7 {
                let x = store(t(i, p));
                k.min[i] = k.min[i].min(x);
                k.max[i] = k.max[i].max(x);
            }
        }
        k
    }

    pub fn dop14_fit(which: u32, points: &[Vec3]) -> Dop14 {
        match which {
            // The box's corners as the points: loose on the diagonals.
            1 => Dop14::from_aabb(&Aabb::fit(points)),
            // Projections in f32, rounded to nearest.
            2 => fit_with(
                points,
                |i, p| {
                    let d = Dop14::direction(i);
                    (d[0] as f32 * p.x + d[1] as f32 * p.y + d[2] as f32 * p.z) as f64
                },
                f32::INFINITY,
                |x| x as f32,
            ),
            // Projections in f64, but rounded to nearest when stored.
            5 => fit_with(points, project, f32::INFINITY, |x| x as f32),
            // Unit-length diagonals (divided by sqrt 3): not the DOP's directions.
            6 => fit_with(
                points,
                |i, p| project(i, p) / if i < 3 { 1.0 } else { 3f64.sqrt() },
                f32::INFINITY,
                |x| x as f32,
            ),
            // Bounds that start at 0 instead of the empty interval.
            7 => {
                let mut k = Reference.dop14_fit(points);
                for i in 0..7 {
                    k.min[i] = k.min[i].min(0.0);
                    k.max[i] = k.max[i].max(0.0);
                }
                k
            }
            _ => Reference.dop14_fit(points),
        }
    }

    pub fn dop14_overlaps(which: u32, a: &Dop14, b: &Dop14) -> bool {
        match which {
            // Touching is not overlapping.
            3 => (0..7).all(|i| a.min[i] < b.max[i] && b.min[i] < a.max[i]),
            // The box test: the three axes only.
            4 => (0..3).all(|i| a.min[i] <= b.max[i] && b.min[i] <= a.max[i]),
            // Off by one: the last diagonal is never tested.
            8 => (0..6).all(|i| a.min[i] <= b.max[i] && b.min[i] <= a.max[i]),
            _ => Reference.dop14_overlaps(a, b),
        }
    }
}
