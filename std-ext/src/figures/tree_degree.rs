//! Figures of the book's `tree-degree.md` chapter: one scene as a binary
//! tree and as its collapse into a 4-wide tree.

use super::introduction::{draw_triangles, extent, levels, plural, rect, scene, LevelNode};
use super::svg::{colour, Style, Svg};
use super::{Figure, FigureError};
use crate::OwnedBvh;
use bvhkit::glam::Vec2;
use bvhkit::layout::{Wide, WideNode};
use bvhkit::{Aabb, Hierarchy, TopDown};
use std::path::Path;

pub(super) fn figures(book_src: &Path) -> Result<Vec<Figure>, FigureError> {
    let _ = book_src;
    Ok(vec![binary_and_wide()?])
}

/// The first two levels below the root of the binary tree `TopDown::sah()`
/// builds and of the `layout::Wide` tree collapsed from it.
fn binary_and_wide() -> Result<Figure, FigureError> {
    let tris = scene(
        &[
            (Vec2::new(1.6, 1.4), Vec2::new(1.2, 1.0), 12),
            (Vec2::new(6.4, 4.4), Vec2::new(1.6, 0.9), 12),
            (Vec2::new(6.8, 1.2), Vec2::new(1.2, 0.9), 10),
            (Vec2::new(2.0, 4.6), Vec2::new(1.2, 0.6), 10),
        ],
        0.5,
        0x5851_f42d_4c95_7f2d,
    );
    let tree = OwnedBvh::<Aabb>::build(&TopDown::sah(), &tris)?;
    let bvh = tree.view();
    let mut records = vec![WideNode::EMPTY; Wide::records_needed(&bvh)?];
    let wide = Wide::from_bvh(&bvh, &mut records)?;

    let (lo, hi) = extent(&tris, 0.3);
    // Room under the scene for a line about the levels drawn.
    let lo = lo - Vec2::new(0.0, 0.12 * (hi.y - lo.y));
    let panels: [(&str, usize, usize, Vec<Vec<LevelNode>>); 2] = [
        (
            "binary",
            Hierarchy::node_count(&bvh),
            Hierarchy::depth(&bvh),
            levels(&bvh),
        ),
        ("4-wide", wide.node_count(), wide.depth(), levels(&wide)),
    ];
    let mut svg = Svg::new(880.0, 330.0, lo, hi);
    for (i, (name, nodes, depth, levels)) in panels.iter().enumerate() {
        svg.panel(
            i,
            panels.len(),
            lo,
            hi,
            &format!("{name}: {}, depth {depth}", plural(*nodes, "node", "nodes")),
        );
        draw_triangles(&mut svg, &tris, |_| false);
        let level = |d: usize| levels.get(d).map_or(&[][..], |l| &l[..]);
        for node in level(2) {
            rect(
                &mut svg,
                &node.bv,
                Style::line(colour(node.branch)).width(1.0),
            );
        }
        for node in level(1) {
            rect(
                &mut svg,
                &node.bv,
                Style::filled(colour(node.branch), 0.12).width(2.5),
            );
        }
        svg.label(
            Vec2::new((lo.x + hi.x) * 0.5, lo.y + 0.05 * (hi.y - lo.y)),
            &format!(
                "level 1: {} (thick), level 2: {} (thin)",
                plural(level(1).len(), "box", "boxes"),
                plural(level(2).len(), "box", "boxes")
            ),
            12.0,
        );
    }
    Ok(Figure {
        name: "binary-and-4-wide",
        chapter: "tree-degree.md",
        svg: svg.finish(),
    })
}
