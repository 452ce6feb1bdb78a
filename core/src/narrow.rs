//! Narrow phase: exact tests between two primitives.
//!
//! Lecture: *collision detection system*. The hierarchy only finds primitive
//! pairs whose bounds overlap (the candidates); the narrow phase decides which
//! candidates really touch. Triangles are decided **exactly** for `f32` input:
//! every branch depends only on the sign of an orientation determinant, and
//! those signs come from Shewchuk's adaptive predicates (the `robust` crate),
//! which are exact. Touching counts as intersecting: a shared vertex, a shared
//! edge, or a vertex resting on a face all report `true`.
//!
//! | pair | method | exact? |
//! |---|---|---|
//! | triangle–triangle | Guigue–Devillers; coplanar pairs in 2-D; zero-area triangles as segments or points | yes |
//! | box–box | interval comparisons | yes |
//! | box–triangle | 13 separating axes, each decided by exact orientation signs | yes |
//! | sphere–sphere | squared distance in `f64` | to `f64` rounding |
//!
//! [`triangle_contact`] goes one step further: *where* two triangles meet
//! (the segment of two crossing triangles, the polygon two coplanar ones
//! share), decided exactly and placed in `f64`. For solids (boxes, spheres),
//! [`Penetrate`] gives the contact a solver pushes apart: a point, a normal
//! and a depth.

mod contact;
mod penetration;

pub use contact::{triangle_contact, Contact};
pub use penetration::{Penetrate, Penetration};

use crate::bv::Aabb;
#[cfg(feature = "sphere")]
use crate::bv::Sphere;
use crate::primitive::Triangle;
use glam::{Vec3, Vec3A};
use robust::{orient2d, orient3d, Coord, Coord3D};

/// Whether two primitives touch. Implemented where the test can be exact.
///
/// ```
/// use bvhkit::{Intersects, Triangle};
/// use glam::Vec3;
/// let floor = Triangle::new(Vec3::ZERO, Vec3::new(4.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 4.0));
/// let post = Triangle::new(Vec3::new(1.0, -1.0, 1.0), Vec3::new(1.0, 1.0, 1.0), Vec3::new(1.5, 1.0, 1.0));
/// let resting = Triangle::new(Vec3::new(1.0, 0.0, 1.0), Vec3::new(1.0, 2.0, 1.0), Vec3::new(2.0, 2.0, 1.0));
/// assert!(floor.intersects(&post));
/// assert!(floor.intersects(&resting)); // touching at one vertex counts
/// assert!(!floor.intersects(&resting.translated(Vec3::Y * 1e-6)));
/// ```
pub trait Intersects<Q: ?Sized = Self> {
    /// `true` when the two closed sets share at least one point.
    fn intersects(&self, other: &Q) -> bool;
}

impl Intersects for Triangle {
    #[inline]
    fn intersects(&self, other: &Triangle) -> bool {
        triangles_intersect(self, other)
    }
}

impl Intersects for Aabb {
    #[inline]
    fn intersects(&self, other: &Aabb) -> bool {
        self.overlaps(other)
    }
}

#[cfg(feature = "sphere")]
impl Intersects for Sphere {
    fn intersects(&self, other: &Sphere) -> bool {
        let d = self.center.as_dvec3() - other.center.as_dvec3();
        let r = self.radius as f64 + other.radius as f64;
        d.length_squared() <= r * r
    }
}

impl<P: Intersects<Q>, Q> Intersects<Q> for &P {
    #[inline]
    fn intersects(&self, other: &Q) -> bool {
        (**self).intersects(other)
    }
}

/// A box and a triangle: exact ([`box_triangle_intersect`]).
impl Intersects<Triangle> for Aabb {
    #[inline]
    fn intersects(&self, other: &Triangle) -> bool {
        box_triangle_intersect(self, other)
    }
}

/// Three corners are a [`Triangle`]: the same exact test.
impl Intersects for [Vec3; 3] {
    #[inline]
    fn intersects(&self, other: &[Vec3; 3]) -> bool {
        triangles_intersect(&Triangle::from(*self), &Triangle::from(*other))
    }
}

/// Three corners and a box: the triangle's exact test.
impl Intersects<Aabb> for [Vec3; 3] {
    #[inline]
    fn intersects(&self, other: &Aabb) -> bool {
        box_triangle_intersect(other, &Triangle::from(*self))
    }
}

/// A triangle and a box: exact ([`box_triangle_intersect`]).
impl Intersects<Aabb> for Triangle {
    #[inline]
    fn intersects(&self, other: &Aabb) -> bool {
        box_triangle_intersect(other, self)
    }
}

/// Exact box–triangle intersection (closed sets, touching counts) by
/// separating axes: the two convex sets are disjoint exactly when their
/// projections onto one of 13 axes are, namely the box's three face
/// normals, the triangle's normal, and the nine cross products of a
/// triangle edge with a box axis. Each axis test is decided by exact signs,
/// never by a rounded projection:
///
/// - a box axis: the triangle's extent on that coordinate against the box's
///   (plain comparisons);
/// - the triangle's normal: the box's eight corners all strictly on one side
///   of the triangle's plane ([`orient3`]);
/// - edge `e` × axis `k`: projected along `k`, the box is a rectangle and the
///   triangle a triangle in the plane, and that axis separates them exactly
///   when the rectangle's four corners lie strictly on the far side of the
///   projected edge's line from the third vertex ([`orient2`]); if the
///   projected triangle is flat (the third vertex on that line), strictly on
///   either side. For two convex polygons in a plane, one disjoint from the
///   other always lies beyond an edge line of one of them, so with the box
///   axes this covers the axis's other side too.
///
/// Zero-area triangles need no special case: an axis that degenerates to
/// zero sees every corner at sign 0 and separates nothing, and the
/// remaining axes are those of a segment (or point) against a box. A NaN
/// anywhere makes every comparison false, so the box axes report no
/// separation; queries refuse NaN coordinates before they get here.
///
/// ```
/// use bvhkit::{Aabb, Intersects, Triangle};
/// use glam::Vec3;
/// let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
/// // Across the box's (1, 1, 1) corner, in the plane x + y + z = 3.25: its
/// // bounding box overlaps the unit box, the triangle itself misses it.
/// let past = Triangle::new(Vec3::new(2.25, 0.5, 0.5), Vec3::new(0.5, 2.25, 0.5), Vec3::new(0.5, 0.5, 2.25));
/// assert!(unit.overlaps(&bvhkit::Primitive::bounds(&past)));
/// assert!(!unit.intersects(&past));
/// // In the plane x + y + z = 3, the corner is the triangle's centroid:
/// // touching counts.
/// let touching = Triangle::new(Vec3::new(2.0, 0.5, 0.5), Vec3::new(0.5, 2.0, 0.5), Vec3::new(0.5, 0.5, 2.0));
/// assert!(unit.intersects(&touching) && touching.intersects(&unit));
/// ```
pub fn box_triangle_intersect(b: &Aabb, t: &Triangle) -> bool {
    let [v0, v1, v2] = t.v;
    // The box's face normals: the triangle's extent per coordinate.
    let (lo, hi) = (v0.min(v1).min(v2), v0.max(v1).max(v2));
    if hi.cmplt(b.min).any() || lo.cmpgt(b.max).any() {
        return false;
    }
    let corner = |k: usize| {
        Vec3::new(
            if k & 1 == 0 { b.min.x } else { b.max.x },
            if k & 2 == 0 { b.min.y } else { b.max.y },
            if k & 4 == 0 { b.min.z } else { b.max.z },
        )
    };
    // The triangle's normal: every corner strictly on one side of the plane.
    let first = orient3(v0, v1, v2, corner(0));
    if first != 0 && (1..8).all(|k| orient3(v0, v1, v2, corner(k)) == first) {
        return false;
    }
    // Edge x box axis, as the projected triangle's edge lines against the
    // projected box's four corners.
    for k in 0..3 {
        let (u, w) = plane_axes(k);
        let rect = |m: usize| {
            let mut p = b.min;
            p[u] = if m & 1 == 0 { b.min[u] } else { b.max[u] };
            p[w] = if m & 2 == 0 { b.min[w] } else { b.max[w] };
            p
        };
        for (a, c, opposite) in [(v0, v1, v2), (v1, v2, v0), (v2, v0, v1)] {
            let inner = orient2(a, c, opposite, k);
            let side = orient2(a, c, rect(0), k);
            let beyond = if inner == 0 {
                side != 0
            } else {
                side == -inner
            };
            if beyond && (1..4).all(|m| orient2(a, c, rect(m), k) == side) {
                return false;
            }
        }
    }
    true
}

/// Sign (-1, 0, 1) of `det[b - a, c - a, d - a]`, computed exactly: positive
/// when `d` lies on the side of plane `abc` that `(b - a) × (c - a)` points to.
#[inline]
pub fn orient3(a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> i8 {
    // Shewchuk's orient3d is det[a - d, b - d, c - d] = -det[b - a, c - a, d - a].
    sign(-orient3d(c3(a), c3(b), c3(c), c3(d)))
}

/// Sign of the `k`-th component of `(b - a) × (c - a)`, computed exactly: the
/// 2-D orientation of the three points projected along axis `k`.
#[inline]
pub fn orient2(a: Vec3, b: Vec3, c: Vec3, k: usize) -> i8 {
    sign(orient2d(c2(a, k), c2(b, k), c2(c, k)))
}

/// Where the triangle test's orientation signs come from. The test's logic
/// is the same for all; only [`ExactSigns`] makes its answer exact. The
/// others exist to measure what exactness buys (`bvhkit bench`, book chapter
/// "Robustness"): they evaluate the same determinants in plain floating
/// point, which gets the sign wrong when a point is nearly on a plane.
pub trait Orientation: Copy {
    /// Sign of `det[b - a, c - a, d - a]` (see [`orient3`]).
    fn orient3(self, a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> i8;
    /// Sign of the `k`-th component of `(b - a) × (c - a)` (see [`orient2`]).
    fn orient2(self, a: Vec3, b: Vec3, c: Vec3, k: usize) -> i8;
}

/// Exact signs (Shewchuk's adaptive predicates): the library's choice.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ExactSigns;

/// The determinants in `f64`, without error bounds: exact only while the
/// products fit 53 bits.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct F64Signs;

/// The determinants in `f32`, as a naive implementation computes them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct F32Signs;

impl Orientation for ExactSigns {
    #[inline]
    fn orient3(self, a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> i8 {
        orient3(a, b, c, d)
    }
    #[inline]
    fn orient2(self, a: Vec3, b: Vec3, c: Vec3, k: usize) -> i8 {
        orient2(a, b, c, k)
    }
}

impl Orientation for F64Signs {
    #[inline]
    fn orient3(self, a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> i8 {
        let (a, b, c, d) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3(), d.as_dvec3());
        sign((b - a).dot((c - a).cross(d - a)))
    }
    #[inline]
    fn orient2(self, a: Vec3, b: Vec3, c: Vec3, k: usize) -> i8 {
        let (u, v) = plane_axes(k);
        let (e, f) = (b.as_dvec3() - a.as_dvec3(), c.as_dvec3() - a.as_dvec3());
        sign(e[u] * f[v] - e[v] * f[u])
    }
}

impl Orientation for F32Signs {
    #[inline]
    fn orient3(self, a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> i8 {
        sign((b - a).dot((c - a).cross(d - a)) as f64)
    }
    #[inline]
    fn orient2(self, a: Vec3, b: Vec3, c: Vec3, k: usize) -> i8 {
        let (u, v) = plane_axes(k);
        let (e, f) = (b - a, c - a);
        sign((e[u] * f[v] - e[v] * f[u]) as f64)
    }
}

/// Exact triangle–triangle intersection (closed triangles, touching counts).
/// Zero-area triangles are treated as the segment or point they are. Two
/// triangles with a common corner meet without any predicate evaluated
/// ([`triangles_intersect_with`] tests the signs alone).
pub fn triangles_intersect(t1: &Triangle, t2: &Triangle) -> bool {
    shares_a_corner(t1, t2) || triangles_intersect_with(t1, t2, ExactSigns)
}

/// Whether a corner of `t1` is exactly a corner of `t2`: a common point, so
/// the closed triangles meet. Neighbours in one mesh share corners, and a
/// mesh against itself or a copy of it in place (coincident surfaces) is
/// almost only such pairs: every orientation there is exactly zero, the
/// case the exact predicates settle last and slowest.
#[inline]
fn shares_a_corner(t1: &Triangle, t2: &Triangle) -> bool {
    // Nine comparisons without a branch: the pairs of a moved copy share no
    // corner, and a branch per comparison showed in their time.
    let b = t2.v.map(Vec3A::from);
    t1.v.iter().fold(false, |any, &a| {
        let a = Vec3A::from(a);
        any | a.cmpeq(b[0]).all() | a.cmpeq(b[1]).all() | a.cmpeq(b[2]).all()
    })
}

/// The same test with the orientation signs of `o`: exact with
/// [`ExactSigns`], approximate with [`F64Signs`] or [`F32Signs`].
///
/// ```
/// use bvhkit::narrow::{triangles_intersect_with, ExactSigns, F32Signs};
/// use bvhkit::Triangle;
/// use glam::Vec3;
/// // A vertex resting on a face, far from the origin: the f32 determinant
/// // rounds, the exact sign does not.
/// let o = Vec3::new(1000.1, 2000.3, -511.7);
/// let floor = Triangle::new(o, o + Vec3::new(3.7, 0.1, 0.0), o + Vec3::new(0.3, 2.9, 0.0));
/// let tip = o + Vec3::new(1.1, 0.9, 0.0);
/// let post = Triangle::new(tip, tip + Vec3::new(0.2, 0.1, 1.3), tip + Vec3::new(-0.1, 0.3, 1.1));
/// assert_eq!(triangles_intersect_with(&floor, &post, ExactSigns), bvhkit::narrow::triangles_intersect(&floor, &post));
/// let _maybe_wrong = triangles_intersect_with(&floor, &post, F32Signs);
/// ```
pub fn triangles_intersect_with<O: Orientation>(t1: &Triangle, t2: &Triangle, o: O) -> bool {
    match (degenerate(t1, o), degenerate(t2, o)) {
        (None, None) => guigue_devillers(t1, t2, o),
        (None, Some(s)) => segment_triangle(s, t1, o),
        (Some(s), None) => segment_triangle(s, t2, o),
        (Some(s1), Some(s2)) => segments_intersect(s1, s2, o),
    }
}

/// Exact triangle–triangle intersection by the plain definition: two closed
/// triangles meet iff an edge of one meets the other. Slower than
/// [`triangles_intersect`], written independently of it, and used as its
/// reference in tests.
pub fn triangles_intersect_by_edges(t1: &Triangle, t2: &Triangle) -> bool {
    let edges_meet = |s: &Triangle, t: &Triangle| {
        (0..3).any(|i| {
            let e = [s.v[i], s.v[(i + 1) % 3]];
            match degenerate(t, ExactSigns) {
                None => segment_triangle(e, t, ExactSigns),
                Some(s) => segments_intersect(e, s, ExactSigns),
            }
        })
    };
    edges_meet(t1, t2) || edges_meet(t2, t1)
}

/// What a zero-area triangle degenerates to, decided exactly: `None` for a
/// proper triangle, else the segment between its extreme corners (both ends
/// equal for a point).
fn degenerate<O: Orientation>(t: &Triangle, o: O) -> Option<[Vec3; 2]> {
    let [a, b, c] = t.v;
    // The cross product is zero iff all three projected orientations are.
    if (0..3).any(|k| o.orient2(a, b, c, k) != 0) {
        return None;
    }
    // Collinear: the extreme points along an axis where they differ.
    let k = (0..3).find(|&k| a[k] != b[k] || a[k] != c[k]).unwrap_or(0);
    let (mut lo, mut hi) = (a, a);
    for p in [b, c] {
        if p[k] < lo[k] {
            lo = p;
        }
        if p[k] > hi[k] {
            hi = p;
        }
    }
    Some([lo, hi])
}

/// Guigue & Devillers (2003) for two non-degenerate triangles. Every branch
/// reads one exact orientation sign.
fn guigue_devillers<O: Orientation>(t1: &Triangle, t2: &Triangle, o: O) -> bool {
    let [p1, q1, r1] = t1.v;
    let [p2, q2, r2] = t2.v;
    let (dp1, dq1, dr1) = (
        o.orient3(p2, q2, r2, p1),
        o.orient3(p2, q2, r2, q1),
        o.orient3(p2, q2, r2, r1),
    );
    if strictly_one_side(dp1, dq1, dr1) {
        return false;
    }
    let (dp2, dq2, dr2) = (
        o.orient3(p1, q1, r1, p2),
        o.orient3(p1, q1, r1, q2),
        o.orient3(p1, q1, r1, r2),
    );
    if strictly_one_side(dp2, dq2, dr2) {
        return false;
    }
    if dp1 == 0 && dq1 == 0 && dr1 == 0 {
        return coplanar(t1, t2, o);
    }
    // Rotate triangle 1 so that p1 is alone on its side of plane 2, and swap
    // q2/r2 so that p1 is on the positive side.
    let d2 = (dp2, dq2, dr2);
    let d2s = (dp2, dr2, dq2);
    if dp1 > 0 {
        if dq1 > 0 {
            tri_tri_3d([r1, p1, q1], [p2, r2, q2], d2s, t1, t2, o)
        } else if dr1 > 0 {
            tri_tri_3d([q1, r1, p1], [p2, r2, q2], d2s, t1, t2, o)
        } else {
            tri_tri_3d([p1, q1, r1], [p2, q2, r2], d2, t1, t2, o)
        }
    } else if dp1 < 0 {
        if dq1 < 0 {
            tri_tri_3d([r1, p1, q1], [p2, q2, r2], d2, t1, t2, o)
        } else if dr1 < 0 {
            tri_tri_3d([q1, r1, p1], [p2, q2, r2], d2, t1, t2, o)
        } else {
            tri_tri_3d([p1, q1, r1], [p2, r2, q2], d2s, t1, t2, o)
        }
    } else if dq1 < 0 {
        if dr1 >= 0 {
            tri_tri_3d([q1, r1, p1], [p2, r2, q2], d2s, t1, t2, o)
        } else {
            tri_tri_3d([p1, q1, r1], [p2, q2, r2], d2, t1, t2, o)
        }
    } else if dq1 > 0 {
        if dr1 > 0 {
            tri_tri_3d([p1, q1, r1], [p2, r2, q2], d2s, t1, t2, o)
        } else {
            tri_tri_3d([q1, r1, p1], [p2, q2, r2], d2, t1, t2, o)
        }
    } else if dr1 > 0 {
        tri_tri_3d([r1, p1, q1], [p2, q2, r2], d2, t1, t2, o)
    } else {
        tri_tri_3d([r1, p1, q1], [p2, r2, q2], d2s, t1, t2, o)
    }
}

fn strictly_one_side(a: i8, b: i8, c: i8) -> bool {
    (a > 0 && b > 0 && c > 0) || (a < 0 && b < 0 && c < 0)
}

/// Second permutation step: put p2 alone on its side of plane 1, then compare
/// the two intervals on the planes' common line with two orientation signs.
fn tri_tri_3d<O: Orientation>(
    [p1, q1, r1]: [Vec3; 3],
    [p2, q2, r2]: [Vec3; 3],
    (dp2, dq2, dr2): (i8, i8, i8),
    t1: &Triangle,
    t2: &Triangle,
    o: O,
) -> bool {
    let check = |[p1, q1, r1]: [Vec3; 3], [p2, q2, r2]: [Vec3; 3]| {
        o.orient3(q1, p2, p1, q2) <= 0 && o.orient3(p1, p2, r1, r2) <= 0
    };
    if dp2 > 0 {
        if dq2 > 0 {
            check([p1, r1, q1], [r2, p2, q2])
        } else if dr2 > 0 {
            check([p1, r1, q1], [q2, r2, p2])
        } else {
            check([p1, q1, r1], [p2, q2, r2])
        }
    } else if dp2 < 0 {
        if dq2 < 0 {
            check([p1, q1, r1], [r2, p2, q2])
        } else if dr2 < 0 {
            check([p1, q1, r1], [q2, r2, p2])
        } else {
            check([p1, r1, q1], [p2, q2, r2])
        }
    } else if dq2 < 0 {
        if dr2 >= 0 {
            check([p1, r1, q1], [q2, r2, p2])
        } else {
            check([p1, q1, r1], [p2, q2, r2])
        }
    } else if dq2 > 0 {
        if dr2 > 0 {
            check([p1, r1, q1], [p2, q2, r2])
        } else {
            check([p1, q1, r1], [q2, r2, p2])
        }
    } else if dr2 > 0 {
        check([p1, q1, r1], [r2, p2, q2])
    } else if dr2 < 0 {
        check([p1, r1, q1], [r2, p2, q2])
    } else {
        coplanar(t1, t2, o)
    }
}

/// Two coplanar, non-degenerate triangles: in the projection that keeps
/// triangle 1 non-degenerate (then it is one-to-one on the common plane),
/// they meet iff two edges cross or a vertex of one lies in the other.
fn coplanar<O: Orientation>(t1: &Triangle, t2: &Triangle, o: O) -> bool {
    let k = projection_axis(t1, o);
    (0..3).any(|i| {
        let e = [t1.v[i], t1.v[(i + 1) % 3]];
        (0..3).any(|j| segments_intersect_2d(e, [t2.v[j], t2.v[(j + 1) % 3]], k, o))
    }) || point_in_triangle_2d(t1.v[0], t2, k, o)
        || point_in_triangle_2d(t2.v[0], t1, k, o)
}

/// An axis along which the (non-degenerate) triangle projects to a
/// non-degenerate triangle.
fn projection_axis<O: Orientation>(t: &Triangle, o: O) -> usize {
    (0..3)
        .find(|&k| o.orient2(t.v[0], t.v[1], t.v[2], k) != 0)
        .unwrap_or(2)
}

/// Segment (possibly a point) against a non-degenerate triangle.
fn segment_triangle<O: Orientation>([s0, s1]: [Vec3; 2], t: &Triangle, o: O) -> bool {
    let [a, b, c] = t.v;
    let (d0, d1) = (o.orient3(a, b, c, s0), o.orient3(a, b, c, s1));
    if d0 * d1 > 0 {
        return false;
    }
    if d0 == 0 && d1 == 0 {
        let k = projection_axis(t, o);
        return point_in_triangle_2d(s0, t, k, o)
            || point_in_triangle_2d(s1, t, k, o)
            || (0..3).any(|i| segments_intersect_2d([s0, s1], [t.v[i], t.v[(i + 1) % 3]], k, o));
    }
    // The segment meets the plane in exactly one point; the line through it
    // passes through the closed triangle iff it is on the same side of all
    // three edges (zeros allowed).
    let e = [
        o.orient3(s0, s1, a, b),
        o.orient3(s0, s1, b, c),
        o.orient3(s0, s1, c, a),
    ];
    e.iter().all(|&x| x >= 0) || e.iter().all(|&x| x <= 0)
}

/// Two segments (either may be a point) in 3-D. Segments that meet are
/// coplanar; coplanar segments meet iff they meet in all three axis
/// projections (at least one projection is one-to-one on their plane).
fn segments_intersect<O: Orientation>(s: [Vec3; 2], t: [Vec3; 2], o: O) -> bool {
    o.orient3(s[0], s[1], t[0], t[1]) == 0 && (0..3).all(|k| segments_intersect_2d(s, t, k, o))
}

/// Closed segments in the projection along axis `k`.
fn segments_intersect_2d<O: Orientation>(
    [p1, q1]: [Vec3; 2],
    [p2, q2]: [Vec3; 2],
    k: usize,
    o: O,
) -> bool {
    let o1 = o.orient2(p1, q1, p2, k);
    let o2 = o.orient2(p1, q1, q2, k);
    let o3 = o.orient2(p2, q2, p1, k);
    let o4 = o.orient2(p2, q2, q1, k);
    if o1 * o2 < 0 && o3 * o4 < 0 {
        return true;
    }
    (o1 == 0 && within(p2, p1, q1, k))
        || (o2 == 0 && within(q2, p1, q1, k))
        || (o3 == 0 && within(p1, p2, q2, k))
        || (o4 == 0 && within(q1, p2, q2, k))
}

/// For a point collinear with segment `ab` (in projection `k`): whether it
/// lies in the segment's bounding rectangle, i.e. on the segment.
fn within(p: Vec3, a: Vec3, b: Vec3, k: usize) -> bool {
    let (u, v) = plane_axes(k);
    let inside = |i: usize| a[i].min(b[i]) <= p[i] && p[i] <= a[i].max(b[i]);
    inside(u) && inside(v)
}

/// Closed, non-degenerate triangle in projection `k`.
fn point_in_triangle_2d<O: Orientation>(p: Vec3, t: &Triangle, k: usize, o: O) -> bool {
    let [a, b, c] = t.v;
    let s = [
        o.orient2(a, b, p, k),
        o.orient2(b, c, p, k),
        o.orient2(c, a, p, k),
    ];
    s.iter().all(|&x| x >= 0) || s.iter().all(|&x| x <= 0)
}

/// The two kept axes when projecting along `k`, in cyclic order so that the
/// 2-D orientation equals the `k`-th component of the 3-D cross product.
#[inline]
fn plane_axes(k: usize) -> (usize, usize) {
    ((k + 1) % 3, (k + 2) % 3)
}

#[inline]
fn c2(p: Vec3, k: usize) -> Coord<f32> {
    let (u, v) = plane_axes(k);
    Coord { x: p[u], y: p[v] }
}

#[inline]
fn c3(p: Vec3) -> Coord3D<f32> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

#[inline]
fn sign(v: f64) -> i8 {
    if v > 0.0 {
        1
    } else if v < 0.0 {
        -1
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orientation_signs_follow_the_right_hand_rule() {
        assert_eq!(orient3(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z), 1);
        assert_eq!(orient3(Vec3::ZERO, Vec3::Y, Vec3::X, Vec3::Z), -1);
        assert_eq!(orient3(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::X * 3.0), 0);
        // orient2 along k equals the k-th cross-product component.
        let (a, b, c) = (
            Vec3::ZERO,
            Vec3::new(1.0, 2.0, 0.5),
            Vec3::new(-1.0, 0.5, 2.0),
        );
        let n = (b - a).cross(c - a);
        for k in 0..3 {
            assert_eq!(orient2(a, b, c, k), sign(n[k] as f64), "axis {k}");
        }
    }

    /// Two triangles with a corner in common meet, whichever corners they
    /// are, whatever else the triangles do (coplanar and overlapping, apart
    /// but for the corner, zero area, far from the origin, `-0.0` against
    /// `0.0`), as the edge reference says; and a corner that misses by one
    /// float is decided by the full test.
    #[test]
    fn a_shared_corner_is_a_meeting() {
        let far = Vec3::new(3.0e6, -1.5e6, 7.25e5);
        let mut checked = 0;
        for origin in [Vec3::ZERO, far] {
            let c = origin + Vec3::new(0.5, 0.25, -0.75);
            let others: [[Vec3; 2]; 5] = [
                [Vec3::X, Vec3::Y],                  // coplanar neighbour
                [-Vec3::X, -Vec3::Y],                // coplanar, opposite side
                [Vec3::Z, Vec3::new(0.0, 1.0, 1.0)], // a wall
                [Vec3::X * 2.0, Vec3::X],            // zero area
                [Vec3::ZERO, Vec3::ZERO],            // a point
            ];
            for [p, q] in others {
                let t1 = Triangle::new(
                    c,
                    c + Vec3::new(1.0, 0.5, 0.0),
                    c + Vec3::new(0.0, 1.0, 0.0),
                );
                let t2 = Triangle::new(c, c + p, c + q);
                for r1 in 0..3 {
                    for r2 in 0..3 {
                        let a = Triangle::new(t1.v[r1], t1.v[(r1 + 1) % 3], t1.v[(r1 + 2) % 3]);
                        let b = Triangle::new(t2.v[r2], t2.v[(r2 + 1) % 3], t2.v[(r2 + 2) % 3]);
                        assert!(shares_a_corner(&a, &b) && shares_a_corner(&b, &a));
                        assert!(triangles_intersect(&a, &b), "{a:?} {b:?}");
                        assert!(triangles_intersect_by_edges(&a, &b), "{a:?} {b:?}");
                        assert!(triangles_intersect_with(&a, &b, ExactSigns));
                        checked += 1;
                    }
                }
            }
        }
        assert_eq!(checked, 90);
        // Two corners in common (an edge), three (the same triangle), one
        // corner given twice: still a corner in common.
        let t = Triangle::new(far, far + Vec3::X, far + Vec3::Y);
        let edge = Triangle::new(far + Vec3::Y, far, far - Vec3::X);
        let twice = Triangle::new(far + Vec3::X, far + Vec3::X, far + Vec3::Z);
        let ends = Triangle::new(far + Vec3::X, far + Vec3::Z, far + Vec3::X);
        let last = Triangle::new(far + Vec3::Z, far + Vec3::X, far + Vec3::X);
        for (a, b) in [
            (t, edge),
            (t, t),
            (t, twice),
            (twice, twice),
            (t, ends),
            (t, last),
        ] {
            assert!(
                shares_a_corner(&a, &b) && shares_a_corner(&b, &a),
                "{a:?} {b:?}"
            );
            assert!(triangles_intersect(&a, &b) && triangles_intersect_by_edges(&a, &b));
        }
        // `-0.0` is the same point as `0.0`.
        let t1 = Triangle::new(Vec3::new(-0.0, 0.0, 0.0), Vec3::X, Vec3::Y);
        let t2 = Triangle::new(Vec3::ZERO, -Vec3::X, -Vec3::Z);
        assert!(shares_a_corner(&t1, &t2) && triangles_intersect(&t1, &t2));
        // One float away: no shared corner, and the triangles are apart.
        let next = Vec3::new(f32::from_bits(1.0f32.to_bits() + 1), 0.0, 0.0);
        let t1 = Triangle::new(Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::new(0.0, 1.0, 0.0));
        let t2 = Triangle::new(next, Vec3::new(2.0, 0.0, 0.0), Vec3::new(2.0, -1.0, 0.0));
        assert!(!shares_a_corner(&t1, &t2));
        assert!(!triangles_intersect(&t1, &t2) && !triangles_intersect_by_edges(&t1, &t2));
    }

    #[test]
    fn degenerate_shapes_are_recognised() {
        let seg = Triangle::new(Vec3::ZERO, Vec3::splat(2.0), Vec3::ONE);
        assert_eq!(
            degenerate(&seg, ExactSigns),
            Some([Vec3::ZERO, Vec3::splat(2.0)])
        );
        assert_eq!(
            degenerate(&Triangle::new(Vec3::ONE, Vec3::ONE, Vec3::ONE), ExactSigns),
            Some([Vec3::ONE; 2])
        );
        assert_eq!(
            degenerate(&Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y), ExactSigns),
            None
        );
    }

    /// The box–triangle test against its definition, decided exactly
    /// another way: a closed triangle meets a closed box iff a vertex lies
    /// in the box or the triangle meets one of the 12 triangles of the box's
    /// surface ([`triangles_intersect_by_edges`]; a flat box's surface
    /// triangles cover it). Boxes flat on one or two axes or a point,
    /// triangles with vertices on corners, edges and faces and one `f32` step
    /// outside them, through a corner, degenerate, at scales 1e-3 to 1e4.
    #[test]
    fn box_triangle_matches_its_definition() {
        let mut next = crate::test_floats(0x51ce_b0a7_d00d_f00d);
        let reference = |b: &Aabb, t: &Triangle| {
            let c = |k: usize| {
                Vec3::new(
                    if k & 1 == 0 { b.min.x } else { b.max.x },
                    if k & 2 == 0 { b.min.y } else { b.max.y },
                    if k & 4 == 0 { b.min.z } else { b.max.z },
                )
            };
            // Two triangles per face: corners differing in one axis bit.
            let faces = [
                (0, 1, 3, 2),
                (4, 5, 7, 6),
                (0, 1, 5, 4),
                (2, 3, 7, 6),
                (0, 2, 6, 4),
                (1, 3, 7, 5),
            ];
            t.v.iter()
                .any(|p| p.cmpge(b.min).all() && p.cmple(b.max).all())
                || faces.iter().any(|&(p, q, r, w)| {
                    triangles_intersect_by_edges(&Triangle::new(c(p), c(q), c(r)), t)
                        || triangles_intersect_by_edges(&Triangle::new(c(p), c(r), c(w)), t)
                })
        };
        let (mut hits, mut near_misses, mut stepped_in, mut stepped_out) = (0, 0, 0, 0);
        for round in 0..40_000usize {
            let scale = [1.0f32, 1e-3, 1e4][round % 3];
            let offset = Vec3::splat([0.0f32, 1e4][round / 3 % 2] * scale);
            let min = offset + Vec3::new(next(), next(), next()) * scale;
            let mut extent = Vec3::new(next().abs(), next().abs(), next().abs()) * scale;
            match round / 6 % 6 {
                0 => extent[round % 3] = 0.0,
                1 => extent = Vec3::ZERO,
                _ => {}
            }
            let b = Aabb::new(min, min + extent);
            let corner = |k: usize| {
                Vec3::new(
                    if k & 1 == 0 { b.min.x } else { b.max.x },
                    if k & 2 == 0 { b.min.y } else { b.max.y },
                    if k & 4 == 0 { b.min.z } else { b.max.z },
                )
            };
            let mut point = |kind: usize| -> Vec3 {
                let r = Vec3::new(next(), next(), next());
                match kind {
                    // Near the box.
                    0 => b.center() + r * (extent.max_element() + scale * 0.05),
                    // A corner.
                    1 => corner((next().abs() * 8.0) as usize % 8),
                    // On a face: one coordinate pinned to the box's.
                    2 => {
                        let mut p = b.center() + r * extent * 0.5;
                        let k = (next().abs() * 3.0) as usize % 3;
                        p[k] = if next() < 0.0 { b.min[k] } else { b.max[k] };
                        p
                    }
                    // A corner moved one f32 step outwards on one axis.
                    _ => {
                        let k = (next().abs() * 8.0) as usize % 8;
                        let mut p = corner(k);
                        let a = (next().abs() * 3.0) as usize % 3;
                        let up = k >> a & 1 == 1;
                        let bits = p[a].to_bits();
                        let step = if (p[a] >= 0.0) == up {
                            bits + 1
                        } else {
                            bits.wrapping_sub(1)
                        };
                        p[a] = if p[a] == 0.0 {
                            if up {
                                1e-45
                            } else {
                                -1e-45
                            }
                        } else {
                            f32::from_bits(step)
                        };
                        p
                    }
                }
            };
            let kinds = [round % 4, round / 4 % 4, round / 16 % 4];
            let mut v = kinds.map(&mut point);
            match round / 64 % 7 {
                0 => v[2] = v[0],
                1 => v[2] = v[0] + (v[1] - v[0]) * 0.5,
                // Through a corner: two vertices mirrored about it.
                2 => {
                    let c = corner(round % 8);
                    v[1] = c + (c - v[0]);
                }
                // Across a corner, square to its diagonal: the plane through
                // the corner, just past it, or just short of it.
                3 | 4 => {
                    let k = round % 8;
                    let c = corner(k);
                    let out = Vec3::new(
                        if k & 1 == 0 { -1.0 } else { 1.0 },
                        if k & 2 == 0 { -1.0 } else { 1.0 },
                        if k & 4 == 0 { -1.0 } else { 1.0 },
                    );
                    let h = next().abs() * scale + scale * 0.01;
                    let d = [0.0, h * 1e-6, -h * 1e-6][round / 448 % 3];
                    let (long, short) = (2.0 * h + d, -h + d);
                    v = [
                        c + out * Vec3::new(long, short, short),
                        c + out * Vec3::new(short, long, short),
                        c + out * Vec3::new(short, short, long),
                    ];
                }
                _ => {}
            }
            let t = Triangle::new(v[0], v[1], v[2]);
            let want = reference(&b, &t);
            assert_eq!(
                box_triangle_intersect(&b, &t),
                want,
                "round {round}: {b:?} {t:?}"
            );
            assert_eq!(t.intersects(&b), want);
            let bounds_meet = b.overlaps(&crate::Primitive::bounds(&t));
            hits += want as usize;
            near_misses += (!want && bounds_meet) as usize;
            // Every vertex on the box's surface or one step outside it.
            let on_edge = kinds.iter().all(|&k| k != 0) && round / 64 % 7 > 4;
            (stepped_in, stepped_out) = match (on_edge, want) {
                (true, true) => (stepped_in + 1, stepped_out),
                (true, false) => (stepped_in, stepped_out + 1),
                _ => (stepped_in, stepped_out),
            };
        }
        assert!(
            hits > 10_000 && near_misses > 2_000,
            "{hits} hits, {near_misses} near misses"
        );
        assert!(
            stepped_in > 1_000 && stepped_out > 40,
            "{stepped_in} / {stepped_out} at the surface"
        );
    }
}
