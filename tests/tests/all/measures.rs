//! Every bounding volume's measures and predicates on shapes whose answers
//! are known in closed form: volume, area, size, distance, containment and
//! overlap, with the negative cases (far apart, just apart, touching,
//! nested). The expected values are written out here from geometry, not
//! computed by the code under test, so a broken measure cannot agree with
//! itself (a brute-force reference that shares the predicate would).

use bvhkit::glam::{Mat3, Vec3};
use bvhkit::narrow::Intersects;
use bvhkit::{Aabb, BoundingVolume, Dop14, Obb, Sphere};
use std::f32::consts::PI;

fn close(got: f32, want: f32, what: &str) {
    assert!(
        (got - want).abs() <= 1e-4 * want.abs().max(1.0),
        "{what}: got {got}, want {want}"
    );
}

/// The 8 corners of the box `[c - h, c + h]`.
fn corners(c: Vec3, h: Vec3) -> Vec<Vec3> {
    (0..8)
        .map(|i| {
            c + Vec3::new(
                if i & 1 == 0 { -h.x } else { h.x },
                if i & 2 == 0 { -h.y } else { h.y },
                if i & 4 == 0 { -h.z } else { h.z },
            )
        })
        .collect()
}

#[test]
fn aabb_measures_and_predicates() {
    let c = Vec3::new(10.0, -3.0, 2.0);
    let b = Aabb::fit(corners(c, Vec3::new(1.0, 2.0, 3.0)).as_slice());
    close(b.volume(), 2.0 * 4.0 * 6.0, "volume");
    close(
        b.surface_area(),
        2.0 * (2.0 * 4.0 + 4.0 * 6.0 + 2.0 * 6.0),
        "area",
    );
    close(
        b.half_area(),
        2.0 * 4.0 + 4.0 * 6.0 + 2.0 * 6.0,
        "half area",
    );
    assert_eq!(b.longest_axis(), 2);
    // Distance from outside points: along an axis, and to an edge.
    close(
        b.distance_squared(c + Vec3::new(4.0, 0.0, 0.0)),
        9.0,
        "to a face",
    );
    close(
        b.distance_squared(c + Vec3::new(2.0, 3.0, 0.0)),
        2.0,
        "to an edge",
    );
    close(b.distance_squared(c), 0.0, "inside");
    let shifted = |d: Vec3| Aabb::new(b.min + d, b.max + d);
    // Overlap: apart, just apart, touching, overlapping, nested.
    assert!(!b.overlaps(&shifted(Vec3::new(5.0, 0.0, 0.0))));
    assert!(!b.overlaps(&shifted(Vec3::new(2.001, 0.0, 0.0))));
    assert!(
        b.overlaps(&shifted(Vec3::new(2.0, 0.0, 0.0))),
        "touching faces"
    );
    assert!(
        b.overlaps(&shifted(Vec3::new(2.0, 4.0, 6.0))),
        "touching corners"
    );
    assert!(!b.overlaps(&shifted(Vec3::new(2.0, 4.0, 6.001))));
    let inner = Aabb::new(c - Vec3::splat(0.5), c + Vec3::splat(0.5));
    assert!(b.overlaps(&inner) && inner.overlaps(&b));
    assert!(b.contains(&inner) && !inner.contains(&b));
    assert!(b.contains_point(c + Vec3::new(1.0, 2.0, 3.0)));
    assert!(!b.contains_point(c + Vec3::new(1.0, 2.0, 3.001)));
    // Symmetric in its arguments.
    for d in [Vec3::X * 2.5, Vec3::Y * 3.9, Vec3::new(1.9, -3.9, 5.9)] {
        assert_eq!(b.overlaps(&shifted(d)), shifted(d).overlaps(&b));
    }
}

#[test]
fn sphere_measures_and_predicates() {
    let s = Sphere::new(Vec3::new(1.0, 2.0, 3.0), 2.0);
    close(s.volume(), 4.0 / 3.0 * PI * 8.0, "volume");
    close(s.surface_area(), 4.0 * PI * 4.0, "area");
    let at = |d: Vec3, r: f32| Sphere::new(s.center + d, r);
    // Centres 5 apart: radii 2 + 2.9 apart, 2 + 3 touching, 2 + 3.1 overlapping.
    let d = Vec3::new(3.0, 4.0, 0.0);
    assert!(!s.overlaps(&at(d, 2.9)) && !at(d, 2.9).overlaps(&s));
    assert!(s.overlaps(&at(d, 3.0)), "touching");
    assert!(s.overlaps(&at(d, 3.1)));
    assert!(s.overlaps(&at(Vec3::ZERO, 0.5)) && s.contains(&at(Vec3::ZERO, 0.5)));
    assert!(!at(Vec3::ZERO, 0.5).contains(&s));
    // Against boxes: the nearest box corner at distance sqrt(3) * 1.5 > 2.
    let corner = s.center + Vec3::splat(1.5);
    let far = Aabb::new(corner, corner + Vec3::ONE);
    assert!(!s.overlaps_aabb(&far), "box corner at 2.6 from the centre");
    // A box whose face is 1.9 from the centre, but no corner within 2.
    let face = Aabb::new(
        s.center + Vec3::new(1.9, -5.0, -5.0),
        s.center + Vec3::splat(5.0),
    );
    assert!(s.overlaps_aabb(&face));
    let beyond = Aabb::new(
        s.center + Vec3::new(2.1, -5.0, -5.0),
        s.center + Vec3::splat(5.0),
    );
    assert!(!s.overlaps_aabb(&beyond));
    // The box of a sphere is the cube of side 2r.
    let b = s.aabb();
    close(b.volume(), 64.0, "box of the sphere");
    // The exact sphere-sphere narrow phase, and through references.
    assert!(s.intersects(&at(d, 3.0)) && !s.intersects(&at(d, 2.9)));
    // Through the blanket impl for references (`&Sphere: Intersects<Sphere>`).
    fn by_value<P: Intersects<Q>, Q>(p: P, q: &Q) -> bool {
        p.intersects(q)
    }
    let r: &Sphere = &s;
    assert!(by_value(r, &at(d, 3.0)) && !by_value(r, &at(d, 2.9)));
    // Fits of the unit cube's corners: the smallest enclosing sphere has
    // radius sqrt(3) / 2 (Welzl is exact up to rounding); Ritter's is no smaller.
    let pts = corners(Vec3::new(5.0, 5.0, 5.0), Vec3::splat(0.5));
    let w = Sphere::welzl(pts.as_slice());
    close(w.radius, 3f32.sqrt() / 2.0, "Welzl radius");
    assert!(Sphere::ritter(pts.as_slice()).radius >= w.radius * 0.9999);
}

#[test]
fn obb_measures_and_predicates() {
    // A 2 x 4 x 6 box turned 45 degrees about z.
    let rot = Mat3::from_rotation_z(PI / 4.0);
    let h = Vec3::new(1.0, 2.0, 3.0);
    let c = Vec3::new(-4.0, 1.0, 7.0);
    let pts: Vec<Vec3> = corners(Vec3::ZERO, h)
        .iter()
        .map(|&p| c + rot * p)
        .collect();
    let axes = [rot * Vec3::X, rot * Vec3::Y, Vec3::Z];
    let o = Obb::fit_with_axes(pts.as_slice(), axes);
    close(o.volume(), 48.0, "volume");
    close(o.surface_area(), 2.0 * (8.0 + 24.0 + 12.0), "area");
    // Its axis-aligned box is larger: (1 + 2) * sqrt(2) on x and y.
    let side = 3.0 * 2f32.sqrt();
    close(o.aabb().volume(), side * side * 6.0, "enclosing box");
    assert!(o.contains_point(c) && !o.contains_point(c + axes[0] * 1.01));
    // Another copy moved along its own x axis: apart, touching, overlapping.
    let moved = |k: f32| {
        Obb::fit_with_axes(
            pts.iter()
                .map(|&p| p + axes[0] * k)
                .collect::<Vec<_>>()
                .as_slice(),
            axes,
        )
    };
    assert!(!o.overlaps(&moved(2.05)) && !moved(2.05).overlaps(&o));
    assert!(o.overlaps(&moved(1.95)));
    // Moved by 2.1 along their own x axis, i.e. by (1.48, 1.48, 0): the
    // axis-aligned boxes (4.24 wide) overlap, but the oriented boxes are
    // apart (half extents 1 + 1 < 2.1 along that axis).
    let apart = moved(2.1);
    assert!(o.aabb().overlaps(&apart.aabb()), "the boxes overlap");
    assert!(!o.overlaps(&apart), "the oriented boxes are apart");
}

#[test]
fn kdop_measures_and_predicates() {
    // Two octahedra |x| + |y| + |z| <= 1, one moved by 0.7 on each axis:
    // their boxes overlap ([-1, 1] against [-0.3, 1.7]), but the slab
    // x + y + z separates them (max 1 against min 2.1 - 1 = 1.1).
    let octahedron = |c: Vec3| -> Vec<Vec3> {
        [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z]
            .iter()
            .map(|&d| c + d)
            .collect()
    };
    let a = Dop14::fit(octahedron(Vec3::ZERO).as_slice());
    let b = Dop14::fit(octahedron(Vec3::splat(0.7)).as_slice());
    assert!(a.aabb().overlaps(&b.aabb()));
    assert!(!a.overlaps(&b) && !b.overlaps(&a));
    let c = Dop14::fit(octahedron(Vec3::splat(0.6)).as_slice());
    assert!(a.overlaps(&c), "x + y + z: 1 against 1.8 - 1 = 0.8");
    // The corner (0.9, 0.9, 0) is in the octahedron's box, not in its 14-DOP.
    assert!(!a.contains_point(Vec3::new(0.9, 0.9, 0.0)));
    assert!(a.contains_point(Vec3::new(0.3, 0.3, 0.3)));
    assert!(!a.contains_point(Vec3::new(0.34, 0.34, 0.34)));
    // A cube's 14-DOP is the cube: the diagonal slabs cut nothing off.
    let cube = Dop14::fit(corners(Vec3::new(2.0, 3.0, 4.0), Vec3::splat(0.5)).as_slice());
    close(cube.volume(), 1.0, "cube volume");
    close(cube.surface_area(), 6.0, "cube area");
    // Against a box in the corner region cut off by a diagonal slab.
    let corner_box = Aabb::new(Vec3::new(0.6, 0.6, 0.0), Vec3::new(1.0, 1.0, 0.1));
    assert!(a.aabb().overlaps(&corner_box) && !a.overlaps_aabb(&corner_box));
}

/// The pair stack bound is the largest count of waiting pairs over every
/// split of a path into two-sided and one-sided steps (counted here step by
/// step, not by the formula).
#[test]
fn pair_stack_bound_is_the_worst_path() {
    for ka in [2usize, 4] {
        for kb in [2usize, 4] {
            for da in 0..12 {
                for db in 0..12 {
                    let mut worst = 0;
                    for both in 0..=da.min(db) {
                        let mut waiting = 0;
                        for _ in 0..both {
                            waiting += ka * kb - 1;
                        }
                        for _ in both..da {
                            waiting += ka - 1;
                        }
                        for _ in both..db {
                            waiting += kb - 1;
                        }
                        worst = worst.max(waiting + 1);
                    }
                    assert_eq!(
                        bvhkit::query::pair_stack_bound((ka, da), (kb, db)),
                        worst,
                        "arity {ka}/{kb}, depth {da}/{db}"
                    );
                }
            }
        }
    }
}
