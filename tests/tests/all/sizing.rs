//! Static memory sizing, as firmware uses it: the `const fn` buffer sizes are
//! enough (and the builders refuse one entry less with an error), zero-bit
//! storage builds the same trees, and pair queries answer alike on both sides
//! of the depth where the small pair stack hands over to the large one.

use bvhkit::builders::{BottomUp, BottomUpScratch, Cluster, DynNode, Insertion};
use bvhkit::glam::Vec3;
use bvhkit::layout::{QuantizedWide, Wide};
use bvhkit::query::{pair_stack_bound, PAIR_STACK, SMALL_PAIR_STACK};
use bvhkit::{
    brute_force, max_nodes, max_nodes_for_leaves, Aabb, BoundingVolume, Dop14, Error, Node, Obb,
    PairTraversal, Pairs, Sphere, SplitPoint, TopDown, Triangle,
};
use bvhkit_tests::*;
use proptest::prelude::*;

fn zero_bits(xs: &[f32]) -> bool {
    xs.iter().all(|x| x.to_bits() == 0)
}

#[test]
fn zero_storage_constants_are_all_zero_bits() {
    let a = Node::<Aabb>::ZERO;
    assert!(zero_bits(&a.bv.min.to_array()) && zero_bits(&a.bv.max.to_array()));
    assert_eq!((a.first, a.count), (0, 0));
    let s = Node::<Sphere>::ZERO.bv;
    assert!(zero_bits(&s.center.to_array()) && s.radius.to_bits() == 0);
    let o = Node::<Obb>::ZERO.bv;
    assert!(zero_bits(&o.center.to_array()) && zero_bits(&o.half_extents.to_array()));
    assert!(o.axes.iter().all(|v| zero_bits(&v.to_array())));
    let k = Node::<Dop14>::ZERO.bv;
    assert!(zero_bits(&k.min) && zero_bits(&k.max));
}

/// The same build into storage filled with `ZERO` and with `EMPTY`.
fn same_tree_from_zero_storage<B: BoundingVolume>(cfg: &TopDown, prims: &[Triangle]) {
    let n = prims.len();
    let mut zero = vec![Node::<B>::ZERO; max_nodes(n)];
    let mut empty = vec![Node::<B>::EMPTY; max_nodes(n)];
    let (mut i1, mut i2) = (
        vec![0; cfg.index_capacity(n)],
        vec![0; cfg.index_capacity(n)],
    );
    let a = cfg.build(prims, &mut zero, &mut i1).unwrap();
    let b = cfg.build(prims, &mut empty, &mut i2).unwrap();
    assert_eq!(a.nodes(), b.nodes());
    assert_eq!(a.indices(), b.indices());
}

proptest! {
    #![proptest_config(proptest_config(24))]

    /// Exactly `max_nodes(n)` nodes and `index_capacity(n)` indices build
    /// every top-down configuration; one index fewer is an error, not a panic.
    #[test]
    fn const_sizes_are_enough_and_one_less_is_an_error(cfg in any_top_down(), prims in scene(80)) {
        let n = prims.len();
        let mut nodes = vec![Node::<Aabb>::ZERO; max_nodes(n)];
        let mut idx = vec![0u32; cfg.index_capacity(n)];
        let bvh = cfg.build(&prims, &mut nodes, &mut idx).unwrap();
        prop_assert!(bvh.node_count() <= max_nodes(n));
        let (leaves, used) = (bvh.stats().leaves, bvh.node_count());
        let (want_nodes, want_idx) = (bvh.nodes().to_vec(), bvh.indices().to_vec());
        prop_assert_eq!(
            cfg.bytes_needed::<Aabb>(n),
            max_nodes(n) * std::mem::size_of::<Node<Aabb>>() + cfg.index_capacity(n) * 4
        );
        // The wide layouts never need more than their const bound.
        prop_assert!(Wide::records_needed(&bvh).unwrap() <= Wide::max_records(n));
        prop_assert!(QuantizedWide::records_needed(&bvh).unwrap() <= QuantizedWide::max_records(n));
        let mut short = vec![0u32; cfg.index_capacity(n) - 1];
        let refused = cfg.build(&prims, &mut nodes, &mut short);
        let is_index_error = matches!(refused, Err(Error::IndexCapacity { .. }));
        prop_assert!(is_index_error);

        same_tree_from_zero_storage::<Aabb>(&cfg, &prims);
        same_tree_from_zero_storage::<Sphere>(&cfg, &prims);

        // Sized by its leaf count: exactly the nodes the tree uses, the same
        // tree again; one node fewer is an error, not a panic.
        prop_assert_eq!(used, max_nodes_for_leaves(leaves));
        let mut exact = vec![Node::<Aabb>::ZERO; max_nodes_for_leaves(leaves)];
        let again = cfg.build(&prims, &mut exact, &mut idx).unwrap();
        prop_assert_eq!(again.nodes(), &want_nodes[..]);
        prop_assert_eq!(again.indices(), &want_idx[..]);
        let mut fewer = vec![Node::<Aabb>::ZERO; max_nodes_for_leaves(leaves) - 1];
        let refused = cfg.build(&prims, &mut fewer, &mut idx);
        let is_node_error = matches!(refused, Err(Error::NodeCapacity { .. }));
        prop_assert!(is_node_error, "{:?}", refused.map(|t| t.node_count()));
    }

    /// The bottom-up and insertion builders with exactly their `scratch_len`.
    #[test]
    fn bottom_up_and_insertion_scratch_lengths_are_enough(prims in scene(60)) {
        let n = prims.len();
        let (nc, nw, nk) = BottomUp::scratch_len(n);
        let mut clusters = vec![Cluster::<Aabb>::EMPTY; nc];
        let (mut work, mut keys) = (vec![0u32; nw], vec![0u64; nk]);
        let mut scratch = BottomUpScratch { clusters: &mut clusters, work: &mut work, keys: &mut keys };
        let mut nodes = vec![Node::<Aabb>::ZERO; max_nodes(n)];
        let mut idx = vec![0u32; n];
        let t = BottomUp::default().build(&prims, &mut nodes, &mut idx, &mut scratch).unwrap();
        prop_assert_eq!(t.primitive_count(), n);

        let (ns, no) = Insertion::scratch_len(n);
        let (mut storage, mut order) = (vec![DynNode::<Aabb>::EMPTY; ns], vec![0u32; no]);
        let t = Insertion::default().build(&prims, &mut storage, &mut order, &mut nodes, &mut idx).unwrap();
        prop_assert_eq!(t.primitive_count(), n);
        if n > 1 {
            let mut short = vec![DynNode::<Aabb>::EMPTY; ns - 1];
            let refused = Insertion::default().build(&prims, &mut short, &mut order, &mut nodes, &mut idx);
            let is_node_error = matches!(refused, Err(Error::NodeCapacity { .. }));
            prop_assert!(is_node_error);
        }
    }
}

proptest! {
    #![proptest_config(proptest_config(32))]

    /// Every buffer sized by one `Capacity::for_primitives(n)` and nothing
    /// else: each builder, layout, check and bake fits in it.
    #[test]
    fn one_capacity_sizes_every_buffer(prims in scene(60), leaf in 1u32..5) {
        let n = prims.len();
        let cap = bvhkit::Capacity::for_primitives(n);
        prop_assert_eq!(cap.primitives, n);
        let mut nodes = vec![Node::<Aabb>::ZERO; cap.nodes];
        let mut idx = vec![0u32; cap.indices];
        let mut sweep_idx = vec![0u32; cap.sweep_indices];
        let sweep = TopDown { split: SplitPoint::Sweep, ..TopDown::default() };
        sweep.build(&prims, &mut nodes, &mut sweep_idx)?;
        let (c, w, k) = cap.bottom_up;
        let mut clusters = vec![Cluster::<Aabb>::EMPTY; c];
        let (mut work, mut keys) = (vec![0u32; w], vec![0u64; k]);
        let mut scratch = BottomUpScratch { clusters: &mut clusters, work: &mut work, keys: &mut keys };
        BottomUp::default().build(&prims, &mut nodes, &mut idx, &mut scratch)?;
        let (s, o) = cap.insertion;
        let (mut storage, mut order) = (vec![DynNode::<Aabb>::EMPTY; s], vec![0u32; o]);
        Insertion::default().build(&prims, &mut storage, &mut order, &mut nodes, &mut idx)?;
        let mut dynamic = vec![DynNode::<Aabb>::EMPTY; cap.dynamic_nodes];
        let mut tree = bvhkit::builders::DynamicTree::new(&mut dynamic, Default::default())?;
        for (i, t) in prims.iter().enumerate() {
            tree.insert(i as u32, &bvhkit::Primitive::bounds(t))?;
        }

        let mut kept = vec![Aabb::ZERO; cap.leaf_bounds];
        let t = TopDown::default().with_max_leaf_size(leaf).build(&prims, &mut nodes, &mut idx)?;
        let mut wide = vec![bvhkit::layout::WideNode::ZERO; cap.wide_records];
        Wide::from_bvh(&t, &mut wide)?;
        let mut quant = vec![bvhkit::layout::QuantNode::ZERO; cap.quantized_records];
        QuantizedWide::from_bvh(&t, &mut quant)?;
        let mut pre = vec![bvhkit::layout::PreNode::<Aabb, u32>::EMPTY; cap.nodes];
        bvhkit::layout::Preorder::from_bvh(&t, &mut pre)?;
        let mut seen = vec![0u32; cap.validate_words];
        t.validate(&prims, &mut seen)?;
        let mut baked = vec![0u8; cap.baked_bytes];
        t.bake(&mut baked)?;
        let t = t.with_leaf_bounds(&prims, &mut kept)?;
        let mut baked = vec![0u8; cap.baked_bytes_with_bounds];
        t.bake(&mut baked)?;
    }
}

#[test]
fn pair_stack_bound_of_binary_trees_is_both_depths_plus_the_smaller() {
    for da in 0..70 {
        for db in 0..70 {
            assert_eq!(pair_stack_bound((2, da), (2, db)), da + db + da.min(db) + 1);
        }
    }
    // The small stack serves two trees up to 22 deep; the large one 64.
    assert!(pair_stack_bound((2, 22), (2, 22)) <= SMALL_PAIR_STACK);
    assert!(pair_stack_bound((2, 23), (2, 23)) > SMALL_PAIR_STACK);
    assert!(pair_stack_bound((2, 64), (2, 64)) <= PAIR_STACK);
}

/// Triangles spaced `3^i` apart: a spatial-median split peels one off per
/// level, so the tree is as deep as the count allows.
fn chain(n: usize, shift: f32) -> Vec<Triangle> {
    (0..n)
        .map(|i| {
            let p = Vec3::new(3f32.powi(i as i32) + shift, 0.0, 0.0);
            Triangle::new(p, p + Vec3::X * 0.1, p + Vec3::Y * 0.1)
        })
        .collect()
}

/// Trees on both sides of the small stack's limit (depth 16) answer every
/// stack traversal like brute force.
#[test]
fn pair_queries_across_the_small_stack_limit_match_brute_force() {
    let cfg = TopDown {
        split: SplitPoint::SpatialMedian,
        ..TopDown::median()
    }
    .with_max_leaf_size(1);
    let mut depths = Vec::new();
    for n in [12, 20, 23, 24, 26, 30] {
        let (a, b) = (chain(n, 0.0), chain(n, 0.05));
        let mut na = vec![Node::<Aabb>::ZERO; max_nodes(n)];
        let mut nb = vec![Node::<Aabb>::ZERO; max_nodes(n)];
        let (mut ia, mut ib) = (vec![0u32; n], vec![0u32; n]);
        let ta = cfg.build(&a, &mut na, &mut ia).unwrap();
        let tb = cfg.build(&b, &mut nb, &mut ib).unwrap();
        depths.push(ta.depth().min(tb.depth()));
        let want = brute_force::pairs(&a, &b, |_, _| {});
        assert!(want > 0);
        for t in [
            PairTraversal::default(),
            PairTraversal::SIMULTANEOUS,
            PairTraversal::Stack(bvhkit::Descent::AFirst),
        ] {
            let got = Pairs::new(&ta, &a, &tb, &b).traversal(t).count().unwrap();
            assert_eq!(got, want, "n = {n}, depth {}, {}", ta.depth(), t.name());
        }
    }
    // Both sides of the limit were exercised.
    assert!(
        depths.iter().any(|&d| d <= 22) && depths.iter().any(|&d| d >= 23),
        "{depths:?}"
    );
}

/// Found by the property test above on a CI run: two primitives split into
/// two leaves need two wide records (the header holding the root, and the
/// root's record), where `max_records(2)` said 1. From three primitives on,
/// `n - 1` holds: a record that opens an inner child absorbs two inner
/// nodes, and only a root whose children are both leaves absorbs one.
#[test]
fn two_primitives_in_two_leaves_fit_the_wide_bound() {
    let zero = Triangle::new(Vec3::ZERO, Vec3::ZERO, Vec3::ZERO);
    let apart = |x: f32| Triangle::new(Vec3::X * x, Vec3::X * x + Vec3::Y, Vec3::X * x + Vec3::Z);
    for prims in [vec![zero, zero], vec![apart(0.0), apart(5.0)]] {
        for n in 1..=prims.len() {
            let cfg = TopDown::median().with_max_leaf_size(1);
            let mut nodes = vec![Node::<Aabb>::ZERO; max_nodes(n)];
            let mut idx = vec![0u32; cfg.index_capacity(n)];
            let bvh = cfg.build(&prims[..n], &mut nodes, &mut idx).unwrap();
            let (wide, quantized) = (
                Wide::records_needed(&bvh).unwrap(),
                QuantizedWide::records_needed(&bvh).unwrap(),
            );
            assert!(wide <= Wide::max_records(n), "{n}: {wide} wide records");
            assert!(
                quantized <= QuantizedWide::max_records(n),
                "{n}: {quantized}"
            );
        }
    }
}
