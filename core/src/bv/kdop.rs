//! Discrete-orientation polytopes (k-DOPs): slabs along `K` fixed directions.
//!
//! A k-DOP is the intersection of `K` slabs `min[i] <= d_i . x <= max[i]` with
//! directions fixed for all volumes, so overlap is `K` interval tests and a
//! merge is `K` min/max pairs. The directions have components in {-1, 0, 1}:
//!
//! * `K = 3`: the coordinate axes (6-DOP, an AABB);
//! * `K = 7`: axes + the four body diagonals (14-DOP);
//! * `K = 9`: axes + the six face diagonals (18-DOP);
//! * `K = 13`: all of them (26-DOP).
//!
//! Slab bounds are computed in `f64` and rounded outward. Volume and surface
//! area are the polytope's own (the intersection of the slabs, computed face
//! by face in [`polytope`](super::polytope)), so a k-DOP measures smaller than
//! its enclosing box wherever a diagonal plane cuts a corner or an edge off,
//! and exactly as its box where none does.
//!
//! The exact measures cost microseconds (a 26-DOP clips up to 26 faces), a
//! box's a few nanoseconds. Builders evaluate a cost millions of times, so a
//! k-DOP's *cost* measures ([`BoundingVolume::cost_area_scaled`],
//! [`cost_volume_scaled`](BoundingVolume::cost_volume_scaled), `size`) are its
//! enclosing box's; statistics and reports use the exact ones. [`ExactKdop`]
//! is a k-DOP whose builders and descent use the exact measures, to measure
//! what they buy.

use super::polytope::Planes;
use super::{Aabb, Axes, BoundingVolume, PointSet};
use crate::round;
use glam::{DVec3, Vec3};

/// A k-DOP over `K` direction pairs; see the module docs for the allowed `K`.
///
/// ```
/// use bvhkit::{Aabb, BoundingVolume, Dop14};
/// use glam::Vec3;
/// let tri = [Vec3::ZERO, Vec3::X, Vec3::Y];
/// let dop = Dop14::fit(&tri);
/// // The box corner (1,1,0) is outside the triangle's 14-DOP but inside its AABB.
/// assert!(Aabb::fit(&tri).contains_point(Vec3::new(1.0, 1.0, 0.0)));
/// assert!(!dop.contains_point(Vec3::new(1.0, 1.0, 0.0)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Kdop<const K: usize> {
    /// Lower slab bound along each direction.
    pub min: [f32; K],
    /// Upper slab bound along each direction.
    pub max: [f32; K],
}

/// 14-DOP: axes and body diagonals.
pub type Dop14 = Kdop<7>;
/// 18-DOP: axes and face diagonals.
pub type Dop18 = Kdop<9>;
/// 26-DOP: axes, body and face diagonals.
pub type Dop26 = Kdop<13>;

const AXES: [[i8; 3]; 3] = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
const BODY: [[i8; 3]; 4] = [[1, 1, 1], [1, 1, -1], [1, -1, 1], [1, -1, -1]];
const FACE: [[i8; 3]; 6] = [
    [1, 1, 0],
    [1, -1, 0],
    [1, 0, 1],
    [1, 0, -1],
    [0, 1, 1],
    [0, 1, -1],
];

impl<const K: usize> Kdop<K> {
    const CHECK: () = assert!(
        K == 3 || K == 7 || K == 9 || K == 13,
        "Kdop<K>: K must be 3, 7, 9 or 13"
    );

    /// Direction `i` (unnormalised, components in {-1, 0, 1}).
    pub const fn direction(i: usize) -> [i8; 3] {
        #[allow(clippy::let_unit_value)]
        let () = Self::CHECK;
        if i < 3 {
            AXES[i]
        } else if K == 9 {
            FACE[i - 3]
        } else if i < 7 {
            BODY[i - 3]
        } else {
            FACE[i - 7]
        }
    }

    /// The empty k-DOP.
    pub const EMPTY: Self = Kdop {
        min: [f32::INFINITY; K],
        max: [f32::NEG_INFINITY; K],
    };

    #[inline]
    fn dot64(i: usize, p: DVec3) -> f64 {
        let d = Self::direction(i);
        d[0] as f64 * p.x + d[1] as f64 * p.y + d[2] as f64 * p.z
    }

    /// The polytope's `(volume, area)` in units of its box's longest side
    /// `s`, and `s`; `None` when the measures are the box's: no diagonal
    /// plane cuts the box, or the box is empty, a point or not finite.
    fn polytope(&self) -> Option<(f64, f64, f64)> {
        let b = self.aabb();
        if K == 3 || self.is_empty() || !(b.min.is_finite() && b.max.is_finite()) {
            return None;
        }
        let (lo, hi) = (b.min.as_dvec3(), b.max.as_dvec3());
        let s = (hi - lo).max_element();
        if s <= 0.0 {
            return None;
        }
        // Centre the box on the origin and make its longest side 1.
        let (c, inv) = ((lo + hi) * 0.5, 1.0 / s);
        let half = (hi - lo) * 0.5 * inv;
        let mut planes = Planes::new();
        for (axis, h) in [DVec3::X, DVec3::Y, DVec3::Z]
            .into_iter()
            .zip(half.to_array())
        {
            planes.push(axis, h);
            planes.push(-axis, h);
        }
        let mut cuts = false;
        for i in 3..K {
            let d = Self::direction(i);
            let d = DVec3::new(d[0] as f64, d[1] as f64, d[2] as f64);
            let len = d.length();
            let n = d / len;
            // How far the box reaches along n: a plane at least this far out
            // cuts nothing. A plane within 1e-6 of it (a few f32 roundings:
            // the slabs of `from_aabb` touch the box's corners and edges,
            // each rounded outward by an ulp) cuts off at most an edge
            // prism of volume 1e-12 of the box's, below what f32 can
            // show, so it counts as not cutting and the box's own f32
            // measures stand, to the bit.
            let reach = n.abs().dot(half) - 1e-6;
            let centre = d.dot(c);
            let upper = (self.max[i] as f64 - centre) * inv / len;
            let lower = (centre - self.min[i] as f64) * inv / len;
            if upper < reach {
                planes.push(n, upper);
                cuts = true;
            }
            if lower < reach {
                planes.push(-n, lower);
                cuts = true;
            }
        }
        if !cuts {
            return None;
        }
        let (v, a) = planes.measures();
        // A flat slab: the two sides' terms cancel only up to rounding.
        let flat = (0..K).any(|i| self.max[i] <= self.min[i]);
        Some((if flat { 0.0 } else { v }, a, s))
    }

    /// Rounds an f64 interval outward to f32, with a pad for the f64 sum's own rounding.
    fn store(&mut self, i: usize, lo: f64, hi: f64, magnitude: f64) {
        let pad = magnitude * 4.0 * f64::EPSILON;
        self.min[i] = round::down(lo - pad);
        self.max[i] = round::up(hi + pad);
    }
}

impl<const K: usize> BoundingVolume for Kdop<K> {
    const NAME: &'static str = match K {
        3 => "6-dop",
        7 => "14-dop",
        9 => "18-dop",
        _ => "26-dop",
    };
    const EMPTY: Self = Kdop::EMPTY;
    const ZERO: Self = Kdop {
        min: [0.0; K],
        max: [0.0; K],
    };

    fn fit<S: PointSet + ?Sized>(points: &S) -> Self {
        let mut lo = [f64::INFINITY; K];
        let mut hi = [f64::NEG_INFINITY; K];
        let mut mag: f64 = 0.0;
        for j in 0..points.len() {
            let p = points.point(j).as_dvec3();
            mag = mag.max(p.abs().element_sum());
            for i in 0..K {
                let t = Self::dot64(i, p);
                lo[i] = lo[i].min(t);
                hi[i] = hi[i].max(t);
            }
        }
        let mut k = Self::EMPTY;
        if points.is_empty() {
            return k;
        }
        for i in 0..K {
            k.store(i, lo[i], hi[i], mag);
        }
        k
    }

    fn from_aabb(aabb: &Aabb) -> Self {
        if BoundingVolume::is_empty(aabb) {
            return Self::EMPTY;
        }
        let (lo, hi) = (aabb.min.as_dvec3(), aabb.max.as_dvec3());
        let mag = lo.abs().max(hi.abs()).element_sum();
        let mut k = Self::EMPTY;
        for i in 0..K {
            let d = Self::direction(i);
            let (mut a, mut b) = (0.0, 0.0);
            for c in 0..3 {
                let w = d[c] as f64;
                let (x, y) = (w * lo[c], w * hi[c]);
                a += x.min(y);
                b += x.max(y);
            }
            k.store(i, a, b, mag);
        }
        k
    }

    /// One slab computation per box instead of eight corner projections.
    fn fit_boxes<S: super::BoxSet + ?Sized>(boxes: &S, _union: &Aabb) -> Self {
        let mut k = Self::EMPTY;
        for i in 0..boxes.len() {
            k = k.merge(&Self::from_aabb(&boxes.aabb(i)));
        }
        k
    }

    fn merge(&self, other: &Self) -> Self {
        let mut k = *self;
        for i in 0..K {
            k.min[i] = k.min[i].min(other.min[i]);
            k.max[i] = k.max[i].max(other.max[i]);
        }
        k
    }

    #[inline]
    fn overlaps(&self, other: &Self) -> bool {
        (0..K).all(|i| self.min[i] <= other.max[i] && other.min[i] <= self.max[i])
    }

    fn overlaps_aabb(&self, aabb: &Aabb) -> bool {
        self.overlaps(&Self::from_aabb(aabb))
    }

    fn contains_point(&self, p: Vec3) -> bool {
        let p = p.as_dvec3();
        (0..K).all(|i| {
            let t = Self::dot64(i, p);
            self.min[i] as f64 <= t && t <= self.max[i] as f64
        })
    }

    fn contains(&self, other: &Self) -> bool {
        other.is_empty()
            || (0..K).all(|i| self.min[i] <= other.min[i] && other.max[i] <= self.max[i])
    }

    /// The polytope's volume: at most the enclosing box's, equal to it when
    /// no diagonal plane cuts the box.
    ///
    /// ```
    /// use bvhkit::{BoundingVolume, Dop14};
    /// use glam::Vec3;
    /// // A tetrahedron at a corner of the unit cube: its 14-DOP is the
    /// // tetrahedron itself (volume 1/6), its box the cube.
    /// let dop = Dop14::fit(&[Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z]);
    /// assert!((dop.volume() - 1.0 / 6.0).abs() < 1e-5);
    /// assert!((dop.aabb().volume() - 1.0).abs() < 1e-5);
    /// ```
    fn volume(&self) -> f32 {
        self.volume_scaled(1.0)
    }

    /// The polytope's surface area: at most the enclosing box's.
    fn surface_area(&self) -> f32 {
        self.surface_area_scaled(1.0)
    }

    fn surface_area_scaled(&self, scale: f32) -> f32 {
        let boxed = self.aabb().surface_area_scaled(scale);
        match self.polytope() {
            // Computed in f64 with the lengths scaled first, so it overflows
            // f32 only where the box's area does.
            Some((_, a, s)) => {
                let l = s * scale as f64;
                ((a * l * l) as f32).min(boxed)
            }
            None => boxed,
        }
    }

    fn volume_scaled(&self, scale: f32) -> f32 {
        let boxed = self.aabb().volume_scaled(scale);
        match self.polytope() {
            Some((v, _, s)) => {
                let l = s * scale as f64;
                ((v * l * l * l) as f32).min(boxed)
            }
            None => boxed,
        }
    }

    /// The enclosing box's area: see the module docs.
    #[inline]
    fn cost_area_scaled(&self, scale: f32) -> f32 {
        self.aabb().surface_area_scaled(scale)
    }

    /// The enclosing box's volume: see the module docs.
    #[inline]
    fn cost_volume_scaled(&self, scale: f32) -> f32 {
        self.aabb().volume_scaled(scale)
    }

    fn aabb(&self) -> Aabb {
        Aabb::new(
            Vec3::new(self.min[0], self.min[1], self.min[2]),
            Vec3::new(self.max[0], self.max[1], self.max[2]),
        )
    }

    fn axes(&self) -> Axes {
        let mut a = Axes::XYZ;
        for i in 0..K {
            let d = Self::direction(i);
            a.axes[i] = Vec3::new(d[0] as f32, d[1] as f32, d[2] as f32).normalize();
        }
        a.len = K;
        a
    }

    fn is_empty(&self) -> bool {
        !(0..K).all(|i| self.min[i] <= self.max[i])
    }
}

/// A k-DOP whose builders and size-based descent use its exact polytope
/// measures rather than its box's (see the module docs): trees built with it
/// are the ones the exact measures choose, at microseconds per cost
/// evaluation. Everything else is the wrapped [`Kdop`]'s.
///
/// ```
/// use bvhkit::{BoundingVolume, Dop14, ExactKdop};
/// use glam::Vec3;
/// let corner = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
/// let (dop, exact) = (Dop14::fit(&corner), ExactKdop::<7>::fit(&corner));
/// assert_eq!(exact.0, dop);
/// // The tetrahedron's own volume against its box's.
/// assert!((exact.cost_volume_scaled(1.0) - 1.0 / 6.0).abs() < 1e-5);
/// assert!((dop.cost_volume_scaled(1.0) - 1.0).abs() < 1e-5); // its box's
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExactKdop<const K: usize>(pub Kdop<K>);

impl<const K: usize> BoundingVolume for ExactKdop<K> {
    const NAME: &'static str = match K {
        3 => "6-dop-exact",
        7 => "14-dop-exact",
        9 => "18-dop-exact",
        _ => "26-dop-exact",
    };
    const EMPTY: Self = ExactKdop(Kdop::EMPTY);
    const ZERO: Self = ExactKdop(<Kdop<K> as BoundingVolume>::ZERO);

    fn fit<S: PointSet + ?Sized>(points: &S) -> Self {
        ExactKdop(Kdop::fit(points))
    }
    fn from_aabb(aabb: &Aabb) -> Self {
        ExactKdop(Kdop::from_aabb(aabb))
    }
    fn fit_boxes<S: super::BoxSet + ?Sized>(boxes: &S, union: &Aabb) -> Self {
        ExactKdop(Kdop::fit_boxes(boxes, union))
    }
    fn merge(&self, other: &Self) -> Self {
        ExactKdop(self.0.merge(&other.0))
    }
    fn overlaps(&self, other: &Self) -> bool {
        self.0.overlaps(&other.0)
    }
    fn overlaps_aabb(&self, aabb: &Aabb) -> bool {
        self.0.overlaps_aabb(aabb)
    }
    fn contains_point(&self, p: Vec3) -> bool {
        self.0.contains_point(p)
    }
    fn contains(&self, other: &Self) -> bool {
        self.0.contains(&other.0)
    }
    fn contains_aabb(&self, aabb: &Aabb) -> bool {
        self.0.contains_aabb(aabb)
    }
    fn volume(&self) -> f32 {
        self.0.volume()
    }
    fn surface_area(&self) -> f32 {
        self.0.surface_area()
    }
    fn surface_area_scaled(&self, scale: f32) -> f32 {
        self.0.surface_area_scaled(scale)
    }
    fn volume_scaled(&self, scale: f32) -> f32 {
        self.0.volume_scaled(scale)
    }
    /// The polytope's own area.
    fn cost_area_scaled(&self, scale: f32) -> f32 {
        self.0.surface_area_scaled(scale)
    }
    /// The polytope's own volume.
    fn cost_volume_scaled(&self, scale: f32) -> f32 {
        self.0.volume_scaled(scale)
    }
    fn aabb(&self) -> Aabb {
        self.0.aabb()
    }
    fn axes(&self) -> Axes {
        self.0.axes()
    }
    fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
    fn transformed(&self, t: &crate::Rigid) -> Self {
        ExactKdop(self.0.transformed(t))
    }
    fn transformed_with_boxes(&self, t: &crate::Rigid) -> Self {
        ExactKdop(self.0.transformed_with_boxes(t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(got: f32, want: f64, what: &str) {
        assert!(
            (got as f64 - want).abs() <= 1e-5 * want.abs().max(1.0),
            "{what}: got {got}, want {want}"
        );
    }

    #[test]
    fn a_box_measures_as_its_box() {
        let b = Aabb::new(Vec3::new(1.0, 2.0, 3.0), Vec3::new(2.0, 4.0, 6.0));
        for (v, a) in [
            (
                Dop14::from_aabb(&b).volume(),
                Dop14::from_aabb(&b).surface_area(),
            ),
            (
                Dop18::from_aabb(&b).volume(),
                Dop18::from_aabb(&b).surface_area(),
            ),
            (
                Dop26::from_aabb(&b).volume(),
                Dop26::from_aabb(&b).surface_area(),
            ),
        ] {
            // No diagonal plane cuts the box it was made from: the same f32 value.
            assert_eq!(v, Dop26::from_aabb(&b).aabb().volume());
            assert_eq!(a, Dop26::from_aabb(&b).aabb().surface_area());
        }
    }

    #[test]
    fn an_octahedron_is_its_own_14_dop() {
        let pts = [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z];
        let d = Dop14::fit(&pts);
        close(d.volume(), 4.0 / 3.0, "volume");
        // Eight equilateral triangles of side sqrt(2).
        close(d.surface_area(), 8.0 * 3f64.sqrt() / 2.0, "area");
        // The 18-DOP's face diagonals (|x ± y| <= 1, ...) cut the box less
        // than the body diagonals do: between the octahedron and the box.
        let d18 = Dop18::fit(&pts);
        assert!(d18.volume() > d.volume() && d18.volume() < 8.0);
        // The 26-DOP has the 14-DOP's planes and more.
        close(Dop26::fit(&pts).volume(), 4.0 / 3.0, "26-dop volume");
    }

    #[test]
    fn a_triangle_is_flat_with_both_sides_of_area() {
        let tri = [Vec3::ZERO, Vec3::X, Vec3::Y];
        for (v, a) in [
            (Dop14::fit(&tri).volume(), Dop14::fit(&tri).surface_area()),
            (Dop18::fit(&tri).volume(), Dop18::fit(&tri).surface_area()),
            (Dop26::fit(&tri).volume(), Dop26::fit(&tri).surface_area()),
        ] {
            // The z slab is padded by its rounding bound (4.4e-16), no more.
            assert!(v < 1e-15, "{v}");
            close(a, 1.0, "two sides of a triangle of area 1/2");
        }
        // A segment along a face diagonal, and a point: nothing at all.
        let seg = [Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0)];
        let d = Dop18::fit(&seg);
        assert!(d.volume() < 1e-12 && d.surface_area() < 1e-5, "{d:?}");
        let p = Dop26::fit(&[Vec3::splat(3.0)]);
        // (a point's slabs are padded by an ulp: a speck, not nothing)
        assert!(p.volume() < 1e-15 && p.surface_area() < 1e-10, "{p:?}");
        let origin = Dop26::fit(&[Vec3::ZERO]);
        assert!(origin.volume() == 0.0 && origin.surface_area() == 0.0);
        assert_eq!(Dop26::EMPTY.volume(), 0.0);
        assert_eq!(Dop26::EMPTY.surface_area(), 0.0);
    }

    #[test]
    fn far_and_huge_tetrahedra_scale_as_they_should() {
        let tet = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
        for (offset, size) in [(1e5, 1.0), (0.0, 1e30), (1e30, 1e30), (0.0, 1e-20)] {
            let pts = tet.map(|p| Vec3::splat(offset) + p * size);
            let d = Dop14::fit(&pts);
            let unit = 1.0 / size;
            let (v, a) = (d.volume_scaled(unit), d.surface_area_scaled(unit));
            assert!(v.is_finite() && a.is_finite() && v >= 0.0 && a >= 0.0);
            // Far from the origin the slabs are padded by their rounding (a
            // 1e5 offset in f32 is 1/128 units); the shape stays within it.
            let tol = if offset == 1e5 { 0.05 } else { 1e-4 };
            assert!((v as f64 - 1.0 / 6.0).abs() < tol, "{offset} {size}: {v}");
            let area = 1.5 + 3f64.sqrt() / 2.0;
            assert!((a as f64 - area).abs() < 6.0 * tol, "{offset} {size}: {a}");
            assert!(v <= d.aabb().volume_scaled(unit) && a <= d.aabb().surface_area_scaled(unit));
        }
        // Unscaled, a 1e30 tetrahedron overflows exactly as its box does.
        let huge = Dop14::fit(&tet.map(|p| p * 1e30));
        assert_eq!(huge.volume(), f32::INFINITY);
        assert_eq!(huge.aabb().volume(), f32::INFINITY);
        assert!(
            huge.surface_area() == f32::INFINITY
                || huge.surface_area() <= huge.aabb().surface_area()
        );
    }
}
