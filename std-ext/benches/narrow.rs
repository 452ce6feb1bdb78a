//! The report's narrow-phase measurement as a criterion bench: one
//! triangle–triangle test reading exact, `f64` or `f32` orientation signs, on
//! near-touching (adversarial) pairs and on random pairs. The disagreement
//! rates are printed before timing (they do not change from run to run).
//!
//! Run: `cargo bench -p bvhkit-std --features cli --bench narrow`

use bvhkit::narrow::{triangles_intersect_with, ExactSigns, F32Signs, F64Signs, Orientation};
use bvhkit::Triangle;
use bvhkit_std::near_misses;
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn all<O: Orientation>(pairs: &[(Triangle, Triangle)], o: O) -> usize {
    pairs
        .iter()
        .filter(|(a, b)| triangles_intersect_with(black_box(a), black_box(b), o))
        .count()
}

fn bench(c: &mut Criterion) {
    print!("{}", near_misses::render(&near_misses::measure(20_000, 1)));
    let adversarial = near_misses::adversarial_pairs(20_000, 1.0e3, 0xad5e);
    let mut g = c.benchmark_group("triangle test, 20 000 near-touching pairs");
    g.bench_function("exact signs", |b| b.iter(|| all(&adversarial, ExactSigns)));
    g.bench_function("f64 signs", |b| b.iter(|| all(&adversarial, F64Signs)));
    g.bench_function("f32 signs", |b| b.iter(|| all(&adversarial, F32Signs)));
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
