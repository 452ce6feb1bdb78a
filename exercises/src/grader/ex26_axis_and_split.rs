//! Exercise 26: axis choice and split point. The checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 26.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 26,
            name:
                "axis choice: longest extent or largest variance (in f64), ties to the lower axis",
            points: 5,
            run: |e| {
                use crate::{AxisRule::*, PointRule::SpatialMedian};
                let v = Vec3::new;
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
                // Extents past f32's range: 6e38 on x, 6.4e38 on y.
                let wide = [v(-3.0e38, -3.2e38, 0.0), v(3.0e38, 3.2e38, 1.0)];
                // Ten thousand units out, variances 0.32, 0.39 and 0 in some
                // order: E[x^2] - E[x]^2 in f32 gets 8, 0 and 0 there.
                let far = |order: [usize; 3]| -> Vec<Vec3> {
                    (0..8)
                        .map(|i| {
                            let d = [1.125 * (i % 2) as f32, 1.25 * (i % 2) as f32, 0.0];
                            Vec3::new(d[order[0]], d[order[1]], d[order[2]]) + 1.0e4
                        })
                        .collect()
                };
                let fixed: Vec<(Vec<Vec3>, crate::AxisRule, usize)> = vec![
                    (outlier.clone(), Longest, 0),
                    (outlier, Variance, 1),
                    (cube.to_vec(), Longest, 0),
                    (cube.to_vec(), Variance, 0),
                    (yz.to_vec(), Longest, 1),
                    (yz.to_vec(), Variance, 1),
                    (vec![v(5.0, 5.0, 5.0)], Longest, 0),
                    (vec![v(5.0, 5.0, 5.0)], Variance, 0),
                    (wide.to_vec(), Longest, 1),
                    (far([0, 1, 2]), Variance, 1),
                    (far([1, 2, 0]), Variance, 0),
                    (far([2, 0, 1]), Variance, 2),
                    (far([1, 0, 2]), Variance, 0),
                ];
                let mut r = Rng(2626);
                fixed.iter().all(|(c, rule, k)| {
                    let want = Reference.split_plane(c, *rule, SpatialMedian);
                    want.is_some_and(|w| w.0 == *k) && plane_is(e, c, *rule, SpatialMedian, want)
                }) && plane_is(e, &[], Longest, SpatialMedian, None)
                    && (0..500).all(|_| {
                        let n = 1 + (r.next() * 12.0) as usize;
                        let squash = r.point(1.0, Vec3::ZERO).abs();
                        let c: Vec<Vec3> =
                            (0..n).map(|_| r.point(4.0, Vec3::ZERO) * squash).collect();
                        [Longest, Variance].iter().all(|&rule| {
                            let want = Reference.split_plane(&c, rule, SpatialMedian);
                            plane_is(e, &c, rule, SpatialMedian, want)
                        })
                    })
            },
        },
        Check {
            exercise: 26,
            name: "split point: the sorted coordinate at n/2, mean and middle of the extent in f64",
            points: 5,
            run: |e| {
                use crate::{AxisRule::Longest, PointRule::*};
                let v = Vec3::new;
                // x: 0, 1, 2, 10 (longest); the upper middle is 2.
                let row = [
                    v(10.0, 0.0, 0.0),
                    v(0.0, 0.0, 0.0),
                    v(2.0, 0.0, 0.0),
                    v(1.0, 0.0, 0.0),
                ];
                let three = [v(-1.0, 0.0, 0.0), v(7.0, 0.0, 0.0), v(3.0, 0.0, 0.0)];
                // Near f32::MAX: (min + max) overflows f32 but not f64.
                let huge = [
                    v(3.0e38, 0.0, 0.0),
                    v(3.2e38, 0.0, 0.0),
                    v(2.0e38, 0.0, 0.0),
                ];
                let at = |c: &[Vec3], rule, x: f32| plane_is(e, c, Longest, rule, Some((0, x)));
                let mut r = Rng(2627);
                at(&row, ObjectMedian, 2.0)
                    && at(&row, ObjectMean, 3.25)
                    && at(&row, SpatialMedian, 5.0)
                    && at(&three, ObjectMedian, 3.0)
                    && [SpatialMedian, ObjectMean].iter().all(|&rule| {
                        let want = Reference.split_plane(&huge, Longest, rule);
                        want.is_some_and(|w| w.1.is_finite())
                            && plane_is(e, &huge, Longest, rule, want)
                    })
                    && (0..500).all(|_| {
                        let n = 1 + (r.next() * 15.0) as usize;
                        let shift = r.point(1e4, Vec3::ZERO);
                        let c: Vec<Vec3> = (0..n).map(|_| r.point(3.0, shift)).collect();
                        [ObjectMedian, ObjectMean, SpatialMedian]
                            .iter()
                            .all(|&rule| {
                                let want = Reference.split_plane(&c, Longest, rule);
                                plane_is(e, &c, Longest, rule, want)
                            })
                    })
            },
        },
    ]
}

/// Whether `split_plane(c, axis, point)` is `want`, explained when it is not.
fn plane_is(
    e: &dyn Exercises,
    c: &[Vec3],
    axis: crate::AxisRule,
    point: crate::PointRule,
    want: Option<(usize, f32)>,
) -> bool {
    // Coordinates near f32::MAX in scientific notation, others as usual.
    let x = |v: f32| match v.abs() >= 1e16 {
        true => format!("{v:e}"),
        false => v.to_string(),
    };
    let at = |p: &Vec3| format!("({}, {}, {})", x(p.x), x(p.y), x(p.z));
    let shown = if c.len() <= 12 {
        c.iter().map(at).collect::<Vec<_>>().join(", ")
    } else {
        format!("{} centroids, the first {}", c.len(), at(&c[0]))
    };
    let call = format!("split_plane([{shown}], {axis:?}, {point:?})");
    same(call, want, e.split_plane(c, axis, point))
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 8;

    pub fn split_plane(
        which: u32,
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
        match which {
            // Ties to the higher axis.
            1 if axis == AxisRule::Longest => {
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
            2 if axis == AxisRule::Variance => {
                Reference.split_plane(centroids, AxisRule::Longest, point)
            }
            // The lower middle.
            3 if point == PointRule::ObjectMedian => {
                let mut v: Vec<f32> = xs().collect();
                v.sort_by(f32::total_cmp);
                Some((k, v[(v.len() - 1) / 2]))
            }
            // The middle of the extent in f32: overflows near f32::MAX.
            4 if point == PointRule::SpatialMedian => {
                let (lo, hi) = xs().fold((f32::INFINITY, f32::NEG_INFINITY), |(l, h), x| {
                    (l.min(x), h.max(x))
                });
                Some((k, (lo + hi) / 2.0))
            }
            // The mean taken as the middle of the extent.
            5 if point == PointRule::ObjectMean => {
                Reference.split_plane(centroids, axis, PointRule::SpatialMedian)
            }
            // The variance as E[x^2] - E[x]^2 in f32: noise far from the origin.
            6 if axis == AxisRule::Variance => {
                let var = |k: usize| {
                    let n = centroids.len() as f32;
                    let (s, s2) = centroids
                        .iter()
                        .fold((0f32, 0f32), |(s, s2), c| (s + c[k], s2 + c[k] * c[k]));
                    s2 / n - (s / n) * (s / n)
                };
                let mut best = 0;
                for j in 1..3 {
                    if var(j) > var(best) {
                        best = j;
                    }
                }
                let moved: Vec<Vec3> = centroids.iter().map(|c| Vec3::splat(c[best])).collect();
                Some((
                    best,
                    Reference.split_plane(&moved, AxisRule::Longest, point)?.1,
                ))
            }
            // The median without sorting: the centroid at n / 2 in input order.
            7 if point == PointRule::ObjectMedian => Some((k, centroids[centroids.len() / 2][k])),
            // Extents in f32: past f32::MAX both are infinite, and x wins the tie.
            8 if axis == AxisRule::Longest => {
                let mut best = 0;
                for j in 1..3 {
                    if extent(j) > extent(best) {
                        best = j;
                    }
                }
                let moved: Vec<Vec3> = centroids.iter().map(|c| Vec3::splat(c[best])).collect();
                Some((
                    best,
                    Reference.split_plane(&moved, AxisRule::Longest, point)?.1,
                ))
            }
            _ => Some(right),
        }
    }
}
