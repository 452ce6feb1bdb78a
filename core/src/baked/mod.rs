//! Baked trees: built once on a host, stored as bytes, queried where they
//! land without a rebuild and without a copy.
//!
//! Lecture: *efficient tree representation*, offsets instead of pointers. A
//! [`Bvh`] names its children and primitives by array offsets, never by
//! address, so its arrays mean the same thing wherever they sit. Written out
//! as they are, they can be read back in place: on a microcontroller the
//! bytes stay in flash (`include_bytes!`), and opening the tree costs one
//! validation pass and no RAM for nodes.
//!
//! # Format, version 1
//!
//! Little-endian; every field 4 bytes, so every array starts 4-byte aligned.
//!
//! | offset | bytes | field |
//! |---|---|---|
//! | 0 | 4 | magic, the ASCII bytes `BVHK` |
//! | 4 | 4 | version, 1 |
//! | 8 | 4 | kind: 1 = binary tree of axis-aligned boxes; 2 = 4-wide records ([`Wide`](crate::layout::Wide)), 3 = quantized 4-wide records (see below) |
//! | 12 | 4 | node count `n` |
//! | 16 | 4 | primitive count `p` (entries of the index array) |
//! | 20 | 4 | depth (edges from the root to the deepest leaf) |
//! | 24 | 4 | flags: bit 0 = the primitives' bounds follow the indices |
//! | 28 | 4 | reserved, 0 |
//! | 32 | 32 `n` | nodes: `min.xyz`, `max.xyz` (`f32`), `first`, `count` (`u32`), as [`Node`] |
//! | 32 + 32 `n` | 4 `p` | primitive indices in leaf order |
//! | 32 + 36 `n`... | 24 `p` | with flag bit 0: each index entry's primitive bounds, as [`Aabb`] |
//!
//! The length must be exactly what the counts say. [`Bvh::from_baked`]
//! refuses anything else with [`Error::BadBake`] (naming the byte), and then
//! checks the tree as [`Bvh::validate`] does, minus the primitives it does
//! not have: every node reached once from the root, children after their
//! parent, each primitive in exactly one leaf, every box finite and
//! containing its children's boxes and its leaf's kept bounds, and the depth
//! field equal to the depth found. No byte string makes it panic or read out
//! of bounds. Whether the tree was built over *your* primitives it cannot
//! know: [`Bvh::validate`] checks that, given them.
//!
//! # Kind 2: a 4-wide tree
//!
//! A [`Wide`](crate::layout::Wide) layout (feature `layouts`) bakes with
//! the same header, kind 2, the record count in place of the node count.
//! Its records are 64-byte aligned, so they start at byte 64 (bytes 32 to
//! 63 are zero); each is 128 bytes, as [`WideNode`](crate::layout::WideNode)
//! lays them out: the four slots' `min.x`, then `min.y`, `min.z`, `max.x`,
//! `max.y`, `max.z` (four `f32` each), then four `u32` links and four `u32`
//! counts (`2^31 + c` for an internal slot whose record has `c` slots in
//! use, the primitive count of a leaf, `u32::MAX` for an unused slot). The
//! index array and the optional bounds follow as in kind 1.
//! [`Wide::from_baked`](crate::layout::Wide::from_baked) checks the same
//! things in the wide form: every record reached once, from a slot of an
//! earlier record; used slots first in each record, as many as the slot
//! that opens the record says; every box finite and inside its parent slot's
//! box; every primitive in exactly one leaf.
//!
//! # Kind 3: a quantized 4-wide tree
//!
//! A [`QuantizedWide`](crate::layout::QuantizedWide) layout bakes as kind 3,
//! laid out as kind 2 but with 64-byte records as
//! [`QuantNode`](crate::layout::QuantNode) lays them out: the grid's origin
//! (three `f32`), its three exponents (`i8`) and the child-count bits, the
//! 8-bit low and high grid coordinates (`lo[axis][slot]`, then `hi`), four
//! `u32` links, four `u8` counts (0 internal, 255 unused, else a leaf's
//! size), then four bytes of padding, zero. Besides the kind 2 checks, every
//! origin must be finite and every step a normal power of two. Decoded
//! boxes are not required to nest: each is rounded outward on its own
//! record's grid, and built trees have children that poke out of their
//! parent's rounding. What a query relies on, every primitive inside every
//! box above it, is checked against the kept bounds when the tree has them,
//! and by [`QuantizedWide::validate`](crate::layout::QuantizedWide::validate)
//! given the primitives.

#[cfg(feature = "layouts")]
mod wide;
#[cfg(feature = "layouts")]
pub use wide::{quantized_baked_len, wide_baked_len};

use crate::builders::BuildReport;
use crate::bv::{Aabb, BoundingVolume};
use crate::tree::{validate, Bvh, Node};
use crate::Error;
use core::mem::{align_of, size_of};

/// The first four bytes of every baked tree.
pub const MAGIC: [u8; 4] = *b"BVHK";
/// The format version this crate writes and reads.
pub const VERSION: u32 = 1;
/// Bytes before the node array.
pub const HEADER_BYTES: usize = 32;
/// Kind 1: a binary tree of [`Aabb`] nodes.
const KIND_AABB_BINARY: u32 = 1;
/// Kind 2: a 4-wide tree of [`WideNode`](crate::layout::WideNode) records.
const KIND_WIDE: u32 = 2;
/// Kind 3: a quantized 4-wide tree of [`QuantNode`](crate::layout::QuantNode) records.
const KIND_QUANTIZED: u32 = 3;
/// Flag bit: the primitives' bounds follow the indices.
const FLAG_LEAF_BOUNDS: u32 = 1;

const NODE_BYTES: usize = 32;
const BOX_BYTES: usize = 24;
// The in-place read relies on these layouts (see `Plain`).
const _: () = assert!(size_of::<Node<Aabb>>() == NODE_BYTES && align_of::<Node<Aabb>>() == 4);
const _: () = assert!(size_of::<Aabb>() == BOX_BYTES && align_of::<Aabb>() == 4);

/// Bytes with the alignment a baked tree needs (4 for a binary tree, 64
/// for the records of a 4-wide one; 64 also keeps each node in one cache
/// line). `include_bytes!` gives bytes aligned to 1, so wrap them:
///
/// ```
/// use bvhkit::baked::Aligned;
/// static TREE: &Aligned<[u8]> = &Aligned([0u8; 32]); // include_bytes!("tree.bin") in a firmware
/// assert_eq!(TREE.0.as_ptr() as usize % 64, 0);
/// ```
#[repr(C, align(64))]
#[derive(Debug)]
pub struct Aligned<T: ?Sized>(pub T);

/// Bytes of a baked tree of `nodes` nodes over `primitives` primitives, with
/// or without the kept leaf bounds: a `const fn`, for `static` buffers.
///
/// ```
/// use bvhkit::baked::{baked_len, HEADER_BYTES};
/// assert_eq!(baked_len(3, 2, false), HEADER_BYTES + 3 * 32 + 2 * 4);
/// assert_eq!(baked_len(3, 2, true), HEADER_BYTES + 3 * 32 + 2 * 28);
/// ```
pub const fn baked_len(nodes: usize, primitives: usize, leaf_bounds: bool) -> usize {
    let per_primitive = if leaf_bounds { 4 + BOX_BYTES } else { 4 };
    // Saturating, like every sizing function: no count makes it panic.
    HEADER_BYTES
        .saturating_add(nodes.saturating_mul(NODE_BYTES))
        .saturating_add(primitives.saturating_mul(per_primitive))
}

/// What a kind of tree puts after the header: its number in the kind
/// field, where its records start and how long each is.
struct Kind {
    id: u32,
    first: usize,
    record: usize,
}

/// Kind 1: [`Node<Aabb>`] records right after the header.
const BINARY: Kind = Kind {
    id: KIND_AABB_BINARY,
    first: HEADER_BYTES,
    record: NODE_BYTES,
};

/// The header fields, checked against the length of the bytes.
struct Header {
    /// Records (nodes of a binary tree).
    nodes: usize,
    primitives: usize,
    depth: u32,
    leaf_bounds: bool,
}

fn bad(offset: usize, what: &'static str) -> Error {
    Error::BadBake { offset, what }
}

fn word(bytes: &[u8], at: usize) -> u32 {
    let mut w = [0u8; 4];
    if let Some(b) = bytes.get(at..at + 4) {
        w.copy_from_slice(b);
    }
    u32::from_le_bytes(w)
}

impl Header {
    fn read(bytes: &[u8], kind: &Kind) -> Result<Header, Error> {
        if bytes.len() < HEADER_BYTES {
            return Err(bad(bytes.len(), "shorter than the 32-byte header"));
        }
        if bytes[..4] != MAGIC {
            return Err(bad(0, "no BVHK magic"));
        }
        if word(bytes, 4) != VERSION {
            return Err(bad(4, "a format version this crate does not read"));
        }
        match word(bytes, 8) {
            k if k == kind.id => {}
            KIND_AABB_BINARY => return Err(bad(8, "a binary tree: open it with Bvh::from_baked")),
            KIND_WIDE => return Err(bad(8, "a 4-wide tree: open it with Wide::from_baked")),
            KIND_QUANTIZED => {
                return Err(bad(
                    8,
                    "a quantized 4-wide tree: open it with QuantizedWide::from_baked",
                ))
            }
            _ => return Err(bad(8, "a tree kind this crate does not read")),
        }
        let flags = word(bytes, 24);
        if flags & !FLAG_LEAF_BOUNDS != 0 {
            return Err(bad(24, "unknown flag bits"));
        }
        if word(bytes, 28) != 0 {
            return Err(bad(28, "the reserved word is not zero"));
        }
        let h = Header {
            nodes: word(bytes, 12) as usize,
            primitives: word(bytes, 16) as usize,
            depth: word(bytes, 20),
            leaf_bounds: flags & FLAG_LEAF_BOUNDS != 0,
        };
        // Counts come from the file: compute the length without overflow.
        let per_primitive = if h.leaf_bounds { 4 + BOX_BYTES } else { 4 };
        let want = h
            .nodes
            .checked_mul(kind.record)
            .zip(h.primitives.checked_mul(per_primitive))
            .and_then(|(n, p)| n.checked_add(p))
            .and_then(|np| np.checked_add(kind.first));
        if want != Some(bytes.len()) {
            return Err(bad(12, "the counts do not match the length of the bytes"));
        }
        // Between the header and the records: padding, zero.
        if let Some(at) = (HEADER_BYTES..kind.first).find(|&at| bytes[at] != 0) {
            return Err(bad(at, "the padding before the records is not zero"));
        }
        Ok(h)
    }

    /// The record array, the index array and the kept bounds of `bytes`
    /// (whose header this is), read in place.
    fn arrays<'a, R: Plain>(&self, bytes: &'a [u8], kind: &Kind) -> Result<Arrays<'a, R>, Error> {
        if cfg!(target_endian = "big") {
            return Err(bad(
                0,
                "baked trees open in place on little-endian targets only",
            ));
        }
        // `read` checked the length: every range is in bounds.
        let indices_at = kind.first + self.nodes * kind.record;
        let bounds_at = indices_at + self.primitives * 4;
        Ok((
            cast(&bytes[kind.first..indices_at], kind.first)?,
            cast(&bytes[indices_at..bounds_at], indices_at)?,
            cast(&bytes[bounds_at..], bounds_at)?,
        ))
    }
}

/// A baked tree's arrays: its records, its index array, its kept bounds
/// (empty when it keeps none).
type Arrays<'a, R> = (&'a [R], &'a [u32], &'a [Aabb]);

/// Writes the words of a baked tree: the header, zero padding up to the
/// records, each record's words, the indices and the kept bounds. `out`
/// holds exactly the bytes the counts say (the caller checked).
fn write(
    out: &mut [u8],
    kind: &Kind,
    records: impl IntoIterator<Item = u32>,
    counts: (usize, usize, usize),
    indices: &[u32],
    kept: Option<&[Aabb]>,
) -> Result<(), Error> {
    let count = |n: usize| u32::try_from(n).map_err(|_| Error::IndexOverflow { count: n });
    let header = [
        u32::from_le_bytes(MAGIC),
        VERSION,
        kind.id,
        count(counts.0)?,
        count(counts.1)?,
        count(counts.2)?,
        if kept.is_some() { FLAG_LEAF_BOUNDS } else { 0 },
        0,
    ];
    let mut words = out.chunks_exact_mut(4);
    let mut put = |w: u32| {
        if let Some(slot) = words.next() {
            slot.copy_from_slice(&w.to_le_bytes());
        }
    };
    header.into_iter().for_each(&mut put);
    (HEADER_BYTES..kind.first).step_by(4).for_each(|_| put(0));
    records.into_iter().for_each(&mut put);
    indices.iter().copied().for_each(&mut put);
    for b in kept.unwrap_or(&[]) {
        box_words(b).into_iter().for_each(&mut put);
    }
    Ok(())
}

/// A box as six words: `min.xyz`, `max.xyz`.
fn box_words(b: &Aabb) -> [u32; 6] {
    let (lo, hi) = (b.min, b.max);
    [lo.x, lo.y, lo.z, hi.x, hi.y, hi.z].map(f32::to_bits)
}

/// Types whose every bit pattern is a valid value, with no padding bytes.
///
/// # Safety
///
/// Implement only for such types: [`cast`] reads them from arbitrary bytes.
// SAFETY: only declares the contract above; each `unsafe impl` below
// states why its type keeps it.
#[allow(unsafe_code)]
unsafe trait Plain: Copy {}

// SAFETY: four bytes, any of which make a `u32`.
#[allow(unsafe_code)]
unsafe impl Plain for u32 {}
// SAFETY: `repr(C)`, two glam `Vec3` (each `repr(C)`, three `f32`): 24
// bytes, no padding (asserted above); any bits are an `f32` (NaN included,
// which the validation refuses: a value, not undefined behaviour).
#[allow(unsafe_code)]
unsafe impl Plain for Aabb {}
// SAFETY: `repr(C)`, an `Aabb` then two `u32`: 32 bytes, alignment 4, no
// padding (asserted above); any bits make each field.
#[allow(unsafe_code)]
unsafe impl Plain for Node<Aabb> {}

/// `bytes` read in place as `T`s, or an error if they are not aligned for
/// `T` or not a whole number of them.
fn cast<T: Plain>(bytes: &[u8], offset: usize) -> Result<&[T], Error> {
    if (bytes.as_ptr() as usize) % align_of::<T>() != 0 {
        let what = match align_of::<T>() {
            4 => "not 4-byte aligned in memory (wrap the bytes in baked::Aligned)",
            _ => "not 64-byte aligned in memory (wrap the bytes in baked::Aligned)",
        };
        return Err(bad(offset, what));
    }
    if bytes.len() % size_of::<T>() != 0 {
        return Err(bad(offset, "an array of partial records"));
    }
    // SAFETY: the pointer is aligned for `T` (checked above) and valid for
    // reads of `bytes.len()` initialised bytes, exactly `len / size_of::<T>()`
    // values (checked above), for the lifetime of `bytes`, which the result
    // borrows; nothing writes them while it lives (a shared borrow); and
    // `T: Plain` makes any bytes a valid `T`.
    #[allow(unsafe_code)]
    let values = unsafe {
        core::slice::from_raw_parts(bytes.as_ptr().cast::<T>(), bytes.len() / size_of::<T>())
    };
    Ok(values)
}

impl<'a> Bvh<'a, Aabb> {
    /// Bytes [`bake`](Self::bake) writes for this tree.
    pub fn baked_len(&self) -> usize {
        baked_len(
            self.node_count(),
            self.indices().len(),
            self.leaf_bounds().is_some(),
        )
    }

    /// Writes the tree (and its kept leaf bounds, if any) into `out` in the
    /// [baked format](crate::baked), little-endian on every host; returns
    /// the bytes written. `out` shorter than [`baked_len`](Self::baked_len)
    /// is an error and nothing is written.
    ///
    /// ```
    /// use bvhkit::{baked, Aabb, Bvh, Node, Pairs, TopDown, Triangle};
    /// use glam::Vec3;
    /// let tris: Vec<Triangle> = (0..6).map(|i| {
    ///     let o = Vec3::new(i as f32 * 0.7, 0.0, 0.0);
    ///     Triangle::new(o, o + Vec3::X, o + Vec3::Y)
    /// }).collect();
    /// let (mut nodes, mut idx) = ([Node::<Aabb>::ZERO; 11], [0u32; 6]);
    /// let tree = TopDown::default().with_max_leaf_size(2).build(&tris, &mut nodes, &mut idx)?;
    ///
    /// // On the host: bake.
    /// let mut bytes = baked::Aligned([0u8; 512]);
    /// let len = tree.bake(&mut bytes.0)?;
    /// assert_eq!(len, tree.baked_len());
    ///
    /// // On the device: open in place (one validation pass), then query.
    /// let mut seen = [0u32; 1];
    /// let opened = Bvh::from_baked(&bytes.0[..len], &mut seen)?;
    /// assert_eq!(opened.nodes(), tree.nodes());
    /// let pairs = Pairs::new(&opened, &tris, &opened, &tris).count()?;
    /// assert_eq!(pairs, Pairs::new(&tree, &tris, &tree, &tris).count()?);
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn bake(&self, out: &mut [u8]) -> Result<usize, Error> {
        // The format names primitives 0..p, each once (as every builder
        // numbers them); a tree naming ids with gaps would not open again.
        if self.index_bound() != self.indices().len() {
            return Err(Error::InvalidTree(
                "only trees over primitives 0..n bake (this one names ids with gaps)",
            ));
        }
        let len = self.baked_len();
        if out.len() < len {
            return Err(Error::ScratchCapacity {
                needed: len,
                available: out.len(),
            });
        }
        let nodes = self
            .nodes()
            .iter()
            .flat_map(|n| box_words(&n.bv).into_iter().chain([n.first, n.count]));
        let counts = (self.node_count(), self.indices().len(), self.depth());
        write(
            &mut out[..len],
            &BINARY,
            nodes,
            counts,
            self.indices(),
            self.leaf_bounds(),
        )?;
        Ok(len)
    }

    /// Opens a [baked](crate::baked) tree in place: no copy, the returned
    /// tree borrows `bytes`. Every field and the whole tree are checked
    /// first (see the [module notes](crate::baked)); `seen` is scratch of
    /// [`baked_seen_words`](Self::baked_seen_words) words. The bytes must be
    /// 4-byte aligned in memory ([`baked::Aligned`](crate::baked::Aligned)
    /// does it for `include_bytes!`).
    ///
    /// ```
    /// use bvhkit::{Bvh, Error};
    /// let mut seen = [0u32; 1];
    /// let not_a_tree = bvhkit::baked::Aligned(*b"BVHX____________________________");
    /// assert!(matches!(Bvh::from_baked(&not_a_tree.0, &mut seen), Err(Error::BadBake { offset: 0, .. })));
    /// ```
    pub fn from_baked(bytes: &'a [u8], seen: &mut [u32]) -> Result<Self, Error> {
        let h = Header::read(bytes, &BINARY)?;
        let (nodes, indices, bounds) = h.arrays::<Node<Aabb>>(bytes, &BINARY)?;
        let depth = check(nodes, indices, bounds, seen)?;
        if depth != h.depth as usize {
            return Err(bad(20, "the depth field differs from the tree's depth"));
        }
        Ok(Bvh::from_kept(
            nodes,
            indices,
            bounds,
            depth,
            indices.len(),
            BuildReport::default(),
        ))
    }

    /// Scratch words [`from_baked`](Self::from_baked) needs for `bytes`
    /// (from their header), so a host can size it; a firmware knows its
    /// counts and uses [`Bvh::seen_words`] in a `const`.
    pub fn baked_seen_words(bytes: &[u8]) -> Result<usize, Error> {
        let h = Header::read(bytes, &BINARY)?;
        Ok(Bvh::<Aabb>::seen_words(h.nodes, h.primitives))
    }
}

/// The checks [`Bvh::from_baked`] makes once the bytes are read as arrays,
/// for parts from anywhere (a file format of your own, a network):
/// `nodes` from the root at 0, the index array, and either no kept bounds
/// or one per index entry. Every node reached exactly once from the root,
/// with its children after it; every index entry in exactly one leaf and
/// every primitive in exactly one entry; every box finite, not inverted,
/// containing its children's boxes and its leaf's kept bounds; depth at
/// most [`MAX_DEPTH`](crate::tree::MAX_DEPTH). Returns the depth. `seen`
/// is scratch of [`Bvh::seen_words`] words.
///
/// ```
/// use bvhkit::{baked, Aabb, Node};
/// use glam::Vec3;
/// let b = Aabb::new(Vec3::ZERO, Vec3::ONE);
/// let leaf = |first| Node { bv: b, first, count: 1 };
/// let root = Node { bv: b, first: 1, count: 0 };
/// let mut seen = [0u32; 1];
/// assert_eq!(baked::check(&[root, leaf(0), leaf(1)], &[1, 0], &[], &mut seen), Ok(1));
/// // Both leaves on entry 0: primitive 0 twice over, primitive 1 never.
/// assert!(baked::check(&[root, leaf(0), leaf(0)], &[1, 0], &[], &mut seen).is_err());
/// ```
pub fn check(
    nodes: &[Node<Aabb>],
    indices: &[u32],
    kept: &[Aabb],
    seen: &mut [u32],
) -> Result<usize, Error> {
    if !kept.is_empty() && kept.len() != indices.len() {
        return Err(Error::PrimitiveCountMismatch {
            tree: indices.len(),
            given: kept.len(),
        });
    }
    let depth = validate::structure(nodes, indices, indices.len(), seen)?;
    check_boxes(nodes, kept)?;
    Ok(depth as usize)
}

/// Finite on every axis and not inverted: a box a baked node may hold.
fn sound(b: &Aabb) -> bool {
    b.min.is_finite() && b.max.is_finite() && b.min.cmple(b.max).all()
}

/// The geometric half of the check, without primitives: every box sound,
/// each internal node's box containing its children's, each leaf's box
/// containing its kept bounds.
fn check_boxes(nodes: &[Node<Aabb>], kept: &[Aabb]) -> Result<(), Error> {
    for n in nodes {
        if !sound(&n.bv) {
            return Err(Error::InvalidTree(
                "a node's box is not finite or is inverted",
            ));
        }
        match n.children() {
            Some((l, r)) => {
                // `structure` checked both children in range.
                let inside = |c: u32| nodes.get(c as usize).is_some_and(|c| n.bv.contains(&c.bv));
                if !inside(l) || !inside(r) {
                    return Err(Error::InvalidTree("a node does not contain its children"));
                }
            }
            None if !kept.is_empty() => {
                let range = n.first as usize..n.first as usize + n.count as usize;
                let Some(leaf) = kept.get(range) else {
                    return Err(Error::InvalidTree("leaf range outside the kept bounds"));
                };
                if !leaf.iter().all(|b| sound(b) && n.bv.contains(b)) {
                    return Err(Error::InvalidTree(
                        "a leaf does not contain its kept bounds",
                    ));
                }
            }
            None => {}
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Pairs, TopDown, Triangle};
    use glam::Vec3;

    fn tris() -> [Triangle; 9] {
        core::array::from_fn(|i| {
            let o = Vec3::new((i % 3) as f32 * 0.8, (i / 3) as f32 * 0.8, i as f32 * 0.05);
            Triangle::new(o, o + Vec3::X, o + Vec3::Y)
        })
    }

    /// A baked copy of a tree over `tris()` with leaves of up to 2, with or
    /// without kept bounds.
    fn baked(kept: bool, out: &mut Aligned<[u8; 1024]>) -> usize {
        let t = tris();
        let (mut nodes, mut idx, mut bounds) = ([Node::ZERO; 17], [0u32; 9], [Aabb::ZERO; 9]);
        let tree = TopDown::default()
            .with_max_leaf_size(2)
            .build(&t, &mut nodes, &mut idx)
            .unwrap();
        let tree = if kept {
            tree.with_leaf_bounds(&t, &mut bounds).unwrap()
        } else {
            tree
        };
        tree.bake(&mut out.0).unwrap()
    }

    /// The tree opens in place (its nodes are the bytes, not a copy) and
    /// answers as the tree it was baked from; this is the test Miri runs.
    #[test]
    fn opens_in_place_and_answers_the_same() {
        let t = tris();
        for kept in [false, true] {
            let mut buf = Aligned([0u8; 1024]);
            let len = baked(kept, &mut buf);
            let mut seen = [0u32; 1];
            assert_eq!(Bvh::baked_seen_words(&buf.0[..len]).unwrap(), 1);
            let tree = Bvh::from_baked(&buf.0[..len], &mut seen).unwrap();
            assert_eq!(
                tree.nodes().as_ptr().cast::<u8>(),
                buf.0[HEADER_BYTES..].as_ptr()
            );
            assert_eq!(tree.leaf_bounds().is_some(), kept);
            assert_eq!(tree.baked_len(), len);
            tree.validate(&t, &mut seen).unwrap();
            let mut brute = 0;
            for a in &t {
                for b in &t {
                    brute += usize::from(
                        crate::Primitive::bounds(a).overlaps(&crate::Primitive::bounds(b)),
                    );
                }
            }
            assert_eq!(Pairs::new(&tree, &t, &tree, &t).count().unwrap(), brute);
            // Baked again, the bytes are the same.
            let mut again = [0u8; 1024];
            assert_eq!(tree.bake(&mut again).unwrap(), len);
            assert_eq!(again[..len], buf.0[..len]);
        }
    }

    /// A tree whose leaves name ids with gaps (as a dynamic tree's can)
    /// would not open again: refused when baking, nothing written.
    #[test]
    fn trees_with_id_gaps_do_not_bake() {
        let b = Aabb::new(Vec3::ZERO, Vec3::ONE);
        let nodes = [
            Node {
                bv: b,
                first: 1,
                count: 0,
            },
            Node {
                bv: b,
                first: 0,
                count: 1,
            },
            Node {
                bv: b,
                first: 1,
                count: 1,
            },
        ];
        let tree = Bvh::from_raw_parts(&nodes, &[0, 5], 1);
        let mut out = Aligned([9u8; 256]);
        assert!(matches!(tree.bake(&mut out.0), Err(Error::InvalidTree(_))));
        assert!(out.0.iter().all(|&x| x == 9));
        let dense = Bvh::from_raw_parts(&nodes, &[1, 0], 1);
        let len = dense.bake(&mut out.0).unwrap();
        assert!(Bvh::from_baked(&out.0[..len], &mut [0u32; 1]).is_ok());
    }

    #[test]
    fn an_empty_tree_bakes_and_answers_nothing() {
        let t: [Triangle; 0] = [];
        let (mut nodes, mut idx) = ([Node::<Aabb>::ZERO; 1], [0u32; 0]);
        let tree = TopDown::default().build(&t, &mut nodes, &mut idx).unwrap();
        let mut buf = Aligned([0u8; 64]);
        let len = tree.bake(&mut buf.0).unwrap();
        assert_eq!(len, HEADER_BYTES);
        let opened = Bvh::from_baked(&buf.0[..len], &mut []).unwrap();
        assert!(opened.is_empty());
        assert_eq!(Pairs::new(&opened, &t, &opened, &t).count().unwrap(), 0);
    }

    #[test]
    fn a_short_buffer_is_refused_and_left_alone() {
        let mut buf = Aligned([0u8; 1024]);
        let len = baked(true, &mut buf);
        let t = tris();
        let (mut nodes, mut idx) = ([Node::ZERO; 17], [0u32; 9]);
        let tree = TopDown::default().build(&t, &mut nodes, &mut idx).unwrap();
        let mut small = [7u8; 40];
        assert!(matches!(
            tree.bake(&mut small),
            Err(Error::ScratchCapacity { .. })
        ));
        assert!(small.iter().all(|&b| b == 7));
        assert!(len > 40);
    }

    /// Each header field refused with its own offset.
    #[test]
    fn every_header_field_is_checked() {
        let mut buf = Aligned([0u8; 1024]);
        let len = baked(true, &mut buf);
        let mut seen = [0u32; 1];
        let offset_of = |bytes: &[u8], seen: &mut [u32]| match Bvh::from_baked(bytes, seen) {
            Err(Error::BadBake { offset, .. }) => offset,
            other => panic!("{other:?}"),
        };
        for (at, value) in [
            (0usize, 0x42u32),
            (4, 2),
            (8, 7),
            (24, 3),
            (28, 1),
            (12, 18),
            (16, 8),
            (20, 9),
        ] {
            let mut copy = Aligned([0u8; 1024]);
            copy.0[..len].copy_from_slice(&buf.0[..len]);
            copy.0[at..at + 4].copy_from_slice(&value.to_le_bytes());
            // A wrong primitive count shows as a length mismatch (the counts' field).
            let want = if at == 16 { 12 } else { at };
            assert_eq!(offset_of(&copy.0[..len], &mut seen), want, "field at {at}");
        }
        // Counts so large that the length overflows.
        let mut copy = Aligned([0u8; 1024]);
        copy.0[..len].copy_from_slice(&buf.0[..len]);
        copy.0[12..20].copy_from_slice(&[0xFF; 8]);
        assert_eq!(offset_of(&copy.0[..len], &mut seen), 12);
        // Short of a header, one byte too long, one too short.
        assert_eq!(offset_of(&buf.0[..31], &mut seen), 31);
        assert_eq!(offset_of(&buf.0[..len + 1], &mut seen), 12);
        assert_eq!(offset_of(&buf.0[..len - 1], &mut seen), 12);
        // Misaligned in memory: the same bytes one further on.
        let mut shifted = Aligned([0u8; 1025]);
        shifted.0[1..=len].copy_from_slice(&buf.0[..len]);
        assert_eq!(offset_of(&shifted.0[1..=len], &mut seen), HEADER_BYTES);
        // Scratch too small.
        assert!(matches!(
            Bvh::from_baked(&buf.0[..len], &mut []),
            Err(Error::InvalidConfig(_))
        ));
    }

    /// Trees that are well-formed bytes but not valid trees.
    #[test]
    fn structural_and_geometric_lies_are_refused() {
        let mut buf = Aligned([0u8; 1024]);
        let len = baked(true, &mut buf);
        let mut seen = [0u32; 1];
        let node = |k: usize| HEADER_BYTES + k * NODE_BYTES;
        let patch = |at: usize, bytes: &[u8]| {
            let mut copy = Aligned([0u8; 1024]);
            copy.0[..len].copy_from_slice(&buf.0[..len]);
            copy.0[at..at + bytes.len()].copy_from_slice(bytes);
            copy
        };
        let tree = Bvh::from_baked(&buf.0[..len], &mut seen).unwrap();
        let root_first = tree.nodes()[0].first;
        let leaf = tree.nodes().iter().position(|n| n.is_leaf()).unwrap();
        let cases: [(usize, &[u8], &str); 5] = [
            // The root's first child pointing at the root itself.
            (node(0) + 24, &0u32.to_le_bytes(), "child"),
            // The root's box shrunk to a point: it no longer contains its children.
            (node(0) + 12, &[0; 12], "contain"),
            // A NaN in a leaf's box.
            (node(leaf), &f32::NAN.to_bits().to_le_bytes(), "finite"),
            // The first index entry naming primitive 1 (now named twice).
            (
                node(tree.node_count()),
                &(tree.indices()[0] ^ 1).to_le_bytes(),
                "twice",
            ),
            // The depth field one less than the tree's depth.
            (20, &(tree.depth() as u32 - 1).to_le_bytes(), "depth"),
        ];
        assert!(root_first > 0);
        for (at, bytes, what) in cases {
            let copy = patch(at, bytes);
            let err = Bvh::from_baked(&copy.0[..len], &mut seen).unwrap_err();
            let message = err.as_str();
            assert!(message.contains(what), "{what}: {err:?}");
        }
    }

    /// No byte string panics: every prefix, and every byte of a real tree
    /// flipped in two ways, either opens as a valid tree or is refused.
    #[test]
    fn no_corruption_panics() {
        let t = tris();
        let mut buf = Aligned([0u8; 1024]);
        let len = baked(true, &mut buf);
        let mut seen = [0u32; 1];
        for cut in 0..len {
            assert!(Bvh::from_baked(&buf.0[..cut], &mut seen).is_err());
        }
        for at in 0..len {
            for mask in [0x01u8, 0x80, 0xFF] {
                let mut copy = Aligned([0u8; 1024]);
                copy.0[..len].copy_from_slice(&buf.0[..len]);
                copy.0[at] ^= mask;
                if let Ok(tree) = Bvh::from_baked(&copy.0[..len], &mut seen) {
                    // Opened: its structure holds and a query runs to the end.
                    assert!(Pairs::new(&tree, &t, &tree, &t).count().is_ok());
                }
            }
        }
    }
}
