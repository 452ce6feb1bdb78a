//! Axis-aligned bounding box: two corners, overlap by three interval tests.

use super::{Axes, BoundingVolume, BoxSet, PointSet};
use glam::{Vec3, Vec4, Vec4Swizzles};

/// An axis-aligned box `[min, max]`. Min/max are exact in floating point, so an
/// AABB fitted to points contains them with no rounding slack at all.
///
/// ```
/// use bvhkit::Aabb;
/// use glam::Vec3;
/// let a = Aabb::new(Vec3::ZERO, Vec3::ONE);
/// let b = Aabb::new(Vec3::splat(1.0), Vec3::splat(2.0));
/// assert!(a.overlaps(&b)); // touching counts
/// assert_eq!(a.union(&b), Aabb::new(Vec3::ZERO, Vec3::splat(2.0)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct Aabb {
    /// Smallest corner.
    pub min: Vec3,
    /// Largest corner.
    pub max: Vec3,
}

impl Aabb {
    /// The empty box (`min = +inf`, `max = -inf`): the identity of [`union`](Self::union).
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    /// A box from its two corners.
    pub const fn new(min: Vec3, max: Vec3) -> Self {
        Aabb { min, max }
    }

    /// The degenerate box around one point.
    pub const fn from_point(p: Vec3) -> Self {
        Aabb { min: p, max: p }
    }

    /// Smallest box containing both.
    ///
    /// Written with plain comparisons (one `minss`/`maxss` per lane) rather than
    /// `f32::min`, whose NaN rule costs a compare-and-blend: builders reject NaN
    /// before any fold, so the faster rule is safe where it matters.
    #[inline]
    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb {
            min: min3(self.min, other.min),
            max: max3(self.max, other.max),
        }
    }

    /// Grows the box to contain `p`.
    #[inline]
    pub fn grow(&mut self, p: Vec3) {
        self.min = min3(self.min, p);
        self.max = max3(self.max, p);
    }

    /// Whether the boxes share at least one point (touching counts). Exact.
    ///
    /// The six comparisons run side by side in 4-lane registers with one
    /// branch at the end: this test is the inner loop of every pair
    /// query, and the chain of short-circuit compares it replaced cost a
    /// branch per axis (about 10% of the pair query's time). A NaN compares
    /// false in both forms.
    #[inline(always)]
    pub fn overlaps(&self, other: &Aabb) -> bool {
        let (a_min, a_max) = self.lanes();
        let (b_min, b_max) = other.lanes();
        xyz_all((a_min.cmple(b_max) & b_min.cmple(a_max)).bitmask())
    }

    /// The corners in 4-lane registers, x, y, z in lanes 0-2: each from one
    /// load of four neighbouring floats (`min` then `max.x`; `min.z` then
    /// `max`, moved down a lane), where a `Vec3A` of each corner costs three
    /// instructions.
    #[inline(always)]
    pub(crate) fn lanes(&self) -> (Vec4, Vec4) {
        let min = Vec4::new(self.min.x, self.min.y, self.min.z, self.max.x);
        let max = Vec4::new(self.min.z, self.max.x, self.max.y, self.max.z);
        (min, max.yzww())
    }

    /// The intersection box, or `None` when disjoint.
    pub fn intersection(&self, other: &Aabb) -> Option<Aabb> {
        let b = Aabb::new(self.min.max(other.min), self.max.min(other.max));
        b.min.cmple(b.max).all().then_some(b)
    }

    /// `max - min` (zero for a point, negative for the empty box).
    #[inline]
    pub fn extent(&self) -> Vec3 {
        self.max - self.min
    }

    /// Centre point, computed without overflowing at huge coordinates.
    #[inline]
    pub fn center(&self) -> Vec3 {
        self.min * 0.5 + self.max * 0.5
    }

    /// Half the surface area: the quantity the SAH compares.
    #[inline]
    pub fn half_area(&self) -> f32 {
        let e = self.extent().max(Vec3::ZERO);
        e.x * e.y + e.y * e.z + e.z * e.x
    }

    /// Index (0, 1, 2) of the longest side.
    pub fn longest_axis(&self) -> usize {
        let e = self.extent();
        if e.x >= e.y && e.x >= e.z {
            0
        } else if e.y >= e.z {
            1
        } else {
            2
        }
    }

    /// Corner `i` in 0..8 (bit 0 picks x, bit 1 y, bit 2 z).
    #[inline]
    pub fn corner(&self, i: usize) -> Vec3 {
        Vec3::new(
            if i & 1 == 0 { self.min.x } else { self.max.x },
            if i & 2 == 0 { self.min.y } else { self.max.y },
            if i & 4 == 0 { self.min.z } else { self.max.z },
        )
    }

    /// Whether all six coordinates are finite.
    pub fn is_finite(&self) -> bool {
        self.min.is_finite() && self.max.is_finite()
    }

    /// Squared distance from `p` to the box (zero inside).
    pub fn distance_squared(&self, p: Vec3) -> f32 {
        let d = (self.min - p).max(p - self.max).max(Vec3::ZERO);
        d.length_squared()
    }
}

#[inline(always)]
fn min3(a: Vec3, b: Vec3) -> Vec3 {
    Vec3::new(
        if b.x < a.x { b.x } else { a.x },
        if b.y < a.y { b.y } else { a.y },
        if b.z < a.z { b.z } else { a.z },
    )
}

#[inline(always)]
fn max3(a: Vec3, b: Vec3) -> Vec3 {
    Vec3::new(
        if b.x > a.x { b.x } else { a.x },
        if b.y > a.y { b.y } else { a.y },
        if b.z > a.z { b.z } else { a.z },
    )
}

impl Default for Aabb {
    fn default() -> Self {
        Aabb::EMPTY
    }
}

impl BoundingVolume for Aabb {
    const NAME: &'static str = "aabb";
    const EMPTY: Self = Aabb::EMPTY;
    const ZERO: Self = Aabb::new(Vec3::ZERO, Vec3::ZERO);
    const EXACT_MERGE: bool = true;

    fn fit<S: PointSet + ?Sized>(points: &S) -> Self {
        let mut b = Aabb::EMPTY;
        for i in 0..points.len() {
            b.grow(points.point(i));
        }
        b
    }
    fn from_aabb(aabb: &Aabb) -> Self {
        *aabb
    }
    fn fit_boxes<S: BoxSet + ?Sized>(_boxes: &S, union: &Aabb) -> Self {
        *union
    }
    #[inline]
    fn merge(&self, other: &Self) -> Self {
        self.union(other)
    }
    #[inline]
    fn overlaps(&self, other: &Self) -> bool {
        Aabb::overlaps(self, other)
    }
    #[inline]
    fn overlaps_aabb(&self, aabb: &Aabb) -> bool {
        Aabb::overlaps(self, aabb)
    }
    fn contains_point(&self, p: Vec3) -> bool {
        self.min.cmple(p).all() && p.cmple(self.max).all()
    }
    fn contains(&self, other: &Self) -> bool {
        other.is_empty() || (self.min.cmple(other.min).all() && other.max.cmple(self.max).all())
    }
    fn contains_aabb(&self, aabb: &Aabb) -> bool {
        self.contains(aabb)
    }
    fn volume(&self) -> f32 {
        let e = self.extent().max(Vec3::ZERO);
        e.x * e.y * e.z
    }
    fn surface_area(&self) -> f32 {
        2.0 * self.half_area()
    }
    fn surface_area_scaled(&self, scale: f32) -> f32 {
        let e = (self.extent() * scale).max(Vec3::ZERO);
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }
    fn volume_scaled(&self, scale: f32) -> f32 {
        let e = (self.extent() * scale).max(Vec3::ZERO);
        e.x * e.y * e.z
    }
    fn aabb(&self) -> Aabb {
        *self
    }
    fn axes(&self) -> Axes {
        Axes::XYZ
    }
    fn is_empty(&self) -> bool {
        !self.min.cmple(self.max).all()
    }
}

/// Whether lanes x, y and z of a comparison's `bitmask` are all set. The
/// corners from [`Aabb::lanes`] carry a spare value in lane w, so a
/// comparison of them counts lanes 0-2 only.
#[inline(always)]
pub(crate) fn xyz_all(bitmask: u32) -> bool {
    bitmask & 0b111 == 0b111
}

/// Whether any of lanes x, y and z of a comparison's `bitmask` is set (see
/// [`xyz_all`]).
#[cfg(feature = "insertion")]
#[inline(always)]
pub(crate) fn xyz_any(bitmask: u32) -> bool {
    bitmask & 0b111 != 0
}
