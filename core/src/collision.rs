//! The collision system: broad phase over objects, narrow phase per pair.
//!
//! Lecture: *collision detection system*. Three steps, one direction:
//!
//! 1. **Broad phase**: a hierarchy over the objects' world boxes finds the
//!    object pairs whose boxes overlap (the pair list);
//! 2. **Narrow phase**: each listed pair runs a tree-against-tree query with
//!    B carried into A's frame by their relative [`Rigid`] motion (no rebuild),
//!    down to primitive pairs, decided exactly ([`Intersects`]);
//! 3. **Results**: each [`Contact`] (object ids and primitive ids) goes to the
//!    application's callback.
//!
//! All storage comes from the caller ([`BroadPhase`]); nothing allocates.

#[cfg(feature = "insertion")]
mod tracker;
#[cfg(feature = "insertion")]
pub use tracker::{PairEvent, PairTracker, Slot, StepReport, TrackerStorage};

use crate::builders::TopDown;
use crate::bv::{Aabb, BoundingVolume};
use crate::narrow::Intersects;
use crate::primitive::Primitive;
use crate::query::{DescentRule, PairTraversal, Pairs, SelfPairs};
use crate::transform::{Rigid, Transform};
use crate::tree::{Bvh, Node};
use crate::Error;
use glam::Vec3;

/// One object of a scene: its tree and primitives in its own model frame,
/// and where it is in the world.
#[derive(Clone, Copy, Debug)]
pub struct Object<'a, B, P> {
    /// The tree over `prims`, in model coordinates.
    pub tree: &'a Bvh<'a, B>,
    /// The primitives, in model coordinates.
    pub prims: &'a [P],
    /// Model frame to world frame.
    pub pose: Rigid,
}

/// Two primitives, of two objects, that touch.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Contact {
    /// Object ids (indices into the object slice), `a < b`.
    pub objects: (u32, u32),
    /// Primitive of object `a` and primitive of object `b`.
    pub prims: (u32, u32),
}

/// Caller-provided storage for the broad phase over `n` objects: `n` boxes,
/// [`max_nodes(n)`](crate::max_nodes) nodes and `n` indices.
#[derive(Debug)]
pub struct BroadPhase<'s> {
    /// World boxes of the objects.
    pub boxes: &'s mut [Aabb],
    /// Nodes of the object hierarchy.
    pub nodes: &'s mut [Node<Aabb>],
    /// Indices of the object hierarchy.
    pub indices: &'s mut [u32],
}

/// The world box of an object, padded so that the broad phase never drops a
/// pair the narrow phase would report: the narrow phase rounds moved
/// primitives to `f32` in A's frame, which can move them by a few ulps of
/// their coordinates. `None` for an object whose tree is empty: it has no
/// extent and touches nothing.
pub fn world_bounds<B: BoundingVolume, P>(object: &Object<'_, B, P>) -> Option<Aabb> {
    let model = object.tree.root()?.bv.aabb();
    let world = object.pose.apply_aabb(&model);
    let size = model.min.abs().max(model.max.abs()).max_element()
        + world.min.abs().max(world.max.abs()).max_element();
    let pad = Vec3::splat(size * 8.0 * f32::EPSILON);
    Some(Aabb::new(world.min - pad, world.max + pad))
}

/// Broad phase: calls `f(a, b)` (with `a < b`) for every object pair whose
/// world boxes overlap; returns the count. Builds a hierarchy over the
/// objects' world boxes in `scratch` and queries it against itself
/// ([`SelfPairs`]).
pub fn object_pairs<B: BoundingVolume, P>(
    objects: &[Object<'_, B, P>],
    scratch: &mut BroadPhase<'_>,
    mut f: impl FnMut(u32, u32),
) -> Result<usize, Error> {
    let n = objects.len();
    if n < 2 {
        return Ok(0);
    }
    let available = scratch.boxes.len();
    let boxes = scratch.boxes.get_mut(..n).ok_or(Error::IndexCapacity {
        needed: n,
        available,
    })?;
    // An empty object keeps its slot (so tree leaves are object ids) with a
    // stand-in point box; its pairs are dropped below, as it touches nothing.
    for (b, o) in boxes.iter_mut().zip(objects) {
        *b = world_bounds(o).unwrap_or(Aabb::new(Vec3::ZERO, Vec3::ZERO));
    }
    let boxes = &*boxes;
    let tree = TopDown::default().build(boxes, scratch.nodes, scratch.indices)?;
    let mut found = 0;
    // The tree against itself, each pair once (not both orders and every
    // object with itself, half of it thrown away).
    SelfPairs::new(&tree, boxes).for_each(|a, b| {
        if !objects[a as usize].tree.is_empty() && !objects[b as usize].tree.is_empty() {
            f(a, b);
            found += 1;
        }
    })?;
    Ok(found)
}

/// The whole system: broad phase, then an exact narrow phase on every listed
/// object pair (object `b` queried in `a`'s frame with `traversal`). Calls `f`
/// with every contact; returns the count. The answer equals
/// [`brute_force::contacts`](crate::brute_force::contacts).
///
/// ```
/// use bvhkit::collision::{collide, BroadPhase, Object};
/// use bvhkit::{Aabb, Node, PairTraversal, Rigid, TopDown, Triangle};
/// use glam::Vec3;
/// // One small mesh (two triangles forming a square), used by three objects.
/// let quad = [
///     Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y),
///     Triangle::new(Vec3::X, Vec3::X + Vec3::Y, Vec3::Y),
/// ];
/// let mut nodes = [Node::<Aabb>::EMPTY; 3];
/// let mut idx = [0u32; 2];
/// let tree = TopDown::default().with_max_leaf_size(1).build(&quad, &mut nodes, &mut idx)?;
/// let tilted = Rigid::new(glam::Quat::from_rotation_x(1.0), Vec3::new(0.5, 0.5, -0.3))?;
/// let objects = [
///     Object { tree: &tree, prims: &quad, pose: Rigid::IDENTITY },
///     Object { tree: &tree, prims: &quad, pose: tilted },
///     Object { tree: &tree, prims: &quad, pose: Rigid::translation(Vec3::splat(10.0))? },
/// ];
/// let (mut boxes, mut bnodes, mut bidx) = ([Aabb::EMPTY; 3], [Node::EMPTY; 5], [0u32; 3]);
/// let mut scratch = BroadPhase { boxes: &mut boxes, nodes: &mut bnodes, indices: &mut bidx };
/// let mut contacts = Vec::new();
/// collide(&objects, &mut scratch, PairTraversal::default(), |c| contacts.push(c))?;
/// assert!(!contacts.is_empty());
/// assert!(contacts.iter().all(|c| c.objects == (0, 1))); // object 2 is far away
/// # Ok::<(), bvhkit::Error>(())
/// ```
pub fn collide<B, P, D>(
    objects: &[Object<'_, B, P>],
    scratch: &mut BroadPhase<'_>,
    traversal: PairTraversal<D>,
    mut f: impl FnMut(Contact),
) -> Result<usize, Error>
where
    B: BoundingVolume,
    P: Primitive + Intersects + Transform,
    D: DescentRule + Copy,
{
    for o in objects {
        crate::tree::hierarchy::check_query(o.tree, o.prims.len())?;
    }
    let mut found = 0;
    let mut failure = None;
    object_pairs(objects, scratch, |i, j| {
        if failure.is_some() {
            return;
        }
        let (a, b) = (&objects[i as usize], &objects[j as usize]);
        let relative = a.pose.inverse().after(&b.pose);
        let result = Pairs::new(a.tree, a.prims, b.tree, b.prims)
            .traversal(traversal)
            .in_frame(relative)
            .exact()
            .for_each(|p, q| {
                f(Contact {
                    objects: (i, j),
                    prims: (p, q),
                })
            });
        match result {
            Ok(n) => found += n,
            Err(e) => failure = Some(e),
        }
    })?;
    match failure {
        Some(e) => Err(e),
        None => Ok(found),
    }
}
