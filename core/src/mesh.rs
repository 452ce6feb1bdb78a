//! A triangle mesh and its tree in one value (the `alloc` feature).
//!
//! Everything else in the crate takes a tree and its primitives as two
//! arguments, so that storage can come from anywhere. A [`Mesh`] owns both,
//! built once with the fast defaults, so that each everyday question is one
//! call with nothing else to pass, and the tree can never be asked about
//! another mesh's triangles. The answers carry the geometry (points,
//! normals, barycentric coordinates, features), not only an index.

#[cfg(feature = "layouts")]
use alloc::vec;
use alloc::vec::Vec;

use glam::{DVec3, Vec3};

use crate::bv::Aabb;
#[cfg(feature = "layouts")]
use crate::layout::{Wide, WideNode};
#[cfg(feature = "layouts")]
use crate::query::Query;
use crate::query::{Ray, RayOrder, TriangleFeature};
use crate::transform::Rigid;
#[cfg(feature = "layouts")]
use crate::Hierarchy;
use crate::{Bvh, Error, OwnedBvh, Pairs, TopDown, Triangle};

/// A triangle mesh with its tree: built once, then queried by value.
///
/// ```
/// use bvhkit::{Mesh, Ray, Rigid, Triangle};
/// use bvhkit::glam::{Quat, Vec3};
/// // A floor of 2 x 50 x 50 triangles.
/// let mut tris = Vec::new();
/// for i in 0..50 {
///     for j in 0..50 {
///         let o = Vec3::new(i as f32, j as f32, 0.0);
///         tris.push(Triangle::new(o, o + Vec3::X, o + Vec3::Y));
///         tris.push(Triangle::new(o + Vec3::X, o + Vec3::ONE.with_z(0.0), o + Vec3::Y));
///     }
/// }
/// let floor = Mesh::new(tris)?;
///
/// // A ray straight down: where, on which triangle, which way it faces.
/// let down = Ray::new(Vec3::new(10.25, 20.5, 3.0), -Vec3::Z, f32::INFINITY)?;
/// let hit = floor.cast_ray(&down).unwrap();
/// assert_eq!((hit.t, hit.point, hit.normal), (3.0, Vec3::new(10.25, 20.5, 0.0), Vec3::Z));
///
/// // The closest point of the floor to a point above it.
/// let near = floor.closest_point(Vec3::new(3.3, 4.6, 2.0)).unwrap();
/// assert_eq!(near.distance, 2.0);
///
/// // Every triangle within 0.1 of a point on the floor.
/// assert!(floor.within(Vec3::new(7.5, 7.5, 0.05), 0.1).len() >= 2);
///
/// // Every pair of crossing triangles of the floor and a tilted copy.
/// let tilt = Rigid::new(Quat::from_rotation_x(0.3), Vec3::new(0.0, 0.0, -0.5))?;
/// let pairs = floor.pairs(&floor, &tilt);
/// assert!(!pairs.is_empty());
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Mesh {
    triangles: Vec<Triangle>,
    tree: OwnedBvh<Aabb>,
    /// The tree collapsed to 4-wide nodes, for rays (see [`Mesh::new`]).
    #[cfg(feature = "layouts")]
    wide: WideTree,
}

/// A [`Wide`] layout's records with what its view needs besides them.
#[cfg(feature = "layouts")]
#[derive(Clone, Debug)]
struct WideTree {
    records: Vec<WideNode>,
    depth: usize,
    nodes: usize,
}

/// Where a ray first meets a [`Mesh`] ([`Mesh::cast_ray`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHit {
    /// The triangle's index in the mesh.
    pub triangle: u32,
    /// Distance along the ray, in units of its direction.
    pub t: f32,
    /// The hit point, `origin + t * dir`.
    pub point: Vec3,
    /// The triangle's unit normal (counter-clockwise corners face it).
    pub normal: Vec3,
    /// Whether the ray arrives on the side `normal` points to.
    pub front: bool,
    /// Barycentric coordinates of the hit point on the triangle.
    pub barycentric: DVec3,
}

/// The point of a [`Mesh`] closest to a query point ([`Mesh::closest_point`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointHit {
    /// The index of the triangle it lies on (on a shared edge or vertex,
    /// the lowest such index among the closest).
    pub triangle: u32,
    /// The closest point, in `f64`.
    pub point: DVec3,
    /// Its distance from the query point, in `f64`.
    pub distance: f64,
    /// Its barycentric coordinates on the triangle.
    pub barycentric: DVec3,
    /// The vertex, edge or face of the triangle it lies on.
    pub feature: TriangleFeature,
}

impl Mesh {
    /// Builds the tree over `triangles` with the default builder
    /// ([`TopDown::default`]: binned SAH, the fastest build of the crate's
    /// good trees). Errors: a NaN, infinite or too large coordinate (named
    /// by its triangle), more triangles than 32-bit indices name. No
    /// triangles is not an error: an empty mesh answers every query with
    /// nothing.
    ///
    /// ```
    /// use bvhkit::{Mesh, Triangle};
    /// use glam::Vec3;
    /// let floor = Mesh::new(vec![
    ///     Triangle::new(Vec3::ZERO, Vec3::new(4.0, 0.0, 0.0), Vec3::new(0.0, 4.0, 0.0)),
    ///     Triangle::new(Vec3::new(4.0, 0.0, 0.0), Vec3::new(4.0, 4.0, 0.0), Vec3::new(0.0, 4.0, 0.0)),
    /// ])?;
    /// assert_eq!(floor.triangles().len(), 2);
    /// assert!(Mesh::new(vec![Triangle::new(Vec3::NAN, Vec3::ZERO, Vec3::X)]).is_err());
    /// assert!(Mesh::new(Vec::new())?.cast_ray(&bvhkit::Ray::new(Vec3::ZERO, Vec3::X, 1.0)?).is_none());
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn new(triangles: Vec<Triangle>) -> Result<Mesh, Error> {
        Mesh::with_builder(triangles, &TopDown::default())
    }

    /// A mesh given as shared vertices and a triple of vertex indices per
    /// triangle (as mesh files and engines keep it), built as
    /// [`new`](Self::new) builds. Errors as `new`, and
    /// [`Error::VertexIndexOutOfRange`] naming the first triangle with an
    /// index past `vertices`.
    ///
    /// ```
    /// use bvhkit::{Error, Mesh};
    /// use bvhkit::glam::Vec3;
    /// // A unit square of two triangles sharing an edge.
    /// let vertices = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
    /// let square = Mesh::from_indexed(&vertices, &[[0, 1, 2], [0, 2, 3]])?;
    /// assert_eq!(square.triangles().len(), 2);
    /// assert_eq!(square.closest_point(Vec3::new(0.25, 0.75, 1.0)).unwrap().triangle, 1);
    /// assert_eq!(
    ///     Mesh::from_indexed(&vertices, &[[0, 1, 4]]).unwrap_err(),
    ///     Error::VertexIndexOutOfRange { triangle: 0, vertices: 4 }
    /// );
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn from_indexed(vertices: &[Vec3], triangles: &[[u32; 3]]) -> Result<Mesh, Error> {
        let corner = |k: usize, i: u32| {
            vertices
                .get(i as usize)
                .copied()
                .ok_or(Error::VertexIndexOutOfRange {
                    triangle: k,
                    vertices: vertices.len(),
                })
        };
        let tris = triangles
            .iter()
            .enumerate()
            .map(|(k, t)| {
                Ok(Triangle::new(
                    corner(k, t[0])?,
                    corner(k, t[1])?,
                    corner(k, t[2])?,
                ))
            })
            .collect::<Result<Vec<Triangle>, Error>>()?;
        Mesh::new(tris)
    }

    /// [`new`](Self::new) with another top-down configuration.
    pub fn with_builder(triangles: Vec<Triangle>, builder: &TopDown) -> Result<Mesh, Error> {
        let tree = OwnedBvh::build(builder, &triangles)?;
        #[cfg(feature = "layouts")]
        let wide = {
            let view = tree.view();
            let mut records = vec![WideNode::ZERO; Wide::records_needed(&view)?];
            let w = Wide::from_bvh(&view, &mut records)?;
            let (depth, nodes) = (w.depth(), w.node_count());
            WideTree {
                records,
                depth,
                nodes,
            }
        };
        Ok(Mesh {
            triangles,
            tree,
            #[cfg(feature = "layouts")]
            wide,
        })
    }

    /// The triangles, in the order given.
    pub fn triangles(&self) -> &[Triangle] {
        &self.triangles
    }

    /// The tree, as the view every query of the crate takes (with the
    /// triangles, [`triangles`](Self::triangles)): for the questions and
    /// settings the one-call methods do not offer.
    pub fn tree(&self) -> Bvh<'_, Aabb> {
        self.tree.view()
    }

    /// The first triangle `ray` meets (the smallest `t`; on a tie, the
    /// lowest index), with the hit point, normal and barycentric
    /// coordinates; `None` if it meets none within its `t_max`.
    ///
    /// ```
    /// use bvhkit::{Mesh, Ray, Triangle};
    /// use glam::Vec3;
    /// let floor = Mesh::new(vec![
    ///     Triangle::new(Vec3::ZERO, Vec3::new(4.0, 0.0, 0.0), Vec3::new(0.0, 4.0, 0.0)),
    ///     Triangle::new(Vec3::new(4.0, 0.0, 0.0), Vec3::new(4.0, 4.0, 0.0), Vec3::new(0.0, 4.0, 0.0)),
    /// ])?;
    /// let down = Ray::new(Vec3::new(3.0, 3.0, 2.0), -Vec3::Z, f32::INFINITY)?;
    /// let hit = floor.cast_ray(&down).expect("it lands on the floor");
    /// assert_eq!((hit.triangle, hit.t, hit.point), (1, 2.0, Vec3::new(3.0, 3.0, 0.0)));
    /// assert!(hit.front && hit.normal == Vec3::Z); // arrives from above
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn cast_ray(&self, ray: &Ray) -> Option<RayHit> {
        let tree = self.tree.view();
        // The tree was built over exactly these triangles and within the
        // stack's depth: the query's checks cannot fail.
        #[cfg(feature = "layouts")]
        let hit = {
            let WideTree {
                records,
                depth,
                nodes,
            } = &self.wide;
            let wide = Wide::from_kept(records, &tree, *depth, *nodes);
            Query::cast_ray(&wide, &self.triangles, ray, RayOrder::default(), ())
        };
        #[cfg(not(feature = "layouts"))]
        let hit = tree.cast_ray(&self.triangles, ray, RayOrder::default(), ());
        let hit = hit.ok()??;
        let tri = self.triangles.get(hit.prim as usize)?;
        let on = tri.ray_intersection(ray)?;
        Some(RayHit {
            triangle: hit.prim,
            t: hit.t,
            point: ray.origin() + ray.dir() * hit.t,
            normal: on.normal,
            front: on.front,
            barycentric: on.barycentric,
        })
    }

    /// The point of the mesh closest to `p`, with its triangle, distance,
    /// barycentric coordinates and feature. `None` for an empty mesh, and
    /// for a `p` with a NaN or infinite coordinate (no point is closest).
    ///
    /// ```
    /// use bvhkit::{Mesh, Triangle};
    /// use glam::Vec3;
    /// let floor = Mesh::new(vec![
    ///     Triangle::new(Vec3::ZERO, Vec3::new(4.0, 0.0, 0.0), Vec3::new(0.0, 4.0, 0.0)),
    ///     Triangle::new(Vec3::new(4.0, 0.0, 0.0), Vec3::new(4.0, 4.0, 0.0), Vec3::new(0.0, 4.0, 0.0)),
    /// ])?;
    /// let c = floor.closest_point(Vec3::new(1.0, 1.0, 3.0)).unwrap();
    /// assert_eq!((c.triangle, c.distance), (0, 3.0));
    /// assert_eq!(c.point, glam::DVec3::new(1.0, 1.0, 0.0));
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn closest_point(&self, p: Vec3) -> Option<PointHit> {
        let tree = self.tree.view();
        let near =
            crate::query::nearest::nearest_nearer_first(&tree, &self.triangles, p).ok()??;
        let c = self.triangles.get(near.prim as usize)?.closest_point(p);
        Some(PointHit {
            triangle: near.prim,
            point: c.point,
            distance: libm::sqrt(c.distance_squared),
            barycentric: c.barycentric,
            feature: c.feature,
        })
    }

    /// Every triangle within `distance` of `p` (its closest point at most
    /// that far, computed in `f64` as [`closest_point`](Self::closest_point)
    /// does), in increasing index order. Empty for a `p` or `distance` that
    /// is NaN or infinite, or a negative `distance`.
    ///
    /// ```
    /// use bvhkit::{Mesh, Triangle};
    /// use glam::Vec3;
    /// let floor = Mesh::new(vec![
    ///     Triangle::new(Vec3::ZERO, Vec3::new(4.0, 0.0, 0.0), Vec3::new(0.0, 4.0, 0.0)),
    ///     Triangle::new(Vec3::new(4.0, 0.0, 0.0), Vec3::new(4.0, 4.0, 0.0), Vec3::new(0.0, 4.0, 0.0)),
    /// ])?;
    /// // Above the shared diagonal: both triangles are half a unit away.
    /// assert_eq!(floor.within(Vec3::new(2.0, 2.0, 0.5), 0.5), [0, 1]);
    /// assert!(floor.within(Vec3::new(2.0, 2.0, 0.5), 0.4).is_empty());
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn within(&self, p: Vec3, distance: f32) -> Vec<u32> {
        let mut found = Vec::new();
        if !(p.is_finite() && distance.is_finite() && distance >= 0.0) {
            return found;
        }
        let limit = f64::from(distance) * f64::from(distance);
        // The box around the ball. Its corners round in f32, but rounding
        // is monotone: a coordinate of a triangle (an f32) within
        // `distance` of `p`'s stays inside the rounded `p -+ distance`.
        let region = Aabb::new(p - distance, p + distance);
        let tris = &self.triangles;
        let _ = self.tree.view().overlapping(tris, &region, |i| {
            if tris[i as usize].closest_point(p).distance_squared <= limit {
                found.push(i);
            }
        });
        found.sort_unstable();
        found
    }

    /// Every pair `(a, b)` of a triangle of this mesh and one of `other`
    /// that intersect (share at least one point, decided exactly), with
    /// `other` placed by `motion` (a rigid motion into this mesh's frame;
    /// [`Rigid::IDENTITY`] for none), sorted. Neither tree is rebuilt: the
    /// motion is applied during the walk.
    ///
    /// ```
    /// use bvhkit::{Mesh, Rigid, Triangle};
    /// use glam::Vec3;
    /// let floor = Mesh::new(vec![
    ///     Triangle::new(Vec3::ZERO, Vec3::new(4.0, 0.0, 0.0), Vec3::new(0.0, 4.0, 0.0)),
    ///     Triangle::new(Vec3::new(4.0, 0.0, 0.0), Vec3::new(4.0, 4.0, 0.0), Vec3::new(0.0, 4.0, 0.0)),
    /// ])?;
    /// // A wall standing on the floor's first triangle, then lifted away.
    /// let wall = Mesh::new(vec![Triangle::new(
    ///     Vec3::new(0.5, 0.5, -1.0),
    ///     Vec3::new(1.5, 0.5, -1.0),
    ///     Vec3::new(1.0, 0.5, 1.0),
    /// )])?;
    /// assert_eq!(floor.pairs(&wall, &Rigid::IDENTITY), [(0, 0)]);
    /// assert!(floor.intersects(&wall, &Rigid::IDENTITY));
    /// let lifted = Rigid::translation(Vec3::new(0.0, 0.0, 5.0))?;
    /// assert!(floor.pairs(&wall, &lifted).is_empty() && !floor.intersects(&wall, &lifted));
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn pairs(&self, other: &Mesh, motion: &Rigid) -> Vec<(u32, u32)> {
        let (a, b) = (self.tree.view(), other.tree.view());
        let (ta, tb) = (&self.triangles[..], &other.triangles[..]);
        let mut out = Vec::new();
        let push = |i, j| out.push((i, j));
        // Both trees were built over exactly these triangles and within the
        // stack's depth: the queries' checks cannot fail.
        let _ = if motion.is_identity() {
            Pairs::new(&a, ta, &b, tb).exact().for_each(push)
        } else {
            Pairs::new(&a, ta, &b, tb)
                .in_frame(*motion)
                .exact()
                .for_each(push)
        };
        out.sort_unstable();
        out
    }

    /// Whether any triangle of this mesh intersects one of `other` placed
    /// by `motion`: [`pairs`](Self::pairs) stopped at the first pair.
    pub fn intersects(&self, other: &Mesh, motion: &Rigid) -> bool {
        let (a, b) = (self.tree.view(), other.tree.view());
        let (ta, tb) = (&self.triangles[..], &other.triangles[..]);
        let first = if motion.is_identity() {
            Pairs::new(&a, ta, &b, tb).exact().first()
        } else {
            Pairs::new(&a, ta, &b, tb).in_frame(*motion).exact().first()
        };
        matches!(first, Ok(Some(_)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn floor() -> Mesh {
        Mesh::new(vec![
            Triangle::new(
                Vec3::ZERO,
                Vec3::new(4.0, 0.0, 0.0),
                Vec3::new(0.0, 4.0, 0.0),
            ),
            Triangle::new(
                Vec3::new(4.0, 0.0, 0.0),
                Vec3::new(4.0, 4.0, 0.0),
                Vec3::new(0.0, 4.0, 0.0),
            ),
        ])
        .unwrap()
    }

    #[test]
    fn within_keeps_only_what_is_that_close_and_refuses_bad_input_quietly() {
        let floor = floor();
        // Off the corner (4, 4, 0): 0.9 away. The box around a ball of 0.8
        // reaches both triangles' boxes, the ball reaches neither.
        let p = Vec3::new(4.6, 4.6, 0.3);
        assert!(floor.within(p, 0.8).is_empty());
        assert_eq!(floor.within(p, 0.9), [1]);
        // Bad input: nothing, not a panic.
        let inside = Vec3::new(1.0, 1.0, 0.0);
        assert_eq!(floor.within(inside, 0.0), [0]);
        for (p, d) in [
            (Vec3::new(f32::NAN, 1.0, 0.0), 1.0),
            (Vec3::new(1.0, f32::INFINITY, 0.0), 1.0),
            (inside, f32::NAN),
            (inside, f32::INFINITY),
            (inside, -1.0),
        ] {
            assert!(floor.within(p, d).is_empty(), "{p} {d}");
        }
    }
}
