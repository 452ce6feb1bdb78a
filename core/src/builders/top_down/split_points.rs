//! Split points (Ericson 6.2.4): where candidate planes go along a direction
//! (bins, the spatial median, the object mean or median, random centroids,
//! the exact sweep), and the general evaluator that scores them under any
//! criterion.

use super::axes::directions;
use super::binned::plan_binned;
use super::criteria::{cost, Norm};
use super::partition::bounds_of;
use super::source::{centroid, Source};
use super::Task;
use crate::builders::strategy::{AxisChoice, Partition, SplitPoint, MAX_BINS};
use crate::bv::{Aabb, BoundingVolume};
use glam::Vec3;

/// How primitives are assigned to bins along one direction.
#[derive(Clone, Copy, Debug)]
pub(super) enum Binning {
    /// `k` equal bins over `[lo, lo + k / scale]`.
    Even { lo: f32, scale: f32, k: usize },
    /// Bin `i` holds `planes[i-1] <= t < planes[i]`; `m` planes, `m + 1` bins.
    Planes { planes: [f32; MAX_BINS], m: usize },
}

impl Binning {
    #[inline]
    pub(super) fn bins(&self) -> usize {
        match *self {
            Binning::Even { k, .. } => k,
            Binning::Planes { m, .. } => m + 1,
        }
    }
    #[inline]
    pub(super) fn bin(&self, t: f32) -> usize {
        match *self {
            Binning::Even { lo, scale, k } => even_bin(t, lo, scale, k),
            Binning::Planes { ref planes, m } => planes[..m].partition_point(|&p| p <= t),
        }
    }
}

/// The bin of `t` among `k` (at most 64) bins from `lo`, `scale` bins per
/// unit: `(t - lo) * scale` clamped to `[0, k - 1]`, then [`bin_of`].
#[inline(always)]
pub(super) fn even_bin(t: f32, lo: f32, scale: f32, k: usize) -> usize {
    bin_of(((t - lo) * scale).max(0.0).min((k - 1) as f32))
}

/// The whole part of `x` in `[0, 63]`, read from the bits of `x + 64`: the
/// sum's exponent is fixed, so its top six mantissa bits are the bin. A
/// float-to-integer conversion costs a saturation check per value, and the
/// binning loop makes three per primitive. The sum rounds, so an `x` within
/// 2^-18 below a whole number lands in the bin above; every binning and
/// partition goes through this one rule (or [`goes_left`], its comparison
/// form), so bins and partitions agree on every primitive.
#[inline(always)]
pub(super) fn bin_of(x: f32) -> usize {
    bin_of_sum(x + 64.0)
}

/// [`bin_of`] given the sum `x + 64` (which the binning loop forms for three
/// lanes at once).
#[inline(always)]
pub(super) fn bin_of_sum(sum: f32) -> usize {
    const _: () = assert!(MAX_BINS <= 64, "bin_of reads six bits");
    (sum.to_bits() >> 17) as usize & 63
}

/// `even_bin(t, lo, scale, k) < boundary` for `1 <= boundary < k`, without
/// the clamp: the sum rounds monotonically, and `64 + boundary` is whole,
/// so the comparison of the unclamped sum gives the same answer on either
/// side of the clamp.
#[inline(always)]
pub(super) fn goes_left(t: f32, lo: f32, scale: f32, boundary: usize) -> bool {
    (t - lo) * scale + 64.0 < 64.0 + boundary as f32
}

#[derive(Clone, Copy, Debug)]
pub(super) struct Bin {
    pub(super) bounds: Aabb,
    pub(super) count: u32,
}

pub(super) const EMPTY_BIN: Bin = Bin {
    bounds: Aabb::EMPTY,
    count: 0,
};

/// A chosen split, before the range is partitioned.
#[derive(Clone, Copy, Debug)]
pub(super) enum Plan {
    /// Left iff `binning.bin(dir . c) < boundary`.
    Plane {
        dir: Vec3,
        binning: Binning,
        boundary: usize,
    },
    /// Left iff `bin(c[axis]) < boundary` with even bins (the fast path).
    Axis {
        axis: usize,
        lo: f32,
        scale: f32,
        k: usize,
        boundary: usize,
        /// The left count and both children's boxes, when the bins gave them.
        known: Option<(usize, [Aabb; 2])>,
    },
    /// The `mid` primitives with the smallest `dir . c` go left.
    Order { dir: Vec3, mid: usize },
}

/// Scores candidate splits and returns the best plan (without moving anything
/// except for median/sweep evaluation, which reorder the range).
#[allow(clippy::too_many_arguments)]
pub(super) fn plan<S: Source, B: BoundingVolume>(
    src: &S,
    range: &mut [S::Item],
    scratch: &mut [u32],
    task: &Task,
    bv: &B,
    axis: AxisChoice,
    split: SplitPoint,
    partition: Partition,
    norm: &Norm,
) -> Option<Plan> {
    if let (
        SplitPoint::Bins(k),
        AxisChoice::BestOfXyz | AxisChoice::Longest,
        Partition::SurfaceArea,
    ) = (split, axis, partition)
    {
        let mut axes = [true; 3];
        if axis == AxisChoice::Longest {
            let l = task.centroids.longest_axis();
            axes = [l == 0, l == 1, l == 2];
        }
        // More bins than primitives cannot help; a bin array sized to the node
        // keeps the fixed cost of the many small nodes near the leaves low.
        let k = (k as usize).min(range.len().max(2));
        return plan_binned(src, range, task, k, axes, norm);
    }
    #[cfg(feature = "strategies")]
    return plan_by_directions(src, range, scratch, task, bv, axis, split, partition, norm);
    // `check` refused every other configuration.
    #[cfg(not(feature = "strategies"))]
    {
        let _ = (scratch, bv);
        None
    }
}

/// Every other combination: candidate directions, each scored by its split
/// point. Kept out of [`plan`] so its frame is not on the stack of the fast path.
#[inline(never)]
#[allow(clippy::too_many_arguments)]
pub(super) fn plan_by_directions<S: Source, B: BoundingVolume>(
    src: &S,
    range: &mut [S::Item],
    scratch: &mut [u32],
    task: &Task,
    bv: &B,
    axis: AxisChoice,
    split: SplitPoint,
    partition: Partition,
    norm: &Norm,
) -> Option<Plan> {
    let dirs = directions(src, range, task, bv, axis);
    let mut best: Option<(f32, Plan)> = None;
    let mut consider = |c: f32, p: Plan| {
        if best.is_none_or(|(b, _)| c < b) {
            best = Some((c, p));
        }
    };
    for &dir in dirs.as_slice() {
        let t = |i: S::Item| dir.dot(centroid(src, i));
        let (lo, hi) = projection_range(range, &t, dir, &task.centroids);
        if hi.partial_cmp(&lo) != Some(core::cmp::Ordering::Greater) {
            continue; // every centroid projects to one point: nothing to split
        }
        match split {
            SplitPoint::ObjectMedian => {
                let mid = range.len() / 2;
                range.select_nth_unstable_by(mid, |&a, &b| {
                    t(a).total_cmp(&t(b)).then(src.id(a).cmp(&src.id(b)))
                });
                let (l, _) = bounds_of(src, &range[..mid]);
                let (r, _) = bounds_of(src, &range[mid..]);
                let c = cost::<B>(
                    partition,
                    norm,
                    &task.bounds,
                    &l,
                    mid as u32,
                    &r,
                    (range.len() - mid) as u32,
                );
                consider(c, Plan::Order { dir, mid });
            }
            SplitPoint::Sweep => {
                if let Some((c, mid)) = sweep_sah(src, range, scratch, &t, norm) {
                    consider(c, Plan::Order { dir, mid });
                }
            }
            _ => {
                let binning = match split {
                    SplitPoint::Bins(k) => Binning::Even {
                        lo,
                        scale: k as f32 / (hi - lo),
                        k: k as usize,
                    },
                    SplitPoint::SpatialMedian => planes(&[lo * 0.5 + hi * 0.5]),
                    SplitPoint::ObjectMean => {
                        let mean =
                            range.iter().map(|&i| t(i) as f64).sum::<f64>() / range.len() as f64;
                        planes(&[mean as f32])
                    }
                    SplitPoint::RandomCentroids { count, seed } => {
                        // Seeded by what the node holds (its centroids' box and
                        // count), not by its number: a forked build numbers
                        // nodes differently and must draw the same candidates.
                        let c = &task.centroids;
                        let key = [c.min, c.max]
                            .iter()
                            .flat_map(|v| v.to_array())
                            .fold(range.len() as u64, |h, x| {
                                (h ^ u64::from(x.to_bits())).wrapping_mul(0x9E37_79B9_7F4A_7C15)
                            });
                        let mut rng = SplitMix(seed ^ key);
                        let mut p = [0.0f32; MAX_BINS];
                        let m = (count as usize).min(MAX_BINS);
                        for slot in p.iter_mut().take(m) {
                            *slot = t(range[(rng.next() % range.len() as u64) as usize]);
                        }
                        planes(&p[..m])
                    }
                    // Handled by the arms above.
                    SplitPoint::ObjectMedian | SplitPoint::Sweep => continue,
                };
                if let Some((c, boundary)) =
                    evaluate_bins::<S, B>(src, range, &t, &binning, partition, norm, task)
                {
                    consider(
                        c,
                        Plan::Plane {
                            dir,
                            binning,
                            boundary,
                        },
                    );
                }
            }
        }
    }
    best.map(|(_, p)| p)
}

pub(super) fn planes(values: &[f32]) -> Binning {
    let mut p = [0.0f32; MAX_BINS];
    let m = values.len().min(MAX_BINS - 1);
    p[..m].copy_from_slice(&values[..m]);
    p[..m].sort_unstable_by(f32::total_cmp);
    // Remove duplicates so no bin is empty by construction.
    let mut k = 0;
    for i in 0..m {
        if k == 0 || p[i] != p[k - 1] {
            p[k] = p[i];
            k += 1;
        }
    }
    Binning::Planes { planes: p, m: k }
}

pub(super) fn projection_range<T: Copy>(
    range: &[T],
    t: &impl Fn(T) -> f32,
    dir: Vec3,
    centroids: &Aabb,
) -> (f32, f32) {
    for k in 0..3 {
        if dir == crate::bv::Axes::XYZ.axes[k] {
            return (centroids.min[k], centroids.max[k]);
        }
    }
    let mut lo = f32::INFINITY;
    let mut hi = f32::NEG_INFINITY;
    for &i in range {
        let v = t(i);
        lo = lo.min(v);
        hi = hi.max(v);
    }
    (lo, hi)
}

/// Bins the range and scores every boundary; returns (cost, boundary).
pub(super) fn evaluate_bins<S: Source, B: BoundingVolume>(
    src: &S,
    range: &[S::Item],
    t: &impl Fn(S::Item) -> f32,
    binning: &Binning,
    partition: Partition,
    norm: &Norm,
    task: &Task,
) -> Option<(f32, usize)> {
    let k = binning.bins();
    let mut bins = [EMPTY_BIN; MAX_BINS];
    for &i in range {
        let b = &mut bins[binning.bin(t(i))];
        b.bounds = b.bounds.union(&src.bounds(i));
        b.count += 1;
    }
    let mut right = [EMPTY_BIN; MAX_BINS];
    let mut acc = EMPTY_BIN;
    for j in (1..k).rev() {
        acc.bounds = acc.bounds.union(&bins[j].bounds);
        acc.count += bins[j].count;
        right[j] = acc;
    }
    let mut left = EMPTY_BIN;
    let mut best: Option<(f32, usize)> = None;
    for j in 1..k {
        left.bounds = left.bounds.union(&bins[j - 1].bounds);
        left.count += bins[j - 1].count;
        if left.count == 0 || right[j].count == 0 {
            continue;
        }
        let c = cost::<B>(
            partition,
            norm,
            &task.bounds,
            &left.bounds,
            left.count,
            &right[j].bounds,
            right[j].count,
        );
        if best.is_none_or(|(b, _)| c < b) {
            best = Some((c, j));
        }
    }
    best
}

/// Exact SAH sweep along one direction; `scratch` holds right-side costs as f32 bits.
pub(super) fn sweep_sah<S: Source>(
    src: &S,
    range: &mut [S::Item],
    scratch: &mut [u32],
    t: &impl Fn(S::Item) -> f32,
    norm: &Norm,
) -> Option<(f32, usize)> {
    let n = range.len();
    if scratch.len() < n {
        return None;
    }
    range.sort_unstable_by(|&a, &b| t(a).total_cmp(&t(b)).then(src.id(a).cmp(&src.id(b))));
    let mut acc = Aabb::EMPTY;
    for j in (1..n).rev() {
        acc = acc.union(&src.bounds(range[j]));
        scratch[j] = (norm.half_area(&acc) * (n - j) as f32).to_bits();
    }
    let mut left = Aabb::EMPTY;
    let mut best: Option<(f32, usize)> = None;
    for j in 1..n {
        left = left.union(&src.bounds(range[j - 1]));
        let c = norm.half_area(&left) * j as f32 + f32::from_bits(scratch[j]);
        if best.is_none_or(|(b, _)| c < b) {
            best = Some((c, j));
        }
    }
    best
}

/// SplitMix64: a tiny seeded generator for reproducible random candidates.
#[derive(Clone, Copy, Debug)]
pub(super) struct SplitMix(u64);

impl SplitMix {
    pub(super) fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
}

#[cfg(test)]
mod tests {
    use super::{bin_of, even_bin, goes_left};

    /// `bin_of` is the whole part for whole numbers and halves, and a value
    /// within 2^-18 below a whole number rounds up into the next bin (the
    /// documented rounding), never past 63.
    #[test]
    fn bin_of_reads_the_whole_part() {
        for j in 0..64u32 {
            let x = j as f32;
            assert_eq!(bin_of(x), j as usize);
            if j < 63 {
                assert_eq!(bin_of(x + 0.5), j as usize);
                assert_eq!(bin_of(x + 1.0 - 1.0 / 1024.0), j as usize);
            }
            if j > 0 {
                // The largest float below j rounds up when added to 64.
                let below = f32::from_bits(x.to_bits() - 1);
                assert_eq!(bin_of(below), j as usize, "{below}");
            }
        }
        assert_eq!(bin_of(0.0), 0);
        assert_eq!(bin_of(-0.0), 0);
        assert_eq!(bin_of(1e-30), 0);
    }

    /// Every value gets a bin in `[0, k)`, bins never decrease along the
    /// axis, and the partition's comparison sends a value left exactly when
    /// its bin is below the boundary: on random values, on every plane and
    /// the floats next to it, and far outside the extent.
    #[test]
    fn bins_and_the_partition_agree_near_every_plane() {
        let mut next = crate::test_floats(0x5eed_b145);
        let mut checked = 0;
        for case in 0..200 {
            let k = [2usize, 3, 8, 16, 31, 32][case % 6];
            let lo = next() * [1.0, 1e3, 1e6, 3e-5][case % 4];
            let extent = (next().abs() + 1e-3) * [1.0, 1e4, 1e-3][case % 3];
            let scale = k as f32 / extent;
            let mut values = [0.0f32; 200];
            for (i, v) in values.iter_mut().enumerate() {
                *v = match i % 5 {
                    // On a plane, and one or two floats either side of it.
                    0..=2 => {
                        let plane = lo + (i % k) as f32 / scale;
                        let step = (i % 3) as u32;
                        if i % 2 == 0 {
                            f32::from_bits(plane.to_bits().wrapping_add(step))
                        } else {
                            f32::from_bits(plane.to_bits().wrapping_sub(step))
                        }
                    }
                    3 => lo + (next() * 0.5 + 0.5) * extent,
                    _ => lo + next() * 4.0 * extent, // outside too
                };
            }
            values.sort_by(f32::total_cmp);
            let mut last = 0;
            for &t in &values {
                let bin = even_bin(t, lo, scale, k);
                assert!(bin < k, "bin {bin} of {k} for {t}");
                assert!(bin >= last, "bins decrease at {t}");
                last = bin;
                for boundary in 1..k {
                    assert_eq!(
                        goes_left(t, lo, scale, boundary),
                        bin < boundary,
                        "t {t}, lo {lo}, scale {scale}, boundary {boundary} of {k}"
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 100_000, "{checked}");
    }
}
