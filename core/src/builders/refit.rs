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
use crate::tree::{Bvh, Node, Shape};
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

impl<'a, B: BoundingVolume> Bvh<'a, B> {
    /// Refits the tree a builder wrote into `nodes` and `indices` to the
    /// moved `prims` ([`refit_all`], leaves grown by `margin`) and opens it
    /// again. `shape` is the built tree's [`Bvh::shape`]; the arrays may be
    /// the whole buffers the builder was given (a `static` sized by
    /// [`max_nodes`](crate::max_nodes)): only the part the shape names is
    /// touched. Refitting keeps the tree's topology, so its depth and leaves
    /// stay valid and the tree is not checked again. The reopened tree keeps
    /// no leaf bounds (the primitives moved).
    ///
    /// Errors, found before anything is written: arrays shorter than
    /// `shape`, a layout no builder of this crate writes (children before
    /// their parent, leaves past the index array), an index past `prims`, a
    /// non-finite moved primitive, a bad margin. An empty tree's shape
    /// reopens the empty tree.
    ///
    /// ```
    /// use bvhkit::{max_nodes, Aabb, Bvh, Node, Query, TopDown};
    /// use glam::Vec3;
    /// let mut boxes: Vec<Aabb> = (0..16)
    ///     .map(|i| Aabb::new(Vec3::X * i as f32, Vec3::X * i as f32 + Vec3::ONE))
    ///     .collect();
    /// // Storage sized for the worst case, as a firmware's statics are.
    /// let mut nodes = [Node::<Aabb>::ZERO; max_nodes(16)];
    /// let mut indices = [0u32; 16];
    /// let shape = TopDown::default().build(&boxes, &mut nodes, &mut indices)?.shape();
    /// for b in &mut boxes {
    ///     *b = Aabb::new(b.min + Vec3::Y * 10.0, b.max + Vec3::Y * 10.0); // every box moves
    /// }
    /// let tree = Bvh::refit(&mut nodes, &indices, &boxes, shape, 0.0)?;
    /// let probe = Aabb::new(Vec3::new(3.5, 10.5, 0.5), Vec3::new(4.5, 10.5, 0.5));
    /// assert_eq!(tree.overlapping(&boxes, &probe, |_| {})?, 2);
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn refit<P: Primitive>(
        nodes: &'a mut [Node<B>],
        indices: &'a [u32],
        prims: &[P],
        shape: Shape,
        margin: f32,
    ) -> Result<Bvh<'a, B>, Error> {
        if nodes.len() < shape.nodes {
            return Err(Error::NodeCapacity {
                needed: shape.nodes,
                available: nodes.len(),
            });
        }
        if indices.len() < shape.indices {
            return Err(Error::IndexCapacity {
                needed: shape.indices,
                available: indices.len(),
            });
        }
        let (nodes, indices) = (&mut nodes[..shape.nodes], &indices[..shape.indices]);
        refit_all(nodes, indices, prims, margin, ())?;
        let nodes: &'a [Node<B>] = nodes;
        Ok(Bvh::from_raw_parts(nodes, indices, shape.depth))
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::query::brute_force;
    use crate::{max_nodes, TopDown, Triangle};

    /// 24 triangles in rows of six.
    fn rows() -> [Triangle; 24] {
        core::array::from_fn(|i| {
            let o = Vec3::new((i % 6) as f32 * 1.5, (i / 6) as f32, 0.0);
            Triangle::new(o, o + Vec3::X, o + Vec3::Y)
        })
    }

    /// `Bvh::refit` on the whole worst-case buffers equals `refit_all` on
    /// the used part, answers queries as brute force does on the moved
    /// primitives, and keeps shape and depth.
    #[test]
    fn refit_on_whole_buffers_reopens_the_moved_tree() {
        let tris = rows();
        let mut nodes = [Node::<Aabb>::ZERO; max_nodes(24)];
        let mut indices = [0u32; 24];
        let built = TopDown::default()
            .with_max_leaf_size(2)
            .build(&tris, &mut nodes, &mut indices)
            .unwrap();
        let shape = built.shape();
        assert!(shape.nodes < nodes.len() && shape.depth > 0);
        let mut expected = nodes;
        // Move every triangle up by 7 and one of them far aside.
        let mut moved = tris.map(|t| t.translated(Vec3::Y * 7.0));
        moved[5] = moved[5].translated(Vec3::Z * 40.0);
        refit_all(&mut expected[..shape.nodes], &indices, &moved, 0.0, ()).unwrap();
        let tree = Bvh::refit(&mut nodes, &indices, &moved, shape, 0.0).unwrap();
        assert_eq!(tree.shape(), shape);
        assert_eq!(tree.nodes(), &expected[..shape.nodes]);
        for probe in [
            Aabb::new(Vec3::new(0.0, 7.0, 0.0), Vec3::new(3.0, 9.0, 0.0)),
            Aabb::new(Vec3::new(7.0, 7.0, 39.0), Vec3::new(9.0, 9.0, 41.0)),
            Aabb::new(Vec3::splat(-5.0), Vec3::splat(-4.0)),
        ] {
            let got = tree.overlapping(&moved, &probe, |_| {}).unwrap();
            assert_eq!(got, brute_force::overlapping(&moved, &probe, |_| {}));
        }
        assert_eq!(
            tree.overlapping(
                &moved,
                &Aabb::new(Vec3::new(7.5, 7.0, 39.0), Vec3::new(8.0, 8.0, 41.0)),
                |_| {}
            )
            .unwrap(),
            1
        );
    }

    /// Short arrays, a NaN primitive and a bad margin are errors found
    /// before anything is written; an empty shape reopens the empty tree.
    #[test]
    fn refit_refuses_bad_input_untouched() {
        let tris = rows();
        let mut nodes = [Node::<Aabb>::ZERO; max_nodes(24)];
        let mut indices = [0u32; 24];
        let shape = TopDown::default()
            .build(&tris, &mut nodes, &mut indices)
            .unwrap()
            .shape();
        let before = nodes;
        let short = Bvh::refit(&mut nodes[..shape.nodes - 1], &indices, &tris, shape, 0.0);
        assert!(
            matches!(short, Err(Error::NodeCapacity { .. })),
            "{short:?}"
        );
        let short = Bvh::refit(&mut nodes, &indices[..3], &tris, shape, 0.0);
        assert!(
            matches!(short, Err(Error::IndexCapacity { .. })),
            "{short:?}"
        );
        let mut nan = tris;
        nan[3].v[1].y = f32::NAN;
        let err = Bvh::refit(&mut nodes, &indices, &nan, shape, 0.0);
        assert!(
            matches!(err, Err(Error::NonFiniteCoordinate { .. })),
            "{err:?}"
        );
        let err = Bvh::refit(&mut nodes, &indices, &tris, shape, -1.0);
        assert!(matches!(err, Err(Error::InvalidConfig(_))), "{err:?}");
        let err = Bvh::refit(&mut nodes, &indices, &tris[..4], shape, 0.0);
        assert!(
            matches!(err, Err(Error::PrimitiveCountMismatch { .. })),
            "{err:?}"
        );
        assert_eq!(nodes, before);
        let empty = Bvh::refit(&mut nodes, &indices, &tris[..0], Shape::default(), 0.0).unwrap();
        assert!(empty.is_empty());
        assert_eq!(
            empty
                .overlapping(&tris[..0], &Aabb::new(Vec3::ZERO, Vec3::ONE), |_| {})
                .unwrap(),
            0
        );
    }
}
