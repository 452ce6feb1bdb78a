//! What each tree representation costs and buys: bytes, conversion time,
//! pair-query and ray-cast time, and volume tests, on one scene.

use crate::{median_time, OwnedBvh};
use bvhkit::glam::Vec3;
use bvhkit::layout::{
    FarLink, Implicit, PreNode, Preorder, QuantNode, QuantizedWide, Slot, TriNode, TriNodes, Wide,
    WideNode,
};
use bvhkit::{Aabb, Counts, Error, Hierarchy, Pairs, Query, Ray, RayOrder, TopDown, Triangle};
use serde::Serialize;
use std::time::Instant;

/// One representation measured.
#[derive(Clone, Debug, Serialize)]
pub struct LayoutRow {
    /// Layout name.
    pub layout: &'static str,
    /// Bytes of one record.
    pub record_bytes: usize,
    /// Records in use.
    pub records: usize,
    /// Records plus primitive index array, tree A.
    pub total_bytes: usize,
    /// Total bytes per triangle of A.
    pub bytes_per_triangle: f64,
    /// Median ms of the canonical build plus the conversion (tree A).
    pub build_ms: f64,
    /// Median ms of the conversion alone.
    pub convert_ms: f64,
    /// Median ms of the A-against-B pair query (both trees in this layout).
    pub pairs_ms: f64,
    /// Volume tests of that query (Nv).
    pub pair_bv_tests: u64,
    /// Median ms of casting all rays at A (closest hit, depth-first).
    pub rays_ms: f64,
    /// Pairs the query found.
    pub pairs: usize,
    /// Whether pairs and ray hits equal the canonical tree's.
    pub same_answers: bool,
    /// Why the layout was refused, if it was (then the numbers are zero).
    pub refused: Option<String>,
}

/// The scene's rays: from a sphere around the scene toward points near its centre.
pub fn rays(prims: &[Triangle], n: usize) -> Vec<Ray> {
    let mut b = Aabb::EMPTY;
    for t in prims {
        b = b.union(&bvhkit::Primitive::bounds(t));
    }
    let (c, r) = (b.center(), b.extent().length());
    let mut s = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
    };
    (0..n)
        .filter_map(|_| {
            let from = c + Vec3::new(next(), next(), next()).normalize_or(Vec3::X) * r;
            let to = c + Vec3::new(next(), next(), next()) * r * 0.3;
            Ray::new(from, to - from, f32::INFINITY).ok()
        })
        .collect()
}

struct Scene<'s> {
    a: &'s [Triangle],
    b: &'s [Triangle],
    rays: &'s [Ray],
    runs: usize,
}

/// Answers and timings of one layout.
struct Measured {
    pairs_ms: f64,
    pair_bv_tests: u64,
    pairs: usize,
    rays_ms: f64,
    hits: Vec<Option<u32>>,
}

/// Answers of one layout: pair count and Nv, ray hits, timings.
fn run<H: Hierarchy<Bv = Aabb>>(s: &Scene<'_>, ta: &H, tb: &H) -> Result<Measured, Error> {
    let mut counts = Counts::default();
    let n = Pairs::new(ta, s.a, tb, s.b).counted(&mut counts).count()?;
    let (t_pairs, _) = median_time(s.runs, || Pairs::new(ta, s.a, tb, s.b).count());
    let cast = || -> Result<Vec<Option<u32>>, Error> {
        s.rays
            .iter()
            .map(|r| {
                Ok(ta
                    .cast_ray(s.a, r, RayOrder::DepthFirst, ())?
                    .map(|h| h.prim))
            })
            .collect()
    };
    let hits = cast()?;
    let (t_rays, _) = median_time(s.runs, cast);
    Ok(Measured {
        pairs_ms: t_pairs.as_secs_f64() * 1e3,
        pair_bv_tests: counts.bv_tests,
        pairs: n,
        rays_ms: t_rays.as_secs_f64() * 1e3,
        hits,
    })
}

/// Measures every representation on `a` against `b` with `builder` (AABB).
pub fn measure(
    a: &[Triangle],
    b: &[Triangle],
    builder: &TopDown,
    n_rays: usize,
    runs: usize,
) -> Result<Vec<LayoutRow>, Error> {
    let (t_build, ta) = median_time(runs, || OwnedBvh::<Aabb>::build(builder, a));
    let ta = ta?;
    let tb = OwnedBvh::<Aabb>::build(builder, b)?;
    // The representations by themselves: the bytes below count records and
    // indices, so the trees keep no leaf bounds (an option of every layout,
    // 24 more bytes per triangle, measured in the book's representations
    // chapter).
    let (va, vb) = (ta.plain_view(), tb.plain_view());
    let build_ms = t_build.as_secs_f64() * 1e3;
    let ray_set = rays(a, n_rays);
    let scene = Scene {
        a,
        b,
        rays: &ray_set,
        runs,
    };
    let base = run(&scene, &va, &vb)?;
    let mut rows = Vec::new();
    let row = |layout: &'static str,
               record_bytes: usize,
               records: usize,
               convert_ms: f64,
               r: &Measured| {
        let total = record_bytes * records + 4 * a.len();
        LayoutRow {
            layout,
            record_bytes,
            records,
            total_bytes: total,
            bytes_per_triangle: total as f64 / a.len() as f64,
            build_ms: build_ms + convert_ms,
            convert_ms,
            pairs_ms: r.pairs_ms,
            pair_bv_tests: r.pair_bv_tests,
            rays_ms: r.rays_ms,
            pairs: r.pairs,
            same_answers: r.pairs == base.pairs && r.hits == base.hits,
            refused: None,
        }
    };
    let refused = |layout: &'static str, record_bytes: usize, e: Error| LayoutRow {
        layout,
        record_bytes,
        records: 0,
        total_bytes: 0,
        bytes_per_triangle: 0.0,
        build_ms: 0.0,
        convert_ms: 0.0,
        pairs_ms: 0.0,
        pair_bv_tests: 0,
        rays_ms: 0.0,
        pairs: 0,
        same_answers: true,
        refused: Some(e.to_string()),
    };
    rows.push(row(
        "canonical",
        size_of::<bvhkit::Node<Aabb>>(),
        va.node_count(),
        0.0,
        &base,
    ));

    macro_rules! layout {
        ($name:expr, $rec:ty, $needed:expr, $empty:expr, $convert:expr) => {{
            let go = || -> Result<LayoutRow, Error> {
                let (na, nb) = ($needed(&va)?, $needed(&vb)?);
                let (mut sa, mut sb): (Vec<$rec>, Vec<$rec>) = (vec![$empty; na], vec![$empty; nb]);
                let t = Instant::now();
                let la = $convert(&va, &mut sa)?;
                let mut convert = t.elapsed();
                for _ in 1..runs {
                    let mut scratch: Vec<$rec> = vec![$empty; na];
                    let t = Instant::now();
                    $convert(&va, &mut scratch)?;
                    convert = convert.min(t.elapsed());
                }
                let lb = $convert(&vb, &mut sb)?;
                let r = run(&scene, &la, &lb)?;
                Ok(row(
                    $name,
                    size_of::<$rec>(),
                    na,
                    convert.as_secs_f64() * 1e3,
                    &r,
                ))
            };
            rows.push(go().unwrap_or_else(|e| refused($name, size_of::<$rec>(), e)));
        }};
    }
    layout!(
        "implicit",
        Slot<Aabb>,
        Implicit::slots_needed,
        Slot::EMPTY,
        Implicit::from_bvh
    );
    let nodes = |t: &bvhkit::Bvh<Aabb>| Ok::<usize, Error>(t.node_count());
    layout!(
        "preorder-32",
        PreNode<Aabb, u32>,
        nodes,
        PreNode::EMPTY,
        Preorder::from_bvh
    );
    // 16-bit links: any tree converts, with the links too far for 16 bits
    // in a far table (counted in the bytes).
    let pre16 = || -> Result<LayoutRow, Error> {
        let far_needed = |t| Preorder::<Aabb, u16>::far_links_needed(t);
        let (fa, fb) = (far_needed(&va)?, far_needed(&vb)?);
        let (na, nb) = (va.node_count(), vb.node_count());
        let empty = PreNode::<Aabb, u16>::EMPTY;
        let (mut sa, mut sb) = (vec![empty; na], vec![empty; nb]);
        let (mut far_a, mut far_b) = (vec![FarLink::EMPTY; fa], vec![FarLink::EMPTY; fb]);
        let t = Instant::now();
        let la = Preorder::from_bvh_with_far(&va, &mut sa, &mut far_a)?;
        let mut convert = t.elapsed();
        for _ in 1..runs {
            let mut scratch = vec![PreNode::<Aabb, u16>::EMPTY; na];
            let mut far = vec![FarLink::EMPTY; fa];
            let t = Instant::now();
            Preorder::from_bvh_with_far(&va, &mut scratch, &mut far)?;
            convert = convert.min(t.elapsed());
        }
        let lb = Preorder::from_bvh_with_far(&vb, &mut sb, &mut far_b)?;
        let r = run(&scene, &la, &lb)?;
        let mut line = row(
            "preorder-16",
            size_of::<PreNode<Aabb, u16>>(),
            na,
            convert.as_secs_f64() * 1e3,
            &r,
        );
        line.total_bytes += fa * size_of::<FarLink>();
        line.bytes_per_triangle = line.total_bytes as f64 / a.len() as f64;
        Ok(line)
    };
    rows.push(
        pre16().unwrap_or_else(|e| refused("preorder-16", size_of::<PreNode<Aabb, u16>>(), e)),
    );
    layout!(
        "tri-node",
        TriNode<Aabb>,
        TriNodes::records_needed,
        TriNode::EMPTY,
        TriNodes::from_bvh
    );
    layout!(
        "wide-4",
        WideNode,
        Wide::records_needed,
        WideNode::EMPTY,
        Wide::from_bvh
    );
    layout!(
        "quantized-4",
        QuantNode,
        QuantizedWide::records_needed,
        QuantNode::EMPTY,
        QuantizedWide::from_bvh
    );
    Ok(rows)
}

/// The rows as a markdown table.
pub fn render(rows: &[LayoutRow]) -> String {
    let mut out = String::from(
        "| layout | record B | records | total MB | B/tri | build+convert ms | convert ms | pairs ms | pair Nv | rays ms | same answers |\n\
         |---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n",
    );
    for r in rows {
        if let Some(why) = &r.refused {
            out += &format!(
                "| {} | {} | refused: {} | | | | | | | | |\n",
                r.layout, r.record_bytes, why
            );
            continue;
        }
        out += &format!(
            "| {} | {} | {} | {:.2} | {:.1} | {:.1} | {:.2} | {:.3} | {} | {:.2} | {} |\n",
            r.layout,
            r.record_bytes,
            r.records,
            r.total_bytes as f64 / 1e6,
            r.bytes_per_triangle,
            r.build_ms,
            r.convert_ms,
            r.pairs_ms,
            r.pair_bv_tests,
            r.rays_ms,
            if r.same_answers { "yes" } else { "NO" }
        );
    }
    out
}
