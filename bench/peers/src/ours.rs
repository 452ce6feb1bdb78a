//! bvhkit itself, as a user runs it: the default builder (`TopDown::default()`,
//! binned SAH) with the default queries (`Pairs::new(..)`, `cast_ray` with
//! `RayOrder::default()`), the same tree in the 4-wide and quantized 4-wide
//! layouts, and PLOC (`BottomUp::default()`, and at radius 1) as fast builders.
//!
//! Trees are built from the scene's boxes (`Aabb` is a `Primitive`), the
//! input every crate gets; the pair query reports pairs of those boxes, and
//! rays test the triangles through the same indices.

use crate::common::{sah, time, Measured, PairSum, RayHit, Runs, Scene, Timing};
use bvhkit::builders::{BottomUp, Collapse, Method};
use bvhkit::layout::{QuantNode, QuantizedWide, Wide, WideNode};
use bvhkit::{Aabb, Bvh, Hierarchy, Pairs, Query, RayOrder, TopDown};
use bvhkit_std::OwnedBvh;

/// Builds and queries bvhkit's trees on `scene`.
pub fn run(scene: &Scene, runs: Runs) -> Vec<Measured> {
    let default = TopDown::default();
    let top_down = |boxes: &[Aabb]| OwnedBvh::<Aabb>::build(&default, boxes).expect("builds");
    let (build, a) = time(runs.build, || top_down(&scene.boxes_a));
    let b = top_down(&scene.boxes_b);
    let (va, vb) = (a.view(), b.view());
    let mut rows = vec![measure(scene, runs, "sah", build, &va, &vb, &va)];

    // The same tree collapsed to 4-wide nodes, and quantized to 8 bits per
    // coordinate (64-byte nodes). Build time = the sah build + the collapse,
    // each timed on its own (median plus median, minimum plus minimum).
    let sah_build = build;
    macro_rules! layout {
        ($name:expr, $layout:ident, $empty:expr, $va:expr, $vb:expr) => {{
            let (va, vb) = ($va, $vb);
            let convert = |t: &Bvh<'_, Aabb>| {
                let mut records = vec![$empty; $layout::records_needed(t).expect("fits")];
                $layout::from_bvh(t, &mut records).expect("converts");
                records
            };
            let (collapse, mut ra) = time(runs.build, || convert(&va));
            let mut rb = convert(&vb);
            let la = $layout::from_bvh(&va, &mut ra).expect("converts");
            let lb = $layout::from_bvh(&vb, &mut rb).expect("converts");
            let build = Timing {
                median_ms: sah_build.median_ms + collapse.median_ms,
                min_ms: sah_build.min_ms + collapse.min_ms,
            };
            rows.push(measure(scene, runs, $name, build, &la, &lb, &va));
        }};
    }
    // The 4-wide layout shares the kept leaf bounds (the fast pair query);
    // the quantized one is the compact layout, without them.
    layout!("sah/wide4", Wide, WideNode::EMPTY, va, vb);
    let (pa, pb) = (a.plain_view(), b.plain_view());
    layout!("sah/quantized4", QuantizedWide, QuantNode::EMPTY, pa, pb);

    // PLOC with the default leaf collapse: the default search radius, and
    // radius 1 (the radius of obvhs's fastest preset); and radius 1 with one
    // primitive per leaf, as obvhs's fastest preset leaves its tree.
    let r1 = BottomUp {
        method: Method::Ploc { radius: 1 },
        ..BottomUp::default()
    };
    for (name, builder) in [
        ("ploc", BottomUp::default()),
        ("ploc-r1", r1),
        (
            "ploc-r1-1leaf",
            BottomUp {
                collapse: Collapse::None,
                ..r1
            },
        ),
    ] {
        let ploc =
            |boxes: &[Aabb]| OwnedBvh::<Aabb>::build_bottom_up(&builder, boxes).expect("builds");
        let (build, a) = time(runs.build, || ploc(&scene.boxes_a));
        let b = ploc(&scene.boxes_b);
        let (va, vb) = (a.view(), b.view());
        rows.push(measure(scene, runs, name, build, &va, &vb, &va));
    }
    rows
}

/// Queries one pair of trees (any layout) and scores the binary tree it
/// came from.
fn measure<H: Hierarchy<Bv = Aabb>>(
    scene: &Scene,
    runs: Runs,
    builder: &str,
    build: Timing,
    a: &H,
    b: &H,
    binary: &Bvh<'_, Aabb>,
) -> Measured {
    let pairs = time(runs.pairs, || {
        let mut sum = PairSum::default();
        Pairs::new(a, &scene.boxes_a, b, &scene.boxes_b)
            .for_each(|i, j| sum.add(i, j))
            .expect("pair query");
        sum
    });
    let rays = time(runs.rays, || {
        scene
            .rays
            .iter()
            .map(|r| -> RayHit {
                a.cast_ray(&scene.a, r, RayOrder::default(), ())
                    .expect("ray query")
                    .map(|h| (h.prim, h.t))
            })
            .collect::<Vec<_>>()
    });
    let nodes = binary.nodes();
    let leaves = nodes.iter().filter(|n| n.children().is_none()).count();
    let wide = builder.contains('/');
    Measured {
        krate: "bvhkit",
        builder: builder.to_string(),
        build,
        leaves,
        sah: (!wide).then(|| {
            let counts = nodes
                .iter()
                .map(|n| (n.bv, if n.children().is_none() { n.count } else { 0 }));
            sah(&nodes[0].bv, counts)
        }),
        bytes: a.bytes(),
        pairs: Some(pairs),
        rays: Some(rays),
        note: if builder == "sah/quantized4" {
            "the sah tree collapsed to quantized 4-wide nodes, without kept leaf bounds \
             (build includes the collapse)"
        } else if wide {
            "the sah tree collapsed to 4-wide nodes, sharing its kept leaf bounds \
             (build includes the collapse)"
        } else if builder == "ploc" {
            "BottomUp::default() (PLOC, radius 16, leaves collapsed by SAH to <= 4), \
             OwnedBvh::build_bottom_up"
        } else if builder == "ploc-r1" {
            "BottomUp with Method::Ploc { radius: 1 } (leaves collapsed by SAH to <= 4), \
             OwnedBvh::build_bottom_up"
        } else if builder == "ploc-r1-1leaf" {
            "BottomUp with Method::Ploc { radius: 1 } and Collapse::None (one primitive \
             per leaf, as obvhs fastest_build), OwnedBvh::build_bottom_up"
        } else {
            "TopDown::default() (binned SAH, 16 bins, <= 4 per leaf), OwnedBvh::build \
             (primitive bounds kept in leaf order)"
        },
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn answers_match_brute_force() {
        let m = crate::common::reference::run_and_check(super::run);
        assert_eq!(m.len(), 6);
    }
}
