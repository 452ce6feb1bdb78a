//! Which tree each builder makes, and how much each query prunes: checks that
//! fail when a tree gets worse even though every answer stays right.
//!
//! The property tests compare answers with brute force, but any valid tree
//! gives the same answers, so a builder, a measure or a pruning test could
//! get much worse without one of them failing. Here, on fixed scenes made in
//! the test:
//!
//! - every builder's tree (node and leaf counts, depth, largest leaf, SAH
//!   cost) is compared with the values recorded in `quality.recorded`;
//! - the node and primitive tests (`Nv`, `Np`) of fixed queries, for every
//!   traversal order and descent rule, are compared with the recorded ones;
//! - relations that must hold whatever the values are checked on their own
//!   (binned SAH close to the full sweep, SAH no worse than the median
//!   split, median children within one primitive, PLOC's radius).
//!
//! Builds are deterministic, so counts must match exactly and SAH costs to
//! a relative 1e-5 (room for a compiler reordering float sums, nothing
//! more). An intended change re-records with `BVHKIT_BLESS=1 cargo test -p
//! bvhkit-tests --test all quality::` and commits the new file with the reason.

use bvhkit::glam::Vec3;
use bvhkit::query::Counts;
use bvhkit::{
    Aabb, BoundingVolume, Descent, Kdop, Obb, Order, PairTraversal, Pairs, RayOrder, Sphere,
    TopDown, Triangle,
};
use bvhkit_std::builders::{catalogue, Builder};
use bvhkit_std::{scene, OwnedBvh};
use std::collections::BTreeMap;
use std::fmt::Write as _;

const RECORDED: &str = "quality.recorded";

/// The fixed scenes: a closed rock, a flat grid of quads, long slivers, and
/// tight clusters far apart (a few hundred triangles each, so the O(n^3)
/// textbook bottom-up build stays quick).
fn scenes() -> Vec<(&'static str, Vec<Triangle>)> {
    let mut grid = Vec::new();
    for i in 0..12 {
        for j in 0..12 {
            let p = Vec3::new(i as f32, 0.0, j as f32);
            grid.push(Triangle::new(p, p + Vec3::X, p + Vec3::Z));
            grid.push(Triangle::new(
                p + Vec3::X,
                p + Vec3::X + Vec3::Z,
                p + Vec3::Z,
            ));
        }
    }
    vec![
        ("rock", scene::rock(2, 7)),
        ("grid", grid),
        ("slivers", scene::slivers(240, 5)),
        ("clustered", scene::clustered(240, 9)),
    ]
}

/// What is recorded of a tree.
fn shape<B: BoundingVolume>(tree: &OwnedBvh<B>) -> String {
    let s = tree.view().stats();
    format!(
        "nodes {} leaves {} depth {} max_leaf {} sah {:.6e}",
        s.nodes, s.leaves, s.max_depth, s.max_leaf_size, s.sah_cost
    )
}

fn sah<B: BoundingVolume>(tree: &OwnedBvh<B>) -> f64 {
    tree.view().stats().sah_cost
}

/// Every measured line, keyed `section scene name`.
fn measure() -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    for (scene_name, tris) in scenes() {
        for (name, _, builder) in catalogue() {
            let tree = builder.build::<Aabb>(&tris).unwrap();
            out.insert(format!("tree {scene_name} {name}"), shape(&tree));
        }
        // The default build for every volume type.
        let default = TopDown::default();
        let sphere = OwnedBvh::<Sphere>::build(&default, &tris).unwrap();
        let obb = OwnedBvh::<Obb>::build(&default, &tris).unwrap();
        let kdop = OwnedBvh::<Kdop<7>>::build(&default, &tris).unwrap();
        out.insert(format!("tree {scene_name} default/sphere"), shape(&sphere));
        out.insert(format!("tree {scene_name} default/obb"), shape(&obb));
        out.insert(format!("tree {scene_name} default/dop14"), shape(&kdop));
    }
    prunes(&mut out);
    out
}

fn tally(c: &Counts) -> String {
    format!("nv {} np {}", c.bv_tests, c.prim_tests)
}

/// Node and primitive tests of fixed queries on the rock against a moved
/// copy: every pair traversal and descent rule, every region order, both ray
/// orders, nearest.
fn prunes(out: &mut BTreeMap<String, String>) {
    let (a, b) = scene::rock_pair(3);
    let ta = OwnedBvh::<Aabb>::build(&TopDown::default(), &a).unwrap();
    let tb = OwnedBvh::<Aabb>::build(&TopDown::default(), &b).unwrap();
    let (va, vb) = (ta.view(), tb.view());
    let mut pair_walks: Vec<(String, PairTraversal)> = Vec::new();
    for rule in Descent::ALL {
        pair_walks.push((
            format!("recursive/{}", rule.name()),
            PairTraversal::Recursive(rule),
        ));
        pair_walks.push((format!("stack/{}", rule.name()), PairTraversal::Stack(rule)));
    }
    pair_walks.push(("simultaneous".into(), PairTraversal::SIMULTANEOUS));
    pair_walks.push(("leaf-directed".into(), PairTraversal::LEAF_DIRECTED));
    for (name, walk) in pair_walks {
        let mut c = Counts::default();
        let n = Pairs::new(&va, &a, &vb, &b)
            .traversal(walk)
            .counted(&mut c)
            .count()
            .unwrap();
        out.insert(
            format!("prune pairs {name}"),
            format!("{} pairs {n}", tally(&c)),
        );
    }
    let region = Aabb::new(Vec3::new(-0.3, -0.3, -0.3), Vec3::new(0.4, 0.2, 1.5));
    let mut queue = vec![0u32; va.breadth_first_queue()];
    for (name, order) in [
        ("depth-first", Order::DepthFirst),
        ("recursive", Order::Recursive),
        ("breadth-first", Order::BreadthFirst(&mut queue)),
    ] {
        let mut c = Counts::default();
        let n = va.search(&a, &region, order, &mut c, |_| {}).unwrap();
        out.insert(
            format!("prune region {name}"),
            format!("{} found {n}", tally(&c)),
        );
    }
    let rays = bvhkit_std::layouts::rays(&a, 200);
    for (name, order) in [
        ("depth-first", RayOrder::DepthFirst),
        ("best-first", RayOrder::BestFirst),
    ] {
        let mut c = Counts::default();
        let hits = rays
            .iter()
            .filter(|r| va.cast_ray(&a, r, order, &mut c).unwrap().is_some())
            .count();
        out.insert(
            format!("prune rays {name}"),
            format!("{} hits {hits}", tally(&c)),
        );
    }
    let mut c = Counts::default();
    for k in 0..50 {
        let p = Vec3::new(
            (k as f32 * 0.37).sin(),
            (k as f32 * 0.91).cos(),
            0.02 * k as f32,
        ) * 2.0;
        va.nearest(&a, p, &mut c).unwrap().unwrap();
    }
    out.insert("prune nearest best-first".into(), tally(&c));
}

fn parse(text: &str) -> BTreeMap<String, String> {
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let (k, v) = l.split_once(" : ").expect("`key : value` lines");
            (k.to_string(), v.to_string())
        })
        .collect()
}

/// `a` and `b` agree: every word equal, except numbers with an exponent
/// (SAH costs), which agree to a relative 1e-5.
fn agree(a: &str, b: &str) -> bool {
    let (wa, wb): (Vec<_>, Vec<_>) = (a.split(' ').collect(), b.split(' ').collect());
    wa.len() == wb.len()
        && wa.iter().zip(&wb).all(|(x, y)| {
            x == y
                || (x.contains('e') && y.contains('e'))
                    && match (x.parse::<f64>(), y.parse::<f64>()) {
                        (Ok(p), Ok(q)) => (p - q).abs() <= 1e-5 * p.abs().max(q.abs()),
                        _ => false,
                    }
        })
}

#[test]
fn trees_and_pruning_match_the_recorded_values() {
    let got = measure();
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(RECORDED);
    if std::env::var_os("BVHKIT_BLESS").is_some() {
        let mut text = String::from(
            "# Recorded by tests/tests/all/quality.rs (BVHKIT_BLESS=1 cargo test -p bvhkit-tests --test all quality::).\n\
             # A change here must say in its commit why the trees or the pruning changed.\n",
        );
        for (k, v) in &got {
            writeln!(text, "{k} : {v}").unwrap();
        }
        std::fs::write(&path, text).unwrap();
        return;
    }
    let want = parse(
        &std::fs::read_to_string(&path).expect("the recorded values, tests/quality.recorded"),
    );
    let mut differences = Vec::new();
    for (k, v) in &got {
        match want.get(k) {
            Some(w) if agree(v, w) => {}
            Some(w) => differences.push(format!("{k}\n    recorded {w}\n    now      {v}")),
            None => differences.push(format!("{k}: not recorded (now {v})")),
        }
    }
    for k in want.keys().filter(|k| !got.contains_key(*k)) {
        differences.push(format!("{k}: recorded but no longer measured"));
    }
    assert!(
        differences.is_empty(),
        "{} trees or queries differ from tests/quality.recorded (if intended, re-record with \
         BVHKIT_BLESS=1 and say why in the commit):\n{}",
        differences.len(),
        differences.join("\n")
    );
}

#[test]
fn the_recorded_check_catches_a_changed_value() {
    assert!(agree("nodes 5 sah 1.000000e1", "nodes 5 sah 1.000001e1"));
    assert!(!agree("nodes 5 sah 1.000000e1", "nodes 5 sah 1.000100e1"));
    assert!(!agree("nodes 5 sah 1.000000e1", "nodes 6 sah 1.000000e1"));
    assert!(!agree("nv 10 np 4", "nv 11 np 4"));
    assert!(!agree("nv 10", "nv 10 np 4"));
}

fn by_name(name: &str) -> Builder {
    Builder::by_name(name).unwrap()
}

/// Relations between builders that hold whatever the recorded values are.
#[test]
fn builders_keep_their_relations_on_every_scene() {
    for (scene_name, tris) in scenes() {
        let cost = |name: &str| sah(&by_name(name).build::<Aabb>(&tris).unwrap());
        let (binned, sweep, median) = (cost("sah"), cost("sah-sweep"), cost("median"));
        eprintln!(
            "{scene_name}: sah {binned:.3} sweep {sweep:.3} median {median:.3} ploc r1 {:.3} r16 {:.3} exhaustive {:.3}",
            cost("ploc-r1"),
            cost("ploc-r16"),
            cost("bottom-up-exhaustive")
        );
        // Binning approximates the full sweep closely.
        assert!(
            binned <= sweep * 1.05,
            "{scene_name}: binned SAH {binned:.3} > 1.05 x sweep {sweep:.3}"
        );
        // Choosing splits by SAH beats splitting at the median, by SAH.
        assert!(
            binned <= median * 1.001,
            "{scene_name}: SAH build {binned:.3} worse than the median split {median:.3}"
        );
        // A wider PLOC search does not make a much worse tree than radius
        // 1. Greedy merging can lose with more candidates where every merge
        // costs the same (the grid: r16 is 17% worse there, r4 as good as
        // r1), so the grid gets a wider margin; on the other scenes the
        // wider search is as good or better.
        let (r1, r16) = (cost("ploc-r1"), cost("ploc-r16"));
        let margin = if scene_name == "grid" { 1.20 } else { 1.02 };
        assert!(
            r16 <= r1 * margin,
            "{scene_name}: PLOC r16 {r16:.3} > {margin} x r1 {r1:.3}"
        );
        // The textbook bottom-up search (best pair of all) is no worse than PLOC r1.
        let exhaustive = cost("bottom-up-exhaustive");
        assert!(
            exhaustive <= r1 * 1.05,
            "{scene_name}: exhaustive bottom-up {exhaustive:.3} > 1.05 x PLOC r1 {r1:.3}"
        );
    }
}

/// The object median halves the primitives at every split: the two
/// children's primitive counts differ by at most one.
#[test]
fn median_split_children_differ_by_at_most_one_primitive() {
    for (scene_name, tris) in scenes() {
        let tree = by_name("median").build::<Aabb>(&tris).unwrap();
        let v = tree.view();
        let nodes = v.nodes();
        fn count(nodes: &[bvhkit::Node<Aabb>], n: usize) -> usize {
            match nodes[n].children() {
                Some((l, r)) => count(nodes, l as usize) + count(nodes, r as usize),
                None => nodes[n].count as usize,
            }
        }
        let mut splits = 0;
        for n in 0..v.node_count() {
            if let Some((l, r)) = nodes[n].children() {
                let (cl, cr) = (count(nodes, l as usize), count(nodes, r as usize));
                assert!(
                    cl.abs_diff(cr) <= 1,
                    "{scene_name}: node {n} splits {} into {cl} + {cr}",
                    cl + cr
                );
                splits += 1;
            }
        }
        assert!(splits > 50, "{scene_name}: only {splits} splits");
    }
}
