//! # bvhkit exercises
//!
//! Each exercise is a method of the [`Exercises`] trait. Your answers go in
//! [`student.rs`](student) (they start as `todo!()`); the reference answers in
//! [`reference`](mod@reference) use the library. The grader runs the same checks on either:
//!
//! ```text
//! cargo run -p bvhkit-exercises --bin grade                # grades your answers
//! cargo run -p bvhkit-exercises --bin grade -- --reference # grades the reference (100%)
//! ```
//!
//! An exercise that panics (for example, still `todo!()`) scores 0 and the
//! grader moves on.

pub mod grader;
pub mod reference;
pub mod student;

use bvhkit::builders::DynNode;
use bvhkit::glam::{DVec3, Vec3};
use bvhkit::{
    Aabb, Bvh, CostModel, Counts, Decision, Descent, Dop14, Node, Obb, Open, Partition, Sphere,
    Stop, Triangle,
};

/// The exercises, one method each. Statements and hints are in the book
/// (chapter "Exercises") and on the stubs in [`student`].
pub trait Exercises {
    /// Exercise 1: do two axis-aligned boxes overlap? Touching counts.
    fn aabb_overlaps(&self, a: &Aabb, b: &Aabb) -> bool;

    /// Exercise 2a: the smallest axis-aligned box around a non-empty point set.
    fn aabb_fit(&self, points: &[Vec3]) -> Aabb;
    /// Exercise 2b: the smallest axis-aligned box containing two boxes.
    fn aabb_merge(&self, a: &Aabb, b: &Aabb) -> Aabb;
    /// Exercise 2c: a sphere containing every point of a non-empty set (each
    /// point's distance to the centre, computed in `f64`, at most the radius)
    /// and at most 1.5 times the radius of the minimal sphere. Ritter's
    /// method is enough on the grader's point sets (the bound of 1.5 leaves
    /// room for its variants).
    fn sphere_fit(&self, points: &[Vec3]) -> Sphere;
    /// Exercise 2d: a sphere containing two spheres, as small as possible.
    fn sphere_merge(&self, a: &Sphere, b: &Sphere) -> Sphere;

    /// Exercise 3: the object-median partition of a top-down builder.
    /// `indices` (`n` of them) names some of the `centroids` (in a builder,
    /// one node's primitives; `centroids` holds every primitive's). Take the
    /// bounding box of the named centroids only, and its longest axis (on a
    /// tie, x before y before z). Reorder `indices` so that the first `n / 2`
    /// name the centroids with the smallest coordinates along that axis (the
    /// object median: half the centroids on each side, not the middle of the
    /// box; equal coordinates may go either side), and return `n / 2`.
    fn median_partition(&self, centroids: &[Vec3], indices: &mut [u32]) -> usize;

    /// Exercise 4: the "descend the larger volume" rule of a two-tree
    /// traversal. `true` means open `a`, `false` means open `b`. A leaf is
    /// never opened; otherwise open the node with the larger volume (`a` on a
    /// tie). Called only when at least one node is internal.
    fn descend_a(&self, a: &Node<Aabb>, b: &Node<Aabb>) -> bool;

    /// Exercise 5: the informed depth-first traversal of two trees, written
    /// recursively: push `(i, j)` into `out` for every primitive `i` of A and
    /// `j` of B whose boxes overlap, each pair once, in any order. Prune: a
    /// pair of nodes (the roots too) whose boxes miss is skipped with
    /// everything beneath it; open the node [`descend_a`](Self::descend_a)
    /// picks. The grader moves some nodes' boxes away from their contents:
    /// nothing beneath such a node may be reported, so a pass over every
    /// pair of leaves (or one that tests boxes only at the leaves) fails.
    fn informed_dfs(
        &self,
        a: &Bvh<Aabb>,
        prims_a: &[Aabb],
        b: &Bvh<Aabb>,
        prims_b: &[Aabb],
        out: &mut Vec<(u32, u32)>,
    );

    /// Exercise 6: the same traversal (same pairs, same pruning) without
    /// recursion, using only the caller's fixed `stack` of node pairs: push
    /// `(0, 0)`, then pop a pair at a time, skip it if its boxes miss, test
    /// the primitives at two leaves, else push the two child pairs of the
    /// opened node. Returns `false` (and must not panic) as soon as a push
    /// finds the stack full; `true` when the traversal finished. A stack of
    /// `depth(A) + depth(B) + 1` entries is always enough, and the grader
    /// gives exactly that many on trees where that fills it to the last entry.
    fn stack_dfs(
        &self,
        a: &Bvh<Aabb>,
        prims_a: &[Aabb],
        b: &Bvh<Aabb>,
        prims_b: &[Aabb],
        stack: &mut [(u32, u32)],
        out: &mut Vec<(u32, u32)>,
    ) -> bool;

    /// Exercise 7: the cost function `T = Nv*Cv + Np*Cp + Nu*Cu + Co` from a
    /// query's counters and the unit costs, computed in `f64` throughout:
    /// each `u64` counter converted to `f64` (counters can pass `u32` and
    /// the 24 bits an `f32` holds exactly) and multiplied by its `f64` unit
    /// cost. The grader accepts a relative difference of 1e-9.
    fn predicted_cost(&self, counts: &Counts, model: &CostModel) -> f64;

    /// Exercise 8: the textbook bottom-up build, as its sequence of merges.
    /// Clusters `0..n` are the boxes; merge number `k` creates cluster
    /// `n + k` (`k` from 0). At every step merge the two live clusters whose
    /// merged box has the smallest volume (on a tie, any of them); return
    /// the pairs `(a, b)` merged, in order: `n - 1` of them, none for fewer
    /// than two boxes.
    fn bottom_up_merges(&self, boxes: &[Aabb]) -> Vec<(u32, u32)>;

    /// Exercise 9: refit a tree after its primitives moved. Every leaf box
    /// becomes the union of its primitives' boxes, every internal box the
    /// union of its two children. Children are stored after their parent.
    /// Change the boxes only (not `first` or `count`).
    fn refit(&self, nodes: &mut [Node<Aabb>], indices: &[u32], prims: &[Aabb]);

    /// Exercise 10: the Goldsmith–Salmon cost of inserting a new object with
    /// box `new` next to the node with box `sibling`, whose ancestors (parent
    /// first, root last) have boxes `ancestors`: the surface area of the new
    /// parent joining `sibling` and `new`, plus how much each ancestor's
    /// surface area grows when it must also contain `new`. Each area as
    /// [`BoundingVolume::surface_area`](bvhkit::BoundingVolume::surface_area)
    /// gives it (`f32`), converted to `f64` before subtracting and adding up
    /// (the total can pass 2^25, where `f32` steps by 4).
    fn insertion_cost(&self, sibling: &Aabb, ancestors: &[Aabb], new: &Aabb) -> f64;

    /// Exercise 11a: in the implicit array of a complete binary tree (root at
    /// 0, level by level), the indices of the two children of entry `i`, as
    /// `(left, right)`.
    fn implicit_children(&self, i: usize) -> (usize, usize);
    /// Exercise 11b: the index of the parent of entry `i` (`None` for the root).
    fn implicit_parent(&self, i: usize) -> Option<usize>;
    /// Exercise 11c: how many entries the implicit array of a tree of depth
    /// `depth` needs (the root alone has depth 0), for every depth up to 62
    /// (the largest for which `(1 << (depth + 1)) - 1` does not overflow a
    /// 64-bit `usize`).
    fn implicit_len(&self, depth: u32) -> usize;

    /// Exercise 12: the tree in preorder. Return one entry per node, in
    /// preorder (a node, then its whole first subtree, then its second): the
    /// node's box, and for an internal node the position *in your output* of
    /// its second (right) child; `None` for a leaf. The first child is always
    /// the next entry. A tree built from no primitives has no entries; a tree
    /// can be up to [`bvhkit::MAX_DEPTH`] (64) levels deep.
    fn to_preorder(&self, tree: &Bvh<Aabb>) -> Vec<(Aabb, Option<u32>)>;

    /// Exercise 13: quantize `child` (inside `parent`) to 8-bit grid
    /// coordinates `(lo, hi)` per axis, conservatively: with
    /// [`dequantize`]`(parent, k, q)` as the decoder, `dequantize(lo[k]) <=
    /// child.min[k]` and `dequantize(hi[k]) >= child.max[k]`, and as tight as
    /// possible (the largest such `lo`, the smallest such `hi`). On an axis
    /// where the parent is flat (`min == max`) every grid line decodes to the
    /// same value, so that axis gets `lo = 255` and `hi = 0`.
    fn quantize(&self, parent: &Aabb, child: &Aabb) -> ([u8; 3], [u8; 3]);

    /// Exercise 14a: bytes of `static` storage a top-down build over `n`
    /// primitives needs: the most nodes a binary tree over `n` primitives can
    /// have, `node_bytes` each, plus one `u32` index per primitive (no
    /// primitives: no tree, 0 bytes).
    fn top_down_bytes(&self, n: usize, node_bytes: usize) -> usize;
    /// Exercise 14b: the most node pairs that can wait on the explicit stack
    /// of a two-tree traversal of two binary trees `depth_a` and `depth_b`
    /// deep (a step opens one side, leaving one pair waiting, or both sides,
    /// leaving three), counting the pair being expanded.
    fn pair_stack_bound(&self, depth_a: usize, depth_b: usize) -> usize;

    /// Exercise 15a: the total time of a workload run for `frames` frames
    /// with a tree that takes `build_ms` to build and `query_ms` per query:
    /// built once when `rebuild_every_frame` is false, built every frame
    /// when it is true; one query per frame either way. With 0 frames a tree
    /// built once is still built (`build_ms`); one rebuilt every frame costs
    /// nothing. Computed in `f64`.
    fn workload_ms(
        &self,
        build_ms: f64,
        query_ms: f64,
        rebuild_every_frame: bool,
        frames: usize,
    ) -> f64;
    /// Exercise 15b: the Pareto front of `(time, error)` points, both to be
    /// minimised: the indices, ascending, of the points no other point
    /// dominates (another point dominates when it is no worse on both and
    /// strictly better on one). Equal points do not dominate each other.
    fn pareto_front(&self, points: &[(f64, f64)]) -> Vec<usize>;

    /// Exercise 16: the surface area heuristic over a row of bins. `bins`
    /// are the bins along one axis, in order: each with the box of its
    /// primitives ([`Aabb::EMPTY`] when it has none) and their count.
    /// Boundary `b` (in `1..bins.len()`) puts `bins[..b]` on the left and
    /// `bins[b..]` on the right, at cost `area(L) * n(L) + area(R) * n(R)`,
    /// where `L` and `R` are the boxes of all the primitives on each side.
    /// Return the cheapest boundary that leaves primitives on both sides (the
    /// smallest such `b` among equal costs), or `None` when none does.
    fn sah_best_boundary(&self, bins: &[(Aabb, u32)]) -> Option<usize>;

    /// Exercise 17a: the 14-DOP of a non-empty point set: along each of its
    /// seven directions `Dop14::direction(i)` (the axes, then the four body
    /// diagonals, unnormalised), the smallest and largest projection of the
    /// points, rounded *outward* to `f32` so that every point is inside even
    /// when the sum rounds (the library checks containment in `f64`).
    fn dop14_fit(&self, points: &[Vec3]) -> Dop14;
    /// Exercise 17b: do two 14-DOPs overlap? Touching counts.
    fn dop14_overlaps(&self, a: &Dop14, b: &Dop14) -> bool;

    /// Exercise 18: the other descent rules of a two-tree traversal, for two
    /// internal nodes that overlap: which side to open under `rule`.
    /// `AFirst` and `BFirst` always open their tree; `Simultaneous` opens
    /// both; `Alternate` opens A at even `d.depth` and B at odd; `Overlap`
    /// opens the side whose children lie, on average, least inside the other
    /// node, "inside" being the fraction of a child box's volume within the
    /// other node's box: the product over the axes of the shared extent over
    /// the child's own, each factor clamped to `[0, 1]`. The children are
    /// given (two, or up to four for a wide node: average over however many
    /// there are), each of positive extent on every axis; A on a tie. Never
    /// called with `Larger` (that is exercise 4).
    fn descent_open(&self, rule: Descent, d: &Decision<'_, Aabb>) -> Open;

    /// Exercise 19: the partition criteria of a top-down split, as a cost to
    /// minimise, in `f64` (areas and volumes from the extents `max - min`
    /// widened to `f64`, the counts too), for children boxes `l` and `r`
    /// holding `nl` and `nr` primitives: `Balance` is `|nl - nr|`; `SurfaceArea` is
    /// `nl * A(l) + nr * A(r)` (full surface areas); `Volume` is
    /// `V(l) + V(r)`; `LargerChild` is `max(V(l), V(r))`; `Overlap` is the
    /// volume of `l ∩ r` (0 when they do not overlap); `Separation` is minus
    /// the gap between the boxes, the gap being the largest distance between
    /// them along any axis (negative when they overlap on every axis, 0 when
    /// they touch). Never called with `Weighted`.
    fn partition_cost(&self, criterion: Partition, l: &Aabb, nl: u32, r: &Aabb, nr: u32) -> f64;

    /// Exercise 20: the order in which a traversal from the root visits the
    /// nodes of `tree`, as node indices: depth-first is preorder, the left
    /// child's subtree before the right's; breadth-first is level by level,
    /// left to right. The empty tree has no nodes; a tree can be up to
    /// [`bvhkit::MAX_DEPTH`] (64) levels deep.
    fn visit_order(&self, tree: &Bvh<Aabb>, breadth_first: bool) -> Vec<u32>;

    /// Exercise 21: do two oriented boxes overlap? The separating-axis test:
    /// the boxes are disjoint exactly when their projections are disjoint on
    /// one of fifteen axes (A's three, B's three, and the nine cross products
    /// of an axis of A with one of B). Touching counts as overlapping.
    fn obb_overlaps(&self, a: &Obb, b: &Obb) -> bool;

    /// Exercise 22: best-first search for the primitive box nearest to `p`.
    /// The distance from `p` to a box is `b.distance_squared(p).sqrt()` in
    /// `f32` (0 inside). Take nodes from a priority queue ordered by their
    /// box's distance to `p`, nearest first, and stop once the nearest
    /// waiting node is strictly farther than the best primitive found (a
    /// node exactly as far is still taken). Return the primitive (the
    /// smallest index among primitives equally near), its distance (not
    /// squared), and how many nodes were taken from the queue: with this
    /// stopping rule, exactly the nodes whose box is no farther from `p` than
    /// the answer. `None` for the empty tree.
    fn best_first_nearest(
        &self,
        tree: &Bvh<Aabb>,
        prims: &[Aabb],
        p: Vec3,
    ) -> Option<(u32, f32, usize)>;

    /// Exercise 23a: the primitives' bounds in leaf order. One box per entry
    /// of the tree's index array: entry `k` bounds primitive
    /// `tree.indices()[k]` (what `Bvh::with_leaf_bounds` keeps).
    fn leaf_order_bounds(&self, tree: &Bvh<Aabb>, prims: &[Triangle]) -> Vec<Aabb>;

    /// Exercise 23b: the candidate pairs of one leaf pair, from kept bounds.
    /// Each leaf is its primitive ids and, side by side, their boxes. Return
    /// every `(id of a, id of b)` whose boxes overlap (`Aabb::overlaps`:
    /// touching counts), A's ids in their order, for each of them B's ids in
    /// theirs (a loop over A around a loop over B); nothing when none do.
    fn leaf_pair_candidates(&self, a: (&[u32], &[Aabb]), b: (&[u32], &[Aabb])) -> Vec<(u32, u32)>;

    /// Exercise 24: what a top-down builder does with a node of `n`
    /// primitives at `depth` (the root is at 0), given its stopping rules
    /// `stop` (ignore `min_volume`; `max_leaf_size >= 1`) and the split its
    /// criterion proposes, `left <= n` primitives on one side (the smaller
    /// side holds `min(left, n - left)`). `weighs_counts` says whether the
    /// criterion weighs how many primitives each side gets
    /// (`Partition::weighs_counts`). In this order:
    /// [`NodeStep::Leaf`] when `n <= stop.max_leaf_size` or
    /// `depth >= stop.max_depth`; [`NodeStep::Halve`] when the levels left,
    /// `stop.max_depth - depth`, are no more than the levels needed to halve
    /// the node down to leaves, `ceil(log2(ceil(n / max_leaf_size)))`,
    /// exact (in integers: `n` goes up to `u32::MAX`, and more than 31
    /// levels may be left); [`NodeStep::FallBack`] when the proposed split
    /// puts everything on one side, or (only for a criterion that does not
    /// weigh counts) when `n >= 100` and the smaller side holds under 1% of
    /// `n`, exactly `100 * smaller < n` (exactly 1% is not under it);
    /// [`NodeStep::Split`] otherwise.
    fn node_step(
        &self,
        n: u32,
        depth: u32,
        stop: &Stop,
        left: u32,
        weighs_counts: bool,
    ) -> NodeStep;

    /// Exercise 25: fit the unit costs `(Cv, Cp)` to measured queries.
    /// Each sample is `(Nv, Np, t)`: a query's volume tests, primitive tests
    /// and measured time. Return the `Cv >= 0, Cp >= 0` that minimise the
    /// sum of squared *relative* errors, `((Nv*Cv + Np*Cp - t) / t)^2`,
    /// computed in `f64` (the grader compares each cost to 1e-6, relative).
    /// Samples with `t <= 0` (or not finite) carry no information: skip
    /// them. When the best unconstrained pair has a negative entry, or the
    /// rows `(Nv/t, Np/t)` are all proportional so that no pair is best
    /// (the 2x2 normal equations' determinant at most `1e-12` times the
    /// product of its diagonal), return the better one-cost fit: `Cv` alone
    /// with `Cp = 0`, or `Cp` alone with `Cv = 0`, whichever leaves the
    /// smaller error (`Cv` alone on a tie). With a negative entry that is
    /// the one held at 0. No usable sample (or only zero counts):
    /// `(0.0, 0.0)`.
    fn fit_unit_costs(&self, samples: &[(u64, u64, f64)]) -> (f64, f64);

    /// Exercise 26: where a top-down split goes, as `(axis, value)` with
    /// axis 0 = x, 1 = y, 2 = z: the plane `coordinate[axis] = value`.
    /// `axis` picks the coordinate axis from the centroids:
    /// [`AxisRule::Longest`] the largest extent (max - min, in `f64`: it
    /// may pass `f32::MAX`), [`AxisRule::Variance`] the largest population
    /// variance (`sum((c - mean)^2) / n`, in `f64`, the mean first: far from
    /// the origin `E[c^2] - mean^2` cancels); a tie goes to the lower axis.
    /// `point` places the plane on that axis: [`PointRule::ObjectMedian`]
    /// the coordinate at index `n / 2` of the sorted coordinates (the upper
    /// middle for even `n`), [`PointRule::ObjectMean`] the mean and
    /// [`PointRule::SpatialMedian`] the middle of the extent, `(min + max) / 2`,
    /// both computed in `f64` and returned rounded to `f32`. No centroids:
    /// `None`.
    fn split_plane(
        &self,
        centroids: &[Vec3],
        axis: AxisRule,
        point: PointRule,
    ) -> Option<(usize, f32)>;

    /// Exercise 27: measure a tree against the desired characteristics.
    /// `max_depth`: the deepest leaf's depth, the root at 0.
    /// `mean_leaf_depth`: the mean over leaves (each leaf counts once,
    /// whatever it holds). `sah_cost`: the sum over internal nodes of
    /// `A(n) / A(root)` plus the sum over leaves of
    /// `A(l) / A(root) * count(l)`, with `A` the box's surface area
    /// `2 (xy + yz + zx)`, the corners widened to `f64` before subtracting
    /// (a box 1e30 wide has an area past `f32`'s range); when the
    /// root's area is 0 every ratio counts as 1. An empty tree measures
    /// all zeros. Trees may be deeper than 32. The grader compares the
    /// means and costs to 1e-9, relative.
    fn tree_measures(&self, tree: &Bvh<Aabb>) -> TreeMeasures;

    /// Exercise 28: the cost of storing `tree` as tri-nodes (a parent and
    /// both its children fused in one record, as `bvhkit::layout::TriNodes`
    /// does). Return `(records, unused_slots)`: a record is rooted at every
    /// node at an even depth (the root at 0), so `records` counts those
    /// nodes; a record rooted at a leaf fills one of its three volume slots
    /// and wastes the other two, so `unused_slots` is twice the number of
    /// leaves at an even depth. An empty tree: `(0, 0)`; a tree that is
    /// one leaf: `(1, 2)`.
    fn tri_node_records(&self, tree: &Bvh<Aabb>) -> (usize, usize);

    /// Exercise 29: the tightest oriented box with the given orthonormal
    /// `axes` around `points` (the second half of OBB fitting; the first
    /// picks the axes, for example by PCA). It must contain every point
    /// exactly: for each point `p` and axis `k`,
    /// `|axes[k] . (p - center)| <= half_extents[k]`, evaluated in `f64` on
    /// the `f32` values returned. And it must be tight: each half extent at
    /// most `1e-5` (relative) above the exact one (half the projection
    /// range), plus what rounding costs far from the origin (the centre
    /// rounded to `f32`, and `f32` axes orthonormal only to about `1e-7`):
    /// `2^-20 * max|center coordinate|`. The box keeps the `axes` given,
    /// unchanged, and its centre is in world coordinates. `Obb::EMPTY` for
    /// no points. Work in `f64`, place the centre at the middle of each axis's
    /// projection range, then measure the half extents from the centre as
    /// rounded to `f32`, and round them up.
    fn fit_obb(&self, points: &[Vec3], axes: [Vec3; 3]) -> Obb;

    /// Exercise 30: offsets instead of pointers. In preorder a node's left
    /// child is the next record, so only the right child needs a link, and
    /// stored as an offset from its parent that link is
    /// `1 + (nodes in the left subtree)`. Return `(as_built, smaller_first)`:
    /// the largest such offset over the tree's internal nodes with the
    /// children in the order the tree has them (`Node::children`'s first
    /// is the left), and the largest when every node puts its smaller
    /// subtree first, `1 + min(left, right)`; subtree sizes count nodes,
    /// leaves and internal alike. A tree without internal nodes (empty, or
    /// one leaf): `(0, 0)`.
    fn preorder_offsets(&self, tree: &Bvh<Aabb>) -> (usize, usize);

    /// Exercise 31: the collision system's two phases. `boxes[i]` is object
    /// `i`'s world box. Broad phase: every pair `a < b` whose boxes overlap
    /// (`Aabb::overlaps`: touching counts; `Aabb::EMPTY` overlaps nothing).
    /// Narrow phase: call `narrow(a, b)`, `a < b`, exactly once for each
    /// such pair, and never for any other pair (nor `(b, a)`, nor `(a, a)`);
    /// it returns the pair's primitive contacts `(pa, pb)`. Return every
    /// contact as `((a, b), (pa, pb))`, ordered by `(a, b)` (by `a`, then
    /// `b`), and within a pair in the order `narrow` gave them, none
    /// dropped and none reordered.
    fn collide_objects(
        &self,
        boxes: &[Aabb],
        narrow: &mut dyn FnMut(u32, u32) -> Vec<(u32, u32)>,
    ) -> Vec<((u32, u32), (u32, u32))>;

    /// Exercise 32a: where insertion puts a new object (the walk of the
    /// library's `SiblingSearch::Descent`). `nodes[root]` is the root of a
    /// tree of [`DynNode`]s holding at least one object (a leaf has
    /// `left == NULL`; an internal node's children are `left` and `right`).
    /// Walk down from the root. With `A` a box's surface area
    /// (`BoundingVolume::surface_area`, widened to `f64`) and `n + new` the
    /// union of two boxes, at an internal node `n`: staying costs
    /// `2 A(n + new)`; descending into child `c` costs
    /// `2 (A(n + new) - A(n))` (the growth of `n`, counted twice) plus
    /// `A(c + new)` when `c` is a leaf, or plus `A(c + new) - A(c)` when it
    /// is internal. Stop at `n` when staying costs strictly less than both
    /// children; otherwise descend into the cheaper child (the left one on
    /// a tie). A leaf ends the walk (so a tree of one leaf gives the
    /// root). Return the node the walk ends at: the new object's sibling.
    fn insertion_sibling(&self, nodes: &[DynNode<Aabb>], root: u32, new: &Aabb) -> u32;

    /// Exercise 32b: build a tree by inserting `boxes[order[0]]`, then
    /// `boxes[order[1]]`, and so on. The first object is the root (a leaf);
    /// each later one gets a new parent that takes the place of the sibling
    /// 32a finds and joins the two (its box their union), and every
    /// ancestor's box grows to contain the object. No rotations. Return
    /// `(height, area_sum)`: the height (edges on the longest root-to-leaf
    /// path, 0 for one leaf) and the sum of every node's surface area, each
    /// widened to `f64` (what `DynamicTree::area_sum` reports). An empty
    /// `order`: `(0, 0.0)`.
    fn insertion_build(&self, boxes: &[Aabb], order: &[u32]) -> (usize, f64);

    /// Exercise 33: best-first search for the closest hit along the ray
    /// `origin + t * dir`, `t >= 0` (`dir` is finite and non-zero, of any
    /// length: `t` is in its units). `hit(k)` tests primitive `k`: where
    /// the ray hits it, `None` where it misses; the tree's node boxes bound
    /// the primitives. A node's entry distance is the smallest `t >= 0` at
    /// which the ray is in its box (closed: touching counts; 0 when `origin`
    /// is inside), none when the ray misses it; where `dir` has a zero
    /// component the ray is inside that slab for every `t` or for none.
    /// Keep the nodes the ray enters in a priority queue by entry distance,
    /// start with the root, always open the nearest, and stop when it is
    /// farther than the best hit so far (one at exactly that distance is
    /// still opened: it may hold a tie). Return the closest hit `(k, t)`,
    /// `t` as `hit` gave it, the smaller `k` on equal `t`; `None` when
    /// nothing is hit (or the tree is empty). Call `hit` at most once per
    /// primitive: the grader counts the calls.
    fn ray_closest(
        &self,
        tree: &Bvh<Aabb>,
        origin: Vec3,
        dir: Vec3,
        hit: &mut dyn FnMut(u32) -> Option<f32>,
    ) -> Option<(u32, f32)>;

    /// Exercise 34a: one node of the 4-wide collapse, as `layout::Wide`
    /// builds it from `tree`. The slots start as `node`'s two children,
    /// `[left, right]`. While there are fewer than four slots and one of
    /// them is an internal node, open the internal slot whose box has the
    /// largest `Aabb::half_area()` (compared as `f32`; equal areas: the
    /// larger `extent().element_sum()`; still equal: the later slot): its
    /// left child takes its place and its right child is appended. Return
    /// the slots (node indices of `tree`) in slot order; an empty `Vec`
    /// when `node` is a leaf.
    fn wide_collapse(&self, tree: &Bvh<Aabb>, node: u32) -> Vec<u32>;

    /// Exercise 34b: the whole 4-wide tree. Its root holds the collapse
    /// (34a) of `tree`'s root; each internal slot is a wide node holding
    /// the collapse of its own node, and each leaf slot is a leaf. Return
    /// `(inner, depth, empty_slots)`: how many wide internal nodes there
    /// are, the depth of the deepest leaf in wide levels (`tree`'s root
    /// at 0), and how many of the wide internal nodes' slots stay empty
    /// (4 per node, less its children). A tree of one leaf, or none:
    /// `(0, 0, 0)`.
    fn wide_measures(&self, tree: &Bvh<Aabb>) -> (usize, usize, usize);

    /// Exercise 35: a whole top-down build, into the caller's arrays.
    /// Build a tree over `boxes` (`n` of them) in `nodes` and `indices`:
    /// - a node over at most `max_leaf` primitives (`max_leaf >= 1`) is a
    ///   leaf; any other node is split by exercise 3's object median (the
    ///   box of the node's centroids, its longest axis, the `n / 2` smallest
    ///   centroids on the left), even when its centroids all coincide;
    /// - the canonical layout: the root is `nodes[0]`; a leaf has
    ///   `count >= 1` and holds `indices[first..first + count]`; an internal
    ///   node has `count == 0` and its children at `first` (left) and
    ///   `first + 1` (right);
    /// - every node's `bv` is exactly the union of its primitives' boxes
    ///   (`Aabb::union`; a centroid is `Aabb::center`);
    /// - each primitive `0..n` is in exactly one leaf.
    ///
    /// Return the number of nodes written (`0` for no boxes), or `None`,
    /// without panicking, when `nodes` has fewer than `2n - 1` entries or
    /// `indices` fewer than `n`. The arrays may hold anything before.
    fn top_down_build(
        &self,
        boxes: &[Aabb],
        max_leaf: u32,
        nodes: &mut [Node<Aabb>],
        indices: &mut [u32],
    ) -> Option<usize>;

    /// Exercise 36a: 16-bit right links with an escape. Lay `tree` out in
    /// preorder (the root, its whole left subtree, then its right subtree;
    /// the left child is `Node::children`'s first) and return one `u16`
    /// per record, in that order, and the far table:
    /// - a leaf's entry is `0`;
    /// - an internal node at record `i` whose right child lands at record
    ///   `j` stores the offset `j - i` when it is at most `reach`;
    /// - a larger offset stores [`ESCAPE`] (65 535) instead, and `(i, j)`
    ///   goes into the far table.
    ///
    /// Return the far table sorted by record. `reach` is at most 65 534 (so
    /// a stored offset is never the escape). An empty tree: two empty lists.
    fn short_links(&self, tree: &Bvh<Aabb>, reach: u16) -> (Vec<u16>, Vec<(u32, u32)>);

    /// Exercise 36b: the right child's record of the internal node at
    /// `record`, from 36a's `links` and sorted `far` table: the record plus
    /// its offset, or, when its entry is [`ESCAPE`], the far table's entry
    /// for `record` (found by binary search).
    fn decode_right(&self, links: &[u16], far: &[(u32, u32)], record: usize) -> usize;

    /// Exercise 37: fuller quantized records. `bvhkit::layout::QuantizedWide`
    /// stores a whole small subtree as one leaf slot, naming its primitives
    /// as one run of the index array, `(first, count)`: the entries
    /// `tree.indices()[first..first + count]`. Return that run for `node`:
    /// - a leaf: its own `(first, count)`, whatever `merge`;
    /// - an internal node: `Some` when the leaves under it hold at most
    ///   `merge` primitives in all and their entries are one contiguous run
    ///   (no gap; `first` is the smallest entry), `None` otherwise. A tree
    ///   from a top-down builder never has a gap; one written by hand (or by
    ///   another builder) may. `merge = 0` merges no internal node.
    fn merged_run(&self, tree: &Bvh<Aabb>, node: u32, merge: u32) -> Option<(u32, u32)>;

    /// Exercise 38a: clip a convex polygon by a half-space, one step of
    /// measuring a k-DOP exactly (Sutherland–Hodgman for one plane).
    /// `polygon` is convex and planar, with at least three vertices, no two
    /// consecutive ones equal, and its last vertex joined to its first.
    /// Write to `out` the vertices of its part where `normal . p <= offset`
    /// and return how many. Walk the edges `p -> q`, the closing edge (last
    /// to first) included: keep `p` when `normal . p <= offset`, then add
    /// the point where the edge crosses the plane when its ends lie
    /// strictly on opposite sides. So a vertex exactly on the plane is kept
    /// once, and an edge that only touches the plane at an end adds no
    /// point. What is left may be nothing (0), or only a vertex or an edge
    /// of a polygon touching the plane from outside (1 or 2 vertices); a
    /// polygon lying in the plane is kept whole. `normal` need not be of
    /// unit length. `out` has `polygon.len() + 1` entries, the most a convex
    /// polygon can need. The grader accepts any starting vertex (the order
    /// around the polygon must be the input's) and coordinates within
    /// 1e-9, relative.
    fn clip_polygon(
        &self,
        polygon: &[DVec3],
        normal: DVec3,
        offset: f64,
        out: &mut [DVec3],
    ) -> usize;

    /// Exercise 38b: the area of what is left of a convex polygon after
    /// clipping it by each half-space `normal . p <= offset` of `planes` in
    /// turn (with 38a): the face of a k-DOP on one of its planes is a large
    /// square in that plane clipped by every other plane. 0 when fewer than
    /// three vertices are left. `polygon.len() + planes.len()` is at most
    /// [`CLIP_CAPACITY`], so two arrays of that many vertices hold every
    /// step.
    fn clipped_area(&self, polygon: &[DVec3], planes: &[(DVec3, f64)]) -> f64;

    /// Exercise 39a: a subtree built on its own, moved into the whole tree
    /// (the second pass of the parallel build). `piece` is in the canonical
    /// layout of its own: its root is `piece[0]`, an internal node's
    /// children are `piece[first]` and `piece[first + 1]`, a leaf holds the
    /// piece's own primitives `first..first + count`. In the whole tree the
    /// root goes to a slot elsewhere (its parent's child slot), the other
    /// nodes go in order to nodes `base`, `base + 1`, ..., and the piece's
    /// primitives start at entry `start` of the index array. Return the
    /// piece's nodes as the whole tree holds them, the root first: links
    /// and ranges moved, volumes and counts unchanged.
    fn relocate_piece(&self, piece: &[Node<Aabb>], start: u32, base: u32) -> Vec<Node<Aabb>>;

    /// Exercise 39b: where two halves go. A split node's children take
    /// nodes `pair` and `pair + 1`; below them come the other nodes of one
    /// half, then those of the other: the half over fewer primitives
    /// first, the left one on a tie (the order the sequential builder
    /// finishes them). `left` and `right` are each half's (primitives,
    /// nodes), nodes counting the half's own root. Return the node where
    /// each half's other nodes start, `(left, right)`.
    fn piece_bases(&self, pair: u32, left: (u32, u32), right: (u32, u32)) -> (u32, u32);

    /// Exercise 40a: leaf collapse, the price of the best cut. Every
    /// subtree of `tree` holding at most `max_leaf_size` primitives may
    /// become one leaf. Costs, with `A` a node's `Aabb::surface_area()` in
    /// `f64`: a leaf of `k` primitives costs `k * A`; an internal node kept
    /// as it is costs `traversal_cost * A` plus its children's costs. Each
    /// node takes the cheaper of the two (a tie makes a leaf), its children
    /// priced the same way first. Return the root's cost: the SAH cost of
    /// the cheapest tree the collapse can make, the root's own visit
    /// included. Existing leaves may hold several primitives already; an
    /// empty tree costs 0.
    fn best_cut_cost(&self, tree: &Bvh<Aabb>, max_leaf_size: u32, traversal_cost: f64) -> f64;

    /// Exercise 40b: the leaves of that cheapest tree, each as its run of
    /// the index array `(first, count)`, sorted by `first`. A node that
    /// becomes a leaf hides the nodes below it: report only the topmost.
    /// In the trees the grader gives, every subtree's primitives are one
    /// run of the index array (as every builder of the library writes
    /// them).
    fn collapsed_leaves(
        &self,
        tree: &Bvh<Aabb>,
        max_leaf_size: u32,
        traversal_cost: f64,
    ) -> Vec<(u32, u32)>;

    /// Exercise 41: does the closed box `b` share a point with the closed
    /// triangle `t`? Exactly, for any `f32` input: the two are disjoint
    /// exactly when their projections are disjoint on one of 13 axes (the
    /// box's three, the triangle's normal, and each triangle edge crossed
    /// with each box axis), and each of those tests can be decided by signs
    /// alone: coordinate comparisons, `bvhkit::narrow::orient3` (a box
    /// corner against the triangle's plane) and `bvhkit::narrow::orient2`
    /// (a box corner against an edge's line, projected along an axis), all
    /// exact. Touching counts; a zero-area triangle is the segment or point
    /// it is; a box may be flat.
    fn box_triangle(&self, b: &Aabb, t: &Triangle) -> bool;

    /// Exercise 42: self-collision, one tree against itself. Push `(i, j)`
    /// with `i < j` into `out` for every two primitives of `tree` whose
    /// boxes overlap (touching counts), each pair exactly once, in any
    /// order. Two primitives in the same leaf are paired inside that leaf:
    /// test every pair of its primitives. Two in different leaves meet at
    /// the lowest internal node above both, one beneath each child: for
    /// every internal node, walk its two children against each other with
    /// the informed traversal of exercise 5 (test the two nodes' boxes and
    /// skip the pair with everything beneath it when they miss; at two
    /// leaves test the primitives' own boxes; otherwise open the node
    /// [`descend_a`](Self::descend_a) picks), reporting each pair with the
    /// smaller index first. Nothing else: a node's own box is never tested
    /// against itself (a box always overlaps itself). Never walk the tree
    /// against itself with exercise 5, which finds each pair twice, `(i, j)`
    /// and `(j, i)`, and every primitive with itself. The grader moves an
    /// internal node's box away from its contents: a pair with one
    /// primitive beneath that node must not be reported (the walk that
    /// meets the node prunes it), a pair with both beneath it still must
    /// (the node's children are walked against each other without testing
    /// its own box).
    fn self_pairs(&self, tree: &Bvh<Aabb>, prims: &[Aabb], out: &mut Vec<(u32, u32)>);

    /// Exercise 43: the closest pair of primitives of two trees, by branch
    /// and bound. `distance(i, j)` measures primitive `i` of A against
    /// primitive `j` of B: their squared distance (`f64`, 0 when they touch
    /// or overlap), the expensive step. Each tree's node boxes bound its
    /// primitives, so the squared distance between two node boxes (per axis
    /// the gap `max(0, a.min - b.max, b.min - a.max)`, the corners widened
    /// to `f64`, the three gaps squared and added, x + y + z: what
    /// [`PairDistance::closest_points`](bvhkit::query::PairDistance::closest_points)
    /// gives for two boxes) is a lower bound on the distance of every pair
    /// beneath them. Walk the node pairs depth first from the roots. Take a
    /// pair; skip it, with everything beneath it, when its bound is not
    /// below the best distance found so far (`bound >= best`, tested when
    /// the pair is taken: the best may have shrunk since it was queued).
    /// At two leaves measure every pair of their primitives and keep the
    /// smallest distance over the whole walk; otherwise open the node
    /// [`descend_a`](Self::descend_a) picks and visit its two child pairs
    /// nearer first (the smaller bound; either on a tie). Return
    /// `(i, j, d)`: a closest pair and its squared distance as `distance`
    /// gave it (on a tie, any pair at the smallest distance); `None` when a
    /// tree is empty. Call `distance` at most once per pair: the grader
    /// counts the calls, and moves node boxes far from their contents: the
    /// walk prunes by what the boxes say, so once a nearer pair has been
    /// measured nothing beneath a moved node is.
    fn closest_pair(
        &self,
        a: &Bvh<Aabb>,
        b: &Bvh<Aabb>,
        distance: &mut dyn FnMut(u32, u32) -> f64,
    ) -> Option<(u32, u32, f64)>;

    /// Exercise 44: where two triangles cross. `t1` and `t2` are never in
    /// one plane and never of zero area (the grader asks about no other
    /// kind). Return the segment the two closed triangles share, its two
    /// ends in either order (equal when they touch at one point), or `None`
    /// when they do not touch. The segment lies on the line where the two
    /// planes meet, whose direction is `n1 x n2` (the normals
    /// `(b - a) x (c - a)` of each triangle's corners `a, b, c`, in `f64`).
    /// Each triangle cuts the other's plane in a segment of that line (or a
    /// point, or not at all): its corners on that plane, and for each edge
    /// whose two ends lie strictly on opposite sides, the point where it
    /// crosses. The answer is the overlap of the two cuts along the line:
    /// from the later of their starts to the earlier of their ends, ordered
    /// by `p.dot(n1 x n2)`. Which side of a plane a corner is on may be
    /// decided with `bvhkit::narrow::orient3` (exact) or with the signed
    /// height `n.dot(p - a)` in `f64`, whose sign is right on every case the
    /// grader gives. Ends are compared within 1e-9 times the largest
    /// coordinate of the six corners (at least 1).
    fn crossing_segment(&self, t1: &Triangle, t2: &Triangle) -> Option<[DVec3; 2]>;

    /// Exercise 45a: how deep two solid boxes overlap. Return
    /// `(normal, depth)`: moving `b` by `normal * depth` leaves the boxes
    /// touching, and no shorter move separates them. Compute in `f64` from
    /// the `f32` corners. On each axis `k`, `b` can leave upwards, by
    /// `a.max[k] - b.min[k]` along `+k`, or downwards, by
    /// `b.max[k] - a.min[k]` along `-k`; the answer is the smallest of these
    /// six moves, its normal the unit axis with that sign (so it points from
    /// `a` towards `b`). Ties go to the lowest axis (x, then y, then z), and
    /// on one axis to `+` (the upward move). `None` when the boxes do not
    /// overlap (some move is negative); boxes that only touch overlap, with
    /// depth 0. Flat boxes and points (`min == max` on some axis) are boxes
    /// like any other; [`Aabb::EMPTY`] overlaps nothing. The grader gives no
    /// other box with `min > max`. Normals are compared within 1e-9, depths
    /// within 1e-9 times the largest coordinate (at least 1).
    fn box_penetration(&self, a: &Aabb, b: &Aabb) -> Option<(DVec3, f64)>;
    /// Exercise 45b: how deep two solid spheres overlap, as in 45a: moving
    /// `b` by `normal * depth` leaves them touching. Compute in `f64`: with
    /// `d = b.center - a.center` and the distance `|d|`, the depth is
    /// `a.radius + b.radius - |d|` and the normal is `d / |d|`, a unit
    /// vector from `a`'s centre towards `b`'s; `+x` when the centres
    /// coincide. `None` when they do not overlap (a negative depth), and
    /// when either radius is negative ([`Sphere::EMPTY`]); spheres that only
    /// touch give depth 0, and a radius of 0 is a point. Compared as in 45a
    /// (the largest coordinate or radius, at least 1).
    fn sphere_penetration(&self, a: &Sphere, b: &Sphere) -> Option<(DVec3, f64)>;

    /// Exercise 46a: is the handle `(index, generation)` live in a dynamic
    /// tree's `storage`? Live means node `index` exists, is a leaf of the
    /// tree (height 0 and no children: `left == NULL`; a free node has
    /// height `u32::MAX`, an internal node has children) and is in exactly
    /// that generation. Any other handle, one past the end of the storage
    /// included, is not live (return `false`, never panic).
    fn handle_is_live(&self, storage: &[DynNode<Aabb>], index: u32, generation: u32) -> bool;
    /// Exercise 46b: free node `node` of `storage`, whose free list starts
    /// at `free` ([`NULL`](bvhkit::builders::NULL) when empty; the list runs
    /// through `parent`). The node becomes blank ([`DynNode::EMPTY`]) but
    /// for two fields: `parent`, the old head `free`, and `generation`, its
    /// own plus one (wrapping past `u32::MAX` to 0). Return the new head of
    /// the free list.
    fn release_node(&self, storage: &mut [DynNode<Aabb>], free: u32, node: u32) -> u32;

    /// Exercise 47: every triangle of `tris` within `distance` of `p`, in
    /// increasing index order, found through `tree` (built over `tris`):
    /// a broad phase, a region query with the box `p - distance ..= p +
    /// distance` that prunes every node whose box misses it, then a narrow
    /// phase, each candidate's exact distance. A triangle is within when
    /// its closest point ([`Triangle::closest_point`], in `f64`) is at most
    /// `distance` away: the squared distances compared in `f64`, touching
    /// counts. The grader moves some nodes' boxes away from their
    /// contents: nothing beneath such a node may be reported. It gives no
    /// NaN, infinite or negative input; `tree` may be empty.
    fn triangles_within(
        &self,
        tree: &Bvh<Aabb>,
        tris: &[Triangle],
        p: Vec3,
        distance: f32,
    ) -> Vec<u32>;

    /// Exercise 48: rebuild every node above the leaves of the dynamic tree
    /// in `storage` (rooted at `root`, [`NULL`](bvhkit::builders::NULL) when
    /// empty; its free list starts at `free` and runs through `parent`), as
    /// [`DynamicTree::rebuild`](bvhkit::builders::DynamicTree::rebuild)
    /// does. Every leaf keeps its node, volume, item and generation (only
    /// its `parent` changes). First every internal node is released as in
    /// exercise 46b (blank, next generation, pushed on the free list); then
    /// the tree over the leaves is built top down, each new internal node
    /// taken from the head of the free list, keeping that node's generation,
    /// with `bv` the union of its children's ([`Aabb::union`]), `height` one
    /// more than the taller child's, `item` 0 and the children's `parent`
    /// set. A set of two or more leaves splits along the longest side of the
    /// box of its leaves' centres ([`Aabb::center`] of each `bv`; of equal
    /// sides the first, x before y before z): ordered by the centre's
    /// coordinate on that axis, then by node index, the first `len / 2` go
    /// left. Return the new root (`NULL` for an empty tree) and the new head
    /// of the free list. `scratch` has room for one entry per leaf.
    fn rebuild_dynamic(
        &self,
        storage: &mut [DynNode<Aabb>],
        root: u32,
        free: u32,
        scratch: &mut [u32],
    ) -> (u32, u32);

    /// Exercise 49: may parts read from a baked tree's bytes be trusted, as
    /// [`baked::check`](bvhkit::baked::check) decides? `nodes` has the root
    /// at 0; a node with `count == 0` is internal, its children at `first`
    /// and `first + 1`; a leaf (`count > 0`) holds the index entries
    /// `first .. first + count`. `kept` is empty or holds one box per index
    /// entry (the primitive's bounds). Return the depth (edges from the
    /// root to the deepest leaf) when all of these hold, `None` otherwise:
    /// - no nodes is the empty tree (depth 0), valid only with no index
    ///   entries and no kept boxes;
    /// - every child's index is greater than its parent's and inside
    ///   `nodes`, every node is reached exactly once from the root, and the
    ///   depth is at most 64;
    /// - every leaf's range lies inside the index array, and every index
    ///   entry is in exactly one leaf;
    /// - every value in the index array is below its length, and none
    ///   appears twice;
    /// - every node's box is finite and not inverted (`min <= max` on each
    ///   axis), and an internal node's box contains both children's
    ///   ([`Aabb::contains`](bvhkit::BoundingVolume::contains));
    /// - every kept box, if any, is finite, not inverted and inside its
    ///   leaf's box.
    ///
    /// The grader gives corrupted trees of every kind, cycles included:
    /// never panic, never loop for ever.
    fn baked_depth(&self, nodes: &[Node<Aabb>], indices: &[u32], kept: &[Aabb]) -> Option<usize>;

    /// Exercise 50: the world box `[min, max]` (in `f64`) entered into a
    /// local frame at `origin`, as [`LocalFrame::aabb`](bvhkit::LocalFrame::aabb)
    /// does: an `f32` box that contains every point of the world box's
    /// offsets from `origin`, with each bound the nearest `f32` on the outer
    /// side (the smallest such box). Every input is finite.
    fn frame_box(&self, origin: DVec3, min: DVec3, max: DVec3) -> Aabb;

    /// Exercise 51: the time of impact of a ball of `radius` whose centre
    /// moves along `centre + t * dir` against the triangle `tri`, as
    /// [`CastTarget::cast_hit`](bvhkit::CastTarget::cast_hit) answers for a
    /// [`ShapeCast::sphere`](bvhkit::ShapeCast::sphere): the smallest `t` in
    /// `[0, t_max]` at which the ball touches the triangle (its face, an
    /// edge or a corner; `0` if it starts touching), or `None`. Every input
    /// is finite except `t_max`, which may be infinite; `dir` is not zero.
    fn sphere_cast(
        &self,
        tri: &Triangle,
        centre: Vec3,
        radius: f32,
        dir: Vec3,
        t_max: f32,
    ) -> Option<f32>;

    /// Exercise 52: the rotation by area of a dynamic tree's node, as
    /// [`area_rotation`](bvhkit::builders::area_rotation) chooses it. The
    /// node has `children` (0 left, 1 right); `grandchildren[k]` holds
    /// `children[k]`'s own two children, or `None` if it is a leaf. A swap
    /// `(down, up)` moves `children[down]` into the other child, in place of
    /// that child's child `up`, which moves up. Only the child that receives
    /// a node changes its box (the union of what it then holds), so return
    /// the swap after which that box has the smallest surface area, if that
    /// is smaller than the box's area before; `None` if no swap shrinks it.
    /// Ties go to the first in the order (0, 0), (0, 1), (1, 0), (1, 1).
    fn area_rotation(
        &self,
        children: [Aabb; 2],
        grandchildren: [Option<[Aabb; 2]>; 2],
    ) -> Option<(usize, usize)>;

    /// Exercise 53a: the bin of a centroid coordinate `t` among `k` bins of
    /// width `1 / scale` that start at `lo` (bin `j` holds
    /// `lo + j / scale <= t < lo + (j + 1) / scale`); a `t` outside them
    /// goes to the nearer end bin, so the largest centroid, at
    /// `lo + k / scale`, is in bin `k - 1`. `t`, `lo` and `scale` are
    /// finite, `scale > 0`, `k >= 2`.
    fn bin_index(&self, t: f32, lo: f32, scale: f32, k: usize) -> usize;

    /// Exercise 53b: whether the partition sends `t` left of the plane
    /// between bins `boundary - 1` and `boundary` (`1 <= boundary < k`). It
    /// must be `bin_index(t, lo, scale, k) < boundary` for every `t`: the
    /// children's boxes come from the bins.
    fn bin_goes_left(&self, t: f32, lo: f32, scale: f32, k: usize, boundary: usize) -> bool;
}

/// Exercise 38b's bound on `polygon.len() + planes.len()`: a 26-DOP's face
/// is a square clipped by the 25 other planes, 29 vertices at most.
pub const CLIP_CAPACITY: usize = 32;

/// The escape value of exercise 36: "the link is in the far table" (the
/// library's [`bvhkit::layout::ESCAPE`]).
pub const ESCAPE: u16 = u16::MAX;

/// What exercise 27 measures (the library's `Bvh::stats` reports these and
/// more).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct TreeMeasures {
    /// Depth of the deepest leaf (root = 0).
    pub max_depth: usize,
    /// Mean depth of the leaves.
    pub mean_leaf_depth: f64,
    /// SAH cost with one unit per node visit and per primitive test.
    pub sah_cost: f64,
}

/// The axis choices of exercise 26 (the library's [`bvhkit::AxisChoice`]
/// has more, and directions that are not coordinate axes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AxisRule {
    /// The coordinate axis along which the centroids spread furthest.
    Longest,
    /// The coordinate axis along which the centroids vary most.
    Variance,
}

/// The split points of exercise 26 (the library's [`bvhkit::SplitPoint`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PointRule {
    /// The middle centroid: equal halves.
    ObjectMedian,
    /// The mean of the centroids.
    ObjectMean,
    /// The middle of the centroids' extent.
    SpatialMedian,
}

/// What a top-down builder does with one node (exercise 24).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NodeStep {
    /// Stop: the node becomes a leaf.
    Leaf,
    /// The depth budget: halve the node at its object median.
    Halve,
    /// The proposed split failed: try another axis choice, the SAH, then the
    /// object median (and count it in the tree's `BuildReport`).
    FallBack,
    /// Take the proposed split.
    Split,
}

/// The decoder of exercise 13: grid line `q` of axis `k` of `parent`. Line 0 is
/// `parent.min[k]` and line 255 is `parent.max[k]`, both exactly; line `q`
/// between them is `min + q * (extent / 255)`, rounded as `f32` arithmetic
/// rounds.
pub fn dequantize(parent: &Aabb, k: usize, q: u8) -> f32 {
    match q {
        255 => parent.max[k],
        _ => parent.min[k] + q as f32 * ((parent.max[k] - parent.min[k]) / 255.0),
    }
}
