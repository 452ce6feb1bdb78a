//! Exercise 2: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// How much larger than the minimal sphere `sphere_fit` may be.
const SPHERE_SLACK: f32 = 1.5;

/// The checks of exercise 2.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 2,
            name: "aabb_fit is exact (also for negative coordinates)",
            points: 4,
            run: |e| {
                clouds().iter().all(|c| {
                    same_box(
                        format!("aabb_fit({})", describe(c)),
                        &Aabb::fit(c.as_slice()),
                        &e.aabb_fit(c),
                    )
                })
            },
        },
        Check {
            exercise: 2,
            name: "aabb_fit of one point is that point",
            points: 1,
            run: |e| {
                let p = Vec3::new(-1.0, 2.0, -3.0);
                same_box(
                    format!("aabb_fit([{}])", show_point(p)),
                    &Aabb::from_point(p),
                    &e.aabb_fit(&[p]),
                )
            },
        },
        Check {
            exercise: 2,
            name: "aabb_merge is exact (disjoint, overlapping, nested; both orders)",
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
                    let call = |p: &Aabb, q: &Aabb| {
                        format!("aabb_merge({}, {})", show_box(p), show_box(q))
                    };
                    same_box(call(x, y), &x.union(y), &e.aabb_merge(x, y))
                        && same_box(call(y, x), &x.union(y), &e.aabb_merge(y, x))
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
                    match c.iter().find(|&&p| !s.contains_point(p)) {
                        None => true,
                        Some(&p) => fail(format!(
                            "sphere_fit({}) returned {}, but the point {} is outside it \
                             (at distance {} from the centre, computed in f64)",
                            describe(c),
                            show_sphere(&s),
                            show_point(p),
                            (p.as_dvec3() - s.center.as_dvec3()).length()
                        )),
                    }
                })
            },
        },
        Check {
            exercise: 2,
            name: "sphere_fit is within 1.5x of the minimal radius",
            points: 3,
            run: |e| {
                clouds().iter().all(|c| {
                    let s = e.sphere_fit(c);
                    let w = Sphere::welzl(c.as_slice());
                    s.radius <= w.radius * SPHERE_SLACK * (1.0 + 1e-5) + 1e-3
                        || fail(format!(
                            "sphere_fit({}) returned {}; the minimal sphere has radius {}, \
                             so the radius may be at most {SPHERE_SLACK} x {} = {}",
                            describe(c),
                            show_sphere(&s),
                            w.radius,
                            w.radius,
                            w.radius * SPHERE_SLACK
                        ))
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
                    let missed = if !m.contains(&x) {
                        "first"
                    } else if !m.contains(&y) {
                        "second"
                    } else {
                        return true;
                    };
                    fail(format!(
                        "sphere_merge({}, {}) returned {}, which does not contain the {missed} \
                         sphere",
                        show_sphere(&x),
                        show_sphere(&y),
                        show_sphere(&m)
                    ))
                })
            },
        },
        Check {
            exercise: 2,
            name: "sphere_merge is minimal (and returns a containing input as is, either order)",
            points: 2,
            run: |e| {
                let mut r = Rng(8);
                let nested = Sphere::new(Vec3::ZERO, 5.0);
                let inner = Sphere::new(Vec3::ONE, 1.0);
                let minimal = |x: &Sphere, y: &Sphere| {
                    let best = x.merge(y).radius;
                    let got = e.sphere_merge(x, y);
                    got.radius <= best * (1.0 + 1e-4) + 1e-5
                        || fail(format!(
                            "sphere_merge({}, {}) returned {}; the smallest sphere around \
                             both has radius {best}",
                            show_sphere(x),
                            show_sphere(y),
                            show_sphere(&got)
                        ))
                };
                minimal(&nested, &inner)
                    && minimal(&inner, &nested)
                    && (0..200).all(|_| {
                        let x = Sphere::new(r.point(10.0, Vec3::ZERO), r.next() * 3.0);
                        let y = Sphere::new(r.point(10.0, Vec3::ZERO), r.next() * 3.0);
                        minimal(&x, &y)
                    })
            },
        },
    ]
}

/// `want == got` for boxes, explained with the boxes written out.
fn same_box(call: String, want: &Aabb, got: &Aabb) -> bool {
    want == got
        || fail(format!(
            "{call} returned {}, expected {}",
            show_box(got),
            show_box(want)
        ))
}

/// A sphere as `centre (x, y, z), radius r`.
fn show_sphere(s: &Sphere) -> String {
    format!("centre {}, radius {}", show_point(s.center), s.radius)
}

/// A point set in a few words: up to three points written out, else how
/// many and the box they span.
fn describe(c: &[Vec3]) -> String {
    if c.len() <= 3 {
        let pts: Vec<String> = c.iter().map(|&p| show_point(p)).collect();
        format!("[{}]", pts.join(", "))
    } else {
        format!(
            "{} points spanning the box {}",
            c.len(),
            show_box(&Aabb::fit(c))
        )
    }
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 8;

    pub fn aabb_fit(which: u32, points: &[Vec3]) -> Aabb {
        let grow = |b: Aabb, p: &Vec3| Aabb::new(b.min.min(*p), b.max.max(*p));
        match which {
            // Starts from the origin instead of the first point.
            1 => points.iter().fold(Aabb::new(Vec3::ZERO, Vec3::ZERO), grow),
            // Off by one: the loop stops before the last point.
            6 => points[..points.len() - 1]
                .iter()
                .fold(Aabb::from_point(points[0]), grow),
            _ => Reference.aabb_fit(points),
        }
    }

    pub fn aabb_merge(which: u32, a: &Aabb, b: &Aabb) -> Aabb {
        match which {
            // The loop over the axes stops at y: z stays a's.
            5 => {
                let (mut lo, mut hi) = (a.min, a.max);
                for k in 0..2 {
                    lo[k] = a.min[k].min(b.min[k]);
                    hi[k] = a.max[k].max(b.max[k]);
                }
                Aabb::new(lo, hi)
            }
            _ => Reference.aabb_merge(a, b),
        }
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
            // Ritter's first pass only: the sphere on the widest x extremes,
            // never grown to take in the other points.
            8 => {
                let lo = points
                    .iter()
                    .copied()
                    .reduce(|p, q| if q.x < p.x { q } else { p });
                let hi = points
                    .iter()
                    .copied()
                    .reduce(|p, q| if q.x > p.x { q } else { p });
                let (lo, hi) = (lo.unwrap_or_default(), hi.unwrap_or_default());
                Sphere::new((lo + hi) * 0.5, lo.distance(hi) * 0.5)
            }
            _ => Reference.sphere_fit(points),
        }
    }

    pub fn sphere_merge(which: u32, a: &Sphere, b: &Sphere) -> Sphere {
        match which {
            // Centre halfway between the centres, radius to cover the larger.
            4 => Sphere::new(
                (a.center + b.center) * 0.5,
                a.center.distance(b.center) * 0.5 + a.radius.max(b.radius),
            ),
            // Returns `a` when it contains `b`, but forgets the other way round.
            7 => {
                if b.contains(a) {
                    let d = b.center.distance(a.center);
                    let r = (d + a.radius + b.radius) * 0.5;
                    let dir = if d > 0.0 {
                        (b.center - a.center) / d
                    } else {
                        Vec3::X
                    };
                    Sphere::new(a.center + dir * (r - a.radius), r * (1.0 + 1e-6))
                } else {
                    Reference.sphere_merge(a, b)
                }
            }
            _ => Reference.sphere_merge(a, b),
        }
    }
}
