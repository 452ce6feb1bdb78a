//! The dynamic tree's upkeep: inserting the 20,480 boxes of the default rock
//! (in the scene's order and sorted along x) with the default height
//! rotations and with rotations by area, and one `optimize` pass (every node
//! reinserted once) over a tree grown from sorted input without rotations,
//! against `rebuild`. Prints each tree's area sum per object.
//!
//! Run: `cargo bench -p bvhkit-std --bench dynamic`

use bvhkit::builders::{DynNode, DynamicConfig, DynamicTree, Rotations};
use bvhkit::{Aabb, Primitive};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;

/// Inserts `boxes` in order into a tree over `storage`.
fn grow<'s>(
    storage: &'s mut [DynNode<Aabb>],
    boxes: &[Aabb],
    rotations: Rotations,
) -> DynamicTree<'s, Aabb> {
    let config = DynamicConfig {
        rotations,
        ..Default::default()
    };
    let mut tree = DynamicTree::new(storage, config).unwrap();
    for (i, b) in boxes.iter().enumerate() {
        tree.insert(i as u32, b).unwrap();
    }
    tree
}

fn bench(c: &mut Criterion) {
    let rock: Vec<Aabb> = bvhkit_std::scene::rock(5, 1)
        .iter()
        .map(Primitive::bounds)
        .collect();
    let mut sorted = rock.clone();
    sorted.sort_by(|a, b| a.min.x.total_cmp(&b.min.x));
    let n = rock.len();
    let mut storage = vec![DynNode::<Aabb>::EMPTY; 2 * n - 1];
    let mut g = c.benchmark_group("dynamic-tree");
    g.sample_size(10);
    for (order, boxes) in [("given", &rock), ("sorted", &sorted)] {
        for (name, rotations) in [
            ("default", DynamicConfig::default().rotations),
            ("area", Rotations::Area),
        ] {
            let label = format!("insert {n}, {order}, rotations {name}");
            let tree = grow(&mut storage, boxes, rotations);
            eprintln!(
                "{label}: area sum {:.4} per object, height {}",
                tree.area_sum() / n as f64,
                tree.height()
            );
            g.bench_function(BenchmarkId::new("insert", &label), |b| {
                b.iter(|| black_box(grow(&mut storage, boxes, rotations).height()))
            });
        }
    }
    // A tree holds its storage, so the repairs are timed with the sorted,
    // unrotated growth that needs them: subtract the first row.
    let mut scratch = vec![0u32; n];
    g.bench_function("sorted growth without rotations", |b| {
        b.iter(|| black_box(grow(&mut storage, &sorted, Rotations::Off).height()))
    });
    g.bench_function("... then one optimize pass (every node once)", |b| {
        b.iter(|| {
            let mut tree = grow(&mut storage, &sorted, Rotations::Off);
            black_box(tree.optimize(2 * n).unwrap())
        })
    });
    g.bench_function("... then rebuild", |b| {
        b.iter(|| {
            let mut tree = grow(&mut storage, &sorted, Rotations::Off);
            tree.rebuild(&mut scratch).unwrap();
            black_box(tree.height())
        })
    });
    let mut tree = grow(&mut storage, &sorted, Rotations::Off);
    let before = tree.area_sum() / n as f64;
    tree.optimize(2 * n).unwrap();
    let optimized = tree.area_sum() / n as f64;
    tree.rebuild(&mut scratch).unwrap();
    eprintln!(
        "sorted, no rotations: area sum {before:.4} per object; one optimize pass {optimized:.4}; \
         rebuilt {:.4}",
        tree.area_sum() / n as f64
    );
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
