//! Figures of the book's `exercises.md` chapter: the inputs of exercise 1
//! with the library's answer.

use super::svg::{colour, Style, Svg};
use super::{Figure, FigureError};
use bvhkit::glam::{Vec2, Vec3};
use bvhkit::Aabb;
use std::path::Path;

pub(super) fn figures(book_src: &Path) -> Result<Vec<Figure>, FigureError> {
    let _ = book_src;
    Ok(vec![aabb_overlap_cases()])
}

/// A box of the plane, one unit thick in z (both boxes of a case share
/// their z interval, so only x and y decide).
fn plate(x0: f32, y0: f32, x1: f32, y1: f32) -> Aabb {
    Aabb::new(Vec3::new(x0, y0, 0.0), Vec3::new(x1, y1, 1.0))
}

/// Pairs of boxes overlapping, touching along a face, touching at a
/// corner and apart on one axis only, each titled with `Aabb::overlaps`.
fn aabb_overlap_cases() -> Figure {
    let cases = [
        (
            "overlapping",
            plate(0.0, 0.0, 2.0, 2.0),
            plate(1.2, 0.8, 3.0, 2.6),
        ),
        (
            "touching sides",
            plate(0.0, 0.0, 2.0, 2.0),
            plate(2.0, 0.6, 3.0, 2.6),
        ),
        (
            "touching corners",
            plate(0.0, 0.0, 2.0, 2.0),
            plate(2.0, 2.0, 3.0, 2.6),
        ),
        (
            "apart in y only",
            plate(0.0, 0.0, 2.0, 1.6),
            plate(1.0, 2.0, 3.0, 2.6),
        ),
    ];
    let (lo, hi) = (Vec2::new(-0.6, -1.0), Vec2::new(3.2, 2.7));
    let mut svg = Svg::new(880.0, 270.0, lo, hi);
    for (i, (name, a, b)) in cases.iter().enumerate() {
        svg.panel(i, cases.len(), lo, hi, name);
        for (k, (bx, label)) in [(a, "a"), (b, "b")].into_iter().enumerate() {
            let (min, max) = (bx.min.truncate(), bx.max.truncate());
            svg.rect(min, max, Style::filled(colour(k), 0.25).width(2.0));
            svg.label((min + max) * 0.5, label, 14.0);
            // The box's x interval under the drawing, its y interval left
            // of it: boxes overlap when their intervals do on every axis.
            let at = -0.2 - 0.15 * k as f32;
            let style = Style::line(colour(k)).width(3.0);
            svg.line(Vec2::new(min.x, at), Vec2::new(max.x, at), style);
            svg.line(Vec2::new(at, min.y), Vec2::new(at, max.y), style);
        }
        svg.label(
            Vec2::new(1.3, -0.72),
            &format!("a.overlaps(&b) = {}", a.overlaps(b)),
            13.0,
        );
    }
    Figure {
        name: "aabb-overlap-cases",
        chapter: "exercises.md",
        svg: svg.finish(),
    }
}
