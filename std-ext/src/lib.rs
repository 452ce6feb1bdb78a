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
pub mod hull;
pub mod layouts;
pub mod mesh;
pub mod motion;
pub mod near_misses;
pub mod report;
pub mod scene;
pub mod stamp;
pub mod stats;
pub mod tour;

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

impl<B: BoundingVolume> OwnedBvh<B> {
    /// Builds into freshly allocated storage (with the bounds cache of
    /// [`TopDown::build_cached`]), then trims it to what was used.
    pub fn build<P: Primitive>(builder: &TopDown, prims: &[P]) -> Result<Self, Error> {
        let mut nodes = vec![Node::<B>::EMPTY; bvhkit::max_nodes(prims.len())];
        let mut indices = vec![0u32; builder.index_capacity(prims.len())];
        let mut cache = vec![bvhkit::builders::PrimitiveRef::EMPTY; prims.len()];
        let (used, depth, report) = {
            let t = builder.build_cached(prims, &mut nodes, &mut indices, &mut cache)?;
            (t.node_count(), t.depth(), t.build_report())
        };
        nodes.truncate(used);
        nodes.shrink_to_fit();
        indices.truncate(prims.len());
        indices.shrink_to_fit();
        // After the build the records are in leaf order: their boxes are
        // the leaf bounds, read in one pass.
        let leaf_bounds = cache.iter().map(|r| r.bounds()).collect();
        Ok(OwnedBvh {
            nodes,
            indices,
            leaf_bounds,
            depth,
            report,
        })
    }

    /// Builds bottom-up (scratch allocated here and dropped after the build).
    pub fn build_bottom_up<P: Primitive>(
        builder: &bvhkit::builders::BottomUp,
        prims: &[P],
    ) -> Result<Self, Error> {
        use bvhkit::builders::{BottomUp, BottomUpScratch, Cluster};
        let (nc, nw, nk) = BottomUp::scratch_len(prims.len());
        let mut clusters = vec![Cluster::<B>::EMPTY; nc];
        let (mut work, mut keys) = (vec![0u32; nw], vec![0u64; nk]);
        let mut scratch = BottomUpScratch {
            clusters: &mut clusters,
            work: &mut work,
            keys: &mut keys,
        };
        let mut nodes = vec![Node::<B>::EMPTY; bvhkit::max_nodes(prims.len())];
        let mut indices = vec![0u32; prims.len()];
        let (used, depth, report) = {
            let t = builder.build(prims, &mut nodes, &mut indices, &mut scratch)?;
            (t.node_count(), t.depth(), t.build_report())
        };
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
        let mut nodes = vec![Node::<B>::EMPTY; bvhkit::max_nodes(n)];
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
        let mut leaf_bounds = vec![Aabb::EMPTY; indices.len()];
        Bvh::from_raw_parts(&nodes, &indices, depth).with_leaf_bounds(prims, &mut leaf_bounds)?;
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
