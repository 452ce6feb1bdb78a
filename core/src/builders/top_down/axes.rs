//! Axis choice: the candidate directions a split is tried along (Ericson
//! 6.2.3: the coordinate axes, the longest one, the principal component of
//! the centroids, the direction through the most distant pair).

use super::source::{centroid, Source};
use super::Task;
use crate::builders::strategy::AxisChoice;
use crate::bv::BoundingVolume;
use glam::{DMat3, DVec3, Vec3};

/// The coordinate axis along which the centroids spread most (the boxes, when
/// every centroid coincides).
pub(super) fn longest_direction(task: &Task) -> Vec3 {
    let c = if task.centroids.extent().max_element() > 0.0 {
        task.centroids
    } else {
        task.bounds
    };
    crate::bv::Axes::XYZ.axes[c.longest_axis()]
}

/// Candidate directions for an axis choice (at most 13).
pub(super) fn directions<S: Source, B: BoundingVolume>(
    src: &S,
    range: &[S::Item],
    task: &Task,
    bv: &B,
    axis: AxisChoice,
) -> crate::bv::Axes {
    use crate::bv::Axes;
    let one = |d: Vec3| {
        let mut a = Axes::XYZ;
        a.axes[0] = d;
        a.len = 1;
        a
    };
    match axis {
        AxisChoice::X => one(Vec3::X),
        AxisChoice::Y => one(Vec3::Y),
        AxisChoice::Z => one(Vec3::Z),
        AxisChoice::BestOfXyz => Axes::XYZ,
        AxisChoice::Longest => one(longest_direction(task)),
        AxisChoice::Variance => one(principal_direction(src, range)),
        AxisChoice::DistantPoints => one(distant_direction(src, range)),
        AxisChoice::ParentVolume => bv.axes(),
    }
}

/// Principal component of the centroids (normalised covariance, f64 Jacobi).
pub(super) fn principal_direction<S: Source>(src: &S, range: &[S::Item]) -> Vec3 {
    let n = range.len() as f64;
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    let mut mean = DVec3::ZERO;
    for &i in range {
        let c = centroid(src, i).as_dvec3();
        mean += c;
        lo = lo.min(c);
        hi = hi.max(c);
    }
    mean /= n;
    let scale = 1.0 / (hi - lo).max_element().max(f64::MIN_POSITIVE);
    let mut cov = DMat3::ZERO;
    for &i in range {
        let v = (centroid(src, i).as_dvec3() - mean) * scale;
        cov += DMat3::from_cols(v * v.x, v * v.y, v * v.z);
    }
    let (_, vecs) = crate::bv::symmetric_eigen(cov);
    let d = vecs.x_axis.as_vec3();
    if d.is_finite() && d.length_squared() > 0.5 {
        d
    } else {
        Vec3::X
    }
}

/// Direction through the most distant pair among the six axis-extreme centroids.
pub(super) fn distant_direction<S: Source>(src: &S, range: &[S::Item]) -> Vec3 {
    let c = |i: S::Item| centroid(src, i);
    let mut lo = [range[0]; 3];
    let mut hi = [range[0]; 3];
    for &i in range {
        let p = c(i);
        for k in 0..3 {
            if p[k] < c(lo[k])[k] {
                lo[k] = i;
            }
            if p[k] > c(hi[k])[k] {
                hi[k] = i;
            }
        }
    }
    let mut best = Vec3::X;
    let mut best_d = -1.0f64;
    for k in 0..3 {
        let v = c(hi[k]).as_dvec3() - c(lo[k]).as_dvec3();
        if v.length_squared() > best_d {
            best_d = v.length_squared();
            best = v.normalize_or(DVec3::X).as_vec3();
        }
    }
    best
}
