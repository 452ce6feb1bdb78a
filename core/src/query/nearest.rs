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
use glam::{DVec3, Vec3};

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

pub(super) fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let sum = va + vb + vc;
    if sum > 0.0 {
        return a + ab * (vb / sum) + ac * (vc / sum);
    }
    // Zero-area triangle whose regions did not settle: the nearest of its
    // three edges (segments).
    let seg = |s: DVec3, e: DVec3| {
        let d = e - s;
        let len = d.length_squared();
        let t = if len > 0.0 {
            ((p - s).dot(d) / len).clamp(0.0, 1.0)
        } else {
            0.0
        };
        s + d * t
    };
    let mut best = seg(a, b);
    for q in [seg(b, c), seg(c, a)] {
        if (q - p).length_squared() < (best - p).length_squared() {
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

/// A lower bound on the squared distance from `p` to anything inside `bv`,
/// lowered by a margin (1e-9 of the coordinates' size) that dwarfs the `f64`
/// rounding of the primitive distances, so no true candidate is skipped.
fn lower_bound<B: BoundingVolume>(bv: &B, p: DVec3) -> f64 {
    let b = bv.aabb();
    let d = libm::sqrt(box_distance_squared(&b, p));
    let scale = p.abs().max_element() + b.min.abs().max(b.max.abs()).max_element() as f64;
    let d = d - 1e-9 * scale;
    if d > 0.0 {
        d * d
    } else {
        0.0
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
    check_query(h, prims.len())?;
    if !point.is_finite() {
        return Err(Error::InvalidQuery("the query point must be finite"));
    }
    if h.is_empty() {
        return Ok(None);
    }
    let p = point.as_dvec3();
    let mut best: Option<Nearest> = None;
    let mut heap = MinHeap::<BEST_FIRST_QUEUE>::new();
    tally.bv_tests(1);
    heap.push(lower_bound(&h.bv(h.root()), p), h.root());
    while let Some((bound, n)) = heap.pop() {
        if best.is_some_and(|b| bound > b.distance_squared) {
            break;
        }
        match h.content(n) {
            Content::Leaf(here) => nearest_in_leaf(prims, point, here, &mut best, &mut tally),
            Content::Inner(kids) => {
                tally.bv_tests(kids.as_slice().len() as u32);
                for &c in kids.as_slice() {
                    let bc = lower_bound(&h.bv(c), p);
                    if best.is_some_and(|b| bc > b.distance_squared) {
                        continue;
                    }
                    if !heap.push(bc, c) {
                        nearest_depth_first(h, prims, point, c, &mut best, &mut tally)?;
                    }
                }
            }
        }
    }
    Ok(best)
}

fn nearest_in_leaf<P: PointDistance>(
    prims: &[P],
    point: Vec3,
    here: &[u32],
    best: &mut Option<Nearest>,
    tally: &mut impl Tally,
) {
    tally.prim_tests(here.len() as u32);
    for &i in here {
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
    point: Vec3,
    root: u32,
    best: &mut Option<Nearest>,
    tally: &mut impl Tally,
) -> Result<(), Error> {
    let p = point.as_dvec3();
    let mut stack = Stack::<u32, DFS_STACK>::with(root, h.depth());
    while let Some(n) = stack.pop() {
        tally.bv_tests(1);
        if best.is_some_and(|b| lower_bound(&h.bv(n), p) > b.distance_squared) {
            continue;
        }
        match h.content(n) {
            Content::Leaf(here) => nearest_in_leaf(prims, point, here, best, tally),
            Content::Inner(kids) => {
                for &c in kids.as_slice().iter().rev() {
                    stack.push(c)?;
                }
            }
        }
    }
    Ok(())
}
