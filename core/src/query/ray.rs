//! Ray casts: the closest primitive hit by a ray, or any hit at all.
//!
//! The answer is defined by the primitive test alone ([`RayTarget`]): the
//! smallest hit distance `t` in `[0, t_max]`, ties going to the lowest
//! primitive index. The tree only prunes: its slab test runs on each node's
//! enclosing box, padded so that rounding never rejects a box whose primitive
//! the `f64` primitive test would hit, and handles rays parallel to a slab
//! without dividing by zero.

use super::heap::{MinHeap, BEST_FIRST_QUEUE};
use super::stack::Stack;
use super::Tally;
use crate::bv::{Aabb, BoundingVolume};
use crate::primitive::Triangle;
use crate::tree::hierarchy::{check_query, BINARY_DFS_STACK, DFS_STACK};
use crate::tree::{Boxes4, Bvh, Content, Hierarchy, Kids, MAX_CHILDREN};
use crate::Error;
#[cfg(feature = "sphere")]
use crate::Sphere;
use glam::{DVec3, Vec3, Vec3A, Vec3Swizzles};

/// A ray `origin + t * dir` for `t` in `[0, t_max]`.
///
/// Made only by [`Ray::new`], which checks it: the fields are private, so a
/// ray with a NaN or zero direction (which no query could answer
/// meaningfully) cannot reach a query.
///
/// ```
/// use bvhkit::glam::Vec3;
/// use bvhkit::{Error, Ray};
/// let ray = Ray::new(Vec3::ZERO, Vec3::new(0.0, 0.0, 2.0), 10.0)?;
/// assert_eq!((ray.dir(), ray.t_max()), (Vec3::new(0.0, 0.0, 2.0), 10.0));
/// assert!(matches!(Ray::new(Vec3::ZERO, Vec3::ZERO, 1.0), Err(Error::InvalidQuery(_))));
/// assert!(Ray::new(Vec3::NAN, Vec3::X, 1.0).is_err());
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    origin: Vec3,
    dir: Vec3,
    t_max: f32,
}

impl Ray {
    /// A ray, checked: finite origin, finite non-zero direction, `t_max >= 0`
    /// and not NaN (it may be infinite).
    ///
    /// ```
    /// use bvhkit::query::Ray;
    /// use bvhkit::glam::Vec3;
    /// let r = Ray::new(Vec3::ZERO, Vec3::X, 10.0)?;
    /// assert_eq!((r.origin(), r.dir(), r.t_max()), (Vec3::ZERO, Vec3::X, 10.0));
    /// assert!(Ray::new(Vec3::ZERO, Vec3::new(f32::NAN, 0.0, 1.0), 1.0).is_err());
    /// assert!(Ray::new(Vec3::ZERO, Vec3::ZERO, 1.0).is_err());
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn new(origin: Vec3, dir: Vec3, t_max: f32) -> Result<Ray, Error> {
        if !origin.is_finite()
            || !dir.is_finite()
            || dir == Vec3::ZERO
            || t_max.is_nan()
            || t_max < 0.0
        {
            return Err(Error::InvalidQuery(
                "a ray needs a finite origin, a finite non-zero direction and t_max >= 0",
            ));
        }
        Ok(Ray { origin, dir, t_max })
    }

    /// Start point.
    #[inline]
    pub const fn origin(&self) -> Vec3 {
        self.origin
    }

    /// Direction (need not be unit length; `t` is measured in its units).
    #[inline]
    pub const fn dir(&self) -> Vec3 {
        self.dir
    }

    /// Largest `t` of interest (may be infinite).
    #[inline]
    pub const fn t_max(&self) -> f32 {
        self.t_max
    }

    /// The same ray ending at `t_max` (`>= 0`, not NaN, may be infinite).
    /// Cheap: origin and direction were checked when the ray was made.
    #[inline]
    pub fn with_t_max(&self, t_max: f32) -> Result<Ray, Error> {
        if t_max.is_nan() || t_max < 0.0 {
            return Err(Error::InvalidQuery("a ray needs t_max >= 0"));
        }
        Ok(Ray { t_max, ..*self })
    }
}

/// A ray hit: which primitive, and where along the ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Primitive index.
    pub prim: u32,
    /// Distance along the ray, in units of `dir`.
    pub t: f32,
}

impl Hit {
    /// Whether `self` beats `other` (smaller `t`, then smaller index).
    fn before(&self, other: &Option<Hit>) -> bool {
        match other {
            None => true,
            Some(o) => self.t < o.t || (self.t == o.t && self.prim < o.prim),
        }
    }
}

/// A primitive a ray can hit.
pub trait RayTarget {
    /// The smallest `t` in `[0, ray.t_max]` where the ray meets the primitive.
    fn ray_hit(&self, ray: &Ray) -> Option<f32>;
}

impl RayTarget for Triangle {
    /// Möller–Trumbore in `f64`. A ray in the triangle's plane does not hit it
    /// (it would touch only an edge, a set of zero area).
    fn ray_hit(&self, ray: &Ray) -> Option<f32> {
        moller_trumbore(self, ray).map(|m| m.t)
    }
}

/// Where a ray meets a triangle ([`Triangle::ray_intersection`]): the
/// distance of [`RayTarget::ray_hit`], plus the geometry a shader or a
/// contact needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit {
    /// Distance along the ray, in units of its direction: the `t` of
    /// [`RayTarget::ray_hit`] and of a tree's [`Hit`].
    pub t: f32,
    /// Barycentric coordinates `b` of the hit point (`b.x v[0] + b.y v[1] +
    /// b.z v[2]`), in `f64`, each in `[0, 1]`.
    pub barycentric: DVec3,
    /// The triangle's unit normal, `(v[1] - v[0]) x (v[2] - v[0])`
    /// normalised: counter-clockwise corners face it.
    pub normal: Vec3,
    /// Whether the ray arrives on the side `normal` points to.
    pub front: bool,
}

impl Triangle {
    /// The ray's hit on this triangle with its geometry: the same `t` as
    /// [`RayTarget::ray_hit`] (so a tree's [`Hit`] can be expanded after
    /// the query, for the one triangle it names), the barycentric
    /// coordinates, the unit normal and the side the ray arrives on.
    ///
    /// ```
    /// use bvhkit::{Query, Ray, RayOrder, RayTarget, TopDown, Triangle};
    /// use bvhkit::glam::{DVec3, Vec3};
    /// let floor = Triangle::new(Vec3::ZERO, Vec3::X * 4.0, Vec3::Y * 4.0);
    /// let down = Ray::new(Vec3::new(1.0, 2.0, 5.0), -Vec3::Z, f32::INFINITY)?;
    /// let hit = floor.ray_intersection(&down).unwrap();
    /// assert_eq!(Some(hit.t), floor.ray_hit(&down));
    /// assert_eq!((hit.t, hit.normal, hit.front), (5.0, Vec3::Z, true));
    /// assert_eq!(hit.barycentric, DVec3::new(0.25, 0.25, 0.5));
    /// // From below, the back.
    /// let up = Ray::new(Vec3::new(1.0, 2.0, -1.0), Vec3::Z, f32::INFINITY)?;
    /// assert!(!floor.ray_intersection(&up).unwrap().front);
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn ray_intersection(&self, ray: &Ray) -> Option<TriangleHit> {
        let m = moller_trumbore(self, ray)?;
        let [a, b, c] = self.v.map(|p| p.as_dvec3());
        let n = (b - a).cross(c - a);
        Some(TriangleHit {
            t: m.t,
            barycentric: DVec3::new(1.0 - m.u - m.v, m.u, m.v),
            normal: n.normalize_or_zero().as_vec3(),
            front: m.det > 0.0,
        })
    }
}

/// A Möller–Trumbore hit: `t` (checked against the ray), the barycentric
/// `u`, `v` of corners 1 and 2, and the determinant (positive when the ray
/// meets the front).
struct MollerTrumbore {
    t: f32,
    u: f64,
    v: f64,
    det: f64,
}

fn moller_trumbore(tri: &Triangle, ray: &Ray) -> Option<MollerTrumbore> {
    if F32_FILTER && surely_outside(tri, ray) {
        return None;
    }
    moller_trumbore_f64(tri, ray)
}

/// The test itself, in `f64`.
fn moller_trumbore_f64(tri: &Triangle, ray: &Ray) -> Option<MollerTrumbore> {
    let [a, b, c] = tri.v.map(|p| p.as_dvec3());
    let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
    let (e1, e2) = (b - a, c - a);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let inv = 1.0 / det;
    let s = o - a;
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = d.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv;
    // A ray nearly in the triangle's plane makes `det` tiny and `u`, `v`,
    // `t` unreliable: the "hit" can lie far outside the triangle (found
    // by fuzzing: a ray along an edge reported t = 0 at a point 2 mm from
    // it). Keep only hits inside the triangle's box, padded by less than
    // the tree's box test allows, so that the tree never prunes a box
    // whose triangle this test hits. The tree pads a box by `PAD` of its
    // magnitude and widens each entry and exit by `WIDEN` of its `t`: a
    // point `e` outside a face along axis `k` still passes when `e <=
    // WIDEN * t * |d_k|`. The check allows half the first and a quarter of
    // the second, less a bound on the rounding of the hit point (the
    // product `d * t` and the sum, each within 2^-53 of its size; 2^-51
    // leaves a factor 4). Without the second term, a triangle in a
    // coordinate plane through the origin (a floor at z = 0: no magnitude,
    // so no pad) was missed by a ray straight at it.
    let hit = o + d * t;
    let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
    let travel = (d * t).abs();
    let rounding = (travel + hit.abs()) * (1.0 / (1u64 << 51) as f64);
    let pad =
        lo.abs().max(hi.abs()) * (PAD as f64 * 0.5) + travel * (WIDEN as f64 * 0.25) - rounding;
    if hit.cmplt(lo - pad).any() || hit.cmpgt(hi + pad).any() {
        return None;
    }
    let t = within(t, ray)?;
    Some(MollerTrumbore { t, u, v, det })
}

#[cfg(feature = "sphere")]
impl RayTarget for Sphere {
    /// Entry point, or `t = 0` when the ray starts inside.
    fn ray_hit(&self, ray: &Ray) -> Option<f32> {
        let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
        let m = o - self.center.as_dvec3();
        let r = self.radius as f64;
        let c = m.length_squared() - r * r;
        if c <= 0.0 {
            return Some(0.0);
        }
        let (a, b) = (d.length_squared(), m.dot(d));
        let disc = b * b - a * c;
        if b > 0.0 || disc < 0.0 {
            return None;
        }
        within((-b - libm::sqrt(disc)) / a, ray)
    }
}

impl RayTarget for Aabb {
    /// Entry point, or `t = 0` when the ray starts inside.
    ///
    /// In `f32`, so that a device with an `f32`-only FPU runs it in hardware:
    /// each slab bound `(plane - o) / d` is two correctly rounded operations
    /// on exact inputs, within 2 ulp of its exact value, and the tree's node
    /// test widens its own bounds by more than that (`WIDEN`), so it never
    /// rejects a box this test hits nor enters later than this test says.
    fn ray_hit(&self, ray: &Ray) -> Option<f32> {
        let (o, d) = (ray.origin, ray.dir);
        let (mut t0, mut t1) = (0.0f32, ray.t_max);
        for k in 0..3 {
            if d[k] == 0.0 {
                if o[k] < self.min[k] || o[k] > self.max[k] {
                    return None;
                }
                continue;
            }
            let (a, b) = ((self.min[k] - o[k]) / d[k], (self.max[k] - o[k]) / d[k]);
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
            if t0 > t1 {
                return None;
            }
        }
        Some(t0)
    }
}

/// Three corners are a [`Triangle`]: the same test, the same answers.
impl RayTarget for [Vec3; 3] {
    #[inline]
    fn ray_hit(&self, ray: &Ray) -> Option<f32> {
        Triangle::from(*self).ray_hit(ray)
    }
}

impl<P: RayTarget> RayTarget for &P {
    fn ray_hit(&self, ray: &Ray) -> Option<f32> {
        (**self).ray_hit(ray)
    }
}

/// Whether [`surely_outside`] runs before the `f64` test: only where `f64`
/// is costly. On x86, Arm64 and WebAssembly an `f64` operation costs what
/// an `f32` one does, and the filter made rays 28% slower on the armadillo
/// (it adds its own work to every test that it cannot settle, and saves
/// only a conversion and a division on those it can); on a
/// microcontroller whose FPU is single precision, every `f64` operation is
/// a software routine, and the filter saves most of them.
const F32_FILTER: bool = !cfg!(any(
    target_arch = "x86_64",
    target_arch = "x86",
    target_arch = "aarch64",
    target_arch = "wasm32"
));

/// Whether the `f64` test below would certainly reject the ray for
/// passing beside the triangle (`u < 0`, `v < 0` or `u + v > 1`), decided
/// in `f32` with a bound on its rounding: most triangles a ray is tested
/// against are missed to the side, and this settles them without the
/// conversions to `f64` and the division (on a microcontroller with an
/// `f32` unit, without software `f64`). It never decides a case the `f64`
/// test could answer otherwise, so answers do not change (a unit test
/// checks it on rays aimed at edges and corners).
///
/// The bound: the determinant and the numerators of `u` and `v` are each a
/// sum of six products of three differences of the inputs (`e1 . (d x
/// e2)`, `s . (d x e2)`, `d . (s x e1)`); each product, in `f32`, carries
/// at most 7 roundings (two differences, two products, the cross
/// product's difference, the dot product's two sums), so its error is
/// under `7.1 eps` of its size, and the sum's under `7.1 eps` of the sum of
/// the sizes, which the same formulas on absolute values give (`eps =
/// 2^-24`). Twice that (`16 eps`), and `4 eta (|outer|_1 + 1)` for
/// products rounded into the subnormal range (each off by at most `eta =
/// 2^-150`, scaled by the outer factor), bound the error. A side is
/// decided only when the `f32` value clears twice its bound, so the exact
/// value clears it once, a margin some 10^9 times the `f64` test's own
/// rounding, which therefore sees the same side. Sizes from 2^120 up (an
/// `f32` product could overflow) are left to `f64`.
#[inline(always)]
fn surely_outside(tri: &Triangle, ray: &Ray) -> bool {
    const EPS16: f32 = 16.0 * (f32::EPSILON * 0.5);
    const ETA4: f32 = 4.0 * f32::from_bits(1) * 0.5; // 4 * 2^-150 = 2^-148
    const LIMIT: f32 = (1u128 << 120) as f32;
    let [a, b, c] = tri.v.map(Vec3A::from);
    let (o, d) = (Vec3A::from(ray.origin), Vec3A::from(ray.dir));
    let (e1, e2, s) = (b - a, c - a, o - a);
    let (p, q) = (d.cross(e2), s.cross(e1));
    let (det, u, v) = (e1.dot(p), s.dot(p), d.dot(q));
    // The same sums with every term's size: `|x| . (|y| x |z|)` with the
    // cross product's difference made a sum.
    let size = |x: Vec3A, y: Vec3A, z: Vec3A| {
        let (y, z) = (y.abs(), z.abs());
        let pos = y.yzx() * z.zxy() + y.zxy() * z.yzx();
        x.abs().dot(pos)
    };
    let (m_det, m_u, m_v) = (size(e1, d, e2), size(s, d, e2), size(d, s, e1));
    // NaN fails these too: left to `f64`.
    if !(m_det < LIMIT && m_u < LIMIT && m_v < LIMIT) {
        return false;
    }
    let l1 = |x: Vec3A| x.abs().element_sum() + 1.0;
    let err_det = EPS16 * m_det + ETA4 * l1(e1);
    let err_u = EPS16 * m_u + ETA4 * l1(s);
    let err_v = EPS16 * m_v + ETA4 * l1(d);
    // Finite here (the sizes are), so no NaN.
    if det.abs() <= 2.0 * err_det {
        return false; // the sign of the determinant is not certain
    }
    let (u, v, det) = if det < 0.0 {
        (-u, -v, -det)
    } else {
        (u, v, det)
    };
    // (`u > 1` needs no test of its own: with `v >= 0` it makes `u + v > 1`.)
    u < -2.0 * err_u || v < -2.0 * err_v || (u + v) - det > 2.0 * (err_u + err_v + err_det)
}

fn within(t: f64, ray: &Ray) -> Option<f32> {
    let t32 = t as f32;
    (t >= 0.0 && t32 <= ray.t_max).then_some(t32)
}

/// The node test: the ray's parameter interval inside `b` (padded), as its
/// entry `t`, or `None` when the ray misses.
///
/// The three axes are computed side by side in one 4-lane register
/// (`Vec3A`), with no branch per axis: the scalar loop it replaced spent
/// about 250 instructions per box on indexing and branches, and this test
/// runs once per child visited. A lane is ignored (as `f32::max`/`min`
/// ignore a NaN operand) where the ray is parallel to that slab, or where
/// `0 * inf` gives NaN; since the interval only shrinks axis by axis, taking
/// the largest entry and smallest exit at the end gives the answer the
/// axis-by-axis loop with early exits gave.
#[inline(always)]
fn slab(b: &Aabb, ray: &Ray, inv: Vec3) -> Option<f32> {
    // The rounding margin, plus a pad of each coordinate's size that covers
    // the f64 primitive test's rounding.
    let (mn, mx) = (Vec3A::from(b.min), Vec3A::from(b.max));
    let pad = mn.abs().max(mx.abs()) * PAD;
    let (lo, hi) = (mn - pad, mx + pad);
    let o = Vec3A::from(ray.origin);
    let parallel = Vec3A::from(ray.dir).cmpeq(Vec3A::ZERO);
    // A ray parallel to a slab misses unless it starts between its planes.
    if (parallel & (o.cmplt(lo) | o.cmpgt(hi))).any() {
        return None;
    }
    let i = Vec3A::from(inv);
    let (a, c) = ((lo - o) * i, (hi - o) * i);
    let swap = a.cmple(c);
    let (near, far) = (Vec3A::select(swap, a, c), Vec3A::select(swap, c, a));
    let (near, far) = (near - near.abs() * WIDEN, far + far.abs() * WIDEN);
    // Lanes that bound nothing: parallel, or NaN (NaN != NaN).
    let (near_ok, far_ok) = (near.cmpeq(near) & !parallel, far.cmpeq(far) & !parallel);
    let near = Vec3A::select(near_ok, near, Vec3A::NEG_INFINITY);
    let far = Vec3A::select(far_ok, far, Vec3A::INFINITY);
    let t0 = near.max_element().max(0.0);
    let t1 = far.min_element().min(ray.t_max + ray.t_max * WIDEN);
    // Not `t0 <= t1`: a NaN bound (inf - inf after an overflow) keeps the box.
    if t0 > t1 {
        None
    } else {
        Some(t0)
    }
}

/// [`slab`] for four boxes at once, lane by lane the same answer: the entry
/// `t` of each box the ray hits. Both take the larger (smaller) of a NaN and
/// a number to be the number, so a `0 * inf` keeps the box in both.
#[inline(always)]
fn slab4(b: &Boxes4, ray: &Ray, inv: Vec3) -> [Option<f32>; MAX_CHILDREN] {
    use glam::{BVec4A, Vec4};
    let (mut t0, mut t1) = (Vec4::ZERO, Vec4::splat(ray.t_max + ray.t_max * WIDEN));
    let mut live = BVec4A::TRUE;
    for k in 0..3 {
        let (mn, mx) = (Vec4::from_array(b.min[k]), Vec4::from_array(b.max[k]));
        let pad = mn.abs().max(mx.abs()) * PAD;
        let (lo, hi) = (mn - pad, mx + pad);
        let o = Vec4::splat(ray.origin[k]);
        if ray.dir[k] == 0.0 {
            live &= o.cmpge(lo) & o.cmple(hi);
            continue;
        }
        let i = Vec4::splat(inv[k]);
        let (a, c) = ((lo - o) * i, (hi - o) * i);
        let swap = a.cmple(c);
        let (near, far) = (Vec4::select(swap, a, c), Vec4::select(swap, c, a));
        let (near, far) = (near - near.abs() * WIDEN, far + far.abs() * WIDEN);
        // Explicit selects, not min/max: their NaN behaviour differs by
        // platform, and a NaN must leave the bound as it was.
        t0 = Vec4::select(near.cmpgt(t0), near, t0);
        t1 = Vec4::select(far.cmplt(t1), far, t1);
    }
    let hit = live & t0.cmple(t1);
    let t = t0.to_array();
    core::array::from_fn(|k| hit.test(k).then_some(t[k]))
}

/// What every node test of one ray shares, worked out once per ray.
///
/// The general tests ([`slab`], [`slab4`]) pad each box by a fraction of its
/// own coordinates and handle rays parallel to a slab lane by lane. For the
/// usual ray, whose `1 / dir` is finite on every axis, the same margin can be
/// paid once: padding a box by `p` along an axis moves its entry and exit by
/// `p * |1 / dir|` along the ray, so a pad taken from the root box (at least
/// every node's own pad, hence at least as conservative) becomes a per-axis
/// slack in `t`, and the rounding margin is applied once to the final entry
/// and exit instead of to every lane. About half the instructions of the
/// general test per box, with the same guarantee: a box whose primitive the
/// `f64` primitive test would hit is never rejected.
///
/// A swept shape is the same probe ([`Probe::swept`]): its centre's ray
/// against every box grown by the shape's half extents (their Minkowski
/// sum), the growth folded into the per-axis slack.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Probe<G: Growth = NoGrowth> {
    ray: Ray,
    /// How much every box grows on each side: nothing for a ray.
    grow: G,
    inv: Vec3,
    /// Whether the fast test applies (finite `1 / dir` and slack).
    fast: bool,
    origin: Vec3A,
    inv_a: Vec3A,
    /// Per-axis slack in `t`: twice the root's pad times `|1 / dir|` (twice,
    /// so that it also covers the rounding of `(lo - o) / dir` before the
    /// slack is taken off).
    slack: Vec3A,
    /// `t_max` widened by the rounding margin.
    t_max: f32,
}

/// Rounding margin of the slab test: 2 * gamma(3) of PBRT, rounded up.
const WIDEN: f32 = 4.0e-7;
/// The pad of a box, per unit of its largest coordinate magnitude: covers the
/// `f64` primitive test's rounding with a wide margin.
const PAD: f32 = 1.0 / 1_048_576.0;

/// How a [`Probe`] grows each box before testing it. A ray's probe holds
/// [`NoGrowth`], which is zero-sized and compiles away: ray queries carry
/// no code for swept shapes (firmware sizes unchanged).
pub(crate) trait Growth: Copy + core::fmt::Debug {
    /// Whether boxes grow at all.
    const GROWS: bool;
    /// `b` grown on every side.
    fn grown(&self, b: &Aabb) -> Aabb;
}

/// A ray's probe: boxes as they are.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NoGrowth;

impl Growth for NoGrowth {
    const GROWS: bool = false;
    #[inline(always)]
    fn grown(&self, b: &Aabb) -> Aabb {
        *b
    }
}

/// A swept shape's half extents.
impl Growth for Vec3 {
    const GROWS: bool = true;
    #[inline(always)]
    fn grown(&self, b: &Aabb) -> Aabb {
        Aabb::new(b.min - *self, b.max + *self)
    }
}

impl Probe {
    fn new(ray: &Ray, root: &Aabb) -> Probe {
        let inv = ray.dir.recip();
        let magnitude = Vec3A::from(root.min.abs().max(root.max.abs()));
        let inv_a = Vec3A::from(inv);
        let slack = magnitude * (2.0 * PAD) * inv_a.abs();
        Probe {
            grow: NoGrowth,
            ray: *ray,
            inv,
            fast: inv_a.is_finite() && slack.is_finite(),
            origin: Vec3A::from(ray.origin),
            inv_a,
            slack,
            t_max: ray.t_max + ray.t_max * WIDEN,
        }
    }
}

impl Probe<Vec3> {
    /// The probe of a shape with half extents `grow` (`>= 0`, finite) whose
    /// centre follows `ray`: each box `b` is tested as `[b.min - grow,
    /// b.max + grow]`. The pad is sized from the grown root, so it also
    /// covers the rounding of `grow * |1 / dir|` in the slack.
    pub(crate) fn swept(ray: &Ray, root: &Aabb, grow: Vec3) -> Probe<Vec3> {
        let inv = ray.dir.recip();
        let grown = Aabb::new(root.min - grow, root.max + grow);
        let magnitude = Vec3A::from(grown.min.abs().max(grown.max.abs()));
        let inv_a = Vec3A::from(inv);
        let slack = (magnitude * (2.0 * PAD) + Vec3A::from(grow)) * inv_a.abs();
        Probe {
            grow,
            ray: *ray,
            inv,
            fast: inv_a.is_finite() && slack.is_finite(),
            origin: Vec3A::from(ray.origin),
            inv_a,
            slack,
            t_max: ray.t_max + ray.t_max * WIDEN,
        }
    }
}

impl<G: Growth> Probe<G> {
    /// The entry `t` of the ray into `b`, or `None` when it misses.
    #[inline(always)]
    fn enter(&self, b: &Aabb) -> Option<f32> {
        if !self.fast {
            return slab(&self.grow.grown(b), &self.ray, self.inv);
        }
        let (mn, mx) = (Vec3A::from(b.min), Vec3A::from(b.max));
        let (a, c) = (
            (mn - self.origin) * self.inv_a,
            (mx - self.origin) * self.inv_a,
        );
        // No lane is NaN here (finite `inv`, finite or infinite differences),
        // so the plain min / max are exact on every platform.
        let near = (a.min(c) - self.slack).max_element();
        let far = (a.max(c) + self.slack).min_element();
        // A NaN (inf - inf after an overflow) keeps the box, as f32::max
        // and f32::min ignore it.
        let t0 = (near - near.abs() * WIDEN).max(0.0);
        let t1 = (far + far.abs() * WIDEN).min(self.t_max);
        if t0 > t1 {
            None
        } else {
            Some(t0)
        }
    }

    /// [`Probe::enter`] for four boxes at once, lane by lane the same answer.
    #[inline(always)]
    fn enter4(&self, b: &Boxes4) -> [Option<f32>; MAX_CHILDREN] {
        use glam::Vec4;
        if !self.fast {
            if G::GROWS {
                // A swept shape moving parallel to a slab: box by box.
                return core::array::from_fn(|k| self.enter(&b.get(k)));
            }
            return slab4(b, &self.ray, self.inv);
        }
        let (mut near, mut far) = (Vec4::NEG_INFINITY, Vec4::INFINITY);
        for k in 0..3 {
            let (mn, mx) = (Vec4::from_array(b.min[k]), Vec4::from_array(b.max[k]));
            let (o, i, s) = (
                Vec4::splat(self.origin[k]),
                Vec4::splat(self.inv_a[k]),
                Vec4::splat(self.slack[k]),
            );
            let (a, c) = ((mn - o) * i, (mx - o) * i);
            near = near.max(a.min(c) - s);
            far = far.min(a.max(c) + s);
        }
        let t0 = near - near.abs() * WIDEN;
        let t1 = far + far.abs() * WIDEN;
        let (t0, t1) = (t0.to_array(), t1.to_array());
        core::array::from_fn(|k| {
            let (t0, t1) = (t0[k].max(0.0), t1[k].min(self.t_max));
            (t0 <= t1 || t0.is_nan() || t1.is_nan()).then_some(t0)
        })
    }
}

/// Entry `t` of each child of a node (`None` where the ray misses), four at
/// once when the layout stores the children's boxes side by side.
#[inline(always)]
fn enter_children<H: Hierarchy + ?Sized, G: Growth>(
    h: &H,
    kids: &Kids,
    probe: &Probe<G>,
) -> [Option<f32>; MAX_CHILDREN] {
    if let Some(b) = h.children_boxes(kids) {
        return probe.enter4(b);
    }
    let mut out = [None; MAX_CHILDREN];
    for (o, &c) in out.iter_mut().zip(kids.of_arity(H::ARITY)) {
        *o = enter(h, c, probe);
    }
    out
}

/// How a ray query orders the nodes it visits.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum RayOrder {
    /// Depth-first, nearer child first, pruning by the best hit so far.
    #[default]
    DepthFirst,
    /// Best-first: always open the node with the smallest entry distance
    /// (a fixed queue of [`BEST_FIRST_QUEUE`] entries; when it is full the
    /// overflow is searched depth-first, so nothing is skipped).
    BestFirst,
}

impl<B: BoundingVolume> Bvh<'_, B> {
    /// The closest primitive the ray hits, or `None`. The answer equals
    /// [`brute_force::ray_closest`](crate::brute_force::ray_closest) for every
    /// volume type and order; `tally` counts the node tests (`Nv`) and
    /// primitive tests (`Np`).
    ///
    /// ```
    /// use bvhkit::{Aabb, Node, TopDown, Triangle};
    /// use bvhkit::query::{Ray, RayOrder};
    /// use glam::Vec3;
    /// // A row of walls along x, at x = 0, 2, 4, ...
    /// let walls: Vec<Triangle> = (0..8).map(|i| {
    ///     let x = i as f32 * 2.0;
    ///     Triangle::new(Vec3::new(x, -5.0, -5.0), Vec3::new(x, 5.0, -5.0), Vec3::new(x, 0.0, 5.0))
    /// }).collect();
    /// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(8)];
    /// let mut idx = vec![0; 8];
    /// let bvh = TopDown::default().with_max_leaf_size(1).build(&walls, &mut nodes, &mut idx)?;
    /// let ray = Ray::new(Vec3::new(5.0, 0.0, 0.0), Vec3::X, f32::INFINITY)?;
    /// let hit = bvh.cast_ray(&walls, &ray, RayOrder::BestFirst, ())?.unwrap();
    /// assert_eq!((hit.prim, hit.t), (3, 1.0));
    /// assert!(bvh.ray_hits_any(&walls, &Ray::new(Vec3::ZERO, -Vec3::X, 0.5)?, ())?.is_some());
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn cast_ray<P: RayTarget>(
        &self,
        prims: &[P],
        ray: &Ray,
        order: RayOrder,
        tally: impl Tally,
    ) -> Result<Option<Hit>, Error> {
        cast_ray(self, prims, ray, order, tally)
    }

    /// Some primitive the ray hits (not necessarily the closest), or `None`:
    /// stops at the first hit (shadow and line-of-sight rays).
    pub fn ray_hits_any<P: RayTarget>(
        &self,
        prims: &[P],
        ray: &Ray,
        tally: impl Tally,
    ) -> Result<Option<Hit>, Error> {
        ray_hits_any(self, prims, ray, tally)
    }
}

/// The ray's entry parameter into a node's volume (through its box).
#[inline(always)]
pub(crate) fn enter<H: Hierarchy + ?Sized, G: Growth>(
    h: &H,
    n: u32,
    probe: &Probe<G>,
) -> Option<f32> {
    probe.enter(&h.bv(n).aabb())
}

/// Tests a leaf's primitives with `hit` (a primitive's entry `t`, or `None`),
/// keeping the closest hit in `best`.
#[inline(always)]
fn closest_in_leaf(
    here: &[u32],
    hit: &impl Fn(u32) -> Option<f32>,
    best: &mut Option<Hit>,
    tally: &mut impl Tally,
) {
    tally.prim_tests(here.len() as u32);
    for &p in here {
        if let Some(t) = hit(p) {
            let h = Hit { prim: p, t };
            if h.before(best) {
                *best = Some(h);
            }
        }
    }
}

/// Closest hit on any [`Hierarchy`] (see [`Bvh::cast_ray`]).
pub(crate) fn cast_ray<H: Hierarchy + ?Sized, P: RayTarget>(
    h: &H,
    prims: &[P],
    ray: &Ray,
    order: RayOrder,
    tally: impl Tally,
) -> Result<Option<Hit>, Error> {
    check_query(h, prims.len())?;
    if h.is_empty() {
        return Ok(None);
    }
    let probe = Probe::new(ray, &h.bv(h.root()).aabb());
    closest_hit(h, &probe, |p| prims[p as usize].ray_hit(ray), order, tally)
}

/// Closest hit of a probe whose primitive test is `hit` (a ray's, or a
/// swept shape's through its centre): the traversal both queries share.
#[inline(always)]
pub(crate) fn closest_hit<H: Hierarchy + ?Sized, G: Growth>(
    h: &H,
    probe: &Probe<G>,
    hit: impl Fn(u32) -> Option<f32>,
    order: RayOrder,
    mut tally: impl Tally,
) -> Result<Option<Hit>, Error> {
    tally.bv_tests(1);
    let Some(t_root) = enter(h, h.root(), probe) else {
        return Ok(None);
    };
    match order {
        // Each order in its own function, so only its stack is on the call stack.
        RayOrder::DepthFirst if H::ARITY == 2 => {
            ray_depth_first::<H, G, _, BINARY_DFS_STACK>(h, &hit, probe, t_root, &mut tally)
        }
        RayOrder::DepthFirst => {
            ray_depth_first::<H, G, _, DFS_STACK>(h, &hit, probe, t_root, &mut tally)
        }
        RayOrder::BestFirst => ray_best_first(h, &hit, probe, t_root, &mut tally),
    }
}

/// Depth-first closest hit, nearer child first, on a stack of `N` entries.
#[inline(never)]
fn ray_depth_first<H: Hierarchy + ?Sized, G: Growth, F: Fn(u32) -> Option<f32>, const N: usize>(
    h: &H,
    hit: &F,
    probe: &Probe<G>,
    t_root: f32,
    tally: &mut impl Tally,
) -> Result<Option<Hit>, Error> {
    let mut best: Option<Hit> = None;
    // The best hit's distance (infinite before the first hit): a node whose
    // entry lies beyond it cannot hold a closer (or tying) hit.
    let mut best_t = f32::INFINITY;
    let mut stack = Stack::<(u32, f32), N>::with((h.root(), t_root), h.depth());
    // The node to open next: the nearest child of the last node opened is
    // taken at once, without a round trip through the stack.
    let mut next = stack.pop();
    while let Some((n, t)) = next {
        next = None;
        if t <= best_t {
            match h.content(n) {
                Content::Leaf(here) => {
                    closest_in_leaf(here, hit, &mut best, tally);
                    best_t = best.map_or(f32::INFINITY, |b| b.t);
                }
                Content::Inner(kids) => {
                    let entries = enter_children(h, &kids, probe);
                    let kids = kids.of_arity(H::ARITY);
                    tally.bv_tests(kids.len() as u32);
                    next = nearest_first(kids, &entries, &mut stack)?;
                }
            }
        }
        if next.is_none() {
            next = stack.pop();
        }
    }
    Ok(best)
}

/// Pushes the children the ray enters, farthest first, except the nearest,
/// which it returns (`None` when the ray enters none).
#[inline(always)]
fn nearest_first<const N: usize>(
    kids: &[u32],
    entries: &[Option<f32>; MAX_CHILDREN],
    stack: &mut Stack<(u32, f32), N>,
) -> Result<Option<(u32, f32)>, Error> {
    if let ([a, b], [ea, eb, ..]) = (kids, entries) {
        // A binary node: no sort, at most one push.
        return Ok(match (*ea, *eb) {
            (Some(ta), Some(tb)) => {
                let (near, far) = if tb < ta {
                    ((*b, tb), (*a, ta))
                } else {
                    ((*a, ta), (*b, tb))
                };
                stack.push(far)?;
                Some(near)
            }
            (Some(ta), None) => Some((*a, ta)),
            (None, Some(tb)) => Some((*b, tb)),
            (None, None) => None,
        });
    }
    // Wider nodes: sort keys (entry bits above child slot; a missed child
    // sorts last) with a fixed network of compare-exchanges, which compile
    // to conditional moves: the insertion sort it replaced mispredicted on
    // most nodes. Entries are >= +0, whose bit patterns order like the values.
    const _: () = assert!(MAX_CHILDREN == 4, "the network and the slot mask assume 4");
    let mut key = [u64::MAX; MAX_CHILDREN];
    for (k, (slot, entry)) in key.iter_mut().zip(entries).enumerate().take(kids.len()) {
        *slot = entry.map_or(u64::MAX, |t| {
            (u64::from((t + 0.0).to_bits()) << 32) | k as u64
        });
    }
    for (i, j) in [(0, 1), (2, 3), (0, 2), (1, 3), (1, 2)] {
        let (lo, hi) = (key[i].min(key[j]), key[i].max(key[j]));
        key[i] = lo;
        key[j] = hi;
    }
    let m = key.iter().take_while(|&&k| k != u64::MAX).count();
    let unkey = |k: u64| (kids[(k & 3) as usize], f32::from_bits((k >> 32) as u32));
    for &k in key[1..m.max(1)].iter().rev() {
        stack.push(unkey(k))?;
    }
    let nearest = (m > 0).then(|| unkey(key[0]));
    Ok(nearest)
}

/// Best-first closest hit on the fixed queue.
#[inline(never)]
fn ray_best_first<H: Hierarchy + ?Sized, G: Growth>(
    h: &H,
    hit: &impl Fn(u32) -> Option<f32>,
    probe: &Probe<G>,
    t_root: f32,
    tally: &mut impl Tally,
) -> Result<Option<Hit>, Error> {
    let mut best: Option<Hit> = None;
    let beaten = |t: f32, best: &Option<Hit>| best.is_some_and(|b| t > b.t);
    let mut heap = MinHeap::<BEST_FIRST_QUEUE>::new();
    heap.push(t_root as f64, h.root());
    while let Some((t, n)) = heap.pop() {
        if beaten(t as f32, &best) {
            // Every queued node is at least this far: done.
            break;
        }
        match h.content(n) {
            Content::Leaf(here) => closest_in_leaf(here, hit, &mut best, tally),
            Content::Inner(kids) => {
                let entries = enter_children(h, &kids, probe);
                let kids = kids.of_arity(H::ARITY);
                tally.bv_tests(kids.len() as u32);
                for (&c, &entry) in kids.iter().zip(&entries) {
                    let Some(tc) = entry else {
                        continue;
                    };
                    if !heap.push(tc as f64, c) {
                        // Queue full: search this subtree depth-first now.
                        best = subtree_ray(h, hit, probe, c, best, tally)?;
                    }
                }
            }
        }
    }
    Ok(best)
}

/// Depth-first closest hit below `root`, starting from `best`.
fn subtree_ray<H: Hierarchy + ?Sized, G: Growth>(
    h: &H,
    hit: &impl Fn(u32) -> Option<f32>,
    probe: &Probe<G>,
    root: u32,
    mut best: Option<Hit>,
    tally: &mut impl Tally,
) -> Result<Option<Hit>, Error> {
    let mut stack = Stack::<u32, DFS_STACK>::with(root, h.depth());
    while let Some(n) = stack.pop() {
        tally.bv_tests(1);
        match enter(h, n, probe) {
            Some(t) if !best.is_some_and(|b| t > b.t) => {}
            _ => continue,
        }
        match h.content(n) {
            Content::Leaf(here) => closest_in_leaf(here, hit, &mut best, tally),
            Content::Inner(kids) => {
                for &c in kids.as_slice().iter().rev() {
                    stack.push(c)?;
                }
            }
        }
    }
    Ok(best)
}

/// Any hit on any [`Hierarchy`] (see [`Bvh::ray_hits_any`]).
pub(crate) fn ray_hits_any<H: Hierarchy + ?Sized, P: RayTarget>(
    h: &H,
    prims: &[P],
    ray: &Ray,
    tally: impl Tally,
) -> Result<Option<Hit>, Error> {
    check_query(h, prims.len())?;
    if h.is_empty() {
        return Ok(None);
    }
    let probe = Probe::new(ray, &h.bv(h.root()).aabb());
    any_hit(h, &probe, |p| prims[p as usize].ray_hit(ray), tally)
}

/// Some hit of a probe whose primitive test is `hit`, stopping at the first.
#[inline(always)]
pub(crate) fn any_hit<H: Hierarchy + ?Sized, G: Growth>(
    h: &H,
    probe: &Probe<G>,
    hit: impl Fn(u32) -> Option<f32>,
    mut tally: impl Tally,
) -> Result<Option<Hit>, Error> {
    let mut stack = Stack::<u32, DFS_STACK>::with(h.root(), h.depth());
    while let Some(n) = stack.pop() {
        tally.bv_tests(1);
        if enter(h, n, probe).is_none() {
            continue;
        }
        match h.content(n) {
            Content::Leaf(here) => {
                for &p in here {
                    tally.prim_tests(1);
                    if let Some(t) = hit(p) {
                        return Ok(Some(Hit { prim: p, t }));
                    }
                }
            }
            Content::Inner(kids) => {
                for &c in kids.as_slice().iter().rev() {
                    stack.push(c)?;
                }
            }
        }
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The `f32` filter only rejects what the `f64` test rejects: rays aimed
    /// at edges and corners (the cases its rounding bound is for), at points
    /// just inside and just outside, on triangles from 1e-30 to 1e30 in
    /// size, near the origin and far from it, some nearly edge-on; and it
    /// settles nearly all the rays that pass well beside the triangle.
    #[test]
    fn the_f32_filter_rejects_only_what_the_f64_test_rejects() {
        let mut next = crate::test_floats(0x2545_f491_4f6c_dd1d);
        let (mut near, mut hits_near) = (0, 0);
        let (mut beside, mut settled) = ([0; 3], [0; 3]);
        for round in 0..300_000 {
            let scale = [1.0f32, 1e-30, 1e-3, 1e4, 1e30, 1e-13, 1e-15][round % 7];
            let centre = [Vec3::ZERO, Vec3::splat(1e4 * scale)][round % 2];
            let mut corner = || centre + Vec3::new(next(), next(), next()) * scale;
            let tri = Triangle::new(corner(), corner(), corner());
            let origin = centre + (corner() - centre) * [1.0, 3.0, 100.0][round % 3];
            // Barycentric aim: on an edge, on a corner, a hair either side of
            // an edge, or well beside the triangle past one of its three
            // sides (`u < 0`, `v < 0`, `u + v > 1`).
            let (w1, w2) = (next().abs(), next().abs());
            let (u, v) = match round % 8 {
                0 => (0.0, w2),
                1 => (w1, 1.0 - w1),
                2 => (0.0, 0.0),
                3 => (-1e-6 * w1, w2 * 0.5),
                4 => (w1 * 0.5, 1e-6 * w2),
                5 => (-0.5 - w1, w2 * 0.5),
                6 => (w1 * 0.5, -0.5 - w2),
                _ => (0.6 + 0.4 * w1, 0.6 + 0.4 * w2),
            };
            let [a, b, c] = tri.v;
            let target = a + (b - a) * u + (c - a) * v;
            let Ok(ray) = Ray::new(origin, target - origin, f32::INFINITY) else {
                continue;
            };
            let rejected = surely_outside(&tri, &ray);
            let hit = moller_trumbore_f64(&tri, &ray).is_some();
            assert!(
                !(rejected && hit),
                "the filter rejected a hit: {tri:?} {ray:?} (round {round})"
            );
            // Sizes whose products `f32` holds without underflow or overflow.
            let moderate = (1e-3..=1e4).contains(&scale);
            let side = (round % 8).checked_sub(5);
            if let (Some(k), true) = (side, moderate) {
                beside[k] += 1;
                settled[k] += usize::from(rejected);
            } else if moderate {
                near += 1;
                hits_near += usize::from(hit);
            }
        }
        // Rays well beside, past each side: settled in f32 but for nearly
        // edge-on ones (at 1e-30 the products underflow, at 1e30 they
        // overflow: left to f64).
        for k in 0..3 {
            assert!(
                settled[k] * 100 > beside[k] * 95,
                "side {k}: {} of {}",
                settled[k],
                beside[k]
            );
        }
        // The rays at the edges hit often enough for the first check to bite.
        assert!(hits_near * 3 > near, "{hits_near} of {near}");
    }

    /// The triangle test itself: a ray through the inside hits at the right
    /// distance with the barycentric coordinates of its aim; one past each
    /// side, one pointing away and one in the triangle's plane miss.
    #[test]
    fn moller_trumbore_hits_inside_and_misses_beside() {
        let tri = Triangle::new(
            Vec3::ZERO,
            Vec3::new(4.0, 0.0, 0.0),
            Vec3::new(0.0, 4.0, 0.0),
        );
        let down =
            |x: f32, y: f32| Ray::new(Vec3::new(x, y, 2.0), -Vec3::Z, f32::INFINITY).unwrap();
        let m = moller_trumbore(&tri, &down(1.0, 2.0)).unwrap();
        assert_eq!((m.t, m.u, m.v), (2.0, 0.25, 0.5));
        assert!(m.det > 0.0, "from above: the front, the normal (+z) side");
        for (x, y) in [(-0.5, 1.0), (1.0, -0.5), (3.0, 3.0)] {
            assert!(moller_trumbore(&tri, &down(x, y)).is_none(), "({x}, {y})");
        }
        let away = Ray::new(Vec3::new(1.0, 1.0, 2.0), Vec3::Z, f32::INFINITY).unwrap();
        let flat = Ray::new(Vec3::new(-1.0, 1.0, 0.0), Vec3::X, f32::INFINITY).unwrap();
        assert!(moller_trumbore(&tri, &away).is_none());
        assert!(moller_trumbore(&tri, &flat).is_none());
        let short = Ray::new(Vec3::new(1.0, 2.0, 2.0), -Vec3::Z, 1.5).unwrap();
        assert!(moller_trumbore(&tri, &short).is_none(), "past t_max");
    }

    /// The 4-lane slab test answers exactly like the scalar one, including
    /// rays parallel to a slab, rays starting on a face (0 * inf = NaN),
    /// flat boxes and huge coordinates.
    #[test]
    fn four_lane_slab_equals_the_scalar_slab() {
        let mut next = crate::test_floats(0x9e37_79b9_7f4a_7c15);
        let mut checked = 0;
        for round in 0..20_000 {
            let scale = [1.0f32, 1e-3, 1e5, 1e30][round % 4];
            let mut b = Boxes4 {
                min: [[0.0; 4]; 3],
                max: [[0.0; 4]; 3],
            };
            for k in 0..4 {
                for axis in 0..3 {
                    let (x, y) = (next() * scale, next() * scale);
                    let flat = round % 7 == 0 && axis == k % 3;
                    b.min[axis][k] = x.min(y);
                    b.max[axis][k] = if flat { x.min(y) } else { x.max(y) };
                }
            }
            let mut origin = Vec3::new(next(), next(), next()) * scale;
            let mut dir = Vec3::new(next(), next(), next());
            match round % 5 {
                0 => dir[round % 3] = 0.0,
                1 => origin[round % 3] = b.min[round % 3][round % 4],
                2 => {
                    dir = Vec3::ZERO;
                    dir[round % 3] = 1.0;
                    origin[(round + 1) % 3] = b.max[(round + 1) % 3][0];
                }
                _ => {}
            }
            let Ok(ray) = Ray::new(origin, dir, [f32::INFINITY, scale][round % 2]) else {
                continue;
            };
            let inv = ray.dir.recip();
            let four = slab4(&b, &ray, inv);
            for (k, got) in four.iter().enumerate() {
                let one = Aabb::new(
                    Vec3::new(b.min[0][k], b.min[1][k], b.min[2][k]),
                    Vec3::new(b.max[0][k], b.max[1][k], b.max[2][k]),
                );
                let want = slab(&one, &ray, inv);
                assert_eq!(
                    got.map(f32::to_bits),
                    want.map(f32::to_bits),
                    "round {round} lane {k}"
                );
                checked += want.is_some() as usize;
            }
        }
        assert!(checked > 1000, "too few hits to mean anything: {checked}");
    }

    /// The shared per-ray test answers like the general one's four-lane
    /// form, lane by lane, and its four-lane form like its one-box form.
    #[test]
    fn probe_four_lanes_equal_one_box() {
        let mut next = crate::test_floats(0x1234_5678_9abc_def1);
        let (mut fast, mut hits) = (0, 0);
        for round in 0..20_000 {
            let scale = [1.0f32, 1e-3, 1e5, 1e30][round % 4];
            let mut b = Boxes4::EMPTY;
            for k in 0..4 {
                for axis in 0..3 {
                    let (x, y) = (next() * scale, next() * scale);
                    b.min[axis][k] = x.min(y);
                    b.max[axis][k] = if round % 7 == 0 { x.min(y) } else { x.max(y) };
                }
            }
            let mut dir = Vec3::new(next(), next(), next());
            if round % 5 == 0 {
                dir[round % 3] = 0.0;
            }
            let origin = Vec3::new(next(), next(), next()) * scale;
            let Ok(ray) = Ray::new(origin, dir, [f32::INFINITY, scale][round % 2]) else {
                continue;
            };
            let root = Aabb::new(Vec3::splat(-scale), Vec3::splat(scale));
            let probe = Probe::new(&ray, &root);
            fast += probe.fast as usize;
            let four = probe.enter4(&b);
            for (k, got) in four.iter().enumerate() {
                let one = Aabb::new(
                    Vec3::new(b.min[0][k], b.min[1][k], b.min[2][k]),
                    Vec3::new(b.max[0][k], b.max[1][k], b.max[2][k]),
                );
                assert_eq!(
                    got.map(f32::to_bits),
                    probe.enter(&one).map(f32::to_bits),
                    "round {round} lane {k}"
                );
                hits += got.is_some() as usize;
            }
        }
        assert!(fast > 10_000 && hits > 1000, "fast {fast}, hits {hits}");
    }

    /// No box the ray truly enters is rejected, and the entry reported is
    /// never later than a point of the ray inside the box: boxes are built
    /// around a point of the ray (in f64, rounded outward to f32), as thin
    /// as f32 allows, at scales from 1e-4 to 1e6 and with the origin near
    /// or far.
    #[test]
    fn probe_never_rejects_a_box_the_ray_enters() {
        let mut next = crate::test_floats(0x0dd_ba11_cafe_f00d);
        let mut fast = 0;
        for round in 0..50_000 {
            let scale = [1.0f32, 1e-4, 1e3, 1e6][round % 4];
            let centre = Vec3::new(next(), next(), next()) * scale * [0.0, 1.0, 100.0][round % 3];
            let origin = centre + Vec3::new(next(), next(), next()) * scale;
            let dir = Vec3::new(next(), next(), next());
            let Ok(ray) = Ray::new(origin, dir, f32::INFINITY) else {
                continue;
            };
            let t = (next().abs() * 4.0) as f64;
            let q = ray.origin.as_dvec3() + ray.dir.as_dvec3() * t;
            // The box: q rounded down and up per axis, grown by a random
            // thickness on some axes (zero on others: flat boxes).
            let (mut lo, mut hi) = (Vec3::ZERO, Vec3::ZERO);
            for k in 0..3 {
                let x = q[k] as f32;
                let (down, up) = if (x as f64) > q[k] {
                    (x.next_down(), x)
                } else if (x as f64) < q[k] {
                    (x, x.next_up())
                } else {
                    (x, x)
                };
                let grow = if (round + k) % 3 == 0 {
                    0.0
                } else {
                    next().abs() * scale
                };
                lo[k] = down - grow;
                hi[k] = up + grow * (round % 2) as f32;
            }
            let b = Aabb::new(lo, hi);
            let root = Aabb::new(lo.min(origin) - scale, hi.max(origin) + scale);
            let probe = Probe::new(&ray, &root);
            fast += probe.fast as usize;
            let entry = probe.enter(&b);
            assert!(
                entry.is_some_and(|e| e as f64 <= t * (1.0 + 1e-6) + 1e-30),
                "round {round}: {ray:?} enters {b:?} by t = {t}, got {entry:?}"
            );
            assert_eq!(entry.is_some(), slab(&b, &ray, ray.dir.recip()).is_some());
        }
        assert!(fast > 40_000, "fast path taken {fast} times");
    }

    /// Rays through a corner, an edge or a face of a box, exactly: on a
    /// coarse grid `origin = q - t * dir` is exact in f32, so the ray meets
    /// the point `q` at `t` with no rounding, and only the slab test's own
    /// rounding (of `1 / dir` and of each product) can separate its entry
    /// from its exit. Such a box must still be entered, by `t` at the latest.
    #[test]
    fn probe_keeps_boxes_the_ray_only_touches() {
        let mut next = crate::test_floats(0xfeed_beef_1357_9bdf);
        let grid = |x: f32, step: f32| (x / step).round() * step;
        let (mut point_boxes, mut checked) = (0, 0);
        for round in 0..50_000 {
            let scale = [1.0f32, 1.0 / 1024.0, 1024.0][round % 3];
            let q = Vec3::new(next(), next(), next()).map(|x| grid(x * scale, scale / 64.0));
            let dir = Vec3::new(next(), next(), next()).map(|x| grid(x * 3.0, 1.0 / 16.0));
            let t = [1.0f32, 4.0, 0.5, 32.0][round % 4];
            let origin = q - dir * t;
            // Some rays end exactly at the point they touch the box.
            let t_max = [f32::INFINITY, t][round % 2];
            let Ok(ray) = Ray::new(origin, dir, t_max) else {
                continue;
            };
            assert_eq!(origin + dir * t, q, "not exact: {origin} {dir} {t}");
            // A point box, or a box with q on a face, an edge or a corner.
            let mut lo = q;
            let mut hi = q;
            let mode = (round / 3) % 5;
            for k in 0..3 {
                match if mode == 4 { 0 } else { (mode + k) % 4 } {
                    0 => {}
                    1 => hi[k] += scale * next().abs(),
                    2 => lo[k] -= scale * next().abs(),
                    _ => {
                        lo[k] -= scale * next().abs();
                        hi[k] += scale * next().abs();
                    }
                }
            }
            point_boxes += (lo == hi) as usize;
            let b = Aabb::new(lo, hi);
            let root = Aabb::new(Vec3::splat(-4.0 * scale), Vec3::splat(4.0 * scale))
                .union(&Aabb::new(origin, origin));
            let probe = Probe::new(&ray, &root);
            let entry = probe.enter(&b);
            assert!(
                entry.is_some_and(|e| e <= t * (1.0 + 1e-6)),
                "round {round}: {ray:?} touches {b:?} at t = {t}, got {entry:?}"
            );
            assert!(
                slab(&b, &ray, ray.dir.recip()).is_some(),
                "round {round}: general test"
            );
            checked += 1;
        }
        assert!(
            checked > 45_000 && point_boxes > 1000,
            "{checked} rays, {point_boxes} point boxes"
        );
    }
}
