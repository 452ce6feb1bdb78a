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
