//! What a build did besides following its configuration.
//!
//! The lectures give every strategy a way out: a split that separates
//! nothing falls back to another axis and then to the object median, and a
//! build that runs short of depth halves nodes instead of following its
//! criterion. A tree built that way is still exact, but it is not the tree
//! the configuration describes, so the builder counts each way out and
//! keeps the counts with the tree ([`Bvh::build_report`](crate::Bvh::build_report)).

/// Counts of a builder's fallbacks and warnings; all zero for a tree built
/// exactly as configured (and for a tree opened from storage, which carries
/// no report).
///
/// ```
/// use bvhkit::{Aabb, Node, Partition, TopDown, Triangle};
/// use glam::Vec3;
/// // A row of triangles spaced ever wider: maximum separation peels them
/// // off a few at a time. Cuts of under 1% are failed splits (the SAH
/// // takes those nodes), and near the depth limit the budget halves nodes.
/// let row: Vec<Triangle> = (0..1000)
///     .map(|i| {
///         let o = Vec3::new(1.02f32.powi(i), 0.0, 0.0);
///         Triangle::new(o, o + Vec3::X * 1e-3, o + Vec3::Y * 1e-3)
///     })
///     .collect();
/// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(row.len())];
/// let mut idx = vec![0u32; row.len()];
/// let separation = TopDown { partition: Partition::Separation, ..TopDown::sah() };
/// let report = separation.build(&row, &mut nodes, &mut idx)?.build_report();
/// assert!(report.fallback_splits > 0 && report.depth_limited > 0);
/// assert_eq!(report.oversized_leaves, 0); // every leaf within max_leaf_size
/// assert!(!report.has_warnings());
/// // The SAH weighs the counts: it follows its configuration throughout.
/// let report = TopDown::sah().build(&row, &mut nodes, &mut idx)?.build_report();
/// assert_eq!((report.fallback_splits, report.depth_limited), (0, 0));
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BuildReport {
    /// Nodes whose configured split failed: nothing separated, both halves
    /// nearly as large as the node, or (for criteria that ignore how many
    /// primitives each side holds: volume, larger child, overlap,
    /// separation) a lopsided cut leaving under 1% of a node of 100 or more
    /// primitives on one side. The fallbacks, in order: the criterion over
    /// x, y and z; binned SAH; the object median. When even that separates
    /// nothing, [`OnFailure::Leaf`](crate::OnFailure::Leaf) makes the node a
    /// leaf (then also counted in `oversized_leaves`).
    pub fallback_splits: u32,
    /// Interventions of the depth limit: top-down nodes halved at the object
    /// median because the levels left were only just enough, bottom-up
    /// subtrees rebuilt balanced, insertions that rebalanced a dynamic tree
    /// by rotations its configuration did not ask for.
    pub depth_limited: u32,
    /// Leaves holding more than [`max_leaf_size`](Self::max_leaf_size)
    /// primitives (a node no strategy could split with
    /// [`OnFailure::Leaf`](crate::OnFailure::Leaf), a `min_volume` stop, or
    /// a `max_depth` too small for the input). Queries stay exact; they get
    /// slower.
    pub oversized_leaves: u32,
    /// The largest leaf the configuration allows (0 when not known).
    pub max_leaf_size: u32,
}

impl BuildReport {
    /// Whether the tree breaks a limit its configuration stated (a leaf
    /// over the maximum size). Fallbacks alone are not warnings: they are
    /// how the configured strategy is made to work on every input.
    pub const fn has_warnings(&self) -> bool {
        self.oversized_leaves > 0
    }
}
