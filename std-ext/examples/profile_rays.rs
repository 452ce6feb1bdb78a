//! Closest-hit rays on a mesh, as the peer benchmark casts them (random rays
//! into the mesh's box), on the default tree and its 4-wide layout (medians;
//! also a loop for profilers): `cargo run --release -p bvhkit-std --features cli --example
//! profile_rays -- [MESH] [RUNS] [RAYS]` (the mesh defaults to the
//! armadillo that `scripts/fetch-meshes` gets).
use bvhkit::layout::{Wide, WideNode};
use bvhkit::{Aabb, Primitive, Query, RayOrder, TopDown};
use bvhkit_std::{layouts::rays, median_time, OwnedBvh};

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .unwrap_or_else(|| "data/meshes/armadillo.off".into());
    let runs: usize = args.next().and_then(|r| r.parse().ok()).unwrap_or(9);
    let n: usize = args.next().and_then(|r| r.parse().ok()).unwrap_or(100_000);
    let mesh = bvhkit_std::mesh::load(std::path::Path::new(&path)).expect("mesh loads");
    let boxes: Vec<Aabb> = mesh.iter().map(|t| t.bounds()).collect();
    let tree = OwnedBvh::<Aabb>::build(&TopDown::default(), &boxes).expect("builds");
    let view = tree.view();
    let mut records = vec![WideNode::EMPTY; Wide::records_needed(&view).expect("fits")];
    let wide = Wide::from_bvh(&view, &mut records).expect("converts");
    let rs = rays(&mesh, n);
    let cast = |h: &dyn Fn(&bvhkit::query::Ray) -> Option<bvhkit::Hit>| {
        median_time(runs, || rs.iter().filter_map(h).count())
    };
    let (t, hits) = cast(&|r| {
        view.cast_ray(&mesh, r, RayOrder::default(), ())
            .expect("ray query")
    });
    let (tw, hw) = cast(&|r| {
        wide.cast_ray(&mesh, r, RayOrder::default(), ())
            .expect("ray query")
    });
    assert_eq!(hits, hw);
    let rate = |t: std::time::Duration| rs.len() as f64 / t.as_secs_f64() / 1e6;
    println!(
        "{path}: {} triangles, {} rays, {hits} hits; default tree {:.3} Mrays/s, wide4 {:.3} Mrays/s (medians of {runs})",
        mesh.len(),
        rs.len(),
        rate(t),
        rate(tw)
    );
}
