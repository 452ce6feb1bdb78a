//! Every top-down configuration x every bounding volume x every descent rule
//! returns exactly the brute-force answer, and every tree passes validation.
//! Raise the case count with `PROPTEST_CASES=5000 cargo test -p bvhkit-tests`.

use bvhkit::glam::{EulerRot, Quat, Vec3};
use bvhkit::{
    Aabb, BoundingVolume, Bounds, Dop14, Dop18, Dop26, Exact, Kdop, Obb, Rigid, Same, Sphere,
    TopDown, Triangle,
};
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
        let region = region_in(&a, r.0, r.1);
        check_against_brute_force::<Obb>(&cfg, &a, &b, &region)?;
        check_against_brute_force::<bvhkit::ObbDito>(&cfg, &a, &b, &region)?;
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

/// A rigid motion that turns `b` about its centre and moves it by a fraction
/// of the scene's size, so that the moved copy usually meets `a`.
fn motion(b: &[Triangle], angles: (f32, f32, f32), shift: Vec3) -> Rigid {
    let bounds = region_in(b, 0.0, 1.0);
    let c = bounds.center();
    let turn = Quat::from_euler(EulerRot::XYZ, angles.0, angles.1, angles.2);
    let to_origin = Rigid::translation(-c).unwrap();
    let back = Rigid::translation(c + shift * bounds.extent()).unwrap();
    back.after(&Rigid::new(turn, Vec3::ZERO).unwrap().after(&to_origin))
}

fn angles() -> impl Strategy<Value = (f32, f32, f32)> {
    (-3.2f32..3.2, -3.2f32..3.2, -3.2f32..3.2)
}

fn shift() -> impl Strategy<Value = Vec3> {
    (-0.4f32..0.4, -0.4f32..0.4, -0.4f32..0.4).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn check_moved<B: BoundingVolume>(
    cfg: &TopDown,
    a: &[Triangle],
    b: &[Triangle],
    m: Rigid,
) -> Result<(), TestCaseError> {
    let (na, ia, _) = build::<B, _>(cfg, a).map_err(|e| TestCaseError::fail(format!("{e}")))?;
    let (nb, ib, _) = build::<B, _>(cfg, b).map_err(|e| TestCaseError::fail(format!("{e}")))?;
    let (ta, tb) = (open(&na, &ia, a), open(&nb, &ib, b));
    check_pairs(&ta, a, &tb, b, &m, Exact, cfg)?;
    check_pairs(&ta, a, &tb, b, &m, Bounds, cfg)?;
    check_pairs(&ta, a, &tb, b, &Same, Exact, cfg)?;
    // Kept leaf bounds are in each tree's own frame: a moved B must place
    // its primitives rather than use them.
    let (mut ba, mut bb) = (vec![Aabb::EMPTY; a.len()], vec![Aabb::EMPTY; b.len()]);
    let (la, lb) = (
        ta.with_leaf_bounds(a, &mut ba).unwrap(),
        tb.with_leaf_bounds(b, &mut bb).unwrap(),
    );
    check_pairs(&la, a, &lb, b, &m, Bounds, cfg)?;
    check_pairs(&la, a, &lb, b, &m, Exact, cfg)
}

proptest! {
    #![proptest_config(config())]

    /// Tree B moved by a rigid motion, queried in A's frame without a rebuild,
    /// with the exact triangle test: every traversal, rule and mode agrees
    /// with brute force over the moved triangles, for every volume type.
    #[test]
    fn moved_exact_pairs_match(cfg in any_top_down(), a in scene(30), b in scene(30), ang in angles(), s in shift()) {
        let m = motion(&b, ang, s);
        check_moved::<Aabb>(&cfg, &a, &b, m)?;
        check_moved::<Sphere>(&cfg, &a, &b, m)?;
        check_moved::<Obb>(&cfg, &a, &b, m)?;
        check_moved::<bvhkit::ObbDito>(&cfg, &a, &b, m)?;
        check_moved::<Dop14>(&cfg, &a, &b, m)?;
    }

    /// A copy of the scene moved onto itself: many touching, coplanar and
    /// crossing triangle pairs.
    #[test]
    fn moved_self_copies_match(cfg in any_top_down(), a in scene(40), ang in angles(), s in shift()) {
        let m = motion(&a, (ang.0 * 0.05, ang.1 * 0.05, ang.2 * 0.05), s * 0.05);
        check_moved::<Aabb>(&cfg, &a, &a, m)?;
        check_moved::<Sphere>(&cfg, &a, &a, m)?;
    }
}

proptest! {
    #![proptest_config(config())]

    /// The cached build partitions copies of the bounds instead of indices; the
    /// tree must be the same, node for node.
    #[test]
    fn cached_build_makes_the_same_tree(cfg in any_top_down(), a in scene(80)) {
        use bvhkit::{builders::PrimitiveRef, Node, Sphere};
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

    /// The forked build (both halves of large nodes through a `Fork`) makes
    /// the sequential tree, bit for bit, for any configuration and grain,
    /// on the calling thread (`InOrder`) and on a pool of threads.
    #[test]
    fn forked_build_makes_the_same_tree(
        cfg in any_top_down(),
        a in scene(80),
        grain in 2usize..40,
    ) {
        use bvhkit::builders::{InOrder, PrimitiveRef};
        use bvhkit::{Node, Sphere};
        use bvhkit_std::parallel::Threads;
        let n = a.len();
        let mut n1 = vec![Node::<Sphere>::EMPTY; bvhkit::max_nodes(n)];
        let mut i1 = vec![0u32; cfg.index_capacity(n)];
        let mut cache = vec![PrimitiveRef::EMPTY; n];
        let t1 = cfg.build_cached(&a, &mut n1, &mut i1, &mut cache).unwrap();
        let pool = rayon::ThreadPoolBuilder::new().num_threads(3).build().unwrap();
        for threads in [false, true] {
            let mut n2 = vec![Node::<Sphere>::ZERO; bvhkit::max_nodes(n)];
            let mut scratch = n2.clone();
            let mut i2 = vec![0u32; cfg.index_capacity(n)];
            let mut cache = vec![PrimitiveRef::ZERO; n];
            let t2 = if threads {
                pool.install(|| {
                    cfg.build_cached_forked(&a, &mut n2, &mut i2, &mut cache, &mut scratch, &Threads { grain })
                })
            } else {
                cfg.build_cached_forked(&a, &mut n2, &mut i2, &mut cache, &mut scratch, &InOrder { grain })
            }
            .unwrap();
            prop_assert_eq!(t1.nodes(), t2.nodes());
            prop_assert_eq!(t1.indices(), t2.indices());
            prop_assert_eq!(t1.depth(), t2.depth());
            prop_assert_eq!(t1.build_report(), t2.build_report());
        }
    }
}
