//! Profiles one broad-phase workload: 100 000 boxes drifting, every box (or
//! one in ten, with `--tenth`) moving each step; times the updates and the
//! steps separately. `--descent` and `--area` pick the tree's sibling search
//! and area rotations. `cargo run --release -p bvhkit-std --example profile_broad_phase`
use bvhkit::builders::DynamicConfig;
use bvhkit::collision::PairTracker;
use std::time::{Duration, Instant};

fn main() {
    let every = if std::env::args().any(|a| a == "--tenth") {
        10
    } else {
        1
    };
    let n = 100_000usize;
    // The benchmarks' scene: boxes drifting in a cube, bouncing off its walls.
    let mut drift = bvhkit_std::scene::Drift::new(n);
    let mut buffers = bvhkit_std::TrackerBuffers::new(n, 16 * n);
    let storage = buffers.storage();
    let mut world = PairTracker::new(
        storage,
        DynamicConfig {
            margin: 0.1,
            search: if std::env::args().any(|a| a == "--descent") {
                bvhkit::builders::SiblingSearch::Descent
            } else {
                Default::default()
            },
            rotations: if std::env::args().any(|a| a == "--area") {
                bvhkit::builders::Rotations::Area
            } else {
                DynamicConfig::default().rotations
            },
        },
    )
    .unwrap();
    for (i, b) in drift.boxes().iter().enumerate() {
        world.insert(i as u32, b).unwrap();
    }
    world.step(|_| {}).unwrap();
    let (mut t_update, mut t_step) = (Duration::ZERO, Duration::ZERO);
    for step in 0..30 {
        let t = Instant::now();
        drift.advance(every, step, |i, b| world.set_bounds(i as u32, &b).unwrap());
        t_update += t.elapsed();
        let t = Instant::now();
        world.step(|_| {}).unwrap();
        t_step += t.elapsed();
    }
    println!(
        "per step: updates {:.1} ms, step {:.1} ms, height {}",
        t_update.as_secs_f64() * 1e3 / 30.0,
        t_step.as_secs_f64() * 1e3 / 30.0,
        world.tree().height()
    );
}
