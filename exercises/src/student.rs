//! Your answers. Replace each `todo!()`; run the grader to see your points.
#![allow(clippy::todo)] // the stubs are meant to be unfinished

use crate::{AxisRule, Exercises, NodeStep, PointRule, TreeMeasures};
use bvhkit::builders::DynNode;
use bvhkit::glam::{DVec3, Vec3};
use bvhkit::{
    Aabb, Bvh, CostModel, Counts, Decision, Descent, Dop14, Node, Obb, Open, Partition, Sphere,
    Stop, Triangle,
};

/// Your implementation of the exercises.
#[derive(Debug, Default)]
pub struct Student;

impl Exercises for Student {
    /// Two boxes overlap when their intervals overlap on *every* axis.
    /// Hint: touching boxes (sharing a face, an edge or a corner) overlap.
    fn aabb_overlaps(&self, a: &Aabb, b: &Aabb) -> bool {
        let _ = (a, b);
        todo!("exercise 1")
    }

    /// Hint: start from the first point, not from zero.
    fn aabb_fit(&self, points: &[Vec3]) -> Aabb {
        let _ = points;
        todo!("exercise 2a")
    }

    /// Hint: component-wise min of the mins and max of the maxes.
    fn aabb_merge(&self, a: &Aabb, b: &Aabb) -> Aabb {
        let _ = (a, b);
        todo!("exercise 2b")
    }

    /// Hint (Ritter): take the two most separated points among the extremes
    /// along x, y and z as a diameter; then for every point outside, grow the
    /// sphere just enough to include it, moving the centre towards the point.
    /// Floating point: make sure every point really ends up inside.
    fn sphere_fit(&self, points: &[Vec3]) -> Sphere {
        let _ = points;
        todo!("exercise 2c")
    }

    /// Hint: if one sphere contains the other, return it. Otherwise the merged
    /// sphere's diameter runs along the line through both centres.
    fn sphere_merge(&self, a: &Sphere, b: &Sphere) -> Sphere {
        let _ = (a, b);
        todo!("exercise 2d")
    }

    /// Hint: `select_nth_unstable_by` does the reordering in linear time.
    /// The axis is chosen from the box of the centroids that `indices`
    /// names (not the primitives' boxes, not every centroid);
    /// `Aabb::longest_axis` breaks ties as asked.
    fn median_partition(&self, centroids: &[Vec3], indices: &mut [u32]) -> usize {
        let _ = (centroids, indices);
        todo!("exercise 3")
    }

    /// Hint: `Node::is_leaf`, and `BoundingVolume::volume` for the size. Which
    /// node must be opened when exactly one of them is a leaf?
    fn descend_a(&self, a: &Node<Aabb>, b: &Node<Aabb>) -> bool {
        let _ = (a, b);
        todo!("exercise 4")
    }

    /// Hint: write a helper `fn visit(i, j)` over node indices, starting at
    /// the roots `(0, 0)`: return if the volumes miss; at two leaves, test the
    /// primitive pairs (`Bvh::leaf_primitives`); otherwise use your
    /// `descend_a` and recurse on the two children (`Node::children`).
    fn informed_dfs(
        &self,
        a: &Bvh<Aabb>,
        prims_a: &[Aabb],
        b: &Bvh<Aabb>,
        prims_b: &[Aabb],
        out: &mut Vec<(u32, u32)>,
    ) {
        let _ = (a, prims_a, b, prims_b, out);
        todo!("exercise 5")
    }

    /// Hint: replace the recursion by a loop that pops a pair and pushes the
    /// child pairs. `stack.get_mut(top)` returns `None` when the stack is full:
    /// return `false` then instead of indexing out of bounds.
    fn stack_dfs(
        &self,
        a: &Bvh<Aabb>,
        prims_a: &[Aabb],
        b: &Bvh<Aabb>,
        prims_b: &[Aabb],
        stack: &mut [(u32, u32)],
        out: &mut Vec<(u32, u32)>,
    ) -> bool {
        let _ = (a, prims_a, b, prims_b, stack, out);
        todo!("exercise 6")
    }

    /// Hint: the counters are integers (`u64`), the unit costs `f64`: convert
    /// each counter with `as f64` (not through `u32` or `f32`) and keep
    /// everything in `f64`.
    fn predicted_cost(&self, counts: &Counts, model: &CostModel) -> f64 {
        let _ = (counts, model);
        todo!("exercise 7")
    }

    /// Hint: keep a list of live clusters (id and box). At each step try every
    /// pair, merge the one whose *merged* box has the smallest volume, and
    /// replace the two by the new cluster (id `n + k` for the k-th merge).
    fn bottom_up_merges(&self, boxes: &[Aabb]) -> Vec<(u32, u32)> {
        let _ = boxes;
        todo!("exercise 8")
    }

    /// Hint: walk the node array from the *end*: children come after their
    /// parent, so they are done first. A leaf's primitives are
    /// `indices[first .. first + count]`.
    fn refit(&self, nodes: &mut [Node<Aabb>], indices: &[u32], prims: &[Aabb]) {
        let _ = (nodes, indices, prims);
        todo!("exercise 9")
    }

    /// Hint: `BoundingVolume::surface_area` and `Aabb::union`. An ancestor that
    /// already contains `new` does not grow at all.
    fn insertion_cost(&self, sibling: &Aabb, ancestors: &[Aabb], new: &Aabb) -> f64 {
        let _ = (sibling, ancestors, new);
        todo!("exercise 10")
    }

    /// Hint: level by level, entry `i` has children `2i + 1` and `2i + 2`.
    fn implicit_children(&self, i: usize) -> (usize, usize) {
        let _ = i;
        todo!("exercise 11a")
    }

    /// Hint: invert the children formula; both children must give the same parent.
    fn implicit_parent(&self, i: usize) -> Option<usize> {
        let _ = i;
        todo!("exercise 11b")
    }

    /// Hint: a complete tree of depth `d` has `d + 1` full levels.
    fn implicit_len(&self, depth: u32) -> usize {
        let _ = depth;
        todo!("exercise 11c")
    }

    /// Hint: depth-first with a stack of node indices (push the right child
    /// first so the left one is emitted next). The right child's output
    /// position is known only once the whole left subtree is out: remember
    /// which entry to patch. `tree.nodes()[i].children()` gives the children;
    /// `tree.root()` is `None` for a tree built from no primitives. Trees can
    /// be `bvhkit::MAX_DEPTH` (64) levels deep: size a fixed stack for that.
    fn to_preorder(&self, tree: &Bvh<Aabb>) -> Vec<(Aabb, Option<u32>)> {
        let _ = tree;
        todo!("exercise 12")
    }

    /// Hint: estimate with `floor` / `ceil` of `(x - min) / step`, then check
    /// the estimate with `dequantize` itself and step it down (for `lo`) or up
    /// (for `hi`) while it is on the wrong side: rounding can put it there.
    /// A grid line exactly on the child's face is fine (`<=` and `>=`). A flat
    /// parent axis has step 0: do not divide by it (the answer is 255, 0).
    fn quantize(&self, parent: &Aabb, child: &Aabb) -> ([u8; 3], [u8; 3]) {
        let _ = (parent, child);
        todo!("exercise 13")
    }

    fn top_down_bytes(&self, n: usize, node_bytes: usize) -> usize {
        // Hint: how many nodes has a binary tree with n leaves of one
        // primitive each? Mind n = 0.
        let _ = (n, node_bytes);
        todo!("exercise 14a")
    }

    fn pair_stack_bound(&self, depth_a: usize, depth_b: usize) -> usize {
        // Hint: a path from the root pair has at most min(depth_a, depth_b)
        // steps that open both sides; every other step opens one.
        let _ = (depth_a, depth_b);
        todo!("exercise 14b")
    }

    fn workload_ms(
        &self,
        build_ms: f64,
        query_ms: f64,
        rebuild_every_frame: bool,
        frames: usize,
    ) -> f64 {
        // Hint: how many builds and how many queries does each case run
        // (with 0 frames too)? Keep everything in f64.
        let _ = (build_ms, query_ms, rebuild_every_frame, frames);
        todo!("exercise 15a")
    }

    fn pareto_front(&self, points: &[(f64, f64)]) -> Vec<usize> {
        // Hint: compare every point with every other (n² is fine here);
        // "no worse on both" is <=, "strictly better on one" is <.
        let _ = points;
        todo!("exercise 15b")
    }

    fn sah_best_boundary(&self, bins: &[(Aabb, u32)]) -> Option<usize> {
        // Hint: a side's box is the union of its bins' boxes (`Aabb::union`),
        // not the sum of their areas; `BoundingVolume::surface_area` gives
        // the area. Skip a boundary with no primitives on one side. One
        // sweep from each end makes it linear, but two loops are fine here.
        let _ = bins;
        todo!("exercise 16")
    }

    fn dop14_fit(&self, points: &[Vec3]) -> Dop14 {
        // Hint: `Dop14::direction(i)` gives the direction's components as
        // i8; project in f64, then store `f32` bounds no tighter than the
        // f64 values (step a rounded `as f32` value outward with
        // `f32::next_down` / `next_up` where it landed inside).
        let _ = points;
        todo!("exercise 17a")
    }

    fn dop14_overlaps(&self, a: &Dop14, b: &Dop14) -> bool {
        // Hint: like two boxes, one interval test per direction.
        let _ = (a, b);
        todo!("exercise 17b")
    }

    fn descent_open(&self, rule: Descent, d: &Decision<'_, Aabb>) -> Open {
        // Hint: `match rule`; four arms are one line each. For `Overlap`,
        // the part of child `c` inside box `o` is the product over the axes
        // of (shared extent) / (c's extent), each factor clamped to [0, 1];
        // average it over `d.a_children.unwrap()` against `d.b`, and over
        // B's children against `d.a` (there may be four children, not two:
        // divide by how many there are).
        let _ = (rule, d);
        todo!("exercise 18")
    }

    fn partition_cost(&self, criterion: Partition, l: &Aabb, nl: u32, r: &Aabb, nr: u32) -> f64 {
        // Hint: `match criterion`. The intersection of two boxes has extents
        // `min(maxes) - max(mins)`: clamp negative ones to 0 before
        // multiplying (two negative extents make a positive product). The gap
        // along an axis is `max(l.min - r.max, r.min - l.max)`. Widen to f64
        // before multiplying: a count of 2^24 + 1 is not an f32.
        let _ = (criterion, l, nl, r, nr);
        todo!("exercise 19")
    }

    fn visit_order(&self, tree: &Bvh<Aabb>, breadth_first: bool) -> Vec<u32> {
        // Hint: `tree.nodes()` and `Node::children()`; a queue (VecDeque)
        // for breadth-first, a stack for depth-first (which child goes on
        // the stack first?). Trees can be 64 levels deep.
        let _ = (tree, breadth_first);
        todo!("exercise 20")
    }

    fn obb_overlaps(&self, a: &Obb, b: &Obb) -> bool {
        // Hint: on axis `l`, box `x` projects to `x.center . l` plus or
        // minus `sum_k x.half_extents[k] * |x.axes[k] . l|`. Skip a cross
        // product of (nearly) parallel axes: it is (nearly) zero and says
        // nothing. Face axes alone miss boxes that pass edge to edge.
        let _ = (a, b);
        todo!("exercise 21")
    }

    fn best_first_nearest(
        &self,
        tree: &Bvh<Aabb>,
        prims: &[Aabb],
        p: Vec3,
    ) -> Option<(u32, f32, usize)> {
        // Hint: `std::collections::BinaryHeap` is a max-heap: wrap keys in
        // `std::cmp::Reverse`; an `f32` is not `Ord`, but a non-negative
        // one's `to_bits()` sorts the same way. `Aabb::distance_squared`
        // gives a box's squared distance to `p`: take its `sqrt()`. Stop on
        // `>`, not `>=` (an equally near node may hold a smaller index), and
        // count a node when you take it from the queue, not when you push it.
        let _ = (tree, prims, p);
        todo!("exercise 22")
    }

    fn leaf_order_bounds(&self, tree: &Bvh<Aabb>, prims: &[Triangle]) -> Vec<Aabb> {
        // Hint: walk `tree.indices()` in order; `bvhkit::Primitive::bounds`
        // gives a triangle's box.
        let _ = (tree, prims);
        todo!("exercise 23a")
    }

    fn leaf_pair_candidates(&self, a: (&[u32], &[Aabb]), b: (&[u32], &[Aabb])) -> Vec<(u32, u32)> {
        // Hint: zip each leaf's ids with its boxes; report ids, not
        // positions; `Aabb::overlaps` counts touching boxes.
        let _ = (a, b);
        todo!("exercise 23b")
    }

    fn node_step(
        &self,
        n: u32,
        depth: u32,
        stop: &Stop,
        left: u32,
        weighs_counts: bool,
    ) -> NodeStep {
        // Hint: test in the order the statement gives. `u32::div_ceil`
        // rounds the leaf count up; ceil(log2(k)) is the number of bits of
        // `k - 1` (`f32::log2` rounds 2^24 + 1 down to 2^24). A 99-to-1
        // split is fine for the SAH, which prices it. `100 * smaller`
        // overflows a u32 past 42.9 million: widen to u64.
        let _ = (n, depth, stop, left, weighs_counts);
        todo!("exercise 24")
    }

    fn fit_unit_costs(&self, samples: &[(u64, u64, f64)]) -> (f64, f64) {
        // Hint: divide each row (Nv, Np) and its target t by t; then it is
        // ordinary least squares towards 1, with the 2x2 normal equations
        // (sums in f64: nearly proportional rows leave f32 nothing). If a
        // coefficient comes out negative, fit each cost alone and keep the
        // one with the smaller error.
        let _ = samples;
        todo!("exercise 25")
    }

    fn split_plane(
        &self,
        centroids: &[Vec3],
        axis: AxisRule,
        point: PointRule,
    ) -> Option<(usize, f32)> {
        // Hint: `Vec3` indexes as `c[k]`. Widen to f64 before adding or
        // subtracting: two coordinates near 3e38 overflow f32. Take the mean
        // first, then the squared differences. A strict `>` keeps ties on
        // the lower axis.
        let _ = (centroids, axis, point);
        todo!("exercise 26")
    }

    fn tree_measures(&self, tree: &Bvh<Aabb>) -> TreeMeasures {
        // Hint: walk from node 0 with an explicit stack of (node, depth);
        // `Node::children` is `None` for a leaf and `node.count` is its
        // size. Sum areas in f64 and divide once by the root's.
        let _ = tree;
        todo!("exercise 27")
    }

    fn tri_node_records(&self, tree: &Bvh<Aabb>) -> (usize, usize) {
        // Hint: walk with the depth as in exercise 27; a node at an odd
        // depth lives inside its parent's record, it roots none.
        let _ = tree;
        todo!("exercise 28")
    }

    fn fit_obb(&self, points: &[Vec3], axes: [Vec3; 3]) -> Obb {
        // Hint: `v.as_dvec3()` widens to f64. The centre you return is
        // rounded to f32, so measure the half extents from that rounded
        // centre; `bvhkit::round::up` rounds an f64 up to the next f32.
        let _ = (points, axes);
        todo!("exercise 29")
    }

    fn preorder_offsets(&self, tree: &Bvh<Aabb>) -> (usize, usize) {
        // Hint: a subtree's node count is 1 for a leaf and 1 + both
        // children's counts otherwise; children have higher indices than
        // their parent in every bvhkit tree, so one pass from the last node
        // to the first can fill the counts.
        let _ = tree;
        todo!("exercise 30")
    }

    fn collide_objects(
        &self,
        boxes: &[Aabb],
        narrow: &mut dyn FnMut(u32, u32) -> Vec<(u32, u32)>,
    ) -> Vec<((u32, u32), (u32, u32))> {
        // Hint: list the broad phase's pairs first (a < b, each once), sort
        // them, then run the narrow phase pair by pair, keeping its contacts
        // in the order it gives them. An empty box (`Aabb::EMPTY`) overlaps
        // nothing (and a builder refuses it: leave it out of a tree).
        let _ = (boxes, narrow);
        todo!("exercise 31")
    }

    fn insertion_sibling(&self, nodes: &[DynNode<Aabb>], root: u32, new: &Aabb) -> u32 {
        // Hint: `bvhkit::builders::NULL` marks a leaf's missing `left`;
        // `BoundingVolume::surface_area` (in scope with
        // `use bvhkit::BoundingVolume`) and `Aabb::union` give the terms.
        // Compare in `f64` exactly as the statement writes the costs.
        let _ = (nodes, root, new);
        todo!("exercise 32a")
    }

    fn insertion_build(&self, boxes: &[Aabb], order: &[u32]) -> (usize, f64) {
        // Hint: keep the nodes in a `Vec<DynNode<Aabb>>` (a leaf and, from
        // the second object on, a new parent per object) and reuse your
        // 32a; after linking the parent in, walk up through `parent` and
        // widen each box.
        let _ = (boxes, order);
        todo!("exercise 32b")
    }

    fn ray_closest(
        &self,
        tree: &Bvh<Aabb>,
        origin: Vec3,
        dir: Vec3,
        hit: &mut dyn FnMut(u32) -> Option<f32>,
    ) -> Option<(u32, f32)> {
        // Hint: the slab test, axis by axis: where `dir[k] == 0` do not
        // divide (the ray is inside the slab for all `t` or for none); else
        // the slab's two planes at `(min - origin) / dir` and
        // `(max - origin) / dir`. The queue as in exercise 22 (`Reverse`,
        // `to_bits` of a non-negative `f32`; `t + 0.0` turns a `-0.0` into
        // `0.0`).
        let _ = (tree, origin, dir, hit);
        todo!("exercise 33")
    }

    fn wide_collapse(&self, tree: &Bvh<Aabb>, node: u32) -> Vec<u32> {
        // Hint: `Node::children` gives `(left, right)` and `None` for a
        // leaf; keep the slots in a `Vec` and pick the slot to open with a
        // loop that keeps the best so far, replacing it on `>=` so that the
        // later slot wins a complete tie.
        let _ = (tree, node);
        todo!("exercise 34a")
    }

    fn wide_measures(&self, tree: &Bvh<Aabb>) -> (usize, usize, usize) {
        // Hint: a stack of (node, wide depth) pairs starting at the root;
        // an internal node is one wide node with `wide_collapse` as its
        // children, each one wide level deeper.
        let _ = tree;
        todo!("exercise 34b")
    }

    fn top_down_build(
        &self,
        boxes: &[Aabb],
        max_leaf: u32,
        nodes: &mut [Node<Aabb>],
        indices: &mut [u32],
    ) -> Option<usize> {
        // Hint: check the capacities first. Fill `indices` with 0..n, then
        // keep a stack (or recurse) of (node, start, end) ranges of
        // `indices`. For a range larger than `max_leaf`, call your
        // `median_partition` on the centroids (exercise 3), take the next
        // two free entries of `nodes` for the children, and push both
        // halves. Write every field of every node you use.
        let _ = (boxes, max_leaf, nodes, indices);
        todo!("exercise 35")
    }

    fn short_links(&self, tree: &Bvh<Aabb>, reach: u16) -> (Vec<u16>, Vec<(u32, u32)>) {
        // Hint: walk in preorder with a stack of (node, record waiting for
        // it as its right child). When a node gets its record, fill in the
        // waiting parent's entry: you learn how far the right child is only
        // when you reach it. Sort the far table at the end.
        let _ = (tree, reach);
        todo!("exercise 36a")
    }

    fn decode_right(&self, links: &[u16], far: &[(u32, u32)], record: usize) -> usize {
        // Hint: `slice::binary_search_by_key` finds the entry whose first
        // element is `record`.
        let _ = (links, far, record);
        todo!("exercise 36b")
    }
    fn merged_run(&self, tree: &Bvh<Aabb>, node: u32, merge: u32) -> Option<(u32, u32)> {
        // Hint: a leaf answers at once. Otherwise walk the subtree (a stack
        // or recursion), summing the leaves' counts and keeping the smallest
        // `first` and the largest `first + count`; stop early once the sum
        // passes `merge`. The leaves' entries never overlap, so they are one
        // run exactly when largest end - smallest first == the sum.
        let _ = (tree, node, merge);
        todo!("exercise 37")
    }

    fn clip_polygon(
        &self,
        polygon: &[DVec3],
        normal: DVec3,
        offset: f64,
        out: &mut [DVec3],
    ) -> usize {
        // Hint: the signed distance `s = normal.dot(p) - offset` says which
        // side a vertex is on. For each edge p -> q (i + 1 wraps to 0):
        // keep p if s(p) <= 0; if s(p) and s(q) have strictly opposite
        // signs, add p + (q - p) * t with t = s(p) / (s(p) - s(q)), the
        // fraction of the way from p where the distance reaches 0.
        let _ = (polygon, normal, offset, out);
        todo!("exercise 38a")
    }

    fn clipped_area(&self, polygon: &[DVec3], planes: &[(DVec3, f64)]) -> f64 {
        // Hint: two arrays of `crate::CLIP_CAPACITY` vertices; copy the
        // polygon into one, then clip from one into the other and swap
        // their roles after each plane. The area of a convex polygon is
        // half the length of the sum of (v[i] - v[0]) x (v[i+1] - v[0]).
        let _ = (polygon, planes);
        todo!("exercise 38b")
    }

    fn relocate_piece(&self, piece: &[Node<Aabb>], start: u32, base: u32) -> Vec<Node<Aabb>> {
        // Hint: node k of the piece (k >= 1) lands on node base + k - 1, so
        // an internal link `first` becomes base + first - 1; a leaf's range
        // moves with the primitives, by `start`. The root is element 0 of
        // your answer like any other node.
        let _ = (piece, start, base);
        todo!("exercise 39a")
    }

    fn piece_bases(&self, pair: u32, left: (u32, u32), right: (u32, u32)) -> (u32, u32) {
        // Hint: each half's root is already in the pair, so a half of `m`
        // nodes puts `m - 1` below it. Compare the primitive counts, not
        // the node counts.
        let _ = (pair, left, right);
        todo!("exercise 39b")
    }

    fn best_cut_cost(&self, tree: &Bvh<Aabb>, max_leaf_size: u32, traversal_cost: f64) -> f64 {
        // Hint: a recursive helper returning (best cost, primitives) for a
        // node does it all: a leaf's cost is count * area; an internal node
        // compares traversal_cost * area + both children's *best* costs
        // with count * area, the latter only when count <= max_leaf_size.
        let _ = (tree, max_leaf_size, traversal_cost);
        todo!("exercise 40a")
    }

    fn collapsed_leaves(
        &self,
        tree: &Bvh<Aabb>,
        max_leaf_size: u32,
        traversal_cost: f64,
    ) -> Vec<(u32, u32)> {
        // Hint: walk down from the root with the costs of 40a; where a node
        // is cheaper as a leaf, report its run (the smallest `first` of the
        // leaves below it, and their total count) and do not go further.
        let _ = (tree, max_leaf_size, traversal_cost);
        todo!("exercise 40b")
    }

    fn box_triangle(&self, b: &Aabb, t: &Triangle) -> bool {
        // Hint: first the box's own axes (compare the triangle's smallest
        // and largest coordinate with the box's); then the plane: are all
        // eight corners strictly on one side (`orient3`)? Then, for each
        // axis k and each edge (a, c) with third vertex m: are the four
        // corners of the box seen along k strictly on the other side of the
        // line through a and c than m (`orient2(a, c, corner, k)`)?
        let _ = (b, t);
        todo!("exercise 41")
    }

    fn self_pairs(&self, tree: &Bvh<Aabb>, prims: &[Aabb], out: &mut Vec<(u32, u32)>) {
        // Hint: two parts. For each leaf, every pair of its primitives
        // (`Bvh::leaf_primitives`; the second loop starts after the first's
        // position, never at it). For each internal node (`Node::children`),
        // your exercise 5 walk started at its two children `(l, r)` instead
        // of the roots: test the two boxes first, at two leaves test the
        // primitives' own boxes, else open what `descend_a` says. A walk
        // meets a pair either way round: push the smaller id first.
        let _ = (tree, prims, out);
        todo!("exercise 42")
    }

    fn closest_pair(
        &self,
        a: &Bvh<Aabb>,
        b: &Bvh<Aabb>,
        distance: &mut dyn FnMut(u32, u32) -> f64,
    ) -> Option<(u32, u32, f64)> {
        // Hint: a stack of node pairs, starting with the roots `(0, 0)`,
        // and `best: Option<(u32, u32, f64)>`. Pop a pair and compare the
        // squared distance of its two boxes (`use bvhkit::query::PairDistance;`
        // then `x.bv.closest_points(&y.bv).distance_squared`) with the best
        // *now*. At two leaves, `distance(i, j)` for every `i` of one and `j`
        // of the other (`Bvh::leaf_primitives`). Otherwise, of the node
        // `descend_a` opens, compute both child pairs' bounds and push the
        // farther first, so that the nearer is popped next.
        let _ = (a, b, distance);
        todo!("exercise 43")
    }

    fn crossing_segment(&self, t1: &Triangle, t2: &Triangle) -> Option<[DVec3; 2]> {
        // Hint: write one helper, `cut(t, other, dir) -> Option<[DVec3; 2]>`,
        // and call it both ways round with the same `dir = n1.cross(n2)`.
        // In it, the side of each corner `p` of `t`: with `other`'s corners
        // `a, b, c`, `bvhkit::narrow::orient3(a, b, c, p)` (exact), or the
        // sign of `n.dot(p - a)` in `f64`, n = (b - a) x (c - a). Collect each
        // corner whose side is 0, and for each edge i -> j (j = (i + 1) % 3)
        // whose sides are opposite (1 and -1) the point p + (q - p) * h_i /
        // (h_i - h_j), the heights h in `f64`. No point: `None`. Of the
        // points, return the one with the smallest `dot(dir)` and the one
        // with the largest.
        // Then the overlap: the start with the larger `dot(dir)`, the end
        // with the smaller, and `None` only when the start comes strictly
        // after the end (equal means they touch at one point).
        let _ = (t1, t2);
        todo!("exercise 44")
    }

    fn box_penetration(&self, a: &Aabb, b: &Aabb) -> Option<(DVec3, f64)> {
        // Hint: in `f64` (`a.min.as_dvec3()` and so on), for each axis k in
        // order x, y, z: `up = a.max[k] - b.min[k]` (move b along +k) and
        // `down = b.max[k] - a.min[k]` (along -k). Either negative: `None`,
        // the boxes are apart. Keep the smallest of the six moves, replacing
        // the best only when a move is strictly smaller, trying up before
        // down: then ties go to the lowest axis, then to +. Not the width of
        // the overlap, `min(a.max, b.max) - max(a.min, b.min)`: when one box
        // spans the other on an axis, that is shorter than the way out.
        let _ = (a, b);
        todo!("exercise 45a")
    }

    fn sphere_penetration(&self, a: &Sphere, b: &Sphere) -> Option<(DVec3, f64)> {
        // Hint: a negative radius first (`None`). Then, in `f64`,
        // `d = b.center - a.center`, `len = d.length()`, depth
        // `ra + rb - len`: negative means apart, zero touching. The normal
        // is `d / len`, or `DVec3::X` when `len` is 0.
        let _ = (a, b);
        todo!("exercise 45b")
    }

    fn handle_is_live(&self, storage: &[DynNode<Aabb>], index: u32, generation: u32) -> bool {
        // Hint: `storage.get(index as usize)` instead of indexing (a handle
        // may name a node past the end). Three tests on the node, all
        // needed: a leaf (`left == NULL`), in the tree (`height == 0`: a
        // free node also has no children), and the same generation.
        let _ = (storage, index, generation);
        todo!("exercise 46a")
    }

    fn release_node(&self, storage: &mut [DynNode<Aabb>], free: u32, node: u32) -> u32 {
        // Hint: start from `DynNode::EMPTY` so that nothing of the old leaf
        // is left (a freed node that still reads height 0 and no children
        // would look like a live leaf); set `parent` and the next
        // generation (`wrapping_add`); the node is the new head.
        let _ = (storage, free, node);
        todo!("exercise 46b")
    }

    fn triangles_within(
        &self,
        tree: &Bvh<Aabb>,
        tris: &[Triangle],
        p: Vec3,
        distance: f32,
    ) -> Vec<u32> {
        // Hint: `tree.overlapping(tris, &region, |i| ...)` is the broad
        // phase (it prunes by the nodes' boxes and tests each triangle's
        // box); in its callback, keep `i` when
        // `tris[i].closest_point(p).distance_squared` is at most the
        // distance squared, both in `f64`. Sort at the end: the tree
        // reports in its own order.
        let _ = (tree, tris, p, distance);
        todo!("exercise 47")
    }

    fn rebuild_dynamic(
        &self,
        storage: &mut [DynNode<Aabb>],
        root: u32,
        free: u32,
        scratch: &mut [u32],
    ) -> (u32, u32) {
        // Hint: walk from the root with a stack: a leaf (`left == NULL`)
        // goes into `scratch`; an internal node pushes its two children and
        // is released (`node.released(free)`, then it is the new head).
        // Then build recursively over the leaves in `scratch`: for two or
        // more, the box of their `bv.center()`s, its `extent().max_position()`
        // as the axis, sort by (coordinate, index), split at `len / 2`,
        // build both halves, and take the parent from the head of the free
        // list (its `parent` is the next free node). The root's parent is
        // `NULL`.
        let _ = (storage, root, free, scratch);
        todo!("exercise 48")
    }

    fn baked_depth(&self, nodes: &[Node<Aabb>], indices: &[u32], kept: &[Aabb]) -> Option<usize> {
        // Hint: walk from the root with a stack of (node, depth) and a
        // `seen` flag per node (reached twice: refuse; a stack deeper than
        // 64 levels: refuse). Then one pass over the leaves marking index
        // entries, one over the index array marking primitives, and one
        // over every node for the boxes (`is_finite`, `cmple(..).all()`,
        // `contains`), the kept boxes with it. Checked arithmetic for
        // `first + count`: it comes from a file.
        let _ = (nodes, indices, kept);
        todo!("exercise 49")
    }

    fn frame_box(&self, origin: DVec3, min: DVec3, max: DVec3) -> Aabb {
        // Hint: subtract in `f64` first (`min - origin`): rounded to `f32`
        // first, a coordinate 600 km away has already lost its millimetres.
        // Then round each bound outward: `v as f32` is the nearest `f32`,
        // which may lie inside; step it with `next_down` / `next_up` only
        // when it does (compare `f64::from(f)` with `v`).
        let _ = (origin, min, max);
        todo!("exercise 50")
    }

    fn sphere_cast(
        &self,
        tri: &Triangle,
        centre: Vec3,
        radius: f32,
        dir: Vec3,
        t_max: f32,
    ) -> Option<f32> {
        // Hint: the ball touches the triangle when its centre is within
        // `radius` of it, so follow the centre's ray into the triangle grown
        // by the ball: a slab of half thickness `radius` over the triangle
        // (the plane's two offsets, clipped by the three edge planes) and a
        // capsule around each edge (a cylinder clipped to the edge's length,
        // and a ball at each end). Each piece gives an interval of `t`
        // (a quadratic for balls and cylinders); the answer is the earliest
        // start, clamped to 0, of an interval that reaches `[0, t_max]`.
        // Work in f64 (`as_dvec3`).
        let _ = (tri, centre, radius, dir, t_max);
        todo!("exercise 51")
    }

    fn area_rotation(
        &self,
        children: [Aabb; 2],
        grandchildren: [Option<[Aabb; 2]>; 2],
    ) -> Option<(usize, usize)> {
        // Hint: for `down` in 0 and 1, the other child `1 - down` must have
        // children to receive it. Before: that child's area. After moving
        // `children[down]` in place of grandchild `up`, the child holds
        // `children[down]` and the grandchild `1 - up`: the area of their
        // union. Keep the largest saving (before - after) that is positive,
        // replacing it only when a later one is strictly larger.
        let _ = (children, grandchildren);
        todo!("exercise 52")
    }

    fn bin_index(&self, t: f32, lo: f32, scale: f32, k: usize) -> usize {
        // Hint: `(t - lo) * scale` counts bin widths from `lo`; clamp it to
        // `[0, k - 1]` before taking the whole part, so that neither a value
        // below `lo` nor the largest centroid falls outside the bins.
        let _ = (t, lo, scale, k);
        todo!("exercise 53")
    }

    fn bin_goes_left(&self, t: f32, lo: f32, scale: f32, k: usize, boundary: usize) -> bool {
        // Hint: compare the same number `bin_index` takes the whole part
        // of, not the plane's position in world units (`lo + boundary /
        // scale` rounds differently).
        let _ = (t, lo, scale, k, boundary);
        todo!("exercise 53")
    }
}
