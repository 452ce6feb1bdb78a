//! Every top-down configuration x every bounding volume x every descent rule
//! returns exactly the brute-force answer, and every tree passes validation.
//! Raise the case count with `PROPTEST_CASES=5000 cargo test -p bvhkit-tests`.

use bvhkit::{Aabb, Dop14, Dop18, Dop26, Kdop, Obb, Sphere};
use bvhkit_tests::*;
use proptest::prelude::*;

fn config() -> ProptestConfig {
    proptest_config(48)
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

proptest! {
    #![proptest_config(config())]

    /// The cached build partitions copies of the bounds instead of indices; the
    /// tree must be the same, node for node.
    #[test]
    fn cached_build_makes_the_same_tree(cfg in any_top_down(), a in scene(80)) {
        use bvhkit::{build::PrimitiveRef, Node, Sphere};
        let mut n1 = vec![Node::<Sphere>::EMPTY; bvhkit::max_nodes(a.len())];
        let mut n2 = n1.clone();
        let mut i1 = vec![0u32; cfg.index_capacity(a.len())];
        let mut i2 = i1.clone();
        let mut cache = vec![PrimitiveRef::EMPTY; a.len()];
        let t1 = cfg.build(&a, &mut n1, &mut i1).unwrap();
        let t2 = cfg.build_cached(&a, &mut n2, &mut i2, &mut cache).unwrap();
        prop_assert_eq!(t1.nodes(), t2.nodes());
        prop_assert_eq!(t1.indices(), t2.indices());
        prop_assert_eq!(t1.depth(), t2.depth());
    }
}
