//! `bvhkit stats`: one tree over one mesh, measured, with the memory each
//! representation would take.

use crate::builders::Builder;
use crate::{collide::VOLUMES, median_time};
use bvhkit::layout::{
    FarLink, Implicit, PreNode, Preorder, QuantNode, QuantizedWide, Slot, TriNode, TriNodes, Wide,
    WideNode,
};
use bvhkit::{Aabb, BoundingVolume, Dop14, Dop18, Dop26, Obb, Sphere, Triangle};
use serde::Serialize;
use std::mem::size_of;

/// What to build.
#[derive(Clone, Debug)]
pub struct StatsOptions {
    /// A builder preset name (see [`PRESETS`](bvhkit::builders::PRESETS)).
    pub builder: String,
    /// One of [`VOLUMES`].
    pub volume: String,
    /// Most primitives per leaf (`None`: the preset's own).
    pub leaf_size: Option<u32>,
    /// Timed builds; the median is reported.
    pub runs: usize,
}

/// Bytes of the tree in one representation.
#[derive(Clone, Debug, Serialize)]
pub struct MemoryLine {
    /// Representation.
    pub layout: &'static str,
    /// Bytes of records plus the index array, or why it does not fit.
    pub bytes: Result<usize, String>,
}

/// The measurements.
#[derive(Clone, Debug, Serialize)]
pub struct StatsReport {
    /// Mesh name.
    pub mesh: String,
    /// Triangles.
    pub triangles: usize,
    /// Builder preset.
    pub builder: String,
    /// Volume type.
    pub volume: String,
    /// Median build time.
    pub build_ms: f64,
    /// Nodes.
    pub nodes: usize,
    /// Leaves.
    pub leaves: usize,
    /// Deepest leaf.
    pub max_depth: usize,
    /// Mean leaf depth.
    pub mean_leaf_depth: f64,
    /// Balance: `log2(leaves) / mean leaf depth` (1 for a perfectly balanced
    /// tree, smaller for a lopsided one).
    pub balance: f64,
    /// Largest leaf.
    pub max_leaf_size: usize,
    /// SAH cost (`C_t = C_i = 1`).
    pub sah_cost: f64,
    /// Sum of node volumes over the root volume.
    pub volume_sum: f64,
    /// Sum of node surface areas (of their boxes) over the root's.
    pub area_sum: f64,
    /// Sibling overlap (area of sibling box intersections over the root area).
    pub sibling_overlap: f64,
    /// What the builder did besides following its configuration.
    pub build: BuildLine,
    /// Bytes per representation.
    pub memory: Vec<MemoryLine>,
}

/// The builder's fallbacks and warnings ([`bvhkit::BuildReport`]).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct BuildLine {
    /// Nodes split by a fallback instead of the configured strategy.
    pub fallback_splits: u32,
    /// Interventions of the depth limit.
    pub depth_limited: u32,
    /// Leaves over the configured maximum size (a warning).
    pub oversized_leaves: u32,
    /// The configured maximum leaf size.
    pub max_leaf_size: u32,
}

/// Builds and measures a tree over `mesh`.
pub fn run(name: &str, mesh: &[Triangle], opts: &StatsOptions) -> Result<StatsReport, String> {
    match opts.volume.as_str() {
        "aabb" => run_with::<Aabb>(name, mesh, opts),
        "sphere" => run_with::<Sphere>(name, mesh, opts),
        "obb" => run_with::<Obb>(name, mesh, opts),
        "obb-dito" => run_with::<bvhkit::ObbDito>(name, mesh, opts),
        "14-dop" => run_with::<Dop14>(name, mesh, opts),
        "18-dop" => run_with::<Dop18>(name, mesh, opts),
        "26-dop" => run_with::<Dop26>(name, mesh, opts),
        other => Err(format!("unknown volume '{other}' (one of {VOLUMES:?})")),
    }
}

fn run_with<B: BoundingVolume>(
    name: &str,
    mesh: &[Triangle],
    opts: &StatsOptions,
) -> Result<StatsReport, String> {
    let mut builder = Builder::by_name(&opts.builder)
        .ok_or_else(|| format!("unknown builder '{}'", opts.builder))?;
    if let Some(k) = opts.leaf_size {
        match &mut builder {
            Builder::TopDown(t) => *t = t.with_max_leaf_size(k),
            _ => {
                return Err(format!(
                "--leaf-size applies to the top-down builders; '{}' keeps one triangle per leaf",
                opts.builder
            ))
            }
        }
    }
    let (t, tree) = median_time(opts.runs, || builder.build::<B>(mesh));
    let tree = tree.map_err(|e| e.to_string())?;
    let v = tree.view();
    let s = v.stats();
    let root_area = v.root().map_or(0.0, |r| r.bv.aabb().half_area() as f64);
    let area_sum = v
        .nodes()
        .iter()
        .map(|n| n.bv.aabb().half_area() as f64)
        .fold(0.0, |sum, a| sum + a) // +0.0 for the empty tree (f64's `sum` starts at -0.0)
        / root_area.max(f64::MIN_POSITIVE);
    let index = 4 * mesh.len();
    let records = |n: Result<usize, bvhkit::Error>, each: usize| match n {
        Ok(n) => Ok(n * each + index),
        Err(e) => Err(e.to_string()),
    };
    // 16-bit links take any tree: records of 28 bytes (with a box), and
    // the few links too far for 16 bits in the far table.
    let pre16 = Preorder::<B, u16>::far_links_needed(&v)
        .map(|far| v.node_count() * size_of::<PreNode<B, u16>>() + far * size_of::<FarLink>());
    let memory = vec![
        MemoryLine {
            layout: "canonical",
            bytes: Ok(tree.plain_view().bytes()),
        },
        // Every layout can keep them too, at the same cost.
        MemoryLine {
            layout: "canonical + leaf bounds",
            bytes: Ok(v.bytes()),
        },
        MemoryLine {
            layout: "implicit",
            bytes: records(Implicit::slots_needed(&v), size_of::<Slot<B>>()),
        },
        MemoryLine {
            layout: "preorder-32",
            bytes: records(Ok(v.node_count()), size_of::<PreNode<B, u32>>()),
        },
        MemoryLine {
            layout: "preorder-16",
            bytes: records(pre16, 1),
        },
        MemoryLine {
            layout: "tri-node",
            bytes: records(TriNodes::records_needed(&v), size_of::<TriNode<B>>()),
        },
        MemoryLine {
            layout: "wide-4 (boxes)",
            bytes: records(Wide::records_needed(&v), size_of::<WideNode>()),
        },
        MemoryLine {
            layout: "quantized-4 (boxes)",
            bytes: records(QuantizedWide::records_needed(&v), size_of::<QuantNode>()),
        },
    ];
    Ok(StatsReport {
        mesh: name.to_string(),
        triangles: mesh.len(),
        builder: opts.builder.clone(),
        volume: B::NAME.to_string(),
        build_ms: t.as_secs_f64() * 1e3,
        nodes: s.nodes,
        leaves: s.leaves,
        max_depth: s.max_depth,
        mean_leaf_depth: s.mean_leaf_depth,
        balance: if s.mean_leaf_depth > 0.0 {
            (s.leaves as f64).log2() / s.mean_leaf_depth
        } else {
            1.0
        },
        max_leaf_size: s.max_leaf_size,
        sah_cost: s.sah_cost,
        volume_sum: s.volume_sum,
        area_sum,
        sibling_overlap: s.sibling_overlap,
        build: {
            let r = v.build_report();
            BuildLine {
                fallback_splits: r.fallback_splits,
                depth_limited: r.depth_limited,
                oversized_leaves: r.oversized_leaves,
                max_leaf_size: r.max_leaf_size,
            }
        },
        memory,
    })
}

/// The report as text.
pub fn render(r: &StatsReport) -> String {
    let mut s = format!(
        "mesh: {} ({} triangles)\ntree: {} builder, {} volumes, built in {:.2} ms (median)\n\n",
        r.mesh, r.triangles, r.builder, r.volume, r.build_ms
    );
    for (k, v) in [
        ("nodes", r.nodes.to_string()),
        ("leaves", r.leaves.to_string()),
        ("max depth", r.max_depth.to_string()),
        ("mean leaf depth", format!("{:.2}", r.mean_leaf_depth)),
        (
            "balance (log2 leaves / mean depth)",
            format!("{:.3}", r.balance),
        ),
        ("largest leaf", r.max_leaf_size.to_string()),
        ("SAH cost", format!("{:.2}", r.sah_cost)),
        ("sum of volumes / root", format!("{:.2}", r.volume_sum)),
        ("sum of box areas / root", format!("{:.2}", r.area_sum)),
        ("sibling overlap", format!("{:.4}", r.sibling_overlap)),
        (
            "fallback splits (strategy failed)",
            r.build.fallback_splits.to_string(),
        ),
        (
            "depth-limited splits or rebuilds",
            r.build.depth_limited.to_string(),
        ),
        (
            "leaves over the maximum size",
            r.build.oversized_leaves.to_string(),
        ),
    ] {
        s += &format!("{k:<36} {v:>12}\n");
    }
    if r.build.oversized_leaves > 0 {
        s += &format!(
            "warning: {} leaves hold more triangles than the configured maximum ({}): \
             queries stay exact but slower; raise max_depth or use OnFailure::ForceSplit\n",
            r.build.oversized_leaves, r.build.max_leaf_size
        );
    }
    s += "\nmemory (records + 4-byte index per triangle):\n";
    for m in &r.memory {
        match &m.bytes {
            Ok(b) if r.triangles == 0 => s += &format!("  {:<22} {:>12} bytes\n", m.layout, b),
            Ok(b) => {
                s += &format!(
                    "  {:<22} {:>12} bytes {:>7.1} B/triangle\n",
                    m.layout,
                    b,
                    *b as f64 / r.triangles as f64
                )
            }
            Err(e) => s += &format!("  {:<22} does not fit: {e}\n", m.layout),
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_of_an_empty_mesh_are_zero_and_print_no_nan() {
        let opts = StatsOptions {
            builder: "sah".into(),
            volume: "aabb".into(),
            leaf_size: None,
            runs: 1,
        };
        let r = run("empty", &[], &opts).unwrap();
        assert_eq!((r.nodes, r.leaves, r.max_depth), (0, 0, 0));
        assert_eq!((r.sah_cost, r.area_sum), (0.0, 0.0));
        assert!(r.area_sum.is_sign_positive());
        let text = render(&r);
        assert!(!text.contains("NaN") && !text.contains("-0.00"), "{text}");
        assert!(text.contains("(0 triangles)"));
    }

    #[test]
    fn stats_of_the_rock_are_consistent() {
        let mesh = crate::scene::rock(3, 1);
        let opts = StatsOptions {
            builder: "median".into(),
            volume: "aabb".into(),
            leaf_size: Some(1),
            runs: 1,
        };
        let r = run("rock", &mesh, &opts).unwrap();
        assert_eq!(r.leaves, mesh.len());
        assert_eq!(r.nodes, 2 * mesh.len() - 1);
        assert!(r.balance > 0.9 && r.balance <= 1.0 + 1e-9, "{}", r.balance);
        assert_eq!(r.memory[0].bytes, Ok(r.nodes * 32 + 4 * mesh.len()));
        assert_eq!(r.memory[1].bytes, Ok(r.nodes * 32 + 28 * mesh.len()));
        assert!(render(&r).contains("quantized-4"));
        // The build report: a median tree needs no fallback; a tree with a
        // leaf over the stated size gets the warning line.
        assert_eq!(
            (
                r.build.fallback_splits,
                r.build.oversized_leaves,
                r.build.max_leaf_size
            ),
            (0, 0, 1)
        );
        assert!(!render(&r).contains("warning"));
        // Small triangles spaced ever wider: maximum separation peels them.
        let row: Vec<Triangle> = (0..3000)
            .map(|i| {
                let o = bvhkit::glam::Vec3::new(1.01f32.powi(i), 0.0, 0.0);
                Triangle::new(o, o + o * 1e-6, o + bvhkit::glam::Vec3::Y * 1e-3)
            })
            .collect();
        let peeled = run(
            "row",
            &row,
            &StatsOptions {
                builder: "max-separation".into(),
                leaf_size: None,
                ..opts.clone()
            },
        )
        .unwrap();
        let b = peeled.build;
        assert!(b.fallback_splits > 0 && b.depth_limited > 0, "{b:?}");
        let line = format!(
            "{:<36} {:>12}",
            "fallback splits (strategy failed)", b.fallback_splits
        );
        assert!(render(&peeled).contains(&line), "{}", render(&peeled));
        let mut over = r.clone();
        over.build.oversized_leaves = 3;
        assert!(render(&over)
            .contains("warning: 3 leaves hold more triangles than the configured maximum (1)"));
        assert!(run(
            "rock",
            &mesh,
            &StatsOptions {
                volume: "cone".into(),
                ..opts
            }
        )
        .is_err());
    }
}
