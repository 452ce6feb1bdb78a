//! Exercise 44: where two triangles cross. The checks, and the plausible
//! wrong answers they must reject.
//!
//! The hand-made cases have small coordinates, so that every side of a
//! plane is exact in `f64` too and most points are, and carry their answers
//! written out. Each is also asked with the axes turned and mirrored, the
//! corners of either triangle started at each corner and taken the other
//! way round, and the two triangles both ways round (216 questions per
//! case). The random cases are graded against the library's
//! `narrow::triangle_contact`, and kept only where no corner is near the
//! other triangle's plane, the planes are far from parallel and the two
//! cuts neither nearly touch nor nearly miss, so that `f64` signs and any
//! honest formula agree with it. No case has its triangles in one plane or
//! a triangle of zero area.

use super::common::*;
use bvhkit::glam::DVec3;

/// The checks of exercise 44.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 44,
            name: "a blade through a floor: the blade's cut, inside the floor's",
            points: 1,
            run: |e| agrees(e, &variants(&blade_cases())),
        },
        Check {
            exercise: 44,
            name: "crossing partly: the overlap of the two cuts, each longer on one side",
            points: 2,
            run: |e| agrees(e, &variants(&partial_cases())),
        },
        Check {
            exercise: 44,
            name: "touching at one point: a corner on a face, corner on corner, edge across \
                   edge, corner on an edge",
            points: 2,
            run: |e| agrees(e, &variants(&point_cases())),
        },
        Check {
            exercise: 44,
            name: "corners exactly on the other's plane: an edge lying on a face, a corner \
                   between two crossing edges",
            points: 2,
            run: |e| agrees(e, &variants(&on_plane_cases())),
        },
        Check {
            exercise: 44,
            name: "apart: a triangle that does not reach the other's plane",
            points: 1,
            run: |e| agrees(e, &variants(&apart_cases())),
        },
        Check {
            exercise: 44,
            name: "the planes' line crosses both triangles, but the two cuts miss each other",
            points: 1,
            run: |e| agrees(e, &variants(&missing_cases())),
        },
        Check {
            exercise: 44,
            name: "random crossing and passing triangles, at three scales, as \
                   triangle_contact places them",
            points: 1,
            run: |e| agrees(e, &random_cases()),
        },
    ]
}

/// Two triangles and the segment they share.
#[derive(Clone, Copy, Debug)]
struct Case {
    t1: Triangle,
    t2: Triangle,
    want: Option<[DVec3; 2]>,
}

/// Whether `e` answers every case, the ends in either order and each within
/// [`tolerance`]; explains the first it does not.
fn agrees(e: &dyn Exercises, cases: &[Case]) -> bool {
    cases.iter().all(|c| {
        let got = e.crossing_segment(&c.t1, &c.t2);
        let tol = tolerance(&c.t1, &c.t2);
        same_segment(got, c.want, tol)
            || fail(format!(
                "crossing_segment({}, {}) returned {}, expected {} (the ends in either \
                 order, each within {tol:e})",
                show_triangle(&c.t1),
                show_triangle(&c.t2),
                show_segment(got),
                show_segment(c.want),
            ))
    })
}

/// 1e-9 times the largest coordinate of the six corners, at least 1e-9.
fn tolerance(t1: &Triangle, t2: &Triangle) -> f64 {
    let largest =
        t1.v.iter()
            .chain(&t2.v)
            .map(|p| f64::from(p.abs().max_element()))
            .fold(1.0, f64::max);
    1e-9 * largest
}

/// Whether two answers are the same segment, the ends in either order and
/// each within `tol`.
fn same_segment(got: Option<[DVec3; 2]>, want: Option<[DVec3; 2]>, tol: f64) -> bool {
    let near = |p: DVec3, q: DVec3| (p - q).length() <= tol;
    match (got, want) {
        (None, None) => true,
        (Some([p, q]), Some([a, b])) => (near(p, a) && near(q, b)) || (near(p, b) && near(q, a)),
        _ => false,
    }
}

fn show_triangle(t: &Triangle) -> String {
    format!(
        "triangle {} {} {}",
        show_point(t.v[0]),
        show_point(t.v[1]),
        show_point(t.v[2])
    )
}

fn show_segment(s: Option<[DVec3; 2]>) -> String {
    let show = |p: DVec3| format!("({}, {}, {})", p.x, p.y, p.z);
    match s {
        None => "None".to_string(),
        Some([p, q]) => format!("Some([{}, {}])", show(p), show(q)),
    }
}

fn v(p: [f32; 3]) -> Vec3 {
    Vec3::from(p)
}

fn tri(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> Triangle {
    Triangle::new(v(a), v(b), v(c))
}

fn case(t2: Triangle, want: Option<[[f64; 3]; 2]>) -> Case {
    Case {
        t1: floor(),
        t2,
        want: want.map(|[p, q]| [DVec3::from(p), DVec3::from(q)]),
    }
}

/// The floor every hand-made case is about: in the plane z = 0, from
/// x = -2 to 2 where it crosses y = 0 (from x = -4 to 4 along its edge at
/// y = -4, narrowing to its corner at y = 4).
fn floor() -> Triangle {
    tri([-4.0, -4.0, 0.0], [4.0, -4.0, 0.0], [0.0, 4.0, 0.0])
}

/// Upright blades whose cut lies inside the floor's.
fn blade_cases() -> Vec<Case> {
    vec![
        // In the plane y = 0, across z = 0 from x = -0.5 to 0.5.
        case(
            tri([-1.0, 0.0, -1.0], [1.0, 0.0, -1.0], [0.0, 0.0, 1.0]),
            Some([[-0.5, 0.0, 0.0], [0.5, 0.0, 0.0]]),
        ),
        // At y = 1 (the floor from x = -1.5 to 1.5), corners 1, 3 and 1
        // from the floor: the crossings are a half and three quarters of
        // the way along their edges.
        case(
            tri([-1.0, 1.0, -1.0], [1.0, 1.0, -3.0], [0.0, 1.0, 1.0]),
            Some([[-0.5, 1.0, 0.0], [0.25, 1.0, 0.0]]),
        ),
        // Slanted, in the plane z = y.
        case(
            tri([-1.0, -1.0, -1.0], [2.0, -1.0, -1.0], [0.0, 3.0, 3.0]),
            Some([[-0.75, 0.0, 0.0], [1.5, 0.0, 0.0]]),
        ),
    ]
}

/// Blades across the floor's edge: each cut runs past the contact on one
/// side.
fn partial_cases() -> Vec<Case> {
    vec![
        // The blade's cut from x = 1.5 to 2.5, the floor's from -2 to 2.
        case(
            tri([1.0, 0.0, -1.0], [3.0, 0.0, -1.0], [2.0, 0.0, 1.0]),
            Some([[1.5, 0.0, 0.0], [2.0, 0.0, 0.0]]),
        ),
        // At y = 2: the blade's cut from x = 0 to 1.75, the floor's from -1
        // to 1.
        case(
            tri([-1.0, 2.0, -1.0], [4.0, 2.0, -3.0], [1.0, 2.0, 1.0]),
            Some([[0.0, 2.0, 0.0], [1.0, 2.0, 0.0]]),
        ),
        // Slanted (z = y): the blade's cut from x = 0 to 4.5.
        case(
            tri([-1.0, -1.0, -1.0], [5.0, -1.0, -1.0], [3.0, 3.0, 3.0]),
            Some([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]]),
        ),
        // Along the diagonal x = y: the blade's cut from (-2, -2) to
        // (2.5, 2.5); the floor's from its corner (-4, -4), which lies on
        // the blade's plane, to (4/3, 4/3) on its far edge.
        case(
            tri([-3.0, -3.0, -1.0], [3.0, 3.0, -1.0], [1.0, 1.0, 3.0]),
            Some([[-2.0, -2.0, 0.0], [4.0 / 3.0, 4.0 / 3.0, 0.0]]),
        ),
    ]
}

/// Triangles that touch the floor at one point: both ends equal.
fn point_cases() -> Vec<Case> {
    vec![
        // A corner resting on the middle of the floor, the rest above it.
        case(
            tri([0.0, 0.0, 0.0], [-1.0, 1.0, 2.0], [1.0, 1.0, 2.0]),
            Some([[0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]),
        ),
        // On the floor's corner (4, -4, 0), the rest above; the floor's
        // corner is on this triangle's plane, its other two on either side.
        case(
            tri([4.0, -4.0, 0.0], [6.0, -4.0, 2.0], [5.0, -2.0, 3.0]),
            Some([[4.0, -4.0, 0.0], [4.0, -4.0, 0.0]]),
        ),
        // Upright in the plane x = 0, an edge crossing the floor's edge
        // y = -4 at (0, -4, 0): its cut ends where the floor's begins.
        case(
            tri([0.0, -5.0, 1.0], [0.0, -1.0, -3.0], [0.0, -6.0, -1.0]),
            Some([[0.0, -4.0, 0.0], [0.0, -4.0, 0.0]]),
        ),
        // A corner on the floor's edge at (2, 0, 0), its other two corners
        // above and below the floor beyond that edge.
        case(
            tri([2.0, 0.0, 0.0], [3.0, 0.0, 2.0], [3.0, 1.0, -1.0]),
            Some([[2.0, 0.0, 0.0], [2.0, 0.0, 0.0]]),
        ),
    ]
}

/// Corners exactly on the floor.
fn on_plane_cases() -> Vec<Case> {
    vec![
        // An edge lying on the floor, inside it: the contact is that edge.
        case(
            tri([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 2.0]),
            Some([[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]]),
        ),
        // An edge lying on the floor from x = 1 to 5: the part up to x = 2.
        case(
            tri([1.0, 0.0, 0.0], [5.0, 0.0, 0.0], [3.0, 1.0, 2.0]),
            Some([[1.0, 0.0, 0.0], [2.0, 0.0, 0.0]]),
        ),
        // An edge lying on the floor aslant, from a point of the floor's
        // edge, (-3, -2), to (3, 1) outside it: the part up to the floor's
        // other edge, at (1.8, 0.4).
        case(
            tri([-3.0, -2.0, 0.0], [3.0, 1.0, 0.0], [0.0, 0.0, -2.0]),
            Some([[-3.0, -2.0, 0.0], [1.8, 0.4, 0.0]]),
        ),
        // Upright in the plane x = 0, a corner on the floor at (0, -1, 0)
        // and the opposite edge crossing it at (0, 1, 0).
        case(
            tri([0.0, -1.0, 0.0], [0.0, 1.0, 1.0], [0.0, 1.0, -3.0]),
            Some([[0.0, -1.0, 0.0], [0.0, 1.0, 0.0]]),
        ),
    ]
}

/// One of the two triangles does not reach the other's plane.
fn apart_cases() -> Vec<Case> {
    vec![
        // Above the floor, and below it.
        case(
            tri([-1.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 3.0]),
            None,
        ),
        case(
            tri([-1.0, -1.0, -2.0], [2.0, 0.0, -1.0], [0.0, 2.0, -3.0]),
            None,
        ),
        // Across the floor's plane at x = 10: the floor does not reach x = 10.
        case(
            tri([10.0, 0.0, -1.0], [10.0, 1.0, 1.0], [10.0, -1.0, 1.0]),
            None,
        ),
        // Upright at x = 1 above the floor: the floor crosses its plane, it
        // does not reach the floor's.
        case(
            tri([1.0, -1.0, 1.0], [1.0, 1.0, 1.0], [1.0, 0.0, 3.0]),
            None,
        ),
    ]
}

/// Each triangle crosses the other's plane, but the cuts miss each other.
fn missing_cases() -> Vec<Case> {
    vec![
        // In the plane y = 0: its cut from x = 5.5 to 6.5, the floor's from
        // -2 to 2; then from 2.25 to 2.75, just past the floor's edge.
        case(
            tri([5.0, 0.0, -1.0], [7.0, 0.0, -1.0], [6.0, 0.0, 1.0]),
            None,
        ),
        case(
            tri([2.0, 0.0, -1.0], [3.0, 0.0, -1.0], [2.5, 0.0, 1.0]),
            None,
        ),
        // Slanted (z = y), its cut from x = 5.5 to 8.5.
        case(
            tri([5.0, -1.0, -1.0], [9.0, -1.0, -1.0], [7.0, 3.0, 3.0]),
            None,
        ),
        // Along the diagonal x = y, from (3.5, 3.5) to (4.5, 4.5): the
        // floor's cut ends at (4/3, 4/3).
        case(
            tri([3.0, 3.0, -1.0], [5.0, 5.0, -1.0], [4.0, 4.0, 1.0]),
            None,
        ),
        // Upright at x = 0, its cut from y = -6 to -4.5, the floor's from
        // -4 to 4.
        case(
            tri([0.0, -5.5, 1.0], [0.0, -1.5, -3.0], [0.0, -6.5, -1.0]),
            None,
        ),
    ]
}

/// Each case asked with the axes turned (x, y, z taken as y, z, x and as
/// z, x, y) and mirrored (x negated), the corners of each triangle started
/// at each corner, the second triangle's corners reversed or not, and the
/// two triangles both ways round; the answer moved with them. The
/// unchanged case comes first.
fn variants(base: &[Case]) -> Vec<Case> {
    let mut out = Vec::new();
    for c in base {
        for axes in 0..3 {
            for mirror in [false, true] {
                let moved = |p: DVec3| {
                    let q = DVec3::new(p[axes], p[(axes + 1) % 3], p[(axes + 2) % 3]);
                    if mirror {
                        DVec3::new(-q.x, q.y, q.z)
                    } else {
                        q
                    }
                };
                // Exact: the coordinates are only reordered and negated.
                let corners = |t: &Triangle, start: usize, reverse: bool| {
                    let mut v = t.v.map(|p| moved(p.as_dvec3()).as_vec3());
                    v.rotate_left(start);
                    if reverse {
                        v.reverse();
                    }
                    Triangle::new(v[0], v[1], v[2])
                };
                let want = c.want.map(|[p, q]| [moved(p), moved(q)]);
                for start1 in 0..3 {
                    for start2 in 0..3 {
                        for reverse in [false, true] {
                            let t1 = corners(&c.t1, start1, false);
                            let t2 = corners(&c.t2, start2, reverse);
                            out.push(Case { t1, t2, want });
                            out.push(Case {
                                t1: t2,
                                t2: t1,
                                want,
                            });
                        }
                    }
                }
            }
        }
    }
    out
}

/// `(b - a) x (c - a)` in `f64`.
fn normal(t: &Triangle) -> DVec3 {
    let [a, b, c] = t.v.map(|p| p.as_dvec3());
    (b - a).cross(c - a)
}

/// Random pairs of triangles in one cube (about half of them touching),
/// both ways round, at unit size, a thousandth of it, and a thousand units
/// from the origin; only the well-posed ones (see [`well_posed`]). The
/// answers are the library's.
fn random_cases() -> Vec<Case> {
    let mut r = Rng(0x44_c0ff_ee15);
    let mut out = Vec::new();
    for i in 0..1200 {
        let (scale, offset) = [(1.0f32, 0.0f32), (1e-3, 0.0), (1.0, 1000.0)][i % 3];
        let at = Vec3::splat(offset);
        let mut random = || {
            Triangle::new(
                r.point(2.0 * scale, at),
                r.point(2.0 * scale, at),
                r.point(2.0 * scale, at),
            )
        };
        let (t1, t2) = (random(), random());
        if !well_posed(&t1, &t2, f64::from(scale)) {
            continue;
        }
        for (t1, t2) in [(t1, t2), (t2, t1)] {
            let want = Reference.crossing_segment(&t1, &t2);
            out.push(Case { t1, t2, want });
        }
    }
    out
}

/// Whether a random pair leaves no doubt: neither triangle thin, the planes
/// at least 11.5 degrees apart, no corner within a thousandth of `scale` of
/// the other's plane, and the two cuts (when both exist) overlapping or
/// apart by at least a thousandth of `scale` along the line.
fn well_posed(t1: &Triangle, t2: &Triangle, scale: f64) -> bool {
    let (n1, n2) = (normal(t1), normal(t2));
    let thick = |t: &Triangle, n: DVec3| {
        let longest = (0..3)
            .map(|i| (t.v[(i + 1) % 3] - t.v[i]).as_dvec3().length())
            .fold(0.0, f64::max);
        // The height over the longest edge.
        n.length() / longest > 0.05 * scale
    };
    if !thick(t1, n1) || !thick(t2, n2) {
        return false;
    }
    let dir = n1.cross(n2);
    if dir.length() < 0.2 * n1.length() * n2.length() {
        return false;
    }
    let clear = |t: &Triangle, other: &Triangle, n: DVec3| {
        let a = other.v[0].as_dvec3();
        t.v.iter()
            .all(|p| (n.dot(p.as_dvec3() - a) / n.length()).abs() > 1e-3 * scale)
    };
    if !clear(t1, t2, n2) || !clear(t2, t1, n1) {
        return false;
    }
    // Where each triangle crosses the other's plane, along the unit line.
    let unit = dir.normalize();
    let cut = |t: &Triangle, other: &Triangle, n: DVec3| {
        let a = other.v[0].as_dvec3();
        let h = t.v.map(|p| n.dot(p.as_dvec3() - a));
        let along: Vec<f64> = (0..3)
            .filter(|&i| (h[i] < 0.0) != (h[(i + 1) % 3] < 0.0))
            .map(|i| {
                let (p, q) = (t.v[i].as_dvec3(), t.v[(i + 1) % 3].as_dvec3());
                (p + (q - p) * (h[i] / (h[i] - h[(i + 1) % 3]))).dot(unit)
            })
            .collect();
        (along.len() == 2).then(|| (along[0].min(along[1]), along[0].max(along[1])))
    };
    match (cut(t1, t2, n2), cut(t2, t1, n1)) {
        (Some((lo1, hi1)), Some((lo2, hi2))) => (lo1.max(lo2) - hi1.min(hi2)).abs() > 1e-3 * scale,
        _ => true,
    }
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;
    use bvhkit::narrow::orient3;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 9;

    /// Not wrong: signs from `f64` heights measured from another corner,
    /// the normal from other edges, each crossing interpolated from its
    /// other end, and the cuts compared by position along the unit line.
    /// Scores full marks (see the tests).
    pub const HONEST: u32 = 100;

    /// The wrong answers, one slip each:
    /// 1: t1's cut, not its overlap with t2's (`None` when either is missing);
    /// 2: the union of the two cuts, not their overlap;
    /// 3: corners exactly on the plane forgotten (only edges crossing it);
    /// 4: the crossing interpolated from the wrong end, `h_j / (h_j - h_i)`;
    /// 5: the crossing at `h_j / (h_i - h_j)`;
    /// 6: `Some` whenever both cuts exist, even when they miss;
    /// 7: `None` when the cuts meet at one point (strict overlap);
    /// 8: each cut ordered along its own normal x the other's, so t2's
    ///    runs backwards;
    /// 9: the points ordered by x instead of along the line.
    pub fn crossing_segment(which: u32, t1: &Triangle, t2: &Triangle) -> Option<[DVec3; 2]> {
        match which {
            1..=9 => slipped(which, t1, t2),
            HONEST => honest(t1, t2),
            _ => Reference.crossing_segment(t1, t2),
        }
    }

    fn slipped(which: u32, t1: &Triangle, t2: &Triangle) -> Option<[DVec3; 2]> {
        let dir = normal(t1).cross(normal(t2));
        let key = |p: DVec3| if which == 9 { p.x } else { p.dot(dir) };
        let key2 = |p: DVec3| if which == 8 { -p.dot(dir) } else { key(p) };
        let s1 = cut(which, t1, t2, &key);
        let s2 = cut(which, t2, t1, &key2);
        let (Some(s1), Some(s2)) = (s1, s2) else {
            return None;
        };
        if which == 1 {
            return Some(s1);
        }
        let (lo, hi) = if which == 2 {
            (
                if key(s1[0]) <= key(s2[0]) {
                    s1[0]
                } else {
                    s2[0]
                },
                if key(s1[1]) >= key(s2[1]) {
                    s1[1]
                } else {
                    s2[1]
                },
            )
        } else {
            (
                if key(s1[0]) >= key(s2[0]) {
                    s1[0]
                } else {
                    s2[0]
                },
                if key(s1[1]) <= key(s2[1]) {
                    s1[1]
                } else {
                    s2[1]
                },
            )
        };
        let apart = if which == 7 {
            key(lo) >= key(hi)
        } else {
            key(lo) > key(hi)
        };
        if apart && which != 6 {
            return None;
        }
        Some([lo, hi])
    }

    /// Where `t` meets `other`'s plane, ordered by `key`, with wrong answer
    /// `which`'s slip.
    fn cut(
        which: u32,
        t: &Triangle,
        other: &Triangle,
        key: &dyn Fn(DVec3) -> f64,
    ) -> Option<[DVec3; 2]> {
        let [a, b, c] = other.v;
        let n = normal(other);
        let h = t.v.map(|p| n.dot(p.as_dvec3() - a.as_dvec3()));
        let side = t.v.map(|p| orient3(a, b, c, p));
        let mut points = Vec::new();
        for i in 0..3 {
            let j = (i + 1) % 3;
            let (p, q) = (t.v[i].as_dvec3(), t.v[j].as_dvec3());
            if side[i] == 0 && which != 3 {
                points.push(p);
            }
            if side[i] * side[j] < 0 {
                let s = match which {
                    4 => h[j] / (h[j] - h[i]),
                    5 => h[j] / (h[i] - h[j]),
                    _ => h[i] / (h[i] - h[j]),
                };
                points.push(p + (q - p) * s);
            }
        }
        let first = *points.first()?;
        let (mut lo, mut hi) = (first, first);
        for &p in &points {
            if key(p) < key(lo) {
                lo = p;
            }
            if key(p) > key(hi) {
                hi = p;
            }
        }
        Some([lo, hi])
    }

    fn honest(t1: &Triangle, t2: &Triangle) -> Option<[DVec3; 2]> {
        // Normals from the edges at the second corner: the same direction.
        let normal = |t: &Triangle| {
            let [a, b, c] = t.v.map(|p| p.as_dvec3());
            (c - b).cross(a - b)
        };
        let unit = normal(t1).cross(normal(t2)).normalize();
        let cut = |t: &Triangle, other: &Triangle| -> Option<(f64, DVec3, f64, DVec3)> {
            let (n, o) = (normal(other), other.v[1].as_dvec3());
            let h = t.v.map(|p| n.dot(p.as_dvec3() - o));
            let mut found: Option<(f64, DVec3, f64, DVec3)> = None;
            let mut add = |p: DVec3| {
                let x = p.dot(unit);
                found = Some(match found {
                    None => (x, p, x, p),
                    Some((lo, lp, hi, hp)) => {
                        let (lo, lp) = if x < lo { (x, p) } else { (lo, lp) };
                        let (hi, hp) = if x > hi { (x, p) } else { (hi, hp) };
                        (lo, lp, hi, hp)
                    }
                });
            };
            for i in 0..3 {
                let j = (i + 1) % 3;
                let (p, q) = (t.v[i].as_dvec3(), t.v[j].as_dvec3());
                if h[i] == 0.0 {
                    add(p);
                } else if h[j] != 0.0 && (h[i] < 0.0) != (h[j] < 0.0) {
                    add(q + (p - q) * (h[j] / (h[j] - h[i])));
                }
            }
            found
        };
        let (lo1, p1, hi1, q1) = cut(t1, t2)?;
        let (lo2, p2, hi2, q2) = cut(t2, t1)?;
        let (lo, start) = if lo2 > lo1 { (lo2, p2) } else { (lo1, p1) };
        let (hi, end) = if hi2 < hi1 { (hi2, q2) } else { (hi1, q1) };
        (lo <= hi).then_some([end, start])
    }
}

#[cfg(test)]
mod tests {
    use super::wrong::HONEST;
    use super::*;
    use crate::grader::grade_exercises;
    use crate::grader::wrong::Wrong;
    use bvhkit::narrow::{orient3, triangle_contact, Contact};

    fn hand_cases() -> Vec<Case> {
        [
            blade_cases(),
            partial_cases(),
            point_cases(),
            on_plane_cases(),
            apart_cases(),
            missing_cases(),
        ]
        .concat()
    }

    /// The grader asks only about triangles of positive area in two planes:
    /// decided exactly (some corner of each strictly off the other's plane,
    /// and a triangle's corners not on one line).
    #[test]
    fn no_case_is_flat_or_in_one_plane() {
        let all: Vec<Case> = variants(&hand_cases())
            .into_iter()
            .chain(random_cases())
            .collect();
        for c in &all {
            let [a, b, cc] = c.t1.v;
            assert!(c.t2.v.iter().any(|&p| orient3(a, b, cc, p) != 0), "{c:?}");
            for t in [c.t1, c.t2] {
                let [p, q, r] = t.v;
                assert!(
                    (0..3).any(|k| bvhkit::narrow::orient2(p, q, r, k) != 0),
                    "{c:?}"
                );
            }
        }
    }

    /// The library's contact is the answer written out, on every variant
    /// of every hand-made case, and a segment wherever there is one.
    #[test]
    fn the_hand_made_answers_are_the_librarys() {
        for c in variants(&hand_cases()) {
            let got = match triangle_contact(&c.t1, &c.t2) {
                None => None,
                Some(Contact::Segment(ends)) => Some(ends),
                Some(area) => panic!("{c:?}: {area:?}"),
            };
            assert!(
                same_segment(got, c.want, tolerance(&c.t1, &c.t2)),
                "{c:?}: {got:?}"
            );
        }
    }

    /// The random cases are many, touching and apart in good numbers, some
    /// touching along a real segment, at every scale.
    #[test]
    fn random_cases_are_mixed() {
        let cases = random_cases();
        let some = cases.iter().filter(|c| c.want.is_some()).count();
        println!("{} random cases, {some} touching", cases.len());
        assert!(cases.len() >= 600, "{}", cases.len());
        assert!(some >= 150 && cases.len() - some >= 150, "{some}");
        for far in [false, true] {
            assert!(cases
                .iter()
                .any(|c| c.want.is_some() && (c.t1.v[0].x > 500.0) == far));
        }
    }

    /// Another honest answer (`f64` signs, other formulas) scores every point.
    #[test]
    fn an_honest_variant_scores_everything() {
        let e: &'static Wrong = Box::leak(Box::new(Wrong {
            exercise: 44,
            k: HONEST,
        }));
        let s = &grade_exercises(e, &[44], crate::grader::CHECK_TIME_LIMIT, |_| {})[0];
        assert_eq!(s.earned, s.possible, "{s:?}");
    }

    /// Which checks each wrong answer fails (printed with --nocapture).
    #[test]
    fn each_wrong_answer_fails_where_expected() {
        let names: Vec<&str> = checks().iter().map(|c| c.name).collect();
        for k in 1..=wrong::COUNT {
            let e: &'static Wrong = Box::leak(Box::new(Wrong { exercise: 44, k }));
            let s = &grade_exercises(e, &[44], crate::grader::CHECK_TIME_LIMIT, |_| {})[0];
            println!("wrong answer {k}: {}/{}", s.earned, s.possible);
            for f in &s.failed {
                println!("    {f}");
            }
            assert!(s.earned < s.possible, "wrong answer {k}: {s:?}");
            assert!(s.failed.iter().all(|f| !names.contains(&f.as_str())));
        }
    }
}
