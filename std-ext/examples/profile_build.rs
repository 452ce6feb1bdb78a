//! Builds the default rock repeatedly (for profilers): `cargo run --release -p bvhkit-std --example profile_build`.
//! `OWNED=1` builds through `OwnedBvh::build` (fresh buffers, kept leaf
//! bounds: what the peer benchmark times). `PLOC=r` builds bottom-up with PLOC of radius `r` instead (with the
//! default leaf collapse, or none with `COLLAPSE=none`), in the same caller
//! buffers each time; add `OWNED=1` to build through
//! `OwnedBvh::build_bottom_up` (fresh buffers and kept leaf bounds, as the
//! peer benchmark does) from the triangles' boxes. `MESH=path` builds a
//! mesh file instead of the rock.
use bvhkit::builders::{BottomUp, BottomUpScratch, Cluster, Collapse, Method, PrimitiveRef};
use bvhkit::{Aabb, Node, Primitive, TopDown};
fn main() {
    if let Some(radius) = std::env::var("PLOC").ok().and_then(|v| v.parse().ok()) {
        return ploc(radius);
    }
    let tris = input();
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
        total += if std::env::var_os("OWNED").is_some() {
            bvhkit_std::OwnedBvh::<Aabb>::build(&cfg, &tris)
                .unwrap()
                .view()
                .node_count()
        } else if cached {
            cfg.build_cached(&tris, &mut nodes, &mut idx, &mut cache)
                .unwrap()
                .node_count()
        } else {
            cfg.build(&tris, &mut nodes, &mut idx).unwrap().node_count()
        };
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    times.sort_by(f64::total_cmp);
    // The tree's shape and what the builder did, on stderr (the timing
    // line on stdout stays one line for scripts).
    let tree = bvhkit_std::OwnedBvh::<Aabb>::build(&cfg, &tris).unwrap();
    let stats = tree.view().stats();
    let sah = stats.sah_cost;
    eprintln!(
        "{:?}; mean leaf depth {:.2}, max {}, {} leaves over {} primitives",
        tree.view().build_report(),
        stats.mean_leaf_depth,
        stats.max_depth,
        stats.leaves,
        tris.len()
    );
    println!(
        "sah {sah:.3}, {} nodes, {:.2} ms min, {:.2} ms median per build",
        total / reps,
        times[0],
        times[reps / 2]
    );
}

/// The rock, or the mesh file `MESH` names.
fn input() -> Vec<bvhkit::Triangle> {
    match std::env::var("MESH") {
        Ok(path) => bvhkit_std::mesh::load(path.as_ref()).expect("MESH loads"),
        Err(_) => bvhkit_std::scene::rock(6, 1),
    }
}

fn ploc(radius: u32) {
    let tris = input();
    let n = tris.len();
    let builder = BottomUp {
        method: Method::Ploc { radius },
        collapse: match std::env::var("COLLAPSE").as_deref() {
            Ok("none") => Collapse::None,
            _ => Collapse::DEFAULT,
        },
        ..BottomUp::default()
    };
    let (nc, nw, nk) = BottomUp::scratch_len(n);
    let mut clusters = vec![Cluster::<Aabb>::EMPTY; nc];
    let (mut work, mut keys) = (vec![0u32; nw], vec![0u64; nk]);
    let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(n)];
    let mut idx = vec![0u32; n];
    let reps: usize = std::env::var("REPS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(20);
    let mut times = Vec::with_capacity(reps);
    let mut stats = None;
    for _ in 0..reps {
        let mut scratch = BottomUpScratch {
            clusters: &mut clusters,
            work: &mut work,
            keys: &mut keys,
        };
        if std::env::var_os("OWNED").is_some() {
            let boxes: Vec<Aabb> = tris.iter().map(|t| t.bounds()).collect();
            let t = std::time::Instant::now();
            let owned = bvhkit_std::OwnedBvh::<Aabb>::build_bottom_up(&builder, &boxes).unwrap();
            times.push(t.elapsed().as_secs_f64() * 1e3);
            if stats.is_none() {
                stats = Some((owned.view().node_count(), owned.view().stats().sah_cost));
            }
            continue;
        }
        let t = std::time::Instant::now();
        let bvh = builder
            .build(&tris, &mut nodes, &mut idx, &mut scratch)
            .unwrap();
        times.push(t.elapsed().as_secs_f64() * 1e3);
        if stats.is_none() {
            stats = Some((bvh.node_count(), bvh.stats().sah_cost));
        }
    }
    times.sort_by(f64::total_cmp);
    let (count, sah) = stats.unwrap();
    println!(
        "PLOC r{radius}, {n} triangles: sah {sah:.3}, {count} nodes, {:.2} ms min, {:.2} ms median per build",
        times[0],
        times[reps / 2]
    );
}
