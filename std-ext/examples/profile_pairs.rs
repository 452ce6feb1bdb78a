//! The default pair query on a mesh against a moved copy, as the peer
//! benchmark runs it, with and without the kept leaf bounds (medians; also a
//! loop for profilers): `cargo run --release -p bvhkit-std --example
//! profile_pairs -- [MESH] [RUNS] [kept|plain|moved]` (the mesh defaults to
//! the armadillo that `scripts/fetch-meshes` gets; the last argument times
//! one only). `moved` is the same query with B as A's own tree moved by the
//! same motion (`in_frame`, no rebuild).
use bvhkit::glam::{Quat, Vec3};
use bvhkit::{Aabb, Counts, Pairs, Primitive, Rigid, TopDown};
use bvhkit_std::{median_time, scene, OwnedBvh};

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .unwrap_or_else(|| "data/meshes/armadillo.off".into());
    let runs: usize = args.next().and_then(|r| r.parse().ok()).unwrap_or(50);
    let only = args.next();
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
    for (key, name, va, vb) in [
        ("kept", "kept leaf bounds (default)", ta.view(), tb.view()),
        (
            "plain",
            "without leaf bounds",
            ta.plain_view(),
            tb.plain_view(),
        ),
    ] {
        if only.as_deref().is_some_and(|o| o != key) {
            continue;
        }
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
    if only.as_deref().is_none_or(|o| o == "moved") {
        // The motion of `scene::transformed`: about y, then half about x.
        let turn = Quat::from_rotation_y(0.02) * Quat::from_rotation_x(0.01);
        let motion = Rigid::new(turn, shift).expect("motion");
        let va = ta.view();
        let mut moved = Counts::default();
        Pairs::new(&va, &boxes_a, &va, &boxes_a)
            .in_frame(motion)
            .counted(&mut moved)
            .count()
            .expect("query");
        println!(
            "B moved: Nv {} Np {} Nu {}",
            moved.bv_tests, moved.prim_tests, moved.updates
        );
        let (t, m) = median_time(runs, || {
            Pairs::new(&va, &boxes_a, &va, &boxes_a)
                .in_frame(motion)
                .count()
                .expect("query")
        });
        println!(
            "{:<28} {:.3} ms (median of {runs}), {m} pairs",
            "B moved (in_frame)",
            t.as_secs_f64() * 1e3
        );
    }
}
