//! The incremental broad phase against a rebuild every step: `n` boxes
//! drifting in a cube (density fixed: about 4 overlapping pairs per box),
//! either all of them moving each step or one in ten. One step of
//! `collision::PairTracker` (set the movers' boxes, then `step`) against a
//! top-down build over all boxes plus `SelfPairs` over that tree. The
//! comparison with parry3d's broad phase belongs to `scripts/bench-peers`.
//!
//! Run: `cargo bench -p bvhkit-std --bench broad_phase`

use bvhkit::builders::{DynNode, DynamicConfig};
use bvhkit::collision::{PairTracker, Slot, TrackerStorage};
use bvhkit::glam::Vec3;
use bvhkit::query::SelfPairs;
use bvhkit::{Aabb, Node, TopDown};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;

/// Positions and velocities of `n` boxes of side 1 in a cube sized for
/// a fixed density (a small deterministic generator, no dependency).
fn scene(n: usize) -> (Vec<Vec3>, Vec<Vec3>, f32) {
    let side = (n as f32 * 2.0).cbrt() * 1.6;
    let mut s = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / (1u64 << 24) as f32
    };
    let pos = (0..n)
        .map(|_| Vec3::new(next(), next(), next()) * side)
        .collect();
    let vel = (0..n)
        .map(|_| (Vec3::new(next(), next(), next()) - 0.5) * 0.04)
        .collect();
    (pos, vel, side)
}

fn boxed(p: Vec3) -> Aabb {
    Aabb::new(p, p + 1.0)
}

/// Advances the movers (every `every`-th box, shifted by `step`) and
/// bounces them off the cube's walls.
fn advance(
    pos: &mut [Vec3],
    vel: &mut [Vec3],
    side: f32,
    every: usize,
    step: usize,
    mut f: impl FnMut(usize, Vec3),
) {
    for i in (step % every..pos.len()).step_by(every) {
        pos[i] += vel[i];
        for a in 0..3 {
            if pos[i][a] < 0.0 || pos[i][a] > side {
                vel[i][a] = -vel[i][a];
            }
        }
        f(i, pos[i]);
    }
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("broad-phase-step");
    g.sample_size(10);
    for n in [10_000usize, 100_000] {
        for every in [1usize, 10] {
            let label = format!("{n} boxes, 1 in {every} moving");
            let (mut pos, mut vel, side) = scene(n);
            let m = 16 * n;
            let mut nodes = vec![DynNode::<Aabb>::EMPTY; 2 * n - 1];
            let (mut slots, mut boxes, mut moved) =
                (vec![Slot::EMPTY; n], vec![Aabb::EMPTY; n], vec![0u32; n]);
            let (mut pairs, mut next) = (vec![(0, 0); m], vec![(0, 0); m]);
            let storage = TrackerStorage {
                nodes: &mut nodes,
                slots: &mut slots,
                boxes: &mut boxes,
                moved: &mut moved,
                pairs: &mut pairs,
                next: &mut next,
            };
            let config = DynamicConfig {
                margin: 0.1,
                ..Default::default()
            };
            let mut world = PairTracker::new(storage, config).unwrap();
            for (i, p) in pos.iter().enumerate() {
                world.insert(i as u32, &boxed(*p)).unwrap();
            }
            world.step(|_| {}).unwrap();
            let mut step = 0;
            g.bench_function(BenchmarkId::new("tracker", &label), |b| {
                b.iter(|| {
                    step += 1;
                    advance(&mut pos, &mut vel, side, every, step, |i, p| {
                        world.set_bounds(i as u32, &boxed(p)).unwrap()
                    });
                    black_box(world.step(|_| {}).unwrap())
                })
            });
            let pair_count = world.pairs().len();
            let (mut pos, mut vel, side) = scene(n);
            let mut all: Vec<Aabb> = pos.iter().map(|p| boxed(*p)).collect();
            let mut tnodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(n)];
            let mut idx = vec![0u32; n];
            let mut step = 0;
            g.bench_function(BenchmarkId::new("rebuild + self query", &label), |b| {
                b.iter(|| {
                    step += 1;
                    advance(&mut pos, &mut vel, side, every, step, |i, p| {
                        all[i] = boxed(p)
                    });
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
