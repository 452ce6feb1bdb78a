//! `Mesh`, the owned one-value API, from arbitrary bytes: vertices (any
//! `f32` bits, NaN and infinities included), index triples (any `u32`), a
//! ray, a point, a distance and a rigid motion. Building either refuses with
//! an error or gives a mesh; every query on it runs to the end, and its
//! answers agree with brute force over the mesh's own triangles. Never a
//! panic, never a hang.
#![no_main]
use bvhkit::glam::{Quat, Vec3};
use bvhkit::{brute_force, Mesh, Ray, Rigid};

/// Reads little-endian words from the input, then zeros once it runs out.
struct Words<'a>(&'a [u8]);
impl Words<'_> {
    fn u32(&mut self) -> u32 {
        let (head, rest) = self.0.split_at(self.0.len().min(4));
        self.0 = rest;
        let mut b = [0u8; 4];
        b[..head.len()].copy_from_slice(head);
        u32::from_le_bytes(b)
    }
    fn f32(&mut self) -> f32 {
        f32::from_bits(self.u32())
    }
    fn vec3(&mut self) -> Vec3 {
        Vec3::new(self.f32(), self.f32(), self.f32())
    }
}

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let mut w = Words(data);
    let (nv, nt) = ((w.u32() % 24) as usize, (w.u32() % 32) as usize);
    let vertices: Vec<Vec3> = (0..nv).map(|_| w.vec3()).collect();
    // Mostly valid indices, with an occasional one out of range.
    let triangles: Vec<[u32; 3]> = (0..nt)
        .map(|_| {
            let mut t = [w.u32(), w.u32(), w.u32()];
            for i in &mut t {
                if *i & 0xff != 0xff {
                    *i %= nv.max(1) as u32;
                }
            }
            t
        })
        .collect();
    let Ok(mesh) = Mesh::from_indexed(&vertices, &triangles) else {
        return;
    };
    let tris = mesh.triangles();
    let (origin, dir, point, distance) = (w.vec3(), w.vec3(), w.vec3(), w.f32());
    if let Ok(ray) = Ray::new(origin, dir, f32::INFINITY) {
        let hit = mesh.cast_ray(&ray).map(|h| h.t);
        assert_eq!(hit, brute_force::ray_closest(tris, &ray).map(|h| h.t));
    }
    if point.is_finite() {
        let near = mesh.closest_point(point);
        let brute = brute_force::nearest(tris, point);
        assert_eq!(near.is_some(), brute.is_some());
        if distance.is_finite() && distance >= 0.0 {
            let _ = mesh.within(point, distance);
        }
    }
    let rotation = Quat::from_xyzw(w.f32(), w.f32(), w.f32(), w.f32());
    if let Ok(motion) = Rigid::new(rotation, w.vec3()) {
        let pairs = mesh.pairs(&mesh, &motion);
        assert_eq!(mesh.intersects(&mesh, &motion), !pairs.is_empty());
    }
});
