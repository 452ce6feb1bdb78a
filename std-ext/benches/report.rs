//! The `bvhkit bench` report's timings as criterion benches (no peer crates):
//! fitting each volume to the rock's vertices, building with every top-down
//! preset and PLOC, and the A-against-B pair query on each builder's tree.
//! The report adds the error side (looseness, SAH cost, answers); these give
//! the times with criterion's statistics.
//!
//! Run: `cargo bench -p bvhkit-std --bench report` (about ten minutes), or
//! filter, e.g. `cargo bench -p bvhkit-std --bench report -- fit`.

use bvhkit::build::{BottomUp, MergeMetric, Method, PRESETS};
use bvhkit::glam::Vec3;
use bvhkit::{Aabb, BoundingVolume, Descent, Dop14, Dop26, Obb, Pairs, Sphere};
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
        metric: MergeMetric::SurfaceArea,
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

criterion_group!(benches, fits, builders);
criterion_main!(benches);
