//! An empty scene is not bad input: every builder builds the empty tree
//! (no nodes), every layout converts it, and every query on it answers with
//! nothing and no error, including a pair query of an empty tree against a
//! full one, the collision system with empty objects, refits and validation.

use bvhkit::builders::{
    refit_all, BottomUp, DynNode, DynamicConfig, DynamicTree, Insertion, Method, Refit, PRESETS,
};
use bvhkit::collision::{collide, object_pairs, world_bounds, BroadPhase, Object};
use bvhkit::glam::Vec3;
use bvhkit::layout::{
    to_bvh, Implicit, PreNode, Preorder, QuantNode, QuantizedWide, Slot, TriNode, TriNodes, Wide,
    WideNode,
};
use bvhkit::{
    Aabb, BoundingVolume, Bvh, Counts, Dop14, Hierarchy, Node, Obb, Order, PairTraversal, Pairs,
    Query, Ray, RayOrder, Rigid, Sphere, TopDown, Triangle,
};
use bvhkit_tests::*;

const NONE: [Triangle; 0] = [];

fn some_triangles() -> Vec<Triangle> {
    (0..20)
        .map(|i| {
            let o = Vec3::new(i as f32 * 0.5, 0.0, 0.0);
            Triangle::new(o, o + Vec3::X, o + Vec3::Y)
        })
        .collect()
}

/// Every query of one hierarchy `h` over no primitives answers with nothing,
/// and a pair query against the full tree `full` (both ways round, every
/// traversal, same frame and moved) finds no pair.
fn check_queries_answer_nothing<H, F>(h: &H, full: &F, prims: &[Triangle], name: &str)
where
    H: Hierarchy,
    F: Hierarchy<Bv = H::Bv>,
{
    assert!(h.is_empty(), "{name}");
    assert_eq!(
        (h.node_count(), h.primitive_count(), h.depth()),
        (0, 0, 0),
        "{name}"
    );
    let everywhere = Aabb::new(Vec3::splat(-1e6), Vec3::splat(1e6));
    let mut queue = [0u32; 8];
    for order in [
        Order::DepthFirst,
        Order::Recursive,
        Order::BreadthFirst(&mut queue),
    ] {
        let mut counts = Counts::default();
        let found = h
            .search(&NONE, &everywhere, order, &mut counts, |_| {
                panic!("{name}: a primitive from nowhere")
            })
            .unwrap();
        assert_eq!((found, counts), (0, Counts::default()), "{name}");
    }
    assert_eq!(h.overlapping(&NONE, &everywhere, |_| ()).unwrap(), 0);
    let ray = Ray::new(Vec3::new(-10.0, 0.2, 0.2), Vec3::X, f32::INFINITY).unwrap();
    for order in [RayOrder::DepthFirst, RayOrder::BestFirst] {
        assert_eq!(h.cast_ray(&NONE, &ray, order, ()).unwrap(), None, "{name}");
    }
    assert_eq!(h.ray_hits_any(&NONE, &ray, ()).unwrap(), None, "{name}");
    let ball = bvhkit::ShapeCast::sphere(Vec3::ZERO, 1.0, Vec3::X, f32::INFINITY).unwrap();
    for order in [RayOrder::DepthFirst, RayOrder::BestFirst] {
        assert_eq!(
            h.cast_shape(&NONE, &ball, order, ()).unwrap(),
            None,
            "{name}"
        );
    }
    assert_eq!(h.shape_hits_any(&NONE, &ball, ()).unwrap(), None, "{name}");
    assert_eq!(h.nearest(&NONE, Vec3::ZERO, ()).unwrap(), None, "{name}");
    // A bad query point is still an error on the empty tree: the caller's
    // mistake does not depend on the scene.
    assert!(h.nearest(&NONE, Vec3::NAN, ()).is_err(), "{name}");
    // The primitive count is still checked.
    assert!(h.nearest(&prims[..1], Vec3::ZERO, ()).is_err(), "{name}");

    let moved = Rigid::new(
        bvhkit::glam::Quat::from_rotation_z(0.3),
        Vec3::new(0.1, 0.0, 0.0),
    )
    .unwrap();
    for traversal in all_traversals() {
        let with_h_first = || Pairs::new(h, &NONE, full, prims).traversal(traversal);
        let with_h_second = || Pairs::new(full, prims, h, &NONE).traversal(traversal);
        let mut counts = Counts::default();
        assert_eq!(
            with_h_first().counted(&mut counts).count().unwrap(),
            0,
            "{name}"
        );
        assert_eq!(counts, Counts::default(), "{name}: work on an empty tree");
        assert_eq!(with_h_second().exact().first().unwrap(), None, "{name}");
        assert_eq!(
            with_h_first().in_frame(moved).exact().count().unwrap(),
            0,
            "{name}"
        );
        assert_eq!(
            with_h_second()
                .in_frame(moved)
                .for_each(|_, _| panic!("{name}: a pair from nowhere"))
                .unwrap(),
            0
        );
    }
}

/// The empty canonical tree of volume `B`, converted to every layout; all of
/// them answer with nothing.
fn check_volume<B: BoundingVolume>(name: &str) {
    let prims = some_triangles();
    let (full_nodes, full_idx, full_depth) = build::<B, _>(&TopDown::sah(), &prims).unwrap();
    let full = Bvh::from_raw_parts(&full_nodes, &full_idx, full_depth);

    let empty: Bvh<B> = TopDown::sah().build(&NONE, &mut [], &mut []).unwrap();
    assert!(empty.root().is_none());
    assert_eq!(empty.stats(), bvhkit::TreeStats::default());
    let mut seen = [0u32; 1];
    empty.validate(&NONE, &mut seen).unwrap();
    Bvh::from_parts(&[] as &[Node<B>], &[], &NONE, &mut seen).unwrap();
    check_queries_answer_nothing(&empty, &full, &prims, name);

    assert_eq!(Implicit::slots_needed(&empty).unwrap(), 0);
    let implicit = Implicit::from_bvh(&empty, &mut [] as &mut [Slot<B>]).unwrap();
    assert_eq!(implicit.unused(), 0);
    check_queries_answer_nothing(&implicit, &full, &prims, name);

    let pre32 = Preorder::<B, u32>::from_bvh(&empty, &mut [] as &mut [PreNode<B, u32>]).unwrap();
    check_queries_answer_nothing(&pre32, &full, &prims, name);
    let pre16 = Preorder::<B, u16>::from_bvh(&empty, &mut [] as &mut [PreNode<B, u16>]).unwrap();
    check_queries_answer_nothing(&pre16, &full, &prims, name);

    assert_eq!(TriNodes::records_needed(&empty).unwrap(), 0);
    let tri = TriNodes::from_bvh(&empty, &mut [] as &mut [TriNode<B>]).unwrap();
    assert_eq!(tri.fill(), 1.0);
    check_queries_answer_nothing(&tri, &full, &prims, name);

    // Back to canonical from any layout: still the empty tree.
    let back = to_bvh(&pre16, &mut [] as &mut [Node<B>], &mut []).unwrap();
    assert!(back.is_empty());
}

#[test]
fn every_volume_and_binary_layout_answers_nothing() {
    check_volume::<Aabb>("aabb");
    check_volume::<Sphere>("sphere");
    check_volume::<Obb>("obb");
    check_volume::<Dop14>("14-dop");
}

#[test]
fn wide_layouts_answer_nothing() {
    let prims = some_triangles();
    let (nodes, idx, depth) = build::<Aabb, _>(&TopDown::sah(), &prims).unwrap();
    let full = Bvh::from_raw_parts(&nodes, &idx, depth);
    let (mut wide_full, mut quant_full) = (
        vec![WideNode::EMPTY; Wide::records_needed(&full).unwrap()],
        vec![QuantNode::EMPTY; QuantizedWide::records_needed(&full).unwrap()],
    );
    let wide_full = Wide::from_bvh(&full, &mut wide_full).unwrap();
    let quant_full = QuantizedWide::from_bvh(&full, &mut quant_full).unwrap();

    let empty: Bvh<Aabb> = TopDown::sah().build(&NONE, &mut [], &mut []).unwrap();
    assert_eq!(Wide::records_needed(&empty).unwrap(), 0);
    assert_eq!(QuantizedWide::records_needed(&empty).unwrap(), 0);
    let wide = Wide::from_bvh(&empty, &mut []).unwrap();
    let quant = QuantizedWide::from_bvh(&empty, &mut []).unwrap();
    assert!(wide.records().is_empty() && quant.records().is_empty());
    check_queries_answer_nothing(&wide, &wide_full, &prims, "wide");
    check_queries_answer_nothing(&quant, &quant_full, &prims, "quantized");
    check_queries_answer_nothing(&wide, &full, &prims, "wide vs canonical");
    let back = to_bvh(&quant, &mut [], &mut []).unwrap();
    assert!(back.is_empty());
}

/// Every builder of the library: the top-down presets (plain and cached),
/// PLOC and the exhaustive bottom-up build, both insertion orders, and the
/// dynamic tree with nothing in it (or everything removed again).
#[test]
fn every_builder_builds_the_empty_tree() {
    for preset in PRESETS {
        let t: Bvh<Aabb> = preset.builder.build(&NONE, &mut [], &mut []).unwrap();
        assert!(t.is_empty(), "{}", preset.name);
        let t: Bvh<Aabb> = preset
            .builder
            .build_cached(&NONE, &mut [], &mut [], &mut [])
            .unwrap();
        assert!(t.is_empty(), "{} cached", preset.name);
    }
    for method in [Method::Exhaustive, Method::Ploc { radius: 16 }] {
        let cfg = BottomUp {
            method,
            ..BottomUp::default()
        };
        let (nodes, idx, depth) = build_bottom_up::<Aabb, Triangle>(&cfg, &NONE).unwrap();
        assert_eq!((nodes.len(), idx.len(), depth), (0, 0, 0), "{method:?}");
    }
    for insertion in [
        Insertion::default(),
        Insertion {
            order: bvhkit::builders::InsertOrder::Sorted,
            ..Insertion::default()
        },
    ] {
        let t: Bvh<Aabb> = insertion
            .build(&NONE, &mut [], &mut [], &mut [], &mut [])
            .unwrap();
        assert!(t.is_empty(), "{insertion:?}");
    }

    let mut storage = vec![DynNode::<Aabb>::EMPTY; 8];
    let mut tree = DynamicTree::new(&mut storage, DynamicConfig::default()).unwrap();
    assert!(tree.to_bvh(&mut [], &mut []).unwrap().is_empty());
    let leaf = tree.insert(0, &Aabb::new(Vec3::ZERO, Vec3::ONE)).unwrap();
    tree.remove(leaf).unwrap();
    assert!(tree.is_empty());
    assert!(tree.to_bvh(&mut [], &mut []).unwrap().is_empty());
}

#[test]
fn refits_of_the_empty_tree_do_nothing() {
    let mut nodes: [Node<Aabb>; 0] = [];
    assert_eq!(refit_all(&mut nodes, &[], &NONE, 0.1, ()).unwrap(), 0);
    let (mut parents, mut leaf_of) = ([0u32; 0], [0u32; 0]);
    let refit = Refit::new(&nodes, &[], &mut parents, &mut leaf_of).unwrap();
    assert_eq!(
        refit.moved(&mut nodes, &[], &NONE, &[], 0.1, ()).unwrap(),
        0
    );
    // Moving a primitive the tree does not hold is the caller's mistake.
    let one = some_triangles();
    assert!(refit.moved(&mut nodes, &[], &one, &[0], 0.1, ()).is_err());
}

/// The collision system with empty objects: they have no world box, pair
/// with nothing, and leave the contacts of the other objects as they were.
#[test]
fn empty_objects_touch_nothing() {
    let prims = some_triangles();
    let (nodes, idx, depth) = build::<Aabb, _>(&TopDown::sah(), &prims).unwrap();
    let full = Bvh::from_raw_parts(&nodes, &idx, depth);
    let empty: Bvh<Aabb> = TopDown::sah().build(&NONE, &mut [], &mut []).unwrap();
    let none: &[Triangle] = &NONE;
    let object = |tree, prims, x: f32| Object {
        tree,
        prims,
        pose: Rigid::translation(Vec3::new(x, 0.0, 0.0)).unwrap(),
    };
    // Two full objects that touch, with empty objects at the same place.
    let scenes = [
        vec![],
        vec![object(&empty, none, 0.0)],
        vec![object(&empty, none, 0.0), object(&empty, none, 0.0)],
        vec![object(&full, &prims, 0.0), object(&full, &prims, 0.25)],
        vec![
            object(&empty, none, 0.0),
            object(&full, &prims, 0.0),
            object(&empty, none, 0.1),
            object(&full, &prims, 0.25),
            object(&empty, none, 0.2),
        ],
    ];
    let mut found = Vec::new();
    for objects in &scenes {
        let n = objects.len();
        let (mut boxes, mut bnodes, mut bidx) = (
            vec![Aabb::EMPTY; n],
            vec![Node::EMPTY; bvhkit::max_nodes(n)],
            vec![0u32; n],
        );
        let mut scratch = BroadPhase {
            boxes: &mut boxes,
            nodes: &mut bnodes,
            indices: &mut bidx,
        };
        let mut broad = Vec::new();
        object_pairs(objects, &mut scratch, |a, b| broad.push((a, b))).unwrap();
        let mut contacts = Vec::new();
        collide(objects, &mut scratch, PairTraversal::default(), |c| {
            contacts.push(c)
        })
        .unwrap();
        let mut want = Vec::new();
        bvhkit::brute_force::contacts(objects, |c| want.push(c));
        contacts.sort();
        want.sort();
        assert_eq!(contacts, want);
        for o in objects {
            assert_eq!(world_bounds(o).is_none(), o.tree.is_empty());
        }
        for &(a, b) in &broad {
            assert!(!objects[a as usize].tree.is_empty() && !objects[b as usize].tree.is_empty());
        }
        if n == 5 {
            assert_eq!(broad, [(1, 3)]);
        }
        found.push(contacts);
    }
    // The same contacts with and without the empty objects (ids shifted).
    assert!(found[..3].iter().all(|c| c.is_empty()));
    assert!(!found[3].is_empty());
    let shifted: Vec<_> = found[3]
        .iter()
        .map(|c| bvhkit::collision::Contact {
            objects: (1, 3),
            prims: c.prims,
        })
        .collect();
    assert_eq!(found[4], shifted);
}
