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
//! area are reported for the axis slabs only (the enclosing box): an upper bound
//! that keeps those measures cheap; the cut corners make the true k-DOP smaller.

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

    fn volume(&self) -> f32 {
        BoundingVolume::volume(&self.aabb())
    }

    fn surface_area(&self) -> f32 {
        BoundingVolume::surface_area(&self.aabb())
    }

    fn surface_area_scaled(&self, scale: f32) -> f32 {
        self.aabb().surface_area_scaled(scale)
    }

    fn volume_scaled(&self, scale: f32) -> f32 {
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
