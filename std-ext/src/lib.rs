//! # bvhkit-std
//!
//! The std side of bvhkit. The core crate never allocates; this crate is
//! where `Vec`s, files, threads and clocks live:
//!
//! - [`mesh`]: OBJ, STL, PLY and OFF files into triangles, every error naming
//!   the file and the line (or byte);
//! - [`OwnedBvh`] (the core's owned tree) and [`ParallelBuild`], the same tree
//!   built on every core, bit for bit;
//! - [`scene`]: the built-in scenes (a rock, a scene of mixed objects);
//! - [`TrackerBuffers`]: heap storage for the core's incremental broad phase.
//!
//! ## Features
//!
//! | feature | default | adds | brings in |
//! |---|---|---|---|
//! | `obj`, `stl`, `ply` | on | that mesh format ([`mesh`]; OFF needs nothing) | `tobj`, `stl_io`, `ply-rs` |
//! | `parallel` | on | [`ParallelBuild`], `parallel` | `rayon` |
//! | `cli` | off | the `bvhkit` command-line tool and its reports (tour, stats, collide, advise, cost model, bench report, the book's figures) | `clap`, `serde`, `serde_json`, `indicatif`, `plotters`, `quickhull`, `time` |
//!
//! A program that loads meshes depends on the defaults and compiles none of
//! the tool's dependencies. The tool: `cargo install bvhkit-std --features cli`,
//! or in this repository `cargo run --release -p bvhkit-std --features cli --bin bvhkit -- tour`.
//!
//! ```
//! use bvhkit::{Aabb, TopDown};
//! use bvhkit_std::OwnedBvh;
//! # let dir = std::env::temp_dir().join("bvhkit-std-lib-doc");
//! # std::fs::create_dir_all(&dir).unwrap();
//! # let path = dir.join("quad.off");
//! # std::fs::write(&path, "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n").unwrap();
//! let triangles = bvhkit_std::mesh::load(&path)?; // a quad: two triangles
//! let tree = OwnedBvh::<Aabb>::build(&TopDown::default(), &triangles)?;
//! assert_eq!(tree.view().indices().len(), 2);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#[cfg(feature = "cli")]
pub mod advisor;
#[cfg(feature = "cli")]
pub mod builders;
#[cfg(feature = "cli")]
pub mod collide;
#[cfg(feature = "cli")]
pub mod cost;
#[cfg(feature = "cli")]
pub mod cost_fit;
#[cfg(feature = "cli")]
pub mod figures;
#[cfg(feature = "cli")]
pub mod hull;
#[cfg(feature = "cli")]
pub mod layouts;
pub mod mesh;
#[cfg(feature = "cli")]
pub mod motion;
#[cfg(feature = "cli")]
pub mod near_misses;
#[cfg(feature = "parallel")]
pub mod parallel;
#[cfg(feature = "cli")]
pub mod report;
pub mod scene;
#[cfg(feature = "cli")]
pub mod stamp;
#[cfg(feature = "cli")]
pub mod stats;
#[cfg(feature = "cli")]
pub mod tour;
#[cfg(feature = "cli")]
pub mod volumes;

use bvhkit::Aabb;

// The README's snippet compiles (`cargo test --doc`).
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeSnippet;
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
#[cfg(feature = "parallel")]
pub trait ParallelBuild: Sized {
    /// Builds with `builder` on rayon's pool.
    fn build_parallel<P: bvhkit::Primitive + Sync>(
        builder: &bvhkit::TopDown,
        prims: &[P],
    ) -> Result<Self, bvhkit::Error>;
}

#[cfg(feature = "parallel")]
impl<B: bvhkit::BoundingVolume + Send + Sync> ParallelBuild for OwnedBvh<B> {
    fn build_parallel<P: bvhkit::Primitive + Sync>(
        builder: &bvhkit::TopDown,
        prims: &[P],
    ) -> Result<Self, bvhkit::Error> {
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
