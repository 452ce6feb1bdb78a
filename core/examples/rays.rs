//! Closest hits of rays on a mesh, with the point and the normal.
//! `cargo run -p bvhkit --features alloc --example rays`
use bvhkit::glam::Vec3;
use bvhkit::{brute_force, Mesh, Ray};

#[path = "shared/sphere.rs"]
mod sphere;

fn main() -> Result<(), bvhkit::Error> {
    let mesh = Mesh::new(sphere::triangles(32))?;
    let mut hits = 0;
    for k in 0..200 {
        let a = k as f32 * 0.7;
        let origin = Vec3::new(3.0 * a.cos(), 3.0 * a.sin(), (k % 7) as f32 * 0.3 - 1.0);
        let ray = Ray::new(origin, -origin, f32::INFINITY)?; // towards the centre
        let hit = mesh.cast_ray(&ray);
        let want = brute_force::ray_closest(mesh.triangles(), &ray);
        assert_eq!(hit.map(|h| (h.triangle, h.t)), want.map(|h| (h.prim, h.t)));
        if let Some(h) = hit {
            // Outside the sphere, looking in: the front side of its surface.
            assert!(h.front && (h.point.length() - 1.0).abs() < 0.05);
            hits += 1;
        }
    }
    println!("{hits} of 200 rays hit the sphere, each on its outer side");
    Ok(())
}
