//! Exercise 21: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 21.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 21,
            name: "touching and nested boxes overlap",
            points: 3,
            run: |e| {
                let (a, touching) = (cube(Vec3::ZERO), cube(Vec3::new(2.0, 0.5, 0.0)));
                let inner = Obb {
                    half_extents: Vec3::splat(0.25),
                    ..turned(Vec3::ZERO, 0.7, 0.3)
                };
                // Touching along z only, with exact numbers: a face shared.
                let on_top = cube(Vec3::new(-0.5, 0.25, 2.0));
                overlap_is(e, &a, &touching, true)
                    && overlap_is(e, &a, &on_top, true)
                    && overlap_is(e, &a, &inner, true)
            },
        },
        Check {
            exercise: 21,
            name: "apart along one axis, on either side, and along a turned box's own axis only",
            points: 2,
            run: |e| {
                let a = cube(Vec3::ZERO);
                // Apart along x, y or z by 0.5, on both sides; and a cube
                // turned 45 degrees about z, apart along A's x by 0.1.
                let mut pairs = Vec::new();
                for k in 0..3 {
                    for s in [-1.0, 1.0] {
                        let mut c = Vec3::ZERO;
                        c[k] = 2.5 * s;
                        pairs.push(cube(c));
                    }
                }
                for s in [-1.0, 1.0] {
                    pairs.push(Obb {
                        center: Vec3::new((1.1 + std::f32::consts::SQRT_2) * s, 0.3, 0.0),
                        ..turned_cube(std::f32::consts::FRAC_PI_4)
                    });
                }
                // A box turned about two axes, 0.05 beyond the other along
                // its own thinnest axis and along no other of the fifteen
                // (each of them overlaps by 0.3 or more).
                let flat = turned(Vec3::ZERO, 0.0, 0.0);
                let tilted = turned(Vec3::ZERO, 0.75, 4.25);
                let u = tilted.axes[2];
                let reach = |x: &Obb| -> f32 {
                    (0..3)
                        .map(|k| x.half_extents[k] * x.axes[k].dot(u).abs())
                        .sum()
                };
                let t = reach(&flat) + reach(&tilted) + 0.05;
                let beyond = Obb {
                    center: u * t,
                    ..tilted
                };
                pairs.iter().all(|b| overlap_is(e, &a, b, false))
                    && overlap_is(e, &flat, &beyond, false)
            },
        },
        Check {
            exercise: 21,
            name: "random turned boxes, edge-to-edge misses included, against the library",
            points: 5,
            run: |e| {
                let mut r = Rng(21);
                let mut clear = 0;
                let agree = (0..4000).all(|_| {
                    let a = turned(r.point(0.5, Vec3::ZERO), r.next() * 6.0, r.next() * 6.0);
                    let b = turned(r.point(5.0, Vec3::ZERO), r.next() * 6.0, r.next() * 6.0);
                    // Only pairs the answer of which does not change when
                    // both boxes grow or shrink by 1%: no rounding question.
                    let scaled = |x: &Obb, f: f32| Obb {
                        half_extents: x.half_extents * f,
                        ..*x
                    };
                    let lo = scaled(&a, 0.99).overlaps(&scaled(&b, 0.99));
                    let hi = scaled(&a, 1.01).overlaps(&scaled(&b, 1.01));
                    if lo != hi {
                        return true;
                    }
                    clear += 1;
                    overlap_is(e, &a, &b, lo)
                });
                agree
                    && (clear > 3000
                        || fail(format!("only {clear} of 4000 random pairs were clear-cut")))
            },
        },
    ]
}

/// The cube of half extent 1 at `c`, along the coordinate axes.
fn cube(c: Vec3) -> Obb {
    Obb {
        center: c,
        axes: [Vec3::X, Vec3::Y, Vec3::Z],
        half_extents: Vec3::ONE,
    }
}

/// The cube of half extent 1 at the origin, turned by `yaw` about z.
fn turned_cube(yaw: f32) -> Obb {
    let q = bvhkit::glam::Quat::from_rotation_z(yaw);
    Obb {
        center: Vec3::ZERO,
        axes: [q * Vec3::X, q * Vec3::Y, Vec3::Z],
        half_extents: Vec3::ONE,
    }
}

/// An oriented box in words.
fn show_obb(x: &Obb) -> String {
    format!(
        "[centre {}, axes {}, {}, {}, half extents {}]",
        show_point(x.center),
        show_point(x.axes[0]),
        show_point(x.axes[1]),
        show_point(x.axes[2]),
        show_point(x.half_extents)
    )
}

/// Asks about `a, b` and `b, a`: the answer must be `want` both ways.
fn overlap_is(e: &dyn Exercises, a: &Obb, b: &Obb, want: bool) -> bool {
    let ask = |a: &Obb, b: &Obb| {
        let call = format!("obb_overlaps({}, {})", show_obb(a), show_obb(b));
        same(call, want, e.obb_overlaps(a, b))
    };
    ask(a, b) && ask(b, a)
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 6;

    /// The separating-axis test over `axes`: on each, apart when the centres'
    /// distance `dist` exceeds the radii (`>=` when `strict`), the radius of
    /// a box given by `radius`.
    fn sat(
        a: &Obb,
        b: &Obb,
        axes: &[Vec3],
        dist: impl Fn(f32) -> f32,
        radius: impl Fn(&Obb, Vec3) -> f32,
        strict: bool,
    ) -> bool {
        !axes.iter().any(|&l| {
            if l.length_squared() < 1e-12 {
                return false;
            }
            let d = dist((b.center - a.center).dot(l));
            let r = radius(a, l) + radius(b, l);
            if strict {
                d >= r
            } else {
                d > r
            }
        })
    }

    fn radius(x: &Obb, l: Vec3) -> f32 {
        (0..3)
            .map(|k| x.half_extents[k] * x.axes[k].dot(l).abs())
            .sum()
    }

    fn cross(a: &Obb, b: &Obb) -> Vec<Vec3> {
        a.axes
            .iter()
            .flat_map(|&u| b.axes.iter().map(move |&v| u.cross(v)))
            .collect()
    }

    pub fn obb_overlaps(which: u32, a: &Obb, b: &Obb) -> bool {
        let faces: Vec<Vec3> = a.axes.iter().chain(&b.axes).copied().collect();
        let all: Vec<Vec3> = faces.iter().copied().chain(cross(a, b)).collect();
        match which {
            // Face axes only: misses boxes that pass edge to edge.
            1 => sat(a, b, &faces, f32::abs, radius, false),
            // Touching counts as apart.
            2 => sat(a, b, &faces, f32::abs, radius, true) && Reference.obb_overlaps(a, b),
            // The centres' distance without its absolute value: only a box
            // on the positive side is ever apart.
            3 => sat(a, b, &all, |d| d, radius, false),
            // The radius without absolute values: turned axes cancel out.
            4 => sat(
                a,
                b,
                &all,
                f32::abs,
                |x, l| (0..3).map(|k| x.half_extents[k] * x.axes[k].dot(l)).sum(),
                false,
            ),
            // A's face axes and the cross products, but not B's face axes.
            5 => {
                let some: Vec<Vec3> = a.axes.iter().copied().chain(cross(a, b)).collect();
                sat(a, b, &some, f32::abs, radius, false)
            }
            // The half extents taken as full sizes (halved again).
            6 => sat(a, b, &all, f32::abs, |x, l| radius(x, l) / 2.0, false),
            _ => Reference.obb_overlaps(a, b),
        }
    }
}
