//! The cost model `T = Nv*Cv + Np*Cp + Nu*Cu + Co`, calibrated on this machine.
//!
//! Each unit cost is timed in isolation on samples from the scene itself:
//! `Cv` on node pairs of the two trees, `Cu` on moving B's node volumes into
//! A's frame, `Cp` on primitive pairs the traversal really visits (a box
//! filter on every pair, placing B's primitive and deciding exactly only where
//! the boxes overlap), and `Co` on a query whose
//! root volumes miss. Then every descent rule is run with counters, and the
//! predicted time is set against the measured one. What the model leaves out
//! (stack pushes, the rule's decisions, cache misses) shows up as the error.

use crate::{median_time, OwnedBvh};
use bvhkit::{
    Aabb, BoundingVolume, Bvh, CostModel, Counts, Exact, PairTraversal, Pairs, Place, Primitive,
    Rigid, TopDown, Triangle,
};
use serde::Serialize;
use std::hint::black_box;

/// One query configuration measured against the model.
#[derive(Clone, Debug, Serialize)]
pub struct CostRow {
    /// Bounding volume.
    pub volume: String,
    /// Traversal kind.
    pub traversal: String,
    /// Descent rule (empty for traversals that fix their own).
    pub descent: String,
    /// `Nv`.
    pub bv_tests: u64,
    /// `Np`.
    pub prim_tests: u64,
    /// `Nu`.
    pub updates: u64,
    /// Exact contacts found.
    pub intersecting_pairs: usize,
    /// Median measured time.
    pub measured_ms: f64,
    /// The model's prediction.
    pub predicted_ms: f64,
    /// `(predicted - measured) / measured`.
    pub error: f64,
}

/// The calibrated model of one volume type, in nanoseconds.
#[derive(Clone, Debug, Serialize)]
pub struct Calibration {
    /// Bounding volume.
    pub volume: String,
    /// ns per volume test.
    pub cv_ns: f64,
    /// ns per primitive test.
    pub cp_ns: f64,
    /// ns per volume update.
    pub cu_ns: f64,
    /// ns of fixed cost per query.
    pub co_ns: f64,
}

impl Calibration {
    /// As the core's [`CostModel`] (nanoseconds).
    pub fn model(&self) -> CostModel {
        CostModel {
            cv: self.cv_ns,
            cp: self.cp_ns,
            cu: self.cu_ns,
            co: self.co_ns,
        }
    }
}

/// Nanoseconds per call of `f`, the median of five timed batches of `n` calls.
fn per_call(n: usize, mut f: impl FnMut(usize)) -> f64 {
    let (t, _) = median_time(5, || {
        for i in 0..n {
            f(i)
        }
    });
    t.as_secs_f64() * 1e9 / n as f64
}

/// Times the unit costs for volume type `B` on trees `ta`, `tb` (B moved by `motion`).
pub fn calibrate<B: BoundingVolume>(
    ta: &Bvh<B>,
    a: &[Triangle],
    tb: &Bvh<B>,
    b: &[Triangle],
    motion: Rigid,
) -> Result<Calibration, bvhkit::Error> {
    let (na, nb) = (ta.nodes(), tb.nodes());
    const K: usize = 1 << 14;
    // Walk the node arrays in order, as a traversal mostly does (children
    // are stored next to each other).
    let pick = |len: usize, i: usize| i % len;
    let moved: Vec<B> = (0..K)
        .map(|i| nb[pick(nb.len(), i)].bv.transformed(&motion))
        .collect();
    let cv = per_call(K * 8, |i| {
        let x = &na[pick(na.len(), i / 8 + i % 8)].bv;
        black_box(x.overlaps(black_box(&moved[i % K])));
    });
    let cu = per_call(K, |i| {
        black_box(black_box(&nb[pick(nb.len(), i)].bv).transformed(&motion));
    });
    // Primitive pairs the traversal really reaches (`Np`). The leaf kernel
    // tests each pair's boxes first (four of A's at once, each primitive of
    // B placed once per four) and decides exactly only the pairs whose boxes
    // overlap, so `Cp` is the per-pair box filter plus that fraction of the
    // exact test.
    let mut visited = Vec::with_capacity(1 << 16);
    let mut overlapping = 0u64;
    let mut counts = Counts::default();
    Pairs::new(ta, a, tb, b)
        .in_frame(motion)
        .counted(&mut counts)
        .answer(|p: &Triangle, q: &Triangle| {
            overlapping += 1;
            if visited.len() < (1 << 16) {
                visited.push((*p, *q));
            }
            false
        })
        .count()?;
    let cp = if visited.is_empty() || counts.prim_tests == 0 {
        0.0
    } else {
        let n = visited.len();
        let mut exact = Exact;
        let exact_ns = per_call(n * 4, |i| {
            let (p, q) = &visited[i % n];
            let placed = Place::place(&motion, black_box(q));
            black_box(bvhkit::Answer::accept(&mut exact, p, &placed));
        });
        let place_ns = per_call(n * 4, |i| {
            black_box(Place::place(&motion, black_box(&visited[i % n].1)).bounds());
        });
        let boxes: Vec<(Aabb, Aabb)> = visited
            .iter()
            .map(|(p, q)| (p.bounds(), q.bounds()))
            .collect();
        let box_ns = per_call(n * 4, |i| {
            let (x, y) = &boxes[(i * 7) % n];
            let (_, z) = &boxes[i % n];
            black_box(black_box(x).overlaps(black_box(y)) | x.overlaps(z));
        }) / 2.0;
        let fraction = overlapping as f64 / counts.prim_tests as f64;
        box_ns + place_ns / 4.0 + fraction * exact_ns
    };
    // Fixed cost: B moved far away, so only the roots are tested.
    let extent = |t: &Bvh<B>| {
        t.root()
            .map_or(0.0, |r| r.bv.aabb().max.abs().max_element())
    };
    let away = Rigid::translation(bvhkit::glam::Vec3::splat(4.0 * (extent(ta) + extent(tb))))?
        .after(&motion);
    let whole = per_call(20_000, |_| {
        black_box(Pairs::new(ta, a, tb, b).in_frame(away).exact().count().ok());
    });
    let co = (whole - cv - cu).max(0.0);
    Ok(Calibration {
        volume: B::NAME.to_string(),
        cv_ns: cv,
        cp_ns: cp,
        cu_ns: cu,
        co_ns: co,
    })
}

/// Runs every descent rule (stack traversal) and the other traversal kinds
/// with counters; returns one row per configuration with measured and
/// predicted time.
pub fn rule_table<B: BoundingVolume>(
    ta: &Bvh<B>,
    a: &[Triangle],
    tb: &Bvh<B>,
    b: &[Triangle],
    motion: Rigid,
    model: &CostModel,
    runs: usize,
) -> Result<Vec<CostRow>, bvhkit::Error> {
    let mut rows = Vec::new();
    for traversal in crate::cost_fit::traversals() {
        let q = || {
            Pairs::new(ta, a, tb, b)
                .traversal(traversal)
                .in_frame(motion)
                .exact()
        };
        let mut counts = Counts::default();
        let found = q().counted(&mut counts).count()?;
        let (t, n) = median_time(runs, || q().count());
        n?;
        let measured = t.as_secs_f64() * 1e3;
        let predicted = model.predict(&counts) * 1e-6;
        let descent = match traversal {
            PairTraversal::Stack(d) | PairTraversal::Recursive(d) => d.name().to_string(),
            _ => String::new(),
        };
        rows.push(CostRow {
            volume: B::NAME.to_string(),
            traversal: traversal.name().to_string(),
            descent,
            bv_tests: counts.bv_tests,
            prim_tests: counts.prim_tests,
            updates: counts.updates,
            intersecting_pairs: found,
            measured_ms: measured,
            predicted_ms: predicted,
            error: (predicted - measured) / measured,
        });
    }
    Ok(rows)
}

/// Calibration and rule table for one volume type on a mesh and its moved copy.
pub fn report_for<B: BoundingVolume>(
    mesh: &[Triangle],
    motion: Rigid,
    runs: usize,
) -> Result<(Calibration, Vec<CostRow>), bvhkit::Error> {
    let tree = OwnedBvh::<B>::build(&TopDown::sah(), mesh)?;
    let t = tree.view();
    let cal = calibrate(&t, mesh, &t, mesh, motion)?;
    let rows = rule_table(&t, mesh, &t, mesh, motion, &cal.model(), runs)?;
    Ok((cal, rows))
}

/// Spearman rank correlation of predicted and measured time over `rows`
/// (1 = the model orders the configurations exactly as measured).
pub fn rank_agreement(rows: &[&CostRow]) -> f64 {
    let rank = |key: &dyn Fn(&CostRow) -> f64| {
        let mut order: Vec<usize> = (0..rows.len()).collect();
        order.sort_by(|&i, &j| key(rows[i]).total_cmp(&key(rows[j])));
        let mut r = vec![0.0; rows.len()];
        for (pos, &i) in order.iter().enumerate() {
            r[i] = pos as f64;
        }
        r
    };
    let (p, m) = (rank(&|r| r.predicted_ms), rank(&|r| r.measured_ms));
    let n = rows.len() as f64;
    if n < 2.0 {
        return 1.0;
    }
    let d2: f64 = p.iter().zip(&m).map(|(a, b)| (a - b) * (a - b)).sum();
    1.0 - 6.0 * d2 / (n * (n * n - 1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(predicted_ms: f64, measured_ms: f64) -> CostRow {
        CostRow {
            volume: String::new(),
            traversal: String::new(),
            descent: String::new(),
            bv_tests: 0,
            prim_tests: 0,
            updates: 0,
            intersecting_pairs: 0,
            measured_ms,
            predicted_ms,
            error: 0.0,
        }
    }

    #[test]
    fn rank_agreement_is_one_for_the_same_order_and_minus_one_reversed() {
        let same = [row(1.0, 10.0), row(2.0, 20.0), row(3.0, 25.0)];
        let reversed = [row(1.0, 30.0), row(2.0, 20.0), row(3.0, 10.0)];
        assert_eq!(rank_agreement(&same.iter().collect::<Vec<_>>()), 1.0);
        assert_eq!(rank_agreement(&reversed.iter().collect::<Vec<_>>()), -1.0);
    }
}
