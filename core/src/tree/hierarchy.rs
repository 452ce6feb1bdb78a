//! The one view every query runs on.
//!
//! Lecture: *efficient tree representation*. A tree can be stored in many ways
//! (the canonical [`Bvh`], the [layouts](crate::layout)), but a query only ever
//! asks three things of a node: its volume, whether it is a leaf (and which
//! primitives it holds) or which children it has. [`Hierarchy`] is exactly
//! that, so each traversal is written once and runs on every representation.
//!
//! A node is named by a `u32` the representation chooses: an array index for
//! the binary layouts, a (record, slot) pair packed into the `u32` for the
//! layouts that keep a child's volume inside its parent. One id type for all
//! keeps the traversal stacks and the breadth-first queue plain `u32` arrays.

use super::{Bvh, MAX_DEPTH};
use crate::bv::{Aabb, BoundingVolume};
use crate::Error;
use glam::{BVec4A, Vec3, Vec4};

/// Most children a node of any representation has (the 4-wide layouts).
pub const MAX_CHILDREN: usize = 4;

/// The children of an internal node: between 2 and [`MAX_CHILDREN`] ids.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Kids {
    ids: [u32; MAX_CHILDREN],
    len: u8,
}

impl Kids {
    /// Two children (every binary layout).
    #[inline(always)]
    pub fn two(l: u32, r: u32) -> Self {
        Kids {
            ids: [l, r, r, r],
            len: 2,
        }
    }

    /// The first `len` of `ids` (`len` is clamped to [`MAX_CHILDREN`]).
    #[inline(always)]
    pub fn new(ids: [u32; MAX_CHILDREN], len: usize) -> Self {
        Kids {
            ids,
            len: len.min(MAX_CHILDREN) as u8,
        }
    }

    /// The children, in the representation's order.
    #[inline(always)]
    pub fn as_slice(&self) -> &[u32] {
        &self.ids[..self.len as usize]
    }

    /// The children of a node of a tree of this arity: for binary trees a
    /// slice of constant length 2, which lets the compiler unroll the loops
    /// over it (measurably faster on the pair query's hot path).
    #[inline(always)]
    pub fn of_arity(&self, arity: usize) -> &[u32] {
        if arity == 2 {
            &self.ids[..2]
        } else {
            self.as_slice()
        }
    }
}

/// The boxes of up to four sibling nodes side by side (a structure of
/// arrays: the four `min.x` together, then the four `min.y`, ...), as a wide
/// layout stores them. Lets a query test one ray or box against four boxes
/// with 4-lane arithmetic.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct Boxes4 {
    /// Lower corners: `min[axis][child]`.
    pub min: [[f32; MAX_CHILDREN]; 3],
    /// Upper corners: `max[axis][child]`.
    pub max: [[f32; MAX_CHILDREN]; 3],
}

impl Boxes4 {
    /// Four empty boxes (`min = +inf`, `max = -inf`).
    pub const EMPTY: Boxes4 = Boxes4 {
        min: [[f32::INFINITY; MAX_CHILDREN]; 3],
        max: [[f32::NEG_INFINITY; MAX_CHILDREN]; 3],
    };

    /// Stores `b` as box `k` (`k < 4`).
    #[inline(always)]
    pub fn set(&mut self, k: usize, b: &Aabb) {
        for axis in 0..3 {
            self.min[axis][k] = b.min[axis];
            self.max[axis][k] = b.max[axis];
        }
    }

    /// Box `k` (`k < 4`).
    #[inline]
    pub fn get(&self, k: usize) -> Aabb {
        Aabb::new(
            Vec3::new(self.min[0][k], self.min[1][k], self.min[2][k]),
            Vec3::new(self.max[0][k], self.max[1][k], self.max[2][k]),
        )
    }

    /// Which of the four boxes overlap `other`: bit `k` for box `k`. The same
    /// closed-interval test as [`Aabb::overlaps`] (touching counts, NaN never
    /// overlaps), in six 4-lane comparisons instead of four separate tests.
    ///
    /// ```
    /// use bvhkit::{Aabb, Boxes4};
    /// use glam::Vec3;
    /// let mut four = Boxes4::EMPTY;
    /// four.set(0, &Aabb::new(Vec3::ZERO, Vec3::ONE));
    /// four.set(2, &Aabb::new(Vec3::splat(5.0), Vec3::splat(6.0)));
    /// let probe = Aabb::new(Vec3::splat(1.0), Vec3::splat(2.0)); // touches box 0
    /// assert_eq!(four.overlapping(&probe), 0b0001);
    /// ```
    #[inline(always)]
    pub fn overlapping(&self, other: &Aabb) -> u32 {
        let mut hit = BVec4A::TRUE;
        for axis in 0..3 {
            let lo = Vec4::from_array(self.min[axis]);
            let hi = Vec4::from_array(self.max[axis]);
            hit &= lo.cmple(Vec4::splat(other.max[axis]));
            hit &= hi.cmpge(Vec4::splat(other.min[axis]));
        }
        hit.bitmask()
    }
}

/// What a node holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Content<'a> {
    /// A leaf: entries of the primitive index array.
    Leaf(&'a [u32]),
    /// An internal node and its children.
    Inner(Kids),
}

/// A bounding volume hierarchy as queries see it: volumes, leaves, children.
///
/// Implemented by the canonical [`Bvh`] and by every [layout](crate::layout).
/// The queries ([`Query::search`](crate::Query::search),
/// [`Query::cast_ray`](crate::Query::cast_ray),
/// [`Query::nearest`](crate::Query::nearest), [`Pairs`](crate::Pairs)) are written once
/// against this trait.
///
/// ```
/// use bvhkit::{Aabb, Content, Hierarchy, Node, TopDown, Triangle};
/// use glam::Vec3;
/// let tris: Vec<Triangle> = (0..4).map(|i| {
///     let o = Vec3::new(i as f32 * 3.0, 0.0, 0.0);
///     Triangle::new(o, o + Vec3::X, o + Vec3::Y)
/// }).collect();
/// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(4)];
/// let mut idx = vec![0; 4];
/// let bvh = TopDown::default().with_max_leaf_size(1).build(&tris, &mut nodes, &mut idx)?;
/// // Count the leaves by walking the view.
/// fn leaves<H: Hierarchy>(h: &H, n: u32) -> usize {
///     match h.content(n) {
///         Content::Leaf(_) => 1,
///         Content::Inner(kids) => kids.as_slice().iter().map(|&c| leaves(h, c)).sum(),
///     }
/// }
/// assert_eq!(leaves(&bvh, Hierarchy::root(&bvh)), 4);
/// # Ok::<(), bvhkit::Error>(())
/// ```
pub trait Hierarchy {
    /// The volume type of the nodes as queries see them.
    type Bv: BoundingVolume;
    /// Most children of one node (2 for binary layouts).
    const ARITY: usize;

    /// The root. Meaningless for the empty tree: see [`is_empty`](Self::is_empty).
    fn root(&self) -> u32;
    /// The volume of a node (decoded, for compressed layouts).
    fn bv(&self, node: u32) -> Self::Bv;
    /// Leaf primitives or children of a node.
    fn content(&self, node: u32) -> Content<'_>;
    /// Depth of the deepest leaf (the root alone has depth 0).
    fn depth(&self) -> usize;
    /// Number of primitives the tree was built over.
    fn primitive_count(&self) -> usize;
    /// The largest primitive index a leaf names, plus one: the shortest
    /// slice a query takes (see [`Bvh::index_bound`]). The layouts hold
    /// dense trees only, so the default is the count.
    fn index_bound(&self) -> usize {
        self.primitive_count()
    }
    /// Whether the leaves name exactly the ids `0..primitive_count()`, as
    /// every builder's tree does. A query on such a tree then takes a
    /// primitive slice of exactly that length, which catches a slice of the
    /// wrong mesh. A tree whose ids the caller chose (a
    /// [`DynamicTree`](crate::builders::DynamicTree), a snapshot of one after
    /// removals) says `false`: the slice need only hold every id named.
    fn dense_ids(&self) -> bool {
        self.index_bound() == self.primitive_count()
    }
    /// Number of logical nodes (leaves and internal nodes).
    fn node_count(&self) -> usize;
    /// Bytes of storage in use: node records and the primitive index array.
    fn bytes(&self) -> usize;

    /// Whether the tree holds no nodes (built from no primitives). Queries
    /// check it first and answer with nothing.
    #[inline(always)]
    fn is_empty(&self) -> bool {
        self.node_count() == 0
    }

    /// Whether a node is a leaf.
    #[inline(always)]
    fn is_leaf(&self, node: u32) -> bool {
        matches!(self.content(node), Content::Leaf(_))
    }

    /// The bounds of a leaf's primitives, side by side with the ids of its
    /// [`Content::Leaf`] (entry `k` bounds id `k`), if the representation
    /// keeps them ([`Bvh::with_leaf_bounds`]). They must equal each
    /// primitive's [`bounds`](crate::Primitive::bounds). The default, `None`,
    /// makes queries read the primitives.
    #[inline(always)]
    fn leaf_bounds(&self, node: u32) -> Option<&[Aabb]> {
        let _ = node;
        None
    }

    /// The children's boxes side by side, if the layout stores them so. They
    /// must equal `self.bv(c).aabb()` for each child `c` (slots past the
    /// children are ignored). The default, `None`, makes queries fetch them
    /// one by one.
    #[inline(always)]
    fn children_boxes(&self, kids: &Kids) -> Option<&Boxes4> {
        let _ = kids;
        None
    }

    /// Which of `kids` (the children of one node) have a volume overlapping
    /// `other`: bit `k` for `kids.as_slice()[k]`. The default tests them one
    /// by one; a layout that stores the children side by side tests them at
    /// once. Must equal the one-by-one answer.
    #[inline(always)]
    fn children_overlapping(&self, kids: &Kids, other: &Self::Bv) -> u32 {
        let mut mask = 0;
        for (k, &c) in kids.of_arity(Self::ARITY).iter().enumerate() {
            mask |= (self.bv(c).overlaps(other) as u32) << k;
        }
        mask
    }
}

/// Checks that a query can run on `h`: the primitive slice matches and the
/// tree fits the fixed traversal stacks.
pub(crate) fn check_query<H: Hierarchy + ?Sized>(h: &H, given: usize) -> Result<(), Error> {
    // Leaves numbered 0..n (every builder): the slice must be the one the
    // tree was built over, as long. Leaves naming ids with gaps (a dynamic
    // tree after removals): the slice must hold every id named.
    let (count, bound) = (h.primitive_count(), h.index_bound());
    let fits = if h.dense_ids() {
        given == count
    } else {
        given >= bound
    };
    if !fits {
        return Err(Error::PrimitiveCountMismatch { tree: bound, given });
    }
    if h.depth() > MAX_DEPTH {
        return Err(Error::StackOverflow {
            depth: h.depth(),
            capacity: MAX_DEPTH,
        });
    }
    Ok(())
}

/// Entries of a depth-first stack that serves every representation: at most
/// `ARITY - 1` siblings wait per level.
pub(crate) const DFS_STACK: usize = (MAX_CHILDREN - 1) * MAX_DEPTH + 1;
/// The depth-first stack of a binary tree: one waiting node per level.
pub(crate) const BINARY_DFS_STACK: usize = MAX_DEPTH + 1;

impl<B: BoundingVolume> Hierarchy for Bvh<'_, B> {
    type Bv = B;
    const ARITY: usize = 2;

    #[inline(always)]
    fn root(&self) -> u32 {
        0
    }

    #[inline(always)]
    fn bv(&self, node: u32) -> B {
        self.nodes()[node as usize].bv
    }

    #[inline(always)]
    fn content(&self, node: u32) -> Content<'_> {
        let n = &self.nodes()[node as usize];
        match n.children() {
            Some((l, r)) => Content::Inner(Kids::two(l, r)),
            None => Content::Leaf(self.leaf_primitives(n)),
        }
    }

    #[inline(always)]
    fn is_leaf(&self, node: u32) -> bool {
        self.nodes()[node as usize].is_leaf()
    }

    #[inline(always)]
    fn leaf_bounds(&self, node: u32) -> Option<&[Aabb]> {
        let all = Bvh::leaf_bounds(self)?;
        let n = &self.nodes()[node as usize];
        all.get(n.first as usize..n.first as usize + n.count as usize)
    }

    fn depth(&self) -> usize {
        Bvh::depth(self)
    }

    fn primitive_count(&self) -> usize {
        Bvh::primitive_count(self)
    }

    fn index_bound(&self) -> usize {
        Bvh::index_bound(self)
    }

    fn node_count(&self) -> usize {
        Bvh::node_count(self)
    }

    fn bytes(&self) -> usize {
        Bvh::bytes(self)
    }
}
