//! Figures of the book's `introduction.md` chapter: a bounding volume
//! hierarchy at a glance, level by level. Also the small 2-D scenes and the
//! level walk that the figures of `characteristics.md` and `tree-degree.md`
//! share.

use super::svg::{colour, Style, Svg};
use super::{Figure, FigureError};
use crate::OwnedBvh;
use bvhkit::glam::Vec2;
use bvhkit::{Aabb, BoundingVolume, Content, Hierarchy, TopDown, Triangle};
use std::path::Path;

pub(super) fn figures(book_src: &Path) -> Result<Vec<Figure>, FigureError> {
    let _ = book_src;
    Ok(vec![bvh_levels()?])
}

/// A small deterministic generator (xorshift64), uniform in `[0, 1)`.
pub(super) struct Rng(pub(super) u64);

impl Rng {
    pub(super) fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// Small triangles in the plane z = 0: `count` of them around each
/// `(centre, spread)` of `clusters`, each one a random turn of a triangle
/// about `size` across.
pub(super) fn scene(clusters: &[(Vec2, Vec2, usize)], size: f32, seed: u64) -> Vec<Triangle> {
    let mut r = Rng(seed);
    let mut out = Vec::new();
    for &(centre, spread, count) in clusters {
        for _ in 0..count {
            let c = centre + Vec2::new(r.next() * 2.0 - 1.0, r.next() * 2.0 - 1.0) * spread;
            let turn = r.next() * std::f32::consts::TAU;
            let corner = |k: f32, s: f32| {
                let a = turn + k * std::f32::consts::TAU / 3.0;
                (c + Vec2::new(a.cos(), a.sin()) * size * 0.5 * s).extend(0.0)
            };
            out.push(Triangle::new(
                corner(0.0, 1.0),
                corner(1.0, 0.8),
                corner(2.0, 1.1),
            ));
        }
    }
    out
}

/// The world box to show around `tris`, with room `pad` on every side.
pub(super) fn extent(tris: &[Triangle], pad: f32) -> (Vec2, Vec2) {
    let mut b = Aabb::EMPTY;
    for t in tris {
        for p in t.v {
            b.grow(p);
        }
    }
    (
        b.min.truncate() - Vec2::splat(pad),
        b.max.truncate() + Vec2::splat(pad),
    )
}

/// Draws the triangles, those for which `dark` says so in black, the others
/// in grey.
pub(super) fn draw_triangles(svg: &mut Svg, tris: &[Triangle], dark: impl Fn(usize) -> bool) {
    for (i, t) in tris.iter().enumerate() {
        let pts: Vec<Vec2> = t.v.iter().map(|p| p.truncate()).collect();
        let style = if dark(i) {
            Style::filled("#000000", 0.75).width(0.8)
        } else {
            Style::filled("#999999", 0.5).width(0.8)
        };
        svg.polygon(&pts, style);
    }
}

/// An axis-aligned box as a rectangle of the plane.
pub(super) fn rect(svg: &mut Svg, b: &Aabb, style: Style) {
    svg.rect(b.min.truncate(), b.max.truncate(), style);
}

/// One node of a tree as a level of it shows: its box, whether it is a
/// leaf, and which child of the root it descends from (0 for the root
/// itself).
#[derive(Clone, Copy, Debug)]
pub(super) struct LevelNode {
    pub(super) bv: Aabb,
    pub(super) leaf: bool,
    pub(super) branch: usize,
}

/// The nodes of any hierarchy (binary or wide) level by level, walked
/// through the public [`Hierarchy`] view: entry `d` holds the nodes at
/// depth `d`, in the tree's child order.
pub(super) fn levels<H: Hierarchy>(h: &H) -> Vec<Vec<LevelNode>> {
    let mut out = Vec::new();
    if h.is_empty() {
        return out;
    }
    let mut current = vec![(h.root(), 0usize)];
    while !current.is_empty() {
        let mut level = Vec::new();
        let mut next = Vec::new();
        for &(n, branch) in &current {
            let bv = h.bv(n).aabb();
            match h.content(n) {
                Content::Leaf(_) => level.push(LevelNode {
                    bv,
                    leaf: true,
                    branch,
                }),
                Content::Inner(kids) => {
                    level.push(LevelNode {
                        bv,
                        leaf: false,
                        branch,
                    });
                    for (k, &c) in kids.as_slice().iter().enumerate() {
                        next.push((c, if out.is_empty() { k } else { branch }));
                    }
                }
            }
        }
        out.push(level);
        current = next;
    }
    out
}

/// `n` with the word `one` or its plural.
pub(super) fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// Twenty triangles in three loose groups, and the default builder's tree
/// over them drawn one level per panel.
fn bvh_levels() -> Result<Figure, FigureError> {
    let tris = scene(
        &[
            (Vec2::new(1.5, 4.0), Vec2::new(1.2, 1.0), 7),
            (Vec2::new(5.8, 4.4), Vec2::new(1.0, 0.8), 6),
            (Vec2::new(3.6, 0.9), Vec2::new(2.4, 0.6), 7),
        ],
        0.7,
        0x9e37_79b9_7f4a_7c15,
    );
    let tree = OwnedBvh::<Aabb>::build(&TopDown::default(), &tris)?;
    let bvh = tree.view();
    let levels = levels(&bvh);
    let (lo, hi) = extent(&tris, 0.3);
    let n = levels.len();
    let mut svg = Svg::new(225.0 * n as f32, 240.0, lo, hi);
    for (d, level) in levels.iter().enumerate() {
        let leaves = level.iter().filter(|l| l.leaf).count();
        let title = if d == 0 {
            format!(
                "depth 0: root, {}",
                plural(tris.len(), "triangle", "triangles")
            )
        } else if leaves == 0 {
            format!("depth {d}: {}", plural(level.len(), "node", "nodes"))
        } else if leaves == level.len() {
            format!("depth {d}: {}", plural(leaves, "leaf", "leaves"))
        } else {
            format!(
                "depth {d}: {}, {}",
                plural(level.len(), "node", "nodes"),
                plural(leaves, "leaf", "leaves")
            )
        };
        svg.panel(d, n, lo, hi, &title);
        // Leaves made higher up: done, but still holding their triangles.
        for done in levels[..d].iter().flatten().filter(|l| l.leaf) {
            rect(&mut svg, &done.bv, Style::filled("#999999", 0.2).width(1.0));
        }
        draw_triangles(&mut svg, &tris, |_| false);
        if d > 0 {
            for parent in levels[d - 1].iter().filter(|p| !p.leaf) {
                rect(
                    &mut svg,
                    &parent.bv,
                    Style::line("#555555").width(1.0).dashed(),
                );
            }
        }
        for (k, node) in level.iter().enumerate() {
            let c = colour(k);
            let style = if node.leaf {
                Style::filled(c, 0.25).width(2.0)
            } else {
                Style::line(c).width(2.0)
            };
            rect(&mut svg, &node.bv, style);
        }
    }
    Ok(Figure {
        name: "bvh-levels",
        chapter: "introduction.md",
        svg: svg.finish(),
    })
}
