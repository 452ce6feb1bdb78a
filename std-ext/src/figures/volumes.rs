//! Bounding volumes: the four kinds fitted around one point set.

use super::svg::{colour, Style, Svg};
use super::{kdop_section, lift, obb_section, Figure, FigureError};
use bvhkit::glam::Vec2;
use bvhkit::{Aabb, BoundingVolume, Dop18, Obb, Sphere};

pub(super) fn figures() -> Result<Vec<Figure>, FigureError> {
    Ok(vec![volumes_around_points()])
}

/// A tilted, elongated cloud: where the four volumes differ most.
fn cloud() -> Vec<Vec2> {
    let mut s = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
    };
    let (c, sn) = (0.5f32.cos(), 0.5f32.sin());
    (0..24)
        .map(|_| {
            let (u, v) = (next() * 3.0, next() * 0.8);
            Vec2::new(u * c - v * sn, u * sn + v * c)
        })
        .collect()
}

/// Area of a polygon (shoelace).
fn area(poly: &[Vec2]) -> f32 {
    let mut a = 0.0;
    for (i, p) in poly.iter().enumerate() {
        let q = poly[(i + 1) % poly.len()];
        a += p.perp_dot(q);
    }
    a.abs() * 0.5
}

fn volumes_around_points() -> Figure {
    let points = cloud();
    let pts3 = lift(&points);
    let aabb = Aabb::fit(pts3.as_slice());
    let sphere = Sphere::welzl(pts3.as_slice());
    let obb = Obb::pca(pts3.as_slice());
    let dop = Dop18::fit(pts3.as_slice());
    let (lo, hi) = (
        sphere.center.truncate() - Vec2::splat(sphere.radius),
        sphere.center.truncate() + Vec2::splat(sphere.radius),
    );
    let (lo, hi) = (lo.min(aabb.min.truncate()), hi.max(aabb.max.truncate()));
    let box_poly = [
        aabb.min.truncate(),
        Vec2::new(aabb.max.x, aabb.min.y),
        aabb.max.truncate(),
        Vec2::new(aabb.min.x, aabb.max.y),
    ];
    let panels: [(&str, Vec<Vec2>); 4] = [
        ("box (AABB)", box_poly.to_vec()),
        ("sphere (Welzl)", Vec::new()),
        ("OBB (PCA)", obb_section(&obb)),
        ("18-DOP", kdop_section(&dop)),
    ];
    let mut svg = Svg::new(880.0, 260.0, lo, hi);
    for (i, (name, poly)) in panels.iter().enumerate() {
        let a = if poly.is_empty() {
            core::f32::consts::PI * sphere.radius * sphere.radius
        } else {
            area(poly)
        };
        svg.panel(i, 4, lo, hi, &format!("{name}: area {a:.1}"));
        let style = Style::filled(colour(i), 0.15);
        if poly.is_empty() {
            svg.circle(sphere.center.truncate(), sphere.radius, style);
        } else {
            svg.polygon(poly, style);
        }
        for &p in &points {
            svg.dot(p, 2.5, "#000000");
        }
    }
    Figure {
        name: "volumes-around-points",
        chapter: "bounding-volumes.md",
        svg: svg.finish(),
    }
}
