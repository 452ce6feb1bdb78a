//! Triangle contacts: where two triangles meet, checked without the
//! method's own steps: every point of the contact lies on both triangles,
//! every end or corner lies on an edge of one of them (so the contact
//! cannot be extended), and there is a contact exactly when the exact
//! predicate says the triangles touch.

use bvhkit::glam::{DVec3, Vec3};
use bvhkit::narrow::{triangle_contact, triangles_intersect, Contact};
use bvhkit::query::PairDistance;
use bvhkit::Triangle;
use bvhkit_tests::*;
use proptest::prelude::*;

fn corner(r: f32) -> impl Strategy<Value = Vec3> {
    (-r..r, -r..r, -r..r).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// Distance from `p` to the triangle.
fn off(t: &Triangle, p: DVec3) -> f64 {
    p.as_vec3().closest_points(t).distance()
}

/// Distance from `p` to the triangle's three edges.
fn off_edges(t: &Triangle, p: DVec3) -> f64 {
    (0..3)
        .map(|i| {
            let (a, b) = (t.v[i], t.v[(i + 1) % 3]);
            off(&Triangle::new(a, b, b), p)
        })
        .fold(f64::INFINITY, f64::min)
}

fn check(t1: &Triangle, t2: &Triangle) -> Result<(), TestCaseError> {
    let contact = triangle_contact(t1, t2);
    prop_assert_eq!(contact.is_some(), triangles_intersect(t1, t2));
    let Some(contact) = contact else {
        return Ok(());
    };
    // f32 input, f64 arithmetic: a point is "on" within 1e-5 of the unit
    // scale of these scenes (and the f32 rounding of the points themselves
    // when converted back for the distance test).
    let tol = 1e-4;
    for &p in contact.points() {
        prop_assert!(
            off(t1, p) < tol && off(t2, p) < tol,
            "{:?} off a triangle",
            p
        );
    }
    let ends = contact.points();
    let single_point = ends.iter().all(|p| (*p - ends[0]).length() < tol);
    if !single_point {
        for &p in ends {
            prop_assert!(
                off_edges(t1, p).min(off_edges(t2, p)) < tol,
                "{:?}: {:?} is inside both triangles",
                contact,
                p
            );
        }
    }
    if let Contact::Area { len, .. } = contact {
        prop_assert!((1..=6).contains(&len));
    }
    Ok(())
}

proptest! {
    #![proptest_config(proptest_config(200))]

    #[test]
    fn crossing_triangles_share_a_maximal_segment(
        a in corner(3.0), b in corner(3.0), c in corner(3.0),
        p in corner(1.0), q in corner(1.0), r in corner(1.0),
        w in (0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0),
    ) {
        let t1 = Triangle::new(a, b, c);
        // Second triangle around a point of the first, so they often cross.
        let (u, v) = (w.0 * 0.5, w.1 * 0.5);
        let m = a + (b - a) * u + (c - a) * v;
        let t2 = Triangle::new(m + p * 2.0, m + q * 2.0, m + r * 2.0);
        check(&t1, &t2)?;
        check(&t2, &t1)?;
    }

    #[test]
    fn triangles_in_one_plane_share_a_polygon(
        a in corner(3.0), b in corner(3.0), c in corner(3.0),
        d in corner(3.0), e in corner(3.0), f in corner(3.0),
        z in -2.0f32..2.0,
        shared in 0usize..3,
    ) {
        let flat = |p: Vec3| Vec3::new(p.x, p.y, z);
        let t1 = Triangle::new(flat(a), flat(b), flat(c));
        let mut t2 = Triangle::new(flat(d), flat(e), flat(f));
        // Sometimes a shared corner or edge.
        if shared == 1 {
            t2.v[0] = t1.v[0];
        } else if shared == 2 {
            t2.v[0] = t1.v[0];
            t2.v[1] = t1.v[1];
        }
        check(&t1, &t2)?;
        check(&t2, &t1)?;
    }

    #[test]
    fn zero_area_triangles_give_a_common_point(
        a in corner(3.0), b in corner(3.0), c in corner(3.0),
        s in 0.0f32..1.0, p in corner(1.0),
    ) {
        let t1 = Triangle::new(a, b, c);
        // A segment through a point of the first triangle, and a point on it.
        let m = a + (b - a) * (s * 0.5) + (c - a) * (s * 0.4);
        let seg = Triangle::new(m - p, m + p, m + p);
        check(&t1, &seg)?;
        check(&seg, &t1)?;
        let dot = Triangle::new(t1.v[0], t1.v[0], t1.v[0]);
        check(&t1, &dot)?;
    }
}

#[test]
fn a_triangle_inside_another_is_the_contact() {
    let big = Triangle::new(
        Vec3::ZERO,
        Vec3::new(8.0, 0.0, 0.0),
        Vec3::new(0.0, 8.0, 0.0),
    );
    let small = Triangle::new(
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(2.0, 1.0, 0.0),
        Vec3::new(1.0, 2.0, 0.0),
    );
    let Some(Contact::Area { corners, len }) = triangle_contact(&small, &big) else {
        panic!("coplanar overlap is an area")
    };
    assert_eq!(len, 3);
    assert_eq!(&corners[..3], &small.v.map(|v| v.as_dvec3()));
    // Sharing only an edge: a degenerate polygon along it (two corners).
    let beside = Triangle::new(
        Vec3::ZERO,
        Vec3::new(8.0, 0.0, 0.0),
        Vec3::new(0.0, -8.0, 0.0),
    );
    let c = triangle_contact(&big, &beside).unwrap();
    assert!(c.points().iter().all(|p| p.y == 0.0 && p.z == 0.0), "{c:?}");
    // Apart by one f32 step: nothing.
    let up = Triangle::new(
        Vec3::new(1.0, 1.0, 1e-7),
        Vec3::new(2.0, 1.0, 1e-7),
        Vec3::new(1.0, 2.0, 1e-7),
    );
    assert_eq!(triangle_contact(&big, &up), None);
}

mod solids {
    use bvhkit::glam::{DVec3, Vec3};
    use bvhkit::narrow::{Penetrate, Penetration};
    use bvhkit::{Aabb, Sphere};
    use bvhkit_tests::*;
    use proptest::prelude::*;

    #[derive(Clone, Copy, Debug)]
    enum Shape {
        Box(Aabb),
        Ball(Sphere),
    }

    impl Shape {
        /// Whether `self` overlaps `other` moved by `t` (touching counts),
        /// in `f64`, written apart from the method under test.
        fn overlaps_moved(&self, other: &Shape, t: DVec3) -> bool {
            let box_ball = |b: &Aabb, c: DVec3, r: f64| {
                let q = c.clamp(b.min.as_dvec3(), b.max.as_dvec3());
                (c - q).length() <= r
            };
            match (self, other) {
                (Shape::Box(a), Shape::Box(b)) => (0..3).all(|k| {
                    a.max.as_dvec3()[k] >= b.min.as_dvec3()[k] + t[k]
                        && b.max.as_dvec3()[k] + t[k] >= a.min.as_dvec3()[k]
                }),
                (Shape::Ball(a), Shape::Ball(b)) => {
                    (b.center.as_dvec3() + t - a.center.as_dvec3()).length()
                        <= a.radius as f64 + b.radius as f64
                }
                (Shape::Box(a), Shape::Ball(b)) => {
                    box_ball(a, b.center.as_dvec3() + t, b.radius as f64)
                }
                (Shape::Ball(a), Shape::Box(b)) => {
                    box_ball(b, a.center.as_dvec3() - t, a.radius as f64)
                }
            }
        }

        /// How far `p` lies outside the solid (0 inside).
        fn outside(&self, p: DVec3) -> f64 {
            match self {
                Shape::Box(b) => (p - p.clamp(b.min.as_dvec3(), b.max.as_dvec3())).length(),
                Shape::Ball(s) => ((p - s.center.as_dvec3()).length() - s.radius as f64).max(0.0),
            }
        }
    }

    fn penetration(a: &Shape, b: &Shape) -> Option<Penetration> {
        match (a, b) {
            (Shape::Box(a), Shape::Box(b)) => a.penetration(b),
            (Shape::Ball(a), Shape::Ball(b)) => a.penetration(b),
            (Shape::Box(a), Shape::Ball(b)) => a.penetration(b),
            (Shape::Ball(a), Shape::Box(b)) => a.penetration(b),
        }
    }

    fn shape() -> impl Strategy<Value = Shape> {
        let v = |r: f32| (-r..r, -r..r, -r..r).prop_map(|(x, y, z)| Vec3::new(x, y, z));
        prop_oneof![
            (v(2.0), (0.0f32..2.0, 0.0f32..2.0, 0.0f32..2.0))
                .prop_map(|(o, e)| Shape::Box(Aabb::new(o, o + Vec3::from(e)))),
            (v(2.0), 0.0f32..1.5).prop_map(|(c, r)| Shape::Ball(Sphere {
                center: c,
                radius: r
            })),
        ]
    }

    proptest! {
        #![proptest_config(proptest_config(300))]

        /// A contact exactly when the solids overlap; moving the second by
        /// a hair more than the depth along the normal separates them; no
        /// move shorter than the depth, in any of 26 directions, does.
        #[test]
        fn the_depth_is_the_least_move_that_separates(pair in prop_oneof![
            3 => (shape(), shape()),
            // A ball centred inside a box, either way round: rarer above.
            1 => (shape(), (0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0), 0.0f32..1.5, any::<bool>()).prop_map(|(s, f, r, swap)| {
                let b = match s {
                    Shape::Box(b) => b,
                    Shape::Ball(s) => Aabb::new(s.center, s.center + Vec3::splat(1.0 + s.radius)),
                };
                let ball = Shape::Ball(Sphere { center: b.min + (b.max - b.min) * Vec3::from(f), radius: r });
                if swap { (ball, Shape::Box(b)) } else { (Shape::Box(b), ball) }
            }),
        ]) {
            let (a, b) = pair;
            let p = penetration(&a, &b);
            prop_assert_eq!(p.is_some(), a.overlaps_moved(&b, DVec3::ZERO), "{:?}", p);
            let Some(p) = p else { return Ok(()) };
            prop_assert!((p.normal.length() - 1.0).abs() < 1e-12 && p.depth >= 0.0);
            let eps = 1e-6;
            prop_assert!(!a.overlaps_moved(&b, p.normal * (p.depth + eps)), "{:?} does not separate", p);
            // The point is halfway between the surfaces: at most half the
            // depth outside either solid.
            prop_assert!(a.outside(p.point).max(b.outside(p.point)) <= p.depth / 2.0 + eps, "{:?}", p);
            if p.depth > eps {
                for x in -1..=1 {
                    for y in -1..=1 {
                        for z in -1..=1 {
                            let u = DVec3::new(x as f64, y as f64, z as f64);
                            if u == DVec3::ZERO {
                                continue;
                            }
                            let u = u.normalize();
                            prop_assert!(
                                a.overlaps_moved(&b, u * (p.depth - eps)),
                                "{:?}: a shorter move along {} separates",
                                p,
                                u
                            );
                        }
                    }
                }
            }
        }
    }
}
