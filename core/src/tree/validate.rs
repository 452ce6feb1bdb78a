//! Invariant checks for a tree (the `bvh_validation` of parry, for any volume).

use super::{Bvh, Node, MAX_DEPTH};
use crate::bv::BoundingVolume;
use crate::primitive::Primitive;
use crate::Error;

pub(crate) fn test_and_set(seen: &mut [u32], i: usize) -> bool {
    let (w, b) = (i / 32, 1u32 << (i % 32));
    let was = seen[w] & b != 0;
    seen[w] |= b;
    was
}

/// Structural checks; returns the depth. Needs `seen` of `Bvh::seen_words` words.
pub(crate) fn structure<B: BoundingVolume>(
    nodes: &[Node<B>],
    indices: &[u32],
    prim_count: usize,
    seen: &mut [u32],
) -> Result<u32, Error> {
    if nodes.is_empty() && indices.is_empty() && prim_count == 0 {
        return Ok(0); // the empty tree
    }
    if nodes.is_empty() {
        return Err(Error::InvalidTree("no nodes"));
    }
    if indices.len() != prim_count {
        return Err(Error::PrimitiveCountMismatch {
            tree: indices.len(),
            given: prim_count,
        });
    }
    let words = Bvh::<B>::seen_words(nodes.len(), prim_count);
    if seen.len() < words {
        return Err(Error::InvalidConfig(
            "validation scratch smaller than Bvh::seen_words",
        ));
    }
    let seen = &mut seen[..words];
    seen.fill(0);
    // Each node reached exactly once, children after their parent, depth bounded.
    let mut stack = [(0u32, 0u32); MAX_DEPTH + 1];
    let mut top = 1;
    let mut depth = 0;
    let mut visited = 0usize;
    let mut leaf_slots = 0usize;
    test_and_set(seen, 0);
    while top > 0 {
        top -= 1;
        let (i, d) = stack[top];
        visited += 1;
        depth = depth.max(d);
        let node = &nodes[i as usize];
        match node.children() {
            None => {
                // In u64: on a 32-bit target `first + count` from a file
                // could wrap and pass.
                let end = u64::from(node.first) + u64::from(node.count);
                if end > indices.len() as u64 {
                    return Err(Error::InvalidTree("leaf range outside the index array"));
                }
                leaf_slots += node.count as usize;
            }
            Some((l, r)) => {
                if l <= i || l as usize >= nodes.len() || r as usize >= nodes.len() {
                    return Err(Error::InvalidTree(
                        "child index out of range or not after its parent",
                    ));
                }
                if d as usize >= MAX_DEPTH || top + 2 > stack.len() {
                    return Err(Error::InvalidTree("deeper than MAX_DEPTH"));
                }
                for c in [l, r] {
                    if test_and_set(seen, c as usize) {
                        return Err(Error::InvalidTree("a node is reached twice"));
                    }
                    stack[top] = (c, d + 1);
                    top += 1;
                }
            }
        }
    }
    if visited != nodes.len() {
        return Err(Error::InvalidTree(
            "some nodes are not reachable from the root",
        ));
    }
    if leaf_slots != indices.len() {
        return Err(Error::InvalidTree(
            "leaves do not cover the index array exactly",
        ));
    }
    // Each index entry in exactly one leaf: with the slot count equal to the
    // array's length, no entry twice means every entry once. (Two leaves on
    // the same entries would leave others in no leaf, never queried.)
    seen.fill(0);
    for node in nodes.iter().filter(|n| n.is_leaf()) {
        // `first + count` is within the array (checked in the walk).
        for entry in node.first as usize..node.first as usize + node.count as usize {
            if test_and_set(seen, entry) {
                return Err(Error::InvalidTree("two leaves share an index entry"));
            }
        }
    }
    // Each primitive exactly once.
    seen.fill(0);
    for &p in indices {
        if p as usize >= prim_count {
            return Err(Error::InvalidTree("primitive index out of range"));
        }
        if test_and_set(seen, p as usize) {
            return Err(Error::InvalidTree("a primitive appears twice"));
        }
    }
    Ok(depth)
}

/// Geometric checks: parents contain children, leaves contain their primitives' bounds.
pub(super) fn containment<B: BoundingVolume, P: Primitive>(
    bvh: &Bvh<'_, B>,
    prims: &[P],
) -> Result<(), Error> {
    for node in bvh.nodes() {
        match node.children() {
            Some((l, r)) => {
                let nodes = bvh.nodes();
                if !node.bv.contains(&nodes[l as usize].bv)
                    || !node.bv.contains(&nodes[r as usize].bv)
                {
                    return Err(Error::InvalidTree("a node does not contain its children"));
                }
            }
            None => {
                for &p in bvh.leaf_primitives(node) {
                    // `structure` checked every index against `prims`.
                    if !node.bv.contains_aabb(&prims[p as usize].bounds()) {
                        return Err(Error::InvalidTree(
                            "a leaf does not contain its primitive's bounds",
                        ));
                    }
                }
            }
        }
    }
    if let Some(bounds) = bvh.leaf_bounds() {
        let same = bounds.len() == bvh.indices().len()
            && bounds
                .iter()
                .zip(bvh.indices())
                .all(|(b, &p)| prims.get(p as usize).is_some_and(|q| q.bounds() == *b));
        if !same {
            return Err(Error::InvalidTree(
                "leaf bounds differ from the primitives' bounds",
            ));
        }
    }
    Ok(())
}
