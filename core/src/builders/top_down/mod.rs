//! The top-down builder: one shared skeleton, pluggable split evaluation.
//!
//! Skeleton (Ericson 6.2.1), written with an explicit stack so it is safe on a
//! small thread or interrupt stack:
//!
//! 1. bound the node's primitives;
//! 2. stop if a [`Stop`] criterion holds;
//! 3. otherwise evaluate candidate splits (axis x split point, scored by the
//!    [`Partition`] criterion), partition the index range in place, and
//!    continue with both halves.
//!
//! The smaller half is processed next and the larger one pushed, so the stack
//! never holds more than `log2(n) + 1` entries. The default configuration
//! (binned SAH over x, y and z) has a dedicated single-pass binning loop; every
//! other combination goes through the general evaluator, which is compiled
//! only with the `strategies` cargo feature (on by default): without it, the
//! builder keeps the binned-SAH fast path and the object-median fallback,
//! about a third of the code, for firmware that wants small flash.
// Without `strategies`, the general evaluator is compiled but unreachable.
#![cfg_attr(not(feature = "strategies"), allow(dead_code))]

mod axes;
mod binned;
mod criteria;
mod fork;
mod partition;
mod source;
mod split_points;
mod stop;

pub use fork::{Fork, InOrder};
pub use source::PrimitiveRef;

use super::strategy::{AxisChoice, OnFailure, Partition, SplitPoint, Stop, MAX_BINS};
use super::BuildReport;
use crate::bv::{Aabb, BoundingVolume};
use crate::primitive::{validate_bounds, validate_bounds_each, Primitive};
use crate::tree::{max_nodes, Bvh, Node, MAX_DEPTH};
use crate::Error;
use partition::bounds_of;
use source::{Cached, Indexed, Source, SourceBoxes};

/// A top-down builder: a plain configuration value; [`build`](Self::build) does the work.
///
/// ```
/// use bvhkit::{Aabb, Node, TopDown, Triangle, Partition, SplitPoint, AxisChoice};
/// use glam::Vec3;
/// let tris: Vec<Triangle> = (0..100)
///     .map(|i| Triangle::new(Vec3::new(i as f32, 0.0, 0.0), Vec3::new(i as f32, 1.0, 0.0), Vec3::new(i as f32, 0.0, 1.0)))
///     .collect();
/// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(tris.len())];
/// let mut indices = vec![0u32; tris.len()];
/// // Median cut along the axis of greatest variance, two primitives per leaf.
/// let builder = TopDown {
///     partition: Partition::Balance,
///     axis: AxisChoice::Variance,
///     split: SplitPoint::ObjectMedian,
///     ..TopDown::default()
/// }
/// .with_max_leaf_size(2);
/// let bvh = builder.build(&tris, &mut nodes, &mut indices)?;
/// assert_eq!(bvh.depth(), 6); // 100 -> 50 -> 25 -> 13 -> 7 -> 4 -> 2
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TopDown {
    /// What a split minimises.
    pub partition: Partition,
    /// Which axes splits are tried along.
    pub axis: AxisChoice,
    /// Where candidate planes are placed.
    pub split: SplitPoint,
    /// When to make a leaf.
    pub stop: Stop,
    /// What to do when no criterion separates a node.
    pub on_failure: OnFailure,
}

impl Default for TopDown {
    /// Binned SAH ([`TopDown::sah`]).
    fn default() -> Self {
        TopDown::sah()
    }
}

/// One node waiting to be processed: its index range and known bounds.
#[derive(Clone, Copy, Debug)]
struct Task {
    node: u32,
    start: u32,
    end: u32,
    /// At most `MAX_DEPTH`: 16 bits keep the task, with `tight`, at 64
    /// bytes (each level of the build's recursion holds two).
    depth: u16,
    bounds: Aabb,
    /// A box containing the primitives' centroids: their own box when
    /// `tight`, else the node's box (see [`Task::tightened`]).
    centroids: Aabb,
    tight: bool,
}

/// Result of partitioning a range: the split position and both halves' bounds.
#[derive(Clone, Copy, Debug)]
struct Halves {
    mid: usize,
    bounds: [Aabb; 2],
    centroids: [Aabb; 2],
    /// Whether `centroids` are the centroids' own boxes.
    tight: bool,
}

impl TopDown {
    /// Binned SAH over x, y and z with 16 bins: the fast, high-quality default.
    pub const fn sah() -> Self {
        TopDown {
            partition: Partition::SurfaceArea,
            axis: AxisChoice::BestOfXyz,
            split: SplitPoint::Bins(16),
            stop: Stop {
                max_leaf_size: 4,
                min_volume: 0.0,
                max_depth: MAX_DEPTH as u32,
            },
            on_failure: OnFailure::ForceSplit,
        }
    }

    /// SAH evaluated at every centroid (the exact sweep): the best SAH trees
    /// this builder makes, `O(n log^2 n)`.
    pub const fn sah_sweep() -> Self {
        TopDown {
            split: SplitPoint::Sweep,
            ..TopDown::sah()
        }
    }

    /// The classic median cut: equal halves along the longest axis.
    ///
    /// ```
    /// use bvhkit::{Aabb, Node, TopDown};
    /// use glam::Vec3;
    /// // Points bunched at one end: the median still halves them, so the
    /// // tree is balanced; the SAH cuts where the gap is.
    /// let pts: Vec<Vec3> = (0..64).map(|i| Vec3::new(if i < 60 { i as f32 * 0.01 } else { 100.0 + i as f32 }, 0.0, 0.0)).collect();
    /// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(64)];
    /// let mut idx = vec![0; 64];
    /// let median = TopDown::median().with_max_leaf_size(1).build(&pts, &mut nodes, &mut idx)?;
    /// assert_eq!(median.depth(), 6); // 64 leaves, perfectly balanced
    /// let sah = TopDown::sah().with_max_leaf_size(1).build(&pts, &mut nodes, &mut idx)?;
    /// assert!(sah.depth() > 6);
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub const fn median() -> Self {
        TopDown {
            partition: Partition::Balance,
            axis: AxisChoice::Longest,
            split: SplitPoint::ObjectMedian,
            ..TopDown::sah()
        }
    }

    /// The same configuration with another leaf size.
    pub const fn with_max_leaf_size(mut self, k: u32) -> Self {
        self.stop.max_leaf_size = k;
        self
    }

    /// Index-buffer entries a build over `n` primitives needs: `n`, or `2n` for
    /// [`SplitPoint::Sweep`], which keeps per-node scratch in the second half.
    pub const fn index_capacity(&self, n: usize) -> usize {
        match self.split {
            SplitPoint::Sweep => 2 * n,
            _ => n,
        }
    }

    /// Bytes of caller memory a build over `n` primitives needs with volume
    /// `B`: nodes plus indices. A `const fn`, so firmware can check a budget
    /// at compile time:
    ///
    /// ```
    /// use bvhkit::{Aabb, TopDown};
    /// const BYTES: usize = TopDown::sah().bytes_needed::<Aabb>(256);
    /// assert_eq!(BYTES, 511 * 32 + 256 * 4);
    /// ```
    pub const fn bytes_needed<B: BoundingVolume>(&self, n: usize) -> usize {
        max_nodes(n) * core::mem::size_of::<Node<B>>() + self.index_capacity(n) * 4
    }

    /// Whether this configuration takes the binned-SAH fast path only, the
    /// one a build without the `strategies` feature supports: `Bins(k)`,
    /// `SurfaceArea`, and x/y/z or the longest axis.
    pub const fn is_binned_sah(&self) -> bool {
        matches!(
            (self.split, self.axis, self.partition),
            (
                SplitPoint::Bins(_),
                AxisChoice::BestOfXyz | AxisChoice::Longest,
                Partition::SurfaceArea
            )
        )
    }

    fn check(&self) -> Result<(), Error> {
        if !cfg!(feature = "strategies") && !self.is_binned_sah() {
            return Err(Error::InvalidConfig(
                "only binned SAH (Bins, SurfaceArea, BestOfXyz or Longest) is compiled: \
                 enable bvhkit's `strategies` feature for the others",
            ));
        }
        if self.stop.max_leaf_size == 0 {
            return Err(Error::InvalidConfig("max_leaf_size must be at least 1"));
        }
        if self.stop.max_depth as usize > MAX_DEPTH {
            return Err(Error::InvalidConfig(
                "max_depth must be at most MAX_DEPTH (64)",
            ));
        }
        if self.stop.min_volume.is_nan() || self.stop.min_volume < 0.0 {
            return Err(Error::InvalidConfig(
                "min_volume must be a non-negative number",
            ));
        }
        match self.split {
            SplitPoint::Bins(k) if !(2..=MAX_BINS as u8).contains(&k) => {
                return Err(Error::InvalidConfig("bin count must be in 2..=MAX_BINS"))
            }
            SplitPoint::RandomCentroids { count, .. } if !(1..MAX_BINS as u8).contains(&count) => {
                return Err(Error::InvalidConfig(
                    "random candidate count must be in 1..MAX_BINS",
                ))
            }
            SplitPoint::Sweep if self.partition != Partition::SurfaceArea => {
                return Err(Error::InvalidConfig(
                    "the sweep split point evaluates the SurfaceArea criterion only",
                ))
            }
            _ => {}
        }
        if let Partition::Weighted {
            surface_area,
            volume,
            overlap,
            balance,
        } = self.partition
        {
            if ![surface_area, volume, overlap, balance]
                .iter()
                .all(|w| w.is_finite() && *w >= 0.0)
            {
                return Err(Error::InvalidConfig(
                    "weights must be finite and non-negative",
                ));
            }
        }
        Ok(())
    }

    /// Builds a tree over `prims` into the caller's storage, with the least
    /// memory: `nodes` (up to [`max_nodes`]`(n)` entries; running out is an
    /// [`Error::NodeCapacity`]) and `indices`
    /// ([`index_capacity`](Self::index_capacity)`(n)` entries). No allocation.
    ///
    /// Each pass reads primitives through the permuted index array, i.e. in
    /// random order. When memory allows, [`build_cached`](Self::build_cached)
    /// is several times faster on large inputs.
    pub fn build<'a, P: Primitive, B: BoundingVolume>(
        &self,
        prims: &[P],
        nodes: &'a mut [Node<B>],
        indices: &'a mut [u32],
    ) -> Result<Bvh<'a, B>, Error> {
        let n = self.prepare(prims.len(), nodes.len(), indices.len())?;
        let root = validate_bounds(prims)?;
        let (idx, scratch) = indices.split_at_mut(n);
        for (i, slot) in idx.iter_mut().enumerate() {
            *slot = i as u32;
        }
        let src = Indexed(prims);
        let (used, depth, report) = self.run(&src, nodes, idx, scratch, root)?;
        refit_to_contain_children(&mut nodes[..used]);
        let nodes: &'a [Node<B>] = nodes;
        let idx: &'a [u32] = idx;
        Ok(Bvh::from_built(&nodes[..used], idx, depth).with_build_report(report))
    }

    /// Builds like [`build`](Self::build), but first copies every primitive's
    /// bounds into `cache` (`n` entries, 32 bytes each) and partitions those
    /// records instead of indices: every pass then reads memory in order. The
    /// tree is identical to the one [`build`](Self::build) makes.
    ///
    /// ```
    /// use bvhkit::{builders::PrimitiveRef, Aabb, Node, TopDown, Triangle};
    /// use glam::Vec3;
    /// let tris: Vec<Triangle> = (0..1000).map(|i| {
    ///     let o = Vec3::new((i % 10) as f32, (i / 10 % 10) as f32, (i / 100) as f32);
    ///     Triangle::new(o, o + Vec3::X, o + Vec3::Y)
    /// }).collect();
    /// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(tris.len())];
    /// let mut idx = vec![0u32; tris.len()];
    /// let mut cache = vec![PrimitiveRef::EMPTY; tris.len()];
    /// let fast = TopDown::sah().build_cached(&tris, &mut nodes, &mut idx, &mut cache)?.stats();
    /// let mut nodes2 = nodes.clone();
    /// let slow = TopDown::sah().build(&tris, &mut nodes2, &mut idx)?.stats();
    /// assert_eq!(fast, slow);
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn build_cached<'a, P: Primitive, B: BoundingVolume>(
        &self,
        prims: &[P],
        nodes: &'a mut [Node<B>],
        indices: &'a mut [u32],
        cache: &mut [PrimitiveRef],
    ) -> Result<Bvh<'a, B>, Error> {
        let n = self.prepare(prims.len(), nodes.len(), indices.len())?;
        if cache.len() < n {
            return Err(Error::IndexCapacity {
                needed: n,
                available: cache.len(),
            });
        }
        let items = &mut cache[..n];
        // The input check computes every box anyway: the cache is filled
        // in the same pass.
        let root = validate_bounds_each(prims, |i, b| {
            if let Some(slot) = items.get_mut(i) {
                *slot = PrimitiveRef::new(b, i as u32);
            }
        })?;
        // The index array is free until the end: it serves as sweep scratch.
        let (used, depth, report) = self.run(&Cached, nodes, items, indices, root)?;
        for (slot, item) in indices.iter_mut().zip(items.iter()) {
            *slot = item.index();
        }
        // Leaves of a cached build point into `items`, which has the same order.
        refit_to_contain_children(&mut nodes[..used]);
        let nodes: &'a [Node<B>] = nodes;
        let idx: &'a [u32] = indices;
        Ok(Bvh::from_built(&nodes[..used], &idx[..n], depth).with_build_report(report))
    }

    /// The checks of the configuration and the storage (the primitives are
    /// checked by the caller, in its pass over them); returns n.
    fn prepare(&self, n: usize, nodes: usize, indices: usize) -> Result<usize, Error> {
        self.check()?;
        if n > crate::tree::MAX_PRIMITIVES {
            return Err(Error::IndexOverflow { count: n });
        }
        let needed = self.index_capacity(n);
        if indices < needed {
            return Err(Error::IndexCapacity {
                needed,
                available: indices,
            });
        }
        if nodes == 0 && n > 0 {
            return Err(Error::NodeCapacity {
                needed: max_nodes(n),
                available: 0,
            });
        }
        Ok(n)
    }

    /// The skeleton: returns (nodes used, depth, what it did). `root` is
    /// the box around every primitive's box and the box around their
    /// centres, from the input check.
    fn run<S: Source, B: BoundingVolume>(
        &self,
        src: &S,
        nodes: &mut [Node<B>],
        idx: &mut [S::Item],
        scratch: &mut [u32],
        (bounds, centroids): (Aabb, Aabb),
    ) -> Result<(usize, u32, BuildReport), Error> {
        let mut report = BuildReport {
            max_leaf_size: self.stop.max_leaf_size,
            ..BuildReport::default()
        };
        if idx.is_empty() {
            return Ok((0, 0, report)); // the empty tree: no nodes at all
        }
        let root = Task {
            node: 0,
            start: 0,
            end: idx.len() as u32,
            depth: 0,
            bounds,
            centroids,
            tight: true,
        };
        let (used, depth) = self.run_task(src, nodes, idx, scratch, root, &mut report)?;
        Ok((used, depth, report))
    }

    /// One node's decision: its volume, and its two halves unless it is a
    /// leaf (the halves' ranges are relative to `range`).
    fn step<S: Source, B: BoundingVolume>(
        &self,
        src: &S,
        range: &mut [S::Item],
        scratch: &mut [u32],
        task: &mut Task,
        report: &mut BuildReport,
    ) -> (B, Option<Halves>) {
        let bv = B::fit_boxes(&SourceBoxes { src, items: range }, &task.bounds);
        let count = range.len() as u32;
        let stop = count <= self.stop.max_leaf_size
            || u32::from(task.depth) >= self.stop.max_depth
            || (self.stop.min_volume > 0.0 && bv.cost_volume_scaled(1.0) < self.stop.min_volume);
        let halves = if stop {
            None
        } else {
            let m = range.len().min(scratch.len());
            self.split(src, range, &mut scratch[..m], task, &bv, report)
        };
        if halves.is_none() {
            report.oversized_leaves += u32::from(count > self.stop.max_leaf_size);
        }
        (bv, halves)
    }

    /// Builds the subtree of `task` (whose range indexes `idx`) into `nodes`,
    /// its root at `task.node`; returns (nodes used, deepest leaf's depth).
    fn run_task<S: Source, B: BoundingVolume>(
        &self,
        src: &S,
        nodes: &mut [Node<B>],
        idx: &mut [S::Item],
        scratch: &mut [u32],
        task: Task,
        report: &mut BuildReport,
    ) -> Result<(usize, u32), Error> {
        let mut out = Emitted {
            used: task.node as usize + 1,
            depth: 0,
        };
        let total = idx.len();
        let mut store = Store {
            nodes,
            idx,
            scratch,
            total,
        };
        self.subtree(src, &mut store, &task, report, &mut out)?;
        Ok((out.used, out.depth))
    }

    /// One subtree: splits `task` until a leaf, recursing into the smaller
    /// half and continuing with the larger one (as quicksort does), so the
    /// recursion is at most log2(n) + 1 calls deep. Recursion, not a fixed
    /// stack of pending tasks: the stack in use grows with the depth this
    /// build reaches (a few hundred bytes for 64 boxes on a Cortex-M4), where
    /// a fixed stack sized for the largest possible input (33 tasks, 2 KiB)
    /// cost every build the same. The nodes come out in the order the loop
    /// with a stack gave: the same tree, bit for bit.
    fn subtree<S: Source, B: BoundingVolume>(
        &self,
        src: &S,
        store: &mut Store<'_, S::Item, B>,
        task: &Task,
        report: &mut BuildReport,
        out: &mut Emitted,
    ) -> Result<(), Error> {
        // `pair` holds the task to split next (`pair[which]`), then its two
        // halves, the smaller first: one array, so each level of the
        // recursion holds two tasks and nothing else.
        let mut pair = [*task, *task];
        let mut which = 0;
        while self.node(src, store, &mut pair, which, report, out)? {
            self.subtree(src, store, &pair[0], report, out)?;
            which = 1;
        }
        Ok(())
    }

    /// One node of [`subtree`](Self::subtree): `pair[which]`'s. Writes it
    /// (a leaf, or an inner node with two fresh children) and, for an inner
    /// node, puts its two halves' tasks in `pair`, the smaller first, and
    /// returns `true`. Out of line, so that the bins, planes and halves of
    /// the decision are gone before the recursion goes deeper.
    #[inline(never)]
    fn node<S: Source, B: BoundingVolume>(
        &self,
        src: &S,
        store: &mut Store<'_, S::Item, B>,
        pair: &mut [Task; 2],
        which: usize,
        report: &mut BuildReport,
        out: &mut Emitted,
    ) -> Result<bool, Error> {
        let mut task = pair[which];
        let (s, e) = (task.start as usize, task.end as usize);
        let (bv, halves) = self.step(src, &mut store.idx[s..e], store.scratch, &mut task, report);
        let Some(h) = halves else {
            store.nodes[task.node as usize] = Node {
                bv,
                first: task.start,
                count: (e - s) as u32,
            };
            out.depth = out.depth.max(u32::from(task.depth));
            return Ok(false);
        };
        if out.used + 2 > store.nodes.len() {
            return Err(Error::NodeCapacity {
                needed: max_nodes(store.total),
                available: store.nodes.len(),
            });
        }
        let left = out.used as u32;
        out.used += 2;
        store.nodes[task.node as usize] = Node {
            bv,
            first: left,
            count: 0,
        };
        let (l, r) = task.children(left, &h);
        *pair = if l.end - l.start <= r.end - r.start {
            [l, r]
        } else {
            [r, l]
        };
        Ok(true)
    }
}

/// The storage a build writes: nodes, the index array (and its scratch),
/// and the primitive count (for the capacity error).
struct Store<'s, I, B> {
    nodes: &'s mut [Node<B>],
    idx: &'s mut [I],
    scratch: &'s mut [u32],
    total: usize,
}

/// What a build has emitted so far: nodes used, deepest leaf's depth.
struct Emitted {
    used: usize,
    depth: u32,
}

impl Task {
    /// Replaces a box around the centroids by their own box, gathered in
    /// one pass over `range` (in place: the driver's stack frame holds the
    /// only copy of the task).
    // Out of line: rare on the fast path, and its pass's locals stay off
    // the driver's frame.
    #[inline(never)]
    fn tighten<S: Source>(&mut self, src: &S, range: &[S::Item]) {
        if !self.tight {
            self.centroids = bounds_of(src, range).1;
            self.tight = true;
        }
    }

    /// The two halves of this node, in nodes `left` and `left + 1`.
    fn children(&self, left: u32, h: &Halves) -> (Task, Task) {
        let mid = self.start + h.mid as u32;
        let child = |i: usize, start: u32, end: u32| Task {
            node: left + i as u32,
            start,
            end,
            depth: self.depth + 1,
            bounds: h.bounds[i],
            centroids: h.centroids[i],
            tight: h.tight,
        };
        (child(0, self.start, mid), child(1, mid, self.end))
    }
}

/// Makes every parent contain its children's volumes. AABBs and k-DOPs fitted
/// top-down already do; a sphere or OBB fitted to a superset may not contain a
/// child fitted to a subset, so it is enlarged (or replaced by the children's
/// merge when that is smaller). Children always follow their parent in the
/// array, so one reverse sweep sees children before parents.
fn refit_to_contain_children<B: BoundingVolume>(nodes: &mut [Node<B>]) {
    for i in (0..nodes.len()).rev() {
        if let Some((l, r)) = nodes[i].children() {
            let (lb, rb) = (nodes[l as usize].bv, nodes[r as usize].bv);
            nodes[i].bv = containing_children(&nodes[i].bv, &lb, &rb);
        }
    }
}

/// `bv`, or when it misses a child's volume, the smaller of `bv` enlarged
/// to take both children and the children's merge.
fn containing_children<B: BoundingVolume>(bv: &B, lb: &B, rb: &B) -> B {
    if bv.contains(lb) && bv.contains(rb) {
        return *bv;
    }
    let enlarged = bv.merge(lb).merge(rb);
    let merged = lb.merge(rb);
    let mut pick = if merged.cost_volume_scaled(1.0) < enlarged.cost_volume_scaled(1.0) {
        merged
    } else {
        enlarged
    };
    // Merges are conservative but a rounding step may still leave a hair
    // outside; fall back to merging again until containment holds.
    for _ in 0..4 {
        if pick.contains(lb) && pick.contains(rb) {
            break;
        }
        pick = pick.merge(lb).merge(rb);
    }
    pick
}

#[cfg(test)]
mod feature_tests {
    use super::*;
    use crate::Triangle;
    use glam::Vec3;

    fn tris() -> [Triangle; 40] {
        core::array::from_fn(|i| {
            let o = Vec3::new((i % 8) as f32, (i / 8) as f32, 0.0);
            Triangle::new(o, o + Vec3::X, o + Vec3::Y)
        })
    }

    /// Binned SAH builds in every feature set, with any bin count or axis.
    #[test]
    fn binned_sah_builds_with_and_without_strategies() {
        let prims = tris();
        for cfg in [
            TopDown::sah(),
            TopDown {
                split: SplitPoint::Bins(8),
                ..TopDown::sah()
            },
            TopDown {
                axis: AxisChoice::Longest,
                ..TopDown::sah()
            },
        ] {
            assert!(cfg.is_binned_sah());
            let mut nodes = [Node::<Aabb>::ZERO; 79];
            let mut idx = [0u32; 40];
            let t = cfg.build(&prims, &mut nodes, &mut idx).unwrap();
            assert_eq!(t.primitive_count(), 40);
        }
    }

    /// Below the root, the bins span each node's box (the partition does
    /// not gather the centroids' box). When that box is much larger than
    /// the centroids' (one large triangle around a tight cluster), every
    /// centroid falls in one bin: the split is planned again over the
    /// centroids' own box, not handed to a fallback.
    #[test]
    fn bins_over_a_loose_box_are_retried_over_the_centroids() {
        let tri = |o: Vec3, s: f32| Triangle::new(o, o + Vec3::X * s, o + Vec3::Y * s);
        let mut prims = [tri(Vec3::ZERO, 0.0); 14];
        // A triangle whose box centre is (50, 50, 0), around eight small
        // ones within 0.1 of it ...
        prims[0] = tri(Vec3::ZERO, 100.0);
        for (i, p) in prims[1..9].iter_mut().enumerate() {
            *p = tri(Vec3::new(50.0 + 0.01 * i as f32, 50.0, 0.0), 0.01);
        }
        // ... and five far away, which the root splits off.
        for (i, p) in prims[9..].iter_mut().enumerate() {
            *p = tri(Vec3::new(1000.0 + i as f32, 0.0, 0.0), 0.5);
        }
        let mut nodes = [Node::<Aabb>::ZERO; 27];
        let mut idx = [0u32; 14];
        let t = TopDown::sah().build(&prims, &mut nodes, &mut idx).unwrap();
        assert_eq!(t.build_report().fallback_splits, 0);
        assert_eq!(t.build_report().oversized_leaves, 0);
        assert_eq!(t.primitive_count(), 14);
    }

    /// Other configurations build only with `strategies`; without it they
    /// are a clear error, never a silently different tree.
    #[test]
    fn other_strategies_need_the_feature() {
        let prims = tris();
        for cfg in [
            TopDown::median(),
            TopDown::sah_sweep(),
            TopDown {
                axis: AxisChoice::X,
                ..TopDown::sah()
            },
            TopDown {
                partition: Partition::Volume,
                ..TopDown::sah()
            },
        ] {
            assert!(!cfg.is_binned_sah());
            let mut nodes = [Node::<Aabb>::ZERO; 79];
            let mut idx = [0u32; 80];
            let r = cfg.build(&prims, &mut nodes, &mut idx);
            if cfg!(feature = "strategies") {
                assert_eq!(r.unwrap().primitive_count(), 40);
            } else {
                assert!(matches!(r, Err(Error::InvalidConfig(_))), "{cfg:?}");
            }
        }
    }
}
