//! The default's fast path: binned SAH over x, y and z in one pass over the
//! primitives, with bins kept in 4-lane registers.

use super::criteria::Norm;
use super::source::Source;
use super::split_points::{even_bin, Plan};
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
    #[inline(always)]
    pub(super) fn of(b: &Aabb) -> LaneBin {
        LaneBin {
            min: b.min.into(),
            max: b.max.into(),
        }
    }
}

/// The fast path: one pass bins every primitive along x, y and z at once.
/// Not inlined, so that only the bin array of the size in use is on the
/// stack (inlined, all four sizes' frames add up: 4 KiB on a Cortex-M4).
#[inline(never)]
pub(super) fn plan_binned_sah<S: Source, const N: usize>(
    src: &S,
    range: &[S::Item],
    task: &Task,
    k: usize,
    axes: [bool; 3],
    norm: &Norm,
) -> Option<Plan> {
    let k = k.min(N);
    let c = &task.centroids;
    let ext = c.extent();
    let mut scale = [0.0f32; 3];
    for a in 0..3 {
        scale[a] = if ext[a] > 0.0 && axes[a] {
            k as f32 / ext[a]
        } else {
            0.0
        };
    }
    if axes != [true; 3] {
        // One axis: bin only along it.
        let a = axes.iter().position(|&x| x)?;
        if scale[a] == 0.0 {
            return None;
        }
        let (mut bins, mut counts) = ([[LaneBin::EMPTY; N]], [[0u32; N]]);
        for &i in range {
            let b = src.bounds(i);
            let j = even_bin(b.center()[a], c.min[a], scale[a], k);
            bins[0][j] = bins[0][j].union(&LaneBin::of(&b));
            counts[0][j] += 1;
        }
        let (row, count) = (&bins[0][..k], &counts[0][..k]);
        let best = best_of_rows(
            [row; 3],
            [count; 3],
            range.len(),
            [true, false, false],
            norm,
        );
        return best.map(|(_, _, boundary)| Plan::Axis {
            axis: a,
            lo: c.min[a],
            scale: scale[a],
            k,
            boundary,
            known: None,
        });
    }
    // Bin bounds in 4-lane registers: a union is two instructions, and the
    // three bin indices come from one subtract and multiply. Each lane does
    // the scalar path's arithmetic (`Aabb::center`, `even_bin`, `Aabb::union`
    // with the same operand order), so the bins, and the tree, are the same
    // as one axis at a time would give.
    let mut lanes = [[LaneBin::EMPTY; N]; 3];
    let mut counts = [[0u32; N]; 3];
    let (lo_c, sc) = (Vec3A::from(c.min), Vec3A::from(Vec3::from(scale)));
    let top = k.clamp(1, N) - 1; // < N: no bounds check in the loop
    let top_f = Vec3A::splat(top as f32);
    for &i in range {
        let (lo, hi) = src.lanes(i);
        let t = ((lo * 0.5 + hi * 0.5) - lo_c) * sc;
        // Clamping before the conversion is `(t as usize).min(top)`: top is
        // a whole number and t is finite.
        let t = t.max(Vec3A::ZERO).min(top_f);
        for a in 0..3 {
            let j = (t[a] as i32 as usize).min(top);
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
        range.len(),
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

/// The SAH-best boundary over rows of bins (one row per axis tried; bin `j`
/// of row `a` holds `counts[a][j]` primitives, `n` in all, every row of the
/// same length), as (cost, row, boundary). Each row is swept once from the
/// right (costs kept) and once from the left, scoring without branches; the
/// first of equal costs wins, within a row and across rows.
// Not generic and out of line: one copy in the firmware, and the frame of
// its cost array is not added to every caller's.
#[inline(never)]
fn best_of_rows(
    lanes: [&[LaneBin]; 3],
    counts: [&[u32]; 3],
    n: usize,
    enabled: [bool; 3],
    norm: &Norm,
) -> Option<(f32, usize, usize)> {
    let mut pick: Option<(f32, usize, usize)> = None;
    let mut right = [0.0f32; MAX_BINS];
    for a in (0..3).filter(|&a| enabled[a]) {
        let (row, count) = (lanes[a], counts[a]);
        let k = row.len().min(count.len()).min(MAX_BINS);
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
