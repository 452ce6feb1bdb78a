//! Every tree representation against brute force: region searches in every
//! order, rays, sphere and box casts, nearest, and two-tree pairs under every traversal and rule
//! (same frame and moved), for trees from several builders, including
//! unbalanced and degenerate ones. Also: round trips, conservative
//! quantization, record sizes, 16-bit links with far links (forced on small
//! trees by a short reach, and real on a tree of 600 000 nodes), and the
//! refusals (a short far table, sparse implicit arrays, oversized quantized
//! leaves).

use bvhkit::glam::{Quat, Vec3};
use bvhkit::layout::{
    to_bvh, FarLink, Implicit, PreNode, Preorder, QuantNode, QuantizedWide, Slot, TriNode,
    TriNodes, Wide, WideNode, ESCAPE,
};
use bvhkit::{
    brute_force, Aabb, BoundingVolume, Bounds, Bvh, Content, Dop14, Error, Exact, Hierarchy, Node,
    Order, Query, Ray, RayOrder, Rigid, Same, Sphere, TopDown, Triangle,
};
use bvhkit_tests::*;
use proptest::prelude::*;

/// Owned storage for every layout of one canonical tree.
struct Layouts<B> {
    implicit: Result<Vec<Slot<B>>, Error>,
    pre32: Vec<PreNode<B, u32>>,
    pre16: Vec<PreNode<B, u16>>,
    /// Far links of the 16-bit preorder at full reach, then at each of
    /// [`SHORT_REACHES`] (which make small trees escape).
    far16: Vec<Vec<FarLink>>,
    tri: Vec<TriNode<B>>,
    wide: Vec<WideNode>,
    quant: Vec<QuantNode>,
    /// Quantized without merging, and with the largest merge limit.
    quant_plain: Vec<QuantNode>,
    quant_most: Vec<QuantNode>,
}

impl<B: BoundingVolume> Layouts<B> {
    fn storage(bvh: &Bvh<B>) -> Self {
        Layouts {
            implicit: Implicit::slots_needed(bvh).map(|n| vec![Slot::EMPTY; n]),
            pre32: vec![PreNode::EMPTY; bvh.node_count()],
            pre16: vec![PreNode::EMPTY; bvh.node_count()],
            far16: std::iter::once(usize::MAX)
                .chain(short_reaches(bvh))
                .map(|reach| {
                    let n = Preorder::<B, u16>::far_links_needed_reaching(bvh, reach).unwrap();
                    vec![FarLink::EMPTY; n]
                })
                .collect(),
            tri: vec![TriNode::EMPTY; TriNodes::records_needed(bvh).unwrap()],
            wide: vec![WideNode::EMPTY; Wide::records_needed(bvh).unwrap()],
            quant: vec![QuantNode::EMPTY; QuantizedWide::records_needed(bvh).unwrap()],
            quant_plain: vec![
                QuantNode::EMPTY;
                QuantizedWide::records_needed_merged(bvh, 0).unwrap()
            ],
            quant_most: vec![
                QuantNode::EMPTY;
                QuantizedWide::records_needed_merged(
                    bvh,
                    QuantizedWide::MAX_MERGED_LEAF
                )
                .unwrap()
            ],
        }
    }
}

/// Reaches that make the 16-bit preorder escape on small trees: 2 (only
/// a left child that is a leaf, and a leaf within 2 entries of its
/// predicted start, stay short: nearly every link escapes) and a quarter of
/// the tree (the links near the root escape, as in a large tree).
fn short_reaches<B: BoundingVolume>(bvh: &Bvh<B>) -> [usize; 2] {
    [2, bvh.node_count() / 4]
}

macro_rules! each_layout {
    ($bvh:expr, $storage:expr, |$name:ident, $view:ident| $body:block) => {{
        let bvh = $bvh;
        let st = $storage;
        {
            let $name = "canonical";
            let $view = bvh;
            $body
        }
        match st.implicit.as_mut() {
            Ok(slots) => {
                let $name = "implicit";
                let $view = &Implicit::from_bvh(bvh, slots).unwrap();
                $body
            }
            Err(e) => assert!(matches!(e, Error::SparseTree { .. }), "{e}"),
        }
        {
            let $name = "preorder-32";
            let $view = &Preorder::from_bvh(bvh, &mut st.pre32).unwrap();
            $body
        }
        {
            let $name = "preorder-16";
            let $view = &Preorder::from_bvh_with_far(bvh, &mut st.pre16, &mut st.far16[0]).unwrap();
            $body
        }
        for (k, reach) in short_reaches(bvh).into_iter().enumerate() {
            let $name = ["preorder-16 (reach 2)", "preorder-16 (reach n/4)"][k];
            let far = &mut st.far16[k + 1];
            let $view = &Preorder::from_bvh_reaching(bvh, &mut st.pre16, far, reach).unwrap();
            $body
        }
        {
            let $name = "tri-node";
            let $view = &TriNodes::from_bvh(bvh, &mut st.tri).unwrap();
            $body
        }
    }};
}

macro_rules! each_box_layout {
    ($bvh:expr, $storage:expr, |$name:ident, $view:ident| $body:block) => {{
        let bvh = $bvh;
        let st = $storage;
        {
            let $name = "wide";
            let $view = &Wide::from_bvh(bvh, &mut st.wide).unwrap();
            $body
        }
        {
            let $name = "quantized";
            let $view = &QuantizedWide::from_bvh(bvh, &mut st.quant).unwrap();
            $body
        }
        {
            let $name = "quantized-unmerged";
            let $view = &QuantizedWide::from_bvh_merged(bvh, 0, &mut st.quant_plain).unwrap();
            $body
        }
        {
            let $name = "quantized-merged-64";
            let most = QuantizedWide::MAX_MERGED_LEAF;
            let $view = &QuantizedWide::from_bvh_merged(bvh, most, &mut st.quant_most).unwrap();
            $body
        }
    }};
}

/// Every node's volume contains the bounds of every primitive beneath it
/// (the conservativeness every query relies on), and each primitive is in
/// exactly one leaf.
fn check_contains<H: Hierarchy>(h: &H, prims: &[Triangle], name: &str) {
    fn walk<H: Hierarchy>(h: &H, n: u32, prims: &[Triangle], seen: &mut [u32]) -> Vec<u32> {
        let bv = h.bv(n);
        let below = match h.content(n) {
            Content::Leaf(here) => {
                for &p in here {
                    seen[p as usize] += 1;
                }
                // Kept leaf bounds, if any, are exactly the ids' bounds.
                if let Some(kept) = h.leaf_bounds(n) {
                    assert_eq!(kept.len(), here.len(), "node {n}: kept bounds per id");
                    for (b, &p) in kept.iter().zip(here) {
                        assert_eq!(*b, bvhkit::Primitive::bounds(&prims[p as usize]));
                    }
                }
                here.to_vec()
            }
            Content::Inner(kids) => kids
                .as_slice()
                .iter()
                .flat_map(|&c| walk(h, c, prims, seen))
                .collect(),
        };
        for &p in &below {
            let b = bvhkit::Primitive::bounds(&prims[p as usize]);
            assert!(bv.contains_aabb(&b), "node {n} misses primitive {p}");
        }
        below
    }
    let mut seen = vec![0u32; prims.len()];
    walk(h, h.root(), prims, &mut seen);
    assert!(
        seen.iter().all(|&s| s == 1),
        "{name}: a primitive is lost or repeated"
    );
}

/// Region (three orders and three region types), ray, any-hit and nearest
/// against brute force.
fn check_single<H: Hierarchy>(
    h: &H,
    prims: &[Triangle],
    probe: (f32, f32, f32),
    name: &str,
) -> Result<(), TestCaseError> {
    check_contains(h, prims, name);
    let region = region_in(prims, probe.0.min(probe.1), probe.0.max(probe.1));
    let ball = Sphere::new(region.center(), region.extent().length() * 0.35);
    let dop = Dop14::fit(&[
        region.min,
        region.max,
        Vec3::new(region.min.x, region.max.y, 0.0),
    ]);
    let mut want = Vec::new();
    brute_force::overlapping(prims, &region, |i| want.push(i));
    let mut queue = vec![0u32; h.breadth_first_queue()];
    for order in [
        Order::DepthFirst,
        Order::Recursive,
        Order::BreadthFirst(&mut queue),
    ] {
        let label = format!("{order:?}");
        let mut got = Vec::new();
        h.search(prims, &region, order, (), |i| got.push(i))
            .unwrap();
        got.sort_unstable();
        prop_assert_eq!(&got, &want, "{} search {}", name, label);
    }
    let mut got = Vec::new();
    h.overlapping(prims, &region, |i| got.push(i)).unwrap();
    got.sort_unstable();
    prop_assert_eq!(&got, &want, "{} overlapping", name);
    for (what, mut got, want) in [
        ("sphere", Vec::new(), collect(prims, &ball)),
        ("14-dop", Vec::new(), collect(prims, &dop)),
    ] {
        match what {
            "sphere" => h.overlapping(prims, &ball, |i| got.push(i)).unwrap(),
            _ => h.overlapping(prims, &dop, |i| got.push(i)).unwrap(),
        };
        got.sort_unstable();
        prop_assert_eq!(got, want, "{} {} region", name, what);
    }

    let bounds = region_in(prims, 0.0, 1.0);
    let origin = bounds.min + bounds.extent() * (Vec3::new(probe.0, probe.1, probe.2) * 1.2 - 0.1);
    let target = bounds.center() + bounds.extent() * (probe.2 - 0.5) * 0.3;
    let dir = target - origin;
    if dir.length_squared() > 0.0 && dir.is_finite() {
        let ray = Ray::new(origin, dir, f32::INFINITY).unwrap();
        let want = brute_force::ray_closest(prims, &ray);
        for order in [RayOrder::DepthFirst, RayOrder::BestFirst] {
            prop_assert_eq!(
                h.cast_ray(prims, &ray, order, ()).unwrap(),
                want,
                "{} ray {:?}",
                name,
                order
            );
        }
        let any = h.ray_hits_any(prims, &ray, ()).unwrap();
        prop_assert_eq!(any.is_some(), want.is_some(), "{} any-hit", name);
        let size = bounds.extent().max_element() * 0.1 * probe.1;
        check_casts(h, prims, origin, dir, size, f32::INFINITY, name)?;
    }
    let near = h.nearest(prims, origin, ()).unwrap();
    prop_assert_eq!(
        near,
        brute_force::nearest(prims, origin),
        "{} nearest",
        name
    );
    Ok(())
}

fn collect<R: BoundingVolume>(prims: &[Triangle], r: &R) -> Vec<u32> {
    let mut v = Vec::new();
    brute_force::overlapping(prims, r, |i| v.push(i));
    v
}

/// Pairs of `h` against `other` (another representation) in every traversal,
/// same frame and moved, bounds and exact.
fn check_two<A: Hierarchy, H: Hierarchy<Bv = A::Bv>>(
    ta: &A,
    a: &[Triangle],
    tb: &H,
    b: &[Triangle],
    motion: &Rigid,
    name: &str,
) -> Result<(), TestCaseError> {
    check_pairs(ta, a, tb, b, &Same, Bounds, &name)?;
    check_pairs(ta, a, tb, b, motion, Exact, &name)?;
    check_pairs(ta, a, tb, b, motion, Bounds, &name)
}

pub(crate) fn run_all<B: BoundingVolume>(
    (na, ia): (&[Node<B>], &[u32]),
    (nb, ib): (&[Node<B>], &[u32]),
    a: &[Triangle],
    b: &[Triangle],
    probe: (f32, f32, f32),
) -> Result<(), TestCaseError> {
    // Half the cases keep A's primitive bounds in leaf order: every layout
    // shares them with the canonical tree (and its leaf step uses them).
    let mut kept = vec![Aabb::EMPTY; a.len()];
    let ta = keep_bounds(open(na, ia, a), a, &mut kept, probe.0 < 0.5);
    let tb = open(nb, ib, b);
    let motion = Rigid::new(
        Quat::from_rotation_y(0.3 + probe.0),
        Vec3::splat(probe.1 - 0.5),
    )
    .unwrap();
    let mut sa = Layouts::storage(&ta);
    let mut sb = Layouts::storage(&tb);
    let mut result = Ok(());
    each_layout!(&ta, &mut sa, |name, view| {
        if result.is_ok() {
            result = check_single(view, a, probe, name);
        }
        // Each layout of A against B's canonical tree and B's same layout.
        if result.is_ok() {
            result = check_two(view, a, &tb, b, &motion, name);
        }
    });
    result?;
    // Layout against layout (A preorder-32 against B tri-node: mixed kinds).
    let pa = Preorder::from_bvh(&ta, &mut sa.pre32).unwrap();
    let qb = TriNodes::from_bvh(&tb, &mut sb.tri).unwrap();
    check_two(&pa, a, &qb, b, &motion, "preorder x tri-node")?;
    // Both trees 16-bit with nearly every link escaped.
    let ea = Preorder::from_bvh_reaching(&ta, &mut sa.pre16, &mut sa.far16[1], 2).unwrap();
    let eb = Preorder::from_bvh_reaching(&tb, &mut sb.pre16, &mut sb.far16[1], 2).unwrap();
    check_two(
        &ea,
        a,
        &eb,
        b,
        &motion,
        "preorder-16 x preorder-16 (reach 2)",
    )?;
    Ok(())
}

pub(crate) fn run_boxes(
    (na, ia): (&[Node<Aabb>], &[u32]),
    (nb, ib): (&[Node<Aabb>], &[u32]),
    a: &[Triangle],
    b: &[Triangle],
    probe: (f32, f32, f32),
) -> Result<(), TestCaseError> {
    let mut kept = vec![Aabb::EMPTY; a.len()];
    let ta = keep_bounds(open(na, ia, a), a, &mut kept, probe.0 >= 0.5);
    let tb = open(nb, ib, b);
    let motion = Rigid::new(
        Quat::from_rotation_x(0.7 - probe.2),
        Vec3::splat(probe.0 - 0.5),
    )
    .unwrap();
    let mut sa = Layouts::storage(&ta);
    let mut sb = Layouts::storage(&tb);
    let mut result = Ok(());
    each_box_layout!(&ta, &mut sa, |name, view| {
        if result.is_ok() {
            result = check_single(view, a, probe, name);
        }
        if result.is_ok() {
            result = check_two(view, a, &tb, b, &motion, name);
        }
        // The self query on every layout (box trees; every volume type is
        // checked on the canonical trees, and the self walk is the pair
        // walk checked above for every volume and layout). Once per layout
        // here, not per volume: compiled for each, it added minutes to this
        // binary's build in CI.
        if result.is_ok() {
            result = check_self(view, a, &name);
        }
        // Distances, each layout against B's canonical tree.
        if result.is_ok() {
            result = check_distance(view, a, &tb, b, probe.1 as f64 * 3.0, &name).map(|_| ());
        }
    });
    result?;
    // Wide against quantized: two 4-wide trees of different record types.
    let wa = Wide::from_bvh(&ta, &mut sa.wide).unwrap();
    let qb = QuantizedWide::from_bvh(&tb, &mut sb.quant).unwrap();
    check_two(&wa, a, &qb, b, &motion, "wide x quantized")
}

/// `tree` with its primitives' bounds kept in `out`, if `keep`.
fn keep_bounds<'a, B: BoundingVolume>(
    tree: Bvh<'a, B>,
    prims: &[Triangle],
    out: &'a mut [Aabb],
    keep: bool,
) -> Bvh<'a, B> {
    if keep {
        let kept = tree.with_leaf_bounds(prims, out).unwrap();
        assert!(kept.leaf_bounds().is_some() || prims.is_empty());
        kept
    } else {
        tree
    }
}

fn built<B: BoundingVolume>(cfg: &TopDown, prims: &[Triangle]) -> Result<Built<B>, TestCaseError> {
    build::<B, _>(cfg, prims).map_err(|e| TestCaseError::fail(format!("{e}")))
}

proptest! {
    #![proptest_config(proptest_config(24))]

    #[test]
    fn every_layout_answers_like_brute_force(
        cfg in any_top_down(),
        a in scene(40),
        b in scene(40),
        probe in (0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0),
    ) {
        let (na, ia, _) = built::<Aabb>(&cfg, &a)?;
        let (nb, ib, _) = built::<Aabb>(&cfg, &b)?;
        run_all((&na, &ia), (&nb, &ib), &a, &b, probe)?;
        run_boxes((&na, &ia), (&nb, &ib), &a, &b, probe)?;
        let (na, ia, _) = built::<Sphere>(&cfg, &a)?;
        let (nb, ib, _) = built::<Sphere>(&cfg, &b)?;
        run_all((&na, &ia), (&nb, &ib), &a, &b, probe)?;
        let (na, ia, _) = built::<Dop14>(&cfg, &a)?;
        let (nb, ib, _) = built::<Dop14>(&cfg, &b)?;
        run_all((&na, &ia), (&nb, &ib), &a, &b, probe)?;
    }

    #[test]
    fn bottom_up_trees_in_every_layout(
        a in scene(40),
        b in scene(40),
        probe in (0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0),
    ) {
        use bvhkit::builders::{BottomUp, Method};
        let cfg = BottomUp { method: Method::Ploc { radius: 2 }, ..BottomUp::default() };
        let (na, ia, _) = build_bottom_up::<Aabb, _>(&cfg, &a).map_err(|e| TestCaseError::fail(format!("{e}")))?;
        let (nb, ib, _) = build_bottom_up::<Aabb, _>(&cfg, &b).map_err(|e| TestCaseError::fail(format!("{e}")))?;
        run_all((&na, &ia), (&nb, &ib), &a, &b, probe)?;
        run_boxes((&na, &ia), (&nb, &ib), &a, &b, probe)?;
    }

    #[test]
    fn binary_layouts_round_trip_to_the_same_tree(cfg in any_top_down(), a in scene(60)) {
        let (na, ia, _) = built::<Sphere>(&cfg, &a)?;
        let t = open(&na, &ia, &a);
        let mut st = Layouts::storage(&t);
        let mut back = vec![Node::EMPTY; t.node_count()];
        let mut back_idx = vec![0; a.len()];
        each_layout!(&t, &mut st, |name, view| {
            let r = to_bvh(view, &mut back, &mut back_idx).unwrap();
            assert!(same_tree(&t, 0, &r, 0), "{name} round trip changed the tree");
            assert_eq!(r.depth(), t.depth(), "{name}");
            open(r.nodes(), r.indices(), &a);
        });
    }

    #[test]
    fn wide_layouts_convert_back_to_valid_equivalent_trees(cfg in any_top_down(), a in scene(60), b in scene(30)) {
        let (na, ia, _) = built::<Aabb>(&cfg, &a)?;
        let (nb, ib, _) = built::<Aabb>(&cfg, &b)?;
        let (t, tb) = (open(&na, &ia, &a), open(&nb, &ib, &b));
        let mut st = Layouts::storage(&t);
        let mut want = Vec::new();
        brute_force::pairs(&a, &b, |i, j| want.push((i, j)));
        want.sort_unstable();
        let mut back = vec![Node::EMPTY; bvhkit::max_nodes(a.len())];
        let mut back_idx = vec![0; a.len()];
        each_box_layout!(&t, &mut st, |name, view| {
            let r = to_bvh(view, &mut back, &mut back_idx).unwrap();
            // Validated (structure, containment, every primitive once) and
            // answering like brute force.
            let r = open(r.nodes(), r.indices(), &a);
            let mut got = Vec::new();
            bvhkit::Pairs::new(&r, &a, &tb, &b).for_each(|i, j| got.push((i, j))).unwrap();
            got.sort_unstable();
            prop_assert_eq!(&got, &want, "{} -> canonical", name);
        });
    }

    #[test]
    fn conversions_between_layouts_go_through_the_canonical_tree(cfg in any_top_down(), a in scene(60)) {
        // preorder -> canonical -> tri-node equals canonical -> tri-node.
        let (na, ia, _) = built::<Dop14>(&cfg, &a)?;
        let t = open(&na, &ia, &a);
        let mut pre = vec![PreNode::<Dop14, u32>::EMPTY; t.node_count()];
        let pre = Preorder::from_bvh(&t, &mut pre).unwrap();
        let mut back = vec![Node::EMPTY; t.node_count()];
        let mut back_idx = vec![0; a.len()];
        let mid = to_bvh(&pre, &mut back, &mut back_idx).unwrap();
        let mut t1 = vec![TriNode::EMPTY; TriNodes::records_needed(&t).unwrap()];
        let mut t2 = vec![TriNode::EMPTY; TriNodes::records_needed(&mid).unwrap()];
        let direct = TriNodes::from_bvh(&t, &mut t1).unwrap();
        let via = TriNodes::from_bvh(&mid, &mut t2).unwrap();
        prop_assert!(same_tree(&direct, 0, &via, 0));
        prop_assert_eq!(direct.records().len(), via.records().len());
    }

    #[test]
    fn quantized_boxes_contain_the_exact_boxes(
        boxes in prop::collection::vec(
            ((-1e6f32..1e6, -1e6f32..1e6, -1e6f32..1e6), (0.0f32..1e3, 0.0f32..1e-2, 0.0f32..1e6), 0i32..20),
            1..5,
        )
    ) {
        let boxes: Vec<Aabb> = boxes
            .into_iter()
            .map(|((x, y, z), (w, h, d), scale)| {
                let s = (2.0f32).powi(scale - 10);
                let lo = Vec3::new(x, y, z) * s;
                Aabb::new(lo, lo + Vec3::new(w, h, d) * s)
            })
            .collect();
        let q = QuantNode::encode(&boxes);
        for (k, b) in boxes.iter().enumerate() {
            let d = q.slot_box(k);
            prop_assert!(d.contains_aabb(b), "slot {} decoded {:?} misses {:?}", k, d, b);
        }
    }
}

/// Structural equality of two trees given as views: same volumes, same
/// leaves, same child order.
fn same_tree<X: Hierarchy, Y: Hierarchy<Bv = X::Bv>>(x: &X, i: u32, y: &Y, j: u32) -> bool
where
    X::Bv: PartialEq,
{
    if x.bv(i) != y.bv(j) {
        return false;
    }
    match (x.content(i), y.content(j)) {
        (Content::Leaf(p), Content::Leaf(q)) => p == q,
        (Content::Inner(k), Content::Inner(l)) => {
            k.as_slice().len() == l.as_slice().len()
                && k.as_slice()
                    .iter()
                    .zip(l.as_slice())
                    .all(|(&c, &d)| same_tree(x, c, y, d))
        }
        _ => false,
    }
}

fn line(n: usize, spacing: impl Fn(usize) -> f32) -> Vec<Vec3> {
    (0..n).map(|i| Vec3::new(spacing(i), 0.0, 0.0)).collect()
}

#[test]
fn record_sizes_are_as_documented() {
    use core::mem::size_of;
    assert_eq!(size_of::<Node<Aabb>>(), 32);
    assert_eq!(size_of::<Slot<Aabb>>(), 28);
    assert_eq!(size_of::<Slot<Sphere>>(), 20);
    assert_eq!(size_of::<PreNode<Aabb, u32>>(), 32);
    assert_eq!(size_of::<PreNode<Aabb, u16>>(), 28);
    assert_eq!(size_of::<PreNode<Sphere, u16>>(), 20);
    assert_eq!(size_of::<TriNode<Aabb>>(), 92);
    assert_eq!(size_of::<WideNode>(), 128);
    assert_eq!(std::mem::align_of::<WideNode>(), 64);
    assert_eq!(size_of::<QuantNode>(), 64);
}

/// `n` small boxes on a jittered grid (a deterministic scene of any size).
fn small_boxes(n: usize) -> Vec<Aabb> {
    let side = (n as f64).cbrt().ceil() as usize;
    (0..n)
        .map(|i| {
            let (x, y, z) = (i % side, (i / side) % side, i / (side * side));
            let jitter = ((i as u32).wrapping_mul(2_654_435_761) >> 24) as f32 / 1024.0;
            let lo = Vec3::new(x as f32, y as f32 + jitter, z as f32);
            Aabb::new(lo, lo + Vec3::splat(0.5 + jitter))
        })
        .collect()
}

/// 300 000 boxes: a tree of far more than 65 535 nodes and primitives
/// takes 16-bit links, the few too far for them go to the far table, and
/// every query answers exactly as brute force and the 32-bit layout do.
#[test]
fn sixteen_bit_links_take_a_tree_of_any_size_through_far_links() {
    let a = small_boxes(300_000);
    let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(a.len())];
    let mut idx = vec![0; a.len()];
    let t = TopDown::default().build(&a, &mut nodes, &mut idx).unwrap();
    assert!(t.node_count() > 65_535, "{} nodes", t.node_count());
    let needed = Preorder::<Aabb, u16>::far_links_needed(&t).unwrap();
    // A handful near the root, not one per node.
    assert!((1..=64).contains(&needed), "{needed} far links");
    let mut recs = vec![PreNode::<Aabb, u16>::EMPTY; t.node_count()];
    // No far table, or one entry short: refused, and nothing written.
    let mut short = vec![FarLink::EMPTY; needed - 1];
    for far in [&mut [][..], &mut short[..]] {
        let available = far.len();
        let err = Preorder::from_bvh_with_far(&t, &mut recs, far).unwrap_err();
        assert_eq!(err, Error::FarLinkCapacity { needed, available });
    }
    assert!(recs.iter().all(|r| *r == PreNode::EMPTY));
    let mut far = vec![FarLink::EMPTY; needed];
    let pre = Preorder::from_bvh_with_far(&t, &mut recs, &mut far).unwrap();
    assert_eq!(pre.far_links().len(), needed);
    assert_eq!(
        pre.records()[0].link(),
        ESCAPE,
        "the root's right child is far"
    );
    let mut recs32 = vec![PreNode::<Aabb, u32>::EMPTY; t.node_count()];
    let pre32 = Preorder::from_bvh(&t, &mut recs32).unwrap();
    for i in 0..t.node_count() {
        assert_eq!(pre.right(i), pre32.right(i), "record {i}");
        assert_eq!(pre.content(i as u32), pre32.content(i as u32), "record {i}");
    }
    // Records stay 28 bytes; the far links add 8 bytes each.
    assert_eq!(pre.bytes(), pre32.bytes() - 4 * t.node_count() + 8 * needed);
    // Queries: regions and nearest against brute force, rays against the
    // canonical tree, pairs with every traversal against brute force.
    for k in 0..4 {
        let lo = Vec3::new(5.0 + 13.0 * k as f32, 2.0 * k as f32, 40.0 - 9.0 * k as f32);
        let region = Aabb::new(lo, lo + Vec3::new(7.5, 3.0, 2.5));
        let mut want = Vec::new();
        brute_force::overlapping(&a, &region, |i| want.push(i));
        let mut got = Vec::new();
        pre.overlapping(&a, &region, |i| got.push(i)).unwrap();
        got.sort_unstable();
        assert_eq!(got, want, "region {k}");
        assert!(!want.is_empty());
        let point = lo * 1.1 - Vec3::splat(3.0);
        assert_eq!(
            pre.nearest(&a, point, ()).unwrap(),
            brute_force::nearest(&a, point)
        );
        let ray = Ray::new(
            point,
            Vec3::new(1.0, 0.7 - 0.2 * k as f32, 0.3),
            f32::INFINITY,
        )
        .unwrap();
        for order in [RayOrder::DepthFirst, RayOrder::BestFirst] {
            let got = pre.cast_ray(&a, &ray, order, ()).unwrap();
            assert_eq!(got, t.cast_ray(&a, &ray, order, ()).unwrap(), "ray {k}");
            assert!(got.is_some());
        }
    }
    // B: 400 boxes of a few units across the whole grid, every pair query
    // with every traversal and descent rule, same frame.
    let b: Vec<Aabb> = (0..400)
        .map(|i| {
            let c = Vec3::new(
                (i * 7 % 67) as f32,
                (i * 13 % 67) as f32,
                (i * 29 % 67) as f32,
            );
            Aabb::new(c, c + Vec3::splat(1.0 + (i % 3) as f32))
        })
        .collect();
    let mut nb = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(b.len())];
    let mut ib = vec![0; b.len()];
    let tb = TopDown::default().build(&b, &mut nb, &mut ib).unwrap();
    let mut want = Vec::new();
    brute_force::pairs(&a, &b, |i, j| want.push((i, j)));
    want.sort_unstable();
    assert!(want.len() > 1000, "{} pairs", want.len());
    for traversal in all_traversals() {
        let mut got = Vec::new();
        bvhkit::Pairs::new(&pre, &a, &tb, &b)
            .traversal(traversal)
            .for_each(|i, j| got.push((i, j)))
            .unwrap();
        got.sort_unstable();
        assert_eq!(got, want, "{traversal:?}");
    }
}

/// Every escaped link is in the far table, the table is sorted and sized
/// by `far_links_needed`, and every link decodes to the 32-bit layout's.
fn check_far_links<B: BoundingVolume>(t: &Bvh<B>, reach: usize) -> Result<(), TestCaseError> {
    let needed = Preorder::<B, u16>::far_links_needed_reaching(t, reach).unwrap();
    let mut recs = vec![PreNode::<B, u16>::EMPTY; t.node_count()];
    if needed > 0 {
        let mut short = vec![FarLink::EMPTY; needed - 1];
        let err = Preorder::from_bvh_reaching(t, &mut recs, &mut short, reach).unwrap_err();
        prop_assert_eq!(
            err,
            Error::FarLinkCapacity {
                needed,
                available: needed - 1
            }
        );
    }
    // A longer table than needed is fine; only `needed` entries are used.
    let mut far = vec![FarLink::EMPTY; needed + 3];
    let pre = Preorder::from_bvh_reaching(t, &mut recs, &mut far, reach).unwrap();
    let mut recs32 = vec![PreNode::<B, u32>::EMPTY; t.node_count()];
    let pre32 = Preorder::from_bvh(t, &mut recs32).unwrap();
    prop_assert_eq!(pre.far_links().len(), needed);
    prop_assert!(pre
        .far_links()
        .windows(2)
        .all(|w| w[0].record < w[1].record));
    let escaped: Vec<u32> = (pre.records().iter().enumerate())
        .filter(|(_, r)| r.link() == ESCAPE)
        .map(|(i, _)| i as u32)
        .collect();
    let listed: Vec<u32> = pre.far_links().iter().map(|f| f.record).collect();
    prop_assert_eq!(escaped, listed);
    for (i, r) in pre.records().iter().enumerate() {
        prop_assert_eq!(pre.right(i), pre32.right(i), "record {}", i);
        prop_assert_eq!(
            pre.content(i as u32),
            pre32.content(i as u32),
            "record {}",
            i
        );
        // A short link never exceeds the reach.
        if r.link() != ESCAPE && r.has_left_child() {
            prop_assert!(r.link() as usize <= reach);
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(proptest_config(48))]

    /// Small trees with the reach lowered so that links escape: from none
    /// (full reach) to nearly all (reach 0).
    #[test]
    fn sixteen_bit_links_escape_exactly_when_too_far(
        cfg in any_top_down(),
        a in scene(60),
        reach in prop_oneof![Just(0usize), Just(2), 0usize..40, Just(usize::MAX)],
    ) {
        let (na, ia, _) = built::<Aabb>(&cfg, &a)?;
        check_far_links(&open(&na, &ia, &a), reach)?;
    }
}

#[test]
fn implicit_array_refuses_a_chain_and_reports_its_waste() {
    // Points at 2^i: every spatial-median split cuts off one point, a chain.
    let pts = line(30, |i| (2.0f32).powi(i as i32));
    let cfg = TopDown {
        split: bvhkit::SplitPoint::SpatialMedian,
        ..TopDown::default()
    }
    .with_max_leaf_size(1);
    let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(pts.len())];
    let mut idx = vec![0; pts.len()];
    let t = cfg.build(&pts, &mut nodes, &mut idx).unwrap();
    assert!(t.depth() >= 20, "depth {}", t.depth());
    let err = Implicit::slots_needed(&t).unwrap_err();
    assert!(matches!(err, Error::SparseTree { nodes: 59, .. }), "{err}");
    // A balanced tree of 24 points fits with the waste reported.
    let pts = line(24, |i| i as f32);
    let t = TopDown::median()
        .with_max_leaf_size(1)
        .build(&pts, &mut nodes, &mut idx[..24])
        .unwrap();
    let mut slots = vec![Slot::EMPTY; Implicit::slots_needed(&t).unwrap()];
    let im = Implicit::from_bvh(&t, &mut slots).unwrap();
    assert_eq!(im.slots().len(), 63); // depth 5
    assert_eq!(im.unused(), 63 - 47);
}

#[test]
fn too_small_storage_and_oversized_quantized_leaves_are_errors() {
    let pts = line(300, |i| (i % 3) as f32);
    let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(pts.len())];
    let mut idx = vec![0; pts.len()];
    let t = TopDown::default()
        .with_max_leaf_size(300)
        .build(&pts, &mut nodes, &mut idx)
        .unwrap();
    assert_eq!(t.node_count(), 1);
    let mut recs = vec![QuantNode::EMPTY; 4];
    let err = QuantizedWide::from_bvh(&t, &mut recs).unwrap_err();
    assert!(
        matches!(
            err,
            Error::FieldOverflow {
                value: 300,
                max: 254,
                ..
            }
        ),
        "{err}"
    );
    // The float wide layout takes it.
    let mut wide = vec![WideNode::EMPTY; 1];
    assert!(Wide::from_bvh(&t, &mut wide).is_ok());

    let t = TopDown::default()
        .with_max_leaf_size(1)
        .build(&pts, &mut nodes, &mut idx)
        .unwrap();
    let mut few = vec![TriNode::EMPTY; 3];
    assert!(matches!(
        TriNodes::from_bvh(&t, &mut few),
        Err(Error::NodeCapacity { .. })
    ));
    let mut few = vec![PreNode::<Aabb, u32>::EMPTY; 3];
    assert!(matches!(
        Preorder::from_bvh(&t, &mut few),
        Err(Error::NodeCapacity { .. })
    ));

    // A 16-bit leaf size holds 65 535 primitives: one leaf of 65 536 is
    // refused (by the sizing too), never wrapped around to a count of 0.
    let pts = line(65_536, |i| i as f32);
    let mut nodes = vec![Node::<Aabb>::EMPTY; 1];
    let mut idx = vec![0; pts.len()];
    let t = TopDown::default()
        .with_max_leaf_size(65_536)
        .build(&pts, &mut nodes, &mut idx)
        .unwrap();
    let overflow = Error::FieldOverflow {
        field: "leaf size of a preorder link",
        value: 65_536,
        max: 65_535,
    };
    assert_eq!(Preorder::<Aabb, u16>::far_links_needed(&t), Err(overflow));
    let mut one = vec![PreNode::<Aabb, u16>::EMPTY; 1];
    assert_eq!(Preorder::from_bvh(&t, &mut one).unwrap_err(), overflow);
    assert_eq!(one[0], PreNode::EMPTY);
}

#[test]
fn quantized_boxes_are_looser_but_every_query_still_matches() {
    let (a, b) = (bumpy(48, 0.0), bumpy(48, 0.3));
    let (na, ia, _) = build::<Aabb, _>(&TopDown::sah(), &a).unwrap();
    let (nb, ib, _) = build::<Aabb, _>(&TopDown::sah(), &b).unwrap();
    let (ta, tb) = (open(&na, &ia, &a), open(&nb, &ib, &b));
    let mut sa = Layouts::storage(&ta);
    // Unmerged: exactly the records of the float collapse.
    let q = QuantizedWide::from_bvh_merged(&ta, 0, &mut sa.quant_plain).unwrap();
    let mut wide = vec![WideNode::EMPTY; Wide::records_needed(&ta).unwrap()];
    let w = Wide::from_bvh(&ta, &mut wide).unwrap();
    // Same structure, looser boxes: never smaller, somewhere larger.
    let (mut looser, mut total) = (0, 0);
    for id in 0..(4 * w.records().len() as u32) {
        let (rec, k) = ((id / 4) as usize, (id % 4) as usize);
        if w.records()[rec].used() <= k {
            continue;
        }
        let (exact, coarse) = (w.bv(id), q.bv(id));
        assert!(coarse.contains_aabb(&exact));
        looser += (coarse != exact) as usize;
        total += 1;
    }
    assert!(looser > total / 2, "{looser} of {total} boxes grew");
    let mut counts = [bvhkit::Counts::default(); 2];
    let mut found = [0; 2];
    for (k, n) in [
        bvhkit::Pairs::new(&w, &a, &tb, &b)
            .counted(&mut counts[0])
            .count(),
        bvhkit::Pairs::new(&q, &a, &tb, &b)
            .counted(&mut counts[1])
            .count(),
    ]
    .into_iter()
    .enumerate()
    {
        found[k] = n.unwrap();
    }
    assert_eq!(found[0], found[1]);
    assert_eq!(found[0], brute_force::pairs(&a, &b, |_, _| {}));
    assert!(counts[1].bv_tests >= counts[0].bv_tests);
}

/// A wavy height field of `2 n^2` triangles, raised by `lift`.
fn bumpy(n: usize, lift: f32) -> Vec<Triangle> {
    let h = |x: usize, y: usize| {
        let (fx, fy) = (x as f32 * 0.37, y as f32 * 0.29);
        Vec3::new(x as f32, y as f32, fx.sin() * fy.cos() * 2.0 + lift)
    };
    let mut out = Vec::new();
    for y in 0..n {
        for x in 0..n {
            out.push(Triangle::new(h(x, y), h(x + 1, y), h(x, y + 1)));
            out.push(Triangle::new(h(x + 1, y), h(x + 1, y + 1), h(x, y + 1)));
        }
    }
    out
}

/// PITFALLS: trees of 1-3 leaves (far apart and touching) and coordinates
/// up to 1e30, in every layout, against brute force.
#[test]
fn tiny_trees_and_huge_coordinates_in_every_layout() {
    let tri = |o: Vec3, s: f32| Triangle::new(o, o + Vec3::X * s, o + Vec3::Y * s);
    for scale in [1.0f32, 1.0e28] {
        for n in 1..=3usize {
            for gap in [0.0f32, 0.5, 100.0] {
                let a: Vec<Triangle> = (0..n)
                    .map(|i| tri(Vec3::new(i as f32 * 1.5, 0.0, 0.0) * scale, scale))
                    .collect();
                let b: Vec<Triangle> = (0..n)
                    .map(|i| {
                        tri(
                            Vec3::new(i as f32 * 1.5 + gap + 0.2, 0.3, 0.0) * scale,
                            scale,
                        )
                    })
                    .collect();
                let cfg = TopDown::default().with_max_leaf_size(1);
                let (na, ia, _) = build::<Aabb, _>(&cfg, &a).unwrap();
                let (nb, ib, _) = build::<Aabb, _>(&cfg, &b).unwrap();
                let probe = (0.3, 0.6, 0.5);
                let ctx = format!("n {n}, gap {gap}, scale {scale:e}");
                run_all((&na, &ia), (&nb, &ib), &a, &b, probe).expect(&ctx);
                run_boxes((&na, &ia), (&nb, &ib), &a, &b, probe).expect(&ctx);
                let (na, ia, _) = build::<Sphere, _>(&cfg, &a).unwrap();
                let (nb, ib, _) = build::<Sphere, _>(&cfg, &b).unwrap();
                run_all((&na, &ia), (&nb, &ib), &a, &b, probe).expect(&ctx);
            }
        }
    }
}

/// Issue #18's memory target: the default quantized layout of the default
/// tree takes at most 12 bytes per triangle with its index array (obvhs's
/// compressed wide BVH takes 12.2 to 12.5 on the peer meshes), its records
/// alone at most 8; without merging it took over 13.
#[test]
fn quantized_layout_takes_at_most_12_bytes_per_triangle() {
    for (name, tris) in [
        ("rock(5)", bvhkit_std::scene::rock(5, 7)),
        ("bumpy(60)", bumpy(60, 0.0)),
    ] {
        let n = tris.len();
        let (nodes, idx, _) = build::<Aabb, _>(&TopDown::default(), &tris).unwrap();
        let t = open(&nodes, &idx, &tris);
        let per_tri = |merge: u32| {
            let mut recs =
                vec![QuantNode::EMPTY; QuantizedWide::records_needed_merged(&t, merge).unwrap()];
            let q = QuantizedWide::from_bvh_merged(&t, merge, &mut recs).unwrap();
            let records = std::mem::size_of_val(q.records()) as f64 / n as f64;
            (q.bytes() as f64 / n as f64, records)
        };
        let (total, records) = per_tri(QuantizedWide::MERGED_LEAF);
        let (plain, _) = per_tri(0);
        assert!(
            total <= 12.0,
            "{name}: {total:.2} B/tri with the index array"
        );
        assert!(records <= 8.0, "{name}: records take {records:.2} B/tri");
        assert!(plain > 13.0, "{name}: unmerged {plain:.2} B/tri");
        // `from_bvh` is the default merge.
        let mut recs = vec![QuantNode::EMPTY; QuantizedWide::records_needed(&t).unwrap()];
        let q = QuantizedWide::from_bvh(&t, &mut recs).unwrap();
        assert_eq!(q.bytes() as f64 / n as f64, total, "{name}");
    }
}

/// Merging never makes a leaf of more than the limit, and every merged leaf
/// is a subtree of the canonical tree whose entries were one run.
#[test]
fn merged_quantized_leaves_respect_the_limit() {
    let tris = bumpy(30, 0.0);
    let (nodes, idx, _) =
        build::<Aabb, _>(&TopDown::default().with_max_leaf_size(3), &tris).unwrap();
    let t = open(&nodes, &idx, &tris);
    for merge in [0, 1, 3, 4, 5, 8, 13, QuantizedWide::MAX_MERGED_LEAF] {
        let mut recs =
            vec![QuantNode::EMPTY; QuantizedWide::records_needed_merged(&t, merge).unwrap()];
        let q = QuantizedWide::from_bvh_merged(&t, merge, &mut recs).unwrap();
        let mut largest = 0;
        let mut stack = vec![q.root()];
        while let Some(n) = stack.pop() {
            match q.content(n) {
                Content::Leaf(ids) => largest = largest.max(ids.len()),
                Content::Inner(kids) => stack.extend_from_slice(kids.as_slice()),
            }
        }
        // Leaves of the tree itself hold up to 3; merged ones up to `merge`.
        assert!(
            largest <= (merge as usize).max(3),
            "merge {merge}: a leaf of {largest}"
        );
        if merge >= 8 {
            assert!(largest > 3, "merge {merge}: nothing merged");
        }
        check_contains(&q, &tris, "merged");
    }
    let mut recs = vec![QuantNode::EMPTY; 8];
    let too_many = QuantizedWide::MAX_MERGED_LEAF + 1;
    assert!(matches!(
        QuantizedWide::records_needed_merged(&t, too_many),
        Err(Error::FieldOverflow {
            value: 65,
            max: 64,
            ..
        })
    ));
    assert!(matches!(
        QuantizedWide::from_bvh_merged(&t, too_many, &mut recs),
        Err(Error::FieldOverflow {
            value: 65,
            max: 64,
            ..
        })
    ));
}

/// Balls and boxes dropped onto a terrain and thrown across it, on every
/// layout (binary and wide) of a box tree: the same first contact as brute
/// force, with about half the casts landing and the rest passing over or
/// beside.
#[test]
fn casts_onto_a_terrain_in_every_layout() {
    let ground = bumpy(20, 0.0);
    let cfg = TopDown::default();
    let (nodes, idx, _) = build::<Aabb, _>(&cfg, &ground).unwrap();
    let mut kept = vec![Aabb::EMPTY; ground.len()];
    let tree = keep_bounds(open(&nodes, &idx, &ground), &ground, &mut kept, true);
    let mut storage = Layouts::storage(&tree);
    let (mut hits, mut casts) = (0, 0);
    macro_rules! throw_at {
        ($name:expr, $view:expr) => {
            for k in 0..40 {
                let f = k as f32;
                let start = Vec3::new((f * 7.3) % 24.0 - 2.0, (f * 3.1) % 24.0 - 2.0, 6.0);
                let (dir, size) = if k % 3 == 0 {
                    (Vec3::new(1.0, 0.4, -0.05), 0.3 + (f * 0.13) % 1.5)
                } else {
                    (
                        Vec3::new(0.1 * (f % 5.0 - 2.0), 0.05, -1.0),
                        (f * 0.37) % 2.0,
                    )
                };
                hits += check_casts($view, &ground, start, dir, size, 40.0, $name).unwrap();
                casts += 3;
            }
        };
    }
    each_layout!(&tree, &mut storage, |name, view| {
        throw_at!(name, view);
    });
    each_box_layout!(&tree, &mut storage, |name, view| {
        throw_at!(name, view);
    });
    assert!(
        hits * 3 > casts && hits < casts,
        "{hits} of {casts} casts hit"
    );
}
