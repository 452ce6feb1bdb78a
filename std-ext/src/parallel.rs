//! Building on every core: a thread pool behind core's [`Fork`].
//!
//! Core's [`TopDown::build_cached_forked`](bvhkit::TopDown::build_cached_forked)
//! hands both halves of every large node to a [`Fork`]; [`Threads`] runs them
//! on [rayon]'s work-stealing pool, so a half waits only when every core is
//! busy. The tree is the sequential build's, bit for bit, on any number of
//! threads. [`OwnedBvh::build_parallel`](crate::ParallelBuild::build_parallel)
//! is the one-call form.
//!
//! To choose the number of threads, run the build inside a pool of that size:
//!
//! ```
//! use bvhkit::{Aabb, TopDown};
//! use bvhkit_std::{OwnedBvh, ParallelBuild};
//! let tris = bvhkit_std::scene::rock(4, 1); // 5,120 triangles
//! let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
//! let tree = pool.install(|| OwnedBvh::<Aabb>::build_parallel(&TopDown::default(), &tris))?;
//! let sequential = OwnedBvh::<Aabb>::build(&TopDown::default(), &tris)?;
//! assert_eq!(tree.view().nodes(), sequential.view().nodes());
//! # Ok::<(), bvhkit::Error>(())
//! ```

use bvhkit::builders::Fork;

/// Runs forked work on rayon's current pool (the global one, or the pool a
/// caller `install`ed).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Threads {
    /// Nodes of at least this many primitives are split across threads
    /// ([`Fork::grain`]).
    pub grain: usize,
}

impl Threads {
    /// The grain [`OwnedBvh::build_parallel`](crate::ParallelBuild::build_parallel)
    /// uses: pieces of 4,096 primitives or more. Forking costs a few
    /// microseconds, a piece this large takes about a millisecond.
    pub const GRAIN: usize = 4096;
}

impl Default for Threads {
    fn default() -> Self {
        Threads {
            grain: Threads::GRAIN,
        }
    }
}

impl Fork for Threads {
    fn join<RA: Send, RB: Send>(
        &self,
        a: impl FnOnce() -> RA + Send,
        b: impl FnOnce() -> RB + Send,
    ) -> (RA, RB) {
        rayon::join(a, b)
    }
    fn grain(&self) -> usize {
        self.grain
    }
}
