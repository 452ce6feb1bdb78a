//! Your answers. Replace each `todo!()`; run the grader to see your points.
#![allow(clippy::todo)] // the stubs are meant to be unfinished

use crate::Exercises;
use bvhkit::glam::Vec3;
use bvhkit::{Aabb, Sphere};

/// Your implementation of the exercises.
#[derive(Debug, Default)]
pub struct Student;

impl Exercises for Student {
    /// Two boxes overlap when their intervals overlap on *every* axis.
    /// Hint: touching boxes (sharing a face, an edge or a corner) overlap.
    fn aabb_overlaps(&self, a: &Aabb, b: &Aabb) -> bool {
        let _ = (a, b);
        todo!("exercise 1")
    }

    /// Hint: start from the first point, not from zero.
    fn aabb_fit(&self, points: &[Vec3]) -> Aabb {
        let _ = points;
        todo!("exercise 2a")
    }

    /// Hint: component-wise min of the mins and max of the maxes.
    fn aabb_merge(&self, a: &Aabb, b: &Aabb) -> Aabb {
        let _ = (a, b);
        todo!("exercise 2b")
    }

    /// Hint (Ritter): take the two most separated points among the extremes
    /// along x, y and z as a diameter; then for every point outside, grow the
    /// sphere just enough to include it, moving the centre towards the point.
    /// Floating point: make sure every point really ends up inside.
    fn sphere_fit(&self, points: &[Vec3]) -> Sphere {
        let _ = points;
        todo!("exercise 2c")
    }

    /// Hint: if one sphere contains the other, return it. Otherwise the merged
    /// sphere's diameter runs along the line through both centres.
    fn sphere_merge(&self, a: &Sphere, b: &Sphere) -> Sphere {
        let _ = (a, b);
        todo!("exercise 2d")
    }

    /// Hint: `select_nth_unstable_by` does the reordering in linear time.
    /// The axis is chosen from the *centroids'* box, not the primitives'.
    fn median_partition(&self, centroids: &[Vec3], indices: &mut [u32]) -> usize {
        let _ = (centroids, indices);
        todo!("exercise 3")
    }
}
