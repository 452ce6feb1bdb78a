//! Exercise 52: the rotation by area of a dynamic tree's node.
//! The checks, and the plausible wrong answers they must reject.
//!
//! The expected answer is the reference's (the library's
//! [`bvhkit::builders::area_rotation`]). Every case's areas are far from a
//! tie unless the tie is exact (mirror images, equal boxes), so a student who
//! compares plain surface areas agrees with the library's scaled ones.

use super::common::*;

/// The checks of exercise 52.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 52,
            name: "two leaves, or a leaf beside a node already in its best shape: no rotation",
            points: 1,
            run: |e| agrees(e, &still_cases()),
        },
        Check {
            exercise: 52,
            name: "a leaf beside a node, on either side: the far grandchild moves up",
            points: 2,
            run: |e| agrees(e, &leaf_cases()),
        },
        Check {
            exercise: 52,
            name: "two inner children: the best of the four swaps, in both directions",
            points: 2,
            run: |e| agrees(e, &inner_cases()),
        },
        Check {
            exercise: 52,
            name: "ties go to the first swap in order; a swap that only keeps the area is not made",
            points: 2,
            run: |e| agrees(e, &tie_cases()),
        },
        Check {
            exercise: 52,
            name: "800 random nodes, leaves and inner children mixed, near-ties left out",
            points: 3,
            run: |e| agrees(e, &random_cases()),
        },
    ]
}

/// A node's two children and their children (`None` for a leaf).
#[derive(Clone, Debug)]
struct Case {
    children: [Aabb; 2],
    grandchildren: [Option<[Aabb; 2]>; 2],
}

impl Case {
    /// A child over two grandchildren (its box their union).
    fn inner(a: Aabb, b: Aabb) -> (Aabb, Option<[Aabb; 2]>) {
        (a.union(&b), Some([a, b]))
    }
    fn new(left: (Aabb, Option<[Aabb; 2]>), right: (Aabb, Option<[Aabb; 2]>)) -> Case {
        Case {
            children: [left.0, right.0],
            grandchildren: [left.1, right.1],
        }
    }
}

fn leaf(b: Aabb) -> (Aabb, Option<[Aabb; 2]>) {
    (b, None)
}

fn unit(x: f32, y: f32) -> Aabb {
    b([x, y, 0.0], [x + 1.0, y + 1.0, 1.0])
}

fn agrees(e: &dyn Exercises, cases: &[Case]) -> bool {
    cases.iter().all(|c| {
        let want = Reference.area_rotation(c.children, c.grandchildren);
        let got = e.area_rotation(c.children, c.grandchildren);
        got == want
            || fail(format!(
                "area_rotation(children {:?}, grandchildren {:?}): expected {want:?}, got {got:?}",
                c.children, c.grandchildren
            ))
    })
}

fn still_cases() -> Vec<Case> {
    vec![
        Case::new(leaf(unit(0.0, 0.0)), leaf(unit(5.0, 0.0))),
        // c beside (a, b), a and b side by side: already best.
        Case::new(
            leaf(unit(9.0, 0.0)),
            Case::inner(unit(0.0, 0.0), unit(1.0, 0.0)),
        ),
        Case::new(
            Case::inner(unit(0.0, 0.0), unit(1.0, 0.0)),
            leaf(unit(9.0, 0.0)),
        ),
    ]
}

fn leaf_cases() -> Vec<Case> {
    vec![
        Case::new(
            leaf(unit(0.0, 0.0)),
            Case::inner(unit(1.0, 0.0), unit(9.0, 0.0)),
        ),
        Case::new(
            leaf(unit(0.0, 0.0)),
            Case::inner(unit(9.0, 0.0), unit(1.0, 0.0)),
        ),
        Case::new(
            Case::inner(unit(1.0, 0.0), unit(9.0, 0.0)),
            leaf(unit(0.0, 0.0)),
        ),
        Case::new(
            Case::inner(unit(9.0, 3.0), unit(1.0, 0.0)),
            leaf(unit(0.0, 0.5)),
        ),
    ]
}

fn inner_cases() -> Vec<Case> {
    let small = || Case::inner(unit(0.0, 0.0), unit(1.0, 0.0));
    let long = || Case::inner(unit(2.0, 0.0), unit(30.0, 0.0));
    let long_flipped = || Case::inner(unit(30.0, 0.0), unit(2.0, 0.0));
    vec![
        Case::new(small(), long()),
        Case::new(small(), long_flipped()),
        Case::new(long(), small()),
        Case::new(long_flipped(), small()),
        // The right child is the one to move down: a big box beside a node
        // of two far apart small ones.
        Case::new(
            Case::inner(unit(0.0, 0.0), unit(0.0, 40.0)),
            Case::inner(unit(1.0, 1.0), unit(1.0, 2.0)),
        ),
    ]
}

fn tie_cases() -> Vec<Case> {
    vec![
        // a between b and c, mirror images: (down 0, up 0) and (0, 1) tie.
        Case::new(
            leaf(unit(0.0, 0.0)),
            Case::inner(unit(-9.0, 0.0), unit(9.0, 0.0)),
        ),
        Case::new(
            Case::inner(unit(-9.0, 0.0), unit(9.0, 0.0)),
            leaf(unit(0.0, 0.0)),
        ),
        // Equal boxes everywhere: every swap keeps every area.
        Case::new(
            leaf(unit(0.0, 0.0)),
            Case::inner(unit(0.0, 0.0), unit(0.0, 0.0)),
        ),
        Case::new(
            Case::inner(unit(3.0, 3.0), unit(3.0, 3.0)),
            Case::inner(unit(3.0, 3.0), unit(3.0, 3.0)),
        ),
        // Four unit boxes in a row, two per child in order: every swap
        // makes a child wider; none is made.
        Case::new(
            Case::inner(unit(0.0, 0.0), unit(1.0, 0.0)),
            Case::inner(unit(2.0, 0.0), unit(3.0, 0.0)),
        ),
    ]
}

/// The surface area a student would compute.
fn area(b: &Aabb) -> f64 {
    let e = (b.max - b.min).as_dvec3();
    2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
}

/// Whether two of the swaps (or a swap and "keep") come within a part in a
/// thousand of each other, where rounding may decide.
fn near_tie(c: &Case) -> bool {
    let mut sizes = Vec::new();
    for down in 0..2 {
        let Some(kids) = c.grandchildren[1 - down] else {
            continue;
        };
        let before = area(&c.children[1 - down]);
        for up in 0..2 {
            sizes.push(before - area(&c.children[down].union(&kids[1 - up])));
        }
    }
    sizes.push(0.0);
    let scale = area(&c.children[0].union(&c.children[1]));
    sizes
        .iter()
        .enumerate()
        .any(|(i, x)| sizes[i + 1..].iter().any(|y| (x - y).abs() <= 1e-3 * scale))
}

fn random_cases() -> Vec<Case> {
    let mut rng = Rng(0x5EED_0052);
    let mut cases = Vec::new();
    let boxed = |rng: &mut Rng| {
        let lo = rng.point(20.0, Vec3::ZERO);
        Aabb::new(lo, lo + Vec3::new(rng.next(), rng.next(), rng.next()) * 4.0)
    };
    while cases.len() < 800 {
        let child = |rng: &mut Rng| {
            if rng.next() < 0.3 {
                leaf(boxed(rng))
            } else {
                let (a, b) = (boxed(rng), boxed(rng));
                Case::inner(a, b)
            }
        };
        let (l, r) = (child(&mut rng), child(&mut rng));
        let c = Case::new(l, r);
        if !near_tie(&c) {
            cases.push(c);
        }
    }
    // Every outcome appears.
    debug_assert!(cases.iter().any(|c| Reference
        .area_rotation(c.children, c.grandchildren)
        .is_none()));
    cases
}

/// Plausible wrong answers (for the grader's self-test).
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 5;

    /// Wrong answer `which`:
    /// 1 only ever moves the left child down;
    /// 2 makes a swap that saves nothing (`>=` where `>` is meant);
    /// 3 the largest area after, not the smallest;
    /// 4 the last of tied swaps, not the first;
    /// 5 measures the node's own area, which no swap changes: never rotates.
    pub fn area_rotation(
        which: u32,
        children: [Aabb; 2],
        grandchildren: [Option<[Aabb; 2]>; 2],
    ) -> Option<(usize, usize)> {
        if which == 0 || which == 5 {
            return if which == 0 {
                Reference.area_rotation(children, grandchildren)
            } else {
                None
            };
        }
        let mut best: Option<((usize, usize), f64)> = None;
        let downs: &[usize] = if which == 1 { &[0] } else { &[0, 1] };
        for &down in downs {
            let Some(kids) = grandchildren[1 - down] else {
                continue;
            };
            let before = area(&children[1 - down]);
            for up in 0..2 {
                let after = area(&children[down].union(&kids[1 - up]));
                let saved = before - after;
                let better = match which {
                    2 => saved >= 0.0 && best.is_none_or(|(_, b)| saved > b),
                    3 => best.is_none_or(|(_, b)| -saved > b),
                    4 => saved > 0.0 && best.is_none_or(|(_, b)| saved >= b),
                    _ => saved > 0.0 && best.is_none_or(|(_, b)| saved > b),
                };
                if better {
                    best = Some(((down, up), if which == 3 { -saved } else { saved }));
                }
            }
        }
        best.map(|(r, _)| r)
    }
}
