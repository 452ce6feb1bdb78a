//! Oriented bounding box: centre, three orthonormal axes, half extents.
//!
//! Fitted by principal component analysis: the eigenvectors of the points'
//! covariance give the axes. PCA can be arbitrarily bad (clustered points drag
//! the axes; a cube's covariance has no preferred axes), so the fit keeps the
//! axis-aligned box when that is smaller. Overlap is the separating-axis test
//! over 15 axes, with the usual epsilon on the rotation terms so two nearly
//! parallel edges (cross product near zero) cannot produce a false separation.

use super::{Aabb, Axes, BoundingVolume, PointSet};
use crate::round;
use glam::{DMat3, DVec3, Vec3};

/// An oriented box: the set of `x` with `|axes[i] . (x - center)| <= half_extents[i]`.
///
/// ```
/// use bvhkit::{BoundingVolume, Obb};
/// use glam::Vec3;
/// // Points along the diagonal: the OBB is a thin stick, far smaller than the AABB.
/// let pts: Vec<Vec3> = (0..50).map(|i| Vec3::splat(i as f32) + Vec3::new(0.1, -0.1, 0.0) * (i % 2) as f32).collect();
/// let obb = Obb::fit(pts.as_slice());
/// assert!(pts.iter().all(|&p| obb.contains_point(p)));
/// assert!(obb.volume() < bvhkit::Aabb::fit(pts.as_slice()).volume() * 0.1);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct Obb {
    /// Centre.
    pub center: Vec3,
    /// Unit axes, mutually orthogonal.
    pub axes: [Vec3; 3],
    /// Half extent along each axis (negative for the empty box).
    pub half_extents: Vec3,
}

impl Obb {
    /// The empty box.
    pub const EMPTY: Obb = Obb {
        center: Vec3::ZERO,
        axes: [Vec3::X, Vec3::Y, Vec3::Z],
        half_extents: Vec3::splat(-1.0),
    };

    /// Fits a box with the given (orthonormal) axes tightly around the points,
    /// computing in `f64` and rounding the extents up.
    pub fn fit_with_axes<S: PointSet + ?Sized>(points: &S, axes: [Vec3; 3]) -> Obb {
        if points.is_empty() {
            return Obb::EMPTY;
        }
        let ax = axes.map(|a| a.as_dvec3());
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for i in 0..points.len() {
            let p = points.point(i).as_dvec3();
            let t = DVec3::new(ax[0].dot(p), ax[1].dot(p), ax[2].dot(p));
            lo = lo.min(t);
            hi = hi.max(t);
        }
        let mid = (lo + hi) * 0.5;
        let center = (ax[0] * mid.x + ax[1] * mid.y + ax[2] * mid.z).as_vec3();
        let c = center.as_dvec3();
        // Re-measure from the rounded centre so containment holds exactly.
        let mut e = DVec3::ZERO;
        for i in 0..points.len() {
            let v = points.point(i).as_dvec3() - c;
            e = e.max(DVec3::new(
                ax[0].dot(v).abs(),
                ax[1].dot(v).abs(),
                ax[2].dot(v).abs(),
            ));
        }
        Obb::with_extents(center, axes, e)
    }

    /// A box from exact `f64` half extents, padded for the `f64` rounding of
    /// the projections and rounded up to `f32`.
    fn with_extents(center: Vec3, axes: [Vec3; 3], e: DVec3) -> Obb {
        let pad = 1.0 + 16.0 * f64::EPSILON;
        Obb {
            center,
            axes,
            half_extents: Vec3::new(
                round::up(e.x * pad),
                round::up(e.y * pad),
                round::up(e.z * pad),
            ),
        }
    }

    /// The PCA axes of a point set (orthonormal, by decreasing variance).
    pub fn pca_axes<S: PointSet + ?Sized>(points: &S) -> [Vec3; 3] {
        let n = points.len().max(1) as f64;
        let mut mean = DVec3::ZERO;
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for i in 0..points.len() {
            let p = points.point(i).as_dvec3();
            mean += p;
            lo = lo.min(p);
            hi = hi.max(p);
        }
        mean /= n;
        // Normalise so the covariance never overflows, whatever the coordinates.
        let scale = 1.0 / (hi - lo).max_element().max(f64::MIN_POSITIVE);
        let mut cov = DMat3::ZERO;
        for i in 0..points.len() {
            let v = (points.point(i).as_dvec3() - mean) * scale;
            cov += DMat3::from_cols(v * v.x, v * v.y, v * v.z);
        }
        let (_, vecs) = crate::bv::symmetric_eigen(cov * (1.0 / n));
        orthonormal(vecs)
    }

    /// PCA fit, falling back to the axis-aligned box when that is not larger.
    pub fn pca<S: PointSet + ?Sized>(points: &S) -> Obb {
        if points.is_empty() {
            return Obb::EMPTY;
        }
        let aligned = Obb::fit_with_axes(points, [Vec3::X, Vec3::Y, Vec3::Z]);
        let rotated = Obb::fit_with_axes(points, Obb::pca_axes(points));
        if rotated.volume() < aligned.volume() * 0.999 {
            rotated
        } else if rotated.volume() == 0.0 && aligned.volume() == 0.0 {
            // Flat sets: compare areas instead.
            if rotated.surface_area() < aligned.surface_area() {
                rotated
            } else {
                aligned
            }
        } else {
            aligned
        }
    }

    /// A fast tight fit of the DiTO family (Larsson and Källberg 2011,
    /// "Fast computation of tight-fitting oriented bounding boxes"): the
    /// extremal points along the 7 directions of a 14-DOP, a large base
    /// triangle among them, the two points farthest off its plane (a
    /// ditetrahedron), and every triangle's edges as candidate axes; the
    /// candidate whose box over the 14 extremal points has the smallest
    /// area wins, and is fitted over all points. Two passes over the points,
    /// no allocation; falls back to the axis-aligned box when that is not
    /// larger, and is conservative like every fit ([`fit_with_axes`](Self::fit_with_axes)).
    ///
    /// ```
    /// use bvhkit::{BoundingVolume, Obb};
    /// use glam::{Quat, Vec3};
    /// // A rotated 4 x 2 x 1 brick's corners: DiTO finds the brick.
    /// let q = Quat::from_euler(glam::EulerRot::XYZ, 0.3, 0.5, 0.7);
    /// let pts: Vec<Vec3> = (0..8)
    ///     .map(|i| q * Vec3::new([-2.0, 2.0][i & 1], [-1.0, 1.0][i >> 1 & 1], [-0.5, 0.5][i >> 2]))
    ///     .collect();
    /// let obb = Obb::dito(pts.as_slice());
    /// assert!(pts.iter().all(|&p| obb.contains_point(p)));
    /// assert!(obb.volume() < 8.0 * 1.01, "{}", obb.volume());
    /// ```
    pub fn dito<S: PointSet + ?Sized>(points: &S) -> Obb {
        if points.is_empty() {
            return Obb::EMPTY;
        }
        const DIRS: [[f64; 3]; 7] = [
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
            [1.0, 1.0, -1.0],
            [1.0, -1.0, 1.0],
            [1.0, -1.0, -1.0],
        ];
        // Extremal points, in coordinates relative to the first point (so
        // that a set far from the origin keeps its precision).
        let origin = points.point(0).as_dvec3();
        let mut lo = [(f64::INFINITY, DVec3::ZERO); 7];
        let mut hi = [(f64::NEG_INFINITY, DVec3::ZERO); 7];
        for i in 0..points.len() {
            let p = points.point(i).as_dvec3() - origin;
            for (k, d) in DIRS.iter().enumerate() {
                let t = DVec3::from_array(*d).dot(p);
                if t < lo[k].0 {
                    lo[k] = (t, p);
                }
                if t > hi[k].0 {
                    hi[k] = (t, p);
                }
            }
        }
        let mut ext = [DVec3::ZERO; 14];
        for k in 0..7 {
            ext[2 * k] = lo[k].1;
            ext[2 * k + 1] = hi[k].1;
        }
        let aligned = Obb::fit_with_axes(points, [Vec3::X, Vec3::Y, Vec3::Z]);
        // Base triangle: the farthest extremal pair, then the point farthest from their line.
        let (mut p0, mut p1) = (ext[0], ext[1]);
        for k in 0..7 {
            if (ext[2 * k + 1] - ext[2 * k]).length_squared() > (p1 - p0).length_squared() {
                (p0, p1) = (ext[2 * k], ext[2 * k + 1]);
            }
        }
        let e0 = p1 - p0;
        if e0.length_squared() == 0.0 {
            return aligned; // every point the same
        }
        let line_dist = |p: DVec3| e0.cross(p - p0).length_squared();
        let p2 = ext
            .iter()
            .copied()
            .fold(p0, |b, p| if line_dist(p) > line_dist(b) { p } else { b });
        let mut best: Option<([DVec3; 3], f64)> = None;
        let mut consider = |u: DVec3, n: DVec3| {
            let u = u.normalize_or_zero();
            let v = n.cross(u).normalize_or_zero();
            if u == DVec3::ZERO || v == DVec3::ZERO {
                return;
            }
            let w = u.cross(v);
            let (mut a, mut b) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
            for p in ext {
                let t = DVec3::new(u.dot(p), v.dot(p), w.dot(p));
                a = a.min(t);
                b = b.max(t);
            }
            let e = b - a;
            let half_area = e.x * e.y + e.y * e.z + e.z * e.x;
            if best.is_none_or(|(_, q)| half_area < q) {
                best = Some(([u, v, w], half_area));
            }
        };
        let n = e0.cross(p2 - p0);
        if line_dist(p2) <= 1e-24 * e0.length_squared() * e0.length_squared() {
            // Collinear extremal points: the line, and any frame about it.
            consider(e0, e0.any_orthonormal_vector());
        } else {
            let tri = [p0, p1, p2];
            for i in 0..3 {
                consider(tri[(i + 1) % 3] - tri[i], n);
            }
            // The ditetrahedron: the points farthest above and below the base.
            let (mut below, mut above) = ((0.0, p0), (0.0, p0));
            for p in ext {
                let t = n.dot(p - p0);
                if t < below.0 {
                    below = (t, p);
                }
                if t > above.0 {
                    above = (t, p);
                }
            }
            for (t, q) in [below, above] {
                if t == 0.0 {
                    continue;
                }
                for i in 0..3 {
                    let (a, b) = (tri[i], tri[(i + 1) % 3]);
                    let m = (b - a).cross(q - a);
                    consider(b - a, m);
                    consider(q - b, m);
                    consider(a - q, m);
                }
            }
        }
        let Some((axes, _)) = best else {
            return aligned;
        };
        let rotated = Obb::fit_with_axes(
            points,
            orthonormal(DMat3::from_cols(axes[0], axes[1], axes[2])),
        );
        if rotated.volume() < aligned.volume() * 0.999
            || (aligned.volume() == 0.0 && rotated.surface_area() < aligned.surface_area())
        {
            rotated
        } else {
            aligned
        }
    }

    /// The eight corners, in `f64`.
    fn corners64(&self) -> [DVec3; 8] {
        self.corners64_with(self.half_extents.as_dvec3())
    }

    /// The corners for half extents `e` (in `f64`) about this centre and axes.
    fn corners64_with(&self, e: DVec3) -> [DVec3; 8] {
        let c = self.center.as_dvec3();
        let a = self.axes.map(|a| a.as_dvec3());
        core::array::from_fn(|i| {
            let sx = if i & 1 == 0 { -1.0 } else { 1.0 };
            let sy = if i & 2 == 0 { -1.0 } else { 1.0 };
            let sz = if i & 4 == 0 { -1.0 } else { 1.0 };
            c + a[0] * (sx * e.x) + a[1] * (sy * e.y) + a[2] * (sz * e.z)
        })
    }

    /// [`corners64`](Self::corners64) of this box with each half extent
    /// grown by 2e-6 of their sum: the hull of these corners contains the
    /// box's slab set. With `f32` unit axes the pairwise dot products and
    /// the lengths' errors stay under 3e-7 (well inside 1e-6), so a point
    /// whose projections are within the extents has coordinates along the
    /// axes within `e_k + 1e-6 * (e_x + e_y + e_z) / (1 - 3e-6)`.
    fn outer_corners64(&self) -> [DVec3; 8] {
        let e = self.half_extents.as_dvec3();
        self.corners64_with(e + DVec3::splat(2e-6 * (e.x + e.y + e.z)))
    }

    fn contains64(&self, p: DVec3) -> bool {
        let v = p - self.center.as_dvec3();
        (0..3).all(|k| self.axes[k].as_dvec3().dot(v).abs() <= self.half_extents[k] as f64)
    }
}

/// Gram-Schmidt in f64, then round to f32 unit vectors; a right-handed frame.
pub(super) fn orthonormal(m: DMat3) -> [Vec3; 3] {
    let mut a = m.x_axis.normalize_or(DVec3::X);
    if !a.is_finite() {
        a = DVec3::X;
    }
    let mut b = (m.y_axis - a * a.dot(m.y_axis)).normalize_or_zero();
    if b.length_squared() < 0.5 {
        b = a.any_orthonormal_vector();
    }
    let c = a.cross(b).normalize();
    [a.as_vec3(), b.as_vec3(), c.as_vec3()]
}

/// The centres of a box set, as points.
struct Centers<'a, S: ?Sized>(&'a S);
impl<S: super::BoxSet + ?Sized> PointSet for Centers<'_, S> {
    fn len(&self) -> usize {
        self.0.len()
    }
    fn point(&self, i: usize) -> Vec3 {
        self.0.aabb(i).center()
    }
}

struct Points8([DVec3; 16], usize);
impl PointSet for Points8 {
    fn len(&self) -> usize {
        self.1
    }
    fn point(&self, i: usize) -> Vec3 {
        self.0[i].as_vec3()
    }
}

impl Obb {
    /// The box around `boxes` along `axes` (each box's projected interval
    /// per axis, in `f64`), or the axis-aligned box of `union` when that is
    /// no larger: the node fit of [`Obb`] (PCA axes) and [`ObbDito`] (DiTO's).
    fn fit_boxes_along<S: super::BoxSet + ?Sized>(boxes: &S, union: &Aabb, axes: [Vec3; 3]) -> Obb {
        let n = boxes.len();
        let ax = axes.map(|a| a.as_dvec3());
        let interval = |i: usize, center: DVec3| {
            let b = boxes.aabb(i);
            let (lo, hi) = (b.min.as_dvec3(), b.max.as_dvec3());
            let c = (lo + hi) * 0.5 - center;
            let e = (hi - lo) * 0.5;
            ax.map(|u| (u.dot(c), u.abs().dot(e)))
        };
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for i in 0..n {
            let t = interval(i, DVec3::ZERO);
            for k in 0..3 {
                lo[k] = lo[k].min(t[k].0 - t[k].1);
                hi[k] = hi[k].max(t[k].0 + t[k].1);
            }
        }
        let mid = (lo + hi) * 0.5;
        let center = (ax[0] * mid.x + ax[1] * mid.y + ax[2] * mid.z).as_vec3();
        let mut e = DVec3::ZERO;
        for i in 0..n {
            let t = interval(i, center.as_dvec3());
            for k in 0..3 {
                e[k] = e[k].max(t[k].0.abs() + t[k].1);
            }
        }
        let rotated = Obb::with_extents(center, axes, e);
        let aligned = Obb::from_aabb(union);
        if rotated.volume() < aligned.volume() * 0.999
            || (aligned.volume() == 0.0 && rotated.surface_area() < aligned.surface_area())
        {
            rotated
        } else {
            aligned
        }
    }
}

impl BoundingVolume for Obb {
    const NAME: &'static str = "obb";
    const EMPTY: Self = Obb::EMPTY;
    const ZERO: Self = Obb {
        center: Vec3::ZERO,
        axes: [Vec3::ZERO; 3],
        half_extents: Vec3::ZERO,
    };

    fn fit<S: PointSet + ?Sized>(points: &S) -> Self {
        Obb::pca(points)
    }

    /// PCA of the box centres, then each box's projected interval per axis
    /// (`c.u +/- sum |u_k| e_k`): `n` boxes instead of `8n` corners.
    fn fit_boxes<S: super::BoxSet + ?Sized>(boxes: &S, union: &Aabb) -> Self {
        if boxes.is_empty() {
            return Obb::EMPTY;
        }
        Obb::fit_boxes_along(boxes, union, Obb::pca_axes(&Centers(boxes)))
    }

    fn from_aabb(aabb: &Aabb) -> Self {
        if BoundingVolume::is_empty(aabb) {
            return Obb::EMPTY;
        }
        Obb::fit_with_axes(&[aabb.min, aabb.max], [Vec3::X, Vec3::Y, Vec3::Z])
    }

    fn merge(&self, other: &Self) -> Self {
        if self.is_empty() {
            return *other;
        }
        if other.is_empty() {
            return *self;
        }
        // Corners rounded to f32 may fall a hair inside the f64 corners, so
        // round each outward along its own direction from the centre of the set.
        // And the parts' corners are taken a little outside them: with axes
        // rounded to f32 a box's slab set (what `contains_point` tests)
        // pokes out of the hull of its exact corners by up to about 1e-7
        // of the sum of its sides; covering that keeps every point of a
        // part inside the merge, not only its corners.
        let mut pts = [DVec3::ZERO; 16];
        pts[..8].copy_from_slice(&self.outer_corners64());
        pts[8..].copy_from_slice(&other.outer_corners64());
        let set = Points8(pts, 16);
        let mut merged = Obb::pca(&set);
        let grow = |m: &mut Obb| {
            for p in &set.0 {
                let v = *p - m.center.as_dvec3();
                for k in 0..3 {
                    let need = m.axes[k].as_dvec3().dot(v).abs() * (1.0 + 8.0 * f64::EPSILON);
                    if need > m.half_extents[k] as f64 {
                        m.half_extents[k] = round::up(need);
                    }
                }
            }
        };
        grow(&mut merged);
        merged
    }

    fn overlaps(&self, other: &Self) -> bool {
        if self.is_empty() || other.is_empty() {
            return false;
        }
        sat(self, other)
    }

    fn overlaps_aabb(&self, aabb: &Aabb) -> bool {
        if BoundingVolume::is_empty(aabb) {
            return false;
        }
        self.overlaps(&Obb::from_aabb(aabb))
    }

    fn contains_point(&self, p: Vec3) -> bool {
        self.contains64(p.as_dvec3())
    }

    fn contains(&self, other: &Self) -> bool {
        other.is_empty() || other.corners64().iter().all(|&p| self.contains64(p))
    }

    fn volume(&self) -> f32 {
        let e = self.half_extents.max(Vec3::ZERO) * 2.0;
        e.x * e.y * e.z
    }

    fn surface_area(&self) -> f32 {
        let e = self.half_extents.max(Vec3::ZERO) * 2.0;
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    fn surface_area_scaled(&self, scale: f32) -> f32 {
        let e = self.half_extents.max(Vec3::ZERO) * (2.0 * scale);
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    fn volume_scaled(&self, scale: f32) -> f32 {
        let e = self.half_extents.max(Vec3::ZERO) * (2.0 * scale);
        e.x * e.y * e.z
    }

    fn aabb(&self) -> Aabb {
        if self.is_empty() {
            return Aabb::EMPTY;
        }
        let mut b = Aabb::EMPTY;
        let corners = self.corners64();
        for k in 0..3 {
            let lo = corners.iter().map(|c| c[k]).fold(f64::INFINITY, f64::min);
            let hi = corners
                .iter()
                .map(|c| c[k])
                .fold(f64::NEG_INFINITY, f64::max);
            let pad = (hi - lo).abs() * 4.0 * f64::EPSILON + hi.abs().max(lo.abs()) * f64::EPSILON;
            b.min[k] = round::down(lo - pad);
            b.max[k] = round::up(hi + pad);
        }
        b
    }

    fn axes(&self) -> Axes {
        let mut a = Axes::XYZ;
        a.axes[..3].copy_from_slice(&self.axes);
        a
    }

    fn is_empty(&self) -> bool {
        !self.half_extents.cmpge(Vec3::ZERO).all()
    }
}

/// Separating-axis test over the 15 candidate axes (Gottschalk et al.; Ericson 4.4.1).
/// Comparisons are widened by a relative slack so rounding errs towards overlap.
fn sat(a: &Obb, b: &Obb) -> bool {
    const GUARD: f32 = 1e-6;
    let ea = a.half_extents;
    let eb = b.half_extents;
    let mut r = [[0.0f32; 3]; 3];
    let mut abs_r = [[0.0f32; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            r[i][j] = a.axes[i].dot(b.axes[j]);
            abs_r[i][j] = r[i][j].abs() + GUARD;
        }
    }
    let tw = b.center - a.center;
    let t = Vec3::new(tw.dot(a.axes[0]), tw.dot(a.axes[1]), tw.dot(a.axes[2]));
    let scale = ea.max_element() + eb.max_element() + tw.abs().max_element();
    let slack = round::SLACK * 4.0 * scale;
    let separated = |dist: f32, ra: f32, rb: f32| dist > ra + rb + slack;
    for i in 0..3 {
        let rb = eb[0] * abs_r[i][0] + eb[1] * abs_r[i][1] + eb[2] * abs_r[i][2];
        if separated(t[i].abs(), ea[i], rb) {
            return false;
        }
    }
    for j in 0..3 {
        let ra = ea[0] * abs_r[0][j] + ea[1] * abs_r[1][j] + ea[2] * abs_r[2][j];
        let dist = (t[0] * r[0][j] + t[1] * r[1][j] + t[2] * r[2][j]).abs();
        if separated(dist, ra, eb[j]) {
            return false;
        }
    }
    for i in 0..3 {
        let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
        for j in 0..3 {
            let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
            let ra = ea[i1] * abs_r[i2][j] + ea[i2] * abs_r[i1][j];
            let rb = eb[j1] * abs_r[i][j2] + eb[j2] * abs_r[i][j1];
            let dist = (t[i2] * r[i1][j] - t[i1] * r[i2][j]).abs();
            if separated(dist, ra, rb) {
                return false;
            }
        }
    }
    true
}

/// An OBB whose fits are DiTO's ([`Obb::dito`] around points; DiTO's axes
/// over the box centres, then each box's interval, around a node's boxes)
/// instead of PCA's. A tree built with it is the same shape as an [`Obb`]
/// tree (top-down builders score primitive boxes) with other node boxes;
/// everything but the fit is the wrapped [`Obb`]'s.
///
/// ```
/// use bvhkit::{BoundingVolume, Obb, ObbDito};
/// use glam::{Quat, Vec3};
/// // A long thin box, turned: DiTO finds its axes from extremal points.
/// let q = Quat::from_rotation_z(0.5) * Quat::from_rotation_x(0.3);
/// let pts: Vec<Vec3> = (0..8)
///     .map(|i| q * Vec3::new([-4.0, 4.0][i & 1], [-1.0, 1.0][i >> 1 & 1], [-0.5, 0.5][i >> 2]))
///     .collect();
/// let dito = ObbDito::fit(pts.as_slice());
/// assert!(pts.iter().all(|&p| dito.contains_point(p)));
/// assert_eq!(dito.0, Obb::dito(pts.as_slice()));
/// assert!(dito.volume() < 8.0 * 2.0 * 1.0 * 1.01);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObbDito(pub Obb);

impl BoundingVolume for ObbDito {
    const NAME: &'static str = "obb-dito";
    const EMPTY: Self = ObbDito(Obb::EMPTY);
    const ZERO: Self = ObbDito(<Obb as BoundingVolume>::ZERO);

    fn fit<S: PointSet + ?Sized>(points: &S) -> Self {
        ObbDito(Obb::dito(points))
    }
    fn fit_boxes<S: super::BoxSet + ?Sized>(boxes: &S, union: &Aabb) -> Self {
        if boxes.is_empty() {
            return Self::EMPTY;
        }
        let axes = Obb::dito(&Centers(boxes)).axes;
        ObbDito(Obb::fit_boxes_along(boxes, union, axes))
    }
    fn from_aabb(aabb: &Aabb) -> Self {
        ObbDito(Obb::from_aabb(aabb))
    }
    fn merge(&self, other: &Self) -> Self {
        ObbDito(self.0.merge(&other.0))
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
    fn cost_area_scaled(&self, scale: f32) -> f32 {
        self.0.cost_area_scaled(scale)
    }
    fn cost_volume_scaled(&self, scale: f32) -> f32 {
        self.0.cost_volume_scaled(scale)
    }
    fn size(&self) -> f32 {
        self.0.size()
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
        ObbDito(self.0.transformed(t))
    }
    fn transformed_with_boxes(&self, t: &crate::Rigid) -> Self {
        ObbDito(self.0.transformed_with_boxes(t))
    }
}

#[cfg(test)]
mod dito_tests {
    use super::*;

    /// DiTO contains every point and is never looser than the axis-aligned
    /// OBB it falls back to, also at 1e35 (where the centre's rounding
    /// costs an ulp of 8e27) and on flat and single-point sets.
    #[test]
    fn dito_contains_and_is_no_looser_than_its_fallback() {
        let sets: [&[Vec3]; 5] = [
            &[
                Vec3::new(1.0000001e35, -5e34, 2.5e34),
                Vec3::new(1e35, -4.999817e34, 2.5000115e34),
            ],
            &[Vec3::ZERO, Vec3::new(3.6271255e30, -3.6384125e30, 0.0)],
            &[Vec3::splat(7.0)],
            &[
                Vec3::ZERO,
                Vec3::X,
                Vec3::Y,
                Vec3::new(1.0, 1.0, 0.0),
                Vec3::new(0.3, 0.9, 0.0),
            ],
            &[Vec3::ZERO, Vec3::ONE, Vec3::splat(2.0), Vec3::splat(3.5)],
        ];
        for pts in sets {
            let d = Obb::dito(pts);
            let a = Obb::fit_with_axes(pts, [Vec3::X, Vec3::Y, Vec3::Z]);
            assert!(pts.iter().all(|&p| d.contains_point(p)), "{d:?}");
            let ext = pts
                .iter()
                .fold(Aabb::EMPTY, |b, &p| b.union(&Aabb::from_point(p)));
            let unit = 1.0 / ext.extent().max_element().max(f32::MIN_POSITIVE);
            let (dv, av) = (d.volume_scaled(unit), a.volume_scaled(unit));
            let (da, aa) = (d.surface_area_scaled(unit), a.surface_area_scaled(unit));
            assert!(
                dv <= av * 1.001 + 1e-6 || da <= aa * 1.001 + 1e-6,
                "{d:?} looser than {a:?}"
            );
        }
    }
}

#[cfg(test)]
mod merge_tests {
    use super::*;

    /// A merged OBB contains every point its parts contain, not only their
    /// corners. The axes are unit vectors rounded to `f32`, so a box's slab
    /// set (what `contains_point` tests) pokes out of the hull of its
    /// corners by about 1e-7 of its largest side; a merge that covered only
    /// the corners lost such points (found by a bottom-up property test:
    /// a point triangle outside its collapsed leaf).
    #[test]
    fn a_merge_contains_every_point_of_its_parts() {
        let mut s = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 40) as f32 / (1u64 << 24) as f32 - 0.5
        };
        let mut missed = 0;
        for _ in 0..20_000 {
            let scale = [1e-2f32, 1.0, 1e3][(next() + 0.5) as usize % 3];
            let three = next() > 0.0;
            let mut point = || Vec3::new(next(), next(), next()) * scale;
            // A thin part (two or three points) and a bulky other part.
            let part: [Vec3; 3] = [point(), point(), point()];
            let part_box = Obb::fit(&part[..2 + usize::from(three)]);
            let other: [Vec3; 4] = [point(), point(), point(), point()];
            let other_box = Obb::fit(&other[..]);
            let merged = part_box.merge(&other_box);
            for p in part {
                if part_box.contains_point(p) && !merged.contains_point(p) {
                    missed += 1;
                }
            }
        }
        assert_eq!(missed, 0, "points of a part outside the merge");
    }
}

#[cfg(test)]
mod measure_tests {
    use super::*;
    use glam::{Mat3, Quat};

    fn close(got: f32, want: f32, what: &str) {
        assert!(
            (got - want).abs() <= 1e-4 * want.abs().max(1.0),
            "{what}: {got} against {want}"
        );
    }

    fn rotation(next: &mut impl FnMut() -> f32) -> [Vec3; 3] {
        let axis = Vec3::new(next(), next(), next()) + Vec3::new(0.0, 0.0, 1e-3);
        let m = Mat3::from_quat(Quat::from_axis_angle(axis.normalize(), next() * 3.1));
        [m.x_axis, m.y_axis, m.z_axis]
    }

    fn obb(center: Vec3, axes: [Vec3; 3], half_extents: Vec3) -> Obb {
        Obb {
            center,
            axes,
            half_extents,
        }
    }

    /// Overlap by the 15 candidate axes with both boxes' eight corners
    /// projected in `f64`: no radius formula shared with `sat`. Returns the
    /// largest gap between the projections (negative: they overlap), in
    /// units of the axis length.
    fn widest_gap(a: &Obb, b: &Obb) -> f64 {
        let (ca, cb) = (a.corners64(), b.corners64());
        let mut axes = [DVec3::ZERO; 15];
        for i in 0..3 {
            axes[i] = a.axes[i].as_dvec3();
            axes[3 + i] = b.axes[i].as_dvec3();
            for j in 0..3 {
                axes[6 + 3 * i + j] = a.axes[i].as_dvec3().cross(b.axes[j].as_dvec3());
            }
        }
        let mut widest = f64::NEG_INFINITY;
        for ax in axes {
            let len = ax.length();
            if len < 1e-6 {
                continue;
            }
            let span = |cs: &[DVec3; 8]| {
                cs.iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
                        let t = c.dot(ax) / len;
                        (lo.min(t), hi.max(t))
                    })
            };
            let ((alo, ahi), (blo, bhi)) = (span(&ca), span(&cb));
            widest = widest.max((blo - ahi).max(alo - bhi));
        }
        widest
    }

    #[test]
    fn measures_by_value() {
        let mut next = crate::test_floats(5);
        let o = obb(
            Vec3::new(1.0, 2.0, 3.0),
            rotation(&mut next),
            Vec3::new(1.0, 2.0, 3.0),
        );
        close(o.volume(), 48.0, "volume");
        close(o.surface_area(), 88.0, "area");
        close(o.surface_area_scaled(0.5), 22.0, "scaled area");
        close(o.volume_scaled(0.5), 6.0, "scaled volume");
        close(o.volume_scaled(2.0), 384.0, "scaled volume up");
        let d = ObbDito(o);
        close(d.volume(), 48.0, "dito volume");
        close(d.surface_area(), 88.0, "dito area");
        close(d.surface_area_scaled(0.5), 22.0, "dito scaled area");
        close(d.volume_scaled(0.5), 6.0, "dito scaled volume");
        assert_eq!(d.size(), o.size());
        assert!(o.size() > 0.0);
        assert!(!o.is_empty() && !d.is_empty());
        let flat = obb(
            Vec3::ZERO,
            [Vec3::X, Vec3::Y, Vec3::Z],
            Vec3::new(1.0, 1.0, 0.0),
        );
        assert!(!flat.is_empty());
        assert_eq!(flat.volume(), 0.0);
        let hollow = obb(
            Vec3::ZERO,
            [Vec3::X, Vec3::Y, Vec3::Z],
            Vec3::new(1.0, -0.5, 1.0),
        );
        assert!(hollow.is_empty() && ObbDito(hollow).is_empty());
        assert!(Obb::EMPTY.is_empty());
        assert_eq!(Obb::EMPTY.aabb(), Aabb::EMPTY);
        // The axis-aligned box of a box turned 45 degrees about z.
        let s = core::f32::consts::FRAC_1_SQRT_2;
        let turned = obb(
            Vec3::ZERO,
            [Vec3::new(s, s, 0.0), Vec3::new(-s, s, 0.0), Vec3::Z],
            Vec3::new(1.0, 1.0, 1.0),
        );
        let b = turned.aabb();
        close(b.max.x, 2.0f32.sqrt(), "turned box max x");
        close(b.min.y, -(2.0f32.sqrt()), "turned box min y");
        close(b.max.z, 1.0, "turned box max z");
        assert!(b.contains(&ObbDito(turned).aabb()) && ObbDito(turned).aabb().contains(&b));
    }

    /// `overlaps` (and through it `overlaps_aabb`) agrees with the corner
    /// projections on random pairs, except within a hair of touching where
    /// the guard may call it either way; far apart is never an overlap.
    #[test]
    fn sat_agrees_with_corner_projections() {
        let mut next = crate::test_floats(9);
        let (mut apart, mut touching) = (0, 0);
        for _ in 0..4000 {
            let a = obb(
                Vec3::new(next(), next(), next()) * 3.0,
                rotation(&mut next),
                Vec3::new(next(), next(), next()).abs() * 2.0 + 0.05,
            );
            let b = obb(
                Vec3::new(next(), next(), next()) * 3.0,
                rotation(&mut next),
                Vec3::new(next(), next(), next()).abs() * 2.0 + 0.05,
            );
            let gap = widest_gap(&a, &b);
            if gap.abs() < 1e-4 {
                continue;
            }
            let want = gap < 0.0;
            apart += usize::from(!want);
            touching += usize::from(want);
            assert_eq!(a.overlaps(&b), want, "{a:?} {b:?} gap {gap}");
            assert_eq!(b.overlaps(&a), want);
            assert_eq!(ObbDito(a).overlaps(&ObbDito(b)), want);
            let box_b = b.aabb();
            let as_obb = Obb::from_aabb(&box_b);
            let want_box = widest_gap(&a, &as_obb) < 0.0;
            if widest_gap(&a, &as_obb).abs() >= 1e-4 {
                assert_eq!(a.overlaps_aabb(&box_b), want_box);
                assert_eq!(ObbDito(a).overlaps_aabb(&box_b), want_box);
            }
        }
        assert!(
            apart > 400 && touching > 400,
            "{apart} apart, {touching} overlapping"
        );
        let unit = obb(Vec3::ZERO, [Vec3::X, Vec3::Y, Vec3::Z], Vec3::ONE);
        assert!(!unit.overlaps(&Obb::EMPTY) && !Obb::EMPTY.overlaps(&unit));
        assert!(!unit.overlaps_aabb(&Aabb::EMPTY));
    }

    /// Containment along turned axes: a point on a face is in, a hair
    /// beyond is out; a smaller turned box inside, a larger one not.
    #[test]
    fn containment_along_turned_axes() {
        let mut next = crate::test_floats(13);
        for _ in 0..50 {
            let axes = rotation(&mut next);
            let c = Vec3::new(next(), next(), next()) * 5.0;
            let o = obb(c, axes, Vec3::new(1.0, 2.0, 0.5));
            let d = ObbDito(o);
            for (k, axis) in axes.iter().enumerate() {
                let half = *axis * o.half_extents[k];
                let (on, beyond) = (c + half * 0.999, c + half * 1.01);
                assert!(o.contains_point(on) && d.contains_point(on));
                assert!(!o.contains_point(beyond) && !d.contains_point(beyond));
                assert!(!o.contains_point(c - half * 1.01));
            }
            let inner = obb(c, axes, o.half_extents * 0.9);
            let outer = obb(c, axes, o.half_extents * Vec3::new(1.0, 1.0, 1.05));
            assert!(o.contains(&inner) && d.contains(&ObbDito(inner)));
            assert!(!o.contains(&outer) && !d.contains(&ObbDito(outer)));
            assert!(o.contains(&Obb::EMPTY));
            let little = Aabb::new(c - Vec3::splat(0.2), c + Vec3::splat(0.2));
            assert!(o.contains_aabb(&little) && d.contains_aabb(&little));
            let big = Aabb::new(c - Vec3::splat(3.0), c + Vec3::splat(3.0));
            assert!(!o.contains_aabb(&big) && !d.contains_aabb(&big));
        }
    }

    /// Points filling a turned box of sides 8, 2 and 0.5 (its corners
    /// among them): every fit holds them all; PCA finds the long axis, and
    /// PCA and DiTO stay near the box's own volume (8) where the
    /// axis-aligned box is far larger; from boxes, every box is inside.
    #[test]
    fn fits_find_a_turned_box() {
        let mut next = crate::test_floats(17);
        for _ in 0..20 {
            let axes = rotation(&mut next);
            let half = Vec3::new(4.0, 1.0, 0.25);
            let c = Vec3::new(next(), next(), next()) * 10.0;
            let at = |u: Vec3| {
                c + axes[0] * u.x * half.x + axes[1] * u.y * half.y + axes[2] * u.z * half.z
            };
            let mut pts = [Vec3::ZERO; 72];
            for (i, p) in pts.iter_mut().enumerate() {
                *p = if i < 8 {
                    at(Vec3::new(
                        if i & 1 == 0 { -1.0 } else { 1.0 },
                        if i & 2 == 0 { -1.0 } else { 1.0 },
                        if i & 4 == 0 { -1.0 } else { 1.0 },
                    ))
                } else {
                    at(Vec3::new(next(), next(), next()))
                };
            }
            let long = Obb::pca_axes(&pts[..])[0];
            assert!(long.dot(axes[0]).abs() > 0.98, "{long} against {}", axes[0]);
            let aabb_volume = Aabb::fit(&pts[..]).volume();
            for (name, o) in [
                ("pca", Obb::pca(&pts[..])),
                ("dito", Obb::dito(&pts[..])),
                ("fit", Obb::fit(&pts[..])),
            ] {
                assert!(pts.iter().all(|&p| o.contains_point(p)), "{name}");
                assert!(o.volume() >= 8.0 * 0.999, "{name}: {}", o.volume());
                assert!(
                    o.volume() <= 8.0 * 1.6 || o.volume() < aabb_volume * 0.5,
                    "{name}: {} (aabb {aabb_volume})",
                    o.volume()
                );
            }
            let boxes: [Aabb; 9] = core::array::from_fn(|i| {
                Aabb::new(pts[i * 8] - Vec3::splat(0.1), pts[i * 8] + Vec3::splat(0.1))
            });
            let union = boxes.iter().fold(Aabb::EMPTY, |u, b| u.union(b));
            let o = <Obb as BoundingVolume>::fit_boxes(&boxes[..], &union);
            let d = <ObbDito as BoundingVolume>::fit_boxes(&boxes[..], &union);
            assert!(boxes
                .iter()
                .all(|b| o.contains_aabb(b) && d.contains_aabb(b)));
            assert!(o.volume() <= union.volume() * 1.001 && d.volume() <= union.volume() * 1.001);
        }
        assert!(Obb::pca::<[Vec3]>(&[]).is_empty() && Obb::dito::<[Vec3]>(&[]).is_empty());
    }
}
