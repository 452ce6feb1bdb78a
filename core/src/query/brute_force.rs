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

/// Every pair `(i, j)`, `i < j`, of one set whose bounds overlap; returns
/// the count. The reference for [`SelfPairs`](super::SelfPairs) (which by
/// default also skips [`Adjacent`](super::Adjacent) pairs: filter this
/// answer the same way to compare).
///
/// ```
/// use bvhkit::{brute_force, Aabb};
/// use glam::Vec3;
/// let boxes = [Aabb::new(Vec3::ZERO, Vec3::ONE), Aabb::new(Vec3::ONE, Vec3::splat(2.0)), Aabb::new(Vec3::splat(5.0), Vec3::splat(6.0))];
/// let mut pairs = Vec::new();
/// assert_eq!(brute_force::self_pairs(&boxes, |i, j| pairs.push((i, j))), 1);
/// assert_eq!(pairs, [(0, 1)]); // touching counts; no box with itself
/// ```
pub fn self_pairs<P: Primitive>(prims: &[P], mut f: impl FnMut(u32, u32)) -> usize {
    let mut found = 0;
    for (i, p) in prims.iter().enumerate() {
        let pb = p.bounds();
        for (j, q) in prims.iter().enumerate().skip(i + 1) {
            if pb.overlaps(&q.bounds()) {
                f(i as u32, j as u32);
                found += 1;
            }
        }
    }
    found
}

/// Every pair `(i, j)` that `answer` accepts, with `b[j]` first placed in A's
/// frame by `frame` (for example a [`Rigid`](crate::Rigid) motion); returns
/// the count. The reference for [`Pairs`](crate::Pairs) with any frame and
/// answer.
///
/// ```
/// use bvhkit::{brute_force, Exact, Rigid, Triangle};
/// use glam::Vec3;
/// let a = [Triangle::new(Vec3::ZERO, Vec3::X * 2.0, Vec3::Y * 2.0)];
/// let b = [Triangle::new(Vec3::new(0.5, 0.5, -1.0), Vec3::new(0.5, 0.5, 1.0), Vec3::new(0.6, 0.5, 1.0))];
/// let lift = Rigid::translation(Vec3::Z * 5.0)?;
/// assert_eq!(brute_force::pairs_placed(&a, &b, &bvhkit::Same, Exact, |_, _| {}), 1);
/// assert_eq!(brute_force::pairs_placed(&a, &b, &lift, Exact, |_, _| {}), 0);
/// # Ok::<(), bvhkit::Error>(())
/// ```
pub fn pairs_placed<P, Q, F: crate::Place<Q>, X: crate::Answer<P, Q>>(
    a: &[P],
    b: &[Q],
    frame: &F,
    mut answer: X,
    mut f: impl FnMut(u32, u32),
) -> usize {
    let mut found = 0;
    for (j, q) in b.iter().enumerate() {
        let q = frame.place(q);
        for (i, p) in a.iter().enumerate() {
            if answer.accept(p, &q) {
                f(i as u32, j as u32);
                found += 1;
            }
        }
    }
    found
}

/// The first primitive a shape cast touches over all primitives (smallest
/// `t`, then smallest index): the reference for
/// [`Query::cast_shape`](crate::Query::cast_shape).
///
/// ```
/// use bvhkit::{brute_force, ShapeCast};
/// use glam::Vec3;
/// let pts = [Vec3::new(4.0, 0.0, 0.0), Vec3::new(2.0, 0.0, 0.0), Vec3::new(2.0, 3.0, 0.0)];
/// let ball = ShapeCast::sphere(Vec3::ZERO, 1.0, Vec3::X, 10.0)?;
/// let hit = brute_force::cast_closest(&pts, &ball).unwrap();
/// assert_eq!((hit.prim, hit.t), (1, 1.0));
/// # Ok::<(), bvhkit::Error>(())
/// ```
pub fn cast_closest<P: crate::CastTarget>(
    prims: &[P],
    cast: &crate::ShapeCast,
) -> Option<crate::Hit> {
    let mut best: Option<crate::Hit> = None;
    for (i, p) in prims.iter().enumerate() {
        if let Some(t) = p.cast_hit(cast) {
            if best.is_none_or(|b| t < b.t) {
                best = Some(crate::Hit { prim: i as u32, t });
            }
        }
    }
    best
}

/// The closest ray hit over all primitives (smallest `t`, then smallest index).
pub fn ray_closest<P: crate::RayTarget>(prims: &[P], ray: &crate::Ray) -> Option<crate::Hit> {
    let mut best: Option<crate::Hit> = None;
    for (i, p) in prims.iter().enumerate() {
        if let Some(t) = p.ray_hit(ray) {
            if best.is_none_or(|b| t < b.t) {
                best = Some(crate::Hit { prim: i as u32, t });
            }
        }
    }
    best
}

/// The nearest primitive to `point` (smallest squared distance, then smallest index).
pub fn nearest<P: crate::PointDistance>(prims: &[P], point: glam::Vec3) -> Option<crate::Nearest> {
    let mut best: Option<crate::Nearest> = None;
    for (i, p) in prims.iter().enumerate() {
        let d = p.distance_squared(point);
        if best.is_none_or(|b| d < b.distance_squared) {
            best = Some(crate::Nearest {
                prim: i as u32,
                distance_squared: d,
            });
        }
    }
    best
}

/// Every contact of a scene, without any hierarchy: all object pairs `a < b`,
/// all primitive pairs, object `b`'s primitives moved into `a`'s frame. The
/// reference for [`collide`](crate::collision::collide).
pub fn contacts<B, P>(
    objects: &[crate::collision::Object<'_, B, P>],
    mut f: impl FnMut(crate::collision::Contact),
) -> usize
where
    P: Primitive + crate::Intersects + crate::Transform,
{
    let mut found = 0;
    for (i, a) in objects.iter().enumerate() {
        for (j, b) in objects.iter().enumerate().skip(i + 1) {
            let relative = a.pose.inverse().after(&b.pose);
            found += pairs_placed(a.prims, b.prims, &relative, crate::Exact, |p, q| {
                f(crate::collision::Contact {
                    objects: (i as u32, j as u32),
                    prims: (p, q),
                })
            });
        }
    }
    found
}

/// The closest pair `(i, j)` of `a[i]` and `b[j]`, by
/// [`PairDistance`](super::PairDistance): the least squared distance, ties
/// going to the lowest `(i, j)`. `None` when either set is empty. The
/// reference for [`Distance::closest`](super::Distance::closest), which
/// finds the same distance (perhaps at another pair of equal distance).
///
/// ```
/// use bvhkit::brute_force;
/// use glam::Vec3;
/// let a = [Vec3::ZERO, Vec3::new(5.0, 0.0, 0.0)];
/// let b = [Vec3::new(9.0, 0.0, 0.0), Vec3::new(5.0, 2.0, 0.0)];
/// let c = brute_force::closest_pair(&a, &b).unwrap();
/// assert_eq!((c.a, c.b, c.distance()), (1, 1, 2.0));
/// ```
pub fn closest_pair<P: super::PairDistance<Q>, Q>(a: &[P], b: &[Q]) -> Option<super::Closest> {
    let mut best: Option<super::Closest> = None;
    for (i, p) in a.iter().enumerate() {
        for (j, q) in b.iter().enumerate() {
            let points = p.closest_points(q);
            if best.is_none_or(|c| points.distance_squared < c.points.distance_squared) {
                best = Some(super::Closest {
                    a: i as u32,
                    b: j as u32,
                    points,
                });
            }
        }
    }
    best
}

/// Every pair `(i, j)` with `a[i]` and `b[j]` at most `distance` apart (by
/// [`PairDistance`](super::PairDistance)); returns the count. The reference
/// for [`Distance::within`](super::Distance::within).
pub fn pairs_within<P: super::PairDistance<Q>, Q>(
    a: &[P],
    b: &[Q],
    distance: f64,
    mut f: impl FnMut(u32, u32),
) -> usize {
    let mut found = 0;
    for (i, p) in a.iter().enumerate() {
        for (j, q) in b.iter().enumerate() {
            if p.closest_points(q).distance_squared <= distance * distance {
                f(i as u32, j as u32);
                found += 1;
            }
        }
    }
    found
}
