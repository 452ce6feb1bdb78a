//! The exact triangle–triangle test against two references:
//! - an independent exact test (edges against triangles, same predicates);
//! - a separating-axis test in `f64`, exact for small integer coordinates.
//!
//! Small integer grids make coplanar, touching, shared-edge, shared-vertex and
//! zero-area cases common instead of rare.
//!
//! The exact box–triangle test against its definition (a vertex in the box,
//! or the triangle meeting the box's surface) and a 13-axis separating test
//! in `f64`, and inside the pair query's exact answer.

use bvhkit::glam::{DVec3, Vec3};
use bvhkit::narrow::{
    box_triangle_intersect, triangles_intersect, triangles_intersect_by_edges,
    triangles_intersect_with, ExactSigns, F32Signs, F64Signs, Orientation,
};
use bvhkit::{
    brute_force, Aabb, Descent, Exact, Intersects, PairTraversal, Pairs, Rigid, TopDown, Triangle,
};
use bvhkit_tests::{build, open, proptest_config};
use proptest::prelude::*;

/// Separating-axis test in f64 for non-degenerate triangles. Candidate axes:
/// both normals, the nine edge-edge cross products, and each normal crossed
/// with its own edges (needed when the triangles are coplanar). Touching
/// counts as intersecting. Exact when all products fit in 53 bits.
fn sat_f64(t1: &Triangle, t2: &Triangle) -> bool {
    let p: Vec<DVec3> = t1.v.iter().map(|v| v.as_dvec3()).collect();
    let q: Vec<DVec3> = t2.v.iter().map(|v| v.as_dvec3()).collect();
    let e1 = [p[1] - p[0], p[2] - p[1], p[0] - p[2]];
    let e2 = [q[1] - q[0], q[2] - q[1], q[0] - q[2]];
    let (n1, n2) = (e1[0].cross(e1[1]), e2[0].cross(e2[1]));
    let mut axes = vec![n1, n2];
    for a in e1 {
        for b in e2 {
            axes.push(a.cross(b));
        }
    }
    for a in e1 {
        axes.push(n1.cross(a));
    }
    for b in e2 {
        axes.push(n2.cross(b));
    }
    let range = |pts: &[DVec3], ax: DVec3| {
        let d: Vec<f64> = pts.iter().map(|x| x.dot(ax)).collect();
        (
            d.iter().cloned().fold(f64::INFINITY, f64::min),
            d.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
        )
    };
    !axes.into_iter().filter(|a| *a != DVec3::ZERO).any(|ax| {
        let (lo1, hi1) = range(&p, ax);
        let (lo2, hi2) = range(&q, ax);
        hi1 < lo2 || hi2 < lo1
    })
}

fn non_degenerate(t: &Triangle) -> bool {
    let (a, b, c) = (t.v[0].as_dvec3(), t.v[1].as_dvec3(), t.v[2].as_dvec3());
    (b - a).cross(c - a) != DVec3::ZERO
}

fn grid_point(r: i32) -> impl Strategy<Value = Vec3> {
    (-r..=r, -r..=r, -r..=r).prop_map(|(x, y, z)| Vec3::new(x as f32, y as f32, z as f32))
}

fn grid_triangle(r: i32) -> impl Strategy<Value = Triangle> {
    (grid_point(r), grid_point(r), grid_point(r)).prop_map(|(a, b, c)| Triangle::new(a, b, c))
}

/// A second triangle sharing a vertex or an edge with the first, or lying in
/// its plane (z = 0 grid), to force the delicate cases.
fn related_pair() -> impl Strategy<Value = (Triangle, Triangle)> {
    (grid_triangle(3), grid_point(3), grid_point(3), 0..4u8).prop_map(|(t, p, q, kind)| {
        let flat = |v: Vec3| Vec3::new(v.x, v.y, 0.0);
        match kind {
            0 => (t, Triangle::new(t.v[0], p, q)),
            1 => (t, Triangle::new(t.v[0], t.v[1], p)),
            2 => (
                Triangle::new(flat(t.v[0]), flat(t.v[1]), flat(t.v[2])),
                Triangle::new(flat(p), flat(q), flat(t.v[2] + p)),
            ),
            _ => (t, Triangle::new(p, q, (t.v[0] + t.v[1]) * 0.5)),
        }
    })
}

proptest! {
    #![proptest_config(proptest_config(3000))]

    #[test]
    fn agrees_with_the_edge_reference(t1 in grid_triangle(2), t2 in grid_triangle(2)) {
        prop_assert_eq!(triangles_intersect(&t1, &t2), triangles_intersect_by_edges(&t1, &t2), "{:?} {:?}", t1, t2);
        prop_assert_eq!(triangles_intersect(&t1, &t2), triangles_intersect(&t2, &t1), "symmetry");
    }

    #[test]
    fn agrees_with_f64_separating_axes(t1 in grid_triangle(4), t2 in grid_triangle(4)) {
        prop_assume!(non_degenerate(&t1) && non_degenerate(&t2));
        prop_assert_eq!(t1.intersects(&t2), sat_f64(&t1, &t2), "{:?} {:?}", t1, t2);
    }

    /// On small integer grids every determinant is exact in `f32` too, so
    /// the floating-point signs must agree with the exact ones there, and
    /// the test must give one answer whatever signs it reads.
    #[test]
    fn float_signs_are_exact_on_small_grids((t1, t2) in related_pair(), a in grid_point(4), b in grid_point(4), c in grid_point(4), d in grid_point(4)) {
        for k in 0..3 {
            prop_assert_eq!(F32Signs.orient2(a, b, c, k), ExactSigns.orient2(a, b, c, k));
            prop_assert_eq!(F64Signs.orient2(a, b, c, k), ExactSigns.orient2(a, b, c, k));
        }
        prop_assert_eq!(F32Signs.orient3(a, b, c, d), ExactSigns.orient3(a, b, c, d));
        prop_assert_eq!(F64Signs.orient3(a, b, c, d), ExactSigns.orient3(a, b, c, d));
        let exact = triangles_intersect(&t1, &t2);
        prop_assert_eq!(triangles_intersect_with(&t1, &t2, ExactSigns), exact);
        prop_assert_eq!(triangles_intersect_with(&t1, &t2, F64Signs), exact);
        prop_assert_eq!(triangles_intersect_with(&t1, &t2, F32Signs), exact);
    }

    #[test]
    fn delicate_cases_agree((t1, t2) in related_pair()) {
        let exact = triangles_intersect(&t1, &t2);
        prop_assert_eq!(exact, triangles_intersect_by_edges(&t1, &t2), "{:?} {:?}", t1, t2);
        if non_degenerate(&t1) && non_degenerate(&t2) {
            prop_assert_eq!(exact, sat_f64(&t1, &t2), "{:?} {:?}", t1, t2);
        }
    }

    /// Random real-valued triangles, including cyclic reorderings and flips of
    /// each triangle: the answer must not depend on vertex order.
    #[test]
    fn vertex_order_does_not_matter(
        a in prop::array::uniform3((-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0)),
        b in prop::array::uniform3((-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0)),
    ) {
        let t1 = Triangle::new(a[0].into(), a[1].into(), a[2].into());
        let t2 = Triangle::new(b[0].into(), b[1].into(), b[2].into());
        let want = triangles_intersect_by_edges(&t1, &t2);
        for perm in [[0, 1, 2], [1, 2, 0], [2, 0, 1], [0, 2, 1], [2, 1, 0], [1, 0, 2]] {
            let p2 = Triangle::new(t2.v[perm[0]], t2.v[perm[1]], t2.v[perm[2]]);
            prop_assert_eq!(triangles_intersect(&t1, &p2), want);
            prop_assert_eq!(triangles_intersect(&p2, &t1), want);
        }
        if non_degenerate(&t1) && non_degenerate(&t2) {
            prop_assert_eq!(want, sat_f64(&t1, &t2));
        }
    }
}

fn tri(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> Triangle {
    Triangle::new(a.into(), b.into(), c.into())
}

#[test]
fn hand_made_cases() {
    let base = tri([0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [0.0, 4.0, 0.0]);
    let cases = [
        (
            "crossing",
            tri([1.0, 1.0, -1.0], [1.0, 1.0, 1.0], [2.0, 1.0, 1.0]),
            true,
        ),
        (
            "shared vertex only",
            tri([0.0, 0.0, 0.0], [-1.0, 0.0, 1.0], [0.0, -1.0, 1.0]),
            true,
        ),
        (
            "shared edge, folded",
            tri([0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [0.0, 0.0, 3.0]),
            true,
        ),
        (
            "vertex resting on the face",
            tri([1.0, 1.0, 0.0], [1.0, 1.0, 2.0], [2.0, 2.0, 2.0]),
            true,
        ),
        (
            "edge touching an edge",
            tri([2.0, 2.0, 0.0], [2.0, 2.0, 2.0], [5.0, 5.0, 1.0]),
            true,
        ),
        (
            "coplanar, overlapping",
            tri([1.0, 1.0, 0.0], [5.0, 1.0, 0.0], [1.0, 5.0, 0.0]),
            true,
        ),
        (
            "coplanar, one inside the other",
            tri([0.5, 0.5, 0.0], [1.0, 0.5, 0.0], [0.5, 1.0, 0.0]),
            true,
        ),
        (
            "coplanar, touching at a vertex",
            tri([4.0, 0.0, 0.0], [5.0, 0.0, 0.0], [5.0, 1.0, 0.0]),
            true,
        ),
        (
            "coplanar, apart",
            tri([3.0, 3.0, 0.0], [5.0, 3.0, 0.0], [3.0, 5.0, 0.0]),
            false,
        ),
        (
            "parallel planes",
            tri([0.0, 0.0, 1.0], [4.0, 0.0, 1.0], [0.0, 4.0, 1.0]),
            false,
        ),
        (
            "above, not touching",
            tri([1.0, 1.0, 0.5], [1.0, 1.0, 2.0], [2.0, 2.0, 2.0]),
            false,
        ),
        (
            "zero-area segment piercing",
            tri([1.0, 1.0, -1.0], [1.0, 1.0, 1.0], [1.0, 1.0, 0.0]),
            true,
        ),
        (
            "zero-area segment beside",
            tri([5.0, 5.0, -1.0], [5.0, 5.0, 1.0], [5.0, 5.0, 0.0]),
            false,
        ),
        (
            "point on the face",
            tri([1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [1.0, 1.0, 0.0]),
            true,
        ),
        (
            "point off the face",
            tri([1.0, 1.0, 1e-7], [1.0, 1.0, 1e-7], [1.0, 1.0, 1e-7]),
            false,
        ),
    ];
    for (name, t, want) in cases {
        assert_eq!(base.intersects(&t), want, "{name}");
        assert_eq!(t.intersects(&base), want, "{name} (swapped)");
        assert_eq!(
            triangles_intersect_by_edges(&base, &t),
            want,
            "{name} (edge reference)"
        );
        if non_degenerate(&t) {
            assert_eq!(sat_f64(&base, &t), want, "{name} (f64 reference)");
        }
    }
    // Two degenerate triangles: collinear overlapping segments, crossing
    // segments, and points.
    let s1 = tri([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
    let s2 = tri([1.5, 0.0, 0.0], [3.0, 0.0, 0.0], [3.0, 0.0, 0.0]);
    let s3 = tri([1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [1.0, 1.0, 0.0]);
    let s4 = tri([1.0, -1.0, 1.0], [1.0, 1.0, 1.0], [1.0, 0.0, 1.0]);
    assert!(s1.intersects(&s2) && s1.intersects(&s3) && !s1.intersects(&s4));
    let p = tri([2.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 0.0, 0.0]);
    assert!(p.intersects(&s1) && p.intersects(&s2) && !p.intersects(&s3) && p.intersects(&p));
}

/// Near-touching at huge and tiny scales: a floating-point test with an
/// epsilon gets one of these wrong; the exact test gets all right.
#[test]
fn exact_at_every_scale() {
    for scale in [1e-30f32, 1e-3, 1.0, 1e5, 1e30] {
        let s = |v: [f32; 3]| Vec3::from(v) * scale;
        let base = Triangle::new(s([0.0, 0.0, 0.0]), s([4.0, 0.0, 0.0]), s([0.0, 4.0, 0.0]));
        let touching = Triangle::new(s([1.0, 1.0, 0.0]), s([1.0, 1.0, 2.0]), s([2.0, 2.0, 2.0]));
        assert!(base.intersects(&touching), "touching at scale {scale}");
        let lifted = Triangle {
            v: touching
                .v
                .map(|v| Vec3::new(v.x, v.y, v.z.next_up().max(f32::from_bits(1)))),
        };
        assert!(
            !base.intersects(&lifted),
            "lifted by one ulp at scale {scale}"
        );
    }
}

/// The box's eight corners, bit `a` of `k` choosing min or max on axis `a`.
fn corners(b: &Aabb) -> [Vec3; 8] {
    core::array::from_fn(|k| {
        Vec3::new(
            if k & 1 == 0 { b.min.x } else { b.max.x },
            if k & 2 == 0 { b.min.y } else { b.max.y },
            if k & 4 == 0 { b.min.z } else { b.max.z },
        )
    })
}

/// A closed triangle meets a closed box iff one of its vertices is in the box
/// or it meets the box's surface (12 triangles; a flat box's cover it).
fn box_triangle_by_surface(b: &Aabb, t: &Triangle) -> bool {
    let c = corners(b);
    let faces = [
        (0, 1, 3, 2),
        (4, 5, 7, 6),
        (0, 1, 5, 4),
        (2, 3, 7, 6),
        (0, 2, 6, 4),
        (1, 3, 7, 5),
    ];
    t.v.iter()
        .any(|p| p.cmpge(b.min).all() && p.cmple(b.max).all())
        || faces.iter().any(|&(p, q, r, w)| {
            triangles_intersect_by_edges(&Triangle::new(c[p], c[q], c[r]), t)
                || triangles_intersect_by_edges(&Triangle::new(c[p], c[r], c[w]), t)
        })
}

/// Box–triangle separating axes in `f64`: the three coordinate axes, the
/// normal and each edge crossed with each coordinate axis (zero axes
/// skipped). Exact while every product fits 53 bits.
fn box_sat_f64(b: &Aabb, t: &Triangle) -> bool {
    let p: Vec<DVec3> = t.v.iter().map(|v| v.as_dvec3()).collect();
    let c: Vec<DVec3> = corners(b).iter().map(|v| v.as_dvec3()).collect();
    let e = [p[1] - p[0], p[2] - p[1], p[0] - p[2]];
    let mut axes = vec![DVec3::X, DVec3::Y, DVec3::Z, e[0].cross(e[1])];
    for edge in e {
        for axis in [DVec3::X, DVec3::Y, DVec3::Z] {
            axes.push(edge.cross(axis));
        }
    }
    let range = |pts: &[DVec3], ax: DVec3| {
        pts.iter()
            .map(|x| x.dot(ax))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| {
                (lo.min(d), hi.max(d))
            })
    };
    !axes.into_iter().filter(|a| *a != DVec3::ZERO).any(|ax| {
        let ((lo1, hi1), (lo2, hi2)) = (range(&p, ax), range(&c, ax));
        hi1 < lo2 || hi2 < lo1
    })
}

/// A box with corners on the integer grid, flat on an axis where the two
/// draws coincide.
fn grid_box(r: i32) -> impl Strategy<Value = Aabb> {
    (grid_point(r), grid_point(r)).prop_map(|(a, b)| Aabb::new(a.min(b), a.max(b)))
}

proptest! {
    #![proptest_config(proptest_config(3000))]

    #[test]
    fn box_triangle_agrees_with_its_definition(b in grid_box(2), t in grid_triangle(3)) {
        let want = box_triangle_by_surface(&b, &t);
        prop_assert_eq!(box_triangle_intersect(&b, &t), want, "{:?} {:?}", b, t);
        prop_assert_eq!(b.intersects(&t), want);
        prop_assert_eq!(t.intersects(&b), want);
    }

    #[test]
    fn box_triangle_agrees_with_f64_separating_axes(b in grid_box(4), t in grid_triangle(4)) {
        prop_assert_eq!(box_triangle_intersect(&b, &t), box_sat_f64(&b, &t), "{:?} {:?}", b, t);
    }
}

/// A tree of boxes against a mesh tree with the exact answer: the pairs are
/// the boxes and triangles that really touch, for every traversal and with
/// the mesh moved, the same as testing every pair; and fewer than the
/// candidates whose bounds overlap.
#[test]
fn box_tree_against_a_mesh_reports_exact_pairs() {
    let mesh = bvhkit_std::scene::rock(2, 7);
    let bounds = mesh
        .iter()
        .fold(Aabb::EMPTY, |u, t| u.union(&bvhkit::Primitive::bounds(t)));
    let size = bounds.max - bounds.min;
    // Boxes scattered over the rock's box, a tenth of its size each.
    let mut s = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / (1u64 << 24) as f32
    };
    let boxes: Vec<Aabb> = (0..300)
        .map(|_| {
            let lo = bounds.min + size * Vec3::new(next(), next(), next());
            Aabb::new(lo, lo + size * 0.1 * Vec3::new(next(), next(), next()))
        })
        .collect();
    let cfg = TopDown::default();
    let (na, ia, _) = build::<Aabb, _>(&cfg, &boxes).unwrap();
    let (nb, ib, _) = build::<Aabb, _>(&cfg, &mesh).unwrap();
    let (ta, tb) = (open(&na, &ia, &boxes), open(&nb, &ib, &mesh));
    let turn = Rigid::new(
        bvhkit::glam::Quat::from_rotation_z(0.3),
        size * Vec3::new(0.05, -0.02, 0.0),
    )
    .unwrap();
    let sorted = |mut v: Vec<(u32, u32)>| {
        v.sort_unstable();
        v
    };
    let mut same = Vec::new();
    brute_force::pairs_placed(&boxes, &mesh, &bvhkit::Same, Exact, |i, j| {
        same.push((i, j))
    });
    let mut moved = Vec::new();
    brute_force::pairs_placed(&boxes, &mesh, &turn, Exact, |i, j| moved.push((i, j)));
    let candidates = brute_force::pairs(&boxes, &mesh, |_, _| {});
    assert!(
        !same.is_empty() && same.len() < candidates,
        "{} of {candidates}",
        same.len()
    );
    let (same, moved) = (sorted(same), sorted(moved));
    for rule in Descent::ALL {
        for traversal in PairTraversal::all(rule) {
            let run = |frame: Option<Rigid>| {
                let mut got = Vec::new();
                let pairs = Pairs::new(&ta, &boxes, &tb, &mesh).traversal(traversal);
                match frame {
                    None => pairs.exact().for_each(|i, j| got.push((i, j))),
                    Some(m) => pairs.in_frame(m).exact().for_each(|i, j| got.push((i, j))),
                }
                .unwrap();
                sorted(got)
            };
            assert_eq!(run(None), same, "{traversal:?}");
            assert_eq!(run(Some(turn)), moved, "{traversal:?} moved");
        }
    }
}
