//! The `bvhkit bench` report's timings as criterion benches (no peer crates):
//! fitting each volume to the rock's vertices, building with every top-down
//! preset and PLOC, and the A-against-B pair query on each builder's tree.
//! The report adds the error side (looseness, SAH cost, answers); these give
//! the times with criterion's statistics. The last group is the
//! representations table: the pair query and a batch of rays on every
//! layout (canonical, implicit, preorder 32-bit, tri-node, 4-wide, quantized
//! 4-wide), each answer checked against the canonical tree's first.
//!
//! Run: `cargo bench -p bvhkit-std --features cli --bench report` (about fifteen minutes),
//! or filter, e.g. `cargo bench -p bvhkit-std --features cli --bench report -- layout`.

use bvhkit::builders::{BottomUp, Method, PRESETS};
use bvhkit::glam::Vec3;
use bvhkit::layout::{
    Implicit, PreNode, Preorder, QuantNode, QuantizedWide, Slot, TriNode, TriNodes, Wide, WideNode,
};
use bvhkit::{
    Aabb, BoundingVolume, Descent, Dop14, Dop26, Hierarchy, Obb, Pairs, Query, Ray, RayOrder,
    Sphere, Triangle,
};
use bvhkit_std::{scene, OwnedBvh};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn fits(c: &mut Criterion) {
    let rock = scene::rock(6, 1);
    let points: Vec<Vec3> = rock.iter().flat_map(|t| t.v).collect();
    let mut g = c.benchmark_group("fit one volume to the rock's vertices");
    g.bench_function("aabb", |b| b.iter(|| Aabb::fit(black_box(&points[..]))));
    g.bench_function("sphere-ritter", |b| {
        b.iter(|| Sphere::ritter(black_box(&points[..])))
    });
    g.bench_function("sphere-refined", |b| {
        b.iter(|| Sphere::ritter_refined(black_box(&points[..]), 8))
    });
    g.bench_function("sphere-welzl", |b| {
        b.iter(|| Sphere::welzl(black_box(&points[..])))
    });
    g.bench_function("obb-pca", |b| b.iter(|| Obb::fit(black_box(&points[..]))));
    g.bench_function("14-dop", |b| b.iter(|| Dop14::fit(black_box(&points[..]))));
    g.bench_function("26-dop", |b| b.iter(|| Dop26::fit(black_box(&points[..]))));
    g.finish();
}

fn builders(c: &mut Criterion) {
    let (a, b) = scene::rock_pair(6);
    let tree_b = OwnedBvh::<Aabb>::build(&bvhkit::TopDown::sah(), &b).unwrap();
    let mut build = c.benchmark_group("build the rock (81 920 triangles)");
    build.sample_size(10);
    for p in PRESETS {
        build.bench_function(p.name, |bch| {
            bch.iter(|| OwnedBvh::<Aabb>::build(&p.builder, black_box(&a)).unwrap())
        });
    }
    let ploc = BottomUp {
        method: Method::Ploc { radius: 4 },
        ..BottomUp::default()
    };
    build.bench_function("ploc-r4", |bch| {
        bch.iter(|| OwnedBvh::<Aabb>::build_bottom_up(&ploc, black_box(&a)).unwrap())
    });
    build.finish();

    let mut query = c.benchmark_group("pair query on each builder's tree");
    for p in PRESETS {
        let tree_a = OwnedBvh::<Aabb>::build(&p.builder, &a).unwrap();
        query.bench_function(p.name, |bch| {
            bch.iter(|| {
                Pairs::new(&tree_a.view(), &a, &tree_b.view(), &b)
                    .descent(Descent::Larger)
                    .count()
                    .unwrap()
            })
        });
    }
    query.finish();
}

/// Pairs and rays of one layout, after checking its answers against `want`.
fn bench_layout<H: Hierarchy<Bv = Aabb>>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: &str,
    (ta, a): (&H, &[Triangle]),
    (tb, b): (&H, &[Triangle]),
    rays: &[Ray],
    want: &(usize, Vec<Option<u32>>),
) {
    let cast = || -> Vec<Option<u32>> {
        rays.iter()
            .map(|r| {
                ta.cast_ray(a, r, RayOrder::DepthFirst, ())
                    .unwrap()
                    .map(|h| h.prim)
            })
            .collect()
    };
    let pairs = || Pairs::new(ta, a, tb, b).descent(Descent::Larger).count();
    assert_eq!(
        (pairs().unwrap(), cast()),
        *want,
        "{name}: answers differ from the canonical tree's"
    );
    g.bench_function(format!("{name}: pairs"), |bch| {
        bch.iter(|| pairs().unwrap())
    });
    g.bench_function(format!("{name}: 10k rays"), |bch| bch.iter(cast));
}

fn layouts(c: &mut Criterion) {
    let (a, b) = scene::rock_pair(6);
    let sah = bvhkit::TopDown::sah();
    let (oa, ob) = (
        OwnedBvh::<Aabb>::build(&sah, &a).unwrap(),
        OwnedBvh::<Aabb>::build(&sah, &b).unwrap(),
    );
    let (va, vb) = (oa.view(), ob.view());
    let rays = bvhkit_std::layouts::rays(&a, 10_000);
    let want = {
        let hits = rays
            .iter()
            .map(|r| {
                va.cast_ray(&a, r, RayOrder::DepthFirst, ())
                    .unwrap()
                    .map(|h| h.prim)
            })
            .collect();
        (Pairs::new(&va, &a, &vb, &b).count().unwrap(), hits)
    };
    let mut g = c.benchmark_group("layouts (two rocks of 81 920 triangles, SAH)");
    g.sample_size(20);
    bench_layout(&mut g, "canonical", (&va, &a), (&vb, &b), &rays, &want);
    macro_rules! layout {
        ($name:expr, $empty:expr, $needed:expr, $convert:expr) => {{
            let (mut sa, mut sb) = (
                vec![$empty; $needed(&va).unwrap()],
                vec![$empty; $needed(&vb).unwrap()],
            );
            let (la, lb) = (
                $convert(&va, &mut sa).unwrap(),
                $convert(&vb, &mut sb).unwrap(),
            );
            bench_layout(&mut g, $name, (&la, &a), (&lb, &b), &rays, &want);
        }};
    }
    let nodes = |t: &bvhkit::Bvh<Aabb>| Ok::<usize, bvhkit::Error>(t.node_count());
    layout!(
        "implicit",
        Slot::<Aabb>::EMPTY,
        Implicit::slots_needed,
        Implicit::from_bvh
    );
    layout!(
        "preorder-32",
        PreNode::<Aabb, u32>::EMPTY,
        nodes,
        Preorder::from_bvh
    );
    layout!(
        "tri-node",
        TriNode::<Aabb>::EMPTY,
        TriNodes::records_needed,
        TriNodes::from_bvh
    );
    layout!(
        "wide-4",
        WideNode::EMPTY,
        Wide::records_needed,
        Wide::from_bvh
    );
    layout!(
        "quantized-4",
        QuantNode::EMPTY,
        QuantizedWide::records_needed,
        QuantizedWide::from_bvh
    );
    g.finish();
}

criterion_group!(benches, fits, builders, layouts);
criterion_main!(benches);
