//! Quick timing of the pair query and ray casts per layout and leaf size
//! (medians), for tuning. The measured report is `bvhkit layouts`.
//!
//! Run: `cargo run --release -p bvhkit-std --features cli --example layout_speed`

use bvhkit::layout::{PreNode, Preorder, Wide, WideNode};
use bvhkit::{Aabb, Descent, Hierarchy, Pairs, Query, RayOrder, TopDown, Triangle};
use bvhkit_std::{layouts::rays, median_time, scene, OwnedBvh};

fn time<H: Hierarchy<Bv = Aabb>>(name: &str, ta: &H, tb: &H, a: &[Triangle], b: &[Triangle]) {
    let rs = rays(a, 20_000);
    for rule in [Descent::Larger, Descent::Simultaneous] {
        let (t, n) = median_time(31, || {
            Pairs::new(ta, a, tb, b).descent(rule).count().unwrap()
        });
        println!(
            "{name:<16} {:<13} pairs {n:>6} {:>8.3} ms",
            rule.name(),
            t.as_secs_f64() * 1e3
        );
    }
    let (t, _) = median_time(5, || {
        rs.iter()
            .filter(|r| {
                ta.cast_ray(a, r, RayOrder::DepthFirst, ())
                    .unwrap()
                    .is_some()
            })
            .count()
    });
    println!(
        "{name:<16} rays 20k             {:>8.3} ms",
        t.as_secs_f64() * 1e3
    );
}

fn main() {
    let (a, b) = scene::default_pair();
    for leaf in [1, 4] {
        let ta = OwnedBvh::<Aabb>::build(&TopDown::sah().with_max_leaf_size(leaf), &a).unwrap();
        let tb = OwnedBvh::<Aabb>::build(&TopDown::sah().with_max_leaf_size(leaf), &b).unwrap();
        let (va, vb) = (ta.view(), tb.view());
        time(&format!("canonical-{leaf}"), &va, &vb, &a, &b);
        let mut pa = vec![PreNode::<Aabb, u32>::EMPTY; va.node_count()];
        let mut pb = vec![PreNode::<Aabb, u32>::EMPTY; vb.node_count()];
        let (pa, pb) = (
            Preorder::from_bvh(&va, &mut pa).unwrap(),
            Preorder::from_bvh(&vb, &mut pb).unwrap(),
        );
        time(&format!("preorder-{leaf}"), &pa, &pb, &a, &b);
        let mut wa = vec![WideNode::EMPTY; Wide::records_needed(&va).unwrap()];
        let mut wb = vec![WideNode::EMPTY; Wide::records_needed(&vb).unwrap()];
        let (wa, wb) = (
            Wide::from_bvh(&va, &mut wa).unwrap(),
            Wide::from_bvh(&vb, &mut wb).unwrap(),
        );
        time(&format!("wide-{leaf}"), &wa, &wb, &a, &b);
    }
}
