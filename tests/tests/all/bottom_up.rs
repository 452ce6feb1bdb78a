//! Bottom-up builders (exhaustive and PLOC) against brute force, for every
//! volume type, plus their pitfalls.

use bvhkit::builders::{BottomUp, Collapse, MergeMetric, Method};
use bvhkit::glam::Vec3;
use bvhkit::{
    brute_force, Aabb, BoundingVolume, Bounds, Dop14, Error, Exact, Obb, PairTraversal, Pairs,
    Rigid, Same, Sphere, TopDown, Triangle,
};
use bvhkit_tests::*;
use proptest::prelude::*;

fn any_bottom_up(max_exhaustive: usize, n: usize) -> impl Strategy<Value = BottomUp> {
    let exhaustive_ok = n <= max_exhaustive;
    let collapse = prop_oneof![
        Just(Collapse::None),
        (0u32..10, 0.0f32..4.0).prop_map(|(max_leaf_size, traversal_cost)| Collapse::Sah {
            max_leaf_size,
            traversal_cost
        })
    ];
    (any::<bool>(), 1u32..20, any::<bool>(), collapse).prop_map(
        move |(exhaustive, radius, area, collapse)| BottomUp {
            method: if exhaustive && exhaustive_ok {
                Method::Exhaustive
            } else {
                Method::Ploc { radius }
            },
            metric: if area {
                MergeMetric::SurfaceArea
            } else {
                MergeMetric::Volume
            },
            collapse,
        },
    )
}

fn check<B: BoundingVolume>(
    cfg: &BottomUp,
    a: &[Triangle],
    b: &[Triangle],
    region: &Aabb,
) -> Result<(), TestCaseError> {
    let (na, ia, _) =
        build_bottom_up::<B, _>(cfg, a).map_err(|e| TestCaseError::fail(format!("{e}")))?;
    let (nb, ib, _) =
        build_bottom_up::<B, _>(cfg, b).map_err(|e| TestCaseError::fail(format!("{e}")))?;
    // `open` validates: every node contains its children and primitives.
    let (ta, tb) = (open(&na, &ia, a), open(&nb, &ib, b));
    let mut got = Vec::new();
    ta.overlapping(a, region, |i| got.push(i)).unwrap();
    got.sort_unstable();
    let mut want = Vec::new();
    brute_force::overlapping(a, region, |i| want.push(i));
    prop_assert_eq!(got, want, "{} region {:?}", B::NAME, cfg);
    let shown = TopDown::default(); // only printed in failure messages
    check_pairs(&ta, a, &tb, b, &Same, Bounds, &shown)?;
    let m = Rigid::new(
        bvhkit::glam::Quat::from_rotation_z(0.3),
        Vec3::new(0.1, 0.0, 0.0),
    )
    .unwrap();
    check_pairs(&ta, a, &tb, b, &m, Exact, &shown)
}

proptest! {
    #![proptest_config(proptest_config(32))]

    #[test]
    fn bottom_up_trees_match_brute_force(
        (a, cfg) in scene(40).prop_flat_map(|a| { let n = a.len(); (Just(a), any_bottom_up(40, n)) }),
        b in scene(40),
        r in (0.0f32..1.0, 0.0f32..1.0),
    ) {
        let region = region_in(&a, r.0, r.1);
        check::<Aabb>(&cfg, &a, &b, &region)?;
        check::<Sphere>(&cfg, &a, &b, &region)?;
        check::<Obb>(&cfg, &a, &b, &region)?;
        check::<bvhkit::ObbDito>(&cfg, &a, &b, &region)?;
        check::<Dop14>(&cfg, &a, &b, &region)?;
        // Exact k-DOP measures steer the merges: another tree, the same answers.
        check::<bvhkit::ExactKdop<7>>(&cfg, &a, &b, &region)?;
    }
}

/// n = 1, 2, 3 for both methods.
#[test]
fn tiny_inputs_build() {
    for n in 1..=3 {
        let tris: Vec<_> = (0..n)
            .map(|i| {
                Triangle::new(
                    Vec3::X * i as f32,
                    Vec3::X * i as f32 + Vec3::Y,
                    Vec3::X * i as f32 + Vec3::Z,
                )
            })
            .collect();
        for cfg in [
            BottomUp::exhaustive(MergeMetric::Volume),
            BottomUp::default(),
        ] {
            let (nodes, idx, depth) = build_bottom_up::<Aabb, _>(&cfg, &tris).unwrap();
            let t = open(&nodes, &idx, &tris);
            // One triangle per leaf; the default collapses these few
            // neighbours into one leaf (3 * A(2x1x1) = 30 against
            // 2 * 10 + 2 * 6 + 2 in surface areas, for three).
            let want = if cfg.collapse == Collapse::None {
                2 * n - 1
            } else {
                1
            };
            assert_eq!(t.node_count(), want, "{cfg:?}");
            assert!(depth < n.max(1));
        }
    }
}

/// The scenes PLOC used to refuse ("tree depth 65 exceeds the traversal
/// stack capacity 64"): identical triangles (equal costs everywhere), a
/// geometric progression (merging is always cheapest at the small end, a
/// chain), and a scene 1e30 wide (areas overflowed f32). Every builder
/// builds them, no deeper than MAX_DEPTH, and answers like brute force.
#[test]
fn adversarial_scenes_build_and_answer_like_brute_force() {
    let tri = |o: Vec3, s: f32| Triangle::new(o, o + Vec3::X * s, o + Vec3::Y * s);
    let identical = vec![tri(Vec3::ZERO, 1.0); 300];
    let graded: Vec<Triangle> = (0..120)
        .map(|i| {
            let x = 1e-12 * 1.5f32.powi(i);
            tri(Vec3::new(x, 0.0, 0.0), x * 0.1)
        })
        .collect();
    let mut state = 7u64;
    let mut uniform = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    let huge: Vec<Triangle> = (0..600)
        .map(|_| {
            let o = Vec3::new(uniform(), uniform(), uniform()) * 1e30;
            tri(o, 1e28 * (0.1 + uniform()))
        })
        .collect();
    let points: Vec<Vec3> = (0..90)
        .map(|i| Vec3::new(1.3f32.powi(i), 0.0, 0.0))
        .collect();
    let builders = [
        BottomUp::default(),
        BottomUp {
            method: Method::Ploc { radius: 1 },
            collapse: Collapse::None,
            ..BottomUp::default()
        },
        BottomUp {
            method: Method::Ploc { radius: 16 },
            metric: MergeMetric::Volume,
            collapse: Collapse::Sah {
                max_leaf_size: 8,
                traversal_cost: 3.0,
            },
        },
    ];
    for (name, scene) in [
        ("identical", &identical),
        ("graded", &graded),
        ("1e30", &huge),
    ] {
        for cfg in builders {
            let (nodes, idx, depth) = build_bottom_up::<Aabb, _>(&cfg, scene)
                .unwrap_or_else(|e| panic!("{name} {cfg:?}: {e}"));
            assert!(depth <= bvhkit::MAX_DEPTH, "{name} {cfg:?}: depth {depth}");
            let t = open(&nodes, &idx, scene);
            let m = Rigid::translation(Vec3::X * 1e-13).unwrap();
            let mut want = Vec::new();
            brute_force::pairs_placed(scene, scene, &m, Exact, |i, j| want.push((i, j)));
            want.sort_unstable();
            for traversal in [PairTraversal::default(), PairTraversal::LeafDirected] {
                let mut got = Vec::new();
                Pairs::new(&t, scene, &t, scene)
                    .traversal(traversal)
                    .in_frame(m)
                    .exact()
                    .for_each(|i, j| got.push((i, j)))
                    .unwrap();
                got.sort_unstable();
                // Not `assert_eq!`: a million pairs would be printed.
                assert!(
                    got == want,
                    "{name} {cfg:?} {traversal:?}: {} pairs, want {}",
                    got.len(),
                    want.len()
                );
            }
            if name == "identical" {
                // Equal costs pair up and halve: a balanced tree.
                assert!(depth <= 10, "{cfg:?}: identical triangles to depth {depth}");
            }
        }
        // Other volumes: the rebuilt subtrees' parents still contain them
        // (`open` validates containment).
        let cfg = BottomUp::default();
        let (nodes, idx, _) = build_bottom_up::<Sphere, _>(&cfg, scene).unwrap();
        open(&nodes, &idx, scene);
        let (nodes, idx, _) = build_bottom_up::<Obb, _>(&cfg, scene).unwrap();
        open(&nodes, &idx, scene);
    }
    // Costs in the scene's unit: at 1e30, PLOC's tree is as good as usual
    // against the top-down SAH tree (in raw f32, every merge wider than
    // about 1e19 cost infinity, and all of them tied).
    let sah = |nodes: &[bvhkit::Node<Aabb>], idx: &[u32], scene: &[Triangle]| {
        open(nodes, idx, scene).stats().sah_cost
    };
    // One primitive per leaf on both sides: the merges are what is compared.
    let merges_only = BottomUp {
        collapse: Collapse::None,
        ..BottomUp::default()
    };
    let (n1, i1, _) = build_bottom_up::<Aabb, _>(&merges_only, &huge).unwrap();
    let (n2, i2, _) = build::<Aabb, _>(&TopDown::sah().with_max_leaf_size(1), &huge).unwrap();
    let (ploc, top_down) = (sah(&n1, &i1, &huge), sah(&n2, &i2, &huge));
    assert!(
        ploc < 1.2 * top_down,
        "PLOC SAH {ploc} against top-down {top_down}"
    );
    for cfg in [
        BottomUp::exhaustive(MergeMetric::SurfaceArea),
        BottomUp::default(),
    ] {
        let (_, _, depth) = build_bottom_up::<Aabb, _>(&cfg, &points).unwrap();
        assert!(depth <= bvhkit::MAX_DEPTH);
        let (_, _, depth) = build_bottom_up::<Aabb, _>(&cfg, &graded[..100]).unwrap();
        assert!(depth <= bvhkit::MAX_DEPTH, "{cfg:?}: {depth}");
    }
}

#[test]
fn bad_input_and_small_buffers_are_errors() {
    let cfg = BottomUp::default();
    // No primitives is not bad input: it builds the empty tree (tests/empty.rs).
    assert_eq!(build_bottom_up::<Aabb, Triangle>(&cfg, &[]).unwrap().2, 0);
    let nan = [Triangle::new(Vec3::NAN, Vec3::X, Vec3::Y)];
    assert!(matches!(
        build_bottom_up::<Aabb, _>(&cfg, &nan),
        Err(Error::NonFiniteCoordinate { primitive: 0 })
    ));
    let bad_radius = BottomUp {
        method: Method::Ploc { radius: 0 },
        ..BottomUp::default()
    };
    let tris = [Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y); 4];
    assert!(build_bottom_up::<Aabb, _>(&bad_radius, &tris).is_err());
    // Scratch too small.
    use bvhkit::builders::{BottomUpScratch, Cluster};
    let mut clusters = vec![Cluster::<Aabb>::EMPTY; 3];
    let (mut work, mut keys) = (vec![0u32; 8], vec![0u64; 4]);
    let mut scratch = BottomUpScratch {
        clusters: &mut clusters,
        work: &mut work,
        keys: &mut keys,
    };
    let mut nodes = vec![bvhkit::Node::<Aabb>::EMPTY; 7];
    let mut idx = vec![0u32; 4];
    assert!(cfg
        .build(&tris, &mut nodes, &mut idx, &mut scratch)
        .is_err());
}

/// The exhaustive builder really merges the globally smallest pair first:
/// with three clustered boxes and one far away, the far one joins last.
#[test]
fn exhaustive_merges_the_smallest_pair_first() {
    let boxes = [
        Aabb::new(Vec3::ZERO, Vec3::ONE),
        Aabb::new(Vec3::new(1.1, 0.0, 0.0), Vec3::new(2.1, 1.0, 1.0)),
        Aabb::new(Vec3::new(50.0, 0.0, 0.0), Vec3::new(51.0, 1.0, 1.0)),
        Aabb::new(Vec3::new(0.0, 1.2, 0.0), Vec3::new(1.0, 2.2, 1.0)),
    ];
    let (nodes, idx, _) =
        build_bottom_up::<Aabb, _>(&BottomUp::exhaustive(MergeMetric::Volume), &boxes).unwrap();
    let t = open(&nodes, &idx, &boxes);
    let (l, r) = t.root().unwrap().children().unwrap();
    let leaf_sides: Vec<bool> = [l, r]
        .iter()
        .map(|&c| t.nodes()[c as usize].is_leaf())
        .collect();
    // One side of the root is the far box alone.
    let far_side = [l, r]
        .into_iter()
        .find(|&c| t.nodes()[c as usize].is_leaf())
        .expect("a leaf child");
    assert_eq!(t.leaf_primitives(&t.nodes()[far_side as usize]), &[2]);
    assert_eq!(leaf_sides.iter().filter(|x| **x).count(), 1);
}

/// PLOC written the plain way: a comparison sort of (Morton code, index),
/// every pair cost computed from both sides, ties as documented. The
/// builder caches pair costs and radix-sorts; its trees must be the same.
fn plain_ploc(boxes: &[Aabb], radius: usize) -> String {
    fn spread(v: u32) -> u32 {
        let mut v = v & 0x3ff;
        v = (v | (v << 16)) & 0x030000ff;
        v = (v | (v << 8)) & 0x0300f00f;
        v = (v | (v << 4)) & 0x030c30c3;
        (v | (v << 2)) & 0x09249249
    }
    let n = boxes.len();
    let scene = boxes.iter().fold(Aabb::EMPTY, |s, b| s.union(b));
    let scale = 1.0 / scene.extent().max_element();
    let mut centres = Aabb::EMPTY;
    for b in boxes {
        centres.grow(b.center());
    }
    let ext = centres.extent();
    let mut keys: Vec<u64> = (0..n)
        .map(|i| {
            let c = boxes[i].center();
            let q: [u32; 3] = core::array::from_fn(|k| {
                let t = if ext[k] > 0.0 {
                    (c[k] - centres.min[k]) / ext[k]
                } else {
                    0.0
                };
                (t.clamp(0.0, 1.0) * 1023.0) as u32
            });
            let code = spread(q[0]) | spread(q[1]) << 1 | spread(q[2]) << 2;
            (code as u64) << 32 | i as u64
        })
        .collect();
    keys.sort();
    // (box, text of the subtree)
    let mut active: Vec<(Aabb, String)> = keys
        .iter()
        .map(|&k| (boxes[k as u32 as usize], (k as u32).to_string()))
        .collect();
    let tie = |i: usize, j: usize, cur: usize| {
        cur == i || {
            let (dj, dc) = (i.abs_diff(j), i.abs_diff(cur));
            dj < dc || (dj == dc && j == i ^ 1)
        }
    };
    while active.len() > 1 {
        let k = active.len();
        let nearest: Vec<usize> = (0..k)
            .map(|i| {
                let (mut best, mut partner) = (f32::INFINITY, i);
                for j in i.saturating_sub(radius)..(i + radius + 1).min(k) {
                    if j == i {
                        continue;
                    }
                    let c = BoundingVolume::surface_area_scaled(
                        &active[i].0.union(&active[j].0),
                        scale,
                    );
                    if c < best || (c == best && tie(i, j, partner)) {
                        (best, partner) = (c, j);
                    }
                }
                partner
            })
            .collect();
        let mut next = Vec::new();
        let mut gone = vec![false; k];
        for i in 0..k {
            let j = nearest[i];
            if gone[i] {
                continue;
            }
            if j > i && nearest[j] == i {
                gone[j] = true;
                let b = active[i].0.union(&active[j].0);
                next.push((b, format!("({},{})", active[i].1, active[j].1)));
            } else {
                next.push(active[i].clone());
            }
        }
        assert!(next.len() < k, "the plain PLOC always merges a pair");
        active = next;
    }
    active.pop().map(|(_, s)| s).unwrap_or_default()
}

/// The same text for a built tree: a leaf is its primitive, an inner node
/// `(left,right)`.
fn shape(nodes: &[bvhkit::Node<Aabb>], indices: &[u32], at: usize) -> String {
    let node = &nodes[at];
    match node.children() {
        Some((l, r)) => format!(
            "({},{})",
            shape(nodes, indices, l as usize),
            shape(nodes, indices, r as usize)
        ),
        None => indices[node.first as usize].to_string(),
    }
}

#[test]
fn ploc_equals_the_plain_algorithm() {
    // A rock (curved, no ties) and a grid (many equal costs): every radius
    // the cost cache holds, and wider ones, which recompute.
    let mut scenes = vec![bvhkit_std::scene::rock(2, 7)];
    scenes.push(
        (0..300)
            .map(|i| {
                let o = Vec3::new((i % 17) as f32, (i / 17) as f32, 0.0);
                Triangle::new(o, o + Vec3::X * 0.5, o + Vec3::Y * 0.5)
            })
            .collect(),
    );
    for tris in &scenes {
        let boxes: Vec<Aabb> = tris.iter().map(bvhkit::Primitive::bounds).collect();
        for radius in [1, 2, 5, 16, 17, 40] {
            let cfg = BottomUp {
                method: Method::Ploc {
                    radius: radius as u32,
                },
                // The reference merges only: one primitive per leaf.
                collapse: Collapse::None,
                ..BottomUp::default()
            };
            let (nodes, indices, _) = build_bottom_up::<Aabb, _>(&cfg, &boxes).unwrap();
            assert_eq!(
                shape(&nodes, &indices, 0),
                plain_ploc(&boxes, radius),
                "radius {radius}, {} primitives",
                boxes.len()
            );
        }
    }
}

/// PLOC without a collapse builds straight into the node buffer and needs
/// no cluster scratch: the same tree as with it, except that a tree too
/// deep to traverse is then refused (there is nowhere to rebuild it), while
/// `OwnedBvh` retries with the clusters and limits the depth.
#[test]
fn ploc_without_a_collapse_needs_no_clusters() {
    use bvhkit::builders::{BottomUpScratch, Cluster};
    let build = |cfg: &BottomUp, prims: &[Triangle], clusters: usize| {
        let n = prims.len();
        let (_, nw, nk) = BottomUp::scratch_len(n);
        let mut clusters = vec![Cluster::<Aabb>::EMPTY; clusters];
        let (mut work, mut keys) = (vec![0u32; nw], vec![0u64; nk]);
        let mut scratch = BottomUpScratch {
            clusters: &mut clusters,
            work: &mut work,
            keys: &mut keys,
        };
        let mut nodes = vec![bvhkit::Node::<Aabb>::EMPTY; bvhkit::max_nodes(n)];
        let mut idx = vec![0u32; n];
        cfg.build(prims, &mut nodes, &mut idx, &mut scratch)
            .map(|t| {
                (
                    t.nodes().to_vec(),
                    t.indices().to_vec(),
                    t.depth(),
                    t.build_report(),
                )
            })
    };
    let cloud = bvhkit_std::scene::rock(2, 3);
    // Each merge is cheapest at the small end: a chain.
    let chain: Vec<Triangle> = (0..200)
        .map(|i| {
            let x = 1e-12 * 1.5f32.powi(i);
            let o = Vec3::new(x, 0.0, 0.0);
            Triangle::new(o, o + Vec3::X * x * 0.1, o + Vec3::Y * x * 0.1)
        })
        .collect();
    for radius in [1, 4] {
        let lean = BottomUp {
            method: Method::Ploc { radius },
            collapse: Collapse::None,
            ..BottomUp::default()
        };
        assert!(!lean.needs_clusters());
        let nc = bvhkit::max_nodes(cloud.len());
        assert_eq!(build(&lean, &cloud, 0), build(&lean, &cloud, nc));
        // The chain is deeper than MAX_DEPTH as merged.
        let refused = build(&lean, &chain, 0)
            .map(|x| (x.2, x.3))
            .expect_err("refused");
        assert!(
            matches!(refused, Error::StackOverflow { depth, capacity }
                if depth > bvhkit::MAX_DEPTH && capacity == bvhkit::MAX_DEPTH),
            "{refused:?}"
        );
        let (_, _, depth, report) = build(&lean, &chain, bvhkit::max_nodes(200)).unwrap();
        assert!(depth <= bvhkit::MAX_DEPTH && report.depth_limited > 0);
        let owned = bvhkit_std::OwnedBvh::<Aabb>::build_bottom_up(&lean, &chain).unwrap();
        assert_eq!(owned.view().depth(), depth);
        assert_eq!(owned.view().build_report(), report);
    }
    // A collapse, or the exhaustive method, needs them all.
    for cfg in [
        BottomUp::default(),
        BottomUp::exhaustive(MergeMetric::SurfaceArea),
    ] {
        assert!(cfg.needs_clusters());
        assert!(matches!(
            build(&cfg, &cloud[..50], 10),
            Err(Error::InvalidConfig(_))
        ));
    }
}
