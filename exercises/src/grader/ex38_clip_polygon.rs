//! Exercise 38: clipping a convex polygon by a half-space, the building
//! block of a k-DOP's exact measures (issue #25). The checks, and the
//! plausible wrong answers they must reject. A clip is compared with the
//! expected polygon up to its starting vertex, coordinates within 1e-9
//! (relative); the exact cases (a plane through a vertex or along an edge)
//! use coordinates whose signed distances every order of operations
//! computes as exactly 0.

use super::common::*;
use bvhkit::glam::DVec3;
use bvhkit::Dop26;

/// The checks of exercise 38.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 38,
            name: "an edge crossing the plane off its middle: the point where it meets the plane",
            points: 3,
            run: |e| clips_all(e, &crossing_cases()),
        },
        Check {
            exercise: 38,
            name: "the closing edge (last vertex back to the first) is an edge too",
            points: 2,
            run: |e| clips_all(e, &closing_cases()),
        },
        Check {
            exercise: 38,
            name: "a polygon entirely inside is written to out whole; one entirely outside leaves nothing",
            points: 2,
            run: |e| clips_all(e, &inside_outside_cases()),
        },
        Check {
            exercise: 38,
            name: "a plane through a vertex: the vertex kept once, no point added at it",
            points: 2,
            run: |e| clips_all(e, &through_vertex_cases()),
        },
        Check {
            exercise: 38,
            name: "a plane along an edge or touching a vertex from outside leaves that edge or \
                   vertex; a polygon in the plane is kept whole",
            points: 2,
            run: |e| clips_all(e, &touching_cases()),
        },
        Check {
            exercise: 38,
            name: "random convex polygons (3 to 8 vertices, in space) against random planes",
            points: 3,
            run: |e| {
                random_clips().into_iter().enumerate().all(|(k, (poly, n, d))| {
                    let mut want = vec![DVec3::ZERO; poly.len() + 1];
                    let m = Reference.clip_polygon(&poly, n, d, &mut want);
                    want.truncate(m);
                    let what = format!("random polygon {k}: {}", show_polygon(&poly));
                    clips_to(e, &(what, poly, n, d, want))
                })
            },
        },
        Check {
            exercise: 38,
            name: "clipped areas: a cube's face with its corner cut off, no planes, clipped to \
                   an edge or to nothing",
            points: 2,
            run: |e| {
                area_cases().iter().all(|(what, poly, planes, want)| {
                    near(
                        format!("clipped_area({what})"),
                        *want,
                        e.clipped_area(poly, planes),
                    )
                })
            },
        },
        Check {
            exercise: 38,
            name: "clipped areas: every face of 26-DOPs around random points, a flat set and a \
                   single point",
            points: 2,
            run: |e| {
                dop_faces().iter().all(|(what, faces)| {
                    faces.iter().enumerate().all(|(f, (square, planes))| {
                        let call = format!(
                            "clipped_area(face {f} of the 26-DOP of {what}: {}, the other 25 planes)",
                            show_polygon(square)
                        );
                        near(
                            call,
                            Reference.clipped_area(square, planes),
                            e.clipped_area(square, planes),
                        )
                    })
                })
            },
        },
    ]
}

/// A point.
fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

/// One clip: `(what, polygon, normal, offset, expected polygon)`.
type Clip = (String, Vec<DVec3>, DVec3, f64, Vec<DVec3>);

/// The square of side 2 in z = 0, counter-clockwise about z, and its name.
fn sq() -> (String, Vec<DVec3>) {
    let s = square(2.0).to_vec();
    (format!("the square {}", show_polygon(&s)), s)
}

/// The triangle with corners on the axes at 1, 2 and 3, and its name.
fn tilted() -> (String, Vec<DVec3>) {
    let t = vec![v(1.0, 0.0, 0.0), v(0.0, 2.0, 0.0), v(0.0, 0.0, 3.0)];
    (format!("the triangle {}", show_polygon(&t)), t)
}

fn crossing_cases() -> Vec<Clip> {
    let ((s, square), (t, tri)) = (sq(), tilted());
    let corner = vec![v(0.0, 0.0, 0.0), v(0.5, 0.0, 0.0), v(0.0, 0.5, 0.0)];
    let rest = vec![
        v(0.5, 0.0, 0.0),
        v(2.0, 0.0, 0.0),
        v(2.0, 2.0, 0.0),
        v(0.0, 2.0, 0.0),
        v(0.0, 0.5, 0.0),
    ];
    let below = vec![
        v(1.0, 0.0, 0.0),
        v(0.0, 2.0, 0.0),
        v(0.0, 4.0 / 3.0, 1.0),
        v(2.0 / 3.0, 0.0, 1.0),
    ];
    vec![
        // x + y <= 1/2 cuts the square's corner a quarter of the way along
        // two edges; then the other side of the same plane.
        (s.clone(), square.clone(), v(1.0, 1.0, 0.0), 0.5, corner),
        (s, square, v(-1.0, -1.0, 0.0), -0.5, rest),
        // z <= 1 a third of the way up the edges to (0,0,3).
        (t, tri, DVec3::Z, 1.0, below),
    ]
}

fn closing_cases() -> Vec<Clip> {
    let (s, square) = sq();
    vec![
        // y <= 1 crosses edge 1 -> 2 and the closing edge 3 -> 0.
        (
            s.clone(),
            square.clone(),
            DVec3::Y,
            1.0,
            vec![
                v(0.0, 0.0, 0.0),
                v(2.0, 0.0, 0.0),
                v(2.0, 1.0, 0.0),
                v(0.0, 1.0, 0.0),
            ],
        ),
        // y >= 1: the same edges, the other way.
        (
            s,
            square,
            DVec3::NEG_Y,
            -1.0,
            vec![
                v(2.0, 1.0, 0.0),
                v(2.0, 2.0, 0.0),
                v(0.0, 2.0, 0.0),
                v(0.0, 1.0, 0.0),
            ],
        ),
    ]
}

fn inside_outside_cases() -> Vec<Clip> {
    let ((s, square), (t, tri)) = (sq(), tilted());
    vec![
        (s.clone(), square.clone(), DVec3::X, 5.0, square.clone()),
        (t.clone(), tri.clone(), DVec3::ONE, 3.0, tri.clone()),
        (s, square, DVec3::X, -0.5, vec![]),
        (t, tri, DVec3::NEG_ONE, -3.5, vec![]),
    ]
}

fn through_vertex_cases() -> Vec<Clip> {
    let (s, square) = sq();
    let tri = vec![v(0.0, 0.0, 0.0), v(4.0, 0.0, 0.0), v(0.0, 2.0, 0.0)];
    let t = format!("the triangle {}", show_polygon(&tri));
    let cut = v(4.0 / 3.0, 4.0 / 3.0, 0.0);
    let (o, x2, y2) = (v(0.0, 0.0, 0.0), v(2.0, 0.0, 0.0), v(0.0, 2.0, 0.0));
    vec![
        // x + y <= 2 passes through (2,0,0) and (0,2,0); both sides.
        (
            s.clone(),
            square.clone(),
            v(1.0, 1.0, 0.0),
            2.0,
            vec![o, x2, y2],
        ),
        (
            s,
            square,
            v(-1.0, -1.0, 0.0),
            -2.0,
            vec![x2, v(2.0, 2.0, 0.0), y2],
        ),
        // x - y <= 0 through the vertex (0,0,0), across the far edge; both sides.
        (
            t.clone(),
            tri.clone(),
            v(1.0, -1.0, 0.0),
            0.0,
            vec![o, cut, y2],
        ),
        (
            t,
            tri,
            v(-1.0, 1.0, 0.0),
            0.0,
            vec![o, v(4.0, 0.0, 0.0), cut],
        ),
    ]
}

fn touching_cases() -> Vec<Clip> {
    let (s, square) = sq();
    let edge = vec![v(2.0, 0.0, 0.0), v(2.0, 2.0, 0.0)];
    vec![
        // x <= 2: the edge x = 2 is on the plane, the square stays whole.
        (s.clone(), square.clone(), DVec3::X, 2.0, square.clone()),
        // x >= 2: only that edge is left.
        (s.clone(), square.clone(), DVec3::NEG_X, -2.0, edge),
        // x + y >= 4: only the corner (2,2,0).
        (
            s.clone(),
            square.clone(),
            v(-1.0, -1.0, 0.0),
            -4.0,
            vec![v(2.0, 2.0, 0.0)],
        ),
        // The square lies in z = 0: kept whole, either way round.
        (s.clone(), square.clone(), DVec3::Z, 0.0, square.clone()),
        (s, square.clone(), DVec3::NEG_Z, 0.0, square),
    ]
}

/// One area: `(what, polygon, planes, expected area)`.
type Area = (String, Vec<DVec3>, Vec<(DVec3, f64)>, f64);

fn area_cases() -> Vec<Area> {
    let face = vec![
        v(-0.5, -0.5, 0.5),
        v(0.5, -0.5, 0.5),
        v(0.5, 0.5, 0.5),
        v(-0.5, 0.5, 0.5),
    ];
    let sides = [
        (DVec3::X, 0.5),
        (DVec3::NEG_X, 0.5),
        (DVec3::Y, 0.5),
        (DVec3::NEG_Y, 0.5),
    ];
    let corner = (DVec3::ONE, 1.0);
    let (t, tri) = tilted();
    let f = "the unit cube's face z = 1/2";
    vec![
        // The corner plane x + y + z <= 1 cuts a right triangle of legs
        // 1/2 off the face; its sides run along the square's edges.
        (
            format!("{f}, its four sides and x + y + z <= 1"),
            face.clone(),
            [&sides[..], &[corner]].concat(),
            0.875,
        ),
        (
            format!("{f}, x + y + z <= 1 and its four sides"),
            face.clone(),
            [&[corner][..], &sides[..]].concat(),
            0.875,
        ),
        (format!("{t}, no planes"), tri, vec![], 3.5),
        (
            format!("{f}, its four sides and x >= 1/2 (an edge is left)"),
            face.clone(),
            [&sides[..], &[(DVec3::NEG_X, -0.5)]].concat(),
            0.0,
        ),
        (
            format!("{f}, z <= 1/4 and its four sides"),
            face,
            [&[(DVec3::Z, 0.25)][..], &sides[..]].concat(),
            0.0,
        ),
    ]
}

/// Runs [`clips_to`] on every case.
fn clips_all(e: &dyn Exercises, cases: &[Clip]) -> bool {
    cases.iter().all(|c| clips_to(e, c))
}

/// The square `(0,0,0) (s,0,0) (s,s,0) (0,s,0)`.
fn square(s: f64) -> [DVec3; 4] {
    [
        DVec3::ZERO,
        DVec3::new(s, 0.0, 0.0),
        DVec3::new(s, s, 0.0),
        DVec3::new(0.0, s, 0.0),
    ]
}

/// A point as `(x, y, z)`.
fn show_dpoint(p: &DVec3) -> String {
    format!("({}, {}, {})", p.x, p.y, p.z)
}

fn show_polygon(poly: &[DVec3]) -> String {
    let v: Vec<String> = poly.iter().map(show_dpoint).collect();
    format!("[{}]", v.join(" "))
}

/// Whether two points agree within 1e-9, relative to the larger of 1 and
/// the expected coordinate.
fn close_point(got: DVec3, want: DVec3) -> bool {
    (0..3).all(|k| (got[k] - want[k]).abs() <= 1e-9 * want[k].abs().max(1.0))
}

/// Whether `got` is `want` starting at any vertex, in the same order.
fn same_cycle(want: &[DVec3], got: &[DVec3]) -> bool {
    let m = want.len();
    got.len() == m
        && (m == 0 || (0..m).any(|r| (0..m).all(|k| close_point(got[(k + r) % m], want[k]))))
}

/// Clips with `e` into `polygon.len() + 1` entries (filled with NaN first)
/// and compares with the expected polygon up to the starting vertex,
/// explaining a difference.
fn clips_to(e: &dyn Exercises, (what, polygon, normal, offset, want): &Clip) -> bool {
    let mut out = vec![DVec3::NAN; polygon.len() + 1];
    let m = e.clip_polygon(polygon, *normal, *offset, &mut out);
    let call = format!(
        "clip_polygon({what}, normal {}, offset {offset})",
        show_dpoint(normal)
    );
    if m > out.len() {
        return fail(format!(
            "{call} returned {m}, more than the {} entries of out",
            out.len()
        ));
    }
    same_cycle(want, &out[..m])
        || fail(format!(
            "{call} returned {m} vertices {}, expected {} vertices {} (starting at any of them)",
            show_polygon(&out[..m]),
            want.len(),
            show_polygon(want)
        ))
}

/// Random convex polygons in space (3 to 8 vertices on an ellipse, in a
/// random plane), each with a random plane (normals of length 0.5 to 2.5)
/// that usually crosses it and never passes within 1e-6 of a vertex, so
/// that every way of computing the side of a vertex agrees.
fn random_clips() -> Vec<(Vec<DVec3>, DVec3, f64)> {
    let mut r = Rng(3838);
    let mut u = move || r.next() as f64;
    let mut cases = Vec::new();
    while cases.len() < 300 {
        let c = DVec3::new(u() - 0.5, u() - 0.5, u() - 0.5) * 4.0;
        let m = DVec3::new(u() - 0.5, u() - 0.5, u() - 0.5);
        let n = DVec3::new(u() - 0.5, u() - 0.5, u() - 0.5);
        if m.length() < 0.1 || n.length() < 0.1 {
            continue;
        }
        let (a, b) = m.normalize().any_orthonormal_pair();
        let k = 3 + (u() * 6.0) as usize;
        let mut angles: Vec<f64> = (0..k).map(|_| u() * std::f64::consts::TAU).collect();
        angles.sort_by(f64::total_cmp);
        let gaps = (0..k).map(|i| {
            let next = if i + 1 == k {
                angles[0] + std::f64::consts::TAU
            } else {
                angles[i + 1]
            };
            next - angles[i]
        });
        if gaps.fold(f64::INFINITY, f64::min) < 0.2 {
            continue;
        }
        let (ra, rb) = (0.5 + 1.5 * u(), 0.5 + 1.5 * u());
        let poly: Vec<DVec3> = angles
            .iter()
            .map(|t| c + a * (ra * t.cos()) + b * (rb * t.sin()))
            .collect();
        let n = n.normalize() * (0.5 + 2.0 * u());
        // A point of the polygon's plane near it: most planes cross it,
        // some miss it on either side.
        let target = c + (a * (u() - 0.5) * ra + b * (u() - 0.5) * rb) * 3.0;
        let d = n.dot(target);
        if poly.iter().any(|p| (n.dot(*p) - d).abs() < 1e-6) {
            continue;
        }
        cases.push((poly, n, d));
    }
    cases
}

/// One k-DOP face to measure: the starting square and the other planes.
type Face = (Vec<DVec3>, Vec<(DVec3, f64)>);

/// The point sets whose 26-DOPs' faces exercise 38b measures: random
/// clouds, a flat set and a single point, all within 2 of the origin.
fn dop_point_sets() -> Vec<(String, Vec<Vec3>)> {
    let mut r = Rng(0x38d0);
    let mut sets: Vec<(String, Vec<Vec3>)> = (0..6)
        .map(|i| {
            let n = 4 + 7 * i;
            let pts = r.cloud(n, 2.0, Vec3::new(0.2, -0.1, 0.3));
            (format!("{n} random points"), pts)
        })
        .collect();
    let flat = r
        .cloud(12, 2.0, Vec3::ZERO)
        .into_iter()
        .map(|p| Vec3::new(p.x, p.y, 0.25))
        .collect();
    sets.push(("12 random points in the plane z = 1/4".into(), flat));
    sets.push((
        "the single point (0.5, -0.25, 0.125)".into(),
        vec![Vec3::new(0.5, -0.25, 0.125)],
    ));
    sets
}

/// The 26 faces of `dop`, each as the core measures it: a square of half
/// side 4 in the face's plane (the points are within 2 of the origin),
/// counter-clockwise about the outward normal, and the 25 other planes
/// (unnormalised directions, as the k-DOP stores its slabs).
fn faces_of(dop: &Dop26) -> Vec<Face> {
    let mut planes = Vec::new();
    for i in 0..13 {
        let d = Dop26::direction(i);
        let d = DVec3::new(d[0] as f64, d[1] as f64, d[2] as f64);
        planes.push((d, dop.max[i] as f64));
        planes.push((-d, -(dop.min[i] as f64)));
    }
    (0..planes.len())
        .map(|f| {
            let (n, h) = planes[f];
            let unit = n.normalize();
            let c = unit * (h / n.length());
            let (u, v) = unit.any_orthonormal_pair();
            // (u, v, unit) is right-handed, so this runs counter-clockwise.
            let square = [(-4.0, -4.0), (4.0, -4.0), (4.0, 4.0), (-4.0, 4.0)]
                .map(|(s, t)| c + u * s + v * t)
                .to_vec();
            let others = [&planes[..f], &planes[f + 1..]].concat();
            (square, others)
        })
        .collect()
}

/// Every point set's 26-DOP faces.
fn dop_faces() -> Vec<(String, Vec<Face>)> {
    dop_point_sets()
        .into_iter()
        .map(|(what, pts)| (what, faces_of(&Dop26::fit(pts.as_slice()))))
        .collect()
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 9;

    pub fn clip_polygon(
        which: u32,
        polygon: &[DVec3],
        normal: DVec3,
        offset: f64,
        out: &mut [DVec3],
    ) -> usize {
        let n = polygon.len();
        let s = |p: DVec3| normal.dot(p) - offset;
        // One Sutherland–Hodgman pass over `edges` edges with the given
        // tests: keep p?, crossing between sp and sq?, and t.
        let mut pass = |edges: usize,
                        keep: &dyn Fn(f64) -> bool,
                        cross: &dyn Fn(f64, f64) -> bool,
                        t: &dyn Fn(f64, f64) -> f64| {
            let mut m = 0;
            for i in 0..edges {
                let (p, q) = (polygon[i], polygon[(i + 1) % n]);
                let (sp, sq) = (s(p), s(q));
                if keep(sp) {
                    out[m] = p;
                    m += 1;
                }
                if cross(sp, sq) {
                    out[m] = p + (q - p) * t(sp, sq);
                    m += 1;
                }
            }
            m
        };
        let strict = |sp: f64, sq: f64| (sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0);
        let t = |sp: f64, sq: f64| sp / (sp - sq);
        match which {
            // The wrong side kept: n . p >= d.
            1 => pass(n, &|sp| sp >= 0.0, &strict, &t),
            // The crossing measured from the wrong end of the edge.
            2 => pass(n, &|sp| sp <= 0.0, &strict, &|sp, sq| sq / (sq - sp)),
            // The closing edge (last vertex back to the first) forgotten.
            3 => pass(n - 1, &|sp| sp <= 0.0, &strict, &t),
            // A crossing whenever p and q are on different sides of
            // "inside or on": a vertex on the plane next to one outside
            // comes out twice.
            4 => pass(n, &|sp| sp <= 0.0, &|sp, sq| (sp <= 0.0) != (sq <= 0.0), &t),
            // Vertices on the plane dropped: only those strictly inside kept.
            5 => pass(n, &|sp| sp < 0.0, &strict, &t),
            // "Not a polygon any more": a point or an edge is reported as nothing.
            6 => match Reference.clip_polygon(polygon, normal, offset, out) {
                m if m < 3 => 0,
                m => m,
            },
            // A shortcut that says "all of it" without writing `out`.
            7 if polygon.iter().all(|&p| s(p) <= 0.0) => n,
            _ => Reference.clip_polygon(polygon, normal, offset, out),
        }
    }

    pub fn clipped_area(which: u32, polygon: &[DVec3], planes: &[(DVec3, f64)]) -> f64 {
        match which {
            // The buffers not swapped: every plane clips the original
            // polygon, and the last clip is measured.
            8 => {
                let mut out = [DVec3::ZERO; crate::CLIP_CAPACITY];
                let mut len = polygon.len();
                out[..len].copy_from_slice(polygon);
                for &(n, d) in planes {
                    len = Reference.clip_polygon(polygon, n, d, &mut out);
                }
                if len < 3 {
                    0.0
                } else {
                    crate::reference::polygon_area(&out[..len])
                }
            }
            // The length of the cross products' sum, not halved.
            9 => 2.0 * Reference.clipped_area(polygon, planes),
            _ => Reference.clipped_area(polygon, planes),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The faces the grader measures add up to the library's own surface
    /// area of each 26-DOP (core clips with a tolerance and rounds to f32).
    #[test]
    fn the_faces_add_up_to_the_librarys_surface_area() {
        for (what, pts) in dop_point_sets() {
            let dop = Dop26::fit(pts.as_slice());
            let sum: f64 = faces_of(&dop)
                .iter()
                .map(|(sq, planes)| Reference.clipped_area(sq, planes))
                .sum();
            let core = dop.surface_area() as f64;
            assert!(
                (sum - core).abs() <= 1e-5 * core.max(1e-3),
                "{what}: faces {sum}, core {core}"
            );
            // And the faces are not all slivers: the sets have area.
            assert!(what.contains("single") || sum > 0.1, "{what}: {sum}");
        }
    }

    /// The random clips cross the plane in most cases, miss it on both
    /// sides in some, and cover every polygon size.
    #[test]
    fn the_random_clips_cover_every_outcome() {
        let cases = random_clips();
        let (mut cut, mut whole, mut none) = (0, 0, 0);
        let mut sizes = [0; 9];
        for (poly, n, d) in &cases {
            let mut out = vec![DVec3::ZERO; poly.len() + 1];
            match Reference.clip_polygon(poly, *n, *d, &mut out) {
                0 => none += 1,
                m if m == poly.len() && poly.iter().all(|p| n.dot(*p) <= *d) => whole += 1,
                _ => cut += 1,
            }
            sizes[poly.len()] += 1;
        }
        assert!(cut > 150 && whole > 10 && none > 10, "{cut} {whole} {none}");
        assert!(sizes[3..].iter().all(|&s| s > 10), "{sizes:?}");
    }
}
