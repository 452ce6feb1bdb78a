//! Figures of the book's `insertion.md` chapter: a dynamic tree growing
//! from sorted input, without rotations and with them.

use super::svg::stack_rows;
use super::svg::{colour, Style, Svg};
use super::top_down::{flat, uniform};
use super::{Figure, FigureError};
use bvhkit::builders::{DynNode, DynamicConfig, DynamicTree, Rotations, SiblingSearch};
use bvhkit::glam::Vec2;
use bvhkit::{Aabb, Content, Hierarchy};
use std::path::Path;

pub(super) fn figures(book_src: &Path) -> Result<Vec<Figure>, FigureError> {
    let _ = book_src;
    Ok(vec![sorted_insertions()?])
}

/// Objects in the row.
const N: usize = 16;
/// The snapshots: objects inserted so far.
const SNAPSHOTS: [usize; 3] = [4, 8, 16];
/// Vertical distance between two heights of the tree drawing.
const STEP: f32 = 0.5;
/// Where the tree drawing starts, above the row of objects.
const BASE: f32 = 1.6;

/// A row of boxes along x, already sorted by their centres (the insertion
/// order of `InsertOrder::Sorted`): the chapter's worst case.
fn row() -> Vec<Aabb> {
    let mut next = uniform(0x51de_ca11_0dd5_eed5);
    (0..N)
        .map(|i| {
            let lo = Vec2::new(i as f32 + next() * 0.2, 0.0);
            Aabb::new(lo.extend(0.0), (lo + Vec2::splat(0.7)).extend(0.0))
        })
        .collect()
}

/// One snapshot: the node-link drawing of a tree, as segments and dots.
struct Drawing {
    height: usize,
    segments: Vec<(Vec2, Vec2)>,
    inner: Vec<Vec2>,
}

/// Inserts the first `k` objects, in order, with the descent search (the
/// one-walk search of Goldsmith and Salmon, which sorted input drives into
/// a chain; branch and bound makes a comb about half as tall), and draws
/// the tree: each leaf
/// above its object, each inner node midway between its children, at its
/// height over the row.
fn snapshot(objects: &[Aabb], k: usize, rotations: Rotations) -> Result<Drawing, FigureError> {
    let mut storage = vec![DynNode::<Aabb>::EMPTY; 2 * k - 1];
    let config = DynamicConfig {
        rotations,
        search: SiblingSearch::Descent,
        ..DynamicConfig::default()
    };
    let mut tree = DynamicTree::new(&mut storage, config)?;
    for (i, b) in objects[..k].iter().enumerate() {
        tree.insert(i as u32, b)?;
    }
    tree.validate()?;
    let mut d = Drawing {
        height: tree.height(),
        segments: Vec::new(),
        inner: Vec::new(),
    };
    walk(&tree, Hierarchy::root(&tree), &mut d);
    Ok(d)
}

/// Draws node `n` and returns where it is, and its height.
fn walk(tree: &DynamicTree<Aabb>, n: u32, d: &mut Drawing) -> (Vec2, usize) {
    match tree.content(n) {
        Content::Leaf(_) => (Vec2::new(tree.bv(n).center().x, BASE), 0),
        Content::Inner(kids) => {
            let mut h = 0;
            let mut ends = Vec::new();
            for &c in kids.as_slice() {
                let (p, hc) = walk(tree, c, d);
                h = h.max(hc + 1);
                ends.push(p);
            }
            let x = ends.iter().map(|p| p.x).sum::<f32>() / ends.len() as f32;
            let at = Vec2::new(x, BASE + h as f32 * STEP);
            for p in ends {
                d.segments.push((at, p));
            }
            d.inner.push(at);
            (at, h)
        }
    }
}

fn sorted_insertions() -> Result<Figure, FigureError> {
    let objects = row();
    let configs = [
        (Rotations::Off, "Rotations::Off"),
        (Rotations::Always, "Rotations::Always"),
    ];
    let mut drawings = Vec::new();
    for (rotations, _) in configs {
        let mut row = Vec::new();
        for k in SNAPSHOTS {
            row.push(snapshot(&objects, k, rotations)?);
        }
        drawings.push(row);
    }
    let tallest = drawings
        .iter()
        .flatten()
        .map(|d| d.height)
        .max()
        .unwrap_or(0);
    let lo = Vec2::new(-0.4, -0.4);
    let hi = Vec2::new(N as f32 + 0.6, BASE + tallest as f32 * STEP + 0.4);
    let (width, row_height) = (900.0, 200.0);
    let mut rows = Vec::new();
    for ((_, name), row) in configs.iter().zip(&drawings) {
        let mut svg = Svg::new(width, row_height, lo, hi);
        for (i, (k, d)) in SNAPSHOTS.iter().zip(row).enumerate() {
            svg.panel(
                i,
                SNAPSHOTS.len(),
                lo,
                hi,
                &format!("{name}, {k} objects: height {}", d.height),
            );
            for (j, b) in objects.iter().enumerate() {
                let (a, c) = flat(b);
                if j < *k {
                    svg.rect(a, c, Style::filled(colour(1), 0.5).width(0.8));
                } else {
                    svg.rect(a, c, Style::line("#999999").dashed().width(0.8));
                }
            }
            for &(a, b) in &d.segments {
                svg.line(a, b, Style::line(colour(0)).width(1.2));
            }
            for b in &objects[..*k] {
                let x = b.center().x;
                svg.line(
                    Vec2::new(x, b.max.y),
                    Vec2::new(x, BASE),
                    Style::line("#999999").width(0.8),
                );
                svg.dot(Vec2::new(x, BASE), 2.5, colour(1));
            }
            for &p in &d.inner {
                svg.dot(p, 3.0, colour(0));
            }
        }
        rows.push((row_height, svg.finish()));
    }
    Ok(Figure {
        name: "insertion-sorted-rotations",
        chapter: "insertion.md",
        svg: stack_rows(width, &rows),
    })
}
