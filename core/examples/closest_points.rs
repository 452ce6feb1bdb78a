//! The closest point of a mesh to many points, and every triangle within a
//! distance of each. `cargo run -p bvhkit --features alloc --example closest_points`
use bvhkit::glam::Vec3;
use bvhkit::{brute_force, Mesh};

#[path = "shared/sphere.rs"]
mod sphere;

fn main() -> Result<(), bvhkit::Error> {
    let mesh = Mesh::new(sphere::triangles(32))?;
    let mut near = 0;
    for k in 0..200 {
        let a = k as f32 * 0.37;
        let p =
            Vec3::new(a.cos(), a.sin(), (k % 11) as f32 * 0.1 - 0.5) * (0.5 + (k % 5) as f32 * 0.3);
        let c = mesh.closest_point(p).expect("a mesh with triangles");
        let want = brute_force::nearest(mesh.triangles(), p).unwrap();
        assert_eq!(
            (c.triangle, c.distance),
            (want.prim, want.distance_squared.sqrt())
        );
        let within = mesh.within(p, 0.25);
        let limit = 0.25f64 * 0.25;
        let all = mesh.triangles().iter().enumerate();
        let want: Vec<u32> = all
            .filter(|(_, t)| t.closest_point(p).distance_squared <= limit)
            .map(|(i, _)| i as u32)
            .collect();
        assert_eq!(within, want);
        near += within.len();
    }
    println!("200 points: closest points found, {near} triangles within 0.25 in all");
    Ok(())
}
