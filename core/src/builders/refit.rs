//! Refitting: keeping a tree's volumes right after its primitives move.
//!
//! Lecture: *cost function*, the `Nu * Cu` term. When primitives move but stay
//! near their neighbours (a deforming mesh, a ragdoll), the tree's *shape* can
//! stay: only the volumes must grow or shrink to contain the moved primitives.
//! A refit does that bottom-up and counts every node it rewrote (`Nu`).
//!
//! - [`refit_all`] recomputes every volume (one reverse sweep, `O(n)`).
//! - [`Refit::moved`] recomputes only the leaves holding the moved primitives
//!   and their ancestors, stopping early where a volume did not change.
//! - A *margin* fattens the leaf volumes so that small motions need no update
//!   at all: a moved primitive still inside its leaf's fat volume costs
//!   nothing.
//!
//! A refitted tree is correct (every query still equals brute force) but its
//! quality decays as the motion grows; `bvhkit-std` measures when a rebuild
//! pays off.

use super::enclose;
use crate::bv::{Aabb, BoundingVolume, BoxSet};
use crate::primitive::Primitive;
use crate::query::Tally;
use crate::tree::Node;
use crate::Error;
use glam::Vec3;

/// No parent (the root).
const NONE: u32 = u32::MAX;

/// The boxes of one leaf's primitives, grown by a margin.
struct LeafBoxes<'a, P> {
    prims: &'a [P],
    items: &'a [u32],
    margin: f32,
}

impl<P: Primitive> BoxSet for LeafBoxes<'_, P> {
    fn len(&self) -> usize {
        self.items.len()
    }
    fn aabb(&self, i: usize) -> Aabb {
        grow(&self.prims[self.items[i] as usize].bounds(), self.margin)
    }
}

fn grow(b: &Aabb, margin: f32) -> Aabb {
    if margin == 0.0 {
        return *b;
    }
    let m = Vec3::splat(margin);
    Aabb::new(b.min - m, b.max + m)
}

/// The volume of a leaf over its primitives (grown by `margin`).
fn fit_leaf<B: BoundingVolume, P: Primitive>(prims: &[P], items: &[u32], margin: f32) -> B {
    let boxes = LeafBoxes {
        prims,
        items,
        margin,
    };
    let mut union = Aabb::EMPTY;
    for i in 0..boxes.len() {
        union = union.union(&boxes.aabb(i));
    }
    B::fit_boxes(&boxes, &union)
}

/// Checks that children follow their parents in the array (true for every
/// builder of this crate) and that indices are in range.
fn check_layout<B: BoundingVolume>(nodes: &[Node<B>], indices: &[u32]) -> Result<(), Error> {
    for (i, n) in nodes.iter().enumerate() {
        match n.children() {
            Some((l, r)) => {
                if (l as usize) <= i || r as usize >= nodes.len() {
                    return Err(Error::InvalidTree(
                        "refit needs children stored after their parent",
                    ));
                }
            }
            None => {
                if n.first as usize + n.count as usize > indices.len() {
                    return Err(Error::InvalidTree("leaf range outside the index array"));
                }
            }
        }
    }
    Ok(())
}

/// Recomputes every volume of the tree stored in `nodes` / `indices` over the
/// (moved) `prims`, leaves grown by `margin`; counts each node as an update.
///
/// ```
/// use bvhkit::builders::refit_all;
/// use bvhkit::{Aabb, Node, TopDown, Triangle};
/// use glam::Vec3;
/// let mut tris: Vec<Triangle> = (0..8).map(|i| {
///     let o = Vec3::X * i as f32;
///     Triangle::new(o, o + Vec3::Y, o + Vec3::Z)
/// }).collect();
/// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(8)];
/// let mut idx = vec![0u32; 8];
/// let used = TopDown::default().with_max_leaf_size(1).build(&tris, &mut nodes, &mut idx)?.node_count();
/// for t in &mut tris { *t = t.translated(Vec3::Y * 5.0); } // everything moves
/// let updated = refit_all(&mut nodes[..used], &idx, &tris, 0.0, ())?;
/// assert_eq!(updated, used);
/// assert_eq!(nodes[0].bv.min.y, 5.0);
/// # Ok::<(), bvhkit::Error>(())
/// ```
pub fn refit_all<B: BoundingVolume, P: Primitive>(
    nodes: &mut [Node<B>],
    indices: &[u32],
    prims: &[P],
    margin: f32,
    mut tally: impl Tally,
) -> Result<usize, Error> {
    check_inputs(nodes, indices, prims, margin)?;
    for i in (0..nodes.len()).rev() {
        let n = nodes[i];
        nodes[i].bv = match n.children() {
            Some((l, r)) => enclose(&nodes[l as usize].bv, &nodes[r as usize].bv),
            None => fit_leaf(
                prims,
                &indices[n.first as usize..(n.first + n.count) as usize],
                margin,
            ),
        };
    }
    tally.updates(nodes.len() as u32);
    Ok(nodes.len())
}

fn check_inputs<B: BoundingVolume, P: Primitive>(
    nodes: &[Node<B>],
    indices: &[u32],
    prims: &[P],
    margin: f32,
) -> Result<(), Error> {
    if !(margin >= 0.0 && margin.is_finite()) {
        return Err(Error::InvalidConfig(
            "the refit margin must be finite and >= 0",
        ));
    }
    check_layout(nodes, indices)?;
    if indices.iter().any(|&p| p as usize >= prims.len()) {
        return Err(Error::PrimitiveCountMismatch {
            tree: indices.len(),
            given: prims.len(),
        });
    }
    crate::primitive::validate(prims)
}

/// Incremental refits for one tree: the parent of every node and the leaf of
/// every primitive, kept in caller scratch (`nodes.len()` and `prims.len()`
/// words).
///
/// ```
/// use bvhkit::builders::{refit_all, Refit};
/// use bvhkit::{Aabb, Counts, Node, TopDown, Triangle};
/// use glam::Vec3;
/// let mut tris: Vec<Triangle> = (0..64).map(|i| {
///     let o = Vec3::new((i % 8) as f32, (i / 8) as f32, 0.0);
///     Triangle::new(o, o + Vec3::X * 0.5, o + Vec3::Y * 0.5)
/// }).collect();
/// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(64)];
/// let mut idx = vec![0u32; 64];
/// let used = TopDown::default().build(&tris, &mut nodes, &mut idx)?.node_count();
/// let nodes = &mut nodes[..used];
/// // Fatten the leaves by 0.1 once, then keep parent links.
/// refit_all(nodes, &idx, &tris, 0.1, ())?;
/// let (mut parents, mut leaf_of) = (vec![0u32; used], vec![0u32; 64]);
/// let refit = Refit::new(nodes, &idx, &mut parents, &mut leaf_of)?;
///
/// // A small move stays inside the fat leaf: nothing to update.
/// tris[10] = tris[10].translated(Vec3::X * 0.05);
/// let mut counts = Counts::default();
/// refit.moved(nodes, &idx, &tris, &[10], 0.1, &mut counts)?;
/// assert_eq!(counts.updates, 0);
/// // A large one updates its leaf and the ancestors that change.
/// tris[10] = tris[10].translated(Vec3::Z * 3.0);
/// refit.moved(nodes, &idx, &tris, &[10], 0.1, &mut counts)?;
/// assert!(counts.updates >= 2);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Debug)]
pub struct Refit<'s> {
    parents: &'s [u32],
    leaf_of: &'s [u32],
}

impl<'s> Refit<'s> {
    /// Records parents and leaves of the tree in `nodes` / `indices`.
    pub fn new<B: BoundingVolume>(
        nodes: &[Node<B>],
        indices: &[u32],
        parents: &'s mut [u32],
        leaf_of: &'s mut [u32],
    ) -> Result<Refit<'s>, Error> {
        check_layout(nodes, indices)?;
        if parents.len() < nodes.len() {
            return Err(Error::NodeCapacity {
                needed: nodes.len(),
                available: parents.len(),
            });
        }
        if let Some(root) = parents.first_mut() {
            *root = NONE; // the empty tree has no root
        }
        let available = leaf_of.len();
        for (i, n) in nodes.iter().enumerate() {
            match n.children() {
                Some((l, r)) => {
                    parents[l as usize] = i as u32;
                    parents[r as usize] = i as u32;
                }
                None => {
                    for &p in &indices[n.first as usize..(n.first + n.count) as usize] {
                        *leaf_of.get_mut(p as usize).ok_or(Error::IndexCapacity {
                            needed: p as usize + 1,
                            available,
                        })? = i as u32;
                    }
                }
            }
        }
        Ok(Refit { parents, leaf_of })
    }

    /// Updates the tree after the primitives listed in `moved` changed in
    /// `prims`. A primitive still inside its leaf's volume costs nothing;
    /// otherwise its leaf is refitted (grown by `margin`) and then each
    /// ancestor, stopping at the first one that already contains its new
    /// children. Ancestors only ever grow here; [`refit_all`] also shrinks
    /// them. Returns the number of nodes rewritten (also given to `tally`
    /// as updates).
    pub fn moved<B: BoundingVolume, P: Primitive>(
        &self,
        nodes: &mut [Node<B>],
        indices: &[u32],
        prims: &[P],
        moved: &[u32],
        margin: f32,
        mut tally: impl Tally,
    ) -> Result<usize, Error> {
        if nodes.len() > self.parents.len() {
            return Err(Error::InvalidTree(
                "refit scratch was made for another tree",
            ));
        }
        if !(margin >= 0.0 && margin.is_finite()) {
            return Err(Error::InvalidConfig(
                "the refit margin must be finite and >= 0",
            ));
        }
        let mut updated = 0;
        for &p in moved {
            let prim = prims.get(p as usize).ok_or(Error::PrimitiveCountMismatch {
                tree: self.leaf_of.len(),
                given: prims.len(),
            })?;
            if !prim.is_finite() {
                return Err(Error::NonFiniteCoordinate {
                    primitive: p as usize,
                });
            }
            let leaf = match self.leaf_of.get(p as usize) {
                Some(&l) if (l as usize) < nodes.len() => l as usize,
                _ => {
                    return Err(Error::PrimitiveCountMismatch {
                        tree: self.leaf_of.len(),
                        given: prims.len(),
                    })
                }
            };
            if nodes[leaf].bv.contains_aabb(&prim.bounds()) {
                continue; // still inside the (fat) leaf volume
            }
            let n = nodes[leaf];
            nodes[leaf].bv = fit_leaf(
                prims,
                &indices[n.first as usize..(n.first + n.count) as usize],
                margin,
            );
            updated += 1;
            let mut child = leaf;
            while self.parents[child] != NONE {
                let parent = self.parents[child] as usize;
                let (l, r) = match nodes[parent].children() {
                    Some(c) => c,
                    None => return Err(Error::InvalidTree("a parent link points to a leaf")),
                };
                let (lb, rb) = (nodes[l as usize].bv, nodes[r as usize].bv);
                if nodes[parent].bv.contains(&lb) && nodes[parent].bv.contains(&rb) {
                    break; // ancestors above already contain everything
                }
                nodes[parent].bv = enclose(&lb, &rb);
                updated += 1;
                child = parent;
            }
        }
        tally.updates(updated as u32);
        Ok(updated)
    }
}
