//! Local frames: world coordinates in `f64`, trees in `f32`.
//!
//! Trees store `f32`: half the memory of `f64` and twice the lanes per
//! register. An `f32` keeps 24 bits, so a coordinate near `x` is rounded by up
//! to half an ulp of `x`: 0.5 mm at 10 km, 3 cm at 500 km. Geometry far from
//! the origin therefore moves when it is rounded, and two triangles that
//! touch in the world can miss each other in the tree, or meet where they
//! did not (the book's robustness chapter measures it). The bounds stay
//! conservative for the rounded geometry either way; what is lost is the
//! world's geometry itself, before any tree is built.
//!
//! A [`LocalFrame`] is the remedy: an origin kept in `f64`, with geometry
//! entering the tree relative to it. Rounding then depends on the distance
//! from the frame's origin, not from the world's, so a scene placed around
//! its own origin keeps its full `f32` precision wherever it is in the
//! world. Answers are ids, distances and ray parameters, which do not change
//! with the frame; points go back with [`LocalFrame::to_world`].

use crate::round;
use crate::{Aabb, Error, Triangle};
use glam::{DVec3, Vec3};

/// An origin in `f64` world coordinates; points enter the `f32` tree as
/// their offset from it, rounded to the nearest `f32`.
///
/// ```
/// use bvhkit::glam::DVec3;
/// use bvhkit::narrow::triangles_intersect;
/// use bvhkit::LocalFrame;
///
/// // Two triangles 600 km from the world's origin: `b` hovers 1 cm above `a`.
/// let at = DVec3::new(600_000.0, 250_000.0, 600_000.0);
/// let a = [at, at + DVec3::new(1.0, 0.0, 0.0), at + DVec3::new(0.0, 1.0, 0.0)];
/// let tip = at + DVec3::new(0.3, 0.3, 0.01);
/// let b = [tip, tip + DVec3::new(0.0, 0.1, 1.0), tip + DVec3::new(0.1, 0.0, 1.0)];
///
/// // Rounded straight to f32 (steps of 6.25 cm there), the gap vanishes.
/// let naive = |t: [DVec3; 3]| bvhkit::Triangle::new(t[0].as_vec3(), t[1].as_vec3(), t[2].as_vec3());
/// assert!(triangles_intersect(&naive(a), &naive(b))); // a contact that is not there
///
/// // Relative to a frame at them, the centimetre stays.
/// let frame = LocalFrame::new(at)?;
/// assert!(!triangles_intersect(&frame.triangle(a), &frame.triangle(b)));
/// assert!(frame.max_rounding(2.0) < 1.2e-7); // metres, within 2 m of the frame
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalFrame {
    origin: DVec3,
}

impl LocalFrame {
    /// A frame at `origin`, which must be finite.
    pub fn new(origin: DVec3) -> Result<Self, Error> {
        if origin.is_finite() {
            Ok(LocalFrame { origin })
        } else {
            Err(Error::InvalidConfig(
                "a local frame's origin must be finite",
            ))
        }
    }

    /// A frame at the centre of the box around `points` (the world's origin
    /// for no points). A non-finite point is an error, not a frame at NaN.
    pub fn around(points: impl IntoIterator<Item = DVec3>) -> Result<Self, Error> {
        let mut lo = DVec3::INFINITY;
        let mut hi = DVec3::NEG_INFINITY;
        for p in points {
            if !p.is_finite() {
                return Err(Error::InvalidConfig(
                    "a local frame's points must be finite",
                ));
            }
            lo = lo.min(p);
            hi = hi.max(p);
        }
        if lo.cmpgt(hi).any() {
            return Ok(LocalFrame {
                origin: DVec3::ZERO,
            });
        }
        // Halves first: the sum of two large finite values could overflow.
        LocalFrame::new(lo * 0.5 + hi * 0.5)
    }

    /// The frame's origin in world coordinates.
    pub fn origin(&self) -> DVec3 {
        self.origin
    }

    /// `p` in the frame: its offset from the origin, rounded to the nearest
    /// `f32`. A non-finite or out-of-range result is left as it is, for the
    /// builder to refuse with the primitive's index.
    pub fn point(&self, p: DVec3) -> Vec3 {
        (p - self.origin).as_vec3()
    }

    /// A triangle in the frame, each corner as [`point`](Self::point) rounds it.
    pub fn triangle(&self, corners: [DVec3; 3]) -> Triangle {
        let [a, b, c] = corners.map(|p| self.point(p));
        Triangle::new(a, b, c)
    }

    /// A box in the frame, rounded outward: it contains every point of the
    /// world box `[min, max]`, so a query with it misses nothing the world
    /// box touches.
    pub fn aabb(&self, min: DVec3, max: DVec3) -> Aabb {
        let (lo, hi) = (min - self.origin, max - self.origin);
        Aabb::new(
            Vec3::new(round::down(lo.x), round::down(lo.y), round::down(lo.z)),
            Vec3::new(round::up(hi.x), round::up(hi.y), round::up(hi.z)),
        )
    }

    /// A point of the frame (a contact, a ray's hit point) back in world
    /// coordinates, exactly: every `f32` is an `f64`.
    pub fn to_world(&self, p: Vec3) -> DVec3 {
        self.origin + p.as_dvec3()
    }

    /// The most a coordinate within `radius` of the origin moves when
    /// [`point`](Self::point) rounds it: half an `f32` ulp at `radius`
    /// (rounded up to the next power of two's ulp, so it is an upper bound).
    /// A distance moves by at most `sqrt(3)` times this.
    pub fn max_rounding(&self, radius: f64) -> f64 {
        let r = round::up(radius.abs());
        if !r.is_finite() {
            return f64::INFINITY;
        }
        (r.next_up() as f64 - r as f64) / 2.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_origins_and_points_are_errors() {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(LocalFrame::new(DVec3::new(0.0, bad, 0.0)).is_err());
            assert!(LocalFrame::around([DVec3::ZERO, DVec3::splat(bad)]).is_err());
        }
        assert_eq!(LocalFrame::around([]).unwrap().origin(), DVec3::ZERO);
        // The largest finite values do not overflow to an infinite centre.
        let f = LocalFrame::around([DVec3::splat(f64::MAX), DVec3::splat(f64::MAX)]).unwrap();
        assert_eq!(f.origin(), DVec3::splat(f64::MAX));
    }

    #[test]
    fn boxes_contain_their_world_box_and_points_round_within_the_bound() {
        // splitmix64 for reproducible "random" coordinates.
        let mut z = 7u64;
        let mut next = || {
            z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut x = z;
            x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            ((x ^ (x >> 31)) >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for scale in [1e-3, 1.0, 1e3, 1e6, 1e9] {
            let origin = DVec3::new(next(), next(), next()) * 1e7;
            let frame = LocalFrame::new(origin).unwrap();
            for _ in 0..2_000 {
                let p = origin + DVec3::new(next(), next(), next()) * scale;
                let q = p + DVec3::new(next(), next(), next()).abs() * scale;
                let b = frame.aabb(p, q);
                let (lo, hi) = (b.min.as_dvec3() + origin, b.max.as_dvec3() + origin);
                // Compared in the frame, where the test's own sums are exact
                // enough: the stored box contains the world box's offsets.
                assert!((b.min.as_dvec3()).cmple(p - origin).all(), "{lo} {p}");
                assert!((b.max.as_dvec3()).cmpge(q - origin).all(), "{hi} {q}");
                let moved = (frame.point(p).as_dvec3() - (p - origin))
                    .abs()
                    .max_element();
                let radius = (p - origin).abs().max_element();
                assert!(moved <= frame.max_rounding(radius), "{moved} at {radius}");
            }
        }
    }

    #[test]
    fn frames_centre_on_their_points_and_triangles_move_with_them() {
        let f =
            LocalFrame::around([DVec3::new(0.0, 4.0, -6.0), DVec3::new(2.0, 0.0, 6.0)]).unwrap();
        assert_eq!(f.origin(), DVec3::new(1.0, 2.0, 0.0));
        let t = f.triangle([
            DVec3::new(1.5, 2.0, 0.0),
            DVec3::new(1.0, 3.0, 0.0),
            DVec3::new(1.0, 2.0, -0.25),
        ]);
        assert_eq!(
            t.v,
            [
                Vec3::new(0.5, 0.0, 0.0),
                Vec3::Y,
                Vec3::new(0.0, 0.0, -0.25)
            ]
        );
    }

    #[test]
    fn points_go_back_to_the_world_exactly() {
        let frame = LocalFrame::new(DVec3::new(6.4e6, -1.25e5, 3.0)).unwrap();
        let p = Vec3::new(0.1, -2.5, 1e-3);
        assert_eq!(frame.point(frame.to_world(p)), p);
        assert_eq!(frame.max_rounding(1.0), f64::from(f32::EPSILON) / 2.0); // half the ulp above 1
        assert_eq!(frame.max_rounding(f64::MAX), f64::INFINITY);
    }
}
