//! Bounding volumes: the shapes a hierarchy wraps around its primitives.
//!
//! Lecture: *bounding volumes* and *desired characteristics*. A tighter volume
//! prunes more (smaller `Nv`, `Np` in the cost function) but costs more to test
//! (larger `Cv`). The four kinds here span that trade-off:
//!
//! | volume | test cost | tightness | fit |
//! |---|---|---|---|
//! | [`Aabb`] | cheapest | loose on rotated shapes | min/max |
//! | [`Sphere`] | cheap | loose on long shapes | Ritter, refined Ritter, exact Welzl |
//! | [`Obb`] | expensive (15 axes) | tight on rotated shapes | PCA, DiTO; from a hull: surface PCA, face-flush |
//! | [`Kdop`] | k/2 interval tests | between AABB and hull | min/max along fixed directions |
//!
//! Every fit is *conservative in `f32`*: the fitting code computes in `f64` and
//! rounds outward, so every input point passes [`BoundingVolume::contains_point`].
//! Every overlap test errs only towards "overlapping", so a hierarchy never
//! prunes a pair that really touches.

mod aabb;
mod eigen;
#[cfg(feature = "kdop")]
mod kdop;
#[cfg(feature = "obb")]
mod obb;
#[cfg(feature = "obb")]
mod obb_hull;
#[cfg(feature = "kdop")]
mod polytope;
#[cfg(feature = "sphere")]
mod sphere;

pub use aabb::Aabb;
#[cfg(feature = "insertion")]
pub(crate) use aabb::{xyz_all, xyz_any};
pub use eigen::symmetric_eigen;
#[cfg(feature = "kdop")]
pub use kdop::{Dop14, Dop18, Dop26, ExactKdop, Kdop};
#[cfg(feature = "obb")]
pub use obb::{Obb, ObbDito};
#[cfg(feature = "sphere")]
pub use sphere::Sphere;

use glam::Vec3;

/// A random-access set of points, so fits can make several passes without a buffer.
pub trait PointSet {
    /// Number of points.
    fn len(&self) -> usize;
    /// The `i`-th point, `i < len()`.
    fn point(&self, i: usize) -> Vec3;
    /// `true` when there are no points.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl PointSet for [Vec3] {
    fn len(&self) -> usize {
        <[Vec3]>::len(self)
    }
    fn point(&self, i: usize) -> Vec3 {
        self[i]
    }
}

impl<const N: usize> PointSet for [Vec3; N] {
    fn len(&self) -> usize {
        N
    }
    fn point(&self, i: usize) -> Vec3 {
        self[i]
    }
}

/// A random-access set of boxes (the primitive bounds beneath a node).
pub trait BoxSet {
    /// Number of boxes.
    fn len(&self) -> usize;
    /// The `i`-th box.
    fn aabb(&self, i: usize) -> Aabb;
    /// `true` when there are no boxes.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl BoxSet for [Aabb] {
    fn len(&self) -> usize {
        <[Aabb]>::len(self)
    }
    fn aabb(&self, i: usize) -> Aabb {
        self[i]
    }
}

/// The eight corners of every box of a [`BoxSet`], seen as one point set.
#[derive(Clone, Copy, Debug)]
pub struct Corners<'a, S: ?Sized>(pub &'a S);

impl<S: BoxSet + ?Sized> PointSet for Corners<'_, S> {
    fn len(&self) -> usize {
        self.0.len() * 8
    }
    fn point(&self, i: usize) -> Vec3 {
        self.0.aabb(i / 8).corner(i % 8)
    }
}

/// Up to 13 unit axes of a volume, used by the "axes of the parent volume" split choice.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Axes {
    /// Storage; only the first `len` entries are meaningful.
    pub axes: [Vec3; 13],
    /// Number of axes.
    pub len: usize,
}

impl Axes {
    /// The three coordinate axes.
    pub const XYZ: Axes = Axes {
        axes: [
            Vec3::X,
            Vec3::Y,
            Vec3::Z,
            Vec3::ZERO,
            Vec3::ZERO,
            Vec3::ZERO,
            Vec3::ZERO,
            Vec3::ZERO,
            Vec3::ZERO,
            Vec3::ZERO,
            Vec3::ZERO,
            Vec3::ZERO,
            Vec3::ZERO,
        ],
        len: 3,
    };

    /// The axes as a slice.
    pub fn as_slice(&self) -> &[Vec3] {
        &self.axes[..self.len]
    }
}

/// The interface every bounding volume implements; builders and queries are
/// generic over it. A volume is plain data (`'static`: it borrows nothing),
/// which lets an owned tree pick its storage by the volume's type.
///
/// ```
/// use bvhkit::{Aabb, BoundingVolume, Sphere};
/// use glam::Vec3;
/// let pts = [Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0)];
/// let s = Sphere::fit(&pts);
/// let b = Aabb::fit(&pts);
/// assert!(pts.iter().all(|&p| s.contains_point(p) && b.contains_point(p)));
/// assert!(s.overlaps(&Sphere::new(Vec3::new(3.0, 0.0, 0.0), 1.5)));
/// ```
pub trait BoundingVolume: Copy + core::fmt::Debug + PartialEq + 'static {
    /// Short name for tables ("aabb", "sphere", ...).
    const NAME: &'static str;
    /// The empty volume: the identity of [`merge`](Self::merge), contains nothing.
    const EMPTY: Self;
    /// Every bit zero (a point at the origin). Only for initialising storage:
    /// a `static` array of nodes filled with it lands in `.bss` and costs no
    /// flash, whereas one filled with [`EMPTY`](Self::EMPTY) (infinities) is
    /// copied from flash at start-up.
    const ZERO: Self;

    /// Fits a volume around a non-empty point set. Conservative: every point is inside.
    fn fit<S: PointSet + ?Sized>(points: &S) -> Self;
    /// The volume of this kind around a box (contains the whole box).
    fn from_aabb(aabb: &Aabb) -> Self;
    /// Fits around a set of boxes whose union is `union` (already known to the
    /// caller, which lets [`Aabb`] skip the work). Default: fit the corners.
    fn fit_boxes<S: BoxSet + ?Sized>(boxes: &S, union: &Aabb) -> Self {
        let _ = union;
        Self::fit(&Corners(boxes))
    }
    /// A volume containing both `self` and `other`.
    fn merge(&self, other: &Self) -> Self;
    /// Whether [`merge`](Self::merge) always contains both volumes exactly
    /// (no rounding can leave a hair of either outside): builders then skip
    /// the check that merges again (a box's merge is a min and a max).
    const EXACT_MERGE: bool = false;
    /// Conservative overlap test: `false` only when the volumes are disjoint.
    fn overlaps(&self, other: &Self) -> bool;
    /// Conservative overlap test against a box.
    fn overlaps_aabb(&self, aabb: &Aabb) -> bool;
    /// Whether `p` is inside (boundary included), decided without rounding loss.
    fn contains_point(&self, p: Vec3) -> bool;
    /// Whether `other` lies entirely inside `self`.
    fn contains(&self, other: &Self) -> bool;
    /// Whether the whole box lies inside `self`.
    fn contains_aabb(&self, aabb: &Aabb) -> bool {
        (0..8).all(|i| self.contains_point(aabb.corner(i)))
    }
    /// Volume.
    fn volume(&self) -> f32;
    /// Surface area.
    fn surface_area(&self) -> f32;
    /// [`surface_area`](Self::surface_area) of the volume with every length
    /// multiplied by `scale`. Bottom-up builders compare merges with the
    /// scene's size as the unit (`scale = 1 / size`), so that a scene 1e30
    /// wide does not overflow `f32` (its areas would be 1e60) and every
    /// candidate keeps its own cost. Implementations scale the lengths
    /// before multiplying them; the default scales the area afterwards.
    fn surface_area_scaled(&self, scale: f32) -> f32 {
        self.surface_area() * scale * scale
    }
    /// [`volume`](Self::volume) with every length multiplied by `scale` (see
    /// [`surface_area_scaled`](Self::surface_area_scaled)).
    fn volume_scaled(&self, scale: f32) -> f32 {
        self.volume() * scale * scale * scale
    }
    /// The surface area that builders' costs compare (the SAH, bottom-up
    /// merges, insertion), lengths scaled as in
    /// [`surface_area_scaled`](Self::surface_area_scaled). Builders evaluate
    /// it millions of times, so it must cost about what a box's area costs.
    /// It is the exact area for every volume but a k-DOP, whose exact area
    /// clips a polytope (microseconds) and which answers with its enclosing
    /// box's area instead; `ExactKdop` makes a k-DOP tree use the exact one.
    fn cost_area_scaled(&self, scale: f32) -> f32 {
        self.surface_area_scaled(scale)
    }
    /// The volume that builders' costs compare (see
    /// [`cost_area_scaled`](Self::cost_area_scaled)).
    fn cost_volume_scaled(&self, scale: f32) -> f32 {
        self.volume_scaled(scale)
    }
    /// The size measure the "descend the larger volume" rule compares; cheap
    /// like [`cost_volume_scaled`](Self::cost_volume_scaled), which it
    /// defaults to.
    fn size(&self) -> f32 {
        self.cost_volume_scaled(1.0)
    }
    /// The enclosing axis-aligned box.
    fn aabb(&self) -> Aabb;
    /// The volume's own axes (for the "parent volume axes" split choice).
    fn axes(&self) -> Axes {
        Axes::XYZ
    }
    /// Whether this is the empty volume.
    fn is_empty(&self) -> bool;

    /// The volume carried by a rigid motion, conservatively: it contains every
    /// point of `self` moved by [`Rigid::apply`](crate::Rigid::apply). The
    /// default boxes the moved enclosing box, which is valid for every volume
    /// but loose for rotated OBBs and k-DOPs; types override it when they can
    /// do better.
    #[inline]
    fn transformed(&self, t: &crate::Rigid) -> Self {
        Self::from_aabb(&t.apply_aabb(&self.aabb()))
    }

    /// Like [`transformed`](Self::transformed), but also containing the
    /// axis-aligned box (in the new frame) of every moved point set inside.
    /// Queries whose answer compares primitive *boxes* after a motion need
    /// this: a moved sphere contains a moved triangle, but not that
    /// triangle's new bounding box. Volumes whose `transformed` goes through
    /// a box (the default) already satisfy it.
    #[inline]
    fn transformed_with_boxes(&self, t: &crate::Rigid) -> Self {
        self.transformed(t)
    }
}
