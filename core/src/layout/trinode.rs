//! Tri-nodes: a parent and its two children fused into one record.

use super::{check_capacity, Leaves};
use crate::bv::{Aabb, BoundingVolume};
use crate::query::stack::Stack;
use crate::tree::hierarchy::DFS_STACK;
use crate::tree::{Bvh, Content, Hierarchy, Kids};
use crate::Error;

/// A parent node and both its children in one record.
///
/// `bv` holds the volumes of the parent, the left and the right child. For
/// each child, two words of `next`: either the records of its two children
/// (each record is rooted at a grandchild of this one) or, for a leaf, its
/// first index entry and primitive count. `flags` marks which children are in
/// use (a record rooted at a leaf uses only its first volume: the empty
/// slots are the lectures' waste on sparse trees) and which of the three
/// nodes are leaves. With an [`Aabb`](crate::Aabb): 92 bytes for 3 nodes.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct TriNode<B> {
    /// Volumes of the parent, left child and right child.
    pub bv: [B; 3],
    next: [u32; 4],
    flags: u32,
}

const USED_LEFT: u32 = 1;
const USED_RIGHT: u32 = 2;
/// Leaf flags: bit `LEAF << position` (position 0 = parent, 1 = left, 2 = right).
const LEAF: u32 = 4;

impl<B: BoundingVolume> TriNode<B> {
    /// A blank record, for initialising storage.
    pub const EMPTY: Self = TriNode {
        bv: [B::EMPTY; 3],
        next: [0; 4],
        flags: 0,
    };

    /// How many of the three node places are in use (1 or 3).
    pub const fn used(&self) -> u32 {
        1 + (self.flags & USED_LEFT) + (self.flags & USED_RIGHT) / 2
    }
}

/// A tree of tri-nodes, borrowing its storage. Node ids are
/// `record * 4 + position` (0 parent, 1 left, 2 right).
///
/// ```
/// use bvhkit::layout::{TriNode, TriNodes};
/// use bvhkit::{Aabb, Node, TopDown};
/// use glam::Vec3;
/// let pts: Vec<Vec3> = (0..8).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
/// let mut nodes = vec![Node::<Aabb>::EMPTY; 15];
/// let mut idx = vec![0; 8];
/// let bvh = TopDown::median().with_max_leaf_size(1).build(&pts, &mut nodes, &mut idx)?;
/// // Depth 3: records at levels 0 (one) and 2 (four, rooted at the grandchildren).
/// let mut recs = vec![TriNode::EMPTY; TriNodes::records_needed(&bvh)?];
/// let tri = TriNodes::from_bvh(&bvh, &mut recs)?;
/// assert_eq!(tri.records().len(), 5);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct TriNodes<'a, B> {
    records: &'a [TriNode<B>],
    leaves: Leaves<'a>,
    depth: u32,
    nodes: u32,
}

impl<'a, B: BoundingVolume> TriNodes<'a, B> {
    /// Records needed for `bvh`: one per node at an even depth.
    pub fn records_needed(bvh: &Bvh<'_, B>) -> Result<usize, Error> {
        crate::tree::hierarchy::check_query(bvh, bvh.primitive_count())?;
        if bvh.is_empty() {
            return Ok(0);
        }
        let nodes = bvh.nodes();
        let mut count = 0;
        let mut stack = Stack::<(u32, u32), DFS_STACK>::with((0, 0), bvh.depth());
        while let Some((n, d)) = stack.pop() {
            count += (d % 2 == 0) as usize;
            if let Some((l, r)) = nodes[n as usize].children() {
                stack.push((l, d + 1))?;
                stack.push((r, d + 1))?;
            }
        }
        Ok(count)
    }

    /// Fuses `bvh` into tri-nodes in `out` (at least
    /// [`records_needed`](Self::records_needed)).
    pub fn from_bvh(bvh: &Bvh<'a, B>, out: &'a mut [TriNode<B>]) -> Result<Self, Error> {
        super::dense(bvh)?;
        let needed = Self::records_needed(bvh)?;
        check_capacity(needed, out.len())?;
        if needed > (u32::MAX / 4) as usize {
            return Err(Error::FieldOverflow {
                field: "tri-node record index",
                value: needed,
                max: (u32::MAX / 4) as usize,
            });
        }
        let nodes = bvh.nodes();
        if bvh.is_empty() {
            return Ok(TriNodes {
                records: &out[..0],
                leaves: Leaves::of(bvh),
                depth: 0,
                nodes: 0,
            });
        }
        // (canonical node, record rooted at it)
        let mut stack = Stack::<(u32, u32), DFS_STACK>::with((0, 0), bvh.depth());
        let mut next = 1u32;
        while let Some((n, rec)) = stack.pop() {
            let node = &nodes[n as usize];
            let mut r = TriNode::EMPTY;
            r.bv[0] = node.bv;
            match node.children() {
                None => {
                    r.flags = LEAF;
                    r.next[0] = node.first;
                    r.next[1] = node.count;
                }
                Some((l, rt)) => {
                    r.flags = USED_LEFT | USED_RIGHT;
                    for (pos, c) in [(1usize, l), (2, rt)] {
                        let child = &nodes[c as usize];
                        r.bv[pos] = child.bv;
                        let words = &mut r.next[2 * (pos - 1)..2 * pos];
                        match child.children() {
                            None => {
                                r.flags |= LEAF << pos;
                                words.copy_from_slice(&[child.first, child.count]);
                            }
                            Some((gl, gr)) => {
                                words.copy_from_slice(&[next, next + 1]);
                                stack.push((gl, next))?;
                                stack.push((gr, next + 1))?;
                                next += 2;
                            }
                        }
                    }
                }
            }
            out[rec as usize] = r;
        }
        let records: &'a [TriNode<B>] = &out[..next as usize];
        Ok(TriNodes {
            records,
            leaves: Leaves::of(bvh),
            depth: bvh.depth() as u32,
            nodes: bvh.node_count() as u32,
        })
    }

    /// The records; record 0 is rooted at the root.
    pub fn records(&self) -> &'a [TriNode<B>] {
        self.records
    }

    /// Node places in use over places allocated (1.0 for a complete tree of
    /// odd depth; lower when subtrees end at even depths; 1.0 for the empty
    /// tree, which allocates nothing).
    pub fn fill(&self) -> f32 {
        if self.records.is_empty() {
            return 1.0;
        }
        self.nodes as f32 / (3 * self.records.len()) as f32
    }
}

impl<B: BoundingVolume> Hierarchy for TriNodes<'_, B> {
    type Bv = B;
    const ARITY: usize = 2;

    #[inline(always)]
    fn root(&self) -> u32 {
        0
    }

    #[inline(always)]
    fn bv(&self, node: u32) -> B {
        self.records[(node >> 2) as usize].bv[(node & 3) as usize]
    }

    #[inline(always)]
    fn content(&self, node: u32) -> Content<'_> {
        let (rec, pos) = ((node >> 2) as usize, node & 3);
        let r = &self.records[rec];
        let leaf = r.flags & (LEAF << pos) != 0;
        let words = match pos {
            0 if !leaf => return Content::Inner(Kids::two(node + 1, node + 2)),
            0 | 1 => [r.next[0], r.next[1]],
            _ => [r.next[2], r.next[3]],
        };
        if leaf {
            let first = words[0] as usize;
            Content::Leaf(self.leaves.ids(first, words[1] as usize))
        } else {
            Content::Inner(Kids::two(words[0] * 4, words[1] * 4))
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
        core::mem::size_of_val(self.records) + self.leaves.bytes()
    }
}
