//! Insertion construction and the dynamic tree: random insert / remove /
//! move sequences keep the invariants and the answers, for every volume type.

use bvhkit::builders::{
    Collapse, DynNode, DynamicConfig, DynamicTree, InsertOrder, Insertion, LeafHandle, Rotations,
    SiblingSearch,
};
use bvhkit::glam::Vec3;
use bvhkit::{
    brute_force, Aabb, BoundingVolume, Bounds, Dop14, Error, Node, Obb, Same, Sphere, TopDown,
    Triangle,
};
use bvhkit_tests::*;
use proptest::prelude::*;

#[derive(Clone, Debug)]
enum Op {
    Insert(Vec3, Vec3),
    Remove(usize),
    Move(usize, Vec3),
    /// Every node above the leaves made anew (`DynamicTree::rebuild`).
    Rebuild,
    /// Up to this many leaves reinserted (`DynamicTree::optimize`).
    Optimize(usize),
}

fn op() -> impl Strategy<Value = Op> {
    let v = || {
        (-10.0f32..10.0, -10.0f32..10.0, -10.0f32..10.0).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    };
    prop_oneof![
        5 => (v(), (0.0f32..2.0, 0.0f32..2.0, 0.0f32..2.0)).prop_map(|(o, (x, y, z))| Op::Insert(o, Vec3::new(x, y, z))),
        2 => (0usize..1000).prop_map(Op::Remove),
        3 => (0usize..1000, v()).prop_map(|(i, d)| Op::Move(i, d * 0.1)),
        1 => Just(Op::Rebuild),
        1 => (0usize..80).prop_map(Op::Optimize),
    ]
}

fn config() -> impl Strategy<Value = DynamicConfig> {
    (
        any::<bool>(),
        prop_oneof![
            Just(Rotations::Off),
            Just(Rotations::Always),
            (0u32..6).prop_map(Rotations::AboveHeight),
            Just(Rotations::Area),
        ],
        prop_oneof![Just(0.0f32), 0.0f32..1.0],
    )
        .prop_map(|(bb, rotations, margin)| DynamicConfig {
            search: if bb {
                SiblingSearch::BranchAndBound
            } else {
                SiblingSearch::Descent
            },
            rotations,
            margin,
        })
}

/// Runs the operations; after each, checks the live set, node count and
/// (every few steps) the exported tree against brute force.
fn run<B: BoundingVolume>(
    cfg: DynamicConfig,
    ops: &[Op],
    other: &[Triangle],
) -> Result<(), TestCaseError> {
    let cap = 64;
    let mut storage = vec![DynNode::<B>::EMPTY; 2 * cap - 1];
    let mut tree = DynamicTree::new(&mut storage, cfg).unwrap();
    // Live objects: (item, handle, bounds); items are unique ids.
    let mut live: Vec<(u32, LeafHandle, Aabb)> = Vec::new();
    // Handles of removed objects: every operation must refuse them.
    let mut dead: Vec<LeafHandle> = Vec::new();
    let mut next_item = 0u32;
    let (no, io, _) = build::<B, _>(&TopDown::default(), other).unwrap();
    let t_other = open(&no, &io, other);
    for (step, op) in ops.iter().enumerate() {
        match op {
            Op::Insert(o, e) => {
                let b = Aabb::new(*o, *o + *e);
                match tree.insert(next_item, &b) {
                    Ok(h) => live.push((next_item, h, b)),
                    Err(Error::NodeCapacity { .. }) => prop_assert_eq!(live.len(), cap),
                    Err(e) => return Err(TestCaseError::fail(format!("insert: {e}"))),
                }
                next_item += 1;
            }
            Op::Remove(i) if !live.is_empty() => {
                let (_, h, _) = live.swap_remove(i % live.len());
                tree.remove(h).unwrap();
                dead.push(h);
            }
            Op::Move(i, d) if !live.is_empty() => {
                let k = i % live.len();
                let b = Aabb::new(live[k].2.min + *d, live[k].2.max + *d);
                match tree.update(live[k].1, &b) {
                    Ok(_) => live[k].2 = b,
                    Err(e) => return Err(TestCaseError::fail(format!("update: {e}"))),
                }
            }
            Op::Rebuild => {
                let height = tree.height();
                // Too little scratch: refused, nothing changes.
                if !live.is_empty() {
                    let mut short = vec![0u32; live.len() - 1];
                    prop_assert!(tree.rebuild(&mut short).is_err());
                    prop_assert_eq!(tree.height(), height);
                }
                let mut scratch = vec![0u32; live.len()];
                tree.rebuild(&mut scratch).unwrap();
                // Balanced: the median split gives ceil(log2 n) levels.
                let n = live.len().max(1);
                let levels = (usize::BITS - (n - 1).leading_zeros()) as usize;
                prop_assert_eq!(tree.height(), levels);
            }
            Op::Optimize(budget) => {
                let before = tree.area_sum();
                let moved = tree.optimize(*budget).unwrap();
                // Every leaf keeps its slot, so a call sees each one (and
                // the inner nodes, which may move slots as they go).
                if live.len() < 3 {
                    prop_assert_eq!(moved, 0);
                } else {
                    prop_assert!(moved <= *budget && moved >= (*budget).min(live.len()));
                }
                // An exact search puts each box back where it costs least,
                // its old place among the candidates, and area rotations
                // only shrink the area: the box tree's area never grows.
                // (Merged spheres and OBBs depend on the merge order, and
                // height rotations trade area for balance.)
                let area_only = matches!(cfg.rotations, Rotations::Off | Rotations::Area);
                if B::NAME == Aabb::NAME && cfg.search == SiblingSearch::BranchAndBound && area_only
                {
                    let after = tree.area_sum();
                    prop_assert!(after <= before * (1.0 + 1e-6), "{before} -> {after}");
                }
            }
            _ => {}
        }
        prop_assert_eq!(tree.len(), live.len());
        if let Some(&h) = dead.get(step % dead.len().max(1)) {
            // A stale handle moves and removes nothing, even where its
            // node now holds a live object.
            let far = Aabb::new(Vec3::splat(50.0), Vec3::splat(51.0));
            let stale = Err(Error::StaleHandle {
                index: h.index(),
                generation: h.generation(),
            });
            prop_assert!(!tree.contains(h));
            prop_assert_eq!(tree.update(h, &far), stale.map(|()| false));
            prop_assert_eq!(tree.remove(h), stale);
            prop_assert_eq!(tree.len(), live.len());
        }
        for &(item, h, _) in &live {
            prop_assert_eq!(tree.item(h), Ok(item));
        }
        if let Err(e) = tree.validate() {
            return Err(TestCaseError::fail(format!("after {op:?}: {e}")));
        }
        if live.is_empty() || step % 4 != 3 {
            continue;
        }
        // Export and compare with brute force over the live boxes, indexed by item.
        let mut prims = vec![Aabb::new(Vec3::splat(1e6), Vec3::splat(1e6)); next_item as usize];
        for &(item, _, b) in &live {
            prims[item as usize] = b;
        }
        let n = live.len();
        let mut nodes = vec![Node::<B>::EMPTY; 2 * n - 1];
        let mut idx = vec![0u32; n];
        let count = tree.to_bvh(&mut nodes, &mut idx).unwrap().node_count();
        prop_assert_eq!(count, 2 * n - 1);
        let mut items: Vec<u32> = idx.clone();
        items.sort_unstable();
        let mut want_items: Vec<u32> = live.iter().map(|l| l.0).collect();
        want_items.sort_unstable();
        prop_assert_eq!(&items, &want_items, "every live object exactly once");
        // Renumber: leaf position k holds object idx[k], as primitive k.
        let compact: Vec<Aabb> = idx.iter().map(|&i| prims[i as usize]).collect();
        let renum: Vec<u32> = (0..n as u32).collect();
        // `open` validates containment of every primitive and child.
        let tree_view = open(&nodes, &renum, &compact);
        let region = Aabb::new(Vec3::new(-3.0, -3.0, -3.0), Vec3::new(4.0, 2.0, 5.0));
        let mut got = Vec::new();
        tree_view
            .overlapping(&compact, &region, |i| got.push(i))
            .unwrap();
        got.sort_unstable();
        let mut want = Vec::new();
        brute_force::overlapping(&compact, &region, |i| want.push(i));
        prop_assert_eq!(got, want);
        let mut got = Vec::new();
        bvhkit::overlapping_pairs(
            &tree_view,
            &compact,
            &t_other,
            other,
            bvhkit::Descent::Larger,
            |i, j| got.push((i, j)),
        )
        .unwrap();
        got.sort_unstable();
        let mut want = Vec::new();
        brute_force::pairs(&compact, other, |i, j| want.push((i, j)));
        prop_assert_eq!(got, want);
        let mut pairs = Vec::new();
        bvhkit::overlapping_pairs(
            &tree_view,
            &compact,
            &tree_view,
            &compact,
            bvhkit::Descent::Larger,
            |i, j| pairs.push((i, j)),
        )
        .unwrap();
        let mut want_pairs = Vec::new();
        brute_force::pairs(&compact, &compact, |i, j| want_pairs.push((i, j)));
        pairs.sort_unstable();
        prop_assert_eq!(pairs, want_pairs);
        // The same questions asked of the dynamic tree itself (no export),
        // with the primitives indexed by item id.
        direct_queries(&tree, &prims, &live, other, &t_other)?;
    }
    Ok(())
}

/// Every query on a [`DynamicTree`] directly equals brute force over the
/// live objects: regions in every order, rays in both orders, nearest,
/// pairs against a built tree and against itself with every traversal.
/// `prims` is indexed by item; items not in `live` lie far away.
fn direct_queries<B: BoundingVolume>(
    tree: &DynamicTree<'_, B>,
    prims: &[Aabb],
    live: &[(u32, LeafHandle, Aabb)],
    other: &[Triangle],
    t_other: &bvhkit::Bvh<'_, B>,
) -> Result<(), TestCaseError> {
    use bvhkit::{Hierarchy, Order, Pairs, Query, Ray, RayOrder};
    let is_live = |i: u32| live.iter().any(|l| l.0 == i);
    prop_assert_eq!(tree.primitive_count(), live.len());
    let top = live.iter().map(|l| l.0).max().unwrap();
    prop_assert_eq!(tree.index_bound(), top as usize + 1);
    // A slice too short to hold the largest id is an error, not a panic.
    let short = tree.overlapping(&prims[..top as usize], &prims[0], |_| {});
    let refused = matches!(short, Err(Error::PrimitiveCountMismatch { .. }));
    prop_assert!(refused, "a short slice gave {:?}", short);
    let region = Aabb::new(Vec3::new(-3.0, -3.0, -3.0), Vec3::new(4.0, 2.0, 5.0));
    let mut want = Vec::new();
    brute_force::overlapping(prims, &region, |i| want.push(i));
    want.retain(|&i| is_live(i));
    let mut queue = vec![0u32; tree.breadth_first_queue()];
    for order in 0..3 {
        let order = match order {
            0 => Order::DepthFirst,
            1 => Order::Recursive,
            _ => Order::BreadthFirst(&mut queue),
        };
        let mut got = Vec::new();
        tree.search(prims, &region, order, (), |i| got.push(i))
            .unwrap();
        got.sort_unstable();
        prop_assert_eq!(&got, &want, "region on the dynamic tree");
    }
    // Rays and nearest: the far filler boxes are out of the ray's reach
    // and never nearest while a live box exists.
    let ray = Ray::new(
        Vec3::new(-12.0, 0.3, -0.2),
        Vec3::new(1.0, 0.05, 0.02),
        100.0,
    )
    .unwrap();
    let want = brute_force::ray_closest(prims, &ray);
    for order in [RayOrder::DepthFirst, RayOrder::BestFirst] {
        prop_assert_eq!(tree.cast_ray(prims, &ray, order, ()).unwrap(), want);
    }
    check_casts(
        tree,
        prims,
        ray.origin(),
        ray.dir(),
        0.4,
        100.0,
        "dynamic tree",
    )?;
    let probe = Vec3::new(0.5, -0.25, 1.0);
    prop_assert_eq!(
        tree.nearest(prims, probe, ()).unwrap(),
        brute_force::nearest(prims, probe)
    );
    let mut want = Vec::new();
    brute_force::pairs(prims, other, |i, j| want.push((i, j)));
    want.retain(|&(i, _)| is_live(i));
    let mut want_self = Vec::new();
    brute_force::pairs(prims, prims, |i, j| want_self.push((i, j)));
    want_self.retain(|&(i, j)| is_live(i) && is_live(j));
    for traversal in all_traversals() {
        let mut got = Vec::new();
        Pairs::new(tree, prims, t_other, other)
            .traversal(traversal)
            .for_each(|i, j| got.push((i, j)))
            .unwrap();
        got.sort_unstable();
        prop_assert_eq!(&got, &want, "dynamic against built, {:?}", traversal);
        let mut got = Vec::new();
        Pairs::new(t_other, other, tree, prims)
            .traversal(traversal)
            .for_each(|j, i| got.push((i, j)))
            .unwrap();
        got.sort_unstable();
        prop_assert_eq!(&got, &want, "built against dynamic, {:?}", traversal);
        let mut got = Vec::new();
        Pairs::new(tree, prims, tree, prims)
            .traversal(traversal)
            .for_each(|i, j| got.push((i, j)))
            .unwrap();
        got.sort_unstable();
        prop_assert_eq!(&got, &want_self, "dynamic against itself, {:?}", traversal);
        let mut got = Vec::new();
        let n = bvhkit::query::SelfPairs::new(tree, prims)
            .traversal(traversal)
            .for_each(|i, j| got.push((i, j)))
            .unwrap();
        got.sort_unstable();
        let once: Vec<_> = want_self.iter().copied().filter(|&(i, j)| i < j).collect();
        prop_assert_eq!(n, got.len());
        prop_assert_eq!(&got, &once, "dynamic self query, {:?}", traversal);
    }
    Ok(())
}

proptest! {
    #![proptest_config(proptest_config(48))]

    #[test]
    fn operation_sequences_keep_invariants_and_answers(cfg in config(), ops in prop::collection::vec(op(), 1..120), other in scene(20)) {
        run::<Aabb>(cfg, &ops, &other)?;
        run::<Sphere>(cfg, &ops, &other)?;
        run::<Obb>(cfg, &ops, &other)?;
        run::<Dop14>(cfg, &ops, &other)?;
        run::<bvhkit::ExactKdop<7>>(cfg, &ops, &other)?;
    }

    #[test]
    fn insertion_builds_match_brute_force(
        cfg in config(), order in prop_oneof![Just(InsertOrder::Given), Just(InsertOrder::Sorted), any::<u64>().prop_map(InsertOrder::Shuffled)],
        collapse in prop_oneof![Just(Collapse::None), (0u32..10, 0.0f32..4.0).prop_map(|(max_leaf_size, traversal_cost)| Collapse::Sah { max_leaf_size, traversal_cost })],
        a in scene(40), b in scene(40),
    ) {
        let builder = Insertion { config: DynamicConfig { margin: 0.0, ..cfg }, order, collapse };
        fn check<B: BoundingVolume>(builder: &Insertion, a: &[Triangle], b: &[Triangle]) -> Result<(), TestCaseError> {
            let built = |p: &[Triangle]| {
                let n = p.len();
                let mut storage = vec![DynNode::<B>::EMPTY; 2 * n - 1];
                let mut order = vec![0u32; n];
                let mut nodes = vec![Node::<B>::EMPTY; 2 * n - 1];
                let mut idx = vec![0u32; n];
                let (used, depth) = builder.build(p, &mut storage, &mut order, &mut nodes, &mut idx).map(|t| (t.node_count(), t.depth()))?;
                // A collapse leaves fewer nodes than the buffer holds.
                nodes.truncate(used);
                Ok::<_, bvhkit::Error>((nodes, idx, depth))
            };
            let (na, ia, _) = match built(a) {
                Ok(x) => x,
                Err(e) => return Err(TestCaseError::fail(format!("{e}"))),
            };
            let (nb, ib, _) = match built(b) {
                Ok(x) => x,
                Err(e) => return Err(TestCaseError::fail(format!("{e}"))),
            };
            let (ta, tb) = (open(&na, &ia, a), open(&nb, &ib, b));
            check_pairs(&ta, a, &tb, b, &Same, Bounds, &TopDown::default())
        }
        check::<Aabb>(&builder, &a, &b)?;
        check::<Sphere>(&builder, &a, &b)?;
        check::<Dop14>(&builder, &a, &b)?;
    }
}

/// Adversarial insertion orders (#19: depth is never a reason to refuse):
/// sorted collinear points, identical boxes, boxes nested ever larger,
/// exponentially spaced points and a row filled from both ends. With
/// rotations the depth stays logarithmic; with rotations off (or starting
/// above the depth limit) the tree would grow past `MAX_DEPTH`, and is
/// rebalanced instead: every object goes in, the tree stays valid and
/// queryable, and every answer equals brute force.
#[test]
fn adversarial_orders_are_never_refused_for_depth() {
    let n = 3000;
    let point = |x: f32| Aabb::from_point(Vec3::new(x, 0.0, 0.0));
    let scenes: Vec<(&str, Vec<Aabb>)> = vec![
        (
            "sorted collinear",
            (0..n)
                .map(|i| point(1.5f32.powi(i % 50) + i as f32))
                .collect(),
        ),
        ("identical", vec![Aabb::new(Vec3::ZERO, Vec3::ONE); 2000]),
        (
            "nested, growing",
            (1..=2000)
                .map(|i| Aabb::new(Vec3::splat(-(i as f32)), Vec3::splat(i as f32)))
                .collect(),
        ),
        (
            "exponential",
            (0..120).map(|i| point(1e-12 * 1.5f32.powi(i))).collect(),
        ),
        (
            "both ends",
            (0..n)
                .map(|i| point(if i % 2 == 0 { i as f32 } else { -(i as f32) }))
                .collect(),
        ),
    ];
    let mut tall = 0;
    for (name, boxes) in &scenes {
        for search in [SiblingSearch::Descent, SiblingSearch::BranchAndBound] {
            for rotations in [
                Rotations::Off,
                Rotations::AboveHeight(1000),
                Rotations::AboveHeight(24),
                Rotations::Always,
                Rotations::Area,
            ] {
                let cfg = DynamicConfig {
                    search,
                    rotations,
                    margin: 0.0,
                };
                let mut storage = vec![DynNode::<Aabb>::EMPTY; 2 * boxes.len() - 1];
                let mut tree = DynamicTree::new(&mut storage, cfg).unwrap();
                let mut handles = Vec::new();
                for (i, b) in boxes.iter().enumerate() {
                    match tree.insert(i as u32, b) {
                        Ok(h) => handles.push(h),
                        Err(e) => panic!("{name} {cfg:?}: object {i} refused: {e}"),
                    }
                    assert!(tree.height() <= bvhkit::MAX_DEPTH, "{name} {cfg:?}");
                }
                // Moves reinsert too: shift every object along the row.
                for (i, &h) in handles.iter().enumerate().step_by(7) {
                    let b = boxes[i];
                    let shift = Vec3::new(0.5, 0.0, 0.0);
                    tree.update(h, &Aabb::new(b.min + shift, b.max + shift))
                        .unwrap_or_else(|e| panic!("{name} {cfg:?}: move {i}: {e}"));
                }
                assert_eq!(tree.len(), boxes.len(), "{name} {cfg:?}");
                tree.validate().unwrap();
                if rotations == Rotations::Off && tree.height() > 40 {
                    tall += 1; // without rotations, the tree grew towards the limit
                }
                let mut moved = boxes.clone();
                for b in moved.iter_mut().step_by(7) {
                    let shift = Vec3::new(0.5, 0.0, 0.0);
                    *b = Aabb::new(b.min + shift, b.max + shift);
                }
                let mut nodes = vec![Node::<Aabb>::EMPTY; 2 * boxes.len() - 1];
                let mut idx = vec![0u32; boxes.len()];
                let bvh = tree.to_bvh(&mut nodes, &mut idx).unwrap();
                assert!(bvh.depth() <= bvhkit::MAX_DEPTH);
                let all = moved.iter().fold(Aabb::EMPTY, |a, b| a.union(b));
                for k in 0..5 {
                    let lo = all.min + all.extent() * (k as f32 / 6.0);
                    let region = Aabb::new(lo, lo + all.extent() * 0.2);
                    assert_eq!(
                        bvh.overlapping(&moved, &region, |_| {}).unwrap(),
                        brute_force::overlapping(&moved, &region, |_| {}),
                        "{name} {cfg:?}"
                    );
                }
            }
        }
    }
    // The scenes are adversarial: without rotations some trees grew to the
    // limit (3,000 sorted points make a 3,000-level chain if nothing rotates).
    assert!(tall > 0);
}

#[test]
fn bad_handles_and_bounds_are_errors() {
    let mut storage = vec![DynNode::<Aabb>::EMPTY; 5];
    let mut tree = DynamicTree::new(&mut storage, DynamicConfig::default()).unwrap();
    let h = tree.insert(0, &Aabb::new(Vec3::ZERO, Vec3::ONE)).unwrap();
    assert!(tree.insert(1, &Aabb::new(Vec3::NAN, Vec3::ONE)).is_err());
    assert!(tree.insert(1, &Aabb::new(Vec3::ONE, Vec3::ZERO)).is_err());
    let h2 = tree
        .insert(1, &Aabb::new(Vec3::ONE, Vec3::splat(2.0)))
        .unwrap();
    tree.insert(2, &Aabb::new(Vec3::ONE, Vec3::splat(3.0)))
        .unwrap();
    assert!(matches!(
        tree.insert(3, &Aabb::new(Vec3::ONE, Vec3::splat(3.0))),
        Err(Error::NodeCapacity { .. })
    ));
    // A handle of another (bigger) tree names a node this one lacks.
    let mut big = vec![DynNode::<Aabb>::EMPTY; 99];
    let mut other = DynamicTree::new(&mut big, DynamicConfig::default()).unwrap();
    let mut far = other.insert(0, &Aabb::new(Vec3::ZERO, Vec3::ONE)).unwrap();
    while far.index() < 50 {
        far = other.insert(0, &Aabb::new(Vec3::ZERO, Vec3::ONE)).unwrap();
    }
    assert!(matches!(tree.remove(far), Err(Error::StaleHandle { .. })));
    tree.remove(h).unwrap();
    assert!(tree.remove(h).is_err(), "double removal");
    assert!(
        tree.update(h, &Aabb::new(Vec3::ZERO, Vec3::ONE)).is_err(),
        "update after removal"
    );
    assert!(matches!(
        tree.insert(7, &Aabb::new(Vec3::ZERO, Vec3::splat(1e33))),
        Err(Error::CoordinateOutOfRange { primitive: 7 })
    ));
    tree.remove(h2).unwrap();
    assert_eq!(tree.len(), 1);
    assert!(DynamicTree::<Aabb>::new(
        &mut [],
        DynamicConfig {
            margin: f32::NAN,
            ..Default::default()
        }
    )
    .is_err());
}

/// A handle kept past its removal is refused by every operation, even once
/// its node holds another object: before handles carried a generation, the
/// next insert returned the same handle and `update` on the old one moved
/// the new object (`Ok(true)`), and `remove` removed it.
#[test]
fn a_stale_handle_is_refused_even_after_its_node_is_reused() {
    let unit = |x: f32| Aabb::new(Vec3::new(x, 0.0, 0.0), Vec3::new(x + 1.0, 1.0, 1.0));
    let mut storage = vec![DynNode::<Aabb>::EMPTY; 7];
    let mut tree = DynamicTree::new(&mut storage, DynamicConfig::default()).unwrap();
    let kept = tree.insert(0, &unit(0.0)).unwrap();
    let old = tree.insert(1, &unit(5.0)).unwrap();
    tree.remove(old).unwrap();
    let new = tree.insert(2, &unit(9.0)).unwrap();
    assert_eq!(new.index(), old.index(), "the freed node is reused");
    assert_ne!(new, old);
    let stale = Error::StaleHandle {
        index: old.index(),
        generation: old.generation(),
    };
    assert_eq!(tree.update(old, &unit(20.0)), Err(stale));
    assert_eq!(tree.remove(old), Err(stale));
    assert_eq!(tree.item(old), Err(stale));
    assert!(!tree.contains(old) && tree.contains(new) && tree.contains(kept));
    // The new object is untouched: still there, at its own box.
    assert_eq!(tree.len(), 2);
    assert_eq!(tree.item(new), Ok(2));
    assert_eq!(tree.fat_bounds(new), Ok(unit(9.0)));
    tree.validate().unwrap();
    // A new tree over the same storage makes every earlier handle stale.
    let mut tree = DynamicTree::new(&mut storage, DynamicConfig::default()).unwrap();
    let again = tree.insert(3, &unit(0.0)).unwrap();
    assert_eq!(again.index(), kept.index());
    assert!(tree.update(kept, &unit(1.0)).is_err() && tree.contains(again));
}

/// After removals the leaves of a dynamic tree carry ids that are not
/// `0..len`: the tree it writes must answer every query over the caller's
/// whole slice (indexed by id), refuse a slice too short for its largest id
/// with an error, and never panic (it did, in the pair walk, found by trying
/// the engine workflow: insert, remove, `to_bvh`, `Pairs::new`).
#[test]
fn a_dynamic_tree_with_removed_ids_answers_by_id_and_never_panics() {
    use bvhkit::query::{Ray, RayOrder};
    use bvhkit::Pairs;
    let tris: Vec<Triangle> = (0..10)
        .map(|i| {
            let o = Vec3::new(i as f32 * 0.6, 0.0, 0.0);
            Triangle::new(o, o + Vec3::X, o + Vec3::Y)
        })
        .collect();
    let mut storage = vec![DynNode::<Aabb>::EMPTY; 2 * tris.len()];
    let mut tree = DynamicTree::new(&mut storage, DynamicConfig::default()).unwrap();
    let handles: Vec<LeafHandle> = tris
        .iter()
        .enumerate()
        .map(|(i, t)| {
            tree.insert(i as u32, &bvhkit::Primitive::bounds(t))
                .unwrap()
        })
        .collect();
    tree.remove(handles[3]).unwrap();
    tree.remove(handles[0]).unwrap();
    let mut nodes = vec![Node::<Aabb>::EMPTY; 2 * tris.len()];
    let mut idx = vec![0u32; tris.len()];
    let bvh = tree.to_bvh(&mut nodes, &mut idx).unwrap();
    assert_eq!((bvh.primitive_count(), bvh.index_bound()), (8, 10));
    // Every query over the whole slice answers for the ids still in the tree.
    let kept = |i: u32| i != 3 && i != 0;
    let mut want = Vec::new();
    brute_force::pairs(&tris, &tris, |i, j| {
        if kept(i) {
            want.push((i, j));
        }
    });
    let mut got = Vec::new();
    Pairs::new(&bvh, &tris, &other(&tris), &tris)
        .for_each(|i, j| got.push((i, j)))
        .unwrap();
    got.sort_unstable();
    want.sort_unstable();
    assert_eq!(got, want);
    let everything = Aabb::new(Vec3::splat(-10.0), Vec3::splat(10.0));
    let mut found = Vec::new();
    bvh.overlapping(&tris, &everything, |i| found.push(i))
        .unwrap();
    found.sort_unstable();
    assert_eq!(found, [1, 2, 4, 5, 6, 7, 8, 9]);
    let ray = Ray::new(Vec3::new(0.1, 0.1, -1.0), Vec3::Z, f32::INFINITY).unwrap();
    assert_eq!(
        bvh.cast_ray(&tris, &ray, RayOrder::DepthFirst, ()).unwrap(),
        None
    );
    assert!(bvh
        .nearest(&tris, Vec3::ZERO, ())
        .unwrap()
        .is_some_and(|n| kept(n.prim)));
    // A slice too short for id 9 is an error from every query, not a panic.
    let short = &tris[..9];
    let expect = Err(Error::PrimitiveCountMismatch { tree: 10, given: 9 });
    assert_eq!(
        Pairs::new(&bvh, short, &other(&tris), &tris).count(),
        expect
    );
    assert_eq!(bvh.overlapping(short, &everything, |_| {}), expect);
    assert_eq!(
        bvh.nearest(short, Vec3::ZERO, ()).map(|_| ()),
        expect.map(|_: usize| ())
    );
    // Layouts need dense ids: converting is refused with a reason.
    let mut pre = vec![bvhkit::layout::PreNode::<Aabb, u32>::EMPTY; bvh.node_count()];
    assert!(matches!(
        bvhkit::layout::Preorder::from_bvh(&bvh, &mut pre),
        Err(Error::InvalidTree(_))
    ));
    let mut wide = vec![bvhkit::layout::WideNode::EMPTY; 64];
    assert!(matches!(
        bvhkit::layout::Wide::from_bvh(&bvh, &mut wide),
        Err(Error::InvalidTree(_))
    ));
}

#[test]
fn a_dynamic_tree_is_queried_in_place_by_id() {
    use bvhkit::{Hierarchy, Pairs, Query};
    let tris: Vec<Triangle> = (0..10)
        .map(|i| {
            let o = Vec3::new(i as f32 * 0.6, 0.0, 0.0);
            Triangle::new(o, o + Vec3::X, o + Vec3::Y)
        })
        .collect();
    let mut storage = vec![DynNode::<Aabb>::EMPTY; 2 * tris.len()];
    let mut tree = DynamicTree::new(&mut storage, DynamicConfig::default()).unwrap();
    // The empty tree answers every query with nothing.
    let everything = Aabb::new(Vec3::splat(-10.0), Vec3::splat(10.0));
    assert_eq!(tree.overlapping(&tris, &everything, |_| {}), Ok(0));
    assert_eq!(Pairs::new(&tree, &tris, &tree, &tris).count(), Ok(0));
    assert_eq!(tree.nearest(&tris, Vec3::ZERO, ()), Ok(None));
    let handles: Vec<LeafHandle> = tris
        .iter()
        .enumerate()
        .map(|(i, t)| {
            tree.insert(i as u32, &bvhkit::Primitive::bounds(t))
                .unwrap()
        })
        .collect();
    tree.remove(handles[3]).unwrap();
    tree.remove(handles[9]).unwrap(); // the largest id: the bound shrinks
    assert_eq!((tree.primitive_count(), tree.index_bound()), (8, 9));
    assert!(!tree.dense_ids());
    // Ids are the caller's: a slice longer than the largest id is fine.
    let mut found = Vec::new();
    tree.overlapping(&tris, &everything, |i| found.push(i))
        .unwrap();
    found.sort_unstable();
    assert_eq!(found, [0, 1, 2, 4, 5, 6, 7, 8]);
    // One short of the largest id is an error naming both lengths.
    assert_eq!(
        tree.overlapping(&tris[..8], &everything, |_| {}),
        Err(Error::PrimitiveCountMismatch { tree: 9, given: 8 })
    );
    let mut want = Vec::new();
    brute_force::pairs(&tris, &tris, |i, j| {
        if ![3, 9].contains(&i) {
            want.push((i, j));
        }
    });
    let mut got = Vec::new();
    Pairs::new(&tree, &tris, &other(&tris), &tris)
        .exact()
        .for_each(|i, j| got.push((i, j)))
        .unwrap();
    got.sort_unstable();
    want.retain(|&(i, j)| bvhkit::Intersects::intersects(&tris[i as usize], &tris[j as usize]));
    want.sort_unstable();
    assert_eq!(got, want);
    // Emptied again, it answers nothing; the bound is back to zero.
    for (i, &h) in handles.iter().enumerate() {
        if i != 3 && i != 9 {
            tree.remove(h).unwrap();
        }
    }
    assert_eq!((tree.node_count(), tree.index_bound()), (0, 0));
    assert_eq!(tree.overlapping(&tris, &everything, |_| {}), Ok(0));
}

/// A dense tree over the same triangles, for the other side of pair queries.
fn other(tris: &[Triangle]) -> bvhkit::Bvh<'static, Aabb> {
    let nodes =
        Box::leak(vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(tris.len())].into_boxed_slice());
    let idx = Box::leak(vec![0u32; tris.len()].into_boxed_slice());
    TopDown::sah().build(tris, nodes, idx).unwrap()
}

/// #19: insertion costs are compared in the scene's unit, so a scene 1e30
/// wide (whose areas, 1e60, overflow `f32`) or 1e-15 wide (1e-30 areas,
/// where products of extents fall to subnormals and zero) gets the tree the
/// same scene gets at unit size. In raw `f32` every candidate at 1e30 cost
/// infinity and tied, and insertion built a chain.
#[test]
fn insertion_builds_the_same_tree_at_any_scale() {
    let mut state = 11u64;
    let mut uniform = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    let unit: Vec<(Vec3, f32)> = (0..600)
        .map(|_| {
            (
                Vec3::new(uniform(), uniform(), uniform()),
                0.01 * (0.1 + uniform()),
            )
        })
        .collect();
    // Power-of-two scales: every coordinate scales exactly.
    let scaled = |s: f32| -> Vec<Aabb> {
        unit.iter()
            .map(|&(o, size)| Aabb::new(o * s, (o + Vec3::splat(size)) * s))
            .collect()
    };
    for search in [SiblingSearch::Descent, SiblingSearch::BranchAndBound] {
        let cfg = DynamicConfig {
            search,
            ..DynamicConfig::default()
        };
        let shape = |boxes: &[Aabb]| {
            let mut storage = vec![DynNode::<Aabb>::EMPTY; 2 * boxes.len() - 1];
            let mut tree = DynamicTree::new(&mut storage, cfg).unwrap();
            for (i, b) in boxes.iter().enumerate() {
                tree.insert(i as u32, b).unwrap();
            }
            let mut nodes = vec![Node::<Aabb>::EMPTY; 2 * boxes.len() - 1];
            let mut idx = vec![0u32; boxes.len()];
            let t = tree.to_bvh(&mut nodes, &mut idx).unwrap();
            let s = t.stats();
            (s.sah_cost, s.max_depth, idx.clone())
        };
        let reference = shape(&scaled(1.0));
        for s in [2f32.powi(100), 2f32.powi(-50)] {
            let got = shape(&scaled(s));
            // Not `assert_eq!` on the whole: 600 indices would be printed.
            assert_eq!(
                (got.0, got.1),
                (reference.0, reference.1),
                "{search:?} at scale {s:e}: SAH and depth"
            );
            assert!(
                got.2 == reference.2,
                "{search:?} at scale {s:e}: leaf order"
            );
        }
    }
}
