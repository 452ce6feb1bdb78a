//! Exercise 26: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 26.
pub fn checks() -> Vec<Check> {
    vec![
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
    ]
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 5;

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
            _ => Some(right),
        }
    }
}
