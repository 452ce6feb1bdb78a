//! The default pair query on a mesh against a moved copy, as the peer
//! benchmark runs it, with and without the kept leaf bounds (medians; also a
//! loop for profilers): `cargo run --release -p bvhkit-std --example
//! profile_pairs -- [MESH] [RUNS]` (the mesh defaults to the armadillo that
//! `scripts/fetch-meshes` gets).
use bvhkit::glam::Vec3;
use bvhkit::{Aabb, Counts, Pairs, Primitive, TopDown};
use bvhkit_std::{median_time, scene, OwnedBvh};

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .unwrap_or_else(|| "data/meshes/armadillo.off".into());
    let runs: usize = args.next().and_then(|r| r.parse().ok()).unwrap_or(50);
    let a = bvhkit_std::mesh::load(std::path::Path::new(&path)).expect("mesh loads");
    let boxes_a: Vec<Aabb> = a.iter().map(|t| t.bounds()).collect();
    let bounds = boxes_a.iter().fold(Aabb::EMPTY, |u, b| u.union(b));
    // The peer benchmark's motion: 0.02 rad, 1% of the box.
    let shift = (bounds.max - bounds.min) * Vec3::new(0.01, 0.007, 0.004);
    let b = scene::transformed(&a, 0.02, shift);
    let boxes_b: Vec<Aabb> = b.iter().map(|t| t.bounds()).collect();
    let ta = OwnedBvh::<Aabb>::build(&TopDown::default(), &boxes_a).expect("builds");
    let tb = OwnedBvh::<Aabb>::build(&TopDown::default(), &boxes_b).expect("builds");
    let mut counts = Counts::default();
    let n = Pairs::new(&ta.view(), &boxes_a, &tb.view(), &boxes_b)
        .counted(&mut counts)
        .count()
        .expect("query");
    println!(
        "{path}: {} triangles, {n} pairs, Nv {} Np {}",
        a.len(),
        counts.bv_tests,
        counts.prim_tests
    );
    for (name, va, vb) in [
        ("kept leaf bounds (default)", ta.view(), tb.view()),
        ("without leaf bounds", ta.plain_view(), tb.plain_view()),
    ] {
        let (t, m) = median_time(runs, || {
            Pairs::new(&va, &boxes_a, &vb, &boxes_b)
                .count()
                .expect("query")
        });
        assert_eq!(m, n);
        println!(
            "{name:<28} {:.3} ms (median of {runs})",
            t.as_secs_f64() * 1e3
        );
    }
}
