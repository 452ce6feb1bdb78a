//! Where two triangles meet: the contact's geometry, not only its existence.
//!
//! [`triangles_intersect`](super::triangles_intersect) decides *whether*
//! two triangles touch, exactly. [`triangle_contact`] adds *where*: for two
//! triangles crossing each other, the segment along which their planes meet
//! inside both; for two triangles in one plane, the polygon they share. The
//! decision (touching or not, in one plane or not, which side of a plane a
//! corner is on) is exact; the coordinates are computed in `f64` from those
//! exact decisions, so they are as close as `f64` rounding allows.

use super::{degenerate, orient3, triangles_intersect, ExactSigns};
use crate::primitive::Triangle;
use crate::query::PairDistance;
use glam::DVec3;

/// Where two touching triangles meet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Contact {
    /// The triangles cross (or touch) out of one plane: they share the
    /// segment between these two points, on the line where their planes
    /// meet. The two points are equal when they touch at one point. A
    /// zero-area triangle (a segment or a point) gives one common point.
    Segment([DVec3; 2]),
    /// The triangles lie in one plane and overlap: the convex polygon they
    /// share, its first `len` corners in order around it (up to six; fewer
    /// when they share an edge, a segment or a point).
    Area {
        /// The corners; those past `len` are unused.
        corners: [DVec3; 6],
        /// How many corners there are.
        len: usize,
    },
}

impl Contact {
    /// The points of the contact: the segment's two ends or the polygon's corners.
    pub fn points(&self) -> &[DVec3] {
        match self {
            Contact::Segment(ends) => ends,
            Contact::Area { corners, len } => &corners[..*len],
        }
    }
}

/// Where triangles `t1` and `t2` meet, or `None` when they do not touch
/// (decided exactly, as by [`triangles_intersect`]).
///
/// ```
/// use bvhkit::narrow::{triangle_contact, Contact};
/// use bvhkit::Triangle;
/// use glam::{DVec3, Vec3};
/// // A vertical triangle through a horizontal one: they share a segment on
/// // the floor's plane z = 0.
/// let floor = Triangle::new(Vec3::new(-4.0, -4.0, 0.0), Vec3::new(4.0, -4.0, 0.0), Vec3::new(0.0, 4.0, 0.0));
/// let wall = Triangle::new(Vec3::new(-1.0, 0.0, -1.0), Vec3::new(1.0, 0.0, -1.0), Vec3::new(0.0, 0.0, 1.0));
/// let Some(Contact::Segment([p, q])) = triangle_contact(&floor, &wall) else { panic!() };
/// assert!(p.z == 0.0 && q.z == 0.0 && (p - q).length() == 1.0); // from x = -0.5 to 0.5
/// assert_eq!(triangle_contact(&floor, &wall.translated(Vec3::Z * 2.0)), None);
/// ```
pub fn triangle_contact(t1: &Triangle, t2: &Triangle) -> Option<Contact> {
    if !triangles_intersect(t1, t2) {
        return None;
    }
    if degenerate(t1, ExactSigns).is_some() || degenerate(t2, ExactSigns).is_some() {
        return Some(one_point(t1, t2));
    }
    let [a, b, c] = t1.v;
    let side = t2.v.map(|p| orient3(a, b, c, p));
    if side == [0, 0, 0] {
        return Some(coplanar(t1, t2).unwrap_or_else(|| one_point(t1, t2)));
    }
    // Out of one plane: each triangle meets the other's plane in a segment
    // (or a point) on the line where the planes meet; the contact is the
    // overlap of the two segments along that line.
    let dir = normal(t1).cross(normal(t2));
    let s1 = in_plane_of(t1, t2, dir);
    let s2 = in_plane_of(t2, t1, dir);
    let at = |p: DVec3| p.dot(dir);
    let (lo, hi) = match (s1, s2) {
        (Some(s1), Some(s2)) => {
            let lo = if at(s1[0]) >= at(s2[0]) { s1[0] } else { s2[0] };
            let hi = if at(s1[1]) <= at(s2[1]) { s1[1] } else { s2[1] };
            (lo, hi)
        }
        _ => return Some(one_point(t1, t2)),
    };
    if at(lo) > at(hi) {
        // Rounding crossed the ends of a contact that is (exactly) a point.
        let m = (lo + hi) * 0.5;
        return Some(Contact::Segment([m, m]));
    }
    Some(Contact::Segment([lo, hi]))
}

fn normal(t: &Triangle) -> DVec3 {
    let [a, b, c] = t.v.map(|v| v.as_dvec3());
    (b - a).cross(c - a)
}

/// Where triangle `t` meets the plane of `other`, as a segment ordered
/// along `dir` (`None` when it does not reach the plane). Which corners lie
/// on the plane or on which side is decided exactly.
fn in_plane_of(t: &Triangle, other: &Triangle, dir: DVec3) -> Option<[DVec3; 2]> {
    let [a, b, c] = other.v;
    let side = t.v.map(|p| orient3(a, b, c, p));
    let n = normal(other);
    let origin = a.as_dvec3();
    let height = t.v.map(|p| n.dot(p.as_dvec3() - origin));
    let mut points = [DVec3::ZERO; 3];
    let mut len = 0;
    for i in 0..3 {
        let j = (i + 1) % 3;
        if side[i] == 0 {
            points[len] = t.v[i].as_dvec3();
            len += 1;
        } else if side[j] != 0 && side[i] != side[j] {
            let (p, q) = (t.v[i].as_dvec3(), t.v[j].as_dvec3());
            let s = height[i] / (height[i] - height[j]);
            points[len] = p + (q - p) * s.clamp(0.0, 1.0);
            len += 1;
        }
        if len == 3 {
            break;
        }
    }
    if len == 0 {
        return None;
    }
    let points = &points[..len];
    let (mut lo, mut hi) = (points[0], points[0]);
    for &p in points {
        if p.dot(dir) < lo.dot(dir) {
            lo = p;
        }
        if p.dot(dir) > hi.dot(dir) {
            hi = p;
        }
    }
    Some([lo, hi])
}

/// Two triangles in one plane: `t1` clipped by `t2`'s three edges
/// (Sutherland–Hodgman in 2-D, the plane seen along its normal's largest
/// axis; the corners interpolated in 3-D, so they stay in the plane).
fn coplanar(t1: &Triangle, t2: &Triangle) -> Option<Contact> {
    let n = normal(t1);
    let k = n.abs().max_position();
    let (u, v) = ((k + 1) % 3, (k + 2) % 3);
    let cross2 = |a: DVec3, b: DVec3, p: DVec3| {
        (b[u] - a[u]) * (p[v] - a[v]) - (b[v] - a[v]) * (p[u] - a[u])
    };
    let clip = t2.v.map(|p| p.as_dvec3());
    // Inside every edge means on the side of its third corner.
    let orientation = cross2(clip[0], clip[1], clip[2]).signum();
    let mut poly = [DVec3::ZERO; 9];
    let mut len = 3;
    for (i, p) in t1.v.iter().enumerate() {
        poly[i] = p.as_dvec3();
    }
    for e in 0..3 {
        let (a, b) = (clip[e], clip[(e + 1) % 3]);
        let mut out = [DVec3::ZERO; 9];
        let mut out_len = 0;
        for i in 0..len {
            let (p, q) = (poly[i], poly[(i + 1) % len]);
            let (dp, dq) = (cross2(a, b, p) * orientation, cross2(a, b, q) * orientation);
            if dp >= 0.0 {
                out[out_len] = p;
                out_len += 1;
            }
            if (dp >= 0.0) != (dq >= 0.0) && out_len < 9 {
                out[out_len] = p + (q - p) * (dp / (dp - dq));
                out_len += 1;
            }
        }
        poly = out;
        len = out_len.min(9);
        if len == 0 {
            return None;
        }
    }
    // Drop repeated corners (a shared edge or corner clips to copies).
    let mut corners = [DVec3::ZERO; 6];
    let mut n_corners = 0;
    for &p in &poly[..len] {
        if n_corners > 0 && corners[n_corners - 1] == p {
            continue;
        }
        if n_corners == 6 {
            break;
        }
        corners[n_corners] = p;
        n_corners += 1;
    }
    if n_corners > 1 && corners[n_corners - 1] == corners[0] {
        n_corners -= 1;
    }
    Some(Contact::Area {
        corners,
        len: n_corners,
    })
}

/// A common point of two touching triangles: the middle of their closest
/// points (for zero-area triangles, and where rounding left nothing).
fn one_point(t1: &Triangle, t2: &Triangle) -> Contact {
    let c = t1.closest_points(t2);
    let m = (c.on_a + c.on_b) * 0.5;
    Contact::Segment([m, m])
}
