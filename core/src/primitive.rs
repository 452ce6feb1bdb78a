//! Primitives: what the leaves of a hierarchy hold.
//!
//! A builder only needs one thing from a primitive: its axis-aligned bounds.
//! It sorts primitives by the centre of those bounds (the usual "centroid" of
//! SAH builders), so a tree depends on nothing else. Anything
//! implementing [`Primitive`] can be put in a tree: triangles, points, boxes,
//! spheres, or your own types.

use crate::bv::Aabb;
#[cfg(feature = "sphere")]
use crate::bv::Sphere;
use glam::Vec3;

/// Largest coordinate magnitude accepted by the builders (1e32).
///
/// Beyond it, extents and areas overflow `f32` and cost comparisons lose their
/// meaning; such input is rejected with [`Error::CoordinateOutOfRange`](crate::Error).
/// Coordinates up to this bound (1e30 is tested) build and query exactly.
pub const MAX_COORDINATE: f32 = 1.0e32;

/// Something a hierarchy can bound.
///
/// ```
/// use bvhkit::{Aabb, Primitive};
/// use glam::Vec3;
/// /// A capsule-like segment with a radius, as a user primitive.
/// struct Stick { a: Vec3, b: Vec3, r: f32 }
/// impl Primitive for Stick {
///     fn bounds(&self) -> Aabb {
///         Aabb::new(self.a.min(self.b) - self.r, self.a.max(self.b) + self.r)
///     }
///     fn is_finite(&self) -> bool {
///         self.a.is_finite() && self.b.is_finite() && self.r.is_finite()
///     }
/// }
/// let s = Stick { a: Vec3::ZERO, b: Vec3::X, r: 0.5 };
/// assert_eq!(s.bounds().min, Vec3::new(-0.5, -0.5, -0.5));
/// assert_eq!(s.bounds().center(), Vec3::new(0.5, 0.0, 0.0));
/// ```
pub trait Primitive {
    /// The smallest axis-aligned box containing the primitive.
    fn bounds(&self) -> Aabb;
    /// Whether every coordinate is finite. `f32::min` ignores NaN, so this must
    /// look at the raw data, not at [`bounds`](Self::bounds).
    fn is_finite(&self) -> bool;
}

/// A triangle given by its three corners.
///
/// ```
/// use bvhkit::{Primitive, Triangle};
/// use glam::Vec3;
/// let t = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
/// assert_eq!(t.bounds().max, Vec3::new(1.0, 1.0, 0.0));
/// assert!((t.area() - 0.5).abs() < 1e-6);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[repr(C)]
pub struct Triangle {
    /// The three corners.
    pub v: [Vec3; 3],
}

impl Triangle {
    /// A triangle from three corners.
    pub const fn new(a: Vec3, b: Vec3, c: Vec3) -> Self {
        Triangle { v: [a, b, c] }
    }

    /// Area (zero for degenerate triangles).
    pub fn area(&self) -> f32 {
        (self.v[1] - self.v[0])
            .cross(self.v[2] - self.v[0])
            .length()
            * 0.5
    }

    /// The triangle moved by `offset`.
    pub fn translated(&self, offset: Vec3) -> Triangle {
        Triangle {
            v: self.v.map(|p| p + offset),
        }
    }
}

impl Primitive for Triangle {
    #[inline]
    fn bounds(&self) -> Aabb {
        Aabb::new(
            self.v[0].min(self.v[1]).min(self.v[2]),
            self.v[0].max(self.v[1]).max(self.v[2]),
        )
    }
    #[inline]
    #[allow(clippy::eq_op)] // `x - x` is the point: 0 only for a finite `x`
    fn is_finite(&self) -> bool {
        // `x - x` is 0 for a finite `x` and NaN for an infinite or NaN one:
        // one comparison for all nine coordinates.
        let [a, b, c] = self.v;
        ((a - a) + (b - b) + (c - c)).cmpeq(Vec3::ZERO).all()
    }
}

/// Corners to a triangle, in the same order.
impl From<[Vec3; 3]> for Triangle {
    #[inline]
    fn from(v: [Vec3; 3]) -> Triangle {
        Triangle { v }
    }
}

/// A triangle's corners.
impl From<Triangle> for [Vec3; 3] {
    #[inline]
    fn from(t: Triangle) -> [Vec3; 3] {
        t.v
    }
}

/// Three corners, as many mesh crates hand triangles out: a [`Triangle`] in
/// all but name. Bounds, ray casts, closest points, distances, rigid
/// motions, self-pair adjacency and the exact intersection tests give the
/// triangle's answers, so a `Vec<[Vec3; 3]>` from a loader needs no
/// conversion.
///
/// ```
/// use bvhkit::{Aabb, Intersects, Node, Primitive, Query, Ray, RayOrder, TopDown};
/// use glam::Vec3;
/// let tris: Vec<[Vec3; 3]> = (0..8)
///     .map(|i| {
///         let o = Vec3::X * (2 * i) as f32;
///         [o, o + Vec3::X, o + Vec3::Y]
///     })
///     .collect();
/// assert_eq!(tris[1].bounds().min, Vec3::new(2.0, 0.0, 0.0));
/// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(tris.len())];
/// let mut idx = vec![0u32; tris.len()];
/// let tree = TopDown::default().build(&tris, &mut nodes, &mut idx)?;
/// assert_eq!(tree.primitive_count(), 8);
/// // Straight down onto the third triangle, 1 unit below the ray's start.
/// let down = Ray::new(Vec3::new(4.2, 0.2, 1.0), -Vec3::Z, f32::INFINITY)?;
/// let hit = tree.cast_ray(&tris, &down, RayOrder::default(), ())?.unwrap();
/// assert_eq!((hit.prim, hit.t), (2, 1.0));
/// assert!(tris[0].intersects(&[Vec3::new(0.5, 0.2, -1.0), Vec3::new(0.5, 0.2, 1.0), Vec3::Z]));
/// # Ok::<(), bvhkit::Error>(())
/// ```
impl Primitive for [Vec3; 3] {
    #[inline]
    fn bounds(&self) -> Aabb {
        Aabb::new(
            self[0].min(self[1]).min(self[2]),
            self[0].max(self[1]).max(self[2]),
        )
    }
    fn is_finite(&self) -> bool {
        self.iter().all(|p| p.is_finite())
    }
}

impl Primitive for Vec3 {
    #[inline]
    fn bounds(&self) -> Aabb {
        Aabb::from_point(*self)
    }
    fn is_finite(&self) -> bool {
        Vec3::is_finite(*self)
    }
}

impl Primitive for Aabb {
    #[inline]
    fn bounds(&self) -> Aabb {
        *self
    }
    fn is_finite(&self) -> bool {
        Aabb::is_finite(self) && self.min.cmple(self.max).all()
    }
}

#[cfg(feature = "sphere")]
impl Primitive for Sphere {
    fn bounds(&self) -> Aabb {
        crate::BoundingVolume::aabb(self)
    }
    fn is_finite(&self) -> bool {
        self.center.is_finite() && self.radius.is_finite() && self.radius >= 0.0
    }
}

impl<P: Primitive> Primitive for &P {
    fn bounds(&self) -> Aabb {
        (**self).bounds()
    }
    fn is_finite(&self) -> bool {
        (**self).is_finite()
    }
}

/// Checks a primitive slice once, before any min/max fold can hide a bad value.
/// An empty slice is valid: it builds the empty tree.
pub(crate) fn validate<P: Primitive>(prims: &[P]) -> Result<(), crate::Error> {
    validate_bounds(prims).map(|_| ())
}

/// [`validate`], returning what the same pass sees: the box around every
/// primitive and the box around their boxes' centres (both empty for no
/// primitives). Builders that need them save a pass over the input.
pub(crate) fn validate_bounds<P: Primitive>(prims: &[P]) -> Result<(Aabb, Aabb), crate::Error> {
    validate_bounds_each(prims, |_, _| {})
}

/// [`validate_bounds`], handing each primitive's box to `each` (with its
/// index) on the way: a builder that keeps the boxes fills its cache in the
/// same pass. On an error, what `each` was given is meaningless.
#[inline(always)]
pub(crate) fn validate_bounds_each<P: Primitive>(
    prims: &[P],
    mut each: impl FnMut(usize, &Aabb),
) -> Result<(Aabb, Aabb), crate::Error> {
    use crate::Error;
    if prims.len() > crate::tree::MAX_PRIMITIVES {
        return Err(Error::IndexOverflow { count: prims.len() });
    }
    // One branch-free pass for the common case; a bad primitive is looked
    // up again only to name it.
    let limit = Vec3::splat(MAX_COORDINATE);
    let in_range =
        |p: &P, b: &Aabb| p.is_finite() & b.min.abs().max(b.max.abs()).cmple(limit).all();
    let (mut scene, mut centres, mut ok) = (Aabb::EMPTY, Aabb::EMPTY, true);
    for (i, p) in prims.iter().enumerate() {
        let b = p.bounds();
        each(i, &b);
        ok &= in_range(p, &b);
        scene = scene.union(&b);
        centres.grow(b.center());
    }
    if !ok {
        for (i, p) in prims.iter().enumerate() {
            if !p.is_finite() {
                return Err(Error::NonFiniteCoordinate { primitive: i });
            }
            if !in_range(p, &p.bounds()) {
                return Err(Error::CoordinateOutOfRange { primitive: i });
            }
        }
    }
    Ok((scene, centres))
}
