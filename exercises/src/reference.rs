//! Reference answers, written with the library.

use crate::Exercises;
use bvhkit::glam::Vec3;
use bvhkit::{Aabb, BoundingVolume, Sphere};

/// The reference implementation: scores 100%.
#[derive(Debug, Default)]
pub struct Reference;

impl Exercises for Reference {
    fn aabb_overlaps(&self, a: &Aabb, b: &Aabb) -> bool {
        a.overlaps(b)
    }
    fn aabb_fit(&self, points: &[Vec3]) -> Aabb {
        Aabb::fit(points)
    }
    fn aabb_merge(&self, a: &Aabb, b: &Aabb) -> Aabb {
        a.union(b)
    }
    fn sphere_fit(&self, points: &[Vec3]) -> Sphere {
        Sphere::ritter(points)
    }
    fn sphere_merge(&self, a: &Sphere, b: &Sphere) -> Sphere {
        a.merge(b)
    }
    fn median_partition(&self, centroids: &[Vec3], indices: &mut [u32]) -> usize {
        let cb = Aabb::fit(centroids);
        let axis = cb.longest_axis();
        let mid = indices.len() / 2;
        if mid > 0 {
            indices.select_nth_unstable_by(mid, |&a, &b| {
                centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis])
            });
        }
        mid
    }
}
