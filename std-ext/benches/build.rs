//! Build speed and tree quality of bvhkit's builders (top-down presets, as
//! users call them and into reused buffers; PLOC; insertion), on one rock of
//! the default scene (81 920 triangles). The comparison with other crates is
//! `scripts/bench-peers` (its own workspace, so the peers stay out of this one).
//!
//! Run: `cargo bench -p bvhkit-std --bench build`
//! Before the timings it prints the SAH cost of each tree (C_t = C_i = 1,
//! AABB areas, relative to the root).

use bvhkit::builders::{BottomUp, Insertion, Method, PrimitiveRef};
use bvhkit::{Aabb, AxisChoice, Node, TopDown, Triangle};
use bvhkit_std::{scene, OwnedBvh};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn report_quality(tris: &[Triangle]) {
    eprintln!("SAH cost, {} triangles:", tris.len());
    let preset = |name: &str| {
        bvhkit::builders::PRESETS
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
    let mut g = c.benchmark_group("build-81920");
    g.sample_size(20);
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
    // As users build: everything allocated per build (`OwnedBvh`).
    g.bench_function("bvhkit-default-owned", |b| {
        b.iter(|| {
            let t = OwnedBvh::<Aabb>::build(&TopDown::default(), black_box(&tris)).unwrap();
            black_box(t.view().node_count())
        })
    });
    for radius in [1, 16] {
        let ploc = BottomUp {
            method: Method::Ploc { radius },
            ..BottomUp::default()
        };
        g.bench_function(format!("bvhkit-ploc-r{radius}-owned"), |b| {
            b.iter(|| {
                let t = OwnedBvh::<Aabb>::build_bottom_up(&ploc, black_box(&tris)).unwrap();
                black_box(t.view().node_count())
            })
        });
    }
    g.bench_function("bvhkit-insertion-owned", |b| {
        b.iter(|| {
            let t = OwnedBvh::<Aabb>::build_by_insertion(&Insertion::default(), black_box(&tris))
                .unwrap();
            black_box(t.view().node_count())
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
