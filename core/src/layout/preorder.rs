//! Preorder (depth-first) order: the left child follows its parent.
//!
//! Lecture: *efficient tree representation*, "offsets instead of pointers".
//! In preorder a node needs one link (its right child; the left is the next
//! record). With `u32` links that link is the right child's index. With
//! `u16` links it is an *offset* from the node's own record, which is small
//! for all but a few nodes near the root; a link too far for 16 bits is
//! stored as the reserved [`ESCAPE`] value, and its real target is kept in a
//! caller-provided side table of 32-bit [`FarLink`]s, sorted by record, found
//! by binary search. Records stay 28 bytes (with an [`Aabb`]) whatever the
//! tree's size; only the few far links cost 8 bytes more each.
//!
//! A leaf's link names its first entry of the index array. Stored as an
//! offset from the record it would not stay small (a leaf at record `i`
//! starts near entry `i * primitives / records`), so a leaf stores the
//! difference from exactly that prediction, plus [`LEAF_BIAS`] so that it
//! can be negative. For trees whose leaves follow each other in the index
//! array (every top-down build), the difference stays within a few leaves'
//! worth of primitives; any other leaf escapes too, so every tree converts.

use super::{check_capacity, Leaves};
use crate::bv::{Aabb, BoundingVolume};
use crate::tree::{Bvh, Content, Hierarchy, Kids, Node, MAX_DEPTH};
use crate::Error;

/// The 16-bit link value meaning "too far: the link is in the far table".
pub const ESCAPE: u16 = u16::MAX;

/// Added to a leaf's (signed) distance from its predicted first index entry,
/// so that distances from `-32 768` to `32 766` are stored as `0..ESCAPE`.
pub const LEAF_BIAS: u16 = 0x8000;

/// The integer type of a [`Preorder`] link: `u32` (absolute indices), or
/// `u16` (offsets from the record, with an [`ESCAPE`] to a far table for the
/// rare link that does not fit; half the link bytes, for any tree size).
pub trait Offset: Copy + core::fmt::Debug + PartialEq + 'static {
    /// Largest value the type holds.
    const MAX: usize;
    /// Zero.
    const ZERO: Self;
    /// Whether links are offsets from the record with an [`ESCAPE`] (`u16`)
    /// rather than absolute indices (`u32`).
    const RELATIVE: bool = false;
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
    const RELATIVE: bool = true;
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
///   is the next record; `link` names the right child.
/// * Leaf (`count > 0`): `link` names its first entry in the index array.
///
/// With `u32` links `link` is that index itself; with `u16` it is encoded
/// (see [`Preorder`] and [`Preorder::right`]).
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

    /// The link as stored: an index (`u32`); an offset, a biased leaf
    /// distance or [`ESCAPE`] (`u16`).
    pub fn link(&self) -> O {
        self.link
    }
}

impl<B: BoundingVolume> PreNode<B, u32> {
    /// Index of the right child (internal nodes only). With `u16` links a
    /// record alone cannot say it: ask [`Preorder::right`].
    pub fn right(&self) -> Option<usize> {
        self.has_left_child().then_some(self.link as usize)
    }
}

/// A link of a 16-bit [`Preorder`] that does not fit 16 bits: record
/// `record` (whose own link is [`ESCAPE`]) links to `link` (the right
/// child's record, or a leaf's first index entry). A tree's far links are
/// sorted by `record`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub struct FarLink {
    /// The record whose link this is.
    pub record: u32,
    /// The record's real link.
    pub link: u32,
}

impl FarLink {
    /// A blank entry, for initialising storage.
    pub const EMPTY: Self = FarLink { record: 0, link: 0 };
}

/// The first index entry predicted for a leaf at `record`: `record *
/// primitives / records`, in 32.32 fixed point (`ratio`). Encoding and
/// decoding use this same function, so its rounding never matters.
#[inline(always)]
fn predicted(record: usize, ratio: u64) -> usize {
    ((record as u64).wrapping_mul(ratio) >> 32) as usize
}

/// The fixed-point ratio of [`predicted`] for a tree.
fn ratio_of(primitives: usize, records: usize) -> u64 {
    ((primitives as u64) << 32) / (records.max(1) as u64)
}

/// The 16-bit link of record `record`: to its right child `target` (an
/// internal node), or to its first index entry `target` (a leaf, whose
/// entry was predicted at `predicted`). `None` when it does not fit, or
/// is farther than `reach` (the tests lower it to force escapes).
#[inline]
fn short_link(record: usize, target: usize, leaf: Option<usize>, reach: usize) -> Option<u16> {
    match leaf {
        None => {
            let offset = target.checked_sub(record)?;
            (offset <= reach && offset < ESCAPE as usize).then_some(offset as u16)
        }
        Some(predicted) => {
            let distance = target as i64 - predicted as i64;
            let stored = distance + LEAF_BIAS as i64;
            (distance.unsigned_abs() <= reach as u64 && (0..ESCAPE as i64).contains(&stored))
                .then_some(stored as u16)
        }
    }
}

/// One step of the preorder walk of a canonical tree.
enum Visit<'n, B> {
    /// The next record is canonical node `node`.
    Record { record: usize, node: &'n Node<B> },
    /// The right child of `parent` is at `right` (handed out when the walk
    /// reaches it: the left subtree's size is known only then).
    Right { parent: usize, right: usize },
}

/// Walks `bvh` in preorder; returns the number of records.
fn walk<'n, B: BoundingVolume>(
    bvh: &Bvh<'n, B>,
    mut visit: impl FnMut(Visit<'n, B>) -> Result<(), Error>,
) -> Result<usize, Error> {
    let nodes = bvh.nodes();
    // (canonical node, record whose right link points here, or MAX).
    let mut stack = [(0u32, usize::MAX); MAX_DEPTH + 2];
    let mut top = usize::from(bvh.node_count() > 0); // the empty tree has no root
    let mut next = 0;
    while top > 0 {
        top -= 1;
        let (n, parent) = stack[top];
        if parent != usize::MAX {
            visit(Visit::Right {
                parent,
                right: next,
            })?;
        }
        let node = &nodes[n as usize];
        if let Some((l, r)) = node.children() {
            // Right waits with the record to patch; left comes next.
            stack[top] = (r, next);
            stack[top + 1] = (l, usize::MAX);
            top += 2;
        }
        visit(Visit::Record { record: next, node })?;
        next += 1;
    }
    Ok(next)
}

/// A tree in preorder, borrowing its storage. Converting needs exactly
/// `bvh.node_count()` records and, with `u16` links,
/// [`far_links_needed`](Self::far_links_needed) far-link entries.
///
/// ```text
///        0              records:  0   1   2   3   4   5   6
///      /   \                      A   B   D   E   C   F   G
///     1     4           right:    4   3   -   -   6   -   -
///    / \   / \          u16 link: 4   2   -   -   2   -   -   (right - record)
///   2   3 5   6         left = next record whenever count == 0
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
/// // The root's left child is record 1, its right child record 4,
/// // stored as the offset 4 - 0; record 1's right child 3 as 3 - 1.
/// assert_eq!((pre.right(0), pre.records()[0].link()), (Some(4), 4));
/// assert_eq!((pre.right(1), pre.records()[1].link()), (Some(3), 2));
/// assert_eq!(core::mem::size_of::<PreNode<Aabb, u16>>(), 28);
/// # Ok::<(), bvhkit::Error>(())
/// ```
///
/// A tree of any size takes 16-bit links; the few links too far for them
/// go to a far table the caller sizes with
/// [`far_links_needed`](Self::far_links_needed):
///
/// ```
/// use bvhkit::layout::{FarLink, PreNode, Preorder, ESCAPE};
/// use bvhkit::{Aabb, Error, Hierarchy, Node, Query, TopDown};
/// use glam::Vec3;
/// // 33 000 points in [0, 1) and one far away: cut at the spatial middle,
/// // the root's left subtree holds 65 999 nodes, too many for 16 bits.
/// let mut pts: Vec<Vec3> = (0..33_000).map(|i| Vec3::new(i as f32 / 33_000.0, 0.0, 0.0)).collect();
/// pts.push(Vec3::new(100.0, 0.0, 0.0));
/// let builder = TopDown { split: bvhkit::SplitPoint::SpatialMedian, ..TopDown::median() };
/// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(pts.len())];
/// let mut idx = vec![0; pts.len()];
/// let bvh = builder.with_max_leaf_size(1).build(&pts, &mut nodes, &mut idx)?;
/// let mut recs = vec![PreNode::<Aabb, u16>::EMPTY; bvh.node_count()];
/// // Without a far table, the conversion says how many entries it needs.
/// let needed = Preorder::<Aabb, u16>::far_links_needed(&bvh)?;
/// assert_eq!(needed, 1);
/// assert_eq!(
///     Preorder::from_bvh(&bvh, &mut recs).unwrap_err(),
///     Error::FarLinkCapacity { needed: 1, available: 0 }
/// );
/// let mut far = vec![FarLink::EMPTY; needed];
/// let pre = Preorder::from_bvh_with_far(&bvh, &mut recs, &mut far)?;
/// assert_eq!(pre.records()[0].link(), ESCAPE);
/// assert_eq!(pre.far_links(), &[FarLink { record: 0, link: 66_000 }]);
/// assert_eq!(pre.right(0), Some(66_000));
/// let region = Aabb::new(Vec3::splat(-1.0), Vec3::new(0.0001, 1.0, 1.0));
/// assert_eq!(pre.overlapping(&pts, &region, |_| {})?, bvh.overlapping(&pts, &region, |_| {})?);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Preorder<'a, B, O> {
    records: &'a [PreNode<B, O>],
    /// `u16` links only: the links that escaped, sorted by record.
    far: &'a [FarLink],
    leaves: Leaves<'a>,
    /// `u16` links only: the ratio of [`predicted`].
    ratio: u64,
    depth: u32,
}

/// No limit on a 16-bit link beyond what its bits hold.
const FULL_REACH: usize = usize::MAX;

impl<'a, B: BoundingVolume, O: Offset> Preorder<'a, B, O> {
    /// Writes `bvh` in preorder into `out` (at least `bvh.node_count()`
    /// records), without a far table: with `u16` links, a tree that needs
    /// far links is an [`Error::FarLinkCapacity`] (use
    /// [`from_bvh_with_far`](Self::from_bvh_with_far)). A value beyond
    /// the link type (a `u32` index past `u32::MAX`, a `u16` leaf of more
    /// than 65 535 primitives) is an [`Error::FieldOverflow`], never a
    /// wrap-around. Nothing is written when it fails.
    pub fn from_bvh(bvh: &Bvh<'a, B>, out: &'a mut [PreNode<B, O>]) -> Result<Self, Error> {
        Self::convert(bvh, out, &mut [], FULL_REACH)
    }

    /// [`from_bvh`](Self::from_bvh) with a far table for the `u16` links
    /// that do not fit 16 bits: at least
    /// [`far_links_needed`](Self::far_links_needed) entries, else an
    /// [`Error::FarLinkCapacity`] before anything is written. `u32` links
    /// never use it.
    pub fn from_bvh_with_far(
        bvh: &Bvh<'a, B>,
        out: &'a mut [PreNode<B, O>],
        far: &'a mut [FarLink],
    ) -> Result<Self, Error> {
        Self::convert(bvh, out, far, FULL_REACH)
    }

    /// How many far-link entries converting `bvh` needs: 0 for `u32` links;
    /// for `u16`, the internal nodes whose right child is 65 535 or more
    /// records ahead and the leaves more than about 32 767 entries from
    /// their predicted start. A balanced tree of leaves of one primitive
    /// needs none up to 131 071 nodes and a handful beyond.
    pub fn far_links_needed(bvh: &Bvh<'_, B>) -> Result<usize, Error> {
        Self::far_links_needed_reaching(bvh, FULL_REACH)
    }

    /// [`far_links_needed`](Self::far_links_needed) for links that may
    /// reach at most `reach` (for tests: a small reach makes small trees
    /// escape). Not part of the stable API.
    #[doc(hidden)]
    pub fn far_links_needed_reaching(bvh: &Bvh<'_, B>, reach: usize) -> Result<usize, Error> {
        super::dense(bvh)?;
        crate::tree::hierarchy::check_query(bvh, bvh.primitive_count())?;
        if !O::RELATIVE {
            return Ok(0);
        }
        let ratio = ratio_of(bvh.primitive_count(), bvh.node_count());
        let mut needed = 0;
        walk(bvh, |visit| {
            let fits = match visit {
                Visit::Record { record, node } if node.is_leaf() => {
                    fit::<O>(node.count as usize, "leaf size of a preorder link")?;
                    let first = node.first as usize;
                    short_link(record, first, Some(predicted(record, ratio)), reach).is_some()
                }
                Visit::Record { .. } => true,
                Visit::Right { parent, right } => short_link(parent, right, None, reach).is_some(),
            };
            needed += usize::from(!fits);
            Ok(())
        })?;
        Ok(needed)
    }

    /// [`from_bvh_with_far`](Self::from_bvh_with_far) with links that may
    /// reach at most `reach` (for tests). Not part of the stable API.
    #[doc(hidden)]
    pub fn from_bvh_reaching(
        bvh: &Bvh<'a, B>,
        out: &'a mut [PreNode<B, O>],
        far: &'a mut [FarLink],
        reach: usize,
    ) -> Result<Self, Error> {
        Self::convert(bvh, out, far, reach)
    }

    fn convert(
        bvh: &Bvh<'a, B>,
        out: &'a mut [PreNode<B, O>],
        far: &'a mut [FarLink],
        reach: usize,
    ) -> Result<Self, Error> {
        super::dense(bvh)?;
        let count = bvh.node_count();
        check_capacity(count, out.len())?;
        crate::tree::hierarchy::check_query(bvh, bvh.primitive_count())?;
        let ratio = ratio_of(bvh.primitive_count(), count);
        // Fail before writing anything.
        if O::RELATIVE {
            let needed = Self::far_links_needed_reaching(bvh, reach)?;
            if far.len() < needed {
                return Err(Error::FarLinkCapacity {
                    needed,
                    available: far.len(),
                });
            }
        } else {
            // The largest links: the last record, the last leaf start.
            fit::<O>(count.saturating_sub(1), "node index of a preorder link")?;
            fit::<O>(
                bvh.primitive_count().saturating_sub(1),
                "leaf start of a preorder link",
            )?;
        }
        let mut used = 0;
        // The stored link from `record` to `target` (`leaf`: its predicted
        // start); a 16-bit one that does not fit escapes to the far table.
        let mut link = |record: usize, target: usize, leaf: Option<usize>| -> Result<O, Error> {
            if !O::RELATIVE {
                return fit(target, "link of a preorder record");
            }
            let short = short_link(record, target, leaf, reach);
            let stored = short.unwrap_or_else(|| {
                far[used] = FarLink {
                    record: record as u32,
                    link: target as u32,
                };
                used += 1;
                ESCAPE
            });
            fit(stored as usize, "16-bit preorder link")
        };
        let next = walk(bvh, |visit| {
            match visit {
                Visit::Record { record, node } => {
                    out[record] = if node.is_leaf() {
                        let leaf = Some(predicted(record, ratio));
                        PreNode {
                            bv: node.bv,
                            link: link(record, node.first as usize, leaf)?,
                            count: fit(node.count as usize, "leaf size of a preorder link")?,
                        }
                    } else {
                        PreNode {
                            bv: node.bv,
                            link: O::ZERO,
                            count: O::ZERO,
                        }
                    }
                }
                Visit::Right { parent, right } => out[parent].link = link(parent, right, None)?,
            }
            Ok(())
        })?;
        // Right links escape when the walk reaches the right child, after
        // later records' leaf links: sort for the binary search.
        far[..used].sort_unstable_by_key(|f| f.record);
        let records: &'a [PreNode<B, O>] = &out[..next];
        let far: &'a [FarLink] = &far[..used];
        Ok(Preorder {
            records,
            far,
            leaves: Leaves::of(bvh),
            ratio,
            depth: bvh.depth() as u32,
        })
    }

    /// The records in preorder.
    pub fn records(&self) -> &'a [PreNode<B, O>] {
        self.records
    }

    /// The links that did not fit 16 bits, sorted by record (none with
    /// `u32` links).
    pub fn far_links(&self) -> &'a [FarLink] {
        self.far
    }

    /// The record of the right child of the internal node at `record`;
    /// `None` for a leaf or past the end.
    pub fn right(&self, record: usize) -> Option<usize> {
        let r = self.records.get(record)?;
        r.has_left_child()
            .then(|| self.decode(record, r.link.get(), false))
    }

    /// The index (`u32`) or record (`u16`) a stored link names.
    #[inline(always)]
    fn decode(&self, record: usize, stored: usize, leaf: bool) -> usize {
        if !O::RELATIVE {
            stored
        } else if stored == ESCAPE as usize {
            self.far_link(record)
        } else if leaf {
            (predicted(record, self.ratio) + stored).wrapping_sub(LEAF_BIAS as usize)
        } else {
            record + stored
        }
    }

    /// The far link of `record`: a binary search of the sorted far table.
    #[cold]
    #[inline(never)]
    fn far_link(&self, record: usize) -> usize {
        let k = self
            .far
            .binary_search_by_key(&(record as u32), |f| f.record);
        // Every escaped record has its entry (the conversion wrote both);
        // the fallback is never taken.
        k.map_or(usize::MAX, |k| self.far[k].link as usize)
    }
}

/// `v` in a field of type `O`, or the overflow error naming `field`.
fn fit<O: Offset>(v: usize, field: &'static str) -> Result<O, Error> {
    O::new(v).ok_or(Error::FieldOverflow {
        field,
        value: v,
        max: O::MAX,
    })
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
            let right = self.decode(node as usize, r.link.get(), false);
            Content::Inner(Kids::two(node + 1, right as u32))
        } else {
            let first = self.decode(node as usize, r.link.get(), true);
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
        core::mem::size_of_val(self.records)
            + core::mem::size_of_val(self.far)
            + self.leaves.bytes()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The edges of the 16-bit encoding: the largest offset and the
    /// farthest leaf distances that fit, and the first ones that escape.
    #[test]
    fn short_links_fit_up_to_the_escape_and_no_further() {
        let full = FULL_REACH;
        assert_eq!(short_link(10, 10 + 65_534, None, full), Some(65_534));
        assert_eq!(short_link(10, 10 + 65_535, None, full), None);
        // A right child before its parent cannot be; it escapes, not wraps.
        assert_eq!(short_link(10, 9, None, full), None);
        let p = 100_000;
        assert_eq!(short_link(0, p - 32_768, Some(p), full), Some(0));
        assert_eq!(short_link(0, p - 32_769, Some(p), full), None);
        assert_eq!(short_link(0, p + 32_766, Some(p), full), Some(ESCAPE - 1));
        assert_eq!(short_link(0, p + 32_767, Some(p), full), None);
        assert_eq!(short_link(0, p, Some(p), full), Some(LEAF_BIAS));
        // A reach below the bits' own limit escapes earlier, both ways.
        assert_eq!(short_link(5, 8, None, 3), Some(3));
        assert_eq!(short_link(5, 9, None, 3), None);
        assert_eq!(short_link(0, p - 3, Some(p), 3), Some(LEAF_BIAS - 3));
        assert_eq!(short_link(0, p - 4, Some(p), 3), None);
    }

    /// The prediction is exact at both ends of a tree of leaves of one
    /// primitive: record 0 starts at entry 0, the last at about half.
    #[test]
    fn the_leaf_prediction_follows_the_primitives_per_record() {
        let r = ratio_of(1000, 1999);
        assert_eq!(predicted(0, r), 0);
        assert_eq!(predicted(1998, r), 999);
        // No overflow for the largest trees: u32::MAX primitives, one record each.
        let r = ratio_of(u32::MAX as usize, u32::MAX as usize);
        assert_eq!(predicted(u32::MAX as usize - 1, r), u32::MAX as usize - 1);
    }
}
