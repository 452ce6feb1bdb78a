//! Kind 2: a [`Wide`] layout baked and opened in place.

use super::{bad, sound, Header, Kind, Plain, BOX_BYTES, HEADER_BYTES, KIND_WIDE};
use crate::bv::{Aabb, BoundingVolume};
use crate::layout::wide::{INNER, UNUSED};
use crate::layout::{Wide, WideNode};
use crate::tree::validate::test_and_set;
use crate::tree::{Bvh, MAX_CHILDREN, MAX_DEPTH};
use crate::Error;
use core::mem::{align_of, size_of};

/// Bytes of one record.
const RECORD_BYTES: usize = 128;
/// Where the records start: the first multiple of their alignment after
/// the header.
const RECORDS_AT: usize = 64;

const _: () = assert!(size_of::<WideNode>() == RECORD_BYTES && align_of::<WideNode>() == 64);
const _: () = assert!(RECORDS_AT >= HEADER_BYTES && RECORDS_AT % align_of::<WideNode>() == 0);

/// Kind 2: 128-byte records from byte 64.
const WIDE: Kind = Kind {
    id: KIND_WIDE,
    first: RECORDS_AT,
    record: RECORD_BYTES,
};

// SAFETY: `repr(C, align(64))`: a `Boxes4` (`repr(C)`, 24 `f32`, 96 bytes),
// then two `[u32; 4]`: 128 bytes, no padding (asserted above); any bits
// make each field (a NaN box is a value, which the validation refuses).
#[allow(unsafe_code)]
unsafe impl Plain for WideNode {}

/// Bytes of a baked 4-wide tree of `records` records over `primitives`
/// primitives, with or without the kept leaf bounds: a `const fn`, for
/// `static` buffers.
///
/// ```
/// use bvhkit::baked::wide_baked_len;
/// assert_eq!(wide_baked_len(2, 5, false), 64 + 2 * 128 + 5 * 4);
/// assert_eq!(wide_baked_len(2, 5, true), 64 + 2 * 128 + 5 * 28);
/// ```
pub const fn wide_baked_len(records: usize, primitives: usize, leaf_bounds: bool) -> usize {
    let per_primitive = if leaf_bounds { 4 + BOX_BYTES } else { 4 };
    RECORDS_AT
        .saturating_add(records.saturating_mul(RECORD_BYTES))
        .saturating_add(primitives.saturating_mul(per_primitive))
}

/// A record's words in the order of its bytes.
fn record_words(r: &WideNode) -> impl Iterator<Item = u32> + '_ {
    let b = &r.boxes;
    let lanes = b.min.iter().chain(&b.max).flatten().map(|x| x.to_bits());
    lanes.chain(r.child).chain(r.count)
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
        let len = self.baked_len();
        if out.len() < len {
            return Err(Error::ScratchCapacity {
                needed: len,
                available: out.len(),
            });
        }
        let records = self.records().iter().flat_map(record_words);
        let counts = (self.records().len(), self.indices().len(), self.depth_of());
        super::write(
            &mut out[..len],
            &WIDE,
            records,
            counts,
            self.indices(),
            self.leaf_bounds(),
        )?;
        Ok(len)
    }

    fn depth_of(&self) -> usize {
        crate::Hierarchy::depth(self)
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
        let h = Header::read(bytes, &WIDE)?;
        let (records, indices, bounds) = h.arrays::<WideNode>(bytes, &WIDE)?;
        let nodes = check_wide(records, indices, bounds, seen)?;
        let wide = Wide::from_checked(records, indices, bounds, nodes)?;
        let depth = wide.depth_of();
        if depth > MAX_DEPTH {
            return Err(Error::InvalidTree("deeper than MAX_DEPTH"));
        }
        if depth != h.depth as usize {
            return Err(bad(20, "the depth field differs from the tree's depth"));
        }
        Ok(wide)
    }

    /// Scratch words [`from_baked`](Self::from_baked) needs for `bytes`
    /// (from their header).
    pub fn baked_seen_words(bytes: &[u8]) -> Result<usize, Error> {
        let h = Header::read(bytes, &WIDE)?;
        Ok(Bvh::<Aabb>::seen_words(h.nodes, h.primitives))
    }
}

/// Slots in use at the front of `r` (a used slot after an unused one is an
/// error).
fn used_prefix(r: &WideNode) -> Result<usize, Error> {
    let used = r.count.iter().take_while(|&&c| c != UNUSED).count();
    if r.count[used..].iter().any(|&c| c != UNUSED) {
        return Err(Error::InvalidTree(
            "a wide record uses a slot after an unused one",
        ));
    }
    Ok(used)
}

/// The checks of [`Wide::from_baked`] once the bytes are arrays; returns the
/// number of nodes (slots in use). Records are visited in order: a record's
/// parent slot is in an earlier record, so by the time a record comes, it
/// has been reached (once) or never will be.
fn check_wide(
    records: &[WideNode],
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
            "validation scratch smaller than Wide::baked_seen_words",
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
        let used = used_prefix(r)?;
        nodes += used;
        for k in 0..used {
            let b = r.slot_box(k);
            if !sound(&b) {
                return Err(Error::InvalidTree(
                    "a node's box is not finite or is inverted",
                ));
            }
            let (link, count) = (r.child[k], r.count[k]);
            if count & INNER != 0 {
                let c = (count & !INNER) as usize;
                let child = link as usize;
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
                if c == 0 || used_prefix(rc)? != c {
                    return Err(Error::InvalidTree(
                        "a slot's child count differs from its record's slots in use",
                    ));
                }
                if !(0..c).all(|j| b.contains(&rc.slot_box(j))) {
                    return Err(Error::InvalidTree("a node does not contain its children"));
                }
            } else {
                // In u64: on a 32-bit target `first + count` could wrap.
                let end = u64::from(link) + u64::from(count);
                if count == 0 || end > p as u64 {
                    return Err(Error::InvalidTree("leaf range outside the index array"));
                }
                leaf_slots += count as usize;
                let run = link as usize..end as usize;
                if let Some(leaf) = kept.get(run) {
                    if !leaf.iter().all(|k| sound(k) && b.contains(k)) {
                        return Err(Error::InvalidTree(
                            "a leaf does not contain its kept bounds",
                        ));
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
            let (link, count) = (r.child[k] as usize, r.count[k]);
            if count & INNER != 0 {
                continue; // internal or unused
            }
            // Every leaf's run is within the array (checked above).
            for entry in link..link + count as usize {
                if test_and_set(seen, entry) {
                    return Err(Error::InvalidTree("two leaves share an index entry"));
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
