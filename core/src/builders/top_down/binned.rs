//! The default's fast path: binned SAH over x, y and z in one pass over the
//! primitives, with bins kept in 4-lane registers.

use super::criteria::Norm;
use super::source::Source;
use super::split_points::{bin_of, bin_of_sum, Plan};
use super::Task;
use crate::builders::strategy::MAX_BINS;
use crate::bv::Aabb;
use glam::{Vec3, Vec3A};

/// A bin's bounds in 4-lane registers (the fourth lane is unused).
#[derive(Clone, Copy, Debug)]
pub(super) struct LaneBin {
    pub(super) min: Vec3A,
    pub(super) max: Vec3A,
}

impl LaneBin {
    pub(super) const EMPTY: LaneBin = LaneBin {
        min: Vec3A::splat(f32::INFINITY),
        max: Vec3A::splat(f32::NEG_INFINITY),
    };

    /// `Aabb::union`'s operand order, lane by lane.
    #[inline(always)]
    pub(super) fn union(&self, other: &LaneBin) -> LaneBin {
        LaneBin {
            min: other.min.min(self.min),
            max: other.max.max(self.max),
        }
    }
    #[inline(always)]
    pub(super) fn aabb(&self) -> Aabb {
        Aabb::new(self.min.into(), self.max.into())
    }
}

/// The fast path: binned SAH with `k` bins along the axes in `axes`. Bin
/// arrays come in four sizes (4, 8, 16, [`MAX_BINS`]), the smallest that
/// holds `k`, each in its own out-of-line function, so that only the array
/// in use is on the stack. All three axes are binned in one pass or one
/// axis at a time ([`ONE_PASS`]).
#[inline(always)]
pub(super) fn plan_binned<S: Source>(
    src: &S,
    range: &[S::Item],
    task: &Task,
    k: usize,
    axes: [bool; 3],
    norm: &Norm,
) -> Option<Plan> {
    macro_rules! sized {
        ($f:ident) => {
            match k {
                0..=4 => $f::<S, 4>(src, range, task, k, axes, norm),
                5..=8 => $f::<S, 8>(src, range, task, k, axes, norm),
                9..=16 => $f::<S, 16>(src, range, task, k, axes, norm),
                _ => $f::<S, MAX_BINS>(src, range, task, k, axes, norm),
            }
        };
    }
    if axes != [true; 3] {
        plan_one_axis(src, range, task, k, axes, norm)
    } else if ONE_PASS {
        sized!(plan_three_axes)
    } else {
        plan_axis_by_axis(src, range, task, k, norm)
    }
}

/// Bins per unit of length along each axis: `k` bins over the centroids'
/// extent, 0 where the axis is off or the extent is 0 (nothing to split).
#[inline(always)]
fn bin_scales(c: &Aabb, k: usize, axes: [bool; 3]) -> [f32; 3] {
    let ext = c.extent();
    core::array::from_fn(|a| {
        if ext[a] > 0.0 && axes[a] {
            k as f32 / ext[a]
        } else {
            0.0
        }
    })
}

/// One axis only ([`AxisChoice::Longest`](crate::AxisChoice::Longest)):
/// bins along it; the partition then measures both halves. Generic over
/// the source only; the row of bins comes from [`score_axis`].
#[inline(never)]
fn plan_one_axis<S: Source>(
    src: &S,
    range: &[S::Item],
    task: &Task,
    k: usize,
    axes: [bool; 3],
    norm: &Norm,
) -> Option<Plan> {
    let k = k.min(MAX_BINS);
    let c = &task.centroids;
    let scale = bin_scales(c, k, axes);
    let a = axes.iter().position(|&x| x)?;
    if scale[a] == 0.0 {
        return None;
    }
    let axis = Axis {
        a,
        lo: c.min[a],
        scale: scale[a],
    };
    // The one-axis-at-a-time scorer; its halves and count are not used:
    // the partition measures both halves itself on this path.
    let (_, boundary, _, _) = score_sized(src, range, axis, k, norm)?;
    Some(Plan::Axis {
        axis: a,
        lo: axis.lo,
        scale: axis.scale,
        k,
        boundary,
        known: None,
    })
}

/// One pass bins every primitive along x, y and z at once.
#[inline(never)]
fn plan_three_axes<S: Source, const N: usize>(
    src: &S,
    range: &[S::Item],
    task: &Task,
    k: usize,
    axes: [bool; 3],
    norm: &Norm,
) -> Option<Plan> {
    let k = k.min(N);
    let c = &task.centroids;
    let scale = bin_scales(c, k, axes);
    // Bin bounds in 4-lane registers: a union is two instructions, and the
    // three bin indices come from one subtract and multiply. Each lane does
    // the scalar path's arithmetic (`Aabb::center`, `bin_of`, `Aabb::union`
    // with the same operand order), so the bins, and the tree, are the same
    // as one axis at a time would give.
    let mut lanes = [[LaneBin::EMPTY; N]; 3];
    let mut counts = [[0u32; N]; 3];
    let (lo_c, sc) = (Vec3A::from(c.min), Vec3A::from(Vec3::from(scale)));
    let top = k.clamp(1, N) - 1; // the last bin, < N
    let top_f = Vec3A::splat(top as f32);
    for &i in range {
        let (lo, hi) = src.lanes(i);
        let t = ((lo * 0.5 + hi * 0.5) - lo_c) * sc;
        // `bin_of`, lane by lane: the clamp and the sum in registers.
        let t: [f32; 3] = (t.max(Vec3A::ZERO).min(top_f) + Vec3A::splat(64.0)).into();
        for a in 0..3 {
            // `& (N - 1)`: the bin is at most `top < N` already (N is a
            // power of two); the mask lets the compiler drop the bounds check.
            let j = bin_of_sum(t[a]) & (N - 1);
            let bin = &mut lanes[a][j];
            bin.min = lo.min(bin.min);
            bin.max = hi.max(bin.max);
            counts[a][j] += 1;
        }
    }
    let enabled = [scale[0] != 0.0, scale[1] != 0.0, scale[2] != 0.0];
    let k = k.min(N);
    let best = best_of_rows(
        [&lanes[0][..k], &lanes[1][..k], &lanes[2][..k]],
        [&counts[0][..k], &counts[1][..k], &counts[2][..k]],
        enabled,
        norm,
    );
    let (_, a, boundary) = best?;
    // The children's boxes are the unions of their bins, exactly the boxes
    // of the primitives the partition will put on each side.
    let (mut halves, mut mid) = ([LaneBin::EMPTY; 2], 0u32);
    for j in 0..k {
        let side = usize::from(j >= boundary);
        halves[side] = halves[side].union(&lanes[a][j]);
        mid += if side == 0 { counts[a][j] } else { 0 };
    }
    Some(Plan::Axis {
        axis: a,
        lo: c.min[a],
        scale: scale[a],
        k,
        boundary,
        known: Some((mid as usize, [halves[0].aabb(), halves[1].aabb()])),
    })
}

/// Whether the fast path bins x, y and z in one pass (three rows of bins on
/// the stack, 1.7 KiB at 16 bins) or one axis at a time (one row, a third of
/// the stack, three passes over the primitives). One pass where 4-lane
/// registers make it pay (x86, Arm64, WebAssembly); one axis at a time on
/// the rest, microcontrollers above all, where the stack is the budget and
/// a 4-lane value is four scalar operations anyway. Both give the same plan,
/// hence the same tree, bit for bit (a unit test compares them).
const ONE_PASS: bool = cfg!(any(
    target_arch = "x86_64",
    target_arch = "x86",
    target_arch = "aarch64",
    target_arch = "wasm32"
));

/// The fast path one axis at a time: bins one row, scores it, and keeps the
/// best boundary with its two halves' boxes, with the one-pass path's
/// arithmetic (bin index, unions, scores and the first-of-equal-costs rule
/// within and across axes), so the plan is the one that path makes.
/// Generic over the source only: one copy in a firmware.
#[inline(never)]
fn plan_axis_by_axis<S: Source>(
    src: &S,
    range: &[S::Item],
    task: &Task,
    k: usize,
    norm: &Norm,
) -> Option<Plan> {
    let c = &task.centroids;
    let k = k.min(MAX_BINS);
    let scale = bin_scales(c, k, [true; 3]);
    // (cost, axis, boundary, left count, halves)
    let mut pick: Option<(f32, usize, usize, u32, [LaneBin; 2])> = None;
    for (a, &sc) in scale.iter().enumerate() {
        if sc == 0.0 {
            continue;
        }
        let axis = Axis {
            a,
            lo: c.min[a],
            scale: sc,
        };
        let Some((cost, boundary, mid, halves)) = score_sized(src, range, axis, k, norm) else {
            continue;
        };
        if pick.is_none_or(|(b, ..)| cost < b) {
            pick = Some((cost, a, boundary, mid, halves));
        }
    }
    let (_, a, boundary, mid, halves) = pick?;
    Some(Plan::Axis {
        axis: a,
        lo: c.min[a],
        scale: scale[a],
        k,
        boundary,
        known: Some((mid as usize, [halves[0].aabb(), halves[1].aabb()])),
    })
}

/// One axis to bin along: its index, the bins' start and bins per unit.
#[derive(Clone, Copy)]
struct Axis {
    a: usize,
    lo: f32,
    scale: f32,
}

/// [`score_axis`] with the smallest row that holds `k` bins.
#[inline(always)]
fn score_sized<S: Source>(
    src: &S,
    range: &[S::Item],
    axis: Axis,
    k: usize,
    norm: &Norm,
) -> Option<(f32, usize, u32, [LaneBin; 2])> {
    match k {
        0..=4 => score_axis::<S, 4>(src, range, axis, k, norm),
        5..=8 => score_axis::<S, 8>(src, range, axis, k, norm),
        9..=16 => score_axis::<S, 16>(src, range, axis, k, norm),
        _ => score_axis::<S, MAX_BINS>(src, range, axis, k, norm),
    }
}

/// A row of `N` bins on the stack for [`score_row`]: out of line, one small
/// copy per size, so only the row in use is on the stack.
#[inline(never)]
fn score_axis<S: Source, const N: usize>(
    src: &S,
    range: &[S::Item],
    axis: Axis,
    k: usize,
    norm: &Norm,
) -> Option<(f32, usize, u32, [LaneBin; 2])> {
    let mut row = [LaneBin::EMPTY; N];
    let mut count = [0u32; N];
    let k = k.min(N);
    score_row(src, range, axis, &mut row[..k], &mut count[..k], norm)
}

/// Bins `range` along one axis into `row` (empty bins) and `count`
/// (zeros), with the one-pass path's bin index (`((lo + hi) / 2 - lo) *
/// scale`, clamped to `[0, k - 1]`, then truncated), and returns the best
/// boundary's cost, the boundary, the left count and the two halves.
#[inline(never)]
fn score_row<S: Source>(
    src: &S,
    range: &[S::Item],
    axis: Axis,
    row: &mut [LaneBin],
    count: &mut [u32],
    norm: &Norm,
) -> Option<(f32, usize, u32, [LaneBin; 2])> {
    let k = row.len().min(count.len());
    let top = k.checked_sub(1)?;
    let top_f = top as f32;
    let a = axis.a;
    for &i in range {
        let (lo, hi) = src.lanes(i);
        let t = ((lo[a] * 0.5 + hi[a] * 0.5) - axis.lo) * axis.scale;
        let j = bin_of(t.max(0.0).min(top_f));
        if let (Some(bin), Some(n)) = (row.get_mut(j), count.get_mut(j)) {
            bin.min = lo.min(bin.min);
            bin.max = hi.max(bin.max);
            *n += 1;
        }
    }
    let (row, count) = (&row[..k], &count[..k]);
    let (cost, _, boundary) = best_of_rows([row; 3], [count; 3], [true, false, false], norm)?;
    let (mut halves, mut mid) = ([LaneBin::EMPTY; 2], 0u32);
    for j in 0..k {
        let side = usize::from(j >= boundary);
        halves[side] = halves[side].union(&row[j]);
        mid += if side == 0 { count[j] } else { 0 };
    }
    Some((cost, boundary, mid, halves))
}

/// The SAH-best boundary over rows of bins (one row per axis tried; bin `j`
/// of row `a` holds `counts[a][j]` primitives, every row of the same length
/// and count), as (cost, row, boundary). Each row's non-empty bins are swept
/// once from the right (costs kept) and once from the left, scoring without
/// branches; the first of equal costs wins, within a row and across rows.
// Not generic and out of line: one copy in the firmware, and the frame of
// its cost array is not added to every caller's.
#[inline(never)]
fn best_of_rows(
    lanes: [&[LaneBin]; 3],
    counts: [&[u32]; 3],
    enabled: [bool; 3],
    norm: &Norm,
) -> Option<(f32, usize, usize)> {
    let mut pick: Option<(f32, usize, usize)> = None;
    let mut right = [0.0f32; MAX_BINS];
    // The non-empty bins of a row, in order. Only they are swept: a boundary
    // next to an empty bin splits the primitives as the one past it does,
    // at the same cost (a union with an empty bin changes no bit), and the
    // first of those, the one just after a non-empty bin, is the one the
    // first-of-equal-costs rule would pick. The nodes near the leaves,
    // most of the tree, fill a few of their bins.
    let mut full = [0u8; MAX_BINS];
    for a in (0..3).filter(|&a| enabled[a]) {
        let (row, count) = (lanes[a], counts[a]);
        let k = row.len().min(count.len()).min(MAX_BINS);
        let mut len = 0;
        for (j, &c) in count[..k].iter().enumerate() {
            full[len] = j as u8;
            len += usize::from(c != 0);
        }
        let full = &full[..len];
        let (mut acc, mut m) = (LaneBin::EMPTY, 0u32);
        for q in (1..len).rev() {
            let j = usize::from(full[q]);
            acc = acc.union(&row[j]);
            m += count[j];
            right[q] = norm.half_area_lanes(&acc) * m as f32;
        }
        let (mut left, mut m) = (LaneBin::EMPTY, 0u32);
        let mut best = (f32::INFINITY, 0usize);
        for q in 1..len {
            let j = usize::from(full[q - 1]);
            left = left.union(&row[j]);
            m += count[j];
            // Never empty on either side: both hold a non-empty bin.
            let c = norm.half_area_lanes(&left) * m as f32 + right[q];
            if c < best.0 {
                best = (c, j + 1);
            }
        }
        if best.0 < f32::INFINITY && pick.is_none_or(|(b, _, _)| best.0 < b) {
            pick = Some((best.0, a, best.1));
        }
    }
    pick
}

#[cfg(test)]
mod tests {
    use super::super::partition::bounds_of;
    use super::super::source::Indexed;
    use super::*;

    /// A small deterministic generator (no dependency in core's tests).
    fn next(state: &mut u64) -> f32 {
        *state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((*state >> 40) as f32) / (1u64 << 24) as f32
    }

    /// Both ways of binning choose the same axis, boundary, left count and
    /// halves on every node shape tried (clustered, flat along an axis,
    /// coincident centroids, far from the origin), for every bin array size.
    #[test]
    fn one_axis_at_a_time_plans_what_one_pass_plans() {
        let mut state = 7u64;
        let mut compared = 0;
        for case in 0..400 {
            let n = 2 + case % 37;
            let offset = [0.0, 1.0e4, -3.0e6][case % 3];
            let flat = case % 5; // 0..2: that axis has one coordinate
            let boxes: [Aabb; 40] = core::array::from_fn(|_| {
                let mut p = Vec3::new(next(&mut state), next(&mut state), next(&mut state));
                if flat < 3 {
                    p[flat] = 0.5;
                }
                if case % 7 == 0 {
                    p = (p * 4.0).floor(); // many equal centroids
                }
                let p = p * 10.0 + Vec3::splat(offset);
                Aabb::new(p, p + Vec3::splat(next(&mut state)))
            });
            let prims = &boxes[..n];
            let src = Indexed(prims);
            let idx: [u32; 40] = core::array::from_fn(|i| i as u32);
            let range = &idx[..n];
            let (bounds, centroids) = bounds_of(&src, range);
            let task = Task {
                node: 0,
                start: 0,
                end: n as u32,
                depth: 0,
                bounds,
                centroids,
                tight: true,
            };
            let norm = Norm::new(&bounds);
            for k in [2usize, 4, 7, 8, 12, 16, 32] {
                let one = match k {
                    0..=4 => plan_three_axes::<_, 4>(&src, range, &task, k, [true; 3], &norm),
                    5..=8 => plan_three_axes::<_, 8>(&src, range, &task, k, [true; 3], &norm),
                    9..=16 => plan_three_axes::<_, 16>(&src, range, &task, k, [true; 3], &norm),
                    _ => plan_three_axes::<_, MAX_BINS>(&src, range, &task, k, [true; 3], &norm),
                };
                let each = plan_axis_by_axis(&src, range, &task, k, &norm);
                let (one, each) = (plan_bits(&one), plan_bits(&each));
                assert_eq!(one, each, "case {case}, {k} bins");
                compared += usize::from(one.is_some());
            }
        }
        assert!(compared > 2000, "only {compared} plans compared");
    }

    /// The sweep over every boundary, empty bins included, as it was before
    /// the sweep skipped them: the reference for the test below.
    fn every_boundary(
        lanes: [&[LaneBin]; 3],
        counts: [&[u32]; 3],
        n: usize,
        enabled: [bool; 3],
        norm: &Norm,
    ) -> Option<(f32, usize, usize)> {
        let mut pick: Option<(f32, usize, usize)> = None;
        for a in (0..3).filter(|&a| enabled[a]) {
            let (row, count) = (lanes[a], counts[a]);
            let k = row.len();
            let mut right = [0.0f32; MAX_BINS];
            let (mut acc, mut m) = (LaneBin::EMPTY, 0u32);
            for j in (1..k).rev() {
                acc = acc.union(&row[j]);
                m += count[j];
                right[j] = norm.half_area_lanes(&acc) * m as f32;
            }
            let (mut left, mut m) = (LaneBin::EMPTY, 0u32);
            let mut best = (f32::INFINITY, 0usize);
            for j in 1..k {
                left = left.union(&row[j - 1]);
                m += count[j - 1];
                let c = norm.half_area_lanes(&left) * m as f32 + right[j];
                let c = if m != 0 && m as usize != n {
                    c
                } else {
                    f32::INFINITY
                };
                if c < best.0 {
                    best = (c, j);
                }
            }
            if best.0 < f32::INFINITY && pick.is_none_or(|(b, _, _)| best.0 < b) {
                pick = Some((best.0, a, best.1));
            }
        }
        pick
    }

    /// Skipping the empty bins picks the boundary, row and cost (bit for
    /// bit) that sweeping every boundary picks: rows mostly empty, rows
    /// full, one bin full, and repeated bins (equal costs, where the first
    /// must win), for every row length.
    #[test]
    fn skipping_empty_bins_picks_what_every_boundary_picks() {
        let mut state = 11u64;
        let norm = Norm::new(&Aabb::new(Vec3::ZERO, Vec3::splat(10.0)));
        let mut picked = 0;
        for case in 0..3000 {
            let k = [2, 3, 4, 7, 8, 16, 32][case % 7];
            let fill = [0.1f32, 0.5, 1.0][case % 3];
            let mut lanes = [[LaneBin::EMPTY; MAX_BINS]; 3];
            let mut counts = [[0u32; MAX_BINS]; 3];
            let repeat = case % 4 == 0;
            let mut n = [0usize; 3];
            for a in 0..3 {
                for j in 0..k {
                    if next(&mut state) >= fill {
                        continue;
                    }
                    let p = if repeat {
                        Vec3::splat(1.0) // identical bins: equal costs
                    } else {
                        Vec3::new(next(&mut state), next(&mut state), next(&mut state)) * 9.0
                    };
                    let size = if repeat { 1.0 } else { next(&mut state) };
                    let b = Aabb::new(p, p + Vec3::splat(size));
                    lanes[a][j] = LaneBin {
                        min: b.min.into(),
                        max: b.max.into(),
                    };
                    counts[a][j] = if repeat {
                        2
                    } else {
                        1 + (next(&mut state) * 5.0) as u32
                    };
                    n[a] += counts[a][j] as usize;
                }
            }
            // Every row holds the same primitives, as binning makes them.
            for a in 1..3 {
                if n[a] != n[0] {
                    lanes[a] = lanes[0];
                    counts[a] = counts[0];
                }
            }
            let rows = [&lanes[0][..k], &lanes[1][..k], &lanes[2][..k]];
            let cs = [&counts[0][..k], &counts[1][..k], &counts[2][..k]];
            let enabled = [true, case % 5 != 1, case % 6 != 2];
            let bits = |p: Option<(f32, usize, usize)>| p.map(|(c, a, j)| (c.to_bits(), a, j));
            let want = every_boundary(rows, cs, n[0], enabled, &norm);
            assert_eq!(
                bits(best_of_rows(rows, cs, enabled, &norm)),
                bits(want),
                "case {case}"
            );
            picked += usize::from(want.is_some());
        }
        assert!(picked > 1500, "only {picked} rows had a boundary");
    }

    /// Every field of a fast-path plan, floats as bits (so `-0.0` and
    /// `0.0` differ).
    type Bits = (usize, u32, u32, usize, usize, usize, [u32; 12]);

    fn plan_bits(p: &Option<Plan>) -> Option<Bits> {
        let Some(Plan::Axis {
            axis,
            lo,
            scale,
            k,
            boundary,
            known,
        }) = *p
        else {
            return None;
        };
        let (mid, [l, r]) = known.expect("the fast path knows its halves");
        let mut b = [0u32; 12];
        for (slot, v) in b.iter_mut().zip(
            [l.min, l.max, r.min, r.max]
                .iter()
                .flat_map(|v| v.to_array()),
        ) {
            *slot = v.to_bits();
        }
        Some((axis, lo.to_bits(), scale.to_bits(), k, boundary, mid, b))
    }
}
