//! Kinds 2 and 3: a [`Wide`] or [`QuantizedWide`] layout baked and opened
//! in place. One check serves both: it reads each record through
//! [`WideRecord`], which decodes a slot whichever way the record stores it.

use super::{bad, sound, Header, Kind, Plain, BOX_BYTES, HEADER_BYTES, KIND_QUANTIZED, KIND_WIDE};
use crate::bv::{Aabb, BoundingVolume};
use crate::layout::{quantized, wide, QuantNode, QuantizedWide, Wide, WideNode};
use crate::tree::validate::test_and_set;
use crate::tree::{Bvh, Hierarchy, MAX_CHILDREN, MAX_DEPTH};
use crate::Error;
use core::mem::{align_of, size_of};

/// Where the records start: the first multiple of their alignment (64)
/// after the header.
const RECORDS_AT: usize = 64;

const _: () = assert!(size_of::<WideNode>() == 128 && align_of::<WideNode>() == 64);
const _: () = assert!(size_of::<QuantNode>() == 64 && align_of::<QuantNode>() == 64);
const _: () = assert!(RECORDS_AT >= HEADER_BYTES && RECORDS_AT % 64 == 0);

/// Kind 2: 128-byte [`WideNode`] records from byte 64.
const WIDE: Kind = Kind {
    id: KIND_WIDE,
    first: RECORDS_AT,
    record: size_of::<WideNode>(),
};

/// Kind 3: 64-byte [`QuantNode`] records from byte 64.
const QUANTIZED: Kind = Kind {
    id: KIND_QUANTIZED,
    first: RECORDS_AT,
    record: size_of::<QuantNode>(),
};

// SAFETY: `repr(C, align(64))`: a `Boxes4` (`repr(C)`, 24 `f32`, 96 bytes),
// then two `[u32; 4]`: 128 bytes, no padding (asserted above); any bits
// make each field (a NaN box is a value, which the validation refuses).
#[allow(unsafe_code)]
unsafe impl Plain for WideNode {}
// SAFETY: `repr(C, align(64))`: `[f32; 3]`, `[i8; 3]`, `u8`, two
// `[[u8; 4]; 3]`, `[u32; 4]` (at offset 40, aligned), `[u8; 4]`: 60 bytes
// of fields and 4 of trailing padding, never read as a value. Any bits
// make each field (an exponent outside the normal range is a value, which
// the validation refuses).
#[allow(unsafe_code)]
unsafe impl Plain for QuantNode {}

/// A slot of a 4-wide record, decoded.
enum Slot {
    Unused,
    /// An internal child: the record holding its children, and how many.
    Inner {
        record: u32,
        children: usize,
    },
    /// A leaf: its run of the index array.
    Leaf {
        first: u32,
        count: u32,
    },
}

/// What the check and the writer need of a 4-wide record, whichever way it
/// stores its slots.
trait WideRecord: Plain {
    /// Whether honest records nest: each slot's box contains the boxes of
    /// the record it opens. True of exact boxes; quantized boxes are each
    /// rounded outward on their own record's grid, and a child's rounding
    /// can poke out of its parent's (seen on built trees).
    const NESTED: bool;
    /// Bytes of each record that no field covers (written zero, and
    /// refused unless zero, so that every byte of a baked tree means
    /// something).
    const PADDING: core::ops::Range<usize>;
    /// The record as little-endian words in the order of its bytes (the
    /// first `size / 4` of the array).
    fn words(&self) -> [u32; 32];
    fn slot(&self, k: usize) -> Slot;
    fn slot_box(&self, k: usize) -> Aabb;
    /// Whether the record's own fields besides its slots (a quantized
    /// record's grid) are sound.
    fn frame_sound(&self) -> bool {
        true
    }
}

impl WideRecord for WideNode {
    const NESTED: bool = true;
    const PADDING: core::ops::Range<usize> = 0..0;

    fn words(&self) -> [u32; 32] {
        let b = &self.boxes;
        let mut w = [0; 32];
        let lanes = b.min.iter().chain(&b.max).flatten().map(|x| x.to_bits());
        for (slot, v) in w.iter_mut().zip(lanes.chain(self.child).chain(self.count)) {
            *slot = v;
        }
        w
    }

    fn slot(&self, k: usize) -> Slot {
        match (self.child[k], self.count[k]) {
            (_, wide::UNUSED) => Slot::Unused,
            (record, c) if c & wide::INNER != 0 => Slot::Inner {
                record,
                children: (c & !wide::INNER) as usize,
            },
            (first, count) => Slot::Leaf { first, count },
        }
    }

    fn slot_box(&self, k: usize) -> Aabb {
        WideNode::slot_box(self, k)
    }
}

impl WideRecord for QuantNode {
    const NESTED: bool = false;
    const PADDING: core::ops::Range<usize> = 60..64;

    fn words(&self) -> [u32; 32] {
        let mut w = [0; 32];
        let [e0, e1, e2] = self.exp.map(|e| e as u8);
        let bytes = |rows: &[[u8; MAX_CHILDREN]; 3]| rows.map(u32::from_le_bytes);
        let head = self
            .origin
            .map(f32::to_bits)
            .into_iter()
            .chain([u32::from_le_bytes([e0, e1, e2, self.kids])]);
        let all = head
            .chain(bytes(&self.lo))
            .chain(bytes(&self.hi))
            .chain(self.child)
            .chain([u32::from_le_bytes(self.count), 0]);
        for (slot, v) in w.iter_mut().zip(all) {
            *slot = v;
        }
        w
    }

    fn slot(&self, k: usize) -> Slot {
        match (self.child[k], self.count[k]) {
            (_, quantized::UNUSED) => Slot::Unused,
            (record, 0) => Slot::Inner {
                record,
                children: 2 + ((self.kids >> (2 * k)) & 3) as usize,
            },
            (first, count) => Slot::Leaf {
                first,
                count: u32::from(count),
            },
        }
    }

    fn slot_box(&self, k: usize) -> Aabb {
        QuantNode::slot_box(self, k)
    }

    /// A finite origin and normal power-of-two steps (what `decode`
    /// computes exactly); the decoded boxes are checked on their own.
    fn frame_sound(&self) -> bool {
        self.origin.iter().all(|o| o.is_finite()) && self.exp.iter().all(|&e| e >= -126)
    }
}

/// Bytes of a baked 4-wide tree of `records` records over `primitives`
/// primitives, with or without the kept leaf bounds: a `const fn`, for
/// `static` buffers. [`Wide`] records are 128 bytes, [`QuantizedWide`]
/// records 64.
///
/// ```
/// use bvhkit::baked::wide_baked_len;
/// assert_eq!(wide_baked_len(2, 5, false), 64 + 2 * 128 + 5 * 4);
/// assert_eq!(wide_baked_len(2, 5, true), 64 + 2 * 128 + 5 * 28);
/// ```
pub const fn wide_baked_len(records: usize, primitives: usize, leaf_bounds: bool) -> usize {
    records_baked_len(&WIDE, records, primitives, leaf_bounds)
}

/// [`wide_baked_len`] for a [`QuantizedWide`] tree (64-byte records).
///
/// ```
/// use bvhkit::baked::quantized_baked_len;
/// assert_eq!(quantized_baked_len(2, 5, false), 64 + 2 * 64 + 5 * 4);
/// ```
pub const fn quantized_baked_len(records: usize, primitives: usize, leaf_bounds: bool) -> usize {
    records_baked_len(&QUANTIZED, records, primitives, leaf_bounds)
}

const fn records_baked_len(
    kind: &Kind,
    records: usize,
    primitives: usize,
    leaf_bounds: bool,
) -> usize {
    let per_primitive = if leaf_bounds { 4 + BOX_BYTES } else { 4 };
    kind.first
        .saturating_add(records.saturating_mul(kind.record))
        .saturating_add(primitives.saturating_mul(per_primitive))
}

/// Writes `records` and the leaves in `kind`'s format into `out`; returns
/// the bytes written, or an error (nothing written) when `out` is short.
fn bake<R: WideRecord>(
    kind: &Kind,
    records: &[R],
    indices: &[u32],
    kept: Option<&[Aabb]>,
    depth: usize,
    out: &mut [u8],
) -> Result<usize, Error> {
    let len = records_baked_len(kind, records.len(), indices.len(), kept.is_some());
    if out.len() < len {
        return Err(Error::ScratchCapacity {
            needed: len,
            available: out.len(),
        });
    }
    let per = kind.record / 4;
    let words = records.iter().flat_map(|r| r.words().into_iter().take(per));
    let counts = (records.len(), indices.len(), depth);
    super::write(&mut out[..len], kind, words, counts, indices, kept)?;
    Ok(len)
}

/// The checked parts of `bytes` in `kind`'s format: records, indices, kept
/// bounds, node count and the header's depth field.
type Opened<'a, R> = (&'a [R], &'a [u32], &'a [Aabb], usize, u32);

fn open<'a, R: WideRecord>(
    bytes: &'a [u8],
    kind: &Kind,
    seen: &mut [u32],
) -> Result<Opened<'a, R>, Error> {
    let h = Header::read(bytes, kind)?;
    let (records, indices, bounds) = h.arrays::<R>(bytes, kind)?;
    // `read` checked the length: the records' bytes are all there.
    let body = &bytes[kind.first..kind.first + records.len() * kind.record];
    for (r, record) in body.chunks_exact(kind.record).enumerate() {
        if let Some(at) = R::PADDING.clone().find(|&at| record[at] != 0) {
            return Err(bad(
                kind.first + r * kind.record + at,
                "a record's padding is not zero",
            ));
        }
    }
    let nodes = check_records(records, indices, bounds, seen)?;
    Ok((records, indices, bounds, nodes, h.depth))
}

/// The depth a layout measured, against the header's field.
fn check_depth(measured: usize, field: u32) -> Result<(), Error> {
    if measured > MAX_DEPTH {
        return Err(Error::InvalidTree("deeper than MAX_DEPTH"));
    }
    if measured != field as usize {
        return Err(bad(20, "the depth field differs from the tree's depth"));
    }
    Ok(())
}

impl<'a> Wide<'a> {
    /// Bytes [`bake`](Self::bake) writes for this tree.
    pub fn baked_len(&self) -> usize {
        wide_baked_len(
            self.records().len(),
            self.indices().len(),
            self.leaf_bounds().is_some(),
        )
    }

    /// Writes the records, the index array and the kept leaf bounds (if
    /// any) into `out` in the [baked format](crate::baked) (kind 2),
    /// little-endian on every host; returns the bytes written. `out`
    /// shorter than [`baked_len`](Self::baked_len) is an error and nothing
    /// is written.
    ///
    /// ```
    /// use bvhkit::baked::Aligned;
    /// use bvhkit::layout::{Wide, WideNode};
    /// use bvhkit::{Aabb, Node, Pairs, TopDown, Triangle};
    /// use glam::Vec3;
    /// let tris: Vec<Triangle> = (0..12).map(|i| {
    ///     let o = Vec3::new(i as f32 * 0.7, (i % 3) as f32, 0.0);
    ///     Triangle::new(o, o + Vec3::X, o + Vec3::Y)
    /// }).collect();
    /// let (mut nodes, mut idx) = ([Node::<Aabb>::ZERO; 23], [0u32; 12]);
    /// let tree = TopDown::default().with_max_leaf_size(2).build(&tris, &mut nodes, &mut idx)?;
    /// let mut records = [WideNode::ZERO; Wide::max_records(12)];
    /// let wide = Wide::from_bvh(&tree, &mut records)?;
    ///
    /// // On the host: bake.
    /// let mut bytes = Aligned([0u8; 2048]);
    /// let len = wide.bake(&mut bytes.0)?;
    ///
    /// // On the device: open in place (one validation pass), then query.
    /// let mut seen = [0u32; 1];
    /// let opened = Wide::from_baked(&bytes.0[..len], &mut seen)?;
    /// assert_eq!(opened.records(), wide.records());
    /// let pairs = Pairs::new(&opened, &tris, &opened, &tris).count()?;
    /// assert_eq!(pairs, Pairs::new(&tree, &tris, &tree, &tris).count()?);
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn bake(&self, out: &mut [u8]) -> Result<usize, Error> {
        let depth = Hierarchy::depth(self);
        bake(
            &WIDE,
            self.records(),
            self.indices(),
            self.leaf_bounds(),
            depth,
            out,
        )
    }

    /// Opens a [baked](crate::baked) 4-wide tree in place: no copy, the
    /// returned tree borrows `bytes`. Every field and the whole tree are
    /// checked first (see the [module notes](crate::baked)); `seen` is
    /// scratch of [`baked_seen_words`](Self::baked_seen_words) words. The
    /// bytes must be 64-byte aligned in memory
    /// ([`baked::Aligned`](crate::baked::Aligned) does it for
    /// `include_bytes!`).
    ///
    /// ```
    /// use bvhkit::baked::Aligned;
    /// use bvhkit::{layout::Wide, Error};
    /// // A binary tree's bytes (kind 1) are not a wide tree.
    /// let mut bytes = Aligned([0u8; 32]);
    /// bytes.0[..12].copy_from_slice(b"BVHK\x01\0\0\0\x01\0\0\0");
    /// let err = Wide::from_baked(&bytes.0, &mut []).unwrap_err();
    /// assert!(matches!(err, Error::BadBake { offset: 8, .. }));
    /// assert!(err.as_str().contains("Bvh::from_baked"));
    /// ```
    pub fn from_baked(bytes: &'a [u8], seen: &mut [u32]) -> Result<Self, Error> {
        let (records, indices, bounds, nodes, depth) = open(bytes, &WIDE, seen)?;
        let wide = Wide::from_checked(records, indices, bounds, nodes)?;
        check_depth(Hierarchy::depth(&wide), depth)?;
        Ok(wide)
    }

    /// Scratch words [`from_baked`](Self::from_baked) needs for `bytes`
    /// (from their header).
    pub fn baked_seen_words(bytes: &[u8]) -> Result<usize, Error> {
        let h = Header::read(bytes, &WIDE)?;
        Ok(Bvh::<Aabb>::seen_words(h.nodes, h.primitives))
    }
}

impl<'a> QuantizedWide<'a> {
    /// Bytes [`bake`](Self::bake) writes for this tree.
    pub fn baked_len(&self) -> usize {
        quantized_baked_len(
            self.records().len(),
            self.indices().len(),
            self.leaf_bounds().is_some(),
        )
    }

    /// [`Wide::bake`] for the quantized records (kind 3, 64 bytes a record:
    /// the grid's origin and exponents, the 8-bit boxes, links and counts as
    /// [`QuantNode`] lays them out, its four bytes of padding zero).
    ///
    /// ```
    /// use bvhkit::baked::Aligned;
    /// use bvhkit::layout::{QuantNode, QuantizedWide};
    /// use bvhkit::{Aabb, Node, Pairs, TopDown, Triangle};
    /// use glam::Vec3;
    /// let tris: Vec<Triangle> = (0..30).map(|i| {
    ///     let o = Vec3::new(i as f32 * 0.7, (i % 3) as f32, 0.0);
    ///     Triangle::new(o, o + Vec3::X, o + Vec3::Y)
    /// }).collect();
    /// let (mut nodes, mut idx) = ([Node::<Aabb>::ZERO; 59], [0u32; 30]);
    /// let tree = TopDown::default().with_max_leaf_size(1).build(&tris, &mut nodes, &mut idx)?;
    /// let mut records = [QuantNode::ZERO; QuantizedWide::max_records(30)];
    /// let q = QuantizedWide::from_bvh(&tree, &mut records)?;
    /// let mut bytes = Aligned([0u8; 4096]);
    /// let len = q.bake(&mut bytes.0)?;
    /// let opened = QuantizedWide::from_baked(&bytes.0[..len], &mut [0u32; 1])?;
    /// assert_eq!(opened.records(), q.records());
    /// assert_eq!(Pairs::new(&opened, &tris, &opened, &tris).count()?, Pairs::new(&tree, &tris, &tree, &tris).count()?);
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn bake(&self, out: &mut [u8]) -> Result<usize, Error> {
        let depth = Hierarchy::depth(self);
        bake(
            &QUANTIZED,
            self.records(),
            self.indices(),
            self.leaf_bounds(),
            depth,
            out,
        )
    }

    /// [`Wide::from_baked`] for a baked quantized tree (kind 3). Besides
    /// the wide checks, each record's grid must have a finite origin and
    /// normal steps. Decoded boxes need not nest (each is rounded outward
    /// on its own record's grid); with kept bounds, each kept box must lie
    /// inside every decoded box above it, which is what a query relies on.
    /// Without them, [`validate`](Self::validate) checks that against the
    /// primitives.
    pub fn from_baked(bytes: &'a [u8], seen: &mut [u32]) -> Result<Self, Error> {
        let (records, indices, bounds, nodes, depth) = open(bytes, &QUANTIZED, seen)?;
        let q = QuantizedWide::from_checked(records, indices, bounds, nodes)?;
        check_depth(Hierarchy::depth(&q), depth)?;
        // Decoded boxes need not nest; what queries need is each primitive
        // inside every box above it, checked here with the kept bounds.
        enclosed(&q, |node, clip| {
            Hierarchy::leaf_bounds(&q, node)
                .is_none_or(|kept| kept.iter().all(|b| clip.contains(b)))
        })?;
        Ok(q)
    }

    /// Scratch words [`from_baked`](Self::from_baked) needs for `bytes`
    /// (from their header).
    pub fn baked_seen_words(bytes: &[u8]) -> Result<usize, Error> {
        let h = Header::read(bytes, &QUANTIZED)?;
        Ok(Bvh::<Aabb>::seen_words(h.nodes, h.primitives))
    }

    /// Checks that this tree was built over `prims`: as many primitives,
    /// and each primitive's box inside every decoded box above it (what a
    /// query relies on to miss no overlap). A baked tree without kept
    /// bounds can only be checked this way, given its primitives.
    ///
    /// ```
    /// use bvhkit::layout::{QuantNode, QuantizedWide};
    /// use bvhkit::{Aabb, Node, TopDown, Triangle};
    /// use glam::Vec3;
    /// let mut tris: Vec<Triangle> = (0..20).map(|i| {
    ///     let o = Vec3::new(i as f32, 0.0, 0.0);
    ///     Triangle::new(o, o + Vec3::X, o + Vec3::Y)
    /// }).collect();
    /// let (mut nodes, mut idx) = (vec![Node::<Aabb>::ZERO; 39], vec![0u32; 20]);
    /// let tree = TopDown::default().build(&tris, &mut nodes, &mut idx)?;
    /// let mut records = vec![QuantNode::ZERO; QuantizedWide::max_records(20)];
    /// let q = QuantizedWide::from_bvh(&tree, &mut records)?;
    /// assert!(q.validate(&tris).is_ok());
    /// tris[3] = Triangle::new(Vec3::splat(50.0), Vec3::splat(51.0), Vec3::splat(52.0));
    /// assert!(q.validate(&tris).is_err()); // moved out of its boxes
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn validate<P: crate::Primitive>(&self, prims: &[P]) -> Result<(), Error> {
        validate_against(self, prims)
    }
}

impl Wide<'_> {
    /// [`QuantizedWide::validate`] for a 4-wide tree: built over `prims`,
    /// each primitive's box inside every box above it.
    ///
    /// ```
    /// use bvhkit::layout::{Wide, WideNode};
    /// use bvhkit::{Aabb, Node, TopDown};
    /// use glam::Vec3;
    /// let mut pts: Vec<Vec3> = (0..9).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
    /// let (mut nodes, mut idx) = (vec![Node::<Aabb>::ZERO; 17], vec![0u32; 9]);
    /// let tree = TopDown::default().build(&pts, &mut nodes, &mut idx)?;
    /// let mut records = vec![WideNode::ZERO; Wide::max_records(9)];
    /// let wide = Wide::from_bvh(&tree, &mut records)?;
    /// assert!(wide.validate(&pts).is_ok());
    /// pts[4].y = 1.0; // out of every box
    /// assert!(wide.validate(&pts).is_err());
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn validate<P: crate::Primitive>(&self, prims: &[P]) -> Result<(), Error> {
        validate_against(self, prims)
    }
}

/// Both layouts' `validate`.
fn validate_against<H: Hierarchy<Bv = Aabb>, P: crate::Primitive>(
    h: &H,
    prims: &[P],
) -> Result<(), Error> {
    if prims.len() != h.primitive_count() {
        return Err(Error::PrimitiveCountMismatch {
            tree: h.primitive_count(),
            given: prims.len(),
        });
    }
    enclosed(h, |node, clip| match h.content(node) {
        crate::Content::Leaf(ids) => ids.iter().all(|&i| {
            prims
                .get(i as usize)
                .is_some_and(|p| clip.contains(&p.bounds()))
        }),
        crate::Content::Inner(_) => true,
    })
}

/// Walks `h` depth first with the intersection of the boxes from the root
/// down (`clip`), and asks `leaf_ok(leaf, clip)` at each leaf: whether its
/// primitives lie in every box above them.
fn enclosed<H: Hierarchy<Bv = Aabb>>(
    h: &H,
    mut leaf_ok: impl FnMut(u32, &Aabb) -> bool,
) -> Result<(), Error> {
    use crate::query::stack::Stack;
    use crate::tree::hierarchy::DFS_STACK;
    if h.is_empty() {
        return Ok(());
    }
    let everything = Aabb::new(
        glam::Vec3::splat(f32::NEG_INFINITY),
        glam::Vec3::splat(f32::INFINITY),
    );
    let mut stack = Stack::<(u32, Aabb), DFS_STACK>::with((h.root(), everything), h.depth());
    while let Some((node, above)) = stack.pop() {
        // Disjoint boxes leave nothing a primitive could lie in.
        let clip = above.intersection(&h.bv(node)).unwrap_or(Aabb::EMPTY);
        match h.content(node) {
            crate::Content::Inner(kids) => {
                for &c in kids.as_slice() {
                    stack.push((c, clip))?;
                }
            }
            crate::Content::Leaf(_) if !leaf_ok(node, &clip) => {
                return Err(Error::InvalidTree(
                    "a primitive lies outside a box above it",
                ));
            }
            crate::Content::Leaf(_) => {}
        }
    }
    Ok(())
}

/// Slots in use at the front of `r` (a used slot after an unused one is an
/// error).
fn used_prefix<R: WideRecord>(r: &R) -> Result<usize, Error> {
    let used = (0..MAX_CHILDREN)
        .take_while(|&k| !matches!(r.slot(k), Slot::Unused))
        .count();
    if (used..MAX_CHILDREN).any(|k| !matches!(r.slot(k), Slot::Unused)) {
        return Err(Error::InvalidTree(
            "a wide record uses a slot after an unused one",
        ));
    }
    Ok(used)
}

/// The checks of `from_baked` once the bytes are arrays; returns the number
/// of nodes (slots in use). Records are visited in order: a record's parent
/// slot is in an earlier record, so by the time a record comes, it has been
/// reached (once) or never will be.
fn check_records<R: WideRecord>(
    records: &[R],
    indices: &[u32],
    kept: &[Aabb],
    seen: &mut [u32],
) -> Result<usize, Error> {
    let p = indices.len();
    if !kept.is_empty() && kept.len() != p {
        return Err(Error::PrimitiveCountMismatch {
            tree: p,
            given: kept.len(),
        });
    }
    // Node ids are `record * 4 + slot` in a `u32`.
    if records.len() > (u32::MAX / 4) as usize {
        return Err(Error::InvalidTree(
            "more records than u32 node ids can name",
        ));
    }
    if records.is_empty() {
        return match p {
            0 => Ok(0), // the empty tree
            _ => Err(Error::InvalidTree("no records")),
        };
    }
    let words = Bvh::<Aabb>::seen_words(records.len(), p);
    let Some(seen) = seen.get_mut(..words) else {
        return Err(Error::InvalidConfig(
            "validation scratch smaller than the layout's baked_seen_words",
        ));
    };
    seen.fill(0);
    // The header record holds the root alone.
    if used_prefix(&records[0])? != 1 {
        return Err(Error::InvalidTree("the first record holds not one root"));
    }
    let (mut nodes, mut leaf_slots) = (0usize, 0usize);
    for (i, r) in records.iter().enumerate() {
        if i > 0 && !test_and_set(seen, i) {
            return Err(Error::InvalidTree(
                "a record is not reachable from the root",
            ));
        }
        if !r.frame_sound() {
            return Err(Error::InvalidTree(
                "a quantized record's grid is not finite or its step not normal",
            ));
        }
        let used = used_prefix(r)?;
        nodes += used;
        for k in 0..used {
            let b = r.slot_box(k);
            if !sound(&b) {
                return Err(Error::InvalidTree(
                    "a node's box is not finite or is inverted",
                ));
            }
            match r.slot(k) {
                Slot::Unused => {} // not in the used prefix
                Slot::Inner { record, children } => {
                    let child = record as usize;
                    if child <= i || child >= records.len() {
                        return Err(Error::InvalidTree(
                            "child index out of range or not after its parent",
                        ));
                    }
                    // Marked as reached; its own turn comes later (child > i).
                    if test_and_set(seen, child) {
                        return Err(Error::InvalidTree("a node is reached twice"));
                    }
                    let rc = &records[child];
                    if children == 0 || children > MAX_CHILDREN || used_prefix(rc)? != children {
                        return Err(Error::InvalidTree(
                            "a slot's child count differs from its record's slots in use",
                        ));
                    }
                    if R::NESTED && !(0..children).all(|j| b.contains(&rc.slot_box(j))) {
                        return Err(Error::InvalidTree("a node does not contain its children"));
                    }
                }
                Slot::Leaf { first, count } => {
                    // In u64: on a 32-bit target `first + count` could wrap.
                    let end = u64::from(first) + u64::from(count);
                    if count == 0 || end > p as u64 {
                        return Err(Error::InvalidTree("leaf range outside the index array"));
                    }
                    leaf_slots += count as usize;
                    if let Some(leaf) = kept.get(first as usize..end as usize) {
                        if !leaf.iter().all(|k| sound(k) && b.contains(k)) {
                            return Err(Error::InvalidTree(
                                "a leaf does not contain its kept bounds",
                            ));
                        }
                    }
                }
            }
        }
    }
    if leaf_slots != p {
        return Err(Error::InvalidTree(
            "leaves do not cover the index array exactly",
        ));
    }
    // Each index entry in exactly one leaf (with the slot count equal to
    // the array's length, none twice means each once), then each primitive
    // exactly once.
    seen.fill(0);
    for r in records {
        for k in 0..MAX_CHILDREN {
            if let Slot::Leaf { first, count } = r.slot(k) {
                // Every leaf's run is within the array (checked above).
                for entry in first as usize..first as usize + count as usize {
                    if test_and_set(seen, entry) {
                        return Err(Error::InvalidTree("two leaves share an index entry"));
                    }
                }
            }
        }
    }
    seen.fill(0);
    for &q in indices {
        if q as usize >= p {
            return Err(Error::InvalidTree("primitive index out of range"));
        }
        if test_and_set(seen, q as usize) {
            return Err(Error::InvalidTree("a primitive appears twice"));
        }
    }
    Ok(nodes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::baked::Aligned;
    use crate::layout::wide::{INNER, UNUSED};

    const RECORD_BYTES: usize = 128;
    use crate::tree::Node;
    use crate::{Hierarchy, Pairs, Query, Ray, RayOrder, TopDown, Triangle};
    use glam::Vec3;

    const N: usize = 40;
    type Buf = Aligned<[u8; 8192]>;

    fn tris() -> [Triangle; N] {
        core::array::from_fn(|i| {
            let o = Vec3::new(
                (i % 7) as f32 * 0.8,
                (i / 7) as f32 * 0.8,
                (i % 3) as f32 * 0.3,
            );
            Triangle::new(o, o + Vec3::X, o + Vec3::Y)
        })
    }

    /// Bakes a wide tree over `tris()` (leaves of up to 2) into `out`, with or
    /// without kept bounds; returns the length.
    fn baked(kept: bool, out: &mut Buf) -> usize {
        let t = tris();
        let (mut nodes, mut idx) = ([Node::<Aabb>::ZERO; 2 * N], [0u32; N]);
        let mut bounds = [Aabb::ZERO; N];
        let mut records = [WideNode::ZERO; Wide::max_records(N)];
        let tree = TopDown::default()
            .with_max_leaf_size(2)
            .build(&t, &mut nodes, &mut idx)
            .unwrap();
        let tree = if kept {
            tree.with_leaf_bounds(&t, &mut bounds).unwrap()
        } else {
            tree
        };
        let wide = Wide::from_bvh(&tree, &mut records).unwrap();
        wide.bake(&mut out.0).unwrap()
    }

    fn copy(buf: &Buf, len: usize) -> Buf {
        let mut c = Aligned([0u8; 8192]);
        c.0[..len].copy_from_slice(&buf.0[..len]);
        c
    }

    /// Opened in place (the records are the bytes), it answers every pair
    /// and ray query as brute force does, and bakes to the same bytes.
    /// Miri runs this test over the in-place read.
    #[test]
    fn opens_in_place_and_answers_the_same() {
        let t = tris();
        for kept in [false, true] {
            let mut buf = Aligned([0u8; 8192]);
            let len = baked(kept, &mut buf);
            assert_eq!(len % 4, 0);
            let mut seen = [0u32; 2];
            assert_eq!(Wide::baked_seen_words(&buf.0[..len]).unwrap(), 2);
            let wide = Wide::from_baked(&buf.0[..len], &mut seen).unwrap();
            assert_eq!(
                wide.records().as_ptr().cast::<u8>(),
                buf.0[RECORDS_AT..].as_ptr()
            );
            assert_eq!(wide.leaf_bounds().is_some(), kept);
            assert_eq!(wide.baked_len(), len);
            assert_eq!(wide.primitive_count(), N);
            let brute = crate::query::brute_force::pairs(&t, &t, |_, _| {});
            assert!(brute > N);
            assert_eq!(Pairs::new(&wide, &t, &wide, &t).count().unwrap(), brute);
            let ray = Ray::new(Vec3::new(1.3, 1.1, 5.0), -Vec3::Z, f32::INFINITY).unwrap();
            let hit = Query::cast_ray(&wide, &t, &ray, RayOrder::DepthFirst, ());
            let want = crate::query::brute_force::ray_closest(&t, &ray);
            assert!(want.is_some());
            assert_eq!(hit.unwrap(), want);
            let mut again = [0u8; 8192];
            assert_eq!(wide.bake(&mut again).unwrap(), len);
            assert_eq!(again[..len], buf.0[..len]);
        }
    }

    #[test]
    fn an_empty_tree_bakes_and_answers_nothing() {
        let t: [Triangle; 0] = [];
        let (mut nodes, mut idx) = ([Node::<Aabb>::ZERO; 1], [0u32; 0]);
        let tree = TopDown::default().build(&t, &mut nodes, &mut idx).unwrap();
        let wide = Wide::from_bvh(&tree, &mut []).unwrap();
        let mut buf = Aligned([0u8; 8192]);
        let len = wide.bake(&mut buf.0).unwrap();
        assert_eq!(len, RECORDS_AT);
        let opened = Wide::from_baked(&buf.0[..len], &mut []).unwrap();
        assert!(opened.is_empty());
        assert_eq!(Pairs::new(&opened, &t, &opened, &t).count().unwrap(), 0);
    }

    #[test]
    fn a_short_buffer_or_a_misplaced_one_is_refused() {
        let mut buf = Aligned([0u8; 8192]);
        let len = baked(true, &mut buf);
        let mut seen = [0u32; 2];
        let wide = Wide::from_baked(&buf.0[..len], &mut seen).unwrap();
        let mut small = [7u8; 100];
        assert!(matches!(
            wide.bake(&mut small),
            Err(Error::ScratchCapacity { .. })
        ));
        assert!(small.iter().all(|&b| b == 7));
        // Four bytes on: 4-byte aligned (a binary tree would open) but not 64.
        let mut shifted = Aligned([0u8; 8192]);
        shifted.0[4..4 + len].copy_from_slice(&buf.0[..len]);
        let err = Wide::from_baked(&shifted.0[4..4 + len], &mut seen).unwrap_err();
        assert!(
            matches!(
                err,
                Error::BadBake {
                    offset: RECORDS_AT,
                    ..
                }
            ),
            "{err:?}"
        );
        // A kind 2 tree is not a binary tree.
        let err = Bvh::from_baked(&buf.0[..len], &mut seen).unwrap_err();
        assert!(err.as_str().contains("Wide::from_baked"), "{err:?}");
        // Padding, length and scratch.
        let mut c = copy(&buf, len);
        c.0[40] = 1;
        assert!(matches!(
            Wide::from_baked(&c.0[..len], &mut seen),
            Err(Error::BadBake { offset: 40, .. })
        ));
        assert!(matches!(
            Wide::from_baked(&buf.0[..len - 4], &mut seen),
            Err(Error::BadBake { offset: 12, .. })
        ));
        assert!(matches!(
            Wide::from_baked(&buf.0[..len], &mut [0u32; 1]),
            Err(Error::InvalidConfig(_))
        ));
    }

    /// Well-formed bytes that are not a valid tree, each refused with its
    /// reason.
    #[test]
    fn structural_and_geometric_lies_are_refused() {
        let mut buf = Aligned([0u8; 8192]);
        let len = baked(true, &mut buf);
        let mut seen = [0u32; 2];
        let wide = Wide::from_baked(&buf.0[..len], &mut seen).unwrap();
        let records = wide.records();
        assert!(records.len() > 3);
        // Byte offsets within the bytes: record r's min.x of slot k, its
        // link and count of slot k.
        let rec = |r: usize| RECORDS_AT + r * RECORD_BYTES;
        let min_x = |r: usize, k: usize| rec(r) + 4 * k;
        let max_x = |r: usize, k: usize| rec(r) + 48 + 4 * k;
        let link = |r: usize, k: usize| rec(r) + 96 + 4 * k;
        let count = |r: usize, k: usize| rec(r) + 112 + 4 * k;
        // Record 1 (the root's) and its first internal and leaf slots.
        let r1 = &records[1];
        let used = used_prefix(r1).unwrap();
        let inner = (0..used).find(|&k| r1.count[k] & INNER != 0).unwrap();
        let leaf = (0..records.len())
            .flat_map(|r| (0..4).map(move |k| (r, k)))
            .find(|&(r, k)| records[r].count[k] & INNER == 0)
            .unwrap();
        let child = r1.child[inner] as usize;
        let indices_at = rec(records.len());
        let w = |v: u32| v.to_le_bytes();
        let kept_at = indices_at + 4 * N;
        let cases: [(usize, [u8; 4], &str); 13] = [
            // The root slot pointing at its own record.
            (link(0, 0), w(0), "after its parent"),
            // A link past the last record.
            (link(1, inner), w(records.len() as u32), "out of range"),
            // Two slots opening the same record.
            (link(1, used - 1), w(child as u32), "twice"),
            // A child count that differs from the record's slots in use.
            (
                count(1, inner),
                w(INNER | ((r1.count[inner] & 3) + 1)),
                "child count",
            ),
            // A slot marked unused before a used one.
            (count(1, 0), w(UNUSED), "after an unused"),
            // The root record with two slots.
            (count(0, 1), w(1), "one root"),
            // A NaN box, an inverted one.
            (min_x(1, 0), f32::NAN.to_bits().to_le_bytes(), "finite"),
            (max_x(1, 0), (-1e30f32).to_bits().to_le_bytes(), "inverted"),
            // The root's box shrunk: it no longer holds its children.
            (max_x(0, 0), 1.0f32.to_bits().to_le_bytes(), "contain"),
            // A leaf's run past the index array.
            (link(leaf.0, leaf.1), w(N as u32), "outside the index array"),
            // The first index entry naming another primitive (now twice).
            (indices_at, w(wide.indices()[0] ^ 1), "twice"),
            // A kept bound grown out of its leaf's box.
            (
                kept_at + 12,
                100.0f32.to_bits().to_le_bytes(),
                "kept bounds",
            ),
            // The depth field off by one.
            (20, w(wide.depth() as u32 + 1), "depth"),
        ];
        for (at, bytes, what) in cases {
            let mut c = copy(&buf, len);
            c.0[at..at + 4].copy_from_slice(&bytes);
            match Wide::from_baked(&c.0[..len], &mut seen) {
                Err(err) => assert!(err.as_str().contains(what), "{what}: {err:?}"),
                Ok(_) => panic!("{what}: opened"),
            }
        }
    }

    /// No byte string panics: every prefix, and every byte of a real tree
    /// flipped three ways, either opens as a valid tree that answers a
    /// query to the end, or is refused.
    #[test]
    fn no_corruption_panics() {
        let t = tris();
        let mut buf = Aligned([0u8; 8192]);
        let len = baked(true, &mut buf);
        let mut seen = [0u32; 2];
        for cut in 0..len {
            assert!(Wide::from_baked(&buf.0[..cut], &mut seen).is_err());
        }
        let mut opened = 0;
        for at in 0..len {
            for mask in [0x01u8, 0x80, 0xFF] {
                let mut c = copy(&buf, len);
                c.0[at] ^= mask;
                if let Ok(wide) = Wide::from_baked(&c.0[..len], &mut seen) {
                    opened += 1;
                    assert!(Pairs::new(&wide, &t, &wide, &t).count().is_ok());
                }
            }
        }
        // Flips in box bits that keep every box sound and nested open.
        assert!(opened > 0 && opened < 3 * len);
    }
}
#[cfg(test)]
mod quantized_tests {
    use super::*;
    use crate::baked::Aligned;
    use crate::tree::Node;
    use crate::{Pairs, TopDown, Triangle};
    use glam::Vec3;

    const N: usize = 60;

    fn scene(seed: u64) -> [Triangle; N] {
        let mut next = crate::test_floats(seed);
        // A table, not `powi`: Miri perturbs `powi` afresh on each call.
        let scale = [1e-3, 1e-2, 0.1, 1.0, 10.0, 100.0, 1e3][(seed % 7) as usize];
        // Near the origin and far from it (a grid origin of 2.5e6 with steps
        // of 1e-3 leaves few bits for the grid).
        let far = [17.3, -4.0e4, 2.5e6][(seed % 5 % 3) as usize];
        core::array::from_fn(|_| {
            let o = Vec3::new(next(), next(), next()) * 5.0 * scale + Vec3::splat(far);
            let mut c = || o + Vec3::new(next(), next(), next()) * scale;
            Triangle::new(c(), c(), c())
        })
    }

    /// Bakes the quantized tree of `scene(seed)` (leaves and merge limit
    /// varying with the seed) into `out`; returns the length.
    fn baked(seed: u64, kept: bool, out: &mut Aligned<[u8; 16384]>) -> usize {
        let t = scene(seed);
        let (mut nodes, mut idx) = ([Node::<Aabb>::ZERO; 2 * N], [0u32; N]);
        let mut bounds = [Aabb::EMPTY; N];
        let leaf = 1 + (seed % 4) as u32;
        let tree = TopDown::default()
            .with_max_leaf_size(leaf)
            .build(&t, &mut nodes, &mut idx)
            .unwrap();
        let tree = if kept {
            tree.with_leaf_bounds(&t, &mut bounds).unwrap()
        } else {
            tree
        };
        let mut recs = [QuantNode::ZERO; N];
        let q = QuantizedWide::from_bvh_merged(&tree, (seed % 3) as u32 * 4, &mut recs).unwrap();
        q.bake(&mut out.0).unwrap()
    }

    /// Built trees at scales from 1e-3 to 1e3, near the origin and up to
    /// 2.5e6 from it, open, though their decoded
    /// boxes do not always nest (a nesting check refused each of the first five
    /// seeds), answer as brute force, and validate against their triangles.
    #[test]
    fn honest_quantized_trees_open_though_their_boxes_do_not_nest() {
        for seed in 1..120u64 {
            let t = scene(seed);
            let brute = crate::query::brute_force::pairs(&t, &t, |_, _| {});
            for kept in [false, true] {
                let mut buf = Aligned([0u8; 16384]);
                let len = baked(seed, kept, &mut buf);
                let q = QuantizedWide::from_baked(&buf.0[..len], &mut [0u32; 4])
                    .unwrap_or_else(|e| panic!("seed {seed}, kept {kept}: {e}"));
                assert_eq!(
                    q.records().as_ptr().cast::<u8>(),
                    buf.0[RECORDS_AT..].as_ptr()
                );
                assert_eq!(q.leaf_bounds().is_some(), kept);
                assert_eq!(q.baked_len(), len);
                q.validate(&t).unwrap();
                assert_eq!(
                    Pairs::new(&q, &t, &q, &t).count().unwrap(),
                    brute,
                    "seed {seed}"
                );
                let mut again = [0u8; 16384];
                assert_eq!(q.bake(&mut again).unwrap(), len);
                assert_eq!(again[..len], buf.0[..len]);
            }
        }
    }

    /// Lies about the grid, the child counts and the kept bounds, each
    /// refused with its reason; the wrong primitives fail `validate`.
    #[test]
    fn quantized_lies_are_refused() {
        let mut buf = Aligned([0u8; 16384]);
        let seed = 4; // leaves of 1, nothing merged: every slot kind
        let len = baked(seed, true, &mut buf);
        let q = QuantizedWide::from_baked(&buf.0[..len], &mut [0u32; 4]).unwrap();
        let records = q.records();
        let rec = |r: usize| RECORDS_AT + r * 64;
        let inner = (0..4).find(|&k| records[1].count[k] == 0).unwrap();
        let kept_at = rec(records.len()) + 4 * N;
        let cases: [(usize, &[u8], &str); 7] = [
            // An exponent below the normal range, a NaN origin.
            (rec(1) + 12, &[(-127i8) as u8], "step not normal"),
            (
                rec(1),
                &f32::NAN.to_bits().to_le_bytes(),
                "grid is not finite",
            ),
            // Child-count bits saying 5 children.
            (rec(1) + 15, &[3 << (2 * inner)], "child count"),
            // A slot count of 255 (unused) before used ones.
            (rec(1) + 56, &[255], "after an unused"),
            // A kept box moved far from its leaf.
            (kept_at, &1.0e6f32.to_bits().to_le_bytes(), "kept"),
            // Nonzero padding at the end of a record; a record count the
            // length does not match.
            (rec(2) + 60, &[1], "padding"),
            (12, &[0xFF, 0xFF, 0xFF, 0x0F], "length"),
        ];
        for (at, bytes, what) in cases {
            let mut c = Aligned([0u8; 16384]);
            c.0[..len].copy_from_slice(&buf.0[..len]);
            c.0[at..at + bytes.len()].copy_from_slice(bytes);
            match QuantizedWide::from_baked(&c.0[..len], &mut [0u32; 4]) {
                Err(e) => assert!(e.as_str().contains(what), "{what}: {e:?}"),
                Ok(_) => panic!("{what}: opened"),
            }
        }
        let mut moved = scene(seed);
        moved[7] = Triangle::new(Vec3::splat(-90.0), Vec3::splat(-91.0), Vec3::splat(-92.0));
        assert!(q.validate(&moved).is_err());
        assert!(q.validate(&moved[..N - 1]).is_err());
        // Bytes of one kind are not another.
        let err = Wide::from_baked(&buf.0[..len], &mut [0u32; 4]).unwrap_err();
        assert!(
            err.as_str().contains("QuantizedWide::from_baked"),
            "{err:?}"
        );
    }

    /// The in-place read on one small tree, for Miri.
    #[test]
    fn quantized_opens_in_place() {
        for kept in [false, true] {
            let mut buf = Aligned([0u8; 16384]);
            let len = baked(4, kept, &mut buf);
            let q = QuantizedWide::from_baked(&buf.0[..len], &mut [0u32; 4]).unwrap();
            assert_eq!(
                q.records().as_ptr().cast::<u8>(),
                buf.0[RECORDS_AT..].as_ptr()
            );
            q.validate(&scene(4)).unwrap();
        }
    }

    /// Every prefix refused; every byte flipped three ways either refused
    /// or opened as a tree a query runs to the end on.
    #[test]
    fn no_quantized_corruption_panics() {
        let mut buf = Aligned([0u8; 16384]);
        let len = baked(5, true, &mut buf);
        let t = scene(5);
        let mut seen = [0u32; 4];
        for cut in 0..len {
            assert!(QuantizedWide::from_baked(&buf.0[..cut], &mut seen).is_err());
        }
        let mut opened = 0;
        for at in 0..len {
            for mask in [0x01u8, 0x80, 0xFF] {
                let mut c = Aligned([0u8; 16384]);
                c.0[..len].copy_from_slice(&buf.0[..len]);
                c.0[at] ^= mask;
                if let Ok(q) = QuantizedWide::from_baked(&c.0[..len], &mut seen) {
                    opened += 1;
                    assert!(Pairs::new(&q, &t, &q, &t).count().is_ok());
                }
            }
        }
        assert!(opened > 0 && opened < 3 * len);
    }
}
