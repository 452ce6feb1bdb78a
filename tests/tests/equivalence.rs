//! Every top-down configuration x every bounding volume x every descent rule
//! returns exactly the brute-force answer, and every tree passes validation.
//! Raise the case count with `PROPTEST_CASES=5000 cargo test -p bvhkit-tests`.

use bvhkit::{Aabb, Dop14, Dop18, Dop26, Kdop, Obb, Sphere};
use bvhkit_tests::*;
use proptest::prelude::*;

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(48),
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn aabb_trees_match_brute_force(cfg in any_top_down(), a in scene(40), b in scene(40), r in (0.0f32..1.0, 0.0f32..1.0)) {
        check_against_brute_force::<Aabb>(&cfg, &a, &b, &region_in(&a, r.0, r.1))?;
    }

    #[test]
    fn sphere_trees_match_brute_force(cfg in any_top_down(), a in scene(40), b in scene(40), r in (0.0f32..1.0, 0.0f32..1.0)) {
        check_against_brute_force::<Sphere>(&cfg, &a, &b, &region_in(&a, r.0, r.1))?;
    }

    #[test]
    fn obb_trees_match_brute_force(cfg in any_top_down(), a in scene(30), b in scene(30), r in (0.0f32..1.0, 0.0f32..1.0)) {
        check_against_brute_force::<Obb>(&cfg, &a, &b, &region_in(&a, r.0, r.1))?;
    }

    #[test]
    fn kdop_trees_match_brute_force(cfg in any_top_down(), a in scene(40), b in scene(40), r in (0.0f32..1.0, 0.0f32..1.0)) {
        let region = region_in(&a, r.0, r.1);
        check_against_brute_force::<Kdop<3>>(&cfg, &a, &b, &region)?;
        check_against_brute_force::<Dop14>(&cfg, &a, &b, &region)?;
        check_against_brute_force::<Dop18>(&cfg, &a, &b, &region)?;
        check_against_brute_force::<Dop26>(&cfg, &a, &b, &region)?;
    }

    /// Overlapping copies: the second scene is the first, shifted by a fraction
    /// of a triangle, so there are many touching pairs.
    #[test]
    fn shifted_copies_match(cfg in any_top_down(), a in scene(60), f in 0.0f32..0.3, r in (0.0f32..1.0, 0.0f32..1.0)) {
        let e = region_in(&a, 0.0, 1.0).extent() * f * 0.05;
        let b: Vec<_> = a.iter().map(|t| t.translated(e)).collect();
        let region = region_in(&a, r.0, r.1);
        check_against_brute_force::<Aabb>(&cfg, &a, &b, &region)?;
        check_against_brute_force::<Sphere>(&cfg, &a, &b, &region)?;
        check_against_brute_force::<Dop14>(&cfg, &a, &b, &region)?;
    }
}
