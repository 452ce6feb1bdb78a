//! Distance queries (closest pair, pairs within a distance) against brute
//! force: every volume type, mixed volume types, a tree against itself,
//! points against triangles, the dynamic tree, and bad arguments.

use bvhkit::builders::{DynNode, DynamicConfig, DynamicTree, LeafHandle};
use bvhkit::glam::Vec3;
use bvhkit::query::{Distance, PairDistance};
use bvhkit::{Aabb, Dop14, Error, Node, Obb, Primitive, Sphere, TopDown, Triangle};
use bvhkit_tests::*;
use proptest::prelude::*;

type Corner = (f32, f32, f32);

/// A radius that catches some pairs: a fraction of the scene's size.
fn radius(prims: &[Triangle], f: f32) -> f64 {
    let b = prims.iter().fold(Aabb::EMPTY, |b, t| b.union(&t.bounds()));
    (b.max.as_dvec3() - b.min.as_dvec3()).length() * f as f64 * 0.3
}

proptest! {
    #![proptest_config(proptest_config(24))]

    #[test]
    fn closest_pair_and_pairs_within_equal_brute_force(
        cfg in any_top_down(),
        a in scene(40),
        b in scene(40),
        f in 0.0f32..1.0,
    ) {
        let r = radius(&a, f);
        macro_rules! same_volume {
            ($($bv:ty),*) => {$(
                let (na, ia, _) = build::<$bv, _>(&cfg, &a).unwrap();
                let (nb, ib, _) = build::<$bv, _>(&cfg, &b).unwrap();
                let (ta, tb) = (open(&na, &ia, &a), open(&nb, &ib, &b));
                check_distance(&ta, &a, &tb, &b, r, &(&cfg, stringify!($bv)))?;
                // A tree against itself: every primitive touches itself.
                check_distance(&ta, &a, &ta, &a, r, &(&cfg, stringify!($bv), "self"))?;
            )*};
        }
        same_volume!(Aabb, Sphere, Obb, Dop14);
        // Different volume types on the two sides.
        let (na, ia, _) = build::<Aabb, _>(&cfg, &a).unwrap();
        let (nb, ib, _) = build::<Sphere, _>(&cfg, &b).unwrap();
        check_distance(&open(&na, &ia, &a), &a, &open(&nb, &ib, &b), &b, r, &(&cfg, "box x sphere"))?;
    }

    #[test]
    fn points_against_triangles_and_points(
        a in scene(30),
        b in scene(30),
        f in 0.0f32..1.0,
    ) {
        let points: Vec<Vec3> = a.iter().map(|t| t.v[(t.v[0].x.to_bits() % 3) as usize]).collect();
        let r = radius(&a, f);
        let cfg = TopDown::default();
        let (np, ip, _) = build::<Aabb, _>(&cfg, &points).unwrap();
        let (nb, ib, _) = build::<Aabb, _>(&cfg, &b).unwrap();
        let (tp, tb) = (open(&np, &ip, &points), open(&nb, &ib, &b));
        check_distance(&tp, &points, &tb, &b, r, &"points x triangles")?;
        check_distance(&tb, &b, &tp, &points, r, &"triangles x points")?;
        check_distance(&tp, &points, &tp, &points, r, &"points x points")?;
    }

    #[test]
    fn a_dynamic_tree_of_boxes_against_a_built_one(
        boxes in prop::collection::vec(
            ((-10.0f32..10.0, -10.0f32..10.0, -10.0f32..10.0), (0.0f32..2.0, 0.0f32..2.0, 0.0f32..2.0)),
            0..50,
        ),
        others in prop::collection::vec(
            ((-10.0f32..10.0, -10.0f32..10.0, -10.0f32..10.0), (0.0f32..2.0, 0.0f32..2.0, 0.0f32..2.0)),
            0..30,
        ),
        removed in prop::collection::vec(any::<bool>(), 50),
        f in 0.0f32..1.0,
    ) {
        let to_boxes = |v: Vec<(Corner, Corner)>| -> Vec<Aabb> {
            v.into_iter()
                .map(|(o, e)| {
                    let o = Vec3::from(o);
                    Aabb::new(o, o + Vec3::from(e))
                })
                .collect()
        };
        let (boxes, bb) = (to_boxes(boxes), to_boxes(others));
        let mut storage = vec![DynNode::<Aabb>::EMPTY; 2 * boxes.len().max(1)];
        let mut tree = DynamicTree::new(&mut storage, DynamicConfig::default()).unwrap();
        let handles: Vec<LeafHandle> = (0..boxes.len() as u32).map(|i| tree.insert(i, &boxes[i as usize]).unwrap()).collect();
        // Removed boxes are absent from the tree: brute force sees them far away.
        let mut live = boxes.clone();
        for (i, h) in handles.iter().enumerate() {
            if removed[i] {
                tree.remove(*h).unwrap();
                live[i] = Aabb::new(Vec3::splat(1e6), Vec3::splat(1e6));
            }
        }
        let (nb, ib, _) = build::<Aabb, _>(&TopDown::default(), &bb).unwrap();
        let tb = open(&nb, &ib, &bb);
        // Only pairs with live boxes may answer; the far stand-ins are
        // farther than the radius (at most 11) and any live pair (at most 40).
        let r = 35.0 * f as f64 * 0.3;
        if live.iter().any(|b| b.min.x < 1e5) {
            check_distance(&tree, &live, &tb, &bb, r, &"dynamic x built")?;
        } else {
            prop_assert_eq!(Distance::new(&tree, &live, &tb, &bb).closest().unwrap(), None);
        }
    }
}

#[test]
fn empty_trees_answer_nothing_and_bad_distances_are_errors() {
    let tris = [Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y)];
    let none: [Triangle; 0] = [];
    let mut nodes = [Node::<Aabb>::EMPTY; 2];
    let (n1, n2) = nodes.split_at_mut(1);
    let (mut i1, mut i2) = ([0u32; 1], [0u32; 0]);
    let one = TopDown::default().build(&tris, n1, &mut i1).unwrap();
    let empty = TopDown::default().build(&none, n2, &mut i2).unwrap();
    assert_eq!(
        Distance::new(&one, &tris, &empty, &none).closest(),
        Ok(None)
    );
    assert_eq!(
        Distance::new(&empty, &none, &one, &tris).within(1.0, |_, _| panic!()),
        Ok(0)
    );
    for bad in [f64::NAN, -1.0, f64::INFINITY] {
        assert!(matches!(
            Distance::new(&one, &tris, &one, &tris).within(bad, |_, _| {}),
            Err(Error::InvalidQuery(_))
        ));
    }
    // A slice that is not the tree's: an error, not a panic.
    assert!(matches!(
        Distance::new(&one, &tris, &one, &none).closest(),
        Err(Error::PrimitiveCountMismatch { .. })
    ));
    let c = Distance::new(&one, &tris, &one, &tris)
        .closest()
        .unwrap()
        .unwrap();
    assert_eq!((c.a, c.b, c.distance()), (0, 0, 0.0));
}

#[test]
fn far_from_the_origin_the_closest_pair_is_still_exact() {
    // Two strips 1e-3 apart at 3e4 from the origin, where an f32 step is
    // about 2e-3: the bound's margin must not prune the true pair.
    let o = Vec3::splat(30_000.0);
    let strip = |dz: f32| -> Vec<Triangle> {
        (0..64)
            .map(|i| {
                let p = o + Vec3::new(i as f32 * 0.5, 0.0, dz);
                Triangle::new(p, p + Vec3::X * 0.5, p + Vec3::Y)
            })
            .collect()
    };
    let (a, b) = (strip(0.0), strip(0.004));
    let (na, ia, _) = build::<Aabb, _>(&TopDown::default(), &a).unwrap();
    let (nb, ib, _) = build::<Aabb, _>(&TopDown::default(), &b).unwrap();
    let (ta, tb) = (open(&na, &ia, &a), open(&nb, &ib, &b));
    let n = check_distance(&ta, &a, &tb, &b, 0.01, &"far").unwrap();
    assert_eq!(n, 4);
    let c = Distance::new(&ta, &a, &tb, &b).closest().unwrap().unwrap();
    let want = (b[0].v[0].z - a[0].v[0].z) as f64;
    assert!((c.distance() - want).abs() < 1e-9, "{c:?}");
    // Every strip triangle has a partner straight above it.
    assert!(
        Distance::new(&ta, &a, &tb, &b)
            .within(want, |_, _| {})
            .unwrap()
            >= 64
    );
}

#[test]
fn the_closest_pair_points_lie_on_their_triangles() {
    let a: Vec<Triangle> = (0..30)
        .map(|i| {
            let p = Vec3::new((i % 6) as f32 * 2.0, (i / 6) as f32 * 2.0, 0.0);
            Triangle::new(p, p + Vec3::X, p + Vec3::Y)
        })
        .collect();
    let b: Vec<Triangle> = a
        .iter()
        .map(|t| t.translated(Vec3::new(0.2, 0.1, 1.5)))
        .collect();
    let (na, ia, _) = build::<Aabb, _>(&TopDown::default(), &a).unwrap();
    let (nb, ib, _) = build::<Aabb, _>(&TopDown::default(), &b).unwrap();
    let c = Distance::new(&open(&na, &ia, &a), &a, &open(&nb, &ib, &b), &b)
        .closest()
        .unwrap()
        .unwrap();
    assert!((c.distance() - 1.5).abs() < 1e-6);
    assert_eq!(c.points.on_a.z, 0.0);
    assert!((c.points.on_b.z - 1.5).abs() < 1e-6);
    // The points are on their triangles: distance to each is zero.
    let on = |t: &Triangle, p: bvhkit::glam::DVec3| p.as_vec3().closest_points(t).distance() < 1e-6;
    assert!(on(&a[c.a as usize], c.points.on_a) && on(&b[c.b as usize], c.points.on_b));
}

fn corner() -> impl Strategy<Value = Vec3> {
    (-3.0f32..3.0, -3.0f32..3.0, -3.0f32..3.0).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// Points of `t` on a barycentric grid (`n` steps per edge).
fn samples(t: &Triangle, n: u32) -> Vec<bvhkit::glam::DVec3> {
    let [a, b, c] = t.v.map(|v| v.as_dvec3());
    let mut out = Vec::new();
    for i in 0..=n {
        for j in 0..=n - i {
            let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
            out.push(a + (b - a) * u + (c - a) * v);
        }
    }
    out
}

proptest! {
    #![proptest_config(proptest_config(48))]

    /// The triangle distance checked independently of its own method: the
    /// two points lie on their triangles (so the distance is at least the
    /// true one), no sampled pair of points is closer (so it is at most the
    /// true one, up to rounding), and it is zero exactly when the triangles
    /// meet by the exact predicate.
    #[test]
    fn triangle_distance_is_the_least_over_sampled_points(
        t1 in (corner(), corner(), corner()),
        t2 in (corner(), corner(), corner()),
        flat in any::<bool>(),
    ) {
        let t1 = Triangle::new(t1.0, t1.1, t1.2);
        // Half the cases put the second triangle in the first one's plane
        // (overlap and touching without crossing).
        let t2 = if flat {
            let [a, b, c] = t1.v;
            Triangle::new(a + (b - a) * t2.0.x * 0.5 + (c - a) * t2.0.y * 0.5, a + (b - a) * t2.1.x + (c - a) * t2.1.y, a + (b - a) * t2.2.x + (c - a) * t2.2.y)
        } else {
            Triangle::new(t2.0, t2.1, t2.2)
        };
        let c = t1.closest_points(&t2);
        let on = |t: &Triangle, p: bvhkit::glam::DVec3| {
            let d = p.as_vec3().closest_points(t).distance();
            d < 1e-5
        };
        prop_assert!(on(&t1, c.on_a) && on(&t2, c.on_b), "{:?}", c);
        prop_assert_eq!(c.distance_squared == 0.0, bvhkit::narrow::triangles_intersect(&t1, &t2));
        let (s1, s2) = (samples(&t1, 12), samples(&t2, 12));
        let sampled = s1
            .iter()
            .flat_map(|p| s2.iter().map(move |q| (*p - *q).length()))
            .fold(f64::INFINITY, f64::min);
        prop_assert!(c.distance() <= sampled + 1e-5, "{} > sampled {}", c.distance(), sampled);
        // Symmetric up to rounding (the two orders round differently).
        let back = t2.closest_points(&t1).distance_squared;
        prop_assert!((c.distance_squared - back).abs() <= 1e-12 * c.distance_squared.max(1.0));
    }
}

/// B measured through a rigid motion (no rebuild) against brute force over
/// B's primitives placed by the same motion.
fn check_moved<A: bvhkit::Hierarchy, H: bvhkit::Hierarchy>(
    ta: &A,
    a: &[Triangle],
    tb: &H,
    b: &[Triangle],
    motion: bvhkit::Rigid,
    radius: f64,
) -> Result<(), TestCaseError> {
    use bvhkit::Place;
    let placed: Vec<Triangle> = b.iter().map(|t| motion.place(t)).collect();
    let want = bvhkit::brute_force::closest_pair(a, &placed);
    let got = Distance::new(ta, a, tb, b)
        .in_frame(motion)
        .closest()
        .unwrap();
    prop_assert_eq!(
        got.map(|c| c.points.distance_squared),
        want.map(|c| c.points.distance_squared)
    );
    if let Some(g) = got {
        prop_assert_eq!(
            a[g.a as usize].closest_points(&placed[g.b as usize]),
            g.points
        );
    }
    for d in [0.0, radius] {
        let mut expect = Vec::new();
        bvhkit::brute_force::pairs_within(a, &placed, d, |i, j| expect.push((i, j)));
        let mut found = Vec::new();
        Distance::new(ta, a, tb, b)
            .in_frame(motion)
            .within(d, |i, j| found.push((i, j)))
            .unwrap();
        found.sort_unstable();
        prop_assert_eq!(found, expect, "within {}", d);
    }
    Ok(())
}

proptest! {
    #![proptest_config(proptest_config(24))]

    #[test]
    fn b_through_a_rigid_motion_equals_brute_force_over_placed_b(
        cfg in any_top_down(),
        a in scene(40),
        b in scene(40),
        angle in -3.0f32..3.0,
        axis in (-1.0f32..1.0, -1.0f32..1.0, 0.1f32..1.0),
        shift in (-3.0f32..3.0, -3.0f32..3.0, -3.0f32..3.0),
        f in 0.0f32..1.0,
    ) {
        let rotation = bvhkit::glam::Quat::from_axis_angle(Vec3::from(axis).normalize(), angle);
        // The shift in the scene's own scale (scenes sit in frames up to 1e30).
        let size = radius(&a, 1.0 / 0.3) as f32;
        let Ok(motion) = bvhkit::Rigid::new(rotation, Vec3::from(shift) * size.min(1e30) * 0.1) else {
            return Ok(());
        };
        let r = radius(&a, f);
        macro_rules! each_volume {
            ($($bv:ty),*) => {$(
                let (na, ia, _) = build::<$bv, _>(&cfg, &a).unwrap();
                let (nb, ib, _) = build::<$bv, _>(&cfg, &b).unwrap();
                check_moved(&open(&na, &ia, &a), &a, &open(&nb, &ib, &b), &b, motion, r)?;
            )*};
        }
        each_volume!(Aabb, Sphere, Obb);
    }
}

/// A corner on a small integer grid (so that triangles are often flat,
/// collinear or repeat a corner), scaled.
fn grid_point(scale: f32) -> impl Strategy<Value = Vec3> {
    (-3i32..4, -3i32..4, -3i32..4)
        .prop_map(move |(x, y, z)| Vec3::new(x as f32, y as f32, z as f32) * scale)
}

proptest! {
    #![proptest_config(proptest_config(256))]

    /// `Triangle::closest_point` against sampling: its point is on the
    /// triangle (its barycentric coordinates rebuild it), no sample of the
    /// triangle is closer, its feature agrees with its coordinates, and it
    /// is the point and distance the distance queries use.
    #[test]
    fn closest_point_on_a_triangle_is_closest_and_names_its_feature(
        scale in prop_oneof![Just(1.0f32), Just(0.01), Just(250.0)],
        a in grid_point(1.0), b in grid_point(1.0), c in grid_point(1.0),
        p in (-5.0f32..5.0, -5.0f32..5.0, -5.0f32..5.0),
    ) {
        use bvhkit::glam::DVec3;
        use bvhkit::{PointDistance, TriangleFeature};
        let t = Triangle::new(a * scale, b * scale, c * scale);
        let p = Vec3::new(p.0, p.1, p.2) * scale;
        let got = t.closest_point(p);
        let v = t.v.map(|x| x.as_dvec3());
        let size = v.iter().fold(1.0f64, |m, x| m.max(x.abs().max_element())) + p.abs().max_element() as f64;
        let tol = size * 1e-9;

        // The same point and distance as the distance queries.
        prop_assert_eq!(got.point, p.closest_points(&t).on_b);
        prop_assert_eq!(got.distance_squared, t.distance_squared(p));
        prop_assert_eq!(got.distance_squared, (got.point - p.as_dvec3()).length_squared());

        // On the triangle.
        let w = got.barycentric;
        prop_assert!(w.min_element() >= -1e-12 && w.max_element() <= 1.0 + 1e-12, "{:?}", w);
        prop_assert!((w.element_sum() - 1.0).abs() < 1e-9, "{:?}", w);
        let rebuilt = v[0] * w.x + v[1] * w.y + v[2] * w.z;
        prop_assert!((rebuilt - got.point).abs().max_element() <= tol, "{:?} {:?}", rebuilt, got.point);

        // The feature agrees with the coordinates.
        match got.feature {
            TriangleFeature::Vertex(k) => {
                prop_assert_eq!(got.point, v[k as usize]);
                prop_assert_eq!(w[k as usize], 1.0);
            }
            TriangleFeature::Edge(k) => prop_assert_eq!(w[(k as usize + 2) % 3], 0.0),
            TriangleFeature::Face => prop_assert!(w.min_element() >= 0.0, "{:?}", w),
        }

        // No sample of the triangle is closer (sampling: a 24 x 24
        // barycentric grid, which includes the corners and the edges).
        let q = p.as_dvec3();
        let n = 24;
        for i in 0..=n {
            for j in 0..=n - i {
                let (s, r) = (i as f64 / n as f64, j as f64 / n as f64);
                let x: DVec3 = v[0] * (1.0 - s - r) + v[1] * s + v[2] * r;
                let d = (x - q).length_squared();
                prop_assert!(got.distance_squared <= d + tol * size, "sample {:?} at {} < {}", x, d, got.distance_squared);
            }
        }
    }
}
