//! Owned trees, for programs with a heap (the `alloc` feature).
//!
//! The builders write into storage the caller sizes; [`OwnedBvh`] does that
//! sizing, allocates, builds, and trims the storage to what the tree used,
//! in one call. The allocation-free API underneath is unchanged: a view of
//! an owned tree is the same [`Bvh`] every query takes.

use alloc::boxed::Box;
use alloc::vec;
use alloc::vec::Vec;
use core::any::Any;

use crate::builders::{Fork, PrimitiveRef};
use crate::bv::{Aabb, BoundingVolume};
use crate::{BuildReport, Bvh, Error, Node, Primitive, TopDown};

/// A tree with its storage in `Vec`s, sized exactly for the input, and the
/// primitives' bounds in leaf order ([`Bvh::with_leaf_bounds`]): pair
/// queries on it read no primitive to test a pair's bounds.
///
/// ```
/// use bvhkit::{Aabb, OwnedBvh, TopDown, Triangle};
/// use bvhkit::glam::Vec3;
/// let tris: Vec<Triangle> = (0..100)
///     .map(|i| {
///         let o = Vec3::new(i as f32, 0.0, 0.0);
///         Triangle::new(o, o + Vec3::X, o + Vec3::Y)
///     })
///     .collect();
/// let tree = OwnedBvh::<Aabb>::build(&TopDown::default(), &tris)?;
/// assert_eq!(tree.view().primitive_count(), 100);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct OwnedBvh<B> {
    nodes: Vec<Node<B>>,
    indices: Vec<u32>,
    /// `leaf_bounds[k]` bounds primitive `indices[k]`.
    leaf_bounds: Vec<Aabb>,
    depth: usize,
    /// The largest index plus one ([`Bvh::index_bound`]), kept so that a
    /// view costs no pass over the indices.
    bound: usize,
    /// What the builder did besides following its configuration.
    report: BuildReport,
}

/// The storage of a cached top-down build ([`TopDown::build_cached`]),
/// freshly allocated, and how it becomes an [`OwnedBvh`].
struct CachedStorage<B> {
    nodes: Vec<Node<B>>,
    indices: Vec<u32>,
    cache: Vec<PrimitiveRef>,
    scratch: Vec<Node<B>>,
    n: usize,
}

impl<B: BoundingVolume> CachedStorage<B> {
    /// Every buffer is of zero bits, from [`zeroed`]: fresh pages cost
    /// nothing until written, where a fill would write all of them first
    /// (over 2n nodes, of which a tree of 4-primitive leaves uses about a
    /// third).
    fn new(builder: &TopDown, n: usize, scratch: usize) -> Self {
        CachedStorage {
            nodes: zeroed_nodes(crate::max_nodes(n)),
            indices: vec![0u32; builder.index_capacity(n)],
            cache: zeroed(n),
            scratch: zeroed_nodes(scratch),
            n,
        }
    }

    /// Trims the storage to the `used` nodes of the built tree. After a
    /// cached build the records are in leaf order: their boxes are the leaf
    /// bounds, read in one pass (its halves handed to `fork` when large).
    fn finish<F: Fork>(
        self,
        used: usize,
        depth: usize,
        report: BuildReport,
        fork: &F,
    ) -> OwnedBvh<B> {
        let CachedStorage {
            mut nodes,
            mut indices,
            cache,
            scratch,
            n,
        } = self;
        drop(scratch);
        nodes.truncate(used);
        nodes.shrink_to_fit();
        indices.truncate(n);
        indices.shrink_to_fit();
        // Zero bits again: the first write is the only pass over the pages.
        let mut leaf_bounds = zeroed::<Aabb>(n);
        copy_bounds(&cache, &mut leaf_bounds, fork);
        OwnedBvh::keep(nodes, indices, leaf_bounds, depth, report)
    }
}

/// `out[k] = cache[k].bounds()`, in halves through `fork` down to its grain.
fn copy_bounds<F: Fork>(cache: &[PrimitiveRef], out: &mut [Aabb], fork: &F) {
    if cache.len() < fork.grain().max(2) {
        for (o, r) in out.iter_mut().zip(cache) {
            *o = r.bounds();
        }
        return;
    }
    let half = cache.len() / 2;
    let (ca, cb) = cache.split_at(half);
    let (oa, ob) = out.split_at_mut(half);
    fork.join(|| copy_bounds(ca, oa, fork), || copy_bounds(cb, ob, fork));
}

impl<B: BoundingVolume> OwnedBvh<B> {
    /// A built tree's parts, kept with their index bound (one pass over the
    /// indices here, none per view).
    fn keep(
        nodes: Vec<Node<B>>,
        indices: Vec<u32>,
        leaf_bounds: Vec<Aabb>,
        depth: usize,
        report: BuildReport,
    ) -> Self {
        OwnedBvh {
            bound: crate::tree::index_bound_of(&indices) as usize,
            nodes,
            indices,
            leaf_bounds,
            depth,
            report,
        }
    }

    /// Builds into freshly allocated storage (with the bounds cache of
    /// [`TopDown::build_cached`]), then trims it to what was used.
    pub fn build<P: Primitive>(builder: &TopDown, prims: &[P]) -> Result<Self, Error> {
        let mut storage = CachedStorage::new(builder, prims.len(), 0);
        let t = builder.build_cached(
            prims,
            &mut storage.nodes,
            &mut storage.indices,
            &mut storage.cache,
        )?;
        let (used, depth, report) = (t.node_count(), t.depth(), t.build_report());
        let in_one_pass = crate::builders::InOrder { grain: usize::MAX };
        Ok(storage.finish(used, depth, report, &in_one_pass))
    }

    /// [`build`](Self::build) with the halves of every large node handed to
    /// `fork` ([`TopDown::build_cached_forked`]): the same tree, bit for bit.
    /// `bvhkit-std`'s `build_parallel` passes a thread pool. The forked build
    /// needs a second node array as scratch (allocated here and dropped).
    ///
    /// ```
    /// use bvhkit::builders::InOrder;
    /// use bvhkit::{Aabb, OwnedBvh, TopDown, Triangle};
    /// use bvhkit::glam::Vec3;
    /// let tris: Vec<Triangle> = (0..3000)
    ///     .map(|i| {
    ///         let o = Vec3::new((i % 50) as f32, (i / 50) as f32, (i % 7) as f32);
    ///         Triangle::new(o, o + Vec3::X, o + Vec3::Y)
    ///     })
    ///     .collect();
    /// let fork = InOrder { grain: 500 }; // pieces of at least 500 triangles
    /// let forked = OwnedBvh::<Aabb>::build_forked(&TopDown::default(), &tris, &fork)?;
    /// let plain = OwnedBvh::<Aabb>::build(&TopDown::default(), &tris)?;
    /// assert_eq!(forked.view().nodes(), plain.view().nodes());
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn build_forked<P, F>(builder: &TopDown, prims: &[P], fork: &F) -> Result<Self, Error>
    where
        P: Primitive + Sync,
        B: Send + Sync,
        F: Fork,
    {
        let n = prims.len();
        let scratch = if n >= fork.grain() {
            crate::max_nodes(n)
        } else {
            0
        };
        let mut storage = CachedStorage::new(builder, n, scratch);
        let t = builder.build_cached_forked(
            prims,
            &mut storage.nodes,
            &mut storage.indices,
            &mut storage.cache,
            &mut storage.scratch,
            fork,
        )?;
        let (used, depth, report) = (t.node_count(), t.depth(), t.build_report());
        Ok(storage.finish(used, depth, report, fork))
    }

    /// Builds bottom-up (scratch allocated here and dropped after the build).
    ///
    /// ```
    /// use bvhkit::builders::BottomUp;
    /// use bvhkit::{Aabb, OwnedBvh, Query};
    /// use glam::Vec3;
    /// let pts: Vec<Vec3> = (0..100).map(|i| Vec3::new(i as f32, (i * 7 % 10) as f32, 0.0)).collect();
    /// let tree = OwnedBvh::<Aabb>::build_bottom_up(&BottomUp::default(), &pts)?; // PLOC
    /// assert_eq!(tree.view().primitive_count(), 100);
    /// let region = Aabb::new(Vec3::new(10.0, 0.0, -1.0), Vec3::new(20.0, 9.0, 1.0));
    /// assert_eq!(tree.view().overlapping(&pts, &region, |_| {})?, 11); // x = 10 ..= 20
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    #[cfg(feature = "bottom-up")]
    pub fn build_bottom_up<P: Primitive>(
        builder: &crate::builders::BottomUp,
        prims: &[P],
    ) -> Result<Self, Error> {
        use crate::builders::{BottomUp, BottomUpScratch, Cluster};
        let (nc, nw, nk) = BottomUp::scratch_len(prims.len());
        let (mut work, mut keys) = (vec![0u32; nw], vec![0u64; nk]);
        let mut nodes = zeroed_nodes::<B>(crate::max_nodes(prims.len()));
        let mut indices = vec![0u32; prims.len()];
        // PLOC without a collapse builds in `nodes`: the clusters (as many
        // bytes again) are allocated only if the tree comes out too deep
        // and must be rebuilt there.
        let mut attempt = |clusters: &mut [Cluster<B>]| {
            let mut scratch = BottomUpScratch {
                clusters,
                work: &mut work,
                keys: &mut keys,
            };
            builder
                .build(prims, &mut nodes, &mut indices, &mut scratch)
                .map(|t| (t.node_count(), t.depth(), t.build_report()))
        };
        let (used, depth, report) = if builder.needs_clusters() {
            attempt(&mut vec![Cluster::ZERO; nc])
        } else {
            match attempt(&mut []) {
                Err(Error::StackOverflow { .. }) => attempt(&mut vec![Cluster::ZERO; nc]),
                other => other,
            }
        }?;
        nodes.truncate(used);
        OwnedBvh::with_leaf_bounds(nodes, indices, prims, depth, report)
    }

    /// Builds by insertion (dynamic-tree storage allocated here and dropped).
    ///
    /// ```
    /// use bvhkit::builders::{InsertOrder, Insertion};
    /// use bvhkit::{Aabb, OwnedBvh, Query};
    /// use glam::Vec3;
    /// let pts: Vec<Vec3> = (0..100).map(|i| Vec3::new(i as f32, (i * 7 % 10) as f32, 0.0)).collect();
    /// let shuffled = Insertion { order: InsertOrder::Shuffled(7), ..Insertion::default() };
    /// let tree = OwnedBvh::<Aabb>::build_by_insertion(&shuffled, &pts)?;
    /// assert_eq!(tree.view().primitive_count(), 100);
    /// let region = Aabb::new(Vec3::new(10.0, 0.0, -1.0), Vec3::new(20.0, 9.0, 1.0));
    /// assert_eq!(tree.view().overlapping(&pts, &region, |_| {})?, 11); // x = 10 ..= 20
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    #[cfg(feature = "insertion")]
    pub fn build_by_insertion<P: Primitive>(
        builder: &crate::builders::Insertion,
        prims: &[P],
    ) -> Result<Self, Error> {
        use crate::builders::DynNode;
        let n = prims.len();
        let mut storage = vec![DynNode::<B>::EMPTY; crate::max_nodes(n)];
        let mut order = vec![0u32; n];
        let mut nodes = zeroed_nodes::<B>(crate::max_nodes(n));
        let mut indices = vec![0u32; n];
        let (used, depth, report) = {
            let t = builder.build(prims, &mut storage, &mut order, &mut nodes, &mut indices)?;
            (t.node_count(), t.depth(), t.build_report())
        };
        nodes.truncate(used);
        OwnedBvh::with_leaf_bounds(nodes, indices, prims, depth, report)
    }

    /// Keeps a built tree with its primitives' bounds in leaf order, as
    /// the core writes them ([`Bvh::with_leaf_bounds`]).
    #[cfg(any(feature = "bottom-up", feature = "insertion"))]
    fn with_leaf_bounds<P: Primitive>(
        nodes: Vec<Node<B>>,
        indices: Vec<u32>,
        prims: &[P],
        depth: usize,
        report: BuildReport,
    ) -> Result<Self, Error> {
        // Collected rather than written into a zeroed vector: one pass
        // over the new memory instead of two.
        let leaf_bounds = indices
            .iter()
            .map(|&i| prims.get(i as usize).map(Primitive::bounds))
            .collect::<Option<Vec<Aabb>>>()
            .ok_or(Error::PrimitiveCountMismatch {
                tree: crate::tree::index_bound_of(&indices) as usize,
                given: prims.len(),
            })?;
        Ok(OwnedBvh::keep(nodes, indices, leaf_bounds, depth, report))
    }

    /// The tree without its kept leaf bounds: what a layout converted for
    /// compactness (for example [`QuantizedWide`](crate::layout::QuantizedWide))
    /// shares, at 24 bytes per primitive less and slower pair queries.
    pub fn plain_view(&self) -> Bvh<'_, B> {
        Bvh::from_kept(
            &self.nodes,
            &self.indices,
            &[],
            self.depth,
            self.bound,
            self.report,
        )
    }

    /// The tree as the core's borrowed view, leaf bounds attached. Costs
    /// nothing: take one per query if that is simpler.
    pub fn view(&self) -> Bvh<'_, B> {
        // One bound per index entry, as built.
        Bvh::from_kept(
            &self.nodes,
            &self.indices,
            &self.leaf_bounds,
            self.depth,
            self.bound,
            self.report,
        )
    }
}

/// Types for which a value of all-zero bits is valid: plain `f32` and `u32`
/// fields, no references, no niches, no invariant beyond their bits.
///
/// # Safety
///
/// Implement only for such types: [`zeroed`] hands out their values without
/// writing them.
// SAFETY: only declares the contract above; each `unsafe impl` below
// states why its type keeps it.
#[allow(unsafe_code)]
unsafe trait ZeroBits {}

// SAFETY: two `Vec3` of `f32`; zero bits are the point box at the origin.
#[allow(unsafe_code)]
unsafe impl ZeroBits for Aabb {}
// SAFETY: an `Aabb` and two `u32`; zero bits are `Node::ZERO`.
#[allow(unsafe_code)]
unsafe impl ZeroBits for Node<Aabb> {}
// SAFETY: two `Vec4` of `f32`; zero bits are `PrimitiveRef::ZERO`.
#[allow(unsafe_code)]
unsafe impl ZeroBits for PrimitiveRef {}

/// `n` values of zero bits, without writing them: the allocator's zeroed
/// memory (fresh pages from the system for a large block), so a page costs
/// something only when the builder first writes it. `vec![x; n]` writes
/// every value first: for the 2.6 M-node arrays of a 1.3 M-triangle build,
/// 80 ms of a 406 ms build, and most of those pages a tree with several
/// primitives per leaf never uses. (`vec!` skips the writes only for
/// integers and floats, not for a struct of them.)
#[allow(unsafe_code)]
fn zeroed<T: ZeroBits>(n: usize) -> Vec<T> {
    let layout = match core::alloc::Layout::array::<T>(n) {
        Ok(l) if l.size() > 0 => l,
        // Nothing to allocate (n = 0), or more than the address space: the
        // plain path returns the empty vector or reports the overflow.
        _ => return Vec::with_capacity(n),
    };
    // SAFETY: `layout` has a non-zero size (checked above).
    let ptr = unsafe { alloc::alloc::alloc_zeroed(layout) }.cast::<T>();
    if ptr.is_null() {
        alloc::alloc::handle_alloc_error(layout);
    }
    // SAFETY: `ptr` comes from the global allocator with the layout of `n`
    // values of `T` (so `Vec` may free it with capacity `n`), it is aligned
    // for `T`, and its `n` values are initialised: all-zero bits, valid for
    // `T` by `ZeroBits`.
    unsafe { Vec::from_raw_parts(ptr, n, n) }
}

/// `n` nodes of zero bits: through [`zeroed`] for the box nodes every
/// default build makes, filled with [`Node::ZERO`] for other volumes (whose
/// every field the compiler cannot vouch for).
fn zeroed_nodes<B: BoundingVolume>(n: usize) -> Vec<Node<B>> {
    if core::any::TypeId::of::<B>() == core::any::TypeId::of::<Aabb>() {
        let nodes: Box<dyn Any> = Box::new(zeroed::<Node<Aabb>>(n));
        if let Ok(nodes) = nodes.downcast::<Vec<Node<B>>>() {
            return *nodes;
        }
    }
    vec![Node::<B>::ZERO; n]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Triangle;
    use glam::Vec3;

    /// The zeroed storage holds the zero values the fill would have written,
    /// for the box nodes (allocator path) and another volume (fill path);
    /// an empty request allocates nothing. Small, so that Miri runs it
    /// (`cargo +nightly miri test -p bvhkit --features alloc --lib zeroed`).
    #[test]
    fn zeroed_storage_holds_zero_values() {
        let boxes: Vec<Node<Aabb>> = zeroed_nodes(5);
        assert_eq!(boxes, vec![Node::<Aabb>::ZERO; 5]);
        #[cfg(feature = "sphere")]
        {
            let spheres: Vec<Node<crate::Sphere>> = zeroed_nodes(3);
            assert_eq!(spheres, vec![Node::<crate::Sphere>::ZERO; 3]);
        }
        let refs: Vec<PrimitiveRef> = zeroed(4);
        assert!(refs.iter().all(|r| r.bounds() == Aabb::ZERO));
        let mut grown: Vec<Aabb> = zeroed(2);
        grown.push(Aabb::EMPTY); // the allocation is Vec's own: it grows and frees
        assert_eq!(grown, [Aabb::ZERO, Aabb::ZERO, Aabb::EMPTY]);
        assert!(zeroed::<Aabb>(0).is_empty() && zeroed_nodes::<Aabb>(0).capacity() == 0);
    }

    /// The kept view is the view the raw parts give (same bound, depth,
    /// leaf bounds and report), without the pass over the indices.
    #[test]
    fn the_kept_view_equals_the_raw_parts_view() {
        let tris: Vec<Triangle> = (0..500)
            .map(|i| {
                let o = Vec3::new((i % 13) as f32, (i / 13) as f32, (i % 5) as f32 * 0.5);
                Triangle::new(o, o + Vec3::X, o + Vec3::Z)
            })
            .collect();
        let owned = OwnedBvh::<Aabb>::build(&TopDown::default(), &tris).unwrap();
        let (kept, plain) = (owned.view(), owned.plain_view());
        let raw = Bvh::from_raw_parts_with_bounds(
            kept.nodes(),
            kept.indices(),
            kept.leaf_bounds().unwrap(),
            kept.depth(),
        )
        .unwrap();
        assert_eq!(kept.index_bound(), raw.index_bound());
        assert_eq!(kept.index_bound(), 500);
        assert_eq!(
            (kept.depth(), kept.leaf_bounds()),
            (raw.depth(), raw.leaf_bounds())
        );
        assert_eq!(plain.leaf_bounds(), None);
        assert_eq!((plain.index_bound(), plain.depth()), (500, raw.depth()));
        assert_eq!(kept.build_report(), owned.report);
        for (k, &i) in kept.indices().iter().enumerate() {
            assert_eq!(
                kept.leaf_bounds().unwrap()[k],
                crate::Primitive::bounds(&tris[i as usize])
            );
        }
    }
}
