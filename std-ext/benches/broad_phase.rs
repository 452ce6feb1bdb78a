//! The incremental broad phase against a rebuild every step: `n` boxes
//! drifting in a cube (density fixed: about 4 overlapping pairs per box),
//! either all of them moving each step or one in ten. One step of
//! `collision::PairTracker` (set the movers' boxes, then `step`) against a
//! top-down build over all boxes plus `SelfPairs` over that tree. The
//! comparison with parry3d's broad phase belongs to `scripts/bench-peers`.
//!
//! Run: `cargo bench -p bvhkit-std --bench broad_phase`

use bvhkit::builders::DynamicConfig;
use bvhkit::collision::PairTracker;
use bvhkit::query::SelfPairs;
use bvhkit::{Aabb, Node, TopDown};
use bvhkit_std::scene::Drift;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("broad-phase-step");
    g.sample_size(10);
    for n in [10_000usize, 100_000] {
        for every in [1usize, 10] {
            let label = format!("{n} boxes, 1 in {every} moving");
            let mut drift = Drift::new(n);
            let mut buffers = bvhkit_std::TrackerBuffers::new(n, 16 * n);
            let storage = buffers.storage();
            let config = DynamicConfig {
                margin: 0.1,
                ..Default::default()
            };
            let mut world = PairTracker::new(storage, config).unwrap();
            for (i, b) in drift.boxes().iter().enumerate() {
                world.insert(i as u32, b).unwrap();
            }
            world.step(|_| {}).unwrap();
            let mut step = 0;
            g.bench_function(BenchmarkId::new("tracker", &label), |b| {
                b.iter(|| {
                    step += 1;
                    drift.advance(every, step, |i, b| world.set_bounds(i as u32, &b).unwrap());
                    black_box(world.step(|_| {}).unwrap())
                })
            });
            let pair_count = world.pairs().len();
            let mut drift = Drift::new(n);
            let mut all: Vec<Aabb> = drift.boxes();
            let mut tnodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(n)];
            let mut idx = vec![0u32; n];
            let mut step = 0;
            g.bench_function(BenchmarkId::new("rebuild + self query", &label), |b| {
                b.iter(|| {
                    step += 1;
                    drift.advance(every, step, |i, b| all[i] = b);
                    let tree = TopDown::default()
                        .build(&all, &mut tnodes, &mut idx)
                        .unwrap();
                    black_box(SelfPairs::new(&tree, &all).count().unwrap())
                })
            });
            eprintln!("{label}: {pair_count} pairs");
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
