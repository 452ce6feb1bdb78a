//! The named choices of a top-down build (Ericson 6.2.1 - 6.2.3).

use crate::tree::MAX_DEPTH;

/// Most bins / candidate planes a split evaluation may use.
pub const MAX_BINS: usize = 32;

/// What a split minimises. Costs are evaluated on the children's boxes
/// (converted to the tree's volume type where the criterion measures volume),
/// in coordinates normalised to the parent, so they never overflow.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Partition {
    /// Median cut: divide the primitives equally (cost `|n_l - n_r|`). Balanced
    /// trees, predictable depth; ignores geometry.
    Balance,
    /// Surface area heuristic: `n_l * A(l) + n_r * A(r)`. The probability that a
    /// random ray or box hits a child grows with its area; weighting by count
    /// estimates the work beneath. The best general-purpose choice.
    SurfaceArea,
    /// Minimise the sum of child volumes `V(l) + V(r)`.
    Volume,
    /// Minimise the larger child volume `max(V(l), V(r))`.
    LargerChild,
    /// Minimise the volume of the children's intersection (their boxes).
    Overlap,
    /// Maximise the gap between the children (their boxes); a negative gap is overlap.
    Separation,
    /// A weighted sum of the normalised criteria above.
    Weighted {
        /// Weight of the SAH term.
        surface_area: f32,
        /// Weight of the volume-sum term.
        volume: f32,
        /// Weight of the overlap term.
        overlap: f32,
        /// Weight of the balance term.
        balance: f32,
    },
}

impl Partition {
    /// Whether the cost weighs how many primitives each side gets (balance,
    /// the SAH, a weighted sum with either): criteria that do not can be
    /// satisfied by cutting off a sliver, which the builder treats as a
    /// failed split ([`BuildReport::fallback_splits`](super::BuildReport)).
    pub const fn weighs_counts(&self) -> bool {
        match *self {
            Partition::Balance | Partition::SurfaceArea => true,
            Partition::Weighted {
                surface_area,
                balance,
                ..
            } => surface_area > 0.0 || balance > 0.0,
            Partition::Volume
            | Partition::LargerChild
            | Partition::Overlap
            | Partition::Separation => false,
        }
    }
}

/// Which axis (or axes) candidate splits are placed along.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AxisChoice {
    /// The local x axis only.
    X,
    /// The local y axis only.
    Y,
    /// The local z axis only.
    Z,
    /// All three coordinate axes; the partition criterion picks the best.
    BestOfXyz,
    /// The axis of longest extent of the primitive centroids.
    Longest,
    /// The direction of greatest centroid variance (principal component).
    Variance,
    /// The direction through the two most distant centroids (among the six
    /// axis-extreme ones: linear time, as Ritter's sphere does).
    DistantPoints,
    /// The axes of the node's own bounding volume (an OBB's frame, a k-DOP's
    /// directions; x/y/z for AABBs and spheres); the criterion picks the best.
    ParentVolume,
}

/// Where along an axis candidate split planes are placed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SplitPoint {
    /// The middle primitive by centroid: equal halves, balanced trees.
    ObjectMedian,
    /// The mean of the centroids: follows where the mass is.
    ObjectMean,
    /// The middle of the centroids' extent: cheap, can unbalance the tree.
    SpatialMedian,
    /// `bins - 1` evenly spaced planes over the centroids' extent (binning).
    Bins(u8),
    /// Between every two consecutive centroids: the exact sweep (sorts per node,
    /// uses `n` extra scratch entries in the index buffer).
    Sweep,
    /// At the centroids of `count` primitives drawn with a seeded generator:
    /// deterministic for a given seed.
    RandomCentroids {
        /// Number of candidate planes (at most [`MAX_BINS`]).
        count: u8,
        /// Seed of the generator.
        seed: u64,
    },
}

/// When to stop splitting and make a leaf.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stop {
    /// A node with at most this many primitives becomes a leaf (>= 1).
    pub max_leaf_size: u32,
    /// A node whose volume (in the tree's volume type) is below this becomes a
    /// leaf; 0 disables the test.
    pub min_volume: f32,
    /// A node at this depth becomes a leaf (at most [`MAX_DEPTH`]). The
    /// builder budgets for it: once the levels left are only just enough to
    /// halve a node down to `max_leaf_size`, the node is halved at its object
    /// median whatever the partition criterion, so leaves stay within
    /// `max_leaf_size` unless `max_depth` itself is too small for the input.
    pub max_depth: u32,
}

impl Default for Stop {
    fn default() -> Self {
        Stop {
            max_leaf_size: 4,
            min_volume: 0.0,
            max_depth: MAX_DEPTH as u32,
        }
    }
}

/// What to do when every criterion fails to separate a node (all primitives on
/// one side, or both children nearly as large as the parent). Before this, the
/// builder always tries the other two axes and then the object median.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum OnFailure {
    /// Split at the object median anyway: keeps the leaf-size bound.
    #[default]
    ForceSplit,
    /// Make the node a leaf, however many primitives it holds.
    Leaf,
}
