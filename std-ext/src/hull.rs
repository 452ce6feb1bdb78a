//! The convex hull's volume: the lower bound of every convex bounding
//! volume, against which the bench reports each fit's looseness.
//!
//! The hull comes from the `quickhull` crate (Quickhull, Barber et al. 1996,
//! as in Jolt and parry); the volume is summed here in `f64` over the hull's
//! triangles, each as a signed tetrahedron with the hull's centroid.

use bvhkit::glam::{DVec3, Vec3};

/// The volume of the convex hull of `points`; `None` when the hull is flat
/// (fewer than four points off one plane) or could not be built.
///
/// ```
/// use bvhkit::glam::Vec3;
/// let cube: Vec<Vec3> = (0..8)
///     .map(|i| Vec3::new((i & 1) as f32, (i >> 1 & 1) as f32, (i >> 2) as f32))
///     .chain([Vec3::splat(0.5)])
///     .collect();
/// let v = bvhkit_std::hull::volume(&cube).unwrap();
/// assert!((v - 1.0).abs() < 1e-6);
/// assert_eq!(bvhkit_std::hull::volume(&[Vec3::ZERO, Vec3::X, Vec3::Y]), None);
/// ```
pub fn volume(points: &[Vec3]) -> Option<f64> {
    let pts: Vec<quickhull_glam::Vec3A> = points
        .iter()
        .map(|p| quickhull_glam::Vec3A::new(p.x, p.y, p.z))
        .collect();
    let hull = quickhull::ConvexTriangleMesh::try_from_points(&pts, None).ok()?;
    let verts: Vec<DVec3> = hull
        .vertices()
        .iter()
        .map(|v| DVec3::new(v.x as f64, v.y as f64, v.z as f64))
        .collect();
    if verts.is_empty() || hull.indices().len() < 4 {
        return None;
    }
    let centre = verts.iter().copied().sum::<DVec3>() / verts.len() as f64;
    let six_v: f64 = hull
        .indices()
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| verts[i as usize] - centre);
            a.dot(b.cross(c))
        })
        .sum();
    let v = six_v.abs() / 6.0;
    (v > 0.0).then_some(v)
}
