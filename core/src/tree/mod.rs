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

pub(crate) mod hierarchy;
mod validate;

pub use hierarchy::{Boxes4, Content, Hierarchy, Kids, MAX_CHILDREN};

use crate::bv::BoundingVolume;
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
/// // Size static storage at compile time:
/// static mut NODES: [bvhkit::Node<bvhkit::Aabb>; bvhkit::max_nodes(64)] =
///     [bvhkit::Node::EMPTY; bvhkit::max_nodes(64)];
/// ```
pub const fn max_nodes(n: usize) -> usize {
    if n == 0 {
        0
    } else {
        2 * n - 1
    }
}

/// One node: a bounding volume and either two children or a run of primitives.
///
/// For an internal node (`count == 0`) the children are `first` and `first + 1`.
/// For a leaf (`count > 0`) the primitives are `indices[first .. first + count]`.
/// With an [`Aabb`](crate::Aabb) the node is 32 bytes.
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
    depth: u32,
    /// The largest primitive index a leaf names, plus one: the shortest
    /// primitive slice a query can take. Builders number primitives `0..n`
    /// (so it is `n`); a [`DynamicTree`](crate::builders::DynamicTree) after
    /// removals names the caller's ids, which can leave gaps.
    bound: u32,
}

impl<'a, B: BoundingVolume> Bvh<'a, B> {
    /// Assembles a tree from storage without checks; builders use this.
    pub(crate) fn from_built(nodes: &'a [Node<B>], indices: &'a [u32], depth: u32) -> Self {
        Bvh {
            nodes,
            indices,
            depth,
            bound: indices.len() as u32,
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
            depth: depth.min(u32::MAX as usize) as u32,
            bound: index_bound_of(indices),
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
            depth,
            bound: index_bound_of(indices),
        };
        bvh.validate(prims, seen)?;
        Ok(bvh)
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

    /// Bytes of node and index storage in use.
    pub fn bytes(&self) -> usize {
        core::mem::size_of_val(self.nodes) + core::mem::size_of_val(self.indices)
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
    /// children's volumes and the bounds of its primitives.
    pub fn validate<P: Primitive>(&self, prims: &[P], seen: &mut [u32]) -> Result<(), Error> {
        validate::structure(self.nodes, self.indices, prims.len(), seen)?;
        validate::containment(self, prims)
    }
}
