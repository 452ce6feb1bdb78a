//! Figures of the book's `collision-system.md` chapter: the split between
//! the pairs a tree query delivers (their boxes overlap) and the pairs that
//! really touch (the exact triangle test), on one object against a moved
//! copy of itself.

use super::descent::{corners, outline};
use super::svg::{colour, Style, Svg};
use super::{Figure, FigureError};
use crate::OwnedBvh;
use bvhkit::glam::{DVec3, Quat, Vec2, Vec3};
use bvhkit::narrow::{triangle_contact, Contact};
use bvhkit::{Aabb, Counts, Hierarchy, Pairs, Primitive, Rigid, TopDown, Transform, Triangle};
use std::path::Path;

pub(super) fn figures(book_src: &Path) -> Result<Vec<Figure>, FigureError> {
    let _ = book_src;
    Ok(vec![candidates_and_contacts()?])
}

/// A point of a contact, in the plane.
fn flat(p: &DVec3) -> Vec2 {
    p.truncate().as_vec2()
}

/// One outline against a turned and shifted copy of itself (one tree, two
/// objects, as in the chapter): the objects' boxes, the candidate pairs and
/// the touching pairs with where they touch.
fn candidates_and_contacts() -> Result<Figure, FigureError> {
    let tris = outline(16, 2.0, 0.0, 0x7f4a_7c15_9e37_79b9);
    let tree = OwnedBvh::<Aabb>::build(&TopDown::default().with_max_leaf_size(1), &tris)?;
    let t = tree.view();
    let motion = Rigid::new(Quat::from_rotation_z(0.5), Vec3::new(2.7, 1.1, 0.0))?;
    // B's triangles where the motion puts them, as the query places them.
    let moved: Vec<Triangle> = tris.iter().map(|p| p.transformed(&motion)).collect();

    // The candidates: the pair query's default answer (boxes overlap).
    let mut counts = Counts::default();
    let mut candidates = Vec::new();
    Pairs::new(&t, &tris, &t, &tris)
        .in_frame(motion)
        .counted(&mut counts)
        .for_each(|i, j| candidates.push((i, j)))?;
    // The same walk with the exact answer.
    let mut touching = Vec::new();
    Pairs::new(&t, &tris, &t, &tris)
        .in_frame(motion)
        .exact()
        .for_each(|i, j| touching.push((i, j)))?;
    let contacts = touching
        .iter()
        .map(|&(i, j)| triangle_contact(&tris[i as usize], &moved[j as usize]))
        .collect::<Option<Vec<Contact>>>()
        .ok_or_else(|| {
            FigureError("a touching pair of the collision figure has no contact".into())
        })?;

    let box_a = Hierarchy::bv(&t, 0);
    let box_b = moved.iter().fold(Aabb::EMPTY, |b, p| b.union(&p.bounds()));
    let all = box_a.union(&box_b);
    let (lo, hi) = (
        all.min.truncate() - Vec2::splat(0.2),
        all.max.truncate() + Vec2::splat(0.2),
    );
    let (ca, cb) = (colour(0), colour(2));
    let draw_objects = |svg: &mut Svg, opacity: f32| {
        for (set, c) in [(&tris, ca), (&moved, cb)] {
            for p in set.iter() {
                svg.polygon(&corners(p), Style::filled(c, opacity).width(0.8));
            }
        }
    };
    let mut svg = Svg::new(900.0, 300.0, lo, hi);

    svg.panel(0, 3, lo, hi, "broad phase: boxes of A and B overlap");
    draw_objects(&mut svg, 0.3);
    for (b, c) in [(box_a, ca), (box_b, cb)] {
        svg.rect(
            b.min.truncate(),
            b.max.truncate(),
            Style::line(c).width(1.5),
        );
    }
    let both = Aabb::new(box_a.min.max(box_b.min), box_a.max.min(box_b.max));
    svg.rect(
        both.min.truncate(),
        both.max.truncate(),
        Style::filled("#777777", 0.15).width(0.5).dashed(),
    );

    svg.panel(
        1,
        3,
        lo,
        hi,
        &format!(
            "{} candidate pairs (Nv {}, Np {})",
            candidates.len(),
            counts.bv_tests,
            counts.prim_tests
        ),
    );
    draw_objects(&mut svg, 0.12);
    for &(i, j) in &candidates {
        for (p, c) in [(&tris[i as usize], ca), (&moved[j as usize], cb)] {
            svg.polygon(&corners(p), Style::filled(c, 0.45).width(1.0));
        }
    }
    for &(i, j) in &candidates {
        let (p, q) = (tris[i as usize].bounds(), moved[j as usize].bounds());
        let common = Aabb::new(p.min.max(q.min), p.max.min(q.max));
        svg.rect(
            common.min.truncate(),
            common.max.truncate(),
            Style::filled(colour(1), 0.5).width(1.0),
        );
    }

    svg.panel(
        2,
        3,
        lo,
        hi,
        &format!("{} of them touch (exact test)", touching.len()),
    );
    draw_objects(&mut svg, 0.12);
    for (&(i, j), contact) in touching.iter().zip(&contacts) {
        for (p, c) in [(&tris[i as usize], ca), (&moved[j as usize], cb)] {
            svg.polygon(&corners(p), Style::filled(c, 0.45).width(1.0));
        }
        let points: Vec<Vec2> = contact.points().iter().map(flat).collect();
        match contact {
            Contact::Area { .. } if points.len() >= 3 => {
                svg.polygon(&points, Style::filled(colour(5), 0.9).width(1.0))
            }
            _ => {
                svg.line(
                    points[0],
                    points[points.len() - 1],
                    Style::line(colour(5)).width(2.0),
                );
                svg.dot(points[0], 2.5, colour(5));
            }
        }
    }
    Ok(Figure {
        name: "collision-candidates-and-contacts",
        chapter: "collision-system.md",
        svg: svg.finish(),
    })
}
