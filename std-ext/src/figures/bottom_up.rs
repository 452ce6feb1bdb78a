//! Figures of the book's `bottom-up.md` chapter: the merge order of the
//! textbook (exhaustive) builder on a few boxes in the plane.

use super::svg::{colour, Style, Svg};
use super::top_down::{flat, primitives_under, uniform};
use super::{Figure, FigureError};
use bvhkit::builders::{BottomUp, BottomUpScratch, Cluster, MergeMetric};
use bvhkit::glam::Vec2;
use bvhkit::{Aabb, Bvh, Node};
use std::collections::BTreeMap;
use std::path::Path;

pub(super) fn figures(book_src: &Path) -> Result<Vec<Figure>, FigureError> {
    let _ = book_src;
    Ok(vec![merge_order()?])
}

/// Twelve boxes scattered in the plane (flat: z = 0), seeded; a box
/// that would come too near one already placed is drawn again, so that
/// every box shows.
fn scene() -> Vec<Aabb> {
    let mut next = uniform(0x0bad_5eed_1234_5678);
    let mut boxes: Vec<Aabb> = Vec::new();
    while boxes.len() < 12 {
        let lo = Vec2::new(next() * 10.0, next() * 5.0);
        let size = Vec2::new(0.4 + next() * 0.7, 0.4 + next() * 0.7);
        let b = Aabb::new(lo.extend(0.0), (lo + size).extend(0.0));
        let near = Aabb::new(b.min - 0.2, b.max + 0.2);
        if boxes.iter().all(|o| !o.overlaps(&near)) {
            boxes.push(b);
        }
    }
    boxes
}

/// The letter naming primitive `i` (a, b, c, ...).
fn letter(i: u32) -> String {
    char::from(b'a' + i as u8).to_string()
}

/// The primitives of cluster `c` (ids below `n` are the primitives).
fn cluster_primitives(clusters: &[Cluster<Aabb>], c: u32, out: &mut Vec<u32>) {
    let cl = &clusters[c as usize];
    if cl.left == cl.right {
        out.push(cl.left);
    } else {
        cluster_primitives(clusters, cl.left, out);
        cluster_primitives(clusters, cl.right, out);
    }
}

/// Height of node `n` above its deepest leaf.
fn height(tree: &Bvh<Aabb>, n: u32) -> u32 {
    match tree.nodes()[n as usize].children() {
        None => 0,
        Some((l, r)) => 1 + height(tree, l).max(height(tree, r)),
    }
}

fn merge_order() -> Result<Figure, FigureError> {
    let boxes = scene();
    let n = boxes.len();
    let builder = BottomUp::exhaustive(MergeMetric::SurfaceArea);
    let (nc, nw, nk) = BottomUp::scratch_len(n);
    let mut clusters = vec![Cluster::<Aabb>::EMPTY; nc];
    let (mut work, mut keys) = (vec![0u32; nw], vec![0u64; nk]);
    let mut scratch = BottomUpScratch {
        clusters: &mut clusters,
        work: &mut work,
        keys: &mut keys,
    };
    let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(n)];
    let mut idx = vec![0u32; n];
    let tree = builder.build(&boxes, &mut nodes, &mut idx, &mut scratch)?;
    // The exhaustive builder writes merge k into cluster n + k of its
    // scratch: the merge order. Each inner node of the built tree is the
    // merge with the same primitives.
    let mut merge_of = BTreeMap::new();
    for k in 0..n - 1 {
        let mut prims = Vec::new();
        cluster_primitives(&clusters, (n + k) as u32, &mut prims);
        prims.sort_unstable();
        merge_of.insert(prims, k + 1);
    }
    let mut number = vec![0usize; tree.node_count()];
    for (i, node) in tree.nodes().iter().enumerate() {
        if node.is_leaf() {
            continue;
        }
        let mut prims = Vec::new();
        primitives_under(&tree, i as u32, &mut prims);
        prims.sort_unstable();
        number[i] = *merge_of.get(&prims).ok_or_else(|| {
            FigureError(format!(
                "node {i} of the built tree is no merge of the builder"
            ))
        })?;
    }

    let mut world = Aabb::EMPTY;
    for b in &boxes {
        world = world.union(b);
    }
    let pad = 0.15;
    let (lo, hi) = (
        world.min.truncate() - Vec2::splat(0.6 + 4.0 * pad),
        world.max.truncate() + Vec2::splat(0.6 + 4.0 * pad),
    );
    let mut svg = Svg::new(900.0, 340.0, lo, hi);
    svg.panel(
        0,
        2,
        lo,
        hi,
        &format!("{n} boxes, {} merges: each merged cluster's box", n - 1),
    );
    // Each merged cluster's box, enlarged by its height so that nested
    // boxes show; its number goes in the first corner where it covers no
    // box and no number placed before it (the first merges first).
    let scale = ((900.0 / 2.0 - 24.0) / (hi - lo).x).min((340.0 - 40.0) / (hi - lo).y);
    let mut taken: Vec<(Vec2, Vec2)> = boxes.iter().map(flat).collect();
    let mut order: Vec<usize> = (0..tree.node_count())
        .filter(|&i| !tree.nodes()[i].is_leaf())
        .collect();
    order.sort_by_key(|&i| number[i]);
    for &i in &order {
        let grow = pad * height(&tree, i as u32) as f32;
        let (a, b) = flat(&tree.nodes()[i].bv);
        let (a, b) = (a - Vec2::splat(grow), b + Vec2::splat(grow));
        svg.rect(a, b, Style::line(colour(0)).width(1.2));
        let text = number[i].to_string();
        let half = Vec2::new(3.5 * text.len() as f32 + 2.0, 6.0) / scale;
        let inside = |x: f32, y: f32, sx: f32, sy: f32| Vec2::new(x + sx * half.x, y + sy * half.y);
        let candidates = [
            inside(a.x, b.y, 1.0, -1.0),
            inside(b.x, b.y, -1.0, -1.0),
            inside(a.x, a.y, 1.0, 1.0),
            inside(b.x, a.y, -1.0, 1.0),
            inside(a.x, b.y, 1.0, 1.0),
            inside(b.x, b.y, -1.0, 1.0),
            inside(a.x, a.y, 1.0, -1.0),
            inside(b.x, a.y, -1.0, -1.0),
        ];
        let free = |c: &Vec2| {
            taken.iter().all(|(p, q)| {
                c.x + half.x <= p.x
                    || c.x - half.x >= q.x
                    || c.y + half.y <= p.y
                    || c.y - half.y >= q.y
            })
        };
        let at = candidates
            .iter()
            .copied()
            .find(free)
            .unwrap_or(candidates[0]);
        taken.push((at - half, at + half));
        svg.label(at, &text, 10.0);
    }
    for (i, b) in boxes.iter().enumerate() {
        let (a, c) = flat(b);
        svg.rect(a, c, Style::filled(colour(1), 0.5).width(0.8));
        svg.label((a + c) * 0.5, &letter(i as u32), 10.0);
    }

    // The merge order as a dendrogram: leaves in the tree's order along the
    // bottom, merge k at height k.
    let mut leaf_x = BTreeMap::new();
    let mut x_of = vec![0.0f32; tree.node_count()];
    place(&tree, 0, &mut leaf_x, &mut x_of);
    let top = (n - 1) as f32;
    svg.panel(
        1,
        2,
        Vec2::new(-1.0, -1.5),
        Vec2::new(n as f32, top + 1.0),
        "merge order: merge k joins its two clusters at height k",
    );
    let y_of = |i: usize| number[i] as f32;
    for (i, node) in tree.nodes().iter().enumerate() {
        match node.children() {
            None => {
                let p = tree.leaf_primitives(node)[0];
                svg.label(Vec2::new(x_of[i], -0.7), &letter(p), 11.0);
                svg.dot(Vec2::new(x_of[i], 0.0), 2.5, colour(1));
            }
            Some((l, r)) => {
                let y = y_of(i);
                for c in [l as usize, r as usize] {
                    let yc = if tree.nodes()[c].is_leaf() {
                        0.0
                    } else {
                        y_of(c)
                    };
                    svg.line(
                        Vec2::new(x_of[c], yc),
                        Vec2::new(x_of[c], y),
                        Style::line(colour(0)),
                    );
                }
                svg.line(
                    Vec2::new(x_of[l as usize], y),
                    Vec2::new(x_of[r as usize], y),
                    Style::line(colour(0)),
                );
                svg.label(Vec2::new(x_of[i], y + 0.45), &number[i].to_string(), 10.0);
            }
        }
    }
    Ok(Figure {
        name: "bottom-up-merge-order",
        chapter: "bottom-up.md",
        svg: svg.finish(),
    })
}

/// Places the leaves under `n` at 0, 1, 2, ... in depth-first order and
/// every inner node midway between its children.
fn place(tree: &Bvh<Aabb>, n: u32, leaves: &mut BTreeMap<u32, f32>, x: &mut [f32]) {
    match tree.nodes()[n as usize].children() {
        None => {
            let at = leaves.len() as f32;
            leaves.insert(n, at);
            x[n as usize] = at;
        }
        Some((l, r)) => {
            place(tree, l, leaves, x);
            place(tree, r, leaves, x);
            x[n as usize] = (x[l as usize] + x[r as usize]) * 0.5;
        }
    }
}
