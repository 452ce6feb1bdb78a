//! Building hierarchies.
//!
//! Lecture: *building strategies*. The top-down family ([`TopDown`]) splits the
//! input recursively; every choice the lectures list is a named value:
//! [`Partition`] (the criterion a split minimises), [`AxisChoice`],
//! [`SplitPoint`], [`Stop`], and [`OnFailure`] for splits that do not separate
//! anything. Bottom-up and insertion builders come with their own modules.

#[cfg(feature = "bottom-up")]
mod bottom_up;
#[cfg(any(feature = "bottom-up", feature = "insertion"))]
mod collapse;
#[cfg(feature = "insertion")]
mod dynamic;
mod presets;
mod refit;
mod report;
mod strategy;
mod top_down;

#[cfg(feature = "bottom-up")]
pub use bottom_up::{BottomUp, BottomUpScratch, Cluster, MergeMetric, Method};
#[cfg(any(feature = "bottom-up", feature = "insertion"))]
pub use collapse::Collapse;
#[cfg(feature = "insertion")]
pub use dynamic::{
    area_rotation, AreaRotation, DynNode, DynamicConfig, DynamicTree, InsertOrder, Insertion,
    LeafHandle, Rotations, SiblingSearch, NULL,
};
pub use presets::{Preset, PRESETS};
pub use refit::{refit_all, Refit};
pub use report::BuildReport;

pub use strategy::{AxisChoice, OnFailure, Partition, SplitPoint, Stop, MAX_BINS};
pub use top_down::{Fork, InOrder, PrimitiveRef, TopDown};

use crate::bv::BoundingVolume;
#[cfg(any(feature = "bottom-up", feature = "insertion"))]
use crate::{
    tree::{Node, MAX_DEPTH},
    Error,
};

/// A volume containing both, as tight as `merge` makes it (merging again
/// when a rounding step left a hair outside).
pub(crate) fn enclose<B: BoundingVolume>(l: &B, r: &B) -> B {
    let mut pick = l.merge(r);
    if B::EXACT_MERGE {
        return pick;
    }
    for _ in 0..4 {
        if pick.contains(l) && pick.contains(r) {
            break;
        }
        pick = pick.merge(l).merge(r);
    }
    pick
}

/// Writes a binary tree held elsewhere (clusters, dynamic nodes) in the query
/// layout: depth-first, children adjacent, one primitive per leaf. `node(i)`
/// gives a node's volume and either its children or its primitive. Returns
/// the depth; deeper than [`MAX_DEPTH`] is an error.
#[cfg(any(feature = "bottom-up", feature = "insertion"))]
pub(crate) fn emit_layout<B: BoundingVolume>(
    root: u32,
    nodes: &mut [Node<B>],
    indices: &mut [u32],
    node: impl Fn(u32) -> (B, Result<(u32, u32), u32>),
) -> Result<u32, Error> {
    let too_deep = |depth: u32| Error::StackOverflow {
        depth: depth as usize,
        capacity: MAX_DEPTH,
    };
    let (mut next_slot, mut next_index, mut max_depth) = (1u32, 0u32, 0u32);
    // (source node, slot, depth); one waiting sibling per level.
    let mut stack = [(0u32, 0u32, 0u32); MAX_DEPTH + 2];
    stack[0] = (root, 0, 0);
    let mut top = 1;
    while top > 0 {
        top -= 1;
        let (c, slot, depth) = stack[top];
        if depth as usize > MAX_DEPTH {
            return Err(too_deep(depth));
        }
        max_depth = max_depth.max(depth);
        let (bv, kind) = node(c);
        match kind {
            Err(prim) => {
                indices[next_index as usize] = prim;
                nodes[slot as usize] = Node {
                    bv,
                    first: next_index,
                    count: 1,
                };
                next_index += 1;
            }
            Ok((left, right)) => {
                let first = next_slot;
                next_slot += 2;
                nodes[slot as usize] = Node {
                    bv,
                    first,
                    count: 0,
                };
                for entry in [(right, first + 1, depth + 1), (left, first, depth + 1)] {
                    *stack.get_mut(top).ok_or(too_deep(depth + 1))? = entry;
                    top += 1;
                }
            }
        }
    }
    Ok(max_depth)
}
