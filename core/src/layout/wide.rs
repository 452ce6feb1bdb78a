//! The 4-wide layout: four children's boxes side by side.

use super::{fill_wide, wide_walk, Leaves};
use crate::bv::{Aabb, BoundingVolume};
use crate::tree::{Boxes4, Bvh, Content, Hierarchy, Kids, MAX_CHILDREN};
use crate::Error;
use glam::Vec3;

/// Marks a slot no child occupies.
pub(crate) const UNUSED: u32 = u32::MAX;
/// Flag of an internal child; the low bits hold its number of children.
pub(crate) const INNER: u32 = 1 << 31;

/// One 4-wide record: the boxes of up to four children as a structure of
/// arrays (all four `min.x` together, and so on), so a traversal that opens
/// the record has all four boxes in two cache lines. `count[k]` is
/// `2^31 + c` for an internal child with `c` children (then `child[k]` is its
/// record), the primitive count of a leaf child (then `child[k]` is its first
/// index entry), or `u32::MAX` for an unused slot. 128 bytes, aligned to 64.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
pub struct WideNode {
    pub(crate) boxes: Boxes4,
    pub(crate) child: [u32; MAX_CHILDREN],
    pub(crate) count: [u32; MAX_CHILDREN],
}

impl WideNode {
    /// A blank record, for initialising storage.
    pub const EMPTY: Self = WideNode {
        boxes: Boxes4 {
            min: [[0.0; MAX_CHILDREN]; 3],
            max: [[0.0; MAX_CHILDREN]; 3],
        },
        child: [0; MAX_CHILDREN],
        count: [UNUSED; MAX_CHILDREN],
    };

    /// A record of zero bits, for `static` storage (`.bss`, no flash); see
    /// [`Node::ZERO`](crate::Node::ZERO).
    pub const ZERO: Self = WideNode {
        count: [0; MAX_CHILDREN],
        ..WideNode::EMPTY
    };

    /// The box of slot `k`.
    #[inline(always)]
    pub fn slot_box(&self, k: usize) -> Aabb {
        let b = &self.boxes;
        Aabb::new(
            Vec3::new(b.min[0][k], b.min[1][k], b.min[2][k]),
            Vec3::new(b.max[0][k], b.max[1][k], b.max[2][k]),
        )
    }

    /// Slots in use.
    pub fn used(&self) -> usize {
        self.count.iter().filter(|&&c| c != UNUSED).count()
    }
}

/// A 4-wide tree of [`WideNode`]s, borrowing its storage. Built by
/// collapsing a binary tree: each record takes a node's two children and,
/// while there is room, replaces the child with the largest surface area by
/// its own two children. Node ids are `record * 4 + slot`; record 0 holds
/// only the root. The volumes are boxes whatever the source tree's type.
///
/// ```
/// use bvhkit::layout::{Wide, WideNode};
/// use bvhkit::{Aabb, Hierarchy, Node, TopDown};
/// use glam::Vec3;
/// let pts: Vec<Vec3> = (0..16).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
/// let mut nodes = vec![Node::<Aabb>::EMPTY; 31];
/// let mut idx = vec![0; 16];
/// let bvh = TopDown::median().with_max_leaf_size(1).build(&pts, &mut nodes, &mut idx)?;
/// let mut recs = vec![WideNode::EMPTY; Wide::records_needed(&bvh)?];
/// let wide = Wide::from_bvh(&bvh, &mut recs)?;
/// // Header, the root's 4 grandchildren, then their 4 children each: 16 leaves in 2 levels.
/// assert_eq!(wide.records().len(), 6);
/// assert_eq!(wide.depth(), 2); // root -> 4 inner -> 16 leaves
/// assert_eq!(core::mem::size_of::<WideNode>(), 128);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Wide<'a> {
    records: &'a [WideNode],
    leaves: Leaves<'a>,
    depth: u32,
    nodes: u32,
}

impl<'a> Wide<'a> {
    /// Most records a tree over `n` primitives can need: a header holding the
    /// root, then one per record of the collapse. A record that opens an inner
    /// child absorbs at least two inner nodes, so from three primitives on
    /// `n - 1` records suffice; two primitives in two leaves need two (the
    /// header and the root's record), one primitive one. A `const fn` to size
    /// `static` storage; [`records_needed`](Self::records_needed) gives the
    /// exact count of a built tree.
    ///
    /// ```
    /// use bvhkit::layout::{Wide, WideNode};
    /// static mut RECORDS: [WideNode; Wide::max_records(256)] = [WideNode::ZERO; Wide::max_records(256)];
    /// assert_eq!(Wide::max_records(256), 255);
    /// ```
    pub const fn max_records(n: usize) -> usize {
        crate::Capacity::for_primitives(n).wide_records
    }

    /// Records the collapse of `bvh` needs.
    pub fn records_needed<B: BoundingVolume>(bvh: &Bvh<'_, B>) -> Result<usize, Error> {
        wide_walk(bvh, 0, |_, _| Ok(()))
    }

    /// Collapses `bvh` into `out` (at least
    /// [`records_needed`](Self::records_needed) records).
    pub fn from_bvh<B: BoundingVolume>(
        bvh: &Bvh<'a, B>,
        out: &'a mut [WideNode],
    ) -> Result<Self, Error> {
        let (needed, count) = fill_wide(bvh, 0, out, |boxes, slots| {
            let mut r = WideNode::EMPTY;
            for (k, (b, s)) in boxes.iter().zip(slots).enumerate() {
                for axis in 0..3 {
                    r.boxes.min[axis][k] = b.min[axis];
                    r.boxes.max[axis][k] = b.max[axis];
                }
                r.child[k] = s.link;
                r.count[k] = if s.count == 0 {
                    INNER | s.child_slots
                } else {
                    s.count
                };
            }
            Ok(r)
        })?;
        let records: &'a [WideNode] = &out[..needed];
        let mut wide = Wide {
            records,
            leaves: Leaves::of(bvh),
            depth: 0,
            nodes: count,
        };
        wide.depth = measure_depth(&wide)? as u32;
        Ok(wide)
    }

    /// The records; record 0 holds the root.
    pub fn records(&self) -> &'a [WideNode] {
        self.records
    }

    /// The layout over checked parts (a baked tree's, once
    /// [`from_baked`](Self::from_baked) has checked them), its depth
    /// measured here.
    pub(crate) fn from_checked(
        records: &'a [WideNode],
        indices: &'a [u32],
        bounds: &'a [Aabb],
        nodes: usize,
    ) -> Result<Self, Error> {
        let mut wide = Wide {
            records,
            leaves: Leaves::new(indices, bounds),
            depth: 0,
            nodes: nodes as u32,
        };
        wide.depth = measure_depth(&wide)? as u32;
        Ok(wide)
    }

    /// The index array the leaves name runs of.
    pub fn indices(&self) -> &'a [u32] {
        self.leaves.indices()
    }

    /// The primitives' bounds in index order, when the tree keeps them.
    pub fn leaf_bounds(&self) -> Option<&'a [Aabb]> {
        self.leaves.kept()
    }

    /// The view of `records`, which [`from_bvh`](Self::from_bvh) wrote
    /// from `bvh` earlier and measured as `depth` levels and `nodes` nodes
    /// (an owner keeps the records and rebuilds the view per query, without
    /// walking it again). The caller guarantees all three.
    #[cfg(feature = "alloc")]
    pub(crate) fn from_kept<B: BoundingVolume>(
        records: &'a [WideNode],
        bvh: &Bvh<'a, B>,
        depth: usize,
        nodes: usize,
    ) -> Self {
        Wide {
            records,
            leaves: Leaves::of(bvh),
            depth: depth as u32,
            nodes: nodes as u32,
        }
    }
}

/// Depth of a wide layout, by walking it (the collapse shortens paths
/// unevenly, so the source tree's depth only bounds it).
pub(crate) fn measure_depth<H: Hierarchy>(h: &H) -> Result<usize, Error> {
    use crate::query::stack::Stack;
    if h.is_empty() {
        return Ok(0);
    }
    let mut max = 0;
    let mut stack = Stack::<(u32, u32), { crate::tree::hierarchy::DFS_STACK }>::with(
        (h.root(), 0),
        crate::MAX_DEPTH,
    );
    while let Some((n, d)) = stack.pop() {
        max = max.max(d);
        if let Content::Inner(kids) = h.content(n) {
            for &c in kids.as_slice() {
                stack.push((c, d + 1))?;
            }
        }
    }
    Ok(max as usize)
}

impl Hierarchy for Wide<'_> {
    type Bv = Aabb;
    const ARITY: usize = MAX_CHILDREN;

    #[inline(always)]
    fn root(&self) -> u32 {
        0
    }

    #[inline(always)]
    fn bv(&self, node: u32) -> Aabb {
        self.records[(node >> 2) as usize].slot_box((node & 3) as usize)
    }

    #[inline(always)]
    fn content(&self, node: u32) -> Content<'_> {
        let (rec, k) = ((node >> 2) as usize, (node & 3) as usize);
        let r = &self.records[rec];
        let (link, count) = (r.child[k], r.count[k]);
        if count & INNER == 0 {
            let first = link as usize;
            return Content::Leaf(self.leaves.ids(first, count as usize));
        }
        let base = link * 4;
        let len = (count & !INNER) as usize;
        Content::Inner(Kids::new([base, base + 1, base + 2, base + 3], len))
    }

    #[inline(always)]
    fn is_leaf(&self, node: u32) -> bool {
        self.records[(node >> 2) as usize].count[(node & 3) as usize] & INNER == 0
    }

    /// The four boxes of the record against one box in a few 4-lane
    /// comparisons (the same closed-interval test as [`Aabb::overlaps`]).
    #[inline(always)]
    fn children_overlapping(&self, kids: &Kids, other: &Aabb) -> u32 {
        let ids = kids.as_slice();
        let Some(&first) = ids.first() else { return 0 };
        let r = &self.records[(first >> 2) as usize].boxes;
        r.overlapping(other) & ((1 << ids.len()) - 1)
    }

    #[inline(always)]
    fn children_boxes(&self, kids: &Kids) -> Option<&Boxes4> {
        let first = *kids.as_slice().first()?;
        Some(&self.records[(first >> 2) as usize].boxes)
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
        self.nodes as usize
    }

    fn bytes(&self) -> usize {
        core::mem::size_of_val(self.records) + self.leaves.bytes()
    }
}
