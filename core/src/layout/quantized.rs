//! Quantized 4-wide records: child boxes as 8-bit integers in the parent's frame.

use super::{fill_wide, wide::measure_depth, wide_walk, Leaves, MAX_LEAF_MERGE};
use crate::bv::{Aabb, BoundingVolume};
use crate::tree::{Bvh, Content, Hierarchy, Kids, MAX_CHILDREN};
use crate::Error;
use glam::Vec3;

/// Leaf-size value of an unused slot.
pub(crate) const UNUSED: u8 = u8::MAX;
/// Largest leaf a quantized slot can hold.
const MAX_LEAF: usize = UNUSED as usize - 1;

/// One quantized 4-wide record: 64 bytes, one cache line.
///
/// The children's boxes are stored as 8-bit grid coordinates: a coordinate
/// `q` on axis `k` stands for `origin[k] + q * 2^exp[k]`. The grid spans the
/// union of the children's boxes, and each child's box is rounded *outward*
/// to grid lines (checked by decoding it again), so the decoded box always
/// contains the exact one: quantized bounds are looser, never wrong.
/// `count[k]` is 0 for an internal child, 1..=254 for a leaf, 255 unused;
/// bits `2k, 2k+1` of `kids` hold an internal child's number of children
/// minus 2, so a query learns it without touching the child's record.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
pub struct QuantNode {
    pub(crate) origin: [f32; 3],
    pub(crate) exp: [i8; 3],
    pub(crate) kids: u8,
    pub(crate) lo: [[u8; MAX_CHILDREN]; 3],
    pub(crate) hi: [[u8; MAX_CHILDREN]; 3],
    pub(crate) child: [u32; MAX_CHILDREN],
    pub(crate) count: [u8; MAX_CHILDREN],
}

/// `2^e` for `e` in the normal `f32` range, exactly.
#[inline(always)]
fn pow2(e: i8) -> f32 {
    f32::from_bits(((e as i32 + 127) as u32) << 23)
}

impl QuantNode {
    /// A blank record, for initialising storage.
    pub const EMPTY: Self = QuantNode {
        origin: [0.0; 3],
        exp: [0; 3],
        kids: 0,
        lo: [[0; MAX_CHILDREN]; 3],
        hi: [[0; MAX_CHILDREN]; 3],
        child: [0; MAX_CHILDREN],
        count: [UNUSED; MAX_CHILDREN],
    };

    /// A record of zero bits, for `static` storage (`.bss`, no flash); see
    /// [`Node::ZERO`](crate::Node::ZERO).
    pub const ZERO: Self = QuantNode {
        count: [0; MAX_CHILDREN],
        ..QuantNode::EMPTY
    };

    /// Decodes one grid coordinate: the only formula queries use, so the
    /// encoder checks its roundings against exactly this.
    #[inline(always)]
    fn decode(&self, axis: usize, q: u8) -> f32 {
        self.origin[axis] + q as f32 * pow2(self.exp[axis])
    }

    /// The (conservative) box of slot `k`.
    #[inline(always)]
    pub fn slot_box(&self, k: usize) -> Aabb {
        Aabb::new(
            Vec3::new(
                self.decode(0, self.lo[0][k]),
                self.decode(1, self.lo[1][k]),
                self.decode(2, self.lo[2][k]),
            ),
            Vec3::new(
                self.decode(0, self.hi[0][k]),
                self.decode(1, self.hi[1][k]),
                self.decode(2, self.hi[2][k]),
            ),
        )
    }

    /// Encodes exact child boxes (all finite) into a record whose grid spans
    /// their union; each decoded box contains its exact box.
    pub fn encode(boxes: &[Aabb]) -> QuantNode {
        let mut r = QuantNode::EMPTY;
        let Some(first) = boxes.first() else {
            return r;
        };
        let frame = boxes.iter().fold(*first, |acc, b| acc.union(b));
        for axis in 0..3 {
            let (lo, hi) = (frame.min[axis], frame.max[axis]);
            r.origin[axis] = lo;
            // Smallest power of two whose 255 steps reach the frame's top.
            let span = (hi as f64 - lo as f64) / 255.0;
            let mut e: i32 = if span > 0.0 {
                libm::ceil(libm::log2(span)) as i32
            } else {
                -126
            };
            e = e.clamp(-126, 127);
            while e < 127 && {
                r.exp[axis] = e as i8;
                r.decode(axis, 255) < hi
            } {
                e += 1;
            }
            r.exp[axis] = e as i8;
            for (k, b) in boxes.iter().enumerate() {
                let step = pow2(r.exp[axis]) as f64;
                let qlo = libm::floor((b.min[axis] as f64 - lo as f64) / step).clamp(0.0, 255.0);
                let qhi = libm::ceil((b.max[axis] as f64 - lo as f64) / step).clamp(0.0, 255.0);
                let (mut qlo, mut qhi) = (qlo as u8, qhi as u8);
                while qlo > 0 && r.decode(axis, qlo) > b.min[axis] {
                    qlo -= 1;
                }
                while qhi < 255 && r.decode(axis, qhi) < b.max[axis] {
                    qhi += 1;
                }
                r.lo[axis][k] = qlo;
                r.hi[axis][k] = qhi;
            }
        }
        r
    }
}

/// Refuses a merge limit past what the merging walk handles.
fn check_merge(merge: u32) -> Result<(), Error> {
    if merge > MAX_LEAF_MERGE {
        return Err(Error::FieldOverflow {
            field: "merged leaf size of a quantized layout",
            value: merge as usize,
            max: MAX_LEAF_MERGE as usize,
        });
    }
    Ok(())
}

/// A 4-wide tree of [`QuantNode`]s, borrowing its storage: the [`Wide`]
/// collapse with 8-bit child boxes, about half the bytes per record, and
/// with every subtree of at most [`MERGED_LEAF`](Self::MERGED_LEAF)
/// primitives stored as one leaf slot (their index entries are one run), so
/// about half the records: with the index array, under 10 bytes per
/// triangle on the meshes of the peer benchmark (under obvhs's compressed
/// wide BVH, at 12.2 to 12.5). The looser boxes cost extra volume tests
/// and the merged leaves extra primitive tests (measured in the book). Node
/// ids are `record * 4 + slot`; record 0 holds only the root.
///
/// [`Wide`]: super::Wide
///
/// ```
/// use bvhkit::layout::{QuantNode, QuantizedWide};
/// use bvhkit::{Aabb, BoundingVolume, Hierarchy, Node, TopDown};
/// use glam::Vec3;
/// let pts: Vec<Vec3> = (0..64).map(|i| Vec3::new(i as f32 * 0.37, (i % 7) as f32, 0.0)).collect();
/// let mut nodes = vec![Node::<Aabb>::EMPTY; 127];
/// let mut idx = vec![0; 64];
/// let bvh = TopDown::default().build(&pts, &mut nodes, &mut idx)?;
/// let mut recs = vec![QuantNode::EMPTY; QuantizedWide::records_needed(&bvh)?];
/// let q = QuantizedWide::from_bvh(&bvh, &mut recs)?;
/// assert!(q.bv(0).contains_aabb(&bvh.root().unwrap().bv)); // rounded outward
/// assert_eq!(core::mem::size_of::<QuantNode>(), 64);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct QuantizedWide<'a> {
    records: &'a [QuantNode],
    leaves: Leaves<'a>,
    depth: u32,
    nodes: u32,
}

impl<'a> QuantizedWide<'a> {
    /// Most records a tree over `n` primitives can need: a header holding the
    /// root, then one per record of the collapse. A record that opens an inner
    /// child absorbs at least two inner nodes, so from three primitives on
    /// `n - 1` records suffice; two primitives in two leaves need two (the
    /// header and the root's record), one primitive one. A `const fn` to size
    /// `static` storage; [`records_needed`](Self::records_needed) gives the
    /// exact count of a built tree.
    ///
    /// ```
    /// use bvhkit::layout::{QuantizedWide, QuantNode};
    /// static mut RECORDS: [QuantNode; QuantizedWide::max_records(256)] = [QuantNode::ZERO; QuantizedWide::max_records(256)];
    /// assert_eq!(QuantizedWide::max_records(256), 255);
    /// ```
    pub const fn max_records(n: usize) -> usize {
        crate::Capacity::for_primitives(n).quantized_records
    }

    /// Subtrees of at most this many primitives that
    /// [`from_bvh`](Self::from_bvh) stores as one leaf slot (twice the
    /// default builder's leaf size). Without merging, records near the
    /// leaves hold two or three slots and a third of them more than the
    /// leaves need; merged, the armadillo's records take 5.6 bytes per
    /// triangle instead of 10.1, and pair queries got faster (measured in
    /// the book, "Tree representations").
    pub const MERGED_LEAF: u32 = 8;

    /// Most primitives [`from_bvh_merged`](Self::from_bvh_merged) merges into one leaf slot.
    pub const MAX_MERGED_LEAF: u32 = MAX_LEAF_MERGE;

    /// Records the collapse of `bvh` needs.
    pub fn records_needed<B: BoundingVolume>(bvh: &Bvh<'_, B>) -> Result<usize, Error> {
        Self::records_needed_merged(bvh, Self::MERGED_LEAF)
    }

    /// Records [`from_bvh_merged`](Self::from_bvh_merged) needs with the same `merge`.
    pub fn records_needed_merged<B: BoundingVolume>(
        bvh: &Bvh<'_, B>,
        merge: u32,
    ) -> Result<usize, Error> {
        check_merge(merge)?;
        wide_walk(bvh, merge, |_, _| Ok(()))
    }

    /// Collapses and quantizes `bvh` into `out` (at least
    /// [`records_needed`](Self::records_needed) records), merging subtrees
    /// of at most [`MERGED_LEAF`](Self::MERGED_LEAF) primitives into one
    /// leaf slot. A leaf of more than 254 primitives is an
    /// [`Error::FieldOverflow`].
    pub fn from_bvh<B: BoundingVolume>(
        bvh: &Bvh<'a, B>,
        out: &'a mut [QuantNode],
    ) -> Result<Self, Error> {
        Self::from_bvh_merged(bvh, Self::MERGED_LEAF, out)
    }

    /// [`from_bvh`](Self::from_bvh) with your own merge limit (at most
    /// [`MAX_MERGED_LEAF`](Self::MAX_MERGED_LEAF)): an internal node whose
    /// subtree holds at most `merge` primitives, contiguous in the index
    /// array (always so for the top-down builders), becomes one leaf slot
    /// over all of them. `0` merges nothing: the records then hold exactly
    /// the [`Wide`](super::Wide) collapse of `bvh`. Larger limits save
    /// records and cost primitive tests.
    ///
    /// ```
    /// use bvhkit::layout::{QuantNode, QuantizedWide};
    /// use bvhkit::{Aabb, Hierarchy, Node, TopDown};
    /// use glam::Vec3;
    /// let pts: Vec<Vec3> = (0..256).map(|i| Vec3::new(i as f32, (i * i % 17) as f32, 0.0)).collect();
    /// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(256)];
    /// let mut idx = vec![0; 256];
    /// let bvh = TopDown::default().build(&pts, &mut nodes, &mut idx)?;
    /// let mut plain = vec![QuantNode::EMPTY; QuantizedWide::records_needed_merged(&bvh, 0)?];
    /// let mut merged = vec![QuantNode::EMPTY; QuantizedWide::records_needed_merged(&bvh, 8)?];
    /// let plain = QuantizedWide::from_bvh_merged(&bvh, 0, &mut plain)?;
    /// let merged = QuantizedWide::from_bvh_merged(&bvh, 8, &mut merged)?;
    /// assert!(merged.bytes() < plain.bytes());
    /// assert_eq!(merged.primitive_count(), 256);
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn from_bvh_merged<B: BoundingVolume>(
        bvh: &Bvh<'a, B>,
        merge: u32,
        out: &'a mut [QuantNode],
    ) -> Result<Self, Error> {
        check_merge(merge)?;
        let (needed, count) = fill_wide(bvh, merge, out, |boxes, slots| {
            let mut r = QuantNode::encode(boxes);
            for (k, s) in slots.iter().enumerate() {
                if s.count as usize > MAX_LEAF {
                    return Err(Error::FieldOverflow {
                        field: "leaf size in a quantized record",
                        value: s.count as usize,
                        max: MAX_LEAF,
                    });
                }
                r.child[k] = s.link;
                r.count[k] = s.count as u8;
                if s.count == 0 {
                    r.kids |= (s.child_slots.saturating_sub(2) as u8 & 3) << (2 * k);
                }
            }
            Ok(r)
        })?;
        let records: &'a [QuantNode] = &out[..needed];
        let mut q = QuantizedWide {
            records,
            leaves: Leaves::of(bvh),
            depth: 0,
            nodes: count,
        };
        q.depth = measure_depth(&q)? as u32;
        Ok(q)
    }

    /// The records; record 0 holds the root.
    pub fn records(&self) -> &'a [QuantNode] {
        self.records
    }

    /// The layout over checked parts (a baked tree's, once
    /// [`from_baked`](Self::from_baked) has checked them), its depth
    /// measured here.
    pub(crate) fn from_checked(
        records: &'a [QuantNode],
        indices: &'a [u32],
        bounds: &'a [Aabb],
        nodes: usize,
    ) -> Result<Self, Error> {
        let mut q = QuantizedWide {
            records,
            leaves: Leaves::new(indices, bounds),
            depth: 0,
            nodes: nodes as u32,
        };
        q.depth = measure_depth(&q)? as u32;
        Ok(q)
    }

    /// The index array the leaves name runs of.
    pub fn indices(&self) -> &'a [u32] {
        self.leaves.indices()
    }

    /// The primitives' bounds in index order, when the tree keeps them.
    pub fn leaf_bounds(&self) -> Option<&'a [Aabb]> {
        self.leaves.kept()
    }
}

impl Hierarchy for QuantizedWide<'_> {
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
        if count != 0 {
            let first = link as usize;
            return Content::Leaf(self.leaves.ids(first, count as usize));
        }
        let base = link * 4;
        let len = 2 + ((r.kids >> (2 * k)) & 3) as usize;
        Content::Inner(Kids::new([base, base + 1, base + 2, base + 3], len))
    }

    #[inline(always)]
    fn is_leaf(&self, node: u32) -> bool {
        self.records[(node >> 2) as usize].count[(node & 3) as usize] != 0
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tree::Node;
    use crate::Query;

    /// Three points on a line, `x = 0, 1, 2`; node 1 holds points 0 and 2
    /// when `gap`, so its subtree's index entries are not one run.
    fn tree<'a>(nodes: &'a mut [Node<Aabb>; 5], gap: bool) -> Bvh<'a, Aabb> {
        let leaf = |first: u32, x: f32| Node {
            bv: Aabb::new(Vec3::new(x, 0.0, 0.0), Vec3::new(x, 0.0, 0.0)),
            first,
            count: 1,
        };
        let inner = |first: u32, lo: f32, hi: f32| Node {
            bv: Aabb::new(Vec3::new(lo, 0.0, 0.0), Vec3::new(hi, 0.0, 0.0)),
            first,
            count: 0,
        };
        // Index entries [0, 1, 2] name points 0, 1, 2.
        *nodes = if gap {
            // root -> (node 1 = {0, 2}, leaf {1}); node 1's entries 0 and 2.
            [
                inner(1, 0.0, 2.0),
                inner(3, 0.0, 2.0),
                leaf(1, 1.0),
                leaf(0, 0.0),
                leaf(2, 2.0),
            ]
        } else {
            // root -> (node 1 = {0, 1}, leaf {2}); node 1's entries 0 and 1.
            [
                inner(1, 0.0, 2.0),
                inner(3, 0.0, 1.0),
                leaf(2, 2.0),
                leaf(0, 0.0),
                leaf(1, 1.0),
            ]
        };
        Bvh::from_raw_parts(&nodes[..], &[0, 1, 2], 2)
    }

    /// The primitive counts of the leaves, in slot order.
    fn leaf_sizes(q: &QuantizedWide<'_>) -> [usize; 3] {
        let mut sizes = [0; 3];
        let mut k = 0;
        for node in 0..4 * q.records().len() as u32 {
            if q.records()[(node / 4) as usize].count[(node % 4) as usize] == UNUSED {
                continue;
            }
            if let Content::Leaf(ids) = q.content(node) {
                sizes[k] = ids.len();
                k += 1;
            }
        }
        sizes
    }

    const POINTS: [Vec3; 3] = [Vec3::ZERO, Vec3::X, Vec3::new(2.0, 0.0, 0.0)];

    #[test]
    fn a_subtree_whose_entries_are_not_one_run_stays_a_record() {
        let mut nodes = [Node::EMPTY; 5];
        let t = tree(&mut nodes, true);
        assert_eq!(super::super::run(&t, 1, 2), None);
        assert_eq!(super::super::run(&t, 2, 2), Some((1, 1))); // a leaf, always
                                                               // Nothing merged: the root's record takes node 1's children up.
        assert_eq!(QuantizedWide::records_needed_merged(&t, 2), Ok(2));
        let mut recs = [QuantNode::EMPTY; 2];
        let q = QuantizedWide::from_bvh_merged(&t, 2, &mut recs).unwrap();
        assert_eq!(leaf_sizes(&q), [1, 1, 1]);
        for (k, want) in [(0.0f32, 1), (1.0, 1), (2.0, 1)] {
            let probe = Aabb::new(Vec3::new(k, -1.0, -1.0), Vec3::new(k, 1.0, 1.0));
            let mut found = [false; 3];
            let n = q.overlapping(&POINTS, &probe, |i| found[i as usize] = true);
            assert_eq!(n, Ok(want));
            assert!(found[k as usize]);
        }
    }

    #[test]
    fn a_run_of_at_most_the_limit_becomes_one_leaf_slot() {
        let mut nodes = [Node::EMPTY; 5];
        let t = tree(&mut nodes, false);
        assert_eq!(super::super::run(&t, 1, 2), Some((0, 2)));
        assert_eq!(super::super::run(&t, 1, 1), None); // over the limit
        assert_eq!(super::super::run(&t, 0, 2), None); // the root holds 3
                                                       // Node 1 merged into one leaf slot beside leaf {2}.
        let mut recs = [QuantNode::EMPTY; 2];
        let q = QuantizedWide::from_bvh_merged(&t, 2, &mut recs).unwrap();
        assert_eq!(leaf_sizes(&q), [2, 1, 0]);
        assert_eq!(q.content(4), Content::Leaf(&[0, 1]));
        let q = QuantizedWide::from_bvh_merged(&t, 1, &mut recs).unwrap();
        assert_eq!(leaf_sizes(&q), [1, 1, 1]);
        // A limit of 3 takes the whole tree into the header's one slot.
        assert_eq!(QuantizedWide::records_needed_merged(&t, 3), Ok(1));
        let mut recs = [QuantNode::EMPTY; 1];
        let q = QuantizedWide::from_bvh_merged(&t, 3, &mut recs).unwrap();
        assert_eq!(q.content(0), Content::Leaf(&[0, 1, 2]));
        assert_eq!((q.depth(), q.node_count()), (0, 1));
        let probe = Aabb::new(Vec3::splat(-1.0), Vec3::splat(3.0));
        assert_eq!(q.overlapping(&POINTS, &probe, |_| {}), Ok(3));
    }

    #[test]
    fn merge_limits_past_the_walk_are_refused() {
        let mut nodes = [Node::EMPTY; 5];
        let t = tree(&mut nodes, false);
        let most = QuantizedWide::MAX_MERGED_LEAF;
        assert!(QuantizedWide::records_needed_merged(&t, most).is_ok());
        let err = QuantizedWide::records_needed_merged(&t, most + 1);
        assert!(matches!(err, Err(Error::FieldOverflow { max: 64, .. })));
    }

    #[test]
    fn encoded_boxes_contain_the_exact_ones_at_the_edges() {
        // A zero-size box, a box spanning the whole frame, boxes at 1e30 and
        // at denormal scale: each decoded box contains its exact box.
        let cases: [&[Aabb]; 3] = [
            &[
                Aabb::new(Vec3::ONE, Vec3::ONE),
                Aabb::new(Vec3::ZERO, Vec3::splat(3.0)),
            ],
            &[
                Aabb::new(Vec3::splat(-1.0e30), Vec3::splat(-0.5e30)),
                Aabb::new(Vec3::splat(0.25e30), Vec3::splat(1.0e30)),
            ],
            &[
                Aabb::new(Vec3::splat(1.0e-39), Vec3::splat(2.0e-39)),
                Aabb::new(Vec3::splat(3.0e-39), Vec3::splat(3.0e-39)),
            ],
        ];
        for boxes in cases {
            let r = QuantNode::encode(boxes);
            for (k, b) in boxes.iter().enumerate() {
                assert!(
                    r.slot_box(k).contains_aabb(b),
                    "{b:?} -> {:?}",
                    r.slot_box(k)
                );
            }
        }
    }
}
