//! Tree representations: the same hierarchy stored smaller or friendlier to
//! the cache.
//!
//! Lecture: *efficient tree representation and traversal*. Memory traffic,
//! not arithmetic, bounds most traversals, so the layout of the nodes matters.
//! Each layout here is converted from the canonical [`Bvh`] (built by any
//! builder) into caller storage, and implements [`Hierarchy`], so every query
//! runs on it unchanged.
//!
//! | layout | record | bytes (AABB) | children found by | what it saves |
//! |---|---|---:|---|---|
//! | canonical [`Bvh`] | [`Node`] | 32 | `first`, `first + 1` | one index names both children |
//! | [`Implicit`] | [`Slot`] | 28 | `2i + 1`, `2i + 2` | no child links at all (if balanced) |
//! | [`Preorder`] `u32` | [`PreNode`] | 32 | `i + 1` and a stored right index | left link; left child shares the cache line |
//! | [`Preorder`] `u16` | [`PreNode`] | 28 | the same, as an offset from the record (an escape to a [`FarLink`] when too far) | half of each index, for any tree size |
//! | [`TriNodes`] | [`TriNode`] | 92 (3 nodes) | two links per child | links of every other level |
//! | [`Wide`] | [`WideNode`] | 128 (4 children) | one link per child | 3 of 4 levels; one fetch tests 4 boxes |
//! | [`QuantizedWide`] | [`QuantNode`] | 64 (4 children) | one link per child | 8-bit boxes relative to the parent; small subtrees merged into one leaf slot, so fewer records |
//!
//! Every layout keeps the canonical tree's primitive index array, and
//! [`to_bvh`] turns any of them back into a canonical tree: exactly the same
//! tree for the binary layouts, an equivalent (wider boxes, extra levels) one
//! for the wide ones, and for the quantized one an equivalent whose merged
//! leaves hold up to [`QuantizedWide::MERGED_LEAF`] primitives.

mod implicit;
mod preorder;
pub(crate) mod quantized;
mod trinode;
pub(crate) mod wide;

pub use implicit::{Implicit, Slot};
pub use preorder::{FarLink, Offset, PreNode, Preorder, ESCAPE, LEAF_BIAS};
pub use quantized::{QuantNode, QuantizedWide};
pub use trinode::{TriNode, TriNodes};
pub use wide::{Wide, WideNode};

use crate::builders::enclose;
use crate::bv::{Aabb, BoundingVolume};
use crate::query::stack::Stack;
use crate::tree::hierarchy::DFS_STACK;
use crate::tree::{Bvh, Content, Hierarchy, Node, MAX_CHILDREN, MAX_DEPTH};
use crate::Error;

/// The leaf storage a layout shares with the [`Bvh`] it was converted from:
/// the primitive index array and, if the tree keeps them
/// ([`Bvh::with_leaf_bounds`]), the primitives' bounds side by side with it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Leaves<'a> {
    indices: &'a [u32],
    bounds: &'a [Aabb],
}

impl<'a> Leaves<'a> {
    pub(crate) fn of<B: BoundingVolume>(bvh: &Bvh<'a, B>) -> Self {
        Leaves {
            indices: bvh.indices(),
            bounds: bvh.leaf_bounds().unwrap_or(&[]),
        }
    }

    pub(crate) fn new(indices: &'a [u32], bounds: &'a [Aabb]) -> Self {
        Leaves { indices, bounds }
    }

    pub(crate) fn indices(&self) -> &'a [u32] {
        self.indices
    }

    /// The kept bounds, if any.
    pub(crate) fn kept(&self) -> Option<&'a [Aabb]> {
        (!self.bounds.is_empty()).then_some(self.bounds)
    }

    /// The ids of the leaf whose run starts at `first`.
    #[inline(always)]
    pub(crate) fn ids(&self, first: usize, count: usize) -> &'a [u32] {
        &self.indices[first..first + count]
    }

    /// The kept bounds of a leaf's ids (`content` is the layout's answer for
    /// the node). A leaf's ids are always a run of the shared index array,
    /// so the run's start is the ids' offset from the array's start; layouts
    /// thereby need no second decoding of their records.
    #[inline(always)]
    pub(crate) fn bounds_of(&self, content: Content<'_>) -> Option<&'a [Aabb]> {
        let Content::Leaf(ids) = content else {
            return None;
        };
        if self.bounds.is_empty() {
            return None;
        }
        let offset = (ids.as_ptr() as usize).checked_sub(self.indices.as_ptr() as usize)?;
        let first = offset / core::mem::size_of::<u32>();
        self.bounds.get(first..first + ids.len())
    }

    pub(crate) fn len(&self) -> usize {
        self.indices.len()
    }

    /// Bytes of the index array and the kept bounds.
    pub(crate) fn bytes(&self) -> usize {
        core::mem::size_of_val(self.indices) + core::mem::size_of_val(self.bounds)
    }
}

/// Checks a caller buffer against what a conversion needs.
pub(crate) fn check_capacity(needed: usize, available: usize) -> Result<(), Error> {
    if available < needed {
        return Err(Error::NodeCapacity { needed, available });
    }
    Ok(())
}

/// Writes any [`Hierarchy`] as a canonical [`Bvh`] into `nodes` and `indices`
/// (at least [`max_nodes`](crate::max_nodes)`(h.primitive_count())` and
/// `h.primitive_count()` entries). A binary layout comes back as exactly the
/// tree it was made from (node order aside). A node with more than two
/// children becomes a small binary subtree over them, whose inner volumes
/// enclose the children's; a quantized parent box that does not contain a
/// child's (each level is rounded on its own grid) is grown to contain it.
///
/// ```
/// use bvhkit::layout::{to_bvh, PreNode, Preorder};
/// use bvhkit::{Aabb, Hierarchy, Node, TopDown, Triangle};
/// use glam::Vec3;
/// let tris: Vec<Triangle> = (0..6).map(|i| {
///     let o = Vec3::new(i as f32, 0.0, 0.0);
///     Triangle::new(o, o + Vec3::X, o + Vec3::Y)
/// }).collect();
/// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(6)];
/// let mut idx = vec![0; 6];
/// let bvh = TopDown::default().with_max_leaf_size(1).build(&tris, &mut nodes, &mut idx)?;
/// let mut pre = vec![PreNode::<Aabb, u16>::EMPTY; bvh.node_count()];
/// let pre = Preorder::from_bvh(&bvh, &mut pre)?;
/// let (mut back, mut back_idx) = (vec![Node::EMPTY; bvh.node_count()], vec![0; 6]);
/// let back = to_bvh(&pre, &mut back, &mut back_idx)?;
/// assert_eq!(back.node_count(), bvh.node_count());
/// assert_eq!(back.root(), bvh.root());
/// # Ok::<(), bvhkit::Error>(())
/// ```
pub fn to_bvh<'o, H: Hierarchy>(
    h: &H,
    nodes: &'o mut [Node<H::Bv>],
    indices: &'o mut [u32],
) -> Result<Bvh<'o, H::Bv>, Error> {
    let n = h.primitive_count();
    crate::tree::hierarchy::check_query(h, n)?;
    if indices.len() < n {
        return Err(Error::IndexCapacity {
            needed: n,
            available: indices.len(),
        });
    }
    if h.is_empty() {
        return Ok(Bvh::from_built(&nodes[..0], &indices[..0], 0));
    }
    // A work item is a group of 1..=4 nodes of `h` that becomes one node of
    // the output: a real node when alone, a virtual inner node otherwise.
    type Item = ([u32; MAX_CHILDREN], u8, u32, u32); // (ids, len, slot, depth)
    let (mut next_slot, mut next_index, mut depth) = (1usize, 0usize, 0u32);
    check_capacity(1, nodes.len())?;
    let mut stack = [([0u32; MAX_CHILDREN], 0u8, 0u32, 0u32); 2 * MAX_DEPTH + 2];
    stack[0] = ([h.root(), 0, 0, 0], 1, 0, 0);
    let mut top = 1;
    let too_deep = Error::StackOverflow {
        depth: 2 * MAX_DEPTH,
        capacity: MAX_DEPTH,
    };
    while top > 0 {
        top -= 1;
        let (ids, len, slot, d): Item = stack[top];
        depth = depth.max(d);
        if d as usize > MAX_DEPTH {
            return Err(too_deep);
        }
        let group = &ids[..len as usize];
        // The members to split into two children, when this is an inner node.
        let mut members = [0u32; MAX_CHILDREN];
        let mut m = 0;
        let bv;
        if let [only] = group {
            bv = h.bv(*only);
            match h.content(*only) {
                Content::Leaf(prims) => {
                    let end = next_index + prims.len();
                    if end > n {
                        return Err(Error::InvalidTree(
                            "leaves hold more primitives than the tree",
                        ));
                    }
                    indices[next_index..end].copy_from_slice(prims);
                    nodes[slot as usize] = Node {
                        bv,
                        first: next_index as u32,
                        count: prims.len() as u32,
                    };
                    next_index = end;
                    continue;
                }
                Content::Inner(kids) => {
                    for &c in kids.as_slice() {
                        members[m] = c;
                        m += 1;
                    }
                }
            }
        } else {
            let mut acc = h.bv(group[0]);
            for &g in &group[1..] {
                acc = enclose(&acc, &h.bv(g));
            }
            bv = acc;
            members[..group.len()].copy_from_slice(group);
            m = group.len();
        }
        check_capacity(next_slot + 2, nodes.len())?;
        nodes[slot as usize] = Node {
            bv,
            first: next_slot as u32,
            count: 0,
        };
        // Split the members in two halves: (a, b) or ((a, b), (c, d)) etc.
        let half = m.div_ceil(2);
        let (left, right) = members[..m].split_at(half);
        for (k, part) in [right, left].into_iter().enumerate() {
            if top + 1 > stack.len() {
                return Err(too_deep);
            }
            let mut ids = [0u32; MAX_CHILDREN];
            ids[..part.len()].copy_from_slice(part);
            let child_slot = next_slot + 1 - k;
            stack[top] = (ids, part.len() as u8, child_slot as u32, d + 1);
            top += 1;
        }
        next_slot += 2;
    }
    if next_index != n {
        return Err(Error::InvalidTree("leaves do not hold every primitive"));
    }
    // A canonical node must contain its children. Layouts that round boxes
    // per level (quantized) only promise that each node contains its
    // primitives, so grow parents where needed, children first (they come
    // after their parent). Exact layouts pass through unchanged.
    for i in (0..next_slot).rev() {
        if let Some((l, r)) = nodes[i].children() {
            let mut bv = nodes[i].bv;
            for c in [l, r] {
                let child = nodes[c as usize].bv;
                if !bv.contains(&child) {
                    bv = enclose(&bv, &child);
                }
            }
            nodes[i].bv = bv;
        }
    }
    let (nodes, indices) = (&nodes[..next_slot], &indices[..n]);
    Ok(Bvh::from_built(nodes, indices, depth))
}

/// The 4-way collapse rule shared by the wide layouts: start from a node's
/// two children and, while there is room, replace the internal child with the
/// largest surface area by its own two children (ties, as among flat boxes,
/// go to the longer box). Large children are the likeliest to be opened by
/// a query, so pulling their children up saves the most node fetches. A
/// child whose subtree is a [`run`] of at most `merge` primitives counts as a
/// leaf (it will be one leaf slot); `merge = 0` merges nothing.
/// Returns the (2..=4) canonical nodes that become slots.
pub(crate) fn collapse<B: BoundingVolume>(
    bvh: &Bvh<'_, B>,
    node: u32,
    merge: u32,
) -> ([u32; MAX_CHILDREN], usize) {
    let nodes = bvh.nodes();
    let (l, r) = nodes[node as usize].children().unwrap_or((node, node));
    let mut slots = [l, r, 0, 0];
    let mut len = 2;
    while len < MAX_CHILDREN {
        let widest = (0..len)
            .filter(|&k| run(bvh, slots[k], merge).is_none())
            .max_by(|&x, &y| {
                let size = |k: usize| {
                    let b = nodes[slots[k] as usize].bv.aabb();
                    (b.half_area(), b.extent().element_sum())
                };
                let ((ax, lx), (ay, ly)) = (size(x), size(y));
                ax.total_cmp(&ay).then(lx.total_cmp(&ly))
            });
        let Some(k) = widest else { break };
        let (cl, cr) = nodes[slots[k] as usize]
            .children()
            .unwrap_or((slots[k], slots[k]));
        slots[k] = cl;
        slots[len] = cr;
        len += 1;
    }
    (slots, len)
}

/// The primitives of `node`'s subtree as one run of the index array,
/// `(first, count)`: for a leaf always; for an internal node when its
/// subtree holds at most `merge` primitives and their entries are contiguous
/// (a top-down builder always makes them so; others need not), so one leaf
/// slot of a wide record can stand for the whole subtree.
pub(crate) fn run<B: BoundingVolume>(
    bvh: &Bvh<'_, B>,
    node: u32,
    merge: u32,
) -> Option<(u32, u32)> {
    let nodes = bvh.nodes();
    let n = &nodes[node as usize];
    if n.is_leaf() {
        return Some((n.first, n.count));
    }
    if merge == 0 {
        return None;
    }
    // A subtree of at most `merge` primitives has at most `merge` leaves
    // (a leaf holds one or more), so at most `merge - 1` nodes wait.
    let (mut lo, mut hi, mut count) = (u32::MAX, 0u32, 0u32);
    let mut stack = Stack::<u32, { MAX_LEAF_MERGE as usize }>::with(node, 0);
    while let Some(i) = stack.pop() {
        let n = &nodes[i as usize];
        match n.children() {
            Some((l, r)) => {
                stack.push(l).ok()?;
                stack.push(r).ok()?;
            }
            None => {
                count = count.checked_add(n.count)?;
                if count > merge {
                    return None;
                }
                lo = lo.min(n.first);
                hi = hi.max(n.first + n.count);
            }
        }
    }
    (hi - lo == count).then_some((lo, count))
}

/// Most primitives [`run`] merges into one leaf slot.
pub(crate) const MAX_LEAF_MERGE: u32 = 64;

/// One slot of a wide record as the conversion walk hands it out.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SlotSource {
    /// The canonical node the slot holds.
    pub node: u32,
    /// Record of its children (inner) or its first index entry (leaf).
    pub link: u32,
    /// Primitive count (leaf) or 0 (inner).
    pub count: u32,
    /// Slots of the child record (inner), so a query learns a node's
    /// number of children without touching the child record; 0 for a leaf.
    pub child_slots: u32,
}

/// Fills `out` with the records of a 4-wide layout of `bvh`: one record per
/// step of [`wide_walk`], made by `record` from the slots' exact boxes and
/// sources. Returns the records used and the number of logical nodes.
#[inline(never)] // its stack stays out of the caller's frame
/// Refuses a tree whose leaves name ids with gaps (a dynamic tree after
/// removals): a layout keeps only the primitive count, so its queries index
/// the slice by position.
pub(crate) fn dense<B: BoundingVolume>(bvh: &Bvh<'_, B>) -> Result<(), Error> {
    if bvh.index_bound() != bvh.primitive_count() {
        return Err(Error::InvalidTree(
            "the layouts need leaves numbered 0..n; this tree names ids with gaps \
             (a dynamic tree after removals): query it as it is",
        ));
    }
    Ok(())
}

pub(crate) fn fill_wide<B: BoundingVolume, R>(
    bvh: &Bvh<'_, B>,
    merge: u32,
    out: &mut [R],
    mut record: impl FnMut(&[crate::bv::Aabb], &[SlotSource]) -> Result<R, Error>,
) -> Result<(usize, u32), Error> {
    dense(bvh)?;
    let needed = wide_walk(bvh, merge, |_, _| Ok(()))?;
    check_capacity(needed, out.len())?;
    let nodes = bvh.nodes();
    let mut count = 0u32;
    wide_walk(bvh, merge, |rec, slots| {
        let mut boxes = [crate::bv::Aabb::EMPTY; MAX_CHILDREN];
        for (b, s) in boxes.iter_mut().zip(slots) {
            *b = nodes[s.node as usize].bv.aabb();
        }
        out[rec] = record(&boxes[..slots.len()], slots)?;
        count += slots.len() as u32;
        Ok(())
    })?;
    Ok((needed, count))
}

/// The walk shared by the 4-wide layouts. Record 0 is a header whose only
/// slot is the root; every other record holds the [`collapse`] of one
/// canonical node. Calls `emit(record, slots)` once per record and returns
/// the number of records. With an `emit` that does nothing it sizes storage.
#[inline(never)] // its stack stays out of the caller's frame
pub(crate) fn wide_walk<B: BoundingVolume>(
    bvh: &Bvh<'_, B>,
    merge: u32,
    mut emit: impl FnMut(usize, &[SlotSource]) -> Result<(), Error>,
) -> Result<usize, Error> {
    crate::tree::hierarchy::check_query(bvh, bvh.primitive_count())?;
    if bvh.is_empty() {
        return Ok(0); // no records, not even the header
    }
    let mut next = 1u32;
    // (canonical node whose collapse fills the record, record); the header
    // record 0 holds the root alone. The collapse is recomputed on pop, so an
    // entry is 8 bytes, not the 24 of the whole group.
    const HEADER: u32 = u32::MAX;
    let mut stack = Stack::<(u32, u32), DFS_STACK>::with((HEADER, 0), bvh.depth());
    while let Some((parent, rec)) = stack.pop() {
        let (group, len) = if parent == HEADER {
            ([0; MAX_CHILDREN], 1)
        } else {
            collapse(bvh, parent, merge)
        };
        let mut slots = [SlotSource {
            node: 0,
            link: 0,
            count: 0,
            child_slots: 0,
        }; MAX_CHILDREN];
        for (slot, &c) in slots.iter_mut().zip(&group[..len]) {
            *slot = if let Some((first, count)) = run(bvh, c, merge) {
                SlotSource {
                    node: c,
                    link: first,
                    count,
                    child_slots: 0,
                }
            } else {
                let kids = collapse(bvh, c, merge);
                stack.push((c, next))?;
                if next >= u32::MAX / 4 {
                    return Err(Error::FieldOverflow {
                        field: "wide record index",
                        value: next as usize + 1,
                        max: (u32::MAX / 4) as usize,
                    });
                }
                next += 1;
                SlotSource {
                    node: c,
                    link: next - 1,
                    count: 0,
                    child_slots: kids.1 as u32,
                }
            };
        }
        emit(rec as usize, &slots[..len])?;
    }
    Ok(next as usize)
}
