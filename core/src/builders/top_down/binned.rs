//! The default's fast path: binned SAH over x, y and z in one pass over the
//! primitives, with bins kept in 4-lane registers.

use super::criteria::Norm;
use super::source::Source;
use super::split_points::{even_bin, Plan};
use super::Task;
use crate::builders::strategy::MAX_BINS;
use crate::bv::Aabb;
use glam::{BVec4A, Vec3, Vec3A, Vec4};

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
/// right (costs kept) and once from the left; the first of equal costs wins,
/// within a row and across rows.
///
/// The three rows are swept side by side, row `a` in lane `a` of 4-lane
/// registers: one step scores a boundary on all three axes at once, without
/// branches, and the three running unions are independent chains instead of
/// one long one. Each lane does the arithmetic of
/// [`Norm::half_area_lanes`] in the same order, so the costs, and the tree,
/// are those of one row at a time.
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
    let k = lanes
        .iter()
        .map(|r| r.len())
        .chain(counts.iter().map(|c| c.len()))
        .min()
        .unwrap_or(0)
        .min(MAX_BINS);
    let (lanes, counts) = (lanes.map(|r| &r[..k]), counts.map(|c| &c[..k]));
    let inv = norm.inv;
    // Half areas of three boxes, box `a` in lane `a`: the extents are
    // transposed so that each lane computes `x*y + y*z + z*x` in that order.
    let half_areas = |b: &[LaneBin; 3]| -> Vec4 {
        let e = b.map(|b| ((b.max - b.min) * inv).max(Vec3A::ZERO));
        let x = Vec4::new(e[0].x, e[1].x, e[2].x, 0.0);
        let y = Vec4::new(e[0].y, e[1].y, e[2].y, 0.0);
        let z = Vec4::new(e[0].z, e[1].z, e[2].z, 0.0);
        x * y + y * z + z * x
    };
    // Running counts per row, and as floats the way a scalar `m as f32` rounds.
    let add = |m: &mut [u32; 3], j: usize| {
        for (m, row) in m.iter_mut().zip(&counts) {
            *m += row[j];
        }
    };
    let float = |m: &[u32; 3]| Vec4::new(m[0] as f32, m[1] as f32, m[2] as f32, 0.0);
    let mut right = [Vec4::ZERO; MAX_BINS];
    let (mut acc, mut m) = ([LaneBin::EMPTY; 3], [0u32; 3]);
    for j in (1..k).rev() {
        for (a, row) in acc.iter_mut().zip(&lanes) {
            *a = a.union(&row[j]);
        }
        add(&mut m, j);
        right[j] = half_areas(&acc) * float(&m);
    }
    let (mut left, mut m) = ([LaneBin::EMPTY; 3], [0u32; 3]);
    let (mut best, mut best_j) = (Vec4::INFINITY, Vec4::ZERO);
    // A boundary with every primitive on one side is no split.
    let n = n.min(u32::MAX as usize) as u32;
    for j in 1..k {
        for (l, row) in left.iter_mut().zip(&lanes) {
            *l = l.union(&row[j - 1]);
        }
        add(&mut m, j - 1);
        let c = half_areas(&left) * float(&m) + right[j];
        let splits = BVec4A::new(
            m[0] != 0 && m[0] != n,
            m[1] != 0 && m[1] != n,
            m[2] != 0 && m[2] != n,
            false,
        );
        let c = Vec4::select(splits, c, Vec4::INFINITY);
        let better = c.cmplt(best);
        best = Vec4::select(better, c, best);
        best_j = Vec4::select(better, Vec4::splat(j as f32), best_j);
    }
    let mut pick: Option<(f32, usize, usize)> = None;
    for a in (0..3).filter(|&a| enabled[a]) {
        let c = best[a];
        if c < f32::INFINITY && pick.is_none_or(|(b, _, _)| c < b) {
            pick = Some((c, a, best_j[a] as usize));
        }
    }
    pick
}
