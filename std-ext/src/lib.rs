//! # bvhkit-std
//!
//! The std side of bvhkit: owned storage for trees ([`OwnedBvh`]), the built-in
//! scenes ([`scene`]), timing helpers, and the `tour` behind the `bvhkit`
//! command-line tool. The core crate never allocates; this crate is where
//! `Vec`s, files and clocks live.

pub mod advisor;
pub mod builders;
pub mod collide;
pub mod cost;
pub mod cost_fit;
pub mod figures;
pub mod hull;
pub mod layouts;
pub mod mesh;
pub mod motion;
pub mod near_misses;
pub mod parallel;
pub mod report;
pub mod scene;
pub mod stamp;
pub mod stats;
pub mod tour;
pub mod volumes;

use bvhkit::{Aabb, BoundingVolume, BuildReport, Bvh, Error, Node, Primitive, TopDown};
use std::time::{Duration, Instant};

/// A tree with its storage in `Vec`s, sized exactly for the input, and the
/// primitives' bounds in leaf order ([`Bvh::with_leaf_bounds`]): pair
/// queries on it read no primitive to test a pair's bounds.
///
/// ```
/// use bvhkit::{Aabb, TopDown, Triangle};
/// use bvhkit_std::OwnedBvh;
/// let tris = bvhkit_std::scene::rock(2, 0x5eed);
/// let tree = OwnedBvh::<Aabb>::build(&TopDown::default(), &tris)?;
/// assert_eq!(tree.view().primitive_count(), tris.len());
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct OwnedBvh<B> {
    nodes: Vec<Node<B>>,
    indices: Vec<u32>,
    /// `leaf_bounds[k]` bounds primitive `indices[k]`.
    leaf_bounds: Vec<Aabb>,
    depth: usize,
    /// What the builder did besides following its configuration.
    report: BuildReport,
}

/// The storage of a cached top-down build ([`TopDown::build_cached`]), freshly
/// allocated, and how it becomes an [`OwnedBvh`].
struct CachedStorage<B> {
    nodes: Vec<Node<B>>,
    indices: Vec<u32>,
    cache: Vec<bvhkit::builders::PrimitiveRef>,
    scratch: Vec<Node<B>>,
    n: usize,
}

impl<B: BoundingVolume> CachedStorage<B> {
    /// Every buffer is of zero bits: the allocator hands out zeroed pages
    /// that cost nothing until written, where a non-zero fill would write
    /// all of them first (over 2n nodes, of which a tree of 4-primitive
    /// leaves uses about a third).
    fn new(builder: &TopDown, n: usize, scratch: usize) -> Self {
        CachedStorage {
            nodes: vec![Node::<B>::ZERO; bvhkit::max_nodes(n)],
            indices: vec![0u32; builder.index_capacity(n)],
            cache: vec![bvhkit::builders::PrimitiveRef::ZERO; n],
            scratch: vec![Node::<B>::ZERO; scratch],
            n,
        }
    }

    #[allow(clippy::type_complexity)]
    fn parts(
        &mut self,
    ) -> (
        &mut [Node<B>],
        &mut [u32],
        &mut [bvhkit::builders::PrimitiveRef],
        &mut [Node<B>],
    ) {
        (
            &mut self.nodes,
            &mut self.indices,
            &mut self.cache,
            &mut self.scratch,
        )
    }

    /// Trims the storage to the `used` nodes of the built tree. After a
    /// cached build the records are in leaf order: their boxes are the leaf
    /// bounds, read in one pass (on rayon's pool when `parallel`).
    fn finish(self, used: usize, depth: usize, report: BuildReport, parallel: bool) -> OwnedBvh<B> {
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
        OwnedBvh {
            nodes,
            indices,
            leaf_bounds: if parallel {
                use rayon::prelude::*;
                cache.par_iter().map(|r| r.bounds()).collect()
            } else {
                cache.iter().map(|r| r.bounds()).collect()
            },
            depth,
            report,
        }
    }
}

impl<B: BoundingVolume> OwnedBvh<B> {
    /// Builds into freshly allocated storage (with the bounds cache of
    /// [`TopDown::build_cached`]), then trims it to what was used.
    pub fn build<P: Primitive>(builder: &TopDown, prims: &[P]) -> Result<Self, Error> {
        let mut storage = CachedStorage::new(builder, prims.len(), 0);
        let (used, depth, report) = {
            let (nodes, indices, cache, _) = storage.parts();
            let t = builder.build_cached(prims, nodes, indices, cache)?;
            (t.node_count(), t.depth(), t.build_report())
        };
        Ok(storage.finish(used, depth, report, false))
    }

    /// [`build`](Self::build) on every core of rayon's current pool
    /// ([`parallel::Threads`]): the same tree, bit for bit. The forked build
    /// needs a second node array as scratch (allocated here and dropped).
    ///
    /// ```
    /// use bvhkit::{Aabb, TopDown};
    /// use bvhkit_std::OwnedBvh;
    /// let tris = bvhkit_std::scene::rock(5, 7); // 20,480 triangles
    /// let parallel = OwnedBvh::<Aabb>::build_parallel(&TopDown::default(), &tris)?;
    /// let sequential = OwnedBvh::<Aabb>::build(&TopDown::default(), &tris)?;
    /// assert_eq!(parallel.view().nodes(), sequential.view().nodes());
    /// assert_eq!(parallel.view().indices(), sequential.view().indices());
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn build_parallel<P: Primitive + Sync>(
        builder: &TopDown,
        prims: &[P],
    ) -> Result<Self, Error>
    where
        B: Send + Sync,
    {
        let fork = parallel::Threads::default();
        let n = prims.len();
        let scratch = if n >= fork.grain {
            bvhkit::max_nodes(n)
        } else {
            0
        };
        let mut storage = CachedStorage::new(builder, n, scratch);
        let (used, depth, report) = {
            let (nodes, indices, cache, scratch) = storage.parts();
            let t = builder.build_cached_forked(prims, nodes, indices, cache, scratch, &fork)?;
            (t.node_count(), t.depth(), t.build_report())
        };
        Ok(storage.finish(used, depth, report, true))
    }

    /// Builds bottom-up (scratch allocated here and dropped after the build).
    pub fn build_bottom_up<P: Primitive>(
        builder: &bvhkit::builders::BottomUp,
        prims: &[P],
    ) -> Result<Self, Error> {
        use bvhkit::builders::{BottomUp, BottomUpScratch, Cluster};
        let (nc, nw, nk) = BottomUp::scratch_len(prims.len());
        let (mut work, mut keys) = (vec![0u32; nw], vec![0u64; nk]);
        let mut nodes = vec![Node::<B>::ZERO; bvhkit::max_nodes(prims.len())];
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
    pub fn build_by_insertion<P: Primitive>(
        builder: &bvhkit::builders::Insertion,
        prims: &[P],
    ) -> Result<Self, Error> {
        use bvhkit::builders::DynNode;
        let n = prims.len();
        let mut storage = vec![DynNode::<B>::EMPTY; bvhkit::max_nodes(n)];
        let mut order = vec![0u32; n];
        let mut nodes = vec![Node::<B>::ZERO; bvhkit::max_nodes(n)];
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
                tree: indices.iter().max().map_or(0, |&i| i as usize + 1),
                given: prims.len(),
            })?;
        Ok(OwnedBvh {
            nodes,
            indices,
            leaf_bounds,
            depth,
            report,
        })
    }

    /// The tree without its kept leaf bounds: what a layout converted for
    /// compactness (for example [`QuantizedWide`](bvhkit::layout::QuantizedWide))
    /// shares, at 24 bytes per primitive less and slower pair queries.
    pub fn plain_view(&self) -> Bvh<'_, B> {
        Bvh::from_raw_parts(&self.nodes, &self.indices, self.depth).with_build_report(self.report)
    }

    /// The tree as the core's borrowed view, leaf bounds attached.
    pub fn view(&self) -> Bvh<'_, B> {
        // One bound per index entry, as built: the fallback never runs.
        Bvh::from_raw_parts_with_bounds(&self.nodes, &self.indices, &self.leaf_bounds, self.depth)
            .map(|t| t.with_build_report(self.report))
            .unwrap_or_else(|_| self.plain_view())
    }
}

/// Owned storage for a [`PairTracker`](bvhkit::collision::PairTracker):
/// the caller storage the core asks for, sized once, for programs that
/// have a heap.
///
/// ```
/// use bvhkit::builders::DynamicConfig;
/// use bvhkit::collision::PairTracker;
/// use bvhkit::glam::Vec3;
/// use bvhkit::Aabb;
/// let mut buffers = bvhkit_std::TrackerBuffers::new(100, 1_000);
/// let mut world = PairTracker::new(buffers.storage(), DynamicConfig::default())?;
/// world.insert(0, &Aabb::new(Vec3::ZERO, Vec3::ONE))?;
/// world.insert(1, &Aabb::new(Vec3::splat(0.5), Vec3::splat(2.0)))?;
/// let mut begun = 0;
/// world.step(|_| begun += 1)?;
/// assert_eq!(begun, 1);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct TrackerBuffers {
    nodes: Vec<bvhkit::builders::DynNode<Aabb>>,
    slots: Vec<bvhkit::collision::Slot>,
    boxes: Vec<Aabb>,
    moved: Vec<u32>,
    pairs: Vec<(u32, u32)>,
    next: Vec<(u32, u32)>,
}

impl TrackerBuffers {
    /// Room for object ids below `objects` and `pairs` overlapping pairs
    /// at a time.
    pub fn new(objects: usize, pairs: usize) -> Self {
        TrackerBuffers {
            nodes: vec![bvhkit::builders::DynNode::EMPTY; bvhkit::max_nodes(objects)],
            slots: vec![bvhkit::collision::Slot::EMPTY; objects],
            boxes: vec![Aabb::EMPTY; objects],
            moved: vec![0; objects],
            pairs: vec![(0, 0); pairs],
            next: vec![(0, 0); pairs],
        }
    }

    /// The buffers as the tracker takes them.
    pub fn storage(&mut self) -> bvhkit::collision::TrackerStorage<'_> {
        bvhkit::collision::TrackerStorage {
            nodes: &mut self.nodes,
            slots: &mut self.slots,
            boxes: &mut self.boxes,
            moved: &mut self.moved,
            pairs: &mut self.pairs,
            next: &mut self.next,
        }
    }
}

/// Runs `f` `runs` times and returns the median duration and the last result.
pub fn median_time<R>(runs: usize, mut f: impl FnMut() -> R) -> (Duration, R) {
    let mut times = Vec::with_capacity(runs.max(1));
    let mut last = None;
    for _ in 0..runs.max(1) {
        let t = Instant::now();
        let r = f();
        times.push(t.elapsed());
        last = Some(r);
    }
    times.sort_unstable();
    let r = last.unwrap_or_else(|| unreachable!("runs >= 1"));
    (times[times.len() / 2], r)
}
