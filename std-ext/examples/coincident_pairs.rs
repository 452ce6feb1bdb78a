//! Every intersecting pair of triangles (exact) of a mesh against a copy of
//! itself in place (coincident surfaces) and against a slightly moved copy
//! (the peer benchmark's motion), through `Mesh::pairs` (medians of 21):
//! `cargo run --release -p bvhkit-std --example coincident_pairs -- [MESH]`
//! (the armadillo by default; `ONLY_MOVED=1` skips the coincident case).
use bvhkit::glam::{Quat, Vec3};
use bvhkit::{Aabb, Mesh, Primitive, Rigid};
use bvhkit_std::median_time;
fn main() {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "data/meshes/armadillo.off".into());
    let tris = bvhkit_std::mesh::load(std::path::Path::new(&path)).unwrap();
    let bounds = tris.iter().fold(Aabb::EMPTY, |u, t| u.union(&t.bounds()));
    let shift = (bounds.max - bounds.min) * Vec3::new(0.01, 0.007, 0.004);
    let mesh = Mesh::new(tris).unwrap();
    for (name, motion) in [
        ("unmoved", Rigid::IDENTITY),
        (
            "moved",
            Rigid::new(
                Quat::from_rotation_y(0.02) * Quat::from_rotation_x(0.01),
                shift,
            )
            .unwrap(),
        ),
    ] {
        if std::env::var_os("ONLY_MOVED").is_some() && name == "unmoved" {
            continue;
        }
        let (t, n) = median_time(21, || mesh.pairs(&mesh, &motion).len());
        println!("{name}: {n} pairs, {:.1} ms", t.as_secs_f64() * 1e3);
    }
}
