//! The queries whose traversal containers are a fixed stack or a fixed
//! min-queue (core's `query/stack.rs` and `query/heap.rs`, both on heapless
//! since #23): closest-hit rays depth-first (stack) and best-first (queue),
//! nearest-point queries (queue) and box region queries (stack), 1,000 each
//! on a 20,480-triangle rock. Criterion compares a run with a saved baseline,
//! which is how the book's heapless measurement was made:
//!
//! ```text
//! cargo bench -p bvhkit-std --bench containers -- --save-baseline before
//! (change the containers)
//! cargo bench -p bvhkit-std --bench containers -- --baseline before
//! ```

use bvhkit::glam::Vec3;
use bvhkit::{Aabb, Primitive, Query, Ray, RayOrder, TopDown};
use bvhkit_std::{scene, OwnedBvh};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

/// A deterministic point in the unit cube, from a counter (splitmix64).
fn unit(k: u64) -> Vec3 {
    let mut z = k.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut next = || {
        z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut x = z;
        x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((x ^ (x >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    };
    Vec3::new(next(), next(), next())
}

fn bench(c: &mut Criterion) {
    let tris = scene::rock(5, 7);
    let tree = OwnedBvh::<Aabb>::build(&TopDown::default(), &tris).expect("builds");
    let bvh = tree.view();
    let bounds = tris.iter().fold(Aabb::EMPTY, |u, t| u.union(&t.bounds()));
    let size = bounds.max - bounds.min;
    let inside = |k: u64| bounds.min + unit(k) * size;
    // Rays from points on a sphere around the rock towards points inside it.
    let rays: Vec<Ray> = (0..1_000u64)
        .map(|k| {
            let from = bounds.center() + (unit(2 * k) - 0.5).normalize_or(Vec3::X) * size.length();
            Ray::new(from, inside(2 * k + 1) - from, f32::INFINITY).expect("finite ray")
        })
        .collect();
    let points: Vec<Vec3> = (0..1_000u64).map(|k| inside(10_000 + k)).collect();
    let boxes: Vec<Aabb> = points
        .iter()
        .map(|&p| Aabb::new(p - size * 0.02, p + size * 0.02))
        .collect();

    let mut g = c.benchmark_group("containers-20480");
    for (name, order) in [
        ("rays-depth-first-stack", RayOrder::DepthFirst),
        ("rays-best-first-queue", RayOrder::BestFirst),
    ] {
        g.bench_function(name, |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| bvh.cast_ray(&tris, r, order, ()).expect("casts").is_some())
                    .count()
            })
        });
    }
    g.bench_function("nearest-queue", |b| {
        b.iter(|| {
            points
                .iter()
                .map(|&p| {
                    bvh.nearest(&tris, p, ())
                        .expect("searches")
                        .map_or(0, |n| n.prim)
                })
                .fold(0u32, u32::wrapping_add)
        })
    });
    g.bench_function("region-stack", |b| {
        b.iter(|| {
            boxes
                .iter()
                .map(|r| {
                    Query::overlapping(&bvh, &tris, r, |i| {
                        black_box(i);
                    })
                })
                .map(|n| n.expect("searches"))
                .sum::<usize>()
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
