//! Exercise 2: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 2.
pub fn checks() -> Vec<Check> {
    vec![
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
    ]
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 4;

    pub fn aabb_fit(which: u32, points: &[Vec3]) -> Aabb {
        match which {
            1 => points
                .iter()
                .fold(Aabb::new(Vec3::ZERO, Vec3::ZERO), |b, p| {
                    Aabb::new(b.min.min(*p), b.max.max(*p))
                }),
            _ => Reference.aabb_fit(points),
        }
    }

    pub fn aabb_merge(_which: u32, a: &Aabb, b: &Aabb) -> Aabb {
        Reference.aabb_merge(a, b)
    }

    pub fn sphere_fit(which: u32, points: &[Vec3]) -> Sphere {
        match which {
            // Ritter without any rounding care: f32 arithmetic throughout.
            2 => {
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
            3 => BoundingVolume::from_aabb(&Aabb::fit(points)),
            _ => Reference.sphere_fit(points),
        }
    }

    pub fn sphere_merge(which: u32, a: &Sphere, b: &Sphere) -> Sphere {
        match which {
            4 => Sphere::new(
                (a.center + b.center) * 0.5,
                a.center.distance(b.center) * 0.5 + a.radius.max(b.radius),
            ),
            _ => Reference.sphere_merge(a, b),
        }
    }
}
