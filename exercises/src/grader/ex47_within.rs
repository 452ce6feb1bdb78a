//! Exercise 47: every triangle within a distance of a point, through a
//! tree. The checks, and the plausible wrong answers they must reject.
//!
//! Every expected answer is the reference's, which is the library's
//! `Mesh::within` on the tree given; where the tree is honest (no box
//! moved) the answer is also checked against brute force over every
//! triangle, so the reference itself is held to the statement.

use super::common::*;

/// The checks of exercise 47.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 47,
            name: "random soups and rocks, points near and inside them, many distances: exactly \
                   the triangles within, in increasing order",
            points: 2,
            run: |e| agrees(e, &random_cases()),
        },
        Check {
            exercise: 47,
            name: "a triangle exactly at the distance is within (at most, not less than)",
            points: 1,
            run: |e| agrees(e, &exact_cases()),
        },
        Check {
            exercise: 47,
            name: "the closest point can be inside a face or an edge, far from every corner and \
                   from the centroid",
            points: 1,
            run: |e| agrees(e, &feature_cases()),
        },
        Check {
            exercise: 47,
            name: "distance 0: the triangles the point lies on",
            points: 1,
            run: |e| agrees(e, &touching_cases()),
        },
        Check {
            exercise: 47,
            name: "the tree prunes: nothing beneath a node whose box was moved away is reported",
            points: 2,
            run: |e| agrees(e, &tampered_cases()),
        },
        Check {
            exercise: 47,
            name: "an empty tree and mesh: nothing",
            points: 1,
            run: |e| agrees(e, &[empty_case()]),
        },
    ]
}

/// Triangles, their tree (possibly with boxes moved), a point and a
/// distance, and the answer expected.
struct Case {
    tris: Vec<Triangle>,
    nodes: Vec<Node<Aabb>>,
    indices: Vec<u32>,
    depth: usize,
    p: Vec3,
    distance: f32,
    what: String,
    /// Whether every node's box is the one the builder wrote (then the
    /// answer is also brute force's).
    honest: bool,
}

impl Case {
    fn tree(&self) -> Bvh<'_, Aabb> {
        Bvh::from_raw_parts(&self.nodes, &self.indices, self.depth)
    }

    /// The case over `tris` with an honest tree (leaves of up to `leaf`).
    fn new(tris: Vec<Triangle>, leaf: u32, p: Vec3, distance: f32, what: String) -> Case {
        let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(tris.len())];
        let mut indices = vec![0u32; tris.len()];
        let (used, depth) =
            match TopDown::default()
                .with_max_leaf_size(leaf)
                .build(&tris, &mut nodes, &mut indices)
            {
                Ok(t) => (t.node_count(), t.depth()),
                Err(_) => (0, 0),
            };
        nodes.truncate(used);
        Case {
            tris,
            nodes,
            indices,
            depth,
            p,
            distance,
            what,
            honest: true,
        }
    }
}

/// Every triangle within, by testing them all.
fn brute(c: &Case) -> Vec<u32> {
    let limit = f64::from(c.distance) * f64::from(c.distance);
    (0..c.tris.len() as u32)
        .filter(|&i| c.tris[i as usize].closest_point(c.p).distance_squared <= limit)
        .collect()
}

fn agrees(e: &dyn Exercises, cases: &[Case]) -> bool {
    cases.iter().all(|c| {
        let tree = c.tree();
        let want = Reference.triangles_within(&tree, &c.tris, c.p, c.distance);
        if c.honest && want != brute(c) {
            return fail(format!(
                "the reference disagrees with brute force on {} (a grader bug)",
                c.what
            ));
        }
        let got = e.triangles_within(&tree, &c.tris, c.p, c.distance);
        let show = |v: &[u32]| {
            if v.len() <= 12 {
                format!("{v:?}")
            } else {
                format!("{} triangles starting {:?}", v.len(), &v[..12])
            }
        };
        got == want
            || fail(format!(
                "triangles_within({}, p = {}, distance = {}) returned {}, expected {}",
                c.what,
                c.p,
                c.distance,
                show(&got),
                show(&want)
            ))
    })
}

fn tri(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> Triangle {
    Triangle::new(Vec3::from(a), Vec3::from(b), Vec3::from(c))
}

/// A soup of `n` small triangles in a cube of side `scale` around `at`.
fn soup(r: &mut Rng, n: usize, scale: f32, at: Vec3) -> Vec<Triangle> {
    (0..n)
        .map(|_| {
            let a = r.point(scale, at);
            Triangle::new(
                a,
                a + r.point(scale * 0.1, Vec3::ZERO),
                a + r.point(scale * 0.1, Vec3::ZERO),
            )
        })
        .collect()
}

fn random_cases() -> Vec<Case> {
    let mut r = Rng(4747);
    let mut out = Vec::new();
    for (k, (scale, at)) in [
        (10.0, Vec3::ZERO),
        (1.0e-2, Vec3::ZERO),
        (100.0, Vec3::splat(1.0e5)),
    ]
    .into_iter()
    .enumerate()
    {
        for leaf in [1, 4] {
            let tris = soup(&mut r, 300, scale, at);
            for _ in 0..12 {
                let p = r.point(scale * 1.2, at);
                let distance = r.next() * scale * 0.3;
                let what = format!("a soup of 300 triangles (scene {k}, leaves of {leaf})");
                out.push(Case::new(tris.clone(), leaf, p, distance, what));
            }
        }
    }
    let rock = bvhkit_std::scene::rock(3, 9);
    for _ in 0..12 {
        let p = r.point(2.4, Vec3::ZERO);
        let what = "the rock of 1,280 triangles".to_string();
        out.push(Case::new(rock.clone(), 4, p, r.next() * 0.5, what));
    }
    out
}

/// Distances that equal a triangle's distance exactly in `f64`.
fn exact_cases() -> Vec<Case> {
    let floor = |z: f32| tri([-4.0, -4.0, z], [4.0, -4.0, z], [0.0, 4.0, z]);
    let mut out = Vec::new();
    for (z, pz) in [(0.0, 1.5), (-2.25, 0.75), (1024.0, 1030.5)] {
        let tris = vec![floor(z), floor(z - 10.0), floor(z + 10.0)];
        let what = format!("three floors at z = {}, {} and {}", z, z - 10.0, z + 10.0);
        out.push(Case::new(tris, 1, Vec3::new(0.5, 0.25, pz), pz - z, what));
    }
    out
}

/// Closest points inside a face and inside an edge: every corner and the
/// centroid are far beyond the distance.
fn feature_cases() -> Vec<Case> {
    let big = tri([-50.0, -50.0, 0.0], [50.0, -50.0, 0.0], [0.0, 80.0, 0.0]);
    let far = tri([200.0, 0.0, 0.0], [201.0, 0.0, 0.0], [200.0, 1.0, 0.0]);
    vec![
        Case::new(
            vec![big, far],
            1,
            Vec3::new(-20.0, 10.0, 0.5),
            1.0,
            "a triangle with corners 50 apart and another far off, the point 0.5 above the \
             first's face"
                .into(),
        ),
        Case::new(
            vec![far, big],
            1,
            Vec3::new(10.0, -50.75, 0.0),
            1.0,
            "the same two triangles, the point 0.75 beside the long edge from (-50, -50) to \
             (50, -50)"
                .into(),
        ),
    ]
}

/// Distance 0: a point on a face, on a shared edge, on a shared corner.
fn touching_cases() -> Vec<Case> {
    let fan = vec![
        tri([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]),
        tri([2.0, 0.0, 0.0], [2.0, 2.0, 0.0], [0.0, 2.0, 0.0]),
        tri([0.0, 0.0, 0.0], [0.0, 2.0, 0.0], [-2.0, 1.0, 0.0]),
        tri([5.0, 5.0, 5.0], [6.0, 5.0, 5.0], [5.0, 6.0, 5.0]),
    ];
    let what = "a fan of three triangles in the plane z = 0 and one apart";
    [
        Vec3::new(0.5, 0.5, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ]
    .into_iter()
    .map(|p| Case::new(fan.clone(), 1, p, 0.0, what.into()))
    .collect()
}

/// Honest trees with one node's box moved 1000 along x (its contents left
/// in place): a query that prunes never looks beneath it.
fn tampered_cases() -> Vec<Case> {
    let mut r = Rng(4711);
    let mut out = Vec::new();
    for (leaf, node) in [(1u32, 1usize), (4, 2), (2, 3)] {
        let tris = soup(&mut r, 200, 4.0, Vec3::ZERO);
        let mut c = Case::new(
            tris,
            leaf,
            Vec3::ZERO,
            10.0,
            format!("200 triangles, all within 10 of p, leaves of {leaf}, with the box of node {node} moved 1000 along x (its contents left in place)"),
        );
        c.honest = false;
        let moved = &mut c.nodes[node].bv;
        *moved = Aabb::new(moved.min + Vec3::X * 1000.0, moved.max + Vec3::X * 1000.0);
        out.push(c);
    }
    out
}

fn empty_case() -> Case {
    Case::new(
        Vec::new(),
        1,
        Vec3::ZERO,
        1.0,
        "no triangles, the empty tree".into(),
    )
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 8;

    pub fn triangles_within(
        which: u32,
        tree: &Bvh<Aabb>,
        tris: &[Triangle],
        p: Vec3,
        distance: f32,
    ) -> Vec<u32> {
        let d2 = f64::from(distance) * f64::from(distance);
        let dist2 = |i: u32| tris[i as usize].closest_point(p).distance_squared;
        let region = Aabb::new(p - distance, p + distance);
        let through_tree = |keep: &dyn Fn(u32) -> bool, region: &Aabb| {
            let mut v = Vec::new();
            let _ = tree.overlapping(tris, region, |i| {
                if keep(i) {
                    v.push(i);
                }
            });
            v
        };
        let mut v = match which {
            // 1: every triangle tested, the tree ignored.
            1 => (0..tris.len() as u32).filter(|&i| dist2(i) <= d2).collect(),
            // 2: strictly closer than the distance.
            2 => through_tree(&|i| dist2(i) < d2, &region),
            // 3: the broad phase alone: a triangle whose box meets the
            // region's.
            3 => through_tree(&|_| true, &region),
            // 4: the distance to the nearest corner, not the triangle.
            4 => through_tree(
                &|i| {
                    tris[i as usize]
                        .v
                        .iter()
                        .map(|v| (v.as_dvec3() - p.as_dvec3()).length_squared())
                        .fold(f64::INFINITY, f64::min)
                        <= d2
                },
                &region,
            ),
            // 5: in the tree's order, unsorted.
            5 => {
                return through_tree(&|i| dist2(i) <= d2, &region);
            }
            // 6: nothing at distance 0.
            6 if distance == 0.0 => Vec::new(),
            // 7: the region's half-width taken as half the distance.
            7 => {
                let half = Aabb::new(p - distance * 0.5, p + distance * 0.5);
                through_tree(&|i| dist2(i) <= d2, &half)
            }
            // 8: the squared distance compared with the distance.
            8 => through_tree(&|i| dist2(i) <= f64::from(distance), &region),
            _ => return Reference.triangles_within(tree, tris, p, distance),
        };
        v.sort_unstable();
        v
    }
}
