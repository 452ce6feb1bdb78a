//! Reference answers, written with the library.

use crate::{AxisRule, Exercises, NodeStep, PointRule, TreeMeasures};
use bvhkit::builders::{DynNode, DynamicConfig, DynamicTree, Rotations, SiblingSearch, NULL};
use bvhkit::glam::{DVec3, Vec3};
use bvhkit::layout::{Wide, WideNode};
use bvhkit::narrow::{triangle_contact, Contact, Penetrate};
use bvhkit::query::{PairDistance, Ray, RayTarget, SelfPairs};
use bvhkit::{
    Aabb, BoundingVolume, Bvh, CostModel, Counts, Decision, Descent, Dop14, Hierarchy, Node, Obb,
    Open, PairTraversal, Pairs, Partition, Primitive, Sphere, Stop, Triangle,
};

/// The reference implementation: scores 100%.
#[derive(Debug, Default)]
pub struct Reference;

impl Exercises for Reference {
    fn baked_depth(&self, nodes: &[Node<Aabb>], indices: &[u32], kept: &[Aabb]) -> Option<usize> {
        // The library's checks, with the scratch they ask for.
        let mut seen = vec![0u32; Bvh::<Aabb>::seen_words(nodes.len(), indices.len())];
        bvhkit::baked::check(nodes, indices, kept, &mut seen).ok()
    }

    fn frame_box(&self, origin: DVec3, min: DVec3, max: DVec3) -> Aabb {
        // Every case's origin is finite; a frame the library refuses gives
        // the empty box, which no check accepts.
        bvhkit::LocalFrame::new(origin).map_or(Aabb::EMPTY, |f| f.aabb(min, max))
    }

    fn sphere_cast(
        &self,
        tri: &Triangle,
        centre: Vec3,
        radius: f32,
        dir: Vec3,
        t_max: f32,
    ) -> Option<f32> {
        // Every case is a valid cast; one the library refuses gives `None`.
        let cast = bvhkit::ShapeCast::sphere(centre, radius, dir, t_max).ok()?;
        bvhkit::CastTarget::cast_hit(tri, &cast)
    }

    fn area_rotation(
        &self,
        children: [Aabb; 2],
        grandchildren: [Option<[Aabb; 2]>; 2],
    ) -> Option<(usize, usize)> {
        let [l, r] = &children;
        let [gl, gr] = &grandchildren;
        let (gl, gr) = (
            gl.as_ref().map(|[a, b]| [a, b]),
            gr.as_ref().map(|[a, b]| [a, b]),
        );
        bvhkit::builders::area_rotation([l, r], [gl, gr]).map(|r| (r.down, r.up))
    }

    fn bin_index(&self, t: f32, lo: f32, scale: f32, k: usize) -> usize {
        // The textbook rule; the library reads the whole part from the bits
        // of `x + 64` instead (no saturating conversion), with the same
        // agreement between bins and partition.
        let x = ((t - lo) * scale).clamp(0.0, (k - 1) as f32);
        x as usize
    }

    fn bin_goes_left(&self, t: f32, lo: f32, scale: f32, _k: usize, boundary: usize) -> bool {
        // `floor(clamp(x)) < boundary` is `x < boundary` for a whole
        // `boundary` in `1..k`, on either side of the clamp.
        (t - lo) * scale < boundary as f32
    }

    fn aabb_overlaps(&self, a: &Aabb, b: &Aabb) -> bool {
        a.overlaps(b)
    }
    fn aabb_fit(&self, points: &[Vec3]) -> Aabb {
        Aabb::fit(points)
    }
    fn aabb_merge(&self, a: &Aabb, b: &Aabb) -> Aabb {
        a.union(b)
    }
    fn sphere_fit(&self, points: &[Vec3]) -> Sphere {
        Sphere::ritter(points)
    }
    fn sphere_merge(&self, a: &Sphere, b: &Sphere) -> Sphere {
        a.merge(b)
    }
    fn median_partition(&self, centroids: &[Vec3], indices: &mut [u32]) -> usize {
        // The box of the centroids the indices name (one node's primitives
        // in a builder), not of the whole array.
        let cb = indices.iter().fold(Aabb::EMPTY, |b, &i| {
            b.union(&Aabb::from_point(centroids[i as usize]))
        });
        let axis = cb.longest_axis();
        let mid = indices.len() / 2;
        if mid > 0 {
            indices.select_nth_unstable_by(mid, |&a, &b| {
                centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis])
            });
        }
        mid
    }

    fn descend_a(&self, a: &Node<Aabb>, b: &Node<Aabb>) -> bool {
        b.is_leaf() || (!a.is_leaf() && a.bv.volume() >= b.bv.volume())
    }

    fn informed_dfs(
        &self,
        a: &Bvh<Aabb>,
        prims_a: &[Aabb],
        b: &Bvh<Aabb>,
        prims_b: &[Aabb],
        out: &mut Vec<(u32, u32)>,
    ) {
        let query = Pairs::new(a, prims_a, b, prims_b)
            .traversal(PairTraversal::Recursive(Descent::Larger))
            .for_each(|i, j| out.push((i, j)));
        if let Err(e) = query {
            panic!("the reference traversal failed: {e}");
        }
    }

    fn stack_dfs(
        &self,
        a: &Bvh<Aabb>,
        prims_a: &[Aabb],
        b: &Bvh<Aabb>,
        prims_b: &[Aabb],
        stack: &mut [(u32, u32)],
        out: &mut Vec<(u32, u32)>,
    ) -> bool {
        let (na, nb) = (a.nodes(), b.nodes());
        let mut top = 0;
        let push = |stack: &mut [(u32, u32)], top: &mut usize, pair| match stack.get_mut(*top) {
            Some(slot) => {
                *slot = pair;
                *top += 1;
                true
            }
            None => false,
        };
        if !push(stack, &mut top, (0, 0)) {
            return false;
        }
        while top > 0 {
            top -= 1;
            let (i, j) = stack[top];
            let (x, y) = (&na[i as usize], &nb[j as usize]);
            if !x.bv.overlaps(&y.bv) {
                continue;
            }
            if x.is_leaf() && y.is_leaf() {
                for &p in a.leaf_primitives(x) {
                    for &q in b.leaf_primitives(y) {
                        if prims_a[p as usize].overlaps(&prims_b[q as usize]) {
                            out.push((p, q));
                        }
                    }
                }
                continue;
            }
            let open_a = self.descend_a(x, y);
            let Some((l, r)) = (if open_a { x.children() } else { y.children() }) else {
                return false; // a rule that opens a leaf; not this one
            };
            let pairs = if open_a {
                [(r, j), (l, j)]
            } else {
                [(i, r), (i, l)]
            };
            for pair in pairs {
                if !push(stack, &mut top, pair) {
                    return false;
                }
            }
        }
        true
    }

    fn predicted_cost(&self, counts: &Counts, model: &CostModel) -> f64 {
        model.predict(counts)
    }

    fn bottom_up_merges(&self, boxes: &[Aabb]) -> Vec<(u32, u32)> {
        // Live clusters as (id, box); O(n^2) pairs per step, n - 1 steps.
        let mut live: Vec<(u32, Aabb)> = boxes
            .iter()
            .enumerate()
            .map(|(i, b)| (i as u32, *b))
            .collect();
        let mut merges = Vec::new();
        let mut next = boxes.len() as u32;
        while live.len() > 1 {
            let (mut best, mut pair) = (f32::INFINITY, (0, 1));
            for i in 0..live.len() {
                for j in i + 1..live.len() {
                    let v = live[i].1.union(&live[j].1).volume();
                    if v < best {
                        (best, pair) = (v, (i, j));
                    }
                }
            }
            let (i, j) = pair;
            let merged = live[i].1.union(&live[j].1);
            merges.push((live[i].0, live[j].0));
            live[i] = (next, merged);
            live.swap_remove(j);
            next += 1;
        }
        merges
    }

    fn refit(&self, nodes: &mut [Node<Aabb>], indices: &[u32], prims: &[Aabb]) {
        if let Err(e) = bvhkit::builders::refit_all(nodes, indices, prims, 0.0, ()) {
            panic!("the reference refit failed: {e}");
        }
    }

    fn insertion_cost(&self, sibling: &Aabb, ancestors: &[Aabb], new: &Aabb) -> f64 {
        let area = |b: &Aabb| b.surface_area() as f64;
        area(&sibling.union(new))
            + ancestors
                .iter()
                .map(|a| area(&a.union(new)) - area(a))
                .sum::<f64>()
    }

    fn implicit_children(&self, i: usize) -> (usize, usize) {
        (2 * i + 1, 2 * i + 2)
    }

    fn implicit_parent(&self, i: usize) -> Option<usize> {
        (i > 0).then(|| (i - 1) / 2)
    }

    fn implicit_len(&self, depth: u32) -> usize {
        (1usize << (depth + 1)) - 1
    }

    fn to_preorder(&self, tree: &Bvh<Aabb>) -> Vec<(Aabb, Option<u32>)> {
        use bvhkit::layout::{PreNode, Preorder};
        let mut records = vec![PreNode::<Aabb, u32>::EMPTY; tree.node_count()];
        match Preorder::from_bvh(tree, &mut records) {
            Ok(pre) => pre
                .records()
                .iter()
                .map(|r| (r.bv, r.right().map(|i| i as u32)))
                .collect(),
            Err(e) => panic!("the reference conversion failed: {e}"),
        }
    }

    fn top_down_bytes(&self, n: usize, node_bytes: usize) -> usize {
        bvhkit::max_nodes(n) * node_bytes + n * 4
    }

    fn pair_stack_bound(&self, depth_a: usize, depth_b: usize) -> usize {
        bvhkit::query::pair_stack_bound((2, depth_a), (2, depth_b))
    }

    fn workload_ms(
        &self,
        build_ms: f64,
        query_ms: f64,
        rebuild_every_frame: bool,
        frames: usize,
    ) -> f64 {
        use bvhkit_std::advisor::{workload_ms, Motion};
        let motion = if rebuild_every_frame {
            Motion::Deforming
        } else {
            Motion::Static
        };
        workload_ms(build_ms, query_ms, motion, frames)
    }

    fn pareto_front(&self, points: &[(f64, f64)]) -> Vec<usize> {
        let keys: Vec<[f64; 2]> = points.iter().map(|&(t, e)| [t, e]).collect();
        bvhkit_std::report::pareto(&keys)
            .iter()
            .enumerate()
            .filter_map(|(i, &on)| on.then_some(i))
            .collect()
    }

    fn quantize(&self, parent: &Aabb, child: &Aabb) -> ([u8; 3], [u8; 3]) {
        let (mut lo, mut hi) = ([0u8; 3], [255u8; 3]);
        for k in 0..3 {
            let step = (parent.max[k] as f64 - parent.min[k] as f64) / 255.0;
            let (a, b) = if step > 0.0 {
                (
                    ((child.min[k] as f64 - parent.min[k] as f64) / step).floor(),
                    ((child.max[k] as f64 - parent.min[k] as f64) / step).ceil(),
                )
            } else {
                (0.0, 0.0)
            };
            let (mut l, mut h) = (a.clamp(0.0, 255.0) as u8, b.clamp(0.0, 255.0) as u8);
            while l > 0 && crate::dequantize(parent, k, l) > child.min[k] {
                l -= 1;
            }
            while l < 255 && crate::dequantize(parent, k, l + 1) <= child.min[k] {
                l += 1;
            }
            while h < 255 && crate::dequantize(parent, k, h) < child.max[k] {
                h += 1;
            }
            while h > 0 && crate::dequantize(parent, k, h - 1) >= child.max[k] {
                h -= 1;
            }
            (lo[k], hi[k]) = (l, h);
        }
        (lo, hi)
    }

    fn sah_best_boundary(&self, bins: &[(Aabb, u32)]) -> Option<usize> {
        // Written out plainly; the library's binned builder sweeps the bins
        // once from each end instead (`core/src/builders/top_down/binned.rs`).
        let side = |s: &[(Aabb, u32)]| {
            s.iter()
                .fold((Aabb::EMPTY, 0u32), |(b, n), (x, m)| (b.union(x), n + m))
        };
        let mut best: Option<(f32, usize)> = None;
        for b in 1..bins.len() {
            let ((l, nl), (r, nr)) = (side(&bins[..b]), side(&bins[b..]));
            if nl == 0 || nr == 0 {
                continue;
            }
            let cost = l.surface_area() * nl as f32 + r.surface_area() * nr as f32;
            if best.is_none_or(|(c, _)| cost < c) {
                best = Some((cost, b));
            }
        }
        best.map(|(_, b)| b)
    }

    fn dop14_fit(&self, points: &[Vec3]) -> Dop14 {
        BoundingVolume::fit(points)
    }

    fn dop14_overlaps(&self, a: &Dop14, b: &Dop14) -> bool {
        BoundingVolume::overlaps(a, b)
    }

    fn descent_open(&self, rule: Descent, d: &Decision<'_, Aabb>) -> Open {
        bvhkit::DescentRule::choose(&rule, d)
    }

    fn partition_cost(&self, criterion: Partition, l: &Aabb, nl: u32, r: &Aabb, nr: u32) -> f64 {
        // Written out in f64; the builder scores the same criteria on boxes
        // scaled into the parent's unit cube (`core/src/builders/top_down/criteria.rs`).
        let ext = |b: &Aabb| (b.max - b.min).as_dvec3().max(bvhkit::glam::DVec3::ZERO);
        let area = |b: &Aabb| {
            let e = ext(b);
            2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
        };
        let volume = |b: &Aabb| ext(b).element_product();
        let shared = (l.max.min(r.max) - l.min.max(r.min)).as_dvec3();
        let gap = (l.min - r.max).max(r.min - l.max).max_element() as f64;
        match criterion {
            Partition::Balance => (nl as f64 - nr as f64).abs(),
            Partition::SurfaceArea => nl as f64 * area(l) + nr as f64 * area(r),
            Partition::Volume => volume(l) + volume(r),
            Partition::LargerChild => volume(l).max(volume(r)),
            Partition::Overlap => shared.max(bvhkit::glam::DVec3::ZERO).element_product(),
            Partition::Separation => -gap,
            Partition::Weighted { .. } => panic!("exercise 19 is not asked for Weighted"),
        }
    }

    fn visit_order(&self, tree: &Bvh<Aabb>, breadth_first: bool) -> Vec<u32> {
        let nodes = tree.nodes();
        let mut order = Vec::with_capacity(nodes.len());
        let mut waiting = std::collections::VecDeque::new();
        if !nodes.is_empty() {
            waiting.push_back(0u32);
        }
        // A queue taken from the front is breadth-first; from the back, with
        // the right child put in first, depth-first.
        while let Some(i) = if breadth_first {
            waiting.pop_front()
        } else {
            waiting.pop_back()
        } {
            order.push(i);
            if let Some((l, r)) = nodes[i as usize].children() {
                if breadth_first {
                    waiting.extend([l, r]);
                } else {
                    waiting.extend([r, l]);
                }
            }
        }
        order
    }

    fn obb_overlaps(&self, a: &Obb, b: &Obb) -> bool {
        BoundingVolume::overlaps(a, b)
    }

    fn best_first_nearest(
        &self,
        tree: &Bvh<Aabb>,
        prims: &[Aabb],
        p: Vec3,
    ) -> Option<(u32, f32, usize)> {
        use std::cmp::Reverse;
        use std::collections::BinaryHeap;
        // Distances are non-negative, so their bit patterns order like them.
        let dist = |b: &Aabb| b.distance_squared(p).sqrt();
        let nodes = tree.nodes();
        let mut queue = BinaryHeap::new();
        if let Some(root) = nodes.first() {
            queue.push(Reverse((dist(&root.bv).to_bits(), 0u32)));
        }
        let (mut best, mut taken) = (None::<(u32, f32)>, 0);
        while let Some(Reverse((d, i))) = queue.pop() {
            if best.is_some_and(|(_, b)| f32::from_bits(d) > b) {
                break;
            }
            taken += 1;
            let node = &nodes[i as usize];
            match node.children() {
                Some((l, r)) => {
                    for c in [l, r] {
                        queue.push(Reverse((dist(&nodes[c as usize].bv).to_bits(), c)));
                    }
                }
                None => {
                    for &k in
                        &tree.indices()[node.first as usize..(node.first + node.count) as usize]
                    {
                        let d = dist(&prims[k as usize]);
                        if best.is_none_or(|(j, b)| d < b || (d == b && k < j)) {
                            best = Some((k, d));
                        }
                    }
                }
            }
        }
        best.map(|(k, d)| (k, d, taken))
    }

    fn leaf_order_bounds(&self, tree: &Bvh<Aabb>, prims: &[Triangle]) -> Vec<Aabb> {
        tree.indices()
            .iter()
            .map(|&p| prims[p as usize].bounds())
            .collect()
    }

    fn leaf_pair_candidates(
        &self,
        (ids_a, boxes_a): (&[u32], &[Aabb]),
        (ids_b, boxes_b): (&[u32], &[Aabb]),
    ) -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        for (&p, x) in ids_a.iter().zip(boxes_a) {
            for (&q, y) in ids_b.iter().zip(boxes_b) {
                if x.overlaps(y) {
                    out.push((p, q));
                }
            }
        }
        out
    }

    fn node_step(
        &self,
        n: u32,
        depth: u32,
        stop: &Stop,
        left: u32,
        weighs_counts: bool,
    ) -> NodeStep {
        if n <= stop.max_leaf_size || depth >= stop.max_depth {
            return NodeStep::Leaf;
        }
        let leaves = n.div_ceil(stop.max_leaf_size);
        let needed = u32::BITS - (leaves - 1).leading_zeros(); // ceil(log2(leaves))
        if stop.max_depth - depth <= needed {
            return NodeStep::Halve;
        }
        let smaller = left.min(n - left.min(n));
        // In u64: 100 times a side of 43 million primitives overflows u32.
        if smaller == 0 || (!weighs_counts && n >= 100 && smaller as u64 * 100 < n as u64) {
            return NodeStep::FallBack;
        }
        NodeStep::Split
    }

    fn fit_unit_costs(&self, samples: &[(u64, u64, f64)]) -> (f64, f64) {
        // Divided by t, each sample asks (Nv/t)*Cv + (Np/t)*Cp = 1: least
        // squares on the relative error is ordinary least squares on the
        // scaled rows. The same sums give every candidate's error.
        let (mut xx, mut xy, mut yy, mut x1, mut y1, mut n) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        for &(nv, np, t) in samples {
            if t <= 0.0 || !t.is_finite() {
                continue;
            }
            let (x, y) = (nv as f64 / t, np as f64 / t);
            (xx, xy, yy) = (xx + x * x, xy + x * y, yy + y * y);
            (x1, y1, n) = (x1 + x, y1 + y, n + 1.0);
        }
        let error = |cv: f64, cp: f64| {
            n - 2.0 * (cv * x1 + cp * y1) + cv * cv * xx + 2.0 * cv * cp * xy + cp * cp * yy
        };
        let det = xx * yy - xy * xy;
        if det > 1e-12 * xx * yy {
            let cv = (x1 * yy - y1 * xy) / det;
            let cp = (xx * y1 - xy * x1) / det;
            if cv >= 0.0 && cp >= 0.0 {
                return (cv, cp);
            }
        }
        let only_cv = if xx > 0.0 { (x1 / xx).max(0.0) } else { 0.0 };
        let only_cp = if yy > 0.0 { (y1 / yy).max(0.0) } else { 0.0 };
        if error(only_cv, 0.0) <= error(0.0, only_cp) {
            (only_cv, 0.0)
        } else {
            (0.0, only_cp)
        }
    }

    fn split_plane(
        &self,
        centroids: &[Vec3],
        axis: AxisRule,
        point: PointRule,
    ) -> Option<(usize, f32)> {
        if centroids.is_empty() {
            return None;
        }
        let n = centroids.len() as f64;
        let on = |k: usize| centroids.iter().map(move |c| c[k] as f64);
        let score = |k: usize| match axis {
            AxisRule::Longest => {
                let (lo, hi) = on(k).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
                    (l.min(x), h.max(x))
                });
                hi - lo
            }
            AxisRule::Variance => {
                let mean = on(k).sum::<f64>() / n;
                on(k).map(|x| (x - mean) * (x - mean)).sum::<f64>() / n
            }
        };
        let mut best = 0;
        for k in 1..3 {
            if score(k) > score(best) {
                best = k;
            }
        }
        let value = match point {
            PointRule::ObjectMedian => {
                let mut xs: Vec<f32> = centroids.iter().map(|c| c[best]).collect();
                xs.sort_by(f32::total_cmp);
                xs[xs.len() / 2]
            }
            PointRule::ObjectMean => (on(best).sum::<f64>() / n) as f32,
            PointRule::SpatialMedian => {
                let (lo, hi) = on(best).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
                    (l.min(x), h.max(x))
                });
                ((lo + hi) / 2.0) as f32
            }
        };
        Some((best, value))
    }

    fn tree_measures(&self, tree: &Bvh<Aabb>) -> TreeMeasures {
        let nodes = tree.nodes();
        let area = |b: &Aabb| {
            let e = b.max.as_dvec3() - b.min.as_dvec3();
            2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
        };
        let Some(root) = nodes.first() else {
            return TreeMeasures::default();
        };
        let root_area = area(&root.bv);
        let ratio = |b: &Aabb| {
            if root_area > 0.0 {
                area(b) / root_area
            } else {
                1.0
            }
        };
        let (mut m, mut leaves, mut depth_sum) = (TreeMeasures::default(), 0usize, 0usize);
        let mut stack = vec![(0u32, 0usize)];
        while let Some((i, depth)) = stack.pop() {
            let node = &nodes[i as usize];
            match node.children() {
                Some((l, r)) => {
                    m.sah_cost += ratio(&node.bv);
                    stack.push((l, depth + 1));
                    stack.push((r, depth + 1));
                }
                None => {
                    m.sah_cost += ratio(&node.bv) * node.count as f64;
                    m.max_depth = m.max_depth.max(depth);
                    leaves += 1;
                    depth_sum += depth;
                }
            }
        }
        m.mean_leaf_depth = depth_sum as f64 / leaves as f64;
        m
    }

    fn tri_node_records(&self, tree: &Bvh<Aabb>) -> (usize, usize) {
        let nodes = tree.nodes();
        if nodes.is_empty() {
            return (0, 0);
        }
        let (mut records, mut unused) = (0, 0);
        let mut stack = vec![(0u32, 0usize)];
        while let Some((i, depth)) = stack.pop() {
            let node = &nodes[i as usize];
            let children = node.children();
            if depth % 2 == 0 {
                records += 1;
                if children.is_none() {
                    unused += 2;
                }
            }
            if let Some((l, r)) = children {
                stack.extend([(l, depth + 1), (r, depth + 1)]);
            }
        }
        (records, unused)
    }

    fn fit_obb(&self, points: &[Vec3], axes: [Vec3; 3]) -> Obb {
        Obb::fit_with_axes(points, axes)
    }

    fn preorder_offsets(&self, tree: &Bvh<Aabb>) -> (usize, usize) {
        let nodes = tree.nodes();
        // Children come after their parent: fill subtree sizes backwards.
        let mut size = vec![1usize; nodes.len()];
        for i in (0..nodes.len()).rev() {
            if let Some((l, r)) = nodes[i].children() {
                size[i] = 1 + size[l as usize] + size[r as usize];
            }
        }
        let (mut as_built, mut smaller_first) = (0, 0);
        for node in nodes {
            if let Some((l, r)) = node.children() {
                let (l, r) = (size[l as usize], size[r as usize]);
                as_built = as_built.max(1 + l);
                smaller_first = smaller_first.max(1 + l.min(r));
            }
        }
        (as_built, smaller_first)
    }

    fn collide_objects(
        &self,
        boxes: &[Aabb],
        narrow: &mut dyn FnMut(u32, u32) -> Vec<(u32, u32)>,
    ) -> Vec<((u32, u32), (u32, u32))> {
        // Broad phase: a tree over the non-empty object boxes (an empty box
        // has infinite corners, which a builder rejects, and overlaps
        // nothing) queried against itself: each unordered pair shows up
        // twice, and every object with itself.
        let ids: Vec<u32> = (0..boxes.len() as u32)
            .filter(|&i| boxes[i as usize].min.cmple(boxes[i as usize].max).all())
            .collect();
        let kept: Vec<Aabb> = ids.iter().map(|&i| boxes[i as usize]).collect();
        let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(kept.len())];
        let mut idx = vec![0u32; kept.len()];
        let mut pairs = Vec::new();
        if let Ok(tree) = bvhkit::TopDown::default().build(&kept, &mut nodes, &mut idx) {
            let _ = Pairs::new(&tree, &kept, &tree, &kept).for_each(|a, b| {
                let (a, b) = (ids[a as usize], ids[b as usize]);
                if a < b {
                    pairs.push((a, b));
                }
            });
        }
        pairs.sort_unstable();
        // Narrow phase, pair by pair.
        let mut out = Vec::new();
        for (a, b) in pairs {
            out.extend(narrow(a, b).into_iter().map(|p| ((a, b), p)));
        }
        out
    }

    fn insertion_sibling(&self, nodes: &[DynNode<Aabb>], root: u32, new: &Aabb) -> u32 {
        // The walk of `SiblingSearch::Descent` in `core/src/builders/dynamic.rs`.
        let area = |b: &Aabb| b.surface_area() as f64;
        let mut n = root;
        while nodes[n as usize].left != NULL {
            let node = &nodes[n as usize];
            let combined = area(&node.bv.union(new));
            let here = 2.0 * combined;
            let inheritance = 2.0 * (combined - area(&node.bv));
            let child_cost = |c: u32| {
                let cb = &nodes[c as usize].bv;
                let m = area(&cb.union(new));
                inheritance
                    + if nodes[c as usize].left == NULL {
                        m
                    } else {
                        m - area(cb)
                    }
            };
            let (cl, cr) = (child_cost(node.left), child_cost(node.right));
            if here < cl && here < cr {
                break;
            }
            n = if cl <= cr { node.left } else { node.right };
        }
        n
    }

    fn insertion_build(&self, boxes: &[Aabb], order: &[u32]) -> (usize, f64) {
        let config = DynamicConfig {
            search: SiblingSearch::Descent,
            rotations: Rotations::Off,
            margin: 0.0,
        };
        let mut storage = vec![DynNode::<Aabb>::EMPTY; bvhkit::max_nodes(order.len())];
        let Ok(mut tree) = DynamicTree::new(&mut storage, config) else {
            return (0, 0.0);
        };
        for &i in order {
            if tree.insert(i, &boxes[i as usize]).is_err() {
                return (0, f64::NAN);
            }
        }
        (tree.height(), tree.area_sum())
    }

    fn ray_closest(
        &self,
        tree: &Bvh<Aabb>,
        origin: Vec3,
        dir: Vec3,
        hit: &mut dyn FnMut(u32) -> Option<f32>,
    ) -> Option<(u32, f32)> {
        use std::cmp::Reverse;
        use std::collections::BinaryHeap;
        // A node's entry distance: the library's ray test of a box (the
        // slab test in `f64`, parallel slabs without a division).
        let ray = Ray::new(origin, dir, f32::INFINITY).ok()?;
        let enter = |b: &Aabb| b.ray_hit(&ray).map(|t| (t + 0.0).to_bits());
        let nodes = tree.nodes();
        let mut queue = BinaryHeap::new();
        if let Some(t) = nodes.first().and_then(|root| enter(&root.bv)) {
            queue.push(Reverse((t, 0u32)));
        }
        let mut best = None::<(u32, f32)>;
        while let Some(Reverse((t, i))) = queue.pop() {
            if best.is_some_and(|(_, b)| f32::from_bits(t) > b) {
                break; // everything still queued is farther
            }
            let node = &nodes[i as usize];
            match node.children() {
                Some((l, r)) => {
                    for c in [l, r] {
                        if let Some(tc) = enter(&nodes[c as usize].bv) {
                            queue.push(Reverse((tc, c)));
                        }
                    }
                }
                None => {
                    let ids =
                        &tree.indices()[node.first as usize..(node.first + node.count) as usize];
                    for &k in ids {
                        if let Some(t) = hit(k) {
                            if best.is_none_or(|(j, b)| t < b || (t == b && k < j)) {
                                best = Some((k, t));
                            }
                        }
                    }
                }
            }
        }
        best
    }

    fn wide_collapse(&self, tree: &Bvh<Aabb>, node: u32) -> Vec<u32> {
        // The rule of `collapse` in `core/src/layout/mod.rs`.
        let nodes = tree.nodes();
        let Some((l, r)) = nodes[node as usize].children() else {
            return Vec::new();
        };
        let mut slots = vec![l, r];
        while slots.len() < 4 {
            let size = |k: usize| {
                let b = &nodes[slots[k] as usize].bv;
                (b.half_area(), b.extent().element_sum())
            };
            // `max_by` keeps the last of equal elements: the later slot.
            let widest = (0..slots.len())
                .filter(|&k| !nodes[slots[k] as usize].is_leaf())
                .max_by(|&x, &y| {
                    let ((ax, lx), (ay, ly)) = (size(x), size(y));
                    ax.total_cmp(&ay).then(lx.total_cmp(&ly))
                });
            let Some(k) = widest else { break };
            let Some((cl, cr)) = nodes[slots[k] as usize].children() else {
                break;
            };
            slots[k] = cl;
            slots.push(cr);
        }
        slots
    }

    fn wide_measures(&self, tree: &Bvh<Aabb>) -> (usize, usize, usize) {
        let Ok(needed) = Wide::records_needed(tree) else {
            return (0, 0, 0);
        };
        let mut records = vec![WideNode::EMPTY; needed];
        let Ok(wide) = Wide::from_bvh(tree, &mut records) else {
            return (0, 0, 0);
        };
        // Record 0 is a header holding only the root; every other record
        // is one wide internal node.
        let inner = &wide.records()[needed.min(1)..];
        let empty = inner.iter().map(|r| 4 - r.used()).sum();
        (inner.len(), wide.depth(), empty)
    }

    fn top_down_build(
        &self,
        boxes: &[Aabb],
        max_leaf: u32,
        nodes: &mut [Node<Aabb>],
        indices: &mut [u32],
    ) -> Option<usize> {
        // The library's version is `TopDown::median()`; this one writes the
        // rule of the statement out, node by node.
        let n = boxes.len();
        if n == 0 {
            return Some(0);
        }
        if nodes.len() < 2 * n - 1 || indices.len() < n {
            return None;
        }
        let centroids: Vec<Vec3> = boxes.iter().map(Aabb::center).collect();
        for (k, i) in indices[..n].iter_mut().enumerate() {
            *i = k as u32;
        }
        let mut used = 1;
        // (node, start, end) ranges of `indices` still to place.
        let mut work = vec![(0usize, 0usize, n)];
        while let Some((node, start, end)) = work.pop() {
            let bv = indices[start..end]
                .iter()
                .fold(Aabb::EMPTY, |b, &i| b.union(&boxes[i as usize]));
            if end - start <= max_leaf as usize {
                nodes[node] = Node {
                    bv,
                    first: start as u32,
                    count: (end - start) as u32,
                };
                continue;
            }
            let mid = start + self.median_partition(&centroids, &mut indices[start..end]);
            nodes[node] = Node {
                bv,
                first: used as u32,
                count: 0,
            };
            work.push((used, start, mid));
            work.push((used + 1, mid, end));
            used += 2;
        }
        Some(used)
    }

    fn short_links(&self, tree: &Bvh<Aabb>, reach: u16) -> (Vec<u16>, Vec<(u32, u32)>) {
        let nodes = tree.nodes();
        let mut links: Vec<u16> = Vec::with_capacity(nodes.len());
        let mut far = Vec::new();
        // (node, the record waiting for it as its right child).
        let mut stack = vec![(0u32, None::<usize>)];
        if nodes.is_empty() {
            stack.clear();
        }
        while let Some((n, parent)) = stack.pop() {
            let record = links.len();
            if let Some(p) = parent {
                let offset = record - p;
                links[p] = if offset <= reach as usize {
                    offset as u16
                } else {
                    far.push((p as u32, record as u32));
                    crate::ESCAPE
                };
            }
            links.push(0);
            if let Some((l, r)) = nodes[n as usize].children() {
                stack.push((r, Some(record)));
                stack.push((l, None));
            }
        }
        // A right link is found after the links of its whole left subtree.
        far.sort_unstable();
        (links, far)
    }

    fn decode_right(&self, links: &[u16], far: &[(u32, u32)], record: usize) -> usize {
        match links[record] {
            crate::ESCAPE => far
                .binary_search_by_key(&(record as u32), |&(r, _)| r)
                .map_or(usize::MAX, |k| far[k].1 as usize),
            offset => record + offset as usize,
        }
    }

    fn merged_run(&self, tree: &Bvh<Aabb>, node: u32, merge: u32) -> Option<(u32, u32)> {
        // The library's version is `run` in core/src/layout/mod.rs.
        let nodes = tree.nodes();
        let n = nodes[node as usize];
        if n.is_leaf() {
            return Some((n.first, n.count));
        }
        let (mut lo, mut hi, mut count) = (u32::MAX, 0u32, 0u64);
        let mut stack = vec![node];
        while let Some(i) = stack.pop() {
            let n = nodes[i as usize];
            match n.children() {
                Some((l, r)) => stack.extend([l, r]),
                None => {
                    count += n.count as u64;
                    if count > merge as u64 {
                        return None;
                    }
                    lo = lo.min(n.first);
                    hi = hi.max(n.first + n.count);
                }
            }
        }
        (u64::from(hi - lo) == count).then_some((lo, count as u32))
    }

    fn clip_polygon(
        &self,
        polygon: &[DVec3],
        normal: DVec3,
        offset: f64,
        out: &mut [DVec3],
    ) -> usize {
        // The library's version is `clip` in core/src/bv/polytope.rs: it
        // counts a vertex within 1e-12 of the plane as on it and may then
        // repeat it (an area does not mind), where this one is exact.
        let n = polygon.len();
        let mut m = 0;
        for i in 0..n {
            let (p, q) = (polygon[i], polygon[(i + 1) % n]);
            let (sp, sq) = (normal.dot(p) - offset, normal.dot(q) - offset);
            if sp <= 0.0 {
                out[m] = p;
                m += 1;
            }
            // Strictly on opposite sides: an end on the plane is a vertex
            // already kept (or about to be), not a crossing.
            if (sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0) {
                out[m] = p + (q - p) * (sp / (sp - sq));
                m += 1;
            }
        }
        m
    }

    fn clipped_area(&self, polygon: &[DVec3], planes: &[(DVec3, f64)]) -> f64 {
        // The library's version is `Planes::face_area` in core/src/bv/polytope.rs.
        let mut buf = [[DVec3::ZERO; crate::CLIP_CAPACITY]; 2];
        let mut len = polygon.len();
        buf[0][..len].copy_from_slice(polygon);
        for (k, &(normal, offset)) in planes.iter().enumerate() {
            let [a, b] = &mut buf;
            let (from, to) = if k % 2 == 0 { (a, b) } else { (b, a) };
            len = self.clip_polygon(&from[..len], normal, offset, to);
            if len < 3 {
                return 0.0;
            }
        }
        polygon_area(&buf[planes.len() % 2][..len])
    }

    fn relocate_piece(&self, piece: &[Node<Aabb>], start: u32, base: u32) -> Vec<Node<Aabb>> {
        // The library does this in `place` in core/src/builders/top_down/fork.rs.
        // Node k >= 1 of the piece lands on node base + k - 1.
        piece
            .iter()
            .map(|n| Node {
                first: if n.is_leaf() {
                    n.first + start
                } else {
                    base + n.first - 1
                },
                ..*n
            })
            .collect()
    }

    fn piece_bases(&self, pair: u32, left: (u32, u32), right: (u32, u32)) -> (u32, u32) {
        // Each half keeps its own root in the pair, so it has nodes - 1 below.
        if left.0 <= right.0 {
            (pair + 2, pair + 2 + (left.1 - 1))
        } else {
            (pair + 2 + (right.1 - 1), pair + 2)
        }
    }

    fn best_cut_cost(&self, tree: &Bvh<Aabb>, max_leaf_size: u32, traversal_cost: f64) -> f64 {
        if tree.node_count() == 0 {
            return 0.0;
        }
        best_cut(tree.nodes(), 0, max_leaf_size, traversal_cost).0
    }

    fn collapsed_leaves(
        &self,
        tree: &Bvh<Aabb>,
        max_leaf_size: u32,
        traversal_cost: f64,
    ) -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        if tree.node_count() > 0 {
            collect_cut(tree.nodes(), 0, max_leaf_size, traversal_cost, &mut out);
        }
        out.sort_unstable();
        out
    }

    fn box_triangle(&self, b: &Aabb, t: &Triangle) -> bool {
        bvhkit::narrow::box_triangle_intersect(b, t)
    }

    fn self_pairs(&self, tree: &Bvh<Aabb>, prims: &[Aabb], out: &mut Vec<(u32, u32)>) {
        // Boxes have no neighbours, so the default neighbour filter would
        // skip nothing; `keep_adjacent` says so. Each inner node's children
        // are walked with exercise 5's traversal.
        let query = SelfPairs::new(tree, prims)
            .keep_adjacent()
            .traversal(PairTraversal::Recursive(Descent::Larger))
            .for_each(|i, j| out.push((i, j)));
        if let Err(e) = query {
            panic!("the reference self query failed: {e}");
        }
    }

    fn closest_pair(
        &self,
        a: &Bvh<Aabb>,
        b: &Bvh<Aabb>,
        distance: &mut dyn FnMut(u32, u32) -> f64,
    ) -> Option<(u32, u32, f64)> {
        // The walk of `Distance::closest` (core/src/query/distance.rs) with
        // exercise 4's descent rule and the exact box bound: the library
        // lowers its bound by a margin against the rounding of triangle
        // distances, which box distances do not need.
        let (na, nb) = (a.nodes(), b.nodes());
        if na.is_empty() || nb.is_empty() {
            return None;
        }
        let bound = |i: u32, j: u32| {
            na[i as usize]
                .bv
                .closest_points(&nb[j as usize].bv)
                .distance_squared
        };
        let mut best: Option<(u32, u32, f64)> = None;
        let mut stack = vec![(0u32, 0u32)];
        while let Some((i, j)) = stack.pop() {
            if best.is_some_and(|(_, _, d)| bound(i, j) >= d) {
                continue; // nothing beneath can be closer than the best
            }
            let (x, y) = (&na[i as usize], &nb[j as usize]);
            let kids = if self.descend_a(x, y) {
                x.children().map(|(l, r)| [(l, j), (r, j)])
            } else {
                y.children().map(|(l, r)| [(i, l), (i, r)])
            };
            match kids {
                None => {
                    for &p in a.leaf_primitives(x) {
                        for &q in b.leaf_primitives(y) {
                            let d = distance(p, q);
                            if best.is_none_or(|(_, _, e)| d < e) {
                                best = Some((p, q, d));
                            }
                        }
                    }
                }
                Some([first, second]) => {
                    // The nearer child pair on top of the stack: pushed last.
                    let (near, far) = if bound(second.0, second.1) < bound(first.0, first.1) {
                        (second, first)
                    } else {
                        (first, second)
                    };
                    stack.extend([far, near]);
                }
            }
        }
        best
    }

    fn crossing_segment(&self, t1: &Triangle, t2: &Triangle) -> Option<[DVec3; 2]> {
        // The library's contact; out of one plane it is always a segment.
        match triangle_contact(t1, t2) {
            None => None,
            Some(Contact::Segment(ends)) => Some(ends),
            Some(Contact::Area { .. }) => {
                panic!("exercise 44 is about triangles in two planes; these lie in one")
            }
        }
    }

    fn box_penetration(&self, a: &Aabb, b: &Aabb) -> Option<(DVec3, f64)> {
        // The library's contact, without its point.
        a.penetration(b).map(|p| (p.normal, p.depth))
    }

    fn sphere_penetration(&self, a: &Sphere, b: &Sphere) -> Option<(DVec3, f64)> {
        a.penetration(b).map(|p| (p.normal, p.depth))
    }

    fn handle_is_live(&self, storage: &[DynNode<Aabb>], index: u32, generation: u32) -> bool {
        // The test `DynamicTree` applies to every handle it is given.
        storage
            .get(index as usize)
            .is_some_and(|n| n.is_live_leaf(generation))
    }

    fn release_node(&self, storage: &mut [DynNode<Aabb>], free: u32, node: u32) -> u32 {
        // What `DynamicTree::remove` does with the removed leaf's node.
        storage[node as usize] = storage[node as usize].released(free);
        node
    }

    fn triangles_within(
        &self,
        tree: &Bvh<Aabb>,
        tris: &[Triangle],
        p: Vec3,
        distance: f32,
    ) -> Vec<u32> {
        // As `Mesh::within` does it, on the tree given.
        let limit = f64::from(distance) * f64::from(distance);
        let region = Aabb::new(p - distance, p + distance);
        let mut found = Vec::new();
        let _ = tree.overlapping(tris, &region, |i| {
            if tris[i as usize].closest_point(p).distance_squared <= limit {
                found.push(i);
            }
        });
        found.sort_unstable();
        found
    }

    fn rebuild_dynamic(
        &self,
        storage: &mut [DynNode<Aabb>],
        root: u32,
        free: u32,
        scratch: &mut [u32],
    ) -> (u32, u32) {
        // As `DynamicTree::rebuild` does it: one walk collects the leaves
        // and releases the nodes above them, then a median build.
        use bvhkit::builders::NULL;
        if root == NULL {
            return (NULL, free);
        }
        let (mut free, mut found) = (free, 0);
        let mut stack = vec![root];
        while let Some(i) = stack.pop() {
            let node = storage[i as usize];
            if node.left == NULL {
                scratch[found] = i;
                found += 1;
            } else {
                stack.push(node.left);
                stack.push(node.right);
                storage[i as usize] = node.released(free);
                free = i;
            }
        }
        fn build(storage: &mut [DynNode<Aabb>], leaves: &mut [u32], free: &mut u32) -> u32 {
            if let [one] = leaves {
                return *one;
            }
            let centre = |s: &[DynNode<Aabb>], i: u32| s[i as usize].bv.center();
            let mut centres = Aabb::EMPTY;
            for &i in leaves.iter() {
                centres.grow(centre(storage, i));
            }
            let axis = centres.extent().max_position();
            leaves.sort_by(|&a, &b| {
                centre(storage, a)[axis]
                    .total_cmp(&centre(storage, b)[axis])
                    .then(a.cmp(&b))
            });
            let mid = leaves.len() / 2;
            let (lo, hi) = leaves.split_at_mut(mid);
            let left = build(storage, lo, free);
            let right = build(storage, hi, free);
            let parent = *free;
            *free = storage[parent as usize].parent;
            let (l, r) = (storage[left as usize], storage[right as usize]);
            storage[parent as usize] = DynNode {
                bv: l.bv.union(&r.bv),
                parent: NULL,
                left,
                right,
                item: 0,
                height: 1 + l.height.max(r.height),
                generation: storage[parent as usize].generation,
            };
            storage[left as usize].parent = parent;
            storage[right as usize].parent = parent;
            parent
        }
        let root = build(storage, &mut scratch[..found], &mut free);
        storage[root as usize].parent = NULL;
        (root, free)
    }
}

/// Exercise 40: `(best cost, primitives, first entry, cheaper as a leaf)`
/// of the subtree under `x`.
fn best_cut(nodes: &[Node<Aabb>], x: u32, max: u32, ct: f64) -> (f64, u32, u32, bool) {
    let n = &nodes[x as usize];
    let area = f64::from(n.bv.surface_area());
    match n.children() {
        None => (f64::from(n.count) * area, n.count, n.first, true),
        Some((l, r)) => {
            let (lc, ln, lf, _) = best_cut(nodes, l, max, ct);
            let (rc, rn, rf, _) = best_cut(nodes, r, max, ct);
            let count = ln + rn;
            let keep = ct * area + lc + rc;
            let leaf = f64::from(count) * area;
            if count <= max && leaf <= keep {
                (leaf, count, lf.min(rf), true)
            } else {
                (keep, count, lf.min(rf), false)
            }
        }
    }
}

/// Exercise 40b: the topmost nodes cheaper as leaves, below `x`.
fn collect_cut(nodes: &[Node<Aabb>], x: u32, max: u32, ct: f64, out: &mut Vec<(u32, u32)>) {
    let (_, count, first, leaf) = best_cut(nodes, x, max, ct);
    match nodes[x as usize].children() {
        Some((l, r)) if !leaf => {
            collect_cut(nodes, l, max, ct, out);
            collect_cut(nodes, r, max, ct, out);
        }
        _ => out.push((first, count)),
    }
}

/// The area of a planar polygon: half the length of the sum of the
/// triangles' cross products from its first vertex (any orientation).
pub(crate) fn polygon_area(poly: &[DVec3]) -> f64 {
    let mut twice = DVec3::ZERO;
    for i in 1..poly.len().saturating_sub(1) {
        twice += (poly[i] - poly[0]).cross(poly[i + 1] - poly[0]);
    }
    0.5 * twice.length()
}
