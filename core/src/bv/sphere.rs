//! Bounding sphere: centre and radius; three fits of increasing quality.
//!
//! * [`Sphere::ritter`]: two passes; often close to the minimum, but with no
//!   bound tighter than the method's own (it can be well above it).
//! * [`Sphere::ritter_refined`]: Ritter, then repeatedly shrink and regrow over a
//!   shuffled order, keeping the smallest (Ericson's iterative refinement).
//! * [`Sphere::welzl`]: the exact minimal sphere, Welzl's algorithm written as
//!   four nested loops (no recursion, no buffer) over a pseudo-random order.
//!
//! All three end with the same conservative pass: the radius becomes the largest
//! `f64` distance from the chosen centre, rounded up to `f32`.

use super::{Aabb, BoundingVolume, PointSet};
use crate::round;
use glam::{DVec3, Vec3};

/// A sphere. An empty sphere has a negative radius.
///
/// ```
/// use bvhkit::{BoundingVolume, Sphere};
/// use glam::Vec3;
/// let pts = [Vec3::new(-1.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.5, 0.0)];
/// let exact = Sphere::welzl(&pts);
/// assert!((exact.radius - 1.0).abs() < 1e-6);
/// assert!(Sphere::ritter(&pts).radius >= exact.radius);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct Sphere {
    /// Centre.
    pub center: Vec3,
    /// Radius (negative for the empty sphere).
    pub radius: f32,
}

/// How many shrink-and-regrow passes [`BoundingVolume::fit`] uses for spheres.
pub const DEFAULT_REFINEMENTS: usize = 4;

/// Visits `0..n` in a fixed pseudo-random order: `i -> (a*i + b) mod n` with
/// `gcd(a, n) = 1` is a permutation, needing no buffer.
#[derive(Clone, Copy)]
struct Shuffle {
    n: u64,
    a: u64,
    b: u64,
}

impl Shuffle {
    fn new(n: usize, seed: u64) -> Self {
        let n = n.max(1) as u64;
        let mut a = (0x9E37_79B9_7F4A_7C15u64 ^ seed.wrapping_mul(0x2545_F491_4F6C_DD1D)) % n;
        while gcd(a, n) != 1 {
            a = (a + 1) % n;
        }
        Shuffle { n, a, b: seed % n }
    }
    #[inline]
    fn at(&self, i: usize) -> usize {
        ((self.a as u128 * i as u128 + self.b as u128) % self.n as u128) as usize
    }
}

fn gcd(mut a: u64, mut b: u64) -> u64 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

#[inline]
fn d(v: Vec3) -> DVec3 {
    v.as_dvec3()
}

/// Working sphere in f64 while fitting.
#[derive(Clone, Copy, Debug)]
struct S64 {
    c: DVec3,
    r: f64,
}

impl S64 {
    #[inline]
    fn contains(&self, p: DVec3) -> bool {
        // Relative tolerance: the algorithm's decisions only need to be near-exact;
        // the final conservative pass restores strict containment.
        (p - self.c).length() <= self.r * (1.0 + 1e-9) + 1e-30
    }
    fn from2(a: DVec3, b: DVec3) -> S64 {
        let c = (a + b) * 0.5;
        S64 {
            c,
            r: (a - c).length().max((b - c).length()),
        }
    }
    /// Circumsphere of a triangle (smallest sphere with all three on its boundary).
    fn from3(a: DVec3, b: DVec3, c: DVec3) -> S64 {
        let ab = b - a;
        let ac = c - a;
        let n = ab.cross(ac);
        let den = 2.0 * n.length_squared();
        if den <= 1e-300 || den < 1e-24 * ab.length_squared() * ac.length_squared() {
            // Collinear: the two farthest points span the sphere.
            return best_of_pairs(&[a, b, c]);
        }
        let off = (n.cross(ab) * ac.length_squared() + ac.cross(n) * ab.length_squared()) / den;
        let center = a + off;
        S64 {
            c: center,
            r: off.length(),
        }
    }
    /// Smallest sphere with all four points on or inside, all four on the boundary when possible.
    fn from4(a: DVec3, b: DVec3, c: DVec3, e: DVec3) -> S64 {
        let u = b - a;
        let v = c - a;
        let w = e - a;
        let det = 2.0 * u.dot(v.cross(w));
        let scale = u.length() * v.length() * w.length();
        if det.abs() > 1e-12 * scale && det != 0.0 {
            let off = (v.cross(w) * u.length_squared()
                + w.cross(u) * v.length_squared()
                + u.cross(v) * w.length_squared())
                / det;
            return S64 {
                c: a + off,
                r: off.length(),
            };
        }
        // Coplanar: the minimal sphere is spanned by a subset; try them all.
        let pts = [a, b, c, e];
        let mut best = best_of_pairs(&pts);
        for (i, j, k) in [(0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)] {
            let s = S64::from3(pts[i], pts[j], pts[k]);
            if s.r < best.r && pts.iter().all(|&p| s.contains(p)) {
                best = s;
            }
        }
        best
    }
}

/// Smallest "diameter" sphere over pairs that contains all points (always exists: the farthest pair... or a grown one).
fn best_of_pairs(pts: &[DVec3]) -> S64 {
    let mut best: Option<S64> = None;
    for i in 0..pts.len() {
        for j in i + 1..pts.len() {
            let s = S64::from2(pts[i], pts[j]);
            if pts.iter().all(|&p| s.contains(p)) && best.is_none_or(|b| s.r < b.r) {
                best = Some(s);
            }
        }
    }
    best.unwrap_or_else(|| {
        // Not reachable for collinear input, but stay total: grow around the first.
        let mut s = S64 { c: pts[0], r: 0.0 };
        for &p in pts {
            s.r = s.r.max((p - s.c).length());
        }
        s
    })
}

impl Sphere {
    /// The empty sphere.
    pub const EMPTY: Sphere = Sphere {
        center: Vec3::ZERO,
        radius: -1.0,
    };

    /// A sphere from centre and radius.
    pub const fn new(center: Vec3, radius: f32) -> Self {
        Sphere { center, radius }
    }

    /// Rounds the working sphere's centre to `f32`, then sets the radius to the
    /// largest exact distance to any point, rounded up: containment is guaranteed.
    fn conservative<S: PointSet + ?Sized>(points: &S, c: DVec3) -> Sphere {
        let center = c.as_vec3();
        let cd = d(center);
        let mut r2: f64 = 0.0;
        for i in 0..points.len() {
            r2 = r2.max((d(points.point(i)) - cd).length_squared());
        }
        Sphere {
            center,
            radius: round::up(libm::sqrt(r2) * (1.0 + 4.0 * f64::EPSILON)),
        }
    }

    fn ritter64<S: PointSet + ?Sized>(points: &S) -> S64 {
        let n = points.len();
        // Most separated pair among the six extreme points along x, y, z.
        let mut lo = [0usize; 3];
        let mut hi = [0usize; 3];
        for i in 1..n {
            let p = points.point(i);
            for k in 0..3 {
                if p[k] < points.point(lo[k])[k] {
                    lo[k] = i;
                }
                if p[k] > points.point(hi[k])[k] {
                    hi[k] = i;
                }
            }
        }
        let mut best = (lo[0], hi[0]);
        let mut best_d = -1.0;
        for k in 0..3 {
            let dd = (d(points.point(hi[k])) - d(points.point(lo[k]))).length_squared();
            if dd > best_d {
                best_d = dd;
                best = (lo[k], hi[k]);
            }
        }
        let mut s = S64::from2(d(points.point(best.0)), d(points.point(best.1)));
        for i in 0..n {
            grow(&mut s, d(points.point(i)));
        }
        s
    }

    /// Ritter's two-pass approximation: start from the most separated pair of
    /// axis-extreme points, then grow just enough for each point outside.
    pub fn ritter<S: PointSet + ?Sized>(points: &S) -> Sphere {
        if points.is_empty() {
            return Sphere::EMPTY;
        }
        let s = Self::ritter64(points);
        Self::conservative(points, s.c)
    }

    /// Ritter, then `iterations` rounds of "shrink by 5%, regrow over a shuffled
    /// order", keeping the smallest sphere seen.
    pub fn ritter_refined<S: PointSet + ?Sized>(points: &S, iterations: usize) -> Sphere {
        if points.is_empty() {
            return Sphere::EMPTY;
        }
        let mut best = Self::ritter64(points);
        let mut s = best;
        let n = points.len();
        for it in 0..iterations {
            s.r *= 0.95;
            let order = Shuffle::new(n, it as u64 + 1);
            for i in 0..n {
                grow(&mut s, d(points.point(order.at(i))));
            }
            if s.r < best.r {
                best = s;
            }
        }
        Self::conservative(points, best.c)
    }

    /// The exact minimal enclosing sphere (Welzl), as nested loops over a
    /// pseudo-random order: expected linear time, no recursion, no buffer.
    pub fn welzl<S: PointSet + ?Sized>(points: &S) -> Sphere {
        let n = points.len();
        if n == 0 {
            return Sphere::EMPTY;
        }
        let order = Shuffle::new(n, 0x5eed);
        let pt = |i: usize| d(points.point(order.at(i)));
        let mut s = S64 { c: pt(0), r: 0.0 };
        for i in 1..n {
            let p = pt(i);
            if s.contains(p) {
                continue;
            }
            s = S64 { c: p, r: 0.0 };
            for j in 0..i {
                let q = pt(j);
                if s.contains(q) {
                    continue;
                }
                s = S64::from2(p, q);
                for k in 0..j {
                    let r = pt(k);
                    if s.contains(r) {
                        continue;
                    }
                    s = S64::from3(p, q, r);
                    for l in 0..k {
                        let t = pt(l);
                        if !s.contains(t) {
                            s = S64::from4(p, q, r, t);
                        }
                    }
                }
            }
        }
        Self::conservative(points, s.c)
    }
}

/// Ritter's growth step for a ball: the smallest sphere containing `s` and the ball.
#[inline]
fn grow_ball(s: &mut S64, c: DVec3, r: f64) {
    let v = c - s.c;
    let dist = v.length();
    if dist + r <= s.r {
        return;
    }
    if dist + s.r <= r || dist == 0.0 {
        *s = S64 { c, r: r.max(s.r) };
        return;
    }
    let new_r = (s.r + dist + r) * 0.5;
    s.c += v * ((new_r - s.r) / dist);
    s.r = new_r;
}

/// Ritter's growth step: move the centre towards `p` just enough to include it.
#[inline]
fn grow(s: &mut S64, p: DVec3) {
    let v = p - s.c;
    let dist = v.length();
    if dist > s.r {
        let new_r = (s.r + dist) * 0.5;
        s.c += v * ((new_r - s.r) / dist);
        s.r = new_r;
    }
}

impl BoundingVolume for Sphere {
    const NAME: &'static str = "sphere";
    const EMPTY: Self = Sphere::EMPTY;
    const ZERO: Self = Sphere::new(Vec3::ZERO, 0.0);

    fn fit<S: PointSet + ?Sized>(points: &S) -> Self {
        Sphere::ritter_refined(points, DEFAULT_REFINEMENTS)
    }

    /// Ritter over the boxes' circumscribed balls: `n` balls instead of `8n`
    /// corners. A sphere containing every ball contains every box.
    fn fit_boxes<S: super::BoxSet + ?Sized>(boxes: &S, _union: &Aabb) -> Self {
        let n = boxes.len();
        if n == 0 {
            return Sphere::EMPTY;
        }
        let ball = |i: usize| {
            let b = boxes.aabb(i);
            let c = d(b.min) * 0.5 + d(b.max) * 0.5;
            (c, (d(b.max) - c).length())
        };
        let (mut lo, mut hi) = ([0usize; 3], [0usize; 3]);
        for i in 1..n {
            let c = ball(i).0;
            for k in 0..3 {
                if c[k] < ball(lo[k]).0[k] {
                    lo[k] = i;
                }
                if c[k] > ball(hi[k]).0[k] {
                    hi[k] = i;
                }
            }
        }
        let mut s = S64 {
            c: ball(0).0,
            r: ball(0).1,
        };
        let mut widest = -1.0;
        for k in 0..3 {
            let (a, b) = (ball(lo[k]), ball(hi[k]));
            let w = (a.0 - b.0).length() + a.1 + b.1;
            if w > widest {
                widest = w;
                s = S64 { c: a.0, r: a.1 };
                grow_ball(&mut s, b.0, b.1);
            }
        }
        for i in 0..n {
            let (c, r) = ball(i);
            grow_ball(&mut s, c, r);
        }
        let mut best = s;
        for it in 0..2 {
            s.r *= 0.95;
            let order = Shuffle::new(n, it + 1);
            for i in 0..n {
                let (c, r) = ball(order.at(i));
                grow_ball(&mut s, c, r);
            }
            if s.r < best.r {
                best = s;
            }
        }
        let center = best.c.as_vec3();
        let cd = d(center);
        let mut radius: f64 = 0.0;
        for i in 0..n {
            let (c, r) = ball(i);
            radius = radius.max((c - cd).length() + r);
        }
        Sphere {
            center,
            radius: round::up(radius * (1.0 + 16.0 * f64::EPSILON)),
        }
    }

    fn from_aabb(aabb: &Aabb) -> Self {
        if BoundingVolume::is_empty(aabb) {
            return Sphere::EMPTY;
        }
        let c = d(aabb.min) * 0.5 + d(aabb.max) * 0.5;
        // All eight corners: in exact arithmetic they are equally far from the
        // centre, but after rounding the centre any one of them may be the
        // farthest.
        let corners: [Vec3; 8] = core::array::from_fn(|i| aabb.corner(i));
        Sphere::conservative(&corners, c)
    }

    fn merge(&self, other: &Self) -> Self {
        if self.is_empty() {
            return *other;
        }
        if other.is_empty() {
            return *self;
        }
        let (c1, c2) = (d(self.center), d(other.center));
        let (r1, r2) = (self.radius as f64, other.radius as f64);
        let dist = (c2 - c1).length();
        if dist + r2 <= r1 {
            return *self;
        }
        if dist + r1 <= r2 {
            return *other;
        }
        let r = (dist + r1 + r2) * 0.5;
        let c = c1 + (c2 - c1) * ((r - r1) / dist);
        let center = c.as_vec3();
        let cd = d(center);
        let radius = ((d(self.center) - cd).length() + r1).max((c2 - cd).length() + r2);
        Sphere {
            center,
            radius: round::up(radius * (1.0 + 4.0 * f64::EPSILON)),
        }
    }

    #[inline]
    fn overlaps(&self, other: &Self) -> bool {
        // Each radius on its own: the empty sphere (radius -1) overlaps
        // nothing, not even a sphere of radius 1 or more around its centre.
        let r = self.radius + other.radius;
        self.radius >= 0.0
            && other.radius >= 0.0
            && (self.center - other.center).length_squared() <= r * r * (1.0 + round::SLACK)
    }

    #[inline]
    fn overlaps_aabb(&self, aabb: &Aabb) -> bool {
        self.radius >= 0.0
            && aabb.distance_squared(self.center)
                <= self.radius * self.radius * (1.0 + round::SLACK)
    }

    fn contains_point(&self, p: Vec3) -> bool {
        (d(p) - d(self.center)).length() <= self.radius as f64
    }

    fn contains(&self, other: &Self) -> bool {
        other.is_empty()
            || (d(other.center) - d(self.center)).length() + other.radius as f64
                <= self.radius as f64
    }

    fn contains_aabb(&self, aabb: &Aabb) -> bool {
        // The farthest corner decides.
        let c = self.center;
        let far = Vec3::select((c - aabb.min).cmpgt(aabb.max - c), aabb.min, aabb.max);
        self.contains_point(far)
    }

    fn volume(&self) -> f32 {
        let r = self.radius.max(0.0);
        4.0 / 3.0 * core::f32::consts::PI * r * r * r
    }

    fn surface_area(&self) -> f32 {
        let r = self.radius.max(0.0);
        4.0 * core::f32::consts::PI * r * r
    }

    fn surface_area_scaled(&self, scale: f32) -> f32 {
        let r = self.radius.max(0.0) * scale;
        4.0 * core::f32::consts::PI * r * r
    }

    fn volume_scaled(&self, scale: f32) -> f32 {
        let r = self.radius.max(0.0) * scale;
        4.0 / 3.0 * core::f32::consts::PI * r * r * r
    }

    fn size(&self) -> f32 {
        self.radius
    }

    fn aabb(&self) -> Aabb {
        if self.is_empty() {
            return Aabb::EMPTY;
        }
        let r = Vec3::splat(self.radius);
        // Outward rounding of c +/- r.
        let mut b = Aabb::new(self.center - r, self.center + r);
        for k in 0..3 {
            b.min[k] = round::down(self.center[k] as f64 - self.radius as f64);
            b.max[k] = round::up(self.center[k] as f64 + self.radius as f64);
        }
        b
    }

    fn is_empty(&self) -> bool {
        self.radius < 0.0 || self.radius.is_nan()
    }

    /// Moves the centre; the radius grows by a few `f32` ulps of the moved
    /// coordinates so that points moved and rounded by [`Rigid::apply`](crate::Rigid::apply) stay inside.
    fn transformed(&self, t: &crate::Rigid) -> Self {
        if self.is_empty() {
            return *self;
        }
        let c = t.apply(self.center);
        let scale = c.abs().max_element() as f64 + self.radius as f64;
        let r = self.radius as f64 + 4.0 * f32::EPSILON as f64 * scale;
        Sphere::new(c, crate::round::up(r))
    }

    /// The moved sphere's radius times sqrt(3): the ball around the cube that
    /// bounds the moved ball, so it contains the new bounding box of anything
    /// inside.
    fn transformed_with_boxes(&self, t: &crate::Rigid) -> Self {
        let s = self.transformed(t);
        if s.is_empty() {
            return s;
        }
        // sqrt(3) rounded up, then the product rounded up.
        Sphere::new(
            s.center,
            crate::round::up(s.radius as f64 * 1.732_050_807_568_877_3 * (1.0 + 1e-15)),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f32::consts::PI;

    fn close(got: f32, want: f32, what: &str) {
        assert!(
            (got - want).abs() <= 1e-5 * want.abs().max(1.0),
            "{what}: {got} against {want}"
        );
    }

    /// The minimal enclosing sphere by brute force, sharing no code with
    /// the fits: every sphere through two points as a diameter, through
    /// three on a great circle, or through four, solved here by Cramer's
    /// rule; the smallest that holds every point.
    fn minimal_radius(pts: &[Vec3]) -> f64 {
        let p: [DVec3; 8] =
            core::array::from_fn(|i| pts.get(i).map_or(DVec3::ZERO, |v| v.as_dvec3()));
        let n = pts.len();
        let holds = |c: DVec3, r: f64| {
            p[..n]
                .iter()
                .all(|q| (*q - c).length() <= r * (1.0 + 1e-9) + 1e-12)
        };
        let mut best = f64::INFINITY;
        let mut consider = |c: DVec3, r: f64| {
            if r < best && holds(c, r) {
                best = r;
            }
        };
        // Centre x solving 2 (q_k - q_0) . x = |q_k|^2 - |q_0|^2 for the
        // given rows, within the plane of the points when there are three.
        let det3 = |a: DVec3, b: DVec3, c: DVec3| a.dot(b.cross(c));
        for i in 0..n {
            for j in i + 1..n {
                consider((p[i] + p[j]) / 2.0, (p[i] - p[j]).length() / 2.0);
                for k in j + 1..n {
                    let (u, v) = (p[j] - p[i], p[k] - p[i]);
                    let w = u.cross(v);
                    let rows = [u * 2.0, v * 2.0, w];
                    let rhs = [u.length_squared(), v.length_squared(), 0.0];
                    let det = det3(rows[0], rows[1], rows[2]);
                    if det.abs() > 1e-12 {
                        let col = |m: usize| {
                            let r: [DVec3; 3] = core::array::from_fn(|t| {
                                let mut row = rows[t].to_array();
                                row[m] = rhs[t];
                                DVec3::from_array(row)
                            });
                            det3(r[0], r[1], r[2]) / det
                        };
                        let x = DVec3::new(col(0), col(1), col(2));
                        consider(p[i] + x, x.length());
                    }
                    for l in k + 1..n {
                        let t = p[l] - p[i];
                        let rows = [u * 2.0, v * 2.0, t * 2.0];
                        let rhs = [u.length_squared(), v.length_squared(), t.length_squared()];
                        let det = det3(rows[0], rows[1], rows[2]);
                        if det.abs() > 1e-12 {
                            let col = |m: usize| {
                                let r: [DVec3; 3] = core::array::from_fn(|s| {
                                    let mut row = rows[s].to_array();
                                    row[m] = rhs[s];
                                    DVec3::from_array(row)
                                });
                                det3(r[0], r[1], r[2]) / det
                            };
                            let x = DVec3::new(col(0), col(1), col(2));
                            consider(p[i] + x, x.length());
                        }
                    }
                }
            }
        }
        best
    }

    #[test]
    fn measures_by_value() {
        let s = Sphere::new(Vec3::new(1.0, 2.0, 3.0), 2.0);
        close(s.volume(), 4.0 / 3.0 * PI * 8.0, "volume");
        close(s.surface_area(), 16.0 * PI, "area");
        close(s.surface_area_scaled(0.5), 4.0 * PI, "scaled area");
        close(s.volume_scaled(0.5), 4.0 / 3.0 * PI, "scaled volume");
        close(
            s.volume_scaled(3.0),
            4.0 / 3.0 * PI * 216.0,
            "scaled volume up",
        );
        assert_eq!(s.size(), 2.0);
        assert_eq!(
            s.aabb(),
            Aabb::new(Vec3::new(-1.0, 0.0, 1.0), Vec3::new(3.0, 4.0, 5.0))
        );
        for empty in [Sphere::EMPTY, Sphere::new(Vec3::ONE, f32::NAN)] {
            assert!(empty.is_empty());
            assert_eq!(empty.volume(), 0.0);
            assert_eq!(empty.surface_area_scaled(2.0), 0.0);
            assert_eq!(empty.aabb(), Aabb::EMPTY);
        }
        assert!(!Sphere::new(Vec3::ONE, 0.0).is_empty());
    }

    /// Each predicate on a near case either side of its boundary, nested
    /// cases and the empty sphere.
    #[test]
    fn predicates_either_side_of_the_boundary() {
        let s = Sphere::new(Vec3::ZERO, 1.0);
        let at = |x: f32, r: f32| Sphere::new(Vec3::new(x, 0.0, 0.0), r);
        assert!(s.overlaps(&at(2.0, 1.0))); // touching
        assert!(!s.overlaps(&at(2.01, 1.0)));
        assert!(s.overlaps(&at(0.1, 0.1))); // nested
        assert!(!s.overlaps(&Sphere::EMPTY));
        let cube = |x: f32| Aabb::new(Vec3::new(x, -0.5, -0.5), Vec3::new(x + 1.0, 0.5, 0.5));
        assert!(s.overlaps_aabb(&cube(0.999)));
        assert!(!s.overlaps_aabb(&cube(1.01)));
        assert!(s.overlaps_aabb(&cube(-0.5)));
        assert!(!Sphere::EMPTY.overlaps_aabb(&cube(0.0)));
        assert!(s.contains_point(Vec3::new(0.0, 1.0, 0.0)));
        assert!(!s.contains_point(Vec3::new(0.0, 1.001, 0.0)));
        assert!(s.contains(&at(0.5, 0.5)));
        assert!(!s.contains(&at(0.5, 0.51)));
        assert!(s.contains(&Sphere::EMPTY));
        let small = Aabb::new(Vec3::splat(-0.5), Vec3::splat(0.5)); // corner at 0.866
        assert!(s.contains_aabb(&small));
        assert!(!s.contains_aabb(&Aabb::new(Vec3::splat(-0.5), Vec3::new(0.5, 0.5, 0.8))));
        // The far corner decides, whichever side it is on.
        assert!(!s.contains_aabb(&Aabb::new(Vec3::new(-0.8, -0.5, -0.5), Vec3::splat(0.5))));
    }

    #[test]
    fn merge_is_the_smallest_sphere_around_both() {
        let a = Sphere::new(Vec3::ZERO, 1.0);
        let b = Sphere::new(Vec3::new(4.0, 0.0, 0.0), 1.0);
        for m in [a.merge(&b), b.merge(&a)] {
            close(m.radius, 3.0, "radius");
            close(m.center.x, 2.0, "centre");
            assert!(m.contains(&a) && m.contains(&b));
        }
        let c = Sphere::new(Vec3::new(4.0, 0.0, 0.0), 3.0);
        let m = a.merge(&c);
        close(m.radius, 4.0, "unequal radius");
        close(m.center.x, 3.0, "unequal centre");
        let inner = Sphere::new(Vec3::new(0.5, 0.0, 0.0), 0.25);
        assert_eq!(a.merge(&inner), a);
        assert_eq!(inner.merge(&a), a);
        assert_eq!(a.merge(&Sphere::EMPTY), a);
        assert_eq!(Sphere::EMPTY.merge(&a), a);
    }

    /// Welzl equals the brute-force minimal sphere on random sets (which
    /// exercise the sphere through two, three and four points) and on sets
    /// whose answer is known: an obtuse triangle (two points span it), a
    /// regular tetrahedron, coplanar and collinear points.
    #[test]
    fn welzl_is_the_minimal_sphere() {
        let third = (3.0f32).sqrt();
        let known: [(&[Vec3], f32); 5] = [
            (
                &[
                    Vec3::new(-1.0, 0.0, 0.0),
                    Vec3::new(1.0, 0.0, 0.0),
                    Vec3::new(0.0, 0.1, 0.0),
                ],
                1.0,
            ),
            (
                &[
                    Vec3::new(1.0, 0.0, 0.0),
                    Vec3::new(-0.5, third / 2.0, 0.0),
                    Vec3::new(-0.5, -third / 2.0, 0.0),
                ],
                1.0,
            ),
            (
                &[
                    Vec3::new(1.0, 1.0, 1.0),
                    Vec3::new(1.0, -1.0, -1.0),
                    Vec3::new(-1.0, 1.0, -1.0),
                    Vec3::new(-1.0, -1.0, 1.0),
                ],
                third,
            ),
            (
                &[
                    Vec3::new(1.0, 0.0, 0.0),
                    Vec3::new(0.0, 1.0, 0.0),
                    Vec3::new(-1.0, 0.0, 0.0),
                    Vec3::new(0.0, -1.0, 0.0),
                    Vec3::ZERO,
                ],
                1.0,
            ),
            (
                &[
                    Vec3::ZERO,
                    Vec3::new(1.0, 1.0, 1.0),
                    Vec3::new(3.0, 3.0, 3.0),
                    Vec3::new(2.0, 2.0, 2.0),
                ],
                1.5 * third,
            ),
        ];
        for (pts, r) in known {
            let w = Sphere::welzl(pts);
            close(w.radius, r, "known set");
            assert!(pts.iter().all(|&p| w.contains_point(p)));
        }
        let mut next = crate::test_floats(41);
        for n in 1..=8 {
            for _ in 0..40 {
                let pts: [Vec3; 8] =
                    core::array::from_fn(|_| Vec3::new(next(), next(), next()) * 3.0);
                let pts = &pts[..n];
                let w = Sphere::welzl(pts);
                assert!(pts.iter().all(|&p| w.contains_point(p)));
                close(w.radius, minimal_radius(pts) as f32, "random set");
                // The approximations contain everything too, and are no smaller.
                for s in [
                    Sphere::ritter(pts),
                    Sphere::ritter_refined(pts, 4),
                    Sphere::fit(pts),
                ] {
                    assert!(pts.iter().all(|&p| s.contains_point(p)));
                    assert!(s.radius >= w.radius * (1.0 - 1e-6));
                    assert!(
                        s.radius <= w.radius * 1.5 + 1e-6,
                        "{} against {}",
                        s.radius,
                        w.radius
                    );
                }
            }
        }
    }

    /// Ritter traced by hand on a triangle: the x extremes span the first
    /// sphere (radius 1 about the origin), the apex at height sqrt(3) lies
    /// outside, and one growth step gives radius (1 + sqrt 3) / 2.
    #[test]
    fn ritter_grows_as_traced_by_hand() {
        let pts = [
            Vec3::new(-1.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 3.0f32.sqrt(), 0.0),
        ];
        let s = Sphere::ritter(&pts);
        close(s.radius, (1.0 + 3.0f32.sqrt()) / 2.0, "grown radius");
        close(s.center.y, (3.0f32.sqrt() - 1.0) / 2.0, "grown centre");
        close(s.center.x, 0.0, "centre x");
        assert!(Sphere::ritter::<[Vec3]>(&[]).is_empty());
        assert!(Sphere::ritter_refined::<[Vec3]>(&[], 3).is_empty());
        assert!(Sphere::welzl::<[Vec3]>(&[]).is_empty());
    }

    /// From boxes: every box inside, no larger than the sphere around the
    /// boxes' corners by more than the Ritter slack; one box gives its
    /// circumscribed sphere.
    #[test]
    fn fit_from_boxes_holds_every_box() {
        let one = Aabb::new(Vec3::new(1.0, 2.0, 3.0), Vec3::new(3.0, 4.0, 5.0));
        let s = Sphere::fit_boxes(&[one][..], &one);
        close(s.radius, 3.0f32.sqrt(), "one box");
        close(s.center.x, 2.0, "one box centre");
        assert_eq!(Sphere::from_aabb(&one).center, Vec3::new(2.0, 3.0, 4.0));
        close(Sphere::from_aabb(&one).radius, 3.0f32.sqrt(), "from_aabb");
        assert!(Sphere::from_aabb(&Aabb::EMPTY).is_empty());
        let mut next = crate::test_floats(43);
        for _ in 0..30 {
            let boxes: [Aabb; 6] = core::array::from_fn(|_| {
                let c = Vec3::new(next(), next(), next()) * 4.0;
                let h = Vec3::new(next(), next(), next()).abs();
                Aabb::new(c - h, c + h)
            });
            let union = boxes.iter().fold(Aabb::EMPTY, |u, b| u.union(b));
            let s = Sphere::fit_boxes(&boxes[..], &union);
            assert!(boxes.iter().all(|b| s.contains_aabb(b)));
            let corners: [Vec3; 48] = core::array::from_fn(|i| boxes[i / 8].corner(i % 8));
            let tight = minimal_radius(&corners[..8]).max(0.0) as f32; // a lower bound: one box's corners
            assert!(s.radius >= tight * (1.0 - 1e-6));
            assert!(s.radius <= Sphere::welzl(&corners[..]).radius * 1.5);
        }
    }
}
