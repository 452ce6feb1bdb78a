//! What leaf collapse buys bottom-up and insertion trees: build time, nodes,
//! SAH cost, the pair query (a mesh against a copy turned by 0.02 rad and
//! shifted by 1% of its box, as the peer benchmark runs it) and closest-hit
//! rays, for PLOC and insertion trees with each collapse, beside the default
//! top-down tree. Medians; every answer checked equal to the top-down
//! tree's. `cargo run --release -p bvhkit-std --features cli --example collapse_sweep --
//! [--runs N] [MESH...]` (the mesh defaults to the armadillo of
//! `scripts/fetch-meshes`; a mesh that does not load is replaced by the
//! built-in rock). `scripts/book-measure collapse` records it for the book.
use bvhkit::builders::{BottomUp, Collapse, Insertion, Method};
use bvhkit::glam::Vec3;
use bvhkit::{Aabb, Pairs, Primitive, Ray, RayOrder, TopDown, Triangle};
use bvhkit_std::{median_time, scene, OwnedBvh};
use std::time::Instant;

fn main() {
    let mut runs = 15usize;
    let mut paths = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        if a == "--runs" {
            runs = args.next().and_then(|r| r.parse().ok()).expect("--runs N");
        } else {
            paths.push(a);
        }
    }
    if paths.is_empty() {
        paths.push("data/meshes/armadillo.off".into());
    }
    let sah = |c, t| Collapse::Sah {
        max_leaf_size: c,
        traversal_cost: t,
    };
    let collapses = [
        ("none", Collapse::None),
        ("4, ct 1", sah(4, 1.0)),
        ("4, ct 2", sah(4, 2.0)),
        ("4, ct 3 (default)", Collapse::DEFAULT),
        ("8, ct 3", sah(8, 3.0)),
    ];
    println!(
        "20,000 rays per mesh, medians of {runs} queries and of {} builds",
        runs.clamp(1, 5)
    );
    println!();
    println!("| mesh | tree | collapse | build ms | nodes | SAH | pairs ms | rays ms |");
    println!("|---|---|---|---:|---:|---:|---:|---:|");
    for path in &paths {
        let a: Vec<Triangle> = match bvhkit_std::mesh::load(std::path::Path::new(path)) {
            Ok(m) => m,
            Err(e) => {
                eprintln!("{e}: the built-in rock instead");
                scene::rock(4, 5)
            }
        };
        let name = std::path::Path::new(path)
            .file_stem()
            .map_or("rock".into(), |s| s.to_string_lossy().into_owned());
        let boxes_a: Vec<Aabb> = a.iter().map(|t| t.bounds()).collect();
        let bounds = boxes_a.iter().fold(Aabb::EMPTY, |u, b| u.union(b));
        let shift = (bounds.max - bounds.min) * Vec3::new(0.01, 0.007, 0.004);
        let b = scene::transformed(&a, 0.02, shift);
        let boxes_b: Vec<Aabb> = b.iter().map(|t| t.bounds()).collect();
        let rays = bvhkit_std::layouts::rays(&a, 20_000);
        let scene = Scene {
            name: &name,
            a: &a,
            boxes_a: &boxes_a,
            boxes_b: &boxes_b,
            rays: &rays,
            runs,
        };
        let top_down = |p: &[Aabb]| OwnedBvh::<Aabb>::build(&TopDown::default(), p);
        let reference = scene.measure("top-down default", "(4 per leaf)", &top_down, None);
        for (radius, label) in [(1, "PLOC r1"), (16, "PLOC r16")] {
            for (what, collapse) in collapses {
                let builder = BottomUp {
                    method: Method::Ploc { radius },
                    collapse,
                    ..BottomUp::default()
                };
                let build = |p: &[Aabb]| OwnedBvh::<Aabb>::build_bottom_up(&builder, p);
                scene.measure(label, what, &build, Some(&reference));
            }
        }
        for (what, collapse) in [collapses[0], collapses[3]] {
            let builder = Insertion {
                collapse,
                ..Insertion::default()
            };
            let build = |p: &[Aabb]| OwnedBvh::<Aabb>::build_by_insertion(&builder, p);
            scene.measure("insertion", what, &build, Some(&reference));
        }
    }
}

/// One mesh, its moved copy and its rays.
struct Scene<'s> {
    name: &'s str,
    a: &'s [Triangle],
    boxes_a: &'s [Aabb],
    boxes_b: &'s [Aabb],
    rays: &'s [Ray],
    runs: usize,
}

type Answers = (usize, Vec<Option<u32>>);

/// Builds a tree over boxes.
type Build<'b> = &'b dyn Fn(&[Aabb]) -> Result<OwnedBvh<Aabb>, bvhkit::Error>;

impl Scene<'_> {
    /// Builds A's and B's trees with `build`, prints the row, checks the
    /// answers against `reference` (the top-down tree's) and returns them.
    fn measure(
        &self,
        tree: &str,
        collapse: &str,
        build: Build<'_>,
        reference: Option<&Answers>,
    ) -> Answers {
        let (a, boxes_a, boxes_b, rays, runs) =
            (self.a, self.boxes_a, self.boxes_b, self.rays, self.runs);
        let mut build_ms = Vec::new();
        let mut trees = None;
        for _ in 0..runs.clamp(1, 5) {
            let t = Instant::now();
            let ta = build(boxes_a).expect("builds");
            build_ms.push(t.elapsed().as_secs_f64() * 1e3);
            trees = Some(ta);
        }
        build_ms.sort_by(f64::total_cmp);
        let ta = trees.expect("built");
        let tb = build(boxes_b).expect("builds");
        let (va, vb) = (ta.view(), tb.view());
        let (pairs_t, pairs) = median_time(runs, || {
            Pairs::new(&va, boxes_a, &vb, boxes_b)
                .count()
                .expect("query")
        });
        let (rays_t, hits) = median_time(runs, || {
            rays.iter()
                .map(|r| {
                    va.cast_ray(a, r, RayOrder::default(), ())
                        .expect("ray query")
                        .map(|h| h.prim)
                })
                .collect::<Vec<_>>()
        });
        let stats = va.stats();
        println!(
            "| {} | {tree} | {collapse} | {:.1} | {} | {:.2} | {:.3} | {:.3} |",
            self.name,
            build_ms[build_ms.len() / 2],
            va.node_count(),
            stats.sah_cost,
            pairs_t.as_secs_f64() * 1e3,
            rays_t.as_secs_f64() * 1e3
        );
        let answers = (pairs, hits);
        if let Some(want) = reference {
            assert_eq!(answers.0, want.0, "{tree} {collapse}: pair count");
            // Rays: the same closest primitive, up to ties at equal t.
            let differ = answers
                .1
                .iter()
                .zip(&want.1)
                .filter(|(x, y)| x != y)
                .count();
            assert!(
                differ * 1000 <= rays.len(),
                "{tree} {collapse}: {differ} rays differ"
            );
        }
        answers
    }
}
