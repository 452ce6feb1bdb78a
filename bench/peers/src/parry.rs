//! parry3d's `Bvh`, as a user runs it: both builders (`BvhBuildStrategy::Binned`
//! and `Ploc`) through `Bvh::from_leaves`, the pair query `Bvh::leaf_pairs`
//! and the closest hit `Bvh::cast_ray` with our triangle test as leaf callback.
//!
//! parry stores a binary tree as `BvhNodeWide` records (a left and a right
//! `BvhNode`, 64 bytes), children of one node side by side. The first record
//! holds the root's two children: the root itself is never stored, so the
//! SAH adds it as a virtual node. Every leaf holds exactly one primitive, its
//! index inline in the node, so there is no primitive index array.

use crate::common::{
    boxes_overlap, hit_triangle, sah, time, Measured, PairSum, RayHit, Runs, Scene,
};
use bvhkit::glam::Vec3;
use bvhkit::Aabb;
use parry3d::bounding_volume::Aabb as ParryAabb;
use parry3d::math::Vector;
use parry3d::partitioning::{Bvh, BvhBuildStrategy, BvhNode, BvhNodeWide, TraversalAction};
use parry3d::query::Ray as ParryRay;

/// Builds and queries parry3d's trees on `scene`.
pub fn run(scene: &Scene, runs: Runs) -> Vec<Measured> {
    // parry uses its own glam version: convert the inputs once, untimed.
    let to_parry = |boxes: &[Aabb]| -> Vec<ParryAabb> {
        boxes
            .iter()
            .map(|b| ParryAabb::new(vector(b.min), vector(b.max)))
            .collect()
    };
    let (boxes_a, boxes_b) = (to_parry(&scene.boxes_a), to_parry(&scene.boxes_b));
    let rays: Vec<ParryRay> = scene
        .rays
        .iter()
        .map(|r| ParryRay::new(vector(r.origin()), vector(r.dir())))
        .collect();

    let builders = [
        (
            BvhBuildStrategy::Binned,
            "binned",
            "Bvh::from_leaves(Binned), leaf_pairs with BvhNode::intersects, \
             cast_ray with our triangle test",
        ),
        (
            BvhBuildStrategy::Ploc,
            "ploc",
            "Bvh::from_leaves(Ploc), leaf_pairs with BvhNode::intersects, \
             cast_ray with our triangle test",
        ),
    ];
    builders
        .into_iter()
        .map(|(strategy, builder, note)| {
            // `from_leaves` gives leaf `i` the primitive index `i`.
            let (build, a) = time(runs.build, || Bvh::from_leaves(strategy, &boxes_a));
            let b = Bvh::from_leaves(strategy, &boxes_b);
            let nodes_a = nodes(&a);
            let leaves = nodes_a.iter().filter(|n| n.count == 1).count();

            // `leaf_pairs` applies `check` to every pair it descends into, leaf
            // pairs included, but not to the (up to four) pairs of root
            // children it starts from. Those are leaf pairs only when both
            // roots have a leaf child: only then must the answers be filtered.
            let root_leaf = |nodes: &[Node]| nodes.iter().any(|n| n.root_child && n.count == 1);
            let unchecked_leaf_pairs = root_leaf(&nodes_a) && root_leaf(&nodes(&b));
            let pairs = time(runs.pairs, || {
                let mut sum = PairSum::default();
                // `BvhNode::intersects` is closed (`<=`/`>=` on x, y, z), as
                // `boxes_overlap`.
                for (i, j) in a.leaf_pairs(&b, BvhNode::intersects) {
                    if !unchecked_leaf_pairs
                        || boxes_overlap(&scene.boxes_a[i as usize], &scene.boxes_b[j as usize])
                    {
                        sum.add(i, j);
                    }
                }
                sum
            });

            let rays = time(runs.rays, || {
                scene
                    .rays
                    .iter()
                    .zip(&rays)
                    .map(|(ray, parry_ray)| -> RayHit {
                        // The callback gets the closest distance so far, so the
                        // triangle test can stop at it.
                        a.cast_ray(parry_ray, ray.t_max(), |prim, best| {
                            hit_triangle(&scene.a, prim, ray, best)
                        })
                    })
                    .collect::<Vec<_>>()
            });

            // The stored root record is a pair: the root is virtual, the
            // union of the pair (unless the tree is a single leaf).
            let root = aabb(&a.root_aabb());
            let virtual_root = (nodes_a.len() > 1).then_some((root, 0));
            let sah = sah(
                &root,
                virtual_root
                    .into_iter()
                    .chain(nodes_a.iter().map(|n| (n.bv, n.count))),
            );

            // Bytes: the `BvhNodeWide` records the tree occupies, one per
            // internal node plus the root pair (after `from_leaves`' compacting
            // refit that is exactly the stored array, `leaves - 1` records).
            // Not counted: `parents` (8 bytes a record) and `leaf_node_indices`
            // (8 bytes a leaf), which map back from nodes and primitives for
            // updates and removal; no query reads them.
            let internal = nodes_a.len() - leaves;
            let bytes = (internal + 1) * size_of::<BvhNodeWide>();

            Measured {
                krate: "parry3d",
                builder: builder.to_string(),
                build,
                leaves,
                sah: Some(sah),
                bytes,
                pairs: Some(pairs),
                rays: Some(rays),
                note,
            }
        })
        .collect()
}

/// A stored node of a parry tree.
struct Node {
    bv: Aabb,
    /// Primitives: 1 for a leaf, 0 for an internal node.
    count: u32,
    /// Whether it is one of the root pair (the first `BvhNodeWide`).
    root_child: bool,
}

/// Every stored node, through the public traversal (the node array is private).
fn nodes(bvh: &Bvh) -> Vec<Node> {
    let mut nodes = Vec::new();
    bvh.traverse_indexed(None, |node, index| {
        nodes.push(Node {
            bv: aabb(&node.aabb()),
            count: u32::from(node.is_leaf()),
            root_child: index.decompose().0 == 0,
        });
        TraversalAction::Continue
    });
    nodes
}

/// Our vector in parry's glam version.
fn vector(v: Vec3) -> Vector {
    Vector::from_array(v.to_array())
}

/// parry's box in our glam version.
fn aabb(b: &ParryAabb) -> Aabb {
    Aabb::new(
        Vec3::from_array(b.mins.to_array()),
        Vec3::from_array(b.maxs.to_array()),
    )
}

#[cfg(test)]
mod tests {
    #[test]
    fn answers_match_brute_force() {
        let m = crate::common::reference::run_and_check(super::run);
        assert_eq!(m.len(), 2);
        assert!(m
            .iter()
            .all(|m| m.pairs.is_some() && m.rays.is_some() && m.sah.is_some()));
    }
}
