//! The pointerless array: a complete binary tree stored level by level.

use super::{check_capacity, Leaves};
use crate::bv::{Aabb, BoundingVolume};
use crate::tree::{Bvh, Content, Hierarchy, Kids};
use crate::Error;

/// One entry of the implicit array: a volume and a packed leaf span.
///
/// The children of entry `i` are entries `2i + 1` and `2i + 2`, so no links
/// are stored. `span` is 0 for an internal node, `u32::MAX` for an entry no
/// node occupies, and otherwise `first << 8 | count` for a leaf (at most 255
/// primitives per leaf and 2^24 - 1 primitives in all). With an
/// [`Aabb`](crate::Aabb) an entry is 28 bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct Slot<B> {
    /// Bounds of the subtree (meaningless in an unused entry).
    pub bv: B,
    span: u32,
}

const INNER: u32 = 0;
const UNUSED: u32 = u32::MAX;

impl<B: BoundingVolume> Slot<B> {
    /// An unused entry, for initialising storage.
    pub const EMPTY: Self = Slot {
        bv: B::EMPTY,
        span: UNUSED,
    };

    /// Whether no node occupies this entry (wasted space).
    pub const fn is_unused(&self) -> bool {
        self.span == UNUSED
    }
}

/// A tree in the implicit (pointerless) array layout, borrowing its storage.
///
/// A complete tree of depth `d` takes `2^(d+1) - 1` entries whatever its node
/// count, so an unbalanced tree wastes the entries of its missing subtrees.
/// Trees needing more than [`Implicit::MAX_WASTE`] entries per real node are
/// refused with [`Error::SparseTree`]; a median-cut tree
/// ([`TopDown::median`](crate::TopDown::median)) over a power-of-two number
/// of primitives wastes nothing.
///
/// ```
/// use bvhkit::layout::{Implicit, Slot};
/// use bvhkit::{Aabb, Hierarchy, Node, TopDown};
/// use glam::Vec3;
/// let pts: Vec<Vec3> = (0..16).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
/// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(16)];
/// let mut idx = vec![0; 16];
/// let bvh = TopDown::median().with_max_leaf_size(1).build(&pts, &mut nodes, &mut idx)?;
/// let mut slots = vec![Slot::EMPTY; Implicit::slots_needed(&bvh)?];
/// let tree = Implicit::from_bvh(&bvh, &mut slots)?;
/// assert_eq!(tree.slots().len(), 31); // a perfect tree: no waste
/// assert_eq!(tree.unused(), 0);
/// // Children of entry 1 are 3 and 4.
/// assert!(matches!(tree.content(1), bvhkit::Content::Inner(k) if k.as_slice() == [3, 4]));
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Implicit<'a, B> {
    slots: &'a [Slot<B>],
    leaves: Leaves<'a>,
    depth: u32,
    nodes: u32,
}

impl<'a, B: BoundingVolume> Implicit<'a, B> {
    /// Most array entries accepted per real node. Beyond this the layout
    /// costs more than the links it removes.
    pub const MAX_WASTE: usize = 16;

    /// Entries the array needs for `bvh`: `2^(depth+1) - 1`. An error when
    /// that exceeds [`MAX_WASTE`](Self::MAX_WASTE) per node.
    pub fn slots_needed(bvh: &Bvh<'_, B>) -> Result<usize, Error> {
        if bvh.is_empty() {
            return Ok(0);
        }
        let nodes = bvh.node_count();
        let depth = bvh.depth();
        let slots = if depth >= 40 {
            usize::MAX
        } else {
            (1usize << (depth + 1)) - 1
        };
        if slots / Self::MAX_WASTE > nodes || slots > u32::MAX as usize {
            return Err(Error::SparseTree { slots, nodes });
        }
        Ok(slots)
    }

    /// Lays `bvh` out level by level in `out` (at least
    /// [`slots_needed`](Self::slots_needed) entries).
    pub fn from_bvh(bvh: &Bvh<'a, B>, out: &'a mut [Slot<B>]) -> Result<Self, Error> {
        super::dense(bvh)?;
        let needed = Self::slots_needed(bvh)?;
        check_capacity(needed, out.len())?;
        let out = &mut out[..needed];
        out.fill(Slot::EMPTY);
        let nodes = bvh.nodes();
        // (canonical node, slot); one waiting sibling per level.
        let mut stack = [(0u32, 0usize); crate::MAX_DEPTH + 2];
        let mut top = usize::from(!bvh.is_empty());
        while top > 0 {
            top -= 1;
            let (n, s) = stack[top];
            let node = &nodes[n as usize];
            let span = match node.children() {
                Some((l, r)) => {
                    stack[top] = (r, 2 * s + 2);
                    stack[top + 1] = (l, 2 * s + 1);
                    top += 2;
                    INNER
                }
                None => pack(node.first, node.count)?,
            };
            out[s] = Slot { bv: node.bv, span };
        }
        let out: &'a [Slot<B>] = out;
        Ok(Implicit {
            slots: out,
            leaves: Leaves::of(bvh),
            depth: bvh.depth() as u32,
            nodes: bvh.node_count() as u32,
        })
    }

    /// The array, unused entries included.
    pub fn slots(&self) -> &'a [Slot<B>] {
        self.slots
    }

    /// Entries no node occupies: the price of the missing links.
    pub fn unused(&self) -> usize {
        self.slots.len() - self.nodes as usize
    }
}

/// Packs a leaf span; refuses what does not fit instead of wrapping.
fn pack(first: u32, count: u32) -> Result<u32, Error> {
    if count == 0 || count > 0xFF {
        return Err(Error::FieldOverflow {
            field: "leaf size in the implicit layout",
            value: count as usize,
            max: 0xFF,
        });
    }
    if first >= 0x00FF_FFFF {
        return Err(Error::FieldOverflow {
            field: "first primitive of a leaf in the implicit layout",
            value: first as usize,
            max: 0x00FF_FFFE,
        });
    }
    Ok(first << 8 | count)
}

impl<B: BoundingVolume> Hierarchy for Implicit<'_, B> {
    type Bv = B;
    const ARITY: usize = 2;

    #[inline(always)]
    fn root(&self) -> u32 {
        0
    }

    #[inline(always)]
    fn bv(&self, node: u32) -> B {
        self.slots[node as usize].bv
    }

    #[inline(always)]
    fn content(&self, node: u32) -> Content<'_> {
        match self.slots[node as usize].span {
            INNER => Content::Inner(Kids::two(2 * node + 1, 2 * node + 2)),
            span => {
                let (first, count) = ((span >> 8) as usize, (span & 0xFF) as usize);
                Content::Leaf(self.leaves.ids(first, count))
            }
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
        self.nodes as usize
    }

    fn bytes(&self) -> usize {
        core::mem::size_of_val(self.slots) + self.leaves.bytes()
    }
}
