//! How deep two solid convex shapes overlap: the contact a solver pushes
//! apart.
//!
//! Convention: the normal is a unit vector pointing from the first shape
//! towards the second; moving the second shape by `normal * depth` (or the
//! first by the opposite) leaves them touching, and no shorter move in any
//! direction separates them. The point lies halfway between the two
//! surfaces along the normal. Surfaces (triangles) have no inside and so
//! no depth: their contact is [`triangle_contact`](super::triangle_contact).

use crate::bv::Aabb;
#[cfg(feature = "sphere")]
use crate::bv::Sphere;
use glam::DVec3;

/// A contact between two overlapping solids.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Penetration {
    /// Halfway between the two surfaces along the normal.
    pub point: DVec3,
    /// Unit vector from the first shape towards the second.
    pub normal: DVec3,
    /// How far the second shape must move along `normal` to touch only.
    pub depth: f64,
}

/// Two solid shapes with a penetration depth.
///
/// ```
/// use bvhkit::narrow::Penetrate;
/// use bvhkit::Aabb;
/// use glam::{DVec3, Vec3};
/// let floor = Aabb::new(Vec3::new(-10.0, -1.0, -10.0), Vec3::new(10.0, 0.0, 10.0));
/// let crate_ = Aabb::new(Vec3::new(0.0, -0.25, 0.0), Vec3::new(1.0, 0.75, 1.0));
/// let p = floor.penetration(&crate_).unwrap();
/// assert_eq!((p.normal, p.depth), (DVec3::Y, 0.25)); // lift the crate by 0.25
/// let above = Aabb::new(Vec3::new(0.0, 0.75, 0.0), Vec3::new(1.0, 1.75, 1.0));
/// assert_eq!(floor.penetration(&above), None);
/// ```
pub trait Penetrate<Q: ?Sized = Self> {
    /// The contact, or `None` when the shapes do not overlap. Shapes that
    /// only touch have depth zero.
    fn penetration(&self, other: &Q) -> Option<Penetration>;
}

impl Penetrate for Aabb {
    /// The axis and side of least overlap (ties to the lowest axis, then
    /// to moving the second box towards +). Computed in `f64` from the `f32`
    /// corners, so the depth is exact for boxes up to 2^29 apart.
    fn penetration(&self, other: &Aabb) -> Option<Penetration> {
        let (a0, a1) = (self.min.as_dvec3(), self.max.as_dvec3());
        let (b0, b1) = (other.min.as_dvec3(), other.max.as_dvec3());
        let mut best: Option<(f64, usize, f64)> = None;
        for k in 0..3 {
            // Moving B up by a1 - b0 clears A's top; down by b1 - a0 its bottom.
            let (up, down) = (a1[k] - b0[k], b1[k] - a0[k]);
            if up < 0.0 || down < 0.0 {
                return None;
            }
            for (depth, sign) in [(up, 1.0), (down, -1.0)] {
                if best.is_none_or(|(d, _, _)| depth < d) {
                    best = Some((depth, k, sign));
                }
            }
        }
        let (depth, k, sign) = best?;
        let mut normal = DVec3::ZERO;
        normal[k] = sign;
        // The overlap region's centre, moved to halfway between the faces
        // along the normal.
        let lo = a0.max(b0);
        let hi = a1.min(b1);
        let mut point = (lo + hi) * 0.5;
        point[k] = if sign > 0.0 {
            0.5 * (a1[k] + b0[k])
        } else {
            0.5 * (a0[k] + b1[k])
        };
        Some(Penetration {
            point,
            normal,
            depth,
        })
    }
}

#[cfg(feature = "sphere")]
impl Penetrate for Sphere {
    /// Along the line of centres (`+x` when the centres coincide).
    fn penetration(&self, other: &Sphere) -> Option<Penetration> {
        let (c1, c2) = (self.center.as_dvec3(), other.center.as_dvec3());
        let (r1, r2) = (self.radius as f64, other.radius as f64);
        let d = c2 - c1;
        let len = d.length();
        let depth = r1 + r2 - len;
        if depth < 0.0 || r1 < 0.0 || r2 < 0.0 {
            return None;
        }
        let normal = if len > 0.0 { d / len } else { DVec3::X };
        // Surfaces at c1 + n r1 and c2 - n r2; halfway between them.
        let point = (c1 + normal * r1 + c2 - normal * r2) * 0.5;
        Some(Penetration {
            point,
            normal,
            depth,
        })
    }
}

#[cfg(feature = "sphere")]
impl Penetrate<Aabb> for Sphere {
    /// From the box's closest point to the centre; when the centre is
    /// inside the box, out through the nearest face.
    fn penetration(&self, b: &Aabb) -> Option<Penetration> {
        b.penetration(self).map(|p| Penetration {
            normal: -p.normal,
            ..p
        })
    }
}

#[cfg(feature = "sphere")]
impl Penetrate<Sphere> for Aabb {
    fn penetration(&self, s: &Sphere) -> Option<Penetration> {
        let (lo, hi) = (self.min.as_dvec3(), self.max.as_dvec3());
        let c = s.center.as_dvec3();
        let r = s.radius as f64;
        if r < 0.0 {
            return None;
        }
        let q = c.clamp(lo, hi);
        let d = c - q;
        let len = d.length();
        if len > 0.0 {
            // Centre outside the box: along the closest point's direction.
            let depth = r - len;
            if depth < 0.0 {
                return None;
            }
            let normal = d / len;
            let point = (q + (c - normal * r)) * 0.5;
            return Some(Penetration {
                point,
                normal,
                depth,
            });
        }
        // Centre inside: leave through the nearest face.
        let mut best = (f64::INFINITY, 0, 1.0);
        for k in 0..3 {
            for (gap, sign) in [(hi[k] - c[k], 1.0), (c[k] - lo[k], -1.0)] {
                if gap < best.0 {
                    best = (gap, k, sign);
                }
            }
        }
        let (gap, k, sign) = best;
        let mut normal = DVec3::ZERO;
        normal[k] = sign;
        let face = c + normal * gap;
        let depth = gap + r;
        let point = (face + (c - normal * r)) * 0.5;
        Some(Penetration {
            point,
            normal,
            depth,
        })
    }
}
