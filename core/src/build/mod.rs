//! Building hierarchies.
//!
//! Lecture: *building strategies*. The top-down family ([`TopDown`]) splits the
//! input recursively; every choice the lectures list is a named value:
//! [`Partition`] (the criterion a split minimises), [`AxisChoice`],
//! [`SplitPoint`], [`Stop`], and [`OnFailure`] for splits that do not separate
//! anything. Bottom-up and insertion builders come with their own modules.

mod bottom_up;
mod dynamic;
mod presets;
mod refit;
mod strategy;
mod top_down;

pub use bottom_up::{BottomUp, BottomUpScratch, Cluster, MergeMetric, Method};
pub use dynamic::{
    DynNode, DynamicConfig, DynamicTree, InsertOrder, Insertion, Rotations, SiblingSearch, NULL,
};
pub use presets::{Preset, PRESETS};
pub use refit::{refit_all, Refit};

pub use strategy::{AxisChoice, OnFailure, Partition, SplitPoint, Stop, MAX_BINS};
pub use top_down::{PrimitiveRef, TopDown};
