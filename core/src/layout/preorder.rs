//! Preorder (depth-first) order: the left child follows its parent.

use super::{check_capacity, Leaves};
use crate::bv::{Aabb, BoundingVolume};
use crate::tree::{Bvh, Content, Hierarchy, Kids, MAX_DEPTH};
use crate::Error;

/// The integer type of a [`Preorder`] link: `u32`, or `u16` for trees of at
/// most 65 535 nodes and primitives (half the link bytes; what the lectures
/// call offsets instead of pointers).
pub trait Offset: Copy + core::fmt::Debug + PartialEq + 'static {
    /// Largest value the type holds.
    const MAX: usize;
    /// Zero.
    const ZERO: Self;
    /// The value, or `None` when it does not fit.
    fn new(v: usize) -> Option<Self>;
    /// The value as an index.
    fn get(self) -> usize;
}

impl Offset for u32 {
    const MAX: usize = u32::MAX as usize;
    const ZERO: Self = 0;
    #[inline(always)]
    fn new(v: usize) -> Option<Self> {
        u32::try_from(v).ok()
    }
    #[inline(always)]
    fn get(self) -> usize {
        self as usize
    }
}

impl Offset for u16 {
    const MAX: usize = u16::MAX as usize;
    const ZERO: Self = 0;
    #[inline(always)]
    fn new(v: usize) -> Option<Self> {
        u16::try_from(v).ok()
    }
    #[inline(always)]
    fn get(self) -> usize {
        self as usize
    }
}

/// One node in preorder: a volume, one link and a count.
///
/// * Internal node (`count == 0`, the "has a left child" bit): the left child
///   is the next record; `link` is the index of the right child.
/// * Leaf (`count > 0`): `link` is its first entry in the index array.
///
/// With an [`Aabb`](crate::Aabb): 32 bytes with `u32` links, 28 with `u16`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct PreNode<B, O> {
    /// Bounds of the subtree.
    pub bv: B,
    link: O,
    count: O,
}

impl<B: BoundingVolume, O: Offset> PreNode<B, O> {
    /// A blank record, for initialising storage.
    pub const EMPTY: Self = PreNode {
        bv: B::EMPTY,
        link: O::ZERO,
        count: O::ZERO,
    };

    /// Whether the next record is this node's left child.
    pub fn has_left_child(&self) -> bool {
        self.count == O::ZERO
    }

    /// Index of the right child (internal nodes only).
    pub fn right(&self) -> Option<usize> {
        self.has_left_child().then(|| self.link.get())
    }
}

/// A tree in preorder, borrowing its storage. Converting needs exactly
/// `bvh.node_count()` records.
///
/// ```text
///        0              records:  0   1   2   3   4   5   6
///      /   \                      A   B   D   E   C   F   G
///     1     4           right:    4   3   -   -   6   -   -
///    / \   / \          left = next record whenever count == 0
///   2   3 5   6
/// ```
///
/// ```
/// use bvhkit::layout::{PreNode, Preorder};
/// use bvhkit::{Aabb, Error, Hierarchy, Node, TopDown};
/// use glam::Vec3;
/// let pts: Vec<Vec3> = (0..4).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
/// let mut nodes = vec![Node::<Aabb>::EMPTY; 7];
/// let mut idx = vec![0; 4];
/// let bvh = TopDown::median().with_max_leaf_size(1).build(&pts, &mut nodes, &mut idx)?;
/// let mut recs = vec![PreNode::<Aabb, u16>::EMPTY; bvh.node_count()];
/// let pre = Preorder::from_bvh(&bvh, &mut recs)?;
/// // The root's left child is record 1, its right child record 4.
/// assert_eq!(pre.records()[0].right(), Some(4));
/// assert_eq!(pre.records()[1].right(), Some(3));
/// assert_eq!(core::mem::size_of::<PreNode<Aabb, u16>>(), 28);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Preorder<'a, B, O> {
    records: &'a [PreNode<B, O>],
    leaves: Leaves<'a>,
    depth: u32,
}

impl<'a, B: BoundingVolume, O: Offset> Preorder<'a, B, O> {
    /// Writes `bvh` in preorder into `out` (at least `bvh.node_count()`
    /// records). A node index or leaf start beyond the link type is an
    /// [`Error::FieldOverflow`], never a wrap-around.
    pub fn from_bvh(bvh: &Bvh<'a, B>, out: &'a mut [PreNode<B, O>]) -> Result<Self, Error> {
        super::dense(bvh)?;
        let count = bvh.node_count();
        check_capacity(count, out.len())?;
        crate::tree::hierarchy::check_query(bvh, bvh.primitive_count())?;
        let fit = |v: usize, field: &'static str| {
            O::new(v).ok_or(Error::FieldOverflow {
                field,
                value: v,
                max: O::MAX,
            })
        };
        // Fail before writing anything: the largest link is the last record
        // or the last leaf start.
        fit(count.saturating_sub(1), "node index of a preorder link")?;
        fit(
            bvh.primitive_count().saturating_sub(1),
            "leaf start of a preorder link",
        )?;
        let nodes = bvh.nodes();
        // (canonical node, record whose right link points here, or MAX).
        let mut stack = [(0u32, usize::MAX); MAX_DEPTH + 2];
        let mut top = usize::from(count > 0); // the empty tree has no root
        let mut next = 0;
        while top > 0 {
            top -= 1;
            let (n, parent) = stack[top];
            if parent != usize::MAX {
                out[parent].link = fit(next, "node index of a preorder link")?;
            }
            let node = &nodes[n as usize];
            out[next] = match node.children() {
                Some((l, r)) => {
                    // Right waits with the record to patch; left comes next.
                    stack[top] = (r, next);
                    stack[top + 1] = (l, usize::MAX);
                    top += 2;
                    PreNode {
                        bv: node.bv,
                        link: O::ZERO,
                        count: O::ZERO,
                    }
                }
                None => PreNode {
                    bv: node.bv,
                    link: fit(node.first as usize, "leaf start of a preorder link")?,
                    count: fit(node.count as usize, "leaf size of a preorder link")?,
                },
            };
            next += 1;
        }
        let records: &'a [PreNode<B, O>] = &out[..next];
        Ok(Preorder {
            records,
            leaves: Leaves::of(bvh),
            depth: bvh.depth() as u32,
        })
    }

    /// The records in preorder.
    pub fn records(&self) -> &'a [PreNode<B, O>] {
        self.records
    }
}

impl<B: BoundingVolume, O: Offset> Hierarchy for Preorder<'_, B, O> {
    type Bv = B;
    const ARITY: usize = 2;

    #[inline(always)]
    fn root(&self) -> u32 {
        0
    }

    #[inline(always)]
    fn bv(&self, node: u32) -> B {
        self.records[node as usize].bv
    }

    #[inline(always)]
    fn content(&self, node: u32) -> Content<'_> {
        let r = &self.records[node as usize];
        if r.count == O::ZERO {
            Content::Inner(Kids::two(node + 1, r.link.get() as u32))
        } else {
            let first = r.link.get();
            Content::Leaf(self.leaves.ids(first, r.count.get()))
        }
    }

    #[inline(always)]
    fn leaf_bounds(&self, node: u32) -> Option<&[Aabb]> {
        self.leaves.bounds_of(self.content(node))
    }

    fn depth(&self) -> usize {
        self.depth as usize
    }

    fn primitive_count(&self) -> usize {
        self.leaves.len()
    }

    fn node_count(&self) -> usize {
        self.records.len()
    }

    fn bytes(&self) -> usize {
        core::mem::size_of_val(self.records) + self.leaves.bytes()
    }
}
