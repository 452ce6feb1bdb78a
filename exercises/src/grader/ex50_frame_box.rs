//! Exercise 50: a world box entered into a local frame, rounded outward.
//! The checks, and the plausible wrong answers they must reject.
//!
//! The expected answer is the reference's (the library's
//! [`bvhkit::LocalFrame::aabb`]): each bound the nearest `f32` on the outer
//! side of the exact offset `bound - origin`. The grader also holds the
//! reference to the statement's two properties on every case: the box
//! contains the world box's offsets, and no bound could move inward.

use super::common::*;
use bvhkit::glam::DVec3;

/// The checks of exercise 50.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 50,
            name: "offsets that are f32 values stay as they are (no widening)",
            points: 1,
            run: |e| agrees(e, &exact_cases()),
        },
        Check {
            exercise: 50,
            name: "boxes of every size around origins up to 1e7 away, negative sides too: \
                   outward and tightest",
            points: 2,
            run: |e| agrees(e, &random_cases()),
        },
        Check {
            exercise: 50,
            name: "a 1 mm box 600 km away: the offset taken in f64, before rounding",
            points: 2,
            run: |e| agrees(e, &far_cases()),
        },
    ]
}

/// A frame's origin and a world box.
struct Case {
    origin: DVec3,
    min: DVec3,
    max: DVec3,
}

/// The largest `f32` at or below `v`, found without the library's helper.
fn floor32(v: f64) -> f32 {
    let f = v as f32;
    if f64::from(f) > v {
        f.next_down()
    } else {
        f
    }
}

/// Contains the offsets, and each bound is the tightest that does.
fn sound(b: &Aabb, c: &Case) -> bool {
    let (lo, hi) = (c.min - c.origin, c.max - c.origin);
    (0..3).all(|k| {
        let (mn, mx) = (f64::from(b.min[k]), f64::from(b.max[k]));
        mn <= lo[k]
            && mx >= hi[k]
            && f64::from(b.min[k].next_up()) > lo[k]
            && f64::from(b.max[k].next_down()) < hi[k]
            && b.min[k] == floor32(lo[k])
    })
}

fn agrees(e: &dyn Exercises, cases: &[Case]) -> bool {
    cases.iter().all(|c| {
        let want = Reference.frame_box(c.origin, c.min, c.max);
        if !sound(&want, c) {
            return fail(format!(
                "the reference's box {want:?} for origin {} and [{}, {}] is not the tightest \
                 outward box (a grader bug)",
                c.origin, c.min, c.max
            ));
        }
        let got = e.frame_box(c.origin, c.min, c.max);
        got == want
            || fail(format!(
                "frame_box(origin {}, min {}, max {}): expected {want:?}, got {got:?}",
                c.origin, c.min, c.max
            ))
    })
}

fn exact_cases() -> Vec<Case> {
    let d = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    vec![
        Case {
            origin: DVec3::ZERO,
            min: d(-1.0, 0.0, 0.5),
            max: d(1.0, 2.0, 0.75),
        },
        Case {
            origin: d(1e6, -2e6, 4096.0),
            min: d(1e6 - 0.25, -2e6, 4096.0),
            max: d(1e6 + 0.5, -2e6 + 1.0, 4100.0),
        },
        Case {
            origin: d(0.1, 0.1, 0.1),
            min: d(0.1, 0.1, 0.1),
            max: d(0.1, 0.1, 0.1),
        },
    ]
}

fn random_cases() -> Vec<Case> {
    let mut rng = Rng(0x5EED_0050);
    let mut v = |scale: f64| (f64::from(rng.next()) - 0.5) * scale + f64::from(rng.next()) * 1e-9;
    let mut cases = Vec::new();
    for scale in [1e-3, 1.0, 1e3, 1e7] {
        for _ in 0..200 {
            let origin = DVec3::new(v(1e7), v(1e7), v(1e7));
            let min = origin + DVec3::new(v(scale), v(scale), v(scale));
            let max = min + DVec3::new(v(scale).abs(), v(scale).abs(), v(scale).abs());
            cases.push(Case { origin, min, max });
        }
    }
    cases
}

fn far_cases() -> Vec<Case> {
    let origin = DVec3::new(600_000.0, 250_000.0, -600_000.0);
    (0..50)
        .map(|i| {
            let at = origin + DVec3::splat(f64::from(i) * 0.013_7);
            Case {
                origin,
                min: at,
                max: at + DVec3::splat(0.001),
            }
        })
        .collect()
}

/// Plausible wrong answers (for the grader's self-test).
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 5;

    /// Wrong answer `which`:
    /// 1 rounds each bound to the nearest `f32` (inward half the time);
    /// 2 rounds the coordinates to `f32` first and subtracts in `f32`;
    /// 3 always moves each bound one `f32` outward, even when exact;
    /// 4 rounds both bounds down;
    /// 5 rounds towards zero (outward only on one side of the origin).
    pub fn frame_box(which: u32, origin: DVec3, min: DVec3, max: DVec3) -> Aabb {
        let (lo, hi) = (min - origin, max - origin);
        let down = |v: f64| floor32(v);
        let up = |v: f64| -floor32(-v);
        let each = |p: DVec3, f: &dyn Fn(f64) -> f32| Vec3::new(f(p.x), f(p.y), f(p.z));
        match which {
            0 => Aabb::new(each(lo, &down), each(hi, &up)),
            1 => Aabb::new(lo.as_vec3(), hi.as_vec3()),
            2 => Aabb::new(
                min.as_vec3() - origin.as_vec3(),
                max.as_vec3() - origin.as_vec3(),
            ),
            3 => Aabb::new(
                each(lo, &|v| (v as f32).next_down()),
                each(hi, &|v| (v as f32).next_up()),
            ),
            4 => Aabb::new(each(lo, &down), each(hi, &down)),
            _ => {
                let toward_zero = |v: f64| if v >= 0.0 { down(v) } else { up(v) };
                Aabb::new(each(lo, &toward_zero), each(hi, &toward_zero))
            }
        }
    }
}
