//! `Mesh`, the owned triangles-plus-tree value of the `alloc` feature: every
//! one-call query equals brute force over all triangles, and its geometry
//! agrees with the triangle it names.

use bvhkit::glam::{Quat, Vec3};
use bvhkit::{brute_force, Aabb, Error, Exact, Mesh, Ray, Rigid, Same, Triangle};
use bvhkit_tests::*;
use proptest::prelude::*;

/// A point near (and sometimes inside) the scene's box.
fn probe(tris: &[Triangle], s: (f32, f32, f32)) -> Vec3 {
    let b = tris
        .iter()
        .fold(Aabb::EMPTY, |b, t| b.union(&bvhkit::Primitive::bounds(t)));
    let e = (b.max - b.min).max(Vec3::splat(1e-3));
    b.min - e * 0.25 + e * 1.5 * Vec3::new(s.0, s.1, s.2)
}

proptest! {
    #![proptest_config(proptest_config(32))]

    #[test]
    fn every_mesh_query_equals_brute_force(
        tris in scene(60),
        other in scene(40),
        at in prop::collection::vec((0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0), 1..6),
        dirs in prop::collection::vec((-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0), 1..6),
        reach in 0.0f32..0.3,
        angle in -0.5f32..0.5,
    ) {
        let mesh = Mesh::new(tris.clone()).unwrap();
        prop_assert_eq!(mesh.triangles(), &tris[..]);
        let scale = {
            let b = tris.iter().fold(Aabb::EMPTY, |b, t| b.union(&bvhkit::Primitive::bounds(t)));
            (b.max - b.min).max_element().max(1e-3)
        };
        for (s, d) in at.iter().zip(&dirs) {
            let p = probe(&tris, *s);
            // Rays: the same triangle and t as brute force, and the point
            // and normal of that triangle's own intersection.
            let dir = Vec3::new(d.0, d.1, d.2);
            if let Ok(ray) = Ray::new(p, dir, f32::INFINITY) {
                let got = mesh.cast_ray(&ray);
                let want = brute_force::ray_closest(&tris, &ray);
                prop_assert_eq!(got.map(|h| (h.triangle, h.t)), want.map(|h| (h.prim, h.t)));
                if let Some(h) = got {
                    let on = tris[h.triangle as usize].ray_intersection(&ray).unwrap();
                    prop_assert_eq!((h.normal, h.front, h.barycentric), (on.normal, on.front, on.barycentric));
                    prop_assert_eq!(h.point, ray.origin() + ray.dir() * h.t);
                }
            }
            // The closest point: brute force's triangle and distance.
            let near = mesh.closest_point(p).unwrap();
            let want = brute_force::nearest(&tris, p).unwrap();
            prop_assert_eq!(near.triangle, want.prim);
            prop_assert_eq!(near.distance, want.distance_squared.sqrt());
            let c = tris[near.triangle as usize].closest_point(p);
            prop_assert_eq!((near.point, near.feature), (c.point, c.feature));
            // Within a distance: exactly the triangles that close.
            let r = reach * scale;
            let want: Vec<u32> = (0..tris.len() as u32)
                .filter(|&i| tris[i as usize].closest_point(p).distance_squared <= f64::from(r) * f64::from(r))
                .collect();
            prop_assert_eq!(mesh.within(p, r), want);
        }
        // Pairs: every exactly intersecting pair, in the same frame and moved.
        let b = Mesh::new(other.clone()).unwrap();
        let moves = [
            Rigid::IDENTITY,
            Rigid::new(Quat::from_rotation_y(angle), Vec3::splat(scale * angle * 0.1)).unwrap(),
        ];
        for motion in moves {
            let mut want = Vec::new();
            if motion.is_identity() {
                brute_force::pairs_placed(&tris, &other, &Same, Exact, |i, j| want.push((i, j)));
            } else {
                brute_force::pairs_placed(&tris, &other, &motion, Exact, |i, j| want.push((i, j)));
            }
            want.sort_unstable();
            prop_assert_eq!(mesh.intersects(&b, &motion), !want.is_empty());
            prop_assert_eq!(mesh.pairs(&b, &motion), want);
        }
    }
}

/// An empty mesh is not an error: it answers every query with nothing.
#[test]
fn an_empty_mesh_answers_with_nothing() {
    let empty = Mesh::new(Vec::new()).unwrap();
    let full = Mesh::new(bvhkit_std::scene::rock(1, 3)).unwrap();
    let ray = Ray::new(Vec3::splat(-5.0), Vec3::ONE, f32::INFINITY).unwrap();
    assert_eq!(empty.cast_ray(&ray), None);
    assert!(full.cast_ray(&ray).is_some());
    assert_eq!(empty.closest_point(Vec3::ZERO), None);
    assert!(empty.within(Vec3::ZERO, 10.0).is_empty());
    assert!(empty.pairs(&full, &Rigid::IDENTITY).is_empty());
    assert!(full.pairs(&empty, &Rigid::IDENTITY).is_empty());
    assert!(!empty.intersects(&full, &Rigid::IDENTITY));
}

/// Bad coordinates are refused at construction, naming the triangle; a
/// bad query point or distance finds nothing rather than panicking.
#[test]
fn bad_input_is_an_error_or_nothing_never_a_panic() {
    let mut tris = bvhkit_std::scene::rock(1, 3);
    tris[7].v[1].y = f32::NAN;
    assert_eq!(
        Mesh::new(tris).unwrap_err(),
        Error::NonFiniteCoordinate { primitive: 7 }
    );
    let mesh = Mesh::new(bvhkit_std::scene::rock(1, 3)).unwrap();
    assert_eq!(mesh.closest_point(Vec3::new(f32::NAN, 0.0, 0.0)), None);
    assert_eq!(mesh.closest_point(Vec3::splat(f32::INFINITY)), None);
    assert!(mesh.within(Vec3::ZERO, -1.0).is_empty());
    assert!(mesh.within(Vec3::ZERO, f32::NAN).is_empty());
    assert!(mesh.within(Vec3::ZERO, f32::INFINITY).is_empty());
    assert!(
        !mesh.within(Vec3::ZERO, 10.0).is_empty(),
        "the rock lies within 10 of its centre"
    );
}

/// `within` keeps a triangle at exactly the distance (the smallest `f32`
/// at least as far as the triangle), at every magnitude: the candidate box
/// `p - d` rounds in `f32`, and must still reach the triangle.
#[test]
fn within_keeps_a_triangle_at_the_rounded_distance_at_every_magnitude() {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    for k in 0..2000 {
        let mag = 10f32.powf(next() * 9.0 - 2.0);
        let tz = (next() * 2.0 - 1.0) * mag;
        let pz = tz + next() * mag;
        let exact = f64::from(pz) - f64::from(tz);
        let mut d = exact as f32;
        if f64::from(d) < exact {
            d = f32::from_bits(d.to_bits() + 1);
        }
        let w = mag.max(1.0);
        let t = Triangle::new(
            Vec3::new(-w, -w, tz),
            Vec3::new(w, -w, tz),
            Vec3::new(0.0, w, tz),
        );
        let mesh = Mesh::new(vec![t]).unwrap();
        let p = Vec3::new(0.0, 0.0, pz);
        assert_eq!(
            mesh.within(p, d),
            [0],
            "case {k}: triangle at z = {tz}, p.z = {pz}, d = {d}"
        );
    }
}

/// The same at a corner, far from the origin.
#[test]
fn within_keeps_a_triangle_at_exactly_the_distance_far_from_the_origin() {
    for o in [0.0f32, 1e3, 1e6, -3e7] {
        let base = Vec3::new(o, o, o);
        let t = Triangle::new(base, base + Vec3::X * 0.5, base + Vec3::Y * 0.5);
        let mesh = Mesh::new(vec![t]).unwrap();
        // A point straight above the corner, at a representable height.
        let p = base + Vec3::Z * 0.25;
        let d = (p - base).z;
        assert_eq!(mesh.within(p, d), [0], "at {o}");
        assert_eq!(mesh.closest_point(p).unwrap().distance, f64::from(d));
    }
}

proptest! {
    #![proptest_config(proptest_config(32))]

    /// A mesh from shared vertices and index triples is the mesh of the
    /// triangles they name; an index past the vertices names its triangle.
    #[test]
    fn an_indexed_mesh_is_the_mesh_of_its_triangles(
        tris in scene(40),
        bad in any::<prop::sample::Index>(),
    ) {
        // Weld nothing: three vertices per triangle, in order.
        let vertices: Vec<Vec3> = tris.iter().flat_map(|t| t.v).collect();
        let corners: Vec<[u32; 3]> = (0..tris.len() as u32).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
        let mesh = Mesh::from_indexed(&vertices, &corners).unwrap();
        prop_assert_eq!(mesh.triangles(), &tris[..]);
        let mut broken = corners.clone();
        let k = bad.index(broken.len());
        broken[k][1] = vertices.len() as u32;
        prop_assert_eq!(
            Mesh::from_indexed(&vertices, &broken).unwrap_err(),
            Error::VertexIndexOutOfRange { triangle: k, vertices: vertices.len() }
        );
    }
}
