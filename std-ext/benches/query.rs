//! Two-tree query speed on the default scene (two rocks of 81 920 triangles
//! each): traversals, descent rules, layouts, the cost of counting and of
//! querying a moved tree. The comparison with other crates (parry3d's
//! `leaf_pairs` among them) is `scripts/bench-peers`.
//!
//! Run: `cargo bench -p bvhkit-std --bench query`
//!
//! What is measured: the candidate pairs (primitive boxes overlap). Before
//! timing, the bench checks that every variant finds the same pairs.

use bvhkit::layout::{PreNode, Preorder, Wide, WideNode};
use bvhkit::{Aabb, Counts, Descent, PairTraversal, Pairs, Rigid, TopDown};
use bvhkit_std::{scene, OwnedBvh};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let (a, b) = scene::default_pair();
    let leaf1 = OwnedBvh::<Aabb>::build(&TopDown::sah().with_max_leaf_size(1), &a).unwrap();
    let leaf1_b = OwnedBvh::<Aabb>::build(&TopDown::sah().with_max_leaf_size(1), &b).unwrap();
    let leaf4 = OwnedBvh::<Aabb>::build(&TopDown::sah(), &a).unwrap();
    let leaf4_b = OwnedBvh::<Aabb>::build(&TopDown::sah(), &b).unwrap();
    let (t1a, t1b, t4a, t4b) = (leaf1.view(), leaf1_b.view(), leaf4.view(), leaf4_b.view());
    let (p4a, p4b) = (leaf4.plain_view(), leaf4_b.plain_view());

    let ours = |ta, tb, rule| Pairs::new(ta, &a, tb, &b).descent(rule).count().unwrap();
    let want = ours(&t4a, &t4b, Descent::Larger);
    eprintln!("candidate pairs: {want}");
    assert_eq!(ours(&t1a, &t1b, Descent::Simultaneous), want);

    let mut g = c.benchmark_group("pairs-81920x81920");
    g.sample_size(30);
    for (name, ta, tb) in [("leaf1", &t1a, &t1b), ("leaf4", &t4a, &t4b)] {
        for rule in [Descent::Larger, Descent::Simultaneous] {
            g.bench_function(format!("bvhkit-{name}-stack-{}", rule.name()), |bch| {
                bch.iter(|| black_box(ours(ta, tb, rule)))
            });
        }
        if name == "leaf4" {
            // The default query on the same trees without their kept leaf
            // bounds: what `with_leaf_bounds` buys.
            g.bench_function("bvhkit-leaf4-stack-simultaneous-no-kept-bounds", |bch| {
                bch.iter(|| black_box(ours(&p4a, &p4b, Descent::Simultaneous)))
            });
        }
        g.bench_function(format!("bvhkit-{name}-recursive-larger"), |bch| {
            bch.iter(|| {
                let q =
                    Pairs::new(ta, &a, tb, &b).traversal(PairTraversal::Recursive(Descent::Larger));
                black_box(q.count().unwrap())
            })
        });
    }
    // The same trees in the preorder and 4-wide layouts.
    let (mut p1a, mut p1b) = (
        vec![PreNode::<Aabb, u32>::EMPTY; t1a.node_count()],
        vec![PreNode::<Aabb, u32>::EMPTY; t1b.node_count()],
    );
    let (p1a, p1b) = (
        Preorder::from_bvh(&t1a, &mut p1a).unwrap(),
        Preorder::from_bvh(&t1b, &mut p1b).unwrap(),
    );
    let wide = |t: &bvhkit::Bvh<Aabb>| vec![WideNode::EMPTY; Wide::records_needed(t).unwrap()];
    let (mut w1a, mut w1b, mut w4a, mut w4b) = (wide(&t1a), wide(&t1b), wide(&t4a), wide(&t4b));
    let (w1a, w1b) = (
        Wide::from_bvh(&t1a, &mut w1a).unwrap(),
        Wide::from_bvh(&t1b, &mut w1b).unwrap(),
    );
    let (w4a, w4b) = (
        Wide::from_bvh(&t4a, &mut w4a).unwrap(),
        Wide::from_bvh(&t4b, &mut w4b).unwrap(),
    );
    let rule = Descent::Simultaneous;
    assert_eq!(
        Pairs::new(&w1a, &a, &w1b, &b)
            .descent(rule)
            .count()
            .unwrap(),
        want
    );
    g.bench_function("bvhkit-leaf1-preorder-stack-simultaneous", |bch| {
        bch.iter(|| {
            black_box(
                Pairs::new(&p1a, &a, &p1b, &b)
                    .descent(rule)
                    .count()
                    .unwrap(),
            )
        })
    });
    for (name, ta, tb) in [("leaf1", &w1a, &w1b), ("leaf4", &w4a, &w4b)] {
        g.bench_function(format!("bvhkit-{name}-wide-stack-simultaneous"), |bch| {
            bch.iter(|| black_box(Pairs::new(ta, &a, tb, &b).descent(rule).count().unwrap()))
        });
    }
    // Counting is free when the tally is `()`, cheap when it is `Counts`.
    g.bench_function("bvhkit-leaf4-stack-larger-counted", |bch| {
        bch.iter(|| {
            let mut counts = Counts::default();
            let n = Pairs::new(&t4a, &a, &t4b, &b)
                .counted(&mut counts)
                .count()
                .unwrap();
            black_box((n, counts))
        })
    });
    g.finish();

    // B moved by a rigid motion into A's frame: bvhkit moves node volumes
    // conservatively (f64, outward rounding), no rebuild.
    let rot = bvhkit::glam::Quat::from_rotation_y(0.3);
    let shift = bvhkit::glam::Vec3::new(0.2, 0.0, 0.1);
    let motion = Rigid::new(rot, shift).unwrap();
    let ours_moved = |ta, tb, traversal| {
        Pairs::new(ta, &a, tb, &b)
            .traversal(traversal)
            .in_frame(motion)
            .count()
            .unwrap()
    };
    eprintln!(
        "moved candidate pairs: {}",
        ours_moved(&t1a, &t1b, PairTraversal::default())
    );
    let mut g = c.benchmark_group("pairs-moved-81920x81920");
    g.sample_size(30);
    for (name, ta, tb) in [("leaf1", &t1a, &t1b), ("leaf4", &t4a, &t4b)] {
        for traversal in [
            PairTraversal::Stack(Descent::Larger),
            PairTraversal::Recursive(Descent::Larger),
        ] {
            g.bench_function(
                format!("bvhkit-{name}-{}-larger", traversal.name()),
                |bch| bch.iter(|| black_box(ours_moved(ta, tb, traversal))),
            );
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
