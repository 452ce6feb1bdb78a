//! Queries: what the hierarchy is for.
//!
//! Lecture: *hierarchy traversal* and *descent rules*. Every answer is defined at
//! the primitive level (primitives whose bounds overlap the region; primitive
//! pairs whose bounds overlap each other), so it is the same for every builder,
//! volume type and layout: the tree only decides how much work is skipped.
//! [`brute_force`] computes the same answers without a tree, as the reference.
//!
//! Results go to a callback or to a caller-provided buffer ([`Collector`]);
//! nothing allocates. Every traversal owns a fixed stack sized from
//! [`MAX_DEPTH`](crate::MAX_DEPTH).

pub mod brute_force;
mod cast;
mod collect;
mod descent;
mod distance;
mod heap;
pub(crate) mod nearest;
mod pair;
mod ray;
mod self_pairs;
mod single;
pub(crate) mod stack;
mod tally;

pub use cast::{CastTarget, ShapeCast, Swept};
pub use collect::Collector;
pub use descent::{Decision, DepthSwitch, Descent, DescentRule, Open};
pub use distance::{Closest, ClosestPoints, Distance, PairDistance};
pub use heap::BEST_FIRST_QUEUE;
pub use nearest::{ClosestOnTriangle, Nearest, PointDistance, TriangleFeature};
pub use pair::{
    overlapping_pairs, pair_stack_bound, Answer, Bounds, Exact, Frame, PairTraversal, Pairs, Place,
    Same, PAIR_STACK, SMALL_PAIR_STACK, WIDE_PAIR_STACK,
};
pub use ray::{Hit, Ray, RayOrder, RayTarget, TriangleHit};
pub use self_pairs::{Adjacent, KeepAll, SelfFilter, SelfPairs, SkipAdjacent, SkipIds};
pub use single::{Order, Query, Region};
pub use tally::{CostModel, Counts, Tally};
