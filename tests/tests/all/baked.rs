//! A baked tree, opened in place, is the tree that was baked: on random
//! scenes (empty ones included) every pair and ray answer equals brute force,
//! with and without kept leaf bounds, and the bytes bake back identically.

use bvhkit::glam::Vec3;
use bvhkit::{brute_force, Aabb, Bvh, Exact, Pairs, Ray, RayOrder, Same, TopDown, Triangle};
use bvhkit_std::OwnedBvh;
use bvhkit_tests::proptest_config;
use proptest::prelude::*;

fn triangle() -> impl Strategy<Value = Triangle> {
    let p = || {
        (-8i32..=8, -8i32..=8, -8i32..=8)
            .prop_map(|(x, y, z)| Vec3::new(x as f32, y as f32, z as f32) * 0.25)
    };
    (p(), p(), p()).prop_map(|(a, b, c)| Triangle::new(a, a + b * 0.5, a + c * 0.5))
}

proptest! {
    #![proptest_config(proptest_config(64))]

    #[test]
    fn opened_trees_answer_as_brute_force(
        a in prop::collection::vec(triangle(), 0..60),
        b in prop::collection::vec(triangle(), 0..60),
        leaf in 1u32..6,
        kept in any::<bool>(),
        o in (-3.0f32..3.0, -3.0f32..3.0),
    ) {
        let builder = TopDown::default().with_max_leaf_size(leaf);
        let (oa, ob) = (OwnedBvh::<Aabb>::build(&builder, &a)?, OwnedBvh::<Aabb>::build(&builder, &b)?);
        let bake = |t: &OwnedBvh<Aabb>| -> Result<Vec<u8>, bvhkit::Error> {
            let view = if kept { t.view() } else { t.plain_view() };
            let mut bytes = vec![0u8; view.baked_len()];
            view.bake(&mut bytes)?;
            Ok(bytes)
        };
        let (bytes_a, bytes_b) = (bake(&oa)?, bake(&ob)?);
        let mut seen_a = vec![0u32; Bvh::baked_seen_words(&bytes_a)?];
        let mut seen_b = vec![0u32; Bvh::baked_seen_words(&bytes_b)?];
        let ta = Bvh::from_baked(&bytes_a, &mut seen_a)?;
        let tb = Bvh::from_baked(&bytes_b, &mut seen_b)?;
        prop_assert_eq!(ta.leaf_bounds().is_some(), kept && !a.is_empty());
        ta.validate(&a, &mut seen_a)?;
        let mut again = vec![0u8; bytes_a.len()];
        ta.bake(&mut again)?;
        prop_assert_eq!(&again, &bytes_a);

        let mut got = Vec::new();
        Pairs::new(&ta, &a, &tb, &b).exact().for_each(|i, j| got.push((i, j)))?;
        got.sort_unstable();
        let mut want = Vec::new();
        brute_force::pairs_placed(&a, &b, &Same, Exact, |i, j| want.push((i, j)));
        want.sort_unstable();
        prop_assert_eq!(got, want);

        let ray = Ray::new(Vec3::new(o.0, o.1, 9.0), Vec3::new(0.05, -0.03, -1.0), f32::INFINITY)?;
        let hit = ta.cast_ray(&a, &ray, RayOrder::default(), ())?.map(|h| h.t);
        let brute = brute_force::ray_closest(&a, &ray).map(|h| h.t);
        prop_assert_eq!(hit, brute);
    }
}
