//! Shared helpers for the integration tests: scene generators, every builder
//! configuration, and the brute-force comparison run on every tree.

use bvhkit::glam::Vec3;
use bvhkit::query::{Distance, PairDistance};
use bvhkit::{
    brute_force, overlapping_pairs, Aabb, Answer, AxisChoice, BoundingVolume, Bounds, Bvh, Counts,
    DepthSwitch, Descent, Frame, Hierarchy, Node, OnFailure, PairTraversal, Pairs, Partition,
    Place, Primitive, Same, SplitPoint, Stop, TopDown, Triangle,
};
use proptest::prelude::*;

/// Property-test settings: `default_cases` cases, or `PROPTEST_CASES` when set
/// (for long local runs).
pub fn proptest_config(default_cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases: std::env::var("PROPTEST_CASES")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(default_cases),
        ..ProptestConfig::default()
    }
}

/// Every partition criterion.
pub const PARTITIONS: [Partition; 7] = [
    Partition::Balance,
    Partition::SurfaceArea,
    Partition::Volume,
    Partition::LargerChild,
    Partition::Overlap,
    Partition::Separation,
    Partition::Weighted {
        surface_area: 1.0,
        volume: 0.5,
        overlap: 2.0,
        balance: 0.25,
    },
];

/// Every axis choice.
pub const AXES: [AxisChoice; 8] = [
    AxisChoice::X,
    AxisChoice::Y,
    AxisChoice::Z,
    AxisChoice::BestOfXyz,
    AxisChoice::Longest,
    AxisChoice::Variance,
    AxisChoice::DistantPoints,
    AxisChoice::ParentVolume,
];

/// Every split point (with a couple of parameter values).
pub const SPLITS: [SplitPoint; 8] = [
    SplitPoint::ObjectMedian,
    SplitPoint::ObjectMean,
    SplitPoint::SpatialMedian,
    SplitPoint::Bins(2),
    SplitPoint::Bins(16),
    SplitPoint::Sweep,
    SplitPoint::RandomCentroids { count: 4, seed: 7 },
    SplitPoint::RandomCentroids { count: 31, seed: 1 },
];

/// A random but valid top-down configuration covering every option.
pub fn any_top_down() -> impl Strategy<Value = TopDown> {
    (
        0..PARTITIONS.len(),
        0..AXES.len(),
        0..SPLITS.len(),
        1u32..6,
        prop_oneof![Just(0.0f32), Just(1e-3f32)],
        prop_oneof![Just(64u32), 0u32..6],
        any::<bool>(),
    )
        .prop_map(|(p, a, s, leaf, min_volume, max_depth, leaf_on_failure)| {
            let split = SPLITS[s];
            // The sweep scores the SAH only (documented, and an error otherwise).
            let partition = if split == SplitPoint::Sweep {
                Partition::SurfaceArea
            } else {
                PARTITIONS[p]
            };
            TopDown {
                partition,
                axis: AXES[a],
                split,
                stop: Stop {
                    max_leaf_size: leaf,
                    min_volume,
                    max_depth,
                },
                on_failure: if leaf_on_failure {
                    OnFailure::Leaf
                } else {
                    OnFailure::ForceSplit
                },
            }
        })
}

/// Coordinate frames that stress floating point: near the origin, far away,
/// tiny, and huge (1e30).
pub const FRAMES: [(f32, f32); 5] = [
    (1.0, 0.0),
    (1.0, 1.0e5),
    (1.0e-3, 0.0),
    (1.0e27, 1.0e30),
    (1.0, -2.0e4),
];

fn point() -> impl Strategy<Value = Vec3> {
    (-10.0f32..10.0, -10.0f32..10.0, -10.0f32..10.0).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// One raw triangle: ordinary, zero-area (point or segment), or flat in z.
fn triangle() -> impl Strategy<Value = Triangle> {
    prop_oneof![
        6 => (point(), point(), point()).prop_map(|(a, b, c)| Triangle::new(a, a + b * 0.2, a + c * 0.2)),
        1 => point().prop_map(|a| Triangle::new(a, a, a)),
        1 => (point(), point()).prop_map(|(a, b)| Triangle::new(a, b, a)),
        1 => (point(), point()).prop_map(|(a, b)| Triangle::new(a, Vec3::new(b.x, b.y, a.z), Vec3::new(a.x, b.y, a.z))),
    ]
}

/// A scene of `1..max` triangles with duplicates, in one of the [`FRAMES`].
pub fn scene(max: usize) -> impl Strategy<Value = Vec<Triangle>> {
    (
        prop::collection::vec(triangle(), 1..max),
        0..FRAMES.len(),
        any::<u8>(),
    )
        .prop_map(|(mut tris, frame, dup)| {
            // Duplicate a few triangles exactly (identical centroids).
            let k = tris.len();
            for i in 0..(dup as usize % 4).min(k) {
                let t = tris[i * 7 % k];
                tris.push(t);
            }
            let (scale, offset) = FRAMES[frame];
            for t in &mut tris {
                for v in &mut t.v {
                    *v = *v * scale + Vec3::splat(offset);
                }
            }
            tris
        })
}

/// A built tree's storage: nodes, indices, and the depth.
pub type Built<B> = (Vec<Node<B>>, Vec<u32>, usize);

/// Builds with Vec storage; returns the owned storage.
pub fn build<B: BoundingVolume, P: Primitive>(
    cfg: &TopDown,
    prims: &[P],
) -> Result<Built<B>, bvhkit::Error> {
    let mut nodes = vec![Node::<B>::EMPTY; bvhkit::max_nodes(prims.len())];
    let mut idx = vec![0u32; cfg.index_capacity(prims.len())];
    let (used, depth) = {
        let bvh: Bvh<B> = cfg.build(prims, &mut nodes, &mut idx)?;
        // Every build's report counts the leaves over the stated size.
        let over = bvh
            .nodes()
            .iter()
            .filter(|n| n.is_leaf() && n.count > cfg.stop.max_leaf_size)
            .count();
        assert_eq!(
            bvh.build_report().oversized_leaves as usize,
            over,
            "{cfg:?}"
        );
        (bvh.node_count(), bvh.depth())
    };
    nodes.truncate(used);
    idx.truncate(prims.len());
    Ok((nodes, idx, depth))
}

/// Opens owned storage as a validated tree.
pub fn open<'a, B: BoundingVolume, P: Primitive>(
    nodes: &'a [Node<B>],
    idx: &'a [u32],
    prims: &[P],
) -> Bvh<'a, B> {
    let mut seen = vec![0u32; Bvh::<B>::seen_words(nodes.len(), prims.len())];
    match Bvh::from_parts(nodes, idx, prims, &mut seen) {
        Ok(b) => b,
        Err(e) => panic!(
            "tree over {} primitives failed validation: {e}",
            prims.len()
        ),
    }
}

/// A query region derived from the scene so it usually hits something.
pub fn region_in(prims: &[Triangle], a: f32, b: f32) -> Aabb {
    let mut bounds = Aabb::EMPTY;
    for t in prims {
        bounds = bounds.union(&t.bounds());
    }
    let e = bounds.extent();
    let lo = bounds.min + e * a.min(b);
    let hi = bounds.min + e * a.max(b);
    Aabb::new(lo, hi)
}

/// Checks one configuration and volume type against brute force: invariants,
/// region query, and pair query under every descent rule.
pub fn check_against_brute_force<B: BoundingVolume>(
    cfg: &TopDown,
    a: &[Triangle],
    b: &[Triangle],
    region: &Aabb,
) -> Result<(), TestCaseError> {
    let (na, ia, _) = build::<B, _>(cfg, a).map_err(|e| TestCaseError::fail(format!("{e}")))?;
    let (nb, ib, _) = build::<B, _>(cfg, b).map_err(|e| TestCaseError::fail(format!("{e}")))?;
    check_trees_against_brute_force((&na, &ia), a, (&nb, &ib), b, region, cfg)
}

/// [`check_against_brute_force`] on trees already built (any builder):
/// validated, then every query checked. `cfg` names them in failures.
pub fn check_trees_against_brute_force<B: BoundingVolume>(
    (na, ia): (&[Node<B>], &[u32]),
    a: &[Triangle],
    (nb, ib): (&[Node<B>], &[u32]),
    b: &[Triangle],
    region: &Aabb,
    cfg: &dyn std::fmt::Debug,
) -> Result<(), TestCaseError> {
    let ta = open(na, ia, a);
    let tb = open(nb, ib, b);

    let mut got = Vec::new();
    let n = ta.overlapping(a, region, |i| got.push(i)).unwrap();
    let mut want = Vec::new();
    brute_force::overlapping(a, region, |i| want.push(i));
    got.sort_unstable();
    prop_assert_eq!(n, got.len());
    prop_assert_eq!(&got, &want, "region query, {} {:?}", B::NAME, cfg);
    check_self(&ta, a, cfg)?;

    // Non-box regions: a sphere and a slanted 14-DOP derived from the box.
    let ball = bvhkit::Sphere::new(region.center(), region.extent().length() * 0.35);
    let slab = bvhkit::Dop14::fit(&[
        region.min,
        region.max,
        Vec3::new(region.min.x, region.max.y, region.min.z),
    ]);
    for (name, got, want) in [
        ("sphere", query(&ta, a, &ball), reference(a, &ball)),
        ("14-dop", query(&ta, a, &slab), reference(a, &slab)),
    ] {
        prop_assert_eq!(got, want, "{} region, {} tree {:?}", name, B::NAME, cfg);
    }

    let mut want = Vec::new();
    brute_force::pairs(a, b, |i, j| want.push((i, j)));
    want.sort_unstable();
    for rule in Descent::ALL {
        let mut got = Vec::new();
        let n = overlapping_pairs(&ta, a, &tb, b, rule, |i, j| got.push((i, j))).unwrap();
        got.sort_unstable();
        prop_assert_eq!(n, got.len());
        prop_assert_eq!(&got, &want, "pairs, {} {:?} {:?}", B::NAME, rule, cfg);
    }
    check_pairs(&ta, a, &tb, b, &Same, Bounds, cfg)?;
    // The same trees with their primitives' bounds kept in leaf order: the
    // leaf step reads those instead of the primitives (on one side or both).
    let (mut ba, mut bb) = (vec![Aabb::EMPTY; a.len()], vec![Aabb::EMPTY; b.len()]);
    let la = ta.with_leaf_bounds(a, &mut ba).unwrap();
    let lb = tb.with_leaf_bounds(b, &mut bb).unwrap();
    check_pairs(&la, a, &lb, b, &Same, Bounds, cfg)?;
    // Region queries read the kept bounds too, in every order.
    prop_assert_eq!(query(&la, a, region), reference(a, region));
    prop_assert_eq!(query(&la, a, &ball), reference(a, &ball));
    let mut queue = vec![0u32; la.breadth_first_queue()];
    for order in 0..3 {
        let order = match order {
            0 => bvhkit::Order::DepthFirst,
            1 => bvhkit::Order::Recursive,
            _ => bvhkit::Order::BreadthFirst(&mut queue),
        };
        let mut got = Vec::new();
        la.search(a, &slab, order, (), |i| got.push(i)).unwrap();
        got.sort_unstable();
        prop_assert_eq!(&got, &reference(a, &slab), "kept bounds, 14-dop region");
    }
    check_pairs(&la, a, &tb, b, &Same, bvhkit::Exact, cfg)?;
    check_pairs(&ta, a, &lb, b, &Same, Bounds, cfg)?;
    Ok(())
}

/// Every traversal kind with every descent rule, plus a user combination.
pub fn all_traversals() -> Vec<PairTraversal<DepthSwitch<Descent, Descent>>> {
    let mut out = Vec::new();
    let fixed = |d: Descent| DepthSwitch {
        depth: 0,
        near: d,
        far: d,
    };
    for rule in Descent::ALL {
        out.push(PairTraversal::Recursive(fixed(rule)));
        out.push(PairTraversal::Stack(fixed(rule)));
    }
    let mixed = DepthSwitch {
        depth: 3,
        near: Descent::Simultaneous,
        far: Descent::Overlap,
    };
    out.push(PairTraversal::Stack(mixed));
    out.push(PairTraversal::Recursive(mixed));
    out.push(PairTraversal::Simultaneous);
    out.push(PairTraversal::LeafDirected);
    out
}

/// Checks every traversal and the three result modes against
/// [`brute_force::pairs_placed`] for one frame and answer.
pub fn check_pairs<A, H, F, X>(
    ta: &A,
    a: &[Triangle],
    tb: &H,
    b: &[Triangle],
    frame: &F,
    answer: X,
    cfg: &dyn std::fmt::Debug,
) -> Result<(), TestCaseError>
where
    A: Hierarchy,
    H: Hierarchy<Bv = A::Bv>,
    F: Frame + Place<Triangle> + Copy + std::fmt::Debug,
    X: Answer<Triangle, Triangle> + Copy + std::fmt::Debug,
{
    let mut want = Vec::new();
    brute_force::pairs_placed(a, b, frame, answer, |i, j| want.push((i, j)));
    want.sort_unstable();
    for traversal in all_traversals() {
        let query = || {
            Pairs::new(ta, a, tb, b)
                .traversal(traversal)
                .in_frame_of(*frame)
                .answer(answer)
        };
        let mut got = Vec::new();
        let mut counts = Counts::default();
        let n = query()
            .counted(&mut counts)
            .for_each(|i, j| got.push((i, j)))
            .unwrap();
        got.sort_unstable();
        prop_assert_eq!(n, got.len());
        prop_assert_eq!(
            &got,
            &want,
            "{} tree, {:?}, {:?}, {:?}, {:?}",
            <A::Bv as BoundingVolume>::NAME,
            traversal,
            frame,
            answer,
            cfg
        );
        prop_assert!(counts.prim_tests >= n as u64);
        prop_assert_eq!(counts.updates > 0, F::MOVES);
        prop_assert_eq!(query().count().unwrap(), want.len());
        let first = query().first().unwrap();
        prop_assert_eq!(first.is_some(), !want.is_empty());
        if let Some(p) = first {
            prop_assert!(
                want.binary_search(&p).is_ok(),
                "first pair {:?} is not an answer",
                p
            );
        }
    }
    Ok(())
}

/// Checks the self query of `tree` over `prims` against brute force, for
/// every traversal: all overlapping pairs, neighbours skipped (the
/// default), an id rule, and exact; each pair `i < j` exactly once, in two
/// result modes. One filter and one answer type switched at run time, so
/// the query is compiled once per tree type (this runs on every layout).
pub fn check_self<H: Hierarchy>(
    tree: &H,
    prims: &[Triangle],
    cfg: &dyn std::fmt::Debug,
) -> Result<(), TestCaseError> {
    use bvhkit::query::{Adjacent, SelfFilter, SelfPairs};
    use bvhkit::Intersects;
    #[derive(Clone, Copy, Debug, PartialEq)]
    enum Mode {
        All,
        NoNeighbours,
        IdRule,
        Exact,
    }
    let rule = |i: u32, j: u32| (i + 2 * j).is_multiple_of(3);
    struct Filter(Mode);
    impl SelfFilter<Triangle> for Filter {
        fn skip(&mut self, i: u32, j: u32, p: &Triangle, q: &Triangle) -> bool {
            match self.0 {
                Mode::All => false,
                Mode::IdRule => (i + 2 * j).is_multiple_of(3),
                Mode::NoNeighbours | Mode::Exact => p.adjacent(q),
            }
        }
    }
    let mut all = Vec::new();
    brute_force::self_pairs(prims, |i, j| all.push((i, j)));
    let apart = |&(i, j): &(u32, u32)| !prims[i as usize].adjacent(&prims[j as usize]);
    let not_adjacent: Vec<_> = all.iter().copied().filter(apart).collect();
    let touching: Vec<_> = not_adjacent
        .iter()
        .copied()
        .filter(|&(i, j)| prims[i as usize].intersects(&prims[j as usize]))
        .collect();
    let wants = [
        (Mode::All, all.clone()),
        (Mode::NoNeighbours, not_adjacent),
        (
            Mode::IdRule,
            all.iter().copied().filter(|&(i, j)| !rule(i, j)).collect(),
        ),
        (Mode::Exact, touching),
    ];
    let name = <H::Bv as BoundingVolume>::NAME;
    for traversal in all_traversals() {
        for (mode, want) in &wants {
            let exact = *mode == Mode::Exact;
            let answer = move |p: &Triangle, q: &Triangle| !exact || p.intersects(q);
            let mut counts = Counts::default();
            let q = || {
                SelfPairs::new(tree, prims)
                    .traversal(traversal)
                    .filter(Filter(*mode))
                    .answer(answer)
            };
            let mut got = Vec::new();
            let n = q()
                .counted(&mut counts)
                .for_each(|i, j| got.push((i, j)))
                .map_err(|e| TestCaseError::fail(format!("{e}")))?;
            prop_assert_eq!(n, got.len());
            prop_assert!(got.iter().all(|&(i, j)| i < j), "a pair not ordered i < j");
            got.sort_unstable();
            prop_assert_eq!(
                &got,
                want,
                "self, {:?}, {} {:?} {:?}",
                mode,
                name,
                traversal,
                cfg
            );
            prop_assert!(counts.prim_tests >= n as u64);
            let first = q().counted(&mut counts).first().unwrap();
            prop_assert_eq!(first.is_some(), !want.is_empty());
            if let Some(p) = first {
                prop_assert!(
                    want.binary_search(&p).is_ok(),
                    "first pair {:?} is not an answer",
                    p
                );
            }
        }
    }
    Ok(())
}

fn query<B: BoundingVolume, R: bvhkit::Region>(t: &Bvh<B>, prims: &[Triangle], r: &R) -> Vec<u32> {
    let mut got = Vec::new();
    let n = t.overlapping(prims, r, |i| got.push(i)).unwrap();
    assert_eq!(n, got.len());
    got.sort_unstable();
    got
}

fn reference<R: BoundingVolume>(prims: &[Triangle], r: &R) -> Vec<u32> {
    let mut want = Vec::new();
    brute_force::overlapping(prims, r, |i| want.push(i));
    want
}

/// Builds bottom-up with Vec storage (and Vec scratch); returns the storage.
pub fn build_bottom_up<B: BoundingVolume, P: Primitive>(
    cfg: &bvhkit::builders::BottomUp,
    prims: &[P],
) -> Result<Built<B>, bvhkit::Error> {
    use bvhkit::builders::{BottomUp, BottomUpScratch, Cluster};
    let (nc, nw, nk) = BottomUp::scratch_len(prims.len());
    let mut clusters = vec![Cluster::<B>::EMPTY; nc];
    let (mut work, mut keys) = (vec![0u32; nw], vec![0u64; nk]);
    let mut scratch = BottomUpScratch {
        clusters: &mut clusters,
        work: &mut work,
        keys: &mut keys,
    };
    let mut nodes = vec![Node::<B>::EMPTY; bvhkit::max_nodes(prims.len())];
    let mut idx = vec![0u32; prims.len()];
    let (used, depth) = {
        let bvh = cfg.build(prims, &mut nodes, &mut idx, &mut scratch)?;
        (bvh.node_count(), bvh.depth())
    };
    // A collapse leaves fewer nodes than the buffer holds.
    nodes.truncate(used);
    Ok((nodes, idx, depth))
}

/// Checks both distance queries of tree `a` over `pa` against tree `b` over
/// `pb` against brute force: the closest pair's distance (the pair itself
/// may differ among equals, so its recomputed points must match), and the
/// pairs within 0, the least distance, and `radius`. Returns how many
/// answers were compared.
pub fn check_distance<A: Hierarchy, H: Hierarchy, P: PairDistance<Q>, Q: Clone>(
    a: &A,
    pa: &[P],
    b: &H,
    pb: &[Q],
    radius: f64,
    cfg: &dyn std::fmt::Debug,
) -> Result<usize, TestCaseError> {
    let want = brute_force::closest_pair(pa, pb);
    let got = Distance::new(a, pa, b, pb)
        .closest()
        .map_err(|e| TestCaseError::fail(format!("{cfg:?}: {e}")))?;
    match (want, got) {
        (None, None) => {}
        (Some(w), Some(g)) => {
            prop_assert_eq!(
                g.points.distance_squared,
                w.points.distance_squared,
                "{:?}: closest {:?} against brute force {:?}",
                cfg,
                g,
                w
            );
            prop_assert_eq!(
                pa[g.a as usize].closest_points(&pb[g.b as usize]),
                g.points,
                "{:?}",
                cfg
            );
        }
        (w, g) => prop_assert!(false, "{:?}: closest {:?}, brute force {:?}", cfg, g, w),
    }
    let mut compared = 1;
    let least = want.map_or(0.0, |w| w.distance());
    for d in [0.0, least, radius] {
        let mut expect = Vec::new();
        brute_force::pairs_within(pa, pb, d, |i, j| expect.push((i, j)));
        let mut found = Vec::new();
        let n = Distance::new(a, pa, b, pb)
            .within(d, |i, j| found.push((i, j)))
            .map_err(|e| TestCaseError::fail(format!("{cfg:?}: {e}")))?;
        prop_assert_eq!(n, found.len());
        found.sort_unstable();
        prop_assert_eq!(&found, &expect, "{:?}: pairs within {}", cfg, d);
        compared += 1;
    }
    Ok(compared)
}

/// Sphere and box casts from `origin` along `dir` (shapes of about `size`)
/// on any tree, every order and the any-hit variant, against
/// [`brute_force::cast_closest`]. Returns how many casts hit, so a caller can
/// check its scenes exercise hits and misses.
pub fn check_casts<H: bvhkit::Query, P: bvhkit::CastTarget>(
    h: &H,
    prims: &[P],
    origin: Vec3,
    dir: Vec3,
    size: f32,
    t_max: f32,
    name: &str,
) -> Result<usize, TestCaseError> {
    use bvhkit::{RayOrder, ShapeCast};
    let mut hits = 0;
    let boxed = Aabb::new(
        origin - Vec3::new(size, 0.5 * size, 0.25 * size),
        origin + Vec3::new(0.5 * size, size, 0.75 * size),
    );
    for cast in [
        ShapeCast::sphere(origin, size, dir, t_max),
        ShapeCast::aabb(&boxed, dir, t_max),
        ShapeCast::sphere(origin, 0.0, dir, t_max),
    ] {
        let cast = cast.map_err(|e| TestCaseError::fail(format!("{e}")))?;
        let want = brute_force::cast_closest(prims, &cast);
        hits += usize::from(want.is_some());
        for order in [RayOrder::DepthFirst, RayOrder::BestFirst] {
            let got = h.cast_shape(prims, &cast, order, ()).unwrap();
            prop_assert_eq!(got, want, "{} {:?} cast {:?}", name, order, cast);
        }
        let any = h.shape_hits_any(prims, &cast, ()).unwrap();
        prop_assert_eq!(any.is_some(), want.is_some(), "{} any {:?}", name, cast);
        if let Some(a) = any {
            prop_assert_eq!(
                bvhkit::CastTarget::cast_hit(&prims[a.prim as usize], &cast),
                Some(a.t)
            );
        }
    }
    Ok(hits)
}
