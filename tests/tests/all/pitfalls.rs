//! Every failure in `shared/PITFALLS.md` (reported against other BVH libraries),
//! turned into a test, plus regressions found while building bvhkit.

use bvhkit::glam::Vec3;
use bvhkit::{
    brute_force, overlapping_pairs, Aabb, BoundingVolume, Bvh, Descent, Dop14, Error, Exact, Node,
    Obb, OnFailure, Order, PairTraversal, Pairs, Partition, Ray, RayOrder, Rigid, Sphere,
    SplitPoint, Stop, TopDown, Triangle,
};
use bvhkit_tests::{build, open};

fn pairs_sorted<B: BoundingVolume>(
    cfg: &TopDown,
    a: &[Triangle],
    b: &[Triangle],
    rule: Descent,
) -> Vec<(u32, u32)> {
    let (na, ia, _) = build::<B, _>(cfg, a).unwrap();
    let (nb, ib, _) = build::<B, _>(cfg, b).unwrap();
    let (ta, tb) = (open(&na, &ia, a), open(&nb, &ib, b));
    let mut got = Vec::new();
    overlapping_pairs(&ta, a, &tb, b, rule, |i, j| got.push((i, j))).unwrap();
    got.sort_unstable();
    // The same trees keeping their primitives' bounds in leaf order must
    // give the same answer on every pitfall scene.
    let (mut ba, mut bb) = (vec![Aabb::EMPTY; a.len()], vec![Aabb::EMPTY; b.len()]);
    let (ka, kb) = (
        ta.with_leaf_bounds(a, &mut ba).unwrap(),
        tb.with_leaf_bounds(b, &mut bb).unwrap(),
    );
    let mut kept = Vec::new();
    overlapping_pairs(&ka, a, &kb, b, rule, |i, j| kept.push((i, j))).unwrap();
    kept.sort_unstable();
    assert_eq!(kept, got, "kept leaf bounds change the answer");
    got
}

fn brute(a: &[Triangle], b: &[Triangle]) -> Vec<(u32, u32)> {
    let mut want = Vec::new();
    brute_force::pairs(a, b, |i, j| want.push((i, j)));
    want
}

fn tri_at(o: Vec3, s: f32) -> Triangle {
    Triangle::new(o, o + Vec3::new(s, 0.0, 0.0), o + Vec3::new(0.0, s, s))
}

fn all_configs() -> Vec<TopDown> {
    let mut v = vec![TopDown::sah(), TopDown::sah_sweep(), TopDown::median()];
    for partition in bvhkit_tests::PARTITIONS {
        for split in bvhkit_tests::SPLITS {
            if split == SplitPoint::Sweep && partition != Partition::SurfaceArea {
                continue;
            }
            for axis in bvhkit_tests::AXES {
                v.push(
                    TopDown {
                        partition,
                        split,
                        axis,
                        ..TopDown::sah()
                    }
                    .with_max_leaf_size(1),
                );
            }
        }
    }
    v
}

/// Regression: the builder continued with the larger half and pushed the
/// smaller; splits that peel one primitive at a time then grew the task stack
/// linearly (found by the property tests at 40 entries).
#[test]
fn builder_stack_stays_logarithmic_when_splits_peel_one_primitive() {
    // Exponentially spaced along x: SAH and spatial splits peel a few primitives at a time.
    let tris: Vec<Triangle> = (0..5000)
        .map(|i| tri_at(Vec3::new(1.01f32.powi(i), 0.0, 0.0), 1e-3))
        .collect();
    let spatial = TopDown {
        split: SplitPoint::SpatialMedian,
        ..TopDown::sah()
    };
    for cfg in [TopDown::sah(), TopDown::sah_sweep(), spatial] {
        let (nodes, idx, depth) = build::<Aabb, _>(&cfg.with_max_leaf_size(1), &tris).unwrap();
        let t = open(&nodes, &idx, &tris);
        assert!(depth <= bvhkit::MAX_DEPTH);
        assert_eq!(t.primitive_count(), tris.len());
    }
}

/// Zero-area triangles, points and segments build and query correctly.
#[test]
fn degenerate_primitives_build_and_query() {
    let mut a = Vec::new();
    for i in 0..30 {
        let o = Vec3::new(i as f32 * 0.5, (i % 3) as f32, 0.0);
        a.push(Triangle::new(o, o, o)); // point
        a.push(Triangle::new(o, o + Vec3::X, o)); // segment
        a.push(Triangle::new(o, o + Vec3::X, o + Vec3::X * 2.0)); // collinear
    }
    let b: Vec<_> = a
        .iter()
        .map(|t| t.translated(Vec3::new(0.25, 0.0, 0.0)))
        .collect();
    let want = brute(&a, &b);
    assert!(!want.is_empty());
    for cfg in all_configs() {
        assert_eq!(
            pairs_sorted::<Aabb>(&cfg, &a, &b, Descent::Larger),
            want,
            "{cfg:?}"
        );
        assert_eq!(
            pairs_sorted::<Sphere>(&cfg, &a, &b, Descent::Simultaneous),
            want,
            "{cfg:?}"
        );
    }
}

/// n = 0 builds the empty tree (no nodes) even into no storage; n = 0..=3
/// work for every builder and query.
#[test]
fn empty_single_and_two_primitive_inputs() {
    let none: [Triangle; 0] = [];
    let empty = TopDown::sah()
        .build::<_, Aabb>(&none, &mut [], &mut [])
        .unwrap();
    assert!(empty.is_empty() && empty.root().is_none());
    assert_eq!((empty.node_count(), empty.depth()), (0, 0));
    for n in 0..=3 {
        let a: Vec<_> = (0..n).map(|i| tri_at(Vec3::splat(i as f32), 1.0)).collect();
        for cfg in all_configs() {
            assert_eq!(
                pairs_sorted::<Aabb>(&cfg, &a, &a, Descent::Larger),
                brute(&a, &a)
            );
            assert_eq!(
                pairs_sorted::<Obb>(&cfg, &a, &a, Descent::AFirst),
                brute(&a, &a)
            );
        }
    }
}

/// Tiny trees (1, 2, 3 leaves each side), far apart and touching.
#[test]
fn tiny_trees_far_apart_and_touching() {
    for na in 1..=3 {
        for nb in 1..=3 {
            for gap in [100.0f32, 1.0, 0.5, 0.0] {
                let a: Vec<_> = (0..na)
                    .map(|i| tri_at(Vec3::new(i as f32, 0.0, 0.0), 1.0))
                    .collect();
                let b: Vec<_> = (0..nb)
                    .map(|i| tri_at(Vec3::new(i as f32, gap, 0.0), 1.0))
                    .collect();
                let want = brute(&a, &b);
                if gap == 100.0 {
                    assert!(want.is_empty());
                }
                if gap == 0.5 {
                    assert!(!want.is_empty());
                }
                let cfg = TopDown::sah().with_max_leaf_size(1);
                for rule in Descent::ALL {
                    assert_eq!(pairs_sorted::<Aabb>(&cfg, &a, &b, rule), want);
                    assert_eq!(pairs_sorted::<Sphere>(&cfg, &a, &b, rule), want);
                    assert_eq!(pairs_sorted::<Dop14>(&cfg, &a, &b, rule), want);
                }
                // Every traversal kind, also with B moved and the exact test.
                let (na_, ia_, _) = build::<Aabb, _>(&cfg, &a).unwrap();
                let (nb_, ib_, _) = build::<Aabb, _>(&cfg, &b).unwrap();
                let (ta, tb) = (open(&na_, &ia_, &a), open(&nb_, &ib_, &b));
                let nudge = Rigid::translation(Vec3::new(0.0, 0.0, 1e-3)).unwrap();
                let mut exact_want = Vec::new();
                brute_force::pairs_placed(&a, &b, &nudge, Exact, |i, j| exact_want.push((i, j)));
                exact_want.sort_unstable();
                for rule in Descent::ALL {
                    for traversal in PairTraversal::all(rule) {
                        let mut got = Vec::new();
                        Pairs::new(&ta, &a, &tb, &b)
                            .traversal(traversal)
                            .for_each(|i, j| got.push((i, j)))
                            .unwrap();
                        got.sort_unstable();
                        assert_eq!(got, want, "{traversal:?}, gap {gap}, {na}x{nb}");
                        let mut got = Vec::new();
                        Pairs::new(&ta, &a, &tb, &b)
                            .traversal(traversal)
                            .in_frame(nudge)
                            .exact()
                            .for_each(|i, j| got.push((i, j)))
                            .unwrap();
                        got.sort_unstable();
                        assert_eq!(got, exact_want, "{traversal:?} moved, gap {gap}, {na}x{nb}");
                    }
                }
            }
        }
    }
}

/// NaN/inf input is rejected up front with an error naming the primitive.
#[test]
fn nan_and_infinity_are_rejected_naming_the_primitive() {
    let mut nodes = vec![Node::<Aabb>::EMPTY; 20];
    let mut idx = vec![0u32; 10];
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        for pos in [0usize, 3, 9] {
            for corner in 0..3 {
                let mut tris: Vec<_> = (0..10)
                    .map(|i| tri_at(Vec3::splat(i as f32), 1.0))
                    .collect();
                tris[pos].v[corner].y = bad;
                let err = TopDown::sah()
                    .build(&tris, &mut nodes, &mut idx)
                    .unwrap_err();
                assert_eq!(err, Error::NonFiniteCoordinate { primitive: pos });
                assert!(err.to_string().contains(&format!("primitive {pos}")));
            }
        }
    }
}

/// Finite coordinates up to 1e30 build and query exactly; beyond the limit is an error.
#[test]
fn huge_finite_coordinates_work_and_beyond_the_limit_is_an_error() {
    for scale in [1e19f32, 1e25, 1e30] {
        let a: Vec<_> = (0..50)
            .map(|i| {
                tri_at(
                    Vec3::new(i as f32, (i % 5) as f32, 0.0) * scale * 1e-2 + Vec3::splat(scale),
                    scale * 1e-2,
                )
            })
            .collect();
        let b: Vec<_> = a
            .iter()
            .map(|t| t.translated(Vec3::splat(scale * 3e-3)))
            .collect();
        let want = brute(&a, &b);
        assert!(!want.is_empty(), "scale {scale}");
        for cfg in [TopDown::sah(), TopDown::sah_sweep(), TopDown::median()] {
            assert_eq!(pairs_sorted::<Aabb>(&cfg, &a, &b, Descent::Larger), want);
            assert_eq!(pairs_sorted::<Sphere>(&cfg, &a, &b, Descent::Larger), want);
            assert_eq!(pairs_sorted::<Obb>(&cfg, &a, &b, Descent::Larger), want);
            assert_eq!(pairs_sorted::<Dop14>(&cfg, &a, &b, Descent::Larger), want);
        }
    }
    let tris = [tri_at(Vec3::splat(2e32), 1.0)];
    let mut nodes = [Node::<Aabb>::EMPTY; 1];
    let mut idx = [0u32; 1];
    assert_eq!(
        TopDown::sah()
            .build(&tris, &mut nodes, &mut idx)
            .unwrap_err(),
        Error::CoordinateOutOfRange { primitive: 0 }
    );
}

/// Coplanar and flat (zero-thickness) scenes along each axis.
#[test]
fn flat_scenes_along_each_axis() {
    for axis in 0..3 {
        let flatten = |mut t: Triangle| {
            for v in &mut t.v {
                v[axis] = 3.0;
            }
            t
        };
        let a: Vec<_> = (0..60)
            .map(|i| {
                flatten(tri_at(
                    Vec3::new((i % 8) as f32, (i / 8) as f32, (i % 5) as f32),
                    1.1,
                ))
            })
            .collect();
        let b: Vec<_> = a
            .iter()
            .map(|t| t.translated(Vec3::splat(0.3)))
            .map(flatten)
            .collect();
        let want = brute(&a, &b);
        assert!(!want.is_empty());
        for cfg in all_configs() {
            assert_eq!(
                pairs_sorted::<Aabb>(&cfg, &a, &b, Descent::Larger),
                want,
                "{cfg:?}"
            );
        }
        for cfg in [TopDown::sah(), TopDown::median()] {
            assert_eq!(pairs_sorted::<Obb>(&cfg, &a, &b, Descent::Larger), want);
            assert_eq!(pairs_sorted::<Sphere>(&cfg, &a, &b, Descent::Larger), want);
        }
    }
}

/// Identical centroids (all primitives in one bin): the builder terminates
/// with a forced split or a leaf, as configured.
#[test]
fn identical_centroids_terminate() {
    let a = vec![tri_at(Vec3::ONE, 1.0); 300];
    for on_failure in [OnFailure::ForceSplit, OnFailure::Leaf] {
        for base in all_configs() {
            let cfg = TopDown { on_failure, ..base };
            let (nodes, idx, _) = build::<Aabb, _>(&cfg, &a).unwrap();
            let t = open(&nodes, &idx, &a);
            let s = t.stats();
            match on_failure {
                OnFailure::ForceSplit => {
                    assert!(s.max_leaf_size <= cfg.stop.max_leaf_size as usize)
                }
                OnFailure::Leaf => assert_eq!((s.leaves, s.max_leaf_size), (1, 300)),
            }
        }
    }
}

/// Criteria that split off a few primitives at a time (here: exponentially
/// spaced input; on real meshes, minimum overlap and maximum separation)
/// used to spend all 64 levels and end in leaves far over the limit,
/// silently. Once the levels left are only just enough, the builder halves
/// at the object median, so every leaf keeps to the stated size.
#[test]
fn leaves_keep_their_size_when_a_criterion_peels_primitives() {
    let tris: Vec<Triangle> = (0..5000)
        .map(|i| tri_at(Vec3::new(1.01f32.powi(i), 0.0, 0.0), 1e-3))
        .collect();
    for p in bvhkit::builders::PRESETS {
        for leaf in [1, 4] {
            let cfg = p.builder.with_max_leaf_size(leaf);
            let (nodes, idx, depth) = build::<Aabb, _>(&cfg, &tris).unwrap();
            let s = open(&nodes, &idx, &tris).stats();
            assert!(depth <= bvhkit::MAX_DEPTH, "{}", p.name);
            assert!(
                s.max_leaf_size <= leaf as usize,
                "{} (leaf {leaf}): a leaf of {} at depth {}",
                p.name,
                s.max_leaf_size,
                s.max_depth
            );
        }
    }
    // A depth cap the caller chose still stops the build (leaves grow).
    let capped = TopDown {
        stop: Stop {
            max_depth: 3,
            ..Stop::default()
        },
        ..TopDown::sah()
    };
    let (nodes, idx, depth) = build::<Aabb, _>(&capped, &tris).unwrap();
    assert!(depth <= 3);
    assert_eq!(open(&nodes, &idx, &tris).primitive_count(), tris.len());
}

/// Sorted, collinear input cannot make the tree deeper than the traversal
/// stacks: the builder bounds the depth, and leaves grow instead.
#[test]
fn depth_is_bounded_for_adversarial_input() {
    let tris: Vec<Triangle> = (0..5000)
        .map(|i| tri_at(Vec3::new(1.01f32.powi(i), 0.0, 0.0), 1e-3))
        .collect();
    for cfg in [
        TopDown::sah().with_max_leaf_size(1),
        TopDown {
            split: SplitPoint::SpatialMedian,
            ..TopDown::sah()
        }
        .with_max_leaf_size(1),
    ] {
        let (nodes, idx, depth) = build::<Aabb, _>(&cfg, &tris).unwrap();
        assert!(depth <= bvhkit::MAX_DEPTH);
        let t = open(&nodes, &idx, &tris);
        let region = Aabb::new(Vec3::new(10.0, -1.0, -1.0), Vec3::new(100.0, 1.0, 1.0));
        let mut got = Vec::new();
        t.overlapping(&tris, &region, |i| got.push(i)).unwrap();
        got.sort_unstable();
        let mut want = Vec::new();
        brute_force::overlapping(&tris, &region, |i| want.push(i));
        assert_eq!(got, want);
    }
}

/// Same input, same configuration: the same tree and the same pair order, bit for bit.
#[test]
fn builds_and_queries_are_deterministic() {
    let a: Vec<_> = (0..400)
        .map(|i| {
            tri_at(
                Vec3::new((i * 37 % 101) as f32, (i * 11 % 29) as f32, (i % 7) as f32),
                2.0,
            )
        })
        .collect();
    for cfg in all_configs().into_iter().step_by(7) {
        let (n1, i1, _) = build::<Sphere, _>(&cfg, &a).unwrap();
        let (n2, i2, _) = build::<Sphere, _>(&cfg, &a).unwrap();
        assert_eq!(i1, i2);
        assert!(n1.iter().zip(&n2).all(|(x, y)| x.first == y.first
            && x.count == y.count
            && x.bv.center.to_array().map(f32::to_bits)
                == y.bv.center.to_array().map(f32::to_bits)
            && x.bv.radius.to_bits() == y.bv.radius.to_bits()));
        let t1 = open(&n1, &i1, &a);
        let mut p1 = Vec::new();
        let mut p2 = Vec::new();
        overlapping_pairs(&t1, &a, &t1, &a, Descent::Larger, |i, j| p1.push((i, j))).unwrap();
        overlapping_pairs(&t1, &a, &t1, &a, Descent::Larger, |i, j| p2.push((i, j))).unwrap();
        assert_eq!(p1, p2);
    }
}

/// A query given the wrong primitive slice is an error, not an out-of-bounds panic.
#[test]
fn query_with_the_wrong_primitives_is_an_error() {
    let a: Vec<_> = (0..10)
        .map(|i| tri_at(Vec3::splat(i as f32), 1.0))
        .collect();
    let (nodes, idx, _) = build::<Aabb, _>(&TopDown::sah(), &a).unwrap();
    let t = open(&nodes, &idx, &a);
    let err = t
        .overlapping(&a[..5], &Aabb::new(Vec3::ZERO, Vec3::ONE), |_| {})
        .unwrap_err();
    assert_eq!(err, Error::PrimitiveCountMismatch { tree: 10, given: 5 });
    let mut seen = vec![0u32; 4];
    assert!(Bvh::from_parts(&nodes, &idx, &a[..5], &mut seen).is_err());
    let mismatch = Error::PrimitiveCountMismatch { tree: 10, given: 5 };
    for traversal in PairTraversal::all(Descent::Larger) {
        let q = Pairs::new(&t, &a[..5], &t, &a).traversal(traversal);
        assert_eq!(q.count().unwrap_err(), mismatch);
    }
    let ray = Ray::new(Vec3::ZERO, Vec3::X, 1.0).unwrap();
    assert_eq!(
        t.cast_ray(&a[..5], &ray, RayOrder::BestFirst, ())
            .unwrap_err(),
        mismatch
    );
    assert_eq!(t.ray_hits_any(&a[..5], &ray, ()).unwrap_err(), mismatch);
    assert_eq!(t.nearest(&a[..5], Vec3::ZERO, ()).unwrap_err(), mismatch);
}

/// A tree claiming more depth than the fixed stacks hold is refused by every
/// query with an error before any stack is touched.
#[test]
fn every_query_refuses_a_tree_deeper_than_its_stack() {
    let a: Vec<_> = (0..10)
        .map(|i| tri_at(Vec3::splat(i as f32), 1.0))
        .collect();
    let (nodes, idx, _) = build::<Aabb, _>(&TopDown::sah(), &a).unwrap();
    let deep = Bvh::from_raw_parts(&nodes, &idx, bvhkit::MAX_DEPTH + 1);
    let is_overflow = |e: Error| matches!(e, Error::StackOverflow { .. });
    for traversal in PairTraversal::all(Descent::Overlap) {
        assert!(is_overflow(
            Pairs::new(&deep, &a, &deep, &a)
                .traversal(traversal)
                .count()
                .unwrap_err()
        ));
    }
    let region = Aabb::new(Vec3::ZERO, Vec3::ONE);
    let mut queue = vec![0u32; 64];
    for order in [
        Order::DepthFirst,
        Order::Recursive,
        Order::BreadthFirst(&mut queue),
    ] {
        assert!(is_overflow(
            deep.search(&a, &region, order, (), |_| {}).unwrap_err()
        ));
    }
    let ray = Ray::new(Vec3::ZERO, Vec3::X, 1.0).unwrap();
    assert!(is_overflow(
        deep.cast_ray(&a, &ray, RayOrder::DepthFirst, ())
            .unwrap_err()
    ));
    assert!(is_overflow(deep.ray_hits_any(&a, &ray, ()).unwrap_err()));
    assert!(is_overflow(deep.nearest(&a, Vec3::ZERO, ()).unwrap_err()));
}

/// The builders say what they did besides following their configuration
/// (#19): splits where the criterion failed and a fallback took over, the
/// depth limit's halvings and rebuilds, and leaves over the stated size
/// (the one warning). The owned tree keeps the report.
#[test]
fn build_reports_count_fallbacks_depth_limits_and_oversized_leaves() {
    use bvhkit::builders::{
        BottomUp, BuildReport, DynamicConfig, InsertOrder, Insertion, Rotations,
    };
    use bvhkit_std::OwnedBvh;
    let row: Vec<Triangle> = (0..5000)
        .map(|i| tri_at(Vec3::new(1.01f32.powi(i), 0.0, 0.0), 1e-3))
        .collect();
    let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(row.len())];
    let mut idx = vec![0u32; row.len()];
    let mut report = |cfg: TopDown, prims: &[Triangle]| {
        let t = cfg.build(prims, &mut nodes, &mut idx).unwrap();
        let r = t.build_report();
        // The oversized count is the tree's own: leaves over the size.
        let over = t
            .nodes()
            .iter()
            .filter(|n| n.is_leaf() && n.count > cfg.stop.max_leaf_size)
            .count();
        assert_eq!(r.oversized_leaves as usize, over, "{cfg:?}");
        assert_eq!(r.max_leaf_size, cfg.stop.max_leaf_size);
        r
    };

    // The default on an ordinary mesh: nothing to report.
    let rock = bvhkit_std::scene::rock(3, 1);
    let quiet = BuildReport {
        max_leaf_size: 4,
        ..BuildReport::default()
    };
    assert_eq!(report(TopDown::sah(), &rock), quiet);
    assert_eq!(report(TopDown::sah(), &row), quiet);

    // Maximum separation peels the row: slivers under 1% are failed splits
    // (the SAH takes over), the rest spends the depth until the budget
    // halves nodes, and leaves keep to their size.
    let separation = TopDown {
        partition: Partition::Separation,
        ..TopDown::sah()
    };
    let r = report(separation, &row);
    assert!(r.fallback_splits > 0 && r.depth_limited > 0, "{r:?}");
    assert!(!r.has_warnings(), "{r:?}");

    // Nothing separates identical triangles: every split is a fallback;
    // made leaves instead, one leaf of 300 with a warning.
    let same = vec![tri_at(Vec3::ONE, 1.0); 300];
    let r = report(TopDown::sah(), &same);
    assert!(r.fallback_splits >= 60 && r.oversized_leaves == 0, "{r:?}");
    let as_leaf = TopDown {
        on_failure: OnFailure::Leaf,
        ..TopDown::sah()
    };
    let r = report(as_leaf, &same);
    assert_eq!((r.fallback_splits, r.oversized_leaves), (1, 1), "{r:?}");
    assert!(r.has_warnings());

    // A depth cap of 3 over 5,000 triangles: the 7 inner nodes are halved
    // by the depth budget, and the 8 leaves of 625 are each over the size.
    let capped = TopDown {
        stop: Stop {
            max_depth: 3,
            ..Stop::default()
        },
        ..TopDown::sah()
    };
    let r = report(capped, &row);
    assert_eq!((r.depth_limited, r.oversized_leaves), (7, 8), "{r:?}");

    // Bottom-up: a chain too deep for the traversals is rebuilt balanced.
    let points: Vec<Vec3> = (0..90)
        .map(|i| Vec3::new(1.3f32.powi(i), 0.0, 0.0))
        .collect();
    let mut limited = 0;
    for cfg in [
        BottomUp::default(),
        BottomUp::exhaustive(Default::default()),
    ] {
        let tree = OwnedBvh::<Aabb>::build_bottom_up(&cfg, &points).unwrap();
        let r = tree.view().build_report();
        // The default collapses to leaves of up to 4; the textbook
        // builder keeps one primitive per leaf.
        assert_eq!(
            (r.fallback_splits, r.oversized_leaves, r.max_leaf_size),
            (0, 0, cfg.collapse.max_leaf_size())
        );
        assert_eq!(tree.plain_view().build_report(), r);
        limited += r.depth_limited;
    }
    assert!(limited > 0);
    let r = OwnedBvh::<Aabb>::build_bottom_up(&BottomUp::default(), &rock)
        .unwrap()
        .view()
        .build_report();
    assert_eq!(r.depth_limited, 0);

    // Insertion without rotations: sorted input reaches the depth limit,
    // and the tree is rebalanced instead of refusing the object.
    let off = Insertion {
        config: DynamicConfig {
            rotations: Rotations::Off,
            ..DynamicConfig::default()
        },
        order: InsertOrder::Sorted,
        ..Insertion::default()
    };
    let tree = OwnedBvh::<Aabb>::build_by_insertion(&off, &row).unwrap();
    let r = tree.view().build_report();
    assert!(
        r.depth_limited > 0 && tree.view().depth() <= bvhkit::MAX_DEPTH,
        "{r:?}"
    );
    let tree = OwnedBvh::<Aabb>::build_by_insertion(&Insertion::default(), &rock).unwrap();
    assert_eq!(tree.view().build_report().depth_limited, 0);
}
