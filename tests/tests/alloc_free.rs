//! Proof that building and querying never touch the heap.
//!
//! A `harness = false` test binary with a counting global allocator: the count
//! is read before and after each build/query; any difference is a failure.
//! (Inside the normal test harness other threads allocate, so a global counter
//! would be unreliable there.)

use bvhkit::builders::{
    refit_all, BottomUp, BottomUpScratch, Cluster, DynNode, DynamicConfig, DynamicTree,
    InsertOrder, Insertion, LeafHandle, MergeMetric, Refit, Rotations, SiblingSearch,
};
use bvhkit::collision::{collide, BroadPhase, Object};
use bvhkit::glam::{Quat, Vec3};
use bvhkit::{
    overlapping_pairs, Aabb, BoundingVolume, Bvh, Collector, Counts, DepthSwitch, Descent, Dop14,
    Dop26, Node, Obb, Order, PairTraversal, Pairs, Primitive, Ray, RayOrder, Rigid, Sphere,
    TopDown, Triangle,
};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;
static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn count<R>(f: impl FnOnce() -> R) -> (R, usize) {
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    let r = f();
    (r, ALLOCATIONS.load(Ordering::SeqCst) - before)
}

fn grid(n: usize, shift: f32) -> Vec<Triangle> {
    (0..n)
        .map(|i| {
            let o = Vec3::new(
                (i % 17) as f32,
                (i / 17 % 13) as f32 + shift,
                (i / 221) as f32,
            );
            Triangle::new(
                o,
                o + Vec3::new(1.2, 0.1, 0.0),
                o + Vec3::new(0.0, 1.1, 0.3),
            )
        })
        .collect()
}

const CONFIGS: [(&str, TopDown); 4] = [
    ("sah", TopDown::sah()),
    ("sah-sweep", TopDown::sah_sweep()),
    ("median", TopDown::median()),
    (
        "variance-mean-volume",
        TopDown {
            partition: bvhkit::Partition::Volume,
            axis: bvhkit::AxisChoice::Variance,
            split: bvhkit::SplitPoint::ObjectMean,
            ..TopDown::sah()
        },
    ),
];

fn check<B: BoundingVolume + Send + Sync>(failures: &mut Vec<String>) {
    let a = grid(500, 0.0);
    let b = grid(400, 0.4);
    for (name, cfg) in CONFIGS {
        // Storage is allocated here, outside the measured regions.
        let mut na = vec![Node::<B>::EMPTY; bvhkit::max_nodes(a.len())];
        let mut nb = vec![Node::<B>::EMPTY; bvhkit::max_nodes(b.len())];
        let mut ia = vec![0u32; cfg.index_capacity(a.len())];
        let mut ib = vec![0u32; cfg.index_capacity(b.len())];
        let mut out = vec![(0u32, 0u32); 100_000];
        let mut cache = vec![bvhkit::builders::PrimitiveRef::EMPTY; a.len()];
        let mut hits = vec![0u32; 1000];
        let mut queue = vec![0u32; bvhkit::max_nodes(a.len())];
        let mut objects_scratch = (
            vec![Aabb::EMPTY; 3],
            vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(3)],
            vec![0u32; 3],
        );
        let (bn, bw, bk) = BottomUp::scratch_len(a.len());
        let mut clusters = vec![Cluster::<B>::EMPTY; bn];
        let (mut work, mut keys) = (vec![0u32; bw], vec![0u64; bk]);
        let mut bu_nodes = vec![Node::<B>::EMPTY; bvhkit::max_nodes(a.len())];
        let mut bu_idx = vec![0u32; a.len()];
        let mut small = vec![Node::<B>::EMPTY; bvhkit::max_nodes(60)];
        let mut small_idx = vec![0u32; 60];
        let mut forked_nodes = vec![Node::<B>::EMPTY; bvhkit::max_nodes(a.len())];
        let mut forked_scratch = forked_nodes.clone();
        let mut forked_idx = vec![0u32; cfg.index_capacity(a.len())];
        let mut forked_cache = cache.clone();
        let (trees, allocs) = count(|| {
            let forked = cfg
                .build_cached_forked(
                    &a,
                    &mut forked_nodes,
                    &mut forked_idx,
                    &mut forked_cache,
                    &mut forked_scratch,
                    &bvhkit::builders::InOrder { grain: 8 },
                )
                .unwrap();
            assert!(forked.node_count() > 0);
            let ta = cfg.build_cached(&a, &mut na, &mut ia, &mut cache).unwrap();
            let tb = cfg.build(&b, &mut nb, &mut ib).unwrap();
            let mut scratch = BottomUpScratch {
                clusters: &mut clusters,
                work: &mut work,
                keys: &mut keys,
            };
            let ploc = BottomUp::default()
                .build(&a, &mut bu_nodes, &mut bu_idx, &mut scratch)
                .unwrap();
            let exhaustive = BottomUp::exhaustive(MergeMetric::Volume)
                .build(&a[..60], &mut small, &mut small_idx, &mut scratch)
                .unwrap();
            assert!(ploc.node_count() > 0 && exhaustive.node_count() > 0);
            (ta, tb)
        });
        if allocs != 0 {
            failures.push(format!(
                "{} {name}: build allocated {allocs} times",
                B::NAME
            ));
        }
        // Refits of a separate copy of tree A's storage, after a motion.
        let mut rn = trees.0.nodes().to_vec();
        let ri = trees.0.indices().to_vec();
        let used = rn.len();
        let moved: Vec<Triangle> = a
            .iter()
            .map(|t| t.translated(Vec3::new(0.3, 0.0, 0.1)))
            .collect();
        let (mut parents, mut leaf_of) = (vec![0u32; used], vec![0u32; a.len()]);
        let ids: Vec<u32> = (0..a.len() as u32).step_by(3).collect();
        let (_, allocs) = count(|| {
            refit_all(&mut rn, &ri, &moved, 0.05, ()).unwrap();
            let refit = Refit::new(&rn, &ri, &mut parents, &mut leaf_of).unwrap();
            refit.moved(&mut rn, &ri, &a, &ids, 0.0, ()).unwrap();
        });
        if allocs != 0 {
            failures.push(format!(
                "{} {name}: refit allocated {allocs} times",
                B::NAME
            ));
        }
        // Insertion builds and dynamic-tree operations.
        let mut storage = vec![DynNode::<B>::EMPTY; bvhkit::max_nodes(a.len())];
        let mut order = vec![0u32; a.len()];
        let mut ins_nodes = vec![Node::<B>::EMPTY; bvhkit::max_nodes(a.len())];
        let mut ins_idx = vec![0u32; a.len()];
        let (_, allocs) = count(|| {
            for search in [SiblingSearch::Descent, SiblingSearch::BranchAndBound] {
                let builder = Insertion {
                    config: DynamicConfig {
                        search,
                        ..DynamicConfig::default()
                    },
                    order: InsertOrder::Sorted,
                    ..Insertion::default()
                };
                builder
                    .build(&a, &mut storage, &mut order, &mut ins_nodes, &mut ins_idx)
                    .unwrap();
            }
            let mut tree = DynamicTree::new(
                &mut storage,
                DynamicConfig {
                    margin: 0.1,
                    ..DynamicConfig::default()
                },
            )
            .unwrap();
            let handles: [LeafHandle; 3] =
                core::array::from_fn(|i| tree.insert(i as u32, &a[i].bounds()).unwrap());
            tree.update(handles[1], &a[40].bounds()).unwrap();
            tree.remove(handles[0]).unwrap();
            tree.validate().unwrap();
            tree.to_bvh(&mut ins_nodes, &mut ins_idx).unwrap();
            // Rotations by area and the reinsertion optimiser.
            let mut tree = DynamicTree::new(
                &mut storage,
                DynamicConfig {
                    rotations: Rotations::Area,
                    ..DynamicConfig::default()
                },
            )
            .unwrap();
            for (i, p) in a.iter().enumerate().take(40) {
                tree.insert(i as u32, &p.bounds()).unwrap();
            }
            assert!(tree.optimize(100).unwrap() > 0);
            tree.validate().unwrap();
        });
        if allocs != 0 {
            failures.push(format!(
                "{} {name}: insertion or dynamic-tree operations allocated {allocs} times",
                B::NAME
            ));
        }
        let (ta, tb) = trees;
        let (found, allocs) = count(|| {
            let mut total = 0;
            for rule in Descent::ALL {
                let mut c = Collector::new(&mut out);
                overlapping_pairs(&ta, &a, &tb, &b, rule, |i, j| c.push((i, j))).unwrap();
                total += c.finish().unwrap().len();
            }
            let mut c = Collector::new(&mut hits);
            let region = Aabb::new(Vec3::splat(2.0), Vec3::splat(5.0));
            ta.overlapping(&a, &region, |i| c.push(i)).unwrap();
            total += c.finish().unwrap().len() + ta.stats().leaves;
            total + every_other_query(&ta, &a, &tb, &b, &mut queue, &mut objects_scratch)
        });
        if allocs != 0 {
            failures.push(format!(
                "{} {name}: queries allocated {allocs} times",
                B::NAME
            ));
        }
        if found == 0 {
            failures.push(format!(
                "{} {name}: the scene produced no results; the test would prove nothing",
                B::NAME
            ));
        }
    }
}

type Scratch = (Vec<Aabb>, Vec<Node<Aabb>>, Vec<u32>);

/// Every traversal kind, rule, mode, frame and answer of the two-tree query;
/// every single-tree order; rays; nearest; the collision system. Returns a
/// count of results so the caller can check the scene is not empty.
fn every_other_query<B: BoundingVolume>(
    ta: &Bvh<B>,
    a: &[Triangle],
    tb: &Bvh<B>,
    b: &[Triangle],
    queue: &mut [u32],
    scratch: &mut Scratch,
) -> usize {
    let mut total = 0;
    let motion = Rigid::new(Quat::from_rotation_z(0.2), Vec3::new(0.3, -0.2, 0.1)).unwrap();
    for rule in Descent::ALL {
        for traversal in PairTraversal::all(rule) {
            let q = || Pairs::new(ta, a, tb, b).traversal(traversal);
            let mut counts = Counts::default();
            total += q().counted(&mut counts).count().unwrap();
            total += q().in_frame(motion).exact().count().unwrap();
            total += q().in_frame(motion).first().unwrap().is_some() as usize;
            total += q().exact().for_each(|_, _| {}).unwrap();
            total += counts.bv_tests as usize;
        }
    }
    let mixed = DepthSwitch {
        depth: 3,
        near: Descent::Simultaneous,
        far: Descent::Overlap,
    };
    total += Pairs::new(ta, a, tb, b).descent(mixed).count().unwrap();
    let region = Aabb::new(Vec3::splat(2.0), Vec3::splat(5.0));
    total += ta
        .search(a, &region, Order::DepthFirst, (), |_| {})
        .unwrap();
    total += ta.search(a, &region, Order::Recursive, (), |_| {}).unwrap();
    total += ta
        .search(a, &region, Order::BreadthFirst(queue), (), |_| {})
        .unwrap();
    let ray = Ray::new(
        Vec3::new(-1.0, 3.3, 0.2),
        Vec3::new(1.0, 0.01, 0.02),
        f32::INFINITY,
    )
    .unwrap();
    for order in [RayOrder::DepthFirst, RayOrder::BestFirst] {
        total += ta.cast_ray(a, &ray, order, ()).unwrap().is_some() as usize;
    }
    total += ta.ray_hits_any(a, &ray, ()).unwrap().is_some() as usize;
    let start = Aabb::new(ray.origin() - 0.2, ray.origin() + 0.2);
    for cast in [
        bvhkit::ShapeCast::sphere(ray.origin(), 0.3, ray.dir(), ray.t_max()).unwrap(),
        bvhkit::ShapeCast::aabb(&start, ray.dir(), ray.t_max()).unwrap(),
    ] {
        for order in [RayOrder::DepthFirst, RayOrder::BestFirst] {
            total += ta.cast_shape(a, &cast, order, ()).unwrap().is_some() as usize;
        }
        total += ta.shape_hits_any(a, &cast, ()).unwrap().is_some() as usize;
    }
    total += ta
        .nearest(a, Vec3::new(3.1, 2.2, 9.0), ())
        .unwrap()
        .is_some() as usize;
    let distance = bvhkit::Distance::new(ta, a, tb, b);
    total += distance.closest().unwrap().is_some() as usize;
    total += distance.within(0.5, |_, _| {}).unwrap();
    let objects = [
        Object {
            tree: ta,
            prims: a,
            pose: Rigid::IDENTITY,
        },
        Object {
            tree: tb,
            prims: b,
            pose: motion,
        },
        Object {
            tree: ta,
            prims: a,
            pose: motion.inverse(),
        },
    ];
    let mut broad = BroadPhase {
        boxes: &mut scratch.0,
        nodes: &mut scratch.1,
        indices: &mut scratch.2,
    };
    total += collide(&objects, &mut broad, PairTraversal::default(), |_| {}).unwrap();
    total
}

/// Converting to every layout and querying each one, storage preallocated.
fn check_layouts(failures: &mut Vec<String>) {
    use bvhkit::layout::{
        to_bvh, Implicit, PreNode, Preorder, QuantNode, QuantizedWide, Slot, TriNode, TriNodes,
        Wide, WideNode,
    };
    use bvhkit::Query;
    let (a, b) = (grid(600, 0.0), grid(600, 0.4));
    let cfg = TopDown::median();
    let mut na = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(a.len())];
    let mut nb = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(b.len())];
    let (mut ia, mut ib) = (vec![0u32; a.len()], vec![0u32; b.len()]);
    let ta = cfg.build(&a, &mut na, &mut ia).unwrap();
    let tb = cfg.build(&b, &mut nb, &mut ib).unwrap();
    let mut slots = vec![Slot::EMPTY; Implicit::slots_needed(&ta).unwrap()];
    let mut pre16 = vec![PreNode::<Aabb, u16>::EMPTY; ta.node_count()];
    let mut tri = vec![TriNode::EMPTY; TriNodes::records_needed(&ta).unwrap()];
    let mut wide = vec![WideNode::EMPTY; Wide::records_needed(&ta).unwrap()];
    let mut quant = vec![QuantNode::EMPTY; QuantizedWide::records_needed(&ta).unwrap()];
    let mut back = (vec![Node::EMPTY; ta.node_count()], vec![0u32; a.len()]);
    let region = Aabb::new(Vec3::new(2.0, 2.0, 0.0), Vec3::new(9.0, 7.0, 2.0));
    let ray = Ray::new(
        Vec3::new(-1.0, 3.3, 0.7),
        Vec3::new(1.0, 0.1, 0.05),
        f32::INFINITY,
    )
    .unwrap();
    fn queries<H: bvhkit::Hierarchy<Bv = Aabb>>(
        h: &H,
        a: &[Triangle],
        tb: &Bvh<Aabb>,
        b: &[Triangle],
        region: &Aabb,
        ray: &Ray,
    ) -> usize {
        let mut n = h.overlapping(a, region, |_| {}).unwrap();
        n += h
            .cast_ray(a, ray, RayOrder::DepthFirst, ())
            .unwrap()
            .is_some() as usize;
        n += h.nearest(a, Vec3::splat(3.0), ()).unwrap().is_some() as usize;
        for traversal in PairTraversal::all(Descent::Overlap) {
            n += Pairs::new(h, a, tb, b)
                .traversal(traversal)
                .exact()
                .count()
                .unwrap();
        }
        n
    }
    let mut total = 0;
    let (_, allocs) = count(|| {
        let im = Implicit::from_bvh(&ta, &mut slots).unwrap();
        total += queries(&im, &a, &tb, &b, &region, &ray);
        let pre = Preorder::from_bvh(&ta, &mut pre16).unwrap();
        total += queries(&pre, &a, &tb, &b, &region, &ray);
        let t3 = TriNodes::from_bvh(&ta, &mut tri).unwrap();
        total += queries(&t3, &a, &tb, &b, &region, &ray);
        let w = Wide::from_bvh(&ta, &mut wide).unwrap();
        total += queries(&w, &a, &tb, &b, &region, &ray);
        let q = QuantizedWide::from_bvh(&ta, &mut quant).unwrap();
        total += queries(&q, &a, &tb, &b, &region, &ray);
        let r = to_bvh(&q, &mut back.0, &mut back.1).unwrap();
        total += r.node_count();
    });
    if allocs != 0 {
        failures.push(format!("layouts: {allocs} allocations"));
    }
    if total == 0 {
        failures.push("layouts: the queries found nothing (scene broken)".into());
    }
}

/// The incremental broad phase: arrivals, small moves (reinsertions),
/// every object jumping (refits in place and a rebuild in walk order), the
/// whole-tree walk, departures, all on caller storage.
fn check_tracker(failures: &mut Vec<String>) {
    use bvhkit::collision::{PairTracker, Slot, TrackerStorage};
    const N: usize = 200;
    let mut nodes = vec![DynNode::<Aabb>::EMPTY; 2 * N - 1];
    let (mut slots, mut boxes, mut moved) =
        (vec![Slot::EMPTY; N], vec![Aabb::EMPTY; N], vec![0u32; N]);
    let (mut pairs, mut next) = (vec![(0u32, 0u32); 20 * N], vec![(0u32, 0u32); 20 * N]);
    let place = |i: usize, t: f32| {
        let o = Vec3::new(
            (i % 10) as f32 * 1.5,
            (i / 10 % 10) as f32 * 1.5,
            (i / 100) as f32 * 1.5,
        );
        Aabb::new(o + t, o + t + 2.0)
    };
    let (found, allocs) = count(|| {
        let storage = TrackerStorage {
            nodes: &mut nodes,
            slots: &mut slots,
            boxes: &mut boxes,
            moved: &mut moved,
            pairs: &mut pairs,
            next: &mut next,
        };
        let config = DynamicConfig {
            margin: 0.1,
            ..DynamicConfig::default()
        };
        let mut world = PairTracker::new(storage, config).unwrap();
        let mut found = 0;
        for i in 0..N {
            world.insert(i as u32, &place(i, 0.0)).unwrap();
        }
        found += world.step(|_| {}).unwrap().pairs;
        for (k, t) in [0.05f32, 0.5, 0.9, 1.4].into_iter().enumerate() {
            // First one object in 25 moves, then all of them.
            let every = if k == 0 { 25 } else { 1 };
            for i in (0..N).step_by(every) {
                world.set_bounds(i as u32, &place(i, t)).unwrap();
            }
            found += world.step(|_| {}).unwrap().pairs;
        }
        world.remove(7).unwrap();
        found += world.step(|_| {}).unwrap().pairs;
        world.tree().validate().unwrap();
        found
    });
    if allocs != 0 {
        failures.push(format!("PairTracker: steps allocated {allocs} times"));
    }
    if found == 0 {
        failures.push("PairTracker: no pairs found; the test would prove nothing".into());
    }
}

fn main() {
    let mut failures = Vec::new();
    check_layouts(&mut failures);
    check_tracker(&mut failures);
    check::<Aabb>(&mut failures);
    check::<Sphere>(&mut failures);
    check::<Obb>(&mut failures);
    check::<Dop14>(&mut failures);
    check::<Dop26>(&mut failures);
    // Sanity: the counter itself works.
    let (_, n) = count(|| std::hint::black_box(vec![1u8; 10]));
    if n == 0 {
        failures.push("the counting allocator saw no allocation from vec![]".into());
    }
    let cases = 5 * CONFIGS.len() + 3;
    for f in &failures {
        eprintln!("FAILED: {f}");
    }
    println!(
        "{} passed, {} failed",
        cases - failures.len().min(cases),
        failures.len()
    );
    if !failures.is_empty() {
        std::process::exit(1);
    }
}
