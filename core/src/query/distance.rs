//! Distance between two trees: the closest pair of primitives, and every
//! pair within a distance.
//!
//! Both queries walk A and B together, like a pair query, but prune a node
//! pair by a *lower bound on the distance* between anything inside its two
//! volumes instead of by overlap: branch and bound. The closest-pair search
//! opens the nearer child pairs first, so the best distance found shrinks
//! early and prunes the rest. Distances are computed in `f64` by
//! [`PairDistance`]; a node pair is skipped only when its bound, lowered by
//! a margin far above `f64` rounding, exceeds the best distance (or the
//! radius), so the answers equal [`brute_force::closest_pair`] and
//! [`brute_force::pairs_within`](super::brute_force::pairs_within).

use super::nearest::closest_on_triangle;
use super::stack::Stack;
use super::{Frame, Place, Same, Tally};
use crate::bv::{Aabb, BoundingVolume};
use crate::narrow::triangles_intersect;
use crate::primitive::Triangle;
use crate::transform::Rigid;
use crate::tree::hierarchy::{check_query, DFS_STACK};
use crate::tree::{Content, Hierarchy, Kids};
use crate::Error;
#[cfg(feature = "sphere")]
use crate::Sphere;
use glam::{DVec3, Vec3};

#[cfg(doc)]
use super::brute_force;

/// The closest points of two primitives and their squared distance (`f64`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosestPoints {
    /// The point of the first primitive nearest to the second.
    pub on_a: DVec3,
    /// The point of the second primitive nearest to the first.
    pub on_b: DVec3,
    /// Squared distance between them: exactly `0.0` when the primitives
    /// touch (decided exactly for triangles), so "touching" never depends
    /// on rounding.
    pub distance_squared: f64,
}

impl ClosestPoints {
    fn between(on_a: DVec3, on_b: DVec3) -> Self {
        ClosestPoints {
            on_a,
            on_b,
            distance_squared: (on_a - on_b).length_squared(),
        }
    }

    /// The same points seen from the other primitive.
    pub fn swapped(self) -> Self {
        ClosestPoints {
            on_a: self.on_b,
            on_b: self.on_a,
            distance_squared: self.distance_squared,
        }
    }

    /// The distance (the square root of [`distance_squared`](Self::distance_squared)).
    pub fn distance(&self) -> f64 {
        libm::sqrt(self.distance_squared)
    }
}

/// Two primitives with a distance between them.
///
/// ```
/// use bvhkit::query::PairDistance;
/// use bvhkit::Triangle;
/// use glam::Vec3;
/// let floor = Triangle::new(Vec3::ZERO, Vec3::X * 4.0, Vec3::Y * 4.0);
/// let above = floor.translated(Vec3::new(1.0, 1.0, 2.0));
/// let c = floor.closest_points(&above);
/// assert_eq!(c.distance(), 2.0); // the faces are parallel, 2 apart
/// assert_eq!(floor.closest_points(&floor).distance_squared, 0.0);
/// ```
pub trait PairDistance<Q: ?Sized = Self> {
    /// The closest points of `self` and `other`.
    fn closest_points(&self, other: &Q) -> ClosestPoints;
}

impl<P: PairDistance<Q>, Q> PairDistance<Q> for &P {
    fn closest_points(&self, other: &Q) -> ClosestPoints {
        (**self).closest_points(other)
    }
}

impl PairDistance for Vec3 {
    fn closest_points(&self, other: &Vec3) -> ClosestPoints {
        ClosestPoints::between(self.as_dvec3(), other.as_dvec3())
    }
}

impl PairDistance<Triangle> for Vec3 {
    fn closest_points(&self, t: &Triangle) -> ClosestPoints {
        let p = self.as_dvec3();
        let [a, b, c] = t.v.map(|v| v.as_dvec3());
        ClosestPoints::between(p, closest_on_triangle(p, a, b, c))
    }
}

impl PairDistance<Vec3> for Triangle {
    fn closest_points(&self, p: &Vec3) -> ClosestPoints {
        p.closest_points(self).swapped()
    }
}

/// Three corners are a [`Triangle`].
impl PairDistance<[Vec3; 3]> for Vec3 {
    fn closest_points(&self, t: &[Vec3; 3]) -> ClosestPoints {
        self.closest_points(&Triangle::from(*t))
    }
}

/// Three corners are a [`Triangle`].
impl PairDistance for [Vec3; 3] {
    fn closest_points(&self, other: &[Vec3; 3]) -> ClosestPoints {
        Triangle::from(*self).closest_points(&Triangle::from(*other))
    }
}

impl PairDistance for Aabb {
    /// Per axis: the facing sides when the boxes are apart on it, the middle
    /// of the shared interval when they overlap on it.
    fn closest_points(&self, other: &Aabb) -> ClosestPoints {
        let (a0, a1) = (self.min.as_dvec3(), self.max.as_dvec3());
        let (b0, b1) = (other.min.as_dvec3(), other.max.as_dvec3());
        let (mut p, mut q) = (DVec3::ZERO, DVec3::ZERO);
        for k in 0..3 {
            (p[k], q[k]) = if a1[k] < b0[k] {
                (a1[k], b0[k])
            } else if b1[k] < a0[k] {
                (a0[k], b1[k])
            } else {
                let mid = 0.5 * (a0[k].max(b0[k]) + a1[k].min(b1[k]));
                (mid, mid)
            };
        }
        ClosestPoints::between(p, q)
    }
}

impl PairDistance<Vec3> for Aabb {
    fn closest_points(&self, p: &Vec3) -> ClosestPoints {
        let q = p.as_dvec3();
        let on = q.clamp(self.min.as_dvec3(), self.max.as_dvec3());
        ClosestPoints::between(on, q)
    }
}

impl PairDistance<Aabb> for Vec3 {
    fn closest_points(&self, b: &Aabb) -> ClosestPoints {
        b.closest_points(self).swapped()
    }
}

#[cfg(feature = "sphere")]
impl PairDistance for Sphere {
    /// Along the line of centres; zero (at the midpoint of the surfaces'
    /// nearest points) when the balls overlap.
    fn closest_points(&self, other: &Sphere) -> ClosestPoints {
        let (c1, c2) = (self.center.as_dvec3(), other.center.as_dvec3());
        let (r1, r2) = (self.radius as f64, other.radius as f64);
        let d = c2 - c1;
        let len = d.length();
        let dir = if len > 0.0 { d / len } else { DVec3::X };
        if len <= r1 + r2 {
            let mid = c1 + dir * (0.5 * (len + r1 - r2));
            return ClosestPoints {
                on_a: mid,
                on_b: mid,
                distance_squared: 0.0,
            };
        }
        ClosestPoints::between(c1 + dir * r1, c2 - dir * r2)
    }
}

impl PairDistance for Triangle {
    /// Disjoint triangles are closest at a vertex of one against the face of
    /// the other or at two edges: the least of those 15 candidates (Ericson,
    /// section 5.1.9 for two segments). Touching triangles (decided exactly,
    /// [`triangles_intersect`]) are at distance `0.0`, the points taken
    /// where an edge crosses the other triangle.
    fn closest_points(&self, other: &Triangle) -> ClosestPoints {
        let a = self.v.map(|v| v.as_dvec3());
        let b = other.v.map(|v| v.as_dvec3());
        let mut best = ClosestPoints::between(a[0], b[0]);
        let mut consider = |p: DVec3, q: DVec3| {
            let c = ClosestPoints::between(p, q);
            if c.distance_squared < best.distance_squared {
                best = c;
            }
        };
        for &p in &a {
            consider(p, closest_on_triangle(p, b[0], b[1], b[2]));
        }
        for &q in &b {
            consider(closest_on_triangle(q, a[0], a[1], a[2]), q);
        }
        for i in 0..3 {
            for j in 0..3 {
                let (p, q) = closest_on_segments(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]);
                consider(p, q);
            }
        }
        if triangles_intersect(self, other) {
            // An edge piercing the other face: its crossing point is a
            // common point, which none of the 15 candidates need be.
            for (s, t, flip) in [(&a, &b, false), (&b, &a, true)] {
                for i in 0..3 {
                    if let Some(x) = plane_crossing(s[i], s[(i + 1) % 3], t) {
                        let y = closest_on_triangle(x, t[0], t[1], t[2]);
                        if flip {
                            consider(y, x);
                        } else {
                            consider(x, y);
                        }
                    }
                }
            }
            best.distance_squared = 0.0;
        }
        best
    }
}

/// Where segment `p`-`q` crosses the plane of triangle `t`, when its ends are
/// strictly on opposite sides.
fn plane_crossing(p: DVec3, q: DVec3, t: &[DVec3; 3]) -> Option<DVec3> {
    let n = (t[1] - t[0]).cross(t[2] - t[0]);
    let (dp, dq) = (n.dot(p - t[0]), n.dot(q - t[0]));
    if (dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0) {
        Some(p + (q - p) * (dp / (dp - dq)))
    } else {
        None
    }
}

/// The closest points of segments `p1`-`q1` and `p2`-`q2` (Ericson 5.1.9),
/// points (zero-length segments) included.
fn closest_on_segments(p1: DVec3, q1: DVec3, p2: DVec3, q2: DVec3) -> (DVec3, DVec3) {
    let (d1, d2, r) = (q1 - p1, q2 - p2, p1 - p2);
    let (a, e, f) = (d1.length_squared(), d2.length_squared(), d2.dot(r));
    let (s, t) = if a == 0.0 && e == 0.0 {
        (0.0, 0.0)
    } else if a == 0.0 {
        (0.0, (f / e).clamp(0.0, 1.0))
    } else {
        let c = d1.dot(r);
        if e == 0.0 {
            ((-c / a).clamp(0.0, 1.0), 0.0)
        } else {
            let b = d1.dot(d2);
            let denom = a * e - b * b;
            let s = if denom > 0.0 {
                ((b * f - c * e) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let t = (b * s + f) / e;
            if t < 0.0 {
                ((-c / a).clamp(0.0, 1.0), 0.0)
            } else if t > 1.0 {
                (((b - c) / a).clamp(0.0, 1.0), 1.0)
            } else {
                (s, t)
            }
        }
    };
    (p1 + d1 * s, p2 + d2 * t)
}

/// The closest pair of primitives of two trees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Closest {
    /// Primitive index in A.
    pub a: u32,
    /// Primitive index in B.
    pub b: u32,
    /// The two points and their squared distance.
    pub points: ClosestPoints,
}

impl Closest {
    /// The distance between the two primitives.
    pub fn distance(&self) -> f64 {
        self.points.distance()
    }
}

/// A lower bound on the squared distance between anything inside boxes `a`
/// and `b`, lowered by a margin (1e-9 of the coordinates' size) that dwarfs
/// the `f64` rounding of the primitive distances.
fn lower_bound(a: &Aabb, b: &Aabb) -> f64 {
    let gap = (a.min.as_dvec3() - b.max.as_dvec3())
        .max(b.min.as_dvec3() - a.max.as_dvec3())
        .max(DVec3::ZERO);
    let scale = a
        .min
        .abs()
        .max(a.max.abs())
        .max(b.min.abs().max(b.max.abs()))
        .max_element() as f64;
    let d = libm::sqrt(gap.length_squared()) - 1e-9 * scale;
    if d > 0.0 {
        d * d
    } else {
        0.0
    }
}

/// Entries of the distance walk's stack: one-sided steps only, so a path
/// leaves at most `MAX_CHILDREN - 1` pairs per level of either tree.
const DISTANCE_STACK: usize = 2 * DFS_STACK;

/// A distance query between tree A over `pa` and tree B over `pb`: the
/// [closest pair](Self::closest) or every pair [within](Self::within) a
/// distance. The trees may differ in volume type and representation (any
/// [`Hierarchy`], the dynamic tree included); only their volumes' boxes
/// bound the distances.
///
/// ```
/// use bvhkit::query::Distance;
/// use bvhkit::{Aabb, Node, TopDown, Triangle};
/// use glam::Vec3;
/// let strip = |x: f32| -> Vec<Triangle> {
///     (0..20).map(|i| {
///         let o = Vec3::new(x, i as f32, 0.0);
///         Triangle::new(o, o + Vec3::X, o + Vec3::Y)
///     }).collect()
/// };
/// let (left, right) = (strip(0.0), strip(3.5));
/// let mut nodes = vec![Node::<Aabb>::EMPTY; 2 * bvhkit::max_nodes(20)];
/// let (na, nb) = nodes.split_at_mut(bvhkit::max_nodes(20));
/// let (mut ia, mut ib) = (vec![0; 20], vec![0; 20]);
/// let a = TopDown::default().build(&left, na, &mut ia)?;
/// let b = TopDown::default().build(&right, nb, &mut ib)?;
///
/// let closest = Distance::new(&a, &left, &b, &right).closest()?.unwrap();
/// assert!((closest.distance() - 2.5).abs() < 1e-6); // x = 1 against x = 3.5
/// let near = Distance::new(&a, &left, &b, &right).within(2.6, |_, _| {})?;
/// assert!(near >= 20);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Distance<'q, A, H, P, Q, F = Same, T = ()> {
    a: &'q A,
    pa: &'q [P],
    b: &'q H,
    pb: &'q [Q],
    frame: F,
    tally: T,
}

impl<'q, A: Hierarchy, H: Hierarchy, P, Q> Distance<'q, A, H, P, Q> {
    /// Tree A over `pa` against tree B over `pb`, both in one frame.
    pub fn new(a: &'q A, pa: &'q [P], b: &'q H, pb: &'q [Q]) -> Self {
        Distance {
            a,
            pa,
            b,
            pb,
            frame: Same,
            tally: (),
        }
    }
}

impl<'q, A, H, P, Q, F, T> Distance<'q, A, H, P, Q, F, T> {
    /// Counts `Nv` (box pairs bounded), `Np` (primitive pairs measured) and,
    /// in a moved frame, `Nu` (B's volumes moved).
    pub fn counted<T2: Tally>(self, tally: T2) -> Distance<'q, A, H, P, Q, F, T2> {
        Distance {
            a: self.a,
            pa: self.pa,
            b: self.b,
            pb: self.pb,
            frame: self.frame,
            tally,
        }
    }

    /// Measures B as if moved by `motion` (B's frame to A's), without
    /// rebuilding it: B's volumes are moved as they are reached (each
    /// containing the moved boxes of everything beneath it), and B's
    /// primitives are placed before they are measured. The answer equals
    /// brute force over B's primitives placed by the same motion.
    pub fn in_frame(self, motion: Rigid) -> Distance<'q, A, H, P, Q, Rigid, T> {
        self.in_frame_of(motion)
    }

    /// Places B by any [`Frame`] ([`Same`] or a [`Rigid`] motion).
    pub fn in_frame_of<F2>(self, frame: F2) -> Distance<'q, A, H, P, Q, F2, T> {
        Distance {
            a: self.a,
            pa: self.pa,
            b: self.b,
            pb: self.pb,
            frame,
            tally: self.tally,
        }
    }
}

impl<A, H, P, Q, F, T> Distance<'_, A, H, P, Q, F, T>
where
    A: Hierarchy,
    H: Hierarchy,
    P: PairDistance<Q>,
    F: Frame + Place<Q>,
    T: Tally,
{
    /// Primitive `i` of A against primitive `j` of B placed in A's frame.
    #[inline]
    fn measure(&self, i: u32, j: u32) -> ClosestPoints {
        let (p, q) = (&self.pa[i as usize], &self.pb[j as usize]);
        if F::MOVES {
            p.closest_points(&self.frame.place(q))
        } else {
            p.closest_points(q)
        }
    }

    /// B's node `n` as a box in A's frame.
    fn b_box(&mut self, n: u32) -> Aabb {
        let bv = self.b.bv(n);
        if F::MOVES {
            self.tally.updates(1);
            self.frame.bv_with_boxes(&bv).aabb()
        } else {
            bv.aabb()
        }
    }

    /// The closest pair of primitives (`None` when a tree is empty). The
    /// distance is the minimum over all pairs; which pair is reported when
    /// several share it depends on the walk. The search stops at the first
    /// touching pair (distance `0.0`).
    pub fn closest(mut self) -> Result<Option<Closest>, Error> {
        self.check()?;
        if self.a.is_empty() || self.b.is_empty() {
            return Ok(None);
        }
        let (a, b) = (self.a, self.b);
        let mut best: Option<Closest> = None;
        let mut stack = Stack::<(u32, u32), DISTANCE_STACK>::with(
            (a.root(), b.root()),
            a.depth().max(b.depth()),
        );
        while let Some((na, nb)) = stack.pop() {
            let (ba, bb) = (a.bv(na).aabb(), self.b_box(nb));
            self.tally.bv_tests(1);
            let limit = best.map_or(f64::INFINITY, |c| c.points.distance_squared);
            if lower_bound(&ba, &bb) >= limit {
                continue;
            }
            match (a.content(na), b.content(nb)) {
                (Content::Leaf(la), Content::Leaf(lb)) => {
                    self.tally.prim_tests((la.len() * lb.len()) as u32);
                    for &i in la {
                        for &j in lb {
                            let points = self.measure(i, j);
                            if best
                                .is_none_or(|c| points.distance_squared < c.points.distance_squared)
                            {
                                best = Some(Closest { a: i, b: j, points });
                            }
                        }
                    }
                    if best.is_some_and(|c| c.points.distance_squared == 0.0) {
                        break;
                    }
                }
                (ca, cb) => {
                    // Nearest child pair on top of the stack: pushed last.
                    let mut next = [(0.0f64, 0u32, 0u32); crate::tree::MAX_CHILDREN];
                    let mut len = 0;
                    match open(ca, cb, &ba, &bb) {
                        Some(Open::A(kids)) => {
                            for &c in kids.as_slice() {
                                next[len] = (lower_bound(&a.bv(c).aabb(), &bb), c, nb);
                                len += 1;
                            }
                        }
                        Some(Open::B(kids)) => {
                            for &c in kids.as_slice() {
                                next[len] = (lower_bound(&ba, &self.b_box(c)), na, c);
                                len += 1;
                            }
                        }
                        None => {} // two leaves: measured above
                    }
                    self.tally.bv_tests(len as u32);
                    let next = &mut next[..len];
                    next.sort_unstable_by(|x, y| y.0.total_cmp(&x.0));
                    for &(bound, ca, cb) in next.iter() {
                        if bound < limit {
                            stack.push((ca, cb))?;
                        }
                    }
                }
            }
        }
        Ok(best)
    }

    /// Calls `f(a, b)` for every pair of primitives at most `distance`
    /// apart (touching pairs included); returns how many there were. The
    /// distance must be finite and not negative.
    pub fn within(mut self, distance: f64, mut f: impl FnMut(u32, u32)) -> Result<usize, Error> {
        self.check()?;
        if !(distance.is_finite() && distance >= 0.0) {
            return Err(Error::InvalidQuery(
                "the distance must be finite and not negative",
            ));
        }
        if self.a.is_empty() || self.b.is_empty() {
            return Ok(0);
        }
        let radius = distance * distance;
        let (a, b) = (self.a, self.b);
        let mut found = 0;
        let mut stack = Stack::<(u32, u32), DISTANCE_STACK>::with(
            (a.root(), b.root()),
            a.depth().max(b.depth()),
        );
        while let Some((na, nb)) = stack.pop() {
            let (ba, bb) = (a.bv(na).aabb(), self.b_box(nb));
            self.tally.bv_tests(1);
            if lower_bound(&ba, &bb) > radius {
                continue;
            }
            match (a.content(na), b.content(nb)) {
                (Content::Leaf(la), Content::Leaf(lb)) => {
                    self.tally.prim_tests((la.len() * lb.len()) as u32);
                    for &i in la {
                        for &j in lb {
                            let d = self.measure(i, j);
                            if d.distance_squared <= radius {
                                f(i, j);
                                found += 1;
                            }
                        }
                    }
                }
                (ca, cb) => {
                    match open(ca, cb, &ba, &bb) {
                        Some(Open::A(kids)) => {
                            for &c in kids.as_slice().iter().rev() {
                                stack.push((c, nb))?;
                            }
                        }
                        Some(Open::B(kids)) => {
                            for &c in kids.as_slice().iter().rev() {
                                stack.push((na, c))?;
                            }
                        }
                        None => {} // two leaves: measured above
                    }
                }
            }
        }
        Ok(found)
    }

    fn check(&self) -> Result<(), Error> {
        check_query(self.a, self.pa.len())?;
        check_query(self.b, self.pb.len())
    }
}

/// The node of a pair a walk opens: A's or B's, with its children.
enum Open {
    A(Kids),
    B(Kids),
}

/// The descent rule of both walks: open the inner node, and of two inner
/// nodes the larger box (by surface area, A's on a tie), so the boxes
/// shrink evenly; two leaves open nothing.
fn open(ca: Content<'_>, cb: Content<'_>, ba: &Aabb, bb: &Aabb) -> Option<Open> {
    match (ca, cb) {
        (Content::Leaf(_), Content::Leaf(_)) => None,
        (Content::Inner(kids), Content::Leaf(_)) => Some(Open::A(kids)),
        (Content::Leaf(_), Content::Inner(kids)) => Some(Open::B(kids)),
        (Content::Inner(ka), Content::Inner(kb)) => Some(if ba.half_area() >= bb.half_area() {
            Open::A(ka)
        } else {
            Open::B(kb)
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> Triangle {
        Triangle::new(Vec3::from(a), Vec3::from(b), Vec3::from(c))
    }

    #[test]
    fn segments_closest_points_cover_parallel_crossing_and_degenerate_cases() {
        let x = |v: f64| DVec3::new(v, 0.0, 0.0);
        // Crossing at right angles, one above the other.
        let (p, q) = closest_on_segments(
            x(-1.0),
            x(1.0),
            DVec3::new(0.0, -1.0, 2.0),
            DVec3::new(0.0, 1.0, 2.0),
        );
        assert_eq!((p, q), (DVec3::ZERO, DVec3::new(0.0, 0.0, 2.0)));
        // Parallel, overlapping in x: distance is the offset.
        let (p, q) = closest_on_segments(
            x(0.0),
            x(2.0),
            DVec3::new(1.0, 3.0, 0.0),
            DVec3::new(5.0, 3.0, 0.0),
        );
        assert_eq!((p - q).length(), 3.0);
        // A point against a segment, and two points.
        let (p, q) = closest_on_segments(x(5.0), x(5.0), x(0.0), x(2.0));
        assert_eq!((p, q), (x(5.0), x(2.0)));
        let (p, q) = closest_on_segments(x(5.0), x(5.0), x(1.0), x(1.0));
        assert_eq!((p, q), (x(5.0), x(1.0)));
    }

    #[test]
    fn crossing_triangles_are_at_zero_with_a_common_point() {
        // A vertical triangle piercing a horizontal one through its interior:
        // no vertex or edge pair of the 15 candidates is at distance zero.
        let floor = tri([-5.0, -5.0, 0.0], [5.0, -5.0, 0.0], [0.0, 5.0, 0.0]);
        let post = tri([0.0, 0.0, -1.0], [0.3, 0.0, 3.0], [-0.3, 0.0, 3.0]);
        let c = floor.closest_points(&post);
        assert_eq!(c.distance_squared, 0.0);
        assert!((c.on_a - c.on_b).length() < 1e-12);
        // On the crossing segment: z = 0, y = 0, |x| <= 0.075.
        let p = c.on_a;
        assert!(
            p.z.abs() < 1e-12 && p.y.abs() < 1e-12 && p.x.abs() <= 0.0751,
            "{p}"
        );
        assert_eq!(post.closest_points(&floor).distance_squared, 0.0);
    }

    #[test]
    fn disjoint_triangles_take_the_least_candidate() {
        let floor = tri([0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [0.0, 4.0, 0.0]);
        // A vertex above the face.
        let spike = tri([1.0, 1.0, 0.5], [1.0, 1.0, 3.0], [2.0, 1.0, 3.0]);
        let c = floor.closest_points(&spike);
        assert!((c.distance() - 0.5).abs() < 1e-12);
        assert_eq!(c.on_a, DVec3::new(1.0, 1.0, 0.0));
        // Skew edges: the bar crosses over the hypotenuse 1 above it.
        let bar = tri([0.0, 0.0, 1.0], [4.0, 4.0, 1.0], [4.0, 4.0, 5.0]);
        let c = floor.closest_points(&bar);
        assert!((c.distance() - 1.0).abs() < 1e-12, "{c:?}");
        assert_eq!(c, bar.closest_points(&floor).swapped());
    }

    #[test]
    fn boxes_and_points() {
        let a = Aabb::new(Vec3::ZERO, Vec3::ONE);
        let b = Aabb::new(Vec3::new(3.0, 0.5, -2.0), Vec3::new(4.0, 2.0, -1.5));
        let c = a.closest_points(&b);
        assert_eq!(c.distance_squared, 4.0 + 2.25);
        assert_eq!(c.on_a, DVec3::new(1.0, 0.75, 0.0));
        assert_eq!(a.closest_points(&a).distance_squared, 0.0);
        assert_eq!(a.closest_points(&Vec3::new(0.5, 3.0, 0.5)).distance(), 2.0);
        let p = Vec3::new(0.25, 0.25, 1.0);
        assert_eq!(
            p.closest_points(&tri([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]))
                .distance(),
            1.0
        );
    }

    #[test]
    fn the_bound_never_exceeds_a_distance_far_from_the_origin() {
        let o = Vec3::splat(30_000.0);
        let a = Aabb::new(o, o + Vec3::ONE);
        let b = Aabb::new(o + Vec3::new(1.0 + 1e-3, 0.0, 0.0), o + Vec3::splat(2.0));
        let d = a.closest_points(&b).distance_squared;
        assert!(lower_bound(&a, &b) <= d && d > 0.0);
    }
}
