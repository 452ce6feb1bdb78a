//! Bad input gets a clear error: never a panic, a hang or a silent drop.

use bvhkit::glam::Vec3;
use bvhkit::{
    Aabb, Collector, Error, Node, Partition, SplitPoint, Stop, TopDown, Triangle, MAX_DEPTH,
};

fn tris(n: usize) -> Vec<Triangle> {
    (0..n)
        .map(|i| {
            Triangle::new(
                Vec3::splat(i as f32),
                Vec3::splat(i as f32) + Vec3::X,
                Vec3::splat(i as f32) + Vec3::Y,
            )
        })
        .collect()
}

#[test]
fn node_capacity_exceeded_is_an_error() {
    let t = tris(100);
    let mut idx = vec![0u32; 100];
    for cap in [0usize, 1, 10, 198] {
        let mut nodes = vec![Node::<Aabb>::EMPTY; cap];
        let err = TopDown::sah()
            .with_max_leaf_size(1)
            .build(&t, &mut nodes, &mut idx)
            .unwrap_err();
        assert_eq!(
            err,
            Error::NodeCapacity {
                needed: 199,
                available: cap
            }
        );
        assert!(err.to_string().contains("199"));
    }
    let mut nodes = vec![Node::<Aabb>::EMPTY; 199];
    assert!(TopDown::sah()
        .with_max_leaf_size(1)
        .build(&t, &mut nodes, &mut idx)
        .is_ok());
}

#[test]
fn index_capacity_exceeded_is_an_error() {
    let t = tris(50);
    let mut nodes = vec![Node::<Aabb>::EMPTY; 99];
    let mut idx = vec![0u32; 49];
    assert_eq!(
        TopDown::sah().build(&t, &mut nodes, &mut idx).unwrap_err(),
        Error::IndexCapacity {
            needed: 50,
            available: 49
        }
    );
    let mut idx = vec![0u32; 99];
    assert_eq!(
        TopDown::sah_sweep()
            .build(&t, &mut nodes, &mut idx)
            .unwrap_err(),
        Error::IndexCapacity {
            needed: 100,
            available: 99
        }
    );
}

#[test]
fn invalid_configurations_are_errors() {
    let t = tris(10);
    let mut nodes = vec![Node::<Aabb>::EMPTY; 19];
    let mut idx = vec![0u32; 20];
    let bad = [
        TopDown::sah().with_max_leaf_size(0),
        TopDown {
            stop: Stop {
                max_depth: MAX_DEPTH as u32 + 1,
                ..Stop::default()
            },
            ..TopDown::sah()
        },
        TopDown {
            stop: Stop {
                min_volume: f32::NAN,
                ..Stop::default()
            },
            ..TopDown::sah()
        },
        TopDown {
            split: SplitPoint::Bins(1),
            ..TopDown::sah()
        },
        TopDown {
            split: SplitPoint::Bins(200),
            ..TopDown::sah()
        },
        TopDown {
            split: SplitPoint::RandomCentroids { count: 0, seed: 1 },
            ..TopDown::sah()
        },
        TopDown {
            split: SplitPoint::Sweep,
            partition: Partition::Volume,
            ..TopDown::sah()
        },
        TopDown {
            partition: Partition::Weighted {
                surface_area: -1.0,
                volume: 0.0,
                overlap: 0.0,
                balance: 0.0,
            },
            ..TopDown::sah()
        },
    ];
    for cfg in bad {
        match cfg.build(&t, &mut nodes, &mut idx) {
            Err(Error::InvalidConfig(why)) => assert!(!why.is_empty()),
            other => panic!("{cfg:?} gave {other:?}"),
        }
    }
}

#[test]
fn non_finite_user_primitives_are_rejected() {
    let boxes = [
        Aabb::new(Vec3::ZERO, Vec3::ONE),
        Aabb::new(Vec3::ZERO, Vec3::new(1.0, f32::NAN, 1.0)),
    ];
    let mut nodes = vec![Node::<Aabb>::EMPTY; 3];
    let mut idx = vec![0u32; 2];
    assert_eq!(
        TopDown::sah()
            .build(&boxes, &mut nodes, &mut idx)
            .unwrap_err(),
        Error::NonFiniteCoordinate { primitive: 1 }
    );
    let pts = [Vec3::ONE, Vec3::new(f32::INFINITY, 0.0, 0.0)];
    assert_eq!(
        TopDown::sah()
            .build(&pts, &mut nodes, &mut idx)
            .unwrap_err(),
        Error::NonFiniteCoordinate { primitive: 1 }
    );
}

#[test]
fn a_full_result_buffer_reports_the_true_count() {
    let t = tris(20);
    let mut nodes = vec![Node::<Aabb>::EMPTY; 39];
    let mut idx = vec![0u32; 20];
    let bvh = TopDown::sah().build(&t, &mut nodes, &mut idx).unwrap();
    let mut buf = [0u32; 3];
    let mut c = Collector::new(&mut buf);
    let n = bvh
        .overlapping(
            &t,
            &Aabb::new(Vec3::splat(-100.0), Vec3::splat(100.0)),
            |i| c.push(i),
        )
        .unwrap();
    assert_eq!(n, 20);
    assert_eq!(
        c.finish().unwrap_err(),
        Error::ResultCapacity {
            found: 20,
            capacity: 3
        }
    );
}

#[test]
fn every_error_has_a_message() {
    let all = [
        Error::NonFiniteCoordinate { primitive: 3 },
        Error::CoordinateOutOfRange { primitive: 3 },
        Error::IndexOverflow { count: 1 << 40 },
        Error::NodeCapacity {
            needed: 9,
            available: 1,
        },
        Error::IndexCapacity {
            needed: 9,
            available: 1,
        },
        Error::ResultCapacity {
            found: 9,
            capacity: 1,
        },
        Error::StackOverflow {
            depth: 99,
            capacity: 64,
        },
        Error::PrimitiveCountMismatch { tree: 9, given: 1 },
        Error::VertexIndexOutOfRange {
            triangle: 2,
            vertices: 8,
        },
        Error::ScratchCapacity {
            needed: 16,
            available: 4,
        },
        Error::InvalidConfig("x"),
        Error::InvalidTree("y"),
    ];
    for e in all {
        assert!(e.to_string().len() > 10, "{e:?}");
    }
}

/// A query's own input is checked: a NaN or inverted region, a negative
/// radius, a NaN point or ray is an `InvalidQuery`, on a full tree and on an
/// empty one, never an answer of nothing that looks like a miss. Infinite
/// bounds ask for everything.
#[test]
fn unusable_query_inputs_are_invalid_query_errors() {
    use bvhkit::query::{Order, Query, Ray, RayOrder};
    use bvhkit::{BoundingVolume, Dop14, Sphere};
    let t = tris(20);
    let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(20)];
    let mut idx = vec![0u32; 20];
    let full = TopDown::sah().build(&t, &mut nodes, &mut idx).unwrap();
    let empty = TopDown::sah()
        .build(&[] as &[Triangle], &mut [], &mut [])
        .unwrap();
    let nan = Vec3::new(0.0, f32::NAN, 0.0);
    let boxes = [
        Aabb::new(nan, Vec3::ONE),
        Aabb::new(Vec3::ONE, Vec3::ZERO),
        Aabb::new(Vec3::new(0.0, 2.0, 0.0), Vec3::new(1.0, 1.0, 1.0)),
        Aabb::EMPTY,
    ];
    for (tree, prims) in [(&full, &t[..]), (&empty, &[][..])] {
        for b in &boxes {
            let got = tree.overlapping(prims, b, |_| {});
            assert!(matches!(got, Err(Error::InvalidQuery(_))), "{b:?}: {got:?}");
            let got = Query::search(tree, prims, b, Order::DepthFirst, (), |_| {});
            assert!(matches!(got, Err(Error::InvalidQuery(_))), "{b:?}: {got:?}");
        }
        for s in [
            Sphere::new(nan, 1.0),
            Sphere::new(Vec3::ZERO, -1.0),
            Sphere::new(Vec3::ZERO, f32::NAN),
            Sphere::new(Vec3::splat(f32::INFINITY), 1.0),
        ] {
            let got = tree.overlapping(prims, &s, |_| {});
            assert!(matches!(got, Err(Error::InvalidQuery(_))), "{s:?}: {got:?}");
        }
        let mut dop = Dop14::fit(&[Vec3::ZERO, Vec3::ONE][..]);
        dop.min[4] = dop.max[4] + 1.0;
        let got = tree.overlapping(prims, &dop, |_| {});
        assert!(matches!(got, Err(Error::InvalidQuery(_))), "{got:?}");
        let got = tree.nearest(prims, nan, ());
        assert!(matches!(got, Err(Error::InvalidQuery(_))), "{got:?}");
        // Valid regions still answer (everything, on the full tree),
        // infinite ones included.
        let all = Aabb::new(Vec3::splat(-1.0), Vec3::splat(30.0));
        assert_eq!(tree.overlapping(prims, &all, |_| {}), Ok(prims.len()));
        let infinite = Aabb::new(Vec3::splat(f32::NEG_INFINITY), Vec3::splat(f32::INFINITY));
        assert_eq!(tree.overlapping(prims, &infinite, |_| {}), Ok(prims.len()));
        let huge = Sphere::new(Vec3::ZERO, f32::INFINITY);
        assert_eq!(tree.overlapping(prims, &huge, |_| {}), Ok(prims.len()));
    }
    for (o, d, t_max) in [
        (nan, Vec3::X, 1.0),
        (Vec3::ZERO, nan, 1.0),
        (Vec3::ZERO, Vec3::ZERO, 1.0),
        (Vec3::ZERO, Vec3::X, f32::NAN),
        (Vec3::ZERO, Vec3::X, -1.0),
        (Vec3::ZERO, Vec3::splat(f32::INFINITY), 1.0),
    ] {
        assert!(matches!(Ray::new(o, d, t_max), Err(Error::InvalidQuery(_))));
    }
    let ray = Ray::new(Vec3::ZERO, Vec3::X, 1.0).unwrap();
    assert!(matches!(
        ray.with_t_max(f32::NAN),
        Err(Error::InvalidQuery(_))
    ));
    assert_eq!(
        ray.with_t_max(f32::INFINITY).unwrap().t_max(),
        f32::INFINITY
    );
    let hit = full.cast_ray(&t, &ray, RayOrder::DepthFirst, ());
    assert!(hit.is_ok());
}

/// Found by fuzzing (`scripts/fuzz`, target `tree_bytes`): a node whose
/// first child index is out of range, up to `u32::MAX` (where the second
/// child's index wraps to 0), made `Bvh::from_parts` panic instead of
/// refusing the tree.
#[test]
fn trees_from_bytes_with_child_indices_out_of_range_are_refused() {
    use bvhkit::Bvh;
    let tris = tris(2);
    let leaf = |first| Node {
        bv: Aabb::new(Vec3::splat(-10.0), Vec3::splat(10.0)),
        first,
        count: 1,
    };
    for first in [u32::MAX, u32::MAX - 1, 1 << 27, 3] {
        let nodes = [
            Node {
                bv: Aabb::new(Vec3::splat(-10.0), Vec3::splat(10.0)),
                first,
                count: 0,
            },
            leaf(0),
            leaf(1),
        ];
        let mut seen = vec![0u32; Bvh::<Aabb>::seen_words(3, 2)];
        let got = Bvh::from_parts(&nodes, &[0, 1], &tris, &mut seen);
        assert!(
            matches!(got, Err(Error::InvalidTree(_))),
            "first {first}: {got:?}"
        );
    }
}

/// The first bad primitive is named, whichever way it is bad and whatever
/// comes after it: the builders check the whole slice in one pass without
/// stopping, then look the culprit up again.
#[test]
fn the_first_bad_primitive_is_the_one_named() {
    use bvhkit::builders::{BottomUp, Collapse, Method};
    use bvhkit_std::OwnedBvh;
    let ok = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
    let far = Triangle::new(Vec3::ZERO, Vec3::X * 1e33, Vec3::Y);
    let mut corners = [Vec3::ZERO, Vec3::X, Vec3::Y];
    let mut cases = Vec::new();
    // Every coordinate of every corner, each non-finite value.
    for corner in 0..3 {
        for axis in 0..3 {
            for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
                corners[corner][axis] = bad;
                let t = Triangle::new(corners[0], corners[1], corners[2]);
                assert!(!bvhkit::Primitive::is_finite(&t), "{t:?}");
                cases.push((
                    vec![ok, ok, t, far, ok],
                    Error::NonFiniteCoordinate { primitive: 2 },
                ));
                corners = [Vec3::ZERO, Vec3::X, Vec3::Y];
            }
        }
    }
    let nan = Triangle::new(Vec3::NAN, Vec3::X, Vec3::Y);
    cases.push((
        vec![ok, far, nan, ok],
        Error::CoordinateOutOfRange { primitive: 1 },
    ));
    // The largest finite coordinates are finite, and too far.
    let max = Triangle::new(Vec3::splat(f32::MAX), Vec3::splat(-f32::MAX), Vec3::ZERO);
    assert!(bvhkit::Primitive::is_finite(&max));
    cases.push((
        vec![ok, ok, ok, max],
        Error::CoordinateOutOfRange { primitive: 3 },
    ));
    let ploc = BottomUp {
        method: Method::Ploc { radius: 1 },
        collapse: Collapse::None,
        ..BottomUp::default()
    };
    for (tris, want) in cases {
        assert_eq!(
            OwnedBvh::<Aabb>::build(&TopDown::sah(), &tris).err(),
            Some(want)
        );
        for cfg in [BottomUp::default(), ploc] {
            assert_eq!(
                OwnedBvh::<Aabb>::build_bottom_up(&cfg, &tris).err(),
                Some(want),
                "{cfg:?}"
            );
        }
    }
}
