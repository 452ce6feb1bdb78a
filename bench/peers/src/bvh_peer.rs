//! The `bvh` crate (svenstaro/bvh 0.13, single thread: no `rayon`).
//!
//! `Bvh::build` is a top-down binned SAH builder: 6 buckets along the axis of
//! largest centroid spread, the split with the least `n_l A_l + n_r A_r`, and
//! it always splits down to one shape per leaf. A `BvhNode` is an enum: a leaf
//! holds its shape's index, an inner node holds both children's indices and
//! boxes, so a node's own box lives in its parent (the root's in none).
//!
//! `bvh` has no tree-against-tree query and no closest-hit traversal with a
//! callback, so pairs query A's tree once per box of B, and rays walk its
//! nearest-first iterator, stopping once the next leaf's box starts beyond the
//! best hit.

use crate::common::{
    boxes_overlap, hit_triangle, sah, time, time_setup, Measured, PairSum, RayHit, Runs, Scene,
};
use bvh::aabb::{Aabb as BAabb, Bounded};
use bvh::bounding_hierarchy::BHShape;
use bvh::bvh::{Bvh, BvhNode};
use bvh::ray::Ray as BRay;
use bvhkit::glam::Vec3;
use bvhkit::Aabb;

/// One triangle as `bvh` sees it: its index in the scene, its box, and the
/// leaf `bvh` put it in (`BHShape` makes the user store that).
#[derive(Clone, Debug)]
struct Tri {
    index: u32,
    aabb: BAabb<f32, 3>,
    node: usize,
}

impl Bounded<f32, 3> for Tri {
    fn aabb(&self) -> BAabb<f32, 3> {
        self.aabb
    }
}

impl BHShape<f32, 3> for Tri {
    fn set_bh_node_index(&mut self, index: usize) {
        self.node = index;
    }

    fn bh_node_index(&self) -> usize {
        self.node
    }
}

/// `BvhTraverseIterator` keeps its path in a fixed `[usize; 32]` stack and
/// panics on a leaf deeper than 31; deeper trees use the recursive
/// (allocating) `Bvh::traverse` instead.
const ITERATOR_MAX_DEPTH: usize = 31;

/// Relative slack on the early exit of the ray walk: the f32 slab entry of a
/// leaf's box may round a few ulps above the f64 triangle distance of a hit
/// lying on that box's face, so stop only clearly beyond the best hit.
const EXIT_SLACK: f32 = 1e-5;

/// A bvhkit box as `bvh`'s (nalgebra points, reached through `From<[f32; 3]>`
/// so this crate needs no nalgebra dependency of its own).
fn to_bvh(b: &Aabb) -> BAabb<f32, 3> {
    BAabb::with_bounds(b.min.to_array().into(), b.max.to_array().into())
}

/// A `bvh` box back as bvhkit's, for [`sah`].
fn from_bvh(b: &BAabb<f32, 3>) -> Aabb {
    Aabb::new(
        Vec3::new(b.min.x, b.min.y, b.min.z),
        Vec3::new(b.max.x, b.max.y, b.max.z),
    )
}

/// Depth of the deepest leaf (the root at 0).
fn max_depth(nodes: &[BvhNode<f32, 3>]) -> usize {
    let mut deepest = 0;
    let mut stack = vec![(0, 0)];
    while let Some((i, depth)) = stack.pop() {
        deepest = usize::max(deepest, depth);
        if let BvhNode::Node {
            child_l_index,
            child_r_index,
            ..
        } = nodes[i]
        {
            stack.extend([(child_l_index, depth + 1), (child_r_index, depth + 1)]);
        }
    }
    deepest
}

/// SAH of the tree: the root with the union of all boxes, then every child
/// with the box its parent stores; 1 primitive per leaf, 0 for inner nodes.
fn sah_of(nodes: &[BvhNode<f32, 3>], root: &Aabb) -> f64 {
    let count = |i: usize| u32::from(nodes[i].is_leaf());
    let children = nodes.iter().filter_map(|n| match *n {
        BvhNode::Node {
            child_l_index,
            child_l_aabb,
            child_r_index,
            child_r_aabb,
            ..
        } => Some([
            (from_bvh(&child_l_aabb), count(child_l_index)),
            (from_bvh(&child_r_aabb), count(child_r_index)),
        ]),
        BvhNode::Leaf { .. } => None,
    });
    sah(
        root,
        std::iter::once((*root, count(0))).chain(children.flatten()),
    )
}

/// Builds and queries this crate's tree on `scene`.
pub fn run(scene: &Scene, runs: Runs) -> Vec<Measured> {
    let shapes: Vec<Tri> = scene
        .boxes_a
        .iter()
        .enumerate()
        .map(|(i, b)| Tri {
            index: i as u32,
            aabb: to_bvh(b),
            node: 0,
        })
        .collect();

    // The build writes each shape's leaf index, so every run gets a fresh copy.
    let (build, bvh) = time_setup(runs.build, || shapes.clone(), |mut s| Bvh::build(&mut s));
    let nodes = &bvh.nodes;
    let leaves = nodes.iter().filter(|n| n.is_leaf()).count();
    let sah = sah_of(nodes, &crate::common::union(&scene.boxes_a));
    // The nodes are all `bvh` stores: a leaf holds its shape's index itself.
    let bytes = std::mem::size_of::<BvhNode<f32, 3>>() * nodes.len();

    let queries: Vec<BAabb<f32, 3>> = scene.boxes_b.iter().map(to_bvh).collect();
    let deep = max_depth(nodes) > ITERATOR_MAX_DEPTH;
    let pairs = time(runs.pairs, || {
        let mut sum = PairSum::default();
        for (j, q) in queries.iter().enumerate() {
            let mut visit = |s: &Tri| {
                if boxes_overlap(&scene.boxes_a[s.index as usize], &scene.boxes_b[j]) {
                    sum.add(s.index, j as u32);
                }
            };
            if deep {
                bvh.traverse(q, &shapes).into_iter().for_each(&mut visit);
            } else {
                bvh.traverse_iterator(q, &shapes).for_each(&mut visit);
            }
        }
        sum
    });

    // The scene's directions are unit already: set the fields directly rather
    // than through `Ray::new`, which would normalise them again.
    let rays: Vec<BRay<f32, 3>> = scene
        .rays
        .iter()
        .map(|r| BRay {
            origin: r.origin().to_array().into(),
            direction: r.dir().to_array().into(),
            inv_direction: r.dir().recip().to_array().into(),
        })
        .collect();
    let hits = time(runs.rays, || {
        rays.iter()
            .zip(&scene.rays)
            .map(|(bray, ray)| {
                let mut best: RayHit = None;
                // Leaves come out by increasing entry distance of their box (a
                // binary heap over nodes, allocated per ray), so once a leaf's
                // box starts beyond the best hit, no later leaf can beat it.
                for s in bvh.nearest_traverse_iterator(bray, &shapes) {
                    let t_max = best.map_or(f32::INFINITY, |b| b.1);
                    let entry = bray
                        .intersection_slice_for_aabb(&s.aabb)
                        .map_or(0.0, |e| e.0);
                    if entry > t_max * (1.0 + EXIT_SLACK) {
                        break;
                    }
                    if let Some(t) = hit_triangle(&scene.a, s.index, ray, t_max) {
                        if best.is_none_or(|b| t < b.1) {
                            best = Some((s.index, t));
                        }
                    }
                }
                best
            })
            .collect::<Vec<RayHit>>()
    });

    vec![Measured {
        krate: "bvh",
        builder: "binned-sah".to_string(),
        build,
        leaves,
        sah: Some(sah),
        bytes,
        pairs: Some(pairs),
        rays: Some(hits),
        note: if deep {
            "bvh 0.13 Bvh::build (binned SAH, 6 buckets, 1 shape per leaf); pairs: Bvh::traverse \
             per box of B (the tree is too deep for traverse_iterator's 32-entry stack); rays: \
             nearest_traverse_iterator, stopped past the best hit"
        } else {
            "bvh 0.13 Bvh::build (binned SAH, 6 buckets, 1 shape per leaf); pairs: \
             traverse_iterator per box of B; rays: nearest_traverse_iterator, stopped past the \
             best hit"
        },
    }]
}

#[cfg(test)]
mod tests {
    #[test]
    fn answers_match_brute_force() {
        let m = crate::common::reference::run_and_check(super::run);
        assert_eq!(m.len(), 1);
        assert!(m[0].pairs.is_some() && m[0].rays.is_some() && m[0].sah.is_some());
    }
}
