//! Exercise 41: box against triangle, exactly. The checks, and the plausible
//! wrong answers they must reject. Each case is graded against the library's
//! `narrow::box_triangle_intersect`.

use super::common::*;

/// The checks of exercise 41.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 41,
            name: "boxes and triangles near each other, at three scales",
            points: 4,
            run: |e| agrees(e, &near_cases()),
        },
        Check {
            exercise: 41,
            name: "a plane across a box's corner: through it, just past it, just short of it",
            points: 3,
            run: |e| agrees(e, &corner_cases()),
        },
        Check {
            exercise: 41,
            name: "separated only by an edge of the triangle crossed with a box axis",
            points: 3,
            run: |e| agrees(e, &edge_cases()),
        },
        Check {
            exercise: 41,
            name: "touching counts; flat boxes, zero-area triangles, a box through a face",
            points: 2,
            run: |e| agrees(e, &touching_cases()),
        },
    ]
}

/// Whether `e` answers every case as the library does; explains the first
/// that differs.
fn agrees(e: &dyn Exercises, cases: &[(Aabb, Triangle)]) -> bool {
    cases.iter().all(|(b, t)| {
        let want = Reference.box_triangle(b, t);
        let got = e.box_triangle(b, t);
        got == want
            || fail(format!(
                "box_triangle({}, triangle {} {} {}) returned {got}, expected {want}",
                show_box(b),
                show_point(t.v[0]),
                show_point(t.v[1]),
                show_point(t.v[2])
            ))
    })
}

fn tri(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> Triangle {
    Triangle::new(Vec3::from(a), Vec3::from(b), Vec3::from(c))
}

/// The box's corner `k`: bit `a` of `k` picks min or max on axis `a`.
fn corner(b: &Aabb, k: usize) -> Vec3 {
    Vec3::new(
        if k & 1 == 0 { b.min.x } else { b.max.x },
        if k & 2 == 0 { b.min.y } else { b.max.y },
        if k & 4 == 0 { b.min.z } else { b.max.z },
    )
}

/// Random boxes (some flat) with triangles around them: vertices near the
/// box, on its corners or on its faces; at unit scale, a thousandth, and a
/// thousand units from the origin.
fn near_cases() -> Vec<(Aabb, Triangle)> {
    let mut r = Rng(0x41b0_7e57);
    let mut out = Vec::new();
    for i in 0..1500 {
        let (scale, offset) = [(1.0, 0.0), (1e-3, 0.0), (1.0, 1000.0)][i % 3];
        let offset = Vec3::splat(offset);
        let min = r.point(2.0 * scale, offset);
        let mut extent = Vec3::new(r.next(), r.next(), r.next()) * scale;
        if i % 11 == 0 {
            extent[i % 3] = 0.0;
        }
        let b = Aabb::new(min, min + extent);
        let mut vertex = |kind: usize| match kind {
            0 => corner(&b, (r.next() * 8.0) as usize % 8),
            1 => {
                let mut p =
                    b.center() + Vec3::new(r.next() - 0.5, r.next() - 0.5, r.next() - 0.5) * extent;
                let k = (r.next() * 3.0) as usize % 3;
                p[k] = if r.next() < 0.5 { b.min[k] } else { b.max[k] };
                p
            }
            _ => r.point(3.0 * scale, b.center()),
        };
        let v = [vertex(i % 4), vertex(i / 4 % 4), vertex(2)];
        out.push((b, Triangle::new(v[0], v[1], v[2])));
    }
    out
}

/// Triangles square to a corner's diagonal, with their plane through the
/// corner (touching), a little past it, and a little short of it, down to
/// one `f32` step, on a unit box and on a box a thousand units out (where a
/// plane test computed in `f32` rounds the wrong way).
fn corner_cases() -> Vec<(Aabb, Triangle)> {
    let mut out = Vec::new();
    for (lo, hi) in [(0.0f32, 1.0f32), (1000.0, 1001.0), (-3.0, 5.0)] {
        let b = Aabb::new(Vec3::splat(lo), Vec3::splat(hi));
        for k in 0..8 {
            let c = corner(&b, k);
            let out_dir = Vec3::new(
                if k & 1 == 0 { -1.0 } else { 1.0 },
                if k & 2 == 0 { -1.0 } else { 1.0 },
                if k & 4 == 0 { -1.0 } else { 1.0 },
            );
            // One f32 step at this magnitude, and a few more.
            let step = f32::EPSILON * c.abs().max_element().max(1.0);
            for h in [0.5f32, 0.75] {
                for d in [0.0, step, -step, 3.0 * step, -3.0 * step, 1e-3, -1e-3] {
                    let (long, short) = (2.0 * h + d, -h + d);
                    out.push((
                        b,
                        Triangle::new(
                            c + out_dir * Vec3::new(long, short, short),
                            c + out_dir * Vec3::new(short, long, short),
                            c + out_dir * Vec3::new(short, short, long),
                        ),
                    ));
                }
            }
        }
    }
    out
}

/// Cases where the box's axes and the triangle's plane do not separate, but
/// an edge crossed with a box axis does (or just fails to), by hand and by
/// mirroring them into every octant.
fn edge_cases() -> Vec<(Aabb, Triangle)> {
    let unit = b([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]);
    let base = [
        // Edge along x + y = 2.1 at z = 0.5, the plane tilted through the box.
        tri([1.6, 0.5, 0.5], [0.5, 1.6, 0.5], [3.0, 3.0, 5.0]),
        // The same edge along x + y = 2: it touches the box's edge.
        tri([1.5, 0.5, 0.5], [0.5, 1.5, 0.5], [3.0, 3.0, 5.0]),
        // Along y + z = 2.25 past the box's x-parallel edge.
        tri([0.5, 1.75, 0.5], [0.5, 0.5, 1.75], [4.0, 3.0, 3.0]),
        // A zero-area triangle (a segment) along x + y = 2.1: no plane at all.
        tri([2.6, -0.5, 0.5], [-0.5, 2.6, 0.5], [2.6, -0.5, 0.5]),
        // The same segment along x + y = 2: touching.
        tri([2.5, -0.5, 0.5], [-0.5, 2.5, 0.5], [2.5, -0.5, 0.5]),
        // A segment along x - z = 1.25 at y = 0.5.
        tri([1.5, 0.5, 0.25], [2.5, 0.5, 1.25], [1.5, 0.5, 0.25]),
    ];
    let mut out = Vec::new();
    for t in base {
        for m in 0..8 {
            // Mirror through the box's centre on the axes set in `m`.
            let flip = |p: Vec3| {
                Vec3::new(
                    if m & 1 == 0 { p.x } else { 1.0 - p.x },
                    if m & 2 == 0 { p.y } else { 1.0 - p.y },
                    if m & 4 == 0 { p.z } else { 1.0 - p.z },
                )
            };
            out.push((
                unit,
                Triangle::new(flip(t.v[0]), flip(t.v[1]), flip(t.v[2])),
            ));
        }
    }
    out
}

/// Contact without overlap, and the degenerate shapes.
fn touching_cases() -> Vec<(Aabb, Triangle)> {
    let unit = b([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]);
    vec![
        // A vertex on a face, the rest outside.
        (unit, tri([0.5, 0.5, 1.0], [0.0, 0.0, 3.0], [1.0, 0.0, 3.0])),
        // A vertex one step above that face: apart.
        (
            unit,
            tri(
                [0.5, 0.5, 1.0 + f32::EPSILON],
                [0.0, 0.0, 3.0],
                [1.0, 0.0, 3.0],
            ),
        ),
        // An edge lying on the box's edge x = 1, y = 1.
        (
            unit,
            tri([1.0, 1.0, -1.0], [1.0, 1.0, 2.0], [3.0, 2.0, 0.5]),
        ),
        // A face flush with the box's top face.
        (
            unit,
            tri([-1.0, -1.0, 1.0], [3.0, -1.0, 1.0], [-1.0, 3.0, 1.0]),
        ),
        // A big triangle with a small box through its middle, no edge near.
        (
            b([0.4, 0.4, -0.1], [0.6, 0.6, 0.1]),
            tri([-5.0, -5.0, 0.0], [9.0, -5.0, 0.0], [-5.0, 9.0, 0.0]),
        ),
        // The same box just above the triangle's plane.
        (
            b([0.4, 0.4, 0.001], [0.6, 0.6, 0.1]),
            tri([-5.0, -5.0, 0.0], [9.0, -5.0, 0.0], [-5.0, 9.0, 0.0]),
        ),
        // A flat box lying in the triangle's plane, inside it.
        (
            b([0.1, 0.1, 0.0], [0.2, 0.2, 0.0]),
            tri([0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [0.0, 4.0, 0.0]),
        ),
        // A point box on the triangle, and just off it.
        (
            b([0.5, 0.5, 0.0], [0.5, 0.5, 0.0]),
            tri([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ),
        (
            b([0.5, 0.5, 0.25], [0.5, 0.5, 0.25]),
            tri([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ),
        // A point box on the hypotenuse, and one step beyond it.
        (
            b([0.5, 0.5, 0.0], [0.5, 0.5, 0.0]),
            tri([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.0]),
        ),
        (
            b([0.5, 0.50000006, 0.0], [0.5, 0.50000006, 0.0]),
            tri([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.0]),
        ),
        // A segment through the box, and a point on its corner.
        (
            unit,
            tri([-1.0, 0.5, 0.5], [2.0, 0.5, 0.5], [-1.0, 0.5, 0.5]),
        ),
        (unit, tri([1.0, 1.0, 1.0], [1.0, 1.0, 1.0], [1.0, 1.0, 1.0])),
        // A point just outside the corner.
        (
            unit,
            tri(
                [1.0, 1.0, 1.0000001],
                [1.0, 1.0, 1.0000001],
                [1.0, 1.0, 1.0000001],
            ),
        ),
    ]
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;
    use bvhkit::narrow::{orient2, orient3};

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 8;

    pub fn box_triangle(which: u32, bx: &Aabb, t: &Triangle) -> bool {
        let [v0, v1, v2] = t.v;
        let (lo, hi) = (v0.min(v1).min(v2), v0.max(v1).max(v2));
        let apart = if which == 4 {
            // 4: touching is taken for apart.
            hi.cmple(bx.min).any() || lo.cmpge(bx.max).any()
        } else {
            hi.cmplt(bx.min).any() || lo.cmpgt(bx.max).any()
        };
        if apart {
            return false;
        }
        match which {
            // 1: the bounding boxes only.
            1 => return true,
            // 8: a vertex in the box, or an edge meeting it.
            8 => {
                let inside =
                    t.v.iter()
                        .any(|p| p.cmpge(bx.min).all() && p.cmple(bx.max).all());
                return inside
                    || (0..3).any(|i| {
                        let (a, c) = (t.v[i], t.v[(i + 1) % 3]);
                        Reference.box_triangle(bx, &Triangle::new(a, c, a))
                    });
            }
            _ => {}
        }
        let signs: Vec<i8> = (0..8)
            .map(|k| {
                let c = corner(bx, k);
                if which == 5 {
                    // 5: the plane test in f32 arithmetic.
                    let d = (v1 - v0).cross(v2 - v0).dot(c - v0);
                    (d > 0.0) as i8 - (d < 0.0) as i8
                } else {
                    orient3(v0, v1, v2, c)
                }
            })
            .collect();
        let one_side = if which == 4 {
            signs.iter().all(|&s| s >= 0) || signs.iter().all(|&s| s <= 0)
        } else {
            signs[0] != 0 && signs.iter().all(|&s| s == signs[0])
        };
        // 2: no plane test.
        if which != 2 && one_side {
            return false;
        }
        // 3: no edge tests.
        if which == 3 {
            return true;
        }
        for k in 0..3 {
            let (u, w) = ((k + 1) % 3, (k + 2) % 3);
            let rect = |m: usize| {
                let mut p = bx.min;
                p[u] = if m & 1 == 0 { bx.min[u] } else { bx.max[u] };
                p[w] = if m & 2 == 0 { bx.min[w] } else { bx.max[w] };
                p
            };
            for (a, c, m) in [(v0, v1, v2), (v1, v2, v0), (v2, v0, v1)] {
                let inner = orient2(a, c, m, k);
                let sides: Vec<i8> = (0..4).map(|q| orient2(a, c, rect(q), k)).collect();
                let beyond = match (which, inner) {
                    // 7: a flat projection separates nothing.
                    (7, 0) => false,
                    (_, 0) => sides[0] != 0 && sides.iter().all(|&s| s == sides[0]),
                    // 6: the corners on the third vertex's side.
                    (6, _) => sides.iter().all(|&s| s == inner),
                    (4, _) => sides.iter().all(|&s| s != inner),
                    _ => sides.iter().all(|&s| s == -inner),
                };
                if beyond {
                    return false;
                }
            }
        }
        true
    }
}
