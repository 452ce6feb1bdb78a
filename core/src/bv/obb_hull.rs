//! Two OBB fits that start from a convex hull the caller already has:
//! PCA of the hull's *surface* ([`Obb::pca_hull`]) and the face-flush fit
//! ([`Obb::face_flush`]).
//!
//! Lecture: *OBBs*, Ericson 4.4. PCA over the vertices ([`Obb::pca`]) lets
//! the vertex density steer the axes: a dense patch of a scan drags them.
//! Covariance over the hull's surface, each triangle weighted by its area
//! (Gottschalk's "continuous" formula), depends only on the shape. The
//! face-flush fit goes further: the minimum-volume box of a point set
//! has a face flush with a hull face in the common case (O'Rourke 1985
//! proves two flush faces, or one face and edges, in general), so trying
//! every hull face as the box's base, with the smallest rectangle of the
//! projected hull on it (rotating calipers), gets close to the optimum.
//! It costs O(F · V log V) for F faces and V vertices: fine for a report
//! or an offline fit of a rigid body's root, far too slow for every node
//! of a tree build (where the hull alone would cost more than the build).
//!
//! No allocation: the hull's vertices and triangles come from the caller
//! (`bvhkit_std::hull::mesh` builds them with quickhull), and the 2-D
//! hull of the face-flush fit is built in a caller's scratch slice.

use super::obb::orthonormal;
use super::Obb;
use crate::Error;
use glam::{DMat3, DVec2, DVec3, Vec2, Vec3};
use robust::{orient2d, Coord};

impl Obb {
    /// PCA of a convex hull's surface: the covariance of a uniform
    /// distribution over the triangles (each weighted by its area, with
    /// the exact second moment of the triangle, Ericson 4.4.3 / Gottschalk
    /// 2000), then the conservative box over every vertex with those axes
    /// ([`fit_with_axes`](Self::fit_with_axes)). Unlike [`Obb::pca`], many
    /// vertices crowded in one place do not drag the axes.
    ///
    /// `triangles` index `vertices`; they are meant to be the hull's faces
    /// (any triangles work, the axes are then those of that surface). The
    /// box contains every vertex given. Like `pca`, it keeps the
    /// axis-aligned box when that is smaller. With no triangle of positive
    /// area (no triangles, a flat or collinear "hull") it is
    /// [`Obb::pca`] of the vertices; no vertices give [`Obb::EMPTY`].
    ///
    /// # Errors
    ///
    /// [`Error::VertexIndexOutOfRange`] when a triangle names a vertex
    /// past the end of `vertices`; [`Error::NonFiniteCoordinate`] (with the
    /// vertex's index as `primitive`) for a NaN or infinite vertex.
    ///
    /// ```
    /// use bvhkit::{BoundingVolume, Obb};
    /// use glam::{Quat, Vec3};
    /// // A rotated 4 x 2 x 1 brick, its 12 triangles, and 200 extra vertices
    /// // crowded near one corner (inside the brick): vertex PCA is dragged
    /// // by them, surface PCA is not.
    /// let q = Quat::from_euler(glam::EulerRot::XYZ, 0.3, 0.5, 0.7);
    /// let corner = |i: usize| Vec3::new([-2.0, 2.0][i & 1], [-1.0, 1.0][i >> 1 & 1], [-0.5, 0.5][i >> 2]);
    /// let mut pts: Vec<Vec3> = (0..8).map(|i| q * corner(i)).collect();
    /// pts.extend((0..200).map(|i| q * (corner(0) * 0.9 + Vec3::splat(0.001 * i as f32))));
    /// let tris = [[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
    ///             [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]];
    /// let obb = Obb::pca_hull(&pts, &tris).unwrap();
    /// assert!(pts.iter().all(|&p| obb.contains_point(p)));
    /// assert!(obb.volume() < 8.0 * 1.01, "{}", obb.volume());
    /// assert!(Obb::pca(pts.as_slice()).volume() > 8.0 * 1.2);
    /// ```
    pub fn pca_hull(vertices: &[Vec3], triangles: &[[u32; 3]]) -> Result<Obb, Error> {
        check_mesh(vertices, triangles)?;
        if vertices.is_empty() {
            return Ok(Obb::EMPTY);
        }
        let Some(axes) = surface_axes(vertices, triangles) else {
            return Ok(Obb::pca(vertices));
        };
        Ok(keep_smaller(vertices, Obb::fit_with_axes(vertices, axes)))
    }

    /// The scratch length [`Obb::face_flush`] needs for `vertices` vertices:
    /// `2 * vertices` (the projected points, and the 2-D hull beside them).
    ///
    /// ```
    /// assert_eq!(bvhkit::Obb::face_flush_scratch_len(8), 16);
    /// ```
    pub const fn face_flush_scratch_len(vertices: usize) -> usize {
        vertices.saturating_mul(2)
    }

    /// The face-flush fit, near the minimum-volume box: for every hull
    /// face, project the vertices onto its plane, take their 2-D convex
    /// hull (monotone chain, exact orientation signs) and its
    /// minimum-area rectangle (rotating calipers), and extend it along
    /// the face's normal over the vertices; the smallest such box wins.
    /// The search runs in `f64` on coordinates centred and scaled to the
    /// set's box (2-D points are stored in `f32` in the scratch); the
    /// winner is made conservative in `f32` by
    /// [`fit_with_axes`](Self::fit_with_axes) over every vertex. Like the
    /// other fits, it keeps the axis-aligned box if that is smaller.
    ///
    /// `vertices` should be the hull's vertices (every one is projected for
    /// every face) and `triangles` its faces; the box contains every
    /// vertex given. To bound the mesh the hull came from, refit it with
    /// `Obb::fit_with_axes(mesh_points, obb.axes)`: one pass, the same
    /// volume up to rounding. Triangles of zero area are skipped; with
    /// none left (no triangles, a flat or collinear "hull") the fit is
    /// [`Obb::pca`] of the vertices. No vertices give [`Obb::EMPTY`].
    ///
    /// Cost: O(F · V log V) time for F triangles and V vertices (a sort
    /// of the projected vertices per face), O(V) scratch. That is a fit
    /// for a report or for an offline root volume, not for every node of
    /// a tree build: on a hull of 2 000 vertices it is thousands of times
    /// slower than `Obb::pca`.
    ///
    /// # Errors
    ///
    /// [`Error::ScratchCapacity`] when `scratch` is shorter than
    /// [`face_flush_scratch_len(vertices.len())`](Self::face_flush_scratch_len);
    /// [`Error::VertexIndexOutOfRange`] and
    /// [`Error::NonFiniteCoordinate`] as for [`Obb::pca_hull`].
    ///
    /// ```
    /// use bvhkit::{BoundingVolume, Obb};
    /// use glam::{Quat, Vec2, Vec3};
    /// // A rotated 4 x 2 x 1 brick and its 12 triangles: face-flush finds it.
    /// let q = Quat::from_euler(glam::EulerRot::XYZ, 0.3, 0.5, 0.7);
    /// let pts: Vec<Vec3> = (0..8)
    ///     .map(|i| q * Vec3::new([-2.0, 2.0][i & 1], [-1.0, 1.0][i >> 1 & 1], [-0.5, 0.5][i >> 2]))
    ///     .collect();
    /// let tris = [[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
    ///             [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]];
    /// let mut scratch = vec![Vec2::ZERO; Obb::face_flush_scratch_len(pts.len())];
    /// let obb = Obb::face_flush(&pts, &tris, &mut scratch).unwrap();
    /// assert!(pts.iter().all(|&p| obb.contains_point(p)));
    /// assert!((obb.volume() - 8.0).abs() < 8.0 * 1e-5, "{}", obb.volume());
    /// // Too little scratch is an error, not a panic.
    /// assert!(Obb::face_flush(&pts, &tris, &mut scratch[..15]).is_err());
    /// ```
    pub fn face_flush(
        vertices: &[Vec3],
        triangles: &[[u32; 3]],
        scratch: &mut [Vec2],
    ) -> Result<Obb, Error> {
        check_mesh(vertices, triangles)?;
        let needed = Obb::face_flush_scratch_len(vertices.len());
        if scratch.len() < needed {
            return Err(Error::ScratchCapacity {
                needed,
                available: scratch.len(),
            });
        }
        if vertices.is_empty() {
            return Ok(Obb::EMPTY);
        }
        let frame = Frame::of(vertices);
        let n = vertices.len();
        let scratch = &mut scratch[..needed];
        let mut best: Option<(Measure, [DVec3; 3])> = None;
        for tri in triangles {
            let [a, b, c] = tri.map(|k| frame.local(vertices[k as usize]));
            let normal = (b - a).cross(c - a).normalize_or_zero();
            let u0 = (b - a).normalize_or_zero();
            if normal == DVec3::ZERO || u0 == DVec3::ZERO {
                continue; // zero area: no plane
            }
            let v0 = normal.cross(u0);
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for (slot, &p) in scratch[..n].iter_mut().zip(vertices) {
                let q = frame.local(p);
                *slot = Vec2::new(u0.dot(q) as f32, v0.dot(q) as f32);
                let h = normal.dot(q);
                lo = lo.min(h);
                hi = hi.max(h);
            }
            let m = convex_hull_2d(scratch, n);
            let rect = min_area_rectangle(&scratch[n..n + m]);
            let depth = hi - lo;
            let measure = Measure {
                volume: rect.width * rect.length * depth,
                half_area: rect.width * rect.length + (rect.width + rect.length) * depth,
            };
            if best.is_none_or(|(b, _)| measure.smaller_than(&b)) {
                let u = u0 * rect.direction.x + v0 * rect.direction.y;
                best = Some((measure, [u, normal.cross(u), normal]));
            }
        }
        let Some((_, [u, v, w])) = best else {
            return Ok(Obb::pca(vertices));
        };
        let axes = orthonormal(DMat3::from_cols(u, v, w));
        Ok(keep_smaller(vertices, Obb::fit_with_axes(vertices, axes)))
    }
}

/// Rejects a non-finite vertex and a triangle index past the end.
fn check_mesh(vertices: &[Vec3], triangles: &[[u32; 3]]) -> Result<(), Error> {
    if let Some(i) = vertices.iter().position(|p| !p.is_finite()) {
        return Err(Error::NonFiniteCoordinate { primitive: i });
    }
    if let Some(t) = triangles
        .iter()
        .position(|tri| tri.iter().any(|&k| k as usize >= vertices.len()))
    {
        return Err(Error::VertexIndexOutOfRange {
            triangle: t,
            vertices: vertices.len(),
        });
    }
    Ok(())
}

/// Coordinates centred on the set's box and scaled to its largest extent,
/// in `f64`: a set at 1e5 keeps its precision, one at 1e30 never overflows.
struct Frame {
    origin: DVec3,
    scale: f64,
}

impl Frame {
    fn of(vertices: &[Vec3]) -> Frame {
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for p in vertices {
            lo = lo.min(p.as_dvec3());
            hi = hi.max(p.as_dvec3());
        }
        let extent = (hi - lo).max_element();
        Frame {
            origin: (lo + hi) * 0.5,
            scale: if extent > 0.0 { 1.0 / extent } else { 1.0 },
        }
    }

    fn local(&self, p: Vec3) -> DVec3 {
        (p.as_dvec3() - self.origin) * self.scale
    }
}

/// The axes of the area-weighted covariance of the triangles' surface, or
/// `None` when the total area is zero.
fn surface_axes(vertices: &[Vec3], triangles: &[[u32; 3]]) -> Option<[Vec3; 3]> {
    let frame = Frame::of(vertices);
    let mut area = 0.0;
    let mut first = DVec3::ZERO; // sum of area * centroid
    let mut second = DMat3::ZERO; // sum of the second moments
    let outer = |v: DVec3| DMat3::from_cols(v * v.x, v * v.y, v * v.z);
    for tri in triangles {
        let [a, b, c] = tri.map(|k| frame.local(vertices[k as usize]));
        let ai = 0.5 * (b - a).cross(c - a).length();
        if ai <= 0.0 {
            continue;
        }
        let m = (a + b + c) / 3.0;
        area += ai;
        first += m * ai;
        // The second moment of a uniform triangle about the origin:
        // A/12 (9 m m^T + a a^T + b b^T + c c^T).
        second += (outer(m) * 9.0 + outer(a) + outer(b) + outer(c)) * (ai / 12.0);
    }
    if area <= 0.0 {
        return None;
    }
    let mean = first / area;
    let cov = second * (1.0 / area) - outer(mean);
    let (_, vecs) = crate::bv::symmetric_eigen(cov);
    Some(orthonormal(vecs))
}

/// A candidate box's size in the set's scaled unit. Flat candidates
/// (volume within rounding of zero) are told apart by area.
#[derive(Clone, Copy)]
struct Measure {
    volume: f64,
    half_area: f64,
}

impl Measure {
    const FLAT: f64 = 1e-12;

    fn smaller_than(&self, other: &Measure) -> bool {
        if self.volume <= Measure::FLAT && other.volume <= Measure::FLAT {
            self.half_area < other.half_area
        } else {
            self.volume < other.volume
        }
    }

    fn of(obb: &Obb, unit: f32) -> Measure {
        let e = (obb.half_extents.max(Vec3::ZERO) * 2.0).as_dvec3() * unit as f64;
        Measure {
            volume: e.x * e.y * e.z,
            half_area: e.x * e.y + e.y * e.z + e.z * e.x,
        }
    }
}

/// `rotated`, or the axis-aligned box over `points` when that is smaller
/// (compared in the set's unit, so a 1e30 set's volume does not overflow).
fn keep_smaller(points: &[Vec3], rotated: Obb) -> Obb {
    let aligned = Obb::fit_with_axes(points, [Vec3::X, Vec3::Y, Vec3::Z]);
    let size = aligned.half_extents.max_element() * 2.0;
    let unit = if size > 0.0 { 1.0 / size } else { 1.0 };
    if Measure::of(&aligned, unit).smaller_than(&Measure::of(&rotated, unit)) {
        aligned
    } else {
        rotated
    }
}

/// Andrew's monotone chain over the `n` points in `scratch[..n]`, with
/// exact orientation signs (`robust::orient2d`), so the hull of the `f32`
/// points is exactly convex. Leaves the hull counter-clockwise, without
/// repeated or collinear points, in `scratch[n..n + m]` and returns `m`
/// (1 for a single point, 2 for a segment). `scratch` holds `2 * n`.
fn convex_hull_2d(scratch: &mut [Vec2], n: usize) -> usize {
    let (pts, out) = scratch.split_at_mut(n);
    // Finite points (checked by the caller), so `partial_cmp` is total and,
    // unlike `total_cmp`, puts -0.0 and 0.0 together as the chain needs.
    let order = |a: f32, b: f32| a.partial_cmp(&b).unwrap_or(core::cmp::Ordering::Equal);
    pts.sort_unstable_by(|p, q| order(p.x, q.x).then(order(p.y, q.y)));
    let turn = |a: Vec2, b: Vec2, c: Vec2| {
        let c2 = |p: Vec2| Coord { x: p.x, y: p.y };
        orient2d(c2(a), c2(b), c2(c))
    };
    // Lower chain, left to right, into `out`.
    let mut k = 0;
    for &p in pts.iter() {
        while k >= 2 && turn(out[k - 2], out[k - 1], p) <= 0.0 {
            k -= 1;
        }
        if k > 0 && out[k - 1] == p {
            continue;
        }
        out[k] = p;
        k += 1;
    }
    // Upper chain, left to right, in place over the sorted points (its
    // length never passes the index being read).
    let mut u = 0;
    for i in 0..n {
        let p = pts[i];
        while u >= 2 && turn(pts[u - 2], pts[u - 1], p) >= 0.0 {
            u -= 1;
        }
        if u > 0 && pts[u - 1] == p {
            continue;
        }
        pts[u] = p;
        u += 1;
    }
    // Counter-clockwise: the lower chain, then the upper one right to left
    // without its two ends (shared with the lower chain). Exact signs make
    // the two chains' inner points distinct, so `k + u - 2 <= n`; the bound
    // is checked anyway rather than trusted.
    let inner = u.saturating_sub(2).min(out.len() - k);
    for j in 0..inner {
        out[k + j] = pts[u - 2 - j];
    }
    k + inner
}

/// The smallest rectangle around a convex polygon.
struct Rectangle {
    /// Unit direction of its first side (along a hull edge).
    direction: DVec2,
    width: f64,
    length: f64,
}

/// Rotating calipers (Toussaint 1983): the minimum-area enclosing
/// rectangle has a side on a hull edge; for each edge in turn, three
/// pointers (farthest along the edge, farthest behind it, farthest off
/// it) only move forward, so all edges cost O(m).
fn min_area_rectangle(hull: &[Vec2]) -> Rectangle {
    let m = hull.len();
    let at = |i: usize| hull[i % m].as_dvec2();
    if m < 3 {
        let d = if m == 2 { at(1) - at(0) } else { DVec2::ZERO };
        return Rectangle {
            direction: d.normalize_or(DVec2::X),
            width: d.length(),
            length: 0.0,
        };
    }
    let mut best = Rectangle {
        direction: DVec2::X,
        width: f64::INFINITY,
        length: f64::INFINITY,
    };
    let (mut right, mut top, mut left) = (0, 0, 0);
    let mut started = false;
    for i in 0..m {
        let u = (at(i + 1) - at(i)).normalize_or_zero();
        if u == DVec2::ZERO {
            continue;
        }
        let v = u.perp(); // inward for a counter-clockwise polygon
        if !started {
            started = true;
            // Start each pointer at its extreme by a full scan.
            let arg =
                |f: &dyn Fn(usize) -> f64| (0..m).fold(0, |b, j| if f(j) > f(b) { j } else { b });
            right = arg(&|j| u.dot(at(j)));
            top = arg(&|j| v.dot(at(j)));
            left = arg(&|j| -u.dot(at(j)));
        } else {
            // Advance while the next vertex is farther; at most m steps each.
            let advance = |p: &mut usize, f: &dyn Fn(usize) -> f64| {
                for _ in 0..m {
                    if f(*p + 1) > f(*p) {
                        *p = (*p + 1) % m;
                    } else {
                        break;
                    }
                }
            };
            advance(&mut right, &|j| u.dot(at(j)));
            advance(&mut top, &|j| v.dot(at(j)));
            advance(&mut left, &|j| -u.dot(at(j)));
        }
        let width = u.dot(at(right) - at(left));
        let length = v.dot(at(top) - at(i));
        if width * length < best.width * best.length {
            best = Rectangle {
                direction: u,
                width,
                length,
            };
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::BoundingVolume;
    use glam::Quat;

    /// The 12 triangles of a box over corners numbered `x + 2y + 4z`.
    const BOX: [[u32; 3]; 12] = [
        [0, 1, 3],
        [0, 3, 2],
        [4, 6, 7],
        [4, 7, 5],
        [0, 4, 5],
        [0, 5, 1],
        [2, 3, 7],
        [2, 7, 6],
        [0, 2, 6],
        [0, 6, 4],
        [1, 5, 7],
        [1, 7, 3],
    ];

    fn corners(half: Vec3, q: Quat, at: Vec3) -> [Vec3; 8] {
        core::array::from_fn(|i| {
            let s = Vec3::new(
                [-1.0, 1.0][i & 1],
                [-1.0, 1.0][i >> 1 & 1],
                [-1.0, 1.0][i >> 2],
            );
            at + q * (half * s)
        })
    }

    fn inside(obb: &Obb, pts: &[Vec3]) -> bool {
        pts.iter().all(|&p| obb.contains_point(p))
    }

    #[test]
    fn a_unit_cube_gives_volume_one() {
        let pts = corners(Vec3::splat(0.5), Quat::IDENTITY, Vec3::splat(0.5));
        let mut scratch = [Vec2::ZERO; 16];
        for obb in [
            Obb::pca_hull(&pts, &BOX).unwrap(),
            Obb::face_flush(&pts, &BOX, &mut scratch).unwrap(),
        ] {
            assert!(inside(&obb, &pts), "{obb:?}");
            assert!((obb.volume() - 1.0).abs() < 1e-5, "{obb:?}");
        }
    }

    /// A rotated brick, moved far away: face-flush recovers it to within
    /// rounding, axes and all; surface PCA too (its three variances differ).
    #[test]
    fn a_rotated_box_is_recovered() {
        for at in [Vec3::ZERO, Vec3::new(1e5, -3e4, 7e4)] {
            let q = Quat::from_euler(glam::EulerRot::ZXY, 0.4, -1.1, 0.25);
            let half = Vec3::new(3.0, 1.5, 0.25);
            let pts = corners(half, q, at);
            let mut scratch = [Vec2::ZERO; 16];
            let exact = 8.0 * half.x * half.y * half.z;
            let f = Obb::face_flush(&pts, &BOX, &mut scratch).unwrap();
            let p = Obb::pca_hull(&pts, &BOX).unwrap();
            // At 1e5 an f32 corner is off by up to 2^-7 = 0.008.
            let tol = if at == Vec3::ZERO { 1e-5 } else { 0.05 };
            for obb in [f, p] {
                assert!(inside(&obb, &pts), "{obb:?}");
                assert!(
                    (obb.volume() - exact).abs() < exact * tol,
                    "{} vs {exact}",
                    obb.volume()
                );
            }
            // The box's own axes, up to sign and order.
            for a in f.axes {
                let along = [q * Vec3::X, q * Vec3::Y, q * Vec3::Z];
                assert!(along.iter().any(|b| a.dot(*b).abs() > 1.0 - 1e-4), "{a:?}");
            }
        }
    }

    /// No input panics: empty, one point, collinear, coplanar, zero-area
    /// triangles, bad indices, short scratch, NaN.
    #[test]
    fn degenerate_inputs_fall_back_or_are_errors() {
        let mut scratch = [Vec2::ZERO; 32];
        // Empty: the empty box (and no triangle may name a vertex).
        assert_eq!(Obb::pca_hull(&[], &[]), Ok(Obb::EMPTY));
        assert_eq!(Obb::face_flush(&[], &[], &mut []), Ok(Obb::EMPTY));
        assert_eq!(
            Obb::face_flush(&[], &[[0, 0, 0]], &mut scratch),
            Err(Error::VertexIndexOutOfRange {
                triangle: 0,
                vertices: 0
            })
        );
        let one = [Vec3::new(2.0, -1.0, 3.0)];
        let line: [Vec3; 5] = core::array::from_fn(|i| Vec3::new(1.0, 2.0, 3.0) * i as f32);
        let plane: [Vec3; 6] = core::array::from_fn(|i| {
            let (x, y) = ((i % 3) as f32, (i / 3) as f32 * 2.0);
            Vec3::new(x, y, x) // the plane z = x
        });
        // Quickhull's answers on such sets: degenerate triangles ([0, 1, 0]
        // for a segment) or a flat two-sided hull. Also no triangles at all.
        let sets: [(&[Vec3], &[[u32; 3]]); 6] = [
            (&one, &[[0, 0, 0]]),
            (&one, &[]),
            (&line, &[[0, 4, 0], [4, 0, 0]]),
            (&line, &[]),
            (&plane, &[[0, 2, 5], [0, 5, 3], [5, 2, 0], [3, 5, 0]]),
            (&plane, &[]),
        ];
        for (pts, tris) in sets {
            let p = Obb::pca_hull(pts, tris).unwrap();
            let f = Obb::face_flush(pts, tris, &mut scratch).unwrap();
            for obb in [p, f] {
                assert!(inside(&obb, pts), "{obb:?} {pts:?}");
                assert!(obb.half_extents.is_finite());
            }
            if tris.is_empty() {
                assert_eq!(p, Obb::pca(pts));
                assert_eq!(f, Obb::pca(pts));
            }
        }
        // The flat set with its two-sided hull: the flat box of the
        // smallest rectangle (2 sqrt 2 along the tilted x, 2 along y).
        let f = Obb::face_flush(&plane, sets[4].1, &mut scratch).unwrap();
        let e = f.half_extents * 2.0;
        let mut e = [e.x, e.y, e.z];
        e.sort_by(f32::total_cmp);
        assert!(e[0] < 1e-5, "{f:?}");
        assert!((e[1] * e[2] - 4.0 * 2f32.sqrt()).abs() < 1e-4, "{f:?}");
        // Bad index, short scratch, NaN: errors.
        assert_eq!(
            Obb::pca_hull(&plane, &[[0, 1, 2], [0, 1, 6]]),
            Err(Error::VertexIndexOutOfRange {
                triangle: 1,
                vertices: 6
            })
        );
        assert_eq!(
            Obb::face_flush(&plane, &[[0, 1, u32::MAX]], &mut scratch),
            Err(Error::VertexIndexOutOfRange {
                triangle: 0,
                vertices: 6
            })
        );
        assert_eq!(
            Obb::face_flush(&plane, &[], &mut scratch[..11]),
            Err(Error::ScratchCapacity {
                needed: 12,
                available: 11
            })
        );
        let nan = [Vec3::ZERO, Vec3::new(0.0, f32::NAN, 0.0)];
        assert_eq!(
            Obb::face_flush(&nan, &[], &mut scratch),
            Err(Error::NonFiniteCoordinate { primitive: 1 })
        );
        assert_eq!(
            Obb::pca_hull(&nan, &[]),
            Err(Error::NonFiniteCoordinate { primitive: 1 })
        );
    }

    /// A tiny generator for the tests (no_std: no rand).
    fn lcg(state: &mut u64) -> f32 {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*state >> 40) as f32 / (1u64 << 24) as f32
    }

    /// The 2-D hull on a coarse grid (duplicates, collinear runs): every
    /// input point is on the left of (or on) every hull edge, the hull is
    /// strictly convex, and its vertices are input points.
    #[test]
    fn the_2d_hull_encloses_every_point_and_turns_left() {
        let mut s = 7;
        for round in 0..200 {
            let n = 1 + round % 24;
            let mut scratch = [Vec2::ZERO; 48];
            let mut pts = [Vec2::ZERO; 24];
            for p in pts[..n].iter_mut() {
                // Coarse grid: many duplicates and collinear triples.
                *p = Vec2::new((lcg(&mut s) * 6.0).floor(), (lcg(&mut s) * 6.0).floor());
            }
            scratch[..n].copy_from_slice(&pts[..n]);
            let m = convex_hull_2d(&mut scratch[..2 * n], n);
            let hull = &scratch[n..n + m];
            assert!(m >= 1 && m <= n);
            let c2 = |p: Vec2| Coord { x: p.x, y: p.y };
            if m >= 3 {
                for i in 0..m {
                    let (a, b) = (hull[i], hull[(i + 1) % m]);
                    for &p in &pts[..n] {
                        assert!(
                            orient2d(c2(a), c2(b), c2(p)) >= 0.0,
                            "{p:?} outside {hull:?}"
                        );
                    }
                    // Strictly convex: no collinear hull vertex.
                    assert!(orient2d(c2(a), c2(b), c2(hull[(i + 2) % m])) > 0.0);
                }
            }
            // Every hull vertex is an input point.
            assert!(hull.iter().all(|h| pts[..n].contains(h)));
        }
    }

    /// Rotating calipers against brute force over every hull edge.
    #[test]
    fn calipers_find_the_smallest_rectangle() {
        let mut s = 11;
        for round in 0..300 {
            let n = 3 + round % 30;
            let mut scratch = [Vec2::ZERO; 64];
            for p in scratch[..n].iter_mut() {
                *p = Vec2::new(lcg(&mut s) * 4.0 - 2.0, lcg(&mut s) - 0.5);
            }
            let m = convex_hull_2d(&mut scratch[..2 * n], n);
            let hull = &scratch[n..n + m];
            let rect = min_area_rectangle(hull);
            let mut brute = f64::INFINITY;
            for i in 0..m {
                let u = (hull[(i + 1) % m] - hull[i]).as_dvec2().normalize();
                let v = u.perp();
                let (mut lo, mut hi) =
                    (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
                for p in hull {
                    let t = DVec2::new(u.dot(p.as_dvec2()), v.dot(p.as_dvec2()));
                    lo = lo.min(t);
                    hi = hi.max(t);
                }
                brute = brute.min((hi - lo).x * (hi - lo).y);
            }
            let got = rect.width * rect.length;
            assert!(
                (got - brute).abs() <= 1e-12 * brute.max(1e-300),
                "{got} vs {brute}"
            );
            // And the rectangle really encloses the hull.
            let v = rect.direction.perp();
            let spread = |d: DVec2| {
                let t = hull.iter().map(|p| d.dot(p.as_dvec2()));
                t.clone().fold(f64::NEG_INFINITY, f64::max) - t.fold(f64::INFINITY, f64::min)
            };
            assert!(spread(rect.direction) <= rect.width * (1.0 + 1e-12));
            assert!(spread(v) <= rect.length * (1.0 + 1e-12));
        }
    }
}
