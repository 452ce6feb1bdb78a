//! Distance between two meshes: the rock of the tour (81 920 triangles)
//! against a copy shifted along x just past touching, so the closest pair
//! is a small positive distance apart and the search cannot stop at a
//! touching pair. `Distance::closest` on the default top-down trees,
//! `Distance::within` at a radius that catches a few thousand triangle
//! pairs (the count is printed before the measurements), and for comparison the nearest triangle of A to one point (the
//! closest point on B).
//!
//! Run: `cargo bench -p bvhkit-std --bench distance`

use bvhkit::glam::Vec3;
use bvhkit::query::Distance;
use bvhkit::{Aabb, Primitive, TopDown, Triangle};
use bvhkit_std::{scene, OwnedBvh};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

/// Pairs within `d`.
fn within(
    a: &bvhkit::Bvh<Aabb>,
    pa: &[Triangle],
    b: &bvhkit::Bvh<Aabb>,
    pb: &[Triangle],
    d: f64,
) -> usize {
    Distance::new(a, pa, b, pb).within(d, |_, _| {}).unwrap()
}

fn bench(c: &mut Criterion) {
    let a: Vec<Triangle> = scene::rock(6, 1);
    let bounds = a.iter().fold(Aabb::EMPTY, |acc, t| acc.union(&t.bounds()));
    // B's leftmost x is A's rightmost plus the gap: apart, and near only
    // where the rock bulges furthest along x.
    let gap = 0.01;
    let shift = Vec3::new(bounds.max.x - bounds.min.x + gap, 0.0, 0.0);
    let b: Vec<Triangle> = a.iter().map(|t| t.translated(shift)).collect();
    let ta = OwnedBvh::<Aabb>::build(&TopDown::default(), &a).unwrap();
    let tb = OwnedBvh::<Aabb>::build(&TopDown::default(), &b).unwrap();
    let (ta, tb) = (ta.view(), tb.view());

    let closest = Distance::new(&ta, &a, &tb, &b).closest().unwrap().unwrap();
    assert!(closest.distance() > 0.0);
    // The radius: bisected until `within` catches 2 000 to 5 000 pairs.
    let (mut lo, mut hi) = (closest.distance(), closest.distance() + 1.0);
    let mut radius = hi;
    for _ in 0..60 {
        radius = 0.5 * (lo + hi);
        match within(&ta, &a, &tb, &b, radius) {
            n if n < 2_000 => lo = radius,
            n if n > 5_000 => hi = radius,
            _ => break,
        }
    }
    let caught = within(&ta, &a, &tb, &b, radius);
    let point = closest.points.on_b.as_vec3();
    eprintln!(
        "{} + {} triangles: closest pair {} x {} at {:.6}; within {radius:.6}: {caught} pairs",
        a.len(),
        b.len(),
        closest.a,
        closest.b,
        closest.distance()
    );

    let mut g = c.benchmark_group(format!("distance-{}", a.len()));
    g.sample_size(20);
    g.bench_function("closest", |bench| {
        bench.iter(|| black_box(Distance::new(&ta, &a, &tb, &b).closest().unwrap()))
    });
    g.bench_function("within", |bench| {
        bench.iter(|| black_box(within(&ta, &a, &tb, &b, radius)))
    });
    g.bench_function("nearest to one point", |bench| {
        bench.iter(|| black_box(ta.nearest(&a, black_box(point), ()).unwrap()))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
