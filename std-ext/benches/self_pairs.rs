//! Self-collision of one mesh: the self query (each pair `i < j` once,
//! neighbours skipped before the exact test) against the two-tree query of
//! the tree with itself, whose answers must then be filtered (both orders,
//! every triangle with itself and its neighbours, all tested exactly).
//!
//! Run: `cargo bench -p bvhkit-std --bench self_pairs`

use bvhkit::query::{Adjacent, SelfPairs};
use bvhkit::{Aabb, Intersects, Pairs, Primitive, Triangle};
use bvhkit_std::{scene, OwnedBvh};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let tris: Vec<Triangle> = scene::rock(6, 1);
    let tree = OwnedBvh::<Aabb>::build(&bvhkit::TopDown::sah(), &tris).unwrap();
    let t = tree.view();
    let mut g = c.benchmark_group(format!("self-{}", tris.len()));
    g.sample_size(20);
    g.bench_function("self-query exact", |b| {
        b.iter(|| black_box(SelfPairs::new(&t, &tris).exact().count().unwrap()))
    });
    g.bench_function("self-query candidates", |b| {
        b.iter(|| black_box(SelfPairs::new(&t, &tris).count().unwrap()))
    });
    // The same answer from the two-tree query: keep i < j, drop
    // neighbours, then the exact test.
    g.bench_function("tree against itself, filtered", |b| {
        b.iter(|| {
            let answer = |p: &Triangle, q: &Triangle| {
                p.bounds().overlaps(&q.bounds()) && !p.adjacent(q) && p.intersects(q)
            };
            let mut n = 0usize;
            Pairs::new(&t, &tris, &t, &tris)
                .answer(answer)
                .for_each(|i, j| n += (i < j) as usize)
                .unwrap();
            black_box(n)
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
