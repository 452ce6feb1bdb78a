//! Single-tree queries against brute force: region search in every order,
//! ray casts (closest and any hit, depth- and best-first), and nearest
//! primitive, for every volume type and random builder configurations.

use bvhkit::glam::Vec3;
use bvhkit::{
    brute_force, Aabb, BoundingVolume, Counts, Dop14, Obb, Order, Ray, RayOrder, Sphere, TopDown,
    Triangle,
};
use bvhkit_tests::*;
use proptest::prelude::*;

fn direction() -> impl Strategy<Value = Vec3> {
    prop_oneof![
        // Axis-parallel rays: two direction components are exactly zero.
        (0..6usize).prop_map(|k| {
            let mut d = Vec3::ZERO;
            d[k % 3] = if k < 3 { 1.0 } else { -1.0 };
            d
        }),
        // One zero component.
        (-1.0f32..1.0, -1.0f32..1.0).prop_map(|(x, y)| Vec3::new(x, y, 0.0) + Vec3::X * 1e-3),
        (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0)
            .prop_map(|(x, y, z)| Vec3::new(x, y, z) + Vec3::splat(1e-3)),
    ]
}

fn check<B: BoundingVolume>(
    cfg: &TopDown,
    prims: &[Triangle],
    probe: (f32, f32, f32),
    dir: Vec3,
    t_max: Option<f32>,
) -> Result<(), TestCaseError> {
    let (nodes, idx, _) =
        build::<B, _>(cfg, prims).map_err(|e| TestCaseError::fail(format!("{e}")))?;
    let tree = open(&nodes, &idx, prims);
    let bounds = region_in(prims, 0.0, 1.0);
    // A probe point in (or just outside) the scene's box; snapped to a
    // primitive corner one time in four, so rays graze edges and faces.
    let mut point =
        bounds.min + bounds.extent() * (Vec3::new(probe.0, probe.1, probe.2) * 1.2 - 0.1);
    if probe.0 < 0.25 {
        point = prims[(probe.1 * prims.len() as f32) as usize % prims.len()].v[0];
    }

    // Region search: every order, same set as brute force.
    let region = region_in(prims, probe.0.min(probe.1), probe.0.max(probe.1));
    let mut want = Vec::new();
    brute_force::overlapping(prims, &region, |i| want.push(i));
    let mut queue = vec![0u32; tree.breadth_first_queue()];
    for order in [
        Order::DepthFirst,
        Order::Recursive,
        Order::BreadthFirst(&mut queue),
    ] {
        let name = format!("{order:?}");
        let mut got = Vec::new();
        let mut counts = Counts::default();
        let n = tree
            .search(prims, &region, order, &mut counts, |i| got.push(i))
            .unwrap();
        got.sort_unstable();
        prop_assert_eq!(n, got.len());
        prop_assert_eq!(&got, &want, "{} search on {} tree {:?}", name, B::NAME, cfg);
        prop_assert!(counts.bv_tests >= 1);
    }
    let mut tiny = [0u32; 0];
    let too_small = tree.search(prims, &region, Order::BreadthFirst(&mut tiny), (), |_| {});
    prop_assert!(too_small.is_err());

    // Rays.
    let ray = Ray::new(
        point - dir * bounds.extent().max_element() * 0.3,
        dir,
        t_max.unwrap_or(f32::INFINITY),
    )
    .unwrap();
    let want = brute_force::ray_closest(prims, &ray);
    for order in [RayOrder::DepthFirst, RayOrder::BestFirst] {
        let got = tree.cast_ray(prims, &ray, order, ()).unwrap();
        prop_assert_eq!(
            got,
            want,
            "{:?} ray on {} tree {:?} {:?}",
            order,
            B::NAME,
            cfg,
            ray
        );
    }
    let size = bounds.extent().max_element() * 0.1 * probe.2;
    check_casts(&tree, prims, ray.origin(), dir, size, ray.t_max(), B::NAME)?;
    let any = tree.ray_hits_any(prims, &ray, ()).unwrap();
    prop_assert_eq!(any.is_some(), want.is_some());
    if let Some(h) = any {
        prop_assert_eq!(
            bvhkit::RayTarget::ray_hit(&prims[h.prim as usize], &ray),
            Some(h.t)
        );
    }

    // Nearest primitive.
    let want = brute_force::nearest(prims, point);
    let got = tree.nearest(prims, point, ()).unwrap();
    prop_assert_eq!(got, want, "nearest on {} tree {:?}", B::NAME, cfg);
    Ok(())
}

fn t_max() -> impl Strategy<Value = Option<f32>> {
    prop_oneof![Just(None), (0.0f32..100.0).prop_map(Some)]
}

proptest! {
    #![proptest_config(proptest_config(64))]

    #[test]
    fn single_tree_queries_match_brute_force(
        cfg in any_top_down(), prims in scene(50),
        probe in (0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0), dir in direction(), t in t_max(),
    ) {
        check::<Aabb>(&cfg, &prims, probe, dir, t)?;
        check::<Sphere>(&cfg, &prims, probe, dir, t)?;
        check::<Obb>(&cfg, &prims, probe, dir, t)?;
        check::<Dop14>(&cfg, &prims, probe, dir, t)?;
    }

    /// Integer grids: rays start on slab planes and run along box faces.
    #[test]
    fn grid_rays_graze_exactly(
        tris in prop::collection::vec(
            ((-3i32..3, -3i32..3, -3i32..3), 0..3usize).prop_map(|((x, y, z), k)| {
                let o = Vec3::new(x as f32, y as f32, z as f32);
                let (u, v) = (Vec3::AXES[(k + 1) % 3], Vec3::AXES[(k + 2) % 3]);
                Triangle::new(o, o + u, o + v)
            }), 1..40),
        origin in (-4i32..4, -4i32..4, -4i32..4), axis in 0..6usize,
    ) {
        let tree_cfg = TopDown::default().with_max_leaf_size(1);
        let (nodes, idx, _) = build::<Aabb, _>(&tree_cfg, &tris).unwrap();
        let tree = open(&nodes, &idx, &tris);
        let mut dir = Vec3::ZERO;
        dir[axis % 3] = if axis < 3 { 1.0 } else { -1.0 };
        let o = Vec3::new(origin.0 as f32, origin.1 as f32, origin.2 as f32) + Vec3::splat(0.25) - dir * 0.25;
        let ray = Ray::new(o, dir, f32::INFINITY).unwrap();
        let want = brute_force::ray_closest(&tris, &ray);
        prop_assert_eq!(tree.cast_ray(&tris, &ray, RayOrder::DepthFirst, ()).unwrap(), want);
        prop_assert_eq!(tree.cast_ray(&tris, &ray, RayOrder::BestFirst, ()).unwrap(), want);
    }
}

/// Equidistant points defeat pruning, so the best-first queue (64 entries)
/// overflows and the depth-first fallback must keep the answer exact.
#[test]
fn best_first_queue_overflow_keeps_the_answer() {
    let n = 4000;
    let pts: Vec<Vec3> = (0..n)
        .map(|i| {
            let t = i as f32 * 2.399_963;
            let z = 1.0 - 2.0 * (i as f32 + 0.5) / n as f32;
            let r = (1.0 - z * z).sqrt();
            Vec3::new(r * t.cos(), r * t.sin(), z) * 100.0
        })
        .collect();
    let (nodes, idx, _) = build::<Sphere, _>(&TopDown::default(), &pts).unwrap();
    let tree = open(&nodes, &idx, &pts);
    for probe in [Vec3::ZERO, Vec3::new(1.0, 2.0, 3.0), Vec3::splat(200.0)] {
        let mut counts = Counts::default();
        let got = tree.nearest(&pts, probe, &mut counts).unwrap();
        assert_eq!(got, brute_force::nearest(&pts, probe), "probe {probe}");
        assert!(counts.prim_tests > 0);
    }
    // Rays through the centre: every box is entered at nearly the same t.
    let tris: Vec<Triangle> = pts
        .iter()
        .map(|&p| Triangle::new(p, p + Vec3::X, p + Vec3::Y))
        .collect();
    let (nodes, idx, _) = build::<Aabb, _>(&TopDown::default(), &tris).unwrap();
    let tree = open(&nodes, &idx, &tris);
    let ray = Ray::new(Vec3::new(0.3, 0.2, -500.0), Vec3::Z, f32::INFINITY).unwrap();
    assert_eq!(
        tree.cast_ray(&tris, &ray, RayOrder::BestFirst, ()).unwrap(),
        brute_force::ray_closest(&tris, &ray)
    );
}

#[test]
fn bad_rays_and_points_are_errors() {
    assert!(Ray::new(Vec3::ZERO, Vec3::ZERO, 1.0).is_err());
    assert!(Ray::new(Vec3::NAN, Vec3::X, 1.0).is_err());
    assert!(Ray::new(Vec3::ZERO, Vec3::X, f32::NAN).is_err());
    assert!(Ray::new(Vec3::ZERO, Vec3::X, -1.0).is_err());
    let pts = [Vec3::ZERO, Vec3::ONE];
    let (nodes, idx, _) = build::<Aabb, _>(&TopDown::default(), &pts).unwrap();
    let tree = open(&nodes, &idx, &pts);
    assert!(tree.nearest(&pts, Vec3::INFINITY, ()).is_err());
    assert!(
        tree.nearest(&pts[..1], Vec3::ZERO, ()).is_err(),
        "wrong primitive slice"
    );
}

/// Found by fuzzing (`scripts/fuzz`, target `build_query`): a ray running
/// along an edge of a triangle, in its plane, made the f64 Möller–Trumbore
/// test report a hit at t = 0, 2 mm away from the triangle (outside its
/// box), so brute force and the tree (which pruned that box) disagreed. A
/// hit now lies in the triangle's box, and both answer alike.
#[test]
fn a_ray_in_a_triangles_plane_never_hits_outside_its_box() {
    use bvhkit::glam::Vec3;
    use bvhkit::{brute_force, Aabb, Ray, RayOrder, Triangle};
    let tris = [
        Triangle::new(
            Vec3::new(-1.5625e-7, -0.0040960936, -0.0018957813),
            Vec3::new(-0.0018874999, -0.0018874999, -0.0018874999),
            Vec3::new(-1.5625e-7, -1.5625e-7, -1.5625e-7),
        ),
        Triangle::new(
            Vec3::new(-1.5625e-7, -1.5625e-7, -1.6093749e-5),
            Vec3::new(-0.0040801563, -0.0040960936, -0.0040960936),
            Vec3::new(-0.0040960936, -0.0040960936, -0.0040960936),
        ),
    ];
    let ray = Ray::new(
        Vec3::splat(-0.0040960936),
        Vec3::splat(0.004095937),
        f32::INFINITY,
    )
    .unwrap();
    let want = brute_force::ray_closest(&tris, &ray);
    for builder in bvhkit_std::builders::catalogue() {
        let tree = builder.2.build::<Aabb>(&tris).unwrap();
        let got = tree
            .view()
            .cast_ray(&tris, &ray, RayOrder::DepthFirst, ())
            .unwrap();
        assert_eq!(got.map(|h| h.t), want.map(|h| h.t), "{}", builder.0);
    }
    // Any hit on the first triangle lies in its box.
    if let Some(t) = bvhkit::RayTarget::ray_hit(&tris[0], &ray) {
        let p = ray.origin() + ray.dir() * t;
        let b = bvhkit::Primitive::bounds(&tris[0]);
        assert!(b.distance_squared(p) < 1e-12, "hit at {p} outside {b:?}");
    }
}

/// Boxes as primitives (a broad phase's rays): random boxes, some far from
/// the origin, some flat or tiny, and rays that start on a face's plane,
/// run along faces or aim at a corner. The box's own ray test (`f32`) and the
/// tree's node test must agree on every hit: the tree may never prune a box
/// its primitive test hits, nor report a later entry.
fn box_scene() -> impl Strategy<Value = Vec<Aabb>> {
    let coord = |scale: f32| (-8i32..8).prop_map(move |k| k as f32 * scale);
    (
        prop_oneof![Just(0.25f32), Just(1.0), Just(1e-3), Just(37.5)],
        prop_oneof![Just(0.0f32), Just(1e4), Just(-3e6)],
    )
        .prop_flat_map(move |(scale, shift)| {
            prop::collection::vec(
                (
                    (coord(scale), coord(scale), coord(scale)),
                    (0..4i32, 0..4i32, 0..4i32),
                ),
                1..40,
            )
            .prop_map(move |v| {
                v.into_iter()
                    .map(|((x, y, z), (a, b, c))| {
                        let lo = Vec3::new(x, y, z) + Vec3::splat(shift);
                        let side = Vec3::new(a as f32, b as f32, c as f32) * scale;
                        Aabb::new(lo, lo + side)
                    })
                    .collect()
            })
        })
}

proptest! {
    #![proptest_config(proptest_config(64))]

    #[test]
    fn rays_on_box_primitives_match_brute_force(
        boxes in box_scene(), pick in 0..1000usize, corner in 0..8usize,
        dir in direction(), aim in any::<bool>(), leaf in 1..5u32,
    ) {
        let cfg = TopDown::default().with_max_leaf_size(leaf);
        let (nodes, idx, _) = build::<Aabb, _>(&cfg, &boxes).unwrap();
        let tree = open(&nodes, &idx, &boxes);
        let target = boxes[pick % boxes.len()];
        let c = Vec3::new(
            if corner & 1 == 0 { target.min.x } else { target.max.x },
            if corner & 2 == 0 { target.min.y } else { target.max.y },
            if corner & 4 == 0 { target.min.z } else { target.max.z },
        );
        let ray = if aim {
            // From outside the scene, straight at a corner of one box.
            let from = c - dir * (region_in_boxes(&boxes) + 1.0);
            Ray::new(from, c - from, f32::INFINITY)
        } else {
            // From a corner, along `dir`: on a face plane, often along a face.
            Ray::new(c, dir, f32::INFINITY)
        };
        let Ok(ray) = ray else { return Ok(()) };
        let want = brute_force::ray_closest(&boxes, &ray);
        for order in [RayOrder::DepthFirst, RayOrder::BestFirst] {
            let got = tree.cast_ray(&boxes, &ray, order, ()).unwrap();
            prop_assert_eq!(got, want, "{:?} ray {:?}", order, ray);
        }
        prop_assert_eq!(tree.ray_hits_any(&boxes, &ray, ()).unwrap().is_some(), want.is_some());
    }
}

/// The scene's largest extent.
fn region_in_boxes(boxes: &[Aabb]) -> f32 {
    let all = boxes.iter().fold(boxes[0], |a, b| a.union(b));
    all.extent().max_element()
}

/// Found while writing `Triangle::ray_intersection`: a triangle lying in a
/// coordinate plane through the origin (a floor at z = 0) was missed by a
/// ray straight at it. Its box has no extent and no magnitude along that
/// axis, so the hit check's pad (a fraction of the magnitude, less the
/// rounding of the hit point) was negative, and the exact hit point, on
/// the plane, counted as outside. Brute force used the same test, so the
/// trees agreed with it: both said "no hit".
#[test]
fn a_ray_hits_a_triangle_in_a_coordinate_plane_through_the_origin() {
    use bvhkit::{brute_force, Ray, RayOrder, RayTarget, Triangle};
    let s = 4.0;
    let floors = [
        Triangle::new(Vec3::ZERO, Vec3::X * s, Vec3::Y * s), // z = 0
        Triangle::new(Vec3::ZERO, Vec3::Y * s, Vec3::Z * s), // x = 0
        Triangle::new(Vec3::ZERO, Vec3::Z * s, Vec3::X * s), // y = 0
    ];
    for (k, floor) in floors.iter().enumerate() {
        let inside = (floor.v[1] + floor.v[2]) * 0.3; // a point of the face
        let normal = Vec3::AXES[(k + 2) % 3];
        for (from, dir, want) in [
            (inside + normal * 5.0, -normal, 5.0), // straight down
            (inside - normal * 2.5, normal, 2.5),  // straight up, from below
            (
                inside + normal * 3.0 + floor.v[1] * 0.01,
                -normal * 2.0,
                1.5,
            ), // any scale
            (inside, -normal, 0.0),                // starting on the face
        ] {
            let ray = Ray::new(from, dir, f32::INFINITY).unwrap();
            assert_eq!(floor.ray_hit(&ray), Some(want), "plane {k}, from {from}");
            let tris = [*floor, floor.translated(Vec3::splat(10.0))];
            let (nodes, idx, _) =
                build::<Aabb, _>(&TopDown::default().with_max_leaf_size(1), &tris).unwrap();
            let tree = open(&nodes, &idx, &tris);
            let hit = tree
                .cast_ray(&tris, &ray, RayOrder::DepthFirst, ())
                .unwrap();
            assert_eq!(hit, brute_force::ray_closest(&tris, &ray));
            assert_eq!(hit.map(|h| h.prim), Some(0));
        }
    }
}

proptest! {
    #![proptest_config(proptest_config(256))]

    /// `Triangle::ray_intersection` is `ray_hit` with geometry: the same
    /// `t` (and the same misses), barycentric coordinates that rebuild the
    /// hit point, a unit normal across both edges, and `front` on the side
    /// the normal points to.
    #[test]
    fn ray_intersection_is_ray_hit_with_its_geometry(
        a in (-3i32..4, -3i32..4, -3i32..4), b in (-3i32..4, -3i32..4, -3i32..4),
        c in (-3i32..4, -3i32..4, -3i32..4), o in (-6.0f32..6.0, -6.0f32..6.0, -6.0f32..6.0),
        aim in (0.0f32..1.0, 0.0f32..1.0), dir in direction(),
    ) {
        use bvhkit::RayTarget;
        let p = |(x, y, z): (i32, i32, i32)| Vec3::new(x as f32, y as f32, z as f32);
        let t = Triangle::new(p(a), p(b), p(c));
        let o = Vec3::new(o.0, o.1, o.2);
        // Half the rays aim at a point of the triangle, half go anywhere.
        let target = t.v[0] + (t.v[1] - t.v[0]) * aim.0 + (t.v[2] - t.v[0]) * (aim.1 * (1.0 - aim.0));
        let d = if aim.0 < 0.5 { target - o } else { dir };
        let Ok(ray) = Ray::new(o, d, f32::INFINITY) else { return Ok(()) };
        let got = t.ray_intersection(&ray);
        prop_assert_eq!(got.map(|h| h.t), t.ray_hit(&ray));
        if let Some(h) = got {
            let w = h.barycentric;
            prop_assert!(w.min_element() >= -1e-12 && (w.element_sum() - 1.0).abs() < 1e-9, "{:?}", w);
            let on = t.v[0].as_dvec3() * w.x + t.v[1].as_dvec3() * w.y + t.v[2].as_dvec3() * w.z;
            let along = o.as_dvec3() + d.as_dvec3() * h.t as f64;
            let size = 10.0 + (d.length() * h.t) as f64;
            prop_assert!((on - along).length() <= size * 1e-6, "{:?} {:?}", on, along);
            let n = h.normal;
            prop_assert!((n.length() - 1.0).abs() < 1e-6);
            let (e1, e2) = (t.v[1] - t.v[0], t.v[2] - t.v[0]);
            prop_assert!(n.dot(e1).abs() <= 1e-5 * e1.length() && n.dot(e2).abs() <= 1e-5 * e2.length());
            prop_assert!(n.dot(e1.cross(e2)) > 0.0);
            prop_assert_eq!(h.front, d.dot(n) < 0.0);
        }
    }
}
