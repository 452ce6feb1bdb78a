//! Build speed and tree quality against parry3d's binned builder, on the same
//! triangles (one rock of the default scene, 81 920 triangles).
//!
//! Run: `cargo bench -p bvhkit-std --features peers --bench build`
//! Before the timings it prints the SAH cost of each tree, computed with the
//! same formula (C_t = C_i = 1, AABB areas, relative to the root).

use bvhkit::build::PrimitiveRef;
use bvhkit::{Aabb, AxisChoice, Node, Primitive, TopDown, Triangle};
use bvhkit_std::scene;
use criterion::{criterion_group, criterion_main, Criterion};
use parry3d::bounding_volume::Aabb as PAabb;
use parry3d::partitioning::{Bvh, BvhBuildStrategy, TraversalAction};
use std::hint::black_box;

fn parry_aabbs(tris: &[Triangle]) -> Vec<PAabb> {
    tris.iter()
        .map(|t| {
            let b = t.bounds();
            PAabb::new(b.min.to_array().into(), b.max.to_array().into())
        })
        .collect()
}

/// SAH cost of parry's tree: its root is a pair of nodes, so the virtual root
/// (area ratio 1) is added to match bvhkit's single root node.
fn parry_sah(bvh: &Bvh) -> f64 {
    let area = |b: PAabb| {
        let e = [
            (b.maxs.x - b.mins.x) as f64,
            (b.maxs.y - b.mins.y) as f64,
            (b.maxs.z - b.mins.z) as f64,
        ];
        2.0 * (e[0] * e[1] + e[1] * e[2] + e[2] * e[0])
    };
    let root = area(bvh.root_aabb());
    let mut cost = 1.0;
    bvh.traverse(|n| {
        let a = area(n.aabb()) / root;
        cost += a; // an internal node (C_t) or a one-primitive leaf (C_i * 1)
        TraversalAction::Continue
    });
    cost
}

fn report_quality(tris: &[Triangle]) {
    let aabbs = parry_aabbs(tris);
    let p = Bvh::from_leaves(BvhBuildStrategy::Binned, &aabbs);
    eprintln!("SAH cost, {} triangles:", tris.len());
    eprintln!("  parry3d binned (1 per leaf)  {:.3}", parry_sah(&p));
    let preset = |name: &str| {
        bvhkit::build::PRESETS
            .iter()
            .find(|p| p.name == name)
            .map(|p| p.builder)
            .unwrap_or_else(|| panic!("no preset {name}"))
    };
    for (name, cfg) in [
        ("sah (1 per leaf)", preset("sah").with_max_leaf_size(1)),
        ("sah (4 per leaf)", preset("sah")),
        (
            "sah-8bins (1 per leaf)",
            preset("sah-8bins").with_max_leaf_size(1),
        ),
        (
            "sah-longest (1 per leaf)",
            preset("sah-longest").with_max_leaf_size(1),
        ),
        ("sah-longest (4 per leaf)", preset("sah-longest")),
        (
            "spatial-median (1 per leaf)",
            preset("spatial-median").with_max_leaf_size(1),
        ),
        (
            "sah-sweep (1 per leaf)",
            preset("sah-sweep").with_max_leaf_size(1),
        ),
    ] {
        let t = bvhkit_std::OwnedBvh::<Aabb>::build(&cfg, tris).unwrap();
        eprintln!("  bvhkit {name:<30} {:.3}", t.view().stats().sah_cost);
    }
}

fn bench(c: &mut Criterion) {
    let tris = scene::rock(6, 1);
    report_quality(&tris);
    let aabbs = parry_aabbs(&tris);
    let mut g = c.benchmark_group("build-81920");
    g.sample_size(20);
    g.bench_function("parry3d-binned", |b| {
        b.iter(|| {
            black_box(Bvh::from_leaves(
                BvhBuildStrategy::Binned,
                black_box(&aabbs),
            ))
        })
    });
    let longest = TopDown {
        axis: AxisChoice::Longest,
        ..TopDown::sah()
    };
    for (name, cfg) in [
        ("bvhkit-sah-leaf1", TopDown::sah().with_max_leaf_size(1)),
        ("bvhkit-sah-leaf4", TopDown::sah()),
        ("bvhkit-sah-longest-leaf1", longest.with_max_leaf_size(1)),
        ("bvhkit-sah-longest-leaf4", longest),
    ] {
        let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(tris.len())];
        let mut idx = vec![0u32; tris.len()];
        let mut cache = vec![PrimitiveRef::EMPTY; tris.len()];
        g.bench_function(format!("{name}-cached"), |b| {
            b.iter(|| {
                let t = cfg
                    .build_cached(black_box(&tris), &mut nodes, &mut idx, &mut cache)
                    .unwrap();
                black_box(t.node_count())
            })
        });
        g.bench_function(format!("{name}-indexed"), |b| {
            b.iter(|| {
                let t = cfg.build(black_box(&tris), &mut nodes, &mut idx).unwrap();
                black_box(t.node_count())
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
