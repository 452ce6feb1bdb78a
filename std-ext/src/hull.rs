//! The convex hull: its volume, the lower bound of every convex bounding
//! volume, against which the bench reports each fit's looseness; and its
//! vertices and triangles, which the hull-based OBB fits of the core
//! (`Obb::pca_hull`, `Obb::face_flush`) start from.
//!
//! The hull comes from the `quickhull` crate (Quickhull, Barber et al. 1996,
//! as in Jolt and parry); the volume is summed here in `f64` over the hull's
//! triangles, each as a signed tetrahedron with the hull's centroid.

use bvhkit::glam::{DVec3, Vec3};
use std::collections::HashSet;

/// A convex hull as a triangle mesh.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// The hull's vertices: input points, bit for bit, each used by a triangle.
    pub vertices: Vec<Vec3>,
    /// The hull's triangles, indexing `vertices` (counter-clockwise seen
    /// from outside for a solid hull).
    pub triangles: Vec<[u32; 3]>,
}

/// The convex hull of `points` as vertices and triangles; `None` when
/// quickhull fails (a NaN, or a set it finds nearly coplanar) or gives a
/// vertex that is not one of `points` (checked: it happens on some
/// two-point sets).
///
/// Degenerate sets come back as quickhull builds them: a point or a segment
/// as triangles of zero area (`[0, 1, 0]`), a flat set sometimes as a
/// two-sided flat hull. The core's hull fits accept all of these (they skip
/// zero-area triangles and fall back to `Obb::pca` when none is left).
///
/// ```
/// use bvhkit::glam::{Vec2, Vec3};
/// use bvhkit::{BoundingVolume, Obb};
/// let cube: Vec<Vec3> = (0..8)
///     .map(|i| Vec3::new((i & 1) as f32, (i >> 1 & 1) as f32, (i >> 2) as f32))
///     .chain([Vec3::splat(0.5)])
///     .collect();
/// let hull = bvhkit_std::hull::mesh(&cube).unwrap();
/// assert_eq!(hull.vertices.len(), 8); // the centre is inside
/// assert_eq!(hull.triangles.len(), 12);
/// let mut scratch = vec![Vec2::ZERO; Obb::face_flush_scratch_len(hull.vertices.len())];
/// let obb = Obb::face_flush(&hull.vertices, &hull.triangles, &mut scratch).unwrap();
/// assert!((obb.volume() - 1.0).abs() < 1e-5);
/// ```
pub fn mesh(points: &[Vec3]) -> Option<Mesh> {
    let pts: Vec<quickhull_glam::Vec3A> = points
        .iter()
        .map(|p| quickhull_glam::Vec3A::new(p.x, p.y, p.z))
        .collect();
    let hull = quickhull::ConvexTriangleMesh::try_from_points(&pts, None).ok()?;
    let (vertices, triangles) = hull.into_parts();
    let vertices: Vec<Vec3> = vertices.iter().map(|v| Vec3::new(v.x, v.y, v.z)).collect();
    // Checked, not trusted: quickhull 0.1 answers some two-point sets with
    // a "segment" from the origin to the origin (its extremes start there,
    // and a NaN direction never moves them). A vertex that is no input
    // point, or a triangle past the vertices, means no hull.
    let bits = |p: &Vec3| p.to_array().map(f32::to_bits);
    let inputs: HashSet<[u32; 3]> = points.iter().map(bits).collect();
    let valid = vertices.iter().all(|v| inputs.contains(&bits(v)))
        && triangles
            .iter()
            .flatten()
            .all(|&k| (k as usize) < vertices.len());
    valid.then_some(Mesh {
        vertices,
        triangles,
    })
}

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
    mesh(points)?.volume()
}

impl Mesh {
    /// The volume enclosed; `None` when it is flat (or fewer than four
    /// triangles).
    pub fn volume(&self) -> Option<f64> {
        let verts: Vec<DVec3> = self.vertices.iter().map(|v| v.as_dvec3()).collect();
        if verts.is_empty() || self.triangles.len() < 4 {
            return None;
        }
        let centre = verts.iter().copied().sum::<DVec3>() / verts.len() as f64;
        let six_v: f64 = self
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| verts[i as usize] - centre);
                a.dot(b.cross(c))
            })
            .sum();
        let v = six_v.abs() / 6.0;
        (v > 0.0).then_some(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every hull vertex is an input point, or there is no hull. Quickhull
    /// 0.1 answered this segment (found by the property test of the hull
    /// fits) with the origin, twice: its segment case starts its extremes
    /// at the origin and a NaN direction never moves them.
    #[test]
    fn hull_vertices_are_input_points() {
        let sets: [&[Vec3]; 3] = [
            &[
                Vec3::new(-1.9400345, -2.136965, 0.0),
                Vec3::new(-1.3193092, 1.509896, 0.0),
            ],
            &[
                Vec3::new(100001.086, -50004.363, 24995.291) * 1e-30,
                Vec3::new(99998.914, -50000.43, 24998.924) * 1e-30,
            ],
            &[Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z, Vec3::splat(0.2)],
        ];
        for pts in sets {
            if let Some(hull) = mesh(pts) {
                for v in &hull.vertices {
                    assert!(pts.contains(v), "{v:?} is not one of {pts:?}");
                }
            }
        }
        assert_eq!(mesh(sets[2]).map(|h| h.vertices.len()), Some(4));
    }
}
