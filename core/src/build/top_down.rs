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

use super::strategy::{AxisChoice, OnFailure, Partition, SplitPoint, Stop, MAX_BINS};
use crate::bv::BoxSet;
use crate::bv::{Aabb, BoundingVolume};
use crate::primitive::{validate, Primitive};
use crate::tree::{max_nodes, Bvh, Node, MAX_DEPTH};
use crate::Error;
use glam::{BVec3A, DMat3, DVec3, Vec3, Vec3A};

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
    depth: u32,
    bounds: Aabb,
    centroids: Aabb,
}

/// Result of partitioning a range: the split position and both halves' bounds.
#[derive(Clone, Copy, Debug)]
struct Halves {
    mid: usize,
    bounds: [Aabb; 2],
    centroids: [Aabb; 2],
}

/// How primitives are assigned to bins along one direction.
#[derive(Clone, Copy, Debug)]
enum Binning {
    /// `k` equal bins over `[lo, lo + k / scale]`.
    Even { lo: f32, scale: f32, k: usize },
    /// Bin `i` holds `planes[i-1] <= t < planes[i]`; `m` planes, `m + 1` bins.
    Planes { planes: [f32; MAX_BINS], m: usize },
}

impl Binning {
    #[inline]
    fn bins(&self) -> usize {
        match *self {
            Binning::Even { k, .. } => k,
            Binning::Planes { m, .. } => m + 1,
        }
    }
    #[inline]
    fn bin(&self, t: f32) -> usize {
        match *self {
            Binning::Even { lo, scale, k } => even_bin(t, lo, scale, k),
            Binning::Planes { ref planes, m } => planes[..m].partition_point(|&p| p <= t),
        }
    }
}

#[inline(always)]
fn even_bin(t: f32, lo: f32, scale: f32, k: usize) -> usize {
    // `as usize` saturates negative values to 0; the min clamps t == hi.
    (((t - lo) * scale) as usize).min(k - 1)
}

#[derive(Clone, Copy, Debug)]
struct Bin {
    bounds: Aabb,
    count: u32,
}

const EMPTY_BIN: Bin = Bin {
    bounds: Aabb::EMPTY,
    count: 0,
};

/// A bin's bounds in 4-lane registers (the fourth lane is unused).
#[derive(Clone, Copy, Debug)]
struct LaneBin {
    min: Vec3A,
    max: Vec3A,
}

impl LaneBin {
    const EMPTY: LaneBin = LaneBin {
        min: Vec3A::splat(f32::INFINITY),
        max: Vec3A::splat(f32::NEG_INFINITY),
    };
    /// `Aabb::union`'s operand order, lane by lane.
    #[inline(always)]
    fn union(&self, other: &LaneBin) -> LaneBin {
        LaneBin {
            min: other.min.min(self.min),
            max: other.max.max(self.max),
        }
    }
    #[inline(always)]
    fn aabb(&self) -> Aabb {
        Aabb::new(self.min.into(), self.max.into())
    }
    #[inline(always)]
    fn of(b: &Aabb) -> LaneBin {
        LaneBin {
            min: b.min.into(),
            max: b.max.into(),
        }
    }
}

/// A chosen split, before the range is partitioned.
#[derive(Clone, Copy, Debug)]
enum Plan {
    /// Left iff `binning.bin(dir . c) < boundary`.
    Plane {
        dir: Vec3,
        binning: Binning,
        boundary: usize,
    },
    /// Left iff `bin(c[axis]) < boundary` with even bins (the fast path).
    Axis {
        axis: usize,
        lo: f32,
        scale: f32,
        k: usize,
        boundary: usize,
        /// The left count and both children's boxes, when the bins gave them.
        known: Option<(usize, [Aabb; 2])>,
    },
    /// The `mid` primitives with the smallest `dir . c` go left.
    Order { dir: Vec3, mid: usize },
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
        let n = self.prepare(prims, nodes.len(), indices.len())?;
        let (idx, scratch) = indices.split_at_mut(n);
        for (i, slot) in idx.iter_mut().enumerate() {
            *slot = i as u32;
        }
        let src = Indexed(prims);
        let (used, depth) = self.run(&src, nodes, idx, scratch)?;
        refit_to_contain_children(&mut nodes[..used]);
        let nodes: &'a [Node<B>] = nodes;
        let idx: &'a [u32] = idx;
        Ok(Bvh::from_built(&nodes[..used], idx, depth))
    }

    /// Builds like [`build`](Self::build), but first copies every primitive's
    /// bounds into `cache` (`n` entries, 28 bytes each) and partitions those
    /// records instead of indices: every pass then reads memory in order. The
    /// tree is identical to the one [`build`](Self::build) makes.
    ///
    /// ```
    /// use bvhkit::{build::PrimitiveRef, Aabb, Node, TopDown, Triangle};
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
        let n = self.prepare(prims, nodes.len(), indices.len())?;
        if cache.len() < n {
            return Err(Error::IndexCapacity {
                needed: n,
                available: cache.len(),
            });
        }
        let items = &mut cache[..n];
        for (i, (slot, p)) in items.iter_mut().zip(prims).enumerate() {
            *slot = PrimitiveRef {
                bounds: p.bounds(),
                index: i as u32,
            };
        }
        // The index array is free until the end: it serves as sweep scratch.
        let (used, depth) = self.run(&Cached, nodes, items, indices)?;
        for (slot, item) in indices.iter_mut().zip(items.iter()) {
            *slot = item.index;
        }
        // Leaves of a cached build point into `items`, which has the same order.
        refit_to_contain_children(&mut nodes[..used]);
        let nodes: &'a [Node<B>] = nodes;
        let idx: &'a [u32] = indices;
        Ok(Bvh::from_built(&nodes[..used], &idx[..n], depth))
    }

    /// Shared input checks; returns n.
    fn prepare<P: Primitive>(
        &self,
        prims: &[P],
        nodes: usize,
        indices: usize,
    ) -> Result<usize, Error> {
        self.check()?;
        validate(prims)?;
        let n = prims.len();
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

    /// The skeleton: returns (nodes used, depth).
    fn run<S: Source, B: BoundingVolume>(
        &self,
        src: &S,
        nodes: &mut [Node<B>],
        idx: &mut [S::Item],
        scratch: &mut [u32],
    ) -> Result<(usize, u32), Error> {
        if idx.is_empty() {
            return Ok((0, 0)); // the empty tree: no nodes at all
        }
        let (bounds, centroids) = bounds_of(src, idx);
        const STACK: usize = 33; // >= log2(MAX_PRIMITIVES) + 2
        let mut stack = [Task {
            node: 0,
            start: 0,
            end: 0,
            depth: 0,
            bounds: Aabb::EMPTY,
            centroids: Aabb::EMPTY,
        }; STACK];
        let mut top = 0;
        let mut used = 1usize;
        let mut max_depth = 0u32;
        let mut task = Task {
            node: 0,
            start: 0,
            end: idx.len() as u32,
            depth: 0,
            bounds,
            centroids,
        };
        loop {
            let (s, e) = (task.start as usize, task.end as usize);
            let range = &mut idx[s..e];
            let bv = B::fit_boxes(&SourceBoxes { src, items: range }, &task.bounds);
            let count = (e - s) as u32;
            let stop = count <= self.stop.max_leaf_size
                || task.depth >= self.stop.max_depth
                || (self.stop.min_volume > 0.0 && bv.volume() < self.stop.min_volume);
            let halves = if stop {
                None
            } else {
                let m = range.len().min(scratch.len());
                self.split(src, range, &mut scratch[..m], &task, &bv)
            };
            match halves {
                None => {
                    nodes[task.node as usize] = Node {
                        bv,
                        first: task.start,
                        count,
                    };
                    max_depth = max_depth.max(task.depth);
                    if top == 0 {
                        break;
                    }
                    top -= 1;
                    task = stack[top];
                }
                Some(h) => {
                    if used + 2 > nodes.len() {
                        return Err(Error::NodeCapacity {
                            needed: max_nodes(idx.len()),
                            available: nodes.len(),
                        });
                    }
                    let left = used as u32;
                    used += 2;
                    nodes[task.node as usize] = Node {
                        bv,
                        first: left,
                        count: 0,
                    };
                    let mid = (s + h.mid) as u32;
                    let child = |i: usize, start: u32, end: u32| Task {
                        node: left + i as u32,
                        start,
                        end,
                        depth: task.depth + 1,
                        bounds: h.bounds[i],
                        centroids: h.centroids[i],
                    };
                    let l = child(0, task.start, mid);
                    let r = child(1, mid, task.end);
                    // Defer the larger half and continue with the smaller one (as
                    // quicksort recurses on the smaller side): everything pushed
                    // before the deferred half is popped lies inside a range at
                    // most half as large, so the stack stays below log2(n) + 1.
                    let (next, later) = if l.end - l.start <= r.end - r.start {
                        (l, r)
                    } else {
                        (r, l)
                    };
                    if top == STACK {
                        return Err(Error::StackOverflow {
                            depth: top,
                            capacity: STACK,
                        });
                    }
                    stack[top] = later;
                    top += 1;
                    task = next;
                }
            }
        }
        Ok((used, max_depth))
    }

    /// Tries the configured strategy, then the fallbacks of the lectures.
    fn split<S: Source, B: BoundingVolume>(
        &self,
        src: &S,
        range: &mut [S::Item],
        scratch: &mut [u32],
        task: &Task,
        bv: &B,
    ) -> Option<Halves> {
        let norm = Norm::new(&task.bounds);
        // Depth budget: a node of n primitives needs log2(n / max leaf)
        // more levels even when halved exactly. A criterion that splits off
        // a few primitives at a time (minimum overlap, maximum separation on
        // a curved surface) would spend the levels left and end in a leaf
        // far over the limit at `max_depth`; once the levels left are only
        // just enough, the node is halved at its object median instead.
        let leaves = range
            .len()
            .div_ceil(self.stop.max_leaf_size.max(1) as usize);
        let needed = usize::BITS - (leaves.max(1) - 1).leading_zeros(); // ceil(log2)
        let left = self.stop.max_depth.saturating_sub(task.depth);
        if needed >= left && leaves > 1 {
            let dir = longest_direction(task);
            let mid = range.len() / 2;
            return Some(apply(src, range, Plan::Order { dir, mid }));
        }
        let mut attempt = |axis: AxisChoice, split: SplitPoint, partition: Partition| {
            let plan = plan(src, range, scratch, task, bv, axis, split, partition, &norm)?;
            let h = apply(src, range, plan);
            (h.mid > 0 && h.mid < range.len()).then_some(h)
        };
        let acceptable = |h: &Halves| {
            !(norm.nearly_as_large(&h.bounds[0], &task.bounds)
                && norm.nearly_as_large(&h.bounds[1], &task.bounds))
        };
        if let Some(h) = attempt(self.axis, self.split, self.partition) {
            if acceptable(&h) {
                return Some(h);
            }
        }
        if self.axis != AxisChoice::BestOfXyz {
            if let Some(h) = attempt(AxisChoice::BestOfXyz, self.split, self.partition) {
                if acceptable(&h) {
                    return Some(h);
                }
            }
        }
        // The object median always separates by count, even identical centroids.
        let dir = longest_direction(task);
        let forced = apply(
            src,
            range,
            Plan::Order {
                dir,
                mid: range.len() / 2,
            },
        );
        match self.on_failure {
            OnFailure::ForceSplit => Some(forced),
            OnFailure::Leaf => acceptable(&forced).then_some(forced),
        }
    }
}

/// Node bounds and centroid bounds over an index range.
fn bounds_of<S: Source>(src: &S, idx: &[S::Item]) -> (Aabb, Aabb) {
    let mut b = Aabb::EMPTY;
    let mut c = Aabb::EMPTY;
    for &i in idx {
        let bounds = src.bounds(i);
        b = b.union(&bounds);
        c.grow(bounds.center());
    }
    (b, c)
}

/// Parent-relative coordinates: every cost is computed on boxes scaled into the
/// unit cube of the parent, so areas and volumes never overflow at 1e30.
#[derive(Clone, Copy, Debug)]
struct Norm {
    origin: Vec3,
    inv: f32,
}

impl Norm {
    fn new(parent: &Aabb) -> Self {
        let ext = parent.extent().max_element();
        Norm {
            origin: parent.min,
            inv: if ext > 0.0 { 1.0 / ext } else { 1.0 },
        }
    }
    #[inline]
    fn apply(&self, b: &Aabb) -> Aabb {
        Aabb::new(
            (b.min - self.origin) * self.inv,
            (b.max - self.origin) * self.inv,
        )
    }
    #[inline]
    fn half_area(&self, b: &Aabb) -> f32 {
        let e = (b.extent() * self.inv).max(Vec3::ZERO);
        e.x * e.y + e.y * e.z + e.z * e.x
    }
    /// [`half_area`](Self::half_area) of a bin in 4-lane registers: the same
    /// operations lane by lane, so the same value.
    #[inline(always)]
    fn half_area_lanes(&self, b: &LaneBin) -> f32 {
        let e = ((b.max - b.min) * self.inv).max(Vec3A::ZERO);
        e.x * e.y + e.y * e.z + e.z * e.x
    }
    /// Both the area and the longest side are within 1% of the parent's.
    fn nearly_as_large(&self, child: &Aabb, parent: &Aabb) -> bool {
        self.half_area(child) >= 0.99 * self.half_area(parent)
            && child.extent().max_element() >= 0.99 * parent.extent().max_element()
    }
}

/// Cost of a candidate split under a criterion (lower is better).
#[allow(clippy::too_many_arguments)]
fn cost<B: BoundingVolume>(
    partition: Partition,
    norm: &Norm,
    parent: &Aabb,
    l: &Aabb,
    nl: u32,
    r: &Aabb,
    nr: u32,
) -> f32 {
    let vol = |b: &Aabb| B::from_aabb(&norm.apply(b)).volume();
    let sah = || {
        (norm.half_area(l) * nl as f32 + norm.half_area(r) * nr as f32)
            / (norm.half_area(parent).max(f32::MIN_POSITIVE) * (nl + nr) as f32)
    };
    let overlap = || match l.intersection(r) {
        Some(i) => vol(&i) + norm.half_area(&i) * 1e-3,
        None => 0.0,
    };
    let balance = || (nl as f32 - nr as f32).abs() / (nl + nr) as f32;
    match partition {
        Partition::Balance => balance(),
        Partition::SurfaceArea => sah(),
        Partition::Volume => vol(l) + vol(r),
        Partition::LargerChild => vol(l).max(vol(r)),
        Partition::Overlap => overlap(),
        Partition::Separation => {
            let (a, b) = (norm.apply(l), norm.apply(r));
            let gap = (a.min - b.max).max(b.min - a.max).max_element();
            -gap
        }
        Partition::Weighted {
            surface_area,
            volume,
            overlap: w_overlap,
            balance: w_balance,
        } => {
            let mut c = 0.0;
            if surface_area > 0.0 {
                c += surface_area * sah();
            }
            if volume > 0.0 {
                c += volume * (vol(l) + vol(r));
            }
            if w_overlap > 0.0 {
                c += w_overlap * overlap();
            }
            if w_balance > 0.0 {
                c += w_balance * balance();
            }
            c
        }
    }
}

/// The coordinate axis along which the centroids spread most (the boxes, when
/// every centroid coincides).
fn longest_direction(task: &Task) -> Vec3 {
    let c = if task.centroids.extent().max_element() > 0.0 {
        task.centroids
    } else {
        task.bounds
    };
    crate::bv::Axes::XYZ.axes[c.longest_axis()]
}

/// Candidate directions for an axis choice (at most 13).
fn directions<S: Source, B: BoundingVolume>(
    src: &S,
    range: &[S::Item],
    task: &Task,
    bv: &B,
    axis: AxisChoice,
) -> crate::bv::Axes {
    use crate::bv::Axes;
    let one = |d: Vec3| {
        let mut a = Axes::XYZ;
        a.axes[0] = d;
        a.len = 1;
        a
    };
    match axis {
        AxisChoice::X => one(Vec3::X),
        AxisChoice::Y => one(Vec3::Y),
        AxisChoice::Z => one(Vec3::Z),
        AxisChoice::BestOfXyz => Axes::XYZ,
        AxisChoice::Longest => one(longest_direction(task)),
        AxisChoice::Variance => one(principal_direction(src, range)),
        AxisChoice::DistantPoints => one(distant_direction(src, range)),
        AxisChoice::ParentVolume => bv.axes(),
    }
}

/// Principal component of the centroids (normalised covariance, f64 Jacobi).
fn principal_direction<S: Source>(src: &S, range: &[S::Item]) -> Vec3 {
    let n = range.len() as f64;
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    let mut mean = DVec3::ZERO;
    for &i in range {
        let c = centroid(src, i).as_dvec3();
        mean += c;
        lo = lo.min(c);
        hi = hi.max(c);
    }
    mean /= n;
    let scale = 1.0 / (hi - lo).max_element().max(f64::MIN_POSITIVE);
    let mut cov = DMat3::ZERO;
    for &i in range {
        let v = (centroid(src, i).as_dvec3() - mean) * scale;
        cov += DMat3::from_cols(v * v.x, v * v.y, v * v.z);
    }
    let (_, vecs) = crate::bv::symmetric_eigen(cov);
    let d = vecs.x_axis.as_vec3();
    if d.is_finite() && d.length_squared() > 0.5 {
        d
    } else {
        Vec3::X
    }
}

/// Direction through the most distant pair among the six axis-extreme centroids.
fn distant_direction<S: Source>(src: &S, range: &[S::Item]) -> Vec3 {
    let c = |i: S::Item| centroid(src, i);
    let mut lo = [range[0]; 3];
    let mut hi = [range[0]; 3];
    for &i in range {
        let p = c(i);
        for k in 0..3 {
            if p[k] < c(lo[k])[k] {
                lo[k] = i;
            }
            if p[k] > c(hi[k])[k] {
                hi[k] = i;
            }
        }
    }
    let mut best = Vec3::X;
    let mut best_d = -1.0f64;
    for k in 0..3 {
        let v = c(hi[k]).as_dvec3() - c(lo[k]).as_dvec3();
        if v.length_squared() > best_d {
            best_d = v.length_squared();
            best = v.normalize_or(DVec3::X).as_vec3();
        }
    }
    best
}

/// Scores candidate splits and returns the best plan (without moving anything
/// except for median/sweep evaluation, which reorder the range).
#[allow(clippy::too_many_arguments)]
fn plan<S: Source, B: BoundingVolume>(
    src: &S,
    range: &mut [S::Item],
    scratch: &mut [u32],
    task: &Task,
    bv: &B,
    axis: AxisChoice,
    split: SplitPoint,
    partition: Partition,
    norm: &Norm,
) -> Option<Plan> {
    if let (
        SplitPoint::Bins(k),
        AxisChoice::BestOfXyz | AxisChoice::Longest,
        Partition::SurfaceArea,
    ) = (split, axis, partition)
    {
        let mut axes = [true; 3];
        if axis == AxisChoice::Longest {
            let l = task.centroids.longest_axis();
            axes = [l == 0, l == 1, l == 2];
        }
        // More bins than primitives cannot help; a bin array sized to the node
        // keeps the fixed cost of the many small nodes near the leaves low.
        let k = (k as usize).min(range.len().max(2));
        return match k {
            0..=4 => plan_binned_sah::<S, 4>(src, range, task, k, axes, norm),
            5..=8 => plan_binned_sah::<S, 8>(src, range, task, k, axes, norm),
            9..=16 => plan_binned_sah::<S, 16>(src, range, task, k, axes, norm),
            _ => plan_binned_sah::<S, MAX_BINS>(src, range, task, k, axes, norm),
        };
    }
    #[cfg(feature = "strategies")]
    return plan_by_directions(src, range, scratch, task, bv, axis, split, partition, norm);
    // `check` refused every other configuration.
    #[cfg(not(feature = "strategies"))]
    {
        let _ = (scratch, bv);
        None
    }
}

/// Every other combination: candidate directions, each scored by its split
/// point. Kept out of [`plan`] so its frame is not on the stack of the fast path.
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn plan_by_directions<S: Source, B: BoundingVolume>(
    src: &S,
    range: &mut [S::Item],
    scratch: &mut [u32],
    task: &Task,
    bv: &B,
    axis: AxisChoice,
    split: SplitPoint,
    partition: Partition,
    norm: &Norm,
) -> Option<Plan> {
    let dirs = directions(src, range, task, bv, axis);
    let mut best: Option<(f32, Plan)> = None;
    let mut consider = |c: f32, p: Plan| {
        if best.is_none_or(|(b, _)| c < b) {
            best = Some((c, p));
        }
    };
    for &dir in dirs.as_slice() {
        let t = |i: S::Item| dir.dot(centroid(src, i));
        let (lo, hi) = projection_range(range, &t, dir, &task.centroids);
        if hi.partial_cmp(&lo) != Some(core::cmp::Ordering::Greater) {
            continue; // every centroid projects to one point: nothing to split
        }
        match split {
            SplitPoint::ObjectMedian => {
                let mid = range.len() / 2;
                range.select_nth_unstable_by(mid, |&a, &b| {
                    t(a).total_cmp(&t(b)).then(src.id(a).cmp(&src.id(b)))
                });
                let (l, _) = bounds_of(src, &range[..mid]);
                let (r, _) = bounds_of(src, &range[mid..]);
                let c = cost::<B>(
                    partition,
                    norm,
                    &task.bounds,
                    &l,
                    mid as u32,
                    &r,
                    (range.len() - mid) as u32,
                );
                consider(c, Plan::Order { dir, mid });
            }
            SplitPoint::Sweep => {
                if let Some((c, mid)) = sweep_sah(src, range, scratch, &t, norm) {
                    consider(c, Plan::Order { dir, mid });
                }
            }
            _ => {
                let binning = match split {
                    SplitPoint::Bins(k) => Binning::Even {
                        lo,
                        scale: k as f32 / (hi - lo),
                        k: k as usize,
                    },
                    SplitPoint::SpatialMedian => planes(&[lo * 0.5 + hi * 0.5]),
                    SplitPoint::ObjectMean => {
                        let mean =
                            range.iter().map(|&i| t(i) as f64).sum::<f64>() / range.len() as f64;
                        planes(&[mean as f32])
                    }
                    SplitPoint::RandomCentroids { count, seed } => {
                        let mut rng =
                            SplitMix(seed ^ (task.node as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
                        let mut p = [0.0f32; MAX_BINS];
                        let m = (count as usize).min(MAX_BINS);
                        for slot in p.iter_mut().take(m) {
                            *slot = t(range[(rng.next() % range.len() as u64) as usize]);
                        }
                        planes(&p[..m])
                    }
                    // Handled by the arms above.
                    SplitPoint::ObjectMedian | SplitPoint::Sweep => continue,
                };
                if let Some((c, boundary)) =
                    evaluate_bins::<S, B>(src, range, &t, &binning, partition, norm, task)
                {
                    consider(
                        c,
                        Plan::Plane {
                            dir,
                            binning,
                            boundary,
                        },
                    );
                }
            }
        }
    }
    best.map(|(_, p)| p)
}

fn planes(values: &[f32]) -> Binning {
    let mut p = [0.0f32; MAX_BINS];
    let m = values.len().min(MAX_BINS - 1);
    p[..m].copy_from_slice(&values[..m]);
    p[..m].sort_unstable_by(f32::total_cmp);
    // Remove duplicates so no bin is empty by construction.
    let mut k = 0;
    for i in 0..m {
        if k == 0 || p[i] != p[k - 1] {
            p[k] = p[i];
            k += 1;
        }
    }
    Binning::Planes { planes: p, m: k }
}

fn projection_range<T: Copy>(
    range: &[T],
    t: &impl Fn(T) -> f32,
    dir: Vec3,
    centroids: &Aabb,
) -> (f32, f32) {
    for k in 0..3 {
        if dir == crate::bv::Axes::XYZ.axes[k] {
            return (centroids.min[k], centroids.max[k]);
        }
    }
    let mut lo = f32::INFINITY;
    let mut hi = f32::NEG_INFINITY;
    for &i in range {
        let v = t(i);
        lo = lo.min(v);
        hi = hi.max(v);
    }
    (lo, hi)
}

/// Bins the range and scores every boundary; returns (cost, boundary).
fn evaluate_bins<S: Source, B: BoundingVolume>(
    src: &S,
    range: &[S::Item],
    t: &impl Fn(S::Item) -> f32,
    binning: &Binning,
    partition: Partition,
    norm: &Norm,
    task: &Task,
) -> Option<(f32, usize)> {
    let k = binning.bins();
    let mut bins = [EMPTY_BIN; MAX_BINS];
    for &i in range {
        let b = &mut bins[binning.bin(t(i))];
        b.bounds = b.bounds.union(&src.bounds(i));
        b.count += 1;
    }
    let mut right = [EMPTY_BIN; MAX_BINS];
    let mut acc = EMPTY_BIN;
    for j in (1..k).rev() {
        acc.bounds = acc.bounds.union(&bins[j].bounds);
        acc.count += bins[j].count;
        right[j] = acc;
    }
    let mut left = EMPTY_BIN;
    let mut best: Option<(f32, usize)> = None;
    for j in 1..k {
        left.bounds = left.bounds.union(&bins[j - 1].bounds);
        left.count += bins[j - 1].count;
        if left.count == 0 || right[j].count == 0 {
            continue;
        }
        let c = cost::<B>(
            partition,
            norm,
            &task.bounds,
            &left.bounds,
            left.count,
            &right[j].bounds,
            right[j].count,
        );
        if best.is_none_or(|(b, _)| c < b) {
            best = Some((c, j));
        }
    }
    best
}

/// The fast path: one pass bins every primitive along x, y and z at once.
/// Not inlined, so that only the bin array of the size in use is on the
/// stack (inlined, all four sizes' frames add up: 4 KiB on a Cortex-M4).
#[inline(never)]
fn plan_binned_sah<S: Source, const N: usize>(
    src: &S,
    range: &[S::Item],
    task: &Task,
    k: usize,
    axes: [bool; 3],
    norm: &Norm,
) -> Option<Plan> {
    let k = k.min(N);
    let c = &task.centroids;
    let ext = c.extent();
    let mut scale = [0.0f32; 3];
    for a in 0..3 {
        scale[a] = if ext[a] > 0.0 && axes[a] {
            k as f32 / ext[a]
        } else {
            0.0
        };
    }
    if axes != [true; 3] {
        // One axis: bin only along it.
        let a = axes.iter().position(|&x| x)?;
        if scale[a] == 0.0 {
            return None;
        }
        let (mut bins, mut counts) = ([LaneBin::EMPTY; N], [0u32; N]);
        for &i in range {
            let b = src.bounds(i);
            let j = even_bin(b.center()[a], c.min[a], scale[a], k);
            bins[j] = bins[j].union(&LaneBin::of(&b));
            counts[j] += 1;
        }
        return best_boundary(&bins[..k], &counts[..k], range.len(), norm).map(|(_, boundary)| {
            Plan::Axis {
                axis: a,
                lo: c.min[a],
                scale: scale[a],
                k,
                boundary,
                known: None,
            }
        });
    }
    // Bin bounds in 4-lane registers: a union is two instructions, and the
    // three bin indices come from one subtract and multiply. Each lane does
    // the scalar path's arithmetic (`Aabb::center`, `even_bin`, `Aabb::union`
    // with the same operand order), so the bins, and the tree, are the same
    // as one axis at a time would give.
    let mut lanes = [[LaneBin::EMPTY; N]; 3];
    let mut counts = [[0u32; N]; 3];
    let (lo_c, sc) = (Vec3A::from(c.min), Vec3A::from(Vec3::from(scale)));
    let top = k.clamp(1, N) - 1; // < N: no bounds check in the loop
    let top_f = Vec3A::splat(top as f32);
    for &i in range {
        let b = src.bounds(i);
        let (lo, hi) = (Vec3A::from(b.min), Vec3A::from(b.max));
        let t = ((lo * 0.5 + hi * 0.5) - lo_c) * sc;
        // Clamping before the conversion is `(t as usize).min(top)`: top is
        // a whole number and t is finite.
        let t = t.max(Vec3A::ZERO).min(top_f);
        for a in 0..3 {
            let j = (t[a] as i32 as usize).min(top);
            let bin = &mut lanes[a][j];
            bin.min = lo.min(bin.min);
            bin.max = hi.max(bin.max);
            counts[a][j] += 1;
        }
    }
    let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, boundary)
    for a in (0..3).filter(|&a| scale[a] != 0.0) {
        if let Some((cost, j)) = best_boundary(&lanes[a][..k], &counts[a][..k], range.len(), norm) {
            if best.is_none_or(|(b, _, _)| cost < b) {
                best = Some((cost, a, j));
            }
        }
    }
    let (_, a, boundary) = best?;
    // The children's boxes are the unions of their bins, exactly the boxes
    // of the primitives the partition will put on each side.
    let (mut halves, mut mid) = ([LaneBin::EMPTY; 2], 0u32);
    for j in 0..k {
        let side = usize::from(j >= boundary);
        halves[side] = halves[side].union(&lanes[a][j]);
        mid += if side == 0 { counts[a][j] } else { 0 };
    }
    Some(Plan::Axis {
        axis: a,
        lo: c.min[a],
        scale: scale[a],
        k,
        boundary,
        known: Some((mid as usize, [halves[0].aabb(), halves[1].aabb()])),
    })
}

/// The SAH-best boundary of a row of bins (`counts[j]` primitives in bin
/// `j`, `n` in all): (cost, boundary). The first of equal costs wins.
fn best_boundary(bins: &[LaneBin], counts: &[u32], n: usize, norm: &Norm) -> Option<(f32, usize)> {
    let k = bins.len();
    let mut right_cost = [0.0f32; MAX_BINS];
    let (mut acc, mut m) = (LaneBin::EMPTY, 0u32);
    for j in (1..k).rev() {
        acc = acc.union(&bins[j]);
        m += counts[j];
        right_cost[j] = norm.half_area_lanes(&acc) * m as f32;
    }
    let (mut left, mut m) = (LaneBin::EMPTY, 0u32);
    let mut best: Option<(f32, usize)> = None;
    for j in 1..k {
        left = left.union(&bins[j - 1]);
        m += counts[j - 1];
        if m == 0 || m as usize == n {
            continue;
        }
        let c = norm.half_area_lanes(&left) * m as f32 + right_cost[j];
        if best.is_none_or(|(b, _)| c < b) {
            best = Some((c, j));
        }
    }
    best
}

/// Exact SAH sweep along one direction; `scratch` holds right-side costs as f32 bits.
fn sweep_sah<S: Source>(
    src: &S,
    range: &mut [S::Item],
    scratch: &mut [u32],
    t: &impl Fn(S::Item) -> f32,
    norm: &Norm,
) -> Option<(f32, usize)> {
    let n = range.len();
    if scratch.len() < n {
        return None;
    }
    range.sort_unstable_by(|&a, &b| t(a).total_cmp(&t(b)).then(src.id(a).cmp(&src.id(b))));
    let mut acc = Aabb::EMPTY;
    for j in (1..n).rev() {
        acc = acc.union(&src.bounds(range[j]));
        scratch[j] = (norm.half_area(&acc) * (n - j) as f32).to_bits();
    }
    let mut left = Aabb::EMPTY;
    let mut best: Option<(f32, usize)> = None;
    for j in 1..n {
        left = left.union(&src.bounds(range[j - 1]));
        let c = norm.half_area(&left) * j as f32 + f32::from_bits(scratch[j]);
        if best.is_none_or(|(b, _)| c < b) {
            best = Some((c, j));
        }
    }
    best
}

/// Partitions the range by the plan and measures both halves.
fn apply<S: Source>(src: &S, range: &mut [S::Item], plan: Plan) -> Halves {
    match plan {
        Plan::Axis {
            axis,
            lo,
            scale,
            k: _,
            boundary,
            known: Some((mid, bounds)),
        } => {
            // `even_bin(c, lo, scale, k) < boundary` without the conversion:
            // `boundary <= k - 1` is whole, so truncating first changes nothing.
            let edge = boundary as f32;
            let (left, centroids) = partition_known(src, range, |c| (c - lo) * scale < edge, axis);
            debug_assert_eq!(left, mid, "the partition disagrees with the bins");
            Halves {
                mid: left,
                bounds,
                centroids,
            }
        }
        Plan::Axis {
            axis,
            lo,
            scale,
            k,
            boundary,
            known: None,
        } => partition_by(src, range, |c| even_bin(c[axis], lo, scale, k) < boundary),
        Plan::Plane {
            dir,
            binning,
            boundary,
        } => partition_by(src, range, |c| binning.bin(dir.dot(c)) < boundary),
        Plan::Order { dir, mid } => {
            let t = |i: S::Item| dir.dot(centroid(src, i));
            range.select_nth_unstable_by(mid, |&a, &b| {
                t(a).total_cmp(&t(b)).then(src.id(a).cmp(&src.id(b)))
            });
            let (lb, lc) = bounds_of(src, &range[..mid]);
            let (rb, rc) = bounds_of(src, &range[mid..]);
            Halves {
                mid,
                bounds: [lb, rb],
                centroids: [lc, rc],
            }
        }
    }
}

/// Partitions when the children's boxes are known already (from the bins):
/// only the centroid bounds are gathered. Branch-free (Lomuto's scheme: every
/// element is swapped into place, and the left end advances by the test's
/// result), because at the top of the tree the test is a coin toss that a
/// branch predictor loses half the time. Returns the left count and the
/// centroid bounds of both sides.
#[inline(always)]
fn partition_known<S: Source>(
    src: &S,
    range: &mut [S::Item],
    goes_left: impl Fn(f32) -> bool,
    axis: usize,
) -> (usize, [Aabb; 2]) {
    let (mut lmin, mut lmax) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY);
    let (mut rmin, mut rmax) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY);
    let mut j = 0;
    for i in 0..range.len() {
        let item = range[i];
        let b = src.bounds(item);
        let c = Vec3A::from(b.min) * 0.5 + Vec3A::from(b.max) * 0.5;
        let left = goes_left(c[axis]);
        let m = BVec3A::splat(left);
        // Same operand order as `Aabb::grow`.
        lmin = Vec3A::select(m, c.min(lmin), lmin);
        lmax = Vec3A::select(m, c.max(lmax), lmax);
        rmin = Vec3A::select(m, rmin, c.min(rmin));
        rmax = Vec3A::select(m, rmax, c.max(rmax));
        range[i] = range[j];
        range[j] = item;
        j += usize::from(left);
    }
    (
        j,
        [
            Aabb::new(lmin.into(), lmax.into()),
            Aabb::new(rmin.into(), rmax.into()),
        ],
    )
}

/// In-place two-pointer partition; every element is classified exactly once
/// and its bounds added to its side.
fn partition_by<S: Source>(
    src: &S,
    range: &mut [S::Item],
    goes_left: impl Fn(Vec3) -> bool,
) -> Halves {
    let mut bounds = [Aabb::EMPTY; 2];
    let mut centroids = [Aabb::EMPTY; 2];
    let (mut i, mut j) = (0, range.len());
    while i < j {
        let item = range[i];
        let b = src.bounds(item);
        let c = b.center();
        let side = if goes_left(c) {
            i += 1;
            0
        } else {
            j -= 1;
            range.swap(i, j);
            1
        };
        bounds[side] = bounds[side].union(&b);
        centroids[side].grow(c);
    }
    Halves {
        mid: i,
        bounds,
        centroids,
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
            let bv = nodes[i].bv;
            if bv.contains(&lb) && bv.contains(&rb) {
                continue;
            }
            let enlarged = bv.merge(&lb).merge(&rb);
            let merged = lb.merge(&rb);
            let mut pick = if merged.volume() < enlarged.volume() {
                merged
            } else {
                enlarged
            };
            // Merges are conservative but a rounding step may still leave a hair
            // outside; fall back to merging again until containment holds.
            for _ in 0..4 {
                if pick.contains(&lb) && pick.contains(&rb) {
                    break;
                }
                pick = pick.merge(&lb).merge(&rb);
            }
            nodes[i].bv = pick;
        }
    }
}

/// SplitMix64: a tiny seeded generator for reproducible random candidates.
#[derive(Clone, Copy, Debug)]
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
}

/// A primitive's bounds and its index, cached for [`TopDown::build_cached`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimitiveRef {
    /// Bounds of the primitive.
    pub bounds: Aabb,
    /// Index of the primitive in the caller's slice.
    pub index: u32,
}

impl PrimitiveRef {
    /// A blank record, for initialising storage.
    pub const EMPTY: PrimitiveRef = PrimitiveRef {
        bounds: Aabb::EMPTY,
        index: 0,
    };
}

/// Where the builder reads bounds from: the caller's primitives through an
/// index ([`Indexed`]), or cached records that move with the partition ([`Cached`]).
/// One skeleton serves both.
trait Source {
    type Item: Copy;
    fn bounds(&self, item: Self::Item) -> Aabb;
    /// The primitive's index: breaks ties so every ordering is total, and the
    /// tree does not depend on how an unstable sort treats equal keys.
    fn id(&self, item: Self::Item) -> u32;
}

/// The point builders sort by: the centre of the primitive's bounds.
#[inline(always)]
fn centroid<S: Source>(src: &S, item: S::Item) -> Vec3 {
    src.bounds(item).center()
}

struct Indexed<'a, P>(&'a [P]);

impl<P: Primitive> Source for Indexed<'_, P> {
    type Item = u32;
    #[inline(always)]
    fn bounds(&self, i: u32) -> Aabb {
        self.0[i as usize].bounds()
    }
    #[inline(always)]
    fn id(&self, i: u32) -> u32 {
        i
    }
}

struct Cached;

impl Source for Cached {
    type Item = PrimitiveRef;
    #[inline(always)]
    fn bounds(&self, r: PrimitiveRef) -> Aabb {
        r.bounds
    }
    #[inline(always)]
    fn id(&self, r: PrimitiveRef) -> u32 {
        r.index
    }
}

/// The bounds of a range of items, as a [`BoxSet`] for volume fitting.
struct SourceBoxes<'a, S: Source> {
    src: &'a S,
    items: &'a [S::Item],
}

impl<S: Source> BoxSet for SourceBoxes<'_, S> {
    fn len(&self) -> usize {
        self.items.len()
    }
    fn aabb(&self, i: usize) -> Aabb {
        self.src.bounds(self.items[i])
    }
}

#[cfg(test)]
mod feature_tests {
    use super::*;
    use crate::Triangle;

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
