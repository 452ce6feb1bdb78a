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

use bvhkit::{Aabb, BoundingVolume, Error, Primitive, TopDown};
use std::time::{Duration, Instant};

/// The core's owned tree (its `alloc` feature), re-exported where desktop
/// programs have always found it.
pub use bvhkit::OwnedBvh;

/// [`OwnedBvh::build_forked`] on every core of rayon's current pool
/// ([`parallel::Threads`]): the same tree as the sequential build, bit for
/// bit. A trait so that it reads as a constructor of the core's type.
///
/// ```
/// use bvhkit::{Aabb, TopDown};
/// use bvhkit_std::{OwnedBvh, ParallelBuild};
/// let tris = bvhkit_std::scene::rock(5, 7); // 20,480 triangles
/// let parallel = OwnedBvh::<Aabb>::build_parallel(&TopDown::default(), &tris)?;
/// let sequential = OwnedBvh::<Aabb>::build(&TopDown::default(), &tris)?;
/// assert_eq!(parallel.view().nodes(), sequential.view().nodes());
/// assert_eq!(parallel.view().indices(), sequential.view().indices());
/// # Ok::<(), bvhkit::Error>(())
/// ```
pub trait ParallelBuild: Sized {
    /// Builds with `builder` on rayon's pool.
    fn build_parallel<P: Primitive + Sync>(builder: &TopDown, prims: &[P]) -> Result<Self, Error>;
}

impl<B: BoundingVolume + Send + Sync> ParallelBuild for OwnedBvh<B> {
    fn build_parallel<P: Primitive + Sync>(builder: &TopDown, prims: &[P]) -> Result<Self, Error> {
        OwnedBvh::build_forked(builder, prims, &parallel::Threads::default())
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
