//! The volume and surface area of a convex polytope given as half-spaces,
//! for the k-DOP's measures.
//!
//! Lecture: *bounding volumes*, k-DOPs. A k-DOP is the intersection of its
//! slabs, smaller than its enclosing box wherever a diagonal plane cuts a
//! corner or an edge off; its measures must say so, or a student sees a
//! 26-DOP exactly as loose as a box.
//!
//! Method: each face separately. The face on plane `n . x = h` is a big
//! square in that plane clipped (Sutherland–Hodgman) by every other
//! half-space; its area is the shoelace sum. The surface area is the sum of
//! the face areas, and the volume is `sum(area_f * h_f) / 3`: the divergence
//! theorem with the origin as the apex of every face's pyramid (signed, so
//! the origin need not be inside). Faces are independent, so a degenerate
//! polytope cannot confuse the others: a flat k-DOP has two faces (both
//! sides of the sheet) of the sheet's area and `h_top = -h_bottom`, hence 0
//! volume; a segment or a point has faces of no area at all.
//!
//! Everything is `f64` on fixed-size arrays (no allocation): at most
//! [`MAX_PLANES`] planes, a face polygon of at most 4 + 25 vertices. The
//! caller translates and scales the planes so that the polytope lies in the
//! cube `[-1/2, 1/2]^3`: then a tolerance of [`EPS`] in the in/out decisions
//! is relative, and no coordinate of 1e30 ever meets a product.

use glam::DVec3;

/// Most planes a polytope may have (the 26-DOP's).
pub(super) const MAX_PLANES: usize = 26;
/// A face starts as a square and each clip adds at most one vertex.
const MAX_VERTICES: usize = 4 + MAX_PLANES;
/// How far outside a plane a vertex may lie and still count as on it, in
/// the normalised unit (the polytope's box has longest side 1). Rounding
/// in the clips is about 1e-16; a vertex this close to a plane moves the
/// measures by at most `EPS` times the perimeter.
const EPS: f64 = 1e-12;
/// Half the side of the starting square: it covers every point of the plane
/// within distance 2 of the origin, so the whole cube `[-1/2, 1/2]^3`.
const HALF_SIDE: f64 = 2.0;

/// Half-spaces `normal[i] . x <= offset[i]` with unit normals.
#[derive(Clone, Copy, Debug)]
pub(super) struct Planes {
    normal: [DVec3; MAX_PLANES],
    offset: [f64; MAX_PLANES],
    len: usize,
}

impl Planes {
    pub(super) const fn new() -> Self {
        Planes {
            normal: [DVec3::ZERO; MAX_PLANES],
            offset: [0.0; MAX_PLANES],
            len: 0,
        }
    }

    /// Adds `normal . x <= offset` (`normal` of unit length). Returns
    /// `false`, adding nothing, when the set is full.
    pub(super) fn push(&mut self, normal: DVec3, offset: f64) -> bool {
        if self.len == MAX_PLANES {
            return false;
        }
        self.normal[self.len] = normal;
        self.offset[self.len] = offset;
        self.len += 1;
        true
    }

    /// `(volume, surface area)` of the intersection of the half-spaces,
    /// which must lie within distance 2 of the origin (see the module docs).
    /// Never negative, never NaN for finite planes.
    pub(super) fn measures(&self) -> (f64, f64) {
        let (mut volume, mut area) = (0.0, 0.0);
        for f in 0..self.len {
            let a = self.face_area(f);
            area += a;
            volume += a * self.offset[f];
        }
        ((volume / 3.0).max(0.0), area.max(0.0))
    }

    /// The area of the face on plane `f`: its square clipped by every other plane.
    fn face_area(&self, f: usize) -> f64 {
        let n = self.normal[f];
        // An orthonormal frame (u, v, n), so the square runs counter-clockwise about n.
        let helper = if n.x.abs() < 0.5 { DVec3::X } else { DVec3::Y };
        let u = helper.cross(n).normalize();
        let v = n.cross(u);
        let c = n * self.offset[f];
        // Two buffers in turn: a clip reads one and writes the other, and
        // a plane that leaves every vertex inside (most of them: a plane
        // meets only the faces near it) copies nothing.
        let mut buf = [[DVec3::ZERO; MAX_VERTICES]; 2];
        let (mut cur, mut len) = (0, 4);
        buf[0][0] = c + (-u - v) * HALF_SIDE;
        buf[0][1] = c + (u - v) * HALF_SIDE;
        buf[0][2] = c + (u + v) * HALF_SIDE;
        buf[0][3] = c + (-u + v) * HALF_SIDE;
        for g in 0..self.len {
            if g == f {
                continue;
            }
            let (from, to) = if cur == 0 {
                let (a, b) = buf.split_at_mut(1);
                (&a[0], &mut b[0])
            } else {
                let (a, b) = buf.split_at_mut(1);
                (&b[0], &mut a[0])
            };
            match clip(&from[..len], self.normal[g], self.offset[g], to) {
                None => {}
                Some(m) if m < 3 => return 0.0,
                Some(m) => {
                    len = m;
                    cur = 1 - cur;
                }
            }
        }
        area(&buf[cur][..len], n)
    }
}

/// The part of the polygon `poly` with `normal . x <= offset` (within
/// [`EPS`]), Sutherland–Hodgman, written to `out`: its vertex count, or
/// `None` when every vertex is inside (`out` untouched).
fn clip(
    poly: &[DVec3],
    normal: DVec3,
    offset: f64,
    out: &mut [DVec3; MAX_VERTICES],
) -> Option<usize> {
    // Most planes meet only the faces near them: stop at the first vertex outside.
    if poly.iter().all(|p| normal.dot(*p) - offset <= EPS) {
        return None;
    }
    let mut m = 0;
    let mut push = |p: DVec3| {
        // A convex polygon cut by a line gains at most one vertex, so this
        // never fills up; if rounding ever made it, dropping a vertex only
        // shrinks a sliver, it never panics.
        if m < MAX_VERTICES {
            out[m] = p;
            m += 1;
        }
    };
    let mut dp = normal.dot(poly[0]) - offset;
    for i in 0..poly.len() {
        let j = if i + 1 == poly.len() { 0 } else { i + 1 };
        let (p, q) = (poly[i], poly[j]);
        let dq = normal.dot(q) - offset;
        let (p_in, q_in) = (dp <= EPS, dq <= EPS);
        if p_in {
            push(p);
        }
        if p_in != q_in {
            // One side is above EPS and the other at most EPS, so the
            // denominator is nonzero; t is clamped against the tolerance band.
            let t = (dp / (dp - dq)).clamp(0.0, 1.0);
            push(p + (q - p) * t);
        }
        dp = dq;
    }
    Some(m)
}

/// Area of a planar polygon (shoelace, projected on its plane's normal `n`).
fn area(poly: &[DVec3], n: DVec3) -> f64 {
    let mut twice = DVec3::ZERO;
    let o = poly[0];
    for i in 1..poly.len() - 1 {
        twice += (poly[i] - o).cross(poly[i + 1] - o);
    }
    (0.5 * twice.dot(n)).max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(h: f64) -> Planes {
        let mut p = Planes::new();
        for a in [DVec3::X, DVec3::Y, DVec3::Z] {
            p.push(a, h);
            p.push(-a, h);
        }
        p
    }

    #[test]
    fn a_cube_and_a_cut_cube() {
        let (v, a) = cube(0.5).measures();
        assert!(
            (v - 1.0).abs() < 1e-12 && (a - 6.0).abs() < 1e-12,
            "{v} {a}"
        );
        // Cut off the corner (1/2, 1/2, 1/2) at x + y + z <= 1: a
        // tetrahedron of legs 1/2 is removed (volume 1/48); three right
        // triangles of legs 1/2 (area 1/8 each) are replaced by an
        // equilateral triangle of side sqrt(1/2).
        let mut p = cube(0.5);
        p.push(DVec3::ONE / 3f64.sqrt(), 1.0 / 3f64.sqrt());
        let (v, a) = p.measures();
        assert!((v - (1.0 - 1.0 / 48.0)).abs() < 1e-12, "{v}");
        let tri = 3f64.sqrt() / 4.0 * 0.5;
        assert!((a - (6.0 - 3.0 / 8.0 + tri)).abs() < 1e-12, "{a}");
    }

    #[test]
    fn a_flat_sheet_has_no_volume_and_both_sides_of_area() {
        let mut p = Planes::new();
        p.push(DVec3::X, 0.5);
        p.push(-DVec3::X, 0.5);
        p.push(DVec3::Y, 0.25);
        p.push(-DVec3::Y, 0.25);
        p.push(DVec3::Z, 0.1);
        p.push(-DVec3::Z, -0.1);
        let (v, a) = p.measures();
        // The two sides cancel up to rounding (the k-DOP returns 0 for a flat slab).
        assert!(v.abs() < 1e-15, "{v}");
        assert!((a - 2.0 * 0.5).abs() < 1e-12, "{a}");
    }

    #[test]
    fn an_empty_intersection_measures_nothing() {
        let mut p = cube(0.5);
        p.push(DVec3::ONE / 3f64.sqrt(), -1.0);
        assert_eq!(p.measures(), (0.0, 0.0));
    }
}
