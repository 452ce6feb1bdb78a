//! Where the builder reads primitive bounds: through the caller's slice, or
//! from cached records that move with the partition.

use crate::bv::{Aabb, BoxSet};
use crate::primitive::Primitive;
use glam::{Vec3, Vec3A, Vec4};

/// A primitive's bounds and its index, cached for [`TopDown::build_cached`]:
/// 32 bytes, 16-byte aligned, so each corner is one aligned 4-lane load and a
/// record moves in two. The index rides in the unused fourth lanes, as two
/// 16-bit halves stored as small whole numbers (never a NaN or a subnormal
/// that would slow the lane arithmetic).
///
/// [`TopDown::build_cached`]: super::TopDown::build_cached
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimitiveRef {
    min: Vec4,
    max: Vec4,
}

impl PrimitiveRef {
    /// A blank record, for initialising storage.
    pub const EMPTY: PrimitiveRef = PrimitiveRef {
        min: Vec4::new(f32::INFINITY, f32::INFINITY, f32::INFINITY, 0.0),
        max: Vec4::new(f32::NEG_INFINITY, f32::NEG_INFINITY, f32::NEG_INFINITY, 0.0),
    };

    /// A record of zero bits (a point box at the origin, index 0), for storage
    /// the builder overwrites: a `Vec` of it comes from zeroed memory, which
    /// costs nothing until a page is written (see [`Node::ZERO`](crate::Node::ZERO)).
    pub const ZERO: PrimitiveRef = PrimitiveRef {
        min: Vec4::ZERO,
        max: Vec4::ZERO,
    };

    /// The record of primitive `index` with these bounds.
    ///
    /// ```
    /// use bvhkit::{builders::PrimitiveRef, Aabb};
    /// use glam::Vec3;
    /// let b = Aabb::new(Vec3::ZERO, Vec3::ONE);
    /// let r = PrimitiveRef::new(&b, 1_000_000);
    /// assert_eq!((r.bounds(), r.index()), (b, 1_000_000));
    /// assert_eq!(core::mem::size_of::<PrimitiveRef>(), 32);
    /// ```
    pub fn new(bounds: &Aabb, index: u32) -> Self {
        PrimitiveRef {
            min: bounds.min.extend((index & 0xFFFF) as f32),
            max: bounds.max.extend((index >> 16) as f32),
        }
    }

    /// Bounds of the primitive.
    #[inline(always)]
    pub fn bounds(&self) -> Aabb {
        Aabb::new(self.min.truncate(), self.max.truncate())
    }

    /// Index of the primitive in the caller's slice.
    #[inline(always)]
    pub fn index(&self) -> u32 {
        self.min.w as u32 | (self.max.w as u32) << 16
    }

    /// Both corners in 4-lane registers (the fourth lane is not a coordinate).
    #[inline(always)]
    pub(super) fn lanes(&self) -> (Vec3A, Vec3A) {
        (Vec3A::from_vec4(self.min), Vec3A::from_vec4(self.max))
    }
}

/// Where the builder reads bounds from: the caller's primitives through an
/// index ([`Indexed`]), or cached records that move with the partition ([`Cached`]).
/// One skeleton serves both.
pub(super) trait Source {
    type Item: Copy;
    fn bounds(&self, item: Self::Item) -> Aabb;
    /// The bounds' corners in 4-lane registers, for the hot loops.
    #[inline(always)]
    fn lanes(&self, item: Self::Item) -> (Vec3A, Vec3A) {
        let b = self.bounds(item);
        (b.min.into(), b.max.into())
    }
    /// The primitive's index: breaks ties so every ordering is total, and the
    /// tree does not depend on how an unstable sort treats equal keys.
    fn id(&self, item: Self::Item) -> u32;
}

/// The point builders sort by: the centre of the primitive's bounds.
#[inline(always)]
pub(super) fn centroid<S: Source>(src: &S, item: S::Item) -> Vec3 {
    src.bounds(item).center()
}

pub(super) struct Indexed<'a, P>(pub(super) &'a [P]);

impl<P: Primitive> Source for Indexed<'_, P> {
    type Item = u32;
    #[inline(always)]
    fn bounds(&self, i: u32) -> Aabb {
        self.0[i as usize].bounds()
    }
    #[inline(always)]
    fn id(&self, i: u32) -> u32 {
        i
    }
}

pub(super) struct Cached;

impl Source for Cached {
    type Item = PrimitiveRef;
    #[inline(always)]
    fn bounds(&self, r: PrimitiveRef) -> Aabb {
        r.bounds()
    }
    #[inline(always)]
    fn lanes(&self, r: PrimitiveRef) -> (Vec3A, Vec3A) {
        r.lanes()
    }
    #[inline(always)]
    fn id(&self, r: PrimitiveRef) -> u32 {
        r.index()
    }
}

/// The bounds of a range of items, as a [`BoxSet`] for volume fitting.
pub(super) struct SourceBoxes<'a, S: Source> {
    pub(super) src: &'a S,
    pub(super) items: &'a [S::Item],
}

impl<S: Source> BoxSet for SourceBoxes<'_, S> {
    fn len(&self) -> usize {
        self.items.len()
    }
    fn aabb(&self, i: usize) -> Aabb {
        self.src.bounds(self.items[i])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn primitive_ref_keeps_bounds_and_every_index() {
        let b = Aabb::new(Vec3::new(-1.5, 0.0, 2.0), Vec3::new(3.0, 1e-30, 1e30));
        let max = crate::tree::MAX_PRIMITIVES as u32;
        for index in [0, 1, 0xFFFF, 0x1_0000, 0x1_2345, 16_777_217, max - 1, max] {
            let r = PrimitiveRef::new(&b, index);
            assert_eq!(r.index(), index);
            assert_eq!(r.bounds(), b);
            let (lo, hi) = r.lanes();
            assert_eq!((Vec3::from(lo), Vec3::from(hi)), (b.min, b.max));
        }
        let zero = PrimitiveRef::ZERO;
        assert_eq!(
            (zero.bounds(), zero.index()),
            (Aabb::new(Vec3::ZERO, Vec3::ZERO), 0)
        );
        assert_eq!(core::mem::size_of::<PrimitiveRef>(), 32);
        assert_eq!(core::mem::align_of::<PrimitiveRef>(), 16);
    }
}
