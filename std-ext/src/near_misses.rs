//! Adversarial triangle pairs for the narrow phase: pairs that touch or miss
//! by about one rounding error, far from the origin, where the sign of an
//! orientation determinant computed in floating point can be wrong. Used to
//! measure what the exact predicates buy: time against disagreement rate for
//! the same triangle test reading `f32`, `f64` or exact signs.

use crate::median_time;
use crate::scene::Rng;
use bvhkit::glam::Vec3;
use bvhkit::narrow::{triangles_intersect_with, ExactSigns, F32Signs, F64Signs, Orientation};
use bvhkit::Triangle;
use serde::Serialize;

/// The kinds of near contact, cycled through by [`adversarial_pairs`].
pub const KINDS: [&str; 4] = [
    "vertex on a face",
    "edge across an edge",
    "nearly coplanar overlap",
    "shared edge, small dihedral angle",
];

/// `n` pairs of near-touching triangles (kinds in turn), placed up to
/// `offset` away from the origin so that coordinates carry few fraction bits.
///
/// ```
/// let pairs = bvhkit_std::near_misses::adversarial_pairs(100, 1.0e3, 7);
/// assert_eq!(pairs.len(), 100);
/// ```
pub fn adversarial_pairs(n: usize, offset: f32, seed: u64) -> Vec<(Triangle, Triangle)> {
    let mut r = Rng(seed);
    (0..n)
        .map(|i| {
            let o = r.vec() * offset;
            let t = Triangle::new(o + r.vec(), o + r.vec(), o + r.vec());
            let [a, b, c] = t.v;
            let n = (b - a).cross(c - a).normalize_or_zero();
            // A point of the first triangle, rounded to f32: on its plane up
            // to rounding, so the exact answer goes either way.
            let (u, v) = (r.next() * 0.5, r.next() * 0.5);
            let p = a + (b - a) * u + (c - a) * v;
            let side = r.vec();
            let other = match i % 4 {
                0 => Triangle::new(p, p + n + side * 0.3, p + n * 0.7 - side * 0.3),
                1 => {
                    // Through a point of edge ab, crossing the plane.
                    let e = a + (b - a) * r.next();
                    Triangle::new(e + n, e - n + side * 0.2, e + side)
                }
                2 => {
                    let q = p + r.vec();
                    let mut lift = |x: Vec3| x + n * (r.next() - 0.5) * 1.0e-6 * (1.0 + offset);
                    Triangle::new(lift(p), lift(p + side), lift(q))
                }
                _ => Triangle::new(a, b, c + n * 1.0e-4 + side * 1.0e-3),
            };
            (t, other)
        })
        .collect()
}

/// One way of computing the signs, on one set of pairs.
#[derive(Clone, Debug, Serialize)]
pub struct NarrowRow {
    /// `exact`, `f64` or `f32`.
    pub signs: &'static str,
    /// The pair set: `adversarial` or `random` (well separated or deeply
    /// intersecting, where rounding cannot matter).
    pub pairs: &'static str,
    /// Median time of one triangle test, in nanoseconds.
    pub ns_per_test: f64,
    /// Fraction of pairs answered differently from the exact test.
    pub disagreement: f64,
    /// Pairs tested.
    pub tested: usize,
}

fn measure_one<O: Orientation>(
    signs: &'static str,
    set: &'static str,
    pairs: &[(Triangle, Triangle)],
    truth: &[bool],
    o: O,
    runs: usize,
) -> NarrowRow {
    let (t, answers) = median_time(runs, || {
        pairs
            .iter()
            .map(|(x, y)| triangles_intersect_with(x, y, o))
            .collect::<Vec<bool>>()
    });
    let wrong = answers.iter().zip(truth).filter(|(a, b)| a != b).count();
    NarrowRow {
        signs,
        pairs: set,
        ns_per_test: t.as_secs_f64() * 1e9 / pairs.len().max(1) as f64,
        disagreement: wrong as f64 / pairs.len().max(1) as f64,
        tested: pairs.len(),
    }
}

/// Times the triangle test with exact, `f64` and `f32` signs on `n`
/// adversarial pairs and on `n` random pairs, and counts disagreements with
/// the exact answers.
pub fn measure(n: usize, runs: usize) -> Vec<NarrowRow> {
    let adversarial = adversarial_pairs(n, 1.0e3, 0xad5e);
    let mut r = Rng(0x7a2d);
    let random: Vec<(Triangle, Triangle)> = (0..n)
        .map(|_| {
            let o = r.vec() * 2.0;
            let t = |r: &mut Rng| Triangle::new(o + r.vec(), o + r.vec(), o + r.vec());
            (t(&mut r), t(&mut r))
        })
        .collect();
    let mut rows = Vec::new();
    for (set, pairs) in [("adversarial", &adversarial), ("random", &random)] {
        let truth: Vec<bool> = pairs
            .iter()
            .map(|(x, y)| triangles_intersect_with(x, y, ExactSigns))
            .collect();
        rows.push(measure_one("exact", set, pairs, &truth, ExactSigns, runs));
        rows.push(measure_one("f64", set, pairs, &truth, F64Signs, runs));
        rows.push(measure_one("f32", set, pairs, &truth, F32Signs, runs));
    }
    rows
}

/// The rows as a markdown table.
pub fn render(rows: &[NarrowRow]) -> String {
    let mut md = String::from(
        "| pairs | signs | ns per test | disagreement with exact |\n|---|---|---:|---:|\n",
    );
    for r in rows {
        md += &format!(
            "| {} | {} | {:.1} | {:.2}% ({} of {}) |\n",
            r.pairs,
            r.signs,
            r.ns_per_test,
            r.disagreement * 100.0,
            (r.disagreement * r.tested as f64).round() as usize,
            r.tested
        );
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The adversarial set is adversarial: `f32` signs get some of it wrong,
    /// exact signs none; on random pairs the float signs are right.
    #[test]
    fn float_signs_disagree_on_adversarial_pairs_only() {
        let rows = measure(4000, 1);
        let get = |set: &str, signs: &str| {
            rows.iter()
                .find(|r| r.pairs == set && r.signs == signs)
                .unwrap()
                .disagreement
        };
        assert_eq!(get("adversarial", "exact"), 0.0);
        assert!(get("adversarial", "f32") > 0.0, "{rows:?}");
        assert!(get("adversarial", "f32") >= get("adversarial", "f64"));
        assert_eq!(get("random", "f32"), 0.0, "{rows:?}");
    }
}
