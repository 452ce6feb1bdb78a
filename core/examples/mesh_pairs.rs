//! Every intersecting triangle pair of a mesh and a moved copy of it, decided
//! exactly, without rebuilding the copy's tree.
//! `cargo run -p bvhkit --features alloc --example mesh_pairs`
use bvhkit::glam::{Quat, Vec3};
use bvhkit::{brute_force, Exact, Mesh, Rigid};

#[path = "shared/sphere.rs"]
mod sphere;

fn main() -> Result<(), bvhkit::Error> {
    let mesh = Mesh::new(sphere::triangles(24))?;
    let motion = Rigid::new(Quat::from_rotation_y(0.4), Vec3::new(0.3, 0.1, 0.0))?;
    let pairs = mesh.pairs(&mesh, &motion);

    let mut want = Vec::new();
    brute_force::pairs_placed(
        mesh.triangles(),
        mesh.triangles(),
        &motion,
        Exact,
        |i, j| want.push((i, j)),
    );
    want.sort_unstable();
    assert_eq!(pairs, want);
    println!(
        "{} triangles: {} intersecting pairs",
        mesh.triangles().len(),
        pairs.len()
    );
    Ok(())
}
