//! Three corners (`[Vec3; 3]`) are a `Triangle` in all but name: every
//! primitive test gives the triangle's answer, bit for bit, and a tree over
//! corners answers rays, nearest points and exact pairs (same frame and
//! moved) as brute force over the triangles does.

use bvhkit::glam::Vec3;
use bvhkit::query::{PairDistance, PointDistance};
use bvhkit::{
    brute_force, Aabb, Exact, Intersects, Pairs, Primitive, Ray, RayOrder, RayTarget, Rigid, Same,
    TopDown, Transform, Triangle,
};
use bvhkit_tests::{build, open, proptest_config};
use proptest::prelude::*;

/// A corner on a small grid: shared, touching and coplanar cases are common.
fn corner() -> impl Strategy<Value = Vec3> {
    (-4i32..=4, -4i32..=4, -4i32..=4)
        .prop_map(|(x, y, z)| Vec3::new(x as f32, y as f32, z as f32) * 0.5)
}

fn corners() -> impl Strategy<Value = [Vec3; 3]> {
    [corner(), corner(), corner()]
}

proptest! {
    #![proptest_config(proptest_config(256))]

    #[test]
    fn every_test_gives_the_triangles_answer(
        a in corners(),
        b in corners(),
        o in corner(),
        d in corner(),
        p in corner(),
        turn in -3.0f32..3.0,
    ) {
        let (ta, tb) = (Triangle::from(a), Triangle::from(b));
        prop_assert_eq!(a.bounds(), ta.bounds());
        prop_assert_eq!(a.is_finite(), ta.is_finite());
        if let Ok(ray) = Ray::new(o + Vec3::splat(0.1), d, f32::INFINITY) {
            prop_assert_eq!(a.ray_hit(&ray).map(f32::to_bits), ta.ray_hit(&ray).map(f32::to_bits));
        }
        prop_assert_eq!(a.distance_squared(p).to_bits(), ta.distance_squared(p).to_bits());
        prop_assert_eq!(a.intersects(&b), ta.intersects(&tb));
        let cube = Aabb::new(p.min(o), p.max(o));
        prop_assert_eq!(a.intersects(&cube), ta.intersects(&cube));
        prop_assert_eq!(a.closest_points(&b), ta.closest_points(&tb));
        prop_assert_eq!(p.closest_points(&a), p.closest_points(&ta));
        let m = Rigid::new(bvhkit::glam::Quat::from_rotation_y(turn), d).unwrap();
        prop_assert_eq!(Triangle::from(a.transformed(&m)), ta.transformed(&m));
        prop_assert_eq!(<[Vec3; 3]>::from(ta), a);
    }

    #[test]
    fn a_tree_over_corners_answers_as_brute_force_over_triangles(
        mesh in prop::collection::vec(corners(), 1..60),
        other in prop::collection::vec(corners(), 1..60),
        o in corner(),
        d in corner(),
        turn in -3.0f32..3.0,
    ) {
        let tris: Vec<Triangle> = mesh.iter().map(|&c| c.into()).collect();
        let others: Vec<Triangle> = other.iter().map(|&c| c.into()).collect();
        let cfg = TopDown::default();
        let (na, ia, _) = build::<Aabb, _>(&cfg, &mesh).unwrap();
        let (nb, ib, _) = build::<Aabb, _>(&cfg, &other).unwrap();
        let (a, b) = (open(&na, &ia, &mesh), open(&nb, &ib, &other));
        if let Ok(ray) = Ray::new(o + Vec3::splat(0.1), d, f32::INFINITY) {
            let got = a.cast_ray(&mesh, &ray, RayOrder::default(), ()).unwrap();
            prop_assert_eq!(got.map(|h| h.t), brute_force::ray_closest(&tris, &ray).map(|h| h.t));
        }
        let near = a.nearest(&mesh, o, ()).unwrap();
        prop_assert_eq!(near.map(|n| n.distance_squared), brute_force::nearest(&tris, o).map(|n| n.distance_squared));
        let m = Rigid::new(bvhkit::glam::Quat::from_rotation_z(turn), d * 0.3).unwrap();
        let sorted = |mut v: Vec<(u32, u32)>| { v.sort_unstable(); v };
        let (mut want, mut want_moved) = (Vec::new(), Vec::new());
        brute_force::pairs_placed(&tris, &others, &Same, Exact, |i, j| want.push((i, j)));
        brute_force::pairs_placed(&tris, &others, &m, Exact, |i, j| want_moved.push((i, j)));
        let (mut got, mut got_moved) = (Vec::new(), Vec::new());
        Pairs::new(&a, &mesh, &b, &other).exact().for_each(|i, j| got.push((i, j))).unwrap();
        Pairs::new(&a, &mesh, &b, &other).in_frame(m).exact().for_each(|i, j| got_moved.push((i, j))).unwrap();
        prop_assert_eq!(sorted(got), sorted(want));
        prop_assert_eq!(sorted(got_moved), sorted(want_moved));
    }
}
