//! Every fit is conservative in f32 (all points inside), including far from the
//! origin and on degenerate sets; Welzl's sphere is the minimal one; overlap
//! tests never say "disjoint" for volumes that share a point.

use bvhkit::glam::Vec3;
use bvhkit::{Aabb, BoundingVolume, Dop14, Dop18, Dop26, Kdop, Obb, Sphere};
use bvhkit_tests::proptest_config;
use proptest::prelude::*;

fn config() -> ProptestConfig {
    proptest_config(128)
}

/// Point sets: general, collinear, coplanar, one point, clustered; then moved far away.
fn points() -> impl Strategy<Value = Vec<Vec3>> {
    let p = || (-5.0f32..5.0, -5.0f32..5.0, -5.0f32..5.0).prop_map(|(x, y, z)| Vec3::new(x, y, z));
    let set = prop_oneof![
        prop::collection::vec(p(), 1..40),
        (p(), p(), prop::collection::vec(-3.0f32..3.0, 1..30))
            .prop_map(|(a, d, ts)| ts.iter().map(|&t| a + d * t).collect()),
        (
            prop::collection::vec((-5.0f32..5.0, -5.0f32..5.0), 1..30),
            -5.0f32..5.0
        )
            .prop_map(|(xy, z)| xy.iter().map(|&(x, y)| Vec3::new(x, y, z)).collect()),
        p().prop_map(|a| vec![a]),
        (prop::collection::vec(p(), 1..30), p()).prop_map(|(v, far)| {
            let mut v: Vec<Vec3> = v.iter().map(|q| *q * 1e-3).collect();
            v.push(far);
            v
        }),
    ];
    (
        set,
        prop_oneof![Just(0.0f32), Just(1.0e5), Just(-7.3e4), Just(3.0e2)],
    )
        .prop_map(|(v, off)| {
            v.into_iter()
                .map(|q| q + Vec3::new(off, -off * 0.5, off * 0.25))
                .collect()
        })
}

fn all_inside<B: BoundingVolume>(b: &B, pts: &[Vec3]) -> Result<(), TestCaseError> {
    for (i, p) in pts.iter().enumerate() {
        prop_assert!(
            b.contains_point(*p),
            "{} misses point {i} {p:?}: {b:?}",
            B::NAME
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn every_fit_contains_its_points(pts in points()) {
        all_inside(&Aabb::fit(pts.as_slice()), &pts)?;
        all_inside(&Sphere::ritter(pts.as_slice()), &pts)?;
        all_inside(&Sphere::ritter_refined(pts.as_slice(), 8), &pts)?;
        all_inside(&Sphere::welzl(pts.as_slice()), &pts)?;
        all_inside(&Obb::pca(pts.as_slice()), &pts)?;
        all_inside(&Obb::dito(pts.as_slice()), &pts)?;
        all_inside(&Kdop::<3>::fit(pts.as_slice()), &pts)?;
        all_inside(&Dop14::fit(pts.as_slice()), &pts)?;
        all_inside(&Dop18::fit(pts.as_slice()), &pts)?;
        all_inside(&Dop26::fit(pts.as_slice()), &pts)?;
    }

    /// The OBB fits on huge (1e30) sets: every point inside, no overflow
    /// to an infinite or NaN box; DiTO no looser than the axis-aligned box.
    #[test]
    fn obb_fits_contain_huge_point_sets(pts in points(), scale in prop_oneof![Just(1e30f32), Just(1e-30f32)]) {
        let pts: Vec<Vec3> = pts.iter().map(|p| *p * scale).collect();
        for obb in [Obb::pca(pts.as_slice()), Obb::dito(pts.as_slice())] {
            all_inside(&obb, &pts)?;
            prop_assert!(obb.half_extents.is_finite() && obb.center.is_finite(), "{obb:?}");
        }
        // Never looser than the axis-aligned OBB it falls back to (not the
        // Aabb: at 1e35 an OBB's rounded centre costs it an ulp of 8e27 on
        // each side, found by this test). Measured in the set's own unit:
        // an f32 volume of a 1e30 box is infinite, or NaN when it is flat.
        let d = Obb::dito(pts.as_slice());
        let a = Obb::fit_with_axes(pts.as_slice(), [Vec3::X, Vec3::Y, Vec3::Z]);
        let unit = 1.0 / Aabb::fit(pts.as_slice()).extent().max_element().max(f32::MIN_POSITIVE);
        let (dv, av) = (d.volume_scaled(unit), a.volume_scaled(unit));
        let (da, aa) = (d.surface_area_scaled(unit), a.surface_area_scaled(unit));
        prop_assert!(dv <= av * 1.001 + 1e-6 || da <= aa * 1.001 + 1e-6, "{d:?} looser than {a:?}");
    }

    /// Welzl is minimal: never larger than Ritter, and no sphere through any 2 or 3
    /// of the points (brute force over small sets) that contains all is smaller.
    #[test]
    fn welzl_is_minimal(pts in prop::collection::vec((-5.0f32..5.0, -5.0f32..5.0, -5.0f32..5.0).prop_map(|(x, y, z)| Vec3::new(x, y, z)), 1..9)) {
        let w = Sphere::welzl(pts.as_slice());
        let r = Sphere::ritter(pts.as_slice());
        let rr = Sphere::ritter_refined(pts.as_slice(), 8);
        prop_assert!(w.radius <= r.radius * (1.0 + 1e-5) + 1e-6);
        prop_assert!(w.radius <= rr.radius * (1.0 + 1e-5) + 1e-6);
        // Lower bound: half the diameter of the set.
        let mut diam: f32 = 0.0;
        for a in &pts { for b in &pts { diam = diam.max(a.distance(*b)); } }
        prop_assert!(w.radius >= diam * 0.5 * (1.0 - 1e-5));
        // Brute force over 2-point diameter spheres that contain everything.
        for a in &pts { for b in &pts {
            let c = (*a + *b) * 0.5;
            let rad = a.distance(*b) * 0.5;
            if pts.iter().all(|p| p.distance(c) <= rad * (1.0 + 1e-6) + 1e-6) {
                prop_assert!(w.radius <= rad * (1.0 + 1e-4) + 1e-5, "welzl {} > pair sphere {}", w.radius, rad);
            }
        }}
    }

    /// Merges contain both inputs; overlap tests agree with a shared point.
    #[test]
    fn merges_contain_and_overlaps_are_conservative(a in points(), b in points(), t in 0.0f32..1.0) {
        fn check<B: BoundingVolume>(a: &[Vec3], b: &[Vec3], t: f32) -> Result<(), TestCaseError> {
            let (x, y) = (B::fit(a), B::fit(b));
            let m = x.merge(&y);
            prop_assert!(m.contains(&x) && m.contains(&y), "{} merge", B::NAME);
            // A point inside both volumes forces overlap: take a point of `a` and
            // move `b` so that it contains it.
            let p = a[0].lerp(a[a.len() - 1], t);
            let shift = p - b[0];
            let moved: Vec<Vec3> = b.iter().map(|q| *q + shift).collect();
            let y2 = B::fit(moved.as_slice());
            if x.contains_point(p) && y2.contains_point(p) {
                prop_assert!(x.overlaps(&y2), "{} overlap missed", B::NAME);
                prop_assert!(x.overlaps_aabb(&Aabb::from_point(p)), "{} box overlap missed", B::NAME);
            }
            Ok(())
        }
        check::<Aabb>(&a, &b, t)?;
        check::<Sphere>(&a, &b, t)?;
        check::<Obb>(&a, &b, t)?;
        check::<bvhkit::ObbDito>(&a, &b, t)?;
        check::<Dop14>(&a, &b, t)?;
        check::<Dop26>(&a, &b, t)?;
    }
}

proptest! {
    #![proptest_config(config())]

    /// `from_aabb` must contain the whole box (all eight corners) in f32; a
    /// sphere fitted to the two diagonal corners alone missed the others by
    /// an ulp at 1e5 (found by the bottom-up builder's property test).
    #[test]
    fn from_aabb_contains_every_corner(pts in points()) {
        let b = Aabb::fit(pts.as_slice());
        fn check<B: BoundingVolume>(b: &Aabb) -> Result<(), TestCaseError> {
            let v = B::from_aabb(b);
            prop_assert!(v.contains_aabb(b), "{} from_aabb misses a corner of {:?}: {:?}", B::NAME, b, v);
            Ok(())
        }
        check::<Aabb>(&b)?;
        check::<Sphere>(&b)?;
        check::<Obb>(&b)?;
        check::<bvhkit::ObbDito>(&b)?;
        check::<Kdop<3>>(&b)?;
        check::<Dop14>(&b)?;
        check::<Dop18>(&b)?;
        check::<Dop26>(&b)?;
    }
}

#[test]
fn from_aabb_contains_the_box_found_by_bottom_up() {
    let b = Aabb::new(
        Vec3::new(100000.0, 99998.83, 99998.97),
        Vec3::new(100000.85, 100001.31, 100001.21),
    );
    assert!(Sphere::from_aabb(&b).contains_aabb(&b));
}

#[test]
fn obb_falls_back_to_the_aabb_for_a_cube() {
    // A cube's covariance is isotropic: PCA axes are arbitrary. The fit must not
    // be worse than the axis-aligned box.
    let mut pts = Vec::new();
    for i in 0..8 {
        pts.push(Aabb::new(Vec3::ZERO, Vec3::ONE).corner(i));
    }
    let obb = Obb::pca(pts.as_slice());
    assert!(obb.volume() <= 1.0 + 1e-4, "{obb:?}");
}

#[test]
fn kdop_is_tighter_than_its_box_on_a_diagonal_triangle() {
    let tri = [
        Vec3::ZERO,
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(1.0, 1.0, 1.0),
    ];
    let d = Dop26::fit(&tri);
    let outside = Vec3::new(1.0, 0.0, 0.0); // inside the AABB, outside the hull
    assert!(Aabb::fit(&tri).contains_point(outside));
    assert!(!d.contains_point(outside));
}

/// The convex hull of `pts` from quickhull, its triangles re-indexed into
/// `pts` itself (quickhull's vertices are input points, bit for bit), so
/// the hull fits get every point as a vertex and must contain them all.
/// No hull (quickhull refuses a NaN or a nearly flat set): no triangles,
/// which the fits document as their fallback to `Obb::pca`.
fn hull_of(pts: &[Vec3]) -> Vec<[u32; 3]> {
    let Some(hull) = bvhkit_std::hull::mesh(pts) else {
        return Vec::new();
    };
    let index = |v: Vec3| {
        pts.iter()
            .position(|p| p.to_array().map(f32::to_bits) == v.to_array().map(f32::to_bits))
    };
    hull.triangles
        .iter()
        .map(|t| {
            t.map(|k| {
                index(hull.vertices[k as usize]).expect("a hull vertex is an input point") as u32
            })
        })
        .collect()
}

/// Both hull fits, on `pts` with their hull's triangles.
fn hull_fits(pts: &[Vec3]) -> (Vec<[u32; 3]>, Obb, Obb) {
    let tris = hull_of(pts);
    let mut scratch = vec![bvhkit::glam::Vec2::ZERO; Obb::face_flush_scratch_len(pts.len())];
    let p = Obb::pca_hull(pts, &tris).expect("finite points, indices in range");
    let f = Obb::face_flush(pts, &tris, &mut scratch).expect("scratch of the documented length");
    (tris, p, f)
}

proptest! {
    #![proptest_config(config())]

    /// The hull fits contain every point, near and far (1e5), on general,
    /// collinear, coplanar, single-point and clustered sets, and fall back
    /// to `Obb::pca` where quickhull gives no hull.
    #[test]
    fn hull_fits_contain_their_points(pts in points()) {
        let (tris, p, f) = hull_fits(&pts);
        all_inside(&p, &pts)?;
        all_inside(&f, &pts)?;
        if tris.is_empty() {
            prop_assert_eq!(p, Obb::pca(pts.as_slice()));
            prop_assert_eq!(f, Obb::pca(pts.as_slice()));
        }
    }

    /// The same at 1e30 and 1e-30: every point inside, a finite box.
    #[test]
    fn hull_fits_contain_huge_point_sets(pts in points(), scale in prop_oneof![Just(1e30f32), Just(1e-30f32)]) {
        let pts: Vec<Vec3> = pts.iter().map(|p| *p * scale).collect();
        let (_, p, f) = hull_fits(&pts);
        for obb in [p, f] {
            all_inside(&obb, &pts)?;
            prop_assert!(obb.half_extents.is_finite() && obb.center.is_finite(), "{obb:?}");
        }
    }

    /// Face-flush is the smallest box flush with a hull face: brute force
    /// over every hull face and every direction in its plane between two
    /// points (the minimum rectangle has a side along a 2-D hull edge,
    /// which joins two projected points) finds none smaller, up to the
    /// `f32` rounding of axes and of the scratch's 2-D points.
    #[test]
    fn face_flush_is_the_smallest_face_flush_box(
        pts in prop::collection::vec((-5.0f32..5.0, -5.0f32..5.0, -5.0f32..5.0).prop_map(|(x, y, z)| Vec3::new(x, y, z)), 4..14),
    ) {
        let (tris, _, f) = hull_fits(&pts);
        let volume = |o: &Obb| (o.half_extents.max(Vec3::ZERO) * 2.0).as_dvec3().to_array().iter().product::<f64>();
        let mut brute = volume(&Obb::fit_with_axes(pts.as_slice(), [Vec3::X, Vec3::Y, Vec3::Z]));
        for t in &tris {
            let [a, b, c] = t.map(|k| pts[k as usize].as_dvec3());
            let n = (b - a).cross(c - a).normalize_or_zero();
            if n == bvhkit::glam::DVec3::ZERO {
                continue;
            }
            for p in &pts {
                for q in &pts {
                    let d = q.as_dvec3() - p.as_dvec3();
                    let u = (d - n * n.dot(d)).normalize_or_zero();
                    if u == bvhkit::glam::DVec3::ZERO {
                        continue;
                    }
                    let axes = [u, n.cross(u), n].map(|a| a.as_vec3());
                    brute = brute.min(volume(&Obb::fit_with_axes(pts.as_slice(), axes)));
                }
            }
        }
        prop_assert!(volume(&f) <= brute * (1.0 + 1e-4) + 1e-9, "face-flush {} > brute force {}", volume(&f), brute);
    }
}

/// The two sets the property tests found quickhull answering with the
/// origin as a hull vertex: now no hull, so both fits fall back to PCA.
#[test]
fn hull_fits_on_the_two_point_sets_quickhull_got_wrong() {
    for pts in [
        vec![
            Vec3::new(-1.9400345, -2.136965, 0.0),
            Vec3::new(-1.3193092, 1.509896, 0.0),
        ],
        vec![
            Vec3::new(100001.086, -50004.363, 24995.291) * 1e-30,
            Vec3::new(99998.914, -50000.43, 24998.924) * 1e-30,
        ],
    ] {
        let (tris, p, f) = hull_fits(&pts);
        assert!(tris.is_empty());
        assert_eq!((p, f), (Obb::pca(pts.as_slice()), Obb::pca(pts.as_slice())));
        assert!(pts
            .iter()
            .all(|&q| p.contains_point(q) && f.contains_point(q)));
    }
}
