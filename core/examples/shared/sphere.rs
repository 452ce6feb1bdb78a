//! A shared helper of the examples (not an example itself).

use bvhkit::glam::Vec3;
use bvhkit::Triangle;

/// A unit sphere of `2 * n * n` triangles (`n` bands of `2n` sectors).
pub fn triangles(n: usize) -> Vec<Triangle> {
    let point = |band: usize, sector: usize| {
        let (theta, phi) = (
            core::f32::consts::PI * band as f32 / n as f32,
            core::f32::consts::PI * sector as f32 / n as f32,
        );
        Vec3::new(
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        )
    };
    let mut out = Vec::new();
    for band in 0..n {
        for sector in 0..2 * n {
            let (a, b) = (point(band, sector), point(band, sector + 1));
            let (c, d) = (point(band + 1, sector), point(band + 1, sector + 1));
            out.push(Triangle::new(a, c, b));
            out.push(Triangle::new(b, c, d));
        }
    }
    out
}
