//! Shape casts: the first primitive a moving sphere or box touches.
//!
//! Lecture: *moving objects*. A shape moving in a straight line touches a
//! primitive exactly when its centre's ray enters the Minkowski sum of the
//! two (the primitive grown by the shape), so a cast is a ray cast against
//! grown volumes. The tree grows each node's box by the shape's half extents
//! (a box around the shape, so conservative for a sphere) and reuses the
//! ray traversal; the primitive test computes the time of impact against
//! the primitive itself, not its box: a sphere swept past a triangle's
//! corner misses it even where it crosses the triangle's box.
//!
//! As for rays, the answer is defined by the primitive test alone
//! ([`CastTarget`]): the smallest `t` in `[0, t_max]`, ties going to the
//! lowest index, equal to [`brute_force::cast_closest`](super::brute_force::cast_closest)
//! on every tree.

use super::ray::{any_hit, closest_hit, Probe};
use super::{Hit, Ray, RayOrder, Tally};
use crate::bv::{Aabb, BoundingVolume};
use crate::primitive::Triangle;
use crate::tree::hierarchy::check_query;
use crate::tree::Hierarchy;
use crate::Error;
#[cfg(feature = "sphere")]
use crate::Sphere;
use glam::{DVec3, Vec3};

/// The shape a [`ShapeCast`] moves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Swept {
    /// A ball of this radius (`>= 0`; zero makes the cast a ray).
    Sphere {
        /// Radius.
        radius: f32,
    },
    /// An axis-aligned box with these half extents (each `>= 0`); it does
    /// not rotate as it moves.
    Box {
        /// Half the box's size on each axis.
        half: Vec3,
    },
}

/// A sphere or a box whose centre moves from `origin` along `origin + t *
/// dir`, `t` in `[0, t_max]`.
///
/// Made by [`ShapeCast::sphere`] or [`ShapeCast::aabb`], which check it, so
/// a query never sees a NaN or a negative size.
///
/// ```
/// use bvhkit::glam::Vec3;
/// use bvhkit::{Aabb, CastTarget, ShapeCast, Triangle};
/// // A floor at z = 0, a ball of radius 1 falling from z = 5.
/// let floor = Triangle::new(Vec3::new(-9.0, -9.0, 0.0), Vec3::new(9.0, -9.0, 0.0), Vec3::new(0.0, 9.0, 0.0));
/// let ball = ShapeCast::sphere(Vec3::new(0.0, 0.0, 5.0), 1.0, -Vec3::Z, 10.0)?;
/// assert_eq!(floor.cast_hit(&ball), Some(4.0));
/// // A box with half height 0.5 lands half a unit later.
/// let crate_ = Aabb::new(Vec3::new(-1.0, -1.0, 4.5), Vec3::new(1.0, 1.0, 5.5));
/// let fall = ShapeCast::aabb(&crate_, -Vec3::Z, 10.0)?;
/// assert_eq!(floor.cast_hit(&fall), Some(4.5));
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeCast {
    shape: Swept,
    centre: Ray,
}

impl ShapeCast {
    /// A sphere of `radius` centred at `centre`, moving along `dir` up to
    /// `t_max`. Refused ([`Error::InvalidQuery`]): a non-finite centre or
    /// direction, a zero direction, a radius that is NaN, negative or
    /// infinite, a `t_max` that is NaN or negative (it may be infinite).
    ///
    /// ```
    /// use bvhkit::{ShapeCast, Swept};
    /// use glam::Vec3;
    /// // A ball of radius 0.5 falling from z = 3 for at most 10 units of time.
    /// let fall = ShapeCast::sphere(Vec3::new(1.0, 1.0, 3.0), 0.5, -Vec3::Z, 10.0)?;
    /// assert_eq!(fall.shape(), Swept::Sphere { radius: 0.5 });
    /// assert!(ShapeCast::sphere(Vec3::ZERO, -1.0, Vec3::X, 1.0).is_err()); // negative radius
    /// assert!(ShapeCast::sphere(Vec3::ZERO, 1.0, Vec3::ZERO, 1.0).is_err()); // no direction
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn sphere(centre: Vec3, radius: f32, dir: Vec3, t_max: f32) -> Result<ShapeCast, Error> {
        if !(radius.is_finite() && radius >= 0.0) {
            return Err(Error::InvalidQuery(
                "a swept sphere needs a finite radius >= 0",
            ));
        }
        Ok(ShapeCast {
            shape: Swept::Sphere { radius },
            centre: centre_path(centre, dir, t_max)?,
        })
    }

    /// The box `start` moving along `dir` up to `t_max` (it does not
    /// rotate). Refused ([`Error::InvalidQuery`]): a box with a non-finite
    /// corner or inverted (`min > max` on an axis), a direction that is not
    /// finite or is zero, a `t_max` that is NaN or negative.
    ///
    /// ```
    /// use bvhkit::{Aabb, ShapeCast};
    /// use glam::Vec3;
    /// let crate_box = Aabb::new(Vec3::ZERO, Vec3::new(2.0, 1.0, 1.0));
    /// let slide = ShapeCast::aabb(&crate_box, Vec3::X, 5.0)?;
    /// assert_eq!(slide.half_extents(), Vec3::new(1.0, 0.5, 0.5));
    /// assert_eq!(slide.path().origin(), Vec3::new(1.0, 0.5, 0.5)); // its centre
    /// let inverted = Aabb::new(Vec3::ONE, Vec3::ZERO);
    /// assert!(ShapeCast::aabb(&inverted, Vec3::X, 5.0).is_err());
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn aabb(start: &Aabb, dir: Vec3, t_max: f32) -> Result<ShapeCast, Error> {
        if !start.min.is_finite() || !start.max.is_finite() || start.min.cmpgt(start.max).any() {
            return Err(Error::InvalidQuery(
                "a swept box needs finite corners with min <= max",
            ));
        }
        // The centre and half extents in f32 can round: a half extent is
        // raised by an ulp at a time until the swept box holds `start`.
        let centre = start.min * 0.5 + start.max * 0.5;
        let mut half = (start.max - centre).max(centre - start.min);
        for k in 0..3 {
            while half[k].is_finite()
                && (centre[k] - half[k] > start.min[k] || centre[k] + half[k] < start.max[k])
            {
                half[k] = half[k].next_up();
            }
        }
        if !half.is_finite() {
            return Err(Error::InvalidQuery(
                "a swept box is too large to take its half extents in f32",
            ));
        }
        Ok(ShapeCast {
            shape: Swept::Box { half },
            centre: centre_path(centre, dir, t_max)?,
        })
    }

    /// The shape moved.
    #[inline]
    pub const fn shape(&self) -> Swept {
        self.shape
    }

    /// The path of the shape's centre: origin, direction and `t_max`.
    #[inline]
    pub const fn path(&self) -> &Ray {
        &self.centre
    }

    /// The same cast ending at `t_max` (`>= 0`, not NaN, may be infinite).
    pub fn with_t_max(&self, t_max: f32) -> Result<ShapeCast, Error> {
        Ok(ShapeCast {
            centre: self.centre.with_t_max(t_max)?,
            ..*self
        })
    }

    /// Half extents of the box around the shape: how much the tree grows
    /// every node box it tests.
    #[inline]
    pub fn half_extents(&self) -> Vec3 {
        match self.shape {
            Swept::Sphere { radius } => Vec3::splat(radius),
            Swept::Box { half } => half,
        }
    }

    /// A box holding the shape at `t` (conservative: rounded outward).
    pub fn bounds_at(&self, t: f32) -> Aabb {
        let c = self.centre.origin() + self.centre.dir() * t;
        let h = self.half_extents() + c.abs() * (2.0 * f32::EPSILON);
        Aabb::new(c - h, c + h)
    }

    /// A box holding the whole sweep, `t` in `[0, t_max]` (a broad phase's
    /// fat bounds for a moving object); an infinite `t_max` gives infinite
    /// bounds along the motion.
    ///
    /// ```
    /// use bvhkit::{Aabb, BoundingVolume, ShapeCast};
    /// use glam::Vec3;
    /// let fall = ShapeCast::sphere(Vec3::new(0.0, 0.0, 3.0), 0.5, -Vec3::Z, 2.0)?;
    /// let fat = fall.swept_bounds(); // from z = 3 down to z = 1, radius 0.5 around
    /// assert!(fat.contains_aabb(&Aabb::new(Vec3::new(-0.5, -0.5, 0.5), Vec3::new(0.5, 0.5, 3.5))));
    /// assert!(fat.contains_aabb(&fall.bounds_at(1.0)));
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn swept_bounds(&self) -> Aabb {
        let start = self.bounds_at(0.0);
        let end = self.bounds_at(self.centre.t_max());
        // `0 * inf` on an axis the shape does not move along: NaN, kept as
        // the start's bounds on that axis.
        let min = Vec3::select(end.min.is_nan_mask(), start.min, start.min.min(end.min));
        let max = Vec3::select(end.max.is_nan_mask(), start.max, start.max.max(end.max));
        Aabb::new(min, max)
    }
}

/// The centre's path, refused with a message about casts (not rays).
fn centre_path(centre: Vec3, dir: Vec3, t_max: f32) -> Result<Ray, Error> {
    Ray::new(centre, dir, t_max).map_err(|_| {
        Error::InvalidQuery(
            "a shape cast needs a finite centre, a finite non-zero direction and t_max >= 0",
        )
    })
}

/// A primitive a [`ShapeCast`] can touch.
pub trait CastTarget {
    /// The smallest `t` in `[0, cast.t_max]` where the moving shape touches
    /// the primitive (`0` when it starts touching), or `None`. Computed in
    /// `f64` and rounded down to `f32`, so that moving the shape by the
    /// answer never carries it into the primitive by more than rounding.
    fn cast_hit(&self, cast: &ShapeCast) -> Option<f32>;
}

impl CastTarget for Triangle {
    /// Exact against the triangle, not its box: for a sphere, the union of
    /// the slab of thickness `2r` over the triangle and the capsules around
    /// its edges; for a box, the separating axes of a box and a triangle
    /// (the box's three, the triangle's normal and the nine edge crosses),
    /// each giving the interval of `t` where the projections overlap.
    fn cast_hit(&self, cast: &ShapeCast) -> Option<f32> {
        let v = self.v.map(|p| p.as_dvec3());
        let (o, d) = path(cast);
        let span = match cast.shape {
            Swept::Sphere { radius } => {
                sphere_triangle(o, d, v, radius as f64, cast.centre.t_max() as f64)
            }
            Swept::Box { half } => {
                box_triangle(o, d, v, half.as_dvec3(), cast.centre.t_max() as f64)
            }
        };
        first(span, cast)
    }
}

/// Three corners are a [`Triangle`]: the same test, the same answers.
impl CastTarget for [Vec3; 3] {
    #[inline]
    fn cast_hit(&self, cast: &ShapeCast) -> Option<f32> {
        Triangle::from(*self).cast_hit(cast)
    }
}

impl CastTarget for Vec3 {
    /// A point: when the shape first covers it.
    fn cast_hit(&self, cast: &ShapeCast) -> Option<f32> {
        let p = self.as_dvec3();
        let (o, d) = path(cast);
        let span = match cast.shape {
            Swept::Sphere { radius } => sphere_span(o, d, p, radius as f64),
            Swept::Box { half } => box_span(o, d, p - half.as_dvec3(), p + half.as_dvec3()),
        };
        first(span, cast)
    }
}

impl CastTarget for Aabb {
    /// A box: for a swept box, the grown box's slabs; for a sphere, the box
    /// with rounded edges and corners (three boxes grown on one axis each,
    /// and the twelve edge capsules).
    fn cast_hit(&self, cast: &ShapeCast) -> Option<f32> {
        let (lo, hi) = (self.min.as_dvec3(), self.max.as_dvec3());
        let (o, d) = path(cast);
        let span = match cast.shape {
            Swept::Sphere { radius } => rounded_box(o, d, lo, hi, radius as f64),
            Swept::Box { half } => {
                let h = half.as_dvec3();
                box_span(o, d, lo - h, hi + h)
            }
        };
        first(span, cast)
    }
}

#[cfg(feature = "sphere")]
impl CastTarget for Sphere {
    /// A ball: for a swept sphere, the ball grown by its radius; for a box,
    /// the box seen from the ball, which moves the other way (a rounded box).
    fn cast_hit(&self, cast: &ShapeCast) -> Option<f32> {
        let (c, r) = (self.center.as_dvec3(), self.radius as f64);
        let (o, d) = path(cast);
        let span = match cast.shape {
            Swept::Sphere { radius } => sphere_span(o, d, c, r + radius as f64),
            Swept::Box { half } => {
                let h = half.as_dvec3();
                rounded_box(c, -d, o - h, o + h, r)
            }
        };
        first(span, cast)
    }
}

impl<P: CastTarget> CastTarget for &P {
    fn cast_hit(&self, cast: &ShapeCast) -> Option<f32> {
        (**self).cast_hit(cast)
    }
}

/// A closed interval of `t`; `None` is empty.
type Span = Option<(f64, f64)>;

fn path(cast: &ShapeCast) -> (DVec3, DVec3) {
    (
        cast.centre.origin().as_dvec3(),
        cast.centre.dir().as_dvec3(),
    )
}

/// The earliest `t` of `span` in `[0, t_max]`, rounded down to `f32`.
fn first(span: Span, cast: &ShapeCast) -> Option<f32> {
    let (t0, t1) = span?;
    let t = t0.max(0.0);
    // Negated, so that a NaN (from a primitive with an infinite or NaN
    // coordinate, which no tree holds) is a miss.
    if t0.is_nan() || !(t <= t1 && t <= cast.centre.t_max() as f64) {
        return None;
    }
    let t32 = t as f32;
    Some(if t32 as f64 > t { t32.next_down() } else { t32 })
}

fn both(a: Span, b: Span) -> Span {
    let ((a0, a1), (b0, b1)) = (a?, b?);
    let (t0, t1) = (a0.max(b0), a1.min(b1));
    (t0 <= t1).then_some((t0, t1))
}

/// The earliest-starting of two spans that are not empty after `t = 0`
/// (the union's first entry is the smaller first entry).
fn earliest(a: Span, b: Span) -> Span {
    let live = |s: Span| s.filter(|&(_, t1)| t1 >= 0.0);
    match (live(a), live(b)) {
        (Some(x), Some(y)) => Some(if y.0.max(0.0) < x.0.max(0.0) { y } else { x }),
        (x, None) => x,
        (None, y) => y,
    }
}

/// Where `lo <= n . (o + t d) <= hi`.
fn plane_span(n: DVec3, o: DVec3, d: DVec3, lo: f64, hi: f64) -> Span {
    let (s, v) = (n.dot(o), n.dot(d));
    if v == 0.0 {
        return (lo <= s && s <= hi).then_some((f64::NEG_INFINITY, f64::INFINITY));
    }
    let (a, b) = ((lo - s) / v, (hi - s) / v);
    Some((a.min(b), a.max(b)))
}

/// Where the point `o + t d` is in the box `[lo, hi]`.
fn box_span(o: DVec3, d: DVec3, lo: DVec3, hi: DVec3) -> Span {
    let mut span = Some((f64::NEG_INFINITY, f64::INFINITY));
    for (k, axis) in [DVec3::X, DVec3::Y, DVec3::Z].into_iter().enumerate() {
        span = both(span, plane_span(axis, o, d, lo[k], hi[k]));
    }
    span
}

/// Where `o + t d` is within `r` of `c`.
fn sphere_span(o: DVec3, d: DVec3, c: DVec3, r: f64) -> Span {
    let m = o - c;
    let (a, b, cc) = (d.length_squared(), m.dot(d), m.length_squared() - r * r);
    let disc = b * b - a * cc;
    if disc < 0.0 || a == 0.0 {
        return None;
    }
    let s = libm::sqrt(disc);
    Some(((-b - s) / a, (-b + s) / a))
}

/// Where `o + t d` is within `r` of the segment `p q`, not counting its end
/// balls: the infinite cylinder cut by the planes through the ends. With
/// the balls at the ends (which callers add once per corner) it is the
/// capsule around the segment.
fn cylinder_span(o: DVec3, d: DVec3, p: DVec3, q: DVec3, r: f64) -> Span {
    let e = q - p;
    let l2 = e.length_squared();
    if l2 == 0.0 {
        return None;
    }
    // Distance to the axis squared, |(x - p) x e|^2 / |e|^2, as a quadratic
    // in t; the cross products keep the leading term >= 0 (no cancellation).
    let (me, de) = ((o - p).cross(e), d.cross(e));
    let (a, b, c) = (
        de.length_squared(),
        me.dot(de),
        me.length_squared() - r * r * l2,
    );
    let tube = if a == 0.0 {
        // Moving along the axis: inside for all t, or never.
        (c <= 0.0).then_some((f64::NEG_INFINITY, f64::INFINITY))
    } else {
        let disc = b * b - a * c;
        (disc >= 0.0).then(|| {
            let s = libm::sqrt(disc);
            ((-b - s) / a, (-b + s) / a)
        })
    };
    both(tube, plane_span(e, o, d, e.dot(p), e.dot(q)))
}

/// A swept sphere against a triangle: the slab of half thickness `r` over
/// the triangle, and the capsules around its edges (three cylinders and the
/// three corner balls). A path that misses the triangle's box grown by `r`
/// misses them all: most leaf tests end there.
fn sphere_triangle(o: DVec3, d: DVec3, [a, b, c]: [DVec3; 3], r: f64, t_max: f64) -> Span {
    let grown = box_span(o, d, a.min(b).min(c) - r, a.max(b).max(c) + r);
    if grown.is_none_or(|(t0, t1)| t1 < 0.0 || t0 > t_max) {
        return None;
    }
    let n = (b - a).cross(c - a);
    let len = n.length();
    let mut span = None;
    if len != 0.0 && len.is_finite() {
        // Not degenerate (a segment or a point is covered by its capsules).
        let n = n / len;
        let mut prism = plane_span(n, o, d, n.dot(a) - r, n.dot(a) + r);
        for (p, q) in [(a, b), (b, c), (c, a)] {
            // Inward normal of edge p q in the triangle's plane.
            let m = n.cross(q - p);
            prism = both(prism, plane_span(m, o, d, m.dot(p), f64::INFINITY));
        }
        span = prism;
    }
    for (p, q) in [(a, b), (b, c), (c, a)] {
        span = earliest(span, cylinder_span(o, d, p, q, r));
        span = earliest(span, sphere_span(o, d, p, r));
    }
    span
}

/// A swept box (half extents `h`) against a triangle: the intersection of
/// the intervals in which the projections overlap on each of the thirteen
/// candidate separating axes. A zero axis (parallel edges) constrains
/// nothing, as `plane_span` answers for `n = 0`.
fn box_triangle(o: DVec3, d: DVec3, v: [DVec3; 3], h: DVec3, t_max: f64) -> Span {
    let edges = [v[1] - v[0], v[2] - v[1], v[0] - v[2]];
    let mut axes = [DVec3::ZERO; 13];
    axes[0] = DVec3::X;
    axes[1] = DVec3::Y;
    axes[2] = DVec3::Z;
    axes[3] = edges[0].cross(edges[1]);
    for (i, e) in edges.iter().enumerate() {
        for (j, b) in [DVec3::X, DVec3::Y, DVec3::Z].iter().enumerate() {
            axes[4 + 3 * i + j] = e.cross(*b);
        }
    }
    let mut span = Some((f64::NEG_INFINITY, f64::INFINITY));
    for l in axes {
        let p = [l.dot(v[0]), l.dot(v[1]), l.dot(v[2])];
        let (lo, hi) = (p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2]));
        let reach = h.dot(l.abs());
        span = both(span, plane_span(l, o, d, lo - reach, hi + reach));
        // The box axes come first: most paths end here, outside the
        // triangle's box grown by the box, or beyond [0, t_max].
        let (t0, t1) = span?;
        if t1 < 0.0 || t0 > t_max {
            return None;
        }
    }
    span
}

/// Where `o + t d` is within `r` of the box `[lo, hi]`: the box grown by `r`
/// on one axis at a time, and the capsules around its twelve edges.
fn rounded_box(o: DVec3, d: DVec3, lo: DVec3, hi: DVec3, r: f64) -> Span {
    let mut span = None;
    for k in 0..3 {
        let mut g = DVec3::ZERO;
        g[k] = r;
        span = earliest(span, box_span(o, d, lo - g, hi + g));
    }
    let corner = |i: usize| {
        DVec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        )
    };
    for i in 0..8 {
        span = earliest(span, sphere_span(o, d, corner(i), r));
        for bit in [1, 2, 4] {
            if i & bit == 0 {
                span = earliest(span, cylinder_span(o, d, corner(i), corner(i | bit), r));
            }
        }
    }
    span
}

/// The closest primitive a shape cast touches, on any [`Hierarchy`] (see
/// [`Query::cast_shape`](super::Query::cast_shape)).
pub(crate) fn cast_shape<H: Hierarchy + ?Sized, P: CastTarget>(
    h: &H,
    prims: &[P],
    cast: &ShapeCast,
    order: RayOrder,
    tally: impl Tally,
) -> Result<Option<Hit>, Error> {
    check_query(h, prims.len())?;
    if h.is_empty() {
        return Ok(None);
    }
    let probe = Probe::swept(&cast.centre, &h.bv(h.root()).aabb(), cast.half_extents());
    closest_hit(
        h,
        &probe,
        |p| prims[p as usize].cast_hit(cast),
        order,
        tally,
    )
}

/// Some primitive a shape cast touches (see
/// [`Query::shape_hits_any`](super::Query::shape_hits_any)).
pub(crate) fn shape_hits_any<H: Hierarchy + ?Sized, P: CastTarget>(
    h: &H,
    prims: &[P],
    cast: &ShapeCast,
    tally: impl Tally,
) -> Result<Option<Hit>, Error> {
    check_query(h, prims.len())?;
    if h.is_empty() {
        return Ok(None);
    }
    let probe = Probe::swept(&cast.centre, &h.bv(h.root()).aabb(), cast.half_extents());
    any_hit(h, &probe, |p| prims[p as usize].cast_hit(cast), tally)
}

impl<B: BoundingVolume> crate::Bvh<'_, B> {
    /// The first primitive a moving sphere or box touches, or `None`: the
    /// smallest time of impact `t` in `[0, t_max]` (`0` when the shape
    /// starts touching), ties going to the lowest index. The answer equals
    /// [`brute_force::cast_closest`](crate::brute_force::cast_closest) for
    /// every volume type, layout and order; `tally` counts node tests
    /// (`Nv`) and primitive tests (`Np`).
    ///
    /// ```
    /// use bvhkit::glam::Vec3;
    /// use bvhkit::{Aabb, Node, RayOrder, ShapeCast, TopDown, Triangle};
    /// // Walls across x at x = 0, 2, 4, ... 14.
    /// let walls: Vec<Triangle> = (0..8).map(|i| {
    ///     let x = i as f32 * 2.0;
    ///     Triangle::new(Vec3::new(x, -5.0, -5.0), Vec3::new(x, 5.0, -5.0), Vec3::new(x, 0.0, 5.0))
    /// }).collect();
    /// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(8)];
    /// let mut idx = vec![0; 8];
    /// let bvh = TopDown::default().build(&walls, &mut nodes, &mut idx)?;
    /// // A ball of radius 0.5 rolling along +x from x = 5 touches the wall at x = 6.
    /// let ball = ShapeCast::sphere(Vec3::new(5.0, 0.0, 0.0), 0.5, Vec3::X, f32::INFINITY)?;
    /// let hit = bvh.cast_shape(&walls, &ball, RayOrder::DepthFirst, ())?.unwrap();
    /// assert_eq!((hit.prim, hit.t), (3, 0.5));
    /// // Above the walls' tops (z = 5) the ball passes over them all.
    /// let high = ShapeCast::sphere(Vec3::new(-1.0, 0.0, 6.0), 0.5, Vec3::X, 20.0)?;
    /// assert_eq!(bvh.cast_shape(&walls, &high, RayOrder::DepthFirst, ())?, None);
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn cast_shape<P: CastTarget>(
        &self,
        prims: &[P],
        cast: &ShapeCast,
        order: RayOrder,
        tally: impl Tally,
    ) -> Result<Option<Hit>, Error> {
        cast_shape(self, prims, cast, order, tally)
    }

    /// Some primitive the moving shape touches (not necessarily the first),
    /// or `None`: stops at the first found ("can this object move there?").
    pub fn shape_hits_any<P: CastTarget>(
        &self,
        prims: &[P],
        cast: &ShapeCast,
        tally: impl Tally,
    ) -> Result<Option<Hit>, Error> {
        shape_hits_any(self, prims, cast, tally)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::narrow::box_triangle_intersect;

    fn floats(seed: u64) -> impl FnMut() -> f32 {
        let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
        move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 40) as f32 / (1u64 << 24) as f32
        }
    }

    /// Whether the shape, grown by `grow` (or shrunk, when negative), touches
    /// `prim` with its centre at `c`: the oracle, from the exact closest
    /// point and the exact box-triangle test, independent of the cast code.
    fn touches(prim: &Prim, shape: Swept, c: Vec3, grow: f32) -> bool {
        match (prim, shape) {
            (Prim::Tri(t), Swept::Sphere { radius }) => {
                let r = (radius + grow).max(0.0) as f64;
                t.closest_point(c).distance_squared <= r * r
            }
            (Prim::Tri(t), Swept::Box { half }) => {
                let h = (half + grow).max(Vec3::ZERO);
                box_triangle_intersect(&Aabb::new(c - h, c + h), t)
            }
            (Prim::Box(b), Swept::Sphere { radius }) => {
                let q = c.clamp(b.min, b.max);
                q.distance(c) <= (radius + grow).max(0.0)
            }
            (Prim::Box(b), Swept::Box { half }) => {
                let h = (half + grow).max(Vec3::ZERO);
                Aabb::new(c - h, c + h).overlaps(b)
            }
            (Prim::Point(p), Swept::Sphere { radius }) => p.distance(c) <= (radius + grow).max(0.0),
            (Prim::Point(p), Swept::Box { half }) => {
                let h = (half + grow).max(Vec3::ZERO);
                (c - h).cmple(*p).all() && p.cmple(c + h).all()
            }
            #[cfg(feature = "sphere")]
            (Prim::Ball(s), Swept::Sphere { radius }) => {
                s.center.distance(c) <= (radius + s.radius + grow).max(0.0)
            }
            #[cfg(feature = "sphere")]
            (Prim::Ball(s), Swept::Box { half }) => {
                let h = (half + grow).max(Vec3::ZERO);
                let q = s.center.clamp(c - h, c + h);
                q.distance(s.center) <= (s.radius + grow).max(0.0)
            }
        }
    }

    enum Prim {
        Tri(Triangle),
        Box(Aabb),
        Point(Vec3),
        #[cfg(feature = "sphere")]
        Ball(Sphere),
    }

    impl Prim {
        fn cast_hit(&self, cast: &ShapeCast) -> Option<f32> {
            match self {
                Prim::Tri(t) => {
                    let hit = t.cast_hit(cast);
                    // Corners and references: the same test.
                    assert_eq!(t.v.cast_hit(cast), hit);
                    assert_eq!((&t).cast_hit(cast), hit);
                    hit
                }
                Prim::Box(b) => b.cast_hit(cast),
                Prim::Point(p) => p.cast_hit(cast),
                #[cfg(feature = "sphere")]
                Prim::Ball(s) => s.cast_hit(cast),
            }
        }
    }

    /// Against the oracle sampled along the path: the reported time touches
    /// (within a tolerance), no earlier sample touches, and a miss touches
    /// at no sample. Triangles (some degenerate), boxes, points and balls;
    /// swept spheres and boxes of every size including zero; paths through,
    /// past and along faces.
    #[test]
    fn time_of_impact_agrees_with_sampled_contact() {
        let mut f = floats(7);
        let mut p = move |s: f32| (Vec3::new(f(), f(), f()) - 0.5) * s;
        let (mut hits, mut misses, mut at_start) = (0, 0, 0);
        for case in 0..3000 {
            let a = p(8.0);
            let prim = match case % 6 {
                0 => Prim::Box(Aabb::new(a, a + p(4.0).abs())),
                1 => Prim::Tri(Triangle::new(a, a + p(6.0), a)),
                4 => Prim::Point(a),
                #[cfg(feature = "sphere")]
                5 => Prim::Ball(Sphere::new(a, p(4.0).x.abs())),
                _ => Prim::Tri(Triangle::new(a, a + p(6.0), a + p(6.0))),
            };
            let shape = if (case / 6) % 3 == 0 {
                Swept::Box {
                    half: p(2.0).abs() * f32::from(u8::from(case % 7 != 0)),
                }
            } else {
                Swept::Sphere {
                    radius: p(2.0).x.abs() * f32::from(u8::from(case % 5 != 0)),
                }
            };
            // One in eight starts at the primitive.
            let origin = if case % 8 == 5 { a + p(1.0) } else { p(16.0) };
            // Aimed near the primitive (so that most paths hit or graze),
            // one in four in a random direction.
            let mut dir = if case % 4 == 3 {
                p(2.0)
            } else {
                (a + p(2.0) - origin) / 8.0
            };
            if case % 11 == 0 {
                dir.z = 0.0; // parallel to a slab
            }
            let cast = match shape {
                Swept::Sphere { radius } => ShapeCast::sphere(origin, radius, dir, 16.0),
                Swept::Box { half } => {
                    ShapeCast::aabb(&Aabb::new(origin - half, origin + half), dir, 16.0)
                }
            };
            let Ok(cast) = cast else { continue };
            let shape = cast.shape();
            let at = |t: f32| origin + dir * t;
            let tol = 1e-3;
            let samples = 2000;
            let first = (0..=samples)
                .map(|i| 16.0 * i as f32 / samples as f32)
                .find(|&t| touches(&prim, shape, at(t), -tol));
            match prim.cast_hit(&cast) {
                Some(t) => {
                    hits += 1;
                    at_start += usize::from(t == 0.0);
                    assert!((0.0..=16.0).contains(&t), "case {case}: t = {t}");
                    assert!(
                        touches(&prim, shape, at(t), tol),
                        "case {case}: not touching at the reported t = {t}"
                    );
                    if let Some(s) = first {
                        assert!(t <= s, "case {case}: touching at {s} before t = {t}");
                    }
                    // The shape is clear of the primitive just before `t`.
                    let step = 16.0 / samples as f32;
                    let mut s = t - step;
                    while s >= 0.0 {
                        assert!(
                            !touches(&prim, shape, at(s), -tol),
                            "case {case}: touching at {s} < t = {t}"
                        );
                        s -= step;
                    }
                }
                None => {
                    misses += 1;
                    assert_eq!(first, None, "case {case}: missed a contact at {first:?}");
                }
            }
        }
        assert!(
            hits > 500 && misses > 500 && at_start > 50,
            "{hits} {misses} {at_start}"
        );
    }

    #[test]
    fn casts_refuse_bad_shapes_and_paths() {
        let bad = [
            ShapeCast::sphere(Vec3::ZERO, -1.0, Vec3::X, 1.0),
            ShapeCast::sphere(Vec3::ZERO, f32::NAN, Vec3::X, 1.0),
            ShapeCast::sphere(Vec3::ZERO, f32::INFINITY, Vec3::X, 1.0),
            ShapeCast::sphere(Vec3::NAN, 1.0, Vec3::X, 1.0),
            ShapeCast::sphere(Vec3::ZERO, 1.0, Vec3::ZERO, 1.0),
            ShapeCast::sphere(Vec3::ZERO, 1.0, Vec3::X, -1.0),
            ShapeCast::aabb(&Aabb::new(Vec3::ONE, Vec3::ZERO), Vec3::X, 1.0),
            ShapeCast::aabb(&Aabb::new(Vec3::ZERO, Vec3::INFINITY), Vec3::X, 1.0),
            ShapeCast::aabb(&Aabb::new(Vec3::ZERO, Vec3::ONE), Vec3::NAN, 1.0),
        ];
        for (k, b) in bad.iter().enumerate() {
            assert!(matches!(b, Err(Error::InvalidQuery(_))), "{k}: {b:?}");
        }
        // A box with one infinite corner is refused as a box (not later, as
        // a path whose centre is infinite).
        for corners in [
            (Vec3::ZERO, Vec3::INFINITY),
            (Vec3::NEG_INFINITY, Vec3::ZERO),
        ] {
            let half_open = ShapeCast::aabb(&Aabb::new(corners.0, corners.1), Vec3::X, 1.0);
            assert!(
                matches!(half_open, Err(Error::InvalidQuery(m)) if m.contains("finite corners"))
            );
        }
        let ok = ShapeCast::sphere(Vec3::ZERO, 1.0, Vec3::X, f32::INFINITY).unwrap();
        assert!(ok.with_t_max(f32::NAN).is_err());
        assert_eq!(ok.with_t_max(2.0).unwrap().path().t_max(), 2.0);
        // The largest boxes are fine: the centre is taken without overflow.
        let huge = Aabb::new(Vec3::splat(f32::MAX * 0.75), Vec3::splat(f32::MAX));
        let c = ShapeCast::aabb(&huge, Vec3::X, 1.0).unwrap();
        assert!(c.bounds_at(0.0).contains(&huge));
    }

    /// The swept box holds the box it was made from, even where the centre
    /// and half extents round in `f32`.
    #[test]
    fn a_swept_box_holds_its_start() {
        let mut f = floats(3);
        for _ in 0..2000 {
            let lo = Vec3::new(f(), f(), f()) * 1e6 - 5e5;
            let hi = lo + Vec3::new(f(), f(), f()) * 1e-3 * f() * 1e6;
            let start = Aabb::new(lo, hi);
            let cast = ShapeCast::aabb(&start, Vec3::X, 1.0).unwrap();
            let c = cast.path().origin();
            let h = cast.half_extents();
            assert!((c - h).cmple(lo).all() && (c + h).cmpge(hi).all());
            assert!(cast.bounds_at(0.0).contains(&start));
        }
        let c = ShapeCast::aabb(&Aabb::new(Vec3::ZERO, Vec3::ONE), Vec3::X, 1.0).unwrap();
        assert_eq!(
            (c.path().origin(), c.half_extents()),
            (Vec3::splat(0.5), Vec3::splat(0.5))
        );
        // A box whose rounded half extent falls short on the low side only
        // (found by a search over f32 boxes): raised until it holds.
        let (lo, hi) = (Vec3::splat(4477.117), Vec3::splat(694224.0));
        let c = ShapeCast::aabb(&Aabb::new(lo, hi), Vec3::X, 1.0).unwrap();
        let (centre, half) = (c.path().origin(), c.half_extents());
        assert!((centre - half).cmple(lo).all() && (centre + half).cmpge(hi).all());
    }

    /// The reference keeps the smallest `t` and, on a tie, the lowest
    /// index; a miss is `None`.
    #[test]
    fn brute_force_keeps_the_first_contact_and_the_lowest_index() {
        use crate::query::brute_force::cast_closest;
        let pts = [
            Vec3::new(6.0, 0.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::new(2.0, 5.0, 0.0),
            Vec3::new(5.0, 0.0, 0.0),
        ];
        let ball = ShapeCast::sphere(Vec3::ZERO, 1.0, Vec3::X, 10.0).unwrap();
        let hit = cast_closest(&pts, &ball).unwrap();
        assert_eq!((hit.prim, hit.t), (1, 2.0));
        let reversed: [Vec3; 5] = core::array::from_fn(|i| pts[4 - i]);
        let hit = cast_closest(&reversed, &ball).unwrap();
        assert_eq!((hit.prim, hit.t), (2, 2.0));
        let away = ShapeCast::sphere(Vec3::ZERO, 1.0, -Vec3::X, 10.0).unwrap();
        assert_eq!(cast_closest(&pts, &away), None);
    }

    #[test]
    fn swept_bounds_cover_the_path() {
        let c = ShapeCast::sphere(Vec3::ZERO, 1.0, Vec3::new(2.0, 0.0, 0.0), 3.0).unwrap();
        let b = c.swept_bounds();
        assert!(b.min.cmple(Vec3::new(-1.0, -1.0, -1.0)).all());
        assert!(b.max.cmpge(Vec3::new(7.0, 1.0, 1.0)).all());
        assert!(b.max.x < 7.001 && b.min.y > -1.001);
        let far = c.with_t_max(f32::INFINITY).unwrap().swept_bounds();
        assert_eq!(far.max.x, f32::INFINITY);
        assert!(far.max.y.is_finite() && far.min.z.is_finite());
    }
}
