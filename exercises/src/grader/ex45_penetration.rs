//! Exercise 45: how deep two overlapping boxes, or two spheres, are. The
//! checks, and the plausible wrong answers they must reject.
//!
//! Every expected answer is the library's `narrow::Penetrate` (its normal
//! and depth; not its point). The hand-made cases have small coordinates,
//! so that every move is exact in `f64`, and carry their answers written
//! out (a test checks that the library gives them). Each is also asked with
//! the axes in each of their six orders, each of the eight mirrorings, and
//! the two shapes both ways round (96 questions per case), each answer asked
//! of the library: a tie keeps the library's order (the lowest axis, then
//! `+`) however the case is turned, so only that order passes. The random
//! cases, at three scales, are kept only where nothing is close: no move
//! (or sphere depth) within a thousandth of the scale of zero, and the least
//! move of two boxes clear of the next by as much, so that any honest
//! formula in `f64` agrees with the library there.

use super::common::*;
use bvhkit::glam::DVec3;
use bvhkit::narrow::Penetrate;

/// The checks of exercise 45.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 45,
            name: "overlapping boxes: the least of the six moves, out of the nearer side of the \
                   axis of least overlap",
            points: 1,
            run: |e| agrees(e, &variants(&overlapping_boxes())),
        },
        Check {
            exercise: 45,
            name: "one box spanning the other on an axis: the way out, not the overlap's width",
            points: 1,
            run: |e| agrees(e, &variants(&spanning_boxes())),
        },
        Check {
            exercise: 45,
            name: "boxes touching at a face, an edge or a corner overlap with depth 0; boxes \
                   apart, and the empty box, do not",
            points: 1,
            run: |e| agrees(e, &variants(&touching_boxes())),
        },
        Check {
            exercise: 45,
            name: "flat boxes and points: a plate, two plates in one plane, a point inside, on \
                   and outside a box",
            points: 1,
            run: |e| agrees(e, &variants(&flat_boxes())),
        },
        Check {
            exercise: 45,
            name: "ties between moves: the lowest axis, then the move towards +",
            points: 1,
            run: |e| agrees(e, &variants(&tied_boxes())),
        },
        Check {
            exercise: 45,
            name: "random boxes at three scales, as Penetrate places them",
            points: 1,
            run: |e| agrees(e, &random_boxes()),
        },
        Check {
            exercise: 45,
            name: "overlapping spheres: along the line of centres, a unit normal, the radii's \
                   sum less the distance",
            points: 1,
            run: |e| agrees(e, &variants(&overlapping_spheres())),
        },
        Check {
            exercise: 45,
            name: "spheres touching (depth 0) and apart, points (radius 0), and the empty sphere \
                   (negative radius), which overlaps nothing",
            points: 1,
            run: |e| agrees(e, &variants(&touching_spheres())),
        },
        Check {
            exercise: 45,
            name: "one sphere around the other's centre; the same centre: +x",
            points: 1,
            run: |e| agrees(e, &variants(&nested_spheres())),
        },
        Check {
            exercise: 45,
            name: "random spheres at three scales, as Penetrate places them",
            points: 1,
            run: |e| agrees(e, &random_spheres()),
        },
    ]
}

/// A normal and a depth, or `None`.
type Answer = Option<(DVec3, f64)>;

/// Two shapes and how deep they overlap.
#[derive(Clone, Copy, Debug)]
struct Case<S> {
    a: S,
    b: S,
    want: Answer,
}

/// An axis order and mirroring: new axis `i` is old axis `order[i]`,
/// negated when `mirror[i]`.
#[derive(Clone, Copy, Debug)]
struct Turn {
    order: [usize; 3],
    mirror: [bool; 3],
}

impl Turn {
    fn point(&self, p: Vec3) -> Vec3 {
        let mut q = Vec3::ZERO;
        for i in 0..3 {
            q[i] = if self.mirror[i] {
                -p[self.order[i]] + 0.0
            } else {
                p[self.order[i]]
            };
        }
        q
    }
}

/// What the checks need of boxes and spheres alike.
trait Solid: Copy + std::fmt::Debug + Penetrate {
    /// The method under test.
    const METHOD: &'static str;
    fn ask(e: &dyn Exercises, a: &Self, b: &Self) -> Answer;
    fn show(&self) -> String;
    /// The largest finite coordinate (or radius), in magnitude.
    fn largest(&self) -> f64;
    /// The shape with its axes turned (exact: coordinates are only
    /// reordered and negated).
    fn turned(&self, t: &Turn) -> Self;
}

impl Solid for Aabb {
    const METHOD: &'static str = "box_penetration";
    fn ask(e: &dyn Exercises, a: &Self, b: &Self) -> Answer {
        e.box_penetration(a, b)
    }
    fn show(&self) -> String {
        if *self == Aabb::EMPTY {
            return "Aabb::EMPTY".to_string();
        }
        show_box(self)
    }
    fn largest(&self) -> f64 {
        let m = self.min.abs().max(self.max.abs());
        m.to_array()
            .into_iter()
            .filter(|x| x.is_finite())
            .fold(0.0, |acc, x| acc.max(f64::from(x)))
    }
    fn turned(&self, t: &Turn) -> Self {
        // Mirrored, an axis's min comes from the old max: the empty box
        // stays empty.
        let (mut lo, mut hi) = (Vec3::ZERO, Vec3::ZERO);
        for i in 0..3 {
            let k = t.order[i];
            (lo[i], hi[i]) = if t.mirror[i] {
                // `+ 0.0`: a mirrored 0 prints as 0, not -0.
                (-self.max[k] + 0.0, -self.min[k] + 0.0)
            } else {
                (self.min[k], self.max[k])
            };
        }
        Aabb::new(lo, hi)
    }
}

impl Solid for Sphere {
    const METHOD: &'static str = "sphere_penetration";
    fn ask(e: &dyn Exercises, a: &Self, b: &Self) -> Answer {
        e.sphere_penetration(a, b)
    }
    fn show(&self) -> String {
        format!("sphere {} radius {}", show_point(self.center), self.radius)
    }
    fn largest(&self) -> f64 {
        f64::from(self.center.abs().max_element().max(self.radius.abs()))
    }
    fn turned(&self, t: &Turn) -> Self {
        Sphere {
            center: t.point(self.center),
            radius: self.radius,
        }
    }
}

/// The library's answer: its normal and depth.
fn library<S: Solid>(a: &S, b: &S) -> Answer {
    a.penetration(b).map(|p| (p.normal, p.depth))
}

/// 1e-9 times the largest coordinate or radius of the two shapes, at least
/// 1e-9.
fn tolerance<S: Solid>(a: &S, b: &S) -> f64 {
    1e-9 * a.largest().max(b.largest()).max(1.0)
}

/// Whether two answers agree: both `None`, or normals within 1e-9 and
/// depths within `tol`.
fn same_answer(got: Answer, want: Answer, tol: f64) -> bool {
    match (got, want) {
        (None, None) => true,
        (Some((n, d)), Some((wn, wd))) => (n - wn).length() <= 1e-9 && (d - wd).abs() <= tol,
        _ => false,
    }
}

fn show_answer(x: Answer) -> String {
    match x {
        None => "None".to_string(),
        Some((n, d)) => format!("Some((normal ({}, {}, {}), depth {d}))", n.x, n.y, n.z),
    }
}

/// Whether `e` answers every case; explains the first it does not.
fn agrees<S: Solid>(e: &dyn Exercises, cases: &[Case<S>]) -> bool {
    cases.iter().all(|c| {
        let got = S::ask(e, &c.a, &c.b);
        let tol = tolerance(&c.a, &c.b);
        same_answer(got, c.want, tol)
            || fail(format!(
                "{}({}, {}) returned {}, expected {} (the normal within 1e-9, the depth \
                 within {tol:e})",
                S::METHOD,
                c.a.show(),
                c.b.show(),
                show_answer(got),
                show_answer(c.want),
            ))
    })
}

/// The six orders of the axes.
const ORDERS: [[usize; 3]; 6] = [
    [0, 1, 2],
    [1, 2, 0],
    [2, 0, 1],
    [0, 2, 1],
    [2, 1, 0],
    [1, 0, 2],
];

/// Each case with the axes in each order and each mirroring, the two
/// shapes both ways round; the answers the library's. The unchanged case
/// comes first.
fn variants<S: Solid>(base: &[Case<S>]) -> Vec<Case<S>> {
    let mut out = Vec::new();
    for c in base {
        for order in ORDERS {
            for m in 0..8 {
                let t = Turn {
                    order,
                    mirror: [m & 1 != 0, m & 2 != 0, m & 4 != 0],
                };
                let (a, b) = (c.a.turned(&t), c.b.turned(&t));
                for (a, b) in [(a, b), (b, a)] {
                    let want = library(&a, &b);
                    out.push(Case { a, b, want });
                }
            }
        }
    }
    out
}

fn bx(a: &Aabb, b: &Aabb, want: Option<([f64; 3], f64)>) -> Case<Aabb> {
    Case {
        a: *a,
        b: *b,
        want: want.map(|(n, d)| (DVec3::from(n), d)),
    }
}

/// The cube from 0 to `s` on every axis.
fn cube(s: f32) -> Aabb {
    b([0.0; 3], [s; 3])
}

/// A point as a box.
fn dot(p: [f32; 3]) -> Aabb {
    b(p, p)
}

const X: [f64; 3] = [1.0, 0.0, 0.0];
const Y: [f64; 3] = [0.0, 1.0, 0.0];
const Z: [f64; 3] = [0.0, 0.0, 1.0];
const NX: [f64; 3] = [-1.0, 0.0, 0.0];
const NY: [f64; 3] = [0.0, -1.0, 0.0];
const NZ: [f64; 3] = [0.0, 0.0, -1.0];

/// Boxes overlapping on every axis, neither spanning the other on any, the
/// least move clear of the others.
fn overlapping_boxes() -> Vec<Case<Aabb>> {
    vec![
        // Moves x 1 up, 6 down; y 3, 5; z 2, 7.
        bx(
            &cube(4.0),
            &b([3.0, 1.0, 2.0], [6.0, 5.0, 7.0]),
            Some((X, 1.0)),
        ),
        // x 5, 2; y 7, 0.5; z 3, 6.
        bx(
            &cube(4.0),
            &b([-1.0, -3.0, 1.0], [2.0, 0.5, 6.0]),
            Some((NY, 0.5)),
        ),
        // x 6, 1; y 1.5, 6; z 0.75, 8.
        bx(
            &cube(4.0),
            &b([-2.0, 2.5, 3.25], [1.0, 6.0, 8.0]),
            Some((Z, 0.75)),
        ),
        // x 0.5, 3; y 1, 6; z 11, 0.75.
        bx(
            &b([-3.0, -2.0, -5.0], [-1.0, 2.0, 5.0]),
            &b([-1.5, 1.0, -6.0], [0.0, 4.0, -4.25]),
            Some((X, 0.5)),
        ),
        // x 3, 0.25; y 3.5, 3; z 0.5, 4.
        bx(
            &cube(2.0),
            &b([-1.0, 0.5, 1.5], [0.25, 3.0, 4.0]),
            Some((NX, 0.25)),
        ),
        // Away from the origin: x 0.25, 3; y 3, 1.5; z 0.5, 2.
        bx(
            &b([100.0, 50.0, -7.0], [101.0, 52.0, -6.0]),
            &b([100.75, 49.0, -6.5], [103.0, 51.5, -5.0]),
            Some((X, 0.25)),
        ),
    ]
}

/// One box spanning the other on an axis: the overlap there is the inner
/// box's width, shorter than either way out.
fn spanning_boxes() -> Vec<Case<Aabb>> {
    vec![
        // Inside: x 9, 2; y 7, 5; z 8, 9 (widths 1, 2, 7).
        bx(
            &cube(10.0),
            &b([1.0, 3.0, 2.0], [2.0, 5.0, 9.0]),
            Some((NX, 2.0)),
        ),
        // Around: x 5, 6; y 6, 6; z 7, 6 (widths 1, 2, 3).
        bx(
            &b([4.0, 4.0, 4.0], [5.0, 6.0, 7.0]),
            &cube(10.0),
            Some((X, 5.0)),
        ),
        // Spanning on x and z: x 6, 5; y 1.5, 3; z 11, 20 (widths 1, 1.5,
        // 10).
        bx(
            &b([0.0, 0.0, 0.0], [10.0, 2.0, 10.0]),
            &b([4.0, 0.5, -1.0], [5.0, 3.0, 20.0]),
            Some((Y, 1.5)),
        ),
        // A rod through a box: x 2.5, 2; y 3, 3.5; z 5, 6 (widths 0.5,
        // 2.5, 4).
        bx(
            &cube(4.0),
            &b([1.5, 1.0, -1.0], [2.0, 3.5, 6.0]),
            Some((NX, 2.0)),
        ),
    ]
}

/// Touching boxes (depth 0), boxes apart, and the empty box.
fn touching_boxes() -> Vec<Case<Aabb>> {
    let unit = cube(1.0);
    vec![
        // A face: x up is 0.
        bx(&unit, &b([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]), Some((X, 0.0))),
        // A face below: y down is 0.
        bx(
            &unit,
            &b([0.25, -1.0, 0.0], [0.75, 0.0, 1.0]),
            Some((NY, 0.0)),
        ),
        // A face, the boxes offset: z up is 0.
        bx(&unit, &b([0.5, -2.0, 1.0], [3.0, 0.5, 4.0]), Some((Z, 0.0))),
        // An edge: x up and y up are 0.
        bx(&unit, &b([1.0, 1.0, 0.5], [2.0, 2.0, 1.5]), Some((X, 0.0))),
        // A corner: every down move is 0.
        bx(&unit, &b([-1.0; 3], [0.0; 3]), Some((NX, 0.0))),
        // Apart on one axis.
        bx(&unit, &b([1.5, 0.0, 0.0], [2.0, 1.0, 1.0]), None),
        bx(&unit, &b([0.0, 0.0, -3.0], [1.0, 1.0, -0.125]), None),
        bx(&cube(4.0), &b([1.0, 1.0, 4.5], [3.0, 3.0, 6.0]), None),
        // Apart on every axis.
        bx(&cube(4.0), &b([5.0; 3], [6.0; 3]), None),
        // The empty box overlaps nothing, not even itself.
        bx(&Aabb::EMPTY, &cube(4.0), None),
        bx(&Aabb::EMPTY, &Aabb::EMPTY, None),
    ]
}

/// Boxes flat on one axis or more.
fn flat_boxes() -> Vec<Case<Aabb>> {
    vec![
        // A floor plate at y = 0, a box through it: y 0.25, 0.75.
        bx(
            &b([-5.0, 0.0, -5.0], [5.0, 0.0, 5.0]),
            &b([0.0, -0.25, 0.0], [1.0, 0.75, 1.0]),
            Some((Y, 0.25)),
        ),
        // Two plates in the plane z = 1: z 0, 0 (touching, +).
        bx(
            &b([0.0, 0.0, 1.0], [2.0, 2.0, 1.0]),
            &b([1.0, 0.5, 1.0], [3.0, 3.0, 1.0]),
            Some((Z, 0.0)),
        ),
        // A plate across a box: x 3, 3; y 5, 6; z 2.5, 1.5.
        bx(
            &cube(4.0),
            &b([1.0, -1.0, 1.5], [3.0, 6.0, 1.5]),
            Some((NZ, 1.5)),
        ),
        // A segment through a box: x 5, 6; y 3, 1; z 0.5, 3.5.
        bx(
            &cube(4.0),
            &b([-1.0, 1.0, 3.5], [6.0, 1.0, 3.5]),
            Some((Z, 0.5)),
        ),
        // A point inside: x 3, 1; y 0.75, 3.25; z 1.5, 2.5.
        bx(&cube(4.0), &dot([1.0, 3.25, 2.5]), Some((Y, 0.75))),
        // A point on a face, and outside.
        bx(&cube(4.0), &dot([4.0, 1.0, 2.0]), Some((X, 0.0))),
        bx(&cube(4.0), &dot([4.5, 1.0, 2.0]), None),
        // Two points at one place.
        bx(&dot([1.0, 2.0, 3.0]), &dot([1.0, 2.0, 3.0]), Some((X, 0.0))),
    ]
}

/// Two or more moves equally least.
fn tied_boxes() -> Vec<Case<Aabb>> {
    vec![
        // The same box: all six moves 1.
        bx(&cube(1.0), &cube(1.0), Some((X, 1.0))),
        // Centred in a larger cube: all six 3.
        bx(&cube(4.0), &b([1.0; 3], [3.0; 3]), Some((X, 3.0))),
        // Centred on x, where the overlap is least: x 3, 3; y 8, 9; z 9, 8.
        bx(
            &b([0.0, 0.0, 0.0], [4.0, 10.0, 10.0]),
            &b([1.0, 2.0, 1.0], [3.0, 9.0, 8.0]),
            Some((X, 3.0)),
        ),
        // x down against y up: x 5, 1; y 1, 6; z 3, 9.
        bx(
            &cube(4.0),
            &b([-1.0, 3.0, 1.0], [1.0, 6.0, 9.0]),
            Some((NX, 1.0)),
        ),
        // y down against z up: x 3, 3; y 5, 1; z 1, 6.
        bx(
            &cube(4.0),
            &b([1.0, -1.0, 3.0], [3.0, 1.0, 6.0]),
            Some((NY, 1.0)),
        ),
        // Three ways: x 1, 6; y 6, 1; z 1, 7.
        bx(
            &cube(4.0),
            &b([3.0, -2.0, 3.0], [6.0, 1.0, 7.0]),
            Some((X, 1.0)),
        ),
    ]
}

/// The six moves of `b` out of `a`, in `f64`: up and down on x, y and z.
fn moves(a: &Aabb, b: &Aabb) -> [f64; 6] {
    let (a0, a1) = (a.min.as_dvec3(), a.max.as_dvec3());
    let (b0, b1) = (b.min.as_dvec3(), b.max.as_dvec3());
    let mut m = [0.0; 6];
    for k in 0..3 {
        m[2 * k] = a1[k] - b0[k];
        m[2 * k + 1] = b1[k] - a0[k];
    }
    m
}

/// The three scales of the random cases: (size, offset of the cube).
const SCALES: [(f32, f32); 3] = [(1.0, 0.0), (1e-3, 0.0), (1.0, 1000.0)];

/// Random pairs of boxes in one cube (about half of them overlapping),
/// both ways round, at unit size, a thousandth of it, and a thousand units
/// from the origin; only the clear ones.
fn random_boxes() -> Vec<Case<Aabb>> {
    let mut r = Rng(0x45_b0c5_ea5e);
    let mut out = Vec::new();
    for i in 0..450 {
        let (scale, offset) = SCALES[i % 3];
        let at = Vec3::splat(offset);
        let mut random = || {
            let lo = r.point(1.5 * scale, at);
            let size = Vec3::new(r.next(), r.next(), r.next()) * 1.5 * scale + 0.25 * scale;
            Aabb::new(lo, lo + size)
        };
        let (a, b) = (random(), random());
        let m = moves(&a, &b);
        let close = 1e-3 * f64::from(scale);
        if m.iter().any(|x| x.abs() <= close) {
            continue;
        }
        let mut sorted = m;
        sorted.sort_by(f64::total_cmp);
        if sorted[0] > 0.0 && sorted[1] - sorted[0] <= close {
            continue;
        }
        for (a, b) in [(a, b), (b, a)] {
            out.push(Case {
                a,
                b,
                want: library(&a, &b),
            });
        }
    }
    out
}

fn ball(c: [f32; 3], r: f32) -> Sphere {
    Sphere {
        center: Vec3::from(c),
        radius: r,
    }
}

fn sp(a: Sphere, b: Sphere, want: Option<([f64; 3], f64)>) -> Case<Sphere> {
    Case {
        a,
        b,
        want: want.map(|(n, d)| (DVec3::from(n), d)),
    }
}

/// Spheres overlapping, neither around the other's centre.
fn overlapping_spheres() -> Vec<Case<Sphere>> {
    vec![
        sp(
            ball([0.0; 3], 1.0),
            ball([1.5, 0.0, 0.0], 1.0),
            Some((X, 0.5)),
        ),
        // Centres 5 apart, radii 2 and 4.
        sp(
            ball([0.0; 3], 2.0),
            ball([3.0, 4.0, 0.0], 4.0),
            Some(([0.6, 0.8, 0.0], 1.0)),
        ),
        // Centres 3 apart along (1, 2, 2).
        sp(
            ball([1.0; 3], 2.0),
            ball([2.0, 3.0, 3.0], 2.0),
            Some(([1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0], 1.0)),
        ),
        sp(
            ball([-2.0, 0.0, 1.0], 0.75),
            ball([-2.0, -1.0, 1.0], 0.5),
            Some((NY, 0.25)),
        ),
        sp(
            ball([0.0; 3], 1.0),
            ball([0.0, 0.0, -2.5], 2.0),
            Some((NZ, 0.5)),
        ),
    ]
}

/// Spheres touching and apart, points, and empty spheres.
fn touching_spheres() -> Vec<Case<Sphere>> {
    vec![
        // Touching: centres 3 apart, radii 1 and 2.
        sp(
            ball([0.0; 3], 1.0),
            ball([0.0, 3.0, 0.0], 2.0),
            Some((Y, 0.0)),
        ),
        // A point on the surface, inside, and outside.
        sp(
            ball([0.0; 3], 2.0),
            ball([0.0, 0.0, -2.0], 0.0),
            Some((NZ, 0.0)),
        ),
        sp(
            ball([0.0; 3], 2.0),
            ball([0.0, 0.0, 1.5], 0.0),
            Some((Z, 0.5)),
        ),
        sp(ball([0.0; 3], 2.0), ball([0.0, 0.0, 2.25], 0.0), None),
        // Two points at one place: touching, +x.
        sp(ball([1.0; 3], 0.0), ball([1.0; 3], 0.0), Some((X, 0.0))),
        // Apart.
        sp(ball([0.0; 3], 1.0), ball([2.0, 2.0, 0.0], 1.0), None),
        sp(ball([0.0; 3], 1.0), ball([0.0, 0.0, 2.5], 1.0), None),
        // The empty sphere, inside a sphere, and a negative radius near one.
        sp(Sphere::EMPTY, ball([0.0; 3], 3.0), None),
        sp(ball([0.0, 0.5, 0.0], -0.25), ball([0.0; 3], 1.0), None),
    ]
}

/// One sphere around the other's centre, and the same centre.
fn nested_spheres() -> Vec<Case<Sphere>> {
    vec![
        sp(
            ball([0.0; 3], 5.0),
            ball([0.0, -1.0, 0.0], 1.0),
            Some((NY, 5.0)),
        ),
        sp(
            ball([0.0; 3], 1.0),
            ball([0.0, 0.0, 0.5], 3.0),
            Some((Z, 3.5)),
        ),
        sp(
            ball([1.0, 2.0, 3.0], 1.0),
            ball([1.0, 2.0, 3.0], 0.5),
            Some((X, 1.5)),
        ),
        sp(
            ball([-4.0, 0.0, 2.0], 0.25),
            ball([-4.0, 0.0, 2.0], 2.0),
            Some((X, 2.25)),
        ),
    ]
}

/// Random pairs of spheres in one cube (about half of them overlapping),
/// both ways round, at the three scales; only those whose depth and
/// distance between centres are clear of zero.
fn random_spheres() -> Vec<Case<Sphere>> {
    let mut r = Rng(0x455b_e7e5);
    let mut out = Vec::new();
    for i in 0..450 {
        let (scale, offset) = SCALES[i % 3];
        let at = Vec3::splat(offset);
        let mut random = || Sphere {
            center: r.point(1.5 * scale, at),
            radius: (0.1 + 0.8 * r.next()) * scale,
        };
        let (a, b) = (random(), random());
        let close = 1e-3 * f64::from(scale);
        let d = (b.center.as_dvec3() - a.center.as_dvec3()).length();
        let depth = f64::from(a.radius) + f64::from(b.radius) - d;
        if depth.abs() <= close || d <= close {
            continue;
        }
        for (a, b) in [(a, b), (b, a)] {
            out.push(Case {
                a,
                b,
                want: library(&a, &b),
            });
        }
    }
    out
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 16;

    /// Not wrong: boxes from their centres and half sizes (the least move
    /// on an axis is the half sizes' sum less the distance between the
    /// centres), the empty box found by its corners; spheres with
    /// `normalize()` and the depth summed in another order. Scores full
    /// marks (see the tests).
    pub const HONEST: u32 = 100;

    /// The wrong answers, one slip each. Boxes (45a):
    /// 1: the depth the sum of the three axes' least moves;
    /// 2: the axis whose least move is the largest;
    /// 3: the normal pointing from `b` to `a`;
    /// 4: touching boxes apart (`None` at depth 0);
    /// 5: the overlap's width, `min(max) - max(min)`, as the move, the side
    ///    by the centres (one box spanning the other forgotten);
    /// 6: ties to the highest axis (`<=` instead of `<`);
    /// 7: ties on one axis to `-` (the downward move tried first);
    /// 8: every `+` move tried before any `-` move;
    /// 9: never `None`: boxes apart get a negative depth.
    ///
    /// Spheres (45b):
    /// 10: the depth the radii's sum, the distance not subtracted;
    /// 11: the normal `d`, not `d / |d|`;
    /// 12: the normal pointing from `b` to `a`;
    /// 13: touching spheres apart (`None` at depth 0);
    /// 14: the same centre gives a zero normal (`normalize_or_zero`);
    /// 15: a negative radius not checked;
    /// 16: the squared distance subtracted (no square root).
    pub fn box_penetration(which: u32, a: &Aabb, b: &Aabb) -> Answer {
        match which {
            1..=9 => box_slipped(which, a, b),
            HONEST => box_honest(a, b),
            _ => Reference.box_penetration(a, b),
        }
    }

    pub fn sphere_penetration(which: u32, a: &Sphere, b: &Sphere) -> Answer {
        match which {
            10..=16 => sphere_slipped(which, a, b),
            HONEST => sphere_honest(a, b),
            _ => Reference.sphere_penetration(a, b),
        }
    }

    fn unit(k: usize, sign: f64) -> DVec3 {
        let mut n = DVec3::ZERO;
        n[k] = sign;
        n
    }

    fn box_slipped(which: u32, a: &Aabb, b: &Aabb) -> Answer {
        let (a0, a1) = (a.min.as_dvec3(), a.max.as_dvec3());
        let (b0, b1) = (b.min.as_dvec3(), b.max.as_dvec3());
        // (move, axis, sign), in the order they are tried.
        let mut moves: Vec<(f64, usize, f64)> = Vec::new();
        for k in 0..3 {
            let (up, down) = (a1[k] - b0[k], b1[k] - a0[k]);
            match which {
                5 => {
                    let width = a1[k].min(b1[k]) - a0[k].max(b0[k]);
                    let sign = if b0[k] + b1[k] >= a0[k] + a1[k] {
                        1.0
                    } else {
                        -1.0
                    };
                    moves.push((width, k, sign));
                }
                7 => moves.extend([(down, k, -1.0), (up, k, 1.0)]),
                _ => moves.extend([(up, k, 1.0), (down, k, -1.0)]),
            }
        }
        if which == 8 {
            // Stable: the + moves first, each side's axes in order.
            moves.sort_by_key(|m| m.2 < 0.0);
        }
        let least = moves.iter().map(|m| m.0).fold(f64::INFINITY, f64::min);
        let apart = if which == 4 {
            least <= 0.0
        } else {
            least < 0.0
        };
        if apart && which != 9 {
            return None;
        }
        if which == 2 {
            // Each axis's least move (+ on a tie), then the largest of those.
            let per_axis: Vec<(f64, usize, f64)> = moves
                .chunks(2)
                .map(|m| if m[1].0 < m[0].0 { m[1] } else { m[0] })
                .collect();
            let mut best = per_axis[0];
            for &m in &per_axis[1..] {
                if m.0 > best.0 {
                    best = m;
                }
            }
            return Some((unit(best.1, best.2), best.0));
        }
        let mut best = moves[0];
        for &m in &moves[1..] {
            let better = if which == 6 {
                m.0 <= best.0
            } else {
                m.0 < best.0
            };
            if better {
                best = m;
            }
        }
        let (depth, k, sign) = best;
        match which {
            1 => {
                let sum = moves.chunks(2).map(|m| m[0].0.min(m[1].0)).sum();
                Some((unit(k, sign), sum))
            }
            3 => Some((unit(k, -sign), depth)),
            _ => Some((unit(k, sign), depth)),
        }
    }

    fn box_honest(a: &Aabb, b: &Aabb) -> Answer {
        if a.min.cmpgt(a.max).any() || b.min.cmpgt(b.max).any() {
            return None;
        }
        let (ca, cb) = (
            (a.min.as_dvec3() + a.max.as_dvec3()) * 0.5,
            (b.min.as_dvec3() + b.max.as_dvec3()) * 0.5,
        );
        let half =
            ((a.max.as_dvec3() - a.min.as_dvec3()) + (b.max.as_dvec3() - b.min.as_dvec3())) * 0.5;
        let mut best: Option<(f64, DVec3)> = None;
        for k in 0..3 {
            let gap = cb[k] - ca[k];
            let depth = half[k] - gap.abs();
            if depth < 0.0 {
                return None;
            }
            if best.is_none_or(|(d, _)| depth < d) {
                best = Some((depth, unit(k, if gap >= 0.0 { 1.0 } else { -1.0 })));
            }
        }
        best.map(|(d, n)| (n, d))
    }

    fn sphere_slipped(which: u32, a: &Sphere, b: &Sphere) -> Answer {
        let (ra, rb) = (f64::from(a.radius), f64::from(b.radius));
        if which != 15 && (ra < 0.0 || rb < 0.0) {
            return None;
        }
        let d = b.center.as_dvec3() - a.center.as_dvec3();
        let len = d.length();
        let depth = ra + rb - len;
        let apart = if which == 13 {
            depth <= 0.0
        } else {
            depth < 0.0
        };
        if apart {
            return None;
        }
        let normal = if len > 0.0 { d / len } else { DVec3::X };
        Some(match which {
            10 => (normal, ra + rb),
            11 => (d, depth),
            12 => (-normal, depth),
            14 => (d.normalize_or_zero(), depth),
            16 => (normal, ra + rb - d.length_squared()),
            _ => (normal, depth),
        })
    }

    fn sphere_honest(a: &Sphere, b: &Sphere) -> Answer {
        if a.radius < 0.0 || b.radius < 0.0 {
            return None;
        }
        let d = b.center.as_dvec3() - a.center.as_dvec3();
        let len = d.dot(d).sqrt();
        let depth = (f64::from(a.radius) - len) + f64::from(b.radius);
        if depth < 0.0 {
            return None;
        }
        let normal = if len == 0.0 { DVec3::X } else { d.normalize() };
        Some((normal, depth))
    }
}

#[cfg(test)]
mod tests {
    use super::wrong::HONEST;
    use super::*;
    use crate::grader::grade_exercises;
    use crate::grader::wrong::Wrong;

    fn hand_boxes() -> Vec<Case<Aabb>> {
        [
            overlapping_boxes(),
            spanning_boxes(),
            touching_boxes(),
            flat_boxes(),
            tied_boxes(),
        ]
        .concat()
    }

    fn hand_spheres() -> Vec<Case<Sphere>> {
        [overlapping_spheres(), touching_spheres(), nested_spheres()].concat()
    }

    /// The library gives the answers written out: exactly for boxes (every
    /// move is exact), within rounding for spheres.
    #[test]
    fn the_hand_made_answers_are_the_librarys() {
        for c in hand_boxes() {
            assert_eq!(library(&c.a, &c.b), c.want, "{c:?}");
        }
        for c in hand_spheres() {
            assert!(
                same_answer(library(&c.a, &c.b), c.want, 1e-15),
                "{c:?}: {:?}",
                library(&c.a, &c.b)
            );
        }
    }

    /// The overlapping, spanning and flat cases have one least move (their
    /// 96 variants are the same case turned); the tied cases have several.
    #[test]
    fn only_the_tied_cases_tie() {
        let ties = |c: &Case<Aabb>| {
            let m = moves(&c.a, &c.b);
            let least = m.iter().copied().fold(f64::INFINITY, f64::min);
            m.iter().filter(|&&x| x == least).count()
        };
        for c in [overlapping_boxes(), spanning_boxes(), flat_boxes()].concat() {
            if c.want.is_some_and(|(_, d)| d > 0.0) {
                assert_eq!(ties(&c), 1, "{c:?}");
            }
        }
        for c in tied_boxes() {
            assert!(ties(&c) >= 2, "{c:?}");
        }
    }

    /// Of the 720 orders in which the six moves could be preferred on a
    /// tie, only the library's (x up, x down, y up, y down, z up, z down)
    /// answers every box case.
    #[test]
    fn only_one_tie_order_passes() {
        fn orders(prefix: Vec<usize>, out: &mut Vec<Vec<usize>>) {
            if prefix.len() == 6 {
                out.push(prefix);
                return;
            }
            for m in 0..6 {
                if !prefix.contains(&m) {
                    let mut p = prefix.clone();
                    p.push(m);
                    orders(p, out);
                }
            }
        }
        let mut all = Vec::new();
        orders(Vec::new(), &mut all);
        assert_eq!(all.len(), 720);
        let cases: Vec<Case<Aabb>> = variants(&hand_boxes())
            .into_iter()
            .chain(random_boxes())
            .collect();
        let passing: Vec<Vec<usize>> = all
            .into_iter()
            .filter(|order| {
                cases.iter().all(|c| {
                    let m = moves(&c.a, &c.b);
                    let got = if m.iter().any(|&x| x < 0.0) {
                        None
                    } else {
                        let mut best = order[0];
                        for &i in &order[1..] {
                            if m[i] < m[best] {
                                best = i;
                            }
                        }
                        let sign = if best % 2 == 0 { 1.0 } else { -1.0 };
                        let mut n = DVec3::ZERO;
                        n[best / 2] = sign;
                        Some((n, m[best]))
                    };
                    got == c.want
                })
            })
            .collect();
        assert_eq!(passing, vec![vec![0, 1, 2, 3, 4, 5]]);
    }

    /// The random cases are many, overlapping and apart in good numbers,
    /// at every scale.
    #[test]
    fn random_cases_are_mixed() {
        fn mixed<S: Solid>(cases: &[Case<S>], far: impl Fn(&S) -> bool) {
            let some = cases.iter().filter(|c| c.want.is_some()).count();
            println!(
                "{} {} random cases, {some} overlapping",
                S::METHOD,
                cases.len()
            );
            assert!(cases.len() >= 500, "{}", cases.len());
            assert!(some >= 150 && cases.len() - some >= 150, "{some}");
            for far_away in [false, true] {
                assert!(cases
                    .iter()
                    .any(|c| c.want.is_some() && far(&c.a) == far_away));
            }
        }
        mixed(&random_boxes(), |a: &Aabb| a.min.x > 500.0);
        mixed(&random_spheres(), |a: &Sphere| a.center.x > 500.0);
    }

    /// Another honest answer (centres and half sizes, other sums) scores
    /// every point.
    #[test]
    fn an_honest_variant_scores_everything() {
        let e: &'static Wrong = Box::leak(Box::new(Wrong {
            exercise: 45,
            k: HONEST,
        }));
        let s = &grade_exercises(e, &[45], crate::grader::CHECK_TIME_LIMIT, |_| {})[0];
        assert_eq!(s.earned, s.possible, "{s:?}");
    }

    /// Which checks each wrong answer fails (printed with --nocapture).
    #[test]
    fn each_wrong_answer_fails_where_expected() {
        let names: Vec<&str> = checks().iter().map(|c| c.name).collect();
        for k in 1..=wrong::COUNT {
            let e: &'static Wrong = Box::leak(Box::new(Wrong { exercise: 45, k }));
            let s = &grade_exercises(e, &[45], crate::grader::CHECK_TIME_LIMIT, |_| {})[0];
            println!("wrong answer {k}: {}/{}", s.earned, s.possible);
            for f in &s.failed {
                println!("    {f}");
            }
            assert!(s.earned < s.possible, "wrong answer {k}: {s:?}");
            assert!(s.failed.iter().all(|f| !names.contains(&f.as_str())));
        }
    }
}
