//! Nearest primitive to a point: the textbook case for best-first search.
//!
//! The answer is the primitive with the smallest squared distance (computed in
//! `f64` by [`PointDistance`]), ties going to the lowest index. A node is
//! skipped only when a lower bound on its distance, shrunk by a margin far
//! above `f64` rounding, exceeds the best distance so far.

use super::heap::{MinHeap, BEST_FIRST_QUEUE};
use super::stack::Stack;
use super::Tally;
use crate::bv::{Aabb, BoundingVolume};
use crate::primitive::Triangle;
use crate::tree::hierarchy::{check_query, DFS_STACK};
use crate::tree::{Bvh, Content, Hierarchy};
use crate::Error;
#[cfg(feature = "sphere")]
use crate::Sphere;
use glam::{DVec3, Vec3, Vec3A};

/// A primitive with a distance to a point.
pub trait PointDistance {
    /// Squared Euclidean distance from `p` to the closest point of the primitive.
    fn distance_squared(&self, p: Vec3) -> f64;
}

impl PointDistance for Vec3 {
    fn distance_squared(&self, p: Vec3) -> f64 {
        (self.as_dvec3() - p.as_dvec3()).length_squared()
    }
}

impl PointDistance for Aabb {
    fn distance_squared(&self, p: Vec3) -> f64 {
        box_distance_squared(self, p.as_dvec3())
    }
}

#[cfg(feature = "sphere")]
impl PointDistance for Sphere {
    fn distance_squared(&self, p: Vec3) -> f64 {
        let d = (self.center.as_dvec3() - p.as_dvec3()).length() - self.radius as f64;
        if d > 0.0 {
            d * d
        } else {
            0.0
        }
    }
}

impl PointDistance for Triangle {
    /// Closest point by Voronoi regions of the vertices, edges and face
    /// (Ericson, section 5.1.5), in `f64`; zero-area triangles included.
    fn distance_squared(&self, p: Vec3) -> f64 {
        let [a, b, c] = self.v.map(|v| v.as_dvec3());
        (closest_on_triangle(p.as_dvec3(), a, b, c) - p.as_dvec3()).length_squared()
    }
}

/// Three corners are a [`Triangle`].
impl PointDistance for [Vec3; 3] {
    fn distance_squared(&self, p: Vec3) -> f64 {
        Triangle::from(*self).distance_squared(p)
    }
}

impl<P: PointDistance> PointDistance for &P {
    fn distance_squared(&self, p: Vec3) -> f64 {
        (**self).distance_squared(p)
    }
}

fn box_distance_squared(b: &Aabb, p: DVec3) -> f64 {
    let d = (b.min.as_dvec3() - p)
        .max(p - b.max.as_dvec3())
        .max(DVec3::ZERO);
    d.length_squared()
}

/// Which part of a triangle a closest point lies on: the Voronoi region of
/// the query point. Vertices are numbered as in [`Triangle::v`]; edge `k`
/// joins vertex `k` and vertex `(k + 1) % 3` (edge 0 is `v[0]v[1]`, edge 1
/// `v[1]v[2]`, edge 2 `v[2]v[0]`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TriangleFeature {
    /// A corner: `v[k]` itself.
    Vertex(u8),
    /// Inside edge `k` (or at one of its ends, on the boundary of the
    /// vertex's region).
    Edge(u8),
    /// Inside the face.
    Face,
}

/// The point of a triangle closest to a query point
/// ([`Triangle::closest_point`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosestOnTriangle {
    /// The closest point, in `f64`.
    pub point: DVec3,
    /// Its barycentric coordinates `b`, with `point = b.x v[0] + b.y v[1] +
    /// b.z v[2]`: each in `[0, 1]`, summing to 1 up to rounding; exactly 1
    /// at a vertex and exactly 0 away from an edge's two ends.
    pub barycentric: DVec3,
    /// The vertex, edge or face the point lies on.
    pub feature: TriangleFeature,
    /// Squared distance from the query point, in `f64` (the value
    /// [`PointDistance::distance_squared`] gives).
    pub distance_squared: f64,
}

impl Triangle {
    /// The point of the triangle closest to `p`, with its barycentric
    /// coordinates, the feature (vertex, edge or face) it lies on and the
    /// squared distance. By the Voronoi regions of the vertices, edges and
    /// face (Ericson, *Real-Time Collision Detection*, section 5.1.5), in
    /// `f64`; a zero-area triangle (a segment or a point) answers with its
    /// nearest edge or vertex. The point is the one every distance query of
    /// the crate uses.
    ///
    /// ```
    /// use bvhkit::{Triangle, TriangleFeature};
    /// use bvhkit::glam::{DVec3, Vec3};
    /// let t = Triangle::new(Vec3::ZERO, Vec3::X * 2.0, Vec3::Y * 2.0);
    /// // Above the face: straight down onto it.
    /// let c = t.closest_point(Vec3::new(0.5, 0.5, 3.0));
    /// assert_eq!(c.point, DVec3::new(0.5, 0.5, 0.0));
    /// assert_eq!((c.feature, c.distance_squared), (TriangleFeature::Face, 9.0));
    /// assert_eq!(c.barycentric, DVec3::new(0.5, 0.25, 0.25));
    /// // Beyond the corner v[1]: the corner itself.
    /// let c = t.closest_point(Vec3::new(5.0, -1.0, 0.0));
    /// assert_eq!((c.point, c.feature), (DVec3::new(2.0, 0.0, 0.0), TriangleFeature::Vertex(1)));
    /// // Below the edge v[0]v[1]: a point inside it.
    /// let c = t.closest_point(Vec3::new(1.5, -4.0, 0.0));
    /// assert_eq!((c.point, c.feature), (DVec3::new(1.5, 0.0, 0.0), TriangleFeature::Edge(0)));
    /// ```
    pub fn closest_point(&self, p: Vec3) -> ClosestOnTriangle {
        let [a, b, c] = self.v.map(|v| v.as_dvec3());
        let p = p.as_dvec3();
        let (point, barycentric, feature) = closest_with_feature(p, a, b, c);
        ClosestOnTriangle {
            point,
            barycentric,
            feature,
            distance_squared: (point - p).length_squared(),
        }
    }
}

#[inline]
pub(super) fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    closest_with_feature(p, a, b, c).0
}

/// The closest point of triangle `abc` to `p`, its barycentric coordinates
/// and its feature.
#[inline(always)]
fn closest_with_feature(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> (DVec3, DVec3, TriangleFeature) {
    use TriangleFeature::{Edge, Face, Vertex};
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, DVec3::X, Vertex(0));
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return (b, DVec3::Y, Vertex(1));
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0 {
        let t = d1 / (d1 - d3);
        return (a + ab * t, DVec3::new(1.0 - t, t, 0.0), Edge(0));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return (c, DVec3::Z, Vertex(2));
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0 {
        let t = d2 / (d2 - d6);
        return (a + ac * t, DVec3::new(1.0 - t, 0.0, t), Edge(2));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0 {
        let t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (b + (c - b) * t, DVec3::new(0.0, 1.0 - t, t), Edge(1));
    }
    let sum = va + vb + vc;
    if sum > 0.0 {
        let (v, w) = (vb / sum, vc / sum);
        return (a + ab * v + ac * w, DVec3::new(1.0 - v - w, v, w), Face);
    }
    // Zero-area triangle whose regions did not settle: the nearest of its
    // three edges (segments), edge k from corner k to corner k + 1.
    let corners = [a, b, c];
    let seg = |k: usize| {
        let (s, e) = (corners[k], corners[(k + 1) % 3]);
        let d = e - s;
        let len = d.length_squared();
        let t = if len > 0.0 {
            ((p - s).dot(d) / len).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let mut bary = DVec3::ZERO;
        bary[k] = 1.0 - t;
        bary[(k + 1) % 3] = t;
        let feature = if t == 0.0 {
            Vertex(k as u8)
        } else if t == 1.0 {
            Vertex(((k + 1) % 3) as u8)
        } else {
            Edge(k as u8)
        };
        (s + d * t, bary, feature)
    };
    let mut best = seg(0);
    for q in [seg(1), seg(2)] {
        if (q.0 - p).length_squared() < (best.0 - p).length_squared() {
            best = q;
        }
    }
    best
}

/// The nearest primitive and its squared distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nearest {
    /// Primitive index.
    pub prim: u32,
    /// Squared distance (`f64`).
    pub distance_squared: f64,
}

impl Nearest {
    fn before(&self, other: &Option<Nearest>) -> bool {
        match other {
            None => true,
            Some(o) => {
                self.distance_squared < o.distance_squared
                    || (self.distance_squared == o.distance_squared && self.prim < o.prim)
            }
        }
    }
}

/// A query point, for lower bounds on the squared distance from it to
/// anything inside a box, lowered by a margin (about 1e-9 of the
/// coordinates' size, `m`) that
/// dwarfs the `f64` rounding of the primitive distances, so no true
/// candidate is skipped.
///
/// With `x` the box's distance, the margin's bound `(x - m)^2` would need a
/// square root (the slowest step of a nearest search: this runs for every
/// child visited); `x^2 (1 - e) - m^2 / e` is below it for any `e > 0`
/// (since `2 m x <= e x^2 + m^2 / e`) and needs none. With `e = 2^-20` it
/// prunes as `(x - m)^2` does but for a millionth of the distance and
/// `1.05e-12` of the size squared.
///
/// The box's squared distance is computed in `f32` (4 lanes): its rounding
/// (under `5 * 2^-24` of it: two differences, three products, two sums) is
/// covered by taking `2^-19` off instead of `e`. Outside `f32`'s range
/// (a sum that overflows, or squares that may have underflowed), in `f64`.
///
/// The margin depends on the size of the coordinates only, so a search
/// takes it once, from the root's box (every box inside is no larger, so
/// the margin is no smaller).
#[derive(Clone, Copy)]
struct Probe {
    point: Vec3,
    p: DVec3,
    p32: Vec3A,
    /// `m^2 / e`, the part of the bound that depends on sizes only.
    cut: f64,
}

impl Probe {
    const E: f64 = 1.0 / (1u64 << 20) as f64;

    #[inline]
    fn new(p: DVec3, within: &Aabb) -> Probe {
        let p32 = Vec3A::from(p.as_vec3());
        let size = Vec3A::from(within.min)
            .abs()
            .max(Vec3A::from(within.max).abs());
        let m = 1e-9 * (f64::from(p32.abs().max_element()) + f64::from(size.max_element()));
        Probe {
            point: p.as_vec3(),
            p,
            p32,
            cut: m * m * (1.0 / Self::E),
        }
    }

    /// The bound for box `b` (inside the box the probe was made for).
    #[inline]
    fn bound(&self, b: &Aabb) -> f64 {
        let (lo, hi) = (Vec3A::from(b.min), Vec3A::from(b.max));
        let g = (lo - self.p32).max(self.p32 - hi).max(Vec3A::ZERO);
        let d2_32 = g.dot(g);
        let d2 = if (1e-30..=f32::MAX).contains(&d2_32) {
            f64::from(d2_32) * (1.0 - 2.0 * Self::E)
        } else if g == Vec3A::ZERO {
            0.0 // inside: a difference rounds to zero only when it is zero
        } else {
            box_distance_squared(b, self.p) * (1.0 - Self::E)
        };
        (d2 - self.cut).max(0.0)
    }

    /// The squared gap from the point to `b` in `f32` (rounded: see
    /// [`may_beat`](Self::may_beat)).
    #[cfg(feature = "alloc")] // only the nearer-first search (`Mesh`) prunes in `f32`
    #[inline]
    fn gap2(&self, b: &Aabb) -> f32 {
        let (lo, hi) = (Vec3A::from(b.min), Vec3A::from(b.max));
        let g = (lo - self.p32).max(self.p32 - hi).max(Vec3A::ZERO);
        g.dot(g)
    }

    /// The `f32` threshold for a best squared distance `best`: a box whose
    /// [`gap2`](Self::gap2) is past it (in the range where
    /// [`bound`](Self::bound) trusts `f32`) has `bound > best`. `bound` is
    /// `d2 (1 - 2E) - cut` there, so the threshold is `(best + cut) / (1 -
    /// 2E)`, nudged up and rounded up to `f32`: a gap at or under it is
    /// only visited, never wrongly pruned.
    #[cfg(feature = "alloc")] // only the nearer-first search (`Mesh`) prunes in `f32`
    fn limit(&self, best: f64) -> f32 {
        let t = (best + self.cut) / (1.0 - 2.0 * Self::E) * (1.0 + 1e-9);
        if t.is_nan() || t >= f64::from(f32::MAX) {
            return f32::INFINITY;
        }
        let t32 = t as f32;
        if f64::from(t32) < t {
            f32::from_bits(t32.to_bits() + 1) // t > 0: the next f32 up
        } else {
            t32
        }
    }

    /// Whether the box with squared gap `d2` (from [`gap2`](Self::gap2);
    /// `b` makes the box again) may hold something no farther than `best`,
    /// the squared distance whose [`limit`](Self::limit) is `limit`: `d2`
    /// at or under the limit, or [`bound`](Self::bound) at most `best`
    /// where `d2` is out of the range `bound` trusts.
    #[cfg(feature = "alloc")] // only the nearer-first search (`Mesh`) prunes in `f32`
    #[inline]
    fn may_beat(&self, d2: f32, limit: f32, best: f64, b: impl FnOnce() -> Aabb) -> bool {
        if d2 <= limit {
            return true;
        }
        if (1e-30..=f32::MAX).contains(&d2) {
            return false;
        }
        self.bound(&b()) <= best
    }
}

impl<B: BoundingVolume> Bvh<'_, B> {
    /// The primitive nearest to `point`, best-first: the node with the
    /// smallest distance bound is opened next, and the search stops once that
    /// bound exceeds the best distance found. The queue holds
    /// [`BEST_FIRST_QUEUE`] nodes; overflow is searched depth-first, so the
    /// answer never depends on the queue size. Equals
    /// [`brute_force::nearest`](crate::brute_force::nearest).
    ///
    /// ```
    /// use bvhkit::{Node, Sphere, TopDown};
    /// use glam::Vec3;
    /// let pts: Vec<Vec3> = (0..100).map(|i| Vec3::new((i % 10) as f32, (i / 10) as f32, 0.0)).collect();
    /// let mut nodes = vec![Node::<Sphere>::EMPTY; bvhkit::max_nodes(100)];
    /// let mut idx = vec![0; 100];
    /// let bvh = TopDown::default().build(&pts, &mut nodes, &mut idx)?;
    /// let near = bvh.nearest(&pts, Vec3::new(3.2, 4.9, 1.0), ())?.unwrap();
    /// assert_eq!(near.prim, 53);
    /// assert!((near.distance_squared - (0.04 + 0.01 + 1.0)).abs() < 1e-5);
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn nearest<P: PointDistance>(
        &self,
        prims: &[P],
        point: Vec3,
        tally: impl Tally,
    ) -> Result<Option<Nearest>, Error> {
        nearest(self, prims, point, tally)
    }
}

/// Best-first nearest primitive on any [`Hierarchy`] (see [`Bvh::nearest`]).
pub(crate) fn nearest<H: Hierarchy + ?Sized, P: PointDistance>(
    h: &H,
    prims: &[P],
    point: Vec3,
    mut tally: impl Tally,
) -> Result<Option<Nearest>, Error> {
    if !can_search(h, prims.len(), point)? {
        return Ok(None);
    }
    let probe = Probe::new(point.as_dvec3(), &h.bv(h.root()).aabb());
    let mut best: Option<Nearest> = None;
    let mut heap = MinHeap::<BEST_FIRST_QUEUE>::new();
    tally.bv_tests(1);
    heap.push(probe.bound(&h.bv(h.root()).aabb()), h.root());
    while let Some((bound, n)) = heap.pop() {
        if best.is_some_and(|b| bound > b.distance_squared) {
            break;
        }
        match h.content(n) {
            Content::Leaf(here) => {
                nearest_in_leaf(h, n, here, prims, &probe, &mut best, &mut tally)
            }
            Content::Inner(kids) => {
                tally.bv_tests(kids.as_slice().len() as u32);
                for &c in kids.as_slice() {
                    let bc = probe.bound(&h.bv(c).aabb());
                    if best.is_some_and(|b| bc > b.distance_squared) {
                        continue;
                    }
                    if !heap.push(bc, c) {
                        nearest_depth_first(h, prims, &probe, c, &mut best, &mut tally)?;
                    }
                }
            }
        }
    }
    Ok(best)
}

/// The nearest primitive by a depth-first walk that opens the nearer child
/// first and carries each node's bound on the stack: the same answer as
/// the best-first [`nearest`] (the same candidates, the same tie rule),
/// without a priority queue to keep in order. Cheaper per node where the
/// tree is small against the queue's bookkeeping; what [`Mesh`] uses.
///
/// [`Mesh`]: crate::Mesh
#[cfg(feature = "alloc")]
pub(crate) fn nearest_nearer_first<H: Hierarchy + ?Sized, P: PointDistance>(
    h: &H,
    prims: &[P],
    point: Vec3,
) -> Result<Option<Nearest>, Error> {
    if !can_search(h, prims.len(), point)? {
        return Ok(None);
    }
    let root = h.root();
    let probe = Probe::new(point.as_dvec3(), &h.bv(root).aabb());
    let mut best: Option<Nearest> = None;
    // Nodes are ordered and pruned on their `f32` squared gaps against a
    // limit made from the best distance (see `Probe::limit`); `f64` only
    // for the rare gap out of `f32`'s comfortable range and at the leaves.
    let mut limit = f32::INFINITY;
    let first = (probe.gap2(&h.bv(root).aabb()), root);
    let mut stack = Stack::<(f32, u32), DFS_STACK>::with(first, h.depth());
    let may_beat = |best: &Option<Nearest>, limit: f32, d2: f32, n: u32| match best {
        None => true,
        Some(b) => probe.may_beat(d2, limit, b.distance_squared, || h.bv(n).aabb()),
    };
    // The node to open next: the nearer child goes straight here, not
    // through the stack (one push and pop fewer a level).
    let mut next = None;
    while let Some((d2, n)) = next.take().or_else(|| stack.pop()) {
        if !may_beat(&best, limit, d2, n) {
            continue;
        }
        match h.content(n) {
            Content::Leaf(here) => {
                let before = best.map(|b| b.distance_squared);
                nearest_in_leaf(h, n, here, prims, &probe, &mut best, &mut ());
                let after = best.map(|b| b.distance_squared);
                if after != before {
                    limit = after.map_or(f32::INFINITY, |b| probe.limit(b));
                }
            }
            Content::Inner(kids) => {
                let kids = kids.as_slice();
                let mut order = [(0.0f32, 0u32); crate::tree::hierarchy::MAX_CHILDREN];
                for (slot, &c) in order.iter_mut().zip(kids) {
                    *slot = (probe.gap2(&h.bv(c).aabb()), c);
                }
                let order = &mut order[..kids.len()];
                // Farthest first, so the nearest is opened next (two
                // children, a binary tree's, by one comparison).
                if let [a, b] = order {
                    if a.0 < b.0 {
                        core::mem::swap(a, b);
                    }
                } else {
                    order.sort_unstable_by(|a, b| b.0.total_cmp(&a.0));
                }
                if let Some((&nearest, farther)) = order.split_last() {
                    for &(dc, c) in farther {
                        if may_beat(&best, limit, dc, c) {
                            stack.push((dc, c))?;
                        }
                    }
                    next = Some(nearest);
                }
            }
        }
    }
    Ok(best)
}

/// The checks every nearest search makes first; `Ok(false)` for an empty
/// tree (nothing is nearest).
fn can_search<H: Hierarchy + ?Sized>(h: &H, prims: usize, point: Vec3) -> Result<bool, Error> {
    check_query(h, prims)?;
    if !point.is_finite() {
        return Err(Error::InvalidQuery("the query point must be finite"));
    }
    Ok(!h.is_empty())
}

/// Leaf `n`'s primitives (`here`) against the best so far. With the tree's
/// kept bounds for the leaf, a primitive whose box is already farther than
/// the best is passed over without its exact distance (a box holds its
/// primitive, so the primitive is no nearer).
fn nearest_in_leaf<H: Hierarchy + ?Sized, P: PointDistance>(
    h: &H,
    n: u32,
    here: &[u32],
    prims: &[P],
    probe: &Probe,
    best: &mut Option<Nearest>,
    tally: &mut impl Tally,
) {
    let kept = h.leaf_bounds(n).filter(|b| b.len() == here.len());
    tally.prim_tests(here.len() as u32);
    let point = probe.point;
    for (k, &i) in here.iter().enumerate() {
        if let (Some(b), Some(kept)) = (*best, kept) {
            if probe.bound(&kept[k]) > b.distance_squared {
                continue;
            }
        }
        let cand = Nearest {
            prim: i,
            distance_squared: prims[i as usize].distance_squared(point),
        };
        if cand.before(best) {
            *best = Some(cand);
        }
    }
}

/// Depth-first nearest search below `root` (the best-first queue's overflow).
fn nearest_depth_first<H: Hierarchy + ?Sized, P: PointDistance>(
    h: &H,
    prims: &[P],
    probe: &Probe,
    root: u32,
    best: &mut Option<Nearest>,
    tally: &mut impl Tally,
) -> Result<(), Error> {
    let mut stack = Stack::<u32, DFS_STACK>::with(root, h.depth());
    while let Some(n) = stack.pop() {
        tally.bv_tests(1);
        if best.is_some_and(|b| probe.bound(&h.bv(n).aabb()) > b.distance_squared) {
            continue;
        }
        match h.content(n) {
            Content::Leaf(here) => nearest_in_leaf(h, n, here, prims, probe, best, tally),
            Content::Inner(kids) => {
                for &c in kids.as_slice().iter().rev() {
                    stack.push(c)?;
                }
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The `f32` pruning of the nearer-first search never drops a box that
    /// the `f64` bound keeps (`bound(b) <= best`), at every magnitude,
    /// with the best just under, at and over the box's bound, and with
    /// squared gaps that leave `f32`'s range (under 1e-30, over its
    /// largest value); and it does prune a box well past the best.
    #[cfg(feature = "alloc")]
    #[test]
    fn the_f32_limit_prunes_only_what_the_f64_bound_prunes() {
        let mut pruned = 0;
        for k in -24..=30 {
            let scale = 10f32.powi(k);
            for (x, y) in [(1.0, 0.0), (1.0, 1.0), (0.3, 2.0), (0.0, 0.0)] {
                let p = Vec3::new(-1.0, 0.5, 0.25) * scale;
                let b = Aabb::new(
                    Vec3::new(x, y, 0.0) * scale,
                    Vec3::new(x + 1.0, y + 1.0, 1.0) * scale,
                );
                let within = b.union(&Aabb::new(p, p));
                let probe = Probe::new(p.as_dvec3(), &within);
                let bound = probe.bound(&b);
                let d2 = probe.gap2(&b);
                for best in [
                    bound * 0.5,
                    bound * (1.0 - 1e-12),
                    bound,
                    bound * (1.0 + 1e-12),
                    bound * 2.0,
                    0.0,
                ] {
                    let keep = probe.may_beat(d2, probe.limit(best), best, || b);
                    assert!(
                        keep || bound > best,
                        "10^{k} ({x}, {y}): dropped at best {best}, bound {bound}"
                    );
                    pruned += usize::from(!keep);
                }
            }
        }
        assert!(pruned > 100, "{pruned} pruned");
    }

    /// The depth-first, nearer-child-first search (what `Mesh` runs) finds
    /// what brute force finds, for points inside, near and far from a
    /// sheet of triangles, on trees of one and of four triangles a leaf.
    #[cfg(feature = "alloc")]
    #[test]
    fn nearer_first_search_equals_brute_force() {
        use crate::tree::Node;
        use crate::TopDown;
        let mut tris = [Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y); 48];
        for (i, t) in tris.iter_mut().enumerate() {
            let o = Vec3::new((i % 8) as f32, (i / 8) as f32, ((i * 5) % 3) as f32 * 0.3);
            *t = Triangle::new(
                o,
                o + Vec3::new(0.9, 0.1, 0.0),
                o + Vec3::new(0.2, 0.8, 0.4),
            );
        }
        for leaf in [1, 4] {
            let mut nodes = [Node::<Aabb>::EMPTY; 95];
            let mut idx = [0u32; 48];
            let tree = TopDown::default()
                .with_max_leaf_size(leaf)
                .build(&tris, &mut nodes, &mut idx)
                .unwrap();
            for k in 0..200 {
                let f = k as f32;
                let p = Vec3::new(
                    (f * 0.37) % 12.0 - 2.0,
                    (f * 0.61) % 9.0 - 1.5,
                    (f * 0.23) % 6.0 - 3.0,
                ) * [1.0, 1.0, 40.0][k % 3];
                let got = nearest_nearer_first(&tree, &tris, p).unwrap();
                assert_eq!(
                    got,
                    crate::brute_force::nearest(&tris, p),
                    "{p:?}, leaves of {leaf}"
                );
            }
        }
    }

    /// The square-root-free, `f32` bound never exceeds the bound it replaced,
    /// `(sqrt(d2) - m)^2` in `f64` (which the searches' brute-force tests
    /// check), for boxes and points from 1e-30 to 1e30 (beyond `f32`'s
    /// squares), points inside, on a face and far away; and it prunes
    /// nearly as well (within a few millionths of the distance squared).
    #[test]
    fn the_fast_bound_stays_under_the_square_root_bound() {
        let mut next = crate::test_floats(0x9e37_79b9_7f4a_7c15);
        for round in 0..100_000 {
            let scale = [1.0f32, 1e-30, 1e-3, 1e5, 1e19, 1e30][round % 6];
            let (x, y) = (
                Vec3::new(next(), next(), next()) * scale,
                Vec3::new(next(), next(), next()) * scale,
            );
            let b = Aabb::new(x.min(y), x.max(y));
            let mut p = Vec3::new(next(), next(), next()) * scale * [1.0, 3.0, 1000.0][round % 3];
            if round % 5 == 0 {
                p[round % 3] = b.max[round % 3]; // on a face's plane
            }
            let pd = p.as_dvec3();
            let d2 = box_distance_squared(&b, pd);
            let scale = pd.abs().max_element() + b.min.abs().max(b.max.abs()).max_element() as f64;
            let d = libm::sqrt(d2) - 1e-9 * scale;
            let old = if d > 0.0 { d * d } else { 0.0 };
            let new = Probe::new(pd, &b).bound(&b);
            assert!(new <= old, "{b:?} {p:?}: {new} > {old}");
            assert!(
                new >= old * (1.0 - 4e-6) - 4e-12 * scale * scale,
                "{b:?} {p:?}: {new} prunes much less than {old}"
            );
        }
    }
}
