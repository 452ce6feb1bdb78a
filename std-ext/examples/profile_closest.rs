//! The closest point of a mesh's surface to many points, as the peer
//! benchmark's `closest-points` task asks it (`Mesh::closest_point`; seeded
//! points in the mesh's box grown by half its size on every side), timed
//! without the build (medians; also a loop for profilers): `cargo run
//! --release -p bvhkit-std --example profile_closest -- [MESH] [RUNS]
//! [POINTS]` (the mesh defaults to the elephant that `scripts/fetch-meshes`
//! gets). Prints a digest of the distances, so that a change to the search
//! can be checked to give the same answers.
use bvhkit::glam::Vec3;
use bvhkit::{Aabb, Mesh, Primitive};
use bvhkit_std::median_time;

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .unwrap_or_else(|| "data/meshes/elephant.off".into());
    let runs: usize = args.next().and_then(|r| r.parse().ok()).unwrap_or(5);
    let n: usize = args.next().and_then(|r| r.parse().ok()).unwrap_or(100_000);
    let tris = bvhkit_std::mesh::load(std::path::Path::new(&path)).expect("mesh loads");
    let bounds = tris.iter().fold(Aabb::EMPTY, |b, t| b.union(&t.bounds()));
    let mut s = 0x5eed_0002u64;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / (1u64 << 24) as f32
    };
    let size = bounds.max - bounds.min;
    let points: Vec<Vec3> = (0..n)
        .map(|_| bounds.min + (Vec3::new(next(), next(), next()) * 2.0 - 0.5) * size)
        .collect();
    let mesh = Mesh::new(tris).expect("a valid mesh");
    let (t, digest) = median_time(runs, || {
        points
            .iter()
            .map(|&p| mesh.closest_point(p).expect("a point").distance)
            .sum::<f64>()
    });
    println!(
        "{path}: {} triangles, {n} points, {:.1} ms (median of {runs}), distance sum {digest:.6}",
        mesh.triangles().len(),
        t.as_secs_f64() * 1e3
    );
}
