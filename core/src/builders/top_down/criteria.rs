//! Partition criteria: what a split minimises (Ericson 6.2.2), each scored
//! on boxes scaled into the parent's unit cube.

use crate::builders::strategy::Partition;
use crate::bv::{Aabb, BoundingVolume};
use glam::{Vec3, Vec3A};

use super::binned::LaneBin;

/// Parent-relative coordinates: every cost is computed on boxes scaled into the
/// unit cube of the parent, so areas and volumes never overflow at 1e30.
#[derive(Clone, Copy, Debug)]
pub(super) struct Norm {
    pub(super) origin: Vec3,
    pub(super) inv: f32,
}

impl Norm {
    pub(super) fn new(parent: &Aabb) -> Self {
        let ext = parent.extent().max_element();
        Norm {
            origin: parent.min,
            inv: if ext > 0.0 { 1.0 / ext } else { 1.0 },
        }
    }
    #[inline]
    pub(super) fn apply(&self, b: &Aabb) -> Aabb {
        Aabb::new(
            (b.min - self.origin) * self.inv,
            (b.max - self.origin) * self.inv,
        )
    }
    #[inline]
    pub(super) fn half_area(&self, b: &Aabb) -> f32 {
        let e = (b.extent() * self.inv).max(Vec3::ZERO);
        e.x * e.y + e.y * e.z + e.z * e.x
    }
    /// [`half_area`](Self::half_area) of a bin in 4-lane registers: the same
    /// operations lane by lane, so the same value.
    #[inline(always)]
    pub(super) fn half_area_lanes(&self, b: &LaneBin) -> f32 {
        let e = ((b.max - b.min) * self.inv).max(Vec3A::ZERO);
        e.x * e.y + e.y * e.z + e.z * e.x
    }
    /// Both the area and the longest side are within 1% of the parent's.
    pub(super) fn nearly_as_large(&self, child: &Aabb, parent: &Aabb) -> bool {
        self.half_area(child) >= 0.99 * self.half_area(parent)
            && child.extent().max_element() >= 0.99 * parent.extent().max_element()
    }
}

/// Cost of a candidate split under a criterion (lower is better).
#[allow(clippy::too_many_arguments)]
pub(super) fn cost<B: BoundingVolume>(
    partition: Partition,
    norm: &Norm,
    parent: &Aabb,
    l: &Aabb,
    nl: u32,
    r: &Aabb,
    nr: u32,
) -> f32 {
    let vol = |b: &Aabb| B::from_aabb(&norm.apply(b)).cost_volume_scaled(1.0);
    let sah = || {
        (norm.half_area(l) * nl as f32 + norm.half_area(r) * nr as f32)
            / (norm.half_area(parent).max(f32::MIN_POSITIVE) * (nl + nr) as f32)
    };
    let overlap = || match l.intersection(r) {
        Some(i) => vol(&i) + norm.half_area(&i) * 1e-3,
        None => 0.0,
    };
    let balance = || (nl as f32 - nr as f32).abs() / (nl + nr) as f32;
    match partition {
        Partition::Balance => balance(),
        Partition::SurfaceArea => sah(),
        Partition::Volume => vol(l) + vol(r),
        Partition::LargerChild => vol(l).max(vol(r)),
        Partition::Overlap => overlap(),
        Partition::Separation => {
            let (a, b) = (norm.apply(l), norm.apply(r));
            let gap = (a.min - b.max).max(b.min - a.max).max_element();
            -gap
        }
        Partition::Weighted {
            surface_area,
            volume,
            overlap: w_overlap,
            balance: w_balance,
        } => {
            let mut c = 0.0;
            if surface_area > 0.0 {
                c += surface_area * sah();
            }
            if volume > 0.0 {
                c += volume * (vol(l) + vol(r));
            }
            if w_overlap > 0.0 {
                c += w_overlap * overlap();
            }
            if w_balance > 0.0 {
                c += w_balance * balance();
            }
            c
        }
    }
}
