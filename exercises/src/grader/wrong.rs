//! The plausible wrong answers of every exercise, as one [`Exercises`]
//! implementation: [`Wrong`] answers exercise `exercise` with its wrong
//! answer number `k` (kept in that exercise's file, module `wrong`) and
//! every other exercise with the reference.

use super::common::*;
use super::ex01_aabb_overlap;
use super::ex02_fit_and_merge;
use super::ex03_object_median;
use super::ex04_larger_volume;
use super::ex05_recursive_pairs;
use super::ex06_stack_pairs;
use super::ex07_cost_function;
use super::ex08_bottom_up;
use super::ex09_refit;
use super::ex10_insertion_cost;
use super::ex11_implicit_array;
use super::ex12_preorder;
use super::ex13_quantize;
use super::ex14_static_sizing;
use super::ex15_workload_pareto;
use super::ex16_sah_bins;
use super::ex17_kdop;
use super::ex18_descent_rules;
use super::ex19_partition_criteria;
use super::ex20_bfs_dfs;
use super::ex21_obb_overlap;
use super::ex22_best_first_nearest;
use super::ex23_leaf_order;
use super::ex24_stop_and_fall_back;
use super::ex25_fit_unit_costs;
use super::ex26_axis_and_split;
use super::ex27_tree_measures;
use super::ex28_tri_nodes;
use super::ex29_fit_obb;
use super::ex30_preorder_offsets;
use super::ex31_collision_system;
use super::ex32_insertion_descent;
use super::ex33_ray_best_first;
use super::ex34_wide_nodes;
use super::ex35_top_down_build;
use super::ex36_short_links;
use super::ex37_merged_leaves;
use super::ex38_clip_polygon;
use super::ex39_relocate_pieces;
use super::ex40_leaf_collapse;
use super::ex41_box_triangle;
use super::ex42_self_pairs;
use super::ex43_closest_pair;
use super::ex44_crossing_segment;
use super::ex45_penetration;
use super::ex46_handles;
use super::ex47_within;
use super::ex48_rebuild;
use super::ex49_baked;
use super::ex50_frame_box;
use super::ex51_sphere_cast;
use super::ex52_area_rotation;
use super::ex53_bins_and_partition;
use bvhkit::builders::DynNode;
use bvhkit::glam::DVec3;

/// Wrong answer `k` (from 1) of exercise `exercise`; the reference elsewhere.
pub struct Wrong {
    pub exercise: u32,
    pub k: u32,
}

/// Exercise 8's wrong answer that never returns.
pub const LOOPS: u32 = 1000;
/// Exercise 11's wrong answer whose `implicit_len` panics.
pub const PANICS: u32 = 1001;

/// How many wrong answers each exercise keeps, by exercise number.
pub fn counts() -> Vec<(u32, u32)> {
    vec![
        (1, ex01_aabb_overlap::wrong::COUNT),
        (2, ex02_fit_and_merge::wrong::COUNT),
        (3, ex03_object_median::wrong::COUNT),
        (4, ex04_larger_volume::wrong::COUNT),
        (5, ex05_recursive_pairs::wrong::COUNT),
        (6, ex06_stack_pairs::wrong::COUNT),
        (7, ex07_cost_function::wrong::COUNT),
        (8, ex08_bottom_up::wrong::COUNT),
        (9, ex09_refit::wrong::COUNT),
        (10, ex10_insertion_cost::wrong::COUNT),
        (11, ex11_implicit_array::wrong::COUNT),
        (12, ex12_preorder::wrong::COUNT),
        (13, ex13_quantize::wrong::COUNT),
        (14, ex14_static_sizing::wrong::COUNT),
        (15, ex15_workload_pareto::wrong::COUNT),
        (16, ex16_sah_bins::wrong::COUNT),
        (17, ex17_kdop::wrong::COUNT),
        (18, ex18_descent_rules::wrong::COUNT),
        (19, ex19_partition_criteria::wrong::COUNT),
        (20, ex20_bfs_dfs::wrong::COUNT),
        (21, ex21_obb_overlap::wrong::COUNT),
        (22, ex22_best_first_nearest::wrong::COUNT),
        (23, ex23_leaf_order::wrong::COUNT),
        (24, ex24_stop_and_fall_back::wrong::COUNT),
        (25, ex25_fit_unit_costs::wrong::COUNT),
        (26, ex26_axis_and_split::wrong::COUNT),
        (27, ex27_tree_measures::wrong::COUNT),
        (28, ex28_tri_nodes::wrong::COUNT),
        (29, ex29_fit_obb::wrong::COUNT),
        (30, ex30_preorder_offsets::wrong::COUNT),
        (31, ex31_collision_system::wrong::COUNT),
        (32, ex32_insertion_descent::wrong::COUNT),
        (33, ex33_ray_best_first::wrong::COUNT),
        (34, ex34_wide_nodes::wrong::COUNT),
        (35, ex35_top_down_build::wrong::COUNT),
        (36, ex36_short_links::wrong::COUNT),
        (37, ex37_merged_leaves::wrong::COUNT),
        (38, ex38_clip_polygon::wrong::COUNT),
        (39, ex39_relocate_pieces::wrong::COUNT),
        (40, ex40_leaf_collapse::wrong::COUNT),
        (41, ex41_box_triangle::wrong::COUNT),
        (42, ex42_self_pairs::wrong::COUNT),
        (43, ex43_closest_pair::wrong::COUNT),
        (44, ex44_crossing_segment::wrong::COUNT),
        (45, ex45_penetration::wrong::COUNT),
        (46, ex46_handles::wrong::COUNT),
        (47, ex47_within::wrong::COUNT),
        (48, ex48_rebuild::wrong::COUNT),
        (49, ex49_baked::wrong::COUNT),
        (50, ex50_frame_box::wrong::COUNT),
        (51, ex51_sphere_cast::wrong::COUNT),
        (52, ex52_area_rotation::wrong::COUNT),
        (53, ex53_bins_and_partition::wrong::COUNT),
    ]
}

impl Wrong {
    /// The wrong answer to use for `exercise`'s methods: 0 (the reference) unless it is ours.
    fn k(&self, exercise: u32) -> u32 {
        if self.exercise == exercise {
            self.k
        } else {
            0
        }
    }
}

impl Exercises for Wrong {
    fn aabb_overlaps(&self, a: &Aabb, b: &Aabb) -> bool {
        ex01_aabb_overlap::wrong::aabb_overlaps(self.k(1), a, b)
    }
    fn aabb_fit(&self, points: &[Vec3]) -> Aabb {
        ex02_fit_and_merge::wrong::aabb_fit(self.k(2), points)
    }
    fn aabb_merge(&self, a: &Aabb, b: &Aabb) -> Aabb {
        ex02_fit_and_merge::wrong::aabb_merge(self.k(2), a, b)
    }
    fn sphere_fit(&self, points: &[Vec3]) -> Sphere {
        ex02_fit_and_merge::wrong::sphere_fit(self.k(2), points)
    }
    fn sphere_merge(&self, a: &Sphere, b: &Sphere) -> Sphere {
        ex02_fit_and_merge::wrong::sphere_merge(self.k(2), a, b)
    }
    fn median_partition(&self, centroids: &[Vec3], indices: &mut [u32]) -> usize {
        ex03_object_median::wrong::median_partition(self.k(3), centroids, indices)
    }
    fn descend_a(&self, a: &Node<Aabb>, b: &Node<Aabb>) -> bool {
        ex04_larger_volume::wrong::descend_a(self.k(4), a, b)
    }
    fn informed_dfs(
        &self,
        a: &Bvh<Aabb>,
        pa: &[Aabb],
        b: &Bvh<Aabb>,
        pb: &[Aabb],
        out: &mut Vec<(u32, u32)>,
    ) {
        ex05_recursive_pairs::wrong::informed_dfs(self.k(5), a, pa, b, pb, out)
    }
    fn stack_dfs(
        &self,
        a: &Bvh<Aabb>,
        pa: &[Aabb],
        b: &Bvh<Aabb>,
        pb: &[Aabb],
        stack: &mut [(u32, u32)],
        out: &mut Vec<(u32, u32)>,
    ) -> bool {
        ex06_stack_pairs::wrong::stack_dfs(self.k(6), a, pa, b, pb, stack, out)
    }
    fn predicted_cost(&self, counts: &Counts, model: &CostModel) -> f64 {
        ex07_cost_function::wrong::predicted_cost(self.k(7), counts, model)
    }
    fn bottom_up_merges(&self, boxes: &[Aabb]) -> Vec<(u32, u32)> {
        ex08_bottom_up::wrong::bottom_up_merges(self.k(8), boxes)
    }
    fn refit(&self, nodes: &mut [Node<Aabb>], indices: &[u32], prims: &[Aabb]) {
        ex09_refit::wrong::refit(self.k(9), nodes, indices, prims)
    }
    fn insertion_cost(&self, sibling: &Aabb, ancestors: &[Aabb], new: &Aabb) -> f64 {
        ex10_insertion_cost::wrong::insertion_cost(self.k(10), sibling, ancestors, new)
    }
    fn implicit_children(&self, i: usize) -> (usize, usize) {
        ex11_implicit_array::wrong::implicit_children(self.k(11), i)
    }
    fn implicit_parent(&self, i: usize) -> Option<usize> {
        ex11_implicit_array::wrong::implicit_parent(self.k(11), i)
    }
    fn implicit_len(&self, depth: u32) -> usize {
        ex11_implicit_array::wrong::implicit_len(self.k(11), depth)
    }
    fn to_preorder(&self, tree: &Bvh<Aabb>) -> Vec<(Aabb, Option<u32>)> {
        ex12_preorder::wrong::to_preorder(self.k(12), tree)
    }
    fn quantize(&self, parent: &Aabb, child: &Aabb) -> ([u8; 3], [u8; 3]) {
        ex13_quantize::wrong::quantize(self.k(13), parent, child)
    }
    fn top_down_bytes(&self, n: usize, node_bytes: usize) -> usize {
        ex14_static_sizing::wrong::top_down_bytes(self.k(14), n, node_bytes)
    }
    fn pair_stack_bound(&self, depth_a: usize, depth_b: usize) -> usize {
        ex14_static_sizing::wrong::pair_stack_bound(self.k(14), depth_a, depth_b)
    }
    fn workload_ms(&self, build: f64, query: f64, rebuild: bool, frames: usize) -> f64 {
        ex15_workload_pareto::wrong::workload_ms(self.k(15), build, query, rebuild, frames)
    }
    fn pareto_front(&self, points: &[(f64, f64)]) -> Vec<usize> {
        ex15_workload_pareto::wrong::pareto_front(self.k(15), points)
    }
    fn sah_best_boundary(&self, bins: &[(Aabb, u32)]) -> Option<usize> {
        ex16_sah_bins::wrong::sah_best_boundary(self.k(16), bins)
    }
    fn dop14_fit(&self, points: &[Vec3]) -> Dop14 {
        ex17_kdop::wrong::dop14_fit(self.k(17), points)
    }
    fn dop14_overlaps(&self, a: &Dop14, b: &Dop14) -> bool {
        ex17_kdop::wrong::dop14_overlaps(self.k(17), a, b)
    }
    fn descent_open(&self, rule: Descent, d: &Decision<'_, Aabb>) -> Open {
        ex18_descent_rules::wrong::descent_open(self.k(18), rule, d)
    }
    fn partition_cost(&self, c: Partition, l: &Aabb, nl: u32, r: &Aabb, nr: u32) -> f64 {
        ex19_partition_criteria::wrong::partition_cost(self.k(19), c, l, nl, r, nr)
    }
    fn visit_order(&self, tree: &Bvh<Aabb>, breadth_first: bool) -> Vec<u32> {
        ex20_bfs_dfs::wrong::visit_order(self.k(20), tree, breadth_first)
    }
    fn obb_overlaps(&self, a: &Obb, b: &Obb) -> bool {
        ex21_obb_overlap::wrong::obb_overlaps(self.k(21), a, b)
    }
    fn best_first_nearest(
        &self,
        tree: &Bvh<Aabb>,
        prims: &[Aabb],
        p: Vec3,
    ) -> Option<(u32, f32, usize)> {
        ex22_best_first_nearest::wrong::best_first_nearest(self.k(22), tree, prims, p)
    }
    fn leaf_order_bounds(&self, tree: &Bvh<Aabb>, prims: &[Triangle]) -> Vec<Aabb> {
        ex23_leaf_order::wrong::leaf_order_bounds(self.k(23), tree, prims)
    }
    fn leaf_pair_candidates(&self, a: (&[u32], &[Aabb]), b: (&[u32], &[Aabb])) -> Vec<(u32, u32)> {
        ex23_leaf_order::wrong::leaf_pair_candidates(self.k(23), a, b)
    }
    fn node_step(&self, n: u32, depth: u32, stop: &Stop, left: u32, w: bool) -> NodeStep {
        ex24_stop_and_fall_back::wrong::node_step(self.k(24), n, depth, stop, left, w)
    }
    fn fit_unit_costs(&self, samples: &[(u64, u64, f64)]) -> (f64, f64) {
        ex25_fit_unit_costs::wrong::fit_unit_costs(self.k(25), samples)
    }
    fn split_plane(
        &self,
        centroids: &[Vec3],
        axis: crate::AxisRule,
        point: crate::PointRule,
    ) -> Option<(usize, f32)> {
        ex26_axis_and_split::wrong::split_plane(self.k(26), centroids, axis, point)
    }
    fn tree_measures(&self, tree: &Bvh<Aabb>) -> crate::TreeMeasures {
        ex27_tree_measures::wrong::tree_measures(self.k(27), tree)
    }
    fn tri_node_records(&self, tree: &Bvh<Aabb>) -> (usize, usize) {
        ex28_tri_nodes::wrong::tri_node_records(self.k(28), tree)
    }
    fn fit_obb(&self, points: &[Vec3], axes: [Vec3; 3]) -> Obb {
        ex29_fit_obb::wrong::fit_obb(self.k(29), points, axes)
    }
    fn preorder_offsets(&self, tree: &Bvh<Aabb>) -> (usize, usize) {
        ex30_preorder_offsets::wrong::preorder_offsets(self.k(30), tree)
    }
    fn collide_objects(
        &self,
        boxes: &[Aabb],
        narrow: &mut dyn FnMut(u32, u32) -> Vec<(u32, u32)>,
    ) -> Vec<((u32, u32), (u32, u32))> {
        ex31_collision_system::wrong::collide_objects(self.k(31), boxes, narrow)
    }
    fn insertion_sibling(&self, nodes: &[DynNode<Aabb>], root: u32, new: &Aabb) -> u32 {
        ex32_insertion_descent::wrong::insertion_sibling(self.k(32), nodes, root, new)
    }
    fn insertion_build(&self, boxes: &[Aabb], order: &[u32]) -> (usize, f64) {
        ex32_insertion_descent::wrong::insertion_build(self.k(32), boxes, order)
    }
    fn ray_closest(
        &self,
        tree: &Bvh<Aabb>,
        origin: Vec3,
        dir: Vec3,
        hit: &mut dyn FnMut(u32) -> Option<f32>,
    ) -> Option<(u32, f32)> {
        ex33_ray_best_first::wrong::ray_closest(self.k(33), tree, origin, dir, hit)
    }
    fn wide_collapse(&self, tree: &Bvh<Aabb>, node: u32) -> Vec<u32> {
        ex34_wide_nodes::wrong::wide_collapse(self.k(34), tree, node)
    }
    fn wide_measures(&self, tree: &Bvh<Aabb>) -> (usize, usize, usize) {
        ex34_wide_nodes::wrong::wide_measures(self.k(34), tree)
    }
    fn top_down_build(
        &self,
        boxes: &[Aabb],
        max_leaf: u32,
        nodes: &mut [Node<Aabb>],
        indices: &mut [u32],
    ) -> Option<usize> {
        ex35_top_down_build::wrong::top_down_build(self.k(35), boxes, max_leaf, nodes, indices)
    }
    fn short_links(&self, tree: &Bvh<Aabb>, reach: u16) -> (Vec<u16>, Vec<(u32, u32)>) {
        ex36_short_links::wrong::short_links(self.k(36), tree, reach)
    }
    fn decode_right(&self, links: &[u16], far: &[(u32, u32)], record: usize) -> usize {
        ex36_short_links::wrong::decode_right(self.k(36), links, far, record)
    }
    fn merged_run(&self, tree: &Bvh<Aabb>, node: u32, merge: u32) -> Option<(u32, u32)> {
        ex37_merged_leaves::wrong::merged_run(self.k(37), tree, node, merge)
    }
    fn clip_polygon(
        &self,
        polygon: &[DVec3],
        normal: DVec3,
        offset: f64,
        out: &mut [DVec3],
    ) -> usize {
        ex38_clip_polygon::wrong::clip_polygon(self.k(38), polygon, normal, offset, out)
    }
    fn clipped_area(&self, polygon: &[DVec3], planes: &[(DVec3, f64)]) -> f64 {
        ex38_clip_polygon::wrong::clipped_area(self.k(38), polygon, planes)
    }
    fn relocate_piece(&self, piece: &[Node<Aabb>], start: u32, base: u32) -> Vec<Node<Aabb>> {
        ex39_relocate_pieces::wrong::relocate_piece(self.k(39), piece, start, base)
    }
    fn piece_bases(&self, pair: u32, left: (u32, u32), right: (u32, u32)) -> (u32, u32) {
        ex39_relocate_pieces::wrong::piece_bases(self.k(39), pair, left, right)
    }
    fn best_cut_cost(&self, tree: &Bvh<Aabb>, max_leaf_size: u32, traversal_cost: f64) -> f64 {
        ex40_leaf_collapse::wrong::best_cut_cost(self.k(40), tree, max_leaf_size, traversal_cost)
    }
    fn collapsed_leaves(
        &self,
        tree: &Bvh<Aabb>,
        max_leaf_size: u32,
        traversal_cost: f64,
    ) -> Vec<(u32, u32)> {
        ex40_leaf_collapse::wrong::collapsed_leaves(self.k(40), tree, max_leaf_size, traversal_cost)
    }
    fn box_triangle(&self, b: &Aabb, t: &Triangle) -> bool {
        ex41_box_triangle::wrong::box_triangle(self.k(41), b, t)
    }
    fn self_pairs(&self, tree: &Bvh<Aabb>, prims: &[Aabb], out: &mut Vec<(u32, u32)>) {
        ex42_self_pairs::wrong::self_pairs(self.k(42), tree, prims, out)
    }
    fn closest_pair(
        &self,
        a: &Bvh<Aabb>,
        b: &Bvh<Aabb>,
        distance: &mut dyn FnMut(u32, u32) -> f64,
    ) -> Option<(u32, u32, f64)> {
        ex43_closest_pair::wrong::closest_pair(self.k(43), a, b, distance)
    }
    fn crossing_segment(&self, t1: &Triangle, t2: &Triangle) -> Option<[DVec3; 2]> {
        ex44_crossing_segment::wrong::crossing_segment(self.k(44), t1, t2)
    }
    fn box_penetration(&self, a: &Aabb, b: &Aabb) -> Option<(DVec3, f64)> {
        ex45_penetration::wrong::box_penetration(self.k(45), a, b)
    }
    fn sphere_penetration(&self, a: &Sphere, b: &Sphere) -> Option<(DVec3, f64)> {
        ex45_penetration::wrong::sphere_penetration(self.k(45), a, b)
    }
    fn handle_is_live(&self, storage: &[DynNode<Aabb>], index: u32, generation: u32) -> bool {
        ex46_handles::wrong::handle_is_live(self.k(46), storage, index, generation)
    }
    fn release_node(&self, storage: &mut [DynNode<Aabb>], free: u32, node: u32) -> u32 {
        ex46_handles::wrong::release_node(self.k(46), storage, free, node)
    }
    fn triangles_within(
        &self,
        tree: &Bvh<Aabb>,
        tris: &[Triangle],
        p: Vec3,
        distance: f32,
    ) -> Vec<u32> {
        ex47_within::wrong::triangles_within(self.k(47), tree, tris, p, distance)
    }
    fn rebuild_dynamic(
        &self,
        storage: &mut [DynNode<Aabb>],
        root: u32,
        free: u32,
        scratch: &mut [u32],
    ) -> (u32, u32) {
        ex48_rebuild::wrong::rebuild_dynamic(self.k(48), storage, root, free, scratch)
    }
    fn baked_depth(&self, nodes: &[Node<Aabb>], indices: &[u32], kept: &[Aabb]) -> Option<usize> {
        ex49_baked::wrong::baked_depth(self.k(49), nodes, indices, kept)
    }
    fn frame_box(&self, origin: DVec3, min: DVec3, max: DVec3) -> Aabb {
        ex50_frame_box::wrong::frame_box(self.k(50), origin, min, max)
    }
    fn sphere_cast(
        &self,
        tri: &Triangle,
        centre: Vec3,
        radius: f32,
        dir: Vec3,
        t_max: f32,
    ) -> Option<f32> {
        ex51_sphere_cast::wrong::sphere_cast(self.k(51), tri, centre, radius, dir, t_max)
    }

    fn area_rotation(
        &self,
        children: [Aabb; 2],
        grandchildren: [Option<[Aabb; 2]>; 2],
    ) -> Option<(usize, usize)> {
        ex52_area_rotation::wrong::area_rotation(self.k(52), children, grandchildren)
    }

    fn bin_index(&self, t: f32, lo: f32, scale: f32, k: usize) -> usize {
        ex53_bins_and_partition::wrong::bin_index(self.k(53), t, lo, scale, k)
    }

    fn bin_goes_left(&self, t: f32, lo: f32, scale: f32, k: usize, boundary: usize) -> bool {
        ex53_bins_and_partition::wrong::bin_goes_left(self.k(53), t, lo, scale, k, boundary)
    }
}
