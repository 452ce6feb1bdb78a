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
//! primitives and no pair is missed.

use crate::bv::Aabb;
use crate::primitive::Triangle;
use crate::round::{down, up};
use crate::Error;
#[cfg(feature = "sphere")]
use crate::Sphere;
use glam::{DMat3, DQuat, DVec3, Quat, Vec3};

/// A rotation followed by a translation, held in `f64`.
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
}

impl Rigid {
    /// No motion.
    pub const IDENTITY: Rigid = Rigid {
        rotation: DMat3::IDENTITY,
        translation: DVec3::ZERO,
    };

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
        Ok(Rigid {
            rotation: DMat3::from_quat(q / len),
            translation: translation.as_dvec3(),
        })
    }

    /// A pure translation.
    pub fn translation(offset: Vec3) -> Result<Rigid, Error> {
        Rigid::new(Quat::IDENTITY, offset)
    }

    /// The inverse motion.
    pub fn inverse(&self) -> Rigid {
        let r = self.rotation.transpose();
        Rigid {
            rotation: r,
            translation: -(r * self.translation),
        }
    }

    /// `self` after `first`: the motion that applies `first`, then `self`.
    pub fn after(&self, first: &Rigid) -> Rigid {
        Rigid {
            rotation: self.rotation * first.rotation,
            translation: self.rotation * first.translation + self.translation,
        }
    }

    /// The moved point, computed in `f64` and rounded to the nearest `f32`.
    #[inline]
    pub fn apply(&self, p: Vec3) -> Vec3 {
        (self.rotation * p.as_dvec3() + self.translation).as_vec3()
    }

    /// A box containing every moved point of `b` (as [`apply`](Self::apply)
    /// rounds it), rounded outward.
    pub fn apply_aabb(&self, b: &Aabb) -> Aabb {
        if crate::BoundingVolume::is_empty(b) {
            return *b;
        }
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
    fn transformed(&self, t: &Rigid) -> Aabb {
        t.apply_aabb(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::BoundingVolume;

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
}
