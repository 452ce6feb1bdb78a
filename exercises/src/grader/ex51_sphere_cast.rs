//! Exercise 51: the time of impact of a moving ball against a triangle.
//! The checks, and the plausible wrong answers they must reject.
//!
//! The expected answer is the reference's (the library's
//! [`bvhkit::CastTarget::cast_hit`] for a [`bvhkit::ShapeCast::sphere`]).
//! A student's arithmetic rounds differently, so times agree within a
//! tolerance, and the random cases leave out grazing paths (where a radius
//! one part in a thousand larger or smaller changes hit into miss), whose
//! answer rounding may flip either way.

use super::common::*;
use bvhkit::{CastTarget, ShapeCast};

/// The checks of exercise 51.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 51,
            name: "falling onto the face: the centre stops one radius short of the plane",
            points: 2,
            run: |e| agrees(e, &face_cases()),
        },
        Check {
            exercise: 51,
            name: "passing an edge or a corner: the first contact is on the rim, not the plane",
            points: 3,
            run: |e| agrees(e, &rim_cases()),
        },
        Check {
            exercise: 51,
            name: "starting in contact (t = 0), moving away, stopping short (t_max), \
                   a zero radius (a ray), a zero-area triangle",
            points: 2,
            run: |e| agrees(e, &edge_of_the_rules()),
        },
        Check {
            exercise: 51,
            name: "600 random balls and triangles, grazing paths left out",
            points: 3,
            run: |e| agrees(e, &random_cases()),
        },
    ]
}

/// A triangle and a ball's motion.
struct Case {
    tri: Triangle,
    centre: Vec3,
    radius: f32,
    dir: Vec3,
    t_max: f32,
}

impl Case {
    fn want(&self) -> Option<f32> {
        Reference.sphere_cast(&self.tri, self.centre, self.radius, self.dir, self.t_max)
    }
}

fn close(got: Option<f32>, want: Option<f32>) -> bool {
    match (got, want) {
        (Some(g), Some(w)) => (g - w).abs() <= 1e-4 * (1.0 + w.abs()),
        (None, None) => true,
        _ => false,
    }
}

fn agrees(e: &dyn Exercises, cases: &[Case]) -> bool {
    cases.iter().all(|c| {
        let want = c.want();
        let got = e.sphere_cast(&c.tri, c.centre, c.radius, c.dir, c.t_max);
        close(got, want)
            || fail(format!(
                "sphere_cast({:?}, centre {}, radius {}, dir {}, t_max {}): expected {want:?}, \
                 got {got:?}",
                c.tri.v, c.centre, c.radius, c.dir, c.t_max
            ))
    })
}

fn floor() -> Triangle {
    Triangle::new(
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(4.0, 0.0, 0.0),
        Vec3::new(0.0, 4.0, 0.0),
    )
}

fn case(tri: Triangle, centre: Vec3, radius: f32, dir: Vec3, t_max: f32) -> Case {
    Case {
        tri,
        centre,
        radius,
        dir,
        t_max,
    }
}

fn face_cases() -> Vec<Case> {
    let v = Vec3::new;
    vec![
        case(floor(), v(1.0, 1.0, 5.0), 1.0, v(0.0, 0.0, -1.0), 10.0),
        case(floor(), v(1.0, 1.0, -5.0), 0.5, v(0.0, 0.0, 2.0), 10.0),
        case(floor(), v(0.5, 0.5, 3.0), 0.25, v(0.1, 0.2, -1.0), 10.0),
        case(
            Triangle::new(v(2.0, -1.0, 0.0), v(2.0, 3.0, 0.0), v(2.0, 1.0, 4.0)),
            v(-3.0, 1.0, 1.0),
            0.75,
            v(1.0, 0.0, 0.0),
            f32::INFINITY,
        ),
    ]
}

fn rim_cases() -> Vec<Case> {
    let v = Vec3::new;
    vec![
        // Beside the edge y = 0, outside the triangle: touches the edge.
        case(floor(), v(2.0, -0.5, 5.0), 1.0, v(0.0, 0.0, -1.0), 10.0),
        // Beyond the corner at the origin: touches the corner.
        case(floor(), v(-0.6, -0.6, 5.0), 1.0, v(0.0, 0.0, -1.0), 10.0),
        // Rolling flat along the plane into the hypotenuse.
        case(floor(), v(5.0, 5.0, 0.0), 0.5, v(-1.0, -1.0, 0.0), 10.0),
        // Sideways into the corner (4, 0, 0).
        case(floor(), v(9.0, 0.0, 0.3), 0.5, v(-1.0, 0.0, 0.0), 10.0),
        // Passing beside the corner, missing by 0.1.
        case(floor(), v(-1.1, -5.0, 0.0), 1.0, v(0.0, 1.0, 0.0), 10.0),
        // Dropping beside the hypotenuse, missing by a little.
        case(
            floor(),
            v(2.0 + 0.8, 2.0 + 0.8, 4.0),
            1.0,
            v(0.0, 0.0, -1.0),
            10.0,
        ),
    ]
}

fn edge_of_the_rules() -> Vec<Case> {
    let v = Vec3::new;
    vec![
        // Already touching: t = 0, whichever way it moves.
        case(floor(), v(1.0, 1.0, 0.5), 1.0, v(0.0, 0.0, 1.0), 10.0),
        case(floor(), v(1.0, 1.0, 0.5), 1.0, v(0.0, 0.0, -1.0), 10.0),
        // Moving away, never touching.
        case(floor(), v(1.0, 1.0, 3.0), 1.0, v(0.0, 0.0, 1.0), 10.0),
        // Would touch at t = 4, stops at 3.
        case(floor(), v(1.0, 1.0, 5.0), 1.0, v(0.0, 0.0, -1.0), 3.0),
        // Touches exactly at t_max.
        case(floor(), v(1.0, 1.0, 5.0), 1.0, v(0.0, 0.0, -1.0), 4.0),
        // A zero radius: a ray through the face.
        case(floor(), v(1.0, 1.0, 5.0), 0.0, v(0.0, 0.0, -2.0), 10.0),
        // A zero-area triangle (a segment from (0,0,0) to (4,0,0)).
        case(
            Triangle::new(v(0.0, 0.0, 0.0), v(2.0, 0.0, 0.0), v(4.0, 0.0, 0.0)),
            v(1.0, 3.0, 0.0),
            1.0,
            v(0.0, -1.0, 0.0),
            10.0,
        ),
        // A point triangle.
        case(
            Triangle::new(v(1.0, 1.0, 1.0), v(1.0, 1.0, 1.0), v(1.0, 1.0, 1.0)),
            v(1.0, 1.0, 5.0),
            0.5,
            v(0.0, 0.0, -1.0),
            10.0,
        ),
    ]
}

fn random_cases() -> Vec<Case> {
    let mut rng = Rng(0x5EED_0051);
    let mut cases = Vec::new();
    while cases.len() < 600 {
        let a = rng.point(8.0, Vec3::ZERO);
        let tri = Triangle::new(
            a,
            a + rng.point(6.0, Vec3::ZERO),
            a + rng.point(6.0, Vec3::ZERO),
        );
        let centre = rng.point(16.0, Vec3::ZERO);
        let radius = rng.next() * 2.0;
        let aim = a + rng.point(3.0, Vec3::ZERO);
        let dir = (aim - centre) * (0.1 + rng.next() * 0.2);
        let c = case(tri, centre, radius, dir, 10.0);
        let near = |r: f32| {
            ShapeCast::sphere(centre, r, dir, 10.0)
                .map_or(None, |s| tri.cast_hit(&s))
                .is_some()
        };
        if near(radius * 1.001 + 1e-4) == near((radius * 0.999 - 1e-4).max(0.0)) {
            cases.push(c);
        }
    }
    cases
}

/// Plausible wrong answers (for the grader's self-test).
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 5;

    /// Wrong answer `which`:
    /// 1 the plane and the face only (no edges, no corners);
    /// 2 the triangle's bounding box grown by the radius;
    /// 3 the infinite plane (no edges at all);
    /// 4 ignores `t_max`;
    /// 5 refuses a ball that starts in contact (only entries after 0).
    pub fn sphere_cast(
        which: u32,
        tri: &Triangle,
        centre: Vec3,
        radius: f32,
        dir: Vec3,
        t_max: f32,
    ) -> Option<f32> {
        let reference = |t_max: f32| Reference.sphere_cast(tri, centre, radius, dir, t_max);
        let [a, b, c] = tri.v;
        let n = (b - a).cross(c - a).normalize_or_zero();
        // Where the centre crosses the plane offset by the radius towards it.
        let plane = || {
            let (s, v) = (n.dot(centre - a), n.dot(dir));
            if s.abs() <= radius {
                return Some(0.0);
            }
            if v == 0.0 || s * v > 0.0 {
                return None;
            }
            let t = (s.abs() - radius) / v.abs();
            (t <= t_max).then_some(t)
        };
        match which {
            0 => reference(t_max),
            1 => {
                let t = plane()?;
                let p = centre + dir * t - n * n.dot(centre + dir * t - a);
                let inside = [(a, b), (b, c), (c, a)]
                    .iter()
                    .all(|&(p0, p1)| n.dot((p1 - p0).cross(p - p0)) >= 0.0);
                inside.then_some(t)
            }
            2 => {
                let s = ShapeCast::sphere(centre, 0.0, dir, t_max).ok()?;
                let bounds = bvhkit::Primitive::bounds(tri);
                Aabb::new(bounds.min - radius, bounds.max + radius).cast_hit(&s)
            }
            3 => plane(),
            4 => reference(f32::INFINITY),
            _ => reference(t_max).filter(|&t| t > 0.0),
        }
    }
}
