//! Figures of the book's `top-down.md` chapter: the first splits of several
//! partition strategies (the library's presets) on one small scene.

use super::svg::{colour, stack_rows, Style, Svg};
use super::{Figure, FigureError};
use bvhkit::builders::PRESETS;
use bvhkit::glam::Vec2;
use bvhkit::{Aabb, Bvh, Node};
use std::path::Path;

pub(super) fn figures(book_src: &Path) -> Result<Vec<Figure>, FigureError> {
    let _ = book_src;
    Ok(vec![first_splits()?])
}

/// The presets shown, in the order of the panels (two rows of four).
const SHOWN: [&str; 8] = [
    "sah",
    "median",
    "spatial-median",
    "distant-points",
    "min-volume",
    "min-overlap",
    "max-separation",
    "mean-variance",
];

/// How thick the scene's boxes are along z: thin, so that the SAH sees
/// mostly their areas in the plane, but not flat, so that the criteria
/// that weigh volumes see the boxes' areas in the plane too.
const THICKNESS: f32 = 0.2;

/// A seeded xorshift generator of numbers in `[0, 1)`.
pub(super) fn uniform(seed: u64) -> impl FnMut() -> f32 {
    let mut s = seed;
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// A small scene of boxes in the plane (z from 0 to [`THICKNESS`]): a
/// dense cluster on the left, a sparse scatter on the right and one long
/// thin box across the top, where the criteria disagree. Each box sits in
/// a cell of its own grid, jittered, so that the boxes stay apart.
fn scene() -> Vec<Aabb> {
    let mut next = uniform(0x9e37_79b9_7f4a_7c15);
    let mut boxes = Vec::new();
    let mut add = |lo: Vec2, size: Vec2| {
        boxes.push(Aabb::new(lo.extend(0.0), (lo + size).extend(THICKNESS)));
    };
    for cell in 0..12 {
        let corner = Vec2::new((cell % 4) as f32, (cell / 4) as f32) * 0.9;
        let size = Vec2::new(0.3 + next() * 0.3, 0.3 + next() * 0.3);
        add(corner + Vec2::new(next(), next()) * (0.85 - size), size);
    }
    for cell in [0, 1, 2, 4, 5, 7, 8] {
        let corner = Vec2::new(5.0, 0.0) + Vec2::new((cell % 3) as f32, (cell / 3) as f32) * 1.8;
        let size = Vec2::new(0.5 + next() * 0.6, 0.5 + next() * 0.6);
        add(corner + Vec2::new(next(), next()) * (1.7 - size), size);
    }
    add(Vec2::new(0.5, 5.9), Vec2::new(7.0, 0.3));
    boxes
}

/// The primitives under node `n` of `tree`.
pub(super) fn primitives_under(tree: &Bvh<Aabb>, n: u32, out: &mut Vec<u32>) {
    let node = &tree.nodes()[n as usize];
    match node.children() {
        None => out.extend_from_slice(tree.leaf_primitives(node)),
        Some((l, r)) => {
            primitives_under(tree, l, out);
            primitives_under(tree, r, out);
        }
    }
}

/// The corners in the plane of a box.
pub(super) fn flat(b: &Aabb) -> (Vec2, Vec2) {
    (b.min.truncate(), b.max.truncate())
}

fn first_splits() -> Result<Figure, FigureError> {
    let boxes = scene();
    let mut world = Aabb::EMPTY;
    for b in &boxes {
        world = world.union(b);
    }
    let pad = Vec2::splat(0.4);
    let (lo, hi) = (world.min.truncate() - pad, world.max.truncate() + pad);
    let n = boxes.len();
    let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(n)];
    let mut idx = vec![0u32; 2 * n];
    let (width, row_height, per_row) = (900.0, 200.0, 4);
    let mut rows = Vec::new();
    for names in SHOWN.chunks(per_row) {
        let mut svg = Svg::new(width, row_height, lo, hi);
        for (i, &name) in names.iter().enumerate() {
            let preset = PRESETS
                .iter()
                .find(|p| p.name == name)
                .ok_or_else(|| FigureError(format!("no preset named {name}")))?;
            let tree = preset.builder.build(&boxes, &mut nodes, &mut idx)?;
            let (l, r) = tree.nodes()[0]
                .children()
                .ok_or_else(|| FigureError(format!("{name}: the root is a leaf")))?;
            let (mut left, mut right) = (Vec::new(), Vec::new());
            primitives_under(&tree, l, &mut left);
            primitives_under(&tree, r, &mut right);
            svg.panel(
                i,
                per_row,
                lo,
                hi,
                &format!("{name}: {} | {}", left.len(), right.len()),
            );
            for (side, (child, prims)) in [(l, &left), (r, &right)].into_iter().enumerate() {
                let c = colour(side);
                for &p in prims.iter() {
                    let (a, b) = flat(&boxes[p as usize]);
                    svg.rect(a, b, Style::filled(c, 0.45).width(0.8));
                }
                let node = &tree.nodes()[child as usize];
                if let Some((gl, gr)) = node.children() {
                    for g in [gl, gr] {
                        let (a, b) = flat(&tree.nodes()[g as usize].bv);
                        svg.rect(a, b, Style::line(c).dashed().width(1.0));
                    }
                }
                let (a, b) = flat(&node.bv);
                svg.rect(a, b, Style::line(c).width(2.0));
            }
        }
        rows.push((row_height, svg.finish()));
    }
    Ok(Figure {
        name: "top-down-first-splits",
        chapter: "top-down.md",
        svg: stack_rows(width, &rows),
    })
}
