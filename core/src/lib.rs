//! # bvhkit
//!
//! Bounding volume hierarchies for collision detection, following chapter 6 of
//! Ericson's *Real-Time Collision Detection*: every bounding volume, build
//! strategy and traversal rule of the textbook, as small selectable values.
//!
//! The core is `#![no_std]` and never allocates: the caller owns all storage
//! (a `static` array on a microcontroller, a `Vec` on a desktop) and the tree
//! refers to nodes by index into it.
//!
//! Cargo features (all on by default) let an embedded build compile only what
//! it uses: `strategies` (every top-down partition strategy, axis choice and
//! split point beyond binned SAH), `sphere`, `obb`, `kdop` (volume types),
//! `bottom-up`, `insertion` (builders beyond top-down) and `layouts` (the
//! compact tree representations). With `default-features = false` the crate
//! keeps AABB trees, the binned-SAH top-down builder, every query and the
//! collision system. One feature is off by default: `alloc`, for programs
//! with a heap, adds [`OwnedBvh`] (a tree that sizes and owns its storage)
//! and [`Mesh`] (a triangle mesh with its tree, queried in one call each).
//!
//! Data flows one way: primitives -> [`TopDown`] builder -> [`Bvh`] ->
//! queries ([`Bvh::overlapping`], [`overlapping_pairs`]) -> your callback.
//!
//! ```
//! use bvhkit::{overlapping_pairs, Aabb, Descent, Node, TopDown, Triangle};
//! use glam::Vec3;
//!
//! // Two small "meshes": a row of triangles, and the same row shifted a little.
//! let row = |dy: f32| -> Vec<Triangle> {
//!     (0..8).map(|i| {
//!         let o = Vec3::new(i as f32, dy, 0.0);
//!         Triangle::new(o, o + Vec3::new(0.9, 0.0, 0.0), o + Vec3::new(0.0, 0.9, 0.0))
//!     }).collect()
//! };
//! let (a, b) = (row(0.0), row(0.5));
//!
//! // Storage comes from the caller: at most 2n - 1 nodes and n indices.
//! let mut nodes_a = [Node::<Aabb>::ZERO; bvhkit::max_nodes(8)];
//! let mut nodes_b = [Node::<Aabb>::ZERO; bvhkit::max_nodes(8)];
//! let (mut idx_a, mut idx_b) = ([0u32; 8], [0u32; 8]);
//! let tree_a = TopDown::default().build(&a, &mut nodes_a, &mut idx_a)?;
//! let tree_b = TopDown::default().build(&b, &mut nodes_b, &mut idx_b)?;
//!
//! let mut count = 0;
//! overlapping_pairs(&tree_a, &a, &tree_b, &b, Descent::Larger, |_, _| count += 1)?;
//! assert_eq!(count, bvhkit::brute_force::pairs(&a, &b, |_, _| {}));
//! # Ok::<(), bvhkit::Error>(())
//! ```
#![no_std]
#![deny(unsafe_code)]
#![warn(missing_docs)]

#[cfg(feature = "alloc")]
extern crate alloc;

pub mod baked;
pub mod builders;
pub mod bv;
pub mod collision;
mod error;
mod frame;
#[cfg(feature = "layouts")]
pub mod layout;
#[cfg(feature = "alloc")]
mod mesh;
pub mod narrow;
#[cfg(feature = "alloc")]
mod owned;
mod primitive;
pub mod query;
pub mod round;
mod stats;
pub mod transform;
pub mod tree;

/// A small xorshift source of floats in [-1, 1), for the unit tests' random
/// scenes (one generator, so every test draws the same kind of numbers).
#[cfg(test)]
pub(crate) fn test_floats(seed: u64) -> impl FnMut() -> f32 {
    let mut s = seed;
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
    }
}

pub use builders::{AxisChoice, BuildReport, OnFailure, Partition, SplitPoint, Stop, TopDown};
#[cfg(feature = "sphere")]
pub use bv::Sphere;
pub use bv::{symmetric_eigen, Aabb, BoundingVolume, PointSet};
#[cfg(feature = "kdop")]
pub use bv::{Dop14, Dop18, Dop26, ExactKdop, Kdop};
#[cfg(feature = "obb")]
pub use bv::{Obb, ObbDito};
pub use error::Error;
pub use frame::LocalFrame;
#[cfg(feature = "alloc")]
pub use mesh::{Mesh, PointHit, RayHit};
pub use narrow::Intersects;
#[cfg(feature = "alloc")]
pub use owned::OwnedBvh;
pub use primitive::{Primitive, Triangle, MAX_COORDINATE};
pub use query::{
    brute_force, overlapping_pairs, Answer, Bounds, CastTarget, ClosestOnTriangle, Collector,
    CostModel, Counts, Decision, DepthSwitch, Descent, DescentRule, Distance, Exact, Frame, Hit,
    Nearest, Open, Order, PairTraversal, Pairs, Place, PointDistance, Query, Ray, RayOrder,
    RayTarget, Region, Same, ShapeCast, Swept, Tally, TriangleFeature, TriangleHit,
};
pub use stats::TreeStats;
pub use transform::{Rigid, Transform};
pub use tree::{
    max_nodes, max_nodes_for_leaves, Boxes4, Bvh, Capacity, Content, Hierarchy, Kids, Node, Shape,
    MAX_DEPTH,
};

pub use glam;
