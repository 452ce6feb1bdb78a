//! The reference answers, computed without any tree.
//!
//! `O(n)` for a region, `O(n * m)` for pairs: too slow for real scenes, exactly
//! right for checking every hierarchy against.

use crate::bv::BoundingVolume;
use crate::primitive::Primitive;

/// Every primitive whose bounds overlap `region` (by `region.overlaps_aabb`); returns the count.
///
/// ```
/// use bvhkit::{brute_force, Aabb};
/// use glam::Vec3;
/// let pts = [Vec3::ZERO, Vec3::splat(5.0)];
/// let n = brute_force::overlapping(&pts, &Aabb::new(Vec3::splat(-1.0), Vec3::ONE), |_| {});
/// assert_eq!(n, 1);
/// ```
pub fn overlapping<P: Primitive, R: BoundingVolume>(
    prims: &[P],
    region: &R,
    mut f: impl FnMut(u32),
) -> usize {
    let mut found = 0;
    for (i, p) in prims.iter().enumerate() {
        if region.overlaps_aabb(&p.bounds()) {
            f(i as u32);
            found += 1;
        }
    }
    found
}

/// Every pair `(i, j)` with `a[i]`'s bounds overlapping `b[j]`'s; returns the count.
pub fn pairs<P: Primitive, Q: Primitive>(a: &[P], b: &[Q], mut f: impl FnMut(u32, u32)) -> usize {
    let mut found = 0;
    for (i, p) in a.iter().enumerate() {
        let pb = p.bounds();
        for (j, q) in b.iter().enumerate() {
            if pb.overlaps(&q.bounds()) {
                f(i as u32, j as u32);
                found += 1;
            }
        }
    }
    found
}
