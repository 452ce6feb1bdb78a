//! Figures of the book's `characteristics.md` chapter: the desired
//! characteristics and the cost function's counts on a picture.

use super::introduction::{draw_triangles, extent, levels, rect, scene};
use super::svg::{colour, Style, Svg};
use super::{Figure, FigureError};
use crate::OwnedBvh;
use bvhkit::glam::{Vec2, Vec3};
use bvhkit::{Aabb, Counts, Order, TopDown};
use std::path::Path;

pub(super) fn figures(book_src: &Path) -> Result<Vec<Figure>, FigureError> {
    let _ = book_src;
    Ok(vec![median_and_sah()?])
}

/// One scene of uneven density under `TopDown::median()` and
/// `TopDown::sah()`: every node's box, and the counts of one box query.
fn median_and_sah() -> Result<Figure, FigureError> {
    let tris = scene(
        &[
            (Vec2::new(1.2, 1.2), Vec2::new(0.7, 0.7), 14),
            (Vec2::new(7.6, 4.3), Vec2::new(0.8, 0.6), 10),
            (Vec2::new(4.6, 2.6), Vec2::new(3.8, 2.2), 12),
        ],
        0.5,
        0x2545_f491_4f6c_dd1d,
    );
    let query = Aabb::new(Vec3::new(2.3, 0.6, -1.0), Vec3::new(4.1, 2.4, 1.0));
    let (lo, hi) = extent(&tris, 0.3);
    let builders = [
        ("TopDown::median()", TopDown::median()),
        ("TopDown::sah()", TopDown::sah()),
    ];
    let mut svg = Svg::new(880.0, 300.0, lo, hi);
    for (i, (name, builder)) in builders.iter().enumerate() {
        let tree = OwnedBvh::<Aabb>::build(builder, &tris)?;
        let bvh = tree.view();
        let stats = bvh.stats();
        let mut counts = Counts::default();
        let mut found = Vec::new();
        bvh.search(&tris, &query, Order::DepthFirst, &mut counts, |p| {
            found.push(p as usize)
        })?;
        svg.panel(
            i,
            builders.len(),
            lo,
            hi,
            &format!(
                "{name}: SAH {:.2}, depth {}; Nv {}, Np {}",
                stats.sah_cost, stats.max_depth, counts.bv_tests, counts.prim_tests
            ),
        );
        for (depth, level) in levels(&bvh).iter().enumerate() {
            for node in level {
                let style = if node.leaf {
                    Style::filled(colour(node.branch), 0.2).width(1.5)
                } else {
                    Style::line("#555555").width(if depth == 0 { 1.5 } else { 0.8 })
                };
                rect(&mut svg, &node.bv, style);
            }
        }
        draw_triangles(&mut svg, &tris, |p| found.contains(&p));
        rect(&mut svg, &query, Style::line("#d55e00").width(2.5).dashed());
    }
    Ok(Figure {
        name: "median-and-sah-trees",
        chapter: "characteristics.md",
        svg: svg.finish(),
    })
}
