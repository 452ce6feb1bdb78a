//! obvhs 0.4.0 (single-threaded: default features off, so no `parallel`),
//! through its public API, with three of its presets:
//!
//! | preset          | PLOC radius         | reinsertion (after collapse) | Bvh2 leaves         |
//! |-----------------|---------------------|------------------------------|---------------------|
//! | `fastest_build` | 1                   | none                         | 1 prim, no collapse |
//! | `fast_build`    | 6, 1 in passes 1-2  | 2 % of nodes (none)          | SAH collapse, <= 8  |
//! | `medium_build`  | 14, 1 in passes 1-3 | 5 % of nodes (10 %)          | SAH collapse, <= 8  |
//!
//! All three sort 64-bit Morton codes; the collapse uses traversal cost 3.
//!
//! None of them pre-splits triangles (`pre_split: false`, and the box
//! builders ignore it anyway), so every tree is built from
//! `scene.boxes_a` exactly as the other crates' trees are.
//!
//! Per preset two rows: the binary `Bvh2` (`build_bvh2`: PLOC, reinsertion,
//! leaf collapse, second reinsertion) and the compressed 8-wide `CwBvh`
//! (`build_cwbvh`: PLOC, reinsertion, then `bvh2_to_cwbvh` with at most
//! `max_prims_per_leaf.clamp(1, 3)` primitives per leaf slot; no Bvh2
//! collapse). Both helpers are timed whole, so the time covers everything
//! the preset does (debug validation only runs with debug assertions, i.e.
//! not in the release benchmark).

use crate::common::{
    boxes_overlap, hit_triangle, sah, time, Measured, PairSum, RayHit, Runs, Scene,
};
// `obvhs::traverse!` names `UVec2::ZERO` unqualified, so it must be obvhs's
// glam `UVec2` in scope: bvhkit and obvhs share glam 0.34 (a version split
// would fail to compile here, not misbehave).
use bvhkit::glam::UVec2;
use bvhkit::{Aabb, Ray};
use obvhs::bvh2::{builder::build_bvh2, node::Bvh2Node, Bvh2};
use obvhs::cwbvh::{builder::build_cwbvh, node::CwBvhNode, CwBvh};
use obvhs::BvhBuildParams;
use std::time::Duration;

/// The presets measured, by name.
const PRESETS: [(&str, BvhBuildParams); 3] = [
    ("fastest_build", BvhBuildParams::fastest_build()),
    ("fast_build", BvhBuildParams::fast_build()),
    ("medium_build", BvhBuildParams::medium_build()),
];

/// The query inputs in obvhs's types, converted once outside every timing.
struct Inputs {
    /// `scene.boxes_a`: what the trees are built from.
    boxes: Vec<obvhs::aabb::Aabb>,
    /// `scene.boxes_b`: the pair query's boxes.
    queries: Vec<obvhs::aabb::Aabb>,
    /// `scene.rays` with `tmin = 0`, `tmax = INFINITY` (directions are
    /// already unit length, so `t` is the same as bvhkit's).
    rays: Vec<obvhs::ray::Ray>,
}

/// Builds and queries obvhs's trees on `scene`.
pub fn run(scene: &Scene, runs: Runs) -> Vec<Measured> {
    let input = Inputs {
        boxes: scene.boxes_a.iter().map(to_obvhs).collect(),
        queries: scene.boxes_b.iter().map(to_obvhs).collect(),
        rays: scene.rays.iter().map(to_obvhs_ray).collect(),
    };
    PRESETS
        .iter()
        .flat_map(|&(name, params)| {
            [
                bvh2(scene, runs, &input, name, params),
                cwbvh(scene, runs, &input, name, params),
            ]
        })
        .collect()
}

/// The binary `Bvh2` of one preset.
fn bvh2(scene: &Scene, runs: Runs, input: &Inputs, name: &str, params: BvhBuildParams) -> Measured {
    let (build, bvh) = time(runs.build, || {
        build_bvh2(&input.boxes, params, &mut Duration::default())
    });

    // `aabb_traverse` calls back with each leaf whose box overlaps the query
    // (closed intervals, like `boxes_overlap`); its primitives are a range
    // of `primitive_indices`.
    let pairs = time(runs.pairs, || {
        let mut sum = PairSum::default();
        for (j, q) in input.queries.iter().enumerate() {
            bvh.aabb_traverse(*q, |bvh, leaf| {
                let leaf = &bvh.nodes[leaf as usize];
                let range =
                    leaf.first_index as usize..(leaf.first_index + leaf.prim_count) as usize;
                for &i in &bvh.primitive_indices[range] {
                    if boxes_overlap(&scene.boxes_a[i as usize], &scene.boxes_b[j]) {
                        sum.add(i, j as u32);
                    }
                }
                true // keep going
            });
        }
        sum
    });

    let rays = time(runs.rays, || closest_hits(scene, input, &bvh));

    // PLOC and the collapse leave `nodes` compact (no dead slots), root at 0.
    let node_box = |n: &Bvh2Node| to_bvhkit(n.aabb());
    // `prim_count` is 0 for inner nodes, as `sah` wants.
    let nodes = bvh.nodes.iter().map(|n| (node_box(n), n.prim_count));
    let sah = sah(&node_box(&bvh.nodes[0]), nodes);
    Measured {
        krate: "obvhs",
        builder: name.to_string(),
        build,
        leaves: bvh.nodes.iter().filter(|n| n.is_leaf()).count(),
        sah: Some(sah),
        bytes: size_of::<Bvh2Node>() * bvh.nodes.len() + 4 * bvh.primitive_indices.len(),
        pairs: Some(pairs),
        rays: Some(rays),
        note: "build_bvh2 (PLOC, reinsertion, SAH leaf collapse per preset); \
               pairs: Bvh2::aabb_traverse per box of B; rays: Bvh2::ray_traverse",
    }
}

/// The compressed 8-wide `CwBvh` of one preset.
fn cwbvh(
    scene: &Scene,
    runs: Runs,
    input: &Inputs,
    name: &str,
    params: BvhBuildParams,
) -> Measured {
    let (build, bvh) = time(runs.build, || {
        build_cwbvh(&input.boxes, params, &mut Duration::default())
    });

    // obvhs's generic traversal (`traverse!`) with its box test per node
    // (`CwBvhNode::intersect_aabb`: the query moved into the node's 8-bit
    // grid, whose child boxes are rounded outwards, so no overlap is lost);
    // `state.primitive_id` is a position in `primitive_indices`. The
    // traversal direction only orders children, so any will do.
    let pairs = time(runs.pairs, || {
        let mut sum = PairSum::default();
        for (j, q) in input.queries.iter().enumerate() {
            let mut state = bvh.new_traversal([1.0; 3].into());
            let mut node: &CwBvhNode;
            obvhs::traverse!(bvh, node, state, node.intersect_aabb(q, state.oct_inv4), {
                let i = bvh.primitive_indices[state.primitive_id as usize];
                if boxes_overlap(&scene.boxes_a[i as usize], &scene.boxes_b[j]) {
                    sum.add(i, j as u32);
                }
            });
        }
        sum
    });

    let rays = time(runs.rays, || closest_hits(scene, input, &bvh));

    Measured {
        krate: "obvhs",
        builder: format!("{name}/cwbvh"),
        build,
        // Leaves = occupied leaf child slots (each holds 1..=3 primitives).
        leaves: bvh
            .nodes
            .iter()
            .map(|n| {
                (0..8)
                    .filter(|&c| n.is_leaf(c) && !n.is_child_empty(c))
                    .count()
            })
            .sum(),
        sah: None,
        bytes: size_of::<CwBvhNode>() * bvh.nodes.len() + 4 * bvh.primitive_indices.len(),
        pairs: Some(pairs),
        rays: Some(rays),
        note: "build_cwbvh (PLOC, reinsertion, bvh2_to_cwbvh, <= 3 prims per leaf slot); \
               pairs: traverse! + CwBvhNode::intersect_aabb; rays: CwBvh::ray_traverse",
    }
}

/// The closest-hit ray traversal both obvhs trees offer, with the same
/// callback contract: the callback gets the traversal's ray (its `tmax`
/// shrinks to the closest hit so far) and a position in
/// `primitive_indices`, and returns the hit distance or `INFINITY`; obvhs
/// keeps a `t < tmax` and reports the closest position in `RayHit`.
trait ClosestHit {
    /// Maps positions back to the input (triangle) indices.
    fn primitive_indices(&self) -> &[u32];
    /// The tree's `ray_traverse`.
    fn traverse(
        &self,
        ray: obvhs::ray::Ray,
        hit: &mut obvhs::ray::RayHit,
        f: impl FnMut(&obvhs::ray::Ray, usize) -> f32,
    ) -> bool;
}

impl ClosestHit for Bvh2 {
    fn primitive_indices(&self) -> &[u32] {
        &self.primitive_indices
    }
    fn traverse(
        &self,
        ray: obvhs::ray::Ray,
        hit: &mut obvhs::ray::RayHit,
        f: impl FnMut(&obvhs::ray::Ray, usize) -> f32,
    ) -> bool {
        self.ray_traverse(ray, hit, f)
    }
}

impl ClosestHit for CwBvh {
    fn primitive_indices(&self) -> &[u32] {
        &self.primitive_indices
    }
    fn traverse(
        &self,
        ray: obvhs::ray::Ray,
        hit: &mut obvhs::ray::RayHit,
        f: impl FnMut(&obvhs::ray::Ray, usize) -> f32,
    ) -> bool {
        self.ray_traverse(ray, hit, f)
    }
}

/// The closest hit of every ray, as original triangle indices; the
/// triangle test is the shared one, on the scene's own ray, limited to the
/// traversal's current `tmax`.
fn closest_hits(scene: &Scene, input: &Inputs, bvh: &impl ClosestHit) -> Vec<RayHit> {
    let indices = bvh.primitive_indices();
    input
        .rays
        .iter()
        .zip(&scene.rays)
        .map(|(&ray, r)| {
            let mut hit = obvhs::ray::RayHit::none();
            let found = bvh.traverse(ray, &mut hit, |ray, k| {
                hit_triangle(&scene.a, indices[k], r, ray.tmax).unwrap_or(f32::INFINITY)
            });
            found.then(|| (indices[hit.primitive_id as usize], hit.t))
        })
        .collect()
}

/// A bvhkit box as obvhs's (through arrays: no shared glam types assumed).
fn to_obvhs(b: &Aabb) -> obvhs::aabb::Aabb {
    obvhs::aabb::Aabb::new(b.min.to_array().into(), b.max.to_array().into())
}

/// An obvhs box as bvhkit's.
fn to_bvhkit(b: &obvhs::aabb::Aabb) -> Aabb {
    Aabb::new(b.min.to_array().into(), b.max.to_array().into())
}

/// A scene ray as obvhs's, `t` in `[0, INFINITY)`.
fn to_obvhs_ray(r: &Ray) -> obvhs::ray::Ray {
    obvhs::ray::Ray::new(
        r.origin().to_array().into(),
        r.dir().to_array().into(),
        0.0,
        f32::INFINITY,
    )
}

#[cfg(test)]
mod tests {
    #[test]
    fn answers_match_brute_force() {
        let m = crate::common::reference::run_and_check(super::run);
        assert_eq!(m.len(), 6);
        assert!(m.iter().all(|m| m.rays.is_some()));
    }
}
