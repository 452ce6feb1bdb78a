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
    ]
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 4;

    pub fn dop14_fit(which: u32, points: &[Vec3]) -> Dop14 {
        match which {
            // The box's corners as the points: loose on the diagonals.
            1 => Dop14::from_aabb(&Aabb::fit(points)),
            // Projections in f32, rounded to nearest.
            2 => {
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

    pub fn dop14_overlaps(which: u32, a: &Dop14, b: &Dop14) -> bool {
        match which {
            // Touching is not overlapping.
            3 => (0..7).all(|i| a.min[i] < b.max[i] && b.min[i] < a.max[i]),
            // The box test: the three axes only.
            4 => (0..3).all(|i| a.min[i] <= b.max[i] && b.min[i] <= a.max[i]),
            _ => Reference.dop14_overlaps(a, b),
        }
    }
}
