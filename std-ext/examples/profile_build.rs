//! Builds the default rock repeatedly (for profilers): `cargo run --release -p bvhkit-std --example profile_build`.
use bvhkit::{Aabb, Node, TopDown};
fn main() {
    let tris = bvhkit_std::scene::rock(6, 1);
    let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(tris.len())];
    let mut idx = vec![0u32; tris.len()];
    let cfg = TopDown::sah().with_max_leaf_size(1);
    let t = std::time::Instant::now();
    let mut total = 0;
    for _ in 0..20 {
        total += cfg.build(&tris, &mut nodes, &mut idx).unwrap().node_count();
    }
    println!("{} nodes, {:.2} ms per build", total / 20, t.elapsed().as_secs_f64() * 1e3 / 20.0);
}
