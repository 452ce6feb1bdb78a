//! Rigid transforms: query a tree that has moved without rebuilding it.
//!
//! Lecture: *collision detection system*. Each object keeps its tree in its own
//! model frame. To test object B against object A, B's volumes are carried
//! into A's frame as the traversal reaches them (each such carry is one update,
//! `Nu` in the cost function), instead of rebuilding B.
//!
//! The transform is kept in `f64`. A moved primitive is defined as its corners
//! transformed in `f64` and rounded to the nearest `f32`; moved volumes are
//! rounded outward with a little slack, so they always contain the moved
//! primitives and no pair is missed. Boxes, moved once per visited node of
//! B, are moved in `f32` with a padding that bounds every rounding (under
//! ten parts in a million of the coordinates' size): the `f64` version was
//! most of a moved pair query's time, and software `f64` on an `f32`-only
//! FPU.

use crate::bv::Aabb;
use crate::primitive::Triangle;
use crate::round::{down, up};
use crate::Error;
#[cfg(feature = "sphere")]
use crate::Sphere;
use glam::{DMat3, DQuat, DVec3, Mat3A, Quat, Vec3, Vec3A};

/// A rotation followed by a translation, held in `f64` (points move in
/// `f64`; boxes in `f32`, padded: see [`apply_aabb`](Self::apply_aabb)).
///
/// ```
/// use bvhkit::Rigid;
/// use glam::{Quat, Vec3};
/// let t = Rigid::new(Quat::from_rotation_z(core::f32::consts::FRAC_PI_2), Vec3::new(1.0, 0.0, 0.0))?;
/// let p = t.apply(Vec3::X);
/// assert!((p - Vec3::new(1.0, 1.0, 0.0)).length() < 1e-6);
/// assert!((t.inverse().apply(p) - Vec3::X).length() < 1e-6);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rigid {
    rotation: DMat3,
    translation: DVec3,
    /// The motion rounded to `f32` and `|R|`, for moving boxes.
    fast: Rigid32,
}

/// A rigid motion's `f32` copy: rotation, its entrywise absolute value, and
/// translation (each entry rounded to the nearest `f32`).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Rigid32 {
    rotation: Mat3A,
    abs: Mat3A,
    translation: Vec3A,
}

/// Padding of an `f32`-moved box, relative to the size of the terms that
/// made it: 16 `f32` epsilons (about 1.9e-6). The rounding of the rotation,
/// the translation, the box's centre and half size, the matrix products and
/// the final sums add up to at most about 14 half-epsilons of those terms
/// (and the `f64` moved point's own rounding to one more), so every moved
/// point stays inside.
const PAD32: f32 = 16.0 * f32::EPSILON;

impl Rigid32 {
    const IDENTITY: Rigid32 = Rigid32 {
        rotation: Mat3A::IDENTITY,
        abs: Mat3A::IDENTITY,
        translation: Vec3A::ZERO,
    };

    fn of(rotation: &DMat3, translation: DVec3) -> Rigid32 {
        let rotation = Mat3A::from(rotation.as_mat3());
        Rigid32 {
            rotation,
            abs: Mat3A::from_cols(
                rotation.x_axis.abs(),
                rotation.y_axis.abs(),
                rotation.z_axis.abs(),
            ),
            translation: Vec3A::from(translation.as_vec3()),
        }
    }
}

impl Rigid {
    /// No motion.
    pub const IDENTITY: Rigid = Rigid {
        rotation: DMat3::IDENTITY,
        translation: DVec3::ZERO,
        fast: Rigid32::IDENTITY,
    };

    /// The motion from its `f64` parts, with its `f32` copy.
    fn from_parts(rotation: DMat3, translation: DVec3) -> Rigid {
        Rigid {
            fast: Rigid32::of(&rotation, translation),
            rotation,
            translation,
        }
    }

    /// A rigid motion from a rotation (normalised here, in `f64`) and a
    /// translation. Non-finite values and a zero quaternion are errors.
    pub fn new(rotation: Quat, translation: Vec3) -> Result<Rigid, Error> {
        let q = DQuat::from_xyzw(
            rotation.x as f64,
            rotation.y as f64,
            rotation.z as f64,
            rotation.w as f64,
        );
        let len = q.length();
        if !q.is_finite() || !translation.is_finite() || len == 0.0 {
            return Err(Error::InvalidConfig(
                "a rigid transform needs a finite, non-zero rotation and a finite translation",
            ));
        }
        Ok(Rigid::from_parts(
            DMat3::from_quat(q / len),
            translation.as_dvec3(),
        ))
    }

    /// A pure translation.
    pub fn translation(offset: Vec3) -> Result<Rigid, Error> {
        Rigid::new(Quat::IDENTITY, offset)
    }

    /// The inverse motion.
    pub fn inverse(&self) -> Rigid {
        let r = self.rotation.transpose();
        Rigid::from_parts(r, -(r * self.translation))
    }

    /// `self` after `first`: the motion that applies `first`, then `self`.
    pub fn after(&self, first: &Rigid) -> Rigid {
        Rigid::from_parts(
            self.rotation * first.rotation,
            self.rotation * first.translation + self.translation,
        )
    }

    /// The moved point, computed in `f64` and rounded to the nearest `f32`.
    #[inline]
    pub fn apply(&self, p: Vec3) -> Vec3 {
        (self.rotation * p.as_dvec3() + self.translation).as_vec3()
    }

    /// A box containing every moved point of `b` (as [`apply`](Self::apply)
    /// rounds it). Computed in `f32`, padded by a bound on its rounding (see
    /// the module notes); boxes so far out that the `f32` sums overflow are
    /// moved in `f64` instead.
    ///
    /// ```
    /// use bvhkit::{Aabb, BoundingVolume, Rigid};
    /// use glam::{Quat, Vec3};
    /// let t = Rigid::new(Quat::from_rotation_z(0.5), Vec3::new(3.0, 0.0, 1.0))?;
    /// let b = Aabb::new(Vec3::new(-1.0, 2.0, 0.0), Vec3::new(1.0, 3.0, 0.5));
    /// let moved = t.apply_aabb(&b);
    /// assert!((0..8).all(|i| moved.contains_point(t.apply(b.corner(i)))));
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    #[inline]
    pub fn apply_aabb(&self, b: &Aabb) -> Aabb {
        let (lo, hi) = self.apply_aabb_a(b);
        Aabb::new(lo.into(), hi.into())
    }

    /// [`apply_aabb`](Self::apply_aabb) as two aligned vectors. Every path
    /// meets here in vector registers and becomes an `Aabb` once: when the
    /// paths met as an `Aabb`, the box went through memory in 8- and 4-byte
    /// pieces that the next 16-byte load could not be forwarded from, a
    /// stall that tripled the cost of a moved box (15 against 5 ns).
    #[inline(always)]
    fn apply_aabb_a(&self, b: &Aabb) -> (Vec3A, Vec3A) {
        let (min, max) = (Vec3A::from(b.min), Vec3A::from(b.max));
        if crate::BoundingVolume::is_empty(b) {
            return (min, max);
        }
        let f = &self.fast;
        let c = (min + max) * 0.5;
        let h = (max - min) * 0.5;
        let mc = f.rotation * c + f.translation;
        let mh = f.abs * h;
        let terms = f.abs * c.abs() + f.translation.abs() + mc.abs() + mh;
        let pad = terms * PAD32 + Vec3A::splat(f32::MIN_POSITIVE);
        let (lo, hi) = (mc - mh - pad, mc + mh + pad);
        if lo.is_finite() && hi.is_finite() {
            (lo, hi)
        } else {
            let r = self.apply_aabb_f64(b);
            (r.min.into(), r.max.into())
        }
    }

    /// [`apply_aabb`](Self::apply_aabb) in `f64`, rounded outward: the
    /// reference the `f32` version is tested against, and its fallback.
    #[cold]
    #[inline(never)]
    fn apply_aabb_f64(&self, b: &Aabb) -> Aabb {
        let c = (b.min.as_dvec3() + b.max.as_dvec3()) * 0.5;
        let h = (b.max.as_dvec3() - b.min.as_dvec3()) * 0.5;
        let abs = DMat3::from_cols(
            self.rotation.x_axis.abs(),
            self.rotation.y_axis.abs(),
            self.rotation.z_axis.abs(),
        );
        let c = self.rotation * c + self.translation;
        // Slack covers the f64 rounding above; f32 rounding of the moved points
        // is monotone, so outward rounding of the box covers it.
        let h = abs * h + (c.abs() + abs * h) * 1e-12;
        Aabb::new(
            Vec3::new(down(c.x - h.x), down(c.y - h.y), down(c.z - h.z)),
            Vec3::new(up(c.x + h.x), up(c.y + h.y), up(c.z + h.z)),
        )
    }

    /// Whether this is exactly the identity.
    pub fn is_identity(&self) -> bool {
        *self == Rigid::IDENTITY
    }
}

/// A primitive that can be moved by a [`Rigid`] motion.
pub trait Transform: Sized {
    /// The primitive as seen after the motion.
    fn transformed(&self, t: &Rigid) -> Self;
}

impl Transform for Triangle {
    #[inline]
    fn transformed(&self, t: &Rigid) -> Triangle {
        Triangle {
            v: self.v.map(|p| t.apply(p)),
        }
    }
}

impl Transform for [Vec3; 3] {
    #[inline]
    fn transformed(&self, t: &Rigid) -> [Vec3; 3] {
        self.map(|p| t.apply(p))
    }
}

impl Transform for Vec3 {
    #[inline]
    fn transformed(&self, t: &Rigid) -> Vec3 {
        t.apply(*self)
    }
}

#[cfg(feature = "sphere")]
impl Transform for Sphere {
    #[inline]
    fn transformed(&self, t: &Rigid) -> Sphere {
        Sphere::new(t.apply(self.center), self.radius)
    }
}

impl Transform for Aabb {
    /// A rotated box is no longer axis-aligned: the result is the smallest
    /// box around it, rounded outward (conservative, not exact).
    #[inline]
    fn transformed(&self, t: &Rigid) -> Aabb {
        t.apply_aabb(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::BoundingVolume;

    #[test]
    fn only_the_identity_is_the_identity() {
        assert!(Rigid::IDENTITY.is_identity());
        assert!(Rigid::new(Quat::IDENTITY, Vec3::ZERO)
            .unwrap()
            .is_identity());
        assert!(!Rigid::translation(Vec3::new(0.0, 1e-30, 0.0))
            .unwrap()
            .is_identity());
        let turn = Rigid::new(Quat::from_rotation_z(1e-3), Vec3::ZERO).unwrap();
        assert!(!turn.is_identity());
    }

    #[test]
    fn moved_boxes_contain_moved_points() {
        let t = Rigid::new(
            Quat::from_euler(glam::EulerRot::XYZ, 0.3, -1.1, 2.0),
            Vec3::new(1e4, -3.0, 0.25),
        )
        .unwrap();
        let b = Aabb::new(Vec3::new(-1.0, 2.0, 3.0), Vec3::new(1.5, 2.5, 7.0));
        let moved = t.apply_aabb(&b);
        for i in 0..8 {
            assert!(moved.contains_point(t.apply(b.corner(i))));
        }
        assert!(Rigid::new(Quat::from_xyzw(0.0, 0.0, 0.0, 0.0), Vec3::ZERO).is_err());
        assert!(Rigid::translation(Vec3::NAN).is_err());
        let round = t.inverse().after(&t);
        assert!((round.apply(Vec3::new(3.0, 4.0, 5.0)) - Vec3::new(3.0, 4.0, 5.0)).length() < 1e-3);
    }

    /// The `f32` box transform against its `f64` reference: at every scale
    /// from 1e-30 to 1e30 (points, slivers and boxes, near and far from the
    /// origin, turned by any angle) it contains the reference box, which
    /// contains every moved point; and it is looser by at most two parts
    /// in a hundred thousand of the coordinates' size.
    #[test]
    fn f32_moved_boxes_contain_the_f64_ones() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            ((seed >> 40) as f32) / (1u64 << 24) as f32 * 2.0 - 1.0
        };
        let mut cases = 0;
        for exp in (-30..=30).step_by(3) {
            let scale = 10f32.powi(exp);
            for _ in 0..200 {
                let turn = Quat::from_xyzw(next(), next(), next(), next() + 0.01);
                let shift = Vec3::new(next(), next(), next()) * scale * 4.0;
                let t = Rigid::new(turn, shift).unwrap();
                let c = Vec3::new(next(), next(), next()) * scale * 3.0;
                let size = Vec3::new(next().abs(), next().abs(), next().abs())
                    * scale
                    * if next() > 0.5 { 0.0 } else { 1.0 };
                let b = Aabb::new(c - size, c + size);
                let (fast, exact) = (t.apply_aabb(&b), t.apply_aabb_f64(&b));
                assert!(
                    fast.contains_aabb(&exact),
                    "{b:?} {t:?}: {fast:?} misses {exact:?}"
                );
                let reach = (exact.max.abs().max(exact.min.abs())).max_element() + scale;
                let looser = (exact.min - fast.min)
                    .max(fast.max - exact.max)
                    .max_element();
                assert!(looser <= reach * 2e-5, "{looser} against {reach}");
                for i in 0..8 {
                    assert!(fast.contains_point(t.apply(b.corner(i))));
                }
                cases += 1;
            }
        }
        assert_eq!(cases, 21 * 200);
        // Beyond what `f32` sums can hold: the `f64` path.
        let far = Aabb::new(Vec3::splat(3e38), Vec3::splat(3.3e38));
        let t = Rigid::new(Quat::from_rotation_z(0.7), Vec3::ZERO).unwrap();
        assert_eq!(t.apply_aabb(&far), t.apply_aabb_f64(&far));
    }
}
