//! Figure of the book's `engines.md` chapter: the frame loop of its
//! snippet (six bodies of one rock shape closing in on a ring), seen from
//! above at three frames: each body's world box, the pairs of boxes the
//! broad phase (`PairTracker`) reports, and which of them touch (the
//! narrow phase, `Mesh::intersects`).

use super::svg::{colour, Style, Svg};
use super::{Figure, FigureError};
use crate::TrackerBuffers;
use bvhkit::builders::DynamicConfig;
use bvhkit::collision::PairTracker;
use bvhkit::glam::{Quat, Vec2, Vec3};
use bvhkit::{Aabb, Mesh, Primitive, Rigid};
use std::path::Path;

pub(super) fn figures(book_src: &Path) -> Result<Vec<Figure>, FigureError> {
    let _ = book_src;
    Ok(vec![frame_loop()?])
}

/// Body `i` at frame `f`, as the chapter's snippet places it.
fn place(i: u32, f: u32) -> Result<Rigid, bvhkit::Error> {
    let a = i as f32 * std::f32::consts::TAU / 6.0 + f as f32 * 0.02;
    let r = 4.0 - f as f32 * 0.05;
    Rigid::new(
        Quat::from_rotation_y(a),
        Vec3::new(r * a.cos(), 0.0, r * a.sin()),
    )
}

/// Seen from above: x across, z up the page.
fn top(p: Vec3) -> Vec2 {
    Vec2::new(p.x, p.z)
}

fn frame_loop() -> Result<Figure, FigureError> {
    let rock = Mesh::new(crate::scene::rock(2, 1))?;
    let shape = rock
        .triangles()
        .iter()
        .fold(Aabb::EMPTY, |b, t| b.union(&t.bounds()));
    let mut storage = TrackerBuffers::new(6, 15);
    let config = DynamicConfig {
        margin: 0.1,
        ..Default::default()
    };
    let mut world = PairTracker::new(storage.storage(), config)?;
    for i in 0..6 {
        world.insert(i, &place(i, 0)?.apply_aabb(&shape))?;
    }
    let shown = [20, 41, 49];
    let (lo, hi) = (Vec2::splat(-5.3), Vec2::splat(5.3));
    let mut svg = Svg::new(900.0, 330.0, lo, hi);
    for f in 0..=shown[shown.len() - 1] {
        for i in 0..6 {
            world.set_bounds(i, &place(i, f)?.apply_aabb(&shape))?;
        }
        world.step(|_| {})?;
        let Some(panel) = shown.iter().position(|&s| s == f) else {
            continue;
        };
        let mut touching = Vec::new();
        for &(a, b) in world.pairs() {
            let b_in_a = place(a, f)?.inverse().after(&place(b, f)?);
            if rock.intersects(&rock, &b_in_a) {
                touching.push((a, b));
            }
        }
        svg.panel(
            panel,
            shown.len(),
            lo,
            hi,
            &format!(
                "frame {f}: {} box pairs, {} touch",
                world.pairs().len(),
                touching.len()
            ),
        );
        for i in 0..6u32 {
            let at = place(i, f)?;
            let seen: Vec<Vec2> = rock
                .triangles()
                .iter()
                .flat_map(|t| t.v)
                .map(|v| top(at.apply(v)))
                .collect();
            svg.polygon(&outline(seen), Style::filled(colour(0), 0.35).width(0.8));
            let b = world.boxes()[i as usize];
            let paired = world.pairs().iter().any(|&(a, c)| a == i || c == i);
            let style = if paired {
                Style::line(colour(1)).width(1.2)
            } else {
                Style::line("#999999").width(0.8).dashed()
            };
            svg.rect(top(b.min), top(b.max), style);
        }
        let centre = |i: u32| top(world.boxes()[i as usize].center());
        for &(a, b) in world.pairs() {
            let style = if touching.contains(&(a, b)) {
                Style::line(colour(5)).width(2.5)
            } else {
                Style::line(colour(1)).width(0.8).dashed()
            };
            svg.line(centre(a), centre(b), style);
        }
    }
    Ok(Figure {
        name: "engines-frame-loop",
        chapter: "engines.md",
        svg: svg.finish(),
    })
}

/// The convex outline of points in the plane, counter-clockwise (Andrew's
/// monotone chain): a body seen from above, one polygon instead of its
/// hundreds of triangles.
fn outline(mut p: Vec<Vec2>) -> Vec<Vec2> {
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let turn = |o: Vec2, a: Vec2, b: Vec2| (a - o).perp_dot(b - o);
    let mut hull: Vec<Vec2> = Vec::with_capacity(2 * p.len());
    for pass in 0..2 {
        let start = hull.len();
        let points: Box<dyn Iterator<Item = &Vec2>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &q in points {
            while hull.len() >= start + 2
                && turn(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop(); // the next pass starts from it
    }
    hull
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_outline_is_the_convex_hull() {
        // A square's corners, points inside and on its edges, repeated.
        let mut p = vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(2.0, 0.0),
            Vec2::new(2.0, 2.0),
            Vec2::new(0.0, 2.0),
        ];
        p.extend([
            Vec2::new(1.0, 1.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(2.0, 1.5),
            Vec2::new(0.5, 1.9),
        ]);
        p.extend(p.clone());
        let hull = outline(p);
        assert_eq!(
            hull,
            [
                Vec2::new(0.0, 0.0),
                Vec2::new(2.0, 0.0),
                Vec2::new(2.0, 2.0),
                Vec2::new(0.0, 2.0)
            ]
        );
        // A triangle, and a single point.
        let tri = outline(vec![
            Vec2::new(3.0, 0.0),
            Vec2::ZERO,
            Vec2::new(1.0, 2.0),
            Vec2::new(1.0, 0.5),
        ]);
        assert_eq!(tri, [Vec2::ZERO, Vec2::new(3.0, 0.0), Vec2::new(1.0, 2.0)]);
        assert_eq!(outline(vec![Vec2::ONE; 3]), [Vec2::ONE]);
    }
}
