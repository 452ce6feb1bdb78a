//! The canonical hierarchy: a flat array of nodes the caller owns.
//!
//! Lecture: *tree representation* ("offsets instead of pointers"). Nodes live in
//! a slice the caller provides (a `static` array on a microcontroller, a `Vec`
//! on a desktop); a node names its children by index into that slice, never by
//! reference. Children are stored side by side, so one index names both.
//!
//! Sizing: a binary tree over `n` primitives with at least one primitive per
//! leaf has at most `2n - 1` nodes ([`max_nodes`]) and its index array holds `n`
//! entries.

mod capacity;
pub(crate) mod hierarchy;
pub(crate) mod validate;

pub use capacity::Capacity;
pub use hierarchy::{Boxes4, Content, Hierarchy, Kids, MAX_CHILDREN};

use crate::builders::BuildReport;
use crate::bv::{Aabb, BoundingVolume};
use crate::primitive::Primitive;
use crate::Error;

/// Deepest tree the builders produce and the queries accept. Every traversal
/// owns a fixed stack sized from this, so no query can overflow.
pub const MAX_DEPTH: usize = 64;

/// Most primitives a tree can hold: node indices (`2n - 1`) must fit a `u32`.
pub const MAX_PRIMITIVES: usize = (u32::MAX / 2) as usize;

/// Upper bound on the node count of a binary tree over `n` primitives: `2n - 1`.
///
/// ```
/// assert_eq!(bvhkit::max_nodes(64), 127);
/// // Size static storage at compile time (zero bits: `.bss`, not flash):
/// static NODES: [bvhkit::Node<bvhkit::Aabb>; bvhkit::max_nodes(64)] =
///     [bvhkit::Node::ZERO; bvhkit::max_nodes(64)];
/// ```
pub const fn max_nodes(n: usize) -> usize {
    if n == 0 {
        0
    } else {
        // Saturating: past `MAX_PRIMITIVES` no build accepts the input
        // anyway, and a sizing function must not panic.
        n.saturating_mul(2) - 1
    }
}

/// Node count of a binary tree with `leaves` leaves: `2 * leaves - 1` (every
/// inner node has two children), 0 for none.
///
/// [`max_nodes`] sizes for the worst case, one primitive per leaf; a tree
/// with several primitives per leaf uses far fewer nodes. No builder can
/// promise a leaf count in advance (a split may cut one primitive off), but
/// for a scene known ahead (a static mesh in flash) the leaf count of its
/// build is known: build it once on the host, read
/// [`TreeStats::leaves`](crate::TreeStats) (or [`Shape::nodes`]), and size
/// the device's array by it. The same build on the device then fits
/// exactly; a scene that needs more nodes is an [`Error::NodeCapacity`],
/// never a write past the array.
///
/// ```
/// use bvhkit::{max_nodes, max_nodes_for_leaves, Aabb, Node, TopDown, Triangle};
/// use bvhkit::glam::Vec3;
/// let tris: [Triangle; 512] = core::array::from_fn(|i| {
///     let o = Vec3::new((i % 32) as f32, (i / 32) as f32, 0.0);
///     Triangle::new(o, o + Vec3::X, o + Vec3::Y)
/// });
/// // On the host: the worst case, then the count this scene needs.
/// let mut big = vec![Node::<Aabb>::ZERO; max_nodes(512)];
/// let mut idx = [0u32; 512];
/// let leaves = TopDown::sah().build(&tris, &mut big, &mut idx)?.stats().leaves;
/// assert_eq!(max_nodes(512), 1023);
/// assert!(max_nodes_for_leaves(leaves) < 400); // leaves of up to 4
/// // On the device: exactly that many nodes.
/// let mut nodes = vec![Node::<Aabb>::ZERO; max_nodes_for_leaves(leaves)];
/// let tree = TopDown::sah().build(&tris, &mut nodes, &mut idx)?;
/// assert_eq!(tree.node_count(), nodes.len());
/// // One node short is an error, not a panic.
/// assert!(TopDown::sah().build(&tris, &mut nodes[1..], &mut idx).is_err());
/// # Ok::<(), bvhkit::Error>(())
/// ```
pub const fn max_nodes_for_leaves(leaves: usize) -> usize {
    if leaves == 0 {
        0
    } else {
        leaves.saturating_mul(2) - 1
    }
}

/// One node: a bounding volume and either two children or a run of primitives.
///
/// For an internal node (`count == 0`) the children are `first` and `first + 1`.
/// For a leaf (`count > 0`) the primitives are `indices[first .. first + count]`.
/// With an [`Aabb`] the node is 32 bytes.
///
/// Storage for a tree is an array of nodes the caller sizes
/// ([`max_nodes`]); `Node::ZERO` fills a `static` at no
/// flash cost, `Node::EMPTY` a `Vec`.
///
/// ```
/// use bvhkit::glam::Vec3;
/// use bvhkit::{max_nodes, Aabb, Node, TopDown};
/// let points = [Vec3::ZERO, Vec3::X, Vec3::Y];
/// let mut nodes = [Node::<Aabb>::ZERO; max_nodes(3)];
/// let mut indices = [0u32; 3];
/// let tree = TopDown::default().with_max_leaf_size(1).build(&points, &mut nodes, &mut indices)?;
/// let root = tree.root().unwrap();
/// assert_eq!((root.count, root.first), (0, 1)); // internal: children at 1 and 2
/// assert_eq!(root.bv, Aabb::new(Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0)));
/// assert_eq!(core::mem::size_of::<Node<Aabb>>(), 32);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct Node<B> {
    /// Bounds of everything beneath this node.
    pub bv: B,
    /// First child (internal) or first entry in the index array (leaf).
    pub first: u32,
    /// Number of primitives for a leaf; 0 for an internal node.
    pub count: u32,
}

impl<B: BoundingVolume> Node<B> {
    /// A blank node, for initialising storage.
    pub const EMPTY: Self = Node {
        bv: B::EMPTY,
        first: 0,
        count: 0,
    };

    /// A node of zero bits, for `static` storage: it goes to `.bss` (no
    /// flash), where an array of [`EMPTY`](Self::EMPTY) would be copied from
    /// flash at start-up. Builders overwrite every node they use.
    ///
    /// ```
    /// use bvhkit::{max_nodes, Aabb, Node};
    /// static mut NODES: [Node<Aabb>; max_nodes(256)] = [Node::ZERO; max_nodes(256)];
    /// ```
    pub const ZERO: Self = Node {
        bv: B::ZERO,
        first: 0,
        count: 0,
    };

    /// Whether this node is a leaf.
    #[inline]
    pub const fn is_leaf(&self) -> bool {
        self.count > 0
    }

    /// The two children of an internal node.
    #[inline]
    pub const fn children(&self) -> Option<(u32, u32)> {
        if self.count == 0 {
            // Wrapping: a corrupt node (from a file) must not panic here;
            // validation refuses it.
            Some((self.first, self.first.wrapping_add(1)))
        } else {
            None
        }
    }
}

/// The largest index in `indices` plus one (0 for none): the shortest
/// primitive slice a tree with these leaves can be queried with.
pub(crate) fn index_bound_of(indices: &[u32]) -> u32 {
    indices.iter().max().map_or(0, |&m| m.saturating_add(1))
}

/// A built hierarchy, borrowing the caller's node and index storage.
///
/// ```
/// use bvhkit::{Aabb, Bvh, Node, TopDown, Triangle};
/// use glam::Vec3;
/// let tris = [
///     Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y),
///     Triangle::new(Vec3::splat(5.0), Vec3::splat(5.0) + Vec3::X, Vec3::splat(5.0) + Vec3::Y),
/// ];
/// let mut nodes = [Node::<Aabb>::EMPTY; 3];
/// let mut indices = [0u32; 2];
/// let bvh: Bvh<Aabb> = TopDown::default().with_max_leaf_size(1).build(&tris, &mut nodes, &mut indices)?;
/// assert_eq!(bvh.node_count(), 3);
/// assert_eq!(bvh.depth(), 1);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Bvh<'a, B> {
    nodes: &'a [Node<B>],
    indices: &'a [u32],
    /// `leaf_bounds[k]` is the bounds of primitive `indices[k]` (leaf
    /// order), or the slice is empty: see [`Bvh::with_leaf_bounds`].
    leaf_bounds: &'a [Aabb],
    depth: u32,
    /// The largest primitive index a leaf names, plus one: the shortest
    /// primitive slice a query can take. Builders number primitives `0..n`
    /// (so it is `n`); a [`DynamicTree`](crate::builders::DynamicTree) after
    /// removals names the caller's ids, which can leave gaps.
    bound: u32,
    /// What the builder reported (all zero for storage opened otherwise).
    report: BuildReport,
}

/// How much of its storage a tree uses, and its depth: what it takes to open
/// the same storage again (after a [refit](Bvh::refit), say) without
/// checking it or saving numbers by hand. A plain `Copy` value, so it
/// outlives the tree's borrow of the arrays.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Shape {
    /// Nodes in use, from the start of the node array.
    pub nodes: usize,
    /// Entries of the index array in use.
    pub indices: usize,
    /// Depth of the deepest leaf.
    pub depth: usize,
}

impl<'a, B: BoundingVolume> Bvh<'a, B> {
    /// This tree's [`Shape`]: keep it to reopen the storage later.
    #[inline]
    pub fn shape(&self) -> Shape {
        Shape {
            nodes: self.nodes.len(),
            indices: self.indices.len(),
            depth: self.depth as usize,
        }
    }

    /// Assembles a tree from storage without checks; builders use this.
    pub(crate) fn from_built(nodes: &'a [Node<B>], indices: &'a [u32], depth: u32) -> Self {
        Bvh {
            nodes,
            indices,
            leaf_bounds: &[],
            depth,
            bound: indices.len() as u32,
            report: BuildReport::default(),
        }
    }

    /// [`from_built`](Self::from_built) for leaves naming ids below `bound`.
    #[cfg(feature = "insertion")]
    pub(crate) fn from_built_ids(
        nodes: &'a [Node<B>],
        indices: &'a [u32],
        depth: u32,
        bound: u32,
    ) -> Self {
        Bvh {
            bound,
            ..Bvh::from_built(nodes, indices, depth)
        }
    }

    /// Views storage that a builder of this crate filled (for example kept in a
    /// `Vec` by the std side), without re-checking it. `depth` is the depth the
    /// builder reported. For storage from anywhere else (a file, user code) use
    /// [`from_parts`](Self::from_parts), which validates: a query over
    /// inconsistent raw parts may index out of bounds. Reads the indices
    /// once for the largest (a tree written by a
    /// [`DynamicTree`](crate::builders::DynamicTree) names ids with gaps).
    pub fn from_raw_parts(nodes: &'a [Node<B>], indices: &'a [u32], depth: usize) -> Self {
        Bvh {
            nodes,
            indices,
            leaf_bounds: &[],
            depth: depth.min(u32::MAX as usize) as u32,
            bound: index_bound_of(indices),
            report: BuildReport::default(),
        }
    }

    /// [`from_raw_parts`](Self::from_raw_parts) with the primitives' bounds
    /// in leaf order, as [`with_leaf_bounds`](Self::with_leaf_bounds) wrote
    /// them (kept elsewhere, for instance in a `Vec` by the std side). Their
    /// values are trusted like the rest of the raw parts; only their length is
    /// checked (one per index entry, or none).
    ///
    /// ```
    /// use bvhkit::{Aabb, Bvh, Node, TopDown, Triangle};
    /// use glam::Vec3;
    /// let tris: Vec<Triangle> = (0..8).map(|i| {
    ///     let o = Vec3::new(i as f32, 0.0, 0.0);
    ///     Triangle::new(o, o + Vec3::X, o + Vec3::Y)
    /// }).collect();
    /// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(8)];
    /// let mut idx = vec![0; 8];
    /// let mut kept = vec![Aabb::EMPTY; 8];
    /// let (used, depth) = {
    ///     let t = TopDown::default().build(&tris, &mut nodes, &mut idx)?;
    ///     t.with_leaf_bounds(&tris, &mut kept)?;
    ///     (t.node_count(), t.depth())
    /// };
    /// nodes.truncate(used);
    /// // Later, from storage kept elsewhere:
    /// let tree = Bvh::from_raw_parts_with_bounds(&nodes, &idx, &kept, depth)?;
    /// assert_eq!(tree.leaf_bounds().map(|b| b.len()), Some(8));
    /// // A bounds slice of the wrong length is refused.
    /// assert!(Bvh::from_raw_parts_with_bounds(&nodes, &idx, &kept[..3], depth).is_err());
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn from_raw_parts_with_bounds(
        nodes: &'a [Node<B>],
        indices: &'a [u32],
        leaf_bounds: &'a [Aabb],
        depth: usize,
    ) -> Result<Self, Error> {
        if !leaf_bounds.is_empty() && leaf_bounds.len() != indices.len() {
            return Err(Error::PrimitiveCountMismatch {
                tree: indices.len(),
                given: leaf_bounds.len(),
            });
        }
        Ok(Bvh {
            leaf_bounds,
            ..Bvh::from_raw_parts(nodes, indices, depth)
        })
    }

    /// The view of parts an owner keeps from a build: no pass over the
    /// indices for their bound (`bound` is the one the build's view had),
    /// so that a view costs nothing per query. The caller guarantees
    /// everything [`from_raw_parts_with_bounds`](Self::from_raw_parts_with_bounds)
    /// trusts, and `leaf_bounds` empty or one per index.
    pub(crate) fn from_kept(
        nodes: &'a [Node<B>],
        indices: &'a [u32],
        leaf_bounds: &'a [Aabb],
        depth: usize,
        bound: usize,
        report: BuildReport,
    ) -> Self {
        Bvh {
            nodes,
            indices,
            leaf_bounds,
            depth: depth.min(u32::MAX as usize) as u32,
            bound: bound.min(u32::MAX as usize) as u32,
            report,
        }
    }

    /// Re-opens a tree from storage kept elsewhere (a file, a previous build),
    /// checking every invariant against `prims` first. `seen` is scratch of at
    /// least [`Bvh::seen_words`] entries.
    pub fn from_parts<P: Primitive>(
        nodes: &'a [Node<B>],
        indices: &'a [u32],
        prims: &[P],
        seen: &mut [u32],
    ) -> Result<Self, Error> {
        let depth = validate::structure(nodes, indices, prims.len(), seen)?;
        let bvh = Bvh {
            nodes,
            indices,
            leaf_bounds: &[],
            depth,
            bound: index_bound_of(indices),
            report: BuildReport::default(),
        };
        bvh.validate(prims, seen)?;
        Ok(bvh)
    }

    /// What the builder did besides following its configuration: its
    /// fallbacks, the depth limit's interventions and any leaf over the
    /// stated size (see [`BuildReport`]). All zero for a tree opened from
    /// storage, unless [`with_build_report`](Self::with_build_report) put
    /// the builder's report back.
    pub fn build_report(&self) -> BuildReport {
        self.report
    }

    /// The same tree carrying `report`: for storage kept elsewhere (as
    /// `bvhkit-std`'s owned tree does) to keep what its builder reported.
    pub fn with_build_report(self, report: BuildReport) -> Self {
        Bvh { report, ..self }
    }

    /// The nodes; the root is `nodes()[0]`.
    #[inline]
    pub fn nodes(&self) -> &'a [Node<B>] {
        self.nodes
    }

    /// The primitive index array that leaves point into.
    #[inline]
    pub fn indices(&self) -> &'a [u32] {
        self.indices
    }

    /// The primitives' bounds in leaf order (entry `k` bounds primitive
    /// `indices()[k]`), if attached by [`with_leaf_bounds`](Self::with_leaf_bounds).
    #[inline]
    pub fn leaf_bounds(&self) -> Option<&'a [Aabb]> {
        (!self.leaf_bounds.is_empty()).then_some(self.leaf_bounds)
    }

    /// Writes every primitive's bounds into `out` in leaf order and keeps
    /// them with the tree. Pair queries then test primitive pairs on these
    /// boxes, read in the order the traversal meets the leaves, instead of
    /// fetching each primitive from wherever the caller's slice holds it:
    /// on large meshes those scattered reads are most of a pair query's time.
    /// A [`Bounds`](crate::Bounds) answer in the same frame never touches
    /// the primitives at all. Costs 24 bytes per primitive (`out` needs one
    /// entry per index entry: [`primitive_count`](Self::primitive_count)).
    ///
    /// ```
    /// use bvhkit::{Aabb, Node, Pairs, TopDown, Triangle};
    /// use glam::Vec3;
    /// let tris: Vec<Triangle> = (0..64).map(|i| {
    ///     let o = Vec3::new((i % 8) as f32, (i / 8) as f32, 0.0);
    ///     Triangle::new(o, o + Vec3::new(1.5, 0.0, 0.0), o + Vec3::new(0.0, 1.5, 0.0))
    /// }).collect();
    /// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(tris.len())];
    /// let mut idx = vec![0; tris.len()];
    /// let mut bounds = vec![Aabb::EMPTY; tris.len()];
    /// let plain = TopDown::default().build(&tris, &mut nodes, &mut idx)?;
    /// let before = Pairs::new(&plain, &tris, &plain, &tris).count()?;
    /// let tree = plain.with_leaf_bounds(&tris, &mut bounds)?;
    /// assert_eq!(tree.leaf_bounds().map(|b| b.len()), Some(64));
    /// assert_eq!(Pairs::new(&tree, &tris, &tree, &tris).count()?, before);
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn with_leaf_bounds<P: Primitive>(
        self,
        prims: &[P],
        out: &'a mut [Aabb],
    ) -> Result<Bvh<'a, B>, Error> {
        let n = self.indices.len();
        if out.len() < n {
            return Err(Error::IndexCapacity {
                needed: n,
                available: out.len(),
            });
        }
        if prims.len() < self.index_bound() {
            return Err(Error::PrimitiveCountMismatch {
                tree: self.index_bound(),
                given: prims.len(),
            });
        }
        let out = &mut out[..n];
        for (slot, &p) in out.iter_mut().zip(self.indices) {
            // In range: every index is below `index_bound`, checked above.
            *slot = prims.get(p as usize).map_or(Aabb::EMPTY, Primitive::bounds);
        }
        Ok(Bvh {
            leaf_bounds: out,
            ..self
        })
    }

    /// The root node; `None` for the empty tree (built from no primitives).
    #[inline]
    pub fn root(&self) -> Option<&'a Node<B>> {
        self.nodes.first()
    }

    /// Whether the tree holds nothing (built from no primitives): every
    /// query on it answers with nothing.
    ///
    /// ```
    /// use bvhkit::{Aabb, Bvh, Query, TopDown, Triangle};
    /// use glam::Vec3;
    /// let none: [Triangle; 0] = [];
    /// // No primitives need no storage, and build the empty tree.
    /// let tree: Bvh<Aabb> = TopDown::default().build(&none, &mut [], &mut [])?;
    /// assert!(tree.is_empty() && tree.root().is_none());
    /// let everywhere = Aabb::new(Vec3::splat(-1e6), Vec3::splat(1e6));
    /// assert_eq!(tree.overlapping(&none, &everywhere, |_| ())?, 0);
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Number of nodes in use.
    #[inline]
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Number of primitives the tree was built over.
    #[inline]
    pub fn primitive_count(&self) -> usize {
        self.indices.len()
    }

    /// The shortest primitive slice a query takes: the largest index a leaf
    /// names, plus one. It equals [`primitive_count`](Self::primitive_count)
    /// for every builder, whose leaves name `0..n`; a
    /// [`DynamicTree`](crate::builders::DynamicTree) after removals writes a
    /// tree whose leaves name the caller's ids, and its queries take the
    /// caller's whole slice, indexed by id.
    #[inline]
    pub fn index_bound(&self) -> usize {
        self.bound as usize
    }

    /// Depth of the deepest leaf (the root alone has depth 0).
    #[inline]
    pub fn depth(&self) -> usize {
        self.depth as usize
    }

    /// The primitive indices stored in a leaf (empty for an internal node).
    #[inline]
    pub fn leaf_primitives(&self, node: &Node<B>) -> &'a [u32] {
        if node.is_leaf() {
            &self.indices[node.first as usize..(node.first + node.count) as usize]
        } else {
            &[]
        }
    }

    /// Bytes of node, index and leaf-bounds storage in use.
    pub fn bytes(&self) -> usize {
        core::mem::size_of_val(self.nodes)
            + core::mem::size_of_val(self.indices)
            + core::mem::size_of_val(self.leaf_bounds)
    }

    /// Scratch words [`validate`](Self::validate) needs: one bit per node or primitive.
    pub const fn seen_words(nodes: usize, primitives: usize) -> usize {
        let n = if nodes > primitives {
            nodes
        } else {
            primitives
        };
        n.div_ceil(32)
    }

    /// Checks every invariant: the structure is a tree reaching each node once;
    /// each primitive is in exactly one leaf; each node's volume contains its
    /// children's volumes and the bounds of its primitives; attached leaf
    /// bounds equal the primitives' bounds.
    pub fn validate<P: Primitive>(&self, prims: &[P], seen: &mut [u32]) -> Result<(), Error> {
        validate::structure(self.nodes, self.indices, prims.len(), seen)?;
        validate::containment(self, prims)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Pairs, TopDown, Triangle};
    use glam::Vec3;

    fn tris() -> [Triangle; 12] {
        core::array::from_fn(|i| {
            let o = Vec3::new(
                (i % 4) as f32 * 0.8,
                (i / 4) as f32 * 0.8,
                (i % 3) as f32 * 0.1,
            );
            Triangle::new(o, o + Vec3::X, o + Vec3::Y)
        })
    }

    #[test]
    fn leaf_bounds_follow_the_index_array() {
        let t = tris();
        let mut nodes = [Node::<Aabb>::EMPTY; 23];
        let mut idx = [0u32; 12];
        let mut out = [Aabb::EMPTY; 12];
        let tree = TopDown::default()
            .with_max_leaf_size(3)
            .build(&t, &mut nodes, &mut idx)
            .unwrap();
        let plain = Pairs::new(&tree, &t, &tree, &t).count().unwrap();
        let kept = tree.with_leaf_bounds(&t, &mut out).unwrap();
        let bounds = kept.leaf_bounds().unwrap();
        for (b, &p) in bounds.iter().zip(kept.indices()) {
            assert_eq!(*b, t[p as usize].bounds());
        }
        assert_eq!(kept.bytes(), tree.bytes() + 12 * 24);
        assert_eq!(Pairs::new(&kept, &t, &kept, &t).count().unwrap(), plain);
        let mut seen = [0u32; 1];
        assert_eq!(kept.validate(&t, &mut seen), Ok(()));
    }

    #[test]
    fn leaf_bounds_refuse_short_storage_and_wrong_values() {
        let t = tris();
        let mut nodes = [Node::<Aabb>::EMPTY; 23];
        let mut idx = [0u32; 12];
        let tree = TopDown::default().build(&t, &mut nodes, &mut idx).unwrap();
        let mut short = [Aabb::EMPTY; 11];
        assert_eq!(
            tree.with_leaf_bounds(&t, &mut short).err(),
            Some(Error::IndexCapacity {
                needed: 12,
                available: 11
            })
        );
        let mut out = [Aabb::EMPTY; 12];
        assert_eq!(
            tree.with_leaf_bounds(&t[..5], &mut out).err(),
            Some(Error::PrimitiveCountMismatch { tree: 12, given: 5 })
        );
        // Raw parts: the length is checked, the values by validation.
        let mut wrong = [Aabb::EMPTY; 12];
        let kept = tree.with_leaf_bounds(&t, &mut out).unwrap();
        wrong.copy_from_slice(kept.leaf_bounds().unwrap());
        assert!(
            Bvh::from_raw_parts_with_bounds(tree.nodes(), tree.indices(), &wrong[..3], 3).is_err()
        );
        wrong[5].max.x += 1.0;
        let forged =
            Bvh::from_raw_parts_with_bounds(tree.nodes(), tree.indices(), &wrong, tree.depth())
                .unwrap();
        let mut seen = [0u32; 1];
        assert_eq!(
            forged.validate(&t, &mut seen),
            Err(Error::InvalidTree(
                "leaf bounds differ from the primitives' bounds"
            ))
        );
    }

    /// Two leaves naming the same index entries, so that others are in no
    /// leaf: the slot count still adds up and every primitive is in the
    /// index array once, but a query would never reach the primitives left
    /// out. Refused.
    #[test]
    fn leaves_sharing_index_entries_are_refused() {
        let t = [
            Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y),
            Triangle::new(Vec3::ONE, Vec3::ONE + Vec3::X, Vec3::ONE + Vec3::Y),
        ];
        let all = Aabb::new(Vec3::ZERO, Vec3::splat(2.0));
        let leaf = |first| Node {
            bv: all,
            first,
            count: 1,
        };
        let nodes = [
            Node {
                bv: all,
                first: 1,
                count: 0,
            },
            leaf(0),
            leaf(0),
        ];
        let mut seen = [0u32; 1];
        assert_eq!(
            Bvh::from_parts(&nodes, &[0, 1], &t, &mut seen).err(),
            Some(Error::InvalidTree("two leaves share an index entry"))
        );
        // With the second leaf on entry 1 it is a valid tree.
        let nodes = [nodes[0], leaf(0), leaf(1)];
        assert!(Bvh::from_parts(&nodes, &[0, 1], &t, &mut seen).is_ok());
    }
}
