//! Builds the default rock repeatedly (for profilers): `cargo run --release -p bvhkit-std --example profile_build`.
use bvhkit::{builders::PrimitiveRef, Aabb, Node, TopDown};
fn main() {
    let tris = bvhkit_std::scene::rock(6, 1);
    let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(tris.len())];
    let mut idx = vec![0u32; tris.len()];
    let mut cache = vec![PrimitiveRef::EMPTY; tris.len()];
    let cached = std::env::args().any(|a| a == "--cached");
    let leaf: u32 = std::env::var("LEAF")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1);
    let mut cfg = TopDown::sah().with_max_leaf_size(leaf);
    if std::env::args().any(|a| a == "--longest") {
        cfg.axis = bvhkit::AxisChoice::Longest;
    }
    if let Some(k) = std::env::var("BINS").ok().and_then(|v| v.parse().ok()) {
        cfg.split = bvhkit::SplitPoint::Bins(k);
    }
    let reps: usize = std::env::var("REPS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(20);
    let (mut times, mut total) = (Vec::with_capacity(reps), 0);
    for _ in 0..reps {
        let t = std::time::Instant::now();
        total += if cached {
            cfg.build_cached(&tris, &mut nodes, &mut idx, &mut cache)
                .unwrap()
                .node_count()
        } else {
            cfg.build(&tris, &mut nodes, &mut idx).unwrap().node_count()
        };
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    times.sort_by(f64::total_cmp);
    let sah = bvhkit_std::OwnedBvh::<Aabb>::build(&cfg, &tris)
        .unwrap()
        .view()
        .stats()
        .sah_cost;
    println!(
        "sah {sah:.3}, {} nodes, {:.2} ms min, {:.2} ms median per build",
        total / reps,
        times[0],
        times[reps / 2]
    );
}
